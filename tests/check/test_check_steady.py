"""Marking steady motion (issue 18): the steady values, where each exists, the generalized force the
cyclic coordinate needs, and the stability; matched by value, not by tutgen's order.

Right answers in the forms a student writes them (cos theta = g/(R omega^2), 2 pi - acos, a decimal
as printed, g/(R omega^2) <= 1) pass; wrong ones (a sign, a factor 2, the other root, a wrong
verdict) fail with why; malformed ones are located errors, never a traceback.
"""

from __future__ import annotations

import pytest

from tests.check.helpers import errors, mark_text, reference, verdicts
from tests.conftest import SPECS
from tutgen.check.compare import Status
from tutgen.check.decimals import half_unit

DRIVEN = SPECS / "examples" / "s-bead-on-driven-hoop.yaml"
FREE = SPECS / "examples" / "t-bead-on-free-hoop.yaml"
CONE = SPECS / "examples" / "u-conical-pendulum.yaml"

RIGHT = """\
steady_motion:
  - at: {theta: "cos(theta) = g/(R*omega^2)"}
    exists_where: "g/(R*omega^2) <= 1"
    required: {phi: 0}
    inputs: {tau: 0}
    momenta: {phi: "M*R**2*omega/2 + R**2*m*omega - g**2*m/omega**3"}
    stability: stable
  - at: {theta: 0}
    exists_where: always
    stability: conditionally stable
    stable_where: "R*omega**2 < g"
  - at: {theta: pi}
    stability: Unstable
"""


def _statuses(result: object) -> dict[str, Status]:
    return {name: status for name, (status, _) in verdicts(result).items()}  # type: ignore[arg-type]


def test_right_steady_motion_answers_pass() -> None:
    result = mark_text(reference(DRIVEN), RIGHT)
    marks = verdicts(result)
    assert all(status is Status.CORRECT for status, _ in marks.values()), marks
    # the equation matches both tilted motions (theta = +-acos), and every field is checked against each
    assert "steady_motion[1].stability" in marks and "steady_motion[3].at" in marks
    (item,) = [i for i in result.items if i.name == "steady_motion"]
    assert item.status is Status.CORRECT


def test_each_root_may_be_given_as_its_own_value_up_to_two_pi() -> None:
    text = """\
    steady_motion:
      - at: {theta: "acos(g/(R*omega**2))"}
      - at: {theta: "2*pi - acos(g/(R*omega**2))"}
      - at: {theta: "0"}
      - at: {theta: "-pi"}
    """
    marks = verdicts(mark_text(reference(DRIVEN), text))
    assert {s for s, _ in marks.values()} == {Status.CORRECT}, marks


@pytest.mark.parametrize(
    ("answer", "wrong", "said"),
    [
        pytest.param('{at: {theta: "cos(theta) = -g/(R*omega**2)"}}', "steady_motion[1].at", "not a steady", id="sign"),
        pytest.param(
            '{at: {theta: "cos(theta) = 2*g/(R*omega**2)"}}', "steady_motion[1].at", "not a steady", id="factor-2"
        ),
        pytest.param(
            '{at: {theta: "pi - acos(g/(R*omega**2))"}}', "steady_motion[1].at", "not a steady", id="other-root"
        ),
        pytest.param(
            '{at: {theta: "acos(g/(R*omega**2))"}, exists_where: "g <= 2*R*omega**2"}',
            "steady_motion[1].exists_where",
            "expected g <= R*omega**2",
            id="condition-factor-2",
        ),
        pytest.param(
            '{at: {theta: "acos(g/(R*omega**2))"}, exists_where: "g >= R*omega**2"}',
            "steady_motion[1].exists_where",
            "expected g <= R*omega**2",
            id="condition-reversed",
        ),
        pytest.param(
            '{at: {theta: 0}, stability: conditional, stable_where: "g < R*omega**2"}',
            "steady_motion[1].stable_where",
            "expected g > R*omega**2",
            id="stable-where-sign",
        ),
        pytest.param(
            '{at: {theta: "acos(g/(R*omega**2))"}, stability: unstable}',
            "steady_motion[1].stability",
            "expected 'stable'",
            id="verdict",
        ),
        pytest.param(
            '{at: {theta: "acos(g/(R*omega**2))"}, required: {phi: "m*g*R"}}',
            "steady_motion[1].required.phi",
            "the correct value is 0",
            id="required-force",
        ),
        pytest.param(
            '{at: {theta: pi}, momenta: {phi: "M*R**2*omega"}}',
            "steady_motion[1].momenta.phi",
            "",
            id="momentum-factor-2",
        ),
    ],
)
def test_wrong_steady_motion_answers_fail(answer: str, wrong: str, said: str) -> None:
    marks = verdicts(mark_text(reference(DRIVEN), f"steady_motion:\n  - {answer}\n"))
    status, feedback = marks[wrong]
    assert status is Status.WRONG and said in feedback, marks


def test_unanswered_motions_are_missing_and_a_repeat_is_wrong() -> None:
    text = """\
    steady_motion:
      - at: {theta: 0}
      - at: {theta: "2*pi"}
    """
    result = mark_text(reference(DRIVEN), text)
    (item,) = [i for i in result.items if i.name == "steady_motion"]
    missing = [e.feedback for e in item.entries if e.status is Status.MISSING]
    assert sorted(missing) == [
        "no answer for the steady motion theta = -acos(g/(R*omega**2))",
        "no answer for the steady motion theta = acos(g/(R*omega**2))",
        "no answer for the steady motion theta = pi",
    ]
    assert verdicts(result)["steady_motion[2].at"] == (
        Status.WRONG,
        "the same steady motion as steady_motion[1]; each is answered once",
    )


def test_free_hoop_momentum_and_a_wrong_sign_in_it() -> None:
    text = """\
    steady_motion:
      - at: {theta: "acos(g/(R*Omega**2))"}
        required: {phi: 0}
        momenta: {phi: "M*Omega*R**2/2 + Omega*R**2*m - g**2*m/Omega**3"}
        stability: stable
      - at: {theta: "-acos(g/(R*Omega**2))"}
        momenta: {phi: "M*Omega*R**2/2 + Omega*R**2*m + g**2*m/Omega**3"}
    """
    marks = verdicts(mark_text(reference(FREE), text))
    assert marks["steady_motion[1].momenta.phi"][0] is Status.CORRECT
    assert marks["steady_motion[1].stability"][0] is Status.CORRECT
    assert marks["steady_motion[2].momenta.phi"] == (Status.WRONG, "wrong sign of the term -g**2*m/Omega**3")


def test_numeric_spec_accepts_decimals_as_printed_and_the_pole_verdicts() -> None:
    text = """\
    steady_motion:
      - {at: {theta: "acos(981/2000)"}, exists_where: "g <= 25*l", stability: stable, momenta: {phi: 1.215}}
      - {at: {theta: -1.058}, stability: stable}
      - {at: {theta: 0}, stability: stable}
      - {at: {theta: pi}, stability: unstable}
    """
    marks = verdicts(mark_text(reference(CONE), text))
    assert {s for s, _ in marks.values()} == {Status.CORRECT}, marks
    wrong = verdicts(mark_text(reference(CONE), "steady_motion: [{at: {theta: 0}, stability: undetermined}]\n"))
    status, feedback = wrong["steady_motion[1].stability"]
    assert status is Status.WRONG and "expected 'stable'" in feedback and "singular" in feedback


@pytest.mark.parametrize(
    ("text", "message"),
    [
        pytest.param(
            'steady_motion: "theta = 0"\n', "1:16: error: steady_motion is a list of steady motions", id="text"
        ),
        pytest.param("steady_motion: [5]\n", "1:17: error: a steady motion is a mapping", id="not-a-mapping"),
        pytest.param(
            "steady_motion: [{stability: stable}]\n", "a steady motion says where it is: `at: {theta: ...}`", id="no-at"
        ),
        pytest.param("steady_motion: [{at: {phi: 0}}]\n", "'phi' is held at its rate (phi)", id="held-coordinate"),
        pytest.param(
            "steady_motion: [{at: {theta: 0}, stabilty: stable}]\n",
            "a steady motion has no field 'stabilty'",
            id="misspelt-field",
        ),
        pytest.param(
            "steady_motion: [{at: {theta: 0}, stability: wobbly}]\n",
            "cannot read the stability 'wobbly'; expected one of: stable, unstable",
            id="unknown-verdict",
        ),
        pytest.param(
            "steady_motion.states[1].stability: stable\n",
            "names a part of steady_motion by its place in tutgen's list",
            id="by-place",
        ),
    ],
)
def test_malformed_steady_motion_answers_are_located_errors(text: str, message: str) -> None:
    result = mark_text(reference(DRIVEN), text)
    assert any(message in e for e in errors(result)), errors(result)


@pytest.mark.parametrize(
    ("value", "why"),
    [
        pytest.param('"acos(g/(R*omega**2)"', "unclosed '(' of the call to 'acos'", id="unclosed"),
        pytest.param('"__import__(1)"', "unknown name '__import__'", id="code"),
        pytest.param('"x + 1"', "unknown name 'x'", id="unknown-name"),
        pytest.param('"theta_dot"', "holds no coordinate, acceleration or rate but a held one", id="a-rate"),
        pytest.param('"cos(theta) = 1 = 2"', "an equation has one '='", id="two-equals"),
        pytest.param('"(theta+1)**(10**9)"', "the exponent 1000000000 is too large", id="huge-power"),
        pytest.param('"10**10**10"', "is too large", id="tower"),
        pytest.param('"1/0"', "division by zero", id="pole"),
    ],
)
def test_hostile_or_unreadable_values_are_wrong_with_why_not_fatal(value: str, why: str) -> None:
    result = mark_text(reference(DRIVEN), f"steady_motion: [{{at: {{theta: {value}}}}}]\n")
    status, feedback = verdicts(result)["steady_motion[1].at.theta"]
    assert status is Status.WRONG and why in feedback


def test_a_steady_value_may_hold_the_rate_of_the_held_coordinate() -> None:
    """Without `analysis.steady` the held rate is phi_dot itself: cos theta = g/(R phi_dot^2)."""
    import yaml

    from tests.models import system_of
    from tutgen.check.verdicts import reference_from
    from tutgen.engine.pipeline import derive

    data = yaml.safe_load(DRIVEN.read_text(encoding="utf-8"))
    del data["analysis"]
    system = system_of(data)
    ref = reference_from(system, derive(system), "hoop.yaml")
    text = "steady_motion: [{at: {theta: 'acos(g/(R*phi_dot**2))'}, exists_where: 'g <= R*phi_dot^2'}]\n"
    marks = verdicts(mark_text(ref, text))
    assert {s for s, _ in marks.values() if s is not Status.MISSING} == {Status.CORRECT}, marks


def test_steady_motion_is_graded_without_a_key_when_the_spec_asks_for_it() -> None:
    ref = reference(DRIVEN)
    assert "steady_motion" in ref.asked and ref.angles == frozenset({"phi", "theta"})
    result = mark_text(ref, "student: Ada\n")  # answers nothing: every asked item is missing
    (item,) = [i for i in result.items if i.name == "steady_motion"]
    assert item.status is Status.MISSING


def test_half_unit_of_a_negative_decimal_counts_its_digits_not_its_sign() -> None:
    assert half_unit("-1.058", 4) == half_unit("1.058", 4)


def test_a_marking_key_may_ask_for_steady_motion_alone() -> None:
    result = mark_text(reference(DRIVEN), RIGHT, key="ask: [steady_motion]\n")
    assert [(i.name, i.status) for i in result.items] == [("steady_motion", Status.CORRECT)]


def test_a_stability_tutgen_does_not_decide_is_not_marked_wrong() -> None:
    """The heavy top at theta = 0 spins about its own axis: tutgen leaves its stability undetermined
    (and says why), so a student's verdict on it cannot be marked either way."""
    import yaml

    from tests.models import system_of
    from tutgen.check.verdicts import reference_from
    from tutgen.engine.pipeline import derive

    data = yaml.safe_load((SPECS / "examples" / "g-heavy-symmetric-top.yaml").read_text(encoding="utf-8"))
    data["ask"] = ["equations_of_motion", "steady_motion"]
    system = system_of(data)
    ref = reference_from(system, derive(system), "top.yaml")
    marks = verdicts(mark_text(ref, "steady_motion: [{at: {theta: 0}, stability: stable}]\n"))
    status, feedback = marks["steady_motion[1].stability"]
    assert status is Status.CANNOT_EVALUATE and "spinning about its own axis" in feedback
