"""The Monte Carlo of pointing on an estimate that docs/estimation.md quotes ("Monte Carlo").

Fifty cases of a small body (moments 0.02, 0.03, 0.04 kg m^2, three reaction wheels) pointing
with MRP feedback at a fixed target for ten minutes from a uniformly drawn attitude, fed the MEKF's
estimate (:class:`tumble.dynamics.control.estimated.Estimated`) from a gyroscope (1e-4 rad/s
noise, a bias of 2e-4 rad/s per axis drawn per case), a magnetometer (200 nT) and six coarse sun
cells (2e-3), sunlit (a 500 km orbit of 97.4 deg, the March equinox: the eclipse starts after the
ten minutes), every sensor's noise scaled per case by a factor spread by 30 %
(:func:`tumble.ensemble.knowledge.knowledge_cases`). The errors count from 300 s, after the filter
and the law have settled. Prints the summary (median, 95th percentile, largest; deg) and the CPU
seconds a case.

Run: ``python benchmarks/knowledge_mc.py [--cases N]``.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np
from scipy.spatial.transform import Rotation

from tumble.dynamics.control.controllers import MRPFeedback
from tumble.dynamics.environment.magnetic import DipoleField
from tumble.dynamics.environment.orbit import CircularOrbit
from tumble.dynamics.environment.sun import Sunlight
from tumble.dynamics.models.actuators import ReactionWheels
from tumble.dynamics.models.sensors import Sensors
from tumble.dynamics.models.vector_sensors import CoarseSunSensor
from tumble.ensemble.knowledge import knowledge_cases, pointing_monte_carlo

ORBIT = CircularOrbit(altitude=500e3, inclination=1.7)
MOMENTS = [0.02, 0.03, 0.04]
WHEELS = ReactionWheels(np.eye(3), inertia=1e-5, max_torque=2e-3)
LAW = MRPFeedback(K=4e-3, P=1.2e-2, period=1.0, moments=MOMENTS, wheels=WHEELS, target=Rotation.from_rotvec([0.1, 0.2, 0.0]))
SENSORS = Sensors(gyro_noise=1e-4, magnetometer_noise=2e-7, attitude="none", sun_sensor=CoarseSunSensor(noise=2e-3),
                  sunlight=Sunlight(ORBIT, "2026-03-20T14:46:00"))
T_END, SETTLE = 600.0, 300.0


def main(argv: list[str] | None = None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=50)
    args = parser.parse_args(argv)
    cases = knowledge_cases(args.cases, gyro_bias_sigma=2e-4, noise_spread=0.3, seed=2026)
    start = time.process_time()
    mc = pointing_monte_carlo(cases, moments=MOMENTS, controller=LAW, field=DipoleField(ORBIT), sensors=SENSORS,
                              wheels=WHEELS, t_end=T_END, settle=SETTLE)
    summary = {**mc.summary(), "cpu_seconds_a_case": (time.process_time() - start) / args.cases}
    print(json.dumps(summary, indent=1))
    return summary


if __name__ == "__main__":
    main()
