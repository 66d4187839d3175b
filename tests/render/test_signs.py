"""tutgen.render.signs: the signs read off numbers are sympy's answers."""

from __future__ import annotations

import sympy as sp
from sympy.core.function import _coeff_isneg

from tutgen.render.order import positive_lead
from tutgen.render.signs import coefficient_negative, commutative_factors, negative_number

x, y = sp.symbols("x y")
A, B = sp.symbols("A B", commutative=False)

NUMBERS = [
    sp.Integer(0),
    sp.Integer(3),
    sp.Integer(-3),
    sp.S.NegativeOne,
    sp.Rational(-2, 7),
    sp.Rational(5, 3),
    sp.Float("2.5"),
    sp.Float("-2.5"),
    sp.Float("-0.0"),
    sp.Float("1e-300"),
    sp.Float("-1e-300"),
    sp.Float("-3.25e300"),
    sp.Float("-1.5", 50),
    sp.oo,
    -sp.oo,
    sp.zoo,
    sp.nan,
    sp.pi,
    -sp.pi,
    sp.E,
    sp.sqrt(2),
    -sp.sqrt(2),
]

EXPRESSIONS = [
    *NUMBERS,
    x,
    -x,
    2 * x * y,
    -2 * x * y,
    sp.Float("-2.5") * x,
    sp.Float("0.75") * x * sp.sin(y),
    sp.Rational(-1, 3) * x**2,
    -sp.pi * x,
    sp.sqrt(2) * x,
    -sp.sqrt(2) * x,
    x + y,
    -x - y,
    sp.Mul(-3, x, evaluate=False),
    sp.Mul(x, -3, evaluate=False),
    sp.Mul(sp.Float("-1.5"), x, y, evaluate=False),
    sp.Mul(sp.S.NegativeOne, x, evaluate=False),
    sp.sin(x),
    -sp.oo * x,
]


def test_negative_number_is_sympys() -> None:
    for a in EXPRESSIONS:
        assert negative_number(a) == bool(a.is_Number and a.is_extended_negative), a


def test_coefficient_negative_is_coeff_isneg() -> None:
    for a in [*EXPRESSIONS, -2 * x * A, 3 * A * B, sp.MatrixSymbol("M", 2, 2) * -2]:
        assert coefficient_negative(a) == bool(_coeff_isneg(a)), a


def test_commutative_factors_are_args_cnc() -> None:
    for a in EXPRESSIONS:
        if a.is_commutative:
            assert commutative_factors(a) == a.args_cnc()[0], a


def test_positive_lead_is_could_extract_minus_sign() -> None:
    for a in EXPRESSIONS:
        if a is sp.nan or a is sp.zoo:
            continue
        sign, body = positive_lead(a)
        expected = a.could_extract_minus_sign()
        assert sign == (-1 if expected else 1), a
        assert body == (-a if expected else a), a
