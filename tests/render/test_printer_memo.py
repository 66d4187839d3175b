"""What the printer remembers (issue 17): printers of the same settings share their texts, a printer given
new names never reuses a text printed under the old ones, and every table can be emptied."""

from __future__ import annotations

import dataclasses

import pytest
import sympy as sp

from tests.conftest import SPECS, solved
from tutgen.render import order
from tutgen.render import printer as printer_module
from tutgen.render.printer import TexPrinter, forget

P05 = SPECS / "tutorial-1" / "p05-rr-arm.yaml"


@pytest.fixture
def counted(monkeypatch: pytest.MonkeyPatch) -> list[sp.Basic]:
    """The expressions the printer really prints (not looked up), in order."""
    calls: list[sp.Basic] = []
    real = TexPrinter._print

    def counting(self: TexPrinter, expr: object) -> str:
        calls.append(expr)  # type: ignore[arg-type]
        return real(self, expr)

    monkeypatch.setattr(TexPrinter, "_print", counting)
    forget()
    return calls


def test_printer_prints_an_expression_once(counted: list[sp.Basic]) -> None:
    system, d, _ = solved(str(P05))
    tex = TexPrinter(system)
    h11 = d.mass_matrix[0, 0]
    first = tex(h11)
    assert counted == [h11]
    assert tex(h11) == first
    assert tex.ordered(d.equations_of_motion[0]) == tex.ordered(d.equations_of_motion[0])
    assert counted.count(h11) == 1


def test_printers_of_the_same_settings_share_their_texts(counted: list[sp.Basic]) -> None:
    """A sheet's variants of one problem differ in their values only: the second printer looks up what
    the first printed (and an order._Levels is shared, the key of the arrangements' memo)."""
    system, d, _ = solved(str(P05))
    other = dataclasses.replace(system, title="another variant")  # same symbols, roles and coordinates
    first, second = TexPrinter(system), TexPrinter(other)
    assert first.levels is second.levels
    expr = d.mass_matrix[0, 0]
    assert first(expr) == second(expr)
    assert counted.count(expr) == 1


def test_more_significant_figures_is_another_table(counted: list[sp.Basic]) -> None:
    system, _, _ = solved(str(P05))
    third = sp.Rational(1, 3) * sp.Symbol("m1", positive=True)
    plain = TexPrinter(system)
    precise = TexPrinter(dataclasses.replace(system, significant_figures=8))
    number = sp.Float(1, 15) / 3
    assert plain(number) == "0.3333"
    assert precise(number) == "0.33333333"
    assert plain(third) == plain(third)


def test_names_given_later_are_never_looked_up_under_the_old_ones() -> None:
    """The Newton–Euler step names its unknown reactions (R[pivot].x -> R_{pivot,x}) after other sections
    printed: what it prints then is printed with the names."""
    forget()
    system, _, _ = solved(str(P05))
    unknown = sp.Symbol("R[shoulder].x")
    tex = TexPrinter(system)
    before = tex(2 * unknown)
    tex.name({unknown: "R_{\\mathrm{shoulder},x}"})
    after = tex(2 * unknown)
    assert before != after
    assert "R_{\\mathrm{shoulder},x}" in after
    # and a fresh printer without the names does not see the named text
    assert TexPrinter(system)(2 * unknown) == before


def test_forget_empties_every_table(counted: list[sp.Basic]) -> None:
    system, d, _ = solved(str(P05))
    expr = d.mass_matrix[0, 0]
    TexPrinter(system)(expr)
    forget()
    assert order.arranged.cache_info().currsize == 0
    assert not printer_module._PRINTED
    TexPrinter(system)(expr)
    assert counted.count(expr) == 2
