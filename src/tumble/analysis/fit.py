"""The inverse problem: inertia ratios from a measured tumble (a gyroscope's angular velocity).

A torque-free rigid body's angular velocity in its principal frame follows Euler's equations,
solved exactly by Jacobi's elliptic functions (Landau & Lifshitz, *Mechanics*, sec. 37;
:mod:`tumble.dynamics.exact`). It depends on the moments only through their ratios, so the
scale is fixed by ``I3 = 1`` and the unknowns are

- the ratios ``I1/I3`` and ``I2/I3``;
- the angular velocity ``omega0`` at the first sample time, principal frame, rad/s;
- the rotation ``R`` from the sensor's axes to the principal axes (a rotation vector, rad), so
  that ``omega_principal = R @ omega_sensor``; or the identity when the sensor is aligned;
- the sensor's constant bias ``b`` (rad/s, sensor axes), optional.

The model of a sample is ``omega_sensor(t) = R^T omega_principal(t - t[0]) + b``; the
parameters minimise the sum of squared residuals over all samples and axes
(:func:`scipy.optimize.least_squares`, trust region reflective, the Jacobian by forward
differences evaluated for all parameters at once with the vectorised exact solution
:func:`tumble.dynamics.exact_batch.free_rotation_batch`).

Parametrisation of the ratios. Every body has ``I1 <= I2 <= I3`` and ``I1 + I2 >= I3`` (the
triangle inequality), so ``(x, y) = (I1/I3, I2/I3)`` lies in the triangle ``1/2 <= y <= 1``,
``1 - y <= x <= y``. The optimiser works on two unconstrained numbers ``(u, v)``::

    y = (1 + s(v)) / 2,        x = 1 - y + (2 y - 1) s(u),        s = the logistic function,

which map the plane onto the triangle's interior, so the ratios stay ascending and physical
without bounds; the ordering of the sensor's axes is absorbed by the fitted rotation. The
uncertainties are reported for ``I1/I3`` and ``I2/I3`` themselves: the Jacobian with respect
to the internal parameters is carried to the physical ones by the chain rule at the optimum.

Starting values, without a user guess:

1. Principal axes. Along a torque-free motion two quadratic forms of omega are constant,
   ``omega^T J omega`` (twice the energy) and ``omega^T J^2 omega`` (``|L|^2``), with ``J`` the
   inertia tensor in the sensor frame; both, and every combination, share ``J``'s eigenvectors.
   The null space of the samples' quadratic monomials ``[wx^2, wy^2, wz^2, 2 wx wy, 2 wx wz,
   2 wy wz, -1]`` (its two smallest right singular vectors) gives two such forms; their joint
   eigenvectors are the principal axes in the sensor frame.
2. Ratios. In the principal frame ``d(omega_i^2)/dt = 2 omega_1 omega_2 omega_3 (I_j - I_k) / I_i``
   (Euler's equations, ``(i, j, k)`` cyclic), so the samples' ``omega_i^2`` lie on a line with
   direction ``d = ((I2 - I3)/I1, (I3 - I1)/I2, (I1 - I2)/I3)``, which fixes both ratios. The
   line's direction (the first principal component of the squared components) is matched
   against a grid over the triangle, for each of the six labellings of the axes.
3. The best few candidates are ranked by the exact model on a short first window, and the
   best is fitted on windows that double in length up to the whole record (so that a small
   error in the period does not wrap the phase on a long record).

The covariance is ``(J^T J)^-1 s^2`` with ``s^2 = SSR / (m - n)`` (``m`` residuals, ``n``
parameters): Press et al., *Numerical Recipes*, 3rd ed., sec. 15.5. It holds for independent
noise of equal variance on every axis; correlated or non-Gaussian noise, or a model error
(a torque, a flexible body), makes it optimistic.

From periods instead of a gyroscope record: :func:`tumble.analysis.periods_consistent`
(:mod:`tumble.analysis.period_inversion`).

Refused with a one-line ``ValueError``: fewer than 20 samples, non-finite values, times not
strictly increasing, wrong shapes, a steady spin (omega constant within the noise: the ratios
do not enter the data) and a fit whose Jacobian is rank deficient (e.g. a symmetric body, whose
sensor rotation about the symmetry axis is undetermined).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from ..dynamics.exact_batch import free_rotation_batch

__all__ = ["RotationFit", "fit_rotation"]

#: Fewest samples accepted.
MIN_SAMPLES = 20
#: A Jacobian whose smallest singular value, columns scaled to unit norm, is below this is
#: rank deficient (the parameters it combines are not determined by the data).
RANK_TOL = 1e-8
#: The four rotations by 0 or pi about a principal axis map a torque-free motion onto itself:
#: the sensor rotation is reported as the one of the four with the smallest angle.
_D2 = (np.eye(3), np.diag([1.0, -1.0, -1.0]), np.diag([-1.0, 1.0, -1.0]), np.diag([-1.0, -1.0, 1.0]))


@dataclass(frozen=True)
class RotationFit:
    """A torque-free motion fitted to angular-velocity samples (:func:`fit_rotation`).

    Attributes
    ----------
    ratios : ndarray, shape (2,)
        ``I1/I3``, ``I2/I3`` (dimensionless, ascending, ``I3`` the largest moment).
    ratios_std : ndarray, shape (2,)
        Their standard uncertainties.
    omega0 : ndarray, shape (3,)
        Angular velocity at ``t[0]``, principal frame, rad/s.
    omega0_std : ndarray, shape (3,)
        Its standard uncertainties, rad/s.
    sensor_rotation : scipy Rotation
        Sensor axes to principal axes: ``omega_principal = sensor_rotation.apply(omega_sensor)``.
    rotvec_std : ndarray, shape (3,) or None
        Standard uncertainties of its rotation vector, rad (None when fixed to the identity).
    bias : ndarray, shape (3,)
        The sensor's constant bias, sensor axes, rad/s (zeros when not fitted).
    bias_std : ndarray, shape (3,) or None
        Its standard uncertainties (None when not fitted).
    residual_rms : float
        Root mean square of the residuals over all samples and axes, rad/s.
    samples : int
        Number of time samples.
    t : ndarray, shape (n,)
        The sample times, s.
    omega_model : ndarray, shape (n, 3)
        The fitted model at the sample times, sensor axes, bias included, rad/s.
    covariance : ndarray
        Covariance of the fitted parameters in the order of :attr:`parameter_names`.
    parameter_names : tuple of str
        The parameters' names (``I1/I3``, ``I2/I3``, ``omega0_1..3``, ``rotvec_x..z``, ``bias_x..z``).
    iterations : int
        Function evaluations of the final least-squares run.
    """

    ratios: np.ndarray
    ratios_std: np.ndarray
    omega0: np.ndarray
    omega0_std: np.ndarray
    sensor_rotation: Rotation
    rotvec_std: np.ndarray | None
    bias: np.ndarray
    bias_std: np.ndarray | None
    residual_rms: float
    samples: int
    t: np.ndarray = field(repr=False)
    omega_model: np.ndarray = field(repr=False)
    covariance: np.ndarray = field(repr=False)
    parameter_names: tuple = ()
    iterations: int = 0

    @property
    def moments(self) -> np.ndarray:
        """Principal moments scaled so that ``I3 = 1`` (dimensionless), ascending."""
        return np.array([self.ratios[0], self.ratios[1], 1.0])

    def summary(self) -> dict:
        """The fitted values and their uncertainties as plain JSON-ready numbers (SI units)."""
        def listed(x):
            return None if x is None else [float(v) for v in np.ravel(x)]

        return {
            "I1_over_I3": float(self.ratios[0]),
            "I2_over_I3": float(self.ratios[1]),
            "I1_over_I3_std": float(self.ratios_std[0]),
            "I2_over_I3_std": float(self.ratios_std[1]),
            "ratios_correlation": float(self.covariance[0, 1] / (self.ratios_std[0] * self.ratios_std[1])),
            "omega0": listed(self.omega0),
            "omega0_std": listed(self.omega0_std),
            "t0": float(self.t[0]),
            "sensor_rotation_rotvec": listed(self.sensor_rotation.as_rotvec()),
            "sensor_rotation_rotvec_std": listed(self.rotvec_std),
            "sensor_rotation_matrix": [listed(row) for row in self.sensor_rotation.as_matrix()],
            "bias": listed(self.bias),
            "bias_std": listed(self.bias_std),
            "residual_rms": float(self.residual_rms),
            "samples": int(self.samples),
            "parameters": list(self.parameter_names),
            "units": {"ratios": "dimensionless", "omega0": "rad/s", "rotvec": "rad", "bias": "rad/s",
                      "residual_rms": "rad/s", "t0": "s", "ratios_correlation": "dimensionless"},
        }


def _logistic(z):
    return 0.5 * (1.0 + np.tanh(0.5 * z))


def _logit(p):
    p = np.clip(p, 1e-12, 1 - 1e-12)
    return np.log(p / (1.0 - p))


def _ratios(u, v):
    """Internal ``(u, v)`` -> ``(I1/I3, I2/I3)``, any shapes (broadcast); ``u, v`` are clipped
    to +-30 so that ``I1`` stays positive (logistic(-30) ~ 1e-13)."""
    u, v = np.clip(u, -30.0, 30.0), np.clip(v, -30.0, 30.0)
    y = 0.5 * (1.0 + _logistic(v))
    return 1.0 - y + (2.0 * y - 1.0) * _logistic(u), y


def _internal(x, y):
    """``(I1/I3, I2/I3)`` inside the triangle -> internal ``(u, v)``."""
    return _logit((x - (1.0 - y)) / (2.0 * y - 1.0)), _logit(2.0 * y - 1.0)


def _ratio_jacobian(u, v) -> np.ndarray:
    """d(I1/I3, I2/I3) / d(u, v), 2 x 2."""
    su, sv = _logistic(u), _logistic(v)
    dsu, dsv = su * (1 - su), sv * (1 - sv)
    y = 0.5 * (1 + sv)
    dy_dv = 0.5 * dsv
    return np.array([[(2 * y - 1) * dsu, (-1 + 2 * su) * dy_dv], [0.0, dy_dv]])


class _Model:
    """The parameter vector's layout and the model's omega for many parameter vectors at once."""

    def __init__(self, tau, rotation: bool, bias: bool):
        self.tau, self.rotation, self.bias = tau, rotation, bias
        names = ["I1/I3", "I2/I3", "omega0_1", "omega0_2", "omega0_3"]
        if rotation:
            names += ["rotvec_x", "rotvec_y", "rotvec_z"]
        if bias:
            names += ["bias_x", "bias_y", "bias_z"]
        self.names = tuple(names)
        self.n = len(names)

    def unpack(self, P):
        P = np.atleast_2d(P)
        x, y = _ratios(P[:, 0], P[:, 1])
        w0 = P[:, 2:5]
        k = 5
        if self.rotation:
            R = Rotation.from_rotvec(P[:, k:k + 3]).as_matrix()
            k += 3
        else:
            R = np.broadcast_to(np.eye(3), (len(P), 3, 3))
        b = P[:, k:k + 3] if self.bias else np.zeros((len(P), 3))
        return x, y, w0, R, b

    def omega(self, P, tau=None) -> np.ndarray:
        """Model omega (sensor axes, bias included), shape (len(P), T, 3)."""
        tau = self.tau if tau is None else tau
        x, y, w0, R, b = self.unpack(P)
        moments = np.stack([x, y, np.ones_like(x)], axis=1)
        quat = np.tile([0.0, 0.0, 0.0, 1.0], (len(moments), 1))
        wp, _ = free_rotation_batch(moments, w0, quat, tau, attitude=False)
        # omega_sensor = R^T omega_principal, i.e. row vectors times R
        return np.einsum("ntj,njk->ntk", wp, R) + b[:, None, :]


def _check(t, omega) -> tuple[np.ndarray, np.ndarray]:
    try:
        t = np.asarray(t, dtype=float)
        omega = np.asarray(omega, dtype=float)
    except (TypeError, ValueError):
        raise ValueError("t and omega_measured must be arrays of numbers") from None
    if t.ndim != 1:
        raise ValueError(f"t must be one-dimensional (s), got shape {t.shape}")
    if omega.shape != (len(t), 3):
        raise ValueError(f"omega_measured must have shape ({len(t)}, 3) to match t (rad/s), got {omega.shape}")
    if len(t) < MIN_SAMPLES:
        raise ValueError(f"{len(t)} samples are too few to fit a tumble; give at least {MIN_SAMPLES}")
    bad = np.flatnonzero(~np.isfinite(t))
    if bad.size:
        raise ValueError(f"t[{bad[0]}] = {t[bad[0]]} is not finite")
    bad = np.flatnonzero(~np.all(np.isfinite(omega), axis=1))
    if bad.size:
        raise ValueError(f"omega_measured[{bad[0]}] = {omega[bad[0]].tolist()} is not finite")
    steps = np.diff(t)
    bad = np.flatnonzero(~(steps > 0))
    if bad.size:
        i = bad[0] + 1
        raise ValueError(f"t must be strictly increasing: t[{i}] = {t[i]} follows t[{i - 1}] = {t[i - 1]} (s)")
    return t, omega


def _noise_floor(omega) -> float:
    """A robust estimate of the white noise per axis, rad/s, from second differences
    (``var(w[i+1] - 2 w[i] + w[i-1]) = 6 sigma^2`` for white noise on a smooth signal)."""
    d2 = omega[2:] - 2 * omega[1:-1] + omega[:-2]
    mad = np.median(np.abs(d2 - np.median(d2, axis=0)), axis=0) * 1.4826
    return float(np.sqrt(np.mean(mad ** 2) / 6.0))


def _check_not_steady(omega) -> None:
    """Refuse a record whose omega is constant within the noise: the ratios do not enter it."""
    spread = float(np.sqrt(np.mean(np.sum((omega - omega.mean(axis=0)) ** 2, axis=1)) / 3.0))
    noise = _noise_floor(omega)
    scale = float(np.sqrt(np.mean(np.sum(omega ** 2, axis=1))))
    if not spread > max(5.0 * noise, 1e-9 * scale, 1e-12):
        raise ValueError(
            f"omega is constant within the noise (spread {spread:.3g} rad/s, noise {noise:.3g} rad/s): a steady spin "
            "does not determine the inertia ratios; record a tumble")


def _principal_axes(omega) -> np.ndarray:
    """Columns: the principal axes in the sensor frame, from two conserved quadratic forms."""
    wx, wy, wz = omega.T
    Q = np.column_stack([wx * wx, wy * wy, wz * wz, 2 * wx * wy, 2 * wx * wz, 2 * wy * wz, -np.ones_like(wx)])
    scale = np.linalg.norm(Q, axis=0)
    _, _, Vt = np.linalg.svd(Q / scale, full_matrices=False)
    forms = []
    for row in Vt[-2:]:
        c = row / scale
        forms.append(np.array([[c[0], c[3], c[4]], [c[3], c[1], c[5]], [c[4], c[5], c[2]]]))
    best, best_gap = np.eye(3), -1.0
    for mu in (-3.0, -1.0, -0.3, 0.0, 0.3, 1.0, 3.0, 1e3):
        M = forms[0] / np.linalg.norm(forms[0]) + mu * forms[1] / np.linalg.norm(forms[1])
        vals, vecs = np.linalg.eigh(M)
        gap = np.min(np.diff(vals)) / (np.max(np.abs(vals)) or 1.0)
        if gap > best_gap:
            best, best_gap = vecs, gap
    return best


def _direction_grid(n: int = 200):
    """Points of the triangle and the unit direction of the line of omega_i^2 (Euler) at each."""
    y = np.linspace(0.5, 1.0, n)[1:-1]
    frac = np.linspace(0.0, 1.0, n)[1:-1]
    Y, F = np.meshgrid(y, frac, indexing="ij")
    X = 1.0 - Y + (2 * Y - 1) * F
    X, Y = X.ravel(), Y.ravel()
    keep = (X < Y - 1e-6) & (Y < 1 - 1e-6)
    X, Y = X[keep], Y[keep]
    d = np.stack([(Y - 1.0) / X, (1.0 - X) / Y, X - Y], axis=1)
    return X, Y, d / np.linalg.norm(d, axis=1, keepdims=True)


def _candidates(omega, fit_rotation: bool, keep: int = 3):
    """Starting (ratios, R) pairs: the principal axes, each labelling and the best ratios for it."""
    if fit_rotation:
        V = _principal_axes(omega)
        perms = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
    else:
        V, perms = np.eye(3), [(0, 1, 2)]
    X, Y, D = _direction_grid()
    out = []
    for p in perms:
        A = V[:, list(p)].copy()
        if np.linalg.det(A) < 0:
            A[:, 2] *= -1.0
        R = A.T  # sensor -> principal
        wp = omega @ R.T
        sq = wp ** 2
        sq = sq - sq.mean(axis=0)
        _, _, vt = np.linalg.svd(sq, full_matrices=False)
        dd = vt[0]
        score = np.abs(D @ dd)  # |cos| of the angle between the lines
        order = np.argsort(-score)[:keep]
        for i in order:
            out.append((1.0 - score[i], X[i], Y[i], R))
    out.sort(key=lambda c: c[0])
    return out


def _rotvec(R) -> np.ndarray:
    return Rotation.from_matrix(R).as_rotvec()


def _canonical(P, model: _Model) -> np.ndarray:
    """Of the four equivalent rotations (a turn by pi about a principal axis maps the motion onto
    itself, with omega0's other two components negated), keep the one with the smallest angle."""
    if not model.rotation:
        return P
    R = Rotation.from_rotvec(P[5:8]).as_matrix()
    best = None
    for S in _D2:
        R2 = S @ R
        rv = _rotvec(R2)
        if best is None or np.linalg.norm(rv) < np.linalg.norm(best[0]) - 1e-12:
            best = (rv, S)
    P = P.copy()
    P[5:8] = best[0]
    P[2:5] = best[1] @ P[2:5]
    return P


def fit_rotation(t, omega_measured, *, sensor_rotation: str = "fit", bias: bool = True,
                 initial_guess: dict | None = None, max_nfev: int = 200) -> RotationFit:
    """Fit a torque-free rigid-body motion to angular-velocity samples (a gyroscope's record).

    Parameters
    ----------
    t : array_like, shape (n,)
        Sample times, s, strictly increasing (uneven spacing allowed).
    omega_measured : array_like, shape (n, 3)
        Angular velocity measured along the sensor's three axes, rad/s.
    sensor_rotation : {"fit", "identity"}
        ``"fit"``: the rotation from the sensor's axes to the principal axes is fitted (three
        parameters); ``"identity"``: the sensor's x, y, z are the principal axes 1, 2, 3 (minor,
        intermediate, major).
    bias : bool
        Fit a constant bias on each sensor axis (rad/s).
    initial_guess : dict, optional
        Starting values instead of the automatic ones: ``ratios`` ``(I1/I3, I2/I3)`` (required),
        ``omega0`` (principal frame, rad/s; default from the first sample), ``rotvec`` (sensor to
        principal, rad; default zero), ``bias`` (rad/s; default zero).
    max_nfev : int
        Function evaluations allowed to each least-squares run.

    Returns
    -------
    RotationFit

    Raises
    ------
    ValueError
        Too few samples, non-finite values, times not strictly increasing, a steady spin, an
        unknown option, or a rank-deficient Jacobian at the optimum (the data do not determine
        every parameter).

    Notes
    -----
    The model, the parametrisation of the ratios and the starting values are described in the
    module docstring (:mod:`tumble.analysis.fit`). The ratios' uncertainties come from the
    Jacobian at the optimum, ``sqrt(diag((J^T J)^-1) s^2)`` (Numerical Recipes, sec. 15.5).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.exact import FreeRotation
    >>> from scipy.spatial.transform import Rotation
    >>> t = np.linspace(0.0, 10.0, 1001)
    >>> w = FreeRotation([0.3, 0.7, 1.0], [0.2, 5.0, 0.3], Rotation.identity()).omega(t)
    >>> fit = fit_rotation(t, w, sensor_rotation="identity", bias=False)
    >>> np.round(fit.ratios, 6).tolist()
    [0.3, 0.7]
    """
    if sensor_rotation not in ("fit", "identity"):
        raise ValueError(f"sensor_rotation = {sensor_rotation!r} must be 'fit' or 'identity'")
    t, omega = _check(t, omega_measured)
    _check_not_steady(omega)
    tau = t - t[0]
    model = _Model(tau, sensor_rotation == "fit", bool(bias))

    def pack(x, y, w0, R, b):
        P = [*_internal(x, y), *w0]
        if model.rotation:
            P += list(_rotvec(R))
        if model.bias:
            P += list(b)
        return np.array(P, float)

    if initial_guess is not None:
        starts = [_start_from_guess(initial_guess, omega, pack)]
    else:
        starts = []
        for _, x, y, R in _candidates(omega, model.rotation):
            w0 = R @ _first_value(tau, omega)
            starts.append(pack(x, y, w0, R, np.zeros(3)))

    # the first window: about two turns of omega's largest component, at least 40 samples
    spin = float(np.max(np.sqrt(np.mean(omega ** 2, axis=0))))
    horizon = min(tau[-1], max(2.0 * 2 * np.pi / max(spin, 1e-300), tau[min(len(tau) - 1, 39)]))

    def residuals(P, n):
        try:
            return (model.omega(P, tau[:n])[0] - omega[:n]).ravel()
        except ValueError:  # a step so far out that a phase would exceed MAX_PHASE
            return np.full(3 * n, 1e6)

    def jacobian(P, n):
        h = 1e-7 * np.maximum(1.0, np.abs(P))
        Ps = np.vstack([P, P + np.diag(h)])
        try:
            out = model.omega(Ps, tau[:n])
        except ValueError:
            return np.zeros((3 * n, len(P)))
        return ((out[1:] - out[0]) / h[:, None, None]).reshape(len(P), -1).T

    def solve(P, n, nfev):
        return least_squares(residuals, P, jac=jacobian, args=(n,), method="trf", x_scale="jac",
                             max_nfev=nfev)

    n0 = int(np.searchsorted(tau, horizon, side="right"))
    if len(starts) > 1:
        # cheapest first: rank the starts by their cost on the first window (one batched
        # evaluation), then improve them in that order until one fits down to the noise
        with np.errstate(all="ignore"):
            try:
                first = model.omega(np.array(starts), tau[:n0]) - omega[:n0]
                order = np.argsort(np.nan_to_num(np.sum(first ** 2, axis=(1, 2)), nan=np.inf))
            except ValueError:
                order = np.arange(len(starts))
        good = 3.0 * max(_noise_floor(omega), 1e-6 * spin) ** 2 * 3 * n0 / 2.0  # cost at ~1.7 x the noise
        best = None
        for i in order:
            with np.errstate(all="ignore"):
                r = solve(starts[i], n0, 15)
            if best is None or r.cost < best.cost:
                best = r
            if r.cost < good:
                break
        P = best.x
    else:
        P = starts[0]
    n = n0
    while True:
        with np.errstate(all="ignore"):
            res = solve(P, n, max_nfev)
        P = res.x
        if n == len(tau):
            break
        span = 2.0 * tau[n - 1]
        n = len(tau) if span >= tau[-1] else int(np.searchsorted(tau, span, side="right"))
    return _result(P, res, model, t, omega)


def _first_value(tau, omega) -> np.ndarray:
    """omega at tau = 0 from a quadratic through the first few samples (less noise than one)."""
    k = min(7, len(tau))
    coef = np.polyfit(tau[:k], omega[:k], 2)
    return coef[-1]


def _start_from_guess(guess: dict, omega, pack) -> np.ndarray:
    if not isinstance(guess, dict) or "ratios" not in guess:
        raise ValueError("initial_guess must be a dict with 'ratios' (I1/I3, I2/I3) and optionally "
                         "'omega0', 'rotvec', 'bias'")
    x, y = (float(v) for v in guess["ratios"])
    if not (0.5 < y < 1.0 and 1.0 - y < x < y):
        raise ValueError(f"initial_guess ratios = ({x}, {y}) must satisfy I1 < I2 < I3 and I1 + I2 > I3 strictly")
    R = Rotation.from_rotvec(np.asarray(guess.get("rotvec", np.zeros(3)), float)).as_matrix()
    b = np.asarray(guess.get("bias", np.zeros(3)), float)
    w0 = np.asarray(guess["omega0"], float) if "omega0" in guess else R @ (omega[0] - b)
    return pack(x, y, w0, R, b)


def _result(P, res, model: _Model, t, omega) -> RotationFit:
    P = _canonical(P, model)
    tau = t - t[0]
    model_omega = model.omega(P, tau)[0]
    r = (model_omega - omega).ravel()
    m, n = r.size, model.n
    # the Jacobian in the physical parameters: forward differences in (u, v, ...), chain rule
    h = 1e-7 * np.maximum(1.0, np.abs(P))
    Ps = np.vstack([P, P + np.diag(h)])
    out = model.omega(Ps, tau)
    J = ((out[1:] - out[0]) / h[:, None, None]).reshape(n, -1).T
    D = np.eye(n)
    D[:2, :2] = _ratio_jacobian(P[0], P[1])
    with np.errstate(all="ignore"):
        try:
            Jp = np.linalg.solve(D.T, J.T).T  # J_phys = J_int D^-1
        except np.linalg.LinAlgError:
            Jp = np.full_like(J, np.nan)
    if not np.all(np.isfinite(Jp)):
        raise ValueError("the fit ran onto the edge of the triangle of inertia ratios (a planar or symmetric body): "
                         "the Jacobian is singular there")
    norms = np.linalg.norm(Jp, axis=0)
    sv = np.linalg.svd(Jp / np.where(norms > 0, norms, 1.0), compute_uv=False)
    if norms.min() == 0 or sv[-1] < RANK_TOL * sv[0]:
        raise ValueError(
            f"the Jacobian at the optimum is rank deficient (singular values {sv[-1]:.2g} / {sv[0]:.2g} after scaling): "
            "the data do not determine every parameter (a symmetric body, or too short a record)")
    dof = max(m - n, 1)
    s2 = float(r @ r) / dof
    Js = Jp / norms
    cov = np.linalg.inv(Js.T @ Js) / np.outer(norms, norms) * s2
    std = np.sqrt(np.diag(cov))
    x, y = _ratios(P[0], P[1])
    k = 5
    rotvec_std = None
    R = Rotation.identity()
    if model.rotation:
        R = Rotation.from_rotvec(P[5:8])
        rotvec_std = std[5:8]
        k = 8
    bias = P[k:k + 3] if model.bias else np.zeros(3)
    bias_std = std[k:k + 3] if model.bias else None
    return RotationFit(
        ratios=np.array([float(x), float(y)]), ratios_std=std[:2].copy(), omega0=P[2:5].copy(),
        omega0_std=std[2:5].copy(), sensor_rotation=R, rotvec_std=rotvec_std, bias=np.array(bias, float),
        bias_std=bias_std, residual_rms=float(np.sqrt(np.mean(r ** 2))), samples=len(t), t=t.copy(),
        omega_model=model_omega, covariance=cov, parameter_names=model.names, iterations=int(res.nfev))
