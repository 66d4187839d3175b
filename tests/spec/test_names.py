"""Default display names (tutgen.spec.names): a name is typeset as a reader expects, never as a product."""

from __future__ import annotations

import re

import pytest
from hypothesis import given
from hypothesis import strategies as st

from tests.conftest import all_specs
from tutgen.spec.latexname import check_latex_name
from tutgen.spec.loader import load_yaml_file
from tutgen.spec.names import default_latex
from tutgen.spec.validate import load_system, load_system_text


@pytest.mark.parametrize(
    ("name", "latex"),
    [
        pytest.param("m1", "m_1", id="letter-digit"),
        pytest.param("Ixx1", "I_{xx,1}", id="inertia-with-link"),
        pytest.param("Jz3", "J_{z,3}", id="one-axis-with-link"),
        pytest.param("cx1", "c_{x,1}", id="centre-of-mass-component"),
        pytest.param("Izz", "I_{zz}", id="letters-only"),
        pytest.param("theta_m", "\\theta_m", id="greek-underscore"),
        pytest.param("theta1", "\\theta_1", id="greek-digit"),
        pytest.param("theta12", "\\theta_{12}", id="greek-two-digits"),
        pytest.param("l_AB", "l_{AB}", id="underscore-two-letters"),
        pytest.param("I_zz3", "I_{zz,3}", id="underscore-letters-digit"),
        pytest.param("k_theta", "k_{\\theta}", id="greek-subscript"),
        pytest.param("rho", "\\rho", id="greek"),
        pytest.param("Omega", "\\Omega", id="greek-capital"),
        pytest.param("Alpha", "A", id="greek-capital-latin-shape"),
        pytest.param("varphi", "\\varphi", id="greek-variant"),
        pytest.param("lamda", "\\lambda", id="sympy-lambda"),
        pytest.param("mus", "\\mu_s", id="greek-with-subscript-letter"),
        pytest.param("omegan", "\\omega_n", id="greek-with-subscript-letter-2"),
        pytest.param("x", "x", id="one-letter"),
        pytest.param("L0", "L_0", id="capital-digit"),
        pytest.param("EI", "\\mathit{EI}", id="capitals-word"),
        pytest.param("mass", "\\mathit{mass}", id="word"),
        pytest.param("a1b", "\\mathit{a1b}", id="digits-inside"),
        pytest.param("a__b", "\\mathit{a\\_\\_b}", id="empty-part"),
        pytest.param("q_dot", "\\dot{q}", id="free-rate"),
        pytest.param("theta1_ddot", "\\ddot{\\theta}_1", id="free-acceleration"),
    ],
)
def test_default_latex_reads_as_a_reader_expects(name: str, latex: str) -> None:
    assert default_latex(name) == latex


_NAMES = st.from_regex(r"[A-Za-z][A-Za-z0-9]{0,6}(_[A-Za-z0-9]{1,4}){0,2}", fullmatch=True)


@given(_NAMES)
def test_default_latex_passes_the_whitelist_and_keeps_every_digit(name: str) -> None:
    latex = default_latex(name)
    check_latex_name(latex)  # raises if not allowed
    assert re.sub(r"\D", "", latex) == re.sub(r"\D", "", name)  # no digit lost or made up


def _product_of_letters(latex: str) -> bool:
    """Whether ``latex`` would print two or more italic letters side by side outside a subscript or a
    \\mathit word (Ixx_{1} prints as I x x with a subscript 1)."""
    outside = re.sub(r"_\{[^{}]*\}|_.|\\mathit\{[^{}]*\}|\\[A-Za-z]+", "", latex)
    return re.search(r"[A-Za-z]{2}", outside) is not None


def test_no_name_of_a_spec_is_typeset_as_a_product_of_letters() -> None:
    # one loop, not one test per spec: conftest marks the per-spec tests of the symbolic PUMA and
    # Stanford arms slow, and theirs are the names that matter here (Ixx1, cx1); loading is quick
    checked = 0
    for spec in all_specs():
        system = load_system(spec)
        written, _ = load_yaml_file(spec)
        for section, items in (("parameters", system.parameters), ("coordinates", system.coordinates)):
            entries = written.get(section)
            for item in items:
                entry = entries.get(item.name) if isinstance(entries, dict) else None
                given_latex = entry.get("latex") if isinstance(entry, dict) else None
                # a latex: given in the spec wins; else tutgen's rule
                assert item.latex == (given_latex if given_latex is not None else default_latex(item.name))
                assert not _product_of_letters(item.latex), (spec.name, item.name, item.latex)
                checked += 1
    assert checked > 300  # the arms' inertia names are among them


def test_product_detector_finds_sympys_rule() -> None:
    assert _product_of_letters("Ixx_{1}")
    assert not _product_of_letters("I_{xx,1}")


def test_a_given_latex_wins_over_the_default() -> None:
    system = load_system_text(
        "title: t\nparameters:\n  Ixx1: {latex: 'J_1'}\n  m1:\ncoordinates:\n  theta: {latex: '\\vartheta'}\n"
        "energy: {kinetic: Ixx1*theta_dot**2/2 + m1*theta_dot**2}\n",
        "given.yaml",
    )
    assert [p.latex for p in system.parameters] == ["J_1", "m_1"]
    assert system.coordinates[0].latex == "\\vartheta"
