"""Marking answers files against one spec: derive once, mark every file, in input order.

The spec is loaded and derived once per run (:func:`load_reference`); each answers file is then read
and marked on its own (:func:`mark_file`), in worker processes when there are several files
(:func:`mark_files`). A file that cannot be read is not fatal to the run: its result holds the
located errors, and the other files are still marked.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path

from tutgen.check.compare import ItemResult, Reference, Status
from tutgen.errors import EXIT_CHECK_FAILED, EXIT_INVALID_SPEC, EXIT_OK, SpecErrors

__all__ = ["CheckRun", "FileResult", "check", "load_reference", "mark_file", "mark_files"]


@dataclass(frozen=True)
class FileResult:
    """The marks of one answers file, or the errors that kept it from being marked."""

    path: str
    student: str | None
    items: tuple[ItemResult, ...]
    errors: tuple[str, ...] = ()  # "file:line:col: error: ..." when the file is invalid

    @property
    def status(self) -> str:
        """``pass`` (every item correct), ``fail`` (an item wrong or missing) or ``invalid``."""
        if self.errors:
            return "invalid"
        return "pass" if all(i.status is Status.CORRECT for i in self.items) else "fail"

    def count(self, status: Status) -> int:
        return sum(1 for i in self.items if i.status is status)


@dataclass(frozen=True)
class CheckRun:
    """One `tutgen check`: a spec and the marks of every answers file, in the order given."""

    spec: str
    title: str
    files: tuple[FileResult, ...]

    @property
    def exit_code(self) -> int:
        """3 if an answers file is invalid, else 1 if an answer is wrong or missing, else 0."""
        if any(f.errors for f in self.files):
            return EXIT_INVALID_SPEC
        if any(f.status != "pass" for f in self.files):
            return EXIT_CHECK_FAILED
        return EXIT_OK

    @property
    def errors(self) -> list[str]:
        return [e for f in self.files for e in f.errors]


def load_reference(spec: str | Path) -> Reference:
    """Load, validate and derive a spec (raises SpecErrors / DerivationError) as a :class:`Reference`."""
    from tutgen.check.compare import reference_from
    from tutgen.engine.pipeline import derive
    from tutgen.spec.validate import load_system

    system = load_system(spec)
    return reference_from(system, derive(system), str(spec))


def mark_file(ref: Reference, path: str | Path) -> FileResult:
    """Read one answers file and mark it; a file that cannot be read gives a result with its errors."""
    from tutgen.check.answers import read_answers
    from tutgen.check.compare import check_sheet

    try:
        sheet = read_answers(path)
        items = check_sheet(sheet, ref)
    except SpecErrors as exc:
        return FileResult(str(path), None, (), tuple(str(e) for e in exc.errors))
    return FileResult(sheet.path, sheet.student, tuple(items))


_worker_reference: Reference | None = None


def _init_worker(ref: Reference) -> None:
    global _worker_reference
    _worker_reference = ref


def _mark_in_worker(path: str) -> FileResult:
    assert _worker_reference is not None
    return mark_file(_worker_reference, path)


def mark_files(
    ref: Reference,
    paths: Sequence[str | Path],
    *,
    jobs: int | None = None,
    on_done: Callable[[], None] | None = None,
) -> list[FileResult]:
    """Mark every answers file, in ``jobs`` worker processes (default: one per core), and return the
    results in the order of ``paths`` whatever order the workers finish in. ``on_done`` is called once
    per finished file (for a progress bar)."""
    workers = min(jobs or os.cpu_count() or 1, len(paths))
    if workers <= 1:
        out = []
        for path in paths:
            out.append(mark_file(ref, path))
            if on_done:
                on_done()
        return out
    with ProcessPoolExecutor(max_workers=workers, initializer=_init_worker, initargs=(ref,)) as pool:
        futures = [pool.submit(_mark_in_worker, str(p)) for p in paths]
        for _ in as_completed(futures):
            if on_done:
                on_done()
        return [f.result() for f in futures]


def check(
    spec: str | Path,
    answers: Sequence[str | Path],
    *,
    jobs: int | None = None,
    on_done: Callable[[], None] | None = None,
) -> CheckRun:
    """Derive ``spec`` once and mark every answers file against it."""
    ref = load_reference(spec)
    return CheckRun(ref.spec, ref.title, tuple(mark_files(ref, answers, jobs=jobs, on_done=on_done)))
