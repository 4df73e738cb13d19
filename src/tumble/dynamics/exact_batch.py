"""The exact torque-free motion of N rigid bodies at common times.

The mathematics is that of :mod:`tumble.dynamics.exact` (Landau & Lifshitz, *Mechanics*,
sec. 37): omega from Jacobi's elliptic functions, the attitude from the precession angle about
L given by the incomplete elliptic integral of the third kind.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from .exact import FreeRotation, check_phase_limit

__all__ = ["free_rotation_batch"]


def free_rotation_batch(moments, omega0, quat0, t) -> tuple[np.ndarray, np.ndarray]:
    """Omega and attitude of N free rigid bodies at times ``t``.

    Parameters
    ----------
    moments : ndarray, shape (N, 3)
        Principal moments, ascending, positive, kg m^2.
    omega0 : ndarray, shape (N, 3)
        Angular velocity at t = 0, principal frame, rad/s.
    quat0 : ndarray, shape (N, 4)
        Unit quaternions, principal frame to world at t = 0, scalar last.
    t : ndarray, shape (T,)
        Times, s.

    Returns
    -------
    omega : ndarray, shape (N, T, 3)
    quat : ndarray, shape (N, T, 4)

    Raises
    ------
    ValueError
        If a body's phase would exceed :data:`tumble.dynamics.exact.MAX_PHASE` (naming the body).
    """
    t = np.asarray(t, float)
    t_end = float(np.max(np.abs(t)))
    omega, quat = np.empty((len(moments), len(t), 3)), np.empty((len(moments), len(t), 4))
    for i in range(len(moments)):
        try:
            check_phase_limit(moments[i], omega0[i], t_end)
        except ValueError as err:
            raise ValueError(f"omega0[{i}]: {err}") from None
        motion = FreeRotation(moments[i], omega0[i], Rotation.from_quat(quat0[i]))
        omega[i], quat[i] = motion.omega(t), motion.attitude(t).as_quat()
    return omega, quat
