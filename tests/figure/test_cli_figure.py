"""`tutgen figure` and the figure files beside a Markdown solution."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tests.conftest import SPECS
from tutgen.cli.main import app

P05 = SPECS / "tutorial-1" / "p05-rr-arm.yaml"
P09 = SPECS / "tutorial-1" / "p09-pr-manipulator.yaml"


def test_cli_figure_svg_and_tex(tmp_path: Path) -> None:
    runner = CliRunner()
    out = tmp_path / "fig.svg"
    result = runner.invoke(app, ["figure", str(P05), "-o", str(out)])
    assert result.exit_code == 0, result.output
    ET.fromstring(out.read_bytes())
    first = out.read_bytes()
    again = runner.invoke(app, ["figure", str(P05), "-o", str(out), "--force"])
    assert again.exit_code == 0 and out.read_bytes() == first
    tex = tmp_path / "fig.tex"
    assert runner.invoke(app, ["figure", str(P05), "-o", str(tex)]).exit_code == 0
    text = tex.read_text()
    assert "\\begin{tikzpicture}" in text and "\\theta_1" in text and "\\documentclass" in text


def test_cli_figure_refuses_unknown_suffix_and_existing_file(tmp_path: Path) -> None:
    runner = CliRunner()
    bad = runner.invoke(app, ["figure", str(P05), "-o", str(tmp_path / "fig.png")])
    assert bad.exit_code == 2 and "expected a file ending in .svg, .tex or .pdf" in bad.output
    existing = tmp_path / "fig.svg"
    existing.write_text("mine")
    kept = runner.invoke(app, ["figure", str(P05), "-o", str(existing)])
    assert kept.exit_code == 2 and existing.read_text() == "mine"


def test_cli_figure_bad_spec_is_a_spec_error(tmp_path: Path) -> None:
    spec = tmp_path / "s.yaml"
    spec.write_text("title: t\nfigure: {file: ../x.png}\n")
    result = CliRunner().invoke(app, ["figure", str(spec), "-o", str(tmp_path / "f.svg")])
    assert result.exit_code == 3
    assert "s.yaml:2:16: error: figure.file '../x.png' leads out" in result.output
    assert "Traceback" not in result.output


@pytest.mark.slow
def test_cli_figure_pdf(tmp_path: Path) -> None:
    out = tmp_path / "fig.pdf"
    result = CliRunner().invoke(app, ["figure", str(P05), "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert out.read_bytes().startswith(b"%PDF")


def test_solve_markdown_writes_the_svg_beside_it(tmp_path: Path) -> None:
    runner = CliRunner()
    out = tmp_path / "sol.md"
    result = runner.invoke(app, ["solve", str(P09), "-o", str(out)])
    assert result.exit_code == 0, result.output
    svg = tmp_path / "p09-pr-manipulator.figure.svg"
    assert svg.exists()
    assert "](<p09-pr-manipulator.figure.svg>)" in out.read_text()
    again = runner.invoke(app, ["solve", str(P09), "-o", str(out)])
    assert again.exit_code == 2  # the .md exists: nothing is overwritten without --force


def test_solve_markdown_refuses_to_overwrite_a_figure(tmp_path: Path) -> None:
    svg = tmp_path / "p09-pr-manipulator.figure.svg"
    svg.write_text("mine")
    result = CliRunner().invoke(app, ["solve", str(P09), "-o", str(tmp_path / "sol.md")])
    assert result.exit_code == 2 and "exists; add --force" in result.output
    assert svg.read_text() == "mine" and not (tmp_path / "sol.md").exists()


def test_solve_json_says_where_the_figure_is() -> None:
    result = CliRunner().invoke(app, ["solve", str(P09), "--format", "json"])
    assert result.exit_code == 0, result.output
    figure = json.loads(result.output)["figure"]
    assert figure["svg"] == "p09-pr-manipulator.figure.svg"
    assert figure["generated"] is True and figure["file"] is None
    assert figure["view"] == "planar"
    assert set(figure["at"]) == {"d", "theta"}
    assert "coordinate:theta" in figure["labels"]


def test_sheet_latex_sets_the_figure_beside_each_problem() -> None:
    from tests.conftest import solved
    from tutgen.sheet.render import problem_view, render_sheet, sheet_context

    _system, derivation, _doc = solved(str(P09))
    header = {"title": "Sheet", "course": "", "date": "", "label": ""}
    context = sheet_context(header, [derivation, derivation], solution=False)
    tex = render_sheet(context, "questions", "tex")
    assert tex.count("\\begin{tikzpicture}") == 2
    assert "\\usepackage{tikz}" in tex
    assert problem_view(1, derivation, solution=False)["figure"]["svg"] == "p09-pr-manipulator.figure.svg"


def test_solution_latex_and_markdown_hold_the_figure() -> None:
    from tests.conftest import solved
    from tutgen.api import render

    _system, derivation, _doc = solved(str(P09))
    tex = render(derivation, "tex")
    assert isinstance(tex, str)
    assert "\\usepackage{tikz}" in tex and tex.index("\\begin{tikzpicture}") < tex.index("\\section")
    md = render(derivation, "md")
    assert isinstance(md, str) and md.splitlines()[2] == (
        "![Figure: PR manipulator with a singular inertia matrix](<p09-pr-manipulator.figure.svg>)"
    )
