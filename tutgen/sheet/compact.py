"""A worked solution's blocks set tersely, for a sheet: many problems in one document (issue 15).

A single solution (``tutgen solve``) gives each short result a display of its own, one equation a line;
a printed tutorial sheet sets short displays two to a line. This pass changes only the LAYOUT of a
solution's blocks (tutgen/render/blocks.py), never what they say: every equation of every block is
still there, in the same order.

1. A stacked display (``lines`` set one a line in ``rows``) whose lines fit on one line together goes
   on one line (``a = 1,\\quad b = 2``); else, when its lines are unbroken and the two columns they make
   fit the line side by side, it is set in two columns of equations: a row ``a &= 1, & b &= 2,``
   (``align*``/``aligned`` take pairs of columns), read across then down, as the lines were in order.
2. Consecutive displays that are each one line (a list ``H_{11} = …`` and the matrix ``H = …``) share
   a line when they fit on it together, separated by ``\\qquad``; so do consecutive boxed answers (the
   equations of motion), each keeping its box.
3. A short lead-in paragraph that ends in a colon (``Coordinate θ:``) runs into the one-line display
   after it, as ``\\text{Coordinate }\\theta\\text{:}\\quad …``, when both fit on the line.
4. A free-body diagram and the list of its forces that follows it become one ``beside`` block
   (``{"kind": "beside", "left": <freebody>, "right": <math>}``): the LaTeX sheet sets them side by side
   when TeX finds they fit (templates/latex/blocks/beside.tex.j2), Markdown one after the other.
5. Across the problems of one sheet (:func:`shared_intros`): a section's introduction (its conventions,
   the same words for every problem) is printed in full once, where it first appears; a later section
   with the same title and the same introduction says where it stands (``As in Problem 2 (2.3).``).
6. A partial derivative is written on the line, ``\\partial L/\\partial \\dot q`` for
   ``\\frac{\\partial L}{\\partial \\dot q}``, and ``\\tfrac{d}{dt}`` small, as a printed tutorial writes them
   (:func:`slashed`): a display of Lagrange's terms or of Christoffel symbols is half as tall.

Widths are the line breaker's estimates (tutgen.render.layout), which measure 11 pt type: the sheet's
10 pt type on its 494 pt line (17.4 cm) has room for about 540 pt of such estimates, so the sheet's
displays are joined up to :data:`SHEET_WIDTH_PT`, a margin left for the estimate's error.
"""

from __future__ import annotations

import re
from typing import Any

from tutgen.render.layout import tex_width

__all__ = ["COLUMN_GAP", "SHEET_WIDTH_PT", "compact_blocks", "compact_sections", "shared_intros", "slashed"]

Block = dict[str, Any]

#: the widest a joined display of the sheet is made, in the line breaker's 11 pt estimate
SHEET_WIDTH_PT = 490.0
#: the space between the two columns of equations (an ``align*`` gap is about 2 em at 11 pt)
COLUMN_GAP = 24.0
#: the widest a lead-in paragraph may be to run into the display after it
LEAD_IN_WIDTH = 120.0
#: text a lead-in may hold, to be set in ``\text{}`` as it is in both formats (tutgen's own wording)
_PLAIN = re.compile(r"[A-Za-z0-9 ,;:.'()-]*")


def compact_sections(sections: list[dict[str, Any]], width: float = SHEET_WIDTH_PT) -> list[dict[str, Any]]:
    """The sections with their blocks compacted (new dicts; the input is left as it was)."""
    return [{**sec, "blocks": compact_blocks(sec["blocks"], width)} for sec in sections]


def shared_intros(problems: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The problems of a sheet (tutgen/sheet/render.py's problem views, in sheet order) with each section
    introduction that an earlier problem printed already replaced by a pointer to it (new dicts: a
    worker's cached views are left as they were)."""
    first: dict[tuple[str, str], str] = {}  # (title, introduction) -> where it was printed
    out = []
    for problem in problems:
        solution = problem.get("solution") or {}
        sections = []
        for k, sec in enumerate(solution.get("sections") or []):
            intro = sec.get("intro") or []
            key = (str(sec.get("title")), repr(intro))
            if intro and key in first:
                sec = {**sec, "intro": [{"kind": "text", "text": f"As in {first[key]}."}]}
            elif intro:
                first[key] = f"Problem {problem['number']} ({problem['number']}.{k + 1})"
            sections.append(sec)
        out.append({**problem, "solution": {**solution, "sections": sections}} if solution else problem)
    return out


def compact_blocks(blocks: list[Block], width: float = SHEET_WIDTH_PT) -> list[Block]:
    """The blocks with short stacked displays in two columns and short consecutive displays on one line."""
    out: list[Block] = []
    for block in blocks:
        block = _slashed_block(block)
        block = _columns(block, width) if block.get("kind") == "math" else block
        prev = out[-1] if out else None
        if prev is not None and _one_line(prev) and _one_line(block):
            joined = f"{_as_math(prev)}\\qquad {_as_math(block)}"
            if tex_width(joined) <= width:
                out[-1] = {"kind": "math", "tex": joined, "lines": [joined], "rows": []}
                continue
        if prev is not None and prev.get("kind") == "freebody" and block.get("kind") == "math":
            out[-1] = {"kind": "beside", "left": prev, "right": block}
            continue
        lead = _lead_in(prev) if prev is not None and _one_line(block) and block["kind"] == "math" else None
        if lead is not None and tex_width(f"{lead}\\quad {block['tex']}") <= width:
            joined = f"{lead}\\quad {block['tex']}"
            out[-1] = {**block, "tex": joined, "lines": [joined], "rows": []}
            continue
        out.append(block)
    return out


_PARTIAL = "\\frac{\\partial"


def _braced(tex: str, start: int) -> int:
    """The index just after the braced group that opens at ``tex[start]`` (``{``), or -1."""
    depth = 0
    i = start
    while i < len(tex):
        ch = tex[i]
        if ch == "\\":
            i += 2
            continue
        depth += {"{": 1, "}": -1}.get(ch, 0)
        i += 1
        if depth == 0:
            return i
    return -1


def slashed(tex: str) -> str:
    """``\\frac{\\partial A}{\\partial B}`` as ``\\partial A/\\partial B`` (braced when A or B is more than one
    factor, so the slash reads right), and ``\\frac{d}{dt}`` as ``\\tfrac{d}{dt}``."""
    tex = tex.replace("\\frac{d}{dt}", "\\tfrac{d}{dt}")
    out, i = [], 0
    while True:
        k = tex.find(_PARTIAL, i)
        if k < 0:
            break
        num_end = _braced(tex, k + 5)
        den_end = _braced(tex, num_end) if num_end > 0 and tex.startswith("{", num_end) else -1
        if den_end < 0:
            out.append(tex[i : k + 1])
            i = k + 1
            continue
        num, den = tex[k + 6 : num_end - 1].strip(), tex[num_end + 1 : den_end - 1].strip()
        if not den.startswith("\\partial") or any(c in num + den for c in "+-"):
            out.append(tex[i:den_end])  # a quotient that is not one partial derivative: as it is
        else:
            out.append(f"{tex[i:k]}{{{num}/{den}}}")
        i = den_end
    out.append(tex[i:])
    return "".join(out)


def _slashed_block(block: Block) -> Block:
    if block.get("kind") not in ("math", "boxed") or _PARTIAL not in str(block.get("tex")) + "".join(
        block.get("rows") or []
    ):
        return block
    return {
        **block,
        "tex": slashed(block["tex"]),
        "lines": [slashed(x) for x in block.get("lines") or []],
        "rows": [slashed(x) for x in block.get("rows") or []],
    }


def _one_line(block: Block) -> bool:
    return block.get("kind") in ("math", "boxed") and not block.get("rows")


def _as_math(block: Block) -> str:
    """A one-line display as maths to set beside another: a boxed answer keeps its box."""
    return f"\\boxed{{{block['tex']}}}" if block["kind"] == "boxed" else str(block["tex"])


def _lead_in(block: Block) -> str | None:
    """A short paragraph ending in a colon as maths (``\\text{Coordinate }\\theta\\text{:}``), else None."""
    if block.get("kind") != "text":
        return None
    parts = block.get("parts") or []
    if not parts or parts[-1].get("kind") != "text" or not parts[-1]["text"].rstrip().endswith(":"):
        return None
    pieces = []
    for p in parts:
        if p.get("kind") == "math":
            pieces.append(p["tex"])
        elif p.get("kind") == "text" and _PLAIN.fullmatch(p["text"]):
            pieces.append(f"\\text{{{p['text']}}}")
        else:
            return None
    tex = "".join(pieces)
    return tex if tex_width(tex) <= LEAD_IN_WIDTH else None


def _columns(block: Block, width: float) -> Block:
    """A stacked display of short, unbroken lines in two columns (or on one line when it has few)."""
    lines: list[str] = block.get("lines") or []
    rows: list[str] = block.get("rows") or []
    # each line one row, with its own single alignment point: nothing was broken or expanded entry-wise
    if len(lines) < 2 or len(rows) != len(lines) or any(r.count("&") != 1 for r in rows):
        return block
    joined = ",\\quad ".join(lines)
    if tex_width(joined) <= width:
        return {**block, "tex": joined, "rows": []}
    widths = [tex_width(r) for r in rows]
    # the two columns as wide as their widest equation each (the rows at even and at odd places)
    if max(widths[0::2]) + max(widths[1::2]) + COLUMN_GAP > width:
        return block
    paired = [" & ".join(rows[k : k + 2]) for k in range(0, len(rows), 2)]
    return {**block, "rows": paired}
