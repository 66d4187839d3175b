"""Prescribed (driven) coordinates (issue 18, point 4): the equations of the free coordinates and the
force or torque that drives each prescribed one.

A coordinate with ``prescribed: f(t)`` (or ``rate: w``, f = q0 + w t) is not a degree of freedom: a
drive imposes q_p = f(t), q_p_dot = f'(t), q_p_ddot = f''(t). The route is the one a textbook takes:

1. derive every coordinate as free (the general route's H q_ddot + C + G = Q, unchanged);
2. substitute the prescribed motion into the rows of the free coordinates: these are Lagrange's
   equations of L(q_f, q_f_dot, t) = L with the motion substituted (the time derivative then includes
   the explicit dt-part, which is what the substitution gives). In matrix form
   H_f q_f_ddot + C_f + G_f + D_f = Q_f, where H_f, C_f (the free rates only), G_f and Q_f are the
   free rows and columns with q_p = f(t) (so they may depend on t), and D_f collects what the driven
   motion adds: sum_p H_fp q_p_ddot + the terms of C that hold a driven rate;
3. the row of a driven coordinate, evaluated along the motion, no longer decides q_p: it is the force
   the drive must add, Q_drive_p = (d/dt dL/dq_p_dot - dL/dq_p - Q_p) along q_p = f(t), with Q_p the
   spec's other generalized forces on q_p.

Checks: the matrix form of the free coordinates against the substituted rows (exact), against
Lagrange's equations of the substituted Lagrangian with d/dt = chain rule + d/dt explicit, and the drive
force against Newton-Euler's equation of the driven coordinate along the motion.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from tutgen.engine.derivation import Check, Derivation
from tutgen.engine.kinematics import total_derivative
from tutgen.engine.tidy import is_zero, tidy, tidy_rates
from tutgen.errors import DerivationError
from tutgen.model.system import TIME, Coordinate, JointKind, System

__all__ = ["DrivenCoordinate", "PrescribedMotion", "drive_kind", "prescribed_motion"]

#: the free accelerations are eliminated from a drive force (its value along the motion as a function of
#: the state) only for this many free coordinates, and the result kept only when this short
_SOLVE_FREE = 1
_ALONG_OPS = 150
#: the substituted Lagrangian's equations are compared only when the equations are this short
_CHECK_OPS = 4000


@dataclass(frozen=True)
class DrivenCoordinate:
    """One prescribed coordinate: its motion and the force that drives it (the module's conventions)."""

    coordinate: Coordinate
    index: int  # in ``system.coordinates``
    motion: sp.Expr  # q_p(t)
    rate: sp.Expr  # q_p_dot(t)
    acceleration: sp.Expr  # q_p_ddot(t)
    drive: sp.Expr  # Q_drive_p: the row of q_p along the motion (free accelerations, rates, coordinates, t)
    # the same with the free accelerations from the equations of motion (None when they do not appear, or
    # the result is too long)
    drive_along_motion: sp.Expr | None
    kind: str  # "torque", "force" or "generalized force" (drive_kind)

    @property
    def name(self) -> str:
        return self.coordinate.name


@dataclass(frozen=True)
class PrescribedMotion:
    """The free coordinates' equations H_f q_f_ddot + C_f + G_f + D_f = Q_f and the drive forces."""

    driven: tuple[DrivenCoordinate, ...]
    free: tuple[int, ...]  # indices of the free coordinates in ``system.coordinates``
    substitution: tuple[tuple[sp.Symbol, sp.Expr], ...]  # q_p, q_p_dot, q_p_ddot -> their functions of t
    mass_matrix: sp.ImmutableMatrix  # H_f
    coriolis_vector: sp.ImmutableMatrix  # C_f: the free rates only
    gravity_vector: sp.ImmutableMatrix  # G_f
    driving_vector: sp.ImmutableMatrix  # D_f: what the driven motion adds
    generalized_forces: sp.ImmutableMatrix  # Q_f
    equations_of_motion: sp.ImmutableMatrix  # H_f q_f_ddot + C_f + G_f + D_f - Q_f, each = 0
    is_time_dependent: bool  # t appears in the free coordinates' equations
    checks: tuple[Check, ...]


def drive_kind(system: System, c: Coordinate) -> str:
    """What drives the coordinate: "torque" (an angle: declared so, or a revolute joint's), "force" (a
    length, or a prismatic joint's) or "generalized force"."""
    kinds = {j.kind for j in system.joints if j.coordinate is not None and j.coordinate.name == c.name}
    if c.dimension == "angle" or (c.dimension is None and kinds == {JointKind.REVOLUTE}):
        return "torque"
    if c.dimension == "length" or (c.dimension is None and kinds == {JointKind.PRISMATIC}):
        return "force"
    return "generalized force"


def prescribed_motion(d: Derivation) -> PrescribedMotion:
    """The prescribed motion substituted into the equations of motion of every coordinate as free.

    Examples
    ========
    >>> from tutgen.spec.validate import load_system_text
    >>> from tutgen.engine.pipeline import derive
    >>> bead = load_system_text('''
    ... {tutgen: 1, title: bead, parameters: [m, w], coordinates: {r: {}, phi: {rate: w}},
    ...  bodies: {bead: {mass: m, position: ['r*cos(phi)', 'r*sin(phi)', 0]}}}
    ... ''')
    >>> pm = derive(bead).prescribed
    >>> pm.equations_of_motion[0], pm.driven[0].drive
    (-m*r*w**2 + m*r_ddot, 2*m*r*r_dot*w)
    """
    s = d.system
    h, c_vec, g_vec, q_vec, eom = (
        d.mass_matrix,
        d.coriolis_vector,
        d.gravity_vector,
        d.generalized_forces,
        d.equations_of_motion,
    )
    if h is None or c_vec is None or g_vec is None or q_vec is None or eom is None:
        raise ValueError("prescribed_motion needs the equations of motion of every coordinate")
    coords = s.coordinates
    free = tuple(i for i, c in enumerate(coords) if c.prescribed is None)
    drivenix = tuple(i for i, c in enumerate(coords) if c.prescribed is not None)
    sub: dict[sp.Symbol, sp.Expr] = {}
    for i in drivenix:
        f = coords[i].prescribed
        assert f is not None
        sub[coords[i].q] = f
        sub[coords[i].qd] = tidy(sp.diff(f, TIME))
        sub[coords[i].qdd] = tidy(sp.diff(f, TIME, 2))
    still = {coords[i].qd: sp.Integer(0) for i in drivenix}  # the driven rates held at zero: C_f
    qdf = [coords[i].qd for i in free]
    qddf = [coords[i].qdd for i in free]

    def along(e: sp.Expr) -> sp.Expr:
        return e.xreplace(sub)

    hf = sp.ImmutableMatrix([[tidy(along(h[i, j])) for j in free] for i in free])
    cf = sp.ImmutableMatrix([tidy_rates(along(c_vec[i].xreplace(still)), qdf) for i in free])
    df = sp.ImmutableMatrix(
        [
            tidy_rates(
                along(sp.Add(*[h[i, p] * coords[p].qdd for p in drivenix]) + c_vec[i] - c_vec[i].xreplace(still)),
                qdf,
            )
            for i in free
        ]
    )
    gf = sp.ImmutableMatrix([tidy(along(g_vec[i])) for i in free])
    qf_vec = sp.ImmutableMatrix([tidy(along(q_vec[i])) for i in free])
    n = len(free)
    eom_f = sp.ImmutableMatrix(
        [sp.Add(*[hf[a, b] * qddf[b] for b in range(n)], cf[a], gf[a], df[a], -qf_vec[a]) for a in range(n)]
    )
    for a, i in enumerate(free):
        if not is_zero(eom_f[a] - along(eom[i]))[0]:
            raise DerivationError(
                f"internal check failed: the equation of '{coords[i].name}' with the prescribed motion differs "
                "from its matrix form; please report this spec as a tutgen bug",
                coords[i].origin,
            )
    checks = [_reduced_lagrangian_check(d, sub, free, eom_f)]

    accelerations = _free_accelerations(hf, eom_f, qddf)
    driven = []
    for p in drivenix:
        drive = tidy_rates(along(eom[p]), [*qddf, *qdf])
        along_motion = None
        if accelerations is not None and drive.has(*qddf):
            solved = tidy_rates(drive.xreplace(accelerations), qdf)
            along_motion = solved if sp.count_ops(solved) <= _ALONG_OPS else None
        c = coords[p]
        kind = drive_kind(s, c)
        driven.append(DrivenCoordinate(c, p, sub[c.q], sub[c.qd], sub[c.qdd], drive, along_motion, kind))
    if d.newton_euler is not None:
        ne = d.newton_euler.equations_of_motion
        ok = all(is_zero(along(ne[x.index]) - x.drive)[0] for x in driven)
        names = ", ".join(x.name for x in driven)
        checks.append(
            Check(
                "drive_force_equals_newton_euler",
                ok,
                f"The drive on {names} from the Newton–Euler equation along the prescribed motion equals Lagrange's"
                if ok
                else f"The drive on {names} from the Newton–Euler equation DIFFERS from Lagrange's",
            )
        )
    for check in checks:
        if not check.passed:
            raise DerivationError(
                f"internal check failed: {check.detail}; please report this spec as a tutgen bug", s.origin
            )
    return PrescribedMotion(
        driven=tuple(driven),
        free=free,
        substitution=tuple(sub.items()),
        mass_matrix=hf,
        coriolis_vector=cf,
        gravity_vector=gf,
        driving_vector=df,
        generalized_forces=qf_vec,
        equations_of_motion=eom_f,
        is_time_dependent=any(e.has(TIME) for e in eom_f),
        checks=tuple(checks),
    )


def _reduced_lagrangian_check(
    d: Derivation, sub: dict[sp.Symbol, sp.Expr], free: tuple[int, ...], eom_f: sp.ImmutableMatrix
) -> Check:
    """Lagrange's equations of L(q_f, q_f_dot, t), the Lagrangian with the motion substituted, where d/dt
    is the chain rule over the free coordinates plus the explicit d/dt, against the free equations."""
    name = "prescribed_equals_reduced_lagrangian"
    lagrangian, q_vec = d.lagrangian, d.generalized_forces
    if lagrangian is None or q_vec is None or sp.count_ops(eom_f) > _CHECK_OPS:
        return Check(
            name, True, "The free coordinates' equations not compared with the substituted Lagrangian's: too long"
        )
    coords = d.system.coordinates
    q = [coords[i].q for i in free]
    qd = [coords[i].qd for i in free]
    qdd = [coords[i].qdd for i in free]
    reduced = lagrangian.xreplace(sub)
    ok = True
    for a, i in enumerate(free):
        momentum = sp.diff(reduced, qd[a])
        ddt = total_derivative(momentum, q, qd, qdd) + sp.diff(momentum, TIME)
        lhs = ddt - sp.diff(reduced, q[a]) - q_vec[i].xreplace(sub)
        ok = ok and is_zero(lhs - eom_f[a])[0]
    return Check(
        name,
        ok,
        "The free coordinates' equations equal Lagrange's equations of the Lagrangian with the motion substituted"
        if ok
        else "The free coordinates' equations DIFFER from Lagrange's equations of the substituted Lagrangian",
    )


def _free_accelerations(
    hf: sp.ImmutableMatrix, eom_f: sp.ImmutableMatrix, qddf: list[sp.Symbol]
) -> dict[sp.Symbol, sp.Expr] | None:
    """q_f_ddot from H_f q_f_ddot = -(the rest), for a few free coordinates; None if H_f is singular."""
    n = len(qddf)
    if n > _SOLVE_FREE or sp.count_ops(eom_f) > 4 * _ALONG_OPS:  # an arm's: long, and its solution longer
        return None
    rest = sp.ImmutableMatrix([-eom_f[a].xreplace({x: 0 for x in qddf}) for a in range(n)])
    det = tidy(hf.det(method="berkowitz"))
    if det == 0:
        return None
    solved = hf.LUsolve(rest)
    return {qddf[a]: solved[a] for a in range(n)}  # tidied in the drive it is substituted into
