"""Building a sheet: derive each problem once, then every variant by substitution.

:func:`build_sheet` returns every file's path (relative to the output directory) and content, in a fixed
order; the CLI writes them into a staging directory and moves it to the output only when everything
succeeded (tutgen/sheet/run.py). Given that staging directory (``stage``), the workers write each sheet's
files into it themselves as they build it, and the content returned is None for those. The
output layout (docs/sheets.md)::

    questions.<fmt>, solutions.<fmt>                 the sheet at the nominal values
    variants/<id>/questions.<fmt>, solutions.<fmt>   per variant (or per student, by id)
    variants/<id>/specs/<problem>.yaml               its concrete specs: every parameter fixed
    variants/<id>/key-<problem>.yaml                 its answer keys, for `tutgen check`
    variants/<id>/marking-<problem>.yaml             its marking keys (`tutgen check --key`)
    variants/index.csv                               id, name and the values of each variant
"""

from __future__ import annotations

import csv
import dataclasses
import io
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from tutgen.engine.derivation import Derivation
from tutgen.model.marking import Marking
from tutgen.sheet.model import Sheet
from tutgen.sheet.variants import Variant

FORMATS = ("md", "tex", "pdf", "moodle", "qti")
#: The LMS exports (tutgen/lms, docs/lms.md): one file for the whole sheet, every variant in it.
LMS_FILES = {"moodle": "questions-moodle.xml", "qti": "questions-qti.zip"}


@dataclass(frozen=True)
class ProblemBase:
    """What a worker needs of one problem: shipped once to each worker."""

    number: int
    key: str
    path: str
    text: str
    derivation: Derivation
    marking: Marking | None = None  # the sheet's or the problem's marking: (for its marking keys)


@dataclass(frozen=True)
class Unit:
    """One problem at one set of values, built once per sheet: the nominal sheet's (``variant`` None), or
    that of the first variant with these values (every variant with the same values shares it)."""

    problem: int  # the index of the problem in Shared.problems
    variant: str | None


@dataclass(frozen=True)
class UnitResult:
    """What the sheets of one problem at one set of values are made of (plain data, pickled back)."""

    view: dict[str, Any]
    system: Any  # the problem's system as set (its numbers): its figure and LMS question
    assets: Any  # its free-body SVGs and simulation plots (tutgen/sheet/assets.py)
    results: str = ""  # the answer key's results (a variant's, or the nominal one's for an LMS export)
    marks: str = ""  # the marking key
    concrete: str = ""  # a variant's concrete spec
    fresh: bool = False  # derived afresh, not by substitution (variant_derivation)
    derive_seconds: float = 0.0
    render_seconds: float = 0.0
    figure: tuple[str, str] | None = None  # a Markdown sheet's figure: (file name, SVG), drawn with the unit


@dataclass(frozen=True)
class Shared:
    header: dict[str, str]
    problems: tuple[ProblemBase, ...]
    formats: tuple[str, ...]
    seed: int
    method: str | None  # the --method override, or None: each spec's own `methods:`
    has_variants: bool = False  # an LMS export holds the variants, or (without) the nominal sheet
    stage: tuple[str, str] | None = None  # where the jobs write their files, and the -o it stands for
    units: dict[tuple[Any, ...], UnitResult] = field(default_factory=dict)  # unit_key -> its result


@dataclass(frozen=True)
class Job:
    """One sheet to build: the nominal one (``variant`` None) or a variant."""

    variant: Variant | None


@dataclass(frozen=True)
class JobResult:
    files: tuple[tuple[str, str | bytes | None], ...]  # None: written into Shared.stage
    values: tuple[tuple[str, str, str], ...]  # (problem, parameter, value as written)
    rederived: tuple[str, ...]  # the problems derived afresh for this variant
    derive_seconds: float
    render_seconds: float
    lms: tuple[Any, ...] = ()  # this sheet's tutgen.lms LmsQuestions, for -f moodle / -f qti


@dataclass
class SheetBuild:
    files: list[tuple[str, str | bytes | None]] = field(default_factory=list)  # None: written to the stage
    derive_seconds: float = 0.0  # the symbolic derivations (once per problem, plus any variant re-derived)
    render_seconds: float = 0.0  # substitution, views, templates, keys, concrete specs, PDFs
    rederived: list[tuple[str, str]] = field(default_factory=list)  # (variant, problem)
    notes: list[str] = field(default_factory=list)  # what an LMS export left out, by name


def variant_derivation(
    base: ProblemBase, variant: str, seed: int, method: str | None
) -> tuple[Derivation, dict[str, Any], bool, str]:
    """This variant's derivation of one problem: the base derivation with the variant's values put in,
    or, when the values change the structure, a fresh derivation of the concrete spec. Also returns the
    values, whether it was derived afresh, and the concrete spec's text."""
    from tutgen.engine.pipeline import derive
    from tutgen.sheet.variants import changes_structure, concrete_spec, sample, with_values
    from tutgen.spec.validate import load_system_text

    system = base.derivation.system
    values = sample(system, base.key, variant, seed)
    concrete = concrete_spec(base.text, base.path, system, values)
    if changes_structure(system, values):
        return derive(load_system_text(concrete, base.path), method), values, True, concrete
    fixed = with_values(system, values)
    return substituted(base.derivation, fixed), values, False, concrete


@dataclass(frozen=True)
class VariantDerivation(Derivation):
    """A derivation with a variant's values: the same symbolic results, and a :meth:`numeric` that
    replaces the parameters by their values as ``xreplace`` does (exact; the symbols are atoms, so nothing
    else is needed) and remembers each result, as the views and the answer key ask for the same ones."""

    _memo: dict[Any, Any] = field(default_factory=dict, compare=False, repr=False)
    #: every subtree replaced so far, with whether it changed (:func:`tutgen.engine.replace.replaced`):
    #: the results share most of their subtrees (H's entries in the equations, T's terms in L), each
    #: rebuilt once per unit (3 % less CPU over a sheet of 30 variants)
    _trees: dict[Any, tuple[Any, bool]] = field(default_factory=dict, compare=False, repr=False)

    def numeric(self, expr: Any) -> Any:
        import sympy as sp

        from tutgen.engine.replace import replaced

        values = self.values
        if not values or not hasattr(expr, "xreplace"):
            return expr
        try:
            return self._memo[expr]
        except (KeyError, TypeError):
            pass
        if isinstance(expr, sp.MatrixBase):  # entry by entry, as a matrix's own xreplace
            out = expr.applyfunc(lambda e: replaced(e, values, self._trees)[0])
        elif isinstance(expr, sp.Basic):
            out = replaced(expr, values, self._trees)[0]
        else:
            out = expr.xreplace(values)
        try:
            self._memo[expr] = out
        except TypeError:  # an unhashable (mutable) matrix
            pass
        return out


def substituted(derivation: Derivation, system: Any) -> VariantDerivation:
    """``derivation`` with ``system`` (the same problem, other parameter values) in its place.

    Everything the engine derives is symbolic in the parameters, except the principal moments and axes,
    which it computes from the numbers: those are computed again, as the engine does, from this system.
    """
    from tutgen.engine.inertia import body_principal

    fields = {f.name: getattr(derivation, f.name) for f in dataclasses.fields(Derivation)}
    fields["system"] = system
    if system.values != derivation.system.values:
        values = system.values
        fields["principal"] = tuple(body_principal(bi, values) for bi in derivation.inertia)
        fields["simulation"] = None  # the run was of the other values: run again (tutgen/sim/solution.py)
    return VariantDerivation(**fields)


def unit_key(shared: Shared, problem: int, variant: str | None) -> tuple[Any, ...]:
    """The values a unit is built at: the same key, the same input, the same text (no Python ``hash()``
    of anything: a key only looks results up, in one build)."""
    if variant is None:
        return (problem, None)
    from tutgen.sheet.variants import sample

    base = shared.problems[problem]
    return (problem, tuple(sample(base.derivation.system, base.key, variant, shared.seed).items()))


def plan_units(shared: Shared, variants: Sequence[Variant]) -> list[Unit]:
    """Every distinct problem-and-values of the sheet, once: the nominal problems, then each variant's
    problems whose values no earlier variant had (a problem that does not vary is built once)."""
    units = [Unit(i, None) for i in range(len(shared.problems))]
    seen: set[tuple[Any, ...]] = set()
    for v in variants:
        for i in range(len(shared.problems)):
            key = unit_key(shared, i, v.id)
            if key not in seen:
                seen.add(key)
                units.append(Unit(i, v.id))
    return units


def build_unit(shared: Shared, unit: Unit) -> UnitResult:
    """One problem at one set of values: its derivation by substitution (or afresh), its worked
    solution's view, its keys and its assets; runs in a worker."""
    from tutgen.sheet.assets import problem_assets
    from tutgen.sheet.render import key_results, marking_key, problem_view, results_json

    base = shared.problems[unit.problem]
    start = time.perf_counter()
    t_derive = 0.0
    concrete, fresh = "", False
    if unit.variant is None:
        d: Derivation = substituted(base.derivation, base.derivation.system)
    else:
        d, _, fresh, concrete = variant_derivation(base, unit.variant, shared.seed, shared.method)
        t_derive = time.perf_counter() - start if fresh else 0.0
        d = _simulated(d)
    view = problem_view(base.number, d, solution=True)
    wants_lms = any(f in LMS_FILES for f in shared.formats) and shared.has_variants == (unit.variant is not None)
    results = marks = ""
    if unit.variant is not None or wants_lms:
        document = results_json(d, working=False)  # once, for both keys (which leave the working out)
        results = key_results(d, document)
        marks = marking_key(d, base.marking, f"specs/{base.key}.yaml", document)
    extra = problem_assets(base.key, base.number, d, shared.formats)
    figure = _figure_svg(base.key, d.system) if "md" in shared.formats else None
    if "tex" in shared.formats or "pdf" in shared.formats:
        # the figure's TikZ while its drawing is at hand (a job is built after every unit, when the drawings
        # remembered per system are gone); pickled to the parent, the view is this plain dict all the same
        view["figure"] = dict(view["figure"].items())
    total = time.perf_counter() - start
    return UnitResult(view, d.system, extra, results, marks, concrete, fresh, t_derive, total - t_derive, figure=figure)


def unit_pieces(shared: Shared, units: Sequence[Unit], workers: int) -> list[tuple[Unit, ...]]:
    """The units as the tasks of the workers, all decided before the first is built (for an executor that
    takes its tasks at once: one worker, a Dask cluster; a local pool takes them as it goes,
    :class:`UnitQueue`): every unit of a problem in one piece, so that one worker builds all of that
    problem's variants (its printer's texts, arranged terms and sympy's cache serve every variant after
    the first: a sheet of 100 variants took 13 % less CPU than with the units dealt out one by one), split
    only where a problem has more than its share of a pool twice the size of ``workers`` (a cluster). The
    largest pieces first (units times the size of the problem's equations, :func:`problem_sizes`), so that
    the last one to finish is a small one. The results do not depend on the pieces."""
    by_problem: dict[int, list[Unit]] = {}
    for u in units:
        by_problem.setdefault(u.problem, []).append(u)
    share = max(1, -(-len(units) // (2 * max(workers, 1))))  # ceil
    pieces = [tuple(g[i : i + share]) for _, g in sorted(by_problem.items()) for i in range(0, len(g), share)]
    sizes = problem_sizes(shared)

    def weight(piece: tuple[Unit, ...]) -> int:
        return len(piece) * sizes[piece[0].problem]

    return sorted(pieces, key=weight, reverse=True)  # stable: equal weights keep the sheet's order


def problem_sizes(shared: Shared) -> list[int]:
    """How much a unit of each problem prints: its steps' equations and its joint reactions (the keys'
    largest entries), in operations (the tutorial's order of cost: p08, p05, p07, p03, ...). A guess: a
    problem of numbers (the composite inertia of p01) costs more than its operations say."""
    import sympy as sp

    from tutgen.render.size import count_ops_upto

    sizes = []
    for problem in shared.problems:
        d = problem.derivation
        sides = [x for st in d.steps for eq in st.equations for x in (eq.lhs, eq.rhs) if isinstance(x, sp.Basic)]
        ne = d.newton_euler
        reactions = [x for r in ne.reactions for x in (*r.force, *r.moment)] if ne is not None else []
        sizes.append(1 + count_ops_upto(sides, 10**6) + count_ops_upto(reactions, 10**6))
    return sizes


class UnitQueue:
    """The units handed to the workers of a local pool as each becomes free (``ProcessExecutor.pull``),
    so that neither a guess of their cost nor the order of the pieces can leave a worker idle at the end
    while the other builds a problem it had guessed small (p01, the composite inertia, ran last and alone
    for half a second of a 100-variant sheet).

    A worker goes on with the problem it built last (its caches are warm for it), taking half of what is
    left of it each time; with nothing left there, it starts the largest problem no one has started (by
    :func:`problem_sizes`); with none left, it takes half of what is left of the problem with the most
    work still to hand out (by the seconds its units have taken so far), which another worker is building.
    The pieces get smaller as the work runs out, so the workers finish within a small piece of each other.
    Which worker builds which unit never changes what is built."""

    def __init__(self, shared: Shared, units: Sequence[Unit]) -> None:
        self._sizes = problem_sizes(shared)
        self._left: dict[int, list[Unit]] = {}
        for u in units:
            self._left.setdefault(u.problem, []).append(u)
        self._fresh = sorted(self._left, key=lambda p: (-len(self._left[p]) * self._sizes[p], p))
        self._seconds: dict[int, tuple[float, int]] = {}  # problem -> (seconds, units) built so far

    def next(self, last: int | None) -> tuple[Unit, ...] | None:
        """The next piece for a worker that last built a piece of problem ``last`` (None: none yet)."""
        if last is not None and self._left.get(last):
            return self._take(last)
        while self._fresh:
            problem = self._fresh.pop(0)
            if self._left.get(problem):
                return self._take(problem)
        busy = [p for p, left in self._left.items() if left]
        if not busy:
            return None
        return self._take(max(busy, key=lambda p: (self._cost(p) * len(self._left[p]), -p)))

    def done(self, piece: tuple[Unit, ...], results: Sequence[UnitResult]) -> None:
        """Remember how long the piece's units took (to choose what to share at the end)."""
        seconds, count = self._seconds.get(piece[0].problem, (0.0, 0))
        took = sum(r.derive_seconds + r.render_seconds for r in results)
        self._seconds[piece[0].problem] = (seconds + took, count + len(results))

    def _cost(self, problem: int) -> float:
        """Seconds per unit of ``problem``: as measured, or its size at the rate measured over all."""
        seconds, count = self._seconds.get(problem, (0.0, 0))
        if count:
            return seconds / count
        total = sum(s for s, _ in self._seconds.values())
        weight = sum(n * self._sizes[p] for p, (_, n) in self._seconds.items())
        return self._sizes[problem] * (total / weight if weight else 1.0)

    def _take(self, problem: int) -> tuple[Unit, ...]:
        left = self._left[problem]
        n = -(-len(left) // 2)  # half, rounded up
        piece, self._left[problem] = tuple(left[:n]), left[n:]
        return piece


def build_units(shared: Shared, piece: tuple[Unit, ...]) -> list[UnitResult]:
    """:func:`build_unit` of each unit of a piece, in order; runs in a worker."""
    return [build_unit(shared, u) for u in piece]


def build_job(shared: Shared, job: Job) -> JobResult:
    """Every file of one sheet (nominal or a variant), from its problems' units (``shared.units``,
    built by :func:`build_unit`); runs in a worker."""
    from tutgen.sheet.compact import shared_intros
    from tutgen.sheet.render import answer_key, render_sheet
    from tutgen.sheet.variants import quantity_text

    start = time.perf_counter()
    variant = job.variant.id if job.variant is not None else None
    units = [shared.units[unit_key(shared, i, variant)] for i in range(len(shared.problems))]
    views = [u.view for u in units]
    systems = [u.system for u in units]  # each problem's system as set (a variant's numbers), for its figure
    assets = [u.assets for u in units]
    files: list[tuple[str, str | bytes | None]] = []
    values_out: list[tuple[str, str, str]] = []
    rederived: list[str] = []
    lms: list[Any] = []
    wants_lms = any(f in LMS_FILES for f in shared.formats) and shared.has_variants == (job.variant is not None)
    prefix = ""
    header = dict(shared.header)
    if job.variant is not None:
        prefix = f"variants/{job.variant.id}/"
        header["label"] = job.variant.label
        for i, (base, u) in enumerate(zip(shared.problems, units, strict=True)):
            if u.fresh:
                rederived.append(base.key)
            params = {p.name: p for p in base.derivation.system.parameters}
            _, values = unit_key(shared, i, variant)
            values_out += [(base.key, n, quantity_text(params[n], v)) for n, v in values]
            files.append((f"{prefix}specs/{base.key}.yaml", u.concrete))
            key = answer_key(u.results, f"specs/{base.key}.yaml", job.variant.label)
            files.append((f"{prefix}key-{base.key}.yaml", key))
            files.append((f"{prefix}marking-{base.key}.yaml", u.marks))
            if wants_lms:
                lms.append(_lms(base, u.view, u.results, u.marks, u.system, job.variant.id, job.variant.label))
    elif wants_lms:
        for base, u in zip(shared.problems, units, strict=True):
            lms.append(_lms(base, u.view, u.results, u.marks, u.system, "nominal", ""))
    views = [a.view(v, md=False) for a, v in zip(assets, views, strict=True)]  # the plots' names on the sheet
    figures = {b.key: u.figure for b, u in zip(shared.problems, units, strict=True) if u.figure is not None}
    views = shared_intros(views)  # a section's conventions printed once per sheet (tutgen/sheet/compact.py)
    context = {**header, "problems": views}
    for kind in ("questions", "solutions"):
        tex = None
        for fmt in shared.formats:
            if fmt in LMS_FILES:
                continue  # one file for the whole sheet: build_sheet writes it
            if fmt == "md":
                md_views = [
                    _md_figure(a.view(v, md=True), figures.get(b.key))
                    for b, v, a in zip(shared.problems, views, assets, strict=True)
                ]
                files.append((f"{prefix}{kind}.md", render_sheet({**context, "problems": md_views}, kind, "md")))
            else:
                tex = tex if tex is not None else render_sheet(context, kind, "tex")
                if fmt == "tex":
                    files.append((f"{prefix}{kind}.tex", tex))
                else:
                    from tutgen.figure.picture import picture_files
                    from tutgen.render.pdf import compile_pdf

                    inputs = picture_files(systems)  # the problems' own pictures, and their simulations' plots
                    inputs.update(f for a in assets for f in a.tex_files)
                    pdf = compile_pdf(tex, files=inputs)
                    files.append((f"{prefix}{kind}.pdf", pdf))
    files += [(f"{prefix}{name}", svg) for name, svg in figures.values()]
    files += [(f"{prefix}{name}", content) for a in assets for name, content in a.files]
    if shared.stage is not None:  # written here, by the worker; the parent gets the names
        from tutgen.sheet.files import write_files

        root, shown = shared.stage
        write_files(Path(root), files, Path(shown))
        files = [(name, None) for name, _ in files]
    total = time.perf_counter() - start
    return JobResult(tuple(files), tuple(values_out), tuple(rederived), 0.0, total, tuple(lms))


def _lms(base: ProblemBase, view: Any, results: str, marks: str, system: Any, variant: str, label: str) -> Any:
    from tutgen.lms.collect import lms_question

    return lms_question(
        key=base.key, view=view, results_yaml=results, marking_yaml=marks, system=system, variant=variant, label=label
    )


def figure_name(key: str) -> str:
    """Where a Markdown sheet's figure of problem ``key`` is written, relative to the sheet."""
    return f"figures/{key}.svg"


def has_figure(system: Any) -> bool:
    """Whether the problem gets a generated figure (``figure: {generated: false}`` turns it off)."""
    return system.figure is None or system.figure.generated


def _figure_svg(key: str, system: Any) -> tuple[str, str] | None:
    """(file name, SVG) of the figure a Markdown sheet shows beside problem ``key``, or None. Drawn where
    the unit is built, with the drawing its worked solution's view uses (one drawing per unit)."""
    from tutgen.figure.view import svg_file
    from tutgen.sheet.render import as_set

    made = svg_file(as_set(system)) if has_figure(system) else None
    return (figure_name(key), made[1]) if made is not None else None


def _md_figure(view: dict[str, Any], figure: tuple[str, str] | None) -> dict[str, Any]:
    """A problem's view for a Markdown sheet: its figure by the sheet's own relative path. The spec's own
    picture (``figure.file``) is relative to the spec, not to the sheet, so it is left to the LaTeX sheets."""
    shown = {**view["figure"], "generated": figure is not None, "svg": figure[0] if figure else "", "file_md": False}
    # the Newton–Euler step's free-body diagrams: their SVGs in figures/ (tutgen/sheet/assets.py)
    return {**view, "figure": shown}


def _simulated(d: Derivation) -> Derivation:
    """``d`` with the run of its `simulate` section, when it asks for one (``ask: [simulation]``)."""
    from tutgen.engine.steps import StepKind

    if not d.has_step(StepKind.SIMULATION) or d.simulation is not None:
        return d
    from tutgen.sim.solution import attach_simulation

    return attach_simulation(d)


def derive_problems(
    sheet: Sheet, method: str | None = None, timeout: float | None = None, executor: Any = None
) -> tuple[list[Derivation], float]:
    """Each problem's derivation, once (raises DerivationError naming the spec); and the seconds taken
    (of the derivations themselves: with several workers, more than the wall time). With an ``executor``
    of several workers the problems are derived in its workers, each derivation pickled back (as a Dask
    cluster receives them; tests/sheet/test_sheet_work.py checks that the sheets are the same bytes):
    the derivations were a tenth of a 100-variant sheet's wall time on two cores, all in one process."""
    if executor is None or executor.workers <= 1:
        derived = [_derived(system, method, timeout) for system in (p.system for p in sheet.problems)]
    else:
        # imported once here, before the pool forks its workers (Newton–Euler is otherwise imported on use)
        import tutgen.engine.newton_euler
        import tutgen.engine.pipeline
        import tutgen.engine.planar_ne  # noqa: F401

        jobs = [p.system for p in sheet.problems]
        derived = executor.map(_derive_job, (method, timeout), jobs)
    return [d for d, _ in derived], sum(seconds for _, seconds in derived)


def _derived(system: Any, method: str | None, timeout: float | None) -> tuple[Derivation, float]:
    from tutgen.engine.pipeline import derive_with_deadline

    start = time.perf_counter()
    d = _simulated(derive_with_deadline(system, method, timeout))
    return d, time.perf_counter() - start


def _derive_job(shared: tuple[str | None, float | None], system: Any) -> tuple[Derivation, float]:
    """One problem's derivation in a worker (:func:`derive_problems`), within the time the run has left,
    so that a timeout names the spec and the step it was at (tutgen.limits.inherited_deadline)."""
    from tutgen.limits import inherited_deadline

    method, timeout = shared
    with inherited_deadline():
        return _derived(system, method, timeout)


def build_sheet(
    sheet: Sheet,
    *,
    formats: Sequence[str] = ("md",),
    variants: Sequence[Variant] = (),
    seed: int = 0,
    executor: Any = None,
    method: str | None = None,
    timeout: float | None = None,
    derivations: Sequence[Derivation] | None = None,
    on_done: Callable[[], None] | None = None,
    stage: Callable[[], tuple[Path, Path]] | None = None,
) -> SheetBuild:
    """Every file of the sheet and of its variants, in a fixed order (see the module's docstring).

    ``stage``, for an executor whose workers share this machine's files, gives (once the sheets are about
    to be built) a directory for the files and the output it stands for (named in an error): each sheet's
    files are written there by the worker that builds it, and their content in the result is None."""
    from tutgen.sheet.executor import SerialExecutor

    out = SheetBuild()
    if derivations is None:
        derivations, out.derive_seconds = derive_problems(sheet, method, timeout)
    shared = Shared(
        header={"title": sheet.title, "course": sheet.course, "date": sheet.date, "label": ""},
        problems=tuple(
            ProblemBase(p.number, p.key, str(p.path), p.text, d, p.marking)
            for p, d in zip(sheet.problems, derivations, strict=True)
        ),
        formats=tuple(f for f in FORMATS if f in formats),
        seed=seed,
        method=method,
        has_variants=bool(variants),
    )
    run = executor or SerialExecutor()
    # first every distinct problem-and-values (the expensive part: views, keys), each once, spread over
    # the workers in small pieces; then every sheet from them (templates only), in the order of the jobs
    units = plan_units(shared, variants)
    _warm_imports()  # imported once here, before a pool forks its workers
    built: dict[Unit, UnitResult] = {}
    pull = getattr(run, "pull", None)
    if pull is not None and run.workers > 1:  # a local pool: each worker's next piece as it becomes free
        queue = UnitQueue(shared, units)
        tick = _ticks(len(units), 1 + len(variants), on_done)

        def next_piece(last: tuple[Unit, ...] | None, results: list[UnitResult] | None) -> tuple[Unit, ...] | None:
            if last is not None and results is not None:
                queue.done(last, results)
                built.update(zip(last, results, strict=True))
                if tick is not None:
                    for _ in last:
                        tick()
            return queue.next(last[0].problem if last else None)

        pull(build_units, shared, next_piece)
    else:
        pieces = unit_pieces(shared, units, run.workers)
        tick = _ticks(len(pieces), 1 + len(variants), on_done)
        for piece, results_of_piece in zip(pieces, run.map(build_units, shared, pieces, tick), strict=True):
            built.update(zip(piece, results_of_piece, strict=True))
    unit_results = [built[u] for u in units]
    shared = dataclasses.replace(
        shared, units={unit_key(shared, u.problem, u.variant): r for u, r in zip(units, unit_results, strict=True)}
    )
    for r in unit_results:
        out.derive_seconds += r.derive_seconds
        out.render_seconds += r.render_seconds
    _warm_templates(shared.formats)  # compiled once here, inherited by the workers of a fork
    if stage is not None:
        root, shown = stage()
        shared = dataclasses.replace(shared, stage=(str(root), str(shown)))
    jobs = [Job(None), *(Job(v) for v in variants)]
    results = run.map(build_job, shared, jobs, None)
    if on_done:
        on_done()  # the last tick: every sheet is built
    for job, result in zip(jobs, results, strict=True):
        out.files += list(result.files)
        out.render_seconds += result.render_seconds
        out.rederived += [(job.variant.id if job.variant else "", k) for k in result.rederived]
    if variants:
        out.files.append(("variants/index.csv", _index(variants, results[1:])))
    lms_formats = [f for f in shared.formats if f in LMS_FILES]
    if lms_formats:
        from tutgen.lms.export import lms_files

        questions = [q for r in results for q in r.lms]
        files, out.notes = lms_files(sheet.title, questions, lms_formats, LMS_FILES)
        out.files += files
    return out


def _ticks(units: int, jobs: int, on_done: Callable[[], None] | None) -> Callable[[], None] | None:
    """``on_done`` as the progress of the sheets: of the ``jobs`` ticks, all but the last spread over the
    ``units`` (most of the time: the result is called once per unit, or per piece of units, built), the
    last once every sheet is built."""
    if on_done is None:
        return None
    state = {"done": 0, "ticked": 0}

    def tick() -> None:
        state["done"] += 1
        due = state["done"] * (jobs - 1) // max(units, 1)
        while state["ticked"] < due:
            state["ticked"] += 1
            on_done()

    return tick


def _warm_imports() -> None:
    """Import what :func:`build_unit` needs (the views, the JSON of the keys, sympy's solvers that the
    views call), so that the workers of a fork inherit the modules instead of each importing them."""
    import sympy.calculus.util
    import sympy.solvers.solveset  # noqa: F401

    import tutgen.render.jsonout
    import tutgen.sheet.assets
    import tutgen.sheet.render  # noqa: F401


def _warm_templates(formats: Sequence[str]) -> None:
    """Compile the sheets' templates in this process (once per process; a forked worker inherits them)."""
    from tutgen.sheet.render import warm_templates

    warm_templates([f for f in formats if f not in LMS_FILES])


def _index(variants: Sequence[Variant], results: Sequence[JobResult]) -> str:
    columns: list[tuple[str, str]] = []
    for result in results:
        for problem, name, _ in result.values:
            if (problem, name) not in columns:
                columns.append((problem, name))
    from tutgen.safetext import csv_cell

    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(["id", "label", *(f"{p}:{n}" for p, n in columns)])
    for v, result in zip(variants, results, strict=True):
        got = {(p, n): text for p, n, text in result.values}
        # a student's name is the roster's text: a spreadsheet must not read it as a formula
        writer.writerow([csv_cell(v.id), csv_cell(v.label), *(csv_cell(got.get(c, "")) for c in columns)])
    return buf.getvalue()


def file_names(
    sheet: Sheet,
    variants: Sequence[Variant],
    formats: Sequence[str],
    derivations: Sequence[Derivation] | None = None,
) -> list[str]:
    """The files :func:`build_sheet` makes, in its order: before anything is derived, all but the
    problems' free-body diagrams and simulation plots, which ``derivations`` (each problem's, as
    :func:`derive_problems` gives them) add (tutgen/sheet/assets.py)."""
    from tutgen.sheet.assets import asset_names

    fmts = [f for f in FORMATS if f in formats]
    figures = [figure_name(p.key) for p in sheet.problems if has_figure(p.system)] if "md" in fmts else []
    for p, d in zip(sheet.problems, derivations or (), strict=False):
        figures += asset_names(p.key, d, fmts)
    docs = [f for f in fmts if f not in LMS_FILES]
    names = [f"{kind}.{fmt}" for kind in ("questions", "solutions") for fmt in docs] + figures
    for v in variants:
        prefix = f"variants/{v.id}/"
        for p in sheet.problems:
            names += [f"{prefix}specs/{p.key}.yaml", f"{prefix}key-{p.key}.yaml", f"{prefix}marking-{p.key}.yaml"]
        names += [f"{prefix}{kind}.{fmt}" for kind in ("questions", "solutions") for fmt in docs]
        names += [f"{prefix}{name}" for name in figures]
    if variants:
        names.append("variants/index.csv")
    names += [LMS_FILES[f] for f in fmts if f in LMS_FILES]
    return names
