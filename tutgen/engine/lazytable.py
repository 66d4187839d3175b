"""Results converted to sympy when first read (issue 17): a table of Christoffel symbols, and a matrix.

A 6-DOF arm's tutorial table h_ijk took longer to convert to sympy than everything else of its
derivation, and a worked solution does not print it: the serial route (:mod:`tutgen.engine.serial`)
hands the :class:`~tutgen.engine.derivation.Derivation` a :class:`LazyTable`, whose keys, length,
nonzero count and a lower bound of its size are known from the exact polynomials without converting.

The same holds for C q_dot, C and the equations of motion of a large arm (the symbolic PUMA's C q_dot
is 140 000 operations, converted from about a hundred Christoffel symbols): a Markdown solution only
decides, by their size, not to print them. :class:`LazyMatrix` is an ``ImmutableMatrix`` whose entries
are computed on first read; its shape and a lower bound of its size are known before.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping, Sequence
from typing import Any

import sympy as sp

__all__ = ["LazyMatrix", "LazyTable"]


class LazyTable(Mapping[tuple[int, int, int], sp.Expr]):
    """Every symbol (i, j, k) of an n x n x n table, zeros included, computed on first read from
    ``nonzero`` (the converted nonzero symbols); ``keys`` gives the keys of the nonzero symbols and
    ``bound`` a lower bound of ``sympy.count_ops`` of the symbol of a key, from the exact polynomials
    (without converting, and for the tutorial's h_ijk without computing the symbol either), for the
    sizes. Pickled, it is a plain dict (a sheet's worker sends its results)."""

    def __init__(
        self,
        n: int,
        nonzero: Callable[[], Mapping[tuple[int, int, int], sp.Expr]],
        keys: Callable[[], Sequence[tuple[int, int, int]]],
        bound: Callable[[tuple[int, int, int]], int],
    ) -> None:
        self._n = n
        self._nonzero = nonzero
        self._keys = keys
        self._bound = bound
        self._table: dict[tuple[int, int, int], sp.Expr] | None = None

    @property
    def is_converted(self) -> bool:
        """Whether the symbols have been converted to sympy (read at least once)."""
        return self._table is not None

    def nonzero_count(self) -> int:
        """How many symbols are not zero, without converting any."""
        return len(self._keys())

    def min_ops(self, limit: int | None = None) -> int:
        """A lower bound of ``sympy.count_ops`` of the nonzero symbols together, without converting any
        (the sum of ``bound``). With ``limit``, the sum stops as soon as it passes the limit (a large
        arm's worked solution needs a fifth of its 195 h_ijk to know they are too long to print)."""
        total = 0
        for key in self._keys():
            total += self._bound(key)
            if limit is not None and total > limit:
                break
        return total

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


class LazyMatrix(sp.ImmutableDenseMatrix):
    """An immutable ``rows x cols`` matrix whose entries ``entries()`` (row-major) gives on first read.

    It is an ``ImmutableMatrix`` for every reader: indexing, iteration, arithmetic, ``subs``,
    ``applyfunc``, equality and hashing read the entries (converting them once), and every matrix built
    from it is a plain ``ImmutableMatrix``. Only :attr:`is_converted` and :meth:`min_ops` (a lower bound
    of ``sympy.count_ops`` of the entries, from the exact polynomials) do not convert: the budgeted size
    count of :mod:`tutgen.render.size` reads them. Pickled, it is a plain ``ImmutableMatrix``.

    How: sympy keeps a matrix's entries in ``_args`` (a slot of ``Basic``) and ``_rep`` (its
    ``DomainMatrix``); here both are properties that build the plain matrix first.
    """

    def __new__(cls, *args: Any, **kwargs: Any) -> Any:
        """``LazyMatrix(rows, cols, entries, min_ops)``; called any other way (sympy builds the result of
        an operation with the class of its operand, ``typ(mat)``), a plain ``ImmutableMatrix``."""
        if kwargs or len(args) != 4 or not callable(args[2]):
            return sp.ImmutableDenseMatrix(*args, **kwargs)
        rows, cols, entries, min_ops = args
        obj = object.__new__(cls)  # not Basic.__new__, which sets _args
        obj._assumptions = cls.default_assumptions
        obj._mhash = None
        obj._rows, obj._cols = rows, cols
        obj._entries = entries
        obj._min_ops = min_ops
        obj._plain = None
        return obj

    @property
    def is_converted(self) -> bool:
        """Whether the entries have been computed (read at least once)."""
        return self._plain is not None

    def min_ops(self) -> int:
        """A lower bound of ``sympy.count_ops`` of the entries together, without computing them."""
        return self._min_ops()

    def as_plain(self) -> sp.ImmutableDenseMatrix:
        """The same matrix as a plain ``ImmutableMatrix`` (computing the entries on first call)."""
        if self._plain is None:
            entries = list(self._entries())
            if len(entries) != self._rows * self._cols:
                raise ValueError(f"a {self._rows} x {self._cols} matrix needs {self._rows * self._cols} entries")
            self._plain = sp.ImmutableDenseMatrix(self._rows, self._cols, entries)
        return self._plain

    @property  # type: ignore[override]
    def _args(self) -> tuple[sp.Basic, ...]:
        return self.as_plain()._args

    @property  # type: ignore[override]
    def _rep(self) -> object:
        return self.as_plain()._rep

    def __hash__(self) -> int:  # equal to the plain matrix, so the same hash
        return hash(self.as_plain())

    def __eq__(self, other: object) -> bool:
        return self.as_plain() == other

    @property
    def func(self) -> type:  # rebuilding from args gives a plain matrix
        return sp.ImmutableDenseMatrix

    @classmethod
    def _new(cls, *args: object, **kwargs: object) -> sp.ImmutableDenseMatrix:
        return sp.ImmutableDenseMatrix._new(*args, **kwargs)

    @classmethod
    def _fromrep(cls, rep: object) -> sp.ImmutableDenseMatrix:
        return sp.ImmutableDenseMatrix._fromrep(rep)

    def __reduce_ex__(self, protocol: object) -> tuple[type, tuple[int, int, list[sp.Expr]]]:
        return (sp.ImmutableDenseMatrix, (self._rows, self._cols, list(self.as_plain())))

    def __reduce__(self) -> tuple[type, tuple[int, int, list[sp.Expr]]]:
        return self.__reduce_ex__(2)
