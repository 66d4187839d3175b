"""Degenerate but valid systems: a result and a remark, never a crash.

Each spec in ``tests/degenerate/`` starts with ``# expect-remark: TEXT``; solving it must succeed
(exit 0, JSON) with a remark containing TEXT, and every check of the derivation must pass.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tests.conftest import ROOT
from tutgen.cli.main import app
from tutgen.errors import EXIT_OK

DEGENERATE = ROOT / "tests" / "degenerate"
SPECS = sorted(DEGENERATE.glob("*.yaml"))


def expected_remark(spec: Path) -> str:
    first = spec.read_text(encoding="utf-8").splitlines()[0]
    assert first.startswith("# expect-remark: "), f"{spec.name} must start with '# expect-remark: '"
    return first.removeprefix("# expect-remark: ")


def test_degenerate_corpus_covers_each_case() -> None:
    assert {s.stem for s in SPECS} >= {
        "zero-mass-body",
        "zero-stiffness-spring",
        "unused-coordinate",
        "no-gravity",
        "singular-mass-matrix",
    }


@pytest.mark.parametrize("spec", SPECS, ids=lambda p: p.stem)
def test_degenerate_spec_solves_with_remark(spec: Path) -> None:
    result = CliRunner().invoke(app, ["solve", str(spec), "--format", "json"])
    assert result.exit_code == EXIT_OK, result.output
    doc = json.loads(result.stdout)
    remark = expected_remark(spec)
    assert any(remark in r for r in doc["remarks"]), doc["remarks"]
    names = {c["name"] for c in doc["checks"]}
    assert {"positive_semidefinite_mass_matrix", "skew_symmetry", "symmetric_mass_matrix"} <= names
    assert all(c["passed"] for c in doc["checks"]), doc["checks"]
