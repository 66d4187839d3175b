"""The closed-form position analysis of a loop (tutgen/engine/constraints/positions.py) and the numeric
solve of the position constraints (kinematics.solve_positions), against loop-closure equations written
here by hand, Freudenstein's equation and Norton's open/crossed formula for the four-bar, the textbook
slider-crank formula, and each other.

Only the kinematics is built (not the whole derivation: the four-bar's takes 18 s), once per module.
"""

from __future__ import annotations

import cmath
import math
import random
from functools import cache
from pathlib import Path
from typing import Any

import pytest
import sympy as sp

from tests.conftest import SPECS
from tutgen.engine.constraints import constraint_kinematics, with_loop_closures
from tutgen.engine.constraints.kinematics import ConstraintKinematics, solve_positions
from tutgen.engine.constraints.positions import (
    LoopAnalysis,
    LoopBranch,
    _holds,
    assembly_at,
    assembly_ranges,
    branch_at,
)
from tutgen.engine.inertia import body_inertia
from tutgen.engine.kinematics import Kinematics
from tutgen.model.system import ConstraintKind, System
from tutgen.spec.validate import load_system, load_system_text

FOUR_BAR = SPECS / "examples" / "n-four-bar-crank-rocker.yaml"
SLIDER_CRANK = SPECS / "examples" / "o-slider-crank.yaml"
DISC = SPECS / "examples" / "l-disc-rolling-down-incline.yaml"

#: a crank-rocker (Grashof: 0.5 + 2.0 <= 1.2 + 1.8, the crank shortest) and a linkage whose crank
#: cannot turn fully (1.5 + 0.6 > 1.0 + 1.0)
CRANK_ROCKER = {"a": 0.5, "b": 2.0, "c": 1.2, "d": 1.8}
NON_GRASHOF = {"a": 1.0, "b": 1.0, "c": 0.6, "d": 1.5}


@cache
def constrained(name: str) -> tuple[System, ConstraintKinematics]:
    path = {"four-bar": FOUR_BAR, "slider-crank": SLIDER_CRANK, "disc": DISC}[name]
    system = load_system(path)
    kin = Kinematics(system, {bi.name: bi.com for bi in map(body_inertia, system.bodies)})
    system = with_loop_closures(system, list(kin.bodies.values()))
    return system, constraint_kinematics(system)


def _symbols(system: System) -> dict[str, sp.Symbol]:
    return {p.name: p.symbol for p in system.parameters} | {c.name: c.q for c in system.coordinates}


def _branch_values(loop: LoopAnalysis, branch: LoopBranch, values: dict[sp.Symbol, float], system: System) -> dict:
    table = {k: sp.Float(v) for k, v in values.items()}
    out = {}
    for j, e in branch.positions:
        z = complex(sp.N(e.xreplace(table)))
        out[system.coordinates[j].q] = z
    return out


def _four_bar_gap(n: dict[str, float], t2: float, t3: float, t4: float) -> tuple[float, float]:
    """The loop O2 A B O4 by hand: a e^(i t2) + b e^(i t3) - c e^(i t4) - d = 0."""
    a, b, c, d = n["a"], n["b"], n["c"], n["d"]
    return (
        a * math.cos(t2) + b * math.cos(t3) - c * math.cos(t4) - d,
        a * math.sin(t2) + b * math.sin(t3) - c * math.sin(t4),
    )


def test_four_bar_branches_close_the_loop() -> None:
    """Both branches of theta4 (and theta3 from it) satisfy the loop-closure equations at random crank
    angles of a crank-rocker."""
    system, ck = constrained("four-bar")
    loop = ck.loop
    assert loop is not None
    s = _symbols(system)
    rng = random.Random(5)
    for _ in range(6):
        t2 = rng.uniform(-math.pi, math.pi)
        values = {s[k]: v for k, v in CRANK_ROCKER.items()} | {s["theta2"]: t2}
        for branch in loop.branches:
            got = _branch_values(loop, branch, values, system)
            t3, t4 = got[s["theta3"]], got[s["theta4"]]
            assert abs(t3.imag) < 1e-12 and abs(t4.imag) < 1e-12
            gap = _four_bar_gap(CRANK_ROCKER, t2, t3.real, t4.real)
            assert gap == pytest.approx((0, 0), abs=1e-10)
        # the two branches are two assemblies, not one twice
        t4s = [_branch_values(loop, b, values, system)[s["theta4"]].real for b in loop.branches]
        assert abs(math.remainder(t4s[0] - t4s[1], 2 * math.pi)) > 1e-3


def test_four_bar_elimination_is_freudensteins_equation() -> None:
    """The equation in theta4 alone is 2 a c (K1 cos theta4 - K2 cos theta2 + K3 - cos(theta2 - theta4))
    with K1 = d/a, K2 = d/c, K3 = (a^2 - b^2 + c^2 + d^2)/(2 a c)."""
    system, ck = constrained("four-bar")
    loop = ck.loop
    assert loop is not None
    s = _symbols(system)
    a, b, c, d, t2, t4 = (s[k] for k in ("a", "b", "c", "d", "theta2", "theta4"))
    k1, k2, k3 = d / a, d / c, (a**2 - b**2 + c**2 + d**2) / (2 * a * c)
    freudenstein = 2 * a * c * (k1 * sp.cos(t4) - k2 * sp.cos(t2) + k3 - sp.cos(t2 - t4))
    assert sp.simplify(sp.expand_trig(loop.elimination - freudenstein)) == 0
    assert [system.coordinates[loop.eliminated].name, system.coordinates[loop.solved].name] == ["theta3", "theta4"]


def test_four_bar_open_branch_is_nortons() -> None:
    """Norton's closed form (Design of Machinery, eq. 4.10): A t^2 + B t + C = 0 with A = cos theta2 - K1
    - K2 cos theta2 + K3, B = -2 sin theta2, C = K1 - (K2 + 1) cos theta2 + K3; the minus root is the open
    assembly. tutgen's branch named open is that one, at every crank angle tried, and at theta2 = 1 (the
    crank up) its quadrilateral O2 A B O4 is convex (its diagonals cross)."""
    system, ck = constrained("four-bar")
    loop = ck.loop
    assert loop is not None
    s = _symbols(system)
    a, b, c, d = (CRANK_ROCKER[k] for k in "abcd")
    k1, k2, k3 = d / a, d / c, (a**2 - b**2 + c**2 + d**2) / (2 * a * c)
    for t2 in (-2.8, -1.2, 0.0, 1.0, 2.2, 3.0):
        big_a = math.cos(t2) - k1 - k2 * math.cos(t2) + k3
        big_b = -2 * math.sin(t2)
        big_c = k1 - (k2 + 1) * math.cos(t2) + k3
        root = cmath.sqrt(big_b**2 - 4 * big_a * big_c).real
        open_t4 = 2 * math.atan((-big_b - root) / (2 * big_a))
        crossed_t4 = 2 * math.atan((-big_b + root) / (2 * big_a))
        values = {s[k]: v for k, v in CRANK_ROCKER.items()} | {s["theta2"]: t2}
        for t4, name in ((open_t4, "open"), (crossed_t4, "crossed")):
            t3 = math.atan2(c * math.sin(t4) - a * math.sin(t2), d + c * math.cos(t4) - a * math.cos(t2))
            assert _four_bar_gap(CRANK_ROCKER, t2, t3, t4) == pytest.approx((0, 0), abs=1e-10)
            here = values | {s["theta3"]: t3, s["theta4"]: t4}
            assert assembly_at(loop, here) == name, (t2, name)
            assert branch_at(loop, here, [x.q for x in system.coordinates]) == (-1 if name == "open" else 1)
    t2 = 1.0
    big_a = math.cos(t2) - k1 - k2 * math.cos(t2) + k3
    big_b, big_c = -2 * math.sin(t2), k1 - (k2 + 1) * math.cos(t2) + k3
    t4 = 2 * math.atan((-big_b - math.sqrt(big_b**2 - 4 * big_a * big_c)) / (2 * big_a))
    o2, pa, o4 = (0.0, 0.0), (a * math.cos(t2), a * math.sin(t2)), (d, 0.0)
    pb = (d + c * math.cos(t4), c * math.sin(t4))

    def side(p: tuple[float, float], q: tuple[float, float], r: tuple[float, float]) -> float:
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])

    # diagonals O2 B and A O4 cross: O2 and B on opposite sides of A O4, A and O4 of O2 B
    assert side(pa, o4, o2) * side(pa, o4, pb) < 0
    assert side(o2, pb, pa) * side(o2, pb, o4) < 0


def test_four_bar_closed_form_agrees_with_the_numeric_solve() -> None:
    """solve_positions started near each branch lands on it (branch_at names it), and without a start it
    lands on one of the two."""
    system, ck = constrained("four-bar")
    loop = ck.loop
    assert loop is not None
    s = _symbols(system)
    qs = [x.q for x in system.coordinates]
    rng = random.Random(11)
    for _ in range(4):
        t2 = rng.uniform(-math.pi, math.pi)
        values = {s[k]: v for k, v in CRANK_ROCKER.items()} | {s["theta2"]: t2}
        for branch in loop.branches:
            exact = {q: z.real for q, z in _branch_values(loop, branch, values, system).items()}
            start = {q: v + 0.05 for q, v in exact.items()}
            found = solve_positions(system, ck, values, start)
            assert found is not None
            for q, v in exact.items():
                assert math.remainder(found[q] - v, 2 * math.pi) == pytest.approx(0, abs=1e-9)
            assert branch_at(loop, values | found, qs) == branch.sign
        anywhere = solve_positions(system, ck, values)
        assert anywhere is not None and branch_at(loop, values | anywhere, qs) in (1, -1)


def _discriminant(loop: LoopAnalysis, values: dict[sp.Symbol, float]) -> float:
    return float(loop.discriminant.xreplace({k: sp.Float(v) for k, v in values.items()}))


def test_four_bar_cannot_close_where_the_discriminant_is_negative() -> None:
    """A linkage that violates Grashof's condition: near theta2 = pi the pins A and O4 are farther apart
    than b + c, the discriminant is negative (the branches' square root is imaginary), and the numeric
    solve finds no root either; at theta2 = 0 both exist."""
    system, ck = constrained("four-bar")
    loop = ck.loop
    assert loop is not None
    s = _symbols(system)
    base = {s[k]: v for k, v in NON_GRASHOF.items()}
    # |A O4| at theta2 = pi is a + d = 2.5 > b + c = 1.6
    at_pi = base | {s["theta2"]: math.pi}
    assert _discriminant(loop, at_pi) < 0
    for branch in loop.branches:  # theta4 has the square root of the discriminant: not real there
        assert sp.sqrt(loop.discriminant) in dict(branch.positions)[loop.solved].atoms(sp.Pow)
    assert solve_positions(system, ck, at_pi) is None
    at_zero = base | {s["theta2"]: 0.0}
    assert _discriminant(loop, at_zero) > 0
    assert solve_positions(system, ck, at_zero) is not None


def test_four_bar_dead_point_where_the_branches_meet() -> None:
    """Where the discriminant vanishes (found by bisection on theta2) the two branches give one
    configuration, and det A_d (the velocity analysis' denominator) is zero there."""
    system, ck = constrained("four-bar")
    loop = ck.loop
    assert loop is not None
    s = _symbols(system)
    base = {s[k]: v for k, v in NON_GRASHOF.items()}
    lo, hi = 0.0, math.pi  # positive at 0, negative at pi
    for _ in range(60):
        mid = (lo + hi) / 2
        if _discriminant(loop, base | {s["theta2"]: mid}) > 0:
            lo = mid
        else:
            hi = mid
    values = base | {s["theta2"]: lo}
    pair = [{q: z.real for q, z in _branch_values(loop, b, values, system).items()} for b in loop.branches]
    assert math.remainder(pair[0][s["theta4"]] - pair[1][s["theta4"]], 2 * math.pi) == pytest.approx(0, abs=1e-6)
    det = float(ck.determinant.xreplace({k: sp.Float(v) for k, v in (values | pair[0]).items()}))
    assert det == pytest.approx(0, abs=1e-6)
    # and away from it, det A_d is not small
    away = base | {s["theta2"]: 0.3}
    here = {q: z.real for q, z in _branch_values(loop, loop.branches[0], away, system).items()}
    assert abs(float(ck.determinant.xreplace({k: sp.Float(v) for k, v in (away | here).items()}))) > 0.1


def test_slider_crank_textbook_formula() -> None:
    """s = r cos theta +- sqrt(l^2 - r^2 sin^2 theta), and beta from sin beta = -r sin theta / l,
    cos beta = (s - r cos theta) / l, at random crank angles, both branches."""
    system, ck = constrained("slider-crank")
    loop = ck.loop
    assert loop is not None and not loop.sides  # not a four-bar: no open/crossed
    s = _symbols(system)
    r, rod, th = s["r"], s["l"], s["theta"]
    for branch in loop.branches:
        exact = branch.sign * sp.sqrt(rod**2 - r**2 * sp.sin(th) ** 2) + r * sp.cos(th)
        assert sp.simplify(dict(branch.positions)[loop.solved] - exact) == 0
    rng = random.Random(3)
    for _ in range(5):
        values = {r: 0.4, rod: 1.3, th: rng.uniform(-math.pi, math.pi)}
        for branch in loop.branches:
            got = {q: z.real for q, z in _branch_values(loop, branch, values, system).items()}
            beta, pos = got[s["beta"]], got[s["s"]]
            assert 0.4 * math.sin(values[th]) + 1.3 * math.sin(beta) == pytest.approx(0, abs=1e-12)
            assert 0.4 * math.cos(values[th]) + 1.3 * math.cos(beta) - pos == pytest.approx(0, abs=1e-12)


def test_solve_positions_slider_crank() -> None:
    """The function the simulator uses: the dependent coordinates, by name of symbol, near the start."""
    system, ck = constrained("slider-crank")
    s = _symbols(system)
    values = {s["r"]: 0.4, s["l"]: 1.3, s["theta"]: 0.7}
    found = solve_positions(system, ck, values, {s["beta"]: -0.2, s["s"]: 1.5})
    assert found is not None and set(found) == {s["beta"], s["s"]}
    assert found[s["s"]] == pytest.approx(0.4 * math.cos(0.7) + math.sqrt(1.3**2 - (0.4 * math.sin(0.7)) ** 2))
    behind = solve_positions(system, ck, values, {s["beta"]: math.pi, s["s"]: -1.0})
    assert behind is not None
    assert behind[s["s"]] == pytest.approx(0.4 * math.cos(0.7) - math.sqrt(1.3**2 - (0.4 * math.sin(0.7)) ** 2))
    # the spec's own system (a Derivation's, without the loop-closure equations) does as well
    assert solve_positions(load_system(SLIDER_CRANK), ck, values, {s["beta"]: -0.2, s["s"]: 1.5}) == found


def test_a_wrong_closed_form_is_not_kept() -> None:
    """The check that guards the closed form can fail: a branch with a wrong sign inside is rejected."""
    system, ck = constrained("slider-crank")
    loop = ck.loop
    assert loop is not None
    equations = [f for f, c in zip(ck.functions, ck.constraints, strict=True) if c.kind is ConstraintKind.POSITION]
    assert _holds(system, equations, loop)
    s = _symbols(system)
    wrong_branch = LoopBranch(
        1, tuple((j, e.xreplace({s["r"]: -s["r"]}) if j == loop.solved else e) for j, e in loop.branches[0].positions)
    )
    wrong: Any = LoopAnalysis(**{**loop.__dict__, "branches": (wrong_branch, loop.branches[1])})
    assert not _holds(system, equations, wrong)


def test_linear_constraints_keep_the_linear_analysis() -> None:
    """The rolling disc's x = R phi is linear in x: one branch in ck.positions, no loop analysis."""
    system, ck = constrained("disc")
    s = _symbols(system)
    assert ck.loop is None
    assert len(ck.positions) == 1
    ((j, e),) = ck.positions[0]
    assert system.coordinates[j].name == "x" and sp.simplify(e - s["R"] * s["phi"]) == 0


def test_four_bar_written_the_other_way_names_the_same_assembly() -> None:
    """The closing pin written from the rocker to the coupler (the loop-closure equations negated) and
    the rocker's angle listed before the coupler's: the same configuration is named the same assembly,
    and the closed form still closes the loop."""
    text = FOUR_BAR.read_text(encoding="utf-8")
    text = text.replace(
        "parent: coupler, child: rocker, closes_loop: true, origin: [b, 0, 0], child_origin: [c, 0, 0]",
        "parent: rocker, child: coupler, closes_loop: true, origin: [c, 0, 0], child_origin: [b, 0, 0]",
    )
    text = text.replace("  theta3: {latex: '\\theta_3', description: coupler angle, dimension: angle}\n", "")
    text = text.replace(
        "  theta4: {latex: '\\theta_4', description: rocker angle, dimension: angle}\n",
        "  theta4: {latex: '\\theta_4', description: rocker angle, dimension: angle}\n"
        "  theta3: {latex: '\\theta_3', description: coupler angle, dimension: angle}\n",
    )
    assert "parent: rocker, child: coupler" in text and text.index("theta4: {") < text.index("theta3: {")
    system = load_system_text(text, "reversed.yaml")
    kin = Kinematics(system, {bi.name: bi.com for bi in map(body_inertia, system.bodies)})
    system = with_loop_closures(system, list(kin.bodies.values()))
    ck = constraint_kinematics(system)
    loop = ck.loop
    assert loop is not None and loop.sides
    ref_system, ref_ck = constrained("four-bar")
    assert ref_ck.loop is not None
    s, ref = _symbols(system), _symbols(ref_system)
    for t2 in (-2.0, 0.4, 2.5):
        for branch in ref_ck.loop.branches:
            values = {ref[k]: v for k, v in CRANK_ROCKER.items()} | {ref["theta2"]: t2}
            here = {q: z.real for q, z in _branch_values(ref_ck.loop, branch, values, ref_system).items()}
            name = assembly_at(ref_ck.loop, values | here)
            mine = {s[q.name]: v for q, v in (values | here).items()}
            assert assembly_at(loop, mine) == name
            assert branch_at(loop, mine, [x.q for x in system.coordinates]) in (1, -1)
            assert _four_bar_gap(CRANK_ROCKER, t2, mine[s["theta3"]], mine[s["theta4"]]) == pytest.approx(
                (0, 0), abs=1e-10
            )


def _reach(n: dict[str, float]) -> list[tuple[float, float]]:
    """The crank angles (degrees, 0 to 180) where the loop closes, by hand: |A O4|^2 = a^2 + d^2 -
    2 a d cos(theta2) must lie between (b - c)^2 and (b + c)^2."""
    a, b, c, d = (n[k] for k in "abcd")

    def angle(distance: float) -> float:
        cos = (a**2 + d**2 - distance**2) / (2 * a * d)
        return math.degrees(math.acos(max(-1.0, min(1.0, cos))))

    return [(angle(abs(b - c)), angle(b + c))]


@pytest.mark.parametrize(
    "lengths",
    [
        pytest.param(NON_GRASHOF, id="coupler-and-rocker-too-short"),
        pytest.param({"a": 1.0, "b": 0.4, "c": 1.2, "d": 1.5}, id="too-short-and-too-long"),
        pytest.param(CRANK_ROCKER, id="crank-rocker"),
    ],
)
def test_four_bar_crank_range_by_hand(lengths: dict[str, float]) -> None:
    """assembly_ranges against the triangle inequality of A B O4: the full turn for a crank-rocker, and
    otherwise the angles (mirrored about the ground line) between which |b - c| <= |A O4| <= b + c."""
    system, ck = constrained("four-bar")
    loop = ck.loop
    assert loop is not None
    s = _symbols(system)
    ranges = assembly_ranges(loop, {s[k]: v for k, v in lengths.items()})
    assert ranges is not None
    if lengths is CRANK_ROCKER:
        assert ranges == [(-math.pi, math.pi)]
        return
    ((lo, hi),) = _reach(lengths)
    got = sorted((math.degrees(x), math.degrees(y)) for x, y in ranges)
    upper = [(x, y) for x, y in got if y > 0]
    assert upper[-1][1] == pytest.approx(hi, abs=1e-6)
    assert (upper[0][0] if upper[0][0] > 0 else 0.0) == pytest.approx(lo, abs=1e-6)
    mirrored = [v for x, y in reversed(got) for v in (-y, -x)]
    assert mirrored == pytest.approx([v for pair in got for v in pair])  # symmetric about theta2 = 0


@pytest.mark.slow  # derives a four-bar with numbers (about 12 s)
def test_four_bar_solution_states_the_crank_range(tmp_path: Path) -> None:
    """The solution says between which crank angles a linkage that is not a crank-rocker can be assembled."""
    from tutgen.api import render
    from tutgen.engine.pipeline import derive

    text = FOUR_BAR.read_text(encoding="utf-8")
    for name, value in {"a": 1.0, "b": 0.4, "c": 1.2, "d": 1.5}.items():
        text = text.replace(f"  {name}: {{description:", f"  {name}: {{value: {value}, description:")
    text = text.replace("figure: {sizes: {a: 0.6, b: 1.6, c: 1.1, d: 1.5, rf: 0.18}}\n", "")
    md = render(derive(load_system_text(text, "numbers.yaml")), "md")
    assert isinstance(md, str)
    ((lo, hi),) = _reach({"a": 1.0, "b": 0.4, "c": 1.2, "d": 1.5})
    assert f"only for ${-hi:.1f}^\\circ \\le \\theta_2 \\le {-lo:.1f}^\\circ$ and ${lo:.1f}^\\circ" in md
    assert "The figure shows the open assembly." in md
