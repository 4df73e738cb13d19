"""The first torque ``simulate`` in a fresh environment (issue 40 item 6: <= 3 s): what a new user
waits for the first time, numba compiling the engine's kernel included.

Each repeat copies the installed package's sources (no numba cache beside them: ``*.nbi`` and
``*.nbc`` left out) into a new temporary folder and runs, in a new process with ``NUMBA_CACHE_DIR``
pointed at an empty folder of its own, ``import tumble`` and then one first call with a torque,
``method`` left to ``"auto"``: each of :data:`CASES` (a 20 s run of a spinning body, where ``auto``
takes ``rk8``; the tour's first torque call, a T-handle spun up from rest for 5 s, where it takes
``dop853``, whose kernel compiles longer; one orbit of an ellipse's gravity gradient, which compiles
the closed loop's kernel, the longest). The wall and CPU seconds of the import and of the call
are taken inside that process (``time.perf_counter``, ``time.process_time``), so the interpreter's
own start is not counted. Then the same call again, warm.

Each case is measured twice: on a fresh copy as it is, and on a fresh copy after ``tumble compile
GROUP`` (:data:`GROUPS`: the group of kernels that the case's first call uses, compiled ahead in a
process of its own, as the README's install lines do), whose first call then loads its kernels
from numba's cache.
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

#: The first calls measured: label -> the statements that make ``call`` (after ``import tumble``).
CASES = {
    "a body spinning at 5 rad/s, constant torque, 20 s": (
        "body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])\n"
        "call = lambda: tumble.simulate(body, [0.1, 5.0, 0.1], t_end=20.0, "
        "torque=tumble.ConstantTorque([0.01, -0.02, 0.015]))"),
    "the tour's: a T-handle spun up from rest, 5 s (docs/tour.md)": (
        "body = tumble.t_handle()\n"
        "call = lambda: tumble.simulate(body, [0, 0, 0], t_end=5.0, torque=tumble.ConstantTorque((0.0, 0.0, 0.01)))"),
    "the gravity gradient along an ellipse, one orbit (the closed loop's kernel, dynamics/control/free_loop.py)": (
        "from tumble.dynamics import KeplerOrbit, OrbitGravityGradient\n"
        "body = tumble.MassProperties.from_moments([10.0, 12.0, 15.0])\n"
        "orbit = KeplerOrbit(8000e3, 0.1)\n"
        "call = lambda: tumble.simulate(body, [0.05, 0.1, 0.02], t_end=orbit.period, torque=OrbitGravityGradient(orbit))"),
}

#: The group of ``tumble compile`` that holds each case's kernels.
GROUPS = dict(zip(CASES, ("simulate", "simulate", "orbit")))

#: What the fresh process runs (CASE: one of :data:`CASES`): the numbers it prints are JSON.
SCRIPT = """
import json, time
t0, c0 = time.perf_counter(), time.process_time()
import tumble
t1, c1 = time.perf_counter(), time.process_time()
CASE
run = call()
t2, c2 = time.perf_counter(), time.process_time()
call()
t3 = time.perf_counter()
print(json.dumps({"import_wall": t1 - t0, "import_cpu": c1 - c0, "first_wall": t2 - t1, "first_cpu": c2 - c1,
                  "warm_wall": t3 - t2, "method": run.method}))
"""


def one_fresh_run(case: str, ahead: bool = False) -> dict:
    """The first call of ``case`` (:data:`CASES`) in a new process on a copy of the sources with no
    compiled kernels; ``ahead``: after ``tumble compile`` of the case's group (:data:`GROUPS`)."""
    package = Path(tumble.__file__).resolve().parent
    with tempfile.TemporaryDirectory() as folder:
        copy = Path(folder) / "src" / "tumble"
        shutil.copytree(package, copy, ignore=shutil.ignore_patterns("*.nbi", "*.nbc"))
        cache = Path(folder) / "numba-cache"
        cache.mkdir()
        env = {**os.environ, "PYTHONPATH": str(copy.parent), "NUMBA_CACHE_DIR": str(cache)}
        if ahead:
            subprocess.run([sys.executable, "-m", "tumble", "compile", GROUPS[case]], capture_output=True, env=env,
                           cwd=folder, check=True)
        proc = subprocess.run([sys.executable, "-c", SCRIPT.replace("CASE", CASES[case])], capture_output=True, text=True, env=env, cwd=folder,
                              check=True)
        return json.loads(proc.stdout.strip().splitlines()[-1])


def run(out, quick: bool = False) -> str:
    """Measure, write ``bench_first_call.json`` into ``out``, return the markdown."""
    repeat = 2 if quick else 5
    keys = ("import_wall", "import_cpu", "first_wall", "first_cpu", "warm_wall")
    lines = ["# bench_first_call", "",
             f"{repeat} fresh processes a case, each on a copy of the sources with no numba cache (module "
             "docstring), then as many after `tumble compile GROUP` on such a copy; the cases alternating; "
             "medians [min-max].", "",
             "| case | kernels | import tumble, wall (s) | first call, wall (s) | first call, CPU (s) | the same call warm |",
             "|---|---|---|---|---|---|"]
    variants = [(case, ahead) for case in CASES for ahead in (False, True)]
    runs: dict[tuple[str, bool], list[dict]] = {variant: [] for variant in variants}
    for _ in range(repeat):
        for case, ahead in variants:
            runs[case, ahead].append(one_fresh_run(case, ahead))
    result: dict = {"repeats": repeat, "target_seconds": TARGET_S, "cases": {}}
    for (case, ahead), got in runs.items():
        summary = {k: {"median": statistics.median(r[k] for r in got), "min": min(r[k] for r in got),
                       "max": max(r[k] for r in got)} for k in keys}
        total = statistics.median(r["import_wall"] + r["first_wall"] for r in got)
        how = f"after tumble compile {GROUPS[case]}" if ahead else "compiled at the call"
        result["cases"][f"{case}, {how}"] = {"runs": got, "summary": summary, "import_and_first_wall": total,
                                             "meets_target": bool(total <= TARGET_S), "method": got[0]["method"],
                                             "compiled_ahead": ahead}
        i, w, c, warm = (summary[k] for k in ("import_wall", "first_wall", "first_cpu", "warm_wall"))
        lines.append(f"| {case} ({got[0]['method']}) | {how} | {i['median']:.2f} | {w['median']:.2f} "
                     f"[{w['min']:.2f}-{w['max']:.2f}] | {c['median']:.2f} [{c['min']:.2f}-{c['max']:.2f}] "
                     f"| {warm['median'] * 1e3:.2f} ms |")
    result["meets_target"] = all(c["meets_target"] for c in result["cases"].values() if c["compiled_ahead"])
    (out / "bench_first_call.json").write_text(json.dumps(result, indent=2) + "\n")
    lines += ["", f"Import and first call, target <= {TARGET_S:g} s: " + "; ".join(
        f"{case}: {c['import_and_first_wall']:.2f} s, {'met' if c['meets_target'] else '**not met**'}"
        for case, c in result["cases"].items()) + "."]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    print(run(Path(tempfile.mkdtemp()), quick="--quick" in sys.argv))
