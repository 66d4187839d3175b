"""Every spec with bodies, rebuilt with sympy.physics.mechanics and solved by Kane's method.

The reference is built from the validated model (:class:`tutgen.model.System`) alone, without
tutgen's kinematics or Lagrange code: a ``ReferenceFrame`` per body, turned joint by joint with
``orient_axis`` (revolute) or shifted with ``Point.locatenew`` (prismatic); ``RigidBody`` or
``Particle`` with the mass properties of :func:`tutgen.engine.inertia.body_inertia` (tested on its
own); gravity, springs, dampers and applied loads as forces on points and torques on frames; and
Kane's equations with u = q_dot. The two results are compared numerically at random states,
because simplifying Kane's output symbolically is far too slow:

    H(q)                 == KanesMethod.mass_matrix
    Q - C(q, q_dot) - G  == KanesMethod.forcing
    equations_of_motion  == mass_matrix q_ddot - forcing

The reference uses symbols without assumptions (tutgen declares most parameters positive), so a
simplification that holds only for positive values cannot hide in both sides; the two sides are
matched by symbol name.
"""

from __future__ import annotations

import random
import zlib
from dataclasses import dataclass
from typing import Any

import mpmath
import pytest
import sympy as sp
import yaml
from sympy.core.function import AppliedUndef
from sympy.physics.mechanics import (
    KanesMethod,
    Particle,
    Point,
    ReferenceFrame,
    RigidBody,
    Vector,
    dynamicsymbols,
    outer,
)

from tests.conftest import ROOT, all_specs, solved
from tests.models import negative_length, quadratic_drag, spec_models, system_of
from tutgen.engine.inertia import body_inertia
from tutgen.engine.pipeline import derive
from tutgen.model.system import GROUND, JointKind, System

STATES = 5
DIGITS = 30
RTOL = 1e-9

# ---------------------------------------------------------------------------------------------
# The reference model
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Reference:
    """Kane's mass matrix and forcing, in plain symbols named as in the spec (q, q_dot, parameters)."""

    mass_matrix: sp.Matrix
    forcing: sp.Matrix


class MechanicsModel:
    """A sympy.physics.mechanics twin of a System: frames, points, bodies and loads."""

    def __init__(self, system: System) -> None:
        self.system = system
        self.t = dynamicsymbols._t
        self.qs = [dynamicsymbols(f"{c.name}_q") for c in system.coordinates]
        self.us = [dynamicsymbols(f"{c.name}_u") for c in system.coordinates]
        # spec expressions -> the reference's symbols: coordinates -> q(t), rates -> u(t) (= q_dot),
        # parameters -> symbols of the same name without assumptions
        self.to_reference: dict[sp.Symbol, sp.Expr] = {p.symbol: sp.Symbol(p.name) for p in system.parameters}
        self.to_reference |= {c.q: q for c, q in zip(system.coordinates, self.qs, strict=True)}
        self.to_reference |= {c.qd: u for c, u in zip(system.coordinates, self.us, strict=True)}
        self.n_frame = ReferenceFrame("N")
        self.o = Point("O")
        self.o.set_vel(self.n_frame, 0)
        self.frames: dict[str, ReferenceFrame] = {GROUND: self.n_frame}
        self.origins: dict[str, Point] = {GROUND: self.o}
        self.joint_of = {j.child: j for j in system.joints}
        for body in system.bodies:
            self._place(body.name)
        for origin in self.origins.values():
            origin.set_vel(self.n_frame, origin.pos_from(self.o).dt(self.n_frame))

    # -- helpers -------------------------------------------------------------------------------
    def ref(self, expr: Any) -> Any:
        """A spec expression (or matrix) in the reference's symbols."""
        return sp.sympify(expr).xreplace(self.to_reference)

    def vec(self, components: Any, frame: ReferenceFrame) -> Vector:
        x, y, z = (self.ref(c) for c in components)
        return x * frame.x + y * frame.y + z * frame.z

    def point(self, body: str, at: Any, name: str) -> Point:
        """A point fixed in ``body`` at ``at`` (body axes), with its velocity in N."""
        p = self.origins[body].locatenew(name, self.vec(at, self.frames[body]))
        p.set_vel(self.n_frame, p.pos_from(self.o).dt(self.n_frame))
        return p

    def _turned(self, name: str, parent: ReferenceFrame, rotation: sp.MatrixBase) -> ReferenceFrame:
        """A frame turned by a constant rotation R (parent from child: r_parent = R r_child)."""
        rotation = sp.Matrix(self.ref(rotation))
        if rotation == sp.eye(3):
            return parent
        frame = ReferenceFrame(name)
        frame.orient_explicit(parent, rotation)
        return frame

    # -- placing bodies ----------------------------------------------------------------------------
    def _place(self, name: str) -> None:
        if name in self.frames:
            return
        joint = self.joint_of.get(name)
        if joint is None:
            self._place_explicit(name)
            return
        self._place(joint.parent)
        parent, parent_origin = self.frames[joint.parent], self.origins[joint.parent]
        # the joint's origin in the parent's axes, then its fixed rotation, then the motion
        where = parent_origin.locatenew(f"J_{joint.name}", self.vec(joint.origin_offset, parent))
        base = self._turned(f"A_{joint.name}", parent, joint.rotation)
        axis = self.vec(joint.axis, base)
        value = self.ref(joint.offset) + (self.ref(joint.coordinate.q) if joint.coordinate else 0)
        origin = where
        if joint.kind is JointKind.REVOLUTE:
            frame = ReferenceFrame(f"F_{name}")
            if joint.absolute:
                # measured from the world frame, about the axis' (constant) direction in N
                axis_n = [sp.trigsimp(axis.dot(e)) for e in self.n_frame]
                assert not any(c.has(*self.qs) for c in axis_n), f"absolute joint '{joint.name}' with a moving axis"
                start = self._turned(f"A0_{joint.name}", self.n_frame, joint.rotation)
                frame.orient_axis(start, self.vec(axis_n, self.n_frame), value)
            else:
                frame.orient_axis(base, axis, value)
        elif joint.kind is JointKind.PRISMATIC:
            frame = base
            origin = where.locatenew(f"P_{joint.name}", value * axis)
        else:
            frame = base
        self.frames[name] = frame
        self.origins[name] = origin

    def _place_explicit(self, name: str) -> None:
        """A body without a joint: elementary rotations about its own axes, then its position."""
        body = self.system.body(name)
        frame = self.n_frame
        for k, (axis, angle) in enumerate(body.rotation_rates):
            turned = ReferenceFrame(f"R{k}_{name}")
            turned.orient_axis(frame, self.vec(axis, frame), self.ref(angle))
            frame = turned
        position = body.position if body.position is not None else [0, 0, 0]
        self.frames[name] = frame
        self.origins[name] = self.o.locatenew(f"O_{name}", self.vec(position, self.n_frame))

    # -- bodies and loads --------------------------------------------------------------------------
    def bodies_and_loads(self) -> tuple[list[Any], list[tuple[Any, Vector]]]:
        system, n_frame = self.system, self.n_frame
        gravity = self.vec(system.gravity, n_frame) if system.gravity is not None else None
        bodies: list[Any] = []
        loads: list[tuple[Any, Vector]] = []
        for body in system.bodies:
            props = body_inertia(body)
            mass, inertia = self.ref(props.mass), sp.Matrix(self.ref(props.inertia_com))
            frame = self.frames[body.name]
            com = self.point(body.name, props.com, f"G_{body.name}")
            if inertia != sp.zeros(3, 3):
                axes = (frame.x, frame.y, frame.z)
                dyadic = sum(
                    (inertia[i, j] * outer(axes[i], axes[j]) for i in range(3) for j in range(3)),
                    0 * outer(frame.x, frame.x),
                )
                bodies.append(RigidBody(f"B_{body.name}", com, frame, mass, (dyadic, com)))
            elif mass != 0:
                bodies.append(Particle(f"B_{body.name}", com, mass))
            if gravity is not None and mass != 0:
                loads.append((com, mass * gravity))
        for spring in system.springs:
            if spring.between is not None:
                a, b, d = self._ends(spring.name, spring.between)
                length = sp.sqrt(d.dot(d))
                tension = self.ref(spring.stiffness) * (length - self.ref(spring.free_length))
                loads += [(a, -tension / length * d), (b, tension / length * d)]
        for damper in system.dampers:
            if damper.between is not None:
                a, b, d = self._ends(damper.name, damper.between)
                length = sp.sqrt(d.dot(d))
                rate = (a.vel(n_frame) - b.vel(n_frame)).dot(d) / length  # dL/dt
                tension = self.ref(damper.coefficient) * rate
                loads += [(a, -tension / length * d), (b, tension / length * d)]
        for load in system.loads:
            on = self.frames[load.body]
            components = on if load.in_body_frame else n_frame
            reaction = load.reaction_body not in (None, GROUND)
            if load.force is not None:
                force = self.vec(load.force, components)
                where = self.point(load.body, load.at, f"L_{load.name}")
                loads.append((where, force))
                if reaction:
                    # the reaction acts on the material point of the other body that is at the same place
                    other = self.origins[load.reaction_body]
                    twin = other.locatenew(f"R_{load.name}", where.pos_from(other))
                    twin.v2pt_theory(other, n_frame, self.frames[load.reaction_body])
                    loads.append((twin, -force))
            if load.torque is not None:
                torque = self.vec(load.torque, components)
                loads.append((on, torque))
                if reaction:
                    loads.append((self.frames[load.reaction_body], -torque))
        return bodies, loads

    def _ends(self, name: str, between: Any) -> tuple[Point, Point, Vector]:
        a = self.point(between[0].body, between[0].at, f"E0_{name}")
        b = self.point(between[1].body, between[1].at, f"E1_{name}")
        return a, b, a.pos_from(b)

    def extra_forces(self) -> sp.Matrix:
        """Generalized forces that are not loads on points or frames: `generalized_forces`, and springs and
        dampers given by an `extension` e(q), Q_i = -k e de/dq_i and Q_i = -c e_dot de/dq_i."""
        system, qs, us = self.system, self.qs, self.us
        out = sp.zeros(len(qs), 1)
        names = [c.name for c in system.coordinates]
        for cname, value in system.generalized_forces:
            out[names.index(cname)] += self.ref(value)
        for spring in system.springs:
            if spring.extension is not None:
                e = self.ref(spring.extension)
                for i, qi in enumerate(qs):
                    out[i] -= self.ref(spring.stiffness) * e * e.diff(qi)
        for damper in system.dampers:
            if damper.extension is not None:
                e = self.ref(damper.extension)
                rate = sum((e.diff(qj) * uj for qj, uj in zip(qs, us, strict=True)), sp.Integer(0))
                for i, qi in enumerate(qs):
                    out[i] -= self.ref(damper.coefficient) * rate * e.diff(qi)
        return out

    def kane(self) -> Reference:
        bodies, loads = self.bodies_and_loads()
        kd = [q.diff(self.t) - u for q, u in zip(self.qs, self.us, strict=True)]
        km = KanesMethod(self.n_frame, q_ind=self.qs, u_ind=self.us, kd_eqs=kd)
        km.kanes_equations(bodies, loads)
        plain = {u: sp.Symbol(f"{c.name}_dot") for u, c in zip(self.us, self.system.coordinates, strict=True)}
        plain |= {q: sp.Symbol(c.name) for q, c in zip(self.qs, self.system.coordinates, strict=True)}
        mass = km.mass_matrix.xreplace(plain)
        forcing = (km.forcing + self.extra_forces()).xreplace(plain)
        leftover = mass.atoms(AppliedUndef, sp.Derivative) | forcing.atoms(AppliedUndef, sp.Derivative)
        assert not leftover, f"functions of time left in Kane's equations: {leftover}"
        mass = sp.Matrix(mass)
        # a motor's rotor, as the spec format models it: its reflected inertia n^2 J_m on the diagonal
        names = [c.name for c in self.system.coordinates]
        for joint in self.system.joints:
            if joint.reflected_inertia is not None and joint.coordinate is not None:
                i = names.index(joint.coordinate.name)
                mass[i, i] += joint.reflected_inertia
        return Reference(mass, sp.Matrix(forcing))


def reference(system: System) -> Reference:
    return MechanicsModel(system).kane()


# ---------------------------------------------------------------------------------------------
# Numeric comparison, by symbol name
# ---------------------------------------------------------------------------------------------


def random_states(system: System, seed: int, count: int = STATES) -> list[dict[str, sp.Rational]]:
    """Random exact states by name: the parameters' own values, else a random value in (0.5, 2);
    q in (-pi, pi), the rates and accelerations in (-2, 2)."""
    rng = random.Random(seed)
    out = []
    for _ in range(count):
        state = {}
        for p in system.parameters:
            state[p.name] = sp.Rational(rng.randint(500, 2000), 1000) if p.value is None else p.value
        for c in system.coordinates:
            state[c.name] = sp.Rational(rng.randint(-3141, 3141), 1000)
            state[f"{c.name}_dot"] = sp.Rational(rng.randint(-2000, 2000), 1000)
            state[f"{c.name}_ddot"] = sp.Rational(rng.randint(-2000, 2000), 1000)
        out.append(state)
    return out


def _mp(value: sp.Expr) -> mpmath.mpf:
    value = sp.sympify(value)
    if value.is_Rational:
        return mpmath.mpf(int(value.p)) / int(value.q)
    return mpmath.mpf(str(sp.N(value, DIGITS + 10)))


class Numeric:
    """A matrix of expressions, compiled once for mpmath and evaluated at states given by name."""

    def __init__(self, matrix: sp.MatrixBase) -> None:
        matrix = sp.Matrix(matrix)
        self.symbols = sorted(matrix.free_symbols, key=lambda s: s.name)
        self.f = sp.lambdify(self.symbols, matrix, modules="mpmath")

    def __call__(self, state: dict[str, Any]) -> list[Any]:
        with mpmath.workdps(DIGITS):
            result = self.f(*[_mp(state[s.name]) for s in self.symbols])
            return [result[i, j] for i in range(result.rows) for j in range(result.cols)]


def assert_close(what: str, ours: list[Any], theirs: list[Any], state: dict[str, Any]) -> None:
    for k, (a, b) in enumerate(zip(ours, theirs, strict=True)):
        scale = max(1, abs(a), abs(b))
        assert abs(a - b) <= RTOL * scale, f"{what}[{k}]: tutgen {a}, mechanics {b} at {state}"


def cross_check(system: System, derivation: Any, name: str) -> None:
    """tutgen's H, Q - C - G and equations of motion against Kane's, at STATES random states."""
    ref = reference(system)
    qdd = sp.Matrix([sp.Symbol(f"{c.name}_ddot") for c in system.coordinates])
    ours = {
        "H": derivation.mass_matrix,
        "Q-C-G": derivation.generalized_forces - derivation.coriolis_vector - derivation.gravity_vector,
        "EOM": derivation.equations_of_motion,
    }
    theirs = {"H": ref.mass_matrix, "Q-C-G": ref.forcing, "EOM": ref.mass_matrix * qdd - ref.forcing}
    states = random_states(system, zlib.crc32(name.encode()))
    for key in ours:
        f_ours, f_theirs = Numeric(ours[key]), Numeric(theirs[key])
        for state in states:
            assert_close(key, f_ours(state), f_theirs(state), state)


# ---------------------------------------------------------------------------------------------
# The tests
# ---------------------------------------------------------------------------------------------


def dynamic_specs() -> list[Any]:
    """Every spec under specs/ with coordinates and bodies (read as plain YAML, which is cheap)."""
    out = []
    for path in all_specs():
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
        if isinstance(data, dict) and data.get("coordinates") and (data.get("bodies") or data.get("arm")):
            # the numeric PUMA's Kane reference takes half a minute; Pinocchio checks that arm in the default
            # run (tests/engine/test_pinocchio.py), this one with -m slow
            marks = pytest.mark.slow if path.stem == "puma560-numeric" else ()
            out.append(pytest.param(path, id=path.relative_to(ROOT / "specs").with_suffix("").as_posix(), marks=marks))
    return out


@pytest.mark.parametrize("path", dynamic_specs())
def test_mechanics_generic_matches_spec(path: Any) -> None:
    system, derivation, _ = solved(str(path))
    cross_check(system, derivation, path.name)


@pytest.mark.parametrize("name", sorted(spec_models()))
def test_mechanics_generic_matches_model(name: str) -> None:
    # Lagrange's route only: Newton-Euler is checked against it inside derive()
    system = system_of(spec_models()[name])
    cross_check(system, derive(system, method="lagrange"), name)


def test_mechanics_generic_negative_parameter_value() -> None:
    # a parameter with a negative value must not be assumed positive: sqrt(d**2*x**2) is not d*Abs(x)
    system = system_of(negative_length())
    cross_check(system, derive(system, method="lagrange"), "negative-length")


def test_mechanics_generic_force_not_polynomial_in_rates() -> None:
    # a drag force c*x_dot*abs(x_dot) is not a polynomial in the rates: tidy_rates must not need one
    system = system_of(quadratic_drag())
    cross_check(system, derive(system, method="lagrange"), "quadratic-drag")
