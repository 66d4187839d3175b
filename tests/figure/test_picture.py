"""figure.file in a PDF: copied into the sealed compile folder under a safe name, checked again as it
is read (tutgen/figure/picture.py, tutgen/render/pdf.py)."""

from __future__ import annotations

import os
import re
import shutil
import struct
import subprocess
import zlib
from pathlib import Path

import pytest

from tutgen.errors import SpecErrors
from tutgen.figure.picture import picture_files, picture_name, read_picture
from tutgen.figure.view import figure_view
from tutgen.render.pdf import compile_pdf
from tutgen.spec.validate import load_system

SPEC = """title: Pendulum with a picture
parameters: [m, l, g]
coordinates: [theta]
gravity: [0, -g, 0]
bodies:
  bob: {mass: m, com: [0, -l, 0]}
joints:
  pivot: {type: revolute, parent: ground, child: bob, axis: z, coordinate: theta}
figure: {file: '%s'}
"""

needs_latex = pytest.mark.skipif(shutil.which("latexmk") is None, reason="latexmk is not installed")


def _png(width: int, height: int) -> bytes:
    """A real PNG (8-bit grey), small and made here, so pdfimages can report its size."""

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    rows = b"".join(b"\x00" + bytes((x * 37 + y * 11) % 256 for x in range(width)) for y in range(height))
    header = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")


def _system(folder: Path, name: str, data: bytes):  # type: ignore[no-untyped-def]
    (folder / name).parent.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(data)
    spec = folder / "spec.yaml"
    spec.write_text(SPEC % name, encoding="utf-8")
    return load_system(spec)


def test_picture_name_is_safe_and_by_content(tmp_path: Path) -> None:
    data = _png(7, 5)
    odd = _system(tmp_path / "a", "my pic #1%.PNG", data)  # no TeX could take this name as written
    same = _system(tmp_path / "b", "elsewhere/p.png", data)
    other = _system(tmp_path / "c", "p.png", _png(9, 5))
    name = picture_name(odd.figure.file)
    assert re.fullmatch(r"figure-[0-9a-f]{16}\.png", name)
    assert name == picture_name(same.figure.file)  # the same picture, the same name, wherever it is
    assert name != picture_name(other.figure.file)
    view = figure_view(odd)
    assert view["file_tex"] and view["file_tex_name"] == name and not view["file_plain"]
    assert figure_view(same)["file_plain"]  # a plain path may also go into a .tex compiled beside it
    assert picture_files([odd, same, other]) == {name: data, picture_name(other.figure.file): _png(9, 5)}


def test_picture_name_of_a_jpeg_without_extension_is_jpg(tmp_path: Path) -> None:
    system = _system(tmp_path, "photo", b"\xff\xd8\xff\xe0" + b"\x00" * 64)
    assert picture_name(system.figure.file).endswith(".jpg")
    assert not figure_view(system)["file_plain"]  # pdflatex would not know the kind of 'photo'


def test_picture_swapped_for_a_symlink_out_after_the_check_is_refused(tmp_path: Path) -> None:
    folder = tmp_path / "spec"
    folder.mkdir()
    system = _system(folder, "p.png", _png(4, 4))
    secret = tmp_path / "secret.png"
    secret.write_bytes(_png(4, 4))
    os.remove(folder / "p.png")
    os.symlink(secret, folder / "p.png")
    with pytest.raises(SpecErrors) as info:
        read_picture(system)
    (error,) = info.value.errors
    assert "figure.file 'p.png'" in error.message and "changed after the spec was checked" in error.message
    assert error.location.line == 9


def test_picture_swapped_for_a_fifo_does_not_block(tmp_path: Path) -> None:
    system = _system(tmp_path, "p.png", _png(4, 4))
    os.remove(tmp_path / "p.png")
    os.mkfifo(tmp_path / "p.png")
    with pytest.raises(SpecErrors, match="no longer a regular file"):
        picture_files([system])


def test_picture_no_longer_a_picture_is_refused(tmp_path: Path) -> None:
    system = _system(tmp_path, "p.png", _png(4, 4))
    (tmp_path / "p.png").write_bytes(b"#!/bin/sh\n")
    with pytest.raises(SpecErrors, match="no longer a PNG picture"):
        read_picture(system)


@pytest.mark.parametrize(
    "name",
    [
        pytest.param("../x.png", id="dotdot"),
        pytest.param("sub/x.png", id="folder"),
        pytest.param("solution.pdf", id="the-output"),
        pytest.param("x.tex", id="tex"),
        pytest.param("a b.png", id="space"),
    ],
)
def test_compile_pdf_refuses_an_input_name_it_did_not_make(name: str) -> None:
    with pytest.raises(ValueError, match="not a name an input file may have"):
        compile_pdf("\\documentclass{article}\\begin{document}x\\end{document}", files={name: b""})


@needs_latex
def test_picture_is_in_the_pdf_of_the_solution(tmp_path: Path) -> None:
    """The whole route: solve to PDF; the picture (17 x 11 pixels, an odd name) is an image of the PDF,
    beside the generated schematic (vector, so no image)."""
    from tutgen.api import solve_specs

    _system(tmp_path, "my picture.png", _png(17, 11))
    (pdf,) = solve_specs([tmp_path / "spec.yaml"], "pdf", method="lagrange")
    assert isinstance(pdf, bytes)
    (tmp_path / "out.pdf").write_bytes(pdf)
    listed = subprocess.run(
        ["pdfimages", "-list", str(tmp_path / "out.pdf")], capture_output=True, text=True, check=True
    ).stdout.splitlines()[2:]
    assert [(row.split()[3], row.split()[4]) for row in listed] == [("17", "11")]


@pytest.mark.slow  # two PDF compiles (questions, solutions): ~5-11 s
@needs_latex
def test_picture_is_in_the_pdf_of_a_sheet(tmp_path: Path) -> None:
    """A sheet's PDF (compiled in its own sealed folder, the sheet elsewhere than the spec) holds the
    problem's own picture too: the questions and the solutions."""
    from typer.testing import CliRunner

    from tutgen.cli.main import app

    _system(tmp_path, "pics/pendulum.png", _png(13, 7))
    sheet = tmp_path / "sheet.yaml"
    sheet.write_text("tutgen_sheet: 1\ntitle: Sheet\nproblems:\n  - spec.yaml\n", encoding="utf-8")
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["sheet", str(sheet), "-o", str(out), "-f", "pdf"])
    assert result.exit_code == 0, result.output
    pdfs = sorted(out.rglob("*.pdf"))
    assert pdfs
    for pdf in pdfs:
        listed = subprocess.run(["pdfimages", "-list", str(pdf)], capture_output=True, text=True, check=True)
        sizes = [(row.split()[3], row.split()[4]) for row in listed.stdout.splitlines()[2:]]
        assert sizes == [("13", "7")], pdf.name
