"""Attitude sensors beyond the gyroscope: coarse and fine sun sensors and a star tracker, each
with its own mounting, rate and noise.

Each gives what an attitude filter takes: a measured direction in the body frame with its
angular noise (the sun sensors), or a measured attitude with its covariance about the body axes
(the star tracker); :class:`~tumble.dynamics.models.sensors.Sensors` reads them in the loop. The
magnetometer is :class:`~tumble.dynamics.models.sensors.Sensors`' own (its direction's noise is
``magnetometer_noise / |B|``).

- **Coarse sun sensor**: cosine cells (a photocell's current is proportional to the cosine of
  the Sun's angle from its normal, zero when the Sun is behind it; Wertz, ed., *Spacecraft
  Attitude Determination and Control*, Reidel 1978, sec. 6.1). Cells come in opposed pairs along
  ``axes``; a pair's difference is ``f (a . s)`` exactly, whatever side is lit, so the Sun's
  direction is the least-squares solution ``v = (A^T A)^-1 A^T d`` of the differences
  ``d`` (``f`` the light fraction, 1 in full Sun). Each cell's reading has white noise of
  ``noise`` (fraction of a full-Sun current), so ``d`` has ``2 noise^2`` and ``v`` has
  ``2 noise^2 (A^T A)^-1``; the angular noise stated across the direction is the largest across
  it, ``sqrt(2 noise^2 lambda_max) / |v|``. The Earth's albedo is not modelled.
- **Fine sun sensor**: a two-axis head with boresight ``z`` of its own frame (``frame`` turns it
  into the body), reading the angles ``alpha = atan2(s_x, s_z)`` and ``beta = atan2(s_y, s_z)``
  with white noise ``noise`` (rad) each, and nothing when the Sun is more than ``fov`` from the
  boresight. The direction ``(tan alpha, tan beta, 1)`` normalised has noise ``noise`` across it
  at the boresight, less off it; ``noise`` is stated.
- **Star tracker**: a measured attitude ``A exp([C v x])`` with ``v`` of standard deviations
  ``(cross, cross, roll)`` about the sensor's ``x, y`` and boresight ``z`` (the usual
  narrow-across, wide-about-boresight error of a tracker; Markley & Crassidis 2014, sec. 5.5),
  ``C`` the sensor-to-body rotation. Sun and Earth exclusion are not modelled.

A sensor with a ``period`` reads at the control steps that fall on its multiples (the period a
multiple of the controller's); none gives anything in the Earth's shadow (the sun sensors) or
out of its field of view.

Examples
--------
Six cells on a cube's faces see the Sun's direction; none in the umbra:

>>> import numpy as np
>>> from tumble.dynamics.models.vector_sensors import CoarseSunSensor
>>> css = CoarseSunSensor(noise=0.0)
>>> v, sigma = css.measure(np.array([0.6, 0.0, 0.8]), 1.0, np.random.default_rng(0))
>>> v.round(12).tolist(), sigma
([0.6, 0.0, 0.8], 0.0)
>>> css.measure(np.array([0.6, 0.0, 0.8]), 0.0, np.random.default_rng(0)) is None
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, FloatArray
from ...validation import check_positive, check_rotation, check_vectors

__all__ = ["CoarseSunSensor", "FineSunSensor", "StarTracker", "on_period"]


def on_period(t: float, period: float) -> bool:
    """Whether a sensor of ``period`` (s; 0 reads at every step) reads at ``t`` (s): ``t`` a multiple of it.

    Examples
    --------
    >>> from tumble.dynamics.models.vector_sensors import on_period
    >>> [on_period(t, 0.5) for t in (0.0, 0.1, 0.5, 1.0000000001)]
    [True, False, True, True]
    """
    if period == 0.0:
        return True
    k = t / period
    return abs(k - round(k)) < 1e-6


def _period(value: object) -> float:
    return check_positive("period", value, "s", allow_zero=True)


def _frame(value: object) -> Rotation:
    if isinstance(value, Rotation):
        if not value.single:
            raise ValueError("frame must be one rotation (sensor to body), not a stack")
        return value
    return Rotation.from_quat(check_rotation("frame", value))


@dataclass(frozen=True)
class CoarseSunSensor:
    """Cosine cells in opposed pairs (module docstring).

    Parameters
    ----------
    axes : array_like, shape (k, 3)
        The pairs' axes in the body frame (k >= 3, spanning space; each a cell facing ``+a``
        and one facing ``-a``); default the body axes, six cells on a cube's faces.
    noise : float
        Each cell's white noise, as a fraction of its full-Sun current (>= 0).
    period : float
        Seconds between readings (0: at every control step).

    Examples
    --------
    The stated noise covers the spread (2,000 readings, full Sun):

    >>> import numpy as np
    >>> from tumble.dynamics.models.vector_sensors import CoarseSunSensor
    >>> css, s, rng = CoarseSunSensor(noise=0.01), np.array([0.0, 0.6, 0.8]), np.random.default_rng(1)
    >>> readings = [css.measure(s, 1.0, rng) for _ in range(2000)]
    >>> angles = np.array([np.arccos(min(1.0, float(v @ s))) for v, _ in readings])
    >>> round(float(readings[0][1]), 3), round(float(np.sqrt(np.mean(angles**2) / 2)), 3)
    (0.014, 0.014)
    """

    axes: ArrayLike = field(default_factory=lambda: np.eye(3))
    noise: float = 0.0
    period: float = 0.0

    def __post_init__(self) -> None:
        A = check_vectors("axes", self.axes, "unit directions")
        if A.ndim != 2 or A.shape[0] < 3 or np.linalg.matrix_rank(A) < 3:
            raise ValueError(f"axes = {A.tolist()!r} must be at least 3 directions spanning space, shape (k, 3)")
        object.__setattr__(self, "axes", A / np.linalg.norm(A, axis=1, keepdims=True))
        check_positive("noise", self.noise, "fraction of a full-Sun current", allow_zero=True)
        _period(self.period)

    def currents(self, sun_body: FloatArray, light: float, rng: np.random.Generator) -> FloatArray:
        """The cells' readings, shape (k, 2) (facing ``+a``, ``-a``), in full-Sun currents.

        Examples
        --------
        The cosine law; the cells facing away read nothing; half the light, half the current:

        >>> import numpy as np
        >>> from tumble.dynamics.models.vector_sensors import CoarseSunSensor
        >>> CoarseSunSensor().currents(np.array([0.6, 0.0, -0.8]), 0.5, np.random.default_rng(0)).tolist()
        [[0.3, 0.0], [0.0, 0.0], [0.0, 0.4]]
        """
        c = np.asarray(self.axes) @ sun_body
        clean = light * np.stack([np.maximum(c, 0.0), np.maximum(-c, 0.0)], axis=1)
        return np.asarray(clean + self.noise * rng.standard_normal(clean.shape), float)

    def measure(self, sun_body: FloatArray, light: float, rng: np.random.Generator) -> tuple[FloatArray, float] | None:
        """The Sun's measured direction (body, unit) and its angular noise (rad), or None in the umbra.

        ``sun_body`` the true unit direction in the body, ``light`` the fraction of sunlight.

        Examples
        --------
        In the penumbra the currents are smaller, the direction the same and its noise larger:

        >>> import numpy as np
        >>> from tumble.dynamics.models.vector_sensors import CoarseSunSensor
        >>> css = CoarseSunSensor(noise=1e-3)
        >>> full, half = (css.measure(np.array([0.0, 0.0, 1.0]), f, np.random.default_rng(2)) for f in (1.0, 0.5))
        >>> bool(full[0] @ half[0] > 0.999), round(half[1] / full[1], 1)
        (True, 2.0)
        """
        if light <= 0.0:
            return None
        i = self.currents(sun_body, light, rng)
        A = np.asarray(self.axes)
        v, *_ = np.linalg.lstsq(A, i[:, 0] - i[:, 1], rcond=None)
        n = float(np.linalg.norm(v))
        if n == 0.0:
            return None
        u = v / n
        cov = 2.0 * self.noise**2 * np.linalg.inv(A.T @ A)
        across = np.eye(3) - np.outer(u, u)
        return u, math.sqrt(max(float(np.linalg.eigvalsh(across @ cov @ across)[-1]), 0.0)) / n


@dataclass(frozen=True)
class FineSunSensor:
    """A two-axis sun sensor head (module docstring).

    Parameters
    ----------
    frame : scipy Rotation or quaternion
        Sensor to body; the boresight is the sensor's z (default: the body's z).
    fov : float
        Half-angle of the field of view, rad (0 < fov < pi/2).
    noise : float
        White noise of each angle, rad (>= 0).
    period : float
        Seconds between readings (0: at every control step).

    Examples
    --------
    The Sun 10 deg off a boresight turned to the body's x; out of a 30 deg field of view, nothing:

    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.models.vector_sensors import FineSunSensor
    >>> fss = FineSunSensor(frame=Rotation.from_euler("y", 90, degrees=True), fov=np.radians(30))
    >>> s = np.array([np.cos(np.radians(10)), 0.0, np.sin(np.radians(10))])
    >>> v, sigma = fss.measure(s, 1.0, np.random.default_rng(0))
    >>> np.allclose(v, s), fss.measure(np.array([0.0, 1.0, 0.0]), 1.0, np.random.default_rng(0))
    (True, None)
    """

    frame: Rotation | ArrayLike = field(default_factory=Rotation.identity)
    fov: float = math.radians(60.0)
    noise: float = 0.0
    period: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "frame", _frame(self.frame))
        check_positive("fov", self.fov, "rad", at_most=math.pi / 2 - 1e-6)
        check_positive("noise", self.noise, "rad", allow_zero=True)
        _period(self.period)

    def measure(self, sun_body: FloatArray, light: float, rng: np.random.Generator) -> tuple[FloatArray, float] | None:
        """The Sun's measured direction (body, unit) and the angles' noise (rad); None in the umbra or out of view.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.vector_sensors import FineSunSensor
        >>> fss = FineSunSensor(noise=1e-3)
        >>> v, sigma = fss.measure(np.array([0.0, 0.0, 1.0]), 1.0, np.random.default_rng(0))
        >>> bool(np.arccos(v[2]) < 5e-3), sigma
        (True, 0.001)
        """
        C: Rotation = self.frame
        s = C.inv().apply(sun_body)
        if light <= 0.0 or s[2] <= math.cos(self.fov) * float(np.linalg.norm(s)):
            return None
        alpha = math.atan2(s[0], s[2]) + self.noise * rng.standard_normal()
        beta = math.atan2(s[1], s[2]) + self.noise * rng.standard_normal()
        d = np.array([math.tan(alpha), math.tan(beta), 1.0])
        return np.asarray(C.apply(d / np.linalg.norm(d)), float), float(self.noise)


@dataclass(frozen=True)
class StarTracker:
    """A star tracker with its own frame, rate and noise (module docstring).

    Parameters
    ----------
    frame : scipy Rotation or quaternion
        Sensor to body; the boresight is the sensor's z.
    cross : float
        Noise about each axis across the boresight, rad (>= 0).
    roll : float
        Noise about the boresight, rad (>= 0; typically 5-10 times ``cross``).
    period : float
        Seconds between readings (0: at every control step).

    Examples
    --------
    The stated covariance in the body frame, for a tracker looking along the body's x:

    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.models.vector_sensors import StarTracker
    >>> st = StarTracker(frame=Rotation.from_euler("y", 90, degrees=True), cross=1e-5, roll=1e-4)
    >>> np.round(np.sqrt(np.diag(st.covariance)), 9).tolist()
    [0.0001, 1e-05, 1e-05]
    >>> bool(st.measure(Rotation.identity(), np.random.default_rng(0)).magnitude() < 1e-3)
    True
    """

    frame: Rotation | ArrayLike = field(default_factory=Rotation.identity)
    cross: float = 0.0
    roll: float = 0.0
    period: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "frame", _frame(self.frame))
        check_positive("cross", self.cross, "rad", allow_zero=True)
        check_positive("roll", self.roll, "rad", allow_zero=True)
        _period(self.period)

    @property
    def covariance(self) -> FloatArray:
        """The measured attitude's error covariance about the body axes, rad^2 (3, 3).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.vector_sensors import StarTracker
        >>> np.diag(StarTracker(cross=1e-5, roll=1e-4).covariance).tolist()
        [1.0000000000000002e-10, 1.0000000000000002e-10, 1e-08]
        """
        C = self.frame.as_matrix()  # type: ignore[union-attr]
        return np.asarray(C @ np.diag([self.cross**2, self.cross**2, self.roll**2]) @ C.T, float)

    def measure(self, attitude: Rotation, rng: np.random.Generator) -> Rotation:
        """A reading of the true ``attitude`` (body to world): ``attitude * exp(C v)``.

        Examples
        --------
        A tracker without noise reads the truth:

        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.models.vector_sensors import StarTracker
        >>> truth = Rotation.from_rotvec([0.1, 0.2, 0.3])
        >>> float((StarTracker().measure(truth, np.random.default_rng(0)) * truth.inv()).magnitude())
        0.0
        """
        v = np.array([self.cross, self.cross, self.roll]) * rng.standard_normal(3)
        return attitude * Rotation.from_rotvec(self.frame.apply(v))  # type: ignore[union-attr]
