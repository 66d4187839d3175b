"""The drawing of springs, dampers and loads: where a spring or damper attaches, its zig-zag or
dashpot, force arrows, torques (a curled arrow in the plane, a double-headed one in space) and the
generalized forces of coordinates."""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from tutgen.figure.canvas import MASS
from tutgen.figure.coordinates import CoordinateDrawing
from tutgen.figure.geometry import zigzag
from tutgen.figure.pose import Pose, Vec
from tutgen.figure.scene import Point, Stroke
from tutgen.figure.texlabel import word_tex
from tutgen.model.system import GROUND, JointKind


class ElementDrawing(CoordinateDrawing):
    """Draws the springs, dampers, loads and generalized forces of a system."""

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
                zero = self.P(Pose(self.s, self.num.with_(c.q, 0.0)).frames[joint.child][0])
                points.append((zero, now))
                body = joint.child
                grounded = joint.parent == GROUND
            elif c.name in getattr(self, "explicit_marks", {}):
                body_ = self.carrier(c)
                if body_ is None:
                    continue
                now = self.P(self.pose.frames[body_.name][0])
                zero = self.P(Pose(self.s, self.num.with_(c.q, 0.0)).frames[body_.name][0])
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
                    pts = zigzag(tuple(a2), tuple(b2))
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

    def torque(self, names: str, tex: str, at3: Vec, t: Vec, radius: float = 0.36, start_deg: float = 200) -> None:
        at = self.P(at3)
        n = float(np.linalg.norm(t))
        if n < 1e-12:
            return
        axis = t / n
        if self.view == "planar" and abs(abs(float(axis @ self.plane_normal)) - 1) < 1e-6:
            sign = 1.0 if float(axis @ self.plane_normal) > 0 else -1.0
            start = math.radians(start_deg)  # where the arc starts and its label stands
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
