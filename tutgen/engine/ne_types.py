"""The records of a Newton-Euler derivation (tutgen.engine.newton_euler builds them): each body's motion,
free-body diagram and balances, the joint reactions, the equation of each coordinate, and for planar
systems the scalar form of tutgen.engine.planar_ne."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import StrEnum

import sympy as sp

from tutgen.engine.derivation import Check
from tutgen.model.system import JointKind

Vec = sp.ImmutableMatrix
ZERO = sp.ImmutableMatrix.zeros(3, 1)


PROJECTION_REMARK = (
    "The bodies are placed by positions and orientations, not by joints, so the constraint forces are not "
    "named: the Newton–Euler route projects each body's D'Alembert force -m a_G and couple "
    "-(I_G alpha + omega x I_G omega), with the applied forces, onto the partial velocities dv_G/dq_dot_i and "
    "domega/dq_dot_i (virtual work, Kane's method); the constraint forces do no work and drop out."
)


class NEMethod(StrEnum):
    RECURSIVE = "recursive"  # a serial chain of relative joints: outward then inward recursion
    PER_BODY = "per_body"  # a tree of joints (branches, absolute angles): free body by free body
    PROJECTION = "projection"  # bodies placed by positions: D'Alembert forces on partial velocities


@dataclass(frozen=True)
class AppliedLoad:
    """One applied force (acting through ``point``) and/or couple on a body, world components."""

    name: str  # "gravity", "load 'push'", "reaction of load 'motor'", "spring 'tie'", "damper 'drag'"
    force: Vec
    point: Vec
    torque: Vec


@dataclass(frozen=True)
class Motion:
    """A body's angular velocity and acceleration and the acceleration of its centre of mass.

    ``origin_acceleration`` (of the body frame's origin) is set by the outward recursion; ``via``
    says how the values were found (the joint of the recursion, or differentiation of v_G)."""

    body: str
    angular_velocity: Vec
    angular_acceleration: Vec
    origin_acceleration: Vec | None
    acceleration: Vec
    via: str


@dataclass(frozen=True)
class BodyBalance:
    """One body's free-body diagram with D'Alembert's inertial terms, and its two balances.

    ``force_balance`` and ``moment_balance`` (about ``point``) are the sums of all forces and moments
    on the body, with the reactions as the unknown symbols of :class:`JointReaction`; each equals 0.
    """

    body: str
    mass: sp.Expr
    about: str  # the moment point in words: "the origin of joint 'pivot'", "G"
    point: Vec
    loads: tuple[AppliedLoad, ...]
    inertial_force: Vec  # -m a_G, at G
    inertial_moment: Vec  # -(I_G alpha + omega x I_G omega)
    joint_in: str | None  # the joint that places this body: it receives +(R, N)
    joints_out: tuple[str, ...]  # the joints to its children: it receives -(R, N)
    force_balance: Vec
    moment_balance: Vec


@dataclass(frozen=True)
class JointReaction:
    """What the parent exerts on the child through one joint, solved in q, q_dot, q_ddot.

    ``moment`` is about ``point`` (the child frame's origin). ``along_axis`` is the projection that the
    coordinate's equation uses: z . N for a revolute joint, z . R for a prismatic one."""

    joint: str
    kind: JointKind
    parent: str
    child: str
    coordinate: str | None
    axis: Vec  # world components
    point: Vec
    force: Vec
    moment: Vec
    unknown_force: Vec  # the symbols that stand for R_j in the balances
    unknown_moment: Vec
    along_axis: sp.Expr | None


@dataclass(frozen=True)
class ConstraintReaction:
    """A constraint's force in the Newton-Euler balances (issue 21), in its multipliers.

    A loop-closing pin (``kind`` "pin") carries a force through the pin: its loop-closure equations are
    gap = r_parent(parent_at) - r_child(child_at) = 0, so A^T lambda is the generalized force of the force
    ``on_parent`` = (lambda_x, lambda_y, lambda_z) applied at the parent's point and its opposite
    ``on_child`` = -lambda at the child's point (Newton's third law); ``on_child`` is the pin's reaction in
    the convention of :class:`JointReaction` (what the parent exerts on the child). A constraint given as
    an expression (``kind`` "generalized") names no force on a body: its generalized force
    ``generalized_force`` = (A^T lambda)_i for its own rows enters each coordinate's equation as a drive does.
    """

    name: str  # the loop-closing joint, or the spec's constraint
    kind: str  # "pin" or "generalized"
    constraints: tuple[str, ...]  # the constraints (loop-closure equations) whose multipliers these are
    multipliers: tuple[sp.Symbol, ...]
    generalized_force: tuple[sp.Expr, ...]  # its share of A^T lambda, per coordinate
    parent: str | None = None  # a pin: the bodies it joins
    child: str | None = None
    point: Vec | None = None  # a pin: where it is on the parent (world components)
    child_point: Vec | None = None  # and on the child (the same point on the constrained motion)
    on_parent: Vec | None = None  # the pin's force on the parent: the multipliers
    on_child: Vec | None = None  # on the child: minus the multipliers


@dataclass(frozen=True)
class CoordinateEquation:
    """The equation of one coordinate after the reactions are eliminated.

    ``projection`` is z_j . N_j (or z_j . R_j) minus the moments of subtrees behind absolute angles
    (``subtracted``), or, for the projection method, the sum over the bodies of the D'Alembert and
    applied forces on the partial velocities, negated; ``generalized_force`` is Q_i at the joint.
    ``equation`` = projection - generalized_force, in Lagrange's contract (H q_ddot + C + G - Q)_i."""

    coordinate: str
    joint: str | None
    subtracted: tuple[str, ...]
    projection: sp.Expr
    generalized_force: sp.Expr
    equation: sp.Expr
    terms: tuple[tuple[str, sp.Expr], ...] = ()  # (body, its share of the projection)


class ForceKind(StrEnum):
    """What a force on a planar free body is, for its wording (and for tests that look one up)."""

    GRAVITY = "gravity"
    LOAD = "load"  # an applied force or couple of the spec's loads
    LOAD_REACTION = "load_reaction"  # the reaction of a load on its reaction body (a motor's stator)
    SPRING = "spring"
    DAMPER = "damper"
    DRIVE = "drive"  # a generalized force given at a coordinate, acting at its joint
    DRIVE_REACTION = "drive_reaction"  # its reaction on the body the coordinate is measured from
    ROTOR = "rotor"  # the reflected inertia n^2 J_m of a geared motor, taken from the drive
    REACTION = "reaction"  # a joint's constraint force/couple on its child (the unknowns)
    REACTION_ON_PARENT = "reaction_on_parent"  # the same, reversed, on the parent (third law)
    LOOP_REACTION = "loop_reaction"  # a loop-closing pin's force on its child: minus the multipliers
    LOOP_REACTION_ON_PARENT = "loop_reaction_on_parent"  # the pin's force on its parent: the multipliers
    CONSTRAINT = "constraint"  # a spec constraint's generalized force (A^T lambda)_i at a coordinate's joint
    INERTIAL_FORCE = "inertial_force"  # D'Alembert's -m a_G, at G
    INERTIAL_COUPLE = "inertial_couple"  # D'Alembert's -I_G alpha


@dataclass(frozen=True)
class PlanarForce:
    """One force and/or couple on a body of a planar system, in the plane's world components.

    The plain shape a free-body diagram needs: ``point`` is where the force acts (world x, y),
    ``force`` its (F_x, F_y), ``torque`` the couple about z (counter-clockwise positive). A joint
    reaction's components are the unknown symbols of :class:`PlanarReaction`."""

    name: str  # in words: "gravity", "load 'push'", "spring 'wall'", "reaction at joint 'pivot'"
    kind: ForceKind
    source: str | None  # the spec name of the load, spring, damper or joint it comes from
    point: tuple[sp.Expr, sp.Expr]
    force: tuple[sp.Expr, sp.Expr]
    torque: sp.Expr


@dataclass(frozen=True)
class PlanarBalance:
    """A body's free-body diagram (every force on it, D'Alembert's included) and its three scalar
    balances, each = 0: sum of x forces, of y forces, and of moments about ``point``."""

    body: str
    about: str  # the moment point in words: "the pivot, joint 'pivot'", "joint 'slider'"
    joint: str  # the joint whose point is the moment point (the joint that places this body)
    point: tuple[sp.Expr, sp.Expr]
    forces: tuple[PlanarForce, ...]
    sum_fx: sp.Expr
    sum_fy: sp.Expr
    sum_m: sp.Expr


@dataclass(frozen=True)
class PlanarReaction:
    """What the parent exerts on the child through a joint, in the plane: the unknowns the balances
    hold and, solved last, their values in q, q_dot, q_ddot.

    A revolute joint transmits a force (R_x, R_y) through its pivot; a prismatic one a force N
    normal to its axis (along ``normal`` = z x axis) and a couple M; a fixed one both components and a
    couple. What acts along a joint's own motion (its drive) is not a reaction: it is listed among
    the applied forces."""

    joint: str
    kind: JointKind
    parent: str
    child: str
    point: tuple[sp.Expr, sp.Expr]
    normal: tuple[sp.Expr, sp.Expr] | None  # prismatic: the direction of N
    unknowns: tuple[sp.Symbol, ...]
    values: tuple[sp.Expr, ...]  # each unknown solved, in the same order
    force: tuple[sp.Expr, sp.Expr]  # the solved force on the child, world components
    moment: sp.Expr  # the solved couple on the child (0 for a revolute joint)
    solved_from: str  # in words: which balances of the child give it


@dataclass(frozen=True)
class Contribution:
    """One body's balance taken into a coordinate's equation (the virtual motion of that coordinate
    alone): ``kind`` "moment" (its moments about the joint's point), "force_moment" (its forces'
    moment about the joint's point when it is carried at ``via``, behind an absolute angle, without
    turning) or "force" (its forces along the prismatic joint's axis)."""

    body: str
    kind: str
    via: str | None  # the absolute joint it is carried by ("force_moment")
    expr: sp.Expr  # with the reaction unknowns, as the body's balance gives it


@dataclass(frozen=True)
class EliminationStep:
    """The equation of one coordinate with the reactions eliminated: the balances of the bodies that
    its virtual motion moves, added so that every reaction inside that part cancels (third law) and the
    reaction at the joint itself does no work (it passes through the pivot, or is normal to the slide).
    ``result`` = sum of the contributions = Q_i - (H q_ddot + C + G)_i = 0; ``equation`` is its negative,
    Lagrange's contract."""

    coordinate: str
    joint: str
    contributions: tuple[Contribution, ...]
    eliminated: tuple[sp.Symbol, ...]  # the reaction unknowns that cancel
    result: sp.Expr
    equation: sp.Expr


@dataclass(frozen=True)
class PlanarNewtonEuler:
    """Newton-Euler as it is taught for a planar system (every motion in the x-y plane): per body its
    free-body diagram and three scalar balances, then the elimination equation by equation (tips
    first), then the reactions solved last."""

    balances: tuple[PlanarBalance, ...]
    steps: tuple[EliminationStep, ...]
    reactions: tuple[PlanarReaction, ...]
    equations_of_motion: sp.ImmutableMatrix  # Lagrange's contract, coordinates' order


@dataclass(frozen=True)
class NewtonEuler:
    """The Newton-Euler derivation of one spec, checked against Lagrange's."""

    method: NEMethod
    motions: tuple[Motion, ...]
    bodies: tuple[BodyBalance, ...]
    reactions: tuple[JointReaction, ...]
    equations: tuple[CoordinateEquation, ...]
    equations_of_motion: sp.ImmutableMatrix  # (H q_ddot + C + G - Q)_i, each = 0, Lagrange's order and sign
    agreement: Check
    remarks: tuple[str, ...] = ()
    planar: PlanarNewtonEuler | None = None  # the scalar form, when every motion is in the x-y plane
    # issue 21: a constrained spec's constraint reactions, in its multipliers; its equations are then
    # (H q_ddot + C + G - Q - A^T lambda)_i, and ``reduction`` checks them with the reduced route's lambda
    constraint_reactions: tuple[ConstraintReaction, ...] = ()
    reduction: Check | None = None

    @property
    def agrees_with_lagrange(self) -> bool:
        return self.agreement.passed


def group_rates(expr: sp.Expr, rates: list[sp.Symbol], simplify: Callable[[sp.Expr], sp.Expr]) -> sp.Expr:
    """Group an expression by monomials in the rates, highest first (the order of ``tidy_rates``),
    and simplify each coefficient. Splitting the terms directly is much cheaper than building a
    ``Poly`` over trigonometric coefficients; an expression that is not a polynomial in the rates
    (a damper divides by a length) is only expanded and its common factors pulled out."""
    e = sp.expand(expr)
    if not e.is_polynomial(*rates):
        return sp.factor_terms(e)
    groups: dict[tuple[int, ...], list[sp.Expr]] = {}
    for term in sp.Add.make_args(e):
        coeff, mono = term.as_independent(*rates, as_Add=False)
        powers = mono.as_powers_dict()
        key = tuple(int(powers.get(r, 0)) for r in rates)
        groups.setdefault(key, []).append(coeff)
    # a damper between two points divides by the squared distance: cancel such fractions first, as
    # tidy_rates' Poly over a fraction field does for Lagrange's route
    rational = any(p.exp.is_negative and p.exp.is_integer and p.base.free_symbols for p in e.atoms(sp.Pow))
    out = []
    for key in sorted(groups, reverse=True):
        mono = sp.Mul(*[r**k for r, k in zip(rates, key, strict=True)])
        coeff = sp.Add(*groups[key])
        if rational:
            coeff = sp.factor_terms(sp.cancel(coeff))
        out.append(simplify(coeff) * mono)
    return sp.Add(*out)
