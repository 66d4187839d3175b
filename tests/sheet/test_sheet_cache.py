"""A sheet derives each problem once and builds each variant by substitution: every file of a variant
must be byte-identical to the same variant built from scratch, each of its problems derived afresh from
its concrete spec (simplified numbers, term order, perfect squares, "vanishes" remarks and all)."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import pytest

from tests.conftest import SPECS
from tutgen.sheet.build import SheetBuild, build_sheet, derive_problems, plan_units
from tutgen.sheet.model import Sheet, load_sheet
from tutgen.sheet.variants import variant_ids

SHEET = SPECS / "tutorial-1" / "sheet.yaml"


def _sheet(keys: Sequence[str] | None) -> Sheet:
    sheet = load_sheet(SHEET)
    if keys is None:
        return sheet
    return dataclasses.replace(sheet, problems=tuple(p for p in sheet.problems if p.key[:3] in keys))


def _both(
    monkeypatch: pytest.MonkeyPatch, sheet: Sheet, variants: int, formats: tuple[str, ...]
) -> tuple[SheetBuild, SheetBuild]:
    """The sheet built as `tutgen sheet` builds it, and built with every variant's problems derived from
    scratch (the fallback of a variant whose values could change the derivation's structure)."""
    derivations, _ = derive_problems(sheet)
    chosen = variant_ids(variants)
    cached = build_sheet(sheet, formats=formats, variants=chosen, seed=2026, derivations=derivations)
    with monkeypatch.context() as m:
        m.setattr("tutgen.sheet.variants.changes_structure", lambda system, values: True)
        fresh = build_sheet(sheet, formats=formats, variants=chosen, seed=2026, derivations=derivations)
    return cached, fresh


def _assert_same(cached: SheetBuild, fresh: SheetBuild, sheet: Sheet, variants: int) -> None:
    assert not cached.rederived  # by substitution: positive values never change the structure
    # the reference really derived every problem of every variant afresh
    assert len(fresh.rederived) == variants * len(sheet.problems)
    assert [n for n, _ in cached.files] == [n for n, _ in fresh.files]
    for (name, mine), (_, theirs) in zip(cached.files, fresh.files, strict=True):
        assert mine == theirs, f"{name}: substitution differs from a fresh derivation"


def test_substituted_variants_are_byte_identical_to_fresh_derivations(monkeypatch: pytest.MonkeyPatch) -> None:
    # the cart-pendulum (perfect squares, decimals merged) and the PR manipulator (a singular H, terms
    # that vanish), one variant, as Markdown; the slow test below takes the whole sheet
    sheet = _sheet(["p03", "p09"])
    cached, fresh = _both(monkeypatch, sheet, 1, ("md",))
    _assert_same(cached, fresh, sheet, 1)


@pytest.mark.slow
def test_the_whole_tutorial_sheet_by_substitution_is_byte_identical(monkeypatch: pytest.MonkeyPatch) -> None:
    sheet = _sheet(None)
    cached, fresh = _both(monkeypatch, sheet, 4, ("md", "tex"))
    _assert_same(cached, fresh, sheet, 4)


@pytest.mark.parametrize("key", ["p03", "p05", "p09"])
def test_a_keys_results_are_those_of_the_whole_json(key: str) -> None:
    """The keys take ``results`` without building the JSON's steps: the same results as the whole
    document of `tutgen solve --format json`."""
    from tutgen.render.jsonout import derivation_to_json
    from tutgen.sheet.build import ProblemBase, variant_derivation
    from tutgen.sheet.render import results_json

    sheet = _sheet([key])
    (p,) = sheet.problems
    derivations, _ = derive_problems(sheet)
    d, values, _, _ = variant_derivation(
        ProblemBase(p.number, p.key, str(p.path), p.text, derivations[0]), "v003", 7, None
    )
    assert values
    whole = derivation_to_json(d)
    assert whole["steps"]  # the steps the keys leave out
    assert results_json(d) == whole["results"]


def test_each_problem_and_values_is_built_once_per_sheet() -> None:
    """The units of a sheet: the nominal problems, and each distinct problem-and-values once (a problem
    that does not vary is built once, however many variants)."""
    from types import SimpleNamespace

    from tutgen.sheet.build import ProblemBase, Shared, unit_key

    sheet = load_sheet(SHEET)
    problems = tuple(  # a unit's values are sampled from the system alone: no derivation needed here
        ProblemBase(p.number, p.key, str(p.path), p.text, SimpleNamespace(system=p.system), p.marking)  # type: ignore[arg-type]
        for p in sheet.problems
    )
    shared = Shared(header={}, problems=problems, formats=("md",), seed=2026, method=None, has_variants=True)
    variants = variant_ids(40)
    units = plan_units(shared, variants)
    keys = [unit_key(shared, u.problem, u.variant) for u in units]
    assert len(keys) == len(set(keys))
    for i, p in enumerate(sheet.problems):
        distinct = {unit_key(shared, i, v.id) for v in variants}
        assert sum(1 for u in units if u.problem == i and u.variant is not None) == len(distinct)
        if p.key.startswith("p10"):  # no parameters: one unit for all forty variants
            assert len(distinct) == 1


def test_a_keys_results_leave_out_only_the_planar_working() -> None:
    """The keys drop newton_euler.planar (the free bodies in words, not an answer): built without it, the
    rest is the whole JSON's results."""
    from tutgen.render.jsonout import derivation_to_json
    from tutgen.sheet.build import ProblemBase, variant_derivation
    from tutgen.sheet.render import key_results, results_json

    sheet = _sheet(["p03"])
    (p,) = sheet.problems
    derivations, _ = derive_problems(sheet)
    d, _, _, _ = variant_derivation(ProblemBase(p.number, p.key, str(p.path), p.text, derivations[0]), "v002", 7, None)
    whole = derivation_to_json(d)["results"]
    assert "planar" in whole["newton_euler"]
    lean = results_json(d, working=False)
    assert "planar" not in lean["newton_euler"]
    assert lean == {**whole, "newton_euler": {k: v for k, v in whole["newton_euler"].items() if k != "planar"}}
    assert key_results(d, lean) == key_results(d, whole)
