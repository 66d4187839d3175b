"""The state a drawing is built on, and the helpers every element kind draws with.

:class:`Canvas` holds the system, its numbers and pose (steps 1-2 of :mod:`tutgen.figure.build`), the
projection and the scale (steps 3-4), and the primitives, label requests and obstacles drawn so far;
it also answers the questions the element kinds share: where a body's parts and far points are, the
page direction of a world direction, the TeX of an expression, which body a free coordinate moves.
The element kinds are subclasses in turn (:mod:`tutgen.figure.bodies`, :mod:`tutgen.figure.coordinates`,
:mod:`tutgen.figure.elements`, :mod:`tutgen.figure.axes`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import sympy as sp

from tutgen.figure.pose import Numbers, Pose, Vec, close_loops, default_size, read
from tutgen.figure.scene import Box, Circle, Fill, Point, Polyline, Primitive, Stroke
from tutgen.figure.texlabel import expr_tex, name_tex, word_tex
from tutgen.model.figure import FigureConfig, FigureView
from tutgen.model.system import Body, Coordinate, JointKind, Shape, System

#: The skeleton's longer side on the page (cm).
TARGET_SIZE = 5.0
PIN = 0.09
MASS = 0.13
SLIDER = (0.8, 0.5)  # width along the rail, height (cm)
ARC = 0.75
HEAD = (0.22, 0.08)  # arrow head length, half width (cm)
#: Joints drawn at one page point (a spherical wrist's three) have their marks set this far apart
#: (cm) along their own axes, one step per joint already there (see Canvas.axis_shift).
WRIST_STEP = 0.75

#: Angles (degrees) of the first independent coordinate tried when a loop cannot close at its default.
RETRY_ANGLES = (60, 20, 80, 110, 140, 170, -20, -60, -100, -140)

#: Sign patterns tried for the default relative angles when the first pose makes links overlap.
POSE_SIGNS = ((1, 1, 1, 1, 1, 1), (1, -1, 1, -1, 1, -1), (1, 1, -1, -1, 1, 1), (-1, 1, 1, -1, -1, 1))


class Canvas:
    """A system being drawn: its numbers, pose, projection and scale, and what is drawn so far."""

    # set by numbers(), build(), choose_view() and choose_scale(), in that order
    sizes: list[tuple[str, float]]
    typical: float
    at: list[tuple[str, float]]
    num: Numbers
    pose: Pose
    view: str
    screen: tuple[int, int]
    plane_normal: Vec
    matrix: Vec
    up: Vec
    scale: float
    sliders: dict[str, tuple[Point, Point]]

    def __init__(self, system: System, signs: Sequence[int] = POSE_SIGNS[0]) -> None:
        self.s = system
        self.signs = signs  # of the default relative angles, in coordinate order
        self.cfg = system.figure or FigureConfig()
        self.prims: list[Primitive] = []
        self.requests: list[tuple[str, str, Point, Point]] = []  # names, tex, anchor, preferred direction
        self.obstacles: list[Box] = []
        self.remarks: list[str] = []
        self.slider = SLIDER  # the block's size; a free-body diagram draws it larger
        self.only: str | None = None  # a free-body diagram draws this one body (tutgen/figure/freebody.py)
        self.latex_of = {p.symbol: name_tex(p.name, p.latex) for p in system.parameters}
        self.latex_of.update({c.q: name_tex(c.name, c.latex) for c in system.coordinates})

    # -- 1. numbers ------------------------------------------------------------------------
    def numbers(self) -> None:
        s, cfg = self.s, self.cfg
        given_sizes = dict(cfg.sizes)
        table: dict[sp.Symbol, float] = {}
        self.sizes: list[tuple[str, float]] = []
        for p in s.parameters:
            if p.name in given_sizes:
                table[p.symbol] = given_sizes[p.name]
                self.sizes.append((p.name, given_sizes[p.name]))
            elif p.value is not None and p.value.is_number:
                table[p.symbol] = float(p.value)
            elif p.symbol in self._com_only():
                # a centre of mass given only by its own symbols (an arm's cx2, cy2, cz2) is not known
                # to be anywhere in particular: it is drawn on its body's frame origin, not at a made-up
                # offset that would send a spoke off every link
                table[p.symbol] = 0.0
                self.sizes.append((p.name, 0.0))
            else:
                table[p.symbol] = default_size(p.name)
                if self._is_geometric(p.symbol):
                    self.sizes.append((p.name, table[p.symbol]))
        lengths = [v for sym, v in table.items() if self._is_geometric(sym)]
        read(sym for sym in table if self._is_geometric(sym))  # the typical length: the scale, the displacements
        self.typical = max(lengths, default=1.0) or 1.0
        given_at = dict(cfg.at)
        at: list[tuple[str, float]] = []
        k_angle, last_absolute = 0, 0.0
        joint_of = {j.coordinate.name: j for j in s.joints if j.coordinate is not None}
        for c in s.coordinates:
            if c.name in given_at:
                value = given_at[c.name]
            elif self.is_angle(c):
                joint = joint_of.get(c.name)
                if joint is not None and joint.absolute:
                    last_absolute += math.radians(45)
                    value = last_absolute
                else:
                    value = math.radians(40 if k_angle == 0 else 35 - 5 * min(k_angle - 1, 3))
                    value *= self.signs[k_angle % len(self.signs)]
                    if k_angle == 0:
                        last_absolute = value
                k_angle += 1
            else:
                value = 0.6 * self.typical
            table[c.q] = value
            at.append((c.name, value))
        self.num = Numbers(table, frozenset(c.q for c in s.coordinates))
        if s.is_constrained:
            # the dependent coordinates solved so that the loops close (and a disc's x is R phi)
            at = self._closed(at, given_at)
        self.at = at

    def _closed(self, at: list[tuple[str, float]], given_at: dict[str, float]) -> list[tuple[str, float]]:
        """The pose with its loops closed (:func:`tutgen.figure.pose.close_loops`). When they cannot close
        at the default angle of the first independent coordinate (a linkage whose crank cannot turn
        fully), a few other angles are tried, and the one drawn is remarked on."""
        s = self.s
        num, solved, closed = close_loops(s, self.num)
        # the first independent coordinate (without the list, the first coordinate: the engine keeps the first n - m)
        listed = [c for c in s.coordinates if c.name in s.independent_coordinates]
        first = listed[0] if listed else (s.coordinates[0] if s.coordinates else None)
        if not closed and first is not None and first.name not in given_at and self.is_angle(first):
            for degrees in RETRY_ANGLES:
                value = math.radians(degrees)
                num, solved, closed = close_loops(s, self.num.with_(first.q, value))
                if closed:
                    solved = {first.name: value, **solved}
                    self.remarks.append(
                        f"the loop does not close at the default {first.name}: it is drawn at {degrees} degrees"
                    )
                    break
        if not closed:
            self.remarks.append("the loop does not close at the drawn sizes: it is drawn open")
            return at
        self.num = num
        return [(name, solved.get(name, value)) for name, value in at]

    def _com_only(self) -> frozenset[sp.Basic]:
        """The symbols that place only centres of mass given as unknown points: bodies given by mass
        and com whose every com component has a term of its own symbol (``cx2``, ``-cz2`` as a
        standard DH row turns it, ``a2 + cx2`` past a link's length) found in no joint, shape,
        element end, load or explicit position, nor in another component."""
        if not hasattr(self, "_com_symbols"):
            other: set[sp.Basic] = set()
            for j in self.s.joints:
                other |= j.origin_offset.free_symbols | j.offset.free_symbols
            for b in self.s.bodies:
                for part in b.parts:
                    for _name, dim in part.dimensions:
                        for d in dim if isinstance(dim, tuple) else (dim,):
                            other |= sp.sympify(d).free_symbols
                    if not b.is_simple:
                        other |= part.at.free_symbols
                if b.position is not None:
                    other |= b.position.free_symbols
            for el in (*self.s.springs, *self.s.dampers):
                for end in el.between or ():
                    other |= end.at.free_symbols
            for load in self.s.loads:
                other |= load.at.free_symbols
            com: set[sp.Basic] = set()
            for b in self.s.bodies:
                if not b.is_simple:
                    continue
                for part in b.parts:
                    own = []
                    for v in part.at:
                        terms = [t if isinstance(t, sp.Symbol) else -t for t in sp.Add.make_args(sp.sympify(v))]
                        own.append([t for t in terms if isinstance(t, sp.Symbol) and t not in other])
                    flat = [t for ts in own for t in ts]
                    if all(len(ts) == 1 for ts in own) and len(set(flat)) == len(flat):
                        com |= set(flat)
                    else:
                        other |= part.at.free_symbols
            self._com_symbols = frozenset(com - other)
        return self._com_symbols

    def _is_geometric(self, symbol: sp.Symbol) -> bool:
        if not hasattr(self, "_geometric"):
            found: set[sp.Basic] = set()
            for j in self.s.joints:
                found |= j.origin_offset.free_symbols | j.offset.free_symbols
            for b in self.s.bodies:
                for part in b.parts:
                    found |= part.at.free_symbols
                    for _name, dim in part.dimensions:
                        for d in dim if isinstance(dim, tuple) else (dim,):
                            found |= sp.sympify(d).free_symbols
                if b.position is not None:
                    found |= b.position.free_symbols
            for el in (*self.s.springs, *self.s.dampers):
                for end in el.between or ():
                    found |= end.at.free_symbols
            self._geometric = found
        return symbol in self._geometric

    def is_angle(self, c: Coordinate) -> bool:
        if c.dimension in ("angle", "length"):
            return c.dimension == "angle"
        for j in self.s.joints:
            if j.coordinate is not None and j.coordinate.name == c.name:
                return j.kind is JointKind.REVOLUTE
        for b in self.s.bodies:
            if b.rotation is not None and c.q in b.rotation.free_symbols:
                return True
            if any(c.q in sp.sympify(angle).free_symbols for _axis, angle in b.rotation_rates):
                return True
            if b.position is not None:
                for f in sp.Matrix(b.position).atoms(sp.sin, sp.cos):
                    if c.q in f.free_symbols:
                        return True
        if self.s.kinetic_energy is not None:
            for f in sp.sympify(self.s.kinetic_energy).atoms(sp.sin, sp.cos):
                if c.q in f.free_symbols:
                    return True
        return False

    # -- 3. projection ---------------------------------------------------------------------
    def choose_view(self) -> None:
        pose = self.pose
        normal: int | None = None
        planar = bool(self.s.coordinates) and bool(self.s.bodies)
        axes = [pose.axis_of[j.name] for j in self.s.joints if j.kind is JointKind.REVOLUTE]
        for b in self.s.bodies:
            for axis, _angle in b.rotation_rates:
                axes.append(
                    np.array([float(v) for v in axis]) if all(sp.sympify(v).is_number for v in axis) else np.ones(3)
                )
        for a in axes:
            k = int(np.argmax(np.abs(a)))
            if abs(abs(a[k]) - 1) > 1e-9 or (normal is not None and k != normal):
                planar = False
            normal = k if normal is None else normal
        # points must stay in one plane when any coordinate moves
        pts = self.key_points(pose)
        moved = [self.key_points(Pose(self.s, self.num.with_(c.q, self.num(c.q) + 0.37))) for c in self.s.coordinates]
        if normal is None:
            spread = [
                max(abs(p[k] - q[k]) for m in moved for p, q in zip(pts, m, strict=True)) if moved else 0.0
                for k in range(3)
            ]
            flat = [k for k in range(3) if spread[k] < 1e-9 and all(abs(p[k] - pts[0][k]) < 1e-9 for p in pts)]
            normal = 2 if 2 in flat else (flat[0] if flat else None)
            planar = planar and normal is not None
        elif planar:
            for m in moved:
                for p, q in zip(pts, m, strict=True):
                    if abs(p[normal] - q[normal]) > 1e-9:
                        planar = False
        if planar and self.s.gravity is not None and abs(self.num(self.s.gravity[normal or 0])) > 1e-12:
            planar = False
        for b in self.s.bodies:  # a body drawn by its 3-D shape off the plane needs depth
            for part in b.parts:
                if part.shape is Shape.BOX and normal is not None and not planar:
                    break
        if self.cfg.view is FigureView.PLANAR and normal is None:
            normal = 2
        if self.cfg.view is not FigureView.AUTO:
            planar = self.cfg.view is FigureView.PLANAR
        self.view = "planar" if planar else "oblique"
        if planar:
            k = normal if normal is not None else 2
            self.screen = [(0, 1), (0, 2), (0, 1)][0] if k == 2 else ((0, 2) if k == 1 else (1, 2))
            ex, ey = np.zeros(3), np.zeros(3)
            ex[self.screen[0]], ey[self.screen[1]] = 1, 1
            self.plane_normal = np.cross(ex, ey)
            self.matrix = np.array([ex, ey])
        else:
            up = 2
            if self.s.gravity is not None:
                gv = self.num.vec(self.s.gravity)
                if np.linalg.norm(gv) > 0:
                    up = int(np.argmax(np.abs(gv)))
            a, b = {2: (0, 1), 1: (2, 0), 0: (1, 2)}[up]
            m = np.zeros((2, 3))
            m[:, a] = (-0.42, -0.26)
            m[:, b] = (0.95, -0.12)
            m[:, up] = (0.0, 1.0)
            self.matrix = m
            self.plane_normal = np.eye(3)[up]
        self.up = self.plane_normal

    def key_points(self, pose: Pose) -> list[Vec]:
        pts: list[Vec] = [np.zeros(3)]
        for j in self.s.joints:
            pts.append(pose.joint_at[j.name])
        for b in self.s.bodies:
            pts.append(pose.frames[b.name][0])
            for part in b.parts:
                pts.append(pose.point(b.name, self.num.vec(part.at)))
        return pts

    def project(self, p: Vec) -> Vec:
        return self.matrix @ p

    def P(self, p: Vec) -> Point:
        q = self.matrix @ p * self.scale
        return (float(q[0]), float(q[1]))

    # -- 4. scale --------------------------------------------------------------------------
    def choose_scale(self) -> None:
        pts = [self.project(p) for p in self.key_points(self.pose)]
        for b in self.s.bodies:
            for part in b.parts:
                for p in self.part_points(b, part, self.pose):
                    pts.append(self.project(p))
        arr = np.array(pts) if pts else np.zeros((1, 2))
        extent = float(max(np.ptp(arr[:, 0]), np.ptp(arr[:, 1]), 1e-9))
        self.scale = TARGET_SIZE / extent if extent > 1e-6 else 1.0
        if extent <= 1e-6:
            self.scale = TARGET_SIZE / self.typical

    # -- helpers in page space ---------------------------------------------------------------
    def line(
        self, pts: Sequence[Point], stroke: Stroke = Stroke.OUTLINE, fill: Fill = Fill.NONE, closed: bool = False
    ) -> None:
        if len(pts) >= 2:
            self.prims.append(Polyline(tuple((round(x, 3), round(y, 3)) for x, y in pts), stroke, fill, closed))

    def circle(
        self, c: Point, r: float, fill: Fill = Fill.WHITE, stroke: Stroke = Stroke.OUTLINE, obstacle: bool = True
    ) -> None:
        self.prims.append(Circle((round(c[0], 3), round(c[1], 3)), round(r, 3), stroke, fill))
        if obstacle:
            self.obstacles.append(Box(c[0] - r, c[1] - r, c[0] + r, c[1] + r))

    def arrow(self, a: Point, b: Point, stroke: Stroke = Stroke.ARROW, both: bool = False) -> None:
        self.line([a, b], stroke)
        self.head(a, b)
        if both:
            self.head(b, a)

    def head(self, a: Point, b: Point) -> None:
        dx, dy = b[0] - a[0], b[1] - a[1]
        n = math.hypot(dx, dy)
        if n < 1e-9:
            return
        ux, uy = dx / n, dy / n
        ln, hw = HEAD
        base = (b[0] - ux * ln, b[1] - uy * ln)
        self.line(
            [b, (base[0] - uy * hw, base[1] + ux * hw), (base[0] + uy * hw, base[1] - ux * hw)],
            Stroke.NONE,
            Fill.BLACK,
            closed=True,
        )

    def label(self, names: str, tex: str, anchor: Point, direction: Point = (0.0, 1.0)) -> None:
        self.requests.append((names, tex, anchor, direction))

    def hatch(self, a: Point, b: Point, side: Point) -> None:
        """A ground line from a to b, hatched on ``side`` (a unit vector in the page)."""
        self.line([a, b], Stroke.OUTLINE)
        dx, dy = b[0] - a[0], b[1] - a[1]
        n = math.hypot(dx, dy)
        if n < 1e-9:
            return
        steps = max(2, int(n / 0.16))
        for i in range(steps + 1):
            t = i / steps
            x, y = a[0] + dx * t, a[1] + dy * t
            self.line([(x, y), (x + side[0] * 0.14 - dx / n * 0.12, y + side[1] * 0.14 - dy / n * 0.12)], Stroke.THIN)

    def arc_points(self, center: Vec, start: Vec, axis: Vec, angle: float, radius_cm: float) -> list[Point]:
        """A circular arc in 3-D about ``axis`` through ``center``, from the direction ``start``, radius on
        the page ``radius_cm`` (measured in the plane of the arc), projected."""
        u = start - axis * float(start @ axis)
        if np.linalg.norm(u) < 1e-12:
            return []
        u = u / np.linalg.norm(u)
        v = np.cross(axis, u)
        r = radius_cm / self.scale
        n = max(8, int(abs(angle) / math.radians(6)))
        return [self.P(center + r * (math.cos(angle * i / n) * u + math.sin(angle * i / n) * v)) for i in range(n + 1)]

    # -- what the element kinds share ----------------------------------------------------------
    def tex_of(self, expr: object, fallback: str) -> str:
        tex = expr_tex(sp.sympify(expr), self.latex_of)
        return tex if tex is not None else word_tex(fallback)

    def body_tex(self, body: Body) -> str:
        if body.is_simple and len(body.parts) == 1 and body.parts[0].mass is not None:
            tex = expr_tex(body.parts[0].mass, self.latex_of)
            if tex is not None:
                return tex
        return word_tex(body.name)

    def far_points(self, body: Body, pose: Pose) -> list[Vec]:
        """The points a body's bars go to from its frame origin: its joints, its centre of mass."""
        out = []
        for j in self.s.joints:
            if j.parent == body.name:
                out.append(pose.joint_at[j.name])
        if body.is_simple or all(p.shape is Shape.POINT for p in body.parts):
            for part in body.parts:
                out.append(pose.point(body.name, self.num.vec(part.at)))
        return out

    def part_centres(self, body: Body, pose: Pose) -> list[Vec]:
        """The centres of a body's shaped parts (not point masses: far_points has those)."""
        if body.is_simple or all(p.shape is Shape.POINT for p in body.parts):
            return []
        return [pose.point(body.name, self.num.vec(p.at)) for p in body.parts if p.shape is not Shape.POINT]

    def part_points(self, body: Body, part: object, pose: Pose) -> list[Vec]:
        """Points on a part's outline (world), for its shape and for the scale."""
        num = self.num
        at = pose.point(body.name, num.vec(part.at))  # type: ignore[attr-defined]
        rot = pose.frames[body.name][1]
        dims = dict(part.dimensions)  # type: ignore[attr-defined]
        shape = part.shape  # type: ignore[attr-defined]
        if shape is Shape.BOX and "size" in dims:
            sx, sy, sz = (num(v) / 2 for v in dims["size"])
            r = rot @ num.mat(part.rotation)  # type: ignore[attr-defined]
            return [at + r @ np.array([a * sx, b * sy, c * sz]) for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)]
        axis = rot @ num.vec(part.axis) if part.axis is not None else rot @ np.array([0.0, 0.0, 1.0])  # type: ignore[attr-defined]
        length = num(dims.get("length", 0))
        if shape is Shape.ROD:
            return [at - axis * length / 2, at + axis * length / 2]
        if shape in (Shape.CYLINDER, Shape.HOLLOW_CYLINDER, Shape.THIN_CYLINDER, Shape.DISC):
            radius = num(dims.get("radius", dims.get("outer_radius", 0.1)))
            u = np.cross(axis, [1.0, 0, 0]) if abs(axis[0]) < 0.9 else np.cross(axis, [0, 1.0, 0])
            u = u / np.linalg.norm(u)
            v = np.cross(axis, u)
            pts = []
            for end in (-1, 1):
                c = at + axis * end * length / 2
                pts += [c + radius * (math.cos(t) * u + math.sin(t) * v) for t in np.linspace(0, 2 * math.pi, 37)]
            return pts
        if shape in (Shape.SPHERE, Shape.SPHERICAL_SHELL):
            radius = num(dims.get("radius", 0.1))
            return [at + radius * e for e in (*np.eye(3), *-np.eye(3))]
        return [at]

    def axis_shift(self, joint_name: str) -> float:
        """How far along its own axis (cm on the page, signed) a revolute joint's marks are drawn: its
        angle's arc and the end of its axis line. A joint that falls on the page point of an earlier
        joint (the three axes of a spherical wrist meet in one point) is drawn one
        :data:`WRIST_STEP` farther along its axis per such joint, away from the picture's centre: an
        arc anywhere on the axis line shows the same rotation, and the wrist's arcs and labels no
        longer lie on each other. 0 for the first joint at a point, and where the axis is seen nearly
        end-on (the shift would not show)."""
        if not hasattr(self, "_axis_shifts"):
            shifts: dict[str, float] = {}
            seen: list[Point] = []
            pts = [self.P(p) for p in self.key_points(self.pose)]
            cx, cy = sum(p[0] for p in pts) / len(pts), sum(p[1] for p in pts) / len(pts)
            for j in self.s.joints:
                if j.kind is not JointKind.REVOLUTE:
                    continue
                at3, axis = self.pose.joint_at[j.name], self.pose.axis_of[j.name]
                here = self.P(at3)
                k = sum(1 for p in seen if math.dist(p, here) < 0.25)
                seen.append(here)
                tip = self.P(at3 + axis / self.scale)
                seen_len = math.dist(tip, here)  # how long 1 cm of the axis looks on the page
                if k == 0 or self.view != "oblique" or seen_len < 0.35:
                    continue
                out = 1.0 if math.dist(tip, (cx, cy)) >= math.dist(self.P(at3 - axis / self.scale), (cx, cy)) else -1.0
                shifts[j.name] = out * WRIST_STEP * k / seen_len
            self._axis_shifts = shifts
        return self._axis_shifts.get(joint_name, 0.0)

    def outward(self, at: Point) -> Point:
        """A direction away from the skeleton's centre (for a label)."""
        pts = [self.P(p) for p in self.key_points(self.pose)]
        cx = sum(p[0] for p in pts) / len(pts)
        cy = sum(p[1] for p in pts) / len(pts)
        dx, dy = at[0] - cx, at[1] - cy
        n = math.hypot(dx, dy)
        return (dx / n, dy / n) if n > 1e-6 else (0.7, 0.7)

    # -- bodies placed by positions (no joints), sliders, page directions -----------------------
    def carrier(self, c: Coordinate) -> Body | None:
        for b in self.s.bodies:
            if b.name in self.pose.by_child:
                continue
            deps = set()
            if b.position is not None:
                deps |= b.position.free_symbols
            if b.rotation is not None:
                deps |= b.rotation.free_symbols
            for _axis, angle in b.rotation_rates:
                deps |= sp.sympify(angle).free_symbols
            if c.q in deps:
                return b
        return None

    def slider_side(self, body: str, p: Point, toward: Point) -> Point:
        if body in self.sliders:
            return self.slider_side_point(p, toward)
        return p

    def slider_side_point(self, p: Point, toward: Point) -> Point:
        d = np.array(toward) - np.array(p)
        n = np.linalg.norm(d)
        if n < 1e-9:
            return p
        u = d / n
        return (float(p[0] + u[0] * self.slider[0] / 2), float(p[1] + u[1] * self.slider[0] / 2))

    def page_dir(self, at: Vec, world_dir: Vec) -> Point | None:
        a = np.array(self.P(at))
        b = np.array(self.P(at + world_dir / self.scale))
        d = b - a
        n = float(np.linalg.norm(d))
        return (float(d[0] / n), float(d[1] / n)) if n > 1e-9 else None
