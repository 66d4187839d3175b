"""Issue 18's steady-motion section: the cyclic coordinates, the steady values of the others at the
held rates, where each exists, the generalized force the cyclic coordinates then need (and the
conserved momentum of a free one), and each steady motion's stability. The engine's values are in
``Derivation.analysis.steady`` (tutgen/engine/analysis/steady.py)."""

from __future__ import annotations

from typing import Any

import sympy as sp

from tutgen.engine.analysis import SteadyMotion, SteadyState
from tutgen.engine.steps import StepKind
from tutgen.render.blocks import Part, SolutionContext, display, math, para, section, strong, text
from tutgen.render.wording import engine_parts

__all__ = ["steady_motion"]

_REL = {"<=": "\\leq", ">=": "\\geq", "<": "<", ">": ">"}


def _names(c: SolutionContext, names: tuple[str, ...] | list[str]) -> str:
    coords = {q.name: q for q in c.s.coordinates}
    return ",\\ ".join(coords[n].latex for n in names)


def _rates(c: SolutionContext, st: SteadyMotion) -> str:
    coords = {q.name: q for q in c.s.coordinates}
    shown = []
    for name, rate in st.rates:
        qd = c.tex(coords[name].qd)
        value = c.tex(c.num(rate))
        unit = {"angle": "\\ \\mathrm{rad/s}", "length": "\\ \\mathrm{m/s}"}.get(coords[name].dimension or "", "")
        unit = unit if c.num(rate).is_number else ""
        shown.append(qd if value == qd else f"{qd} = {value}{unit}")
    return ",\\ ".join(shown)


def _held(c: SolutionContext, st: SteadyMotion) -> list[Part]:
    """Which stability analysis is made, and why: the rate held (driven) or the momentum (free)."""
    if st.held == "momentum":
        return [
            text("Nothing drives "),
            math(_names(c, st.free)),
            text(
                ", so a disturbance keeps its momentum, not its rate: the small motions of the others are "
                "those of Routh's reduction, with the momentum held and the rate's change eliminated."
            ),
        ]
    if st.held == "rate":
        return [
            text("The drive of "),
            math(_names(c, [n for n, _ in st.rates])),
            text(" holds its rate, so the small motions of the others are linearised with the rate held."),
        ]
    return [
        text("The driven coordinates keep their rate and the free ones "),
        math(_names(c, st.free)),
        text(" their momentum (Routh's reduction) in the small motions of the others."),
    ]


def _verdict(c: SolutionContext, state: SteadyState) -> list[Part]:
    label = "Stable under a condition" if state.verdict == "conditional" else state.verdict.capitalize()
    return [strong(label), text(": "), *engine_parts(f"{state.reason}.", c.tex)]


def _state(
    c: SolutionContext, st: SteadyMotion, state: SteadyState, shared: bool, label: str | None = None
) -> list[dict[str, Any]]:
    """One steady motion: its values, where it exists, what it needs (unless ``shared``: said once for
    all), its conserved momentum and its stability. ``label`` leads the line of its values ("Steady
    motion 2: theta = pi"), so that it is never a heading left alone at the foot of a page."""
    tex, num = c.tex, c.num
    coords = {q.name: q for q in c.s.coordinates}
    blocks: list[dict[str, Any]] = []
    if state.at:
        anywhere = "\\text{any}"
        at = ",\\ ".join(f"{coords[n].latex} = {anywhere if n in st.free_others else tex(num(v))}" for n, v in state.at)
        blocks.append(para(strong(label), text(": "), math(at), text(".")) if label else display(at))
    elif label:
        blocks.append(para(strong(label)))
    if state.exists_where:
        shown = ",\\quad ".join(tex(x) for x in state.exists_where)
        trig = "a cosine" if any(v.has(sp.acos) for _, v in state.at) else "a sine"
        parts: list[Part] = [text("It exists only where "), math(shown), text(f", as {trig} lies in [−1, 1]")]
        if state.exists is not None:
            here = ",\\quad ".join(f"{tex(num(x.lhs))} {_REL[x.rel_op]} {tex(num(x.rhs))}" for x in state.exists_where)
            parts += [text("; here "), math(here)]
        blocks.append(para(*parts, text(".")))
        if state.exists is False:
            blocks.append(
                para(strong("At the given values it does not exist"), text(": there is no such steady motion."))
            )
            return blocks
    if not shared:
        blocks += _needs(c, st, state)
    blocks += _conserved(c, st, state)
    return blocks + _stability(c, state)


def _needs(c: SolutionContext, st: SteadyMotion, state: SteadyState) -> list[dict[str, Any]]:
    """The generalized force each held coordinate needs, and the input that gives it."""
    tex, num = c.tex, c.num
    coords = {q.name: q for q in c.s.coordinates}
    blocks: list[dict[str, Any]] = []
    for name, value in state.required:
        q = coords[name]
        blocks.append(display(f"Q_{{{q.latex}}} = (H\\ddot q + C + G)_{{{q.latex}}} = {tex(num(value))}"))
    for u, value in state.inputs:
        blocks.append(para(text("so the drive gives "), math(f"{tex(u)} = {tex(num(value))}"), text(".")))
    return blocks


def _conserved(c: SolutionContext, st: SteadyMotion, state: SteadyState) -> list[dict[str, Any]]:
    tex, num = c.tex, c.num
    coords = {q.name: q for q in c.s.coordinates}
    blocks: list[dict[str, Any]] = []
    for name, value in state.momenta:
        q = coords[name]
        if name in st.free:
            blocks.append(
                para(
                    math(q.latex),
                    text(" is free ("),
                    math(f"Q_{{{q.latex}}} = 0"),
                    text("), so its momentum is conserved: "),
                    math(f"p_{{{q.latex}}} = \\partial L/\\partial {tex(q.qd)} = {tex(num(value))}"),
                    text("."),
                )
            )
    return blocks


def _stability(c: SolutionContext, state: SteadyState) -> list[dict[str, Any]]:
    tex, num = c.tex, c.num
    blocks: list[dict[str, Any]] = []
    if state.verdict == "neutral":
        blocks.append(para(*_verdict(c, state)))
        return blocks
    if state.mass.shape[0] and state.mass != sp.zeros(*state.mass.shape):
        # at a pole the matrices are those of the rest state on the axis, not of Routh's reduction
        sub = "" if state.pole else "_r"
        lines = [f"M{sub} = {_matrix(c, num(state.mass))}"]
        if state.damping != sp.zeros(*state.damping.shape):
            lines.append(f"D{sub} = {_matrix(c, num(state.damping))}")
        lines.append(f"K{sub} = {_matrix(c, num(state.stiffness))}")
        if state.pole:
            blocks.append(para(text("At rest on the axis, the linear model of the others has")))
        blocks.append(display(",\\quad ".join(lines)))
    if state.eigenvalues is not None:
        shown = ",\\ ".join(_complex(z) for z in state.eigenvalues)
        oscillating = [z for z in state.eigenvalues if z.real == 0 and z.imag > 0]
        extra = (
            [
                text(" (small oscillations at "),
                math(", ".join(f"{z.imag:.4g}" for z in oscillating) + "\\ \\mathrm{rad/s}"),
                text(")"),
            ]
            if oscillating
            else []
        )
        blocks.append(
            para(
                text(
                    "The eigenvalues of the linear model at rest: "
                    if state.pole
                    else "The eigenvalues of the reduced model: "
                ),
                math(f"\\lambda = {shown}\\ \\mathrm{{s^{{-1}}}}"),
                *extra,
                text("."),
            )
        )
    if state.verdict == "conditional" and state.stable_where:
        where = ",\\quad ".join(tex(num(x)) for x in state.stable_where)
        blocks.append(
            para(
                strong("Stable under a condition"),
                text(
                    ": the sign of K depends on the parameters; it is positive definite, and this steady "
                    "motion stable, where "
                ),
                math(where),
                text("."),
            )
        )
        return blocks
    blocks.append(para(*_verdict(c, state)))
    if state.stable_where:
        where = ",\\quad ".join(tex(num(x)) for x in state.stable_where)
        blocks.append(para(text("It is stable where "), math(where), text(".")))
    return blocks


def _matrix(c: SolutionContext, m: sp.MatrixBase) -> str:
    """A reduced matrix with each entry in the engine's textbook form (steady.textbook): the printer's
    teacher's order would expand the collected brackets of a factored fraction again."""
    rows = [" & ".join(_entry(c, e) for e in m.row(i)) for i in range(m.rows)]
    return r"\begin{bmatrix}" + r" \\ ".join(rows) + r"\end{bmatrix}"


def _entry(c: SolutionContext, e: sp.Expr) -> str:
    num, den = sp.fraction(e)
    if (
        e.is_number
        or isinstance(e, sp.Add)
        or not any(isinstance(f, sp.Add) for f in (*sp.Mul.make_args(num), *sp.Mul.make_args(den)))
    ):
        return c.tex(e)
    top, bottom = _product(c, num), _product(c, den)
    if den == 1:
        return top
    sign = ""
    if top.startswith("- "):
        sign, top = "- ", top[2:]
    return f"{sign}\\dfrac{{{top}}}{{{bottom}}}"  # full size inside a matrix


def _product(c: SolutionContext, p: sp.Expr) -> str:
    """A product factor by factor, each sum in brackets with its positive terms first."""
    factors = list(sp.Mul.make_args(p))
    coefficient = sp.Mul(*[f for f in factors if f.is_number])
    plain = sp.Mul(*[f for f in factors if not f.is_number and not isinstance(f, sp.Add)])
    sums = [f for f in factors if isinstance(f, sp.Add)]
    head = coefficient * plain
    text = "" if head == 1 else "- " if head == -1 else c.tex(head)
    if text and text != "- ":
        text += " "
    for f in sums:
        text += "\\left(" + _sum(c, f) + "\\right) "
    return text.strip() or "1"


def _sum(c: SolutionContext, f: sp.Expr) -> str:
    terms = sorted(sp.Add.make_args(f), key=lambda t: t.could_extract_minus_sign())
    out = ""
    for t in terms:
        negative = t.could_extract_minus_sign()
        body = c.tex(-t if negative else t)
        out += (" - " if negative else (" + " if out else "")) + body
    return out.strip()


def _complex(z: complex) -> str:
    def n(x: float) -> str:
        return f"{x:.4g}"

    if z.imag == 0:
        return n(z.real)
    if z.real == 0:
        return f"\\pm {n(abs(z.imag))}\\,i"
    return f"{n(z.real)} \\pm {n(abs(z.imag))}\\,i"


def steady_motion(c: SolutionContext) -> dict[str, Any] | None:
    d = c.d
    a = d.analysis
    if a is None or a.steady is None or not d.has_step(StepKind.STEADY_MOTION):
        return None
    st = a.steady
    sec = section(
        "Steady motion",
        "A coordinate that appears in none of $H$, $G$ and $Q$ is cyclic. With its rate held constant and the "
        "other coordinates at rest ($\\dot q_s = 0$, $\\ddot q = 0$), the equations of motion of the others "
        "become equations in their values alone.",
    )
    blocks = sec["blocks"]
    if not st.rates:
        blocks.append(
            para(text("This system has no cyclic coordinate: it has no steady motion other than its equilibria."))
        )
        return sec
    blocks.append(
        para(
            text("Cyclic: "),
            math(_names(c, st.cyclic)),
            text(". Held at "),
            math(_rates(c, st)),
            text(", with "),
            math(_names(c, st.others)) if st.others else text("no other coordinate"),
            text(" at rest." if st.others else "."),
        )
    )
    coords = {q.name: q for q in c.s.coordinates}
    for name, row in zip(st.others, st.residual, strict=True):
        q = coords[name]
        blocks.append(display(f"(C + G - Q)_{{{q.latex}}} = {c.tex(c.num(row))} = 0"))
    if st.method == "numeric":
        blocks.append(para(text("sympy finds no closed form: the roots below were found numerically in one turn.")))
    if not st.states:
        blocks.append(para(strong("No steady motion"), text(f": {st.remark}." if st.remark else ".")))
        return sec
    if st.others:
        blocks.append(para(*_held(c, st)))
    existing = [x for x in st.states if x.exists is not False]
    shared = len({(x.required, x.inputs) for x in existing}) == 1 and len(st.states) > 1
    if shared:
        blocks += [para(text("At every steady motion below, the held coordinates need:")), *_needs(c, st, existing[0])]
    for i, state in enumerate(st.states, start=1):
        label = f"Steady motion {i}" if len(st.states) > 1 else None
        blocks += _state(c, st, state, shared, label)
    angles = [n for n in st.others if coords[n].dimension == "angle" and n not in st.free_others]
    if angles and st.states:
        blocks.append(para(text("Each angle stands for its family, plus any multiple of "), math("2\\pi"), text(".")))
    return sec
