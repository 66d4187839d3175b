"""LaTeX -> PDF with latexmk and pdflatex, safely and reproducibly.

Safety: ``latexmk -norc`` (no user or system latexmkrc runs), ``-no-shell-escape`` and
``shell_escape=f`` (no \\write18), ``openin_any=p`` and ``openout_any=p`` (TeX may read and write
only below the working directory, a fresh temporary one), a wall-clock timeout, and
``-interaction=nonstopmode -halt-on-error`` so a bad document never waits for input.
Reproducibility: ``SOURCE_DATE_EPOCH`` (default 0) and ``FORCE_SOURCE_DATE=1`` fix the dates
pdfTeX writes, and ``\\pdftrailerid{}`` in the preamble drops the random document ID.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from pathlib import Path

from tutgen.errors import TutgenError

EXIT_PDF_FAILED = 6
DEBIAN_PACKAGES = "texlive-latex-base texlive-latex-recommended texlive-pictures latexmk"
DEFAULT_TIMEOUT = 120.0


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


def compile_pdf(tex: str, timeout: float = DEFAULT_TIMEOUT) -> bytes:
    """Compile a complete LaTeX document; return the PDF's bytes."""
    latexmk = find_latexmk()
    env = dict(os.environ)
    env.update(
        openin_any="p",
        openout_any="p",
        shell_escape="f",
        SOURCE_DATE_EPOCH=os.environ.get("SOURCE_DATE_EPOCH", "0"),
        FORCE_SOURCE_DATE="1",
        TEXMFOUTPUT="",
    )
    with tempfile.TemporaryDirectory(prefix="tutgen-tex-") as tmp:
        work = Path(tmp)
        (work / "solution.tex").write_text(tex, encoding="utf-8")
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
        try:
            proc = subprocess.run(
                cmd, cwd=work, env=env, capture_output=True, text=True, timeout=timeout, stdin=subprocess.DEVNULL
            )
        except subprocess.TimeoutExpired:
            raise PdfError(f"error: LaTeX did not finish within {timeout:g} s; no PDF was written") from None
        pdf = work / "solution.pdf"
        if proc.returncode != 0 or not pdf.exists():
            log = (
                (work / "solution.log").read_text(encoding="utf-8", errors="replace")
                if (work / "solution.log").exists()
                else proc.stdout + proc.stderr
            )
            lines = [ln for ln in log.splitlines() if ln.startswith("!") or ":error:" in ln or ".tex:" in ln]
            detail = "\n  ".join(lines[:8]) or (proc.stderr.strip()[-800:] or "no log")
            raise PdfError(f"error: LaTeX could not compile the solution (a tutgen bug):\n  {detail}")
        return pdf.read_bytes()
