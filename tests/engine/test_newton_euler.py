"""Newton-Euler beside Lagrange: the tutorial's problem 3 both ways, the reactions, the agreement check on
every spec and named model, and random spatial chains against sympy.physics.mechanics' KanesMethod.

The tutorial's answers are read from ``shared/seed/answers.yaml``; the reference for the random chains
is built from the validated model (joint axes, offsets, masses, inertias) with sympy's own frames,
never from tutgen's kinematics.
"""

from __future__ import annotations

import dataclasses
import random
from functools import cache
from pathlib import Path
from typing import Any

import mpmath
import pytest
import sympy as sp
import yaml
from hypothesis import given
from hypothesis import strategies as st
from sympy.physics.mechanics import KanesMethod, Point, ReferenceFrame, RigidBody, dynamicsymbols, inertia

from tests.conftest import SEED, SPECS, all_specs, few_examples, solved
from tests.models import spec_models, system_of
from tutgen.engine.newton_euler import PROJECTION_REMARK, NEMethod, derive_newton_euler
from tutgen.engine.pipeline import derive
from tutgen.engine.serial import is_large_serial_chain
from tutgen.engine.tidy import is_zero
from tutgen.errors import EXIT_METHODS_DISAGREE, AgreementError, DerivationError
from tutgen.model.system import OPT_IN_ASK, Ask, JointKind
from tutgen.render.markdown import render_markdown
from tutgen.spec.expr import parse_expression

ANSWERS = SEED / "answers.yaml"
TUTORIAL = SPECS / "tutorial-1"
P03 = TUTORIAL / "p03-cart-pendulum.yaml"


def names(system: Any) -> dict[str, sp.Expr]:
    table: dict[str, sp.Expr] = {p.name: p.symbol for p in system.parameters}
    for c in system.coordinates:
        table[c.name], table[f"{c.name}_dot"], table[f"{c.name}_ddot"] = c.q, c.qd, c.qdd
    return table


def same(system: Any, expected: str | sp.Expr, derived: Any) -> bool:
    """Equal as expressions; ``derived`` may be a JSON string or a sympy expression."""
    table = names(system)
    e = parse_expression(expected, table) if isinstance(expected, str) else expected
    d = parse_expression(derived, table) if isinstance(derived, str) else sp.sympify(derived)
    return is_zero(e - d)[0]


@cache
def problem3() -> dict[str, Any]:
    data = yaml.safe_load(ANSWERS.read_text(encoding="utf-8"))
    return next(p for p in data["problems"] if int(p["id"]) == 3)


# ---------------------------------------------------------------------------------------------
# Tutorial problem 3, derived both ways
# ---------------------------------------------------------------------------------------------


@pytest.mark.skipif(not ANSWERS.exists(), reason=f"the seed answer key is not at {ANSWERS}")
@pytest.mark.parametrize("coordinate", ["x", "theta"])
def test_newton_euler_problem3_equations_match_answer_key(coordinate: str) -> None:
    system, _, doc = solved(str(P03))
    ne = doc["results"]["newton_euler"]
    eq = next(e for e in problem3()["answers"]["equations_of_motion"] if e["coordinate"] == coordinate)
    i = [c.name for c in system.coordinates].index(coordinate)
    # the key says lhs == force; the contract is the expression equal to zero, lhs - force
    assert same(system, f"({eq['lhs']}) - ({eq['force']})", ne["equations_of_motion"][i])


def test_newton_euler_problem3_pivot_reaction_is_m2_times_ap_plus_g() -> None:
    """The tutorial's reconstruction: the cart pushes on the pendulum with R = m2 (a_p + g j)."""
    system, _, doc = solved(str(P03))
    t = names(system)
    x_dd, th, th_d, th_dd = t["x_ddot"], t["theta"], t["theta_dot"], t["theta_ddot"]
    m2, length, g = t["m2"], t["l"], t["g"]
    a_p = sp.Matrix(
        [
            x_dd + length * th_dd * sp.cos(th) - length * th_d**2 * sp.sin(th),
            length * th_dd * sp.sin(th) + length * th_d**2 * sp.cos(th),
            0,
        ]
    )
    expected = m2 * (a_p + sp.Matrix([0, g, 0]))
    pivot = doc["results"]["newton_euler"]["reaction_forces"]["pivot"]
    assert len(pivot["force"]) == 3 and len(pivot["moment"]) == 3
    for k in range(3):
        assert same(system, expected[k], str(pivot["force"][k])), f"R_pivot[{'xyz'[k]}] = {pivot['force'][k]}"
    # a frictionless pin: no moment about x or y; about z, tau plus the moment that drives theta
    assert pivot["moment"][:2] == [0, 0]


def test_newton_euler_problem3_cart_balance_gives_the_x_equation() -> None:
    """Cart, horizontal forces: F - k x - R_x - m1 x_ddot = 0 is the x equation (R from the pivot)."""
    system, d, _ = solved(str(P03))
    t = names(system)
    pivot = next(r for r in d.newton_euler.reactions if r.joint == "pivot")
    cart_balance = t["F"] - t["k"] * t["x"] - pivot.force[0] - t["m1"] * t["x_ddot"]
    assert is_zero(d.newton_euler.equations_of_motion[0] + cart_balance)[0]


def test_newton_euler_problem3_method_and_balances() -> None:
    _, d, _ = solved(str(P03))
    ne = d.newton_euler
    assert ne.method is NEMethod.RECURSIVE
    assert [b.body for b in ne.bodies] == ["cart", "pendulum"]
    pendulum = ne.bodies[1]
    assert pendulum.joint_in == "pivot" and pendulum.joints_out == ()
    assert pendulum.about == "the origin of joint 'pivot'"
    assert [ld.name for ld in pendulum.loads] == ["gravity", "load 'motor'"]
    assert [ld.name for ld in ne.bodies[0].loads] == ["gravity", "load 'push'", "reaction of load 'motor'"]
    # the motor's reaction acts on the cart: opposite torques
    assert ne.bodies[0].loads[2].torque == -pendulum.loads[1].torque
    # -m a_G of the end mass
    assert all(is_zero(e)[0] for e in pendulum.inertial_force + pendulum.mass * ne.motions[1].acceleration)


def vanishes_at_random_states(expr: sp.Expr, seed: int = 7) -> bool:
    """expr == 0 at three random rational states (every symbol in (0.3, 2.7)); cheap for big 3-D terms."""
    rng = random.Random(seed)
    free = sorted(expr.free_symbols, key=lambda x: x.name)
    f = sp.lambdify(free, expr, "mpmath")
    with mpmath.workdps(30):  # 30 digits: rounding stays far below the tolerance
        for _ in range(3):
            if abs(f(*(mpmath.mpf(rng.randint(300, 2700)) / 1000 for _ in free))) > 1e-15:
                return False
    return True


def balance_residuals(ne: Any) -> list[sp.Expr]:
    """Every body's force and moment balance with the solved reactions put in: all must vanish."""
    values: dict[sp.Symbol, sp.Expr] = {}
    for r in ne.reactions:
        values.update(zip(r.unknown_force, r.force, strict=True))
        values.update(zip(r.unknown_moment, r.moment, strict=True))
    return [e.xreplace(values) for b in ne.bodies for e in (*b.force_balance, *b.moment_balance)]


@pytest.mark.parametrize(
    "spec",
    ["p03-cart-pendulum", "p05-rr-arm", "p07-belt-driven-arm", "p08-spatial-rr", "p09-pr-manipulator"],
)
def test_newton_euler_reactions_satisfy_every_balance(spec: str) -> None:
    _, d, _ = solved(str(TUTORIAL / f"{spec}.yaml"))
    assert all(is_zero(e)[0] for e in balance_residuals(d.newton_euler))


@pytest.mark.parametrize("spec", ["p03-cart-pendulum", "p05-rr-arm", "p08-spatial-rr", "p09-pr-manipulator"])
def test_newton_euler_joint_torque_is_the_reaction_along_the_axis(spec: str) -> None:
    """Recursive route: each coordinate's equation is z . N_j (z . R_j when prismatic) minus Q_i."""
    _, d, _ = solved(str(TUTORIAL / f"{spec}.yaml"))
    ne = d.newton_euler
    by_joint = {r.joint: r for r in ne.reactions}
    for eq in ne.equations:
        r = by_joint[eq.joint]
        along = (r.axis.T * (r.moment if r.kind is JointKind.REVOLUTE else r.force))[0]
        assert is_zero(r.along_axis - along)[0]
        assert is_zero(eq.equation - (r.along_axis - eq.generalized_force))[0]
        assert is_zero(eq.projection - sum((t for _, t in eq.terms), sp.Integer(0)))[0]


def test_newton_euler_absolute_angle_subtracts_the_moment_behind_it() -> None:
    """Problem 7: theta2 is absolute (motor 2 on the base), so theta1's equation is the moment about
    the shoulder minus link 2's moment about the elbow (the tutorial's 'minus_forces')."""
    system, d, _ = solved(str(TUTORIAL / "p07-belt-driven-arm.yaml"))
    ne = d.newton_euler
    assert ne.method is NEMethod.PER_BODY
    first, second = ne.equations
    assert (first.joint, first.subtracted) == ("shoulder", ("elbow",))
    assert (second.joint, second.subtracted) == ("elbow", ())
    shoulder, elbow = ne.reactions
    assert is_zero(first.equation - (shoulder.moment[2] - elbow.moment[2]))[0]
    # both motors are loads from the ground: tau1 + tau2 cross the cut at the shoulder
    t = names(system)
    assert is_zero(sp.diff(shoulder.moment[2], t["tau2"]) + 1)[0]
    assert any("absolute" in r for r in ne.remarks)


@pytest.mark.parametrize(
    ("spec", "method"),
    [
        pytest.param("p02-pivoted-rod", NEMethod.RECURSIVE, id="p02-rigid-rod"),
        pytest.param("p04-rp-arm", NEMethod.PROJECTION, id="p04-positions"),
        pytest.param("p06-two-prismatic", NEMethod.PROJECTION, id="p06-positions"),
        pytest.param("p07-belt-driven-arm", NEMethod.PER_BODY, id="p07-absolute"),
        pytest.param("p08-spatial-rr", NEMethod.RECURSIVE, id="p08-spatial"),
    ],
)
def test_newton_euler_route(spec: str, method: NEMethod) -> None:
    system, d, _ = solved(str(TUTORIAL / f"{spec}.yaml"))
    if d.newton_euler is None:  # p02 asks for T only: no equations of motion, no Newton-Euler
        d = derive(dataclasses.replace(system, ask=frozenset(Ask) - OPT_IN_ASK))
    ne = d.newton_euler
    assert ne.method is method
    if method is NEMethod.PROJECTION:
        assert PROJECTION_REMARK in ne.remarks
        assert ne.reactions == ()
    else:
        assert PROJECTION_REMARK not in ne.remarks
        assert {r.joint for r in ne.reactions} == {j.name for j in d.system.joints}


# ---------------------------------------------------------------------------------------------
# Agreement with Lagrange on every spec and named model
# ---------------------------------------------------------------------------------------------


def assert_agrees(system: Any, d: Any) -> None:
    ne = d.newton_euler
    assert ne is not None
    assert ne.agrees_with_lagrange
    assert ne.equations_of_motion.shape == d.equations_of_motion.shape
    # a constrained spec's: with its constraint reactions, Lagrange's with multipliers (issue 21)
    reactions = d.constraints.constraint_forces if d.constraints is not None else [0] * len(system.coordinates)
    for i, coord in enumerate(system.coordinates):
        zero, _ = is_zero(ne.equations_of_motion[i] - d.equations_of_motion[i] + reactions[i])
        assert zero, f"{coord.name}: NE {ne.equations_of_motion[i]} vs Lagrange {d.equations_of_motion[i]}"
    assert any(c.name == "newton_euler_equals_lagrange" and c.passed for c in d.checks)


@pytest.mark.parametrize("path", all_specs(), ids=lambda p: str(Path(p).relative_to(SPECS).with_suffix("")))
def test_newton_euler_agrees_with_lagrange_on_spec(path: Path) -> None:
    system, d, doc = solved(str(path))
    if system.kinetic_energy is not None or not system.bodies:
        assert d.newton_euler is None  # a given energy has no bodies to balance
        return
    if len(system.coordinates) < 2:
        pytest.skip("one coordinate: Newton-Euler runs, but the issue asks for the multi-DOF specs")
    if is_large_serial_chain(system):
        # the serial-arm route prints no Newton-Euler derivation (pages long); it checks its matrix form
        # against a numeric recursive Newton-Euler pass instead (and tests/engine/test_pinocchio.py)
        assert d.newton_euler is None
        assert any(c.name == "matrix_form_equals_newton_euler" and c.passed for c in d.checks)
        return
    assert_agrees(system, d)
    if "newton_euler" in doc["results"]:
        out = doc["results"]["newton_euler"]
        assert out["agrees_with_lagrange"] is True
        assert out["method"] in {m.value for m in NEMethod}
        assert len(out["equations_of_motion"]) == len(system.coordinates)
        assert set(out["reaction_forces"]) == {r.joint for r in d.newton_euler.reactions}


@pytest.mark.parametrize("name", sorted(spec_models()))
def test_newton_euler_agrees_with_lagrange_on_model(name: str) -> None:
    system = system_of(spec_models()[name])
    d = derive(system)
    assert_agrees(system, d)
    if d.newton_euler.method is not NEMethod.PROJECTION:
        assert all(vanishes_at_random_states(e) for e in balance_residuals(d.newton_euler))


def branching_tree() -> dict[str, Any]:
    """A tree on a base fixed in place: a trunk carrying two branches, one at an absolute angle with a
    slider and a welded cap on it; a spring between the branches, a motor between them, a body-frame
    force reacting on the trunk, and a damper along the slider's coordinate."""
    return {
        "tutgen": 1,
        "title": "Branching tree",
        "parameters": ["m1", "m2", "m3", "a", "b", "k", "c", "g", "tau", "J"],
        "coordinates": ["t1", "t2", "t3", "s"],
        "gravity": [0, "-g", 0],
        "bodies": {
            "base": {"mass": "m1", "position": ["a", 0, 0]},
            "trunk": {"mass": "m1", "com": [0, "a/2", 0], "inertia": {"xx": "J", "yy": "J", "zz": "J"}},
            "left": {"mass": "m2", "com": ["b", 0, 0]},
            "right": {"mass": "m3", "com": ["b", 0, 0]},
            "tip": {"mass": "m2"},
            "cap": {"mass": "m3"},
        },
        "joints": {
            "root": {"type": "revolute", "parent": "base", "child": "trunk", "axis": "z", "coordinate": "t1"},
            "lj": {
                "type": "revolute",
                "parent": "trunk",
                "child": "left",
                "axis": "z",
                "origin": [0, "a", 0],
                "coordinate": "t2",
            },
            "rj": {
                "type": "revolute",
                "parent": "trunk",
                "child": "right",
                "axis": "z",
                "origin": [0, "a", 0],
                "coordinate": "t3",
                "angle": "absolute",
            },
            "sl": {
                "type": "prismatic",
                "parent": "right",
                "child": "tip",
                "axis": "x",
                "origin": ["b", 0, 0],
                "coordinate": "s",
            },
            "weld": {"type": "fixed", "parent": "tip", "child": "cap", "origin": [0, "b", 0]},
        },
        "springs": {"tie": {"stiffness": "k", "between": [{"body": "left", "at": ["b", 0, 0]}, {"body": "cap"}]}},
        "dampers": {"dash": {"coefficient": "c", "extension": "s"}},
        "loads": {
            "motor": {"body": "left", "torque": [0, 0, "tau"], "reaction_body": "right"},
            "pull": {"body": "cap", "force": [0, "tau", 0], "frame": "body", "reaction_body": "trunk"},
        },
    }


def test_newton_euler_branching_tree_with_absolute_branch() -> None:
    system = system_of(branching_tree())
    d = derive(system)
    assert_agrees(system, d)
    ne = d.newton_euler
    assert ne.method is NEMethod.PER_BODY
    assert [(e.joint, e.subtracted) for e in ne.equations] == [("root", ("rj",)), ("lj", ()), ("rj", ()), ("sl", ())]
    assert "base" not in {b.body for b in ne.bodies}  # fixed in place: its support is not a joint
    assert {r.joint for r in ne.reactions} == {"root", "lj", "rj", "sl", "weld"}
    assert all(is_zero(e)[0] for e in balance_residuals(ne))


# ---------------------------------------------------------------------------------------------
# The hook, the error and the output
# ---------------------------------------------------------------------------------------------


def test_derive_method_lagrange_presents_lagrange_and_still_checks_newton_euler() -> None:
    system, _, _ = solved(str(P03))
    d = derive(system, method="lagrange")
    assert d.newton_euler is not None and not d.has_step("newton_euler")
    assert [c.name for c in d.checks].count("newton_euler_equals_lagrange") == 1
    ne = derive(system, method="newton-euler")
    assert ne.has_step("newton_euler") and not ne.has_step("lagrange_equations")


def test_derive_rejects_an_unknown_method() -> None:
    system, _, _ = solved(str(P03))
    with pytest.raises(ValueError, match="newton-euler"):
        derive(system, method="kane")


def test_newton_euler_not_run_for_a_given_energy() -> None:
    system, d, doc = solved(str(TUTORIAL / "p10-given-kinetic-energy.yaml"))
    assert d.newton_euler is None and "newton_euler" not in doc["results"]
    with pytest.raises(DerivationError, match="bodies"):
        derive_newton_euler(system, d)


def test_newton_euler_disagreement_raises_agreement_error() -> None:
    system, d, _ = solved(str(P03))
    wrong = dataclasses.replace(
        d, equations_of_motion=d.equations_of_motion + sp.ImmutableMatrix([0, sp.Symbol("tau") / 2])
    )
    with pytest.raises(AgreementError) as err:
        derive_newton_euler(system, wrong)
    assert err.value.coordinate == "theta"
    assert err.value.exit_code == EXIT_METHODS_DISAGREE == 5
    assert isinstance(err.value, DerivationError)
    assert "Newton-Euler equation for 'theta' differs from Lagrange's" in str(err.value)
    assert str(err.value).startswith(f"{system.coordinates[1].origin}: error:")


def test_newton_euler_json_contract() -> None:
    system, _, doc = solved(str(P03))
    out = doc["results"]["newton_euler"]
    # the keys of the contract, in order (`planar`, additive: p03 presents Newton–Euler, docs/json-output.md)
    keys = ["method", "equations_of_motion", "reaction_forces", "agrees_with_lagrange", "remarks", "planar"]
    assert list(out) == keys
    assert out["method"] == "recursive"
    assert list(out["reaction_forces"]) == ["slider", "pivot"]
    assert all(isinstance(v, str) for v in out["equations_of_motion"])
    # same order and sign as Lagrange's equations_of_motion
    for ne_eq, lag_eq in zip(out["equations_of_motion"], doc["results"]["equations_of_motion"], strict=True):
        assert same(system, ne_eq, lag_eq)
    # a projection spec names no reactions; an unasked result is absent
    assert solved(str(TUTORIAL / "p04-rp-arm.yaml"))[2]["results"]["newton_euler"]["reaction_forces"] == {}
    assert "newton_euler" not in solved(str(TUTORIAL / "p02-pivoted-rod.yaml"))[2]["results"]


@pytest.mark.parametrize("spec", ["p04-rp-arm", "p07-belt-driven-arm", "p08-spatial-rr"])
def test_newton_euler_markdown_renders(spec: str) -> None:
    d = derive(solved(str(TUTORIAL / f"{spec}.yaml"))[0], "both")  # their specs present Lagrange's alone
    text = render_markdown(d)
    assert "Newton–Euler" in text and "The Newton–Euler equations agree with Lagrange's." in text
    assert ("F_c" in text) == (d.newton_euler.method is NEMethod.PROJECTION)


def test_newton_euler_markdown_section() -> None:
    _, d, _ = solved(str(P03))
    text = render_markdown(d)
    section = text[text.index("Newton–Euler") :]
    # planar: the free body and its moments about the pivot (tests/engine/test_planar_ne.py has the records)
    assert "**pendulum**: the free body, with moments about the pivot of joint 'pivot'" in section
    assert "-m\\mathbf a_G" in section and "R_{\\mathrm{pivot},x}" in section
    assert "\\mathbf R_{\\mathrm{pivot}} &= " in section  # the free body lists it, aligned
    assert "The Newton–Euler equations agree with Lagrange's." in section


# ---------------------------------------------------------------------------------------------
# Random spatial serial chains: Newton-Euler, Lagrange and KanesMethod agree numerically
# ---------------------------------------------------------------------------------------------

AXES = ["x", "y", "z", "-x", "-y", "-z"]
small = st.integers(min_value=1, max_value=9).map(lambda k: sp.Rational(k, 4))


@st.composite
def serial_chains(draw: st.DrawFn) -> dict[str, Any]:
    """A spec dict: 1-3 links, each a revolute or prismatic joint about a random axis, offset from
    the previous joint, carrying a rigid body with random mass, centre of mass and inertia (principal
    moments that satisfy the triangle inequality, plus one product of inertia)."""
    n = draw(st.integers(min_value=1, max_value=3))
    bodies: dict[str, Any] = {}
    joints: dict[str, Any] = {}
    coordinates: dict[str, Any] = {}
    for i in range(1, n + 1):
        kind = draw(st.sampled_from(["revolute", "prismatic"]))
        coordinates[f"q{i}"] = {"dimension": "angle" if kind == "revolute" else "length"}
        a, b = draw(small), draw(small)
        product = draw(st.integers(min_value=-2, max_value=2)) * min(a, b) / 8
        bodies[f"b{i}"] = {
            "mass": str(draw(small)),
            "com": [str(draw(small)), str(draw(small) - 1), 0],
            "inertia": {"xx": str(a), "yy": str(b), "zz": str(a + b - min(a, b) / 2), "xy": str(product)},
        }
        joint: dict[str, Any] = {
            "type": kind,
            "parent": "ground" if i == 1 else f"b{i - 1}",
            "child": f"b{i}",
            "axis": draw(st.sampled_from(AXES)),
            "coordinate": f"q{i}",
        }
        if i > 1:
            joint["origin"] = [str(draw(small)), 0, str(draw(small) - 1)]
        joints[f"j{i}"] = joint
    return {
        "tutgen": 1,
        "title": "random serial chain",
        "coordinates": coordinates,
        "gravity": [0, 0, "-49/5"],
        "bodies": bodies,
        "joints": joints,
    }


def kane_equations(system: Any) -> tuple[sp.Matrix, sp.Matrix, list[Any], list[Any]]:
    """M and f of M u_dot = f from sympy.physics.mechanics, built joint by joint from the model."""
    qs = [dynamicsymbols(f"{c.name}_k") for c in system.coordinates]
    us = [dynamicsymbols(f"{c.name}_u") for c in system.coordinates]
    frame_n = ReferenceFrame("N")
    origin = Point("O")
    origin.set_vel(frame_n, 0)
    frames: dict[str, tuple[ReferenceFrame, Point]] = {"ground": (frame_n, origin)}
    bodies, loads = [], []
    q_of = {c.name: qm for c, qm in zip(system.coordinates, qs, strict=True)}
    gravity = sp.Matrix(system.gravity)
    for joint in system.joints:  # parents come first in these chains
        parent_frame, parent_point = frames[joint.parent]
        axis = sum((joint.axis[k] * v for k, v in enumerate(parent_frame)), 0 * parent_frame.x)
        offset = sum((joint.origin_offset[k] * v for k, v in enumerate(parent_frame)), 0 * parent_frame.x)
        q = q_of[joint.coordinate.name]
        if joint.kind is JointKind.REVOLUTE:
            frame = parent_frame.orientnew(f"F_{joint.child}", "Axis", (q, axis))
            point = parent_point.locatenew(f"O_{joint.child}", offset)
        else:
            frame = parent_frame.orientnew(f"F_{joint.child}", "Axis", (0, parent_frame.z))
            point = parent_point.locatenew(f"O_{joint.child}", offset + q * axis)
        frames[joint.child] = (frame, point)
    for body in system.bodies:
        frame, point = frames[body.name]
        (part,) = body.parts
        com = point.locatenew(f"G_{body.name}", sum((part.at[k] * v for k, v in enumerate(frame)), 0 * frame.x))
        com.set_vel(frame_n, com.pos_from(origin).dt(frame_n).subs(dict(zip([q.diff() for q in qs], us, strict=True))))
        j = part.inertia
        dyadic = inertia(frame, j[0, 0], j[1, 1], j[2, 2], j[0, 1], j[1, 2], j[0, 2])
        bodies.append(RigidBody(f"B_{body.name}", com, frame, part.mass, (dyadic, com)))
        loads.append((com, part.mass * sum((gravity[k] * v for k, v in enumerate(frame_n)), 0 * frame_n.x)))
    for frame, _ in frames.values():
        if frame is not frame_n:
            frame.set_ang_vel(
                frame_n, frame.ang_vel_in(frame_n).subs(dict(zip([q.diff() for q in qs], us, strict=True)))
            )
    km = KanesMethod(frame_n, q_ind=qs, u_ind=us, kd_eqs=[q.diff() - u for q, u in zip(qs, us, strict=True)])
    km.kanes_equations(bodies, loads)
    return km.mass_matrix, km.forcing, qs, us


@few_examples
@given(spec=serial_chains(), seed=st.integers(min_value=0, max_value=2**16))
def test_random_serial_chains_newton_euler_lagrange_and_kane_agree(spec: dict[str, Any], seed: int) -> None:
    system = system_of(spec)
    d = derive(system)  # raises AgreementError if Newton-Euler and Lagrange differ
    ne = d.newton_euler
    assert ne is not None and ne.agrees_with_lagrange
    assert ne.method is NEMethod.RECURSIVE
    mass, forcing, qs, us = kane_equations(system)
    rng = random.Random(seed)
    for _ in range(2):
        state = {c.q: sp.Rational(rng.randint(-3000, 3000), 1000) for c in system.coordinates}
        state |= {c.qd: sp.Rational(rng.randint(-2000, 2000), 1000) for c in system.coordinates}
        state |= {c.qdd: sp.Rational(rng.randint(-2000, 2000), 1000) for c in system.coordinates}
        to_kane = {}
        for c, qm, um in zip(system.coordinates, qs, us, strict=True):
            to_kane[qm] = state[c.q]
            to_kane[um] = state[c.qd]
        qdd = sp.Matrix([state[c.qdd] for c in system.coordinates])
        kane = (mass.xreplace(to_kane) * qdd - forcing.xreplace(to_kane)).evalf(30)
        for i in range(len(system.coordinates)):
            ours = sp.N(ne.equations_of_motion[i].xreplace(state), 30)
            lag = sp.N(d.equations_of_motion[i].xreplace(state), 30)
            scale = max(1, abs(kane[i]))
            assert abs(ours - kane[i]) < 1e-12 * scale, f"q{i + 1}: Newton-Euler {ours}, Kane {kane[i]}"
            assert abs(lag - kane[i]) < 1e-12 * scale, f"q{i + 1}: Lagrange {lag}, Kane {kane[i]}"
