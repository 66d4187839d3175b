"""A small sheet built once per module for the LMS tests: the tutorial's problems 1 (numbers only),
2 (numbers and an expression), 3 (expressions, per-coordinate terms) and a spec whose every free text
is hostile, with two variants, exported as Moodle XML and QTI (through the sheet's build, in memory)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from tests.conftest import SPECS

TUTORIAL = SPECS / "tutorial-1"
HOSTILE = Path(__file__).parent / "hostile-pendulum.yaml"

#: The sheet's title carries markup and markers too (it names the Moodle category).
SHEET = f"""
title: "Mini <img src=x onerror=alert(0)> ]]> {{{{1:SHORTANSWER:=x}}}} a/b"
problems:
  - spec: {TUTORIAL / "p01-composite-inertia.yaml"}
    vary:
      m_p: {{range: [0.5, 2], step: 0.5, unit: kg}}
  - spec: {TUTORIAL / "p02-pivoted-rod.yaml"}
    vary:
      m: {{range: [5, 20], step: 1, value: 15, unit: kg}}
  - spec: {TUTORIAL / "p03-cart-pendulum.yaml"}
    vary:
      m1: {{range: [1, 5], step: 0.5, unit: kg}}
      g: 9.81 m/s^2
  - {HOSTILE}
"""


def build(sheet_text: str, tmp: Path, variants: int, formats: tuple[str, ...] = ("moodle", "qti")) -> dict[str, Any]:
    """Every file of the sheet's build (name -> text or bytes), and its notes under ``"notes"``."""
    from tutgen.sheet.build import build_sheet
    from tutgen.sheet.model import load_sheet
    from tutgen.sheet.variants import variant_ids

    path = tmp / "sheet.yaml"
    path.write_text(sheet_text, encoding="utf-8")
    built = build_sheet(load_sheet(path), formats=formats, variants=variant_ids(variants) if variants else ())
    return {**dict(built.files), "notes": built.notes}


@pytest.fixture(scope="session")
def mini(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    return build(SHEET, tmp_path_factory.mktemp("lms"), 2)
