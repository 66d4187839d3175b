"""A sheet's texts (title, course, date) take $…$ maths as a spec's texts do (issue 14)."""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy as sp

from tests.conftest import ROOT
from tutgen.errors import SpecErrors
from tutgen.model.text import MathSpan, RichText
from tutgen.sheet.model import load_sheet

P10 = ROOT / "specs" / "tutorial-1" / "p10-given-kinetic-energy.yaml"


def _sheet(tmp_path: Path, title: str) -> Path:
    (tmp_path / "p10.yaml").write_text(P10.read_text(encoding="utf-8"), encoding="utf-8")
    path = tmp_path / "sheet.yaml"
    path.write_text(f"title: '{title}'\ncourse: Costs \\$5\nproblems: [p10.yaml]\n", encoding="utf-8")
    return path


def test_sheet_texts_are_rich_text(tmp_path: Path) -> None:
    sheet = load_sheet(_sheet(tmp_path, "Dynamics of $H(q) q_ddot = tau$"))
    assert isinstance(sheet.title, RichText) and sheet.title == "Dynamics of $H(q) q_ddot = tau$"
    span = sheet.title.parts[1]
    assert isinstance(span, MathSpan) and span.relations == ("=",)
    assert span.terms[1] == sp.Symbol("tau")
    assert sheet.course.parts == ("Costs $5",)


def test_a_bad_span_in_a_sheet_is_located(tmp_path: Path) -> None:
    with pytest.raises(SpecErrors) as info:
        load_sheet(_sheet(tmp_path, "Tutorial $1 +$"))
    (error,) = info.value.errors
    assert (error.location.line, error.location.col) == (1, 22)
    assert "in the maths '$1 +$': expected an expression after '+'" in error.message
