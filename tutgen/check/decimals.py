"""Decimals copied from a worked solution: right when they are the result as the solution prints it.

A variant's solution prints ``0.2109 θ̇²`` for ``27/128 θ̇²`` (decimals to the spec's
``significant_figures``, 4 by default; tutgen.render.printer). Compared exactly, the copied answer is
wrong. So an answer whose decimals differ from the result is compared once more, allowing each
decimal literal ``d`` to stand for any number it is the rounding of: to ``F`` significant figures,
the figures the solution prints (or to the figures written, when the student wrote more), so that
``d`` stands for ``d ± δ`` with ``δ`` half a unit of its last figure. With ``g(d₁, …, dₙ)`` the answer
as a function of its decimals, it is accepted when at every usable random state

    |g − r| ≤ 1.01 · Σᵢ |∂g/∂dᵢ| · δᵢ

(the first-order effect of rounding each decimal, with 1 % for the second order), evaluated in high
precision as every comparison is (:func:`tutgen.check.numeric.evaluate`), states that cannot be
trusted discarded. A decimal then cannot hide anything: its allowance is proportional to its own
size and to half a unit of its printed last figure. Integers (``2``, ``1235``) are exact, and so is a
decimal that is 0. Off with the marking's ``significant_figures: 0``.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from decimal import Decimal, InvalidOperation

import mpmath
import sympy as sp

from tutgen.check.numeric import CHECK_DPS, NEEDED_DIGITS, TRIALS, evaluate, random_states
from tutgen.spec.expr import number_to_rational

__all__ = ["MAX_DECIMALS", "decimal_literals", "half_unit", "within_rounding"]

#: Answers with more decimal literals than this are compared exactly only.
MAX_DECIMALS = 24
#: A literal with a decimal point or an exponent, not part of a name (``theta1e``) or another number.
_DECIMAL = re.compile(
    r"(?<![A-Za-z0-9_.])(?:(?:[0-9]+\.[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?|[0-9]+[eE][-+]?[0-9]+)(?![A-Za-z0-9_.])"
)
_SECOND_ORDER = mpmath.mpf("1.01")


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
    mantissa = re.split(r"[eE]", literal)[0].replace(".", "").lstrip("0")
    written = len(mantissa)
    return Decimal(5).scaleb(value.adjusted() - max(written, figures))


def within_rounding(
    text: str,
    parse: Callable[[str, Mapping[str, sp.Symbol]], sp.Expr],
    correct: sp.Expr,
    figures: int,
    factors: tuple[int, ...] = (1,),
) -> int | None:
    """Whether the answer ``text`` (ASCII grammar) is ``k`` times ``correct`` for one ``k`` of
    ``factors`` once each of its decimals is read as a rounding to ``figures`` significant figures
    (the module's rule). ``parse(text, extra)`` reads the text with ``extra`` names. Returns that
    ``k``, or None (not equal, nothing to allow for, or fewer than half the states usable)."""
    found = decimal_literals(text)
    if not found or len(found) > MAX_DECIMALS or figures <= 0:
        return None
    names: dict[str, sp.Symbol] = {}
    values: dict[sp.Symbol, sp.Expr] = {}
    halves: dict[sp.Symbol, sp.Expr] = {}
    pieces: list[str] = []
    last = 0
    for i, match in enumerate(found):
        half = half_unit(match.group(), figures)
        pieces.append(text[last : match.start()])
        last = match.end()
        if half is None:
            pieces.append(match.group())
            continue
        name = f"zz_decimal_{i}_"
        symbol = sp.Dummy(name)
        names[name] = symbol
        values[symbol] = number_to_rational(match.group())
        halves[symbol] = number_to_rational(str(half))
        pieces.append(name)
    pieces.append(text[last:])
    if not names:
        return None
    with_symbols = parse("".join(pieces), names)
    given = with_symbols.xreplace(values)
    slopes = [sp.diff(with_symbols, s).xreplace(values) * halves[s] for s in halves]
    for k in factors:
        if _agree(given, k * correct, slopes):
            return k
    return None


def _agree(given: sp.Expr, correct: sp.Expr, slopes: list[sp.Expr]) -> bool:
    used = 0
    symbols = given.free_symbols | correct.free_symbols
    for s in slopes:
        symbols |= s.free_symbols
    for state in random_states(symbols):
        g, c = evaluate(given, state), evaluate(correct, state)
        parts = [evaluate(s, state) for s in slopes]
        if g is None or c is None or any(p is None for p in parts):
            continue
        if min(g.digits, c.digits) < NEEDED_DIGITS:
            continue
        used += 1
        with mpmath.workdps(CHECK_DPS):
            allowed = _SECOND_ORDER * mpmath.fsum(abs(p.value) for p in parts if p is not None)
            allowed += mpmath.mpf(10) ** -NEEDED_DIGITS * max(abs(g.value), abs(c.value))
            if abs(g.value - c.value) > allowed:
                return False
    return used * 2 > TRIALS
