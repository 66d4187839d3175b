"""What springs, dampers, loads and motor rotors contribute, shared by every route of the engine.

- A spring stores U = k (L - L0)^2 / 2, L its length between two points or the elongation it is given.
- Loads and dampers enter through their virtual power: Q_i = F . dr_P/dq_dot_i + M . domega/dq_dot_i for a
  force F at P and a couple M (minus the same on the reaction body), and -c L_dot dL/dq_i for a damper.
- A motor's rotor behind a gearbox of ratio n adds its reflected inertia n^2 J_m to H_ii.

The general route (:mod:`tutgen.engine.lagrange`) and the route for large serial arms
(:mod:`tutgen.engine.serial`, assembled in :mod:`tutgen.engine.pipeline`) both read them from here.
"""

from __future__ import annotations

import sympy as sp

from tutgen.engine.kinematics import Kinematics
from tutgen.engine.tidy import tidy, tidy_rates
from tutgen.errors import DerivationError
from tutgen.model.system import GROUND, Damper, Spring, System

__all__ = ["generalized_forces", "rotors", "spring_energies", "spring_energy"]


def rotors(system: System) -> list[tuple[int, sp.Expr]]:
    """(index of the coordinate, reflected inertia n^2 J_m) for every joint driven by a motor's rotor.

    Only the reflected inertia is modelled: the rotor spins at n q_dot_i about its own axis, so its
    kinetic energy is J_m (n q_dot_i)^2 / 2; its gyroscopic coupling with the links (and its own mass,
    part of the link's) are neglected, as in Spong's and Craig's arm models."""
    index = {c.name: i for i, c in enumerate(system.coordinates)}
    out = []
    for joint in system.joints:
        reflected = joint.reflected_inertia
        if reflected is not None and joint.coordinate is not None:
            out.append((index[joint.coordinate.name], reflected))
    return out


def _length_between(element: Spring | Damper, kin: Kinematics | None) -> sp.Expr:
    assert element.between is not None and kin is not None
    a, b = element.between
    d = kin.point(a.body, a.at) - kin.point(b.body, b.at)
    return tidy((d.T * d)[0])  # the squared length


def spring_energy(spring: Spring, kin: Kinematics | None, system: System) -> sp.Expr:
    """U = k (L - L0)^2 / 2, with L the distance between the ends or the given elongation."""
    if spring.extension is not None:
        return spring.stiffness * spring.extension**2 / 2
    if kin is None:
        raise DerivationError(f"spring '{spring.name}' needs bodies to attach to", spring.origin)
    length2 = _length_between(spring, kin)
    if spring.free_length == 0:
        return tidy(spring.stiffness * length2 / 2)
    return spring.stiffness * (sp.sqrt(length2) - spring.free_length) ** 2 / 2


def spring_energies(system: System, kin: Kinematics | None) -> tuple[tuple[str, sp.Expr], ...]:
    """(name, U) of every spring, in spec order."""
    return tuple((s.name, spring_energy(s, kin, system)) for s in system.springs)


def generalized_forces(
    system: System, kin: Kinematics | None, q: list[sp.Symbol], qd: list[sp.Symbol]
) -> list[sp.Expr]:
    """Q_i from the virtual power of every applied force, torque and damper."""
    n = len(q)
    names = [c.name for c in system.coordinates]
    out = [sp.Integer(0)] * n
    for name, value in system.generalized_forces:
        i = names.index(name)
        out[i] = out[i] + value
    for load in system.loads:
        assert kin is not None
        frame = kin.frames[load.body]
        rot = frame.rotation if load.in_body_frame else sp.eye(3)
        if load.force is not None:
            force = rot * sp.Matrix(load.force)
            where = kin.point(load.body, load.at)
            jac = kin.point_jacobian(load.body, where)
            if load.reaction_body is not None and load.reaction_body != GROUND:
                jac = jac - kin.point_jacobian(load.reaction_body, where)
            for i in range(n):
                out[i] = out[i] + (force.T * jac[:, i])[0]
        if load.torque is not None:
            torque = rot * sp.Matrix(load.torque)
            jw = frame.jw
            if load.reaction_body is not None and load.reaction_body != GROUND:
                jw = jw - kin.frames[load.reaction_body].jw
            for i in range(n):
                out[i] = out[i] + (torque.T * jw[:, i])[0]
    for damper in system.dampers:
        if damper.extension is not None:
            ext = damper.extension
            rate = sum((sp.diff(ext, q[j]) * qd[j] for j in range(n)), sp.Integer(0))
            for i in range(n):
                out[i] = out[i] - damper.coefficient * rate * sp.diff(ext, q[i])
        else:
            length2 = _length_between(damper, kin)
            # L_dot = (dL^2/dt) / (2 L);  Q_i = -c L_dot dL/dq_i = -c (dL^2/dt)(dL^2/dq_i) / (4 L^2)
            rate2 = sum((sp.diff(length2, q[j]) * qd[j] for j in range(n)), sp.Integer(0))
            for i in range(n):
                out[i] = out[i] - damper.coefficient * rate2 * sp.diff(length2, q[i]) / (4 * length2)
    return [tidy_rates(e, qd) if not e.has(sp.Pow) or e.is_polynomial(*qd) else sp.factor_terms(e) for e in out]
