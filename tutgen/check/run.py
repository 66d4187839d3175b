"""Marking answers files against one spec: derive once, mark every file in its own bounded process.

The spec is loaded and derived once per run, under the same time limit as ``tutgen solve``
(:func:`load_reference`). Each answers file is then marked in a child process of its own
(:func:`mark_files`), forked from this one so that the derivation is shared without copying:

- the child's address space is capped (:func:`tutgen.check.limits.cap_memory`), each of its entries
  has ``--timeout`` seconds (:func:`tutgen.check.limits.answer_deadline`), and the child is killed
  when it runs past ``--file-timeout`` seconds, or dies with this process (Linux: ``PR_SET_PDEATHSIG``);
- a file that cannot be read, that runs out of time or memory, or that trips a bug in tutgen gets
  its own verdict; the other files are still marked, and the reports are always written.

Non-regular files (FIFOs, devices, directories) are refused before anything is derived
(:func:`refuse_irregular`): reading a FIFO would wait forever.
"""

from __future__ import annotations

import ctypes
import multiprocessing
import os
import signal
import stat
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from multiprocessing.connection import Connection, wait
from pathlib import Path
from typing import Any

from tutgen.check.compare import DEFAULT_ANSWER_TIMEOUT, ItemResult, Reference, Status, unmarked_items
from tutgen.errors import (
    EXIT_CHECK_FAILED,
    EXIT_INTERNAL,
    EXIT_INVALID_SPEC,
    EXIT_OK,
    Location,
    SpecErrors,
    UsageError,
)
from tutgen.model.marking import Marking

__all__ = [
    "DEFAULT_FILE_TIMEOUT",
    "CheckRun",
    "FileResult",
    "check",
    "load_reference",
    "mark_file",
    "mark_files",
    "marking_for",
    "refuse_irregular",
]

#: Seconds one answers file may take to mark (``tutgen check --file-timeout``).
DEFAULT_FILE_TIMEOUT = 120.0


@dataclass(frozen=True)
class FileResult:
    """The marks of one answers file, or the errors that kept it from being marked."""

    path: str
    student: str | None
    items: tuple[ItemResult, ...]
    errors: tuple[str, ...] = ()  # "file:line:col: error: ..." when the file is invalid
    limit: str = ""  # why the file could not be marked to the end (time or memory), if it could not
    internal: bool = False  # the file tripped a bug in tutgen (the error says which)

    @property
    def status(self) -> str:
        """``pass`` (every item correct), ``fail`` (an item not correct), ``time_limit`` (the file ran
        out of time or memory), ``invalid`` (the file could not be read) or ``error`` (a bug)."""
        if self.internal:
            return "error"
        if self.errors:
            return "invalid"
        if self.limit:
            return "time_limit"
        return "pass" if all(i.status is Status.CORRECT for i in self.items) else "fail"

    def count(self, status: Status) -> int:
        return sum(1 for i in self.items if i.status is status)


#: Exit status of each file status; a run exits with the worst of its files'.
_EXIT_OF = {"pass": EXIT_OK, "fail": EXIT_CHECK_FAILED, "time_limit": EXIT_CHECK_FAILED}
_EXIT_OF |= {"invalid": EXIT_INVALID_SPEC, "error": EXIT_INTERNAL}


@dataclass(frozen=True)
class CheckRun:
    """One `tutgen check`: a spec and the marks of every answers file, in the order given."""

    spec: str
    title: str
    files: tuple[FileResult, ...]
    marking: str = "key"  # where the marked items were stated: key, spec, derived (not stated), answered
    asked: tuple[str, ...] = ()  # the items marked in every file, when the run has a list of them

    @property
    def marking_note(self) -> str:
        """A line for the reports when no marking stated the items graded (empty otherwise): the
        grade is then of items derived by a rule, and an instructor must not take it for theirs."""
        if self.marking == "derived":
            return (
                f"no marking key: {len(self.asked)} items graded, derived from the spec's ask "
                f"({', '.join(self.asked) or 'none'}); state them with --key or the spec's marking:"
            )
        if self.marking == "answered":
            return "no marking key: only the items each file answers are graded"
        return ""

    @property
    def exit_code(self) -> int:
        """The worst verdict of the files: 70 a bug, 3 an invalid file, 1 an answer not correct (or a
        file out of time), 0 every answer correct."""
        return max((_EXIT_OF[f.status] for f in self.files), default=EXIT_OK)

    @property
    def errors(self) -> list[str]:
        return [e for f in self.files for e in f.errors]


def refuse_irregular(paths: Sequence[str | Path]) -> None:
    """Raise UsageError for a path that exists but is not a regular file (a FIFO, a device, a
    directory); a missing file is left for the reader, which reports it as that file's error."""
    for path in paths:
        try:
            mode = os.stat(path).st_mode
        except OSError:
            continue
        if not stat.S_ISREG(mode):
            kind = "a directory" if stat.S_ISDIR(mode) else "a FIFO" if stat.S_ISFIFO(mode) else "not a regular file"
            raise UsageError(f"{path} is {kind}; give a YAML file")


def load_reference(
    spec: str | Path,
    *,
    key: str | Path | None = None,
    answer_timeout: float | None = DEFAULT_ANSWER_TIMEOUT,
    derive_timeout: float | None = None,
) -> Reference:
    """Load, validate and derive a spec (raises SpecErrors / DerivationError) as a :class:`Reference`,
    with the instructor's marking ``key`` (a file; its errors are SpecErrors too). The derivation has
    ``derive_timeout`` seconds (default: ``tutgen solve``'s, :data:`tutgen.limits.DEFAULT_TIMEOUT`)."""
    from tutgen.check.compare import key_problems, reference_from
    from tutgen.check.key import read_key
    from tutgen.engine.pipeline import derive_with_deadline
    from tutgen.limits import DEFAULT_TIMEOUT
    from tutgen.spec.validate import load_system

    marking_key = read_key(key) if key is not None else None
    system = load_system(spec)
    seconds = DEFAULT_TIMEOUT if derive_timeout is None else derive_timeout
    ref = reference_from(system, derive_with_deadline(system, "both", seconds), str(spec))
    ref = replace(ref, answer_timeout=answer_timeout, key=marking_for(ref, marking_key or system.marking))
    problems = key_problems(ref)
    if problems:
        raise SpecErrors(problems)
    return ref


def marking_for(ref: Reference, stated: Marking | None) -> Marking:
    """What ``tutgen check`` marks: the marking key (``--key``), else the spec's ``marking:``; the items
    it asks, else (no ``ask`` stated anywhere) those derived from the spec's ``ask``
    (:func:`tutgen.check.verdicts.derived_ask`), and then its ``source`` is ``derived``, so that the
    reports say no marking was stated."""
    marking = stated if stated is not None else Marking(ref.spec, source="derived")
    if marking.ask is None:
        where = Location(ref.spec)
        ask = tuple((k, (k,), where) for k in ref.asked)
        marking = replace(marking, ask=ask, source="derived")
    return marking


def mark_file(ref: Reference, path: str | Path) -> FileResult:
    """Read one answers file and mark it, in this process; a file that cannot be read gives a result
    with its errors."""
    from tutgen.check.answers import read_answers
    from tutgen.check.compare import check_sheet

    try:
        sheet = read_answers(path)
        items = check_sheet(sheet, ref)
    except SpecErrors as exc:
        return FileResult(str(path), None, (), tuple(str(e) for e in exc.errors))
    return FileResult(sheet.path, sheet.student, tuple(items))


# ---------------------------------------------------------------------------------------------
# One child process per file
# ---------------------------------------------------------------------------------------------


def _die_with_parent() -> None:
    """Ask Linux to kill this process when its parent dies (a no-op elsewhere)."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):  # pragma: no cover - not Linux
        pass


def _child(ref: Reference, path: str, conn: Connection) -> None:
    """Mark one file in this (forked) child and send the result; never raise."""
    from tutgen.check.limits import cap_memory

    _die_with_parent()
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent decides; it kills its children on ^C
    cap_memory()
    try:
        result = mark_file(ref, path)
    except MemoryError:
        result = FileResult(
            path, None, unmarked_items(ref, path, "could not be checked (memory limit)"), limit="memory limit"
        )
    except BaseException as exc:  # a bug: this file's verdict, not the end of the class run
        message = f"{path}: internal error: {type(exc).__name__}: {exc} (a bug in tutgen; please report it)"
        result = FileResult(path, None, (), (message,), internal=True)
    conn.send(result)
    conn.close()


@dataclass
class _Running:
    index: int
    path: str
    process: Any  # multiprocessing.Process
    conn: Connection
    deadline: float


def _start(ref: Reference, index: int, path: str, seconds: float | None) -> _Running:
    ctx = multiprocessing.get_context("fork")  # shares the derivation; nothing is pickled on the way in
    reader, writer = ctx.Pipe(duplex=False)
    process = ctx.Process(target=_child, args=(ref, path, writer), daemon=True)
    process.start()
    writer.close()
    deadline = time.monotonic() + seconds if seconds else float("inf")
    return _Running(index, path, process, reader, deadline)


def _finish(ref: Reference, run: _Running, seconds: float | None) -> FileResult:
    """The result a child sent, or its verdict when it sent none (killed, crashed, out of memory)."""
    result: FileResult | None = None
    if run.conn.poll(0):
        try:
            result = run.conn.recv()
        except (EOFError, OSError):
            result = None
    _stop(run)
    if result is not None:
        return result
    if time.monotonic() >= run.deadline:
        why = f"time limit: {seconds:g} s per file"
    else:
        code = run.process.exitcode
        why = "memory limit" if code in (-signal.SIGKILL, 1) else f"the marking process ended with status {code}"
    return FileResult(run.path, None, unmarked_items(ref, run.path, f"could not be checked ({why})"), limit=why)


def _stop(run: _Running) -> None:
    run.conn.close()
    if run.process.is_alive():
        run.process.kill()
    run.process.join()


def mark_files(
    ref: Reference,
    paths: Sequence[str | Path],
    *,
    jobs: int | None = None,
    on_done: Callable[[], None] | None = None,
    file_timeout: float | None = DEFAULT_FILE_TIMEOUT,
) -> list[FileResult]:
    """Mark every answers file, each in a child process, ``jobs`` at a time (default: one per core),
    and return the results in the order of ``paths`` whatever order the children finish in. A child
    past ``file_timeout`` seconds is killed and its file marked "time limit". ``on_done`` is called
    once per finished file (for a progress bar)."""
    workers = max(1, min(jobs or os.cpu_count() or 1, len(paths)))
    pending = [(i, str(p)) for i, p in enumerate(paths)]
    pending.reverse()
    results: list[FileResult | None] = [None] * len(paths)
    running: list[_Running] = []
    try:
        while pending or running:
            while pending and len(running) < workers:
                index, path = pending.pop()
                running.append(_start(ref, index, path, file_timeout))
            now = time.monotonic()
            wait_for = max(0.0, min(r.deadline for r in running) - now)
            ready = wait([r.conn for r in running], timeout=min(wait_for, 3600.0))
            now = time.monotonic()
            for r in list(running):
                if r.conn in ready or now >= r.deadline:
                    running.remove(r)
                    results[r.index] = _finish(ref, r, file_timeout)
                    if on_done:
                        on_done()
    finally:
        for r in running:  # interrupted (^C, SIGTERM as an exception): no child outlives the run
            _stop(r)
    assert all(r is not None for r in results)
    return [r for r in results if r is not None]


def check(
    spec: str | Path,
    answers: Sequence[str | Path],
    *,
    jobs: int | None = None,
    on_done: Callable[[], None] | None = None,
    key: str | Path | None = None,
    answer_timeout: float | None = DEFAULT_ANSWER_TIMEOUT,
    file_timeout: float | None = DEFAULT_FILE_TIMEOUT,
) -> CheckRun:
    """Derive ``spec`` once and mark every answers file against it (non-regular files refused first)."""
    refuse_irregular([spec, *answers, *([key] if key is not None else [])])
    ref = load_reference(spec, key=key, answer_timeout=answer_timeout)
    files = mark_files(ref, answers, jobs=jobs, on_done=on_done, file_timeout=file_timeout)
    asked = tuple(k for k, _, _ in ref.key.ask or ())
    return CheckRun(ref.spec, ref.title, tuple(files), ref.key.source, asked)
