"""Printing sympy results as LaTeX the way a person writes them: dotted rates, Greek names,
``\\sin\\theta`` rather than ``\\sin{\\left(\\theta \\right)}``, four significant figures."""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from typing import Any, ClassVar

import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.printing.latex import LatexPrinter

from tutgen.model.system import System
from tutgen.render import order
from tutgen.render.order import OrderedSum
from tutgen.spec.units import Dimension, si_unit_latex

SIGNIFICANT_FIGURES = 4
#: sums up to this many operations are printed in a teacher's order (collecting a bigger one costs more
#: than it helps: it is printed entry by entry or as a program anyway)
ORDER_BUDGET = 600


def format_number(x: float, figures: int = SIGNIFICANT_FIGURES) -> str:
    """A number as an engineer writes it: ``figures`` significant figures (trailing zeros dropped), as a
    decimal from 0.001 up to 9999, beyond that in engineering notation, a mantissa from 1 to 999 and an
    exponent that is a multiple of 3 (``375 \\times 10^{-6}``, ``123.5 \\times 10^{3}``): one style for every
    number of a document, so that ``0.007891`` stands beside ``0.01899``."""
    if x == 0 or not math.isfinite(x):
        return "0" if x == 0 else str(x)
    rounded = float(f"{x:.{figures - 1}e}")  # rounding first: 9.99996 is 10.00, with its exponent
    exponent = math.floor(math.log10(abs(rounded)))
    if -3 <= exponent <= 3:
        decimals = max(figures - 1 - exponent, 0)
        return _trim(f"{rounded:.{decimals}f}")
    engineering = 3 * (exponent // 3)
    decimals = max(figures - 1 - (exponent - engineering), 0)
    return f"{_trim(f'{rounded / 10**engineering:.{decimals}f}')} \\times 10^{{{engineering}}}"


def _trim(text: str) -> str:
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


class _Printer(LatexPrinter):
    """sympy's LaTeX printer with tutgen's numbers and, given the ``roles`` of the symbols, a teacher's
    order of the factors of a product and positive-lead brackets (tutgen.render.order)."""

    _default_settings: ClassVar[dict[str, Any]] = {
        **LatexPrinter._default_settings,
        "roles": None,
        "coordinate_index": None,
        "figures": SIGNIFICANT_FIGURES,
    }

    def _print_Float(self, expr: sp.Float) -> str:
        return format_number(float(expr), self._settings["figures"])

    def _print_Add(self, expr: sp.Add, order: str | None = None) -> str:
        """The terms of a sum in sympy's lex order (an ordered equation is printed term by term instead),
        each term's sign as printed: a product whose bracket gave up its minus sign prints a minus."""
        out = ""
        given = isinstance(expr, OrderedSum)  # arranged by tutgen.render.order: printed as it is
        for i, term in enumerate(expr.args if given else self._as_ordered_terms(expr, order="lex")):
            piece = str(self._print(term))
            if self._needs_add_brackets(term):
                piece = f"\\left({piece}\\right)"
            negative = piece.startswith("-")
            if negative:
                piece = piece[1:].lstrip()
            if i == 0:
                out = ("- " if negative else "") + piece
            else:
                out += (" - " if negative else " + ") + piece
        return out

    def _print_Function(self, expr: sp.Function, exp: str | None = None) -> str:
        """A function a statement names (``H(q)``, ``C(q, q_dot)``) as it is written, ``H(q)``; sympy's
        own functions as sympy prints them."""
        if not isinstance(expr, AppliedUndef):
            return str(super()._print_Function(expr, exp))
        name = self._settings["symbol_names"].get(sp.Symbol(expr.func.__name__), expr.func.__name__)
        text = f"{name}({', '.join(self._print(a) for a in expr.args)})"
        return text if exp is None else f"{text}^{{{exp}}}"

    def _print_Mul(self, expr: sp.Mul) -> str:
        """No ``1.0 x``: a unit float coefficient is left out. (Replacing it by 1 in the expression
        does not stick: sympy caches and compares Float(1.0) and 1 as the same.) With roles, the
        factors in a teacher's order, a bracket's minus sign taken outside, ``\\tfrac12`` in front."""
        coeff, rest = expr.as_coeff_Mul()
        if isinstance(coeff, sp.Float) and abs(float(coeff)) == 1.0 and rest != 1:
            body = self._print(rest)
            return body if float(coeff) > 0 else "- " + body
        roles = self._settings["roles"]
        if roles is None or rest == 1:
            return str(super()._print_Mul(expr))
        sign = -1 if coeff.is_negative else 1
        coeff = abs(coeff)
        factors: list[sp.Basic] = []
        for f in _flat_factors(rest):
            if f.is_Number:  # a number inside an unevaluated product (an arranged term's) joins the lead
                coeff *= abs(f)
                sign = -sign if f.is_negative else sign
                continue
            # (an arranged sum has a positive lead already, and negating it would lose its order)
            if isinstance(f, sp.Add) and not isinstance(f, OrderedSum) and f.could_extract_minus_sign():
                f, sign = -f, -sign
            factors.append(f)
        if not factors:
            return ("- " if sign < 0 else "") + str(self._print(coeff))
        index = self._settings["coordinate_index"] or {}
        # a named function of a statement's maths (H(q) in "H(q) q_ddot") leads, as it is written; rates
        # and accelerations by the order of their coordinates (m_2 l \dot x \dot\theta)
        factors.sort(
            key=lambda f: (
                not isinstance(f, AppliedUndef),
                order.factor_role(f, roles),
                index.get(f.as_base_exp()[0], -1),
                sp.default_sort_key(f),
            )
        )
        head = ""
        if coeff.is_Rational and not coeff.is_Integer and coeff.q <= 12 and abs(coeff.p) <= 12:
            if not any(f.is_Pow and f.exp.is_negative for f in factors):
                head, coeff = f"\\tfrac{{{coeff.p}}}{{{coeff.q}}} ", sp.S.One
        lead = [coeff] if coeff != 1 else []
        body = sp.Mul(*lead, *factors, evaluate=False) if len(factors) > 1 or lead else factors[0]
        saved = self._settings["order"]
        self._settings["order"] = "none"
        try:
            text = self._print(body) if not isinstance(body, sp.Mul) else str(super()._print_Mul(body))
        finally:
            self._settings["order"] = saved
        if isinstance(body, sp.Add) and (head or sign < 0):
            # a lone bracket after ½ or a minus keeps its brackets: ¼(a + b), −(a + b), never ¼ a + b
            text = f"\\left({text}\\right)"
        return ("- " if sign < 0 else "") + head + text


def square_outer(tex: str) -> str:
    """A bracket that holds a bracket of its own becomes a square one, as the tutorial writes
    ``[(m_1 + m_2) a_1^2 + m_2 a_2^2] \\ddot\\theta_1``. A function's own ``{\\left(x \\right)}`` is not a
    bracket here (it becomes ``\\sin x``, :func:`tidy_functions`)."""
    out: list[str] = []
    pos = 0
    while (m := _INNER_BRACKET.search(tex, pos)) is not None:
        depth, i = 0, m.start()
        while i < len(tex):
            if tex.startswith("\\left", i) and not tex[i + 5 : i + 6].isalpha():
                depth += 1
            elif tex.startswith("\\right", i) and not tex[i + 6 : i + 7].isalpha():
                depth -= 1
                if depth == 0:
                    break
            i += 1
        inner = tex[m.end() : i]
        if i >= len(tex) or not tex.startswith("\\right)", i) or not _INNER_BRACKET.search(inner):
            out.append(tex[pos : m.end()])
            pos = m.end()
            continue
        out.append(tex[pos : m.start()] + "\\left[" + square_outer(inner) + "\\right]")
        pos = i + len("\\right)")
    out.append(tex[pos:])
    return "".join(out)


def _is_sum(expr: object) -> bool:
    """A sum, or a product with a sum in it (``¼(a + b)``): what a teacher's order applies to."""
    if isinstance(expr, sp.Add):
        return True
    return isinstance(expr, sp.Mul) and any(isinstance(f, sp.Add) for f in expr.args)


def _flat_factors(expr: sp.Basic) -> list[sp.Basic]:
    """The factors of a product, products inside it (an arranged term's, unevaluated) opened."""
    out: list[sp.Basic] = []
    for f in sp.Mul.make_args(expr):
        out += _flat_factors(f) if isinstance(f, sp.Mul) else [f]
    return out


_INNER_BRACKET = re.compile(r"(?<!\{)\\left\(")
_TRIG = re.compile(r"\\(sin|cos|tan|cot|sec|csc)(\^\{[^{}]*\})?\{\\left\(")
_ATOM = re.compile(r"^(\\[A-Za-z]+|[A-Za-z])(_\{[A-Za-z0-9]+\}|_[A-Za-z0-9])?$")


def tidy_functions(tex: str) -> str:
    """``\\sin{\\left(\\theta \\right)}`` -> ``\\sin\\theta``; a longer argument keeps plain parentheses:
    ``\\cos{\\left(\\theta_{1} + \\theta_{2} \\right)}`` -> ``\\cos(\\theta_{1} + \\theta_{2})``."""
    out: list[str] = []
    pos = 0
    while (m := _TRIG.search(tex, pos)) is not None:
        # the argument runs to the brace that closes the one opened before \left(
        depth, i = 1, m.end()
        while i < len(tex) and depth:
            depth += {"{": 1, "}": -1}.get(tex[i], 0) if tex[i - 1] != "\\" else 0
            i += 1
        inner = tex[m.end() : i - 1]
        if not inner.endswith("\\right)"):
            out.append(tex[pos : m.end()])
            pos = m.end()
            continue
        arg = tidy_functions(inner[: -len("\\right)")].strip())
        head = f"\\{m.group(1)}{m.group(2) or ''}"
        if _ATOM.match(arg):
            out.append(tex[pos : m.start()] + head + ("" if arg.startswith("\\") else " ") + arg)
            if re.match(r" +(?![-+=&)},]|\\(right|end|quad|cdot|times|Bigr|bigr)\b|\\\\)", tex[i:]):
                out.append("\\,")  # cos θ θ̈, not cos θθ̈: a thin space before the next factor
        else:
            out.append(tex[pos : m.start()] + f"{head}({arg})")
        pos = i
    out.append(tex[pos:])
    return "".join(out)


#: What printers have printed, per settings (names, roles, coordinates, significant figures): the text of an
#: expression depends on these and on the expression alone, which is immutable and compared by its
#: structure (``x + 1.0`` and ``x + 1`` are different keys). A worked solution prints T, H's entries and
#: the equations' sides several times over, and a sheet's variants of a problem share the expressions
#: that hold only the parameters they share (issue 17). Each table is emptied when it reaches
#: :data:`PRINTED_MAX` entries.
_PRINTED: dict[tuple[object, ...], dict[tuple[str, sp.Basic], str]] = {}
_LEVELS: dict[tuple[object, ...], Any] = {}  # one order._Levels per roles and coordinates (its memo's key)
PRINTED_MAX = 20_000


def _printed(names: frozenset[tuple[sp.Symbol, str]], settings: tuple[object, ...]) -> dict[tuple[str, sp.Basic], str]:
    table = _PRINTED.setdefault((names, settings), {})
    if len(table) >= PRINTED_MAX:
        table.clear()
    if len(_PRINTED) > 256:  # a long-lived process (the tests) sees many systems
        _PRINTED.clear()
        _LEVELS.clear()
        table = _PRINTED.setdefault((names, settings), {})
    return table


def forget() -> None:
    """Empty every table of printed texts and of arranged terms (tests that count the work of printing)."""
    _PRINTED.clear()
    _LEVELS.clear()
    order.forget()


class TexPrinter:
    """sympy's LaTeX printer with the spec's symbol names: theta1_dot -> \\dot{\\theta}_{1}."""

    def __init__(self, system: System) -> None:
        names: dict[sp.Symbol, str] = {}
        for p in system.parameters:
            names[p.symbol] = p.latex
        for c in system.coordinates:
            names[c.q] = c.latex
            names[c.qd] = _dotted(c.latex, r"\dot")
            names[c.qdd] = _dotted(c.latex, r"\ddot")
        self.names = names
        self.system = system
        self.roles = order.symbol_roles(system)
        #: a rate's or an acceleration's coordinate index, so ẋ comes before θ̇ when x is the first coordinate
        self.coordinate_index = {s: i for i, c in enumerate(system.coordinates) for s in (c.q, c.qd, c.qdd)}
        self.kinematic_symbols = set(self.coordinate_index)
        #: the spec's significant figures for decimals (None in the spec: the default, 4)
        self.figures = getattr(system, "significant_figures", None) or SIGNIFICANT_FIGURES
        # every setting the printed text depends on: printers of the same settings (a sheet's variants of
        # one problem differ in their numbers only) share their levels and what they have printed
        coordinates = tuple((c.q, c.qd, c.qdd) for c in system.coordinates)
        level_key = (frozenset(self.roles.items()), coordinates)
        self.levels = _LEVELS.get(level_key) or _LEVELS.setdefault(level_key, order.levels_of(system))
        self._settings = (level_key, self.figures)
        self._printed = _printed(frozenset(names.items()), self._settings)

    def with_names(self, names: dict[sp.Symbol, str]) -> TexPrinter:
        """The same printer knowing more names (a statement's free symbols, ``T``, ``q_dot``)."""
        other = TexPrinter.__new__(TexPrinter)
        other.__dict__.update(self.__dict__)
        other.names = {**names, **self.names}
        other._printed = _printed(frozenset(other.names.items()), self._settings)  # other names, other text
        return other

    def name(self, names: dict[sp.Basic, str]) -> None:
        """Give symbols their LaTeX names from now on (the Newton–Euler step's unknown reactions), in this
        printer itself: what it prints after this is looked up among texts printed with these names."""
        self.names.update(names)
        self._printed = _printed(frozenset(self.names.items()), self._settings)

    def __call__(self, expr: object) -> str:
        return self._remembered("", expr, self._print)

    def _remembered(self, kind: str, expr: object, make: Callable[[Any], str]) -> str:
        """``make(expr)``, looked up first among this printer's texts of that ``kind``; a float or a
        mutable matrix is not remembered."""
        if not isinstance(expr, sp.Basic):
            return make(expr)
        key = (kind, expr)
        text = self._printed.get(key)
        if text is None:
            text = self._printed[key] = make(expr)
        return text

    def _print(self, expr: object) -> str:
        if isinstance(expr, sp.MatrixBase):
            rows = [" & ".join(self(e) for e in expr.row(i)) for i in range(expr.rows)]
            return r"\begin{bmatrix}" + r" \\ ".join(rows) + r"\end{bmatrix}"
        if isinstance(expr, float):
            expr = sp.Float(expr)
        if _is_sum(expr) and order.ops(expr) <= ORDER_BUDGET:
            if isinstance(expr, sp.Add):
                expr = order.arranged(expr, self.levels)
            else:  # a product keeps its factoring (m_2 l_2^2 (…)); its brackets are arranged, minus outside
                args: list[sp.Basic] = []
                for f in expr.args:
                    if isinstance(f, sp.Add):
                        sign, f = order.positive_lead(f)
                        args += [sp.S.NegativeOne] if sign < 0 else []
                        f = order.arranged(f, self.levels)
                    args.append(f)
                expr = sp.Mul(*args, evaluate=False)
        settings = {
            "symbol_names": self.names,
            "roles": self.roles,
            "coordinate_index": self.coordinate_index,
            "figures": self.figures,
        }
        return tidy_functions(square_outer(_Printer(settings).doprint(expr)))

    def ordered(self, expr: sp.Expr) -> str:
        """An equation of motion's side as a teacher writes it (tutgen.render.order.equation_terms):
        accelerations in coordinate order, velocity products, the rest; each bracket with a positive lead."""
        return self._remembered("ordered", expr, self._ordered)

    def _ordered(self, expr: sp.Expr) -> str:
        found = order.arranged_terms(expr, self.levels) if isinstance(expr, sp.Expr) else None
        if not found:
            return self(expr)
        pieces: list[str] = []
        for sign, body in found:
            text = self(body)
            if text.startswith("- "):  # a body printed with its own minus (a negative number factor)
                sign, text = -sign, text[2:]
            pieces.append(("- " if sign < 0 else ("+ " if pieces else "")) + text)
        return " ".join(pieces)

    def equation(self, lhs: str, expr: object, rhs: str = "", dimension: Dimension | None = None) -> str:
        """``lhs = expr`` (or ``expr = rhs`` when ``lhs`` is empty) on one line: where it breaks when it is
        too wide is decided by its typeset width when the display is laid out (tutgen.render.layout).
        With the result's ``dimension``, a numeric result carries its SI unit (:meth:`unit`)."""
        head = f"{lhs} = " if lhs else ""
        tail = f" = {rhs}" if rhs else ""
        small = isinstance(expr, sp.Expr) and order.ops(expr) <= ORDER_BUDGET
        unit = self.unit(expr, dimension) if dimension is not None and not rhs else ""
        return f"{head}{self.ordered(expr) if small else self(expr)}{unit}{tail}"

    def unit(self, value: object, dimension: Dimension | None, torque: bool = False) -> str:
        """The SI unit to print after a numeric result (``\\ \\mathrm{kg\\,m^{2}}``), or ``""``.

        A result carries its unit when its dimension is known and it is numeric: no symbol in it but
        the coordinates, their rates and accelerations, which are in SI units themselves (rad, m, per
        second), so ``T = 2.925 \\dot\\theta^2`` is in J. A result with other symbols carries its
        dimension in them and gets no unit; nor does 0, a dimensionless result, or a matrix of zeros.
        Nor does anything of a problem whose kinetic energy is given as a formula (tutorial p10).
        ``torque`` prints an energy as ``N\\,m`` (a generalized force of an angle)."""
        if dimension is None or dimension.is_dimensionless or self.system.kinetic_energy is not None:
            return ""  # (an energy the spec gives as a formula of plain numbers has no stated unit)
        entries = list(value) if isinstance(value, sp.MatrixBase) else [value]
        exprs = [sp.sympify(e) for e in entries]
        if all(e == 0 for e in exprs):
            return ""
        if any(e.free_symbols - self.kinematic_symbols for e in exprs):
            return ""
        if all(e.is_Symbol or (e.is_Pow and e.base.is_Symbol) for e in exprs):
            return ""  # θ̇ alone, say: nothing numeric to give a unit to
        return f"\\ \\mathrm{{{si_unit_latex(dimension, torque)}}}"


#: a document prints exact fractions only when every number its spec gives is an integer or a fraction
#: with a denominator up to this (½, ⅓, ¾: l/2, m l²/12); one written as a decimal (0.45 m, 2.5 cm) is a
#: measurement, and then every number of the document is a decimal (docs/typesetting.md, "Numbers")
EXACT_DENOMINATOR = 12


def is_decimal_document(system: System) -> bool:
    """Whether a worked solution prints its numbers as decimals: some number the spec gives (a parameter's
    value, a part's mass, size or place, a joint's offset) is not an integer or a short fraction."""
    given: list[object] = [p.value for p in system.parameters if p.value is not None]
    for body in system.bodies:
        for part in body.parts:
            given += [part.mass, part.density, *part.at]
            for _, measure in part.dimensions:
                given += list(measure) if isinstance(measure, tuple) else [measure]
    for joint in system.joints:
        given += [*joint.origin_offset, joint.offset]
    for value in given:
        if isinstance(value, sp.Basic):
            if value.atoms(sp.Float):
                return True
            # a denominator of 10, 20, 100, ... is a decimal as written (0.3 m is 3/10, exact as read)
            if any(r.q > EXACT_DENOMINATOR or r.q % 10 == 0 for r in value.atoms(sp.Rational)):
                return True
    return False


def _dotted(latex: str, accent: str) -> str:
    """Put the dot on the base letter, not on the subscript: \\theta_{1} -> \\dot{\\theta}_{1}."""
    base, sep, sub = latex.partition("_")
    return f"{accent}{{{base}}}{sep}{sub}"
