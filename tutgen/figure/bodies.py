"""The drawing of bodies and joints: ground supports, rails and slider blocks, the links' bars and
pins, and each part by its shape (point masses, rods, spheres, boxes, cylinders)."""

from __future__ import annotations

import math

import numpy as np

from tutgen.figure.canvas import MASS, PIN, Canvas
from tutgen.figure.geometry import convex_hull, points_box
from tutgen.figure.pose import Vec
from tutgen.figure.scene import Box, Fill, Point, Stroke
from tutgen.figure.texlabel import expr_tex, label_size, word_tex
from tutgen.model.system import GROUND, Body, Joint, JointKind, Shape


class BodyDrawing(Canvas):
    """Draws the joints and bodies of a system."""

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

    def draw_prismatic(self, j: Joint, rail: bool = True) -> None:
        """A slider block on its rail (``rail`` False: the block alone, as a free body is drawn)."""
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
        w, h = self.slider
        if not rail:
            pass
        elif j.parent == GROUND:
            off = nrm * (h / 2 + 0.02)
            self.hatch(tuple(lo + off), tuple(hi + off), tuple(nrm))
        else:
            self.line([tuple(lo), tuple(hi)], Stroke.BAR)
        c = np.array(b)
        corners = [c + u * sx * w / 2 + nrm * sy * h / 2 for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        self.line([tuple(p) for p in corners], Stroke.OUTLINE, Fill.GRAY, closed=True)
        self.obstacles.append(points_box([tuple(p) for p in corners]))
        self.sliders[j.child] = (b, (float(u[0]), float(u[1])))
        body = self.s.body(j.child)
        if all(p.shape is Shape.POINT for p in body.parts) and body.parts:
            self.label(f"body:{body.name}", self.body_tex(body), b, tuple(-nrm))  # type: ignore[arg-type]
        elif not body.parts:
            self.label(f"body:{body.name}", word_tex(body.name), b, tuple(-nrm))  # type: ignore[arg-type]

    def draw_links(self) -> None:
        pose = self.pose
        for b in self.s.bodies:
            if b.name not in pose.by_child or (self.only is not None and b.name != self.only):
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
            if j.kind is JointKind.REVOLUTE and (self.only is None or self.only in (j.parent, j.child)):
                self.circle(self.P(self.pose.joint_at[j.name]), PIN)
        for lj in self.s.loop_joints:  # the pin that closes a loop, where its two bodies meet
            if self.only is None or self.only in (lj.parent, lj.child):
                self.circle(self.P(self.pose.point(lj.parent, self.num.vec(lj.parent_at))), PIN)

    def draw_bodies(self) -> None:
        pose = self.pose
        for b, part in self.back_to_front([b for b in self.s.bodies if self.only in (None, b.name)]):
            composite = len(b.parts) > 1
            at3 = pose.point(b.name, self.num.vec(part.at))
            at = self.P(at3)
            name = f"body:{b.name}/{part.name}" if composite else f"body:{b.name}"
            tex = word_tex(part.name) if composite else self.body_tex(b)
            if composite and part.mass is not None:
                tex = expr_tex(part.mass, self.latex_of) or tex
            shape = part.shape
            if shape is Shape.POINT:
                if b.name in self.sliders and np.linalg.norm(np.array(at) - np.array(self.sliders[b.name][0])) < 1e-3:
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
            hull = convex_hull(pts)
            self.line(hull, Stroke.OUTLINE, Fill.WHITE, closed=True)
            if self.view == "oblique" and shape is Shape.BOX:
                self.box_edges(pts, pose.frames[b.name][1] @ self.num.mat(part.rotation))
            elif self.view == "oblique":
                self.cylinder_rims(b, part, pts)
            cx = sum(p[0] for p in hull) / len(hull)
            cy = sum(p[1] for p in hull) / len(hull)
            rim = self.beside_pin(hull, (cx, cy), tex)
            if rim is not None:  # a small disc on its pin (the four-bar's flywheel): the name outside it
                self.label(name, tex, *rim)
                continue
            # the name inside the outline, where a textbook writes it; it is placed before the labels
            # drawn later (loads, coordinates), which then keep off it
            self.label(name, tex, (cx, cy), (0.0, 0.0))

    def beside_pin(self, hull: list[Point], centre: Point, tex: str) -> tuple[Point, Point] | None:
        """Where a disc's name goes in the planar view when the disc turns on a pin at its centre and the
        name has no room beside the pin (more than 45 % of the disc's smaller extent; the four-bar's
        flywheel, whose name sat across its rim): an anchor on the rim, above the disc on the side away
        from the skeleton, and that direction. ``None``: the name fits inside, or the shape is not such a
        disc."""
        if self.view == "oblique":
            return None
        box = points_box(hull)
        room = min(box.x1 - box.x0, box.y1 - box.y0)
        w, h = label_size(tex)
        pins = [self.P(p) for p in self.pose.joint_at.values()]
        if max(w, h) <= 0.45 * room or not any(math.dist(p, centre) < 0.1 * room for p in pins):
            return None
        ux, _ = self.outward(centre)
        dx, dy = (-math.sqrt(0.5) if ux < 0 else math.sqrt(0.5)), math.sqrt(0.5)
        reach = max(math.dist(p, centre) for p in hull)
        return (centre[0] + dx * reach, centre[1] + dy * reach), (dx, dy)

    def back_to_front(self, bodies: list[Body]) -> list[tuple[Body, object]]:
        """The bodies' parts in drawing order: in the oblique view the farthest from the viewer first
        (by its centre's depth), so that each part's white-filled outline hides what lies behind it, as
        a line drawing does (p01's cylinder in front of the block's face, the point mass in front of
        both; the tilting plate's rotor behind its plate); spec order among parts at one depth and in
        the planar view."""
        pairs = [(b, part) for b in bodies for part in b.parts]
        if self.view != "oblique" or len(pairs) < 2:
            return pairs
        w = self.toward_viewer()
        depth = [float(self.pose.point(b.name, self.num.vec(part.at)) @ w) for b, part in pairs]
        order = sorted(range(len(pairs)), key=lambda i: (round(depth[i], 9), i))
        return [pairs[i] for i in order]

    def toward_viewer(self) -> Vec:
        """The world direction the oblique view looks along, toward the viewer: the projection sends
        every point of a line along it to one page point (the null space of the projection), and it
        is taken on the side that keeps the page's right, up and this a right-handed set."""
        w = np.cross(self.matrix[0], self.matrix[1])
        return w / (np.linalg.norm(w) or 1.0)

    def box_edges(self, pts: list[Point], rot: Vec) -> None:
        """A box's twelve edges: solid where a face next to the edge faces the viewer, dashed (hidden)
        where both faces next to it face away."""
        # corners are ordered by (a, b, c) in {-1, 1}^3, bits 4, 2, 1; an edge joins corners differing in one bit
        w = self.toward_viewer()
        bits = (4, 2, 1)
        for i in range(8):
            for k, bit in enumerate(bits):
                j = i ^ bit
                if j < i:
                    continue
                faces = [((1 if i & bits[m] else -1) * rot[:, m]) for m in range(3) if m != k]
                visible = any(float(n @ w) > 1e-9 for n in faces)
                self.line([pts[i], pts[j]], Stroke.THIN if visible else Stroke.DASHED)

    def cylinder_rims(self, body: object, part: object, pts: list[Point]) -> None:
        """A cylinder's two rims (37 points each, the first end's then the second's): the rim of the end
        facing the viewer solid, the other's far half dashed (hidden behind the cylinder)."""
        rot = self.pose.frames[body.name][1]  # type: ignore[attr-defined]
        axis = rot @ self.num.vec(part.axis) if part.axis is not None else rot @ np.array([0.0, 0.0, 1.0])  # type: ignore[attr-defined]
        w = self.toward_viewer()
        facing = float(axis @ w)  # > 0: the second end faces the viewer
        rims = (pts[:37], pts[37:])
        front, back = (rims[1], rims[0]) if facing >= 0 else (rims[0], rims[1])
        self.line(front, Stroke.OUTLINE)
        if abs(facing) < 1e-9:  # seen side on: both rims are edges
            self.line(back, Stroke.OUTLINE)
            return
        # the back rim's points nearer the viewer than its centre are seen; the others are hidden
        cx = sum(p[0] for p in back) / len(back)
        cy = sum(p[1] for p in back) / len(back)
        fx = sum(p[0] for p in front) / len(front) - cx
        fy = sum(p[1] for p in front) / len(front) - cy
        run: list[Point] = []
        hidden_run: bool | None = None
        for p in back:
            hidden = (p[0] - cx) * fx + (p[1] - cy) * fy > 0  # on the side toward the front rim: behind
            if hidden_run is not None and hidden != hidden_run:
                self.line([*run, p], Stroke.DASHED if hidden_run else Stroke.THIN)
                run = []
            run.append(p)
            hidden_run = hidden
        if run:
            self.line(run, Stroke.DASHED if hidden_run else Stroke.THIN)
