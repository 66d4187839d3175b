"""The scanners of tutgen.render.layout and blocks jump from one character that matters to the next
(issue 17: they were a sixth of a sheet's layout time, character by character). Each must agree with
the plain character-by-character reading it replaced, written out here as the reference."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from tutgen.render import layout
from tutgen.render.blocks import split_list

TOKENS = [
    "\\", "{", "}", "&", "a", " ", "\\\\", "\\begin{x}", "\\end{x}", "\\{", "\\&", "\n", "\\frac", "\\left(",
    "\\right)", "\\left.", "\\leftarrow", " = ", " + ", " - ", "=", "+", "-", "(", ")", "[", "]", ",\\quad ",
    ",", "\\quad", "x ",
]  # fmt: skip
TEXTS = st.lists(st.sampled_from(TOKENS), max_size=16).map("".join)
DEPTH = {"{": 1, "}": -1}


def reference_split_top(tex: str, separator: str) -> list[str]:
    pieces, depth, env, start, i = [], 0, 0, 0, 0
    while i < len(tex):
        if tex.startswith("\\begin{", i):
            env += 1
        elif tex.startswith("\\end{", i):
            env -= 1
        if depth == 0 and env == 0 and tex.startswith(separator, i):
            pieces.append(tex[start:i])
            i += len(separator)
            start = i
            continue
        if tex[i] == "\\":
            i += 2
            continue
        depth += DEPTH.get(tex[i], 0)
        i += 1
    return [*pieces, tex[start:]]


def reference_group(tex: str, pos: int) -> tuple[str, int]:
    while pos < len(tex) and tex[pos] == " ":
        pos += 1
    if pos >= len(tex):
        return "", pos
    if tex[pos] == "{":
        depth, start = 0, pos
        while pos < len(tex):
            if tex[pos] == "\\":
                pos += 2
                continue
            depth += DEPTH.get(tex[pos], 0)
            pos += 1
            if depth == 0:
                return tex[start + 1 : pos - 1], pos
        return tex[start + 1 :], pos
    if tex[pos] == "\\":
        m = layout._COMMAND.match(tex, pos)
        return (m.group(0), m.end()) if m is not None else ("\\", len(tex))
    return tex[pos], pos + 1


def reference_scan(tex: str) -> tuple[tuple[int, str], ...]:
    points: list[tuple[int, str]] = []
    depth, i = 0, 0
    while i < len(tex):
        if tex.startswith("\\left", i) and not tex[i + 5 : i + 6].isalpha():
            depth, i = depth + 1, i + 6
            continue
        if tex.startswith("\\right", i) and not tex[i + 6 : i + 7].isalpha():
            depth, i = depth - 1, i + 7
            continue
        depth += tex.startswith("\\begin{", i) - tex.startswith("\\end{", i)
        ch = tex[i]
        if ch == "\\":
            i += 2
            continue
        if ch in "{([":
            depth += 1
        elif ch in "})]":
            depth -= 1
        elif depth == 0 and i > 0 and tex[i - 1] == " " and tex[i + 1 : i + 2] == " ":
            end = len(tex[:i].rstrip())
            if ch == "=":
                points.append((i, "rel"))
            elif ch in "+-" and end > 0 and tex[end - 1] not in "=&(,{":
                if not tex.endswith(("\\quad", "\\left("), 0, end):
                    points.append((i, "add"))
        i += 1
    return tuple(points)


def reference_split_list(tex: str) -> list[str]:
    lines, depth, start, i = [], 0, 0, 0
    while i < len(tex):
        if tex.startswith("\\quad ", i) and depth == 0 and i > 0 and tex[i - 1] == ",":
            lines.append(tex[start : i - 1])
            i += len(",\\quad ") - 1
            start = i
            continue
        if tex[i] == "\\":
            i += 2
            continue
        depth += DEPTH.get(tex[i], 0)
        i += 1
    return [ln.strip() for ln in [*lines, tex[start:]]]


@settings(max_examples=300, deadline=None)
@given(TEXTS, st.integers(min_value=0, max_value=40))
def test_the_scanners_read_as_the_plain_character_loop(tex: str, at: int) -> None:
    for separator in ("&", "\\\\"):
        assert layout.split_top(tex, separator) == reference_split_top(tex, separator)
    cur = layout._Cursor(tex, min(at, len(tex)))
    assert (layout._group(cur), cur.pos) == reference_group(tex, min(at, len(tex)))
    assert layout._scan.__wrapped__(tex) == reference_scan(tex)
    assert split_list(tex) == reference_split_list(tex)


def test_examples_of_each() -> None:
    cells = layout.split_top("a & \\begin{x} b & c \\end{x} & {d & e}", "&")
    assert cells == ["a ", " \\begin{x} b & c \\end{x} ", " {d & e}"]
    assert reference_group("  {a{b}\\}c} rest", 0) == ("a{b}\\}c", 11)
    assert [kind for _, kind in layout._scan("x = a + \\left( b - c \\right) - d")] == ["rel", "add", "add"]
    assert split_list("a = 1,\\quad b = {2,\\quad 3}") == ["a = 1", "b = {2,\\quad 3}"]
