"""The Christoffel tables of a large serial arm, converted on first read (engine/serial.py LazyTable):
the same symbols as converting every one up front, known sizes without converting, a plain dict
when pickled."""

from __future__ import annotations

import pickle

import pytest
import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.engine.lazytable import LazyMatrix, LazyTable
from tutgen.engine.serial import serial_dynamics
from tutgen.render.size import count_ops_upto, nonzero_count


def test_lazy_table_equals_the_table_of_every_symbol():
    system, d, _ = solved(str(SPECS / "arms" / "scara.yaml"))
    dyn = serial_dynamics(system)  # a fresh, independent derivation
    n = len(system.coordinates)
    for table, eager in ((d.christoffel, dyn.christoffel), (d.christoffel_first_kind, dyn.christoffel_first_kind)):
        assert isinstance(table, LazyTable)
        assert len(table) == n**3 and list(table) == sorted(table)
        for key in table:
            assert sp.expand(table[key] - eager.get(key, 0)) == 0, key


def test_lazy_table_is_sized_without_converting():
    system, _, _ = solved(str(SPECS / "arms" / "scara.yaml"))
    dyn = serial_dynamics(system)
    n = len(system.coordinates)
    table = LazyTable(n, lambda: dyn.christoffel, lambda: dyn.christoffel_keys, dyn.christoffel_min_ops)
    bound, count = table.min_ops(), nonzero_count(table)
    assert not table.is_converted
    ops = int(sum(sp.count_ops(v) for v in dyn.christoffel.values()))
    assert 0 < bound <= ops and count == len(dyn.christoffel)
    assert count_ops_upto([table], bound - 1) == bound  # over the limit, decided by the bound alone
    assert not table.is_converted
    assert count_ops_upto([table], ops) == ops  # within it: the exact count of the converted symbols


def test_lazy_table_pickles_as_a_plain_dict():
    _, d, _ = solved(str(SPECS / "arms" / "scara.yaml"))
    back = pickle.loads(pickle.dumps(d.christoffel))
    assert type(back) is dict and back == dict(d.christoffel)


# ---------------------------------------------------------------------------------------------
# C q_dot, C and the equations of motion of a large arm (LazyMatrix)
# ---------------------------------------------------------------------------------------------


def test_lazy_matrix_reads_as_the_plain_matrix():
    x, y = sp.symbols("x y")
    calls: list[int] = []

    def entries() -> list[sp.Expr]:
        calls.append(1)
        return [x + y, x * y, sp.sin(x), sp.Integer(0)]

    m = LazyMatrix(2, 2, entries, lambda: 1)
    assert m.shape == (2, 2) and not m.is_converted and m.min_ops() == 1 and not calls
    plain = sp.ImmutableMatrix([[x + y, x * y], [sp.sin(x), 0]])
    assert m == plain and plain == m and hash(m) == hash(plain) and m.is_converted
    assert type(m.T) is sp.ImmutableMatrix and m.T == plain.T
    assert m.subs(x, 1) == plain.subs(x, 1) and type(m.subs(x, 1)) is sp.ImmutableMatrix
    assert m.applyfunc(lambda e: 2 * e) == 2 * plain and m * m == plain * plain and list(m) == list(plain)
    assert m.free_symbols == {x, y} and sp.ImmutableMatrix(m) == plain
    mixed = m * sp.Matrix([1, 2])  # sympy builds a mixed product with its operand's class
    assert type(mixed) is sp.ImmutableMatrix and mixed == plain * sp.Matrix([1, 2])
    back = pickle.loads(pickle.dumps(m))
    assert type(back) is sp.ImmutableMatrix and back == plain
    assert len(calls) == 1  # converted once


def test_large_arm_matrices_equal_the_eager_ones_and_bound_their_size():
    """The derivation's C q_dot, C and equations of motion (converted when first read) equal a fresh
    serial_dynamics' symbols contracted by hand, and their lower bounds (read before converting) are at
    most sympy's count_ops of the converted entries."""
    for spec in ("scara.yaml", "planar-4r.yaml"):
        system, _, _ = solved(str(SPECS / "arms" / spec))
        from tutgen.engine.pipeline import derive

        d = derive(system)  # a fresh derivation: nothing converted yet
        mats = (d.coriolis_vector, d.coriolis_matrix, d.equations_of_motion)
        assert all(isinstance(m, LazyMatrix) and not m.is_converted for m in mats)
        bounds = [m.min_ops() for m in mats]
        assert not any(m.is_converted for m in mats)
        dyn = serial_dynamics(system)
        n = len(system.coordinates)
        qd = [c.qd for c in system.coordinates]
        qdd = [c.qdd for c in system.coordinates]
        first = dyn.christoffel_first_kind
        c_hand = [sum(first.get((i, j, k), 0) * qd[j] * qd[k] for j in range(n) for k in range(n)) for i in range(n)]
        for i in range(n):
            assert sp.expand(d.coriolis_vector[i] - c_hand[i]) == 0, (spec, i)
            row = sum(d.mass_matrix[i, j] * qdd[j] for j in range(n)) + c_hand[i] + d.gravity_vector[i]
            assert sp.expand(d.equations_of_motion[i] - row + d.generalized_forces[i]) == 0, (spec, i)
        assert sp.expand(d.coriolis_matrix * sp.Matrix(qd) - d.coriolis_vector) == sp.zeros(n, 1)
        for bound, m in zip(bounds, mats, strict=True):
            assert 0 < bound <= sum(sp.count_ops(e) for e in m), spec


def test_trig_poly_bound_is_below_count_ops():
    system, _, _ = solved(str(SPECS / "arms" / "planar-4r.yaml"))
    dyn = serial_dynamics(system)
    polys = [*dyn.exact.gammas.values(), *dyn.christoffel_polys.values(), *dyn.exact.g]
    polys += [p for row in dyn.exact.h for p in row]
    assert polys
    for p in polys:
        assert p.min_ops() <= sp.count_ops(p.to_expr())


def test_lazy_matrix_is_sized_without_converting():
    from tutgen.engine.pipeline import derive

    system, _, _ = solved(str(SPECS / "arms" / "scara.yaml"))
    c = derive(system).coriolis_vector
    bound = c.min_ops()
    assert count_ops_upto([c], bound - 1) == bound  # over the limit, decided by the bound alone
    assert not c.is_converted
    exact = int(sum(sp.count_ops(e) for e in c))
    assert count_ops_upto([c], exact) == exact  # within it: the exact count of the converted entries


# ---------------------------------------------------------------------------------------------
# Sizing a large arm's table for a worked solution: only as many symbols as the budget needs (issue 17)
# ---------------------------------------------------------------------------------------------


def test_christoffel_keys_are_the_nonzero_symbols():
    """The nonzero h_ijk, found by comparing dH_ij/dq_k with dH_jk/dq_i / 2 without subtracting, are
    those of the subtraction, and each symbol equals it."""
    for spec in ("scara.yaml", "planar-4r.yaml", "stanford.yaml"):
        system, _, _ = solved(str(SPECS / "arms" / spec))
        dyn = serial_dynamics(system)
        dh = dyn.exact.dh
        half = dyn.exact.algebra.ring.ground_new(dyn.exact.algebra.ring.domain(1, 2))
        n = len(system.coordinates)
        expected = {}
        for i in range(n):
            for j in range(n):
                for k in range(n):
                    h = dh[i][j][k] - dh[j][k][i].scale(half)
                    if h:
                        expected[(i, j, k)] = h
        assert list(dyn.christoffel_keys) == list(expected), spec
        assert all(dyn.christoffel_poly(key) == p for key, p in expected.items()), spec


def test_christoffel_bound_is_below_the_symbols_own():
    """h_ijk's bound from the terms that cannot cancel is at most its own (TrigPoly.min_ops), which is at
    most sympy's count_ops of it."""
    for spec in ("scara.yaml", "planar-4r.yaml", "stanford.yaml"):
        system, _, _ = solved(str(SPECS / "arms" / spec))
        dyn = serial_dynamics(system)
        for key in dyn.christoffel_keys:
            assert 0 <= dyn.christoffel_min_ops(key) <= dyn.christoffel_poly(key).min_ops(), (spec, key)
        assert sum(dyn.christoffel_min_ops(key) for key in dyn.christoffel_keys) > 0, spec


def test_lazy_table_bound_stops_at_the_limit():
    system, _, _ = solved(str(SPECS / "arms" / "stanford.yaml"))
    dyn = serial_dynamics(system)
    asked: list[tuple[int, int, int]] = []

    def bound(key: tuple[int, int, int]) -> int:
        asked.append(key)
        return dyn.christoffel_poly(key).min_ops()

    table = LazyTable(len(system.coordinates), lambda: dyn.christoffel, lambda: dyn.christoffel_keys, bound)
    full = table.min_ops()
    assert len(asked) == len(dyn.christoffel_keys)
    asked.clear()
    first = dyn.christoffel_poly(dyn.christoffel_keys[0]).min_ops()
    assert table.min_ops(first - 1) == first and len(asked) == 1  # past the limit after one symbol
    asked.clear()
    assert count_ops_upto([table], first - 1) == first and len(asked) == 1 and not table.is_converted
    assert table.min_ops(full) == full


def test_worked_solution_of_a_large_arm_sizes_few_christoffel_symbols(monkeypatch: pytest.MonkeyPatch):
    """The Markdown of the symbolic PUMA 560 says its h_ijk are too long to print, and how many are nonzero,
    from the bounds of a few of them: no symbol is computed, and the table is not converted (the whole
    table was computed, only to be counted)."""
    from tutgen.api import render
    from tutgen.engine import serial
    from tutgen.engine.pipeline import derive
    from tutgen.spec.validate import load_system

    computed: list[tuple[int, int, int]] = []
    bounded: list[tuple[int, int, int]] = []
    poly, bound = serial.SerialDynamics.christoffel_poly, serial.SerialDynamics.christoffel_min_ops

    def counting_poly(self: serial.SerialDynamics, key: tuple[int, int, int]) -> object:
        computed.append(key)
        return poly(self, key)

    def counting_bound(self: serial.SerialDynamics, key: tuple[int, int, int]) -> int:
        bounded.append(key)
        return bound(self, key)

    monkeypatch.setattr(serial.SerialDynamics, "christoffel_poly", counting_poly)
    monkeypatch.setattr(serial.SerialDynamics, "christoffel_min_ops", counting_bound)
    d = derive(load_system(SPECS / "arms" / "puma560.yaml"))
    text = render(d, "md")
    assert "195 of the 216 symbols $h_{ijk}$ are nonzero" in text
    assert not computed and 0 < len(set(bounded)) < 195 // 3
    assert not d.christoffel.is_converted and not d.christoffel_first_kind.is_converted
