"""The shape of a spec (format v1): every key, its type and its meaning, declared in one place.

The pydantic models below are the reference of the spec format: the JSON Schema that
``tutgen schema`` prints is generated from them, and ``docs/spec-format.md`` follows them.
A spec key, the model field and (later) the template variable share one snake_case name.

Only the *shape* is checked here. Names, expressions, units and cross-references (a joint's
parent must be a body, an expression may use only declared names) are checked in
:mod:`tutgen.spec.validate`, which turns a :class:`SpecDoc` into a :class:`tutgen.model.System`
(one builder module of :mod:`tutgen.spec.builders` per top-level key); pydantic's errors on the
shape become located messages in :mod:`tutgen.spec.schema_errors`.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BeforeValidator, Field, StrictBool
from pydantic_core import PydanticCustomError

from tutgen.spec.schema_types import (
    EXPR_SCHEMA,
    SIGNIFICANT_FIGURES_RANGE,
    AxisName,
    DimensionName,
    Expr,
    Name,
    SpecModel,
    Text,
    Vector3,
    describe,
    significant_figures_value,
)

SPEC_FORMAT_VERSION = 1


def _plain_number(value: Any) -> Any:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise PydanticCustomError("tutgen_number", "expected a number, found {found}", {"found": describe(value)})
    return value


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _number_list(value: Any) -> Any:
    if not isinstance(value, list) or not value or not all(_is_number(v) for v in value):
        raise PydanticCustomError(
            "tutgen_numbers", "expected a non-empty list of numbers, found {found}", {"found": describe(value)}
        )
    return value


def _number_pair(value: Any) -> Any:
    if not isinstance(value, list) or len(value) != 2 or not all(_is_number(v) for v in value):
        raise PydanticCustomError(
            "tutgen_range", "expected a range [lo, hi] of two numbers, found {found}", {"found": describe(value)}
        )
    return value


class ParameterSpec(SpecModel):
    """A named quantity of the problem: symbolic (no value) or numeric (a value, with a unit)."""

    value: Expr | None = Field(
        None, description="A number, or a number with a unit ('15 cm'); omitted: the parameter stays symbolic."
    )
    latex: Text | None = Field(
        None,
        description="How to typeset the name, e.g. '\\tau_1': letters, digits, _ ^ { } ' , spaces, Greek "
        "letters and a few commands (\\dot, \\hat, \\mathrm, ...), never raw TeX (default: from the name, "
        "Ixx1 as I_{xx,1}).",
    )
    description: Text | None = Field(
        None, description="What the parameter is, for the reader; may hold maths between dollars ($m_1 g$)."
    )
    dimension: DimensionName | None = Field(
        None, description="The physical dimension; a value whose unit has another dimension is an error."
    )
    range: Annotated[list[Any], BeforeValidator(_number_pair)] | None = Field(
        None,
        description="Variants (tutgen sheet): the allowed values lo, lo + step, ... up to hi, as [lo, hi] "
        "(numbers, in `unit`); `value` (if given) is the nominal one, else the middle one.",
    )
    step: Annotated[Any, BeforeValidator(_plain_number)] | None = Field(
        None, description="The step of `range` (a positive number, in `unit`); default (hi - lo)/10."
    )
    choices: Annotated[list[Any], BeforeValidator(_number_list)] | None = Field(
        None,
        description="Variants (tutgen sheet): the allowed values, as a list of numbers in `unit`; `value` "
        "(if given) is the nominal one, else the first.",
    )
    unit: Text | None = Field(None, description="The unit of `range`, `step` and `choices` ('kg', 'cm', 'N*m').")


def _parameters(value: Any) -> Any:
    """Shorthands: a list of names (all symbolic); `name:` (symbolic); `name: 15 cm` (a value)."""
    if isinstance(value, list):
        out: dict[Any, Any] = {}
        for item in value:
            if not isinstance(item, str):
                raise PydanticCustomError(
                    "tutgen_names", "expected a list of names, found {found} in it", {"found": describe(item)}
                )
            out[item] = {}
        return out
    if isinstance(value, dict):
        return {k: ({} if v is None else {"value": v} if not isinstance(v, dict) else v) for k, v in value.items()}
    return value


class CoordinateSpec(SpecModel):
    """A generalized coordinate q_i. Its velocity is written NAME_dot and its acceleration NAME_ddot."""

    latex: Text | None = Field(
        None, description="How to typeset the name, e.g. '\\theta_1' (the same whitelist as a parameter's)."
    )
    description: Text | None = Field(
        None, description="What the coordinate measures, for the reader; may hold maths between dollars."
    )
    dimension: Literal["length", "angle"] | None = Field(
        None, description="'length' or 'angle'; inferred from the joint that uses it when omitted."
    )
    prescribed: Expr | None = Field(
        None,
        description="A driven coordinate: its motion as an expression of the time t and the parameters, "
        "e.g. 'omega*t' or 'a*sin(Omega*t)'. It leaves the degrees of freedom; tutgen derives the "
        "equations of the others and the force or torque that drives it (docs/spec-format.md#prescribed).",
    )
    rate: Expr | None = Field(
        None,
        description="A coordinate driven at a constant rate (parameters and numbers): "
        "NAME = initial + rate*t; the same as `prescribed` with that expression.",
    )
    initial: Expr | None = Field(
        None, description="With `rate`: the value at t = 0 (parameters and numbers; default 0)."
    )


def _coordinates(value: Any) -> Any:
    if isinstance(value, list):
        return _parameters(value)
    if isinstance(value, dict):
        return {k: ({} if v is None else v) for k, v in value.items()}
    return value


# ---------------------------------------------------------------------------------------------
# Gravity
# ---------------------------------------------------------------------------------------------


class GravitySpec(SpecModel):
    """Uniform gravity: the acceleration vector, or its magnitude and direction."""

    vector: Vector3 | None = Field(None, description="The acceleration of gravity, e.g. [0, -g, 0].")
    g: Expr | None = Field(None, description="The magnitude, e.g. g or '9.81 m/s^2' (with `direction`).")
    direction: AxisName | Vector3 | None = Field(
        None, description="Where gravity points: '-y', '-z' or a vector (with `g`)."
    )


def _gravity(value: Any) -> Any:
    if isinstance(value, list):
        return {"vector": value}
    return value


# ---------------------------------------------------------------------------------------------
# Rotations, parts and bodies
# ---------------------------------------------------------------------------------------------


class RotationSpec(SpecModel):
    """One elementary rotation about a body-fixed axis by an angle."""

    axis: AxisName | Vector3 = Field(description="'x', 'y', 'z' (or negated), or a vector.")
    angle: Expr = Field(description="The angle: an expression of the coordinates, or '30 deg'.")


Orientation = Annotated[
    list[RotationSpec],
    Field(description="Rotations applied in order, each about the axes as already rotated (intrinsic)."),
]


class _PartBase(SpecModel):
    at: Vector3 | None = Field(None, description="Where the part's centroid is, in the body frame (default origin).")


class _SolidPart(_PartBase):
    mass: Expr | None = Field(None, description="The mass; or give `density`.")
    density: Expr | None = Field(None, description="The density (kg/m^3); the mass is density x volume.")


class PointPart(_PartBase):
    """A point mass."""

    shape: Literal["point"]
    mass: Expr = Field(description="The mass.")


class BoxPart(_SolidPart):
    """A solid rectangular block with edges along the part's axes."""

    shape: Literal["box"]
    size: Vector3 = Field(description="Edge lengths along x, y, z.")
    orientation: Orientation | None = None


class CylinderPart(_SolidPart):
    """A solid circular cylinder."""

    shape: Literal["cylinder"]
    radius: Expr
    length: Expr
    axis: AxisName | Vector3 = Field("z", description="The direction of the cylinder's axis.")


class HollowCylinderPart(_SolidPart):
    """A thick-walled tube (inner radius 0 gives a solid cylinder)."""

    shape: Literal["hollow_cylinder"]
    outer_radius: Expr
    inner_radius: Expr
    length: Expr
    axis: AxisName | Vector3 = Field("z", description="The direction of the tube's axis.")


class ThinShellCylinderPart(_SolidPart):
    """A thin-walled tube (all mass at one radius); needs `mass`."""

    shape: Literal["thin_cylinder"]
    radius: Expr
    length: Expr
    axis: AxisName | Vector3 = Field("z", description="The direction of the tube's axis.")


class RodPart(_SolidPart):
    """A slender rod (its thickness neglected); needs `mass`."""

    shape: Literal["rod"]
    length: Expr
    axis: AxisName | Vector3 = Field("x", description="The direction along the rod.")


class DiscPart(_SolidPart):
    """A thin circular disc (its thickness neglected); needs `mass`."""

    shape: Literal["disc"]
    radius: Expr
    axis: AxisName | Vector3 = Field("z", description="The disc's normal.")


class SpherePart(_SolidPart):
    """A solid sphere."""

    shape: Literal["sphere"]
    radius: Expr


class SphericalShellPart(_SolidPart):
    """A thin spherical shell; needs `mass`."""

    shape: Literal["spherical_shell"]
    radius: Expr


class InertiaSpec(SpecModel):
    """An inertia tensor about the centroid, in the part's (or body's) axes: J_ab = integral (r^2 d_ab - a b) dm."""

    xx: Expr = 0
    yy: Expr = 0
    zz: Expr = 0
    xy: Expr = Field(0, description="J_xy = -integral x y dm (the product of inertia, negated).")
    xz: Expr = 0
    yz: Expr = 0


class GeneralPart(_PartBase):
    """Any rigid part given by its mass and centroidal inertia tensor."""

    shape: Literal["general"]
    mass: Expr
    inertia: InertiaSpec = Field(description="About the part's centroid, in the body's axes.")


Part = Annotated[
    PointPart
    | BoxPart
    | CylinderPart
    | HollowCylinderPart
    | ThinShellCylinderPart
    | RodPart
    | DiscPart
    | SpherePart
    | SphericalShellPart
    | GeneralPart,
    Field(discriminator="shape"),
]

SHAPES = (
    "point",
    "box",
    "cylinder",
    "hollow_cylinder",
    "thin_cylinder",
    "rod",
    "disc",
    "sphere",
    "spherical_shell",
    "general",
)


class BodySpec(SpecModel):
    """A body: a point mass (`mass`, `com`), a rigid body (`mass`, `com`, `inertia`) or a composite of `parts`.

    Its placement comes from `joints` (the body frame is the joint frame) or, without joints, from
    `position` and `orientation` given as expressions of the coordinates.
    """

    mass: Expr | None = Field(None, description="The mass (a point mass unless `inertia` is given).")
    com: Vector3 | None = Field(None, description="The centre of mass in the body frame (default origin).")
    inertia: InertiaSpec | None = Field(None, description="The inertia tensor about the centre of mass.")
    parts: dict[Name, Part] | None = Field(
        None, description="Primitive shapes and point masses that make up the body, each placed in the body frame."
    )
    position: Vector3 | None = Field(
        None, description="Where the body frame's origin is, in the world frame, as expressions of the coordinates."
    )
    orientation: Orientation | None = None
    description: Text | None = None


# ---------------------------------------------------------------------------------------------
# Joints, springs, dampers, loads
# ---------------------------------------------------------------------------------------------


class MotorSpec(SpecModel):
    """A motor driving a joint through a gearbox: its rotor adds the reflected inertia n^2 J_m to H_ii.

    Only the reflected inertia is modelled (the rotor's gyroscopic coupling with the links is
    neglected, as in Spong's and Craig's arm models)."""

    rotor_inertia: Expr = Field(description="J_m, the rotor's moment of inertia about its own axis (kg*m^2).")
    gear_ratio: Expr | None = Field(
        None,
        description="n = rotor speed / joint speed (default 1): dimensionless for a revolute joint, "
        "rad/m for a prismatic one. Must be positive.",
    )


class JointSpec(SpecModel):
    """A joint that places `child` relative to `parent` (a body, or `ground`)."""

    type: Literal["revolute", "prismatic", "fixed"]
    parent: Name = Field(description="A body name, or 'ground'.")
    child: Name = Field(description="The body that this joint moves.")
    coordinate: Name | None = Field(None, description="The coordinate of the joint (none for 'fixed').")
    axis: AxisName | Vector3 = Field(
        "z", description="The joint axis, in the parent's frame as turned by `orientation` (if given)."
    )
    origin: Vector3 | None = Field(None, description="Where the joint is, in the parent's frame (default origin).")
    orientation: Orientation | None = Field(
        None, description="A fixed rotation of the child's frame at the joint, before the joint moves."
    )
    offset: Expr | None = Field(None, description="A constant added to the coordinate (angle or length).")
    angle: Literal["relative", "absolute"] = Field(
        "relative",
        description="'relative': the coordinate is measured from the parent link; 'absolute': from the world "
        "frame (planar arms driven from the base, e.g. through a belt).",
    )
    motor: MotorSpec | None = Field(
        None, description="A motor with a gearbox at this joint: {rotor_inertia: Jm1, gear_ratio: n1}."
    )
    closes_loop: bool = Field(
        False,
        description="A revolute joint that closes a loop (four-bar, slider-crank): it places nothing and has no "
        "coordinate; `origin` on the parent and `child_origin` on the child (both already placed) must coincide, "
        "which gives the loop-closure equations (docs/constraints.md).",
    )
    child_origin: Vector3 | None = Field(
        None, description="A loop-closing joint: where it is, in the child's frame (default origin)."
    )


class DHLinkSpec(SpecModel):
    """One row of a Denavit-Hartenberg table: the joint that moves this link, and the link's mass properties.

    Exactly one of `theta` (revolute) and `d` (prismatic) uses a coordinate, as the coordinate plus an
    optional constant ('q2 + pi/2'); the other is a constant. With `convention: modified` (Craig),
    `a` and `alpha` are the row's a_{i-1} and alpha_{i-1}, as Craig's tables list them.
    `com` and `inertia` are given in this link's DH frame i.
    """

    type: Literal["revolute", "prismatic"] | None = Field(
        None, description="The joint type; by default, from which of `theta` and `d` uses a coordinate."
    )
    theta: Expr = Field(0, description="theta_i: a coordinate (revolute), or a constant angle ('90 deg').")
    d: Expr = Field(0, description="d_i: a coordinate (prismatic), or a constant length.")
    a: Expr = Field(0, description="a_i (standard) or a_{i-1} (modified): a length.")
    alpha: Expr = Field(0, description="alpha_i (standard) or alpha_{i-1} (modified): an angle ('-90 deg').")
    joint: Name | None = Field(None, description="The name of the joint (default: joint<i>, i = 1, 2, ...).")
    mass: Expr | None = Field(None, description="The link's mass (omitted: a massless link).")
    com: Vector3 | None = Field(None, description="The centre of mass, in the link's DH frame i.")
    inertia: InertiaSpec | None = Field(
        None, description="The inertia tensor about the centre of mass, in the axes of the link's DH frame i."
    )
    motor: MotorSpec | None = Field(None, description="A motor with a gearbox driving this row's joint.")
    description: Text | None = None


class ArmSpec(SpecModel):
    """A serial arm as a Denavit-Hartenberg table, one row per link from the base outward.

    Each row becomes a body (named by its key) and the joint that moves it; frame 0 is the world frame.
    standard (Spong, Paul): A_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i);
    modified (Craig): A_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i).
    """

    convention: Literal["standard", "modified"] = Field(
        description="'standard' (Spong, Paul: frame i at the far end of link i) or 'modified' (Craig: frame i "
        "on joint axis i)."
    )
    links: dict[Name, DHLinkSpec] = Field(description="The rows of the table, by link name, from the base outward.")


class EndpointSpec(SpecModel):
    """A point on a body (or on the ground), for springs, dampers and loads."""

    body: Name = Field(description="A body name, or 'ground'.")
    at: Vector3 | None = Field(None, description="The point in that body's frame (default its origin).")


def _endpoint(value: Any) -> Any:
    if isinstance(value, str):
        return {"body": value}
    return value


Endpoint = Annotated[EndpointSpec, BeforeValidator(_endpoint)]


class _ElementSpec(SpecModel):
    between: Annotated[list[Endpoint], Field(min_length=2, max_length=2)] | None = Field(
        None, description="The two attachment points; the elongation is their distance minus `free_length`."
    )
    extension: Expr | None = Field(
        None, description="Or the elongation directly, as an expression of the coordinates (e.g. 'x')."
    )
    description: Text | None = None


class SpringSpec(_ElementSpec):
    """A linear spring: U = k (L - L0)^2 / 2."""

    stiffness: Expr
    free_length: Expr | None = Field(None, description="L0 (with `between`; default 0).")


class DamperSpec(_ElementSpec):
    """A viscous damper: the Rayleigh dissipation D = c (dL/dt)^2 / 2 gives Q_i = -dD/d(q_i_dot)."""

    coefficient: Expr


class LoadSpec(SpecModel):
    """An applied force and/or torque on a body; its reaction (if any) on another body."""

    # not `on:`, which YAML 1.1 tools (PyYAML, some editors) read as the boolean true
    body: Name = Field(description="The body the load acts on.")
    force: Vector3 | None = Field(None, description="The force, in world components unless `frame: body`.")
    torque: Vector3 | None = Field(None, description="The torque, in world components unless `frame: body`.")
    at: Vector3 | None = Field(None, description="Where the force acts, in the body frame (default the origin).")
    frame: Literal["world", "body"] = Field("world", description="The frame the components are given in.")
    reaction_body: Name | None = Field(
        None, description="The body that takes the reaction (a motor's stator), e.g. 'ground'; none if omitted."
    )
    description: Text | None = None


class EnergySpec(SpecModel):
    """A system given directly by its energies (no bodies)."""

    kinetic: Expr = Field(description="T as an expression of the coordinates and their velocities (NAME_dot).")
    potential: Expr | None = Field(None, description="U as an expression of the coordinates (default 0).")


AskItem = Literal[
    "inertia",
    "kinetic_energy",
    "potential_energy",
    "lagrangian",
    "lagrange_equations",
    "equations_of_motion",
    "matrix_form",
    "christoffel",
    "simulation",
    "equilibria",
    "linearization",
    "momentum",
    "steady_motion",
]

MethodItem = Literal["lagrange", "newton_euler"]


class SimulateSpec(SpecModel):
    """What `tutgen simulate` integrates (docs/simulate.md)."""

    t: list[Expr] | None = Field(
        None, description="The interval [start, end] in seconds, e.g. [0, 10] or ['0 s', '2 min'] (default [0, 10])."
    )
    q0: dict[Name, Expr] = Field(
        default_factory=dict, description="The initial value of every coordinate, e.g. {theta: 30 deg, x: 0.1 m}."
    )
    qd0: dict[Name, Expr] = Field(
        default_factory=dict, description="Initial rates, e.g. {theta: 1 rad/s} (default 0 for each coordinate)."
    )
    inputs: dict[Name, Expr] = Field(
        default_factory=dict,
        description="Parameters without a value as expressions of time t, the parameters, the coordinates and "
        "their rates, e.g. {tau: 2*sin(t), F: -k_p*x - k_d*x_dot}.",
    )
    samples: int | None = Field(
        None,
        description="How many equally spaced instants the trajectory is written at (default 1001).",
        ge=2,
        le=1_000_000,
    )


class AnalysisSpec(SpecModel):
    """Where the equilibria and the linearisation are taken (docs/spec-format.md#analysis)."""

    about: dict[Name, Expr] | None = Field(
        None,
        description="The equilibrium to linearise about, e.g. {theta: pi} (coordinates not named are at 0); "
        "without it, each equilibrium found is linearised.",
    )
    inputs: dict[Name, Expr] = Field(
        default_factory=dict,
        description="Parameters without a value that are inputs u, with their value at the equilibrium, e.g. "
        "{F: 0}: the columns of the input matrix B. Other parameters without a value stay symbols.",
    )
    steady: dict[Name, Expr] | None = Field(
        None,
        description="The cyclic coordinates of `ask: [steady_motion]` with their constant rate, e.g. {phi: Omega} "
        "(without it, every cyclic coordinate is found and its rate stays its own symbol, phi_dot).",
    )


class FigureSpec(SpecModel):
    """How the problem's figure is drawn (docs/figures.md)."""

    at: dict[Name, Expr] = Field(
        default_factory=dict,
        description="The drawing's value of some coordinates, e.g. {theta: 30 deg, x: 0.4 m} (default: a pose "
        "where every angle is visibly non-zero).",
    )
    sizes: dict[Name, Expr] = Field(
        default_factory=dict,
        description="The drawing size of symbolic lengths, e.g. {l1: 1 m, l2: 0.6 m} (default: 1 m for a length, "
        "less for offsets and radii).",
    )
    file: Text | None = Field(
        None,
        description="The instructor's own picture (PNG, JPEG, PDF or SVG, at most 10 MiB), a path inside the "
        "spec's folder; shown beside the generated figure, or instead of it with `generated: false`.",
    )
    generated: bool = Field(True, description="Whether tutgen draws the schematic (false: only `file`).")
    view: Literal["auto", "planar", "oblique"] = Field(
        "auto", description="The projection: planar for motion in one plane, oblique for spatial systems."
    )


class GivenSpec(SpecModel):
    """What a question states besides its statement and data."""

    coordinates: StrictBool = Field(
        True,
        description="Whether the question sheet lists the generalized coordinates (false: the student is to "
        "propose them; the worked solution still gives them).",
    )


class ConventionsSpec(SpecModel):
    """The notational choices of the worked solution."""

    christoffel: Literal["both", "asada_slotine", "first_kind"] = Field(
        "both",
        description="Which Christoffel symbols are printed: the tutorial's (Asada and Slotine's) h_ijk = "
        "dH_ij/dq_k - 1/2 dH_jk/dq_i ('asada_slotine'), the symmetric symbols of the first kind c_ijk "
        "('first_kind'), or both (the default). The JSON output always has both.",
    )


class SpecDoc(SpecModel):
    """A tutgen spec: one mechanics problem."""

    tutgen: Literal[1] | None = Field(None, description="The spec format version (1).")
    title: Text = Field(description="The problem's title; may hold maths between dollars.")
    statement: Text | None = Field(
        None,
        description="The problem statement, shown in the worked solution; may hold maths between dollars "
        "in the expression grammar ($T = m v^2/2$), and \\$ for a dollar sign.",
    )
    question_title: Text | None = Field(
        None,
        description="The title on a tutorial's question sheet, when the solution's `title` would give the answer "
        "away (default: `title`); may hold maths between dollars.",
    )
    conventions: ConventionsSpec | None = Field(
        None, description="Notational choices of the worked solution (which Christoffel symbols)."
    )
    given: GivenSpec | None = Field(
        None, description="What the question states: `{coordinates: false}` leaves the coordinates to the student."
    )
    significant_figures: Annotated[int, BeforeValidator(significant_figures_value)] | None = Field(
        None,
        description="How many significant figures decimals are printed with, a whole number from 1 to 15 "
        "(default: the renderer's, 4).",
        json_schema_extra={"minimum": SIGNIFICANT_FIGURES_RANGE[0], "maximum": SIGNIFICANT_FIGURES_RANGE[1]},
    )
    parameters: Annotated[dict[Name, ParameterSpec], BeforeValidator(_parameters)] = Field(
        default_factory=dict,
        description="Named quantities: `m1:` (symbolic), `rho: 7849 kg/m^3` (numeric), or a list of names.",
    )
    coordinates: Annotated[dict[Name, CoordinateSpec], BeforeValidator(_coordinates)] = Field(
        default_factory=dict, description="The generalized coordinates, in order: a list of names or a mapping."
    )
    gravity: Annotated[GravitySpec, BeforeValidator(_gravity)] | None = Field(
        None, description="[0, -g, 0], or {g: g, direction: -y}."
    )
    bodies: dict[Name, BodySpec] = Field(default_factory=dict, description="The bodies, by name.")
    arm: ArmSpec | None = Field(
        None, description="A serial arm as a Denavit-Hartenberg table (its links become bodies and joints)."
    )
    joints: dict[Name, JointSpec] = Field(default_factory=dict, description="The joints of a kinematic tree.")
    springs: dict[Name, SpringSpec] = Field(default_factory=dict)
    dampers: dict[Name, DamperSpec] = Field(default_factory=dict)
    loads: dict[Name, LoadSpec] = Field(default_factory=dict, description="Applied forces and torques.")
    generalized_forces: dict[Name, Expr] = Field(
        default_factory=dict, description="Forces acting along coordinates directly: {x: F, theta: tau}."
    )
    energy: EnergySpec | None = None
    constraints: dict[Name, Expr] = Field(
        default_factory=dict,
        description="Constraints, each an expression that is zero: of the coordinates (holonomic, "
        "`rolling: x - R*phi`) or linear and homogeneous in the rates (nonholonomic, "
        "`x_dot - R*phi_dot*cos(theta)`); docs/constraints.md.",
    )
    independent_coordinates: list[Name] | None = Field(
        None,
        description="With `constraints`: the coordinates the equations are reduced to (one fewer per "
        "constraint; default: the first ones in order); the others are solved from the constraints.",
    )
    ask: list[AskItem] | None = Field(None, description="What to derive (default: everything that applies).")
    methods: list[MethodItem] | None = Field(
        None,
        description="The formulations the worked solution presents: [lagrange] (the default), [newton_euler] "
        "or [lagrange, newton_euler]. Newton-Euler is derived for its agreement check whenever the system "
        "has bodies; its working is printed only when it is listed here.",
    )
    figure: FigureSpec | None = Field(None, description="How the figure is drawn, or the instructor's own picture.")
    simulate: SimulateSpec | None = Field(None, description="Initial conditions and inputs for `tutgen simulate`.")
    analysis: AnalysisSpec | None = Field(
        None,
        description="The equilibrium and the inputs of `ask: [equilibria, linearization]`, and the rates of "
        "`ask: [steady_motion]`.",
    )
    marking: dict[str, Any] | None = Field(
        None,
        description="What `tutgen check` marks: {ask: [result keys], tolerance: {rel_tol, abs_tol, rounded}, "
        "items: {result key: rule}, significant_figures: N} (docs/check.md, the marking key).",
    )


def json_schema() -> dict[str, Any]:
    """The JSON Schema of the spec format (draft 2020-12), for editors."""
    schema = SpecDoc.model_json_schema()
    # the shorthands that the BeforeValidators accept, which pydantic cannot see
    props, defs = schema["properties"], schema["$defs"]
    names = {"type": "array", "items": {"type": "string"}}
    props["parameters"] = {
        "description": props["parameters"]["description"],
        "anyOf": [
            names,
            {
                "type": "object",
                "additionalProperties": {"anyOf": [{"type": "null"}, EXPR_SCHEMA, {"$ref": "#/$defs/ParameterSpec"}]},
            },
        ],
    }
    props["coordinates"] = {
        "description": props["coordinates"]["description"],
        "anyOf": [
            names,
            {
                "type": "object",
                "additionalProperties": {"anyOf": [{"type": "null"}, {"$ref": "#/$defs/CoordinateSpec"}]},
            },
        ],
    }
    vector = {"type": "array", "items": EXPR_SCHEMA, "minItems": 3, "maxItems": 3}
    props["gravity"] = {
        "description": props["gravity"]["description"],
        "anyOf": [vector, {"$ref": "#/$defs/GravitySpec"}, {"type": "null"}],
    }
    endpoint = {"anyOf": [{"type": "string"}, {"$ref": "#/$defs/EndpointSpec"}]}
    for element in ("SpringSpec", "DamperSpec"):
        between = defs[element]["properties"]["between"]
        between["anyOf"][0]["items"] = endpoint
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    # tutgen.schemas.schema_id("spec"): a URN, as the project has no web home to name
    schema["$id"] = "urn:tutgen:schema:spec:1"
    schema["title"] = "tutgen spec, format v1"
    return schema
