"""Newton-Euler beside Lagrange: per-body balances, joint reactions, their elimination, and the proof
that the equations of motion are Lagrange's.

Conventions (the sign of every term below follows from them):
- Vectors are world components (3x1 matrices), as everywhere in the engine.
- D'Alembert: each body is in equilibrium under its applied forces, its joint reactions, the
  inertial force -m a_G (acting at G) and the inertial couple -(I_G alpha + omega x I_G omega).
- The reaction of joint j, (R_j, N_j), is the force and the moment (about the child frame's origin,
  which lies on a revolute axis) that the PARENT exerts on the CHILD through the joint. The child
  receives (R_j, N_j), the parent (-R_j, -N_j) (Newton's third law).
- Applied forces are real forces on bodies: gravity at G, loads at their points with the opposite
  force/torque on the reaction body, springs and dampers ``between`` two points along the line of
  the two points. What the spec gives along a coordinate -- ``generalized_forces``, and springs and
  dampers with an ``extension`` -- is not a force on one body: it enters as the generalized force
  Q_i = given value, -dU/dq_i or -dD/dq_dot_i at that coordinate's joint (the joint's drive).
- Eliminating the reactions: a virtual change of q_i alone turns (slides) everything beyond its
  joint about (along) the joint axis, and the other reactions do no work in it. So the equation of
  q_i is  z_j . N_j  (z_j . R_j for a prismatic joint)  =  Q_i. A body behind an absolute angle does
  not turn with q_i, it only translates: the moment of that subtree about its own joint is subtracted.
- Bodies placed by positions and orientations (no joints) have no named reactions: the D'Alembert
  forces are projected on the partial velocities (virtual work, Kane's method) instead.
- A constrained spec (issue 21) adds its constraint reactions, in its multipliers lambda. A loop-closing
  pin's loop-closure equations are gap = r_parent(parent_at) - r_child(child_at) = 0 (components x, y, z
  with multipliers lambda_k), so A^T lambda is the generalized force of the force lambda = (lambda_x,
  lambda_y, lambda_z) on the PARENT at its point and -lambda on the CHILD at its point: the pin's reaction
  in the convention above (parent on child) is -lambda. A constraint given as an expression names no force
  on a body: its generalized force (A^T lambda)_i enters the equation of q_i as a drive does. Each
  equation then reads (H q_ddot + C + G - Q - A^T lambda)_i = 0, compared with Lagrange's with
  multipliers row by row, and, with the reduced route's lambda and accelerations, at consistent states.

Each equation is put in Lagrange's contract, (H q_ddot + C + G - Q)_i = 0, and compared with it.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import sympy as sp

from tutgen.engine.derivation import Check, Derivation
from tutgen.engine.inertia import BodyInertia, body_inertia
from tutgen.engine.kinematics import Kinematics
from tutgen.engine.ne_types import (
    PROJECTION_REMARK,
    ZERO,
    AppliedLoad,
    BodyBalance,
    ConstraintReaction,
    CoordinateEquation,
    JointReaction,
    Motion,
    NEMethod,
    NewtonEuler,
    Vec,
    group_rates,
)
from tutgen.engine.tidy import is_zero, memoised, tidy, trig_reduce
from tutgen.errors import AgreementError, DerivationError
from tutgen.limits import checkpoint
from tutgen.model.system import GROUND, Joint, JointKind, System

if TYPE_CHECKING:  # the constrained and planar routes are imported when a spec takes them (start-up, issue 17)
    from tutgen.engine.constraints import ConstrainedDynamics

__all__ = [
    "PROJECTION_REMARK",
    "AppliedLoad",
    "BodyBalance",
    "ConstraintReaction",
    "CoordinateEquation",
    "JointReaction",
    "Motion",
    "NEMethod",
    "NewtonEuler",
    "derive_newton_euler",
]


def derive_newton_euler(
    system: System,
    derivation: Derivation,
    kinematics: Kinematics | None = None,
    planar: bool = True,
    constraints: ConstrainedDynamics | None = None,
) -> NewtonEuler:
    """Derive the equations of motion body by body with Newton-Euler, and prove they equal Lagrange's.

    Parameters
    ==========
    system : the validated spec; it must place bodies (not an ``energy:`` spec).
    derivation : Lagrange's derivation of the same system (its inertia and equations of motion).
    kinematics : the frames Lagrange's route built, reused; built again when omitted.
    planar : also build the scalar form of a planar system (:mod:`tutgen.engine.planar_ne`), which
        costs about a third more; leave it out when Newton–Euler is derived only for the agreement check.
    constraints : a constrained spec's two routes (``Derivation.constraints``), with ``system`` the system
        whose constraints include the loop-closure equations (``with_loop_closures``): the constraint
        reactions then enter the balances (the module's conventions), the equations are compared with
        Lagrange's with multipliers, and ``reduction`` checks them with the reduced route's lambda.

    Returns
    =======
    A :class:`NewtonEuler` with the per-body balances, the joint reactions, one equation per
    coordinate and the agreement check. Raises :class:`AgreementError` when the equations differ.

    Examples
    ========
    >>> from tutgen.spec.validate import load_system_text
    >>> from tutgen.engine.pipeline import derive
    >>> pendulum = load_system_text('''
    ... tutgen: 1
    ... title: pendulum
    ... parameters: [m, l, g]
    ... coordinates: [theta]
    ... gravity: [0, -g, 0]
    ... bodies: {bob: {mass: m, com: [0, -l, 0]}}
    ... joints: {pivot: {type: revolute, parent: ground, child: bob, axis: z, coordinate: theta}}
    ... ''')
    >>> ne = derive(pendulum).newton_euler
    >>> ne.method.value, ne.equations_of_motion[0], ne.agrees_with_lagrange
    ('recursive', g*l*m*sin(theta) + l**2*m*theta_ddot, True)
    >>> for component in ne.reactions[0].force:  # what the pivot exerts on the bob
    ...     print(component)
    l*m*theta_ddot*cos(theta) - l*m*theta_dot**2*sin(theta)
    g*m + l*m*theta_ddot*sin(theta) + l*m*theta_dot**2*cos(theta)
    0
    """
    if system.kinetic_energy is not None or not system.bodies or not system.coordinates:
        raise DerivationError("Newton-Euler needs bodies and coordinates (not a given kinetic energy)", system.origin)
    if derivation.equations_of_motion is None:
        raise DerivationError("Newton-Euler is checked against Lagrange's equations, which are missing", system.origin)
    inertia = {bi.name: bi for bi in (derivation.inertia or tuple(body_inertia(b) for b in system.bodies))}
    kin = kinematics or Kinematics(system, {name: bi.com for name, bi in inertia.items()})
    rates = [*(c.qdd for c in system.coordinates), *(c.qd for c in system.coordinates)]
    # a constrained spec's multipliers are grouped like the rates: each coefficient is tidied on its own
    rates += list(constraints.multipliers) if constraints is not None else []
    builder = _Builder(system, kin, inertia, rates, constraints)
    lagrange = derivation.equations_of_motion
    if constraints is not None:  # Lagrange's with multipliers: (H q_ddot + C + G - Q)_i = (A^T lambda)_i
        lagrange = sp.ImmutableMatrix(sp.Matrix(lagrange) - sp.Matrix(constraints.constraint_forces))
    ne = builder.build(lagrange)
    if constraints is not None:
        checkpoint("Newton-Euler: with the reduced route's multipliers")
        from tutgen.engine.constrained_ne import reduction_agreement

        ne = dataclasses.replace(ne, reduction=reduction_agreement(system, constraints, ne.equations_of_motion))
    if not planar:
        return ne
    checkpoint("Newton-Euler: the planar form")
    from tutgen.engine.planar_ne import planar_newton_euler

    return dataclasses.replace(ne, planar=planar_newton_euler(system, kin, ne))


# ---------------------------------------------------------------------------------------------


def _dot(a: sp.MatrixBase, b: sp.MatrixBase) -> sp.Expr:
    return (sp.Matrix(a).T * sp.Matrix(b))[0]


@memoised
def _shorter_reduction(e: sp.Expr) -> sp.Expr:
    """The shortest of: as is, its trigonometric reduction, and (for a short coefficient) ``tidy``'s
    forms, which combine products into sums of angles (cos t1 cos t2 + sin t1 sin t2 = cos(t1 - t2))."""
    terms = sp.Add.make_args(e)
    if not e.has(sp.sin, sp.cos) or len(terms) > _LONG:
        return e
    forms = [e]
    reduced = trig_reduce(e)
    if reduced != e:
        forms.append(reduced)
    if 2 <= len(terms) <= 4 and all(_trig_degree(t) <= 2 for t in terms):  # cheap there; costly in 3-D products
        forms.append(tidy(e))
    return min(forms, key=_size) if len(forms) > 1 else e


_EXPAND_NODES = 1200  # nodes of a reaction's unexpanded form beyond which it stays unexpanded
_LONG = 60  # terms beyond which a coefficient is left as expanded (3-D chains: the search costs seconds)


def _size(e: sp.Basic, limit: int = 10**9) -> int:
    """The number of nodes of an expression tree, counted up to ``limit`` (cheaper than count_ops)."""
    n = 0
    for _ in sp.preorder_traversal(e):
        n += 1
        if n > limit:
            break
    return n


def _trig_degree(term: sp.Expr) -> int:
    """How many sines and cosines a product holds, powers counted (sin(a)**2 cos(b) -> 3)."""
    degree = 0
    for factor, power in term.as_powers_dict().items():
        if isinstance(factor, (sp.sin, sp.cos)):
            degree += int(power) if power.is_Integer else 99
    return degree


def _unknowns(letter: str, joint: str) -> Vec:
    """R[joint].x ...: names no spec identifier can take, so they never clash with a parameter."""
    return Vec([sp.Symbol(f"{letter}[{joint}].{c}") for c in "xyz"])


class _Builder:
    def __init__(
        self,
        system: System,
        kin: Kinematics,
        inertia: dict[str, BodyInertia],
        rates: list[sp.Symbol],
        constraints: ConstrainedDynamics | None = None,
    ) -> None:
        self.system = system
        self.constraint_reactions: tuple[ConstraintReaction, ...] = ()
        if constraints:
            from tutgen.engine.constrained_ne import constraint_reactions

            self.constraint_reactions = constraint_reactions(system, kin, constraints)
        self.kin = kin
        self.inertia = inertia
        self.rates = rates
        self.qd = sp.Matrix([c.qd for c in system.coordinates])
        self.by_child = {j.child: j for j in system.joints}
        self.children: dict[str, list[Joint]] = {}
        for j in system.joints:
            self.children.setdefault(j.parent, []).append(j)
        self.remarks: list[str] = []
        # per body: applied + inertial force, their moment about the body's joint origin, that origin
        self.known: dict[str, tuple[sp.Matrix, sp.Matrix, sp.Matrix]] = {}

    # -- tidying ---------------------------------------------------------------------------
    def tidy(self, e: sp.Expr) -> sp.Expr:
        """One equation in the form Lagrange's route prints (as ``tidy_rates``): grouped by q_ddot and
        q_dot monomials, each coefficient tidied."""
        return group_rates(e, self.rates, tidy)

    def light(self, e: sp.Expr) -> sp.Expr:
        """The cheaper tidy of the vectors (accelerations, reactions; large in 3-D): grouped by rate
        monomials, each coefficient as expanded or in its trigonometric reduction (sin^2 -> 1 - cos^2),
        the shorter. The kinematics already writes planar angles as sums (cos(t1 + t2)), so products
        need no search for combined angles; only the equations get the full ``tidy``."""
        return group_rates(e, self.rates, _shorter_reduction)

    def vec(self, v: sp.MatrixBase) -> Vec:
        return Vec(sp.Matrix(v).applyfunc(self.light))

    def shaped(self, v: sp.MatrixBase, reduce: bool = True) -> Vec:
        """A joint reaction for the reader: expanded and grouped by rates while it is small; in large
        3-D chains, left as the sum of the bodies' terms (cross products of tidy vectors), whose
        expansion would cost seconds and run to thousands of terms."""
        return Vec([self.shaped_entry(e, reduce) for e in v])

    def shaped_entry(self, e: sp.Expr, reduce: bool = True) -> sp.Expr:
        if _size(e, _EXPAND_NODES) > _EXPAND_NODES:
            return e
        return self.light(e) if reduce else group_rates(e, self.rates, lambda c: c)

    # -- the route -------------------------------------------------------------------------
    def method(self) -> NEMethod:
        """Named joint reactions when every moving body hangs from a joint and every coordinate drives
        one: a single chain of relative joints recurses, a tree (branches, absolute angles) is taken
        body by body. Otherwise (bodies placed by positions) the D'Alembert forces are projected."""
        kin = self.kin
        moving = [b.name for b in self.system.bodies if not kin.is_static(b.name)]
        driven = {j.coordinate.name for j in self.system.joints if j.coordinate is not None}
        if any(b not in self.by_child for b in moving) or any(c.name not in driven for c in self.system.coordinates):
            return NEMethod.PROJECTION
        roots = [j for j in self.system.joints if j.parent not in self.by_child]
        branching = len(roots) > 1 or any(len(js) > 1 for p, js in self.children.items() if p in self.by_child)
        absolute = any(j.absolute for j in self.system.joints)
        return NEMethod.PER_BODY if branching or absolute else NEMethod.RECURSIVE

    def order(self) -> list[Joint]:
        """The joints, parents before children (depth first, in spec order)."""
        out: list[Joint] = []

        def visit(body: str) -> None:
            for j in self.children.get(body, []):
                out.append(j)
                visit(j.child)

        for j in self.system.joints:
            if j.parent not in self.by_child:
                out.append(j)
                visit(j.child)
        return out

    def axis_of(self, joint: Joint) -> Vec:
        """The joint axis in world components, as the kinematics uses it."""
        parent = self.kin.frames[joint.parent]
        return Vec((parent.rotation * sp.Matrix(joint.rotation) * sp.Matrix(joint.axis)).applyfunc(sp.expand))

    # -- motion ----------------------------------------------------------------------------
    def outward(self, joints: list[Joint]) -> dict[str, Motion]:
        """The outward recursion, link by link from the ground:
        revolute  omega_c = omega_p + z q_dot,  alpha_c = alpha_p + z q_ddot + omega_p x z q_dot
        (absolute angle: omega_c = z q_dot, alpha_c = z q_ddot);
        a_Oc = a_Op + alpha_p x r + omega_p x (omega_p x r)  (prismatic: + 2 omega_p x z q_dot + z q_ddot),
        with r from the parent's origin to the child's; a_G = a_Oc + alpha_c x rho + omega_c x (omega_c x rho)."""
        out: dict[str, Motion] = {}
        kin = self.kin
        for joint in joints:
            checkpoint(f"Newton-Euler: motion of body '{joint.child}'")
            p, c = joint.parent, joint.child
            if p in out:
                w_p, al_p = sp.Matrix(out[p].angular_velocity), sp.Matrix(out[p].angular_acceleration)
                a_p = sp.Matrix(out[p].origin_acceleration)
            else:  # the ground, or a body fixed in place
                w_p, al_p, a_p = sp.zeros(3, 1), sp.zeros(3, 1), sp.zeros(3, 1)
            z = sp.Matrix(self.axis_of(joint))
            qd, qdd = (joint.coordinate.qd, joint.coordinate.qdd) if joint.coordinate else (0, 0)
            r = kin.frames[c].position - kin.frames[p].position
            a_o = a_p + al_p.cross(r) + w_p.cross(w_p.cross(r))
            w, al = w_p, al_p
            if joint.kind is JointKind.REVOLUTE and joint.absolute:
                w, al = z * qd, z * qdd
            elif joint.kind is JointKind.REVOLUTE:
                w, al = w_p + z * qd, al_p + z * qdd + w_p.cross(z) * qd
            elif joint.kind is JointKind.PRISMATIC:
                a_o = a_o + 2 * w_p.cross(z) * qd + z * qdd
            w, al = self.vec(w), self.vec(al)
            a_o = Vec(a_o.applyfunc(sp.expand))  # passed on outward; only a_G is tidied for the reader
            rho = sp.Matrix(kin.bodies[c].com) - kin.frames[c].position
            w_m, al_m = sp.Matrix(w), sp.Matrix(al)
            a_g = self.vec(sp.Matrix(a_o) + al_m.cross(rho) + w_m.cross(w_m.cross(rho)))
            out[c] = Motion(c, w, al, a_o, a_g, f"joint '{joint.name}'")
        return out

    def differentiated(self) -> dict[str, Motion]:
        """omega = J_w q_dot and a_G, alpha by the chain rule, d/dt (J q_dot)."""
        out = {}
        for b in self.system.bodies:
            checkpoint(f"Newton-Euler: motion of body '{b.name}'")
            bk = self.kin.bodies[b.name]
            out[b.name] = Motion(
                b.name,
                Vec(bk.angular_velocity),
                self.vec(self.kin.angular_acceleration(b.name)),
                None,
                self.vec(self.kin.acceleration(b.name)),
                "d/dt of v_G and omega",
            )
        return out

    def inertial(self, body: str, motion: Motion) -> tuple[Vec, Vec]:
        """-m a_G and -(I_G alpha + omega x I_G omega), the latter computed in body axes."""
        bi = self.inertia[body]
        force = Vec(-bi.mass * sp.Matrix(motion.acceleration))  # a_G is tidy already: -m (...)
        j_g = sp.Matrix(bi.inertia_com)
        if j_g == sp.zeros(3, 3):
            return force, ZERO
        rot = sp.Matrix(self.kin.bodies[body].rotation)
        w_b = (rot.T * sp.Matrix(motion.angular_velocity)).applyfunc(self.light)
        al_b = (rot.T * sp.Matrix(motion.angular_acceleration)).applyfunc(self.light)
        m_b = (j_g * al_b + w_b.cross(j_g * w_b)).applyfunc(self.light)
        return force, self.vec(-(rot * m_b))

    # -- applied forces --------------------------------------------------------------------
    def applied(self) -> dict[str, list[AppliedLoad]]:
        """Every applied force and couple, on the body it acts on (the ground's share is dropped)."""
        system, kin = self.system, self.kin
        out: dict[str, list[AppliedLoad]] = {b.name: [] for b in system.bodies}

        def add(body: str, load: AppliedLoad) -> None:
            if body in out:
                out[body].append(load)

        if system.gravity is not None:
            g = sp.Matrix(system.gravity)
            for b in system.bodies:
                m = self.inertia[b.name].mass
                if m != 0:
                    add(b.name, AppliedLoad("gravity", Vec(m * g), Vec(kin.bodies[b.name].com), ZERO))
        for load in system.loads:
            rot = kin.frames[load.body].rotation if load.in_body_frame else sp.eye(3)
            where = Vec(kin.point(load.body, load.at))
            force = self.vec(rot * sp.Matrix(load.force)) if load.force is not None else ZERO
            torque = self.vec(rot * sp.Matrix(load.torque)) if load.torque is not None else ZERO
            add(load.body, AppliedLoad(f"load '{load.name}'", force, where, torque))
            if load.reaction_body is not None and load.reaction_body != GROUND:
                add(load.reaction_body, AppliedLoad(f"reaction of load '{load.name}'", -force, where, -torque))
        for spring in system.springs:
            if spring.between is None:
                continue
            a, b = spring.between
            pa, pb = kin.point(a.body, a.at), kin.point(b.body, b.at)
            d = self.vec(pa - pb)
            if spring.free_length == 0:
                on_a = self.vec(-spring.stiffness * d)
            else:  # -k (L - L0) d / L, the scalar factor kept apart from d
                length = sp.sqrt(self.light(_dot(d, d)))
                on_a = Vec(-spring.stiffness * (1 - spring.free_length / length) * d)
            add(a.body, AppliedLoad(f"spring '{spring.name}'", on_a, Vec(pa), ZERO))
            add(b.body, AppliedLoad(f"spring '{spring.name}'", Vec(-on_a), Vec(pb), ZERO))
        for damper in system.dampers:
            if damper.between is None:
                continue
            a, b = damper.between
            pa, pb = kin.point(a.body, a.at), kin.point(b.body, b.at)
            d = self.vec(pa - pb)
            d_dot = (kin.point_jacobian(a.body, pa) - kin.point_jacobian(b.body, pb)) * self.qd
            # -c L_dot d / L, with L_dot = d . d_dot / L; the scalar factor kept apart from d
            factor = -damper.coefficient * self.light(_dot(d, d_dot)) / self.light(_dot(d, d))
            on_a = Vec(factor * d)
            add(a.body, AppliedLoad(f"damper '{damper.name}'", on_a, Vec(pa), ZERO))
            add(b.body, AppliedLoad(f"damper '{damper.name}'", Vec(-on_a), Vec(pb), ZERO))
        for cr in self.constraint_reactions:  # a loop-closing pin: lambda on the parent, -lambda on the child
            if cr.kind == "pin":
                assert cr.parent and cr.child and cr.point is not None and cr.child_point is not None
                assert cr.on_parent is not None and cr.on_child is not None
                add(cr.parent, AppliedLoad(f"reaction at joint '{cr.name}'", cr.on_parent, cr.point, ZERO))
                add(cr.child, AppliedLoad(f"reaction at joint '{cr.name}'", cr.on_child, cr.child_point, ZERO))
        return out

    def along_coordinates(self) -> list[sp.Expr]:
        """Q_i of what the spec gives along a coordinate: the given generalized forces,
        -dU/dq_i of springs and -dD/dq_dot_i of dampers with an ``extension``."""
        system = self.system
        q = [c.q for c in system.coordinates]
        qd = [c.qd for c in system.coordinates]
        names = [c.name for c in system.coordinates]
        out = [sp.Integer(0)] * len(q)
        for name, value in system.generalized_forces:
            i = names.index(name)
            out[i] += value
        for spring in system.springs:
            if spring.extension is not None:
                energy = spring.stiffness * spring.extension**2 / 2  # as Lagrange's U
                out = [o - sp.diff(energy, qi) for o, qi in zip(out, q, strict=True)]
        for damper in system.dampers:
            if damper.extension is not None:
                rate = sum((sp.diff(damper.extension, qj) * qdj for qj, qdj in zip(q, qd, strict=True)), sp.Integer(0))
                dissipation = damper.coefficient * rate**2 / 2
                out = [o - sp.diff(dissipation, qdi) for o, qdi in zip(out, qd, strict=True)]
        # a constraint given as an expression: its generalized force (A^T lambda)_i, as a drive's
        for cr in self.constraint_reactions:
            if cr.kind == "generalized":
                out = [o + f for o, f in zip(out, cr.generalized_force, strict=True)]
        # a motor's rotor takes n^2 J_m q_ddot_i of the drive's effort to accelerate itself (its reflected
        # inertia): the link receives Q_i - n^2 J_m q_ddot_i through the joint (gyroscopic terms neglected)
        for joint in system.joints:
            reflected = joint.reflected_inertia
            if reflected is not None and joint.coordinate is not None:
                i = names.index(joint.coordinate.name)
                out[i] -= reflected * joint.coordinate.qdd
                self.remarks.append(
                    f"The rotor of the motor at joint '{joint.name}' is accelerated by part of the drive's effort: "
                    f"the link receives Q - n^2 J_m {joint.coordinate.name}_ddot through the joint (n^2 J_m = "
                    f"{f'{float(reflected):.6g}' if reflected.is_number else sp.sstr(reflected)})."
                )
        return [self.tidy(o) for o in out]

    # -- the derivation --------------------------------------------------------------------
    def build(self, lagrange_eom: sp.MatrixBase) -> NewtonEuler:
        method = self.method()
        q_along = self.along_coordinates()
        loads = self.applied()
        if method is NEMethod.PROJECTION:
            motions = self.differentiated()
            bodies, reactions = self.balances_free(motions, loads), ()
            equations = self.projected(motions, loads, q_along)
            self.remarks.append(PROJECTION_REMARK)
        else:
            joints = self.order()
            motions = self.outward(joints) if method is NEMethod.RECURSIVE else self.differentiated()
            bodies, reactions = self.balances_joints(joints, motions, loads)
            equations = self.eliminated(joints, reactions, q_along)
        if (
            self.system.generalized_forces
            or any(e.extension is not None for e in self.system.springs)
            or any(e.extension is not None for e in self.system.dampers)
        ):
            self.remarks.append(
                "The generalized forces given in the spec, and springs and dampers given by an extension, act along "
                "a coordinate rather than on one body: they enter as the generalized force Q_i (-dU/dq_i for a "
                "spring, -dD/dq_dot_i for a damper) at that coordinate's joint."
            )
        eom = sp.ImmutableMatrix([e.equation for e in equations])
        checkpoint("Newton-Euler: agreement with Lagrange")
        agreement = _agreement(self.system, eom, lagrange_eom, bool(self.constraint_reactions))
        order = [b.name for b in self.system.bodies]
        ne = NewtonEuler(
            method=method,
            motions=tuple(motions[b] for b in order if b in motions and not self.kin.is_static(b)),
            bodies=bodies,
            reactions=reactions,
            equations=equations,
            equations_of_motion=eom,
            agreement=agreement,
            remarks=tuple(self.remarks),
            constraint_reactions=self.constraint_reactions,
        )
        return ne

    def balances_joints(
        self, joints: list[Joint], motions: dict[str, Motion], loads: dict[str, list[AppliedLoad]]
    ) -> tuple[tuple[BodyBalance, ...], tuple[JointReaction, ...]]:
        """Each body's force and moment balance about its joint's origin, solved from the tips inward:
        R_j = sum of R_children - (applied + inertial forces),
        N_j = sum of (N_c + (O_c - O_j) x R_c) - (moments of applied and inertial forces about O_j)."""
        kin = self.kin
        solved: dict[str, tuple[Vec, Vec]] = {}
        balances: dict[str, BodyBalance] = {}
        for joint in reversed(joints):
            body = joint.child
            checkpoint(f"Newton-Euler: balance of body '{body}'")
            origin = sp.Matrix(kin.frames[body].position)
            motion = motions[body]
            inertial_force, inertial_moment = self.inertial(body, motion)
            com = sp.Matrix(kin.bodies[body].com)
            known_f = sp.Matrix(inertial_force)
            known_m = sp.Matrix(inertial_moment) + (com - origin).cross(sp.Matrix(inertial_force))
            for ld in loads[body]:
                known_f += ld.force
                known_m += (sp.Matrix(ld.point) - origin).cross(sp.Matrix(ld.force)) + sp.Matrix(ld.torque)
            out = self.children.get(body, [])
            force = -known_f
            moment = -known_m
            sym_f = sp.Matrix(_unknowns("R", joint.name)) + known_f
            sym_m = sp.Matrix(_unknowns("N", joint.name)) + known_m
            for c in out:
                r_c, n_c = solved[c.name]
                lever = sp.Matrix(kin.frames[c.child].position) - origin
                force += r_c
                moment += sp.Matrix(n_c) + lever.cross(sp.Matrix(r_c))
                u_f, u_m = sp.Matrix(_unknowns("R", c.name)), sp.Matrix(_unknowns("N", c.name))
                sym_f -= u_f
                sym_m -= u_m + lever.cross(u_f)
            solved[joint.name] = (Vec(force), Vec(moment))  # as summed; put in shape below
            self.known[body] = (known_f, known_m, origin)
            balances[body] = BodyBalance(
                body=body,
                mass=self.inertia[body].mass,
                about=f"the origin of joint '{joint.name}'",
                point=Vec(origin),
                loads=tuple(loads[body]),
                inertial_force=inertial_force,
                inertial_moment=inertial_moment,
                joint_in=joint.name,
                joints_out=tuple(c.name for c in out),
                force_balance=Vec(sym_f),  # as summed, not expanded: the reader sees the terms
                moment_balance=Vec(sym_m),
            )
        reactions = []
        for joint in joints:
            raw_force, raw_moment = solved[joint.name]
            z = self.axis_of(joint)
            along = None
            if joint.kind is JointKind.REVOLUTE:
                along = self.shaped_entry(_dot(z, raw_moment))
            elif joint.kind is JointKind.PRISMATIC:
                along = self.shaped_entry(_dot(z, raw_force))
            # a force is a sum of tidy terms (m a_G, loads): grouping is enough; a moment holds products
            # of lever arms and forces, whose trigonometric products need reducing
            force, moment = self.shaped(raw_force, reduce=False), self.shaped(raw_moment)
            reactions.append(
                JointReaction(
                    joint=joint.name,
                    kind=joint.kind,
                    parent=joint.parent,
                    child=joint.child,
                    coordinate=joint.coordinate.name if joint.coordinate else None,
                    axis=z,
                    point=Vec(kin.frames[joint.child].position),
                    force=force,
                    moment=moment,
                    unknown_force=_unknowns("R", joint.name),
                    unknown_moment=_unknowns("N", joint.name),
                    along_axis=along,
                )
            )
        order = [b.name for b in self.system.bodies if b.name in balances]
        return tuple(balances[b] for b in order), tuple(reactions)

    def balances_free(self, motions: dict[str, Motion], loads: dict[str, list[AppliedLoad]]) -> tuple[BodyBalance, ...]:
        """Without joints: each moving body's applied and inertial terms, moments about G (the
        unnamed constraint forces are left out; they drop from the projected equations)."""
        out = []
        for b in self.system.bodies:
            if self.kin.is_static(b.name):
                continue
            checkpoint(f"Newton-Euler: balance of body '{b.name}'")
            inertial_force, inertial_moment = self.inertial(b.name, motions[b.name])
            com = sp.Matrix(self.kin.bodies[b.name].com)
            f = sp.Matrix(inertial_force)
            m = sp.Matrix(inertial_moment)
            for ld in loads[b.name]:
                f += ld.force
                m += (sp.Matrix(ld.point) - com).cross(sp.Matrix(ld.force)) + sp.Matrix(ld.torque)
            out.append(
                BodyBalance(
                    body=b.name,
                    mass=self.inertia[b.name].mass,
                    about="G",
                    point=Vec(com),
                    loads=tuple(loads[b.name]),
                    inertial_force=inertial_force,
                    inertial_moment=inertial_moment,
                    joint_in=None,
                    joints_out=(),
                    force_balance=Vec(f),
                    moment_balance=Vec(m),
                )
            )
        return tuple(out)

    def eliminated(
        self, joints: list[Joint], reactions: tuple[JointReaction, ...], q_along: list[sp.Expr]
    ) -> tuple[CoordinateEquation, ...]:
        """z_j . N_j (revolute) or z_j . R_j (prismatic) = Q_i; behind an absolute angle k, the subtree
        only translates when q_i changes, so z_j . N_k is subtracted.

        N_j is the sum over the bodies beyond joint j of minus their applied and inertial moments
        about O_j, so the projection is taken body by body (each term tidied while it is small) and
        then summed: the same value as z_j . N_j, far cheaper to put in shape for 3-D chains."""
        by_name = {r.joint: r for r in reactions}
        joint_of = {j.coordinate.name: j for j in joints if j.coordinate is not None}
        out = []
        for i, coord in enumerate(self.system.coordinates):
            joint = joint_of[coord.name]
            z = sp.Matrix(by_name[joint.name].axis)
            origin = sp.Matrix(self.kin.frames[joint.child].position)
            behind = self.absolute_below(joint) if joint.kind is JointKind.REVOLUTE else []
            translated = {b: k for k in behind for b in self.subtree(k)}
            terms = []
            for body in self.subtree(joint):
                known_f, known_m, own_origin = self.known[body]
                if joint.kind is JointKind.PRISMATIC:
                    term = -_dot(z, known_f)
                elif body in translated:  # moves with O_k, without turning: only its force has a moment
                    o_k = sp.Matrix(self.kin.frames[translated[body].child].position)
                    term = -_dot(z, (o_k - origin).cross(known_f))
                else:
                    term = -_dot(z, known_m + (own_origin - origin).cross(known_f))
                terms.append((body, self.light(term)))
            projection = sp.Add(*(t for _, t in terms))
            subtracted = [k.name for k in behind]
            if subtracted:
                names = ", ".join(f"'{k}'" for k in subtracted)
                self.remarks.append(
                    f"Behind joint {names} the angle is absolute, so a change of {coord.name} alone moves that "
                    f"part without turning it: its moment about joint {names} is subtracted in the equation "
                    f"for {coord.name}."
                )
            out.append(
                CoordinateEquation(
                    coordinate=coord.name,
                    joint=joint.name,
                    subtracted=tuple(subtracted),
                    projection=self.shaped_entry(projection),
                    generalized_force=q_along[i],
                    equation=self.tidy(projection - q_along[i]),
                    terms=tuple(terms),
                )
            )
        return tuple(out)

    def subtree(self, joint: Joint) -> list[str]:
        """The bodies beyond a joint, its child first."""
        out = [joint.child]
        for c in self.children.get(joint.child, []):
            out += self.subtree(c)
        return out

    def absolute_below(self, joint: Joint) -> list[Joint]:
        """The first joints with an absolute angle beyond ``joint``, on every branch."""
        out: list[Joint] = []
        stack = list(self.children.get(joint.child, []))
        while stack:
            j = stack.pop(0)
            if j.kind is JointKind.REVOLUTE and j.absolute:
                out.append(j)
            else:
                stack.extend(self.children.get(j.child, []))
        return out

    def projected(
        self, motions: dict[str, Motion], loads: dict[str, list[AppliedLoad]], q_along: list[sp.Expr]
    ) -> tuple[CoordinateEquation, ...]:
        """sum over bodies of (m a_G - F) . dv/dq_dot_i + (I alpha + omega x I omega - M) . domega/dq_dot_i,
        each applied force taken with the partial velocity of its own point."""
        kin = self.kin
        n = len(self.system.coordinates)
        sums = [sp.Integer(0)] * n
        for b in self.system.bodies:
            if kin.is_static(b.name):
                continue
            checkpoint(f"Newton-Euler: equations, body '{b.name}'")
            bk = kin.bodies[b.name]
            inertial_force, inertial_moment = self.inertial(b.name, motions[b.name])
            jw = kin.frames[b.name].jw
            for i in range(n):
                sums[i] -= _dot(inertial_force, bk.jv[:, i]) + _dot(inertial_moment, jw[:, i])
            for ld in loads[b.name]:
                jac = kin.point_jacobian(b.name, ld.point) if any(e != 0 for e in ld.force) else None
                for i in range(n):
                    if jac is not None:
                        sums[i] -= _dot(ld.force, jac[:, i])
                    sums[i] -= _dot(ld.torque, jw[:, i])
        out = []
        for i, coord in enumerate(self.system.coordinates):
            projection = self.light(sums[i])
            out.append(
                CoordinateEquation(
                    coordinate=coord.name,
                    joint=None,
                    subtracted=(),
                    projection=projection,
                    generalized_force=q_along[i],
                    equation=self.tidy(projection - q_along[i]),
                )
            )
        return tuple(out)


def _agreement(system: System, eom: sp.MatrixBase, lagrange: sp.MatrixBase, constrained: bool = False) -> Check:
    """Each Newton-Euler equation minus Lagrange's must vanish: symbolically, or else numerically at
    random states. A difference is a bug, reported with the coordinate it is about. ``constrained``:
    ``lagrange`` is Lagrange's with multipliers, H q_ddot + C + G - Q - A^T lambda (an identity in q, q_dot,
    q_ddot and lambda, so any state will do)."""
    hows = []
    for i, coord in enumerate(system.coordinates):
        zero, how = is_zero(eom[i] - lagrange[i])
        if not zero:
            raise AgreementError(
                f"internal check failed: the Newton-Euler equation for '{coord.name}' differs from Lagrange's "
                f"(Newton-Euler: {sp.sstr(eom[i])} = 0; Lagrange: {sp.sstr(lagrange[i])} = 0); "
                "please report this spec as a tutgen bug",
                coord.origin,
                coordinate=coord.name,
            )
        hows.append(how)
    numeric = [c.name for c, h in zip(system.coordinates, hows, strict=True) if h.startswith("numerically")]
    detail = "The Newton–Euler equations agree with Lagrange's"
    if constrained:
        detail = (
            "The Newton–Euler equations, with the constraint reactions, agree with Lagrange's with multipliers, "
            "H q_ddot + C + G - Q = A^T lambda, row by row"
        )
    if numeric:
        detail += f" (symbolically, and numerically at random states for {', '.join(numeric)})"
    return Check("newton_euler_equals_lagrange", True, detail)
