"""The sheet's terse layout (tutgen/sheet/compact.py): short displays two to a line, nothing lost."""

from __future__ import annotations

import re
from typing import Any

from tests.conftest import SPECS, solved
from tutgen.render.blocks import display, stacked
from tutgen.render.layout import LINE_WIDTH_PT, tex_width
from tutgen.render.views import solution_view
from tutgen.sheet.compact import SHEET_WIDTH_PT, compact_blocks, compact_sections, slashed


def _maths(blocks: list[dict[str, Any]]) -> str:
    """Every equation the blocks display, as one string without spaces, alignment points or separators."""
    out = []
    for b in blocks:
        for part in (b.get("left"), b.get("right")) if b["kind"] == "beside" else (b,):
            if part is not None and part["kind"] in ("math", "boxed"):
                shown = " ".join(part["rows"]) if part["rows"] else part["tex"]
                out.append(f"\\boxed{{{shown}}}" if part["kind"] == "boxed" else shown)
    text = " ".join(out)
    text = re.sub(r"\\qquad|\\quad|&|,|\{\}|\s", "", text)
    return text


def test_compact_short_stack_goes_on_one_line_and_keeps_every_equation() -> None:
    block = stacked(["a = 1", "b = 2", "c = 3", "d = 4"])
    assert block["rows"]  # a single solution stacks them
    (out,) = compact_blocks([block])
    assert out["rows"] == [] and all(eq in out["tex"] for eq in ("a = 1", "b = 2", "c = 3", "d = 4"))


def test_compact_long_stack_of_short_lines_goes_in_two_columns_in_order() -> None:
    lines = [f"x_{{{i}}} = " + " + ".join(f"y_{{{i}{k}}}" for k in range(6)) for i in range(6)]
    assert tex_width(",\\quad ".join(lines)) > LINE_WIDTH_PT  # too wide for one line
    (out,) = compact_blocks([stacked(lines)])
    assert len(out["rows"]) == 3
    assert all(r.count("&") == 3 for r in out["rows"])  # two equations a row, each with its alignment point
    assert [ln.split(" =")[0] for ln in lines] == re.findall(r"x_\{\d\}", " ".join(out["rows"]))  # across, down


def test_compact_neighbouring_one_line_displays_share_a_line_and_boxes_stay_boxed() -> None:
    blocks = [display("H_{11} = 3"), {**display("u = 1"), "kind": "boxed"}]
    (out,) = compact_blocks(blocks)
    assert out["tex"] == "H_{11} = 3\\qquad \\boxed{u = 1}"


def test_compact_leaves_a_wide_display_and_text_alone() -> None:
    wide = display(" + ".join(f"a_{{{i}}} b_{{{i}}} c_{{{i}}}" for i in range(40)))
    para = {"kind": "text", "parts": [{"kind": "text", "text": "A long sentence that is no lead-in."}]}
    out = compact_blocks([wide, para, wide])
    assert out == [wide, para, wide]


def test_compact_lead_in_runs_into_its_display() -> None:
    lead = {
        "kind": "text",
        "parts": [{"kind": "text", "text": "Coordinate "}, {"kind": "math", "tex": "r"}, {"kind": "text", "text": ":"}],
    }
    (out,) = compact_blocks([lead, display("Q_{r} = f")])
    assert out["tex"] == "\\text{Coordinate }r\\text{:}\\quad Q_{r} = f"


def test_compact_sheet_solutions_keep_every_equation_of_the_tutorial() -> None:
    """Every problem of the tutorial: the compact sections display exactly the maths the single solution
    does (only separators and alignment points differ), and no display is wider than the line."""
    for name in ("p03-cart-pendulum", "p05-rr-arm", "p10-given-kinetic-energy"):
        view = solution_view(solved(str(SPECS / "tutorial-1" / f"{name}.yaml"))[1], decimals=True)
        compact = compact_sections(view["sections"])
        for before, after in zip(view["sections"], compact, strict=True):
            assert _maths(after["blocks"]) == _slash(_maths(before["blocks"])) or _same_maths(
                before["blocks"], after["blocks"]
            ), (name, before["title"])
            for b in after["blocks"]:
                if b["kind"] == "math" and not b["rows"]:
                    assert tex_width(b["tex"]) <= SHEET_WIDTH_PT, (name, b["tex"])


def _same_maths(before: list[dict[str, Any]], after: list[dict[str, Any]]) -> bool:
    """The same maths, a lead-in's words aside (they moved from a paragraph into the display)."""
    plain = re.sub(r"\\text\{[^}]*\}", "", _maths(after))
    return plain == _slash(_maths(before))


def _slash(maths: str) -> str:
    return slashed(maths)


def test_slashed_writes_a_partial_derivative_on_the_line_and_leaves_other_fractions() -> None:
    tex = r"\frac{d}{dt}\frac{\partial L}{\partial \dot{\theta}} = \frac{a + b}{2}"
    tex += r" + \frac{\partial H_{11}}{\partial q_{2}}"
    assert slashed(tex) == (
        r"\tfrac{d}{dt}{\partial L/\partial \dot{\theta}} = \frac{a + b}{2} + {\partial H_{11}/\partial q_{2}}"
    )
