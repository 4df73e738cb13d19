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

from ..._html import field_repr
from ...typing import ArrayLike, FloatArray
from ...validation import check_noise, check_positive, check_rotation, check_vectors
from ..special.quaternion import turned_by

__all__ = ["MAX_ANGLE_NOISE", "CoarseSunSensor", "FineSunSensor", "StarTracker", "cell_currents", "coarse_reading",
           "fine_reading", "fine_view", "on_period", "on_periods", "tracker_noise"]


def on_periods(t: ArrayLike, period: float) -> np.ndarray:
    """Whether a sensor of ``period`` (s; 0 reads at every step) reads at each ``t`` (s): ``t`` a
    multiple of it (within 1e-6 of a period); an array of bool of ``t``'s shape.

    Examples
    --------
    >>> from tumble.dynamics.models.vector_sensors import on_periods
    >>> on_periods([0.0, 0.1, 0.5, 1.0000000001], 0.5).tolist()
    [True, False, True, True]
    """
    k = np.asarray(t, float)
    if period == 0.0:
        return np.ones(k.shape, bool)
    k = k / period
    return np.asarray(np.abs(k - np.round(k)) < 1e-6)


def on_period(t: float, period: float) -> bool:
    """:func:`on_periods` at one ``t`` (s).

    Examples
    --------
    >>> from tumble.dynamics.models.vector_sensors import on_period
    >>> [on_period(t, 0.5) for t in (0.0, 0.1, 0.5, 1.0000000001)]
    [True, False, True, True]
    """
    return bool(on_periods(t, period))


def cell_currents(A: FloatArray, light: float, s0: float, s1: float, s2: float, noise: float, z: FloatArray,
                  out: FloatArray) -> None:
    """The coarse cells' readings into ``out`` (k, 2): the cosine law (module docstring) of the pairs
    ``A`` (k, 3) for the Sun along ``(s0, s1, s2)`` (body, unit) at the light fraction ``light``,
    plus ``noise`` times the standard normals ``z`` (2 k of them, row by row). Plain loops: the
    Python sensor and the compiled loop (:mod:`~tumble.dynamics.control.estimated_loop`) call it.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.vector_sensors import cell_currents
    >>> out = np.empty((3, 2))
    >>> cell_currents(np.eye(3), 0.5, 0.6, 0.0, -0.8, 0.0, np.zeros(6), out)
    >>> out.tolist()
    [[0.3, 0.0], [0.0, 0.0], [0.0, 0.4]]
    """
    for j in range(A.shape[0]):
        c = A[j, 0] * s0 + A[j, 1] * s1 + A[j, 2] * s2
        out[j, 0] = light * max(c, 0.0) + noise * z[2 * j]
        out[j, 1] = light * max(-c, 0.0) + noise * z[2 * j + 1]


def coarse_reading(pinv: FloatArray, gram_inv: FloatArray, noise: float,
                   currents: FloatArray) -> tuple[float, float, float, float]:
    """The coarse sensor's direction (body, unit) and its angular noise (rad) from the cells'
    ``currents`` (k, 2) (:func:`cell_currents`): ``v = A^+ d`` of the pairs' differences ``d`` (``pinv``
    = ``A^+ = (A^T A)^-1 A^T``, ``gram_inv`` = ``(A^T A)^-1``) and the largest variance across
    ``u = v / |v|`` of ``2 noise^2 (A^T A)^-1``, over ``|v|`` (module docstring). The projection
    ``Q`` across ``u`` has ``u`` as a null vector, so its other two eigenvalues are the roots of
    ``x^2 - tr(Q) x + e2`` with ``e2 = (tr(Q)^2 - tr(Q^2)) / 2`` (the characteristic polynomial's
    coefficients; Horn & Johnson, *Matrix Analysis*, 2nd ed., sec. 1.2). A noise below zero
    (``-1``) when ``v`` is zero.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.vector_sensors import coarse_reading
    >>> from tumble.dynamics.models.vector_sensors import cell_currents
    >>> A, currents = np.eye(3), np.empty((3, 2))
    >>> cell_currents(A, 1.0, 0.6, 0.0, 0.8, 1e-3, np.zeros(6), currents)
    >>> u0, u1, u2, sigma = coarse_reading(A, A, 1e-3, currents)
    >>> round(float(u0), 12), round(float(u2), 12), round(float(sigma), 6)
    (0.6, 0.8, 0.001414)
    """
    v0, v1, v2 = 0.0, 0.0, 0.0
    for j in range(currents.shape[0]):
        d = currents[j, 0] - currents[j, 1]
        v0, v1, v2 = v0 + pinv[0, j] * d, v1 + pinv[1, j] * d, v2 + pinv[2, j] * d
    n = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
    if n == 0.0:
        return 0.0, 0.0, 0.0, -1.0
    u = (v0 / n, v1 / n, v2 / n)
    k2 = 2.0 * noise * noise
    cu = (k2 * (gram_inv[0, 0] * u[0] + gram_inv[0, 1] * u[1] + gram_inv[0, 2] * u[2]),
          k2 * (gram_inv[1, 0] * u[0] + gram_inv[1, 1] * u[1] + gram_inv[1, 2] * u[2]),
          k2 * (gram_inv[2, 0] * u[0] + gram_inv[2, 1] * u[1] + gram_inv[2, 2] * u[2]))
    a = u[0] * cu[0] + u[1] * cu[1] + u[2] * cu[2]
    tr, sq = 0.0, 0.0
    for r in range(3):
        for c in range(3):
            q = k2 * gram_inv[r, c] - u[r] * cu[c] - cu[r] * u[c] + a * u[r] * u[c]
            sq += q * q
            if r == c:
                tr += q
    e2 = 0.5 * (tr * tr - sq)
    top = 0.5 * tr + math.sqrt(max(0.25 * tr * tr - e2, 0.0))
    return u[0], u[1], u[2], math.sqrt(max(top, 0.0)) / n


def tracker_noise(C: FloatArray, cross: float, roll: float, z0: float, z1: float, z2: float) -> tuple[float, float, float]:
    """A star tracker's error as a rotation vector in the body frame, ``C v`` (rad): ``v = (cross z0,
    cross z1, roll z2)`` about the sensor's axes for unit normal draws ``z``, ``C`` (3, 3) sensor to
    body (module docstring). The reading is the true attitude turned by it
    (:func:`~tumble.dynamics.special.quaternion.turned_by`, ``q (x) exp(C v / 2)``). Plain floats:
    the Python sensor and the compiled loop call it.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.vector_sensors import tracker_noise
    >>> from tumble.dynamics.special.quaternion import turned_by
    >>> r = tracker_noise(np.eye(3), 0.0, 0.1, 0.0, 0.0, 1.0)   # 0.1 rad of roll, the sensor's z the body's
    >>> [round(float(v), 12) for v in turned_by(0.0, 0.0, 0.0, 1.0, *r)]
    [0.0, 0.0, 0.049979169271, 0.998750260395]
    """
    v0, v1, v2 = cross * z0, cross * z1, roll * z2
    return (C[0, 0] * v0 + C[0, 1] * v1 + C[0, 2] * v2, C[1, 0] * v0 + C[1, 1] * v1 + C[1, 2] * v2,
            C[2, 0] * v0 + C[2, 1] * v1 + C[2, 2] * v2)


def fine_view(C: FloatArray, cos_fov: float, s0: float, s1: float, s2: float,
              light: float) -> tuple[float, float, float, bool]:
    """The Sun's direction ``C^T s`` in a fine sun sensor's frame (``C`` (3, 3) sensor to body, ``s``
    the body-frame direction) and whether the sensor sees it: lit (``light > 0``) and inside the
    field of view, ``a_z > cos(fov) |a|``. Plain floats: the Python sensor and the compiled loop call
    it (:class:`FineSunSensor`).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.vector_sensors import fine_view
    >>> a0, a1, a2, seen = fine_view(np.eye(3), np.cos(np.radians(60)), 0.0, 0.0, 1.0, 1.0)
    >>> [float(a0), float(a1), float(a2)], bool(seen)
    ([0.0, 0.0, 1.0], True)
    >>> bool(fine_view(np.eye(3), np.cos(np.radians(60)), 1.0, 0.0, 0.0, 1.0)[3])   # 90 deg off the boresight
    False
    """
    a0 = C[0, 0] * s0 + C[1, 0] * s1 + C[2, 0] * s2
    a1 = C[0, 1] * s0 + C[1, 1] * s1 + C[2, 1] * s2
    a2 = C[0, 2] * s0 + C[1, 2] * s1 + C[2, 2] * s2
    return a0, a1, a2, light > 0.0 and a2 > cos_fov * math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)


def fine_reading(C: FloatArray, noise: float, a0: float, a1: float, a2: float, z0: float,
                 z1: float) -> tuple[float, float, float]:
    """A fine sun sensor's measured direction (body frame, unit) of the Sun at ``a`` in its frame
    (:func:`fine_view`): the two angles ``atan2(a_x, a_z)`` and ``atan2(a_y, a_z)`` each read with
    white noise ``noise z`` (rad; ``z`` unit normal draws), the unit vector ``(tan alpha, tan beta,
    1)`` they give turned back by ``C`` (module docstring). Plain floats, as :func:`fine_view`.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.vector_sensors import fine_reading
    >>> [round(float(v), 12) for v in fine_reading(np.eye(3), 0.0, 0.6, 0.0, 0.8, 0.0, 0.0)]   # no noise: the direction
    [0.6, 0.0, 0.8]
    """
    d0 = math.tan(math.atan2(a0, a2) + noise * z0)
    d1 = math.tan(math.atan2(a1, a2) + noise * z1)
    n = math.sqrt(d0 * d0 + d1 * d1 + 1.0)
    e0, e1, e2 = d0 / n, d1 / n, 1.0 / n
    return (C[0, 0] * e0 + C[0, 1] * e1 + C[0, 2] * e2, C[1, 0] * e0 + C[1, 1] * e1 + C[1, 2] * e2,
            C[2, 0] * e0 + C[2, 1] * e1 + C[2, 2] * e2)


def _period(value: object) -> float:
    return check_positive("period", value, "s", allow_zero=True)


#: The largest angle noise a direction or attitude sensor is taken with, rad (5.7 deg): a fine sun
#: sensor spreads 0.001-0.01 rad, a star tracker 5e-6-5e-4; past it the noise is most likely in
#: arcsec or deg written as rad (a walkthrough's 10 "rad" for 10 arcsec ran, the knowledge lost).
MAX_ANGLE_NOISE = 0.1


_ANGLE_HINT = "is it in arcsec or deg? Give radians (10 arcsec = 4.8e-5 rad, 1 deg = 0.01745 rad)"


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

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    axes: ArrayLike = field(default_factory=lambda: np.eye(3))
    noise: float = 0.0
    period: float = 0.0

    def __post_init__(self) -> None:
        A = check_vectors("axes", self.axes, "unit directions")
        if A.ndim != 2 or A.shape[0] < 3 or np.linalg.matrix_rank(A) < 3:
            raise ValueError(f"axes = {A.tolist()!r} must be at least 3 directions spanning space, shape (k, 3)")
        object.__setattr__(self, "axes", A / np.linalg.norm(A, axis=1, keepdims=True))
        if check_positive("noise", self.noise, "fraction of a full-Sun current", allow_zero=True) > 1.0:
            raise ValueError(f"noise = {self.noise!r} is more than a cell's full-Sun current; allowed: 0 to 1 (a "
                             "fraction of it: 0.01 is 1 %)")
        _period(self.period)

    def tables(self) -> tuple[FloatArray, FloatArray]:
        """The least squares' ``A^+ = (A^T A)^-1 A^T`` (3, k) and ``(A^T A)^-1`` (3, 3) of the axes ``A``.

        Examples
        --------
        >>> from tumble.dynamics.models.vector_sensors import CoarseSunSensor
        >>> [t.shape for t in CoarseSunSensor().tables()]
        [(3, 3), (3, 3)]
        """
        A = np.asarray(self.axes, float)
        gram_inv = np.linalg.inv(A.T @ A)
        return np.ascontiguousarray(gram_inv @ A.T), np.ascontiguousarray(gram_inv)

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
        A = np.asarray(self.axes, float)
        out = np.empty((A.shape[0], 2))
        s0, s1, s2 = (float(v) for v in sun_body)
        cell_currents(A, light, s0, s1, s2, self.noise, rng.standard_normal(2 * A.shape[0]), out)
        return out

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
        A = np.asarray(self.axes, float)
        pinv, gram_inv = self.tables()
        currents = self.currents(sun_body, light, rng)
        u0, u1, u2, sigma = coarse_reading(pinv, gram_inv, self.noise, currents)
        if sigma < 0.0:
            return None
        return np.array([u0, u1, u2], float), float(sigma)


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

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    frame: Rotation | ArrayLike = field(default_factory=Rotation.identity)
    fov: float = math.radians(60.0)
    noise: float = 0.0
    period: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "frame", _frame(self.frame))
        check_positive("fov", self.fov, "rad", at_most=math.pi / 2 - 1e-6)
        check_noise("noise", self.noise, "rad", MAX_ANGLE_NOISE, "a fine sun sensor", _ANGLE_HINT)
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
        C = self.frame.as_matrix()  # type: ignore[union-attr]
        s0, s1, s2 = (float(v) for v in sun_body)
        a0, a1, a2, seen = fine_view(C, math.cos(self.fov), s0, s1, s2, float(light))
        if not seen:
            return None
        z0 = float(rng.standard_normal())
        z1 = float(rng.standard_normal())
        return np.array(fine_reading(C, self.noise, a0, a1, a2, z0, z1), float), float(self.noise)


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

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    frame: Rotation | ArrayLike = field(default_factory=Rotation.identity)
    cross: float = 0.0
    roll: float = 0.0
    period: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "frame", _frame(self.frame))
        check_noise("cross", self.cross, "rad", MAX_ANGLE_NOISE, "a star tracker", _ANGLE_HINT)
        check_noise("roll", self.roll, "rad", MAX_ANGLE_NOISE, "a star tracker", _ANGLE_HINT)
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
        z0, z1, z2 = (float(v) for v in rng.standard_normal(3))
        x, y, z, s = (float(v) for v in attitude.as_quat())
        C = self.frame.as_matrix()  # type: ignore[union-attr]
        return Rotation.from_quat(turned_by(x, y, z, s, *tracker_noise(C, self.cross, self.roll, z0, z1, z2)))
