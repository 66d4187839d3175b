"""The ``figure:`` section of a spec: drawing values, sizes, and the instructor's own picture.

One standalone function, :func:`validate_figure`, called once by :mod:`tutgen.spec.validate`. It
appends every problem it finds to the caller's error list (collect, then fail once) and returns the
:class:`~tutgen.model.figure.FigureConfig` (None when the spec has no ``figure:``).

The picture file is user input from outside the spec, so it is checked before anything of it is
read: its path must stay inside the spec's folder (no absolute path, no ``..``, no symlink leading
out), it must exist, be a regular file of at most :data:`MAX_IMAGE_BYTES` (by ``stat``), and only
then are its first :data:`HEADER_BYTES` read to tell PNG, JPEG, PDF or SVG by their magic header.
Nothing else of the file is ever read here.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from pathlib import Path, PurePosixPath, PureWindowsPath
from typing import TYPE_CHECKING

import sympy as sp

from tutgen.errors import SpecError
from tutgen.model.figure import FigureConfig, FigureFile, FigureView, ImageKind
from tutgen.spec.expr import ExprError, did_you_mean, parse_expression
from tutgen.spec.units import DIMENSIONS, parse_quantity

if TYPE_CHECKING:
    from tutgen.model.system import Coordinate
    from tutgen.spec.loader import KeyPath, SourceMap
    from tutgen.spec.schema import FigureSpec

#: The largest picture accepted (10 MiB).
MAX_IMAGE_BYTES = 10 * 1024 * 1024
#: How much of a picture is read to tell its kind.
HEADER_BYTES = 1024

_MAGIC = (
    (b"\x89PNG\r\n\x1a\n", ImageKind.PNG),
    (b"\xff\xd8\xff", ImageKind.JPEG),
    (b"%PDF-", ImageKind.PDF),
)


def validate_figure(
    spec: FigureSpec | None,
    smap: SourceMap,
    coordinates: Mapping[str, Coordinate],
    parameters: Mapping[str, sp.Symbol],
    errors: list[SpecError],
) -> FigureConfig | None:
    """Check a spec's ``figure:`` section; append each problem to ``errors``; return the config."""
    if spec is None:
        return None
    base: KeyPath = ("figure",)

    def error(path: KeyPath, message: str, hint: str | None = None, key: bool = False) -> None:
        loc = smap.key_location(path) if key else smap.location(path)
        errors.append(SpecError(loc, message, hint))

    at: list[tuple[str, float]] = []
    for name, value in spec.at.items():
        path = (*base, "at", name)
        coord = coordinates.get(name)
        if coord is None:
            guess = did_you_mean(name, coordinates)
            known = ", ".join(coordinates) or "none"
            error(
                path,
                f"figure.at names '{name}', which is not a coordinate (known: {known})",
                f"did you mean '{guess}'?" if guess else None,
                key=True,
            )
            continue
        is_angle = coord.dimension == "angle" or (
            coord.si_dimension is not None and coord.si_dimension == DIMENSIONS["angle"]
        )
        number = _constant(path, value, "an angle (e.g. 30 deg)" if is_angle else "a number", smap, errors)
        if number is not None:
            at.append((name, number))

    sizes: list[tuple[str, float]] = []
    for name, value in spec.sizes.items():
        path = (*base, "sizes", name)
        if name not in parameters:
            guess = did_you_mean(name, parameters)
            error(
                path,
                f"figure.sizes names '{name}', which is not a parameter",
                f"did you mean '{guess}'?" if guess else None,
                key=True,
            )
            continue
        number = _constant(path, value, "a length (e.g. 0.5 m)", smap, errors)
        if number is None:
            continue
        if not number > 0:
            error(path, f"figure.sizes.{name} must be a positive length; found {value}")
            continue
        sizes.append((name, number))

    file = None
    if spec.file is not None:
        file = check_image(spec.file, Path(smap.path).parent, smap, (*base, "file"), errors)
    if not spec.generated and spec.file is None:
        error(
            (*base, "generated"),
            "figure.generated is false but no figure.file is given",
            "give `file:`, or drop `generated: false`",
        )
    return FigureConfig(
        at=tuple(at),
        sizes=tuple(sizes),
        file=file,
        generated=spec.generated,
        view=FigureView(spec.view),
        origin=smap.key_location(base),
    )


def _constant(path: KeyPath, value: object, expected: str, smap: SourceMap, errors: list[SpecError]) -> float | None:
    """A constant (a number, a quantity such as ``30 deg`` or ``0.4 m``, or ``pi/6``) as a float in SI."""
    try:
        quantity = parse_quantity(value) if isinstance(value, str) else None
        result = quantity.value if quantity is not None else parse_expression(value, {})  # type: ignore[arg-type]
    except ExprError as exc:
        errors.append(SpecError(smap.expr_location(path, exc.offset), exc.message, exc.hint))
        return None
    if not result.is_number or result.has(sp.I) or not math.isfinite(float(result)):
        errors.append(SpecError(smap.location(path), f"expected {expected} made of numbers; found {value}"))
        return None
    return float(result)


def check_image(text: str, folder: Path, smap: SourceMap, path: KeyPath, errors: list[SpecError]) -> FigureFile | None:
    """Check the instructor's picture ``text`` (a path relative to ``folder``); None if it is refused."""
    where = smap.location(path)

    def refuse(message: str, hint: str | None = None) -> None:
        errors.append(SpecError(where, message, hint))

    inside = "a path inside the spec's folder, e.g. figure.png"
    if not text.strip() or "\x00" in text:
        refuse("figure.file is empty; expected " + inside)
        return None
    if PurePosixPath(text).is_absolute() or PureWindowsPath(text).is_absolute() or PureWindowsPath(text).drive:
        refuse(f"figure.file '{text}' is an absolute path; expected {inside}")
        return None
    parts = PureWindowsPath(text).parts  # splits on both / and \
    if ".." in parts:
        refuse(f"figure.file '{text}' leads out of the spec's folder ('..'); expected {inside}")
        return None
    root = folder.resolve()
    target = root.joinpath(*parts)
    try:
        resolved = target.resolve()
    except (OSError, RuntimeError):  # a symlink loop
        refuse(f"figure.file '{text}' cannot be resolved (a symlink loop?)")
        return None
    if not resolved.is_relative_to(root):
        refuse(f"figure.file '{text}' is a symlink leading out of the spec's folder; expected {inside}")
        return None
    try:
        st = resolved.stat()
    except FileNotFoundError:
        refuse(f"figure.file '{text}' does not exist (looked in {folder or '.'})")
        return None
    except OSError as err:
        refuse(f"figure.file '{text}' cannot be read: {err.strerror or err}")
        return None
    if not os.path.isfile(resolved):
        refuse(f"figure.file '{text}' is not a regular file")
        return None
    if st.st_size > MAX_IMAGE_BYTES:
        refuse(
            f"figure.file '{text}' is {st.st_size / 1048576:.1f} MiB; the limit is 10 MiB",
            "scale the picture down or export it at a lower resolution",
        )
        return None
    try:
        with open(resolved, "rb") as fh:
            head = fh.read(HEADER_BYTES)
    except OSError as err:
        refuse(f"figure.file '{text}' cannot be read: {err.strerror or err}")
        return None
    kind = image_kind(head)
    if kind is None:
        refuse(f"figure.file '{text}' is not a PNG, JPEG, PDF or SVG picture (by its first bytes)")
        return None
    return FigureFile(PurePosixPath(*parts).as_posix(), resolved, kind, st.st_size)


def image_kind(head: bytes) -> ImageKind | None:
    """The kind of a picture from its first bytes: PNG, JPEG and PDF by their magic numbers, SVG by an
    ``<svg`` element (after an optional BOM, XML declaration, comments or doctype) in the header."""
    for magic, kind in _MAGIC:
        if head.startswith(magic):
            return kind
    text = head.removeprefix(b"\xef\xbb\xbf").lstrip()
    if text.startswith((b"<svg", b"<?xml", b"<!--", b"<!DOCTYPE svg")) and b"<svg" in text:
        return ImageKind.SVG
    return None
