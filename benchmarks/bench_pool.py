"""Pooling many recordings of one body (issue #29 item 2): 50 recordings of one toss each; and
one 10 s recording of one toss, the whole command.

The target (in-process, on this machine's 2 cores): the 50 recordings, each with its own phone
mount, bias and noise (:func:`tumble.analysis.fit.synthetic.synthetic_recording`, seeds 1000-1049,
the racquet, one toss), pooled by :func:`tumble.analysis.fit.fit_recording` (detection in each,
50 flight fits, one joint fit: ratios and drag shared, mount and bias per recording) in at most
30 s. Baseline, measured in the same run: the 50 recordings fitted one by one (what pooling them
by hand, an inverse-variance mean, would cost).

Run: ``python benchmarks/bench_pool.py [--quick]`` or ``python benchmarks/run.py --suite bench_pool``.
"""

from __future__ import annotations

import json
import platform
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from tumble.analysis.fit import NoFlightError, fit_recording
from tumble.analysis.fit.synthetic import synthetic_recording

TARGET = 30.0
RECORDINGS = 50
#: A 10 s recording of one toss, the whole ``tumble fit`` command in a fresh process: at most 2 s.
TARGET_ONE = 2.0


def _ten_seconds(folder: Path) -> Path:
    """A 10 s, 200 Hz recording of one phone toss that lands, the hold before and after it."""
    rec = synthetic_recording(101, body="phone", tosses=1, ending="landing", rate=200.0)
    t_more = np.arange(rec.t[-1] + 0.005, 10.0, 0.005)
    w_more = rec.omega[-1] + np.random.default_rng(1).normal(0.0, 0.005, (len(t_more), 3))
    t, w = np.r_[rec.t, t_more], np.r_[rec.omega, w_more]
    path = folder / "one_toss_10s.csv"
    path.write_text("t (s),wx (rad/s),wy (rad/s),wz (rad/s)\n" + "".join(
        f"{ti:.4f},{a:.5f},{b:.5f},{c:.5f}\n" for ti, (a, b, c) in zip(t, w)), encoding="utf-8")
    return path


def _whole_command(path: Path, out: Path) -> float:
    """Seconds of ``python -m tumble fit PATH --out OUT`` in a fresh process (compiled kernels cached)."""
    import subprocess

    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "tumble", "fit", str(path), "--out", str(out)], check=True,
                   capture_output=True)
    return time.perf_counter() - t0


def _recordings(n):
    return [synthetic_recording(1000 + k, tosses=1) for k in range(n)]


def _apart(recs):
    """Each recording fitted alone; one whose toss is not usable by itself counts as tried."""
    fits = []
    for r in recs:
        try:
            fits.append(fit_recording(r.t, r.omega, events=r.events))
        except NoFlightError:
            pass
    return fits


def _timed(fn):
    t0 = time.perf_counter()
    value = fn()
    return time.perf_counter() - t0, value


def run(out, quick: bool = False) -> str:
    repeat = 1 if quick else 3
    recs = _recordings(RECORDINGS)
    data = [(r.t, r.omega, r.events) for r in recs]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a stray flight's verdict is not what is timed
        fit_recording(recs[0].t, recs[0].omega, events=recs[0].events)  # compiled kernels' first call, not timed
        pooled_times, apart_times = [], []
        for _ in range(repeat):
            seconds, pooled = _timed(lambda: fit_recording(data))
            pooled_times.append(seconds)
            seconds, apart = _timed(lambda: _apart(recs))
            apart_times.append(seconds)
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        path = _ten_seconds(Path(folder))
        _whole_command(path, Path(folder) / "warm")  # the first run fills numba's cache
        one_times = [_whole_command(path, Path(folder) / f"out{k}") for k in range(repeat)]
    one = float(np.median(one_times))
    med, base = float(np.median(pooled_times)), float(np.median(apart_times))
    truth = recs[0].ratios
    row = {"case": f"{RECORDINGS} recordings of one toss each, pooled (fit_recording: detection, "
                   f"{pooled.tosses_used} flight fits, joint fit with mount and bias per recording)",
           "seconds": med, "range": [min(pooled_times), max(pooled_times)], "target_seconds": TARGET,
           "baseline_seconds": base, "ratio": med / base, "tosses_used": pooled.tosses_used,
           "ratios": pooled.pooled.ratios.tolist(), "ratios_std": pooled.pooled.ratios_std.tolist(),
           "truth": truth.tolist(), "usable_alone": len(apart)}
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    one_row = {"case": "a 10 s recording of one toss (200 Hz, a landing), tumble fit in a fresh process",
               "seconds": one, "range": [min(one_times), max(one_times)], "target_seconds": TARGET_ONE}
    (out / "bench_pool.json").write_text(json.dumps([row, one_row], indent=2) + "\n")
    met = "yes" if med <= TARGET else "NO"
    met_one = "yes" if one <= TARGET_ONE else "NO"
    return "\n".join([
        "# bench_pool", "", f"Python {platform.python_version()} on {platform.machine()}; median over {repeat} "
        "repeats, range in brackets. Baseline: the same recordings fitted one by one "
        f"({row['usable_alone']} of {RECORDINGS} give a fit alone).", "",
        "| case | time (s) | target (s) | met | baseline (s) | ratio to baseline |", "|---|---|---|---|---|---|",
        f"| {row['case']} | {med:.3g} [{row['range'][0]:.3g}-{row['range'][1]:.3g}] | {TARGET:g} | {met} | "
        f"{base:.3g} | {med / base:.3g} |",
        f"| {one_row['case']} | {one:.3g} [{min(one_times):.3g}-{max(one_times):.3g}] | {TARGET_ONE:g} | {met_one} "
        "| | |", "",
        f"Pooled I1/I3 = {row['ratios'][0]:.4f} +- {row['ratios_std'][0]:.2g}, I2/I3 = {row['ratios'][1]:.4f} +- "
        f"{row['ratios_std'][1]:.2g} (true {truth[0]:.4f}, {truth[1]:.4f}) from {pooled.tosses_used} flights.",
    ]) + "\n"


if __name__ == "__main__":
    quick = "--quick" in sys.argv[1:]  # a quick run never overwrites the full results
    results = Path(__file__).resolve().parent / "results"
    print(run(results / "quick" if quick else results, quick=quick), end="")
