"""How a problem's figure is drawn: the validated ``figure:`` section of a spec.

Values are plain numbers in SI (radians for angles, metres for lengths), because they only place a
drawing; nothing derived depends on them.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum
from pathlib import Path

from tutgen.errors import Location


class FigureView(StrEnum):
    """The projection: ``auto`` picks ``planar`` when every motion lies in one world plane."""

    AUTO = "auto"
    PLANAR = "planar"
    OBLIQUE = "oblique"


class ImageKind(StrEnum):
    """The kinds of picture an instructor may give, told apart by their magic header."""

    PNG = "png"
    JPEG = "jpeg"
    PDF = "pdf"
    SVG = "svg"


@dataclass(frozen=True)
class FigureFile:
    """An instructor's picture: ``path`` as written (relative to the spec's folder, POSIX
    separators) and ``resolved``, its checked absolute path inside that folder."""

    path: str
    resolved: Path
    kind: ImageKind
    size: int  # bytes


@dataclass(frozen=True)
class FigureConfig:
    """The drawing configuration of a spec.

    ``at`` gives the drawing's value of some coordinates (others get a default that makes every angle
    visibly non-zero); ``sizes`` the drawing size of symbolic parameters (lengths, radii) in metres;
    ``generated`` is False when only the instructor's ``file`` is shown.
    """

    at: tuple[tuple[str, float], ...] = ()
    sizes: tuple[tuple[str, float], ...] = ()
    file: FigureFile | None = None
    generated: bool = True
    view: FigureView = FigureView.AUTO
    origin: Location | None = None
