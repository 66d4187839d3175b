"""The numerical simulation (``ask: [simulation]``): the run of the spec's `simulate` section, its
plots and the energy check, from ``Derivation.simulation`` (made by tutgen/sim/solution.py before
rendering; this module only lays it out).

A plot is a block ``{"kind": "plot", "file": ..., "tex_name": ..., "caption": ..., "tex_width": ...}``:
``file`` the PNG's name beside a Markdown or LaTeX solution, ``tex_name`` its name inside tutgen's own
PDF compile (:func:`tex_files`; a .tex compiled elsewhere falls back to ``file``), ``tex_width`` the
width LaTeX sets it at.
"""

from __future__ import annotations

import math as pymath
from typing import Any

from tutgen.engine.steps import StepKind
from tutgen.model.simulation import SimulationSummary
from tutgen.render.blocks import Block, SolutionContext, math, para, section, text

__all__ = ["CAPTIONS", "TEX_NAMES", "number_tex", "simulation", "simulation_json", "tex_files"]

#: the plots' names inside tutgen's own PDF compile folder (tutgen.render.pdf.INPUT_NAME), by kind
TEX_NAMES = {"plot": "simulation-plot.png", "snapshots": "simulation-snapshots.png"}

CAPTIONS = {
    "plot": "the coordinates, their rates and the energies over time",
    "snapshots": "the mechanism at equally spaced instants",
}


def tex_files(summary: SimulationSummary) -> dict[str, bytes]:
    """The plots by their names in the compile folder, for :func:`tutgen.render.pdf.compile_pdf`."""
    return {TEX_NAMES[p.kind]: p.png for p in summary.plots}


def number_tex(x: float, digits: int = 4) -> str:
    """A float as a person writes it: 4 significant digits, ``3.1 \\cdot 10^{-11}`` for the very
    small and very large, no ``-0``."""
    if x == 0 or not pymath.isfinite(x):
        return "0" if x == 0 else str(x)
    exponent = pymath.floor(pymath.log10(abs(x)))
    if -3 <= exponent < 5:
        shown = f"{x:.{max(digits - 1 - exponent, 0)}f}"
        if "." in shown:
            shown = shown.rstrip("0").rstrip(".")
        return "0" if shown in ("-0", "0") else shown
    mantissa = f"{x / 10**exponent:.{digits - 1}f}".rstrip("0").rstrip(".")
    return f"10^{{{exponent}}}" if mantissa == "1" else f"{mantissa} \\cdot 10^{{{exponent}}}"


#: the plots' widths in a LaTeX document: the time plot is tall (q, q_dot, E stacked), the strip wide
TEX_WIDTHS = {"plot": "0.7\\linewidth", "snapshots": "\\linewidth"}


def _plot(name: str, kind: str) -> Block:
    return {
        "kind": "plot",
        "file": name,
        "tex_name": TEX_NAMES[kind],
        "caption": CAPTIONS[kind],
        "tex_width": TEX_WIDTHS[kind],
    }


def simulation(c: SolutionContext) -> dict[str, Any] | None:
    d, s, tex = c.d, c.s, c.tex
    run = d.simulation
    if run is None or not d.has_step(StepKind.SIMULATION):
        return None
    coords = {q.name: q for q in s.coordinates}
    solved = "solved for $\\ddot q = H^{-1}(Q - C - G)$"
    if s.is_constrained:  # tutgen/sim/constrained.py: the multipliers' system, Baumgarte-stabilised
        solved = (
            "$H\\ddot q - A^{\\mathsf T}\\lambda = Q - C - G$ with $A\\ddot q + \\dot A\\dot q = 0$, "
            "solved together for $\\ddot q$ and $\\lambda$ (Baumgarte-stabilised)"
        )
    sec = section(
        "Numerical simulation",
        f"The equations of motion, {solved}, are integrated numerically "
        f"from $t = {number_tex(run.t_start)}$ to $t = {number_tex(run.t_end)}\\,\\mathrm{{s}}$ "
        f"({run.method}, relative tolerance ${number_tex(run.rtol)}$, {run.steps} steps), "
        "with the data given."
        + (" The dependent coordinates and rates start where the constraints put them." if s.is_constrained else ""),
    )
    start: list[Any] = [text("Initial state: ")]
    for i, (name, q0, qd0) in enumerate(run.initial):
        sep = ", " if i else ""
        q = coords[name]
        start += [text(sep), math(f"{q.latex}(0) = {number_tex(q0)},\\ {tex(q.qd)}(0) = {number_tex(qd0)}")]
    sec["blocks"].append(para(*start, text(".")))
    if s.simulation is not None and s.simulation.inputs:
        params = {p.name: p for p in s.parameters}
        shown = [f"{params[k].latex} = {tex(c.num(v))}" for k, v in s.simulation.inputs if k in params]
        sec["blocks"].append(para(text("Inputs: "), math(",\\quad ".join(shown)), text(".")))
    for p in run.plots:
        sec["blocks"].append(_plot(p.name, p.kind))
    if run.stopped is not None:
        sec["blocks"].append(
            para(
                text("The integration stopped early, at "),
                math(f"t = {number_tex(run.t_reached)}\\,\\mathrm{{s}}"),
                text(f": {run.stopped}."),
            )
        )
    end = [text("At "), math(f"t = {number_tex(run.t_reached)}\\,\\mathrm{{s}}"), text(": ")]
    for i, (name, q1, qd1) in enumerate(run.final):
        q = coords[name]
        end += [text(", " if i else ""), math(f"{q.latex} = {number_tex(q1)},\\ {tex(q.qd)} = {number_tex(qd1)}")]
    sec["blocks"].append(para(*end, text(".")))
    energy = f"E = T + U = {number_tex(run.energy_initial)}\\,\\mathrm{{J}}"
    if run.conservative and run.drift is not None:
        verdict = "passed" if run.check_passed else "FAILED"
        sec["blocks"].append(
            para(
                text("Without dissipation or inputs the total energy "),
                math(energy),
                text(" must stay constant; over the run its relative drift is "),
                math(number_tex(run.drift, 2)),
                text(" against an allowed 100 times the integrator's tolerance, "),
                math(number_tex(run.tolerance, 2)),
                text(f": {verdict}."),
            )
        )
    else:
        sec["blocks"].append(
            para(
                text("The total energy goes from "),
                math(energy),
                text(" to "),
                math(f"{number_tex(run.energy_final)}\\,\\mathrm{{J}}"),
                text(": dissipation and inputs change it, so it is not a check here."),
            )
        )
    return sec


def simulation_json(summary: SimulationSummary) -> dict[str, Any]:
    """The run in the JSON output (``"simulation"``, docs/json-output.md): where the plots are (their
    names beside the .json), the integrator, the initial and final states and the energy check."""
    return {
        "files": {p.kind: p.name for p in summary.plots},
        "interval": [summary.t_start, summary.t_end],
        "reached": summary.t_reached,
        "integrator": {"method": summary.method, "rtol": summary.rtol, "atol": summary.atol, "steps": summary.steps},
        "samples": summary.samples,
        "inputs": dict(summary.inputs),
        "initial": {name: {"q": q, "qd": qd} for name, q, qd in summary.initial},
        "final": {name: {"q": q, "qd": qd} for name, q, qd in summary.final},
        "energy": {
            "initial": summary.energy_initial,
            "final": summary.energy_final,
            "conservative": summary.conservative,
            "drift": summary.drift,
            "tolerance": summary.tolerance,
            "check_passed": summary.check_passed,
        },
        "stopped": summary.stopped,
    }
