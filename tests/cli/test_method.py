"""`tutgen solve --method`: which derivations the output carries."""

from __future__ import annotations

import json
import re

import pytest
from typer.testing import CliRunner

from tests.conftest import SPECS
from tutgen.cli.main import app

SPEC = str(SPECS / "tutorial-1" / "p06-two-prismatic.yaml")


@pytest.mark.parametrize(
    ("method", "has_ne"),
    [
        pytest.param([], True, id="default-both"),
        pytest.param(["--method", "both"], True, id="both"),
        pytest.param(["-m", "newton-euler"], True, id="newton-euler"),
        pytest.param(["--method", "lagrange"], False, id="lagrange"),
    ],
)
def test_solve_method_selects_newton_euler(method: list[str], has_ne: bool) -> None:
    result = CliRunner().invoke(app, ["solve", SPEC, "--format", "json", *method])
    assert result.exit_code == 0, result.output
    results = json.loads(result.stdout)["results"]
    assert ("newton_euler" in results) is has_ne
    if has_ne:
        assert results["newton_euler"]["agrees_with_lagrange"] is True
    assert "equations_of_motion" in results  # Lagrange is always derived (the reference)


def test_solve_newton_euler_markdown_omits_lagrange_terms() -> None:
    both = CliRunner().invoke(app, ["solve", SPEC]).stdout
    ne_only = CliRunner().invoke(app, ["solve", SPEC, "-m", "newton-euler"]).stdout
    heading = re.compile(r"^## \d+\. Lagrange's equations$", re.M)
    assert heading.search(both) and not heading.search(ne_only)
    assert "Newton–Euler" in ne_only


def test_solve_unknown_method_is_a_usage_error() -> None:
    result = CliRunner().invoke(app, ["solve", SPEC, "--method", "hamilton"])
    assert result.exit_code == 2
