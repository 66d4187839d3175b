"""The validated model of a problem: frozen values holding sympy objects, no YAML left.

Conventions (used by every stage after this one):
- The world (inertial) frame has axes x, y, z; vectors are 3x1 ``sp.ImmutableMatrix`` in world
  components unless a field says "in the body frame".
- A body's frame has its origin at ``position`` and its axes rotated by ``rotation`` (world from
  body: r_world = position + rotation * r_body).
- Inertia tensors use J_ab = integral (r^2 delta_ab - a b) dm, so the off-diagonal J_xy = -integral x y dm.
- Coordinates are plain symbols q with companions q_dot and q_ddot; a time derivative is taken by the
  chain rule (no sympy dynamicsymbols), so results print in the spec grammar (``x_dot``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum

import sympy as sp

from tutgen.errors import Location
from tutgen.model.analysis import Analysis
from tutgen.model.figure import FigureConfig
from tutgen.model.marking import Marking
from tutgen.model.simulation import Simulation
from tutgen.spec.units import Dimension

Vector = sp.ImmutableMatrix
Matrix3 = sp.ImmutableMatrix

GROUND = "ground"
#: the time t in a prescribed motion (``coordinates: {phi: {prescribed: omega*t}}``); no spec may declare ``t``
TIME = sp.Symbol("t", real=True)


@dataclass(frozen=True)
class Parameter:
    """A named quantity; ``value`` is its exact SI value, or None when it stays symbolic."""

    name: str
    symbol: sp.Symbol
    value: sp.Expr | None
    latex: str
    description: str | None
    unit: str | None
    origin: Location
    dimension: Dimension | None = None  # from its unit or declared dimension; None when unknown
    # the allowed values (exact, SI) when the spec gives a range or choices (variants of a tutorial
    # sheet, docs/sheets.md); ``value`` is then the nominal one
    choices: tuple[sp.Expr, ...] | None = None


@dataclass(frozen=True)
class Coordinate:
    """A generalized coordinate with its velocity and acceleration symbols."""

    name: str
    q: sp.Symbol
    qd: sp.Symbol
    qdd: sp.Symbol
    latex: str
    description: str | None
    dimension: str | None  # "length", "angle" or unknown
    origin: Location
    # the same as a Dimension, also when only the joint says it (revolute: angle, prismatic: length)
    si_dimension: Dimension | None = None
    # a driven coordinate (`prescribed:` or `rate:`): its motion q(t), an expression of TIME and the
    # parameters; None for a degree of freedom (tutgen.engine.prescribed)
    prescribed: sp.Expr | None = None

    @property
    def is_prescribed(self) -> bool:
        return self.prescribed is not None


class Shape(StrEnum):
    POINT = "point"
    BOX = "box"
    CYLINDER = "cylinder"
    HOLLOW_CYLINDER = "hollow_cylinder"
    THIN_CYLINDER = "thin_cylinder"
    ROD = "rod"
    DISC = "disc"
    SPHERE = "sphere"
    SPHERICAL_SHELL = "spherical_shell"
    GENERAL = "general"


@dataclass(frozen=True)
class Part:
    """One primitive of a body, placed in the body frame.

    ``dimensions`` keeps the shape's own measures by name (``radius``, ``length``, ``size``) for the
    worked solution; ``axis`` is the unit symmetry axis (axisymmetric shapes) in body axes;
    ``rotation`` turns a box's own axes into the body's (identity for every other shape; a general
    part gives its inertia in the body's axes directly).
    """

    name: str
    shape: Shape
    mass: sp.Expr | None  # None: computed as density * volume
    density: sp.Expr | None
    dimensions: tuple[tuple[str, sp.Expr | tuple[sp.Expr, ...]], ...]
    at: Vector
    axis: Vector | None
    rotation: Matrix3
    inertia: Matrix3 | None  # given directly (shape: general), about the centroid in body axes
    origin: Location


@dataclass(frozen=True)
class Body:
    """A body and its mass distribution; where it is comes from joints or from ``position``/``rotation``."""

    name: str
    parts: tuple[Part, ...]
    position: Vector | None  # explicit kinematics (no joint places this body)
    rotation: Matrix3 | None
    # explicit kinematics: (axis, angle) per elementary rotation, each about the body's axes as
    # already turned by the rotations before it (intrinsic)
    rotation_rates: tuple[tuple[Vector, sp.Expr], ...]
    origin: Location
    is_simple: bool = False  # given as mass/com/inertia rather than parts


class JointKind(StrEnum):
    REVOLUTE = "revolute"
    PRISMATIC = "prismatic"
    FIXED = "fixed"


@dataclass(frozen=True)
class Joint:
    """A joint of the kinematic tree: the child's frame relative to the parent's.

    child frame = parent frame, moved to ``origin`` (parent axes), turned by ``rotation`` (fixed), then
    by the joint motion about/along ``axis`` (a unit vector in the axes after ``rotation``). With
    ``absolute`` the angle is measured from the world frame: the child's rotation is the joint
    rotation alone, about the (constant) world direction of the axis.
    """

    name: str
    kind: JointKind
    parent: str
    child: str
    coordinate: Coordinate | None
    axis: Vector
    origin_offset: Vector
    rotation: Matrix3
    offset: sp.Expr
    absolute: bool
    origin: Location
    # a motor driving this joint through a gearbox: rotor inertia J_m about its own axis and gear
    # ratio n (joint speed = rotor speed / n); it adds the reflected inertia n^2 J_m to H_ii of the
    # joint's coordinate (the rotor's gyroscopic coupling with the links is neglected, as in Spong)
    rotor_inertia: sp.Expr | None = None
    gear_ratio: sp.Expr | None = None

    @property
    def reflected_inertia(self) -> sp.Expr | None:
        if self.rotor_inertia is None:
            return None
        n = self.gear_ratio if self.gear_ratio is not None else sp.Integer(1)
        return n**2 * self.rotor_inertia


@dataclass(frozen=True)
class Endpoint:
    body: str  # a body name or GROUND
    at: Vector


@dataclass(frozen=True)
class Spring:
    name: str
    stiffness: sp.Expr
    free_length: sp.Expr
    between: tuple[Endpoint, Endpoint] | None
    extension: sp.Expr | None
    origin: Location


@dataclass(frozen=True)
class Damper:
    name: str
    coefficient: sp.Expr
    between: tuple[Endpoint, Endpoint] | None
    extension: sp.Expr | None
    origin: Location


@dataclass(frozen=True)
class Load:
    name: str
    body: str
    force: Vector | None
    torque: Vector | None
    at: Vector
    in_body_frame: bool
    reaction_body: str | None
    origin: Location


class Ask(StrEnum):
    INERTIA = "inertia"
    KINETIC_ENERGY = "kinetic_energy"
    POTENTIAL_ENERGY = "potential_energy"
    LAGRANGIAN = "lagrangian"
    LAGRANGE_EQUATIONS = "lagrange_equations"
    EQUATIONS_OF_MOTION = "equations_of_motion"
    MATRIX_FORM = "matrix_form"
    CHRISTOFFEL = "christoffel"
    SIMULATION = "simulation"  # the plots of a run of the spec's `simulate:` section (never by default)
    EQUILIBRIA = "equilibria"
    LINEARIZATION = "linearization"
    MOMENTUM = "momentum"
    STEADY_MOTION = "steady_motion"  # relative equilibria at constant rates of the cyclic coordinates


#: the items of ``ask`` that a spec must name: the default (everything that applies) is the equations
#: of motion and what leads to them, not the analysis that follows them (tutgen.engine.analysis) nor a
#: numerical simulation (tutgen.sim)
OPT_IN_ASK = frozenset({Ask.SIMULATION, Ask.EQUILIBRIA, Ask.LINEARIZATION, Ask.MOMENTUM, Ask.STEADY_MOTION})


class Method(StrEnum):
    """A formulation a worked solution presents (the spec's ``methods:``)."""

    LAGRANGE = "lagrange"
    NEWTON_EULER = "newton_euler"


@dataclass(frozen=True)
class DHRow:
    """One row of an arm's Denavit–Hartenberg table as the spec wrote it (SI values; a joint's variable
    is its coordinate's symbol, plus any constant offset)."""

    link: str
    theta: sp.Expr
    d: sp.Expr
    a: sp.Expr
    alpha: sp.Expr


@dataclass(frozen=True)
class ArmTable:
    """The `arm:` table of a spec, kept for printing: its links are already bodies and joints of the
    system. ``convention`` is "standard" (Spong, Paul: A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)) or
    "modified" (Craig: A_i = Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i), the row holding α_{i-1}, a_{i-1})."""

    convention: str
    rows: tuple[DHRow, ...]

    def transform(self, i: int) -> sp.ImmutableMatrix:
        """The homogeneous transform of row ``i`` (0-based), frame i-1 -> frame i, by the convention."""
        row = self.rows[i]
        ct, st, ca, sa = sp.cos(row.theta), sp.sin(row.theta), sp.cos(row.alpha), sp.sin(row.alpha)
        if self.convention == "standard":
            rows = [
                [ct, -st * ca, st * sa, row.a * ct],
                [st, ct * ca, -ct * sa, row.a * st],
                [0, sa, ca, row.d],
                [0, 0, 0, 1],
            ]
        else:
            rows = [
                [ct, -st, 0, row.a],
                [st * ca, ct * ca, -sa, -sa * row.d],
                [st * sa, ct * sa, ca, ca * row.d],
                [0, 0, 0, 1],
            ]
        return sp.ImmutableMatrix(rows)


class ChristoffelConvention(StrEnum):
    """Which Christoffel symbols a worked solution prints (the spec's ``conventions: {christoffel: …}``)."""

    BOTH = "both"
    #: the tutorial's (Asada and Slotine's) h_ijk = dH_ij/dq_k - 1/2 dH_jk/dq_i, not symmetric in j, k
    ASADA_SLOTINE = "asada_slotine"
    #: the symmetric symbols of the first kind c_ijk = 1/2 (dH_ij/dq_k + dH_ik/dq_j - dH_jk/dq_i)
    FIRST_KIND = "first_kind"


@dataclass(frozen=True)
class Conventions:
    """The notational choices of a worked solution (the spec's ``conventions:``)."""

    christoffel: ChristoffelConvention = ChristoffelConvention.BOTH


class ConstraintKind(StrEnum):
    POSITION = "position"  # holonomic: f(q) = 0
    VELOCITY = "velocity"  # nonholonomic: a(q) . q_dot = 0, linear and homogeneous in the rates


@dataclass(frozen=True)
class Constraint:
    """One constraint of the spec's ``constraints:``: ``expression`` = 0. A position constraint is a function
    of the coordinates (and parameters); a velocity constraint is linear and homogeneous in the rates."""

    name: str
    kind: ConstraintKind
    expression: sp.Expr
    origin: Location


@dataclass(frozen=True)
class LoopJoint:
    """A revolute joint that closes a loop (``closes_loop: true``): the point ``parent_at`` of the parent
    (parent frame) and ``child_at`` of the child (child frame) coincide. Both bodies are placed by the
    tree; the joint adds the loop-closure equations, one per world component that is not identically
    zero (two for a planar loop)."""

    name: str
    parent: str
    child: str
    parent_at: Vector
    child_at: Vector
    origin: Location


@dataclass(frozen=True)
class Given:
    """What a question states besides its statement and data (the spec's ``given:``)."""

    coordinates: bool = True  # False: the question leaves the generalized coordinates to the student


@dataclass(frozen=True)
class System:
    """A validated problem, ready to derive."""

    title: str
    statement: str | None
    source: str
    parameters: tuple[Parameter, ...]
    coordinates: tuple[Coordinate, ...]
    bodies: tuple[Body, ...]
    joints: tuple[Joint, ...]
    gravity: Vector | None
    springs: tuple[Spring, ...] = ()
    dampers: tuple[Damper, ...] = ()
    loads: tuple[Load, ...] = ()
    generalized_forces: tuple[tuple[str, sp.Expr], ...] = ()  # (coordinate name, expression)
    kinetic_energy: sp.Expr | None = None  # given directly (energy: section)
    potential_energy: sp.Expr | None = None
    ask: frozenset[Ask] = field(default_factory=frozenset)
    # the formulations to present, in the spec's order (Lagrange's route is derived whatever they are)
    methods: tuple[Method, ...] = (Method.LAGRANGE,)
    origin: Location = field(default_factory=lambda: Location("<spec>"))
    # how many significant figures decimals are printed with (None: the renderer's default, 4)
    significant_figures: int | None = None
    figure: FigureConfig | None = None  # the spec's `figure:` section (drawing configuration, own picture)
    simulation: Simulation | None = None  # the spec's `simulate:` section (tutgen simulate)
    marking: Marking | None = None  # the spec's `marking:` section: what `tutgen check` marks
    arm: ArmTable | None = None  # the spec's `arm:` table as written (its links are in bodies and joints)
    question_title: str | None = None  # the question sheet's title, when it differs from ``title``
    given: Given = field(default_factory=Given)
    conventions: Conventions = field(default_factory=Conventions)
    analysis: Analysis | None = None  # the spec's `analysis:` section (equilibrium, inputs)
    # the spec's `constraints:` in order, and the coordinates kept independent when the equations are
    # reduced (`independent_coordinates:`; the others are the dependent ones, solved from the constraints)
    constraints: tuple[Constraint, ...] = ()
    independent_coordinates: tuple[str, ...] = ()
    loop_joints: tuple[LoopJoint, ...] = ()  # joints with `closes_loop: true`, in spec order

    @property
    def values(self) -> dict[sp.Symbol, sp.Expr]:
        """Numeric parameter values, to substitute into symbolic results."""
        return {p.symbol: p.value for p in self.parameters if p.value is not None}

    def body(self, name: str) -> Body:
        return next(b for b in self.bodies if b.name == name)

    @property
    def is_constrained(self) -> bool:
        """Whether the coordinates are tied by constraints or loop-closing joints (tutgen.engine.constraints)."""
        return bool(self.constraints or self.loop_joints)

    @property
    def prescribed_coordinates(self) -> tuple[Coordinate, ...]:
        """The driven coordinates (`prescribed:` or `rate:`), in order; the others are the degrees of freedom."""
        return tuple(c for c in self.coordinates if c.prescribed is not None)

    @property
    def has_dynamics(self) -> bool:
        return bool(self.coordinates)
