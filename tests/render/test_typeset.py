"""Every spec's PDF at full size: no display scaled, nothing wider than the line (issue 14).

The LaTeX of each spec is compiled once with pdflatex and its log read: an ``Overfull \\hbox`` wider than
1 pt is a line that runs into the margin, and the source must hold no device that shrinks or hides one
(``\\resizebox``, ``\\scalebox``, a fit-to-width macro, ``\\hfuzz``/``\\hbadness`` loosening, a smaller maths
font). The fully symbolic arms are slow (``-m slow``, by tests/conftest.py)."""

from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
from functools import cache
from pathlib import Path

import pytest

from tests.conftest import all_specs, rendered_text, solved

pytestmark = [
    pytest.mark.pdf,
    pytest.mark.skipif(shutil.which("pdflatex") is None, reason="pdflatex not installed"),
]

#: what a document must not use to make a display fit
SHRINKING = (
    r"\resizebox",
    r"\scalebox",
    r"\fitdisplay",
    r"\adjustbox",
    r"\hfuzz",
    r"\hbadness",
    r"\small",
    r"\footnotesize",
    r"\scriptsize",
    r"\tiny",
    r"\scriptstyle",
)
_OVERFULL = re.compile(r"Overfull \\hbox \(([\d.]+)pt too wide\)")


def overfull_boxes(tex: str, work: Path) -> list[float]:
    """How far each overfull line of the compiled document sticks out, in points."""
    (work / "doc.tex").write_text(tex, encoding="utf-8")
    proc = subprocess.run(
        ["pdflatex", "-interaction=nonstopmode", "-halt-on-error", "-no-shell-escape", "doc.tex"],
        cwd=work,
        capture_output=True,
        text=True,
        timeout=300,
        stdin=subprocess.DEVNULL,
    )
    log = (work / "doc.log").read_text(encoding="utf-8", errors="replace")
    assert proc.returncode == 0, "\n".join(ln for ln in log.splitlines() if ln.startswith("!"))
    return [float(x) for x in _OVERFULL.findall(log)]


@cache
def compiled(spec: str) -> tuple[list[float], str]:
    """A spec's LaTeX compiled once per session (both tests below read it): the overfull lines of the
    log, and the PDF's text by pdftotext ("" when pdftotext is missing)."""
    with tempfile.TemporaryDirectory(prefix="tutgen-typeset-") as work:
        boxes = overfull_boxes(rendered_text(spec, "tex"), Path(work))
        if shutil.which("pdftotext") is None:
            return boxes, ""
        text = subprocess.run(
            ["pdftotext", "-enc", "UTF-8", "doc.pdf", "-"], cwd=work, capture_output=True, text=True, check=True
        ).stdout
    return boxes, text


@pytest.mark.parametrize("spec", all_specs(), ids=lambda p: p.stem)
def test_no_display_is_scaled_or_wider_than_the_line(spec: Path) -> None:
    tex = rendered_text(spec, "tex")
    used = [cmd for cmd in SHRINKING if re.search(re.escape(cmd) + r"(?![A-Za-z])", tex)]
    assert used == []
    too_wide = [w for w in compiled(str(spec))[0] if w > 1.0]
    assert too_wide == [], f"{len(too_wide)} overfull lines, up to {max(too_wide, default=0):.1f} pt"


def test_the_check_sees_an_overfull_line(tmp_path: Path) -> None:
    """The log reading above can fail: a formula set too wide for the line is reported."""
    wide = " + ".join(f"a_{{{i}}} b_{{{i}}}" for i in range(60))
    tex = "\\documentclass{article}\\begin{document}\n\\[ " + wide + " \\]\n\\end{document}\n"
    assert max(overfull_boxes(tex, tmp_path)) > 1.0


#: ASCII maths that must not appear in what tutgen itself writes (issue 14, point 3)
ASCII_MATHS = ("_dot", "_ddot", "theta", "^", "**", "q''", "H = H^T")


def _user_text(spec: Path) -> str:
    """What the spec's author wrote and tutgen prints as given: title, statement, descriptions."""
    system = solved(str(spec))[0]
    texts = [system.title or "", system.statement or ""]
    texts += [p.description or "" for p in system.parameters] + [c.description or "" for c in system.coordinates]
    texts += [b.name for b in system.bodies] + [j.name for j in system.joints]
    return "\n".join(texts)


def _not_from_the_user(found: str, spec: Path) -> list[str]:
    user = _user_text(spec)
    return [tok for tok in ASCII_MATHS if tok in found and tok not in user]


@pytest.mark.parametrize("spec", all_specs(), ids=lambda p: p.stem)
def test_the_pdf_text_has_no_ascii_maths(spec: Path) -> None:
    """pdftotext of the PDF: none of the ASCII tokens, unless the spec's own text has them."""
    if shutil.which("pdftotext") is None:
        pytest.skip("pdftotext not installed")
    text = compiled(str(spec))[1]
    assert text
    assert _not_from_the_user(text, spec) == []
