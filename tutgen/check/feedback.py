"""What differs between a wrong answer and the result, in words a student can use.

A sign, a constant factor, a missing or extra term, the coefficient of a term in the coordinates and
rates (:func:`diagnose`); for numbers, a relative error, a power of ten, a rounding
(:func:`number_feedback`). Only called on answers the decision procedure
(:mod:`tutgen.check.equivalence`) found different, and only on answers small enough to expand.
"""

from __future__ import annotations

import math
import re
from decimal import ROUND_HALF_UP, Decimal, InvalidOperation
from fractions import Fraction

import sympy as sp

from tutgen.check.answers import Tolerance
from tutgen.check.equivalence import constant_factor, decide, groups, reduced, too_large
from tutgen.render.jsonout import expr_text

__all__ = ["diagnose", "is_simple_factor", "number_feedback", "round_half_up", "significant"]

#: How many differences one wrong entry lists before "and N more".
_MAX_DIFFERENCES = 3


def _term(coeff: sp.Expr, key: sp.Expr) -> str:
    return expr_text(coeff * key)


def is_simple_factor(k: sp.Expr) -> bool:
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
    if ratio.is_number and is_simple_factor(ratio):
        return f"{what}: off by a factor {expr_text(ratio)}"
    if key != 1 and (grouped or ratio.is_number):
        return f"coefficient of {expr_text(key)}: yours is {_show(g)}, expected {_show(c)}"
    return f"{what}: yours is {_show(g * key)}, expected {_show(c * key)}"


def _term_differences(given: sp.Expr, correct: sp.Expr, state: frozenset[sp.Symbol]) -> list[str]:
    """Term-by-term differences, from whichever of the expanded or the trigonometrically reduced forms
    shows fewer of them."""
    grouping = state if (given.free_symbols | correct.free_symbols) & state else None
    best: list[tuple[sp.Expr, sp.Expr, sp.Expr]] | None = None
    for form in (sp.expand, reduced):
        g, c = groups(form(given), grouping), groups(form(correct), grouping)
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
    large = too_large(given, correct)
    if large:
        return f"differs from the correct expression ({large})"
    if decide(-given, correct).equal:
        return "wrong sign: yours is the negative of the correct expression"
    k = constant_factor(given, correct, state, frozenset(), monomial=True)
    if k is not None and is_simple_factor(k):
        return f"off by a factor {expr_text(k)} (yours is {expr_text(k)} times the correct expression)"
    diffs = _term_differences(given, correct, state)
    if not diffs:  # differences that only numbers can see (functions the reductions do not touch)
        return "differs from the correct expression"
    text = "; ".join(diffs[:_MAX_DIFFERENCES])
    if len(diffs) > _MAX_DIFFERENCES:
        text += f"; and {len(diffs) - _MAX_DIFFERENCES} more differences"
    return text


def significant(literal: str) -> tuple[Decimal, int] | None:
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


def round_half_up(value: Decimal, figures: int) -> Decimal:
    """``value`` rounded half-up to ``figures`` significant figures."""
    quantum = Decimal(1).scaleb(value.adjusted() - figures + 1)
    return value.quantize(quantum, rounding=ROUND_HALF_UP)


def number_feedback(given: float, correct: float, tol: Tolerance) -> str:
    """What differs between a wrong number and the correct one (both finite or not)."""
    if not (math.isfinite(given) and math.isfinite(correct)):
        return f"far from the correct value {correct:.6g} (yours is {given:.4g})"
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
