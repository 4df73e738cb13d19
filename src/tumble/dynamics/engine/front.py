"""The engine's Python front: a run's arrays in, the kernel's samples out (package docstring).

Imports no numba until a run is asked for: :mod:`~tumble.dynamics.engine.kernels` is loaded on
first use, so ``import tumble`` stays fast.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from types import ModuleType

import numpy as np

from ...jit import PARALLEL_BODIES, cores, kernel_array
from ...typing import FloatArray, IntArray
from ..models.torque_protocols import Form, kernel_terms
from .status import BUDGET_SPENT, MAX_ENGINE_EVALUATIONS, NON_FINITE, STEP_COLLAPSED

__all__ = ["ENGINE_METHODS", "run_bodies", "run_body", "run_damped"]

#: The steppers of the engine by method name: DOP853 with error control and dense output, and
#: fixed-step RK4 and RK8 (the 12-stage 8th-order weights of DOP853).
ENGINE_METHODS = ("dop853", "rk4", "rk8")


@functools.cache
def _kernels() -> ModuleType:
    from . import kernels

    return kernels


@functools.cache
def _lanes() -> ModuleType:
    from . import lanes

    return lanes


@functools.cache
def _damped() -> ModuleType:
    from . import damped

    return damped


def terms(form: Form | Sequence[Form]) -> tuple[tuple[float, ...], float]:
    """The kernels' torque terms ``(P, n)`` (:mod:`~tumble.dynamics.engine.kernels`) of one model's
    form ``(kind, parameters)`` or of a sequence of them, a sum of models
    (:func:`~tumble.dynamics.models.torque_protocols.kernel_terms`): each kind's terms added in its
    slot of ``P``; ``n`` the circular orbit's mean motion (rad/s), 0 without one.

    Examples
    --------
    >>> from tumble.dynamics.engine.front import terms
    >>> from tumble.dynamics.models.torques import KERNEL_BODY, KERNEL_CIRCULAR_GRAVITY
    >>> terms([(KERNEL_BODY, (0.0, 0.0, 1.0)), (KERNEL_BODY, (1.0, 0.0, 0.0)), (KERNEL_CIRCULAR_GRAVITY, (0.5,))])
    ((1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.25, 0.0, 0.0, 0.0), 0.5)
    """
    forms = (form,) if isinstance(form[0], int) else tuple(form)
    return kernel_terms(forms)


def _check_method(method: str, allowed: Sequence[str] = ENGINE_METHODS) -> None:
    """A ValueError naming ``method`` unless it is one of ``allowed`` (a misspelt name would
    otherwise run another method)."""
    if method not in allowed:
        raise ValueError(f"method = {method!r} is not one of the engine's: {', '.join(allowed)}")


def _raise_for(status: int, method: str, t_end: float, body: str = "") -> None:
    if status == STEP_COLLAPSED:
        raise RuntimeError(f"{method} integration failed{body}: the step size fell below 10 ulp of t")
    if status == NON_FINITE:
        raise RuntimeError(f"the {method} integration produced non-finite values{body}")
    if status == BUDGET_SPENT:
        raise RuntimeError(f"{method} gave up{body} after {MAX_ENGINE_EVALUATIONS:,} evaluations of a {t_end:g} s run: "
                           f"the motion is too fast to follow (a torque spinning the body up?)")



def run_body(method: str, moments: FloatArray, omega0: FloatArray, quat0: FloatArray, t: FloatArray,
             form: Form | Sequence[Form], *, rtol: float | None = None, atol: FloatArray | None = None,
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
        The torque's ``(kind, parameters)`` (:func:`~tumble.dynamics.models.torques.kernel_form`), or a
        sequence of them, a sum of models (:func:`terms`).
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
    _check_method(method)
    k = _kernels()
    y0 = np.empty(7)
    y0[:3], y0[3:] = omega0, quat0
    omega, quat = np.empty((len(t), 3)), np.empty((len(t), 4))
    P, n = terms(form)
    if not (moments.flags.writeable and t.flags.writeable):  # read-only: every kernel compiled again (kernel_array)
        moments, t = kernel_array(moments), kernel_array(t)
    if method == "dop853":
        status = k.dop853(y0, t, moments, P, n, rtol, atol, omega, quat)
    else:
        run = k.fixed_rk4 if method == "rk4" else k.fixed_rk8
        status = run(y0, t, moments, P, n, math.inf if step is None else float(step), omega, quat)
    if status:
        _raise_for(status, method, float(t[-1]))
    return omega, quat


def run_bodies(method: str, moments: FloatArray, omega0: FloatArray, quat0: FloatArray, t: FloatArray,
               form: Form | Sequence[Form], *, rtol: float | None = None, atol: FloatArray | None = None,
               step: float | FloatArray | None = None) -> tuple[FloatArray, FloatArray]:
    """N bodies (rows of ``moments``, ``omega0``, ``quat0``, ``atol`` (N, 7) and ``step``, one
    or (N,)), each as :func:`run_body` runs it, on every core from :data:`~tumble.jit.PARALLEL_BODIES`
    bodies: DOP853 with the same arithmetic for each body either way; RK4 and RK8 there in vector
    lanes (:mod:`~tumble.dynamics.engine.lanes`), each body with the same steps as alone and the same
    sums, equal to round-off. Returns ``omega`` (N, n, 3) and ``quat`` (N, n, 4).

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
    _check_method(method)
    k = _kernels()
    N = len(moments)
    y0 = np.ascontiguousarray(np.concatenate([omega0, quat0], axis=1), dtype=float)
    I, t = kernel_array(moments), kernel_array(t)
    P, n = terms(form)
    omega, quat = np.empty((N, len(t), 3)), np.empty((N, len(t), 4))  # body-first, as BatchTrajectory keeps them
    status = np.zeros(N, dtype=np.int64)
    h = kernel_array(math.inf if step is None else step, (N,))
    if N >= PARALLEL_BODIES and cores() > 1:
        if method == "dop853":
            k.dop853_batch(y0, t, I, P, n, float(rtol), np.ascontiguousarray(atol), omega, quat, status)  # type: ignore[arg-type]
        else:
            _in_lanes(method, y0, t, I, P, n, h, omega, quat, status)
    else:
        fixed = k.fixed_rk4 if method == "rk4" else k.fixed_rk8
        for b in range(N):
            if method == "dop853":
                status[b] = k.dop853(y0[b], t, I[b], P, n, float(rtol), atol[b], omega[b], quat[b])  # type: ignore[index, arg-type]
            else:
                status[b] = fixed(y0[b], t, I[b], P, n, h[b], omega[b], quat[b])
    for bad in np.flatnonzero(status).tolist():
        _raise_for(int(status[bad]), method, float(t[-1]), f" for body {bad}")
    return omega, quat


def _in_lanes(method: str, y0: FloatArray, t: FloatArray, I: FloatArray, P: tuple[float, ...], n: float, h: FloatArray,
              omega: FloatArray, quat: FloatArray, status: IntArray) -> None:
    """RK4 or RK8 over the bodies in blocks of vector lanes, sorted by their steps (a block takes one
    step for all its bodies); a block whose bodies split an interval differently, or that overflowed,
    again body by body (its bodies' statuses into ``status``)."""
    k, lanes = _kernels(), _lanes()
    order = np.argsort(h, kind="stable")
    blocks = np.zeros(-(-len(order) // lanes.LANES), dtype=np.int64)
    run = lanes.lanes_rk4 if method == "rk4" else lanes.lanes_rk8
    run(y0[order], t, I[order], P, n, h[order], order, omega, quat, blocks)
    fixed = k.fixed_rk4 if method == "rk4" else k.fixed_rk8
    for block in np.flatnonzero(blocks).tolist():
        for b in order[block * lanes.LANES:(block + 1) * lanes.LANES].tolist():
            status[b] = fixed(y0[b], t, I[b], P, n, h[b], omega[b], quat[b])


def run_damped(method: str, body: FloatArray, y0: FloatArray, t: FloatArray, form: Form | Sequence[Form], *,
               step: float | None = None) -> FloatArray:
    """A body with a spherical damper (and rotors at constant spin) through the samples ``t`` (s, from
    t[0]) with the fixed steps of ``"rk4"`` or ``"rk8"`` (:mod:`~tumble.dynamics.engine.damped`).

    Parameters
    ----------
    method : str
        ``"rk4"`` or ``"rk8"``.
    body : ndarray, shape (8,)
        The principal moments (kg m^2), the damper's moment ``J`` (kg m^2) and damping ``c`` (N m s),
        the rotors' constant momentum ``h`` (kg m^2/s, principal frame).
    y0 : ndarray, shape (11,)
        The initial state ``(L, q, w_d, D)`` (:meth:`~tumble.dynamics.models.internal.InternalModel.initial_state`).
    t : ndarray, shape (n,)
        Sample times, s, increasing.
    form : tuple
        The torque's ``(kind, parameters)``, or a sequence of them (:func:`terms`).
    step : float, optional
        The largest step, s.

    Returns
    -------
    ndarray, shape (n, 11)
        The states at the samples.

    Examples
    --------
    A damper turning with a body in a steady spin about a principal axis: nothing changes but the attitude.

    >>> import numpy as np
    >>> from tumble.dynamics.engine.front import run_damped
    >>> Y = run_damped("rk8", np.array([1.0, 2.0, 3.0, 0.1, 0.5, 0.0, 0.0, 0.0]),
    ...                np.array([0.0, 0.0, 3.1, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0]), np.array([0.0, 2.0]), (0, ()),
    ...                step=0.1)
    >>> Y[-1, [2, 9, 10]].round(12).tolist(), bool(np.isclose(Y[-1, 5], np.sin(1.0)))
    ([3.1, 1.0, 0.0], True)
    >>> run_damped("dop853", np.ones(8), np.zeros(11), np.array([0.0, 1.0]), (0, ()))
    Traceback (most recent call last):
    ...
    ValueError: method = 'dop853' is not one of the engine's: rk4, rk8
    """
    _check_method(method, ("rk4", "rk8"))
    k = _damped()
    Y = np.empty((len(t), 11))
    P, n = terms(form)
    run = k.fixed_damped_rk4 if method == "rk4" else k.fixed_damped_rk8
    status = run(kernel_array(y0), kernel_array(t), kernel_array(body), P, n, math.inf if step is None else float(step), Y)
    if status:
        _raise_for(status, method, float(t[-1]))
    return Y
