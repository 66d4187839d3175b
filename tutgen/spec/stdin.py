"""Standard input as a spec file: the path ``-``, as in most command-line tools (``tutgen solve -``).

:func:`tutgen.spec.loader.load_yaml_file` reads the path ``-`` from here, so every reader (specs, sheets,
answers files, marking keys) takes it, and names it ``<stdin>`` in its errors. A file that is really
called ``-`` is given with its directory (``$PWD/-``; pathlib reads ``./-`` as ``-``).

Standard input is read once per run: a spec validated and then derived, or an answers file read in a
forked marking process (whose own stdin multiprocessing points at /dev/null), comes from the first
read's copy. :func:`forget_stdin` starts a new run (the CLI calls it for each command).
"""

from __future__ import annotations

import sys

from tutgen.errors import Location, SpecError, SpecErrors

__all__ = ["STDIN", "STDIN_NAME", "forget_stdin", "read_stdin"]

#: The path that means standard input.
STDIN: str = "-"
#: How errors of a document read from standard input name it: ``<stdin>:line:col``.
STDIN_NAME: str = "<stdin>"
_stdin_read: list[bytes] = []


def read_stdin(limit: int) -> bytes:
    """Standard input's first ``limit`` bytes (the loader asks for one more than it accepts, to tell a
    document that is too big), read on the first call and the same bytes on every later one until
    :func:`forget_stdin`; SpecErrors at ``<stdin>`` if it cannot be read."""
    if _stdin_read:
        return _stdin_read[0]
    try:
        data = sys.stdin.buffer.read(limit)
    except (OSError, AttributeError, ValueError) as err:  # closed, or not a byte stream
        raise SpecErrors([SpecError(Location(STDIN_NAME), f"cannot read standard input: {err}")]) from None
    _stdin_read[:] = [data]
    return data


def forget_stdin() -> None:
    """Read standard input afresh on the next :func:`read_stdin` (a new command in the same process)."""
    _stdin_read.clear()
