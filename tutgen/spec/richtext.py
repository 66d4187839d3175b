"""Texts with inline maths: ``$…$`` spans in a statement, a title or a description, read as data.

A spec writes maths in its texts between dollars, in its own expression grammar::

    statement: |
      The kinetic energy is $T = (3/2 + cos(theta2)) theta1_dot^2 + theta2_dot^2/2$.

Each span is one or more expressions chained by the relations ``=``, ``!=``, ``<``, ``>``, ``<=`` and
``>=`` (``$0 < theta < pi/2$``). Every expression goes through the whitelist parser of
:mod:`tutgen.spec.expr` (never ``eval`` or ``sympify``), with two allowances that prose needs:

- **Free names.** A span may use the spec's parameters, coordinates and their rates (``theta1_dot``,
  ``x_ddot``), which are the very symbols of the results, and also names the spec does not declare:
  the quantities a statement talks about (``T``, ``U``, ``L``, ``H``, ``Q``, ``tau``, ``F``, ``q``,
  ``q_dot``) are results or generic symbols, not inputs. An undeclared name is a free symbol,
  typeset by the default rule of :mod:`tutgen.spec.names` (``q_dot`` as a dotted q). It must still be
  a name of the grammar starting with a letter; written right before ``(`` it is a function of what
  the parentheses hold (``H(q)``, ``C(q, q_dot)``). A function of the grammar used without its
  argument (``cos theta``: write ``cos(theta)``) stays an error.
- **Products without ``*``.** ``2 m l``, ``(1 + cos(theta2)) theta1_dot`` and ``sin(q1) cos(q2)`` are
  products, as in print: an operand followed by a name or ``(`` is multiplied by it, at the level of
  ``*`` and ``/`` (so ``1/2 m v^2`` is (1/2)·m·v²; write ``1/(2 m)`` for the other). A number after
  an operand still needs ``*`` (``x 2`` is refused: it reads as a typo).

``\\$`` is a literal dollar sign (anywhere in the text, also next to a span); every other character
outside the spans is plain text, escaped by the renderer. An unclosed ``$`` is an error at that dollar,
an empty span ``$$`` too (a text has no display maths), and a span that does not parse is an error at
the offending character inside it. The result is a :class:`tutgen.model.text.RichText`: the text as
written (a ``str``), with its parts (text and :class:`tutgen.model.text.MathSpan`) in order. A span's
``terms`` are sympy values (in sympy's canonical form; its ``source`` keeps the span as written).

Examples
--------
>>> import sympy as sp
>>> theta = sp.Symbol("theta")
>>> text = parse_rich_text("angle $theta < pi/2$, cost \\\\$5", {"theta": theta})
>>> text.parts[0], text.parts[1].relations, text.parts[2]
('angle ', ('<',), ', cost $5')
>>> parse_rich_text("$T = 1/2 m v^2$", {}).parts[0].terms
(T, m*v**2/2)
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Collection, Iterator, Mapping
from typing import Any

import sympy as sp

from tutgen.errors import SpecError
from tutgen.model.system import System
from tutgen.model.text import MathSpan, Placeholder, RichText
from tutgen.spec.expr import CONSTANTS, FUNCTIONS, MAX_LENGTH, ExprError, ExpressionParser
from tutgen.spec.loader import KeyPath, SourceMap

__all__ = ["MAX_MATHS", "MAX_SPANS", "RichTextError", "parse_rich_text", "read_texts", "with_texts"]

#: Most ``$…$`` spans one text may hold (each one is a parse).
MAX_SPANS = 200
#: Most characters of maths (between the dollars) in all the texts of one spec together: prose maths
#: is short, and sympy builds about 15 000 characters of it a second on a busy machine.
MAX_MATHS = 20_000
#: The relations a span may chain expressions with; the two-character ones first.
_RELATION_RE = re.compile(r"<=|>=|!=|=|<|>")
_ESCAPE_HINT = "write \\$ for a dollar sign"
_BRACE_HINT = "a statement quotes a parameter's value as {name}; write {{ and }} for literal braces"


class RichTextError(ValueError):
    """A text whose maths cannot be read: the message, the 0-based offset into the text, a hint."""

    def __init__(self, message: str, offset: int, hint: str | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.offset = offset
        self.hint = hint

    def __str__(self) -> str:
        return self.message


class _ProseNames(Mapping[str, sp.Expr]):
    """The declared names, and any other name of the grammar as a free symbol (see the module docstring).

    Iterating gives the declared names only: that is what an "unknown name" hint lists.
    """

    def __init__(self, declared: Mapping[str, sp.Expr]) -> None:
        self.declared = declared
        self.free: dict[str, sp.Symbol] = {}

    def __contains__(self, name: object) -> bool:
        if not isinstance(name, str):
            return False
        if name in self.declared:
            return True
        return name[:1].isalpha() and name not in FUNCTIONS and name not in CONSTANTS

    def __getitem__(self, name: str) -> sp.Expr:
        if name in self.declared:
            return self.declared[name]
        if name not in self:
            raise KeyError(name)
        return self.free.setdefault(name, sp.Symbol(name))

    def __iter__(self) -> Iterator[str]:
        return iter(self.declared)

    def __len__(self) -> int:
        return len(self.declared)


class _ProseParser(ExpressionParser):
    """The whitelist parser, reading a product written without ``*`` as in print (``2 m l``).

    It extends the parser of :mod:`tutgen.spec.expr` by these two methods only, so that the grammar,
    the limits and the messages stay those of a spec's expressions (tests/spec/test_richtext.py
    checks both): keep them in step if that parser's ``_product`` or ``_name`` change."""

    def _product(self, depth: int) -> sp.Expr:
        left = self._unary(depth)
        while True:
            if self.tok.is_op("*", "/"):
                op = self._advance()
                right = self._unary(depth)
                if op.text == "/":
                    if right == 0:
                        raise ExprError("division by zero", op.offset)
                    right = sp.Pow(right, sp.S.NegativeOne)
            elif self.tok.kind == "name" or self.tok.is_op("("):
                op = self.tok
                right = self._unary(depth)
            else:
                return left
            left = sp.Mul(left, right)
            self._check(left, op.offset)

    def _name(self, depth: int) -> sp.Expr:
        # a declared name followed by '(' is a product here (``l (1 + cos(theta))``), and so is a free
        # name with a space before the '('; a free name right before '(' is a function (``H(q)``)
        tok = self.tok
        name = tok.text
        if name in CONSTANTS or (name in self.symbols and name not in FUNCTIONS):
            self._advance()
            free = isinstance(self.symbols, _ProseNames) and name not in self.symbols.declared
            if free and self.tok.is_op("(") and self.tok.offset == tok.offset + len(name):
                opening = self._advance()
                args = self._arguments(name, opening, self._enter(depth + 1, opening))
                if not args:
                    raise ExprError(f"the function '{name}' needs an argument", opening.offset)
                result = sp.Function(name)(*args)
                self._check(result, tok.offset)
                return result
            return CONSTANTS[name] if name in CONSTANTS else self.symbols[name]
        return super()._name(depth)


def _parse_term(source: str, names: _ProseNames) -> sp.Expr:
    """One expression of a span."""
    if len(source) > MAX_LENGTH:
        raise ExprError(f"the expression is too long ({len(source)} characters; the limit is {MAX_LENGTH})", 0)
    return _ProseParser(source, names).parse()


def _span(source: str, names: _ProseNames, offset: int) -> MathSpan:
    """The span ``$source$`` whose first character (after the dollar) is at ``offset`` of the text."""
    shown = source if len(source) <= 40 else source[:37] + "..."
    pieces: list[tuple[int, str]] = []  # (offset in source, expression text)
    relations: list[str] = []
    start = 0
    for match in _RELATION_RE.finditer(source):
        pieces.append((start, source[start : match.start()]))
        relations.append(match.group())
        start = match.end()
    pieces.append((start, source[start:]))
    terms: list[sp.Expr] = []
    for i, (at, piece) in enumerate(pieces):
        if not piece.strip():
            where = at + len(piece) if i < len(relations) else at
            if relations and i == 0:
                what = f"before '{relations[0]}'"
            elif i < len(relations):
                what = f"between '{relations[i - 1]}' and '{relations[i]}'"
            else:
                what = f"after '{relations[-1]}'"
            raise RichTextError(
                f"in the maths '${shown}$': expected an expression {what}, found nothing", offset + where,
                "a relation joins two expressions, e.g. $T = m v^2/2$",
            )  # fmt: skip
        try:
            terms.append(_parse_term(piece, names))
        except ExprError as exc:
            where = offset + at + exc.offset
            raise RichTextError(f"in the maths '${shown}$': {exc.message}", where, exc.hint) from None
    return MathSpan(source, tuple(terms), tuple(relations))


def parse_rich_text(
    text: str, names: Mapping[str, sp.Expr], max_maths: int = MAX_MATHS, placeholders: Collection[str] | None = None
) -> RichText:
    """Read the ``$…$`` spans of ``text`` (see the module docstring) into a :class:`RichText`.

    ``names`` are the declared names (parameters, coordinates, rates) and their symbols; the spans
    may hold ``max_maths`` characters of maths in all. With ``placeholders`` (the parameters' names, for a
    statement), ``{name}`` outside the maths is a :class:`~tutgen.model.text.Placeholder` for that
    parameter's value, and ``{{``/``}}`` are literal braces. Raises :class:`RichTextError` with the
    0-based offset into ``text`` of the problem.
    """
    prose = _ProseNames(names)
    parts: list[str | MathSpan | Placeholder] = []
    plain: list[str] = []
    spans = 0
    i, end = 0, len(text)
    while i < end:
        char = text[i]
        if char == "\\" and text.startswith("$", i + 1):
            plain.append("$")
            i += 2
            continue
        if placeholders is not None and char in "{}":
            if text.startswith(char * 2, i):  # {{ and }}: a literal brace
                plain.append(char)
                i += 2
                continue
            if char == "}":
                raise RichTextError("unmatched '}'", i, _BRACE_HINT)
            close = text.find("}", i + 1)
            name = text[i + 1 : close].strip() if close > 0 else ""
            if close < 0 or "{" in text[i + 1 : close]:
                raise RichTextError("unclosed '{': a placeholder is a parameter's name in braces, {m}", i, _BRACE_HINT)
            if name not in placeholders:
                known = ", ".join(sorted(placeholders)) or "none"
                raise RichTextError(
                    f"unknown parameter '{name}' in the placeholder '{text[i : close + 1]}' (known: {known})",
                    i,
                    _BRACE_HINT,
                )
            if plain:
                parts.append("".join(plain))
                plain = []
            parts.append(Placeholder(name))
            i = close + 1
            continue
        if char != "$":
            plain.append(char)
            i += 1
            continue
        close = i + 1
        while close < end and not (text[close] == "$" and text[close - 1] != "\\"):
            close += 1
        if close >= end:
            raise RichTextError("unclosed '$': the maths that starts here has no closing '$'", i, _ESCAPE_HINT)
        source = text[i + 1 : close]
        if not source.strip():
            hint = f"write maths between the dollars, or {_ESCAPE_HINT}; a text has no display maths"
            raise RichTextError(f"empty maths '${source}$'", i, hint)
        spans += 1
        if spans > MAX_SPANS:
            raise RichTextError(f"the text has more than {MAX_SPANS} maths spans", i)
        max_maths -= len(source)
        if max_maths < 0:
            raise RichTextError(
                f"the texts hold more than {MAX_MATHS} characters of maths", i, "keep the maths of a text short"
            )
        if plain:
            parts.append("".join(plain))
            plain = []
        parts.append(_span(source, prose, i + 1))
        i = close + 1
    if plain:
        parts.append("".join(plain))
    return RichText(text, tuple(parts))


# ---------------------------------------------------------------------------------------------
# The texts of a spec
# ---------------------------------------------------------------------------------------------

#: Sections whose entries may carry a ``description`` for the reader (``arm`` rows are under arm.links).
_DESCRIBED = ("parameters", "coordinates", "bodies", "springs", "dampers", "loads")


def _text_paths(data: Mapping[str, Any]) -> Iterator[tuple[KeyPath, str, bool]]:
    """(key path, text, whether it is stripped as the model keeps it) of every text of a loaded spec."""
    for key in ("title", "question_title", "statement"):
        if isinstance(data.get(key), str):
            yield (key,), data[key], True
    sections: list[tuple[KeyPath, Any]] = [((section,), data.get(section)) for section in _DESCRIBED]
    arm = data.get("arm")
    if isinstance(arm, Mapping):
        sections.append((("arm", "links"), arm.get("links")))
    for prefix, entries in sections:
        if not isinstance(entries, Mapping):
            continue
        for name, entry in entries.items():
            if isinstance(entry, Mapping) and isinstance(entry.get("description"), str):
                yield (*prefix, name, "description"), entry["description"], False


def read_texts(
    data: Mapping[str, Any], smap: SourceMap, names: Mapping[str, sp.Expr], parameters: Collection[str] = ()
) -> tuple[dict[KeyPath, RichText], list[SpecError]]:
    """Every text of a loaded spec (title, statement, descriptions) read by :func:`parse_rich_text`.

    Returns the texts by key path (title and statement stripped of surrounding white space, as the model
    keeps them) and an error, at its ``file:line:col``, for each text whose maths cannot be read.
    """
    texts: dict[KeyPath, RichText] = {}
    errors: list[SpecError] = []
    budget = MAX_MATHS  # for all the texts together
    for path, raw, strip in _text_paths(data):
        lead = len(raw) - len(raw.lstrip()) if strip else 0
        text = raw.strip() if strip else raw
        try:
            quotes = set(parameters) if path == ("statement",) else None  # placeholders: statements only
            texts[path] = parse_rich_text(text, names, budget, quotes)
        except RichTextError as exc:
            errors.append(SpecError(smap.expr_location(path, lead + exc.offset), exc.message, exc.hint))
            if exc.message.startswith("the texts hold more than"):
                break
            continue
        budget -= sum(len(part.source) for part in texts[path].parts if isinstance(part, MathSpan))
    return texts, errors


def with_texts(system: System, texts: Mapping[KeyPath, RichText]) -> System:
    """``system`` with its title, statement and descriptions as the :class:`RichText` of ``texts``."""

    def described(section: str, item: Any) -> Any:
        text = texts.get((section, item.name, "description"))
        return item if text is None else dataclasses.replace(item, description=text)

    coordinates = {c.name: described("coordinates", c) for c in system.coordinates}
    joints = tuple(
        dataclasses.replace(j, coordinate=coordinates[j.coordinate.name])
        if j.coordinate is not None and j.coordinate.name in coordinates
        else j
        for j in system.joints
    )
    return dataclasses.replace(
        system,
        title=texts.get(("title",), system.title),
        question_title=texts.get(("question_title",), system.question_title),
        statement=texts.get(("statement",), system.statement),
        parameters=tuple(described("parameters", p) for p in system.parameters),
        coordinates=tuple(coordinates.values()),
        joints=joints,
    )
