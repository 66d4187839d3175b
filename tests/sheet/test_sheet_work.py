"""A sheet does each piece of work once (issue 17): each unit (a problem at one set of values) draws its
figure and its free bodies once, for the Markdown and the LaTeX sheets and the files beside them alike."""

from __future__ import annotations

import collections
import dataclasses
import functools
from pathlib import Path

import pytest

from tests.conftest import SPECS
from tutgen.sheet.build import (
    ProblemBase,
    Shared,
    Unit,
    UnitQueue,
    UnitResult,
    build_sheet,
    derive_problems,
    plan_units,
    unit_pieces,
)
from tutgen.sheet.model import load_sheet
from tutgen.sheet.variants import variant_ids


def test_each_unit_draws_its_figure_and_free_bodies_once(monkeypatch: pytest.MonkeyPatch) -> None:
    import tutgen.figure.build as figure_build
    import tutgen.figure.freebody as freebody

    sheet = load_sheet(SPECS / "tutorial-1" / "sheet.yaml")
    # the cart-pendulum prints Newton–Euler with its free bodies; the RR arm does not
    sheet = dataclasses.replace(sheet, problems=tuple(p for p in sheet.problems if p.key[:3] in ("p03", "p05")))
    derivations, _ = derive_problems(sheet)
    drawn: collections.Counter[str] = collections.Counter()
    draw, diagram = figure_build.drawn_by_reads, freebody.free_body_diagram

    def counting_draw(system, what, how):  # type: ignore[no-untyped-def]
        if what == ("system",):  # asked of the drawings shared by values (tests/figure/test_drawn_by_reads.py)
            drawn[system.source] += 1
        return draw(system, what, how)

    def counting_diagram(system, body, forces=None):  # type: ignore[no-untyped-def]
        drawn[f"{body} (free body)"] += 1
        return diagram(system, body, forces)

    monkeypatch.setattr(figure_build, "drawn_by_reads", counting_draw)
    monkeypatch.setattr(freebody, "free_body_diagram", counting_diagram)
    build = build_sheet(sheet, formats=("md", "tex"), variants=variant_ids(2), seed=3, derivations=derivations)
    assert any(name.endswith(".svg") for name, _ in build.files)
    # three units per problem: the nominal values and each variant's (whose values differ here)
    assert {k: v for k, v in drawn.items() if "free body" not in k} == {str(p.path): 3 for p in sheet.problems}
    assert drawn["cart (free body)"] == drawn["pendulum (free body)"] == 3


@pytest.fixture(scope="module")
def tutorial() -> Shared:
    """The tutorial sheet's problems, derived, as the workers get them."""
    sheet = load_sheet(SPECS / "tutorial-1" / "sheet.yaml")
    derivations, _ = derive_problems(sheet)
    problems = tuple(
        ProblemBase(p.number, p.key, str(p.path), p.text, d, p.marking)
        for p, d in zip(sheet.problems, derivations, strict=True)
    )
    return Shared(header={}, problems=problems, formats=("md",), seed=1, method=None, has_variants=True)


def test_units_are_dealt_out_a_problem_at_a_time(tutorial: Shared) -> None:
    """Every unit once; with a few workers all of a problem's units in one piece (one worker builds its
    variants, its tables of printed texts serving each next one), the largest pieces first; with many
    workers (a cluster) a problem's units split so that every worker has work."""
    shared = tutorial
    problems = shared.problems
    units = plan_units(shared, variant_ids(40))
    for workers in (1, 2, 64):
        pieces = unit_pieces(shared, units, workers)
        dealt = [u for piece in pieces for u in piece]
        assert sorted(dealt, key=units.index) == list(units)  # each unit exactly once
        assert all(len({u.problem for u in piece}) == 1 for piece in pieces)
        if workers <= 2:
            assert len(pieces) == len(problems)
    few = unit_pieces(shared, units, 2)
    assert problems[few[0][0].problem].key.startswith("p08")  # the spatial RR arm prints the most
    assert problems[few[-1][0].problem].key.startswith("p10")  # no parameters: one unit
    assert len(unit_pieces(shared, units, 64)) > len(problems)


def test_problems_derived_in_the_workers_make_the_same_sheets() -> None:
    """With several workers the problems are derived in them and pickled back (issue 17: the derivations
    were all in the parent, a tenth of the wall time): the derivations equal those made here, and the
    sheets built from them are the same bytes."""
    from tutgen.sheet.executor import ProcessExecutor

    sheet = load_sheet(SPECS / "tutorial-1" / "sheet.yaml")
    sheet = dataclasses.replace(sheet, problems=tuple(p for p in sheet.problems if p.key[:3] in ("p03", "p08")))
    here, _ = derive_problems(sheet)
    there, seconds = derive_problems(sheet, executor=ProcessExecutor(2))
    assert seconds > 0
    for a, b in zip(here, there, strict=True):
        assert a is not b
        assert a.mass_matrix == b.mass_matrix and a.equations_of_motion == b.equations_of_motion
    built = [
        build_sheet(sheet, formats=("md", "tex"), variants=variant_ids(2), seed=5, derivations=d) for d in (here, there)
    ]
    assert built[0].files == built[1].files


def test_a_problem_that_cannot_be_derived_in_a_worker_is_reported_as_here(monkeypatch: pytest.MonkeyPatch) -> None:
    import tutgen.engine.pipeline
    from tutgen.errors import DerivationError
    from tutgen.sheet.executor import ProcessExecutor

    sheet = load_sheet(SPECS / "tutorial-1" / "sheet.yaml")
    real = tutgen.engine.pipeline.derive

    def derive(system, *args, **kwargs):  # type: ignore[no-untyped-def]
        if "pendulum" in system.title:
            raise DerivationError("no such luck", system.origin)
        return real(system, *args, **kwargs)

    monkeypatch.setattr(tutgen.engine.pipeline, "derive", derive)  # the workers are forked: they see it
    errors = []
    for executor in (None, ProcessExecutor(2)):
        with pytest.raises(DerivationError) as info:
            derive_problems(sheet, executor=executor)
        errors.append((type(info.value), str(info.value)))
    assert errors[0] == errors[1]
    assert "p03-cart-pendulum.yaml" in errors[0][1] and "no such luck" in errors[0][1]


def test_a_staged_build_writes_the_same_files_in_its_workers(tmp_path: Path) -> None:
    """Given a staging directory, the workers write each sheet's files there themselves (issue 17: the
    parent wrote 4600 files after the pool had finished) and send back None for them; the files are those
    a build in memory returns, byte for byte, and only the index is left for the parent to write."""
    from tutgen.sheet.executor import ProcessExecutor

    sheet = load_sheet(SPECS / "tutorial-1" / "sheet.yaml")
    sheet = dataclasses.replace(sheet, problems=tuple(p for p in sheet.problems if p.key[:3] in ("p02", "p10")))
    derivations, _ = derive_problems(sheet)
    kwargs = {"formats": ("md", "tex"), "variants": variant_ids(3), "seed": 4, "derivations": derivations}
    memory = build_sheet(sheet, **kwargs)  # type: ignore[arg-type]
    for executor in (None, ProcessExecutor(2)):
        root = tmp_path / ("serial" if executor is None else "pool")
        root.mkdir()
        ticks: list[None] = []
        tick = functools.partial(ticks.append, None)
        staged = build_sheet(sheet, executor=executor, stage=lambda r=root: (r, Path("out")), on_done=tick, **kwargs)  # type: ignore[arg-type]
        assert len(ticks) == 1 + 3  # the progress: one tick per sheet, the last when every sheet is built
        assert [n for n, _ in staged.files] == [n for n, _ in memory.files]
        left = {n for n, content in staged.files if content is not None}
        assert left == {"variants/index.csv"}
        on_disk = {str(p.relative_to(root)) for p in root.rglob("*") if p.is_file()}
        assert on_disk == {n for n, _ in memory.files} - left
        for name, content in memory.files:
            if name not in left:
                got = (root / name).read_bytes()
                assert got == (content if isinstance(content, bytes) else content.encode("utf-8")), name


#: Seconds per unit of each tutorial problem as measured on a 100-variant sheet (issue 17): p01, the
#: composite inertia, costs far more than its equations' size says
_COST = {"p01": 0.044, "p02": 0.0087, "p03": 0.034, "p04": 0.044, "p05": 0.060, "p06": 0.0094,
         "p07": 0.040, "p08": 0.075, "p09": 0.0046, "p10": 0.015}  # fmt: skip


def _finish(shared: Shared, next_piece, workers: int = 2) -> tuple[list[float], list[tuple[Unit, ...]]]:  # type: ignore[no-untyped-def]
    """When each of ``workers`` workers finishes, pieces taken as ``next_piece(worker, last piece)`` gives
    them (an event simulation at the costs of _COST), and the pieces in the order they were handed out."""
    clock = [0.0] * workers
    last: list[tuple[Unit, ...] | None] = [None] * workers
    dealt: list[tuple[Unit, ...]] = []
    free = list(range(workers))
    while free:
        w = min(free, key=lambda i: (clock[i], i))
        piece = next_piece(w, last[w])
        if piece is None:
            free.remove(w)
            continue
        dealt.append(piece)
        clock[w] += sum(_COST[shared.problems[u.problem].key[:3]] for u in piece)
        last[w] = piece
    return clock, dealt


def test_a_local_pool_takes_the_units_as_its_workers_become_free(tutorial: Shared) -> None:
    """``UnitQueue``: every unit once; each worker starts the largest problem left and goes on with it,
    half of what is left each time; at the end the workers share the problem with the most work left.
    At the tutorial's measured costs two workers end within 0.1 s of each other, where the pieces decided
    in advance (``unit_pieces``) leave one idle for longer (p01 guessed small and built last)."""
    units = plan_units(tutorial, variant_ids(100))
    queue = UnitQueue(tutorial, units)

    def pulled(worker: int, last: tuple[Unit, ...] | None) -> tuple[Unit, ...] | None:
        if last is not None:
            cost = _COST[tutorial.problems[last[0].problem].key[:3]]
            results = [UnitResult(view={}, system=None, assets=None, render_seconds=cost) for _ in last]
            queue.done(last, results)
        return queue.next(last[0].problem if last else None)

    clock, dealt = _finish(tutorial, pulled)
    handed = [u for piece in dealt for u in piece]
    assert sorted(handed, key=units.index) == units  # each unit exactly once
    assert all(len({u.problem for u in piece}) == 1 for piece in dealt)
    first = [tutorial.problems[piece[0].problem].key[:3] for piece in dealt[:2]]
    assert first == ["p08", "p05"]  # the two largest problems first, one for each worker
    p08 = [u for u in units if u.problem == dealt[0][0].problem]
    assert dealt[0] == tuple(p08[: -(-len(p08) // 2)])  # half of it, the rest left for the same worker
    assert abs(clock[0] - clock[1]) < 0.1, clock

    pieces = unit_pieces(tutorial, units, 2)
    static = iter(pieces)
    before, _ = _finish(tutorial, lambda worker, last: next(static, None))
    assert abs(before[0] - before[1]) > abs(clock[0] - clock[1])
