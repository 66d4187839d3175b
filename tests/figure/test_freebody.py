"""Free-body diagrams (tutgen/figure/freebody.py): the forces on each body, from the model, checked
against hand-drawn diagrams of the tutorial's problems, and their drawing."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from functools import cache
from pathlib import Path

import pytest
import sympy as sp
from typer.testing import CliRunner

from tests.conftest import SPECS, all_specs
from tutgen.cli.main import app
from tutgen.figure.build import draw_system
from tutgen.figure.freebody import FORCE_LENGTH, BodyForce, Frame, body_forces, free_body_diagram
from tutgen.figure.scene import Polyline, Stroke
from tutgen.figure.texlabel import is_safe_tex
from tutgen.model.system import System
from tutgen.spec.validate import load_system

P03 = SPECS / "tutorial-1" / "p03-cart-pendulum.yaml"
P05 = SPECS / "tutorial-1" / "p05-rr-arm.yaml"


@cache
def system_of(key: str) -> System:
    folder, stem = key.split(":")
    return load_system(SPECS / folder / f"{stem}.yaml")


@cache
def planar_keys() -> list[str]:
    keys = []
    for path in all_specs():
        key = f"{path.parent.name}:{path.stem}"
        if path.parent.name == "arms" and path.stem != "planar-4r":
            continue  # spatial arms: not planar, and heavy to load
        system = system_of(key)
        if system.bodies and draw_system(system).view == "planar":
            keys.append(key)
    return keys


def _vec(force: BodyForce) -> tuple[sp.Expr, ...]:
    return tuple(sp.sympify(v) for v in force.vector)


def _symbols(system: System, names: str) -> list[sp.Symbol]:
    """The spec's own symbols (with their assumptions), by name."""
    table = {p.name: p.symbol for p in system.parameters} | {c.name: c.q for c in system.coordinates}
    return [table[n] for n in names.split()]


def _by_name(system: System, body: str) -> dict[str, BodyForce]:
    return {f.name: f for f in body_forces(system, body)}


def test_body_forces_of_the_cart_of_p03_as_drawn_by_hand() -> None:
    """p03's cart: its weight, the spring pulling it back, the push, the rail's normal force and
    moment, the pendulum's pin force reversed, and the motor's reaction."""
    system = load_system(P03)
    m1, g, k, x, tau, f = _symbols(system, "m1 g k x tau F")
    forces = _by_name(system, "cart")
    assert set(forces) == {
        "gravity",
        "spring:wall",
        "load:push",
        "load:motor:reaction",
        "reaction:pivot:x",
        "reaction:pivot:y",
        "reaction:slider:normal",
        "reaction:slider:moment",
    }
    assert _vec(forces["gravity"]) == (0, -m1 * g, 0) and forces["gravity"].label == m1 * g
    assert _vec(forces["spring:wall"]) == (-1, 0, 0) and forces["spring:wall"].label == k * x
    assert _vec(forces["load:push"])[0] == f
    motor = forces["load:motor:reaction"]
    assert motor.moment and _vec(motor) == (0, 0, -tau)
    assert _vec(forces["reaction:pivot:x"]) == (-1, 0, 0) and _vec(forces["reaction:pivot:y"]) == (0, -1, 0)
    assert _vec(forces["reaction:slider:normal"]) == (0, 1, 0) and forces["reaction:slider:moment"].moment


def test_body_forces_of_the_pendulum_of_p03_as_drawn_by_hand() -> None:
    system = load_system(P03)
    m2, g, length, tau = _symbols(system, "m2 g l tau")
    forces = _by_name(system, "pendulum")
    assert set(forces) == {"gravity", "load:motor", "reaction:pivot:x", "reaction:pivot:y"}
    assert tuple(sp.sympify(v) for v in forces["gravity"].at) == (0, -length, 0)  # at the end mass
    assert _vec(forces["gravity"]) == (0, -m2 * g, 0)
    assert _vec(forces["load:motor"]) == (0, 0, tau)
    assert _vec(forces["reaction:pivot:x"]) == (1, 0, 0) and forces["reaction:pivot:x"].label == "R_2x"


def test_body_forces_of_p05_link1_carry_the_elbow_torque_reversed() -> None:
    system = load_system(P05)
    forces = _by_name(system, "link1")
    tau1, tau2 = _symbols(system, "tau1 tau2")
    assert _vec(forces["drive:theta1"]) == (0, 0, tau1)
    assert _vec(forces["drive:theta2"]) == (0, 0, -tau2)  # link 2's drive pushes back on link 1
    assert forces["drive:theta2"].at_frame is Frame.BODY
    assert {f.name for f in body_forces(system, "link2")} >= {"drive:theta2", "reaction:elbow:x"}


@pytest.mark.parametrize("key", planar_keys())
def test_reactions_are_equal_and_opposite_on_the_two_bodies_of_a_joint(key: str) -> None:
    """Newton's third law: a joint's reactions on its parent are those on its child reversed, with the
    same labels, at the same world point (the parent's joint origin)."""
    system = system_of(key)
    for joint in system.joints:
        if joint.parent == "ground":
            continue
        on_child = {f.name: f for f in body_forces(system, joint.child) if f.name.startswith(f"reaction:{joint.name}:")}
        on_parent = {
            f.name: f for f in body_forces(system, joint.parent) if f.name.startswith(f"reaction:{joint.name}:")
        }
        assert on_child and set(on_child) == set(on_parent)
        for name, f in on_child.items():
            p = on_parent[name]
            assert p.label == f.label
            if f.frame is p.frame is Frame.WORLD:
                assert tuple(-sp.sympify(v) for v in f.vector) == _vec(p)
            assert tuple(p.at) == tuple(joint.origin_offset)


@pytest.mark.parametrize("key", planar_keys())
def test_free_body_diagram_names_every_force_and_labels_do_not_overlap(key: str) -> None:
    system = system_of(key)
    for body in system.bodies:
        if not body.parts:
            continue
        drawing = free_body_diagram(system, body.name)
        names = drawing.names
        forces = body_forces(system, body.name)
        drawn = {f"force:{f.name}" for f in forces}
        missing = sorted(n for n in drawn if n not in names and not any(n in r for r in drawing.remarks))
        assert not missing, f"{key}/{body.name}: not named: {missing}"
        assert any(n == f"body:{body.name}" or n.startswith(f"body:{body.name}/") for n in names)
        labels = drawing.labels
        for i, a in enumerate(labels):
            assert is_safe_tex(a.tex), a.tex
            assert a.box.inside(drawing.bbox), f"{key}/{body.name}: {a.names} leaves the picture"
            for b in labels[i + 1 :]:
                assert not a.box.overlaps(b.box), f"{key}/{body.name}: {a.names} and {b.names} overlap"


def test_free_body_diagram_draws_a_given_force_at_its_point() -> None:
    """A caller's own list (the engine's Newton–Euler names its forces): the arrow ends at the point
    of application, and its label is the caller's name typeset."""
    system = load_system(P05)
    (a1,) = _symbols(system, "a1")
    push = BodyForce("contact", "N_A", at=(a1, 0, 0), vector=(0, 1, 0), frame=Frame.WORLD)
    drawing = free_body_diagram(system, "link1", [push])
    (label,) = [lb for lb in drawing.labels if lb.names == "force:contact"]
    assert label.tex == "N_{A}"
    reference = free_body_diagram(system, "link1", [])
    new = [p for p in drawing.primitives if p not in reference.primitives]
    shaft = [p for p in new if isinstance(p, Polyline) and p.stroke is Stroke.ARROW]
    assert len(shaft) == 1
    tail, tip = shaft[0].points
    # the elbow (a1 along link 1) is where link 1's bar ends; the arrow's tip is there, its tail below
    bars = [p for p in reference.primitives if isinstance(p, Polyline) and p.stroke is Stroke.BAR]
    ends = {pt for bar in bars for pt in bar.points}
    assert min(math.dist(tip, e) for e in ends) < 0.02
    assert tip[1] > tail[1] and abs(tip[0] - tail[0]) < 1e-6  # world +y: straight up the page
    assert "force:contact" in drawing.names and "force:gravity" not in drawing.names


def test_free_body_diagram_label_never_runs_tex_from_the_caller() -> None:
    system = load_system(P05)
    bad = BodyForce("bad", "\\input{/etc/passwd}", vector=(1, 0, 0))
    worse = BodyForce("worse", sp.Symbol("x") + 1, vector=(1, 0, 0))  # not a product: the name instead
    drawing = free_body_diagram(system, "link2", [bad, worse])
    tex = {lb.names: lb.tex for lb in drawing.labels}
    assert all(is_safe_tex(t) for t in tex.values())
    assert "\\input" not in tex["force:bad"] and tex["force:worse"] == "\\mathrm{worse}"


def test_free_body_diagram_of_an_unknown_body_names_the_bodies() -> None:
    with pytest.raises(ValueError, match=r"no body 'nope' \(bodies: cart, pendulum\)"):
        free_body_diagram(load_system(P03), "nope")


def test_free_body_diagram_is_the_same_on_every_run() -> None:
    system = load_system(P03)
    assert free_body_diagram(system, "cart") == free_body_diagram(load_system(P03), "cart")


def test_cli_figure_body_writes_the_free_body_diagram(tmp_path: Path) -> None:
    runner = CliRunner()
    out = tmp_path / "cart.svg"
    result = runner.invoke(app, ["figure", str(P03), "--body", "cart", "-o", str(out)])
    assert result.exit_code == 0, result.output
    root = ET.fromstring(out.read_bytes())  # well-formed
    assert root.tag.endswith("svg") and "R" in out.read_text()
    bad = runner.invoke(app, ["figure", str(P03), "--body", "nope", "-o", str(tmp_path / "x.svg")])
    assert bad.exit_code == 2 and "no body 'nope'" in bad.output and not (tmp_path / "x.svg").exists()


def test_free_body_views_give_each_body_its_tikz_and_svg() -> None:
    from tutgen.figure.view import free_body_views

    system = load_system(P03)
    views = free_body_views(system)
    assert [v["body"] for v in views] == ["cart", "pendulum"]
    assert views[0]["svg"] == "p03-cart-pendulum.fbd-cart.svg"
    assert "\\begin{tikzpicture}" in views[0]["tikz"] and "<svg" in views[0]["svg_text"]
    assert "force:spring:wall" in views[0]["labels"]
    own = free_body_views(system, {"cart": [BodyForce("only", "Q", vector=(1, 0, 0))]})
    assert "force:only" in own[0]["labels"] and "force:spring:wall" not in own[0]["labels"]
    assert free_body_views(system_of("tutorial-1:p08-spatial-rr")) == []  # spatial: none


def _arrows(drawing: object, reference: object) -> list[tuple[tuple[float, float], tuple[float, float]]]:
    """The force arrows' shafts (tail, tip) of ``drawing`` that ``reference`` does not have (a force
    arrow is FORCE_LENGTH long; the world axes' are shorter)."""
    return [
        (p.points[0], p.points[-1])
        for p in drawing.primitives  # type: ignore[attr-defined]
        if isinstance(p, Polyline)
        and p.stroke is Stroke.ARROW
        and len(p.points) == 2
        and abs(math.dist(p.points[0], p.points[-1]) - FORCE_LENGTH) < 1e-3
        and p not in reference.primitives  # type: ignore[attr-defined]
    ]


def test_pin_reaction_is_drawn_as_two_components_along_the_axes() -> None:
    """A reaction of unknown components (R_x, R_y), as the Newton–Euler step hands it over, is drawn
    as a textbook draws it: one horizontal and one vertical arrow, each named by its component (the
    step's R_{pivot,x}, R_{pivot,y}), reversed on the parent where the components are negated."""
    system = load_system(P03)
    rx, ry = sp.Symbol("R[pivot].x"), sp.Symbol("R[pivot].y")
    name = "reaction at joint 'pivot'"
    for body, sign in (("pendulum", 1), ("cart", -1)):
        force = BodyForce(name, "pivot", vector=(sign * rx, sign * ry, 0), frame=Frame.WORLD, tex="\\mathbf{R}_{p}")
        drawing = free_body_diagram(system, body, [force])
        tex = {lb.names: lb.tex for lb in drawing.labels if lb.names.startswith("force:")}
        assert tex == {f"force:{name}/x": "R_{\\mathrm{pivot},x}", f"force:{name}/y": "R_{\\mathrm{pivot},y}"}
        assert f"force:{name}" in drawing.names  # the force itself is named, by its components
        shafts = _arrows(drawing, free_body_diagram(system, body, []))
        assert len(shafts) == 2, body
        horizontal = [s for s in shafts if abs(s[0][1] - s[1][1]) < 1e-6]
        vertical = [s for s in shafts if abs(s[0][0] - s[1][0]) < 1e-6]
        assert len(horizontal) == len(vertical) == 1, shafts
        (tail, tip), (vtail, vtip) = horizontal[0], vertical[0]
        assert (tip[0] - tail[0]) * sign > 0 and (vtip[1] - vtail[1]) * sign > 0  # +x, +y on the child


def test_slide_normal_force_is_named_as_the_step_names_it() -> None:
    system = load_system(P03)
    force = BodyForce("reaction at joint 'slider'", "slider", vector=(0, sp.Symbol("R[slider].n"), 0))
    drawing = free_body_diagram(system, "cart", [force])
    assert [lb.tex for lb in drawing.labels if lb.names.startswith("force:")] == ["N_{\\mathrm{slider}}"]


def test_a_force_that_is_not_of_unknown_components_stays_one_arrow() -> None:
    system = load_system(P03)
    k, x = sp.symbols("k x")
    drawing = free_body_diagram(system, "cart", [BodyForce("spring", k * x, vector=(-k * x, k * x, 0))])
    assert [lb.names for lb in drawing.labels if lb.names.startswith("force:")] == ["force:spring"]


def test_cart_arrows_on_one_face_stand_apart_and_the_block_fits_them() -> None:
    """p03's cart as the Newton–Euler step draws it (10 arrows): no two force arrows cross or lie on
    one line, every arrow that pushes on the block ends on its outline, and the block is sized to
    the arrows on its faces (three on its right face: the spring, the inertial force, R_{pivot,x})."""
    from tests.conftest import solved
    from tutgen.render.sections.newton_euler import diagram_forces

    system, d, _ = solved(str(P03))
    (balance,) = [b for b in d.newton_euler.planar.balances if b.body == "cart"]
    forces = diagram_forces(balance, {c.name: c.latex for c in system.coordinates})
    drawing = free_body_diagram(system, "cart", forces)
    shafts = _arrows(drawing, free_body_diagram(system, "cart", []))
    assert len(shafts) == 7  # W, push, wall, N, R_x, R_y, inertial (the two couples are arcs)
    for i, (a, b) in enumerate(shafts):
        for c, e in shafts[i + 1 :]:
            assert not _cross(a, b, c, e), (a, b, c, e)
            # parallel arrows are at least 0.5 cm apart or do not overlap along their line
            if abs((b[0] - a[0]) * (e[1] - c[1]) - (b[1] - a[1]) * (e[0] - c[0])) < 1e-9:
                apart = abs((c[0] - a[0]) * (b[1] - a[1]) - (c[1] - a[1]) * (b[0] - a[0])) / math.dist(a, b)
                assert apart > 0.5 or _disjoint(a, b, c, e), (a, b, c, e)
    block = next(p for p in drawing.primitives if isinstance(p, Polyline) and p.closed and p.fill.value == "gray")
    xs, ys = [p[0] for p in block.points], [p[1] for p in block.points]
    right = [tip for tail, tip in shafts if abs(tip[0] - max(xs)) < 1e-3 and tail[0] > tip[0]]
    assert len(right) == 3 and all(min(ys) < tip[1] < max(ys) for tip in right)


def _cross(a: tuple[float, float], b: tuple[float, float], c: tuple[float, float], d: tuple[float, float]) -> bool:
    def side(p: tuple[float, float], q: tuple[float, float], r: tuple[float, float]) -> float:
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])

    return side(a, b, c) * side(a, b, d) < -1e-9 and side(c, d, a) * side(c, d, b) < -1e-9


def _disjoint(a: tuple[float, float], b: tuple[float, float], c: tuple[float, float], d: tuple[float, float]) -> bool:
    ux, uy = (b[0] - a[0]) / math.dist(a, b), (b[1] - a[1]) / math.dist(a, b)
    s = sorted(((c[0] - a[0]) * ux + (c[1] - a[1]) * uy, (d[0] - a[0]) * ux + (d[1] - a[1]) * uy))
    return s[0] >= math.dist(a, b) - 1e-6 or s[1] <= 1e-6


@pytest.mark.parametrize("spec", [p for p in all_specs() if "puma" not in p.name], ids=lambda p: p.stem)
def test_free_body_names_are_the_bodies_drawn(spec: Path) -> None:
    """A sheet plans its files from the names of the free bodies before any is drawn
    (render.sections.newton_euler.free_body_names, issue 17): the same bodies, in the same order."""
    from tests.conftest import solved
    from tutgen.render.sections.newton_euler import free_bodies, free_body_names

    d = solved(str(spec))[1]
    assert free_body_names(d) == [v["body"] for v in free_bodies(d)]
