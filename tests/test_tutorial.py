"""The ten problems of the course tutorial, checked against its answer key.

The answers are read from ``shared/seed/answers.yaml`` (never copied here). Each is compared with
tutgen's JSON output (the public contract), parsed back through the spec grammar. Where the
tutorial has a typo, tutgen must give the corrected value and must NOT give the printed one.
"""

from __future__ import annotations

import math
from typing import Any

import pytest
import sympy as sp

from tests.conftest import SPECS, solved
from tests.seed import ANSWERS, BODY_OF, SPEC_OF, problems
from tutgen.engine.tidy import is_zero
from tutgen.spec.expr import parse_expression

pytestmark = pytest.mark.skipif(not ANSWERS.exists(), reason=f"the seed answer key is not at {ANSWERS}")


def result(pid: int) -> tuple[Any, dict[str, Any]]:
    system, _, doc = solved(str(SPECS / "tutorial-1" / SPEC_OF[pid]))
    return system, doc


def names(system: Any, extra: tuple[str, ...] = ()) -> dict[str, sp.Expr]:
    table: dict[str, sp.Expr] = {p.name: p.symbol for p in system.parameters}
    for c in system.coordinates:
        table[c.name], table[f"{c.name}_dot"], table[f"{c.name}_ddot"] = c.q, c.qd, c.qdd
    for e in extra:
        table[e] = sp.Symbol(e)
    return table


def same(system: Any, expected: Any, derived: Any, extra: tuple[str, ...] = ()) -> bool:
    table = names(system, extra)
    return is_zero(parse_expression(expected, table) - parse_expression(derived, table))[0]


def close(derived: float, expected: float, spec: dict[str, Any]) -> bool:
    tol = max(float(spec.get("abs_tol", 0.0)), float(spec.get("rel_tol", 0.0)) * abs(derived))
    return abs(derived - expected) <= tol


def flat(x: Any) -> list[float]:
    if isinstance(x, list):
        return [v for item in x for v in flat(item)]
    return [float(x)]


# ---------------------------------------------------------------------------------------------
# Problems 1 and 2: numbers
# ---------------------------------------------------------------------------------------------


def numeric_answer(pid: int, key: str) -> Any:
    _, doc = result(pid)
    r = doc["results"]
    if pid == 1:
        parts = r["bodies"]["body"]["parts"]
        prefix, _, rest = key.partition("_")
        if prefix in ("block", "cylinder", "point") and rest:
            part = parts[prefix]
            if rest in ("volume", "mass"):
                return part[rest]
            if rest == "axis_distances":
                return part["axis_distances"]
            axis = "xyz".index(rest[1])
            # the block sits at the origin: its centroidal inertia is about the coordinate axes
            return part["inertia_tensor"][axis][axis]
        if key in ("Ixx", "Iyy", "Izz"):
            axis = "xyz".index(key[1])
            return r["inertia_tensor"][axis][axis]
        if key == "inertia_tensor":
            return r["inertia_tensor"]
        if key == "product_of_inertia_xy":
            return -r["inertia_tensor"][0][1]  # P_xy = integral x y dm = -J_xy
        if key == "principal_moments":
            return r["principal_moments"]
        if key == "principal_axis_angle_deg":
            ax = r["bodies"]["body"]["principal_axes"][0]  # least moment first
            return math.degrees(math.atan2(ax[1], ax[0]))
        if key == "cylinder_axis_distances":
            return parts["cylinder"]["axis_distances"]
    if pid == 2:
        body = r["bodies"]["rod"]
        if key == "pivot_to_centroid":
            return math.hypot(*body["center_of_mass"])
        if key == "centroidal_inertia":
            return body["inertia_tensor_com"][2][2]
        if key == "pivot_inertia":
            return body["inertia_tensor"][2][2]
        if key == "T_coefficient":
            system, _ = result(2)
            t = parse_expression(r["kinetic_energy"], names(system))
            return float(
                sp.Poly(t, sp.Symbol("theta_dot", real=True)).coeff_monomial(sp.Symbol("theta_dot", real=True) ** 2)
            )
    raise KeyError(key)


def numeric_cases() -> list[Any]:
    out = []
    for pid in (1, 2):
        for key, spec in problems().get(pid, {"answers": {}})["answers"].items():
            if isinstance(spec, dict) and "value" in spec:
                out.append(pytest.param(pid, key, spec, id=f"p{pid}-{key}"))
    return out


@pytest.mark.parametrize(("pid", "key", "spec"), numeric_cases())
def test_tutorial_numeric_answer(pid: int, key: str, spec: dict[str, Any]) -> None:
    derived = flat(numeric_answer(pid, key))
    for field in ("value", "printed"):
        if field not in spec:
            continue
        expected = flat(spec[field])
        assert len(expected) == len(derived)
        for d, e in zip(derived, expected, strict=True):
            assert close(d, e, spec), f"{key}: derived {d}, answer key's {field} {e}"


def test_tutorial_problem2_kinetic_energy_exact() -> None:
    system, doc = result(2)
    assert same(system, problems()[2]["answers"]["T"], doc["results"]["kinetic_energy"])


@pytest.mark.parametrize("pid", [1, 2])
def test_tutorial_numeric_typos_are_corrected(pid: int) -> None:
    for typo in problems()[pid].get("typos", []):
        derived = flat(numeric_answer(pid, typo["answer_key"]))[0]
        correct, printed = float(typo["correct"]), float(typo["printed"])
        assert abs(derived - correct) <= 1e-3 * abs(derived), typo["where"]
        assert abs(derived - printed) > abs(derived - correct), typo["where"]


def test_tutorial_problem1_product_of_inertia_reported() -> None:
    """The tutorial ignores J_xy; tutgen reports it, and the axes are not principal."""
    _, doc = result(1)
    assert doc["results"]["inertia_tensor"][0][1] == pytest.approx(-4.007e-3, rel=2e-3)


# ---------------------------------------------------------------------------------------------
# Problems 3-10: expressions
# ---------------------------------------------------------------------------------------------


def derived_value(pid: int, key: str, sub: Any = None) -> Any:
    """Our JSON value for an answer-key entry."""
    system, doc = result(pid)
    r = doc["results"]
    coords = [c.name for c in system.coordinates]
    if key == "T":
        return r["kinetic_energy"]
    if key == "U":
        return r["potential_energy"]
    if key == "H":
        return r["mass_matrix"]
    if key == "C":
        return r["coriolis_vector"]
    if key == "C_matrix":
        return r["coriolis_matrix"]
    if key == "G":
        return r["gravity_vector"]
    if key == "H_determinant":
        return r["mass_matrix_determinant"]
    if key in ("christoffel", "christoffel_first_kind"):
        i, j, k = sub[1:]
        return r[key][f"{i},{j},{k}"]
    if key == "intermediate":
        for term in r["lagrange_terms"]:
            name = term["coordinate"]
            table = {f"dL_d{name}_dot": "dL_dqdot", f"ddt_dL_d{name}_dot": "ddt_dL_dqdot", f"dL_d{name}": "dL_dq"}
            if sub in table:
                return term[table[sub]]
        raise KeyError(sub)
    if key in ("position", "velocity"):
        body = BODY_OF[pid][sub]
        return r["positions" if key == "position" else "velocities"][body]
    if key == "velocity_squared":
        return r["speeds_squared"][BODY_OF[pid][sub]]
    if key == "equations_of_motion":
        return r["equations_of_motion"][coords.index(sub)]
    raise KeyError(key)


def expression_cases() -> list[Any]:
    out = []
    for pid in range(3, 11):
        for key, spec in problems().get(pid, {"answers": {}})["answers"].items():
            if key == "equations_of_motion":
                for eq in spec:
                    out.append(pytest.param(pid, key, eq["coordinate"], eq, id=f"p{pid}-eom-{eq['coordinate']}"))
            elif key in ("christoffel", "christoffel_first_kind", "intermediate", "velocity_squared"):
                for sub, value in spec.items():
                    out.append(pytest.param(pid, key, sub, value, id=f"p{pid}-{key}-{sub}"))
            elif key in ("position", "velocity"):
                for sub, comps in spec.items():
                    out.append(pytest.param(pid, key, sub, comps, id=f"p{pid}-{key}-{sub}"))
            else:
                out.append(pytest.param(pid, key, None, spec, id=f"p{pid}-{key}"))
    return out


@pytest.mark.parametrize(("pid", "key", "sub", "expected"), expression_cases())
def test_tutorial_expression_answer(pid: int, key: str, sub: Any, expected: Any) -> None:
    system, _ = result(pid)
    derived = derived_value(pid, key, sub)
    if key == "equations_of_motion":
        # the key says lhs == force; ours is the expression that equals zero, lhs - force
        assert same(system, f"({expected['lhs']}) - ({expected['force']})", derived)
        return
    if isinstance(expected, list):
        flat_expected = [e for row in expected for e in (row if isinstance(row, list) else [row])]
        flat_derived = [e for row in derived for e in (row if isinstance(row, list) else [row])]
        if key in ("position", "velocity"):  # planar problems: the key gives x and y only
            flat_derived = flat_derived[: len(flat_expected)]
        assert len(flat_expected) == len(flat_derived)
        for i, (e, d) in enumerate(zip(flat_expected, flat_derived, strict=True)):
            assert same(system, e, d), f"{key}[{i}]: expected {e}, derived {d}"
        return
    assert same(system, expected, derived), f"{key} {sub}: expected {expected}, derived {derived}"


def typo_cases() -> list[Any]:
    return [
        pytest.param(pid, typo, id=f"p{pid}-{typo['answer_key']}")
        for pid in range(3, 11)
        for typo in problems().get(pid, {}).get("typos", [])
    ]


@pytest.mark.parametrize(("pid", "typo"), typo_cases())
def test_tutorial_typo_is_corrected(pid: int, typo: dict[str, Any]) -> None:
    system, _ = result(pid)
    key, _, rest = typo["answer_key"].partition(".")
    extra = tuple(typo.get("extra_symbols", []))
    if key == "intermediate":
        derived = derived_value(pid, key, rest)
    elif key in ("velocity",):
        body, _, index = rest.partition(".")
        derived = derived_value(pid, key, body)[int(index)]
    elif key in ("C", "G"):
        derived = derived_value(pid, key)[int(rest)]
    else:
        raise AssertionError(f"unhandled typo key {typo['answer_key']}")
    assert same(system, typo["correct"], derived, extra), typo["where"]
    assert not same(system, typo["printed"], derived, extra), f"tutgen repeats the typo: {typo['where']}"


def test_tutorial_problem9_singular_mass_matrix_is_remarked() -> None:
    _, doc = result(9)
    assert doc["results"]["mass_matrix_determinant"] == 0
    assert any("singular" in r for r in doc["remarks"])
    assert any("theta" in r and "no inertia" in r for r in doc["remarks"])


def test_tutorial_every_problem_has_a_spec() -> None:
    assert sorted(problems()) == sorted(SPEC_OF)
    for name in SPEC_OF.values():
        assert (SPECS / "tutorial-1" / name).exists()
