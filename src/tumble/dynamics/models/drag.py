"""Euler's equations with an aerodynamic drag torque about each principal axis, compiled.

The body's angular velocity in its principal frame obeys (Landau & Lifshitz, *Mechanics*,
sec. 36, with a torque)::

    I_i w_i' = (I_j - I_k) w_j w_k - (a_i + b_i |w_i|) w_i            (i, j, k) cyclic

with a **linear** drag ``a_i`` (N m s: viscous, skin friction at low Reynolds number; a sphere
in a viscous fluid feels ``8 pi mu R^3 w``, Lamb, *Hydrodynamics*, 6th ed., sec. 334) and a
**quadratic** drag ``b_i`` (N m s^2: pressure drag at high Reynolds number; strip theory gives
``b = rho C_D W L^4 / 64`` for a plate ``L x W`` turning about its width's axis, each strip at
radius ``r`` feeling ``0.5 rho C_D W (w r)^2``: Hoerner, *Fluid-Dynamic Drag*, 1965, ch. 3, and
e.g. Knight, *Physics for Scientists and Engineers*, ch. 12). Each axis's torque opposes its
own component: the usual per-axis approximation of a tumbling body's aerodynamic damping
(:func:`~tumble.dynamics.models.aero.drag_component`, the law written once, re-exported here).

:func:`drag_omega` integrates it for many bodies at once with the classical fourth-order
Runge-Kutta method (Hairer, Norsett & Wanner, *Solving ODEs I*, sec. II.1) in a numba kernel
(:func:`tumble.dynamics.models.fit_kernels.drag_integrate`, compiled when first imported),
each body on its own times, forward for ``t >= 0`` and backward for ``t < 0``, with a fixed
number of equal steps between consecutive times that depends only on the times and the
given step bound: so the result is a smooth function of the moments, ``omega0`` and the drag
(finite differences of it are clean, as a least-squares fit needs). Why the engine's fixed-step
RK4 and not an adaptive solver: scipy's ``solve_ivp`` runs one body at a time in Python (about 1
ms a flight for the few hundred steps needed) and chooses its steps by the parameters, and a fit
evaluates some ten bodies per Jacobian hundreds of times; the compiled loop does the same in
microseconds. It agrees with DOP853 to the RK4
error ``~(|w| h)^4`` (tests/test_exact_omega.py).
"""

from __future__ import annotations

import numpy as np

from ...jit import kernel_array
from ...typing import ArrayLike, Vector3
from .aero import drag_component

__all__ = ["drag_component", "drag_omega", "drag_torque"]


def drag_omega(
    moments: ArrayLike, omega0: ArrayLike, t: ArrayLike, linear: ArrayLike | None = None,
    quadratic: ArrayLike | None = None, *, max_step: ArrayLike | None = None,
) -> Vector3:
    """Angular velocity of N bodies under per-axis drag (module docstring), principal frame.

    Parameters
    ----------
    moments : array_like, shape (N, 3)
        Principal moments, positive, kg m^2 (or any common unit, with the drag in the same).
    omega0 : array_like, shape (N, 3)
        Angular velocity at t = 0, principal frame, rad/s.
    t : array_like, shape (T,) or (N, T)
        Times, s, each row ascending (negative times are integrated backward from 0).
    linear, quadratic : array_like, shape (N, 3), optional
        ``a_i`` (N m s) and ``b_i`` (N m s^2) per principal axis (default 0).
    max_step : array_like, shape (N,), optional
        Largest step per body, s; default ``0.04 / |omega0|`` (an RK4 error of ~1e-7 of |omega|
        per radian turned).

    Returns
    -------
    ndarray, shape (N, T, 3)
        rad/s.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.drag import drag_omega
    >>> w = drag_omega([[1.0, 2.0, 3.0]], [[0.0, 0.0, 2.0]], [0.0, 1.0], quadratic=[[0.0, 0.0, 1.5]])
    >>> bool(np.isclose(w[0, 1, 2], 2.0 / (1.0 + 1.5 * 2.0 / 3.0)))  # w' = -(b/I) w^2
    True
    """
    I = kernel_array(np.atleast_2d(np.asarray(moments, float)))  # kernel_array: the one array type compiled
    w = kernel_array(np.atleast_2d(np.asarray(omega0, float)))
    N = len(I)
    times = np.asarray(t, float)
    tau = kernel_array(times, (N, times.shape[-1]))
    lin = np.zeros((N, 3)) if linear is None else kernel_array(linear, (N, 3))
    quad = np.zeros((N, 3)) if quadratic is None else kernel_array(quadratic, (N, 3))
    if max_step is None:
        speed = np.linalg.norm(w, axis=1)
        hmax = 0.04 / np.where(speed > 0, speed, 1.0)
    else:
        hmax = kernel_array(max_step, (N,))
    from .fit_kernels import drag_integrate  # compiled at import: numba only when a fit needs it

    return drag_integrate(I, w, lin, quad, tau, hmax)


def drag_torque(omega: ArrayLike, linear: ArrayLike | None = None, quadratic: ArrayLike | None = None) -> Vector3:
    """The drag torque of the module docstring, ``-(a_i + b_i |w_i|) w_i`` per principal axis, N m
    (``omega`` principal frame, rad/s, shape (..., 3); ``linear`` ``a_i`` in N m s, ``quadratic``
    ``b_i`` in N m s^2, default 0): the torque :func:`drag_omega` integrates, as a function for
    :func:`tumble.simulate`'s ``torque`` (which then also turns the attitude).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.drag import drag_omega, drag_torque
    >>> drag_torque([2.0, -1.0, 0.5], linear=[0.1, 0.1, 0.1], quadratic=[1.0, 0.0, 2.0]).tolist()
    [-4.2, 0.1, -0.55]
    >>> I, w0, b = np.array([1.0, 2.0, 3.0]), np.array([0.3, 2.0, 0.4]), np.array([0.2, 0.1, 0.3])
    >>> h = 1e-4   # the same law as drag_omega's: its rate at t = 0 is (Euler's term + the torque) / I
    >>> w = drag_omega([I], [w0], [-h, 0.0, h], quadratic=[b])[0]
    >>> rate = (w[2] - w[0]) / (2 * h)
    >>> euler = np.array([(I[1] - I[2]) * w0[1] * w0[2], (I[2] - I[0]) * w0[2] * w0[0], (I[0] - I[1]) * w0[0] * w0[1]])
    >>> bool(np.allclose(rate, (euler + drag_torque(w0, quadratic=b)) / I, atol=1e-7))
    True
    """
    w = np.asarray(omega, float)
    a = 0.0 if linear is None else np.asarray(linear, float)
    b = 0.0 if quadratic is None else np.asarray(quadratic, float)
    return np.asarray(drag_component(a, b, w), float)
