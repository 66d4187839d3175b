"""Symbolic parameters are positive (masses, lengths); one with a zero or negative value is not."""

from __future__ import annotations

import pytest

from tutgen.engine.pipeline import derive
from tutgen.render.jsonout import derivation_to_json
from tutgen.spec.validate import load_system_text

SPEC = """
title: A point mass placed by a parameter
parameters: {{a: {value}, m: 1 kg}}
bodies:
  b:
    parts:
      p: {{shape: point, mass: m, at: [a, 0, 0]}}
"""


@pytest.mark.parametrize(
    ("value", "distance", "positive"),
    [
        pytest.param("-20 cm", 0.2, False, id="negative"),
        pytest.param("20 cm", 0.2, True, id="positive"),
        pytest.param("0", 0.0, False, id="zero"),
    ],
)
def test_parameter_sign_follows_its_value(value: str, distance: float, positive: bool) -> None:
    system = load_system_text(SPEC.format(value=value))
    a = next(p for p in system.parameters if p.name == "a")
    assert bool(a.symbol.is_positive) is positive
    doc = derivation_to_json(derive(system))
    part = doc["results"]["bodies"]["b"]["parts"]["p"]
    assert part["axis_distances"][1] == pytest.approx(distance)  # from the y axis: |x| = |a|
    assert part["inertia_tensor"][1][1] == pytest.approx(distance**2)


def test_symbolic_parameters_are_positive_and_forces_real() -> None:
    system = load_system_text("""
title: t
parameters: [m, F]
coordinates: [x]
bodies: {b: {mass: m, position: [x, 0, 0]}}
generalized_forces: {x: F}
""")
    by_name = {p.name: p.symbol for p in system.parameters}
    assert by_name["m"].is_positive
    assert by_name["F"].is_real and by_name["F"].is_positive is None
