"""Derivation -> Markdown worked solution. Views hold strings only; the template lays them out."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import sympy as sp

from tutgen.engine.derivation import Derivation
from tutgen.model.system import Ask
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

    if d.lagrange_terms and Ask.LAGRANGE_EQUATIONS in s.ask:
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

    return {
        "title": md_escape(s.title),
        "statement": md_escape(s.statement) if s.statement else "",
        "given": given,
        "coordinates": coords,
        "sections": sections,
        "remarks": [md_escape(r) for r in d.remarks],
        "checks": [f"{md_escape(c.detail)}: {'passed' if c.passed else 'FAILED'}" for c in d.checks],
    }


def render_markdown(d: Derivation, template_dir: Path | None = None) -> str:
    from tutgen.render.env import markdown_env

    return markdown_env(template_dir).get_template("solution.md.j2").render(**solution_view(d))
