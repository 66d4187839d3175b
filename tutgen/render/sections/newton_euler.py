"""Newton–Euler: per body its motion, applied and inertial terms and balances, the joint reactions and
the equation of each coordinate, checked against Lagrange's."""

from __future__ import annotations

from typing import Any

import sympy as sp

from tutgen.engine.newton_euler import PROJECTION_REMARK, NEMethod, NewtonEuler
from tutgen.model.system import Ask, Coordinate
from tutgen.render.blocks import SolutionContext, display, math, para, section, strong, tex_name, text
from tutgen.render.printer import TexPrinter
from tutgen.render.wording import engine_parts


def newton_euler(c: SolutionContext) -> dict[str, Any] | None:
    d, s = c.d, c.s
    if d.newton_euler is None or Ask.EQUATIONS_OF_MOTION not in s.ask:
        return None
    return newton_euler_section(d.newton_euler, s.coordinates, c.tex, c.num)


_NE_INTRO = {
    NEMethod.RECURSIVE: (
        "Newton–Euler, recursively. Outward from the ground, link by link: "
        "$\\omega_c = \\omega_p + z\\,\\dot q$, "
        "$\\alpha_c = \\alpha_p + z\\,\\ddot q + \\omega_p \\times z\\,\\dot q$ for a revolute joint "
        "(a prismatic one adds $z\\,\\ddot q + 2\\omega_p \\times z\\,\\dot q$ to the acceleration of the "
        "origin), and $\\mathbf a_G = \\mathbf a_O + \\alpha \\times \\rho + \\omega \\times (\\omega \\times \\rho)$. "
    ),
    NEMethod.PER_BODY: (
        "Newton–Euler, one free body at a time, with $\\mathbf a_G$ and $\\alpha$ from differentiating "
        "$\\mathbf v_G$ and $\\omega$. "
    ),
    NEMethod.PROJECTION: (
        "Newton–Euler without joints: the bodies are placed by positions and orientations, so the constraint "
        "forces are not named. Each body's D'Alembert force and couple, with the applied forces, are projected "
        "onto the partial velocities $\\partial \\mathbf v_G/\\partial \\dot q_i$ and "
        "$\\partial \\omega/\\partial \\dot q_i$ (virtual work, Kane's method); the constraint forces "
        "$\\mathbf F_c$, $\\mathbf M_c$ do no work and drop out."
    ),
}
_NE_BALANCE = (
    "Each body is in equilibrium under its applied forces, the joint reactions and D'Alembert's inertial "
    "force $-m\\mathbf a_G$ and couple $-(I_G\\alpha + \\omega \\times I_G\\omega)$; "
    "$\\mathbf R_j$, $\\mathbf N_j$ are the force and the moment (about the joint's origin) that the parent "
    "exerts on the child at joint $j$. Solved from the tips inward, the reactions' components along the "
    "joint axes are the equations of motion."
)


def _nonzero(v: sp.MatrixBase) -> bool:
    return any(e != 0 for e in v)


def _tex_label(name: str) -> str:
    """An applied load's name as a subscript: "load 'push'" -> \\text{push}."""
    label = name.replace("'", "").removeprefix("load ")
    return "\\text{" + label.replace("_", "\\_") + "}"


def newton_euler_section(
    ne: NewtonEuler, coordinates: tuple[Coordinate, ...], tex: TexPrinter, num: Any
) -> dict[str, Any]:
    """Per body: motion, applied and inertial terms, the two balances; then reactions, equations and
    the agreement with Lagrange's route."""
    for r in ne.reactions:
        for letter, unknown in (("R", r.unknown_force), ("N", r.unknown_moment)):
            for axis, sym in zip("xyz", unknown, strict=True):
                tex.names[sym] = f"{letter}_{{{tex_name(r.joint)},{axis}}}"
    intro = _NE_INTRO[ne.method]
    if ne.method is not NEMethod.PROJECTION:
        intro += _NE_BALANCE
    sec = section("Newton–Euler", intro)
    blocks = sec["blocks"]
    motions = {m.body: m for m in ne.motions}
    for b in ne.bodies:
        name = tex_name(b.body)
        blocks.append(
            para(
                strong(b.body),
                text(" (moments about "),
                math("G") if b.about == "G" else text(b.about),
                text("):"),
            )
        )
        m = motions.get(b.body)
        if m is not None:
            blocks.append(
                display(
                    f"\\omega_{{{name}}} = {tex(num(m.angular_velocity))},\\quad "
                    f"\\alpha_{{{name}}} = {tex(num(m.angular_acceleration))},\\quad "
                    f"\\mathbf a_{{G,{name}}} = {tex(num(m.acceleration))}"
                )
            )
        terms = [f"\\mathbf F_{{{_tex_label(ld.name)}}} = {tex(num(ld.force))}" for ld in b.loads if _nonzero(ld.force)]
        terms += [
            f"\\boldsymbol\\tau_{{{_tex_label(ld.name)}}} = {tex(num(ld.torque))}"
            for ld in b.loads
            if _nonzero(ld.torque)
        ]
        terms.append(f"-m\\mathbf a_G = {tex(num(b.inertial_force))}")
        if _nonzero(b.inertial_moment):
            terms.append(f"-(I_G\\alpha + \\omega\\times I_G\\omega) = {tex(num(b.inertial_moment))}")
        blocks.append(display(",\\quad ".join(terms)))
        if b.joint_in is None:  # no named reactions: what is left is balanced by the constraint forces
            blocks.append(
                display(
                    f"{{\\textstyle\\sum}} \\mathbf F - m\\mathbf a_G = {tex(num(b.force_balance))} = -\\mathbf F_c,"
                    f"\\quad {{\\textstyle\\sum}} \\mathbf M_G - (I_G\\alpha + \\omega\\times I_G\\omega) = "
                    f"{tex(num(b.moment_balance))} = -\\mathbf M_c"
                )
            )
        else:
            blocks.append(
                display(
                    f"{{\\textstyle\\sum}} \\mathbf F = {tex(num(b.force_balance))} = \\mathbf 0,\\quad "
                    f"{{\\textstyle\\sum}} \\mathbf M = {tex(num(b.moment_balance))} = \\mathbf 0"
                )
            )
    if ne.reactions:
        blocks.append(para(text("Joint reactions (parent on child, world components):")))
        for r in ne.reactions:
            j = tex_name(r.joint)
            blocks.append(
                display(f"\\mathbf R_{{{j}}} = {tex(num(r.force))},\\quad \\mathbf N_{{{j}}} = {tex(num(r.moment))}")
            )
    blocks.append(para(text("The equation of each coordinate:")))
    for e in ne.equations:
        if e.joint is not None:
            j = tex_name(e.joint)
            kind = next(r.kind for r in ne.reactions if r.joint == e.joint)
            lhs = f"\\mathbf z_{{{j}}}\\cdot\\mathbf {'N' if kind.value == 'revolute' else 'R'}_{{{j}}}"
            for k in e.subtracted:
                lhs += f" - \\mathbf z_{{{j}}}\\cdot\\mathbf N_{{{tex_name(k)}}}"
        else:
            qd = tex(next(c.qd for c in coordinates if c.name == e.coordinate))
            lhs = (
                f"{{\\textstyle\\sum_b}} \\big[(m\\mathbf a_G - \\mathbf F)\\cdot\\frac{{\\partial \\mathbf v}}"
                f"{{\\partial {qd}}} + (I_G\\alpha + \\omega\\times I_G\\omega - \\mathbf M)\\cdot"
                f"\\frac{{\\partial \\omega}}{{\\partial {qd}}}\\big]"
            )
        blocks.append(display(f"{lhs} = {tex(num(e.projection))} = {tex(num(e.generalized_force))}"))
    blocks += [para(engine_parts(r, tex)) for r in ne.remarks if r != PROJECTION_REMARK]  # the intro said it
    if ne.agrees_with_lagrange:
        blocks.append(para(engine_parts(ne.agreement.detail + ".", tex)))
    return sec
