"""Where the chunks of a sweep are computed: in this process, or on a Dask cluster.

A backend has one method, ``map(fn, tasks)``, which calls ``fn(*task)`` for each task and
yields ``(position, result)`` pairs as they finish (in any order); the runner
(:mod:`tumble.ensemble.sweep`) puts them back in order, so the results do not depend on the
backend. Dask (``pip install 'tumble[cluster]'``) is imported only when asked for.

A worker that dies mid-sweep costs only the chunks it held: the scheduler runs them again on
another worker, and when it gives up on a chunk (:class:`distributed.KilledWorker`, after the
scheduler's ``allowed-failures``) :class:`DaskBackend` submits it again itself, up to
``retries`` times. A chunk's columns depend only on the chunk, so a re-run gives the same rows.
"""

from __future__ import annotations

from typing import Callable, Iterable, Iterator

__all__ = ["DaskBackend", "InProcess", "make_backend"]


class InProcess:
    """Compute the tasks one after the other, here, lazily (one chunk in memory at a time)."""

    def map(self, fn: Callable, tasks: Iterable[tuple]) -> Iterator[tuple[int, object]]:
        """Yield ``(position, fn(*task))`` in order."""
        for position, task in enumerate(tasks):
            yield position, fn(*task)

    def close(self) -> None:
        """Nothing to release."""

    def describe(self) -> str:
        """One word for the provenance: ``"in-process"``."""
        return "in-process"


class DaskBackend:
    """Compute the tasks on a Dask cluster: a local one of ``workers`` processes, or the
    scheduler at ``scheduler`` (an address such as ``tcp://10.0.0.5:8786``).

    A local cluster's workers start without Dask's ``MALLOC_TRIM_THRESHOLD_`` (it made large
    chunks 5x slower); workers of a running scheduler are as their nannies start them.

    Parameters
    ----------
    workers : int, optional
        Processes of a local cluster (one thread each); default 1.
    scheduler : str, optional
        The address of a running scheduler, instead.
    retries : int
        How many times a chunk whose workers kept dying is submitted again (module docstring).

    Raises
    ------
    ValueError
        When ``dask.distributed`` is not installed (install the extra ``tumble[cluster]``), or
        for a worker count that is not a whole number >= 1.
    """

    def __init__(self, workers: int | None = None, scheduler: str | None = None, retries: int = 3) -> None:
        if isinstance(retries, bool) or not isinstance(retries, int) or retries < 0:
            raise ValueError(f"retries = {retries!r} must be a whole number >= 0")
        self.retries = retries
        try:
            from dask.distributed import Client, LocalCluster
        except ImportError:
            raise ValueError("workers/scheduler need Dask: pip install 'tumble[cluster]' "
                             "(dask[distributed] >= 2024.1)") from None
        if scheduler is not None:
            if not isinstance(scheduler, str) or not scheduler:
                raise ValueError(f"scheduler = {scheduler!r} must be the address of a Dask scheduler")
            self._cluster = None
            self._client = Client(scheduler)
            self._where = f"dask scheduler {scheduler}"
        else:
            n = 1 if workers is None else workers
            if isinstance(n, bool) or not isinstance(n, int) or n < 1:
                raise ValueError(f"workers = {workers!r} must be a whole number >= 1")
            import dask

            # Dask's nannies set MALLOC_TRIM_THRESHOLD_ in their workers, which turns glibc's
            # adaptive mmap threshold off: every large temporary array is then mapped and
            # faulted in afresh, and a chunk of 65,536 cases ran 5x slower (measured)
            environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}))
            environ.pop("MALLOC_TRIM_THRESHOLD_", None)
            with dask.config.set({"distributed.nanny.pre-spawn-environ": environ}):
                self._cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                             dashboard_address=None)
            self._client = Client(self._cluster)
            self._where = f"dask local cluster of {n} workers"

    def map(self, fn: Callable, tasks: Iterable[tuple]) -> Iterator[tuple[int, object]]:
        """Submit every task, then yield ``(position, result)`` as each finishes; a task lost
        with its workers is submitted again (class docstring).

        Raises
        ------
        ValueError
            When a task was lost with its worker ``retries + 1`` times.
        """
        from dask.distributed import KilledWorker, as_completed

        tasks = list(tasks)
        futures = {self._client.submit(fn, *task, pure=False): k for k, task in enumerate(tasks)}
        lost = dict.fromkeys(range(len(tasks)), 0)
        pending = as_completed(futures)
        try:
            for future in pending:
                k = futures.pop(future)
                try:
                    result = future.result()
                except KilledWorker as exc:
                    lost[k] += 1
                    if lost[k] > self.retries:
                        why = " ".join(str(exc).split())
                        raise ValueError(f"task {k}: its workers kept dying; given up after {lost[k]} "
                                         f"submission(s), retries = {self.retries} (Dask: {why})") from None
                    again = self._client.submit(fn, *tasks[k], pure=False)
                    futures[again] = k
                    pending.add(again)
                    continue
                yield k, result
        finally:
            for future in futures:
                future.cancel()

    def close(self) -> None:
        """Shut the client (and a local cluster) down."""
        self._client.close()
        if self._cluster is not None:
            self._cluster.close()

    def describe(self) -> str:
        """Where the chunks ran, for the provenance."""
        return self._where


def make_backend(workers: int | None = None, scheduler: str | None = None):
    """:class:`InProcess` when neither is given, else a :class:`DaskBackend`."""
    if workers is None and scheduler is None:
        return InProcess()
    if workers is not None and scheduler is not None:
        raise ValueError("give workers (a local Dask cluster) or scheduler (a running one), not both")
    return DaskBackend(workers=workers, scheduler=scheduler)
