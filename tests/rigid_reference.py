"""The tests' independent reference for a rigid body's motion: Euler's equations and the
quaternion kinematics written out here, not tumble's, integrated by scipy's DOP853 at rtol 1e-13."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation


def reference_run(I, w0, q0, t, torque: Callable[[float, np.ndarray, np.ndarray], np.ndarray] | None = None):
    """omega (n, 3) and the unit quaternion (n, 4) at the times ``t`` (from ``t[0]``) of a body of
    principal moments ``I`` (kg m^2) from ``w0`` (rad/s) and ``q0`` (body to world, scalar last):
    ``I w' = tau + (I w) x w`` and ``q' = q (x) (w, 0) / 2`` (Hamilton, scalar last), with
    ``tau = torque(t, w, R)`` (N m, principal frame; ``R`` the rotation matrix, body to world, of
    the quaternion normalised)."""
    I = np.asarray(I, float)

    def rhs(time, y):
        w, (x, yq, z, s) = y[:3], y[3:]
        dq = 0.5 * np.array([s * w[0] + yq * w[2] - z * w[1], s * w[1] + z * w[0] - x * w[2],
                             s * w[2] + x * w[1] - yq * w[0], -(x * w[0] + yq * w[1] + z * w[2])])
        tau = 0.0 if torque is None else torque(time, w, _matrix(y[3:] / np.linalg.norm(y[3:])))
        return np.concatenate([(tau + np.cross(I * w, w)) / I, dq])

    sol = solve_ivp(rhs, (t[0], t[-1]), np.concatenate([w0, q0]), method="DOP853", t_eval=t, rtol=1e-13, atol=1e-16)
    assert sol.success, sol.message
    return sol.y[:3].T, sol.y[3:].T / np.linalg.norm(sol.y[3:], axis=0)[:, None]


def _matrix(q: np.ndarray) -> np.ndarray:
    """The rotation matrix of a unit quaternion ``(x, y, z, s)`` (scalar last), written out."""
    x, y, z, s = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * s), 2 * (x * z + y * s)],
                     [2 * (x * y + z * s), 1 - 2 * (x * x + z * z), 2 * (y * z - x * s)],
                     [2 * (x * z - y * s), 2 * (y * z + x * s), 1 - 2 * (x * x + y * y)]])


def errors(run, omega: np.ndarray, quat: np.ndarray) -> tuple[float, float]:
    """A run's omega error relative to the reference's largest |omega|, and the largest angle (rad)
    between its attitude and the reference's."""
    angle = (run.attitude * Rotation.from_quat(quat).inv()).magnitude().max()
    return float(np.abs(run.omega - omega).max() / np.abs(omega).max()), float(angle)
