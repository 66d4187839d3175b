"""Comparison rules: equivalence of expressions, equations of motion, tables, numbers, and feedback."""

from __future__ import annotations

import json
from typing import Any

import pytest
import sympy as sp
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st
from sympy.simplify.fu import TR8

from tests.check.helpers import mark_text, not_correct, tutorial, verdicts
from tutgen.check.compare import NUMERIC_HOW, Reference, Status, diagnose, entry_name, equal_how, expr_text
from tutgen.spec.expr import parse_expression

a, b, m, x, t = sp.symbols("a b m x t", positive=True)
EXPANDS = "exact: the difference expands to 0"
TRIG = "exact: equal by trigonometric identities"
SIGN = "wrong sign: yours is the negative of the correct expression"
#: infinite at the first random state (x = 1.914): that state is skipped
POLE = sp.Symbol("y") / (x - sp.Rational(1914, 1000))


def factor(k: str) -> str:
    return f"off by a factor {k} (yours is {k} times the correct expression)"


def yaml_text(key: str, value: str) -> str:
    return f"{json.dumps(key)}: {json.dumps(value)}\n"


def verdict(ref: Reference, key: str, value: str) -> tuple[Status, str]:
    found = verdicts(mark_text(ref, yaml_text(key, value)))
    assert len(found) == 1, found
    return next(iter(found.values()))


# ---------------------------------------------------------------------------------------------
# Deciding equality, and saying what differs
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("difference", "how"),
    [
        pytest.param((a + b) ** 2 - a**2 - 2 * a * b - b**2, EXPANDS, id="expanded"),
        pytest.param(a * sp.sin(t) ** 2 + a * sp.cos(t) ** 2 - a, TRIG, id="trig"),
        pytest.param(sp.cos(t + x) - sp.cos(t) * sp.cos(x) + sp.sin(t) * sp.sin(x), TRIG, id="angle-sum"),
        pytest.param(sp.tan(t) - sp.sin(t) / sp.cos(t), NUMERIC_HOW, id="numeric"),
        pytest.param(POLE * (sp.tan(x) - sp.sin(x) / sp.cos(x)), NUMERIC_HOW, id="numeric-past-a-pole"),
    ],
)
def test_compare_equal_how(difference: sp.Expr, how: str) -> None:
    assert equal_how(difference) == how


def test_compare_equal_how_rejects() -> None:
    assert equal_how(a - b) is None
    assert equal_how(sp.sin(t) - sp.cos(t)) is None


@pytest.mark.parametrize(
    ("given", "correct", "message"),
    [
        pytest.param(-(a + b), a + b, SIGN, id="sign"),
        pytest.param(2 * a * x + 2 * b, a * x + b, factor("2"), id="factor"),
        pytest.param(m * (a * x + b), a * x + b, factor("m"), id="factor-m"),
        pytest.param(a * x, a * x + b * sp.sin(x), "missing term b*sin(x)", id="missing-term"),
        pytest.param(a * x + b + m, a * x + b, "extra term m", id="extra-term"),
        pytest.param(a * x - b * t, a * x + b * t, "wrong sign of the term b*t", id="sign-of-term"),
        pytest.param(a * x + 3 * b * t, a * x + b * t, "the term b*t: off by a factor 3", id="factor-of-term"),
        pytest.param(a, sp.S.Zero, "the correct value is 0", id="should-be-zero"),
        pytest.param(sp.S.Zero, a, "the correct value is not 0", id="should-not-be-zero"),
    ],
)
def test_compare_diagnose(given: sp.Expr, correct: sp.Expr, message: str) -> None:
    assert diagnose(given, correct) == message


def test_compare_diagnose_groups_by_state() -> None:
    """With coordinates and rates known, a coefficient in the parameters is compared as a whole."""
    q, qd = sp.symbols("q q_dot", real=True)
    state = frozenset({q, qd})
    given = -(a**2) * m * qd**2 * sp.sin(q) + b
    correct = -a * b * m * qd**2 * sp.sin(q) + b
    assert diagnose(given, correct, state) == ("coefficient of q_dot**2*sin(q): yours is -a**2*m, expected -a*b*m")


def test_compare_entry_names() -> None:
    assert entry_name(("mass_matrix", 0, 1)) == "mass_matrix[1,2]"
    assert entry_name(("christoffel", "1,1,2")) == "christoffel[1,1,2]"
    assert entry_name(("lagrange_terms", 1, "dL_dq")) == "lagrange_terms[2].dL_dq"
    assert entry_name(("bodies", "body", "inertia_tensor", 2, 2)) == "bodies.body.inertia_tensor[3,3]"


# ---------------------------------------------------------------------------------------------
# Rules on the tutorial's problems
# ---------------------------------------------------------------------------------------------


def test_compare_matrix_names_each_wrong_entry() -> None:
    result = mark_text(
        tutorial(5),
        """\
        mass_matrix:
          - ["(m1 + m2)*a1**2 + m2*a2**2 + 2*m2*a1*a2*cos(theta2)", "-m2*a2**2 - m2*a1*a2*cos(theta2)"]
          - ["m2*a2**2 + m2*a1*a2*cos(theta2)", "2*m2*a2**2"]
        """,
    )
    assert verdicts(result) == {
        "mass_matrix[1,1]": (Status.CORRECT, ""),
        "mass_matrix[1,2]": (Status.WRONG, SIGN),
        "mass_matrix[2,1]": (Status.CORRECT, ""),
        "mass_matrix[2,2]": (Status.WRONG, factor("2")),
    }
    assert [i.status for i in result.items] == [Status.WRONG]


def test_compare_missing_and_extra_entries() -> None:
    result = mark_text(
        tutorial(5),
        """\
        gravity_vector: ["(m1 + m2)*g*a1*cos(theta1) + m2*g*a2*cos(theta1 + theta2)"]
        coriolis_vector: [~, "m2*a1*a2*theta1_dot**2*sin(theta2)", "0"]
        potential_energy: ""
        """,
    )
    found = verdicts(result)
    assert found["gravity_vector[2]"] == (Status.MISSING, "no answer")
    assert found["coriolis_vector[1]"] == (Status.MISSING, "no answer")
    assert found["coriolis_vector[3]"] == (Status.WRONG, "extra entry: coriolis_vector has only 2 entries")
    assert found["potential_energy"] == (Status.MISSING, "no answer")
    assert [i.status for i in result.items] == [Status.MISSING, Status.WRONG, Status.MISSING]
    assert result.status == "fail"


def test_compare_lists_by_coordinate_name_and_number() -> None:
    result = mark_text(
        tutorial(4),
        """\
        gravity_vector: {r: "m*g*sin(theta)", 1: "m*g*r*cos(theta)"}
        lagrange_terms.r.dL_dq: "m*r*theta_dot**2 - m*g*sin(theta)"
        lagrange_terms.2.dL_dqdot: "m*r_dot"
        """,
    )
    assert not_correct(result) == set()
    assert set(verdicts(result)) == {
        "gravity_vector[1]",
        "gravity_vector[2]",
        "lagrange_terms[2].dL_dq",
        "lagrange_terms[2].dL_dqdot",
    }


def test_compare_christoffel_other_convention_is_accepted_with_a_remark() -> None:
    """p05's symmetric symbols of the first kind, given as the tutorial's h_ijk: accepted, remarked."""
    result = mark_text(
        tutorial(5),
        """\
        christoffel:
          c111: 0
          c112: -m2*a1*a2*sin(theta2)
          c121: -m2*a1*a2*sin(theta2)
          c122: -m2*a1*a2*sin(theta2)
          c211: m2*a1*a2*sin(theta2)
          c212: 0
          c221: 0
          c222: 0
        """,
    )
    assert not_correct(result) == set()
    (item,) = result.items
    assert item.remarks == (
        "these are the symmetric Christoffel symbols of the first kind c_ijk (the result "
        "'christoffel_first_kind'), not the tutorial's three-index symbols h_ijk; accepted, since both give "
        "the same Coriolis vector",
    )


def test_compare_christoffel_mixed_conventions_are_wrong() -> None:
    result = mark_text(
        tutorial(5),
        """\
        christoffel_first_kind: {"1,1,2": -2*m2*a1*a2*sin(theta2), "1,2,1": -m2*a1*a2*sin(theta2)}
        """,
    )
    assert not_correct(result) == {"christoffel_first_kind[1,1,2]"}


@pytest.mark.parametrize(
    ("answer", "remark"),
    [
        pytest.param("m*r**2*theta_ddot + 2*m*r*r_dot*theta_dot + m*g*r*cos(theta) = n", "", id="as-printed"),
        pytest.param("m*r**2*theta_ddot + 2*m*r*r_dot*theta_dot + m*g*r*cos(theta) - n", "", id="equal-to-zero"),
        pytest.param(
            "n = m*r**2*theta_ddot + 2*m*r*r_dot*theta_dot + m*g*r*cos(theta)",
            "equations_of_motion[1]: the terms are on the other side of '='",
            id="sides-swapped",
        ),
        pytest.param("m*r**2*theta_ddot + m*g*r*cos(theta) = n - 2*m*r*r_dot*theta_dot", "", id="terms-moved"),
        pytest.param(
            "r**2*theta_ddot + 2*r*r_dot*theta_dot + g*r*cos(theta) == n/m",
            "equations_of_motion[1]: scaled by the constant factor 1/m",
            id="divided-by-m",
        ),
        pytest.param(
            "2*m*r**2*theta_ddot + 4*m*r*r_dot*theta_dot = 2*n - 2*m*g*r*cos(theta)",
            "equations_of_motion[1]: scaled by the constant factor 2",
            id="doubled",
        ),
    ],
)
def test_compare_equation_of_motion_equivalents(answer: str, remark: str) -> None:
    result = mark_text(tutorial(4), yaml_text("equations_of_motion[1]", answer))
    (item,) = result.items
    assert item.status is Status.CORRECT, item
    assert item.remarks == ((remark,) if remark else ())


@pytest.mark.parametrize(
    ("answer", "feedback"),
    [
        pytest.param(
            "m*r**2*theta_ddot + 2*m*r*r_dot*theta_dot = n", "missing term g*m*r*cos(theta)", id="dropped-term"
        ),
        pytest.param(
            "2*m*r**2*theta_ddot + 4*m*r*r_dot*theta_dot = 2*n",
            "missing term g*m*r*cos(theta)",
            id="doubled-and-dropped",
        ),
        pytest.param(
            "theta_dot*(m*r**2*theta_ddot + 2*m*r*r_dot*theta_dot + m*g*r*cos(theta) - n)",
            "",
            id="state-factor",
        ),
    ],
)
def test_compare_equation_of_motion_wrong(answer: str, feedback: str) -> None:
    status, text = verdict(tutorial(4), "equations_of_motion[1]", answer)
    assert status is Status.WRONG
    if feedback:
        assert text == feedback


def test_compare_unknown_name_is_a_wrong_answer() -> None:
    status, text = verdict(tutorial(4), "kinetic_energy", "M*r_dot**2/2")
    assert (status, text) == (Status.WRONG, "unknown name 'M' (did you mean 'm'?)")


def test_compare_expression_with_a_tolerance_is_compared_at_random_states() -> None:
    ref = tutorial(2)
    result = mark_text(ref, 'kinetic_energy: "2.92*theta_dot**2"\n', key="items: {kinetic_energy: {rel_tol: 0.005}}\n")
    (entry,) = result.items[0].entries
    assert entry.status is Status.CORRECT
    assert entry.how.startswith("numeric: within rel_tol 0.005")
    status, _ = verdict(ref, "kinetic_energy", "2.92*theta_dot**2")
    assert status is Status.WRONG


# ---------------------------------------------------------------------------------------------
# Numbers, units and tolerances (problem 1: numbers only)
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("answer", "status", "feedback"),
    [
        pytest.param("9.599613228784947e-3", Status.CORRECT, "", id="exact"),
        pytest.param("9.5996e-3", Status.CORRECT, "", id="decimal-rounded-as-written"),
        pytest.param(
            "9.5995e-3",
            Status.WRONG,
            "relative error 0.00% (allowed: rel_tol 1e-09); to 4 significant figures it is 0.009600",
            id="decimal-not-the-rounding",
        ),
        pytest.param("{value: 9.5996e-3, rel_tol: 1e-4}", Status.CORRECT, "", id="rel-tol"),
        pytest.param("{value: 9.59e-3, abs_tol: 1e-5}", Status.CORRECT, "", id="abs-tol"),
        pytest.param("{value: 9.59e-3 kg m^2, rel_tol: 0.01}", Status.CORRECT, "", id="units"),
        pytest.param("{value: 95.996 kg cm^2, rel_tol: 1e-4}", Status.CORRECT, "", id="units-converted"),
        pytest.param(
            "{value: 9.6e-3 kg m, rel_tol: 0.01}",
            Status.WRONG,
            "wrong units: yours are kg*m, expected kg*m^2",
            id="dimension",
        ),
        pytest.param(
            "{value: 9.6e-2, rel_tol: 0.01}",
            Status.WRONG,
            "off by a factor 10^1 (check the units and powers of ten)",
            id="power-of-ten",
        ),
        pytest.param("{value: -9.6e-3, rel_tol: 0.01}", Status.WRONG, "wrong sign", id="sign"),
        pytest.param("{value: 1.92e-2, rel_tol: 0.01}", Status.WRONG, "off by a factor 2", id="factor"),
        pytest.param("{value: 9.60e-3, rounded: true}", Status.CORRECT, "", id="rounded"),
        pytest.param("{value: 9.6e-3, rounded: true}", Status.CORRECT, "", id="rounded-2-figures"),
        pytest.param(
            "{value: 9.59e-3, rounded: true}",
            Status.WRONG,
            "not correctly rounded: to 3 significant figures it is 9.60e-3",
            id="truncated",
        ),
        pytest.param(
            "{value: 0.00959, rounded: true}",
            Status.WRONG,
            "not correctly rounded: to 3 significant figures it is 0.00960",
            id="truncated-decimal",
        ),
    ],
)
def test_compare_numbers(answer: str, status: Status, feedback: str) -> None:
    """A tolerance written next to the value here is the instructor's: it goes into the marking key."""
    key = None
    if answer.startswith("{"):
        data = yaml.safe_load(answer)
        del data["value"]
        data = {k: v if k == "rounded" else float(v) for k, v in data.items()}  # YAML 1.1 reads 1e-4 as text
        answer = answer.split(",")[0].removeprefix("{value:").strip()  # the number as written
        key = "items: " + json.dumps({"inertia_tensor[1,1]": data}) + "\n"
    result = mark_text(tutorial(1), f"inertia_tensor[1,1]: {answer}\n", key=key)
    assert verdicts(result) == {"inertia_tensor[1,1]": (status, feedback)}


def test_compare_numbers_file_tolerance_and_parameter_values() -> None:
    """The key's tolerance applies to the numbers; a parameter with a value (rho) may be used."""
    result = mark_text(
        tutorial(1),
        key="tolerance: {rel_tol: 1e-3}\n",
        text="""\
        bodies.body.parts.block.mass: rho*0.05*0.15*0.05
        bodies.body.parts.cylinder.mass: 1.233 kg
        bodies.body.parts.cylinder.volume: pi*0.025^2*0.08
        mass: 5.17 kg
        """,
    )
    found = verdicts(result)
    assert {k: s for k, (s, _) in found.items()} == {
        "bodies.body.parts.block.mass": Status.CORRECT,
        "bodies.body.parts.cylinder.mass": Status.CORRECT,
        "bodies.body.parts.cylinder.volume": Status.CORRECT,
        "mass": Status.WRONG,
    }
    assert found["mass"][1] == "relative error 0.12% (allowed: rel_tol 0.001); to 4 significant figures it is 5.176"


def test_compare_principal_axes_either_way() -> None:
    ref = tutorial(1)
    axes = ref.results["bodies"]["body"]["principal_axes"]
    flipped = [[-v for v in axes[0]], axes[1], axes[2]]
    result = mark_text(
        ref,
        "bodies.body.principal_axes: " + json.dumps(flipped) + "\n",
        key="items: {bodies.body.principal_axes: {rel_tol: 1.0e-6}}\n",
    )
    assert not_correct(result) == set()
    assert result.items[0].remarks == (
        "bodies.body.principal_axes[1] points the other way; accepted, an axis has no direction",
    )


def test_compare_text_fields() -> None:
    result = mark_text(tutorial(1), "bodies.body.parts.block.shape: box\nbodies.body.parts.cylinder.shape: rod\n")
    assert verdicts(result) == {
        "bodies.body.parts.block.shape": (Status.CORRECT, ""),
        "bodies.body.parts.cylinder.shape": (Status.WRONG, "expected 'cylinder'"),
    }


# ---------------------------------------------------------------------------------------------
# Properties: equivalent rewritings pass, perturbations fail at the right entry
# ---------------------------------------------------------------------------------------------

PROPERTY_PROBLEMS = (3, 5, 7, 8)
_SCALAR_RESULTS = ("kinetic_energy", "potential_energy", "lagrangian", "mass_matrix_determinant")
_TABLE_RESULTS = ("mass_matrix", "coriolis_vector", "gravity_vector", "coriolis_matrix", "velocities", "speeds_squared")


def _leaves(value: Any, path: tuple) -> list[tuple[tuple, Any]]:
    if isinstance(value, dict):
        return [leaf for k, v in value.items() for leaf in _leaves(v, (*path, k))]
    if isinstance(value, list):
        return [leaf for i, v in enumerate(value) for leaf in _leaves(v, (*path, i))]
    return [(path, value)]


def expression_entries(ref: Reference) -> list[tuple[str, sp.Expr]]:
    """(answer key, expression) of every symbolic result entry (not the Christoffel tables, whose
    other convention is accepted on purpose)."""
    out = []
    for key in (*_SCALAR_RESULTS, *_TABLE_RESULTS, "lagrange_terms"):
        if key not in ref.results:
            continue
        for path, value in _leaves(ref.results[key], (key,)):
            if isinstance(value, str) and path[-1] not in ("coordinate", "generalized_force"):
                out.append((entry_name(path), parse_expression(value, ref.symbols)))
    return out


def _state_symbol(ref: Reference, expr: sp.Expr) -> sp.Symbol:
    coords = [ref.symbols[c] for c in ref.coordinates]
    return next((q for q in coords if expr.has(q)), coords[0])


REWRITINGS = {
    "expanded": lambda ref, e: sp.expand(e),
    "factored": lambda ref, e: sp.factor(e),
    "angle-sums-expanded": lambda ref, e: sp.expand_trig(e),
    "products-to-sums": lambda ref, e: TR8(sp.expand(e)),
    "pythagoras": lambda ref, e: e * (sp.sin(_state_symbol(ref, e)) ** 2 + sp.cos(_state_symbol(ref, e)) ** 2),
}


@settings(max_examples=12)
@given(
    pid=st.sampled_from(PROPERTY_PROBLEMS),
    index=st.integers(min_value=0, max_value=10_000),
    rewriting=st.sampled_from(sorted(REWRITINGS)),
)
def test_compare_property_equivalent_rewritings_pass(pid: int, index: int, rewriting: str) -> None:
    ref = tutorial(pid)
    entries = expression_entries(ref)
    key, expr = entries[index % len(entries)]
    answer = expr_text(REWRITINGS[rewriting](ref, expr))
    assert verdict(ref, key, answer)[0] is Status.CORRECT, (key, answer)


def _drop_a_term(expr: sp.Expr, index: int) -> sp.Expr | None:
    terms = sp.Add.make_args(sp.expand(expr))
    if len(terms) < 2:
        return None
    return sp.Add(*(t for i, t in enumerate(terms) if i != index % len(terms)))


@settings(max_examples=12)
@given(
    pid=st.sampled_from(PROPERTY_PROBLEMS),
    index=st.integers(min_value=0, max_value=10_000),
    perturbation=st.sampled_from(["sign", "factor-2", "dropped-term"]),
)
def test_compare_property_perturbations_fail_at_the_entry(pid: int, index: int, perturbation: str) -> None:
    ref = tutorial(pid)
    entries = [(k, e) for k, e in expression_entries(ref) if e != 0]
    key, expr = entries[index % len(entries)]
    if perturbation == "sign":
        wrong, words = -expr, ("sign",)
    elif perturbation == "factor-2":
        wrong, words = 2 * expr, ("factor 2",)
    else:
        dropped = _drop_a_term(expr, index)
        if dropped is None:
            wrong, words = expr + ref.symbols[ref.coordinates[0]], ("extra term", "coefficient of")
        else:
            wrong, words = dropped, ("missing term", "coefficient of", "the terms")
    status, feedback = verdict(ref, key, expr_text(wrong))
    assert status is Status.WRONG, (key, expr_text(wrong))
    assert any(w in feedback for w in words), (key, feedback)


@settings(max_examples=10)
@given(
    pid=st.sampled_from(PROPERTY_PROBLEMS),
    which=st.integers(min_value=0, max_value=1),
    moved=st.sets(st.integers(min_value=0, max_value=20), max_size=4),
    factor=st.sampled_from(["1", "-1", "2", "1/3", "parameter"]),
)
def test_compare_property_equations_rearranged_or_scaled_pass(pid: int, which: int, moved: set, factor: str) -> None:
    ref = tutorial(pid)
    eom = parse_expression(ref.results["equations_of_motion"][which], ref.symbols)
    terms = sp.Add.make_args(sp.expand(eom))
    lhs = sp.Add(*(t for i, t in enumerate(terms) if i not in moved))
    rhs = -sp.Add(*(t for i, t in enumerate(terms) if i in moved))
    scale = ref.symbols["m2"] if factor == "parameter" else sp.Rational(factor)
    answer = f"{expr_text(scale * lhs)} = {expr_text(scale * rhs)}"
    status, feedback = verdict(ref, f"equations_of_motion[{which + 1}]", answer)
    assert status is Status.CORRECT, (answer, feedback)


def test_compare_newton_euler_results() -> None:
    """The Newton-Euler results: equations (same rules as Lagrange's), reactions, flags."""
    ref = tutorial(3)
    if "newton_euler" not in ref.results:
        pytest.skip("this tutgen does not report Newton-Euler results")
    result = mark_text(
        ref,
        """\
        newton_euler.equations_of_motion.theta: m2*l**2*theta_ddot + m2*l*x_ddot*cos(theta) + m2*g*l*sin(theta) = tau
        newton_euler.reaction_forces.pivot.force[2]: m2*g + m2*l*(theta_ddot*sin(theta) + theta_dot**2*cos(theta))
        newton_euler.reaction_forces.pivot.moment[3]: 0
        newton_euler.agrees_with_lagrange: true
        """,
    )
    assert {k: s for k, (s, _) in verdicts(result).items()} == {
        "newton_euler.equations_of_motion[2]": Status.CORRECT,
        "newton_euler.reaction_forces.pivot.force[2]": Status.CORRECT,
        "newton_euler.reaction_forces.pivot.moment[3]": Status.WRONG,
        "newton_euler.agrees_with_lagrange": Status.CORRECT,
    }
