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
own component: the usual per-axis approximation of a tumbling body's aerodynamic damping.

:func:`drag_omega` integrates it for many bodies at once with the classical fourth-order
Runge-Kutta method (Hairer, Norsett & Wanner, *Solving ODEs I*, sec. II.1) in a numba kernel,
each body on its own times, forward for ``t >= 0`` and backward for ``t < 0``, with a fixed
number of equal steps between consecutive times that depends only on the times and the
given step bound: so the result is a smooth function of the moments, ``omega0`` and the drag
(finite differences of it are clean, as a least-squares fit needs). Why a hand-written
integrator: scipy's ``solve_ivp`` runs one body at a time in Python (about 1 ms a flight for
the few hundred steps needed), and a fit evaluates some ten bodies per Jacobian hundreds of
times; the compiled loop does the same in microseconds. It agrees with DOP853 to the RK4
error ``~(|w| h)^4`` (tests/test_exact_omega.py).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any, cast

import numpy as np

from ...typing import ArrayLike, FloatArray, Vector3

__all__ = ["drag_component", "drag_omega", "drag_torque"]


def drag_component(linear: Any, quadratic: Any, w: Any) -> Any:
    """The drag torque about one axis, ``-(a + b |w|) w``, N m (module docstring): the law written
    once, over floats (or arrays, elementwise: a float in a kernel, an array in numpy), for the
    Python path and every compiled kernel.

    Examples
    --------
    >>> from tumble.dynamics.models.drag import drag_component
    >>> drag_component(0.1, 1.0, 2.0), drag_component(0.1, 1.0, -2.0)   # always against the rotation
    (-4.2, 4.2)
    """
    return -(linear + quadratic * abs(w)) * w


_drag = drag_component  # compiled by _compiled(), with the kernels that call it


def _rate(I: FloatArray, lin: FloatArray, quad: FloatArray, w: FloatArray, out: FloatArray) -> None:
    out[0] = ((I[1] - I[2]) * w[1] * w[2] + _drag(lin[0], quad[0], w[0])) / I[0]
    out[1] = ((I[2] - I[0]) * w[2] * w[0] + _drag(lin[1], quad[1], w[1])) / I[1]
    out[2] = ((I[0] - I[1]) * w[0] * w[1] + _drag(lin[2], quad[2], w[2])) / I[2]


def _advance(
    I: FloatArray, lin: FloatArray, quad: FloatArray, w: FloatArray, dt: float, n: int,
    k1: FloatArray, k2: FloatArray, k3: FloatArray, k4: FloatArray, tmp: FloatArray,
) -> None:
    h = dt / n
    for _ in range(n):
        _rate(I, lin, quad, w, k1)
        for c in range(3):
            tmp[c] = w[c] + 0.5 * h * k1[c]
        _rate(I, lin, quad, tmp, k2)
        for c in range(3):
            tmp[c] = w[c] + 0.5 * h * k2[c]
        _rate(I, lin, quad, tmp, k3)
        for c in range(3):
            tmp[c] = w[c] + h * k3[c]
        _rate(I, lin, quad, tmp, k4)
        for c in range(3):
            w[c] += h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c])


def _integrate(
    I: FloatArray, w0: FloatArray, lin: FloatArray, quad: FloatArray, tau: FloatArray, hmax: FloatArray
) -> FloatArray:
    K, T = tau.shape
    out = np.empty((K, T, 3))
    k1, k2, k3, k4, tmp = np.empty(3), np.empty(3), np.empty(3), np.empty(3), np.empty(3)
    w = np.empty(3)
    for b in range(K):
        j0 = 0
        while j0 < T and tau[b, j0] < 0.0:
            j0 += 1
        for side in range(2):
            for c in range(3):
                w[c] = w0[b, c]
            t = 0.0
            if side == 0:
                js = range(j0, T)
            else:
                js = range(j0 - 1, -1, -1)
            for j in js:
                dt = tau[b, j] - t
                if dt != 0.0:
                    n = max(1, int(np.ceil(abs(dt) / hmax[b] - 1e-9)))
                    _advance(I[b], lin[b], quad[b], w, dt, n, k1, k2, k3, k4, tmp)
                    t = tau[b, j]
                for c in range(3):
                    out[b, j, c] = w[c]
    return out


@functools.cache
def _compiled() -> Callable[..., FloatArray]:
    """The kernel compiled by numba (``cache=True``: once per machine), on first use: importing
    numba costs half a second, which every ``tumble`` command would pay at start otherwise.
    The module's functions are replaced by their compiled versions in calling order, so that
    each is compiled against the compiled ones it calls."""
    from ...jit import jit

    globals()["_drag"] = jit(inline="always")(drag_component)
    names = ("_rate", "_advance", "_integrate")
    for name in names:
        globals()[name] = jit()(globals()[name])
    return cast("Callable[..., FloatArray]", globals()["_integrate"])


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
    I = np.ascontiguousarray(np.atleast_2d(np.asarray(moments, float)))
    w = np.ascontiguousarray(np.atleast_2d(np.asarray(omega0, float)))
    N = len(I)
    times = np.asarray(t, float)
    tau = np.ascontiguousarray(np.broadcast_to(times, (N, times.shape[-1])))
    lin = np.zeros((N, 3)) if linear is None else np.ascontiguousarray(np.broadcast_to(np.asarray(linear, float), (N, 3)))
    quad = np.zeros((N, 3)) if quadratic is None else np.ascontiguousarray(
        np.broadcast_to(np.asarray(quadratic, float), (N, 3)))
    if max_step is None:
        speed = np.linalg.norm(w, axis=1)
        hmax = 0.04 / np.where(speed > 0, speed, 1.0)
    else:
        hmax = np.ascontiguousarray(np.broadcast_to(np.asarray(max_step, float), (N,)))
    return _compiled()(I, w, lin, quad, tau, hmax)


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
