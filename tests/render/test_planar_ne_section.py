"""The Newton–Euler section of a planar system as the view gives it (tutgen.render.sections.newton_euler):
per body its free-body diagram and three balances, the equations by elimination tips first, the reactions
last; a spatial system keeps the recursive form."""

from __future__ import annotations

from typing import Any

from tests.conftest import SPECS, solved
from tutgen.engine.pipeline import derive
from tutgen.render.markdown import render_markdown
from tutgen.render.views import solution_view
from tutgen.spec.validate import load_system

P03 = SPECS / "tutorial-1" / "p03-cart-pendulum.yaml"
P08 = SPECS / "tutorial-1" / "p08-spatial-rr.yaml"


def _section(path: Any) -> dict[str, Any]:
    d = solved(str(path))[1] if path == P03 else derive(load_system(path), "both")  # p03 asks for it
    view = solution_view(d)
    return next(s for s in view["sections"] if s["title"] == "Newton–Euler")


def _texts(block: dict[str, Any]) -> str:
    return "".join(p.get("text", "") + p.get("tex", "") for p in block.get("parts", []))


def _lines(sec: dict[str, Any]) -> list[str]:
    return [line for b in sec["blocks"] if b["kind"] == "math" for line in b["lines"]]


def test_p03_cart_free_body_lists_spring_push_and_reactions() -> None:
    lines = _lines(_section(P03))
    assert any(line.startswith("\\mathbf F_{\\text{wall}} = - k x \\mathbf i") for line in lines)
    assert any(line.startswith("\\mathbf F_{\\text{push}} = F \\mathbf i") for line in lines)
    assert any(line.startswith("-\\tau_{\\text{motor}} = - \\tau") for line in lines)  # the motor's reaction
    assert any(line.startswith("-\\mathbf R_{\\mathrm{pivot}} = - R_{\\mathrm{pivot},x} \\mathbf i") for line in lines)
    cart_fx = next(line for line in lines if line.startswith("\\textstyle\\sum F_x") and "m_1" in line)
    assert "- k x" in cart_fx and " F " in cart_fx and "R_{\\mathrm{pivot},x}" in cart_fx and cart_fx.endswith("= 0")


def test_p03_equations_by_elimination_tips_first_then_reactions() -> None:
    sec = _section(P03)
    paragraphs = [_texts(b) for b in sec["blocks"] if b["kind"] == "text"]
    equations = [p for p in paragraphs if p.startswith("Equation of")]
    assert [e.split(":")[0] for e in equations] == ["Equation of \\theta", "Equation of x"]
    assert "R_{\\mathrm{pivot},x} cancel" in equations[1]
    last = paragraphs.index(next(p for p in paragraphs if p.startswith("The reactions, solved last")))
    assert last > paragraphs.index(equations[-1])
    lines = _lines(sec)
    assert any(line.startswith("N_{\\mathrm{slider}} = ") for line in lines)
    assert any(line.startswith("R_{\\mathrm{pivot},y} = ") for line in lines)


def test_p03_markdown_has_no_spatial_vectors() -> None:
    _, d, _ = solved(str(P03))
    text = render_markdown(d).split(". Newton–Euler\n", 1)[1]
    assert "\\begin{bmatrix}" not in text.split("\n## ")[0]  # only the plane's components


def test_spatial_system_keeps_the_recursive_form() -> None:
    sec = _section(P08)
    paragraphs = [_texts(b) for b in sec["blocks"] if b["kind"] == "text"]
    assert not any(p.startswith("Equation of") for p in paragraphs)
    assert any(p.startswith("Joint reactions") for p in paragraphs)
