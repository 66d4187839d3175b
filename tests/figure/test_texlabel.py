"""Label text: the TeX vocabulary a name may use, and its SVG form."""

from __future__ import annotations

import pytest

from tutgen.figure.texlabel import is_safe_tex, label_size, name_tex, svg_runs, word_tex


@pytest.mark.parametrize(
    ("tex", "safe"),
    [
        pytest.param("\\theta_{1}", True, id="greek-subscript"),
        pytest.param("m_2", True, id="subscript"),
        pytest.param("x'", True, id="prime"),
        pytest.param("\\dot{q}_{1}", True, id="accent"),
        pytest.param("\\mathrm{push\\_it}", True, id="upright-word"),
        pytest.param("\\input{x}", False, id="input"),
        pytest.param("\\write18{rm}", False, id="write18"),
        pytest.param("a}b{", False, id="unbalanced"),
        pytest.param("\\theta_{1", False, id="unclosed"),
        pytest.param("$x$", False, id="dollar"),
        pytest.param("x" * 41, False, id="too-long"),
    ],
)
def test_texlabel_vocabulary(tex: str, safe: bool) -> None:
    assert is_safe_tex(tex) is safe


def test_texlabel_name_tex_falls_back_to_the_name() -> None:
    assert name_tex("theta1", "\\input{a}") == "\\theta_{1}"
    assert name_tex("theta1", None) == "\\theta_{1}"
    assert name_tex("x", "\\xi") == "\\xi"
    assert word_tex("rail_friction") == "\\mathrm{rail\\_friction}"


def test_texlabel_svg_runs_greek_and_subscripts() -> None:
    assert svg_runs("\\theta_{1}") == [("θ", "italic", "base"), ("1", "upright", "sub")]
    assert svg_runs("\\mathrm{push\\_it}") == [("push_it", "upright", "base")]
    assert svg_runs("m_{r}") == [("m", "italic", "base"), ("r", "italic", "sub")]


def test_texlabel_size_grows_with_the_text() -> None:
    assert label_size("\\mathrm{motor}")[0] > label_size("\\tau")[0]
    assert label_size("m_{2}")[0] < label_size("mm")[0] + 0.01


@pytest.mark.parametrize(
    ("tex", "runs"),
    [
        # pdflatex: \mathbf sets its letters (and digits) upright bold, its subscript's \mathrm upright
        pytest.param(
            "\\mathbf{R}_{\\mathrm{pivot}}", [("R", "bold", "base"), ("pivot", "upright", "sub")], id="mathbf-braced"
        ),
        pytest.param("\\mathbf W", [("W", "bold", "base")], id="mathbf-unbraced"),
        pytest.param("\\mathbf{F}_{2}", [("F", "bold", "base"), ("2", "upright", "sub")], id="mathbf-digit-outside"),
        # \mathbf leaves small Greek italic and not bold; \boldsymbol makes it bold italic
        pytest.param("\\mathbf{\\tau}", [("τ", "italic", "base")], id="mathbf-small-greek"),
        pytest.param("\\boldsymbol\\tau_{1}", [("τ", "bolditalic", "base"), ("1", "upright", "sub")], id="boldsymbol"),
        pytest.param("\\boldsymbol{\\Omega}", [("Ω", "bold", "base")], id="boldsymbol-capital-greek"),
        pytest.param(
            "R_{\\mathrm{pivot},x}",
            [("R", "italic", "base"), ("pivot,", "upright", "sub"), ("x", "italic", "sub")],
            id="comma-in-subscript",
        ),
    ],
)
def test_texlabel_svg_runs_set_fonts_as_pdflatex_does(tex: str, runs: list[tuple[str, str, str]]) -> None:
    assert is_safe_tex(tex)
    assert svg_runs(tex) == runs


def test_svg_sets_bold_labels_bold() -> None:
    from tutgen.figure.scene import Box, Drawing, Label
    from tutgen.figure.svg import to_svg

    labels = (
        Label("force:w", "\\mathbf{W}", (1, 1), 0.3, 0.5),
        Label("force:t", "\\boldsymbol\\tau", (2, 1), 0.3, 0.5),
    )
    svg = to_svg(Drawing((), labels, Box(0, 0, 3, 2), "planar"))
    assert '<tspan font-style="normal" font-weight="bold">W</tspan>' in svg
    assert '<tspan font-style="italic" font-weight="bold">τ</tspan>' in svg
