"""One throw fitted: the flown body's tensor and centre of mass with their statistical covariances.

1. The flight is found (:func:`~tumble.analysis.tensor.flight.find_flight`), the gyroscope's
   samples at its rail left out (:func:`tumble.analysis.fit.single.saturation_mask`).
2. **Starting values** by an equation-error regression on the integrated gyrostat equation:
   over blocks ``[t_a, t_b]`` of :data:`BLOCK` samples, ``I (w_b - w_a) + integral (w x I w +
   w x h) dt + h_b - h_a = 0`` (Euler's equation of the gyrostat integrated in time; Hughes,
   *Spacecraft Attitude Dynamics*, 1986, ch. 7) is linear in the six entries of ``I``, with the
   integrals by the trapezoidal rule on the samples. It needs no derivative, but the measured
   ``w`` inside the cross products carries noise (an errors-in-variables bias): good enough to
   start from.
3. The **output-error fit** of :class:`~tumble.analysis.tensor.model.ThrowModel` by
   :func:`scipy.optimize.least_squares` over the real sample times: Levenberg-Marquardt
   (MINPACK's, ``x_scale="jac"``; the model needs no bounds). Why not the trust-region methods:
   they take an SVD of the (samples x 15) Jacobian at every step, which LAPACK's threads made
   0.2-0.4 s on a loaded two-core machine (MINPACK's own QR: 2 ms).
4. **Covariance**: ``(J^T J)^-1 s^2 tau`` with the residuals' autocorrelation time ``tau``
   (:func:`tumble.analysis.fit.uncertainty.effective_covariance`), propagated to the tensor's
   entries through ``dI/dC`` (the law of propagation of uncertainty, JCGM 100:2008, sec. 5.1).
5. **Centre of mass**: with ``w`` from the fitted model (not the noisy data), the
   accelerometer's free-fall reading ``f = w' x r + w x (w x r) + b_a`` (Goldstein, Poole &
   Safko, *Classical Mechanics*, 3rd ed., sec. 4.10), integrated over short blocks so that
   ``w'`` drops out (:func:`center_of_mass`), is linear in ``r`` (the accelerometer from the
   centre of mass) and its bias ``b_a``: linear least squares, the covariance as in 4, plus
   the part of the fitted rates' own uncertainty (their parameters' covariance through
   ``dc/dP``, by central differences). The centre of mass
   from the accelerometer is ``-r``. The air's force on the body (~0.2 m/s^2 for a 0.7 kg box at
   3 m/s) is left to the bias.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import cumulative_trapezoid
from scipy.optimize import least_squares

from ...typing import FloatArray
from ..fit.adequacy import Adequacy, judge
from ..fit.single import saturation_mask
from ..fit.uncertainty import effective_covariance, noise_floor
from .device import Throw
from .estimate import tensor_of
from .flight import Window, find_flight, skew
from .model import RotorInput, ThrowModel, cholesky_of, inertia_jacobian, inertia_of, rotor_input

__all__ = ["ACCEL_BLOCK", "BLOCK", "FlownFit", "center_of_mass", "fit_flown", "start_values"]

#: Samples per block of the starting regression (50 ms at 4 kHz): over 10 ms blocks the change of a weakly
#: tumbling throw's rates is little above their noise, and the regression's tensor came out 20-70 % low
#: (errors in variables); over 50 ms, within 8 % on the coverage trials.
BLOCK = 200
#: The factors tried on the starting regression's tensor (:func:`_scaled_start`).
START_SCALES = np.geomspace(0.2, 5.0, 33)
#: Samples per block of the accelerometer's integrated reading (20 ms at 4 kHz).
ACCEL_BLOCK = 80


@dataclass(frozen=True)
class FlownFit:
    """One throw's fit of the flown body (module docstring); ``reason`` non-empty when there is none.

    Examples
    --------
    >>> from tumble.analysis.tensor.throw import FlownFit
    >>> sorted(FlownFit.__dataclass_fields__)[:4]
    ['P', 'accel_bias', 'adequacy', 'center']
    """

    window: Window
    reason: str
    P: FloatArray | None = None
    cov: FloatArray | None = None
    inertia: FloatArray | None = None
    inertia_cov: FloatArray | None = None
    center: FloatArray | None = None
    center_cov: FloatArray | None = None
    accel_bias: FloatArray | None = None
    t: FloatArray | None = None
    omega_measured: FloatArray | None = None
    omega_model: FloatArray | None = None
    residual_rms: float = float("nan")
    adequacy: Adequacy | None = None


def _blocks(ok: np.ndarray, size: int) -> list[tuple[int, int]]:
    """Blocks ``[a, b]`` of at most ``size`` intervals (at least a fifth of it) inside the runs of ``ok`` samples."""
    bad = np.flatnonzero(~ok)
    edges = np.r_[-1, bad, ok.size]
    out = []
    for r0, r1 in zip(edges[:-1] + 1, edges[1:]):
        for a in range(int(r0), int(r1) - 1, size):
            b = min(a + size, int(r1) - 1)
            if b - a >= max(size // 5, 2):
                out.append((a, b))
    return out


def start_values(t: FloatArray, w: FloatArray, keep: np.ndarray, h: FloatArray) -> FloatArray:
    """The tensor from the integrated equation (module docstring, step 2), kg m^2.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.throw import start_values
    >>> from tumble.dynamics.models.gyrostat import gyrostat_omega
    >>> I = np.array([[2e-3, 1e-4, 0.0], [1e-4, 3e-3, 0.0], [0.0, 0.0, 4e-3]])
    >>> t = np.arange(2000) / 4000.0
    >>> h = np.outer(np.minimum(t / 0.1, 1.0) * 2.5e-3, [0.0, 0.0, -1.0])
    >>> w = gyrostat_omega(I[None], [[0.02, 0.01, 0.03]], t, h, 0.5 * (h[1:] + h[:-1]))[0]
    >>> bool(np.allclose(start_values(t, w, np.ones(w.shape, bool), h), I, rtol=1e-3, atol=1e-6))
    True
    """
    basis = tensor_of(np.eye(6))
    Q = [cumulative_trapezoid(np.cross(w, w @ E), t, axis=0, initial=0.0) for E in basis]
    Qh = cumulative_trapezoid(np.cross(w, h), t, axis=0, initial=0.0)
    rows, rhs = [], []
    for a, b in _blocks(np.all(keep, axis=1), BLOCK):
        dw = w[b] - w[a]
        rows.append(np.column_stack([basis[j] @ dw + Q[j][b] - Q[j][a] for j in range(6)]))
        rhs.append(-(Qh[b] - Qh[a] + h[b] - h[a]))
    if len(rows) < 3:
        raise ValueError("too few unclipped blocks of samples to start the fit")
    v = np.linalg.lstsq(np.vstack(rows), np.concatenate(rhs), rcond=None)[0]
    return tensor_of(v)


def center_of_mass(model: ThrowModel, P: FloatArray, accel: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The flown body's centre of mass from the accelerometer (module docstring, step 5): ``(c,
    cov_c, b_a)`` in m, m^2 and m/s^2.

    The reading is integrated over blocks of :data:`ACCEL_BLOCK` samples,
    ``integral f dt = (w_b - w_a) x r + integral w x (w x r) dt + b_a (t_b - t_a)``, so that
    ``w'`` is never needed (it would need the rotor's ``h'``, poorly known at its start).

    Examples
    --------
    >>> from tumble.analysis.tensor.throw import center_of_mass
    >>> callable(center_of_mass)
    True
    """
    w = model.omega(P[None])[0]
    t = model.t
    good = np.all(np.abs(accel) < 15.9 * 9.80665, axis=1)
    Q = cumulative_trapezoid(skew(w) @ skew(w), t, axis=0, initial=0.0)
    F = cumulative_trapezoid(accel, t, axis=0, initial=0.0)
    rows, rhs = [], []
    for a in range(0, t.size - ACCEL_BLOCK, ACCEL_BLOCK):
        b = a + ACCEL_BLOCK
        if not good[a:b + 1].all():
            continue
        rows.append(np.hstack([skew(w[b] - w[a]) + Q[b] - Q[a], (t[b] - t[a]) * np.eye(3)]))
        rhs.append(F[b] - F[a])
    n = len(rows)
    A, y = np.vstack(rows), np.concatenate(rhs)
    x = np.linalg.lstsq(A, y, rcond=None)[0]
    r = A @ x - y
    cov, _ = effective_covariance(A, r, r.reshape(-1, 3), [0, n])
    return -x[:3], cov[:3, :3], x[3:]


def _model_part(model: ThrowModel, P: FloatArray, cov: FloatArray, accel: FloatArray) -> FloatArray:
    """The centre's covariance from the fitted rates' own: ``G cov G^T``, ``G = dc/dP`` by central differences."""
    d = model.steps(P) * 100.0
    G = np.empty((3, P.size))
    for k in range(P.size):
        e = np.zeros(P.size)
        e[k] = d[k]
        G[:, k] = (center_of_mass(model, P + e, accel)[0] - center_of_mass(model, P - e, accel)[0]) / (2 * d[k])
    return G @ cov @ G.T


def _scaled_start(model: ThrowModel, c0: FloatArray, w0: FloatArray, drag: bool) -> FloatArray:
    """The start with the regression's tensor scaled by the factor (of :data:`START_SCALES`) whose
    integrated model fits best, all in one batched integration: the regression's noisy rates bias
    its scale (errors in variables: a factor 3 low on a weakly tumbling throw), and from a wrong
    scale Levenberg-Marquardt crawls along the valley of the scale for hundreds of steps."""
    k = START_SCALES
    I0 = inertia_of(c0)
    P = np.column_stack([np.outer(np.sqrt(k), c0), np.outer(k, I0 @ w0) + model.h[0], np.zeros((k.size, model.n - 9))])
    err = np.where(model.keep, model.sensor(P) - model.data, 0.0)
    with np.errstate(all="ignore"):
        cost = np.nan_to_num(np.sum(err ** 2, axis=(1, 2)), nan=np.inf)
    return P[int(np.argmin(cost))]


def _fit(model: ThrowModel, P0: FloatArray) -> FloatArray:
    with np.errstate(all="ignore"):
        sol = least_squares(model.residuals, P0, jac=model.jacobian, method="lm", x_scale="jac", max_nfev=300,
                            ftol=1e-10, xtol=1e-10, gtol=1e-10)
    return np.asarray(sol.x)


def fit_flown(throw: Throw, rotor_axis: FloatArray, rotor_inertia: float, *, saturation: float | None = None,
              drag: bool = True) -> FlownFit:
    """Fit one throw's flown body (module docstring).

    Parameters
    ----------
    throw : Throw
    rotor_axis : ndarray, shape (3,)
        Unit, sensor frame.
    rotor_inertia : float
        ``J_r``, kg m^2 (1 for a tensor in units of ``J_r``, as the calibration fits the device alone).
    saturation : float, optional
        The gyroscope's range, rad/s (else found from the data).
    drag : bool
        Fit a per-axis quadratic drag.

    Returns
    -------
    FlownFit

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.throw import fit_flown
    >>> from tumble.analysis.tensor.synthetic import ROTOR_AXIS, ROTOR_INERTIA, combine, example_object, synthetic_throw, true_device
    >>> flown = combine(true_device(), example_object())
    >>> fit = fit_flown(synthetic_throw(5, flown), np.array(ROTOR_AXIS), ROTOR_INERTIA)
    >>> err = np.linalg.eigvalsh(fit.inertia) / np.linalg.eigvalsh(flown.inertia) - 1
    >>> bool(np.abs(err).max() < 0.01), bool(np.abs(fit.center - flown.center).max() < 0.003)
    (True, True)
    """
    keep_all, _ = saturation_mask(throw.omega, saturation)
    win = find_flight(throw, keep_all)
    if win.reason:
        return FlownFit(win, win.reason)
    sl = slice(win.first, win.stop)
    t, data, keep = throw.t[sl], throw.omega[sl], keep_all[sl]
    rotor: RotorInput = rotor_input(throw.t, throw.rotor, win.rotor, rotor_inertia, rotor_axis)
    model = ThrowModel(t, data, keep, rotor, drag=drag)
    try:
        I0 = start_values(t, data, keep, model.h)
    except ValueError as error:
        return FlownFit(win, str(error))
    P0 = _scaled_start(model, cholesky_of(I0), np.mean(data[:5], axis=0), drag)
    P = _fit(model, P0)
    J = model.jacobian(P)
    res = model.residuals(P)
    per_sample = np.zeros(data.shape)
    per_sample[keep] = res
    cov, _ = effective_covariance(J, res, per_sample, [0, t.size])
    G = inertia_jacobian(P[:6])
    I = inertia_of(P[:6])
    pred = model.sensor(P[None])[0]
    rms = float(np.sqrt(np.mean(res ** 2)))
    verdict = judge(rms, noise_floor(data), float(np.sqrt(np.mean(data[keep] ** 2))))
    center = center_cov = accel_bias = None
    if throw.accel is not None:
        center, center_cov, accel_bias = center_of_mass(model, P, throw.accel[sl])
        center_cov = center_cov + _model_part(model, P, cov, throw.accel[sl])
    return FlownFit(win, "", P, cov, I, G @ cov[:6, :6] @ G.T, center, center_cov, accel_bias, t, data, pred, rms,
                    verdict)
