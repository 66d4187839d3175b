"""The process pool stopped mid-run leaves nothing for Python's exit hook to trip over."""

from __future__ import annotations

import concurrent.futures.process as cfp
import os
import signal
import threading
import time

import pytest

from tutgen.sheet.executor import ProcessExecutor


def _slow(shared: float, job: int) -> int:
    time.sleep(shared)
    return job


def test_a_stopped_pool_joins_its_manager_thread_and_leaves_the_exit_hook_nothing() -> None:
    """CPython 3.11's exit hook writes to the wake-up pipe of every manager thread it knows; one that
    closes its pipe at that moment prints "Bad file descriptor" after "terminated" (gh-109917). A pool
    stopped by an exception must have joined its manager and dropped it from the hook's table."""
    before = set(cfp._threads_wakeups)

    # Ctrl-C as the terminal sends it (a handler set here: a background shell starts tests with SIGINT
    # ignored)
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(1.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            ProcessExecutor(2).map(_slow, 30.0, list(range(4)))
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    added = set(cfp._threads_wakeups) - before
    assert not added, f"manager threads left for the exit hook: {added}"
    assert not [t for t in threading.enumerate() if "ExecutorManager" in type(t).__name__ and t.is_alive()]
