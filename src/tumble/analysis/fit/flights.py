"""Finding the free flights in a whole gyroscope recording, from the gyroscope (and its
accelerometer, when the recording has one).

A recording of tosses alternates holds (small, slow rates, or the phone swung about at a few
rad/s), throws (the spin ramps up under the hand's torque), free flights and their ends: a
catch that kills the spin in tens of milliseconds, a catch after which the hand turns the phone
on at 5-20 rad/s, or a landing whose impact turns omega at once and is followed by bounces and
rolling. A free flight is a stretch bounded by impulses in which the samples follow a
torque-free motion (with drag). The search (:func:`find_flights`):

1. **Runs.** The record is cut at phyphox's PAUSE events (after a pause the experiment time
   carries on without a gap, so a jump in omega would otherwise look like a torque) and at gaps
   in the samples longer than ``max_gap``.
2. **Active stretches**: where ``|omega|`` (a 3-sample median) exceeds ``min_spin``; in a free
   flight ``|omega| >= |L| / I3`` never dips to zero, while a hold stays below a rad/s.
3. **Cut at the impulses** (:func:`~tumble.analysis.fit.segments.impulses`): a free rigid body's angular acceleration is at
   most ``|omega|^2 / sqrt(3)``, whatever its moments (the triangle inequality in Euler's
   equations); a sample whose rate changes faster than 1.25 times that, plus 20 rad/s^2, is under
   a torque: the throw's start, a catch, an impact, the hand. The stretch is segmented there
   (a segmentation at change points found from the physics, not fitted; cf. Truong, Oudre &
   Vayatis, "Selective review of offline change point detection methods", *Signal Processing*
   167, 2020); each piece between impulses at least ``min_duration`` long is a candidate, and
   a stretch with none is one candidate, skipped with its reason.
4. **The free part of each candidate.** Its middle (from 35 % to 80 %: past any throw's tail,
   before any catch) is fitted (:mod:`~tumble.analysis.fit.single`, with a quadratic drag),
   then the window grows on each side while the model, extrapolated (its time origin kept at
   the middle's first sample: near the separatrix, moving ``omega0`` to another sample by the
   model's own extrapolation can carry it across), still follows the samples
   within ``max(6 x`` the fit's RMS ``, 3 % of |omega|)``; two samples in a row beyond that
   end the flight (the throw's torque before, the catch after), and so does one just before the
   candidate's end. Fit and growth alternate until the window stops moving (a growth whose fit
   no longer follows a free motion is taken back); end samples whose residual exceeds five
   times the fit's RMS are then trimmed. When the middle's fit does not pass, the first and the
   second half are tried (:data:`SEEDS`), then windows near the candidate's end
   (:data:`LATE_SEEDS`); after a refusal other than :data:`RETRY`'s, a fit that passes is taken
   only with a lower residual.
5. **Usable or not**, with a reason: too short (under ``min_duration`` or 30 samples),
   saturated (more than 60 % of its samples with an axis at the rail), a steady spin (no tumble: the
   ratios do not enter), a stable-axis toss or too little of a tumble (the fit leaves a ratio
   undetermined or uncertain by more than ``max_std``, or runs to the rod limit of the
   triangle (:func:`~tumble.analysis.fit.triangle.at_rod_limit`), where no tossed phone, racquet
   or book lies; named the air's drag when the drag law's model error alone takes it over
   ``max_std``), the model does not fit
   (:mod:`~tumble.analysis.fit.adequacy`), or not a rigid body: the body's ``|L|`` or energy
   rises during the flight (:func:`~tumble.analysis.fit.adequacy.rigid_body_check`), or the
   samples leave the fitted motion more than :data:`~tumble.analysis.fit.adequacy.MAX_TAIL` before the impulse that ends the
   flight while still spinning (a rigid body flies free until it is caught or lands; on the
   synthetic tosses the fitted flight reaches the impulse within 0.04 s, or within 0.25 s
   where a hand's grip or a glancing impact is too gentle to show as an impulse, while a rotor
   spinning up inside leaves it 0.2-0.8 s early), or a gyrostat whose rotor spins up explains the
   samples far better than a rigid body's drag and flex can, or the world-frame momentum budget
   holds an internal momentum that steps up and down (a rotor spun up and braked within the
   flight: :func:`~tumble.analysis.fit.rotor.rotor_check`).
   A flight skipped only because its ratios are
   not determined alone (a stable axis, too little of the tumble, the rod limit) while its fit is
   adequate and it flies free up to its impulse is ``joinable``: the joint fit of its recording
   may still use it (:func:`~tumble.analysis.fit.fit_recording`).
6. **After an impact**: a stretch that starts within :data:`AFTER_IMPACT` of the end of a
   flight, with no throw between, is the body in the hand or on the table after the catch or
   the landing, not a flight, whatever motion it follows (:func:`_after_impacts`): a free
   flight is released from a hand and ended by an impact.

**With an accelerometer** (``accel``), each candidate of step 3 is first cut to its free fall
(:func:`~tumble.analysis.fit.freespan.free_span`: the release and the catch or impact), or
skipped when its middle is not in free fall (the hand); step 4 then fits the whole free fall
(its growth where that fails), and the flight keeps the sensor's offset (:attr:`Flight.free_fall`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np

from ..._html import fmt, result_html
from ...typing import ArrayLike
from .. import _display
from .adequacy import _left_path
from .freefall import check_accel
from .freespan import FreeSpan, grown_free_span
from .result import determination, ratio_summary, solution_adequacy
from .rotor import rotor_check
from .segments import _runs, _segments, _stretches, impulses, longest_quiet, pause_times
from .single import MIN_SAMPLES, _check, fit_solution, saturation_mask
from .solve import Solution
from .triangle import EDGES, at_rod_limit
from .uncertainty import SCALE_UNCERTAINTY, noise_floor
from .window import _drag_free, _grow, _refit, _trim

__all__ = ["Flight", "find_flights"]


@dataclass(frozen=True)
class Flight:
    """A stretch of a recording taken for a free flight.

    Attributes
    ----------
    start, end : float
        First and last sample's time, s.
    first, stop : int
        Sample indices: the flight is ``t[first:stop]``.
    status : str
        ``"ok"`` or ``"skipped"``.
    reason : str
        Why it was skipped ("" when ok).
    solution : Solution or None
        The per-flight fit (``tumble.analysis.fit.solve.Solution``) when one was made.
    anchor : float
        The time its ``omega0`` refers to (inside the flight), s.
    joinable : bool
        A skipped flight whose samples follow a rigid body's free motion (its fit is adequate)
        but whose ratios it does not determine alone (too little of the tumble, a stable axis,
        the fit run to the rod limit): the ratios are the body's, shared by every flight, so
        it may still take part in a joint fit with flights that determine them
        (:func:`~tumble.analysis.fit.fit_recording`).
    free_fall : FreeSpan or None
        Where the accelerometer says the candidate fell free, and the sensor's fitted offset from
        the centre of mass (:class:`~tumble.analysis.fit.freespan.FreeSpan`); None without one.

    Examples
    --------
    >>> from tumble.analysis.fit.flights import find_flights
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(7, tosses=2, flight=(0.5, 0.8))
    >>> flights = find_flights(rec.t, rec.omega, events=rec.events)
    >>> [(f.status, f.first < f.stop) for f in flights]
    [('ok', True), ('ok', True)]
    >>> [bool(abs(f.start - release) < 0.05 and abs(f.end - catch) < 0.05) for f, (release, catch) in zip(flights, rec.flights)]
    [True, True]
    >>> # release and catch found to within 50 ms
    """

    start: float
    end: float
    first: int
    stop: int
    status: str = "ok"
    reason: str = ""
    solution: Solution | None = None
    anchor: float = 0.0
    joinable: bool = False
    free_fall: FreeSpan | None = None

    def __repr__(self) -> str:
        return _display.flight_repr(self)

    def _repr_html_(self) -> str:
        return result_html("Flight", [("start", f"{fmt(self.start)} s"), ("end", f"{fmt(self.end)} s"),
                                      ("samples", f"{self.first}..{self.stop}"), ("status", self.status),
                                      ("reason", self.reason or "none"), ("joinable", "yes" if self.joinable else "no")])

    @property
    def samples(self) -> int:
        """Number of samples, ``stop - first``.

        Examples
        --------
        >>> from tumble.analysis.fit.flights import Flight
        >>> Flight(start=1.0, end=1.99, first=100, stop=200).samples
        100
        """
        return self.stop - self.first


def find_flights(t: ArrayLike, omega: ArrayLike, *, events: Sequence[tuple[str, float]] | None = None, saturation: float | None = None, min_spin: float = 3.0,
                 min_duration: float = 0.3, max_gap: float = 0.25, max_std: float = 0.1,
                 drag: str = "auto", rotation: bool = True, bias: bool = True,
                 scale_uncertainty: float = SCALE_UNCERTAINTY,
                 progress: Callable[[int, int], None] | None = None, accel: ArrayLike | None = None) -> list[Flight]:
    """The free flights of a whole recording, each fitted or skipped with a reason.

    Parameters
    ----------
    t : ndarray, shape (n,)
        Times, s, strictly increasing.
    omega : ndarray, shape (n, 3)
        Gyroscope samples, sensor axes, rad/s.
    events : list of (str, float), optional
        phyphox's START/PAUSE events (experiment time, s).
    saturation : float, optional
        The gyroscope's full scale, rad/s (found from the data when not given).
    min_spin : float
        ``|omega|`` above which a stretch may be a flight, rad/s.
    min_duration : float
        Shortest usable flight, s.
    max_gap : float
        Longest gap in the samples inside a flight, s.
    max_std : float
        Largest standard uncertainty of a ratio for a usable flight.
    drag, rotation, bias, scale_uncertainty
        The per-flight fit's options (:func:`tumble.analysis.fit.fit_rotation`).
    progress : callable, optional
        ``progress(done, total)`` after each active stretch.
    accel : array_like, shape (n, 3), optional
        The accelerometer's specific force at the times ``t``, sensor axes, m/s^2: each candidate
        is cut to its free fall (module docstring); without it, the gyroscope alone.

    Returns
    -------
    list of Flight
        In time order; ``status`` says whether each is usable.

    Raises
    ------
    ValueError
        For samples the fit refuses (as :func:`tumble.analysis.fit.fit_rotation`): shapes that do
        not match, values that are not finite, times that do not increase, too few samples.

    Examples
    --------
    >>> from tumble.analysis.fit.flights import find_flights
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(22, tosses=2, flight=(0.5, 0.8))
    >>> flights = find_flights(rec.t, rec.omega, events=rec.events)
    >>> [f.status for f in flights]  # the second toss's samples do not follow a free motion
    ['ok', 'skipped']
    >>> flights[1].reason.startswith(("the model does not fit", "no free flight: the samples do not follow"))
    True

    With the accelerometer, the release and the catch are where the free fall begins and ends:

    >>> rec = synthetic_recording(7, tosses=2, flight=(0.5, 0.8), accel=True)
    >>> found = find_flights(rec.t, rec.omega, events=rec.events, accel=rec.accel.f)
    >>> [bool(abs(f.start - a) < 0.03 and abs(f.end - b) < 0.03) for f, (a, b) in zip(found, rec.flights)]
    [True, True]
    """
    t, omega = _check(t, omega)  # the fit's own checks: shapes, finite values, increasing times
    accel = None if accel is None else check_accel(accel, omega.shape)
    keep, accel_inside = saturation_mask(omega, saturation)[0], None if accel is None else saturation_mask(accel)[0]
    speed = np.linalg.norm(omega, axis=1)
    if len(speed) >= 3:
        speed = np.median(np.stack([np.r_[speed[0], speed[:-1]], speed, np.r_[speed[1:], speed[-1]]]), axis=0)
    stretches = [(a0, b0) for lo, hi in _runs(t, pause_times(events), max_gap)
                 for a0, b0 in _stretches(speed, lo, hi, min_spin)]
    kicked = impulses(t, omega)
    flights = []
    for k, (a0, b0) in enumerate(stretches):
        free = [(a, b) for a, b, ok in _segments(a0, b0, kicked, t, min_duration) if ok]
        if not free and t[b0 - 1] - t[a0] >= min_duration:  # the whole stretch is torqued: one candidate, skipped
            quiet = longest_quiet(a0, b0, kicked, t)
            flights.append(_skip(t, a0, b0, f"no free flight: under impulses (no {min_duration} s between them in which the "
                                            f"rate changes slower than a free rigid body's can: a throw, a catch, an impact or the hand; "
                                            f"the longest stretch between them lasts {quiet:.2g} s"
                                            + (": a toss too short to fit? Throw higher)" if quiet >= 0.1 else ")")))
        else:
            for a, b in free or [(a0, b0)]:
                margin = int(np.searchsorted(t, t[a] + 0.05) - a)  # the accelerometer's cut may lie in the impulse
                span = grown_free_span(t, accel, omega, max(a0, a - margin), min(b0, b + margin), a0, b0,
                                       accel_inside=accel_inside, omega_inside=keep) if accel is not None and b - a >= 30 else None
                if span is not None and not span.free:
                    flights.append(replace(_skip(t, a, b, span.reason), free_fall=span))
                    continue
                a, b = (a, b) if span is None else (span.first, span.stop)
                one = _one(t, omega, keep, a, b, min_duration, max_std, drag, rotation, bias, scale_uncertainty,
                           span is not None)  # with the accelerometer, the whole free fall; else grown
                if span is not None and one.status != "ok":
                    one = _one(t, omega, keep, a, b, min_duration, max_std, drag, rotation, bias, scale_uncertainty)
                flights.append(one if span is None else replace(one, free_fall=span))
        if progress is not None:
            progress(k + 1, len(stretches))
    return _after_impacts(flights)


#: The longest time from the end of a flight to the start of the next stretch that follows a
#: free motion for that stretch to be the body's motion after the impact that ended the flight
#: (turned in the hand, spun on a table), s. A catch or an impact lasts 20-120 ms (the grip and
#: the kill of :mod:`~tumble.analysis.fit.endings`; on the synthetic recordings the stretch
#: after it starts 0.05-0.07 s after the flight ends), while a new flight needs a throw first:
#: the hand grips, swings and releases the body, 0.15-0.3 s after it has held it (the tosses of
#: :mod:`~tumble.analysis.fit.synthetic`; successive flights there lie 1.5 s and more apart).
AFTER_IMPACT = 0.2
#: The reason's first words of a stretch skipped as the body's motion after an impact.
AFTER_IMPACT_REASON = "after an impact, not a free flight"


def _after_impacts(flights: list[Flight]) -> list[Flight]:
    """The flights with every stretch that starts within :data:`AFTER_IMPACT` of the end of a
    flight before it (a free motion: usable or joinable) skipped: a free flight starts with a
    release from a hand or a throw, and what follows an impact at once is the body in contact (in
    the hand, on a table), whatever motion it follows (a phone turned in the fingers cones like a
    free symmetric body). Chained: a stretch after such a stretch is after the impact too. A
    stretch the fit did not follow as a free motion (the model does not fit, under impulses: the
    hand's swing and the throw) ends no flight: a throw's last 0.15 s may lie just before the
    release."""
    out, last = [], None
    for f in flights:
        followed = f.status == "ok" or f.joinable
        if followed and last is not None and 0.0 <= f.start - last < AFTER_IMPACT:
            f = replace(f, status="skipped", joinable=False, reason=(
                f"{AFTER_IMPACT_REASON}: it starts {f.start - last:.2f} s after the flight before it ends, with no throw "
                f"between (the body turned in the hand or on a table after the catch or the landing)"))
        out.append(f)
        if followed:
            last = f.end
    return out


def _skip(t, a, b, reason, sol=None) -> Flight:
    return Flight(float(t[a]), float(t[b - 1]), int(a), int(b), "skipped", reason, sol)


def _one(t, omega, keep, a0, b0, min_duration, max_std, drag, rotation, bias, scale_uncertainty,
         whole=False) -> Flight:
    length = t[b0 - 1] - t[a0]
    if length < min_duration or b0 - a0 < max(30, MIN_SAMPLES):
        return _skip(t, a0, b0, f"too short ({length:.2f} s, {b0 - a0} samples; a flight needs {min_duration} s "
                                f"and 30 samples)")
    sat = np.mean(~np.all(keep[a0:b0], axis=1))
    if sat > 0.6:
        return _skip(t, a0, b0, f"saturated ({100 * sat:.0f} % of the samples at the gyroscope's rail)")
    w = omega[a0:b0]
    spread = np.sqrt(np.mean(np.sum((w - w.mean(axis=0)) ** 2, axis=1)))
    if spread < 0.05 * np.sqrt(np.mean(np.sum(w ** 2, axis=1))):
        return _skip(t, a0, b0, "steady spin (omega nearly constant: no tumble, the ratios do not enter)")
    first, best, tried, refused = None, None, set(), None
    for lo, hi in SEEDS + (() if whole else LATE_SEEDS):  # a free fall is no hand's swing
        a, b = a0 + int(lo * (b0 - a0)), a0 + int(hi * (b0 - a0))
        if b - a < MIN_SAMPLES:
            a, b = a0, b0
        if (a, b) in tried:  # a short candidate's seeds are all of it: the same fit again (29 % of the attempts)
            continue
        tried.add((a, b))
        found = _attempt(t, omega, keep, a0, b0, a, b, min_duration, max_std, drag, rotation, bias, scale_uncertainty,
                         whole)
        if found.status == "ok":
            if refused is not None and found.solution.rms >= refused.solution.rms:
                continue  # no better an optimum than a seed's fit that was refused (RETRY)
            best = found if best is None or found.solution.rms < best.solution.rms else best
            if not whole or best.solution.rms <= POOR_FIT * noise_floor(omega[best.first:best.stop]):
                return best
            continue  # a free fall's fit well above the noise: perhaps a poorer optimum, so the other seeds too
        if best is None:
            if found.reason.startswith(FINAL) or (found.solution is None and not found.reason.startswith(RETRY)):
                return found if refused is not None or first is None else first
            first = first or found
            if not found.reason.startswith(RETRY):
                refused = found if refused is None or found.solution.rms < refused.solution.rms else refused
    return best or refused or first


#: The reason's first words when the solver itself fails (non-finite residuals, a singular
#: system): a numerical failure, not a verdict on the flight.
NUMERICAL = "not fitted"
#: Where the first fit of a candidate is made, as fractions of it: its middle (past any throw,
#: before any catch), then its first and its second half when the middle does not follow a
#: free motion (an impact missed by :func:`~tumble.analysis.fit.segments.impulses` inside it, a throw that ends late).
SEEDS = ((0.35, 0.8), (0.1, 0.5), (0.5, 0.9))
#: Seeds near the candidate's end, tried when those above all failed: the hand's smooth swing
#: before the throw joins the flight's candidate, or the middle seed settles in a poorer basin
#: (fit_coverage's racquet one toss, seeds 1001, 1015, 1017). Every swing between the tosses tries
#: them, paid for by not fitting a seed window twice (a short candidate's seeds are all of it).
#: Not for the accelerometer's free fall: the least RMS among the seeds took a late seed's short
#: window, 0.44 of a 1.3 s flight (fit_coverage racquet "one toss + accel", seed 1029).
LATE_SEEDS: tuple[tuple[float, float], ...] = ((0.6, 0.95), (0.75, 0.97))
#: The reasons for which another seed is tried and its fit taken when it passes: the seed's fit
#: did not follow a free motion, or it settled where the ratios come out undetermined by too
#: little of the tumble for the whole flight (on the synthetic racquet tossed one a file, a
#: window of the same flight from another seed finds the basin in which they are determined, as
#: the flight cut at its true release and impact does). After any other refusal but
#: :data:`FINAL`'s (the rod limit, the air's drag) the other seeds are tried too, but a fit that passes is
#: taken only when its residual RMS is below the refused fit's, a better optimum of the same
#: samples (fit_coverage's racquet one toss, seeds 1001, 1033, 1054: 0.02-0.19 rad/s refused,
#: 0.006-0.02 passed): with any fit that passes, a 0.5 s racquet toss refused at the rod
#: limit was taken from another seed near it, with a small uncertainty, I1/I3 = 0.006 for 0.069.
RETRY = ("no free flight", "the model does not fit", NUMERICAL, "too short (", "too little of the tumble", "saturated")
#: Refusals after which no other seed is tried: a rotor's flight refused from one seed passed
#: from another (tests/test_fit_rotor_flight.py).
FINAL = ("not a rigid body",)
#: A free fall cut by the accelerometer whose flight's residual RMS exceeds this many times its
#: noise floor (:func:`~tumble.analysis.fit.uncertainty.noise_floor`) has the other seeds tried
#: as well, and keeps the fit of least RMS: from the middle seed of a free fall the fit can
#: settle in a poorer optimum (2 of 76 synthetic phone flights: 0.10-0.12 rad/s against 0.02
#: from another seed and from the gyroscope alone, noise floors 0.03-0.05 rad/s). Not for the
#: gyroscope's candidates: a flexing racquet's right fit is 0.7-6.8 times its noise floor
#: (median 1.6), so the test would triple the cost of most of its flights.
POOR_FIT = 1.5


def _attempt(t, omega, keep, a0, b0, a, b, min_duration, max_std, drag, rotation, bias, scale_uncertainty,
             whole=False) -> Flight:
    """Fit the seed window ``[a, b)``, grow it inside ``[a0, b0)``, trim, fit the flight and judge it;
    ``whole``: the grown fit then taken to all of ``[a0, b0)`` (the accelerometer's free fall),
    where it still follows a free motion, and trimmed as any (a gyroscope's sample at the catch
    can still carry the impulse: its own low-pass filter smears it over a sample or two)."""
    if np.count_nonzero(np.all(keep[a:b], axis=1)) < 7:  # the start's conserved forms have 7 coefficients
        return _skip(t, a, b, "saturated (fewer than 7 samples of the window with no axis at the rail)")
    anchor = t[a]
    sol = None
    try:
        # the seed, from the samples alone, then with a quadratic drag
        sol = fit_solution(t[a:b], omega[a:b], keep[a:b], rotation=rotation, bias=bias, drag="quadratic", t0=anchor,
                           covariance=False, max_nfev=40)
        last = None
        for _ in range(6):
            rms = sol.rms
            level = float(np.sqrt(np.mean(np.sum(omega[a:b] ** 2, axis=1)) / 3))
            if rms > 0.1 * level:
                if last is None:
                    return _skip(t, a0, b0, f"no free flight: the samples do not follow a torque-free motion "
                                            f"(residual {rms:.2g} rad/s against rates of {level:.2g} rad/s)", sol)
                a, b, sol = last  # the growth took in the throw's or the catch's end: back to the window before
                break
            last = (a, b, sol)
            a2, b2 = _grow(t, omega, keep, a, b, sol, a0, b0, anchor)
            if (a2, b2) == (a, b):
                break
            a, b = a2, b2
            sol = _refit(t, omega, keep, a, b, sol, anchor)
        grown = None
        if whole and (a, b) != (a0, b0):  # the accelerometer's free fall, whole: from the grown fit
            wide = _refit(t, omega, keep, a0, b0, sol, anchor)
            if wide.rms <= 0.1 * np.sqrt(np.mean(np.sum(omega[a0:b0] ** 2, axis=1)) / 3):
                # a sample of the catch in the wide window swells its RMS: judge the ends by the grown fit's,
                # once that sample, past the wide fit's own, is out and no longer bends the fit at its end
                grown, (a, b) = sol.rms, _trim(omega, keep, a0, b0, wide)
                sol = wide if (a, b) == (a0, b0) else _refit(t, omega, keep, a, b, wide, anchor)
        a, b = _trim(omega, keep, a, b, sol, rms=grown)
        length = t[b - 1] - t[a]
        if length < min_duration or b - a < 30:
            return _skip(t, a, b, f"too short ({length:.2f} s of free flight, {b - a} samples)", sol)
        sol = fit_solution(t[a:b], omega[a:b], keep[a:b], rotation=rotation, bias=bias, drag=drag,
                           P0=_drag_free(sol), drag0=sol.model.drag_vector(sol.P), t0=anchor,
                           scale_uncertainty=scale_uncertainty)
    except (ValueError, np.linalg.LinAlgError) as err:
        return _skip(t, a, b, f"{NUMERICAL}: the least-squares solver failed numerically ({err}); this says nothing "
                              f"about the flight (please report it)", sol)
    verdict = solution_adequacy(sol, omega[None, a:b], keep[None, a:b])
    if not verdict.adequate:
        return _skip(t, a, b, verdict.reason, sol)
    _, std, _, edge = ratio_summary(sol)
    why = determination(sol, std, max_std)
    if edge == EDGES["rod"] or not why and at_rod_limit(float(sol.P[0]), float(sol.cov_stat[0, 0])):
        why = ("ratios not determined: the fit ran to the rod limit of the triangle (I1 -> 0), where no toss of a "
               "phone, racquet or book lies (seen on short or slow flights)")
    rigid = _left_path(t, omega, b, b0)
    if why:  # a free motion up to its impulse, its ratios not determined alone: it may join a joint fit
        return Flight(float(t[a]), float(t[b - 1]), int(a), int(b), "skipped", why, sol, float(anchor), not rigid)
    rigid = rigid or rotor_check(t[a:b], omega[a:b], keep[a:b], sol)
    if rigid:
        return _skip(t, a, b, rigid, sol)
    return Flight(float(t[a]), float(t[b - 1]), int(a), int(b), "ok", "", sol, float(anchor))
