"""Putting expressions in the form a person writes, and deciding whether an expression is zero.

No global ``simplify``: every function here works on one small expression at a time (one entry of
H, one term of T), so cost stays proportional to the size of the result.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Iterable, Iterator, Sequence

import sympy as sp
from sympy.simplify.fu import TR8

#: How many results each memoised function keeps (issue 17): a worked solution tidies the same entry
#: several times (the Lagrange and Newton–Euler routes, the checks, the matrix form), a sheet its variants.
MEMO_SIZE = 4096


def memoised(fn: Callable[[sp.Expr], sp.Expr]) -> Callable[[sp.Expr], sp.Expr]:
    """``fn`` of one expression, remembered for equal expressions. Not for expressions with floats:
    sympy's ``==`` may hold between floats of different precisions, which print differently. The memo
    is emptied when full, so results never depend on what ran before."""
    memo: dict[sp.Basic, sp.Expr] = {}

    def remembered(expr: sp.Expr) -> sp.Expr:
        if not isinstance(expr, sp.Basic) or expr.has(sp.Float):
            return fn(expr)
        hit = memo.get(expr)
        if hit is None:
            hit = fn(expr)
            if len(memo) >= MEMO_SIZE:
                memo.clear()
            memo[expr] = hit
        return hit

    remembered.__name__ = remembered.__qualname__ = fn.__name__
    remembered.__doc__ = fn.__doc__
    remembered.__wrapped__ = fn  # type: ignore[attr-defined]
    return remembered


@memoised
def tidy(expr: sp.Expr) -> sp.Expr:
    """The shortest of three forms of a trigonometric polynomial: as expanded, as a sum of sines
    and cosines of combined angles (products turned into sums, so cos a cos b - sin a sin b becomes
    cos(a - b)... and sin^2 + cos^2 becomes 1), and as a polynomial in the sines and cosines of
    single angles (cos(2t) back to cos(t)^2). Each is cheap: no ``trigsimp``/``simplify`` search.

    Examples
    ========
    >>> import sympy as sp
    >>> a, t, u = sp.symbols("a t u")
    >>> tidy(a*sp.sin(t)**2 + a*sp.cos(t)**2)
    a
    >>> tidy(sp.cos(t)*sp.cos(t + u) + sp.sin(t)*sp.sin(t + u))
    cos(u)
    """
    e = sp.expand(expr)
    if e.is_number or not e.has(sp.sin, sp.cos):
        return e
    combined = sp.expand(TR8(e))
    reduced = trig_reduce(combined) if _single_angles(combined) else combined
    # on a tie, prefer powers of single angles (cos(t)**2) to multiple angles (cos(2*t))
    return min((e, reduced, combined), key=lambda c: (sp.count_ops(c), c is combined))


def _single_angles(expr: sp.Expr) -> bool:
    """True when every sine and cosine has a multiple of one symbol as its argument."""
    return all(len(f.args[0].free_symbols) <= 1 for f in expr.atoms(sp.sin, sp.cos))


def tidy_rates(expr: sp.Expr, rates: Sequence[sp.Symbol]) -> sp.Expr:
    """Group a polynomial in the rates (q_dot or q_ddot) by monomial, each coefficient tidied."""
    e = sp.expand(expr)
    if not rates or not e.is_polynomial(*rates):  # e.g. a drag force c*x_dot*abs(x_dot)
        return tidy(e)
    poly = sp.Poly(e, *rates)
    terms = []
    for monom, coeff in sorted(poly.terms(), key=lambda t: t[0], reverse=True):
        mono = sp.Mul(*[r**k for r, k in zip(rates, monom, strict=True)])
        terms.append(tidy(coeff) * mono)
    return sp.Add(*terms)


@memoised
def trig_reduce(expr: sp.Expr) -> sp.Expr:
    """A canonical form for polynomials in sines and cosines: expand every sum of angles, then
    replace sin(u)^2 by 1 - cos(u)^2 until no even power of a sine is left. Two such polynomials
    are equal exactly when their reduced forms are equal."""
    out = sp.expand(sp.expand_trig(expr))

    def is_sin_square(t: sp.Basic) -> bool:
        return bool(t.is_Pow and isinstance(t.base, sp.sin) and t.exp.is_Integer and t.exp >= 2)

    def lower(t: sp.Pow) -> sp.Expr:
        u = t.base.args[0]
        return (1 - sp.cos(u) ** 2) * sp.sin(u) ** (t.exp - 2)

    while out.has(sp.sin) and any(is_sin_square(t) for t in sp.preorder_traversal(out)):
        out = sp.expand(out.replace(is_sin_square, lower))
    return out


def random_states(symbols: Iterable[sp.Symbol], count: int, seed: int = 4245) -> Iterator[dict[sp.Symbol, sp.Expr]]:
    """``count`` states, the same for the same symbols and seed: each symbol a random k/1000 in [0.3, 2.7]."""
    free = sorted(symbols, key=lambda s: s.name)
    rng = random.Random(seed)
    for _ in range(count):
        yield {s: sp.Rational(rng.randint(300, 2700), 1000) for s in free}


def numerically_zero(expr: sp.Expr, trials: int = 8, seed: int = 4245) -> bool:
    """True when the expression vanishes (to 1e-9, relatively) at random points in (0.3, 2.7).

    Deterministic: a fixed seed, evaluated with sympy's own arbitrary-precision evaluation. A point
    where the expression is not finite (a pole) is skipped; with no usable point the answer is False.
    """
    used = 0
    for point in random_states(expr.free_symbols, 4 * trials, seed):
        if used == trials:
            break
        value = sp.N(expr.subs(point), 30)
        if not value.is_number or value.has(sp.zoo, sp.oo, sp.nan, -sp.oo):
            continue
        terms = [sp.N(a.subs(point), 15) for a in sp.Add.make_args(expr)]
        if any(t.has(sp.zoo, sp.oo, sp.nan, -sp.oo) or not t.is_number for t in terms):
            continue
        used += 1
        scale = max([1.0, *(abs(complex(t)) for t in terms)])
        if abs(complex(value)) > 1e-9 * scale:
            return False
    return used > 0


def is_zero(expr: sp.Expr) -> tuple[bool, str]:
    """Decide expr == 0: symbolically when possible, else numerically. Returns (zero, how)."""
    e = sp.expand(expr)
    if e == 0:
        return True, "expanded"
    if trig_reduce(e) == 0:
        return True, "trigonometric reduction"
    if numerically_zero(e):
        return True, "numerically, at 8 random states"
    return False, "differs"


def sort_symbols(symbols: Iterable[sp.Symbol]) -> list[sp.Symbol]:
    return sorted(symbols, key=sp.default_sort_key)
