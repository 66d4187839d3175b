"""`tutgen solve --method` and the spec's `methods:`: which formulations a worked solution presents.

Newton-Euler is derived for its agreement check whenever the spec has bodies (the JSON always has
its results); what the method changes is which steps exist, and so what is printed.
"""

from __future__ import annotations

import json
import re

import pytest
from typer.testing import CliRunner

from tests.conftest import SPECS
from tutgen.cli.main import app

SPEC = str(SPECS / "tutorial-1" / "p06-two-prismatic.yaml")  # no `methods:`: Lagrange alone
BOTH = str(SPECS / "tutorial-1" / "p03-cart-pendulum.yaml")  # methods: [lagrange, newton_euler]
LAGRANGE_HEADING = re.compile(r"^## \d+\. Lagrange's equations$", re.M)
NE_HEADING = re.compile(r"^## \d+\. Newton–Euler$", re.M)


@pytest.mark.parametrize(
    ("method", "kinds"),
    [
        pytest.param([], {"lagrange_equations"}, id="default-the-spec-s-lagrange"),
        pytest.param(["--method", "both"], {"lagrange_equations", "newton_euler"}, id="both"),
        pytest.param(["-m", "newton-euler"], {"newton_euler"}, id="newton-euler"),
        pytest.param(["--method", "lagrange"], {"lagrange_equations"}, id="lagrange"),
    ],
)
def test_solve_method_selects_the_steps(method: list[str], kinds: set[str]) -> None:
    result = CliRunner().invoke(app, ["solve", SPEC, "--format", "json", *method])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    steps = {s["kind"] for s in doc["steps"]}
    assert steps & {"lagrange_equations", "newton_euler"} == kinds
    eom = next(s for s in doc["steps"] if s["kind"] == "equations_of_motion")
    assert set(eom["depends_on"]) == kinds
    # derived for the check whatever is presented, and reported in one line among the checks
    assert doc["results"]["newton_euler"]["agrees_with_lagrange"] is True
    assert [c["name"] for c in doc["checks"]].count("newton_euler_equals_lagrange") == 1


def test_solve_default_prints_newton_euler_only_where_the_spec_asks() -> None:
    lagrange_only = CliRunner().invoke(app, ["solve", SPEC]).stdout
    assert LAGRANGE_HEADING.search(lagrange_only) and not NE_HEADING.search(lagrange_only)
    assert "agree" in lagrange_only  # the agreement check, one line
    both = CliRunner().invoke(app, ["solve", BOTH]).stdout
    assert LAGRANGE_HEADING.search(both) and NE_HEADING.search(both)


def test_solve_method_overrides_the_spec() -> None:
    ne_only = CliRunner().invoke(app, ["solve", BOTH, "-m", "newton-euler"]).stdout
    assert NE_HEADING.search(ne_only) and not LAGRANGE_HEADING.search(ne_only)
    lagrange = CliRunner().invoke(app, ["solve", BOTH, "-m", "lagrange"]).stdout
    assert LAGRANGE_HEADING.search(lagrange) and not NE_HEADING.search(lagrange)


def test_solve_unknown_method_is_a_usage_error() -> None:
    result = CliRunner().invoke(app, ["solve", SPEC, "--method", "hamilton"])
    assert result.exit_code == 2
