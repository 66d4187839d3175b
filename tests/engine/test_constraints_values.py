"""A constrained spec whose parameters have irrational values (an angle in degrees) derives."""

from __future__ import annotations

from pathlib import Path

from tests.conftest import SPECS
from tutgen.engine.pipeline import derive
from tutgen.spec.validate import load_system


def test_an_incline_of_30_degrees_derives_and_passes_its_checks(tmp_path: Path) -> None:
    """30 deg is pi/6: the consistent states' numbers are evaluated from it (it was an internal error,
    "cannot create mpf from pi/6")."""
    text = (SPECS / "examples" / "l-disc-rolling-down-incline.yaml").read_text(encoding="utf-8")
    assert "  alpha: {latex" in text
    spec = tmp_path / "disc.yaml"
    spec.write_text(text.replace("  alpha: {latex", "  alpha: {value: 30 deg, latex"), encoding="utf-8")
    d = derive(load_system(spec))
    assert d.checks and all(c.passed for c in d.checks), [c.detail for c in d.checks if not c.passed]
    assert any("reduced equations" in c.detail for c in d.checks)
