"""Whether the flights of a pooled fit are one body's: the verdicts of :func:`~tumble.analysis.fit.recording.fit_recording`
on flights that disagree (:func:`split_verdict`) and on a joint fit outside its flights' values
(:func:`outside_caveat`).

The flights' own ratios are compared with the reference flight's in the joint fit
(:func:`~tumble.analysis.fit.joint.joint_solution`: more than five standard uncertainties away is a
gross outlier, left out); what is said when many are, or every one of a recording's, is here.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from ...typing import FloatArray
from .result import public_covariance, ratio_summary

if TYPE_CHECKING:
    from .flights import Flight
    from .tosses import RecordingFit

__all__ = ["MAX_DISAGREEING", "OUTSIDE_SIGMAS", "outside_caveat", "split_verdict"]


#: Share of the fitted flights that may disagree with the others before the recording counts as
#: holding more than one body: a third (one stray flight in twelve is a toss gone wrong; a third
#: that agree among themselves is another body, a loose phone or a changed mount).
MAX_DISAGREEING = 1.0 / 3.0


def split_verdict(used: Sequence[Flight], groups: Sequence[int], outliers: Sequence[int]) -> str:
    """The reason a pooled value is no answer, or "": at least :data:`MAX_DISAGREEING` of the fitted
    flights (two at least) disagree with the others, or every fitted flight of one recording does
    while another recording's agree. The flights that agree are then one body's, but the recording
    left out says the list held another, and which of the two the pool's majority is was the
    user's choice of files, not the data's (a phone's recording pooled with a racquet's was written
    as adequate, exit 0; a walkthrough, 2026-12-02).

    ``used`` are the fitted flights, ``groups`` each one's recording, ``outliers`` the indices of
    those that disagree (:func:`~tumble.analysis.fit.joint.joint_solution`).

    Examples
    --------
    >>> from tumble.analysis.fit.disagreement import split_verdict
    >>> from tumble.analysis.fit.flights import find_flights
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
    >>> used = find_flights(rec.t, rec.omega, events=rec.events)
    >>> split_verdict(used, [0, 0], [])
    ''
    >>> split_verdict(used, [0, 1], [1])[:75]   # as if the second flight were another recording's
    'the recordings disagree: every fitted flight of recordings[1] lies more tha'
    """
    own = np.array([ratio_summary(used[j].solution)[0] for j in outliers]).reshape(-1, 2)

    def spread(rows):
        if len(rows) == 1:
            return f"I1/I3 {rows[0, 0]:.4f}, I2/I3 {rows[0, 1]:.4f}"
        return (f"I1/I3 {np.min(rows[:, 0]):.4f} to {np.max(rows[:, 0]):.4f}, "
                f"I2/I3 {np.min(rows[:, 1]):.4f} to {np.max(rows[:, 1]):.4f}")

    apart = [r for r in sorted(set(groups)) if all(j in outliers for j, g in enumerate(groups) if g == r)]
    if apart and len(apart) < len(set(groups)):
        rest = np.array([ratio_summary(f.solution)[0] for j, f in enumerate(used) if j not in outliers])
        mine = np.array([ratio_summary(used[j].solution)[0] for j in outliers if groups[j] in apart])
        which = ", ".join(f"recordings[{r}]" for r in apart)
        return (f"the recordings disagree: every fitted flight of {which} lies more than five standard uncertainties "
                f"from the other recordings' flights ({spread(mine)} against {spread(rest)}): the recordings hold "
                "more than one body, or the phone sat differently on it; fit each recording apart")
    if len(outliers) < 2 or len(outliers) < MAX_DISAGREEING * len(used):
        return ""
    return (f"the flights disagree: {len(outliers)} of {len(used)} fitted flights lie more than five standard "
            f"uncertainties from the others (their ratios {spread(own)}): the recording holds more than one body "
            "or the phone moved on it; fit each group apart (--start/--end)")


def outside_caveat(fit: RecordingFit, used: Sequence[Flight], numbers: Sequence[int], omega: FloatArray | None,
                   keep: np.ndarray | None, joint: bool) -> str:
    """What to say when the pooled ratios lie outside the range of the flights' own values, on
    one side of them all, each more than :data:`OUTSIDE_SIGMAS` of its own standard uncertainties
    away (a joint fit may fall a little outside the range by right, the shared mount and bias
    pinning it better than any flight alone; not this far): some flight bends the shared mount,
    bias or drag. It names the flight that pulls it: the one whose samples the joint model follows
    worst against its own fit, ``(SSR_joint - SSR_own) / (SSR_own / m)`` largest (the rise of its
    chi^2, its own residual variance taken as its noise), or, where the flights' weighted mean
    stands in for a joint fit (``joint`` false), the flight whose leaving out moves it the most;
    ``""`` otherwise.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit import fit_recording
    >>> from tumble.analysis.fit.disagreement import outside_caveat
    >>> from tumble.analysis.fit.flights import find_flights
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
    >>> fit = fit_recording(rec.t, rec.omega, events=rec.events)
    >>> used = find_flights(rec.t, rec.omega, events=rec.events)
    >>> outside_caveat(fit, used, [0, 1], rec.omega, np.ones(rec.omega.shape, bool), joint=True)
    ''
    """
    own = [(k, f) for k, f in zip(numbers, used) if not f.joinable]
    if len(own) < 2 or len(fit.omega_models) != len(used):
        return ""
    summaries = [ratio_summary(f.solution) for _, f in own]
    values, stds = np.array([r[0] for r in summaries]), np.array([r[1] for r in summaries])
    p = fit.pooled.ratios
    z = (p - values) / np.maximum(stds, 1e-300)
    out = np.all(z > OUTSIDE_SIGMAS, axis=0) | np.all(z < -OUTSIDE_SIGMAS, axis=0)
    if not out.any():
        return ""
    axis = int(np.flatnonzero(out)[0])
    if joint:
        rise = []
        for f, model in zip(used, fit.omega_models):
            sl = slice(f.first, f.first + len(model))
            r2 = np.where(keep[sl], model - omega[sl], 0.0) ** 2
            rise.append((float(np.sum(r2)) - f.solution.ssr) / max(f.solution.ssr / max(f.solution.m, 1), 1e-300))
        j, why = int(np.argmax(rise)), f"its samples followed worst by the shared parameters (chi^2 up by {max(rise):.3g})"
    else:  # the flights' weighted mean: the flight whose leaving out moves it back the most
        W = np.array([np.linalg.pinv(public_covariance(f.solution, statistical=True)[2][:2, :2]) for _, f in own])
        shift = []
        for i in range(len(own)):
            rest = np.arange(len(own)) != i
            mean = np.linalg.pinv(W[rest].sum(axis=0)) @ np.einsum("fij,fj->i", W[rest], values[rest])
            shift.append(abs(float(p[axis] - mean[axis])))
        i = int(np.argmax(shift))
        j = used.index(own[i][1])
        why = f"the weighted mean without it moves by {shift[i]:.3g}"
    lo, hi = values[:, axis].min(), values[:, axis].max()
    return (f"the joint fit's {('I1/I3', 'I2/I3')[axis]} = {p[axis]:.4f} lies outside its flights' own values "
            f"({lo:.4f} to {hi:.4f}; each more than {OUTSIDE_SIGMAS:g} of its standard uncertainties away): the flight "
            f"at {used[j].start:.2f}-{used[j].end:.2f} s (tosses[{numbers[j]}]) pulls it ({why}); check that it is a free flight of this body, or "
            f"fit the flights apart (--start/--end)")


#: How many of its own standard uncertainties every flight's ratio must lie from the joint fit's,
#: all on one side, for the joint fit to be said to lie outside its flights' values (:func:`outside_caveat`).
OUTSIDE_SIGMAS = 2.0
