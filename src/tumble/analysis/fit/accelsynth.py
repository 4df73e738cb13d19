"""The accelerometer of a synthetic recording (:func:`~tumble.analysis.fit.synthetic.synthetic_recording`
with ``accel=True``): the specific force a phone's raw accelerometer reads through the whole record.

A raw accelerometer reads ``f = a - g`` in its own axes (Titterton & Weston, *Strapdown Inertial
Navigation Technology*, 2004, sec. 3.2). At the sensor, ``r`` from the centre of mass (fixed in
the body, anywhere on its plate within 80 % of its half-sides and 4 mm of its mid-plane: a
phone's sensor inside its 8 mm body, or a phone strapped to a racquet, up to 0.27 m along its
handle), ``a = a_cm + omega' x r + omega x
(omega x r)`` (Goldstein, Poole & Safko 2002, eq. 4.104;
:func:`~tumble.analysis.fit.freefall.rigid_acceleration`), so

    ``f = R^T (a_cm - g) + omega' x r + omega x (omega x r)``,

``R`` the attitude (body to world), integrated from the true body rates from a random attitude
of the first hold; ``a_cm - g`` is the contact force per unit mass, drawn per phase:

- **hold**: ``-g`` (the hand carries the weight) plus the hand's motion, 0.5-2 m/s^2 below ~3 Hz;
- **throw** (0.15-0.3 s): the hand's push up and forward, 1-4 g at its peak, its contact force
  falling to zero over the last tenth before the release;
- **free flight**: only the air on the body's plate
  (:func:`~tumble.analysis.fit.tossbody.plate_drag_force`) at the centre of mass's velocity ``v``
  (thrown up for half the flight time, 0-1 m/s sideways): across the plate, so it turns with
  the body, 0.3-2 m/s^2 at a phone's release and none at the top (Hoerner, *Fluid-Dynamic Drag*,
  1965, ch. 3), and none without air (a drag coefficient of 0);
- **catch**: a jolt of 20-60 m/s^2 over the catch, then the hand's hold;
- **caught and turned in the hand**: the grip's jolt, then the hand's force, 2-5 m/s^2, and ``-g``;
- **landing**: an impact of 50-300 m/s^2 over 5-20 ms (its impulse spread over two samples at
  least, as the accelerometer's own low-pass filter does), a smaller spike at each bounce (where
  the true omega jumps), then the table's normal force ``-g`` and the rolling, 0.3-1 m/s^2.

``omega'`` is the flight's exact derivative where the generator has it (the integrator's dense
output) and a central difference of the true rates elsewhere (contact phases, where the contact
force dominates). The sensor (Bosch BMI160/BMI270, ST LSM6DSO datasheets: noise density
150-180 ug/sqrt(Hz)): white noise of 0.01-0.04 m/s^2 per sample (above the datasheet, as phones
show), a bias of 0.05-0.2 m/s^2 per axis, scale errors of 0.5 %, quantisation of 16 g / 2^15 and
clipping at the full scale of +-16 g. Everything is drawn from its own random stream
(``numpy.random.default_rng([seed, 29, 1])``), so a recording made without the accelerometer is
the same as before, sample for sample.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from ..._html import headline_html, headline_repr
from ...dynamics.environment.earth import STANDARD_GRAVITY
from ...dynamics.special.quaternion import quat_multiply
from .endings import _unit, smooth_noise
from .freefall import rigid_acceleration
from .tossbody import TOSS_BODIES, TossBody, plate_drag_force

__all__ = ["ACCEL_FULL_SCALE", "SyntheticAccel", "attitude_from_rates", "phyphox_accel_csv", "synthetic_accel"]

#: The accelerometer's full scale, +-16 g, m/s^2.
ACCEL_FULL_SCALE = 16.0 * STANDARD_GRAVITY
_UP = np.array([0.0, 0.0, 1.0])
PHONE = TOSS_BODIES["phone"]


@dataclass(frozen=True)
class SyntheticAccel:
    """A synthetic accelerometer's samples and the truth behind them.

    Attributes
    ----------
    f : ndarray, shape (n, 3)
        Specific force, sensor axes, m/s^2 (noise, bias, scale, quantisation, clipping).
    offset : ndarray, shape (3,)
        The sensor's position from the centre of mass, sensor axes, m.
    bias : ndarray, shape (3,)
        The accelerometer's bias, sensor axes, m/s^2.
    noise : float
        White noise per sample, m/s^2.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.accelsynth import SyntheticAccel
    >>> SyntheticAccel(np.zeros((4, 3)), np.array([0.05, 0.0, 0.0]), np.zeros(3), 0.02).f.shape
    (4, 3)
    """

    HEADLINE = (("f", "specific force", ""), ("offset", "sensor offset", "m"), ("bias", "bias", "m/s^2"),
                ("noise", "noise", "m/s^2"))
    __repr__ = headline_repr
    _repr_html_ = headline_html

    f: np.ndarray
    offset: np.ndarray
    bias: np.ndarray
    noise: float


def attitude_from_rates(t: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Body-to-world quaternions (scalar last) at ``t``, the identity at ``t[0]``, integrated from
    the body rates ``w`` (rad/s): each interval's turn ``exp(w_mid dt)`` about the mean rate (the
    midpoint rule, second order), composed on the right (body-fixed increments). The products of
    the steps are taken as a parallel prefix scan (Hillis & Steele, Commun. ACM 29 (1986) 1170):
    ``log2(n)`` vectorized quaternion products instead of ``n`` Python ones.

    Examples
    --------
    A steady spin about z for 1 s at 2 rad/s turns the body by 2 rad:

    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.analysis.fit.accelsynth import attitude_from_rates
    >>> t = np.linspace(0.0, 1.0, 401)
    >>> q = attitude_from_rates(t, np.tile([0.0, 0.0, 2.0], (401, 1)))
    >>> bool(np.allclose(Rotation.from_quat(q[-1]).as_rotvec(), [0.0, 0.0, 2.0], atol=1e-12))
    True
    """
    t = np.asarray(t, float)
    w = np.asarray(w, float)
    q = np.empty((t.size, 4))
    q[0] = [0.0, 0.0, 0.0, 1.0]
    if t.size > 1:
        q[1:] = Rotation.from_rotvec(0.5 * (w[1:] + w[:-1]) * np.diff(t)[:, None]).as_quat()
    d = 1
    while d < t.size:
        q[d:] = quat_multiply(q[:-d], q[d:])
        d *= 2
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def _attitude(rng: np.random.Generator, t: np.ndarray, w: np.ndarray) -> Rotation:
    """Body-to-world attitude at ``t`` from a random one, integrated from the body rates ``w`` (:func:`attitude_from_rates`)."""
    return Rotation.random(random_state=rng) * Rotation.from_quat(attitude_from_rates(t, w))


def _bump(x: np.ndarray) -> np.ndarray:
    return np.sin(np.pi * np.clip(x, 0.0, 1.0))


def _contact(rng: np.random.Generator, tt: np.ndarray, w_body: np.ndarray, segments, dt: float,
             body: TossBody, attitude: Rotation) -> np.ndarray:
    """``a_cm - g`` (world axes, m/s^2) per phase (module docstring)."""
    g = STANDARD_GRAVITY
    n = len(tt)
    hand = np.stack([smooth_noise(rng, n, dt, rng.uniform(0.5, 2.0) / np.sqrt(3), 1.5) for _ in range(3)], axis=1)
    F = g * _UP + hand
    v0 = None
    for kind, t0, length, _ in segments:
        sel = (tt >= t0) & (tt < t0 + length)
        tau = tt[sel] - t0
        x = tau / length
        if kind == "throw":
            push = rng.uniform(1.0, 4.0) * g * _unit_up(rng)
            taper = np.clip((1.0 - x) / 0.1, 0.0, 1.0)[:, None]
            F[sel] = (g * _UP + _bump(x)[:, None] * push + hand[sel]) * taper
        elif kind == "flight":
            v0 = np.r_[rng.uniform(-1.0, 1.0, 2), 0.5 * g * length]  # up for half the flight, m/s
            v = v0 - g * _UP * tau[:, None]
            turn = attitude[np.flatnonzero(sel)]
            F[sel] = turn.apply(plate_drag_force(body, turn.inv().apply(v)))
        elif kind in ("catch", "hand", "landing", "turn", "table"):
            kind = {"turn": "hand", "table": "landing"}.get(kind, kind)  # in the fingers; on the table
            grip = min(length, rng.uniform(0.04, 0.12)) if kind != "landing" else rng.uniform(0.005, 0.02)
            grip = max(grip, 2.0 * dt)  # an impulse spread over two samples at least
            peak = (rng.uniform(20.0, 60.0) if kind != "landing" else rng.uniform(50.0, 300.0))
            jolt = peak * _bump(tau / grip)[:, None] * _unit_up(rng)
            held = np.clip(tau / grip, 0.0, 1.0)[:, None] * (g * _UP)
            extra = hand[sel] * (rng.uniform(2.0, 5.0) / 1.25 if kind == "hand" else 1.0)
            if kind == "landing":  # the table: -g and the rolling; a spike at each bounce
                extra = smooth_noise(rng, int(sel.sum()), dt, rng.uniform(0.3, 1.0), 3.0)[:, None] * _unit(rng)
                jump = np.r_[0.0, np.linalg.norm(np.diff(w_body[sel], axis=0), axis=1)]
                for kb in np.flatnonzero(jump > 5.0 * np.median(jump) + 1.0):
                    jolt += (rng.uniform(0.2, 0.5) * peak * _bump((tau - tau[kb] + dt) / (2 * dt)))[:, None] * \
                        _unit_up(rng)
            F[sel] = held + jolt + extra
    return F


def _unit_up(rng: np.random.Generator) -> np.ndarray:
    """A direction within about 45 deg of up (a push, a catch, a bounce)."""
    d = _UP + 0.6 * rng.normal(size=3)
    return d / np.linalg.norm(d)


def synthetic_accel(rng: np.random.Generator, tt: np.ndarray, w_body: np.ndarray, wdot_body: np.ndarray,
                    segments: Sequence[tuple[str, float, float, np.ndarray | float | None]],
                    sensor: np.ndarray, body: TossBody = PHONE) -> SyntheticAccel:
    """The accelerometer of a synthetic recording (module docstring).

    Parameters
    ----------
    rng : numpy Generator
        The accelerometer's own random stream.
    tt : ndarray, shape (n,)
        Sample times, s.
    w_body : ndarray, shape (n, 3)
        True angular velocity, principal axes, rad/s.
    wdot_body : ndarray, shape (n, 3)
        Its derivative where known exactly, rad/s^2; NaN elsewhere (a central difference there).
    segments : list of (kind, t0, length, w0)
        The recording's timeline (``"hold"``, ``"throw"``, ``"flight"``, ``"catch"``,
        ``"hand"``, ``"landing"``, ``"turn"``, ``"table"``).
    sensor : ndarray, shape (3, 3)
        Sensor axes to principal axes (``omega_sensor = omega_principal @ sensor``).
    body : TossBody
        The body whose plate the air drags on (:func:`~tumble.analysis.fit.tossbody.plate_drag_force`;
        a drag coefficient of 0: no air) and on which the sensor sits; default the phone.

    Returns
    -------
    SyntheticAccel

    Examples
    --------
    A phone lying still reads ``g`` upward, whatever its attitude:

    >>> import numpy as np
    >>> from tumble.analysis.fit.accelsynth import synthetic_accel
    >>> t = np.arange(0.0, 1.0, 0.01)
    >>> acc = synthetic_accel(np.random.default_rng(0), t, np.zeros((100, 3)), np.zeros((100, 3)), [], np.eye(3))
    >>> bool(abs(np.median(np.linalg.norm(acc.f, axis=1)) - 9.81) < 0.5)
    True
    """
    dt = float(np.median(np.diff(tt)))
    wdot = np.where(np.isnan(wdot_body), np.gradient(w_body, tt, axis=0), wdot_body)
    r = rng.uniform(-1.0, 1.0, 3) * [0.4 * body.length, 0.4 * body.width, 0.004]
    attitude = _attitude(rng, tt, w_body)
    F = _contact(rng, tt, w_body, segments, dt, body, attitude)
    f_body = attitude.inv().apply(F) + rigid_acceleration(w_body, wdot, r)
    f = f_body @ sensor * (1.0 + rng.normal(0, 0.005, 3))
    bias = rng.normal(0, rng.uniform(0.05, 0.2), 3)
    noise = rng.uniform(0.01, 0.04)
    f = f + bias + rng.normal(0, noise, f.shape)
    lsb = ACCEL_FULL_SCALE / 32768
    f = np.clip(np.round(f / lsb) * lsb, -ACCEL_FULL_SCALE, ACCEL_FULL_SCALE)
    return SyntheticAccel(f, r @ sensor, bias, noise)


def phyphox_accel_csv(t: np.ndarray, f: np.ndarray) -> str:
    """phyphox's raw accelerometer export ("Accelerometer.csv" of an export with several sensors;
    experiment "Acceleration (with g)"), comma-separated.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.accelsynth import phyphox_accel_csv
    >>> phyphox_accel_csv(np.array([0.0, 0.01]), np.array([[0.0, 0.0, 9.81], [0.1, 0.0, 9.8]])).splitlines()[0]
    '"Time (s)","Acceleration x (m/s^2)","Acceleration y (m/s^2)","Acceleration z (m/s^2)","Absolute acceleration (m/s^2)"'
    """
    lines = ['"Time (s)","Acceleration x (m/s^2)","Acceleration y (m/s^2)","Acceleration z (m/s^2)",'
             '"Absolute acceleration (m/s^2)"']
    for ti, (x, y, z), a in zip(t, f, np.linalg.norm(f, axis=1)):
        lines.append(f"{ti:.9E},{x:.9E},{y:.9E},{z:.9E},{a:.9E}")
    return "\n".join(lines) + "\n"
