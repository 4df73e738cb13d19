"""Free fall seen by an accelerometer: what it reads, and where the sensor sits.

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
widening the offset's uncertainty, :func:`fit_offset`). From the samples of a
flight ``r`` and ``c`` follow by linear least squares (:func:`fit_offset`; ``omega`` the
gyroscope's, ``omega'`` its derivative, :func:`rate_derivative`), and the residual
``|f - A r - c|`` of each sample (:func:`free_fall_residual`) is about the accelerometer's
noise in free flight and large under any contact: a hand at rest reads ``|f| ~ g``, a throw
several g, a catch or a landing a spike of tens of m/s^2.
:mod:`~tumble.analysis.fit.freespan` cuts a candidate flight where that residual leaves the
free fall.
"""

from __future__ import annotations

import numpy as np

from ...typing import ArrayLike
from .uncertainty import SCALE_UNCERTAINTY, effective_covariance

__all__ = ["ACCEL_SCALE_UNCERTAINTY", "MAX_ACCEL", "check_accel", "fit_offset", "free_fall_residual", "offset_matrix",
           "rate_derivative", "rigid_acceleration"]

#: Standard uncertainty of a MEMS accelerometer's scale factor per axis (sensitivity tolerance,
#: dimensionless; Bosch BMI160/BMI270, ST LSM6DSO datasheets give about +-1 % as limits), as the
#: gyroscope's :data:`~tumble.analysis.fit.uncertainty.SCALE_UNCERTAINTY`.
ACCEL_SCALE_UNCERTAINTY = 0.005


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


def free_fall_residual(f: ArrayLike, omega: ArrayLike, omega_dot: ArrayLike, r: ArrayLike, c: ArrayLike,
                       inside: ArrayLike | None = None) -> np.ndarray:
    """``|f - A r - c|`` per sample, m/s^2: the contact force per unit mass (module docstring).

    ``inside`` (shape of ``f``, bool) marks the readings inside the accelerometer's range
    (:func:`~tumble.analysis.fit.single.saturation_mask`). A reading at the rail says only that
    the true one lies beyond it (a censored value; Tobin, *Econometrica* 26, 1958, 24): its
    residual is how far the prediction falls short of the rail, and none where the prediction
    lies beyond it too (a phone strapped 0.2 m out on a racquet spun at 25 rad/s reads past
    16 g in free flight).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.freefall import free_fall_residual
    >>> w = np.zeros((2, 3))
    >>> free_fall_residual([[0.0, 0.0, 9.81], [0.0, 0.0, 0.0]], w, w, np.zeros(3), np.zeros(3)).tolist()   # held; falling
    [9.81, 0.0]
    >>> spin = np.array([[0.0, 0.0, 30.0]])   # rad/s: 180 m/s^2 inward at 0.2 m, read at the 16 g rail
    >>> rail = [[-156.9, 0.0, 0.0]]
    >>> free_fall_residual(rail, spin, 0 * spin, [0.2, 0.0, 0.0], np.zeros(3)).round(1).tolist()
    [23.1]
    >>> free_fall_residual(rail, spin, 0 * spin, [0.2, 0.0, 0.0], np.zeros(3), inside=[[False, True, True]]).tolist()
    [0.0]
    """
    f = np.asarray(f, float)
    d = f - rigid_acceleration(omega, omega_dot, r) - np.asarray(c, float)
    if inside is not None:
        beyond = np.sign(f) * (f - d) >= np.abs(f)  # the prediction lies at or beyond the reading at the rail
        d = np.where(~np.asarray(inside, bool) & beyond, 0.0, d)
    return np.linalg.norm(d, axis=-1)
