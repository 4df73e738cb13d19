"""The first torque ``simulate`` in a fresh environment (issue 40 item 6: <= 3 s): what a new user
waits for the first time, numba compiling the engine's kernel included.

Each repeat copies the installed package's sources (no numba cache beside them: ``*.nbi`` and
``*.nbc`` left out) into a new temporary folder and runs, in a new process with ``NUMBA_CACHE_DIR``
pointed at an empty folder of its own, ``import tumble`` and then a 20 s run of a body with a
constant torque, ``method`` left to ``"auto"`` (``rk8`` here). The wall and CPU seconds of the
import and of the call are taken inside that process (``time.perf_counter``, ``time.process_time``),
so the interpreter's own start is not counted. Then the same call again, warm.
"""

from __future__ import annotations

import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import tumble

TARGET_S = 3.0

#: What the fresh process runs: the numbers it prints are JSON.
SCRIPT = """
import json, time
t0, c0 = time.perf_counter(), time.process_time()
import tumble
t1, c1 = time.perf_counter(), time.process_time()
body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])
torque = tumble.ConstantTorque([0.01, -0.02, 0.015])
run = tumble.simulate(body, [0.1, 5.0, 0.1], t_end=20.0, torque=torque)
t2, c2 = time.perf_counter(), time.process_time()
tumble.simulate(body, [0.1, 5.0, 0.1], t_end=20.0, torque=torque)
t3 = time.perf_counter()
print(json.dumps({"import_wall": t1 - t0, "import_cpu": c1 - c0, "first_wall": t2 - t1, "first_cpu": c2 - c1,
                  "warm_wall": t3 - t2, "method": run.method}))
"""


def one_fresh_run() -> dict:
    """The first call in a new process on a copy of the sources with no compiled kernels."""
    package = Path(tumble.__file__).resolve().parent
    with tempfile.TemporaryDirectory() as folder:
        copy = Path(folder) / "src" / "tumble"
        shutil.copytree(package, copy, ignore=shutil.ignore_patterns("*.nbi", "*.nbc"))
        cache = Path(folder) / "numba-cache"
        cache.mkdir()
        env = {**os.environ, "PYTHONPATH": str(copy.parent), "NUMBA_CACHE_DIR": str(cache)}
        proc = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True, env=env, cwd=folder,
                              check=True)
        return json.loads(proc.stdout.strip().splitlines()[-1])


def run(out, quick: bool = False) -> str:
    """Measure, write ``bench_first_call.json`` into ``out``, return the markdown."""
    repeat = 2 if quick else 5
    runs = [one_fresh_run() for _ in range(repeat)]
    keys = ("import_wall", "import_cpu", "first_wall", "first_cpu", "warm_wall")
    summary = {k: {"median": statistics.median(r[k] for r in runs), "min": min(r[k] for r in runs),
                   "max": max(r[k] for r in runs)} for k in keys}
    total = statistics.median(r["import_wall"] + r["first_wall"] for r in runs)
    result = {"repeats": repeat, "runs": runs, "summary": summary, "import_and_first_wall": total,
              "target_seconds": TARGET_S, "meets_target": bool(total <= TARGET_S), "method": runs[0]["method"]}
    (out / "bench_first_call.json").write_text(json.dumps(result, indent=2) + "\n")
    lines = ["# bench_first_call", "",
             f"{repeat} fresh processes, each on a copy of the sources with no numba cache (module docstring); "
             "medians [min-max].", "",
             "| | wall (s) | CPU (s) |", "|---|---|---|"]
    for label, wall, cpu in (("import tumble", "import_wall", "import_cpu"),
                             (f"first simulate with a torque ({result['method']}, 20 s)", "first_wall", "first_cpu")):
        w, c = summary[wall], summary[cpu]
        lines.append(f"| {label} | {w['median']:.2f} [{w['min']:.2f}-{w['max']:.2f}] "
                     f"| {c['median']:.2f} [{c['min']:.2f}-{c['max']:.2f}] |")
    w = summary["warm_wall"]
    lines += [f"| the same call again, warm | {w['median'] * 1e3:.2f} ms [{w['min'] * 1e3:.2f}-{w['max'] * 1e3:.2f}] | |",
              "", f"Import and first call: {total:.2f} s wall (median); target <= {TARGET_S:g} s: "
              f"{'met' if result['meets_target'] else '**not met**'}."]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    print(run(Path(tempfile.mkdtemp()), quick="--quick" in sys.argv))
