"""The constraints (issue 21): the constraint equations and the velocity analysis, the equations with
Lagrange's multipliers (lambda solved and what force it is), and the equations reduced to the independent
coordinates."""

from __future__ import annotations

import math as math_module
from math import pi
from typing import Any

import sympy as sp

from tutgen.engine.constraints.positions import LoopAnalysis, assembly_at, assembly_ranges, branch_at
from tutgen.engine.steps import StepKind
from tutgen.engine.tidy import tidy
from tutgen.figure.build import drawn_values
from tutgen.model.system import ConstraintKind, System
from tutgen.render.blocks import SolutionContext, boxed, display, math, para, prose, section, text
from tutgen.render.printer import TexPrinter


def _vector(names: list[str]) -> str:
    return "\\begin{pmatrix}" + " \\\\ ".join(names) + "\\end{pmatrix}"


def constraint_kinematics(c: SolutionContext) -> dict[str, Any] | None:
    d, s, tex, num = c.d, c.s, c.tex, c.num
    cd = d.constraints
    if cd is None or not d.has_step(StepKind.CONSTRAINTS):
        return None
    ck = cd.kinematics
    coords = s.coordinates
    sec = section(
        "Constraints",
        "Each constraint is an equation that holds along the motion; differentiated, each gives a row of "
        "$A \\dot q = 0$.",
    )
    lines = []
    for con, f in zip(ck.constraints, ck.functions, strict=True):
        kind = "position" if con.kind is ConstraintKind.POSITION else "velocity"
        lines.append(f"{tex(num(f))} = 0\\quad\\text{{({kind}: {con.name.replace('_', ' ')})}}")
    sec["blocks"].append(display(",\\quad ".join(lines), stack=True))
    q_names = [x.latex for x in coords]
    sec["blocks"].append(
        para(
            text("The constraint Jacobian (a position constraint's row is its gradient "),
            math("\\partial f/\\partial q"),
            text(", a velocity constraint's the coefficients of the rates), with "),
            math(f"q = {_vector(q_names)}"),
            text(":"),
        )
    )
    sec["blocks"].append(display(f"A = {tex(num(ck.jacobian))}"))
    ind = [coords[j] for j in ck.independent]
    dep = [coords[j] for j in ck.dependent]
    sec["blocks"].append(
        para(
            text("Independent coordinates "),
            math(", ".join(x.latex for x in ind)),
            text("; dependent "),
            math(", ".join(x.latex for x in dep)),
            text(". Velocity analysis, "),
            math("\\dot q_d = B\\,\\dot q_i"),
            text(" with "),
            math("B = -A_d^{-1} A_i"),
            text(":"),
        )
    )
    rates = [f"{tex(x.qd)} = {tex(num(ck.rates[x.qd]))}" for x in dep]
    sec["blocks"].append(display(",\\quad ".join(rates)))
    if ck.determinant.free_symbols & {x.q for x in coords}:
        # dead points: where det A_d vanishes the dependent rates are not determined by the independent ones
        sec["blocks"].append(
            para(
                text("The velocity ratios have the denominator "),
                math(f"\\det A_d = {tex(num(ck.determinant))}"),
                text(
                    ": where it vanishes (a dead point, or toggle position) the independent coordinates do not "
                    "determine the motion of the others, and the equations below are singular."
                ),
            )
        )
    if ck.positions:
        sec["blocks"].append(
            para(text("Position analysis: the position constraints solved for the dependent coordinates:"))
        )
        for branch in ck.positions:
            sec["blocks"].append(display(",\\quad ".join(f"{coords[j].latex} = {tex(num(e))}" for j, e in branch)))
    elif ck.loop is not None:
        sec["blocks"] += loop_position_analysis(c, ck.loop)
    elif not ck.is_holonomic and not any(x.kind is ConstraintKind.POSITION for x in ck.constraints):
        sec["blocks"].append(
            para(
                text(
                    "The velocity constraints cannot be integrated to relations among the coordinates "
                    "(they are nonholonomic): all the coordinates stay, and only the rates are tied."
                )
            )
        )
    if any(b != 0 for b in ck.bias):
        sec["blocks"].append(
            para(
                text("Acceleration analysis, "),
                math("A\\ddot q + \\dot A\\,\\dot q = 0"),
                text(", with"),
            )
        )
        sec["blocks"].append(display(f"\\dot A\\,\\dot q = {tex(num(ck.bias))}"))
    sec["blocks"].append(para(text("So "), math("\\dot q = T\\,\\dot q_i"), text(" with")))
    sec["blocks"].append(display(f"T = {tex(num(ck.velocity_map))}"))
    return sec


def multipliers(c: SolutionContext) -> dict[str, Any] | None:
    d, s, tex, num = c.d, c.s, c.tex, c.num
    cd = d.constraints
    if cd is None or d.equations_of_motion is None or d.generalized_forces is None:
        return None
    if not d.has_step(StepKind.LAGRANGE_MULTIPLIERS):
        return None
    ck = cd.kinematics
    coords = s.coordinates
    sec = section(
        "Equations with Lagrange's multipliers",
        "The constraint forces add $A^T\\lambda$ to the generalized forces: "
        "$H\\ddot q + C + G = Q + A^T\\lambda$, together with $A\\ddot q + \\dot A\\,\\dot q = 0$.",
    )
    rows = []
    for i in range(len(coords)):
        lhs = num(d.equations_of_motion[i] + d.generalized_forces[i])
        rhs = num(d.generalized_forces[i] + cd.constraint_forces[i])
        rows.append(f"{tex.ordered(lhs)} = {tex(rhs)}")
    for k in range(len(ck.constraints)):
        acc = sp.Add(*[ck.jacobian[k, j] * coords[j].qdd for j in range(len(coords))], ck.bias[k])
        rows.append(f"{tex(num(acc))} = 0")
    sec["blocks"].append(display(",\\quad ".join(rows), stack=True))
    dep = [coords[j] for j in ck.dependent]
    sec["blocks"].append(
        para(
            text("The equations of the dependent coordinates "),
            math(", ".join(x.latex for x in dep)),
            text(" give the multipliers:"),
        )
    )
    for lam, e in zip(cd.multipliers, cd.multipliers_in_accelerations, strict=True):
        sec["blocks"].append(display(f"{tex(lam)} = {tex(num(e))}"))
    if cd.multiplier_values:
        sec["blocks"].append(para(text("and, with the accelerations of the motion (below),")))
        sec["blocks"].append(
            boxed(
                ",\\quad ".join(
                    f"{tex(lam)} = {tex(num(e))}" for lam, e in zip(cd.multipliers, cd.multiplier_values, strict=True)
                )
            )
        )
    for k, (con, lam) in enumerate(zip(ck.constraints, cd.multipliers, strict=True)):
        parts = [math(tex(lam)), text(f" is the multiplier of constraint {con.name.replace('_', ' ')}; it acts")]
        first = True
        for j, x in enumerate(coords):
            a = ck.jacobian[k, j]
            if a == 0:
                continue
            what = (
                "a torque about"
                if x.dimension == "angle"
                else "a force along"
                if x.dimension == "length"
                else "a generalized force on"
            )
            parts += [
                text("" if first else ","),
                text(f" as {what} "),
                math(x.latex),
                text(" of "),
                math(tex(num(a * lam))),
            ]
            first = False
        parts.append(text("."))
        sec["blocks"].append(para(*parts))
    return sec


def reduced_equations(c: SolutionContext) -> dict[str, Any] | None:
    d, s, tex, num = c.d, c.s, c.tex, c.num
    cd = d.constraints
    if cd is None or not d.has_step(StepKind.REDUCED_EQUATIONS):
        return None
    ck = cd.kinematics
    ind = [s.coordinates[j] for j in ck.independent]
    sec = section(
        "Equations in the independent coordinates",
        "With $\\dot q = T\\dot q_i$ and $\\ddot q = T\\ddot q_i + \\dot T\\dot q_i$, and $T^T A^T = 0$: "
        "$H_r \\ddot q_i + C_r + G_r = Q_r$ with $H_r = T^T H T$, $C_r = T^T (C + H \\dot T \\dot q_i)$, "
        "$G_r = T^T G$ and $Q_r = T^T Q$.",
    )
    if any(e != 0 for e in cd.velocity_terms):
        sec["blocks"].append(display(f"\\dot T\\,\\dot q_i = {tex(num(cd.velocity_terms))}"))
    shown = [
        f"{name} = {tex(num(v))}"
        for name, v in (
            ("H_r", cd.mass_matrix),
            ("C_r", cd.coriolis_vector),
            ("G_r", cd.gravity_vector),
            ("Q_r", cd.generalized_forces),
        )
    ]
    sec["blocks"].append(display(",\\quad ".join(shown)))
    sec["blocks"] += _dependent_values(c, cd.equations_of_motion)
    for e, f in zip(cd.equations_of_motion, cd.generalized_forces, strict=True):
        sec["blocks"].append(boxed(f"{tex.ordered(num(e + f))} = {tex(num(f))}"))
    if cd.accelerations:
        sec["blocks"].append(para(text("Solved for the accelerations:")))
        sec["blocks"].append(
            display(
                ",\\quad ".join(f"{tex(x.qdd)} = {tex(num(a))}" for x, a in zip(ind, cd.accelerations, strict=True))
            )
        )
    return sec


def _dependent_values(c: SolutionContext, equations: Any) -> list[dict[str, Any]]:
    """What the dependent coordinates left in the reduced equations stand for: the functions of the
    independent ones that the position analysis gives, on which branch (a four-bar's assembly), so that
    the equations are in the independent coordinates alone."""
    s = c.s
    ck = c.d.constraints.kinematics if c.d.constraints is not None else None
    if ck is None:
        return []
    left = [s.coordinates[j] for j in ck.dependent if any(sp.sympify(e).has(s.coordinates[j].q) for e in equations)]
    if not left:
        return []
    ind = [s.coordinates[j] for j in ck.independent]
    names = " and ".join(", ".join(f"${x.latex}$" for x in left).rsplit(", ", 1))
    of = ", ".join(f"${x.latex}$" for x in ind)
    verb = "is" if len(left) == 1 else "are"
    if ck.positions and len(ck.positions) == 1:
        where = "the position analysis above gives"
    elif ck.loop is not None:
        values = _drawn_values(s)
        shape = assembly_at(ck.loop, values) if values is not None else None
        sign = branch_at(ck.loop, values, [x.q for x in s.coordinates]) if values is not None else None
        word = {1: "+", -1: "−"}
        if shape is not None and sign is not None:
            other = "crossed" if shape == "open" else "open"
            where = (
                f"the closed form of the position analysis above gives, on the {shape} assembly the figure "
                f"shows (the {word[sign]} sign; the {other} assembly, with the {word[-sign]} sign, has the same "
                "equation with its own values)"
            )
        elif sign is not None:
            where = (
                f"the closed form of the position analysis above gives, on the branch with the {word[sign]} sign "
                "(the one the figure shows)"
            )
        else:
            where = "the closed form of the position analysis above gives, on the branch of the motion"
    elif ck.positions:
        where = "the position analysis above gives, on the branch of the motion"
    else:
        where = "the position constraints give (numerically) on the branch of the motion"
    they = "they are the functions" if len(left) > 1 else "it is the function"
    equation = "equations are" if len(ind) > 1 else "equation is"
    sentence = f"In these, {names} {verb} not free: {they} of {of} that {where}. The {equation} thus in {of} alone."
    return [para(prose(sentence))]


def _drawn_values(system: System) -> dict[sp.Symbol, float] | None:
    """The numbers of the figure at the head of the solution (its sizes and its pose), when it is drawn."""
    if system.figure is not None and not system.figure.generated:
        return None
    return drawn_values(system)


def _in_order(tex: TexPrinter, expr: sp.Expr, coordinates: list[sp.Symbol], lead: sp.Symbol | None = None) -> str:
    """A sum printed as a textbook writes a loop's equation: by descending powers of ``lead`` (a slider's
    position), then the terms free of the coordinates, then those of one coordinate (in coordinate order),
    then the rest, each term printed on its own; a long sum, or not a sum, as the printer has it."""
    expanded = sp.expand(expr) if lead is not None else expr
    if not isinstance(expanded, sp.Add) or len(expanded.args) > 12:
        return tex(expr)

    def key(term: sp.Expr) -> tuple[object, ...]:
        power = sp.degree(term, lead) if lead is not None and term.is_polynomial(lead) else 0
        used = [i for i, q in enumerate(coordinates) if q in term.free_symbols and q != lead]
        body = -term if term.could_extract_minus_sign() else term
        return (-power, len(used), max(used, default=-1), body is not term, sp.default_sort_key(body))

    terms = sorted(expanded.args, key=key)
    first = next((t for t in terms if not t.could_extract_minus_sign()), terms[0])  # a positive lead
    terms.remove(first)
    out = ""
    for i, term in enumerate([first, *terms]):
        negative = term.could_extract_minus_sign()
        body = tex(-term if negative else term)
        out += ("- " if negative else "") + body if i == 0 else (" - " if negative else " + ") + body
    return out


def loop_position_analysis(c: SolutionContext, loop: LoopAnalysis) -> list[dict[str, Any]]:
    """The loop's closed-form position analysis (tutgen/engine/constraints/positions.py): the elimination
    of one link's angle, the equation in the other coordinate, its two roots (the branches, the one the
    figure shows named), the eliminated angle from it, and where the loop cannot close."""
    s, tex, num = c.s, c.tex, c.num
    u, v = s.coordinates[loop.eliminated], s.coordinates[loop.solved]
    four_bar = bool(loop.sides)
    qs = [x.q for x in s.coordinates]
    lead = None if loop.is_angle else v.q
    blocks: list[dict[str, Any]] = [
        para(
            text("Position analysis. The loop-closure equations are linear in "),
            math(f"\\cos {u.latex}"),
            text(" and "),
            math(f"\\sin {u.latex}"),
            text("; solved for them, "),
            math(f"\\cos^2 {u.latex} + \\sin^2 {u.latex} = 1"),
            text(" eliminates "),
            math(u.latex),
            text(" (Freudenstein's equation):" if four_bar else ":"),
        ),
        display(f"{_in_order(tex, num(loop.elimination), qs, lead)} = 0"),
    ]
    if loop.is_angle:
        names = sp.symbols("P Q R")
        blocks.append(para(text("that is "), math(f"P \\cos {v.latex} + Q \\sin {v.latex} + R = 0"), text(" with")))
        blocks.append(
            display(
                ",\\quad ".join(
                    f"{tex(k)} = {_in_order(tex, num(e), qs)}" for k, e in zip(names, loop.coefficients, strict=True)
                )
            )
        )
        blocks.append(
            para(
                text("With "),
                math(f"t = \\tan\\tfrac{{{v.latex}}}{{2}}"),
                text(", "),
                math(f"\\cos {v.latex} = \\frac{{1 - t^2}}{{1 + t^2}}"),
                text(" and "),
                math(f"\\sin {v.latex} = \\frac{{2t}}{{1 + t^2}}"),
                text(", it is the quadratic "),
                math("(R - P)\\,t^2 + 2Q\\,t + (R + P) = 0"),
                text(", whose two roots are the loop's two branches:"),
            )
        )
        root = f"{v.latex} = 2 \\operatorname{{atan2}}\\left(-Q \\pm \\sqrt{{P^2 + Q^2 - R^2}},\\ R - P\\right)"
        disc_tex = "P^2 + Q^2 - R^2"
    else:
        p_, q_, _r = loop.coefficients
        centre = tidy(sp.simplify(-q_ / (2 * p_)))
        blocks.append(
            para(text("a quadratic in "), math(v.latex), text(", whose two roots are the loop's two branches:"))
        )
        root = f"{v.latex} = {tex(num(centre))} \\pm {tex(num(sp.sqrt(loop.discriminant)))}"
        disc_tex = tex(num(loop.discriminant))
    y, x = loop.eliminated_value.args
    y, x = (_in_order(tex, num(e), qs, lead) for e in (y, x))
    eliminated = f"{u.latex} = \\operatorname{{atan2}}\\left({y},\\ {x}\\right)"
    blocks.append(boxed(f"{root},\\quad {eliminated}"))
    blocks += _branch_names(c, loop)
    closes = [text("The loop closes only where "), math(f"{disc_tex} \\ge 0")]
    if four_bar:
        crank, coupler, rocker, ground = (tex(e) for e in loop.lengths)  # by name, even when given numbers
        closes += [
            text(". By Grashof's condition the crank "),
            math(crank),
            text(" turns fully when the shortest of "),
            math(f"{crank}, {coupler}, {rocker}, {ground}"),
            text(
                " plus the longest is at most the sum of the other two, and the shortest is the crank or "
                "the ground; otherwise it swings between the angles where "
            ),
            math(f"{disc_tex} = 0"),
            *_crank_range(s, loop),
        ]
    closes += [
        text(". Where "),
        math(f"{disc_tex} = 0"),
        text(" the two branches meet and "),
        math("\\det A_d = 0"),
        text(": a dead point."),
    ]
    blocks.append(para(*closes))
    return blocks


def _crank_range(s: System, loop: LoopAnalysis) -> list[dict[str, str]]:
    """With the spec's numbers for the lengths: whether the crank turns fully, or the crank angles
    between which the loop can be assembled (degrees)."""
    values = {p.symbol: float(p.value) for p in s.parameters if p.value is not None and p.value.is_number}
    ranges = assembly_ranges(loop, values) if loop.crank is not None else None
    if ranges is None:
        return []
    if ranges == [(-pi, pi)]:
        return [text("; with the lengths given, it turns fully")]
    crank = s.coordinates[loop.crank].latex
    spans = [math(f"{_degrees(lo)} \\le {crank} \\le {_degrees(hi)}") for lo, hi in ranges]
    out: list[dict[str, str]] = [text("; with the lengths given, only for ")]
    for k, span in enumerate(spans):
        out += [text(" and " if k == len(spans) - 1 else ", "), span] if k else [span]
    return out


def _degrees(angle: float) -> str:
    """An angle in degrees, to 0.1 degree, for the text."""
    return f"{math_module.degrees(angle):.1f}^\\circ"


def _branch_names(c: SolutionContext, loop: LoopAnalysis) -> list[dict[str, Any]]:
    """Which sign is which assembly (a four-bar's open and crossed), and the one the figure shows."""
    s = c.s
    values = _drawn_values(s)
    if values is None:
        return []
    sign = branch_at(loop, values, [x.q for x in s.coordinates])
    if sign is None:
        return []
    word = {1: "+", -1: "−"}
    shape = assembly_at(loop, values)
    if shape is None:
        return [para(text(f"The figure shows the branch with the {word[sign]} sign."))]
    other = "crossed" if shape == "open" else "open"
    return [
        para(
            text(
                f"The {word[sign]} sign gives the {shape} assembly of the loop and the {word[-sign]} sign the "
                f"{other} one, its mirror image about the line through the coupler's pin and the rocker's "
                f"fixed pivot; each keeps its name along the motion, for the two meet only at a dead point. "
                f"The figure shows the {shape} assembly."
            )
        )
    ]
