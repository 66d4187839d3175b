"""results.program (a serial arm's straight-line program) and the nonzero-only Christoffel symbols of
large systems in the JSON output (docs/json-output.md), read back with the whitelist parser."""

from __future__ import annotations

import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.spec.expr import ExpressionParser


def _reader(doc):
    names = {p: sp.Symbol(p) for p, v in doc["parameters"].items() if v is None}
    for c in doc["coordinates"]:
        for suffix in ("", "_dot", "_ddot"):
            names[c + suffix] = sp.Symbol(c + suffix)

    def read(v, extra=None):
        if isinstance(v, str):
            return ExpressionParser(v, {**names, **(extra or {})}).parse()
        return sp.nsimplify(v) if isinstance(v, float) else sp.Integer(v)

    return read


def _is_zero(e: sp.Expr, coords: list[sp.Symbol]) -> bool:
    """Exactly zero as a polynomial in the parameters, rates and sin/cos of the coordinates (sin^2 = 1 -
    cos^2), without simplify."""
    e = sp.expand(sp.expand_trig(e))
    for q in coords:
        e = sp.expand(e.subs(sp.sin(q) ** 2, 1 - sp.cos(q) ** 2))
    return e == 0


def test_json_program_substitutes_back_to_the_matrix_form():
    """The definitions in order, substituted into H, C q_dot and G of the program, give the JSON's own
    mass_matrix, coriolis_vector and gravity_vector (a symbolic 4-DOF arm: exact comparison)."""
    _, _, doc = solved(str(SPECS / "arms" / "scara.yaml"))
    results = doc["results"]
    program = results["program"]
    read = _reader(doc)
    coords = [sp.Symbol(c) for c in doc["coordinates"]]
    xs: dict[str, sp.Symbol] = {}
    values: dict[sp.Symbol, sp.Expr] = {}
    for item in program["definitions"]:
        e = read(item["value"], xs).xreplace(values)  # only earlier names are known: use before definition fails
        xs[item["name"]] = sym = sp.Symbol(item["name"])
        values[sym] = e
    assert len(values) >= 10
    for key in ("mass_matrix", "coriolis_vector", "gravity_vector"):
        ours = results[key]
        theirs = program[key]
        flat = [v for row in ours for v in (row if isinstance(row, list) else [row])]
        prog = [v for row in theirs for v in (row if isinstance(row, list) else [row])]
        assert len(flat) == len(prog)
        for a, b in zip(flat, prog, strict=True):
            assert _is_zero(read(a) - read(b, xs).xreplace(values), coords), key


def test_json_christoffel_of_large_systems_lists_nonzero_symbols_only():
    """A 4-DOF arm: only the nonzero symbols are listed; every listed key is one of the derivation's,
    nonzero, and every symbol left out is zero."""
    _, d, doc = solved(str(SPECS / "arms" / "scara.yaml"))
    table = doc["results"]["christoffel"]
    n = len(doc["coordinates"])
    assert n >= 4
    for (i, j, k), e in d.christoffel.items():
        key = f"{i + 1},{j + 1},{k + 1}"
        assert (key in table) == (e != 0), key
    assert all(v != 0 for v in table.values())


def test_json_christoffel_of_small_systems_keeps_every_symbol():
    _, _, doc = solved(str(SPECS / "tutorial-1" / "p05-rr-arm.yaml"))
    table = doc["results"]["christoffel"]
    assert len(table) == 8 and "1,1,1" in table and "program" not in doc["results"]
