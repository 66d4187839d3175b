"""`tutgen solve --format tex|pdf` and `--template-dir`."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from typer.testing import CliRunner, Result

from tests.conftest import SPECS, solved
from tutgen.cli.main import app
from tutgen.errors import EXIT_OK, EXIT_USAGE

P05 = SPECS / "tutorial-1" / "p05-rr-arm.yaml"
needs_latex = pytest.mark.skipif(
    shutil.which("latexmk") is None or shutil.which("pdflatex") is None, reason="latexmk/pdflatex not installed"
)


def run(*args: str | Path) -> Result:
    return CliRunner().invoke(app, [str(a) for a in args])


@pytest.fixture
def cached_derive(monkeypatch: pytest.MonkeyPatch) -> None:
    import tutgen.engine.pipeline

    solved(str(P05))
    monkeypatch.setattr(tutgen.engine.pipeline, "derive", lambda system, *_, **__: solved(system.source)[1])


@pytest.mark.usefixtures("cached_derive")
def test_solve_tex_to_stdout() -> None:
    from tutgen.api import render

    result = run("solve", P05, "--format", "tex")
    assert result.exit_code == EXIT_OK, result.output
    assert result.stdout == render(solved(str(P05))[1], "tex")


def test_solve_pdf_needs_an_output_file() -> None:
    result = run("solve", P05, "--format", "pdf")
    assert result.exit_code == EXIT_USAGE
    assert "-o" in result.stderr


@pytest.mark.usefixtures("cached_derive")
def test_solve_pdf_without_latex_exits_6(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    import tutgen.render.pdf

    monkeypatch.setattr(tutgen.render.pdf.shutil, "which", lambda name: None)
    result = run("solve", P05, "--format", "pdf", "-o", tmp_path / "p05.pdf")
    assert result.exit_code == 6
    assert "texlive-latex-base texlive-latex-recommended texlive-pictures latexmk" in result.stderr
    assert list(tmp_path.iterdir()) == []


@pytest.mark.pdf
@needs_latex
@pytest.mark.usefixtures("cached_derive")
def test_solve_pdf_writes_a_pdf(tmp_path: Path) -> None:
    result = run("solve", P05, "--format", "pdf", "-o", f"{tmp_path}/out/")
    assert result.exit_code == EXIT_OK, result.output
    assert [p.name for p in tmp_path.joinpath("out").iterdir()] == ["p05-rr-arm.pdf"]
    assert (tmp_path / "out" / "p05-rr-arm.pdf").read_bytes().startswith(b"%PDF-")


@pytest.mark.usefixtures("cached_derive")
def test_solve_template_dir(tmp_path: Path) -> None:
    (tmp_path / "solution.tex.j2").write_text(r"\title{((( title | latex_escape )))}" + "\n", encoding="utf-8")
    result = run("solve", P05, "--format", "tex", "--template-dir", tmp_path)
    assert result.exit_code == EXIT_OK, result.output
    assert result.stdout == "\\title{Planar RR arm with lumped end masses}\n"


def test_solve_template_dir_must_exist(tmp_path: Path) -> None:
    result = run("solve", P05, "--template-dir", tmp_path / "nope")
    assert result.exit_code == EXIT_USAGE
    assert "nope" in result.stderr


@pytest.mark.parametrize("fmt", ["md", "tex"])
def test_solve_is_byte_identical_across_processes(fmt: str, tmp_path: Path) -> None:
    """Fresh interpreters with different hash seeds give the same bytes (no set or dict order leaks)."""
    import os
    import subprocess
    import sys

    from tests.conftest import ROOT

    outs = []
    for seed in ("1", "2"):
        env = {**os.environ, "PYTHONPATH": str(ROOT), "PYTHONHASHSEED": seed}
        proc = subprocess.run(
            [sys.executable, "-m", "tutgen", "solve", str(P05), "--format", fmt],
            cwd=tmp_path,
            env=env,
            capture_output=True,
            timeout=120,
            check=False,
        )
        assert proc.returncode == EXIT_OK, proc.stderr.decode()
        outs.append(proc.stdout)
    assert outs[0] == outs[1]
