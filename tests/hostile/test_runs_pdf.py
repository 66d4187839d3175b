"""Hostile runs, PDF: SIGTERM or Ctrl-C during a LaTeX compile ends tutgen with 143 or 130, kills latexmk
and pdflatex (their own process group) and removes their temporary directory; nothing is written."""

from __future__ import annotations

import shutil
import signal
from pathlib import Path

import pytest

from tests.conftest import SPECS
from tests.hostile.procs import Runner, processes_in, wait_for

pytestmark = [
    pytest.mark.pdf,
    pytest.mark.skipif(
        shutil.which("latexmk") is None or shutil.which("pdflatex") is None, reason="latexmk/pdflatex not installed"
    ),
]

SPEC = SPECS / "tutorial-1" / "p02-pivoted-rod.yaml"


def compiling(runner: Runner) -> bool:
    return any("latexmk" in cmd or "pdflatex" in cmd for _, cmd in processes_in(runner.tmp))


@pytest.mark.parametrize(
    ("signum", "code"),
    [pytest.param(signal.SIGTERM, 143, id="sigterm"), pytest.param(signal.SIGINT, 130, id="sigint")],
)
def test_runs_signal_during_the_compile_leaves_nothing(tmp_path: Path, signum: int, code: int) -> None:
    runner = Runner(tmp_path)
    proc = runner.start("solve", SPEC, "-f", "pdf", "-o", "out.pdf", "--timeout", "300")
    if not wait_for(lambda: compiling(runner) or proc.poll() is not None, 120):
        proc.kill()
        pytest.fail("latexmk never started")
    if proc.poll() is not None:
        pytest.skip("the compile finished before it could be interrupted")
    proc.send_signal(signum)
    done = runner.finish(proc, limit=30)
    assert done.returncode == code, done.stderr
    assert "Traceback" not in done.stderr
    files, procs = runner.leftovers()
    assert procs == [], f"still running: {procs}"
    assert files == set(), f"left behind: {files}"  # no out.pdf, no temporary directory


def test_runs_pdf_under_a_budget_too_small_names_the_stage(tmp_path: Path) -> None:
    """The compile gets only what the derivation left of --timeout; when that runs out the message
    names the stage, and nothing is left running or written."""
    runner = Runner(tmp_path)
    done = runner.run("solve", SPEC, "-f", "pdf", "-o", "out.pdf", "--timeout", "0.5")
    assert done.returncode == 4, done.stderr
    assert "did not finish within 0.5 s" in done.stderr and "Traceback" not in done.stderr
    files, procs = runner.leftovers()
    assert (files, procs) == (set(), [])
