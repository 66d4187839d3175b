"""v^2 worked with the identities a teacher uses (issue 15 item 4), against the tutorial's printed v^2
(written here by hand from tutorial-1.md) and against the plain expansion at random states."""

from __future__ import annotations

import random

import pytest
import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.engine.kinematics import RULE_COS_DIFFERENCE, RULE_PYTHAGORAS, RULE_SIN_DIFFERENCE, speed_squared_steps

TUTORIAL = SPECS / "tutorial-1"


def _names(system) -> dict[str, sp.Symbol]:
    out = {p.name: p.symbol for p in system.parameters}
    for c in system.coordinates:
        out[c.name] = c.q
        out[f"{c.name}_dot"] = c.qd
    return out


def _tutorial_v2(name: str, n: dict[str, sp.Symbol]) -> sp.Expr:
    """The tutorial's v^2 of the second mass, as printed in tutorial-1.md (problems 5, 7 and 8)."""
    if name == "p05-rr-arm":
        a1, a2, w1, w2, t2 = n["a1"], n["a2"], n["theta1_dot"], n["theta2_dot"], n["theta2"]
        return a1**2 * w1**2 + a2**2 * (w1 + w2) ** 2 + 2 * a1 * a2 * (w1 + w2) * w1 * sp.cos(t2)
    if name == "p07-belt-driven-arm":
        l1, l2, w1, w2 = n["l1"], n["l2"], n["theta1_dot"], n["theta2_dot"]
        return l1**2 * w1**2 + l2**2 * w2**2 + 2 * l1 * l2 * w1 * w2 * sp.cos(n["theta2"] - n["theta1"])
    l1, l2, w1, w2, t2 = n["l1"], n["l2"], n["theta1_dot"], n["theta2_dot"], n["theta2"]
    return (l1 + l2 * sp.cos(t2)) ** 2 * w1**2 + l2**2 * w2**2


@pytest.mark.parametrize(
    ("name", "rules"),
    [
        pytest.param("p05-rr-arm", {RULE_PYTHAGORAS, RULE_COS_DIFFERENCE}, id="p05-relative-angles"),
        pytest.param("p07-belt-driven-arm", {RULE_PYTHAGORAS, RULE_COS_DIFFERENCE}, id="p07-absolute-angles"),
        pytest.param("p08-spatial-rr", {RULE_PYTHAGORAS}, id="p08-spatial"),
    ],
)
def test_speed_squared_uses_the_identity_and_gives_the_tutorial_v2(name: str, rules: set[str]) -> None:
    system, d, _ = solved(str(TUTORIAL / f"{name}.yaml"))
    k = next(b for b in d.kinematics if b.name == "link2")
    steps = k.speed
    assert steps is not None
    assert {i.rule for i in steps.identities} == rules
    for identity in steps.identities:  # each instance is a true identity
        assert sp.simplify(sp.expand_trig(identity.lhs - identity.rhs)) == 0
    tutorial = _tutorial_v2(name, _names(system))
    assert sp.simplify(steps.result - tutorial) == 0
    energy = next(e for e in d.energies if e.name == "link2")
    assert sp.simplify(energy.speed_squared - steps.result) == 0
    # the identities left no product they could have shortened
    assert not (steps.result.has(sp.sin) and steps.result.has(sp.cos) and name != "p08-spatial-rr")


def test_speed_squared_result_equals_expansion_at_random_states() -> None:
    t1, t2, t3, w1, w2, w3, a, b = sp.symbols("t1 t2 t3 w1 w2 w3 a b")
    v = sp.Matrix(
        [
            -a * sp.sin(t1) * w1 - b * sp.sin(t1 + t2 + t3) * (w1 + w2 + w3),
            a * sp.cos(t1) * w1 + b * sp.cos(t1 + t2 + t3) * (w1 + w2 + w3),
            b * sp.cos(t2) * w2,
        ]
    )
    steps = speed_squared_steps(v)
    assert steps is not None and steps.identities
    rng = random.Random(15)
    for _ in range(5):
        point = {s: rng.uniform(-2, 2) for s in (t1, t2, t3, w1, w2, w3, a, b)}
        assert float(steps.result.subs(point)) == pytest.approx(float(steps.expanded.subs(point)), rel=1e-12)
        assert float(steps.expanded.subs(point)) == pytest.approx(float((v.T * v)[0].subs(point)), rel=1e-12)


def test_speed_squared_sine_difference() -> None:
    """sin A cos B - cos A sin B = sin(A - B), where the two products carry opposite coefficients."""
    t1, t2, w = sp.symbols("t1 t2 w")
    v = sp.Matrix([sp.sin(t1) * w + sp.sin(t2) * w, sp.cos(t1) * w - sp.cos(t2) * w, 0])
    # v_x^2 + v_y^2 holds sin t1 sin t2 - cos t1 cos t2 = -cos(t1 + t2): no difference identity applies
    plain = speed_squared_steps(v)
    assert RULE_COS_DIFFERENCE not in {i.rule for i in plain.identities}
    u = sp.Matrix([sp.sin(t1) * w + sp.cos(t2) * w, sp.cos(t1) * w - sp.sin(t2) * w, 0])
    steps = speed_squared_steps(u)
    assert RULE_SIN_DIFFERENCE in {i.rule for i in steps.identities}
    assert sp.simplify(steps.result - (2 * w**2 + 2 * w**2 * sp.sin(t1 - t2))) == 0


def test_speed_squared_identity_on_the_shared_part_of_the_coefficients() -> None:
    """A tilting plate (examples/c): sin^2 theta carries psi_dot^2 + theta_dot^2, cos^2 theta only
    theta_dot^2; sin^2 + cos^2 = 1 applies to the theta_dot^2 they share."""
    e, th, ps, wt, wp = sp.symbols("e theta psi theta_dot psi_dot")
    v = sp.Matrix(
        [
            e * sp.sin(th) * sp.cos(ps) * wp + e * sp.sin(ps) * sp.cos(th) * wt,
            e * sp.sin(ps) * sp.sin(th) * wp - e * sp.cos(ps) * sp.cos(th) * wt,
            -e * sp.sin(th) * wt,
        ]
    )
    steps = speed_squared_steps(v)
    assert sp.expand(steps.result - (e**2 * sp.sin(th) ** 2 * wp**2 + e**2 * wt**2)) == 0
    assert {i.lhs for i in steps.identities} == {sp.sin(th) ** 2 + sp.cos(th) ** 2, sp.sin(ps) ** 2 + sp.cos(ps) ** 2}
