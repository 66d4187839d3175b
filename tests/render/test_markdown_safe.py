"""The Markdown's maths stays in the subset GitHub, KaTeX and MathJax all render."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.conftest import all_specs, solved

FORBIDDEN = [
    r"\\label\b",
    r"\\eqref\b",
    r"\\ref\b",
    r"\\bm\b",
    r"\\begin\{align\*?\}",
    r"\\begin\{equation\*?\}",
    r"\\si\b",
    r"\\SI\b",
    r"\\qty\b",
    r"\\dv\b",
    r"\\pdv\b",
    r"\\vb\b",
    r"\\usepackage",
    r"\\newcommand",
    r"\\def\b",
    r"\\left\(\w+ \\right\)\}",  # sympy's \sin{\left(\theta \right)}
    r"\b1\.0\b",
]


def markdown(spec: Path) -> str:
    from tutgen.render.markdown import render_markdown

    return render_markdown(solved(str(spec))[1])


@pytest.mark.parametrize("spec", all_specs(), ids=lambda p: p.stem)
def test_markdown_maths_uses_the_safe_subset(spec: Path) -> None:
    text = markdown(spec)
    found = sorted({m.group(0) for pattern in FORBIDDEN for m in re.finditer(pattern, text)})
    assert found == []


@pytest.mark.parametrize("spec", all_specs(), ids=lambda p: p.stem)
def test_markdown_display_maths_is_fenced_on_own_lines(spec: Path) -> None:
    text = markdown(spec)
    fences = [line for line in text.splitlines() if "$$" in line]
    assert all(line == "$$" for line in fences)
    assert len(fences) % 2 == 0
    inline = [line for line in text.splitlines() if "$$" not in line]
    for line in inline:  # every unescaped single dollar opens or closes inline maths
        assert len(re.findall(r"(?<!\\)\$", line)) % 2 == 0, line
