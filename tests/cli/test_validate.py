"""`tutgen validate`: specs and sheets read as solve and sheet read them, nothing derived."""

from __future__ import annotations

from pathlib import Path

from typer.testing import CliRunner

from tests.conftest import SPECS
from tutgen.cli.main import app
from tutgen.errors import EXIT_INVALID_SPEC, EXIT_OK


def run(*args: str | Path) -> object:
    return CliRunner().invoke(app, [str(a) for a in args])


def test_every_spec_and_sheet_of_the_repository_is_valid() -> None:
    files = sorted(SPECS.rglob("*.yaml"))
    result = run("validate", *files)
    assert result.exit_code == EXIT_OK, result.output
    assert result.stdout.count(": ok\n") == len(files)


def test_a_sheet_is_read_with_the_specs_it_names(tmp_path: Path) -> None:
    sheet = tmp_path / "sheet.yaml"
    sheet.write_text("title: T\nproblems: [missing.yaml]\n")
    result = run("validate", "--quiet", sheet)
    assert result.exit_code == EXIT_INVALID_SPEC
    assert str(sheet) in result.stderr and "missing.yaml" in result.stderr
    assert result.stdout == ""


def test_every_error_of_every_file_is_reported(tmp_path: Path) -> None:
    bad = [tmp_path / "a.yaml", tmp_path / "b.yaml"]
    bad[0].write_text("tutgen: 1\ntitle: t\nbodys: {}\n")
    bad[1].write_text("tutgen: 1\ntitle: [\n")
    result = run("validate", *bad, SPECS / "tutorial-1/p05-rr-arm.yaml")
    assert result.exit_code == EXIT_INVALID_SPEC
    assert f"{bad[0]}:3:1: error: unknown key 'bodys'" in result.stderr
    assert f"{bad[1]}:" in result.stderr
    assert "p05-rr-arm.yaml: ok" in result.stdout
