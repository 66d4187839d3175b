"""Sheet files, rosters and parameter ranges: read with every problem at its file:line:col."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest
import sympy as sp

from tests.conftest import SPECS
from tutgen.errors import SpecErrors
from tutgen.sheet.model import load_roster, load_sheet
from tutgen.spec.validate import load_system_text

TUTORIAL = SPECS / "tutorial-1"


def write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text).lstrip("\n"), encoding="utf-8")
    return path


def errors_of(func, *args) -> list[str]:
    with pytest.raises(SpecErrors) as info:
        func(*args)
    return [str(e) for e in info.value.errors]


def test_sheet_tutorial_loads_every_problem_in_order() -> None:
    sheet = load_sheet(TUTORIAL / "sheet.yaml")
    assert [p.number for p in sheet.problems] == list(range(1, 11))
    assert [p.key[:3] for p in sheet.problems] == [f"p{i:02d}" for i in range(1, 11)]
    assert sheet.title and sheet.course and sheet.date
    p03 = {p.name: p for p in sheet.problems[2].system.parameters}
    assert p03["m1"].choices == tuple(sp.Rational(k, 2) for k in range(2, 11))
    assert p03["m1"].value == 3  # the middle of the range is the nominal value
    assert p03["g"].value == sp.Rational(981, 100) and p03["g"].choices is None
    assert p03["F"].value is None  # not varied: stays symbolic
    # the spec file itself is untouched: the tutorial's specs stay symbolic
    assert "range:" not in (TUTORIAL / "p03-cart-pendulum.yaml").read_text()  # not "lagrange"


def test_sheet_errors_are_located_in_the_sheet(tmp_path: Path) -> None:
    spec = TUTORIAL / "p03-cart-pendulum.yaml"
    sheet = write(
        tmp_path,
        "sheet.yaml",
        f"""
        title: T
        dat: 2026
        problems:
          - {spec}
          - spec: {spec}
            vary:
              mass1: {{range: [1, 2], unit: kg}}
          - spec: missing.yaml
          - spec: {TUTORIAL / "p04-rp-arm.yaml"}
            vary:
              m: {{range: [5, 1], unit: kg}}
              g: {{choices: [9.81], unit: m/s^3, dimension: acceleration}}
        """,
    )
    got = errors_of(load_sheet, sheet)
    s = str(sheet)
    assert got == [
        f"{s}:2:1: error: unknown key 'dat' in the sheet; expected one of: tutgen_sheet, title, course, date, "
        "problems, marking\n  hint: did you mean 'date'?",
        f"{s}:7:7: error: the spec '{spec}' has no parameter 'mass1' (its parameters: m1, m2, l, k, g, F, tau)",
        f"{s}:8:11: error: no spec file 'missing.yaml' (looked for {tmp_path / 'missing.yaml'})",
        f"{s}:11:18: error: the range of parameter 'm' goes down: write [lo, hi] with lo <= hi",
        f"{s}:12:34: error: parameter 'g' is declared as an acceleration (m/s^2), but its unit 'm/s^3' is "
        + got[4].split("but its unit 'm/s^3' is ")[1],
    ]


def test_sheet_needs_title_and_problems(tmp_path: Path) -> None:
    sheet = write(tmp_path, "sheet.yaml", "course: C\nproblems: []\n")
    assert errors_of(load_sheet, sheet) == [
        f"{sheet}:1:1: error: the sheet needs a 'title'",
        f"{sheet}:2:11: error: the sheet needs 'problems': a list of spec files",
    ]


def test_sheet_reports_errors_of_its_specs(tmp_path: Path) -> None:
    spec = write(tmp_path, "bad.yaml", "title: t\nbodies: {b: {mas: m}}\n")
    sheet = write(tmp_path, "sheet.yaml", "title: T\nproblems: [bad.yaml]\n")
    (error,) = errors_of(load_sheet, sheet)
    assert error.startswith(f"{spec}:2:14: error: unknown key 'mas'")


def test_roster_reads_ids_and_names(tmp_path: Path) -> None:
    roster = write(tmp_path, "roster.csv", 'id,name,email\nA0001,Ada Lovelace,a@x\n\nA0002,"Babbage, Charles",b@x\n')
    students = load_roster(roster)
    assert [(s.id, s.name) for s in students] == [("A0001", "Ada Lovelace"), ("A0002", "Babbage, Charles")]


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        pytest.param("name,email\nAda,a@x\n", "1:1: error: the roster's header has no 'id' column", id="no-id"),
        pytest.param(
            "name,id\nAda,A1\nBob,A1\n", "3:5: error: the id 'A1' is listed twice (first on line 2)", id="twice"
        ),
        pytest.param("id,name\n../x,Eve\n", "2:1: error: the id '../x' cannot name a directory", id="path"),
        pytest.param("id,name\n,Nobody\n", "2:1: error: this student has no id", id="empty"),
    ],
)
def test_roster_errors_are_located(tmp_path: Path, text: str, expected: str) -> None:
    roster = write(tmp_path, "roster.csv", text)
    (error,) = errors_of(load_roster, roster)
    assert error.startswith(f"{roster}:{expected}")


SPEC = """
title: t
parameters:
  m: {entry}
coordinates: [x]
bodies: {{b: {{mass: m, position: [x, 0, 0]}}}}
"""


@pytest.mark.parametrize(
    ("entry", "choices", "nominal"),
    [
        pytest.param(
            "{range: [1, 2]}", [1 + sp.Rational(k, 10) for k in range(11)], sp.Rational(3, 2), id="default-step"
        ),
        pytest.param(
            "{range: [10, 30], step: 10, unit: g}",
            [sp.Rational(k, 100) for k in (1, 2, 3)],
            sp.Rational(1, 50),
            id="unit",
        ),
        pytest.param("{choices: [2, 1.5], unit: kg}", [2, sp.Rational(3, 2)], 2, id="choices-first"),
        pytest.param(
            "{choices: [2, 1.5], value: 1.5 kg, unit: kg}", [2, sp.Rational(3, 2)], sp.Rational(3, 2), id="value"
        ),
    ],
)
def test_parameter_ranges_and_choices(entry: str, choices: list, nominal: sp.Expr) -> None:
    (m,) = load_system_text(SPEC.format(entry=entry)).parameters
    assert m.choices == tuple(choices)
    assert m.value == nominal
    assert m.symbol.is_positive


def test_parameter_with_a_zero_choice_is_not_assumed_positive() -> None:
    (m,) = load_system_text(SPEC.format(entry="{range: [0, 2], step: 1}")).parameters
    assert m.value == 1 and m.symbol.is_positive is None


@pytest.mark.parametrize(
    ("entry", "expected"),
    [
        pytest.param(
            "{range: [1, 2], choices: [1]}", "4:31: error: parameter 'm' has both a range and choices", id="both"
        ),
        pytest.param("{choices: [1], step: 1}", "4:27: error: parameter 'm' has a step but no range", id="step"),
        pytest.param(
            "{range: [1, 2], step: 0}", "4:28: error: the step of parameter 'm' must be positive", id="zero-step"
        ),
        pytest.param(
            "{range: [1, 2], step: 1e-9}", "4:28: error: the range of parameter 'm' has 1000000001", id="too-many"
        ),
        pytest.param(
            "{choices: [1, 2], value: 3}", "4:31: error: the value of parameter 'm' is not one of", id="not-allowed"
        ),
        pytest.param("{choices: [1, 1]}", "4:20: error: choice 1 of parameter 'm' is listed twice", id="twice"),
        pytest.param(
            "{range: [1]}", "4:14: error: 'range' of parameter 'm' must be a range [lo, hi] of two numbers", id="short"
        ),
        pytest.param(
            "{choices: [a]}",
            "4:16: error: 'choices' of parameter 'm' must be a non-empty list of numbers",
            id="not-number",
        ),
        pytest.param("{range: [1, 2], unit: kgs}", "4:28: error: unknown unit 'kgs'", id="unit"),
    ],
)
def test_parameter_range_errors_are_located(entry: str, expected: str) -> None:
    with pytest.raises(SpecErrors) as info:
        load_system_text(SPEC.format(entry=entry), "s.yaml")
    assert str(info.value.errors[0]).startswith(f"s.yaml:{expected}")
