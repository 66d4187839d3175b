"""Newton–Euler: per body its motion, applied and inertial terms and balances, the joint reactions and
the equation of each coordinate, checked against Lagrange's."""

from __future__ import annotations

from typing import Any

import sympy as sp

from tutgen.engine.derivation import Derivation
from tutgen.engine.ne_types import (
    PROJECTION_REMARK,
    EliminationStep,
    ForceKind,
    NEMethod,
    NewtonEuler,
    PlanarBalance,
    PlanarForce,
    PlanarNewtonEuler,
)
from tutgen.figure.freebody import BodyForce, Frame
from tutgen.memo import ByIdentity
from tutgen.model.system import Ask, Coordinate, JointKind
from tutgen.render.blocks import (
    SolutionContext,
    display,
    math,
    para,
    section,
    stacked,
    strong,
    tex_name,
    text,
)
from tutgen.render.printer import TexPrinter
from tutgen.render.wording import engine_parts


def newton_euler(c: SolutionContext) -> dict[str, Any] | None:
    d, s = c.d, c.s
    if d.newton_euler is None or Ask.EQUATIONS_OF_MOTION not in s.ask:
        return None
    if d.newton_euler.planar is not None:
        diagrams = {v["body"]: v for v in free_bodies(d)}
        return planar_section(d.newton_euler, d.newton_euler.planar, s.coordinates, c.tex, c.num, diagrams)
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
_NE_CONSTRAINED = (
    " The spec's constraints are not built into the placement: their forces do work in a change of one "
    "coordinate alone and enter through their multipliers."
)
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
    tex.name(
        {
            sym: f"{letter}_{{{tex_name(r.joint)},{axis}}}"
            for r in ne.reactions
            for letter, unknown in (("R", r.unknown_force), ("N", r.unknown_moment))
            for axis, sym in zip("xyz", unknown, strict=True)
        }
    )
    intro = _NE_INTRO[ne.method]
    if ne.method is not NEMethod.PROJECTION:
        intro += _NE_BALANCE
    elif ne.constraint_reactions:
        intro += _NE_CONSTRAINED
    sec = section("Newton–Euler", intro)
    blocks = sec["blocks"]
    blocks += constraint_reaction_blocks(ne, coordinates, tex, num)
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
        if m is not None:  # each link's motion stated once; zero vectors and components left out
            motion = [
                f"{sym} = {_ijk(tex, num(v))}"
                for sym, v in (
                    (f"\\omega_{{{name}}}", m.angular_velocity),
                    (f"\\alpha_{{{name}}}", m.angular_acceleration),
                    (f"\\mathbf a_{{G,{name}}}", m.acceleration),
                )
                if _nonzero(num(v))
            ]
            if motion:
                blocks.append(display(",\\quad ".join(motion)))
        terms = [
            f"\\mathbf F_{{{_tex_label(ld.name)}}} = {_ijk(tex, num(ld.force))}" for ld in b.loads if _nonzero(ld.force)
        ]
        terms += [
            f"\\boldsymbol\\tau_{{{_tex_label(ld.name)}}} = {_ijk(tex, num(ld.torque))}"
            for ld in b.loads
            if _nonzero(ld.torque)
        ]
        if m is not None:  # a_G is stated above
            terms.append(f"-m\\mathbf a_G = -{tex(num(b.mass))}\\,\\mathbf a_{{G,{name}}}")
        else:
            terms.append(f"-m\\mathbf a_G = {_ijk(tex, num(b.inertial_force))}")
        if _nonzero(b.inertial_moment):
            terms.append(f"-(I_G\\alpha + \\omega\\times I_G\\omega) = {_ijk(tex, num(b.inertial_moment))}")
        blocks.append(display(",\\quad ".join(terms)))
        if b.joint_in is None:  # no named reactions: what is left is balanced by the constraint forces
            blocks.append(
                display(
                    f"{{\\textstyle\\sum}} \\mathbf F - m\\mathbf a_G = "
                    f"{_ijk(tex, num(b.force_balance))} = -\\mathbf F_c,"
                    f"\\quad {{\\textstyle\\sum}} \\mathbf M_G - (I_G\\alpha + \\omega\\times I_G\\omega) = "
                    f"{_ijk(tex, num(b.moment_balance))} = -\\mathbf M_c"
                )
            )
        else:
            blocks.append(
                display(
                    f"{{\\textstyle\\sum}} \\mathbf F = {_ijk(tex, num(b.force_balance))} = \\mathbf 0,\\quad "
                    f"{{\\textstyle\\sum}} \\mathbf M = {_ijk(tex, num(b.moment_balance))} = \\mathbf 0"
                )
            )
    if ne.reactions:
        blocks.append(para(text("Joint reactions (parent on child, world components):")))
        for r in ne.reactions:
            j = tex_name(r.joint)
            blocks.append(
                display(
                    f"\\mathbf R_{{{j}}} = {_ijk(tex, num(r.force))},\\quad "
                    f"\\mathbf N_{{{j}}} = {_ijk(tex, num(r.moment))}"
                )
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
    blocks += _agreement_blocks(ne, tex)
    return sec


# -- planar systems: Newton–Euler as it is taught ---------------------------------------------

_PLANAR_INTRO = (
    "Newton–Euler in the plane, with D'Alembert's principle: each body is in equilibrium under every force "
    "on it and its inertial force $-m\\mathbf a_G$ (at $G$) and couple $-I_G\\alpha$. "
    "$\\mathbf R_j$ is the force the parent exerts on the child at joint $j$ (the parent receives "
    "$-\\mathbf R_j$); a slide exerts a force $N_j$ normal to it and a couple $M_j$. "
    "Moments are about the body's joint, counter-clockwise positive; $\\mathbf i$, $\\mathbf j$ are the "
    "$x$ and $y$ directions."
)


def _name_unknowns(planar: PlanarNewtonEuler, tex: TexPrinter) -> None:
    """R[pivot].x -> R_{pivot,x}; R[slide].n -> N_{slide}; M[slide] -> M_{slide}."""
    names: dict[sp.Basic, str] = {}
    for r in planar.reactions:
        j = tex_name(r.joint)
        for sym in r.unknowns:
            name = sym.name
            if name.startswith("M["):
                names[sym] = f"M_{{{j}}}"
            elif name.endswith(".n"):
                names[sym] = f"N_{{{j}}}"
            else:
                names[sym] = f"R_{{{j},{name[-1]}}}"
    tex.name(names)


def _ij(tex: TexPrinter, fx: sp.Expr, fy: sp.Expr) -> str:
    """A plane vector as a teacher writes it: -k x i + F j, zero components left out."""
    return _components(tex, ((fx, "\\mathbf i"), (fy, "\\mathbf j")))


def _ijk(tex: TexPrinter, v: sp.MatrixBase) -> str:
    """A vector of world components as x i + y j + z k, zero components left out."""
    return _components(tex, tuple(zip(v, ("\\mathbf i", "\\mathbf j", "\\mathbf k"), strict=True)))


def _components(tex: TexPrinter, pairs: tuple[tuple[sp.Expr, str], ...]) -> str:
    pieces = []
    for c, unit in pairs:
        if c == 0:
            continue
        if c == 1 or c == -1:
            pieces.append(("-" if c == -1 else "") + unit)
            continue
        s = tex(c)
        if isinstance(c, sp.Add):
            s = f"\\left({s}\\right)"
        pieces.append(f"{s} {unit}")  # no thin space: the line breaker splits a term at a comma
    if not pieces:
        return "\\mathbf 0"
    out = pieces[0]
    for p in pieces[1:]:
        out += (" " if p.startswith("-") else " + ") + p
    return out


def _at(tex: TexPrinter, point: tuple[sp.Expr, sp.Expr]) -> str:
    return f"\\quad\\text{{at }}\\left({tex(point[0])},\\ {tex(point[1])}\\right)"


def _label(f: PlanarForce, coords: dict[str, str]) -> tuple[str, str]:
    """The symbols a force and its couple are named by on a free-body diagram (a generalized force by
    its coordinate: Q_theta)."""
    src = "\\text{" + (f.source or "").replace("_", "\\_") + "}"
    if f.kind is ForceKind.GRAVITY:
        return "\\mathbf W", ""
    if f.kind is ForceKind.INERTIAL_FORCE:
        return "\\mathbf F_{\\text{inertial}}", ""
    if f.kind is ForceKind.INERTIAL_COUPLE:
        return "", "M_{\\text{inertial}} = -I_G\\alpha"
    if f.kind in (ForceKind.REACTION, ForceKind.REACTION_ON_PARENT, ForceKind.LOOP_REACTION):
        j = tex_name(f.source or "")
        sign = "" if f.kind in (ForceKind.REACTION, ForceKind.LOOP_REACTION) else "-"
        return f"{sign}\\mathbf R_{{{j}}}", f"{sign}M_{{{j}}}"
    if f.kind is ForceKind.LOOP_REACTION_ON_PARENT:
        return f"-\\mathbf R_{{{tex_name(f.source or '')}}}", ""
    if f.kind is ForceKind.CONSTRAINT:
        return f"\\mathbf F_{{{src}}}", f"\\tau_{{{src}}}"
    if f.kind in (ForceKind.DRIVE, ForceKind.DRIVE_REACTION):
        sign = "" if f.kind is ForceKind.DRIVE else "-"
        q = coords.get(f.source or "", src)
        return f"{sign}\\mathbf Q_{{{q}}}", f"{sign}Q_{{{q}}}"
    if f.kind is ForceKind.ROTOR:
        return "\\mathbf F_{\\text{rotor}}", "\\tau_{\\text{rotor}}"
    sign = "-" if f.kind is ForceKind.LOAD_REACTION else ""
    return f"{sign}\\mathbf F_{{{src}}}", f"{sign}\\tau_{{{src}}}"


_WORDS = {
    ForceKind.GRAVITY: "gravity",
    ForceKind.LOAD: "applied",
    ForceKind.LOAD_REACTION: "reaction of an applied load",
    ForceKind.SPRING: "spring",
    ForceKind.DAMPER: "damper",
    ForceKind.DRIVE: "generalized force at its joint",
    ForceKind.DRIVE_REACTION: "reaction of a generalized force",
    ForceKind.ROTOR: "the geared rotor's reflected inertia",
    ForceKind.REACTION: "joint reaction, on the child",
    ForceKind.REACTION_ON_PARENT: "joint reaction, on the parent",
    ForceKind.LOOP_REACTION: "the loop-closing pin, on the child",
    ForceKind.LOOP_REACTION_ON_PARENT: "the loop-closing pin, on the parent",
    ForceKind.CONSTRAINT: "the constraint's generalized force at its joint",
    ForceKind.INERTIAL_FORCE: "D'Alembert",
    ForceKind.INERTIAL_COUPLE: "D'Alembert",
}


def _force_lines(b: PlanarBalance, mass: str, coords: dict[str, str], tex: TexPrinter, num: Any) -> list[str]:
    lines = []
    for f in b.forces:
        force_name, couple_name = _label(f, coords)
        words = f"\\quad\\text{{({_WORDS[f.kind]})}}"
        fx, fy = num(f.force[0]), num(f.force[1])
        if f.kind is ForceKind.INERTIAL_FORCE:  # a_G is stated above
            lines.append(f"{force_name} = -{mass}\\mathbf a_G\\quad\\text{{at }}G{words}")
            continue
        t = num(f.torque)
        if f.kind in (ForceKind.REACTION, ForceKind.REACTION_ON_PARENT) and t != 0:
            # a reaction couple is its own unknown (M_j): named beside the force, not "M_j = M_j"
            where = _at(tex, (num(f.point[0]), num(f.point[1])))
            couple = f"\\ \\text{{and the couple }}{tex(t)}"
            lines.append(f"{force_name} = {_ij(tex, fx, fy)}{where}{couple}{words}")
            continue
        if fx != 0 or fy != 0:
            at_g = f.kind is ForceKind.GRAVITY
            where = "\\quad\\text{at }G" if at_g else _at(tex, (num(f.point[0]), num(f.point[1])))
            if f.kind in (ForceKind.LOOP_REACTION, ForceKind.LOOP_REACTION_ON_PARENT):  # one point, two bodies
                where = f"\\quad\\text{{at the pin }}{tex_name(f.source or '')}"
            lines.append(f"{force_name} = {_ij(tex, fx, fy)}{where}{words}")
        if t != 0:
            lines.append(f"{couple_name} = {tex(t)}{words}")
    return lines


def _balance_lhs(kind: str, b: str, about: str, axis: str) -> str:
    return {
        "moment": f"\\textstyle\\sum M_{{{about}}}^{{({b})}}",
        "force": f"\\textstyle\\sum F_{{{axis}}}^{{({b})}}",
    }[kind]


def _axis_name(tex: TexPrinter, axis: tuple[sp.Expr, sp.Expr]) -> str:
    if axis == (1, 0):
        return "x"
    if axis == (0, 1):
        return "y"
    return f"\\parallel {_ij(tex, *axis)}"


def planar_section(
    ne: NewtonEuler,
    planar: PlanarNewtonEuler,
    coordinates: tuple[Coordinate, ...],
    tex: TexPrinter,
    num: Any,
    diagrams: dict[str, dict[str, Any]] | None = None,
) -> dict[str, Any]:
    """Per body: its motion, its free-body diagram and its three balances; then the equations of motion,
    the reactions eliminated one coordinate at a time; then the reactions. ``diagrams``: per body, its
    drawn free body (:func:`free_bodies`), shown before the list of its forces."""
    _name_unknowns(planar, tex)
    sec = section("Newton–Euler", _PLANAR_INTRO)
    blocks = sec["blocks"]
    blocks += constraint_reaction_blocks(ne, coordinates, tex, num)
    masses = {b.body: b.mass for b in ne.bodies}
    motions = {m.body: m for m in ne.motions}
    axes = {r.joint: (r.axis[0], r.axis[1]) for r in ne.reactions}
    kinds = {r.joint: r.kind for r in ne.reactions}
    for b in planar.balances:
        about = tex_name(b.joint)
        mass = tex(num(masses[b.body])) if masses[b.body] != 0 else "m"
        if isinstance(num(masses[b.body]), sp.Add):  # a composite body's m_2 + m_f: -(m_2 + m_f) a_G
            mass = f"\\left({mass}\\right)"
        where = f"the pivot of joint '{b.joint}'" if kinds[b.joint] is JointKind.REVOLUTE else f"joint '{b.joint}'"
        blocks.append(
            para(
                strong(b.body),
                text(f": the free body, with moments about {where} at "),
                math(f"\\left({tex(num(b.point[0]))},\\ {tex(num(b.point[1]))}\\right)"),
                text("."),
            )
        )
        m = motions.get(b.body)
        if m is not None and (m.acceleration[0] != 0 or m.acceleration[1] != 0 or m.angular_acceleration[2] != 0):
            motion = [f"\\mathbf a_{{G}} = {_ij(tex, num(m.acceleration[0]), num(m.acceleration[1]))}"]
            if m.angular_acceleration[2] != 0:
                motion.append(f"\\alpha = {tex(num(m.angular_acceleration[2]))}")
            blocks.append(display(",\\quad ".join(motion)))
        coords = {c.name: c.latex for c in coordinates}
        if diagrams and b.body in diagrams:
            blocks.append(freebody_block(diagrams[b.body]))
        blocks.append(stacked(_force_lines(b, mass, coords, tex, num)))
        blocks.append(
            stacked(
                [
                    tex.equation("\\textstyle\\sum F_x", num(b.sum_fx), "0"),
                    tex.equation("\\textstyle\\sum F_y", num(b.sum_fy), "0"),
                    tex.equation(f"\\textstyle\\sum M_{{{about}}}", num(b.sum_m), "0"),
                ]
            )
        )
    blocks.append(
        para(
            text(
                "The reactions eliminated, one coordinate at a time from the tips inward: the balances of the "
                "bodies that a change of that coordinate alone moves are added, so that the reactions between "
                "them cancel and the joint's own reaction does no work."
            )
        )
    )
    for st in planar.steps:
        blocks += _step_blocks(st, axes, kinds, coordinates, tex, num)
    blocks.append(para(text("The reactions, solved last (tips first, each from its child's balances):")))
    for r in reversed(planar.reactions):  # the tips first, as they are solved
        lines = [f"{tex(u)} = {tex(num(v))}" for u, v in zip(r.unknowns, r.values, strict=True)]
        blocks.append(stacked(lines))
    # the recursive route's remarks (what enters as Q_i, what is subtracted behind an absolute angle)
    # describe its own form; here every force is on its free body and the steps say what is added
    blocks += _agreement_blocks(ne, tex)
    return sec


def constraint_reaction_blocks(
    ne: NewtonEuler, coordinates: tuple[Coordinate, ...], tex: TexPrinter, num: Any
) -> list[dict[str, Any]]:
    """What a constrained spec's constraints exert (issue 21), in their multipliers: a loop-closing pin's
    force on both of its bodies; a constraint expression's generalized force along each coordinate."""
    out: list[dict[str, Any]] = []
    latex = {c.name: c.latex for c in coordinates}
    for cr in ne.constraint_reactions:
        lams = ",\\ ".join(tex(x) for x in cr.multipliers)
        if cr.kind == "pin":
            assert cr.on_parent is not None and cr.on_child is not None
            j, parent, child = tex_name(cr.name), tex_name(cr.parent or ""), tex_name(cr.child or "")
            eqs = ", ".join(cr.constraints)
            out.append(
                para(
                    text(f"The pin {cr.name} closes the loop: its loop-closure equations ({eqs}) say that "),
                    math(f"\\mathbf r_{{{parent}}}({j}) - \\mathbf r_{{{child}}}({j})"),
                    text(" (the pin as a point of each body) is zero, so "),
                    math("A^{T}\\lambda"),
                    text(" is the generalized force of the force "),
                    math(_ijk(tex, cr.on_parent)),
                    text(f" on {cr.parent} at the pin and its opposite on {cr.child}: the multipliers "),
                    math(lams),
                    text(f" are the world components of the pin's force on {cr.parent}. In the convention of the "),
                    text(f"other joints (parent on child) the pin's reaction on {cr.child} is "),
                    math(f"\\mathbf R_{{{j}}} = {_ijk(tex, num(cr.on_child))}"),
                    text(f", and {cr.parent} receives "),
                    math(f"-\\mathbf R_{{{j}}}"),
                    text(". Both enter the balances like any other force."),
                )
            )
        else:
            shares = [
                (f"{tex(num(f))}", latex[c.name])
                for c, f in zip(coordinates, cr.generalized_force, strict=True)
                if f != 0
            ]
            words: list[Any] = [text(f"The constraint '{cr.name}' exerts its force through its multiplier ")]
            words += [math(lams), text(": its generalized force ")]
            words.append(math("(A^{T}\\lambda)_i"))
            words.append(text(" enters the equation of each coordinate as a drive does, "))
            for k, (value, q) in enumerate(shares):
                if k:
                    words.append(text(" and " if k == len(shares) - 1 else ", "))
                words += [math(value), text(" along "), math(q)]
            words.append(text("."))
            out.append(para(*words))
    return out


def _agreement_blocks(ne: NewtonEuler, tex: TexPrinter) -> list[dict[str, Any]]:
    """The agreement with Lagrange's (with multipliers, for a constrained spec) and with the reduction."""
    out = []
    if ne.agrees_with_lagrange:
        out.append(para(engine_parts(ne.agreement.detail + ".", tex)))
    if ne.reduction is not None and ne.reduction.passed:
        out.append(para(engine_parts(ne.reduction.detail + ".", tex)))
    return out


def _step_blocks(
    st: EliminationStep,
    axes: dict[str, tuple[sp.Expr, sp.Expr]],
    kinds: dict[str, JointKind],
    coordinates: tuple[Coordinate, ...],
    tex: TexPrinter,
    num: Any,
) -> list[dict[str, Any]]:
    coord = next(c for c in coordinates if c.name == st.coordinate)
    j = tex_name(st.joint)
    bodies = [c.body for c in st.contributions]
    revolute = kinds[st.joint] is JointKind.REVOLUTE
    if revolute:
        what = f"the moments about the pivot of joint '{st.joint}'"
    else:
        what = "the forces along the slide of joint '" + st.joint + "'"
    intro = [strong("Equation of"), text(" "), math(coord.latex), text(f": {what}, of "), text(", ".join(bodies))]
    if st.eliminated:
        intro += [text("; "), math(",\\ ".join(tex(u) for u in st.eliminated)), text(" cancel")]
    intro.append(text("."))
    carried = [c for c in st.contributions if c.kind == "force_moment"]
    if carried:
        names = ", ".join(c.body for c in carried)
        vias = ", ".join(sorted({f"'{c.via}'" for c in carried}))
        intro.append(
            text(
                f" The angle at joint {vias} is absolute, so {names} does not turn when only this angle changes: "
                "it moves with that joint's point, and only the moment of its forces there counts."
            )
        )
    lines = []
    axis = _axis_name(tex, axes[st.joint])
    for c in st.contributions:
        b = tex_name(c.body)
        if c.kind == "force_moment":
            via = tex_name(c.via or "")
            lhs = f"(\\mathbf r_{{{via}}} - \\mathbf r_{{{j}}})\\times{{\\textstyle\\sum}}\\mathbf F^{{({b})}}"
        else:
            lhs = _balance_lhs(c.kind, b, j, axis)
        lines.append(tex.equation(lhs, num(c.expr)))
    if len(st.contributions) > 1:
        lines.append(tex.equation("\\text{sum}", num(st.result), "0"))
    else:
        lines[-1] += " = 0"
    return [para(*intro), stacked(lines)]


# -- the free-body diagrams of the planar step --------------------------------------------------


def free_bodies(d: Derivation) -> list[dict[str, Any]]:
    """The drawn free bodies of the planar Newton–Euler step, as
    :func:`tutgen.figure.view.free_body_views` gives them (``body``, ``tikz``, ``svg``, ``svg_text``,
    ``labels``, ``remarks``), each with the forces of its balance under the names the step gives them;
    empty where the step is not printed (no Newton–Euler, no equations of motion asked, a spatial
    system) or its figure is not drawn in the plane. The section and the writer of the files beside a
    Markdown solution (:func:`tutgen.api.figure_files`) both take them from here."""
    from tutgen.figure.view import free_body_views

    balances = _drawn_balances(d)
    if not balances:
        return []
    views = _VIEWS.get(d)  # made for this derivation already (the section, then the files)
    if views is None:
        coords = {c.name: c.latex for c in d.system.coordinates}
        forces = {b.body: diagram_forces(b, coords) for b in balances}
        # only the bodies the step has a balance for (a massless body has none)
        views = _VIEWS.put(d, [v for v in free_body_views(d.system, forces) if v["body"] in forces])
    return [dict(v) for v in views]


def free_body_names(d: Derivation) -> list[str]:
    """The bodies :func:`free_bodies` draws, in its order, without drawing them (a sheet plans its
    files from them before it builds anything)."""
    from tutgen.figure.view import free_body_bodies

    balanced = {b.body for b in _drawn_balances(d)}
    return [body for body in free_body_bodies(d.system) if body in balanced] if balanced else []


def _drawn_balances(d: Derivation) -> tuple[PlanarBalance, ...]:
    """The planar Newton–Euler step's balances whose free bodies are drawn: none where the step is not
    printed (no Newton–Euler, no equations of motion asked, a spatial system)."""
    ne = d.newton_euler
    if ne is None or ne.planar is None or Ask.EQUATIONS_OF_MOTION not in d.system.ask:
        return ()
    return tuple(ne.planar.balances)


#: the free-body views made for the last few derivations: a solution written to a file asks for them for
#: its Newton–Euler step and again for the SVGs beside it, a sheet's unit for its step and its assets (the
#: diagrams themselves are remembered per system, tutgen.figure.freebody; their TikZ and SVG here)
_VIEWS: ByIdentity[Derivation, list[dict[str, Any]]] = ByIdentity(16)


def diagram_forces(b: PlanarBalance, coords: dict[str, str]) -> tuple[BodyForce, ...]:
    """A balance's forces for its diagram: one arrow per force of the step, named as the step names
    it (``name``: the step's words, ``gravity``, ``reaction at joint 'pivot'``; label: the step's
    symbol), and a couple's arrow beside a force that has one (``<name>:couple``). A force on the
    parent's side (a reaction, a load's or a drive's reaction) keeps its symbol without the sign: the
    arrow is drawn reversed, as a student draws Newton's third law. Points and vectors in world axes."""
    out = []
    for f in b.forces:
        force_name, couple_name = _label(f, coords)
        force_tex, couple_tex = _figure_tex(force_name), _figure_tex(couple_name.split(" =", 1)[0])
        at = (f.point[0], f.point[1], sp.Integer(0))
        has_force = f.force[0] != 0 or f.force[1] != 0
        if has_force:
            vector = (f.force[0], f.force[1], sp.Integer(0))
            out.append(BodyForce(f.name, f.source or f.name, at, vector, Frame.WORLD, Frame.WORLD, tex=force_tex))
        if f.torque != 0:
            name = f"{f.name}:couple" if has_force else f.name
            vector = (sp.Integer(0), sp.Integer(0), f.torque)
            out.append(
                BodyForce(name, f.source or f.name, at, vector, Frame.WORLD, Frame.WORLD, moment=True, tex=couple_tex)
            )
    return tuple(out)


def _figure_tex(symbol: str) -> str:
    """The step's symbol in the figure's label vocabulary: no sign (the arrow shows the direction),
    a bold letter braced (``\\mathbf W`` -> ``\\mathbf{W}``, which the SVG also sets upright)."""
    symbol = symbol.strip().removeprefix("-")
    if symbol.startswith("\\mathbf ") and len(symbol) > 8:
        symbol = "\\mathbf{" + symbol[8] + "}" + symbol[9:]
    return symbol


def freebody_block(view: dict[str, Any]) -> dict[str, Any]:
    """A ``freebody`` block: the drawn free body of one body, TikZ for LaTeX, the SVG beside the
    Markdown by its relative name (docs/figures.md)."""
    return {
        "kind": "freebody",
        "body": view["body"],
        "tikz": view["tikz"],
        "svg": view["svg"],
        "labels": view["labels"],
    }
