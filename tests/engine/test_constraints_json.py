"""The JSON output's ``results.constraints`` (docs/json-output.md#constraints): read back with the
spec grammar's names, it gives the rolling disc's known answers (by hand) and the slider-crank's textbook
position analysis, and it is the same for every hash seed."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import sympy as sp

from tests.conftest import ROOT, SPECS, solved
from tutgen.spec.expr import parse_expression

DISC = str(SPECS / "examples" / "l-disc-rolling-down-incline.yaml")
SLIDER_CRANK = str(SPECS / "examples" / "o-slider-crank.yaml")


def _read(text: object, names: dict[str, sp.Symbol]) -> sp.Expr:
    """An expression of the JSON back as sympy, by the whitelist parser docs/json-output.md prescribes."""
    return parse_expression(text, names)


def _names(system: Any) -> dict[str, sp.Symbol]:
    out = {p.name: p.symbol for p in system.parameters}
    for c in system.coordinates:
        out |= {c.name: c.q, f"{c.name}_dot": c.qd, f"{c.name}_ddot": c.qdd}
    return out


def test_disc_constraints_json_by_hand() -> None:
    """x = R phi (one solution, sign 0); lambda = -m g sin(alpha)/3 (the friction, up the slope);
    phi_ddot = 2 g sin(alpha)/(3 R); H_r = 3/2 m R^2."""
    system, _d, doc = solved(DISC)
    got = dict(doc)["results"]["constraints"]
    n = _names(system)
    m, r, g, alpha = n["m"], n["R"], n["g"], n["alpha"]
    assert got["names"] == ["rolling"] and got["kinds"] == ["position"]
    assert got["independent_coordinates"] == ["phi"] and got["dependent_coordinates"] == ["x"]
    assert got["multipliers"] == ["lambda_1"]
    ((branch,),) = [got["position_analysis"]]
    assert branch["sign"] == 0 and sp.simplify(_read(branch["positions"]["x"], n) - r * n["phi"]) == 0
    assert sp.simplify(_read(got["multiplier_values"][0], n) + m * g * sp.sin(alpha) / 3) == 0
    reduced = got["reduced"]
    assert sp.simplify(_read(reduced["accelerations"][0], n) - 2 * g * sp.sin(alpha) / (3 * r)) == 0
    assert sp.simplify(_read(reduced["mass_matrix"][0][0], n) - sp.Rational(3, 2) * m * r**2) == 0
    # A = [1, -R] (x first): A^T lambda acts on x as lambda and on phi as -R lambda
    jac = [[_read(v, n) for v in row] for row in got["jacobian"]]
    assert sp.simplify(jac[0][0] - 1) == 0 and sp.simplify(jac[0][1] + r) == 0


def test_slider_crank_position_analysis_json() -> None:
    """Both branches: s = r cos(theta) +- sqrt(l^2 - r^2 sin^2(theta)), and beta satisfies the loop."""
    system, _d, doc = solved(SLIDER_CRANK)
    got = dict(doc)["results"]["constraints"]
    n = _names(system)
    r, rod, th = n["r"], n["l"], n["theta"]
    assert got["names"] == ["B_x", "B_y"]
    assert [b["sign"] for b in got["position_analysis"]] == [1, -1]
    for b in got["position_analysis"]:
        s_expr = _read(b["positions"]["s"], n)
        exact = r * sp.cos(th) + b["sign"] * sp.sqrt(rod**2 - r**2 * sp.sin(th) ** 2)
        assert sp.simplify(s_expr - exact) == 0
        beta = _read(b["positions"]["beta"], n).subs({r: 0.3, rod: 1.1, th: 2.0})
        pos = s_expr.subs({r: 0.3, rod: 1.1, th: 2.0})
        assert abs(float(0.3 * math.sin(2.0) + 1.1 * sp.sin(beta))) < 1e-12
        assert abs(float(0.3 * math.cos(2.0) + 1.1 * sp.cos(beta) - pos)) < 1e-12


@pytest.mark.slow  # two processes: about 6 s on a loaded machine
def test_constraints_json_is_the_same_under_any_hash_seed(tmp_path: Path) -> None:
    """Deterministic output: the constraints' results byte-identical for two PYTHONHASHSEEDs."""
    outs = []
    for seed in ("1", "2"):
        env = {**os.environ, "PYTHONHASHSEED": seed, "PYTHONPATH": str(ROOT)}
        run = subprocess.run(
            [sys.executable, "-m", "tutgen", "solve", DISC, "-f", "json", "-q"],
            capture_output=True,
            text=True,
            env=env,
            cwd=ROOT,
            check=True,
        )
        outs.append(json.dumps(json.loads(run.stdout)["results"]["constraints"], sort_keys=True))
    assert outs[0] == outs[1]
