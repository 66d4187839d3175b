"""Remarks that are true (issue 15 item 4): each sentence about a massless body is checked against the
result it comments on (the body's T and U, and H), not against the wording alone."""

from __future__ import annotations

import pytest
import sympy as sp

from tutgen.engine.pipeline import derive
from tutgen.spec.validate import load_system_text

FLYWHEEL = """
title: flywheel
parameters: [J, tau]
coordinates: [phi]
bodies:
  wheel: {mass: 0, inertia: {zz: J}}
joints:
  axle: {type: revolute, parent: ground, child: wheel, axis: z, coordinate: phi}
generalized_forces: {phi: tau}
"""

SLIDING_DISC = """
title: a massless disc that slides without turning, beside a block
parameters: [J, m, g]
coordinates: [x]
gravity: [0, -g, 0]
bodies:
  block: {mass: m}
  disc: {mass: 0, inertia: {zz: J}}
joints:
  slide: {type: prismatic, parent: ground, child: block, axis: x, coordinate: x}
  rail: {type: fixed, parent: block, child: disc}
"""

MASSLESS_POINT = """
title: a massless point beside a mass
parameters: [m, g]
coordinates: [y]
gravity: [0, -g, 0]
bodies:
  bob: {mass: m, position: [0, y, 0]}
  ghost: {mass: 0, position: [y, y, 0]}
"""


def _derive(text: str):
    return derive(load_system_text(text, "t.yaml"))


def _param(d, name: str) -> sp.Symbol:
    return next(p.symbol for p in d.system.parameters if p.name == name)


def _body_remarks(d, body: str) -> list[str]:
    return [r for r in d.remarks if r.startswith(f"Body '{body}'")]


def _check_claims(d) -> None:
    """Every massless-body remark agrees with that body's energies."""
    energy = {e.name: e for e in d.energies}
    for remark in d.remarks:
        if not remark.startswith("Body '"):
            continue
        name = remark.split("'")[1]
        e = energy[name]
        if "adds nothing to T, U or H" in remark:
            assert sp.simplify(e.kinetic) == 0 and sp.simplify(e.gravitational) == 0, remark
        if "adds nothing to U" in remark:
            assert sp.simplify(e.gravitational) == 0, remark
        if "still adds" in remark:
            assert sp.simplify(e.kinetic) != 0, remark


def test_remark_flywheel_is_not_said_to_add_nothing() -> None:
    d = _derive(FLYWHEEL)
    j, phi_dot = _param(d, "J"), d.system.coordinates[0].qd
    assert sp.simplify(d.mass_matrix - sp.Matrix([[j]])) == sp.zeros(1, 1)
    (remark,) = _body_remarks(d, "wheel")
    assert "adds nothing to T" not in remark
    assert "J phi_dot^2/2 to T" in remark
    assert sp.simplify(d.energies[0].kinetic - j * phi_dot**2 / 2) == 0
    _check_claims(d)


@pytest.mark.parametrize(
    ("text", "body", "wording"),
    [
        pytest.param(SLIDING_DISC, "disc", "has zero mass and does not turn", id="disc-that-does-not-turn"),
        pytest.param(MASSLESS_POINT, "ghost", "has zero mass and no moment of inertia", id="massless-point"),
    ],
)
def test_remark_massless_body_that_adds_nothing(text: str, body: str, wording: str) -> None:
    d = _derive(text)
    (remark,) = _body_remarks(d, body)
    assert wording in remark and "adds nothing to T, U or H" in remark
    _check_claims(d)
    # and H is that of the other body alone
    m = _param(d, "m")
    assert sp.simplify(d.mass_matrix - sp.Matrix([[m]])) == sp.zeros(1, 1)
