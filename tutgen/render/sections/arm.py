"""A serial arm's Denavit–Hartenberg table, typeset as a table, and the frame of each link it defines."""

from __future__ import annotations

from typing import Any

import sympy as sp

from tutgen.render.blocks import SolutionContext, display, long_decimals, para, prose, section
from tutgen.render.printer import TexPrinter

#: the transforms of the links are listed for arms up to this many links (each is a 4 × 4 matrix)
FRAMES_LISTED = 8

_HEADINGS = {
    "standard": ("\\theta_i", "d_i", "a_i", "\\alpha_i"),
    "modified": ("\\alpha_{i-1}", "a_{i-1}", "\\theta_i", "d_i"),
}

_INTRO = {
    "standard": (
        "The arm is given by its Denavit–Hartenberg table in the standard convention (Spong, Paul): "
        "frame $i$ follows from frame $i-1$ by $A_i = \\mathrm{Rot}_z(\\theta_i)\\,\\mathrm{Trans}_z(d_i)\\,"
        "\\mathrm{Trans}_x(a_i)\\,\\mathrm{Rot}_x(\\alpha_i)$, frame 0 being the base."
    ),
    "modified": (
        "The arm is given by its Denavit–Hartenberg table in the modified convention (Craig): frame $i$ "
        "follows from frame $i-1$ by $A_i = \\mathrm{Rot}_x(\\alpha_{i-1})\\,\\mathrm{Trans}_x(a_{i-1})\\,"
        "\\mathrm{Rot}_z(\\theta_i)\\,\\mathrm{Trans}_z(d_i)$, frame 0 being the base."
    ),
}


def arm_table(c: SolutionContext) -> dict[str, Any] | None:
    """The section "Denavit–Hartenberg table": the table (one row per link, the joint variables named) and
    each link's transform ``A_i`` from frame ``i-1`` to frame ``i``, both with the spec's names (the values
    of the data are in the problem's "Given"; a number written in the table is printed as a decimal)."""
    s, tex = c.s, c.tex
    table = s.arm
    if table is None or not table.rows:
        return None
    sec = section("Denavit–Hartenberg table", _INTRO[table.convention])
    headings = _HEADINGS[table.convention]
    cells = []
    for i, row in enumerate(table.rows, start=1):
        values = (
            (row.theta, row.d, row.a, row.alpha)
            if table.convention == "standard"
            else (row.alpha, row.a, row.theta, row.d)
        )
        cells.append(f"{i} & " + " & ".join(_entry(tex, v) for v in values))
    head = "i & " + " & ".join(headings)
    body = " \\\\ ".join(cells)
    sec["blocks"].append(display(f"\\begin{{array}}{{c|cccc}} {head} \\\\ \\hline {body} \\end{{array}}"))
    variables = [q.latex for q in s.coordinates]
    sec["blocks"].append(
        para(
            prose("The joint variables are $" + ", ".join(variables) + "$; every other entry is a constant of the arm.")
        )
    )
    if len(table.rows) <= FRAMES_LISTED:
        sec["blocks"].append(para(prose("The frame of each link, relative to the one before:")))
        frames = [f"A_{{{i + 1}}} = {tex(long_decimals(table.transform(i)))}" for i in range(len(table.rows))]
        for k in range(0, len(frames), 2):  # two a line where they fit (the layout stacks them if not)
            sec["blocks"].append(display(",\\quad ".join(frames[k : k + 2])))
    return sec


def _entry(tex: TexPrinter, value: sp.Expr) -> str:
    """A table entry: a multiple of π as a table prints it (``\\frac{\\pi}{2}``, ``-\\pi``), a long
    fraction of measured data as a decimal, anything else by the results' printer."""
    ratio = value / sp.pi
    if value != 0 and ratio.is_Rational:
        p, q = abs(int(ratio.p)), int(ratio.q)
        top = "\\pi" if p == 1 else f"{p}\\pi"
        return ("-" if ratio < 0 else "") + (top if q == 1 else f"\\frac{{{top}}}{{{q}}}")
    return tex(long_decimals(value))
