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
- **a phone turned on in the fingers after the catch** (``"turn"``): the hand closes and then
  rolls the phone about one of its axes, the axis coning at a few hertz and the spin slowing,
  for 0.3-1 s: a smooth motion that a torque-free model with drag follows, of some symmetric
  body (:func:`turned_in_hand`), not a free flight;
- **a phone spinning on a table** (``"table"``): it lands flat, spins about its normal slowed
  by the table's Coulomb friction (a constant torque: the spin falls linearly) and rocks a few
  degrees (:func:`spun_on_table`), until it stops and is picked up;
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

from ...dynamics.euler import cross, euler_rhs
from ...dynamics.methods.exact_omega import free_omega


class TossBody(Protocol):
    """What these functions read of a :class:`~tumble.analysis.fit.synthetic.TossBody`."""

    @property
    def moments(self) -> tuple:
        """Principal moments, kg m^2, ascending."""

    @property
    def length(self) -> float:
        """The plate's length along principal axis 1, m."""

    @property
    def width(self) -> float:
        """The plate's width along principal axis 2, m."""

__all__ = ["ENDINGS", "after_hand", "after_landing", "gyrostat_flight", "smooth_noise", "spun_on_table", "turned_in_hand"]

#: How a toss may end: ``"catch"`` (the spin killed in the hand), ``"hand"`` (caught and turned
#: on in the hand), ``"landing"`` (an impact, bounces and rolling), or ``"mixed"`` (one of the
#: three drawn for each toss), ``"turn"`` (caught and turned smoothly in the fingers) or
#: ``"table"`` (landed flat and spun on a table).
ENDINGS = ("catch", "hand", "landing", "mixed", "turn", "table")


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
        if np.any(sel):  # torque-free between bounces: the closed form (Landau & Lifshitz sec. 37)
            w[sel] = free_omega(I[None], w0[None], tau[sel] - t0)[0]
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
        return euler_rhs(w, I, cross(h, w) - hdot + drag(w))  # the rotor on the body: h x w - h'

    sol = solve_ivp(rhs, (0.0, duration), w0, method="DOP853", rtol=1e-9, atol=1e-10, dense_output=True,
                    max_step=ramp / 4)
    return sol.sol(times).T


def turned_in_hand(rng: np.random.Generator, tau: np.ndarray, length: float, w_end: np.ndarray, spin: float,
                   level: np.ndarray) -> np.ndarray:
    """omega (principal frame, rad/s) of a phone caught and then turned smoothly in the fingers,
    at times ``tau`` (s from the catch) over ``length`` s: a grip of 20-60 ms takes omega from the
    flight's last ``w_end`` to a turning about a random body axis ``a`` at ``spin`` rad/s whose
    direction cones about ``a`` (half-angle 5-25 deg) at ``k`` times the axial rate (``k``
    -0.9 to 0.9: the body-frame precession ``(I_a - I_t) / I_t`` of a free symmetric body,
    Landau & Lifshitz, *Mechanics*, sec. 36), slowed as by a quadratic drag
    (``s / (1 + c s t)``, ``c s`` 0.5-3 /s) and blended into the hold's ``level`` over its last
    15 %. Such a stretch follows a torque-free motion with drag, of another body: only where it
    lies (right after an impact, no throw before it) says it is no flight.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.endings import turned_in_hand
    >>> tau = np.arange(0.0, 0.6, 0.01)
    >>> w = turned_in_hand(np.random.default_rng(1), tau, 0.6, np.array([0.5, 12.0, 0.3]), 10.0, np.zeros((60, 3)))
    >>> bool(np.linalg.norm(w[0] - [0.5, 12.0, 0.3]) < 1e-9), bool(4.0 < np.linalg.norm(w[10:30], axis=1).mean() < 10.0)
    (True, True)
    """
    grip = rng.uniform(0.02, 0.06)
    a = _unit(rng)
    b = np.cross(a, _unit(rng))
    b /= np.linalg.norm(b)
    c = np.cross(a, b)
    cone, slow = np.deg2rad(rng.uniform(5.0, 25.0)), rng.uniform(0.5, 3.0) / spin
    # the cone turns at k times the axial rate, k = (I_a - I_t) / I_t of the symmetric body it
    # mimics (-0.7 .. 0.9: prolate to oblate); the angle is k times the axial turn so far
    k = rng.choice([-1.0, 1.0]) * rng.uniform(0.3, 0.9) if rng.random() < 0.5 else -rng.uniform(0.3, 0.7)
    phase = k * np.cos(cone) * np.log1p(slow * spin * tau) / slow + rng.uniform(0.0, 2 * np.pi)
    direction = np.cos(cone) * a + np.sin(cone) * (np.cos(phase)[:, None] * b + np.sin(phase)[:, None] * c)
    turning = (spin / (1.0 + slow * spin * tau))[:, None] * direction
    x = np.clip((tau / length - 0.85) / 0.15, 0.0, 1.0)[:, None]  # the hold takes over in the last 15 %
    turning = (1.0 - x) * turning + x * level
    g = np.clip(tau / grip, 0.0, 1.0)[:, None]
    return (1.0 - g) * w_end + g * turning


def spun_on_table(rng: np.random.Generator, body: TossBody, tau: np.ndarray, length: float, spin: float,
                  level: np.ndarray) -> np.ndarray:
    """omega (principal frame, rad/s) of a phone that lands flat on a table and spins there, at
    times ``tau`` (s from the impact) over ``length`` s: the impact leaves it spinning at ``spin``
    rad/s about its normal (principal axis 3); the table's Coulomb friction, a torque of constant
    size ``mu m g r`` (``mu`` 0.2-0.4, ``r`` a third of the diagonal; Goyal, Ruina & Papadopoulos,
    *Wear* 143, 1991), slows it linearly to rest within 80 % of ``length`` (sooner if friction
    wins), while it rocks about its two other axes (1-3 deg at 8-15 Hz, decaying in 0.1 s); then
    it lies still and is picked up (``level``, the hold's motion).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.endings import spun_on_table
    >>> from tumble.analysis.fit.synthetic import TOSS_BODIES
    >>> tau = np.arange(0.0, 0.8, 0.005)
    >>> w = spun_on_table(np.random.default_rng(2), TOSS_BODIES["phone"], tau, 0.8, 12.0, np.zeros((len(tau), 3)))
    >>> bool(abs(w[0, 2]) > 10.0), bool(np.all(np.diff(np.abs(w[:40, 2])) <= 0.0)), bool(np.linalg.norm(w[-1]) < 1e-9)
    (True, True, True)
    """
    mu, g = rng.uniform(0.2, 0.4), 9.81
    # Coulomb friction on a plate of mass m: a torque mu m g r, r about a third of its diagonal d;
    # with I3 = m d^2 / 12 (a thin plate's) the deceleration is 4 mu g / d, rad/s^2
    diagonal = float(np.hypot(body.length, body.width))
    decel = 4.0 * mu * g / diagonal
    stop = min(0.8 * length, spin / decel)
    sign = rng.choice([-1.0, 1.0])
    w = np.zeros((len(tau), 3))
    w[:, 2] = sign * np.clip(spin - decel * tau, 0.0, None)
    rock = np.deg2rad(rng.uniform(1.0, 3.0)) * 2 * np.pi * rng.uniform(8.0, 15.0)
    fr, ph = rng.uniform(8.0, 15.0, 2), rng.uniform(0.0, 2 * np.pi, 2)
    for k in range(2):
        w[:, k] = rock * np.exp(-tau / 0.1) * np.sin(2 * np.pi * fr[k] * tau + ph[k])
    rest = tau >= stop
    w[rest] = 0.0
    late = tau >= 0.8 * length
    if np.any(late):
        x = (tau[late] - 0.8 * length) / max(0.2 * length, 1e-9)
        w[late] = x[:, None] * level[late]
    return w
