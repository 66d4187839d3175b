"""The kinematics of each body: the position and velocity of its centre of mass, and v^2 worked out from
the squares of the velocity's components with the trigonometric identities used."""

from __future__ import annotations

from typing import Any

from tutgen.engine.kinematics import RULE_COS_DIFFERENCE, RULE_PYTHAGORAS, RULE_SIN_DIFFERENCE, BodyKinematics
from tutgen.render.blocks import Block, Part, SolutionContext, display, math, para, section, tex_name, text
from tutgen.render.layout import LINE_WIDTH_PT, tex_width

#: the widest squared component shown in the working of v^2 (the rest of its row is the relation)
SQUARE_WIDTH = 0.8 * LINE_WIDTH_PT

#: each identity's general form, as the solution names it
RULE_TEX = {
    RULE_PYTHAGORAS: "\\sin^2 A + \\cos^2 A = 1",
    RULE_COS_DIFFERENCE: "\\cos A\\cos B + \\sin A\\sin B = \\cos(A - B)",
    RULE_SIN_DIFFERENCE: "\\sin A\\cos B - \\cos A\\sin B = \\sin(A - B)",
}


def kinematics(c: SolutionContext) -> dict[str, Any] | None:
    d, tex, num = c.d, c.tex, c.num
    if not d.kinematics or d.kinetic_energy is None:
        return None
    sec = section(
        "Kinematics",
        "Position and velocity of each centre of mass, in world axes, and $v^2 = \\mathbf v\\cdot\\mathbf v$, "
        "the sum of the squares of the velocity's components.",
    )
    for k, e in zip(d.kinematics, d.energies, strict=True):
        name = tex_name(k.name)
        placed = f"\\mathbf r_{{{name}}} = {tex(num(k.com))},\\quad \\mathbf v_{{{name}}} = {tex(num(k.velocity))}"
        if k.speed is None or not k.speed.identities:  # v^2 needs no working: on the same line
            sec["blocks"].append(display(f"{placed},\\quad " + tex.equation(f"v_{{{name}}}^2", num(e.speed_squared))))
            continue
        sec["blocks"].append(display(placed))
        sec["blocks"] += _speed_blocks(c, k, name, num(e.speed_squared))
    return sec


def _speed_blocks(c: SolutionContext, k: BodyKinematics, name: str, final: Any) -> list[Block]:
    """``v^2 = v_x^2 + v_y^2 = (…)^2 + (…)^2 = …``, and the identities that shortened it (a body whose v^2
    needs none has it beside its velocity instead)."""
    tex, num = c.tex, c.num
    head = f"v_{{{name}}}^2"
    steps = k.speed
    if steps is None:
        return [display(tex.equation(head, final))]
    shown = [(axis, comp) for axis, comp in zip("xyz", steps.components, strict=True) if comp != 0]
    if not shown:
        return [display(f"{head} = 0")]
    forms = [" + ".join(f"v_{axis}^2" for axis, _ in shown)]
    squares = [f"\\left({tex(num(comp))}\\right)^2" for _, comp in shown]
    # a square is broken only between its terms' brackets, never inside: one too wide is left out
    if all(tex_width(sq) <= SQUARE_WIDTH for sq in squares):
        forms.append(" + ".join(squares))
    result = tex.ordered(num(steps.result))
    final_tex = tex.ordered(final)
    forms.append(result)
    if final_tex != result:
        forms.append(final_tex)
    out: list[Block] = [display(" = ".join([head, *forms]))]
    if steps.identities:
        out.append(para(_identity_parts(c, steps.identities)))
    return out


def _identity_parts(c: SolutionContext, identities: Any) -> list[Part]:
    """``using sin²θ₁ + cos²θ₁ = 1 and cosθ₁cos(θ₁+θ₂) + sinθ₁sin(θ₁+θ₂) = cosθ₂ (cos A cos B + …)``."""
    tex = c.tex
    parts: list[Part] = [text("using ")]
    for i, identity in enumerate(identities):
        if i:
            parts.append(text(" and " if i == len(identities) - 1 else ", "))
        parts.append(math(f"{tex(identity.lhs)} = {tex(identity.rhs)}"))
        if identity.rule != RULE_PYTHAGORAS:
            parts += [text(" ("), math(RULE_TEX[identity.rule]), text(")")]
    parts.append(text("."))
    return parts
