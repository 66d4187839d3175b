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
