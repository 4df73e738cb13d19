"""Sweeps on Dask when workers die: only their chunks are lost, run again, and the rows stay the same.

A chunk function that kills its own worker process (SIGKILL, as an out-of-memory killer or a
lost node would) the first time it runs a given chunk, recorded through a file, so that the
re-run of that chunk on another worker finishes. Skipped without ``dask.distributed``.
"""

from __future__ import annotations

import functools
import os
import signal
import sys
from pathlib import Path

import pytest

distributed = pytest.importorskip("dask.distributed")
cloudpickle = pytest.importorskip("cloudpickle")

import tumble.io.sweepfile as sweepfile  # noqa: E402
from tumble.ensemble import DaskBackend  # noqa: E402
from tumble.io.sweepfile import run_sweep  # noqa: E402

# the workers unpickle this module's functions by value: they need not import the tests
cloudpickle.register_pickle_by_value(sys.modules[__name__])

SWEEP = """\
body = "t-handle"

[sweep]
cases = 48
seed = 21
chunk = 6

[[dispersion]]
target = "moments"
relative = 0.02

[[dispersion]]
target = "axes"
absolute = 0.01

[simulation]
samples = 200
t_end = 12.0

[initial]
spread = [0.05, 0.3, 0.05]
distribution = "uniform"
omega = [0.1, 8.0, 0.1]
"""


def kill_first_run(marks: str, doomed: tuple, fn, sweep, start, stop):
    """``fn(sweep, start, stop)``, but the first run of a chunk starting in ``doomed`` kills its worker."""
    mark = Path(marks) / f"chunk-{start}"
    if start in doomed and not mark.exists():
        mark.write_text(str(os.getpid()))
        os.kill(os.getpid(), signal.SIGKILL)
    (Path(marks) / f"done-{start}-{os.getpid()}").touch()
    return fn(sweep, start, stop)


class Killing:
    """A backend whose chunk function kills its worker on the first run of the ``doomed`` chunks."""

    def __init__(self, inner, marks: Path, doomed: tuple) -> None:
        self.inner, self.marks, self.doomed = inner, marks, doomed

    def map(self, fn, tasks):
        return self.inner.map(functools.partial(kill_first_run, str(self.marks), self.doomed, fn), tasks)

    def close(self) -> None:
        self.inner.close()

    def describe(self) -> str:
        return self.inner.describe()


def test_a_worker_killed_mid_sweep_costs_only_its_chunk_and_the_cases_are_the_same(tmp_path, monkeypatch):
    path = tmp_path / "kill.toml"
    path.write_text(SWEEP)
    here = run_sweep(path, tmp_path / "here")
    marks = tmp_path / "marks"
    marks.mkdir()
    doomed = (0, 24, 42)  # chunks 0, 4 and 7 of 8: the first, one in the middle, the last
    monkeypatch.setattr(sweepfile, "make_backend", lambda workers, scheduler: Killing(DaskBackend(workers=2),
                                                                                      marks, doomed))
    there = run_sweep(path, tmp_path / "there", workers=2)
    killed = sorted(int(p.read_text()) for p in marks.glob("chunk-*"))
    assert len(killed) == 3 and len(set(killed)) == 3  # three workers died, one per doomed chunk
    done = [p.name.split("-")[1] for p in marks.glob("done-*")]
    # every chunk ran to the end, the doomed ones on another worker after their kill; a death
    # loses the chunk it ran and any finished result the worker still held (measured: 1 chunk
    # run twice in 8), never the sweep: fewer re-runs than the 3 x 8 of starting over each time
    assert sorted(set(done), key=int) == [str(s) for s in range(0, 48, 6)]
    assert len(done) - 8 < 3 * 8
    assert there["backend"] == "dask local cluster of 2 workers"
    assert (tmp_path / "here" / "cases.csv").read_bytes() == (tmp_path / "there" / "cases.csv").read_bytes()
    assert here["statistics"] == there["statistics"]


def kill_always(fn, sweep, start, stop):
    os.kill(os.getpid(), signal.SIGKILL)


def test_a_chunk_that_kills_every_worker_is_refused_in_one_line():
    import dask

    with dask.config.set({"distributed.scheduler.allowed-failures": 0}):  # the scheduler gives up at once
        backend = DaskBackend(workers=1, retries=1)
    try:
        with pytest.raises(ValueError, match=r"^task 0: its workers kept dying; given up after 2 submission\(s\), "
                                             r"retries = 1 \(Dask: [^\n]*\)$"):
            list(backend.map(functools.partial(kill_always, None), [(None, 0, 1)]))
    finally:
        backend.close()


def test_retries_must_be_a_whole_number():
    with pytest.raises(ValueError, match=r"^retries = -1 must be a whole number >= 0$"):
        DaskBackend(workers=1, retries=-1)
