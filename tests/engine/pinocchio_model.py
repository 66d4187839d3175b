"""A tutgen :class:`~tutgen.model.system.System` rebuilt as a Pinocchio model, for numeric cross-checks.

Only systems whose bodies hang from the ground by a tree of revolute, prismatic and fixed joints with
relative angles can be rebuilt; :func:`serial_skip_reason` says why any other one cannot (absolute
angles, bodies placed by an explicit ``position``/``orientation``, a given kinetic energy, ...).

The conventions line up one to one:

- tutgen's child frame is the parent frame moved to ``origin_offset`` (parent axes), turned by the
  joint's fixed ``rotation`` and then by the joint motion about/along ``axis``; Pinocchio's joint
  frame is ``oMparent * placement * motion(q)``, so the placement is ``SE3(rotation, origin_offset)``
  and the motion is a ``JointModelRevolute*``/``JointModelPrismatic*`` about/along ``axis``.
- The joint ``offset`` (theta = q + offset) is folded into the placement: a rotation about the same
  axis (rotations about one axis commute) or a shift along it, so Pinocchio's q is tutgen's q.
- A body's mass properties are :func:`tutgen.engine.inertia.body_inertia`'s ``mass``, ``com`` (body
  frame) and ``inertia_com`` (about the centre of mass, body axes), which is exactly what
  ``pin.Inertia(m, c, I_c)`` takes; tutgen's J_xy = -integral x y dm is Pinocchio's sign too.
- A fixed joint does not become a Pinocchio joint: its child's inertia is appended to the joint the
  parent moves with, at the accumulated placement.
- A motor rotor adds ``Joint.reflected_inertia`` (n^2 J_m) to ``model.armature`` at the joint's
  velocity index; Pinocchio's ``crba`` and ``rnea`` both include the armature.
- Gravity is ``model.gravity.linear`` (zero when the spec has none: Pinocchio's default is -9.81 z).

Springs are not rebuilt: tutgen folds their potential into G, so :func:`spring_gradient` gives the
part of G to take off before comparing with Pinocchio's gravity torques. Dampers and loads go into
tutgen's Q, which is not compared.
"""

from __future__ import annotations

import random
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin
import sympy as sp

from tutgen.engine.inertia import body_inertia
from tutgen.engine.kinematics import rotation_about
from tutgen.model.system import GROUND, Joint, JointKind, Shape, System

RTOL = 1e-9
STATES = 5


# ---------------------------------------------------------------------------------------------
# Which systems can be rebuilt
# ---------------------------------------------------------------------------------------------


def serial_skip_reason(system: System) -> str | None:
    """None when the system is a tree of revolute/prismatic/fixed joints from the ground that
    Pinocchio can model; otherwise a short reason to put in a skip message."""
    if not system.coordinates:
        return "no coordinates (nothing to derive)"
    if system.kinetic_energy is not None or system.potential_energy is not None:
        return "energies given directly, no bodies to rebuild"
    if not system.bodies:
        return "no bodies"
    by_child = {j.child: j for j in system.joints}
    q_symbols = {c.q for c in system.coordinates}
    for body in system.bodies:
        if body.name in by_child:
            continue
        placed_by = [*(body.position or []), *(angle for _, angle in body.rotation_rates)]
        if any(sp.sympify(e).free_symbols & q_symbols for e in placed_by):
            return f"body '{body.name}' is placed by an explicit position/orientation, not by joints"
    driven: dict[str, int] = {}
    for joint in system.joints:
        if joint.absolute:
            return f"joint '{joint.name}' measures an absolute angle"
        if joint.kind not in (JointKind.REVOLUTE, JointKind.PRISMATIC, JointKind.FIXED):
            return f"joint '{joint.name}' is of kind {joint.kind}"
        constant = [*joint.axis, *joint.origin_offset, *joint.rotation, joint.offset]
        if any(sp.sympify(e).free_symbols & q_symbols for e in constant):
            return f"joint '{joint.name}' is placed or offset by a coordinate"
        if joint.coordinate is not None and joint.kind is not JointKind.FIXED:
            driven[joint.coordinate.name] = driven.get(joint.coordinate.name, 0) + 1
    for c in system.coordinates:
        if driven.get(c.name, 0) != 1:
            return f"coordinate '{c.name}' drives {driven.get(c.name, 0)} joints (Pinocchio needs exactly one)"
    return None


# ---------------------------------------------------------------------------------------------
# Numbers for the symbols
# ---------------------------------------------------------------------------------------------


def _product_of_inertia_symbols(system: System) -> set[sp.Symbol]:
    """Parameters that appear only in the off-diagonal entries of given (shape: general) inertias."""
    off: set[sp.Symbol] = set()
    elsewhere: set[sp.Symbol] = set()
    for body in system.bodies:
        for part in body.parts:
            if part.shape is Shape.GENERAL and part.inertia is not None:
                for i in range(3):
                    for j in range(3):
                        (off if i != j else elsewhere).update(sp.sympify(part.inertia[i, j]).free_symbols)
    return off - elsewhere


def is_physical(inertia: np.ndarray, tol: float = 1e-12) -> bool:
    """A rotational inertia about the centre of mass is physical when it is symmetric, positive
    semi-definite and its principal moments satisfy the triangle inequality (I1 + I2 >= I3)."""
    if not np.allclose(inertia, inertia.T, atol=tol):
        return False
    moments = np.linalg.eigvalsh(inertia)
    return bool(moments[0] >= -tol and moments[0] + moments[1] >= moments[2] - tol)


def parameter_values(system: System, seed: int, tries: int = 100) -> dict[sp.Symbol, float]:
    """A float for every parameter: its own value, else a random one in (0.5, 2) (products of
    inertia that are symbols: in (-0.1, 0.1)), drawn again until every body's inertia is physical.

    A spec may give inertias that no values make physical (a planar link with only ``zz``: then
    I_xx + I_yy < I_zz); the last draw is returned and :func:`unphysical_bodies` names those bodies.
    Pinocchio computes with such inertias all the same, and H, C, G stay comparable."""
    rng = random.Random(seed)
    products = _product_of_inertia_symbols(system)
    symbols = [p.symbol for p in system.parameters]
    inertias = [body_inertia(b) for b in system.bodies]
    mass_props = sp.lambdify(symbols, [[bi.mass, sp.Matrix(bi.inertia_com)] for bi in inertias], modules="numpy")
    values: dict[sp.Symbol, float] = {}
    for _ in range(tries):
        values = {}
        for p in system.parameters:
            if p.value is not None:
                values[p.symbol] = float(p.value)
            elif p.symbol in products:
                values[p.symbol] = rng.uniform(-0.1, 0.1)
            else:
                values[p.symbol] = rng.uniform(0.5, 2.0)
        props = mass_props(*(values[s] for s in symbols))
        if all(float(m) >= 0 and is_physical(np.array(j, dtype=float)) for m, j in props):
            break
    return values


def unphysical_bodies(system: System, values: dict[sp.Symbol, float]) -> list[str]:
    """The bodies whose mass is negative or whose inertia about the centre of mass is not physical."""
    out = []
    for body in system.bodies:
        bi = body_inertia(body)
        if float(sp.sympify(bi.mass).subs(values)) < 0 or not is_physical(_numeric(bi.inertia_com, values)):
            out.append(body.name)
    return out


def _numeric(matrix: Any, values: dict[sp.Symbol, float]) -> np.ndarray:
    m = sp.Matrix(matrix).subs(values)
    return np.array(m.evalf(), dtype=float)


# ---------------------------------------------------------------------------------------------
# The Pinocchio model
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class PinocchioModel:
    """A Pinocchio model of a System, with its coordinates' velocity indices in tutgen's order."""

    model: pin.Model
    v_index: tuple[int, ...]  # tutgen coordinate k is Pinocchio's q[v_index[k]] (1-dof joints: nq = nv)
    values: dict[sp.Symbol, float]

    def to_pin(self, x: np.ndarray) -> np.ndarray:
        """A vector in tutgen's coordinate order, in Pinocchio's order."""
        out = np.zeros(self.model.nv)
        out[list(self.v_index)] = x
        return out

    def from_pin(self, x: np.ndarray) -> np.ndarray:
        return np.asarray(x)[list(self.v_index)]


_ALIGNED = {
    (JointKind.REVOLUTE, (1, 0, 0)): pin.JointModelRX,
    (JointKind.REVOLUTE, (0, 1, 0)): pin.JointModelRY,
    (JointKind.REVOLUTE, (0, 0, 1)): pin.JointModelRZ,
    (JointKind.PRISMATIC, (1, 0, 0)): pin.JointModelPX,
    (JointKind.PRISMATIC, (0, 1, 0)): pin.JointModelPY,
    (JointKind.PRISMATIC, (0, 0, 1)): pin.JointModelPZ,
}


def _joint_model(kind: JointKind, axis: np.ndarray) -> Any:
    key = (kind, tuple(int(a) if float(a).is_integer() else None for a in axis))
    if key in _ALIGNED:
        return _ALIGNED[key]()
    if kind is JointKind.REVOLUTE:
        return pin.JointModelRevoluteUnaligned(axis)
    return pin.JointModelPrismaticUnaligned(axis)


def build_model(system: System, values: dict[sp.Symbol, float]) -> PinocchioModel:
    """Rebuild ``system`` (which :func:`serial_skip_reason` accepts) with the parameter ``values``."""
    reason = serial_skip_reason(system)
    if reason is not None:
        raise ValueError(f"cannot rebuild '{system.title}' in Pinocchio: {reason}")
    model = pin.Model()
    model.name = system.title
    model.gravity.linear = _numeric(system.gravity, values).ravel() if system.gravity is not None else np.zeros(3)
    by_child = {j.child: j for j in system.joints}
    # body name -> (Pinocchio joint it moves with, placement of the body frame in that joint's frame)
    placed: dict[str, tuple[int, pin.SE3]] = {GROUND: (0, pin.SE3.Identity())}
    coordinate_joint: dict[str, int] = {}

    def place(name: str) -> tuple[int, pin.SE3]:
        if name in placed:
            return placed[name]
        joint = by_child.get(name)
        if joint is None:  # a body at a constant pose: fixed to the ground
            placed[name] = (0, _explicit_placement(system, name, values))
            return placed[name]
        parent_id, parent_placement = place(joint.parent)
        placement = parent_placement * _joint_placement(joint, values)
        moving = joint.kind is not JointKind.FIXED and joint.coordinate is not None
        if moving:
            axis = _numeric(joint.axis, values).ravel()
            jid = model.addJoint(parent_id, _joint_model(joint.kind, axis), placement, f"j_{joint.name}")
            assert joint.coordinate is not None
            coordinate_joint[joint.coordinate.name] = jid
            if joint.reflected_inertia is not None:
                model.armature[model.joints[jid].idx_v] += float(sp.sympify(joint.reflected_inertia).subs(values))
            placed[name] = (jid, pin.SE3.Identity())
        else:
            placed[name] = (parent_id, placement)
        return placed[name]

    for body in system.bodies:
        place(body.name)
    for body in system.bodies:
        jid, where = placed[body.name]
        bi = body_inertia(body)
        mass = float(sp.sympify(bi.mass).subs(values))
        com = _numeric(bi.com, values).ravel()
        inertia = pin.Inertia(mass, com, _numeric(bi.inertia_com, values))
        model.appendBodyToJoint(jid, inertia, where)
    v_index = tuple(model.joints[coordinate_joint[c.name]].idx_v for c in system.coordinates)
    return PinocchioModel(model, v_index, values)


def _joint_placement(joint: Joint, values: dict[sp.Symbol, float]) -> pin.SE3:
    """SE3 of the child frame at q = 0 in the parent frame, with the joint's offset folded in (and, for
    a joint without a coordinate, its motion at the offset)."""
    rotation = _numeric(joint.rotation, values)
    origin = _numeric(joint.origin_offset, values).ravel()
    offset = float(sp.sympify(joint.offset).subs(values))
    axis = _numeric(joint.axis, values).ravel()
    if joint.kind is JointKind.REVOLUTE:
        rotation = rotation @ _numeric(rotation_about(sp.Matrix(axis.tolist()), sp.Float(offset)), {})
    elif joint.kind is JointKind.PRISMATIC:
        origin = origin + rotation @ axis * offset
    return pin.SE3(rotation, origin)


def _explicit_placement(system: System, name: str, values: dict[sp.Symbol, float]) -> pin.SE3:
    body = system.body(name)
    rotation = sp.eye(3)
    for axis, angle in body.rotation_rates:  # intrinsic: each about the axes turned by the ones before
        rotation = rotation * rotation_about(sp.Matrix(axis), angle)
    position = body.position if body.position is not None else sp.zeros(3, 1)
    return pin.SE3(_numeric(rotation, values), _numeric(position, values).ravel())


# ---------------------------------------------------------------------------------------------
# Comparison
# ---------------------------------------------------------------------------------------------


def spring_gradient(system: System, spring_energies: Sequence[tuple[str, sp.Expr]]) -> sp.Matrix:
    """dV_springs/dq, the part of tutgen's G that is not gravity (Pinocchio has no springs)."""
    total = sum((e for _, e in spring_energies), sp.Integer(0))
    return sp.Matrix([sp.diff(total, c.q) for c in system.coordinates])


@dataclass(frozen=True)
class Comparison:
    """The worst relative errors of tutgen against Pinocchio over the states compared."""

    mass_matrix: float  # H against crba
    gravity: float  # G against computeGeneralizedGravity
    inverse_dynamics: float  # H a + C + G against rnea(q, v, a)

    @property
    def worst(self) -> float:
        return max(self.mass_matrix, self.gravity, self.inverse_dynamics)

    @property
    def agrees(self) -> bool:
        return self.worst <= RTOL


def _relative(ours: np.ndarray, theirs: np.ndarray) -> float:
    """max |ours - theirs| over max(1, max |theirs|): relative to the magnitude, absolute near 0."""
    return float(np.max(np.abs(ours - theirs)) / max(1.0, float(np.max(np.abs(theirs)))))


def _compile(args: list[sp.Symbol], exprs: list[sp.Expr]) -> Any:
    """A float function of ``args`` returning ``exprs`` as a flat array: symengine's Lambdify when it is
    installed (a 6-DOF arm's H, C, G compile in about a second), else sympy.lambdify with cse."""
    try:
        import symengine as se
    except ImportError:
        f = sp.lambdify(args, exprs, modules="numpy", cse=True)
        return lambda x: np.array(f(*x), dtype=float).ravel()
    g = se.Lambdify([se.sympify(a) for a in args], [se.sympify(e) for e in exprs], backend="lambda", cse=True)
    return lambda x: np.asarray(g(np.asarray(x, dtype=float)), dtype=float).ravel()


def compare(
    system: System,
    mass_matrix: sp.MatrixBase,
    coriolis_vector: sp.MatrixBase,
    gravity_vector: sp.MatrixBase,
    rebuilt: PinocchioModel,
    seed: int,
    states: int = STATES,
) -> Comparison:
    """Evaluate tutgen's H, C (C(q, q_dot) q_dot as a vector) and G (gravity only, springs taken off)
    with the model's parameter values at ``states`` random states, and compare with Pinocchio."""
    q = [c.q for c in system.coordinates]
    qd = [c.qd for c in system.coordinates]
    n = len(q)
    params = sorted(rebuilt.values, key=lambda s: s.name)
    p_vals = [rebuilt.values[s] for s in params]
    evaluate = _compile([*q, *qd, *params], [*mass_matrix, *coriolis_vector, *gravity_vector])
    rng = np.random.default_rng(seed)
    model = rebuilt.model
    data = model.createData()
    worst = [0.0, 0.0, 0.0]
    for _ in range(states):
        qv, vv, av = rng.uniform(-np.pi, np.pi, n), rng.uniform(-2, 2, n), rng.uniform(-2, 2, n)
        out = evaluate([*qv, *vv, *p_vals])
        h, c, g = out[: n * n].reshape(n, n), out[n * n : n * n + n], out[n * n + n :]
        qp, vp, ap = rebuilt.to_pin(qv), rebuilt.to_pin(vv), rebuilt.to_pin(av)
        m = np.array(pin.crba(model, data, qp))
        m = np.triu(m) + np.triu(m, 1).T  # crba fills the upper triangle only
        idx = list(rebuilt.v_index)
        h_pin = m[np.ix_(idx, idx)]
        g_pin = rebuilt.from_pin(pin.computeGeneralizedGravity(model, data, qp))
        tau_pin = rebuilt.from_pin(pin.rnea(model, data, qp, vp, ap))
        worst[0] = max(worst[0], _relative(h, h_pin))
        worst[1] = max(worst[1], _relative(g, g_pin))
        worst[2] = max(worst[2], _relative(h @ av + c + g, tau_pin))
    return Comparison(*worst)
