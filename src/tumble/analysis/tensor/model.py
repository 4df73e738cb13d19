"""The fit's model of one throw: the gyrostat with a measured rotor, seen by a biased gyroscope.

**Physical tensors.** ``I = tr(S) E - S``, ``S = C C^T`` (:mod:`~tumble.analysis.tensor.physical`):
every ``C`` gives a physical tensor, and the fit needs no bounds.

**Dynamics.** ``L' = L x w - b_i |w_i| w_i - k Omega_r |Omega_r| a``, ``w = I^-1 (L - h(t))``, ``h = J_r Omega_r(t - lag) a``
(the gyrostat in the momentum form: :mod:`tumble.dynamics.models.gyrostat`), from ``L(t_0)``.
The gyroscope reads ``w + bias``. Parameters: ``C`` (6), ``L(t_0)`` (3), the bias (3), the
per-axis quadratic drag ``b`` (3), the rotor log's lag behind the gyroscope's time stamps
(1, s: the motor's telemetry comes a fraction of a millisecond late, and in a spin-up ``h``
changes by 3 % of itself in a millisecond: unmodelled, a 0.5 ms lag took the gyroscope's bias
to 0.5 rad/s and the tensor 1 % off) and the air's drag on the rotor ``k`` (1, N m s^2: the
torque ``-k Omega_r |Omega_r| a`` that the motor holds the rotor's speed against is external to
the whole, and over the plateau it takes ~1 % of the rotor's momentum away: unmodelled, the
proof's tensor came out 0.5 % high). The drags are never negative (the air only takes energy
away): one that comes out negative is held at 0 and the rest fitted again (the active-set
solution of the bound-constrained problem; Nocedal & Wright, *Numerical Optimization*, 2nd
ed., sec. 16.5).

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
from ...typing import ArrayLike, FloatArray
from .physical import cholesky_of, inertia_jacobian, inertia_of

__all__ = ["DYNAMIC", "MAX_STEP", "MEAN_SPAN", "NAMES", "NONNEGATIVE", "integration_grid", "sample_means", "ROTOR_BANDWIDTH", "drag_scale", "RotorInput", "ThrowModel", "cholesky_of", "inertia_jacobian", "inertia_of",
           "rotor_input"]

#: The equivalent kernel bandwidth of the rotor speed's smoothing, s.
ROTOR_BANDWIDTH = 1e-3
#: The parameters, in order.
NAMES = ("c_xx", "c_yy", "c_zz", "c_yx", "c_zx", "c_zy", "L_x", "L_y", "L_z", "bias_x", "bias_y", "bias_z",
         "drag_x", "drag_y", "drag_z", "rotor_lag", "rotor_drag")
#: The parameters integrated for the Jacobian (the bias enters the reading linearly).
DYNAMIC = np.r_[0:9, 12:17]
#: The parameters held non-negative: the air's drags.
NONNEGATIVE = np.r_[12:15, 16]


#: The span over which the samples are averaged before a model is fitted to them, s: the free
#: motion and the rotor's switches (tens of ms) are smooth at 1 kHz, and the means of a 4 kHz
#: log's samples keep their information (the noise falls by the square root of their number)
#: at a quarter of the cost (the joint fit of 12 throws took 12 s on all the samples).
MEAN_SPAN = 1e-3


def sample_means(t: ArrayLike, *series: ArrayLike, keep: np.ndarray | None = None,
                 span: float = MEAN_SPAN) -> tuple[np.ndarray, ...]:
    """The means of consecutive groups of samples spanning about ``span`` s (a whole number of
    samples, at least 1; a last incomplete group dropped): their times, each series' means, and
    with ``keep`` (bool, like the series) where every sample of a group was kept.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.model import sample_means
    >>> t = np.arange(10) * 2.5e-4
    >>> tm, x = sample_means(t, np.arange(10.0))
    >>> tm.round(7).tolist(), x.tolist()   # four samples a mean at 4 kHz; the last two dropped
    ([0.000375, 0.001375], [1.5, 5.5])
    """
    t = np.asarray(t, float)
    k = max(1, int(round(span / float(np.median(np.diff(t)))))) if t.size > 1 else 1
    n = (t.size // k) * k

    def means(x: np.ndarray) -> np.ndarray:
        x = np.asarray(x)[:n]
        return x.reshape((n // k, k) + x.shape[1:]).mean(axis=1)

    out = [means(t), *[means(np.asarray(x, float)) for x in series]]
    if keep is not None:
        k_ = np.asarray(keep)[:n]
        out.append(k_.reshape((n // k, k) + k_.shape[1:]).all(axis=1))
    return tuple(out)


#: The longest step the integration takes, in median sample intervals: a gap in a log (samples
#: lost) is integrated over in steps no longer (one RK4 step over 20 ms of a 15 rad/s tumble errs
#: by ~(|w| dt)^5 ~ 2e-3 of the rates, which took the tensor 2-3 % off).
MAX_STEP = 1.5


def integration_grid(t: ArrayLike) -> tuple[FloatArray, np.ndarray]:
    """The times the model integrates over: the samples, with steps inserted evenly into every
    interval longer than :data:`MAX_STEP` median intervals; and where the samples lie in it.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.model import integration_grid
    >>> t = np.r_[np.arange(10), np.arange(14, 20)] * 2.5e-4   # four samples lost
    >>> grid, at = integration_grid(t)
    >>> grid.size, bool(np.allclose(grid[at], t)), round(float(np.diff(grid).max()) / 2.5e-4, 9)   # the gap in 4 steps
    (19, True, 1.25)
    """
    t = np.asarray(t, float)
    if t.size < 3:
        return t, np.arange(t.size)
    dt = np.diff(t)
    step = MAX_STEP * float(np.median(dt))
    parts = np.maximum(np.ceil(dt / step - 1e-9).astype(int), 1)
    if np.all(parts == 1):
        return t, np.arange(t.size)
    pieces = [t[:1]] + [t[k] + dt[k] * np.arange(1, parts[k] + 1) / parts[k] for k in range(t.size - 1)]
    grid = np.concatenate(pieces)
    at = np.r_[0, np.cumsum(parts)]
    grid[at] = t
    return grid, at


def drag_scale(inertia_size: float) -> float:
    """The size of the drag ``b`` for a body of mean moment ``inertia_size`` (kg m^2): 1 % of it
    in N m s^2 (the finite differences' scale, as :meth:`ThrowModel.steps` takes it).

    Examples
    --------
    >>> from tumble.analysis.tensor.model import drag_scale
    >>> drag_scale(1e-3)
    1e-05
    """
    return 1e-2 * float(inertia_size)


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

    def speed(self, t: ArrayLike) -> FloatArray:
        """The smoothed speed, rad/s: 0 up to the last stopped sample, linear from it to the first
        moving one, the spline from there on.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.model import rotor_input
        >>> t = np.arange(200) / 4000.0
        >>> r = rotor_input(t, np.r_[np.zeros(20), np.full(180, 100.0)], 20, 1e-6, [0, 0, 1])
        >>> r.speed([t[10], 0.5 * (t[19] + t[20]), t[100]]).round(9).tolist()   # at rest, half-way up, spun up
        [0.0, 50.0, 100.0]
        """
        t = np.asarray(t, float)
        s = self.spline(np.maximum((t - self.t_start) * self.scale, 0.0))  # type: ignore[operator]
        s0 = float(self.spline(0.0))  # type: ignore[operator]
        ramp = s0 * (t - self.t_before) / max(self.t_start - self.t_before, 1e-12)
        return np.where(t >= self.t_start, s, np.where(t > self.t_before, ramp, 0.0))

    def h(self, t: ArrayLike) -> FloatArray:
        """``J_r Omega_r(t) a``, kg m^2/s, shape ``t.shape + (3,)``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.model import rotor_input
        >>> t = np.arange(200) / 4000.0
        >>> r = rotor_input(t, np.r_[np.zeros(20), np.full(180, 100.0)], 20, 1e-6, [2, 0, 0])   # any length
        >>> r.h([0.0, 0.02]).round(12).tolist()   # at rest, then 1e-6 kg m^2 x 100 rad/s along x
        [[0.0, 0.0, 0.0], [0.0001, 0.0, 0.0]]
        >>> r.h(np.zeros((2, 5))).shape
        (2, 5, 3)
        """
        return self.rotor_inertia * self.speed(t)[..., None] * self.axis


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
        Whether the drag's three parameters, the rotor's lag and its drag are fitted (else 0).

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
        self.grid, self.at = integration_grid(t)
        self.h = rotor.h(t)
        self.h_mid = rotor.h(0.5 * (t[1:] + t[:-1]))
        self.n = 17 if drag else 12
        self.names = NAMES[: self.n]
        self._lagged: dict[float, tuple[FloatArray, FloatArray]] = {}

    def momentum(self, lag: float = 0.0) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """``J_r Omega_r(t - lag)`` at the samples and the midpoints, kg m^2/s (the rotor's log
        ``lag`` s late against the gyroscope's), and ``-Omega_r |Omega_r|`` there, rad^2/s^2 (the
        rotor's air drag's profile); the last few kept.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.model import ThrowModel, rotor_input
        >>> t = np.arange(400) / 4000.0
        >>> m = ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor_input(t, 1e4 * t, 1, 1e-6, [0, 0, 1]))
        >>> s = m.momentum(1e-3)[0]
        >>> round(float(s[200] / 1e-6), 6), round(float(t[200] - 1e-3) * 1e4, 6)   # the speed a millisecond before
        (490.0, 490.0)
        """
        lag = float(lag)
        if lag not in self._lagged:
            if len(self._lagged) > 4:
                self._lagged.pop(next(iter(self._lagged)))
            J = self.rotor.rotor_inertia
            g = self.grid
            at, mid = self.rotor.speed(g - lag), self.rotor.speed(0.5 * (g[1:] + g[:-1]) - lag)
            self._lagged[lag] = (J * at, J * mid, -at * np.abs(at), -mid * np.abs(mid))
        return self._lagged[lag]

    def split(self, P: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """``(C entries, L(t_0), bias, drag)`` of parameter rows ``(K, n)``; the drag 0 when not fitted.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.model import ThrowModel, rotor_input
        >>> t = np.arange(400) / 4000.0
        >>> m = ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor_input(t, np.full(400, 1e3), 0, 1e-6,
        ...                [0, 0, 1]), drag=False)
        >>> c, L0, bias, drag = m.split(np.arange(12.0)[None])   # one row of the 12 parameters
        >>> c.shape, L0.tolist(), bias.tolist(), drag.tolist()
        ((1, 6), [[6.0, 7.0, 8.0]], [[9.0, 10.0, 11.0]], [[0.0, 0.0, 0.0]])
        """
        quad = P[:, 12:15] if self.drag else np.zeros((P.shape[0], 3))
        return P[:, :6], P[:, 6:9], P[:, 9:12], quad

    def omega(self, P: FloatArray, axis: FloatArray | None = None) -> FloatArray:
        """The body's rates ``(K, T, 3)`` (no bias), rad/s, of parameter rows ``(K, n)``; the rotor
        along ``axis`` (unit, sensor frame) instead of its own when given.

        Examples
        --------
        A rotor spun up along a principal axis of a body spinning about it: the spin stays
        about that axis, ``w_z = (L_z - h_z(t)) / I_zz`` (``L`` fixed); and with any tensor and
        ``L``, ``|I w + h|`` is conserved (``L' = L x w``):

        >>> import numpy as np
        >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
        >>> t = np.arange(400) / 4000.0
        >>> speed = np.where(t >= 0.01, 1500.0 * (1 - np.exp(-(t - 0.01) / 0.03)), 0.0)
        >>> m = ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor_input(t, speed, 41, 1.7e-6,
        ...                [0, 0, 1]), drag=False)
        >>> P = np.r_[cholesky_of(np.diag([2e-4, 3e-4, 4e-4])), 0.0, 0.0, 4e-3, np.zeros(3)]
        >>> w = m.omega(P[None])
        >>> w.shape, bool(np.allclose(w[0], np.c_[0 * t, 0 * t, (4e-3 - m.h[:, 2]) / 4e-4], rtol=0, atol=1e-9))
        ((1, 400, 3), True)
        >>> I = np.array([[2e-4, 1e-5, 0.0], [1e-5, 3e-4, 2e-5], [0.0, 2e-5, 4e-4]])
        >>> L = m.omega(np.r_[cholesky_of(I), 1e-3, 2e-3, 3e-3, np.zeros(3)][None])[0] @ I + m.h
        >>> bool(np.ptp(np.linalg.norm(L, axis=1)) < 1e-12 * np.linalg.norm(L[0]))
        True
        """
        c, L0, _, quad = self.split(P)
        a = self.rotor.axis if axis is None else axis
        lags = P[:, 15] if self.drag else np.zeros(P.shape[0])
        k = P[:, 16] if self.drag else np.zeros(P.shape[0])
        out = np.empty((P.shape[0], self.grid.size, 3))
        I = inertia_of(c)
        moments = np.linalg.eigvalsh(I)
        flat = ~(moments[:, 0] > 1e-9 * np.abs(moments[:, 2]))  # a tensor with no inverse (a rod, or NaN): no motion
        I[flat] = np.eye(3)
        for lag in np.unique(lags):
            rows = lags == lag
            s, s_mid, g, g_mid = self.momentum(lag)
            out[rows] = gyrostat_omega(I[rows], L0[rows], self.grid, np.outer(s, a), np.outer(s_mid, a), quad[rows],
                                       torque=(np.outer(g, a), np.outer(g_mid, a)), torque_scale=k[rows])
        out[flat] = np.nan
        return out[:, self.at]

    def sensor(self, P: FloatArray) -> FloatArray:
        """What the gyroscope reads ``(K, T, 3)``: the rates plus the bias, rad/s.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
        >>> t = np.linspace(0.0, 0.1, 300)
        >>> m = ThrowModel(t, np.zeros((300, 3)), np.ones((300, 3), bool), rotor_input(t, np.linspace(0.0, 1e3, 300), 1,
        ...                2e-6, [1, 1, 0]))   # the drags and lag fitted: 17 parameters
        >>> c = cholesky_of([[2e-4, 1e-5, 0.0], [1e-5, 3e-4, 0.0], [0.0, 0.0, 4e-4]])
        >>> biases = ([0.01, -0.02, 0.03], [0.0, 0.0, 0.1])   # two parameter rows at once
        >>> P = np.array([np.r_[c, 1e-3, 0.0, 2e-3, bias, np.full(3, 1e-6), 2e-4, 1e-11] for bias in biases])
        >>> offset = m.sensor(P) - m.omega(P)
        >>> offset.shape, bool(np.allclose(offset, P[:, None, 9:12], rtol=0, atol=1e-15))
        ((2, 300, 3), True)
        """
        return self.omega(P) + self.split(P)[2][:, None, :]

    def residuals(self, P: FloatArray) -> FloatArray:
        """``model - data`` on the kept sample axes, flat, rad/s, of one parameter vector ``(n,)``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
        >>> t = np.arange(400) / 4000.0
        >>> rotor = rotor_input(t, np.full(400, 1e3), 0, 1e-6, [0, 0, 1])
        >>> keep = np.ones((400, 3), bool)
        >>> keep[100:150, 0] = False   # x saturated for 50 samples
        >>> P = np.r_[cholesky_of(np.diag([2e-4, 3e-4, 4e-4])), 1e-3, 0.0, 2e-3, 0.01, -0.02, 0.03]
        >>> truth = ThrowModel(t, np.zeros((400, 3)), keep, rotor, drag=False).sensor(P[None])[0]
        >>> r = ThrowModel(t, truth + 0.005, keep, rotor, drag=False).residuals(P)
        >>> r.shape, bool(np.allclose(r, -0.005, rtol=0, atol=1e-15))   # 1200 - 50 sample axes
        ((1150,), True)
        """
        return (self.sensor(P[None])[0] - self.data)[self.keep]

    def steps(self, P: FloatArray) -> FloatArray:
        """Finite-difference steps ``(n,)``: 1e-6 of each group's size (``C``'s largest entry,
        ``|L(t_0)|``, 0.01 rad/s for the bias, :func:`drag_scale` for the drag, 1 s for the lag,
        ``1e-4 J_r`` for the rotor's drag).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
        >>> t = np.linspace(0.0, 0.2, 500)
        >>> rotor = rotor_input(t, np.full(500, 800.0), 0, 2e-6, [0, 1, 0])
        >>> m = ThrowModel(t, np.zeros((500, 3)), np.ones((500, 3), bool), rotor)   # the drags and lag: 17 parameters
        >>> d = m.steps(np.r_[cholesky_of(np.diag([2e-4, 3e-4, 4e-4])), 3e-3, 0.0, 4e-3, np.zeros(8)])
        >>> d.shape, bool(np.allclose(d[6:], 1e-6 * np.r_[np.repeat([5e-3, 0.01, 3e-6], 3), 1.0, 2e-10], rtol=1e-12, atol=0))
        ((17,), True)
        """
        c_size = max(float(np.abs(P[:6]).max()), 1e-30)
        L_size = max(float(np.linalg.norm(P[6:9])), 1e-30)
        I_size = float(np.trace(inertia_of(P[:6]))) / 3.0
        sizes = np.r_[np.full(6, c_size), np.full(3, L_size), np.full(3, 0.01), np.full(3, drag_scale(I_size)), 1.0,
                      1e-4 * self.rotor.rotor_inertia]
        return 1e-6 * sizes[: self.n]

    def jacobian(self, P: FloatArray) -> FloatArray:
        """``d residuals / dP`` ``(kept sample axes, n)`` by forward differences, all columns in
        one batched integration.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
        >>> t = np.arange(400) / 4000.0
        >>> m = ThrowModel(t, np.zeros((400, 3)), np.ones((400, 3), bool), rotor_input(t, np.full(400, 1e3), 0, 1e-6,
        ...                [0, 0, 1]), drag=False)
        >>> P = np.r_[cholesky_of(np.diag([2e-4, 3e-4, 4e-4])), 1e-3, 0.0, 2e-3, 0.01, -0.02, 0.03]
        >>> J = m.jacobian(P)
        >>> J.shape, bool(np.allclose(J[:3, 9:12], np.eye(3), rtol=0, atol=1e-6))   # the bias: 1 on its own axis
        ((1200, 12), True)
        >>> e = np.r_[1e-8, np.zeros(11)]   # the c_xx column against a central difference
        >>> central = (m.residuals(P + e) - m.residuals(P - e)) / 2e-8
        >>> bool(np.allclose(J[:, 0], central, rtol=0, atol=1e-5 * np.abs(central).max()))
        True
        """
        d = self.steps(P)
        dyn = DYNAMIC[DYNAMIC < self.n]
        batch = np.vstack([P, P + np.diag(d)[dyn]])
        pred = self.omega(batch)
        cols = np.zeros((self.n,) + pred.shape[1:])
        cols[dyn] = (pred[1:] - pred[0]) / d[dyn, None, None]
        cols[9:12] = np.eye(3)[:, None, :]
        return cols[:, self.keep].T
