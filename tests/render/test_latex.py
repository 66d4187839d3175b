"""The LaTeX printer's notation, escaping, and the view as data."""

from __future__ import annotations

from collections.abc import Mapping

import pytest
import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.render.latex import format_number, latex_escape, tidy_functions

P03 = SPECS / "tutorial-1" / "p03-cart-pendulum.yaml"
P05 = SPECS / "tutorial-1" / "p05-rr-arm.yaml"


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        pytest.param(0.006131, "0.006131", id="decimal-down-to-a-thousandth"),
        pytest.param(0.000375, r"375 \times 10^{-6}", id="small-engineering"),
        pytest.param(0.0001571, r"157.1 \times 10^{-6}", id="small-engineering-four-figures"),
        pytest.param(2.94337, "2.943", id="four-figures"),
        pytest.param(0.05, "0.05", id="trailing-zeros-dropped"),
        pytest.param(123456.0, r"123.5 \times 10^{3}", id="large-engineering"),
        pytest.param(7849.0, "7849", id="up-to-9999-a-decimal"),
        pytest.param(-0.0123, "-0.0123", id="negative"),
        pytest.param(0.0, "0", id="zero"),
        pytest.param(9.99996, "10", id="rounds-up"),
    ],
)
def test_format_number_significant_figures(value: float, expected: str) -> None:
    assert format_number(value) == expected


@pytest.mark.parametrize(
    ("tex", "expected"),
    [
        pytest.param(r"\sin{\left(\theta \right)}", r"\sin\theta", id="greek"),
        pytest.param(r"\cos{\left(q_{1} \right)}", r"\cos q_{1}", id="latin-subscript"),
        pytest.param(
            r"\cos{\left(\theta_{1} + \theta_{2} \right)}", r"\cos(\theta_{1} + \theta_{2})", id="sum-in-parentheses"
        ),
        pytest.param(r"\sin^{2}{\left(\theta \right)}", r"\sin^{2}\theta", id="power"),
        pytest.param(r"\sin{\left(\cos{\left(x \right)} \right)}", r"\sin(\cos x)", id="nested"),
    ],
)
def test_tidy_functions_writes_trig_as_a_person_does(tex: str, expected: str) -> None:
    assert tidy_functions(tex) == expected


def test_latex_escape_neutralises_commands() -> None:
    assert latex_escape(r"50% of \input{x} & $y_1$ #~^") == (
        r"50\% of \textbackslash{}input\{x\} \& \$y\_1\$ \#\textasciitilde{}\^{}"
    )


def test_printer_drops_unit_floats() -> None:
    from tutgen.render.latex import TexPrinter

    system = solved(str(P05))[0]
    x = sp.Symbol("x")
    assert TexPrinter(system)(sp.Float(1.0) * x + sp.Float(0.00006131)) == r"x + 61.31 \times 10^{-6}"


def test_view_is_plain_data_with_raw_text() -> None:
    from tutgen.render.views import solution_view

    view = solution_view(solved(str(P03))[1])
    assert view["title"] == "Cart on a spring carrying a motor-driven pendulum"

    def plain(value: object) -> bool:
        # a Mapping: the figure's keys are drawn when first read (tutgen.figure.view.FigureView)
        if isinstance(value, Mapping):
            return all(isinstance(k, str) and plain(v) for k, v in value.items())
        if isinstance(value, list):
            return all(plain(v) for v in value)
        return isinstance(value, str | bool)

    assert plain(view)
    kinds = {b["kind"] for s in view["sections"] for b in s["blocks"]}
    assert kinds <= {"text", "subheading", "math", "boxed", "freebody"}  # tutgen/render/blocks.py
    eom = next(s for s in view["sections"] if s["title"] == "Equations of motion")
    assert [b["kind"] for b in eom["blocks"]] == ["boxed", "boxed"]
    assert all(r"\sin{\left(" not in b["tex"] for s in view["sections"] for b in s["blocks"] if "tex" in b)


def test_user_text_is_escaped_in_both_formats() -> None:
    import dataclasses

    from tutgen.render.latex import render_latex
    from tutgen.render.markdown import render_markdown

    system, d, _ = solved(str(P03))
    evil = r"Cart \input{/etc/passwd} $x$ 100% # _under_ <b>"
    d2 = dataclasses.replace(d, system=dataclasses.replace(system, title=evil, statement=evil))
    tex = render_latex(d2)
    assert r"\input{/etc/passwd}" not in tex
    assert r"\textbackslash{}input\{/etc/passwd\} \$x\$ 100\% \# \_under\_ \textless{}b\textgreater{}" in tex
    md = render_markdown(d2)
    assert r"Cart \\input\{/etc/passwd\} \$x\$ 100% \# \_under\_ \<b\>" in md


def test_latex_document_is_complete_and_deterministic() -> None:
    from tutgen.render.latex import render_latex

    d = solved(str(P05))[1]
    tex = render_latex(d)
    assert tex.startswith(r"\documentclass") and tex.endswith("\\end{document}\n")
    assert r"\pdftrailerid{}" in tex  # no random document ID in the PDF
    assert r"\boxed{" in tex and r"\begin{bmatrix}" in tex
    assert render_latex(d) == tex


def test_the_specs_significant_figures_set_every_decimal() -> None:
    import dataclasses

    from tutgen.render.printer import TexPrinter

    system = solved(str(P05))[0]
    assert TexPrinter(system)(sp.Float(2.94337)) == "2.943"  # the default, 4
    three = dataclasses.replace(system, significant_figures=3)
    assert TexPrinter(three)(sp.Float(2.94337) * sp.Symbol("x")) == "2.94 x"


def test_latex_escape_is_the_character_by_character_rule() -> None:
    """``latex_escape`` (one ``str.translate``, issue 17) replaces each character as the rule says: a TeX
    special by its escape, else a known Unicode symbol by its maths, else the character itself."""
    import random

    from tutgen.render.escape import _SPECIALS, _UNICODE, latex_escape

    alphabet = [*_SPECIALS, *_UNICODE, *"abc XYZ 019 .,;:!?'\"()[]*+-=/@", "\u00e9", "\u4e2d", "\U0001f600"]
    rng = random.Random(17)
    for _ in range(500):
        text = "".join(rng.choice(alphabet) for _ in range(rng.randint(0, 40)))
        assert latex_escape(text) == "".join(_SPECIALS.get(ch) or _UNICODE.get(ch, ch) for ch in text)
