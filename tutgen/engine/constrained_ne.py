"""A constrained spec's reactions in Newton-Euler (issue 21): what each constraint exerts, in its
multipliers, and the check of the Newton-Euler equations with the reduced route's multipliers.

Conventions (tutgen.engine.newton_euler applies the reactions):
- A loop-closing pin's loop-closure equations are gap = r_parent(parent_at) - r_child(child_at) = 0, one
  per world component that is not identically zero, with multipliers lambda_k (the order of
  ``system.constraints``: the loop-closure equations first). A^T lambda is then the generalized force of
  the force lambda = (lambda_x, lambda_y, lambda_z) applied at the parent's point and -lambda at the
  child's point: the pin's force on the parent is lambda, its reaction on the child -lambda.
- A constraint given as an expression names no force on a body: its share of A^T lambda, (A^T lambda)_i
  for its own row, enters the equation of each coordinate as a drive does.
"""

from __future__ import annotations

import random
from typing import Any

import mpmath
import sympy as sp

from tutgen.engine.constraints import ConstrainedDynamics, multiplier_symbol
from tutgen.engine.constraints.kinematics import consistent_states
from tutgen.engine.derivation import Check
from tutgen.engine.kinematics import Kinematics
from tutgen.engine.ne_types import ConstraintReaction, Vec
from tutgen.engine.tidy import tidy
from tutgen.errors import AgreementError
from tutgen.model.system import GROUND, System

__all__ = ["constraint_reactions", "reduction_agreement"]


def constraint_reactions(system: System, kin: Kinematics, cd: ConstrainedDynamics) -> tuple[ConstraintReaction, ...]:
    """The constraint reactions of a constrained spec (the module's conventions): each loop-closing pin's
    force, then each constraint given as an expression, in the order of ``system.constraints`` (the
    loop-closure equations first, named ``<joint>_x``, ...)."""
    a = cd.kinematics.jacobian
    names = [c.name for c in system.constraints]
    n = len(system.coordinates)

    def share(rows: list[int]) -> tuple[sp.Expr, ...]:
        return tuple(
            tidy(sp.Add(*(a[k, i] * multiplier_symbol(k + 1) for k in rows))) if rows else sp.Integer(0)
            for i in range(n)
        )

    def where(body: str, at: sp.MatrixBase) -> Vec:
        return Vec(sp.Matrix(at) if body == GROUND else kin.point(body, at))

    out: list[ConstraintReaction] = []
    pinned: set[int] = set()
    for joint in system.loop_joints:
        rows = [names.index(f"{joint.name}_{axis}") for axis in "xyz" if f"{joint.name}_{axis}" in names]
        pinned.update(rows)
        lam = Vec(
            [
                multiplier_symbol(names.index(f"{joint.name}_{x}") + 1) if f"{joint.name}_{x}" in names else 0
                for x in "xyz"
            ]
        )
        out.append(
            ConstraintReaction(
                name=joint.name,
                kind="pin",
                constraints=tuple(names[k] for k in rows),
                multipliers=tuple(multiplier_symbol(k + 1) for k in rows),
                generalized_force=share(rows),
                parent=joint.parent,
                child=joint.child,
                point=where(joint.parent, joint.parent_at),
                child_point=where(joint.child, joint.child_at),
                on_parent=lam,
                on_child=Vec(-lam),
            )
        )
    for k, c in enumerate(system.constraints):
        if k not in pinned:
            out.append(ConstraintReaction(c.name, "generalized", (c.name,), (multiplier_symbol(k + 1),), share([k])))
    return tuple(out)


#: consistent states at which Newton-Euler is checked with the reduced route's multipliers
_REDUCTION_STATES = 3
_REDUCTION_TOLERANCE = mpmath.mpf("1e-15")


def reduction_agreement(system: System, cd: ConstrainedDynamics, eom: sp.MatrixBase) -> Check:
    """Newton-Euler's equations, every row, at consistent states with the reduced route's accelerations
    (q_ddot_i solved from H_r q_ddot_i + C_r + G_r = Q_r, then q_ddot = T q_ddot_i + T_dot q_dot_i) and
    its multipliers (lambda = A_d^-T (H q_ddot + C + G - Q)_d): each must vanish. A residual is a bug."""
    ck = cd.kinematics
    coords = system.coordinates
    qd = [c.qd for c in coords]
    qdd = [c.qdd for c in coords]
    ind = ck.independent
    qdd_i = [qdd[j] for j in ind]
    rng = random.Random(11)
    compiled: dict[sp.Expr, tuple[list[sp.Symbol], Any]] = {}

    def num(e: sp.Expr, values: dict[sp.Symbol, mpmath.mpf]) -> mpmath.mpf:
        if e not in compiled:
            args = sorted(sp.sympify(e).free_symbols, key=sp.default_sort_key)
            compiled[e] = (args, sp.lambdify(args, e, modules="mpmath"))
        args, f = compiled[e]
        return mpmath.mpf(f(*[values[x] for x in args]))

    reduced = [sp.expand(e) for e in cd.equations_of_motion]
    h_r = [[r.coeff(x) for x in qdd_i] for r in reduced]
    rest = [r.xreplace(dict.fromkeys(qdd_i, 0)) for r in reduced]
    worst = mpmath.mpf(0)
    checked = 0
    with mpmath.workdps(30):
        for state in consistent_states(system, ck.functions, ck.dependent, _REDUCTION_STATES):
            values = dict(state.values)
            for j in ind:
                values[qd[j]] = mpmath.mpf(rng.uniform(-1, 1))
            for v, e in ck.rates.items():
                values[v] = mpmath.mpf(sp.N(e.subs(values), 30))
            hm = mpmath.matrix([[num(e, values) for e in row] for row in h_r])
            rhs = mpmath.matrix([-num(e, values) for e in rest])
            try:
                acc_i = mpmath.lu_solve(hm, rhs)
            except ZeroDivisionError:
                continue
            values.update({x: acc_i[k] for k, x in enumerate(qdd_i)})
            t = ck.velocity_map
            for j in range(len(coords)):
                values[qdd[j]] = sum((num(t[j, k], values) * acc_i[k] for k in range(len(ind))), mpmath.mpf(0)) + num(
                    cd.velocity_terms[j], values
                )
            lam = [num(e, values) for e in cd.multipliers_in_accelerations]
            values.update(dict(zip(cd.multipliers, lam, strict=True)))
            scale = 1 + max(abs(x) for x in [*acc_i, *lam])
            for e in eom:
                worst = max(worst, abs(num(e, values)) / scale)
            checked += 1
    if checked == 0:
        return Check("newton_euler_equals_reduction", True, "not checked: no consistent state was found")
    if worst > _REDUCTION_TOLERANCE:
        raise AgreementError(
            "internal check failed: the Newton-Euler equations with the constraint reactions do not hold at the "
            f"reduced route's accelerations and multipliers (relative residual {mpmath.nstr(worst, 3)}); please "
            "report this spec as a tutgen bug",
            system.constraints[0].origin,
        )
    return Check(
        "newton_euler_equals_reduction",
        True,
        "The Newton–Euler equations, every row, hold at the reduced equations' accelerations with the "
        f"multipliers solved from them, at {checked} consistent states",
    )
