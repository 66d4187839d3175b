"""Printing sympy results as LaTeX the way a person writes them: dotted rates, Greek names,
``\\sin\\theta`` rather than ``\\sin{\\left(\\theta \\right)}``, four significant figures."""

from __future__ import annotations

import math
import re

import sympy as sp
from sympy.printing.latex import LatexPrinter

from tutgen.model.system import System

SIGNIFICANT_FIGURES = 4


def format_number(x: float, figures: int = SIGNIFICANT_FIGURES) -> str:
    """A number as a person writes it: 4 significant figures, trailing zeros dropped,
    ``6.131 \\times 10^{-3}`` below 0.01 and from 10^5 up."""
    if x == 0 or not math.isfinite(x):
        return "0" if x == 0 else str(x)
    exponent = math.floor(math.log10(abs(x)))
    mantissa = round(x / 10**exponent, figures - 1)
    if abs(mantissa) >= 10:  # 9.9996 rounds up to 10.00
        mantissa /= 10
        exponent += 1
    if -2 <= exponent < 5:
        decimals = max(figures - 1 - exponent, 0)
        text = f"{round(x, decimals):.{decimals}f}"
        return _trim(text)
    return f"{_trim(f'{mantissa:.{figures - 1}f}')} \\times 10^{{{exponent}}}"


def _trim(text: str) -> str:
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


class _Printer(LatexPrinter):
    def _print_Float(self, expr: sp.Float) -> str:
        return format_number(float(expr))

    def _print_Mul(self, expr: sp.Mul) -> str:
        """No ``1.0 x``: a unit float coefficient is left out. (Replacing it by 1 in the expression
        does not stick: sympy caches and compares Float(1.0) and 1 as the same.)"""
        coeff, rest = expr.as_coeff_Mul()
        if isinstance(coeff, sp.Float) and abs(float(coeff)) == 1.0 and rest != 1:
            body = self._print(rest)
            return body if float(coeff) > 0 else "- " + body
        return super()._print_Mul(expr)


_TRIG = re.compile(r"\\(sin|cos|tan|cot|sec|csc)(\^\{[^{}]*\})?\{\\left\(")
_ATOM = re.compile(r"^(\\[A-Za-z]+|[A-Za-z])(_\{[A-Za-z0-9]+\}|_[A-Za-z0-9])?$")


def tidy_functions(tex: str) -> str:
    """``\\sin{\\left(\\theta \\right)}`` -> ``\\sin\\theta``; a longer argument keeps plain parentheses:
    ``\\cos{\\left(\\theta_{1} + \\theta_{2} \\right)}`` -> ``\\cos(\\theta_{1} + \\theta_{2})``."""
    out: list[str] = []
    pos = 0
    while (m := _TRIG.search(tex, pos)) is not None:
        # the argument runs to the brace that closes the one opened before \left(
        depth, i = 1, m.end()
        while i < len(tex) and depth:
            depth += {"{": 1, "}": -1}.get(tex[i], 0) if tex[i - 1] != "\\" else 0
            i += 1
        inner = tex[m.end() : i - 1]
        if not inner.endswith("\\right)"):
            out.append(tex[pos : m.end()])
            pos = m.end()
            continue
        arg = tidy_functions(inner[: -len("\\right)")].strip())
        head = f"\\{m.group(1)}{m.group(2) or ''}"
        if _ATOM.match(arg):
            out.append(tex[pos : m.start()] + head + ("" if arg.startswith("\\") else " ") + arg)
        else:
            out.append(tex[pos : m.start()] + f"{head}({arg})")
        pos = i
    out.append(tex[pos:])
    return "".join(out)


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
        if isinstance(expr, float):
            expr = sp.Float(expr)
        return tidy_functions(_Printer({"symbol_names": self.names}).doprint(expr))

    def equation(self, lhs: str, expr: object, rhs: str = "") -> str:
        """``lhs = expr`` (or ``expr = rhs`` when ``lhs`` is empty) on one line: where it breaks when it is
        too wide is decided by its typeset width when the display is laid out (tutgen.render.layout)."""
        head = f"{lhs} = " if lhs else ""
        tail = f" = {rhs}" if rhs else ""
        return f"{head}{self(expr)}{tail}"


def _dotted(latex: str, accent: str) -> str:
    """Put the dot on the base letter, not on the subscript: \\theta_{1} -> \\dot{\\theta}_{1}."""
    base, sep, sub = latex.partition("_")
    return f"{accent}{{{base}}}{sep}{sub}"
