"""The drawing of what orients the figure: joint axes and body frames (oblique view), the gravity
arrow, the world axes, and the stand-in box of a spec given by its energies alone."""

from __future__ import annotations

import numpy as np
import sympy as sp

from tutgen.figure.canvas import TARGET_SIZE
from tutgen.figure.elements import ElementDrawing
from tutgen.figure.geometry import points_box
from tutgen.figure.pose import Vec
from tutgen.figure.scene import Box, Fill, Polyline, Stroke
from tutgen.figure.texlabel import word_tex
from tutgen.model.system import JointKind


class AxesDrawing(ElementDrawing):
    """Draws the frames, gravity and world axes of a system."""

    def draw_frames(self) -> None:
        """Oblique view: each joint's axis (dash-dot) and each moving body's frame (x and z arrows).

        An arm of more than three joints stays legible so: where a body's z axis lies on its joint's
        axis (a Denavit–Hartenberg frame), that axis line is the z axis — it gets the arrow head and
        the label at its end, and no second arrow is drawn along it; the x axes are short and
        unlabelled."""
        long_arm = len(self.s.joints) > 3
        axis_end: dict[str, tuple[Vec, Vec, float]] = {}  # child -> its joint point, axis, line end
        for j in self.s.joints:
            if j.kind is JointKind.FIXED:
                continue
            at = self.pose.joint_at[j.name]
            axis = self.pose.axis_of[j.name]
            # a wrist joint's axis line reaches past its arc, set along it (Canvas.axis_shift)
            shift = self.axis_shift(j.name)
            lo, hi = min(-0.8, shift - 0.6), max(1.1, shift + 0.6)
            self.line([self.P(at + axis * lo / self.scale), self.P(at + axis * hi / self.scale)], Stroke.AXIS)
            axis_end[j.child] = (at, axis, hi)
        k = 0
        for b in self.s.bodies:
            j = self.pose.by_child.get(b.name)
            if j is None or j.kind is JointKind.FIXED:
                continue
            k += 1
            o, r = self.pose.frames[b.name]
            for col, letter in ((0, "x"), (2, "z")):
                d = self.page_dir(o, r[:, col])
                if d is None:
                    continue
                names, tex = f"frame:{b.name}:{letter}", f"{letter}_{{{k}}}"
                if long_arm and letter == "z" and b.name in axis_end and _on_axis(o, r[:, col], *axis_end[b.name][:2]):
                    at, axis, hi = axis_end[b.name]
                    tip = at + axis * hi / self.scale
                    self.head(self.P(at + axis * (hi - 0.2) / self.scale), self.P(tip))
                    self.label(names, tex, self.P(tip), self.page_dir(tip, axis) or d)
                    continue
                start = self.P(o)
                length = 0.45 if long_arm else 0.7
                end = (start[0] + d[0] * length, start[1] + d[1] * length)
                self.arrow(start, end, Stroke.THIN)
                if letter == "z" or not long_arm:
                    self.label(names, tex, end, d)

    # -- gravity, world axes, energy-only specs --------------------------------------------------
    def draw_gravity_and_axes(self) -> None:
        pts = [p for prim in self.prims for p in (prim.points if isinstance(prim, Polyline) else (prim.center,))]
        box = points_box(pts) if pts else Box(0, 0, TARGET_SIZE, TARGET_SIZE)
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
        self.axes_at((box.x0 - 1.25, box.y0 - 0.5), 0.8)  # clear of the first joint's labels (a torque's τ₁)

    def axes_at(self, origin: tuple[float, float], length: float) -> None:
        """The world axes x, y (and z when spatial) as arrows of ``length`` cm from ``origin`` on the page."""
        axes = [(0, "x"), (1, "y"), (2, "z")]
        if self.view == "planar":
            axes = [(k, n) for k, n in axes if k in self.screen]
        for k, letter in axes:
            d = self.page_dir(np.zeros(3), np.eye(3)[k])
            if d is None:
                continue
            end = (origin[0] + d[0] * length, origin[1] + d[1] * length)
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


def _is_negative(expr: sp.Expr) -> bool:
    return bool(sp.sympify(expr).could_extract_minus_sign())


def _on_axis(origin: Vec, direction: Vec, at: Vec, axis: Vec) -> bool:
    """Whether the line through ``origin`` along ``direction`` is the joint axis through ``at``."""
    if np.linalg.norm(np.cross(direction, axis)) > 1e-6 * (np.linalg.norm(direction) or 1.0):
        return False
    off = origin - at
    return bool(np.linalg.norm(np.cross(off, axis)) < 1e-6 * max(1.0, float(np.linalg.norm(off))))
