"""Free fall seen by an accelerometer: where a flight begins and ends, and where the sensor sits.

A raw accelerometer reads the specific force ``f = a - g`` at the sensor, in its own axes
(Titterton & Weston, *Strapdown Inertial Navigation Technology*, 2nd ed., 2004, sec. 3.2;
``g`` the gravitational acceleration). At a point ``r`` fixed in a rigid body (from its centre
of mass, body axes) the acceleration is ``a = a_cm + omega' x r + omega x (omega x r)``
(Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed., 2002, eq. 4.104, in the body's
frame), and in free flight the centre of mass falls, ``a_cm = g + F_drag / m``, so

    ``f = omega' x r + omega x (omega x r) + F_drag / m``,

which is linear in ``r``: ``f = A(omega, omega') r + c`` with ``A = [omega']_x + [omega]_x^2``
(:func:`offset_matrix`) and ``c`` the accelerometer's bias plus the air's force, taken constant
over a flight. The air's force is not: ``rho C_D A v^2 / 2m``, 0.3-2.4 m/s^2 on a tossed phone
at its release and none at the top, across its face, so it turns with the body (Hoerner,
*Fluid-Dynamic Drag*, 1965, ch. 3); the fit keeps its mean, the residuals the rest (smooth,
widening the offset's uncertainty, :func:`fit_offset`), and the threshold that cuts a flight
allows for it (:func:`air_allowance`). From the samples of a
flight ``r`` and ``c`` follow by linear least squares (:func:`fit_offset`; ``omega`` the
gyroscope's, ``omega'`` its derivative, :func:`rate_derivative`), and the residual
``|f - A r - c|`` of each sample (:func:`free_fall_residual`) is about the accelerometer's
noise in free flight and large under any contact: a hand at rest reads ``|f| ~ g``, a throw
several g, a catch or a landing a spike of tens of m/s^2. :func:`free_span` cuts a candidate
flight where that residual leaves the free fall: the release and the catch or impact, sharply,
and it refuses a stretch that is not free (the phone swung about in the hand).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..._html import headline_html, headline_repr
from ...dynamics.environment.earth import STANDARD_GRAVITY
from ...typing import ArrayLike
from .uncertainty import SCALE_UNCERTAINTY, effective_covariance

__all__ = ["ACCEL_SCALE_UNCERTAINTY", "FREE_FACTOR", "FREE_FLOOR", "MAX_ACCEL", "MAX_CONTACT", "MAX_DRAG", "MAX_FALL",
           "MAX_OFFSET", "FreeSpan", "air_allowance", "check_accel", "fit_offset", "free_fall_residual",
           "free_span", "offset_matrix", "rate_derivative", "rigid_acceleration"]

#: The residual that ends a flight: this many times its median in the flight's middle ...
FREE_FACTOR = 5.0
#: ... plus this floor, m/s^2 (the derivative's error at high spin, the air's varying force).
FREE_FLOOR = 1.0
#: The largest drag per unit mass and squared speed of a body tossed by hand, ``rho C_D A / 2m``,
#: 1/m: a phone broadside 0.045, a paperback 0.05-0.1, a racquet's head about 0.1 (Hoerner,
#: *Fluid-Dynamic Drag*, 1965, ch. 3: a flat plate's ``C_D`` 1.17; a tennis ball's 0.02).
MAX_DRAG = 0.1
#: The time from the top of a toss, s, past which the air's allowance stops growing: half the
#: longest hand toss (1.5 s, 7.4 m/s at the release and the catch; a hand's hold reads ``g``
#: against the allowance's 5.4 m/s^2 there).
MAX_FALL = 0.75
#: The median residual, m/s^2, above which a candidate's middle is not in free fall (a hand's
#: grip reads ~g; the free fall's residual is the noise and the derivative's error, ~0.1-0.5).
MAX_CONTACT = 2.0
#: Standard uncertainty of a MEMS accelerometer's scale factor per axis (sensitivity tolerance,
#: dimensionless; Bosch BMI160/BMI270, ST LSM6DSO datasheets give about +-1 % as limits), as the
#: gyroscope's :data:`~tumble.analysis.fit.uncertainty.SCALE_UNCERTAINTY`.
ACCEL_SCALE_UNCERTAINTY = 0.005
#: The largest sensor offset from the centre of mass taken for a body tossed by hand, m (a
#: phone on a racquet's handle sits some 0.3 m from its centre of mass).
MAX_OFFSET = 0.5


def check_accel(accel: ArrayLike, shape: tuple) -> np.ndarray:
    """The specific force as an array of ``shape`` (the gyroscope's samples), finite and within
    :data:`MAX_ACCEL`; else a ``ValueError`` naming ``accel``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.freefall import check_accel
    >>> check_accel([[0.0, 0.0, 9.8]], (1, 3)).tolist()
    [[0.0, 0.0, 9.8]]
    >>> check_accel(np.zeros((2, 3)), (3, 3))
    Traceback (most recent call last):
    ...
    ValueError: accel: expected 3 finite rows of 3 (the specific force at the gyroscope's times, m/s^2); got shape (2, 3)
    >>> check_accel([[0.0, 0.0, 9.8], [0.0, float("nan"), 9.8]], (2, 3))
    Traceback (most recent call last):
    ...
    ValueError: accel[1] = [0.0, nan, 9.8] is not finite (the specific force at the gyroscope's times, m/s^2)
    >>> check_accel([[0.0, 0.0, 9.8], [1e300, 0.0, 9.8]], (2, 3))
    Traceback (most recent call last):
    ...
    ValueError: accel[1] = [1e+300, 0.0, 9.8] is beyond an accelerometer's reading (at most 1e+04 m/s^2 per axis; a phone's range is 8-16 g)
    """
    f = np.asarray(accel, float)
    if f.shape != tuple(shape):
        raise ValueError(f"accel: expected {shape[0]} finite rows of 3 (the specific force at the gyroscope's "
                         f"times, m/s^2); got shape {f.shape}")
    bad = np.flatnonzero(~np.all(np.isfinite(f), axis=1))
    if bad.size:  # named as the gyroscope's samples are (tumble.analysis.fit.single._check)
        raise ValueError(f"accel[{bad[0]}] = {f[bad[0]].tolist()} is not finite (the specific force at the "
                         "gyroscope's times, m/s^2)")
    bad = np.flatnonzero(np.any(np.abs(f) > MAX_ACCEL, axis=1))
    if bad.size:  # a value in other units or a corrupt cell: refused as phyphox's Accelerometer.csv's reader does
        raise ValueError(f"accel[{bad[0]}] = {f[bad[0]].tolist()} is beyond an accelerometer's reading (at most "
                         f"{MAX_ACCEL:.0e} m/s^2 per axis; a phone's range is 8-16 g)")
    return f


#: Beyond any accelerometer's reading, m/s^2 per axis (a phone's range is 8-16 g, 78-157 m/s^2):
#: a value in other units or a corrupt cell.
MAX_ACCEL = 1e4


def _cross_matrix(v: np.ndarray) -> np.ndarray:
    """``[v]_x`` with ``[v]_x r = v x r``, for rows ``v`` (n, 3) -> (n, 3, 3)."""
    z = np.zeros(v.shape[:-1])
    x, y, w = v[..., 0], v[..., 1], v[..., 2]
    return np.stack([np.stack([z, -w, y], -1), np.stack([w, z, -x], -1), np.stack([-y, x, z], -1)], -2)


def offset_matrix(omega: ArrayLike, omega_dot: ArrayLike) -> np.ndarray:
    """``A = [omega']_x + [omega]_x [omega]_x``: ``A r = omega' x r + omega x (omega x r)``,
    the acceleration of a point ``r`` of a rigid body relative to its centre of mass (module
    docstring; Goldstein, Poole & Safko 2002, eq. 4.104).

    Parameters
    ----------
    omega, omega_dot : array_like, shape (..., 3)
        Angular velocity (rad/s) and its time derivative (rad/s^2), body axes.

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.freefall import offset_matrix
    >>> A = offset_matrix([0.0, 0.0, 10.0], [0.0, 0.0, 0.0])   # spinning at 10 rad/s about z
    >>> (A @ [0.05, 0.0, 0.0]).round(6).tolist()   # centripetal: -omega^2 r, 5 m/s^2 inward
    [-5.0, 0.0, 0.0]
    """
    w = _cross_matrix(np.asarray(omega, float))
    return _cross_matrix(np.asarray(omega_dot, float)) + w @ w


def rigid_acceleration(omega: ArrayLike, omega_dot: ArrayLike, r: ArrayLike) -> np.ndarray:
    """``omega' x r + omega x (omega x r)``, m/s^2: what an accelerometer at ``r`` (m, from the
    centre of mass, body axes) reads in free flight without air (module docstring).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.freefall import rigid_acceleration
    >>> w, wd, r = np.array([1.0, 2.0, 3.0]), np.array([-4.0, 0.5, 2.0]), np.array([0.03, -0.02, 0.08])
    >>> expected = np.cross(wd, r) + np.cross(w, np.cross(w, r))
    >>> bool(np.allclose(rigid_acceleration(w, wd, r), expected))
    True
    """
    return np.einsum("...ij,...j->...i", offset_matrix(omega, omega_dot), np.asarray(r, float))


def rate_derivative(t: ArrayLike, omega: ArrayLike) -> np.ndarray:
    """``omega'`` at the samples, rad/s^2: the second-order central difference on the real,
    irregular sample times.

    ``numpy.gradient`` (Fornberg, *Math. Comp.* 51, 1988), whose error
    ``omega''' dt^2 / 6`` stays below the noise of a wider smoothing window's bias at the spin
    rates of tosses.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.freefall import rate_derivative
    >>> t = np.cumsum(np.r_[0.0, np.random.default_rng(0).uniform(0.009, 0.011, 99)])
    >>> w = np.stack([np.sin(3 * t), t ** 2, np.zeros_like(t)], axis=1)
    >>> d = rate_derivative(t, w)
    >>> bool(np.allclose(d[1:-1, 0], 3 * np.cos(3 * t[1:-1]), atol=1e-3)), bool(np.allclose(d[1:-1, 1], 2 * t[1:-1]))
    (True, True)
    """
    return np.gradient(np.asarray(omega, float), np.asarray(t, float), axis=0)


def _one_sided(t: np.ndarray, w: np.ndarray, side: int) -> np.ndarray:
    """``omega'`` from the quadratic through a sample and the two before it (``side = -1``) or
    after it (``+1``), rad/s^2 (Fornberg 1988); the record's ends take the central difference."""
    out = rate_derivative(t, w)
    if len(t) < 3:
        return out
    k = np.arange(2, len(t)) if side < 0 else np.arange(0, len(t) - 2)
    i1, i2 = k + side, k + 2 * side
    h1, h2 = t[i1] - t[k], t[i2] - t[i1]
    c0 = -(2 * h1 + h2) / (h1 * (h1 + h2))
    c1 = (h1 + h2) / (h1 * h2)
    c2 = -h1 / (h2 * (h1 + h2))
    out[k] = c0[:, None] * w[k] + c1[:, None] * w[i1] + c2[:, None] * w[i2]
    return out


def air_allowance(tau: ArrayLike) -> np.ndarray:
    """The air's largest force per unit mass on a body ``tau`` seconds from the top of its toss,
    m/s^2: ``MAX_DRAG (g tau)^2`` (the speed ``g tau`` it has gained falling, or has still to lose
    rising), ``tau`` clipped at :data:`MAX_FALL`. The free fall's residual grows so towards a
    flight's ends, as the air's force turns with the body (the fit's constant ``c`` holds only its
    mean), and a threshold fixed at the middle's level would cut a fast flight early.

    Examples
    --------
    >>> from tumble.analysis.fit.freefall import air_allowance
    >>> air_allowance([0.0, 0.5, 2.0]).round(2).tolist()   # m/s^2: at the top, 0.5 s from it, and capped
    [0.0, 2.4, 5.41]
    """
    return MAX_DRAG * (STANDARD_GRAVITY * np.minimum(np.abs(np.asarray(tau, float)), MAX_FALL)) ** 2


def _design(omega: ArrayLike, omega_dot: ArrayLike) -> np.ndarray:
    """The least-squares matrix of ``f = A r + c``: rows ``[A | I]``, (3 n, 6)."""
    A = offset_matrix(omega, omega_dot)
    return np.concatenate([A, np.broadcast_to(np.eye(3), A.shape)], axis=2).reshape(-1, 6)


def fit_offset(f: ArrayLike, omega: ArrayLike, omega_dot: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The sensor's offset ``r`` from the centre of mass and the constant ``c`` (bias plus air)
    that best give the specific force ``f = A r + c`` of free flight (module docstring), by
    linear least squares over the samples.

    Parameters
    ----------
    f : array_like, shape (n, 3)
        Specific force, sensor axes, m/s^2.
    omega, omega_dot : array_like, shape (n, 3)
        Angular velocity (rad/s) and its derivative (rad/s^2), sensor axes.

    Returns
    -------
    r : ndarray, shape (3,)
        Offset, sensor axes, m.
    c : ndarray, shape (3,)
        Constant specific force, m/s^2.
    r_std : ndarray, shape (3,)
        Standard uncertainty of ``r``, m: the least-squares covariance widened by the residuals'
        autocorrelation time (:func:`~tumble.analysis.fit.uncertainty.effective_covariance`),
        plus the accelerometer's and the gyroscope's scale factors
        (:data:`ACCEL_SCALE_UNCERTAINTY`, :data:`~tumble.analysis.fit.uncertainty.SCALE_UNCERTAINTY`)
        propagated to first order (GUM 5.1.2). Checked by coverage over seeded synthetic flights
        (tests/test_fit_accel.py).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.freefall import fit_offset, rigid_acceleration
    >>> rng = np.random.default_rng(1)
    >>> w, wd = rng.normal(0, 10, (200, 3)), rng.normal(0, 50, (200, 3))
    >>> r_true = np.array([0.04, -0.02, 0.07])
    >>> f = rigid_acceleration(w, wd, r_true) + [0.1, 0.0, -0.2] + rng.normal(0, 0.02, (200, 3))
    >>> r, c, r_std = fit_offset(f, w, wd)
    >>> bool(np.all(np.abs(r - r_true) < 4 * r_std)), c.round(2).tolist()
    (True, [0.1, 0.0, -0.2])
    """
    f = np.asarray(f, float)
    M = _design(omega, omega_dot)
    x, *_ = np.linalg.lstsq(M, f.reshape(-1), rcond=None)
    res = M @ x - f.reshape(-1)
    # statistical: the residuals are smooth (the derivative's error, the air), so their
    # autocorrelation time widens the textbook covariance (tumble.analysis.fit.uncertainty)
    cov, _ = effective_covariance(M, res, res.reshape(-1, 3), [0, len(f)])
    # systematic: each axis's scale factor, accelerometer and gyroscope, propagated to first order
    # (GUM, JCGM 100:2008, 5.1.2): x moves by dx/dk per unit scale error k
    omega, omega_dot = np.asarray(omega, float), np.asarray(omega_dot, float)
    pinv = np.linalg.pinv(M)
    sens = []
    for k in range(3):
        scaled = np.zeros_like(f)
        scaled[:, k] = f[:, k]
        sens.append(ACCEL_SCALE_UNCERTAINTY * (pinv @ scaled.reshape(-1)))
        e = np.ones(3)
        e[k] += 1e-6
        sens.append(SCALE_UNCERTAINTY * (np.linalg.pinv(_design(omega * e, omega_dot * e)) @ f.reshape(-1) - x) / 1e-6)
    cov = cov + sum(np.outer(d, d) for d in sens)
    return x[:3], x[3:], np.sqrt(np.diag(cov)[:3])


def free_fall_residual(f: ArrayLike, omega: ArrayLike, omega_dot: ArrayLike, r: ArrayLike, c: ArrayLike) -> np.ndarray:
    """``|f - A r - c|`` per sample, m/s^2: the contact force per unit mass (module docstring).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.freefall import free_fall_residual
    >>> w = np.zeros((2, 3))
    >>> free_fall_residual([[0.0, 0.0, 9.81], [0.0, 0.0, 0.0]], w, w, np.zeros(3), np.zeros(3)).tolist()   # held; falling
    [9.81, 0.0]
    """
    return np.linalg.norm(np.asarray(f, float) - rigid_acceleration(omega, omega_dot, r) - np.asarray(c, float), axis=-1)


@dataclass(frozen=True)
class FreeSpan:
    """Where a candidate flight falls free, by its accelerometer (:func:`free_span`).

    Attributes
    ----------
    first, stop : int
        The free samples: ``[first, stop)``.
    free : bool
        Whether the candidate's middle is in free fall.
    reason : str
        Why not ("" when free).
    offset, offset_std : ndarray, shape (3,)
        The sensor's position from the centre of mass, sensor axes, m, and its standard uncertainty.
    contact : float
        Median residual ``|f - A r - c|`` in the middle, m/s^2.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.freefall import FreeSpan
    >>> span = FreeSpan(10, 90, True, "", np.array([0.03, 0.0, 0.05]), np.full(3, 0.001), 0.2)
    >>> span.summary()["sensor_offset"], span.stop - span.first
    ([0.03, 0.0, 0.05], 80)
    """

    HEADLINE = (("free", "free", ""), ("first", "first sample", ""), ("stop", "stop", ""), ("offset", "sensor offset", "m"),
                ("contact", "contact residual", "m/s^2"), ("reason", "reason", ""))
    __repr__ = headline_repr
    _repr_html_ = headline_html

    first: int
    stop: int
    free: bool
    reason: str
    offset: np.ndarray
    offset_std: np.ndarray
    contact: float

    def summary(self) -> dict:
        """JSON-ready: ``sensor_offset`` and ``sensor_offset_std`` (m, sensor axes).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.freefall import FreeSpan
        >>> sorted(FreeSpan(0, 50, True, "", np.zeros(3), np.zeros(3), 0.1).summary())
        ['sensor_offset', 'sensor_offset_std']
        """
        return {"sensor_offset": [float(v) for v in self.offset], "sensor_offset_std": [float(v) for v in self.offset_std]}


#: Middles tried, as fractions of a candidate (as the gyroscope's search tries its seeds).
MIDDLES = ((0.35, 0.8), (0.1, 0.5), (0.5, 0.9))


def free_span(t: ArrayLike, f: ArrayLike, omega: ArrayLike, a: int, b: int) -> FreeSpan:
    """The free-falling part of the candidate ``[a, b)`` (module docstring).

    ``r`` and ``c`` are fitted on the candidate's middle (35-80 %; then its first and second
    half, :data:`MIDDLES`), refitted twice without the samples beyond the threshold; the flight then reaches, from the middle outwards, up to the first
    two samples in a row (from the centre of its free samples) whose residual exceeds :data:`FREE_FACTOR` times the middle's median
    plus :data:`FREE_FLOOR` and the air's allowance at its distance from the middle (:func:`air_allowance`; the least of the residuals with ``omega'`` a central and a one-sided
    difference: at the edge of a contact the central difference reaches across it). A middle whose median residual exceeds :data:`MAX_CONTACT` (or
    whose fitted offset exceeds :data:`MAX_OFFSET`) is not in free fall.

    Parameters
    ----------
    t : array_like, shape (n,)
        Times, s.
    f : array_like, shape (n, 3)
        Specific force, sensor axes, m/s^2.
    omega : array_like, shape (n, 3)
        Gyroscope samples, sensor axes, rad/s.
    a, b : int
        The candidate: samples ``[a, b)``.

    Returns
    -------
    FreeSpan

    Examples
    --------
    A phone falling free for 0.6 s between a hand at rest (reading ``g``) and a catch:

    >>> import numpy as np
    >>> from tumble.analysis.fit.freefall import free_span, rigid_acceleration
    >>> t = np.arange(0.0, 1.0, 0.01)
    >>> w = np.stack([5 * np.cos(4 * t), 12 + 0 * t, 5 * np.sin(4 * t)], axis=1)
    >>> f = rigid_acceleration(w, np.gradient(w, t, axis=0), [0.05, 0.0, 0.02])
    >>> f[:20] += [0.0, 0.0, 9.81]
    >>> f[80:] += [0.0, 30.0, 9.81]
    >>> span = free_span(t, f, w, 0, 100)
    >>> span.free, span.first, span.stop, span.offset.round(3).tolist()
    (True, 20, 80, [0.05, 0.0, 0.02])
    """
    t, f, omega = np.asarray(t, float), np.asarray(f, float), np.asarray(omega, float)
    wd = rate_derivative(t[a:b], omega[a:b])
    sided = [_one_sided(t[a:b], omega[a:b], side) for side in (-1, 1)]
    w, ff = omega[a:b], f[a:b]
    n = b - a
    best = None
    for lo, hi in MIDDLES:
        i, j = int(lo * n), max(int(hi * n), int(lo * n) + 6)
        use = np.arange(i, j)
        for _ in range(3):  # robust: refitted without the samples under contact (a catch's start in the middle)
            r, c, r_std = fit_offset(ff[use], w[use], wd[use])
            e = free_fall_residual(ff, w, wd, r, c)
            level = float(np.median(e[i:j]))
            use = i + np.flatnonzero(e[i:j] <= FREE_FACTOR * level + FREE_FLOOR)
            if len(use) < 6:
                break
        if best is None or level < best[0]:
            best = (level, i, j, r, c, r_std, e)
        if level <= MAX_CONTACT and np.linalg.norm(r) <= MAX_OFFSET:
            break
    level, i, j, r, c, r_std, e = best
    # at a contact's edge the central difference reaches across it: the one-sided ones do not
    e = np.minimum(e, np.minimum(*(free_fall_residual(ff, w, d, r, c) for d in sided)))
    if level > MAX_CONTACT or np.linalg.norm(r) > MAX_OFFSET:
        what = f"{level:.2g} m/s^2 of contact force" if level > MAX_CONTACT else \
            f"a sensor {np.linalg.norm(r):.2g} m from the centre of mass (at most {MAX_OFFSET} m)"
        return FreeSpan(a, b, False, f"not free: the accelerometer reads {what} where the gyroscope saw a "
                        f"candidate flight (the phone held or moved by the hand)", r, r_std, level)
    first, stop = _free_limits(t[a:b], e, level, i, j)
    return FreeSpan(a + first, a + stop, True, "", r, r_std, level)


def _free_limits(t: np.ndarray, e: np.ndarray, level: float, i: int, j: int) -> tuple[int, int]:
    """The free samples ``[first, stop)`` about the middle ``[i, j)`` (:func:`free_span`): up to the
    first two samples in a row whose residual ``e`` exceeds the threshold, which grows away from
    the middle by the air's largest force at the speed the fall has gained since
    (:func:`air_allowance`)."""
    bad = e > FREE_FACTOR * level + FREE_FLOOR + air_allowance(t - 0.5 * (t[i] + t[j - 1]))
    pairs = bad[:-1] & bad[1:]
    core = i + int(np.median(np.flatnonzero(~bad[i:j])))  # the middle's free samples' centre
    before = np.flatnonzero(pairs[:core])
    after = np.flatnonzero(pairs[core:])
    first = int(before[-1]) + 2 if before.size else 0
    stop = core + int(after[0]) if after.size else len(e)
    return first, stop
