"""`conventions: {christoffel: …}`: which Christoffel symbols the worked solution prints, and its errors."""

from __future__ import annotations

import pytest

from tutgen.api import render
from tutgen.engine.pipeline import derive
from tutgen.errors import SpecErrors
from tutgen.model.system import ChristoffelConvention
from tutgen.spec.validate import load_system_text

SPEC = """\
title: t
coordinates: [a, b]
energy:
  kinetic: (3/2 + cos(b))*a_dot**2 + (1 + cos(b))*a_dot*b_dot + b_dot**2/2
ask: [matrix_form, christoffel]
"""


def _christoffel_section(convention: str | None) -> str:
    text = SPEC + (f"conventions: {{christoffel: {convention}}}\n" if convention else "")
    md = render(derive(load_system_text(text, "t.yaml")), "md")
    assert isinstance(md, str)
    return md[md.index("Christoffel symbols") :]


@pytest.mark.parametrize(
    ("convention", "h", "c"),
    [(None, True, True), ("both", True, True), ("asada_slotine", True, False), ("first_kind", False, True)],
)
def test_the_solution_prints_the_conventions_the_spec_asks_for(convention, h, c):
    section = _christoffel_section(convention)
    assert ("h_{112}" in section) is h
    assert ("c_{112}" in section) is c
    # C is contracted from the symbols that are printed
    assert ("C_i = \\sum_{j,k} h_{ijk}\\,\\dot q_j \\dot q_k" in section) is h
    assert "C = " in section


def test_the_convention_is_part_of_the_model():
    system = load_system_text(SPEC + "conventions: {christoffel: first_kind}\n", "t.yaml")
    assert system.conventions.christoffel is ChristoffelConvention.FIRST_KIND
    assert load_system_text(SPEC, "t.yaml").conventions.christoffel is ChristoffelConvention.BOTH


def test_a_convention_for_symbols_not_asked_for_is_an_error_at_its_key():
    text = SPEC.replace("ask: [matrix_form, christoffel]", "ask: [matrix_form]")
    text += "conventions:\n  christoffel: first_kind\n"
    with pytest.raises(SpecErrors) as info:
        load_system_text(text, "t.yaml")
    message = str(info.value)
    assert "t.yaml:7:" in message and "does not ask" in message


def test_an_unknown_convention_is_an_error_naming_the_choices():
    with pytest.raises(SpecErrors) as info:
        load_system_text(SPEC + "conventions: {christoffel: second_kind}\n", "t.yaml")
    message = str(info.value)
    assert "t.yaml:6:" in message and "asada_slotine" in message and "first_kind" in message
