"""Where every body is, and how fast it moves: positions, rotations and velocity Jacobians.

Velocities are linear in the coordinate rates, v = J_v(q) q_dot and omega = J_w(q) q_dot, so each
body carries its two Jacobians (3 x n, world components). Kinetic energy, generalized forces and
(later) Newton-Euler all read them, instead of differentiating positions again.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp

from tutgen.errors import DerivationError
from tutgen.model.system import GROUND, Body, Coordinate, Joint, JointKind, System

Vec = sp.ImmutableMatrix


def rotation_about(axis: sp.MatrixBase, angle: sp.Expr) -> sp.Matrix:
    """Rodrigues' formula for a unit axis: R = cos(a) E + sin(a) [axis]x + (1 - cos(a)) axis axis^T.

    Examples
    ========
    >>> import sympy as sp
    >>> t = sp.Symbol("t")
    >>> rotation_about(sp.Matrix([0, 0, 1]), t)
    Matrix([
    [cos(t), -sin(t), 0],
    [sin(t),  cos(t), 0],
    [     0,       0, 1]])
    """
    a = sp.Matrix(axis)
    c, s = sp.cos(angle), sp.sin(angle)
    skew = sp.Matrix([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    r = c * sp.eye(3) + s * skew + (1 - c) * (a * a.T)
    return r.applyfunc(sp.expand)


def total_derivative(
    expr: sp.Expr, q: Sequence[sp.Symbol], qd: Sequence[sp.Symbol], qdd: Sequence[sp.Symbol]
) -> sp.Expr:
    """The total time derivative by the chain rule: d/dt f(q, q_dot) = f_q q_dot + f_qdot q_ddot.

    Examples
    ========
    >>> import sympy as sp
    >>> x, xd, xdd = sp.symbols("x x_dot x_ddot")
    >>> total_derivative(x * xd**2, [x], [xd], [xdd])
    2*x*x_ddot*x_dot + x_dot**3
    """
    out = sp.Integer(0)
    for qi, qdi, qddi in zip(q, qd, qdd, strict=True):
        out += sp.diff(expr, qi) * qdi + sp.diff(expr, qdi) * qddi
    return out


@dataclass(frozen=True)
class Frame:
    """A body frame: origin position, rotation (world from body), and the Jacobians of the origin
    velocity and of the angular velocity. ``planar`` records (world axis, angle) while the frame has
    only turned about one fixed axis, so that sums of angles stay sums (cos(t1 + t2))."""

    position: sp.Matrix
    rotation: sp.Matrix
    jv: sp.Matrix
    jw: sp.Matrix
    planar: tuple[tuple[sp.Expr, ...], sp.Expr] | None


@dataclass(frozen=True)
class Identity:
    """A trigonometric identity as a step uses it: the general ``rule`` (ASCII, for the reader) and the
    instance, ``lhs = rhs`` with the step's own angles."""

    rule: str  # "sin(A)^2 + cos(A)^2 = 1", "cos(A) cos(B) + sin(A) sin(B) = cos(A - B)", ...
    lhs: sp.Expr
    rhs: sp.Expr


@dataclass(frozen=True)
class SpeedSquared:
    """v^2 = v . v worked as a teacher does: the squares of the velocity's components, expanded, and the
    identities that shorten it (``cos A cos B + sin A sin B = cos(A - B)`` in a two-link arm).

    ``result`` is the expansion with ``identities`` applied; it equals ``expanded`` for every q, so it is
    the body's v^2 (the energies' tidied ``speed_squared`` prints it in a teacher's order).
    """

    components: tuple[sp.Expr, ...]  # the velocity's components (world axes), x, y, z
    expanded: sp.Expr  # sum of their squares, multiplied out
    identities: tuple[Identity, ...]
    result: sp.Expr


#: velocities longer than this many operations are not worked through identity by identity (a spatial
#: arm's expansion would run to pages; the energies print v^2 directly)
SPEED_STEPS_BUDGET = 400

RULE_PYTHAGORAS = "sin(A)^2 + cos(A)^2 = 1"
RULE_COS_DIFFERENCE = "cos(A) cos(B) + sin(A) sin(B) = cos(A - B)"
RULE_SIN_DIFFERENCE = "sin(A) cos(B) - cos(A) sin(B) = sin(A - B)"


def speed_squared_steps(velocity: sp.MatrixBase) -> SpeedSquared | None:
    """v . v with the identities a teacher uses, or None when the velocity is too long to work through.

    The expansion is a polynomial in the sines and cosines of its angles; the identities are applied
    to the part of the coefficients their two products share: sin^2 A + cos^2 A = 1,
    cos A cos B + sin A sin B = cos(A - B) and sin A cos B - cos A sin B = sin(A - B).

    Examples
    ========
    >>> import sympy as sp
    >>> t1, t2, w1, w2 = sp.symbols("t1 t2 w1 w2")
    >>> w = w1 + w2
    >>> v = sp.Matrix([-sp.sin(t1) * w1 - sp.sin(t1 + t2) * w, sp.cos(t1) * w1 + sp.cos(t1 + t2) * w, 0])
    >>> steps = speed_squared_steps(v)
    >>> [i.rule for i in steps.identities]
    ['sin(A)^2 + cos(A)^2 = 1', 'sin(A)^2 + cos(A)^2 = 1', 'cos(A) cos(B) + sin(A) sin(B) = cos(A - B)']
    >>> sp.expand(steps.result)
    2*w1**2*cos(t2) + 2*w1**2 + 2*w1*w2*cos(t2) + 2*w1*w2 + w2**2
    """
    components = tuple(sp.Matrix(velocity))
    if sum(sp.count_ops(c) for c in components) > SPEED_STEPS_BUDGET:
        return None
    expanded = sp.expand(sum((c**2 for c in components), sp.Integer(0)))
    trig = sorted(expanded.atoms(sp.sin, sp.cos), key=sp.default_sort_key)
    if not trig:
        return SpeedSquared(components, expanded, (), expanded)
    poly = sp.Poly(expanded, *trig)
    terms: dict[tuple[int, ...], sp.Expr] = dict(poly.terms())
    index = {f: k for k, f in enumerate(trig)}
    extra: list[sp.Expr] = []
    used: list[Identity] = []

    def common(a: sp.Expr, b: sp.Expr) -> sp.Expr:
        """The terms two coefficients share (the part of a pair of products an identity can shorten)."""
        others = set(sp.Add.make_args(sp.expand(b)))
        return sp.Add(*[t for t in sp.Add.make_args(sp.expand(a)) if t in others])

    def take(exps: tuple[int, ...], amount: sp.Expr) -> None:
        left = sp.expand(terms.pop(exps) - amount)
        if left != 0:
            terms[exps] = left

    def monomial(exps: tuple[int, ...]) -> sp.Expr:
        return sp.Mul(*[f**e for f, e in zip(trig, exps, strict=True)])

    def note(identity: Identity) -> None:
        if all(i.lhs != identity.lhs for i in used):
            used.append(identity)

    args = sorted({f.args[0] for f in trig}, key=sp.default_sort_key)
    changed = True
    while changed:
        changed = False
        # sin^2 A + cos^2 A = 1
        for a in args:
            si, ci = index.get(sp.sin(a)), index.get(sp.cos(a))
            if si is None or ci is None:
                continue
            for exps in list(terms):
                if exps not in terms or exps[si] < 2:
                    continue
                partner = list(exps)
                partner[si] -= 2
                partner[ci] += 2
                partner_t = tuple(partner)
                coeff = common(terms[exps], terms[partner_t]) if partner_t in terms else sp.Integer(0)
                if coeff != 0:
                    rest = list(exps)
                    rest[si] -= 2
                    take(exps, coeff)
                    take(partner_t, coeff)
                    terms[tuple(rest)] = terms.get(tuple(rest), sp.Integer(0)) + coeff
                    note(Identity(RULE_PYTHAGORAS, sp.sin(a) ** 2 + sp.cos(a) ** 2, sp.Integer(1)))
                    changed = True
        # cos A cos B + sin A sin B = cos(A - B);  sin A cos B - cos A sin B = sin(A - B)
        for i, a in enumerate(args):
            for b in args[i + 1 :]:
                ca, cb, sa, sb = (index.get(f) for f in (sp.cos(a), sp.cos(b), sp.sin(a), sp.sin(b)))
                if None in (ca, cb, sa, sb):
                    continue
                for exps in list(terms):
                    if exps not in terms:
                        continue
                    if exps[ca] >= 1 and exps[cb] >= 1:
                        partner = list(exps)
                        partner[ca] -= 1
                        partner[cb] -= 1
                        partner[sa] += 1
                        partner[sb] += 1
                        partner_t = tuple(partner)
                        coeff = common(terms[exps], terms[partner_t]) if partner_t in terms else sp.Integer(0)
                        if coeff != 0:
                            rest = list(exps)
                            rest[ca] -= 1
                            rest[cb] -= 1
                            take(exps, coeff)
                            take(partner_t, coeff)
                            extra.append(coeff * monomial(tuple(rest)) * sp.cos(a - b))
                            lhs = sp.cos(a) * sp.cos(b) + sp.sin(a) * sp.sin(b)
                            note(Identity(RULE_COS_DIFFERENCE, lhs, sp.cos(a - b)))
                            changed = True
                            continue
                    if exps[sa] >= 1 and exps[cb] >= 1:
                        partner = list(exps)
                        partner[sa] -= 1
                        partner[cb] -= 1
                        partner[ca] += 1
                        partner[sb] += 1
                        partner_t = tuple(partner)
                        coeff = common(terms[exps], -terms[partner_t]) if partner_t in terms else sp.Integer(0)
                        if coeff != 0:
                            rest = list(exps)
                            rest[sa] -= 1
                            rest[cb] -= 1
                            take(exps, coeff)
                            take(partner_t, -coeff)
                            extra.append(coeff * monomial(tuple(rest)) * sp.sin(a - b))
                            lhs = sp.sin(a) * sp.cos(b) - sp.cos(a) * sp.sin(b)
                            note(Identity(RULE_SIN_DIFFERENCE, lhs, sp.sin(a - b)))
                            changed = True
    result = sp.Add(*[coeff * monomial(exps) for exps, coeff in terms.items()], *extra)
    return SpeedSquared(components, expanded, tuple(used), result)


@dataclass(frozen=True)
class BodyKinematics:
    """A body's placement and velocities, in world components."""

    name: str
    position: Vec  # the body frame's origin
    rotation: sp.ImmutableMatrix
    com: Vec  # the centre of mass
    jv: sp.ImmutableMatrix  # v_G = jv * q_dot
    jw: sp.ImmutableMatrix  # omega = jw * q_dot
    velocity: Vec  # v_G
    angular_velocity: Vec
    # v_G . v_G worked step by step, with the identities used (None: too long to work through)
    speed: SpeedSquared | None = None


class Kinematics:
    """The frames of all bodies of a system (ground included), built once."""

    def __init__(self, system: System, com_of: dict[str, sp.ImmutableMatrix]) -> None:
        self.system = system
        self.q = [c.q for c in system.coordinates]
        self.qd = sp.Matrix([c.qd for c in system.coordinates])
        n = len(self.q)
        ground = Frame(sp.zeros(3, 1), sp.eye(3), sp.zeros(3, n), sp.zeros(3, n), ((0, 0, 1), sp.Integer(0)))
        self.frames: dict[str, Frame] = {GROUND: ground}
        by_child = {j.child: j for j in system.joints}
        for body in system.bodies:
            self._frame(body.name, by_child, ())
        self.bodies: dict[str, BodyKinematics] = {}
        for body in system.bodies:
            f = self.frames[body.name]
            com = (f.position + f.rotation * sp.Matrix(com_of[body.name])).applyfunc(sp.expand)
            jv = com.jacobian(self.q) if n else sp.zeros(3, 0)
            velocity = Vec((jv * self.qd).applyfunc(_collect_rates(self.qd)))
            self.bodies[body.name] = BodyKinematics(
                name=body.name,
                position=Vec(f.position),
                rotation=sp.ImmutableMatrix(f.rotation),
                com=Vec(com),
                jv=sp.ImmutableMatrix(jv),
                jw=sp.ImmutableMatrix(f.jw),
                velocity=velocity,
                angular_velocity=Vec((f.jw * self.qd).applyfunc(sp.expand)),
                speed=speed_squared_steps(velocity),
            )

    # -- building frames -----------------------------------------------------------------
    def _frame(self, name: str, by_child: dict[str, Joint], seen: tuple[str, ...]) -> Frame:
        if name in self.frames:
            return self.frames[name]
        if name in seen:  # validate.py rejects cycles; this guards the recursion anyway
            raise DerivationError(f"the joints form a loop through '{name}'")
        joint = by_child.get(name)
        if joint is None:
            frame = self._explicit_frame(self.system.body(name))
        else:
            parent = self._frame(joint.parent, by_child, (*seen, name))
            frame = self._joint_frame(parent, joint)
        self.frames[name] = frame
        return frame

    def _rate_column(self, coordinate: Coordinate | None) -> sp.Matrix:
        n = len(self.q)
        e = sp.zeros(1, n)
        if coordinate is not None:
            e[0, self.q.index(coordinate.q)] = 1
        return e

    def _explicit_frame(self, body: Body) -> Frame:
        n = len(self.q)
        pos = sp.Matrix(body.position) if body.position is not None else sp.zeros(3, 1)
        rot = sp.eye(3)
        jw = sp.zeros(3, n)
        planar: tuple[tuple[sp.Expr, ...], sp.Expr] | None = ((0, 0, 1), sp.Integer(0))
        for axis, angle in body.rotation_rates:
            world_axis = (rot * sp.Matrix(axis)).applyfunc(sp.expand)
            if n:
                jw += world_axis * sp.Matrix([[sp.diff(angle, qi) for qi in self.q]])
            planar = _merge_planar(planar, world_axis, angle)
            rot = _rotation_from_planar(planar) if planar else (rot * rotation_about(axis, angle))
        jv = pos.jacobian(self.q) if n else sp.zeros(3, 0)
        return Frame(pos, rot, jv, jw, planar)

    def _joint_frame(self, parent: Frame, joint: Joint) -> Frame:
        base_pos = (parent.position + parent.rotation * sp.Matrix(joint.origin_offset)).applyfunc(sp.expand)
        fixed = sp.Matrix(joint.rotation)
        is_identity = fixed == sp.eye(3)
        base_rot = parent.rotation * fixed if not is_identity else parent.rotation
        planar = parent.planar if is_identity else None
        axis_world = (base_rot * sp.Matrix(joint.axis)).applyfunc(sp.expand)
        value = (joint.coordinate.q if joint.coordinate else sp.Integer(0)) + joint.offset
        rate = self._rate_column(joint.coordinate)
        jw = parent.jw
        pos = base_pos
        if joint.kind is JointKind.REVOLUTE:
            if joint.absolute:
                if any(axis_world.free_symbols & set(self.q)):
                    raise DerivationError(
                        f"joint '{joint.name}' measures an absolute angle, but its axis turns with the "
                        "parent link; absolute angles need an axis fixed in the world (planar arms)",
                        joint.origin,
                    )
                jw = axis_world * rate
                planar = (tuple(axis_world), value) if is_identity else None
                rot = rotation_about(axis_world, value) * fixed
            else:
                jw = parent.jw + axis_world * rate
                planar = _merge_planar(planar, axis_world, value)
                rot = _rotation_from_planar(planar) if planar else base_rot * rotation_about(joint.axis, value)
        elif joint.kind is JointKind.PRISMATIC:
            rot = base_rot
            pos = (base_pos + axis_world * value).applyfunc(sp.expand)
        else:  # fixed
            rot = base_rot
        rot = sp.Matrix(rot).applyfunc(sp.expand)
        jv = pos.jacobian(self.q) if self.q else sp.zeros(3, 0)
        return Frame(pos, rot, jv, jw, planar)

    # -- points on bodies ------------------------------------------------------------------
    def point(self, body: str, local: sp.MatrixBase) -> sp.Matrix:
        """World position of a point given in a body's frame."""
        f = self.frames[body]
        return (f.position + f.rotation * sp.Matrix(local)).applyfunc(sp.expand)

    def point_jacobian(self, body: str, world_point: sp.MatrixBase) -> sp.Matrix:
        """J such that the velocity of the body's material point now at ``world_point`` is J q_dot:
        J = J_v(origin) + J_w x (r_P - r_O), column by column."""
        f = self.frames[body]
        lever = sp.Matrix(world_point) - f.position
        n = len(self.q)
        cols = [f.jv[:, j] + f.jw[:, j].cross(lever) for j in range(n)]
        return sp.Matrix.hstack(*cols).applyfunc(sp.expand) if n else sp.zeros(3, 0)

    # -- accelerations (for Newton-Euler) ---------------------------------------------------
    def time_derivative(self, expr: sp.Expr) -> sp.Expr:
        """d/dt of an expression in q, q_dot by the chain rule: f_q q_dot + f_qdot q_ddot."""
        coords = self.system.coordinates
        return total_derivative(expr, [c.q for c in coords], [c.qd for c in coords], [c.qdd for c in coords])

    def acceleration(self, body: str) -> sp.Matrix:
        """a_G = d/dt (J_v q_dot) of a body's centre of mass, world components, not yet tidied."""
        return self.bodies[body].velocity.applyfunc(self.time_derivative)

    def angular_acceleration(self, body: str) -> sp.Matrix:
        """alpha = d/dt (J_w q_dot), world components (the derivative taken in the world frame)."""
        return self.bodies[body].angular_velocity.applyfunc(self.time_derivative)

    def is_static(self, body: str) -> bool:
        """True when the body's frame does not move (ground, or a body placed at a constant pose)."""
        f = self.frames[body]
        return all(e == 0 for e in f.jv) and all(e == 0 for e in f.jw)


def _merge_planar(
    planar: tuple[tuple[sp.Expr, ...], sp.Expr] | None, world_axis: sp.MatrixBase, angle: sp.Expr
) -> tuple[tuple[sp.Expr, ...], sp.Expr] | None:
    """Keep (axis, total angle) while every rotation so far is about the same fixed world axis."""
    if planar is None:
        return None
    axis, total = planar
    w = tuple(sp.Matrix(world_axis))
    if total == 0 and all(v.is_number for v in w):
        return (w, angle)
    if w == axis:
        return (axis, total + angle)
    if w == tuple(-v for v in axis):
        return (axis, total - angle)
    return None


def _rotation_from_planar(planar: tuple[tuple[sp.Expr, ...], sp.Expr]) -> sp.Matrix:
    axis, angle = planar
    return rotation_about(sp.Matrix(axis), angle)


def _collect_rates(qd: sp.Matrix):  # noqa: ANN202 - a small closure factory
    rates = list(qd)

    def tidy(e: sp.Expr) -> sp.Expr:
        return sp.collect(sp.expand(e), rates)

    return tidy
