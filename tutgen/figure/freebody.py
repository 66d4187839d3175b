"""Free-body diagrams: one body cut free, with every force and moment on it drawn and named.

The Newton–Euler step writes, body by body, the balance of the forces and moments on it; the figure
of that step is the body alone (no ground, no other bodies; its pins drawn open where it was cut)
with one arrow per force: gravity at the centre of mass, spring and damper forces where they attach,
the loads, the joints' drives, and the joints' reactions — at a pin two components along the world
axes, at a slider a normal force and a moment — on the parent the same reactions reversed (Newton's
third law, with the same names).

A force is a :class:`BodyForce`, a small record a caller may also build itself (the planar
Newton–Euler of the engine names its own forces): where it acts, in the body's frame or the world's;
a vector — its symbolic components, or only a direction — in either frame; a label; whether it is a
moment. :func:`body_forces` makes the list from the model alone, for any body of a spec;
:func:`free_body_diagram` draws a list (that one by default).

Directions are evaluated at the figure's pose (:mod:`tutgen.figure.pose`: unknown symbols count as
1), so an unknown reaction ``R_x`` is drawn along +x, the way a student assumes it, and a spring is
drawn pulling (in tension). A force whose direction vanishes at the pose is left out and remarked on.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from enum import StrEnum

import numpy as np
import sympy as sp

from tutgen.figure.build import DRAWN_MAX, SystemBuilder, drawn_by_reads
from tutgen.figure.canvas import TARGET_SIZE
from tutgen.figure.geometry import prim_box
from tutgen.figure.labels import place_labels
from tutgen.figure.pose import Pose, read_positive
from tutgen.figure.scene import Box, Drawing, Point, Primitive
from tutgen.figure.texlabel import is_safe_tex, name_tex, word_tex
from tutgen.memo import ByIdentity
from tutgen.model.system import Body, Endpoint, JointKind, System

#: Arrow length of a force on the page (cm), the size a free body is scaled to, a slider block's size.
FORCE_LENGTH = 1.0
BODY_SIZE = 0.6 * TARGET_SIZE
BLOCK = (1.6, 1.0)
#: How far an arrow is moved aside when it would lie on the line of another (cm).
ASIDE = 0.3
#: Arrows pushing on one face of a block stand this far apart (cm), so that their labels, set at
#: their tails, do not meet; and this far from the face's ends at least.
SLOT = 0.7
FACE_END = 0.22


class Frame(StrEnum):
    """Whose axes a point or a vector is written in."""

    BODY = "body"
    WORLD = "world"


@dataclass(frozen=True)
class BodyForce:
    """One force (or moment, ``moment=True``) on the body of a free-body diagram.

    ``name``: what it is, unique in the diagram (the drawing's label is ``force:<name>``), e.g.
    ``gravity``, ``spring:wall``, ``reaction:pivot:x``; ``label``: how it is written — an expression
    of the spec's symbols (``m*g``, ``k*x``: products of symbols are typeset, anything else falls back
    to the name) or a name (``R_1x`` -> ``R_{1x}``), never TeX; ``at``: where it acts, in ``at_frame``
    (the body's frame by default; a moment's point only places its arrow); ``vector``: its components
    or just a direction, in ``frame``; ``toward``: instead of ``vector``, a force along the line to a
    point of another body (a spring's or damper's other end), pulling; ``tex``: the label as TeX that
    tutgen itself wrote (the Newton–Euler step's own names, ``\\mathbf{R}_{\\mathrm{pivot}}``), used when
    it is in the label vocabulary (:func:`tutgen.figure.texlabel.is_safe_tex`), else ``label`` is.
    """

    name: str
    label: sp.Basic | str
    at: tuple[sp.Expr | float, ...] = (0, 0, 0)
    vector: tuple[sp.Expr | float, ...] = (0, 0, 0)
    frame: Frame = Frame.WORLD
    at_frame: Frame = Frame.BODY
    moment: bool = False
    toward: Endpoint | None = None
    tex: str = ""


def free_body_diagram(system: System, body_name: str, forces: Sequence[BodyForce] | None = None) -> Drawing:
    """The free-body diagram of ``body_name`` with ``forces`` (by default :func:`body_forces`);
    a :class:`ValueError` naming the bodies there are when there is no such body. Drawn once per
    system object, body and list of forces in a process (a Markdown solve asks for each diagram for
    its section, its JSON entry and the SVG file beside it), as :func:`tutgen.figure.build.draw_system`."""
    _known(system, body_name)
    key = (body_name, tuple(forces) if forces is not None else None)
    drawn = _DIAGRAMS.get(system)
    if drawn is None:
        drawn = _DIAGRAMS.put(system, {})
    drawing = drawn.get(key)
    if drawing is None:
        drawing = drawn[key] = drawn_by_reads(
            system, ("free body", *key), lambda s: _FreeBodyBuilder(s, body_name, forces).build()
        )
    return drawing


#: The diagrams drawn in this process: per system (by identity), by (body, forces).
_DIAGRAMS: ByIdentity[System, dict[tuple[str, tuple[BodyForce, ...] | None], Drawing]] = ByIdentity(DRAWN_MAX)


def _known(system: System, body_name: str) -> Body:
    for body in system.bodies:
        if body.name == body_name:
            return body
    known = ", ".join(b.name for b in system.bodies) or "none"
    raise ValueError(f"there is no body '{body_name}' (bodies: {known})")


def body_forces(system: System, body_name: str, normal: Sequence[float] = (0.0, 0.0, 1.0)) -> tuple[BodyForce, ...]:
    """Every force and moment on ``body_name`` that the model names, in a fixed order: gravity,
    springs, dampers, loads (and the reactions of loads on other bodies), joint drives, joint
    reactions. ``normal``: the world normal of the plane of motion (a reaction moment is about it)."""
    body = _known(system, body_name)
    n = np.array([float(v) for v in normal])
    out: list[BodyForce] = []
    mass = _mass(body)
    if system.gravity is not None and mass is not None and any(v != 0 for v in system.gravity):
        label = _weight_label(mass, body, system.gravity)
        out.append(BodyForce("gravity", label, _com(body), tuple(mass * v for v in system.gravity)))
    for kind, elements in (("spring", system.springs), ("damper", system.dampers)):
        for el in elements:
            out += _element_forces(system, body_name, kind, el)
    for load in system.loads:
        out += _load_forces(system, body_name, load)
    joint_no = {j.name: i for i, j in enumerate(system.joints, start=1)}
    for name, expr in system.generalized_forces:
        joint = next((j for j in system.joints if j.coordinate is not None and j.coordinate.name == name), None)
        if joint is None or body_name not in (joint.child, joint.parent):
            continue
        sign = 1 if body_name == joint.child else -1
        at = (0, 0, 0) if body_name == joint.child else tuple(joint.origin_offset)
        # a joint's axis is in the child's frame (turned by the joint's fixed rotation from the parent's)
        frame = Frame.BODY
        axis = (
            tuple(joint.axis) if body_name == joint.child else tuple(sp.Matrix(joint.rotation) * sp.Matrix(joint.axis))
        )
        axis = tuple(sign * expr * v for v in axis)
        out.append(BodyForce(f"drive:{name}", expr, at, axis, frame, moment=joint.kind is JointKind.REVOLUTE))
    for joint in system.joints:
        if body_name not in (joint.child, joint.parent):
            continue
        out += _reactions(joint, body_name, joint_no[joint.name], n)
    return tuple(out)


# -- the forces of the model, one kind at a time ---------------------------------------------------
def _mass(body: Body) -> sp.Expr | None:
    masses = [p.mass for p in body.parts]
    if not masses or any(m is None for m in masses):
        return None
    return sp.Add(*masses)


def _com(body: Body) -> tuple[sp.Expr, ...]:
    """The centre of mass in the body's frame (parts without a mass count as 1)."""
    if len(body.parts) == 1:
        return tuple(body.parts[0].at)
    total = sp.Add(*[p.mass if p.mass is not None else 1 for p in body.parts]) or 1
    acc = sp.zeros(3, 1)
    for p in body.parts:
        acc += (p.mass if p.mass is not None else 1) * sp.Matrix(p.at)
    return tuple(v / total for v in acc)  # evaluated at the pose only: no simplify


def _weight_label(mass: sp.Expr, body: Body, gravity: object) -> sp.Basic | str:
    """``m g`` (the magnitude: the arrow shows the direction) for a body of one mass symbol along one
    axis of gravity, else ``W_<body>``."""
    nz = [sp.sympify(v) for v in gravity if v != 0]  # type: ignore[attr-defined]
    if isinstance(mass, sp.Symbol) and len(nz) == 1:
        return mass * (-nz[0] if nz[0].could_extract_minus_sign() else nz[0])
    return f"W_{body.name}"


def _element_forces(system: System, body_name: str, kind: str, el: object) -> list[BodyForce]:
    """A spring's or damper's force on the body: along the line to its other end (``between``), or,
    for an ``extension`` in coordinates, along each prismatic joint it stretches (a moment for a
    revolute one)."""
    coef = el.stiffness if kind == "spring" else el.coefficient  # type: ignore[attr-defined]
    name = f"{kind}:{el.name}"  # type: ignore[attr-defined]
    between = el.between  # type: ignore[attr-defined]
    if between is not None:
        ends = [e for e in between if e.body == body_name]
        if len(ends) != 1:
            return []  # not attached, or both ends on the body (an internal force)
        mine = ends[0]
        other = between[1] if between[0] is mine else between[0]
        return [BodyForce(name, _element_label(kind, coef, None), tuple(mine.at), toward=other)]
    ext = sp.sympify(el.extension)  # type: ignore[attr-defined]
    out = []
    for joint in system.joints:
        c = joint.coordinate
        if c is None or c.q not in ext.free_symbols or body_name not in (joint.child, joint.parent):
            continue
        slope = ext.diff(c.q)
        if not slope.is_number or slope == 0:
            continue
        sign = -1 if body_name == joint.child else 1  # it pulls the coordinate back to its zero
        sign *= 1 if slope > 0 else -1
        lone = ext if ext in (c.q, -c.q) else None
        axis = joint.axis if body_name == joint.child else sp.Matrix(joint.rotation) * sp.Matrix(joint.axis)
        at = (0, 0, 0) if body_name == joint.child else tuple(joint.origin_offset)
        out.append(
            BodyForce(
                name if len(out) == 0 else f"{name}:{c.name}",
                _element_label(kind, coef, lone if lone is None else c),
                at,
                tuple(sign * v for v in axis),
                Frame.BODY,
                moment=joint.kind is JointKind.REVOLUTE,
            )
        )
    return out


def _element_label(kind: str, coef: sp.Expr, coordinate: object) -> sp.Basic | str:
    """``k x`` or ``c ẋ`` for an element stretched by one coordinate, else ``F_k`` (``F_c``)."""
    if coordinate is not None:
        return coef * (coordinate.q if kind == "spring" else coordinate.qd)  # type: ignore[attr-defined]
    return f"F_{coef}" if isinstance(coef, sp.Symbol) else f"F_{kind[0]}"


def _load_forces(system: System, body_name: str, load: object) -> list[BodyForce]:
    out = []
    on_body = load.body == body_name  # type: ignore[attr-defined]
    reacting = load.reaction_body == body_name and not on_body  # type: ignore[attr-defined]
    if not (on_body or reacting):
        return out
    frame = Frame.BODY if load.in_body_frame else Frame.WORLD  # type: ignore[attr-defined]
    sign = 1 if on_body else -1
    suffix = "" if on_body else ":reaction"
    for vec, moment in ((load.force, False), (load.torque, True)):  # type: ignore[attr-defined]
        if vec is None or all(v == 0 for v in vec):
            continue
        if reacting and not moment:
            continue  # a reacted force acts where the load does, on the other body: not placed here
        nz = [v for v in vec if v != 0]
        label = nz[0] if len(nz) == 1 else load.name  # type: ignore[attr-defined]
        at = tuple(load.at) if on_body else _joint_point(system, body_name, load.body)  # type: ignore[attr-defined]
        vector = tuple(sign * v for v in vec)
        if reacting and frame is Frame.BODY:
            frame = Frame.WORLD  # a planar moment about the normal is the same in every frame
        out.append(BodyForce(f"load:{load.name}{suffix}", label, at, vector, frame, moment=moment))  # type: ignore[attr-defined]
    return out


def _joint_point(system: System, body_name: str, other: str) -> tuple[sp.Expr, ...]:
    """Where the joint between ``body_name`` and ``other`` is, in ``body_name``'s frame (its origin
    when they are not joined)."""
    for j in system.joints:
        if j.parent == body_name and j.child == other:
            return tuple(j.origin_offset)
        if j.child == body_name and j.parent == other:
            return (0, 0, 0)
    return (0, 0, 0)


def _reactions(joint: object, body_name: str, number: int, normal: np.ndarray) -> list[BodyForce]:
    """The reactions of a joint on the body: at a pin the two components along the world axes of the
    plane, at a slider the normal force and the moment; reversed on the parent."""
    child = joint.child == body_name  # type: ignore[attr-defined]
    sign = 1 if child else -1
    at = (0, 0, 0) if child else tuple(joint.origin_offset)  # type: ignore[attr-defined]
    name = joint.name  # type: ignore[attr-defined]
    k = int(np.argmax(np.abs(normal)))
    plane = [i for i in range(3) if i != k]
    letters = "xyz"
    out = []
    if joint.kind is JointKind.PRISMATIC:  # type: ignore[attr-defined]
        axis = np.array([float(v) for v in joint.axis], dtype=float)  # type: ignore[attr-defined]
        if not child:
            axis = np.array(sp.Matrix(joint.rotation) * sp.Matrix(joint.axis), dtype=float).reshape(-1)  # type: ignore[attr-defined]
        across = np.cross(normal, axis)
        if np.linalg.norm(across) < 1e-9:
            across = np.eye(3)[plane[1]]
        out.append(BodyForce(f"reaction:{name}:normal", f"N_{number}", at, _exact(sign * across), Frame.BODY))
        out.append(
            BodyForce(f"reaction:{name}:moment", f"M_{number}", at, _exact(sign * normal), Frame.WORLD, moment=True)
        )
        return out
    for i in plane:
        e = np.eye(3)[i] * sign
        out.append(BodyForce(f"reaction:{name}:{letters[i]}", f"R_{number}{letters[i]}", at, _exact(e), Frame.WORLD))
    if joint.kind is JointKind.FIXED:  # type: ignore[attr-defined]
        out.append(
            BodyForce(f"reaction:{name}:moment", f"M_{number}", at, _exact(sign * normal), Frame.WORLD, moment=True)
        )
    return out


# -- the drawing ---------------------------------------------------------------------------------
class _FreeBodyBuilder(SystemBuilder):
    """The system's drawing machinery, drawing one body and its forces."""

    def __init__(self, system: System, body_name: str, forces: Sequence[BodyForce] | None) -> None:
        super().__init__(system)
        self.only = body_name
        self.given = forces
        self.slider = BLOCK
        self.drawn: list[tuple[Point, Point]] = []  # the force arrows so far, tail and tip
        # force name -> (the block face it pushes on, its offset along it), set by draw_block
        self.face_slots: dict[str, tuple[tuple[str, int] | None, float]] = {}
        for c in system.coordinates:
            self.latex_of[c.qd] = "\\dot{" + self.latex_of[c.q] + "}"

    def build(self) -> Drawing:
        self.numbers()
        self.pose = Pose(self.s, self.num)
        self.choose_view()
        self.choose_body_scale()
        self.sliders = {}
        body = self.s.body(self.only)  # type: ignore[arg-type]
        given = self.given if self.given is not None else body_forces(self.s, body.name, tuple(self.plane_normal))
        forces = [part for force in given for part in components(force)]
        joint = self.pose.by_child.get(body.name)
        if joint is not None and joint.kind is JointKind.PRISMATIC:
            self.draw_block(joint, body, forces)
        self.draw_links()
        self.draw_bodies()
        for force in forces:
            self.draw_force(body, force)
        self.draw_world_axes()
        if not any(body.name in (j.parent, j.child) for j in self.s.joints):
            self.remarks.append(
                f"body {body.name} is placed by its position, not by joints: the forces that keep it on its "
                "path are not in the model and are not drawn"
            )
        leaders: list[Primitive] = []
        labels = place_labels(self.requests, self.obstacles, self.prims, self.remarks, leaders)
        self.prims += leaders
        box: Box | None = None
        for b in [prim_box(p) for p in self.prims] + [lb.box for lb in labels]:
            box = b if box is None else box.union(b)
        box = box or Box(0, 0, 1, 1)
        box = Box(round(box.x0 - 0.15, 3), round(box.y0 - 0.15, 3), round(box.x1 + 0.15, 3), round(box.y1 + 0.15, 3))
        return Drawing(
            tuple(self.prims), tuple(labels), box, self.view, tuple(self.at), tuple(self.sizes), tuple(self.remarks)
        )

    def choose_body_scale(self) -> None:
        """The body alone fills :data:`BODY_SIZE` (a short link gets as much room as a long one)."""
        body = self.s.body(self.only)  # type: ignore[arg-type]
        o = self.pose.frames[body.name][0]
        pts = [o, *self.far_points(body, self.pose), *self.part_centres(body, self.pose)]
        joint = self.pose.by_child.get(body.name)
        if joint is not None:
            pts.append(self.pose.joint_at[joint.name])
        for part in body.parts:
            pts += self.part_points(body, part, self.pose)
        arr = np.array([self.project(p) for p in pts])
        extent = float(max(np.ptp(arr[:, 0]), np.ptp(arr[:, 1])))
        self.scale = BODY_SIZE / extent if extent > 1e-6 else BODY_SIZE / (2 * self.typical)

    def world(self, body: Body, values: Sequence[object], frame: Frame, point: bool) -> np.ndarray:
        v = self.num.vec(sp.Matrix([sp.sympify(x) for x in values]))
        if frame is Frame.WORLD:
            return v
        o, r = self.pose.frames[body.name]
        return o + r @ v if point else r @ v

    def force_vector(self, body: Body, force: BodyForce) -> np.ndarray:
        """The force's vector in world axes up to a positive factor, which is all its arrow shows: each
        parameter with a positive value that multiplies every component is divided out, and only its
        sign is read (a sheet's variants with other masses or stiffnesses share one diagram)."""
        values = [sp.sympify(v) for v in force.vector]
        scale = _positive_scale(values, self.s)
        if scale:
            read_positive(scale)
            values = [v / sp.Mul(*[b**e for b, e in scale.items()]) for v in values]
        return self.world(body, values, force.frame, point=False)

    def draw_force(self, body: Body, force: BodyForce) -> None:
        at3 = self.world(body, force.at, force.at_frame, point=True)
        if force.toward is not None:
            vec = self.pose.point(force.toward.body, self.num.vec(force.toward.at)) - at3
        else:
            vec = self.force_vector(body, force)
        names = f"force:{force.name}"
        tex = force.tex if force.tex and is_safe_tex(force.tex) else self.force_tex(force.label, force.name)
        norm = float(np.linalg.norm(vec))
        if norm < 1e-12:
            self.remarks.append(f"the force {force.name} is zero at the drawing's pose and is not drawn")
            return
        if force.moment:
            # round its point, inside a block (an arc round the block would cross the arrows on its
            # faces), each next moment at the same point a size larger and its label a quarter turn on
            k = self._moments_at(at3)
            self.torque(names, tex, at3, vec, radius=0.3 + 0.16 * k, start_deg=200 + 90 * k)
            return
        d = self.page_dir(at3, vec / norm)
        if d is None:  # along the line of sight: a label only
            self.label(names, tex, self.P(at3), (0.7, 0.7))
            return
        at = self.P(at3)
        if force.name == "gravity":  # the weight hangs from the centre of mass
            tail, tip = self.aside(at, (at[0] + d[0] * FORCE_LENGTH, at[1] + d[1] * FORCE_LENGTH))
            self.arrow(tail, tip)
            self.label(names, tex, tip, d)
            return
        if self.on_block(body.name, at):  # a force on the block pushes on its face
            at = self.block_face(body.name, (-d[0], -d[1]), force.name)
        # every other force pushes on its point: the arrow ends there
        tail, tip = self.aside((at[0] - d[0] * FORCE_LENGTH, at[1] - d[1] * FORCE_LENGTH), at)
        self.arrow(tail, tip)
        self.label(names, tex, tail, (-d[0], -d[1]))

    def on_block(self, body: str, at: Point) -> bool:
        """Whether a page point is inside the body's slider block (a body on a prismatic joint)."""
        if body not in self.sliders:
            return False
        centre, u = self.sliders[body]
        dx, dy = at[0] - centre[0], at[1] - centre[1]
        w, h = self.slider
        return abs(dx * u[0] + dy * u[1]) <= w / 2 + 1e-9 and abs(-dx * u[1] + dy * u[0]) <= h / 2 + 1e-9

    def block_face(self, body: str, d: Point, name: str = "") -> Point:
        """Where a line from the block's centre in the page direction ``d`` leaves the block, moved
        along the face to the force's own place on it (:meth:`draw_block`), so that the arrows on
        one face stand side by side."""
        centre, u = self.sliders[body]
        w, h = self.slider
        along = abs(d[0] * u[0] + d[1] * u[1])
        across = abs(-d[0] * u[1] + d[1] * u[0])
        t = min(w / 2 / along if along > 1e-9 else math.inf, h / 2 / across if across > 1e-9 else math.inf)
        at = (centre[0] + d[0] * t, centre[1] + d[1] * t)
        face, offset = self.face_slots.get(name, (None, 0.0))
        if face is None or face != _face(d, u, self.slider):
            return at
        t_dir = (-u[1], u[0]) if face[0] == "across" else (u[0], u[1])  # the direction along the face
        return (at[0] + t_dir[0] * offset, at[1] + t_dir[1] * offset)

    def draw_block(self, joint: object, body: Body, forces: Sequence[BodyForce]) -> None:
        """The slider block, sized to the arrows on it: each force that acts inside the block (not
        the weight, not a moment) pushes on the face it points into; the arrows on one face are set
        side by side at :data:`SLOT` apart (clear of the weight's line on the face below the centre),
        and the block grows so that they fit on it."""
        self.slider = BLOCK
        self.draw_prismatic(joint, rail=False)  # type: ignore[arg-type]
        _centre, u = self.sliders[body.name]
        faces: dict[tuple[str, int], list[str]] = {}
        weight_face: tuple[str, int] | None = None
        for force in forces:
            if force.moment or force.toward is not None:
                continue
            at3 = self.world(body, force.at, force.at_frame, point=True)
            vec = self.force_vector(body, force)
            norm = float(np.linalg.norm(vec))
            d = self.page_dir(at3, vec / norm) if norm > 1e-12 else None
            if d is None or not self.on_block(body.name, self.P(at3)):
                continue
            if force.name == "gravity":  # it hangs from the centre: its face keeps the middle free
                weight_face = _face(d, u, BLOCK)
                continue
            faces.setdefault(_face((-d[0], -d[1]), u, BLOCK), []).append(force.name)
        w, h = BLOCK
        for face, names in faces.items():
            offsets = _slots(len(names), face == weight_face)
            for name, off in zip(names, offsets, strict=True):
                self.face_slots[name] = (face, off)
            room = 2 * max(abs(o) for o in offsets) + 2 * FACE_END
            if face[0] == "across":  # a face across the slide: its length is the block's height
                h = max(h, room)
            else:
                w = max(w, room)
        if (w, h) != BLOCK:  # drawn again, at its new size (the block is the first thing drawn)
            del self.prims[:], self.obstacles[:], self.requests[:]
            self.slider = (round(w, 3), round(h, 3))
            self.draw_prismatic(joint, rail=False)  # type: ignore[arg-type]

    def aside(self, tail: Point, tip: Point) -> tuple[Point, Point]:
        """The arrow, moved aside (perpendicular, by :data:`ASIDE`) while it lies on the line of an arrow
        drawn before it and overlaps it: the weight and a normal force on one vertical, say."""
        for _ in range(4):
            if not any(_on_one_line(tail, tip, a, b) for a, b in self.drawn):
                break
            dx, dy = tip[0] - tail[0], tip[1] - tail[1]
            n = math.hypot(dx, dy) or 1.0
            off = (dy / n * ASIDE, -dx / n * ASIDE)
            tail, tip = (tail[0] + off[0], tail[1] + off[1]), (tip[0] + off[0], tip[1] + off[1])
        self.drawn.append((tail, tip))
        return tail, tip

    def _moments_at(self, at3: np.ndarray) -> int:
        """How many moment arrows are already drawn round this point (each next one a size larger)."""
        key = tuple(round(float(v), 6) for v in at3)
        seen = getattr(self, "_moment_points", {})
        count = seen.get(key, 0)
        seen[key] = count + 1
        self._moment_points = seen
        return count

    def force_tex(self, label: sp.Basic | str, name: str) -> str:
        """Safe TeX of a force's label: a product of symbols (``m g``, ``k x``, ``c \\dot{x}``), a
        lone symbol with its sign, or a name (``R_1x`` -> ``R_{1x}``); anything else, the name."""
        if isinstance(label, str):
            tex = (
                name_tex(label)
                if label.isidentifier()
                else word_tex("".join(ch if ch.isalnum() else "_" for ch in label))
            )
            return tex if is_safe_tex(tex) else word_tex("F")
        expr = sp.sympify(label)
        sign = ""
        if expr.could_extract_minus_sign():
            sign, expr = "-", -expr
        factors = sorted(expr.args, key=sp.default_sort_key) if isinstance(expr, sp.Mul) else [expr]
        parts = []
        for f in factors:
            if isinstance(f, sp.Symbol):
                parts.append(self.latex_of.get(f, name_tex(f.name)))
            elif f.is_Integer and f > 0:
                parts.insert(0, str(f))
            else:
                return word_tex(name.replace(":", "_"))  # not a product of symbols: its name, upright
        order = {self.latex_of[p.symbol]: i for i, p in enumerate(self.s.parameters)}
        parts.sort(key=lambda t: (not t[0].isdigit(), order.get(t, len(order)), t))
        tex = sign + " ".join(parts)
        return tex if is_safe_tex(tex) else word_tex("F")

    def draw_world_axes(self) -> None:
        """The world axes in a corner, so that a reaction drawn along +x reads as R_x."""
        pts = [prim_box(p) for p in self.prims]
        box = pts[0] if pts else Box(0, 0, 1, 1)
        for b in pts[1:]:
            box = box.union(b)
        self.axes_at((box.x0 - 1.3, box.y0 - 0.2), 0.6)


def _positive_scale(values: Sequence[sp.Expr], system: System) -> dict[sp.Symbol, int]:
    """The parameters with a positive value that are a factor of every non-zero component, each with its
    lowest power (``m g`` of a weight ``(0, -m g, 0)``; ``m2`` of ``-m2 (l a + b)``)."""
    positive = {
        p.symbol for p in system.parameters if p.value is not None and p.value.is_number and p.value.is_positive
    }
    common: dict[sp.Symbol, int] | None = None
    for v in values:
        if v == 0:
            continue
        powers: dict[sp.Symbol, int] = {}
        for f in sp.Mul.make_args(v):
            b, e = f.as_base_exp()
            if b in positive and e.is_Integer and e > 0:
                powers[b] = powers.get(b, 0) + int(e)
        common = powers if common is None else {b: min(e, powers[b]) for b, e in common.items() if b in powers}
        if not common:
            return {}
    return common or {}


def components(force: BodyForce) -> tuple[BodyForce, ...]:
    """A force of unknown components, drawn as a textbook draws it: one arrow per component along
    its world axis, each named by its own symbol (a pin's reaction ``(R_x, R_y)`` as ``R_{pivot,x}``
    and ``R_{pivot,y}``, a slide's normal force as ``N_{slider}``), the arrow reversed for a negative
    component (Newton's third law on the parent), so the label carries no sign. The parts are named
    ``<name>/x``, ``<name>/y``, ``<name>/z``. A force is split when it is not a moment, has a vector,
    and every non-zero component is a symbol with its sign: two or more of them, or one that is a
    joint's reaction (``R[slider].n``); any other force is returned as it is."""
    if force.moment or force.toward is not None:
        return (force,)
    values = [sp.sympify(v) for v in force.vector]
    parts = [(i, *_signed_symbol(v)) for i, v in enumerate(values) if v != 0]
    if not parts or any(sym is None for _i, _sign, sym in parts):
        return (force,)
    if len(parts) == 1 and _reaction_tex(parts[0][2]) is None:  # type: ignore[arg-type]
        return (force,)
    out = []
    for i, sign, sym in parts:
        assert sym is not None
        unit = tuple(sp.Integer(sign if k == i else 0) for k in range(len(values)))
        tex = _reaction_tex(sym) or ""
        name = f"{force.name}/{'xyz'[i]}" if len(parts) > 1 else force.name
        out.append(BodyForce(name, sym, force.at, unit, force.frame, force.at_frame, tex=tex))
    return tuple(out)


def _signed_symbol(v: sp.Expr) -> tuple[int, sp.Symbol | None]:
    if isinstance(v, sp.Symbol):
        return 1, v
    if isinstance(v, sp.Mul) and len(v.args) == 2 and v.args[0] == -1 and isinstance(v.args[1], sp.Symbol):
        return -1, v.args[1]
    return 1, None


def _reaction_tex(symbol: sp.Symbol) -> str | None:
    """The Newton–Euler step's name of a reaction unknown (tutgen.engine.planar_ne's ``R[pivot].x``,
    ``R[slider].n``), as the step prints it: ``R_{\\mathrm{pivot},x}``, ``N_{\\mathrm{slider}}``; None
    for any other symbol."""
    m = re.fullmatch(r"R\[([A-Za-z_][A-Za-z0-9_]*)\]\.([xyzn])", symbol.name)
    if m is None:
        return None
    joint = word_tex(m.group(1))
    return f"N_{{{joint}}}" if m.group(2) == "n" else f"R_{{{joint},{m.group(2)}}}"


def _face(d: Point, u: Point, size: tuple[float, float]) -> tuple[str, int]:
    """The face of a block (slide direction ``u`` on the page, ``size`` along and across it) that a
    line from its centre in the page direction ``d`` leaves by: ``("across", ±1)`` for the two
    faces across the slide, ``("along", ±1)`` for the two along it."""
    along = d[0] * u[0] + d[1] * u[1]
    across = -d[0] * u[1] + d[1] * u[0]
    if abs(along) * size[1] >= abs(across) * size[0]:
        return ("across", 1 if along > 0 else -1)
    return ("along", 1 if across > 0 else -1)


def _slots(count: int, weight: bool) -> list[float]:
    """Offsets along a face of ``count`` arrows, :data:`SLOT` apart: centred on the face, or, on the
    face the weight crosses, beside its line (0) on alternate sides."""
    if not weight:
        return [round((i - (count - 1) / 2) * SLOT, 3) for i in range(count)]
    return [round(SLOT * (i // 2 + 1) * (1 if i % 2 == 0 else -1), 3) for i in range(count)]


def _on_one_line(a: Point, b: Point, c: Point, d: Point) -> bool:
    """Whether segments ab and cd are parallel, on one line (within 0.1 cm) and overlap along it."""
    ux, uy = b[0] - a[0], b[1] - a[1]
    n = math.hypot(ux, uy)
    if n < 1e-9:
        return False
    ux, uy = ux / n, uy / n
    vx, vy = d[0] - c[0], d[1] - c[1]
    m = math.hypot(vx, vy)
    if m < 1e-9 or abs(ux * vy - uy * vx) / m > 0.05:
        return False
    if any(abs((p[0] - a[0]) * uy - (p[1] - a[1]) * ux) > 0.1 for p in (c, d)):
        return False
    s0, s1 = sorted(((c[0] - a[0]) * ux + (c[1] - a[1]) * uy, (d[0] - a[0]) * ux + (d[1] - a[1]) * uy))
    return s1 > 0.02 and s0 < n - 0.02


def _exact(v: np.ndarray) -> tuple[sp.Expr, ...]:
    """A direction of whole numbers (the axes, their cross products) as sympy integers."""
    return tuple(sp.Integer(round(float(x))) if abs(x - round(float(x))) < 1e-12 else sp.Float(float(x)) for x in v)
