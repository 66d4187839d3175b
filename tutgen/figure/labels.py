"""Label placement: each label beside what it names, moved round its anchor until it overlaps no
other label and as few pins, masses and lines as can be (a move is remarked on, never an error)."""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

import numpy as np

from tutgen.figure.geometry import inside, overlaps
from tutgen.figure.scene import Box, Circle, Label, Point, Polyline, Primitive, Stroke
from tutgen.figure.texlabel import PAD, label_size

#: A label asked for: the names it stands for, its TeX, its anchor, the direction it prefers.
Request = tuple[str, str, Point, Point]
#: A label whose box ends farther than this from its anchor (cm) gets a leader line back to it.
LEADER = 0.45
#: Two labels' boxes (each already padded by :data:`tutgen.figure.texlabel.PAD`) keep at least this
#: far apart (cm): boxes that only touch set two names a hair apart, which a reader takes for one.
READ_GAP = 0.1
#: A label's text (its box less the padding) keeps this clear of a pin's or a mass's disc (cm).
DISC_GAP = 0.05


def place_labels(
    requests: Sequence[Request],
    obstacles: Sequence[Box],
    prims: Sequence[Primitive],
    remarks: list[str],
    leaders: list[Primitive] | None = None,
) -> list[Label]:
    """Each label next to its anchor, on the side it asks for when that place is free; otherwise
    the nearest place (eight directions, four distances) that overlaps no placed label, then the
    fewest pins and masses, then the fewest lines. A label moved off another label is remarked on.

    A label that had to go farther than :data:`LEADER` from its anchor is tied back to it, as a
    textbook does, by a thin leader line into ``leaders`` (left out where it would cross another
    label)."""
    placed: list[Label] = []
    ink = ink_points(prims)
    boxes = np.zeros((0, 4))  # the placed labels' boxes, widened by a small gap
    obstacle_rows = np.array([[b.x0, b.y0, b.x1, b.y1] for b in obstacles]).reshape(-1, 4)
    gap = READ_GAP
    # what a reader sees under a label's text (its box less the padding): a pin or a mass's disc, a
    # link's bar; each costs far more than a thin line, short of sitting on another label
    discs = np.array([[p.center[0], p.center[1], p.radius + DISC_GAP] for p in prims if isinstance(p, Circle)]).reshape(
        -1, 3
    )
    bars = ink_points([p for p in prims if isinstance(p, Polyline) and p.stroke is Stroke.BAR])
    for names, tex, anchor, direction in requests:
        w, h = label_size(tex)
        dx, dy = direction
        n = math.hypot(dx, dy)
        base = math.atan2(dy, dx) if n > 1e-9 else math.pi / 4
        best: tuple[float, Label] | None = None
        first_clash = 0.0
        dists = (0.0, 0.25, 0.5, 0.8, 1.2) if n <= 1e-9 else (0.1, 0.3, 0.55, 0.9, 1.3)
        for i, dist in enumerate(dists):
            for turn in (0, 1, -1, 2, -2, 3, -3, 4):
                a = base + turn * math.pi / 4
                reach = dist + 0.5 * (abs(math.cos(a)) * w + abs(math.sin(a)) * h)
                if n <= 1e-9 and dist == 0.0:
                    reach = 0.0
                at = (round(anchor[0] + math.cos(a) * reach, 3), round(anchor[1] + math.sin(a) * reach, 3))
                cand = Label(names, tex, at, round(w, 3), round(h, 3))
                box = cand.box
                clash = overlaps(box, boxes, gap)
                if i == 0 and turn == 0:
                    first_clash = overlaps(box, boxes, 0.0)  # remarked on only where it covered one
                text = Box(box.x0 + PAD, box.y0 + PAD, box.x1 - PAD, box.y1 - PAD)
                cost = 1000 * clash + 100 * _discs_under(text, discs) + 1.0 * inside(text, bars)
                cost += 10 * overlaps(box, obstacle_rows, 0.0)
                cost += 0.05 * inside(box, ink) + 0.02 * (i + abs(turn))
                if best is None or cost < best[0] - 1e-12:
                    best = (cost, cand)
            if best is not None and best[0] < 0.3:
                break
        assert best is not None
        final = best[1].box
        final_clash = overlaps(final, boxes, gap)
        what = names.replace(":", " ").replace("/", " ")
        if first_clash > 0 and final_clash == 0:
            remarks.append(f"the label of {what} was moved off another label")
        elif final_clash > 0:
            remarks.append(f"the label of {what} still overlaps another label; no free place was found")
        placed.append(best[1])
        boxes = np.vstack([boxes, [final.x0, final.y0, final.x1, final.y1]])
    if leaders is not None:
        for (_names, _tex, anchor, _direction), label in zip(requests, placed, strict=True):
            leader = _leader(anchor, label, placed)
            if leader is not None:
                leaders.append(leader)
    return placed


def _discs_under(box: Box, discs: np.ndarray) -> int:
    """How many of the discs (rows cx, cy, r) the box meets."""
    if not len(discs):
        return 0
    nx = np.clip(discs[:, 0], box.x0, box.x1)
    ny = np.clip(discs[:, 1], box.y0, box.y1)
    return int(np.count_nonzero(np.hypot(nx - discs[:, 0], ny - discs[:, 1]) < discs[:, 2]))


def _leader(anchor: Point, label: Label, placed: Sequence[Label]) -> Polyline | None:
    """A thin line from the anchor to the near side of a label placed far from it, or None."""
    box = label.box
    near = (min(max(anchor[0], box.x0), box.x1), min(max(anchor[1], box.y0), box.y1))
    gap = math.dist(anchor, near)
    if gap <= LEADER:
        return None
    ux, uy = (near[0] - anchor[0]) / gap, (near[1] - anchor[1]) / gap
    a = (round(anchor[0] + ux * 0.08, 3), round(anchor[1] + uy * 0.08, 3))
    b = (round(near[0] - ux * 0.04, 3), round(near[1] - uy * 0.04, 3))
    for other in placed:
        if other is not label and _crosses(a, b, other.box):
            return None
    return Polyline((a, b), Stroke.THIN)


def _crosses(a: Point, b: Point, box: Box) -> bool:
    """Whether the segment ab passes through the box (sampled: labels are small)."""
    for i in range(21):
        t = i / 20
        x, y = a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t
        if box.x0 < x < box.x1 and box.y0 < y < box.y1:
            return True
    return False


def ink_points(prims: Sequence[Primitive]) -> np.ndarray:
    """Points every 0.08 cm along every line drawn, to keep labels off the lines."""
    pts: list[tuple[float, float]] = []
    for prim in prims:
        if isinstance(prim, Circle):
            pts.append(prim.center)
            continue
        ring = (*prim.points, prim.points[0]) if prim.closed else prim.points
        for (x0, y0), (x1, y1) in itertools.pairwise(ring):
            k = max(1, int(math.hypot(x1 - x0, y1 - y0) / 0.08))
            pts += [(x0 + (x1 - x0) * t / k, y0 + (y1 - y0) * t / k) for t in range(k)]
    return np.array(pts) if pts else np.zeros((0, 2))
