"""A whole recording: its free flights fitted one by one and jointly (:func:`fit_recording`).

The flights (:func:`~tumble.analysis.fit.flights.find_flights`) share the body and the sensor,
so the joint model (:class:`~tumble.analysis.fit.model.Model` with ``F`` flights) shares the
ratios, the sensor's rotation and bias and the drag, and gives each flight its own ``omega0``.
It starts from the flight whose ratios are nearest the flights' medians (the others' ``omega0``
turned into its principal frame) and keeps the drag model most flights chose.

The pooled uncertainty: the joint fit's covariance (each flight's residuals scaled for their own
autocorrelation; flights independent of one another), its statistical part multiplied by the
Birge ratio squared ``chi^2 / dof`` when the flights' own ratios scatter about the pooled ones
more than their statistical uncertainties allow (:func:`~tumble.analysis.fit.uncertainty.birge_chi2`),
plus the gyroscope's scale-factor part, which no number of flights averages away.
"""

from __future__ import annotations

import warnings
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike
from .adequacy import InadequateFitWarning
from .flights import Flight, find_flights, pause_times
from .model import Model
from .result import (
    RotationFit,
    public_covariance,
    ratio_summary,
    rotation_fit,
    solution_adequacy,
)
from .single import _check, _check_options, saturation_mask
from .solve import Solution, solve
from .uncertainty import SCALE_UNCERTAINTY, birge_chi2

__all__ = ["NoFlightError", "RecordingFit", "Toss", "fit_recording"]


class NoFlightError(ValueError):
    """A well-formed recording from which no flight could be fitted: none found, or every one skipped.

    The computation failed, the input was readable (``tumble fit`` exits with status 1, not 2);
    a ``ValueError`` still, so that code catching that keeps working.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.recording import NoFlightError, fit_recording
    >>> t = np.linspace(0.0, 10.0, 1001)
    >>> try:
    ...     fit_recording(t, np.zeros((1001, 3)))   # a phone lying still
    ... except NoFlightError as error:
    ...     print(error)
    no free flight found: |omega| never stays above 3.0 rad/s for a flight (1001 samples over 10 s, 0 pauses)
    >>> issubclass(NoFlightError, ValueError)
    True
    """


@dataclass(frozen=True)
class Toss:
    """One flight of a recording: where it is, and its own fit or why it was skipped.

    Attributes
    ----------
    start, end : float
        First and last sample's time, s.
    samples : int
    status : str
        ``"ok"`` (fitted and used in the pooled fit) or ``"skipped"``.
    reason : str
    fit : RotationFit or None
        The flight's own fit (None when there was none).

    Examples
    --------
    >>> from tumble.analysis.fit.recording import Toss, fit_recording
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(22, tosses=2, flight=(0.5, 0.8))
    >>> ok, skipped = fit_recording(rec.t, rec.omega, events=rec.events).tosses
    >>> ok.status, ok.fit is not None, skipped.status, skipped.reason.startswith("no free flight")
    ('ok', True, 'skipped', True)
    """

    start: float
    end: float
    samples: int
    status: str
    reason: str
    fit: RotationFit | None = field(default=None, repr=False)

    def summary(self) -> dict:
        """The row of ``tosses.csv`` and of fit.json's ``"tosses"`` (NaN written as None).

        Examples
        --------
        >>> from tumble.analysis.fit.recording import Toss
        >>> row = Toss(start=1.0, end=1.8, samples=81, status="skipped", reason="too short").summary()
        >>> row["samples"], row["I1_over_I3"], row["status"]   # no fit: its numbers are None
        (81, None, 'skipped')
        """
        f = self.fit

        def num(v):
            return None if v is None or not np.isfinite(v) else float(v)

        return {"start": self.start, "end": self.end, "samples": self.samples,
                "I1_over_I3": num(f.ratios[0]) if f else None, "I2_over_I3": num(f.ratios[1]) if f else None,
                "I1_over_I3_std": num(f.ratios_std[0]) if f else None,
                "I2_over_I3_std": num(f.ratios_std[1]) if f else None,
                "residual_rms": num(f.residual_rms) if f else None, "status": self.status, "reason": self.reason}


@dataclass(frozen=True)
class RecordingFit:
    """The flights of a recording and the body's ratios pooled over them.

    Attributes
    ----------
    tosses : tuple of Toss
        Every flight found, usable or not, in time order.
    pooled : RotationFit
        The joint fit's ratios, sensor rotation, bias and drag (its ``omega0`` and
        ``omega_model`` are those of the first flight used).
    chi2_dof : float
        ``chi^2 / dof`` of the flights' ratios about the pooled ones (statistical uncertainties).
    tosses_used : int
    t, omega : ndarray
        The whole recording (s; rad/s, sensor axes).
    omega_models : tuple of ndarray
        The joint model at each used flight's samples, sensor axes, rad/s.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.recording import fit_recording
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
    >>> fit = fit_recording(rec.t, rec.omega, events=rec.events)
    >>> fit.tosses_used, len(fit.omega_models), bool(np.all(np.abs(fit.pooled.ratios - rec.ratios) < 3 * fit.pooled.ratios_std))
    (2, 2, True)
    """

    tosses: tuple
    pooled: RotationFit
    chi2_dof: float
    tosses_used: int
    t: np.ndarray = field(repr=False)
    omega: np.ndarray = field(repr=False)
    omega_models: tuple = field(default=(), repr=False)

    def summary(self) -> dict:
        """JSON-ready: the pooled fit's keys (as :meth:`RotationFit.summary`), ``"tosses"`` and ``"pooled"``.

        Examples
        --------
        >>> import json
        >>> from tumble.analysis.fit.recording import fit_recording
        >>> from tumble.analysis.fit.synthetic import synthetic_recording
        >>> rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
        >>> summary = fit_recording(rec.t, rec.omega, events=rec.events).summary()
        >>> summary["pooled"]["tosses_used"], [toss["status"] for toss in summary["tosses"]], summary["pooled"]["I1_over_I3"] == summary["I1_over_I3"]
        (2, ['ok', 'ok'], True)
        >>> json.loads(json.dumps(summary)) == summary
        True
        """
        p = self.pooled
        out = p.summary()
        out["tosses"] = [toss.summary() for toss in self.tosses]
        out["pooled"] = {"I1_over_I3": float(p.ratios[0]), "I2_over_I3": float(p.ratios[1]),
                         "I1_over_I3_std": float(p.ratios_std[0]), "I2_over_I3_std": float(p.ratios_std[1]),
                         "I1_over_I3_interval": [float(v) for v in p.ratios_interval[0]],
                         "I2_over_I3_interval": [float(v) for v in p.ratios_interval[1]],
                         "edge": p.edge, "tosses_used": int(self.tosses_used),
                         "chi2_dof": float(self.chi2_dof) if np.isfinite(self.chi2_dof) else None}
        return out


def fit_recording(t: ArrayLike, omega_measured: ArrayLike, *, events: Sequence[tuple[str, float]] | None = None, sensor_rotation: str = "fit", bias: bool = True,
                  drag: str = "auto", saturation: float | None = None,
                  scale_uncertainty: float = SCALE_UNCERTAINTY, min_spin: float = 3.0, max_std: float = 0.1,
                  progress: Callable[[int, int], None] | None = None) -> RecordingFit:
    """Find the free flights of a whole recording, fit each, and fit them jointly.

    Parameters
    ----------
    t : array_like, shape (n,)
        Sample times, s, strictly increasing (phyphox's experiment time).
    omega_measured : array_like, shape (n, 3)
        Gyroscope samples, sensor axes, rad/s.
    events : list of (str, float), optional
        phyphox's START/PAUSE events (``meta/time.csv``), experiment time in s.
    sensor_rotation, bias, drag, saturation, scale_uncertainty
        As for :func:`tumble.analysis.fit.fit_rotation`.
    min_spin : float
        ``|omega|`` above which a stretch may be a flight, rad/s.
    max_std : float
        Largest standard uncertainty of a ratio for a flight to be used.
    progress : callable, optional
        ``progress(done, total)`` after each stretch examined.

    Returns
    -------
    RecordingFit

    Raises
    ------
    ValueError
        Bad input (as :func:`~tumble.analysis.fit.fit_rotation`).
    NoFlightError
        No usable flight (a ``ValueError`` too): one line saying what was found and why each was
        skipped.

    Examples
    --------
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(2, tosses=3)
    >>> fit = fit_recording(rec.t, rec.omega, events=rec.events)
    >>> fit.tosses_used, bool(abs(fit.pooled.ratios[1] - rec.ratios[1]) < 3 * fit.pooled.ratios_std[1])
    (3, True)
    """
    _check_options(sensor_rotation, drag, saturation, scale_uncertainty)
    t, omega = _check(t, omega_measured)
    keep, rail = saturation_mask(omega, saturation)
    rotation = sensor_rotation == "fit"
    flights = find_flights(t, omega, events=events, saturation=rail, min_spin=min_spin, max_std=max_std,
                           drag=drag, rotation=rotation, bias=bool(bias), progress=progress,
                           scale_uncertainty=scale_uncertainty)
    tosses = tuple(_toss(f, t, omega, keep) for f in flights)
    used = [f for f in flights if f.status == "ok"]
    if not used:
        if not flights:
            raise NoFlightError(f"no free flight found: |omega| never stays above {min_spin} rad/s for a flight "
                             f"({len(t)} samples over {t[-1] - t[0]:.3g} s, {len(pause_times(events))} pauses)")
        why = Counter(f.reason.split(":")[0].split(" (")[0] for f in flights)
        raise NoFlightError(f"no usable flight among {len(flights)} found: "
                         + ", ".join(f"{n} {r}" for r, n in why.most_common()))
    if len(used) == 1:
        only = next(toss for toss in tosses if toss.status == "ok")
        return RecordingFit(tosses, only.fit, float("nan"), 1, t, omega, (only.fit.omega_model,))
    joint, models, outliers = _joint(used, t, omega, keep, drag, scale_uncertainty)
    split = _split_verdict(used, outliers)
    if outliers:
        bad = {id(used[j]) for j in outliers}
        tosses = tuple(
            Toss(toss.start, toss.end, toss.samples, "skipped",
                 "disagrees with the other flights: its own ratios lie more than five standard uncertainties "
                 f"from theirs (I1/I3 = {toss.fit.ratios[0]:.4f}, I2/I3 = {toss.fit.ratios[1]:.4f})", toss.fit)
            if id(f) in bad else toss for toss, f in zip(tosses, flights))
        used = [f for f in used if id(f) not in bad]
    fit = _weighted(used, tosses, t, omega, keep) if joint is None else \
        _pooled(joint, used, tosses, t, omega, keep, models)
    if split:
        warnings.warn(f"pooled fit: {split}", InadequateFitWarning, stacklevel=2)
        fit = replace(fit, pooled=replace(fit.pooled, adequate=False, adequacy=split))
    return fit


#: Share of the fitted flights that may disagree with the others before the recording counts as
#: holding more than one body: a third (one stray flight in twelve is a toss gone wrong; a third
#: that agree among themselves is another body, a loose phone or a changed mount).
MAX_DISAGREEING = 1.0 / 3.0


def _split_verdict(used, outliers) -> str:
    """The reason a recording's pooled value is no answer, or "" (:data:`MAX_DISAGREEING`)."""
    if len(outliers) < 2 or len(outliers) < MAX_DISAGREEING * len(used):
        return ""
    own = np.array([ratio_summary(used[j].solution)[0] for j in outliers])
    return (f"the flights disagree: {len(outliers)} of {len(used)} fitted flights lie more than five standard "
            f"uncertainties from the others (their ratios I1/I3 {np.min(own[:, 0]):.4f} to {np.max(own[:, 0]):.4f}, "
            f"I2/I3 {np.min(own[:, 1]):.4f} to {np.max(own[:, 1]):.4f}): the recording holds more than one body "
            "or the phone moved on it; fit each group apart (--start/--end)")


def _toss(f: Flight, t, omega, keep) -> Toss:
    fit = None
    if f.solution is not None and f.status == "ok":
        sl = slice(f.first, f.stop)
        fit = rotation_fit(f.solution, t[sl], omega[sl], keep[sl])
    return Toss(f.start, f.end, f.samples, f.status, f.reason, fit)


def _joint(used, t, omega, keep, drag, scale_uncertainty):
    """The joint solution over the used flights (module docstring), the joint model at each
    flight, and the indices of the flights that disagree grossly with the others (their own
    ratios more than five standard uncertainties from the reference flight's): left out.
    The solution is None when fewer than two flights agree or the joint fit went astray."""
    sols = [f.solution for f in used]
    rat = np.array([ratio_summary(s)[0] for s in sols])
    ref = int(np.argmin(np.sum((rat - np.median(rat, axis=0)) ** 2, axis=1)))
    kinds = Counter(s.model.drag for s in sols)
    kind = drag if drag != "auto" else kinds.most_common(1)[0][0]
    m_ref, P_ref = sols[ref].model, sols[ref].P
    R_ref = m_ref.rotation_matrix(P_ref)
    taus, data, mask, speeds = [], [], [], []
    for f in used:
        sl = slice(f.first, f.stop)
        taus.append(t[sl] - f.anchor)
        speeds.append(float(np.max(np.linalg.norm(omega[sl], axis=1))))
    model = Model(taus, m_ref.rotation, m_ref.bias, kind, speeds)
    data, mask = _stack(used, omega, keep)
    w0 = np.array([R_ref @ s.model.rotation_matrix(s.P).T @ s.model.omega0(s.P)[0] for s in sols])
    same = [s.model.drag_vector(s.P) for s in sols if s.model.drag == kind]
    drag0 = np.median(same, axis=0) if same and kind != "none" else np.zeros(3)
    rv = Rotation.from_matrix(R_ref).as_rotvec() if m_ref.rotation else np.zeros(3)
    P0 = model.pack(P_ref[0], P_ref[1], rv, m_ref.bias_vector(P_ref), w0, drag0)
    # each flight's omega0 refitted under the shared parameters: near the separatrix another
    # flight's ratios move a flight onto another mode, and its own omega0 must follow
    agree = []
    for j, f in enumerate(used):
        n = f.stop - f.first
        one = Model([model.tau[j, :n]], model.rotation, model.bias, kind, model.speeds[j:j + 1])
        shared = P0[:model.ns]

        def fun(w, one=one, j=j, n=n, shared=shared):
            return (one.sensor(np.concatenate([shared, w]))[0] - data[j, :n])[mask[j, :n]]

        with np.errstate(all="ignore"):
            fitted = least_squares(fun, P0[model.ns + 3 * j:model.ns + 3 * j + 3], max_nfev=50)
        P0[model.ns + 3 * j:model.ns + 3 * j + 3] = fitted.x
        # a gross outlier: its own ratios five standard uncertainties (its own and the
        # reference's, statistical) from the reference's; the Birge ratio deals with the rest
        dv = rat[j] - rat[ref]
        C = public_covariance(sols[j], statistical=True)[2][:2, :2] + \
            public_covariance(sols[ref], statistical=True)[2][:2, :2]
        agree.append(bool(dv @ np.linalg.pinv(C) @ dv <= 25.0))
    keep_idx = [j for j, ok in enumerate(agree) if ok]
    if len(keep_idx) < len(used):
        if len(keep_idx) < 2:
            return None, [], [j for j in range(len(used)) if not agree[j]]
        sub = [used[j] for j in keep_idx]
        sol, models, _ = _joint(sub, t, omega, keep, drag, scale_uncertainty)
        return sol, models, [j for j in range(len(used)) if not agree[j]]
    sol = solve(model, data, mask, P0, max_nfev=60, scale_uncertainty=scale_uncertainty)
    own = np.sqrt(sum(s.ssr for s in sols) / sum(s.m for s in sols))
    if np.sqrt(sol.ssr / sol.m) > 2.0 * own + 0.01 * np.sqrt(np.mean(data[mask] ** 2)):
        return None, [], []  # the joint fit went astray: the caller pools the flights' own fits
    return sol, [sol.omega_model[j, :f.stop - f.first] for j, f in enumerate(used)], []


def _stack(used, omega, keep):
    """The used flights' samples and kept axes laid out as a joint model's, shape ``(F, T, 3)``."""
    T = max(f.stop - f.first for f in used)
    data = np.zeros((len(used), T, 3))
    mask = np.zeros((len(used), T, 3), bool)
    for j, f in enumerate(used):
        n = f.stop - f.first
        data[j, :n] = omega[f.first:f.stop]
        mask[j, :n] = keep[f.first:f.stop]
    return data, mask


def _pooled(sol: Solution, used, tosses, t, omega, keep, models) -> RecordingFit:
    rat_joint = ratio_summary(sol)[0]
    values, covs = [], []
    for f in used:
        _, v, c = public_covariance(f.solution, statistical=True)
        values.append(v[:2])
        covs.append(c[:2, :2])
    chi2, dof = birge_chi2(np.array(values), np.array(covs), rat_joint)
    scale = max(1.0, chi2 / dof)
    # inflate the statistical part by chi2/dof, keep the systematic part as it is
    cov = sol.cov_stat * scale + (np.nan_to_num(sol.cov) - np.nan_to_num(sol.cov_stat))
    inflated = Solution(sol.model, sol.P, cov, sol.cov_stat * scale, sol.residuals, sol.omega_model,
                        sol.undetermined, sol.nfev, sol.autocorrelation_time, sol.ssr, sol.m)
    first = used[0]
    sl = slice(first.first, first.stop)
    one = _first_flight_view(inflated)
    pooled = rotation_fit(one, t[sl], omega[sl], keep[sl])
    # judged on all the flights' residuals, not the first flight's view of them
    verdict = solution_adequacy(sol, *_stack(used, omega, keep))
    pooled = replace(pooled, adequate=verdict.adequate, adequacy=verdict.reason, misfit=verdict.misfit)
    if not verdict.adequate:
        warnings.warn(f"pooled fit: {verdict.reason}", InadequateFitWarning, stacklevel=3)
    return RecordingFit(tosses, pooled, chi2 / dof, len(used), t, omega, tuple(models))


def _first_flight_view(sol: Solution) -> Solution:
    """The joint solution seen as a one-flight solution (its first flight's omega0 and samples),
    so that :func:`rotation_fit` reports the shared parameters with their pooled covariance."""
    m = sol.model
    keep = list(range(m.ns + 3))
    n = int(m.lengths[0])
    one = Model([m.tau[0, :n]], m.rotation, m.bias, m.drag, m.speeds[:1])
    undetermined = tuple(name for name in sol.undetermined if name in one.names)
    return Solution(one, sol.P[keep], sol.cov[np.ix_(keep, keep)], sol.cov_stat[np.ix_(keep, keep)],
                    sol.residuals, sol.omega_model[:1, :n], undetermined, sol.nfev, sol.autocorrelation_time, sol.ssr, sol.m)


def _weighted(used, tosses, t, omega, keep) -> RecordingFit:
    """The pooled ratios as the flights' inverse-covariance weighted mean (when the joint fit
    cannot be made): statistical part scaled by the Birge ratio, the systematic part the
    flights' mean (it is common to them, not averaged down)."""
    values, stats, totals = [], [], []
    for f in used:
        _, v, c = public_covariance(f.solution, statistical=True)
        _, _, ct = public_covariance(f.solution)
        values.append(v[:2]), stats.append(c[:2, :2]), totals.append(ct[:2, :2])
    values, stats, totals = np.array(values), np.array(stats), np.array(totals)
    W = np.array([np.linalg.pinv(c) for c in stats])
    cov_stat = np.linalg.pinv(W.sum(axis=0))
    mean = cov_stat @ np.einsum("fij,fj->i", W, values)
    chi2, dof = birge_chi2(values, stats, mean)
    cov = cov_stat * max(1.0, chi2 / dof) + np.mean(totals - stats, axis=0)
    ref = next(toss for toss in tosses if toss.status == "ok" and toss.fit is not None)
    std = np.minimum(np.sqrt(np.diag(cov)), (0.5, 0.25))
    iv = np.array([[max(0.0, mean[0] - 1.96 * std[0]), min(1.0, mean[0] + 1.96 * std[0])],
                   [max(0.5, mean[1] - 1.96 * std[1]), min(1.0, mean[1] + 1.96 * std[1])]])
    pooled = replace(ref.fit, ratios=mean, ratios_std=std, ratios_interval=iv, edge=None)
    return RecordingFit(tosses, pooled, chi2 / dof if len(used) > 1 else float("nan"), len(used), t, omega,
                        tuple(toss.fit.omega_model for toss in tosses if toss.status == "ok"))
