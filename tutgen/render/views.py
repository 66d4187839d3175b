"""Derivation -> a format-neutral template context of plain data: the worked solution's sections in
teaching order, one per kind of step of ``Derivation.steps`` (:data:`BUILDERS`, one builder module each in
tutgen/render/sections/; a section exists only if its step does), with the problem's data, figure,
remarks and checks. The blocks and parts the context is made of are described in
tutgen/render/blocks.py.

``remarks`` and ``checks`` (tutgen's own sentences, maths typeset), ``section.intro``,
``statement_parts`` (the statement, its ``$…$`` maths typeset) and each item of ``given`` and of
``coordinates`` are lists of parts; ``statement`` is the raw text.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any

from tutgen.engine.derivation import Derivation
from tutgen.engine.remarks import REMARK_CONSTANT_MASS_MATRIX
from tutgen.engine.steps import StepKind
from tutgen.figure.view import figure_view
from tutgen.model.system import System
from tutgen.render.blocks import Part, SolutionContext, all_decimals, math, prose, rich, text, unit_tex
from tutgen.render.printer import TexPrinter, is_decimal_document
from tutgen.render.sections.arm import arm_table
from tutgen.render.sections.energy import energies
from tutgen.render.sections.inertia import mass_properties
from tutgen.render.sections.kinematics import kinematics
from tutgen.render.sections.lagrange import equations_of_motion, lagrange_equations
from tutgen.render.sections.matrix import christoffel_symbols, matrix_form
from tutgen.render.wording import engine_parts
from tutgen.spec.units import decimal_text, in_unit

__all__ = ["BUILDERS", "coordinate_items", "given_items", "prose", "rich", "sections", "solution_view"]

Builder = Callable[[SolutionContext], dict[str, Any] | None]


def _on_demand(module: str, name: str) -> Builder:
    """The builder ``name`` of ``tutgen.render.sections.<module>``, imported when a step of its kind is
    first rendered: the sections most specs do not have (Newton–Euler with its free-body diagrams and
    numpy, constraints, analysis, simulation, ...) stay out of a Markdown solution's start-up (issue 17)."""

    def build(context: SolutionContext) -> dict[str, Any] | None:
        section: Builder = getattr(importlib.import_module(f"tutgen.render.sections.{module}"), name)
        return section(context)

    build.__name__ = build.__qualname__ = name
    build.__doc__ = f"tutgen.render.sections.{module}.{name}, imported on first use."
    return build


equilibria = _on_demand("analysis", "equilibria")
linearization = _on_demand("analysis", "linearization")
constraint_kinematics = _on_demand("constraints", "constraint_kinematics")
multipliers = _on_demand("constraints", "multipliers")
reduced_equations = _on_demand("constraints", "reduced_equations")
momentum = _on_demand("momentum", "momentum")
newton_euler = _on_demand("newton_euler", "newton_euler")
drive_force = _on_demand("prescribed", "drive_force")
prescribed_motion = _on_demand("prescribed", "prescribed_motion")
simulation = _on_demand("simulation", "simulation")
steady_motion = _on_demand("steady", "steady_motion")

#: the section builders of each kind of step, in order; kinds that share a builder (T, U and L: the
#: energies) are one section, placed where the first of them is. Each returns its section, or None when
#: the derivation has nothing to show (a lone point mass has no inertia to tabulate, a system that is not
#: an `arm:` has no DH table). An arm's DH table follows its kinematics, or comes before H without them.
BUILDERS: dict[StepKind, tuple[Builder, ...]] = {
    StepKind.INERTIA: (mass_properties,),
    StepKind.KINEMATICS: (kinematics, arm_table),
    StepKind.KINETIC_ENERGY: (arm_table, energies),
    StepKind.POTENTIAL_ENERGY: (energies,),
    StepKind.LAGRANGIAN: (energies,),
    StepKind.LAGRANGE_EQUATIONS: (arm_table, lagrange_equations),
    StepKind.NEWTON_EULER: (newton_euler,),
    StepKind.EQUATIONS_OF_MOTION: (arm_table, equations_of_motion),
    StepKind.MASS_MATRIX: (arm_table, matrix_form),
    StepKind.MATRIX_FORM: (arm_table, matrix_form),
    StepKind.MASS_MATRIX_DERIVATIVES: (christoffel_symbols,),
    StepKind.CHRISTOFFEL: (christoffel_symbols,),
    StepKind.PRESCRIBED_MOTION: (prescribed_motion,),
    StepKind.DRIVE_FORCE: (drive_force,),
    StepKind.SIMULATION: (simulation,),
    StepKind.EQUILIBRIA: (equilibria,),
    StepKind.LINEARIZATION: (linearization,),
    StepKind.STEADY_MOTION: (steady_motion,),
    StepKind.MOMENTUM: (momentum,),
    StepKind.CONSTRAINTS: (constraint_kinematics,),
    StepKind.LAGRANGE_MULTIPLIERS: (multipliers,),
    StepKind.REDUCED_EQUATIONS: (reduced_equations,),
}


def sections(context: SolutionContext) -> list[dict[str, Any]]:
    """The sections of the worked solution: the derivation's steps in order, each kind by its builders,
    each builder once."""
    built: list[Builder] = []
    out: list[dict[str, Any]] = []
    for step in context.d.steps:
        for build in BUILDERS[step.kind]:
            if build in built:
                continue
            built.append(build)
            if (sec := build(context)) is not None:
                out.append(sec)
    return out


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
    items = []
    for c in system.coordinates:
        item = [math(c.latex)] + (rich(c.description, tex, ": ") if c.description else [])
        if c.prescribed is not None:  # a driven coordinate (docs/spec-format.md#prescribed)
            item += [text(" (prescribed: "), math(f"{c.latex} = {tex(c.prescribed)}"), text(")")]
        items.append(item)
    return items


def _said_in(d: Derivation) -> frozenset[str]:
    """The engine's remarks that a printed step already makes in its own words (the Christoffel
    section of a constant H says that every symbol vanishes): not said twice."""
    if any(step.kind is StepKind.CHRISTOFFEL for step in d.steps):
        return frozenset({REMARK_CONSTANT_MASS_MATRIX})
    return frozenset()


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
    parts = sections(context)
    given = given_items(s)
    coords = coordinate_items(s)

    return {
        "title": s.title,
        "statement": s.statement or "",
        "statement_parts": rich(s.statement or "", tex),
        "given": given,
        "coordinates": coords,
        "sections": parts,
        "figure": figure_view(s),  # tutgen/figure/view.py: the schematic (TikZ, SVG name) or the spec's picture
        # tutgen's own sentences, their ASCII maths (q_ddot, theta1, H = H^T) typeset
        "remarks": [engine_parts(r, tex) for r in d.remarks if r not in _said_in(d)],
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
