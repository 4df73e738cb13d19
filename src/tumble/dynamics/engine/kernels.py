"""The engine's compiled core: the rigid body's equations under the built-in torques, and the steppers.

Imported only when a compiled run is asked for (it compiles with numba through
:func:`tumble.jit.jit`, ``cache=True``: once per machine and per version of the sources).

**The state** is ``y = (omega, q)``: the angular velocity (rad/s, principal frame) and the
attitude quaternion (body to world, scalar last), 7 floats. Its right-hand side
(:func:`body_rhs`) is Euler's equations (:func:`tumble.dynamics.euler.euler_components`) and the
quaternion kinematics (:func:`tumble.dynamics.special.quaternion.quaternion_rate_components`),
with the external torque of a built-in model (:func:`external_torque`), component by component
(:func:`rhs_components`). Each formula is the
model's own function over floats, compiled here, not a second writing.

**The steppers**, one body per call (a batch runs them over bodies, :func:`dop853_batch` and
:func:`fixed_batch`, on every core with ``prange``):

- :func:`dop853`: Dormand & Prince's 8(5,3) pair with error control and its 7th-order dense
  output at the sample times (Hairer, Norsett & Wanner, *Solving ODEs I*, 2nd ed., sec. II.10),
  step for step scipy's ``solve_ivp(method="DOP853", t_eval=...)``: its starting step
  (``select_initial_step``, HNW sec. II.4), error norm (the 5th- and 3rd-order estimates
  combined, RMS with ``scale = atol + rtol max(|y|, |y_new|)``), step control (safety 0.9,
  factors in [0.2, 10], no growth after a rejection) and dense output. So the compiled and the
  Python paths agree to round-off, not only to the tolerance (tests/test_engine.py).
- :func:`fixed_rk`: an explicit Runge-Kutta tableau at a fixed step: equal steps no longer than
  ``step`` in each sample interval (RK4, or the 8th-order weights of DOP853: ``"rk4"``, ``"rk8"``).

Quaternions are normalised at the samples only: inside a step the kinematics carry the norm to
round-off, and the torques read the normalised attitude.
"""

from __future__ import annotations

import math

import numpy as np
from numba import prange

from ...jit import jit
from ..euler import euler_components
from ..models.gravity import gradient_components
from ..models.torques import KERNEL_BODY, KERNEL_CIRCULAR_GRAVITY, KERNEL_NONE, KERNEL_WORLD
from ..special.quaternion import quaternion_rate_components, to_body
from .stepsize import equal_steps, error_norm, first_trial_step, initial_step, next_step, rms
from .status import BUDGET_SPENT, MAX_EVALUATIONS, OK, STEP_COLLAPSED
from .tableau import DOP853_A, DOP853_B, DOP853_C, DOP853_D, DOP853_E3, DOP853_E5

__all__ = ["body_rhs", "dop853", "dop853_batch", "external_torque", "fixed_batch", "fixed_rk", "rhs_components"]

#: Size of the state ``(omega, q)``: a constant, so the compiler unrolls the loops over it.
STATE = 7

#: LLVM's fast-math flags the steppers take: fused multiply-adds only (round-off). Not reciprocals
#: (``a / s`` as ``a * (1 / s)`` overflows for the tiny ``atol`` of a body at rest, 1e-312), nor
#: the flags that assume no NaN or inf, so a run that overflows still ends in a status.
_FAST = {"contract"}

_euler = jit(euler_components, error_model="numpy", inline="always")
_quaternion_rate = jit(quaternion_rate_components, error_model="numpy", inline="always")
_to_body = jit(to_body, error_model="numpy", inline="always")
_gravity_gradient = jit(gradient_components, error_model="numpy", inline="always")
_error_norm = jit(error_norm, error_model="numpy", inline="always")
_next_step = jit(next_step, error_model="numpy", inline="always")
_rms = jit(rms, error_model="numpy")
_equal_steps = jit(equal_steps, error_model="numpy", inline="always")
_first_trial_step = jit(first_trial_step, error_model="numpy", inline="always")
_initial_step_of = jit(initial_step, error_model="numpy", inline="always")


@jit(error_model="numpy", inline="always")
def external_torque(kind: int, p: np.ndarray, t: float, I0: float, I1: float, I2: float, x: float, y: float,
                    z: float, s: float) -> tuple[float, float, float]:
    """The built-in model's torque (N m, principal frame) at ``t`` (s) on a body of principal
    moments ``I0, I1, I2`` (kg m^2) at the attitude quaternion ``(x, y, z, s)`` (scalar last, not
    necessarily normalised): ``kind`` and ``p`` from the model's
    :meth:`~tumble.dynamics.models.torques.KernelForm.kernel_form`.

    A constant body torque ``p``; a constant world torque ``p`` seen from the body, ``R^T p``;
    the circular orbit's gravity gradient ``3 n^2 r_b x (I r_b)`` with ``r_b = R^T (cos nt,
    sin nt, 0)`` and ``n = p[0]`` (:class:`~tumble.dynamics.models.gravity.GravityGradient`).
    """
    if kind == KERNEL_NONE:
        return 0.0, 0.0, 0.0
    if kind == KERNEL_BODY:
        return p[0], p[1], p[2]
    scale = 1.0 / math.sqrt(x * x + y * y + z * z + s * s)
    x, y, z, s = x * scale, y * scale, z * scale, s * scale
    if kind == KERNEL_WORLD:
        return _to_body(x, y, z, s, p[0], p[1], p[2])
    n = p[0]
    b0, b1, b2 = _to_body(x, y, z, s, math.cos(n * t), math.sin(n * t), 0.0)
    return _gravity_gradient(n * n, I0, I1, I2, b0, b1, b2)


@jit(error_model="numpy", inline="always")
def rhs_components(t: float, w0: float, w1: float, w2: float, x: float, y: float, z: float, s: float, I0: float,
                   I1: float, I2: float, kind: int, p: np.ndarray) -> tuple[float, float, float, float, float, float, float]:
    """``dy/dt`` of the state ``(omega, q)`` component by component (module docstring)."""
    u0, u1, u2 = external_torque(kind, p, t, I0, I1, I2, x, y, z, s)
    a0, a1, a2 = _euler(w0, w1, w2, I0, I1, I2, u0, u1, u2)
    d0, d1, d2, d3 = _quaternion_rate(x, y, z, s, w0, w1, w2)
    return a0, a1, a2, d0, d1, d2, d3


@jit(error_model="numpy", inline="always")
def body_rhs(t: float, y: np.ndarray, I: np.ndarray, kind: int, p: np.ndarray, out: np.ndarray) -> None:
    """``dy/dt`` of the state ``(omega, q)`` into ``out`` (:func:`rhs_components`)."""
    out[0], out[1], out[2], out[3], out[4], out[5], out[6] = rhs_components(
        t, y[0], y[1], y[2], y[3], y[4], y[5], y[6], I[0], I[1], I[2], kind, p)


@jit(error_model="numpy", inline="always")
def _store(y: np.ndarray, omega: np.ndarray, quat: np.ndarray) -> None:
    """A sample: omega as it is, the quaternion normalised."""
    norm = math.sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6])
    for i in range(3):
        omega[i] = y[i]
    for i in range(4):
        quat[i] = y[3 + i] / norm


@jit(error_model="numpy", inline="always")
def _combine(K: np.ndarray, a: np.ndarray, s: int, y: np.ndarray, h: float, out: np.ndarray) -> None:
    """A stage's state ``y + h sum_{r < s} a_r K_r`` into ``out`` (the sum over stages first, as
    scipy's ``np.dot(K[:s].T, a[:s]) * h``)."""
    c0, c1, c2, c3, c4, c5, c6 = _weighted(K, a, s)
    out[0], out[1], out[2], out[3] = y[0] + c0 * h, y[1] + c1 * h, y[2] + c2 * h, y[3] + c3 * h
    out[4], out[5], out[6] = y[4] + c4 * h, y[5] + c5 * h, y[6] + c6 * h


@jit(error_model="numpy", inline="always")
def _weighted(K: np.ndarray, a: np.ndarray, s: int) -> tuple[float, float, float, float, float, float, float]:
    """``sum_{r < s} a_r K_r``, the state's seven components written out so that the compiler
    packs them into vector instructions (its SLP vectoriser; a loop over the components it does
    not vectorise, not knowing that the arrays do not overlap): 1.3x the whole RK8 step."""
    c0 = c1 = c2 = c3 = c4 = c5 = c6 = 0.0
    for r in range(s):
        c = a[r]
        if c == 0.0:  # a quarter of DOP853's weights are zeros: skipped, not multiplied
            continue
        c0 += K[r, 0] * c
        c1 += K[r, 1] * c
        c2 += K[r, 2] * c
        c3 += K[r, 3] * c
        c4 += K[r, 4] * c
        c5 += K[r, 5] * c
        c6 += K[r, 6] * c
    return c0, c1, c2, c3, c4, c5, c6


@jit(error_model="numpy")
def _initial_step(t0: float, y: np.ndarray, f: np.ndarray, t_bound: float, I: np.ndarray, kind: int, p: np.ndarray,
                  rtol: float, atol: np.ndarray, work: np.ndarray) -> float:
    """scipy's ``select_initial_step`` for an error estimator of order 7 (HNW sec. II.4)."""
    n = STATE
    interval = abs(t_bound - t0)
    scale, y1, f1 = work[0], work[1], work[2]
    for i in range(n):
        scale[i] = atol[i] + abs(y[i]) * rtol
    d1 = _rms(f, scale)
    h0 = _first_trial_step(_rms(y, scale), d1, interval)
    for i in range(n):
        y1[i] = y[i] + h0 * f[i]
    body_rhs(t0 + h0, y1, I, kind, p, f1)
    for i in range(n):
        f1[i] -= f[i]
    return _initial_step_of(h0, d1, _rms(f1, scale) / h0, interval)


@jit(error_model="numpy")
def _dense(t_old: float, h: float, y_old: np.ndarray, y: np.ndarray, K: np.ndarray, I: np.ndarray, kind: int,
           p: np.ndarray, F: np.ndarray, work: np.ndarray) -> None:
    """The 7th-order interpolant of the step from ``t_old`` (s) of length ``h`` into ``F`` (7, n):
    the three extra stages, then scipy's ``Dop853DenseOutput`` coefficients (HNW sec. II.6)."""
    n = STATE
    ys = work[0]
    for s in range(13, 16):
        _combine(K, DOP853_A[s], s, y_old, h, ys)
        body_rhs(t_old + DOP853_C[s] * h, ys, I, kind, p, K[s])
    for i in range(n):
        dy = y[i] - y_old[i]
        F[0, i] = dy
        F[1, i] = h * K[0, i] - dy
        F[2, i] = 2.0 * dy - h * (K[12, i] + K[0, i])
    for r in range(4):
        d = _weighted(K, DOP853_D[r], 16)
        for i in range(n):
            F[3 + r, i] = h * d[i]


@jit(error_model="numpy")
def _interpolate(F: np.ndarray, y_old: np.ndarray, x: float, out: np.ndarray) -> None:
    """The interpolant at the fraction ``x`` of its step (scipy's ``Dop853DenseOutput._call_impl``)."""
    for i in range(y_old.shape[0]):
        v = 0.0
        for j in range(7):
            v += F[6 - j, i]
            v *= x if j % 2 == 0 else 1.0 - x
        out[i] = v + y_old[i]


@jit(error_model="numpy", fastmath=_FAST)
def dop853(y0: np.ndarray, t_eval: np.ndarray, I: np.ndarray, kind: int, p: np.ndarray, rtol: float,
           atol: np.ndarray, omega: np.ndarray, quat: np.ndarray) -> int:
    """DOP853 from ``t_eval[0]`` through ``t_eval[-1]`` (s), the samples into ``omega`` and ``quat``
    (len(t_eval) rows each),
    as scipy's ``solve_ivp`` takes it (module docstring). Returns a status: 0 done, 1 the step fell
    below 10 ulp of t, 2 :data:`MAX_EVALUATIONS` spent."""
    n = STATE
    K = np.empty((16, n))
    F = np.empty((7, n))
    work = np.empty((3, n))
    y, y_old, y_new, ys, sample = y0.copy(), y0.copy(), np.empty(n), np.empty(n), np.empty(n)
    t, t_bound = t_eval[0], t_eval[-1]
    body_rhs(t, y, I, kind, p, K[0])
    evaluations = 2
    h_abs = _initial_step(t, y, K[0], t_bound, I, kind, p, rtol, atol, work)
    k = 0  # the next sample
    while k < t_eval.shape[0]:
        if t == t_bound:  # a run of one sample, at the start
            _store(y, omega[k], quat[k])
            k += 1
            continue
        min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
        h_abs = max(h_abs, min_step)
        rejected = False
        while True:  # one accepted step (scipy's RungeKutta._step_impl)
            if h_abs < min_step:
                return STEP_COLLAPSED
            if evaluations > MAX_EVALUATIONS:
                return BUDGET_SPENT
            t_new = t + h_abs
            if t_new - t_bound > 0.0:
                t_new = t_bound
            h = t_new - t
            h_abs = abs(h)
            for s in range(1, 12):
                _combine(K, DOP853_A[s], s, y, h, ys)
                body_rhs(t + DOP853_C[s] * h, ys, I, kind, p, K[s])
            _combine(K, DOP853_B, 12, y, h, y_new)
            body_rhs(t_new, y_new, I, kind, p, K[12])
            evaluations += 12
            err5, err3 = _weighted(K, DOP853_E5, 13), _weighted(K, DOP853_E3, 13)
            e5, e3 = 0.0, 0.0
            for i in range(n):
                scale = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol
                a5, a3 = err5[i] / scale, err3[i] / scale
                e5 += a5 * a5
                e3 += a3 * a3
            accepted, h_abs = _next_step(_error_norm(e5, e3, h_abs, n), h_abs, rejected)
            if accepted:
                break
            rejected = True
        # samples in (t, t_new], and t itself for the first: scipy's searchsorted(t_eval, t_new, "right")
        if k < t_eval.shape[0] and t_eval[k] <= t_new:
            for i in range(n):
                y_old[i] = y[i]
            _dense(t, h, y_old, y_new, K, I, kind, p, F, work)
            evaluations += 3
            while k < t_eval.shape[0] and t_eval[k] <= t_new:
                _interpolate(F, y_old, (t_eval[k] - t) / h, sample)
                _store(sample, omega[k], quat[k])
                k += 1
        t = t_new
        for i in range(n):
            y[i] = y_new[i]
            K[0, i] = K[12, i]
    return OK


@jit(error_model="numpy", fastmath=_FAST)
def fixed_rk(y0: np.ndarray, t_eval: np.ndarray, I: np.ndarray, kind: int, p: np.ndarray, step: float,
             A: np.ndarray, B: np.ndarray, C: np.ndarray, omega: np.ndarray, quat: np.ndarray) -> int:
    """The explicit Runge-Kutta tableau ``(A, B, C)`` at equal steps no longer than ``step`` (s) in
    each sample interval, the samples into ``omega`` and ``quat``. Returns 0 (the status of :func:`dop853`)."""
    n, stages = STATE, B.shape[0]
    K = np.empty((stages, n))
    y, ys = y0.copy(), np.empty(n)
    _store(y, omega[0], quat[0])
    for k in range(1, t_eval.shape[0]):
        m, h = _equal_steps(t_eval[k] - t_eval[k - 1], step)
        for j in range(m):
            t = t_eval[k - 1] + j * h
            for s in range(stages):
                _combine(K, A[s], s, y, h, ys)
                body_rhs(t + C[s] * h, ys, I, kind, p, K[s])
            _combine(K, B, stages, y, h, ys)
            y[:] = ys
        _store(y, omega[k], quat[k])
    return OK


@jit(parallel=True, error_model="numpy")
def dop853_batch(y0: np.ndarray, t_eval: np.ndarray, I: np.ndarray, kind: int, p: np.ndarray, rtol: float,
                 atol: np.ndarray, omega: np.ndarray, quat: np.ndarray, status: np.ndarray) -> None:
    """:func:`dop853` for each body ``b`` (rows of ``y0``, ``I``, ``p``, ``atol``; its samples
    ``omega[b]``, ``quat[b]``), on every core."""
    for b in prange(y0.shape[0]):
        status[b] = dop853(y0[b], t_eval, I[b], kind, p[b], rtol, atol[b], omega[b], quat[b])


@jit(parallel=True, error_model="numpy")
def fixed_batch(y0: np.ndarray, t_eval: np.ndarray, I: np.ndarray, kind: int, p: np.ndarray, step: np.ndarray,
                A: np.ndarray, B: np.ndarray, C: np.ndarray, omega: np.ndarray, quat: np.ndarray,
                status: np.ndarray) -> None:
    """:func:`fixed_rk` for each body ``b`` (rows of ``y0``, ``I``, ``p``, ``step``; its samples
    ``omega[b]``, ``quat[b]``), on every core."""
    for b in prange(y0.shape[0]):
        status[b] = fixed_rk(y0[b], t_eval, I[b], kind, p[b], step[b], A, B, C, omega[b], quat[b])
