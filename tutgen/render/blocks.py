"""The vocabulary of a worked solution's template context: parts, blocks and sections of plain data.

The context holds strings, lists and dicts only. Text is RAW (user or engine wording, not escaped);
maths is LaTeX in the safe subset that KaTeX, MathJax and GitHub all render (``aligned``, ``bmatrix``,
``\\boldsymbol``; no ``\\label``, no packages beyond amsmath). Each template escapes text with its own
filter (``md_escape`` or ``latex_escape``) and lays out the maths.

Blocks, the items of ``section.blocks``:

- ``{"kind": "text", "parts": [...]}``: a paragraph; each part is ``{"kind": "text", "text": ...}``
  (plain), ``{"kind": "strong", "text": ...}`` (bold) or ``{"kind": "math", "tex": ...}`` (inline maths);
- ``{"kind": "subheading", "text": ...}``: a short bold lead-in, e.g. a body's name;
- ``{"kind": "math", "tex": ..., "lines": [...], "rows": [...]}``: displayed maths; ``tex`` is the
  display on one line, ``lines`` are the equations of a list ``a = …,\\quad b = …`` one by one, and
  ``rows`` is empty when ``tex`` fits the line, else the rows of one alignment that the template sets
  in ``align*`` (LaTeX) or ``aligned`` (Markdown): each row has one ``&``, before its relation sign
  (the line breaking of tutgen.render.layout; nothing is ever scaled to fit);
- ``{"kind": "boxed", "tex": ..., "lines": [...], "rows": [...]}``: a displayed final answer, set
  apart (its rows are laid out a little narrower, for the box);
- ``{"kind": "freebody", "body": ..., "tikz": ..., "svg": ..., "labels": [...]}``: a body's free-body
  diagram in the planar Newton–Euler step: ``tikz`` the picture for LaTeX (set at its size, never
  scaled), ``svg`` the relative name of its SVG beside a Markdown solution, ``labels`` what it names
  (tutgen.render.sections.newton_euler.freebody_block).

``remarks`` and ``checks`` (tutgen's own sentences, maths typeset), ``section.intro``,
``statement_parts`` (the statement, its ``$…$`` maths typeset) and each item of ``given`` and of
``coordinates`` are lists of parts as above; ``statement`` is the raw text.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import sympy as sp

from tutgen.engine.derivation import Derivation
from tutgen.model.system import System
from tutgen.model.text import MathSpan, Placeholder, RichText
from tutgen.render.layout import BOXED_WIDTH_PT, LINE_WIDTH_PT, layout
from tutgen.render.printer import TexPrinter

Part = dict[str, str]
Block = dict[str, Any]


def text(s: str) -> Part:
    return {"kind": "text", "text": s}


def strong(s: str) -> Part:
    return {"kind": "strong", "text": s}


def math(tex: str) -> Part:
    return {"kind": "math", "tex": tex}


def prose(s: str) -> list[Part]:
    """Engine wording with inline maths between single dollars -> parts."""
    parts: list[Part] = []
    for i, piece in enumerate(s.split("$")):
        if piece:
            parts.append(math(piece) if i % 2 else text(piece))
    return parts


def rich(value: str, tex: TexPrinter, before: str = "", after: str = "") -> list[Part]:
    """A reader's text from the spec (a statement, a description) as parts: a :class:`RichText`'s
    ``$…$`` spans typeset by the results' printer, its text parts (and a plain ``str``) kept as text for
    the template to escape. ``before``/``after`` are wording of tutgen's own around it."""
    parts: list[Part] = [text(before)] if before else []
    for piece in value.parts if isinstance(value, RichText) else (value,):
        if isinstance(piece, Placeholder):
            parts.append(math(quoted_value(tex.system, piece.name)))
        elif isinstance(piece, MathSpan):
            span_tex = tex.with_names(_free_names(piece))
            printed = [span_tex(t) for t in piece.terms]
            chain = printed[0]
            for rel, term in zip(piece.relations, printed[1:], strict=True):
                chain += f" {_RELATION_TEX.get(rel, rel)} {term}"
            parts.append(math(chain))
        elif piece:
            parts.append(text(piece))
    if after:
        parts.append(text(after))
    merged: list[Part] = []
    for part in parts:  # neighbouring text parts as one
        if merged and part["kind"] == merged[-1]["kind"] == "text":
            merged[-1] = text(merged[-1]["text"] + part["text"])
        else:
            merged.append(part)
    return merged


def quoted_value(system: System, name: str) -> str:
    """What a statement's placeholder ``{m}`` prints: the parameter's value in its unit as written
    (``1.5\\ \\mathrm{kg}``, this variant's on a tutorial sheet), or its symbol when it has no value."""
    from tutgen.spec.units import decimal_text, in_unit

    p = next(p for p in system.parameters if p.name == name)
    if p.value is None:
        return p.latex
    number = in_unit(p.value, p.unit)
    shown = decimal_text(number) if number.is_Rational else TexPrinter(system)(number)
    return shown + (unit_tex(p.unit) if p.unit else "")


_RELATION_TEX = {"!=": "\\ne", "<=": "\\le", ">=": "\\ge"}


def _free_names(span: MathSpan) -> dict[sp.Symbol, str]:
    """How the names a statement's maths uses without declaring them are typeset (``q_ddot`` -> q̈,
    ``T``, the function names of ``H(q)``): by the spec's rule for display names."""
    from sympy.core.function import AppliedUndef

    from tutgen.spec.names import default_latex

    names: dict[sp.Symbol, str] = {}
    for term in span.terms:
        if not isinstance(term, sp.Basic):  # a plain number
            continue
        for s in term.free_symbols:
            if isinstance(s, sp.Symbol):
                names[s] = default_latex(s.name)
        for f in term.atoms(AppliedUndef):
            names[sp.Symbol(f.func.__name__)] = default_latex(f.func.__name__)
    return names


def para(*parts: Part | list[Part]) -> Block:
    flat: list[Part] = []
    for p in parts:
        flat += p if isinstance(p, list) else [p]
    return {"kind": "text", "parts": flat}


_LISTED = re.compile(r"[\\{}]")


def split_list(tex: str) -> list[str]:
    """The equations of a display written as a list ``a = 1,\\quad b = 2``, each on its own: a LaTeX
    template may set them on separate lines (Markdown shows ``tex`` as one line)."""
    lines: list[str] = []
    depth, start, sep = 0, 0, ",\\quad "
    i, n = 0, len(tex)
    while i < n:
        found = _LISTED.search(tex, i)  # a command or a brace: nothing else changes anything
        if found is None:
            break
        i = found.start()
        ch = tex[i]
        if ch == "\\" and tex.startswith(sep[1:], i) and depth == 0 and i > 0 and tex[i - 1] == ",":
            lines.append(tex[start : i - 1])
            i += len(sep) - 1
            start = i
            continue
        if ch == "\\":
            i += 2
            continue
        depth += 1 if ch == "{" else -1
        i += 1
    lines.append(tex[start:])
    return [ln.strip() for ln in lines]


def display(tex: str, kind: str = "math", stack: bool = False) -> Block:
    """A displayed formula (or a list of equations joined by ``,\\quad``), laid out to the line width;
    ``stack`` sets the equations one a line, relation signs aligned, even when they would fit on one."""
    lines = split_list(tex)
    width = BOXED_WIDTH_PT if kind == "boxed" else LINE_WIDTH_PT
    return {"kind": kind, "tex": tex, "lines": lines, "rows": layout(lines, width, stack=stack)}


def stacked(equations: list[str]) -> Block:
    """Equations one a line, their relation signs aligned (a derivation's steps, a program)."""
    return display(",\\quad ".join(equations), stack=True)


def boxed(tex: str) -> Block:
    return display(tex, "boxed")


def subheading(s: str) -> Block:
    return {"kind": "subheading", "text": s}


def section(title: str, intro: str = "") -> dict[str, Any]:
    return {"title": title, "intro": prose(intro), "blocks": []}


def chain(name: str, *forms: str) -> str:
    """name = form1 = form2, without repeating a form that prints the same."""
    shown: list[str] = []
    for f in forms:
        if f not in shown and f != name:
            shown.append(f)
    return " = ".join([name, *shown]) if shown else ""


def as_number(expr: Any) -> Any:
    """A number as a float (the printer rounds it to 4 significant figures); a formula that still has
    symbols stays exact, as a person writes it (m R^2/4, not 0.25 R^2 m)."""
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(as_number)
    expr = sp.sympify(expr)
    return expr if expr.free_symbols else sp.N(expr)


def unit_tex(unit: str) -> str:
    return "\\ \\mathrm{" + unit.replace("_", "\\_").replace("%", "\\%").replace("*", "\\,") + "}"


#: results longer than this many operations (sympy.count_ops) are not printed whole in a worked
#: solution: T and L become 1/2 q_dot^T H q_dot, the equations of motion are the rows of the matrix
#: form, H, C and G are printed entry by entry, and the Christoffel symbols are left to the JSON output
#: (a fully symbolic 6-DOF arm has a million operations of them). Small problems are never affected.
PRINT_BUDGET = 4000
#: beyond this many operations even entry by entry is unreadable (the fully symbolic PUMA: 180 000);
#: a serial arm's H, C and G are then printed as the recursive program that computes them
PROGRAM_BUDGET = 40000


def ops(*exprs: Any) -> int:
    """Operations of the expressions (sympy's count_ops), exact up to PROGRAM_BUDGET, else PROGRAM_BUDGET + 1:
    a budgeted count (tutgen.render.size) that stops at the budget instead of walking 180 000 operations."""
    from tutgen.render.size import count_ops_upto

    return count_ops_upto(exprs, PROGRAM_BUDGET)


def said(count: int) -> str:
    """A count of :func:`ops` in words: "10503", or "more than 40000" past the budget."""
    from tutgen.render.size import size_text

    return size_text(count, PROGRAM_BUDGET)


def long_decimals(expr: Any) -> Any:
    """Long exact fractions (measured data: 192438147/500000000) as decimals, which the printer rounds
    to 4 significant figures; for results printed entry by entry, where exact fractions swamp the page."""
    if not isinstance(expr, sp.Basic):
        return expr
    return expr.xreplace({r: sp.Float(r, 15) for r in expr.atoms(sp.Rational) if r.q > 100})


def all_decimals(expr: Any) -> Any:
    """Every non-integer rational of an expression as a decimal (printed to 4 significant figures)."""
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(all_decimals)
    if not isinstance(expr, sp.Basic):
        return expr
    return _all_decimals(expr)


#: the subtrees :func:`_all_decimals` has put decimals into, each with its result: the same for every
#: expression, so kept across them (a sheet's variant prints the same products in H, T, L, Lagrange's
#: terms), and forgotten all at once past :data:`DECIMAL_TREES`
_DECIMAL_TREES: dict[Any, tuple[Any, bool]] = {}
DECIMAL_TREES = 1 << 17


@lru_cache(maxsize=1 << 13)
def _all_decimals(expr: sp.Basic) -> sp.Basic:
    """:func:`all_decimals` of an immutable expression, remembered (the sections ask for the same results
    over and over: T in the energies, in L and in Lagrange's terms): ``expr.xreplace({r: Float(r, 15)
    for r in expr.atoms(Rational) if r.q != 1})``, each subtree rebuilt once."""
    from tutgen.engine.replace import DECIMALS, replaced

    if len(_DECIMAL_TREES) > DECIMAL_TREES:
        _DECIMAL_TREES.clear()
    return replaced(expr, DECIMALS, _DECIMAL_TREES)[0]


def tex_name(name: str) -> str:
    """A body's or joint's name as upright text in maths (``\\mathrm{link\\_1}``)."""
    return "\\mathrm{" + name.replace("_", "\\_") + "}"


@dataclass(frozen=True)
class SolutionContext:
    """What every section builder reads: the derivation, its system, the results' printer and ``num``,
    which substitutes the parameters' values (and, on a sheet's variant, prints fractions as decimals)."""

    d: Derivation
    tex: TexPrinter
    num: Callable[[Any], Any]

    @property
    def s(self) -> System:
        return self.d.system
