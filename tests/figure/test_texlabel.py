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
