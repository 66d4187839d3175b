"""How long a result is, counted only as far as a decision needs (issue 17).

A worked solution prints a result whole, entry by entry or not at all, by its number of operations
(``sympy.count_ops``). A full ``count_ops`` walks every node and builds new expressions on the way
(negations, ``fraction``): on the fully symbolic PUMA 560 (180 000 operations of H, C and G alone, a
million of Christoffel symbols) it took most of the time of ``tutgen solve``, only to decide not to
print. :func:`count_ops_upto` first walks the tree for a cheap lower bound of ``count_ops`` and
stops as soon as it passes the limit; only an expression that may fit is counted exactly.

The lower bound counts, node by node, what ``count_ops`` counts for that node at least: ``k - 1``
operations (ADD or SUB) for a sum of ``k`` terms, one for a power (POW, DIV or EXP), one for an
applied function or derivative, and for a product of ``k`` factors ``k - 1`` less one per power
factor (``x*y**-1`` is a single DIV) and less one for a factor -1 (``a - x*y`` is one SUB and one
MUL). ``count_ops``'s rewriting of a product (``-a``, ``fraction``) never removes a sum, a product's
factor or a power's base from the tree, so the bound holds (tests/render/test_size.py checks it on
every kind of node and on derived results).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

import sympy as sp

from tutgen.engine.lazytable import LazyMatrix, LazyTable

__all__ = ["count_ops_upto", "lower_bound_exceeds", "nonzero_count", "size_text"]


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
    if lower_bound_exceeds(items, limit):
        return limit + 1
    total = 0
    for item in items:
        total += int(sp.count_ops(item))
        if total > limit:
            return limit + 1
    return total


def nonzero_count(table: Mapping[Any, sp.Expr]) -> int:
    """How many entries of a table of symbols are not zero (a large arm's, without converting them)."""
    if isinstance(table, LazyTable):
        return table.nonzero_count()
    return sum(1 for v in table.values() if v != 0)


def size_text(ops: int, limit: int) -> str:
    """A count of :func:`count_ops_upto` in words: ``10503`` or ``more than 40000``."""
    return f"more than {limit}" if ops > limit else str(ops)
