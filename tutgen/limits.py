"""A time limit for one derivation, and the name of the step it had reached.

sympy can take a very long time on a large spec (a long spatial chain); rather than hang, tutgen stops
and says where it was. :func:`deadline` arms a one-shot ``SIGALRM`` timer; :func:`checkpoint` records
the step the engine is at, so the :class:`~tutgen.errors.DerivationTimeout` names it. Signals only
reach the main thread, so off it (and with no limit) :func:`deadline` does nothing.

One deadline covers a whole run (``tutgen solve --timeout``: load, derive and render; the budget is
shared, so what the derivation used is gone for rendering): :func:`stage` names the part of the run
the timeout is charged to, :func:`remaining` is what is left (a LaTeX compile gets no more than that),
and :func:`shielded` holds off the alarm, SIGINT and SIGTERM while cleanup that must finish runs
(killing a process group, removing a temporary directory, renaming an output into place).
"""

from __future__ import annotations

import os
import signal
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

from tutgen.errors import DerivationTimeout

__all__ = [
    "DEFAULT_TIMEOUT",
    "alarm",
    "checkpoint",
    "current_step",
    "deadline",
    "inherited_deadline",
    "out_of_time",
    "remaining",
    "shielded",
    "stage",
]

#: Seconds a derivation may take unless ``--timeout`` says otherwise.
DEFAULT_TIMEOUT: float = 120

_state: dict[str, Any] = {
    "step": "start",
    "stage": "derivation",
    "armed": False,
    "expired": None,
    "ends": None,
    "shield": 0,  # how many shielded() blocks are running (the alarm waits for them)
}

#: The signals :func:`shielded` holds off.
_SHIELDED = {signal.SIGALRM, signal.SIGINT, signal.SIGTERM} if hasattr(signal, "SIGALRM") else set()


def checkpoint(step: str) -> None:
    """Record that the derivation has reached ``step`` (e.g. "mass matrix"); cheap, always safe.

    Once the deadline has passed this raises again, in case library code swallowed the first raise.
    """
    expired = _state["expired"]
    if expired is not None:
        raise DerivationTimeout(expired, current_step(), _state["stage"])
    _state["step"] = step


def stage(name: str, step: str = "start") -> None:
    """Charge what follows to the part of the run ``name`` ("derivation", "rendering", "loading the
    specs"); ``step`` says where in it (e.g. the file being rendered). Like :func:`checkpoint`, this
    raises again once the deadline has passed."""
    checkpoint(step)
    _state["stage"] = name


def remaining() -> float | None:
    """Seconds left before the active deadline (at least a little above 0), None when there is none."""
    ends = _state["ends"]
    if ends is None:
        return None
    return max(0.01, ends - time.monotonic())


def out_of_time(stage_name: str, step: str) -> DerivationTimeout:
    """The error of a run whose deadline has passed, charged to ``stage_name`` at ``step`` (for work
    that watches :func:`remaining` itself, such as a LaTeX compile, rather than wait for the alarm)."""
    return DerivationTimeout(_state.get("seconds") or 0, step, stage_name)


@contextmanager
def shielded() -> Iterator[None]:
    """Hold off SIGALRM, SIGINT and SIGTERM while the block runs (cleanup that must not be cut short);
    a signal that arrives meanwhile is delivered when the block ends. Off the main thread, or where
    signal masks do not exist, the block just runs."""
    usable = hasattr(signal, "pthread_sigmask") and threading.current_thread() is threading.main_thread()
    if not usable:
        yield
        return
    # the mask holds the signals off this thread; in a process with other threads (a worker pool's, a
    # test runner's) another thread may take SIGALRM and Python still runs the handler here, so the
    # deadline's handler also looks at this count and waits (tutgen/limits.py, deadline)
    _state["shield"] = int(_state.get("shield") or 0) + 1
    old = signal.pthread_sigmask(signal.SIG_BLOCK, _SHIELDED)
    try:
        yield
    finally:
        _state["shield"] = int(_state.get("shield") or 1) - 1
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def current_step() -> str:
    """The step last recorded by :func:`checkpoint`."""
    return str(_state["step"])


def usable(seconds: float | None, armed: dict[str, Any]) -> bool:
    """Whether :func:`alarm` can arm: a positive limit, ``SIGALRM``, the main thread, none armed yet."""
    return bool(
        seconds
        and seconds > 0
        and hasattr(signal, "setitimer")
        and threading.current_thread() is threading.main_thread()
        and not armed["armed"]
    )


@contextmanager
def alarm(
    seconds: float | None, expired: Callable[[], BaseException], again: float, armed: dict[str, Any]
) -> Iterator[None]:
    """The one-shot ``SIGALRM`` under both time limits (:func:`deadline` here, the answer deadline of
    tutgen.check.limits): raise ``expired()`` if the block runs longer than ``seconds``, and then again
    every ``again`` seconds until the block is left (sympy has a few ``except Exception`` blocks).

    A no-op for ``None`` or ``0``, off the main thread, where ``SIGALRM`` does not exist, and while
    ``armed["armed"]`` says one of its kind is already running (the outer one stays in charge). While a
    :func:`shielded` cleanup runs the alarm waits for it. The timer and the previous handler are
    restored however the block ends."""
    if not usable(seconds, armed):
        yield
        return
    assert seconds is not None

    def expire(signum: int, frame: object) -> None:
        if _state.get("shield"):  # a cleanup that must not be cut short: come back when it is done
            signal.setitimer(signal.ITIMER_REAL, 0.05)
            return
        signal.setitimer(signal.ITIMER_REAL, again)
        raise expired()

    previous = signal.signal(signal.SIGALRM, expire)
    armed["armed"] = True
    signal.setitimer(signal.ITIMER_REAL, float(seconds))
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
        armed["armed"] = False


@contextmanager
def deadline(seconds: float | None) -> Iterator[None]:
    """Raise :class:`~tutgen.errors.DerivationTimeout` if the block runs longer than ``seconds``, naming
    the step and stage reached (:func:`alarm`: a no-op without a limit, off the main thread, and inside
    another active deadline)."""
    if not usable(seconds, _state):
        yield
        return

    def expired() -> BaseException:
        _state["expired"] = seconds
        return DerivationTimeout(seconds, current_step(), _state["stage"])

    assert seconds is not None
    _state["step"] = "start"
    _state["stage"] = "derivation"
    _state["ends"] = time.monotonic() + float(seconds)
    _state["seconds"] = seconds
    _state["owner"] = os.getpid()  # a forked worker has the state, not the alarm (inherited_deadline)
    try:
        with alarm(seconds, expired, 0.25, _state):
            yield
    finally:
        _state["expired"] = None
        _state["ends"] = None


@contextmanager
def inherited_deadline(margin: float = 0.25) -> Iterator[None]:
    """In a worker forked inside the parent's :func:`deadline`: the time the parent has left, less
    ``margin``, as this process's own deadline, so that a timeout here is raised by the work itself,
    naming its stage and step (a sheet's problem being derived), and reaches the parent before the
    parent's own alarm, which knows neither. The message states the run's whole budget. A no-op
    without an inherited deadline, in the process whose deadline it is (an executor that runs a
    single job in the parent), and where :func:`alarm` cannot arm."""
    ends, total = _state["ends"], _state.get("seconds")
    if ends is None or not total or _state.get("owner") == os.getpid():
        yield
        return

    def expired() -> BaseException:
        _state["expired"] = total
        return DerivationTimeout(total, current_step(), _state["stage"])

    _state["armed"] = False  # the parent's alarm, inherited as a flag: it does not ring in this process
    _state["stage"] = "derivation"
    try:
        with alarm(max(ends - time.monotonic() - margin, 0.01), expired, 0.25, _state):
            yield
    finally:
        _state["expired"] = None


def forget_shields() -> None:
    """In a process forked inside :func:`shielded` (a worker pool's child): that block never ends here,
    so the alarm must not wait for it."""
    _state["shield"] = 0
