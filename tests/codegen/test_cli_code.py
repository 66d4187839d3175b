"""`tutgen code` on the command line: stdout, -o FILE and -o DIR/, refusals, a spec with nothing to generate."""

from __future__ import annotations

from pathlib import Path

from typer.testing import CliRunner

from tests.conftest import ROOT
from tutgen.cli.main import app

P05 = ROOT / "specs/tutorial-1/p05-rr-arm.yaml"


def run(*args: str | Path):
    return CliRunner().invoke(app, [str(a) for a in args])


def test_code_writes_stdout_a_file_and_into_a_directory(tmp_path: Path) -> None:
    out = run("code", P05, "--lang", "julia")
    assert out.exit_code == 0, out.output
    assert "module p05_rr_arm" in out.output and "function inverse_dynamics(" in out.output
    target = tmp_path / "arm.c"
    assert run("code", P05, "--lang", "c", "-o", target).exit_code == 0
    assert "void p05_rr_arm_mass_matrix(" in target.read_text()
    again = run("code", P05, "--lang", "c", "-o", target)
    assert again.exit_code == 2 and "exists; add --force" in again.output
    assert run("code", P05, "--lang", "matlab", "-o", f"{tmp_path}/m/").exit_code == 0
    assert (tmp_path / "m" / "p05_rr_arm.m").read_text().startswith("function dyn = p05_rr_arm()")
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["arm.c", "m", "p05_rr_arm.m"]  # no temporary files left


def test_code_refuses_the_spec_and_a_spec_without_dynamics(tmp_path: Path) -> None:
    spec = tmp_path / "s.yaml"
    spec.write_text(P05.read_text())
    out = run("code", spec, "-o", spec, "--force")
    assert out.exit_code == 2 and "refusing to overwrite the spec" in out.output
    assert spec.read_text() == P05.read_text()
    out = run("code", ROOT / "specs/tutorial-1/p01-composite-inertia.yaml")
    assert out.exit_code == 4 and "no coordinates" in out.output and "Traceback" not in out.output
