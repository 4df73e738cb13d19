"""Sensors with noise and bias, sampled at the controller's period: gyroscope, magnetometer,
attitude (ideal or a star tracker), and the vector sensors of
:mod:`~tumble.dynamics.models.vector_sensors` (sun sensors and a star tracker with its own
frame and rate).

Each reading is the true value plus a constant bias plus white Gaussian noise drawn anew at
every sample (the discrete form of the usual rate-gyro model without the bias random walk;
Crassidis & Junkins, *Optimal Estimation of Dynamic Systems*, 2nd ed., sec. 7.2.1). A star
tracker's attitude is the true one turned by a small random rotation whose rotation vector has
independent components of standard deviation ``attitude_noise`` (rad) about each body axis.
Readings are in the body's principal frame; the controller holds them until its next step.
A sun sensor reads the Sun's direction from :class:`~tumble.dynamics.environment.sun.Sunlight`
(the Sun along the orbit and the Earth's shadow) and gives nothing in the umbra.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from ..._html import field_repr
from ...typing import ArrayLike, FloatArray
from ...validation import check_noise, check_positive, check_vector
from ..environment.sun import Sunlight
from ..special.quaternion import turned_by
from .vector_sensors import CoarseSunSensor, FineSunSensor, StarTracker, on_period

__all__ = ["MAX_GYRO_ERROR", "MAX_MAGNETOMETER_NOISE", "Measurement", "Sensors"]

#: The largest magnetometer noise, and bias component, taken, T: past the Earth's field itself (~6.5e-5 T at most at the
#: surface, ~2-5e-5 T in low orbit) a reading says nothing of it; a noise in nT written as T is 1e9 times it.
MAX_MAGNETOMETER_NOISE = 1e-4
#: The largest gyroscope noise or bias taken, rad/s (11 deg/s): a phone's MEMS gyroscope has up to
#: ~0.1 rad/s of bias uncalibrated, a spacecraft's 1e-6-1e-4; past it a value in deg/s written as
#: rad/s is most likely (a walkthrough's bias of 2 "rad/s" for 2 deg/s ran, the knowledge lost).
MAX_GYRO_ERROR = 0.2
_RATE_HINT = "is it in deg/s? Give rad/s (1 deg/s = 0.01745 rad/s)"


@dataclass(frozen=True)
class Measurement:
    """What a controller sees at one of its steps.

    Attributes
    ----------
    t : float
        Time, s.
    omega : ndarray, shape (3,)
        Gyroscope reading, principal frame, rad/s.
    field : ndarray, shape (3,) or None
        Magnetometer reading, principal frame, T (None without a field).
    attitude : scipy Rotation or None
        Body (principal) to world, measured (None when no attitude sensor is fitted).
    wheel_speed : ndarray, shape (k,)
        Wheel spins relative to the body, rad/s (the tachometers; exact).
    sun : ndarray, shape (3,) or None
        The sun sensor's measured direction of the Sun, principal frame, unit (None without a
        sun sensor, between its readings, in the umbra or out of its field of view).
    sun_sigma : float
        That direction's angular noise, rad.
    star_tracker : scipy Rotation or None
        The star tracker's attitude, body to world (None without one or between its readings).

    Examples
    --------
    :meth:`Sensors.sample` makes them; without wheels the tachometers read nothing:

    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.models.sensors import Measurement
    >>> m = Measurement(t=2.0, omega=np.array([0.0, 0.0, 0.1]), field=None, attitude=Rotation.identity())
    >>> m.omega.tolist(), m.field is None, m.wheel_speed.shape
    ([0.0, 0.0, 0.1], True, (0,))
    """

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    t: float
    omega: FloatArray
    field: FloatArray | None
    attitude: Rotation | None
    wheel_speed: FloatArray = dataclasses.field(default_factory=lambda: np.zeros(0))
    sun: FloatArray | None = None
    sun_sigma: float = 0.0
    star_tracker: Rotation | None = None


def _vec(name: str, value: ArrayLike, unit: str) -> FloatArray:
    return np.array(check_vector(name, value, unit))


@dataclass(frozen=True)
class Sensors:
    """The sensor suite: noise standard deviations and constant biases, and a seed.

    Parameters
    ----------
    gyro_noise : float
        Standard deviation of each gyroscope axis, rad/s (>= 0).
    gyro_bias : array_like, shape (3,)
        Constant gyroscope bias, rad/s, principal frame (a control file's is in the design frame and
        turned into this one).
    magnetometer_noise : float
        Standard deviation of each magnetometer axis, T (>= 0).
    magnetometer_bias : array_like, shape (3,)
        Constant magnetometer bias, T, principal frame (as ``gyro_bias``).
    attitude : {"ideal", "star_tracker", "none"}
        The attitude sensor: exact, noisy, or none fitted.
    attitude_noise : float
        Star tracker noise about each axis, rad (>= 0).
    seed : int
        Seed of the noise (numpy's default generator): a run is reproducible.
    sun_sensor : CoarseSunSensor or FineSunSensor, optional
        A sun sensor (:mod:`~tumble.dynamics.models.vector_sensors`); needs ``sunlight``.
    star_tracker : StarTracker, optional
        A star tracker with its own frame, rate and noise.
    sunlight : Sunlight, optional
        The Sun's direction and the Earth's shadow along the orbit, for the sun sensor.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> s = Sensors()
    >>> m = s.sample(0.0, np.array([0.1, 0.0, 0.0]), Rotation.identity(), np.array([0.0, 2e-5, 0.0]),
    ...              np.zeros(0), np.random.default_rng(0))
    >>> m.omega.tolist(), m.field.tolist()
    ([0.1, 0.0, 0.0], [0.0, 2e-05, 0.0])
    """

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    gyro_noise: float = 0.0
    gyro_bias: tuple[float, float, float] = (0.0, 0.0, 0.0)
    magnetometer_noise: float = 0.0
    magnetometer_bias: tuple[float, float, float] = (0.0, 0.0, 0.0)
    attitude: str = "ideal"
    attitude_noise: float = 0.0
    seed: int = 0
    sun_sensor: CoarseSunSensor | FineSunSensor | None = None
    star_tracker: StarTracker | None = None
    sunlight: Sunlight | None = None

    def __post_init__(self) -> None:
        check_noise("gyro_noise", self.gyro_noise, "rad/s", MAX_GYRO_ERROR, "a gyroscope", _RATE_HINT)
        check_positive("magnetometer_noise", self.magnetometer_noise, "T", allow_zero=True)
        check_positive("attitude_noise", self.attitude_noise, "rad", allow_zero=True)
        # noise no sensor has: most likely a unit slip (a walkthrough's 100 "T" for 100 nT ran, the field lost in it)
        if self.magnetometer_noise > MAX_MAGNETOMETER_NOISE:
            raise ValueError(f"magnetometer_noise = {self.magnetometer_noise!r} T is more than the Earth's field (at most "
                             f"~6.5e-5 T at the surface); allowed: 0 to {MAX_MAGNETOMETER_NOISE:g} T: is it in nT? Give "
                             f"tesla (100 nT = 1e-7 T)")
        if self.attitude_noise > math.pi:
            raise ValueError(f"attitude_noise = {self.attitude_noise!r} rad: a spread past pi says nothing of an angle; "
                             f"allowed: 0 to pi rad: is it in arcsec or deg? Give radians (4 arcsec = 2e-5 rad)")
        object.__setattr__(self, "gyro_bias", check_vector("gyro_bias", self.gyro_bias, "rad/s"))
        if max(map(abs, self.gyro_bias)) > MAX_GYRO_ERROR:
            raise ValueError(f"gyro_bias = {list(self.gyro_bias)!r} rad/s is more than any gyroscope's bias (a phone's "
                             f"MEMS gyroscope: up to ~0.1 rad/s); allowed: each within {MAX_GYRO_ERROR:g} rad/s: {_RATE_HINT}")
        object.__setattr__(self, "magnetometer_bias", check_vector("magnetometer_bias", self.magnetometer_bias, "T"))
        if max(map(abs, self.magnetometer_bias)) > MAX_MAGNETOMETER_NOISE:  # a walkthrough's [100, 0, 0] "T" ran
            raise ValueError(f"magnetometer_bias = {list(self.magnetometer_bias)!r} T is more than the Earth's field (at "
                             f"most ~6.5e-5 T at the surface); allowed: each within {MAX_MAGNETOMETER_NOISE:g} T: is it in "
                             f"nT? Give tesla (100 nT = 1e-7 T)")
        if self.attitude not in ("ideal", "star_tracker", "none"):
            raise ValueError(f"attitude = {self.attitude!r} is unknown; allowed: ideal, star_tracker, none")
        if isinstance(self.seed, bool) or not isinstance(self.seed, (int, np.integer)) or self.seed < 0:
            raise ValueError(f"seed = {self.seed!r} must be a non-negative integer")
        if self.sun_sensor is not None and not isinstance(self.sun_sensor, (CoarseSunSensor, FineSunSensor)):
            raise ValueError(f"sun_sensor = {self.sun_sensor!r} must be a CoarseSunSensor or a FineSunSensor")
        if self.star_tracker is not None and not isinstance(self.star_tracker, StarTracker):
            raise ValueError(f"star_tracker = {self.star_tracker!r} must be a StarTracker")
        if self.sun_sensor is not None and not isinstance(self.sunlight, Sunlight):
            raise ValueError("a sun_sensor needs sunlight = Sunlight(orbit, epoch): the Sun's direction and the "
                             "Earth's shadow along the orbit")

    def rng(self) -> np.random.Generator:
        """A fresh noise generator from :attr:`seed`.

        Examples
        --------
        Each call starts the same stream again, so a run with the same seed repeats exactly:

        >>> import numpy as np
        >>> from tumble.dynamics.models.sensors import Sensors
        >>> sensors = Sensors(gyro_noise=1e-3, seed=7)
        >>> np.array_equal(sensors.rng().standard_normal(4), sensors.rng().standard_normal(4))
        True
        >>> np.array_equal(Sensors(seed=8).rng().standard_normal(4), sensors.rng().standard_normal(4))
        False
        """
        return np.random.default_rng(int(self.seed))

    def sample(self, t: float, omega: FloatArray, attitude: Rotation, field_body: FloatArray | None,
               wheel_speed: FloatArray, rng: np.random.Generator) -> Measurement:
        """One reading of every sensor from the true state (rad/s, body to world, T, rad/s).

        Examples
        --------
        The bias shows in the mean of many readings, the noise in their spread (2,000 seeded
        samples: the standard error of the mean is ``1e-3 / sqrt(2000) = 2.2e-5`` rad/s):

        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.models.sensors import Sensors
        >>> sensors = Sensors(gyro_noise=1e-3, gyro_bias=(2e-3, 0.0, -1e-3), attitude="none")
        >>> rng, omega = sensors.rng(), np.array([0.1, 0.0, 0.0])
        >>> readings = np.array([sensors.sample(0.0, omega, Rotation.identity(), None, np.zeros(0), rng).omega
        ...                      for _ in range(2000)])
        >>> bool(np.all(np.abs(readings.mean(axis=0) - (omega + [2e-3, 0.0, -1e-3])) < 1e-4))
        True
        >>> bool(np.allclose(readings.std(axis=0), 1e-3, rtol=0.1))
        True

        A star tracker turns the attitude by a small random angle (about ``attitude_noise`` per
        axis); the ``"none"`` sensor gives no attitude:

        >>> tracker = Sensors(attitude="star_tracker", attitude_noise=1e-4)
        >>> m = tracker.sample(0.0, omega, Rotation.identity(), None, np.zeros(0), tracker.rng())
        >>> bool(0.0 < m.attitude.magnitude() < 1e-3)
        True
        >>> sensors.sample(0.0, omega, Rotation.identity(), None, np.zeros(0), rng).attitude is None
        True

        Six coarse sun cells on a 500 km equatorial orbit at the equinox read the Sun (along world x
        at t = 0) and nothing half an orbit later, in the Earth's shadow:

        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> from tumble.dynamics.environment.sun import Sunlight
        >>> from tumble.dynamics.models.vector_sensors import CoarseSunSensor
        >>> orbit = CircularOrbit(altitude=500e3)
        >>> suite = Sensors(sun_sensor=CoarseSunSensor(noise=1e-3), sunlight=Sunlight(orbit, "2026-03-20T14:46:00"))
        >>> lit = suite.sample(0.0, omega, Rotation.identity(), None, np.zeros(0), suite.rng())
        >>> (np.round(lit.sun, 2) + 0.0).tolist(), round(lit.sun_sigma, 4)
        ([1.0, 0.0, 0.0], 0.0014)
        >>> suite.sample(orbit.period / 2, omega, Rotation.identity(), None, np.zeros(0), suite.rng()).sun is None
        True
        """
        w = omega + np.asarray(self.gyro_bias) + self.gyro_noise * rng.standard_normal(3)
        b = None
        if field_body is not None:
            b = field_body + np.asarray(self.magnetometer_bias) + self.magnetometer_noise * rng.standard_normal(3)
        att: Rotation | None = None
        if self.attitude == "ideal":
            att = attitude
        elif self.attitude == "star_tracker":
            n0, n1, n2 = (float(v) for v in self.attitude_noise * rng.standard_normal(3))
            x, y, z, s = (float(v) for v in attitude.as_quat())
            att = Rotation.from_quat(turned_by(x, y, z, s, n0, n1, n2))   # attitude * Rotation.from_rotvec(n)
        sun, sun_sigma = None, 0.0
        if self.sun_sensor is not None and self.sunlight is not None and on_period(t, self.sun_sensor.period):
            light = float(self.sunlight.fraction(t))
            seen = self.sun_sensor.measure(attitude.inv().apply(self.sunlight.world(t)), light, rng) if light > 0.0 else None
            if seen is not None:
                sun, sun_sigma = seen
        tracker = None
        if self.star_tracker is not None and on_period(t, self.star_tracker.period):
            tracker = self.star_tracker.measure(attitude, rng)
        return Measurement(float(t), np.asarray(w, float), b, att, np.array(wheel_speed, float), sun, sun_sigma, tracker)
