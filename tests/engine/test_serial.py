"""The fast route for serial arms (tutgen/engine/serial.py) and its algebra (tutgen/engine/trigpoly.py).

- trigpoly: products, derivatives and canonical equality, checked against sympy at random points;
- serial_dynamics: H, C q_dot and G equal the general route's (``derive``) on the small serial specs
  of specs/ and on an arm with a fixed tool, a turned box and a massless carriage, and Kane's method
  on a 4-DOF spatial arm with full inertia tensors, a prismatic joint and a joint offset; a fully
  symbolic 6R arm's H is no larger than Kane's;
- properties on random planar chains: H symmetric positive definite, H_dot - 2 C skew, the Christoffel
  contraction equals C q_dot, and agreement with a numeric recursive Newton-Euler pass;
- derive(): a 4-link chain takes the fast path, its Derivation renders in every format, and its
  equations of motion (with dampers, springs, loads) equal Kane's.
"""

from __future__ import annotations

import random
from typing import Any

import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from tests.conftest import SPECS
from tests.engine.test_mechanics_generic import MechanicsModel, Numeric, assert_close, cross_check
from tests.engine.test_mechanics_generic import random_states as named_states
from tests.models import planar_chain, system_of
from tutgen.engine.pipeline import derive
from tutgen.engine.serial import (
    LARGE,
    cse_form,
    is_large_serial_chain,
    is_serial_chain,
    numeric_checks,
    serial_dynamics,
    skew_check,
)
from tutgen.engine.tidy import random_states
from tutgen.engine.trigpoly import NumericEvaluator, TrigAlgebra, TrigPoly
from tutgen.spec.validate import load_system

# ---------------------------------------------------------------------------------------------
# trigpoly
# ---------------------------------------------------------------------------------------------

A, B, X, M, L = sp.symbols("a b x m l")


@pytest.fixture
def alg() -> TrigAlgebra:
    # a, b angles; x a prismatic coordinate; m, l and sqrt(2) l coefficients
    return TrigAlgebra([A, B, X], [True, True, False], [M, L, sp.sqrt(2) * L])


def _samples(alg: TrigAlgebra) -> list[TrigPoly]:
    c = alg.const
    p = alg.cos(0) * c(M) + alg.sin(1) * c(L) + c(X) * alg.sin(0) * alg.cos(1)
    r = alg.sin(0) * alg.sin(1) - alg.cos(1) * c(sp.sqrt(2) * L) + c(sp.Rational(3, 2))
    return [p, r]


def _numeric_zero(expr: sp.Expr, seed: int = 7) -> None:
    for state in random_states(expr.free_symbols, 4, seed):
        assert abs(complex(sp.N(expr.xreplace(state), 30))) < 1e-20, (expr, state)


def test_trigpoly_pythagoras_is_canonical(alg: TrigAlgebra) -> None:
    c, s = alg.cos(0), alg.sin(0)
    assert c * c + s * s == alg.one
    # cos^2 - sin^2 is cos(2a): one term
    assert (c * c - s * s).to_expr() == sp.cos(2 * A)
    assert c * c + s * s != alg.one + alg.one


def test_trigpoly_angle_sum_prints_compactly(alg: TrigAlgebra) -> None:
    m = alg.const(M)
    assert (m * (alg.cos(0) * alg.cos(1) - alg.sin(0) * alg.sin(1))).to_expr() == M * sp.cos(A + B)
    assert (alg.sin(0) * alg.cos(1) - alg.cos(0) * alg.sin(1)).to_expr() == sp.sin(A - B)
    assert (alg.cos(1) * alg.sin(0) + alg.sin(1) * alg.cos(0)).to_expr() == sp.sin(A + B)


def test_trigpoly_products_and_round_trip(alg: TrigAlgebra) -> None:
    p, r = _samples(alg)
    ep, er = p.to_expr(), r.to_expr()
    _numeric_zero((p * r).to_expr() - ep * er)
    _numeric_zero((p * r * p).to_expr() - ep * er * ep)
    _numeric_zero((p - r + r * r).to_expr() - (ep - er + er**2))


def test_trigpoly_products_commute_and_associate(alg: TrigAlgebra) -> None:
    p, r = _samples(alg)
    q = alg.cos(1) + alg.const(X) * alg.sin(0)
    assert p * r == r * p
    assert (p * r) * q == p * (r * q)
    assert p * (r + q) == p * r + p * q
    assert p * r != r * r


@pytest.mark.parametrize("index, symbol", [(0, A), (1, B), (2, X)], ids=["angle-a", "angle-b", "prismatic-x"])
def test_trigpoly_derivatives_exact(alg: TrigAlgebra, index: int, symbol: sp.Symbol) -> None:
    p, r = _samples(alg)
    f = p * r * r
    _numeric_zero(f.diff(index).to_expr() - sp.diff(f.to_expr(), symbol))
    # the product rule holds exactly (canonical form), not only numerically
    assert (p * r).diff(index) == p.diff(index) * r + p * r.diff(index)


def test_trigpoly_numeric_evaluator_matches_sympy(alg: TrigAlgebra) -> None:
    p, r = _samples(alg)
    polys = [p, r, p * r, (p * r).diff(0)]
    evaluate = NumericEvaluator(alg, polys)
    rng = random.Random(3)
    for _ in range(3):
        values = {s: rng.uniform(-2, 2) for s in (A, B, X, M, L)}
        got = evaluate(values)
        for poly, value in zip(polys, got, strict=True):
            assert abs(float(poly.to_expr().subs(values)) - value) < 1e-9


def test_trigpoly_coefficients_are_grouped(alg: TrigAlgebra) -> None:
    c = alg.const
    # 2 m l^2 + 2 m l x: one common factor, not two products
    e = (c(2 * M * L**2) + c(2 * M * L * X)).to_expr()
    assert sp.expand(e - (2 * M * L**2 + 2 * M * L * X)) == 0
    assert sp.count_ops(e) < sp.count_ops(2 * M * L**2 + 2 * M * L * X)


# ---------------------------------------------------------------------------------------------
# serial_dynamics against the general route on the specs
# ---------------------------------------------------------------------------------------------

SMALL_SERIAL = [
    "examples/a-double-pendulum-rods.yaml",  # composite bodies (rods)
    "examples/d-planar-3r-arm.yaml",
    "examples/g-heavy-symmetric-top.yaml",  # spatial, gimbal frames
    "tutorial-1/p05-rr-arm.yaml",
    "tutorial-1/p08-spatial-rr.yaml",
    "tutorial-1/p09-pr-manipulator.yaml",  # prismatic, singular H
]


def _assert_equal_at_states(ours: sp.MatrixBase, theirs: sp.MatrixBase, count: int = 3) -> None:
    diff = sp.Matrix(ours) - sp.Matrix(theirs)
    for state in random_states(diff.free_symbols | sp.Matrix(theirs).free_symbols, count, seed=11):
        values = [complex(sp.N(e.xreplace(state), 30)) for e in diff]
        scale = max(1.0, *(abs(complex(sp.N(e.xreplace(state), 30))) for e in sp.Matrix(theirs)))
        assert max(abs(v) for v in values) < 1e-12 * scale, (values, state)


@pytest.mark.parametrize("name", SMALL_SERIAL)
def test_serial_equals_general_route(name: str) -> None:
    system = load_system(SPECS / name)
    assert is_serial_chain(system)
    assert not is_large_serial_chain(system)  # these stay on the general route in derive()
    dyn = serial_dynamics(system)
    general = derive(system, "lagrange")
    _assert_equal_at_states(dyn.mass_matrix, general.mass_matrix)
    _assert_equal_at_states(dyn.coriolis_vector, general.coriolis_vector)
    assert not system.springs
    _assert_equal_at_states(dyn.gravity_vector, general.gravity_vector)
    # the Christoffel symbols in both conventions, and C, as the general route lists them
    n = len(system.coordinates)
    for table, ref in (
        (dyn.christoffel, general.christoffel),
        (dyn.christoffel_first_kind, general.christoffel_first_kind),
    ):
        keys = [(i, j, k) for i in range(n) for j in range(n) for k in range(n)]
        _assert_equal_at_states(
            sp.Matrix([table.get(key, 0) for key in keys]), sp.Matrix([ref[key] for key in keys]), count=2
        )
    _assert_equal_at_states(dyn.coriolis_matrix, general.coriolis_matrix, count=2)


def tool_arm() -> dict[str, Any]:
    """R-P-R with a fixed joint carrying a tool (a turned box plus a point mass), a joint offset, a
    fixed rotation with a symbolic angle and a massless frame: the corners of the model's conventions."""
    return {
        "tutgen": 1,
        "title": "arm with a tool",
        "parameters": ["m1", "m3", "mt", "l1", "l2", "b", "alpha", "off", "g"],
        "coordinates": ["q1", "s", "q3"],
        "gravity": [0, "-g", 0],
        "bodies": {
            "link1": {"mass": "m1", "com": ["l1/2", 0, 0], "inertia": {"zz": "m1*l1**2/12", "xy": "m1*b**2"}},
            "carriage": {},
            "link3": {"mass": "m3", "com": [0, "l2", 0], "inertia": {"xx": "m3*b**2", "yz": "m3*l2*b/3"}},
            "tool": {
                "parts": {
                    "block": {
                        "shape": "box",
                        "mass": "mt",
                        "size": ["b", "2*b", "b/2"],
                        "at": [0, 0, "b"],
                        "orientation": [{"axis": "z", "angle": "pi/6"}],
                    },
                    "tip": {"shape": "point", "mass": "mt/2", "at": ["b", "b", 0]},
                }
            },
        },
        "joints": {
            "j1": {"type": "revolute", "parent": "ground", "child": "link1", "axis": "z", "coordinate": "q1"},
            "slide": {
                "type": "prismatic",
                "parent": "link1",
                "child": "carriage",
                "origin": ["l1", 0, 0],
                "orientation": [{"axis": "y", "angle": "alpha"}],
                "axis": "x",
                "coordinate": "s",
            },
            "j3": {
                "type": "revolute",
                "parent": "carriage",
                "child": "link3",
                "axis": "y",
                "offset": "off",
                "coordinate": "q3",
            },
            "mount": {
                "type": "fixed",
                "parent": "link3",
                "child": "tool",
                "origin": [0, "l2", 0],
                "orientation": [{"axis": "x", "angle": "pi/2"}],
            },
        },
    }


@pytest.mark.slow  # half a minute: the general route of a 5-joint arm; the 3R/4R/6R routes are checked by default
def test_serial_tool_arm_equals_general_route() -> None:
    system = system_of(tool_arm())
    assert is_serial_chain(system)
    dyn = serial_dynamics(system)
    general = derive(system, "lagrange")
    _assert_equal_at_states(dyn.mass_matrix, general.mass_matrix, count=2)
    _assert_equal_at_states(dyn.coriolis_vector, general.coriolis_vector, count=2)
    _assert_equal_at_states(dyn.gravity_vector, general.gravity_vector, count=2)
    assert numeric_checks(system, dyn, states=2).agreement < 1e-9


def test_serial_planar_arm_is_as_compact_as_trigsimp() -> None:
    # the lumped-mass 3R arm: H in angle sums, e.g. H_12 carries cos(theta2 + theta3)
    system = load_system(SPECS / "examples/d-planar-3r-arm.yaml")
    h = serial_dynamics(system).mass_matrix
    t2, t3 = (c.q for c in system.coordinates[1:])
    assert h[0, 1].has(sp.cos(t2 + t3)) and not h.has(sp.sin)
    trig = h.atoms(sp.cos)
    assert trig == {sp.cos(t2), sp.cos(t3), sp.cos(t2 + t3)}


def test_serial_rejects_what_it_cannot_do() -> None:
    # an absolute angle (belt drive), a body placed by position, a given energy: not serial
    assert not is_serial_chain(load_system(SPECS / "tutorial-1/p07-belt-driven-arm.yaml"))
    assert not is_serial_chain(load_system(SPECS / "tutorial-1/p10-given-kinetic-energy.yaml"))
    assert not is_serial_chain(load_system(SPECS / "examples/e-bead-in-rotating-tube.yaml"))


# ---------------------------------------------------------------------------------------------
# against Kane's method: a 4-DOF spatial arm, every inertia entry symbolic
# ---------------------------------------------------------------------------------------------


def spatial_arm() -> dict[str, Any]:
    """R-R-P-R: a vertical waist, a shoulder turned by -90 deg about x, a prismatic boom, a wrist at
    +90 deg with a symbolic offset; every link with a mass, a 3-vector com and a full inertia tensor."""
    params = ["d1", "a2", "phi", "g"]
    bodies: dict[str, Any] = {}
    for i in range(1, 5):
        params += [f"m{i}", f"cx{i}", f"cy{i}", f"cz{i}", *(f"I{a}{i}" for a in ("xx", "yy", "zz", "xy", "xz", "yz"))]
        bodies[f"link{i}"] = {
            "mass": f"m{i}",
            "com": [f"cx{i}", f"cy{i}", f"cz{i}"],
            "inertia": {a: f"I{a}{i}" for a in ("xx", "yy", "zz", "xy", "xz", "yz")},
        }
    return {
        "tutgen": 1,
        "title": "spatial RRPR arm",
        "parameters": params,
        "coordinates": ["q1", "q2", "q3", "q4"],
        "gravity": [0, 0, "-g"],
        "bodies": bodies,
        "joints": {
            "waist": {"type": "revolute", "parent": "ground", "child": "link1", "axis": "z", "coordinate": "q1"},
            "shoulder": {
                "type": "revolute",
                "parent": "link1",
                "child": "link2",
                "origin": [0, 0, "d1"],
                "orientation": [{"axis": "x", "angle": "-pi/2"}],
                "axis": "z",
                "coordinate": "q2",
            },
            "boom": {
                "type": "prismatic",
                "parent": "link2",
                "child": "link3",
                "origin": ["a2", 0, 0],
                "axis": "x",
                "coordinate": "q3",
            },
            "wrist": {
                "type": "revolute",
                "parent": "link3",
                "child": "link4",
                "orientation": [{"axis": "y", "angle": "pi/2"}],
                "axis": "z",
                "offset": "phi",
                "coordinate": "q4",
            },
        },
    }


def test_serial_equals_kane_spatial_arm() -> None:
    system = system_of(spatial_arm())
    assert is_large_serial_chain(system)
    dyn = serial_dynamics(system)
    ref = MechanicsModel(system).kane()  # no loads: Kane's forcing is -(C q_dot + G)
    ours = {"H": dyn.mass_matrix, "C+G": dyn.coriolis_vector + dyn.gravity_vector}
    theirs = {"H": ref.mass_matrix, "C+G": -ref.forcing}
    for state in named_states(system, seed=5, count=2):
        for key in ours:
            assert_close(key, Numeric(ours[key])(state), Numeric(theirs[key])(state), state)
    assert skew_check(dyn)


def _is_canonical(expr: sp.Expr) -> bool:
    """Every sum and product is the object sympy's own Add/Mul would build from its arguments (the
    output is assembled without sympy's flatten); a number times a sum is kept, as _keep_coeff does."""
    for node in sp.preorder_traversal(expr):
        if node.is_Add and sp.Add(*node.args) != node:
            return False
        if node.is_Mul and not (len(node.args) == 2 and node.args[0].is_Number and node.args[1].is_Add):
            if sp.Mul(*node.args) != node:
                return False
    return True


def test_trigpoly_output_is_canonical_sympy() -> None:
    # sin(a - b - c): sympy writes it -sin(-a + b + c), so the sign must go into the coefficient
    a, b, c = sp.symbols("a b c")
    alg = TrigAlgebra([a, b, c], [True, True, True], [M, L])
    e = (alg.const(M) * alg.sin(0) * alg.cos(1) * alg.cos(2) + alg.const(L) * alg.sin(2)).to_expr()
    assert _is_canonical(e)
    assert e.has(sp.sin(-a + b + c))
    _numeric_zero(e - (M * sp.sin(a) * sp.cos(b) * sp.cos(c) + L * sp.sin(c)))


def test_trigpoly_trig_factors_are_what_sympy_evaluates() -> None:
    """cos/sin are built unevaluated (sympy's rules tried on every argument were most of converting a
    6-DOF arm's H): each is the object sympy's evaluated cos/sin of its argument gives, equal and with the
    same hash, on every arm of specs/arms and a chain whose angle sums need their sign pulled out."""
    a, b, c = sp.symbols("a b c")
    alg = TrigAlgebra([a, b, c], [True, True, True], [M])
    exprs = [(alg.sin(0) * alg.cos(1) * alg.sin(2) - alg.cos(0) * alg.cos(1) * alg.cos(2) * alg.cos(2)).to_expr()]
    for spec in sorted((SPECS / "arms").glob("*.yaml")):
        dyn = serial_dynamics(load_system(spec))
        exprs += [*dyn.mass_matrix, *dyn.gravity_vector, dyn.potential_energy]
    seen = 0
    for e in exprs:
        for node in sp.preorder_traversal(e):
            if isinstance(node, (sp.sin, sp.cos)):
                seen += 1
                evaluated = type(node)(*node.args)
                assert evaluated == node and hash(evaluated) == hash(node) and type(evaluated) is type(node)
    assert seen > 100


def test_trigpoly_combination_is_the_sum(alg: TrigAlgebra) -> None:
    p, r = _samples(alg)
    q = p * r
    half = sp.QQ(1, 2)
    expected = (p + r - q).scale(alg.ring.ground_new(half))
    assert TrigPoly.combination([p, r], [q], half) == expected
    assert TrigPoly.combination([p], [p], half) == alg.zero
    assert TrigPoly.combination([q, q], [p], sp.QQ(3)) == (q + q - p).scale(alg.ring.ground_new(sp.QQ(3)))


def test_serial_output_is_canonical_sympy() -> None:
    dyn = serial_dynamics(system_of(spatial_arm()))
    assert all(_is_canonical(e) for e in dyn.mass_matrix)
    assert all(_is_canonical(e) for e in (*dyn.coriolis_vector, *dyn.gravity_vector))
    # equal to the same expression rebuilt by sympy, so == and hashing behave
    h00 = dyn.mass_matrix[0, 0]
    assert h00.func(*h00.args) == h00 and hash(h00.func(*h00.args)) == hash(h00)


# ---------------------------------------------------------------------------------------------
# properties on random planar chains
# ---------------------------------------------------------------------------------------------


@given(n=st.integers(min_value=2, max_value=6), seed=st.integers(min_value=0, max_value=10**6))
def test_serial_planar_chain_properties(n: int, seed: int) -> None:
    system = system_of(planar_chain(n, seed))
    assert is_serial_chain(system)
    dyn = serial_dynamics(system)
    report = numeric_checks(system, dyn, states=2, seed=seed)
    # positive semi-definite: two prismatic joints along the same axis in a row make H singular
    assert report.lowest_eigenvalue > -1e-12
    assert report.skew < 1e-10
    assert report.agreement < 1e-9
    assert dyn.mass_matrix == dyn.mass_matrix.T


def puma_like() -> dict[str, Any]:
    """A PUMA-like 6R arm, fully symbolic: every link mass, centre of mass and inertia entry a symbol."""
    spec = spatial_arm()
    geometry = [
        ([0, 0, 0], None),
        ([0, 0, "d1"], "-pi/2"),
        (["a2", 0, "d2"], None),
        (["a3", "d4", 0], "-pi/2"),
        ([0, 0, 0], "pi/2"),
        ([0, 0, 0], "-pi/2"),
    ]
    params = ["d1", "a2", "d2", "a3", "d4", "g"]
    bodies: dict[str, Any] = {}
    joints: dict[str, Any] = {}
    for i, (origin, twist) in enumerate(geometry, 1):
        params += [f"m{i}", f"cx{i}", f"cy{i}", f"cz{i}", *(f"I{a}{i}" for a in ("xx", "yy", "zz", "xy", "xz", "yz"))]
        bodies[f"link{i}"] = {
            "mass": f"m{i}",
            "com": [f"cx{i}", f"cy{i}", f"cz{i}"],
            "inertia": {a: f"I{a}{i}" for a in ("xx", "yy", "zz", "xy", "xz", "yz")},
        }
        joint: dict[str, Any] = {
            "type": "revolute",
            "parent": "ground" if i == 1 else f"link{i - 1}",
            "child": f"link{i}",
            "origin": origin,
            "coordinate": f"q{i}",
        }
        if twist:
            joint["orientation"] = [{"axis": "x", "angle": twist}]
        joints[f"joint{i}"] = joint
    return spec | {
        "title": "PUMA-like arm",
        "parameters": params,
        "coordinates": [f"q{i}" for i in range(1, 7)],
        "bodies": bodies,
        "joints": joints,
    }


def test_serial_six_dof_no_larger_than_kane() -> None:
    # KanesMethod's unsimplified H of this arm has 40772 operations (sympy 1.14, measured with the
    # reference model of test_mechanics_generic.py; it takes 4-10 s, so it is not rebuilt here)
    system = system_of(puma_like())
    dyn = serial_dynamics(system)
    assert sp.count_ops(dyn.mass_matrix) <= 40772
    report = numeric_checks(system, dyn, states=1)
    assert report.agreement < 1e-9 and report.skew < 1e-10 and report.lowest_eigenvalue > 0


def test_serial_planar_as_compact_as_kane_trigsimp() -> None:
    # the lumped-mass 3R arm: sympy.trigsimp of Kane's H has 149 operations (sympy 1.14)
    h = serial_dynamics(load_system(SPECS / "examples/d-planar-3r-arm.yaml")).mass_matrix
    assert sp.count_ops(h) <= 149


def test_serial_christoffel_contraction_is_c() -> None:
    system = system_of(planar_chain(3, 17))
    dyn = serial_dynamics(system)
    qd = dyn.rates
    n = len(qd)
    for table in (dyn.christoffel, dyn.christoffel_first_kind):
        contraction = sp.Matrix(
            [
                sum((table.get((i, j, k), 0) * qd[j] * qd[k] for j in range(n) for k in range(n)), sp.Integer(0))
                for i in range(n)
            ]
        )
        _assert_equal_at_states(contraction, dyn.coriolis_vector)
    _assert_equal_at_states(dyn.coriolis_matrix * sp.Matrix(qd), dyn.coriolis_vector)


def test_serial_cse_form_is_smaller() -> None:
    dyn = serial_dynamics(system_of(spatial_arm()))
    replacements, reduced = cse_form(dyn)
    before = sum(sp.count_ops(m) for m in (dyn.mass_matrix, dyn.coriolis_vector, dyn.gravity_vector))
    after = sum(sp.count_ops(e) for _, e in replacements) + sum(sp.count_ops(m) for m in reduced)
    assert after < before
    back = reduced[0].xreplace(dict(reversed(replacements)))
    for _ in range(len(replacements)):  # substitute nested definitions
        back = back.xreplace(dict(replacements))
    _assert_equal_at_states(back[:2, :2], dyn.mass_matrix[:2, :2], count=1)


# ---------------------------------------------------------------------------------------------
# derive() on a large chain
# ---------------------------------------------------------------------------------------------


def test_derive_takes_the_fast_path_and_renders() -> None:
    from tutgen.render.jsonout import derivation_to_json, dumps

    system = system_of(planar_chain(LARGE, 3, conservative=False))  # dampers, forces, a tip load
    d = derive(system)
    assert d.lagrange_terms == () and d.newton_euler is None
    assert "serial chain" in d.remarks[0]
    assert all(c.passed for c in d.checks)
    assert {c.name for c in d.checks} >= {
        "matrix_form_equals_newton_euler",
        "skew_symmetry",
        "positive_semidefinite_mass_matrix",
    }
    cross_check(system, d, "fast-path")  # H, Q - C - G and the EOM against Kane's
    assert '"mass_matrix"' in dumps(derivation_to_json(d))
    _render_all(d)


def _render_all(d: Any) -> None:
    from tutgen.render.latex import render_latex
    from tutgen.render.markdown import render_markdown

    assert "Christoffel" in render_markdown(d)
    assert "\\begin{document}" in render_latex(d)
