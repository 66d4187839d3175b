"""Every spec compiles to a PDF with latexmk and pdflatex, reproducibly."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tests.conftest import PDF_SAMPLE, all_specs, solved

pytestmark = [
    pytest.mark.pdf,
    pytest.mark.skipif(
        shutil.which("latexmk") is None or shutil.which("pdflatex") is None, reason="latexmk/pdflatex not installed"
    ),
]


def pdf_of(spec: Path) -> bytes:
    from tutgen.api import render

    out = render(solved(str(spec))[1], "pdf")
    assert isinstance(out, bytes)
    return out


@pytest.mark.parametrize(
    "spec",
    [pytest.param(p, marks=() if p.stem in PDF_SAMPLE else pytest.mark.slow) for p in all_specs()],
    ids=lambda p: p.stem,
)
def test_pdf_compiles(spec: Path) -> None:
    pdf = pdf_of(spec)
    assert pdf.startswith(b"%PDF-")
    assert pdf.rstrip().endswith(b"%%EOF")


def test_pdf_is_byte_identical_across_runs() -> None:
    spec = next(p for p in all_specs() if p.stem == "p05-rr-arm")
    assert pdf_of(spec) == pdf_of(spec)


def test_pdf_compiles_user_text_with_specials_and_unicode() -> None:
    import dataclasses

    from tutgen.render.latex import render_latex
    from tutgen.render.pdf import compile_pdf

    spec = next(p for p in all_specs() if p.stem == "p03-cart-pendulum")
    system, d, _ = solved(str(spec))
    text = r"θ₀-free arm: 50% of \input{x} & $y_1$ # ~ ^ < > | × 2·3° m² Ω μ"
    text = text.replace("₀", "0")
    d2 = dataclasses.replace(d, system=dataclasses.replace(system, title=text, statement=text))
    assert compile_pdf(render_latex(d2)).startswith(b"%PDF-")
