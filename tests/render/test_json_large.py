"""The JSON of large serial arms (issue 17): ``results.program`` with ``results.expanded`` false
instead of the entries written out, unless ``--expand``; the program, read back with the whitelist
parser and evaluated in floats, gives the same H, C q_dot and G as the expanded symbolic form (and
as an independent numeric recursive Newton-Euler pass) at random states."""

from __future__ import annotations

import json
import os
import random
import subprocess
import sys
from typing import Any

import numpy as np
import pytest
import sympy as sp

from tests.conftest import ROOT, SPECS, solved
from tutgen.api import render
from tutgen.engine.pipeline import derive
from tutgen.engine.serial import numeric_inverse_dynamics, serial_dynamics
from tutgen.engine.trigpoly import NumericEvaluator
from tutgen.render.jsonout import EXPANDED_KEYS, derivation_to_json, dumps, is_program_only
from tutgen.spec.expr import ExpressionParser
from tutgen.spec.validate import load_system, load_system_text

PUMA = str(SPECS / "arms" / "puma560.yaml")


def planar_chain(n: int) -> str:
    """An n-link planar chain, every quantity symbolic (as benchmarks/bench_arms.py builds it)."""
    params = ["g"]
    bodies, joints = [], []
    for i in range(1, n + 1):
        params += [f"m{i}", f"c{i}", f"I{i}"] + ([f"l{i}"] if i < n else [])
        bodies.append(f"  link{i}: {{mass: m{i}, com: [c{i}, 0, 0], inertia: {{zz: I{i}}}}}")
        parent = "ground" if i == 1 else f"link{i - 1}"
        origin = f", origin: [l{i - 1}, 0, 0]" if i > 1 else ""
        joints.append(
            f"  joint{i}: {{type: revolute, parent: {parent}, child: link{i}, axis: z, coordinate: q{i}{origin}}}"
        )
    coords = ", ".join(f"q{i}" for i in range(1, n + 1))
    head = [f"tutgen: 1\ntitle: Planar {n}-link chain\nparameters: [{', '.join(params)}]\ncoordinates: [{coords}]"]
    return "\n".join([*head, "gravity: [0, -g, 0]", "bodies:", *bodies, "joints:", *joints]) + "\n"


@pytest.fixture(scope="module")
def planar9() -> tuple[Any, Any, dict[str, Any]]:
    """planar-9: the smallest planar chain past the budget (H, C q_dot, G: 43 000 operations)."""
    system = load_system_text(planar_chain(9), "planar-9.yaml")
    d = derive(system)
    return system, d, derivation_to_json(d, expand=False)


@pytest.fixture(scope="module")
def puma() -> tuple[Any, Any, dict[str, Any]]:
    system = load_system(PUMA)
    d = derive(system)
    return system, d, derivation_to_json(d, expand=False)


def _names(system: Any) -> dict[str, sp.Symbol]:
    """The JSON's names of the parameters and the state, as the derivation's own symbols."""
    names = {p.name: p.symbol for p in system.parameters}
    for c in system.coordinates:
        names[c.name], names[f"{c.name}_dot"], names[f"{c.name}_ddot"] = c.q, c.qd, c.qdd
    return names


def _state(system: Any, rng: random.Random) -> dict[sp.Symbol, float]:
    """Random values: parameters in [0.5, 2], angles in [-3, 3], rates and accelerations in [-2, 2]."""
    values = {p.symbol: rng.uniform(0.5, 2.0) for p in system.parameters if p.value is None}
    for c in system.coordinates:
        values[c.q], values[c.qd], values[c.qdd] = rng.uniform(-3, 3), rng.uniform(-2, 2), rng.uniform(-2, 2)
    return values


def _run_program(program: dict[str, Any], names: dict[str, sp.Symbol], values: dict[sp.Symbol, float]) -> Any:
    """H, C q_dot and G of ``results.program`` in floats: each definition read with the whitelist parser
    (only the names defined before it are known: a use before its definition fails) and evaluated."""
    known: dict[str, sp.Symbol] = dict(names)
    floats: dict[sp.Basic, sp.Float] = {s: sp.Float(v) for s, v in values.items()}

    def number(text: Any) -> float:
        e = ExpressionParser(text, known).parse() if isinstance(text, str) else sp.Float(text)
        out = e.xreplace(floats)
        assert out.is_number, (text, out.free_symbols)
        return float(out)

    for item in program["definitions"]:
        x = sp.Symbol(item["name"])
        floats[x] = sp.Float(number(item["value"]))
        known[item["name"]] = x
    h = np.array([[number(v) for v in row] for row in program["mass_matrix"]])
    c = np.array([number(v) for v in program["coriolis_vector"]])
    g = np.array([number(v) for v in program["gravity_vector"]])
    return h, c, g


def _numbers(m: sp.MatrixBase, values: dict[sp.Symbol, float]) -> np.ndarray:
    floats = {s: sp.Float(v) for s, v in values.items()}
    return np.array([[float(m[i, j].xreplace(floats)) for j in range(m.shape[1])] for i in range(m.shape[0])])


def _close(a: np.ndarray, b: np.ndarray) -> bool:
    return bool(np.max(np.abs(a - b)) <= 1e-9 * max(1.0, float(np.max(np.abs(b)))))


def test_json_large_planar_chain_is_its_program(planar9):
    """planar-9 without --expand: the program and ``expanded: false``, none of the written-out keys; the
    program equals the expanded H, C q_dot and G of the derivation (sympy) at 3 random states."""
    system, d, doc = planar9
    results = doc["results"]
    assert is_program_only(d)
    assert results["expanded"] is False and "--expand" in results["expanded_note"]
    assert not set(EXPANDED_KEYS) & set(results)
    assert d.coriolis_vector is not None and d.gravity_vector is not None
    rng = random.Random(17)
    for _ in range(3):
        values = _state(system, rng)
        h, c, g = _run_program(results["program"], _names(system), values)
        assert _close(h, _numbers(d.mass_matrix, values))
        assert _close(c, _numbers(d.coriolis_vector, values)[:, 0])
        assert _close(g, _numbers(d.gravity_vector, values)[:, 0])
    long_sides = [e for s in doc["steps"] for e in s["equations"] if e["rhs"] is None]
    assert long_sides and all(e["rhs_latex"] is None for e in long_sides)


@pytest.mark.slow
def test_json_large_puma_program_equals_exact_polynomials_and_newton_euler(puma):
    """The fully symbolic PUMA 560 without --expand: its program equals, at 3 random states, H and G of
    the derivation (sympy, written out), C q_dot from the exact polynomials of the serial engine's
    Christoffel symbols, and H q_ddot + C q_dot + G equals a numeric recursive Newton-Euler pass."""
    system, d, doc = puma
    results = doc["results"]
    assert results["expanded"] is False and not set(EXPANDED_KEYS) & set(results)
    assert not d.coriolis_vector.is_converted  # the JSON did not write C q_dot out, so never built it
    dyn = serial_dynamics(system)
    ex = dyn.exact
    keys = list(ex.gammas)
    evaluate = NumericEvaluator(ex.algebra, [ex.gammas[k] for k in keys])
    n = len(system.coordinates)
    rng = random.Random(560)
    for _ in range(3):
        values = _state(system, rng)
        h, c, g = _run_program(results["program"], _names(system), values)
        assert _close(h, _numbers(d.mass_matrix, values))
        assert _close(g, _numbers(d.gravity_vector, values)[:, 0])
        qd = [values[co.qd] for co in system.coordinates]
        exact_c = np.zeros(n)
        for (i, j, k), gam in zip(keys, evaluate(values), strict=True):
            exact_c[i] += gam * qd[j] * qd[k] * (1 if j == k else 2)
        assert _close(c, exact_c)
        q = [values[co.q] for co in system.coordinates]
        qdd = np.array([values[co.qdd] for co in system.coordinates])
        params = {p.symbol: values[p.symbol] for p in system.parameters if p.symbol in values}
        tau = np.array(numeric_inverse_dynamics(system, params, q, qd, list(qdd)))
        assert _close(h @ qdd + c + g, tau)


def test_json_large_program_can_fail(planar9):
    """The comparison above notices a wrong program: one definition's value changed."""
    system, d, doc = planar9
    program = json.loads(json.dumps(doc["results"]["program"]))
    used = next(i for i, item in enumerate(program["definitions"]) if "m9" in item["value"])
    program["definitions"][used]["value"] = f"({program['definitions'][used]['value']})*(1 + 1/1000)"
    values = _state(system, random.Random(3))
    h, c, g = _run_program(program, _names(system), values)
    expected = [_numbers(d.mass_matrix, values), _numbers(d.coriolis_vector, values)[:, 0]]
    expected.append(_numbers(d.gravity_vector, values)[:, 0])
    assert not all(_close(a, b) for a, b in zip((h, c, g), expected, strict=True))


@pytest.mark.slow
def test_json_expand_writes_the_entries_and_keeps_the_program(planar9):
    """With expand, the same arm's JSON has every written-out key, ``expanded: true`` and the same program."""
    _, d, doc = planar9
    full = derivation_to_json(d, expand=True)
    results = full["results"]
    assert results["expanded"] is True and "expanded_note" not in results
    assert {"mass_matrix", "coriolis_vector", "gravity_vector", "equations_of_motion", "christoffel"} <= set(results)
    assert results["program"] == doc["results"]["program"]
    assert all(e["rhs"] is not None for s in full["steps"] for e in s["equations"])


@pytest.mark.parametrize("spec", ["tutorial-1/p05-rr-arm.yaml", "arms/scara.yaml"])
def test_json_small_systems_are_the_same_with_or_without_expand(spec):
    """Below the budget nothing changes: the tutorial RR arm (no program) and a 4-DOF SCARA (its
    program, ``expanded: true``, every entry)."""
    _, d, _ = solved(str(SPECS / spec))
    assert not is_program_only(d)
    assert dumps(derivation_to_json(d, expand=False)) == dumps(derivation_to_json(d, expand=True))


def test_json_large_render_default_and_cli_expand_option(planar9, tmp_path):
    """``tutgen.api.render(d, "json")`` (what ``tutgen solve -f json`` writes) of planar-9 gives the
    program only; ``tutgen solve --expand`` is accepted and, on a small spec, writes the same bytes."""
    _, d, _ = planar9
    results = json.loads(render(d, "json"))["results"]
    assert results["expanded"] is False and "mass_matrix" not in results and results["program"]["definitions"]
    p05 = SPECS / "tutorial-1" / "p05-rr-arm.yaml"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    cmd = [sys.executable, "-m", "tutgen", "solve", str(p05), "-f", "json", "--expand"]
    out = subprocess.run(cmd, capture_output=True, text=True, env=env, check=True, cwd=tmp_path).stdout
    assert out == render(solved(str(p05))[1], "json")


@pytest.mark.slow
def test_json_large_puma_program_equals_expanded_sympy_form(puma):
    """The PUMA's program against its C q_dot written out in sympy (converted here: seconds)."""
    system, d, doc = puma
    values = _state(system, random.Random(6))
    _, c, _ = _run_program(doc["results"]["program"], _names(system), values)
    assert _close(c, _numbers(d.coriolis_vector, values)[:, 0])


def test_json_large_fits_the_solution_schema(planar9):
    """The program-only document is a valid solution JSON (schemas/solution.schema.json)."""
    from tests.test_schemas import errors

    _, _, doc = planar9
    assert errors("solution", json.loads(json.dumps(doc))) == []
    broken = json.loads(json.dumps(doc))
    broken["results"]["expanded"] = "no"
    assert errors("solution", broken) != []


@pytest.mark.slow
def test_json_large_is_the_same_under_any_hash_seed(tmp_path):
    """Two fresh processes with PYTHONHASHSEED 0 and 1 write the same bytes for planar-9's program-only
    JSON (the definitions' order and text do not depend on hashing)."""
    spec = tmp_path / "planar-9.yaml"
    spec.write_text(planar_chain(9))
    outs = []
    for seed in ("0", "1"):
        env = {**os.environ, "PYTHONPATH": str(ROOT), "PYTHONHASHSEED": seed}
        cmd = [sys.executable, "-m", "tutgen", "solve", str(spec), "-f", "json"]
        outs.append(subprocess.run(cmd, capture_output=True, env=env, check=True, cwd=tmp_path).stdout)
    assert outs[0] == outs[1] and b'"expanded": false' in outs[0]
