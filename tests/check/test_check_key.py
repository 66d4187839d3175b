"""The instructor's marking key: asked items graded whether answered or not, rules per item, its errors."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.check.helpers import mark_text, tutorial, with_key
from tutgen.check.compare import Status, key_problems
from tutgen.check.key import read_key
from tutgen.errors import SpecErrors

EOM2 = (
    "(m2*a2**2 + m2*a1*a2*cos(theta2))*theta1_ddot + m2*a2**2*theta2_ddot + m2*a1*a2*theta1_dot**2*sin(theta2)"
    " + m2*g*a2*cos(theta1 + theta2) - tau2"
)


def test_key_ask_grades_every_asked_item_and_only_those() -> None:
    result = mark_text(
        tutorial(5),
        'mass_matrix[2,2]: "m2*a2**2"\nkinetic_energy: "0"\n',
        key="ask: [mass_matrix, potential_energy]\n",
    )
    assert [(i.name, i.status) for i in result.items] == [
        ("mass_matrix", Status.CORRECT),  # only the entry given is checked: a table may be partial
        ("potential_energy", Status.MISSING),
    ]
    assert result.status == "fail"


def test_key_scaling_off_refuses_a_scaled_equation() -> None:
    answer = f'equations_of_motion.theta2: "2*({EOM2})"\n'
    (scaled,) = mark_text(tutorial(5), answer).items
    assert scaled.status is Status.CORRECT
    assert scaled.entries[0].how.startswith("scaled by 2:")
    (refused,) = mark_text(tutorial(5), answer, key="items: {equations_of_motion: {scaling: false}}\n").items
    assert refused.status is Status.WRONG
    assert refused.entries[0].feedback.startswith("scaled by 2: this equation is marked without scaling")


def test_key_most_specific_rule_wins() -> None:
    key = (
        "tolerance: {rel_tol: 0.5}\nitems: {inertia_tensor: {rel_tol: 0.1}, 'inertia_tensor[1,1]': {rel_tol: 1.0e-3}}\n"
    )
    text = "inertia_tensor[1,1]: 9.6e-3\ninertia_tensor[2,2]: 1.8e-2\n"  # 0.004 and 0.04 off
    found = {e.name: e.status for i in mark_text(tutorial(1), text, key=key).items for e in i.entries}
    assert found == {"inertia_tensor[1,1]": Status.CORRECT, "inertia_tensor[2,2]": Status.CORRECT}
    text = "inertia_tensor[1,1]: 9.7e-3\n"  # 1 % off: outside the entry's own 1e-3
    (item,) = mark_text(tutorial(1), text, key=key).items
    assert item.status is Status.WRONG


def test_key_errors_are_located(tmp_path: Path) -> None:
    path = tmp_path / "key.yaml"
    path.write_text("ask: [mas_matrix]\ntolerence: {}\nitems: {kinetic_energy: {rel_tol: -1, scale: no}}\n")
    with pytest.raises(SpecErrors) as info:
        read_key(path)
    text = str(info.value)
    assert f"{path}:1:7: error: unknown result 'mas_matrix' in the asked item" in text
    assert f"{path}:2:1: error: unknown key 'tolerence' in a marking key" in text
    assert "'rel_tol' must not be negative, found -1" in text
    assert "unknown key 'scale' in a tolerance" in text


def test_key_naming_a_result_this_spec_lacks_is_an_error(tmp_path: Path) -> None:
    path = tmp_path / "key.yaml"
    path.write_text("ask: [christoffel]\n")
    ref = with_key(tutorial(1), path)
    (problem,) = key_problems(ref)
    assert str(problem).startswith(f"{path}:1:7: error: the marking's 'christoffel' names no result")
