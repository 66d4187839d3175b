"""Signs of numbers read off their values, not asked of sympy's assumptions (issue 17).

The first ``is_*`` query on a number that was just made (a variant's coefficients, a product's new
coefficient) copies its class's table of assumptions and deduces from it; the printer and the
operation count ask the sign of every coefficient they meet. A Rational's sign is its numerator's, and
a ``Float`` is always finite (sympy makes ``oo`` and ``nan`` of infinite and undefined floats), so its
sign is its value's. tests/render/test_signs.py compares these with sympy's answers.
"""

from __future__ import annotations

import sympy as sp
from mpmath.libmp import fzero, mpf_lt


def negative_number(a: sp.Basic) -> bool:
    """``a.is_Number and a.is_extended_negative``."""
    if isinstance(a, sp.Rational):
        return a.p < 0
    if isinstance(a, sp.Float):
        return bool(mpf_lt(a._mpf_, fzero))
    return bool(a.is_Number and a.is_extended_negative)


def coefficient_negative(a: sp.Basic) -> bool:
    """``sympy.core.function._coeff_isneg(a)``: a negative number, or a product whose leading factor is one."""
    if a.is_MatMul:
        a = a.args[0]
    if a.is_Mul:
        a = a.args[0]
    return negative_number(a)


def commutative_factors(expr: sp.Basic) -> list[sp.Basic]:
    """``expr.args_cnc()[0]`` of a commutative ``expr`` (a negative coefficient other than -1 split into
    -1 and its magnitude, as sympy splits it)."""
    c = list(expr.args) if expr.is_Mul else [expr]
    first = c[0]
    if first is not sp.S.NegativeOne and negative_number(first):
        c[:1] = [sp.S.NegativeOne, -first]
    return c
