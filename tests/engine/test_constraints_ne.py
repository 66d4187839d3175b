"""Newton–Euler of the constrained examples with their constraint reactions (issue 21), against
sympy.physics.mechanics built independently and against both of tutgen's constrained routes.

Conventions reconciled: tutgen writes H q_ddot + C + G = Q + A^T lambda with A the Jacobian of the
constraints as written (a loop's gap = r_parent(parent_at) - r_child(child_at)); sympy's
``LagrangesMethod`` with ``hol_coneqs``/``nonhol_coneqs`` solves ``mass_matrix_full`` x = ``forcing_full``
for [q_dot; q_ddot; lambda] with the same sign (its ``lam_coeffs`` is -A, on the other side), so its
multipliers are tutgen's as they are (tests/engine/test_constraints.py also compares them). The pin's
force on the parent is then lambda and on the child -lambda.
"""

from __future__ import annotations

import math
import random
from typing import Any

import pytest
import sympy as sp
from sympy.physics.mechanics import (
    LagrangesMethod,
    Lagrangian,
    Particle,
    Point,
    ReferenceFrame,
    RigidBody,
    dynamicsymbols,
    inertia,
)

from tests.conftest import SPECS, solved
from tutgen.engine.newton_euler import derive_newton_euler
from tutgen.engine.tidy import is_zero

EXAMPLES = SPECS / "examples"
DISC = str(EXAMPLES / "l-disc-rolling-down-incline.yaml")
COIN = str(EXAMPLES / "m-vertical-rolling-coin.yaml")
FOUR_BAR = str(EXAMPLES / "n-four-bar-crank-rocker.yaml")
SLIDER_CRANK = str(EXAMPLES / "o-slider-crank.yaml")
ALL = [DISC, COIN, SLIDER_CRANK, pytest.param(FOUR_BAR, marks=pytest.mark.slow)]
IDS = ["disc", "coin", "slider-crank", "four-bar"]


def _params(system: Any) -> dict[str, sp.Symbol]:
    return {p.name: p.symbol for p in system.parameters}


def _coords(system: Any) -> dict[str, Any]:
    return {c.name: c for c in system.coordinates}


# ---------------------------------------------------------------------------------------------
# the structure: which reactions, and the multipliers route row by row
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("path", "kinds"),
    [
        (DISC, {"rolling": "generalized"}),
        (COIN, {"rolling_x": "generalized", "rolling_y": "generalized"}),
        (SLIDER_CRANK, {"B": "pin"}),
        pytest.param(FOUR_BAR, {"B": "pin"}, marks=pytest.mark.slow),
    ],
    ids=IDS,
)
def test_constraint_reactions_are_named(path: str, kinds: dict[str, str]) -> None:
    _, d, _ = solved(path)
    ne = d.newton_euler
    assert {cr.name: cr.kind for cr in ne.constraint_reactions} == kinds
    for cr in ne.constraint_reactions:
        if cr.kind == "pin":  # lambda on the parent, -lambda on the child, at the pin on each
            lam = sp.Matrix([*cr.multipliers, 0])
            assert sp.Matrix(cr.on_parent) == lam
            assert sp.Matrix(cr.on_child) == -lam
            assert cr.constraints == ("B_x", "B_y")


@pytest.mark.parametrize("path", ALL, ids=IDS)
def test_newton_euler_rows_are_lagranges_with_multipliers(path: str) -> None:
    """(NE)_i = (H q_ddot + C + G - Q)_i - (A^T lambda)_i for every coordinate, and each (A^T lambda)_i is
    the sum of the reactions' generalized forces; both checks are reported as passed."""
    system, d, _ = solved(path)
    ne, cd = d.newton_euler, d.constraints
    total = [
        sp.Add(*(cr.generalized_force[i] for cr in ne.constraint_reactions)) for i in range(len(system.coordinates))
    ]
    for i, c in enumerate(system.coordinates):
        assert sp.expand(total[i] - cd.constraint_forces[i]) == 0
        zero, _ = is_zero(ne.equations_of_motion[i] - d.equations_of_motion[i] + cd.constraint_forces[i])
        assert zero, c.name
    names = {ch.name: ch.passed for ch in d.checks}
    assert names["newton_euler_equals_lagrange"] and names["newton_euler_equals_reduction"]


def test_dropping_the_pin_force_breaks_the_agreement() -> None:
    """Without the pin B (the tree cut open), the slider-crank's balances miss A^T lambda: the rows of the
    rod and the piston are not Lagrange's with multipliers (they are the unconstrained ones)."""
    system, d, _ = solved(SLIDER_CRANK)
    cut = derive_newton_euler(d.system, d, planar=False)  # no constraints: the loop's pin force is missing
    cd = d.constraints
    with_multipliers = sp.Matrix(d.equations_of_motion) - sp.Matrix(cd.constraint_forces)
    co = [c.name for c in system.coordinates]
    for name in ("beta", "s"):
        i = co.index(name)
        assert not is_zero(cut.equations_of_motion[i] - with_multipliers[i])[0]
        assert is_zero(d.newton_euler.equations_of_motion[i] - with_multipliers[i])[0]


# ---------------------------------------------------------------------------------------------
# Newton-Euler against the reduced route (closed forms)
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("path", [DISC, COIN], ids=["disc", "coin"])
def test_newton_euler_holds_with_the_reduced_solution(path: str) -> None:
    """The reduced route's q_ddot_i and lambda in closed form, the dependent accelerations from
    q_ddot = T q_ddot_i + T_dot q_dot_i: every Newton-Euler row vanishes identically."""
    system, d, _ = solved(path)
    cd = d.constraints
    ck = cd.kinematics
    assert cd.accelerations and cd.multiplier_values
    qdd = [c.qdd for c in system.coordinates]
    acc_i = sp.Matrix(cd.accelerations)
    qdd_full = sp.Matrix(ck.velocity_map) * acc_i + sp.Matrix(cd.velocity_terms)
    table = {**dict(zip(qdd, qdd_full, strict=True)), **dict(zip(cd.multipliers, cd.multiplier_values, strict=True))}
    for c, e in zip(system.coordinates, d.newton_euler.equations_of_motion, strict=True):
        residual = e.xreplace(table).xreplace(ck.rates)
        assert sp.simplify(residual) == 0, c.name


def test_disc_rolling_force_by_hand() -> None:
    """The disc: lambda_1 along x and -R lambda_1 about phi; m x_ddot = m g sin(alpha) + lambda_1 and
    (1/2) m R^2 phi_ddot = -R lambda_1 with x = R phi give lambda_1 = -m g sin(alpha) / 3 (friction up the
    slope, x growing down it)."""
    system, d, _ = solved(DISC)
    p, co = _params(system), _coords(system)
    cr = d.newton_euler.constraint_reactions[0]
    lam = cr.multipliers[0]
    assert cr.generalized_force == (lam, -p["R"] * lam)
    m, g, r, alpha = p["m"], p["g"], p["R"], p["alpha"]
    eqs = [e.subs(co["x"].qdd, r * co["phi"].qdd) for e in d.newton_euler.equations_of_motion]
    sol = sp.solve(eqs, [co["phi"].qdd, lam], dict=True)[0]
    assert sp.simplify(sol[lam] + m * g * sp.sin(alpha) / 3) == 0
    assert sp.simplify(sol[co["phi"].qdd] - 2 * g * sp.sin(alpha) / (3 * r)) == 0


# ---------------------------------------------------------------------------------------------
# against sympy.physics.mechanics
# ---------------------------------------------------------------------------------------------


def _reference(lm: LagrangesMethod, values: dict[Any, float]) -> tuple[list[float], list[float]]:
    """sympy's q_ddot and lambda: mass_matrix_full x = forcing_full over [q_dot; q_ddot; lambda]."""
    if lm.eom is None:
        lm.form_lagranges_equations()
    x = lm.mass_matrix_full.subs(values).LUsolve(lm.forcing_full.subs(values))
    n = len(lm.q)
    return [float(v) for v in x[n : 2 * n]], [float(v) for v in x[2 * n :]]


def _residuals(d: Any, state: dict[sp.Symbol, float]) -> list[float]:
    return [
        float(sp.N(e.xreplace({k: sp.Float(v) for k, v in state.items()}))) for e in d.newton_euler.equations_of_motion
    ]


def test_slider_crank_against_lagranges_method() -> None:
    """The slider-crank from sympy's own frames, the loop as hol_coneqs (the rod's end minus the piston):
    at consistent states every tutgen Newton-Euler row vanishes at sympy's q_ddot and lambda, the pin's
    force on the piston is -lambda, and Newton on the piston alone holds, m3 s_ddot = F + (force of B)_x."""
    system, d, _ = solved(SLIDER_CRANK)
    p, co = _params(system), _coords(system)
    m1, m2, m3, r, ll, f_gas, tau = (p[k] for k in ("m1", "m2", "m3", "r", "l", "F", "tau"))
    th, be, s = dynamicsymbols("theta beta s")
    t = dynamicsymbols._t
    n = ReferenceFrame("N")
    fc, fr = n.orientnew("C", "Axis", (th, n.z)), n.orientnew("Rd", "Axis", (be, n.z))
    o = Point("O")
    o.set_vel(n, 0)
    g1 = o.locatenew("G1", r / 2 * fc.x)
    g1.v2pt_theory(o, n, fc)
    a = o.locatenew("A", r * fc.x)
    g2 = a.locatenew("G2", ll / 2 * fr.x)
    g2.set_vel(n, g2.pos_from(o).dt(n))
    piston = o.locatenew("P", s * n.x)
    piston.set_vel(n, s.diff(t) * n.x)
    crank = RigidBody("crank", g1, fc, m1, (inertia(fc, 0, 0, m1 * r**2 / 12), g1))
    rod = RigidBody("rod", g2, fr, m2, (inertia(fr, 0, 0, m2 * ll**2 / 12), g2))
    block = Particle("piston", piston, m3)
    gap = a.locatenew("B", ll * fr.x).pos_from(o) - piston.pos_from(o)
    lm = LagrangesMethod(
        Lagrangian(n, crank, rod, block),
        [th, be, s],
        hol_coneqs=[gap.dot(n.x), gap.dot(n.y)],
        forcelist=[(fc, tau * n.z), (piston, f_gas * n.x)],
        frame=n,
    )
    pin = next(cr for cr in d.newton_euler.constraint_reactions if cr.name == "B")
    rng = random.Random(5)
    for _ in range(2):
        values = {m1: 1.3, m2: 0.7, m3: 2.1, r: 0.4, ll: 1.5, f_gas: -0.8, tau: 0.6}
        q_th = rng.uniform(-3, 3)
        q_be = math.asin(-0.4 * math.sin(q_th) / 1.5)
        q_s = 0.4 * math.cos(q_th) + 1.5 * math.cos(q_be)
        u_th = rng.uniform(-1, 1)
        u_be = -0.4 * math.cos(q_th) * u_th / (1.5 * math.cos(q_be))
        u_s = -0.4 * math.sin(q_th) * u_th - 1.5 * math.sin(q_be) * u_be
        ref = {**values, th: q_th, be: q_be, s: q_s, th.diff(t): u_th, be.diff(t): u_be, s.diff(t): u_s}
        qdd, lam = _reference(lm, ref)
        state = {**values, co["theta"].q: q_th, co["beta"].q: q_be, co["s"].q: q_s}
        state |= {co["theta"].qd: u_th, co["beta"].qd: u_be, co["s"].qd: u_s}
        state |= {co[k].qdd: v for k, v in zip(("theta", "beta", "s"), qdd, strict=True)}
        state |= dict(zip(d.constraints.multipliers, lam, strict=True))
        assert _residuals(d, state) == pytest.approx([0, 0, 0], abs=1e-9)
        on_piston = [float(e.subs(state)) for e in pin.on_child]
        assert on_piston[:2] == pytest.approx([-lam[0], -lam[1]], rel=1e-9)
        assert 2.1 * qdd[2] == pytest.approx(-0.8 + on_piston[0], rel=1e-9)


def test_disc_against_lagranges_method() -> None:
    """The rolling disc, x - R phi as hol_coneqs: both Newton-Euler rows vanish at sympy's solution."""
    system, d, _ = solved(DISC)
    p, co = _params(system), _coords(system)
    m, r, alpha, g = p["m"], p["R"], p["alpha"], p["g"]
    x, phi = dynamicsymbols("x phi")
    t = dynamicsymbols._t
    n = ReferenceFrame("N")
    fd = n.orientnew("D", "Axis", (-phi, n.z))
    centre = Point("G")
    centre.set_vel(n, x.diff(t) * (sp.cos(alpha) * n.x - sp.sin(alpha) * n.y))
    disc = RigidBody("disc", centre, fd, m, (inertia(fd, m * r**2 / 4, m * r**2 / 4, m * r**2 / 2), centre))
    disc.potential_energy = -m * g * x * sp.sin(alpha)
    lm = LagrangesMethod(Lagrangian(n, disc), [x, phi], hol_coneqs=[x - r * phi], frame=n)
    values = {m: 1.7, r: 0.3, alpha: 0.4, g: 9.81}
    ref = {**values, x: 0.6, phi: 2.0, x.diff(t): 0.9, phi.diff(t): 3.0}
    qdd, lam = _reference(lm, ref)
    state = {**values, co["x"].q: 0.6, co["phi"].q: 2.0, co["x"].qd: 0.9, co["phi"].qd: 3.0}
    state |= {co["x"].qdd: qdd[0], co["phi"].qdd: qdd[1], d.constraints.multipliers[0]: lam[0]}
    assert _residuals(d, state) == pytest.approx([0, 0], abs=1e-9)
    assert lam[0] == pytest.approx(-1.7 * 9.81 * math.sin(0.4) / 3, rel=1e-9)


@pytest.mark.slow
def test_four_bar_against_lagranges_method() -> None:
    """The four-bar from sympy's frames with its loop as hol_coneqs: every Newton-Euler row vanishes at
    sympy's q_ddot and lambda at consistent states, and the rocker's moment balance about O4 alone gives
    the pin force's moment: (1/3) m4 c^2 theta4_ddot = c (lambda_1 sin theta4 - lambda_2 cos theta4)."""
    system, d, _ = solved(FOUR_BAR)
    p = _params(system)
    m2, m3, m4, mf, rf, a, b, c, dd, tau = (p[k] for k in ("m2", "m3", "m4", "mf", "rf", "a", "b", "c", "d", "tau"))
    th = dynamicsymbols("theta2 theta3 theta4")
    t = dynamicsymbols._t
    n = ReferenceFrame("N")
    frames = [n.orientnew(f"F{k}", "Axis", (q, n.z)) for k, q in enumerate(th)]
    o2 = Point("O2")
    o2.set_vel(n, 0)
    pa = o2.locatenew("A", a * frames[0].x)
    o4 = o2.locatenew("O4", dd * n.x)
    bodies = []
    for k, (start, length, mass, frame) in enumerate(
        [(o2, a, m2, frames[0]), (pa, b, m3, frames[1]), (o4, c, m4, frames[2])]
    ):
        g_pt = start.locatenew(f"G{k}", length / 2 * frame.x)
        g_pt.set_vel(n, g_pt.pos_from(o2).dt(n))
        bodies.append(RigidBody(f"rod{k}", g_pt, frame, mass, (inertia(frame, 0, 0, mass * length**2 / 12), g_pt)))
    bodies.append(RigidBody("flywheel", o2, frames[0], mf, (inertia(frames[0], 0, 0, mf * rf**2 / 2), o2)))
    gap = pa.locatenew("B1", b * frames[1].x).pos_from(o2) - o4.locatenew("B2", c * frames[2].x).pos_from(o2)
    lm = LagrangesMethod(
        Lagrangian(n, *bodies),
        list(th),
        hol_coneqs=[gap.dot(n.x), gap.dot(n.y)],
        forcelist=[(frames[0], tau * n.z)],
        frame=n,
    )
    coords = system.coordinates
    ratios = d.constraints.kinematics.velocity_ratios
    rng = random.Random(29)
    values = {m2: 1.2, m3: 0.8, m4: 1.1, mf: 2.0, rf: 0.3, a: 0.5, b: 2.0, c: 1.2, dd: 1.8, tau: 0.7}
    for _ in range(2):
        q2 = rng.uniform(-3, 3)
        q3, q4 = (
            float(v)
            for v in sp.nsolve(
                [e.subs(values).subs(th[0], q2) for e in (gap.dot(n.x), gap.dot(n.y))], th[1:], [0.5, 1.5]
            )
        )
        u2 = rng.uniform(-1, 1)
        plain = {**values, coords[0].q: q2, coords[1].q: q3, coords[2].q: q4}
        u3, u4 = (float(ratios[k, 0].subs(plain)) * u2 for k in range(2))
        ref = {**values, th[0]: q2, th[1]: q3, th[2]: q4, th[0].diff(t): u2, th[1].diff(t): u3, th[2].diff(t): u4}
        qdd, lam = _reference(lm, ref)
        state = {**plain, coords[0].qd: u2, coords[1].qd: u3, coords[2].qd: u4}
        state |= {cc.qdd: v for cc, v in zip(coords, qdd, strict=True)}
        state |= dict(zip(d.constraints.multipliers, lam, strict=True))
        assert _residuals(d, state) == pytest.approx([0, 0, 0], abs=1e-9)
        assert 1.1 * 1.2**2 / 3 * qdd[2] == pytest.approx(
            1.2 * (lam[0] * math.sin(q4) - lam[1] * math.cos(q4)), rel=1e-9
        )


# ---------------------------------------------------------------------------------------------
# presentation: the free-body diagrams and the JSON
# ---------------------------------------------------------------------------------------------


def test_pin_force_on_both_free_bodies() -> None:
    """The slider-crank's planar free bodies: the pin B's force on the rod (lambda) and on the piston
    (-lambda), both at the pin; and in the JSON, newton_euler.constraint_reactions."""
    from tutgen.engine.ne_types import ForceKind

    _, d, doc = solved(SLIDER_CRANK)
    planar = d.newton_euler.planar
    assert planar is not None
    by_body = {b.body: {f.kind: f for f in b.forces} for b in planar.balances}
    lam1, lam2 = d.constraints.multipliers
    assert by_body["rod"][ForceKind.LOOP_REACTION_ON_PARENT].force == (lam1, lam2)
    assert by_body["piston"][ForceKind.LOOP_REACTION].force == (-lam1, -lam2)
    assert ForceKind.LOOP_REACTION not in by_body["crank"] and ForceKind.LOOP_REACTION_ON_PARENT not in by_body["crank"]
    ne = dict(doc)["results"]["newton_euler"]
    assert ne["agrees_with_reduction"] is True
    assert ne["constraint_reactions"]["B"]["force_on_child"] == ["-lambda_1", "-lambda_2", 0]
    labels = {v["body"]: v["labels"] for v in dict(doc)["figure"]["free_bodies"]}
    assert any("reaction at joint 'B'" in k for k in labels["rod"])
    assert any("reaction at joint 'B'" in k for k in labels["piston"])
