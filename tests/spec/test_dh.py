"""The `arm:` section (a Denavit-Hartenberg table) and joint motors (`motor:`).

The table is desugared into bodies and joints in validation, so the checks here are that the
desugared model puts every link frame, centre of mass and inertia exactly where the DH matrices
put them (both conventions, revolute and prismatic rows, offsets), that an arm written as a table
derives the same H and G as the same arm written with plain joints, and that a motor's rotor adds
its reflected inertia n^2 J_m to H_ii on both routes (Lagrange and Newton-Euler).
"""

from __future__ import annotations

import random

import pytest
import sympy as sp

from tutgen.engine.inertia import body_inertia
from tutgen.engine.kinematics import Kinematics
from tutgen.engine.pipeline import derive
from tutgen.errors import SpecErrors
from tutgen.model.system import JointKind, System
from tutgen.spec.validate import load_system_text


def rot_x(a: sp.Expr) -> sp.Matrix:
    return sp.Matrix([[1, 0, 0, 0], [0, sp.cos(a), -sp.sin(a), 0], [0, sp.sin(a), sp.cos(a), 0], [0, 0, 0, 1]])


def rot_z(a: sp.Expr) -> sp.Matrix:
    return sp.Matrix([[sp.cos(a), -sp.sin(a), 0, 0], [sp.sin(a), sp.cos(a), 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def trans(x: sp.Expr, y: sp.Expr, z: sp.Expr) -> sp.Matrix:
    return sp.Matrix([[1, 0, 0, x], [0, 1, 0, y], [0, 0, 1, z], [0, 0, 0, 1]])


# A spatial RPR arm with every DH parameter non-zero somewhere, offsets on both kinds of joint, and
# links whose centres of mass and inertia tensors are full (all six entries).
ROWS = [
    # theta, d, a, alpha (standard: a_i, alpha_i; modified: a_{i-1}, alpha_{i-1})
    ("q1 + pi/6", "l0", "l1", "pi/2"),
    ("pi/3", "q2 + d0", "a2", "-pi/2"),
    ("q3", "d3", "l3", "pi/4"),
]
COMS = ["[c1, -c1/2, c1/3]", "[0, c2, -c2]", "[c3, c3/2, 0]"]


def arm_spec(convention: str, rows: list[tuple[str, str, str, str]] = ROWS, motors: bool = False) -> str:
    lines = [
        "tutgen: 1",
        f"title: RPR arm, {convention} DH",
        "parameters: [l0, l1, a2, d0, d3, l3, c1, c2, c3, m1, m2, m3, g, Jm1, n1, Jm3]",
        "coordinates: [q1, q2, q3]",
        "gravity: [0, 0, -g]",
        "arm:",
        f"  convention: {convention}",
        "  links:",
    ]
    for i, ((theta, d, a, alpha), com) in enumerate(zip(rows, COMS, strict=True), start=1):
        m = f"m{i}"
        inertia = f"{{xx: 3*{m}, yy: 4*{m}, zz: 5*{m}, xy: {m}/2, xz: -{m}/3, yz: {m}/5}}"
        motor = ""
        if motors and i == 1:
            motor = ", motor: {rotor_inertia: Jm1, gear_ratio: n1}"
        if motors and i == 3:
            motor = ", motor: {rotor_inertia: Jm3}"
        lines.append(
            f"    link{i}: {{theta: '{theta}', d: '{d}', a: '{a}', alpha: '{alpha}', mass: {m}, com: {com}, "
            f"inertia: {inertia}{motor}}}"
        )
    return "\n".join(lines) + "\n"


def random_state(system: System, rng: random.Random) -> dict[sp.Symbol, sp.Expr]:
    values: dict[sp.Symbol, sp.Expr] = {}
    for p in system.parameters:
        values[p.symbol] = sp.Rational(rng.randint(5, 40), 10)
    for c in system.coordinates:
        values[c.q] = sp.Rational(rng.randint(-300, 300), 100)
        values[c.qd] = sp.Rational(rng.randint(-300, 300), 100)
    return values


def dh_transforms(convention: str, values: dict[sp.Symbol, sp.Expr], system: System) -> list[sp.Matrix]:
    """T_0i of DH frame i, computed directly from the DH matrices of ROWS."""
    names = {s.name: s for s in values}
    out = []
    t = sp.eye(4)
    for theta_t, d_t, a_t, alpha_t in ROWS:
        theta, d, a, alpha = (sp.sympify(x, locals=names).subs(values) for x in (theta_t, d_t, a_t, alpha_t))
        if convention == "standard":
            t = t * rot_z(theta) * trans(0, 0, d) * trans(a, 0, 0) * rot_x(alpha)
        else:
            t = t * rot_x(alpha) * trans(a, 0, 0) * rot_z(theta) * trans(0, 0, d)
        out.append(t)
    return out


def close(a: sp.MatrixBase, b: sp.MatrixBase) -> bool:
    return all(abs(complex(sp.N(x - y, 30))) < 1e-20 for x, y in zip(a, b, strict=True))


@pytest.mark.parametrize("convention", ["standard", "modified"])
def test_dh_frames_and_mass_properties_match_the_dh_matrices(convention: str) -> None:
    system = load_system_text(arm_spec(convention))
    assert [j.kind for j in system.joints] == [JointKind.REVOLUTE, JointKind.PRISMATIC, JointKind.REVOLUTE]
    inertia = {b.name: body_inertia(b) for b in system.bodies}
    kin = Kinematics(system, {n: bi.com for n, bi in inertia.items()})
    rng = random.Random(8)
    for _ in range(3):
        values = random_state(system, rng)
        names = {s.name: s for s in values}
        for i, t in enumerate(dh_transforms(convention, values, system), start=1):
            name = f"link{i}"
            frame = kin.frames[name]
            body = sp.eye(4)
            body[:3, :3] = frame.rotation
            body[:3, 3] = frame.position
            body = body.subs(values)
            a, alpha = (sp.sympify(x, locals=names).subs(values) for x in ROWS[i - 1][2:])
            # standard: the body frame is DH frame i before its Tx(a_i) Rx(alpha_i)
            dh = body * trans(a, 0, 0) * rot_x(alpha) if convention == "standard" else body
            assert close(dh, t), f"{convention}: frame of {name}"
            # the centre of mass, given in DH frame i, is where T_0i puts it
            c = sp.Matrix([*sp.sympify(COMS[i - 1], locals=names), 1]).subs(values)
            assert close(kin.bodies[name].com.subs(values), (t * c)[:3, 0]), f"{convention}: com of {name}"
            # and so is the inertia tensor (compared in world axes)
            m = names[f"m{i}"]
            given = sp.Matrix([[3 * m, m / 2, -m / 3], [m / 2, 4 * m, m / 5], [-m / 3, m / 5, 5 * m]]).subs(values)
            world = frame.rotation.subs(values) * inertia[name].inertia_com.subs(values) * frame.rotation.T.subs(values)
            r = t[:3, :3]
            assert close(world, r * given * r.T), f"{convention}: inertia of {name}"


def test_dh_offsets_become_joint_offsets() -> None:
    system = load_system_text(arm_spec("modified"))
    q = {c.name: c for c in system.coordinates}
    d0 = next(p.symbol for p in system.parameters if p.name == "d0")
    assert [j.offset for j in system.joints] == [sp.pi / 6, d0, 0]
    assert [j.coordinate.name for j in system.joints if j.coordinate] == list(q)


PLANAR_DH = """
tutgen: 1
title: RR arm
parameters: [m1, m2, l1, l2, g, tau1, tau2]
coordinates: [theta1, theta2]
gravity: [0, -g, 0]
arm:
  convention: {convention}
  links:
{rows}
generalized_forces: {{theta1: tau1, theta2: tau2}}
"""
STANDARD_RR = """\
    link1: {theta: theta1, a: l1, mass: m1, com: [-l1/2, 0, 0], inertia: {zz: m1*l1**2/12}}
    link2: {theta: theta2, a: l2, mass: m2, com: [-l2/2, 0, 0], inertia: {zz: m2*l2**2/12}}"""
MODIFIED_RR = """\
    link1: {theta: theta1, mass: m1, com: [l1/2, 0, 0], inertia: {zz: m1*l1**2/12}}
    link2: {theta: theta2, a: l1, mass: m2, com: [l2/2, 0, 0], inertia: {zz: m2*l2**2/12}}"""
PLANAR_JOINTS = """
tutgen: 1
title: RR arm
parameters: [m1, m2, l1, l2, g, tau1, tau2]
coordinates: [theta1, theta2]
gravity: [0, -g, 0]
bodies:
  link1: {mass: m1, com: [l1/2, 0, 0], inertia: {zz: m1*l1**2/12}}
  link2: {mass: m2, com: [l2/2, 0, 0], inertia: {zz: m2*l2**2/12}}
joints:
  shoulder: {type: revolute, parent: ground, child: link1, axis: z, coordinate: theta1}
  elbow: {type: revolute, parent: link1, child: link2, axis: z, origin: [l1, 0, 0], coordinate: theta2}
generalized_forces: {theta1: tau1, theta2: tau2}
"""


@pytest.mark.parametrize("convention, rows", [("standard", STANDARD_RR), ("modified", MODIFIED_RR)])
def test_dh_planar_arm_derives_as_the_hand_written_joints(convention: str, rows: str) -> None:
    dh = derive(load_system_text(PLANAR_DH.format(convention=convention, rows=rows)), method="lagrange")
    plain = derive(load_system_text(PLANAR_JOINTS), method="lagrange")
    for key in ("mass_matrix", "gravity_vector", "coriolis_vector", "equations_of_motion"):
        diff = getattr(dh, key) - getattr(plain, key)
        assert diff.applyfunc(sp.simplify) == sp.zeros(*diff.shape), key


def test_dh_spatial_arm_derives_as_the_hand_written_joints() -> None:
    """A spatial RRP arm (standard DH) against the same arm built with joint origins and orientations
    worked out by hand from Spong's matrices (base: frame 0 = world)."""
    table = """
tutgen: 1
title: spatial arm
parameters: [m1, m2, m3, d1, a2, c2, g]
coordinates: [q1, q2, q3]
gravity: [0, 0, -g]
arm:
  convention: standard
  links:
    link1:
      {theta: q1, d: d1, alpha: 90 deg, mass: m1, com: [0, -d1/2, 0], inertia: {xx: m1, yy: m1/2, zz: m1/3, xy: m1/7}}
    link2: {theta: q2, a: a2, mass: m2, com: [-c2, 0, 0], inertia: {xx: m2, yy: 2*m2, zz: 3*m2, yz: m2/5}}
    link3: {theta: 90 deg, d: q3, alpha: -90 deg, mass: m3, com: [0, 0, 0], inertia: {xx: m3, yy: m3, zz: m3/4}}
"""
    # standard row i's body frame is DH frame i before Tx(a_i) Rx(alpha_i): its data turned by Rx(alpha_i)
    # and shifted by a_i, the next joint placed at (a_i, 0, 0) turned by Rx(alpha_i)
    plain = """
tutgen: 1
title: spatial arm
parameters: [m1, m2, m3, d1, a2, c2, g]
coordinates: [q1, q2, q3]
gravity: [0, 0, -g]
bodies:
  link1: {mass: m1, com: [0, 0, -d1/2], inertia: {xx: m1, yy: m1/3, zz: m1/2, xz: m1/7}}
  link2: {mass: m2, com: [a2 - c2, 0, 0], inertia: {xx: m2, yy: 2*m2, zz: 3*m2, yz: m2/5}}
  link3: {mass: m3, inertia: {xx: m3, yy: m3/4, zz: m3}}
joints:
  j1: {type: revolute, parent: ground, child: link1, axis: z, origin: [0, 0, d1], coordinate: q1}
  j2: {type: revolute, parent: link1, child: link2, axis: z, orientation: [{axis: x, angle: 90 deg}], coordinate: q2}
  j3:
    type: prismatic
    parent: link2
    child: link3
    axis: z
    origin: [a2, 0, 0]
    orientation: [{axis: z, angle: 90 deg}]
    coordinate: q3
"""
    dh = derive(load_system_text(table), method="lagrange")
    ref = derive(load_system_text(plain), method="lagrange")
    rng = random.Random(3)
    for _ in range(3):
        values = random_state(dh.system, rng)  # the same symbols (names and assumptions) in both
        for key in ("mass_matrix", "gravity_vector", "coriolis_vector"):
            assert close(getattr(dh, key).subs(values), getattr(ref, key).subs(values)), key


ROTOR_ARM = """
tutgen: 1
title: RR arm with geared motors
parameters: [m1, m2, l1, l2, g, Jm1, Jm2, n1, n2]
coordinates: [q1, q2]
gravity: [0, -g, 0]
bodies:
  link1: {mass: m1, com: [l1/2, 0, 0], inertia: {zz: m1*l1**2/12}}
  link2: {mass: m2, com: [l2/2, 0, 0], inertia: {zz: m2*l2**2/12}}
joints:
  j1: {type: revolute, parent: ground, child: link1, coordinate: q1, motor: {rotor_inertia: Jm1, gear_ratio: n1}}
  j2:
    type: revolute
    parent: link1
    child: link2
    origin: [l1, 0, 0]
    coordinate: q2
    MOTOR2
"""


def test_rotor_adds_reflected_inertia_on_both_routes() -> None:
    with_rotors = derive(load_system_text(ROTOR_ARM.replace("MOTOR2", "motor: {rotor_inertia: Jm2, gear_ratio: n2}")))
    without = derive(
        load_system_text(ROTOR_ARM.replace(", motor: {rotor_inertia: Jm1, gear_ratio: n1}", "").replace("MOTOR2", ""))
    )
    s = with_rotors.system
    p = {x.name: x.symbol for x in s.parameters}
    assert s.joints[0].rotor_inertia == p["Jm1"] and s.joints[0].gear_ratio == p["n1"]
    diff = (with_rotors.mass_matrix - without.mass_matrix).applyfunc(sp.expand)
    assert diff == sp.diag(p["n1"] ** 2 * p["Jm1"], p["n2"] ** 2 * p["Jm2"])
    qd = [c.qd for c in s.coordinates]
    extra = sp.expand(with_rotors.kinetic_energy - without.kinetic_energy)
    assert extra == sp.expand((p["n1"] ** 2 * p["Jm1"] * qd[0] ** 2 + p["n2"] ** 2 * p["Jm2"] * qd[1] ** 2) / 2)
    # Lagrange's term-by-term route carries the rotor too (derive() checks it against the matrix form)
    assert with_rotors.lagrange_terms[0].dL_dqd.has(p["Jm1"])
    # and Newton-Euler, with the rotor's share taken from the drive, agrees with it
    assert with_rotors.newton_euler is not None and with_rotors.newton_euler.agrees_with_lagrange
    assert any("reflected inertia" in r and "'j1'" in r for r in with_rotors.remarks)
    assert any("'j2'" in r for r in with_rotors.newton_euler.remarks)


def test_rotor_in_a_dh_row_with_default_gear_ratio() -> None:
    d = derive(
        load_system_text(
            PLANAR_DH.format(
                convention="standard",
                rows=STANDARD_RR.replace("zz: m2*l2**2/12}", "zz: m2*l2**2/12}, motor: {rotor_inertia: 3 g*m^2}"),
            )
        )
    )
    plain = derive(load_system_text(PLANAR_JOINTS))
    diff = (d.mass_matrix - plain.mass_matrix).applyfunc(sp.simplify)
    assert diff == sp.diag(0, sp.Rational(3, 1000))
    assert d.system.joints[1].gear_ratio is None
    assert d.newton_euler is not None and d.newton_euler.agrees_with_lagrange


@pytest.mark.parametrize(
    "motor, message",
    [
        pytest.param("{rotor_inertia: 2 kg}", "expected an inertia (kg*m^2) for a rotor inertia", id="inertia-unit"),
        pytest.param("{rotor_inertia: Jm1, gear_ratio: 5 m}", "found '5 m', which is a length", id="ratio-unit"),
        pytest.param("{rotor_inertia: -Jm1}", "must not be negative", id="negative-inertia"),
        pytest.param("{rotor_inertia: Jm1, gear_ratio: 0}", "must be positive", id="zero-ratio"),
        pytest.param("{rotor_inertia: Jm1, gear_ratio: nn}", "must be positive", id="negative-ratio-value"),
        pytest.param("{gear_ratio: 3}", "missing required key 'rotor_inertia'", id="no-inertia"),
    ],
)
def test_motor_errors(motor: str, message: str) -> None:
    text = ROTOR_ARM.replace("MOTOR2", "").replace("{rotor_inertia: Jm1, gear_ratio: n1}", motor)
    text = text.replace(
        "parameters: [m1, m2, l1, l2, g, Jm1, Jm2, n1, n2]",
        "parameters: {m1: , m2: , l1: , l2: , g: , Jm1: , Jm2: , n1: , n2: , nn: -50}",
    )
    with pytest.raises(SpecErrors) as exc:
        load_system_text(text)
    shown = "\n".join(str(e) for e in exc.value.errors)
    assert message in shown
    assert len(exc.value.errors) == 1, shown


def test_motor_on_a_fixed_joint_is_refused() -> None:
    text = (
        ROTOR_ARM.replace("MOTOR2", "")
        .replace(
            "j1: {type: revolute, parent: ground, child: link1, coordinate: q1,",
            "j1: {type: fixed, parent: ground, child: link1,",
        )
        .replace("coordinates: [q1, q2]", "coordinates: [q2]")
    )
    with pytest.raises(SpecErrors) as exc:
        load_system_text(text)
    assert [e.message for e in exc.value.errors] == ["joint 'j1' is fixed, so it has no motor; found `motor`"]


def test_rotors_are_listed_in_the_json_output() -> None:
    from tutgen.render.jsonout import derivation_to_json

    d = derive(
        load_system_text(ROTOR_ARM.replace("MOTOR2", "motor: {rotor_inertia: Jm2}")),
        method="lagrange",
    )
    doc = derivation_to_json(d)
    assert doc["results"]["rotors"] == {
        "j1": {"coordinate": "q1", "rotor_inertia": "Jm1", "gear_ratio": "n1", "reflected_inertia": "Jm1*n1**2"},
        "j2": {"coordinate": "q2", "rotor_inertia": "Jm2", "gear_ratio": 1, "reflected_inertia": "Jm2"},
    }
    plain = derivation_to_json(derive(load_system_text(PLANAR_JOINTS), method="lagrange"))
    assert "rotors" not in plain["results"]


def test_bodies_may_hang_from_the_arm() -> None:
    """A tool fixed to the last link with `joints`, a load on a link: the arm's links are bodies."""
    text = PLANAR_DH.format(convention="modified", rows=MODIFIED_RR).replace(
        "generalized_forces:",
        "bodies:\n  tool: {mass: m2, com: [l2, 0, 0]}\n"
        "joints:\n  flange: {type: fixed, parent: link2, child: tool}\n"
        "loads:\n  push: {body: link1, torque: [0, 0, tau1]}\n"
        "generalized_forces:",
    )
    system = load_system_text(text)
    assert [b.name for b in system.bodies] == ["link1", "link2", "tool"]
    assert [(j.name, j.parent, j.child) for j in system.joints] == [
        ("joint1", "ground", "link1"),
        ("joint2", "link1", "link2"),
        ("flange", "link2", "tool"),
    ]
    d = derive(system, method="lagrange")
    tau1 = next(p.symbol for p in system.parameters if p.name == "tau1")
    assert sp.simplify(d.generalized_forces[0] - 2 * tau1) == 0


def test_rotor_on_a_prismatic_joint() -> None:
    """A ball-screw drive: n in rotor radians per metre, n^2 J_m a mass added to H."""
    d = derive(
        load_system_text(
            """
tutgen: 1
title: cart on a ball screw
parameters: [m, Jm, n, F]
coordinates: [x]
bodies: {cart: {mass: m}}
joints: {slide: {type: prismatic, parent: ground, child: cart, axis: x, coordinate: x,
                 motor: {rotor_inertia: Jm, gear_ratio: n}}}
generalized_forces: {x: F}
"""
        )
    )
    p = {x.name: x.symbol for x in d.system.parameters}
    assert d.mass_matrix == sp.Matrix([[p["m"] + p["n"] ** 2 * p["Jm"]]])
    assert d.newton_euler is not None and d.newton_euler.agrees_with_lagrange
