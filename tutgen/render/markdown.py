"""Derivation -> Markdown worked solution. Views hold strings only; the template lays them out."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import sympy as sp

from tutgen.engine.derivation import Derivation
from tutgen.engine.newton_euler import PROJECTION_REMARK, NEMethod, NewtonEuler
from tutgen.model.system import Ask, Coordinate
from tutgen.render.latex import TexPrinter

_MD_SPECIALS = str.maketrans({c: "\\" + c for c in "\\`*_{}[]<>#|$"})


def md_escape(text: str) -> str:
    """User text in Markdown: no markup, no maths, no HTML from it."""
    return text.translate(_MD_SPECIALS)


@dataclass
class Section:
    title: str
    intro: str = ""
    lines: list[str] = field(default_factory=list)  # Markdown paragraphs; maths already in $$ blocks


def _chain(name: str, *forms: str) -> str:
    """name = form1 = form2, without repeating a form that prints the same."""
    shown: list[str] = []
    for f in forms:
        if f not in shown:
            shown.append(f)
    return " = ".join([name, *shown])


def _display(tex: str) -> str:
    return f"$$\n{tex}\n$$"


def solution_view(d: Derivation) -> dict[str, object]:
    """The template context for a worked solution."""
    s = d.system
    tex = TexPrinter(s)
    num = d.numeric
    sections: list[Section] = []

    given = []
    for p in s.parameters:
        if p.value is not None:
            unit = f"\\ \\mathrm{{{p.unit}}}" if p.unit else ""
            given.append(
                f"${p.latex} = {sp.latex(p.value)}{unit}$" + (f" ({md_escape(p.description)})" if p.description else "")
            )
        else:
            given.append(f"${p.latex}$" + (f": {md_escape(p.description)}" if p.description else ""))
    coords = [f"${c.latex}$" + (f": {md_escape(c.description)}" if c.description else "") for c in s.coordinates]

    if Ask.INERTIA in s.ask and d.inertia:
        sec = Section(
            "Mass properties",
            "Each part's inertia about its own centroid, then moved to the body "
            "frame's origin by the parallel-axis theorem $J_O = J_G + m(|d|^2 E - d d^T)$.",
        )
        for bi, principal in zip(d.inertia, d.principal, strict=True):
            if s.coordinates and all(p.shape.value == "point" for p in bi.parts) and len(bi.parts) <= 1:
                continue  # a lone point mass: its inertia is m r^2 in the energies, nothing to tabulate
            for p in bi.parts:
                lines = [f"**{md_escape(bi.name)} / {md_escape(p.name)}** ({p.shape.value.replace('_', ' ')})"]
                if p.volume is not None:
                    lines.append(_display(_chain("V", tex(p.volume), tex(sp.N(num(p.volume), 4)))))
                lines.append(_display(_chain("m", tex(p.mass), tex(sp.N(num(p.mass), 4)))))
                lines.append("About its centroid:")
                lines.append(_display(f"J_G = {tex(sp.N(num(p.inertia_centroid), 4))}"))
                if any(x != 0 for x in p.centroid):
                    lines.append(
                        f"Centroid at $d = {tex(num(p.centroid).T)}$; distances to the axes "
                        f"$({', '.join(tex(sp.N(num(x), 4)) for x in p.axis_distances)})$:"
                    )
                    lines.append(_display(f"J_O = {tex(sp.N(num(p.inertia_origin), 4))}"))
                sec.lines += lines
            sec.lines.append(f"**{md_escape(bi.name)}**, total mass and inertia about the origin:")
            sec.lines.append(
                _display(f"m = {tex(sp.N(num(bi.mass), 4))},\\quad J_O = {tex(sp.N(num(bi.inertia_origin), 4))}")
            )
            if principal is not None:
                sec.lines.append(
                    "Principal moments: " + ", ".join(f"${sp.latex(sp.Float(x, 4))}$" for x in principal.moments) + "."
                )
        if sec.lines:
            sections.append(sec)

    if d.kinematics and d.kinetic_energy is not None:
        sec = Section("Kinematics", "Position and velocity of each centre of mass, in world axes.")
        for k, e in zip(d.kinematics, d.energies, strict=True):
            sec.lines.append(
                _display(
                    f"\\mathbf r_{{\\mathrm{{{k.name}}}}} = {tex(num(k.com))},\\quad "
                    f"\\mathbf v_{{\\mathrm{{{k.name}}}}} = {tex(num(k.velocity))},\\quad "
                    f"v^2 = {tex(num(e.speed_squared))}"
                )
            )
        sections.append(sec)

    if d.kinetic_energy is not None and (Ask.KINETIC_ENERGY in s.ask or Ask.EQUATIONS_OF_MOTION in s.ask):
        intro = (
            "The kinetic energy is given in the problem."
            if s.kinetic_energy is not None
            else "$T = \\sum \\tfrac12 m v_G^2 + \\tfrac12 \\omega^T J_G \\omega$ and "
            "$U = -\\sum m\\,\\mathbf g\\cdot\\mathbf r_G$ plus the springs."
        )
        sec = Section("Energies", intro)
        for e in d.energies:
            sec.lines.append(_display(f"T_{{\\mathrm{{{e.name}}}}} = {tex(num(e.kinetic))}"))
        sec.lines.append(_display(f"T = {tex(num(d.kinetic_energy))}"))
        if d.potential_energy is not None and Ask.POTENTIAL_ENERGY in s.ask:
            sec.lines.append(_display(f"U = {tex(num(d.potential_energy))}"))
        if d.lagrangian is not None and Ask.LAGRANGIAN in s.ask:
            sec.lines.append(_display(f"L = T - U = {tex(num(d.lagrangian))}"))
        sections.append(sec)

    if d.lagrange_terms and Ask.LAGRANGE_EQUATIONS in s.ask and not (d.method == "newton-euler" and d.newton_euler):
        sec = Section(
            "Lagrange's equations",
            "For each coordinate, $\\frac{d}{dt}\\frac{\\partial L}{\\partial \\dot q_i} - "
            "\\frac{\\partial L}{\\partial q_i} = Q_i$.",
        )
        for t, c in zip(d.lagrange_terms, s.coordinates, strict=True):
            qd = tex(c.qd)
            sec.lines.append(f"Coordinate ${c.latex}$:")
            sec.lines.append(
                _display(
                    f"\\begin{{aligned}}\\frac{{\\partial L}}{{\\partial {qd}}} &= {tex(num(t.dL_dqd))}\\\\ "
                    f"\\frac{{d}}{{dt}}\\frac{{\\partial L}}{{\\partial {qd}}} &= {tex(num(t.ddt_dL_dqd))}\\\\ "
                    f"\\frac{{\\partial L}}{{\\partial {c.latex}}} &= {tex(num(t.dL_dq))}\\\\ "
                    f"Q_{{{c.latex}}} &= {tex(num(t.generalized_force))}\\end{{aligned}}"
                )
            )
        sections.append(sec)

    if d.equations_of_motion is not None and Ask.EQUATIONS_OF_MOTION in s.ask:
        sec = Section("Equations of motion")
        for eq, force in zip(d.equations_of_motion, d.generalized_forces, strict=True):
            lhs = num(eq + force)
            sec.lines.append(_display(f"\\boxed{{{tex(lhs)} = {tex(num(force))}}}"))
        sections.append(sec)

    if d.mass_matrix is not None and (Ask.MATRIX_FORM in s.ask or Ask.CHRISTOFFEL in s.ask):
        sec = Section(
            "Matrix form",
            "$H(q)\\ddot q + C(q,\\dot q) + G(q) = Q$, with $H$ read off "
            "$T = \\tfrac12 \\dot q^T H \\dot q$ and $G = \\partial U/\\partial q$.",
        )
        sec.lines.append(_display(f"H = {tex(num(d.mass_matrix))}"))
        if Ask.MATRIX_FORM in s.ask:
            sec.lines.append(
                _display(
                    f"C = {tex(num(d.coriolis_vector))},\\quad G = {tex(num(d.gravity_vector))},"
                    f"\\quad Q = {tex(num(d.generalized_forces))}"
                )
            )
        sections.append(sec)

    if d.christoffel and Ask.CHRISTOFFEL in s.ask:
        sec = Section(
            "Christoffel symbols",
            "In the tutorial's convention $h_{ijk} = \\partial H_{ij}/\\partial q_k - \\tfrac12 "
            "\\partial H_{jk}/\\partial q_i$, with $C_i = \\sum_{j,k} h_{ijk}\\dot q_j \\dot q_k$; "
            "the symmetric symbols of the first kind are $c_{ijk} = \\tfrac12(\\partial_k H_{ij} + "
            "\\partial_j H_{ik} - \\partial_i H_{jk})$.",
        )
        nonzero = [(k, v) for k, v in sorted(d.christoffel.items()) if v != 0]
        if nonzero:
            sec.lines.append(
                _display(",\\quad ".join(f"h_{{{i + 1}{j + 1}{k + 1}}} = {tex(num(v))}" for (i, j, k), v in nonzero))
            )
            sec.lines.append("All other $h_{ijk}$ are zero.")
            first = [(k, v) for k, v in sorted(d.christoffel_first_kind.items()) if v != 0]
            sec.lines.append(
                _display(",\\quad ".join(f"c_{{{i + 1}{j + 1}{k + 1}}} = {tex(num(v))}" for (i, j, k), v in first))
            )
        else:
            sec.lines.append("$H$ is constant, so every Christoffel symbol vanishes and $C = 0$.")
        sections.append(sec)

    if d.newton_euler is not None and Ask.EQUATIONS_OF_MOTION in s.ask:
        sections.append(_newton_euler_section(d.newton_euler, s.coordinates, tex, num))

    return {
        "title": md_escape(s.title),
        "statement": md_escape(s.statement) if s.statement else "",
        "given": given,
        "coordinates": coords,
        "sections": sections,
        "remarks": [md_escape(r) for r in d.remarks],
        "checks": [f"{md_escape(c.detail)}: {'passed' if c.passed else 'FAILED'}" for c in d.checks],
    }


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


def _tex_name(name: str) -> str:
    return "\\mathrm{" + name.replace("_", "\\_") + "}"


def _nonzero(v: sp.MatrixBase) -> bool:
    return any(e != 0 for e in v)


def _tex_label(name: str) -> str:
    """An applied load's name as a subscript: "load 'push'" -> \\text{push}."""
    label = name.replace("'", "").removeprefix("load ")
    return "\\text{" + label.replace("_", "\\_") + "}"


def _newton_euler_section(ne: NewtonEuler, coordinates: tuple[Coordinate, ...], tex: TexPrinter, num: Any) -> Section:
    """Per body: motion, applied and inertial terms, the two balances; then reactions, equations and
    the agreement with Lagrange's route."""
    for r in ne.reactions:
        for letter, unknown in (("R", r.unknown_force), ("N", r.unknown_moment)):
            for axis, sym in zip("xyz", unknown, strict=True):
                tex.names[sym] = f"{letter}_{{{_tex_name(r.joint)},{axis}}}"
    intro = _NE_INTRO[ne.method]
    if ne.method is not NEMethod.PROJECTION:
        intro += _NE_BALANCE
    sec = Section("Newton–Euler", intro)
    motions = {m.body: m for m in ne.motions}
    for b in ne.bodies:
        name = _tex_name(b.body)
        where = "$G$" if b.about == "G" else md_escape(b.about)
        sec.lines.append(f"**{md_escape(b.body)}** (moments about {where}):")
        m = motions.get(b.body)
        if m is not None:
            sec.lines.append(
                _display(
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
        sec.lines.append(_display(",\\quad ".join(terms)))
        if b.joint_in is None:  # no named reactions: what is left is balanced by the constraint forces
            sec.lines.append(
                _display(
                    f"\\textstyle\\sum \\mathbf F - m\\mathbf a_G = {tex(num(b.force_balance))} = -\\mathbf F_c,"
                    f"\\quad \\sum \\mathbf M_G - (I_G\\alpha + \\omega\\times I_G\\omega) = "
                    f"{tex(num(b.moment_balance))} = -\\mathbf M_c"
                )
            )
        else:
            sec.lines.append(
                _display(
                    f"\\textstyle\\sum \\mathbf F = {tex(num(b.force_balance))} = \\mathbf 0,\\quad "
                    f"\\sum \\mathbf M = {tex(num(b.moment_balance))} = \\mathbf 0"
                )
            )
    if ne.reactions:
        sec.lines.append("Joint reactions (parent on child, world components):")
        for r in ne.reactions:
            j = _tex_name(r.joint)
            sec.lines.append(
                _display(f"\\mathbf R_{{{j}}} = {tex(num(r.force))},\\quad \\mathbf N_{{{j}}} = {tex(num(r.moment))}")
            )
    sec.lines.append("The equation of each coordinate:")
    for e in ne.equations:
        if e.joint is not None:
            j = _tex_name(e.joint)
            kind = next(r.kind for r in ne.reactions if r.joint == e.joint)
            lhs = f"\\mathbf z_{{{j}}}\\cdot\\mathbf {'N' if kind.value == 'revolute' else 'R'}_{{{j}}}"
            for k in e.subtracted:
                lhs += f" - \\mathbf z_{{{j}}}\\cdot\\mathbf N_{{{_tex_name(k)}}}"
        else:
            qd = tex(next(c.qd for c in coordinates if c.name == e.coordinate))
            lhs = (
                f"\\textstyle\\sum_b \\big[(m\\mathbf a_G - \\mathbf F)\\cdot\\frac{{\\partial \\mathbf v}}"
                f"{{\\partial {qd}}} + (I_G\\alpha + \\omega\\times I_G\\omega - \\mathbf M)\\cdot"
                f"\\frac{{\\partial \\omega}}{{\\partial {qd}}}\\big]"
            )
        sec.lines.append(_display(f"{lhs} = {tex(num(e.projection))} = {tex(num(e.generalized_force))}"))
    sec.lines += [md_escape(r) for r in ne.remarks if r != PROJECTION_REMARK]  # the intro said it
    if ne.agrees_with_lagrange:
        sec.lines.append(md_escape(ne.agreement.detail) + ".")
    return sec


def render_markdown(d: Derivation, template_dir: Path | None = None) -> str:
    from tutgen.render.env import markdown_env

    return markdown_env(template_dir).get_template("solution.md.j2").render(**solution_view(d))
