"""Decimals copied from a worked solution: right when they are the result as the solution prints it.

A variant's solution prints ``0.2109 θ̇²`` for ``27/128 θ̇²`` (decimals to the spec's
``significant_figures``, 4 by default; tutgen.render.printer). Compared exactly, the copied answer is
wrong. So an answer that holds a decimal literal and differs from the result is compared once more,
coefficient by coefficient: both sides in trigonometric normal form, grouped by their monomials (in the
coordinates, rates and parameters) with numeric coefficients (:func:`tutgen.check.equivalence.groups`).
The answer is accepted when the monomials are the same and each coefficient ``a`` of the answer is
the result's ``r`` rounded: ``|a − r| ≤ δ``, with ``δ`` half a unit of ``a``'s ``F``-th significant
figure (``F`` the figures the solution prints, or more when ``a`` has more: ``9.5996e-3`` must be
right to 5). A decimal therefore hides nothing: a term the result does not have is a wrong answer,
however small, and no coefficient is allowed more than its printed rounding. A plain number is one
coefficient (:func:`half_unit`). Off with the marking's ``significant_figures: 0``.
"""

from __future__ import annotations

import re
from decimal import Decimal, InvalidOperation

import sympy as sp

from tutgen.check.equivalence import groups, reduced

__all__ = ["decimal_literals", "half_unit", "within_rounding"]

#: A literal with a decimal point or an exponent, not part of a name (``theta1e``) or another number.
_DECIMAL = re.compile(
    r"(?<![A-Za-z0-9_.])(?:(?:[0-9]+\.[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?|[0-9]+[eE][-+]?[0-9]+)(?![A-Za-z0-9_.])"
)


def decimal_literals(text: str) -> list[re.Match[str]]:
    """The decimal literals of an answer in the ASCII grammar, in order."""
    return list(_DECIMAL.finditer(text))


def half_unit(literal: str, figures: int) -> Decimal | None:
    """Half a unit of the last significant figure that ``literal`` stands for: of the ``figures``-th,
    or of the last written when more are written; None for a zero (exact)."""
    try:
        value = Decimal(literal)
    except InvalidOperation:
        return None
    if value == 0:
        return None
    mantissa = re.split(r"[eE]", literal)[0].lstrip("+-").replace(".", "").lstrip("0")
    written = len(mantissa)
    return Decimal(5).scaleb(value.adjusted() - max(written, figures))


def _figures_of(value: sp.Rational) -> int | None:
    """How many significant figures a terminating decimal has (``2109/10000``: 4), None otherwise."""
    q, twos, fives = int(value.q), 0, 0
    while q % 2 == 0:
        q, twos = q // 2, twos + 1
    while q % 5 == 0:
        q, fives = q // 5, fives + 1
    if q != 1:
        return None
    digits = str(abs(int(value.p)) * 10 ** max(twos, fives) // int(value.q)).strip("0")
    return len(digits) if len(digits) <= 15 else None


def _is_rounding(a: sp.Expr, r: sp.Expr, figures: int) -> bool:
    """Whether the number ``a`` is ``r`` rounded to its ``figures`` (or more) significant figures."""
    if a == r:
        return True
    if not (a.is_Rational and r.is_number) or a == 0 or r == 0:
        return False
    written = _figures_of(sp.Rational(a))
    places = max(figures, written or figures)
    size = abs(sp.Rational(a))
    exponent = sp.floor(sp.log(size, 10)) if size else 0
    half = sp.Rational(1, 2) * sp.Integer(10) ** (int(exponent) - places + 1)
    return bool(abs(sp.N(a - r, 30)) <= half)


def within_rounding(
    given: sp.Expr, correct: sp.Expr, figures: int, state: frozenset[sp.Symbol], factors: tuple[int, ...] = (1,)
) -> int | None:
    """The ``k`` of ``factors`` for which ``given`` is ``k`` times ``correct`` with each coefficient
    rounded to ``figures`` significant figures (the module's rule), or None. The caller checks that
    the answer holds a decimal and is small enough to expand (:func:`tutgen.check.equivalence.too_large`)."""
    if figures <= 0:
        return None
    mine = groups(reduced(given), None)
    for k in factors:
        theirs = groups(reduced(k * correct), None)
        if set(mine) != set(theirs):
            continue
        if all(_is_rounding(mine[key], theirs[key], figures) for key in theirs):
            return k
    return None
