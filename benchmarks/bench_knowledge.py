"""Attitude knowledge in the loop (issue 41): a 90-minute orbit with the MEKF at 10 Hz, CPU seconds.

A small body (moments 0.02, 0.03, 0.04 kg m^2) with three reaction wheels and 0.2 A m^2 rods
points at a fixed target with MRP feedback and momentum dumping, fed the filter's estimate
(:class:`tumble.dynamics.control.estimated.Estimated`) from a gyroscope (1e-4 rad/s noise, a
bias), a magnetometer (200 nT) and six coarse sun cells (2e-3) through the Earth's shadow, on a
500 km orbit of 97.4 deg inclination at the March equinox: 5,400 s at a 0.1 s control period,
54,000 filter steps. Timed by ``time.process_time`` (CPU seconds, so a loaded machine's waiting
is not counted), warm (compiled kernels cached), on the compiled loop with the estimator
(``tumble.dynamics.control.estimated_loop``) and on the Python path (``Estimated`` called each
step, the same compiled hold intervals), whose runs agree to round-off. Target: <= 2 s.
``--quick`` times the Python path over a tenth of the orbit and scales it.
"""

from __future__ import annotations

import json
import os
import statistics
import time
from pathlib import Path

import numpy as np

T_END, PERIOD, TARGET_S = 5400.0, 0.1, 2.0


def orbit_run(t_end: float, compiled: bool = True):
    """One run: ``(cpu_seconds, run, knowledge)``; ``compiled=False`` takes the Python path."""
    from scipy.spatial.transform import Rotation

    from tumble.dynamics.control import estimated_loop
    from tumble.dynamics.control.controlled import simulate_controlled
    from tumble.dynamics.control.controllers import MomentumDumping, MRPFeedback
    from tumble.dynamics.control.estimated import Estimated
    from tumble.dynamics.environment.magnetic import DipoleField
    from tumble.dynamics.environment.orbit import CircularOrbit
    from tumble.dynamics.environment.sun import Sunlight
    from tumble.dynamics.models.actuators import Magnetorquers, ReactionWheels
    from tumble.dynamics.models.sensors import Sensors
    from tumble.dynamics.models.vector_sensors import CoarseSunSensor

    orbit = CircularOrbit(altitude=500e3, inclination=1.7)
    moments = [0.02, 0.03, 0.04]
    wheels = ReactionWheels(np.eye(3), inertia=1e-5, max_torque=2e-3)
    sensors = Sensors(gyro_noise=1e-4, gyro_bias=(3e-4, -2e-4, 1e-4), magnetometer_noise=2e-7, attitude="none",
                      sun_sensor=CoarseSunSensor(noise=2e-3), sunlight=Sunlight(orbit, "2026-03-20T14:46:00"), seed=3)
    target = Rotation.from_rotvec([0.0, 0.4, 0.2])
    law = MomentumDumping(MRPFeedback(K=4e-3, P=1.2e-2, period=PERIOD, moments=moments, wheels=wheels, target=target),
                          gain=1e-3)
    controller = Estimated(law, sensors, DipoleField(orbit))
    plan = estimated_loop.plan
    if not compiled:
        estimated_loop.plan = lambda *args: None  # type: ignore[assignment]
    try:
        start = time.process_time()
        run = simulate_controlled(moments, [0.0, 0.0, 0.0], t_end=t_end, controller=controller, field=DipoleField(orbit),
                                  wheels=wheels, magnetorquers=Magnetorquers(0.2), sensors=sensors,
                                  attitude0=target * Rotation.from_rotvec([0.5, 0.0, 0.0]))
        seconds = time.process_time() - start
    finally:
        estimated_loop.plan = plan
    return seconds, run, controller.knowledge()


def run(out: Path, quick: bool = False) -> str:
    """Measure, write ``bench_knowledge.json``, return the markdown."""
    orbit_run(10.0)  # compile (or load the cache)
    times = []
    for _ in range(3 if quick else 5):
        seconds, fast, kf = orbit_run(T_END)
        times.append(seconds)
    span = T_END / 10 if quick else T_END
    python_seconds, slow, ks = orbit_run(span, compiled=False)
    python_seconds *= T_END / span
    n = len(slow.t)
    agree = float(np.abs(fast.attitude.as_quat()[:n] - slow.attitude.as_quat()).max())
    error = np.degrees(np.linalg.norm(kf.error(fast), axis=1))
    row = {"case": "90-minute orbit, MEKF at 10 Hz (54,000 steps)", "cpu_seconds": statistics.median(times),
           "cpu_seconds_range": [min(times), max(times)], "python_path_cpu_seconds": python_seconds,
           "python_path_scaled_from_s": span, "speedup": python_seconds / statistics.median(times),
           "max_quaternion_difference": agree, "knowledge_error_rms_deg": float(np.sqrt(np.mean(error**2))),
           "sun_sensor_steps": int(kf.used[:, 1].sum()), "target_seconds": TARGET_S,
           "meets_target": bool(statistics.median(times) <= TARGET_S), "load": os.getloadavg()[0]}
    (out / "bench_knowledge.json").write_text(json.dumps(row, indent=2) + "\n")
    return "\n".join([
        "# bench_knowledge", "",
        "A 90-minute orbit with the MEKF at 10 Hz (magnetometer, coarse sun cells through the eclipse, gyroscope; "
        "MRP feedback with momentum dumping fed the estimate). CPU seconds (`time.process_time`), warm; median of "
        f"{len(times)} [range].", "",
        "| case | compiled loop (CPU-s) | Python path (CPU-s) | speed-up | target | met | paths agree (max dq) |",
        "|---|---|---|---|---|---|---|",
        f"| {row['case']} | {row['cpu_seconds']:.3g} [{min(times):.3g}-{max(times):.3g}] | {python_seconds:.3g}"
        f"{' (scaled from ' + format(span, 'g') + ' s)' if span != T_END else ''} | {row['speedup']:.0f}x "
        f"| <= {TARGET_S:g} s | {'yes' if row['meets_target'] else 'NO'} | {agree:.1e} |",
        "", f"Knowledge error rms {row['knowledge_error_rms_deg']:.4f} deg; the sun cells read at "
        f"{row['sun_sensor_steps']} of {len(kf.t)} steps (the rest in the Earth's shadow); 1-minute load {row['load']:.1f}.",
        ""])


if __name__ == "__main__":
    import sys

    print(run(Path(__file__).resolve().parent / "results" / "quick", quick="--quick" in sys.argv))
