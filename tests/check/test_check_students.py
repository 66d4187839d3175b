"""Answers as students write them (issue 20), tried as a hostile student would: Unicode input keeps
its error locations, copied decimals are right only as printed, the instructor can turn that off."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.check.helpers import errors, mark_text, reference, verdicts
from tutgen.check.compare import Status
from tutgen.check.notation import ascii_answer

ROD = Path(__file__).parent / "specs" / "rod-variant.yaml"  # T = 2119/600 θ̇² = 3.53167 θ̇²


@pytest.mark.parametrize(
    ("answer", "status"),
    [
        pytest.param('"3.532 θ̇²"', Status.CORRECT, id="as-printed"),
        pytest.param('"3.5317 θ̇²"', Status.CORRECT, id="more-figures-right"),
        pytest.param('"3.5318 θ̇²"', Status.WRONG, id="more-figures-wrong"),
        pytest.param('"3.532 θ̇² + 0.0001 θ̇"', Status.WRONG, id="a-small-extra-term"),
        pytest.param('"3.532 θ̇² + 1.0e15*(cosh(θ)**2.0 - sinh(θ)**2.0 - 1.000)"', Status.WRONG, id="hidden-zero"),
        pytest.param('"3.5 θ̇² + 1.0e15*(cosh(θ)**2.0 - sinh(θ)**2.0 - 1.000)"', Status.WRONG, id="hidden-zero-wrong"),
        pytest.param('"1.766 θ̇² + 1.766 θ̇²"', Status.CORRECT, id="terms-collected"),
        pytest.param('"3.532e0 θ̇**2.0"', Status.CORRECT, id="decimal-exponent-is-exact"),
        pytest.param('"3.532 θ̇**2.001"', Status.WRONG, id="decimal-exponent-off"),
    ],
)
def test_students_decimals_are_right_only_as_printed(answer: str, status: Status) -> None:
    found = verdicts(mark_text(reference(ROD), f"kinetic_energy: {answer}\n"))
    assert found["kinetic_energy"][0] is status, found


def test_students_decimals_exact_when_the_marking_says_so() -> None:
    found = verdicts(mark_text(reference(ROD), 'kinetic_energy: "3.532 θ̇²"\n', key="significant_figures: 0\n"))
    assert found["kinetic_energy"][0] is Status.WRONG


def test_students_unicode_parse_errors_point_into_the_text_as_written() -> None:
    """``θ̇²`` becomes ``theta_dot**2`` before parsing; the error still points at the answer's own column."""
    result = mark_text(reference(ROD), 'kinetic_energy: "θ̇² · (3.532 ]"\n')
    status, feedback = verdicts(result)["kinetic_energy"]
    assert status is Status.WRONG
    assert feedback.endswith("(at 1:31)"), feedback  # the ']' (column 31 of the line)
    assert errors(result) == []


@pytest.mark.parametrize(
    ("written", "ascii"),
    [
        ("θ̇₁²", "theta1_dot**2"),
        ("ẍ", "x_ddot"),
        ("m·g·l cos θ₁ θ̇₂", "m*g*l*cos(theta1)*theta2_dot"),
        ("sin²θ + cos 2φ", "sin(theta)**2+cos(2*phi)"),
        ("−½ k x⁻¹", "-(1/2)*k*x**(-1)"),
        ("ω × r", "omega*r"),
        ("2e3 m", "2e3*m"),
    ],
)
def test_students_notation_reads_as_the_spec_grammar(written: str, ascii: str) -> None:
    assert ascii_answer(written).text == ascii
