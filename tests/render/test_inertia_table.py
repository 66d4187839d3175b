"""A composite body's mass properties as tables (tutorial p01): hand-derived numbers in the right cells."""

from __future__ import annotations

import math as m
from typing import Any

import pytest

from tests.conftest import SPECS, solved
from tutgen.render.views import solution_view

P01 = SPECS / "tutorial-1" / "p01-composite-inertia.yaml"
RHO = 7849.0  # the spec's density, kg/m^3; the dimensions are the problem statement's


def _number(cell: list[dict[str, str]]) -> float:
    tex = "".join(p.get("tex", p.get("text", "")) for p in cell)
    tex = tex.replace("\\times 10^{", "e").replace("}", "").replace(" ", "")
    return float(tex)


def _tables() -> list[dict[str, Any]]:
    view = solution_view(solved(str(P01))[1])
    return [b for s in view["sections"] for b in s["blocks"] if b["kind"] == "table"]


def test_p01_parts_table_holds_each_parts_formula_and_hand_derived_moments() -> None:
    parts, _ = _tables()
    names = [row[0][0]["text"] for row in parts["rows"][::2]]
    assert names == ["block (box)", "cylinder", "point"]  # a name that says its shape: not "cylinder (cylinder)"
    head = ["".join(p.get("tex", p.get("text", "")) for p in cell) for cell in parts["header"]]
    assert head[0] == "Part" and all("kg\\,m^2" in h for h in head[3:])  # every moment column has its unit
    block, cyl = parts["rows"][1], parts["rows"][3]
    m_block = RHO * 0.05 * 0.15 * 0.05
    m_cyl = RHO * m.pi * 0.025**2 * 0.08
    assert _number(block[2]) == pytest.approx(m_block, rel=1e-3)
    assert _number(block[3]) == pytest.approx(m_block * (0.15**2 + 0.05**2) / 12, rel=1e-3)
    assert _number(cyl[3]) == pytest.approx(m_cyl * 0.025**2 / 2, rel=1e-3)
    assert _number(cyl[4]) == pytest.approx(m_cyl * (0.08**2 + 3 * 0.025**2) / 12, rel=1e-3)
    # the formula in symbols, in the tutorial's order (m (3r^2 + h^2)/12, the radius first), stacked in its cell
    assert parts["rows"][0][3][0]["tex"].endswith("\\frac{m \\left(b^{2} + c^{2}\\right)}{12}")
    assert parts["rows"][2][4][0]["tex"].endswith("\\frac{m \\left(3 r^{2} + h^{2}\\right)}{12}")


def test_p01_shift_table_holds_each_parts_m_d2_terms() -> None:
    _, shifts = _tables()
    m_cyl = RHO * m.pi * 0.025**2 * 0.08
    rows = {row[0][0]["text"]: row for row in shifts["rows"]}
    cyl, point = rows["cylinder"], rows["point"]
    # columns: part, d, m(dy²+dz²), m(dx²+dz²), m(dx²+dy²), −m dx dy
    assert _number(cyl[2]) == pytest.approx(m_cyl * 0.05**2, rel=1e-3)
    assert _number(cyl[3]) == pytest.approx(m_cyl * 0.065**2, rel=1e-3)
    assert _number(cyl[4]) == pytest.approx(m_cyl * (0.065**2 + 0.05**2), rel=1e-3)
    assert _number(cyl[5]) == pytest.approx(-m_cyl * 0.065 * 0.05, rel=1e-3)
    assert _number(point[3]) == pytest.approx(1.0 * 0.1**2, rel=1e-3)
