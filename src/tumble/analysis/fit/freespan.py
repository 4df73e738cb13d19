"""Where a flight falls free, by its accelerometer: the release and the catch or impact.

The free fall's residual ``|f - A r - c|`` (:func:`~tumble.analysis.fit.freefall.free_fall_residual`,
the offset ``r`` and constant ``c`` fitted on a candidate's middle,
:func:`~tumble.analysis.fit.freefall.fit_offset`) is about the accelerometer's noise in free
flight and large under any contact. :func:`free_span` cuts a candidate flight where it leaves
the free fall, sharply, and refuses a stretch that is not free (the phone swung about in the
hand); the threshold grows away from the flight's middle by the air's largest force at the
speed the fall has gained (:func:`air_allowance`), and :func:`grown_free_span` lets the free
fall run past a candidate's end that no contact made.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..._html import headline_html, headline_repr
from ...dynamics.environment.earth import STANDARD_GRAVITY
from ...typing import ArrayLike
from .freefall import fit_offset, free_fall_residual, rate_derivative

__all__ = ["FREE_FACTOR", "FREE_FLOOR", "MAX_CONTACT", "MAX_DRAG", "MAX_FALL", "MAX_OFFSET", "MIDDLES", "FreeSpan",
           "air_allowance", "free_span", "grown_free_span"]

#: The residual that ends a flight: this many times its median in the flight's middle ...
FREE_FACTOR = 5.0
#: ... plus this floor, m/s^2 (the derivative's error at high spin, the air's varying force).
FREE_FLOOR = 1.0
#: The largest drag per unit mass and squared speed of a body tossed by hand, ``rho C_D A / 2m``,
#: 1/m: a phone broadside 0.045, a paperback 0.05-0.1, a racquet's head about 0.1 (Hoerner,
#: *Fluid-Dynamic Drag*, 1965, ch. 3: a flat plate's ``C_D`` 1.17; a tennis ball's 0.02).
MAX_DRAG = 0.1
#: The time from the top of a toss, s, past which the air's allowance stops growing: half the
#: longest hand toss (1.5 s, 7.4 m/s at the release and the catch; a hand's hold reads ``g``
#: against the allowance's 5.4 m/s^2 there).
MAX_FALL = 0.75
#: The median residual, m/s^2, above which a candidate's middle is not in free fall (a hand's
#: grip reads ~g; the free fall's residual is the noise and the derivative's error, ~0.1-0.5).
MAX_CONTACT = 2.0

#: The largest sensor offset from the centre of mass taken for a body tossed by hand, m (a
#: phone on a racquet's handle sits some 0.3 m from its centre of mass).
MAX_OFFSET = 0.5

def _one_sided(t: np.ndarray, w: np.ndarray, side: int) -> np.ndarray:
    """``omega'`` from the quadratic through a sample and the two before it (``side = -1``) or
    after it (``+1``), rad/s^2 (Fornberg 1988); the record's ends take the central difference."""
    out = rate_derivative(t, w)
    if len(t) < 3:
        return out
    k = np.arange(2, len(t)) if side < 0 else np.arange(0, len(t) - 2)
    i1, i2 = k + side, k + 2 * side
    h1, h2 = t[i1] - t[k], t[i2] - t[i1]
    c0 = -(2 * h1 + h2) / (h1 * (h1 + h2))
    c1 = (h1 + h2) / (h1 * h2)
    c2 = -h1 / (h2 * (h1 + h2))
    out[k] = c0[:, None] * w[k] + c1[:, None] * w[i1] + c2[:, None] * w[i2]
    return out


def air_allowance(tau: ArrayLike) -> np.ndarray:
    """The air's largest force per unit mass on a body ``tau`` seconds from the top of its toss,
    m/s^2: ``MAX_DRAG (g tau)^2`` (the speed ``g tau`` it has gained falling, or has still to lose
    rising), ``tau`` clipped at :data:`MAX_FALL`. The free fall's residual grows so towards a
    flight's ends, as the air's force turns with the body (the fit's constant ``c`` holds only its
    mean), and a threshold fixed at the middle's level would cut a fast flight early.

    Examples
    --------
    >>> from tumble.analysis.fit.freespan import air_allowance
    >>> air_allowance([0.0, 0.5, 2.0]).round(2).tolist()   # m/s^2: at the top, 0.5 s from it, and capped
    [0.0, 2.4, 5.41]
    """
    return MAX_DRAG * (STANDARD_GRAVITY * np.minimum(np.abs(np.asarray(tau, float)), MAX_FALL)) ** 2



@dataclass(frozen=True)
class FreeSpan:
    """Where a candidate flight falls free, by its accelerometer (:func:`free_span`).

    Attributes
    ----------
    first, stop : int
        The free samples: ``[first, stop)``.
    free : bool
        Whether the candidate's middle is in free fall.
    reason : str
        Why not ("" when free).
    offset, offset_std : ndarray, shape (3,)
        The sensor's position from the centre of mass, sensor axes, m, and its standard uncertainty.
    contact : float
        Median residual ``|f - A r - c|`` in the middle, m/s^2.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.freespan import FreeSpan
    >>> span = FreeSpan(10, 90, True, "", np.array([0.03, 0.0, 0.05]), np.full(3, 0.001), 0.2)
    >>> span.summary()["sensor_offset"], span.stop - span.first
    ([0.03, 0.0, 0.05], 80)
    """

    HEADLINE = (("free", "free", ""), ("first", "first sample", ""), ("stop", "stop", ""), ("offset", "sensor offset", "m"),
                ("contact", "contact residual", "m/s^2"), ("reason", "reason", ""))
    __repr__ = headline_repr
    _repr_html_ = headline_html

    first: int
    stop: int
    free: bool
    reason: str
    offset: np.ndarray
    offset_std: np.ndarray
    contact: float

    def summary(self) -> dict:
        """JSON-ready: ``sensor_offset`` and ``sensor_offset_std`` (m, sensor axes).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.freespan import FreeSpan
        >>> sorted(FreeSpan(0, 50, True, "", np.zeros(3), np.zeros(3), 0.1).summary())
        ['sensor_offset', 'sensor_offset_std']
        """
        return {"sensor_offset": [float(v) for v in self.offset], "sensor_offset_std": [float(v) for v in self.offset_std]}


#: Middles tried, as fractions of a candidate (as the gyroscope's search tries its seeds).
MIDDLES = ((0.35, 0.8), (0.1, 0.5), (0.5, 0.9))


def free_span(t: ArrayLike, f: ArrayLike, omega: ArrayLike, a: int, b: int, *, accel_inside: ArrayLike | None = None,
              omega_inside: ArrayLike | None = None) -> FreeSpan:
    """The free-falling part of the candidate ``[a, b)`` (module docstring).

    ``r`` and ``c`` are fitted on the candidate's middle (35-80 %; then its first and second
    half, :data:`MIDDLES`), refitted twice without the samples beyond the threshold; the flight then reaches, from the middle outwards, up to the first
    two samples in a row (from the centre of its free samples) whose residual exceeds :data:`FREE_FACTOR` times the middle's median
    plus :data:`FREE_FLOOR` and the air's allowance at its distance from the middle (:func:`air_allowance`; the least of the residuals with ``omega'`` a central and a one-sided
    difference: at the edge of a contact the central difference reaches across it). A middle whose median residual exceeds :data:`MAX_CONTACT` (or
    whose fitted offset exceeds :data:`MAX_OFFSET`) is not in free fall.

    Parameters
    ----------
    t : array_like, shape (n,)
        Times, s.
    f : array_like, shape (n, 3)
        Specific force, sensor axes, m/s^2.
    omega : array_like, shape (n, 3)
        Gyroscope samples, sensor axes, rad/s.
    a, b : int
        The candidate: samples ``[a, b)``.
    accel_inside, omega_inside : array_like of bool, shape (n, 3), optional
        The accelerometer's and the gyroscope's readings inside their ranges
        (:func:`~tumble.analysis.fit.single.saturation_mask`; default all). A sample with an axis
        at either rail is left out of the offset's fit; one at the gyroscope's rail does not cut
        the flight (its ``omega`` is not known), and the accelerometer's rail is a censored
        reading (:func:`free_fall_residual`).

    Returns
    -------
    FreeSpan

    Examples
    --------
    A phone falling free for 0.6 s between a hand at rest (reading ``g``) and a catch:

    >>> import numpy as np
    >>> from tumble.analysis.fit.freefall import rigid_acceleration
    >>> from tumble.analysis.fit.freespan import free_span
    >>> t = np.arange(0.0, 1.0, 0.01)
    >>> w = np.stack([5 * np.cos(4 * t), 12 + 0 * t, 5 * np.sin(4 * t)], axis=1)
    >>> f = rigid_acceleration(w, np.gradient(w, t, axis=0), [0.05, 0.0, 0.02])
    >>> f[:20] += [0.0, 0.0, 9.81]
    >>> f[80:] += [0.0, 30.0, 9.81]
    >>> span = free_span(t, f, w, 0, 100)
    >>> span.free, span.first, span.stop, span.offset.round(3).tolist()
    (True, 20, 80, [0.05, 0.0, 0.02])
    """
    t, f, omega = np.asarray(t, float), np.asarray(f, float), np.asarray(omega, float)
    wd = rate_derivative(t[a:b], omega[a:b])
    sided = [_one_sided(t[a:b], omega[a:b], side) for side in (-1, 1)]
    w, ff = omega[a:b], f[a:b]
    n = b - a
    inside = np.ones((n, 3), bool) if accel_inside is None else np.asarray(accel_inside, bool)[a:b]
    known = np.ones(n, bool) if omega_inside is None else np.all(np.asarray(omega_inside, bool)[a:b], axis=1)
    fits = known & np.all(inside, axis=1)  # the samples the offset's fit may use

    def residual(d: np.ndarray) -> np.ndarray:  # none where omega is not known: no cut there
        return np.where(known, free_fall_residual(ff, w, d, r, c, inside), 0.0)

    best = None
    for lo, hi in MIDDLES:
        i, j = int(lo * n), max(int(hi * n), int(lo * n) + 6)
        use = mid = i + np.flatnonzero(fits[i:j])
        if len(use) < 6:
            continue
        for _ in range(3):  # robust: refitted without the samples under contact (a catch's start in the middle)
            r, c, r_std = fit_offset(ff[use], w[use], wd[use])
            e = residual(wd)
            level = float(np.median(e[mid]))
            use = i + np.flatnonzero((e[i:j] <= FREE_FACTOR * level + FREE_FLOOR) & fits[i:j])
            if len(use) < 6:
                break
        if best is None or level < best[0]:
            best = (level, i, j, r, c, r_std, e)
        if level <= MAX_CONTACT and np.linalg.norm(r) <= MAX_OFFSET:
            break
    if best is None:
        return FreeSpan(a, b, False, "not free: the accelerometer or the gyroscope is at its rail through the middle "
                        "of the candidate flight", np.full(3, np.nan), np.full(3, np.nan), np.nan)
    level, i, j, r, c, r_std, e = best
    # at a contact's edge the central difference reaches across it: the one-sided ones do not
    e = np.minimum(e, np.minimum(*(residual(d) for d in sided)))
    if level > MAX_CONTACT or np.linalg.norm(r) > MAX_OFFSET:
        what = f"{level:.2g} m/s^2 of contact force" if level > MAX_CONTACT else \
            f"a sensor {np.linalg.norm(r):.2g} m from the centre of mass (at most {MAX_OFFSET} m)"
        return FreeSpan(a, b, False, f"not free: the accelerometer reads {what} where the gyroscope saw a "
                        f"candidate flight (the phone held or moved by the hand)", r, r_std, level)
    first, stop = _free_limits(t[a:b], e, level, i, j)
    return FreeSpan(a + first, a + stop, True, "", r, r_std, level)


def grown_free_span(t: ArrayLike, f: ArrayLike, omega: ArrayLike, a: int, b: int, lo: int, hi: int,
                    **inside: ArrayLike | None) -> FreeSpan:
    """:func:`free_span` of the candidate ``[a, b)``, grown by 0.3 s at a time, within ``[lo, hi)``
    (the gyroscope's stretch of spin), at an end the free fall reaches: there the candidate, not
    a contact, ended it (the gyroscope's impulse test may split a flight where the rate turns
    fast, and the free fall goes on). ``inside``: :func:`free_span`'s keywords.

    Examples
    --------
    A flight from 0.1 s to 0.9 s, held before and caught after, and a candidate that ends at 0.5 s:

    >>> import numpy as np
    >>> from tumble.analysis.fit.freefall import rigid_acceleration
    >>> from tumble.analysis.fit.freespan import grown_free_span
    >>> t = np.linspace(0.0, 1.0, 101)
    >>> w = np.column_stack([3 + t, 10 * np.cos(2 * t), 10 * np.sin(2 * t)])
    >>> f = rigid_acceleration(w, np.gradient(w, t, axis=0), [0.0, 0.04, 0.0]) + (t[:, None] < 0.1) * [0, 0, 9.81]
    >>> f[90:] += [20.0, 0.0, 9.81]
    >>> span = grown_free_span(t, f, w, 5, 50, 0, 101)
    >>> span.first, span.stop
    (10, 90)
    """
    t = np.asarray(t, float)
    span = free_span(t, f, omega, a, b, **inside)
    for _ in range(10):
        grow = (span.first <= a < span.stop and a > lo, span.stop >= b > span.first and b < hi)
        if not span.free or not any(grow):
            break
        a = max(lo, int(np.searchsorted(t, t[a] - 0.3))) if grow[0] else a
        b = min(hi, int(np.searchsorted(t, t[b - 1] + 0.3))) if grow[1] else b
        span = free_span(t, f, omega, a, b, **inside)
    return span


def _free_limits(t: np.ndarray, e: np.ndarray, level: float, i: int, j: int) -> tuple[int, int]:
    """The free samples ``[first, stop)`` about the middle ``[i, j)`` (:func:`free_span`): up to the
    first two samples in a row whose residual ``e`` exceeds the threshold, which grows away from
    the middle by the air's largest force at the speed the fall has gained since
    (:func:`air_allowance`)."""
    bad = e > FREE_FACTOR * level + FREE_FLOOR + air_allowance(t - 0.5 * (t[i] + t[j - 1]))
    pairs = bad[:-1] & bad[1:]
    core = i + int(np.median(np.flatnonzero(~bad[i:j])))  # the middle's free samples' centre
    before = np.flatnonzero(pairs[:core])
    after = np.flatnonzero(pairs[core:])
    first = int(before[-1]) + 2 if before.size else 0
    stop = core + int(after[0]) if after.size else len(e)
    while stop > core and bad[stop - 1]:  # the candidate's last sample, alone past the threshold: the catch's first
        stop -= 1
    while first < core and bad[first]:
        first += 1
    return first, stop
