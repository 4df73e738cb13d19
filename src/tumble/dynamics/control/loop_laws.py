"""The control laws of the compiled closed loop and what a command holds: the laws' command from a
measurement (:func:`law_command`; :mod:`~tumble.dynamics.control.laws`' functions, the ones the
Python controllers call) and the rods' dipole and the wheels' torques it holds (:func:`held`).
The ideal sensors' loop (:mod:`~tumble.dynamics.control.compiled_loop`) and the estimator's
(:mod:`~tumble.dynamics.control.estimated_loop`) call them; compiled by :func:`tumble.jit.jit`.
"""

from __future__ import annotations

from typing import Any

from ...jit import jit
from ...typing import FloatArray
from ..special.quaternion import to_body
from .laws import (attitude_error_components, bdot_components, dumping_dipole_components, feedback_torque_components,
                   gyro_field_rate_components, tracking_feedforward_components)
from .loop_terms import BODY, WHEEL, _wheel_torque, rod_dipole

__all__ = ["LAW_BDOT", "LAW_DUMPING", "LAW_MRP", "NO_MEMORY", "Law", "held", "law_command"]

#: The compiled laws: B-dot (``L = (gain, normalized, difference)``), MRP feedback to a fixed
#: target (``L = (K, P, Ki, integral_limit, gyroscopic, period, target quaternion (4))``), and
#: MRP feedback with momentum dumping (the same, then ``(k_d, h_target (3))``).
LAW_BDOT, LAW_MRP, LAW_DUMPING = 0, 1, 2

_attitude_error = jit(attitude_error_components, error_model="numpy")
_bdot = jit(bdot_components, error_model="numpy")
_gyro_rate = jit(gyro_field_rate_components, error_model="numpy")
_dumping = jit(dumping_dipole_components, error_model="numpy")
_feedback = jit(feedback_torque_components, error_model="numpy")
_feedforward = jit(tracking_feedforward_components, error_model="numpy")

#: The laws' memory at the start: MRP feedback's integral term (N m, 3), B-dot's last reading
#: (T, 3), its time (s) and whether there is one.
NO_MEMORY = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, False)
#: A law of the loop: ``(law, parameters, allocation, reference)``
#: (:func:`~tumble.dynamics.control.control_kernel.compiled_law`); ``law`` None: none (a free run).
Law = tuple[int | None, FloatArray, FloatArray, Any]


@jit(error_model="numpy")
def law_command(law: int, L: FloatArray, pinv: FloatArray, P0: Any, y: Any, t: float, x: float, yq: float, z: float,
                c: float, w0: float, w1: float, w2: float, b0: float, b1: float, b2: float, has_field: bool, memory: Any,
                u: FloatArray, REF: FloatArray, i: int) -> Any:  # pragma: no cover - compiled
    """The law's command at ``t`` (s) from a measurement: the attitude ``(x, yq, z, c)`` (unit
    quaternion, body to world), the rate ``w`` (rad/s), the field ``b`` (T, body frame; used when
    ``has_field``) and the wheels' spins ``y[7:]`` (rad/s, exact): ``(m0, m1, m2, memory)`` the
    dipole asked for (A m^2) and the laws' memory (:data:`NO_MEMORY`), the wheels' torques
    (N m) into ``u``. ``L`` the law's parameters, ``pinv`` the wheels' allocation (:func:`~tumble.dynamics.control.compiled_loop._loop`);
    ``REF[i]`` the moving reference at this instant
    (:func:`~tumble.dynamics.control.pointing.reference_table`; no rows for a fixed target).
    The ideal sensors' loop (:func:`~tumble.dynamics.control.compiled_loop._loop`) and the estimator's
    (:mod:`~tumble.dynamics.control.estimated_loop`) call it."""
    k = pinv.shape[0]
    z0, z1, z2, last0, last1, last2, last_t, has_last = memory
    m0, m1, m2 = 0.0, 0.0, 0.0
    for j in range(k):
        u[j] = 0.0
    if law == LAW_BDOT and has_field:
        d0, d1, d2 = 0.0, 0.0, 0.0
        if L[2] == 0.0:
            d0, d1, d2 = _gyro_rate(b0, b1, b2, w0, w1, w2)
            m0, m1, m2 = _bdot(d0, d1, d2, b0, b1, b2, L[0], L[1] != 0.0)
        else:
            if has_last:
                d0, d1, d2 = (b0 - last0) / (t - last_t), (b1 - last1) / (t - last_t), (b2 - last2) / (t - last_t)
            m0, m1, m2 = _bdot(d0, d1, d2, b0, b1, b2, L[0], L[1] != 0.0)
            last0, last1, last2, last_t, has_last = b0, b1, b2, t, True
    elif law != LAW_BDOT:
        s0, s1, s2 = _attitude_error(L[6], L[7], L[8], L[9], x, yq, z, c)
        r0, r1, r2, a0, a1, a2 = 0.0, 0.0, 0.0, 0.0, 0.0, 0.0  # the reference's rate and its derivative, body
        if REF.shape[0] > 0:
            s0, s1, s2 = _attitude_error(REF[i, 0], REF[i, 1], REF[i, 2], REF[i, 3], x, yq, z, c)
            r0, r1, r2 = to_body(x, yq, z, c, REF[i, 4], REF[i, 5], REF[i, 6])
            a0, a1, a2 = to_body(x, yq, z, c, REF[i, 7], REF[i, 8], REF[i, 9])
        h0, h1, h2 = 0.0, 0.0, 0.0
        for j in range(k):
            js = P0[BODY + WHEEL * j + 3] * y[7 + j]
            h0, h1, h2 = (h0 + js * P0[BODY + WHEEL * j], h1 + js * P0[BODY + WHEEL * j + 1],
                          h2 + js * P0[BODY + WHEEL * j + 2])
        e0, e1, e2 = 0.0, 0.0, 0.0
        if L[4] != 0.0:
            e0, e1, e2 = P0[0] * w0 + h0, P0[1] * w1 + h1, P0[2] * w2 + h2
        f0, f1, f2 = _feedback(s0, s1, s2, w0 - r0, w1 - r1, w2 - r2, w0, w1, w2, L[0], L[1], z0, z1, z2, e0, e1, e2)
        if REF.shape[0] > 0:
            g0, g1, g2 = _feedforward(L[14:23].reshape((3, 3)), r0, r1, r2, a0, a1, a2, w0, w1, w2)
            f0, f1, f2 = f0 + g0, f1 + g1, f2 + g2
        if L[2] > 0.0:
            g = L[2] * L[0] * L[5]
            z0 = min(max(z0 + g * s0, -L[3]), L[3])
            z1 = min(max(z1 + g * s1, -L[3]), L[3])
            z2 = min(max(z2 + g * s2, -L[3]), L[3])
        for j in range(k):
            u[j] = -(pinv[j, 0] * f0 + pinv[j, 1] * f1 + pinv[j, 2] * f2)
        if law == LAW_DUMPING:
            m0, m1, m2 = _dumping(b0, b1, b2, h0, h1, h2, L[10], L[11], L[12], L[13])
    return m0, m1, m2, (z0, z1, z2, last0, last1, last2, last_t, has_last)


@jit(error_model="numpy")
def held(rods: FloatArray, limits: FloatArray, m0: float, m1: float, m2: float, u: FloatArray, y: Any, P0: Any,
         D: FloatArray, U: FloatArray) -> tuple[float, float, float]:  # pragma: no cover - compiled
    """What a command holds: the rods' dipole (A m^2), the dipole ``m`` asked for allocated to the rods
    (``rods``: :attr:`~tumble.dynamics.models.actuators.Magnetorquers.rods`) and clipped to each one's limit, into ``D`` (3,) and returned; the wheels'
    applied torques (N m) of the commands ``u`` at the spins ``y[7:]`` into ``U`` (limits and
    friction, :func:`~tumble.dynamics.models.actuators.wheel_torque`)."""
    d0, d1, d2 = rod_dipole(rods, limits, m0, m1, m2)
    D[0], D[1], D[2] = d0, d1, d2
    for j in range(U.shape[0]):
        b = BODY + WHEEL * j
        U[j] = _wheel_torque(u[j], y[7 + j], P0[b + 4], P0[b + 5], P0[b + 6], P0[b + 7], P0[b + 8])
    return d0, d1, d2
