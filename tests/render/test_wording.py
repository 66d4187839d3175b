"""tutgen's own sentences (checks, remarks, intros) carry typeset maths, never ASCII maths (issue 14)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.conftest import HEAVY_SPECS, SPECS, all_specs, solved
from tutgen.render.printer import TexPrinter
from tutgen.render.wording import engine_parts

ASCII_MATHS = ("_dot", "_ddot", "theta", "^", "**", "q''", "H = H^T")
P05 = SPECS / "tutorial-1" / "p05-rr-arm.yaml"


def _shown(parts: list[dict[str, str]]) -> str:
    return "".join(p["text"] if p["kind"] != "math" else f"${p['tex']}$" for p in parts)


@pytest.mark.parametrize(
    ("sentence", "expected"),
    [
        pytest.param("H = H^T: passed", "$H = H^{T}$: passed", id="symmetry"),
        pytest.param("H q_ddot + C + G - Q equals Lagrange's", r"$H\ddot q + C + G - Q$ equals Lagrange's", id="eom"),
        pytest.param("H_dot - 2 C is skew-symmetric", r"$\dot H - 2C$ is skew-symmetric", id="skew"),
        pytest.param(
            "so a change of theta1 alone moves it", r"so a change of $\theta_1$ alone moves it", id="coordinate-name"
        ),
        pytest.param(
            "that is n^2 J_m theta2_dot^2 / 2 to T",
            r"that is $n^{2} J_{m} \dot{\theta}_2^{2} / 2$ to $T$",
            id="formula-joined",
        ),
        pytest.param("the condition -tau1 = 0.", r"the condition $-\tau_1 = 0$.", id="sign-and-tail"),
        pytest.param("the inertia J_m = 3.3e-05: it", r"the inertia $J_{m} = 33 \times 10^{-6}$: it", id="e-notation"),
        pytest.param("a body at rest is in a state", "a body at rest is in a state", id="words-stay-words"),
        pytest.param(
            "M, D and K of the linear model; D'Alembert", "$M$, $D$ and $K$ of the linear model; D'Alembert", id="mdk"
        ),
    ],
)
def test_engine_sentences_get_typeset_maths(sentence: str, expected: str) -> None:
    tex = TexPrinter(solved(str(P05))[0])
    assert _shown(engine_parts(sentence, tex)) == expected


def test_a_possessive_s_is_a_word_where_s_is_a_name() -> None:
    """The slider-crank has a coordinate s: "Lagrange's" still reads as English, and a quoted 's' or a
    bare s in a formula is still the coordinate."""
    tex = TexPrinter(solved(str(SPECS / "examples" / "f-two-mass-chain.yaml"))[0])
    assert _shown(engine_parts("The Newton–Euler equations agree with Lagrange's: passed", tex)) == (
        "The Newton–Euler equations agree with Lagrange's: passed"
    )
    assert "$" in _shown(engine_parts("a change of s alone", tex))


def _texts(value: object) -> list[str]:
    """Every text part (not maths) of the view's tutgen-written content."""
    if isinstance(value, dict):
        if value.get("kind") in ("text", "strong") and isinstance(value.get("text"), str):
            return [value["text"]]
        return [t for v in value.values() for t in _texts(v)]
    if isinstance(value, list):
        return [t for v in value for t in _texts(v)]
    return []


@pytest.mark.parametrize("spec", [p for p in all_specs() if p.stem not in HEAVY_SPECS], ids=lambda p: p.stem)
def test_tutgens_own_sentences_have_no_ascii_maths(spec: Path) -> None:
    from tutgen.render.views import solution_view

    view = solution_view(solved(str(spec))[1])
    own = {k: view[k] for k in ("sections", "remarks", "checks")}  # not the spec's title, statement, data
    found = [(tok, t) for t in _texts(own) for tok in ASCII_MATHS if tok in t]
    assert found == []


def test_markdown_text_outside_maths_has_no_ascii_maths() -> None:
    from tutgen.render.markdown import render_markdown

    md = render_markdown(solved(str(P05))[1])
    prose = re.sub(r"\$\$.*?\$\$|\$[^$]*\$", "", md, flags=re.S)
    prose = re.sub(r"\*\*([^*\n]+)\*\*", r"\1", prose)  # bold is Markdown, not maths
    assert [tok for tok in ASCII_MATHS if tok in prose] == []
