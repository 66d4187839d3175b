"""`tutgen simulate` (issue 19): physics the integration must keep, and the command's contract.

- A double pendulum (no dissipation, no inputs) keeps its energy within 100 x rtol over 10 s.
- A damped pendulum loses energy monotonically; its run is not called conservative.
- The small oscillation of a simple pendulum has the period 2 pi sqrt(l/g) to 1e-6.
- A driven spring-mass follows the closed-form forced response (inputs in t).
- A mass matrix that becomes singular stops the run where it does (exit 7) with the trajectory so far
  written; missing values and initial conditions are named at their place (exit 3) with nothing
  written; the same run gives the same bytes; `tutgen --help` loads neither scipy nor matplotlib.
"""

from __future__ import annotations

import json
import subprocess
import sys
from functools import cache
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from tests.conftest import ROOT, solved
from tutgen.cli.main import app
from tutgen.engine.pipeline import derive
from tutgen.errors import SimulationError
from tutgen.sim.run import Settings, simulate_system
from tutgen.spec.validate import load_system_text

pytest.importorskip("scipy")
pytest.importorskip("matplotlib")

DOUBLE = str(ROOT / "specs/examples/a-double-pendulum-rods.yaml")

PENDULUM = """
tutgen: 1
title: simple pendulum
parameters: {{m: 0.7 kg, l: 0.9 m, g: 9.81 m/s^2{extra}}}
coordinates: {{theta: {{dimension: angle}}}}
gravity: [0, -g, 0]
bodies: {{bob: {{mass: m, com: [0, -l, 0]}}}}
joints: {{pin: {{type: revolute, parent: ground, child: bob, axis: z, coordinate: theta}}}}
{more}
"""


@cache
def derived(text: str):
    return derive(load_system_text(text))


def run(*args: str | Path):
    return CliRunner().invoke(app, [str(a) for a in args])


def test_double_pendulum_keeps_its_energy_over_10_s() -> None:
    _, derivation, _ = solved(DOUBLE)
    settings = Settings(
        values={"m1": "1", "m2": "0.5", "l1": "1", "l2": "0.8", "g": "9.81"},
        q0={"theta1": "60deg", "theta2": "-30deg"},
        qd0={"theta2": "1"},
        t_end=10,
        samples=201,
    )
    result = simulate_system(derivation, settings, "a.yaml")
    assert result.trajectory.stopped is None and result.trajectory.t[-1] == 10
    assert result.conservative
    assert result.drift is not None and result.drift <= result.tolerance
    assert result.check_passed is True
    assert np.ptp(result.kinetic) > 1  # it really moves: energy goes back and forth between T and U


def test_damped_pendulum_loses_energy_monotonically() -> None:
    text = PENDULUM.format(
        extra=", c: 0.05 N*m*s",
        more="dampers: {air: {coefficient: c, extension: theta}}\nsimulate: {t: [0, 6], q0: {theta: 1}, samples: 301}",
    )
    result = simulate_system(derived(text), Settings(), "p.yaml")
    total = result.total
    assert not result.conservative and result.check_passed is None
    assert np.all(np.diff(total) <= 1e-9 * abs(total[0]))
    assert total[-1] < total[0] - 0.1 * (total[0] - result.potential.min())


def test_small_oscillation_has_the_pendulum_period() -> None:
    length, g = 0.9, 9.81
    period = 2 * np.pi * np.sqrt(length / g)
    text = PENDULUM.format(extra="", more=f"simulate: {{t: [0, {3.2 * period}], q0: {{theta: 1e-4}}, samples: 12001}}")
    result = simulate_system(derived(text), Settings(rtol=1e-12, atol=1e-16), "p.yaml")
    t, theta = result.trajectory.t, result.trajectory.q[:, 0]
    down = np.nonzero((theta[:-1] > 0) & (theta[1:] <= 0))[0]
    crossings = t[down] - theta[down] * (t[down + 1] - t[down]) / (theta[down + 1] - theta[down])
    assert len(crossings) == 3
    measured = np.diff(crossings)
    # the amplitude correction theta0^2/16 is 6e-10: far below the tolerance
    assert np.max(np.abs(measured / period - 1)) < 1e-6


def test_inputs_drive_a_spring_mass_as_the_closed_form_says() -> None:
    text = """
tutgen: 1
title: driven spring-mass
parameters: {m: 2 kg, k: 50 N/m, F0: 3 N, w: 2 rad/s, F: {dimension: force}}
coordinates: [x]
bodies: {block: {mass: m}}
joints: {slide: {type: prismatic, parent: ground, child: block, axis: x, coordinate: x}}
springs: {wall: {stiffness: k, extension: x}}
generalized_forces: {x: F}
simulate: {t: [0, 4], q0: {x: 0}, inputs: {F: F0*sin(w*t)}, samples: 81}
"""
    result = simulate_system(derived(text), Settings(), "s.yaml")
    m, k, f0, w = 2.0, 50.0, 3.0, 2.0
    omega = np.sqrt(k / m)
    t = result.trajectory.t
    exact = f0 / (k - m * w**2) * (np.sin(w * t) - w / omega * np.sin(omega * t))
    assert np.max(np.abs(result.trajectory.q[:, 0] - exact)) < 1e-8
    assert not result.conservative


def test_missing_values_are_named_where_declared(tmp_path: Path) -> None:
    out = tmp_path / "out"
    result = run("simulate", DOUBLE, "-o", out, "--q0", "theta1=1", "--q0", "theta2=0", "--set", "g=9.81")
    assert result.exit_code == 3, result.output
    for name in ("m1", "m2", "l1", "l2"):
        assert f"parameter '{name}' has no value, and the simulation needs one" in result.output
    line = next(i for i, ln in enumerate(Path(DOUBLE).read_text().splitlines(), 1) if ln.strip().startswith("m1:"))
    assert f"a-double-pendulum-rods.yaml:{line}:3: error: parameter 'm1'" in result.output
    assert "'g' has no value" not in result.output
    assert not out.exists()
    assert "Traceback" not in result.output


def test_missing_initial_conditions_and_unknown_names(tmp_path: Path) -> None:
    spec = tmp_path / "p.yaml"
    spec.write_text(PENDULUM.format(extra="", more=""))
    result = run("simulate", spec, "-o", tmp_path)
    assert result.exit_code == 3
    assert f"{spec}:1:1: error: coordinate 'theta' has no initial value" in result.output
    result = run("simulate", spec, "-o", tmp_path, "--q0", "thta=1")
    assert result.exit_code == 2
    assert "unknown coordinate 'thta' (known: theta); did you mean 'theta'?" in result.output
    result = run("simulate", spec, "-o", tmp_path, "--q0", "theta=__import__('os')")
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert list(tmp_path.iterdir()) == [spec]


def test_singular_mass_matrix_stops_the_run_with_the_trajectory_so_far(tmp_path: Path) -> None:
    # T = m x^2 x_dot^2 / 2: H = m x^2 vanishes at x = 0, reached at t = 1/2 from x = 1, x_dot = -1
    spec = tmp_path / "s.yaml"
    spec.write_text(
        "tutgen: 1\ntitle: singular\nparameters: {m: 1 kg}\ncoordinates: [x]\n"
        "energy: {kinetic: m*x^2*x_dot^2/2}\n"
        "simulate: {t: [0, 2], q0: {x: 1}, qd0: {x: -1}, samples: 201}\n"
    )
    result = run("simulate", spec, "-o", tmp_path / "out", "--no-plots")
    assert result.exit_code == 7, result.output
    assert "the mass matrix H is singular at t = 0.5" in result.output
    assert "the trajectory so far is in" in result.output
    doc = json.loads((tmp_path / "out" / "s.trajectory.json").read_text())
    assert doc["stopped"]["reason"] == "singular"
    assert 0.45 < doc["t"][-1] <= 0.5 and abs(doc["stopped"]["t"] - 0.5) < 1e-3
    rows = (tmp_path / "out" / "s.trajectory.csv").read_text().splitlines()
    assert rows[0] == "t,x,x_dot,kinetic_energy,potential_energy,total_energy"
    assert len(rows) - 1 == len(doc["t"])


def test_a_run_out_of_time_is_an_error_and_writes_nothing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import tutgen.limits

    monkeypatch.setattr(tutgen.limits, "remaining", lambda: 1e-9)
    text = PENDULUM.format(extra="", more="simulate: {q0: {theta: 1}}")
    with pytest.raises(SimulationError) as info:
        simulate_system(derived(text), Settings(timeout=5), "p.yaml")
    assert "did not finish within --timeout 5 s" in str(info.value)
    assert info.value.exit_code == 7


def test_outputs_are_the_same_bytes_every_run(tmp_path: Path) -> None:
    spec = tmp_path / "p.yaml"
    spec.write_text(PENDULUM.format(extra="", more="simulate: {t: [0, 1], q0: {theta: 0.5}, samples: 21}"))
    first = run("simulate", spec, "-o", tmp_path / "a")
    second = run("simulate", spec, "-o", tmp_path / "b")
    assert first.exit_code == 0 and second.exit_code == 0, first.output
    assert "relative energy drift" in first.output and ": ok" in first.output
    names = sorted(p.name for p in (tmp_path / "a").iterdir())
    assert names == ["p.plot.png", "p.snapshots.png", "p.trajectory.csv", "p.trajectory.json"]
    for name in names:
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes(), name
    again = run("simulate", spec, "-o", tmp_path / "a")
    assert again.exit_code == 2 and "exists; add --force" in again.output


def test_help_imports_neither_scipy_nor_matplotlib() -> None:
    probe = (
        "import sys\n"
        "from tutgen.cli.main import app\n"
        "try:\n    app(['--help'], prog_name='tutgen')\nexcept SystemExit:\n    pass\n"
        "heavy = sorted(m for m in sys.modules if m.split('.')[0] in ('scipy', 'matplotlib'))\n"
        "print('HEAVY', heavy)\n"
    )
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, cwd=ROOT, check=True)
    assert "HEAVY []" in out.stdout, out.stdout[-500:]


def test_a_failed_energy_check_is_exit_8_with_the_files_written(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import tutgen.sim.run

    # the check compares the drift with DRIFT_FACTOR x rtol: a factor of 1e-9 makes any real drift fail
    monkeypatch.setattr(tutgen.sim.run, "DRIFT_FACTOR", 1e-9)
    spec = tmp_path / "p.yaml"
    spec.write_text(PENDULUM.format(extra="", more="simulate: {t: [0, 1], q0: {theta: 0.5}, samples: 11}"))
    result = run("simulate", spec, "-o", tmp_path / "out", "--no-plots")
    assert result.exit_code == 8, result.output
    assert "energy check failed" in result.output
    doc = json.loads((tmp_path / "out" / "p.trajectory.json").read_text())
    assert doc["energy_check"]["passed"] is False and doc["energy_check"]["conservative"] is True
