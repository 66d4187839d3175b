"""U source by source with its datum (issue 15 item 4): the terms add up to U, and each is zero where its
datum says, checked on the derivation of the tutorial's problems."""

from __future__ import annotations

import pytest
import sympy as sp

from tests.conftest import SPECS, solved

TUTORIAL = SPECS / "tutorial-1"


@pytest.mark.parametrize(
    "name",
    [
        "p03-cart-pendulum",
        "p04-rp-arm",
        "p05-rr-arm",
        "p06-two-prismatic",
        "p07-belt-driven-arm",
        "p08-spatial-rr",
        "p10-given-kinetic-energy",
    ],
)
def test_potential_sources_add_up_to_u(name: str) -> None:
    _, d, _ = solved(str(TUTORIAL / f"{name}.yaml"))
    total = sp.Add(*[src.energy for src in d.potential_sources])
    assert sp.simplify(total - d.potential_energy) == 0
    assert d.potential_sources, "a problem with a U states where it comes from"


@pytest.mark.parametrize(
    ("name", "datum"),
    [
        pytest.param("p03-cart-pendulum", "zero at y = 0, the level of joint 'pivot'", id="p03"),
        pytest.param("p05-rr-arm", "zero at y = 0, the level of joint 'shoulder'", id="p05"),
        pytest.param("p08-spatial-rr", "zero at z = 0, the level of joints 'waist' and 'shoulder'", id="p08"),
        pytest.param("p06-two-prismatic", "zero at y = 0", id="p06-no-pivot"),
    ],
)
def test_potential_gravity_datum_is_where_it_vanishes(name: str, datum: str) -> None:
    system, d, _ = solved(str(TUTORIAL / f"{name}.yaml"))
    gravity = [src for src in d.potential_sources if src.kind == "gravity"]
    assert gravity and all(src.datum == datum for src in gravity)
    axis, zero = gravity[0].zero_at
    k = "xyz".index(str(axis))
    g = sp.Matrix(system.gravity)
    assert [i for i in range(3) if g[i] != 0] == [k]
    masses = {bi.name: bi.mass for bi in d.inertia}
    for src in gravity:
        kin = next(b for b in d.kinematics if b.name == src.name)
        # U_b = -m g . r_G: it is zero exactly where the centre of mass is on the datum plane
        assert sp.simplify(src.energy + masses[src.name] * g[k] * kin.com[k]) == 0
        assert zero == 0


def test_potential_spring_is_zero_at_its_free_length() -> None:
    system, d, _ = solved(str(TUTORIAL / "p03-cart-pendulum.yaml"))
    (spring,) = [src for src in d.potential_sources if src.kind == "spring"]
    lhs, rhs = spring.zero_at
    x = system.coordinates[0].q
    assert lhs == x and rhs == 0
    assert spring.energy.subs(x, 0) == 0
    assert sp.diff(spring.energy, x).subs(x, 0) == 0  # a minimum: the free length
