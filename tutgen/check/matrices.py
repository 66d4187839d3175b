"""What is wrong with a whole matrix: rows or columns swapped, transposed, or a common factor.

A matrix answer whose entries are wrong one by one may be right as a whole in the wrong arrangement
(the coordinates taken in another order, the matrix written transposed) or scaled by one factor. The
report then names that once ("rows 1 and 2 are swapped") instead of listing four wrong entries.
Each arrangement is tried by the decision procedure (:func:`tutgen.check.equivalence.decide`), entry
by entry, stopping at the first entry that does not fit; only matrices up to :data:`MAX_SIZE` rows
and columns are tried (a 4x4 has 23 orders of rows).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from itertools import permutations

import sympy as sp

from tutgen.check.equivalence import constant_factor, decide, is_acceptable_scale
from tutgen.render.jsonout import expr_text

__all__ = ["MAX_SIZE", "matrix_finding"]

#: The largest matrix (rows or columns) whose arrangements are tried.
MAX_SIZE = 4

Grid = list[list[sp.Expr]]


def _order(perm: tuple[int, ...]) -> str:
    """``(1, 0)`` as "1 and 2 are swapped"; a longer cycle as "in the order 2, 3, 1"."""
    moved = [i for i, p in enumerate(perm) if p != i]
    if len(moved) == 2:
        return f"{moved[0] + 1} and {moved[1] + 1} are swapped"
    return "in the order " + ", ".join(str(p + 1) for p in perm)


def _arrangements(rows: int, cols: int) -> Iterator[tuple[str, Callable[[int, int], tuple[int, int]]]]:
    """(what it is called, where entry (i, j) of the answer is in the result), identity excluded."""
    if rows == cols:
        yield "it is transposed (rows and columns exchanged)", lambda i, j: (j, i)
        for p in permutations(range(rows)):
            if list(p) != list(range(rows)):
                yield (
                    f"rows and columns {_order(p)} (the coordinates in another order)",
                    lambda i, j, p=p: (p[i], p[j]),
                )
    for p in permutations(range(rows)):
        if list(p) != list(range(rows)):
            yield f"rows {_order(p)}", lambda i, j, p=p: (p[i], j)
    for p in permutations(range(cols)):
        if list(p) != list(range(cols)):
            yield f"columns {_order(p)}", lambda i, j, p=p: (i, p[j])


def matrix_finding(
    given: Grid, correct: Grid, state: frozenset[sp.Symbol], forbidden: frozenset[sp.Symbol]
) -> str | None:
    """What is wrong with ``given`` as a whole next to ``correct`` (same shape), or None when it is not
    one of: another arrangement of the same entries, or every entry times one constant factor."""
    rows, cols = len(correct), len(correct[0]) if correct else 0
    if not rows or not cols or rows > MAX_SIZE or cols > MAX_SIZE:
        return None
    known: dict[tuple[int, int, int, int], bool] = {}

    def same(i: int, j: int, k: int, m: int) -> bool:
        if (i, j, k, m) not in known:
            known[(i, j, k, m)] = decide(given[i][j], correct[k][m]).equal is True
        return known[(i, j, k, m)]

    for name, where in _arrangements(rows, cols):
        if all(same(i, j, *where(i, j)) for i in range(rows) for j in range(cols)):
            return f"the entries are right but not in their places: {name}"
    pairs = [(i, j) for i in range(rows) for j in range(cols) if correct[i][j] != 0 and given[i][j] != 0]
    if not pairs:
        return None
    i, j = pairs[0]
    k = constant_factor(given[i][j], correct[i][j], state, forbidden)
    if k is None or k == 1 or not is_acceptable_scale(k):
        return None
    if all(decide(given[a][b], k * correct[a][b]).equal is True for a in range(rows) for b in range(cols)):
        if k == -1:
            return "every entry has the wrong sign (yours is the negative of the correct matrix)"
        return f"off by a common factor {expr_text(k)}: every entry is {expr_text(k)} times the correct one"
    return None
