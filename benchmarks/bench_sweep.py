"""Sweep benchmarks: a torque-free sweep of final states and exact flip periods, in-process and on Dask.

The ensembles issue's targets: 1,000,000 cases (final state at t_end = 20 s and the flip
period) in at most 10 s in-process, at least 200x a loop of ``tumble.simulate`` per case; and
a 2-worker local Dask cluster at least 1.6x in-process.

The sweep: a solid box 0.2 x 0.3 x 0.4 m, each principal moment dispersed by 5 % (normal),
initial rates (0.1, 10, 0.1) rad/s about the principal axes with normal spreads (0.1, 0.5,
0.1): spins near the intermediate axis, both sides of the separatrix. ``samples = 2``: the
final state and the exact flip interval (``flip_period_exact``), no measured flips. Timed:
making the cases, running them, reducing them to rows and folding the statistics
(``summarize(run_chunks(...))``), in chunks of :data:`CHUNK` cases.

- in-process vs loop: each repeat times the whole sweep, then a loop over its first
  :data:`LOOP_CASES` cases, each made alone (``Ensemble.inputs(i, i + 1)``), run with
  ``tumble.simulate(times=[20.0])`` and given ``tumble.analysis.flip_interval``; the ratio is
  (loop time per case) / (sweep time per case);
- Dask vs in-process: a local cluster of 2 worker processes (1 thread each), started before
  the timing; each repeat times the sweep on it and in-process, in alternation;
- per-chunk overhead: the same sweep of :data:`TINY_CASES` cases in chunks of 1 case, on the
  cluster and in-process: (Dask wall time - in-process wall time) / chunks.

Medians over the repeats, ranges in brackets.
"""

from __future__ import annotations

import json
import os
import platform
import time

import numpy as np

import tumble
from tumble.analysis import flip_interval
from tumble.ensemble import (BodySampler, DaskBackend, Dispersion, Ensemble, InitialRates, RunSettings, Sweep,
                             run_chunks, summarize)

TARGET_SECONDS = 10.0
TARGET_RATIO = 200.0
TARGET_DASK = 1.6
CHUNK = 65_536
LOOP_CASES = 200
TINY_CASES = 400


def sweep_of(cases: int) -> Sweep:
    """The benchmark's sweep of ``cases`` cases (module docstring)."""
    body = tumble.Body((tumble.Box(mass=1.0, size=(0.2, 0.3, 0.4)),), "box")
    rates = InitialRates(omega=(0.1, 10.0, 0.1), distribution="normal", spread=(0.1, 0.5, 0.1))
    ensemble = Ensemble(BodySampler(body, (Dispersion("moments", 0.05),)), rates, cases, seed=2024)
    return Sweep(ensemble, RunSettings(t_end=20.0, samples=2))


def timed(sweep: Sweep, chunk: int = CHUNK, backend=None) -> float:
    t0 = time.perf_counter()
    summary = summarize(run_chunks(sweep, chunk=chunk, backend=backend), sweep.ensemble.seed)
    seconds = time.perf_counter() - t0
    assert summary.cases == sweep.ensemble.cases
    return seconds


def loop(sweep: Sweep, k: int) -> float:
    """Seconds per case of a loop of ``tumble.simulate`` over the first ``k`` cases."""
    t0 = time.perf_counter()
    for i in range(k):
        x = sweep.ensemble.inputs(i, i + 1)
        props = tumble.MassProperties(1.0, np.zeros(3), np.diag(x.moments[0]), x.moments[0].copy(), np.eye(3))
        tumble.simulate(props, x.omega0[0], times=[20.0], attitude0=x.quat0[0])
        flip_interval(x.omega0[0], x.moments[0])
    return (time.perf_counter() - t0) / k


def _stats(x) -> dict:
    x = np.asarray(x, dtype=float)
    return {"median": float(np.median(x)), "range": [float(x.min()), float(x.max())]}


def measure(quick: bool = False) -> dict:
    repeat = 3
    n = 100_000 if quick else 1_000_000
    n_dask = 20_000 if quick else 1_000_000
    big = sweep_of(n)
    timed(sweep_of(1000))  # imports and caches warm
    sweep_s, loop_s = [], []
    for _ in range(repeat):
        sweep_s.append(timed(big))
        loop_s.append(loop(big, LOOP_CASES))
    ratio = np.array(loop_s) / (np.array(sweep_s) / n)
    rows = {
        "in_process": {"cases": n, "chunk": CHUNK, "repeats": repeat, "seconds": _stats(sweep_s),
                       "loop_cases": LOOP_CASES, "loop_seconds_per_case": _stats(loop_s), "ratio": _stats(ratio),
                       "target_seconds": TARGET_SECONDS * n / 1_000_000, "target_ratio": TARGET_RATIO},
    }
    backend = DaskBackend(workers=2)
    try:
        mid = sweep_of(n_dask)
        timed(mid, backend=backend)  # the workers import tumble and warm up
        here, there = [], []
        for _ in range(repeat):
            there.append(timed(mid, backend=backend))
            here.append(timed(mid))
        tiny = sweep_of(TINY_CASES)
        tiny_here, tiny_there = [], []
        for _ in range(repeat):
            tiny_there.append(timed(tiny, chunk=1, backend=backend))
            tiny_here.append(timed(tiny, chunk=1))
    finally:
        backend.close()
    speedup = np.array(here) / np.array(there)
    overhead = (np.array(tiny_there) - np.array(tiny_here)) / TINY_CASES
    rows["dask"] = {"cases": n_dask, "chunk": CHUNK, "workers": 2, "repeats": repeat, "seconds": _stats(there),
                    "in_process_seconds": _stats(here), "speedup": _stats(speedup), "target_speedup": TARGET_DASK,
                    "tiny_cases": TINY_CASES, "tiny_chunk": 1, "tiny_seconds": _stats(tiny_there),
                    "tiny_in_process_seconds": _stats(tiny_here), "overhead_per_chunk_seconds": _stats(overhead)}
    rows["machine"] = {"python": platform.python_version(), "machine": platform.machine(), "node": platform.node(),
                       "cpus": os.cpu_count()}
    return rows


def _r(s: dict, scale: float = 1.0, fmt: str = ".3g") -> str:
    lo, hi = s["range"]
    return f"{s['median'] * scale:{fmt}} [{lo * scale:{fmt}}-{hi * scale:{fmt}}]"


def to_markdown(r: dict) -> str:
    p, d, m = r["in_process"], r["dask"], r["machine"]
    met = p["seconds"]["median"] <= p["target_seconds"]
    met_ratio = p["ratio"]["median"] >= TARGET_RATIO
    met_dask = d["speedup"]["median"] >= TARGET_DASK
    yes = {True: "yes", False: "NO"}
    return "\n".join([
        "# bench_sweep", "",
        f"Python {m['python']} on {m['machine']}, {m['node']}, {m['cpus']} CPUs; medians over {p['repeats']} repeats, "
        "range in brackets. A torque-free sweep: final state at 20 s + exact flip period "
        "(samples = 2), moments dispersed 5 %, normal initial rates (benchmarks/bench_sweep.py).", "",
        "| case | time (s) | baseline | ratio | target | met (median) |",
        "|---|---|---|---|---|---|",
        f"| in-process sweep, {p['cases']:,} cases, chunks of {p['chunk']:,} | {_r(p['seconds'])} "
        f"| loop of tumble.simulate per case ({p['loop_cases']} cases): {_r(p['loop_seconds_per_case'], 1e3)} ms/case "
        f"| {_r(p['ratio'])} | {p['target_seconds']:.3g} s, ratio {TARGET_RATIO:g} "
        f"| time {yes[met]}, ratio {yes[met_ratio]} |",
        f"| Dask local cluster, {d['workers']} workers, {d['cases']:,} cases, chunks of {d['chunk']:,} "
        f"| {_r(d['seconds'])} | in-process {_r(d['in_process_seconds'])} s | {_r(d['speedup'])} "
        f"| speedup {TARGET_DASK:g} | {yes[met_dask]} |",
        f"| Dask overhead per chunk: {d['tiny_cases']} cases in chunks of 1 | {_r(d['tiny_seconds'])} "
        f"| in-process {_r(d['tiny_in_process_seconds'])} s | {_r(d['overhead_per_chunk_seconds'], 1e3)} ms/chunk "
        f"| - | - |",
        "",
    ])


def run(out, quick: bool = False) -> str:
    """Measure, write ``bench_sweep.json`` into ``out``, return the markdown table."""
    rows = measure(quick)
    (out / "bench_sweep.json").write_text(json.dumps(rows, indent=2) + "\n")
    return to_markdown(rows)
