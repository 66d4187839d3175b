"""The drawing of a system: its model, placed at one pose, projected, and laid out as primitives.

Steps (each a method of :class:`SystemBuilder` and the classes it builds on, in drawing order):

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

This module owns the orchestration: :func:`draw_system` (with the retry of another default pose when
links overlap) and the order of the steps. The steps live by topic: numbers and the pose in
:mod:`tutgen.figure.pose`, projection, scale and page helpers in :mod:`tutgen.figure.canvas`, each
element kind in :mod:`tutgen.figure.bodies`, :mod:`tutgen.figure.coordinates`,
:mod:`tutgen.figure.elements` and :mod:`tutgen.figure.axes`, label placement in
:mod:`tutgen.figure.labels`, plane geometry in :mod:`tutgen.figure.geometry`.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np
import sympy as sp

from tutgen.engine.constraints.positions import LoopAnalysis, assembly_at, branch_at
from tutgen.figure.axes import AxesDrawing
from tutgen.figure.canvas import POSE_SIGNS
from tutgen.figure.geometry import prim_box, segments_cross
from tutgen.figure.labels import place_labels
from tutgen.figure.pose import Pose, Positive, reading
from tutgen.figure.scene import Box, Drawing, Point, Polyline, Primitive, Stroke
from tutgen.memo import ByIdentity
from tutgen.model.system import System

#: A link seen shorter than this fraction of its length (an oblique view looking along it) asks for
#: another default pose, when one shows every link at least :data:`BETTER` of it more.
END_ON = 0.5
BETTER = 0.2


#: The drawings made in this process, by the identity of their system (kept, so that the id is not
#: reused while the entry lives): one solve asks for its figure several times (the solution's view,
#: the JSON entry, the SVG beside the Markdown, the free-body step's check of the view), and a
#: Drawing is immutable, so each is drawn once. The oldest entry goes past :data:`DRAWN_MAX` (a sheet
#: draws each variant's own system once).
DRAWN_MAX = 64
_DRAWN: ByIdentity[System, Drawing] = ByIdentity(DRAWN_MAX)


#: The drawings by what they are a function of: the system without its parameters' values (its
#: :func:`_skeleton`, with what else the drawing is of), and the values of the parameters the drawing
#: read (:func:`tutgen.figure.pose.reading`: a length, not a mass). A sheet's variants that differ in
#: their masses share one drawing. The last :data:`DRAWN_MAX` keys are kept, and for each the last
#: :data:`DRAWN_MAX` sets of values.
_BY_READS: dict[tuple[object, ...], list[tuple[tuple[tuple[sp.Basic, object], ...], Drawing]]] = {}


def draw_system(system: System) -> Drawing:
    """The schematic of ``system``, drawn once per system object in a process, and once for the
    systems that differ only in values the drawing does not read (see :func:`_draw_system` for how, and
    :data:`_DRAWN`, :data:`_BY_READS`)."""
    drawing = _DRAWN.get(system)
    if drawing is None:
        drawing = _DRAWN.put(system, drawn_by_reads(system, ("system",), _draw_system))
    return drawing


def _skeleton(system: System) -> System:
    """``system`` with no parameter values (nor choices of them): what every variant of a sheet's problem
    shares."""
    params = tuple(dataclasses.replace(p, value=None, choices=None) for p in system.parameters)
    return dataclasses.replace(system, parameters=params)


def drawn_by_reads(system: System, what: tuple[object, ...], draw: Callable[[System], Drawing]) -> Drawing:
    """``draw(system)``, or the drawing it made of a system that differs from this one only in the values
    of parameters it did not read; ``what``: what else (hashable) the drawing is of."""
    values = {p.symbol: p.value for p in system.parameters}
    key = (_skeleton(system), *what)
    seen = _BY_READS.pop(key, [])  # put back last: the most recent key is the last forgotten
    while len(_BY_READS) >= DRAWN_MAX:
        _BY_READS.pop(next(iter(_BY_READS)))
    _BY_READS[key] = seen
    for read, drawing in seen:
        if all(_same(values[symbol], value) for symbol, value in read):
            return drawing
    with reading() as symbols:
        drawing = draw(system)
    read = tuple(
        (symbol, value if symbol in symbols else POSITIVE)
        for symbol, value in values.items()
        if symbol in symbols or Positive(symbol) in symbols
    )
    if len(seen) >= DRAWN_MAX:
        del seen[0]
    seen.append((read, drawing))
    return drawing


#: In a drawing's reads, a parameter of which the drawing used only that it is positive (:class:`Positive`).
POSITIVE = object()


def _same(value: object, read: object) -> bool:
    """Whether a parameter's ``value`` gives the drawing that ``read`` (its value, or :data:`POSITIVE`) gave."""
    if read is POSITIVE:
        return isinstance(value, sp.Basic) and bool(value.is_number and value.is_positive)
    return value == read


def drawn_values(system: System) -> dict[sp.Symbol, float]:
    """The numbers of the drawing of ``system``: a float for every parameter with a numeric value or a
    drawing size, and for every coordinate at the pose drawn (the dependent ones solved so that the
    loops close)."""
    drawing = draw_system(system)
    by_name = {p.name: p.symbol for p in system.parameters} | {x.name: x.q for x in system.coordinates}
    values: dict[sp.Symbol, float] = {
        p.symbol: float(p.value) for p in system.parameters if p.value is not None and p.value.is_number
    }
    for name, value in (*drawing.sizes, *drawing.at):
        if name in by_name:
            values[by_name[name]] = value
    return values


def drawn_branch(system: System, loop: LoopAnalysis) -> tuple[int, str | None] | None:
    """The branch of ``loop`` (tutgen/engine/constraints/positions.py) that the drawing of ``system``
    shows: its sign, and for a four-bar its assembly (``"open"`` or ``"crossed"``); ``None`` when the
    drawing is on neither (its loop drawn open)."""
    values = drawn_values(system)
    sign = branch_at(loop, values, [x.q for x in system.coordinates])
    if sign is None:
        return None
    return sign, assembly_at(loop, values)


def _draw_system(system: System) -> Drawing:
    """The schematic of ``system`` (see the module docstring for how it is made).

    When the default pose makes two links overlap (a chain folding back on itself), the next sign
    pattern of the default angles is tried, and the change is remarked on; a pose the spec gives
    (``figure.at``) is kept as it is, with a remark. In the oblique view, a default pose that shows a
    link nearly end-on (a SCARA's arm at +40 degrees points at the viewer) is replaced by the sign
    pattern that shows the links longest, when that one makes no links overlap (for up to four joints).
    """
    builder = SystemBuilder(system)
    drawing = builder.build()
    given = {name for name, _v in (system.figure.at if system.figure else ())}
    if not _links_overlap(drawing):
        # (a six-joint arm's other poses fold it onto itself, and trying them costs more than the figure)
        if given or drawing.view != "oblique" or len(system.joints) > 4 or foreshortening(builder) >= END_ON:
            return drawing
        return _seen_broadside(builder, drawing, foreshortening(builder))
    if given:
        return _remarked(drawing, "two links overlap at the pose given by figure.at")
    for signs in POSE_SIGNS[1:]:
        other = SystemBuilder(system, signs).build()
        if not _links_overlap(other):
            return _remarked(other, "the default pose made two links overlap; some angles are drawn negative")
    return _remarked(drawing, "two links overlap at every default pose tried")


def _seen_broadside(builder: SystemBuilder, drawing: Drawing, worst: float) -> Drawing:
    """The default pose whose links are seen longest, if it is clearly better and overlaps no links.
    The poses are compared on their numbers alone, in the default pose's projection (the view does
    not depend on the signs of the angles, and the ratio not on the scale); only the best is drawn."""
    system = builder.s
    best, best_signs = worst, None
    for signs in POSE_SIGNS[1:]:
        trial = SystemBuilder(system, signs)
        trial.numbers()
        trial.pose = Pose(system, trial.num)
        trial.matrix, trial.scale = builder.matrix, builder.scale
        ratio = foreshortening(trial)
        if ratio > best + 1e-9:
            best, best_signs = ratio, signs
    if best_signs is None or best < worst + BETTER:
        return drawing
    other = SystemBuilder(system, best_signs).build()
    if _links_overlap(other):
        return drawing
    return _remarked(other, "the default pose showed a link end-on; some angles are drawn negative")


def foreshortening(builder: SystemBuilder) -> float:
    """How short the most foreshortened link looks: its length on the page over its length at the
    drawing's scale (1 when seen broadside); links shorter than 0.3 cm on the page are not counted."""
    pose = builder.pose
    worst = 1.0
    for body in builder.s.bodies:
        joint = pose.by_child.get(body.name)
        if joint is None:
            continue
        start = pose.joint_at[joint.name]
        for far in [pose.frames[body.name][0], *builder.far_points(body, pose)]:
            true = float(np.linalg.norm(far - start)) * builder.scale
            if true < 0.3:
                continue
            seen = math.dist(builder.P(far), builder.P(start))
            worst = min(worst, seen / true)
    return worst


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
            if segments_cross(a, b, c, d):
                return True
    return False


class SystemBuilder(AxesDrawing):
    """One drawing of a system, built step by step by :meth:`build`."""

    # -- 5. primitives -------------------------------------------------------------------------
    def build(self) -> Drawing:
        self.numbers()
        self.pose = Pose(self.s, self.num)
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
        leaders: list[Primitive] = []
        labels = place_labels(self.requests, self.obstacles, self.prims, self.remarks, leaders)
        self.prims += leaders
        box = None
        for prim in self.prims:
            b = prim_box(prim)
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
