"""The drawing of coordinates and lengths: an angle's arc from its dashed reference line, a
displacement's dimension arrow, the marks of coordinates that place a body without a joint, and the
dimension lines of bars whose length is one named parameter."""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from tutgen.figure.bodies import BodyDrawing
from tutgen.figure.canvas import ARC, PIN, SLIDER
from tutgen.figure.pose import Pose, Vec
from tutgen.figure.scene import Fill, Point, Stroke
from tutgen.model.system import GROUND, Coordinate, JointKind, Shape


class CoordinateDrawing(BodyDrawing):
    """Draws the coordinates and named lengths of a system."""

    # -- coordinates of bodies placed by positions ---------------------------------------------
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
            zero = Pose(self.s, self.num.with_(c.q, 0.0))
            p_zero = zero.frames[body.name][0]
            tex = self.latex_of[c.q]
            if self.is_angle(c):
                h = 1e-4
                plus = Pose(self.s, self.num.with_(c.q, value + h)).frames[body.name][0]
                minus = Pose(self.s, self.num.with_(c.q, value - h)).frames[body.name][0]
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

    # -- coordinates of joints ---------------------------------------------------------------------
    def draw_joint_coordinates(self) -> None:
        for j in self.s.joints:
            c = j.coordinate
            if c is None:
                continue
            tex = self.latex_of[c.q]
            zero = Pose(self.s, self.num.with_(c.q, 0.0))
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
            # joints at one place (a wrist): each next arc set along its own axis (axis_shift), or,
            # where that does not show (a planar view), of a growing radius, so they do not lie on
            # each other
            shift = self.axis_shift(j.name)
            center = center + axis / (np.linalg.norm(axis) or 1.0) * (shift / self.scale)
            here = self.P(center)
            shared = sum(1 for p in getattr(self, "_arc_centres", []) if math.dist(p, here) < 0.25)
            self._arc_centres = [*getattr(self, "_arc_centres", []), here]
            self.angle_mark(c, center, zero_dir, now_dir, axis, tex, radius=ARC * (1 + 0.45 * shared))

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
