"""The ``latex:`` whitelist (tutgen.spec.latexname): a display name, never raw TeX (issues 13 and 14)."""

from __future__ import annotations

import pytest

from tutgen.errors import SpecErrors
from tutgen.spec.latexname import LatexNameError, check_latex_name
from tutgen.spec.validate import load_system_text


@pytest.mark.parametrize(
    "latex",
    [
        "m_1",
        "I_{xx,1}",
        "\\tau_1",
        "\\dot{\\theta}_{m,1}",
        "\\ddot x",
        "x'",
        "x'^2",
        "x_1^2",
        "x^2_1",
        "\\mathrm{max}",
        "F_{\\mathrm{max}}",
        "\\mathbf{r}_{AB}",
        "\\hat{e}_x",
        "\\bar{m}",
        "\\tilde{\\omega}",
        "\\vec{v}",
        "\\mathit{EI}",
        "\\ell_2",
        "r^{\\prime}",
        "\\varphi",
        "\\Omega_0",
        "a b",
        "\\mathit{a\\_b}",
        "{m}_{1}",
    ],
)
def test_allowed_display_names_pass(latex: str) -> None:
    check_latex_name(latex)


@pytest.mark.parametrize(
    ("latex", "offset", "message"),
    [
        pytest.param("\\def\\x{y}", 0, "'\\def' is not allowed", id="def"),
        pytest.param("\\input{/etc/hostname}", 0, "'\\input' is not allowed", id="input"),
        pytest.param("m\\catcode`\\{=12", 1, "'\\catcode' is not allowed", id="catcode"),
        pytest.param("\\csname x\\endcsname", 0, "'\\csname' is not allowed", id="csname"),
        pytest.param("\\write18{touch x}", 0, "'\\write' is not allowed", id="write18"),
        pytest.param("$x$", 0, "'$' is not allowed", id="dollar"),
        pytest.param("m#1", 1, "'#' is not allowed", id="hash"),
        pytest.param("m%", 1, "'%' is not allowed", id="percent"),
        pytest.param("a&b", 1, "'&' is not allowed", id="ampersand"),
        pytest.param("a~b", 1, "'~' is not allowed", id="tilde"),
        pytest.param("a\\\\b", 1, "'\\\\' is not allowed", id="line-break"),
        pytest.param("<img onerror=alert(1)>", 0, "'<' is not allowed", id="html"),
        pytest.param("m\n1", 1, "U+000A is not allowed", id="newline"),
        pytest.param("θ", 0, "'θ' is not allowed", id="unicode"),
        pytest.param("\\,", 0, "'\\,' is not allowed", id="spacing-command"),
        pytest.param("\\Alpha", 0, "'\\Alpha' is not allowed", id="no-such-greek"),
        pytest.param("x_", 1, "'_' at the end of the display name has no argument", id="script-at-end"),
        pytest.param("x_}", 2, "'_' must be followed by its argument", id="script-before-brace"),
        pytest.param("x_1_2", 3, "double subscript", id="double-subscript"),
        pytest.param("x_{1}_{2}", 5, "double subscript", id="double-subscript-groups"),
        pytest.param("x^2^3", 3, "double superscript", id="double-superscript"),
        pytest.param("x^2'", 3, "a prime after a superscript", id="prime-after-superscript"),
        pytest.param("\\dot", 0, "'\\dot' at the end of the display name has no argument", id="accent-at-end"),
        pytest.param("m_{1", 2, "unclosed '{'", id="unclosed-brace"),
        pytest.param("m}", 1, "unmatched '}'", id="unmatched-brace"),
        pytest.param("", 0, "the display name is empty", id="empty"),
        pytest.param("  ", 0, "the display name is empty", id="blank"),
        pytest.param("m" * 101, 100, "too long", id="too-long"),
    ],
)
def test_display_names_that_are_not_allowed_are_refused_at_the_culprit(latex: str, offset: int, message: str) -> None:
    with pytest.raises(LatexNameError) as info:
        check_latex_name(latex)
    assert message in info.value.message
    assert info.value.offset == offset
    assert info.value.hint is not None


def test_a_refused_latex_is_a_located_spec_error_naming_what_is_allowed() -> None:
    text = "title: t\nparameters:\n  m: {latex: 'm\\def\\x{y}'}\ncoordinates:\n  x: {latex: '\\input{f}'}\n"
    text += "energy: {kinetic: m*x_dot**2/2}\n"
    with pytest.raises(SpecErrors) as info:
        load_system_text(text, "latex.yaml")
    errors = sorted(info.value.errors, key=lambda e: (e.location.line, e.location.col))
    assert [(e.location.line, e.location.col) for e in errors] == [(3, 16), (5, 15)]
    assert "the latex of 'm' is not a display name: '\\def' is not allowed" in errors[0].message
    assert "the latex of 'x' is not a display name: '\\input' is not allowed" in errors[1].message
    assert errors[0].hint is not None and "\\theta" not in errors[0].hint and "\\mathrm" in errors[0].hint
