"""Where the chunks of a sweep are computed: in this process, or on a Dask cluster.

A backend has one method, ``map(fn, tasks)``, which calls ``fn(*task)`` for each task and
yields ``(position, result)`` pairs as they finish (in any order); the runner
(:mod:`tumble.ensemble.sweep`) puts them back in order, so the results do not depend on the
backend. Dask (``pip install 'tumble[cluster]'``) is imported only when asked for.

A worker that dies mid-sweep costs only the chunks it held: the scheduler runs them again on
another worker, and when it gives up on a chunk (:class:`distributed.KilledWorker`, after the
scheduler's ``allowed-failures``) :class:`DaskBackend` submits it again itself, up to
``retries`` times. A chunk's columns depend only on the chunk, so a re-run gives the same rows.

A clean run prints nothing from Dask: its loggers (``distributed``, ``tornado``) are silenced
from the backend's start to the end of its close, here and in a local cluster's workers (whose
shutdown otherwise logs heartbeat tracebacks when many share few cores); the workers ignore
SIGINT, which Ctrl-C sends to every process of the terminal's group (the parent shuts them down);
the scheduler's HTTP server, which Dask starts even without a dashboard, listens on a free
loopback port and serves no route (not port 8787, so no warning when that port is taken). An
address where no Dask scheduler answers is refused within ``timeout`` seconds, in one line.
"""

from __future__ import annotations

import contextlib
import logging
from typing import Callable, Iterable, Iterator

from .._optional import optional_import

__all__ = ["SCHEDULER_TIMEOUT", "DaskBackend", "InProcess", "make_backend"]

#: Seconds given to a running scheduler (``scheduler=``) to accept the connection and answer.
SCHEDULER_TIMEOUT = 5.0
#: Dask's loggers, silenced while a :class:`DaskBackend` lives.
_DASK_LOGGERS = ("distributed", "tornado")


class InProcess:
    """Compute the tasks one after the other, here, lazily (one chunk in memory at a time).

    Examples
    --------
    >>> from tumble.ensemble.backends import InProcess
    >>> list(InProcess().map(pow, [(2, 10), (3, 4)]))  # (position, result), in order
    [(0, 1024), (1, 81)]
    """

    def map(self, fn: Callable, tasks: Iterable[tuple]) -> Iterator[tuple[int, object]]:
        """Yield ``(position, fn(*task))`` in order.

        Examples
        --------
        >>> from tumble.ensemble.backends import InProcess
        >>> done = InProcess().map(divmod, [(7, 2), (9, 4)])
        >>> next(done)  # lazily: one task at a time
        (0, (3, 1))
        """
        for position, task in enumerate(tasks):
            yield position, fn(*task)

    def close(self) -> None:
        """Nothing to release.

        Examples
        --------
        >>> from tumble.ensemble.backends import InProcess
        >>> backend = InProcess()
        >>> backend.close() is None
        True
        """

    def describe(self) -> str:
        """One word for the provenance: ``"in-process"``.

        Examples
        --------
        >>> from tumble.ensemble.backends import InProcess
        >>> InProcess().describe()
        'in-process'
        """
        return "in-process"


class DaskBackend:
    """Compute the tasks on a Dask cluster: a local one of ``workers`` processes, or the
    scheduler at ``scheduler`` (an address such as ``tcp://10.0.0.5:8786``).

    A local cluster's workers start without Dask's ``MALLOC_TRIM_THRESHOLD_`` (it made large
    chunks 5x slower); workers of a running scheduler are as their nannies start them.

    A script that starts a local cluster must do so under ``if __name__ == "__main__":`` (as in
    the example below): each worker is a new Python process that imports the script again
    (multiprocessing's "spawn"), and without the guard it runs the script's top level once more,
    starting clusters of its own; Dask then fails with "Nanny failed to start".

    Parameters
    ----------
    workers : int, optional
        Processes of a local cluster (one thread each); default 1.
    scheduler : str, optional
        The address of a running scheduler, instead.
    retries : int
        How many times a chunk whose workers kept dying is submitted again (module docstring).
    timeout : float
        Seconds for the scheduler at ``scheduler`` to accept the connection and answer.

    Raises
    ------
    ValueError
        When ``dask.distributed`` is not installed (install the extra ``tumble[cluster]``), for
        a worker count that is not a whole number >= 1, or when no Dask scheduler answers at
        ``scheduler`` within ``timeout`` seconds (nothing there, or a server of another kind).

    Examples
    --------
    In a script (``sweep.py``), a local cluster of two processes:

    >>> from tumble.ensemble.backends import DaskBackend
    >>> if __name__ == "__main__":   # doctest: +SKIP
    ...     backend = DaskBackend(workers=2)
    ...     print(sorted(backend.map(pow, [(2, 10), (3, 4)])))
    ...     backend.close()
    [(0, 1024), (1, 81)]

    Interactively (a notebook, where there is no script to import again):

    >>> backend = DaskBackend(workers=2)  # doctest: +SKIP
    >>> sorted(backend.map(pow, [(2, 10), (3, 4)]))  # doctest: +SKIP
    [(0, 1024), (1, 81)]
    >>> backend.close()  # doctest: +SKIP
    """

    def __init__(self, workers: int | None = None, scheduler: str | None = None, retries: int = 3,
                 timeout: float = SCHEDULER_TIMEOUT) -> None:
        if isinstance(retries, bool) or not isinstance(retries, int) or retries < 0:
            raise ValueError(f"retries = {retries!r} must be a whole number >= 0")
        if isinstance(timeout, bool) or not isinstance(timeout, (int, float)) or not 0 < timeout < float("inf"):
            raise ValueError(f"timeout = {timeout!r} must be a number of seconds > 0")
        self.retries = retries
        Client = optional_import("dask.distributed", "cluster", "a Dask backend (workers/scheduler)").Client
        self._quiet = contextlib.ExitStack()
        self._quiet.enter_context(_silenced(_DASK_LOGGERS))
        try:
            self._cluster, self._client, self._where = None, None, ""
            if scheduler is not None:
                if not isinstance(scheduler, str) or not scheduler:
                    raise ValueError(f"scheduler = {scheduler!r} must be the address of a Dask scheduler")
                _check_scheduler(scheduler, float(timeout))
                self._client = Client(scheduler, timeout=timeout)
                self._where = f"dask scheduler {scheduler}"
            else:
                self._start_local(workers)
        except BaseException:
            self.close()
            raise

    def _start_local(self, workers) -> None:
        """A local cluster of ``workers`` processes, quiet (module docstring), and its client."""
        from dask.distributed import Client, LocalCluster

        n = 1 if workers is None else workers
        if isinstance(n, bool) or not isinstance(n, int) or n < 1:
            raise ValueError(f"workers = {workers!r} must be a whole number >= 1")
        import dask

        # Dask's nannies set MALLOC_TRIM_THRESHOLD_ in their workers, which turns glibc's
        # adaptive mmap threshold off: every large temporary array is then mapped and
        # faulted in afresh, and a chunk of 65,536 cases ran 5x slower (measured)
        environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}))
        environ.pop("MALLOC_TRIM_THRESHOLD_", None)
        settings = {"distributed.nanny.pre-spawn-environ": environ,
                    "distributed.scheduler.http.routes": [], "distributed.worker.http.routes": []}
        with dask.config.set(settings):
            # silence_logs: the level of the workers' log handler (and of this process's, while
            # the cluster lives); the preload runs dask_setup in each worker
            self._cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                         dashboard_address=None, silence_logs=_SILENT,
                                         scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
                                         preload=[__name__])
        self._client = Client(self._cluster)
        self._where = f"dask local cluster of {n} workers"

    def map(self, fn: Callable, tasks: Iterable[tuple]) -> Iterator[tuple[int, object]]:
        """Submit every task, then yield ``(position, result)`` as each finishes; a task lost
        with its workers is submitted again (class docstring).

        Raises
        ------
        ValueError
            When a task was lost with its worker ``retries + 1`` times.

        Examples
        --------
        On a threads-only cluster in this process (the scheduler's address as for a remote
        one); the results come as they finish, and in order they are :class:`InProcess`'s:

        >>> from dask.distributed import LocalCluster
        >>> from tumble.ensemble.backends import DaskBackend, InProcess
        >>> cluster = LocalCluster(processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None,
        ...                        protocol="tcp", host="127.0.0.1")   # threads of this process: quick to start
        >>> backend = DaskBackend(scheduler=cluster.scheduler_address)
        >>> tasks = [(7, 2), (9, 4), (20, 6)]
        >>> sorted(backend.map(divmod, tasks))   # (position, result)
        [(0, (3, 1)), (1, (2, 1)), (2, (3, 2))]
        >>> sorted(backend.map(divmod, tasks)) == list(InProcess().map(divmod, tasks))
        True
        >>> backend.close(); cluster.close()
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
        """Shut the client, then a local cluster, down; Dask's loggers speak again after.

        Examples
        --------
        Dask's logger is silent while the backend lives, and has its own level back after:

        >>> import logging
        >>> from dask.distributed import LocalCluster
        >>> from tumble.ensemble.backends import DaskBackend
        >>> cluster = LocalCluster(processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None,
        ...                        protocol="tcp", host="127.0.0.1")   # threads of this process: quick to start
        >>> level = logging.getLogger("distributed").level
        >>> backend = DaskBackend(scheduler=cluster.scheduler_address)
        >>> logging.getLogger("distributed").level > logging.CRITICAL
        True
        >>> backend.close()
        >>> logging.getLogger("distributed").level == level
        True
        >>> cluster.close()
        """
        with self._quiet:
            if self._client is not None:
                self._client.close()
            if self._cluster is not None:
                self._cluster.close()

    def describe(self) -> str:
        """Where the chunks ran, for the provenance.

        Examples
        --------
        >>> from dask.distributed import LocalCluster
        >>> from tumble.ensemble.backends import DaskBackend
        >>> cluster = LocalCluster(processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None,
        ...                        protocol="tcp", host="127.0.0.1")   # threads of this process: quick to start
        >>> backend = DaskBackend(scheduler=cluster.scheduler_address)
        >>> backend.describe() == f"dask scheduler {cluster.scheduler_address}"
        True
        >>> backend.close(); cluster.close()

        A local cluster of its own (processes: seconds to start) says how many workers:

        >>> DaskBackend(workers=2).describe()  # doctest: +SKIP
        'dask local cluster of 2 workers'
        """
        return self._where


#: A logging level above every level: nothing passes.
_SILENT = logging.CRITICAL + 10


@contextlib.contextmanager
def _silenced(names):
    """The loggers ``names`` and those below them that have a level of their own, silent inside."""
    manager = logging.Logger.manager
    chosen = [logging.getLogger(name) for name in names]
    chosen += [logger for key, logger in list(manager.loggerDict.items())
               if isinstance(logger, logging.Logger) and logger.level != logging.NOTSET
               and any(key.startswith(name + ".") for name in names)]
    levels = [logger.level for logger in chosen]
    for logger in chosen:
        logger.setLevel(_SILENT)
    try:
        yield
    finally:
        for logger, level in zip(chosen, levels):
            logger.setLevel(level)


def _check_scheduler(address: str, timeout: float) -> None:
    """Refuse, in one line, an address where no Dask scheduler answers within ``timeout`` seconds.

    Dask's client waits for the scheduler's handshake with no time limit (a server that waits
    for a request, as HTTP does, hangs it), and reads a reply of another protocol as a message
    length (3 EiB asked for an HTTP error): the handshake is tried here first, in its own event
    loop and thread (so also under a running loop, as in Jupyter), under one deadline. The
    connection itself gets 0.8 of it, so that a refusal or an unknown host is told as such.
    """
    import asyncio
    from concurrent.futures import ThreadPoolExecutor

    from distributed.comm import connect, get_address_host_port

    def refuse(why: str):
        return ValueError(f"scheduler = {address!r}: no Dask scheduler there ({why}); give the address "
                          "a running scheduler prints, such as tcp://10.0.0.5:8786")

    try:
        get_address_host_port(address)
    except ValueError as exc:
        raise refuse(f"not an address: {exc}") from None

    async def handshake() -> None:
        comm = await asyncio.wait_for(connect(address, timeout=0.8 * timeout), timeout)
        await comm.close()

    with ThreadPoolExecutor(1) as thread:
        try:
            thread.submit(asyncio.run, handshake()).result()
        except TimeoutError:  # before OSError, its base class
            why = f"connected, but no answer within {timeout:g} s"
        except OSError as exc:  # refused, unknown host, unreachable: the last attempt's error is the cause
            cause = str(exc.__cause__ or "").rpartition(">: ")[2]  # Dask's "in <TCPConnector ...>: "
            why = f"cannot connect: {' '.join((cause or str(exc)).split())}"
        except Exception as exc:  # noqa: BLE001 - a reply, but not Dask's: garbage read as frame lengths
            why = f"the server there does not speak Dask's protocol ({type(exc).__name__} on its reply)"
        else:
            return
    raise refuse(why)


def dask_setup(worker: object) -> None:
    """Dask's preload hook, run in each worker of a local cluster as it starts: ignore SIGINT.

    Ctrl-C reaches every process of the terminal's group; a worker that took it would die with a
    traceback (and be restarted), while the parent process, which also gets it, shuts the
    cluster down. Only in a worker process of its own (its main thread), never in-process.
    """
    import signal
    import threading

    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)


def make_backend(workers: int | None = None, scheduler: str | None = None) -> InProcess | DaskBackend:
    """:class:`InProcess` when neither is given, else a :class:`DaskBackend`.

    Examples
    --------
    >>> from tumble.ensemble.backends import make_backend
    >>> make_backend().describe()
    'in-process'
    >>> make_backend(workers=2, scheduler="tcp://10.0.0.5:8786")
    Traceback (most recent call last):
    ...
    ValueError: give workers (a local Dask cluster) or scheduler (a running one), not both
    """
    if workers is None and scheduler is None:
        return InProcess()
    if workers is not None and scheduler is not None:
        raise ValueError("give workers (a local Dask cluster) or scheduler (a running one), not both")
    return DaskBackend(workers=workers, scheduler=scheduler)
