"""Numeric evaluation of answers in high precision: values that can be trusted, or none.

When symbolic simplification cannot decide whether two expressions are equal, they are compared at
random states. A float comparison there can be fooled: ``1/(sin(x)**2 + cos(x)**2 - 1)`` is a pole
everywhere yet rounds to a finite number, and ``10**30*(cosh(x)**2 - sinh(x)**2 - 1)`` rounds to a
number of size 1 that hides any error. So each side is evaluated with ``mpmath`` twice, at
:data:`WORK_DPS` and at :data:`CHECK_DPS` decimal digits, over the sympy tree (never by turning text
into code). Where the two agree to ``a`` digits, the lower precision lost ``WORK_DPS - a`` digits to
cancellation, and the higher one keeps about ``CHECK_DPS - WORK_DPS + a`` digits (:func:`evaluate`);
when they agree in fewer than 2 digits, the loss cannot be told and no digit is trusted.
A state counts only when both sides are finite, real and keep at least :data:`NEEDED_DIGITS` digits;
the other states are discarded, and when fewer than half of the :data:`TRIALS` states count, the
answer "cannot be evaluated" (:func:`compare_at_states`).

Examples
--------
>>> import sympy as sp
>>> x = sp.Symbol("x")
>>> compare_at_states(sp.tan(x), sp.sin(x) / sp.cos(x)).equal
True
>>> compare_at_states(1 / (sp.sin(x)**2 + sp.cos(x)**2 - 1), x).equal is None
True
>>> compare_at_states(x + 10**60 * (sp.cosh(x)**2 - sp.sinh(x)**2 - 1), x).equal is None
True
>>> compare_at_states(2 + 10**20 * (sp.cosh(x)**2 - sp.sinh(x)**2 - 1) + x, x).equal
False
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass

import mpmath
import sympy as sp

from tutgen.engine.tidy import random_states as tidy_random_states

__all__ = [
    "CHECK_DPS",
    "EQUAL_DIGITS",
    "NEEDED_DIGITS",
    "SEED",
    "TRIALS",
    "WORK_DPS",
    "Comparison",
    "compare_at_states",
    "evaluate",
    "random_states",
    "ratio_at_states",
    "value_of_number",
]

#: Random states tried, and the seed that picks them (each symbol a random k/1000 in [0.3, 2.7]).
TRIALS = 12
SEED = 4245
#: The two precisions (decimal digits) each side is evaluated at.
WORK_DPS = 30
CHECK_DPS = 60
#: Digits a value must keep, after cancellation, for its state to count.
NEEDED_DIGITS = 20
#: Relative agreement (in digits) that makes two values at a state equal.
EQUAL_DIGITS = 15
#: A value of magnitude beyond 2**MAX_MAGNITUDE_BITS counts as not finite (``exp(exp(1000))``): mpmath
#: would represent it, but its exponent is a big integer that would make the next operation crawl.
MAX_MAGNITUDE_BITS = 10**6


def random_states(symbols: Iterable[sp.Symbol]) -> Iterator[dict[sp.Symbol, sp.Expr]]:
    """TRIALS states, the same for the same symbols: each symbol a random k/1000 in [0.3, 2.7]."""
    return tidy_random_states(symbols, TRIALS, SEED)


class _NotFinite(Exception):
    """A pole, a value that is not real, or a magnitude beyond the limit."""


_FUNCTIONS = {
    sp.sin: mpmath.sin,
    sp.cos: mpmath.cos,
    sp.tan: mpmath.tan,
    sp.cot: mpmath.cot,
    sp.sec: mpmath.sec,
    sp.csc: mpmath.csc,
    sp.asin: mpmath.asin,
    sp.acos: mpmath.acos,
    sp.atan: mpmath.atan,
    sp.sinh: mpmath.sinh,
    sp.cosh: mpmath.cosh,
    sp.tanh: mpmath.tanh,
    sp.exp: mpmath.exp,
    sp.log: mpmath.log,
    sp.Abs: abs,
    sp.sign: lambda v: mpmath.sign(v),
}


def _check(value: mpmath.mpf | mpmath.mpc) -> mpmath.mpf | mpmath.mpc:
    if isinstance(value, mpmath.mpc):
        if not (mpmath.isfinite(value.real) and mpmath.isfinite(value.imag)):
            raise _NotFinite
    elif not mpmath.isfinite(value):
        raise _NotFinite
    if value and mpmath.mag(value) > MAX_MAGNITUDE_BITS:
        raise _NotFinite
    return value


def _eval(expr: sp.Basic, state: Mapping[sp.Symbol, mpmath.mpf]) -> mpmath.mpf | mpmath.mpc:
    """``expr`` at ``state`` in the current mpmath precision (may be complex)."""
    if expr.is_Symbol:
        try:
            return state[expr]  # type: ignore[index]
        except KeyError:
            raise _NotFinite from None
    if expr.is_Integer:
        return mpmath.mpf(int(expr))  # type: ignore[arg-type]
    if expr.is_Rational:
        return _check(mpmath.mpf(int(expr.p)) / int(expr.q))  # type: ignore[attr-defined]
    if expr.is_Float:
        return mpmath.mpf(expr._mpf_)  # type: ignore[attr-defined]
    if expr is sp.pi:
        return +mpmath.pi
    if expr is sp.E:
        return +mpmath.e
    if expr in (sp.zoo, sp.oo, -sp.oo, sp.nan):
        raise _NotFinite
    args = expr.args
    if expr.is_Add:
        total = mpmath.mpf(0)
        for a in args:
            total += _eval(a, state)
        return _check(total)
    if expr.is_Mul:
        product = mpmath.mpf(1)
        for a in args:
            product *= _eval(a, state)
            _check(product)
        return product
    if expr.is_Pow:
        base, exponent = args
        b = _eval(base, state)
        if exponent.is_Integer:
            n = int(exponent)  # type: ignore[arg-type]
            if n < 0 and b == 0:
                raise _NotFinite
            return _check(b**n)
        e = _eval(exponent, state)
        if b == 0:
            if e.real > 0 if isinstance(e, mpmath.mpc) else e > 0:
                return mpmath.mpf(0)
            raise _NotFinite
        return _check(mpmath.power(b, e))
    if isinstance(expr, sp.atan2):
        y, x = (_eval(a, state) for a in args)
        if isinstance(y, mpmath.mpc) or isinstance(x, mpmath.mpc) or (x == 0 and y == 0):
            raise _NotFinite
        return mpmath.atan2(y, x)
    func = _FUNCTIONS.get(expr.func)  # type: ignore[call-overload]
    if func is not None and len(args) == 1:
        v = _eval(args[0], state)
        if expr.func in (sp.log,) and v == 0:
            raise _NotFinite
        try:
            return _check(func(v))
        except (ZeroDivisionError, ValueError):
            raise _NotFinite from None
    raise _NotFinite  # a function the grammar does not have: no value, never a guess


def _at(expr: sp.Expr, state: Mapping[sp.Symbol, sp.Expr], dps: int) -> mpmath.mpf | None:
    """``expr`` at ``state`` with ``dps`` digits: a real mpf, or None (not finite, or not real)."""
    with mpmath.workdps(dps):
        values = {s: mpmath.mpf(int(v.p)) / int(v.q) for s, v in state.items()}  # type: ignore[attr-defined]
        try:
            value = _eval(expr, values)
        except (_NotFinite, ZeroDivisionError, ValueError, OverflowError):
            return None
        if isinstance(value, mpmath.mpc):
            # real to the working precision, or not real at all (sqrt of a negative number)
            if abs(value.imag) > abs(value) * mpmath.mpf(10) ** (-(dps - 5)):
                return None
            value = value.real
        return +value


@dataclass(frozen=True)
class Value:
    """A value at a state and how many of its digits are trustworthy (``inf`` for an exact 0)."""

    value: mpmath.mpf
    digits: float


def evaluate(expr: sp.Expr, state: Mapping[sp.Symbol, sp.Expr]) -> Value | None:
    """``expr`` at ``state``: its value at CHECK_DPS digits and the digits that survive cancellation,
    or None where it is not finite or not real."""
    low = _at(expr, state, WORK_DPS)
    high = _at(expr, state, CHECK_DPS)
    if low is None or high is None:
        return None
    with mpmath.workdps(CHECK_DPS):
        if high == 0:
            return Value(high, math.inf if low == 0 else float(CHECK_DPS - WORK_DPS))
        error = abs(low - high) / abs(high)
        agree = WORK_DPS if error == 0 else min(float(WORK_DPS), max(0.0, -float(mpmath.log10(error))))
    if agree < 2:
        # the low precision kept no digit: the loss is at least WORK_DPS digits, and how much of the
        # high precision survived cannot be told, so nothing is trusted
        return Value(high, 0.0)
    return Value(high, CHECK_DPS - WORK_DPS + agree)


@dataclass(frozen=True)
class Comparison:
    """How two expressions compare at the random states.

    ``equal`` is True (equal at every usable state), False (different at a usable state) or None
    (cannot be evaluated: fewer than half of the states were usable). ``states`` is the number of
    usable states, ``reason`` says why the others were discarded.
    """

    equal: bool | None
    states: int
    reason: str = ""


def _usable(value: Value | None) -> bool:
    return value is not None and value.digits >= NEEDED_DIGITS


def compare_at_states(
    given: sp.Expr, correct: sp.Expr, *, rel_tol: float | None = None, abs_tol: float = 0.0
) -> Comparison:
    """Compare ``given`` with ``correct`` at the TRIALS random states of their symbols.

    Equal at a state means ``|g - c| <= max(abs_tol, rel * max(|g|, |c|))`` with ``rel`` 10**-EQUAL_DIGITS
    (or ``rel_tol``, the instructor's tolerance). A state where either side is not finite, not real or
    keeps fewer than NEEDED_DIGITS digits is discarded.
    """
    rel = 10.0**-EQUAL_DIGITS if rel_tol is None else rel_tol
    used = poles = lost = 0
    different = False
    for state in random_states(given.free_symbols | correct.free_symbols):
        g, c = evaluate(given, state), evaluate(correct, state)
        if g is None or c is None:
            poles += 1
            continue
        if not (_usable(g) and _usable(c)):
            lost += 1
            continue
        used += 1
        with mpmath.workdps(CHECK_DPS):
            size = max(abs(g.value), abs(c.value))
            if abs(g.value - c.value) > max(mpmath.mpf(abs_tol), rel * size):
                different = True
    if used * 2 < TRIALS or (used * 2 == TRIALS and not different):
        why = []
        if poles:
            why.append(f"not finite or not real at {poles} of {TRIALS} random states")
        if lost:
            why.append(f"fewer than {NEEDED_DIGITS} digits survive cancellation at {lost} of {TRIALS} states")
        return Comparison(None, used, "; ".join(why))
    return Comparison(not different, used)


def ratio_at_states(given: sp.Expr, correct: sp.Expr) -> tuple[mpmath.mpf | None, int]:
    """The ratio ``given/correct`` if it is the same number at every usable random state (to
    10**-EQUAL_DIGITS, relatively), with the count of usable states; (None, count) if it varies or
    cannot be told."""
    ratio: mpmath.mpf | None = None
    used = 0
    for state in random_states(given.free_symbols | correct.free_symbols):
        g, c = evaluate(given, state), evaluate(correct, state)
        if not (_usable(g) and _usable(c)) or c is None or g is None or c.value == 0:
            continue
        used += 1
        with mpmath.workdps(CHECK_DPS):
            r = g.value / c.value
            if ratio is None:
                ratio = r
            elif abs(r - ratio) > abs(ratio) * mpmath.mpf(10) ** -EQUAL_DIGITS:
                return None, used
    if used * 2 <= TRIALS:
        return None, used
    return ratio, used


def value_of_number(expr: sp.Expr) -> mpmath.mpf | None:
    """A constant expression (an answer with no symbols) as an mpf, or None where it has no finite
    real value (``sqrt(-1)``, ``acos(2)``, ``1/0``) or cannot be told to NEEDED_DIGITS digits."""
    v = evaluate(expr, {})
    if not _usable(v) or v is None:
        return None
    return v.value
