"""The fit's model of one throw: the gyrostat with a measured rotor, seen by a biased gyroscope.

**Physical tensors.** The flown body's tensor about its centre of mass is written
``I = tr(S) E - S`` with ``S = C C^T`` its second moment of mass (``S = integral rho r r^T dV``;
Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed., sec. 5.3) and ``C`` lower triangular
(6 numbers). A tensor is that of some positive mass distribution exactly when ``S`` is positive
semi-definite (Wensing, Kim & Slotine, "Linear matrix inequalities for physically consistent
inertial parameter identification", IEEE RA-L 3 (2018) 60), which gives the triangle
inequalities of the moments: every ``C`` gives a physical tensor, and the fit needs no bounds.

**Dynamics.** ``L' = L x w - b_i |w_i| w_i``, ``w = I^-1 (L - h(t))``, ``h = J_r Omega_r(t) a``
(the gyrostat in the momentum form: :mod:`tumble.dynamics.models.gyrostat`), from ``L(t_0)``.
The gyroscope reads ``w + bias``. Parameters: ``C`` (6), ``L(t_0)`` (3), the bias (3) and the
per-axis quadratic drag ``b`` (3).

**Why not the published estimator.** Blaha et al. (arXiv:2503.13137) solve Euler's equations as a
linear regression in the tensor on the measured rates, their derivatives and the rotor speed's
derivative, all low-passed and differentiated with one mean sampling interval per log: the
derivatives amplify the noise by ``1 / dt`` (4 kHz: a factor ~1000), the low-pass filter that
tames it also delays and flattens the spin-up the scale comes from, and the noise in the
regressors biases the regression's slope toward zero (errors in variables: an
underestimated smallest moment). Integrating the equations (an output-error fit) needs no
derivative of the rates or the rotor speed, uses each real sample time, and leaves the noise
where least squares expects it, in the data.

**Rotor speed.** Used through ``h`` only (never ``h'`` in the fit); its logged noise (4 rad/s on
1500, the motor's telemetry) would add ``J_r / I`` times it to the model's rates, so it is
smoothed by a cubic smoothing spline (:func:`scipy.interpolate.make_smoothing_spline`) of
equivalent kernel bandwidth :data:`ROTOR_BANDWIDTH` (Silverman, "Spline smoothing: the
equivalent variable kernel method", Ann. Stat. 12 (1984) 898: ``lambda = B^4`` with ``B`` in
samples): 1 ms takes the noise down 4-fold and follows the motor's ripple up to ~100 Hz (a
parametric spin-up law would not). It is fitted from the rotor's first moving sample on, and
``h = 0`` before it (the motor at rest).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import make_smoothing_spline

from ...dynamics.models.gyrostat import gyrostat_omega
from ...typing import ArrayLike, FloatArray, Matrix3
from .estimate import vector_of

__all__ = ["NAMES", "ROTOR_BANDWIDTH", "RotorInput", "ThrowModel", "cholesky_of", "inertia_jacobian", "inertia_of",
           "rotor_input"]

#: The equivalent kernel bandwidth of the rotor speed's smoothing, s.
ROTOR_BANDWIDTH = 1e-3
#: The parameters, in order.
NAMES = ("c_xx", "c_yy", "c_zz", "c_yx", "c_zx", "c_zy", "L_x", "L_y", "L_z", "bias_x", "bias_y", "bias_z",
         "drag_x", "drag_y", "drag_z")


def inertia_of(c: ArrayLike) -> Matrix3:
    """``I = tr(S) E - S``, ``S = C C^T`` from the six entries of ``C`` (module docstring), batched.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.model import inertia_of
    >>> inertia_of([1.0, 1.0, 0.0, 0.0, 0.0, 0.0]).diagonal().tolist()   # a flat square: I3 = I1 + I2
    [1.0, 1.0, 2.0]
    """
    c = np.asarray(c, float)
    C = np.zeros(c.shape[:-1] + (3, 3))
    C[..., 0, 0], C[..., 1, 1], C[..., 2, 2] = c[..., 0], c[..., 1], c[..., 2]
    C[..., 1, 0], C[..., 2, 0], C[..., 2, 1] = c[..., 3], c[..., 4], c[..., 5]
    S = C @ np.swapaxes(C, -1, -2)
    return np.trace(S, axis1=-2, axis2=-1)[..., None, None] * np.eye(3) - S


def cholesky_of(inertia: ArrayLike, floor: float = 1e-3) -> FloatArray:
    """The ``C`` of a tensor (inverse of :func:`inertia_of`); a tensor just outside the physical
    set is brought in, each eigenvalue of ``S`` at least ``floor`` of the largest.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.model import cholesky_of, inertia_of
    >>> I = np.array([[2.0, 0.1, 0.0], [0.1, 3.0, 0.2], [0.0, 0.2, 4.0]])
    >>> bool(np.allclose(inertia_of(cholesky_of(I)), I))
    True
    """
    I = np.asarray(inertia, float)
    S = 0.5 * np.trace(I) * np.eye(3) - 0.5 * (I + I.T)
    lam, V = np.linalg.eigh(S)
    lam = np.maximum(lam, floor * max(float(lam.max()), 1e-300))
    C = np.linalg.cholesky((V * lam) @ V.T)
    return np.array([C[0, 0], C[1, 1], C[2, 2], C[1, 0], C[2, 0], C[2, 1]])


def inertia_jacobian(c: ArrayLike) -> FloatArray:
    """``d(I_xx, I_yy, I_zz, I_xy, I_xz, I_yz) / dC``, shape (6, 6) (exact: ``I`` is quadratic in
    ``C``, so central differences are exact but for rounding).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.model import inertia_jacobian
    >>> inertia_jacobian([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])[:3, :3].round(9).tolist()   # I_xx = c_yy^2 + c_zz^2 + ...
    [[0.0, 2.0, 2.0], [2.0, 0.0, 2.0], [2.0, 2.0, 0.0]]
    """
    c = np.asarray(c, float)
    step = 1e-4 * max(float(np.abs(c).max()), 1e-300)
    G = np.empty((6, 6))
    for k in range(6):
        d = np.zeros(6)
        d[k] = step
        G[:, k] = (vector_of(inertia_of(c + d)) - vector_of(inertia_of(c - d))) / (2 * step)
    return G


@dataclass(frozen=True)
class RotorInput:
    """The rotor's relative momentum ``h = J_r Omega_r(t) a`` from the smoothed speed log.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.model import rotor_input
    >>> t = np.arange(400) / 4000.0
    >>> speed = np.where(t >= 0.01, 1500.0 * (1 - np.exp(-(t - 0.01) / 0.03)), 0.0)
    >>> r = rotor_input(t, speed, 41, 1.7e-6, [0.0, 0.0, -1.0])   # sample 41 is the first moving one
    >>> err = r.speed(t) - speed   # within 1.5 rad/s at the start (the spline's end), 0.35 rad/s 2 ms on
    >>> float(np.abs(err).max()) < 1.5, float(np.abs(err[49:]).max()) < 0.35
    (True, True)
    """

    spline: object
    t_start: float
    t_before: float
    scale: float
    rotor_inertia: float
    axis: FloatArray

    def speed(self, t: ArrayLike, nu: int = 0) -> FloatArray:
        """The smoothed speed (``nu = 0``, rad/s) or its rate (``nu = 1``, rad/s^2): 0 before the
        last stopped sample, linear from it to the first moving one."""
        t = np.asarray(t, float)
        x = (t - self.t_start) * self.scale
        s = self.spline(np.maximum(x, 0.0), nu) * self.scale ** nu  # type: ignore[operator]
        s0 = float(self.spline(0.0))  # type: ignore[operator]
        ramp = (t - self.t_before) / max(self.t_start - self.t_before, 1e-12)
        early = (s0 * ramp if nu == 0 else np.full(t.shape, s0 / max(self.t_start - self.t_before, 1e-12)))
        return np.where(t >= self.t_start, s, np.where(t > self.t_before, early, 0.0))

    def h(self, t: ArrayLike) -> FloatArray:
        """``J_r Omega_r(t) a``, kg m^2/s, shape ``t.shape + (3,)``."""
        return self.rotor_inertia * self.speed(t)[..., None] * self.axis

    def h_rate(self, t: ArrayLike) -> FloatArray:
        """``J_r Omega_r'(t) a``, N m (for the accelerometer's model, not the fit's)."""
        return self.rotor_inertia * self.speed(t, 1)[..., None] * self.axis


def rotor_input(t: ArrayLike, rotor: ArrayLike, start: int, rotor_inertia: float, axis: ArrayLike) -> RotorInput:
    """:class:`RotorInput` from the log ``(t, rotor)`` and the rotor's first moving sample ``start`` (module docstring).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.model import rotor_input
    >>> t = np.arange(200) / 4000.0
    >>> rotor_input(t, np.r_[np.zeros(20), np.full(180, 100.0)], 20, 1e-6, [1, 0, 0]).speed([0.0, 0.02]).round(6).tolist()
    [0.0, 100.0]
    """
    t = np.asarray(t, float)
    y = np.asarray(rotor, float)
    dt = float(np.median(np.diff(t[start:])))
    x = (t[start:] - t[start]) / dt
    lam = (ROTOR_BANDWIDTH / dt) ** 4
    spline = make_smoothing_spline(x, y[start:], lam=lam)
    a = np.asarray(axis, float)
    return RotorInput(spline, float(t[start]), float(t[start - 1]) if start > 0 else float(t[start]) - dt, 1.0 / dt,
                      float(rotor_inertia), a / np.linalg.norm(a))


class ThrowModel:
    """One throw's fitted samples and the model's prediction of them (module docstring).

    Parameters
    ----------
    t : ndarray, shape (T,)
        The fitted samples' times, s.
    data : ndarray, shape (T, 3)
        The gyroscope's samples, rad/s.
    keep : ndarray of bool, shape (T, 3)
        The sample axes fitted (within the range).
    rotor : RotorInput
    drag : bool
        Whether the drag's three parameters are fitted (else 0).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.model import ThrowModel, rotor_input
    >>> t = np.arange(400) / 4000.0
    >>> rotor = rotor_input(t, np.full(400, 1000.0), 0, 1e-6, [0, 0, 1])
    >>> m = ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor, drag=False)
    >>> m.n, m.sensor(np.r_[0.01, 0.01, 0.01, 0, 0, 0, 0, 0, 1e-3, 0, 0, 0][None]).shape
    (12, (1, 400, 3))
    """

    def __init__(self, t: FloatArray, data: FloatArray, keep: np.ndarray, rotor: RotorInput, drag: bool = True) -> None:
        self.t, self.data, self.keep, self.rotor, self.drag = t, data, keep, rotor, drag
        self.h = rotor.h(t)
        self.h_mid = rotor.h(0.5 * (t[1:] + t[:-1]))
        self.n = 15 if drag else 12
        self.names = NAMES[: self.n]

    def split(self, P: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """``(C entries, L(t_0), bias, drag)`` of parameter rows ``(K, n)``."""
        quad = P[:, 12:15] if self.drag else np.zeros((P.shape[0], 3))
        return P[:, :6], P[:, 6:9], P[:, 9:12], quad

    def omega(self, P: FloatArray) -> FloatArray:
        """The body's rates ``(K, T, 3)`` (no bias), rad/s."""
        c, L0, _, quad = self.split(P)
        return gyrostat_omega(inertia_of(c), L0, self.t, self.h, self.h_mid, quad)

    def sensor(self, P: FloatArray) -> FloatArray:
        """What the gyroscope reads ``(K, T, 3)``: the rates plus the bias, rad/s."""
        return self.omega(P) + self.split(P)[2][:, None, :]

    def residuals(self, P: FloatArray) -> FloatArray:
        """``model - data`` on the kept sample axes, flat."""
        return (self.sensor(P[None])[0] - self.data)[self.keep]

    def steps(self, P: FloatArray) -> FloatArray:
        """Finite-difference steps: 1e-6 of each group's size."""
        c_size = max(float(np.abs(P[:6]).max()), 1e-30)
        L_size = max(float(np.linalg.norm(P[6:9])), 1e-30)
        I_size = float(np.trace(inertia_of(P[:6]))) / 3.0
        sizes = np.r_[np.full(6, c_size), np.full(3, L_size), np.full(3, 0.01), np.full(3, 1e-2 * I_size)]
        return 1e-6 * sizes[: self.n]

    def jacobian(self, P: FloatArray) -> FloatArray:
        """``d residuals / dP`` by forward differences, all columns in one batched integration."""
        d = self.steps(P)
        batch = np.vstack([P, P + np.diag(d)])
        pred = self.sensor(batch)
        cols = (pred[1:] - pred[0]) / d[:, None, None]
        return cols[:, self.keep].T
