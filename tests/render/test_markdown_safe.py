"""The Markdown's maths stays in the subset GitHub, KaTeX and MathJax all render."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.conftest import ROOT, all_specs, solved

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


def test_given_value_is_shown_in_the_unit_it_was_written_in(tmp_path):
    """`a: 20 cm` is 1/5 m inside; the worked solution gives it back as 20 cm (not "1/5 cm")."""
    from tutgen.engine.pipeline import derive
    from tutgen.render.markdown import render_markdown
    from tutgen.spec.validate import load_system_text

    text = """tutgen: 1
title: units as written
parameters: {m: 2.5 kg, a: 20 cm, g: 9.81 m/s^2, phi: 30 deg}
coordinates: [theta]
gravity: [0, -g, 0]
bodies:
  bob: {mass: m, com: [a, 0, 0]}
joints:
  pivot: {type: revolute, parent: ground, child: bob, axis: z, coordinate: theta, offset: phi}
"""
    md = render_markdown(derive(load_system_text(text, "units.yaml"), method="lagrange"))
    given = next(line for line in md.splitlines() if line.startswith("**Given.**"))
    for shown in (r"m = 2.5\ \mathrm{kg}", r"a = 20\ \mathrm{cm}", r"g = 9.81\ \mathrm{m/s^2}", r"= 30\ \mathrm{deg}"):
        assert shown in given, (shown, given)
    assert "frac" not in given


def test_results_too_long_to_read_are_printed_as_the_recursive_program(monkeypatch):
    """Past PROGRAM_BUDGET operations a serial arm's H, C, G are printed as the straight-line program
    (every x_k used is defined before use), past PRINT_BUDGET entry by entry; the symbolic PUMA's
    180 000 operations otherwise make 7 MB of Markdown."""
    import re

    from tutgen.render.markdown import render_markdown
    from tutgen.render.sections import matrix

    _, d, _ = solved(str(ROOT / "specs" / "arms" / "scara.yaml"))
    assert d.program is not None
    whole = render_markdown(d)
    assert "intermediate quantities" not in whole and "H_{11} &= " in whole  # too wide for a matrix: by entry

    monkeypatch.setattr(matrix, "PRINT_BUDGET", 0)  # read where the matrix sections are built
    entries = render_markdown(d)
    assert "H_{11}" in entries and "H = \\begin{bmatrix}" not in entries and "intermediate" not in entries
    assert "too many to print here" in entries  # the Christoffel symbols are left to the JSON

    monkeypatch.setattr(matrix, "PROGRAM_BUDGET", 0)
    program = render_markdown(d)
    assert "intermediate quantities" in program
    defined: set[str] = set()
    for line in re.findall(r"(x_\{\d+\}) &= ([^\\\n]*(?:\\[^\\\n][^\\\n]*)*)", program):
        name, rhs = line
        used = set(re.findall(r"x_\{\d+\}", rhs))
        assert used <= defined, f"{name} uses {used - defined} before it is defined"
        defined.add(name)
    assert len(defined) >= 10
    for i in range(1, 5):
        assert f"H_{{{i}{i}}} &= " in program and f"C_{{{i}}} &= " in program and f"G_{{{i}}} &= " in program
