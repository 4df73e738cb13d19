"""A whole recording, or several of one body: free flights fitted one by one and jointly (:func:`fit_recording`).

The flights (:func:`~tumble.analysis.fit.flights.find_flights`) share the body and the sensor,
so the joint model (:func:`~tumble.analysis.fit.joint.joint_solution`) shares the ratios and the
drag over every flight, the sensor's rotation and bias over the flights of one recording, and
gives each flight its own ``omega0``. Several recordings (a list of them) are pooled in one joint
fit: the ratios and the drag shared by all, the rotation and the bias each recording's own (a
phone strapped on again, a gyroscope started again).

A flight that follows a free motion but does not determine both ratios alone (too little of
the tumble, a stable axis, a fit run to the rod limit:
:attr:`~tumble.analysis.fit.flights.Flight.joinable`) still constrains the body's ratios with
the others: the joint fit takes it when its recording has a flight that determines them and the
joint fit describes its samples (:func:`_joined`); its toss is ``"ok"``, its reason "used in the
joint fit only: ..." (its own ratios, stated with it, are not determined).

The pooled uncertainty: the joint fit's covariance (each flight's residuals scaled for their own
autocorrelation; flights independent of one another), its statistical part multiplied by the
Birge ratio squared ``chi^2 / dof`` when the flights' own ratios scatter about the pooled ones
more than their statistical uncertainties allow (:func:`~tumble.analysis.fit.uncertainty.birge_chi2`),
plus the gyroscope's scale-factor part, which no number of flights averages away.

The verdicts are the flights': each flight's rigidity and adequacy by its own fit
(:func:`~tumble.analysis.fit.find_flights`), the joint fit's residuals judged flight by flight
(:func:`~tumble.analysis.fit.adequacy.judge_flights`), so that a file whose flights pass gives an
answer. A joint fit whose ratios lie outside its flights' own values (every flight's more than
:data:`~tumble.analysis.fit.disagreement.OUTSIDE_SIGMAS` of its standard uncertainties away, on one side) says so in its caveat and
names the flight that pulls it (:func:`~tumble.analysis.fit.disagreement.outside_caveat`). The same recording given twice (the same
samples, :func:`samples_sha256`) is refused.
"""

from __future__ import annotations

import math
import os
import warnings
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np

from ...dynamics.environment.earth import STANDARD_GRAVITY
from ...typing import ArrayLike, FloatArray
from .adequacy import InadequateFitWarning, judge, judge_flights
from .disagreement import outside_caveat, split_verdict
from .flightmodel import FlightModel
from .flights import Flight, find_flights
from .segments import pause_times
from .joint import first_flight_view, joint_solution, stack_flights
from .result import (
    RotationFit,
    public_covariance,
    rotation_fit,
)
from .single import MAX_RATE, _check, _check_options, saturation_mask
from .solve import Solution, without_drag_law_error
from .summary import flight_budgets, ratio_scale_effect
from .tosses import RecordingFit, Toss
from .uncertainty import SCALE_UNCERTAINTY, birge_chi2, noise_floor

__all__ = ["DEG_S_HINT_RATE", "NoFlightError", "fit_recording", "unit_hint"]

#: A rate no MEMS gyroscope reads, rad/s (4000 deg/s, twice a phone's full scale): a recording past it is most
#: likely in deg/s under a header that does not say so, and its failure or its fit says that (:func:`_unit_slip`).
DEG_S_HINT_RATE = math.radians(4000.0)


def unit_hint(omega: FloatArray) -> str:
    """The hint that rates past :data:`DEG_S_HINT_RATE` may be in deg/s, or that rates near 9.81 in most samples are an
    accelerometer's (gravity at rest); or ``""``.

    It begins ``"; the rates reach"`` and asks ``"are they in deg/s?"``: for a failure's or a fit's
    reason, or a warning.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.recording import unit_hint
    >>> unit_hint(np.array([[0.0, 12.0, 3.0]]))   # rad/s
    ''
    >>> unit_hint(np.array([[0.0, 690.0, 170.0]])).split(":")[0]   # deg/s under a header without a unit
    "; the rates reach 710.6 rad/s, beyond any MEMS gyroscope's range (4000 deg/s = 69.81 rad/s)"
    >>> unit_hint(np.array([[0.0, 1e308, 0.0]]))   # no reading at all (the fit refuses it as such): no hint
    ''
    >>> unit_hint(np.tile([0.1, -0.2, 9.8], (100, 1)))[:59]   # an accelerometer on a table
    '; |omega| stays within 0.5 of 9.81 in 100 % of the samples,'
    """
    top = float(np.max(np.abs(omega), initial=0.0))
    if not top <= MAX_RATE:  # beyond any reading at all (refused as such by the fit): no unit to hint
        return ""
    size = np.linalg.norm(omega, axis=1)
    close = np.abs(size - STANDARD_GRAVITY) < 0.5
    near = float(np.mean(close)) if len(size) else 0.0
    # an accelerometer's file: gravity's 9.8 m/s^2 at rest, one direction (a walkthrough's "30 s steady spin");
    # not a body tumbling at ~10 rad/s, whose omega turns (the T-handle's flips: its mean far below 9.8)
    if near > 0.6 and float(np.linalg.norm(np.mean(omega[close], axis=0))) > 0.95 * STANDARD_GRAVITY:
        return (f"; |omega| stays within 0.5 of 9.81 in {100 * near:.0f} % of the samples, as an accelerometer reads "
                "gravity at rest: is this the accelerometer's file? Give the gyroscope's")
    peak = float(np.max(size, initial=0.0))
    if not peak > DEG_S_HINT_RATE:
        return ""
    return (f"; the rates reach {peak:.4g} rad/s, beyond any MEMS gyroscope's range (4000 deg/s = "
            f"{DEG_S_HINT_RATE:.4g} rad/s): are they in deg/s? Name the unit in the header (\"gyro_x (deg/s)\"; "
            f"correct it where it says rad/s) or convert them to rad/s")


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


def fit_recording(t: ArrayLike | Sequence[tuple], omega_measured: ArrayLike | None = None, *,
                  events: Sequence[tuple[str, float]] | None = None, sensor_rotation: str = "fit", bias: bool = True,
                  drag: str = "auto", saturation: float | None = None,
                  scale_uncertainty: float = SCALE_UNCERTAINTY, min_spin: float = 3.0, max_std: float = 0.1,
                  progress: Callable[[int, int], None] | None = None, accel: ArrayLike | None = None) -> RecordingFit:
    """Find the free flights of a whole recording (or of several), fit each, and fit them jointly.

    Parameters
    ----------
    t : array_like, shape (n,), or list of recordings
        Sample times, s, strictly increasing (phyphox's experiment time). Or, with
        ``omega_measured`` left out, several recordings of one body: a list of ``(t, omega)`` or
        ``(t, omega, events)``, pooled in one joint fit (module docstring): the ratios and the
        drag shared by every flight, the sensor's rotation and bias by the flights of each
        recording, ``omega0`` each flight's own.
    omega_measured : array_like, shape (n, 3)
        Gyroscope samples, sensor axes, rad/s.
    events : list of (str, float), optional
        phyphox's START/PAUSE events (``meta/time.csv``), experiment time in s (one recording;
        for several, each recording's third item).
    sensor_rotation, bias, drag, saturation, scale_uncertainty
        As for :func:`tumble.analysis.fit.fit_rotation`.
    min_spin : float
        ``|omega|`` above which a stretch may be a flight, rad/s.
    max_std : float
        Largest standard uncertainty of a ratio for a flight to be used.
    progress : callable, optional
        ``progress(done, total)`` after each stretch examined.
    accel : array_like, shape (n, 3), optional
        The accelerometer's specific force at the times ``t``, sensor axes, m/s^2 (one recording;
        for several, each recording's fourth item, ``(t, omega, events, accel)``, None where a
        recording has none): the flights are cut to their free fall
        (:func:`~tumble.analysis.fit.flights.find_flights`) and each toss states the sensor's
        offset from the centre of mass.

    Returns
    -------
    RecordingFit
        Each :class:`Toss` names its recording (``Toss.recording``, the index in the list).

    Raises
    ------
    ValueError
        Bad input (as :func:`~tumble.analysis.fit.fit_rotation`; of several recordings, naming
        which), or one recording given twice (the same samples: :func:`samples_sha256`).
    NoFlightError
        No usable flight (a ``ValueError`` too): one line saying what was found and why each was
        skipped.

    Examples
    --------
    >>> from tumble.analysis.fit.recording import fit_recording
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(2, tosses=3)
    >>> fit = fit_recording(rec.t, rec.omega, events=rec.events)
    >>> fit.tosses_used, bool(abs(fit.pooled.ratios[1] - rec.ratios[1]) < 3 * fit.pooled.ratios_std[1])
    (3, True)

    Two recordings of one body, pooled (a phone strapped on anew: its own mount and bias):

    >>> a, b = synthetic_recording(11, tosses=2, flight=(0.5, 0.8)), synthetic_recording(12, tosses=1, flight=(0.5, 0.8))
    >>> both = fit_recording([(a.t, a.omega, a.events), (b.t, b.omega, b.events)])
    >>> both.tosses_used, [toss.recording for toss in both.tosses], both.summary()["pooled"]["per_recording"]
    (3, [0, 0, 1], ['sensor_rotation', 'bias'])
    """
    _check_options(sensor_rotation, drag, saturation, scale_uncertainty)
    recordings = _recordings(t, omega_measured, events, accel)
    rotation = sensor_rotation == "fit"
    parts, flights, groups, offset, done = [], [], [], 0, [0]
    seen: dict[str, int] = {}
    for r, (t_r, w_r, ev_r, acc_r) in enumerate(recordings):
        try:
            t_r, w_r = _check(t_r, w_r)
        except ValueError as err:
            raise (ValueError(f"recording {r}: {err}") if len(recordings) > 1 else err) from None
        digest = samples_sha256(t_r, w_r)
        if digest in seen:  # its flights counted twice: the pooled std too small by sqrt(2)
            raise ValueError(f"recording {r}: the same samples as recording {seen[digest]} (SHA-256 {digest[:12]}); "
                             "a recording given twice counts its flights twice: give each recording once")
        seen[digest] = r
        keep_r, rail = saturation_mask(w_r, saturation)
        base = done[0]

        def step(k, total, base=base):
            done[0] = base + total
            if progress is not None:
                progress(base + k, base + total)

        try:
            found = find_flights(t_r, w_r, events=ev_r, saturation=rail, min_spin=min_spin, max_std=max_std,
                                 drag=drag, rotation=rotation, bias=bool(bias), progress=step,
                                 scale_uncertainty=scale_uncertainty, accel=acc_r)
        except ValueError as err:
            raise (ValueError(f"recording {r}: {err}") if len(recordings) > 1 else err) from None
        flights += [replace(f, first=f.first + offset, stop=f.stop + offset) for f in found]
        groups += [r] * len(found)
        parts.append((t_r, w_r, keep_r, ev_r))
        offset += len(t_r)
    t, omega, keep = (np.concatenate([p[k] for p in parts]) for k in range(3))
    series = tuple((p[0], p[1]) for p in parts)
    tosses = tuple(_toss(f, t, omega, keep, r) for f, r in zip(flights, groups))
    used = [f for f in flights if f.status == "ok"]
    if not used:
        if not flights:
            where = f"{len(t)} samples over {parts[0][0][-1] - parts[0][0][0]:.3g} s" if len(parts) == 1 else \
                f"{len(t)} samples in {len(parts)} recordings"
            pauses = sum(len(pause_times(p[3])) for p in parts)
            raise NoFlightError(f"no free flight found: |omega| never stays above {min_spin} rad/s for a flight "
                                f"({where}, {pauses} pauses){unit_hint(omega)}")
        why = Counter(f.reason.split(":")[0].split(" (")[0] for f in flights)
        said = ", ".join(f"{n} {r}" for r, n in why.most_common()) if len(flights) > 1 else flights[0].reason  # one: whole
        raise NoFlightError(f"no usable flight among {len(flights)} found: {said}{unit_hint(omega)}")
    t0, w0 = series[0]
    joined, first_joint = _joined(flights, groups, t, omega, keep, drag, scale_uncertainty)
    if joined:
        tosses = list(tosses)
        for j in joined:
            flights[j] = replace(flights[j], status="ok", reason=f"{JOINT_ONLY}: {flights[j].reason}")
            tosses[j] = _toss(flights[j], t, omega, keep, groups[j])
        tosses = tuple(tosses)
        used = [f for f in flights if f.status == "ok"]
    number = {id(f): k for k, f in enumerate(flights)}  # a flight's index in the tosses
    if len(used) == 1:
        k = number[id(used[0])]
        only, sol = tosses[k], used[0].solution
        own = _flight_models(None, used, [k], groups)
        return _unit_slip(RecordingFit(tosses, only.fit, float("nan"), 1, t0, w0, (only.fit.omega_model,), series,
                                       sol.ssr, sol.m, own), omega)
    used_groups = [r for f, r in zip(flights, groups) if f.status == "ok"]
    joint, models, outliers = first_joint or joint_solution(used, used_groups, t, omega, keep, drag, scale_uncertainty)
    split = split_verdict(used, used_groups, outliers)
    bad = {id(used[j]) for j in outliers}  # by identity: the list below may lose the flights joined
    if joint is None and joined:  # no joint fit to use them in: skipped after all, with their own reasons
        for j in joined:
            flights[j] = replace(flights[j], status="skipped", reason=flights[j].reason[len(JOINT_ONLY) + 2:])
        tosses = tuple(replace(toss, status="skipped", reason=flights[j].reason) if j in joined else toss
                       for j, toss in enumerate(tosses))
        used = [f for f in flights if f.status == "ok"]
    if bad:
        tosses = tuple(
            replace(toss, status="skipped", reason=(
                "disagrees with the other flights: its own ratios lie more than five standard uncertainties "
                f"from theirs (I1/I3 = {toss.fit.ratios[0]:.4f}, I2/I3 = {toss.fit.ratios[1]:.4f})"))
            if id(f) in bad else toss for toss, f in zip(tosses, flights))
        used = [f for f in used if id(f) not in bad]
    fit = _weighted(used, tosses, t, omega, keep) if joint is None else \
        _pooled(joint, used, tosses, t, omega, keep, models)
    fit = replace(fit, t=t0, omega=w0, recordings=series,
                  flight_models=_flight_models(joint, used, [number[id(f)] for f in used], groups))
    outside = outside_caveat(fit, used, [number[id(f)] for f in used], omega, keep, joint is not None)
    if outside:
        fit = replace(fit, pooled=replace(fit.pooled, caveat="; ".join(filter(None, (fit.pooled.caveat, outside)))))
    if split:
        warnings.warn(f"pooled fit: {split}", InadequateFitWarning, stacklevel=2)
        fit = replace(fit, pooled=replace(fit.pooled, adequate=False, adequacy=split))
    return _unit_slip(fit, omega)


def _unit_slip(fit: RecordingFit, omega: FloatArray) -> RecordingFit:
    """``fit``, not adequate and saying why, where its rates pass :data:`DEG_S_HINT_RATE` (deg/s read as rad/s fit
    flights within a flexing body's relative misfit: 2 of 5, "adequate", I1/I3 = 0.98 for 0.20; a walkthrough)."""
    hint = unit_hint(omega)
    why = "; ".join(filter(None, (hint[2:], fit.pooled.adequacy)))
    return replace(fit, pooled=replace(fit.pooled, adequate=False, adequacy=why)) if hint else fit


#: The reason's first words of a flight used in the joint fit only (:func:`_joined`).
JOINT_ONLY = "used in the joint fit only"


def _joined(flights, groups, t, omega, keep, drag, scale_uncertainty) -> tuple[list[int], tuple | None]:
    """The joinable flights (:attr:`~tumble.analysis.fit.flights.Flight.joinable`: a free motion
    whose ratios it does not determine alone) that the joint fit takes, and that joint fit's
    result when it is the one to keep (every candidate taken).

    A flight's ratios are the body's, so a flight that follows a free motion constrains them
    jointly with the others even when it cannot fix both alone (a likelihood is a product over
    flights). It is taken when its recording has a flight that determines them, and when the
    joint fit of that recording's flights describes its samples by the test every fit meets
    (:func:`~tumble.analysis.fit.adequacy.judge`: the residuals beyond the noise within
    :data:`~tumble.analysis.fit.adequacy.MISFIT_LIMIT` of the rates): its samples follow a free
    motion of this body, with this recording's mount, bias and drag, not only of some body; and
    when its energy and momentum budgets, with the joint fit's moments, are a rigid body's
    (:func:`~tumble.analysis.fit.summary.flight_budgets`: its own fit could not tell, its
    moments not determined)."""
    ok = [j for j, f in enumerate(flights) if f.status == "ok"]
    groups_ok = {groups[j] for j in ok}
    candidates = [j for j, f in enumerate(flights) if f.joinable and groups[j] in groups_ok]
    if not candidates:
        return [], None
    taken, whole = [], None
    for r in sorted({groups[j] for j in candidates}):  # judged with its own recording's flights (fast when pooling)
        idx = sorted(j for j in ok + candidates if groups[j] == r)
        sol, models, outliers = joint_solution([flights[j] for j in idx], [r] * len(idx), t, omega, keep, drag,
                                               scale_uncertainty)
        if sol is None:
            continue
        kept = [j for k, j in enumerate(idx) if k not in outliers]
        for p, (j, model) in enumerate(zip(kept, models)):
            f = flights[j]
            if j in candidates:
                w, mask = omega[f.first:f.stop], keep[f.first:f.stop]
                residuals = model - w
                verdict = judge(float(np.sqrt(np.mean(residuals[mask] ** 2))),
                                noise_floor(residuals[np.all(mask, axis=1)]), float(np.sqrt(np.mean(w[mask] ** 2))),
                                sensor_rotation_fitted=sol.model.rotation)
                # and its budgets with the joint fit's moments, which are determined where its own were not
                if verdict.adequate and not flight_budgets(sol, p, w, mask):
                    taken.append(j)
        if len(idx) == len(ok) + len(candidates):  # every flight in this one recording: the joint fit itself
            whole = (sol, models, outliers)
    return taken, (whole if len(taken) == len(candidates) else None)


def _recordings(t, omega, events, accel=None) -> list:
    """``[(t, omega, events, accel), ...]``: the one recording, or the list given (``omega`` None)."""
    if omega is not None:
        return [(t, omega, events, accel)]
    if events is not None or accel is not None:
        raise ValueError(f"{'events' if events is not None else 'accel'} go with each recording of a list, as its "
                         f"{'third' if events is not None else 'fourth'} item, not as "
                         f"{'events' if events is not None else 'accel'}=")
    if isinstance(t, (str, os.PathLike)):
        raise ValueError(f"t = {os.fspath(t)!r} is a file's name: read it first, t, omega, events = "
                         "tumble.io.gyrodata.read_recording(path) (a phyphox export or a CSV of t, wx, wy, wz)")
    try:
        items = list(t)
    except TypeError:
        raise ValueError("omega_measured is missing: give t and omega_measured, or a list of recordings "
                         "(t, omega) or (t, omega, events)") from None
    if not items:
        raise ValueError("an empty list of recordings; give at least one (t, omega) or (t, omega, events)")
    out = []
    for r, item in enumerate(items):
        if not isinstance(item, (tuple, list)) or len(item) not in (2, 3, 4):
            raise ValueError(f"recording {r}: expected (t, omega), (t, omega, events) or (t, omega, events, accel), got "
                             f"{type(item).__name__}" + (f" of {len(item)} items" if isinstance(item, (tuple, list)) else ""))
        out.append((item[0], item[1], item[2] if len(item) >= 3 else None, item[3] if len(item) == 4 else None))
    return out


def samples_sha256(t: np.ndarray, omega: np.ndarray) -> str:
    """SHA-256 of a recording's samples (times and rates as float64): the same recording, however
    it was given (a copy, a symlink, its zip and its folder), hashes the same.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.recording import samples_sha256
    >>> t, w = np.arange(3.0), np.ones((3, 3))
    >>> samples_sha256(t, w) == samples_sha256(t.copy(), w.copy()), samples_sha256(t, w) == samples_sha256(t, 2 * w)
    (True, False)
    """
    import hashlib

    h = hashlib.sha256(np.ascontiguousarray(t, dtype=np.float64).tobytes())
    h.update(np.ascontiguousarray(omega, dtype=np.float64).tobytes())
    return h.hexdigest()


def _flight_models(sol: Solution | None, used, numbers, groups) -> tuple:
    """Each used flight's :class:`FlightModel`: of the joint solution ``sol`` (its flights are
    ``used``, in order), or of the flight's own solution where there is none."""
    return tuple(FlightModel.of_solution(*((sol, j) if sol is not None else (f.solution, 0)), start=f.start, end=f.end,
                                         t0=f.anchor, recording=groups[k], toss=k)
                 for j, (f, k) in enumerate(zip(used, numbers)))


def _toss(f: Flight, t, omega, keep, recording: int = 0) -> Toss:
    fit = None
    if f.solution is not None and f.status == "ok":
        sl = slice(f.first, f.stop)
        fit = rotation_fit(f.solution, t[sl], omega[sl], keep[sl], t0=f.anchor)
    span = f.free_fall if f.free_fall is not None and f.free_fall.free else None
    return Toss(f.start, f.end, f.samples, f.status, f.reason, fit, recording,
                None if span is None else tuple(float(v) for v in span.offset),
                None if span is None else tuple(float(v) for v in span.offset_std))


def _pooled(sol: Solution, used, tosses, t, omega, keep, models) -> RecordingFit:
    own = [f for f in used if not f.joinable] or used  # the flights used in the joint fit only state no ratios
    values, covs, shared = _own_ratios(own)
    chi2, dof = birge_chi2(values, covs, shared=shared)
    chi2_dof = chi2 / dof if len(values) > 1 else float("nan")  # one flight's own ratios: no scatter to measure
    scale = max(1.0, chi2_dof) if len(values) > 1 else 1.0
    # inflate the statistical part by chi2/dof, keep the systematic part as it is
    cov = sol.cov_stat * scale + (np.nan_to_num(sol.cov) - np.nan_to_num(sol.cov_stat))
    inflated = replace(sol, cov=cov, cov_stat=sol.cov_stat * scale)
    first = used[0]
    sl = slice(first.first, first.stop)
    one = first_flight_view(inflated)
    pooled = rotation_fit(one, t[sl], omega[sl], keep[sl], t0=first.anchor)
    # judged flight by flight on the joint fit's residuals, not the first flight's view of them
    data, mask = stack_flights(used, omega, keep)
    verdict = judge_flights(data, sol.omega_model, mask, sol.model.lengths, [f.start for f in used])[0]
    # the joint fit's sample count and sample axes at the rail (its times, model and residuals shown are the
    # first flight's view)
    pooled = replace(pooled, adequate=verdict.adequate, adequacy=verdict.reason, misfit=verdict.misfit,
                     samples=int(sum(f.samples for f in used)),
                     saturated=_at_rail(used, keep))
    if not verdict.adequate:
        warnings.warn(f"pooled fit: {verdict.reason}", InadequateFitWarning, stacklevel=3)
    return RecordingFit(tosses, pooled, chi2_dof, len(used), t, omega, tuple(models), (), sol.ssr, sol.m)


def _at_rail(used, keep) -> int:
    """The sample axes at the gyroscope's rail in the flights ``used``, all of them (a pooled fit's
    ``saturated``; the first flight's only was fit.json's 0 of a pool whose second flight had 70)."""
    return int(sum(np.count_nonzero(~keep[f.first:f.stop]) for f in used))


def _own_ratios(flights) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The flights' own ratios, their statistical covariances and their answers to the gyroscope's
    common scale error (:func:`~tumble.analysis.fit.summary.ratio_scale_effect`), for :func:`birge_chi2`."""
    own = [public_covariance(f.solution, statistical=True) for f in flights]
    return (np.array([v[:2] for _, v, _ in own]), np.array([c[:2, :2] for _, _, c in own]),
            np.array([ratio_scale_effect(f.solution) for f in flights]))


def _weighted(used, tosses, t, omega, keep) -> RecordingFit:
    """The pooled ratios as the flights' inverse-covariance weighted mean (when the joint fit
    cannot be made): statistical covariance scaled by the Birge ratio squared, the systematic part the
    flights' mean (it is common to them, not averaged down) without the drag law's model
    error, as the joint fit's (:mod:`~tumble.analysis.fit.joint`)."""
    used = [f for f in used if not f.joinable] or used  # a weighted mean of the flights' own ratios
    values, stats, shared = _own_ratios(used)
    totals = np.array([public_covariance(without_drag_law_error(f.solution))[2][:2, :2] for f in used])
    W = np.array([np.linalg.pinv(c) for c in stats])
    cov_stat = np.linalg.pinv(W.sum(axis=0))
    mean = cov_stat @ np.einsum("fij,fj->i", W, values)
    chi2, dof = birge_chi2(values, stats, shared=shared)
    cov = cov_stat * max(1.0, chi2 / dof) + np.mean(totals - stats, axis=0)
    ref = next(toss for toss in tosses if toss.status == "ok" and toss.fit is not None)
    std = np.minimum(np.sqrt(np.diag(cov)), (0.5, 0.25))
    iv = np.array([[max(0.0, mean[0] - 1.96 * std[0]), min(1.0, mean[0] + 1.96 * std[0])],
                   [max(0.5, mean[1] - 1.96 * std[1]), min(1.0, mean[1] + 1.96 * std[1])]])
    # the ratios' block is the mean's; their covariance with the reference flight's other parameters is
    # no one's (NaN), not the reference flight's own (that gave a correlation of -2.9 beside the mean's stds)
    full = np.full_like(ref.fit.covariance, np.nan)
    full[:2, :2], full[2:, 2:] = cov, ref.fit.covariance[2:, 2:]
    pooled = replace(ref.fit, ratios=mean, ratios_std=std, ratios_interval=iv, edge=None, covariance=full,
                     samples=int(sum(f.samples for f in used)),
                     saturated=_at_rail(used, keep))
    return RecordingFit(tosses, pooled, chi2 / dof if len(used) > 1 else float("nan"), len(used), t, omega,
                        tuple(toss.fit.omega_model for toss in tosses if toss.status == "ok"), (),
                        float(sum(f.solution.ssr for f in used)), int(sum(f.solution.m for f in used)))
