"""The control laws of :mod:`~tumble.dynamics.control.controllers` over plain floats: written once.

Each law is a function of scalar components (arithmetic only), which the Python controllers
call (:class:`~tumble.dynamics.control.bdot.BDot`,
:class:`~tumble.dynamics.control.controllers.MRPFeedback`,
:class:`~tumble.dynamics.control.controllers.MomentumDumping`; some on arrays of one shape) and
the compiled closed loop compiles (:mod:`~tumble.dynamics.control.compiled_loop`), so that the
two paths evaluate the same formula in the same order. Imports nothing of tumble.

- B-dot (Stickler & Alfriend, AIAA 74-923, 1974): ``m = -k dB/dt``, ``k`` the gain or, normalised
  (Avanzini & Giulietti, J. Guid. Control Dyn. 35(4), 2012), the gain over ``|B|^2``; ``dB/dt``
  from the gyroscope, ``B x omega`` (:func:`gyro_field_rate_components`), or from two readings.
- MRP feedback (Schaub & Junkins, *Analytical Mechanics of Space Systems*, 4th ed., sec.
  8.3-8.4): the error ``sigma`` of the body relative to a fixed target
  (:func:`attitude_error_components`) and the required torque
  ``L_r = -K sigma - P delta_omega - z + omega x L`` with ``L = I omega + h`` the total momentum
  (:func:`feedback_torque_components`; ``z`` the integral term, ``L`` omitted without the
  feed-forward); tracking a moving reference, ``delta_omega = omega - omega_r`` and the
  feed-forward ``I_RW (omega_r' - omega x omega_r)`` added (sec. 8.3;
  :func:`tracking_feedforward_components`).
- Momentum dumping (Camillo & Markley, J. Guid. Control 3(6), 1980): ``m = B x tau_d / |B|^2``
  with ``tau_d = -k_d (h - h_target)`` (:func:`dumping_dipole_components`).

Units: SI throughout (T, rad/s, N m, A m^2, kg m^2/s).

Examples
--------
>>> from tumble.dynamics.control.laws import bdot_components, gyro_field_rate_components
>>> b, omega = (2e-5, 0.0, 0.0), (0.0, 0.0, 0.1)
>>> [round(m, 12) + 0.0 for m in bdot_components(*gyro_field_rate_components(*b, *omega), *b, 1e4, False)]   # A m^2
[0.0, 0.02, 0.0]
"""

from __future__ import annotations

from typing import Any

__all__ = ["attitude_error_components", "bdot_components", "gyro_field_rate_components", "dumping_dipole_components",
           "feedback_torque_components", "tracking_feedforward_components"]


def bdot_components(d0: Any, d1: Any, d2: Any, b0: Any, b1: Any, b2: Any, gain: Any,
                    normalized: bool) -> tuple[Any, Any, Any]:
    """The B-dot dipole ``m = -k dB/dt`` (A m^2) from ``dB/dt = (d0, d1, d2)`` (T/s) and the field
    ``B = (b0, b1, b2)`` (T, body frame): ``k = gain`` (A m^2 s/T), or ``gain / |B|^2`` (gain in
    N m s) when ``normalized``.

    Examples
    --------
    >>> from tumble.dynamics.control.laws import bdot_components
    >>> [m + 0.0 for m in bdot_components(0.0, 0.0, -2e-6, 2e-5, 0.0, 0.0, 1e4, False)]
    [0.0, 0.0, 0.02]
    >>> [round(m, 9) + 0.0 for m in bdot_components(0.0, 0.0, -2e-6, 2e-5, 0.0, 0.0, 1e-4, True)]   # (1e-4 / 4e-10) 2e-6
    [0.0, 0.0, 0.5]
    """
    k = gain / (b0 * b0 + b1 * b1 + b2 * b2) if normalized else gain
    return -k * d0, -k * d1, -k * d2


def gyro_field_rate_components(b0: Any, b1: Any, b2: Any, w0: Any, w1: Any, w2: Any) -> tuple[Any, Any, Any]:
    """B-dot's ``dB/dt`` (T/s) from the gyroscope: ``B x omega``, the field ``B`` (T) fixed in the
    world seen from a body turning at ``omega`` (rad/s), the field's own motion neglected.

    Examples
    --------
    >>> from tumble.dynamics.control.laws import bdot_components, gyro_field_rate_components
    >>> rate = gyro_field_rate_components(0.0, 3e-5, 0.0, 0.1, 0.2, 0.0)
    >>> [round(m, 12) + 0.0 for m in bdot_components(*rate, 0.0, 3e-5, 0.0, 1e-4, True)]   # A m^2
    [0.0, 0.0, 0.333333333333]
    """
    return b1 * w2 - b2 * w1, b2 * w0 - b0 * w2, b0 * w1 - b1 * w0


def attitude_error_components(t0: float, t1: float, t2: float, t3: float, x: float, y: float, z: float,
                              s: float) -> tuple[float, float, float]:
    """The short-set MRPs ``sigma`` (``|sigma| <= 1``) of the body ``(x, y, z, s)`` relative to the
    target ``(t0, t1, t2, t3)``, both unit quaternions to the world, scalar last: the error
    quaternion ``t* (x) q`` (scipy's ``target.inv() * attitude``; Shuster, J. Astronaut. Sci. 41
    (1993) 439), then ``sigma = v / (1 + w)`` with ``w >= 0`` (Schaub & Junkins, sec. 3.7).

    Examples
    --------
    A turn of 60 degrees about x from the target: ``sigma = tan(15 deg) x``:

    >>> import math
    >>> from tumble.dynamics.control.laws import attitude_error_components
    >>> c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    >>> [round(v, 12) + 0.0 for v in attitude_error_components(0.0, 0.0, 0.0, 1.0, s, 0.0, 0.0, c)]
    [0.267949192431, 0.0, 0.0]
    """
    # (u, w)(v, r) = (w v + r u + u x v, w r - u . v) with u = -(t0, t1, t2), w = t3
    e0 = t3 * x - s * t0 - (t1 * z - t2 * y)
    e1 = t3 * y - s * t1 - (t2 * x - t0 * z)
    e2 = t3 * z - s * t2 - (t0 * y - t1 * x)
    e3 = t3 * s + (t0 * x + t1 * y + t2 * z)
    if e3 < 0.0:
        e0, e1, e2, e3 = -e0, -e1, -e2, -e3
    return e0 / (1.0 + e3), e1 / (1.0 + e3), e2 / (1.0 + e3)


def feedback_torque_components(s0: float, s1: float, s2: float, d0: float, d1: float, d2: float, w0: float, w1: float,
                               w2: float, K: float, P: float, z0: float, z1: float, z2: float, L0: float, L1: float,
                               L2: float) -> tuple[float, float, float]:
    """MRP feedback's required torque ``L_r = -K sigma - P delta_omega - z + omega x L`` (N m, body
    frame): ``sigma`` the error MRPs, ``delta_omega`` the rate error (``omega`` itself for a fixed
    target), ``omega`` (rad/s), the gains ``K`` (N m) and ``P`` (N m s), the integral term ``z``
    (N m) and ``L`` (kg m^2/s) the total momentum ``I omega + h`` for the gyroscopic feed-forward
    (zeros without it). The wheels make ``-L_r``.

    Examples
    --------
    On target, turning at 0.01 rad/s about x, no feed-forward: rate damping ``-P omega``:

    >>> from tumble.dynamics.control.laws import feedback_torque_components
    >>> w = (0.01, 0.0, 0.0)
    >>> [v + 0.0 for v in feedback_torque_components(0, 0, 0, *w, *w, 1e-3, 2e-2, 0, 0, 0, 0, 0, 0)]
    [-0.0002, 0.0, 0.0]
    """
    return (-K * s0 - P * d0 - z0 + (w1 * L2 - w2 * L1), -K * s1 - P * d1 - z1 + (w2 * L0 - w0 * L2),
            -K * s2 - P * d2 - z2 + (w0 * L1 - w1 * L0))


def tracking_feedforward_components(J: Any, r0: float, r1: float, r2: float, a0: float, a1: float, a2: float,
                                    w0: float, w1: float, w2: float) -> tuple[float, float, float]:
    """The tracking law's feed-forward ``I_RW (omega_r' - omega x omega_r)`` (N m, body frame),
    added to :func:`feedback_torque_components`'s ``L_r`` when the target moves (Schaub & Junkins,
    sec. 8.3): ``J`` the body's inertia with the wheels' axial inertia taken out, ``I_RW`` (kg m^2,
    indexed ``J[i, j]``), ``omega_r`` the reference's rate and ``omega_r'`` its inertial derivative
    (rad/s, rad/s^2, both in the body frame), ``omega`` the body's rate (rad/s).

    Examples
    --------
    A body at rest under a reference turning at 0.01 rad/s about z that speeds up at 1e-4 rad/s^2:
    ``I_RW omega_r'``:

    >>> import numpy as np
    >>> from tumble.dynamics.control.laws import tracking_feedforward_components
    >>> [round(float(v), 12) + 0.0 for v in tracking_feedforward_components(np.diag([1.0, 2.0, 3.0]), 0, 0, 0.01, 0, 0, 1e-4, 0, 0, 0)]
    [0.0, 0.0, 0.0003]
    """
    v0, v1, v2 = a0 - (w1 * r2 - w2 * r1), a1 - (w2 * r0 - w0 * r2), a2 - (w0 * r1 - w1 * r0)
    return (J[0, 0] * v0 + J[0, 1] * v1 + J[0, 2] * v2, J[1, 0] * v0 + J[1, 1] * v1 + J[1, 2] * v2,
            J[2, 0] * v0 + J[2, 1] * v1 + J[2, 2] * v2)


def dumping_dipole_components(b0: float, b1: float, b2: float, h0: float, h1: float, h2: float, gain: float,
                              r0: float, r1: float, r2: float) -> tuple[float, float, float]:
    """The dumping dipole ``m = B x tau_d / |B|^2`` (A m^2) with ``tau_d = -k_d (h - h_target)``:
    the field ``B`` (T, body frame), the wheels' momentum ``h`` and its target ``r``
    (kg m^2/s), the gain ``k_d`` (1/s). ``m x B`` is ``tau_d``'s part across ``B``.

    Examples
    --------
    >>> from tumble.dynamics.control.laws import dumping_dipole_components
    >>> [round(v, 9) + 0.0 for v in dumping_dipole_components(0.0, 0.0, 3e-5, 0.5, 0.0, 0.2, 1e-3, 0.0, 0.0, 0.0)]
    [0.0, -16.666666667, 0.0]
    """
    d0, d1, d2 = -gain * (h0 - r0), -gain * (h1 - r1), -gain * (h2 - r2)
    bb = b0 * b0 + b1 * b1 + b2 * b2
    return (b1 * d2 - b2 * d1) / bb, (b2 * d0 - b0 * d2) / bb, (b0 * d1 - b1 * d0) / bb
