"""The budgeted operation count of tutgen.render.size: exact (sympy.count_ops) up to the limit, and a
lower bound that never passes count_ops, so that stopping early never misjudges a result."""

from __future__ import annotations

import pytest
import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.render.size import count_ops_upto, lower_bound_exceeds, size_text

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
