"""Hidden lines in the oblique view, leader lines to far labels, and a long arm's z axes."""

from __future__ import annotations

import math

import numpy as np

from tests.conftest import SPECS
from tutgen.figure.build import SystemBuilder, draw_system
from tutgen.figure.labels import LEADER, place_labels
from tutgen.figure.scene import Box, Polyline, Stroke
from tutgen.spec.validate import load_system

P01 = SPECS / "tutorial-1" / "p01-composite-inertia.yaml"


def test_hidden_edges_of_a_box_are_dashed_and_they_are_the_ones_behind() -> None:
    """A box seen from a general direction shows nine edges and hides three: those at the corner
    farthest from the viewer (the hidden corner is the one against the view direction)."""
    system = load_system(P01)
    builder = SystemBuilder(system)
    drawing = builder.build()
    assert drawing.view == "oblique"
    dashed = [p.points for p in drawing.primitives if isinstance(p, Polyline) and p.stroke is Stroke.DASHED]
    edges = [pts for pts in dashed if len(pts) == 2]  # the cylinder's hidden rim is a curve
    assert len(edges) == 3
    corner = {pt for pts in edges for pt in pts}
    shared = [pt for pt in corner if sum(pt in pts for pts in edges) == 3]
    assert len(shared) == 1  # the three hidden edges meet at one corner
    # that corner is the block's corner farthest along -w (w: toward the viewer), found independently
    w = np.cross(builder.matrix[0], builder.matrix[1])
    block = system.bodies[0].parts[0]
    half = np.array([float(v) for v in block.dimensions[0][1]]) / 2
    centre = np.array([float(v) for v in block.at])
    far = centre - np.sign(w) * half
    assert math.dist(shared[0], builder.P(far)) < 0.01
    assert any(len(pts) > 2 for pts in dashed)  # and the far half of the cylinder's back rim


def test_planar_figures_have_no_hidden_edges_drawn() -> None:
    drawing = draw_system(load_system(SPECS / "tutorial-1" / "p05-rr-arm.yaml"))
    assert drawing.view == "planar"
    assert not any(
        isinstance(p, Polyline) and p.stroke is Stroke.DASHED and len(p.points) > 2 for p in drawing.primitives
    )


def test_a_label_pushed_far_from_its_anchor_gets_a_leader_and_a_near_one_none() -> None:
    # a wall of obstacles round the first anchor sends its label away; the second sits where it asks
    wall = [Box(-0.9, -0.9, 0.9, 0.9)]
    leaders: list = []
    labels = place_labels(
        [("body:far", "m", (0.0, 0.0), (1.0, 0.0)), ("body:near", "k", (5.0, 0.0), (1.0, 0.0))],
        wall,
        [],
        [],
        leaders,
    )
    far, near = labels
    assert not far.box.overlaps(wall[0])
    assert len(leaders) == 1
    (a, b), stroke = leaders[0].points, leaders[0].stroke
    assert stroke is Stroke.THIN
    assert math.dist(a, (0.0, 0.0)) < 0.1  # from the anchor ...
    box = far.box
    assert box.x0 - 0.05 <= b[0] <= box.x1 + 0.05 and box.y0 - 0.05 <= b[1] <= box.y1 + 0.05  # ... to the label
    gap = math.dist((5.0, 0.0), (min(max(5.0, near.box.x0), near.box.x1), min(max(0.0, near.box.y0), near.box.y1)))
    assert gap <= LEADER


def test_long_arm_draws_each_z_axis_once_on_its_joint_axis() -> None:
    """PUMA (six joints): a z label sits at the end of its joint's dash-dot axis line, and no thin
    arrow runs along that axis from the body's origin (the axis line is the z axis)."""
    system = load_system(SPECS / "arms" / "puma560-numeric.yaml")
    builder = SystemBuilder(system)
    drawing = builder.build()
    axes = [p.points for p in drawing.primitives if isinstance(p, Polyline) and p.stroke is Stroke.AXIS]
    ends = [pts[-1] for pts in axes]
    z_anchors = [
        anchor for names, _tex, anchor, _d in builder.requests if names.startswith("frame:") and names.endswith(":z")
    ]
    assert len(z_anchors) == 6
    assert all(min(math.dist(a, e) for e in ends) < 0.01 for a in z_anchors)  # each at its axis' end
    thin = [p.points for p in drawing.primitives if isinstance(p, Polyline) and p.stroke is Stroke.THIN]
    for pts in axes:
        (x0, y0), (x1, y1) = pts
        d = (x1 - x0, y1 - y0)
        n = math.hypot(*d)
        along = [
            q
            for q in thin
            if len(q) == 2
            and abs((q[1][0] - q[0][0]) * d[1] - (q[1][1] - q[0][1]) * d[0]) < 1e-3 * n
            and abs((q[0][0] - x0) * d[1] - (q[0][1] - y0) * d[0]) < 1e-2 * n
            and math.dist(*q) > 0.3
        ]
        assert not along, f"a second arrow along the axis {pts}"


def test_oblique_default_pose_shows_no_link_end_on() -> None:
    """SCARA's arm at +40 degrees points at the viewer of the oblique view (seen at 0.4 of its length);
    the figure takes the sign pattern that shows every link at least half its length, and says so."""
    from tutgen.figure.build import END_ON, foreshortening
    from tutgen.figure.canvas import POSE_SIGNS

    system = load_system(SPECS / "arms" / "scara.yaml")
    first = SystemBuilder(system, POSE_SIGNS[0])
    first.build()
    assert foreshortening(first) < END_ON  # the problem is real at the first pose
    drawing = draw_system(system)
    assert any("end-on" in r for r in drawing.remarks)
    drawn = dict(drawing.at)
    chosen = next(s for s in POSE_SIGNS if math.copysign(1, drawn["q1"]) == s[0] and s != POSE_SIGNS[0])
    again = SystemBuilder(system, chosen)
    again.build()
    assert foreshortening(again) >= END_ON


def test_unknown_centres_of_mass_sit_on_their_frames_and_no_spokes_are_drawn() -> None:
    """Stanford's coms are unknown points (cx_i, cy_i, cz_i): drawn on each body's frame origin, so
    the links are bars between joints and the default pose no longer folds two of them together."""
    system = load_system(SPECS / "arms" / "stanford.yaml")
    builder = SystemBuilder(system)
    drawing = builder.build()
    sizes = dict(drawing.sizes)
    assert all(sizes[f"c{axis}{i}"] == 0.0 for axis in "xyz" for i in range(1, 7))
    for body in system.bodies:
        (part,) = body.parts
        assert np.allclose(builder.pose.point(body.name, builder.num.vec(part.at)), builder.pose.frames[body.name][0])
    assert not any("every default pose" in r for r in draw_system(system).remarks)
    # a com that is a real length (p03: the bob at l below the pivot) keeps its size
    p03 = SystemBuilder(load_system(SPECS / "tutorial-1" / "p03-cart-pendulum.yaml"))
    p03.build()
    assert dict(p03.sizes)["l"] > 0


def test_parts_are_drawn_back_to_front_whatever_the_spec_order() -> None:
    """p01 with its parts listed front first (point mass, cylinder, block): the block, farthest from
    the viewer, is still drawn first, so the cylinder's white outline hides the block's face behind
    it; and the drawing is the same as with the spec's own order."""
    from tutgen.figure.scene import Fill
    from tutgen.spec.validate import load_system_text

    path = P01
    text = path.read_text()
    block = "      block: {shape: box, size: [5 cm, 15 cm, 5 cm], density: rho}\n"
    point = "      point: {shape: point, mass: m_p, at: [10 cm, 0, 0]}\n"
    assert block in text and point in text
    lines = text.replace(block, "").replace(point, "").splitlines(keepends=True)
    at = next(i for i, ln in enumerate(lines) if ln.startswith("      cylinder:"))
    lines[at:at] = [point]  # the point mass first, then the cylinder, then the block
    lines.insert(at + 2, block)
    reordered = "".join(lines)
    assert reordered.index("point:") < reordered.index("cylinder:") < reordered.index("block:")
    front_first = draw_system(load_system_text(reordered))
    own = draw_system(load_system(path))
    hulls = [p for p in front_first.primitives if isinstance(p, Polyline) and p.closed and p.fill is Fill.WHITE]
    own_hulls = [p for p in own.primitives if isinstance(p, Polyline) and p.closed and p.fill is Fill.WHITE]
    assert hulls == own_hulls and len(hulls) == 2
    # the block's hull (8 corners' hull: 6 points) first, the cylinder's (many rim points) after it
    assert len(hulls[0].points) == 6 and len(hulls[1].points) > 6
    dots = [i for i, p in enumerate(front_first.primitives) if getattr(p, "fill", None) is Fill.BLACK]
    assert dots and dots[0] > front_first.primitives.index(hulls[1])  # the point mass, nearest, last
