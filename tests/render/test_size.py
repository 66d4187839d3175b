"""The budgeted operation count of tutgen.render.size: exact (sympy.count_ops) up to the limit, and a
lower bound that never passes count_ops, so that stopping early never misjudges a result."""

from __future__ import annotations

import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from tests.conftest import SPECS, solved
from tutgen.render.size import count_ops, count_ops_upto, lower_bound_exceeds, size_text

x, y, z, a = sp.symbols("x y z a")
q = sp.Function("q")(sp.Symbol("t"))

SHAPES = [
    pytest.param(x - y, id="difference"),
    pytest.param(-x - y, id="all-negative-sum"),
    pytest.param(x / y, id="quotient"),
    pytest.param(1 / (x * y), id="reciprocal-product"),
    pytest.param(-sp.Rational(1, 3) * x * y**-2, id="negative-fraction-coefficient"),
    pytest.param(sp.sqrt(x + y) / (2 * z), id="root-over-product"),
    pytest.param(sp.exp(-x) * sp.sin(y) ** 2, id="exponential-and-trig-power"),
    pytest.param(x ** (-2 * a) + sp.cos(x - y) * (x + y) ** -1, id="symbolic-negative-power"),
    pytest.param(sp.Derivative(q, sp.Symbol("t")) ** 2 * q, id="derivative-of-applied-function"),
    pytest.param(sp.Add(*(sp.Symbol(f"m{i}") * sp.cos(x) ** i for i in range(12))), id="long-sum"),
    pytest.param(a - x * y, id="minus-product-in-sum"),
    pytest.param(a - x * y / z - 2 * x * z, id="minus-quotients-in-sum"),
    pytest.param(-1 / (x * y), id="minus-reciprocal-product"),
    pytest.param(-x * y * z, id="minus-product"),
    pytest.param(x * sp.exp(-y) - z * sp.exp(y) / 3, id="exponentials-in-products"),
    pytest.param((x + y) * (x - z) * sp.sin(a) / (2 * (y + z) ** 2), id="products-of-sums"),
    pytest.param(sp.Mul(x, sp.Mul(y, z, evaluate=False), evaluate=False), id="nested-product"),
]


@pytest.mark.parametrize("expr", SHAPES)
def test_size_is_count_ops_up_to_the_limit_and_a_lower_bound_beyond(expr):
    ops = int(sp.count_ops(expr))
    assert count_ops_upto([expr], ops) == ops
    assert count_ops_upto([expr], ops - 1) == ops  # over the limit: limit + 1
    assert not lower_bound_exceeds([expr], ops)  # the bound never passes the true count


def test_size_of_matrices_sums_their_entries():
    m = sp.Matrix([[x + y, x * y], [sp.sin(x), 0]])
    assert count_ops_upto([m, x - z], 100) == int(sp.count_ops(m)) + 1


@pytest.mark.parametrize(
    "spec",
    [pytest.param("tutorial-1/p05-rr-arm.yaml", id="p05"), pytest.param("arms/scara.yaml", id="scara")],
)
def test_size_lower_bound_holds_on_derived_results(spec):
    """On real results (trigonometric sums, fractions, rates) the walk never stops before count_ops would."""
    _, d, _ = solved(str(SPECS / spec))
    exprs = [*d.mass_matrix, *d.coriolis_vector, *d.gravity_vector, *d.equations_of_motion, d.kinetic_energy]
    for e in exprs:
        ops = int(sp.count_ops(e))
        assert not lower_bound_exceeds([e], ops), e
        assert count_ops_upto([e], max(ops, 1)) == ops


def test_size_text_says_more_than_past_the_limit():
    assert size_text(10503, 40000) == "10503"
    assert size_text(40001, 40000) == "more than 40000"


# ---------------------------------------------------------------------------------------------
# count_ops: sympy's count, faster (issue 17)
# ---------------------------------------------------------------------------------------------

PRODUCTS = [
    pytest.param(sp.Mul(sp.Rational(3, 2), x + y, evaluate=False), id="fraction-times-sum"),
    pytest.param(sp.Mul(sp.Rational(1, 2), x + y, evaluate=False), id="half-a-sum"),
    pytest.param(sp.Mul(sp.Rational(-3, 4), x - y, evaluate=False), id="minus-fraction-times-sum"),
    pytest.param(sp.Mul(sp.Rational(3, 2), x, sp.Mul(y, z, evaluate=False), evaluate=False), id="nested-in-fraction"),
    pytest.param(sp.Mul(2, sp.Mul(sp.Rational(1, 3), y, evaluate=False), evaluate=False), id="nested-fraction"),
    pytest.param(sp.Rational(5, 7) * x**2 * sp.cos(x + y) * (a + z), id="fraction-times-powers-and-sum"),
    pytest.param(sp.Rational(1, 8) * x * sp.sin(-x + y) - sp.Rational(3, 4) * y * z, id="fractions-in-sum"),
    pytest.param(sp.Pow(sp.E, x) * sp.Rational(1, 2) + sp.E, id="powers-of-e"),
    pytest.param(sp.sqrt(2) * x / 3 + x ** sp.Rational(3, 2) * y, id="roots"),
    pytest.param(sp.Float(0.25) * x * y - sp.Float(1.5), id="floats"),
    pytest.param(-sp.Rational(1, 2) * sp.exp(x) * y, id="exp-in-fraction"),
]


@pytest.mark.parametrize("expr", SHAPES + PRODUCTS)
def test_count_ops_is_sympys(expr):
    assert count_ops(expr) == int(sp.count_ops(expr))


@pytest.mark.parametrize(
    "spec",
    [
        pytest.param("tutorial-1/p05-rr-arm.yaml", id="p05"),
        pytest.param("tutorial-1/p08-spatial-rr.yaml", id="p08"),
        pytest.param("examples/g-heavy-symmetric-top.yaml", id="top"),
        pytest.param("examples/o-slider-crank.yaml", id="slider-crank"),
        pytest.param("arms/scara.yaml", id="scara"),
        pytest.param("arms/puma560-numeric.yaml", id="puma560-numeric"),
    ],
)
def test_count_ops_is_sympys_on_derived_results(spec):
    """Every result and every step's equation of a derivation: sums of products with rational and floating
    coefficients, trigonometric functions of sums, quotients."""
    _, d, _ = solved(str(SPECS / spec))
    exprs = [d.kinetic_energy, d.potential_energy, d.lagrangian, *d.mass_matrix, *d.gravity_vector]
    exprs += [e for st in d.steps for eq in st.equations for e in (eq.lhs, eq.rhs)]
    if len(d.system.coordinates) < 6:
        exprs += [*d.coriolis_vector, *d.equations_of_motion]
    exprs = [e for e in exprs if isinstance(e, sp.Basic)]
    assert len(exprs) > 10
    for e in exprs:
        assert count_ops(e) == int(sp.count_ops(e)), e


@given(
    st.recursive(
        st.sampled_from([x, y, z, a, sp.Integer(2), sp.Integer(-1), sp.Rational(1, 2), sp.Rational(-3, 4), sp.pi]),
        lambda children: st.one_of(
            st.lists(children, min_size=2, max_size=4).map(lambda xs: sp.Add(*xs)),
            st.lists(children, min_size=2, max_size=4).map(lambda xs: sp.Mul(*xs)),
            st.lists(children, min_size=2, max_size=3).map(lambda xs: sp.Mul(*xs, evaluate=False)),
            st.tuples(children, st.integers(min_value=-3, max_value=3)).map(lambda t: t[0] ** t[1]),
            children.map(sp.cos),
            children.map(sp.exp),
        ),
        max_leaves=12,
    )
)
def test_count_ops_is_sympys_on_random_expressions(expr):
    assert count_ops(expr) == int(sp.count_ops(expr))


def test_count_ops_stops_past_its_limit():
    long_sum = sp.Add(*(sp.Symbol(f"m{i}") * sp.cos(x) ** i for i in range(40)))
    full = count_ops(long_sum)
    assert count_ops(long_sum, full) == full
    stopped = count_ops(long_sum, 10)
    assert 10 < stopped < full  # a count past the limit, not the whole walk
