"""Line breaking by typeset width (tutgen.render.layout): never scaled, never lost, never too wide."""

from __future__ import annotations

import re

import pytest

from tutgen.render.layout import break_equation, expand_matrices, layout, relation_parts, terms, tex_width


def long_sum(n: int) -> str:
    return " + ".join(
        f"a_{{{i}}} m_{{{i}}} \\dot{{\\theta}}_{{{i}}}^{{2}} \\cos\\theta_{{{i}}}" for i in range(1, n + 1)
    )


LONG_SUM = long_sum(12)


def _content(rows: list[str]) -> str:
    """What the rows say, without the layout: alignment points, indents and the sized brackets."""
    text = " ".join(rows)
    for mark, plain in (
        ("\\bigl(", "\\left("),
        ("\\bigr)", "\\right)"),
        ("\\Bigl(", "\\left("),
        ("\\Bigr)", "\\right)"),
    ):
        text = text.replace(mark, plain)
    text = text.replace("&", " ").replace("\\quad {}", " ").replace("\\quad", " ")
    return re.sub(r"\s+", "", text)


def test_width_grows_with_the_formula_and_fractions_count_their_wider_part() -> None:
    assert 0 < tex_width("x") < tex_width("x + y") < tex_width("x + y + z")
    assert tex_width(r"\frac{a + b + c}{2}") == pytest.approx(tex_width(r"\frac{2}{a + b + c}"))
    assert tex_width(r"\frac{a + b + c}{2}") < tex_width("a + b + c + 2")
    assert tex_width("x^{2}") < tex_width("x 2")  # a script is set small


def test_top_level_terms_and_relations_ignore_brackets_and_fractions() -> None:
    assert terms(r"a - b \left(c + d\right) + \frac{e - f}{2}") == [
        "a",
        r"- b \left(c + d\right)",
        r"+ \frac{e - f}{2}",
    ]
    assert terms("- a + b") == ["- a", "+ b"]  # a leading minus is a sign, not a break
    assert relation_parts(r"L = T - U = \frac{x}{2}") == ["L", "T - U", r"\frac{x}{2}"]


def test_a_short_display_stays_on_one_line() -> None:
    assert layout(["T = a + b"]) == []


@pytest.mark.parametrize("width", [200.0, 300.0, 440.0])
def test_a_long_sum_breaks_before_its_operators_keeping_every_term(width: float) -> None:
    rows = break_equation(f"T = {LONG_SUM}", width)
    assert len(rows) > 1
    assert rows[0].startswith("T &= ")
    assert all(r.startswith("&\\quad {}+ ") for r in rows[1:])  # continuations indented, sign first
    assert all(r.count("&") == 1 for r in rows)
    assert all(tex_width(r) <= width for r in rows)
    assert _content(rows) == re.sub(r"\s+", "", f"T = {LONG_SUM}")


def test_a_term_too_long_for_a_line_breaks_inside_its_bracket() -> None:
    eq = f"H = m \\left({LONG_SUM}\\right) + g"
    rows = break_equation(eq, 300.0)
    assert any("\\bigl(" in r for r in rows) and any("\\bigr)" in r for r in rows)
    assert "\\left(" not in " ".join(rows).split("\\bigl(")[0]  # the broken bracket is the sized pair
    assert _content(rows) == re.sub(r"\s+", "", eq)
    assert all(tex_width(r) <= 300.0 for r in rows)


def test_a_wide_matrix_is_given_entry_by_entry_upper_triangle_when_symmetric() -> None:
    a, b, c = long_sum(5), "x + y", "z"
    eq = f"H = \\begin{{bmatrix}}{a} & {b} \\\\ {b} & {c}\\end{{bmatrix}}"
    assert expand_matrices(eq, 300.0) == [f"H_{{11}} = {a}", f"H_{{12}} = {b}", f"H_{{22}} = {c}"]


def test_a_wide_vector_in_a_chain_is_given_row_by_row() -> None:
    eq = f"\\sum \\mathbf F = \\begin{{bmatrix}}{LONG_SUM} \\\\ y\\end{{bmatrix}} = \\mathbf 0"
    assert expand_matrices(eq, 300.0) == [
        f"\\left(\\sum \\mathbf F\\right)_{{1}} = {LONG_SUM} = 0",
        "\\left(\\sum \\mathbf F\\right)_{2} = y = 0",
    ]


def test_a_list_too_wide_for_one_line_is_stacked_with_aligned_relations() -> None:
    rows = layout(["a = " + long_sum(4), "b = " + long_sum(4)], 300.0)
    firsts = [r for r in rows if not r.startswith("&")]
    assert [r.split("&")[0].strip() for r in firsts] == ["a", "b"]
    assert rows[-1].endswith("}") and any(r.endswith(",") for r in rows)


def test_break_a_bracket_times_a_unit_vector_at_its_thin_space() -> None:
    """``\\left(…\\right)\\,\\mathbf i`` (a Newton–Euler force's component): a sum inside breaks inside its
    bracket, the unit vector kept after its closing; a product inside, that cannot break, breaks at the
    thin space; a text cut right after ``\\,`` (a lone backslash at its end) is measured, never an error."""
    rows = break_equation(f"\\mathbf F = \\left({LONG_SUM}\\right)\\,\\mathbf i", 300.0)
    assert len(rows) > 1 and rows[-1].endswith("\\bigr)\\,\\mathbf i")
    assert _content(rows) == _content([f"\\mathbf F = \\left({LONG_SUM}\\right)\\,\\mathbf i"])
    product = " ".join(f"a_{{{i}}} \\cos\\theta_{{{i}}}" for i in range(1, 11))
    head = f"\\left({product}\\right)"
    tail = "\\frac{m_1 + m_2 + m_3 + m_4}{m_5 + m_6 + m_7 + m_8}\\,\\mathbf i"
    width = tex_width(head) + 30.0
    assert tex_width(f"{head}\\,{tail}") > width
    rows = break_equation(f"{head}\\,{tail}", width)
    assert rows[0].replace("&", "").strip() == head and rows[1].endswith(tail)
    assert all(tex_width(r) <= width for r in rows)
    assert tex_width("x\\right)\\") == pytest.approx(tex_width("x\\right)"))  # asserted before
