"""The free-body diagrams in the planar Newton–Euler step (issues 15 item 3, 16 point 2): one per body,
before the list of its forces, naming every force the step lists; as TikZ inline in LaTeX, as an SVG
beside a Markdown solution (written by the same writer as the main figure); none where Newton–Euler
is not printed."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from tests.conftest import SPECS, solved
from tutgen.api import figure_files
from tutgen.engine.pipeline import derive
from tutgen.render.jsonout import derivation_to_json
from tutgen.render.latex import render_latex
from tutgen.render.markdown import render_markdown
from tutgen.render.sections.newton_euler import free_bodies
from tutgen.render.views import solution_view

P03 = SPECS / "tutorial-1" / "p03-cart-pendulum.yaml"


def _section(d: Any) -> dict[str, Any]:
    return next(s for s in solution_view(d)["sections"] if s["title"] == "Newton–Euler")


def test_every_force_of_a_balance_is_named_in_its_diagram() -> None:
    _, d, _ = solved(str(P03))
    views = {v["body"]: v for v in free_bodies(d)}
    balances = d.newton_euler.planar.balances
    assert sorted(views) == sorted(b.body for b in balances) == ["cart", "pendulum"]
    for b in balances:
        assert b.forces, b.body
        labels = set(views[b.body]["labels"])
        missing = [f.name for f in b.forces if f"force:{f.name}" not in labels]
        assert missing == [], (b.body, missing, sorted(labels))


def test_diagram_labels_are_the_steps_symbols() -> None:
    # written by hand from the tutorial's p03: the cart carries the slider's reaction (and couple), the
    # pendulum's reaction on it, the spring, the push and the motor's reaction; the pendulum the motor
    _, d, _ = solved(str(P03))
    views = {v["body"]: v for v in free_bodies(d)}
    cart, pendulum = views["cart"]["tikz"], views["pendulum"]["tikz"]
    for tex in (
        "\\mathbf{W}",
        "\\mathbf{F}_{\\text{wall}}",
        "\\mathbf{F}_{\\text{push}}",
        "\\tau_{\\text{motor}}",
        "N_{\\mathrm{slider}}",  # the slide's normal force, as the step's sum of y forces names it
        "M_{\\mathrm{slider}}",
        # the pin's reaction as its two components along the axes, as the step's balances name them;
        # on the parent the same names, the arrows reversed
        "R_{\\mathrm{pivot},x}",
        "R_{\\mathrm{pivot},y}",
        "\\mathbf{F}_{\\text{inertial}}",
    ):
        assert "$\\vphantom{(}" + tex + "$" in cart, tex
    for tex in (
        "\\mathbf{W}",
        "\\tau_{\\text{motor}}",
        "R_{\\mathrm{pivot},x}",
        "R_{\\mathrm{pivot},y}",
        "\\mathbf{F}_{\\text{inertial}}",
    ):
        assert "$\\vphantom{(}" + tex + "$" in pendulum, tex
    # no reaction drawn as one (diagonal) arrow any more
    assert "\\mathbf{R}_{\\mathrm{pivot}}" not in cart + pendulum
    assert "\\mathrm{slider}" not in pendulum and "\\text{wall}" not in pendulum
    # the model's own names (R_1x, k x) are not used where the step has its own
    assert "R_{1x}" not in cart and "k x" not in cart


def test_each_body_shows_its_diagram_before_its_forces() -> None:
    _, d, _ = solved(str(P03))
    blocks = _section(d)["blocks"]
    kinds = [b["kind"] for b in blocks]
    diagrams = [i for i, k in enumerate(kinds) if k == "freebody"]
    assert [blocks[i]["body"] for i in diagrams] == ["cart", "pendulum"]
    for i in diagrams:
        assert blocks[i + 1]["kind"] == "math" and blocks[i + 1]["lines"][0].startswith("\\mathbf W = ")
        assert blocks[i]["svg"] == f"p03-cart-pendulum.fbd-{blocks[i]['body']}.svg"


def test_latex_sets_the_diagram_inline_unscaled_and_markdown_links_the_svg() -> None:
    _, d, _ = solved(str(P03))
    tex = render_latex(d).split("Newton–Euler", 1)[1]
    views = free_bodies(d)
    for v in views:
        assert "\\begin{center}\n" + v["tikz"].strip() in tex
    assert "\\resizebox" not in tex and "scale=" not in tex.split("\\begin{tikzpicture}", 1)[1].split("\n", 1)[0]
    md = render_markdown(d)
    for v in views:
        assert f"![Free body: {v['body']}](<{v['svg']}>)" in md


def test_markdown_writer_writes_each_diagram_beside_the_solution(tmp_path: Path) -> None:
    _, d, _ = solved(str(P03))
    target = tmp_path / "sol.md"
    paths, contents = figure_files([P03], [target], force=False, derivations=[d])
    names = [p.name for p in paths]
    assert names == [
        "p03-cart-pendulum.figure.svg",
        "p03-cart-pendulum.fbd-cart.svg",
        "p03-cart-pendulum.fbd-pendulum.svg",
    ]
    for name, text in zip(names[1:], contents[1:], strict=True):
        assert isinstance(text, str) and text.startswith("<?xml") and "<svg" in text
        assert f"(<{name}>)" in render_markdown(d)  # every file the solution links, and only those
    again = figure_files([P03], [target], force=False, derivations=[d])[1]
    assert again == contents  # deterministic
    (tmp_path / "p03-cart-pendulum.fbd-cart.svg").write_text("mine")
    try:
        figure_files([P03], [target], force=False, derivations=[d])
    except Exception as err:  # nothing the user has is overwritten without --force
        assert "exists; add --force" in str(err)
    else:
        raise AssertionError("an existing diagram was to be overwritten without --force")


def test_no_diagram_where_newton_euler_is_not_printed() -> None:
    system, _, _ = solved(str(P03))
    d = derive(system, "lagrange")
    assert free_bodies(d) == []
    assert "fbd-" not in render_markdown(d)
    paths, _ = figure_files([P03], [Path("/nonexistent/sol.md")], force=False, derivations=[d])
    assert [p.name for p in paths] == ["p03-cart-pendulum.figure.svg"]


def test_json_lists_the_diagram_files_beside_the_figure() -> None:
    system, _, doc = solved(str(P03))
    entries = dict(doc)["figure"]["free_bodies"]
    assert [e["body"] for e in entries] == ["cart", "pendulum"]
    assert entries[0]["svg"] == "p03-cart-pendulum.fbd-cart.svg"
    assert "force:reaction at joint 'pivot'" in entries[1]["labels"]
    assert derivation_to_json(derive(system, "lagrange"))["figure"]["free_bodies"] == []
