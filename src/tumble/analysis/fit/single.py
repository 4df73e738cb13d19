"""Fit one free flight: :func:`fit_rotation` and its result :class:`RotationFit`.

The model (:mod:`tumble.analysis.fit.model`) is the exact torque-free motion of Landau &
Lifshitz, *Mechanics*, sec. 37 (:mod:`tumble.dynamics.exact_omega`), or Euler's equations with
an aerodynamic drag about each principal axis (:mod:`tumble.dynamics.drag`), seen by a sensor rotated by ``R`` from the principal axes
and offset by a bias. It depends on the moments only through their ratios, so the scale is
fixed by ``I3 = 1``. The ratios move on the closed triangle (:mod:`tumble.analysis.fit.triangle`),
edges included; starting values come from the samples (:mod:`tumble.analysis.fit.start`): the
best few are ranked on a first window of one turn and the best is refined on windows that double up
to the whole record (so that a small error in the period does not wrap the phase of a long
record). Uncertainties: :mod:`tumble.analysis.fit.uncertainty`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.spatial.transform import Rotation

from .model import Model
from .solve import Solution, solve, solve_drag
from .start import candidates, first_value
from .triangle import EDGES, S_MIN, edge_of, ratio_jacobian, ratios, square
from .uncertainty import SCALE_UNCERTAINTY, effective_dof, interval, noise_floor

__all__ = ["MIN_SAMPLES", "RotationFit", "fit_rotation", "fit_solution", "saturation_mask"]

#: Fewest samples accepted.
MIN_SAMPLES = 20
#: The four rotations by 0 or pi about a principal axis map a torque-free motion onto itself:
#: the sensor rotation is reported as the one of the four with the smallest angle.
_D2 = (np.eye(3), np.diag([1.0, -1.0, -1.0]), np.diag([-1.0, 1.0, -1.0]), np.diag([-1.0, -1.0, 1.0]))
#: Largest standard uncertainties reported for I1/I3 and I2/I3: half their ranges in the triangle.
_STD_CAP = (0.5, 0.25)


@dataclass(frozen=True)
class RotationFit:
    """A torque-free (or uniformly damped) motion fitted to angular-velocity samples.

    Attributes
    ----------
    ratios : ndarray, shape (2,)
        ``I1/I3``, ``I2/I3`` (dimensionless, ascending, ``I3`` the largest moment).
    ratios_std : ndarray, shape (2,)
        Their standard uncertainties (HAC sandwich), at most half their range in the triangle.
    ratios_interval : ndarray, shape (2, 2)
        95 % intervals ``[[lo, hi], [lo, hi]]``, inside the triangle; one-sided on an edge.
    edge : str or None
        The triangle's edge the optimum lies on (e.g. ``"planar (I1 + I2 = I3)"``), or None.
    undetermined : tuple of str
        Parameters the data do not determine (left at their values, uncertainty NaN), e.g.
        ``rotvec_z`` for the sensor's rotation about a symmetric body's axis.
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
    drag : str
        The drag model fitted: ``"none"``, ``"linear"`` or ``"quadratic"``.
    drag_coefficients, drag_coefficients_std : ndarray, shape (3,)
        The drag about each principal axis divided by ``I3`` (:mod:`tumble.dynamics.drag`):
        ``a_i / I3`` in 1/s (linear) or ``b_i / I3`` in 1/rad (quadratic); zeros and NaN when
        no drag is fitted. Times ``I3`` (kg m^2) they are N m s or N m s^2.
    residual_rms : float
        Root mean square of the residuals over the samples and axes fitted, rad/s.
    noise : float
        The white noise per axis the samples show (second differences), rad/s.
    samples : int
        Number of time samples.
    saturated : int
        Sample axes left out because they lie at the sensor's rail.
    t : ndarray, shape (n,)
        The sample times, s.
    omega_model : ndarray, shape (n, 3)
        The fitted model at the sample times, sensor axes, bias included, rad/s.
    covariance : ndarray
        Covariance of the parameters in the order of :attr:`parameter_names`.
    parameter_names : tuple of str
        ``I1/I3``, ``I2/I3``, ``omega0_1..3``, then ``rotvec_x..z``, ``bias_x..z`` and the drag
        coefficient when fitted.
    iterations : int
        Function evaluations of the final least-squares run.
    bandwidth : float
        The sandwich's Bartlett bandwidth, samples.
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
    ratios_interval: np.ndarray = field(default=None, repr=False)
    edge: str | None = None
    undetermined: tuple = ()
    drag: str = "none"
    drag_coefficients: np.ndarray = field(default_factory=lambda: np.zeros(3))
    drag_coefficients_std: np.ndarray = field(default_factory=lambda: np.full(3, np.nan))
    noise: float = 0.0
    saturated: int = 0
    bandwidth: float = 0.0

    @property
    def moments(self) -> np.ndarray:
        """Principal moments scaled so that ``I3 = 1`` (dimensionless), ascending."""
        return np.array([self.ratios[0], self.ratios[1], 1.0])

    def summary(self) -> dict:
        """The fitted values and their uncertainties as plain JSON-ready numbers (SI units);
        NaN (undetermined) is written as None."""
        def num(v):
            v = float(v)
            return v if np.isfinite(v) else None

        def listed(x):
            return None if x is None else [num(v) for v in np.ravel(x)]

        sx, sy = self.ratios_std
        corr = self.covariance[0, 1] / (sx * sy) if sx > 0 and sy > 0 else float("nan")
        return {
            "I1_over_I3": float(self.ratios[0]),
            "I2_over_I3": float(self.ratios[1]),
            "I1_over_I3_std": num(sx),
            "I2_over_I3_std": num(sy),
            "I1_over_I3_interval": listed(self.ratios_interval[0]),
            "I2_over_I3_interval": listed(self.ratios_interval[1]),
            "ratios_correlation": num(corr),
            "edge": self.edge,
            "undetermined": list(self.undetermined),
            "omega0": listed(self.omega0),
            "omega0_std": listed(self.omega0_std),
            "t0": float(self.t[0]),
            "sensor_rotation_rotvec": listed(self.sensor_rotation.as_rotvec()),
            "sensor_rotation_rotvec_std": listed(self.rotvec_std),
            "sensor_rotation_matrix": [listed(row) for row in self.sensor_rotation.as_matrix()],
            "bias": listed(self.bias),
            "bias_std": listed(self.bias_std),
            "drag": self.drag,
            "drag_coefficients": listed(self.drag_coefficients),
            "drag_coefficients_std": listed(self.drag_coefficients_std),
            "residual_rms": float(self.residual_rms),
            "noise": float(self.noise),
            "samples": int(self.samples),
            "saturated": int(self.saturated),
            "parameters": list(self.parameter_names),
            "covariance_method": f"HAC sandwich (Newey-West, Bartlett bandwidth {self.bandwidth:.1f} samples)",
            "units": {"ratios": "dimensionless", "omega0": "rad/s", "rotvec": "rad", "bias": "rad/s",
                      "residual_rms": "rad/s", "noise": "rad/s", "t0": "s", "ratios_correlation": "dimensionless",
                      "drag_coefficients": {"none": "-", "linear": "1/s (a_i / I3)",
                                            "quadratic": "1/rad (b_i / I3)"}[self.drag]},
        }


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
    bad = np.flatnonzero(~(np.diff(t) > 0))
    if bad.size:
        i = bad[0] + 1
        raise ValueError(f"t must be strictly increasing: t[{i}] = {t[i]} follows t[{i - 1}] = {t[i - 1]} (s)")
    return t, omega


def _check_not_steady(omega) -> None:
    """Refuse a record whose omega is constant within the noise: the ratios do not enter it."""
    spread = float(np.sqrt(np.mean(np.sum((omega - omega.mean(axis=0)) ** 2, axis=1)) / 3.0))
    noise = noise_floor(omega)
    scale = float(np.sqrt(np.mean(np.sum(omega ** 2, axis=1))))
    if not spread > max(5.0 * noise, 1e-9 * scale, 1e-12):
        raise ValueError(
            f"omega is constant within the noise (spread {spread:.3g} rad/s, noise {noise:.3g} rad/s): a steady spin "
            "does not determine the inertia ratios; record a tumble")


def saturation_mask(omega, saturation: float | None = None) -> tuple[np.ndarray, float | None]:
    """Sample axes inside the sensor's range, and the rail (rad/s) they were judged against.

    Parameters
    ----------
    omega : ndarray, shape (n, 3)
        Samples, rad/s.
    saturation : float, optional
        The sensor's full scale, rad/s. Without it the rail is found from the data: the largest
        ``|omega|`` of any axis counts as a rail when at least three samples lie within 0.2 % of
        it but fewer than half of those above half of it (an unclipped signal touches its
        peak once; a clipped one sits there a while; a steady spin sits there throughout).

    Returns
    -------
    keep : ndarray of bool, shape (n, 3)
        False where an axis is at the rail (within 0.2 %).
    rail : float or None
    """
    a = np.abs(np.asarray(omega, float))
    rail = saturation
    if rail is None:
        top = float(a.max()) if a.size else 0.0
        at = np.count_nonzero(a >= 0.998 * top)
        # a rail is a flat top: several samples on it, but few of those that come near it (a
        # steady spin sits at its maximum throughout and is not clipped)
        if top > 0 and at >= 3 and at < 0.5 * np.count_nonzero(a > 0.5 * top):
            rail = top
    if rail is None:
        return np.ones(a.shape, bool), None
    return a < 0.998 * float(rail), float(rail)


def _canonical(P, model: Model) -> np.ndarray:
    """Of the four equivalent rotations (a turn by pi about a principal axis maps the motion onto
    itself, with omega0's other two components negated), keep the one with the smallest angle."""
    if not model.rotation:
        return P
    k = model.index["rotvec_x"]
    R = Rotation.from_rotvec(P[k:k + 3]).as_matrix()
    best = None
    for S in _D2:
        rv = Rotation.from_matrix(S @ R).as_rotvec()
        if best is None or np.linalg.norm(rv) < np.linalg.norm(best[0]) - 1e-12:
            best = (rv, S)
    P = P.copy()
    P[k:k + 3] = best[0]
    P[model.ns:] = (model.omega0(P) @ best[1].T).ravel()
    return P


def fit_rotation(t, omega_measured, *, sensor_rotation: str = "fit", bias: bool = True, drag: str = "auto",
                 saturation: float | None = None, scale_uncertainty: float = SCALE_UNCERTAINTY,
                 initial_guess: dict | None = None, max_nfev: int = 100) -> RotationFit:
    """Fit a free rigid-body motion to angular-velocity samples (a gyroscope's record of a flight).

    Parameters
    ----------
    t : array_like, shape (n,)
        Sample times, s, strictly increasing (uneven spacing and gaps allowed).
    omega_measured : array_like, shape (n, 3)
        Angular velocity measured along the sensor's three axes, rad/s.
    sensor_rotation : {"fit", "identity"}
        ``"fit"``: the rotation from the sensor's axes to the principal axes is fitted (three
        parameters); ``"identity"``: the sensor's x, y, z are the principal axes 1, 2, 3.
    bias : bool
        Fit a constant bias on each sensor axis (rad/s).
    drag : {"auto", "none", "linear", "quadratic"}
        The aerodynamic drag about each principal axis (:mod:`tumble.dynamics.drag`): fitted as
        named, or chosen by the Bayesian information criterion (``"auto"``).
    saturation : float, optional
        The gyroscope's full scale, rad/s; sample axes at it are left out. Found from the data
        when not given (:func:`saturation_mask`).
    scale_uncertainty : float
        Standard uncertainty of the gyroscope's scale factor on each axis (dimensionless),
        propagated into the uncertainties as a systematic part
        (:func:`tumble.analysis.fit.uncertainty.scale_covariance`); 0 leaves it out.
    initial_guess : dict, optional
        Starting values instead of the automatic ones: ``ratios`` ``(I1/I3, I2/I3)`` (required),
        ``omega0`` (principal frame, rad/s), ``rotvec`` (sensor to principal, rad), ``bias`` (rad/s).
    max_nfev : int
        Function evaluations allowed to each least-squares run.

    Returns
    -------
    RotationFit

    Raises
    ------
    ValueError
        Too few samples, non-finite values, times not strictly increasing, a steady spin, an
        unknown option; one line naming what is wrong.

    Notes
    -----
    An optimum on an edge of the triangle (a planar or symmetric body) is a result, reported in
    :attr:`RotationFit.edge` with a one-sided interval; a parameter the data cannot determine is
    named in :attr:`RotationFit.undetermined` and the rest are fitted.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.exact import FreeRotation
    >>> from scipy.spatial.transform import Rotation
    >>> t = np.linspace(0.0, 10.0, 1001)
    >>> w = FreeRotation([0.3, 0.7, 1.0], [0.2, 5.0, 0.3], Rotation.identity()).omega(t)
    >>> fit = fit_rotation(t, w, sensor_rotation="identity", bias=False, drag="none")
    >>> np.round(fit.ratios, 6).tolist()
    [0.3, 0.7]
    """
    if sensor_rotation not in ("fit", "identity"):
        raise ValueError(f"sensor_rotation = {sensor_rotation!r} must be 'fit' or 'identity'")
    if drag not in ("auto", "none", "linear", "quadratic"):
        raise ValueError(f"drag = {drag!r} must be 'auto', 'none', 'linear' or 'quadratic'")
    if saturation is not None and not (np.isfinite(saturation) and saturation > 0):
        raise ValueError(f"saturation = {saturation!r} must be a positive number of rad/s")
    t, omega = _check(t, omega_measured)
    keep, _ = saturation_mask(omega, saturation)
    if np.count_nonzero(np.all(keep, axis=1)) < MIN_SAMPLES:
        raise ValueError(f"only {np.count_nonzero(np.all(keep, axis=1))} samples are below the gyroscope's rail; "
                         f"give at least {MIN_SAMPLES} unsaturated samples")
    _check_not_steady(omega[np.all(keep, axis=1)])
    if not (np.isfinite(scale_uncertainty) and 0 <= scale_uncertainty < 0.5):
        raise ValueError(f"scale_uncertainty = {scale_uncertainty!r} must be a number in [0, 0.5)")
    sol = fit_solution(t, omega, keep, rotation=sensor_rotation == "fit", bias=bool(bias), drag=drag,
                       guess=initial_guess, max_nfev=max_nfev, scale_uncertainty=scale_uncertainty)
    return rotation_fit(sol, t, omega, keep)


def fit_solution(t, omega, keep, *, rotation: bool = True, bias: bool = True, drag: str = "auto", guess=None,
                 P0=None, drag0=None, t0=None, max_nfev: int = 100,
                 scale_uncertainty: float = SCALE_UNCERTAINTY, covariance: bool = True) -> Solution:
    """The solved model of one flight (checked inputs; ``keep`` the unsaturated sample axes).

    ``P0``: drag-free parameters to start from instead of the automatic starting values (and
    ``drag0`` the quadratic drag's), with ``omega0`` at time ``t0`` (default ``t[0]``; samples before it are fitted backward in time:
    near the separatrix re-anchoring ``omega0`` at another sample would move it across)."""
    tau = t - (t[0] if t0 is None else t0)
    speed = [float(np.max(np.linalg.norm(omega, axis=1)))]
    P = _start(tau, omega, keep, rotation, bias, guess, max_nfev) if P0 is None else P0
    model = Model([tau], rotation, bias, speeds=speed)
    P = _canonical(P, model)
    return solve_drag(model, omega[None], keep[None], P, drag, drag0=drag0, max_nfev=max_nfev,
                      scale_uncertainty=scale_uncertainty, covariance=covariance)


def _start(tau, omega, keep, rotation, bias, guess, max_nfev) -> np.ndarray:
    """The drag-free parameters refined on windows that double up to the whole record.

    The bias and omega0 are free here (the way from a start to the right basin may pass through
    large values); the final solve bounds them."""
    ok = np.all(keep, axis=1)
    spin = float(np.max(np.sqrt(np.mean(omega[ok] ** 2, axis=0))))
    horizon = min(tau[-1], max(2 * np.pi / max(spin, 1e-300), tau[min(len(tau) - 1, 24)]))
    n = int(np.searchsorted(tau, horizon, side="right"))
    window = Model([tau[:n]], rotation, bias)
    data, mask = omega[None, :n], keep[None, :n]
    if guess is not None:
        starts = [_from_guess(guess, omega, window)]
    else:
        w_first = first_value(tau[ok], omega[ok])
        starts = [window.pack(*square(x, y), Rotation.from_matrix(R).as_rotvec(), np.zeros(3), (R @ w_first)[None])
                  for x, y, R in candidates(omega[ok], rotation, t=tau[ok])]
    if len(starts) > 1:
        costs = [float(np.sum(((window.sensor(P) - data)[mask]) ** 2)) for P in starts]
        order = [0] + [i for i in np.argsort(np.nan_to_num(costs, nan=np.inf)) if i != 0]
        # a start in the right basin fits to the noise plus the model's error (a racquet's drag
        # without its model: a few per cent of the rates); a wrong one leaves tens of per cent
        good = (0.05 * spin) ** 2 * 3 * n
        best = None
        for i in order[:6]:
            sol = solve(window, data, mask, starts[i], max_nfev=15, covariance=False)
            if best is None or sol.ssr < best.ssr:
                best = sol
            if sol.ssr < good:
                break
        P = best.P
    else:
        P = starts[0]
    while n < len(tau):
        span = 2.0 * tau[n - 1]
        n = len(tau) if span >= tau[-1] else int(np.searchsorted(tau, span, side="right"))
        window = Model([tau[:n]], rotation, bias)
        P = solve(window, omega[None, :n], keep[None, :n], P, max_nfev=max_nfev, covariance=False).P
    return P


def _from_guess(guess: dict, omega, model: Model) -> np.ndarray:
    if not isinstance(guess, dict) or "ratios" not in guess:
        raise ValueError("initial_guess must be a dict with 'ratios' (I1/I3, I2/I3) and optionally "
                         "'omega0', 'rotvec', 'bias'")
    x, y = (float(v) for v in guess["ratios"])
    if not (0.5 <= y <= 1.0 and 1.0 - y <= x <= y):
        raise ValueError(f"initial_guess ratios = ({x}, {y}) must satisfy I1 <= I2 <= I3 and I1 + I2 >= I3")
    rv = np.asarray(guess.get("rotvec", np.zeros(3)), float)
    R = Rotation.from_rotvec(rv).as_matrix()
    b = np.asarray(guess.get("bias", np.zeros(3)), float)
    w0 = np.asarray(guess["omega0"], float) if "omega0" in guess else R @ (omega[0] - b)
    return model.pack(*square(x, y), rv, b, w0[None])


def public_covariance(sol: Solution, statistical: bool = False):
    """The ratios, their covariance with everything else in the public order, and the names.

    ``statistical``: leave out the scale factor's systematic part. Returns ``(names, values, cov)`` with ``I1/I3``, ``I2/I3``, ``omega0_*``, ``rotvec_*``,
    ``bias_*``, drag; undetermined parameters keep NaN rows."""
    model, P = sol.model, sol.P
    per = list(model.names[model.ns:])
    rest = [n for n in model.shared if n not in ("s", "g")]
    names = ["I1/I3", "I2/I3"] + per + rest
    idx = {n: i for i, n in enumerate(model.names)}
    G = np.zeros((len(names), model.n))
    G[:2, :2] = ratio_jacobian(P[0], P[1])[:, [0, 1]]
    for i, n in enumerate(names[2:], start=2):
        G[i, idx[n]] = 1.0
    C = np.nan_to_num(sol.cov_stat if statistical else sol.cov, nan=0.0)
    cov = G @ C @ G.T
    bad = np.isnan(np.diag(sol.cov))
    for i, n in enumerate(names):
        if n in idx and bad[idx[n]]:
            cov[i, :] = cov[:, i] = np.nan
    if bad[0] and bad[1]:
        cov[:2, :] = cov[:, :2] = np.nan
    x, y = ratios(P[0], P[1])
    values = np.concatenate([[float(x), float(y)], P[model.ns:], [P[idx[n]] for n in rest]])
    return tuple(names), values, cov


def ratio_summary(sol: Solution):
    """``(ratios, std, interval, edge)`` of a solution.

    The standard uncertainties are capped at half each ratio's range in the triangle. The 95 %
    intervals: inside the triangle, ``+- k std`` clipped to it (``k`` Student's for the
    Welch-Satterthwaite degrees of freedom of the statistical part, ``m / tau - n``, and the
    systematic one); on an edge, the interval of
    the square's coordinates (one-sided in the one normal to the edge,
    :func:`~tumble.analysis.fit.uncertainty.interval`) carried to the ratios through the map
    of :mod:`~tumble.analysis.fit.triangle` (``I1/I3`` grows with both coordinates, ``I2/I3``
    falls with ``s`` and grows with ``g``), so that an optimum held on the planar edge keeps an
    interval along the edge."""
    names, values, cov = public_covariance(sol)
    _, _, cov_stat = public_covariance(sol, statistical=True)
    x, y = values[0], values[1]
    sq, gq = float(sol.P[0]), float(sol.P[1])
    edge = edge_of(sq, gq)
    std = np.sqrt(np.abs(np.diag(cov)[:2]))
    std = np.where(np.isfinite(std), np.minimum(std, _STD_CAP), _STD_CAP)
    # the residuals hold m / tau independent values; n parameters were fitted to them
    dof_stat = max(sol.m / max(sol.bandwidth, 1.0) - sol.model.n, 1.0)
    dof = [effective_dof(cov_stat[i, i], cov[i, i], dof_stat) for i in range(2)]
    if edge is None or edge == EDGES["rod"]:
        ix = interval(x, std[0], 0.0, 1.0, dof=dof[0])
        iy = interval(y, std[1], 0.5, 1.0, dof=dof[1])
        return np.array([x, y]), std, np.array([ix, iy]), edge
    c = np.nan_to_num(sol.cov[:2, :2], nan=np.inf)
    ss, sg = (float(np.sqrt(v)) if np.isfinite(v) else np.inf for v in np.diag(c))
    d = min(dof)
    s_lo, s_hi = interval(sq, ss, S_MIN, 1.0, on_high_edge=edge == EDGES["I1=I2"], dof=d)
    g_lo, g_hi = interval(gq, sg, 0.0, 1.0, on_low_edge=edge == EDGES["planar"], on_high_edge=edge == EDGES["I2=I3"],
                          dof=d)
    ix = (float(ratios(s_lo, g_lo)[0]), float(ratios(s_hi, g_hi)[0]))
    iy = (float(ratios(s_hi, g_lo)[1]), float(ratios(s_lo, g_hi)[1]))
    return np.array([x, y]), std, np.array([ix, iy]), edge


def rotation_fit(sol: Solution, t, omega, keep) -> RotationFit:
    """The public result of a solved flight."""
    model = sol.model
    names, values, cov = public_covariance(sol)
    rat, rstd, rint, edge = ratio_summary(sol)
    std = np.sqrt(np.abs(np.diag(cov)))
    std[np.isnan(np.diag(cov))] = np.nan
    std[:2] = rstd
    pos = {n: i for i, n in enumerate(names)}

    def block(prefix):
        ii = [pos[f"{prefix}_{c}"] for c in "xyz"]
        return values[ii], std[ii]

    R, rotvec_std = Rotation.identity(), None
    if model.rotation:
        rv, rotvec_std = block("rotvec")
        R = Rotation.from_rotvec(rv)
    b, bias_std = (block("bias") if model.bias else (np.zeros(3), None))
    if model.drag != "none":
        ii = [pos[f"drag_{k}"] for k in (1, 2, 3)]
        drag_c, drag_s = values[ii], std[ii]
    else:
        drag_c, drag_s = np.zeros(3), np.full(3, np.nan)
    r = sol.residuals
    return RotationFit(
        ratios=rat, ratios_std=rstd, omega0=values[2:5].copy(), omega0_std=std[2:5].copy(), sensor_rotation=R,
        rotvec_std=rotvec_std, bias=np.array(b, float), bias_std=bias_std,
        residual_rms=float(np.sqrt(np.mean(r ** 2))), samples=len(t), t=t.copy(), omega_model=sol.omega_model[0],
        covariance=cov, parameter_names=names, iterations=sol.nfev, ratios_interval=rint, edge=edge,
        undetermined=tuple(_public_name(n) for n in sol.undetermined), drag=model.drag,
        drag_coefficients=np.array(drag_c, float), drag_coefficients_std=np.array(drag_s, float),
        noise=noise_floor(omega[np.all(keep, axis=1)]), saturated=int(np.count_nonzero(~keep)),
        bandwidth=float(sol.bandwidth))


def _public_name(name: str) -> str:
    return {"s": "(I1 + I3 - I2)/I3", "g": "I2/I3 (across the triangle)"}.get(name, name)
