"""Run every benchmark: ``make bench`` (or ``python benchmarks/run.py [--quick]``).

Each case is timed beside a baseline measured in the same run and reported as a ratio, plus
the absolute numbers the issues' targets name. Results go to ``benchmarks/results/<name>.md``
and ``.json`` (and figures); ``docs/benchmarks.md`` summarises them. ``--quick`` writes to
``benchmarks/results/quick/`` (not tracked) instead.
"""

from __future__ import annotations

import argparse
import importlib
import json
import platform
import sys
import timeit
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
SUITES = ["bench_mass", "bench_dynamics", "bench_engine", "bench_models", "bench_closed_loop", "bench_call",
          "bench_work_precision", "bench_batch", "bench_torqued", "bench_exact_split", "bench_sweep", "bench_fit", "bench_pool", "bench_tensor",
          "bench_basilisk", "bench_basilisk_control", "bench_detumble_mc", "bench_knowledge", "bench_first_call",
          "bench_free_loop"]


def _per_call(timer: timeit.Timer, number: int) -> float:
    return timer.timeit(number=number) / number


def paired_times(candidate, baseline, repeat: int) -> dict:
    """Time candidate and baseline in alternation, ``repeat`` times each (``timeit``'s autorange
    picks the number of calls per repeat), so a load that comes and goes hits both alike.

    Returns the medians and ranges (s) and the median of the per-repeat ratios.
    """
    timers = [timeit.Timer(candidate), timeit.Timer(baseline)]
    numbers = [t.autorange()[0] for t in timers]
    pairs = [tuple(_per_call(t, n) for t, n in zip(timers, numbers)) for _ in range(repeat)]
    cand, base = (np.array(x) for x in zip(*pairs))
    return {
        "seconds": float(np.median(cand)), "seconds_range": [float(cand.min()), float(cand.max())],
        "baseline_seconds": float(np.median(base)), "baseline_range": [float(base.min()), float(base.max())],
        "ratio": float(np.median(cand / base)), "ratio_range": [float((cand / base).min()), float((cand / base).max())],
        "repeats": repeat,
    }


def run_suite(name: str, repeat: int) -> list[dict]:
    module = importlib.import_module(name)
    rows = []
    for title, candidate, baseline, baseline_name, target in module.cases():
        stats = paired_times(candidate, baseline, repeat)
        rows.append({
            "case": title, "baseline": baseline_name, **stats, "target_seconds": target,
            "meets_target": None if target is None else bool(stats["seconds"] <= target),
        })
    return rows


def _ms(x: float) -> str:
    return f"{x * 1e3:.3g}"


def to_markdown(name: str, rows: list[dict]) -> str:
    lines = [
        f"# {name}", "", f"Python {platform.python_version()} on {platform.machine()}, {platform.node()}; "
        f"medians over {rows[0]['repeats'] if rows else 0} alternating repeats, range in brackets", "",
        "| case | time (ms) | baseline | baseline time (ms) | ratio | target | met (median) |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        target = "-" if r["target_seconds"] is None else f"{r['target_seconds'] * 1e3:.3g} ms"
        met = "-" if r["meets_target"] is None else ("yes" if r["meets_target"] else "NO")
        lo, hi = r["seconds_range"]
        blo, bhi = r["baseline_range"]
        rlo, rhi = r["ratio_range"]
        lines.append(
            f"| {r['case']} | {_ms(r['seconds'])} [{_ms(lo)}-{_ms(hi)}] | {r['baseline']} "
            f"| {_ms(r['baseline_seconds'])} [{_ms(blo)}-{_ms(bhi)}] | {r['ratio']:.3g} [{rlo:.3g}-{rhi:.3g}] "
            f"| {target} | {met} |"
        )
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="fewer repeats")
    parser.add_argument("--suite", action="append", choices=SUITES, help="run only these suites")
    args = parser.parse_args(argv)
    # a quick run is a smoke test: it never overwrites the full results that docs/ quotes
    out = HERE / "results" / "quick" if args.quick else HERE / "results"
    out.mkdir(parents=True, exist_ok=True)
    sys.path.insert(0, str(HERE))
    from _harness import peers

    peers()  # the shared reference peers, unchanged: a clear error here if they are missing
    for name in args.suite or SUITES:
        module = importlib.import_module(name)
        if hasattr(module, "run"):  # a suite that measures and tabulates itself
            text = module.run(out, quick=args.quick)
        else:
            rows = run_suite(name, repeat=3 if args.quick else 15)
            text = to_markdown(name, rows)
            (out / f"{name}.json").write_text(json.dumps(rows, indent=2) + "\n")
        print(text)
        (out / f"{name}.md").write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
