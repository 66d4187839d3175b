"""A time limit for one derivation, and the name of the step it had reached.

sympy can take a very long time on a large spec (a long spatial chain); rather than hang, tutgen stops
and says where it was. :func:`deadline` arms a one-shot ``SIGALRM`` timer; :func:`checkpoint` records
the step the engine is at, so the :class:`~tutgen.errors.DerivationTimeout` names it. Signals only
reach the main thread, so off it (and with no limit) :func:`deadline` does nothing.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from tutgen.errors import DerivationTimeout

__all__ = ["DEFAULT_TIMEOUT", "checkpoint", "current_step", "deadline"]

#: Seconds a derivation may take unless ``--timeout`` says otherwise.
DEFAULT_TIMEOUT: float = 120

_state: dict[str, Any] = {"step": "start", "armed": False, "expired": None}


def checkpoint(step: str) -> None:
    """Record that the derivation has reached ``step`` (e.g. "mass matrix"); cheap, always safe.

    Once the deadline has passed this raises again, in case library code swallowed the first raise.
    """
    expired = _state["expired"]
    if expired is not None:
        raise DerivationTimeout(expired, current_step())
    _state["step"] = step


def current_step() -> str:
    """The step last recorded by :func:`checkpoint`."""
    return str(_state["step"])


@contextmanager
def deadline(seconds: float | None) -> Iterator[None]:
    """Raise :class:`~tutgen.errors.DerivationTimeout` if the block runs longer than ``seconds``.

    A no-op for ``None`` or ``0``, off the main thread, where ``SIGALRM`` does not exist, and inside
    another active deadline (the outer one stays in charge). The timer and the previous handler are
    restored on the way out, however the block ends.
    """
    usable = (
        seconds
        and seconds > 0
        and hasattr(signal, "setitimer")
        and threading.current_thread() is threading.main_thread()
        and not _state["armed"]
    )
    if not usable:
        yield
        return
    assert seconds is not None

    def expire(signum: int, frame: object) -> None:
        # sympy has a few ``except Exception`` blocks: keep firing until the block is really left
        _state["expired"] = seconds
        signal.setitimer(signal.ITIMER_REAL, 0.25)
        raise DerivationTimeout(seconds, current_step())

    previous = signal.signal(signal.SIGALRM, expire)
    _state["armed"] = True
    _state["step"] = "start"
    signal.setitimer(signal.ITIMER_REAL, float(seconds))
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
        _state["armed"] = False
        _state["expired"] = None
