"""The absolute tensor on the realistic device (issue #42): windows, accuracy, coverage, calibration.

``python benchmarks/tensor_coverage.py [OBJECTS] [--per-device N] [--jobs J] [--json FILE]``

Each **device** is the synthetic device of :mod:`tumble.analysis.tensor.synthetic` with its own
imperfections drawn (:func:`~tumble.analysis.tensor.firmware.draw_imperfections`: the
gyroscope's scale factors and misalignment, the rotor's axis off its nominal) and is
**calibrated from its own realistic throws** (5 of the device alone, 5 with the proof body:
:func:`tumble.analysis.tensor.calibrate.calibrate`). Each **object** (a random box,
:func:`~tumble.analysis.tensor.synthetic.random_object`) is thrown 3 times with one of the
devices (``--per-device`` objects a device, default 4) and fitted with :func:`tumble.fit_tensor`.
Every throw is the real device's (:func:`~tumble.analysis.tensor.synthetic.synthetic_throw`:
the firmware's idle, spin-up and brake, the log ending in flight, the fingers' touch after the
sensed release, the accelerometer's jolts and smoothing, eRPM quantisation, the rotor log's lag,
the rotor's air drag, the sensors' noise, bias and range).

Reported against the issue's targets:

- the fitted window's end within 10 ms of the log's end, its start within 10 ms after the true
  release (0 to +10 ms);
- the object's principal moments: median relative error of single throws (each throw's own
  estimate) and pooled; the share of 95 % intervals (``|error| <= 1.96 std``) holding the truth,
  single and pooled, with the binomial standard error; the pooled std relative to the moment;
- the object's centre of mass: its error and its 95 % intervals' coverage;
- the calibration: the rotor inertia's relative error, its 95 % interval's coverage, and the
  calibration's own checks (how many devices it flagged);
- time: one throw's fit and 3 pooled (``time.perf_counter``, in a worker process).

Writes ``benchmarks/results/tensor_coverage.md`` (and the raw numbers as JSON with ``--json``).
"""

from __future__ import annotations

import argparse
import json
import os
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

THROWS = 3
CAL_THROWS = 5


def _device_task(args: tuple[int, int]) -> dict:
    """One device calibrated from its throws, and its objects fitted."""
    from tumble.analysis.tensor import Device, fit_tensor
    from tumble.analysis.tensor.calibrate import calibrate
    from tumble.analysis.tensor.firmware import draw_imperfections
    from tumble.analysis.tensor.synthetic import (DEVICE_MASS, ROTOR_AXIS, ROTOR_INERTIA, combine, random_object,
                                                  synthetic_throw, throw_times, true_device, true_proof)

    index, per_device = args
    rng = np.random.default_rng(70_000 + index)
    imp = draw_imperfections(rng, ROTOR_AXIS)
    proof, placed = true_proof()
    seeds = 1_000_000 + 1000 * index
    alone = [synthetic_throw(seeds + k, true_device(), spin=(3.0, 8.0), imperfections=imp, input=f"a{k}")
             for k in range(CAL_THROWS)]
    with_proof = [synthetic_throw(seeds + 100 + k, combine(true_device(), placed), imperfections=imp, input=f"p{k}")
                  for k in range(CAL_THROWS)]
    t0 = time.perf_counter()
    cal = calibrate(Device(DEVICE_MASS, ROTOR_AXIS), alone, with_proof, proof)
    cal_time = time.perf_counter() - t0
    J, J_std = cal.device.rotor_inertia, cal.device.rotor_inertia_std
    out = {"device": index, "cal_problems": list(cal.problems), "cal_chi2": cal.chi2_dof,
           "cal_alone_chi2": cal.alone_chi2_dof, "cal_proof_chi2": cal.proof_chi2_dof, "cal_time": cal_time,
           "J_err": (J / ROTOR_INERTIA - 1) if J else None, "J_rel_std": (J_std / J) if J else None,
           "objects": []}
    if cal.device.rotor_inertia is None:
        return out
    for j in range(per_device):
        orng = np.random.default_rng(80_000 + index * 100 + j)
        obj = random_object(orng)
        flown = combine(true_device(), obj)
        oseeds = [seeds + 200 + 10 * j + k for k in range(THROWS)]
        logs = [synthetic_throw(s, flown, imperfections=imp, input=f"o{k}") for k, s in enumerate(oseeds)]
        t0 = time.perf_counter()
        try:
            fit = fit_tensor(logs, cal.device, obj.mass)
        except ValueError as err:
            out["objects"].append({"failed": str(err)})
            continue
        pooled_time = time.perf_counter() - t0
        truth = np.linalg.eigvalsh(obj.inertia)
        rows = []
        for row, s, log in zip(fit.throws, oseeds, logs):
            tt = throw_times(s)
            r = {"status": row.status, "reason": row.reason,
                 "start_ms": 1e3 * (row.t_release - tt.release) if np.isfinite(row.t_release) else None,
                 "end_ms": 1e3 * (row.t_end - float(log.t[-1])) if np.isfinite(row.t_end) else None}
            if row.object is not None:
                r["err"] = (row.object.principal_moments / truth - 1).tolist()
                r["z"] = ((row.object.principal_moments - truth) / row.object.principal_moments_std).tolist()
            rows.append(r)
        m, sd = fit.object.principal_moments, fit.object.principal_moments_std
        out["objects"].append({"throws": rows, "err": (m / truth - 1).tolist(), "rel_std": (sd / m).tolist(),
                               "z": ((m - truth) / sd).tolist(), "chi2": fit.chi2_dof, "time": pooled_time,
                               "com_err_mm": (1e3 * (fit.object.center_of_mass - obj.center)).tolist(),
                               "com_z": ((fit.object.center_of_mass - obj.center)
                                         / fit.object.center_of_mass_std).tolist()})
    one = [synthetic_throw(seeds + 999, combine(true_device(), random_object(rng)), imperfections=imp)]
    t0 = time.perf_counter()
    try:
        fit_tensor(one, cal.device, 0.5)
    except ValueError:
        pass
    out["one_time"] = time.perf_counter() - t0
    return out


def share(x) -> str:
    x = np.asarray(x, bool)
    if x.size == 0:
        return "n/a"
    p = float(np.mean(x))
    return f"{100 * p:.1f} % +- {100 * np.sqrt(p * (1 - p) / x.size):.1f} (of {x.size})"


def table(results: list[dict], seconds: float) -> str:
    objs = [o for r in results for o in r["objects"] if "err" in o]
    failed = [o["failed"] for r in results for o in r["objects"] if "failed" in o]
    throws = [t for o in objs for t in o["throws"]]
    used = [t for t in throws if "err" in t]
    ends = np.array([abs(t["end_ms"]) <= 10 for t in throws if t["end_ms"] is not None])
    starts = np.array([0 <= t["start_ms"] <= 10 for t in throws if t["start_ms"] is not None])
    start_ms = np.array([t["start_ms"] for t in throws if t["start_ms"] is not None])
    single = np.abs(np.array([t["err"] for t in used]))
    single_z = np.abs(np.array([t["z"] for t in used]))
    pooled = np.abs(np.array([o["err"] for o in objs]))
    pooled_z = np.abs(np.array([o["z"] for o in objs]))
    rel_std = np.array([o["rel_std"] for o in objs])
    J_err = np.array([r["J_err"] for r in results if r["J_err"] is not None])
    J_std = np.array([r["J_rel_std"] for r in results if r["J_err"] is not None])
    flagged = [r for r in results if r["cal_problems"]]
    one = np.array([r["one_time"] for r in results if "one_time" in r])
    pooled_t = np.array([o["time"] for o in objs])

    def row(name, values, fmt="{:.2f} %", scale=100.0):
        return f"| {name} | " + " | ".join(fmt.format(scale * v) for v in values) + " |"

    lines = [
        "# tensor_coverage: the object's tensor on the realistic device (issue #42)",
        "",
        f"{len(results)} devices, each with its imperfections drawn and calibrated from its own {CAL_THROWS} + "
        f"{CAL_THROWS} realistic throws; {len(objs)} objects x {THROWS} throws fitted ({len(failed)} objects failed); "
        f"{len(used)} of {len(throws)} throws used. {seconds:.0f} s.",
        "",
        "## Windows",
        f"- end within 10 ms of the log's end: {share(ends)}",
        f"- start within 0-10 ms after the true release: {share(starts)} (median {np.median(start_ms):+.1f} ms, "
        f"range {start_ms.min():+.1f} to {start_ms.max():+.1f} ms)",
        "",
        "## The object's principal moments",
        "| quantity | I1 | I2 | I3 |",
        "|---|---|---|---|",
        row("median relative error, single throws", np.median(single, axis=0)),
        row("median relative error, pooled (3 throws)", np.median(pooled, axis=0)),
        row("90th percentile, pooled", np.percentile(pooled, 90, axis=0)),
        row("median pooled std / moment", np.median(rel_std, axis=0)),
        row("95th percentile pooled std / moment", np.percentile(rel_std, 95, axis=0)),
        "| single 95 % intervals hold | " + " | ".join(share(single_z[:, i] <= 1.96) for i in range(3)) + " |",
        "| pooled 95 % intervals hold | " + " | ".join(share(pooled_z[:, i] <= 1.96) for i in range(3)) + " |",
        "",
        f"All moments: single intervals hold {share(single_z.ravel() <= 1.96)}; pooled {share(pooled_z.ravel() <= 1.96)}.",
        f"The object's centre of mass (3 throws): median |error| "
        f"{np.median(np.abs([o['com_err_mm'] for o in objs])):.2f} mm, 90th percentile "
        f"{np.percentile(np.abs([o['com_err_mm'] for o in objs]), 90):.2f} mm; its components' 95 % intervals hold "
        f"{share(np.abs(np.array([o['com_z'] for o in objs])).ravel() <= 1.96)}.",
        f"Median chi2/dof of the throws about the joint fit: {np.nanmedian([o['chi2'] for o in objs]):.2f}.",
        "",
        "## Calibration",
        f"- rotor inertia: median |error| {100 * np.median(np.abs(J_err)):.2f} %, max {100 * np.max(np.abs(J_err)):.2f} %; "
        f"median stated std {100 * np.median(J_std):.2f} %; 95 % interval holds {share(np.abs(J_err) <= 1.96 * J_std)}; "
        f"within 1 %: {share(np.abs(J_err) <= 0.01)}",
        f"- flagged by its own checks: {len(flagged)} of {len(results)}"
        + "".join(f"\n  - device {r['device']}: {'; '.join(r['cal_problems'])}" for r in flagged),
        f"- chi2/dof of the parallel-axis equations: median {np.median([r['cal_chi2'] for r in results]):.2f}, max "
        f"{np.max([r['cal_chi2'] for r in results]):.2f}; of the sets about their joint fits: alone median "
        f"{np.nanmedian([r['cal_alone_chi2'] for r in results]):.2f} (max {np.nanmax([r['cal_alone_chi2'] for r in results]):.2f}), "
        f"proof median {np.nanmedian([r['cal_proof_chi2'] for r in results]):.2f} "
        f"(max {np.nanmax([r['cal_proof_chi2'] for r in results]):.2f})",
        "",
        "## Time (a worker process, 2 in parallel on this machine)",
        f"- one throw's fit_tensor: median {np.median(one):.2f} s (max {one.max():.2f} s)",
        f"- 3 throws pooled: median {np.median(pooled_t):.2f} s (max {pooled_t.max():.2f} s)",
        f"- a calibration of {2 * CAL_THROWS} throws: median {np.median([r['cal_time'] for r in results]):.2f} s",
        "",
    ]
    if failed:
        lines += ["Objects that failed:", *[f"- {f}" for f in failed], ""]
    left = [t["reason"] for t in throws if t["status"] != "used"]
    if left:
        lines += ["Throws left out:", *[f"- {why}" for why in left], ""]
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("objects", nargs="?", type=int, default=100)
    parser.add_argument("--per-device", type=int, default=4)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--json", type=Path)
    args = parser.parse_args()
    devices = -(-args.objects // args.per_device)
    t0 = time.perf_counter()
    out = Path(__file__).parent / "results" / "tensor_coverage.md"
    with ProcessPoolExecutor(args.jobs) as pool:
        results = []
        for r in pool.map(_device_task, [(k, args.per_device) for k in range(devices)]):
            results.append(r)
            print(f"device {r['device']}: J_r {100 * (r['J_err'] or 0):+.2f} %, objects "
                  + ", ".join(f"{np.round(100 * np.array(o['err']), 2).tolist()}" if 'err' in o else "failed"
                              for o in r["objects"]), flush=True)
            if len(results) < devices and any(o.get("err") for o in r["objects"]):  # a slow run leaves what it has
                out.write_text(f"**Partial: {len(results)} of {devices} devices so far.**\n\n"
                               + table(results, time.perf_counter() - t0))
                if args.json:
                    args.json.write_text(json.dumps(results, indent=1))
    text = table(results, time.perf_counter() - t0)
    print(text)
    out.write_text(text)
    if args.json:
        args.json.write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
