"""Issue 18's sections after the equations of motion: the equilibria, each classified, and the linear
model about an equilibrium (M, D, K, B, the state space, the characteristic polynomial, the modes and the
verdict on stability). The engine's values are in ``Derivation.analysis`` (tutgen/engine/analysis/)."""

from __future__ import annotations

from typing import Any

import sympy as sp

from tutgen.engine.analysis import LinearModel, Mode
from tutgen.engine.analysis.equilibria import existence
from tutgen.engine.analysis.linear import S
from tutgen.engine.steps import StepKind
from tutgen.render.blocks import Part, SolutionContext, boxed, display, math, para, section, strong, text
from tutgen.render.wording import engine_parts

__all__ = ["equilibria", "linearization"]


def _at(c: SolutionContext, values: tuple[tuple[str, sp.Expr], ...], free: tuple[str, ...] = ()) -> str:
    """``x = 0,\\ \\theta = \\pi`` (a coordinate of ``free`` as "any")."""
    coords = {q.name: q for q in c.s.coordinates}
    shown = []
    for name, v in values:
        value = "\\text{any}" if name in free else c.tex(c.num(v))
        shown.append(f"{coords[name].latex} = {value}")
    return ",\\ ".join(shown)


def _verdict(c: SolutionContext, m: LinearModel) -> list[Part]:
    """The verdict in bold, then its reason (tutgen's sentence, its names and K, D typeset)."""
    label = "Stable under a condition" if m.verdict == "conditional" else m.verdict.capitalize()
    return [strong(label), text(": "), *engine_parts(f"{m.reason}.", c.tex)]


def _where(c: SolutionContext, m: LinearModel) -> list[dict[str, Any]]:
    """The condition of stability of a symbolic equilibrium, as inequalities."""
    if not m.stable_where:
        return []
    shown = ",\\quad ".join(c.tex(c.num(x)) for x in m.stable_where)
    return [para(text("It is stable where")), display(shown)]


def equilibria(c: SolutionContext) -> dict[str, Any] | None:
    d, s, tex, num = c.d, c.s, c.tex, c.num
    a = d.analysis
    if a is None or a.equilibria is None or not d.has_step(StepKind.EQUILIBRIA):
        return None
    eq = a.equilibria
    sec = section(
        "Equilibria",
        "At rest $\\dot q = \\ddot q = 0$, so $H(q)\\ddot q + C(q,\\dot q) + G(q) = Q$ reduces to "
        "$G(q) - Q(q, 0) = 0$.",
    )
    held = s.analysis.inputs if s.analysis is not None else ()
    if held:
        inputs = ",\\ ".join(f"{tex(u)} = {tex(num(v))}" for u, v in held)
        sec["blocks"].append(para(text("The inputs are held at "), math(inputs), text(".")))
    sec["blocks"].append(display(f"G(q) - Q(q, 0) = {tex(num(eq.residual))} = 0"))
    coords = {q.name: q for q in s.coordinates}
    if eq.free:
        names: list[Any] = []
        for i, n in enumerate(eq.free):  # "ψ", "ψ and φ", "x, y and z"
            if i:
                names.append(text(" and " if i == len(eq.free) - 1 else ", "))
            names.append(math(coords[n].latex))
        one = len(eq.free) == 1
        sec["blocks"].append(
            para(
                text("The equations do not contain "),
                *names,
                text(
                    ": the system can rest at any value of it, so its equilibria are not isolated along it."
                    if one
                    else ": the system can rest at any value of them, so its equilibria are not isolated along them."
                ),
            )
        )
    if eq.method == "numeric":
        sec["blocks"].append(
            para(
                text(
                    "sympy finds no closed form: the roots below are every root found numerically with angles "
                    "in one turn and the other coordinates within ±10 (SI units)."
                )
            )
        )
    if not eq.solutions:
        sec["blocks"].append(para(text(eq.remark or "There is no equilibrium.")))
        return sec
    angles = [q for q in s.coordinates if q.dimension == "angle" and q.name not in eq.free]
    for i, (sol, m) in enumerate(zip(eq.solutions, a.classified, strict=False), start=1):
        sec["blocks"].append(display(f"q_{{0,{i}}}:\\quad {_at(c, sol, eq.free)}"))
        exists = [x for _, v in sol for x in existence(v)]
        if exists:
            shown = ",\\quad ".join(tex(num(x)) for x in exists)
            sec["blocks"].append(para(text("It exists only where "), math(shown), text(" (a real angle).")))
        k = "\\left.\\frac{\\partial (G - Q)}{\\partial q}\\right|_{q_{0," + str(i) + "}}"
        sec["blocks"].append(display(f"K = {k} = {tex(num(m.stiffness))}"))
        sec["blocks"].append(para(*_verdict(c, m)))
        sec["blocks"] += _where(c, m)
    if angles:
        names = [math(q.latex) for q in angles]
        sec["blocks"].append(
            para(
                text("Each value of "),
                *names,
                text(" stands for its family, plus any multiple of "),
                math("2\\pi"),
                text("."),
            )
        )
    return sec


def _column(c: SolutionContext, order: int) -> str:
    """The column of the small deviations, or of their rates (``order`` 1) or accelerations (2)."""
    entries = [f"\\delta {c.tex((q.q, q.qd, q.qdd)[order])}" for q in c.s.coordinates]
    return "\\begin{bmatrix}" + " \\\\ ".join(entries) + "\\end{bmatrix}"


def _number(x: float) -> str:
    return f"{x:.4g}".replace("e", "\\times 10^{") + ("}" if "e" in f"{x:.4g}" else "")


def _complex(z: complex) -> str:
    re, im = _number(z.real), _number(abs(z.imag))
    if z.imag == 0:
        return re
    if z.real == 0:
        return f"{'-' if z.imag < 0 else ''}{im}\\,i"
    return f"{re} {'-' if z.imag < 0 else '+'} {im}\\,i"


def _mode(i: int, mode: Mode) -> list[Part]:
    """One eigenvalue (of a complex pair, the pair) and what it means: a neutral motion (0), a growing or
    decaying one (real), or an oscillation with its natural frequency and damping ratio."""
    lam = mode.eigenvalue
    if lam.imag:
        re = f"{_number(lam.real)} " if lam.real else ""
        shown = f"{re}\\pm {_number(lam.imag)}\\,i"
    else:
        shown = _number(lam.real)
    parts: list[Part] = [math(f"\\lambda_{{{i}}} = {shown}\\ \\mathrm{{s^{{-1}}}}")]
    if mode.damping_ratio is None:
        parts.append(text(": a neutral motion (the coordinate drifts, nothing restores it)"))
    elif not lam.imag:
        grows = "grows" if lam.real > 0 else "dies away"
        parts += [
            text(f": real, so the motion {grows} as "),
            math(f"e^{{\\lambda_{{{i}}} t}}"),
            text(", time constant "),
            math(f"1/|\\lambda_{{{i}}}| = {_number(1 / abs(lam.real))}\\ \\mathrm{{s}}"),
        ]
    else:
        parts += [
            text(": an oscillation, "),
            math(
                f"\\omega_{{n}} = |\\lambda_{{{i}}}| = {_number(mode.natural_frequency)}\\ \\mathrm{{rad/s}}"
                f" = {_number(mode.frequency_hz)}\\ \\mathrm{{Hz}}"
            ),
            text(", damping ratio "),
            math(f"\\zeta = -\\operatorname{{Re}}\\lambda_{{{i}}}/|\\lambda_{{{i}}}| = {_number(mode.damping_ratio)}"),
        ]
    shape = "\\begin{bmatrix}" + " \\\\ ".join(_complex(x) for x in mode.shape) + "\\end{bmatrix}"
    parts += [text("; mode shape "), math(f"\\delta q \\propto {shape}"), text(".")]
    return parts


def _polynomial(c: SolutionContext, p: sp.Expr) -> str:
    """A polynomial in s in descending powers (s^4 first), each coefficient as printed."""
    expr = sp.expand(c.num(p))
    poly = sp.Poly(expr, S)
    terms = []
    for (k,), coef in zip(poly.monoms(), poly.coeffs(), strict=True):
        terms.append(c.tex(coef * S**k) if coef.free_symbols or k == 0 else c.tex(sp.Mul(coef, S**k)))
    out = terms[0]
    for t in terms[1:]:
        out += f" - {t[1:].lstrip()}" if t.startswith("-") else f" + {t}"
    return out


def _model(c: SolutionContext, m: LinearModel, number: int | None) -> list[dict[str, Any]]:
    tex, num = c.tex, c.num
    blocks: list[dict[str, Any]] = []
    if number is not None:  # words only: a subheading is plain text (the maths follows in the paragraph)
        blocks.append({"kind": "subheading", "text": f"Equilibrium {number}"})
    blocks.append(
        para(
            text("About "),
            math(_at(c, m.about)),
            text(", with "),
            math("q = q_0 + \\delta q"),
            text(", the first-order terms of the equations of motion are"),
        )
    )
    shown = [
        f"M = H(q_0) = {tex(num(m.mass))}",
        f"D = \\left.\\frac{{\\partial (C - Q)}}{{\\partial \\dot q}}\\right|_0 = {tex(num(m.damping))}",
        f"K = \\left.\\frac{{\\partial (G - Q)}}{{\\partial q}}\\right|_0 = {tex(num(m.stiffness))}",
    ]
    if m.inputs:
        u = "\\begin{bmatrix}" + " \\\\ ".join(tex(x) for x in m.inputs) + "\\end{bmatrix}"
        shown.append(f"B = \\frac{{\\partial Q}}{{\\partial u}} = {tex(num(m.input_matrix))},\\ u = {u}")
    for line in shown:
        blocks.append(display(line))
    du = "\\begin{bmatrix}" + " \\\\ ".join(f"\\delta {tex(u)}" for u in m.inputs) + "\\end{bmatrix}"
    rhs = f"{tex(num(m.input_matrix))}{du}" if m.inputs else "0"
    blocks.append(
        boxed(
            f"{tex(num(m.mass))}{_column(c, 2)} + {tex(num(m.damping))}{_column(c, 1)}"
            f" + {tex(num(m.stiffness))}{_column(c, 0)} = {rhs}"
        )
    )
    if m.state_matrix.shape == (0, 0):  # M singular at this equilibrium: no state space; the verdict says why
        blocks.append(para(*_verdict(c, m)))
        return blocks
    blocks.append(
        para(
            text("With the state "),
            math("\\xi = [\\delta q,\\ \\delta\\dot q]"),
            text(", "),
            math("\\dot \\xi = A \\xi + B_\\xi\\,\\delta u") if m.inputs else math("\\dot \\xi = A \\xi"),
            text(", "),
            math("A = \\begin{bmatrix} 0 & I \\\\ -M^{-1}K & -M^{-1}D \\end{bmatrix}"),
            text(":"),
        )
    )
    state = f"A = {tex(num(m.state_matrix))}"
    if m.inputs:
        state += f",\\quad B_\\xi = {tex(num(m.state_input))}"
    blocks.append(display(state))
    if m.characteristic is not None:
        blocks.append(
            para(text("The characteristic polynomial, whose roots are the eigenvalues of "), math("A"), text(":"))
        )
        blocks.append(display(f"\\det(M s^2 + D s + K) = {_polynomial(c, m.characteristic)} = 0"))
    if m.modes is not None:
        for i, mode in enumerate(m.modes, start=1):
            blocks.append(para(*_mode(i, mode)))
    elif len(m.conditions) > 1:
        minors = ",\\quad ".join(f"\\Delta_{{{i}}} = {tex(num(x))}" for i, x in enumerate(m.conditions, start=1))
        blocks.append(para(text("The leading minors of "), math("K"), text(":")))
        blocks.append(display(minors))
    blocks.append(para(*_verdict(c, m)))
    blocks += _where(c, m)
    return blocks


def linearization(c: SolutionContext) -> dict[str, Any] | None:
    d = c.d
    a = d.analysis
    if a is None or not a.linear or not d.has_step(StepKind.LINEARIZATION):
        return None
    sec = section(
        "Linearisation",
        "Small motions about an equilibrium $q_0$ obey $M\\,\\delta\\ddot q + D\\,\\delta\\dot q + K\\,\\delta q "
        "= B\\,\\delta u$, the first-order expansion of the equations of motion at rest.",
    )
    for i, m in enumerate(a.linear, start=1):
        sec["blocks"] += _model(c, m, None if len(a.linear) == 1 else i)
    return sec
