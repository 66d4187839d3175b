"""Sheets that do not give answers away (issue 15 item 5): a question title of its own, coordinates left
to the student, and statements that quote each variant's numbers through placeholders."""

from __future__ import annotations

import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.engine.pipeline import derive
from tutgen.sheet.build import substituted
from tutgen.sheet.render import ASKED_COORDINATES, problem_view, render_sheet
from tutgen.sheet.variants import with_values
from tutgen.spec.validate import load_system_text

TUTORIAL = SPECS / "tutorial-1"

ROD = """
title: rod
statement: |
  A {m} slender rod is {L} long; {{braces}} stay braces, and $m$ stays maths.
parameters:
  m: {range: [5, 20], step: 1, unit: kg, value: 15 kg}
  L: 1.5 m
coordinates: [theta]
bodies:
  rod: {parts: {rod: {shape: rod, mass: m, length: L, axis: x, at: [L/2, 0, 0]}}}
joints:
  pivot: {type: revolute, parent: ground, child: rod, axis: z, coordinate: theta}
ask: [kinetic_energy]
"""


def _header() -> dict[str, str]:
    return {"title": "t", "course": "c", "date": "d", "label": ""}


def test_sheet_question_title_differs_from_the_solution_title() -> None:
    _, d, _ = solved(str(TUTORIAL / "p09-pr-manipulator.yaml"))
    view = problem_view(9, d, solution=True)
    assert view["title"] == "PR manipulator with a singular inertia matrix"
    assert view["question_title"] == "PR manipulator (quiz 2000)"
    context = {**_header(), "problems": [view]}
    questions = render_sheet(context, "questions", "md")
    solutions = render_sheet(context, "solutions", "md")
    assert "singular" not in questions.lower()
    assert "## Problem 9. PR manipulator (quiz 2000)" in questions
    assert "Problem 9. PR manipulator with a singular inertia matrix" in solutions
    latex = render_sheet(context, "questions", "tex")
    assert "PR manipulator (quiz 2000)" in latex and "singular" not in latex.lower()


def test_sheet_coordinates_left_to_the_student() -> None:
    _, d, _ = solved(str(TUTORIAL / "p08-spatial-rr.yaml"))
    view = problem_view(8, d, solution=True)
    assert view["question_coordinates"] == [] and view["coordinates"]
    assert view["asked"][0].lower() == ASKED_COORDINATES
    context = {**_header(), "problems": [view]}
    assert "Generalized coordinates." not in render_sheet(context, "questions", "md")
    assert "Generalized coordinates." in render_sheet(context, "solutions", "md")
    assert "Generalized coordinates." not in render_sheet(context, "questions", "tex")
    # a spec that says nothing keeps its coordinates on the question sheet
    _, d5, _ = solved(str(TUTORIAL / "p05-rr-arm.yaml"))
    assert problem_view(5, d5, solution=False)["question_coordinates"]


def _statement_text(view: dict) -> str:
    return "".join(p.get("text", "") or f"${p['tex']}$" for p in view["statement_parts"])


def test_sheet_statement_placeholders_quote_each_variant() -> None:
    system = load_system_text(ROD, "rod.yaml")
    base = derive(system)
    nominal = _statement_text(problem_view(1, base, solution=False))
    assert "$15\\ \\mathrm{kg}$ slender rod is $1.5\\ \\mathrm{m}$ long" in nominal
    assert "{braces} stay braces" in nominal and "and $m$ stays maths" in nominal
    kg = next(p for p in system.parameters if p.name == "m")
    variant = substituted(base, with_values(system, {"m": sp.Integer(7)}))
    quoted = _statement_text(problem_view(1, variant, solution=True))
    assert "$7\\ \\mathrm{kg}$ slender rod" in quoted
    assert kg.choices is not None and sp.Integer(7) in kg.choices
    # the raw statement keeps the placeholder (the JSON output and the concrete specs show it as written)
    assert "{m}" in str(variant.system.statement)
