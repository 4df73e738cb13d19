"""One spacecraft, 20 s, against Basilisk's RK4 at equal accuracy (the solver issue's target).

The target: one body, 20 s, a constant body torque and, separately, the gravity gradient of a
circular orbit, at an omega error of 2e-9: tumble at least 20x faster than Basilisk
(``pip install bsk``, in the ``bench`` extra), each at the largest step that reaches that error.

- Basilisk: ``spacecraft.Spacecraft`` hub, ``extForceTorque`` or ``GravityGradientEffector``
  (a point-mass Earth, the circular orbit of tumble's :class:`tumble.GravityGradient`), the
  default ``svIntegratorRK4``; see ``benchmarks/basilisk_runner.py`` for the frames. Timed:
  ``ExecuteSimulation`` alone (the headline: it leaves out Basilisk's set-up, which favours
  Basilisk) and the whole run with the set-up (building the simulation, ``InitializeSimulation``,
  reading the recorder).
- tumble: ``tumble.simulate(..., method="geometric6", torque=..., step=h)``, one call (the
  compiled kernel; a warm-up call first compiles it), everything included.
- Steps: both of the form ``0.2 s / k`` (whole steps per sample interval; Basilisk's clock
  counts nanoseconds, so its step is ``round(2e8 / k)`` ns), the smallest ``k`` whose error is at
  most 2e-9, found by doubling ``k`` and then bisecting (the errors fall monotonically with ``k``
  there: RK4 as ``h^4``, geometric6 as ``h^6``).
- Errors: the largest ``|omega - omega_ref| / max |omega_ref|`` over 101 samples (every 0.2 s),
  and the attitude's rotation angle (rad), against ``tumble.simulate(method="dop853",
  rtol=1e-13)`` at the very times each run sampled; that reference's own error is bounded by its
  difference from rtol 1e-12.

The same comparison with a reaction wheel: a box spacecraft (120 kg, 1.2 x 1.0 x 0.8 m) carrying a
wheel (2 kg, radius 0.15 m, 0.05 m thick, along its major axis, 200 rad/s relative: 4.5 N m s)
at 1 rad/s near its intermediate axis. In Basilisk a ``reactionWheelStateEffector`` wheel with no
motor torque (it keeps its absolute axial momentum); in tumble the :class:`tumble.Rotor` of that
body, whose constant spin gives the same gyrostat when Basilisk's hub is set up by
``basilisk_runner.wheel_setup`` (its module docstring derives it; the two agree to 1e-13 at small
steps, ``tests/test_basilisk.py``), under the constant body torque only: Basilisk's gravity gradient
reads the hub's inertia, which that set-up shifts by ``Js g g^T``. tumble runs it with the compiled ``geometric6`` kernel (constant
wheel momentum); ``exact_split6`` does not take wheels.

Bodies (one at a time, ``CASES``): a spacecraft with moments (10, 12, 15) kg m^2 tumbling at
1 rad/s near its intermediate axis (it flips within the 20 s), and the seed's T-handle, moments
(0.125, 0.3125, 0.4375) kg m^2, at the seed's 10 rad/s about the intermediate axis. Torque
(0.01, -0.02, 0.015) N m in the body frame, or the gravity gradient of a 5400 s circular orbit.
"""

from __future__ import annotations

import functools
import json
import platform
import sys
import time
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

import tumble

sys.path.insert(0, str(Path(__file__).resolve().parent))
from basilisk_runner import earth_mu, run_basilisk, wheel_setup

T_END = 20.0
SAMPLES = 101
INTERVAL = T_END / (SAMPLES - 1)  # 0.2 s
INTERVAL_NS = 200_000_000
TARGET_ERROR = 2e-9
TARGET_RATIO = 20.0
TAU = (0.01, -0.02, 0.015)
ORBIT_PERIOD = 5400.0
QUAT0 = Rotation.from_euler("xyz", [0.3, -0.2, 0.5]).as_quat()
CASES = {
    "spacecraft (10, 12, 15) kg m^2, 1 rad/s": ((10.0, 12.0, 15.0), (0.05, 1.0, 0.05)),
    "seed T-handle, 10 rad/s": ((0.125, 0.3125, 0.4375), (0.1, 10.0, 0.1)),
    "spacecraft (box 120 kg) with a free reaction wheel (4.5 N m s), 1 rad/s": ("wheel", (0.05, 1.0, 0.05)),
}
#: The wheel case's body: hub box (kg, m) and wheel (kg, m, rad/s), the wheel along design z.
WHEEL = {"hub_mass": 120.0, "hub_size": (1.2, 1.0, 0.8), "mass": 2.0, "radius": 0.15, "length": 0.05, "spin": 200.0}
K_MAX = 4096


def _torques(mu: float) -> dict:
    """tumble's model and Basilisk's keyword for each torque."""
    gg = tumble.GravityGradient(orbit_period=ORBIT_PERIOD, mu=mu)
    return {
        f"constant body torque {TAU} N m": (tumble.ConstantTorque(TAU), {"torque": TAU}),
        f"gravity gradient, circular orbit of {ORBIT_PERIOD:g} s (r = {gg.radius / 1e3:.1f} km)":
            (gg, {"orbit_radius": gg.radius}),
    }


@functools.cache  # built once per body, outside the timed calls (as Basilisk's set-up is)
def _props(spec):
    """tumble's body: moments (a tuple), or ``"wheel"``: the box with its wheel (:data:`WHEEL`)."""
    if spec == "wheel":
        w = WHEEL
        return tumble.Body([tumble.Box(mass=w["hub_mass"], size=w["hub_size"]),
                            tumble.Rotor(mass=w["mass"], radius=w["radius"], length=w["length"], axis=(0, 0, 1),
                                         spin_rate=w["spin"])])
    return tumble.MassProperties.from_moments(spec, mass=1.0)


def _basilisk_body(spec, w0) -> tuple:
    """Basilisk's hub moments and extra keywords (hub inertia, wheel) for a body spec."""
    if spec != "wheel":
        return spec, {}
    from tumble.dynamics.models.rotors import Rotors

    body = _props(spec)
    rotors = Rotors.of(body)
    hub, wheel = wheel_setup(body.principal_moments, rotors.axes[0], float(rotors.axial_moments[0]), WHEEL["spin"], w0)
    return tuple(body.principal_moments), {"hub_inertia": hub, "wheel": wheel}


def _reference(moments, w0, model, times, rtol=1e-13):
    return tumble.simulate(_props(moments), w0, times=times, attitude0=QUAT0, method="dop853",
                           rtol=rtol, atol=rtol * 1e-2, torque=model)


def _errors(omega, quat, ref) -> tuple[float, float]:
    ew = float(np.max(np.linalg.norm(omega - ref.omega, axis=1)) / np.max(np.linalg.norm(ref.omega, axis=1)))
    ea = float(np.max((Rotation.from_quat(quat) * Rotation.from_quat(ref.quat).inv()).magnitude()))
    return ew, ea


def _tumble(moments, w0, model, method, step):
    return tumble.simulate(_props(moments), w0, t_end=T_END, samples=SAMPLES, attitude0=QUAT0,
                           method=method, torque=model, step=step)


def _search(error_of, prepare=None) -> tuple[int, list[dict]]:
    """The smallest k with ``error_of(k)[0] <= TARGET_ERROR``: doubling, then bisection.

    ``prepare(ks)``, if given, is told the k the bisection may try before it starts (so that
    one reference run can cover all their sample times).
    """
    ladder, seen = [], {}

    def ok(k):
        if k not in seen:
            ew, ea = error_of(k)
            seen[k] = ew
            ladder.append({"k": k, "step": INTERVAL / k, "omega_error": ew, "attitude_error_rad": ea})
        return seen[k] <= TARGET_ERROR

    hi = 1
    while not ok(hi):
        if hi >= K_MAX:
            raise RuntimeError(f"no step down to {INTERVAL / K_MAX:g} s reaches {TARGET_ERROR:g}")
        hi *= 2
    lo = hi // 2  # fails (or 0)
    if prepare is not None and hi - lo > 1:
        prepare(range(lo + 1, hi))
    while hi - lo > 1:
        mid = (lo + hi) // 2
        lo, hi = (lo, mid) if ok(mid) else (mid, hi)
    return hi, sorted(ladder, key=lambda x: x["k"])


def _basilisk_ns(k: int) -> np.ndarray:
    """The sample times (integer ns) of a Basilisk run at step ``round(0.2 s / k)``: off the
    0.2 s grid by up to 50 k ns at 20 s when k does not divide 2e8."""
    return np.arange(SAMPLES, dtype=np.int64) * (k * round(INTERVAL_NS / k))


class _Reference:
    """DOP853 (rtol 1e-13) samples by integer-ns time, computed in as few runs as possible
    (each run of the seed T-handle takes seconds; its cost is in the steps, not the samples)."""

    def __init__(self, moments, w0, model):
        self.args, self.cache = (moments, w0, model), {}

    def ensure(self, ns) -> None:
        missing = np.setdiff1d(np.asarray(ns, dtype=np.int64), np.fromiter(self.cache, np.int64, len(self.cache)))
        if len(missing):
            tr = _reference(*self.args, missing * 1e-9)
            self.cache.update(zip(missing.tolist(), zip(tr.omega, tr.quat)))

    def at(self, ns):
        self.ensure(ns)
        w, q = zip(*(self.cache[int(t)] for t in ns))
        return _Samples(np.array(w), np.array(q))


class _Samples:
    def __init__(self, omega, quat):
        self.omega, self.quat = omega, quat


def measure_case(moments, w0, model, bsk_kw, repeat: int) -> dict:
    grid = np.arange(SAMPLES, dtype=np.int64) * INTERVAL_NS
    refs = _Reference(moments, w0, model)
    ref = refs.at(grid)
    ref12 = _reference(moments, w0, model, grid * 1e-9, rtol=1e-12)
    ref_bound = _errors(ref12.omega, ref12.quat, ref)
    bsk_moments, bsk_body = _basilisk_body(moments, w0)

    def bsk(k):
        run = run_basilisk(bsk_moments, w0, QUAT0, dt_ns=round(INTERVAL_NS / k), sample_steps=k,
                           samples=SAMPLES, **bsk_kw, **bsk_body)
        assert np.allclose(run.times, _basilisk_ns(k) * 1e-9, rtol=0, atol=1e-12), "Basilisk's sample times"
        return run

    def bsk_error(k):
        run = bsk(k)
        return _errors(run.omega, run.quat, refs.at(_basilisk_ns(k)))

    def tb_error(k):
        tr = _tumble(moments, w0, model, "geometric6", INTERVAL / k)
        return _errors(tr.omega, tr.quat, ref)

    k_bsk, bsk_ladder = _search(bsk_error, lambda ks: refs.ensure(np.concatenate([_basilisk_ns(k) for k in ks])))
    k_tb, tb_ladder = _search(tb_error)
    h = INTERVAL / k_tb
    _tumble(moments, w0, model, "geometric6", h)  # warm (the kernel compiles once per process)
    exe, tot, tb = [], [], []
    for _ in range(repeat):  # alternating, so a load that comes and goes hits both alike
        run = bsk(k_bsk)
        exe.append(run.seconds_execute)
        tot.append(run.seconds_total)
        t0 = time.perf_counter()
        tr = _tumble(moments, w0, model, "geometric6", h)
        tb.append(time.perf_counter() - t0)
    exe, tot, tb = np.array(exe), np.array(tot), np.array(tb)
    bsk_err = _errors(run.omega, run.quat, refs.at(_basilisk_ns(k_bsk)))
    tb_err = _errors(tr.omega, tr.quat, ref)
    exact_split6 = None
    if moments != "wheel":  # for information: the exact free flow with kicks (it takes no wheels)
        _tumble(moments, w0, model, "exact_split6", INTERVAL)  # warm
        t0 = time.perf_counter()
        ex = _tumble(moments, w0, model, "exact_split6", INTERVAL)
        ex_s = time.perf_counter() - t0
        exact_split6 = {"step": INTERVAL, "seconds": ex_s, "omega_error": _errors(ex.omega, ex.quat, ref)[0],
                        "attitude_error_rad": _errors(ex.omega, ex.quat, ref)[1]}

    def stats(x):
        return {"seconds": float(np.median(x)), "seconds_range": [float(x.min()), float(x.max())]}

    ratio, ratio_total = exe / tb, tot / tb
    return {
        "reference_bound": {"omega_error": ref_bound[0], "attitude_error_rad": ref_bound[1]},
        "basilisk": {"integrator": "svIntegratorRK4", "k": k_bsk, "step": INTERVAL_NS / k_bsk * 1e-9,
                     "step_ns": round(INTERVAL_NS / k_bsk), "execute": stats(exe), "total": stats(tot),
                     "omega_error": bsk_err[0], "attitude_error_rad": bsk_err[1], "ladder": bsk_ladder},
        "tumble": {"method": "geometric6", "k": k_tb, "step": h, **stats(tb),
                   "omega_error": tb_err[0], "attitude_error_rad": tb_err[1], "ladder": tb_ladder},
        "exact_split6": exact_split6,
        "ratio": float(np.median(ratio)), "ratio_range": [float(ratio.min()), float(ratio.max())],
        "ratio_total": float(np.median(ratio_total)),
        "ratio_total_range": [float(ratio_total.min()), float(ratio_total.max())],
        "meets_target": bool(np.median(ratio) >= TARGET_RATIO),
    }


def measure(quick: bool = False) -> dict:
    try:
        import Basilisk

        version = getattr(Basilisk, "__version__", None)
        if version is None:
            from importlib.metadata import version as _v

            version = _v("bsk")
    except ImportError as exc:  # the bench extra is not installed
        return {"skipped": f"Basilisk is not installed ({exc}); pip install -e '.[bench]' (bsk)"}
    repeat = 3 if quick else 15
    cases = []
    for (torque_name, (model, kw)) in _torques(earth_mu()).items():
        for body_name, (moments, w0) in CASES.items():
            if moments == "wheel" and "gravity" in torque_name:
                continue  # Basilisk's gravity gradient reads the hub's inertia, which wheel_setup shifts by Js g g^T
            r = measure_case(moments, w0, model, kw, repeat)
            print(f"bench_basilisk: {body_name}, {torque_name}: ratio {r['ratio']:.3g}", file=sys.stderr, flush=True)
            cases.append({"body": body_name, "moments": [float(v) for v in _props(moments).principal_moments],
                          "omega0": list(w0),
                          "torque": torque_name, **r})
    return {"basilisk_version": version, "repeats": repeat, "t_end": T_END, "samples": SAMPLES,
            "target_omega_error": TARGET_ERROR, "target_ratio": TARGET_RATIO, "attitude0_quat": list(QUAT0),
            "cases": cases}


def _ms(x: float) -> str:
    return f"{x * 1e3:.3g}"


def to_markdown(r: dict) -> str:
    if "skipped" in r:
        return f"# bench_basilisk\n\nSKIPPED: {r['skipped']}\n"
    lines = [
        "# bench_basilisk", "",
        (f"Python {platform.python_version()} on {platform.machine()}, {platform.node()}; Basilisk (bsk) "
        f"{r['basilisk_version']}. One body, {r['t_end']:g} s, {r['samples']} samples; each at the largest step "
        f"0.2 s / k reaching an omega error of {r['target_omega_error']:g} (relative to max |omega|) against DOP853 "
        f"rtol 1e-13. Times: medians over {r['repeats']} alternating repeats (Basilisk, then tumble), range in "
        f"brackets. Basilisk 'run' is ExecuteSimulation alone; 'with set-up' adds building and initialising the "
        f"simulation. Ratio = Basilisk time / tumble time, per repeat."), "",
        ("| body | torque | Basilisk RK4 step (s) | Basilisk run (ms) | with set-up (ms) | Basilisk omega / attitude error "
        "| tumble geometric6 step (s) | tumble (ms) | tumble omega / attitude error | ratio (run) | ratio (with set-up) "
        f"| >= {r['target_ratio']:g}x |"),
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for c in r["cases"]:
        b, t = c["basilisk"], c["tumble"]
        e, tot = b["execute"], b["total"]
        lines.append(
            f"| {c['body']} | {c['torque']} | {b['step']:.4g} | {_ms(e['seconds'])} [{_ms(e['seconds_range'][0])}-"
            f"{_ms(e['seconds_range'][1])}] | {_ms(tot['seconds'])} [{_ms(tot['seconds_range'][0])}-"
            f"{_ms(tot['seconds_range'][1])}] | {b['omega_error']:.1e} / {b['attitude_error_rad']:.1e} "
            f"| {t['step']:.4g} | {_ms(t['seconds'])} [{_ms(t['seconds_range'][0])}-{_ms(t['seconds_range'][1])}] "
            f"| {t['omega_error']:.1e} / {t['attitude_error_rad']:.1e} | {c['ratio']:.3g} [{c['ratio_range'][0]:.3g}-"
            f"{c['ratio_range'][1]:.3g}] | {c['ratio_total']:.3g} [{c['ratio_total_range'][0]:.3g}-"
            f"{c['ratio_total_range'][1]:.3g}] | {'met' if c['meets_target'] else 'NOT met'} |")
    lines += ["", ("For information, tumble exact_split6 (exact free flow with torque kicks; compiled) at "
              "h = 0.2 s, single timing after a warm-up (it takes no wheels):"), "", "| body | torque | time (ms) | omega error | attitude error (rad) |",
              "|---|---|---|---|---|"]
    for c in r["cases"]:
        x = c["exact_split6"]
        if x is None:
            continue
        lines.append(f"| {c['body']} | {c['torque']} | {_ms(x['seconds'])} | {x['omega_error']:.1e} "
                     f"| {x['attitude_error_rad']:.1e} |")
    bound = max(c["reference_bound"]["omega_error"] for c in r["cases"])
    lines += ["", f"Reference: its difference from DOP853 rtol 1e-12 is at most {bound:.1e} in omega over the cases.",
              "", "Step searches (k = sample interval / step; doubling, then bisection):", "",
              "| body | torque | integrator | k: omega error |", "|---|---|---|---|"]
    for c in r["cases"]:
        for name, key in (("Basilisk RK4", "basilisk"), ("tumble geometric6", "tumble")):
            steps = ", ".join(f"{x['k']}: {x['omega_error']:.1e}" for x in c[key]["ladder"])
            lines.append(f"| {c['body']} | {c['torque']} | {name} | {steps} |")
    met = sum(c["meets_target"] for c in r["cases"])
    lines += ["", (f"Target {r['target_ratio']:g}x (Basilisk run / tumble, medians): **met in {met} of "
              f"{len(r['cases'])} cases**.")]
    return "\n".join(lines) + "\n"


def run(out, quick: bool = False) -> str:
    """Measure, write ``bench_basilisk.json`` into ``out``, return the markdown."""
    r = measure(quick)
    (out / "bench_basilisk.json").write_text(json.dumps(r, indent=2) + "\n")
    return to_markdown(r)
