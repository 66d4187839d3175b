"""The drawing description: a short list of primitives and labels in picture coordinates.

Coordinates are centimetres on the page, x to the right and y up (TikZ's convention; the SVG back end
flips y). Every primitive is a polyline, a polygon or a circle, so the two back ends draw exactly the
same thing: arcs, ellipses, zig-zags and arrow heads are made into points here, once.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum

Point = tuple[float, float]


class Stroke(StrEnum):
    """Line weights and patterns, named by what they draw (each back end maps them to its own)."""

    BAR = "bar"  # links and rods
    OUTLINE = "outline"  # bodies' shapes, sliders, pins
    THIN = "thin"  # springs, dampers, hatching, dimension lines
    DASHED = "dashed"  # reference lines of angles, hidden edges
    AXIS = "axis"  # joint axes (dash-dot)
    ARROW = "arrow"  # forces, torques, gravity, coordinates, world axes
    NONE = "none"


class Fill(StrEnum):
    NONE = "none"
    WHITE = "white"
    BLACK = "black"
    GRAY = "gray"


@dataclass(frozen=True)
class Polyline:
    """A path through ``points``; closed into a polygon when ``closed``."""

    points: tuple[Point, ...]
    stroke: Stroke = Stroke.OUTLINE
    fill: Fill = Fill.NONE
    closed: bool = False


@dataclass(frozen=True)
class Circle:
    center: Point
    radius: float
    stroke: Stroke = Stroke.OUTLINE
    fill: Fill = Fill.WHITE


Primitive = Polyline | Circle


@dataclass(frozen=True)
class Box:
    """An axis-aligned rectangle: left, bottom, right, top (cm)."""

    x0: float
    y0: float
    x1: float
    y1: float

    def overlaps(self, other: Box, gap: float = 0.0) -> bool:
        return not (
            self.x1 + gap <= other.x0
            or other.x1 + gap <= self.x0
            or self.y1 + gap <= other.y0
            or other.y1 + gap <= self.y0
        )

    def inside(self, other: Box) -> bool:
        return self.x0 >= other.x0 and self.y0 >= other.y0 and self.x1 <= other.x1 and self.y1 <= other.y1

    def union(self, other: Box) -> Box:
        return Box(min(self.x0, other.x0), min(self.y0, other.y0), max(self.x1, other.x1), max(self.y1, other.y1))


@dataclass(frozen=True)
class Label:
    """A piece of maths set at ``at`` (its centre).

    ``names`` says what it labels: ``coordinate:theta``, ``body:cart``, ``load:push``,
    ``generalized_force:theta``, ``length:l``, ``spring:wall``, ``damper:c``, ``gravity``, ``axis:x``,
    ``frame:link1``; ``tex`` is safe TeX for maths mode (built by :mod:`tutgen.figure.texlabel`,
    never the user's text as written); ``width``/``height`` its estimated size.
    """

    names: str
    tex: str
    at: Point
    width: float
    height: float

    @property
    def box(self) -> Box:
        x, y = self.at
        return Box(x - self.width / 2, y - self.height / 2, x + self.width / 2, y + self.height / 2)


@dataclass(frozen=True)
class Drawing:
    """A whole figure: primitives in drawing order, labels on top, and the picture's bounding box.

    ``remarks`` say what the drawing had to adjust (a label moved off another, a pose changed) so that a
    caption or a log can tell the reader; ``view`` is ``planar`` or ``oblique``; ``at`` the coordinate
    values drawn (SI), ``sizes`` the drawing size used for each symbolic length.
    """

    primitives: tuple[Primitive, ...]
    labels: tuple[Label, ...]
    bbox: Box
    view: str
    at: tuple[tuple[str, float], ...] = ()
    sizes: tuple[tuple[str, float], ...] = ()
    remarks: tuple[str, ...] = field(default=())

    @property
    def names(self) -> frozenset[str]:
        """What the labels name; a force drawn as its components (``force:<name>/x``, ``/y``, see
        :func:`tutgen.figure.freebody.components`) names the force itself too."""
        names = {lb.names for lb in self.labels}
        names |= {n.rsplit("/", 1)[0] for n in names if n.startswith("force:") and "/" in n}
        return frozenset(names)
