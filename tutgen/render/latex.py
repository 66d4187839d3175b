"""Printing sympy results as LaTeX the way a person writes them: dotted rates, Greek names."""

from __future__ import annotations

import sympy as sp

from tutgen.model.system import System

_SPECIALS = {
    "\\": r"\textbackslash{}",
    "{": r"\{",
    "}": r"\}",
    "$": r"\$",
    "&": r"\&",
    "#": r"\#",
    "^": r"\^{}",
    "_": r"\_",
    "%": r"\%",
    "~": r"\textasciitilde{}",
}


def latex_escape(text: str) -> str:
    """Escape user text so that LaTeX shows it verbatim (no command in it runs)."""
    return "".join(_SPECIALS.get(ch, ch) for ch in text)


class TexPrinter:
    """sympy's LaTeX printer with the spec's symbol names: theta1_dot -> \\dot{\\theta}_{1}."""

    def __init__(self, system: System) -> None:
        names: dict[sp.Symbol, str] = {}
        for p in system.parameters:
            names[p.symbol] = p.latex
        for c in system.coordinates:
            names[c.q] = c.latex
            names[c.qd] = _dotted(c.latex, r"\dot")
            names[c.qdd] = _dotted(c.latex, r"\ddot")
        self.names = names

    def __call__(self, expr: object) -> str:
        if isinstance(expr, sp.MatrixBase):
            rows = [" & ".join(self(e) for e in expr.row(i)) for i in range(expr.rows)]
            return r"\begin{bmatrix}" + r" \\ ".join(rows) + r"\end{bmatrix}"
        return sp.latex(expr, symbol_names=self.names)


def _dotted(latex: str, accent: str) -> str:
    """Put the dot on the base letter, not on the subscript: \\theta_{1} -> \\dot{\\theta}_{1}."""
    base, sep, sub = latex.partition("_")
    return f"{accent}{{{base}}}{sep}{sub}"
