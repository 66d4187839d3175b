"""Lagrange's route, from the bodies to the energies and to Lagrange's equations term by term.

The stages here follow a worked solution; :func:`tutgen.engine.pipeline.derive` runs them in order:

- :func:`energies`: each body's kinetic energy (translation + rotation) and potential energy of
  gravity, and H(q). H is assembled from the velocity Jacobians, H = sum m J_v^T J_v + J_w^T R J_G R^T J_w
  (plus a motor rotor's reflected inertia n^2 J_m on H_ii), one small entry at a time, so no step needs a
  global simplify; T = q_dot^T H q_dot / 2. A spec may instead give T and U, and T must then be a
  quadratic form in the velocities.
- :func:`lagrange_equations`: d/dt(dL/dq_dot_i) - dL/dq_i = Q_i, its three terms for each coordinate.

The matrix form and its Christoffel symbols are :mod:`tutgen.engine.matrix_form`; what springs, dampers,
loads and rotors add is :mod:`tutgen.engine.forces`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp

from tutgen.engine.derivation import BodyEnergy, LagrangeTerms
from tutgen.engine.forces import rotors
from tutgen.engine.inertia import BodyInertia
from tutgen.engine.kinematics import BodyKinematics, Kinematics, total_derivative
from tutgen.engine.tidy import tidy, tidy_rates
from tutgen.errors import DerivationError
from tutgen.limits import checkpoint
from tutgen.model.system import System

__all__ = ["Energies", "energies", "lagrange_equations"]


@dataclass(frozen=True)
class Energies:
    """T, the potential energy before springs, and H(q); per body when the spec has bodies."""

    mass_matrix: sp.Matrix  # H, every entry tidied
    kinetic_energy: sp.Expr  # T = q_dot^T H q_dot / 2
    potential_energy: sp.Expr  # of gravity (bodies) or as given; the springs' is added later
    bodies: tuple[BodyEnergy, ...] = ()
    kinematics: tuple[BodyKinematics, ...] = ()


def energies(system: System, inertia: tuple[BodyInertia, ...], kin: Kinematics | None) -> Energies:
    """The energies of a spec: from its bodies and their kinematics ``kin``, or as the spec gives them
    (``kin`` is None exactly when the spec gives ``kinetic_energy``)."""
    q = [c.q for c in system.coordinates]
    qd = [c.qd for c in system.coordinates]
    n = len(q)
    if system.kinetic_energy is not None:
        t_total = sp.expand(system.kinetic_energy)
        h = sp.Matrix(n, n, lambda i, j: tidy(sp.diff(t_total, qd[i], qd[j])))
        rest = sp.expand(t_total - (sp.Matrix([qd]) * h * sp.Matrix(qd))[0] / 2)
        if rest != 0 or any(h_ij.has(*qd) for h_ij in h):
            raise DerivationError(
                "the kinetic energy must be a quadratic form in the velocities, T = q_dot^T H(q) q_dot / 2; "
                f"this one has the extra terms {rest}",
                system.origin,
            )
        u_given = sp.expand(system.potential_energy) if system.potential_energy is not None else sp.Integer(0)
        return Energies(h, t_total, u_given)
    assert kin is not None
    h = sp.zeros(n, n)
    u_total = sp.Integer(0)
    qd_vec = sp.Matrix(qd)
    g_vec = sp.Matrix(system.gravity) if system.gravity is not None else None
    bodies: list[BodyEnergy] = []
    for bi in inertia:
        checkpoint(f"energies of body '{bi.name}'")
        bk = kin.bodies[bi.name]
        if len(bi.parts) > 1:
            # part by part (sum of m_p J_p^T J_p, each part's own inertia): the centre of mass,
            # a quotient by the total mass, then never enters the expressions
            h_trans = sp.zeros(n, n)
            grav = sp.Integer(0)
            for part in bi.parts:
                r_p = kin.point(bi.name, part.centroid)
                j_p = r_p.jacobian(q)
                h_trans += (j_p.T * j_p).applyfunc(lambda e, m=part.mass: tidy(m * e))
                if g_vec is not None:
                    grav += -part.mass * (g_vec.T * r_p)[0]
            own = sum((sp.Matrix(part.inertia_centroid) for part in bi.parts), sp.zeros(3, 3))
            h_rot = _rotational_block(own, bk.rotation, bk.jw)
            grav = tidy(grav)
        else:
            h_trans = (bk.jv.T * bk.jv).applyfunc(lambda e, m=bi.mass: tidy(m * e))
            h_rot = _rotational_block(bi.inertia_com, bk.rotation, bk.jw)
            grav = tidy(-bi.mass * (g_vec.T * sp.Matrix(bk.com))[0]) if g_vec is not None else sp.Integer(0)
        h += h_trans + h_rot
        v2 = tidy_rates((qd_vec.T * (bk.jv.T * bk.jv).applyfunc(tidy) * qd_vec)[0], qd)
        t_trans = tidy_rates((qd_vec.T * h_trans * qd_vec)[0] / 2, qd)
        t_rot = tidy_rates((qd_vec.T * h_rot * qd_vec)[0] / 2, qd)
        u_total += grav
        bodies.append(BodyEnergy(bi.name, v2, t_trans, t_rot, tidy_rates(t_trans + t_rot, qd), grav))
    # motor rotors: each adds its reflected inertia n^2 J_m to H_ii, i.e. n^2 J_m q_dot_i^2 / 2 to T
    # (so L, and Lagrange's equation term by term, carry it too)
    for i, reflected in rotors(system):
        h = sp.Matrix(h)
        h[i, i] += reflected
    h = h.applyfunc(tidy)
    t_total = tidy_rates((qd_vec.T * h * qd_vec)[0] / 2, qd)
    return Energies(h, t_total, u_total, tuple(bodies), tuple(kin.bodies[b.name] for b in system.bodies))


def lagrange_equations(
    system: System, lagrangian: sp.Expr, forces: Sequence[sp.Expr]
) -> tuple[tuple[LagrangeTerms, ...], list[sp.Expr]]:
    """Lagrange's equation for each coordinate, term by term: d/dt(dL/dq_dot_i) - dL/dq_i = Q_i.

    Returns the terms and the equations as d/dt(dL/dq_dot_i) - dL/dq_i - Q_i (each = 0), which the
    matrix form must reproduce.
    """
    q = [c.q for c in system.coordinates]
    qd = [c.qd for c in system.coordinates]
    qdd = [c.qdd for c in system.coordinates]
    terms: list[LagrangeTerms] = []
    equations: list[sp.Expr] = []
    for i, coord in enumerate(system.coordinates):
        checkpoint(f"Lagrange's equation for {coord.name}")
        p_i = tidy_rates(sp.diff(lagrangian, qd[i]), qd)
        dp_i = tidy_rates(total_derivative(p_i, q, qd, qdd), [*qdd, *qd])
        f_i = tidy_rates(sp.diff(lagrangian, q[i]), qd)
        terms.append(LagrangeTerms(coord.name, p_i, dp_i, f_i, forces[i]))
        equations.append(dp_i - f_i - forces[i])
    return tuple(terms), equations


def _rotational_block(inertia: sp.MatrixBase, rotation: sp.MatrixBase, jw: sp.MatrixBase) -> sp.Matrix:
    """J_w^T (R J R^T) J_w for an inertia J in body axes, computed as (R^T J_w)^T J (R^T J_w)."""
    n = jw.shape[1]
    if sp.Matrix(inertia) == sp.zeros(3, 3) or n == 0:
        return sp.zeros(n, n)
    jw_body = (sp.Matrix(rotation).T * sp.Matrix(jw)).applyfunc(tidy)
    return (jw_body.T * sp.Matrix(inertia) * jw_body).applyfunc(tidy)
