"""figure.file: the instructor's own picture is confined to the spec's folder and told by its header."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tutgen.errors import SpecErrors
from tutgen.model.figure import ImageKind
from tutgen.spec import figure as spec_figure
from tutgen.spec.figure import MAX_IMAGE_BYTES, image_kind
from tutgen.spec.validate import load_system

SPEC = """title: Pendulum with a picture
parameters: [m, l, g]
coordinates: [theta]
gravity: [0, -g, 0]
bodies:
  bob: {mass: m, com: [0, -l, 0]}
joints:
  pivot: {type: revolute, parent: ground, child: bob, axis: z, coordinate: theta}
figure: {file: %s}
"""
PNG = b"\x89PNG\r\n\x1a\n" + b"\x00" * 32


def _spec(folder: Path, file: str) -> Path:
    path = folder / "spec.yaml"
    path.write_text(SPEC % file, encoding="utf-8")
    return path


def _error(path: Path) -> str:
    with pytest.raises(SpecErrors) as info:
        load_system(path)
    (error,) = info.value.errors
    assert (error.location.line, error.location.col) == (9, 16)
    return error.message


@pytest.mark.parametrize(
    ("head", "kind"),
    [
        pytest.param(PNG, ImageKind.PNG, id="png"),
        pytest.param(b"\xff\xd8\xff\xe0" + b"\x00" * 8, ImageKind.JPEG, id="jpeg"),
        pytest.param(b"%PDF-1.5\n", ImageKind.PDF, id="pdf"),
        pytest.param(b'<svg xmlns="http://www.w3.org/2000/svg"/>', ImageKind.SVG, id="svg"),
        pytest.param(b'\xef\xbb\xbf<?xml version="1.0"?>\n<svg/>', ImageKind.SVG, id="svg-bom-xml"),
        pytest.param(b"<html><body/></html>", None, id="html"),
        pytest.param(b'<?xml version="1.0"?><note/>', None, id="xml-not-svg"),
        pytest.param(b"GIF89a", None, id="gif"),
        pytest.param(b"", None, id="empty"),
    ],
)
def test_figure_file_kind_by_magic_header(head: bytes, kind: ImageKind | None) -> None:
    assert image_kind(head) == kind


def test_figure_file_inside_the_folder_is_accepted(tmp_path: Path) -> None:
    (tmp_path / "pics").mkdir()
    (tmp_path / "pics" / "p.png").write_bytes(PNG)
    system = load_system(_spec(tmp_path, "pics/p.png"))
    assert system.figure is not None and system.figure.file is not None
    assert system.figure.file.path == "pics/p.png"
    assert system.figure.file.kind is ImageKind.PNG


def test_figure_file_symlink_leading_out_is_refused(tmp_path: Path) -> None:
    outside = tmp_path / "outside.png"
    outside.write_bytes(PNG)
    folder = tmp_path / "spec"
    folder.mkdir()
    os.symlink(outside, folder / "link.png")
    assert "symlink leading out" in _error(_spec(folder, "link.png"))


def test_figure_file_symlink_inside_is_accepted(tmp_path: Path) -> None:
    (tmp_path / "real.png").write_bytes(PNG)
    os.symlink(tmp_path / "real.png", tmp_path / "link.png")
    assert load_system(_spec(tmp_path, "link.png")).figure is not None


def test_figure_file_too_big_is_refused_without_reading_it(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    big = tmp_path / "big.png"
    with open(big, "wb") as fh:  # sparse: a header, then a hole up to just over the limit
        fh.write(PNG)
        fh.truncate(MAX_IMAGE_BYTES + 1)
    opened: list[str] = []
    real_open = open

    def spy(file: object, *args: object, **kwargs: object) -> object:
        opened.append(str(file))
        return real_open(file, *args, **kwargs)  # type: ignore[call-overload]

    monkeypatch.setattr(spec_figure, "open", spy, raising=False)
    assert "the limit is 10 MiB" in _error(_spec(tmp_path, "big.png"))
    assert str(big) not in opened


def test_figure_file_reads_only_the_header(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "p.png").write_bytes(PNG + b"\x01" * 100_000)
    sizes: list[int] = []

    class Reader:
        def __init__(self, fh: object) -> None:
            self.fh = fh

        def __enter__(self) -> Reader:
            return self

        def __exit__(self, *exc: object) -> None:
            self.fh.close()  # type: ignore[attr-defined]

        def read(self, n: int = -1) -> bytes:
            sizes.append(n)
            return self.fh.read(n)  # type: ignore[attr-defined]

    real_open = open
    monkeypatch.setattr(spec_figure, "open", lambda *a, **k: Reader(real_open(*a, **k)), raising=False)
    load_system(_spec(tmp_path, "p.png"))
    assert sizes == [spec_figure.HEADER_BYTES]


def test_figure_file_directory_is_refused(tmp_path: Path) -> None:
    (tmp_path / "dir.png").mkdir()
    assert "not a regular file" in _error(_spec(tmp_path, "dir.png"))
