"""Where the variants of a sheet are built: one small interface, three places.

An executor maps a function over jobs, with one shared argument (the sheet's derivations, shipped to
each worker once), and returns the results **in the order of the jobs**, whatever order they finish
in, so the output never depends on the number of workers:

- :class:`SerialExecutor`: in this process (``--workers 1``);
- :class:`ProcessExecutor`: a ``concurrent.futures.ProcessPoolExecutor`` (``--workers N``);
- :class:`DaskExecutor`: a Dask distributed scheduler (``--scheduler ADDRESS``; the optional extra
  ``tutgen[dask]``). Dask is imported only when this one is made.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from typing import Any, Protocol, TypeVar

from tutgen.errors import UsageError

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


class SerialExecutor:
    workers = 1

    def map(
        self, fn: Callable[[S, J], R], shared: S, jobs: Sequence[J], on_done: Callable[[], None] | None = None
    ) -> list[R]:
        out = []
        for job in jobs:
            out.append(fn(shared, job))
            if on_done:
                on_done()
        return out


_worker_state: dict[str, Any] = {}


def _init_worker(fn: Callable[[Any, Any], Any], shared: Any) -> None:
    _worker_state["fn"] = fn
    _worker_state["shared"] = shared


def _run_in_worker(job: Any) -> Any:
    return _worker_state["fn"](_worker_state["shared"], job)


class ProcessExecutor:
    """A pool of ``workers`` processes (default: one per core); the shared argument is handed to each
    worker once, when it starts."""

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
        with ProcessPoolExecutor(max_workers=workers, initializer=_init_worker, initargs=(fn, shared)) as pool:
            futures = [pool.submit(_run_in_worker, job) for job in jobs]
            for _ in as_completed(futures):
                if on_done:
                    on_done()
            return [f.result() for f in futures]


class DaskExecutor:
    """The same interface on a Dask distributed cluster: ``DaskExecutor("tcp://host:8786")`` or
    ``DaskExecutor(client=Client(...))``. The shared argument is scattered to every worker once."""

    def __init__(self, address: str | None = None, client: Any = None) -> None:
        try:
            from dask.distributed import Client
        except ImportError:
            raise UsageError("--scheduler needs Dask: pip install 'tutgen[dask]' (dask[distributed])") from None
        if client is None:
            try:
                client = Client(address, timeout=30)
            except (OSError, TimeoutError) as err:
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
        for _ in dask_completed(futures):
            if on_done:
                on_done()
        return list(self.client.gather(futures))

    def close(self) -> None:
        if self._owned:
            self.client.close()


def make_executor(
    workers: int | None = None, scheduler: str | None = None
) -> SerialExecutor | ProcessExecutor | DaskExecutor:
    """``--scheduler`` wins (Dask); else a process pool of ``workers`` (1: in this process)."""
    if scheduler:
        return DaskExecutor(scheduler)
    if workers == 1:
        return SerialExecutor()
    return ProcessExecutor(workers)
