"""The flown body's centre of mass from the accelerometer: :func:`center_of_mass`.

In free flight an accelerometer at ``r`` from the centre of mass reads ``f = w' x r + w x (w x r)
+ b_a`` (the acceleration of a point of a rigid body, Goldstein, Poole & Safko, *Classical
Mechanics*, 3rd ed., sec. 4.10, less gravity, which a falling accelerometer does not sense; ``b_a``
its bias). With ``w`` from the fitted model (not the noisy data) and the reading integrated over
blocks of :data:`ACCEL_BLOCK` samples,

    ``integral f dt = (w_b - w_a) x r + integral w x (w x r) dt + b_a (t_b - t_a)``,

so that ``w'`` is never needed (it would need the rotor's ``h'``), the reading is linear in
``r`` and the bias: linear least squares, the bias held near 0 by its prior uncertainty
:data:`ACCEL_BIAS_STD` (a Gaussian prior as extra rows: Tarantola, *Inverse Problem Theory*,
2005, ch. 3). Several throws of one rigid mount share ``r`` and the accelerometer's bias (one
sensor through one session).

What the real device's accelerometer adds (issue #42): at each of the rotor's switches the
motor's reaction shakes the structure, a jolt of 5-20 m/s^2 over a few ms that no rigid motion
explains. A block holding one stands far out of the others' residuals: blocks whose residual
exceeds :data:`JOLT_FACTOR` times the blocks' median (a robust scale) are left out and the
regression made again (one pass of a trimmed least squares; Rousseeuw & Leroy, *Robust
Regression and Outlier Detection*, 1987, ch. 4). The air's force on the body (~0.2 m/s^2) is
left to the noise.

The covariance: the blocks' least-squares covariance widened by their residuals'
autocorrelation (:func:`tumble.analysis.fit.uncertainty.autocorrelation_time`), or the
delete-a-group jackknife's over stretches of the flights where it is larger (slow disturbances:
the air's force, the rotor's imbalance, the firmware's smoothing at the rotor's switches), plus the part
of the fitted rates' own uncertainty (their parameters' covariance through ``dr/dP``, by
central differences; the law of propagation of uncertainty, JCGM 100:2008, sec. 5.1). The
centre of mass from the accelerometer is ``-r``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.integrate import cumulative_trapezoid

from ...typing import FloatArray
from ..fit.uncertainty import autocorrelation_time
from .flight import skew
from .model import ThrowModel

__all__ = ["ACCEL_BIAS_STD", "ACCEL_BLOCK", "AIR_STD", "JACKKNIFE_GROUPS", "JOLT_FACTOR", "LAGS", "center_of_mass", "rate_part"]

#: Samples per block of the accelerometer's integrated reading (20 ms at 4 kHz).
ACCEL_BLOCK = 80
#: The lags of the firmware's smoothing tried, s: its low-pass filter delays the reading by its
#: group delay (a second-order Butterworth at 100-200 Hz: 1-2 ms), which matters where the
#: rotor's switches change ``w'`` fast; the model's reading is delayed by the lag that fits best.
LAGS = np.arange(0.0, 4.01e-3, 0.5e-3)
#: The air's force on the thrown body over its mass, m/s^2, per axis: ``rho C_d A v^2 / 2m`` ~
#: 0.1-0.3 m/s^2 for a hand-sized body of 0.3-1 kg at 3-5 m/s (air 1.2 kg/m^3, C_d ~ 1); it
#: turns with the body and changes with the speed, slowly: each throw's reading is taken to be
#: off by it, a standard uncertainty (type B, JCGM 100:2008, sec. 4.3) propagated to ``r``.
AIR_STD = 0.2
#: The stretches of each throw's blocks that the jackknife leaves out in turn (:func:`_jackknife`).
JACKKNIFE_GROUPS = 5
#: A block whose residual exceeds this many times the blocks' median is left out (a jolt).
JOLT_FACTOR = 4.0
#: The accelerometer's bias, m/s^2: a prior standard uncertainty (a flight controller's
#: accelerometer is levelled at rest, leaving ~0.1 m/s^2; MEMS zero-g offsets are +-0.2-0.6 m/s^2
#: before it, e.g. Bosch BMI270, TDK ICM-42688-P data sheets). Without it a throw spinning about
#: one axis trades its centripetal reading, constant, for a bias (they are the same column).
ACCEL_BIAS_STD = 0.2
_RANGE = 15.9 * 9.80665  # a reading this large may be clipped (the 16 g range)


def _blocks(w: FloatArray, t: FloatArray, accel: FloatArray) -> tuple[FloatArray, FloatArray]:
    """One throw's block rows ``(B, 3, 6)`` (``r``'s and the bias's columns) and right-hand sides ``(B, 3)``."""
    good = np.all(np.abs(accel) < _RANGE, axis=1)
    Q = cumulative_trapezoid(skew(w) @ skew(w), t, axis=0, initial=0.0)
    F = cumulative_trapezoid(accel, t, axis=0, initial=0.0)
    rows, rhs = [], []
    for a in range(0, t.size - ACCEL_BLOCK, ACCEL_BLOCK):
        b = a + ACCEL_BLOCK
        if good[a:b + 1].all():
            rows.append(np.hstack([skew(w[b] - w[a]) + Q[b] - Q[a], (t[b] - t[a]) * np.eye(3)]))
            rhs.append(F[b] - F[a])
    return np.array(rows).reshape(-1, 3, 6), np.array(rhs).reshape(-1, 3)


def _delayed(w: FloatArray, t: FloatArray, lag: float) -> FloatArray:
    """The rates ``lag`` s earlier (linear interpolation; held at the first sample before it)."""
    if lag == 0.0:
        return w
    return np.column_stack([np.interp(t - lag, t, w[:, i]) for i in range(3)])


def _design(rows: list[FloatArray], rhs: list[FloatArray]) -> tuple[FloatArray, FloatArray]:
    """The stacked blocks: columns ``r`` (3) and the shared bias (3)."""
    return np.vstack([R.reshape(-1, 6) for R in rows]), np.concatenate([y.ravel() for y in rhs])


def _solve(A: FloatArray, y: FloatArray, weight: float) -> FloatArray:
    """Least squares with the bias's prior rows ``weight x b = 0``."""
    prior = np.hstack([np.zeros((3, 3)), weight * np.eye(3)])
    return np.linalg.lstsq(np.vstack([A, prior]), np.r_[y, np.zeros(3)], rcond=None)[0]


def center_of_mass(models: Sequence[ThrowModel], Ps: Sequence[FloatArray],
                   accels: Sequence[FloatArray]) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The centre of mass shared by one or more throws (module docstring): ``(c, cov_c, b_a)`` in
    m, m^2 and m/s^2, without the rates' part (:func:`rate_part`).

    Parameters
    ----------
    models : sequence of ThrowModel
        Each throw's fitted samples.
    Ps : sequence of ndarray
        Each throw's parameters (:class:`~tumble.analysis.tensor.model.ThrowModel`).
    accels : sequence of ndarray, shape (T_k, 3)
        Each throw's accelerometer at its model's samples, m/s^2.

    Examples
    --------
    A body tumbling about a fixed axis (``w' = 0``), the accelerometer 3 cm from its centre:

    >>> import numpy as np
    >>> from tumble.analysis.tensor.center import center_of_mass
    >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
    >>> t = np.arange(2000) / 4000.0
    >>> m = ThrowModel(t, np.zeros((2000, 3)), np.ones((2000, 3), bool), rotor_input(t, np.zeros(2000), 0, 1e-6, [0, 0, 1]))
    >>> P = np.r_[cholesky_of(np.diag([2e-4, 3e-4, 4e-4])), 0.0, 0.0, 4e-3, np.zeros(6)]   # 10 rad/s about z
    >>> r = np.array([0.03, 0.0, 0.0])
    >>> w = m.omega(P[None])[0]
    >>> f = np.cross(w, np.cross(w, r)) + np.random.default_rng(0).normal(0.0, 0.1, (2000, 3))
    >>> c, cov, bias = center_of_mass([m], [P], [f])
    >>> (c[:2] * 1e3).round(1).tolist(), bool(np.all(np.abs(bias) < 0.01))   # c = -r; the bias held near 0
    ([-30.0, 0.0], True)
    """
    rates = [m.omega(np.asarray(P, float)[None])[0] for m, P in zip(models, Ps)]

    def cost(lag: float) -> float:
        A, y = _design(*zip(*[_blocks(_delayed(w, m.t, lag), m.t, a) for w, m, a in zip(rates, models, accels)]))
        x = np.linalg.lstsq(A, y, rcond=None)[0]
        return float(np.sum((A @ x - y) ** 2))

    lag = float(LAGS[int(np.argmin([cost(x) for x in LAGS]))])
    blocks = [_blocks(_delayed(w, m.t, lag), m.t, a) for w, m, a in zip(rates, models, accels)]
    rows, rhs = [b[0] for b in blocks], [b[1] for b in blocks]
    for _ in range(2):  # the second pass without the jolts' blocks
        A, y = _design(rows, rhs)
        x = np.linalg.lstsq(A, y, rcond=None)[0]
        res = A @ x - y
        s = float(np.sqrt(res @ res / max(res.size - 6, 1)))
        weight = s / ACCEL_BIAS_STD  # a prior row of residual std s: the bias's std ACCEL_BIAS_STD
        x = _solve(A, y, weight)
        norms = np.linalg.norm((A @ x - y).reshape(-1, 3), axis=1)
        kept = np.split(norms <= JOLT_FACTOR * float(np.median(norms)), np.cumsum([len(r) for r in rows])[:-1])
        if all(k.all() for k in kept) or not all(k.sum() >= 2 for k in kept):
            break
        rows = [r[k] for r, k in zip(rows, kept)]
        rhs = [y_[k] for y_, k in zip(rhs, kept)]
    res = A @ x - y
    counts = np.r_[0, np.cumsum([len(r) for r in rows])]
    s2 = float(res @ res) / max(res.size - 6, 1)
    normal = A.T @ A
    normal[3:, 3:] += weight ** 2 * np.eye(3)
    cov = np.linalg.pinv(normal) * s2 * autocorrelation_time(res.reshape(-1, 3), list(counts))
    jack = _jackknife(A, y, weight, counts)
    if np.trace(jack[:3, :3]) > np.trace(cov[:3, :3]):
        cov = jack
    # the air's force: a slow offset of each throw's reading, type B, through the fit's linear response
    inverse = np.linalg.pinv(normal)
    for a, b in zip(3 * counts[:-1], 3 * counts[1:]):
        offset = np.zeros((A.shape[0], 3))
        offset[a:b] = A[a:b, 3:6]
        shift = inverse @ (A.T @ offset)
        cov = cov + AIR_STD ** 2 * shift @ shift.T
    return -x[:3], 0.5 * (cov[:3, :3] + cov[:3, :3].T), x[3:]


def _jackknife(A: FloatArray, y: FloatArray, weight: float, counts: FloatArray) -> FloatArray:
    """The delete-a-group jackknife covariance (Efron & Tibshirani, *An Introduction to the
    Bootstrap*, 1993, ch. 11) over :data:`JACKKNIFE_GROUPS` stretches of each throw's blocks:
    it holds what varies along a flight and from throw to throw (the air's force, the rotor's
    imbalance, the firmware's smoothing at the rotor's switches) as the residuals' formula with
    their short autocorrelation does not."""
    groups = []
    for a, b in zip(counts[:-1], counts[1:]):
        edges = np.linspace(a, b, JACKKNIFE_GROUPS + 1).round().astype(int)
        groups += [(3 * lo, 3 * hi) for lo, hi in zip(edges[:-1], edges[1:]) if hi > lo]
    if len(groups) < 3:
        return np.zeros((6, 6))
    xs = []
    for lo, hi in groups:
        keep = np.r_[0:lo, hi:A.shape[0]]
        xs.append(_solve(A[keep], y[keep], weight))
    xs = np.array(xs)
    g = len(xs)
    d = xs - xs.mean(axis=0)
    return (g - 1) / g * d.T @ d


def rate_part(model: ThrowModel, P: FloatArray, cov: FloatArray, accel: FloatArray, free: Sequence[int]) -> FloatArray:
    """The centre's covariance from one throw's fitted rates': ``G cov G^T``, ``G = dc/dP`` by central
    differences over the parameters ``free`` (indices into ``P``; ``cov`` theirs).

    Examples
    --------
    >>> from tumble.analysis.tensor.center import rate_part
    >>> callable(rate_part)
    True
    """
    d = model.steps(P) * 100.0
    G = np.empty((3, len(free)))
    for col, k in enumerate(free):
        e = np.zeros(P.size)
        e[k] = d[k]
        G[:, col] = (center_of_mass([model], [P + e], [accel])[0] - center_of_mass([model], [P - e], [accel])[0]) / (2 * d[k])
    return G @ cov @ G.T
