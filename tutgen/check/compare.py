"""Comparing answers with one spec's results: equivalence, not string equality.

The results are the ``results`` of tutgen's JSON output (the public contract), parsed back with the
spec grammar's parser; answers are parsed by the same parser with the same names. Rules (also in
docs/check.md):

- Two expressions are equal when their difference expands to 0, or reduces to 0 by trigonometric
  identities (:func:`tutgen.engine.tidy.trig_reduce`), or, when neither decides, when it vanishes
  at :data:`TRIALS` random states (the report says which way was used).
- Numbers are equal within a tolerance (:class:`~tutgen.check.answers.Tolerance`); a number with a
  unit is converted to SI and its dimension checked where the result's dimension is known.
- An equation of motion may be written ``lhs = rhs`` and is accepted up to moving terms across the
  ``=`` and up to a non-zero constant factor (a number or a product of parameters).
- A Christoffel table in the other convention (first kind for the tutorial's, or the reverse) is
  accepted with a remark; so are principal axes that point the other way.
- Tables and matrices are compared entry by entry, and each entry is named as in the reports:
  ``mass_matrix[1,2]``, ``christoffel[1,1,2]``, ``lagrange_terms[2].dL_dq``.

A wrong entry says what differs where that can be seen: a sign, a constant factor, a missing or extra
term, or the coefficient of a term in the coordinates and rates.
"""

from __future__ import annotations

import math
import re
import weakref
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field, replace
from decimal import ROUND_HALF_UP, Decimal, InvalidOperation
from enum import StrEnum
from fractions import Fraction
from functools import lru_cache
from typing import Any

import sympy as sp

from tutgen.check.answers import (
    AnswerItem,
    AnswerSheet,
    Segment,
    Tolerance,
    is_tolerance_form,
    item_tolerance,
)
from tutgen.engine.tidy import random_states as tidy_random_states
from tutgen.engine.tidy import trig_reduce
from tutgen.errors import SpecError, SpecErrors
from tutgen.render.jsonout import expr_text  # the spec grammar, as the JSON writes it
from tutgen.spec.expr import ExprError, did_you_mean, number_to_rational, parse_expression
from tutgen.spec.loader import KeyPath
from tutgen.spec.units import Dimension, parse_quantity, parse_unit

__all__ = [
    "NUMERIC_HOW",
    "SEED",
    "TRIALS",
    "EntryResult",
    "ItemResult",
    "Reference",
    "Status",
    "check_sheet",
    "diagnose",
    "equal_how",
    "expr_text",
    "reference_from",
]

#: Random states tried when symbolic simplification cannot decide, and the seed that picks them.
TRIALS = 12
SEED = 4245
NUMERIC_HOW = (
    f"numeric: equal at {TRIALS} random states (seed {SEED}, every symbol drawn from [0.3, 2.7]); "
    "symbolic simplification did not decide"
)
#: How many differences one wrong entry lists before "and N more".
_MAX_DIFFERENCES = 3
#: Results whose entries are one per coordinate, so a coordinate name may stand for an index.
_PER_COORDINATE = frozenset(
    {"equations_of_motion", "lagrange_terms", "generalized_forces", "coriolis_vector", "gravity_vector"}
)
#: Result fields that are names, compared as text.
_TEXT_FIELDS = frozenset({"coordinate", "shape", "method", "remarks"})

_M, _L, _T = Dimension(mass=1), Dimension(length=1), Dimension(time=1)
_ONE = Dimension()
_ENERGY = Dimension(1, 2, -2)
_INERTIA = Dimension(1, 2, 0)
#: The dimension of a result field, where it does not depend on the spec.
_DIMENSION_OF: Mapping[str, Dimension] = {
    "mass": _M,
    "volume": Dimension(length=3),
    "center_of_mass": _L,
    "centroid": _L,
    "axis_distances": _L,
    "positions": _L,
    "inertia_tensor": _INERTIA,
    "inertia_tensor_com": _INERTIA,
    "inertia_centroid": _INERTIA,
    "principal_moments": _INERTIA,
    "principal_axes": _ONE,
    "velocities": _L / _T,
    "angular_velocities": _ONE / _T,
    "speeds_squared": (_L / _T) ** 2,
    "kinetic_energy": _ENERGY,
    "potential_energy": _ENERGY,
    "lagrangian": _ENERGY,
    "body_kinetic_energies": _ENERGY,
    "force": Dimension(1, 1, -2),  # newton_euler.reaction_forces.<joint>.force
    "moment": _ENERGY,
}
_NUMBER_RE = re.compile(r"\s*[-+]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][-+]?[0-9]+)?")
_CHRISTOFFEL_KEY_RE = re.compile(
    r"[A-Za-z]?\[?\s*([0-9]+)\s*,\s*([0-9]+)\s*,\s*([0-9]+)\s*\]?"  # 1,1,2  h[1,1,2]
    r"|[A-Za-z]?([1-9])([1-9])([1-9])"  # 112  h112  c112
)
_OTHER_TABLE = {"christoffel": "christoffel_first_kind", "christoffel_first_kind": "christoffel"}
_TABLE_WORDS = {
    "christoffel": "the tutorial's three-index symbols h_ijk",
    "christoffel_first_kind": "the symmetric Christoffel symbols of the first kind c_ijk",
}


class Status(StrEnum):
    CORRECT = "correct"
    WRONG = "wrong"
    MISSING = "missing"


@dataclass(frozen=True)
class EntryResult:
    """The verdict on one entry (a scalar) of an answer."""

    name: str  # as in the reports: mass_matrix[1,2]
    status: Status
    how: str = ""  # how a correct entry was decided ("exact: ...", "numeric: ...", "within rel_tol ...")
    feedback: str = ""  # what differs (wrong), what is missing, or a remark
    location: str = ""  # file:line:col of the answer
    given: str | None = None  # the answer as written
    expected: str | None = None  # the result, as in tutgen's JSON


@dataclass(frozen=True)
class ItemResult:
    """The verdict on one answer of the file (a top-level key): the worst of its entries."""

    name: str
    status: Status
    entries: tuple[EntryResult, ...]
    remarks: tuple[str, ...] = ()
    location: str = ""

    @property
    def problems(self) -> tuple[EntryResult, ...]:
        """The entries that are wrong or missing."""
        return tuple(e for e in self.entries if e.status is not Status.CORRECT)


@dataclass(frozen=True, eq=False)
class Reference:
    """What answers are compared with: one spec's results and the names its expressions use.

    Plain data and sympy symbols only, so it can be sent to worker processes. Compared by identity,
    so that each process parses a reference's result expressions once (:func:`_result_cache`).
    """

    spec: str
    title: str
    results: dict[str, Any]
    symbols: dict[str, sp.Symbol]
    values: dict[sp.Symbol, sp.Expr]
    coordinates: tuple[str, ...]
    state: frozenset[sp.Symbol]  # every q, q_dot, q_ddot
    forces: frozenset[sp.Symbol] = field(default_factory=frozenset)  # symbols of the generalized forces


def reference_from(system: Any, derivation: Any, spec: str) -> Reference:
    """The :class:`Reference` of a derived spec (a System and its Derivation)."""
    from tutgen.render.jsonout import derivation_to_json

    doc = derivation_to_json(derivation)
    symbols: dict[str, sp.Symbol] = {p.name: p.symbol for p in system.parameters}
    state: set[sp.Symbol] = set()
    for c in system.coordinates:
        symbols[c.name], symbols[f"{c.name}_dot"], symbols[f"{c.name}_ddot"] = c.q, c.qd, c.qdd
        state |= {c.q, c.qd, c.qdd}
    forces: set[sp.Symbol] = set()
    if derivation.generalized_forces is not None:
        forces = set(derivation.generalized_forces.free_symbols) - state
    return Reference(
        spec=spec,
        title=system.title,
        results=doc["results"],
        symbols=symbols,
        values=dict(system.values),
        coordinates=tuple(c.name for c in system.coordinates),
        state=frozenset(state),
        forces=frozenset(forces),
    )


# ---------------------------------------------------------------------------------------------
# Names of entries
# ---------------------------------------------------------------------------------------------

Path = tuple[str | int, ...]


def entry_name(path: Path) -> str:
    """``("mass_matrix", 0, 1)`` is ``mass_matrix[1,2]``; ``("christoffel", "1,1,2")`` is
    ``christoffel[1,1,2]``; ``("lagrange_terms", 1, "dL_dq")`` is ``lagrange_terms[2].dL_dq``."""
    text = ""
    group: list[str] = []
    for part in (*path, None):
        if isinstance(part, int):
            group.append(str(part + 1))
            continue
        if isinstance(part, str) and re.fullmatch(r"[0-9]+(?:,[0-9]+)*", part):
            group.append(part)
            continue
        if group:
            text += "[" + ",".join(group) + "]"
            group = []
        if part is not None:
            text += ("." if text else "") + part
    return text


def _field(path: Path) -> str | None:
    """The result field a path is in: ``inertia_tensor`` for ``bodies.body.parts.block.inertia_tensor[1,1]``."""
    if not path:
        return None
    if path[0] == "bodies":
        if len(path) >= 3 and path[2] == "parts":
            return str(path[4]) if len(path) >= 5 else None
        return str(path[2]) if len(path) >= 3 else None
    if path[0] == "lagrange_terms" and len(path) >= 3:
        return str(path[2])
    if path[0] == "newton_euler" and len(path) >= 2:
        if path[1] == "reaction_forces":
            return str(path[3]) if len(path) >= 4 else None
        return str(path[1])
    return str(path[0])


def _per_coordinate(path: Path) -> bool:
    """Whether ``path`` is a list with one entry per coordinate (a coordinate name may index it)."""
    return (len(path) == 1 and path[0] in _PER_COORDINATE) or path == ("newton_euler", "equations_of_motion")


# ---------------------------------------------------------------------------------------------
# Deciding equality
# ---------------------------------------------------------------------------------------------


def random_states(symbols: Iterable[sp.Symbol]) -> Iterator[dict[sp.Symbol, sp.Expr]]:
    """TRIALS states, the same for the same symbols: each symbol a random k/1000 in [0.3, 2.7]."""
    return tidy_random_states(symbols, TRIALS, SEED)


def _value(expr: sp.Expr, state: Mapping[sp.Symbol, sp.Expr]) -> complex | None:
    """``expr`` at ``state`` as a complex number, or None where it is not finite (a pole)."""
    try:
        value = complex(sp.N(expr.xreplace(dict(state)), 30))
    except (TypeError, ValueError, ZeroDivisionError):
        return None
    return value if math.isfinite(value.real) and math.isfinite(value.imag) else None


def vanishes_at_states(expr: sp.Expr) -> bool:
    """Whether ``expr`` is 0 (to 1e-9 of the size of its terms) at the random states where it is finite,
    and finite at most of them. (Unlike :func:`tutgen.engine.tidy.numerically_zero`, which draws more states
    until enough are finite, a report needs the fixed TRIALS states it names.)"""
    terms = sp.Add.make_args(expr)
    finite = 0
    for state in random_states(expr.free_symbols):
        value = _value(expr, state)
        sizes = [_value(t, state) for t in terms]
        if value is None or any(v is None for v in sizes):
            continue
        finite += 1
        scale = max([1.0, *(abs(v) for v in sizes if v is not None)])
        if abs(value) > 1e-9 * scale:
            return False
    return finite > TRIALS // 2


def equal_how(difference: sp.Expr) -> str | None:
    """How ``difference`` was shown to be 0 (symbolically, else at random states), or None if it is not."""
    e = sp.expand(difference)
    if e == 0:
        return "exact: the difference expands to 0"
    if e.has(sp.sin, sp.cos) and trig_reduce(e) == 0:
        return "exact: equal by trigonometric identities"
    if e.free_symbols and vanishes_at_states(e):
        return NUMERIC_HOW
    return None


@lru_cache(maxsize=8192)
def _reduced(expr: sp.Expr) -> sp.Expr:
    return trig_reduce(expr) if expr.has(sp.sin, sp.cos) else sp.expand(expr)


def _groups(expr: sp.Expr, state: frozenset[sp.Symbol] | None) -> dict[sp.Expr, sp.Expr]:
    """``expr`` (expanded) as {monomial: coefficient}: by monomials in the state symbols with
    coefficients in the parameters, or (``state`` None) by monomials with numeric coefficients."""
    out: dict[sp.Expr, sp.Expr] = {}
    for term in sp.Add.make_args(expr):
        if state is None:
            coeff, key = term.as_coeff_Mul()
        else:
            coeff, key = term.as_independent(*state, as_Add=False)
        out[key] = out.get(key, sp.S.Zero) + coeff
    return {k: v for k, v in out.items() if sp.expand(v) != 0}


def _constant_factor(
    given: sp.Expr,
    correct: sp.Expr,
    state: frozenset[sp.Symbol],
    forbidden: frozenset[sp.Symbol],
    *,
    monomial: bool = False,
) -> sp.Expr | None:
    """A non-zero ``k`` free of the state (and of ``forbidden``) with given = k * correct, or None.
    With ``monomial``, only a product of powers (2, m2, 1/l) counts, not a ratio of sums."""
    if correct == 0 or given == 0:
        return None
    grouping = state if (given.free_symbols | correct.free_symbols) & state else None
    g, c = _groups(_reduced(given), grouping), _groups(_reduced(correct), grouping)
    tried: set[sp.Expr] = set()
    candidates = [sp.cancel(sp.together(given / correct))]
    candidates += [sp.cancel(g[key] / coeff) for key, coeff in c.items() if key in g]
    for k in candidates:
        if k in tried or k == 0 or k.free_symbols & (state | forbidden):
            continue
        if monomial and any(isinstance(node, sp.Add) for node in sp.preorder_traversal(k)):
            continue
        tried.add(k)
        if k.is_zero is False and equal_how(given - k * correct):
            return k
        if len(tried) >= 4:
            break
    return None


def _term(coeff: sp.Expr, key: sp.Expr) -> str:
    return expr_text(coeff * key)


def _is_simple_factor(k: sp.Expr) -> bool:
    """A factor worth naming as such (2, -1/2, 3/4), rather than a rounding difference (584/585)."""
    if not k.is_Rational:
        return not k.is_number  # a factor in the parameters (m2, 1/l) is always worth naming
    return abs(int(k.p)) <= 12 and int(k.q) <= 12


def _show(expr: sp.Expr) -> str:
    """An expression for a message; a fraction also as a decimal: ``73/25 (= 2.92)``."""
    if expr.is_Rational and not expr.is_Integer:
        return f"{expr_text(expr)} (= {float(expr):.6g})"
    return expr_text(expr)


def _coefficient_message(key: sp.Expr, given: sp.Expr, correct: sp.Expr, grouped: bool) -> str:
    g, c = sp.factor(given), sp.factor(correct)
    if g == 0:
        return f"missing term {_term(correct, key)}"
    if c == 0:
        return f"extra term {_term(given, key)}"
    if sp.expand(g + c) == 0:
        return f"wrong sign of the term {_term(correct, key)}"
    ratio = sp.cancel(g / c)
    what = "the terms in " + expr_text(key) if grouped and key != 1 else "the term " + _term(correct, key)
    if grouped and key == 1:
        what = "the terms without coordinates or rates"
    if ratio.is_number and _is_simple_factor(ratio):
        return f"{what}: off by a factor {expr_text(ratio)}"
    if key != 1 and (grouped or ratio.is_number):
        return f"coefficient of {expr_text(key)}: yours is {_show(g)}, expected {_show(c)}"
    return f"{what}: yours is {_show(g * key)}, expected {_show(c * key)}"


def _term_differences(given: sp.Expr, correct: sp.Expr, state: frozenset[sp.Symbol]) -> list[str]:
    """Term-by-term differences, from whichever of the expanded or the trigonometrically reduced forms
    shows fewer of them."""
    grouping = state if (given.free_symbols | correct.free_symbols) & state else None
    best: list[tuple[sp.Expr, sp.Expr, sp.Expr]] | None = None
    for form in (sp.expand, _reduced):
        g, c = _groups(form(given), grouping), _groups(form(correct), grouping)
        diffs = [
            (key, g.get(key, sp.S.Zero), c.get(key, sp.S.Zero))
            for key in sorted(set(g) | set(c), key=sp.default_sort_key)
            if sp.expand(g.get(key, 0) - c.get(key, 0)) != 0
        ]
        if best is None or len(diffs) < len(best):
            best = diffs
    assert best is not None
    return [_coefficient_message(key, g, c, grouping is not None) for key, g, c in best]


def diagnose(given: sp.Expr, correct: sp.Expr, state: frozenset[sp.Symbol] = frozenset()) -> str:
    """What differs between a wrong answer and the correct expression, in words."""
    if correct == 0:
        return "the correct value is 0"
    if given == 0:
        return "the correct value is not 0"
    if equal_how(given + correct):
        return "wrong sign: yours is the negative of the correct expression"
    k = _constant_factor(given, correct, state, frozenset(), monomial=True)
    if k is not None and _is_simple_factor(k):
        return f"off by a factor {expr_text(k)} (yours is {expr_text(k)} times the correct expression)"
    diffs = _term_differences(given, correct, state)
    if not diffs:  # differences that only numbers can see (functions the reductions do not touch)
        return "differs from the correct expression"
    text = "; ".join(diffs[:_MAX_DIFFERENCES])
    if len(diffs) > _MAX_DIFFERENCES:
        text += f"; and {len(diffs) - _MAX_DIFFERENCES} more differences"
    return text


# ---------------------------------------------------------------------------------------------
# Numbers
# ---------------------------------------------------------------------------------------------


def _significant(literal: str) -> tuple[Decimal, int] | None:
    """A number literal's exact value and its count of significant figures (None for zero)."""
    try:
        value = Decimal(literal.strip())
    except InvalidOperation:
        return None
    mantissa = re.split(r"[eE]", literal.strip().lstrip("+-"))[0]
    digits = mantissa.replace(".", "").lstrip("0")
    if "." not in mantissa:
        digits = digits.rstrip("0")  # 1200: trailing zeros of a whole number are not significant
    if not digits:
        return None
    return value, len(digits)


def _round(value: Decimal, figures: int) -> Decimal:
    """``value`` rounded half-up to ``figures`` significant figures."""
    quantum = Decimal(1).scaleb(value.adjusted() - figures + 1)
    return value.quantize(quantum, rounding=ROUND_HALF_UP)


def _number_feedback(given: float, correct: float, tol: Tolerance) -> str:
    limit = max(tol.abs, tol.rel * abs(correct))
    if correct == 0:
        return f"the correct value is 0 (yours is {given:.4g})"
    if given == 0:
        return "the correct value is not 0"
    if abs(given + correct) <= limit:
        return "wrong sign"
    ratio = given / correct
    if ratio > 0:
        power = math.log10(ratio)
        if abs(power) >= 0.999 and abs(power - round(power)) < 1e-3:
            return f"off by a factor 10^{round(power)} (check the units and powers of ten)"
    simple = Fraction(ratio).limit_denominator(12)
    scaled = float(simple) * correct
    if simple not in (0, 1) and abs(given - scaled) <= max(tol.abs, tol.rel * abs(scaled)):
        return f"off by a factor {simple}"
    error = abs(given - correct) / abs(correct)
    allowed = f"rel_tol {tol.rel:g}" if tol.rel * abs(correct) >= tol.abs else f"abs_tol {tol.abs:g}"
    return f"relative error {error:.2%} (allowed: {allowed})"


# ---------------------------------------------------------------------------------------------
# Marking one answers file
# ---------------------------------------------------------------------------------------------


#: Parsed result expressions, per reference (for as long as the reference lives).
_result_cache: weakref.WeakKeyDictionary[Reference, dict[str, sp.Expr]] = weakref.WeakKeyDictionary()


class _UnknownName(Exception):
    """An answer that uses a name the problem does not have: a wrong answer, with this feedback."""


@dataclass
class _Parsed:
    expr: sp.Expr
    literal: str | None = None  # the number as written, for rounding checks
    unit_factor: sp.Expr = sp.S.One  # SI value of one written unit
    dimension: Dimension | None = None  # of a quantity with a unit


class _Marker:
    """Marks the items of one sheet against one reference, collecting answers-file errors."""

    def __init__(self, sheet: AnswerSheet, ref: Reference) -> None:
        self.sheet = sheet
        self.ref = ref
        self.errors: list[SpecError] = []

    # -- reading ------------------------------------------------------------------------------

    def where(self, keypath: KeyPath) -> str:
        return str(self.sheet.location(keypath))

    def error(self, keypath: KeyPath, message: str, hint: str | None = None, *, key: bool = False) -> None:
        loc = self.sheet.source.key_location(keypath) if key else self.sheet.location(keypath)
        self.errors.append(SpecError(loc, message, hint))

    def parse_text(self, text: str, keypath: KeyPath, offset: int = 0) -> sp.Expr | None:
        try:
            expr = parse_expression(text, self.ref.symbols)
        except ExprError as exc:
            if exc.message.startswith("unknown name"):
                raise _UnknownName(exc.message + (f" ({exc.hint})" if exc.hint else "")) from None
            loc = self.sheet.source.expr_location(keypath, offset + exc.offset)
            self.errors.append(SpecError(loc, exc.message, exc.hint))
            return None
        return expr.xreplace(self.ref.values) if self.ref.values else expr

    def read(self, answer: Any, keypath: KeyPath) -> _Parsed | None:
        """An answer scalar as sympy (None after recording an answers-file error)."""
        if isinstance(answer, bool):
            self.error(keypath, "expected an expression or a number, found true/false")
            return None
        if isinstance(answer, int | float):
            try:
                value = number_to_rational(answer)
            except ExprError as exc:
                self.error(keypath, exc.message)
                return None
            literal = self.sheet.raw_number(keypath, answer) or repr(answer)
            return _Parsed(value, literal)
        text = str(answer)
        try:
            quantity = parse_quantity(text)
        except ExprError as exc:
            self.errors.append(SpecError(self.sheet.source.expr_location(keypath, exc.offset), exc.message, exc.hint))
            return None
        if quantity is not None:
            match = _NUMBER_RE.match(text)
            assert match is not None
            factor, _ = parse_unit(quantity.unit)
            return _Parsed(quantity.value, match.group().strip(), factor, quantity.dimension)
        expr = self.parse_text(text, keypath)
        if expr is None:
            return None
        literal = text.strip() if _NUMBER_RE.fullmatch(text) else None
        return _Parsed(expr, literal)

    def result_expr(self, value: Any) -> sp.Expr:
        """A result entry (a JSON number or an expression string) as sympy."""
        if isinstance(value, int | float) and not isinstance(value, bool):
            return number_to_rational(value)
        text = str(value)
        cache = _result_cache.setdefault(self.ref, {})
        if text not in cache:
            cache[text] = parse_expression(text, self.ref.symbols)
        return cache[text]

    # -- items --------------------------------------------------------------------------------

    def mark(self) -> list[ItemResult]:
        out: list[ItemResult] = []
        seen: dict[Path, str] = {}
        for item in self.sheet.items:
            resolved = self.resolve(item)
            if resolved is None:
                continue
            path, result = resolved
            if path in seen:
                self.error(
                    item.keypath,
                    f"'{item.key}' answers {entry_name(path)} again (already answered by '{seen[path]}')",
                    key=True,
                )
                continue
            seen[path] = item.key
            try:
                out.append(self.mark_item(item, path, result))
            except _Stop:
                continue
        return out

    def resolve(self, item: AnswerItem) -> tuple[Path, Any] | None:
        """The results path and value an item's key names (None after recording an error)."""
        node: Any = self.ref.results
        path: list[str | int] = []
        for i, seg in enumerate(item.segments):
            step = self.step(node, tuple(path), seg)
            if isinstance(step, str):
                hint = None
                if i == 0:
                    hint = "this spec's results are: " + ", ".join(self.ref.results)
                self.error(item.keypath, f"cannot read the key '{item.key}': {step}", hint, key=True)
                return None
            for part in step:
                node = node[part]
                path.append(part)
        return tuple(path), node

    def step(self, node: Any, path: Path, seg: Segment) -> tuple[str | int, ...] | str:
        """The path parts one key segment takes from ``node``, or why it cannot."""
        where = entry_name(path) if path else "the results"
        if isinstance(seg, str):
            if isinstance(node, dict):
                if seg in node:
                    return (seg,)
                if not path:
                    return f"this spec has no result '{seg}' (its spec does not ask for it)"
                close = did_you_mean(seg, [str(k) for k in node])
                return f"{where} has no entry '{seg}'" + (f"; did you mean '{close}'?" if close else "")
            if isinstance(node, list) and _per_coordinate(path):
                if seg in self.ref.coordinates:
                    return (self.ref.coordinates.index(seg),)
                return f"'{seg}' is not a coordinate (coordinates: {', '.join(self.ref.coordinates)})"
            return f"{where} has no entry '{seg}'"
        if isinstance(node, dict):
            key = ",".join(str(i) for i in seg)
            if key in node:
                return (key,)
            return f"{where} has no entry [{key}]"
        parts: list[int] = []
        for index in seg:
            if not isinstance(node, list):
                return f"{entry_name((*path, *parts))} is a single value; it has no entry [{index}]"
            if index > len(node):
                return f"{entry_name((*path, *parts))} has {len(node)} entries; there is no entry [{index}]"
            parts.append(index - 1)
            node = node[index - 1]
        return tuple(parts)

    def mark_item(self, item: AnswerItem, path: Path, result: Any) -> ItemResult:
        remarks: list[str] = []
        entries = self.walk(item.value, item.keypath, result, path, Tolerance())
        table = path[0] if path and path[0] in _OTHER_TABLE else None
        if table and any(e.status is Status.WRONG for e in entries):
            other = (_OTHER_TABLE[table], *path[1:])
            other_result = self.lookup(other)
            if other_result is not None:
                # the same answer against the other table: accepted when no entry is wrong there
                again = self.walk(item.value, item.keypath, other_result, other, Tolerance())
                if not any(a.status is Status.WRONG for a in again):
                    entries = [
                        replace(e, how=a.how, status=Status.CORRECT, feedback="", expected=a.expected)
                        if e.status is Status.WRONG
                        else e
                        for e, a in zip(entries, again, strict=True)
                    ]
                    remarks.append(
                        f"these are {_TABLE_WORDS[other[0]]} (the result '{other[0]}'), not "
                        f"{_TABLE_WORDS[table]}; accepted, since both give the same Coriolis vector"
                    )
        for e in entries:
            if e.status is Status.CORRECT and e.feedback and e.feedback not in remarks:
                remarks.append(e.feedback)
        status = Status.CORRECT
        if any(e.status is Status.WRONG for e in entries):
            status = Status.WRONG
        elif any(e.status is Status.MISSING for e in entries):
            status = Status.MISSING
        return ItemResult(entry_name(path), status, tuple(entries), tuple(remarks), str(item.location))

    def lookup(self, path: Path) -> Any:
        node: Any = self.ref.results
        for part in path:
            try:
                node = node[part]
            except (KeyError, IndexError, TypeError):
                return None
        return node

    # -- walking an answer and a result together ---------------------------------------------------

    def walk(self, answer: Any, keypath: KeyPath, result: Any, path: Path, tol: Tolerance) -> list[EntryResult]:
        if is_tolerance_form(answer):
            tol = item_tolerance(answer, keypath, self.sheet.source, self.errors).over(tol)
            answer, keypath = answer["value"], (*keypath, "value")
        if isinstance(answer, bool) and not isinstance(result, bool):
            self.error(keypath, "expected an expression or a number, found true/false")
            return []
        if answer is None or (isinstance(answer, str) and not answer.strip()):
            return [EntryResult(entry_name(path), Status.MISSING, feedback="no answer", location=self.where(keypath))]
        if isinstance(result, dict):
            return self.walk_table(answer, keypath, result, path, tol)
        if isinstance(result, list):
            return self.walk_list(answer, keypath, result, path, tol)
        if isinstance(answer, list | dict):
            kind = "a list" if isinstance(answer, list) else "a mapping"
            return [self.wrong(path, keypath, answer, result, f"expected a single value, found {kind}")]
        return [self.scalar(answer, keypath, result, path, tol)]

    def walk_table(
        self, answer: Any, keypath: KeyPath, result: dict[str, Any], path: Path, tol: Tolerance
    ) -> list[EntryResult]:
        if not isinstance(answer, dict):
            keys = ", ".join(list(result)[:6]) + (", ..." if len(result) > 6 else "")
            self.error(keypath, f"{entry_name(path)} is a table: expected a mapping of its entries ({keys})")
            raise _Stop
        out: list[EntryResult] = []
        for key, value in answer.items():
            name = self.table_key(str(key), result)
            if name is None:
                close = did_you_mean(str(key), [str(k) for k in result])
                self.error(
                    (*keypath, key),
                    f"{entry_name(path)} has no entry '{key}'; its entries are: " + ", ".join(map(str, result)),
                    f"did you mean '{close}'?" if close else None,
                    key=True,
                )
                continue
            out += self.walk(value, (*keypath, key), result[name], (*path, name), tol)
        return out

    @staticmethod
    def table_key(key: str, result: dict[str, Any]) -> str | None:
        """The entry of ``result`` a table key names: as written, or a Christoffel index in any of the
        forms ``1,1,2``, ``112``, ``h112``, ``c112``, ``[1,1,2]``."""
        if key in result:
            return key
        match = _CHRISTOFFEL_KEY_RE.fullmatch(key.strip())
        if match:
            indices = [g for g in match.groups() if g is not None]
            name = ",".join(str(int(i)) for i in indices)
            if name in result:
                return name
        return None

    def walk_list(
        self, answer: Any, keypath: KeyPath, result: list[Any], path: Path, tol: Tolerance
    ) -> list[EntryResult]:
        n = len(result)
        if isinstance(answer, dict):
            pairs: list[tuple[int, Any, KeyPath]] = []
            for key, value in answer.items():
                index = self.list_key(str(key), path, n)
                if index is None:
                    choices = [str(i) for i in range(1, n + 1)]
                    if _per_coordinate(path):
                        choices = list(self.ref.coordinates)
                    self.error(
                        (*keypath, key),
                        f"{entry_name(path)} has no entry '{key}'; expected one of: {', '.join(choices)}",
                        key=True,
                    )
                    continue
                pairs.append((index, value, (*keypath, key)))
            out: list[EntryResult] = []
            for index, value, kp in sorted(pairs, key=lambda p: p[0]):
                out += self.walk(value, kp, result[index], (*path, index), tol)
            return out
        if not isinstance(answer, list):
            rows = "a matrix" if result and isinstance(result[0], list) else f"a list of {n} entries"
            return [self.wrong(path, keypath, answer, result, f"expected {rows}, found a single value")]
        out = self.walk_items(answer, keypath, result, path, tol)
        is_axis = _field(path) == "principal_axes" and bool(result) and not isinstance(result[0], list)
        if is_axis and len(answer) == n and any(e.status is Status.WRONG for e in out):
            # a principal axis is a direction: accepted pointing the other way
            flipped = [-v if isinstance(v, int | float) and not isinstance(v, bool) else v for v in result]
            again = self.walk_items(answer, keypath, flipped, path, tol)
            if all(e.status is Status.CORRECT for e in again):
                note = f"{entry_name(path)} points the other way; accepted, an axis has no direction"
                return [replace(e, feedback=note) for e in again]
        return out

    def walk_items(
        self, answer: list[Any], keypath: KeyPath, result: list[Any], path: Path, tol: Tolerance
    ) -> list[EntryResult]:
        """A list answer against a list result, entry by entry; short lists miss entries, long ones
        have extra (wrong) ones."""
        n = len(result)
        out: list[EntryResult] = []
        for i, value in enumerate(answer[:n]):
            out += self.walk(value, (*keypath, i), result[i], (*path, i), tol)
        for i in range(len(answer), n):
            out.append(
                EntryResult(entry_name((*path, i)), Status.MISSING, feedback="no answer", location=self.where(keypath))
            )
        for i in range(n, len(answer)):
            out.append(
                EntryResult(
                    entry_name((*path, i)),
                    Status.WRONG,
                    feedback=f"extra entry: {entry_name(path)} has only {n} entries",
                    location=self.where((*keypath, i)),
                    given=_text(answer[i]),
                )
            )
        return out

    def list_key(self, key: str, path: Path, n: int) -> int | None:
        if key.isdigit() and 1 <= int(key) <= n:
            return int(key) - 1
        if _per_coordinate(path) and key in self.ref.coordinates:
            return self.ref.coordinates.index(key)
        return None

    # -- scalars --------------------------------------------------------------------------------

    def wrong(self, path: Path, keypath: KeyPath, answer: Any, result: Any, feedback: str) -> EntryResult:
        return EntryResult(
            entry_name(path),
            Status.WRONG,
            feedback=feedback,
            location=self.where(keypath),
            given=_text(answer),
            expected=_text(result),
        )

    def right(self, path: Path, keypath: KeyPath, answer: Any, result: Any, how: str, remark: str = "") -> EntryResult:
        return EntryResult(
            entry_name(path),
            Status.CORRECT,
            how=how,
            feedback=remark,
            location=self.where(keypath),
            given=_text(answer),
            expected=_text(result),
        )

    def scalar(self, answer: Any, keypath: KeyPath, result: Any, path: Path, tol: Tolerance) -> EntryResult:
        field_name = _field(path)
        if field_name in _TEXT_FIELDS:
            if str(answer).strip() == str(result):
                return self.right(path, keypath, answer, result, "exact: the same text")
            return self.wrong(path, keypath, answer, result, f"expected '{result}'")
        if isinstance(result, bool):
            if answer is result:
                return self.right(path, keypath, answer, result, "exact: the same truth value")
            return self.wrong(path, keypath, answer, result, f"expected {str(result).lower()}")
        if field_name == "equations_of_motion":
            return self.equation(answer, keypath, result, path)
        try:
            parsed = self.read(answer, keypath)
        except _UnknownName as exc:
            return self.wrong(path, keypath, answer, result, str(exc))
        if parsed is None:
            return self.wrong(path, keypath, answer, result, "cannot read the answer")
        correct = self.result_expr(result)
        expected_dim = _DIMENSION_OF.get(field_name or "")
        if parsed.dimension is not None and expected_dim is not None and parsed.dimension != expected_dim:
            return self.wrong(
                path, keypath, answer, result, f"wrong units: yours are {parsed.dimension}, expected {expected_dim}"
            )
        given = parsed.expr
        if not given.free_symbols and not correct.free_symbols:
            return self.number(parsed, answer, keypath, result, path, tol.over(self.sheet.tolerance))
        if tol.is_set and not tol.rounded:
            return self.close_at_states(given, correct, answer, keypath, result, path, tol)
        how = equal_how(given - correct)
        if how:
            return self.right(path, keypath, answer, result, how)
        return self.wrong(path, keypath, answer, result, diagnose(given, correct, self.ref.state))

    def number(
        self, parsed: _Parsed, answer: Any, keypath: KeyPath, result: Any, path: Path, tol: Tolerance
    ) -> EntryResult:
        given, correct = float(sp.N(parsed.expr, 20)), float(sp.N(self.result_expr(result), 20))
        if tol.rounded and parsed.literal is not None:
            shown = _significant(parsed.literal)
            if shown is None:  # a zero: right only if the result is (to abs_tol)
                if abs(correct) <= tol.abs:
                    return self.right(path, keypath, answer, result, f"within abs_tol {tol.abs:g}")
                return self.wrong(path, keypath, answer, result, "the correct value is not 0")
            value, figures = shown
            in_unit = Decimal(repr(float(sp.N(self.result_expr(result) / parsed.unit_factor, 20))))
            if in_unit == 0:
                return self.wrong(path, keypath, answer, result, f"the correct value is 0 (yours is {given:.4g})")
            target = _round(in_unit, figures)
            if value == target:
                return self.right(path, keypath, answer, result, f"correctly rounded to {figures} significant figures")
            if abs(value - in_unit) <= Decimal(1).scaleb(in_unit.adjusted() - figures + 1):
                shown_target = format(target, f".{figures - 1}e") if "e" in parsed.literal.lower() else str(target)
                return self.wrong(
                    path,
                    keypath,
                    answer,
                    result,
                    f"not correctly rounded: to {figures} significant figures it is {shown_target}",
                )
            return self.wrong(path, keypath, answer, result, _number_feedback(given, correct, tol))
        if abs(given - correct) <= max(tol.abs, tol.rel * abs(correct)):
            limit = f"rel_tol {tol.rel:g}" if tol.rel * abs(correct) >= tol.abs else f"abs_tol {tol.abs:g}"
            return self.right(path, keypath, answer, result, f"within {limit}")
        return self.wrong(path, keypath, answer, result, _number_feedback(given, correct, tol))

    def close_at_states(
        self, given: sp.Expr, correct: sp.Expr, answer: Any, keypath: KeyPath, result: Any, path: Path, tol: Tolerance
    ) -> EntryResult:
        """An expression with its own tolerance: within it at every one of TRIALS random states."""
        for state in random_states(given.free_symbols | correct.free_symbols):
            g, c = _value(given, state), _value(correct, state)
            if g is None or c is None:
                continue
            if abs(g - c) > max(tol.abs, tol.rel * abs(c)):
                return self.wrong(
                    path,
                    keypath,
                    answer,
                    result,
                    f"outside the tolerance at a random state; {diagnose(given, correct, self.ref.state)}",
                )
        return self.right(
            path,
            keypath,
            answer,
            result,
            f"numeric: within rel_tol {tol.rel:g} / abs_tol {tol.abs:g} at {TRIALS} random states (seed {SEED})",
        )

    # -- equations of motion ------------------------------------------------------------------------

    def equation(self, answer: Any, keypath: KeyPath, result: Any, path: Path) -> EntryResult:
        """An equation of motion: ``lhs = rhs`` or an expression equal to 0, up to moving terms across the
        ``=`` and a non-zero constant factor."""
        try:
            given = self.read_equation(answer, keypath)
        except _UnknownName as exc:
            return self.wrong(path, keypath, answer, result, str(exc))
        if given is None:
            return self.wrong(path, keypath, answer, result, "cannot read the answer")
        correct = self.result_expr(result)
        how = equal_how(given - correct)
        if how:
            return self.right(path, keypath, answer, result, how)
        k = _constant_factor(given, correct, self.ref.state, self.ref.forces)
        if k is not None:
            if k == -1:
                remark = f"{entry_name(path)}: the terms are on the other side of '='"
            else:
                remark = f"{entry_name(path)}: scaled by the constant factor {expr_text(k)}"
            return self.right(path, keypath, answer, result, "exact: equal up to a constant factor", remark)
        return self.wrong(path, keypath, answer, result, diagnose(self.scaled(given, correct), correct, self.ref.state))

    def scaled(self, given: sp.Expr, correct: sp.Expr) -> sp.Expr:
        """``given`` divided by the constant factor under which most of its terms agree with ``correct``
        (so that one wrong term in a scaled equation is reported as one wrong term)."""
        state = self.ref.state
        g, c = _groups(_reduced(given), state), _groups(_reduced(correct), state)
        best, agreeing = sp.S.One, -1
        for key in c:
            if key not in g:
                continue
            k = sp.cancel(g[key] / c[key])
            if k == 0 or k.free_symbols & (state | self.ref.forces) or k.is_zero is not False:
                continue
            count = sum(1 for kk in c if kk in g and sp.expand(g[kk] - k * c[kk]) == 0)
            if count > agreeing or (count == agreeing and k == 1):
                best, agreeing = k, count
        return given if best == 1 else sp.expand(given / best)

    def read_equation(self, answer: Any, keypath: KeyPath) -> sp.Expr | None:
        if isinstance(answer, str) and "=" in answer:
            text = answer.replace("==", "=")
            if text.count("=") != 1:
                self.errors.append(
                    SpecError(
                        self.sheet.source.expr_location(keypath, answer.rfind("=")),
                        "an equation has one '=': write 'lhs = rhs'",
                    )
                )
                return None
            lhs_text, rhs_text = text.split("=")
            offset = answer.index("=") + (2 if "==" in answer else 1)
            lhs = self.parse_text(lhs_text, keypath)
            rhs = self.parse_text(rhs_text, keypath, offset)
            if lhs is None or rhs is None:
                return None
            return lhs - rhs
        parsed = self.read(answer, keypath)
        return None if parsed is None else parsed.expr


class _Stop(Exception):
    """An item whose shape is wrong for its result: the error is recorded, the item is skipped."""


def _text(value: Any) -> str | None:
    """An answer or a result as text for the reports (None for no answer)."""
    return None if value is None else str(value)


def check_sheet(sheet: AnswerSheet, ref: Reference) -> list[ItemResult]:
    """Mark every item of an answers file; raise SpecErrors for problems with the file itself
    (an expression that cannot be read, a key the spec's results do not have, a bad tolerance)."""
    marker = _Marker(sheet, ref)
    items = marker.mark()
    if sheet.errors or marker.errors:
        raise SpecErrors([*sheet.errors, *marker.errors])
    return items
