"""The constrained equations of motion by two routes, checked against each other.

From the unconstrained matrix form H q_ddot + C + G = Q of all n coordinates (the general route's):

- **Lagrange's multipliers**: H q_ddot + C + G = Q + A^T lambda with A q_ddot + b = 0, a
  differential-algebraic system of n + m equations for q_ddot and the m multipliers lambda. The
  constraint's generalized force on coordinate j is (A^T lambda)_j: a force along a length coordinate,
  a torque about an angle coordinate. lambda is solved from the dependent coordinates' rows,
  lambda = A_d^-T (H q_ddot + C + G - Q)_d, with q_ddot from the reduced equations;
- **reduction to the independent coordinates**: q_dot = T q_dot_i and q_ddot = T q_ddot_i + T_dot q_dot_i,
  and T^T A^T = 0 removes the multipliers: H_r q_ddot_i + C_r + G_r = Q_r with H_r = T^T H T,
  C_r = T^T (C + H T_dot q_dot_i), G_r = T^T G, Q_r = T^T Q, the dependent rates replaced by B q_dot_i and,
  where the position analysis has a closed form, the dependent coordinates by it.

The check solves the multipliers' system numerically at consistent states (without T) and compares its
q_ddot and lambda with the reduced route's.
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Any

import mpmath
import sympy as sp

from tutgen.engine.constraints.kinematics import ConstraintKinematics, consistent_states
from tutgen.engine.derivation import Check
from tutgen.engine.tidy import tidy
from tutgen.errors import DerivationError
from tutgen.model.system import System

__all__ = ["STATES", "ConstrainedDynamics", "constrained_dynamics", "multiplier_symbol"]

#: consistent states at which the two routes are compared
STATES = 3
_TOLERANCE = mpmath.mpf("1e-15")
_SIMPLIFY_OPS = 60  # sp.simplify only expressions this small (it is slow on long ones)
#: q_ddot_i and lambda are solved in closed form only when the reduced equations are this small (a
#: four-bar's are pages long: its lambda stays in the accelerations, and the check is numeric)
_CLOSED_FORM_OPS = 200
_TIDY_OPS = 150
_SHOWN_OPS = 120  # the closed forms of q_ddot_i and lambda are kept only when this short


def multiplier_symbol(k: int) -> sp.Symbol:
    """The multiplier of the constraint ``k`` (1-based, in spec order): ``lambda_k``."""
    return sp.Symbol(f"lambda_{k}")


@dataclass(frozen=True)
class ConstrainedDynamics:
    """Both routes' results (the module's conventions); expressions symbolic, parameters as symbols."""

    kinematics: ConstraintKinematics
    multipliers: tuple[sp.Symbol, ...]
    constraint_forces: sp.ImmutableMatrix  # A^T lambda, n x 1
    # lambda from the dependent rows, in the accelerations, then its value along the motion
    multipliers_in_accelerations: tuple[sp.Expr, ...]
    multiplier_values: tuple[sp.Expr, ...]
    velocity_terms: sp.ImmutableMatrix  # T_dot q_dot_i, n x 1
    mass_matrix: sp.ImmutableMatrix  # H_r
    coriolis_vector: sp.ImmutableMatrix  # C_r
    gravity_vector: sp.ImmutableMatrix  # G_r
    generalized_forces: sp.ImmutableMatrix  # Q_r
    equations_of_motion: sp.ImmutableMatrix  # H_r q_ddot_i + C_r + G_r - Q_r, each = 0
    accelerations: tuple[sp.Expr, ...]  # q_ddot_i solved (empty when H_r is too large to invert here)
    check: Check


def _simplify(e: sp.Expr) -> sp.Expr:
    """The project's tidy form, with a short fraction cancelled (sp.simplify takes minutes on a loop's)."""
    if sp.count_ops(e) > _TIDY_OPS:  # a loop's long entries: tidying them takes minutes, and they stay long
        return e
    e = tidy(e)
    if sp.count_ops(e) <= _SIMPLIFY_OPS:
        simpler = tidy(sp.cancel(e))
        if sp.count_ops(simpler) < sp.count_ops(e):
            return simpler
    return e


def constrained_dynamics(
    system: System,
    ck: ConstraintKinematics,
    h: sp.ImmutableMatrix,
    c_vec: sp.ImmutableMatrix,
    g_vec: sp.ImmutableMatrix,
    q_vec: sp.ImmutableMatrix,
) -> ConstrainedDynamics:
    """Both routes from the unconstrained H, C, G and Q, and their agreement (a difference raises: it is a
    tutgen bug)."""
    coords = system.coordinates
    q = [c.q for c in coords]
    qd = [c.qd for c in coords]
    qdd = [c.qdd for c in coords]
    n, m = len(q), len(system.constraints)
    ind, dep = ck.independent, ck.dependent
    qdd_i = [qdd[j] for j in ind]
    qd_i = sp.Matrix([qd[j] for j in ind])
    t = ck.velocity_map
    places = dict(ck.positions[0]) if len(ck.positions) == 1 else {}
    at_positions = {q[j]: e for j, e in places.items()}

    def along(e: sp.Expr) -> sp.Expr:
        """On the constrained motion: dependent rates from B, dependent positions from the closed form."""
        e = e.xreplace(ck.rates)
        return e.xreplace(at_positions) if at_positions else e

    t_dot = t.applyfunc(lambda e: along(sum((sp.diff(e, q[j]) * qd[j] for j in range(n)), sp.Integer(0))))
    velocity_terms = sp.ImmutableMatrix((t_dot * qd_i).applyfunc(tidy))
    t_m = t.applyfunc(along)
    h_m = h.applyfunc(along)
    c_m = c_vec.applyfunc(along)
    g_m = g_vec.applyfunc(along)
    q_m = q_vec.applyfunc(along)
    h_r = sp.ImmutableMatrix((t_m.T * h_m * t_m).applyfunc(_simplify))
    c_r = sp.ImmutableMatrix((t_m.T * (c_m + h_m * velocity_terms)).applyfunc(_simplify))
    g_r = sp.ImmutableMatrix((t_m.T * g_m).applyfunc(_simplify))
    q_r = sp.ImmutableMatrix((t_m.T * q_m).applyfunc(_simplify))
    eom = sp.ImmutableMatrix(
        [sp.Add(*[h_r[i, k] * qdd_i[k] for k in range(len(ind))], c_r[i], g_r[i], -q_r[i]) for i in range(len(ind))]
    )

    lam = tuple(multiplier_symbol(k + 1) for k in range(m))
    a = ck.jacobian
    forces = sp.ImmutableMatrix((a.T * sp.Matrix(lam)).applyfunc(tidy))
    a_d = a.extract(list(range(m)), list(dep))
    # lambda from the dependent coordinates' equations, in the accelerations
    residual = h * sp.Matrix(qdd) + c_vec + g_vec - q_vec
    # Cramer's rule with the kinematics' simplified det A_d (= det A_d^T), not an LU's nested fractions
    in_acc = (a_d.T.adjugate() * sp.Matrix([residual[j] for j in dep])) / ck.determinant
    in_acc = tuple(_simplify(along(e)) for e in in_acc)
    accelerations: tuple[sp.Expr, ...] = ()
    values: tuple[sp.Expr, ...] = ()
    if len(ind) <= 2 and sp.count_ops(list(h_r) + list(c_r) + list(g_r) + list(q_r)) <= _CLOSED_FORM_OPS:
        sol = h_r.LUsolve(q_r - c_r - g_r)
        accelerations = tuple(_simplify(e) for e in sol)
        qdd_full = t_m * sp.Matrix(accelerations) + velocity_terms
        acc_map = dict(zip(qdd, qdd_full, strict=True))
        values = tuple(_simplify(e.xreplace(acc_map)) for e in in_acc)
        if sp.count_ops([*accelerations, *values]) > _SHOWN_OPS:  # a slider-crank's run to half a page
            accelerations, values = (), ()
    check = _agreement(system, ck, h, c_vec, g_vec, q_vec, eom, in_acc, t_m, velocity_terms)
    return ConstrainedDynamics(
        kinematics=ck,
        multipliers=lam,
        constraint_forces=forces,
        multipliers_in_accelerations=in_acc,
        multiplier_values=values,
        velocity_terms=velocity_terms,
        mass_matrix=h_r,
        coriolis_vector=c_r,
        gravity_vector=g_r,
        generalized_forces=q_r,
        equations_of_motion=eom,
        accelerations=accelerations,
        check=check,
    )


def _agreement(
    system: System,
    ck: ConstraintKinematics,
    h: sp.ImmutableMatrix,
    c_vec: sp.ImmutableMatrix,
    g_vec: sp.ImmutableMatrix,
    q_vec: sp.ImmutableMatrix,
    eom: sp.ImmutableMatrix,
    in_acc: tuple[sp.Expr, ...],
    t_m: sp.ImmutableMatrix,
    velocity_terms: sp.ImmutableMatrix,
) -> Check:
    """The multipliers' DAE, solved numerically at consistent states, against the reduced equations."""
    coords = system.coordinates
    q = [c.q for c in coords]
    qd = [c.qd for c in coords]
    qdd = [c.qdd for c in coords]
    n, m = len(q), len(system.constraints)
    ind = ck.independent
    a = ck.jacobian
    rng = random.Random(7)
    compiled: dict[sp.Expr, tuple[list[sp.Symbol], Any]] = {}
    checked = 0
    worst = mpmath.mpf(0)
    with mpmath.workdps(30):
        for state in consistent_states(system, ck.functions, ck.dependent, STATES):
            values = dict(state.values)
            for j in ind:
                values[qd[j]] = mpmath.mpf(rng.uniform(-1, 1))
            for v, e in ck.rates.items():
                values[v] = mpmath.mpf(sp.N(e.subs(values), 30))

            def num(e: sp.Expr, values: dict[sp.Symbol, mpmath.mpf] = values) -> mpmath.mpf:
                if e not in compiled:  # each expression compiled once, evaluated at every state
                    args = sorted(sp.sympify(e).free_symbols, key=sp.default_sort_key)
                    compiled[e] = (args, sp.lambdify(args, e, modules="mpmath"))
                args, f = compiled[e]
                return mpmath.mpf(f(*[values[x] for x in args]))

            block = mpmath.zeros(n + m, n + m)
            rhs = mpmath.zeros(n + m, 1)
            for i in range(n):
                for j in range(n):
                    block[i, j] = num(h[i, j])
                for k in range(m):
                    block[i, n + k] = -num(a[k, i])
                rhs[i] = num(q_vec[i] - c_vec[i] - g_vec[i])
            for k in range(m):
                for j in range(n):
                    block[n + k, j] = num(a[k, j])
                rhs[n + k] = -num(ck.bias[k])
            try:
                x = mpmath.lu_solve(block, rhs)
            except ZeroDivisionError:
                continue
            # the reduced route: its equations at the DAE's q_ddot_i, and lambda from the dependent rows
            acc = {qdd[j]: x[j] for j in range(n)}
            values_acc = {**values, **acc}
            scale = 1 + max(abs(x[i]) for i in range(n + m))
            for e in eom:
                worst = max(worst, abs(num(e, values_acc)) / scale)
            for k, e in enumerate(in_acc):
                worst = max(worst, abs(num(e, values_acc) - x[n + k]) / scale)
            # the dependent accelerations of q_ddot = T q_ddot_i + T_dot q_dot_i
            for j in range(n):
                predicted = sum((t_m[j, k] * qdd[ind[k]] for k in range(len(ind))), sp.Integer(0)) + velocity_terms[j]
                worst = max(worst, abs(num(predicted, values_acc) - x[j]) / scale)
            checked += 1
    if checked == 0:
        return Check("multipliers_equal_reduction", True, "not checked: no consistent state was found")
    if worst > _TOLERANCE:
        raise DerivationError(
            "internal check failed: the reduced equations and Lagrange's multipliers disagree "
            f"(relative difference {mpmath.nstr(worst, 3)}); please report this spec as a tutgen bug",
            system.constraints[0].origin,
        )
    return Check(
        "multipliers_equal_reduction",
        True,
        f"the reduced equations and Lagrange's multipliers give the same accelerations and multipliers at "
        f"{checked} consistent states",
    )
