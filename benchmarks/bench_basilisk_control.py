"""Closed-loop control beside Basilisk: agreement and time of the two scenarios of
``tests/test_control_basilisk.py`` (issue 21), at Basilisk steps of 20, 10 and 5 ms.

(a) MRP feedback with three reaction wheels, 60 s: the largest omega and attitude differences;
(b) B-dot with magnetorquers in the centred dipole, 100 s: the difference (first order in
Basilisk's step, the field it holds over each step) and that of the Richardson extrapolation of
two successive steps (second order). Times: one run each, set-up included (``perf_counter``).
``benchmarks/basilisk_control.py`` has the frames and the timing.
"""

from __future__ import annotations

import json
import platform
import sys
import time
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

STEPS = (0.02, 0.01, 0.005)


def _timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def run(out: Path, quick: bool = False) -> str:
    """Measure, write ``bench_basilisk_control.json`` and return the markdown table."""
    import test_control_basilisk as s  # the scenarios, one definition
    from basilisk_control import run_detumble, run_pointing

    from tumble.dynamics.control.controlled import simulate_controlled
    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.control.controllers import MRPFeedback
    from tumble.dynamics.models.actuators import Magnetorquers, ReactionWheels
    from tumble.dynamics.environment.magnetic import IGRF13_2020, IGRF_RADIUS

    rows = []
    rw = ReactionWheels(np.eye(3), inertia=s.JS)
    ctrl = MRPFeedback(K=s.K, P=s.P, period=s.PERIOD, moments=s.MOMENTS, wheels=rw, target=s.TARGET)
    tp, tp_s = _timed(lambda: simulate_controlled(s.MOMENTS, s.OMEGA0, t_end=s.T_POINT, attitude0=s.QUAT0, wheels=rw,
                                                  wheel_speed0=s.SPEED0, controller=ctrl))
    for dt in STEPS[1:] if quick else STEPS:
        b, b_s = _timed(lambda dt=dt: run_pointing(s.MOMENTS, s.OMEGA0, s.QUAT0, js=s.JS, wheel_speed0=s.SPEED0, K=s.K,
                                             P=s.P, target_quat=s.TARGET, period=s.PERIOD, dt=dt, t_end=s.T_POINT))
        rows.append({"scenario": "MRP feedback + 3 wheels, 60 s", "basilisk_dt": dt,
                     "omega_diff": float(np.max(np.abs(b.omega - tp.omega))),
                     "angle_diff": float(np.max((Rotation.from_quat(b.quat) * tp.attitude.inv()).magnitude())),
                     "richardson_diff": None, "tumble_seconds": tp_s, "basilisk_seconds": b_s})
    orbit, field, att0 = s.detumble_setup.__wrapped__()
    td, td_s = _timed(lambda: simulate_controlled(s.I_CUBE, s.W_CUBE, t_end=s.T_DETUMBLE, attitude0=att0,
                                                  controller=BDot(s.GAIN, period=1.0), field=field,
                                                  magnetorquers=Magnetorquers(s.MAX_DIPOLE)))
    previous = None
    for dt in STEPS:
        b, b_s = _timed(lambda dt=dt: run_detumble(s.I_CUBE, s.W_CUBE, (orbit.eci_from_world * att0).as_quat(),
                                             r_eci=orbit.position_eci(0.0), v_eci=orbit.velocity_eci(0.0), mu=orbit.mu,
                                             gain=s.GAIN, max_dipole=s.MAX_DIPOLE, coefficients=IGRF13_2020,
                                             radius=IGRF_RADIUS, period=1.0, dt=dt, t_end=s.T_DETUMBLE))
        att = orbit.eci_from_world.inv() * Rotation.from_quat(b.quat)
        rows.append({"scenario": "B-dot + 3 rods, dipole field, 100 s", "basilisk_dt": dt,
                     "omega_diff": float(np.max(np.abs(b.omega - td.omega))),
                     "angle_diff": float(np.max((att * td.attitude.inv()).magnitude())),
                     "richardson_diff": None if previous is None else
                     float(np.max(np.abs(2.0 * b.omega - previous - td.omega))),
                     "tumble_seconds": td_s, "basilisk_seconds": b_s})
        previous = b.omega
    (out / "bench_basilisk_control.json").write_text(json.dumps(rows, indent=2) + "\n")
    lines = ["# bench_basilisk_control", "", (f"Python {platform.python_version()} on {platform.machine()}; "
             "max |omega difference| (rad/s) and attitude angle (rad) over the run; Richardson: "
             "2 b(dt) - b(2 dt) against tumble"), "",
             "| scenario | Basilisk dt (s) | omega diff | angle diff | Richardson | tumble (s) | Basilisk (s) |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        rich = "-" if r["richardson_diff"] is None else f"{r['richardson_diff']:.2g}"
        lines.append(f"| {r['scenario']} | {r['basilisk_dt']:g} | {r['omega_diff']:.2g} | {r['angle_diff']:.2g} | "
                     f"{rich} | {r['tumble_seconds']:.3g} | {r['basilisk_seconds']:.3g} |")
    return "\n".join(lines) + "\n"
