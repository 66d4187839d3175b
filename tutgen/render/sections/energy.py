"""The energies: T per body (its translation and its rotation), U source by source with the datum of each
(where it is zero), their totals and the Lagrangian (T as 1/2 q_dot^T H q_dot when too long)."""

from __future__ import annotations

from typing import Any

import sympy as sp

from tutgen.engine.steps import StepKind
from tutgen.model.system import Ask
from tutgen.render import blocks as budgets  # PRINT_BUDGET, PROGRAM_BUDGET read when a section is built
from tutgen.render.blocks import (
    Block,
    Part,
    SolutionContext,
    boxed,
    display,
    long_decimals,
    math,
    ops,
    para,
    prose,
    said,
    section,
    stacked,
    tex_name,
    text,
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
    parts = {bi.name: len(bi.parts) for bi in d.inertia}
    for e in d.energies:
        blocks.append(display(_body_kinetic(c, e, parts.get(e.name, 1))))
    only_t = Ask.EQUATIONS_OF_MOTION not in s.ask and Ask.KINETIC_ENERGY in s.ask
    if long_t:
        blocks.append(display("T = \\tfrac12\\, \\dot q^T H(q)\\, \\dot q"))
        written = f"written out, $T$ has {said(t_size)} operations"
        blocks.append(para(prose(f"with $H$ of the matrix form below ({written}).")))
    else:
        blocks.append((boxed if only_t else display)(tex.equation("T", num(d.kinetic_energy), dimension=ENERGY)))
    if d.potential_energy is not None and d.has_step(StepKind.POTENTIAL_ENERGY):
        u = num(d.potential_energy)
        blocks += _potential_sources(c, long_t)
        blocks.append(display(tex.equation("U", long_decimals(u) if long_t else u, dimension=ENERGY)))
    if d.lagrangian is not None and d.has_step(StepKind.LAGRANGIAN) and not long_t:
        blocks.append(display(tex.equation("L = T - U", num(d.lagrangian), dimension=ENERGY)))
    return sec


def _body_kinetic(c: SolutionContext, e: Any, parts: int) -> str:
    """``T_b = ½ m v_G² + ½ ωᵀJ_Gω = (translation) + (rotation) = T_b``; a body that does not turn (or
    has no inertia of its own) is its translation alone."""
    tex, num = c.tex, c.num
    name = f"T_{{{tex_name(e.name)}}}"
    trans, rot = num(e.translational), num(e.rotational)
    if rot == 0 or trans == 0:
        return tex.equation(name, num(e.kinetic))
    if parts > 1:
        rule = "\\sum_p \\tfrac12 m_p v_p^2 + \\tfrac12 \\omega^T \\big(\\textstyle\\sum_p J_p\\big) \\omega"
    else:
        rule = "\\tfrac12 m v_G^2 + \\tfrac12 \\omega^T J_G \\omega"
    return f"{name} = {rule} = {tex.ordered(trans)} + {tex.ordered(rot)} = {tex.ordered(num(e.kinetic))}"


def _potential_sources(c: SolutionContext, long_t: bool) -> list[Block]:
    """Each term of U with its datum: the bodies' gravity (one datum for all), each spring, or a given U.
    Nothing when U has a single term that the total already shows with nothing to add."""
    d, tex, num = c.d, c.tex, c.num
    sources = d.potential_sources
    if not sources:
        return []

    def shown(expr: sp.Expr) -> sp.Expr:
        value = num(expr)
        return long_decimals(value) if long_t else value

    out: list[Block] = []
    gravity = [src for src in sources if src.kind == "gravity"]
    if gravity:
        out.append(
            para(
                text("Gravity, "),
                math("U_b = -m_b\\,\\mathbf g\\cdot\\mathbf r_{G,b}"),
                text(", "),
                *_datum(c, gravity[0]),
                text(":"),
            )
        )
        lines = [tex.equation(f"U_{{{tex_name(src.name)}}}", shown(src.energy)) for src in gravity]
        out.append(stacked(lines) if len(lines) > 1 else display(lines[0]))
    for src in sources:
        if src.kind == "spring":
            out.append(
                para(
                    text(f"Spring '{src.name}', "),
                    math("U = \\tfrac12 k\\,(L - L_0)^2"),
                    text(", "),
                    *_datum(c, src),
                    text(":"),
                )
            )
            out.append(display(tex.equation(f"U_{{{tex_name(src.name)}}}", shown(src.energy))))
        elif src.kind == "given":
            out.append(para(text("The potential energy is given in the problem.")))
    return out


def _datum(c: SolutionContext, src: Any) -> list[Part]:
    """``zero at $y = 0$, the level of joint 'pivot'`` as parts."""
    if src.zero_at is None:
        return [text(src.note)]
    lhs, rhs = src.zero_at
    out = [text("zero at "), math(f"{c.tex(lhs)} = {c.tex(rhs)}")]
    if src.note:
        out.append(text(f", {src.note}"))
    return out
