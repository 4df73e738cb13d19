"""Where a whole gyroscope recording is cut before its flights are sought
(:func:`~tumble.analysis.fit.flights.find_flights`, steps 1-3 of its module docstring): phyphox's
PAUSE events and the gaps in the samples (runs), the stretches where the body turns, and the
impulses (a throw's, a catch's, an impact's torque, or the hand's) that bound a free flight.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from numbers import Real

import numpy as np

from ...typing import ArrayLike

__all__ = ["IMPULSE_FACTOR", "IMPULSE_FLOOR", "IMPULSE_SPAN", "impulses", "pause_times"]


def pause_times(events: Sequence[tuple[str, float]] | None) -> list[float]:
    """Experiment times of phyphox's PAUSE events (``[(name, time), ...]``), s.

    Examples
    --------
    >>> from tumble.analysis.fit.segments import pause_times
    >>> pause_times([("START", 0.0), ("PAUSE", 12.5), ("START", 12.5), ("pause", 3.0)]), pause_times(None)
    ([3.0, 12.5], [])
    >>> pause_times([("PAUSE", "12.5 s")])   # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: events[0] = ('PAUSE', '12.5 s'): each event is a (name, time) pair, ...
    >>> pause_times([1, 2, 3])
    Traceback (most recent call last):
    ...
    ValueError: events[0] = 1: each event is a (name, time) pair, ('PAUSE', 12.5) (phyphox's meta/time.csv: name, experiment time in s)
    """
    pauses = []
    for i, event in enumerate(events or []):
        if not (isinstance(event, (tuple, list)) and len(event) == 2 and isinstance(event[0], str)
                and isinstance(event[1], Real) and not isinstance(event[1], bool) and math.isfinite(event[1])):
            raise ValueError(f"events[{i}] = {event!r}: each event is a (name, time) pair, ('PAUSE', 12.5) "
                             f"(phyphox's meta/time.csv: name, experiment time in s)")
        if event[0].upper() == "PAUSE":
            pauses.append(float(event[1]))
    return sorted(pauses)


def _runs(t, pauses, max_gap):
    """Index ranges ``[i, j)`` not crossing a pause or a gap."""
    cuts = set(np.flatnonzero(np.diff(t) > max_gap) + 1)
    for tp in pauses:
        cuts.add(int(np.searchsorted(t, tp, side="right")))
    edges = [0] + sorted(c for c in cuts if 0 < c < len(t)) + [len(t)]
    return list(itertools.pairwise(edges))


def _stretches(speed, lo, hi, min_spin):
    active = speed[lo:hi] > min_spin
    d = np.diff(np.r_[0, active.astype(int), 0])
    return [(lo + a, lo + b) for a, b in zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1))]


#: A free flight's angular acceleration is at most ``|omega|^2 / sqrt(3)`` (torque-free, any
#: rigid body): a sample whose rate changes faster, by this factor plus :data:`IMPULSE_FLOOR`,
#: is under an impulse (module docstring).
IMPULSE_FACTOR = 1.25
#: Angular acceleration always allowed (the body's flex, the gyroscope's noise), rad/s^2.
IMPULSE_FLOOR = 20.0
#: The span over which the angular acceleration is taken, s (a central difference).
IMPULSE_SPAN = 0.02


def impulses(t: ArrayLike, omega: ArrayLike) -> np.ndarray:
    """Which samples lie under an impulse: a throw's, a catch's or an impact's torque, or the hand's.

    Torque-free, Euler's equations give ``|omega_i'| = |(I_j - I_k) / I_i| |omega_j omega_k|
    <= |omega_j omega_k|`` (the moments obey the triangle inequality, ``|I_j - I_k| <= I_i``;
    Landau & Lifshitz, *Mechanics*, sec. 32), so ``|omega'| <= |omega|^2 / sqrt(3)`` whatever
    the body, its axes or the sensor's mount. A sample whose central difference over
    :data:`IMPULSE_SPAN` exceeds :data:`IMPULSE_FACTOR` times that bound plus
    :data:`IMPULSE_FLOOR` cannot be in free flight: the recording is cut there (a segmentation at
    impulses; the fit then tests what lies between).

    Parameters
    ----------
    t : ndarray, shape (n,)
        Times, s, increasing.
    omega : ndarray, shape (n, 3)
        Gyroscope samples, rad/s.

    Returns
    -------
    ndarray of bool, shape (n,)

    Examples
    --------
    A torque-free tumble is never under an impulse; an impact that turns omega in one sample is:

    >>> import numpy as np
    >>> from tumble.analysis.fit.segments import impulses
    >>> from tumble.analysis.fit.endings import gyrostat_flight
    >>> from tumble.analysis.fit.synthetic import TOSS_BODIES
    >>> t = np.arange(0.0, 1.0, 0.005)
    >>> w = gyrostat_flight(TOSS_BODIES["phone"], np.array([0.2, 15.0, 0.3]), 1.0, t, np.array([1.0, 0, 0]), 0.0, 1.0,
    ...                     lambda x: np.zeros(3))
    >>> bool(impulses(t, w).any())
    False
    >>> w[100:] = w[100:] @ np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]) * 0.7   # an impact at 0.5 s
    >>> np.flatnonzero(impulses(t, w)).tolist()   # the samples whose difference spans it
    [98, 99, 100, 101]
    """
    t = np.asarray(t, float)
    omega = np.asarray(omega, float)
    n = len(t)
    if n < 3:
        return np.zeros(n, bool)
    k = max(1, int(round(0.5 * IMPULSE_SPAN / float(np.median(np.diff(t))))))
    i = np.arange(n)
    lo, hi = np.maximum(i - k, 0), np.minimum(i + k, n - 1)
    rate = np.linalg.norm(omega[hi] - omega[lo], axis=1) / np.maximum(t[hi] - t[lo], 1e-12)
    spin2 = np.maximum(np.sum(omega[lo] ** 2, axis=1), np.sum(omega[hi] ** 2, axis=1))
    return rate > IMPULSE_FACTOR * spin2 / np.sqrt(3.0) + IMPULSE_FLOOR


def _segments(a0: int, b0: int, kicked: np.ndarray, t, min_duration: float) -> list[tuple[int, int, bool]]:
    """``[a0, b0)`` cut at the impulses: ``(a, b, free)`` pieces, in order. A piece between two
    impulses shorter than ``min_duration`` is joined with its short neighbours and the impulses
    between them into one piece that is not free (the throw, the catch, the hand's motion)."""
    long = [(a, b) for a, b in _quiet_runs(a0, b0, kicked) if t[b - 1] - t[a] >= min_duration]
    pieces, cursor = [], a0
    for a, b in long:
        if a > cursor:
            pieces.append((cursor, a, False))
        pieces.append((a, b, True))
        cursor = b
    if cursor < b0:
        pieces.append((cursor, b0, False))
    return pieces


def longest_quiet(a0: int, b0: int, kicked: np.ndarray, t) -> float:
    """The longest stretch of samples ``[a0, b0)`` between impulses (``kicked``), s (0 for none): a
    toss whose free flight is shorter than the fit's minimum is said to be so, not only "no free
    flight" (a walkthrough's 0.15 s toss).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.segments import longest_quiet
    >>> t = np.arange(100) / 100.0
    >>> kicked = np.zeros(100, bool)
    >>> kicked[[10, 11, 40, 41, 60]] = True   # quiet 12..39 (0.27 s), 42..59 and 61..99
    >>> round(longest_quiet(0, 100, kicked, t), 2)
    0.38
    """
    return max((float(t[b - 1] - t[a]) for a, b in _quiet_runs(a0, b0, kicked)), default=0.0)


def _quiet_runs(a0: int, b0: int, kicked: np.ndarray) -> list[tuple[int, int]]:
    """The runs ``[a, b)`` of samples of ``[a0, b0)`` between impulses (``kicked`` False), in order."""
    d = np.diff(np.r_[0, (~np.asarray(kicked[a0:b0], bool)).astype(int), 0])
    return [(a0 + int(a), a0 + int(b)) for a, b in zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1))]
