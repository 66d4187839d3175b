"""Lagrange's equations term by term, and the equations of motion they give."""

from __future__ import annotations

from typing import Any

from tutgen.engine.steps import StepKind
from tutgen.render import blocks as budgets  # PRINT_BUDGET, PROGRAM_BUDGET read when a section is built
from tutgen.render.blocks import SolutionContext, boxed, math, ops, para, said, section, stacked, text


def lagrange_equations(c: SolutionContext) -> dict[str, Any] | None:
    d, s, tex, num = c.d, c.s, c.tex, c.num
    if not d.lagrange_terms or not d.has_step(StepKind.LAGRANGE_EQUATIONS):
        return None
    sec = section(
        "Lagrange's equations",
        "For each coordinate, $\\frac{d}{dt}\\frac{\\partial L}{\\partial \\dot q_i} - "
        "\\frac{\\partial L}{\\partial q_i} = Q_i$.",
    )
    for t, q in zip(d.lagrange_terms, s.coordinates, strict=True):
        qd = tex(q.qd)
        sec["blocks"].append(para(text("Coordinate "), math(q.latex), text(":")))
        sec["blocks"].append(
            stacked(
                [
                    f"\\frac{{\\partial L}}{{\\partial {qd}}} = {tex(num(t.dL_dqd))}",
                    f"\\frac{{d}}{{dt}}\\frac{{\\partial L}}{{\\partial {qd}}} = {tex(num(t.ddt_dL_dqd))}",
                    f"\\frac{{\\partial L}}{{\\partial {q.latex}}} = {tex(num(t.dL_dq))}",
                    f"Q_{{{q.latex}}} = {tex(num(t.generalized_force))}",
                ]
            )
        )
    return sec


def equations_of_motion(c: SolutionContext) -> dict[str, Any] | None:
    d, s, tex, num = c.d, c.s, c.tex, c.num
    if d.equations_of_motion is None or not d.has_step(StepKind.EQUATIONS_OF_MOTION):
        return None
    eom_size = ops(d.equations_of_motion)
    if eom_size > budgets.PRINT_BUDGET:
        sec = section(
            "Equations of motion",
            f"Written out, the {len(s.coordinates)} equations have {said(eom_size)} operations: "
            "equation $i$ is row $i$ of the matrix form below,",
        )
        sec["blocks"].append(boxed("H(q)\\,\\ddot q + C(q,\\dot q) + G(q) = Q"))
        return sec
    if d.constraints is not None:  # the constraint forces A^T lambda stand with the inputs (issue 21)
        sec = section("Equations of motion", "With the constraint forces $A^T\\lambda$ (see the constraints below):")
        reactions = list(d.constraints.constraint_forces)
    else:
        sec = section("Equations of motion")
        reactions = [0] * len(s.coordinates)
    for eq, force, reaction in zip(d.equations_of_motion, d.generalized_forces, reactions, strict=True):
        lhs = num(eq + force)  # the equation's side without the inputs, which stand on the right
        sec["blocks"].append(boxed(f"{tex.ordered(lhs)} = {tex(num(force + reaction))}"))
    return sec
