"""Constraints (issue 21): each example against sympy.physics.mechanics built independently, and by hand.

The references build the bodies with sympy's own frames and ``LagrangesMethod`` with ``hol_coneqs`` or
``nonhol_coneqs`` and solve for q_ddot and the multipliers at random consistent states; tutgen's
reduced equations and its lambda must give the same numbers. sympy's ``mass_matrix_full`` and
``forcing_full`` read M q_ddot - A^T lambda = f (its ``lam_coeffs`` is -A, A the Jacobian of the constraints
as written), which is tutgen's convention H q_ddot + C + G = Q + A^T lambda: the multipliers are compared
as they are.
"""

from __future__ import annotations

import math
import random
from typing import Any

import pytest
import sympy as sp
from sympy.physics.mechanics import (
    LagrangesMethod,
    Point,
    ReferenceFrame,
    RigidBody,
    dynamicsymbols,
    inertia,
)

from tests.conftest import SPECS, solved

DISC = str(SPECS / "examples" / "l-disc-rolling-down-incline.yaml")
COIN = str(SPECS / "examples" / "m-vertical-rolling-coin.yaml")


def _symbols(system: Any) -> dict[str, sp.Symbol]:
    return {p.name: p.symbol for p in system.parameters}


def _tutgen_numbers(d: Any, state: dict[sp.Symbol, float]) -> tuple[list[float], list[float]]:
    """tutgen's q_ddot_i (reduced route) and lambda (its closed form) at ``state``."""
    cd = d.constraints
    acc = [float(sp.N(e.subs(state))) for e in cd.accelerations]
    lam = [float(sp.N(e.subs(state))) for e in cd.multiplier_values]
    return acc, lam


def _solve_reference(lm: LagrangesMethod, values: dict[Any, float]) -> tuple[sp.Matrix, sp.Matrix]:
    """sympy's q_ddot and lambda at a state: M_full [q_ddot; lambda] = f_full."""
    if lm.eom is None:  # formed once: a test evaluates it at several states
        lm.form_lagranges_equations()
    m_full = lm.mass_matrix_full.subs(values)
    f_full = lm.forcing_full.subs(values)
    n = len(lm.q)
    x = m_full.LUsolve(f_full)
    # mass_matrix_full is over [q_dot; q_ddot; lambda]: the last rows
    return x[n : 2 * n, 0], x[2 * n :, 0]


def test_disc_rolling_by_hand() -> None:
    """phi_ddot = 2 g sin(alpha) / (3 R); lambda = -m g sin(alpha) / 3: friction up the slope (x grows down it)."""
    system, d, _ = solved(DISC)
    s = _symbols(system)
    m, r, g, alpha = s["m"], s["R"], s["g"], s["alpha"]
    cd = d.constraints
    assert sp.simplify(cd.accelerations[0] - 2 * g * sp.sin(alpha) / (3 * r)) == 0
    assert sp.simplify(cd.multiplier_values[0] + m * g * sp.sin(alpha) / 3) == 0
    assert sp.simplify(cd.mass_matrix[0, 0] - sp.Rational(3, 2) * m * r**2) == 0
    # Newton-Euler on the free disc: m x_ddot = m g sin(alpha) + F (F the friction along x, at the contact)
    # and (m R^2 / 2) phi_ddot = -R F; lambda is F
    x_ddot = r * cd.accelerations[0]
    friction = m * x_ddot - m * g * sp.sin(alpha)
    assert sp.simplify(m * r**2 / 2 * cd.accelerations[0] + r * friction) == 0
    assert sp.simplify(cd.multiplier_values[0] - friction) == 0


def test_disc_rolling_against_lagranges_method() -> None:
    system, d, _ = solved(DISC)
    s = _symbols(system)
    m, r, g, alpha = s["m"], s["R"], s["g"], s["alpha"]
    x, phi = dynamicsymbols("x phi")
    t = dynamicsymbols._t
    n = ReferenceFrame("N")
    b = n.orientnew("B", "Axis", (-phi, n.z))
    o = Point("O")
    o.set_vel(n, 0)
    c = o.locatenew("C", x * (sp.cos(alpha) * n.x - sp.sin(alpha) * n.y))
    c.set_vel(n, c.pos_from(o).dt(n))
    disc = RigidBody("disc", c, b, m, (inertia(b, m * r**2 / 4, m * r**2 / 4, m * r**2 / 2), c))
    disc.potential_energy = m * g * c.pos_from(o).dot(n.y)
    lag = sp.physics.mechanics.Lagrangian(n, disc)
    lm = LagrangesMethod(lag, [x, phi], hol_coneqs=[x - r * phi], frame=n)
    rng = random.Random(21)
    for _ in range(3):
        params = {m: rng.uniform(0.5, 2), r: rng.uniform(0.5, 2), g: 9.81, alpha: rng.uniform(0.1, 1.2)}
        ph, phd = rng.uniform(-2, 2), rng.uniform(-2, 2)
        ref_values = {**params, phi: ph, x: params[r] * ph, phi.diff(t): phd, x.diff(t): params[r] * phd}
        qdd, lam = _solve_reference(lm, ref_values)
        coords = {c.name: c for c in system.coordinates}
        state = {**params, coords["phi"].q: ph, coords["x"].q: params[r] * ph, coords["phi"].qd: phd}
        acc, ours = _tutgen_numbers(d, state)
        assert acc[0] == pytest.approx(float(qdd[1]), rel=1e-9, abs=1e-12)
        assert ours[0] == pytest.approx(float(lam[0]), rel=1e-9, abs=1e-12)


@pytest.mark.slow
def test_coin_against_lagranges_method() -> None:
    system, d, _ = solved(COIN)
    s = _symbols(system)
    m, r = s["m"], s["R"]
    x, y, th, ph = dynamicsymbols("x y theta phi")
    t = dynamicsymbols._t
    n = ReferenceFrame("N")
    a = n.orientnew("A", "Axis", (th, n.z))
    b = a.orientnew("B", "Axis", (ph, a.y))
    o = Point("O")
    o.set_vel(n, 0)
    c = o.locatenew("C", x * n.x + y * n.y + r * n.z)
    c.set_vel(n, c.pos_from(o).dt(n))
    coin = RigidBody("coin", c, b, m, (inertia(b, m * r**2 / 4, m * r**2 / 2, m * r**2 / 4), c))
    lag = sp.physics.mechanics.Lagrangian(n, coin)
    # the contact point at rest, from sympy's own kinematics: v_C + omega x (contact - C) = 0
    contact = c.locatenew("P", -r * n.z)
    v_contact = c.vel(n) + b.ang_vel_in(n).cross(contact.pos_from(c).express(n))
    cons = [v_contact.dot(n.x), v_contact.dot(n.y)]
    lm = LagrangesMethod(lag, [x, y, th, ph], nonhol_coneqs=cons, frame=n)
    rng = random.Random(22)
    coords = {cc.name: cc for cc in system.coordinates}
    for _ in range(3):
        params = {m: rng.uniform(0.5, 2), r: rng.uniform(0.5, 2)}
        q = {name: rng.uniform(-2, 2) for name in ("x", "y", "theta", "phi")}
        thd, phd = rng.uniform(-2, 2), rng.uniform(-2, 2)
        xd = params[r] * phd * sp.cos(q["theta"])
        yd = params[r] * phd * sp.sin(q["theta"])
        ref_values = {**params, x: q["x"], y: q["y"], th: q["theta"], ph: q["phi"]}
        ref_values |= {x.diff(t): xd, y.diff(t): yd, th.diff(t): thd, ph.diff(t): phd}
        qdd, lam = _solve_reference(lm, ref_values)
        state = {**params, **{coords[k].q: v for k, v in q.items()}, coords["theta"].qd: thd, coords["phi"].qd: phd}
        acc, ours = _tutgen_numbers(d, state)
        assert acc == pytest.approx([float(qdd[2]), float(qdd[3])], rel=1e-9, abs=1e-12)
        # sympy's constraints (the contact point's velocity) are tutgen's as written: the same multipliers
        assert ours == pytest.approx([float(v) for v in lam], rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("path", [DISC, COIN], ids=["disc", "coin"])
def test_constraint_forces_do_no_work(path: str) -> None:
    """q_dot . A^T lambda = 0 along the constrained motion (ideal constraints)."""
    system, d, _ = solved(path)
    cd = d.constraints
    power = sum((cc.qd * f for cc, f in zip(system.coordinates, cd.constraint_forces, strict=True)), sp.Integer(0))
    assert sp.simplify(power.xreplace(cd.kinematics.rates)) == 0


_BASE = """
tutgen: 1
title: bad constraints
parameters: [m, R]
coordinates: [x, phi, y]
bodies:
  disc:
    parts: {plate: {shape: disc, mass: m, radius: R}}
    position: [x, y, 0]
    orientation: [{axis: z, angle: phi}]
"""


@pytest.mark.parametrize(
    ("constraints", "line", "message"),
    [
        pytest.param(
            "constraints: {rolling: x - R*phi, twice: 2*x - 2*R*phi}\nindependent_coordinates: [y]",
            11,
            "constraint 'twice' is redundant or inconsistent with those before it: the constraint Jacobian A has "
            "rank 1 < 2",
            id="redundant",
        ),
        pytest.param(
            "constraints: {loop: x**2 + R**2}\nindependent_coordinates: [phi, y]",
            11,
            "the position constraints (loop) hold at no configuration tried",
            id="never-closes",
        ),
        pytest.param(
            "constraints: {rolling: x - R*phi}\nindependent_coordinates: [x, phi]",
            11,
            "the independent coordinates [x, phi] cannot be kept: the constraints do not determine the rates of y",
            id="singular-choice",
        ),
    ],
)
def test_bad_constraints_are_derivation_errors(constraints: str, line: int, message: str) -> None:
    from tutgen.engine.pipeline import derive
    from tutgen.errors import DerivationError
    from tutgen.spec.validate import load_system_text

    system = load_system_text(_BASE + constraints)
    with pytest.raises(DerivationError) as info:
        derive(system)
    assert message in str(info.value)
    assert info.value.location is not None and info.value.location.line == line


def test_singular_choice_suggests_one_that_works() -> None:
    from tutgen.engine.pipeline import derive
    from tutgen.errors import DerivationError
    from tutgen.spec.validate import load_system_text

    system = load_system_text(_BASE + "constraints: {rolling: x - R*phi}\nindependent_coordinates: [x, phi]")
    with pytest.raises(DerivationError) as info:
        derive(system)
    assert "e.g. independent_coordinates: [x, y]" in str(info.value)


def test_bad_constraint_on_the_command_line(tmp_path: Any) -> None:
    from typer.testing import CliRunner

    from tutgen.cli.main import app
    from tutgen.errors import EXIT_CANNOT_DERIVE

    spec = tmp_path / "loop.yaml"
    spec.write_text(_BASE + "constraints: {loop: x**2 + R**2}\nindependent_coordinates: [phi, y]\n")
    result = CliRunner().invoke(app, ["solve", str(spec)])
    assert result.exit_code == EXIT_CANNOT_DERIVE, result.output
    assert "Traceback" not in result.stderr
    assert f"{spec}:11:15: error: the position constraints (loop) hold at no configuration" in result.stderr


FOUR_BAR = str(SPECS / "examples" / "n-four-bar-crank-rocker.yaml")


@pytest.mark.slow
def test_four_bar_against_lagranges_method() -> None:
    """The four-bar from sympy's own frames, with the loop-closure equations as hol_coneqs; at consistent
    states (theta3, theta4 solved by nsolve) tutgen's reduced equation holds at sympy's accelerations and
    its lambda (in the accelerations) equals sympy's pin-force multipliers."""
    system, d, _ = solved(FOUR_BAR)
    s = _symbols(system)
    m2, m3, m4, mf, rf, a, b, c, dd, tau = (s[k] for k in ("m2", "m3", "m4", "mf", "rf", "a", "b", "c", "d", "tau"))
    th = dynamicsymbols("theta2 theta3 theta4")
    t = dynamicsymbols._t
    n = ReferenceFrame("N")
    frames = [n.orientnew(f"F{k}", "Axis", (q, n.z)) for k, q in enumerate(th)]
    o2 = Point("O2")
    o2.set_vel(n, 0)
    pa = o2.locatenew("A", a * frames[0].x)
    o4 = o2.locatenew("O4", dd * n.x)
    o4.set_vel(n, 0)
    bodies = []
    for k, (start, length, mass, frame) in enumerate(
        [(o2, a, m2, frames[0]), (pa, b, m3, frames[1]), (o4, c, m4, frames[2])]
    ):
        g_pt = start.locatenew(f"G{k}", length / 2 * frame.x)
        g_pt.set_vel(n, g_pt.pos_from(o2).dt(n))
        rod = (inertia(frame, 0, 0, mass * length**2 / 12), g_pt)
        bodies.append(RigidBody(f"rod{k}", g_pt, frame, mass, rod))
    # the flywheel: a disc centred at the fixed pin O2, turning with the crank
    bodies.append(RigidBody("flywheel", o2, frames[0], mf, (inertia(frames[0], 0, 0, mf * rf**2 / 2), o2)))
    lag = sp.physics.mechanics.Lagrangian(n, *bodies)
    gap = pa.locatenew("B1", b * frames[1].x).pos_from(o2) - o4.locatenew("B2", c * frames[2].x).pos_from(o2)
    cons = [gap.dot(n.x), gap.dot(n.y)]
    lm = LagrangesMethod(lag, list(th), hol_coneqs=cons, forcelist=[(frames[0], tau * n.z)], frame=n)
    coords = [cc for cc in system.coordinates]
    rng = random.Random(23)
    cd = d.constraints
    for _ in range(2):
        params = {m2: 1.2, m3: 0.8, m4: 1.1, mf: 2.0, rf: 0.3, a: 0.5, b: 2.0, c: 1.2, dd: 1.8, tau: 0.7}
        q2 = rng.uniform(-3, 3)
        eqs = [e.subs(params).subs(th[0], q2) for e in cons]
        q3, q4 = sp.nsolve(eqs, [th[1], th[2]], [0.5, 1.5])
        qd2 = rng.uniform(-1, 1)
        ratios = cd.kinematics.velocity_ratios
        plain = {**params, coords[0].q: q2, coords[1].q: float(q3), coords[2].q: float(q4)}
        qd3, qd4 = (float(ratios[k, 0].subs(plain)) * qd2 for k in range(2))
        ref = {**params, th[0]: q2, th[1]: float(q3), th[2]: float(q4)}
        ref |= {th[0].diff(t): qd2, th[1].diff(t): qd3, th[2].diff(t): qd4}
        qdd, lam = _solve_reference(lm, ref)
        state = {**plain, coords[0].qd: qd2}
        state |= {cc.qdd: float(v) for cc, v in zip(coords, qdd, strict=True)}
        assert float(cd.equations_of_motion[0].subs(state)) == pytest.approx(0, abs=1e-9)
        ours = [float(e.subs(state)) for e in cd.multipliers_in_accelerations]
        assert ours == pytest.approx([float(v) for v in lam], rel=1e-8, abs=1e-10)


def test_code_of_a_constrained_spec_has_its_constraints() -> None:
    """Generated code carries the constraints (tests/codegen/test_constrained_code.py checks the numbers)."""
    from typer.testing import CliRunner

    from tutgen.cli.main import app

    result = CliRunner().invoke(app, ["code", DISC, "-l", "python"])
    assert result.exit_code == 0, result.output
    assert "def constraint_jacobian(" in result.stdout


SLIDER_CRANK = str(SPECS / "examples" / "o-slider-crank.yaml")


@pytest.mark.slow
def test_slider_crank_pin_force_is_newton_eulers() -> None:
    """Newton on the piston alone: m3 s_ddot = F - P_x, with P_x the pin B's force on the rod along x (the
    piston pushes the rod by P_x, the rod the piston by -P_x). The loop's first equation is
    B_x = (rod's end) - (piston) = 0, whose multiplier acts on s as -lambda_1: lambda_1 = P_x = F - m3 s_ddot.
    Also the velocity analysis by hand: s_dot = -r theta_dot sin(theta) - l beta_dot sin(beta) with
    beta_dot = -r cos(theta) theta_dot / (l cos(beta)), from differentiating l sin(beta) + r sin(theta) = 0."""
    system, d, _ = solved(SLIDER_CRANK)
    s = _symbols(system)
    co = {c.name: c for c in system.coordinates}
    cd = d.constraints
    assert sp.simplify(cd.multipliers_in_accelerations[0] - (s["F"] - s["m3"] * co["s"].qdd)) == 0
    beta_dot = -s["r"] * sp.cos(co["theta"].q) * co["theta"].qd / (s["l"] * sp.cos(co["beta"].q))
    s_dot = -s["r"] * co["theta"].qd * sp.sin(co["theta"].q) - s["l"] * beta_dot * sp.sin(co["beta"].q)
    rates = cd.kinematics.rates
    assert sp.simplify(rates[co["beta"].qd] - beta_dot) == 0
    assert sp.simplify(rates[co["s"].qd] - s_dot) == 0


def test_a_loop_that_closes_only_far_from_the_reference_is_solved() -> None:
    """y^2 = -cos(phi) - 1/10 holds only for |phi| >= 1.67 (past the first draws' [-1.5, 1.5]): the states
    are then drawn over the whole turn, not the constraint reported as never holding."""
    from tutgen.engine.constraints.kinematics import consistent_states
    from tutgen.engine.pipeline import derive
    from tutgen.spec.validate import load_system_text

    system = load_system_text(_BASE + "constraints: {loop: y**2 + cos(phi) + 1/10}\nindependent_coordinates: [x, phi]")
    d = derive(system)
    ck = d.constraints.kinematics
    states = list(consistent_states(system, ck.functions, ck.dependent, 4))
    assert len(states) == 4
    phi, y = system.coordinates[1].q, system.coordinates[2].q
    for state in states:
        assert abs(float(state.values[phi])) > 1.6
        assert float(state.values[y]) ** 2 + math.cos(float(state.values[phi])) + 0.1 == pytest.approx(0, abs=1e-12)
