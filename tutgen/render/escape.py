"""Making a reader's text safe to print: LaTeX and Markdown escaping of user and engine wording.

Nothing a spec's author writes runs as a command: every TeX special is escaped, Greek letters and common
symbols become their maths equivalents (which pdflatex typesets), and Markdown loses its markup."""

from __future__ import annotations

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


#: every character :func:`latex_escape` replaces, and by what (a TeX special first, then the Unicode table)
_LATEX = str.maketrans({ch: _SPECIALS.get(ch) or _UNICODE[ch] for ch in (*_SPECIALS, *_UNICODE)})


def latex_escape(text: str) -> str:
    """Escape user text so that LaTeX shows it verbatim (no command in it runs); Greek letters and
    common symbols become their maths equivalents, which pdflatex can typeset."""
    return text.translate(_LATEX)


_MD_SPECIALS = str.maketrans({c: "\\" + c for c in "\\`*_{}[]<>#|$"})


def md_escape(text: str) -> str:
    """User text in Markdown: no markup, no maths, no HTML from it."""
    return text.translate(_MD_SPECIALS)
