"""Tests for tutgen.spec.units: quantities, exact SI conversion and dimensional analysis."""

from __future__ import annotations

import pytest
import sympy as sp

from tutgen.spec.expr import ExprError, parse_expression
from tutgen.spec.units import (
    DIMENSIONS,
    UNITS,
    Dimension,
    DimensionMismatch,
    Quantity,
    UnitError,
    dimension_of,
    parse_quantity,
    parse_unit,
)

D = DIMENSIONS
KNOWN_UNITS = (
    "known units: m, cm, mm, km, um, in, ft, kg, g, mg, t, lb, s, ms, min, h, rad, deg, rev, "
    "N, kN, mN, lbf, J, kJ, W, Pa, kPa, MPa, Hz"
)


# ---------------------------------------------------------------------------------------------
# Dimension
# ---------------------------------------------------------------------------------------------


def test_dimension_arithmetic() -> None:
    force = D["mass"] * D["acceleration"]
    assert force == D["force"] == Dimension(1, 1, -2)
    assert D["energy"] / D["length"] == D["force"]
    assert D["length"] ** 3 == D["volume"]
    assert D["time"] ** -1 == D["frequency"]
    assert D["length"] ** 0 == D["dimensionless"]
    assert D["angle"].is_dimensionless and D["dimensionless"].is_dimensionless
    assert not D["mass"].is_dimensionless
    with pytest.raises(TypeError):
        D["length"] ** 0.5  # type: ignore[operator]
    with pytest.raises(TypeError):
        D["length"] * 2  # type: ignore[operator]


@pytest.mark.parametrize(
    ("name", "text"),
    [
        pytest.param("dimensionless", "1", id="dimensionless"),
        pytest.param("angle", "1", id="angle"),
        pytest.param("mass", "kg", id="mass"),
        pytest.param("length", "m", id="length"),
        pytest.param("area", "m^2", id="area"),
        pytest.param("density", "kg/m^3", id="density"),
        pytest.param("velocity", "m/s", id="velocity"),
        pytest.param("angular_velocity", "1/s", id="angular-velocity"),
        pytest.param("force", "kg*m/s^2", id="force"),
        pytest.param("torque", "kg*m^2/s^2", id="torque"),
        pytest.param("power", "kg*m^2/s^3", id="power"),
        pytest.param("inertia", "kg*m^2", id="inertia"),
        pytest.param("stiffness", "kg/s^2", id="stiffness"),
        pytest.param("damping", "kg/s", id="damping"),
        pytest.param("torsional_damping", "kg*m^2/s", id="torsional-damping"),
        pytest.param("pressure", "kg/(m*s^2)", id="pressure"),
    ],
)
def test_dimension_text(name: str, text: str) -> None:
    assert str(D[name]) == text


def test_dimension_table() -> None:
    assert set(D) == {
        "dimensionless", "angle", "mass", "length", "time", "area", "volume", "density", "velocity",
        "acceleration", "angular_velocity", "force", "torque", "energy", "power", "inertia", "stiffness",
        "torsional_stiffness", "damping", "torsional_damping", "frequency", "pressure",
    }  # fmt: skip
    assert D["torsional_stiffness"] == D["energy"] == D["torque"]
    assert D["angular_velocity"] == D["frequency"]
    assert D["stiffness"] == D["force"] / D["length"]
    assert D["damping"] == D["force"] * D["time"] / D["length"]
    assert D["torsional_damping"] == D["torque"] * D["time"]
    assert D["pressure"] == D["force"] / D["area"]
    assert D["power"] == D["energy"] / D["time"]


@pytest.mark.parametrize("name", sorted(D))
def test_dimension_text_parses_back(name: str) -> None:
    assert parse_unit(str(D[name])) == (sp.Integer(1), D[name])


# ---------------------------------------------------------------------------------------------
# Quantities
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "value", "dimension", "unit"),
    [
        pytest.param("15 cm", sp.Rational(3, 20), D["length"], "cm", id="cm"),
        pytest.param("15cm", sp.Rational(3, 20), D["length"], "cm", id="no-space"),
        pytest.param("  15 \t cm  ", sp.Rational(3, 20), D["length"], "cm", id="padded"),
        pytest.param("-9.81 m/s^2", sp.Rational(-981, 100), D["acceleration"], "m/s^2", id="negative"),
        pytest.param("9.81 m/s**2", sp.Rational(981, 100), D["acceleration"], "m/s**2", id="double-star"),
        pytest.param("7849 kg/m^3", sp.Integer(7849), D["density"], "kg/m^3", id="density"),
        pytest.param("7849 kg m^-3", sp.Integer(7849), D["density"], "kg m^-3", id="negative-power"),
        pytest.param("7849  kg   m^-3", sp.Integer(7849), D["density"], "kg m^-3", id="normalised-space"),
        pytest.param("1.5 kg*m^2", sp.Rational(3, 2), D["inertia"], "kg*m^2", id="inertia"),
        pytest.param("2 N*m/rad", sp.Integer(2), D["torsional_stiffness"], "N*m/rad", id="torsional"),
        pytest.param("3 N m", sp.Integer(3), D["torque"], "N m", id="space-multiplies"),
        pytest.param("4 N*s/m", sp.Integer(4), D["damping"], "N*s/m", id="damping"),
        pytest.param("2 kg m^2 / s^2", sp.Integer(2), D["energy"], "kg m^2 / s^2", id="spaced-slash"),
        pytest.param("1 kg/(m*s^2)", sp.Integer(1), D["pressure"], "kg/(m*s^2)", id="parenthesised"),
        pytest.param("1 J/s/m", sp.Integer(1), Dimension(1, 1, -3), "J/s/m", id="two-slashes"),
        pytest.param("1 m/s*kg", sp.Integer(1), Dimension(1, 1, -1), "m/s*kg", id="slash-binds-one-factor"),
        pytest.param("3 s^(-2)", sp.Integer(3), Dimension(time=-2), "s^(-2)", id="parenthesised-power"),
        pytest.param("1e-3 kg", sp.Rational(1, 1000), D["mass"], "kg", id="exponent-literal"),
        pytest.param("1e3m", sp.Integer(1000), D["length"], "m", id="exponent-literal-no-space"),
        pytest.param("500 g", sp.Rational(1, 2), D["mass"], "g", id="gram"),
        pytest.param("90 deg", sp.pi / 2, D["angle"], "deg", id="deg"),
        pytest.param("0.5 rev", sp.pi, D["angle"], "rev", id="rev"),
        pytest.param("60 rev/min", 2 * sp.pi, D["angular_velocity"], "rev/min", id="rpm"),
        pytest.param("1 lbf", sp.Rational(45359237, 10**8) * sp.Rational(980665, 10**5), D["force"], "lbf", id="lbf"),
        pytest.param("2 lb", sp.Rational(45359237, 5 * 10**7), D["mass"], "lb", id="lb"),
        pytest.param("10 in", sp.Rational(254, 1000), D["length"], "in", id="inch"),
        pytest.param("1 ft", sp.Rational(3048, 10000), D["length"], "ft", id="foot"),
        pytest.param("3 um", sp.Rational(3, 10**6), D["length"], "um", id="micrometre"),
        pytest.param("2 h", sp.Integer(7200), D["time"], "h", id="hour"),
        pytest.param("2 t", sp.Integer(2000), D["mass"], "t", id="tonne"),
        pytest.param("200 MPa", sp.Integer(2 * 10**8), D["pressure"], "MPa", id="megapascal"),
        pytest.param("50 Hz", sp.Integer(50), D["frequency"], "Hz", id="hertz"),
        pytest.param("3 kJ", sp.Integer(3000), D["energy"], "kJ", id="kilojoule"),
        pytest.param("7 W", sp.Integer(7), D["power"], "W", id="watt"),
        pytest.param("2 cm^2", sp.Rational(1, 5000), D["area"], "cm^2", id="unit-power-scales-factor"),
    ],
)
def test_quantities(text: str, value: sp.Expr, dimension: Dimension, unit: str) -> None:
    quantity = parse_quantity(text)
    assert quantity == Quantity(value=value, dimension=dimension, unit=unit)
    assert quantity is not None and not quantity.value.has(sp.Float)


def test_quantity_values_are_exact() -> None:
    quantity = parse_quantity("15 cm")
    assert quantity is not None and quantity.value == sp.Rational(3, 20)
    quantity = parse_quantity("90 deg")
    assert quantity is not None and quantity.value == sp.pi / 2


def test_unit_factors_are_exact() -> None:
    assert UNITS["in"][0] == sp.Rational(254, 10000)
    assert UNITS["ft"][0] == sp.Rational(3048, 10000)
    assert UNITS["lb"][0] == sp.Rational(45359237, 10**8)
    assert UNITS["lbf"] == (sp.Rational(45359237, 10**8) * sp.Rational(980665, 100000), D["force"])
    assert UNITS["deg"] == (sp.pi / 180, D["angle"])
    assert UNITS["rev"] == (2 * sp.pi, D["angle"])
    assert all(not factor.has(sp.Float) for factor, _ in UNITS.values())


@pytest.mark.parametrize(
    "text",
    [
        pytest.param("0.05", id="bare-number"),
        pytest.param("-3", id="bare-negative"),
        pytest.param("m1 + 2", id="expression"),
        pytest.param("2*l", id="product"),
        pytest.param("2 * l", id="spaced-product"),
        pytest.param("1/2", id="fraction"),
        pytest.param("(2) m", id="parenthesised-number"),
        pytest.param("", id="empty"),
        pytest.param("kg", id="unit-alone"),
        pytest.param("- 5 m", id="detached-sign"),
        pytest.param("15 " * 1000 + "cm", id="too-long"),
    ],
)
def test_not_quantities(text: str) -> None:
    assert parse_quantity(text) is None


@pytest.mark.parametrize(
    ("text", "message", "offset", "hint"),
    [
        pytest.param("15 cms", "unknown unit 'cms'", 3, "did you mean 'cm'?", id="plural"),
        pytest.param("3 KG", "unknown unit 'KG'", 2, "did you mean 'kg'?", id="case"),
        pytest.param("2 sec", "unknown unit 'sec'", 2, "did you mean 's'?", id="alias"),
        pytest.param("100 rpm", "unknown unit 'rpm'", 4, "did you mean 'rev/min'?", id="rpm"),
        pytest.param("1 kgg", "unknown unit 'kgg'", 2, "did you mean 'kg'?", id="close"),
        pytest.param("1 kg*mm2", "unknown unit 'mm2'", 5, "write powers with '^', e.g. 'mm^2'", id="glued-power"),
        pytest.param("1 zzz", "unknown unit 'zzz'", 2, KNOWN_UNITS, id="nothing-close"),
        pytest.param("2 e", "unknown unit 'e'", 2, KNOWN_UNITS, id="e"),
        pytest.param(
            "2 kg + 3",
            "expected '*', '/', '^' or the end of the unit after 'kg', found '+'",
            5,
            "a quantity is one number followed by a unit, e.g. '15 cm' or '9.81 m/s^2'",
            id="arithmetic",
        ),
        pytest.param("1 m/", "expected a unit after '/', found the end of the unit", 4, None, id="trailing-slash"),
        pytest.param("1 N*", "expected a unit after '*', found the end of the unit", 4, None, id="trailing-star"),
        pytest.param(
            "1 m^x",
            "expected a whole-number power after '^', found 'x'",
            4,
            "unit powers are whole numbers, e.g. 'm^2' or 's^-2'",
            id="symbolic-power",
        ),
        pytest.param(
            "1 m^",
            "expected a whole-number power after '^', found the end of the unit",
            4,
            "unit powers are whole numbers, e.g. 'm^2' or 's^-2'",
            id="missing-power",
        ),
        pytest.param(
            "1 m^1.5",
            "unexpected character '.' in a unit",
            5,
            "multiply units with '*' or a space, e.g. 'N*m' or 'N m'; unit powers are whole numbers",
            id="fractional-power",
        ),
        pytest.param("1 m^65", "the power of a unit is too large (the limit is ±64)", 4, None, id="huge-power"),
        pytest.param("1 m^(2", "expected ')' after '2', found the end of the unit", 6, None, id="unclosed-power"),
        pytest.param(
            "1 kg/(m*s",
            "unclosed '(' in the unit: expected ')', found the end of the unit",
            5,
            None,
            id="unclosed",
        ),
        pytest.param("1 kg)", "unmatched ')' in the unit: there is no '(' before it", 4, None, id="unmatched"),
        pytest.param("3 µm", "unexpected character 'µ' in a unit", 2, "write micro as 'u', e.g. 'um'", id="micro-sign"),
        pytest.param(
            "1 m 2",
            "expected '*', '/', '^' or the end of the unit after 'm', found '2'",
            4,
            "a unit cannot contain a number; write powers with '^', e.g. 'm^2'",
            id="number-in-unit",
        ),
        pytest.param(
            "1 N·m",
            "unexpected character '·' in a unit",
            3,
            "multiply units with '*' or a space, e.g. 'N*m' or 'N m'",
            id="middle-dot",
        ),
        pytest.param(
            "1 m*" + "(" * 60 + "m",
            "the unit is nested too deeply (more than 50 parentheses)",
            54,
            None,
            id="deep",
        ),
        pytest.param(
            "1e400 m",
            "the decimal exponent of the number '1e400' is out of range (the limit is ±300)",
            0,
            None,
            id="literal-exponent",
        ),
        pytest.param(
            "  -1e400 m",
            "the decimal exponent of the number '1e400' is out of range (the limit is ±300)",
            3,
            None,
            id="literal-offset",
        ),
    ],
)
def test_quantity_errors(text: str, message: str, offset: int, hint: str | None) -> None:
    with pytest.raises(UnitError) as info:
        parse_quantity(text)
    err = info.value
    assert (err.message, err.offset, err.hint) == (message, offset, hint)
    assert isinstance(err, ExprError) and str(err) == message


@pytest.mark.parametrize(
    ("text", "factor", "dimension"),
    [
        pytest.param("kg/m^3", sp.Integer(1), D["density"], id="density"),
        pytest.param(" N  m ", sp.Integer(1), D["torque"], id="spaces"),
        pytest.param("g/cm^3", sp.Integer(1000), D["density"], id="g-per-cc"),
        pytest.param("1/s", sp.Integer(1), D["frequency"], id="one-over"),
        pytest.param("(m/s)^2", sp.Integer(1), D["velocity"] ** 2, id="group-power"),
        pytest.param("km/h", sp.Rational(5, 18), D["velocity"], id="km-per-h"),
        pytest.param("deg/s", sp.pi / 180, D["angular_velocity"], id="deg-per-s"),
        pytest.param("mN*mm", sp.Rational(1, 10**6), D["torque"], id="small-torque"),
    ],
)
def test_parse_unit(text: str, factor: sp.Expr, dimension: Dimension) -> None:
    assert parse_unit(text) == (factor, dimension)


@pytest.mark.parametrize(
    ("text", "message", "offset"),
    [
        pytest.param("", "empty unit", 0, id="empty"),
        pytest.param("   ", "empty unit", 3, id="blank"),
        pytest.param("m/cms", "unknown unit 'cms'", 2, id="unknown"),
        pytest.param("2 m", "expected a unit, found '2'", 0, id="number"),
        pytest.param("m" * 2001, "the unit is too long (2001 characters; the limit is 2000)", 2000, id="long"),
    ],
)
def test_parse_unit_errors(text: str, message: str, offset: int) -> None:
    with pytest.raises(UnitError) as info:
        parse_unit(text)
    assert (info.value.message, info.value.offset) == (message, offset)


# ---------------------------------------------------------------------------------------------
# dimension_of
# ---------------------------------------------------------------------------------------------

m, ell, t, theta, g, k, c, u, w = sp.symbols("m l t theta g k c u w")
q = sp.Function("q")(t)
DIMS: dict[sp.Symbol, Dimension | None] = {
    m: D["mass"],
    ell: D["length"],
    t: D["time"],
    theta: D["angle"],
    g: D["acceleration"],
    k: D["stiffness"],
    c: D["damping"],
    u: None,
}
DIMS_WITH_Q: dict[sp.Basic, Dimension | None] = {**DIMS, q: D["length"]}


@pytest.mark.parametrize(
    ("expr", "expected"),
    [
        pytest.param(sp.Integer(3), D["dimensionless"], id="number"),
        pytest.param(sp.pi / 2, D["dimensionless"], id="pi"),
        pytest.param(sp.sqrt(2) + sp.sin(1), D["dimensionless"], id="numeric-expression"),
        pytest.param(m, D["mass"], id="symbol"),
        pytest.param(u, None, id="symbol-none"),
        pytest.param(w, None, id="symbol-missing"),
        pytest.param(m * ell**2, D["inertia"], id="product"),
        pytest.param(m * g * ell * sp.cos(theta), D["energy"], id="potential-energy"),
        pytest.param(m * ell**2 / 2 + m * ell**2 * sp.sin(theta) ** 2, D["inertia"], id="sum"),
        pytest.param(k / m, D["frequency"] ** 2, id="quotient"),
        pytest.param(sp.sqrt(k / m), D["angular_velocity"], id="natural-frequency"),
        pytest.param(sp.sqrt(ell**2), D["length"], id="sqrt-square"),
        pytest.param(ell**-2, Dimension(length=-2), id="negative-power"),
        pytest.param(theta**2, D["dimensionless"], id="angle-squared"),
        pytest.param(2**theta, D["dimensionless"], id="dimensionless-exponent"),
        pytest.param(ell + u, None, id="sum-with-unknown"),
        pytest.param(ell * u, None, id="product-with-unknown"),
        pytest.param(u**2, None, id="power-of-unknown"),
        pytest.param(sp.sin(theta), D["dimensionless"], id="sin"),
        pytest.param(sp.exp(u) + sp.log(ell / ell), D["dimensionless"], id="exp-of-unknown"),
        pytest.param(sp.atan(ell / ell) + sp.tanh(theta), D["dimensionless"], id="atan-tanh"),
        pytest.param(sp.atan2(ell, ell), D["dimensionless"], id="atan2"),
        pytest.param(sp.atan2(ell, u), D["dimensionless"], id="atan2-unknown"),
        pytest.param(sp.Abs(ell), D["length"], id="abs"),
        pytest.param(sp.sign(ell), D["dimensionless"], id="sign"),
        pytest.param(sp.Derivative(q, t, 2), D["acceleration"], id="derivative"),
        pytest.param(q, D["length"], id="applied-function"),
        pytest.param(
            sp.Eq(m * sp.Derivative(q, t, 2), -k * q - c * sp.Derivative(q, t)),
            D["force"],
            id="equation-of-motion",
        ),
        pytest.param(sp.Piecewise((ell, ell > 0), (m, True)), None, id="unsupported-is-unknown"),
    ],
)
def test_dimension_of(expr: sp.Expr, expected: Dimension | None) -> None:
    assert dimension_of(expr, DIMS_WITH_Q) == expected  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("expr", "message"),
    [
        pytest.param(m + ell, "cannot add m and kg", id="add"),
        pytest.param(ell + 1, "cannot add 1 and m", id="add-number"),
        pytest.param(ell + m + u, "cannot add m and kg", id="add-with-unknown"),
        pytest.param(m * ell**2 + ell, "cannot add m and kg*m^2", id="add-inertia-length"),
        pytest.param(sp.sin(ell + m), "cannot add m and kg", id="nested"),
        pytest.param(u * (ell + m), "cannot add m and kg", id="nested-in-unknown-product"),
        pytest.param(sp.Eq(m, ell), "cannot equate kg and m", id="equation"),
        pytest.param(sp.sin(ell), "the argument of sin must be dimensionless, found m", id="sin"),
        pytest.param(sp.exp(m), "the argument of exp must be dimensionless, found kg", id="exp"),
        pytest.param(sp.log(t), "the argument of log must be dimensionless, found s", id="log"),
        pytest.param(sp.asin(ell), "the argument of asin must be dimensionless, found m", id="asin"),
        pytest.param(sp.cosh(g), "the argument of cosh must be dimensionless, found m/s^2", id="cosh"),
        pytest.param(
            sp.atan2(ell, m),
            "the arguments of atan2 must have the same dimension, found m and kg",
            id="atan2",
        ),
        pytest.param(
            sp.sqrt(ell),
            "cannot raise m to the power 1/2: the result has no whole-number dimension",
            id="sqrt-length",
        ),
        pytest.param(
            ell**u,
            "cannot raise m to the power u: a quantity with a dimension needs a number exponent",
            id="symbolic-exponent",
        ),
        pytest.param(
            ell**sp.pi,
            "cannot raise m to the power pi: a quantity with a dimension needs a number exponent",
            id="irrational-exponent",
        ),
        pytest.param(2**ell, "the exponent of a power must be dimensionless, found m", id="dimensional-exponent"),
        pytest.param(sp.sign(m + ell), "cannot add m and kg", id="sign-checks-argument"),
    ],
)
def test_dimension_mismatch(expr: sp.Expr, message: str) -> None:
    with pytest.raises(DimensionMismatch) as info:
        dimension_of(expr, DIMS)
    assert info.value.message == message
    assert str(info.value) == message
    assert isinstance(info.value, ValueError)


def test_rational_power_with_whole_result() -> None:
    assert dimension_of((m**2 * ell**4) ** sp.Rational(1, 2), DIMS) == Dimension(1, 2, 0)
    assert dimension_of(sp.Pow(ell, sp.Float(2.0), evaluate=False), DIMS) == D["area"]


def test_dimension_of_parsed_expression() -> None:
    names = {"m": m, "l": ell, "g": g, "theta": theta}
    expr = parse_expression("m*g*l*(1 - cos(theta)) + m*l**2/2", names)
    with pytest.raises(DimensionMismatch, match="cannot add"):
        dimension_of(expr, DIMS)
    assert dimension_of(parse_expression("m*g*l*(1 - cos(theta))", names), DIMS) == D["energy"]


def test_quantity_dimension_matches_declared() -> None:
    quantity = parse_quantity("2 N*m/rad")
    assert quantity is not None and quantity.dimension == D["torsional_stiffness"]
    quantity = parse_quantity("7849 kg/m^3")
    assert quantity is not None and quantity.dimension == D["density"]
