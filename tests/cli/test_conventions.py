"""The conventions of command-line tools (docs/cli.md): ``-`` as stdin for an input and as stdout for
``-o -``, ``--quiet`` and ``--progress/--no-progress`` on every command that prints status, help text
without Python type names, and shell completion."""

from __future__ import annotations

import io
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner, Result

import tutgen.cli.stdio
from tests.conftest import ROOT, SPECS, solved
from tutgen.cli.main import app
from tutgen.errors import EXIT_INVALID_SPEC, EXIT_OK, EXIT_USAGE, UsageError

TUTORIAL = SPECS / "tutorial-1"
P02 = TUTORIAL / "p02-pivoted-rod.yaml"
P04 = TUTORIAL / "p04-rp-arm.yaml"
#: Problem 4's answers (as in tests/check/test_check_cli.py), all right
P04_ANSWERS = """\
student: Ada
kinetic_energy: m*(r**2*theta_dot**2 + r_dot**2)/2
mass_matrix: [[m*r^2, 0], [0, m]]
"""
P04_KEY = "ask: [kinetic_energy, mass_matrix]\n"
#: Every command and whether it draws a progress bar
COMMANDS = {
    "solve": False,
    "check": True,
    "sheet": True,
    "simulate": False,
    "code": False,
    "figure": False,
    "validate": False,
}


def run(*args: str | Path, stdin: str | None = None) -> Result:
    return CliRunner().invoke(app, [str(a) for a in args], input=stdin)


class Derived:
    """The systems ``derive`` was given (their sources), served from the session cache; a spec piped to
    stdin by :meth:`pipe` is served by the file it came from."""

    def __init__(self) -> None:
        self.sources: list[str] = []
        self.piped: Path | None = None

    def pipe(self, spec: Path) -> str:
        self.piped = spec
        return spec.read_text(encoding="utf-8")

    def derive(self, system: object, *_: object, **__: object) -> object:
        source = str(system.source)  # type: ignore[attr-defined]
        self.sources.append(source)
        return solved(str(self.piped) if source == "<stdin>" else source)[1]


@pytest.fixture
def derived(monkeypatch: pytest.MonkeyPatch) -> Derived:
    import tutgen.engine.pipeline

    for spec in (P02, P04):
        solved(str(spec))  # warm the cache: solved() itself calls the real derive
    spy = Derived()
    monkeypatch.setattr(tutgen.engine.pipeline, "derive", spy.derive)
    return spy


# --- '-' as standard input ---


def test_solve_reads_its_spec_from_stdin(derived: Derived) -> None:
    from_file = run("solve", P02, "-f", "json")
    from_stdin = run("solve", "-", "-f", "json", stdin=derived.pipe(P02))
    assert from_stdin.exit_code == EXIT_OK, from_stdin.output
    assert derived.sources == [str(P02), "<stdin>"]  # the second system was read from stdin, not the file
    assert json.loads(from_stdin.stdout) == json.loads(from_file.stdout)


@pytest.mark.parametrize(
    ("command", "text", "expected"),
    [
        pytest.param("solve", "title: x\nbodies: [\n", "<stdin>:3:1: error: ", id="solve-syntax"),
        pytest.param("validate", "title: x\nbodys: {}\n", "<stdin>:2:1: error: unknown key 'bodys'", id="validate"),
        pytest.param("code", "- 1\n", "<stdin>:1:1: error: expected a mapping", id="code-not-a-mapping"),
    ],
)
def test_errors_of_a_spec_on_stdin_are_located_at_stdin(command: str, text: str, expected: str) -> None:
    result = run(command, "-", stdin=text)
    assert result.exit_code == EXIT_INVALID_SPEC
    assert result.stderr.startswith(expected), result.stderr
    assert "Traceback" not in result.output


def test_validate_reads_stdin_and_names_it() -> None:
    result = run("validate", "-", P02, stdin=P04.read_text(encoding="utf-8"))
    assert result.exit_code == EXIT_OK, result.output
    assert result.stdout.splitlines() == ["<stdin>: ok", f"{P02}: ok"]


def test_check_reads_an_answers_file_from_stdin(derived: Derived, tmp_path: Path) -> None:
    key = tmp_path / "key.yaml"
    key.write_text(P04_KEY, encoding="utf-8")
    answers = tmp_path / "a.yaml"
    answers.write_text(P04_ANSWERS, encoding="utf-8")
    from_file = run("check", P04, answers, "--key", key, "-f", "json")
    from_stdin = run("check", P04, "-", "--key", key, "-f", "json", stdin=P04_ANSWERS)
    assert from_stdin.exit_code == from_file.exit_code == EXIT_OK, from_stdin.output
    (file_report,) = json.loads(from_file.stdout)["files"]
    (stdin_report,) = json.loads(from_stdin.stdout)["files"]
    assert stdin_report["answers"] == "<stdin>" and stdin_report["student"] == "Ada"
    assert stdin_report["items"] == json.loads(json.dumps(file_report["items"]).replace(str(answers), "<stdin>"))
    wrong = run("check", P04, "-", "--key", key, stdin=P04_ANSWERS.replace("[0, m]]", "[0, 2*m]]"))
    assert wrong.exit_code == 1 and "mass_matrix" in wrong.stdout


def test_check_locates_a_bad_answers_file_on_stdin(derived: Derived, tmp_path: Path) -> None:
    key = tmp_path / "key.yaml"
    key.write_text(P04_KEY, encoding="utf-8")
    result = run("check", P04, "-", "--key", key, stdin="kinetic_energy: [\n")
    assert result.exit_code == EXIT_INVALID_SPEC
    assert result.stderr.startswith("<stdin>:2:1: error: "), result.stderr


def test_check_reads_its_spec_from_stdin(derived: Derived, tmp_path: Path) -> None:
    answers = tmp_path / "a.yaml"
    answers.write_text(P04_ANSWERS, encoding="utf-8")
    key = tmp_path / "key.yaml"
    key.write_text(P04_KEY, encoding="utf-8")
    result = run("check", "-", answers, "--key", key, stdin=derived.pipe(P04))
    assert result.exit_code == EXIT_OK, result.output
    assert derived.sources == ["<stdin>"]


@pytest.mark.parametrize(
    "args",
    [("check", "-", "-"), ("check", P04, "-", "--key", "-"), ("validate", "-", "-"), ("solve", "-", "-", "-o", "x/")],
    ids=["spec-and-answers", "answers-and-key", "validate", "solve"],
)
def test_stdin_is_read_once_at_most(args: tuple[str | Path, ...], tmp_path: Path) -> None:
    result = run(*args, stdin="title: x\n")
    assert result.exit_code == EXIT_USAGE
    assert "standard input can be read only once" in result.stderr


def test_a_file_called_dash_is_read_by_its_path(tmp_path: Path) -> None:
    """``-`` alone is stdin; a file of that name is given with its directory (pathlib reads ``./-`` as ``-``)."""
    (tmp_path / "-").write_text(P02.read_text(encoding="utf-8"), encoding="utf-8")
    result = run("validate", tmp_path / "-", stdin="not: [a spec\n")
    assert result.exit_code == EXIT_OK, result.output
    assert result.stdout == f"{tmp_path / '-'}: ok\n"


# --- '-o -' as standard output ---


@pytest.mark.parametrize(
    "args",
    [("solve", P02, "-f", "json"), ("solve", P02, "-f", "tex"), ("code", P02, "--lang", "c")],
    ids=["solve-json", "solve-tex", "code"],
)
def test_dash_o_dash_writes_the_one_file_to_stdout(
    args: tuple[str | Path, ...], derived: Derived, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    plain = run(*args)
    dashed = run(*args, "-o", "-")
    assert dashed.exit_code == plain.exit_code == EXIT_OK, dashed.output
    assert dashed.stdout == plain.stdout and dashed.stdout
    assert list(tmp_path.iterdir()) == []  # no file called '-'


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("solve", P02, P04, "-o", "-"), "several specs need an output directory"),
        (("sheet", TUTORIAL / "sheet.yaml", "-o", "-"), "-o -: a sheet is a directory of files; give a directory"),
        (("simulate", P02, "-o", "-"), "-o -: a simulation writes several files"),
        (("figure", P02, "-o", "-"), "-o -: the figure's format is chosen by the file's suffix"),
        (("check", P04, "a.yaml", "--junit", "-"), "--junit -: standard output holds the report"),
        (("check", P04, "a.yaml", "--summary", "-"), "--summary -: standard output holds the report"),
        (("solve", "-", "-o", "out/"), "a spec read from standard input ('-') has no file name"),
        (("simulate", "-"), "a spec read from standard input ('-') has no file name"),
    ],
    ids=["solve-several", "sheet", "simulate", "figure", "junit", "summary", "solve-dir", "simulate-stdin"],
)
def test_dash_o_dash_is_refused_where_a_command_writes_several_files(
    args: tuple[str | Path, ...], message: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    result = run(*args, stdin="title: x\n")
    assert result.exit_code == EXIT_USAGE, result.output
    assert result.stderr.startswith("error: ") and message in result.stderr, result.stderr
    assert list(tmp_path.iterdir()) == []


class _Stdout(io.TextIOWrapper):
    def __init__(self, tty: bool) -> None:
        super().__init__(io.BytesIO(), encoding="utf-8")
        self.tty = tty

    def isatty(self) -> bool:
        return self.tty


def test_a_pdf_goes_to_stdout_but_never_to_a_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    pipe = _Stdout(tty=False)
    monkeypatch.setattr(sys, "stdout", pipe)
    tutgen.cli.stdio.write_bytes_to_stdout(b"%PDF-1.5 ...", "a PDF")
    assert pipe.buffer.getvalue() == b"%PDF-1.5 ..."  # type: ignore[attr-defined]
    monkeypatch.setattr(sys, "stdout", _Stdout(tty=True))
    with pytest.raises(UsageError, match="refusing to write a PDF to a terminal"):
        tutgen.cli.stdio.write_bytes_to_stdout(b"%PDF-1.5 ...", "a PDF")


# --- --quiet and --progress ---


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_every_command_that_prints_status_takes_quiet_and_progress(command: str) -> None:
    text = run(command, "--help").stdout
    assert re.search(r"^\s+-q, --quiet\s+Print errors only", text, re.MULTILINE), text
    assert ("--progress / --no-progress" in text) is COMMANDS[command]


def test_quiet_validate_prints_nothing_for_valid_files() -> None:
    result = run("validate", "-q", P02, P04)
    assert result.exit_code == EXIT_OK and result.output == ""


def test_quiet_check_prints_no_table_but_keeps_exit_code_and_json(derived: Derived, tmp_path: Path) -> None:
    key = tmp_path / "key.yaml"
    key.write_text(P04_KEY, encoding="utf-8")
    wrong = P04_ANSWERS.replace("[0, m]]", "[0, 2*m]]")
    loud = run("check", P04, "-", "--key", key, "--no-progress", stdin=wrong)
    quiet = run("check", P04, "-", "--key", key, "--quiet", stdin=wrong)
    assert loud.exit_code == quiet.exit_code == 1
    assert "mass_matrix" in loud.stdout and quiet.output == ""
    as_json = run("check", P04, "-", "--key", key, "-q", "-f", "json", stdin=wrong)
    assert json.loads(as_json.stdout)["files"][0]["status"] == "fail"


def test_quiet_simulate_writes_its_files_and_no_summary(derived: Derived, tmp_path: Path) -> None:
    loud = run(
        "simulate", P02, "-o", tmp_path / "a", "--no-plots", "--t-end", "0.5", "--samples", "11", "--q0", "theta=10deg"
    )
    quiet = run(
        "simulate",
        P02,
        "-o",
        tmp_path / "b",
        "--no-plots",
        "--t-end",
        "0.5",
        "--samples",
        "11",
        "--q0",
        "theta=10deg",
        "-q",
    )
    assert loud.exit_code == quiet.exit_code == EXIT_OK, loud.output
    assert "wrote" in loud.stdout and quiet.output == ""
    assert sorted(p.name for p in (tmp_path / "b").iterdir()) == sorted(p.name for p in (tmp_path / "a").iterdir())


def test_quiet_sheet_prints_no_report(tmp_path: Path) -> None:
    sheet = tmp_path / "sheet.yaml"
    sheet.write_text(f"title: One problem\nproblems:\n  - {P02}\n", encoding="utf-8")
    loud = run("sheet", sheet, "-o", tmp_path / "a", "-j", "1", "--no-progress")
    quiet = run("sheet", sheet, "-o", tmp_path / "b", "-j", "1", "--quiet")
    assert loud.exit_code == quiet.exit_code == EXIT_OK, loud.output
    assert loud.stderr.strip() and quiet.output == ""
    assert (tmp_path / "b" / "solutions.md").read_bytes() == (tmp_path / "a" / "solutions.md").read_bytes()


@pytest.mark.parametrize(
    ("wanted", "quiet", "total", "tty", "shown"),
    [
        (None, False, 3, True, True),
        (None, False, 1, True, False),
        (None, False, 3, False, False),
        (True, False, 1, False, True),
        (False, False, 3, True, False),
        (True, True, 3, True, False),
    ],
)
def test_progress_is_drawn_on_a_terminal_unless_asked_otherwise(
    wanted: bool | None, quiet: bool, total: int, tty: bool, shown: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    from tutgen.cli.options import show_progress

    monkeypatch.setattr(sys, "stderr", _Stdout(tty=tty))
    assert show_progress(wanted, quiet, total) is shown


# --- help ---

#: What Typer and Click print for a parameter's Python type or bounds
LEAKS = re.compile(
    r"list\[|<[a-z]+ ?range>|\b(?:INTEGER|FLOAT|TEXT)(?: RANGE)?\b|\bPATH RANGE\b|<(?:int|float|str|path|bool)>"
    r"|\bPath\b"
    r"|\brange\b|x[<>]=|\{[a-z_]+\}"
)


@pytest.mark.parametrize("command", [*sorted(COMMANDS), "schema", None])
def test_help_shows_no_python_type_names(command: str | None) -> None:
    for flag in ("--help", "-h"):
        result = run(*([command] if command else []), flag)
        assert result.exit_code == EXIT_OK
        assert LEAKS.findall(result.stdout) == [], result.stdout


def test_help_names_arguments_as_a_user_would() -> None:
    usages = {c: run(c, "--help").stdout.splitlines()[0] for c in COMMANDS}
    assert usages["solve"] == "Usage: tutgen solve [OPTIONS] SPEC..."
    assert usages["check"] == "Usage: tutgen check [OPTIONS] SPEC ANSWERS..."
    assert usages["validate"] == "Usage: tutgen validate [OPTIONS] FILE..."
    assert usages["sheet"] == "Usage: tutgen sheet [OPTIONS] SHEET"
    text = " ".join(run("check", "--help").stdout.split())
    for shown in ("--junit FILE", "--timeout SECONDS", "-j, --jobs N", "[at least 1]", "--format FORMAT"):
        assert shown in text
    assert "[1 to 10000]" in " ".join(run("sheet", "--help").stdout.split())


# --- shell completion ---


def _module(*args: str, env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "tutgen", *args],
        env={**os.environ, "PYTHONPATH": str(ROOT), **env},
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )


def test_shell_completion_script_and_completions() -> None:
    """`--show-completion bash` prints the script (shell detection off, as in Typer's own tests), and
    the script's call completes a command's options."""
    script = _module("--show-completion", "bash", env={"_TYPER_COMPLETE_TEST_DISABLE_SHELL_DETECTION": "1"})
    assert script.returncode == 0, script.stderr
    assert "complete -o default -F _tutgen_completion tutgen" in script.stdout
    assert "_TUTGEN_COMPLETE=complete_bash" in script.stdout
    options = _module(env={"_TUTGEN_COMPLETE": "complete_bash", "COMP_WORDS": "tutgen sheet --no", "COMP_CWORD": "2"})
    assert "--no-progress" in options.stdout.split() and "--quiet" not in options.stdout.split()
    assert "--install-completion" in run("--help").stdout


def test_cli_sizes_sympys_cache_before_sympy_is_imported() -> None:
    """sympy reads SYMPY_CACHE_SIZE once, when it is first imported: a command sizes the cache for its
    thousands of expressions (issue 17) and keeps a size the user set; numpy gets one BLAS thread."""
    import os
    import subprocess
    import sys

    probe = (
        "import os, sys; from tutgen.cli import main; assert 'sympy' not in sys.modules; main.prepare_environment(); "
        "import sympy.core.cache as c; print(c.SYMPY_CACHE_SIZE, os.environ['OPENBLAS_NUM_THREADS'])"  # as read
    )
    env = {k: v for k, v in os.environ.items() if k not in ("SYMPY_CACHE_SIZE", "OPENBLAS_NUM_THREADS")}
    out = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["10000", "1"]
    out = subprocess.run(
        [sys.executable, "-c", probe],
        env={**env, "SYMPY_CACHE_SIZE": "123", "OPENBLAS_NUM_THREADS": "4"},
        capture_output=True,
        text=True,
        check=True,
    )
    assert out.stdout.split() == ["123", "4"]
