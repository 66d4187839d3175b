"""A drawing is shared by the systems that differ only in values it does not read (issue 17: a sheet's
variants that differ in their masses draw one figure). Sound only if every number a drawing uses is
recorded as read: changing any parameter it did not read must leave a fresh drawing unchanged."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest
import sympy as sp

from tests.conftest import SPECS, all_specs
from tutgen.figure import build as figure_build
from tutgen.figure import freebody
from tutgen.figure.pose import reading
from tutgen.model.system import System
from tutgen.spec.validate import load_system


def valued(system: System, scale: sp.Expr = sp.S.One, only: set[sp.Basic] | None = None) -> System:
    """``system`` with every parameter (or those in ``only``) at a number: its own value times ``scale``,
    or ``scale`` times 0.7 for a symbolic one."""
    params = []
    for p in system.parameters:
        if only is not None and p.symbol not in only:
            params.append(p)
            continue
        base = p.value if p.value is not None and p.value.is_number else sp.Float(0.7)
        params.append(dataclasses.replace(p, value=sp.nsimplify(base) * scale))
    return dataclasses.replace(system, parameters=tuple(params))


def fresh_and_reads(system: System) -> tuple[object, set[sp.Basic]]:
    with reading() as read:
        drawing = figure_build._draw_system(system)
    return drawing, read


@pytest.mark.parametrize("path", all_specs(), ids=lambda p: str(p.relative_to(SPECS)))
def test_what_a_drawing_does_not_read_does_not_change_it(path: Path) -> None:
    system = valued(load_system(path))
    drawing, read = fresh_and_reads(system)
    unread = {p.symbol for p in system.parameters} - read
    if not unread:
        pytest.skip("the drawing reads every parameter")
    for scale in (sp.Rational(13, 10), sp.Rational(-7, 10)):  # larger, and of the other sign (a load's arrow)
        other = valued(system, scale, only=unread)
        assert figure_build._draw_system(other) == drawing, (scale, sorted(map(str, unread)))


def test_a_sheets_variants_share_a_drawing_when_only_their_masses_differ(monkeypatch: pytest.MonkeyPatch) -> None:
    drawn: list[System] = []
    draw = figure_build._draw_system

    def counting(system: System) -> object:
        drawn.append(system)
        return draw(system)

    monkeypatch.setattr(figure_build, "_draw_system", counting)
    monkeypatch.setattr(figure_build, "_BY_READS", {})
    base = load_system(SPECS / "tutorial-1" / "p05-rr-arm.yaml")
    masses = {p.symbol for p in base.parameters if p.name.startswith("m")}
    a1 = {p.symbol for p in base.parameters if p.name == "a1"}
    a = valued(base)
    b = valued(a, sp.Integer(3), only=masses)  # other masses: the same figure
    c = valued(a, sp.Integer(2), only=a1)  # another first link: another figure
    first = figure_build.draw_system(a)
    assert figure_build.draw_system(b) is first
    assert len(drawn) == 1
    assert figure_build.draw_system(c) != first
    assert len(drawn) == 2
    assert draw(b) == first  # what was shared is what a fresh drawing gives


def test_free_body_diagrams_are_shared_the_same_way(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(figure_build, "_BY_READS", {})
    base = valued(load_system(SPECS / "tutorial-1" / "p03-cart-pendulum.yaml"))
    cart = {p.symbol for p in base.parameters if p.name == "m1"}
    heavier = valued(base, sp.Integer(2), only=cart)  # the cart's mass: not the pendulum's diagram
    first = freebody.free_body_diagram(base, "pendulum")
    assert freebody.free_body_diagram(heavier, "pendulum") is first
    assert freebody._FreeBodyBuilder(heavier, "pendulum", None).build() == first


def test_a_free_body_diagram_reads_only_the_sign_of_a_forces_factor(monkeypatch: pytest.MonkeyPatch) -> None:
    """An arrow shows a force's direction: the mass and g that multiply the weight are read as positive
    only, so a sheet's variants of p03 share the cart's diagram; a negative value does not."""
    monkeypatch.setattr(figure_build, "_BY_READS", {})
    base = valued(load_system(SPECS / "tutorial-1" / "p03-cart-pendulum.yaml"))
    by_name = {p.name: p.symbol for p in base.parameters}
    factors = {by_name["m1"], by_name["g"]}
    with reading() as read:
        first = freebody.free_body_diagram(base, "cart")
    assert {figure_build.Positive(s) for s in factors} <= read
    assert not factors & read  # their values are not read
    larger = valued(base, sp.Rational(13, 10), only=factors)
    assert freebody.free_body_diagram(larger, "cart") is first
    assert freebody._FreeBodyBuilder(larger, "cart", None).build() == first  # what is shared is what a fresh one is
    heavier_down = valued(base, sp.Rational(-7, 10), only={by_name["m1"]})  # the weight points up
    other = freebody.free_body_diagram(heavier_down, "cart")
    assert other is not first
    assert other != first
    assert other == freebody._FreeBodyBuilder(heavier_down, "cart", None).build()


def test_the_newton_euler_steps_diagrams_are_shared_across_masses_and_stiffnesses(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The step's forces (k x, m1 x_ddot, m2 (...)): other masses and stiffness, the same diagrams."""
    from tutgen.engine.pipeline import derive
    from tutgen.render.sections.newton_euler import _drawn_balances, diagram_forces

    monkeypatch.setattr(figure_build, "_BY_READS", {})
    base = valued(load_system(SPECS / "tutorial-1" / "p03-cart-pendulum.yaml"))
    d = derive(base)
    coords = {c.name: c.latex for c in d.system.coordinates}
    forces = {b.body: diagram_forces(b, coords) for b in _drawn_balances(d)}
    assert set(forces) == {"cart", "pendulum"}
    by_name = {p.name: p.symbol for p in base.parameters}
    other = valued(base, sp.Rational(13, 10), only={by_name["m1"], by_name["m2"], by_name["k"]})
    for body, given in forces.items():
        first = freebody.free_body_diagram(base, body, given)
        assert freebody.free_body_diagram(other, body, given) is first
        assert freebody._FreeBodyBuilder(other, body, given).build() == first
