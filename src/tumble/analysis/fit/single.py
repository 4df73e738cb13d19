"""Fit one free flight: :func:`fit_rotation` and its result :class:`RotationFit`.

The model (:mod:`tumble.analysis.fit.model`) is the exact torque-free motion of Landau &
Lifshitz, *Mechanics*, sec. 37 (:mod:`tumble.dynamics.methods.exact_omega`), or Euler's equations with
an aerodynamic drag about each principal axis (:mod:`tumble.dynamics.models.drag`), seen by a sensor rotated by ``R`` from the principal axes
and offset by a bias. It depends on the moments only through their ratios, so the scale is
fixed by ``I3 = 1``. The ratios move on the closed triangle (:mod:`tumble.analysis.fit.triangle`),
edges included; starting values come from the samples (:mod:`tumble.analysis.fit.start`): the
best few are ranked on a first window of one turn and the best is refined on windows that double up
to the whole record (so that a small error in the period does not wrap the phase of a long
record). Uncertainties: :mod:`tumble.analysis.fit.uncertainty`.
"""

from __future__ import annotations

import warnings
from numbers import Integral, Real
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike
from ...validation import check_increasing
from .adequacy import InadequateFitWarning
from .model import Model
from .result import RotationFit, rotation_fit
from .solve import Solution, check_drag, solve, solve_drag
from .start import candidates, first_value
from .triangle import square
from .uncertainty import SCALE_UNCERTAINTY, noise_floor

__all__ = ["MAX_RATE", "MAX_TIME", "MIN_SAMPLES", "RotationFit", "fit_rotation", "fit_solution", "saturation_mask"]

#: Fewest samples accepted.
MIN_SAMPLES = 20
#: Largest |omega| accepted on any axis, rad/s (about 100 000 rpm): phones' gyroscopes end at
#: 35-70 rad/s and no rate gyroscope exceeds a few hundred; beyond this a value is a unit or
#: file error, and its square would overflow the fit's sums of squares.
MAX_RATE = 1e4
#: Largest |t| accepted, s: more than three centuries, so Unix times in seconds pass.
MAX_TIME = 1e10
#: The four rotations by 0 or pi about a principal axis map a torque-free motion onto itself:
#: the sensor rotation is reported as the one of the four with the smallest angle.
_D2 = (np.eye(3), np.diag([1.0, -1.0, -1.0]), np.diag([-1.0, 1.0, -1.0]), np.diag([-1.0, -1.0, 1.0]))


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
    bad = np.flatnonzero(np.abs(t) > MAX_TIME)
    if bad.size:
        raise ValueError(f"t[{bad[0]}] = {t[bad[0]]:.6g} s is beyond +-{MAX_TIME:.0e} s: is the time column in "
                         "other units?")
    big = np.abs(omega) > MAX_RATE
    if big.any():
        i, k = np.argwhere(big)[0]
        raise ValueError(f"omega_measured[{i}] = {omega[i].tolist()}: its {'xyz'[k]} component exceeds "
                         f"{MAX_RATE:.0e} rad/s, more than any gyroscope measures; is it in other units?")
    check_increasing("t", t)
    return t, omega


def _check_options(sensor_rotation: str, drag: str, saturation: float | None, scale_uncertainty: float) -> None:
    """The options :func:`fit_rotation` and :func:`~tumble.analysis.fit.recording.fit_recording` share."""
    if sensor_rotation not in ("fit", "identity"):
        raise ValueError(f"sensor_rotation = {sensor_rotation!r} must be 'fit' or 'identity'")
    check_drag(drag)
    if saturation is not None and not (np.isfinite(saturation) and saturation > 0):
        raise ValueError(f"saturation = {saturation!r} must be a positive number of rad/s")
    if not (isinstance(scale_uncertainty, Real) and np.isfinite(scale_uncertainty) and 0 <= scale_uncertainty < 0.5):
        raise ValueError(f"scale_uncertainty = {scale_uncertainty!r} must be a number in [0, 0.5)")


def _check_not_steady(omega) -> None:
    """Refuse a record whose omega is constant within the noise: the ratios do not enter it."""
    spread = float(np.sqrt(np.mean(np.sum((omega - omega.mean(axis=0)) ** 2, axis=1)) / 3.0))
    noise = noise_floor(omega)
    scale = float(np.sqrt(np.mean(np.sum(omega ** 2, axis=1))))
    if not spread > max(5.0 * noise, 1e-9 * scale, 1e-12):
        raise ValueError(
            f"omega is constant within the noise (spread {spread:.3g} rad/s, noise {noise:.3g} rad/s): a steady spin "
            "does not determine the inertia ratios; record a tumble")


def saturation_mask(omega: ArrayLike, saturation: float | None = None) -> tuple[np.ndarray, float | None]:
    """Sample axes inside the sensor's range, and the rail (rad/s) they were judged against.

    Parameters
    ----------
    omega : ndarray, shape (n, 3)
        Samples, rad/s.
    saturation : float, optional
        The sensor's full scale, rad/s. Without it the rail is found from the data: the largest
        ``|omega|`` of any axis counts as a rail when at least three samples repeat it exactly
        (to 1e-9 relative) but fewer than half of those above half of it (a clipped gyroscope
        returns its full-scale code again and again; an unclipped signal's samples near a
        smooth maximum differ in their noise, even where they stay within 0.2 % of it, as
        a plate's spin about its intermediate axis does for a third of a second; a steady spin
        sits at its maximum throughout and is not clipped). Samples within 0.2 % of the rail are
        left out on every axis (a calibrated phone subtracts each axis's own offset from the
        rail).

    Returns
    -------
    keep : ndarray of bool, shape (n, 3)
        False where an axis is at the rail (within 0.2 %).
    rail : float or None

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import saturation_mask
    >>> t = np.linspace(0.0, 1.0, 101)
    >>> w = np.column_stack([40.0 * np.sin(2 * np.pi * t), np.cos(t), np.zeros_like(t)])
    >>> clipped = np.clip(w, -34.9, 34.9)   # a gyroscope's 2000 deg/s rail
    >>> keep, rail = saturation_mask(clipped)
    >>> rail, bool(keep[:, 1:].all())   # found from the data
    (34.9, True)
    >>> bool(np.array_equal(~keep[:, 0], np.abs(w[:, 0]) >= 0.998 * 34.9))   # left out: the samples within 0.2 % of it
    True
    >>> saturation_mask(w)[1] is None   # a smooth maximum is no rail
    True
    """
    a = np.abs(np.asarray(omega, float))
    rail = saturation
    if rail is None:
        top = float(a.max()) if a.size else 0.0
        at = np.count_nonzero(a >= (1.0 - 1e-9) * top)
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


def fit_rotation(t: ArrayLike, omega_measured: ArrayLike, *, sensor_rotation: str = "fit", bias: bool = True, drag: str = "auto",
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
        The aerodynamic drag about each principal axis (:mod:`tumble.dynamics.models.drag`): fitted as
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

    Warns
    -----
    InadequateFitWarning
        When the model does not describe the data (:attr:`RotationFit.adequate` is False, the
        reason in :attr:`RotationFit.adequacy`; :mod:`tumble.analysis.fit.adequacy`).

    Notes
    -----
    An optimum on an edge of the triangle (a planar or symmetric body) is a result, reported in
    :attr:`RotationFit.edge` with a one-sided interval; a parameter the data cannot determine is
    named in :attr:`RotationFit.undetermined` and the rest are fitted.

    Examples
    --------
    >>> from tumble.analysis.fit.single import fit_rotation
    >>> import numpy as np
    >>> from tumble.dynamics.methods.exact import FreeRotation
    >>> from scipy.spatial.transform import Rotation
    >>> t = np.linspace(0.0, 10.0, 1001)
    >>> w = FreeRotation([0.3, 0.7, 1.0], [0.2, 5.0, 0.3], Rotation.identity()).omega(t)
    >>> fit = fit_rotation(t, w, sensor_rotation="identity", bias=False, drag="none")
    >>> np.round(fit.ratios, 6).tolist()
    [0.3, 0.7]
    """
    _check_options(sensor_rotation, drag, saturation, scale_uncertainty)
    if isinstance(max_nfev, bool) or not isinstance(max_nfev, Integral) or max_nfev < 1:
        raise ValueError(f"max_nfev = {max_nfev!r} must be a positive integer (function evaluations)")
    t, omega = _check(t, omega_measured)
    keep, _ = saturation_mask(omega, saturation)
    if np.count_nonzero(np.all(keep, axis=1)) < MIN_SAMPLES:
        raise ValueError(f"only {np.count_nonzero(np.all(keep, axis=1))} samples are below the gyroscope's rail; "
                         f"give at least {MIN_SAMPLES} unsaturated samples")
    _check_not_steady(omega[np.all(keep, axis=1)])
    sol = fit_solution(t, omega, keep, rotation=sensor_rotation == "fit", bias=bool(bias), drag=drag,
                       guess=initial_guess, max_nfev=max_nfev, scale_uncertainty=scale_uncertainty)
    fit = rotation_fit(sol, t, omega, keep)
    if not fit.adequate:
        warnings.warn(fit.adequacy, InadequateFitWarning, stacklevel=2)
    return fit


def fit_solution(t: np.ndarray, omega: np.ndarray, keep: np.ndarray, *, rotation: bool = True, bias: bool = True,
                 drag: str = "auto", guess: dict[str, Any] | None = None, P0: np.ndarray | None = None,
                 drag0: ArrayLike | None = None, t0: float | None = None, max_nfev: int = 100,
                 scale_uncertainty: float = SCALE_UNCERTAINTY, covariance: bool = True) -> Solution:
    """The solved model of one flight (checked inputs; ``keep`` the unsaturated sample axes).

    ``P0``: drag-free parameters to start from instead of the automatic starting values (and
    ``drag0`` the quadratic drag's), with ``omega0`` at time ``t0`` (default ``t[0]``; samples before it are fitted backward in time:
    near the separatrix re-anchoring ``omega0`` at another sample would move it across).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
    >>> sol = fit_solution(t, w, np.ones(w.shape, bool), rotation=False, bias=False, drag="none")
    >>> sol.model.moments(sol.P).round(2).tolist()   # the automatic start finds I1/I3 = 0.5, I2/I3 = 0.8
    [0.5, 0.8, 1.0]
    """
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
    x, y = (float(v) for v in _guess_entry(guess, "ratios", 2, "(I1/I3, I2/I3)"))
    if not (0.5 <= y <= 1.0 and 1.0 - y <= x <= y):
        raise ValueError(f"initial_guess ratios = ({x}, {y}) must satisfy I1 <= I2 <= I3 and I1 + I2 >= I3")
    rv = _guess_entry(guess, "rotvec", 3, "rad") if "rotvec" in guess else np.zeros(3)
    R = Rotation.from_rotvec(rv).as_matrix()
    b = _guess_entry(guess, "bias", 3, "rad/s") if "bias" in guess else np.zeros(3)
    w0 = _guess_entry(guess, "omega0", 3, "rad/s") if "omega0" in guess else R @ (omega[0] - b)
    return model.pack(*square(x, y), rv, b, w0[None])


def _guess_entry(guess: dict[str, Any], key: str, size: int, unit: str) -> np.ndarray:
    """``initial_guess[key]`` as ``size`` finite numbers, or one ValueError naming it."""
    try:
        v = np.asarray(guess[key], float)
    except (TypeError, ValueError):
        v = None
    if v is None or v.shape != (size,) or not np.all(np.isfinite(v)):
        raise ValueError(f"initial_guess {key} = {guess[key]!r} must be {size} finite numbers ({unit})")
    return v
