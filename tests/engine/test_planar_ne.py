"""Newton–Euler as it is taught, for planar systems (tutgen.engine.planar_ne), tested on its records.

References: the tutorial's problem 3 (its free-body reasoning and the pivot reaction
R = m2 (a_p + g j) written out by hand below), Lagrange's equations of the same specs, and the reactions of
the recursive route (tutgen.engine.newton_euler), which solves the 3-D balances its own way.
"""

from __future__ import annotations

import random
from functools import cache
from pathlib import Path
from typing import Any

import pytest
import sympy as sp

from tests.conftest import SPECS, all_specs
from tests.conftest import solved as solved_default
from tutgen.engine.ne_types import ForceKind, PlanarBalance, PlanarNewtonEuler
from tutgen.engine.planar_ne import reaction_symbol
from tutgen.engine.tidy import is_zero
from tutgen.model.system import JointKind

P03 = SPECS / "tutorial-1" / "p03-cart-pendulum.yaml"


@cache
def solved(path: str) -> tuple[Any, Any, Any]:
    """(system, derivation, document) with Newton-Euler presented: the planar form is built only when its
    working is printed (tutgen.engine.pipeline), so a spec that presents Lagrange alone (the default) is
    derived again with ``--method both``; p03 presents both and shares the session's derivation."""
    from tutgen.engine.pipeline import derive
    from tutgen.model.system import Method

    system, d, doc = solved_default(path)
    if Method.NEWTON_EULER in d.methods:
        return system, d, doc
    return system, derive(system, "both"), None


#: the specs whose motion is planar and that have joints: the planar form must exist for each
PLANAR = {
    "p03-cart-pendulum",
    "p05-rr-arm",
    "p07-belt-driven-arm",
    "p09-pr-manipulator",
    "a-double-pendulum-rods",
    "b-cart-pendulum-sphere",
    "d-planar-3r-arm",
    "f-two-mass-chain",
}
#: the two whose symbolic comparisons take tens of seconds: with ``-m slow`` only
HEAVY = {"b-cart-pendulum-sphere", "d-planar-3r-arm"}
#: jointed specs with motion out of one plane: the recursive form stays
SPATIAL = {"p08-spatial-rr", "c-rotor-tilting-plate", "g-heavy-symmetric-top"}


def _symbols(path: Path) -> dict[str, sp.Symbol]:
    """The spec's own symbols by name (parameters carry assumptions: ``sp.Symbol('k')`` is another symbol)."""
    system, _, _ = solved(str(path))
    out = {p.name: p.symbol for p in system.parameters}
    for c in system.coordinates:
        out.update({c.q.name: c.q, c.qd.name: c.qd, c.qdd.name: c.qdd})
    return out


def _zero_on_shell(path: Path, expr: sp.Expr, states: int = 3) -> bool | None:
    """Whether an expression vanishes along the motion: at random numeric states (parameters, q, q_dot)
    with the accelerations from Lagrange's equations there; None when H is singular there."""
    system, d, _ = solved(str(path))
    accelerations = [c.qdd for c in system.coordinates]
    rng = random.Random(15)
    names = sorted(
        (expr.free_symbols | d.equations_of_motion.free_symbols) - set(accelerations), key=sp.default_sort_key
    )
    for _ in range(states):
        at = {n: sp.Float(rng.uniform(0.5, 1.5)) for n in names}
        eqs = [sp.expand(e.xreplace(at).evalf()) for e in d.equations_of_motion]
        solution = sp.solve(eqs, accelerations, dict=True)
        if not solution or set(solution[0]) != set(accelerations):
            return None
        value = complex(expr.xreplace(at).xreplace(solution[0]).evalf())
        if abs(value) > 1e-9:
            return False
    return True


def _planar(path: Path) -> PlanarNewtonEuler:
    _, d, _ = solved(str(path))
    assert d.newton_euler is not None and d.newton_euler.planar is not None
    return d.newton_euler.planar


def _body(planar: PlanarNewtonEuler, name: str) -> PlanarBalance:
    return next(b for b in planar.balances if b.body == name)


def _planar_params() -> list[Any]:
    return [pytest.param(stem, marks=pytest.mark.slow) if stem in HEAVY else stem for stem in sorted(PLANAR)]


def _jointed() -> list[Path]:
    return [p for p in all_specs() if p.stem in PLANAR | SPATIAL]


def test_planar_specs_are_found() -> None:
    stems = {p.stem for p in all_specs()}
    assert PLANAR <= stems and SPATIAL <= stems  # the lists name real specs


@pytest.mark.parametrize("path", _jointed(), ids=lambda p: p.stem)
def test_planar_form_exactly_where_motion_is_planar(path: Path) -> None:
    _, d, _ = solved(str(path))
    assert d.newton_euler is not None
    assert (d.newton_euler.planar is not None) == (path.stem in PLANAR)


def test_p03_cart_free_body_has_the_spring_and_the_push() -> None:
    planar = _planar(P03)
    cart = _body(planar, "cart")
    S = _symbols(P03).__getitem__
    k, x, F, m1, g = S("k"), S("x"), S("F"), S("m1"), S("g")
    by_kind = {f.kind: f for f in cart.forces}
    spring = by_kind[ForceKind.SPRING]
    assert spring.source == "wall" and sp.expand(spring.force[0] + k * x) == 0 and spring.force[1] == 0
    push = by_kind[ForceKind.LOAD]
    assert push.source == "push" and push.force == (F, 0)
    # the motor's reaction torque is on the cart, the pivot's reaction reversed too
    assert sp.expand(by_kind[ForceKind.LOAD_REACTION].torque + S("tau")) == 0
    assert by_kind[ForceKind.REACTION_ON_PARENT].force == (
        -reaction_symbol("R", "pivot", "x"),
        -reaction_symbol("R", "pivot", "y"),
    )
    assert by_kind[ForceKind.GRAVITY].force == (0, -g * m1)
    fx = sp.expand(cart.sum_fx)
    assert fx.coeff(k) == -x and fx.coeff(F) == 1
    # the tutorial's "F - kx - R_x - m1 x_ddot = 0", term for term
    assert sp.expand(fx - (F - k * x - reaction_symbol("R", "pivot", "x") - m1 * S("x_ddot"))) == 0


def test_p03_pendulum_moments_about_the_pivot() -> None:
    planar = _planar(P03)
    pendulum = _body(planar, "pendulum")
    S = _symbols(P03).__getitem__
    assert pendulum.joint == "pivot" and pendulum.point == (S("x"), 0)
    m2, length, g, tau, theta = S("m2"), S("l"), S("g"), S("tau"), S("theta")
    m = sp.expand(pendulum.sum_m)
    assert m.coeff(tau) == 1  # the motor torque
    assert sp.expand(m.coeff(g) + m2 * length * sp.sin(theta)) == 0  # gravity's moment
    # the reaction passes through the pivot: no reaction in this balance
    assert not {s.name for s in m.free_symbols if "[" in s.name}


def test_p03_elimination_reads_as_the_tutorial() -> None:
    planar = _planar(P03)
    theta_step, x_step = planar.steps  # tips first: the pendulum's moment, then the cart's forces
    assert (theta_step.coordinate, x_step.coordinate) == ("theta", "x")
    assert [c.body for c in theta_step.contributions] == ["pendulum"] and theta_step.eliminated == ()
    assert [(c.body, c.kind) for c in x_step.contributions] == [("cart", "force"), ("pendulum", "force")]
    assert x_step.eliminated == (reaction_symbol("R", "pivot", "x"),)


def test_p03_pivot_reaction_is_m2_times_a_p_plus_g() -> None:
    """The tutorial: the cart pushes on the pendulum with R = m2 (a_p + g j), where
    a_p = (x_ddot + l theta_ddot cos - l theta_dot^2 sin) i + (l theta_ddot sin + l theta_dot^2 cos) j."""
    planar = _planar(P03)
    S = _symbols(P03).__getitem__
    m2, ell, g, th = S("m2"), S("l"), S("g"), S("theta")
    xdd, thd, thdd = S("x_ddot"), S("theta_dot"), S("theta_ddot")
    a_p = (
        xdd + ell * thdd * sp.cos(th) - ell * thd**2 * sp.sin(th),
        ell * thdd * sp.sin(th) + ell * thd**2 * sp.cos(th),
    )
    pivot = next(r for r in planar.reactions if r.joint == "pivot")
    assert sp.expand(pivot.force[0] - m2 * a_p[0]) == 0
    assert sp.expand(pivot.force[1] - m2 * (a_p[1] + g)) == 0
    # the slider carries the weight of both and the pendulum's vertical inertia, and the motor's reaction
    slider = next(r for r in planar.reactions if r.joint == "slider")
    normal, couple = slider.values
    assert sp.expand(normal - (S("m1") * g + m2 * (a_p[1] + g))) == 0 and couple == S("tau")


@pytest.mark.parametrize("stem", _planar_params())
def test_eliminated_equations_equal_lagranges(stem: str) -> None:
    path = next(p for p in all_specs() if p.stem == stem)
    _, d, _ = solved(str(path))
    planar = d.newton_euler.planar
    for i, step_eq in enumerate(planar.equations_of_motion):
        zero, _ = is_zero(step_eq - d.equations_of_motion[i])
        assert zero, (stem, i)
    for st in planar.steps:  # no reaction survives an elimination
        assert not {s for s in st.result.free_symbols if "[" in s.name}
        assert sp.expand(st.result + st.equation) == 0


@pytest.mark.parametrize("stem", _planar_params())
def test_reactions_equal_the_recursive_routes(stem: str) -> None:
    """Solved from the scalar balances tips inward, against the 3-D balances of the recursive route (which
    solves R_j = sum of R_children - known forces in world vectors)."""
    path = next(p for p in all_specs() if p.stem == stem)
    _, d, _ = solved(str(path))
    ne = d.newton_euler
    theirs = {r.joint: r for r in ne.reactions}
    for r in ne.planar.reactions:
        other = theirs[r.joint]
        if r.kind is JointKind.PRISMATIC:
            assert r.normal is not None
            normal = r.normal[0] * other.force[0] + r.normal[1] * other.force[1]
            assert is_zero(r.values[0] - normal)[0], (stem, r.joint)
            # the recursive route's moment holds the drive of the joints beyond (z . N of an unactuated
            # pivot is its equation of motion): the two agree along the motion
            assert _zero_on_shell(path, r.moment - other.moment[2]) in (True, None), (stem, r.joint)
        else:
            assert is_zero(r.force[0] - other.force[0])[0] and is_zero(r.force[1] - other.force[1])[0], (stem, r.joint)


@pytest.mark.parametrize("stem", _planar_params())
def test_every_joint_reaction_acts_on_both_bodies(stem: str) -> None:
    """Third law: what a joint exerts on its child, reversed, is on its parent (unless that is the ground)."""
    planar = _planar(next(p for p in all_specs() if p.stem == stem))
    forces = {b.body: b.forces for b in planar.balances}
    for r in planar.reactions:
        on_child = [f for f in forces[r.child] if f.kind is ForceKind.REACTION and f.source == r.joint]
        assert len(on_child) == 1
        if r.parent in forces:
            back = [f for f in forces[r.parent] if f.kind is ForceKind.REACTION_ON_PARENT and f.source == r.joint]
            assert len(back) == 1
            assert back[0].force == (-on_child[0].force[0], -on_child[0].force[1])
            assert back[0].point == on_child[0].point


def test_spring_given_by_extension_acts_between_its_bodies() -> None:
    """f-two-mass-chain: 'coupling' (extension x2 - x1) pulls block1 and block2 towards each other;
    the dashpot between the blocks acts on both, opposite."""
    path = SPECS / "examples" / "f-two-mass-chain.yaml"
    planar = _planar(path)
    S = _symbols(path).__getitem__
    k2, x1, x2 = S("k2"), S("x1"), S("x2")
    coupling = {
        b.body: f.force[0]
        for b in planar.balances
        for f in b.forces
        if f.kind is ForceKind.SPRING and f.source == "coupling"
    }
    assert sp.expand(coupling["block1"] - k2 * (x2 - x1)) == 0
    assert sp.expand(coupling["block2"] + k2 * (x2 - x1)) == 0
    dash = {b.body: f.force[0] for b in planar.balances for f in b.forces if f.kind is ForceKind.DAMPER}
    assert sp.expand(dash["block1"] + dash["block2"]) == 0 and dash["block1"] != 0


def test_absolute_angle_carries_the_outer_link_without_turning() -> None:
    """p07 (link 2's angle from the x axis): theta1's equation takes link2's forces' moment at the elbow,
    not link2's moment about the shoulder; motor 2's reaction is on the ground, so link1 has no -tau2."""
    path = SPECS / "tutorial-1" / "p07-belt-driven-arm.yaml"
    planar = _planar(path)
    S = _symbols(path).__getitem__
    theta1 = next(s for s in planar.steps if s.coordinate == "theta1")
    assert [(c.body, c.kind, c.via) for c in theta1.contributions] == [
        ("link1", "moment", None),
        ("link2", "force_moment", "elbow"),
    ]
    link1 = _body(planar, "link1")
    assert sp.expand(link1.sum_m).coeff(S("tau2")) == 0 and sp.expand(link1.sum_m).coeff(S("tau1")) == 1
