"""The sheet's template context and templates: the variant's numbers in their units, escaped text."""

from __future__ import annotations

from tutgen.engine.pipeline import derive
from tutgen.sheet.build import substituted
from tutgen.sheet.render import given_items, problem_view, render_sheet
from tutgen.sheet.variants import with_values
from tutgen.spec.validate import load_system_text

SPEC = """
title: Mass & spring
statement: A mass m on a spring of stiffness k, 100% linear.
parameters:
  m: {choices: [150, 200], unit: g, description: the mass}
  k: {range: [10, 20], step: 5, unit: N/m}
  F:
coordinates: {x: {description: position}}
bodies: {b: {mass: m, position: [x, 0, 0]}}
springs: {s: {stiffness: k, extension: x}}
generalized_forces: {x: F}
"""


def test_given_shows_values_in_the_units_written() -> None:
    system = load_system_text(SPEC)
    items = given_items(system)
    assert items[0] == [
        {"kind": "math", "tex": "m = 150\\ \\mathrm{g}"},
        {"kind": "text", "text": " (the mass)"},
    ]
    assert items[1] == [{"kind": "math", "tex": "k = 15\\ \\mathrm{N/m}"}]
    assert items[2] == [{"kind": "math", "tex": "F"}]


def test_sheet_templates_show_the_variant_and_escape_text() -> None:
    system = load_system_text(SPEC)
    variant = substituted(derive(system, "lagrange"), with_values(system, {"m": system.parameters[0].choices[1]}))
    view = problem_view(4, variant, solution=True)
    assert view["asked"][-1] == "the Christoffel symbols"
    header = {"title": "Tutorial #1 & more", "course": "ME_4245", "date": "1 May", "label": "Ada {x} \\input"}
    context = {**header, "problems": [view]}
    md = render_sheet(context, "questions", "md")
    assert md.startswith("# Tutorial \\#1 & more: questions\n\n**ME\\_4245** · 1 May\n\n*Ada \\{x\\} \\\\input*\n\n")
    assert "## Problem 4. Mass & spring\n" in md and "$m = 200\\ \\mathrm{g}$ (the mass)" in md
    tex = render_sheet(context, "solutions", "tex")
    assert "\\title{Tutorial \\#1 \\& more: worked solutions}" in tex
    assert "\\textit{Ada \\{x\\} \\textbackslash{}input}" in tex
    assert "100\\% linear" in tex and "\\subsection{Equations of motion}" in tex
    # m = 0.2 kg substituted, printed as a decimal like the data (not 1/5), rates dotted
    assert "x_{ddot}" not in tex and "0.2 \\ddot{x}" in tex and "\\frac{\\ddot{x}}{5}" not in tex
