"""The Christoffel tables of a large serial arm, converted on first read (engine/serial.py LazyTable):
the same symbols as converting every one up front, known sizes without converting, a plain dict
when pickled."""

from __future__ import annotations

import pickle

import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.engine.lazytable import LazyTable
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
    table = LazyTable(len(system.coordinates), lambda: dyn.christoffel, lambda: dyn.christoffel_polys)
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
