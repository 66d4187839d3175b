"""A sheet's marking: the sheet's (or a problem's) ``marking:`` is copied into every variant's
``marking-<problem>.yaml``, a marking key for `tutgen check --key` that also carries the significant
figures the variant's solution prints decimals with."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner, Result

from tests.conftest import SPECS
from tutgen.cli.main import app
from tutgen.errors import EXIT_CHECK_FAILED, EXIT_INVALID_SPEC, EXIT_OK

TUTORIAL = SPECS / "tutorial-1"
SHEET = f"""
title: Marked sheet
marking: {{ask: [kinetic_energy, mass_matrix], tolerance: {{rel_tol: 0.001}}}}
problems:
  - spec: {TUTORIAL / "p04-rp-arm.yaml"}
    vary:
      m: {{range: [1, 5], step: 0.5, unit: kg}}
      g: 9.81 m/s^2
  - spec: {TUTORIAL / "p10-given-kinetic-energy.yaml"}
    marking: {{ask: [christoffel], items: {{mass_matrix: {{scaling: false}}}}}}
"""


def run(*args: str | Path) -> Result:
    return CliRunner().invoke(app, [str(a) for a in args])


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> Path:
    tmp = tmp_path_factory.mktemp("marked")
    (tmp / "sheet.yaml").write_text(SHEET, encoding="utf-8")
    result = run("sheet", tmp / "sheet.yaml", "-o", tmp / "out", "-f", "tex", "--variants", "1", "-j", "1")
    assert result.exit_code == EXIT_OK, result.output
    return tmp / "out" / "variants" / "v001"


def test_sheet_marking_is_copied_into_each_variants_marking_key(built: Path) -> None:
    def key(problem: str) -> dict[str, object]:
        return yaml.safe_load((built / f"marking-{problem}.yaml").read_text(encoding="utf-8"))

    assert key("p04-rp-arm") == {
        "ask": ["kinetic_energy", "mass_matrix"],
        "tolerance": {"rel_tol": 0.001},
        "significant_figures": 4,
    }
    # a problem's own marking: wins over the sheet's and over its spec's (p10 asks mass_matrix, christoffel)
    assert key("p10-given-kinetic-energy") == {
        "ask": ["christoffel"],
        "items": {"mass_matrix": {"scaling": False}},
        "significant_figures": 4,
    }


def test_sheet_marking_key_marks_the_variant(built: Path, tmp_path: Path) -> None:
    spec = built / "specs" / "p04-rp-arm.yaml"
    marking = built / "marking-p04-rp-arm.yaml"
    own = run("check", spec, built / "key-p04-rp-arm.yaml", "--key", marking, "--format", "json")
    assert own.exit_code == EXIT_OK, own.output
    assert '"source": "key"' in own.stdout
    partial = tmp_path / "partial.yaml"
    keyed = yaml.safe_load((built / "key-p04-rp-arm.yaml").read_text(encoding="utf-8"))
    partial.write_text(yaml.safe_dump({"kinetic_energy": keyed["kinetic_energy"]}), encoding="utf-8")
    result = run("check", spec, partial, "--key", marking)
    assert result.exit_code == EXIT_CHECK_FAILED
    assert "1 correct, 0 wrong, 1 missing" in result.stdout


def test_sheet_marking_errors_are_located_in_the_sheet(tmp_path: Path) -> None:
    sheet = tmp_path / "sheet.yaml"
    sheet.write_text(
        f"title: x\nmarking: {{ask: [H]}}\nproblems:\n  - spec: {TUTORIAL / 'p04-rp-arm.yaml'}\n"
        "    marking: {tolerance: 3}\n",
        encoding="utf-8",
    )
    result = run("sheet", sheet, "-o", tmp_path / "out", "-f", "md", "--variants", "1")
    assert result.exit_code == EXIT_INVALID_SPEC, result.output
    assert f"{sheet}:2:17: error: unknown result 'H' in the asked item" in result.output
    assert f"{sheet}:5:26: error: 'tolerance' is a mapping" in result.output
