"""Where a throw's free flight may lie in its log: :func:`find_flight`, the bounds that the fit of
:func:`tumble.analysis.tensor.throw.fit_flown` narrows by what the free motion explains.

- **Rotor start**: the device starts its rotor 0.06-0.12 s after it senses the release; the
  first sample of the run that leads to 10 % of the rotor's top speed, from the last reading at
  the stopped rotor's level (median + 5 MADs of the readings before; a stopped motor's telemetry
  reads 0).
- **The sensed release** (with an accelerometer): in free fall an accelerometer at ``r`` from
  the centre of mass reads ``f = w' x r + w x (w x r)`` plus its bias (the acceleration of a
  point of a rigid body, Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed., sec. 4.10,
  less gravity, which a falling accelerometer does not sense): ``r`` and the bias are fitted by
  linear least squares on 10-150 ms after the rotor start (the idle's ramp; ``w`` averaged and
  ``w'`` differenced over :data:`SPAN`; a rough fit, for finding the release only). In the hand
  the reading differs from that by the hand's push, about ``g`` or more: the release is where
  the misfit (a running median over :data:`SPAN`) last rises above :data:`MISFIT` (or 6 times
  its median in the flight, when larger) before the rotor's start. The rotor's switches after
  it jolt the accelerometer by as much, so the accelerometer does not end the flight (it ended
  the real device's at the first switch in 52 of 55 throws). Without an accelerometer the
  search starts :data:`SEARCH_BACK` before the rotor's start.
- **The end**: the log's; a catch, only where the fit finds one (:func:`catch_candidates`, the
  gyroscope's impulses, are where it looks).

The fitted window starts :data:`START_MARGIN` after the last sample the fingers' touch disturbs
and ends :data:`END_MARGIN` before a catch.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import median_filter

from ..._html import headline_html, headline_repr
from ..fit.segments import IMPULSE_SPAN, impulses
from .throwlog import Throw

__all__ = ["END_MARGIN", "MIN_FLIGHT", "MISFIT", "SEARCH_BACK", "SPAN", "START_MARGIN", "Window", "catch_candidates",
           "MoreThrowsWarning", "find_flight", "rotor_start", "skew", "spin_up_after"]

#: The misfit of the free-fall accelerometer model above which a sample is held, m/s^2 (g / 2).
MISFIT = 0.5 * 9.80665
#: The span of the averages and differences used to find the flight, s.
SPAN = 0.004
#: Left out after the release that the residuals show and before a catch, s.
START_MARGIN = 0.010
#: Left out before a catch, s.
END_MARGIN = 0.005
#: How far before the rotor's start the release is looked for without an accelerometer, s (the
#: firmware starts the rotor 0.06-0.12 s after it senses the release).
SEARCH_BACK = 0.2
#: The shortest flight fitted, s.
MIN_FLIGHT = 0.15


@dataclass(frozen=True)
class Window:
    """A throw's flight: the fitted samples ``[first, stop)``, the rotor's first moving sample,
    and the release and catch times (s); ``reason`` says why there is none (then the rest is
    meaningless).

    Examples
    --------
    >>> from tumble.analysis.tensor.flight import Window
    >>> Window(10, 2000, 30, 0.25, 0.75, "").reason
    ''
    """

    HEADLINE = (("t_release", "release", "s"), ("t_end", "end", "s"), ("first", "first sample", ""), ("stop", "stop", ""),
                ("rotor", "rotor start", ""), ("reason", "reason", ""))
    __repr__ = headline_repr
    _repr_html_ = headline_html

    first: int
    stop: int
    rotor: int
    t_release: float
    t_end: float
    reason: str


def skew(v: np.ndarray) -> np.ndarray:
    """The cross-product matrices ``[v]x`` of vectors ``(..., 3)``: ``[v]x r = v x r``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.flight import skew
    >>> (skew(np.array([1.0, 2.0, 3.0])) @ np.array([0.0, 0.0, 1.0])).tolist()   # (1, 2, 3) x z
    [2.0, -1.0, 0.0]
    """
    v = np.asarray(v, float)
    z = np.zeros(v.shape[:-1])
    return np.stack([np.stack([z, -v[..., 2], v[..., 1]], -1), np.stack([v[..., 2], z, -v[..., 0]], -1),
                     np.stack([-v[..., 1], v[..., 0], z], -1)], -2)


def rotor_start(rotor: np.ndarray) -> int | None:
    """The rotor's first moving sample (module docstring), or None when it never reaches 50 rad/s.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.flight import rotor_start
    >>> rotor_start(np.r_[np.zeros(10), 3.0, 40.0, 400.0, 1000.0, 1400.0])
    10
    >>> rotor_start(np.zeros(20)) is None
    True
    """
    speed = np.abs(np.asarray(rotor, float))
    top = float(speed.max()) if speed.size else 0.0
    if top < 50.0:
        return None
    cross = int(np.argmax(speed > 0.1 * top))
    before = speed[:cross]
    if before.size == 0:
        return 0
    level = float(np.median(before) + 5 * 1.4826 * np.median(np.abs(before - np.median(before))))
    still = np.flatnonzero(before <= level)
    return int(still[-1]) + 1 if still.size else 0


def _rates(t: np.ndarray, omega: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
    """``w`` averaged and ``w'`` differenced over ``+-k`` samples."""
    n = t.size
    i = np.arange(n)
    lo, hi = np.maximum(i - k, 0), np.minimum(i + k, n - 1)
    wdot = (omega[hi] - omega[lo]) / np.maximum(t[hi] - t[lo], 1e-12)[:, None]
    c = np.vstack([np.zeros(3), np.cumsum(omega, axis=0)])
    w = (c[hi + 1] - c[lo]) / (hi - lo + 1)[:, None]
    return w, wdot


def _run(ok: np.ndarray, inside: int) -> tuple[int, int]:
    """The run ``[a, b)`` of True around index ``inside``."""
    bad = np.flatnonzero(~ok)
    a = int(bad[bad < inside].max()) + 1 if np.any(bad < inside) else 0
    b = int(bad[bad > inside].min()) if np.any(bad > inside) else ok.size
    return a, b


def catch_candidates(t: np.ndarray, omega: np.ndarray, rotor: int, keep: np.ndarray | None = None) -> list[int]:
    """Where a catch may end the flight: the first sample of each run of impulses
    (:func:`tumble.analysis.fit.segments.impulses`) 0.1 s or more after the rotor's start, in order,
    runs less than :data:`SPAN` apart joined, none where the gyroscope is at its rail (``keep``
    False: a clipped axis's corners are no impulse). The rotor's own switches can show as impulses
    too (the reaction of a spin-up turns a light body fast): the fit decides which end its free
    motion explains.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.flight import catch_candidates
    >>> t = np.arange(4000) / 4000.0
    >>> w = np.tile([3.0, 1.0, 0.5], (4000, 1))
    >>> w[3000:] *= np.exp(-(t[3000:, None] - 0.75) / 0.01)   # caught at 0.75 s
    >>> [round(float(t[k]), 3) for k in catch_candidates(t, w, 400)]   # the impulses' span reaches 10 ms before it
    [0.742]
    """
    kicked = impulses(t, omega) & (t >= t[rotor] + 0.1)
    if keep is not None:
        clipped = ~np.all(keep, axis=1)
        near = np.convolve(clipped.astype(float), np.ones(2 * int(round(0.5 * IMPULSE_SPAN / float(np.median(np.diff(t))))) + 1),
                           mode="same") > 0
        kicked &= ~near
    starts = np.flatnonzero(np.diff(np.r_[0, kicked.astype(int)]) == 1)
    out: list[int] = []
    for k in starts:
        if not out or t[k] - t[out[-1]] > SPAN:
            out.append(int(k))
    return out


class MoreThrowsWarning(UserWarning):
    """A throw's log in which the rotor spins up again after the fitted flight: most likely a second
    throw in one log, which is not fitted (:func:`spin_up_after`); a command prints it in one line.

    Examples
    --------
    >>> from tumble.analysis.tensor.flight import MoreThrowsWarning
    >>> issubclass(MoreThrowsWarning, UserWarning), MoreThrowsWarning.cli_one_line
    (True, True)
    """

    cli_one_line = True


def spin_up_after(rotor: np.ndarray, k: int) -> int | None:
    """The first sample after ``k`` at which the rotor, having slowed below a fifth of its top speed
    up to ``k``, is back above half of it: the firmware's next spin-up (each throw's rotor is braked
    after the catch and spun up after the next release), or None.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.flight import spin_up_after
    >>> one = np.r_[np.zeros(5), np.full(10, 1300.0), np.linspace(1300.0, 0.0, 10), np.zeros(5)]
    >>> spin_up_after(one, 15), spin_up_after(np.r_[one, np.full(5, 1250.0)], 15)
    (None, 30)
    """
    speed = np.abs(np.asarray(rotor, float))
    top = float(speed[:k].max()) if k > 0 else 0.0
    slow = np.flatnonzero(speed[k:] < 0.2 * top)
    if top <= 0.0 or slow.size == 0:
        return None
    again = np.flatnonzero(speed[k + int(slow[0]):] > 0.5 * top)
    return k + int(slow[0]) + int(again[0]) if again.size else None


def find_flight(throw: Throw, keep: np.ndarray) -> Window:
    """Where a throw's free flight may lie (module docstring): the search window that the fit
    of :func:`~tumble.analysis.tensor.throw.fit_flown` narrows by what the free motion explains.

    Parameters
    ----------
    throw : Throw
    keep : ndarray of bool, shape (n, 3)
        The gyroscope's samples within its range.

    Returns
    -------
    Window
        ``first`` the sensed release (the accelerometer's free fall; without an accelerometer
        :data:`SEARCH_BACK` before the rotor's start), ``stop`` the log's end.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.flight import find_flight
    >>> from tumble.analysis.tensor.synthetic import combine, example_object, synthetic_throw, throw_times, true_device
    >>> throw = synthetic_throw(4, combine(true_device(), example_object()))
    >>> w = find_flight(throw, np.ones(throw.omega.shape, bool))
    >>> tt = throw_times(4)
    >>> w.reason, bool(abs(w.t_release - tt.apparent) < 0.003), w.stop == throw.t.size   # within 3 ms of the sensed release
    ('', True, True)
    """
    t, omega = throw.t, throw.omega
    s = rotor_start(throw.rotor)
    if s is None:
        return Window(0, 0, 0, np.nan, np.nan, "the rotor did not spin up (it never reached 50 rad/s): without "
                                               "its reaction the tensor's scale is undetermined")
    dt = float(np.median(np.diff(t[s:]))) if t.size - s > 2 else float(np.median(np.diff(t)))
    k = max(1, int(round(0.5 * SPAN / dt)))
    a = int(np.searchsorted(t, t[s] - SEARCH_BACK))
    if throw.accel is not None:
        w, wdot = _rates(t, omega, k)
        M = skew(wdot) + skew(w) @ skew(w)
        good = np.all(keep, axis=1)
        after = (t >= t[s] + 0.01) & (t <= t[s] + 0.15)
        fit = good & after
        if np.count_nonzero(fit) < 20:
            railed, there = int(np.count_nonzero(after & ~good)), int(np.count_nonzero(after))
            # a range given too small (gyro_full_scale = 35 meant as rad/s, read as deg/s) leaves every sample at it,
            # and so do rates in deg/s read as rad/s; times in us read as ns leave no sample there at all
            why = (f" (none in the 0.15 s after it: the log spans {t[-1] - t[0]:.3g} s; its times in another unit than "
                   f"the header says?)") if there == 0 else "" if 2 * railed < there else (
                f" ({railed} of its {there} samples there at the gyroscope's range: is the range too "
                f"small? A device file's gyro_full_scale is in deg/s, --saturation in rad/s; or the rates in deg/s "
                f"under a rad/s header? Or thrown faster than the gyroscope reads: throw it slower)")
            return Window(0, 0, s, np.nan, np.nan, f"too few samples after the rotor start to find the flight{why}")
        A = np.concatenate([M[fit], np.broadcast_to(np.eye(3), (np.count_nonzero(fit), 3, 3))], axis=2).reshape(-1, 6)
        x = np.linalg.lstsq(A, throw.accel[fit].reshape(-1), rcond=None)[0]
        misfit = np.linalg.norm(throw.accel - (M @ x[:3] + x[3:]), axis=1)
        misfit = median_filter(np.where(good, misfit, 0.0), size=2 * k + 1, mode="nearest")
        limit = max(MISFIT, 6.0 * float(np.median(misfit[fit])))
        before = max(s - 2 * k - 1, 0)  # the rotor's start shakes the accelerometer: look before it
        a = max(_run(misfit < limit, before)[0], a)
    if t[-1] - t[a] < MIN_FLIGHT:
        return Window(a, t.size, s, float(t[a]), float(t[-1]),
                      f"the flight found lasts {t[-1] - t[a]:.3g} s, less than the {MIN_FLIGHT} s fitted")
    return Window(a, t.size, s, float(t[a]), float(t[-1]), "")
