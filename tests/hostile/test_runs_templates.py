"""Hostile runs, --template-dir: a template is read only from a regular file inside the directory, and
every error in a user's template is a usage error (exit 2) at its line, never exit 70 "internal
error"; a template that runs forever is stopped by --timeout, which covers rendering."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.conftest import SPECS
from tests.hostile.procs import Runner
from tutgen.errors import EXIT_CANNOT_DERIVE, EXIT_USAGE

SPEC = SPECS / "tutorial-1" / "p02-pivoted-rod.yaml"
SECRET = "TUTGEN_TEST_SECRET_VALUE"


def make(runner: Runner, files: dict[str, str]) -> Path:
    tdir = runner.inputs / "templates"
    tdir.mkdir()
    for name, text in files.items():
        (tdir / name).write_text(text, encoding="utf-8")
    return tdir


def solve(runner: Runner, tdir: Path, *extra: str) -> tuple[int, str, str]:
    runner.env[SECRET] = "leaked"
    done = runner.run("solve", SPEC, "--template-dir", tdir, "-o", "out.md", *extra, limit=120)
    files, procs = runner.leftovers()
    assert procs == []
    if done.returncode != 0:
        assert files == set(), f"a failed run wrote {files}"
    assert "Traceback" not in done.stderr and "internal error" not in done.stderr
    return done.returncode, done.stdout, done.stderr


def test_runs_template_symlink_to_root_cannot_read_the_environment(tmp_path: Path) -> None:
    runner = Runner(tmp_path)
    tdir = make(runner, {"solution.md.j2": '{% include "root/proc/self/environ" %}\n'})
    os.symlink("/", tdir / "root")
    code, _, err = solve(runner, tdir)
    assert code == EXIT_USAGE, err
    assert "leads out of the directory" in err and "leaked" not in err
    assert not (runner.work / "out.md").exists()


def test_runs_template_symlinked_out_of_the_directory_is_refused(tmp_path: Path) -> None:
    runner = Runner(tmp_path)
    outside = runner.inputs / "outside.j2"
    outside.write_text("outside\n", encoding="utf-8")
    tdir = make(runner, {})
    os.symlink(outside, tdir / "solution.md.j2")
    code, _, err = solve(runner, tdir)
    assert code == EXIT_USAGE and "solution.md.j2' leads out of the directory" in err


def test_runs_template_symlink_inside_the_directory_is_followed(tmp_path: Path) -> None:
    runner = Runner(tmp_path)
    tdir = make(runner, {"mine.j2": "# {{ title }} (mine)\n"})
    os.symlink("mine.j2", tdir / "solution.md.j2")
    code, _, err = solve(runner, tdir)
    assert code == 0, err
    assert (runner.work / "out.md").read_text(encoding="utf-8").endswith("(mine)\n")


def test_runs_template_fifo_is_refused_without_waiting(tmp_path: Path) -> None:
    runner = Runner(tmp_path)
    tdir = make(runner, {})
    os.mkfifo(tdir / "solution.md.j2")
    code, _, err = solve(runner, tdir)
    assert code == EXIT_USAGE and "is not a regular file" in err


@pytest.mark.parametrize(
    ("template", "expected"),
    [
        pytest.param("line one\n{% for x in %}\n", "solution.md.j2:2: error: template syntax", id="syntax"),
        pytest.param("ok\n{{ no_such_variable }}\n", "solution.md.j2:2: error: template: ", id="undefined"),
        pytest.param(
            "{{ ''.__class__.__mro__[1].__subclasses__() }}\n", "solution.md.j2:1: error: template: ", id="sandbox"
        ),
        pytest.param(
            '{% include "solution.md.j2" %}\n', "solution.md.j2:1: error: the templates include", id="recursion"
        ),
        pytest.param('{% include "missing.j2" %}\n', "solution.md.j2:1: error: template: ", id="missing"),
    ],
)
def test_runs_template_errors_are_usage_errors_at_their_line(tmp_path: Path, template: str, expected: str) -> None:
    runner = Runner(tmp_path)
    tdir = make(runner, {"solution.md.j2": template})
    code, _, err = solve(runner, tdir)
    assert code == EXIT_USAGE, err
    assert expected in err, err


def test_runs_template_that_loops_is_stopped_by_the_timeout(tmp_path: Path) -> None:
    runner = Runner(tmp_path)
    loop = "{% for i in range(100000) %}{% for j in range(100000) %}{% endfor %}{% endfor %}\n"
    tdir = make(runner, {"solution.md.j2": loop})
    code, _, err = solve(runner, tdir, "--timeout", "8")
    assert code == EXIT_CANNOT_DERIVE, err
    assert "did not finish within 8 s" in err and "it was at: rendering" in err, err
