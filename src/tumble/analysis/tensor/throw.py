"""One throw fitted: the flown body's tensor and centre of mass with their covariances.

1. The flight's bounds are found (:func:`~tumble.analysis.tensor.flight.find_flight`), the
   gyroscope's samples at its rail left out (:func:`tumble.analysis.fit.single.saturation_mask`),
   and the samples averaged over 1 ms (:func:`~tumble.analysis.tensor.model.sample_means`).
2. **Starting values** by an equation-error regression on the integrated gyrostat equation:
   over blocks ``[t_a, t_b]`` of :data:`BLOCK` s, ``I (w_b - w_a) + integral (w x I w +
   w x h) dt + h_b - h_a = 0`` (Euler's equation of the gyrostat integrated in time; Hughes,
   *Spacecraft Attitude Dynamics*, 1986, ch. 7) is linear in the six entries of ``I``, with the
   integrals by the trapezoidal rule on the samples. It needs no derivative, but the measured
   ``w`` inside the cross products carries noise (an errors-in-variables bias): good enough to
   start from.
3. The **output-error fit** of :class:`~tumble.analysis.tensor.model.ThrowModel` by
   :func:`scipy.optimize.least_squares` over the real sample times: Levenberg-Marquardt
   (MINPACK's, ``x_scale="jac"``; the model needs no bounds but the drags', held by an active
   set). Why not the trust-region methods: they take an SVD of the (samples x 17) Jacobian at
   every step, which LAPACK's threads made 0.2-0.4 s on a loaded two-core machine (MINPACK's
   own QR: 2 ms).
4. **The window is what the free motion explains** (:func:`fit_flown`): fitted from
   :data:`PROVISIONAL` after the sensed release to the log's end (or grown from one possible
   catch to the next while the residuals do not jump by :data:`CATCH_JUMP`); its start where the
   model integrated back in time leaves the data (the fingers' touch, :func:`_release`).
5. **Covariance** (the joint fit of one throw, :func:`~tumble.analysis.tensor.joint.fit_joint`):
   ``(J^T J)^-1 s^2 tau`` with the residuals' autocorrelation time ``tau``, plus the sensors'
   stated uncertainties through the fit's linear response, propagated to the tensor's entries
   (the law of propagation of uncertainty, JCGM 100:2008, sec. 5.1).
6. **Centre of mass** from the accelerometer (:mod:`~tumble.analysis.tensor.center`), with the
   fitted rates' own uncertainty propagated.
"""

from __future__ import annotations

import warnings

from dataclasses import dataclass, replace

import numpy as np
from scipy.integrate import cumulative_trapezoid

from ..._html import fmt, headline_html, headline_repr
from ...typing import FloatArray
from ..fit.adequacy import Adequacy, judge
from ..fit.single import saturation_mask
from ..fit.uncertainty import autocorrelation_time, noise_floor
from .throwlog import Throw
from .estimate import tensor_of
from .center import center_of_mass, rate_part
from .flight import (END_MARGIN, MIN_FLIGHT, SPAN, START_MARGIN, MoreThrowsWarning, Window, catch_candidates, find_flight,
                     spin_up_after)
from .joint import JointModel, fit_joint
from .sensors import SensorErrors
from .model import NONNEGATIVE, RotorInput, ThrowModel, cholesky_of, inertia_of, rotor_input, sample_means
from .solve import fit_held

__all__ = ["BLOCK", "MAX_GAP", "PROVISIONAL", "RESIDUAL_LIMIT", "FlownFit", "fit_flown", "start_values"]

#: The length of a block of the starting regression, s (200 samples at 4 kHz): over 10 ms blocks the
#: change of a weakly tumbling throw's rates is little above their noise, and the regression's tensor
#: came out 20-70 % low (errors in variables); over 50 ms, within 8 % on the coverage trials.
BLOCK = 0.05
#: The factors tried on the starting regression's tensor (:func:`_scaled_start`).
START_SCALES = np.geomspace(0.2, 5.0, 33)
#: The provisional fit starts this long after the sensed release, s: past the fingers' touch
#: (10-20 ms on the real device's logs), which the residuals then locate (:func:`_release`).
PROVISIONAL = 0.03
#: A fit whose residuals' RMS exceeds this factor times the gyroscope's noise (measured from the
#: throw's 1 ms means) does not describe the flight: on realistic throws the joint fit leaves
#: 1.3-2.5 times it (the rotor's vibration at its frequency, the eRPM's steps), a rate logged in
#: deg/s and read as rad/s, a wrong rotor axis or a body that is not rigid far more.
RESIDUAL_LIMIT = 4.0
#: The longest gap between samples in a flight that the fit bridges, s (in steps of at most
#: :data:`~tumble.analysis.tensor.model.MAX_STEP` sample intervals): the rotor's log has the same
#: gap, and a spin-up changes its speed 5-fold in 40 ms.
MAX_GAP = 0.01
#: A window grown past a possible catch whose residuals' RMS grows more than this factor (and past
#: the noise's limit) ends at it: the hand's stop multiplies the residuals many-fold, where the
#: model's imperfections (a gyroscope's distortion at high rates) raise them a little at a time.
CATCH_JUMP = 4.0
#: Going back from the provisional start, the fingers' touch begins where the residuals' running
#: RMS exceeds this factor times the fit's (:func:`_release`).
START_LIMIT = 3.0


@dataclass(frozen=True)
class FlownFit:
    """One throw's fit of the flown body (module docstring); ``reason`` non-empty when there is none.

    Examples
    --------
    >>> from tumble.analysis.tensor.throw import FlownFit
    >>> sorted(FlownFit.__dataclass_fields__)[:4]
    ['P', 'accel', 'accel_bias', 'adequacy']
    """

    HEADLINE = (("reason", "verdict", ""), ("residual_rms", "residual RMS", "rad/s"), ("noise", "noise", "rad/s"),
                ("center", "centre of mass", "m"))
    __repr__ = headline_repr
    _repr_html_ = headline_html

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
    model: ThrowModel | None = None
    accel: FloatArray | None = None
    inertia_cov_sensor: FloatArray | None = None
    noise: float = float("nan")
    center_cov_rates: FloatArray | None = None
    tau: float = float("nan")


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
    size = max(8, int(round(BLOCK / float(np.median(np.diff(t))))))
    blocks = _blocks(np.all(keep, axis=1), size)
    for a, b in blocks:
        dw = w[b] - w[a]
        rows.append(np.column_stack([basis[j] @ dw + Q[j][b] - Q[j][a] for j in range(6)]))
        rhs.append(-(Qh[b] - Qh[a] + h[b] - h[a]))
    if len(rows) < 3:
        clipped = int(np.count_nonzero(~np.all(keep, axis=1)))
        raise ValueError(f"the flight holds {len(rows)} stretch(es) of {1e3 * BLOCK:g} ms within the gyroscope's range, "
                         f"too few to start the fit from (3 or more: {t[-1] - t[0]:.3g} s fitted, {clipped} of {t.size} "
                         "samples at the gyroscope's rail)")
    v = np.linalg.lstsq(np.vstack(rows), np.concatenate(rhs), rcond=None)[0]
    return tensor_of(v)


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
    """The least-squares optimum with the drags never negative (:func:`~tumble.analysis.tensor.solve.fit_held`)."""
    return fit_held(model, P0, np.ones(model.n, bool), NONNEGATIVE[NONNEGATIVE < model.n])[0]


def _rms(model: ThrowModel, P: FloatArray) -> float:
    """The residuals' RMS, rad/s (infinite for a model with no motion)."""
    with np.errstate(all="ignore"):
        rms = float(np.sqrt(np.mean(model.residuals(P) ** 2)))
    return rms if np.isfinite(rms) else float("inf")


def _solve(throw: Throw, keep_all: np.ndarray, rotor: RotorInput, first: int, stop: int, drag: bool,
           P0: FloatArray | None = None) -> tuple[ThrowModel, FloatArray] | str:
    """The model of samples ``[first, stop)`` fitted, from ``P0`` (its ``L`` at ``first``) or from the starting
    regression; a reason when it cannot start."""
    sl = slice(first, stop)
    t, data, keep = sample_means(throw.t[sl], throw.omega[sl], keep=keep_all[sl])
    model = ThrowModel(t, data, keep, rotor, drag=drag)
    if P0 is None:
        try:
            I0 = start_values(t, data, keep, model.h)
        except ValueError as error:
            return str(error)
        P0 = _scaled_start(model, cholesky_of(I0), np.mean(data[:5], axis=0), drag)
    return model, _fit(model, P0)


def _momentum_at(throw: Throw, rotor: RotorInput, model: ThrowModel, P: FloatArray, first: int, to: int) -> FloatArray:
    """The fitted model's rates at samples ``to .. first`` (``to <= first``), integrated backward in time from
    ``first`` (the gyrostat's equations run either way), in time order, bias included."""
    idx = np.arange(first, to - 1, -1)
    back = ThrowModel(throw.t[idx], throw.omega[idx], np.ones((idx.size, 3), bool), rotor, drag=model.drag)
    return back.sensor(P[None])[0][::-1]


def _release(throw: Throw, keep_all: np.ndarray, rotor: RotorInput, model: ThrowModel, P: FloatArray,
             search: int, first: int, limit: float) -> int:
    """The first sample after the fingers' touch: going back from ``first`` (the fitted window's start) to
    ``search`` (the sensed release), the model's free motion integrated backward meets the data within
    ``limit`` (rad/s, per axis, RMS over :data:`~tumble.analysis.tensor.flight.SPAN`); the first sample after the
    last one beyond it, plus :data:`~tumble.analysis.tensor.flight.START_MARGIN`."""
    if first <= search:
        return first
    pred = _momentum_at(throw, rotor, model, P, first, search)
    data, keep = throw.omega[search:first + 1], keep_all[search:first + 1]
    sq = np.where(keep, pred - data, 0.0) ** 2
    n = max(1, int(round(SPAN / float(np.median(np.diff(throw.t[search:first + 2]))))))
    run = np.convolve(sq.sum(axis=1), np.ones(n) / n, mode="same") / np.maximum(
        np.convolve(keep.sum(axis=1).astype(float), np.ones(n) / n, mode="same"), 1e-12)
    bad = np.flatnonzero(np.sqrt(run) > limit)
    if bad.size == 0:
        return search
    k = search + int(bad[-1]) + 1
    return min(int(np.searchsorted(throw.t, throw.t[k] + START_MARGIN)), first)


def fit_flown(throw: Throw, rotor_axis: FloatArray, rotor_inertia: float, *, saturation: float | None = None,
              drag: bool = True, errors: SensorErrors | None = None, gyro: FloatArray | None = None) -> FlownFit:
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
        Fit a per-axis quadratic drag (the joint fits need it).
    errors : SensorErrors, optional
        The sensors' stated uncertainties, propagated into the covariance (type B); none by default.
    gyro : ndarray, shape (3, 3), optional
        The gyroscope's calibrated response, ``omega_read = gyro @ omega``
        (:func:`~tumble.analysis.tensor.sensors.gyro_matrix` of the device's ``gyro_distortion``):
        the readings are corrected by its inverse once the samples at the rail are known, and
        the fit holds the distortion there with the calibration's uncertainty (``errors.distortion``).

    Returns
    -------
    FlownFit

    Examples
    --------
    A perfect device's throw gives the flown body within half a per cent; a real gyroscope's scale
    and misalignment shift a lone throw's tensor by a few per cent, within its stated uncertainty
    (the joint fit of several throws removes them: :mod:`~tumble.analysis.tensor.pool`):

    >>> import numpy as np
    >>> from tumble.analysis.tensor.firmware import Imperfections
    >>> from tumble.analysis.tensor.sensors import SensorErrors
    >>> from tumble.analysis.tensor.throw import fit_flown
    >>> from tumble.analysis.tensor.synthetic import ROTOR_AXIS, ROTOR_INERTIA, combine, example_object, synthetic_throw, true_device
    >>> flown = combine(true_device(), example_object())
    >>> perfect = synthetic_throw(5, flown, imperfections=Imperfections.none(ROTOR_AXIS))
    >>> fit = fit_flown(perfect, np.array(ROTOR_AXIS), ROTOR_INERTIA)
    >>> err = np.linalg.eigvalsh(fit.inertia) / np.linalg.eigvalsh(flown.inertia) - 1
    >>> bool(np.abs(err).max() < 0.005), bool(np.abs(fit.center - flown.center).max() < 0.002)
    (True, True)
    >>> real = fit_flown(synthetic_throw(5, flown), np.array(ROTOR_AXIS), ROTOR_INERTIA, errors=SensorErrors())
    >>> std = np.sqrt(np.diag(real.inertia_cov)[:3])
    >>> bool(np.all(np.abs(real.inertia.diagonal() - flown.inertia.diagonal()) < 3 * std))
    True
    """
    keep_all, _ = saturation_mask(throw.omega, saturation)  # the rail: on the readings as logged
    if gyro is not None:
        throw = replace(throw, omega=throw.omega @ np.linalg.inv(np.asarray(gyro, float)).T)
    win = find_flight(throw, keep_all)
    if win.reason:
        return FlownFit(win, win.reason)
    t_all = throw.t
    flown = throw.omega[win.first:win.stop]
    if flown.shape[0] > 1 and np.all(flown == flown[0]):
        # the rotor's spin-up in the flight turns the body (its momentum is taken from the body's), so a gyroscope
        # whose every sample is the same is not reading: a stuck sensor, or a log of one repeated value. Fitted, it
        # gave "not a body's tensor" after seconds of Levenberg-Marquardt's iterations (moments -1.6e12 kg m^2)
        reading = ", ".join(fmt(float(v)) for v in flown[0])
        return FlownFit(win, f"the gyroscope reads the same [{reading}] rad/s on all {flown.shape[0]} "
                             "samples of the flight, while the rotor spins up in it: a stuck gyroscope, or a log "
                             "that repeats one reading")
    gaps = np.flatnonzero(np.diff(t_all[win.first:win.stop]) > MAX_GAP)
    if gaps.size:
        k = win.first + int(gaps[0])
        return FlownFit(win, f"a gap of {1e3 * (t_all[k + 1] - t_all[k]):.3g} ms in the log at t = {t_all[k]:.4g} s, in "
                             f"the flight: longer than the fit bridges ({1e3 * MAX_GAP:g} ms; the rotor's speed in it is "
                             "unknown)")
    rotor: RotorInput = rotor_input(t_all, throw.rotor, win.rotor, rotor_inertia, rotor_axis)
    noise = noise_floor(sample_means(throw.t[win.first:win.stop], throw.omega[win.first:win.stop])[1])
    first = int(np.searchsorted(t_all, win.t_release + PROVISIONAL))
    # the end: the log's, or a catch's: the window grown from one possible catch to the next while the free
    # motion goes on explaining it
    stops = sorted({int(np.searchsorted(t_all, t_all[c] - END_MARGIN))
                    for c in catch_candidates(t_all, throw.omega, win.rotor, keep_all)} | {win.stop})
    stops = [k for k in stops if t_all[k - 1] - t_all[first] >= MIN_FLIGHT]
    if not stops:
        return FlownFit(win, f"the flight found lasts less than the {MIN_FLIGHT} s fitted")
    found = None
    for stop in stops:
        solved = _solve(throw, keep_all, rotor, first, stop, drag, None if found is None else found[2])
        if isinstance(solved, str):
            if found is None:
                return FlownFit(win, solved)
            break
        if found is not None:
            limit = max(RESIDUAL_LIMIT * noise, CATCH_JUMP * _rms(found[1], found[2]))
            if _rms(*solved) > limit:  # a catch, or an optimum the warm start missed: from the regression too
                fresh = _solve(throw, keep_all, rotor, first, stop, drag)
                if isinstance(fresh, str) or _rms(*fresh) > limit:
                    break
                solved = fresh
        found = (stop, *solved)
    assert found is not None
    stop, model, P = found
    # the start: where the free motion, integrated back, meets the data (the fingers' touch left out)
    # the limit for single samples: the fit's misfit beyond the means' noise, plus the samples' own noise
    misfit = np.sqrt(max(_rms(model, P) ** 2 - noise ** 2, 0.0) + noise_floor(throw.omega[first:stop]) ** 2)
    start = _release(throw, keep_all, rotor, model, P, win.first, first, START_LIMIT * misfit)
    if start < first:
        w = _momentum_at(throw, rotor, model, P, first, start)[0] - P[9:12]
        P = P.copy()
        P[6:9] = inertia_of(P[:6]) @ w + rotor.h(t_all[start])
        model, P = _solve(throw, keep_all, rotor, start, stop, drag, P)  # type: ignore[misc]
    win = replace(win, first=start, stop=stop, t_release=float(t_all[start]), t_end=float(t_all[stop - 1]))
    again = spin_up_after(throw.rotor, stop)
    if again is not None:  # a second throw in one log was dropped without a word (a walkthrough, 2026-12-03)
        warnings.warn(f"{throw.input or 'a throw'}: the rotor spins up again at t = {t_all[again]:.4g} s, after this throw's "
                      f"flight (to {win.t_end:.4g} s): a second throw in one log? Only the first is fitted: give each "
                      "throw a file of its own", MoreThrowsWarning, stacklevel=2)
    return _finish(throw, win, model, P, errors)


def _finish(throw: Throw, win: Window, model: ThrowModel, P: FloatArray, errors: SensorErrors | None) -> FlownFit:
    """The fitted throw's uncertainties (through the joint fit of one throw), verdict and centre of mass."""
    res = model.residuals(P)
    moments = np.linalg.eigvalsh(inertia_of(P[:6]))
    if not (np.all(np.isfinite(res)) and moments[0] > 1e-6 * moments[2]):
        return FlownFit(win, "the fit found no rigid body's motion that explains the flight (its tensor came out "
                             "degenerate): the rotor's axis or the sign of its speed may be wrong")
    if errors is not None and errors.calibrated:  # the readings corrected: the distortion held at 0, its std carried
        one = JointModel([model], sensor=True)
        held = np.zeros(one.n, bool)
        held[6:one.base] = True
        single = fit_joint(one, np.r_[P[:6], np.zeros(one.base - 6), P[6:]], errors, held, optimize=False)
        own = np.r_[np.arange(6), np.arange(one.base, one.n)]
        single = replace(single, P=single.P[own], cov_P=single.cov_P[np.ix_(own, own)])
    else:
        single = fit_joint(JointModel([model]), P, errors, optimize=False)
    P = single.P
    data, keep = model.data, model.keep
    res = model.residuals(P)
    rms = float(np.sqrt(np.mean(res ** 2)))
    noise = noise_floor(data)
    verdict = judge(rms, noise, float(np.sqrt(np.mean(data[keep] ** 2))))
    center = center_cov = accel_bias = rates = None
    accel = None if throw.accel is None else sample_means(throw.t[win.first:win.stop], throw.accel[win.first:win.stop])[1]
    if accel is not None:
        center, center_cov, accel_bias, cutoff = center_of_mass([model], [model.omega(P[None])[0]], [accel])
        free = [k for k in range(model.n) if single.cov_P[k, k] > 0]
        rates = rate_part(model, P, single.cov_P[np.ix_(free, free)], accel, free, cutoff)
        center_cov = center_cov + rates
    per_sample = np.zeros(data.shape)
    per_sample[keep] = res
    tau = autocorrelation_time(per_sample, [0, data.shape[0]])
    return FlownFit(win, "", P, single.cov_P, single.inertia, single.inertia_cov, center, center_cov, accel_bias,
                    model.t, data, model.sensor(P[None])[0], rms, verdict, model, accel, single.inertia_cov_sensor, noise,
                    rates, tau)
