"""How a synthetic toss ends, and a body that is not rigid: the parts of
:func:`~tumble.analysis.fit.synthetic.synthetic_recording` that make whole real recordings hard.

Recordings of phones tossed by hand (issue #29) show what a tidy catch hides:

- **a catch in the hand** (``"hand"``): the hand closes in 20-60 ms and then keeps turning the
  phone, at 5-18 rad/s for half a second or so, slowing to the hold's slow motion: the spin
  never drops below a few rad/s between the throw and the rest;
- **a landing** (``"landing"``, on a bed, a sofa or a table): an impact turns omega to a new
  direction and size in a few milliseconds, and the phone bounces and rolls for 0.3-1 s, each
  bounce another impulse, with short torque-free hops between them, until it lies still;
- **hand-held motion between tosses** of 3-10 rad/s when the phone is swung about, not only
  the slow drift and tremor of a steady hold (the ``hand`` range of ``synthetic_recording``);
- **an internal rotor spinning up** during the flight (a flywheel device, a vibration motor, a
  phone in a case with something loose): the body is a gyrostat, ``I w' = (I w + h) x w - h' +
  tau_drag`` (Hughes, *Spacecraft Attitude Dynamics*, 1986, ch. 7, eq. 7.1 with the rotor's
  axial momentum ``h = J s a`` ramping up), which no rigid body with drag can follow.

Each is drawn from its own random stream (``numpy.random.default_rng([seed, 29])``), so the
recordings made without them are the same as before, sample for sample.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol

import numpy as np
from scipy.integrate import solve_ivp


class TossBody(Protocol):
    """What these functions read of a :class:`~tumble.analysis.fit.synthetic.TossBody`."""

    @property
    def moments(self) -> tuple:
        """Principal moments, kg m^2, ascending."""

__all__ = ["ENDINGS", "after_hand", "after_landing", "gyrostat_flight", "smooth_noise"]

#: How a toss may end: ``"catch"`` (the spin killed in the hand), ``"hand"`` (caught and turned
#: on in the hand), ``"landing"`` (an impact, bounces and rolling), or ``"mixed"`` (one of the
#: three drawn for each toss).
ENDINGS = ("catch", "hand", "landing", "mixed")


def _unit(rng: np.random.Generator) -> np.ndarray:
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def smooth_noise(rng: np.random.Generator, n: int, dt: float, sigma: float, corner: float) -> np.ndarray:
    """Gaussian noise low-passed below ``corner`` Hz (a first-order filter run twice), standard
    deviation ``sigma``: the hand's motion, the gyroscope's coloured noise, a turning direction.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.endings import smooth_noise
    >>> x = smooth_noise(np.random.default_rng(0), 2000, 0.01, 0.3, 1.5)
    >>> round(float(np.std(x)), 6), bool(np.std(np.diff(x)) < 0.1 * np.std(x))   # slow: small steps
    (0.3, True)
    """
    from scipy.signal import lfilter

    x = rng.normal(size=n)
    a = np.exp(-2 * np.pi * corner * dt)
    for _ in range(2):
        x = lfilter([1 - a], [1, -a], x)
    s = np.std(x)
    return x * (sigma / s if s > 0 else 0.0)


def after_hand(rng: np.random.Generator, tau: np.ndarray, length: float, w_end: np.ndarray, spin: float,
               level: np.ndarray, dt: float) -> np.ndarray:
    """omega (principal frame, rad/s) of a phone caught and turned on in the hand, at times
    ``tau`` (s from the catch) over ``length`` s: a grip of 20-60 ms takes omega from the flight's
    last ``w_end`` to the hand's motion, a smooth random turning (below ~3 Hz) of ``spin`` rad/s
    that slows to the hold's ``level`` (rows of omega, as long as ``tau``) by the end.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.endings import after_hand
    >>> rng = np.random.default_rng(1)
    >>> tau = np.arange(0.0, 0.6, 0.01)
    >>> w = after_hand(rng, tau, 0.6, np.array([0.5, 12.0, 0.3]), 10.0, np.zeros((60, 3)), 0.01)
    >>> bool(np.linalg.norm(w[0] - [0.5, 12.0, 0.3]) < 1.0), bool(5.0 < np.linalg.norm(w[10:30], axis=1).mean() < 12.0)
    (True, True)
    """
    n = len(tau)
    grip = rng.uniform(0.02, 0.06)
    direction = np.stack([smooth_noise(rng, n, dt, 1.0, 2.0) for _ in range(3)], axis=1) + 2.0 * _unit(rng)
    direction /= np.linalg.norm(direction, axis=1, keepdims=True)
    x = np.clip(tau / length, 0.0, 1.0)
    turning = (spin * (1.0 - x * x))[:, None] * direction + level * x[:, None]
    g = np.clip(tau / grip, 0.0, 1.0)[:, None]
    return (1.0 - g) * w_end + g * turning


def after_landing(rng: np.random.Generator, body: TossBody, tau: np.ndarray, length: float, spin: float,
                  level: np.ndarray) -> np.ndarray:
    """omega (principal frame, rad/s) after a landing, at times ``tau`` (s from the impact) over
    ``length`` s: the impact turns omega to a random direction at ``spin`` rad/s, then every
    50-200 ms a bounce turns it again and keeps 50-85 % of it, with torque-free hops between;
    from 80 % of ``length`` the phone rolls to rest and is picked up (``level``, the hold's
    motion).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.endings import after_landing
    >>> from tumble.analysis.fit.synthetic import TOSS_BODIES
    >>> rng = np.random.default_rng(2)
    >>> tau = np.arange(0.0, 0.8, 0.005)
    >>> w = after_landing(rng, TOSS_BODIES["phone"], tau, 0.8, 15.0, np.zeros((len(tau), 3)))
    >>> round(float(np.linalg.norm(w[0])), 6), bool(np.linalg.norm(w[-1]) < 1.0)   # rad/s at impact; at rest by the end
    (15.0, True)
    """
    I = np.asarray(body.moments, float)
    w = np.zeros((len(tau), 3))
    t0, size = 0.0, spin
    stop = 0.8 * length
    while t0 < stop:
        hop = min(rng.uniform(0.05, 0.2), stop - t0)
        w0 = size * _unit(rng)
        sel = (tau >= t0) & (tau < t0 + hop)
        if np.any(sel):
            sol = solve_ivp(lambda _, x: np.cross(I * x, x) / I, (0.0, hop), w0, method="DOP853", rtol=1e-9,
                            atol=1e-10, dense_output=True)
            w[sel] = sol.sol(tau[sel] - t0).T
        t0 += hop
        size *= rng.uniform(0.5, 0.85)
    rest = tau >= stop
    if np.any(rest):
        x = (tau[rest] - stop) / max(length - stop, 1e-9)
        last = w[~rest][-1] if np.any(~rest) else np.zeros(3)
        w[rest] = np.exp(-8.0 * x)[:, None] * last + (x[:, None] * level[rest])
    return w


def gyrostat_flight(body: TossBody, w0: np.ndarray, duration: float, times: np.ndarray, axis: np.ndarray,
                    h_final: float, ramp: float, drag: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """omega (principal frame, rad/s) of a toss whose internal rotor spins up along ``axis`` (a
    unit vector, principal frame) from rest to the axial momentum ``h_final`` (kg m^2/s) in
    ``ramp`` s: ``I w' = (I w + h) x w - h' + drag(w)`` (Hughes 1986, eq. 7.1), DOP853 at
    rtol 1e-9.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.endings import gyrostat_flight
    >>> from tumble.analysis.fit.synthetic import TOSS_BODIES, plate_drag_torque
    >>> body = TOSS_BODIES["phone"]
    >>> I = np.array(body.moments)
    >>> w0 = np.array([0.3, 10.0, 0.2])
    >>> t = np.linspace(0.0, 0.6, 61)
    >>> no_drag = lambda w: np.zeros(3)
    >>> w = gyrostat_flight(body, w0, 0.6, t, np.array([0.0, 0.0, 1.0]), 0.2 * np.linalg.norm(I * w0), 0.3, no_drag)
    >>> h = np.outer(np.clip(t / 0.3, 0, 1) * 0.2 * np.linalg.norm(I * w0), [0.0, 0.0, 1.0])
    >>> L = np.linalg.norm(I * w + h, axis=1)          # the whole's |L| is kept (no external torque) ...
    >>> bool(np.ptp(L) < 1e-8 * L[0]), bool(np.ptp(np.linalg.norm(I * w, axis=1)) > 0.05 * L[0])   # ... the body's is not
    (True, True)
    """
    I = np.asarray(body.moments, float)
    a = np.asarray(axis, float)

    def rhs(s, w):
        on = s < ramp
        h = h_final * (s / ramp if on else 1.0) * a
        hdot = (h_final / ramp if on else 0.0) * a
        return (np.cross(I * w + h, w) - hdot + drag(w)) / I

    sol = solve_ivp(rhs, (0.0, duration), w0, method="DOP853", rtol=1e-9, atol=1e-10, dense_output=True,
                    max_step=ramp / 4)
    return sol.sol(times).T
