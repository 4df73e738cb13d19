"""The orbit's local frame along any orbit: nadir, the orbit normal, and how fast the frame turns.

For a body at ``r`` (m) moving at ``v`` (m/s) about the Earth, in an inertial world frame, the
*nadir frame* has its axes

``e1 = -r / |r|`` (nadir), ``e2 = h / |h|`` (the orbit normal, ``h = r x v``), ``e3 = e1 x e2``

(``e3`` is the velocity's direction on a circle, the along-track axis in general); it is the
local-vertical local-horizontal (LVLH, or Hill) frame of Schaub & Junkins, *Analytical Mechanics of
Space Systems*, 4th ed., 2018 (the Hill frame, ``o_r = r / |r|``, ``o_h = h / |h|``), with the radial
axis turned to nadir.

**Its angular velocity** (world frame, rad/s) is

``omega = h / |r|^2 + ((a . h) / |h|^2) r``

with ``a`` the body's acceleration (m/s^2). Derived here: the radial axis turns about ``h`` at
``d(r/|r|)/dt . (h x r / |h x r|) = |h| / |r|^2`` (in the two-body problem the true anomaly's
rate, ``f' = h / r^2``, the Hill frame's rate in Schaub & Junkins); the normal turns as
``dh/dt = r x a``, about the radius at ``(r x a) . (r x h) / (|h|^2 |r|) = |r| (a . h) / |h|^2``,
so a frame whose normal is fixed (two-body motion, ``a`` along ``r``) turns about ``h`` alone.

:func:`orbit_acceleration` is the orbit's own ``acceleration_world(t)`` where it has one, else the
central difference of its ``velocity_world`` (an SGP4 orbit gives no acceleration); the frame's
angular acceleration (:func:`orbit_frame_acceleration`) is the central difference of its rate. Both
differences take steps of ``1e-4 / n`` (n the mean motion): a truncation error of order ``(n dt)^2
~ 1e-8`` of the quantity, round-off ~1e-11 (tested against the two-body closed forms).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...typing import ArrayLike, FloatArray

__all__ = ["DIFFERENCE_STEP", "nadir_frame", "nadir_frame_rate", "orbit_acceleration", "orbit_frame_acceleration",
           "orbit_frame_rate"]

#: The central differences' step, in units of ``1 / n`` (n the orbit's mean motion, rad/s).
DIFFERENCE_STEP = 1e-4


def nadir_frame(position: ArrayLike, velocity: ArrayLike) -> FloatArray:
    """The nadir frame's axes as the columns of a matrix (world frame): nadir ``-r/|r|``, the orbit
    normal ``h/|h|`` and their cross product (module docstring); shape ``position.shape + (3,)``.

    Parameters
    ----------
    position, velocity : array_like, shape (..., 3)
        ``r`` (m) and ``v`` (m/s) in an inertial frame.

    Examples
    --------
    On a circle in the x-y plane, a quarter turn on: nadir is -y, the normal +z, the third axis -x
    (the velocity):

    >>> from tumble.dynamics.environment.local_frame import nadir_frame
    >>> (nadir_frame([0.0, 7e6, 0.0], [-7.5e3, 0.0, 0.0]).T + 0.0).tolist()   # the axes as rows
    [[0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]]
    """
    r, v = np.asarray(position, float), np.asarray(velocity, float)
    h = np.cross(r, v)
    nadir = -r / np.linalg.norm(r, axis=-1, keepdims=True)
    normal = h / np.linalg.norm(h, axis=-1, keepdims=True)
    return np.stack([nadir, normal, np.cross(nadir, normal)], axis=-1)


def nadir_frame_rate(position: ArrayLike, velocity: ArrayLike, acceleration: ArrayLike) -> FloatArray:
    """The nadir frame's angular velocity (world frame, rad/s; shape ``position.shape``).

    ``omega = h / |r|^2 + ((a . h) / |h|^2) r`` (module docstring).

    Parameters
    ----------
    position, velocity, acceleration : array_like, shape (..., 3)
        ``r`` (m), ``v`` (m/s) and ``a`` (m/s^2) in an inertial frame.

    Examples
    --------
    At the perigee of an ellipse the frame turns at the true anomaly's rate ``v_p / r_p`` about the
    normal; a push along the normal (``a . h > 0``) adds a turn about the radius:

    >>> from tumble.dynamics.environment.local_frame import nadir_frame_rate
    >>> r, v = [7e6, 0.0, 0.0], [0.0, 8e3, 0.0]
    >>> nadir_frame_rate(r, v, [-8.1, 0.0, 0.0]).tolist() == [0.0, 0.0, 8e3 / 7e6]
    True
    >>> [round(x, 12) for x in nadir_frame_rate(r, v, [-8.1, 0.0, 0.01]).tolist()]   # (a.h) r / |h|^2: 0.01 / 8e3
    [1.25e-06, 0.0, 0.001142857143]
    """
    r, v, a = (np.asarray(x, float) for x in (position, velocity, acceleration))
    h = np.cross(r, v)
    h2 = np.sum(h * h, axis=-1, keepdims=True)
    return np.asarray(h / np.sum(r * r, axis=-1, keepdims=True) + np.sum(a * h, axis=-1, keepdims=True) / h2 * r,
                      dtype=np.float64)


def _step(orbit: Any) -> float:
    """The central differences' step for ``orbit``, s (:data:`DIFFERENCE_STEP` over its mean motion)."""
    return DIFFERENCE_STEP / float(orbit.mean_motion)


def orbit_acceleration(orbit: Any, t: ArrayLike) -> FloatArray:
    """The orbit's acceleration at ``t`` (s), world frame, m/s^2: its own ``acceleration_world(t)``,
    else the central difference of ``velocity_world`` (module docstring); shape ``t.shape + (3,)``.

    Examples
    --------
    A Keplerian orbit's is ``-mu r / |r|^3`` (its own), and the difference of its velocity agrees to
    the difference's truncation error, ~1e-8:

    >>> import numpy as np
    >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
    >>> from tumble.dynamics.environment.local_frame import orbit_acceleration
    >>> orbit = KeplerOrbit(8000e3, 0.1, 0.9)
    >>> class Velocities:   # the same orbit giving only its position and velocity
    ...     mean_motion, velocity_world = orbit.mean_motion, orbit.velocity_world
    >>> a = orbit_acceleration(orbit, [0.0, 1500.0])
    >>> bool(np.allclose(orbit_acceleration(Velocities(), [0.0, 1500.0]), a, rtol=1e-7, atol=0))
    True
    """
    own = getattr(orbit, "acceleration_world", None)
    if callable(own):
        return np.asarray(own(t), dtype=np.float64)
    t = np.asarray(t, float)
    dt = _step(orbit)
    return np.asarray((np.asarray(orbit.velocity_world(t + dt)) - np.asarray(orbit.velocity_world(t - dt))) / (2 * dt),
                      dtype=np.float64)


def orbit_frame_rate(orbit: Any, t: ArrayLike) -> FloatArray:
    """The nadir frame's angular velocity along ``orbit`` at ``t`` (s), world frame, rad/s
    (:func:`nadir_frame_rate` of its position, velocity and :func:`orbit_acceleration`); shape
    ``t.shape + (3,)``.

    Parameters
    ----------
    orbit : object
        With ``position_world(t)`` (m), ``velocity_world(t)`` (m/s) and ``mean_motion`` (rad/s),
        vectorised over ``t``, in an inertial world frame: a
        :class:`~tumble.dynamics.environment.ephemeris.KeplerOrbit`,
        :class:`~tumble.dynamics.environment.ephemeris.TLEOrbit` or
        :class:`~tumble.dynamics.environment.orbit.CircularOrbit`.
    t : array_like
        Times, s.

    Examples
    --------
    On an ellipse the frame turns at ``f' = n (1 + e cos f)^2 / (1 - e^2)^(3/2)`` about the normal,
    fastest at the perigee (f = 0):

    >>> import math
    >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
    >>> from tumble.dynamics.environment.local_frame import orbit_frame_rate
    >>> orbit = KeplerOrbit(8000e3, 0.1)
    >>> math.isclose(orbit_frame_rate(orbit, 0.0)[2], orbit.mean_motion * 1.1**2 / 0.99**1.5, rel_tol=1e-12)
    True
    """
    return nadir_frame_rate(orbit.position_world(t), orbit.velocity_world(t), orbit_acceleration(orbit, t))


def orbit_frame_acceleration(orbit: Any, t: ArrayLike) -> FloatArray:
    """The nadir frame's angular acceleration along ``orbit`` at ``t`` (s), world frame, rad/s^2: the
    central difference of :func:`orbit_frame_rate` (module docstring); shape ``t.shape + (3,)``.

    Examples
    --------
    At the perigee the rate is at its peak (no acceleration); a quarter of a period on it falls:

    >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
    >>> from tumble.dynamics.environment.local_frame import orbit_frame_acceleration
    >>> orbit = KeplerOrbit(8000e3, 0.1)
    >>> bool(abs(orbit_frame_acceleration(orbit, 0.0)[2]) < 1e-9 * orbit.mean_motion**2)
    True
    >>> bool(orbit_frame_acceleration(orbit, orbit.period / 4)[2] < 0.0)
    True
    """
    t = np.asarray(t, float)
    dt = _step(orbit)
    return np.asarray((orbit_frame_rate(orbit, t + dt) - orbit_frame_rate(orbit, t - dt)) / (2 * dt), dtype=np.float64)
