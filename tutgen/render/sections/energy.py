"""The energies: T per body and in all, U and the Lagrangian (T as 1/2 q_dot^T H q_dot when too long)."""

from __future__ import annotations

from typing import Any

from tutgen.engine.steps import StepKind
from tutgen.model.system import Ask
from tutgen.render import blocks as budgets  # PRINT_BUDGET, PROGRAM_BUDGET read when a section is built
from tutgen.render.blocks import (
    SolutionContext,
    boxed,
    display,
    long_decimals,
    ops,
    para,
    prose,
    said,
    section,
    tex_name,
)
from tutgen.spec.units import DIMENSIONS

ENERGY = DIMENSIONS["energy"]  # numeric energies carry J (TexPrinter.unit)


def energies(c: SolutionContext) -> dict[str, Any] | None:
    d, s, tex, num = c.d, c.s, c.tex, c.num
    if d.kinetic_energy is None or not d.has_step(StepKind.KINETIC_ENERGY):
        return None
    intro = (
        "The kinetic energy is given in the problem."
        if s.kinetic_energy is not None
        else "$T = \\sum \\tfrac12 m v_G^2 + \\tfrac12 \\omega^T J_G \\omega$ and "
        "$U = -\\sum m\\,\\mathbf g\\cdot\\mathbf r_G$ plus the springs."
    )
    sec = section("Energies", intro)
    blocks = sec["blocks"]
    t_size = ops(d.kinetic_energy)
    long_t = t_size > budgets.PRINT_BUDGET
    for e in d.energies:
        blocks.append(display(tex.equation(f"T_{{{tex_name(e.name)}}}", num(e.kinetic), dimension=ENERGY)))
    only_t = Ask.EQUATIONS_OF_MOTION not in s.ask and Ask.KINETIC_ENERGY in s.ask
    if long_t:
        blocks.append(display("T = \\tfrac12\\, \\dot q^T H(q)\\, \\dot q"))
        written = f"written out, $T$ has {said(t_size)} operations"
        blocks.append(para(prose(f"with $H$ of the matrix form below ({written}).")))
    else:
        blocks.append((boxed if only_t else display)(tex.equation("T", num(d.kinetic_energy), dimension=ENERGY)))
    if d.potential_energy is not None and d.has_step(StepKind.POTENTIAL_ENERGY):
        u = num(d.potential_energy)
        blocks.append(display(tex.equation("U", long_decimals(u) if long_t else u, dimension=ENERGY)))
    if d.lagrangian is not None and d.has_step(StepKind.LAGRANGIAN) and not long_t:
        blocks.append(display(tex.equation("L = T - U", num(d.lagrangian), dimension=ENERGY)))
    return sec
