"""tumble's engine against the simplest competent alternative, 40 lines of numba, at equal accuracy.

The engine issue's targets (issue 31), measured as a sceptic would:

- **One body, 20 s, 101 samples**, the four Basilisk cases of ``bench_basilisk`` (a spacecraft
  (10, 12, 15) kg m^2 at 1 rad/s and the seed's T-handle at 10 rad/s, each under the constant
  body torque (0.01, -0.02, 0.015) N m and under the gravity gradient of a 5400 s circular orbit),
  at omega error <= 2e-9 (relative to max |omega|) AND attitude error <= 2e-8 rad:
  ``tumble.simulate``'s whole call (checks and the Trajectory included) against the peer's best.
- **2,000 bodies**, constant body torque, 20 s, omega <= 1e-10 and attitude <= 1e-9 rad:
  ``tumble.simulate_batch`` against the peer's ``prange`` loop, both on every core.

**The peer** (``benchmarks/numba_peer.py``, written here, sharing no code with tumble): Euler's
equations and the quaternion kinematics, fixed-step RK4 and the 8th-order step of DOP853, ``@njit``,
``prange`` over bodies; ``k`` equal steps per 0.2 s sample interval, the smallest ``k`` that meets
both errors (searched upwards), timed for both RK4 and RK8; its best is the faster.

**tumble** gets the same search over its own knobs: ``method="dop853"`` at the largest ``rtol``
of a ladder (1e-6, 3e-7, ..., 1e-13) that meets both errors, and ``method="rk8"`` at the
smallest ``k``; its best is the faster. Each side is timed as it is called from Python.

**Reference**: scipy's ``solve_ivp(method="DOP853", rtol=1e-13, atol=1e-16)`` on a numpy
right-hand side written here (not tumble's), its own error bounded by its difference from
rtol 1e-12 (printed). Errors: max over samples (and over the first 8 bodies of the batch).

Times: medians over alternating repeats (peer, then tumble, per repeat: a load that comes and
goes hits both), ranges in brackets; ratio = peer best / tumble best, per repeat.
"""

from __future__ import annotations

import json
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

sys.path.insert(0, str(Path(__file__).resolve().parent))
import numba_peer as peer

import tumble

T_END, SAMPLES = 20.0, 101
TAU = np.array([0.01, -0.02, 0.015])
ORBIT_PERIOD = 5400.0
N_ORBIT = 2 * np.pi / ORBIT_PERIOD
QUAT0 = Rotation.from_euler("xyz", [0.3, -0.2, 0.5]).as_quat()
ONE = {"omega": 2e-9, "attitude": 2e-8}
BATCH = {"omega": 1e-10, "attitude": 1e-9}
BODIES, N_REF = 2000, 8
RTOLS = [1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 3e-10, 1e-10, 3e-11, 1e-11, 3e-12, 1e-12, 3e-13, 1e-13]
CASES = {
    "spacecraft (10, 12, 15) kg m^2, 1 rad/s": ((10.0, 12.0, 15.0), (0.05, 1.0, 0.05)),
    "seed T-handle, 10 rad/s": ((0.125, 0.3125, 0.4375), (0.1, 10.0, 0.1)),
}
TIMES = np.linspace(0.0, T_END, SAMPLES)


def reference(I, w0, q0, gravity: bool, rtol: float = 1e-13):
    """scipy DOP853 on a numpy right-hand side written here: (omega (n, 3), quat (n, 4))."""
    I = np.asarray(I, float)

    def rhs(t, y):
        w, q = y[:3], y[3:] / np.linalg.norm(y[3:])
        tau = TAU
        if gravity:
            R = Rotation.from_quat(q).as_matrix()
            r = R.T @ np.array([np.cos(N_ORBIT * t), np.sin(N_ORBIT * t), 0.0])
            tau = 3 * N_ORBIT**2 * np.cross(r, I * r)
        x, yq, z, s = y[3:]
        dq = 0.5 * np.array([s * w[0] + yq * w[2] - z * w[1], s * w[1] + z * w[0] - x * w[2],
                             s * w[2] + x * w[1] - yq * w[0], -(x * w[0] + yq * w[1] + z * w[2])])
        return np.concatenate([(tau + np.cross(I * w, w)) / I, dq])

    sol = solve_ivp(rhs, (0.0, T_END), np.concatenate([w0, q0]), method="DOP853", t_eval=TIMES, rtol=rtol, atol=1e-16)
    return sol.y[:3].T, sol.y[3:].T / np.linalg.norm(sol.y[3:].T, axis=1, keepdims=True)


def errors(omega, quat, ref) -> tuple[float, float]:
    w_ref, q_ref = ref
    ew = float(np.max(np.linalg.norm(omega - w_ref, axis=-1)) / np.max(np.linalg.norm(w_ref, axis=-1)))
    ea = float(np.max((Rotation.from_quat(quat.reshape(-1, 4)) * Rotation.from_quat(q_ref.reshape(-1, 4)).inv()).magnitude()))
    return ew, ea


def _meets(e, target) -> bool:
    return e[0] <= target["omega"] and e[1] <= target["attitude"]


def _search_k(error_of, target, k_max=1024):
    """The smallest k meeting the target: doubling, then bisection (errors fall with k)."""
    seen = {}

    def ok(k):
        seen.setdefault(k, error_of(k))
        return _meets(seen[k], target)

    hi = 1
    while not ok(hi):
        if hi >= k_max:
            return None, seen
        hi *= 2
    lo = hi // 2
    while hi - lo > 1:
        mid = (lo + hi) // 2
        lo, hi = (lo, mid) if ok(mid) else (mid, hi)
    return hi, seen


def _search_rtol(error_of, target):
    seen = {}
    for r in RTOLS:
        seen[r] = error_of(r)
        if _meets(seen[r], target):
            return r, seen
    return None, seen


def _time(f, min_seconds=0.2):
    f()
    n, t = 1, 0.0
    while True:
        t0 = time.perf_counter()
        for _ in range(n):
            f()
        t = time.perf_counter() - t0
        if t >= min_seconds:
            return t / n
        n *= 2


def _paired(candidates: dict, repeat: int) -> dict:
    """Every candidate timed once per repeat, in turn; medians and ranges."""
    times = {name: [] for name in candidates}
    for _ in range(repeat):
        for name, f in candidates.items():
            times[name].append(_time(f, 0.05))
    return {name: np.array(v) for name, v in times.items()}


def _add(info: dict, choices: dict, name: str, knob: str, found, make) -> None:
    """Record a search's answer (``found`` = (value, errors seen)) and, if any, the call to time."""
    value, seen = found
    info[name] = {knob: value, "errors": seen.get(value)}
    if value is not None:
        choices[name] = make(value)


def _compete(info: dict, choices: dict, repeat: int, target_ratio: float) -> dict:
    """Time every choice, alternating; the ratio of the peer's best to tumble's best, per repeat."""
    times = _paired(choices, repeat)
    peer_best = np.min([v for c, v in times.items() if c.startswith("peer")], axis=0)
    tumble_best = np.min([v for c, v in times.items() if c.startswith("tumble")], axis=0)
    ratio = peer_best / tumble_best
    for c, v in times.items():
        info[c].update({"seconds": float(np.median(v)), "seconds_range": [float(v.min()), float(v.max())]})
    info.update({"ratio": float(np.median(ratio)), "ratio_range": [float(ratio.min()), float(ratio.max())],
                 "meets_target": bool(np.median(ratio) >= target_ratio)})
    return info


def _contenders(info: dict, target: dict, peer_run, peer_errors, tumble_run, tumble_errors) -> dict:
    """The peer's RK4 and RK8 at their smallest k, tumble's dop853 at its largest rtol and rk8 at its
    smallest k, each meeting ``target``: the calls to time, by name."""
    choices: dict = {}
    for name, tableau in {"peer rk4": (peer.A4, peer.B4, peer.C4), "peer rk8": (peer.A8, peer.B8, peer.C8)}.items():
        _add(info, choices, name, "k", _search_k(lambda k, t=tableau: peer_errors(peer_run(k, *t)), target),
             lambda k, t=tableau: (lambda: peer_run(k, *t)))
    _add(info, choices, "tumble dop853", "rtol",
         _search_rtol(lambda r: tumble_errors(tumble_run(method="dop853", rtol=r)), target),
         lambda r: (lambda: tumble_run(method="dop853", rtol=r)))
    _add(info, choices, "tumble rk8", "k",
         _search_k(lambda k: tumble_errors(tumble_run(method="rk8", step=0.2 / k)), target),
         lambda k: (lambda: tumble_run(method="rk8", step=0.2 / k)))
    return choices


def one_body(repeat: int) -> list[dict]:
    rows = []
    for body_name, (moments, w0) in CASES.items():
        I = np.array(moments)
        props = tumble.MassProperties.from_moments(moments)
        for gravity in (False, True):
            torque_name = "gravity gradient, 5400 s orbit" if gravity else f"constant body torque {TAU.tolist()} N m"
            model = tumble.GravityGradient(orbit_period=ORBIT_PERIOD) if gravity else tumble.ConstantTorque(tuple(TAU))
            ref = reference(I, np.array(w0), QUAT0, gravity)
            bound = errors(*reference(I, np.array(w0), QUAT0, gravity, rtol=1e-12), ref)
            y0 = np.concatenate([w0, QUAT0])
            tau, n = (np.zeros(3), N_ORBIT) if gravity else (TAU, 0.0)
            info = {"body": body_name, "torque": torque_name, "reference_bound": bound}
            choices = _contenders(
                info, ONE,
                lambda k, A, B, C, tau=tau, n=n, y0=y0, I=I: peer.run(I, y0, tau, n, T_END, SAMPLES, k, A, B, C),
                lambda out, ref=ref: errors(out[:, :3], out[:, 3:], ref),
                lambda props=props, w0=w0, model=model, **kw: tumble.simulate(
                    props, w0, t_end=T_END, samples=SAMPLES, attitude0=QUAT0, torque=model, **kw),
                lambda traj, ref=ref: errors(traj.omega, traj.quat, ref))
            rows.append(_compete(info, choices, repeat, 1.0))
            print(f"bench_engine: {body_name}, {torque_name}: ratio {info['ratio']:.3g}", file=sys.stderr, flush=True)
    return rows


def batch(repeat: int) -> dict:
    rng = np.random.default_rng(0)  # bench_torqued's bodies: moments in [0.5, 1] kg m^2, |omega| ~ 10 rad/s
    I = np.sort(rng.uniform(0.5, 1.0, (BODIES, 3)), axis=1)
    w = rng.normal(size=(BODIES, 3)) * 6.0
    q = Rotation.random(BODIES, random_state=0).as_quat()
    refs = [reference(I[b], w[b], q[b], False) for b in range(N_REF)]
    ref = (np.stack([r[0] for r in refs], 1), np.stack([r[1] for r in refs], 1))
    y0 = np.concatenate([w, q], axis=1)
    model = tumble.ConstantTorque(tuple(TAU))
    info = {"bodies": BODIES, "cores": len(os.sched_getaffinity(0))}
    choices = _contenders(
        info, BATCH,
        lambda k, A, B, C: peer.run_batch(I, y0, TAU, 0.0, T_END, SAMPLES, k, A, B, C),
        lambda out: errors(out[:, :N_REF, :3], out[:, :N_REF, 3:], ref),
        lambda **kw: tumble.simulate_batch(I, w, t_end=T_END, samples=SAMPLES, attitude0=q, torque=model, **kw),
        lambda b: errors(b.omega[:N_REF].transpose(1, 0, 2), b.quat[:N_REF].transpose(1, 0, 2), ref))
    _compete(info, choices, repeat, 2.0)
    print(f"bench_engine: batch of {BODIES}: ratio {info['ratio']:.3g}", file=sys.stderr, flush=True)
    return info


def _cell(c: dict, knob: str) -> str:
    if c.get(knob) is None:
        return "none meets it"
    e = c["errors"]
    value = f"{knob} {c[knob]:g}"
    lo, hi = c["seconds_range"]
    return f"{value}: {c['seconds'] * 1e3:.3g} ms [{lo * 1e3:.3g}-{hi * 1e3:.3g}], errors {e[0]:.1e} / {e[1]:.1e}"


def to_markdown(r: dict) -> str:
    names = [("peer rk4", "k"), ("peer rk8", "k"), ("tumble dop853", "rtol"), ("tumble rk8", "k")]
    lines = ["# bench_engine", "",
             (f"Python {platform.python_version()} on {platform.machine()}, {r['cores']} cores; medians over "
              f"{r['repeats']} alternating repeats, ranges in brackets; errors omega (relative) / attitude (rad) "
              "against scipy DOP853 rtol 1e-13 on a right-hand side written in the benchmark. Peer: "
              "benchmarks/numba_peer.py (k fixed steps per 0.2 s sample interval). tumble: the whole "
              "simulate / simulate_batch call. Ratio = peer's best / tumble's best."), "",
             "## One body, 20 s: omega <= 2e-9 and attitude <= 2e-8 rad; target ratio >= 1", "",
             "| body | torque | " + " | ".join(n for n, _ in names) + " | ratio | met |",
             "|---|---|" + "---|" * len(names) + "---|---|"]
    for c in r["one_body"]:
        lines.append(f"| {c['body']} | {c['torque']} | " + " | ".join(_cell(c[n], k) for n, k in names)
                     + f" | {c['ratio']:.3g} [{c['ratio_range'][0]:.3g}-{c['ratio_range'][1]:.3g}] | "
                     + ("yes" if c["meets_target"] else "**no**") + " |")
    b = r["batch"]
    lines += ["", f"## {b['bodies']} bodies, constant body torque, 20 s: omega <= 1e-10 and attitude <= 1e-9 rad; "
              "target ratio >= 2 (both on every core)", "",
              "| " + " | ".join(n for n, _ in names) + " | ratio | met |", "|" + "---|" * len(names) + "---|---|",
              "| " + " | ".join(_cell(b[n], k) for n, k in names) + f" | {b['ratio']:.3g} [{b['ratio_range'][0]:.3g}-"
              f"{b['ratio_range'][1]:.3g}] | " + ("yes" if b["meets_target"] else "**no**") + " |"]
    bound = max(max(c["reference_bound"]) for c in r["one_body"])
    lines += ["", f"Reference: its difference from rtol 1e-12 is at most {bound:.1e} (omega or attitude) over the cases."]
    return "\n".join(lines) + "\n"


def run(out, quick: bool = False) -> str:
    """Measure, write ``bench_engine.json`` into ``out``, return the markdown."""
    repeat = 3 if quick else 11
    r = {"repeats": repeat, "cores": len(os.sched_getaffinity(0)), "one_body": one_body(repeat), "batch": batch(repeat)}
    (out / "bench_engine.json").write_text(json.dumps(r, indent=2) + "\n")
    return to_markdown(r)
