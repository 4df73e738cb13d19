"""The absolute inertia tensor from throws with the flywheel device (issues #30, #42): one throw
fitted, and 12 throws pooled.

The targets of issue #42 (in-process, on this machine's 2 cores): one throw of an object with the
real device (:func:`tumble.analysis.tensor.synthetic.synthetic_throw`: 4 kHz, a hand-held swing,
the fingers' touch, the firmware's idle, spin-up and brake, the log ending in flight, one
device's imperfections) fitted by :func:`tumble.fit_tensor` in at most 1 s; 12 such throws
(seeds 3000-3011) fitted jointly in at most 10 s. The throws are made before the clock starts (making them is not the fit). One
throw: each of the 12 throws fitted alone once, the median and the range over the throws (a
fit's time depends on the throw; benchmarks/tensor_coverage.py sees a tail over random
objects). Pooled: the median of a few repeats, the range in brackets. Beside each wall-clock
time, the CPU seconds the process used (``time.process_time``, all its threads): on a machine
that others load, the wall clock measures them too, the CPU time what the fit costs. Also reported: the pooled
principal moments against the truth, and the whole ``tumble tensor`` command on the 12 throws'
files in a fresh process (reading, fitting, tensor.json and tensor.png).

Run: ``python benchmarks/bench_tensor.py [--quick]`` or ``python benchmarks/run.py --suite bench_tensor``.
"""

from __future__ import annotations

import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from tumble.analysis.tensor import fit_tensor
from tumble.analysis.tensor.synthetic import box, calibrated_device, combine, synthetic_throw, true_device
from tumble.io.devicefile import write_device
from tumble.io.throwfile import write_throw

TARGET_ONE = 1.0
TARGET_POOLED = 10.0
THROWS = 12
#: The object: a 0.482 kg aluminium bracket-like box 16 x 9 x 4 cm, turned and off the sensor.
OBJECT = dict(mass=0.482, size=(0.16, 0.09, 0.04), center=(0.012, -0.008, 0.035), rotvec=(0.2, -0.1, 0.35))


def _setup(n: int):
    obj = box(**OBJECT)
    flown = combine(true_device(), obj)
    throws = [synthetic_throw(3000 + k, flown, input=f"o{k + 1}.csv") for k in range(n)]
    return obj, calibrated_device(), throws


def _timed(fn):
    """``(wall seconds, CPU seconds of this process, value)`` of ``fn()``."""
    t0, c0 = time.perf_counter(), time.process_time()
    value = fn()
    return time.perf_counter() - t0, time.process_time() - c0, value


def _command(throws, device, folder: Path) -> float:
    """Seconds of ``python -m tumble tensor ...`` in a fresh process, on the throws' files."""
    paths = [str(write_throw(folder / th.input, th)) for th in throws]
    dev = write_device(folder / "calibrated.toml", device)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "tumble", "tensor", *paths, "--device", str(dev), "--mass",
                    repr(OBJECT["mass"]), "--out", str(folder / f"out{time.monotonic_ns()}"), "--accept-inadequate"],
                   check=True, capture_output=True)
    return time.perf_counter() - t0


def run(out, quick: bool = False) -> str:
    repeat = 1 if quick else 3
    n = 4 if quick else THROWS
    load = os.getloadavg()[0]  # the machine is shared: say how busy it was
    obj, device, throws = _setup(n)
    fit_tensor(throws[:1], device, OBJECT["mass"])  # first call (imports, compiled kernels), not timed
    # one throw: each of the n throws fitted alone (a fit's time depends on the throw), median and range
    one = [_timed(lambda: fit_tensor([th], device, OBJECT["mass"]))[:2] for th in throws]
    one_times, one_cpu = [w for w, _ in one], [c for _, c in one]
    pooled_times, pooled_cpu = [], []
    for _ in range(repeat):
        seconds, cpu, pooled = _timed(lambda: fit_tensor(throws, device, OBJECT["mass"]))
        pooled_times.append(seconds)
        pooled_cpu.append(cpu)
    with tempfile.TemporaryDirectory() as folder:
        command = _command(throws, device, Path(folder))
    truth = np.linalg.eigvalsh(obj.inertia)
    p = pooled.object
    error = (p.principal_moments - truth) / truth
    used = sum(t.status == "used" for t in pooled.throws)
    one_med, pooled_med = float(np.median(one_times)), float(np.median(pooled_times))
    rows = [{"case": f"one throw fitted (fit_tensor), each of the {n} throws alone: median [fastest-slowest]",
             "seconds": one_med, "range": [min(one_times), max(one_times)], "target_seconds": TARGET_ONE,
             "cpu_seconds": float(np.median(one_cpu)), "cpu_range": [min(one_cpu), max(one_cpu)]},
            {"case": f"{n} throws fitted and pooled (fit_tensor)", "seconds": pooled_med,
             "range": [min(pooled_times), max(pooled_times)], "target_seconds": TARGET_POOLED if n == THROWS else None,
             "cpu_seconds": float(np.median(pooled_cpu)), "cpu_range": [min(pooled_cpu), max(pooled_cpu)],
             "throws_used": used, "principal_moments": p.principal_moments.tolist(),
             "principal_moments_std": p.principal_moments_std.tolist(), "truth": truth.tolist(),
             "relative_error": error.tolist(), "chi2_dof": float(pooled.chi2_dof), "adequate": bool(pooled.adequate)},
            {"case": f"tumble tensor on {n} throw files, a fresh process (one run)", "seconds": command}]
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "bench_tensor.json").write_text(json.dumps(rows, indent=2) + "\n")

    def met(seconds, target):
        return "" if target is None else ("yes" if seconds <= target else "NO")

    lines = ["# bench_tensor", "", f"Python {platform.python_version()} on {platform.machine()}, {os.cpu_count()} cores "
             f"(load average {load:.1f} at the start, {os.getloadavg()[0]:.1f} at the end); one throw: each throw fitted once, the median over the throws; "
             f"pooled: the median over {repeat} repeats; ranges in brackets; the throws made before the clock starts.",
             "",
             "| case | time (s) | CPU (s) | target (s) | met (wall clock) | met (CPU) |", "|---|---|---|---|---|---|"]
    for row in rows:
        rng = f" [{row['range'][0]:.3g}-{row['range'][1]:.3g}]" if "range" in row else ""
        cpu = f"{row['cpu_seconds']:.3g} [{row['cpu_range'][0]:.3g}-{row['cpu_range'][1]:.3g}]" if "cpu_seconds" in row else ""
        target = row.get("target_seconds")
        lines.append(f"| {row['case']} | {row['seconds']:.3g}{rng} | {cpu} | {'' if target is None else f'{target:g}'} | "
                     f"{met(row['seconds'], target)} | {met(row['cpu_seconds'], target) if cpu else ''} |")
    lines += ["", f"Pooled principal moments {', '.join(f'{x:.5g} +- {s:.2g}' for x, s in zip(p.principal_moments, p.principal_moments_std))} "
              f"kg m^2 from {used} of {n} throws (true {', '.join(f'{x:.5g}' for x in truth)}; relative errors "
              f"{', '.join(f'{100 * e:+.2f} %' for e in error)}; chi2/dof {pooled.chi2_dof:.2g})."]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    quick = "--quick" in sys.argv[1:]  # a quick run never overwrites the full results
    results = Path(__file__).resolve().parent / "results"
    print(run(results / "quick" if quick else results, quick=quick), end="")
