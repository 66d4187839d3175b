"""The JSON printer (tutgen.render.grammar): its text reads back to the same value through the
whitelist parser, the values equal those printed by sympy's lex-ordered printer of earlier versions
for every spec, and the text is the same under any PYTHONHASHSEED."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest
import sympy as sp
from sympy.printing.str import StrPrinter

from tests.conftest import ROOT, SPECS, solved
from tutgen.render.grammar import LEX_BUDGET, fast_text, grammar_text
from tutgen.spec.expr import ExpressionParser

x, y, z = sp.symbols("x y z")

SHAPES = [
    pytest.param(x - y, id="difference"),
    pytest.param(-x - 2 * y, id="negative-lead"),
    pytest.param(-sp.Rational(3, 2) * x / y, id="negative-fraction"),
    pytest.param(1 / (x * y) + 1 / (2 * z), id="reciprocals"),
    pytest.param(x**-2 * (y + z) ** -1, id="quotient-of-powers"),
    pytest.param((x + y) ** 2 * (x - z) ** 3, id="powers-of-sums"),
    pytest.param(sp.sqrt(x + y) + 1 / sp.sqrt(z), id="roots"),
    pytest.param(x ** sp.Rational(2, 3) + (-x) ** 3 + (2 * x) ** 5 + x**-3, id="exponents"),
    pytest.param(sp.Rational(-1, 3) + sp.Rational(5, 7) * x, id="rational-terms"),
    pytest.param(sp.exp(-x) + sp.E + sp.log(y) * sp.pi, id="e-and-pi"),
    pytest.param(sp.sin(x + y) ** 2 * sp.cos(x - y) - sp.atan2(y, x), id="trigonometry"),
    pytest.param(sp.Abs(x - y) / (x * sp.tanh(z)), id="abs-and-hyperbolic"),
    pytest.param(-(x * (y + z)), id="minus-product-with-sum"),
    pytest.param(sp.Mul(-1, sp.Pow(x + y, -1), evaluate=False) + z, id="minus-reciprocal-of-sum"),
]


class _LexPrinter(StrPrinter):
    """The printer of earlier versions: sympy's, lex-ordered, with e written exp(1)."""

    def _print_Exp1(self, expr):
        return "exp(1)"


def _read(text: str, expr: sp.Expr) -> sp.Expr:
    return ExpressionParser(text, {str(s): s for s in expr.free_symbols}).parse()


@pytest.mark.parametrize("printer", [grammar_text, fast_text], ids=["short-lex", "fast"])
@pytest.mark.parametrize("expr", SHAPES)
def test_grammar_text_reads_back_to_the_same_expression(expr, printer):
    text = printer(expr)
    assert sp.simplify(_read(text, expr) - expr) == 0, text


def test_grammar_text_prints_long_expressions_in_one_walk():
    """Past LEX_BUDGET the fast printer is used (argument order), and reads back all the same."""
    long = sp.Add(*(sp.Symbol(f"m{i}") * sp.cos(x) ** (i % 4) * (y - z) ** (i % 3) for i in range(3 * LEX_BUDGET)))
    text = grammar_text(long)
    assert text == fast_text(long)
    assert sp.expand(_read(text, long) - long) == 0


# every spec but the sheet file and the fully symbolic PUMA (minutes of lex printing)
SPEC_FILES = sorted(p for p in SPECS.rglob("*.yaml") if p.name not in ("sheet.yaml", "puma560.yaml"))


def _strings(node, path=""):
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _strings(v, f"{path}.{k}")
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _strings(v, f"{path}[{i}]")
    elif isinstance(node, str):
        yield path, node


@pytest.mark.slow
@pytest.mark.parametrize("spec", SPEC_FILES, ids=lambda p: p.stem)
def test_grammar_json_values_equal_the_lex_printed_ones(spec):
    """Every expression of every spec's JSON: the new text and sympy's lex-ordered text of earlier
    versions read back to equal values (the printed order is all that changed)."""
    system, d, doc = solved(str(spec))
    old = _LexPrinter({"order": "lex"})
    values = dict(system.values)
    results = doc["results"]
    exprs = {
        "mass_matrix": d.mass_matrix,
        "coriolis_vector": d.coriolis_vector,
        "gravity_vector": d.gravity_vector,
        "equations_of_motion": d.equations_of_motion,
    }
    checked = 0
    for key, m in exprs.items():
        if key not in results or m is None:
            continue
        printed = [v for row in results[key] for v in (row if isinstance(row, list) else [row])]
        for text, e in zip(printed, m, strict=True):
            e = sp.sympify(e).subs(values) if values else e
            if not isinstance(text, str):
                continue
            new, was = _read(text, e), _read(old.doprint(e), e)
            assert sp.expand(new - was) == 0, (key, text)
            checked += 1
    assert checked or not any(k in results for k in exprs)


_HASHED = """
import sympy as sp
from tutgen.render.grammar import grammar_text
names = {f"m{i}" for i in range(40)} | {f"c{i}" for i in range(40)}  # a set: its order follows the hash
x, y = sp.symbols("x y")
terms = [sp.Symbol(n) * sp.cos(x) ** (len(n) % 3) * (x - y) ** (int(n[1:]) % 2 + 1) for n in names]
print(grammar_text(sp.Add(*terms) * sp.Add(*reversed(terms)) + sp.Mul(*[t for t in terms if "c1" in str(t)])))
"""


def test_grammar_text_is_the_same_under_any_hash_seed():
    """A long expression built in a hash-dependent order prints the same bytes in two processes with
    different PYTHONHASHSEED (the terms are sorted by sympy when built, not by hash)."""
    outs = []
    for seed in ("1", "4242"):
        env = {**os.environ, "PYTHONHASHSEED": seed, "PYTHONPATH": str(ROOT)}
        run = subprocess.run([sys.executable, "-c", _HASHED], capture_output=True, text=True, env=env, check=True)
        outs.append(run.stdout)
    assert outs[0] == outs[1] and len(outs[0]) > 1000


@pytest.mark.slow
def test_grammar_json_is_the_same_under_any_hash_seed():
    """Two fresh processes with different PYTHONHASHSEED print byte-identical JSON of a 4-DOF arm."""
    spec = str(SPECS / "arms" / "scara.yaml")
    outs = []
    for seed in ("1", "4242"):
        env = {**os.environ, "PYTHONHASHSEED": seed}
        run = subprocess.run(
            [sys.executable, "-m", "tutgen", "solve", spec, "-f", "json"],
            capture_output=True,
            text=True,
            cwd=ROOT,
            env=env,
            check=True,
        )
        outs.append(run.stdout)
    assert outs[0] == outs[1]
    assert json.loads(outs[0])["results"]["mass_matrix"]


def _sums(expr: sp.Basic):
    """Every sum in ``expr`` (a matrix's entries, an expression's subexpressions)."""
    for entry in expr if isinstance(expr, sp.MatrixBase) else [expr]:
        for node in sp.preorder_traversal(entry):
            if isinstance(node, sp.Add):
                yield node


_TUTORIAL = [pytest.param(p, id=p.stem) for p in sorted((SPECS / "tutorial-1").glob("p*.yaml"))]


@pytest.mark.parametrize("spec", _TUTORIAL)
def test_lex_terms_are_sympys_lex_order(spec):
    """``lex_terms`` (tutgen's fast term order for the short JSON values) gives sympy's own list, on every
    sum of a tutorial problem's results, symbolic and with a sheet's kind of numbers put in (floats,
    fractions, a square root and pi as factors); the printed texts are the same too."""
    from tutgen.render.grammar import _LEX, lex_terms

    system, d, _ = solved(str(spec))
    results = [d.mass_matrix, d.gravity_vector, d.coriolis_vector, d.kinetic_energy, d.potential_energy]
    symbols = sorted({p.symbol for p in system.parameters}, key=str)
    numbers = [sp.Float("2.5"), sp.Rational(3, 4), sp.Float("9.81"), sp.sqrt(2), sp.pi, sp.Float("0.125"), 7]
    valued = {s: numbers[i % len(numbers)] for i, s in enumerate(symbols)}
    old = _LexPrinter({"order": "lex"})
    checked = 0
    for result in results:
        if result is None:
            continue
        for expr in (result, result.xreplace(valued)):
            for total in _sums(expr):
                assert lex_terms(total) == total.as_ordered_terms(order="lex"), total
                checked += 1
            entries = list(expr) if isinstance(expr, sp.MatrixBase) else [expr]
            for entry in entries:
                assert _LEX.doprint(entry) == old.doprint(entry)
    if spec.stem.startswith(("p01", "p10")):
        return  # inertia alone, or a given energy: no matrices of sums
    assert checked > 0


@pytest.mark.parametrize("expr", SHAPES)
def test_lex_terms_on_the_grammar_shapes(expr):
    from tutgen.render.grammar import lex_terms

    for total in _sums(expr):
        assert lex_terms(total) == total.as_ordered_terms(order="lex")


def _random_expressions(count: int, seed: int) -> list[sp.Expr]:
    """Sums of products as results have them: numbers of every kind (negative, fractions, floats, roots,
    pi), powers with negative and fractional exponents, functions of sums, brackets."""
    import random

    rng = random.Random(seed)
    t1, t2 = sp.symbols("theta1 theta2")
    atoms = [x, y, z, t1, t2, sp.sin(t1), sp.cos(t2), sp.sin(t1 + t2), sp.cos(t1 - t2), x + y, y - 2 * z]
    numbers = [sp.Integer(-3), sp.Rational(-1, 2), sp.Rational(3, 4), sp.Float("2.5"), sp.Float("-0.125")]
    numbers += [sp.sqrt(2), sp.pi, sp.Integer(7), sp.Rational(-7, 3), sp.Float("9.81")]
    exprs = []
    for _ in range(count):
        terms = []
        for _ in range(rng.randint(1, 5)):
            factors = [rng.choice(numbers)]
            for _ in range(rng.randint(0, 3)):
                factors.append(
                    rng.choice(atoms) ** rng.choice([1, 1, 2, -1, -2, sp.Rational(1, 2), sp.Rational(-3, 2)])
                )
            terms.append(sp.Mul(*factors))
        exprs.append(sp.Add(*terms))
    return exprs


@pytest.mark.parametrize("seed", range(4))
def test_the_lex_printer_prints_what_sympys_prints(seed):
    """tutgen's lex printer (faster term order, precedence and factor order: issue 17) against sympy's own
    printer of earlier versions, text for text, on the grammar's shapes and on many generated sums."""
    from tutgen.render.grammar import _LEX

    old = _LexPrinter({"order": "lex"})
    exprs = [p.values[0] for p in SHAPES] + _random_expressions(150, seed)
    for expr in exprs:
        assert _LEX.doprint(expr) == old.doprint(expr), expr
        assert _LEX.doprint(-expr) == old.doprint(-expr), -expr
