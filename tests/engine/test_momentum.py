"""Issue 18, momentum: angular momenta against sympy.physics.mechanics' ``RigidBody.angular_momentum`` /
``Particle.angular_momentum`` of a twin built from the validated model (tests/engine/test_mechanics_generic.py),
the skewed rotor's bearing moment against its closed form, and the conserved quantities."""

from __future__ import annotations

import math

import pytest
import sympy as sp

from tests.conftest import SPECS, solved
from tests.engine.test_mechanics_generic import MechanicsModel
from tests.models import system_of
from tutgen.engine.pipeline import derive

ROTOR = str(SPECS / "examples" / "k-rotor-skewed-disc.yaml")
CART = str(SPECS / "examples" / "h-inverted-pendulum-cart.yaml")


def _state(system, seed: int) -> dict[str, float]:
    """A state by name: parameters at their values, else 1.3; q and q_dot fixed non-special values."""
    state = {p.name: float(p.value) if p.value is not None else 1.3 for p in system.parameters}
    for i, c in enumerate(system.coordinates):
        state[c.name] = 0.4 + 0.7 * i + 0.1 * seed
        state[f"{c.name}_dot"] = -0.9 + 0.5 * i + 0.2 * seed
    return state


def _ours(expr, state) -> list[float]:
    names = {s: state[s.name] for s in expr.free_symbols}
    return [float(sp.N(e.xreplace(names))) for e in expr]


@pytest.mark.parametrize("spec", [ROTOR, CART], ids=["rotor", "cart"])
def test_angular_momentum_matches_sympy_mechanics(spec: str) -> None:
    system, d, _ = solved(spec)
    mo = d.analysis.momentum if d.analysis is not None and d.analysis.momentum is not None else None
    if mo is None:  # the cart does not ask for momentum: derive it on purpose
        import dataclasses

        from tutgen.model.system import Ask

        d = derive(dataclasses.replace(system, ask=system.ask | {Ask.MOMENTUM}))
        mo = d.analysis.momentum
    model = MechanicsModel(system)
    bodies, _ = model.bodies_and_loads()
    for seed in range(2):
        state = _state(system, seed)
        to_ref = {sp.Symbol(k): v for k, v in state.items()}
        # the twin's points move with q(t)' and its frames turn with u(t): both are the rate
        to_ref |= {q.diff(model.t): state[f"{c.name}_dot"] for q, c in zip(model.qs, system.coordinates, strict=True)}
        to_ref |= {q: state[c.name] for q, c in zip(model.qs, system.coordinates, strict=True)}
        to_ref |= {u: state[f"{c.name}_dot"] for u, c in zip(model.us, system.coordinates, strict=True)}
        total = sum((b.angular_momentum(model.o, model.n_frame) for b in bodies), sp.S(0) * model.n_frame.x)
        theirs = [float(sp.N(total.dot(axis).xreplace(to_ref))) for axis in model.n_frame]
        assert _ours(d.numeric(mo.angular_origin), state) == pytest.approx(theirs, abs=1e-12)
        for b, ref in zip(mo.bodies, bodies, strict=True):
            about_g = ref.angular_momentum(ref.masscenter, model.n_frame)
            theirs_g = [float(sp.N(about_g.dot(axis).xreplace(to_ref))) for axis in model.n_frame]
            assert _ours(d.numeric(b.angular_com), state) == pytest.approx(theirs_g, abs=1e-12)


def test_skewed_rotor_bearing_moment_closed_form() -> None:
    """Running steadily at w, the bearings carry (J_a - J_t) w^2 sin(beta) cos(beta), turning with the
    shaft: J_a = m r^2/2, J_t = m r^2/4 for a thin disc."""
    system, d, doc = solved(ROTOR)
    steady = d.numeric(d.analysis.momentum.steady_support_moment)
    phi, w = system.coordinates[0].q, system.coordinates[0].qd
    m, r, beta = 2.0, 0.1, math.radians(10)
    amplitude = (m * r**2 / 2 - m * r**2 / 4) * math.sin(beta) * math.cos(beta)
    at = {phi: 0.3, w: 7.0}
    got = [float(sp.N(e.xreplace(at))) for e in steady]
    assert got == pytest.approx([amplitude * 49 * math.cos(0.3), amplitude * 49 * math.sin(0.3), 0.0], abs=1e-12)
    assert len(doc["results"]["momentum"]["steady_support_moment"]) == 3


def test_conserved_momentum_of_a_free_cart_and_its_energy() -> None:
    spec = {
        "tutgen": 1,
        "title": "free cart and pendulum",
        "parameters": ["M", "m", "l", "g"],
        "coordinates": {"x": {"dimension": "length"}, "theta": {"dimension": "angle"}},
        "gravity": [0, "-g", 0],
        "bodies": {"cart": {"mass": "M"}, "bob": {"mass": "m", "com": [0, "-l", 0]}},
        "joints": {
            "rail": {"type": "prismatic", "parent": "ground", "child": "cart", "axis": "x", "coordinate": "x"},
            "hinge": {"type": "revolute", "parent": "cart", "child": "bob", "axis": "z", "coordinate": "theta"},
        },
        "ask": ["momentum"],
    }
    d = derive(system_of(spec))
    mo = d.analysis.momentum
    names = [q.name for q in mo.conserved]
    assert names == ["p_x", "E"]
    # x is cyclic: its conjugate momentum is the total linear momentum along x (independently summed)
    assert sp.simplify(mo.conserved[0].value - mo.linear[0]) == 0
    assert sp.simplify(mo.conserved[1].value - (d.kinetic_energy + d.potential_energy)) == 0


def test_momentum_of_a_given_energy_is_a_spec_error() -> None:
    from tutgen.errors import SpecErrors

    spec = {"tutgen": 1, "title": "e", "coordinates": ["x"], "energy": {"kinetic": "x_dot**2/2"}, "ask": ["momentum"]}
    with pytest.raises(SpecErrors, match="`momentum` needs bodies"):
        system_of(spec)
