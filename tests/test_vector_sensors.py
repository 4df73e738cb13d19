"""The vector sensors (tumble.dynamics.models.vector_sensors) and their place in Sensors: each
reading's stated noise against the spread of many seeded readings, the eclipse and the field of
view, the sensors' own rates, and bad input in one line."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from scipy.stats import chi2

from tumble.dynamics.environment.orbit import CircularOrbit
from tumble.dynamics.environment.sun import Sunlight
from tumble.dynamics.models.sensors import Sensors
from tumble.dynamics.models.vector_sensors import CoarseSunSensor, FineSunSensor, StarTracker

TRIALS = 3000


def _normalised_angles(sensor, s, light, seed):
    """Squared angle of each reading from the truth over its stated variance: chi2(2) when the
    stated noise is the spread (a direction's error has two components across it)."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(TRIALS):
        v, sigma = sensor.measure(s, light, rng)
        out.append(np.arccos(min(1.0, float(v @ s))) ** 2 / sigma**2)
    return np.array(out)


def _band(n: int, dof: int) -> tuple[float, float]:
    lo, hi = chi2.ppf([0.0005, 0.9995], dof * n) / n
    return lo, hi


@pytest.mark.parametrize("light", [1.0, 0.4])
def test_coarse_sun_sensor_states_its_noise(light):
    """Six cells on a cube's faces: the direction's error is isotropic across it and the stated
    noise is its spread, in full Sun and in the penumbra (where the currents are smaller)."""
    s = np.array([0.3, -0.5, 0.6])
    s /= np.linalg.norm(s)
    z = _normalised_angles(CoarseSunSensor(noise=5e-3), s, light, 1)
    lo, hi = _band(TRIALS, 2)
    assert lo < z.mean() < hi


def test_coarse_sun_sensor_with_skewed_pairs_is_conservative():
    """Four pairs along a tetrahedron's axes: the stated noise is the largest across the direction,
    so the normalised error is at most chi2(2)'s."""
    axes = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
    s = np.array([0.0, 0.6, 0.8])
    z = _normalised_angles(CoarseSunSensor(axes=axes, noise=5e-3), s, 1.0, 2)
    assert z.mean() < _band(TRIALS, 2)[1]
    assert z.mean() > 0.5 * 2.0


def test_fine_sun_sensor_at_the_boresight_and_out_of_view():
    fss = FineSunSensor(frame=Rotation.from_euler("x", 90, degrees=True), fov=math.radians(30), noise=1e-3)
    boresight = fss.frame.apply([0.0, 0.0, 1.0])
    z = _normalised_angles(fss, boresight, 1.0, 3)
    lo, hi = _band(TRIALS, 2)
    assert lo < z.mean() < hi
    # 20 deg off the boresight the stated noise still bounds the error
    off = fss.frame.apply([math.sin(math.radians(20)), 0.0, math.cos(math.radians(20))])
    assert _normalised_angles(fss, off, 1.0, 4).mean() < hi
    rng = np.random.default_rng(0)
    outside = fss.frame.apply([math.sin(math.radians(31)), 0.0, math.cos(math.radians(31))])
    assert fss.measure(outside, 1.0, rng) is None
    assert fss.measure(boresight, 0.0, rng) is None   # umbra


def test_star_tracker_covariance_in_the_body():
    st = StarTracker(frame=Rotation.from_euler("zy", [40, 70], degrees=True), cross=2e-5, roll=2e-4)
    rng = np.random.default_rng(5)
    truth = Rotation.random(random_state=7)
    errs = np.array([(truth.inv() * st.measure(truth, rng)).as_rotvec() for _ in range(TRIALS)])
    nees = np.einsum("ki,ij,kj->k", errs, np.linalg.inv(st.covariance), errs)
    lo, hi = _band(TRIALS, 3)
    assert lo < nees.mean() < hi
    # the wide axis is the boresight, turned into the body
    w, V = np.linalg.eigh(st.covariance)
    assert abs(V[:, -1] @ st.frame.apply([0.0, 0.0, 1.0])) == pytest.approx(1.0)


def test_sensors_read_at_their_own_rates_and_not_in_the_shadow():
    orbit = CircularOrbit(altitude=500e3)
    light = Sunlight(orbit, "2026-03-20T14:46:00")
    suite = Sensors(sun_sensor=CoarseSunSensor(noise=1e-3, period=2.0), star_tracker=StarTracker(cross=1e-5, roll=1e-4, period=5.0),
                    sunlight=light)
    rng = suite.rng()
    got = [suite.sample(t, np.zeros(3), Rotation.identity(), None, np.zeros(0), rng) for t in np.arange(0.0, 10.5, 0.5)]
    assert [m.t for m in got if m.sun is not None] == [0.0, 2.0, 4.0, 6.0, 8.0, 10.0]
    assert [m.t for m in got if m.star_tracker is not None] == [0.0, 5.0, 10.0]
    dark = suite.sample(orbit.period / 2, np.zeros(3), Rotation.identity(), None, np.zeros(0), rng)
    assert dark.sun is None and float(light.fraction(orbit.period / 2)) == 0.0


@pytest.mark.parametrize(("make", "message"), [
    (lambda: Sensors(sun_sensor=CoarseSunSensor()), r"^a sun_sensor needs sunlight = Sunlight\(orbit, epoch\)"),
    (lambda: Sensors(star_tracker="yes"), r"^star_tracker = 'yes' must be a StarTracker$"),
    (lambda: CoarseSunSensor(axes=[[1, 0, 0], [0, 1, 0]]), r"^axes = .* must be at least 3 directions spanning space"),
    (lambda: CoarseSunSensor(noise=-1.0), r"^noise = -1.0 must be"),
    (lambda: FineSunSensor(fov=2.0), r"^fov = 2.0 is beyond 1.5708 rad$"),
    (lambda: StarTracker(roll=float("nan")), r"^roll = nan must be"),
    (lambda: StarTracker(period=-1.0), r"^period = -1.0 must be"),
    (lambda: Sunlight(CircularOrbit(altitude=500e3), "2026-03-20T14:46:00", shadow="cone"),
     r"^shadow = 'cone' is unknown; allowed: conical, cylindrical, none$"),
    (lambda: Sunlight(CircularOrbit(altitude=500e3), "yesterday"), r"^epoch = 'yesterday' is not an ISO 8601"),
])
def test_bad_input_one_line(make, message):
    with pytest.raises(ValueError, match=message) as info:
        make()
    assert "\n" not in str(info.value)
