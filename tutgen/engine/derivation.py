"""The engine's output: a frozen :class:`Derivation` that carries every intermediate result.

Renderers and the answer checker read these values; they never derive anything again.
Expressions here are symbolic (parameters as symbols); :meth:`Derivation.numeric` substitutes
the parameters that have values.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import sympy as sp

from tutgen.engine.inertia import BodyInertia, BodyPrincipal
from tutgen.engine.kinematics import BodyKinematics
from tutgen.engine.steps import Step
from tutgen.model.simulation import SimulationSummary
from tutgen.model.system import Method, System

if TYPE_CHECKING:  # newton_euler.py imports this module
    from tutgen.engine.analysis import Analysis
    from tutgen.engine.constraints import ConstrainedDynamics
    from tutgen.engine.newton_euler import NewtonEuler
    from tutgen.engine.potential import PotentialSource
    from tutgen.engine.prescribed import PrescribedMotion
    from tutgen.engine.recursive import NestedDynamics


@dataclass(frozen=True)
class LagrangeTerms:
    """The three terms of Lagrange's equation for one coordinate q_i:
    d/dt(dL/dq_i_dot) - dL/dq_i = Q_i."""

    coordinate: str
    dL_dqd: sp.Expr
    ddt_dL_dqd: sp.Expr
    dL_dq: sp.Expr
    generalized_force: sp.Expr


@dataclass(frozen=True)
class BodyEnergy:
    """One body's kinetic energy (translation + rotation) and potential energy of gravity."""

    name: str
    speed_squared: sp.Expr  # |v_G|^2
    # m |v_G|^2 / 2 and omega . J_G omega / 2; for a body of several parts, the sums over its parts of
    # m_p |v_p|^2 / 2 and omega . J_p omega / 2 (the same total, without dividing by the total mass)
    translational: sp.Expr
    rotational: sp.Expr
    kinetic: sp.Expr
    gravitational: sp.Expr


@dataclass(frozen=True)
class Check:
    """A property the engine verified on its own result."""

    name: str
    passed: bool
    detail: str


@dataclass(frozen=True)
class Derivation:
    """Everything tutgen derived for one spec, in teaching order."""

    system: System
    inertia: tuple[BodyInertia, ...] = ()
    principal: tuple[BodyPrincipal, ...] = ()  # per body, about the body frame's origin and about G
    kinematics: tuple[BodyKinematics, ...] = ()
    energies: tuple[BodyEnergy, ...] = ()
    spring_energies: tuple[tuple[str, sp.Expr], ...] = ()
    potential_sources: tuple[PotentialSource, ...] = ()  # U term by term, each with its datum
    kinetic_energy: sp.Expr | None = None
    potential_energy: sp.Expr | None = None
    lagrangian: sp.Expr | None = None
    lagrange_terms: tuple[LagrangeTerms, ...] = ()
    generalized_forces: sp.ImmutableMatrix | None = None
    mass_matrix: sp.ImmutableMatrix | None = None
    coriolis_vector: sp.ImmutableMatrix | None = None
    coriolis_matrix: sp.ImmutableMatrix | None = None
    gravity_vector: sp.ImmutableMatrix | None = None
    equations_of_motion: sp.ImmutableMatrix | None = None  # (H q_ddot + C + G - Q)_i, each = 0
    # tutorial's h_ijk, 0-based; a large serial arm's are converted when first read (engine/lazytable.py)
    christoffel: Mapping[tuple[int, int, int], sp.Expr] = field(default_factory=dict)
    christoffel_first_kind: Mapping[tuple[int, int, int], sp.Expr] = field(default_factory=dict)
    mass_matrix_determinant: sp.Expr | None = None
    remarks: tuple[str, ...] = ()
    checks: tuple[Check, ...] = ()
    newton_euler: NewtonEuler | None = None  # the same equations body by body, checked against Lagrange's
    method: str = "lagrange"  # what the reader sees: "both", "lagrange" or "newton-euler" (as `methods`)
    methods: tuple[Method, ...] = (Method.LAGRANGE,)  # the formulations presented, in order
    # the worked solution's steps in teaching order (tutgen.engine.steps): what `ask` and `methods` call
    # for, with what they depend on; the renderers print a section only if its step is here
    steps: tuple[Step, ...] = ()
    # serial arms: the same H, C q_dot and G as a straight-line program of named intermediates
    # (tutgen.engine.recursive.NestedDynamics), printed instead of entries too long to read
    program: NestedDynamics | None = None
    # `ask: [simulation]`: the run of the spec's `simulate` section, attached after the derivation by
    # tutgen/sim/solution.py (the engine does not integrate); None until then, and when not asked
    simulation: SimulationSummary | None = None
    # `ask: [equilibria, linearization]`: the rest configurations and the linear models (engine/analysis)
    analysis: Analysis | None = None
    # the spec's `constraints:`: the equations with Lagrange's multipliers and reduced to the independent
    # coordinates (tutgen.engine.constraints); the fields above are those of the unconstrained coordinates
    constraints: ConstrainedDynamics | None = None
    # the spec's prescribed coordinates (`prescribed:`, `rate:`): the equations of the free coordinates with
    # the motion substituted and each drive force (tutgen.engine.prescribed); the fields above are those of
    # every coordinate as free
    prescribed: PrescribedMotion | None = None

    def has_step(self, kind: str) -> bool:
        """Whether the worked solution has a step of this kind (a :class:`~tutgen.engine.steps.StepKind`)."""
        return any(step.kind == kind for step in self.steps)

    @property
    def values(self) -> dict[sp.Symbol, sp.Expr]:
        return self.system.values

    def numeric(self, expr: sp.Expr) -> sp.Expr:
        """Substitute the parameters that have numeric values (exact)."""
        values = self.values
        if not values or not hasattr(expr, "subs"):
            return expr
        return expr.subs(values)
