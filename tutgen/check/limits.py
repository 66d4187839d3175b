"""Bounds on the work one answer, and one answers file, may make `tutgen check` do.

Two layers, because neither is enough alone:

- :func:`answer_deadline` stops the marking of one entry after ``--timeout`` seconds with a one-shot
  ``SIGALRM``; the entry is marked "could not be checked (time limit)" and marking goes on. A signal
  is only seen between Python bytecodes, so it cannot stop one long C-level operation (a big-integer
  power, say).
- so every answers file is also marked in a child process (:mod:`tutgen.check.run`) that is killed
  after ``--file-timeout`` seconds and whose address space is capped (:func:`cap_memory`): a hostile
  expression can end its own file's marking, never the class run.

The spec's derivation is bounded as for ``tutgen solve`` (:func:`tutgen.engine.pipeline.derive_with_deadline`).
"""

from __future__ import annotations

import resource
from collections.abc import Iterator
from contextlib import contextmanager

from tutgen.limits import alarm

__all__ = ["MEMORY_HEADROOM", "AnswerTimeLimit", "answer_deadline", "cap_memory"]

#: Bytes of address space a marking process may use on top of what it had when it started.
MEMORY_HEADROOM = 2 * 1024**3


class AnswerTimeLimit(BaseException):
    """One entry ran past its time limit. A BaseException, so that library code's ``except Exception``
    blocks (sympy has a few) do not swallow it."""

    def __init__(self, seconds: float) -> None:
        super().__init__(seconds)
        self.seconds = seconds


_state = {"armed": False}


@contextmanager
def answer_deadline(seconds: float | None) -> Iterator[None]:
    """Raise :class:`AnswerTimeLimit` if the block runs longer than ``seconds``.

    A no-op for None or 0, off the main thread and inside another active answer deadline. Once
    expired, the alarm fires again every 0.1 s until the block is left, in case a first raise was
    swallowed. The previous handler and timer are restored however the block ends
    (:func:`tutgen.limits.alarm`).
    """
    with alarm(seconds, lambda: AnswerTimeLimit(seconds or 0), 0.1, _state):
        yield


def _address_space() -> int:
    """This process's current virtual memory size in bytes (0 where /proc is not there)."""
    try:
        with open("/proc/self/statm", encoding="ascii") as fh:
            pages = int(fh.read().split()[0])
    except (OSError, ValueError, IndexError):
        return 0
    return pages * resource.getpagesize()


def cap_memory(headroom: int = MEMORY_HEADROOM) -> None:
    """Limit this process's address space to its current size plus ``headroom`` (``RLIMIT_AS``), so
    that an exploding expansion ends in MemoryError rather than in the machine swapping."""
    current = _address_space()
    if not current:
        return
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    limit = current + headroom
    if hard != resource.RLIM_INFINITY:
        limit = min(limit, hard)
    if soft == resource.RLIM_INFINITY or soft > limit:
        resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
