"""The whitelist expression parser: user text is data, never code.

A spec writes expressions such as ``(m1 + m2)*x_ddot + m2*l*cos(theta)``. They are read by a
hand-written tokenizer and recursive-descent parser and built with sympy constructors
(``sp.Add``, ``sp.Mul``, ``sp.Pow``, ``sp.sin``, ...). Nothing here calls ``eval``, ``exec``,
``sympify`` or ``parse_expr``: a name that is not a declared symbol, ``pi`` or one of
:data:`FUNCTIONS` is an error, so text such as ``__import__('os')`` can never run.

Grammar (Python's precedence; ``^`` is a synonym of ``**``)::

    sum     := product (("+" | "-") product)*
    product := unary (("*" | "/") unary)*
    unary   := ("+" | "-") unary | power
    power   := primary (("**" | "^") unary)?          # right-associative, 2**-1 allowed
    primary := NUMBER | NAME | NAME "(" [sum ("," sum)*] ")" | "(" sum ")"

Numbers are exact (``0.1`` is ``1/10``, never a float). Every error is an :class:`ExprError` that
carries the 0-based offset of the offending token in the source text.
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from types import MappingProxyType

import sympy as sp

__all__ = [
    "CONSTANTS",
    "FUNCTIONS",
    "MAX_DEPTH",
    "MAX_DIGITS",
    "MAX_EXPONENT",
    "MAX_LENGTH",
    "ExprError",
    "did_you_mean",
    "number_to_rational",
    "parse_expression",
]

#: Longest expression accepted, in characters (checked before anything else is done).
MAX_LENGTH = 2000
#: Deepest nesting of parentheses, function calls, unary signs and powers.
MAX_DEPTH = 50
#: Largest ``|exponent|`` of a power.
MAX_EXPONENT = 64
#: Most digits in the mantissa of a number literal; its decimal exponent must be within ±300.
MAX_DIGITS = 100
_MAX_DECIMAL_EXPONENT = 300
#: Largest exact number (numerator or denominator, in bits) an expression may create: enough for
#: any literal (100 digits, exponent ±300), small enough that ``((2**64)**64)**64`` or a root of a
#: huge product is refused instead of computed (and every result still prints as a decimal).
_MAX_NUMBER_BITS = 1400
_MAX_NUMBER_DIGITS = 420  # _MAX_NUMBER_BITS in decimal digits, for messages
#: How many known names an "unknown name" hint lists at most.
_MAX_LISTED_NAMES = 12


class ExprError(ValueError):
    """An expression that cannot be read: what was expected, what was found, and where.

    ``offset`` is the 0-based index into the source text of the offending token (the length of
    the text when the problem is at its end). ``str(err)`` is ``err.message``.
    """

    def __init__(self, message: str, offset: int = 0, hint: str | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.offset = offset
        self.hint = hint

    def __str__(self) -> str:
        return self.message

    def __reduce__(self) -> tuple[type[ExprError], tuple[str, int, str | None]]:
        return (type(self), (self.message, self.offset, self.hint))


#: The functions an expression may call: name -> (sympy constructor, number of arguments).
FUNCTIONS: Mapping[str, tuple[Callable[..., sp.Expr], int]] = MappingProxyType(
    {
        "sin": (sp.sin, 1),
        "cos": (sp.cos, 1),
        "tan": (sp.tan, 1),
        "asin": (sp.asin, 1),
        "acos": (sp.acos, 1),
        "atan": (sp.atan, 1),
        "sinh": (sp.sinh, 1),
        "cosh": (sp.cosh, 1),
        "tanh": (sp.tanh, 1),
        "exp": (sp.exp, 1),
        "log": (sp.log, 1),
        "sqrt": (sp.sqrt, 1),
        "atan2": (sp.atan2, 2),
        "abs": (sp.Abs, 1),
        "Abs": (sp.Abs, 1),
        "sign": (sp.sign, 1),
    }
)

#: Named constants. Only ``pi``: ``e``/``E`` are ordinary names (a parameter may be called ``e``).
CONSTANTS: Mapping[str, sp.Expr] = MappingProxyType({"pi": sp.pi})

_NUMBER_RE = re.compile(r"(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_SIGNED_NUMBER_RE = re.compile(r"[+-]?" + _NUMBER_RE.pattern)
_NAME_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_WHITESPACE = frozenset(" \t\r\n\f\v")
_OPERATORS = ("**", "+", "-", "*", "/", "^", "(", ")", ",")
_NON_FINITE = frozenset({sp.S.ComplexInfinity, sp.S.NaN, sp.S.Infinity, sp.S.NegativeInfinity})
_CHAR_HINTS = {
    "=": "an expression has no '='; write only the expression",
    "[": "group with '(' and ')'",
    "]": "group with '(' and ')'",
    "{": "group with '(' and ')'",
    "}": "group with '(' and ')'",
    ".": "'.' is only allowed inside a number, e.g. '0.5'",
    "'": "text in quotes is not an expression",
    '"': "text in quotes is not an expression",
}


def _clip(text: str, limit: int = 40) -> str:
    """``text`` shortened for a message."""
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _kind_of(value: object) -> str:
    """How a non-text value is named in a message."""
    if value is None:
        return "nothing (an empty value)"
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, Mapping):
        return "a mapping"
    if isinstance(value, list | tuple):
        return "a list"
    return f"a value of type {type(value).__name__}"


def did_you_mean(word: str, candidates: Iterable[str]) -> str | None:
    """The candidate closest to ``word`` (a case-insensitive match first), or None if none is close.

    Uses difflib's similarity ratio with its usual 0.6 cut-off; ties go to the alphabetically
    first candidate, so the answer does not depend on the order of ``candidates``.
    """
    pool = sorted(set(candidates))
    lowered = word.lower()
    for cand in pool:
        if cand.lower() == lowered and cand != word:
            return cand
    best: tuple[float, str] | None = None
    matcher = difflib.SequenceMatcher()
    matcher.set_seq2(word)
    for cand in pool:
        if cand == word:
            continue
        matcher.set_seq1(cand)
        if matcher.real_quick_ratio() < 0.6 or matcher.quick_ratio() < 0.6:
            continue
        ratio = matcher.ratio()
        if ratio >= 0.6 and (best is None or ratio > best[0]):
            best = (ratio, cand)
    return None if best is None else best[1]


# ---------------------------------------------------------------------------------------------
# Numbers
# ---------------------------------------------------------------------------------------------


def _literal_value(literal: str, offset: int) -> sp.Rational:
    """The exact value of an unsigned number literal matched by ``_NUMBER_RE``."""
    mantissa, _, exponent_text = literal.replace("E", "e").partition("e")
    whole, _, fraction = mantissa.partition(".")
    digits = whole + fraction
    if len(digits) > MAX_DIGITS:
        raise ExprError(
            f"the number '{_clip(literal)}' has too many digits ({len(digits)}; the limit is {MAX_DIGITS})",
            offset,
        )
    exponent = 0
    if exponent_text:
        sign = -1 if exponent_text.startswith("-") else 1
        magnitude = exponent_text.lstrip("+-").lstrip("0")
        if len(magnitude) > 4 or (magnitude and int(magnitude) > _MAX_DECIMAL_EXPONENT):
            raise ExprError(
                f"the decimal exponent of the number '{_clip(literal)}' is out of range "
                f"(the limit is ±{_MAX_DECIMAL_EXPONENT})",
                offset,
            )
        exponent = sign * int(magnitude or "0")
    scale = exponent - len(fraction)
    numerator = int(digits)
    if scale >= 0:
        return sp.Rational(numerator * 10**scale, 1)
    return sp.Rational(numerator, 10**-scale)


def _check_integer_size(value: int) -> None:
    if abs(value) >= 10**MAX_DIGITS:
        raise ExprError(f"the number has too many digits (the limit is {MAX_DIGITS})", 0)


def number_to_rational(value: int | float | str) -> sp.Rational:
    """The exact rational value of a number: an int, a float or a numeric string.

    A float goes through ``repr`` (``0.065`` is ``13/200``, not the nearest binary fraction); a
    string must be one signed number literal (``"1e-3"`` is ``1/1000``), surrounding whitespace
    allowed. Raises :class:`ExprError` for anything else: a boolean, nan/inf, a non-numeric string,
    too many digits, or a decimal exponent beyond ±300.
    """
    if isinstance(value, bool):
        raise ExprError("expected a number, found a boolean")
    if isinstance(value, int):
        _check_integer_size(value)
        return sp.Integer(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ExprError(f"expected a finite number, found {value!r}")
        text = repr(float(value))
    elif isinstance(value, str):
        text = value
    else:
        raise ExprError(f"expected a number, found {_kind_of(value)}")
    if len(text) > MAX_LENGTH:
        raise ExprError(f"the number is too long ({len(text)} characters; the limit is {MAX_LENGTH})", MAX_LENGTH)
    start = len(text) - len(text.lstrip())
    stripped = text.strip()
    if not _SIGNED_NUMBER_RE.fullmatch(stripped):
        raise ExprError(f"expected a number, found '{_clip(stripped)}'", start)
    negative = stripped.startswith("-")
    unsigned = stripped.lstrip("+-")
    result = _literal_value(unsigned, start + len(stripped) - len(unsigned))
    return sp.Rational(-result.p, result.q) if negative else result


# ---------------------------------------------------------------------------------------------
# Tokens and parser
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class _Token:
    kind: str  # "number", "name", "op" or "end"
    text: str
    offset: int

    def describe(self) -> str:
        return "the end of the text" if self.kind == "end" else f"'{_clip(self.text)}'"

    def is_op(self, *ops: str) -> bool:
        return self.kind == "op" and self.text in ops


def _bits(number: sp.Rational) -> int:
    return max(int(number.p).bit_length(), int(number.q).bit_length())


def _power_bits(base: sp.Expr, exponent: sp.Rational) -> int:
    """An upper bound on the bits of the numbers ``base**exponent`` may create, before building it."""
    total = sum(int(r.p).bit_length() + int(r.q).bit_length() for r in base.atoms(sp.Rational))
    return total * max(1, abs(int(exponent.p)))


def _new_nodes(expr: sp.Expr) -> Iterable[sp.Basic]:
    """``expr``, its arguments and theirs: where a new node can hold new numbers or infinities.

    The operands were checked when they were built; evaluation (sympy folding numbers and
    distributing a coefficient over a sum) only changes the top two levels of the new node.
    """
    yield expr
    for arg in expr.args:
        yield arg
        yield from arg.args


def _problem(nodes: Iterable[sp.Basic]) -> str | None:
    """What is wrong with these nodes: a non-finite value, a too large number, or nothing."""
    for node in nodes:
        if node in _NON_FINITE:
            return "not finite"
        if isinstance(node, sp.Rational) and _bits(node) > _MAX_NUMBER_BITS:
            return "too large"
    return None


def _too_large_message() -> str:
    return f"a number in the expression is too large (more than about {_MAX_NUMBER_DIGITS} digits)"


class ExpressionParser:
    """One parse of one text: tokens are scanned lazily, so the first error is the leftmost."""

    def __init__(self, text: str, symbols: Mapping[str, sp.Expr]) -> None:
        self.text = text
        self.symbols = symbols
        self.pos = 0
        self.prev: _Token | None = None
        self.tok = self._scan()

    # -- tokens -------------------------------------------------------------------------------

    def _scan(self) -> _Token:
        text = self.text
        pos = self.pos
        end = len(text)
        while pos < end and text[pos] in _WHITESPACE:
            pos += 1
        if pos >= end:
            self.pos = end
            return _Token("end", "", end)
        char = text[pos]
        match = _NUMBER_RE.match(text, pos)
        if match:
            self.pos = match.end()
            return _Token("number", match.group(), pos)
        match = _NAME_RE.match(text, pos)
        if match:
            self.pos = match.end()
            return _Token("name", match.group(), pos)
        for op in _OPERATORS:
            if text.startswith(op, pos):
                self.pos = pos + len(op)
                return _Token("op", op, pos)
        hint = _CHAR_HINTS.get(char)
        if hint is None and char.isalpha():
            hint = "names use only the letters A-Z and a-z, digits and '_', e.g. 'theta'"
        raise ExprError(f"unexpected character {char!r}", pos, hint)

    def _advance(self) -> _Token:
        tok = self.tok
        self.prev = tok
        self.tok = self._scan()
        return tok

    @staticmethod
    def _enter(depth: int, tok: _Token) -> int:
        if depth > MAX_DEPTH:
            raise ExprError(
                f"the expression is nested too deeply (more than {MAX_DEPTH} levels of parentheses, "
                "function calls, signs or powers)",
                tok.offset,
            )
        return depth

    def _missing_expression(self) -> ExprError:
        tok = self.tok
        where = "" if self.prev is None else f" after {self.prev.describe()}"
        hint = None
        if tok.is_op(")") and self.prev is not None and self.prev.is_op("("):
            hint = "the parentheses are empty"
        return ExprError(f"expected an expression{where}, found {tok.describe()}", tok.offset, hint)

    def _unexpected_after_operand(self, closing: str | None) -> ExprError:
        tok = self.tok
        expected = "an operator or the end of the text" if closing is None else f"an operator or '{closing}'"
        hint = None
        if tok.kind in ("number", "name") or tok.is_op("("):
            hint = "write multiplication with '*', e.g. '2*x'"
        elif tok.is_op(","):
            hint = "',' only separates the arguments of a function call"
        elif tok.is_op(")") and closing is None:
            return ExprError("unmatched ')': there is no '(' before it", tok.offset)
        after = "" if self.prev is None else f" after {self.prev.describe()}"
        return ExprError(f"expected {expected}{after}, found {tok.describe()}", tok.offset, hint)

    # -- grammar ------------------------------------------------------------------------------

    def parse(self) -> sp.Expr:
        if self.tok.kind == "end":
            raise ExprError("empty expression", 0)
        result = self._sum(0)
        if self.tok.kind != "end":
            raise self._unexpected_after_operand(None)
        self._check(result, 0, sp.preorder_traversal(result))
        return result

    def _sum(self, depth: int) -> sp.Expr:
        left = self._product(depth)
        while self.tok.is_op("+", "-"):
            op = self._advance()
            right = self._product(depth)
            left = sp.Add(left, right) if op.text == "+" else sp.Add(left, sp.Mul(sp.S.NegativeOne, right))
            self._check(left, op.offset)
        return left

    def _product(self, depth: int) -> sp.Expr:
        left = self._unary(depth)
        while self.tok.is_op("*", "/"):
            op = self._advance()
            right = self._unary(depth)
            if op.text == "*":
                left = sp.Mul(left, right)
            else:
                if right == 0:
                    raise ExprError("division by zero", op.offset)
                left = sp.Mul(left, sp.Pow(right, sp.S.NegativeOne))
            self._check(left, op.offset)
        return left

    def _unary(self, depth: int) -> sp.Expr:
        if self.tok.is_op("+", "-"):
            op = self._advance()
            operand = self._unary(self._enter(depth + 1, op))
            return operand if op.text == "+" else sp.Mul(sp.S.NegativeOne, operand)
        return self._power(depth)

    def _power(self, depth: int) -> sp.Expr:
        base = self._primary(depth)
        if not self.tok.is_op("**", "^"):
            return base
        op = self._advance()
        first = self.tok
        exponent = self._unary(self._enter(depth + 1, op))
        source = self.text[first.offset : self.prev.offset + len(self.prev.text)] if self.prev else ""
        if not isinstance(exponent, sp.Rational):
            raise ExprError(
                f"the exponent must be a number, found '{_clip(source)}'",
                first.offset,
                "a power needs a rational number exponent, e.g. 2, -1 or 1/2",
            )
        if abs(exponent) > MAX_EXPONENT:
            shown = f" {exponent}" if _bits(exponent) <= 64 else ""
            raise ExprError(
                f"the exponent{shown} is too large (the limit is ±{MAX_EXPONENT})",
                first.offset,
                None if shown else f"the exponent is '{_clip(source)}'",
            )
        if base == 0 and exponent < 0:
            raise ExprError("division by zero (0 to a negative power)", op.offset)
        if _power_bits(base, exponent) > _MAX_NUMBER_BITS:
            raise ExprError(_too_large_message(), op.offset)
        result = sp.Pow(base, exponent)
        self._check(result, op.offset)
        return result

    def _primary(self, depth: int) -> sp.Expr:
        tok = self.tok
        if tok.kind == "number":
            value = _literal_value(tok.text, tok.offset)
            self._advance()
            return value
        if tok.kind == "name":
            return self._name(depth)
        if tok.is_op("("):
            self._advance()
            inner = self._sum(self._enter(depth + 1, tok))
            self._close(tok, None)
            return inner
        raise self._missing_expression()

    def _close(self, opening: _Token, function: str | None) -> None:
        """Consume the ')' that closes ``opening``."""
        if self.tok.is_op(")"):
            self._advance()
            return
        if self.tok.kind == "end":
            what = "'('" if function is None else f"'(' of the call to '{function}'"
            raise ExprError(f"unclosed {what}: expected ')', found the end of the text", opening.offset)
        raise self._unexpected_after_operand(")")

    def _name(self, depth: int) -> sp.Expr:
        tok = self.tok
        name = tok.text
        if name in self.symbols or name in CONSTANTS:
            value = self.symbols[name] if name in self.symbols else CONSTANTS[name]
            self._advance()
            if self.tok.is_op("("):
                raise ExprError(
                    f"'{name}' is not a function",
                    tok.offset,
                    f"write multiplication with '*', e.g. '{name}*(...)'",
                )
            return value
        if name in FUNCTIONS:
            function, arity = FUNCTIONS[name]
            self._advance()
            if not self.tok.is_op("("):
                raise ExprError(
                    f"expected '(' after the function '{name}', found {self.tok.describe()}",
                    self.tok.offset,
                    f"call it as '{name}(...)'",
                )
            opening = self._advance()
            args = self._arguments(name, opening, self._enter(depth + 1, opening))
            if len(args) != arity:
                plural = "argument" if arity == 1 else "arguments"
                raise ExprError(f"{name}() takes {arity} {plural}, found {len(args)}", tok.offset)
            result = function(*args)
            if _problem(_new_nodes(result)) == "not finite":
                raise ExprError(f"the result of {name}(...) is not a finite number", tok.offset)
            self._check(result, tok.offset)
            return result
        raise self._unknown_name(tok)

    def _arguments(self, name: str, opening: _Token, depth: int) -> list[sp.Expr]:
        args: list[sp.Expr] = []
        if self.tok.is_op(")"):
            self._advance()
            return args
        while True:
            args.append(self._sum(depth))
            if self.tok.is_op(","):
                self._advance()
                continue
            if self.tok.is_op(")") or self.tok.kind == "end":
                self._close(opening, name)
                return args
            raise ExprError(
                f"expected ',' or ')' after argument {len(args)} of '{name}', found {self.tok.describe()}",
                self.tok.offset,
                "write multiplication with '*', e.g. '2*x'" if self.tok.kind != "op" else None,
            )

    def _unknown_name(self, tok: _Token) -> ExprError:
        known = [*self.symbols, *CONSTANTS, *FUNCTIONS]
        close = did_you_mean(tok.text, known)
        if close is not None:
            hint = f"did you mean '{close}'?"
        else:
            ordered = [*sorted(self.symbols), *sorted(CONSTANTS), *sorted(FUNCTIONS)]
            listed = ", ".join(ordered[:_MAX_LISTED_NAMES])
            more = ", ..." if len(ordered) > _MAX_LISTED_NAMES else ""
            hint = f"known names: {listed}{more}"
        return ExprError(f"unknown name '{_clip(tok.text)}'", tok.offset, hint)

    @staticmethod
    def _check(expr: sp.Expr, offset: int, nodes: Iterable[sp.Basic] | None = None) -> None:
        """Refuse a new node that is not finite or holds a too large number."""
        problem = _problem(_new_nodes(expr) if nodes is None else nodes)
        if problem == "not finite":
            raise ExprError("the result is not a finite number", offset)
        if problem == "too large":
            raise ExprError(_too_large_message(), offset)


def parse_expression(
    text: str | int | float, symbols: Mapping[str, sp.Symbol | sp.Expr], *, max_length: int | None = MAX_LENGTH
) -> sp.Expr:
    """Parse a spec expression into a sympy expression, exactly, without evaluating any code.

    ``text`` is an expression string, or a YAML number (an int becomes ``sp.Integer``, a float
    the exact rational of its ``repr``). Names are looked up in ``symbols`` (exact,
    case-sensitive), then :data:`CONSTANTS`, then :data:`FUNCTIONS`. Raises :class:`ExprError`
    (with the offset of the offending token and, where useful, a hint) for anything else.
    ``max_length``: the longest text read (:data:`MAX_LENGTH`, the limit of what a user writes); None
    for text tutgen wrote itself (a large arm's result in the JSON runs to tens of thousands of
    characters), whose nesting is still limited by :data:`MAX_DEPTH`.
    """
    if isinstance(text, bool):
        raise ExprError("expected an expression, found a boolean")
    if isinstance(text, int | float):
        return number_to_rational(text)
    if not isinstance(text, str):
        raise ExprError(f"expected an expression, found {_kind_of(text)}")
    if max_length is not None and len(text) > max_length:
        raise ExprError(f"the expression is too long ({len(text)} characters; the limit is {max_length})", max_length)
    return ExpressionParser(text, symbols).parse()
