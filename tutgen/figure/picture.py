"""The instructor's own picture (``figure.file``) on its way into a PDF.

tutgen compiles a PDF in a sealed temporary folder (:mod:`tutgen.render.pdf`: TeX may read only below
it), so the picture is copied in. It goes in under a name tutgen makes, :func:`picture_name`: the
SHA-256 of its bytes and the extension of its kind (``figure-<16 hex>.png|.jpg|.pdf``). So the name is
always safe to write in TeX, whatever the file is called in the spec's folder (spaces, ``#``, ``%``,
no extension at all), two problems of a sheet with different pictures never share a name, and the
same picture gives the same name on every machine (the ``.tex`` stays byte-identical).

The file was checked when the spec was (:func:`tutgen.spec.figure.check_image`: inside the spec's
folder, a regular file, at most 10 MiB, a picture by its header). It is read here, after those
checks, and checked again as it is opened, since it may have been changed in between: opened without
following a symlink, a regular file by ``fstat`` of the open file, at most 10 MiB, and still of the
kind its header said. A picture that no longer passes is an error naming the spec's ``figure`` key.
"""

from __future__ import annotations

import functools
import hashlib
import os
import stat
from collections.abc import Iterable

from tutgen.errors import SpecError, SpecErrors
from tutgen.model.figure import FigureFile, ImageKind
from tutgen.model.system import System
from tutgen.spec.figure import HEADER_BYTES, MAX_IMAGE_BYTES, image_kind

#: The extension pdflatex goes by, for each kind it can include (SVG it cannot).
TEX_EXTENSIONS = {ImageKind.PNG: "png", ImageKind.JPEG: "jpg", ImageKind.PDF: "pdf"}


def picture_name(file: FigureFile) -> str:
    """The name the picture has inside the PDF's compile folder (see the module docstring)."""
    return _name(file, *_signature(file))


def picture_files(systems: Iterable[System]) -> dict[str, bytes]:
    """The pictures the LaTeX of ``systems`` includes, by the name it includes them under
    (:func:`picture_name`), ready to be copied into a compile folder; SVG pictures are left out."""
    out: dict[str, bytes] = {}
    for system in systems:
        cfg = system.figure
        if cfg is None or cfg.file is None or cfg.file.kind not in TEX_EXTENSIONS:
            continue
        data = read_picture(system)
        out[_name_of(data, cfg.file.kind)] = data
    return out


def read_picture(system: System) -> bytes:
    """The bytes of the spec's picture, checked again as it is opened (see the module docstring)."""
    cfg = system.figure
    assert cfg is not None and cfg.file is not None
    data = _read_checked(cfg.file)
    if isinstance(data, str):
        raise _changed(system, data)
    return data


def _read_checked(file: FigureFile) -> bytes | str:
    """The picture's bytes, or what is wrong with it now: opened without following a symlink and
    without waiting (a FIFO put in its place does not block), a regular file of at most 10 MiB by
    ``fstat`` of the open file, still of its kind."""
    flags = os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(file.resolved, flags)
    except OSError as err:
        return f"cannot be opened any more ({err.strerror or err})"
    with os.fdopen(fd, "rb") as fh:
        st = os.fstat(fh.fileno())
        if not stat.S_ISREG(st.st_mode):
            return "is no longer a regular file"
        if st.st_size > MAX_IMAGE_BYTES:
            return f"is {st.st_size / 1048576:.1f} MiB now; the limit is 10 MiB"
        data = fh.read(MAX_IMAGE_BYTES + 1)
    if len(data) > MAX_IMAGE_BYTES:
        return "grew past 10 MiB while it was read"
    if image_kind(data[:HEADER_BYTES]) is not file.kind:
        return f"is no longer a {file.kind.value.upper()} picture (by its first bytes)"
    return data


def _changed(system: System, what: str) -> SpecErrors:
    cfg = system.figure
    assert cfg is not None and cfg.file is not None
    return SpecErrors(
        [
            SpecError(
                cfg.origin,
                f"figure.file '{cfg.file.path}' {what}: it changed after the spec was checked",
                "run again once the picture is in place",
            )
        ]
    )


def _signature(file: FigureFile) -> tuple[int, int]:
    """What says that a file is unchanged since it was last hashed: its size and modification time."""
    try:
        st = os.stat(file.resolved)
    except OSError:
        return (-1, -1)
    return (st.st_size, st.st_mtime_ns)


@functools.lru_cache(maxsize=64)
def _name(file: FigureFile, size: int, mtime_ns: int) -> str:
    """The name of a picture by its content, hashed once per (file, size, mtime) in a process: a sheet
    renders each problem's view once per variant."""
    del size, mtime_ns  # the cache key only
    data = _read_checked(file)
    if isinstance(data, str):  # read_picture says what is wrong when the PDF is made
        return f"figure-unreadable.{TEX_EXTENSIONS.get(file.kind, 'svg')}"
    return _name_of(data, file.kind)


def _name_of(data: bytes, kind: ImageKind) -> str:
    return f"figure-{hashlib.sha256(data).hexdigest()[:16]}.{TEX_EXTENSIONS.get(kind, 'svg')}"
