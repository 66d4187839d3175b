"""The round trip for the whole tutorial sheet with 30 variants (slow: the build and 300 derivations to
mark against, 24 min on two busy cores): every answer read back out of the Moodle export (300
questions) and the QTI package (its items) is marked correct by the check."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.conftest import SPECS
from tests.lms.conftest import build
from tests.lms.roundtrip import mark, write_tree


@pytest.mark.slow
def test_roundtrip_tutorial_sheet_with_30_variants(tmp_path: Path) -> None:
    sheet = (SPECS / "tutorial-1" / "sheet.yaml").read_text(encoding="utf-8")
    here = SPECS / "tutorial-1"  # the sheet's specs by absolute paths: the sheet file is written elsewhere
    sheet = sheet.replace("spec: p", f"spec: {here}/p").replace("  - p10", f"  - {here}/p10")
    files = build(sheet, tmp_path, 30)
    write_tree(files, tmp_path)
    results = mark(tmp_path, files)
    assert [r for r in results if r[2] != "pass"] == []
    assert len([r for r in results if r[0] == "moodle"]) == 300
