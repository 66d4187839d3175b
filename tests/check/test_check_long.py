"""`tutgen check` of a result longer than an expression a user may write (the spec grammar's 2 000
characters): tutgen's own text is read back without that limit, an answer up to twice the result's."""

from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner, Result

from tests.conftest import ROOT, solved
from tutgen.cli.main import app
from tutgen.errors import EXIT_CHECK_FAILED, EXIT_OK


def run(*args: str | Path) -> Result:
    return CliRunner().invoke(app, [str(a) for a in args])


def test_check_cli_marks_a_result_longer_than_a_users_expression(tmp_path: Path) -> None:
    """The planar 4R arm's first equation of motion is 2 012 characters of tutgen's JSON, past the 2 000
    an expression the user writes may have: reading tutgen's own result back was an internal error (exit
    70) for every answers file. An answer copied from the JSON is marked right; one far longer than the
    result is still refused, as unreadable."""
    spec = ROOT / "specs" / "arms" / "planar-4r.yaml"
    _, _, doc = solved(str(spec))
    eom = doc["results"]["equations_of_motion"]
    assert len(eom[0]) > 2000
    copied = tmp_path / "copied.yaml"
    copied.write_text(json.dumps({"student": "Ada", "equations_of_motion": eom}), encoding="utf-8")
    result = run("check", spec, copied, "--key", _key(tmp_path, "ask: [equations_of_motion]\n"))
    assert result.exit_code == EXIT_OK, result.output
    assert "internal error" not in result.output
    padded = " + ".join([f"({eom[0]})/4"] * 4) + " + 0*q1" * 800
    hostile = tmp_path / "hostile.yaml"
    hostile.write_text(json.dumps({"student": "Bob", "equations_of_motion": [padded, *eom[1:]]}), encoding="utf-8")
    result = run("check", spec, hostile, "--key", _key(tmp_path, "ask: [equations_of_motion]\n"))
    assert result.exit_code == EXIT_CHECK_FAILED, result.output
    assert "the expression is too long" in result.output
    assert "internal error" not in result.output


def _key(tmp_path: Path, text: str) -> Path:
    key = tmp_path / "key.yaml"
    key.write_text(text, encoding="utf-8")
    return key
