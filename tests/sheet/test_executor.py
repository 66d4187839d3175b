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


def _pull_all(executor: ProcessExecutor, fn: object, shared: float, jobs: list[int]) -> None:
    """``executor.pull`` over ``jobs``, in order (the jobs of ``map``)."""
    todo = list(jobs)
    executor.pull(fn, shared, lambda job, result: todo.pop(0) if todo else None)  # type: ignore[arg-type]


@pytest.mark.parametrize("how", ["map", "pull"])
def test_a_stopped_pool_joins_its_manager_thread_and_leaves_the_exit_hook_nothing(how: str) -> None:
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
            if how == "map":
                ProcessExecutor(2).map(_slow, 30.0, list(range(4)))
            else:
                _pull_all(ProcessExecutor(2), _slow, 30.0, list(range(4)))
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    added = set(cfp._threads_wakeups) - before
    assert not added, f"manager threads left for the exit hook: {added}"
    assert not [t for t in threading.enumerate() if "ExecutorManager" in type(t).__name__ and t.is_alive()]


def _square(shared: int, job: int) -> tuple[int, int]:
    if job == shared:
        raise ValueError(f"job {job} failed")
    return os.getpid(), job * job


def test_pull_hands_each_worker_its_next_job_as_it_finishes() -> None:
    """``pull`` asks for one job per worker, then for one more each time a job finishes, told which job
    finished and its result; it stops when there is nothing more to give, and each job runs once."""
    asked: list[tuple[int | None, tuple[int, int] | None]] = []
    todo = list(range(12))

    def next_job(job: int | None, result: tuple[int, int] | None) -> int | None:
        asked.append((job, result))
        return todo.pop(0) if todo else None

    ProcessExecutor(2).pull(_square, -1, next_job)
    assert asked[:2] == [(None, None), (None, None)]  # one job for each of the two workers
    finished = {job: result for job, result in asked[2:]}
    assert sorted(finished) == list(range(12))  # each job once, each told when it finished
    assert all(result is not None and result[1] == job * job for job, result in finished.items())
    assert len({result[0] for result in finished.values() if result}) == 2  # by two processes
    assert os.getpid() not in {result[0] for result in finished.values() if result}


def test_pull_with_one_job_at_a_time_runs_here_and_a_failure_stops_it() -> None:
    seen: list[int] = []
    started: list[int] = []

    def one_at_a_time(job: int | None, result: tuple[int, int] | None) -> int | None:
        if job is None:  # asked once for each worker: a job for the first only
            started.append(0)
            return 0 if len(started) == 1 else None
        assert result is not None
        seen.append(result[0])
        return job + 1 if job < 3 else None

    ProcessExecutor(2).pull(_square, -1, one_at_a_time)  # the second worker gets nothing: none forked
    assert seen == [os.getpid()] * 4
    with pytest.raises(ValueError, match="job 5 failed"):
        ProcessExecutor(2).pull(_square, 5, lambda job, result: (job or 0) + 1 if (job or 0) < 9 else None)
