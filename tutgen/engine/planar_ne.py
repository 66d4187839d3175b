"""Newton–Euler as it is taught, for planar systems: per body a free-body diagram with every force on
it, three scalar balances, the reactions eliminated equation by equation, and the reactions solved last.

Planar means every motion is in the x-y plane: each revolute axis is along z, each prismatic axis lies in
the plane, every angular velocity is along z and every centre of mass stays in its plane, and every applied
force lies in the plane (couples about z). Then each body has three equations, ΣF_x = 0, ΣF_y = 0 and
ΣM = 0 (about its joint's point: the pivot of a revolute joint), and only those are written.

Conventions (as in tutgen.engine.newton_euler, whose motions and applied loads are read here):
- D'Alembert: each body is in equilibrium under its applied forces, its joint reactions, the inertial
  force -m a_G at G and the inertial couple -I_G alpha (the z component of -(I_G alpha + omega x I_G omega)).
- A joint's reaction is what the PARENT exerts on the CHILD; the parent receives its opposite. Revolute:
  a force (R_x, R_y) through the pivot. Prismatic: a force N along n = z x axis and a couple M. Fixed:
  R_x, R_y and M. Nothing along a joint's own motion is a reaction (the joints are frictionless).
- What the spec gives along a coordinate acts at that coordinate's joint, between the body the
  coordinate is measured from and the joint's child: a generalized force Q_i, the share -k e de/dq_i of
  a spring and -c e_dot de/dq_i of a damper given by an extension e, and -n^2 J_m q_ddot_i of a geared
  rotor. On the child it is a couple Q_i about z (revolute) or a force Q_i along the axis (prismatic);
  its reaction is on the parent, or on the ground when the angle is absolute (measured from the world).
- A constrained spec's reactions (tutgen.engine.newton_euler): a loop-closing pin's force is lambda on
  its parent and -lambda on its child, drawn at the pin on both; a constraint given as an expression acts
  along each coordinate as a drive does, (A^T lambda)_i at that coordinate's joint.
- Eliminating the reactions: the equation of q_i is the virtual work of the balances under a change
  of q_i alone. For a revolute joint that is the sum of the moments about its pivot of the bodies that
  turn with it, plus the moments of the forces of the bodies carried without turning (behind an
  absolute angle) about the pivot; for a prismatic joint the sum of the forces along its axis of the
  bodies beyond it. Reactions between those bodies cancel in the sum (third law), and the joint's own
  reaction does no work, so no reaction is left: that is checked, and the result compared with
  Lagrange's by the caller.
"""

from __future__ import annotations

import sympy as sp

from tutgen.engine.kinematics import Kinematics
from tutgen.engine.ne_types import (
    Contribution,
    EliminationStep,
    ForceKind,
    NEMethod,
    NewtonEuler,
    PlanarBalance,
    PlanarForce,
    PlanarNewtonEuler,
    PlanarReaction,
    group_rates,
)
from tutgen.engine.tidy import is_zero, tidy
from tutgen.limits import checkpoint
from tutgen.model.system import GROUND, Joint, JointKind, System

Pair = tuple[sp.Expr, sp.Expr]
_ZERO = sp.Integer(0)


def reaction_symbol(letter: str, joint: str, component: str) -> sp.Symbol:
    """``R[pivot].x``, ``R[slider].n``, ``M[slider]``: names no spec identifier can take."""
    return sp.Symbol(f"{letter}[{joint}].{component}" if component else f"{letter}[{joint}]")


def is_planar(system: System, ne: NewtonEuler) -> bool:
    """True when every motion and every applied force of a jointed system lies in the x-y plane, and
    every coordinate drives exactly one joint (so each has a joint to act at)."""
    if ne.method is NEMethod.PROJECTION or not ne.bodies:
        return False
    driving = [j.coordinate.name for j in system.joints if j.coordinate is not None]
    if sorted(driving) != sorted(c.name for c in system.coordinates):
        return False
    if system.gravity is not None and not _zero(system.gravity[2]):
        return False
    for r in ne.reactions:
        axis = r.axis
        if r.kind is JointKind.REVOLUTE and not (_zero(axis[0]) and _zero(axis[1])):
            return False
        if r.kind is JointKind.PRISMATIC and not _zero(axis[2]):
            return False
    for m in ne.motions:
        w, al, a = m.angular_velocity, m.angular_acceleration, m.acceleration
        if not all(_zero(e) for e in (w[0], w[1], al[0], al[1], a[2])):
            return False
    for b in ne.bodies:
        for ld in b.loads:
            if not all(_zero(e) for e in (ld.force[2], ld.torque[0], ld.torque[1])):
                return False
    return True


def _tidy_coefficient(c: sp.Expr) -> sp.Expr:
    """``tidy``, and a fraction over the parameters (a composite body's I_G holds 1/(m_a + m_b)) put
    over one denominator when that is shorter."""
    t = tidy(c)
    if not any(p.exp.is_negative and p.base.free_symbols for p in t.atoms(sp.Pow)):
        return t
    return min((t, sp.factor_terms(sp.cancel(t))), key=sp.count_ops)


def _zero(e: sp.Expr) -> bool:
    return sp.expand(e) == 0


def _cross_z(r: Pair, f: Pair) -> sp.Expr:
    """The z component of r x f for plane vectors."""
    return r[0] * f[1] - r[1] * f[0]


def _pair(v: sp.MatrixBase) -> Pair:
    return (v[0], v[1])


def _sub(a: Pair, b: Pair) -> Pair:
    return (a[0] - b[0], a[1] - b[1])


def _quoted(name: str) -> str | None:
    """The spec name quoted in an engine name: "load 'push'" -> "push"."""
    return name.split("'")[1] if name.count("'") >= 2 else None


def _load_kind(name: str) -> ForceKind:
    if name == "gravity":
        return ForceKind.GRAVITY
    if name.startswith("reaction of load"):
        return ForceKind.LOAD_REACTION
    if name.startswith("spring"):
        return ForceKind.SPRING
    if name.startswith("damper"):
        return ForceKind.DAMPER
    return ForceKind.LOAD


class _Planar:
    def __init__(self, system: System, kin: Kinematics, ne: NewtonEuler) -> None:
        self.system = system
        self.kin = kin
        self.ne = ne
        self.rates = [*(c.qdd for c in system.coordinates), *(c.qd for c in system.coordinates)]
        self.rates += [x for cr in ne.constraint_reactions for x in cr.multipliers]  # grouped as in ne
        self.joints = {j.name: j for j in system.joints}
        self.reactions = {r.joint: r for r in ne.reactions}  # the recursive route's: axes and points
        self.order = [self.joints[r.joint] for r in ne.reactions]  # parents before children
        self.by_child = {j.child: j for j in system.joints}
        self.children: dict[str, list[Joint]] = {}
        for j in system.joints:
            self.children.setdefault(j.parent, []).append(j)
        self.balances = {b.body: b for b in ne.bodies}
        self.tidied: dict[sp.Expr, sp.Expr] = {}

    def tidy(self, e: sp.Expr) -> sp.Expr:
        return group_rates(e, self.rates, self.coefficient)

    def coefficient(self, c: sp.Expr) -> sp.Expr:
        """A coefficient tidied once: the same ones recur in a body's balances, in the equations and in
        the reactions (tidy's search is where the time of this route goes)."""
        if c not in self.tidied:
            self.tidied[c] = _tidy_coefficient(c)
        return self.tidied[c]

    def point(self, joint: str) -> Pair:
        return _pair(self.reactions[joint].point)

    def axis(self, joint: str) -> Pair:
        return _pair(self.reactions[joint].axis)

    # -- the free-body diagrams ------------------------------------------------------------
    def unknowns(self, joint: Joint) -> tuple[sp.Symbol, ...]:
        name = joint.name
        if joint.kind is JointKind.REVOLUTE:
            return (reaction_symbol("R", name, "x"), reaction_symbol("R", name, "y"))
        if joint.kind is JointKind.PRISMATIC:
            return (reaction_symbol("R", name, "n"), reaction_symbol("M", name, ""))
        return (reaction_symbol("R", name, "x"), reaction_symbol("R", name, "y"), reaction_symbol("M", name, ""))

    def reaction_on_child(self, joint: Joint) -> tuple[Pair, sp.Expr]:
        """The reaction's force and couple on the child, in its unknowns."""
        u = self.unknowns(joint)
        if joint.kind is JointKind.REVOLUTE:
            return (u[0], u[1]), _ZERO
        if joint.kind is JointKind.PRISMATIC:
            nx, ny = self.normal(joint.name)
            return (u[0] * nx, u[0] * ny), u[1]
        return (u[0], u[1]), u[2]

    def normal(self, joint: str) -> Pair:
        """n = z x axis: the direction of a prismatic joint's normal reaction."""
        ax, ay = self.axis(joint)
        return (sp.expand(-ay), sp.expand(ax))

    def drives(self) -> list[tuple[Joint, str, ForceKind, str | None, sp.Expr]]:
        """What the spec gives along each coordinate, element by element: (joint, name, kind, source, Q)."""
        system = self.system
        joint_of = {j.coordinate.name: j for j in system.joints if j.coordinate is not None}
        q = [c.q for c in system.coordinates]
        qd = [c.qd for c in system.coordinates]
        out: list[tuple[Joint, str, ForceKind, str | None, sp.Expr]] = []
        for name, value in system.generalized_forces:
            out.append((joint_of[name], f"generalized force at '{name}'", ForceKind.DRIVE, name, value))
        for s in system.springs:
            if s.extension is not None:
                for c, qi in zip(system.coordinates, q, strict=True):
                    share = -s.stiffness * s.extension * sp.diff(s.extension, qi)
                    if not _zero(share):
                        out.append((joint_of[c.name], f"spring '{s.name}'", ForceKind.SPRING, s.name, share))
        for d in system.dampers:
            if d.extension is not None:
                rate = sp.Add(*(sp.diff(d.extension, qj) * qdj for qj, qdj in zip(q, qd, strict=True)))
                for c, qi in zip(system.coordinates, q, strict=True):
                    share = -d.coefficient * rate * sp.diff(d.extension, qi)
                    if not _zero(share):
                        out.append((joint_of[c.name], f"damper '{d.name}'", ForceKind.DAMPER, d.name, share))
        for j in system.joints:
            if j.reflected_inertia is not None and j.coordinate is not None:
                share = -j.reflected_inertia * j.coordinate.qdd
                out.append((j, f"rotor of the motor at joint '{j.name}'", ForceKind.ROTOR, j.name, share))
        for cr in self.ne.constraint_reactions:  # a constraint given as an expression: (A^T lambda)_i
            if cr.kind == "generalized":
                for c, share in zip(system.coordinates, cr.generalized_force, strict=True):
                    if not _zero(share):
                        out.append(
                            (joint_of[c.name], f"force of constraint '{cr.name}'", ForceKind.CONSTRAINT, cr.name, share)
                        )
        return out

    def diagrams(self) -> dict[str, list[PlanarForce]]:
        """Every force on every moving body, in spec order of the bodies: gravity and loads (as the
        recursive route found them), what acts along the coordinates, the joint reactions, and
        D'Alembert's inertial force and couple."""
        forces: dict[str, list[PlanarForce]] = {b: [] for b in self.balances}

        def add(body: str, force: PlanarForce) -> None:
            if body in forces:  # the ground's share is not drawn
                forces[body].append(force)

        pins = {cr.name: cr for cr in self.ne.constraint_reactions if cr.kind == "pin"}
        for body, bal in self.balances.items():
            for ld in bal.loads:
                kind, source = _load_kind(ld.name), _quoted(ld.name)
                if ld.name.startswith("reaction at joint") and source in pins:  # a loop-closing pin's force
                    on_parent = body == pins[source].parent
                    kind = ForceKind.LOOP_REACTION_ON_PARENT if on_parent else ForceKind.LOOP_REACTION
                add(body, PlanarForce(ld.name, kind, source, _pair(ld.point), _pair(ld.force), ld.torque[2]))
        for joint, name, kind, source, value in self.drives():
            o = self.point(joint.name)
            if joint.kind is JointKind.PRISMATIC:
                ax, ay = self.axis(joint.name)
                on_child: tuple[Pair, sp.Expr] = ((value * ax, value * ay), _ZERO)
            else:
                on_child = ((_ZERO, _ZERO), value)
            reacting = GROUND if joint.kind is JointKind.REVOLUTE and joint.absolute else joint.parent
            (fx, fy), t = on_child
            child_kind = kind
            back_kind = ForceKind.DRIVE_REACTION if kind is ForceKind.DRIVE else kind
            add(joint.child, PlanarForce(name, child_kind, source, o, (fx, fy), t))
            back = name if kind is not ForceKind.DRIVE else f"reaction of the generalized force at '{source}'"
            add(reacting, PlanarForce(back, back_kind, source, o, (-fx, -fy), -t))
        for joint in self.order:
            (fx, fy), t = self.reaction_on_child(joint)
            o = self.point(joint.name)
            name = f"reaction at joint '{joint.name}'"
            add(joint.child, PlanarForce(name, ForceKind.REACTION, joint.name, o, (fx, fy), t))
            add(joint.parent, PlanarForce(name, ForceKind.REACTION_ON_PARENT, joint.name, o, (-fx, -fy), -t))
        for body, bal in self.balances.items():
            com = _pair(self.kin.bodies[body].com)
            f = _pair(bal.inertial_force)
            if not (_zero(f[0]) and _zero(f[1])):
                add(body, PlanarForce("inertial force", ForceKind.INERTIAL_FORCE, None, com, f, _ZERO))
            if not _zero(bal.inertial_moment[2]):
                couple = bal.inertial_moment[2]
                add(body, PlanarForce("inertial couple", ForceKind.INERTIAL_COUPLE, None, com, (_ZERO, _ZERO), couple))
        return forces

    # -- the balances --------------------------------------------------------------------
    @staticmethod
    def sums(forces: list[PlanarForce], about: Pair) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
        fx = sp.Add(*(f.force[0] for f in forces))
        fy = sp.Add(*(f.force[1] for f in forces))
        m = sp.Add(*(_cross_z(_sub(f.point, about), f.force) + f.torque for f in forces))
        return fx, fy, m

    def balance(self, body: str, forces: list[PlanarForce]) -> PlanarBalance:
        joint = self.by_child[body]
        about = self.point(joint.name)
        fx, fy, m = self.sums(forces, about)
        words = f"the pivot, joint '{joint.name}'" if joint.kind is JointKind.REVOLUTE else f"joint '{joint.name}'"
        return PlanarBalance(
            body=body,
            about=words,
            joint=joint.name,
            point=(self.tidy(about[0]), self.tidy(about[1])),
            forces=tuple(forces),
            sum_fx=self.tidy(fx),
            sum_fy=self.tidy(fy),
            sum_m=self.tidy(m),
        )

    # -- elimination ---------------------------------------------------------------------
    def subtree(self, joint: Joint) -> list[str]:
        out = [joint.child]
        for c in self.children.get(joint.child, []):
            out += self.subtree(c)
        return out

    def carried(self, joint: Joint) -> dict[str, Joint]:
        """The bodies beyond ``joint`` behind an absolute angle: they do not turn when its angle changes,
        only move with the absolute joint's point (body -> that joint)."""
        out: dict[str, Joint] = {}
        stack = list(self.children.get(joint.child, []))
        while stack:
            j = stack.pop(0)
            if j.kind is JointKind.REVOLUTE and j.absolute:
                out.update({b: j for b in self.subtree(j)})
            else:
                stack.extend(self.children.get(j.child, []))
        return out

    def step(self, joint: Joint, raw: dict[str, tuple[sp.Expr, sp.Expr, sp.Expr]], unknowns: set) -> EliminationStep:
        assert joint.coordinate is not None
        o = self.point(joint.name)
        carried = self.carried(joint) if joint.kind is JointKind.REVOLUTE else {}
        contributions = []
        for body in self.subtree(joint):
            fx, fy, m_own = raw[body]
            if joint.kind is JointKind.PRISMATIC:
                ax, ay = self.axis(joint.name)
                contributions.append(Contribution(body, "force", None, ax * fx + ay * fy))
            elif body in carried:
                k = carried[body]
                lever = _sub(self.point(k.name), o)
                contributions.append(Contribution(body, "force_moment", k.name, _cross_z(lever, (fx, fy))))
            else:  # its moments about its own joint's point, moved to this pivot
                lever = _sub(self.point(self.by_child[body].name), o)
                contributions.append(Contribution(body, "moment", None, m_own + _cross_z(lever, (fx, fy))))
        shaped = [Contribution(c.body, c.kind, c.via, self.tidy(c.expr)) for c in contributions]
        total = sp.expand(sp.Add(*(c.expr for c in shaped)))  # the tidied terms: cheaper to tidy again
        present = set().union(*(c.expr.free_symbols for c in contributions)) & unknowns
        left = total.free_symbols & unknowns
        if left:  # a reaction that does work in this virtual motion: not a case this route knows
            raise _Unsupported(f"reactions {sorted(map(str, left))} left in the equation of {joint.coordinate.name}")
        result = self.tidy(total)
        return EliminationStep(
            coordinate=joint.coordinate.name,
            joint=joint.name,
            contributions=tuple(shaped),
            eliminated=tuple(sorted(present, key=sp.default_sort_key)),
            result=result,
            equation=-result,
        )

    def solve_reactions(self, raw: dict[str, tuple[sp.Expr, sp.Expr, sp.Expr]]) -> list[PlanarReaction]:
        """Tips inward: each joint's unknowns from its child's balances, the children's reactions
        already substituted. Each unknown enters its balance with a unit coefficient (n is a unit
        vector), so it is minus the rest of that balance."""
        solved: dict[sp.Symbol, sp.Expr] = {}
        out: dict[str, PlanarReaction] = {}
        for joint in reversed(self.order):
            checkpoint(f"Newton-Euler: reactions at joint '{joint.name}'")
            fx, fy, m = (sp.expand(e.xreplace(solved)) for e in raw[joint.child])
            u = self.unknowns(joint)
            if joint.kind is JointKind.PRISMATIC:
                nx, ny = self.normal(joint.name)
                along_n = sp.expand(nx * fx + ny * fy)
                values = (
                    self.tidy(-along_n.subs(u[0], 0) / tidy(nx**2 + ny**2)),
                    self.tidy(-m.subs(u[1], 0)),
                )
                force = (self.tidy(values[0] * nx), self.tidy(values[0] * ny))
                moment = values[1]
                words = "its force balance normal to the slide and its moment balance"
            else:
                values = (self.tidy(-fx.subs(u[0], 0)), self.tidy(-fy.subs(u[1], 0)))
                force = values
                moment = _ZERO
                words = "its force balances"
                if joint.kind is JointKind.FIXED:
                    values = (*values, self.tidy(-m.subs(u[2], 0)))
                    moment = values[2]
                    words = "its force and moment balances"
            solved.update(zip(u, values, strict=True))
            out[joint.name] = PlanarReaction(
                joint=joint.name,
                kind=joint.kind,
                parent=joint.parent,
                child=joint.child,
                point=self.point(joint.name),
                normal=self.normal(joint.name) if joint.kind is JointKind.PRISMATIC else None,
                unknowns=u,
                values=values,
                force=force,
                moment=moment,
                solved_from=f"from {words} of '{joint.child}'",
            )
        return [out[j.name] for j in self.order]

    def build(self) -> PlanarNewtonEuler:
        forces = self.diagrams()
        order = [b.name for b in self.system.bodies if b.name in forces]
        balances = []
        raw: dict[str, tuple[sp.Expr, sp.Expr, sp.Expr]] = {}
        for body in order:
            checkpoint(f"Newton-Euler: planar balance of body '{body}'")
            raw[body] = self.sums(forces[body], self.point(self.by_child[body].name))
            balances.append(self.balance(body, forces[body]))
        unknowns = {u for j in self.order for u in self.unknowns(j)}
        joint_of = {j.coordinate.name: j for j in self.order if j.coordinate is not None}
        steps_by_coord = {}
        for joint in reversed(self.order):  # tips first, as the tutorial eliminates
            if joint.coordinate is not None:
                checkpoint(f"Newton-Euler: equation of {joint.coordinate.name}")
                steps_by_coord[joint.coordinate.name] = self.step(joint, raw, unknowns)
        steps = [steps_by_coord[j.coordinate.name] for j in reversed(self.order) if j.coordinate is not None]
        eom = sp.ImmutableMatrix([steps_by_coord[c.name].equation for c in self.system.coordinates])
        assert set(joint_of) == set(steps_by_coord)
        return PlanarNewtonEuler(
            balances=tuple(balances),
            steps=tuple(steps),
            reactions=tuple(self.solve_reactions(raw)),
            equations_of_motion=eom,
        )


class _Unsupported(Exception):
    """A planar system this route cannot eliminate; the recursive form is shown instead."""


def planar_newton_euler(system: System, kin: Kinematics, ne: NewtonEuler) -> PlanarNewtonEuler | None:
    """The scalar, per-body Newton–Euler of a planar system, or None when the system is not planar.

    Parameters
    ==========
    system : the validated spec.
    kin : its kinematics (centres of mass).
    ne : the recursive (or per-body) Newton–Euler of the same system: its motions, its applied loads
        and its joint axes and points are read here; its equations are those these must equal.

    Returns
    =======
    A :class:`PlanarNewtonEuler`; its equations are checked against ``ne.equations_of_motion`` (which
    equal Lagrange's), and a difference raises :class:`tutgen.errors.AgreementError`.

    Examples
    ========
    >>> from tutgen.spec.validate import load_system_text
    >>> from tutgen.engine.pipeline import derive
    >>> pendulum = load_system_text('''
    ... tutgen: 1
    ... title: pendulum
    ... parameters: [m, l, g, tau]
    ... coordinates: [theta]
    ... gravity: [0, -g, 0]
    ... bodies: {bob: {mass: m, com: [0, -l, 0]}}
    ... joints: {pivot: {type: revolute, parent: ground, child: bob, axis: z, coordinate: theta}}
    ... generalized_forces: {theta: tau}
    ... ''')
    >>> planar = derive(pendulum).newton_euler.planar
    >>> [f.name for f in planar.balances[0].forces]
    ['gravity', "generalized force at 'theta'", "reaction at joint 'pivot'", 'inertial force']
    >>> planar.balances[0].sum_m
    -g*l*m*sin(theta) - l**2*m*theta_ddot + tau
    >>> for value in planar.reactions[0].values:  # R_x, R_y: what the pivot exerts on the bob
    ...     print(value)
    l*m*theta_ddot*cos(theta) - l*m*theta_dot**2*sin(theta)
    g*m + l*m*theta_ddot*sin(theta) + l*m*theta_dot**2*cos(theta)
    """
    from tutgen.errors import AgreementError

    if not is_planar(system, ne):
        return None
    try:
        planar = _Planar(system, kin, ne).build()
    except _Unsupported:
        return None
    for c, mine, theirs in zip(system.coordinates, planar.equations_of_motion, ne.equations_of_motion, strict=True):
        zero, _ = is_zero(mine - theirs)
        if not zero:
            raise AgreementError(
                f"internal check failed: the planar Newton-Euler equation for '{c.name}' differs from the recursive "
                f"one ({sp.sstr(mine)} = 0 against {sp.sstr(theirs)} = 0); please report this spec as a tutgen bug",
                c.origin,
                coordinate=c.name,
            )
    return planar
