"""The matrix C(q, q_dot) of a serial arm's recursive program, for `tutgen code` (docs/code.md).

The serial route (four or more joints) carries H(q) as a straight-line program (the composite-body
recursion of :mod:`tutgen.engine.recursive`), not as expanded entries. C is built from it without
expanding: the program is differentiated forward, one coordinate at a time (each definition's
derivative is a new definition, in terms of the earlier ones and their derivatives), which gives
dH_ij/dq_k as short expressions, and then

    C_ij = sum_k Gamma_ijk q_dot_k,   Gamma_ijk = (dH_ij/dq_k + dH_ik/dq_j - dH_jk/dq_i) / 2,

the Christoffel symbols of the first kind, the convention of the derivation's own ``coriolis_matrix``
(so that H_dot - 2C is skew and C q_dot is the Coriolis vector).
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

from tutgen.engine.recursive import NestedDynamics, needed_definitions

__all__ = ["program_coriolis_matrix"]


def _derivatives(expr: sp.Expr, q: Sequence[sp.Symbol], known: dict[sp.Symbol, list[sp.Expr]]) -> list[sp.Expr]:
    """d expr / d q_k for each k, with the definitions' derivatives ``known`` (chain rule)."""
    out = []
    inputs = sorted(expr.free_symbols, key=sp.default_sort_key)  # a fixed order: the same code every run
    for k, qk in enumerate(q):
        terms = []
        for s in inputs:
            ds = sp.Integer(1) if s == qk else known[s][k] if s in known else sp.Integer(0)
            if ds != 0:
                terms.append(sp.diff(expr, s) * ds)
        out.append(sp.Add(*terms))
    return out


def program_coriolis_matrix(
    prog: NestedDynamics,
) -> tuple[tuple[tuple[sp.Symbol, sp.Expr], ...], sp.ImmutableMatrix]:
    """The definitions C needs beyond ``prog.definitions`` (the derivatives of H's), and C itself in
    their symbols, the program's, the coordinates, the rates and the parameters."""
    q, qd = prog.coordinates, prog.rates
    n = len(q)
    known: dict[sp.Symbol, list[sp.Expr]] = {}
    extra: list[tuple[sp.Symbol, sp.Expr]] = []
    for x, e in needed_definitions(prog.definitions, [prog.mass_matrix]):
        row: list[sp.Expr] = []
        for k, de in enumerate(_derivatives(e, q, known)):
            if de.is_Atom:  # 0, a number or another symbol: no definition of its own
                row.append(de)
            else:
                name = sp.Dummy(f"d{x.name}_d{k}")
                extra.append((name, de))
                row.append(name)
        known[x] = row
    dh = [[_derivatives(prog.mass_matrix[i, j], q, known) for j in range(n)] for i in range(n)]

    def entry(i: int, j: int) -> sp.Expr:
        half = sp.Rational(1, 2)
        return sp.Add(*[half * (dh[i][j][k] + dh[i][k][j] - dh[j][k][i]) * qd[k] for k in range(n)])

    return tuple(extra), sp.ImmutableMatrix(n, n, entry)
