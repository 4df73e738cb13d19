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
"""

from __future__ import annotations

from collections.abc import Sequence

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


def _blocks(w: FloatArray, t: FloatArray, accel: FloatArray, cutoff: float) -> tuple[FloatArray, FloatArray]:
    """One throw's block rows ``(B, 3, 12)`` (the columns of ``r``, the bias, the air's force and its
    rate) and right-hand sides ``(B, 3)``, the model's reading smoothed as the firmware's (:func:`_smoothed`)."""
    bad = np.r_[0, np.cumsum(~np.all(np.abs(accel) < _RANGE, axis=1))]  # clipped samples up to each index
    W = skew(w)
    to_body = Rotation.from_quat(attitude_from_rates(t, w)).inv().as_matrix()  # world (the flight's start) to body
    mid = 0.5 * (t[0] + t[-1])
    air = np.concatenate([to_body, (t - mid)[:, None, None] * to_body], axis=2)
    Q = cumulative_trapezoid(_smoothed((W @ W).reshape(-1, 9), t, cutoff).reshape(-1, 3, 3), t, axis=0, initial=0.0)
    R = cumulative_trapezoid(air, t, axis=0, initial=0.0)
    F = cumulative_trapezoid(accel, t, axis=0, initial=0.0)
    w = _smoothed(w, t, cutoff)
    size = max(2, int(round(ACCEL_BLOCK / float(np.median(np.diff(t))))))
    a = np.arange(0, t.size - size, size)
    b = a + size
    a, b = a[bad[b + 1] == bad[a]], b[bad[b + 1] == bad[a]]  # blocks with no clipped sample
    rows = np.concatenate([skew(w[b] - w[a]) + Q[b] - Q[a], (t[b] - t[a])[:, None, None] * np.eye(3), R[b] - R[a]],
                          axis=2)
    return rows, F[b] - F[a]


def _smoothed(x: FloatArray, t: FloatArray, cutoff: float) -> FloatArray:
    """``x`` (samples in rows) through a second-order Butterworth low-pass at ``cutoff`` Hz
    (:func:`scipy.signal.butter`, run forward from rest at the first sample, at the median sample
    rate); unchanged for an infinite cutoff. The filter is linear and its gain 1 at 0 Hz, so
    smoothing the model's columns smooths its reading ``M r + b`` as the firmware smooths the
    sensor's."""
    if not np.isfinite(cutoff):
        return x
    from scipy.signal import butter, lfilter, lfilter_zi

    fs = 1.0 / float(np.median(np.diff(t)))
    b, a = butter(2, min(cutoff, 0.45 * fs), fs=fs)
    return lfilter(b, a, x, axis=0, zi=lfilter_zi(b, a)[:, None] * x[:1])[0]


def _design(rows: Sequence[FloatArray], rhs: Sequence[FloatArray]) -> tuple[FloatArray, FloatArray]:
    """The stacked blocks: columns ``r`` (3), the shared bias (3), then each throw's air (6)."""
    K = len(rows)
    A = np.zeros((sum(3 * len(R) for R in rows), 6 + 6 * K))
    at = 0
    for k, R in enumerate(rows):
        m = 3 * len(R)
        A[at:at + m, :6] = R[:, :, :6].reshape(m, 6)
        A[at:at + m, 6 + 6 * k:12 + 6 * k] = R[:, :, 6:].reshape(m, 6)
        at += m
    return A, np.concatenate([y.ravel() for y in rhs])


def _priors(K: int, s: float) -> FloatArray:
    """The prior rows' weights (module docstring) for residuals of std ``s``: none on ``r``, the
    bias's :data:`ACCEL_BIAS_STD`, each throw's air :data:`AIR_STD` and its rate over :data:`AIR_TIME`."""
    air = np.tile(np.r_[np.full(3, AIR_STD), np.full(3, AIR_STD / AIR_TIME)], K)
    return np.r_[np.zeros(3), s / np.r_[np.full(3, ACCEL_BIAS_STD), air]]


def _solve(A: FloatArray, y: FloatArray, weights: FloatArray) -> FloatArray:
    """Least squares with the prior rows ``weights_j x_j = 0``."""
    return np.linalg.lstsq(np.vstack([A, np.diag(weights)]), np.r_[y, np.zeros(weights.size)], rcond=None)[0]


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
    K = len(models)

    def cost(fc: float) -> float:
        A, y = _design(*zip(*[_blocks(w, m.t, a, fc) for w, m, a in zip(rates, models, accels)]))
        x = _solve(A, y, _priors(K, 0.01))
        return float(np.sum((A @ x - y) ** 2))

    if cutoff is None:
        cutoff = float(CUTOFFS[int(np.argmin([cost(fc) for fc in CUTOFFS]))])
    blocks = [_blocks(w, m.t, a, cutoff) for w, m, a in zip(rates, models, accels)]
    rows, rhs = [b[0] for b in blocks], [b[1] for b in blocks]
    for _ in range(2 if (covariance if trim is None else trim) else 1):  # the second pass without the jolts' blocks
        A, y = _design(rows, rhs)
        x = np.linalg.lstsq(A, y, rcond=None)[0]
        res = A @ x - y
        s = float(np.sqrt(res @ res / max(res.size - A.shape[1], 1)))
        weights = _priors(K, s)  # prior rows of residual std s
        x = _solve(A, y, weights)
        norms = np.linalg.norm((A @ x - y).reshape(-1, 3), axis=1)
        kept = np.split(norms <= JOLT_FACTOR * float(np.median(norms)), np.cumsum([len(r) for r in rows])[:-1])
        if all(k.all() for k in kept) or not all(k.sum() >= 4 for k in kept):
            break
        rows = [r[k] for r, k in zip(rows, kept)]
        rhs = [y_[k] for y_, k in zip(rhs, kept)]
    if not covariance:
        return -x[:3], np.zeros((3, 3)), x[3:6], cutoff
    res = A @ x - y
    counts = np.r_[0, np.cumsum([len(r) for r in rows])]
    s2 = float(res @ res) / max(res.size - 6, 1)
    normal = A.T @ A + np.diag(weights ** 2)
    cov = np.linalg.pinv(normal) * s2 * autocorrelation_time(res.reshape(-1, 3), list(counts))
    jack = _jackknife(A, y, weights, counts)
    if np.trace(jack[:3, :3]) > np.trace(cov[:3, :3]):
        cov = jack
    return -x[:3], 0.5 * (cov[:3, :3] + cov[:3, :3].T), x[3:6], cutoff


def _jackknife(A: FloatArray, y: FloatArray, weights: FloatArray, counts: FloatArray) -> FloatArray:
    """The delete-a-group jackknife covariance (Efron & Tibshirani, *An Introduction to the
    Bootstrap*, 1993, ch. 11) over :data:`JACKKNIFE_GROUPS` stretches of each throw's blocks:
    it holds what varies along a flight and from throw to throw (the rotor's imbalance, the
    firmware's smoothing at the rotor's switches) as the residuals' formula with their short
    autocorrelation does not."""
    groups = []
    for a, b in zip(counts[:-1], counts[1:]):
        edges = np.linspace(a, b, JACKKNIFE_GROUPS + 1).round().astype(int)
        groups += [(3 * lo, 3 * hi) for lo, hi in zip(edges[:-1], edges[1:]) if hi > lo]
    if len(groups) < 3:
        return np.zeros((A.shape[1], A.shape[1]))
    xs = np.array([_solve(A[np.r_[0:lo, hi:A.shape[0]]], y[np.r_[0:lo, hi:A.shape[0]]], weights) for lo, hi in groups])
    g = len(xs)
    d = xs - xs.mean(axis=0)
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
    d = model.steps(P) * 100.0
    G = np.empty((3, len(free)))
    for col, k in enumerate(free):
        e = np.zeros(P.size)
        e[k] = d[k]
        up, down = model.omega(np.array([P + e, P - e]))
        G[:, col] = (center_of_mass([model], [up], [accel], cutoff, covariance=False)[0]
                     - center_of_mass([model], [down], [accel], cutoff, covariance=False)[0]) / (2 * d[k])
    return G @ cov @ G.T


def sensor_columns(models: Sequence[ThrowModel], rates: Sequence[FloatArray], accels: Sequence[FloatArray],
                   cutoff: float, turn_std: float) -> FloatArray:
    """The centre's shifts for one standard uncertainty of each of the sensors' errors that all
    the throws of one device share (type B, JCGM 100:2008, sec. 4.3), as columns ``(3, 6)``
    (``cov = S S^T``): the accelerometer's three scale factors (:data:`ACCEL_SCALE_STD`) and
    the turn of the gyroscope's axes from the accelerometer's about each axis (``turn_std``,
    rad: the misalignment's antisymmetric part, which no throw can see, and which turns the
    rates the centre is solved with). Each by differences of the estimate (:func:`center_of_mass`
    with its jolts left out, at the firmware's ``cutoff``).

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
    def centre(rs: Sequence[FloatArray], fs: Sequence[FloatArray]) -> FloatArray:
        return center_of_mass(models, rs, fs, cutoff, covariance=False, trim=True)[0]

    c0 = centre(rates, accels)
    step = 1e-3
    cols = []
    for k in range(3):
        scale = np.ones(3)
        scale[k] += step
        cols.append((centre(rates, [a * scale for a in accels]) - c0) / step * ACCEL_SCALE_STD)
    for k in range(3):
        R = Rotation.from_rotvec(step * np.eye(3)[k]).as_matrix()
        cols.append((centre([w @ R.T for w in rates], accels) - c0) / step * float(turn_std))
    return np.array(cols).T
