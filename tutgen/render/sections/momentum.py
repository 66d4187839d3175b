"""Issue 18's momentum section: each body's p, H_G (world and body axes) and H_O, the totals, dH_O/dt and
the moment the supports provide (steadily running, every q_ddot = 0), and the conserved quantities.
The values are the engine's (tutgen/engine/analysis/momentum.py)."""

from __future__ import annotations

from typing import Any

import sympy as sp

from tutgen.engine.steps import StepKind
from tutgen.render.blocks import SolutionContext, boxed, display, math, para, section, subheading, text
from tutgen.render.wording import engine_parts

__all__ = ["momentum"]


def _numbers(c: SolutionContext) -> Any:
    """The section's ``num``: the parameters' values, and functions of numbers (sin(pi/18) of a tilt of
    10 degrees) as decimals, as a reader writes them."""

    def num(expr: Any) -> Any:
        value = c.num(expr)
        if not isinstance(value, sp.Basic):
            return value
        return value.xreplace({f: sp.Float(sp.N(f, 15)) for f in value.atoms(sp.Function) if f.is_number})

    return num


def momentum(c: SolutionContext) -> dict[str, Any] | None:
    d, tex = c.d, c.tex
    num = _numbers(c)
    a = d.analysis
    if a is None or a.momentum is None or not d.has_step(StepKind.MOMENTUM):
        return None
    mo = a.momentum
    sec = section(
        "Momentum",
        "Each body's momentum $p = m v_G$, its angular momentum about its centre of mass "
        "$H_G = R J_G R^T \\omega$ (in body axes $J_G \\omega_{body}$), and about the fixed origin O, "
        "$H_O = r_G \\times m v_G + H_G$.",
    )
    for b in mo.bodies:
        sec["blocks"].append(subheading(b.name))
        sec["blocks"].append(
            display(
                f"p = {tex(num(b.linear))},\\quad H_G = {tex(num(b.angular_com))},\\quad "
                f"H_G^{{body}} = {tex(num(b.angular_com_body))},\\quad H_O = {tex(num(b.angular_origin))}"
            )
        )
    if len(mo.bodies) > 1:
        sec["blocks"].append(para(text("In total:")))
        sec["blocks"].append(display(f"p = {tex(num(mo.linear))},\\quad H_O = {tex(num(mo.angular_origin))}"))
    sec["blocks"].append(
        para(
            text("The rate of change of "),
            math("H_O"),
            text(" is the moment of every external force about O; gravity gives "),
            math("\\sum r_G \\times m g"),
            text(", so the supports (and the applied loads) provide the rest:"),
        )
    )
    sec["blocks"].append(display(f"\\frac{{dH_O}}{{dt}} = {tex(num(mo.angular_rate))}"))
    sec["blocks"].append(display(f"M_O = \\frac{{dH_O}}{{dt}} - \\sum r_G \\times m g = {tex(num(mo.support_moment))}"))
    if mo.steady_support_moment != mo.support_moment:
        sec["blocks"].append(para(text("Running steadily (every "), math("\\ddot q = 0"), text("):")))
        sec["blocks"].append(boxed(f"M_O = {tex(num(mo.steady_support_moment))}"))
    if mo.conserved:
        sec["blocks"].append(para(text("Conserved quantities:")))
        for q in mo.conserved:
            name = (
                "E" if q.name == "E" else f"p_{{{next(x.latex for x in c.s.coordinates if q.name == 'p_' + x.name)}}}"
            )
            sec["blocks"].append(display(f"{name} = {tex(num(q.value))} = \\text{{const}}"))
            sec["blocks"].append(para(*engine_parts(f"{q.why}.", tex)))
    else:
        sec["blocks"].append(
            para(
                text("Nothing here is conserved: no coordinate is cyclic with "),
                math("Q = 0"),
                text(", and not every force is conservative."),
            )
        )
    return sec
