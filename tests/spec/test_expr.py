"""Tests for tutgen.spec.expr: the whitelist expression parser (user text is data, never code)."""

from __future__ import annotations

import ast
import builtins
import pickle
import time
from pathlib import Path

import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from tutgen.spec.expr import (
    CONSTANTS,
    FUNCTIONS,
    MAX_DEPTH,
    MAX_DIGITS,
    MAX_EXPONENT,
    MAX_LENGTH,
    ExprError,
    did_you_mean,
    number_to_rational,
    parse_expression,
)

m1, m2, x, y, ell, theta, x_ddot, e = sp.symbols("m1 m2 x y l theta x_ddot e")
SYMS: dict[str, sp.Expr] = {
    "m1": m1,
    "m2": m2,
    "x": x,
    "y": y,
    "l": ell,
    "theta": theta,
    "x_ddot": x_ddot,
    "e": e,
}


def parse(text: str | int | float) -> sp.Expr:
    return parse_expression(text, SYMS)


def error_of(text: object, symbols: dict[str, sp.Expr] | None = None) -> ExprError:
    with pytest.raises(ExprError) as info:
        parse_expression(text, SYMS if symbols is None else symbols)  # type: ignore[arg-type]
    return info.value


# ---------------------------------------------------------------------------------------------
# Values
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        pytest.param("(m1 + m2)*x_ddot + m2*l*cos(theta)", (m1 + m2) * x_ddot + m2 * ell * sp.cos(theta), id="doc"),
        pytest.param("-x**2", -(x**2), id="neg-binds-looser-than-pow"),
        pytest.param("-2**2", sp.Integer(-4), id="neg-number-pow"),
        pytest.param("(-2)**2", sp.Integer(4), id="parenthesised-neg-pow"),
        pytest.param("2^3^2", sp.Integer(512), id="caret-right-assoc"),
        pytest.param("2**3**2", sp.Integer(512), id="pow-right-assoc"),
        pytest.param("2**-1", sp.Rational(1, 2), id="pow-neg-exponent"),
        pytest.param("x**-2**2", x**-4, id="pow-neg-pow-exponent"),
        pytest.param("x^2 + x**2", 2 * x**2, id="caret-equals-pow"),
        pytest.param("x/y/l", x / y / ell, id="div-left-assoc"),
        pytest.param("x - y - l", x - y - ell, id="sub-left-assoc"),
        pytest.param("x - (y - l)", x - y + ell, id="sub-paren"),
        pytest.param("x*y/l*m1", x * y * m1 / ell, id="mul-div-left-to-right"),
        pytest.param("x + y*l", x + y * ell, id="mul-before-add"),
        pytest.param("(x + y)*l", (x + y) * ell, id="parens"),
        pytest.param("+x", x, id="unary-plus"),
        pytest.param("--x", x, id="double-neg"),
        pytest.param("-+-x", x, id="mixed-signs"),
        pytest.param("2*-x", -2 * x, id="mul-by-neg"),
        pytest.param("x**(1/2)", sp.sqrt(x), id="rational-exponent"),
        pytest.param("x**0.5", sp.sqrt(x), id="decimal-exponent"),
        pytest.param("  x\t*\n y  ", x * y, id="whitespace"),
        pytest.param("e*x", e * x, id="e-is-a-plain-name"),
        pytest.param("pi/2", sp.pi / 2, id="pi"),
        pytest.param("atan2(y, x)", sp.atan2(y, x), id="atan2"),
        pytest.param("abs(x) + Abs(y)", sp.Abs(x) + sp.Abs(y), id="abs"),
        pytest.param("sign(x)", sp.sign(x), id="sign"),
        pytest.param("sqrt(x)*exp(y)*log(l)", sp.sqrt(x) * sp.exp(y) * sp.log(ell), id="sqrt-exp-log"),
        pytest.param("sin(cos(tan(x)))", sp.sin(sp.cos(sp.tan(x))), id="nested-calls"),
        pytest.param("asin(x)+acos(x)+atan(x)", sp.asin(x) + sp.acos(x) + sp.atan(x), id="inverse-trig"),
        pytest.param("sinh(x)+cosh(x)+tanh(x)", sp.sinh(x) + sp.cosh(x) + sp.tanh(x), id="hyperbolic"),
        pytest.param("sin(pi)", sp.Integer(0), id="sympy-evaluates"),
        pytest.param("x/(1+1)", x / 2, id="div-by-folded-number"),
    ],
)
def test_values(text: str, expected: sp.Expr) -> None:
    assert sp.expand(parse(text) - expected) == 0


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        pytest.param("12", sp.Integer(12), id="int"),
        pytest.param("0.05", sp.Rational(1, 20), id="decimal"),
        pytest.param(".5", sp.Rational(1, 2), id="leading-dot"),
        pytest.param("5.", sp.Integer(5), id="trailing-dot"),
        pytest.param("1e-3", sp.Rational(1, 1000), id="exponent"),
        pytest.param("6.5E+2", sp.Integer(650), id="upper-exponent"),
        pytest.param("2.e3", sp.Integer(2000), id="dot-exponent"),
        pytest.param("0.1+0.2", sp.Rational(3, 10), id="exact-sum"),
        pytest.param("1/3", sp.Rational(1, 3), id="exact-division"),
        pytest.param("-0.065", sp.Rational(-13, 200), id="negative"),
        pytest.param("1e300", sp.Integer(10) ** 300, id="largest-exponent"),
        pytest.param("1e-300", sp.Rational(1, 10**300), id="smallest-exponent"),
        pytest.param("9" * MAX_DIGITS, sp.Integer(10**MAX_DIGITS - 1), id="most-digits"),
    ],
)
def test_numbers_are_exact(text: str, expected: sp.Expr) -> None:
    result = parse(text)
    assert result == expected
    assert not result.has(sp.Float)


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        pytest.param(3, sp.Integer(3), id="int"),
        pytest.param(0.065, sp.Rational(13, 200), id="float-via-repr"),
        pytest.param(0.1, sp.Rational(1, 10), id="float-tenth"),
        pytest.param(-2.5, sp.Rational(-5, 2), id="negative-float"),
        pytest.param(1e-5, sp.Rational(1, 100000), id="float-exponent"),
        pytest.param(1e16, sp.Integer(10**16), id="float-big"),
    ],
)
def test_yaml_numbers(value: int | float, expected: sp.Expr) -> None:
    assert parse_expression(value, {}) == expected
    assert isinstance(parse_expression(value, {}), sp.Rational)


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        pytest.param(7, sp.Integer(7), id="int"),
        pytest.param(0.065, sp.Rational(13, 200), id="float"),
        pytest.param("1e-3", sp.Rational(1, 1000), id="string-exponent"),
        pytest.param(" -2.5 ", sp.Rational(-5, 2), id="string-signed-padded"),
        pytest.param("+4", sp.Integer(4), id="string-plus"),
    ],
)
def test_number_to_rational(value: int | float | str, expected: sp.Rational) -> None:
    result = number_to_rational(value)
    assert isinstance(result, sp.Rational)
    assert result == expected


@pytest.mark.parametrize(
    ("value", "message", "offset"),
    [
        pytest.param(True, "expected a number, found a boolean", 0, id="bool"),
        pytest.param(float("nan"), "expected a finite number, found nan", 0, id="nan"),
        pytest.param(float("inf"), "expected a finite number, found inf", 0, id="inf"),
        pytest.param("x", "expected a number, found 'x'", 0, id="name"),
        pytest.param("  1 + 2", "expected a number, found '1 + 2'", 2, id="expression"),
        pytest.param("", "expected a number, found ''", 0, id="empty"),
        pytest.param(
            "1e301",
            "the decimal exponent of the number '1e301' is out of range (the limit is ±300)",
            0,
            id="exponent-range",
        ),
        pytest.param(None, "expected a number, found nothing (an empty value)", 0, id="none"),
        pytest.param(10**MAX_DIGITS, "the number has too many digits (the limit is 100)", 0, id="huge-int"),
    ],
)
def test_number_to_rational_errors(value: object, message: str, offset: int) -> None:
    with pytest.raises(ExprError) as info:
        number_to_rational(value)  # type: ignore[arg-type]
    assert (info.value.message, info.value.offset) == (message, offset)


def test_symbols_may_map_to_expressions() -> None:
    assert parse_expression("2*L", {"L": ell + 1}) == 2 * ell + 2


def test_names_are_case_sensitive() -> None:
    big_x = sp.Symbol("X")
    assert parse_expression("X + x", {"X": big_x, "x": x}) == big_x + x


def test_symbol_shadows_function_and_constant_names() -> None:
    s = sp.Symbol("sign")
    assert parse_expression("2*sign", {"sign": s}) == 2 * s
    assert parse_expression("pi", {"pi": x}) == x


def test_tables() -> None:
    assert set(FUNCTIONS) == {
        "sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "exp", "log", "sqrt",
        "atan2", "abs", "Abs", "sign",
    }  # fmt: skip
    assert FUNCTIONS["atan2"] == (sp.atan2, 2)
    assert FUNCTIONS["abs"][0] is sp.Abs
    assert all(arity == 1 for name, (_, arity) in FUNCTIONS.items() if name != "atan2")
    assert dict(CONSTANTS) == {"pi": sp.pi}
    assert (MAX_LENGTH, MAX_DEPTH, MAX_EXPONENT, MAX_DIGITS) == (2000, 50, 64, 100)


# ---------------------------------------------------------------------------------------------
# Errors: message, offset, hint
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "message", "offset", "hint"),
    [
        pytest.param("", "empty expression", 0, None, id="empty"),
        pytest.param("  \t", "empty expression", 0, None, id="blank"),
        pytest.param("x $ y", "unexpected character '$'", 2, None, id="dollar"),
        pytest.param("x % y", "unexpected character '%'", 2, None, id="percent"),
        pytest.param(
            "x = 1",
            "unexpected character '='",
            2,
            "an expression has no '='; write only the expression",
            id="equals",
        ),
        pytest.param(
            "θ",
            "unexpected character 'θ'",
            0,
            "names use only the letters A-Z and a-z, digits and '_', e.g. 'theta'",
            id="greek",
        ),
        pytest.param(
            "x *",
            "expected an expression after '*', found the end of the text",
            3,
            None,
            id="trailing-operator",
        ),
        pytest.param("* x", "expected an expression, found '*'", 0, None, id="leading-operator"),
        pytest.param("x + * y", "expected an expression after '+', found '*'", 4, None, id="two-operators"),
        pytest.param(
            "x ** ",
            "expected an expression after '**', found the end of the text",
            5,
            None,
            id="trailing-pow",
        ),
        pytest.param(
            "()",
            "expected an expression after '(', found ')'",
            1,
            "the parentheses are empty",
            id="empty-parens",
        ),
        pytest.param("(x + 1", "unclosed '(': expected ')', found the end of the text", 0, None, id="unclosed"),
        pytest.param("((x)", "unclosed '(': expected ')', found the end of the text", 0, None, id="unclosed-outer"),
        pytest.param("x + 1)", "unmatched ')': there is no '(' before it", 5, None, id="unmatched"),
        pytest.param(
            "(x y)",
            "expected an operator or ')' after 'x', found 'y'",
            3,
            "write multiplication with '*', e.g. '2*x'",
            id="paren-juxtaposition",
        ),
        pytest.param(
            "2 x",
            "expected an operator or the end of the text after '2', found 'x'",
            2,
            "write multiplication with '*', e.g. '2*x'",
            id="juxtaposition",
        ),
        pytest.param(
            "2(x)",
            "expected an operator or the end of the text after '2', found '('",
            1,
            "write multiplication with '*', e.g. '2*x'",
            id="implicit-call",
        ),
        pytest.param(
            "x, y",
            "expected an operator or the end of the text after 'x', found ','",
            1,
            "',' only separates the arguments of a function call",
            id="comma",
        ),
        pytest.param(
            "(x, y)",
            "expected an operator or ')' after 'x', found ','",
            2,
            "',' only separates the arguments of a function call",
            id="tuple",
        ),
        pytest.param("x // y", "expected an expression after '/', found '/'", 3, None, id="floor-div"),
        pytest.param(
            "m1(2)",
            "'m1' is not a function",
            0,
            "write multiplication with '*', e.g. 'm1*(...)'",
            id="symbol-call",
        ),
        pytest.param(
            "pi(2)",
            "'pi' is not a function",
            0,
            "write multiplication with '*', e.g. 'pi*(...)'",
            id="constant-call",
        ),
        pytest.param(
            "2*sin",
            "expected '(' after the function 'sin', found the end of the text",
            5,
            "call it as 'sin(...)'",
            id="function-without-call",
        ),
        pytest.param(
            "sin x",
            "expected '(' after the function 'sin', found 'x'",
            4,
            "call it as 'sin(...)'",
            id="function-juxtaposition",
        ),
        pytest.param("sin()", "sin() takes 1 argument, found 0", 0, None, id="arity-zero"),
        pytest.param("1 + cos(x, y)", "cos() takes 1 argument, found 2", 4, None, id="arity-two"),
        pytest.param("atan2(y)", "atan2() takes 2 arguments, found 1", 0, None, id="arity-atan2"),
        pytest.param("atan2(y, )", "expected an expression after ',', found ')'", 9, None, id="trailing-comma"),
        pytest.param(
            "sin(x",
            "unclosed '(' of the call to 'sin': expected ')', found the end of the text",
            3,
            None,
            id="unclosed-call",
        ),
        pytest.param(
            "atan2(y x)",
            "expected ',' or ')' after argument 1 of 'atan2', found 'x'",
            8,
            "write multiplication with '*', e.g. '2*x'",
            id="call-juxtaposition",
        ),
        pytest.param("sin(x))", "unmatched ')': there is no '(' before it", 6, None, id="call-extra-paren"),
        pytest.param("thetaa", "unknown name 'thetaa'", 0, "did you mean 'theta'?", id="did-you-mean"),
        pytest.param("2*Theta", "unknown name 'Theta'", 2, "did you mean 'theta'?", id="did-you-mean-case"),
        pytest.param("coss(x)", "unknown name 'coss'", 0, "did you mean 'cos'?", id="did-you-mean-function"),
        pytest.param("E", "unknown name 'E'", 0, "did you mean 'e'?", id="E-is-not-a-constant"),
        pytest.param("1/0", "division by zero", 1, None, id="div-zero"),
        pytest.param("x/(1-1)", "division by zero", 1, None, id="div-folded-zero"),
        pytest.param("x/(y-y)", "division by zero", 1, None, id="div-symbolic-zero"),
        pytest.param("x/0.0", "division by zero", 1, None, id="div-decimal-zero"),
        pytest.param("0**-1", "division by zero (0 to a negative power)", 1, None, id="zero-negative-power"),
        pytest.param("log(0)", "the result of log(...) is not a finite number", 0, None, id="log-zero"),
        pytest.param("1 + tan(pi/2)", "the result of tan(...) is not a finite number", 4, None, id="tan-pole"),
        pytest.param("atan2(0, 0)", "the result of atan2(...) is not a finite number", 0, None, id="atan2-nan"),
        pytest.param(
            "x**y",
            "the exponent must be a number, found 'y'",
            3,
            "a power needs a rational number exponent, e.g. 2, -1 or 1/2",
            id="symbolic-exponent",
        ),
        pytest.param(
            "x^(y + 1)",
            "the exponent must be a number, found '(y + 1)'",
            2,
            "a power needs a rational number exponent, e.g. 2, -1 or 1/2",
            id="symbolic-exponent-expr",
        ),
        pytest.param(
            "2**pi",
            "the exponent must be a number, found 'pi'",
            3,
            "a power needs a rational number exponent, e.g. 2, -1 or 1/2",
            id="irrational-exponent",
        ),
        pytest.param("x**65", "the exponent 65 is too large (the limit is ±64)", 3, None, id="exponent-65"),
        pytest.param("x**-65", "the exponent -65 is too large (the limit is ±64)", 3, None, id="exponent-minus-65"),
        pytest.param(
            "1e301",
            "the decimal exponent of the number '1e301' is out of range (the limit is ±300)",
            0,
            None,
            id="literal-exponent",
        ),
        pytest.param(
            "x + 1e-301",
            "the decimal exponent of the number '1e-301' is out of range (the limit is ±300)",
            4,
            None,
            id="literal-negative-exponent",
        ),
        pytest.param(
            "2*" + "1" * 101,
            f"the number '{'1' * 37}...' has too many digits (101; the limit is 100)",
            2,
            None,
            id="literal-digits",
        ),
        pytest.param(
            "1e300*1e300",
            "a number in the expression is too large (more than about 420 digits)",
            5,
            None,
            id="product-too-large",
        ),
        pytest.param(
            "(2**64)**64",
            "a number in the expression is too large (more than about 420 digits)",
            7,
            None,
            id="power-too-large",
        ),
        pytest.param(
            "x.y",
            "unexpected character '.'",
            1,
            "'.' is only allowed inside a number, e.g. '0.5'",
            id="attribute",
        ),
    ],
)
def test_errors(text: str, message: str, offset: int, hint: str | None) -> None:
    err = error_of(text)
    assert (err.message, err.offset, err.hint) == (message, offset, hint)
    assert str(err) == message


def test_unknown_name_lists_known_names_when_nothing_is_close() -> None:
    err = error_of("zzz", {"b": sp.Symbol("b"), "a": sp.Symbol("a")})
    assert err.message == "unknown name 'zzz'"
    assert err.hint == "known names: a, b, pi, Abs, abs, acos, asin, atan, atan2, cos, cosh, exp, ..."


def test_unknown_name_hint_without_truncation() -> None:
    err = error_of("qq", {})
    assert err.hint is not None and err.hint.startswith("known names: pi, Abs")


@pytest.mark.parametrize(
    ("value", "message"),
    [
        pytest.param(True, "expected an expression, found a boolean", id="true"),
        pytest.param(False, "expected an expression, found a boolean", id="false"),
        pytest.param(None, "expected an expression, found nothing (an empty value)", id="none"),
        pytest.param([1], "expected an expression, found a list", id="list"),
        pytest.param({"a": 1}, "expected an expression, found a mapping", id="mapping"),
        pytest.param(float("nan"), "expected a finite number, found nan", id="nan"),
        pytest.param(float("-inf"), "expected a finite number, found -inf", id="inf"),
    ],
)
def test_non_text_values(value: object, message: str) -> None:
    assert error_of(value).message == message


def test_error_is_a_value_error_and_pickles() -> None:
    err = ExprError("boom", 3, "try this")
    assert isinstance(err, ValueError)
    copy = pickle.loads(pickle.dumps(err))
    assert (copy.message, copy.offset, copy.hint, str(copy)) == ("boom", 3, "try this", "boom")
    assert (ExprError("m").offset, ExprError("m").hint) == (0, None)


def test_first_error_is_the_leftmost() -> None:
    assert error_of("x + * y $").offset == 4
    assert error_of("bogus $").message == "unknown name 'bogus'"


# ---------------------------------------------------------------------------------------------
# Code is never executed
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "message", "offset"),
    [
        pytest.param("__import__('os').system('id')", "unknown name '__import__'", 0, id="import"),
        pytest.param("().__class__", "expected an expression after '(', found ')'", 1, id="dunder-class"),
        pytest.param('eval("1")', "unknown name 'eval'", 0, id="eval"),
        pytest.param("exec('1')", "unknown name 'exec'", 0, id="exec"),
        pytest.param("os", "unknown name 'os'", 0, id="os"),
        pytest.param("lambda: 1", "unknown name 'lambda'", 0, id="lambda"),
        pytest.param("x.y", "unexpected character '.'", 1, id="attribute"),
        pytest.param("[1]", "unexpected character '['", 0, id="list"),
        pytest.param('"s"', "unexpected character '\"'", 0, id="string"),
        pytest.param("x[0]", "unexpected character '['", 1, id="subscript"),
        pytest.param("sin.__globals__", "unexpected character '.'", 3, id="function-attribute"),
        pytest.param(
            "x if y else 1",
            "expected an operator or the end of the text after 'x', found 'if'",
            2,
            id="conditional",
        ),
        pytest.param("Symbol('x')", "unknown name 'Symbol'", 0, id="sympy-name"),
        pytest.param("x; import os", "unexpected character ';'", 1, id="statement"),
        pytest.param("x @ y", "unexpected character '@'", 2, id="matmul"),
    ],
)
def test_code_is_refused(text: str, message: str, offset: int, monkeypatch: pytest.MonkeyPatch) -> None:
    def forbidden(*args: object, **kwargs: object) -> None:
        raise AssertionError("code evaluation was attempted")

    with monkeypatch.context() as patch:
        for name in ("eval", "exec", "compile"):
            patch.setattr(builtins, name, forbidden)
        patch.setattr(sp, "sympify", forbidden)
        patch.setattr(sp, "parse_expr", forbidden, raising=False)
        try:
            parse(text)
        except ExprError as caught:
            err: ExprError | None = caught
        else:
            err = None
    assert err is not None
    assert (err.message, err.offset) == (message, offset)


def test_payload_has_no_side_effect(tmp_path: Path) -> None:
    marker = tmp_path / "pwned"
    with pytest.raises(ExprError):
        parse(f"__import__('os').system('touch {marker}')")
    assert not marker.exists()


@pytest.mark.parametrize("module", ["tutgen.spec.expr", "tutgen.spec.units"])
def test_source_calls_nothing_that_evaluates_text(module: str) -> None:
    banned = {
        "eval",
        "exec",
        "compile",
        "__import__",
        "sympify",
        "S",
        "parse_expr",
        "lambdify",
        "import_module",
    }
    path = Path(pytest.importorskip(module).__file__ or "")
    called = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Call):
            func = node.func
            if isinstance(func, ast.Attribute):
                if not (isinstance(func.value, ast.Name) and func.value.id == "re"):  # re.compile is fine
                    called.add(func.attr)
            elif isinstance(func, ast.Name):
                called.add(func.id)
    assert not called & banned


# ---------------------------------------------------------------------------------------------
# Limits: refused quickly, never a RecursionError
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "message", "offset"),
    [
        pytest.param("2**2**2**2**2**2", "the exponent 65536 is too large (the limit is ±64)", 6, id="tower"),
        pytest.param("9**9**9**9", "the exponent 387420489 is too large (the limit is ±64)", 6, id="tower-9"),
        pytest.param(
            "((2**64)**64)**64",
            "a number in the expression is too large (more than about 420 digits)",
            8,
            id="nested-powers",
        ),
        pytest.param(
            "(" * 10_000 + "x",
            "the expression is too long (10001 characters; the limit is 2000)",
            MAX_LENGTH,
            id="parens-10000",
        ),
        pytest.param(
            "-" * 10_000 + "x",
            "the expression is too long (10001 characters; the limit is 2000)",
            MAX_LENGTH,
            id="signs-10000",
        ),
        pytest.param(
            "x" * (MAX_LENGTH + 1),
            "the expression is too long (2001 characters; the limit is 2000)",
            MAX_LENGTH,
            id="long-name",
        ),
        pytest.param(
            "(" * 1999 + "x",
            "the expression is nested too deeply (more than 50 levels of parentheses, function calls, signs or powers)",
            MAX_DEPTH,
            id="parens-1999",
        ),
        pytest.param(
            "-" * 1999 + "x",
            "the expression is nested too deeply (more than 50 levels of parentheses, function calls, signs or powers)",
            MAX_DEPTH,
            id="signs-1999",
        ),
        pytest.param(
            "sin(" * 400 + "x",
            "the expression is nested too deeply (more than 50 levels of parentheses, function calls, signs or powers)",
            4 * MAX_DEPTH + 3,
            id="calls-400",
        ),
        pytest.param(
            "x" + "**x" * 600,
            "the expression is nested too deeply (more than 50 levels of parentheses, function calls, signs or powers)",
            3 * MAX_DEPTH + 1,
            id="power-chain",
        ),
        pytest.param(
            "sqrt(" + "*".join(["1e300"] * 300) + "+1)",
            "a number in the expression is too large (more than about 420 digits)",
            10,
            id="huge-root",
        ),
    ],
)
def test_limits(text: str, message: str, offset: int) -> None:
    start = time.perf_counter()
    err = error_of(text)
    assert time.perf_counter() - start < 1.0
    assert (err.message, err.offset) == (message, offset)


def test_nesting_up_to_the_limit_is_fine() -> None:
    assert parse("(" * MAX_DEPTH + "x" + ")" * MAX_DEPTH) == x
    assert parse("-" * MAX_DEPTH + "x") == x
    assert error_of("(" * (MAX_DEPTH + 1) + "x" + ")" * (MAX_DEPTH + 1)).offset == MAX_DEPTH


def test_exponent_at_the_limit_is_fine() -> None:
    assert parse(f"x**{MAX_EXPONENT}") == x**MAX_EXPONENT
    assert parse(f"2**-{MAX_EXPONENT}") == sp.Rational(1, 2**MAX_EXPONENT)


def test_long_flat_expression_is_fast() -> None:
    text = "+".join(["m1*x**2"] * 250)
    assert len(text) <= MAX_LENGTH
    start = time.perf_counter()
    assert parse(text) == 250 * m1 * x**2
    assert time.perf_counter() - start < 1.0


# ---------------------------------------------------------------------------------------------
# did_you_mean and robustness
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("word", "candidates", "expected"),
    [
        pytest.param("cms", ["ms", "cm", "m"], "cm", id="tie-alphabetical"),
        pytest.param("Theta", ["theta", "beta"], "theta", id="case-insensitive"),
        pytest.param("zzz", ["theta"], None, id="nothing-close"),
        pytest.param("x", ["x"], None, id="same-word-is-no-suggestion"),
    ],
)
def test_did_you_mean(word: str, candidates: list[str], expected: str | None) -> None:
    assert did_you_mean(word, candidates) == expected


@given(st.text(alphabet="xy12.e+-*/^()," + " sincoatqrpl_$", max_size=40))
def test_fuzz_only_expr_errors(text: str) -> None:
    try:
        result = parse(text)
    except ExprError as err:
        assert 0 <= err.offset <= len(text)
    else:
        assert isinstance(result, sp.Expr)
        assert not result.has(sp.zoo, sp.nan, sp.oo, -sp.oo, sp.Float)
