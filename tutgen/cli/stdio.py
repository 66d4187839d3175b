"""``-`` as in most command-line tools: standard input for an input file, standard output for ``-o -``.

An input named ``-`` is read from standard input by the spec loader (:data:`tutgen.spec.loader.STDIN`),
so every reader (specs, sheets, answers files, marking keys) takes it, and its errors are located at
``<stdin>:line:col``. Standard input can be read once: at most one input of a run may be ``-``. A file
that is really called ``-`` is named ``./-``.

``-o -`` writes the one file a command makes to standard output. Where a command makes several files
(a sheet's directory, a simulation's CSV, JSON and plots) or picks the format by the file's suffix
(``tutgen figure``), ``-o -`` is a usage error that says so, rather than a file called ``-``.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable
from pathlib import Path

from tutgen.errors import UsageError

#: The name that means standard input (an input) or standard output (``-o``).
STDIO = "-"


def is_stdio(path: str | Path | None) -> bool:
    """Whether ``path`` is ``-`` (``./-`` is a file of that name)."""
    return path is not None and str(path) == STDIO


def refuse_second_stdin(paths: Iterable[str | Path | None]) -> None:
    """A usage error when more than one input is ``-``: standard input can be read only once."""
    if sum(is_stdio(p) for p in paths) > 1:
        raise UsageError("standard input can be read only once: give '-' for at most one input")


def refuse_stdout(option: str, output: str | Path | None, why: str, instead: str = "a file") -> None:
    """A usage error for ``OPTION -`` where the output cannot be standard output (``why``)."""
    if is_stdio(output):
        raise UsageError(f"{option} -: {why}; give {instead} instead of '-'")


def refuse_unnamed(spec: str | Path, why: str) -> None:
    """A usage error for a spec read from standard input where its file name is needed (``why``)."""
    if is_stdio(spec):
        raise UsageError(f"a spec read from standard input ('-') has no file name, and {why}; give its file")


def write_bytes_to_stdout(data: bytes, what: str) -> None:
    """Binary output (a PDF) on standard output, never onto a terminal."""
    if sys.stdout.isatty():
        raise UsageError(f"-o -: refusing to write {what} to a terminal; redirect standard output or give a file")
    sys.stdout.flush()
    sys.stdout.buffer.write(data)
    sys.stdout.buffer.flush()
