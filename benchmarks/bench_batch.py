"""Batch benchmarks: ``tumble.simulate_batch`` against a loop of ``tumble.simulate``, per case.

The target: 1,000,000 bodies' final omega at t_end = 20 s plus their flip interval in at most
5 s on 2 cores (the speed issue, 18; the ensembles issue had asked for 10 s), and at least 200x a
loop of ``simulate`` per case. Each repeat times
the batch and the loop (on a sample of the same bodies) in alternation, so a load that comes and
goes hits both alike; the ratio is (loop time per case) / (batch time per case), and the medians
over the repeats are reported with their ranges. Bodies: random moments in [0.1, 1] kg m^2 (those
that break I1 + I2 >= I3, which no mass distribution has, drawn again) and
omega ~ N(0, 1) rad/s per component (both sides of the separatrix, in the proportions chance
gives), with random attitudes.
"""

from __future__ import annotations

import json
import platform
import time

import numpy as np
from scipy.spatial.transform import Rotation

import tumble
from tumble.analysis import flip_interval
from tumble.dynamics.methods.exact_batch import free_rotation_batch

TARGET_SECONDS = 5.0  # s for 1e6 cases (issue 18)
TARGET_RATIO = 200.0


def _bodies(n: int, seed: int = 0):
    rng = np.random.default_rng(seed)
    I = np.sort(rng.uniform(0.1, 1.0, (n, 3)), axis=1)
    bad = I[:, 2] > I[:, 0] + I[:, 1]  # no positive mass has them: drawn again (simulate_batch refuses them)
    while np.any(bad):
        I[bad] = np.sort(rng.uniform(0.1, 1.0, (int(bad.sum()), 3)), axis=1)
        bad = I[:, 2] > I[:, 0] + I[:, 1]
    w = rng.normal(size=(n, 3))
    q = Rotation.random(n, random_state=seed).as_quat()
    return I, w, q


def _props(I) -> tumble.MassProperties:
    return tumble.MassProperties(1.0, np.zeros(3), np.diag(I), I.copy(), np.eye(3))


def _cases(quick: bool):
    """(title, batch function, loop function over the first k bodies, N, k, target seconds)."""
    n_big = 100_000 if quick else 1_000_000
    I, w, q = _bodies(n_big)
    t500 = np.linspace(0.0, 20.0, 500)
    n_mid = 1_000 if quick else 10_000

    def final_and_flip():
        omega = tumble.simulate_batch(I, w, times=[20.0], attitude0=q).omega[:, -1]
        return omega, flip_interval(w, I)

    def final_and_flip_loop(k):
        for i in range(k):
            tumble.simulate(_props(I[i]), w[i], times=[20.0], attitude0=q[i]).omega[-1]
            flip_interval(w[i], I[i])

    def omega_only():
        return free_rotation_batch(I, w, q, np.array([20.0]), attitude=False)[0][:, -1], flip_interval(w, I)

    def samples_500():
        return tumble.simulate_batch(I[:n_mid], w[:n_mid], times=t500, attitude0=q[:n_mid])

    def samples_500_loop(k):
        for i in range(k):
            tumble.simulate(_props(I[i]), w[i], times=t500, attitude0=q[i])

    return [
        (f"exact, final omega and attitude at 20 s + flip interval, N = {n_big:,} (simulate_batch)",
         final_and_flip, final_and_flip_loop, n_big, 200, TARGET_SECONDS * n_big / 1_000_000),
        (f"exact, final omega only at 20 s + flip interval, N = {n_big:,} (free_rotation_batch, attitude=False)",
         omega_only, final_and_flip_loop, n_big, 200, TARGET_SECONDS * n_big / 1_000_000),
        (f"exact, 500 samples over 20 s, omega and attitude, N = {n_mid:,} (simulate_batch)",
         samples_500, samples_500_loop, n_mid, 20, None),
    ]


def measure(quick: bool = False) -> list[dict]:
    """Every case, batch and loop in alternation; medians and ranges over the repeats."""
    repeat = 3 if quick else 5
    rows = []
    for title, batch, loop, n, k, target in _cases(quick):
        batch_s, loop_s = [], []
        for _ in range(repeat):
            t0 = time.perf_counter()
            batch()
            batch_s.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            loop(k)
            loop_s.append((time.perf_counter() - t0) / k)
        batch_s, loop_s = np.array(batch_s), np.array(loop_s)
        ratio = loop_s / (batch_s / n)
        rows.append({
            "case": title, "bodies": n, "loop_sample": k, "repeats": repeat,
            "seconds": float(np.median(batch_s)), "seconds_range": [float(batch_s.min()), float(batch_s.max())],
            "loop_seconds_per_case": float(np.median(loop_s)),
            "loop_range": [float(loop_s.min()), float(loop_s.max())],
            "ratio": float(np.median(ratio)), "ratio_range": [float(ratio.min()), float(ratio.max())],
            "target_seconds": target, "meets_target": None if target is None else bool(np.median(batch_s) <= target),
        })
    return rows


def to_markdown(rows: list[dict]) -> str:
    lines = [
        "# bench_batch", "",
        f"Python {platform.python_version()} on {platform.machine()}, {platform.node()}; medians over "
        f"{rows[0]['repeats'] if rows else 0} alternating repeats (batch, then a loop of tumble.simulate on a "
        f"sample of the same bodies), range in brackets. Ratio: loop time per case / batch time per case.", "",
        "| case | batch time (s) | loop time per case (ms) | ratio | target | met (median) |",
        "|---|---|---|---|---|---|",
    ]
    for r in rows:
        lo, hi = r["seconds_range"]
        llo, lhi = r["loop_range"]
        rlo, rhi = r["ratio_range"]
        target = "-" if r["target_seconds"] is None else f"{r['target_seconds']:.3g} s, ratio {TARGET_RATIO:g}"
        met = "-" if r["meets_target"] is None else ("yes" if r["meets_target"] and r["ratio"] >= TARGET_RATIO else "NO")
        lines.append(f"| {r['case']} | {r['seconds']:.3g} [{lo:.3g}-{hi:.3g}] | {r['loop_seconds_per_case'] * 1e3:.3g} "
                     f"[{llo * 1e3:.3g}-{lhi * 1e3:.3g}] | {r['ratio']:.3g} [{rlo:.3g}-{rhi:.3g}] | {target} | {met} |")
    return "\n".join(lines) + "\n"


def run(out, quick: bool = False) -> str:
    """Measure, write ``bench_batch.json`` into ``out``, return the markdown table."""
    rows = measure(quick)
    (out / "bench_batch.json").write_text(json.dumps(rows, indent=2) + "\n")
    return to_markdown(rows)
