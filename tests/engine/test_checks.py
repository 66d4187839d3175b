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
