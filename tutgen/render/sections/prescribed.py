"""Prescribed (driven) coordinates (issue 18, point 4): the motion substituted into the equations of the
free coordinates, and the force or torque each drive must supply (tutgen.engine.prescribed)."""

from __future__ import annotations

from typing import Any

from tutgen.engine.prescribed import DrivenCoordinate
from tutgen.engine.steps import StepKind
from tutgen.model.system import Coordinate
from tutgen.render.blocks import Part, SolutionContext, boxed, display, math, para, section, text


def drive_symbol(x: DrivenCoordinate) -> str:
    """The drive's symbol: tau_q for a torque, F_q for a force, Q_q^drive otherwise."""
    c, kind = x.coordinate, x.kind
    if kind == "torque":
        return f"\\tau_{{{c.latex}}}"
    if kind == "force":
        return f"F_{{{c.latex}}}"
    return f"Q^{{\\mathrm{{drive}}}}_{{{c.latex}}}"


def _names(coords: list[Coordinate]) -> list[Part]:
    parts: list[Part] = []
    for k, c in enumerate(coords):
        if k:
            parts.append(text(" and " if k == len(coords) - 1 else ", "))
        parts.append(math(c.latex))
    return parts


def prescribed_motion(c: SolutionContext) -> dict[str, Any] | None:
    d, s, tex, num = c.d, c.s, c.tex, c.num
    pm = d.prescribed
    if pm is None or not d.has_step(StepKind.PRESCRIBED_MOTION):
        return None
    driven = [x.coordinate for x in pm.driven]
    free = [s.coordinates[i] for i in pm.free]
    one = len(driven) == 1
    sec = section("Prescribed motion")
    sec["blocks"].append(
        para(
            *_names(driven),
            text(
                f" {'is' if one else 'are'} prescribed, so {'it is' if one else 'they are'} not a degree of freedom: "
                "the drive imposes"
            ),
        )
    )
    sec["blocks"].append(
        display(
            ",\\quad ".join(
                f"{tex(x.coordinate.q)} = {tex(num(x.motion))},\\quad {tex(x.coordinate.qd)} = {tex(num(x.rate))},"
                f"\\quad {tex(x.coordinate.qdd)} = {tex(num(x.acceleration))}"
                for x in pm.driven
            )
        )
    )
    one_free = len(free) == 1
    args = ", ".join([*(f.latex for f in free), *(tex(f.qd) for f in free), "t"])
    intro = [
        text(f"With the motion substituted, the equation{'' if one_free else 's'} of "),
        *_names(free),
        text(f" above become{'s' if one_free else ''} Lagrange's equation{'' if one_free else 's'} of "),
        math(f"L({args})"),
        text(", the Lagrangian with the motion substituted"),
    ]
    if pm.is_time_dependent:
        intro += [text(", with "), math("d/dt"), text(" including its explicit dependence on "), math("t")]
    intro.append(text(":"))
    sec["blocks"].append(para(*intro))
    qdd = [f.qdd for f in free]
    for a in range(len(free)):
        inertia_and_rates = sum((pm.mass_matrix[a, b] * qdd[b] for b in range(len(free))), pm.coriolis_vector[a])
        pieces = [num(inertia_and_rates), num(pm.driving_vector[a]), num(pm.gravity_vector[a])]
        sec["blocks"].append(boxed(f"{_joined(c, pieces)} = {tex(num(pm.generalized_forces[a]))}"))
    if d.has_step(StepKind.MATRIX_FORM):
        rows = [
            ("H_f", pm.mass_matrix),
            ("C_f", pm.coriolis_vector),
            ("G_f", pm.gravity_vector),
            ("D_f", pm.driving_vector),
            ("Q_f", pm.generalized_forces),
        ]
        sec["blocks"].append(
            para(
                text("In matrix form "),
                math("H_f\\ddot q_f + C_f + G_f + D_f = Q_f"),
                text(": "),
                math("H"),
                text(", "),
                math("C"),
                text(" (the free rates only), "),
                math("G"),
                text(" and "),
                math("Q"),
                text(" of the free coordinates with the motion substituted, and "),
                math("D_f"),
                text(" what the driven motion adds (its accelerations in "),
                math("H"),
                text(", its rates in "),
                math("C"),
                text("):"),
            )
        )
        sec["blocks"].append(display(",\\quad ".join(f"{n} = {tex(num(v))}" for n, v in rows)))
    return sec


def _joined(c: SolutionContext, pieces: list[Any]) -> str:
    """A sum printed piece by piece, in the order given (each piece in a teacher's order), zeros left out."""
    out = ""
    for piece in pieces:
        if piece == 0:
            continue
        shown = c.tex.ordered(piece)
        if not out:
            out = shown
        elif shown.startswith("- "):
            out += f" - {shown[2:]}"
        else:
            out += f" + {shown}"
    return out or "0"


def _drive_blocks(c: SolutionContext, x: DrivenCoordinate, free: list[Coordinate]) -> list[dict[str, Any]]:
    tex, num = c.tex, c.num
    symbol = drive_symbol(x)
    blocks = [boxed(f"{symbol} = {tex.ordered(num(x.drive))}")]
    if x.drive_along_motion is not None:
        blocks.append(
            para(
                text("With "),
                *_names([f for f in free if x.drive.has(f.qdd)]),
                text("'s acceleration" if len(free) == 1 else " accelerations"),
                text(" from the equations of motion, as a function of the state and "),
                math("t"),
                text(":"),
            )
        )
        blocks.append(boxed(f"{symbol} = {tex.ordered(num(x.drive_along_motion))}"))
    return blocks


def drive_force(c: SolutionContext) -> dict[str, Any] | None:
    d, s = c.d, c.s
    pm = d.prescribed
    if pm is None or not d.has_step(StepKind.DRIVE_FORCE):
        return None
    kinds = {x.kind for x in pm.driven}
    title = f"Drive {kinds.pop()}" if len(kinds) == 1 else "Drive forces"
    if len(pm.driven) > 1:
        title += "s" if not title.endswith("s") else ""
    free = [s.coordinates[i] for i in pm.free]
    sec = section(title)
    for x in pm.driven:
        q = x.coordinate
        sec["blocks"].append(
            para(
                text("Along the prescribed motion the equation of "),
                math(q.latex),
                text(f" no longer decides it: it gives the {x.kind} "),
                math(drive_symbol(x)),
                text(" the drive must add to the other generalized forces on it, "),
                math(
                    f"{drive_symbol(x)} = \\frac{{d}}{{dt}}\\frac{{\\partial L}}{{\\partial {c.tex(q.qd)}}} - "
                    f"\\frac{{\\partial L}}{{\\partial {q.latex}}} - Q_{{{q.latex}}}"
                ),
                text(f", with {'its motion' if len(pm.driven) == 1 else 'the motions'} substituted:"),
            )
        )
        sec["blocks"] += _drive_blocks(c, x, free)
    return sec
