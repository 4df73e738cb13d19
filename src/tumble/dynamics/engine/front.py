"""The engine's Python front: a run's arrays in, the kernel's samples out (package docstring).

Imports no numba until a run is asked for: :mod:`~tumble.dynamics.engine.kernels` is loaded on
first use, so ``import tumble`` stays fast.
"""

from __future__ import annotations

import functools
import math
from types import ModuleType

import numpy as np

from ...jit import PARALLEL_BODIES, cores
from ...typing import FloatArray
from .status import BUDGET_SPENT, MAX_EVALUATIONS, STEP_COLLAPSED

__all__ = ["ENGINE_METHODS", "run_bodies", "run_body"]

#: The steppers of the engine by method name: DOP853 with error control and dense output, and
#: fixed-step RK4 and RK8 (the 12-stage 8th-order weights of DOP853).
ENGINE_METHODS = ("dop853", "rk4", "rk8")


@functools.cache
def _kernels() -> ModuleType:
    from . import kernels

    return kernels


@functools.cache
def _tableau(method: str) -> tuple[FloatArray, FloatArray, FloatArray]:
    from .tableau import DOP853_A, DOP853_B, DOP853_C, RK4_A, RK4_B, RK4_C

    if method == "rk4":
        return RK4_A, RK4_B, RK4_C
    return np.ascontiguousarray(DOP853_A[:12, :12]), DOP853_B, np.ascontiguousarray(DOP853_C[:12])


def _raise_for(status: int, method: str, t_end: float, body: str = "") -> None:
    if status == STEP_COLLAPSED:
        raise RuntimeError(f"{method} integration failed{body}: the step size fell below 10 ulp of t")
    if status == BUDGET_SPENT:
        raise RuntimeError(f"{method} gave up{body} after {MAX_EVALUATIONS:,} evaluations of a {t_end:g} s run: "
                           f"the motion is too fast to follow (a torque spinning the body up?)")


def run_body(method: str, moments: FloatArray, omega0: FloatArray, quat0: FloatArray, t: FloatArray,
             form: tuple[int, tuple[float, ...]], *, rtol: float | None = None, atol: FloatArray | None = None,
             step: float | None = None) -> tuple[FloatArray, FloatArray]:
    """One body through the samples ``t`` (s, from t[0]) with a stepper of :data:`ENGINE_METHODS`.

    Parameters
    ----------
    method : str
        ``"dop853"`` (``rtol`` and ``atol`` used), ``"rk4"`` or ``"rk8"`` (``step`` used).
    moments : ndarray, shape (3,)
        Principal moments, kg m^2.
    omega0 : ndarray, shape (3,)
        Initial angular velocity, principal frame, rad/s.
    quat0 : ndarray, shape (4,)
        Initial attitude, body to world, scalar last.
    t : ndarray, shape (n,)
        Sample times, s, increasing.
    form : tuple
        The torque's ``(kind, parameters)`` (:func:`~tumble.dynamics.models.torques.kernel_form`).
    rtol : float, optional
        DOP853's relative tolerance.
    atol : ndarray, shape (7,), optional
        DOP853's absolute tolerance per state component (omega in rad/s, then the quaternion).
    step : float, optional
        The fixed steppers' largest step, s.

    Returns
    -------
    omega, quat : ndarray, shapes (n, 3) and (n, 4)

    Examples
    --------
    A steady spin about a principal axis: the attitude turns at omega.

    >>> import numpy as np
    >>> from tumble.dynamics.engine.front import run_body
    >>> omega, quat = run_body("rk8", np.array([1.0, 2.0, 3.0]), np.array([0.0, 0.0, 0.5]),
    ...                        np.array([0.0, 0.0, 0.0, 1.0]), np.array([0.0, 2.0]), (0, ()), step=0.1)
    >>> np.allclose(quat[-1], [0.0, 0.0, np.sin(0.5), np.cos(0.5)], rtol=0, atol=1e-14)
    True
    """
    k = _kernels()
    y0 = np.empty(7)
    y0[:3], y0[3:] = omega0, quat0
    omega, quat = np.empty((len(t), 3)), np.empty((len(t), 4))
    kind, params = form
    p = np.array(params or (0.0,))
    if method == "dop853":
        status = k.dop853(y0, t, moments, kind, p, rtol, atol, omega, quat)
    else:
        A, B, C = _tableau(method)
        status = k.fixed_rk(y0, t, moments, kind, p, math.inf if step is None else step, A, B, C, omega, quat)
    if status:
        _raise_for(status, method, float(t[-1]))
    return omega, quat


def run_bodies(method: str, moments: FloatArray, omega0: FloatArray, quat0: FloatArray, t: FloatArray,
               form: tuple[int, tuple[float, ...]], *, rtol: float | None = None, atol: FloatArray | None = None,
               step: float | FloatArray | None = None) -> tuple[FloatArray, FloatArray]:
    """N bodies (rows of ``moments``, ``omega0``, ``quat0``, ``atol`` (N, 7) and ``step``, one
    or (N,)), each as :func:`run_body` runs it, on every core from :data:`~tumble.jit.PARALLEL_BODIES`
    bodies: the same arithmetic for each body either way. Returns ``omega`` (N, n, 3) and
    ``quat`` (N, n, 4).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.engine.front import run_bodies
    >>> I = np.array([[1.0, 2.0, 3.0], [2.0, 2.5, 3.0]])
    >>> w = np.array([[0.0, 0.0, 0.5], [0.0, 0.0, 0.5]])
    >>> q = np.tile([0.0, 0.0, 0.0, 1.0], (2, 1))
    >>> omega, quat = run_bodies("dop853", I, w, q, np.array([0.0, 1.0]), (1, (0.0, 0.0, 3.0)), rtol=1e-12,
    ...                          atol=np.full((2, 7), 1e-14))
    >>> omega[:, -1, 2].round(12).tolist()   # omega_3 + tau t / I3
    [1.5, 1.5]
    """
    k = _kernels()
    N = len(moments)
    y0 = np.ascontiguousarray(np.concatenate([omega0, quat0], axis=1), dtype=float)
    I = np.ascontiguousarray(moments, dtype=float)
    kind, params = form
    p = np.ascontiguousarray(np.broadcast_to(np.array(params if params else (0.0,), dtype=float), (N, max(len(params), 1))))
    omega, quat = np.empty((N, len(t), 3)), np.empty((N, len(t), 4))  # body-first, as BatchTrajectory keeps them
    status = np.zeros(N, dtype=np.int64)
    h = np.ascontiguousarray(np.broadcast_to(np.asarray(math.inf if step is None else step, dtype=float), (N,)))
    if N >= PARALLEL_BODIES and cores() > 1:
        if method == "dop853":
            k.dop853_batch(y0, t, I, kind, p, float(rtol), np.ascontiguousarray(atol), omega, quat, status)  # type: ignore[arg-type]
        else:
            k.fixed_batch(y0, t, I, kind, p, h, *_tableau(method), omega, quat, status)
    else:
        for b in range(N):
            if method == "dop853":
                status[b] = k.dop853(y0[b], t, I[b], kind, p[b], float(rtol), atol[b], omega[b], quat[b])  # type: ignore[index, arg-type]
            else:
                status[b] = k.fixed_rk(y0[b], t, I[b], kind, p[b], h[b], *_tableau(method), omega[b], quat[b])
    for bad in np.flatnonzero(status).tolist():
        _raise_for(int(status[bad]), method, float(t[-1]), f" for body {bad}")
    return omega, quat
