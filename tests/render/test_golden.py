"""Golden files: every spec in specs/ rendered as Markdown and LaTeX, compared as exact text (not the
fully symbolic 6-DOF arms of HEAVY_SPECS: megabytes of text no reviewer reads; their dynamics are
checked against Pinocchio and the nested engine instead). A heavy spec that has golden files (the
four-bar, ~10 s to derive) is compared in the ``-m slow`` run only.

Regenerate on purpose only, with ``pytest --update-golden``, and review the diff.
"""

from __future__ import annotations

import difflib
from pathlib import Path

import pytest

from tests.conftest import HEAVY_SPECS, ROOT, all_specs, rendered_text

GOLDEN = ROOT / "tests" / "golden"
FORMATS = ["md", "tex"]


def rendered(spec: Path, fmt: str) -> str:
    return rendered_text(spec, fmt)


@pytest.mark.parametrize("fmt", FORMATS)
# a heavy spec with golden files (the four-bar) is compared too, with ``-m slow`` (tests/conftest.py marks it)
@pytest.mark.parametrize(
    "spec",
    [p for p in all_specs() if p.stem not in HEAVY_SPECS or (GOLDEN / f"{p.stem}.md").exists()],
    ids=lambda p: p.stem,
)
def test_render_matches_golden(spec: Path, fmt: str, request: pytest.FixtureRequest) -> None:
    golden = GOLDEN / f"{spec.stem}.{fmt}"
    actual = rendered(spec, fmt)
    if request.config.getoption("--update-golden"):
        golden.parent.mkdir(parents=True, exist_ok=True)
        golden.write_text(actual, encoding="utf-8", newline="\n")
        return
    assert golden.exists(), f"no golden file {golden.relative_to(ROOT)}; run pytest --update-golden"
    expected = golden.read_text(encoding="utf-8")
    if actual != expected:
        diff = "".join(
            difflib.unified_diff(
                expected.splitlines(keepends=True),
                actual.splitlines(keepends=True),
                fromfile=f"golden/{golden.name}",
                tofile="rendered",
            )
        )
        pytest.fail(f"{golden.name} differs from the rendered output:\n{diff}", pytrace=False)


def test_golden_files_have_a_spec() -> None:
    """No stale golden file is left behind when a spec is renamed or removed."""
    stems = {p.stem for p in all_specs()}
    stale = sorted(p.name for p in GOLDEN.iterdir() if p.name.rsplit(".", 1)[0] not in stems)
    assert stale == []
