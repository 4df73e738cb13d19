"""Work-precision figures: the error in omega and in attitude against the time a call takes, for
every tumble method that takes the problem and the shared peers (issue 38 item 8).

The problems are the peer comparisons' own (``bench_engine``, ``bench_models``,
``bench_closed_loop``): one body (the seed T-handle at 10 rad/s in the gravity gradient), the
batch (constant body torque; 200 bodies in ``--quick``, 2,000 in the full run), the gyrostat
(with a torque), Explorer 1 with its damper, and the closed loop. Each method runs over a ladder
of its knob (rtol 1e-3 to 1e-13, or 1 to 4,096 steps per sample interval) until a call takes
longer than a budget or both errors reach round-off; each point is one timed
batch of calls (``_harness.time_call``), so the figures are for shape, the ratios are in the other
suites. Errors against the same scipy DOP853 rtol 1e-13 references. One PNG per problem,
``work_precision_<problem>.png``, and the points in ``bench_work_precision.json``.
"""

from __future__ import annotations

import json
import sys

import numpy as np
from _harness import Problem, machine, time_call

RTOL_LADDER = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13]
K_LADDER = [1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096]
FLOOR = 1e-14  # both errors at or below: round-off, the ladder stops


def problems(quick: bool) -> dict:
    import bench_closed_loop
    import bench_engine
    import bench_models

    one = [p for p in bench_engine.one_body_problems() if p.name.startswith("seed") and "gravity" in p.name][0]
    return {"one_body": one, "batch": bench_engine.batch_problem(200 if quick else 2000),
            "gyrostat": bench_models.gyrostat_problem(True), "damper": bench_models.damper_problem(),
            "closed_loop": bench_closed_loop.problem()}


def _series(run, errors_of, ladder, budget: float) -> list[dict]:
    """One method over its ladder: (knob, seconds, omega error, attitude error) per point."""
    points = []
    for value in ladder:
        try:
            e = errors_of(run(value))
        except (ValueError, RuntimeError) as exc:  # refused (too many steps) or failed
            print(f"    {value:g}: {exc}", file=sys.stderr)
            continue
        seconds = time_call(lambda: run(value), 0.02)
        points.append({"knob": value, "seconds": seconds, "omega": e[0], "attitude": e[1]})
        if seconds > budget or max(e) <= FLOOR:
            break
    return points


def measure(p: Problem, budget: float) -> dict:
    out = {}
    for m in ("rk4", "rk8"):
        out[f"peer {m}"] = _series(lambda k, m=m: p.peer(m, k), p.peer_errors, K_LADDER, budget)
    for m, knob in p.methods.items():
        if knob == "rtol":
            out[f"tumble {m}"] = _series(lambda r, m=m: p.tumble(method=m, rtol=r), p.tumble_errors, RTOL_LADDER, budget)
        else:
            out[f"tumble {m}"] = _series(lambda k, m=m: p.tumble(method=m, step=p.interval / k), p.tumble_errors,
                                         K_LADDER, budget)
        print(f"  {p.name}: tumble {m}: {len(out[f'tumble {m}'])} points", file=sys.stderr, flush=True)
    return out


def figure(path, title: str, target: dict, series: dict) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharex=True)
    for ax, key, label in ((axes[0], "omega", "omega error (relative to max |omega|)"),
                           (axes[1], "attitude", "attitude error (rad)")):
        for name, pts in series.items():
            if not pts:
                continue
            x = [q["seconds"] for q in pts]
            y = [max(q[key], 1e-17) for q in pts]
            ax.loglog(x, y, "o--" if name.startswith("peer") else "s-", label=name, lw=2 if name.startswith("peer") else 1)
        ax.axhline(target[key], color="k", lw=0.8, ls=":")
        ax.set_xlabel("time per call (s)")
        ax.set_ylabel(label)
        ax.grid(True, which="major", alpha=0.3)
    axes[1].legend(fontsize=7, ncol=2)
    fig.suptitle(f"{title}: dotted line, the accuracy the ratio is taken at", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def run(out, quick: bool = False) -> str:
    """Measure every problem, write the PNGs and ``bench_work_precision.json`` into ``out``."""
    budget = 1.0 if quick else 5.0
    results, lines = {}, ["# bench_work_precision", "", f"{machine()}; one timed batch of calls per point "
                          f"(budget {budget:g} s a call), errors against scipy DOP853 rtol 1e-13.", "",
                          "| problem | figure | methods (points) |", "|---|---|---|"]
    for key, p in problems(quick).items():
        print(f"bench_work_precision: {p.name}", file=sys.stderr, flush=True)
        try:
            series = measure(p, budget)
        except Exception as exc:  # noqa: BLE001 - one problem's failure is reported, the others still drawn
            lines.append(f"| {p.name} | **failed**: {type(exc).__name__}: {exc} | - |")
            print(f"bench_work_precision: {p.name} FAILED: {exc!r}", file=sys.stderr, flush=True)
            continue
        results[key] = {"name": p.name, "target": p.target, "series": series}
        png = out / f"work_precision_{key}.png"
        figure(png, p.name, p.target, series)
        lines.append(f"| {p.name} | {png.name} | " + ", ".join(f"{n} ({len(s)})" for n, s in series.items()) + " |")
    (out / "bench_work_precision.json").write_text(json.dumps(results, indent=2) + "\n")
    return "\n".join(lines) + "\n"
