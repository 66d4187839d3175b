"""The `tutgen` command line: output, files, exit codes, error reports, determinism, the schema.

Most tests run the app in-process with Typer's CliRunner, with the engine's ``derive`` served from
the session cache of ``tests/conftest.py`` (derivations are slow); a few run ``python -m tutgen``
for real, in a subprocess.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import jsonschema
import pytest
from typer.testing import CliRunner, Result

import tutgen
from tests.conftest import ROOT, SPECS, all_specs, rendered_text, solved
from tutgen.cli.main import app
from tutgen.errors import (
    EXIT_CANNOT_DERIVE,
    EXIT_INTERNAL,
    EXIT_INVALID_SPEC,
    EXIT_OK,
    EXIT_USAGE,
    DerivationError,
)
from tutgen.spec.loader import load_yaml_file

P04 = SPECS / "tutorial-1" / "p04-rp-arm.yaml"
P05 = SPECS / "tutorial-1" / "p05-rr-arm.yaml"
P06 = SPECS / "tutorial-1" / "p06-two-prismatic.yaml"
P10 = SPECS / "tutorial-1" / "p10-given-kinetic-energy.yaml"
BAD_SPECS = ROOT / "tests" / "bad_specs"


def run(*args: str | Path) -> Result:
    return CliRunner().invoke(app, [str(a) for a in args])


def run_module(
    *args: str | Path, cwd: Path, hashseed: str = "0", flags: tuple[str, ...] = ()
) -> subprocess.CompletedProcess:
    """``python -m tutgen ARGS`` in a fresh interpreter, with this checkout on the path."""
    env = {**os.environ, "PYTHONPATH": str(ROOT), "PYTHONHASHSEED": hashseed}
    return subprocess.run(
        [sys.executable, *flags, "-m", "tutgen", *map(str, args)],
        cwd=cwd,
        env=env,
        capture_output=True,
        timeout=120,
        check=False,
    )


@pytest.fixture
def cached_derive(monkeypatch: pytest.MonkeyPatch) -> None:
    """Serve ``derive`` from the session cache: the CLI still loads, validates, renders and writes."""
    import tutgen.engine.pipeline

    for spec in (P04, P05, P06):
        solved(str(spec))  # warm the cache first: solved() itself calls the real derive
    monkeypatch.setattr(tutgen.engine.pipeline, "derive", lambda system, *_, **__: solved(system.source)[1])


@pytest.fixture
def broken_derive(monkeypatch: pytest.MonkeyPatch) -> None:
    """A bug in the engine."""
    import tutgen.engine.pipeline

    def derive(system: object, *args: object, **kwargs: object) -> None:
        raise RuntimeError("boom in the engine")

    monkeypatch.setattr(tutgen.engine.pipeline, "derive", derive)


def expected_output(spec: Path, fmt: str) -> str:
    return rendered_text(spec, fmt)


# --- the app itself ---


def test_version_prints_name_and_version() -> None:
    result = run("--version")
    assert result.exit_code == EXIT_OK
    assert result.stdout == f"tutgen {tutgen.__version__}\n"


def test_help_lists_the_commands() -> None:
    result = run("--help")
    assert result.exit_code == EXIT_OK
    assert "solve" in result.stdout
    assert "schema" in result.stdout


@pytest.mark.parametrize("command", [(), ("solve",), ("check",), ("sheet",), ("figure",), ("schema",)])
def test_dash_h_is_help(command: tuple[str, ...]) -> None:
    short, long = run(*command, "-h"), run(*command, "--help")
    assert short.exit_code == long.exit_code == EXIT_OK
    assert short.stdout == long.stdout
    assert "-h, --help" in short.stdout


def test_help_does_not_import_sympy(tmp_path: Path) -> None:
    proc = run_module("--help", cwd=tmp_path, flags=("-X", "importtime"))
    assert proc.returncode == EXIT_OK, proc.stderr.decode()
    assert b"solve" in proc.stdout
    imported = proc.stderr.decode()
    assert "tutgen.cli.main" in imported  # the import log is there ...
    assert "sympy" not in imported  # ... and sympy is not in it


def test_python_m_tutgen_version(tmp_path: Path) -> None:
    proc = run_module("--version", cwd=tmp_path)
    assert proc.returncode == EXIT_OK
    assert proc.stdout.decode() == f"tutgen {tutgen.__version__}\n"


def test_unknown_format_is_a_usage_error() -> None:
    result = run("solve", P04, "--format", "docx")
    assert result.exit_code == EXIT_USAGE
    assert "docx" in result.stderr


# --- solve: stdout and files ---


@pytest.mark.usefixtures("cached_derive")
def test_solve_markdown_to_stdout() -> None:
    result = run("solve", P04)
    assert result.exit_code == EXIT_OK, result.stderr
    assert result.stdout == expected_output(P04, "md")
    assert "Planar RP arm with a tip mass" in result.stdout
    assert result.stderr == ""


@pytest.mark.usefixtures("cached_derive")
def test_solve_json_to_stdout() -> None:
    result = run("solve", P05, "--format", "json")
    assert result.exit_code == EXIT_OK, result.stderr
    document = json.loads(result.stdout)
    assert document["results"]["mass_matrix"]
    assert result.stdout == expected_output(P05, "json")


@pytest.mark.usefixtures("cached_derive")
def test_solve_to_a_file(tmp_path: Path) -> None:
    target = tmp_path / "solution.md"
    result = run("solve", P04, "-o", target)
    assert result.exit_code == EXIT_OK, result.stderr
    assert result.stdout == ""
    assert target.read_text(encoding="utf-8") == expected_output(P04, "md")
    # no temporary file left behind; the figure is written beside the Markdown (docs/figures.md)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p04-rp-arm.figure.svg", "solution.md"]


@pytest.mark.usefixtures("cached_derive")
def test_solve_writes_files_readable_like_any_other(tmp_path: Path) -> None:
    old = os.umask(0o022)
    try:
        result = run("solve", P04, "-o", tmp_path / "solution.md")
    finally:
        os.umask(old)
    assert result.exit_code == EXIT_OK, result.stderr
    assert (tmp_path / "solution.md").stat().st_mode & 0o777 == 0o644


@pytest.mark.usefixtures("broken_derive")
def test_several_specs_need_an_output_directory() -> None:
    # refused before anything is derived (the engine here would fail)
    result = run("solve", P04, P06)
    assert result.exit_code == EXIT_USAGE
    assert result.stderr == "error: several specs need an output directory: add -o DIR\n"
    assert result.stdout == ""


@pytest.mark.usefixtures("cached_derive")
@pytest.mark.parametrize("fmt", ["md", "json"])
def test_output_directory_gets_one_file_per_spec(tmp_path: Path, fmt: str) -> None:
    out = tmp_path / "out"
    result = run("solve", P04, P06, "--format", fmt, "-o", out)
    assert result.exit_code == EXIT_OK, result.stderr
    figures = ["p04-rp-arm.figure.svg", "p06-two-prismatic.figure.svg"] if fmt == "md" else []
    assert sorted(p.name for p in out.iterdir()) == sorted([f"p04-rp-arm.{fmt}", f"p06-two-prismatic.{fmt}", *figures])
    for spec in (P04, P06):
        assert (out / f"{spec.stem}.{fmt}").read_text(encoding="utf-8") == expected_output(spec, fmt)


@pytest.mark.usefixtures("cached_derive")
def test_output_path_ending_in_a_slash_is_a_directory(tmp_path: Path) -> None:
    result = run("solve", P04, "-o", f"{tmp_path / 'out'}/")
    assert result.exit_code == EXIT_OK, result.stderr
    assert (tmp_path / "out" / "p04-rp-arm.md").is_file()


@pytest.mark.usefixtures("broken_derive")
def test_existing_output_is_kept_without_force(tmp_path: Path) -> None:
    target = tmp_path / "solution.md"
    target.write_text("keep me\n", encoding="utf-8")
    result = run("solve", P04, "-o", target)
    assert result.exit_code == EXIT_USAGE
    assert result.stderr == f"error: {target} exists; add --force to overwrite it\n"
    assert target.read_text(encoding="utf-8") == "keep me\n"


@pytest.mark.usefixtures("cached_derive")
def test_existing_output_is_overwritten_with_force(tmp_path: Path) -> None:
    target = tmp_path / "solution.md"
    target.write_text("old\n", encoding="utf-8")
    result = run("solve", P04, "-o", target, "--force")
    assert result.exit_code == EXIT_OK, result.stderr
    assert target.read_text(encoding="utf-8") == expected_output(P04, "md")


@pytest.mark.usefixtures("cached_derive")
@pytest.mark.parametrize("how", ["same-path", "symlink", "hard-link", "directory"])
def test_output_never_overwrites_a_spec(tmp_path: Path, how: str) -> None:
    spec = tmp_path / "arm.yaml"
    shutil.copyfile(P04, spec)
    before = spec.read_bytes()
    if how == "same-path":
        target = spec
    elif how == "symlink":
        target = tmp_path / "link.md"
        target.symlink_to(spec)
    elif how == "hard-link":
        target = tmp_path / "link.md"
        os.link(spec, target)
    else:  # -o DIR where the solution would get the spec's own name
        spec = tmp_path / "arm.md"
        shutil.copyfile(P04, spec)
        before = spec.read_bytes()
        target = tmp_path
    result = run("solve", spec, "-o", target, "--force")
    assert result.exit_code == EXIT_USAGE, result.output
    assert "refusing to overwrite the spec" in result.stderr
    assert spec.read_bytes() == before


# --- errors ---


def test_missing_spec_file(tmp_path: Path) -> None:
    missing = tmp_path / "missing.yaml"
    result = run("solve", missing)
    assert result.exit_code == EXIT_INVALID_SPEC
    assert result.stderr.startswith(f"{missing}: error: cannot read file")
    assert "Traceback" not in result.output


def test_several_bad_specs_report_every_error_in_one_run(tmp_path: Path) -> None:
    bad = [BAD_SPECS / "unknown-keys-nested.yaml", BAD_SPECS / "joint-coordinates.yaml", BAD_SPECS / "units.yaml"]
    out = tmp_path / "out"
    result = run("solve", P04, *bad, "-o", out)
    assert result.exit_code == EXIT_INVALID_SPEC
    assert "Traceback" not in result.output
    errors = [line for line in result.stderr.splitlines() if ": error: " in line]
    expected = sum(line.startswith("# expect:") for p in bad for line in p.read_text(encoding="utf-8").splitlines())
    assert len(errors) == expected
    for path in bad:
        assert any(line.startswith(f"{path}:") for line in errors), path
    assert not out.exists()  # nothing is written when any spec fails


@pytest.mark.usefixtures("broken_derive")
def test_internal_error_says_so_without_a_traceback() -> None:
    result = run("solve", P04)
    assert result.exit_code == EXIT_INTERNAL
    assert "internal error" in result.stderr
    assert "RuntimeError: boom in the engine" in result.stderr
    assert "--debug" in result.stderr
    assert "Traceback" not in result.output
    assert result.stdout == ""


@pytest.mark.usefixtures("broken_derive")
def test_debug_lets_the_exception_through() -> None:
    result = run("--debug", "solve", P04)
    assert result.exit_code != EXIT_OK
    assert isinstance(result.exception, RuntimeError)
    assert str(result.exception) == "boom in the engine"


def test_spec_that_cannot_be_derived_exits_4(monkeypatch: pytest.MonkeyPatch) -> None:
    import tutgen.engine.pipeline

    def derive(system: object, *args: object, **kwargs: object) -> None:
        raise DerivationError("the kinetic energy is not a quadratic form in the velocities")

    monkeypatch.setattr(tutgen.engine.pipeline, "derive", derive)
    result = run("solve", P10)
    assert result.exit_code == EXIT_CANNOT_DERIVE
    assert result.stderr == "error: the kinetic energy is not a quadratic form in the velocities\n"


def test_closed_pipe_is_not_an_internal_error(tmp_path: Path) -> None:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen(
        [sys.executable, "-m", "tutgen", "solve", str(P04)],
        cwd=tmp_path,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    proc.stdout.close()  # like `tutgen solve ... | head -0`: nobody reads the solution
    stderr = proc.stderr.read().decode()
    proc.stderr.close()
    assert proc.wait(timeout=120) == 141
    assert stderr == ""


# --- determinism ---


def test_solving_twice_gives_identical_output() -> None:
    # a real derivation each time (no cache), in one process
    for fmt in ("md", "json"):
        first = run("solve", P06, "--format", fmt)
        second = run("solve", P06, "--format", fmt)
        assert first.exit_code == second.exit_code == EXIT_OK
        assert first.stdout_bytes == second.stdout_bytes


@pytest.mark.parametrize("fmt", ["md", "json"])
def test_output_does_not_depend_on_the_hash_seed(tmp_path: Path, fmt: str) -> None:
    runs = [run_module("solve", P04, "--format", fmt, cwd=tmp_path, hashseed=seed) for seed in ("1", "4242")]
    for proc in runs:
        assert proc.returncode == EXIT_OK, proc.stderr.decode()
    assert runs[0].stdout == runs[1].stdout
    assert runs[0].stdout.decode("utf-8") == expected_output(P04, fmt)


# --- the schema ---


@pytest.fixture(scope="module")
def schema() -> dict:
    result = run("schema")
    assert result.exit_code == EXIT_OK, result.stderr
    return json.loads(result.stdout)


def test_schema_is_a_json_schema(schema: dict) -> None:
    assert "$schema" in schema
    assert "properties" in schema
    jsonschema.Draft202012Validator.check_schema(schema)


@pytest.mark.parametrize("spec", [pytest.param(p, id=p.stem) for p in all_specs()])
def test_every_example_spec_matches_the_schema(schema: dict, spec: Path) -> None:
    data, _ = load_yaml_file(spec)  # as tutgen reads it (YAML 1.2 core scalars)
    errors = sorted(jsonschema.Draft202012Validator(schema).iter_errors(data), key=lambda e: list(e.path))
    assert not errors, "\n".join(f"{list(e.path)}: {e.message}" for e in errors)


@pytest.mark.parametrize(
    "name", ["unknown-key-top", "unknown-keys-nested", "vector-length", "bad-literals", "wrong-types", "shapes"]
)
def test_schema_rejects_shape_errors(schema: dict, name: str) -> None:
    data, _ = load_yaml_file(BAD_SPECS / f"{name}.yaml")
    assert list(jsonschema.Draft202012Validator(schema).iter_errors(data))
