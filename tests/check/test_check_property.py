"""The marking property: every equivalent form of a correct answer is correct, every small perturbation wrong.

Correct answers are result entries of three tutorial specs (each derived once, through the session
cache): mass-matrix, Coriolis and gravity entries, energies. Each is rewritten in an equivalent form
(expanded, factored, angle sums expanded, products of trigonometric functions turned into sums,
multiplied by sin² + cos², with tan written as sin/cos, or as written), or perturbed in one term of
its expansion (a coefficient changed by 1 %, a sign flipped, a factor 2) and then possibly rewritten,
and marked through the real path: the expression printed in the spec grammar, written to an
answers file, read back and marked. Zero false verdicts are allowed: an equivalent form must be
"correct", a perturbation "wrong" (not "cannot be evaluated"). 200 cases in the default run, 2 000
with ``-m slow``.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cache

import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from sympy.simplify.fu import TR8

from tests.check.helpers import mark_text, tutorial
from tutgen.check.compare import Reference, Status, expr_text

PROBLEMS = (4, 5, 7)
#: result entries used as correct answers: (result key, path into the results, as an answers key)
ENTRIES = (
    ("kinetic_energy", ()),
    ("potential_energy", ()),
    ("mass_matrix", (0, 0)),
    ("mass_matrix", (0, 1)),
    ("mass_matrix", (1, 1)),
    ("coriolis_vector", (0,)),
    ("coriolis_vector", (1,)),
    ("gravity_vector", (0,)),
    ("gravity_vector", (1,)),
)


def _key(name: str, index: tuple[int, ...]) -> str:
    return name + ("[" + ",".join(str(i + 1) for i in index) + "]" if index else "")


@cache
def cases() -> list[tuple[int, str, sp.Expr]]:
    """(problem, answers key, correct expression) for every non-constant entry of the problems."""
    out = []
    for pid in PROBLEMS:
        ref = tutorial(pid)
        for name, index in ENTRIES:
            node = ref.results.get(name)
            for i in index:
                node = node[i] if isinstance(node, list) and i < len(node) else None
            if not isinstance(node, str):
                continue
            expr = sp.sympify(0) if node == "0" else _parse(ref, node)
            if expr.free_symbols:
                out.append((pid, _key(name, index), expr))
    return out


def _parse(ref: Reference, text: str) -> sp.Expr:
    from tutgen.spec.expr import parse_expression

    return parse_expression(text, ref.symbols)


def _angle(expr: sp.Expr) -> sp.Symbol:
    """A coordinate the expression uses (for inserting sin² + cos²), else any of its symbols."""
    trig = sorted((a for f in expr.atoms(sp.sin, sp.cos) for a in f.args[0].free_symbols), key=str)
    return trig[0] if trig else sorted(expr.free_symbols, key=str)[0]


REWRITES: dict[str, Callable[[sp.Expr], sp.Expr]] = {
    "as-written": lambda e: e,
    "expanded": sp.expand,
    "factored": sp.factor,
    "angle-sums": lambda e: sp.expand_trig(e),
    "products-to-sums": lambda e: TR8(sp.expand(e)),
    "times-pythagoras": lambda e: e * (sp.sin(_angle(e)) ** 2 + sp.cos(_angle(e)) ** 2),
    "plus-tan-identity": lambda e: e + sp.tan(_angle(e)) - sp.sin(_angle(e)) / sp.cos(_angle(e)),
}
PERTURBATIONS: dict[str, sp.Expr] = {
    "coefficient-1%": sp.Rational(101, 100),
    "sign": sp.Integer(-1),
    "factor-2": sp.Integer(2),
}


def perturb(expr: sp.Expr, term: int, factor: sp.Expr) -> sp.Expr:
    """``expr`` with one term of its expansion multiplied by ``factor`` (so wrong by a non-zero term)."""
    terms = list(sp.Add.make_args(sp.expand(expr)))
    i = term % len(terms)
    terms[i] = factor * terms[i]
    return sp.Add(*terms)


def _check(pid: int, key: str, correct: sp.Expr, rewrite: str, perturbation: str | None, term: int) -> None:
    answer = correct if perturbation is None else perturb(correct, term, PERTURBATIONS[perturbation])
    answer = REWRITES[rewrite](answer)
    result = mark_text(tutorial(pid), f'"{key}": "{expr_text(answer)}"\n')
    assert not result.errors, result.errors
    (item,) = result.items
    (entry,) = item.entries
    expected = Status.CORRECT if perturbation is None else Status.WRONG
    assert entry.status is expected, (pid, key, rewrite, perturbation, expr_text(answer), entry.feedback)


_CASE = st.tuples(
    st.integers(0, 10_000),  # which correct answer
    st.sampled_from(sorted(REWRITES)),
    st.one_of(st.none(), st.sampled_from(sorted(PERTURBATIONS))),
    st.integers(0, 50),  # which term is perturbed
)


def _run(case: tuple[int, str, str | None, int]) -> None:
    index, rewrite, perturbation, term = case
    all_cases = cases()
    pid, key, correct = all_cases[index % len(all_cases)]
    _check(pid, key, correct, rewrite, perturbation, term)


_SETTINGS = {"deadline": None, "database": None, "suppress_health_check": [HealthCheck.too_slow]}


@settings(max_examples=200, derandomize=True, **_SETTINGS)
@given(_CASE)
def test_check_property_equivalent_forms_right_perturbations_wrong(case: tuple[int, str, str | None, int]) -> None:
    _run(case)


@pytest.mark.slow
@settings(max_examples=2000, **_SETTINGS)
@given(_CASE)
def test_check_property_many_cases(case: tuple[int, str, str | None, int]) -> None:
    _run(case)


def test_check_property_cases_cover_every_problem() -> None:
    """The pool of correct answers is not empty and draws on each problem."""
    assert {pid for pid, _, _ in cases()} == set(PROBLEMS)
    assert len(cases()) >= 15
