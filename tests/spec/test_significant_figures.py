"""``significant_figures:``: a top-level spec key filling System.significant_figures (issue 14 point 4)."""

from __future__ import annotations

import pytest

from tutgen.errors import SpecErrors
from tutgen.spec.schema import json_schema
from tutgen.spec.validate import load_system_text

BASE = "title: t\ncoordinates: [x]\nenergy: {kinetic: x_dot**2/2}\n"


def test_unset_leaves_the_renderers_default() -> None:
    assert load_system_text(BASE, "s.yaml").significant_figures is None


@pytest.mark.parametrize("figures", [1, 4, 15])
def test_a_whole_number_from_1_to_15_is_kept(figures: int) -> None:
    assert load_system_text(BASE + f"significant_figures: {figures}\n", "s.yaml").significant_figures == figures


@pytest.mark.parametrize(
    ("value", "found"),
    [
        ("0", "the number 0"),
        ("16", "the number 16"),
        ("-3", "the number -3"),
        ("4.5", "the number 4.5"),
        ("true", "the boolean true"),
        ("'4'", "the text '4'"),
        ("[4]", "a list of 1 item"),
    ],
)
def test_anything_else_is_a_located_spec_error(value: str, found: str) -> None:
    with pytest.raises(SpecErrors) as info:
        load_system_text(BASE + f"significant_figures: {value}\n", "s.yaml")
    (error,) = info.value.errors
    assert (error.location.line, error.location.col) == (4, 22)
    assert error.message == f"'significant_figures' must be a whole number from 1 to 15; found {found}"


def test_the_json_schema_states_the_range() -> None:
    prop = json_schema()["properties"]["significant_figures"]
    assert prop["minimum"] == 1 and prop["maximum"] == 15
