"""The B-dot batch with what a spacecraft sees (issue 21 item 6): the gravity gradient of the orbit
and noisy, biased sensors. Checked against the single-body closed loop with the same noise
realisation, against the torque's closed form, between the two paths, and for independence from
the batch's make-up, its segmentation, the Monte Carlo's chunking and the backend."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tumble.dynamics.control import detumble as dt
from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.bdot import BDot, bdot_gain
from tumble.dynamics.control.detumble import detumble_batch
from tumble.dynamics.models.actuators import Magnetorquers
from tumble.dynamics.models.gravity import GravityGradient
from tumble.dynamics.models.orbit_gravity import gravity_gradient_of
from tumble.dynamics.environment.magnetic import DipoleField
from tumble.dynamics.environment.orbit import CircularOrbit
from tumble.dynamics.models.sensors import Sensors

ORBIT = CircularOrbit(altitude=500e3, inclination=1.69995, raan=0.3)
FIELD = DipoleField(ORBIT)
MOMENTS = np.array([0.0067, 0.0419, 0.0430])  # kg m^2
GAIN = 4 * bdot_gain(ORBIT.mean_motion, ORBIT.inclination, MOMENTS[0])  # N m s
NOISY = Sensors(gyro_noise=1e-3, gyro_bias=(2e-3, -1e-3, 5e-4), magnetometer_noise=3e-7,
                magnetometer_bias=(1e-7, 0.0, -2e-7), attitude="none", seed=42)


def _bodies(n, seed):
    rng = np.random.default_rng(seed)
    return (MOMENTS * (1 + 0.1 * rng.uniform(-1, 1, (n, 3))), rng.normal(size=(n, 3)) * 0.15,
            Rotation.random(n, random_state=seed).as_quat(), rng.uniform(0, 2 * math.pi, n))


@pytest.mark.parametrize("sensors", [None, NOISY, dataclasses.replace(NOISY, attitude="star_tracker", attitude_noise=1e-3)],
                         ids=["ideal", "noisy", "noisy-star-tracker"])
def test_one_body_is_simulate_controlled_with_the_same_model_and_noise(sensors):
    """Gravity gradient and sensors as in the one-body loop (DOP853, rtol 1e-10): the batch draws
    the very noise that Sensors(seed=42) gives there (a star tracker's draws, unused by B-dot,
    skipped as they are taken there), so the runs agree to RK4's error, which falls
    ~16x from 4 to 8 substeps (fourth order); the noise itself moves the rate by far more."""
    w0, q0 = np.array([0.2, -0.15, 0.25]), Rotation.from_rotvec([0.3, -1.0, 0.5]).as_quat()
    gg = gravity_gradient_of(ORBIT)
    run = simulate_controlled(MOMENTS, w0, t_end=200.0, attitude0=q0, controller=BDot(GAIN, period=1.0, form="normalized"),
                              field=DipoleField(ORBIT, gmst0=0.7), magnetorquers=Magnetorquers(0.2),
                              gravity_gradient=gg, sensors=sensors)
    errors = []
    for substeps in (4, 8):
        batch = detumble_batch([MOMENTS], [w0], [q0], field=FIELD, gmst0=0.7, gain=GAIN, magnetorquers=Magnetorquers(0.2),
                               period=1.0, t_end=200.0, substeps=substeps, gravity_gradient=gg,
                               sensors=None if sensors is None else [sensors])
        errors.append(np.max(np.abs(batch.rate[0] - run.rate)))
    assert errors[1] < 2e-9 and errors[0] > 8 * errors[1]
    assert run.rate[-1] < 0.85 * run.rate[0]
    if sensors is not None:  # the noise matters here: without it the run is another one
        ideal = detumble_batch([MOMENTS], [w0], [q0], field=FIELD, gmst0=0.7, gain=GAIN, magnetorquers=Magnetorquers(0.2),
                               period=1.0, t_end=200.0, substeps=8, gravity_gradient=gg)
        assert np.max(np.abs(ideal.rate[0] - run.rate)) > 1e4 * errors[1]


def test_the_gravity_gradient_torque_starts_the_closed_form_spin():
    """A body at rest with its axis 1 at 45 deg from the radius in the orbit plane, rods too weak
    to matter: ``I3 omega3' = (3/2) n^2 (I2 - I1)`` (Hughes ch. 8), so after 2 s omega3 = 2 that /
    I3 to O(t^3); without the gravity gradient nothing moves."""
    q = Rotation.from_rotvec([0.0, 0.0, -math.pi / 4]).as_quat()
    kw = {"field": FIELD, "gmst0": 0.0, "gain": GAIN, "magnetorquers": Magnetorquers(1e-30), "period": 0.5,
          "t_end": 2.0}
    with_gg = detumble_batch([MOMENTS], [[0.0, 0.0, 0.0]], [q], gravity_gradient=gravity_gradient_of(ORBIT), **kw)
    without = detumble_batch([MOMENTS], [[0.0, 0.0, 0.0]], [q], **kw)
    n = ORBIT.mean_motion
    expected = 1.5 * n * n * (MOMENTS[1] - MOMENTS[0]) / MOMENTS[2] * 2.0
    assert with_gg.omega[0, 2] == pytest.approx(expected, rel=1e-5)
    assert np.max(np.abs(without.omega)) < 1e-20


def test_the_compiled_and_numpy_paths_agree_with_every_term():
    """Gravity gradient, biases, noise, a star tracker's extra draws: the two paths to round-off."""
    I, w, q, g = _bodies(5, 3)
    sensors = [Sensors(gyro_noise=2e-4 * i, gyro_bias=(1e-4 * i, 0.0, -2e-4), magnetometer_noise=1e-7,
                       attitude="star_tracker" if i % 2 else "none", seed=100 + i) for i in range(5)]
    kw = {"field": FIELD, "gmst0": g, "gain": GAIN, "magnetorquers": Magnetorquers([0.2, 0.2, 0.1]), "period": 1.0,
          "t_end": 150.0, "substeps": 3, "gravity_gradient": gravity_gradient_of(ORBIT), "sensors": sensors}
    fast, slow = detumble_batch(I, w, q, **kw), detumble_batch(I, w, q, compiled=False, **kw)
    scale = np.max(np.abs(slow.rate))
    assert np.max(np.abs(fast.rate - slow.rate)) < 1e-12 * scale
    assert np.max(np.abs(fast.quat - slow.quat)) < 1e-11


@pytest.mark.parametrize("compiled", [True, False])
def test_a_bodys_noise_depends_only_on_its_own_sensors(compiled, monkeypatch):
    """Body 2 of a batch of 6, the same body alone, and the batch run in segments of 7 steps
    (the noise drawn 7 steps at a time): bit for bit the same."""
    I, w, q, g = _bodies(6, 8)
    sensors = [Sensors(gyro_noise=5e-4, gyro_bias=(0.0, 1e-3, 0.0), magnetometer_noise=2e-7, seed=s)
               for s in (5, 6, 7, 8, 9, 10)]
    kw = {"field": FIELD, "gain": GAIN, "magnetorquers": Magnetorquers(0.2), "period": 2.0, "t_end": 60.0,
          "gravity_gradient": gravity_gradient_of(ORBIT), "compiled": compiled}
    whole = detumble_batch(I, w, q, gmst0=g, sensors=sensors, **kw)
    alone = detumble_batch(I[2:3], w[2:3], q[2:3], gmst0=g[2:3], sensors=sensors[2:3], **kw)
    np.testing.assert_array_equal(whole.rate[2:3], alone.rate)
    monkeypatch.setattr(dt, "NOISE_VALUES", 6 * 6 * 7)
    segmented = detumble_batch(I, w, q, gmst0=g, sensors=sensors, **kw)
    np.testing.assert_array_equal(segmented.rate, whole.rate)
    np.testing.assert_array_equal(segmented.quat, whole.quat)
    one = detumble_batch(I, w, q, gmst0=g, sensors=Sensors(gyro_noise=5e-4, gyro_bias=(0.0, 1e-3, 0.0),
                                                            magnetometer_noise=2e-7, seed=5), **kw)
    np.testing.assert_array_equal(one.rate, whole.rate)  # one Sensors: body i draws from seed + i


def test_bad_models_name_the_field():
    args = ([MOMENTS], [[0.1, 0.0, 0.0]], [[0.0, 0.0, 0.0, 1.0]])
    kw = {"field": FIELD, "gmst0": 0.0, "gain": GAIN, "magnetorquers": Magnetorquers(0.2), "period": 1.0, "t_end": 5.0}
    with pytest.raises(ValueError, match="gravity_gradient has mean motion"):
        detumble_batch(*args, gravity_gradient=GravityGradient(orbit_period=6000.0), **kw)
    with pytest.raises(ValueError, match="gravity_gradient = "):
        detumble_batch(*args, gravity_gradient=True, **kw)
    with pytest.raises(ValueError, match="sequence of 1"):
        detumble_batch(*args, sensors=[Sensors(), Sensors()], **kw)


# --- the Monte Carlo --------------------------------------------------------------------------------

MC = {"field": FIELD, "gain": GAIN, "magnetorquers": Magnetorquers(0.2), "period": 2.0, "t_end": 120.0,
      "threshold": 0.05, "gravity_gradient": gravity_gradient_of(ORBIT),
      "sensors": Sensors(gyro_noise=5e-4, magnetometer_noise=2e-7, magnetometer_bias=(0.0, 1e-7, 0.0)),
      "history": 9}


def _mc_cases(n=60):
    from tumble.ensemble.detumble import detumble_cases

    return detumble_cases(n, moments=MOMENTS, rate_min=0.02, rate_max=0.15, gyro_bias_sigma=1e-3, seed=13)


def test_the_monte_carlo_does_not_depend_on_the_chunking_or_the_backend():
    """Chunks of 7 and of 50 cases, and a Dask cluster (threads of this process): the same times
    and histories, bit for bit, noise and per-case biases included."""
    from tumble.ensemble.detumble import detumble_monte_carlo

    cases = _mc_cases()
    a = detumble_monte_carlo(cases, chunk=7, **MC)
    b = detumble_monte_carlo(cases, chunk=50, **MC)
    np.testing.assert_array_equal(a.times, b.times)
    np.testing.assert_array_equal(a.history, b.history)
    assert 0.0 < a.detumbled < 1.0  # a distribution, not all alike
    distributed = pytest.importorskip("dask.distributed")
    from tumble.ensemble.backends import DaskBackend

    with distributed.LocalCluster(processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None,
                                  protocol="tcp", host="127.0.0.1") as cluster:
        backend = DaskBackend(scheduler=cluster.scheduler_address)
        try:
            c = detumble_monte_carlo(cases, chunk=7, backend=backend, **MC)
        finally:
            backend.close()
    np.testing.assert_array_equal(a.times, c.times)
    np.testing.assert_array_equal(a.history, c.history)


def test_a_monte_carlo_case_is_simulate_controlled_with_its_sensors():
    """Case 2 alone in the one-body loop with ``mc.case_sensors(2)`` (its bias, its seed) and the
    gravity gradient: the same rate history to RK4's error (8 substeps)."""
    from tumble.ensemble.detumble import detumble_monte_carlo

    cases = _mc_cases(6)
    kw = dict(MC, history=61, period=1.0, t_end=60.0)
    mc = detumble_monte_carlo(cases, substeps=8, **kw)
    i = 2
    I = cases.moments[i]
    assert np.all(np.diff(I) > 0)  # simulate_controlled wants I1 <= I2 <= I3: this case has it
    run = simulate_controlled(I, cases.omega0[i], t_end=60.0, attitude0=cases.quat0[i],
                              controller=BDot(GAIN, period=1.0, form="normalized"),
                              field=DipoleField(ORBIT, gmst0=float(cases.gmst0[i])), magnetorquers=Magnetorquers(0.2),
                              gravity_gradient=gravity_gradient_of(ORBIT), sensors=mc.case_sensors(i))
    assert np.array_equal(mc.history_t, run.t)
    assert np.max(np.abs(mc.history[i] - run.rate)) < 1e-9
    assert np.any(mc.case_sensors(i).gyro_bias != mc.case_sensors(i - 1).gyro_bias)


def test_the_summary_is_the_sorted_times():
    """Percentiles, maximum, fractions and the worst cases against a plain sort of the times."""
    from tumble.ensemble.detumble import detumble_monte_carlo

    cases = _mc_cases()
    mc = detumble_monte_carlo(cases, chunk=25, **MC)
    s = mc.summary(worst=4)
    finite = np.sort(mc.times[np.isfinite(mc.times)])
    key = np.sort(np.where(np.isfinite(mc.times), mc.times, np.inf))
    n = len(mc.times)
    assert s["cases"] == n and s["not_detumbled"] == n - len(finite) > 0
    assert s["detumbled"] == len(finite) / n and s["max_s"] == finite[-1]
    for name, p in (("median_s", 50), ("p95_s", 95), ("p99_s", 99)):
        value = key[math.ceil(p / 100 * (n - 1))]  # numpy's "higher" method
        assert s[name] == value or (math.isnan(s[name]) and math.isinf(value))
    never = np.flatnonzero(~np.isfinite(mc.times))
    finals = mc.history[never, -1]
    expected = list(never[np.argsort(-finals)])[:4]
    assert [w["index"] for w in s["worst"]] == expected
    assert s["worst"][0]["final_rate"] == finals.max() > MC["threshold"]
    assert s["worst"][0]["moments"] == cases.moments[expected[0]].tolist()
    assert s["gravity_gradient"] and s["gyro_noise_rad_s"] == 5e-4
    bands = mc.rate_percentiles([5, 50, 95])
    assert np.all(bands[0] <= bands[1]) and np.all(bands[1] <= bands[2])
    np.testing.assert_array_equal(bands[1], np.percentile(mc.history, 50, axis=0))


def test_the_gyro_bias_disperses_the_cases():
    """The cases' gyro biases are Gaussian with the given sigma (180 numbers: the sample standard
    deviation within 15 %), and without them (sigma 0) the same cases are drawn as before."""
    from tumble.ensemble.detumble import detumble_cases

    cases = _mc_cases()
    assert np.std(cases.gyro_bias) == pytest.approx(1e-3, rel=0.15)
    plain = detumble_cases(60, moments=MOMENTS, rate_min=0.02, rate_max=0.15, seed=13)
    np.testing.assert_array_equal(plain.omega0, cases.omega0)
    np.testing.assert_array_equal(plain.quat0, cases.quat0)
    assert not np.any(plain.gyro_bias)
    with pytest.raises(ValueError, match="gyro_bias_sigma"):
        detumble_cases(3, moments=MOMENTS, rate_min=0.1, rate_max=0.2, gyro_bias_sigma=-1.0)
