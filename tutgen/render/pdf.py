"""LaTeX -> PDF with latexmk and pdflatex, safely and reproducibly.

Safety: ``latexmk -norc`` (no user or system latexmkrc runs), ``-no-shell-escape`` and
``shell_escape=f`` (no \\write18), ``openin_any=p`` and ``openout_any=p`` (TeX may read and write
only below the working directory, a fresh temporary one), and
``-interaction=nonstopmode -halt-on-error`` so a bad document never waits for input.
Bounded: latexmk runs in its own session (a process group of its own, with pdflatex under it) for at
most the time left of the run's ``--timeout`` (:func:`tutgen.limits.remaining`; without one, 120 s),
and the files it writes (log, output) may together reach :data:`MAX_OUTPUT_BYTES`. Past either limit,
on any exception, and on SIGINT/SIGTERM of tutgen (which the CLI turns into exceptions), the whole
group is killed, and the temporary directory is always removed.
Reproducibility: ``SOURCE_DATE_EPOCH`` (default 0) and ``FORCE_SOURCE_DATE=1`` fix the dates
pdfTeX writes, and ``\\pdftrailerid{}`` in the preamble drops the random document ID.
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import tempfile
import time
from collections.abc import Mapping
from pathlib import Path

from tutgen.errors import TutgenError

EXIT_PDF_FAILED = 6
DEBIAN_PACKAGES = "texlive-latex-base texlive-latex-recommended texlive-pictures latexmk"
#: Seconds a compile may take when no run deadline is armed.
DEFAULT_TIMEOUT = 120.0
#: What latexmk and pdflatex may write in all (the log of a looping document grows at ~25 MB/s).
MAX_OUTPUT_BYTES = 64 * 1024 * 1024
#: How often the running compile is looked at (time, output size).
POLL_SECONDS = 0.05
#: The names an input file may have in the compile folder (tutgen makes them:
#: :func:`tutgen.figure.picture.picture_name`): one plain name, no folder, no TeX special character.
INPUT_NAME = re.compile(r"[a-z0-9][a-z0-9-]{0,63}\.(png|jpg|pdf)")


class PdfError(TutgenError):
    """LaTeX is missing, or the document did not compile."""

    exit_code = EXIT_PDF_FAILED


def find_latexmk() -> str:
    exe = shutil.which("latexmk")
    if exe is None or shutil.which("pdflatex") is None:
        raise PdfError(
            "error: --format pdf needs latexmk and pdflatex, which are not installed.\n"
            f"  hint: on Debian or Ubuntu: sudo apt-get install {DEBIAN_PACKAGES}\n"
            "  or write the LaTeX source with --format tex and compile it elsewhere."
        )
    return exe


def compile_pdf(tex: str, timeout: float | None = None, files: Mapping[str, bytes] | None = None) -> bytes:
    """Compile a complete LaTeX document; return the PDF's bytes.

    ``files``: pictures the document includes, by name (:data:`INPUT_NAME`, e.g. an instructor's
    ``figure.file`` from :func:`tutgen.figure.picture.picture_files`), written into the sealed
    compile folder beside the document before LaTeX runs; any other name is a bug, refused here.

    ``timeout``: at most this many seconds (default :data:`DEFAULT_TIMEOUT`), and never more than the
    run's deadline leaves (:func:`tutgen.limits.remaining`); past the deadline this raises the run's
    :class:`~tutgen.errors.DerivationTimeout` (stage "LaTeX compile"), past ``timeout`` a
    :class:`PdfError`. Either way, and on any exception, no process of the compile is left running.
    """
    from tutgen.limits import out_of_time, remaining, shielded, stage

    latexmk = find_latexmk()
    inputs = dict(files or {})
    for name in inputs:
        if INPUT_NAME.fullmatch(name) is None or name.startswith("solution."):
            raise ValueError(f"compile_pdf: {name!r} is not a name an input file may have")
    env = dict(os.environ)
    env.update(
        openin_any="p",
        openout_any="p",
        shell_escape="f",
        SOURCE_DATE_EPOCH=os.environ.get("SOURCE_DATE_EPOCH", "0"),
        FORCE_SOURCE_DATE="1",
        TEXMFOUTPUT="",
    )
    own = DEFAULT_TIMEOUT if timeout is None or timeout <= 0 else timeout
    budget = remaining()
    limit = own if budget is None else min(own, budget)
    if budget is not None:
        stage("LaTeX compile", "compiling the PDF")  # what the alarm, if it comes first, names
    work: Path | None = None
    proc: subprocess.Popen[bytes] | None = None
    try:
        with shielded():  # made inside the try, so an alarm that comes now still finds it to remove
            work = Path(tempfile.mkdtemp(prefix="tutgen-tex-"))
        (work / "solution.tex").write_text(tex, encoding="utf-8")
        for name, data in sorted(inputs.items()):
            (work / name).write_bytes(data)
        cmd = [
            latexmk,
            "-norc",
            "-pdf",
            "-interaction=nonstopmode",
            "-halt-on-error",
            "-no-shell-escape",
            "-file-line-error",
            "-quiet",
            "solution.tex",
        ]
        with open(work / "latexmk.out", "wb") as out:
            with shielded():  # the child and its pid are known together, or there is no child
                proc = subprocess.Popen(
                    cmd, cwd=work, env=env, stdin=subprocess.DEVNULL, stdout=out, stderr=out, start_new_session=True
                )
            _limit_file_size(proc.pid)
        stopped = _watch(proc, work, limit, sum(len(d) for d in inputs.values()))
        if stopped == "time":
            if budget is not None and budget <= own:
                raise out_of_time("LaTeX compile", "compiling the PDF")
            raise PdfError(f"error: LaTeX did not finish within {limit:g} s; no PDF was written")
        if stopped == "size":
            raise PdfError(
                f"error: LaTeX wrote more than {MAX_OUTPUT_BYTES // (1024 * 1024)} MiB of log and output and was "
                "stopped; no PDF was written"
            )
        pdf = work / "solution.pdf"
        if proc.returncode != 0 or not pdf.exists():
            raise PdfError(f"error: LaTeX could not compile the solution (a tutgen bug):\n  {_log_excerpt(work)}")
        return pdf.read_bytes()
    finally:
        with shielded():  # neither the alarm nor a second Ctrl-C may cut the cleanup short
            if proc is not None:
                _kill_group(proc)
            if work is not None:
                _remove(work)


def _remove(work: Path) -> None:
    """Remove the compile's directory; again while it reappears: a pdflatex killed on the other core may
    still create a file between rmtree's listing and its last rmdir (seen under a loaded test run)."""
    ends = time.monotonic() + 2.0
    while True:
        shutil.rmtree(work, ignore_errors=True)
        if not work.exists() or time.monotonic() > ends:
            return
        time.sleep(0.02)


def _watch(proc: subprocess.Popen[bytes], work: Path, limit: float, given: int = 0) -> str | None:
    """Wait for latexmk; "time" or "size" when it had to be stopped (it is not yet killed then).
    ``given``: the bytes of the input files tutgen wrote, which are not LaTeX's output."""
    ends = time.monotonic() + limit
    while True:
        try:
            proc.wait(timeout=POLL_SECONDS)
        except subprocess.TimeoutExpired:
            pass
        else:  # ended on its own, or by RLIMIT_FSIZE: a fast TeX fills one file to the cap between two polls
            return "size" if proc.returncode != 0 and _over_size(work, given, MAX_OUTPUT_BYTES) else None
        if time.monotonic() >= ends:
            return "time"
        if _over_size(work, given, MAX_OUTPUT_BYTES + 1):
            return "size"


def _over_size(work: Path, given: int, cap: int) -> bool:
    """Whether LaTeX's output reached ``cap`` bytes: in all (less the ``given`` input files), or in one
    file (``RLIMIT_FSIZE`` stops each file at exactly MAX_OUTPUT_BYTES)."""
    sizes = _sizes(work)
    return sum(sizes) - given >= cap or any(size >= MAX_OUTPUT_BYTES for size in sizes)


def _sizes(work: Path) -> list[int]:
    sizes: list[int] = []
    try:
        with os.scandir(work) as entries:
            for entry in entries:
                try:
                    sizes.append(entry.stat(follow_symlinks=False).st_size)
                except OSError:
                    pass
    except OSError:
        pass
    return sizes


def _limit_file_size(pid: int) -> None:
    """Cap the size of any one file latexmk and its children write (``RLIMIT_FSIZE``, inherited by
    pdflatex), besides the watch on the total: a second guard, where the platform has it."""
    try:
        import resource

        resource.prlimit(pid, resource.RLIMIT_FSIZE, (MAX_OUTPUT_BYTES, MAX_OUTPUT_BYTES))
    except (ImportError, AttributeError, OSError, ValueError):  # not Linux, or latexmk already gone
        pass


def _kill_group(proc: subprocess.Popen[bytes]) -> None:
    """Kill latexmk's process group (pdflatex with it) and reap latexmk.

    While latexmk is unreaped its pid cannot be reused, so the group id is still ours: kill first,
    then wait. After a normal exit the group is usually empty; a straggler is killed all the same.
    """
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:  # pragma: no cover - SIGKILL is not ignored
        pass
    ends = time.monotonic() + 2.0  # and until the rest of the group (pdflatex) is gone
    while time.monotonic() < ends:
        try:
            os.killpg(proc.pid, 0)
        except (ProcessLookupError, PermissionError):
            return
        time.sleep(0.01)


def _log_excerpt(work: Path) -> str:
    log_file = work / "solution.log"
    raw = log_file if log_file.exists() else work / "latexmk.out"
    try:
        with open(raw, "rb") as fh:
            log = fh.read(1024 * 1024).decode("utf-8", errors="replace")
    except OSError:
        log = ""
    lines = [ln for ln in log.splitlines() if ln.startswith("!") or ":error:" in ln or ".tex:" in ln]
    return "\n  ".join(lines[:8]) or (log.strip()[-800:] or "no log")
