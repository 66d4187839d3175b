"""How long a result is, counted only as far as a decision needs (issue 17).

A worked solution prints a result whole, entry by entry or not at all, by its number of operations
(``sympy.count_ops``). A full ``count_ops`` walks every node and builds new expressions on the way
(negations, ``fraction``): on the fully symbolic PUMA 560 (180 000 operations of H, C and G alone, a
million of Christoffel symbols) it took most of the time of ``tutgen solve``, only to decide not to
print. :func:`count_ops_upto` counts with :func:`count_ops` (sympy's count, the same number, faster),
which stops as soon as its count passes the limit; a large arm's results held by
:mod:`tutgen.engine.lazytable` are bounded from below without converting them.

:func:`lower_bound_exceeds` is a cheaper walk for a lower bound alone: it counts, node by node, what
``count_ops`` counts for that node at least: ``k - 1`` operations (ADD or SUB) for a sum of ``k`` terms,
one for a power (POW, DIV or EXP), one for an applied function or derivative, and for a product of ``k``
factors ``k - 1`` less one per power factor (``x*y**-1`` is a single DIV) and less one for a factor -1
(``a - x*y`` is one SUB and one MUL). ``count_ops``'s rewriting of a product (``-a``, ``fraction``)
never removes a sum, a product's factor or a power's base from the tree, so the bound holds
(tests/render/test_size.py checks it on every kind of node and on derived results).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

import sympy as sp
from sympy.core.operations import LatticeOp
from sympy.simplify.radsimp import fraction

from tutgen.engine.lazytable import LazyMatrix, LazyTable
from tutgen.render.signs import coefficient_negative

__all__ = ["count_ops", "count_ops_upto", "lower_bound_exceeds", "nonzero_count", "size_text"]


def lower_bound_exceeds(exprs: Iterable[sp.Basic], limit: int) -> bool:
    """True when ``sympy.count_ops`` of the expressions together is certainly more than ``limit`` (a
    walk that stops there)."""
    total = 0
    stack = list(exprs)
    while stack:
        a = stack.pop()
        args = a.args
        if not args:
            continue
        if a.is_Add:
            total += len(args) - 1
        elif a.is_Mul:
            total += _product_bound(args)
        elif a.is_Pow or a.is_Function or isinstance(a, sp.Derivative):
            total += 1
        if total > limit:
            return True
        stack.extend(args)
    return False


def _product_bound(args: tuple[sp.Basic, ...]) -> int:
    """What count_ops counts for a product of these factors at least, besides its factors' own: k - 1
    multiplications, less one per power or exponential (a denominator's DIV stands for it, and the
    power itself is counted once already) and less one for a factor -1 (in a sum it becomes a SUB,
    which the sum counts)."""
    bound = len(args) - 1 - sum(1 for f in args if f.is_Pow or isinstance(f, sp.exp))
    if args[0] is sp.S.NegativeOne:
        bound -= 1
    return max(bound, 0)


def count_ops_upto(exprs: Iterable[Any], limit: int) -> int:
    """``sympy.count_ops`` of the expressions (and of every entry of a matrix or value of a table)
    together when that is at most ``limit``, else ``limit + 1``: an expression certainly too long is
    never counted in full, and a large arm's table of Christoffel symbols, C q_dot, C or equations of motion
    (:mod:`tutgen.engine.lazytable`) never converted for it.

    >>> x, y = sp.symbols("x y")
    >>> count_ops_upto([x * y + sp.sin(x)], 10), count_ops_upto([sp.Add(*sp.symbols("a:20"))], 5)
    (3, 6)
    """
    items: list[sp.Basic] = []
    bound = 0
    for e in exprs:
        if isinstance(e, LazyTable):  # a large arm's table, not yet converted: its own lower bound
            bound += e.min_ops(limit - bound)  # summed only as far as the limit
            if bound > limit:
                return limit + 1
            items += [x for x in e.values() if x != 0]
        elif isinstance(e, LazyMatrix) and not e.is_converted:  # a large arm's C q_dot, C or equations
            bound += e.min_ops()
            if bound > limit:
                return limit + 1
            items += [x for x in e if isinstance(x, sp.Basic)]
        elif isinstance(e, Mapping):  # a table of symbols: its values
            items += [x for x in e.values() if isinstance(x, sp.Basic) and x != 0]
        elif isinstance(e, sp.MatrixBase):
            items += [x for x in e if isinstance(x, sp.Basic)]
        elif isinstance(e, sp.Basic):
            items.append(e)
    total = 0
    for item in items:  # counted exactly, each stopping once the total passes the limit
        total += count_ops(item, limit - total)
        if total > limit:
            return limit + 1
    return total


def count_ops(expr: sp.Basic, limit: int | None = None) -> int:
    """``sympy.count_ops(expr)``, the same number, about three times as fast on long sums of products
    (issue 17: the symbolic PUMA's T, 22 905 operations, is counted for its worked solution).

    It is sympy's walk with its counts kept as integers: sympy collects each operation as a symbol
    (``ADD``, ``MUL``, ``DIV``, …) in a list and adds them up as a sympy sum at the end, and it calls
    ``fraction`` on every product. Here a product whose factors have no denominator (no negative or
    symbolic power, no ``exp``; at most a rational coefficient) is split without ``fraction``, as
    ``fraction`` would split it; every other node is handled by sympy's own steps (negation,
    ``fraction``). Anything but a non-relational expression goes to ``sympy.count_ops``.
    tests/render/test_size.py compares the two on every derived result of the specs.

    With ``limit``, the walk stops as soon as its count passes the limit and returns that count (more
    than ``limit``, at most the full count): the count only grows along the walk, so a result that
    certainly does not fit is not walked to its end (issue 17).

    >>> x, y = sp.symbols("x y")
    >>> count_ops(x * y / 2 - sp.sin(x) ** 2 + 3), int(sp.count_ops(x * y / 2 - sp.sin(x) ** 2 + 3))
    (7, 7)
    """
    if not isinstance(expr, sp.Expr) or expr.is_Relational:
        return int(sp.count_ops(expr))
    one, minus_one, e = sp.S.One, sp.S.NegativeOne, sp.S.Exp1
    stop = math.inf if limit is None else limit
    total = 0
    todo: list[sp.Basic] = [expr]
    while todo:
        if total > stop:
            return total
        a = todo.pop()
        if a.is_Rational:
            if a is not one:
                total += (a.p < 0) + (a.q != 1)
                continue
        elif a.is_Mul or a.is_MatMul:
            if coefficient_negative(a):
                total += 1  # NEG
                a = a.as_two_terms()[1] if a.args[0] is minus_one else -a
            split = _plain_split(a)
            if split is None:  # sympy's own steps
                n, d = fraction(a)
                if n.is_Integer:
                    total += 1 + (n.p < 0)  # DIV (and NEG)
                    todo.append(d)
                    continue
                if d is not one:
                    if not d.is_Integer:
                        todo.append(d)
                    total += 1  # DIV
                    todo.append(n)
                    continue
            elif split:  # a rational coefficient p/q: DIV, and the numerator p * rest
                total += 1 + split[0]
                todo.extend(split[1])
                continue
        elif a.is_Add or a.is_MatAdd:
            negative = 0
            for term in a.args:
                if coefficient_negative(term):
                    negative += 1
                    todo.append(-term)
                else:
                    todo.append(term)
            total += len(a.args) - 1 + (negative == len(a.args))  # ADD or SUB each (and NEG)
            continue
        if a.is_Pow and a.exp is minus_one:
            total += 1  # DIV
            todo.append(a.base)
            continue
        if a is e:
            total += 1  # EXP
            continue
        if a.is_Pow and a.base is e:
            total += 1  # EXP
            todo.append(a.exp)
            continue
        if a.is_Mul or isinstance(a, LatticeOp):
            total += len(a.args) - 1
        elif a.args and (a.is_Pow or a.is_Function or isinstance(a, (sp.Derivative, sp.Integral, sp.Sum))):
            total += 1
        if not a.is_Symbol:
            todo.extend(a.args)
    return total


def _plain_split(a: sp.Basic) -> tuple[int, list[sp.Basic]] | tuple[()] | None:
    """How ``sympy.fraction`` splits ``a`` (a product with a positive coefficient, or a factor of one),
    when that needs no rewriting: ``()`` when it has no denominator (``fraction`` gives ``(a, 1)``); for a
    coefficient p/q (q > 1) times factors without denominators, (the multiplications of the numerator
    p * factors, the factors); None when sympy's ``fraction`` must decide (a power that is not a positive
    integer, ``exp``, a nested product, a number other than a leading coefficient (pi, I, a root of 2, or
    any number in a product built unevaluated), zero, a negative p, two powers of one base (sympy would
    rebuild those differently), or p times a single sum, which sympy would distribute)."""
    factors = a.args if a.is_Mul else (a,)
    if len(factors) == 1 and factors[0].is_number:  # sympy counts a number left after a minus as a DIV
        return None
    coefficient = None
    for i, f in enumerate(factors):
        if f.is_Rational or f.is_Float:
            if i or f.is_zero:  # a number after the first factor, or zero: sympy may combine them
                return None
            if f.is_Rational and not f.is_Integer:
                coefficient = f
        elif f.is_number:  # pi, I, a root of 2: sympy may combine them
            return None
        elif f.is_Pow:
            if not (f.exp.is_Integer and f.exp > 0):
                return None
        elif isinstance(f, sp.exp) or f.is_Mul:
            return None
    if coefficient is None:
        return ()
    if coefficient.p < 0:  # a product built unevaluated
        return None
    rest = factors[1:]
    bases = [f.base if f.is_Pow else f for f in rest]
    if len(set(bases)) < len(bases) or not all(f.is_commutative for f in rest):
        return None  # factors sympy would multiply together when it builds the numerator
    if coefficient.p != 1:
        if len(rest) == 1 and rest[0].is_Add:
            return None
        return len(rest), rest
    return len(rest) - 1, rest


def nonzero_count(table: Mapping[Any, sp.Expr]) -> int:
    """How many entries of a table of symbols are not zero (a large arm's, without converting them)."""
    if isinstance(table, LazyTable):
        return table.nonzero_count()
    return sum(1 for v in table.values() if v != 0)


def size_text(ops: int, limit: int) -> str:
    """A count of :func:`count_ops_upto` in words: ``10503`` or ``more than 40000``."""
    return f"more than {limit}" if ops > limit else str(ops)
