"""The flown body's centre of mass from the accelerometer: :func:`center_of_mass`.

In free flight an accelerometer at ``r`` from the centre of mass reads ``f = w' x r + w x (w x r)
+ b_a`` (the acceleration of a point of a rigid body, Goldstein, Poole & Safko, *Classical
Mechanics*, 3rd ed., sec. 4.10, less gravity, which a falling accelerometer does not sense; ``b_a``
its bias). With ``w`` from the fitted model (not the noisy data) and the reading integrated over
blocks of :data:`ACCEL_BLOCK` s,

    ``integral f dt = (w_b - w_a) x r + integral w x (w x r) dt + b_a (t_b - t_a)``,

so that ``w'`` is never needed (it would need the rotor's ``h'``), the reading is linear in
``r``, the bias and the air's drag (:data:`AIR_STD`): linear least squares, the bias held near 0 by its prior uncertainty
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

The solve: each throw's rows touch the shared ``r`` and bias and its own air's six unknowns
only, so each throw's normal equations are reduced to the shared six by eliminating its own
(block-angular least squares, Bjorck, *Numerical Methods for Least Squares Problems*, 1996,
sec. 6.3) and the small systems solved with their diagonals scaled to 1: the work grows as the
number of throws, not its cube, and never calls a threaded dense least squares (on a loaded
2-core machine OpenBLAS's threads made a pooled fit's 80 solves take 40 s). The jackknife
reduces again only the throw a group belongs to; the sensors' columns are answers to other
right-hand sides of the same reduction (:func:`sensor_columns`); the rates' part refits each
perturbed throw, their attitudes integrated in one scan (:func:`_to_body`).
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache
from typing import NamedTuple

import numpy as np
from scipy.integrate import cumulative_trapezoid
from scipy.spatial.transform import Rotation

from ...typing import FloatArray
from ..fit.accelsynth import attitude_from_rates
from ..fit.uncertainty import autocorrelation_time
from .flight import skew
from .model import ThrowModel

__all__ = ["ACCEL_BIAS_STD", "ACCEL_BLOCK", "ACCEL_SCALE_STD", "AIR_STD", "JACKKNIFE_GROUPS", "CUTOFFS", "JOLT_FACTOR",
           "center_of_mass", "rate_part", "sensor_columns"]

#: The length of a block of the accelerometer's integrated reading, s.
ACCEL_BLOCK = 0.02
#: The cut-offs of the firmware's smoothing of the accelerometer tried, Hz (infinite: none): a flight
#: controller logs its low-passed accelerometer, which lags and rounds the reading where the rotor's
#: switches change ``w'`` fast; the model's reading is smoothed by the second-order low-pass
#: (:func:`_smoothed`) whose cut-off fits best.
CUTOFFS = (np.inf, 400.0, 300.0, 200.0, 150.0, 100.0, 70.0, 50.0)
#: The air's drag on the thrown body over its mass, m/s^2, a prior standard uncertainty per axis:
#: ``rho C_d A v^2 / 2m`` ~ 0.1-0.5 m/s^2 for a hand-sized body of 0.3-1 kg at 3-5 m/s (air
#: 1.2 kg/m^3, C_d ~ 1). It is fixed in the world and turns in the body frame as the body
#: tumbles, so it looks like a centripetal reading: fitted, a force linear in time in the
#: frame of the flight's start (the attitude integrated from the fitted rates).
AIR_STD = 0.3
#: The time over which the air's drag may change by its own size, s (the speed halves and turns
#: over a throw's apex).
AIR_TIME = 0.3
#: The stretches of each throw's blocks that the jackknife leaves out in turn (:func:`_jackknife`).
JACKKNIFE_GROUPS = 5
#: A block whose residual exceeds this many times the blocks' median is left out (a jolt).
JOLT_FACTOR = 4.0
#: The accelerometer's bias, m/s^2: a prior standard uncertainty (a flight controller's
#: accelerometer is levelled at rest, leaving about 0.1 m/s^2, an assumed size; the synthetic
#: devices' are within it). Without it a throw spinning about
#: one axis trades its centripetal reading, constant, for a bias (they are the same column).
ACCEL_BIAS_STD = 0.2
#: The accelerometer's scale factor per axis, a standard uncertainty (type B, relative): MEMS
#: data sheets state a sensitivity tolerance of 1-3 % (an assumed 1 %, as the synthetic devices
#: draw theirs). The centre of mass scales with the reading: 1 % of a flown body's 40 mm is 0.4 mm.
ACCEL_SCALE_STD = 0.01
_RANGE = 15.9 * 9.80665  # a reading this large may be clipped (the 16 g range)
_TINY = 1e-6  # the residuals' std, m/s^2 s, whose prior rows stand for none (the unweighted fit, kept full rank)


class _Geometry(NamedTuple):
    """One throw's pieces of its block rows that do not depend on the smoothing's cut-off."""
    t: FloatArray
    w: FloatArray
    ww: FloatArray  # (T, 9): w x (w x .) as a flat matrix per sample
    air: FloatArray  # (B, 3, 6): the air's columns integrated over each block
    rhs: FloatArray  # (B, 3): the reading integrated over each block
    a: np.ndarray
    b: np.ndarray


def _geometry(w: FloatArray, t: FloatArray, accel: FloatArray, to_body: FloatArray | None = None) -> _Geometry:
    """The blocks with no clipped sample and what :func:`_rows` needs of them at any cut-off;
    ``to_body`` (world, the flight's start, to body, ``(T, 3, 3)``) from ``w`` unless given."""
    bad = np.r_[0, np.cumsum(~np.all(np.abs(accel) < _RANGE, axis=1))]  # clipped samples up to each index
    W = skew(w)
    if to_body is None:
        to_body = _to_body(t, w[None])[0]
    mid = 0.5 * (t[0] + t[-1])
    air = np.concatenate([to_body, (t - mid)[:, None, None] * to_body], axis=2)
    size = max(2, int(round(ACCEL_BLOCK / float(np.median(np.diff(t))))))
    a = np.arange(0, t.size - size, size)
    b = a + size
    a, b = a[bad[b + 1] == bad[a]], b[bad[b + 1] == bad[a]]  # blocks with no clipped sample
    R = cumulative_trapezoid(air, t, axis=0, initial=0.0)
    F = cumulative_trapezoid(accel, t, axis=0, initial=0.0)
    return _Geometry(t, w, (W @ W).reshape(-1, 9), R[b] - R[a], F[b] - F[a], a, b)


def _to_body(t: FloatArray, ws: FloatArray) -> FloatArray:
    """World-to-body matrices ``(n, T, 3, 3)`` integrated from each of the rates ``ws`` ``(n, T, 3)``
    (:func:`~tumble.analysis.fit.accelsynth.attitude_from_rates`, the identity at ``t[0]``), all in one
    scan: the runs one after another, joined by steps of no time (no turn), each taken relative to its start."""
    n, T = ws.shape[:2]
    span = t[-1] - t[0]
    q = Rotation.from_quat(attitude_from_rates((t - t[0] + span * np.arange(n)[:, None]).ravel(), ws.reshape(-1, 3)))
    start = q[np.repeat(np.arange(n) * T, T)]
    return (q.inv() * start).as_matrix().reshape(n, T, 3, 3)


def _rows(g: _Geometry, cutoff: float) -> FloatArray:
    """One throw's block rows ``(B, 3, 12)`` (the columns of ``r``, the bias, the air's force and its
    rate), the model's reading smoothed as the firmware's (:func:`_smoothed`)."""
    t, a, b = g.t, g.a, g.b
    Q = cumulative_trapezoid(_smoothed(g.ww, t, cutoff).reshape(-1, 3, 3), t, axis=0, initial=0.0)
    w = _smoothed(g.w, t, cutoff)
    return np.concatenate([skew(w[b] - w[a]) + Q[b] - Q[a], (t[b] - t[a])[:, None, None] * np.eye(3), g.air], axis=2)


@lru_cache(maxsize=64)
def _filter(cutoff: float, fs: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    from scipy.signal import butter, lfilter_zi

    b, a = butter(2, min(cutoff, 0.45 * fs), fs=fs)
    return b, a, lfilter_zi(b, a)


def _smoothed(x: FloatArray, t: FloatArray, cutoff: float) -> FloatArray:
    """``x`` (samples in rows) through a second-order Butterworth low-pass at ``cutoff`` Hz
    (:func:`scipy.signal.butter`, run forward from rest at the first sample, at the median sample
    rate); unchanged for an infinite cutoff. The filter is linear and its gain 1 at 0 Hz, so
    smoothing the model's columns smooths its reading ``M r + b`` as the firmware smooths the
    sensor's."""
    if not np.isfinite(cutoff):
        return x
    from scipy.signal import lfilter

    b, a, zi = _filter(float(cutoff), 1.0 / float(np.median(np.diff(t))))
    return lfilter(b, a, x, axis=0, zi=zi[:, None] * x[:1])[0]


def _priors(K: int, s: float) -> FloatArray:
    """The prior rows' weights (module docstring) for residuals of std ``s``: none on ``r``, the
    bias's :data:`ACCEL_BIAS_STD`, each throw's air :data:`AIR_STD` and its rate over :data:`AIR_TIME`."""
    air = np.tile(np.r_[np.full(3, AIR_STD), np.full(3, AIR_STD / AIR_TIME)], K)
    return np.r_[np.zeros(3), s / np.r_[np.full(3, ACCEL_BIAS_STD), air]]


def _spd_solve(M: FloatArray, B: FloatArray) -> FloatArray:
    """``M^-1 B`` for a small symmetric positive (semi)definite ``M``, its diagonal scaled to 1."""
    d = np.sqrt(np.diag(M))
    d = 1.0 / np.where(d > 0, d, 1.0)
    S = M * np.outer(d, d)
    try:
        z = np.linalg.solve(S, B * (d if B.ndim == 1 else d[:, None]))
    except np.linalg.LinAlgError:
        z = np.linalg.pinv(S) @ (B * (d if B.ndim == 1 else d[:, None]))
    return z * (d if z.ndim == 1 else d[:, None])


def _reduce(rows: FloatArray, Y: FloatArray, weights: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """One throw's normal equations with its own unknowns (the air's six, prior ``weights``)
    eliminated (the Schur complement; block-angular least squares, Bjorck, *Numerical Methods
    for Least Squares Problems*, 1996, sec. 6.3): ``(C, c, X)``, its part of the shared six's
    matrix and right-hand sides, and ``X`` giving its own unknowns from the shared ones. ``Y``:
    right-hand sides ``(3 B, m)``."""
    A = rows.reshape(-1, 12)
    N, Nb = A.T @ A, A.T @ Y
    X = _spd_solve(N[6:, 6:] + np.diag(weights ** 2), np.hstack([N[6:, :6], Nb[6:]]))
    return N[:6, :6] - N[:6, 6:] @ X[:, :6], Nb[:6] - N[:6, 6:] @ X[:, 6:], X


def _combine(parts: Sequence[tuple[FloatArray, FloatArray, FloatArray]],
             weights: FloatArray) -> tuple[FloatArray, list[FloatArray], FloatArray]:
    """The shared unknowns ``(6, m)``, each throw's own ``(6, m)`` and the shared six's normal
    matrix (its inverse: their covariance over the residuals' variance)."""
    N = np.diag(weights[:6] ** 2) + sum(C for C, _, _ in parts)
    xs = _spd_solve(N, sum(c for _, c, _ in parts))
    return xs, [X[:, 6:] - X[:, :6] @ xs for _, _, X in parts], N


def _lsq(rows: Sequence[FloatArray], rhs: Sequence[FloatArray], weights: FloatArray,
         extra: Sequence[FloatArray] | None = None) -> tuple[FloatArray, list[FloatArray], FloatArray, list]:
    """Least squares of the stacked throws with the prior rows ``weights_j x_j = 0`` (columns ``r``,
    the shared bias, then each throw's air): ``(x, residuals, shared normal matrix, parts)``,
    ``x`` and the residuals (per throw, ``(B, 3)``) for ``rhs``; with ``extra`` (per throw
    ``(B, 3, m)``), ``x`` is ``(6 + 6 K, 1 + m)``, a column per right-hand side."""
    Ys = [y.reshape(-1, 1) if extra is None else np.hstack([y.reshape(-1, 1), e.reshape(len(y) * 3, -1)])
          for y, e in zip(rhs, extra if extra is not None else rhs)]
    parts = [_reduce(R, Y, weights[6 + 6 * k:12 + 6 * k]) for k, (R, Y) in enumerate(zip(rows, Ys))]
    xs, xl, N = _combine(parts, weights)
    res = [(R.reshape(-1, 12) @ np.r_[xs[:, 0], x[:, 0]] - y.ravel()).reshape(-1, 3) for R, y, x in zip(rows, rhs, xl)]
    x = np.vstack([xs, *xl])
    return (x[:, 0] if extra is None else x), res, N, parts


def _fit(geometries: Sequence[_Geometry], cutoff: float, trim: bool):
    """The trimmed least squares (module docstring): ``(x, residuals, N, parts, rows, rhs, weights,
    unweighted)``, the last the unweighted fit's residuals (flat) whose std sets the priors' weights."""
    K = len(geometries)
    rows, rhs = [_rows(g, cutoff) for g in geometries], [g.rhs for g in geometries]
    for last in ([False, True] if trim else [True]):  # the second pass without the jolts' blocks
        res = np.concatenate(_lsq(rows, rhs, _priors(K, _TINY))[1]).ravel()  # unweighted (a tiny ridge: rank-safe)
        s = float(np.sqrt(res @ res / max(res.size - (6 + 6 * K), 1)))
        weights = _priors(K, s)  # prior rows of residual std s
        x, res_k, N, parts = _lsq(rows, rhs, weights)
        norms = np.linalg.norm(np.concatenate(res_k), axis=1)
        kept = np.split(norms <= JOLT_FACTOR * float(np.median(norms)), np.cumsum([len(r) for r in rows])[:-1])
        if last or all(k.all() for k in kept) or not all(k.sum() >= 4 for k in kept):
            break
        rows = [r[k] for r, k in zip(rows, kept)]
        rhs = [y_[k] for y_, k in zip(rhs, kept)]
    return x, res_k, N, parts, rows, rhs, weights, res


def center_of_mass(models: Sequence[ThrowModel], rates: Sequence[FloatArray], accels: Sequence[FloatArray],
                   cutoff: float | None = None, covariance: bool = True,
                   trim: bool | None = None) -> tuple[FloatArray, FloatArray, FloatArray, float]:
    """The centre of mass shared by one or more throws (module docstring): ``(c, cov_c, b_a,
    cutoff)`` in m, m^2, m/s^2 and Hz, without the rates' part (:func:`rate_part`); the
    firmware's smoothing found (:data:`CUTOFFS`) unless given; without ``covariance`` no
    covariance (zeros), and one pass unless ``trim`` (the second, without the jolts' blocks: by
    default with the covariance), for the differences of :func:`rate_part` and :func:`sensor_columns`.

    Parameters
    ----------
    models : sequence of ThrowModel
        Each throw's fitted samples.
    rates : sequence of ndarray, shape (T_k, 3)
        Each throw's fitted rates at its model's samples (the body's, rotor tilt and gyroscope
        distortion applied), rad/s.
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
    >>> P = np.r_[cholesky_of(np.diag([2e-4, 3e-4, 4e-4])), 0.0, 0.0, 4e-3, np.zeros(8)]   # 10 rad/s about z
    >>> r = np.array([0.03, 0.0, 0.0])
    >>> w = m.omega(P[None])[0]
    >>> f = np.cross(w, np.cross(w, r)) + np.random.default_rng(0).normal(0.0, 0.1, (2000, 3))
    >>> c, cov, bias, cutoff = center_of_mass([m], [w], [f])
    >>> (c[:2] * 1e3).round(1).tolist()[0], bool(abs(c[1]) < 1e-4), bool(np.all(np.abs(bias) < 0.01))   # c = -r
    (-30.0, True, True)
    """
    geometries = [_geometry(w, m.t, a) for w, m, a in zip(rates, models, accels)]
    K = len(models)

    def cost(fc: float) -> float:
        res = _lsq([_rows(g, fc) for g in geometries], [g.rhs for g in geometries], _priors(K, 0.01))[1]
        return float(sum(np.sum(r ** 2) for r in res))

    if cutoff is None:
        cutoff = float(CUTOFFS[int(np.argmin([cost(fc) for fc in CUTOFFS]))])
    x, res_k, N, parts, rows, rhs, weights, _ = _fit(geometries, cutoff, covariance if trim is None else trim)
    if not covariance:
        return -x[:3], np.zeros((3, 3)), x[3:6], cutoff
    res = np.concatenate(res_k).ravel()
    counts = np.r_[0, np.cumsum([len(r) for r in rows])]
    s2 = float(res @ res) / max(res.size - 6, 1)
    cov = np.linalg.pinv(N)[:3, :3] * s2 * autocorrelation_time(res.reshape(-1, 3), list(counts))
    jack = _jackknife(rows, rhs, weights, parts)
    if np.trace(jack) > np.trace(cov):
        cov = jack
    return -x[:3], 0.5 * (cov + cov.T), x[3:6], cutoff


def _jackknife(rows: Sequence[FloatArray], rhs: Sequence[FloatArray], weights: FloatArray,
               parts: list) -> FloatArray:
    """The delete-a-group jackknife covariance of ``r`` (Efron & Tibshirani, *An Introduction to the
    Bootstrap*, 1993, ch. 11) over :data:`JACKKNIFE_GROUPS` stretches of each throw's blocks:
    it holds what varies along a flight and from throw to throw (the rotor's imbalance, the
    firmware's smoothing at the rotor's switches) as the residuals' formula with their short
    autocorrelation does not. A group's throw's part alone is made again (:func:`_reduce`)."""
    xs = []
    for k, (R, y) in enumerate(zip(rows, rhs)):
        edges = np.linspace(0, len(R), JACKKNIFE_GROUPS + 1).round().astype(int)
        for lo, hi in zip(edges[:-1], edges[1:]):
            if hi > lo:
                keep = np.r_[0:lo, hi:len(R)]
                others = parts[:k] + [_reduce(R[keep], y[keep].reshape(-1, 1), weights[6 + 6 * k:12 + 6 * k])] + parts[k + 1:]
                xs.append(_combine(others, weights)[0][:3, 0])
    if len(xs) < 3:
        return np.zeros((3, 3))
    g = len(xs)
    d = np.array(xs) - np.mean(xs, axis=0)
    return (g - 1) / g * d.T @ d


def rate_part(model: ThrowModel, P: FloatArray, cov: FloatArray, accel: FloatArray, free: Sequence[int],
              cutoff: float = np.inf) -> FloatArray:
    """The centre's covariance from one throw's fitted rates': ``G cov G^T``, ``G = dc/dP`` by central
    differences over the parameters ``free`` (indices into ``P``; ``cov`` theirs), at the firmware's ``cutoff``.

    Examples
    --------
    >>> from tumble.analysis.tensor.center import rate_part
    >>> callable(rate_part)
    True
    """
    if len(free) == 0:
        return np.zeros((3, 3))
    d = model.steps(P)[list(free)] * 100.0
    steps = np.zeros((len(free), P.size))
    steps[np.arange(len(free)), list(free)] = d
    ws = model.omega(np.vstack([P + steps, P - steps]))  # every rate changed up, then down
    c = np.array([-_fit([_geometry(w, model.t, accel, R)], cutoff, False)[0][:3]
                  for w, R in zip(ws, _to_body(model.t, ws))])
    G = (c[:len(free)] - c[len(free):]).T / (2 * d)
    return G @ cov @ G.T


def sensor_columns(models: Sequence[ThrowModel], rates: Sequence[FloatArray], accels: Sequence[FloatArray],
                   cutoff: float, turn_std: float) -> FloatArray:
    """The centre's shifts for one standard uncertainty of each of the sensors' errors that all
    the throws of one device share (type B, JCGM 100:2008, sec. 4.3), as columns ``(3, 6)``
    (``cov = S S^T``): the accelerometer's three scale factors (:data:`ACCEL_SCALE_STD`) and
    the turn of the gyroscope's axes from the accelerometer's about each axis (``turn_std``,
    rad: the misalignment's antisymmetric part, which no throw can see, and which turns the
    rates the centre is solved with). Each the linear response of the estimate (:func:`center_of_mass`
    with its jolts left out, at the firmware's ``cutoff``) through its one factorisation: a scale
    factor multiplies one component of the reading, on which the least squares is linear; turning
    the rates by ``R`` turns every column of the model (the cross products, the attitude, the
    air's force) so that ``r(R) = R r(R^T f)`` (the bias's and air's priors are isotropic), whose
    derivative at ``R = 1`` is ``e_k x r`` plus the answer to the reading turned, ``-e_k x f``.

    Why: on 100 realistic objects (benchmarks/tensor_coverage.py) the centre's 95 % intervals
    held 80 %; the errors were common to the objects of one device, its accelerometer's scale
    factors (the centre along the flown body's long axis) and its gyroscope's turn (a 0.008 rad
    turn moved a 45 mm centre by 0.4 mm across).

    Examples
    --------
    A tumbling body, the accelerometer 3 cm from its centre along x: a 1 % scale of the x reading
    moves the centre by about 1 % of 3 cm along x, a turn of 0.005 rad about z moves it along y:

    >>> import numpy as np
    >>> from tumble.analysis.tensor.center import sensor_columns
    >>> from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input
    >>> t = np.arange(2000) / 4000.0
    >>> m = ThrowModel(t, np.zeros((2000, 3)), np.ones((2000, 3), bool), rotor_input(t, np.zeros(2000), 0, 1e-6, [0, 0, 1]))
    >>> P = np.r_[cholesky_of(np.diag([2e-4, 3e-4, 4e-4])), 3e-3, 2e-3, 4e-3, np.zeros(8)]
    >>> w = m.omega(P[None])[0]
    >>> f = np.cross(w, np.cross(w, [0.03, 0.0, 0.0]))
    >>> S = sensor_columns([m], [w], [f], np.inf, 0.005)
    >>> S.shape, round(float(S[0, 0]) * 1e3, 2), round(float(S[1, 5]) * 1e3, 2)   # mm
    ((3, 6), -0.34, -0.26)
    """
    geometries = [_geometry(w, m.t, a) for w, m, a in zip(rates, models, accels)]
    x, _, _, _, rows, rhs, weights, unweighted = _fit(geometries, cutoff, True)
    eye = np.eye(3)
    # the reading's change: its k-th component (scaled), or -e_k x f (turned: r(R) = R r(R^T f))
    dy = [np.stack([y * eye[k] for k in range(3)] + [np.cross(y, eye[k]) for k in range(3)], axis=2) for y in rhs]
    h = 1e-4  # the priors' weights scale with the residuals' std s: dr/ds by a central difference
    up, down = (_lsq(rows, rhs, weights * (1 + e))[0][:3] for e in (h, -h))
    ds_s = -unweighted @ np.concatenate([d.reshape(-1, 6) for d in dy]) / (unweighted @ unweighted)  # ds/s (res: A x - y)
    dx = _lsq(rows, rhs, weights, dy)[0][:3, 1:] + np.outer((up - down) / (2 * h), ds_s)
    scale = -dx[:, :3] * ACCEL_SCALE_STD
    turn = (np.cross(eye, -x[:3]) - dx[:, 3:].T).T * float(turn_std)
    return np.hstack([scale, turn])
