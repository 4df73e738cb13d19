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

HERE = Path(__file__).resolve().parent
SUITES = ["bench_mass", "bench_dynamics"]


def best_time(fn, repeat: int) -> float:
    timer = timeit.Timer(fn)
    number, _ = timer.autorange()
    return min(timer.repeat(repeat=repeat, number=number)) / number


def run_suite(name: str, repeat: int) -> list[dict]:
    module = importlib.import_module(name)
    rows = []
    for title, candidate, baseline, baseline_name, target in module.cases():
        t_c, t_b = best_time(candidate, repeat), best_time(baseline, repeat)
        rows.append({
            "case": title, "seconds": t_c, "baseline": baseline_name, "baseline_seconds": t_b,
            "ratio": t_c / t_b, "target_seconds": target,
            "meets_target": None if target is None else bool(t_c <= target),
        })
    return rows


def to_markdown(name: str, rows: list[dict]) -> str:
    lines = [
        f"# {name}", "", f"Python {platform.python_version()} on {platform.machine()}, {platform.node()}", "",
        "| case | time | baseline | baseline time | ratio | target | met |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        target = "-" if r["target_seconds"] is None else f"{r['target_seconds'] * 1e3:.3g} ms"
        met = "-" if r["meets_target"] is None else ("yes" if r["meets_target"] else "NO")
        lines.append(
            f"| {r['case']} | {r['seconds'] * 1e3:.4g} ms | {r['baseline']} | {r['baseline_seconds'] * 1e3:.4g} ms "
            f"| {r['ratio']:.3g} | {target} | {met} |"
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
    for name in args.suite or SUITES:
        module = importlib.import_module(name)
        if hasattr(module, "run"):  # a suite that measures and tabulates itself
            text = module.run(out, quick=args.quick)
        else:
            rows = run_suite(name, repeat=3 if args.quick else 7)
            text = to_markdown(name, rows)
            (out / f"{name}.json").write_text(json.dumps(rows, indent=2) + "\n")
        print(text)
        (out / f"{name}.md").write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
