"""The engine's compiled core: the rigid body's equations under a sum of built-in torques, and the steppers.

Imported only when a compiled run is asked for (it compiles with numba through
:func:`tumble.jit.jit`, ``cache=True``: once per machine and per version of the sources).

**The state** is ``y = (omega, q)``: the angular velocity (rad/s, principal frame) and the
attitude quaternion (body to world, scalar last), a tuple of 7 floats. Its right-hand side
(:func:`rhs`) is Euler's equations (:func:`tumble.dynamics.euler.euler_components`) and the
quaternion kinematics (:func:`tumble.dynamics.special.quaternion.quaternion_rate_components`),
with the sum of the built-in torque terms (:func:`external_torque`). Each formula is the
model's own function over floats, compiled here, not a second writing.

**The torque terms** are one tuple ``P`` of 10 floats, every built-in model's term in its own
slot, so that a sum of any number of models is one tuple (:func:`~tumble.dynamics.engine.front.terms`
adds them up from the models' :meth:`~tumble.dynamics.models.torques.KernelForm.kernel_form`):
``P[0:3]`` the constant body torque (N m); ``P[3:6]`` the constant world torque (N m), seen from
the body as ``R^T P[3:6]``; ``P[6]`` the ``n^2`` (1/s^2) of the circular orbit's gravity gradient
``3 n^2 r_b x (I r_b)`` with ``r_b = R^T (cos nt, sin nt, 0)``; ``P[7:10]`` the constant internal
momentum ``h`` (kg m^2/s) of rotors at constant spin, whose term is ``h x omega`` (the gyrostat,
Hughes, *Spacecraft Attitude Dynamics*, sec. 3.4). The orbit's mean motion ``n`` (rad/s, 0
without an orbit) is the run's, so its direction is turned from a step's start to its stages
without trigonometry (:mod:`~tumble.dynamics.engine.unrolled`). A tuple, not arrays: its values
stay in registers through a run (a loop over term arrays cost 1.5x the whole RK8 step).

**The steppers**, one body per call (a batch runs them over bodies, :func:`dop853_batch` and
:func:`fixed_batch`, on every core with ``prange``), their steps written out from the tableaux
by :mod:`~tumble.dynamics.engine.unrolled`:

- :func:`dop853`: Dormand & Prince's 8(5,3) pair with error control and its 7th-order dense
  output at the sample times (Hairer, Norsett & Wanner, *Solving ODEs I*, 2nd ed., sec. II.10),
  step for step scipy's ``solve_ivp(method="DOP853", t_eval=...)``: its starting step
  (``select_initial_step``, HNW sec. II.4), error norm (the 5th- and 3rd-order estimates
  combined, RMS with ``scale = atol + rtol max(|y|, |y_new|)``), step control (safety 0.9,
  factors in [0.2, 10], no growth after a rejection; the loop of tries written once,
  :func:`~tumble.dynamics.engine.unrolled.dop853_accept_source`, which the closed loop's hold
  intervals take too) and dense output. So the compiled and the Python paths agree to round-off,
  not only to the tolerance (tests/test_engine.py).
- :data:`fixed_rk4`, :data:`fixed_rk8` (and :func:`fixed_rk`, either by number): RK4 or the 8th-order
  weights of DOP853 (:data:`RK4`, :data:`RK8`) at equal steps no longer than ``step`` in each sample
  interval, the one fixed-step loop of :func:`~tumble.dynamics.engine.unrolled.fixed_loop_source`.

Quaternions are normalised at the samples only: inside a step the kinematics carry the norm to
the integration's accuracy, and the torques divide by it (:func:`external_torque`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numba import prange

from ...jit import jit
from ..environment.orbit import plane_direction
from ..euler import euler_components
from ..models.gravity import gradient_components
from ..models.torques import KERNEL_BODY, KERNEL_CIRCULAR_GRAVITY, KERNEL_WORLD
from ..special.quaternion import quaternion_rate_components, to_body
from .stepsize import equal_steps, error_norm, first_trial_step, initial_step, next_step
from .status import BUDGET_SPENT, MAX_ENGINE_EVALUATIONS, NON_FINITE, OK, STEP_COLLAPSED
from .tableau import DOP853_A, DOP853_B, DOP853_C, RK4_A, RK4_B, RK4_C
from .unrolled import STATE, dop853_accept_source, dop853_sources, fixed_loop_source, fixed_step_source, rotations_source

__all__ = ["RK4", "RK8", "dop853", "dop853_batch", "external_torque", "fixed_batch", "fixed_rk", "fixed_rk4", "fixed_rk8",
           "generated", "rhs"]

#: The fixed-step methods by number: the classical RK4, and the 12-stage 8th-order weights of DOP853.
RK4, RK8 = 0, 1

#: LLVM's fast-math flags the steppers take: fused multiply-adds only (round-off). Not reciprocals
#: (``a / s`` as ``a * (1 / s)`` overflows for the tiny ``atol`` of a body at rest, 1e-312), nor
#: the flags that assume no NaN or inf, so a run that overflows still ends in a status.
_FAST = {"contract"}

# The formulas and the step's helpers compiled as ordinary functions, which LLVM inlines where they
# are called (they are small): the kernels ran as fast as with numba's own inlining, and compiled in
# about half the time (dop853 + fixed_rk 39 -> 20 CPU-s, measured on a loaded machine), as numba
# copies an inlined function's IR, with everything it inlines, at every call site. rhs and
# external_torque, too large for LLVM's own choice, carry LLVM's ``alwaysinline`` (numba's
# ``forceinline``): compiled once each, inlined by LLVM at every stage. With numba's inlining
# (``inline="always"``) their IR was copied into each of the 12 stages of a step, and numba's own
# passes on that IR were most of a first compile: the first torque ``simulate`` (``fixed_rk8``) took
# 6.8 CPU-s, 3.2 with ``forceinline``, the step as fast (measured alternating, 20 s T-handle runs:
# rk8 85.0 / 82.9 us, dop853 175.5 / 173.7 us, gravity gradient 182.5 / 177.8 us). The loop's
# own helpers, each called at one place in a kernel (_state, _store, _finite, _direction, _rigid,
# _sample), are inlined by numba: as functions of their own each was a compile of its own, ~0.3 s
# of the first torque simulate's ~3 s (2.96 -> 2.64 s wall, the steps as fast). Since rhs is
# compiled once (not copied into the stages), the formulas it calls and the step size's helpers,
# each called at one place, are inlined by numba too: no compile of their own (the first dop853
# call 4.42 -> 4.19 CPU-s, the runs as fast; 2026-11-30).
_euler = jit(euler_components, error_model="numpy", inline="always")
_quaternion_rate = jit(quaternion_rate_components, error_model="numpy", inline="always")
_to_body = jit(to_body, error_model="numpy", inline="always")
_gravity_gradient = jit(gradient_components, error_model="numpy", inline="always")
#: A circular orbit's direction (cos n t, sin n t) at t (:func:`~tumble.dynamics.environment.orbit.plane_direction`).
_direction = jit(plane_direction, error_model="numpy", inline="always")
_error_norm = jit(error_norm, error_model="numpy", inline="always")
_next_step = jit(next_step, error_model="numpy", inline="always")
_first_trial_step = jit(first_trial_step, error_model="numpy", inline="always")
_initial_step_of = jit(initial_step, error_model="numpy", inline="always")


@jit(error_model="numpy", forceinline=True)
def external_torque(I: tuple[float, ...], w0: float, w1: float, w2: float, x: float, y: float, z: float, s: float,
                    u0: float, u1: float, P: tuple[float, ...]) -> tuple[float, float, float]:
    """The sum of the torque terms ``P`` (N m, principal frame; module docstring) on a body of
    principal moments ``I`` (kg m^2) turning at ``w`` (rad/s) at the attitude quaternion ``(x, y, z, s)`` (scalar last, not
    necessarily normalised: ``R`` is read through :func:`~tumble.dynamics.special.quaternion.to_body`'s homogeneous
    form and divided by ``|q|^2``), the orbit's direction in the world being ``(u0, u1, 0)``."""
    a0, a1, a2 = P[0], P[1], P[2]
    if P[7] != 0.0 or P[8] != 0.0 or P[9] != 0.0:  # h x omega
        a0, a1, a2 = a0 + (P[8] * w2 - P[9] * w1), a1 + (P[9] * w0 - P[7] * w2), a2 + (P[7] * w1 - P[8] * w0)
    if P[3] != 0.0 or P[4] != 0.0 or P[5] != 0.0 or P[6] != 0.0:
        # to_body of the quaternion as it is: |q|^2 times the unit quaternion's R^T v (its
        # homogeneous form), so the world torque is divided by |q|^2 and the gradient, quadratic
        # in r_b, by |q|^4. The division waits on nothing but q and runs beside the rotation; a
        # normalisation of q first (by a series about |q| = 1, or 1 / sqrt) lay on the stages'
        # chain of dependent operations: a 20 s T-handle run's RK8 in the gravity gradient took 172
        # us against 145 (alternating, one process).
        inverse = 1.0 / (x * x + y * y + z * z + s * s)
        if P[3] != 0.0 or P[4] != 0.0 or P[5] != 0.0:
            b0, b1, b2 = _to_body(x, y, z, s, P[3], P[4], P[5])
            a0, a1, a2 = a0 + b0 * inverse, a1 + b1 * inverse, a2 + b2 * inverse
        if P[6] != 0.0:
            b0, b1, b2 = _to_body(x, y, z, s, u0, u1, 0.0)
            g0, g1, g2 = _gravity_gradient(P[6] * (inverse * inverse), I[0], I[1], I[2], b0, b1, b2)
            a0, a1, a2 = a0 + g0, a1 + g1, a2 + g2
    return a0, a1, a2


@jit(error_model="numpy", forceinline=True)
def rhs(y: tuple[float, ...], I: tuple[float, ...], P: tuple[float, ...], u0: float,
        u1: float) -> tuple[float, float, float, float, float, float, float]:
    """``dy/dt`` of the state ``(omega, q)`` (module docstring), the orbit's direction ``(u0, u1, 0)``."""
    w0, w1, w2, x, yq, z, s = y
    t0, t1, t2 = external_torque(I, w0, w1, w2, x, yq, z, s, u0, u1, P)
    a0, a1, a2 = _euler(w0, w1, w2, I[0], I[1], I[2], t0, t1, t2, I[3], I[4], I[5])
    d0, d1, d2, d3 = _quaternion_rate(x, yq, z, s, w0, w1, w2)
    return a0, a1, a2, d0, d1, d2, d3


def generated(source: str, filename: str, module: str, *, parallel: bool = False, inner: bool = False,
              inline: bool = False, **names: Any) -> dict[str, Any]:
    """The functions the generated ``source`` (:mod:`~tumble.dynamics.engine.unrolled`) defines,
    compiled, by name (``parallel``: with numba's ``prange`` over every core); ``names`` what they
    call (``rhs``, helpers), ``math`` always. ``inner``: functions that only compiled code calls (the
    steps), compiled without the wrapper through which Python calls a kernel (numba's
    ``no_cpython_wrapper``; :data:`tumble.jit._SPEED_ONLY`): a tenth of the first torque
    ``simulate``'s compile. Python must not call them: numba has no entry for it and the
    interpreter crashes. ``inline``: their code copied by numba where they are called (``inline="always"``).
    The helpers of the steps (``rhs``, the formulas) keep theirs, as a
    function's ``py_func`` run in Python calls them. The code object
    is named after ``filename`` (the module that compiles it, ``module`` its name), so numba's cache
    keys the kernels on the sources (:func:`tumble.jit.jit`).

    Each step inlines its right-hand side at its stages (LLVM's ``alwaysinline``, above; without it
    LLVM left the calls, 1.5x the step), but is not itself inlined into the kernels that call it once a step:
    that made the first compile of the two kernels 58 s instead of 25 s (measured, loaded machine;
    7.6 s before the steps were written out), for no speed (a whole run written out with its steps
    in its loop ran the same).

    Examples
    --------
    >>> from tumble.dynamics.engine.kernels import generated
    >>> twice = generated("def twice(x): return 2.0 * x", "example.py", "example")["twice"]
    >>> twice(1.5)
    3.0
    """
    namespace: dict[str, Any] = {"math": math, "__name__": module, **names}
    given = set(namespace)
    exec(compile(source, filename, "exec"), namespace)  # noqa: S102 - our own generated source
    return {name: jit(f, error_model="numpy", fastmath=_FAST, parallel=parallel, no_cpython_wrapper=inner,
                      **({"inline": "always"} if inline else {}))
            for name, f in namespace.items()
            if name not in given and name != "__builtins__"}


_STEPS = generated(fixed_step_source("rk4_step", RK4_A, RK4_B, RK4_C) + rotations_source("rk4_turns", RK4_C)
                   + fixed_step_source("rk8_step", DOP853_A[:12, :12], DOP853_B, DOP853_C[:12])
                   + rotations_source("rk8_turns", DOP853_C[:12])
                   + dop853_sources() + rotations_source("dop853_turns", DOP853_C), __file__, __name__, inner=True,
                   rhs=rhs)
_rk4_step, _rk4_turns = _STEPS["rk4_step"], _STEPS["rk4_turns"]
_rk8_step, _rk8_turns = _STEPS["rk8_step"], _STEPS["rk8_turns"]
_dop853_step, _dop853_errors, _dop853_turns = _STEPS["dop853_step"], _STEPS["dop853_errors"], _STEPS["dop853_turns"]
_dop853_dense, _dop853_interpolate = _STEPS["dop853_dense"], _STEPS["dop853_interpolate"]
#: The length of the array of DOP853's turns to its stage nodes, the step they were made for first.
_DOP853_TURNS = 1 + 2 * len(DOP853_C)
#: One accepted DOP853 step with its rejections (:func:`~tumble.dynamics.engine.unrolled.dop853_accept_source`,
#: the closed loop's too), its code copied by numba into the kernel's loop, as the loop's own was: as a function
#: of its own (inlined by LLVM or not) the tour's first dop853 call compiled in 10.4-11.8 CPU-s against the own
#: loop's 6.5-8.5; copied, 8.1-8.9 (fresh copies of the sources, benchmarks/bench_first_call.py's case,
#: alternating, 2026-12-02; with the turns made for each try instead of kept, 8.1-9.1).
_dop853_accept = generated(dop853_accept_source(), __file__, __name__, inner=True, inline=True, np=np, OK=OK,
                           STEP_COLLAPSED=STEP_COLLAPSED, BUDGET_SPENT=BUDGET_SPENT, _error_norm=_error_norm,
                           _next_step=_next_step, dop853_step=_dop853_step, dop853_errors=_dop853_errors,
                           dop853_turns=_dop853_turns)["dop853_accept"]


@jit(error_model="numpy", inline="always")
def _state(y0: np.ndarray) -> tuple[float, float, float, float, float, float, float]:
    return y0[0], y0[1], y0[2], y0[3], y0[4], y0[5], y0[6]


@jit(error_model="numpy", inline="always")
def _store(y: tuple[float, ...], omega: np.ndarray, quat: np.ndarray) -> None:
    """A sample: omega as it is, the quaternion normalised."""
    norm = math.sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6])
    omega[0], omega[1], omega[2] = y[0], y[1], y[2]
    quat[0], quat[1], quat[2], quat[3] = y[3] / norm, y[4] / norm, y[5] / norm, y[6] / norm


@jit(error_model="numpy", inline="always")
def _finite(y: tuple[float, ...]) -> bool:
    """Whether every component of the state is finite (one sum: a NaN or inf anywhere makes it not)."""
    total = 0.0
    for v in y:
        total += v
    return math.isfinite(total)


@jit(error_model="numpy", inline="always")
def _rms(a: tuple[float, ...], scale: tuple[float, ...]) -> float:
    total = 0.0
    for i in range(STATE):
        v = a[i] / scale[i]
        total += v * v
    return math.sqrt(total / STATE)


@jit(error_model="numpy")
def _initial_step(y: tuple[float, ...], f: tuple[float, ...], t0: float, t_bound: float, I: tuple[float, ...],
                  P: tuple[float, ...], n: float, rtol: float, atol: np.ndarray) -> float:
    """scipy's ``select_initial_step`` for an error estimator of order 7 (HNW sec. II.4)."""
    interval = abs(t_bound - t0)
    scale = (atol[0] + abs(y[0]) * rtol, atol[1] + abs(y[1]) * rtol, atol[2] + abs(y[2]) * rtol,
             atol[3] + abs(y[3]) * rtol, atol[4] + abs(y[4]) * rtol, atol[5] + abs(y[5]) * rtol,
             atol[6] + abs(y[6]) * rtol)
    d1 = _rms(f, scale)
    h0 = _first_trial_step(_rms(y, scale), d1, interval)
    u0, u1 = _direction(n, t0 + h0)
    f1 = rhs((y[0] + h0 * f[0], y[1] + h0 * f[1], y[2] + h0 * f[2], y[3] + h0 * f[3], y[4] + h0 * f[4],
              y[5] + h0 * f[5], y[6] + h0 * f[6]), I, P, u0, u1)
    d2 = _rms((f1[0] - f[0], f1[1] - f[1], f1[2] - f[2], f1[3] - f[3], f1[4] - f[4], f1[5] - f[5], f1[6] - f[6]),
              scale) / h0
    return _initial_step_of(h0, d1, d2, interval)


@jit(error_model="numpy", fastmath=_FAST)
def dop853(y0: np.ndarray, t_eval: np.ndarray, I: np.ndarray, P: tuple[float, ...], n: float,
           rtol: float, atol: np.ndarray, omega: np.ndarray, quat: np.ndarray) -> int:
    """DOP853 from ``t_eval[0]`` through ``t_eval[-1]`` (s), the samples into ``omega`` and ``quat``
    (len(t_eval) rows each), as scipy's ``solve_ivp`` takes it (module docstring); the torque
    terms ``P`` on an orbit of mean motion ``n`` (rad/s). Returns a status: 0 done, 1 the
    step fell below 10 ulp of t, 2 :data:`~tumble.dynamics.engine.status.MAX_ENGINE_EVALUATIONS` spent, 3 a sample not finite."""
    body = (I[0], I[1], I[2], 1.0 / I[0], 1.0 / I[1], 1.0 / I[2])
    y = _state(y0)
    t, t_bound = t_eval[0], t_eval[-1]
    u0, u1 = _direction(n, t)
    f = rhs(y, body, P, u0, u1)
    evaluations = 2
    h_abs = _initial_step(y, f, t, t_bound, body, P, n, rtol, atol)
    k = 0  # the next sample
    samples = t_eval.shape[0]
    R = np.empty(_DOP853_TURNS)  # the step the turns to the stage nodes were made for, and the turns
    R[0] = math.nan
    while k < samples:
        if t == t_bound:  # a run of one sample, at the start
            _store(y, omega[k], quat[k])
            k += 1
            continue
        cs, ss = _direction(n, t)
        status, t_new, y_new, K, h_abs, evaluations = _dop853_accept(t, y, f, h_abs, t_bound, rtol, atol, body, P, cs,
                                                                     ss, n, R, evaluations, MAX_ENGINE_EVALUATIONS)
        if status != OK:
            return int(status)
        h = t_new - t
        # samples in (t, t_new], and t itself for the first: scipy's searchsorted(t_eval, t_new, "right")
        if t_eval[k] <= t_new:
            F = _dop853_dense(y, y_new, K, h, body, P, cs, ss, R[1:])
            evaluations += 3
            while k < samples and t_eval[k] <= t_new:
                sample = _dop853_interpolate(F, y, (t_eval[k] - t) / h)
                if not _finite(sample):
                    return NON_FINITE
                _store(sample, omega[k], quat[k])
                k += 1
        t = t_new
        y = y_new
        f = K[12]
    return OK


@jit(error_model="numpy", inline="always")
def _rigid(y0: np.ndarray, I: np.ndarray) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """The state tuple of ``y0`` and the body's tuple the steps take: the moments and their inverses."""
    return _state(y0), (I[0], I[1], I[2], 1.0 / I[0], 1.0 / I[1], 1.0 / I[2])


@jit(error_model="numpy", inline="always")
def _sample(y: tuple[float, ...], I: np.ndarray, omega: np.ndarray, quat: np.ndarray, k: int) -> None:
    _store(y, omega[k], quat[k])


# The fixed-step runs, :data:`RK4` and :data:`RK8` at equal steps no longer than ``step`` (s) in each
# sample interval, the samples into ``omega`` and ``quat``; the torque terms ``P`` on an orbit of mean
# motion ``n`` (rad/s); a status: 0 done, 3 the state overflowed (a NaN or inf). One kernel a method,
# so that a run compiles only its own step.
_FIXED = generated(fixed_loop_source("fixed_rk4", "rk4_step", "rk4_turns", "_rigid", "_sample", "omega, quat")
                   + fixed_loop_source("fixed_rk8", "rk8_step", "rk8_turns", "_rigid", "_sample", "omega, quat"),
                   __file__, __name__, rk4_step=_rk4_step, rk4_turns=_rk4_turns, rk8_step=_rk8_step,
                   rk8_turns=_rk8_turns, _rigid=_rigid, _sample=_sample, _equal_steps=equal_steps,
                   _direction=_direction, _finite=_finite, OK=OK, NON_FINITE=NON_FINITE)
#: The fixed-step runs of RK4 and RK8 (``run(y0, t_eval, I, P, n, step, omega, quat)``).
fixed_rk4, fixed_rk8 = _FIXED["fixed_rk4"], _FIXED["fixed_rk8"]


@jit(error_model="numpy")
def fixed_rk(y0: np.ndarray, t_eval: np.ndarray, I: np.ndarray, P: tuple[float, ...], n: float,
             step: float, method: int, omega: np.ndarray, quat: np.ndarray) -> int:
    """:data:`RK4` or :data:`RK8` (``method``) at equal steps no longer than ``step`` (s): :func:`fixed_rk4` or
    :func:`fixed_rk8`, for the batch, which takes the method as a number."""
    if method == RK4:
        return int(fixed_rk4(y0, t_eval, I, P, n, step, omega, quat))
    return int(fixed_rk8(y0, t_eval, I, P, n, step, omega, quat))


@jit(parallel=True, error_model="numpy")
def dop853_batch(y0: np.ndarray, t_eval: np.ndarray, I: np.ndarray, P: tuple[float, ...], n: float,
                 rtol: float, atol: np.ndarray, omega: np.ndarray, quat: np.ndarray, status: np.ndarray) -> None:
    """:func:`dop853` for each body ``b`` (rows of ``y0``, ``I``, ``atol``; its
    samples ``omega[b]``, ``quat[b]``), on every core."""
    for b in prange(y0.shape[0]):
        status[b] = dop853(y0[b], t_eval, I[b], P, n, rtol, atol[b], omega[b], quat[b])


@jit(parallel=True, error_model="numpy")
def fixed_batch(y0: np.ndarray, t_eval: np.ndarray, I: np.ndarray, P: tuple[float, ...], n: float,
                step: np.ndarray, method: int, omega: np.ndarray, quat: np.ndarray, status: np.ndarray) -> None:
    """:func:`fixed_rk` for each body ``b`` (rows of ``y0``, ``I``, ``step``; its
    samples ``omega[b]``, ``quat[b]``), on every core."""
    for b in prange(y0.shape[0]):
        status[b] = fixed_rk(y0[b], t_eval, I[b], P, n, step[b], method, omega[b], quat[b])
