"""The CLI boundary: one --timeout budget for load, derive and render; SIGTERM and Ctrl-C end with
143 and 130; over-long -o names are usage errors; messages never carry escape sequences."""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from typer.testing import CliRunner, Result

from tests.conftest import SPECS
from tutgen.cli.main import app
from tutgen.errors import EXIT_CANNOT_DERIVE, EXIT_INTERRUPTED, EXIT_TERMINATED, EXIT_USAGE, Terminated

SPEC = SPECS / "tutorial-1" / "p02-pivoted-rod.yaml"


def invoke(*args: str | Path) -> Result:
    return CliRunner().invoke(app, [str(a) for a in args])


def test_cli_timeout_covers_rendering(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    """What the derivation used is gone for rendering: a slow render is stopped, naming its stage."""
    import tutgen.api

    real = tutgen.api._render

    def slow(*args: object, **kwargs: object) -> object:
        time.sleep(30)
        return real(*args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(tutgen.api, "_render", slow)
    start = time.monotonic()
    result = invoke("solve", SPEC, "--timeout", "2", "-o", tmp_path / "out.md")
    assert time.monotonic() - start < 20
    assert result.exit_code == EXIT_CANNOT_DERIVE, result.output
    assert "the run did not finish within 2 s" in result.stderr
    assert "it was at: rendering, p02-pivoted-rod.yaml as md" in result.stderr
    assert not (tmp_path / "out.md").exists()


@pytest.mark.parametrize(
    ("exc", "code", "word"),
    [pytest.param(Terminated, EXIT_TERMINATED, "terminated", id="sigterm"),
     pytest.param(KeyboardInterrupt, EXIT_INTERRUPTED, "interrupted", id="sigint")],
)  # fmt: skip
def test_cli_signals_end_with_the_shell_codes(
    monkeypatch: pytest.MonkeyPatch, exc: type[BaseException], code: int, word: str
) -> None:
    import tutgen.api

    def stop(*args: object, **kwargs: object) -> None:
        raise exc()

    monkeypatch.setattr(tutgen.api, "solve_and_derive", stop)  # what `tutgen solve` calls
    result = invoke("solve", SPEC)
    assert result.exit_code == code
    assert result.stderr.strip() == word


def test_cli_over_long_output_name_is_a_usage_error(tmp_path: Path) -> None:
    result = invoke("solve", SPEC, "-o", tmp_path / ("n" * 400 + ".md"))
    assert result.exit_code == EXIT_USAGE, result.output
    assert "is 403 bytes long; the file system allows 255" in result.stderr


def test_cli_output_name_with_a_nul_is_a_usage_error() -> None:
    result = invoke("solve", SPEC, "-o", "a\0b.md")
    assert result.exit_code == EXIT_USAGE, result.output
    assert "NUL" in result.stderr


def test_cli_error_messages_carry_no_escape_sequences(tmp_path: Path) -> None:
    """A path the user typed is quoted in the message, without its escape sequences."""
    result = invoke("solve", SPEC, "--template-dir", tmp_path / "t\x1b[2J\x1b]0;pwned\x07")
    assert result.exit_code == EXIT_USAGE, result.output
    assert "\x1b" not in result.stderr and "\x07" not in result.stderr
    assert f"--template-dir {tmp_path}/t: not a directory" in result.stderr
