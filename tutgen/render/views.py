"""Derivation -> a format-neutral template context of plain data: the worked solution's sections in
teaching order (:data:`SECTIONS`, one builder module each in tutgen/render/sections/), with the problem's
data, figure, remarks and checks. The blocks and parts the context is made of are described in
tutgen/render/blocks.py.

``remarks`` and ``checks`` (tutgen's own sentences, maths typeset), ``section.intro``,
``statement_parts`` (the statement, its ``$…$`` maths typeset) and each item of ``given`` and of
``coordinates`` are lists of parts; ``statement`` is the raw text.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from tutgen.engine.derivation import Derivation
from tutgen.figure.view import figure_view
from tutgen.model.system import System
from tutgen.render.blocks import Part, SolutionContext, all_decimals, math, prose, rich, unit_tex
from tutgen.render.printer import TexPrinter, is_decimal_document
from tutgen.render.sections.arm import arm_table
from tutgen.render.sections.energy import energies
from tutgen.render.sections.inertia import mass_properties
from tutgen.render.sections.kinematics import kinematics
from tutgen.render.sections.lagrange import equations_of_motion, lagrange_equations
from tutgen.render.sections.matrix import christoffel_symbols, matrix_form
from tutgen.render.sections.newton_euler import newton_euler
from tutgen.render.wording import engine_parts
from tutgen.spec.units import decimal_text, in_unit

__all__ = ["SECTIONS", "coordinate_items", "given_items", "prose", "rich", "solution_view"]

#: the sections of a worked solution, in teaching order; each returns its section or None
SECTIONS: tuple[Callable[[SolutionContext], dict[str, Any] | None], ...] = (
    mass_properties,
    kinematics,
    arm_table,
    energies,
    lagrange_equations,
    equations_of_motion,
    matrix_form,
    christoffel_symbols,
    newton_euler,
)


def given_items(system: System) -> list[list[Part]]:
    """The data of a problem: each parameter's value in its unit as written (``l = 15 cm``, not the
    SI number with the written unit), or its name, with its description."""
    tex = TexPrinter(system)
    items: list[list[Part]] = []
    for p in system.parameters:
        if p.value is not None:
            number = in_unit(p.value, p.unit)
            shown = decimal_text(number) if number.is_Rational else tex(number)
            item = [math(f"{p.latex} = {shown}{unit_tex(p.unit) if p.unit else ''}")]
            if p.description:
                item += rich(p.description, tex, " (", ")")
        else:
            item = [math(p.latex)]
            if p.description:
                item += rich(p.description, tex, ": ")
        items.append(item)
    return items


def coordinate_items(system: System) -> list[list[Part]]:
    """Each generalized coordinate with its description."""
    tex = TexPrinter(system)
    return [[math(c.latex)] + (rich(c.description, tex, ": ") if c.description else []) for c in system.coordinates]


def solution_view(d: Derivation, decimals: bool = False) -> dict[str, Any]:
    """The template context for a worked solution. With ``decimals`` (a tutorial sheet's variant, whose
    data are decimals like 1.5 kg and 0.6 m) every fraction of a number is printed as a decimal
    (83.39 q_1, not 16677 q_1/200); otherwise only long ones are (see :func:`tutgen.render.blocks.long_decimals`)."""
    s = d.system
    tex = TexPrinter(s)
    num = d.numeric
    if (decimals and s.values) or is_decimal_document(s):  # one style of numbers a document

        def num(expr: Any) -> Any:
            return all_decimals(d.numeric(expr))

    context = SolutionContext(d, tex, num)
    sections = [sec for build in SECTIONS if (sec := build(context)) is not None]
    given = given_items(s)
    coords = coordinate_items(s)

    return {
        "title": s.title,
        "statement": s.statement or "",
        "statement_parts": rich(s.statement or "", tex),
        "given": given,
        "coordinates": coords,
        "sections": sections,
        "figure": figure_view(s),  # tutgen/figure/view.py: the schematic (TikZ, SVG name) or the spec's picture
        # tutgen's own sentences, their ASCII maths (q_ddot, theta1, H = H^T) typeset
        "remarks": [engine_parts(r, tex) for r in d.remarks],
        "checks": [
            engine_parts(
                c.detail
                if c.detail.startswith("dimensions not checked")
                else f"{c.detail}: {'passed' if c.passed else 'FAILED'}",
                tex,
            )
            for c in d.checks
        ],
    }
