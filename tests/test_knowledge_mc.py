"""The Monte Carlo of pointing on an estimate (tumble.ensemble.knowledge): each case is the single
run it says it is, the chunking and the backend do not change the answer, and the statistics
are those of the per-case errors."""

from __future__ import annotations

import functools

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.controllers import MRPFeedback
from tumble.dynamics.control.estimated import Estimated
from tumble.dynamics.environment.magnetic import DipoleField
from tumble.dynamics.environment.orbit import CircularOrbit
from tumble.dynamics.environment.sun import Sunlight
from tumble.dynamics.models.actuators import ReactionWheels
from tumble.dynamics.models.sensors import Sensors
from tumble.dynamics.models.vector_sensors import CoarseSunSensor, StarTracker
from tumble.ensemble.knowledge import knowledge_cases, pointing_monte_carlo

ORBIT = CircularOrbit(altitude=500e3, inclination=1.7)
FIELD = DipoleField(ORBIT)
MOMENTS = [0.02, 0.03, 0.04]
RW = ReactionWheels(np.eye(3), inertia=1e-5, max_torque=2e-3)
LAW = MRPFeedback(K=4e-3, P=1.2e-2, period=1.0, moments=MOMENTS, wheels=RW, target=Rotation.from_rotvec([0.1, 0.2, 0.0]))
SENSORS = Sensors(gyro_noise=1e-4, magnetometer_noise=2e-7, attitude="none", sun_sensor=CoarseSunSensor(noise=2e-3),
                  sunlight=Sunlight(ORBIT, "2026-06-01T00:00:00"), star_tracker=StarTracker(cross=2e-5, roll=2e-4, period=10.0))
CASES = knowledge_cases(6, gyro_bias_sigma=2e-4, noise_spread=0.3, seed=7)


@functools.lru_cache(maxsize=None)
def _mc(chunk: int):
    return pointing_monte_carlo(CASES, moments=MOMENTS, controller=LAW, field=FIELD, sensors=SENSORS, wheels=RW,
                                t_end=90.0, settle=60.0, chunk=chunk)


def test_a_case_is_the_run_it_says():
    mc = _mc(4)
    i = 4
    sensors = mc.case_sensors(i)
    assert sensors.seed == CASES.noise_seed[i] and sensors.sun_sensor.noise == pytest.approx(2e-3 * CASES.noise_scale[i])
    c = Estimated(MRPFeedback(K=4e-3, P=1.2e-2, period=1.0, moments=MOMENTS, wheels=RW, target=LAW.target), sensors, FIELD)
    run = simulate_controlled(MOMENTS, np.zeros(3), t_end=90.0, controller=c, field=FIELD, wheels=RW, sensors=sensors,
                              attitude0=CASES.quat0[i])
    point = run.pointing_error(LAW.target)[run.t >= 60.0]
    know = np.linalg.norm(c.knowledge().error(run), axis=1)[c.knowledge().t >= 60.0]
    assert mc.pointing_rms[i] == pytest.approx(np.sqrt(np.mean(point**2)), rel=1e-12)
    assert mc.knowledge_final[i] == pytest.approx(know[-1], rel=1e-12)


def test_the_chunking_does_not_change_the_answer_and_the_summary_is_the_cases():
    a, b = _mc(4), _mc(1)
    for name in ("knowledge_rms", "knowledge_final", "pointing_rms", "pointing_final"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    s = a.summary()
    assert s["cases"] == 6 and s["pointing_rms_deg"]["max"] == pytest.approx(np.degrees(a.pointing_rms.max()))
    assert s["pointing_rms_deg"]["median"] <= s["pointing_rms_deg"]["p95"] <= s["pointing_rms_deg"]["max"] < 0.5
    # with a star tracker the estimate is good to a few hundredths of a degree, and the pointing follows it
    assert s["knowledge_rms_deg"]["max"] < 0.1


def test_dask_gives_the_same_answer():
    pytest.importorskip("dask.distributed")
    from tumble.ensemble.backends import DaskBackend

    cases = knowledge_cases(2, gyro_bias_sigma=2e-4, seed=9)
    backend = DaskBackend(workers=1)
    try:
        remote = pointing_monte_carlo(cases, moments=MOMENTS, controller=LAW, field=FIELD, sensors=SENSORS, wheels=RW,
                                      t_end=20.0, settle=10.0, chunk=1, backend=backend)
    finally:
        backend.close()
    here = pointing_monte_carlo(cases, moments=MOMENTS, controller=LAW, field=FIELD, sensors=SENSORS, wheels=RW,
                                t_end=20.0, settle=10.0, chunk=2)
    assert np.array_equal(remote.pointing_final, here.pointing_final)
    assert np.array_equal(remote.knowledge_rms, here.knowledge_rms)


@pytest.mark.parametrize(("call", "message"), [
    (lambda: knowledge_cases(0), r"^n = 0 must be a whole number of cases >= 1$"),
    (lambda: knowledge_cases(3, noise_spread=2.0), r"^noise_spread = 2.0 is beyond 1"),
    (lambda: pointing_monte_carlo(CASES, moments=MOMENTS, controller=LAW, field=FIELD, sensors=SENSORS, t_end=10.0, settle=10.0),
     r"^settle = 10.0 must be less than t_end = 10.0 \(s\)$"),
    (lambda: pointing_monte_carlo(CASES, moments=MOMENTS, controller=object(), field=FIELD, sensors=SENSORS, t_end=10.0),
     r"^controller = object has no target"),
])
def test_bad_input_one_line(call, message):
    with pytest.raises(ValueError, match=message):
        call()
