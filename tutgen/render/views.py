"""Derivation -> a format-neutral template context of plain data.

The context holds strings, lists and dicts only. Text is RAW (user or engine wording, not escaped);
maths is LaTeX in the safe subset that KaTeX, MathJax and GitHub all render (``aligned``, ``bmatrix``,
``\\boldsymbol``; no ``\\label``, no packages beyond amsmath). Each template escapes text with its own
filter (``md_escape`` or ``latex_escape``) and lays out the maths.

Blocks, the items of ``section.blocks``:

- ``{"kind": "text", "parts": [...]}``: a paragraph; each part is ``{"kind": "text", "text": ...}``
  (plain), ``{"kind": "strong", "text": ...}`` (bold) or ``{"kind": "math", "tex": ...}`` (inline maths);
- ``{"kind": "subheading", "text": ...}``: a short bold lead-in, e.g. a body's name;
- ``{"kind": "math", "tex": ..., "lines": [...], "rows": [...]}``: displayed maths; ``tex`` is the
  display on one line, ``lines`` are the equations of a list ``a = …,\\quad b = …`` one by one, and
  ``rows`` is empty when ``tex`` fits the line, else the rows of one alignment that the template sets
  in ``align*`` (LaTeX) or ``aligned`` (Markdown): each row has one ``&``, before its relation sign
  (the line breaking of tutgen.render.layout; nothing is ever scaled to fit);
- ``{"kind": "boxed", "tex": ..., "lines": [...], "rows": [...]}``: a displayed final answer, set
  apart (its rows are laid out a little narrower, for the box).

``remarks`` and ``checks`` (tutgen's own sentences, maths typeset), ``section.intro``,
``statement_parts`` (the statement, its ``$…$`` maths typeset) and each item of ``given`` and of
``coordinates`` are lists of parts as above; ``statement`` is the raw text.
"""

from __future__ import annotations

from typing import Any

import sympy as sp

from tutgen.engine.derivation import Derivation
from tutgen.engine.newton_euler import PROJECTION_REMARK, NEMethod, NewtonEuler
from tutgen.figure.view import figure_view
from tutgen.model.system import Ask, Coordinate, System
from tutgen.model.text import MathSpan, RichText
from tutgen.render.layout import BOXED_WIDTH_PT, LINE_WIDTH_PT, layout
from tutgen.render.printer import TexPrinter
from tutgen.render.size import count_ops_upto, nonzero_count, size_text
from tutgen.render.wording import engine_parts
from tutgen.spec.units import decimal_text, in_unit

Part = dict[str, str]
Block = dict[str, Any]


def text(s: str) -> Part:
    return {"kind": "text", "text": s}


def strong(s: str) -> Part:
    return {"kind": "strong", "text": s}


def math(tex: str) -> Part:
    return {"kind": "math", "tex": tex}


def prose(s: str) -> list[Part]:
    """Engine wording with inline maths between single dollars -> parts."""
    parts: list[Part] = []
    for i, piece in enumerate(s.split("$")):
        if piece:
            parts.append(math(piece) if i % 2 else text(piece))
    return parts


def rich(value: str, tex: TexPrinter, before: str = "", after: str = "") -> list[Part]:
    """A reader's text from the spec (a statement, a description) as parts: a :class:`RichText`'s
    ``$…$`` spans typeset by the results' printer, its text parts (and a plain ``str``) kept as text for
    the template to escape. ``before``/``after`` are wording of tutgen's own around it."""
    parts: list[Part] = [text(before)] if before else []
    for piece in value.parts if isinstance(value, RichText) else (value,):
        if isinstance(piece, MathSpan):
            span_tex = tex.with_names(_free_names(piece))
            printed = [span_tex(t) for t in piece.terms]
            chain = printed[0]
            for rel, term in zip(piece.relations, printed[1:], strict=True):
                chain += f" {_RELATION_TEX.get(rel, rel)} {term}"
            parts.append(math(chain))
        elif piece:
            parts.append(text(piece))
    if after:
        parts.append(text(after))
    merged: list[Part] = []
    for part in parts:  # neighbouring text parts as one
        if merged and part["kind"] == merged[-1]["kind"] == "text":
            merged[-1] = text(merged[-1]["text"] + part["text"])
        else:
            merged.append(part)
    return merged


_RELATION_TEX = {"!=": "\\ne", "<=": "\\le", ">=": "\\ge"}


def _free_names(span: MathSpan) -> dict[sp.Symbol, str]:
    """How the names a statement's maths uses without declaring them are typeset (``q_ddot`` -> q̈,
    ``T``, the function names of ``H(q)``): by the spec's rule for display names."""
    from sympy.core.function import AppliedUndef

    from tutgen.spec.names import default_latex

    names: dict[sp.Symbol, str] = {}
    for term in span.terms:
        if not isinstance(term, sp.Basic):  # a plain number
            continue
        for s in term.free_symbols:
            if isinstance(s, sp.Symbol):
                names[s] = default_latex(s.name)
        for f in term.atoms(AppliedUndef):
            names[sp.Symbol(f.func.__name__)] = default_latex(f.func.__name__)
    return names


def para(*parts: Part | list[Part]) -> Block:
    flat: list[Part] = []
    for p in parts:
        flat += p if isinstance(p, list) else [p]
    return {"kind": "text", "parts": flat}


def split_list(tex: str) -> list[str]:
    """The equations of a display written as a list ``a = 1,\\quad b = 2``, each on its own: a LaTeX
    template may set them on separate lines (Markdown shows ``tex`` as one line)."""
    lines: list[str] = []
    depth, start, sep = 0, 0, ",\\quad "
    i = 0
    while i < len(tex):
        ch = tex[i]
        if ch == "\\" and tex.startswith(sep[1:], i) and depth == 0 and i > 0 and tex[i - 1] == ",":
            lines.append(tex[start : i - 1])
            i += len(sep) - 1
            start = i
            continue
        if ch == "\\":
            i += 2
            continue
        depth += {"{": 1, "}": -1}.get(ch, 0)
        i += 1
    lines.append(tex[start:])
    return [ln.strip() for ln in lines]


def display(tex: str, kind: str = "math", stack: bool = False) -> Block:
    """A displayed formula (or a list of equations joined by ``,\\quad``), laid out to the line width;
    ``stack`` sets the equations one a line, relation signs aligned, even when they would fit on one."""
    lines = split_list(tex)
    width = BOXED_WIDTH_PT if kind == "boxed" else LINE_WIDTH_PT
    return {"kind": kind, "tex": tex, "lines": lines, "rows": layout(lines, width, stack=stack)}


def stacked(equations: list[str]) -> Block:
    """Equations one a line, their relation signs aligned (a derivation's steps, a program)."""
    return display(",\\quad ".join(equations), stack=True)


def boxed(tex: str) -> Block:
    return display(tex, "boxed")


def subheading(s: str) -> Block:
    return {"kind": "subheading", "text": s}


def section(title: str, intro: str = "") -> dict[str, Any]:
    return {"title": title, "intro": prose(intro), "blocks": []}


def _chain(name: str, *forms: str) -> str:
    """name = form1 = form2, without repeating a form that prints the same."""
    shown: list[str] = []
    for f in forms:
        if f not in shown and f != name:
            shown.append(f)
    return " = ".join([name, *shown]) if shown else ""


def _n(expr: Any) -> Any:
    """A number as a float (the printer rounds it to 4 significant figures); a formula that still has
    symbols stays exact, as a person writes it (m R^2/4, not 0.25 R^2 m)."""
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(_n)
    expr = sp.sympify(expr)
    return expr if expr.free_symbols else sp.N(expr)


def _unit(unit: str) -> str:
    return "\\ \\mathrm{" + unit.replace("_", "\\_").replace("%", "\\%").replace("*", "\\,") + "}"


#: results longer than this many operations (sympy.count_ops) are not printed whole in a worked
#: solution: T and L become 1/2 q_dot^T H q_dot, the equations of motion are the rows of the matrix
#: form, H, C and G are printed entry by entry, and the Christoffel symbols are left to the JSON output
#: (a fully symbolic 6-DOF arm has a million operations of them). Small problems are never affected.
PRINT_BUDGET = 4000
#: beyond this many operations even entry by entry is unreadable (the fully symbolic PUMA: 180 000);
#: a serial arm's H, C and G are then printed as the recursive program that computes them
PROGRAM_BUDGET = 40000


def _ops(*exprs: Any) -> int:
    return count_ops_upto(exprs, PROGRAM_BUDGET)  # exact up to PROGRAM_BUDGET, else PROGRAM_BUDGET + 1


def _said(ops: int) -> str:
    return size_text(ops, PROGRAM_BUDGET)  # a count of _ops in words: "10503", "more than 40000"


def given_items(system: System) -> list[list[Part]]:
    """The data of a problem: each parameter's value in its unit as written (``l = 15 cm``, not the
    SI number with the written unit), or its name, with its description."""
    tex = TexPrinter(system)
    items: list[list[Part]] = []
    for p in system.parameters:
        if p.value is not None:
            number = in_unit(p.value, p.unit)
            shown = decimal_text(number) if number.is_Rational else tex(number)
            item = [math(f"{p.latex} = {shown}{_unit(p.unit) if p.unit else ''}")]
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
    (83.39 q_1, not 16677 q_1/200); otherwise only long ones are (see :func:`_decimals`)."""
    s = d.system
    tex = TexPrinter(s)
    num = d.numeric
    if decimals and s.values:

        def num(expr: Any) -> Any:
            return _all_decimals(d.numeric(expr))

    sections: list[dict[str, Any]] = []

    given = given_items(s)
    coords = coordinate_items(s)

    if Ask.INERTIA in s.ask and d.inertia:
        sec = section(
            "Mass properties",
            "Each part's inertia about its own centroid, then moved to the body "
            "frame's origin by the parallel-axis theorem $J_O = J_G + m(|d|^2 E - d d^T)$.",
        )
        blocks = sec["blocks"]
        for bi, principal in zip(d.inertia, d.principal, strict=True):
            if s.coordinates and all(p.shape.value == "point" for p in bi.parts) and len(bi.parts) <= 1:
                continue  # a lone point mass: its inertia is m r^2 in the energies, nothing to tabulate
            for p in bi.parts:
                blocks.append(subheading(f"{bi.name} / {p.name} ({p.shape.value.replace('_', ' ')})"))
                chains = [_chain("m", tex(p.mass), tex(_n(num(p.mass))))]  # "m = m" says nothing: left out
                if p.volume is not None:
                    chains.insert(0, _chain("V", tex(p.volume), tex(_n(num(p.volume)))))
                blocks += [display(c) for c in chains if c]
                blocks.append(para(text("About its centroid:")))
                blocks.append(display(f"J_G = {tex(_n(num(p.inertia_centroid)))}"))
                if any(x != 0 for x in p.centroid):
                    blocks.append(
                        para(
                            text("Centroid at "),
                            math(f"d = {tex(_n(num(p.centroid).T))}"),
                            text("; distances to the axes "),
                            math(f"({', '.join(tex(_n(num(x))) for x in p.axis_distances)})"),
                            text(":"),
                        )
                    )
                    blocks.append(display(f"J_O = {tex(_n(num(p.inertia_origin)))}"))
            blocks.append(subheading(f"{bi.name}, total mass and inertia about the origin:"))
            total = [_chain("m", tex(_n(num(bi.mass)))), f"J_O = {tex(_n(num(bi.inertia_origin)))}"]
            blocks.append(boxed(",\\quad ".join(t for t in total if t)))
            if principal is not None:
                moments = ",\\ ".join(tex(sp.Float(x)) for x in principal.moments)
                blocks.append(para(text("Principal moments: "), math(moments), text(".")))
        if blocks:
            sections.append(sec)

    if d.kinematics and d.kinetic_energy is not None:
        sec = section("Kinematics", "Position and velocity of each centre of mass, in world axes.")
        for k, e in zip(d.kinematics, d.energies, strict=True):
            name = _tex_name(k.name)
            sec["blocks"].append(
                display(
                    f"\\mathbf r_{{{name}}} = {tex(num(k.com))},\\quad "
                    f"\\mathbf v_{{{name}}} = {tex(num(k.velocity))},\\quad "
                    + tex.equation("v^2", num(e.speed_squared))
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
        sec = section("Energies", intro)
        blocks = sec["blocks"]
        t_size = _ops(d.kinetic_energy)
        long_t = t_size > PRINT_BUDGET
        for e in d.energies:
            blocks.append(display(tex.equation(f"T_{{{_tex_name(e.name)}}}", num(e.kinetic))))
        only_t = Ask.EQUATIONS_OF_MOTION not in s.ask and Ask.KINETIC_ENERGY in s.ask
        if long_t:
            blocks.append(display("T = \\tfrac12\\, \\dot q^T H(q)\\, \\dot q"))
            written = f"written out, $T$ has {_said(t_size)} operations"
            blocks.append(para(prose(f"with $H$ of the matrix form below ({written}).")))
        else:
            blocks.append((boxed if only_t else display)(tex.equation("T", num(d.kinetic_energy))))
        if d.potential_energy is not None and Ask.POTENTIAL_ENERGY in s.ask:
            u = num(d.potential_energy)
            blocks.append(display(tex.equation("U", _decimals(u) if long_t else u)))
        if d.lagrangian is not None and Ask.LAGRANGIAN in s.ask and not long_t:
            blocks.append(display(tex.equation("L = T - U", num(d.lagrangian))))
        sections.append(sec)

    if d.lagrange_terms and Ask.LAGRANGE_EQUATIONS in s.ask and not (d.method == "newton-euler" and d.newton_euler):
        sec = section(
            "Lagrange's equations",
            "For each coordinate, $\\frac{d}{dt}\\frac{\\partial L}{\\partial \\dot q_i} - "
            "\\frac{\\partial L}{\\partial q_i} = Q_i$.",
        )
        for t, c in zip(d.lagrange_terms, s.coordinates, strict=True):
            qd = tex(c.qd)
            sec["blocks"].append(para(text("Coordinate "), math(c.latex), text(":")))
            sec["blocks"].append(
                stacked(
                    [
                        f"\\frac{{\\partial L}}{{\\partial {qd}}} = {tex(num(t.dL_dqd))}",
                        f"\\frac{{d}}{{dt}}\\frac{{\\partial L}}{{\\partial {qd}}} = {tex(num(t.ddt_dL_dqd))}",
                        f"\\frac{{\\partial L}}{{\\partial {c.latex}}} = {tex(num(t.dL_dq))}",
                        f"Q_{{{c.latex}}} = {tex(num(t.generalized_force))}",
                    ]
                )
            )
        sections.append(sec)

    eom_size = _ops(d.equations_of_motion) if d.equations_of_motion is not None else 0
    long_eom = eom_size > PRINT_BUDGET
    if d.equations_of_motion is not None and Ask.EQUATIONS_OF_MOTION in s.ask and long_eom:
        sec = section(
            "Equations of motion",
            f"Written out, the {len(s.coordinates)} equations have {_said(eom_size)} operations: "
            "equation $i$ is row $i$ of the matrix form below,",
        )
        sec["blocks"].append(boxed("H(q)\\,\\ddot q + C(q,\\dot q) + G(q) = Q"))
        sections.append(sec)
    elif d.equations_of_motion is not None and Ask.EQUATIONS_OF_MOTION in s.ask:
        sec = section("Equations of motion")
        for eq, force in zip(d.equations_of_motion, d.generalized_forces, strict=True):
            lhs = num(eq + force)  # the equation's side without the inputs, which stand on the right
            sec["blocks"].append(boxed(f"{tex.ordered(lhs)} = {tex(num(force))}"))
        sections.append(sec)

    if d.mass_matrix is not None and (Ask.MATRIX_FORM in s.ask or Ask.CHRISTOFFEL in s.ask):
        sec = section(
            "Matrix form",
            "$H(q)\\ddot q + C(q,\\dot q) + G(q) = Q$, with $H$ read off "
            "$T = \\tfrac12 \\dot q^T H \\dot q$ and $G = \\partial U/\\partial q$.",
        )
        size = _ops(d.mass_matrix, d.coriolis_vector, d.gravity_vector)
        if size > PROGRAM_BUDGET and d.program is not None and not s.springs:
            sec["blocks"] += _program_blocks(d, tex, num, size, Ask.MATRIX_FORM in s.ask)
        elif size > PRINT_BUDGET:
            sec["blocks"] += _entry_by_entry(d, tex, num, Ask.MATRIX_FORM in s.ask)
        else:
            sec["blocks"].append(display(f"H = {tex(num(d.mass_matrix))}"))
        if Ask.MATRIX_FORM in s.ask and size <= PRINT_BUDGET:
            sec["blocks"].append(
                display(
                    f"C = {tex(num(d.coriolis_vector))},\\quad G = {tex(num(d.gravity_vector))},"
                    f"\\quad Q = {tex(num(d.generalized_forces))}"
                )
            )
        sections.append(sec)

    if Ask.CHRISTOFFEL in s.ask and d.christoffel:  # asked first: a large arm's are computed on reading
        sec = section(
            "Christoffel symbols",
            "In the tutorial's convention $h_{ijk} = \\partial H_{ij}/\\partial q_k - \\tfrac12 "
            "\\partial H_{jk}/\\partial q_i$, with $C_i = \\sum_{j,k} h_{ijk}\\dot q_j \\dot q_k$; "
            "the symmetric symbols of the first kind are $c_{ijk} = \\tfrac12(\\partial_k H_{ij} + "
            "\\partial_j H_{ik} - \\partial_i H_{jk})$.",
        )
        blocks = sec["blocks"]
        size = _ops(d.christoffel)  # a large arm's table is sized without converting it
        nonzero = [] if size > PRINT_BUDGET else [(k, v) for k, v in sorted(d.christoffel.items()) if v != 0]
        if size > PRINT_BUDGET:
            blocks.append(
                para(
                    prose(
                        f"{nonzero_count(d.christoffel)} of the {len(d.christoffel)} symbols $h_{{ijk}}$ are nonzero; "
                        "together they "
                        f"have {_said(size)} operations, too many to print here. They are in the JSON output "
                        "(tutgen solve --format json, under christoffel), and $C$ above is their contraction."
                    )
                )
            )
        elif nonzero:
            blocks.append(
                display(",\\quad ".join(f"h_{{{i + 1}{j + 1}{k + 1}}} = {tex(num(v))}" for (i, j, k), v in nonzero))
            )
            blocks.append(para(prose("All other $h_{ijk}$ are zero.")))
            first = [(k, v) for k, v in sorted(d.christoffel_first_kind.items()) if v != 0]
            blocks.append(
                display(",\\quad ".join(f"c_{{{i + 1}{j + 1}{k + 1}}} = {tex(num(v))}" for (i, j, k), v in first))
            )
        else:
            blocks.append(para(prose("$H$ is constant, so every Christoffel symbol vanishes and $C = 0$.")))
        sections.append(sec)

    if d.newton_euler is not None and Ask.EQUATIONS_OF_MOTION in s.ask:
        sections.append(_newton_euler_section(d.newton_euler, s.coordinates, tex, num))

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


def _newton_euler_section(
    ne: NewtonEuler, coordinates: tuple[Coordinate, ...], tex: TexPrinter, num: Any
) -> dict[str, Any]:
    """Per body: motion, applied and inertial terms, the two balances; then reactions, equations and
    the agreement with Lagrange's route."""
    for r in ne.reactions:
        for letter, unknown in (("R", r.unknown_force), ("N", r.unknown_moment)):
            for axis, sym in zip("xyz", unknown, strict=True):
                tex.names[sym] = f"{letter}_{{{_tex_name(r.joint)},{axis}}}"
    intro = _NE_INTRO[ne.method]
    if ne.method is not NEMethod.PROJECTION:
        intro += _NE_BALANCE
    sec = section("Newton–Euler", intro)
    blocks = sec["blocks"]
    motions = {m.body: m for m in ne.motions}
    for b in ne.bodies:
        name = _tex_name(b.body)
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
            j = _tex_name(r.joint)
            blocks.append(
                display(f"\\mathbf R_{{{j}}} = {tex(num(r.force))},\\quad \\mathbf N_{{{j}}} = {tex(num(r.moment))}")
            )
    blocks.append(para(text("The equation of each coordinate:")))
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
                f"{{\\textstyle\\sum_b}} \\big[(m\\mathbf a_G - \\mathbf F)\\cdot\\frac{{\\partial \\mathbf v}}"
                f"{{\\partial {qd}}} + (I_G\\alpha + \\omega\\times I_G\\omega - \\mathbf M)\\cdot"
                f"\\frac{{\\partial \\omega}}{{\\partial {qd}}}\\big]"
            )
        blocks.append(display(f"{lhs} = {tex(num(e.projection))} = {tex(num(e.generalized_force))}"))
    blocks += [para(engine_parts(r, tex)) for r in ne.remarks if r != PROJECTION_REMARK]  # the intro said it
    if ne.agrees_with_lagrange:
        blocks.append(para(engine_parts(ne.agreement.detail + ".", tex)))
    return sec


def _decimals(expr: Any) -> Any:
    """Long exact fractions (measured data: 192438147/500000000) as decimals, which the printer rounds
    to 4 significant figures; for results printed entry by entry, where exact fractions swamp the page."""
    if not isinstance(expr, sp.Basic):
        return expr
    return expr.xreplace({r: sp.Float(r, 15) for r in expr.atoms(sp.Rational) if r.q > 100})


def _all_decimals(expr: Any) -> Any:
    """Every non-integer rational of an expression as a decimal (printed to 4 significant figures)."""
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(_all_decimals)
    if not isinstance(expr, sp.Basic):
        return expr
    return expr.xreplace({r: sp.Float(r, 15) for r in expr.atoms(sp.Rational) if r.q != 1})


def _entry_by_entry(d: Derivation, tex: TexPrinter, numeric: Any, with_c_g: bool) -> list[Block]:
    """H (upper triangle; H is symmetric), C and G one entry per display, for results too long for a
    matrix on a page."""

    def num(e: Any) -> Any:
        return _decimals(numeric(e))

    n = d.mass_matrix.shape[0]
    blocks: list[Block] = [para(prose("$H$ is symmetric, $H_{ji} = H_{ij}$; its entries on and above the diagonal:"))]
    for i in range(n):
        for j in range(i, n):
            blocks.append(display(tex.equation(f"H_{{{i + 1}{j + 1}}}", num(d.mass_matrix[i, j]))))
    if with_c_g:
        for name, vec in (("C", d.coriolis_vector), ("G", d.gravity_vector), ("Q", d.generalized_forces)):
            for i in range(n):
                blocks.append(display(tex.equation(f"{name}_{{{i + 1}}}", num(vec[i]))))
    return blocks


def _program_blocks(d: Derivation, tex: TexPrinter, numeric: Any, size: int, with_c_g: bool) -> list[Block]:
    """H, C and G of a serial arm as the straight-line program of tutgen.engine.recursive: the
    intermediate quantities x_k of a recursive Newton-Euler pass (C q_dot with q_ddot = 0 and no gravity,
    G with the arm at rest) and of the composite-rigid-body algorithm (H), in evaluation order."""
    program = d.program
    assert program is not None

    def num(e: Any) -> Any:
        return _decimals(numeric(e))

    n = len(d.system.coordinates)
    outputs = (
        (program.mass_matrix, program.coriolis_vector, program.gravity_vector) if with_c_g else (program.mass_matrix,)
    )
    needed = program.needed(*outputs)
    blocks: list[Block] = [
        para(
            prose(
                f"Written out, the entries of $H$, $C$ and $G$ have {_said(size)} operations. They are computed here "
                f"by the recursion that defines them instead: {len(needed)} intermediate quantities $x_k$, "
                "each from earlier ones (a recursive Newton-Euler pass in the link frames gives $C$ with "
                "$\\ddot q = 0$ and no gravity, and $G$ with the arm at rest; the composite-rigid-body "
                "algorithm gives $H$). The JSON output has the entries written out."
            )
        )
    ]
    # one alignment each (align* breaks across pages between its rows, under \\allowdisplaybreaks)
    blocks.append(stacked([f"{tex(x)} = {tex(num(e))}" for x, e in needed]))
    blocks.append(para(prose("$H$ is symmetric, $H_{ji} = H_{ij}$; its entries on and above the diagonal:")))
    blocks.append(
        stacked(
            [f"H_{{{i + 1}{j + 1}}} = {tex(num(program.mass_matrix[i, j]))}" for i in range(n) for j in range(i, n)]
        )
    )
    if with_c_g:
        lines = [f"C_{{{i + 1}}} = {tex(num(program.coriolis_vector[i]))}" for i in range(n)]
        lines += [f"G_{{{i + 1}}} = {tex(num(program.gravity_vector[i]))}" for i in range(n)]
        lines += [f"Q_{{{i + 1}}} = {tex(num(d.generalized_forces[i]))}" for i in range(n)]
        blocks.append(stacked(lines))
    return blocks
