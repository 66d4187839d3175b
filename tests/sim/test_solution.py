"""`ask: [simulation]` (issue 19): the run of the spec's `simulate` section in the worked solution.

- The section is there only when asked (never by default), after the equations of motion it integrates.
- Markdown and LaTeX name PNG files written beside them; the PDF includes them; JSON says where they are
  and reports the energy check; the plots are the same bytes on every run.
- The numbers are the physics': a small oscillation returns to its start after one analytic period, and
  the energy of a conservative spec is kept.
- A solve that does not ask for it imports neither scipy nor matplotlib.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from functools import cache
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tests.conftest import ROOT
from tutgen.cli.main import app
from tutgen.engine.pipeline import derive
from tutgen.engine.steps import StepKind, plan_steps
from tutgen.sim.solution import attach_simulation
from tutgen.spec.validate import load_system_text

pytest.importorskip("scipy")
pytest.importorskip("matplotlib")

L, G = 0.5, 9.81
PERIOD = 2 * math.pi * math.sqrt(L / G)  # a point mass on a massless rod, small oscillation

#: gravity along +x, so that theta = 0 (the bob on the x axis) is the stable equilibrium
PENDULUM = f"""
tutgen: 1
title: Simple pendulum
parameters: {{m: 1 kg, l: {L} m, g: {G} m/s^2}}
coordinates: [theta]
gravity: [g, 0, 0]
bodies:
  bob: {{parts: {{ball: {{shape: point, mass: m, at: [l, 0, 0]}}}}}}
joints:
  pin: {{type: revolute, parent: ground, child: bob, axis: z, coordinate: theta}}
ask: [equations_of_motion, simulation]
simulate: {{t: [0, {PERIOD!r}], q0: {{theta: 0.001}}, samples: 101}}
"""


@cache
def simulated(text: str = PENDULUM):
    return attach_simulation(derive(load_system_text(text, "pendulum.yaml")))


def solve(tmp_path: Path, fmt: str, name: str = "pendulum.yaml", text: str = PENDULUM) -> Path:
    tmp_path.mkdir(parents=True, exist_ok=True)
    spec = tmp_path / name
    spec.write_text(text, encoding="utf-8")
    out = tmp_path / "out" / f"{spec.stem}.{fmt}"
    result = CliRunner().invoke(app, ["solve", str(spec), "-f", fmt, "-o", str(out)])
    assert result.exit_code == 0, result.output
    return out


def test_simulation_is_a_step_only_when_asked() -> None:
    asked = load_system_text(PENDULUM)
    default = load_system_text(PENDULUM.replace("ask: [equations_of_motion, simulation]\n", ""))
    plan = [kind for kind, _ in plan_steps(asked)]
    assert plan[-1] is StepKind.SIMULATION and StepKind.EQUATIONS_OF_MOTION in plan
    assert not derive(default).has_step(StepKind.SIMULATION)


def test_small_oscillation_returns_to_its_start_after_one_period() -> None:
    run = simulated().simulation
    assert run is not None
    ((name, q1, qd1),) = run.final
    assert name == "theta" and run.t_reached == pytest.approx(PERIOD, rel=1e-12)
    # amplitude 1e-3: the period's correction is theta0^2/16 ~ 6e-8 relative; the return is to ~1e-10
    assert abs(q1 - 1e-3) < 1e-9 and abs(qd1) < 1e-8
    assert run.conservative and run.check_passed is True and run.drift is not None and run.drift < run.tolerance
    assert [p.kind for p in run.plots] == ["plot", "snapshots"]
    assert all(p.png.startswith(b"\x89PNG\r\n\x1a\n") for p in run.plots)


def test_markdown_names_the_plots_written_beside_it(tmp_path: Path) -> None:
    md = solve(tmp_path, "md")
    text = md.read_text(encoding="utf-8")
    assert "## 5. Numerical simulation" in text
    for name in ("pendulum.simulation.png", "pendulum.snapshots.png"):
        assert f"(<{name}>)" in text
        assert (md.parent / name).read_bytes().startswith(b"\x89PNG")
    assert "its relative drift is" in text and ": passed." in text


def test_plots_are_the_same_bytes_on_every_run(tmp_path: Path) -> None:
    first = solve(tmp_path / "a", "md").parent
    second = solve(tmp_path / "b", "md").parent
    for name in ("pendulum.simulation.png", "pendulum.snapshots.png", "pendulum.md"):
        assert (first / name).read_bytes() == (second / name).read_bytes(), name
    png = (first / "pendulum.simulation.png").read_bytes()
    assert b"tEXt" not in png and b"tIME" not in png  # no software version, no date


def test_json_says_where_the_plots_are_and_reports_the_energy(tmp_path: Path) -> None:
    out = solve(tmp_path, "json")
    doc = json.loads(out.read_text(encoding="utf-8"))
    sim = doc["simulation"]
    assert sim["files"] == {"plot": "pendulum.simulation.png", "snapshots": "pendulum.snapshots.png"}
    assert all((out.parent / f).is_file() for f in sim["files"].values())
    assert sim["energy"]["conservative"] is True and sim["energy"]["check_passed"] is True
    assert sim["energy"]["drift"] < sim["energy"]["tolerance"]
    assert sim["initial"] == {"theta": {"q": 0.001, "qd": 0.0}}
    from tutgen.schemas import solution_schema

    jsonschema = pytest.importorskip("jsonschema")
    jsonschema.validate(doc, solution_schema())


def test_latex_includes_the_plots_by_their_compile_names(tmp_path: Path) -> None:
    tex = solve(tmp_path, "tex").read_text(encoding="utf-8")
    assert "\\includegraphics[width=0.7\\linewidth,height=0.4\\textheight,keepaspectratio]{simulation-plot.png}" in tex
    assert "\\IfFileExists{pendulum.snapshots.png}" in tex  # beside a .tex compiled elsewhere
    assert (tmp_path / "out" / "pendulum.simulation.png").is_file()


def test_an_existing_plot_is_not_overwritten_without_force(tmp_path: Path) -> None:
    (tmp_path / "out").mkdir()
    keep = tmp_path / "out" / "pendulum.simulation.png"
    keep.write_bytes(b"mine")
    spec = tmp_path / "pendulum.yaml"
    spec.write_text(PENDULUM, encoding="utf-8")
    result = CliRunner().invoke(app, ["solve", str(spec), "-f", "json", "-o", str(tmp_path / "out" / "p.json")])
    assert result.exit_code == 2 and "add --force" in result.output
    assert keep.read_bytes() == b"mine" and not (tmp_path / "out" / "p.json").exists()


def test_missing_parameter_value_is_a_located_spec_error(tmp_path: Path) -> None:
    text = PENDULUM.replace("l: 0.5 m", "l: {dimension: length}")
    spec = tmp_path / "pendulum.yaml"
    spec.write_text(text, encoding="utf-8")
    result = CliRunner().invoke(app, ["solve", str(spec), "-o", str(tmp_path / "out" / "p.md")])
    assert result.exit_code == 3, result.output
    assert "parameter 'l' has no value, and the simulation needs one" in result.output
    assert "Traceback" not in result.output and not (tmp_path / "out").exists()


@pytest.mark.slow
def test_the_pdf_contains_the_plots_and_is_the_same_bytes_twice(tmp_path: Path) -> None:
    pdf = solve(tmp_path / "a", "pdf").read_bytes()
    assert pdf.count(b"/Subtype /Image") + pdf.count(b"/Subtype/Image") >= 2
    assert solve(tmp_path / "b", "pdf").read_bytes() == pdf


def test_a_solve_without_simulation_imports_neither_scipy_nor_matplotlib(tmp_path: Path) -> None:
    spec = tmp_path / "p.yaml"
    spec.write_text(PENDULUM.replace(", simulation]", "]"), encoding="utf-8")
    code = (
        "import sys; from tutgen.api import solve_specs; from pathlib import Path; "
        f"solve_specs([Path({str(spec)!r})], 'md'); "
        "print(sorted(m for m in ('scipy', 'matplotlib') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_a_markdown_sheet_shows_the_plots_beside_it(tmp_path: Path) -> None:
    (tmp_path / "pendulum.yaml").write_text(PENDULUM, encoding="utf-8")
    sheet = tmp_path / "sheet.yaml"
    sheet.write_text("tutgen_sheet: 1\ntitle: Sheet\nproblems:\n  - spec: pendulum.yaml\n", encoding="utf-8")
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["sheet", str(sheet), "-o", str(out), "-f", "md"])
    assert result.exit_code == 0, result.output
    solutions = (out / "solutions.md").read_text(encoding="utf-8")
    for name in ("figures/pendulum.simulation.png", "figures/pendulum.snapshots.png"):
        assert f"(<{name}>)" in solutions and (out / name).read_bytes().startswith(b"\x89PNG")
    assert "a numerical simulation of the motion" in (out / "questions.md").read_text(encoding="utf-8")
