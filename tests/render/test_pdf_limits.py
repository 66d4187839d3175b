"""A LaTeX compile is bounded: a looping document is stopped within the budget, with its whole process
group, and its temporary directory is removed (however the compile ends)."""

from __future__ import annotations

import shutil
import tempfile
import time
from pathlib import Path

import pytest

from tests.hostile.procs import processes_in, settle
from tutgen.errors import DerivationTimeout
from tutgen.limits import deadline
from tutgen.render.pdf import PdfError, compile_pdf

pytestmark = [
    pytest.mark.pdf,
    pytest.mark.skipif(
        shutil.which("latexmk") is None or shutil.which("pdflatex") is None, reason="latexmk/pdflatex not installed"
    ),
]

#: A document TeX never finishes: \x expands to itself (built here: spec text no longer reaches TeX).
LOOP = "\\documentclass{article}\\begin{document}\\def\\x{\\x}\\x\\end{document}\n"
#: A document that writes its log as fast as TeX can, forever.
CHATTY = (
    "\\documentclass{article}\\begin{document}"
    "\\def\\y{\\message{xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx}\\y}\\y\\end{document}\n"
)


@pytest.fixture
def texdir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """The compile's temporary directories go here, so the test can see what is left of them."""
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    return tmp_path


def assert_nothing_left(texdir: Path) -> None:
    left = settle(lambda: processes_in(texdir))
    assert left == [], f"processes of the compile still running: {left}"
    assert list(texdir.iterdir()) == [], "the compile's temporary directory was not removed"


def test_pdf_loop_is_stopped_by_the_run_deadline(texdir: Path) -> None:
    start = time.monotonic()
    with pytest.raises(DerivationTimeout) as info, deadline(2):
        compile_pdf(LOOP)
    elapsed = time.monotonic() - start
    assert elapsed < 8, f"the 2 s budget took {elapsed:.1f} s to stop LaTeX"
    assert "LaTeX compile" in str(info.value)
    assert_nothing_left(texdir)


def test_pdf_loop_is_stopped_by_its_own_timeout(texdir: Path) -> None:
    start = time.monotonic()
    with pytest.raises(PdfError, match=r"did not finish within 1\.5 s"):
        compile_pdf(LOOP, timeout=1.5)
    assert time.monotonic() - start < 8
    assert_nothing_left(texdir)


def test_pdf_compile_gets_only_what_the_budget_leaves(texdir: Path) -> None:
    """Inside a 3 s deadline, a compile asked for 100 s still ends with the deadline."""
    start = time.monotonic()
    with pytest.raises(DerivationTimeout), deadline(3):
        time.sleep(1.5)  # what the derivation used is gone for rendering
        compile_pdf(LOOP, timeout=100)
    assert time.monotonic() - start < 8
    assert_nothing_left(texdir)


def test_pdf_log_is_capped(texdir: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import tutgen.render.pdf as pdf

    monkeypatch.setattr(pdf, "MAX_OUTPUT_BYTES", 2 * 1024 * 1024)
    with pytest.raises(PdfError, match="MiB of log and output"):
        compile_pdf(CHATTY, timeout=60)
    assert_nothing_left(texdir)


def test_pdf_log_stopped_by_the_file_size_cap_is_reported_as_such(
    texdir: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """TeX filling its log to RLIMIT_FSIZE between two polls of the watch (a fast TeX, or a loaded test
    run whose watch wakes late) is the size limit, not "a tutgen bug": CI saw that message once."""
    import tutgen.render.pdf as pdf

    monkeypatch.setattr(pdf, "MAX_OUTPUT_BYTES", 1024 * 1024)
    monkeypatch.setattr(pdf, "POLL_SECONDS", 30.0)  # the watch never looks: only the cap stops TeX
    with pytest.raises(PdfError, match="MiB of log and output"):
        compile_pdf(CHATTY, timeout=60)
    assert_nothing_left(texdir)


def test_pdf_document_error_is_reported_and_cleaned(texdir: Path) -> None:
    with pytest.raises(PdfError, match="could not compile"):
        compile_pdf("\\documentclass{article}\\begin{document}\\undefinedmacro\\end{document}\n", timeout=60)
    assert_nothing_left(texdir)
