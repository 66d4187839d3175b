"""Momentum: each body's linear momentum and angular momentum about its centre of mass G and about the
fixed world origin O, in world and in body axes; the totals; the rate of change of the total angular
momentum about O, which is the moment of every external force about O (so the supports must provide it
less what gravity and the loads give: a rotor's bearing moment); and the conserved quantities.

    p = m v_G,    H_G = R J_G R^T omega  (body axes: J_G R^T omega),    H_O = r_G x m v_G + H_G,

with R the body's rotation (world from body) and J_G its inertia tensor about G in body axes. Time
derivatives are taken by the chain rule, d/dt = sum q_dot dq + q_ddot dq_dot.

Conserved: the momentum p_i = dL/dq_dot_i conjugate to a cyclic coordinate (one absent from L whose
generalized force Q_i is 0); the energy T + U when every force is conservative (Q = 0: no dampers,
loads or generalized forces, and nothing depends on time explicitly).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from tutgen.engine.derivation import Derivation
from tutgen.engine.tidy import tidy
from tutgen.limits import checkpoint

__all__ = ["BodyMomentum", "Conserved", "Momentum", "momentum"]


@dataclass(frozen=True)
class BodyMomentum:
    """One body's momenta, world components unless named ``_body`` (the body's own axes)."""

    name: str
    linear: sp.ImmutableMatrix  # m v_G
    angular_com: sp.ImmutableMatrix  # H_G
    angular_com_body: sp.ImmutableMatrix  # H_G in body axes, J_G omega_body
    angular_origin: sp.ImmutableMatrix  # H_O


@dataclass(frozen=True)
class Conserved:
    """A conserved quantity: its name, its value, and why it is conserved."""

    name: str  # "p_phi", "E"
    value: sp.Expr
    why: str


@dataclass(frozen=True)
class Momentum:
    """The momenta of every body, their totals, dH_O/dt and the moments that make it, and what is conserved."""

    bodies: tuple[BodyMomentum, ...]
    linear: sp.ImmutableMatrix  # total p
    angular_origin: sp.ImmutableMatrix  # total H_O
    angular_rate: sp.ImmutableMatrix  # dH_O/dt = the total external moment about O
    gravity_moment: sp.ImmutableMatrix  # sum r_G x m g about O
    support_moment: sp.ImmutableMatrix  # dH_O/dt - gravity's moment: the supports and the loads
    steady_support_moment: sp.ImmutableMatrix  # the same when every q_ddot = 0 (running steadily)
    conserved: tuple[Conserved, ...]


def _tidy(m: sp.MatrixBase) -> sp.ImmutableMatrix:
    # expanded, not simplified: simplify folds sin(beta) cos(phi) products into cos(2 beta - phi) sums
    return sp.ImmutableMatrix(m.applyfunc(lambda e: tidy(sp.expand(e))))


def _ddt(d: Derivation, m: sp.MatrixBase) -> sp.Matrix:
    s = d.system
    out = sp.zeros(*m.shape)
    for c in s.coordinates:
        out += m.diff(c.q) * c.qd + m.diff(c.qd) * c.qdd
    return out


def momentum(d: Derivation) -> Momentum:
    """The momenta of a derivation with kinematics (see the module's docstring)."""
    checkpoint("momentum")
    bodies = []
    total_p = sp.zeros(3, 1)
    total_h = sp.zeros(3, 1)
    gravity_moment = sp.zeros(3, 1)
    g = d.system.gravity if d.system.gravity is not None else sp.zeros(3, 1)
    for bi, k in zip(d.inertia, d.kinematics, strict=True):
        r = sp.Matrix(k.rotation)
        p = bi.mass * sp.Matrix(k.velocity)
        omega_body = r.T * sp.Matrix(k.angular_velocity)
        h_body = sp.Matrix(bi.inertia_com) * omega_body
        h_g = r * h_body
        h_o = sp.Matrix(k.com).cross(p) + h_g
        bodies.append(BodyMomentum(bi.name, _tidy(p), _tidy(h_g), _tidy(h_body), _tidy(h_o)))
        total_p += p
        total_h += h_o
        gravity_moment += sp.Matrix(k.com).cross(bi.mass * sp.Matrix(g))
    rate = _tidy(_ddt(d, total_h))
    gm = _tidy(gravity_moment)
    return Momentum(
        bodies=tuple(bodies),
        linear=_tidy(total_p),
        angular_origin=_tidy(total_h),
        angular_rate=rate,
        gravity_moment=gm,
        support_moment=_tidy(rate - gm),
        steady_support_moment=_tidy((rate - gm).xreplace({c.qdd: 0 for c in d.system.coordinates})),
        conserved=conserved(d),
    )


def conserved(d: Derivation) -> tuple[Conserved, ...]:
    """The momenta of cyclic coordinates, and the energy where every force is conservative."""
    s = d.system
    out: list[Conserved] = []
    lagrangian = d.lagrangian if d.lagrangian is not None else sp.Integer(0)
    q_vec = d.generalized_forces if d.generalized_forces is not None else sp.zeros(len(s.coordinates), 1)
    for i, c in enumerate(s.coordinates):
        if not lagrangian.has(c.q) and q_vec[i] == 0:
            out.append(
                Conserved(
                    f"p_{c.name}",
                    tidy(sp.simplify(sp.diff(lagrangian, c.qd))),
                    f"{c.name} is cyclic: L does not contain it and Q_{c.name} = 0, so d/dt(dL/d{c.qd.name}) = 0",
                )
            )
    if all(e == 0 for e in q_vec) and d.kinetic_energy is not None and d.potential_energy is not None:
        out.append(
            Conserved(
                "E",
                tidy(d.kinetic_energy + d.potential_energy),
                "every force is conservative (Q = 0) and nothing depends on time explicitly, so E = T + U",
            )
        )
    return tuple(out)
