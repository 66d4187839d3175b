"""The matrix form H(q) q_ddot + C(q, q_dot) + G(q) = Q from H, U and Q: Christoffel symbols, C and G.

Index conventions (0-based in code, 1-based in print):

- Christoffel symbols of the first kind, symmetric in j and k:
  Gamma_ijk = (dH_ij/dq_k + dH_ik/dq_j - dH_jk/dq_i) / 2, so that C_i = sum_jk Gamma_ijk q_dot_j q_dot_k
  and the Coriolis matrix C_ij = sum_k Gamma_ijk q_dot_k makes H_dot - 2 C skew-symmetric;
- the tutorial's table h_ijk = dH_ij/dq_k - dH_jk/dq_i / 2, not symmetric in j and k but with the same sum
  C_i = sum_jk h_ijk q_dot_j q_dot_k (the course prints this one);
- G_i = dU/dq_i, and Q_i the generalized forces, so each equation reads (H q_ddot + C + G - Q)_i = 0.

Every entry is tidied on its own (:func:`~tutgen.engine.tidy.tidy`), so no step needs a global simplify.
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

from tutgen.engine.tidy import tidy, tidy_rates

__all__ = ["christoffel_symbols", "coriolis_terms", "equations_of_motion", "gravity_vector"]

Table = dict[tuple[int, int, int], sp.Expr]


def christoffel_symbols(h: sp.MatrixBase, q: Sequence[sp.Symbol]) -> tuple[Table, Table]:
    """(Gamma_ijk of the first kind, the tutorial's h_ijk) of a mass matrix H(q), every (i, j, k).

    Examples
    ========
    >>> import sympy as sp
    >>> t1, t2, a = sp.symbols("theta1 theta2 a")
    >>> first, table = christoffel_symbols(sp.Matrix([[2 + 2 * a * sp.cos(t2), 1], [1, 1]]), [t1, t2])
    >>> first[0, 0, 1], table[0, 0, 1], table[0, 1, 0]
    (-a*sin(theta2), -2*a*sin(theta2), 0)
    """
    n = len(q)
    first = {
        (i, j, k): tidy((sp.diff(h[i, j], q[k]) + sp.diff(h[i, k], q[j]) - sp.diff(h[j, k], q[i])) / 2)
        for i in range(n)
        for j in range(n)
        for k in range(n)
    }
    tutorial = {
        (i, j, k): tidy(sp.diff(h[i, j], q[k]) - sp.diff(h[j, k], q[i]) / 2)
        for i in range(n)
        for j in range(n)
        for k in range(n)
    }
    return first, tutorial


def coriolis_terms(first: Table, qd: Sequence[sp.Symbol]) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix]:
    """(the vector C with C_i = sum_jk Gamma_ijk q_dot_j q_dot_k, the matrix C_ij = sum_k Gamma_ijk q_dot_k)."""
    n = len(qd)
    c_vec = sp.ImmutableMatrix(
        [
            tidy_rates(sum((first[i, j, k] * qd[j] * qd[k] for j in range(n) for k in range(n)), sp.Integer(0)), qd)
            for i in range(n)
        ]
    )
    c_mat = sp.ImmutableMatrix(
        n, n, lambda i, j: tidy_rates(sum((first[i, j, k] * qd[k] for k in range(n)), sp.Integer(0)), qd)
    )
    return c_vec, c_mat


def gravity_vector(u: sp.Expr, q: Sequence[sp.Symbol]) -> sp.ImmutableMatrix:
    """G_i = dU/dq_i: the potential terms (gravity and springs)."""
    return sp.ImmutableMatrix([tidy(sp.diff(u, qi)) for qi in q])


def equations_of_motion(
    h: sp.ImmutableMatrix,
    c_vec: sp.ImmutableMatrix,
    g_vec: sp.ImmutableMatrix,
    q_vec: sp.ImmutableMatrix,
    qd: Sequence[sp.Symbol],
    qdd: Sequence[sp.Symbol],
) -> sp.ImmutableMatrix:
    """(H q_ddot + C + G - Q)_i, each = 0, grouped by accelerations and rates."""
    n = len(qd)
    return sp.ImmutableMatrix(
        [tidy_rates((h * sp.Matrix(qdd))[i] + c_vec[i] + g_vec[i] - q_vec[i], [*qdd, *qd]) for i in range(n)]
    )
