"""The engine's checks on its own results: a positive semi-definite H, consistent dimensions."""

from __future__ import annotations

import dataclasses

import pytest
import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.engine.checks import dimension_checks, mass_matrix_checks, verify
from tutgen.engine.pipeline import derive
from tutgen.errors import DerivationError
from tutgen.spec.validate import load_system_text

WITH_UNITS = """
tutgen: 1
title: cart pendulum with units
parameters: {m: {dimension: mass}, l: {dimension: length}, g: {dimension: acceleration},
             k: {dimension: stiffness}, F: {dimension: force}}
coordinates: [x, theta]
gravity: [0, -g, 0]
bodies: {cart: {mass: m}, bob: {mass: m, com: [0, -l, 0]}}
joints:
  s: {type: prismatic, parent: ground, child: cart, axis: x, coordinate: x}
  pivot: {type: revolute, parent: cart, child: bob, axis: z, coordinate: theta}
springs: {w: {stiffness: k, extension: x}}
loads: {push: {body: cart, force: [F, 0, 0]}}
"""


@pytest.fixture(scope="module")
def with_units():
    system = load_system_text(WITH_UNITS, "units.yaml")
    return system, derive(system, "lagrange")


def test_checks_dimensions_of_every_term_agree(with_units) -> None:
    system, derivation = with_units
    [check] = dimension_checks(system, derivation)
    assert check.passed and "'x', 'theta'" in check.detail
    assert any(c.name == "dimensional_consistency" and c.passed for c in derivation.checks)


def test_checks_dimension_mismatch_names_equation_and_terms(with_units) -> None:
    system, derivation = with_units
    x = system.coordinates[0].q
    mass, length = (p.symbol for p in system.parameters if p.name in ("m", "l"))
    eom = derivation.equations_of_motion
    extra = mass * length * x  # kg*m^2 in an equation of forces (kg*m/s^2)
    broken = dataclasses.replace(derivation, equations_of_motion=sp.ImmutableMatrix([eom[0] + extra, eom[1]]))
    [check] = dimension_checks(system, broken)
    assert not check.passed
    assert "the equation for 'x'" in check.detail and "kg*m^2" in check.detail
    with pytest.raises(DerivationError, match=r"internal check failed: in the equation for 'x'.*please report") as info:
        verify(system, broken)
    assert info.value.location == system.coordinates[0].origin


def test_checks_unknown_dimensions_are_not_checked() -> None:
    system, derivation, _ = solved(str(SPECS / "tutorial-1" / "p05-rr-arm.yaml"))
    [check] = dimension_checks(system, derivation)
    assert check.passed and check.detail.startswith("dimensions not checked")


def test_checks_singular_mass_matrix_is_semidefinite() -> None:
    _, derivation, _ = solved(str(SPECS / "tutorial-1" / "p09-pr-manipulator.yaml"))
    [check] = mass_matrix_checks(derivation)
    assert check.passed and "semi-definite" in check.detail


def test_checks_indefinite_mass_matrix_fails(with_units) -> None:
    system, derivation = with_units
    broken = dataclasses.replace(derivation, mass_matrix=-derivation.mass_matrix)
    [check] = mass_matrix_checks(broken)
    assert not check.passed and "negative eigenvalue" in check.detail
    with pytest.raises(DerivationError, match=r"internal check failed: the mass matrix H has the negative"):
        verify(system, broken)


def test_checks_negative_mass_is_the_specs_fault() -> None:
    system = load_system_text(WITH_UNITS.replace("m: {dimension: mass}", "m: {value: -2 kg}"), "neg.yaml")
    with pytest.raises(DerivationError, match=r"a mass or inertia must not be negative \(given: m = -2\)") as info:
        derive(system, "lagrange")
    assert "report" not in str(info.value)


SERIAL_WITH_UNITS = """
tutgen: 1
title: spatial RRPR arm with units
parameters: {m1: {dimension: mass}, m2: {dimension: mass}, m3: {dimension: mass}, m4: {dimension: mass},
             l1: {dimension: length}, l2: {dimension: length}, c3: {dimension: length},
             I1: {dimension: inertia}, I2: {dimension: inertia}, I3: {dimension: inertia}, I4: {dimension: inertia},
             g: {dimension: acceleration}, tau1: {dimension: torque}, F3: {dimension: force}}
coordinates: {q1: {}, q2: {}, d3: {dimension: length}, q4: {}}
gravity: [0, 0, -g]
bodies:
  b1: {mass: m1, com: [0, 0, l1], inertia: {zz: I1}}
  b2: {mass: m2, com: [l2, 0, 0], inertia: {xx: I2, yy: I2, zz: I2}}
  b3: {mass: m3, com: [c3, 0, 0], inertia: {yy: I3, zz: I3, xy: I3}}
  b4: {mass: m4, com: [0, 0, c3], inertia: {xx: I4, zz: I4}}
joints:
  j1: {type: revolute, parent: ground, child: b1, axis: z, coordinate: q1,
       motor: {rotor_inertia: 0.002 kg*m^2, gear_ratio: 50}}
  j2: {type: revolute, parent: b1, child: b2, axis: y, origin: [0, 0, l1], coordinate: q2}
  j3: {type: prismatic, parent: b2, child: b3, axis: x, origin: [l2, 0, 0], coordinate: d3}
  j4: {type: revolute, parent: b3, child: b4, axis: x, coordinate: q4}
generalized_forces: {q1: tau1, d3: F3}
"""


def test_serial_route_checks_dimensions_on_monomials(monkeypatch: pytest.MonkeyPatch) -> None:
    """A large serial arm with units (a prismatic joint, a motor whose rotor inertia is a number): every
    term agrees, checked on the equations with H's and C's entries as their monomials (no trigonometric
    factor, nothing written out), as before on H's entries written out."""
    from tutgen.engine import pipeline

    seen: list[sp.MatrixBase] = []
    original = pipeline.dimension_checks

    def recording(system, derivation):  # type: ignore[no-untyped-def]
        seen.append(derivation.equations_of_motion)
        return original(system, derivation)

    monkeypatch.setattr(pipeline, "dimension_checks", recording)
    system = load_system_text(SERIAL_WITH_UNITS, "arm.yaml")
    d = derive(system)
    [check] = [c for c in d.checks if c.name == "dimensional_consistency"]
    assert check.passed and check.detail == "every term agrees in the equations for 'q1', 'q2', 'd3', 'q4'"
    [sized] = seen
    for e in sized:  # the coefficients of the accelerations: H's entries, as monomials
        assert all(not e.coeff(c.qdd).has(sp.sin, sp.cos) for c in system.coordinates), e
    assert any(e.coeff(c.qdd) != 0 for e in sized for c in system.coordinates)
