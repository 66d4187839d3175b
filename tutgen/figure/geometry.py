"""Plane geometry on page points: segment crossings, bounding boxes, box overlaps, convex hulls and
the zig-zag of a spring. Pure functions of numbers; nothing here knows about a system or a drawing."""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from tutgen.figure.scene import Box, Circle, Point, Primitive


def segments_cross(a: Point, b: Point, c: Point, d: Point) -> bool:
    """Whether the segments a-b and c-d cross at a point inside both (touching does not count)."""

    def side(p: Point, q: Point, r: Point) -> float:
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])

    d1, d2 = side(c, d, a), side(c, d, b)
    d3, d4 = side(a, b, c), side(a, b, d)
    return d1 * d2 < -1e-9 and d3 * d4 < -1e-9


def overlaps(box: Box, boxes: np.ndarray, gap: float) -> float:
    """The total area by which ``box`` overlaps the rows (x0, y0, x1, y1) of ``boxes``."""
    if not len(boxes):
        return 0.0
    w = np.minimum(box.x1, boxes[:, 2]) - np.maximum(box.x0, boxes[:, 0]) + gap
    h = np.minimum(box.y1, boxes[:, 3]) - np.maximum(box.y0, boxes[:, 1]) + gap
    return float(np.sum(np.where((w > 1e-9) & (h > 1e-9), w * h, 0.0)))


def inside(box: Box, pts: np.ndarray) -> int:
    """How many of the rows (x, y) of ``pts`` lie strictly inside ``box``."""
    if not len(pts):
        return 0
    x, y = pts[:, 0], pts[:, 1]
    return int(np.count_nonzero((x > box.x0) & (x < box.x1) & (y > box.y0) & (y < box.y1)))


def points_box(pts: Iterable[Point]) -> Box:
    """The smallest box holding ``pts`` (at least one point)."""
    xs, ys = zip(*pts, strict=True)
    return Box(min(xs), min(ys), max(xs), max(ys))


def prim_box(prim: Primitive) -> Box:
    """The bounding box of one primitive."""
    if isinstance(prim, Circle):
        (x, y), r = prim.center, prim.radius
        return Box(x - r, y - r, x + r, y + r)
    return points_box(prim.points)


def convex_hull(pts: list[Point]) -> list[Point]:
    """The convex hull (Andrew's monotone chain), counter-clockwise."""
    ps = sorted(set((round(x, 4), round(y, 4)) for x, y in pts))
    if len(ps) <= 2:
        return ps

    def cross(o: Point, a: Point, b: Point) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list[Point] = []
    for p in ps:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    upper: list[Point] = []
    for p in reversed(ps):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def zigzag(a: Point, b: Point, width: float = 0.16) -> list[Point]:
    """A spring from a to b: straight leads, then zig-zags of ``width`` either side."""
    pa, pb = np.array(a), np.array(b)
    d = pb - pa
    n = float(np.linalg.norm(d))
    u = d / n
    nrm = np.array([-u[1], u[0]])
    lead = min(0.2, n * 0.15)
    turns = max(4, min(12, int((n - 2 * lead) / 0.18)))
    pts = [pa, pa + u * lead]
    step = (n - 2 * lead) / turns
    for i in range(turns):
        pts.append(pa + u * (lead + step * (i + 0.5)) + nrm * width * (1 if i % 2 == 0 else -1))
    pts += [pb - u * lead, pb]
    return [(float(p[0]), float(p[1])) for p in pts]
