"""The drawing of a system: its model, placed at one pose, projected, and laid out as primitives.

Steps (each a method of :class:`_Builder`, in drawing order):

1. numbers: every parameter gets a number (its value, or a drawing size for a symbolic length,
   ``figure.sizes`` first), every coordinate a drawing value (``figure.at`` first; otherwise angles of
   30-40 degrees, absolute angles 45 degrees apart, displacements 0.6 of the typical length), so that
   every angle is visibly non-zero;
2. pose: the frames of all bodies, numerically, with the model's joint conventions
   (:class:`tutgen.model.system.Joint`);
3. projection: ``planar`` when every joint axis of rotation is one world axis and every motion lies
   in the plane normal to it (screen axes the two others), else an oblique view with the up axis
   against gravity;
4. scale: the skeleton (joints, centres of mass, parts) fills about 5 cm;
5. primitives: ground, rails, links, bodies, springs, dampers, loads, coordinates, lengths, gravity,
   world axes (and, in the oblique view, joint axes and body frames);
6. labels: each placed next to what it names, moved round its anchor until it overlaps no other label
   and no pin or mass (a move is remarked on, never an error).
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import re
from collections.abc import Iterable, Sequence

import numpy as np
import sympy as sp

from tutgen.figure.scene import Box, Circle, Drawing, Fill, Label, Point, Polyline, Primitive, Stroke
from tutgen.figure.texlabel import expr_tex, label_size, name_tex, word_tex
from tutgen.model.figure import FigureConfig, FigureView
from tutgen.model.system import GROUND, Body, Coordinate, Joint, JointKind, Shape, System

#: The skeleton's longer side on the page (cm).
TARGET_SIZE = 5.0
PIN = 0.09
MASS = 0.13
SLIDER = (0.8, 0.5)  # width along the rail, height (cm)
ARC = 0.75
HEAD = (0.22, 0.08)  # arrow head length, half width (cm)

Vec = np.ndarray


#: Sign patterns tried for the default relative angles when the first pose makes links overlap.
_POSE_SIGNS = ((1, 1, 1, 1, 1, 1), (1, -1, 1, -1, 1, -1), (1, 1, -1, -1, 1, 1), (-1, 1, 1, -1, -1, 1))


def draw_system(system: System) -> Drawing:
    """The schematic of ``system`` (see the module docstring for how it is made).

    When the default pose makes two links overlap (a chain folding back on itself), the next sign
    pattern of the default angles is tried, and the change is remarked on; a pose the spec gives
    (``figure.at``) is kept as it is, with a remark."""
    drawing = _Builder(system).build()
    if not _links_overlap(drawing):
        return drawing
    given = {name for name, _v in (system.figure.at if system.figure else ())}
    if given:
        return _remarked(drawing, "two links overlap at the pose given by figure.at")
    for signs in _POSE_SIGNS[1:]:
        other = _Builder(system, signs).build()
        if not _links_overlap(other):
            return _remarked(other, "the default pose made two links overlap; some angles are drawn negative")
    return _remarked(drawing, "two links overlap at every default pose tried")


def _remarked(drawing: Drawing, remark: str) -> Drawing:
    return dataclasses.replace(drawing, remarks=(*drawing.remarks, remark))


def _links_overlap(drawing: Drawing) -> bool:
    """Whether two bars of the drawing cross, or one lies along the other from a shared end."""
    bars = [
        p.points
        for p in drawing.primitives
        if isinstance(p, Polyline) and p.stroke is Stroke.BAR and len(p.points) == 2
    ]
    for i, (a, b) in enumerate(bars):
        for c, d in bars[i + 1 :]:
            shared = [(p, q) for p in (a, b) for q in (c, d) if math.dist(p, q) < 0.02]
            if shared:
                p, _q = shared[0]
                u = (b[0] - a[0], b[1] - a[1]) if p == a else (a[0] - b[0], a[1] - b[1])
                v = (d[0] - c[0], d[1] - c[1]) if math.dist(p, c) < 0.02 else (c[0] - d[0], c[1] - d[1])
                nu, nv = math.hypot(*u), math.hypot(*v)
                if nu > 0.05 and nv > 0.05 and (u[0] * v[0] + u[1] * v[1]) / (nu * nv) > math.cos(math.radians(4)):
                    return True  # folded back along each other
                continue
            if _cross(a, b, c, d):
                return True
    return False


def _cross(a: Point, b: Point, c: Point, d: Point) -> bool:
    def side(p: Point, q: Point, r: Point) -> float:
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])

    d1, d2 = side(c, d, a), side(c, d, b)
    d3, d4 = side(a, b, c), side(a, b, d)
    return d1 * d2 < -1e-9 and d3 * d4 < -1e-9


# ---------------------------------------------------------------------------------------------
# numbers and the pose
# ---------------------------------------------------------------------------------------------


def _default_size(name: str) -> float:
    """A drawing size for a symbolic length, by the usual letter: links 1, offsets and radii less;
    a trailing number shortens each next link a little (l1 = 1, l2 = 0.85, ...)."""
    base = {"r": 0.22, "R": 0.25, "c": 0.5, "h": 0.6, "b": 0.5, "e": 0.3, "w": 0.4}.get(name[0], 1.0)
    digits = re.search(r"(\d+)$", name)
    k = int(digits.group(1)) if digits else 1
    return base * 0.85 ** max(0, min(k, 9) - 1)


def _rotation(axis: Vec, angle: float) -> Vec:
    a = axis / (np.linalg.norm(axis) or 1.0)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.cos(angle) * np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * np.outer(a, a)


class _Numbers:
    """Floats for sympy expressions, from one table of symbol values.

    Values of expressions free of the coordinates are kept in a cache shared by every pose derived
    with :meth:`with_`, since drawing one figure evaluates the same joint offsets for many poses."""

    def __init__(self, table: dict[sp.Symbol, float], moving: frozenset[sp.Symbol] = frozenset()) -> None:
        self.table = {s: sp.Float(v) for s, v in table.items()}
        self.moving = moving
        self.cache: dict[sp.Basic, float] = {}
        self.mcache: dict[int, tuple[object, Vec]] = {}

    def with_(self, symbol: sp.Symbol, value: float) -> _Numbers:
        out = _Numbers({}, self.moving)
        out.table = {**self.table, symbol: sp.Float(value)}
        out.cache, out.mcache = self.cache, self.mcache
        return out

    def __call__(self, expr: object) -> float:
        e0 = sp.sympify(expr)
        if e0.is_Number:
            return float(e0)
        hit = self.cache.get(e0)
        if hit is not None:
            return hit
        e = e0.xreplace(self.table)
        rest = e.free_symbols
        if rest:
            e = e.xreplace({s: sp.Float(1) for s in rest})
        try:
            value = float(e)
        except TypeError:
            value = 0.0
        if not (e0.free_symbols & self.moving):
            self.cache[e0] = value
        return value

    def vec(self, m: object) -> Vec:
        return self.mat(m).reshape(-1)

    def mat(self, m: object) -> Vec:
        """A matrix as floats; a constant one is converted once per drawing (keyed by the object,
        which the model keeps alive)."""
        hit = self.mcache.get(id(m))
        if hit is not None and hit[0] is m:
            return hit[1].copy()
        mm = sp.Matrix(m)
        value = np.array([[self(v) for v in row] for row in mm.tolist()], dtype=float)
        if not (mm.free_symbols & self.moving):
            self.mcache[id(m)] = (m, value)
        return value.copy()


class _Pose:
    """Every body frame (origin, rotation world-from-body) at one set of numbers."""

    def __init__(self, system: System, num: _Numbers) -> None:
        self.system, self.num = system, num
        self.frames: dict[str, tuple[Vec, Vec]] = {GROUND: (np.zeros(3), np.eye(3))}
        self.joint_at: dict[str, Vec] = {}  # joint -> where it is (world)
        self.axis_of: dict[str, Vec] = {}  # joint -> its world axis
        self.by_child = {j.child: j for j in system.joints}
        for body in system.bodies:
            self.frame(body.name, 0)

    def frame(self, name: str, depth: int) -> tuple[Vec, Vec]:
        if name in self.frames:
            return self.frames[name]
        joint = self.by_child.get(name)
        num = self.num
        if joint is None or depth > 64:
            body = self.system.body(name)
            pos = num.vec(body.position) if body.position is not None else np.zeros(3)
            rot = num.mat(body.rotation) if body.rotation is not None else np.eye(3)
            if body.rotation is None:  # intrinsic rotations, each about the axes turned so far
                for axis, angle in body.rotation_rates:
                    rot = rot @ _rotation(num.vec(axis), num(angle))
        else:
            p, r = self.frame(joint.parent, depth + 1)
            base = p + r @ num.vec(joint.origin_offset)
            fixed = num.mat(joint.rotation)
            rb = r @ fixed
            axis_w = rb @ num.vec(joint.axis)
            value = (num(joint.coordinate.q) if joint.coordinate else 0.0) + num(joint.offset)
            pos, rot = base, rb
            if joint.kind is JointKind.REVOLUTE:
                rot = _rotation(axis_w, value) @ fixed if joint.absolute else rb @ _rotation(num.vec(joint.axis), value)
            elif joint.kind is JointKind.PRISMATIC:
                pos = base + axis_w * value
            self.joint_at[joint.name] = base
            self.axis_of[joint.name] = axis_w / (np.linalg.norm(axis_w) or 1.0)
        self.frames[name] = (pos, rot)
        return pos, rot

    def point(self, body: str, local: Vec) -> Vec:
        p, r = self.frames[body]
        return p + r @ local


def _com_local(body: Body, num: _Numbers) -> Vec:
    total, acc = 0.0, np.zeros(3)
    for part in body.parts:
        m = num(part.mass) if part.mass is not None else 1.0
        total += m
        acc = acc + m * num.vec(part.at)
    return acc / total if total else np.zeros(3)


# ---------------------------------------------------------------------------------------------
# the builder
# ---------------------------------------------------------------------------------------------


class _Builder:
    def __init__(self, system: System, signs: Sequence[int] = _POSE_SIGNS[0]) -> None:
        self.s = system
        self.signs = signs  # of the default relative angles, in coordinate order
        self.cfg = system.figure or FigureConfig()
        self.prims: list[Primitive] = []
        self.requests: list[tuple[str, str, Point, Point]] = []  # names, tex, anchor, preferred direction
        self.obstacles: list[Box] = []
        self.remarks: list[str] = []
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
            else:
                table[p.symbol] = _default_size(p.name)
                if self._is_geometric(p.symbol):
                    self.sizes.append((p.name, table[p.symbol]))
        lengths = [v for sym, v in table.items() if self._is_geometric(sym)]
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
        self.at = at
        self.num = _Numbers(table, frozenset(c.q for c in s.coordinates))

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
        moved = [self.key_points(_Pose(self.s, self.num.with_(c.q, self.num(c.q) + 0.37))) for c in self.s.coordinates]
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

    def key_points(self, pose: _Pose) -> list[Vec]:
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

    # -- 5. primitives -------------------------------------------------------------------------
    def build(self) -> Drawing:
        self.numbers()
        self.pose = _Pose(self.s, self.num)
        self.choose_view()
        self.choose_scale()
        self.sliders: dict[str, tuple[Point, Point]] = {}  # body -> (centre, unit direction on the page)
        if not self.s.bodies:
            self.draw_energy_only()
        else:
            self.draw_joints()
            self.draw_links()
            self.draw_bodies()
            self.draw_explicit()
            self.draw_elements()
            self.draw_loads()
            self.draw_generalized_forces()
            self.draw_joint_coordinates()
            self.draw_lengths()
            if self.view == "oblique":
                self.draw_frames()
        self.draw_gravity_and_axes()
        labels = self.place_labels()
        box = None
        for prim in self.prims:
            b = _prim_box(prim)
            box = b if box is None else box.union(b)
        for lb in labels:
            box = lb.box if box is None else box.union(lb.box)
        box = box or Box(0, 0, 1, 1)
        margin = 0.15
        box = Box(
            round(box.x0 - margin, 3), round(box.y0 - margin, 3), round(box.x1 + margin, 3), round(box.y1 + margin, 3)
        )
        return Drawing(
            tuple(self.prims),
            tuple(labels),
            box,
            self.view,
            tuple(self.at),
            tuple(self.sizes),
            tuple(self.remarks),
        )

    def tex_of(self, expr: object, fallback: str) -> str:
        tex = expr_tex(sp.sympify(expr), self.latex_of)
        return tex if tex is not None else word_tex(fallback)

    def body_tex(self, body: Body) -> str:
        if body.is_simple and len(body.parts) == 1 and body.parts[0].mass is not None:
            tex = expr_tex(body.parts[0].mass, self.latex_of)
            if tex is not None:
                return tex
        return word_tex(body.name)

    def draw_joints(self) -> None:
        pose = self.pose
        for j in self.s.joints:
            at = self.P(pose.joint_at[j.name])
            if j.kind is JointKind.PRISMATIC:
                self.draw_prismatic(j)
                continue
            if j.kind is JointKind.REVOLUTE and j.parent == GROUND:
                # a ceiling for a body hanging below its pivot, a floor otherwise
                body = self.s.body(j.child)
                far = self.far_points(body, pose) + self.part_centres(body, pose)
                below = [self.P(p)[1] - at[1] for p in far]
                if self.view == "planar":
                    self.ground_support(at, hanging=bool(below) and sum(below) < -1e-6 * len(below))
                else:  # spatial: a base under the joint's axis, clear of the angle's arc
                    self.ground_support((at[0], at[1] - 0.55))

    def ground_support(self, at: Point, hanging: bool = False) -> None:
        """A fixed pivot's support: a triangle on a hatched floor, or hung from a ceiling."""
        x, y = at
        k = -1.0 if hanging else 1.0  # hanging: mirrored above the pin
        self.line([(x, y), (x - 0.22, y - 0.34 * k), (x + 0.22, y - 0.34 * k)], Stroke.OUTLINE, Fill.WHITE, closed=True)
        self.hatch((x - 0.36, y - 0.34 * k), (x + 0.36, y - 0.34 * k), (0.0, -k))
        self.obstacles.append(Box(x - 0.36, min(y, y - 0.5 * k), x + 0.36, max(y, y - 0.5 * k)))

    def draw_prismatic(self, j: Joint) -> None:
        pose = self.pose
        child_pos = pose.frames[j.child][0]
        base = pose.joint_at[j.name]
        axis = pose.axis_of[j.name]
        value = self.num(j.coordinate.q) if j.coordinate else 0.0
        a, b = self.P(base), self.P(child_pos)
        d = np.array(self.P(base + axis)) - np.array(a)
        if np.linalg.norm(d) < 1e-9:  # the axis points at the viewer
            d = np.array([0.0, 1.0])
        u = d / np.linalg.norm(d)
        ext = max(abs(value) * self.scale, 0.0)
        lo = np.array(a) - u * (0.9 + (ext if value < 0 else 0))
        hi = np.array(a) + u * ((ext if value > 0 else 0) + 0.9)
        nrm = np.array([-u[1], u[0]])
        if nrm[1] > 0 or (abs(nrm[1]) < 1e-9 and nrm[0] > 0):
            nrm = -nrm  # the rail below (or beside) the slider
        w, h = SLIDER
        if j.parent == GROUND:
            off = nrm * (h / 2 + 0.02)
            self.hatch(tuple(lo + off), tuple(hi + off), tuple(nrm))
        else:
            self.line([tuple(lo), tuple(hi)], Stroke.BAR)
        c = np.array(b)
        corners = [c + u * sx * w / 2 + nrm * sy * h / 2 for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        self.line([tuple(p) for p in corners], Stroke.OUTLINE, Fill.GRAY, closed=True)
        self.obstacles.append(_points_box([tuple(p) for p in corners]))
        self.sliders[j.child] = (b, (float(u[0]), float(u[1])))
        body = self.s.body(j.child)
        if all(p.shape is Shape.POINT for p in body.parts) and body.parts:
            self.label(f"body:{body.name}", self.body_tex(body), b, tuple(-nrm))  # type: ignore[arg-type]
        elif not body.parts:
            self.label(f"body:{body.name}", word_tex(body.name), b, tuple(-nrm))  # type: ignore[arg-type]

    def far_points(self, body: Body, pose: _Pose) -> list[Vec]:
        """The points a body's bars go to from its frame origin: its joints, its centre of mass."""
        out = []
        for j in self.s.joints:
            if j.parent == body.name:
                out.append(pose.joint_at[j.name])
        if body.is_simple or all(p.shape is Shape.POINT for p in body.parts):
            for part in body.parts:
                out.append(pose.point(body.name, self.num.vec(part.at)))
        return out

    def part_centres(self, body: Body, pose: _Pose) -> list[Vec]:
        """The centres of a body's shaped parts (not point masses: far_points has those)."""
        if body.is_simple or all(p.shape is Shape.POINT for p in body.parts):
            return []
        return [pose.point(body.name, self.num.vec(p.at)) for p in body.parts if p.shape is not Shape.POINT]

    def draw_links(self) -> None:
        pose = self.pose
        for j in self.s.joints:
            if j.kind is not JointKind.PRISMATIC and j.parent != GROUND:
                pass
        for b in self.s.bodies:
            if b.name not in pose.by_child:
                continue
            o = pose.frames[b.name][0]
            j = pose.by_child[b.name]
            start = pose.joint_at[j.name]
            if np.linalg.norm(o - start) > 1e-9 and j.kind is not JointKind.PRISMATIC:
                self.line([self.P(start), self.P(o)], Stroke.BAR)
            # one bar per direction, to the farthest point: a mass on the way to the next joint sits on it
            ends: list[Vec] = []  # a rod part is the link itself: no second bar along it
            for part in b.parts:
                if part.shape is Shape.ROD:
                    ends += [p - o for p in self.part_points(b, part, pose) if np.linalg.norm(p - o) > 1e-9]
            for far in sorted(self.far_points(b, pose), key=lambda p: -float(np.linalg.norm(p - o))):
                d = far - o
                if np.linalg.norm(d) * self.scale <= 1e-3:
                    continue
                if not any(np.linalg.norm(np.cross(d, e)) < 1e-9 * max(1.0, float(e @ e)) and d @ e > 0 for e in ends):
                    ends.append(d)
                    self.line([self.P(o), self.P(far)], Stroke.BAR)
            for centre in self.part_centres(b, pose):  # a stem to a shape set off the joint (a top)
                if np.linalg.norm(centre - o) * self.scale > 1e-3:
                    self.line([self.P(o), self.P(centre)], Stroke.OUTLINE)
        for j in self.s.joints:
            if j.kind is JointKind.REVOLUTE:
                self.circle(self.P(self.pose.joint_at[j.name]), PIN)

    def part_points(self, body: Body, part: object, pose: _Pose) -> list[Vec]:
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

    def draw_bodies(self) -> None:
        pose = self.pose
        for b in self.s.bodies:
            composite = len(b.parts) > 1
            for part in b.parts:
                at3 = pose.point(b.name, self.num.vec(part.at))
                at = self.P(at3)
                name = f"body:{b.name}/{part.name}" if composite else f"body:{b.name}"
                tex = word_tex(part.name) if composite else self.body_tex(b)
                if composite and part.mass is not None:
                    tex = expr_tex(part.mass, self.latex_of) or tex
                shape = part.shape
                if shape is Shape.POINT:
                    if (
                        b.name in self.sliders
                        and np.linalg.norm(np.array(at) - np.array(self.sliders[b.name][0])) < 1e-3
                    ):
                        continue  # the slider block is the mass
                    if b.is_simple and part.inertia is not None and any(v != 0 for v in part.inertia):
                        self.circle(at, MASS + 0.04, Fill.GRAY)
                    else:
                        self.circle(at, MASS, Fill.BLACK)
                    self.label(name, tex, at, self.outward(at))
                    continue
                pts = [self.P(p) for p in self.part_points(b, part, pose)]
                if shape is Shape.ROD:
                    self.line(pts, Stroke.BAR)
                    self.label(name, tex, ((pts[0][0] + pts[1][0]) / 2, (pts[0][1] + pts[1][1]) / 2), self.outward(at))
                    continue
                if shape in (Shape.SPHERE, Shape.SPHERICAL_SHELL):
                    r = float(np.linalg.norm(np.array(pts[0]) - np.array(at)))
                    r = max(r, MASS)
                    self.circle(at, r, Fill.GRAY)
                    self.label(name, tex, (at[0] + r * 0.7, at[1] + r * 0.7), (0.7, 0.7))
                    continue
                if shape is Shape.GENERAL:
                    self.circle(at, MASS + 0.05, Fill.GRAY)
                    self.label(name, tex, at, self.outward(at))
                    continue
                hull = _hull(pts)
                self.line(hull, Stroke.OUTLINE, Fill.WHITE, closed=True)
                if self.view == "oblique" and shape is Shape.BOX:
                    self.box_edges(pts)
                elif self.view == "oblique":
                    self.line(pts[37:], Stroke.OUTLINE)  # the far end's rim
                    self.line(pts[:37], Stroke.THIN)
                cx = sum(p[0] for p in hull) / len(hull)
                cy = sum(p[1] for p in hull) / len(hull)
                self.label(name, tex, (cx, cy), (0.0, 0.0))
                self.obstacles.append(_points_box([(cx - 0.05, cy - 0.05), (cx + 0.05, cy + 0.05)]))

    def box_edges(self, pts: list[Point]) -> None:
        # corners are ordered by (a, b, c) in {-1, 1}^3; an edge joins corners differing in one sign
        for i in range(8):
            for bit in (1, 2, 4):
                k = i ^ bit
                if k > i:
                    self.line([pts[i], pts[k]], Stroke.THIN)

    def outward(self, at: Point) -> Point:
        """A direction away from the skeleton's centre (for a label)."""
        pts = [self.P(p) for p in self.key_points(self.pose)]
        cx = sum(p[0] for p in pts) / len(pts)
        cy = sum(p[1] for p in pts) / len(pts)
        dx, dy = at[0] - cx, at[1] - cy
        n = math.hypot(dx, dy)
        return (dx / n, dy / n) if n > 1e-6 else (0.7, 0.7)

    # -- bodies placed by positions (no joints) ------------------------------------------------
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

    def draw_explicit(self) -> None:
        joint_coords = {j.coordinate.name for j in self.s.joints if j.coordinate is not None}
        self.explicit_marks: dict[str, tuple[Point, Point]] = {}  # coordinate -> (point, page direction)
        for c in self.s.coordinates:
            if c.name in joint_coords:
                continue
            body = self.carrier(c)
            if body is None:
                continue
            value = self.num(c.q)
            p_now = self.pose.frames[body.name][0]
            zero = _Pose(self.s, self.num.with_(c.q, 0.0))
            p_zero = zero.frames[body.name][0]
            tex = self.latex_of[c.q]
            if self.is_angle(c):
                h = 1e-4
                plus = _Pose(self.s, self.num.with_(c.q, value + h)).frames[body.name][0]
                minus = _Pose(self.s, self.num.with_(c.q, value - h)).frames[body.name][0]
                dp = (plus - minus) / (2 * h)
                n = self.plane_normal
                center = p_now + np.cross(n, dp)
                if np.linalg.norm(dp) < 1e-9:  # only turns: about its own origin, from its x axis
                    center = p_now
                    now_dir = self.pose.frames[body.name][1] @ np.array([1.0, 0, 0])
                    zero_dir = zero.frames[body.name][1] @ np.array([1.0, 0, 0])
                else:
                    now_dir, zero_dir = p_now - center, p_zero - center
                    self.line([self.P(center), self.P(p_now)], Stroke.BAR)
                    self.circle(self.P(center), PIN)
                    if np.linalg.norm(center) < 1e-9 or True:
                        self.ground_support(self.P(center))
                self.angle_mark(c, center, zero_dir, now_dir, n, tex)
                self.explicit_marks[c.name] = (self.P(center), (0.0, 1.0))
            else:
                a, b = self.P(p_zero), self.P(p_now)
                d = np.array(b) - np.array(a)
                if np.linalg.norm(d) < 1e-9:
                    continue
                u = d / np.linalg.norm(d)
                self.line([a, tuple(np.array(b) + u * 0.6)], Stroke.OUTLINE)
                self.circle(a, 0.05, Fill.BLACK, obstacle=False)
                self.dimension(a, b, tex, f"coordinate:{c.name}")
                self.explicit_marks[c.name] = (b, (float(u[0]), float(u[1])))
        for b in self.s.bodies:
            if b.name in self.pose.by_child or b.is_simple or not b.parts:
                continue

    def dimension(self, a: Point, b: Point, tex: str, names: str, offset: float = 0.42) -> None:
        """A dimension arrow from a to b, offset to one side, with extension lines and its label."""
        d = np.array(b) - np.array(a)
        n = float(np.linalg.norm(d))
        if n < 1e-6:
            return
        u = d / n
        nrm = np.array([-u[1], u[0]])
        if nrm[1] < -1e-9 or (abs(nrm[1]) < 1e-9 and nrm[0] < 0):
            nrm = -nrm
        off = nrm * offset
        pa, pb = np.array(a) + off, np.array(b) + off
        self.line([tuple(np.array(a) + nrm * 0.08), tuple(pa + nrm * 0.08)], Stroke.THIN)
        self.line([tuple(np.array(b) + nrm * 0.08), tuple(pb + nrm * 0.08)], Stroke.THIN)
        self.line([tuple(pa), tuple(pb)], Stroke.THIN)
        self.head(tuple(pa), tuple(pb))
        self.head(tuple(pb), tuple(pa))
        mid = (pa + pb) / 2
        side = nrm if offset >= 0 else -nrm
        self.label(names, tex, (float(mid[0]), float(mid[1])), (float(side[0]), float(side[1])))

    def angle_mark(
        self, c: Coordinate, center: Vec, zero_dir: Vec, now_dir: Vec, axis: Vec, tex: str, radius: float = ARC
    ) -> None:
        """The arc of an angle from its reference line (dashed) to the line it measures."""
        if self.view == "oblique":
            radius *= 1.5  # a circle seen obliquely is a flat ellipse: give it room
        axis = axis / (np.linalg.norm(axis) or 1.0)
        u = zero_dir - axis * float(zero_dir @ axis)
        w = now_dir - axis * float(now_dir @ axis)
        if np.linalg.norm(u) < 1e-12 or np.linalg.norm(w) < 1e-12:
            self.label(f"coordinate:{c.name}", tex, self.P(center), (0.7, 0.7))
            return
        u, w = u / np.linalg.norm(u), w / np.linalg.norm(w)
        angle = math.atan2(float(np.cross(u, w) @ axis), float(u @ w))
        ref_len = max(radius + 0.35, 0.9) / self.scale
        self.line([self.P(center), self.P(center + u * ref_len)], Stroke.DASHED)
        if abs(angle) < math.radians(2):
            self.label(f"coordinate:{c.name}", tex, self.P(center + u * ref_len), (0.7, 0.7))
            return
        pts = self.arc_points(center, u, axis, angle, radius)
        self.line(pts, Stroke.THIN)
        if len(pts) >= 2:
            self.head(pts[-3] if len(pts) > 3 else pts[-2], pts[-1])
        mid = self.arc_points(center, u, axis, angle / 2, radius + 0.3)
        anchor = mid[-1] if mid else self.P(center)
        pc = self.P(center)
        self.label(f"coordinate:{c.name}", tex, anchor, (anchor[0] - pc[0], anchor[1] - pc[1]))

    # -- springs and dampers -----------------------------------------------------------------
    def element_ends(self, el: object) -> tuple[Point, Point, bool] | None:
        """The page points a spring or damper joins, and whether its first end is a wall."""
        between = el.between  # type: ignore[attr-defined]
        if between is not None:
            ends = [self.P(self.pose.point(e.body, self.num.vec(e.at))) for e in between]
            ends = [self.slider_side(e.body, p, other) for e, p, other in zip(between, ends, ends[::-1], strict=True)]
            return ends[0], ends[1], between[0].body == GROUND
        ext = sp.sympify(el.extension)  # type: ignore[attr-defined]
        coords = [c for c in self.s.coordinates if c.q in ext.free_symbols]
        points: list[tuple[Point, Point]] = []
        grounded = False
        for c in coords:
            joint = next((j for j in self.s.joints if j.coordinate is not None and j.coordinate.name == c.name), None)
            if joint is not None and joint.kind is JointKind.PRISMATIC:
                now = self.P(self.pose.frames[joint.child][0])
                zero = self.P(_Pose(self.s, self.num.with_(c.q, 0.0)).frames[joint.child][0])
                points.append((zero, now))
                body = joint.child
                grounded = joint.parent == GROUND
            elif c.name in getattr(self, "explicit_marks", {}):
                body_ = self.carrier(c)
                if body_ is None:
                    continue
                now = self.P(self.pose.frames[body_.name][0])
                zero = self.P(_Pose(self.s, self.num.with_(c.q, 0.0)).frames[body_.name][0])
                points.append((zero, now))
                body = ""
            else:
                continue
            points[-1] = (points[-1][0], self.slider_side(body, points[-1][1], points[-1][0]))
        if len(points) == 1:
            zero, now = points[0]
            d = np.array(now) - np.array(zero)
            if np.linalg.norm(d) < 1e-9:
                return None
            if not grounded:  # along a moving line (a bead in a tube): from the coordinate's zero
                return zero, now, False
            u = d / np.linalg.norm(d)
            wall = tuple(np.array(zero) - u * 1.0)
            return wall, now, True  # type: ignore[return-value]
        if len(points) >= 2:
            a, b = points[0][1], points[1][1]
            return a, self.slider_side_point(b, a), False
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
        return (float(p[0] + u[0] * SLIDER[0] / 2), float(p[1] + u[1] * SLIDER[0] / 2))

    def draw_elements(self) -> None:
        count = 0
        for kind, elements in (("spring", self.s.springs), ("damper", self.s.dampers)):
            for el in elements:
                ends = self.element_ends(el)
                if ends is None:
                    self.remarks.append(f"{kind} '{el.name}' is not drawn: its ends could not be placed")
                    continue
                a, b, wall = ends
                d = np.array(b) - np.array(a)
                n = float(np.linalg.norm(d))
                if n < 1e-6:
                    continue
                u = d / n
                nrm = np.array([-u[1], u[0]])
                # a second element between the same places runs beside the first, not over it
                up = nrm if nrm[1] >= 0 else -nrm
                shift = up * 0.3 * count
                a2, b2 = np.array(a) + shift, np.array(b) + shift
                count += 1
                if wall:
                    w0, w1 = np.array(a) + nrm * 0.45, np.array(a) - nrm * 0.45
                    self.hatch(tuple(w1), tuple(w0), tuple(-u))
                coef = el.stiffness if kind == "spring" else el.coefficient
                tex = self.tex_of(coef, el.name)
                if kind == "spring":
                    pts = _zigzag(tuple(a2), tuple(b2))
                else:
                    pts = None
                    self.dashpot(tuple(a2), tuple(b2))
                if pts:
                    self.line(pts, Stroke.THIN)
                mid = (a2 + b2) / 2
                side = nrm if nrm[1] >= 0 else -nrm
                self.label(f"{kind}:{el.name}", tex, (float(mid[0]), float(mid[1])), (float(side[0]), float(side[1])))

    def dashpot(self, a: Point, b: Point) -> None:
        pa, pb = np.array(a), np.array(b)
        d = pb - pa
        n = float(np.linalg.norm(d))
        u = d / n
        nrm = np.array([-u[1], u[0]])
        m = pa + u * n * 0.45
        cyl = 0.18
        self.line([a, tuple(m)], Stroke.THIN)
        self.line(
            [
                tuple(m + nrm * cyl + u * 0.4),
                tuple(m + nrm * cyl),
                tuple(m - nrm * cyl),
                tuple(m - nrm * cyl + u * 0.4),
            ],
            Stroke.THIN,
        )
        piston = m + u * 0.25
        self.line([tuple(piston + nrm * cyl * 0.7), tuple(piston - nrm * cyl * 0.7)], Stroke.OUTLINE)
        self.line([tuple(piston), b], Stroke.THIN)

    # -- loads ---------------------------------------------------------------------------------
    def page_dir(self, at: Vec, world_dir: Vec) -> Point | None:
        a = np.array(self.P(at))
        b = np.array(self.P(at + world_dir / self.scale))
        d = b - a
        n = float(np.linalg.norm(d))
        return (float(d[0] / n), float(d[1] / n)) if n > 1e-9 else None

    def draw_loads(self) -> None:
        for load in self.s.loads:
            body = load.body
            at3 = self.pose.point(body, self.num.vec(load.at))
            at = self.P(at3)
            rot = self.pose.frames[body][1]
            names = f"load:{load.name}"
            if load.force is not None and any(v != 0 for v in load.force):
                f = self.num.vec(load.force)
                if load.in_body_frame:
                    f = rot @ f
                nz = [v for v in load.force if v != 0]
                tex = self.tex_of(nz[0], load.name) if len(nz) == 1 else word_tex(load.name)
                d = self.page_dir(at3, f / (np.linalg.norm(f) or 1.0))
                if d is None:
                    self.label(names, tex, at, (0.7, 0.7))
                    continue
                if body in self.sliders:  # from the block's face, so it does not cross a spring
                    tail = np.array(self.slider_side_point(at, (at[0] + d[0], at[1] + d[1])))
                    tip = tail + np.array(d) * 1.1
                    self.arrow(tuple(tail), tuple(tip))
                    self.label(names, tex, tuple(tip), d)
                    continue
                tip = np.array(at)
                tail = tip - np.array(d) * 1.1
                self.arrow(tuple(tail), tuple(tip))
                self.label(names, tex, tuple(tail), (-d[0], -d[1]))  # type: ignore[arg-type]
            if load.torque is not None and any(v != 0 for v in load.torque):
                t = self.num.vec(load.torque)
                if load.in_body_frame:
                    t = rot @ t
                nz = [v for v in load.torque if v != 0]
                tex = self.tex_of(nz[0], load.name) if len(nz) == 1 else word_tex(load.name)
                self.torque(names, tex, at3, t)

    def torque(self, names: str, tex: str, at3: Vec, t: Vec, radius: float = 0.36) -> None:
        at = self.P(at3)
        n = float(np.linalg.norm(t))
        if n < 1e-12:
            return
        axis = t / n
        if self.view == "planar" and abs(abs(float(axis @ self.plane_normal)) - 1) < 1e-6:
            sign = 1.0 if float(axis @ self.plane_normal) > 0 else -1.0
            start = math.radians(200)
            sweep = math.radians(250) * sign
            steps = 30
            pts = [
                (
                    at[0] + radius * math.cos(start + sweep * i / steps),
                    at[1] + radius * math.sin(start + sweep * i / steps),
                )
                for i in range(steps + 1)
            ]
            self.line(pts, Stroke.ARROW)
            self.head(pts[-3], pts[-1])
            a = start - math.radians(8) * sign
            self.label(
                names,
                tex,
                (at[0] + (radius + 0.25) * math.cos(a), at[1] + (radius + 0.25) * math.sin(a)),
                (math.cos(a), math.sin(a)),
            )
        else:  # a moment vector: a double-headed arrow along its axis
            d = self.page_dir(at3, axis)
            if d is None:
                d = (0.7, 0.7)
            tip = (at[0] + d[0] * 1.0, at[1] + d[1] * 1.0)
            base = (at[0] + d[0] * 0.25, at[1] + d[1] * 0.25)
            self.arrow(base, tip)
            self.head(base, (tip[0] - d[0] * 0.18, tip[1] - d[1] * 0.18))
            self.label(names, tex, tip, d)

    def draw_generalized_forces(self) -> None:
        joint_of = {j.coordinate.name: j for j in self.s.joints if j.coordinate is not None}
        if self.view == "oblique" and len(self.s.coordinates) > 3:
            return  # a spatial arm's joint torques would hide its frames; the solution names them
        for name, expr in self.s.generalized_forces:
            tex = self.tex_of(expr, name)
            names = f"generalized_force:{name}"
            c = next(c for c in self.s.coordinates if c.name == name)
            joint = joint_of.get(name)
            if joint is not None:
                at3 = self.pose.joint_at[joint.name]
                if joint.kind is JointKind.REVOLUTE:
                    self.torque(names, tex, at3, self.pose.axis_of[joint.name], radius=0.34)
                    continue
                child = self.P(self.pose.frames[joint.child][0])
                d = self.page_dir(at3, self.pose.axis_of[joint.name]) or (1.0, 0.0)
                tip = np.array(self.slider_side_point(child, (child[0] - d[0], child[1] - d[1])))
                self.arrow(tuple(tip - np.array(d) * 1.0), tuple(tip))
                self.label(names, tex, tuple(tip - np.array(d) * 1.0), (-d[0], -d[1]))  # type: ignore[arg-type]
                continue
            mark = getattr(self, "explicit_marks", {}).get(name)
            body = self.carrier(c)
            if mark is None or body is None:
                self.label(names, tex, (0.0, 0.0), (0.7, -0.7))
                continue
            point, d = mark
            if self.is_angle(c):
                center = np.linalg.pinv(self.matrix * self.scale) @ np.array(point)
                self.torque(names, tex, center, self.plane_normal, radius=0.34)
            else:
                tip = np.array(point) + np.array(d) * (MASS + 0.05)
                self.arrow(tuple(tip), tuple(tip + np.array(d) * 1.0))
                self.label(names, tex, tuple(tip + np.array(d) * 1.0), d)

    # -- coordinates of joints ---------------------------------------------------------------------
    def draw_joint_coordinates(self) -> None:
        for j in self.s.joints:
            c = j.coordinate
            if c is None:
                continue
            tex = self.latex_of[c.q]
            zero = _Pose(self.s, self.num.with_(c.q, 0.0))
            if j.kind is JointKind.PRISMATIC:
                a = self.P(zero.frames[j.child][0])
                b = self.P(self.pose.frames[j.child][0])
                if math.dist(a, b) < 1e-3:
                    self.label(f"coordinate:{c.name}", tex, b, (0.0, 1.0))
                    continue
                self.circle(a, 0.04, Fill.BLACK, obstacle=False)
                self.dimension(a, b, tex, f"coordinate:{c.name}", offset=SLIDER[1] / 2 + 0.35)
                continue
            center = self.pose.joint_at[j.name]
            axis = self.pose.axis_of[j.name]
            body = self.s.body(j.child)
            now_pts = self.far_points(body, self.pose) + self.part_centres(body, self.pose)
            zero_pts = self.far_points(body, zero) + self.part_centres(body, zero)
            child_o = self.pose.frames[j.child][0]
            if np.linalg.norm(child_o - center) > 1e-9:
                now_pts.insert(0, child_o)
                zero_pts.insert(0, zero.frames[j.child][0])
            good = [
                (p - center, q - center)
                for p, q in zip(now_pts, zero_pts, strict=True)
                if np.linalg.norm(np.cross(p - center, axis)) > 1e-9
            ]
            if good:
                now_dir, zero_dir = good[0]
            else:  # nothing off the axis: the child's x axis turns with it
                now_dir = self.pose.frames[j.child][1] @ np.array([1.0, 0, 0])
                zero_dir = zero.frames[j.child][1] @ np.array([1.0, 0, 0])
                if np.linalg.norm(np.cross(now_dir, axis)) < 1e-9:
                    now_dir = self.pose.frames[j.child][1] @ np.array([0, 1.0, 0])
                    zero_dir = zero.frames[j.child][1] @ np.array([0, 1.0, 0])
            self.angle_mark(c, center, zero_dir, now_dir, axis, tex)

    def draw_lengths(self) -> None:
        """Dimension lines for bars whose length is one named parameter (l, a1): the spec's names."""
        seen: set[str] = set()
        segs: list[tuple[Vec, Vec, sp.Expr]] = []
        for j in self.s.joints:
            if j.parent != GROUND:
                segs.append((self.pose.frames[j.parent][0], self.pose.joint_at[j.name], j.origin_offset))
        for b in self.s.bodies:
            if b.name in self.pose.by_child and (b.is_simple or all(p.shape is Shape.POINT for p in b.parts)):
                for part in b.parts:
                    segs.append((self.pose.frames[b.name][0], self.pose.point(b.name, self.num.vec(part.at)), part.at))
            for part in b.parts:
                if part.shape is Shape.ROD:
                    ends = self.part_points(b, part, self.pose)
                    length = dict(part.dimensions).get("length")
                    segs.append((ends[0], ends[1], sp.Matrix([length, 0, 0])))
        for a, b, local in segs:
            nz = [v for v in sp.Matrix(local) if v != 0]
            if len(nz) != 1:
                continue
            v = nz[0]
            v = -v if isinstance(v, sp.Mul) and v.args[0] == -1 else v
            if not isinstance(v, sp.Symbol) or v not in self.latex_of or v.name in seen:
                continue
            seen.add(v.name)
            pa, pb = self.P(a), self.P(b)
            if math.dist(pa, pb) < 0.3:
                continue
            if self.view == "planar":
                self.dimension(pa, pb, self.latex_of[v], f"length:{v.name}", offset=-0.38)
            else:
                mid = ((pa[0] + pb[0]) / 2, (pa[1] + pb[1]) / 2)
                d = (pb[0] - pa[0], pb[1] - pa[1])
                self.label(f"length:{v.name}", self.latex_of[v], mid, (-d[1], d[0]))

    def draw_frames(self) -> None:
        """Oblique view: each joint's axis (dash-dot) and each moving body's frame (x and z arrows)."""
        for j in self.s.joints:
            if j.kind is JointKind.FIXED:
                continue
            at = self.pose.joint_at[j.name]
            axis = self.pose.axis_of[j.name]
            self.line([self.P(at - axis * 0.8 / self.scale), self.P(at + axis * 1.1 / self.scale)], Stroke.AXIS)
        k = 0
        for b in self.s.bodies:
            j = self.pose.by_child.get(b.name)
            if j is None or j.kind is JointKind.FIXED:
                continue
            k += 1
            o, r = self.pose.frames[b.name]
            # the DH frames: x and z of each; a long arm names only the z axes, to stay legible
            for col, letter in ((0, "x"), (2, "z")):
                d = self.page_dir(o, r[:, col])
                if d is None:
                    continue
                start = self.P(o)
                end = (start[0] + d[0] * 0.7, start[1] + d[1] * 0.7)
                self.arrow(start, end, Stroke.THIN)
                if letter == "z" or len(self.s.joints) <= 3:
                    self.label(f"frame:{b.name}:{letter}", f"{letter}_{{{k}}}", end, d)

    # -- gravity, world axes, energy-only specs --------------------------------------------------
    def draw_gravity_and_axes(self) -> None:
        pts = [p for prim in self.prims for p in (prim.points if isinstance(prim, Polyline) else (prim.center,))]
        box = _points_box(pts) if pts else Box(0, 0, TARGET_SIZE, TARGET_SIZE)
        if self.s.gravity is not None:
            gv = self.num.vec(self.s.gravity)
            d = self.page_dir(np.zeros(3), gv / (np.linalg.norm(gv) or 1.0)) if np.linalg.norm(gv) else None
            if d is not None:
                top = (box.x1 + 0.7, box.y1 - 0.1)
                tail = top if d[1] < 0 else (top[0], top[1] - 1.0)
                tip = (tail[0] + d[0], tail[1] + d[1])
                self.arrow(tail, tip)
                nz = [v for v in self.s.gravity if v != 0]
                # the arrow shows the direction, so the label is the magnitude (g, not -g)
                tex = self.tex_of(-nz[0] if _is_negative(nz[0]) else nz[0], "g") if len(nz) == 1 else "g"
                if tex == word_tex("g"):
                    tex = "g"
                self.label("gravity", tex, ((tail[0] + tip[0]) / 2, (tail[1] + tip[1]) / 2), (1.0, 0.0))
        if not self.s.bodies:
            return  # T and U given: there is no geometry to put axes on
        origin = (box.x0 - 0.9, box.y0 - 0.3)
        axes = [(0, "x"), (1, "y"), (2, "z")]
        if self.view == "planar":
            axes = [(k, n) for k, n in axes if k in self.screen]
        for k, letter in axes:
            d = self.page_dir(np.zeros(3), np.eye(3)[k])
            if d is None:
                continue
            end = (origin[0] + d[0] * 0.8, origin[1] + d[1] * 0.8)
            self.arrow(origin, end)
            self.label(f"axis:{letter}", letter, end, d)

    def draw_energy_only(self) -> None:
        """No bodies (T and U given): a box for the system, an arrow per coordinate with its name."""
        w = 1.2 + 1.0 * len(self.s.coordinates)
        self.line([(0, 0), (w, 0), (w, 1.2), (0, 1.2)], Stroke.OUTLINE, Fill.WHITE, closed=True)
        self.label("system", "T(q,\\dot{q})", (w / 2, 0.6), (0.0, 0.0))
        for i, c in enumerate(self.s.coordinates):
            x = 0.9 + i * 1.0
            self.arrow((x, 1.2), (x, 2.0))
            self.label(f"coordinate:{c.name}", self.latex_of[c.q], (x, 2.0), (0.0, 1.0))
        self.screen = (0, 1)

    # -- 6. labels ----------------------------------------------------------------------------
    def place_labels(self) -> list[Label]:
        """Each label next to its anchor, on the side it asks for when that place is free; otherwise
        the nearest place (eight directions, four distances) that overlaps no placed label, then the
        fewest pins and masses, then the fewest lines. A label moved off another label is remarked on."""
        placed: list[Label] = []
        ink = self.ink_points()
        boxes = np.zeros((0, 4))  # the placed labels' boxes, widened by a small gap
        obstacles = np.array([[b.x0, b.y0, b.x1, b.y1] for b in self.obstacles]).reshape(-1, 4)
        gap = 0.04
        for names, tex, anchor, direction in self.requests:
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
                    clash = _overlaps(box, boxes, gap)
                    if i == 0 and turn == 0:
                        first_clash = clash
                    cost = 1000 * clash + 10 * _overlaps(box, obstacles, 0.0)
                    cost += 0.05 * _inside(box, ink) + 0.02 * (i + abs(turn))
                    if best is None or cost < best[0] - 1e-12:
                        best = (cost, cand)
                if best is not None and best[0] < 0.3:
                    break
            assert best is not None
            final = best[1].box
            final_clash = _overlaps(final, boxes, gap)
            what = names.replace(":", " ").replace("/", " ")
            if first_clash > 0 and final_clash == 0:
                self.remarks.append(f"the label of {what} was moved off another label")
            elif final_clash > 0:
                self.remarks.append(f"the label of {what} still overlaps another label; no free place was found")
            placed.append(best[1])
            boxes = np.vstack([boxes, [final.x0, final.y0, final.x1, final.y1]])
        return placed

    def ink_points(self) -> np.ndarray:
        """Points every 0.08 cm along every line drawn, to keep labels off the lines."""
        pts: list[tuple[float, float]] = []
        for prim in self.prims:
            if isinstance(prim, Circle):
                pts.append(prim.center)
                continue
            ring = (*prim.points, prim.points[0]) if prim.closed else prim.points
            for (x0, y0), (x1, y1) in itertools.pairwise(ring):
                k = max(1, int(math.hypot(x1 - x0, y1 - y0) / 0.08))
                pts += [(x0 + (x1 - x0) * t / k, y0 + (y1 - y0) * t / k) for t in range(k)]
        return np.array(pts) if pts else np.zeros((0, 2))


def _overlaps(box: Box, boxes: np.ndarray, gap: float) -> float:
    """The total area by which ``box`` overlaps the rows (x0, y0, x1, y1) of ``boxes``."""
    if not len(boxes):
        return 0.0
    w = np.minimum(box.x1, boxes[:, 2]) - np.maximum(box.x0, boxes[:, 0]) + gap
    h = np.minimum(box.y1, boxes[:, 3]) - np.maximum(box.y0, boxes[:, 1]) + gap
    return float(np.sum(np.where((w > 1e-9) & (h > 1e-9), w * h, 0.0)))


def _inside(box: Box, pts: np.ndarray) -> int:
    if not len(pts):
        return 0
    x, y = pts[:, 0], pts[:, 1]
    return int(np.count_nonzero((x > box.x0) & (x < box.x1) & (y > box.y0) & (y < box.y1)))


def _is_negative(expr: sp.Expr) -> bool:
    return bool(sp.sympify(expr).could_extract_minus_sign())


def _overlap(a: Box, b: Box, gap: float = 0.0) -> float:
    w = min(a.x1, b.x1) - max(a.x0, b.x0) + gap
    h = min(a.y1, b.y1) - max(a.y0, b.y0) + gap
    return w * h if w > 1e-9 and h > 1e-9 else 0.0


def _points_box(pts: Iterable[Point]) -> Box:
    xs, ys = zip(*pts, strict=True)
    return Box(min(xs), min(ys), max(xs), max(ys))


def _prim_box(prim: Primitive) -> Box:
    if isinstance(prim, Circle):
        (x, y), r = prim.center, prim.radius
        return Box(x - r, y - r, x + r, y + r)
    return _points_box(prim.points)


def _hull(pts: list[Point]) -> list[Point]:
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


def _zigzag(a: Point, b: Point, width: float = 0.16) -> list[Point]:
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
