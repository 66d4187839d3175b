"""A table of Christoffel symbols converted to sympy when first read (issue 17).

A 6-DOF arm's tutorial table h_ijk took longer to convert to sympy than everything else of its
derivation, and a worked solution does not print it: the serial route (:mod:`tutgen.engine.serial`)
hands the :class:`~tutgen.engine.derivation.Derivation` a :class:`LazyTable`, whose keys, length,
nonzero count and a lower bound of its size are known from the exact polynomials without converting.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping

import sympy as sp

from tutgen.engine.trigpoly import TrigPoly

__all__ = ["LazyTable"]


class LazyTable(Mapping[tuple[int, int, int], sp.Expr]):
    """Every symbol (i, j, k) of an n x n x n table, zeros included, computed on first read from
    ``nonzero`` (the converted nonzero symbols); ``polys`` gives the same symbols as exact polynomials,
    for the sizes. Pickled, it is a plain dict (a sheet's worker sends its results)."""

    def __init__(
        self,
        n: int,
        nonzero: Callable[[], Mapping[tuple[int, int, int], sp.Expr]],
        polys: Callable[[], Mapping[tuple[int, int, int], TrigPoly]],
    ) -> None:
        self._n = n
        self._nonzero = nonzero
        self._polys = polys
        self._table: dict[tuple[int, int, int], sp.Expr] | None = None

    @property
    def is_converted(self) -> bool:
        """Whether the symbols have been converted to sympy (read at least once)."""
        return self._table is not None

    def nonzero_count(self) -> int:
        """How many symbols are not zero, without converting any."""
        return len(self._polys())

    def min_ops(self) -> int:
        """A lower bound of ``sympy.count_ops`` of the nonzero symbols together, without converting any:
        a polynomial of s terms converts to a sum with at least s - 1 additions (its coefficients are
        grouped by pulling out single factors, which never merges two terms)."""
        return sum(max(p.size() - 1, 0) for p in self._polys().values())

    def _full(self) -> dict[tuple[int, int, int], sp.Expr]:
        if self._table is None:
            nonzero = self._nonzero()
            zero = sp.Integer(0)
            n = self._n
            keys = [(i, j, k) for i in range(n) for j in range(n) for k in range(n)]
            self._table = {key: nonzero.get(key, zero) for key in keys}
        return self._table

    def __getitem__(self, key: tuple[int, int, int]) -> sp.Expr:
        return self._full()[key]

    def __iter__(self) -> Iterator[tuple[int, int, int]]:
        n = self._n
        return ((i, j, k) for i in range(n) for j in range(n) for k in range(n))

    def __len__(self) -> int:
        return self._n**3

    def __reduce__(self) -> tuple[type, tuple[dict[tuple[int, int, int], sp.Expr]]]:
        return (dict, (self._full(),))
