"""Where the variants of a sheet are built: one small interface, three places.

An executor maps a function over jobs, with one shared argument (the sheet's derivations, shipped to
each worker once), and returns the results **in the order of the jobs**, whatever order they finish
in, so the output never depends on the number of workers:

- :class:`SerialExecutor`: in this process (``--workers 1``);
- :class:`ProcessExecutor`: a ``concurrent.futures.ProcessPoolExecutor`` (``--workers N``), which can
  also take its jobs one at a time as its workers become free (:meth:`ProcessExecutor.pull`);
- :class:`DaskExecutor`: a Dask distributed scheduler (``--scheduler ADDRESS``; the optional extra
  ``tutgen[dask]``). Dask is imported only when this one is made.

Workers end with the parent: a pool's workers ignore SIGINT (Ctrl-C reaches the whole terminal
group; the parent decides) and, when the parent stops for any reason (an error, the deadline,
Ctrl-C, SIGTERM), it terminates them (SIGTERM, then SIGKILL after a grace period) before it goes on.
A worker that gets SIGTERM while it builds runs its cleanup first (a LaTeX compile's process group,
its temporary directory), then exits; an idle one exits at once. On a Dask cluster the workers are not
this process's to kill: when the parent stops, it cancels the sheet's tasks on the scheduler (the queued
ones never start; a running one ends on its own and its result is dropped) and closes its client.
"""

from __future__ import annotations

import contextlib
import os
import re
import signal
import threading
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import Future, ProcessPoolExecutor, as_completed
from typing import Any, Protocol, TypeVar

from tutgen.errors import EXIT_TERMINATED, Terminated, UsageError

#: The addresses ``--scheduler`` takes: ``[tcp|tls|ws|wss|ucx]://host:port`` or ``host:port``, and a
#: scheduler in this process (``inproc://host/pid/n``, what a ``LocalCluster(processes=False)`` gives).
SCHEDULER_ADDRESS = re.compile(
    r"(?:(?:tcp|tls|ws|wss|ucx)://)?(?:\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9._-]+):\d{1,5}"
    r"|inproc://[A-Za-z0-9._:-]+(?:/[0-9]+)*"
)
#: Seconds a terminated worker has to clean up before it is killed.
WORKER_GRACE = 5.0

S = TypeVar("S")
J = TypeVar("J")
R = TypeVar("R")


class Executor(Protocol):
    """Runs ``fn(shared, job)`` for every job; results in job order; ``on_done()`` once per finished job."""

    def map(
        self, fn: Callable[[Any, Any], Any], shared: Any, jobs: Sequence[Any], on_done: Callable[[], None] | None = None
    ) -> list[Any]: ...

    @property
    def workers(self) -> int: ...

    #: whether the jobs run on this machine (and can write files where the caller reads them)
    local: bool


class SerialExecutor:
    workers = 1
    local = True  # its jobs run on this machine: they can write the output's files themselves

    def map(
        self, fn: Callable[[S, J], R], shared: S, jobs: Sequence[J], on_done: Callable[[], None] | None = None
    ) -> list[R]:
        out = []
        for job in jobs:
            out.append(fn(shared, job))
            if on_done:
                on_done()
        return out


_worker_state: dict[str, Any] = {"busy": False}
_SHIELD = {signal.SIGINT, signal.SIGTERM, *([signal.SIGALRM] if hasattr(signal, "SIGALRM") else [])}


def _init_worker(fn: Callable[[Any, Any], Any], shared: Any) -> None:
    _worker_state["fn"] = fn
    _worker_state["shared"] = shared
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, _worker_terminated)
    if hasattr(signal, "SIGALRM"):  # the parent's deadline handler came with the fork; the parent keeps time
        signal.signal(signal.SIGALRM, signal.SIG_DFL)
    if hasattr(signal, "pthread_sigmask"):
        # forked inside the parent's shielded() block (ProcessExecutor.map): this process's own copy of
        # that block never ends, so end it here; a signal sent meanwhile arrives now
        import tutgen.limits

        tutgen.limits.forget_shields()
        signal.pthread_sigmask(signal.SIG_UNBLOCK, _SHIELD)


def _worker_terminated(signum: int, frame: object) -> None:
    if _worker_state["busy"]:
        raise Terminated()  # unwinds through the job's cleanup; _run_in_worker then exits
    os._exit(EXIT_TERMINATED)


def _run_in_worker(job: Any) -> Any:
    _worker_state["busy"] = True
    try:
        return _worker_state["fn"](_worker_state["shared"], job)
    except Terminated:
        os._exit(EXIT_TERMINATED)
    finally:
        _worker_state["busy"] = False


def _stop_workers(pool: ProcessPoolExecutor) -> None:
    """Terminate every worker of ``pool`` and wait for each (SIGKILL after :data:`WORKER_GRACE`)."""
    procs = list((getattr(pool, "_processes", None) or {}).values())
    manager = getattr(pool, "_executor_manager_thread", None)  # shutdown() forgets it
    for proc in procs:
        if proc.is_alive():
            proc.terminate()
    for proc in procs:
        proc.join(WORKER_GRACE)
        if proc.is_alive():
            proc.kill()
            proc.join(1.0)
    pool.shutdown(wait=False, cancel_futures=True)
    if manager is not None:
        _join_manager(manager)


def _join_manager(thread: threading.Thread) -> None:
    """Wait for the pool's manager thread to end (it does, once its workers are gone) and forget it.

    Python 3.11's exit hook (``concurrent.futures.process._python_exit``) wakes every manager thread
    it knows by writing to a pipe that the thread closes as it ends; a thread ending at that moment
    makes the write fail with "Bad file descriptor" and a traceback on stderr after "terminated"
    (CPython gh-109917, fixed in 3.12). A manager joined here has closed its pipe, and one dropped
    from the hook's table is never written to."""
    import concurrent.futures.process as cfp

    thread.join(WORKER_GRACE + 2.0)
    table = getattr(cfp, "_threads_wakeups", None)
    if table is not None and not thread.is_alive():
        table.pop(thread, None)


def _fork_context() -> Any:
    """Fork where it is safe (Linux): the workers inherit the shared argument (the derivations, the built
    units), the imported modules and the compiled templates instead of receiving and rebuilding them;
    elsewhere the platform's default."""
    import multiprocessing
    import sys

    return multiprocessing.get_context("fork") if sys.platform.startswith("linux") else None


class ProcessExecutor:
    """A pool of ``workers`` processes (default: one per core); the shared argument is handed to each
    worker once, when it starts."""

    local = True

    def __init__(self, workers: int | None = None) -> None:
        self._workers = workers or os.cpu_count() or 1

    @property
    def workers(self) -> int:
        return self._workers

    def map(
        self, fn: Callable[[S, J], R], shared: S, jobs: Sequence[J], on_done: Callable[[], None] | None = None
    ) -> list[R]:
        workers = min(self._workers, len(jobs))
        if workers <= 1:
            return SerialExecutor().map(fn, shared, jobs, on_done)
        with _pool(workers, fn, shared, jobs[0]) as (pool, first):
            futures = [first, *(pool.submit(_run_in_worker, job) for job in jobs[1:])]
            for _ in as_completed(futures):
                if on_done:
                    on_done()
            return [f.result() for f in futures]

    def pull(self, fn: Callable[[S, J], R], shared: S, next_job: Callable[[J | None, R | None], J | None]) -> None:
        """Run ``fn(shared, job)`` for every job ``next_job`` gives, one at a time per worker: first
        ``next_job(None, None)`` once for each worker, then, each time a worker finishes a job,
        ``next_job(job, result)`` for its next one (None: nothing more for it). Unlike :meth:`map`, the jobs
        are not known in advance: each is chosen when a worker is free for it, knowing how the finished
        ones went (the one finished is the free worker's own last job: one job is in flight per worker)."""
        from concurrent.futures import FIRST_COMPLETED, wait

        first: list[J] = []
        while len(first) < self._workers:
            job = next_job(None, None)
            if job is None:
                break
            first.append(job)
        if len(first) <= 1:  # at most one job at a time: in this process
            job = first[0] if first else None
            while job is not None:
                job = next_job(job, fn(shared, job))
            return
        with _pool(len(first), fn, shared, first[0]) as (pool, submitted):
            running = {submitted: first[0], **{pool.submit(_run_in_worker, job): job for job in first[1:]}}
            while running:
                finished, _ = wait(running, return_when=FIRST_COMPLETED)
                for future in finished:
                    job = running.pop(future)
                    following = next_job(job, future.result())
                    if following is not None:
                        running[pool.submit(_run_in_worker, following)] = following


@contextlib.contextmanager
def _pool(
    workers: int, fn: Callable[[Any, Any], Any], shared: Any, first: Any
) -> Iterator[tuple[ProcessPoolExecutor, Future[Any]]]:
    """A pool of ``workers`` processes running ``fn(shared, job)``, with ``first`` submitted (for
    :meth:`ProcessExecutor.map` and :meth:`ProcessExecutor.pull`); shut down when the block ends, or, if it
    fails or is stopped, its workers terminated first (:func:`_stop_workers`)."""
    from tutgen.limits import shielded

    pool = ProcessPoolExecutor(
        max_workers=workers, mp_context=_fork_context(), initializer=_init_worker, initargs=(fn, shared)
    )
    try:
        # the first submit forks every worker (the fork start method); a signal then must wait until
        # the worker has its own handlers (_init_worker), or it runs the parent's in Python's at-fork
        # hooks and prints "Exception ignored in ..." with a traceback
        with shielded():
            submitted = pool.submit(_run_in_worker, first)
        yield pool, submitted
    except BaseException:
        with shielded():  # a second Ctrl-C or the alarm must not leave workers behind
            _stop_workers(pool)
        raise
    pool.shutdown(wait=True)


class DaskExecutor:
    """The same interface on a Dask distributed cluster: ``DaskExecutor("tcp://host:8786")`` or
    ``DaskExecutor(client=Client(...))``. The shared argument is scattered to every worker once."""

    local = False  # its workers may be on other machines: they send the files back

    def __init__(self, address: str | None = None, client: Any = None) -> None:
        try:
            from dask.distributed import Client
        except ImportError:
            raise UsageError("--scheduler needs Dask: pip install 'tutgen[dask]' (dask[distributed])") from None
        if client is None:
            assert address is not None
            check_scheduler_address(address)
            try:
                client = Client(address, timeout=30)
            except (OSError, TimeoutError, ValueError) as err:
                raise UsageError(f"--scheduler {address}: cannot reach the Dask scheduler ({err})") from None
            self._owned = True
        else:
            self._owned = False
        self.client = client

    @property
    def workers(self) -> int:
        return max(1, sum(w.get("nthreads", 1) for w in self.client.scheduler_info().get("workers", {}).values()))

    def map(
        self, fn: Callable[[S, J], R], shared: S, jobs: Sequence[J], on_done: Callable[[], None] | None = None
    ) -> list[R]:
        from dask.distributed import as_completed as dask_completed

        if not jobs:
            return []
        shared_future = self.client.scatter(shared, broadcast=True)
        futures = [self.client.submit(fn, shared_future, job, pure=False) for job in jobs]
        try:
            for _ in dask_completed(futures):
                if on_done:
                    on_done()
            return list(self.client.gather(futures))
        except BaseException:
            # stopped (an error, the deadline, Ctrl-C, SIGTERM): the remote workers drop the sheet's
            # queued tasks; a task already running ends on its own, and its result is discarded
            from tutgen.limits import shielded

            with shielded():
                self.client.cancel([*futures, shared_future], force=True)
                self.close()
            raise

    def close(self) -> None:
        if self._owned:
            self._owned = False  # closed once, whether by the caller or by a stopped map
            self.client.close()


def check_scheduler_address(address: str) -> None:
    """Refuse (UsageError) a ``--scheduler`` that is not a Dask scheduler's network address, such as
    ``file://…`` or a path, before anything is derived."""
    if not SCHEDULER_ADDRESS.fullmatch(address.strip()):
        from tutgen.safetext import terminal_text

        shown = terminal_text(address)[:80]
        raise UsageError(
            f"--scheduler {shown!r} is not a Dask scheduler address; expected tcp://HOST:PORT "
            "(or tls://, ws://, wss://, ucx://, HOST:PORT, inproc://)"
        )


def make_executor(
    workers: int | None = None, scheduler: str | None = None
) -> SerialExecutor | ProcessExecutor | DaskExecutor:
    """``--scheduler`` wins (Dask); else a process pool of ``workers`` (1: in this process)."""
    if scheduler:
        return DaskExecutor(scheduler)
    if workers == 1:
        return SerialExecutor()
    return ProcessExecutor(workers)
