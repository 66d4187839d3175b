"""Label text: safe TeX for a name, its estimated size, and the same text for SVG.

The user's ``latex:`` of a parameter or coordinate is used only when it is made of the small
vocabulary a name needs (letters, digits, Greek letters, sub- and superscripts, primes, a few
accents); anything else is replaced by the name's default (sympy's ``theta1`` -> ``\\theta_{1}``), so
no TeX command the user wrote ever runs inside a picture. :func:`svg_runs` reads only that vocabulary.
"""

from __future__ import annotations

import re

import sympy as sp

_GREEK = (
    "alpha beta gamma delta epsilon varepsilon zeta eta theta vartheta iota kappa lambda mu nu xi pi varpi "
    "rho varrho sigma varsigma tau upsilon phi varphi chi psi omega Gamma Delta Theta Lambda Xi Pi Sigma "
    "Upsilon Phi Psi Omega"
).split()
_UNICODE = dict(
    zip(
        _GREEK,
        "αβγδϵεζηθϑικλμνξπϖρϱσςτυϕφχψωΓΔΘΛΞΠΣΥΦΨΩ",
        strict=True,
    )
)
_ACCENTS = {"dot", "ddot", "bar", "hat", "tilde", "vec"}
#: The font commands and the SVG style of each (the PDF's: ``\\mathbf`` upright bold, ``\\boldsymbol``
#: bold italic maths, ``\\mathrm`` and ``\\text`` upright, ``\\mathit`` italic).
_FONTS = {"mathrm": "upright", "text": "upright", "mathit": "italic", "mathbf": "bold", "boldsymbol": "bolditalic"}
_COMMANDS = set(_GREEK) | _ACCENTS | set(_FONTS)
_TOKEN = re.compile(r"\\([A-Za-z]+)|\\_|([A-Za-z0-9])|([_^{}',])|( )")
MAX_LABEL = 40

#: Sizes in cm of the figure's maths (10 pt): an average glyph's width, a line's height.
CHAR_WIDTH = 0.2
LINE_HEIGHT = 0.42
PAD = 0.06


def is_safe_tex(tex: str) -> bool:
    """Whether ``tex`` uses only the label vocabulary, with balanced braces."""
    if not tex or len(tex) > MAX_LABEL:
        return False
    pos, depth = 0, 0
    while pos < len(tex):
        m = _TOKEN.match(tex, pos)
        if m is None:
            return False
        if m.group(1) is not None and m.group(1) not in _COMMANDS:
            return False
        depth += {"{": 1, "}": -1}.get(m.group(3) or "", 0)
        if depth < 0:
            return False
        pos = m.end()
    return depth == 0


def name_tex(name: str, latex: str | None = None) -> str:
    """The TeX of a declared name: the user's ``latex`` if it is safe, else the name's default form."""
    if latex is not None and is_safe_tex(latex.strip()):
        return latex.strip()
    return sp.latex(sp.Symbol(name))


def word_tex(name: str) -> str:
    """A spec name set upright (a load or a body without a mass symbol): ``\\mathrm{push}``. Names are
    identifiers, so escaping ``_`` is all that is needed."""
    return "\\mathrm{" + name.replace("_", "\\_") + "}"


def expr_tex(expr: sp.Expr, latex_of: dict[sp.Symbol, str]) -> str | None:
    """The TeX of a lone symbol or a symbol with a sign (a force ``-F``), else None."""
    sign = ""
    if isinstance(expr, sp.Mul) and expr.args[0] == -1 and len(expr.args) == 2:
        sign, expr = "-", expr.args[1]
    if isinstance(expr, sp.Symbol):
        return sign + latex_of.get(expr, sp.latex(expr))
    return None


def svg_runs(tex: str) -> list[tuple[str, str, str]]:
    """The label as runs of (text, style, position) for SVG: style ``italic``, ``upright``, ``bold``
    (upright bold, ``\\mathbf``) or ``bolditalic`` (``\\boldsymbol``), as pdflatex sets each;
    position ``base``, ``sub`` or ``sup``. Reads only the vocabulary of :func:`is_safe_tex`."""
    runs: list[tuple[str, str, str]] = []
    # a stack of (position, style, is-font-group) entered at each "{"
    stack: list[tuple[str, str]] = [("base", "italic")]
    pending: str | None = None  # "sub"/"sup" for the next token or group, or a font for the next group
    font_next: str | None = None
    accent: str | None = None
    pos = 0
    while pos < len(tex):
        m = _TOKEN.match(tex, pos)
        if m is None:  # not safe TeX: shown as written, upright
            runs.append((tex[pos:], "upright", stack[-1][0]))
            break
        pos = m.end()
        place, style = stack[-1]
        if pending is not None:
            place, pending_used = pending, True
        else:
            pending_used = False
        if m.group(4):
            continue
        cmd, ch, sym = m.group(1), m.group(2), m.group(3)
        if font_next is not None and sym != "{" and cmd not in _FONTS and cmd not in _ACCENTS:
            style, font_next = font_next, None  # an unbraced argument: \mathbf W, \boldsymbol\tau
        if m.group(0) == "\\_":
            runs.append(("_", style, place))
        elif cmd in _FONTS:
            font_next = _FONTS[cmd]
            continue
        elif cmd in _ACCENTS:
            accent = {
                "dot": "\u0307",
                "ddot": "\u0308",
                "bar": "\u0304",
                "hat": "\u0302",
                "tilde": "\u0303",
                "vec": "\u20d7",
            }[cmd]
            continue
        elif cmd in _UNICODE:
            # TeX sets capital Greek upright and small Greek italic; \mathbf makes only the capitals
            # bold, \boldsymbol both (each in its own slant)
            if cmd[0].isupper():
                greek = "bold" if style in ("bold", "bolditalic") else "upright"
            else:
                greek = "bolditalic" if style == "bolditalic" else "italic"
            runs.append((_UNICODE[cmd] + (accent or ""), greek, place))
            accent = None
        elif sym == "{":
            stack.append((place, font_next or style))
            font_next = None
            pending = None
            continue
        elif sym == "}":
            if len(stack) > 1:
                stack.pop()
            continue
        elif sym in ("_", "^"):
            pending = "sub" if sym == "_" else "sup"
            continue
        elif sym == "'":
            runs.append(("\u2032", "upright", place))
        elif sym == ",":  # a subscript's separator (R_{pivot,x}), upright as TeX sets punctuation
            runs.append((",", "upright", place))
        elif ch is not None:
            # a digit is upright in maths, and bold only under a bold font
            digit = "bold" if style in ("bold", "bolditalic") else "upright"
            runs.append((ch + (accent or ""), digit if ch.isdigit() else style, place))
            accent = None
        if pending_used:
            pending = None
    merged: list[tuple[str, str, str]] = []
    for run in runs:
        if merged and merged[-1][1:] == run[1:]:
            merged[-1] = (merged[-1][0] + run[0], run[1], run[2])
        else:
            merged.append(run)
    return merged


def label_size(tex: str) -> tuple[float, float]:
    """The estimated width and height (cm) of a label: sub- and superscripts count 0.7 of a glyph."""
    width = 0.0
    for text, _style, place in svg_runs(tex):
        glyphs = sum(1 for ch in text if not 0x300 <= ord(ch) <= 0x36F and ch != "\u20d7")
        width += glyphs * CHAR_WIDTH * (0.7 if place != "base" else 1.0)
    return width + 2 * PAD, LINE_HEIGHT + 2 * PAD
