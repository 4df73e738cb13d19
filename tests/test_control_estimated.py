"""A controller fed the MEKF's estimate (tumble.dynamics.control.estimated) in the closed loop: the
estimate's error stays inside the filter's own 3-sigma bounds, the true pointing error is the
knowledge error, the sun sensor drops out in the Earth's shadow and the filter says so."""

from __future__ import annotations

import functools
import math

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

MOMENTS = [0.02, 0.03, 0.04]
RW = ReactionWheels(np.eye(3), inertia=1e-5, max_torque=2e-3)
TARGET = Rotation.from_rotvec([0.0, 0.4, 0.2])


@functools.lru_cache(maxsize=None)
def _run(estimate: bool, arg_latitude_deg: float = 0.0, tracker: bool = False, t_end: float = 300.0):
    """Point at TARGET from a 0.5 rad error; an equatorial orbit at the equinox, whose shadow
    begins about 68 deg of argument of latitude before the anti-Sun point (u = 180 deg)."""
    orbit = CircularOrbit(altitude=500e3, arg_latitude=math.radians(arg_latitude_deg), inclination=0.3)
    noise = {"gyro_noise": 1e-4, "gyro_bias": (3e-4, -2e-4, 1e-4), "magnetometer_noise": 2e-7} if estimate else {}
    sensors = Sensors(**noise, attitude="none" if estimate else "ideal",  # type: ignore[arg-type]
                      sun_sensor=CoarseSunSensor(noise=2e-3), sunlight=Sunlight(orbit, "2026-03-20T14:46:00"),
                      star_tracker=StarTracker(cross=2e-5, roll=2e-4, period=10.0) if tracker else None, seed=3)
    law = MRPFeedback(K=4e-3, P=1.2e-2, period=0.5, moments=MOMENTS, wheels=RW, target=TARGET)
    c = Estimated(law, sensors, DipoleField(orbit)) if estimate else law
    run = simulate_controlled(MOMENTS, [0.0, 0.0, 0.0], t_end=t_end, controller=c, field=DipoleField(orbit), wheels=RW,
                              sensors=sensors, attitude0=TARGET * Rotation.from_rotvec([0.5, 0.0, 0.0]))
    return run, (c.knowledge() if estimate else None)


@pytest.mark.parametrize(("u0", "tracker"), [(0.0, False), (100.0, False), (100.0, True)])
def test_knowledge_inside_its_own_bounds(u0, tracker):
    """Sunlit, through the eclipse's start, and with a star tracker: each axis's error inside 3
    sigma at (nearly) every step after the first minute, and the bias found."""
    run, k = _run(True, u0, tracker)
    e = k.error(run)
    late = k.t >= 60.0
    inside = np.all(np.abs(e[late]) < 3.0 * k.sigma[late, :3], axis=1)
    assert inside.mean() > 0.97
    assert np.allclose(k.bias[-1], [3e-4, -2e-4, 1e-4], atol=5e-5)


def test_the_eclipse_is_seen():
    """From u = 100 deg the body enters the umbra a few minutes in: the sun sensor stops exactly
    where the shadow's model says no light arrives, and the filter's uncertainty grows."""
    run, k = _run(True, 100.0)
    orbit = CircularOrbit(altitude=500e3, arg_latitude=math.radians(100.0), inclination=0.3)
    umbra = Sunlight(orbit, "2026-03-20T14:46:00").fraction(k.t) == 0.0
    assert 100.0 < k.t[umbra][0] < 250.0 and umbra[-1]
    assert np.array_equal(k.used[:, 1], ~umbra)
    lit_run, lit = _run(True, 0.0)
    assert lit.used[:, 1].all()
    s_dark, s_lit = k.sigma[:, :3].max(axis=1), lit.sigma[:, :3].max(axis=1)
    assert s_dark[-1] > 1.2 * s_lit[-1]   # 1.1 mrad against 0.76 (the largest axis)


def test_pointing_error_is_the_knowledge_error():
    """Fed the true attitude and rate the law settles on the target; fed the estimate (and the
    gyroscope less its estimated bias) it settles on the estimate, so the true pointing error ends
    at the knowledge error (to the law's own residual)."""
    truth_run, _ = _run(False)
    run, k = _run(True)
    late = run.t[:-1] >= 150.0     # settled (the law's time constant is about 6 s)

    def rms(x):
        return float(np.sqrt(np.mean(x**2)))

    with_truth = rms(truth_run.pointing_error(TARGET)[:-1][late])
    with_estimate = rms(run.pointing_error(TARGET)[:-1][late])
    knowledge = rms(np.linalg.norm(k.error(run), axis=1)[late])
    view = rms((TARGET.inv() * k.attitude).magnitude()[late])   # what the law sees of its own error
    assert with_truth < 1e-4 * with_estimate        # 3.8e-8 rad against 0.83 mrad
    assert with_estimate == pytest.approx(knowledge, rel=0.5)   # 0.83 mrad against 0.73
    assert with_estimate <= knowledge + view        # the triangle inequality of the two turns


def test_bad_input_and_no_start():
    law = MRPFeedback(K=1e-3, P=1e-2, period=0.5, moments=MOMENTS, wheels=RW)
    with pytest.raises(ValueError, match=r"^sensors = 'x' must be the run's Sensors$"):
        Estimated(law, "x")
    with pytest.raises(ValueError, match=r"^magnetometer_period = -1.0 must be"):
        Estimated(law, Sensors(), magnetometer_period=-1.0)
    with pytest.raises(ValueError, match=r"^the filter never started"):
        Estimated(law, Sensors()).knowledge()


def test_a_pointing_law_before_the_filter_starts_says_why():
    """In the umbra at t = 0, with no star tracker, the filter cannot start and MRP feedback has
    no attitude: one line saying so."""
    orbit = CircularOrbit(altitude=500e3, arg_latitude=math.pi)   # the anti-Sun point at the equinox
    sensors = Sensors(attitude="none", sun_sensor=CoarseSunSensor(), sunlight=Sunlight(orbit, "2026-03-20T14:46:00"))
    law = MRPFeedback(K=4e-3, P=1.2e-2, period=0.5, moments=MOMENTS, wheels=RW)
    with pytest.raises(ValueError, match=r"^t = 0 s: the attitude filter has not started .* MRP feedback needs an attitude"):
        simulate_controlled(MOMENTS, [0.0, 0.0, 0.0], t_end=1.0, controller=Estimated(law, sensors, DipoleField(orbit)),
                            field=DipoleField(orbit), wheels=RW, sensors=sensors)


def _both(monkeypatch, controller_of, omega0=(0.0, 0.0, 0.0), **kwargs):
    """One run on the compiled loop with the estimator (control/estimated_loop.py) and the same on
    the Python path (Estimated called each step, the same compiled hold intervals): each run, its
    filter's rows and its controller."""
    from tumble.dynamics.control import estimated_loop

    runs = []
    for compiled in (True, False):
        with monkeypatch.context() as m:
            if not compiled:
                m.setattr(estimated_loop, "plan", lambda *a: None)
            c = controller_of()
            run = simulate_controlled(MOMENTS, omega0, controller=c, wheels=RW, **kwargs)
            runs.append((run, c.knowledge(), c))
    return runs


@pytest.mark.parametrize("law", ["mrp", "bdot"])
def test_the_compiled_loop_is_the_python_path(monkeypatch, law):
    """The sensors, the MEKF and the law in one compiled call give the Python path's run to
    round-off (the same noise, drawn up front in the same order): through the eclipse's start
    (from u = 100 deg), with a star tracker every 10 s starting the filter; B-dot before a TRIAD
    start on a magnetometer and sun cells."""
    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.control.controllers import MomentumDumping
    from tumble.dynamics.models.actuators import Magnetorquers

    orbit = CircularOrbit(altitude=500e3, arg_latitude=math.radians(100.0), inclination=0.3)
    sensors = Sensors(gyro_noise=1e-4, gyro_bias=(3e-4, -2e-4, 1e-4), magnetometer_noise=2e-7, attitude="none",
                      sun_sensor=CoarseSunSensor(noise=2e-3), sunlight=Sunlight(orbit, "2026-03-20T14:46:00"),
                      star_tracker=StarTracker(cross=2e-5, roll=2e-4, period=10.0) if law == "mrp" else None, seed=3)
    if law == "mrp":
        def controller_of():
            point = MRPFeedback(K=4e-3, P=1.2e-2, period=0.5, moments=MOMENTS, wheels=RW, target=TARGET)
            return Estimated(MomentumDumping(point, gain=1e-3), sensors, DipoleField(orbit))
    else:
        def controller_of():
            return Estimated(BDot(gain=1e-3, period=0.5, form="normalized"), sensors, DipoleField(orbit))
    (fast, kf, _), (slow, ks, _) = _both(monkeypatch, controller_of, t_end=240.0, field=DipoleField(orbit),
                                   magnetorquers=Magnetorquers(0.2), sensors=sensors,
                                   attitude0=TARGET * Rotation.from_rotvec([0.5, 0.0, 0.0]))
    assert np.array_equal(kf.t, ks.t) and np.array_equal(kf.used, ks.used)
    assert not kf.used[:, 1].all() and kf.used[:, 1].any()          # the eclipse began
    assert kf.used[:, 2].sum() == (24 if law == "mrp" else 0)
    assert np.abs(fast.attitude.as_quat() - slow.attitude.as_quat()).max() < 1e-9
    assert np.abs(fast.omega - slow.omega).max() < 1e-11
    assert np.abs(fast.dipole - slow.dipole).max() < 1e-9
    assert np.abs(kf.attitude.as_quat() - ks.attitude.as_quat()).max() < 1e-9
    assert np.abs(kf.bias - ks.bias).max() < 1e-10
    assert np.allclose(kf.sigma, ks.sigma, rtol=1e-7, atol=0)


def test_a_fine_sun_sensor_starts_and_updates_the_filter_as_the_python_path_does(monkeypatch):
    """A fine sun sensor (35 deg field of view) on a slowly tumbling body: TRIAD starts the filter at
    the first step it sees the Sun with the magnetometer, its readings update the filter when it
    does, and its two draws only then; the compiled run and filter are the Python path's."""
    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.models.actuators import Magnetorquers
    from tumble.dynamics.models.vector_sensors import FineSunSensor

    orbit = CircularOrbit(altitude=500e3, arg_latitude=math.radians(40.0), inclination=0.3)
    fine = FineSunSensor(frame=Rotation.from_rotvec([0.3, 0.0, 0.0]), fov=math.radians(35.0), noise=5e-4)
    sensors = Sensors(gyro_noise=1e-4, gyro_bias=(3e-4, -2e-4, 1e-4), magnetometer_noise=2e-7, attitude="none",
                      sun_sensor=fine, sunlight=Sunlight(orbit, "2026-03-20T14:46:00"), seed=4)

    def controller_of():
        return Estimated(BDot(gain=1e-3, period=0.5, form="normalized"), sensors, DipoleField(orbit))

    (fast, kf, _), (slow, ks, _) = _both(monkeypatch, controller_of, omega0=(0.03, -0.04, 0.05), t_end=200.0,
                                         field=DipoleField(orbit), magnetorquers=Magnetorquers(0.2), sensors=sensors)
    assert np.array_equal(kf.t, ks.t) and np.array_equal(kf.used, ks.used)
    assert 5 < kf.used[:, 1].sum() < len(kf.t) - 5   # the sensor sees the Sun at some steps, not all
    assert np.abs(fast.omega - slow.omega).max() < 1e-11
    assert np.abs(fast.attitude.as_quat() - slow.attitude.as_quat()).max() < 1e-9
    assert np.abs(kf.attitude.as_quat() - ks.attitude.as_quat()).max() < 1e-9
    assert np.abs(kf.bias - ks.bias).max() < 1e-10


def test_a_mission_fed_the_estimate_is_the_python_paths_run(monkeypatch):
    """B-dot on the readings until the rate the law is handed (the gyroscope's, less the filter's
    bias once it has started) has stayed below 0.01 rad/s for 10 s, then MRP feedback with
    momentum dumping on the estimate: the compiled loop switches at the Python path's step, sets
    the mission's switch time, and gives its run to round-off; the mission's rule is its own
    ``observe`` on the rates the loop gives."""
    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.control.controllers import MomentumDumping
    from tumble.dynamics.control.estimated_loop import plan
    from tumble.dynamics.control.mission import DetumbleThenPoint
    from tumble.dynamics.models.actuators import Magnetorquers

    orbit = CircularOrbit(altitude=500e3, arg_latitude=math.radians(100.0), inclination=0.3)
    sensors = Sensors(gyro_noise=1e-4, gyro_bias=(3e-4, -2e-4, 1e-4), magnetometer_noise=2e-7, attitude="none",
                      sun_sensor=CoarseSunSensor(noise=2e-3), sunlight=Sunlight(orbit, "2026-03-20T14:46:00"), seed=5)

    def controller_of():
        point = MRPFeedback(K=4e-3, P=1.2e-2, period=0.5, moments=MOMENTS, wheels=RW, target=TARGET)
        mission = DetumbleThenPoint(BDot(gain=3e-3, period=0.5, form="normalized"), MomentumDumping(point, gain=1e-3),
                                    switch_rate=0.01, dwell=10.0)
        return Estimated(mission, sensors, DipoleField(orbit))

    (fast, kf, cf), (slow, ks, cs) = _both(monkeypatch, controller_of, omega0=(0.012, -0.01, 0.008), t_end=200.0,
                                           field=DipoleField(orbit), magnetorquers=Magnetorquers(0.2), sensors=sensors,
                                           attitude0=TARGET * Rotation.from_rotvec([0.5, 0.0, 0.0]))
    assert len(plan(cf, sensors, np.array(MOMENTS), RW, DipoleField(orbit))) == 2   # both modes compiled
    switch = cf.controller.switch_time
    assert switch is not None and 10.0 < switch < 150.0 and switch == cs.controller.switch_time
    i = int(round(switch / 0.5))
    assert np.all(fast.wheel_torque[:i] == 0.0) and np.abs(fast.wheel_torque[i:]).max() > 0.0   # B-dot, then the wheels
    assert np.linalg.norm(fast.omega[i - 20:i + 1], axis=1).max() < 0.011 < np.linalg.norm(fast.omega[0])
    assert np.array_equal(kf.t, ks.t) and np.array_equal(kf.used, ks.used)
    assert np.abs(fast.attitude.as_quat() - slow.attitude.as_quat()).max() < 1e-9
    assert np.abs(fast.omega - slow.omega).max() < 1e-11
    assert np.abs(fast.dipole - slow.dipole).max() < 1e-9
    assert np.abs(fast.wheel_torque - slow.wheel_torque).max() < 1e-9
    assert np.abs(kf.bias - ks.bias).max() < 1e-10
    assert np.allclose(kf.sigma, ks.sigma, rtol=1e-7, atol=0)


def test_a_mission_that_never_switches_detumbles_throughout(monkeypatch):
    """A switch rate the run never gets below: B-dot the whole run, no switch time, the Python
    path's run."""
    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.control.mission import DetumbleThenPoint
    from tumble.dynamics.models.actuators import Magnetorquers

    orbit = CircularOrbit(altitude=500e3, inclination=0.3)
    sensors = Sensors(gyro_noise=1e-4, magnetometer_noise=2e-7, attitude="none", sun_sensor=CoarseSunSensor(noise=2e-3),
                      sunlight=Sunlight(orbit, "2026-03-20T14:46:00"), seed=2)

    def controller_of():
        point = MRPFeedback(K=4e-3, P=1.2e-2, period=1.0, moments=MOMENTS, wheels=RW)
        return Estimated(DetumbleThenPoint(BDot(gain=3e-3, period=1.0, form="normalized"), point, switch_rate=1e-4,
                                           dwell=5.0), sensors, DipoleField(orbit))

    (fast, kf, cf), (slow, _, cs) = _both(monkeypatch, controller_of, omega0=(0.05, 0.0, 0.0), t_end=60.0,
                                          field=DipoleField(orbit), magnetorquers=Magnetorquers(0.2), sensors=sensors)
    assert cf.controller.switch_time is None and cs.controller.switch_time is None
    assert np.all(fast.wheel_torque == 0.0) and np.abs(fast.dipole).max() > 0.0
    assert np.abs(fast.omega - slow.omega).max() < 1e-11
    assert np.abs(fast.attitude.as_quat() - slow.attitude.as_quat()).max() < 1e-9


def test_what_the_compiled_loop_cannot_run_stays_python():
    """A law of the user's own, or sensors other than the filter's keep the Python path
    (estimated_loop.plan says None); a fine sun sensor does not."""
    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.control.estimated_loop import plan
    from tumble.dynamics.control.mission import DetumbleThenPoint
    from tumble.dynamics.models.vector_sensors import FineSunSensor

    orbit = CircularOrbit(altitude=500e3)
    light = Sunlight(orbit, "2026-03-20T14:46:00")
    coarse = Sensors(gyro_noise=1e-4, sun_sensor=CoarseSunSensor(noise=1e-3), sunlight=light)
    fine = Sensors(gyro_noise=1e-4, sun_sensor=FineSunSensor(noise=1e-3), sunlight=light)
    moments = np.array(MOMENTS)

    class Mine(BDot):
        def __call__(self, t, m):
            return super().__call__(t, m)

    assert len(plan(Estimated(BDot(gain=1.0, period=1.0), coarse), coarse, moments, None, None)) == 1
    assert len(plan(Estimated(BDot(gain=1.0, period=1.0), fine), fine, moments, None, None)) == 1
    assert plan(Estimated(Mine(gain=1.0, period=1.0), coarse), coarse, moments, None, None) is None
    assert plan(Estimated(BDot(gain=1.0, period=1.0), coarse), Sensors(), moments, None, None) is None

    class MyMission(DetumbleThenPoint):
        def __call__(self, t, m):
            return super().__call__(t, m)

    point = MRPFeedback(K=1e-3, P=1e-2, period=1.0, moments=MOMENTS, wheels=RW)
    for cls, laws in ((DetumbleThenPoint, 2), (MyMission, None)):
        mission = cls(BDot(gain=1.0, period=1.0), point, switch_rate=0.01, dwell=1.0)
        found = plan(Estimated(mission, coarse), coarse, moments, RW, None)
        assert (found if laws is None else len(found)) == laws
    fine_point = DetumbleThenPoint(BDot(gain=1.0, period=1.0), MRPFeedback(K=1e-3, P=1e-2, period=1.0, moments=[1.0, 2.0, 3.0],
                                                                          wheels=RW), switch_rate=0.01, dwell=1.0)
    assert plan(Estimated(fine_point, coarse), coarse, moments, RW, None) is None   # a mode not on the run's moments
