"""A built-in law fed its sensors' readings as they are, noise and bias and all, with no filter:
the whole loop in one compiled call (control/estimated_loop.py, ``plan_readings``), the same
run as the Python path's, where the sensors are sampled and the law called once a period.

The noise is drawn up front from the sensors' seeded generator in the order ``Sensors.sample``
draws it (gyroscope, magnetometer, the attitude sensor, the coarse cells when lit, the star
tracker when it reads), so the two paths see the same numbers and agree to round-off; a
mission's switch is its own ``observe`` on the rates the loop hands back.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tumble.dynamics.control import estimated_loop
from tumble.dynamics.control.bdot import BDot
from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.controllers import MomentumDumping, MRPFeedback
from tumble.dynamics.control.mission import DetumbleThenPoint
from tumble.dynamics.environment.magnetic import DipoleField
from tumble.dynamics.environment.orbit import CircularOrbit
from tumble.dynamics.environment.sun import Sunlight
from tumble.dynamics.models.actuators import Magnetorquers, ReactionWheels
from tumble.dynamics.models.orbit_gravity import gravity_gradient_of
from tumble.dynamics.models.sensors import Sensors
from tumble.dynamics.models.vector_sensors import CoarseSunSensor, FineSunSensor, StarTracker
from tumble.dynamics.special.quaternion import turned_by

MOMENTS = np.array([0.0067, 0.0419, 0.0419])  # kg m^2, a 3U CubeSat
RW = ReactionWheels(np.eye(3), inertia=2e-5, max_torque=2e-3, max_speed=630.0)
ORBIT = CircularOrbit(altitude=500e3, inclination=1.2, raan=0.4, arg_latitude=math.radians(100.0))
FIELD = DipoleField(ORBIT, gmst0=0.3)
EPOCH = "2026-03-20T14:46:00"


def _both(monkeypatch, controller_of, omega0=(0.05, -0.04, 0.03), **kwargs):
    """The run on the compiled loop and on the Python path (``plan_readings`` saying None), each
    with a fresh controller: (run, controller) twice; asserts which path each took."""
    runs, calls = [], []
    original = estimated_loop.run

    def spy(*args, **kw):
        calls.append(1)
        return original(*args, **kw)

    for compiled in (True, False):
        with monkeypatch.context() as m:
            m.setattr(estimated_loop, "run", spy)
            if not compiled:
                m.setattr(estimated_loop, "plan_readings", lambda *a: None)
            c = controller_of()
            runs.append((simulate_controlled(MOMENTS, omega0, controller=c, **kwargs), c))
        assert len(calls) == 1, "the compiled run did not take the readings' loop, or the Python one did"
    return runs


def _same(a, b, rel=1e-10):
    for name in ("omega", "wheel_speed", "wheel_torque", "dipole", "field"):
        x, y = getattr(a, name), getattr(b, name)
        assert x.shape == y.shape, name
        if y.size:
            assert np.max(np.abs(x - y)) <= rel * max(np.max(np.abs(y)), 1e-300), (name, np.max(np.abs(x - y)))
    assert np.max(np.abs(a.attitude.as_quat() - b.attitude.as_quat())) <= rel
    assert np.array_equal(a.t, b.t)


@pytest.mark.parametrize("form, derivative", [("normalized", "gyro"), ("classic", "difference")])
def test_bdot_on_a_noisy_biased_gyroscope_and_magnetometer_is_the_python_paths_run(monkeypatch, form, derivative):
    sensors = Sensors(gyro_noise=2e-4, gyro_bias=(3e-4, -2e-4, 1e-4), magnetometer_noise=2e-7,
                      magnetometer_bias=(1e-7, 0.0, -2e-7), attitude="none", seed=4)
    gain = 3e-3 if form == "normalized" else 2e4

    def controller_of():
        return BDot(gain=gain, period=0.5, form=form, derivative=derivative)

    (fast, _), (slow, _) = _both(monkeypatch, controller_of, t_end=120.0, field=FIELD,
                                 magnetorquers=Magnetorquers([0.2, 0.1, 0.15]), sensors=sensors,
                                 gravity_gradient=gravity_gradient_of(ORBIT),
                                 attitude0=Rotation.from_rotvec([0.3, -0.2, 1.0]))
    _same(fast, slow)
    assert np.abs(fast.dipole).max() > 0.0
    # the law saw the noise: the dipole differs from an ideal-sensor run's
    ideal = simulate_controlled(MOMENTS, (0.05, -0.04, 0.03), t_end=120.0, controller=controller_of(), field=FIELD,
                                magnetorquers=Magnetorquers([0.2, 0.1, 0.15]), gravity_gradient=gravity_gradient_of(ORBIT),
                                attitude0=Rotation.from_rotvec([0.3, -0.2, 1.0]))
    assert np.abs(ideal.dipole - fast.dipole).max() > 1e-3 * np.abs(ideal.dipole).max()


@pytest.mark.parametrize("moving", [False, True], ids=["fixed target", "nadir"])
def test_pointing_on_a_noisy_attitude_with_sun_cells_and_a_star_tracker_drawing_too(monkeypatch, moving):
    """MRP feedback with momentum dumping on the attitude sensor's reading (the truth turned by its
    noise), to a fixed target or tracking nadir; coarse sun cells through the eclipse's start and a
    star tracker every 5 s draw their noise, which no law reads, so the draws after them stay in step."""
    from tumble.dynamics.control.pointing import NadirTarget, target_attitude

    sensors = Sensors(gyro_noise=1e-4, gyro_bias=(2e-4, 0.0, -1e-4), magnetometer_noise=1e-7, attitude="star_tracker",
                      attitude_noise=3e-4, sun_sensor=CoarseSunSensor(noise=2e-3), sunlight=Sunlight(ORBIT, EPOCH),
                      star_tracker=StarTracker(cross=2e-5, roll=2e-4, period=5.0), seed=9)
    target = NadirTarget(ORBIT) if moving else Rotation.from_rotvec([0.1, -0.2, 0.3])

    def controller_of():
        point = MRPFeedback(K=1.1e-3, P=6e-3, period=1.0, moments=MOMENTS, wheels=RW, target=target)
        return MomentumDumping(point, gain=1e-3)

    (fast, _), (slow, _) = _both(monkeypatch, controller_of, omega0=(0.01, -0.02, 0.015), t_end=300.0, field=FIELD,
                                 magnetorquers=Magnetorquers(0.2), wheels=RW, sensors=sensors,
                                 attitude0=Rotation.from_rotvec([1.0, 0.5, -0.5]))
    _same(fast, slow)
    error = (target_attitude(target, fast.t).inv() * fast.attitude).magnitude()   # pointed to well within the first error
    assert error[-1] < 0.05 * error[0]


def test_a_fine_sun_sensor_that_draws_only_when_it_sees_the_sun_keeps_the_draws_in_step(monkeypatch):
    """A fine sun sensor with a 35 deg field of view on a tumbling body: it reads (two noise draws)
    only at the steps the Sun is in its view, which the state decides, so the draws after it (the
    star tracker's) move with them. B-dot on the readings; the Python path's run bit for bit."""
    fine = FineSunSensor(frame=Rotation.from_rotvec([0.0, 0.4, 0.0]), fov=math.radians(35.0), noise=1e-3)
    sensors = Sensors(gyro_noise=1e-4, magnetometer_noise=1e-7, attitude="none", sun_sensor=fine,
                      sunlight=Sunlight(ORBIT, EPOCH), star_tracker=StarTracker(cross=2e-5, roll=2e-4, period=2.0), seed=7)

    def controller_of():
        return BDot(gain=3e-3, period=0.5, form="normalized")

    (fast, _), (slow, _) = _both(monkeypatch, controller_of, omega0=(0.2, -0.15, 0.1), t_end=120.0, field=FIELD,
                                 magnetorquers=Magnetorquers(0.2), sensors=sensors)
    _same(fast, slow)
    seen = [fine.measure(R.inv().apply(sensors.sunlight.world(t)), float(sensors.sunlight.fraction(t)),
                         np.random.default_rng(0)) is not None for t, R in zip(fast.t, fast.attitude)]
    assert 10 < sum(seen) < len(seen) - 10   # in and out of view many times


def test_a_mission_on_noisy_sensors_switches_where_the_python_path_does(monkeypatch):
    """The shipped ``detumble_point`` pattern, shortened: B-dot on noisy readings until the
    gyroscope has read below 1 deg/s for 20 s, then pointing on a noisy attitude; a fine sun sensor
    beside them draws at the steps it sees the Sun, before the switch and after it (the loop's
    pause at the switch keeps the count of those draws)."""
    fine = FineSunSensor(frame=Rotation.from_rotvec([0.0, 0.4, 0.0]), fov=math.radians(85.0), noise=1e-3)
    sensors = Sensors(gyro_noise=1e-4, magnetometer_noise=1e-7, attitude="star_tracker", attitude_noise=2e-5,
                      sun_sensor=fine, sunlight=Sunlight(ORBIT, EPOCH), seed=1)

    def controller_of():
        point = MomentumDumping(MRPFeedback(K=1.1e-3, P=6e-3, period=1.0, moments=MOMENTS, wheels=RW), gain=1e-3)
        return DetumbleThenPoint(BDot(gain=3e-3, period=1.0, form="normalized"), point, switch_rate=0.0175, dwell=20.0)

    (fast, cf), (slow, cs) = _both(monkeypatch, controller_of, omega0=(0.02, -0.015, 0.01), t_end=400.0, field=FIELD,
                                   magnetorquers=Magnetorquers(0.2), wheels=RW, sensors=sensors)
    assert cf.switch_time is not None and cf.switch_time == cs.switch_time and 20.0 <= cf.switch_time < 300.0
    i = int(round(cf.switch_time))
    assert np.all(fast.wheel_torque[:i] == 0.0) and np.abs(fast.wheel_torque[i:]).max() > 0.0
    _same(fast, slow)
    seen = [fine.measure(R.inv().apply(sensors.sunlight.world(t)), 1.0, np.random.default_rng(0)) is not None
            for t, R in zip(fast.t[:i], fast.attitude[:i])]
    assert any(seen)   # draws before the switch: the pause kept them


def test_what_the_readings_loop_cannot_run_stays_python():
    """No attitude sensor under a pointing law (the Python path says why), a law of one's own and
    sensors that sample in their own way are not its; a fine sun sensor is."""
    from tumble.dynamics.control.estimated_loop import plan_readings

    noisy = Sensors(gyro_noise=1e-4, attitude="star_tracker", attitude_noise=1e-4)
    point = MRPFeedback(K=1e-3, P=1e-2, period=1.0, moments=MOMENTS, wheels=RW)
    assert len(plan_readings(point, noisy, MOMENTS, RW, None)) == 1
    blind = Sensors(gyro_noise=1e-4, attitude="none")
    assert plan_readings(point, blind, MOMENTS, RW, None) is None
    with pytest.raises(ValueError, match="MRP feedback needs an attitude reading and got none"):
        simulate_controlled(MOMENTS, (0.0, 0.0, 0.01), t_end=2.0, controller=point, wheels=RW, sensors=blind)
    fine = Sensors(gyro_noise=1e-4, sun_sensor=FineSunSensor(), sunlight=Sunlight(ORBIT, EPOCH))
    assert len(plan_readings(BDot(gain=1.0, period=1.0), fine, MOMENTS, None, None)) == 1

    class Mine(BDot):
        def __call__(self, t, m):
            return super().__call__(t, m)

    assert plan_readings(Mine(gain=1.0, period=1.0), noisy, MOMENTS, None, None) is None

    class Sampled(Sensors):   # sensors that sample in their own way
        def sample(self, *args, **kwargs):
            return super().sample(*args, **kwargs)

    assert plan_readings(BDot(gain=1.0, period=1.0), Sampled(gyro_noise=1e-4), MOMENTS, None, None) is None
    mission = DetumbleThenPoint(BDot(gain=1.0, period=1.0), point, switch_rate=0.01, dwell=1.0)
    assert len(plan_readings(mission, noisy, MOMENTS, RW, None)) == 2
    assert plan_readings(mission, blind, MOMENTS, RW, None) is None


@pytest.mark.parametrize("angle", [0.0, 3e-6, 9e-5, 1.1e-4, 2e-3, 0.4, 3.0])
def test_turned_by_is_scipys_rotation_by_a_rotation_vector(angle):
    """The attitude sensor's noise rotation, against scipy's ``attitude * Rotation.from_rotvec(r)``
    on both sides of the small-angle series (1e-4 rad)."""
    rng = np.random.default_rng(int(angle * 1e6) + 1)
    q = Rotation.random(random_state=rng)
    axis = rng.standard_normal(3)
    r = angle * axis / np.linalg.norm(axis)
    ours = np.array(turned_by(*(float(v) for v in q.as_quat()), *(float(v) for v in r)))
    theirs = (q * Rotation.from_rotvec(r)).as_quat()
    assert np.abs(ours - theirs * np.sign(theirs @ ours)).max() < 4e-16
