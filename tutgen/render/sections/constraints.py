"""The constraints (issue 21): the constraint equations and the velocity analysis, the equations with
Lagrange's multipliers (lambda solved and what force it is), and the equations reduced to the independent
coordinates."""

from __future__ import annotations

from typing import Any

import sympy as sp

from tutgen.engine.steps import StepKind
from tutgen.model.system import ConstraintKind
from tutgen.render.blocks import SolutionContext, boxed, display, math, para, section, text


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
