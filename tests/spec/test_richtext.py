"""Maths in texts (tutgen.spec.richtext): ``$…$`` spans read by the whitelist parser, located errors."""

from __future__ import annotations

import pickle

import pytest
import sympy as sp

from tutgen.errors import SpecErrors
from tutgen.model.text import MathSpan, RichText
from tutgen.spec.richtext import MAX_MATHS, MAX_SPANS, RichTextError, parse_rich_text
from tutgen.spec.validate import load_system_text

theta1, theta2 = sp.symbols("theta1 theta2", real=True)
dot1, dot2 = sp.symbols("theta1_dot theta2_dot", real=True)
m = sp.Symbol("m", positive=True)
NAMES = {"theta1": theta1, "theta2": theta2, "theta1_dot": dot1, "theta2_dot": dot2, "m": m}


def spans(text: RichText) -> list[MathSpan]:
    return [part for part in text.parts if isinstance(part, MathSpan)]


def test_plain_text_is_one_part_and_equal_to_itself() -> None:
    text = parse_rich_text("a cart on a rail", NAMES)
    assert text == "a cart on a rail" and text.parts == ("a cart on a rail",) and not text.has_math


def test_a_span_uses_the_declared_symbols_themselves() -> None:
    text = parse_rich_text("$T = (3/2 + cos(theta2)) theta1_dot^2 + theta2_dot^2/2$, exactly", NAMES)
    (span,) = spans(text)
    assert str(text) == "$T = (3/2 + cos(theta2)) theta1_dot^2 + theta2_dot^2/2$, exactly"
    assert span.relations == ("=",)
    lhs, rhs = span.terms
    assert lhs == sp.Symbol("T")
    assert sp.simplify(rhs - ((sp.Rational(3, 2) + sp.cos(theta2)) * dot1**2 + dot2**2 / 2)) == 0
    assert rhs.free_symbols == {theta2, dot1, dot2}  # the very symbols of the results (same assumptions)
    assert text.parts[-1] == ", exactly"


@pytest.mark.parametrize(
    ("source", "expected"),
    [
        pytest.param("2 m theta1", 2 * m * theta1, id="spaces"),
        pytest.param("2m", 2 * m, id="number-name"),
        pytest.param("sin(theta1) cos(theta2)", sp.sin(theta1) * sp.cos(theta2), id="calls"),
        pytest.param("m (1 + theta1)", m * (1 + theta1), id="name-paren"),
        pytest.param("m(1 + theta1)", m * (1 + theta1), id="declared-name-paren-no-space"),
        pytest.param("1/2 m theta1_dot^2", m * dot1**2 / 2, id="half-first"),
        pytest.param("1/(2 m)", 1 / (2 * m), id="parenthesised-denominator"),
        pytest.param("m*theta1/theta2", m * theta1 / theta2, id="explicit"),
        pytest.param("2 pi m", 2 * sp.pi * m, id="pi"),
    ],
)
def test_products_may_be_written_without_a_star(source: str, expected: sp.Expr) -> None:
    (span,) = spans(parse_rich_text(f"${source}$", NAMES))
    assert sp.simplify(span.terms[0] - expected) == 0


def test_undeclared_names_are_free_symbols_and_functions() -> None:
    text = parse_rich_text("$H(q) q_ddot + C(q, q_dot) + G(q) = tau$ and $L = T - U$", NAMES)
    first, second = spans(text)
    q, qd, qdd = sp.symbols("q q_dot q_ddot")
    H, C, G = sp.Function("H"), sp.Function("C"), sp.Function("G")
    assert first.terms == (H(q) * qdd + C(q, qd) + G(q), sp.Symbol("tau"))
    assert second.terms == (sp.Symbol("L"), sp.Symbol("T") - sp.Symbol("U"))
    assert first.source == "H(q) q_ddot + C(q, q_dot) + G(q) = tau"


def test_relations_chain() -> None:
    (span,) = spans(parse_rich_text("$0 <= theta1 < pi/2 != m >= 1 > 0 = 0$", NAMES))
    assert span.relations == ("<=", "<", "!=", ">=", ">", "=")
    assert span.terms == (0, theta1, sp.pi / 2, m, 1, 0, 0)


def test_escaped_dollars_are_text() -> None:
    text = parse_rich_text("costs \\$5 per $m$\\$ and \\$", NAMES)
    assert text.parts == ("costs $5 per ", MathSpan("m", (m,), ()), "$ and $")
    assert str(text) == "costs \\$5 per $m$\\$ and \\$"  # the text as written


def test_rich_text_pickles_with_its_parts() -> None:
    text = parse_rich_text("the mass $m$ in $H(q) q_ddot = tau$", NAMES)  # sheet workers pickle systems
    again = pickle.loads(pickle.dumps(text))
    assert again == text and again.parts == text.parts


@pytest.mark.parametrize(
    ("text", "offset", "message"),
    [
        pytest.param("a $m + 1", 2, "unclosed '$'", id="unclosed"),
        pytest.param("a $$ b", 2, "empty maths '$$'", id="empty"),
        pytest.param("a $  $ b", 2, "empty maths", id="blank"),
        pytest.param("$m +$", 4, "in the maths '$m +$': expected an expression after '+'", id="syntax"),
        pytest.param("is $cos theta1$", 8, "expected '(' after the function 'cos'", id="function-needs-parens"),
        pytest.param("$m 2$", 3, "expected an operator", id="number-after-operand"),
        pytest.param("$x = = y$", 5, "expected an expression between '=' and '='", id="double-relation"),
        pytest.param("$== y$", 1, "expected an expression before '='", id="relation-first"),
        pytest.param("$y <$", 4, "expected an expression after '<'", id="relation-last"),
        pytest.param("$theta1^m$", 8, "the exponent must be a number", id="symbolic-exponent"),
        pytest.param("$m/0$", 2, "division by zero", id="division-by-zero"),
        pytest.param("$__import__('os')$", 1, "unknown name '__import__'", id="dunder"),
        pytest.param("$m; import os$", 2, "unexpected character ';'", id="statement"),
        pytest.param("$m**99$", 4, "too large", id="exponent-limit"),
        pytest.param("$H()$", 2, "the function 'H' needs an argument", id="empty-call"),
        pytest.param("$m \\$ 2$", 3, "unexpected character '\\\\'", id="escaped-dollar-in-maths"),
    ],
)
def test_maths_that_does_not_parse_is_refused_at_the_character(text: str, offset: int, message: str) -> None:
    with pytest.raises(RichTextError) as info:
        parse_rich_text(text, NAMES)
    assert message in info.value.message
    assert info.value.offset == offset


def test_the_number_of_spans_is_limited() -> None:
    parse_rich_text("$m$ " * MAX_SPANS, NAMES)
    with pytest.raises(RichTextError, match="more than"):
        parse_rich_text("$m$ " * (MAX_SPANS + 1), NAMES)


def test_the_maths_of_all_texts_of_a_spec_is_limited() -> None:
    long = "$" + "+".join(["m"] * 999) + "$"  # 1997 characters of maths
    count = MAX_MATHS // (len(long) - 2) + 1
    descriptions = "".join(f"  p{i}: {{description: '{long}'}}\n" for i in range(count))
    with pytest.raises(SpecErrors) as info:
        load_system_text(f"title: t\nparameters:\n{descriptions}", "long.yaml")
    (error,) = info.value.errors
    assert error.message == f"the texts hold more than {MAX_MATHS} characters of maths"
    # at the opening dollar of the span that crosses the limit, in the last description
    assert (error.location.line, error.location.col) == (count + 2, len(f"  p{count - 1}: {{description: '") + 1)


SPEC = """\
tutgen: 1
title: Energy of $m$ on a rod
statement: |
  A rod of mass $m$ turns by $theta$; its kinetic energy
  is $T = 1/2 m l^2 theta_dot^2$ and \\$5 buys it.
parameters:
  m: {description: 'the mass, $m > 0$'}
  l: {description: length}
coordinates:
  theta: {description: 'the angle, $0 <= theta < 2 pi$'}
energy: {kinetic: m*l**2*theta_dot**2/2}
"""


def test_every_text_of_a_spec_is_rich_text_in_the_model() -> None:
    system = load_system_text(SPEC, "rich.yaml")
    assert isinstance(system.title, RichText) and system.title == "Energy of $m$ on a rod"
    assert isinstance(system.statement, RichText) and system.statement.endswith("buys it.")
    assert system.statement.parts[-1].endswith("and $5 buys it.")
    (m_, l_), (th,) = system.parameters, system.coordinates
    assert isinstance(m_.description, RichText) and spans(m_.description)[0].terms == (m_.symbol, 0)
    assert isinstance(l_.description, RichText) and not l_.description.has_math
    assert spans(th.description)[0].terms == (0, th.q, 2 * sp.pi)
    t_span = spans(system.statement)[2]
    assert sp.simplify(t_span.terms[1] - m_.symbol * l_.symbol**2 * th.qd**2 / 2) == 0


@pytest.mark.parametrize(
    ("old", "new", "where", "message"),
    [
        pytest.param("is $T = 1/2 m", "is $T = 1/2 m */", (5, 18), "expected an expression after '*'", id="block"),
        # a dollar left open pairs with the next one, on the next line: the span does not parse
        pytest.param("by $theta$", "by $theta", (4, 36), "unexpected character ';'", id="open-in-block"),
        pytest.param("$m > 0$", "$m > $", (7, 35), "expected an expression after '>'", id="description"),
        pytest.param("of $m$ on", "of $m$$ on", (2, 21), "unclosed '$'", id="title"),
        pytest.param("length}", "length $x}", (8, 27), "unclosed '$'", id="unclosed-description"),
    ],
)
def test_a_bad_span_is_a_spec_error_pointing_into_it(old: str, new: str, where: tuple[int, int], message: str) -> None:
    assert old in SPEC
    with pytest.raises(SpecErrors) as info:
        load_system_text(SPEC.replace(old, new), "rich.yaml")
    (error,) = info.value.errors
    assert (error.location.line, error.location.col) == where
    assert message in error.message
