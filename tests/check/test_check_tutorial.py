"""`tutgen check` on the course tutorial: its answer key passes, its printed answers are flagged
exactly at the typos the key lists (tests/check/answers/pNN-printed.yaml)."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from tests.check.answer_key import ANSWERS, NUMBER_OF, SPEC_OF, answers_file, numbers_file, problems, typo_entries
from tests.check.helpers import mark_data, not_correct, tutorial, verdicts, with_key
from tutgen.check.compare import Reference, Status
from tutgen.check.run import mark_file

PRINTED = Path(__file__).parent / "answers"
PROBLEMS = list(range(1, 11))

pytestmark = pytest.mark.skipif(not ANSWERS.exists(), reason=f"the seed answer key is not at {ANSWERS}")


def printed(pid: int) -> Path:
    return PRINTED / f"p{pid:02d}-printed.yaml"


def printed_reference(pid: int) -> Reference:
    """The reference of problem ``pid`` with the instructor's key for its printed numbers, if any."""
    key = PRINTED / f"p{pid:02d}-key.yaml"
    return with_key(tutorial(pid), key if key.exists() else None)


@pytest.mark.parametrize("pid", PROBLEMS, ids=[f"p{p:02d}" for p in PROBLEMS])
def test_check_printed_answers_are_flagged_exactly_at_the_typos(pid: int) -> None:
    result = mark_file(printed_reference(pid), printed(pid))
    assert not result.errors
    assert not_correct(result) == typo_entries(pid)
    assert result.status == ("fail" if typo_entries(pid) else "pass")


@pytest.mark.parametrize("pid", PROBLEMS, ids=[f"p{p:02d}" for p in PROBLEMS])
def test_check_answer_key_is_all_correct(pid: int) -> None:
    data, key = numbers_file(pid) if pid <= 2 else (answers_file(pid, printed=False), None)
    result = mark_data(tutorial(pid), data, key)
    assert not_correct(result) == set()
    assert len(verdicts(result)) >= len(data)


@pytest.mark.parametrize("pid", range(3, 11), ids=[f"p{p:02d}" for p in range(3, 11)])
def test_check_printed_files_transcribe_the_answer_key(pid: int) -> None:
    data = yaml.safe_load(printed(pid).read_text(encoding="utf-8"))
    assert data.pop("spec") == f"specs/tutorial-1/{SPEC_OF[pid]}"
    data.pop("student")
    assert data == answers_file(pid, printed=True)


def _number(value: object) -> object:
    """A transcribed number: ``{value: "6.131e-3 kg m^2", ...}`` and ``"6.131e-3 kg m^2"`` are 6.131e-3."""
    if isinstance(value, dict):
        value = value["value"]
    if isinstance(value, list):
        return [_number(v) for v in value]
    return float(str(value).split()[0])


@pytest.mark.parametrize("pid", [1, 2], ids=["p01", "p02"])
def test_check_printed_numbers_are_the_answer_key_printed_ones(pid: int) -> None:
    """Problems 1 and 2 are transcribed by hand, with units: their numbers are the key's printed ones."""
    data = yaml.safe_load(printed(pid).read_text(encoding="utf-8"))
    problem = problems()[pid]
    for key in problem["printed_in_tutorial"]:
        target = NUMBER_OF[pid][key]
        if target is None:  # p02's T_coefficient: printed as T = 2.92 theta_dot^2
            assert data["kinetic_energy"] == f"{problem['answers'][key]['printed']}*theta_dot**2"
            continue
        assert _number(data[target]) == problem["answers"][key]["printed"], key


def feedback(pid: int, entry: str) -> str:
    status, text = verdicts(mark_file(printed_reference(pid), printed(pid)))[entry]
    assert status is Status.WRONG
    return text


def test_check_typo_feedback_names_what_differs() -> None:
    assert feedback(1, "inertia_tensor[1,1]") == "not correctly rounded: to 3 significant figures it is 9.60e-3"
    assert feedback(1, "bodies.body.parts.cylinder.inertia_tensor[1,1]") == (
        "not correctly rounded: to 3 significant figures it is 3.47e-3"
    )
    assert feedback(2, "kinetic_energy") == (
        "coefficient of theta_dot**2: yours is 73/25 (= 2.92), expected 117/40 (= 2.925)"
    )
    assert feedback(5, "lagrange_terms[2].dL_dq") == (
        "coefficient of theta1_dot**2*sin(theta2): yours is -a2**2*m2, expected -a1*a2*m2; "
        "coefficient of theta1_dot*theta2_dot*sin(theta2): yours is -a2**2*m2, expected -a1*a2*m2"
    )
    assert feedback(7, "velocities.link2[1]") == "wrong sign of the term -l2*theta2_dot*sin(theta2)"
    assert feedback(8, "coriolis_vector[1]") == "unknown name 'l' (did you mean 'l1'?)"
