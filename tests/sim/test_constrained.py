"""`tutgen simulate` of constrained specs (issue 21's "energy is conserved along a short simulation").

- The conservative examples (the rolling disc, the vertical coin, the slider-crank without its piston
  force and torque; the four-bar without its torque under -m slow) keep their energy within 100 x rtol,
  and their constraint residuals stay below 1e-8.
- Closed forms: the rolling disc's phi(t) = g sin(alpha) t^2 / (3 R) with the friction
  lambda = -m g sin(alpha) / 3; the coin at constant rates runs on a circle, with lambda_1 = m x_ddot.
- The start: the slider-crank's rod angle and piston from the crank angle (both branches, chosen by the
  guess), the dependent rates from q_dot_d = B q_dot_i; a crank angle at which the loop cannot close, and
  a dependent rate that disagrees with the constraints, are spec errors (exit 3) with nothing written.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from typer.testing import CliRunner

from tests.codegen.compiled import derived_lagrange
from tests.conftest import ROOT
from tutgen.cli.main import app
from tutgen.engine.derivation import Derivation
from tutgen.engine.pipeline import derive
from tutgen.errors import SpecErrors
from tutgen.sim.run import Settings, SimulationResult, simulate_system

pytest.importorskip("scipy")
pytest.importorskip("matplotlib")

DISC = "specs/examples/l-disc-rolling-down-incline.yaml"
COIN = "specs/examples/m-vertical-rolling-coin.yaml"
SLIDER = "specs/examples/o-slider-crank.yaml"
FOUR_BAR = "specs/examples/n-four-bar-crank-rocker.yaml"

#: a short run of each conservative example: parameters, initial values (independent coordinates; the
#: coin's x and y, which only velocity constraints tie), independent rates
RUNS = {
    DISC: ({"m": "2", "R": "0.3", "alpha": "30deg", "g": "9.81"}, {"phi": "0"}, {"phi": "1"}),
    COIN: (
        {"m": "1", "R": "0.3", "g": "9.81"},
        {"x": "0", "y": "0", "theta": "0", "phi": "0"},
        {"theta": "1", "phi": "3"},
    ),
    SLIDER: (
        {"m1": "1", "m2": "2", "m3": "0.5", "r": "0.1", "l": "0.3", "F": "0", "tau": "0"},
        {"theta": "0.3"},
        {"theta": "20"},
    ),
    FOUR_BAR: (
        {"m2": "1", "m3": "2", "m4": "1.5", "mf": "3", "rf": "0.2", "a": "0.1", "b": "0.35", "c": "0.3"}
        | {"d": "0.35", "tau": "0"},
        {"theta2": "0.5", "theta3": "0.5", "theta4": "1.5"},
        {"theta2": "10"},
    ),
}


def _derived(rel: str) -> Derivation:
    return derived_lagrange(rel)  # shared with tests/codegen/test_constrained_code.py


def _run(rel: str, t_end: float = 0.25, **changes: dict[str, str]) -> SimulationResult:
    values, q0, qd0 = RUNS[rel]
    settings = Settings(
        values=values | changes.get("values", {}),
        q0=q0 | changes.get("q0", {}),
        qd0=qd0 | changes.get("qd0", {}),
        t_end=t_end,
        samples=101,
    )
    return simulate_system(_derived(rel), settings, Path(rel).name)


@pytest.mark.parametrize(
    "rel",
    [
        pytest.param(DISC, id="disc"),
        pytest.param(COIN, id="coin"),
        pytest.param(SLIDER, id="slider-crank"),
        pytest.param(FOUR_BAR, marks=pytest.mark.slow, id="four-bar"),
    ],
)
def test_conservative_constrained_runs_keep_their_energy(rel: str) -> None:
    result = _run(rel)
    assert result.trajectory.stopped is None
    assert result.conservative
    assert result.check_passed, (result.drift, result.tolerance)
    assert result.drift is not None and result.drift <= result.tolerance
    assert result.max_residual is not None and result.max_residual < 1e-8
    assert float(np.max(result.kinetic)) > 0.1  # it moved


def test_rolling_disc_follows_the_closed_form_and_lambda_is_the_friction() -> None:
    result = _run(DISC, t_end=1.0, qd0={"phi": "0"})
    m, r, g, alpha = 2.0, 0.3, 9.81, math.radians(30)
    t = result.trajectory.t
    x, phi = result.trajectory.q[:, 0], result.trajectory.q[:, 1]
    assert np.max(np.abs(phi - g * math.sin(alpha) * t**2 / (3 * r))) < 1e-9
    assert np.max(np.abs(x - r * phi)) < 1e-10
    assert result.multipliers is not None
    assert np.max(np.abs(result.multipliers[:, 0] + m * g * math.sin(alpha) / 3)) < 1e-9
    assert result.solved_positions == ("x",) and result.solved_rates == ("x",)


def test_coin_at_constant_rates_rolls_on_a_circle() -> None:
    result = _run(COIN, t_end=2.0)
    m, r, theta_dot, phi_dot = 1.0, 0.3, 1.0, 3.0
    t, q = result.trajectory.t, result.trajectory.q
    radius = r * phi_dot / theta_dot
    theta = theta_dot * t
    assert np.max(np.abs(q[:, 0] - radius * np.sin(theta))) < 1e-9
    assert np.max(np.abs(q[:, 1] - radius * (1 - np.cos(theta)))) < 1e-9
    assert np.max(np.abs(q[:, 3] - phi_dot * t)) < 1e-9
    # lambda_1 acts on x alone among x, y: m x_ddot = lambda_1, x_ddot = -R phi_dot theta_dot sin(theta)
    assert result.multipliers is not None
    assert np.max(np.abs(result.multipliers[:, 0] + m * r * phi_dot * theta_dot * np.sin(theta))) < 1e-8
    assert result.solved_positions == () and result.solved_rates == ("x", "y")


@pytest.mark.parametrize(("guess", "branch"), [("0", 1.0), ("3", -1.0)], ids=["rod-ahead", "rod-behind"])
def test_slider_crank_starts_on_its_loop(guess: str, branch: float) -> None:
    """beta from l sin(beta) = -r sin(theta), the branch picked by the guess; s, beta_dot and s_dot follow."""
    result = _run(SLIDER, t_end=0.01, q0={"beta": guess})
    r, rod, theta, theta_dot = 0.1, 0.3, 0.3, 20.0
    beta = math.asin(-r * math.sin(theta) / rod)
    if branch < 0:
        beta = math.pi - beta
    s = r * math.cos(theta) + rod * math.cos(beta)
    beta_dot = -r * math.cos(theta) * theta_dot / (rod * math.cos(beta))
    s_dot = -r * math.sin(theta) * theta_dot - rod * math.sin(beta) * beta_dot
    assert result.q0 == pytest.approx((theta, beta, s), rel=1e-12, abs=1e-12)
    assert result.qd0 == pytest.approx((theta_dot, beta_dot, s_dot), rel=1e-12, abs=1e-12)


def test_a_loop_that_cannot_close_and_a_wrong_dependent_rate_are_spec_errors(tmp_path: Path) -> None:
    with pytest.raises(SpecErrors, match=r"the constraints hold at no configuration with theta = 1\.5708"):
        _run(SLIDER, values={"r": "0.5"}, q0={"theta": "pi/2"})
    with pytest.raises(
        SpecErrors, match=r"initial rate of the dependent coordinate 's' is 5, and the constraints give"
    ):
        _run(SLIDER, qd0={"s": "5"})
    values = RUNS[DISC][0]
    args = [f"--set={k}={v}" for k, v in values.items()] + ["--q0=phi=0", "--qd0=x=5"]
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["simulate", str(ROOT / DISC), "-o", str(out), "--no-plots", *args])
    assert result.exit_code == 3, result.output
    assert "l-disc-rolling-down-incline.yaml:1:1: error: the initial rate of the dependent coordinate 'x'" in (
        result.output
    )
    assert "Traceback" not in result.output
    assert not out.exists()


def test_outputs_carry_the_residuals_and_the_multipliers(tmp_path: Path) -> None:
    values = RUNS[DISC][0]
    args = [f"--set={k}={v}" for k, v in values.items()] + ["--q0=phi=0", "--t-end=0.2", "--samples=11"]
    result = CliRunner().invoke(app, ["simulate", str(ROOT / DISC), "-o", str(tmp_path), "--no-plots", *args])
    assert result.exit_code == 0, result.output
    assert "from the constraints at the start: x = 0, x_dot = 0" in result.output
    assert "largest constraint residual" in result.output
    stem = Path(DISC).stem
    rows = (tmp_path / f"{stem}.trajectory.csv").read_text().splitlines()
    assert rows[0].endswith(",total_energy,residual_rolling,lambda_1")
    assert len(rows) == 12
    doc = json.loads((tmp_path / f"{stem}.trajectory.json").read_text())
    cons = doc["constraints"]
    assert cons["method"] == "baumgarte" and cons["stabilisation"] == pytest.approx(10 / 0.2)
    (item,) = cons["items"]
    assert item["name"] == "rolling" and item["kind"] == "position" and item["multiplier"] == "lambda_1"
    assert len(item["lambda"]) == len(item["residual"]) == 11
    assert item["lambda"][0] == pytest.approx(-2 * 9.81 * 0.5 / 3, rel=1e-9)
    import jsonschema

    from tutgen.schemas import SCHEMAS

    schema = SCHEMAS["simulation"]()
    jsonschema.Draft202012Validator(schema).validate(doc)
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.Draft202012Validator(schema).validate({**doc, "constraints": {**cons, "items": [{"name": 1}]}})


def test_worked_solution_simulates_the_constrained_motion() -> None:
    """`ask: [simulation]` of a constrained spec runs the multipliers' system from a consistent start (the
    section says so), not the unconstrained coordinates' equations."""
    from tutgen.render.markdown import render_markdown
    from tutgen.sim.solution import attach_simulation
    from tutgen.spec.validate import load_system_text

    text = (ROOT / DISC).read_text(encoding="utf-8")
    for name, value in (("m", "2 kg"), ("R", "0.3 m"), ("alpha", "0.5"), ("g", "9.81 m/s^2")):
        text = text.replace(f"  {name}: {{", f"  {name}: {{value: {value}, ", 1)
    text += "simulate: {t: [0, 1], q0: {phi: 2, x: 0}, samples: 11}\nask: [equations_of_motion, simulation]\n"
    derivation = attach_simulation(derive(load_system_text(text, "disc.yaml"), "lagrange"))
    run = derivation.simulation
    assert run is not None and run.check_passed
    (x0, phi0) = (run.initial[0][1], run.initial[1][1])
    assert (x0, phi0) == pytest.approx((0.6, 2.0), rel=1e-12)  # x = R phi, from the constraint
    md = render_markdown(derivation)
    assert "solved together for $\\ddot q$ and $\\lambda$ (Baumgarte-stabilised)" in md
    assert "The dependent coordinates and rates start where the constraints put them." in md
    # the simulation comes after the constrained equations it integrates
    kinds = [str(step.kind) for step in derivation.steps]
    assert kinds[-1] == "simulation" and kinds.index("reduced_equations") < kinds.index("simulation")
    assert md.index("Constraints") < md.index("Numerical simulation")


def test_ask_simulation_needs_only_the_independent_coordinates_initial_values() -> None:
    """A constrained spec's `q0` may leave out the dependent coordinates (the run solves them); an
    unconstrained spec must still give every coordinate (tests/bad_specs/ask-simulation-without-q0.yaml)."""
    from tutgen.spec.validate import load_system_text

    text = (ROOT / SLIDER).read_text(encoding="utf-8")
    text += "simulate: {t: [0, 1], q0: {theta: 0.3}}\nask: [equations_of_motion, simulation]\n"
    load_system_text(text, "slider.yaml")  # no error
    with pytest.raises(SpecErrors, match="missing: theta"):
        load_system_text(text.replace("q0: {theta: 0.3}", "q0: {s: 0.3}"), "slider.yaml")


def test_a_dead_point_stops_the_run_where_the_loop_locks() -> None:
    """r = l: at theta = 3 pi / 2 the crank and the rod both stand across the line of the piston, A loses
    rank and [[H, -A^T], [A, 0]] is singular; the run stops there (exit 7 from the command), samples kept."""
    result = _run(SLIDER, t_end=0.1, values={"l": "0.1"}, q0={"theta": "4.4"})
    tr = result.trajectory
    assert tr.stop_kind == "singular"
    assert tr.stopped is not None and tr.stopped.startswith("the matrix [[H, -A^T], [A, 0]] is singular at t = ")
    assert tr.stop_state is not None
    assert tr.stop_state[0] == pytest.approx(3 * math.pi / 2, abs=1e-4)
    assert 0 < len(tr.t) < 101 and result.residuals is not None and len(result.residuals) == len(tr.t)


def test_an_input_in_a_constraint_is_refused_at_its_place() -> None:
    """b = A_dot q_dot has no time derivatives: a constraint that moves in time would give a wrong motion."""
    from tutgen.spec.validate import load_system_text

    text = (ROOT / DISC).read_text(encoding="utf-8")
    text += "simulate: {t: [0, 1], q0: {phi: 0, x: 0}, inputs: {R: 0.3 + 0.01*t}}\n"
    derivation = derive(load_system_text(text, "disc.yaml"), "lagrange")
    settings = Settings(values={"m": "2", "alpha": "0.5", "g": "9.81"}, t_end=0.1, samples=11)
    with pytest.raises(SpecErrors) as err:
        simulate_system(derivation, settings, "disc.yaml")
    line = len(text.splitlines())
    assert f"disc.yaml:{line}:" in str(err.value)
    assert "input 'R' enters the constraints, which would then change in time" in str(err.value)


def _start_on_the_figures_branch(rel: str, changes: dict[str, str]) -> None:
    """Without a value for the dependent coordinates the start is the engine's solve
    (kinematics.solve_positions) on the branch the figure shows: the loop closes to 1e-12, and the start
    lies on the figure's branch (a four-bar's assembly, open or crossed, at the run's own lengths)."""
    from tutgen.engine.constraints.positions import assembly_at, branch_at
    from tutgen.figure.build import drawn_branch

    values, _q0, qd0 = RUNS[rel]
    result = simulate_system(
        _derived(rel), Settings(values=values, q0=changes, qd0=qd0, t_end=0.01, samples=3), Path(rel).name
    )
    derivation = _derived(rel)
    ck = derivation.constraints.kinematics
    system = derivation.system
    numbers = {p.symbol: float(values[p.name]) for p in system.parameters}
    numbers |= {c.q: v for c, v in zip(system.coordinates, result.q0, strict=True)}
    residual = [float(f.xreplace({k: sp.Float(v, 30) for k, v in numbers.items()})) for f in ck.functions]
    assert max(abs(r) for r in residual) < 1e-12
    assert ck.loop is not None
    shown = drawn_branch(system, ck.loop)
    assert shown is not None
    sign, assembly = shown
    if assembly is not None:
        assert assembly_at(ck.loop, numbers) == assembly
    else:
        assert branch_at(ck.loop, numbers, [c.q for c in system.coordinates]) == sign


def test_slider_crank_starts_on_the_figures_branch() -> None:
    _start_on_the_figures_branch(SLIDER, {"theta": "0.3"})
    _start_on_the_figures_branch(SLIDER, {"theta": "2.5"})


@pytest.mark.slow  # the four-bar's Lagrange derivation: about 5 CPU-s
def test_four_bar_starts_on_the_figures_assembly() -> None:
    _start_on_the_figures_branch(FOUR_BAR, {"theta2": "0.5"})
    _start_on_the_figures_branch(FOUR_BAR, {"theta2": "-2"})
