"""Printing sympy results as LaTeX the way a person writes them: dotted rates, Greek names,
``\\sin\\theta`` rather than ``\\sin{\\left(\\theta \\right)}``, four significant figures."""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import TYPE_CHECKING

import sympy as sp
from sympy.printing.latex import LatexPrinter

from tutgen.model.system import System

if TYPE_CHECKING:
    from tutgen.engine.derivation import Derivation

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
    "<": r"\textless{}",
    ">": r"\textgreater{}",
    "|": r"\textbar{}",
}

SIGNIFICANT_FIGURES = 4
LINE_WIDTH = 70  # visible characters of a displayed formula before a long sum is broken


_GREEK = (
    "alpha beta gamma delta epsilon zeta eta theta iota kappa lambda mu nu xi omicron pi rho varsigma sigma "
    "tau upsilon phi chi psi omega"
).split()
# Unicode that pdflatex's utf8 input does not know, as maths in text (user text often has θ, ×, °)
_UNICODE = {chr(0x3B1 + i): f"\\ensuremath{{\\{name}}}" for i, name in enumerate(_GREEK) if name != "omicron"}
_UNICODE.update(
    {
        chr(0x391 + i): f"\\ensuremath{{\\{name.capitalize()}}}"
        for i, name in enumerate(_GREEK)
        if name in ("gamma", "delta", "theta", "lambda", "xi", "pi", "sigma", "upsilon", "phi", "psi", "omega")
    }
)
_UNICODE.update(
    {
        "\u03bf": "o",
        "\u00b5": r"\ensuremath{\mu}",
        "\u00d7": r"\ensuremath{\times}",
        "\u00b7": r"\ensuremath{\cdot}",
        "\u00b0": r"\ensuremath{^\circ}",
        "\u00b2": r"\textsuperscript{2}",
        "\u00b3": r"\textsuperscript{3}",
        "\u2212": r"\ensuremath{-}",
        "\u2248": r"\ensuremath{\approx}",
        "\u2264": r"\ensuremath{\le}",
        "\u2265": r"\ensuremath{\ge}",
        "\u00b1": r"\ensuremath{\pm}",
        "\u2192": r"\ensuremath{\to}",
        "\u2032": r"\ensuremath{'}",
    }
)


def latex_escape(text: str) -> str:
    """Escape user text so that LaTeX shows it verbatim (no command in it runs); Greek letters and
    common symbols become their maths equivalents, which pdflatex can typeset."""
    return "".join(_SPECIALS.get(ch) or _UNICODE.get(ch, ch) for ch in text)


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

    def equation(self, lhs: str, expr: object, rhs: str = "", width: int = LINE_WIDTH) -> str:
        """``lhs = expr`` (or ``expr = rhs`` when ``lhs`` is empty); a sum too long for one line is
        broken before a + or - into an ``aligned`` block, the way a person breaks it by hand (KaTeX,
        MathJax and amsmath all read it)."""
        lines = self.sum_lines(expr, width) if isinstance(expr, sp.Basic) else [self(expr)]
        tail = f" = {rhs}" if rhs else ""
        head = f"{lhs} = " if lhs else ""
        if len(lines) == 1:
            return f"{head}{lines[0]}{tail}"
        first = f"{lhs} &= {lines[0]}" if lhs else f"&{lines[0]}"
        body = r" \\ &\quad ".join([first, *lines[1:]])
        return f"\\begin{{aligned}}{body}{tail}\\end{{aligned}}"

    def sum_lines(self, expr: sp.Basic, width: int = LINE_WIDTH) -> list[str]:
        """The terms of a sum, printed as sympy orders them, gathered into lines of about ``width``
        visible characters; anything else is one line."""
        whole = self(expr)
        if not isinstance(expr, sp.Add) or visible_length(whole) <= width:
            return [whole]
        printer = _Printer({"symbol_names": self.names})
        lines: list[str] = []
        current = ""
        for i, term in enumerate(printer._as_ordered_terms(expr, order=None)):
            sign = ""
            if i and term.could_extract_minus_sign():
                sign, term = "- ", -term
            elif i:
                sign = "+ "
            piece = tidy_functions(printer._print(term))
            if printer._needs_add_brackets(term):
                piece = f"\\left({piece}\\right)"
            if current and visible_length(current + piece) > width:
                lines.append(current.rstrip())
                current = ""
            current += sign + piece + " "
        lines.append(current.rstrip())
        return lines


_BMATRIX = re.compile(r"\\begin\{bmatrix\}(.*?)\\end\{bmatrix\}")


def visible_length(tex: str) -> int:
    """Roughly how many characters a formula shows: a command is one glyph, braces and spaces none,
    a fraction about half its parts."""
    tex = _BMATRIX.sub(lambda m: max(m.group(1).split("\\\\"), key=len), tex)  # a matrix is as wide as its widest row
    fracs = tex.count("\\frac")
    plain = re.sub(r"\\(left|right|mathrm|mathbf|dot|ddot|tfrac|frac|begin|end|quad)\b|[{}\s]", "", tex)
    plain = re.sub(r"\\[A-Za-z]+", "x", plain)
    return max(len(plain) - 3 * fracs, 0)


def _dotted(latex: str, accent: str) -> str:
    """Put the dot on the base letter, not on the subscript: \\theta_{1} -> \\dot{\\theta}_{1}."""
    base, sep, sub = latex.partition("_")
    return f"{accent}{{{base}}}{sep}{sub}"


def render_latex(d: Derivation, template_dir: Path | None = None) -> str:
    from tutgen.render.env import latex_env
    from tutgen.render.views import solution_view

    return latex_env(template_dir).get_template("solution.tex.j2").render(**solution_view(d))
