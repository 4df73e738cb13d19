"""The whole closed loop in one compiled call: the control law at each control instant, the command
held, the dynamics integrated by the engine's steps.

Imported only when a compiled closed loop is asked for (by
:mod:`~tumble.dynamics.control.control_kernel` and :func:`~tumble.dynamics.control.controlled.simulate_controlled`);
compiled at import by :func:`tumble.jit.jit` (``cache=True``), once for every wheel count: the
state is a tuple of ``N = 10 +`` :data:`MAX_WHEELS` floats (:mod:`~tumble.dynamics.control.loop_terms`),
a run's wheels in the first slots and the slots past its count ``P[20]`` left at zero (the
right-hand side skips them; scipy's error norm and starting step are taken over the run's own
``10 + k`` components, so the steps are those of the unpadded state). The right-hand side and the
steps are written out for that size (:data:`LAYOUT`, from the engine's tableaux), the right-hand
side taking the run's parameters and tables in one array (``P``,
:func:`~tumble.dynamics.control.loop_terms.packed`), into which the loop writes the command it
holds (:func:`set_command`). One size, not one per count: each size compiled for 27-39 CPU-s (measured,
loaded machine); the padded size with its right-hand side called, not inlined, compiles in 17
CPU-s (:func:`_generated`).

**One hold interval** (:func:`_advance`): DOP853 with scipy's error norm, step control and
starting step, the engine's loop of tries (:func:`~tumble.dynamics.engine.unrolled.dop853_accept_source`
over this state) and its helpers (:mod:`~tumble.dynamics.engine.stepsize`; Hairer, Norsett & Wanner, *Solving
ODEs I*, 2nd ed., sec. II.4 and II.10), step for step scipy's ``solve_ivp`` over the interval;
or, with ``carry``, starting from the step the last interval's error control proposed
(clipped to the interval) instead of a new starting-step estimate: where a step spans an
interval that is one step of 13 evaluations instead of two of 26 (a variable-step solver
that continues over a sample hit, as Simulink's do). Or fixed-step RK4 or RK8 (DOP853's 8th-order
weights) at equal steps no longer than ``step`` in each interval.

**The laws** (:mod:`~tumble.dynamics.control.loop_laws`) are
:mod:`~tumble.dynamics.control.laws`' functions, the ones the Python controllers call, with the
ideal sensors' measurement (the true omega, attitude, field and wheel spins) and the controllers'
memory (B-dot's last reading, MRP feedback's integral) carried in the loop.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ...jit import jit
from ...typing import FloatArray
from ..engine.kernels import _direction  # a circular orbit's direction, the engine's
from ..engine.status import BUDGET_SPENT, OK as _OK, STEP_COLLAPSED as _STEP_COLLAPSED
from ..engine.stepsize import equal_steps, error_norm, first_trial_step, initial_step, next_step, rms
from ..engine.tableau import DOP853_A, DOP853_B, DOP853_C, RK4_A, RK4_B, RK4_C
from ..engine.unrolled import Layout, dop853_accept_source, dop853_sources, fixed_step_source, rotations_source
from .loop_laws import NO_MEMORY, held, law_command
from .loop_terms import BODY, FIELD_NONE, WHEEL, field_body, packed, rhs_namespace, rhs_source, tables

__all__ = ["DOP853", "LAYOUT", "MAX_WHEELS", "N", "RK4", "RK8", "TABLES", "kernels", "method_flags", "padded", "rhs_of",
           "set_command", "unpadded"]

#: The methods of a hold interval: DOP853 (error control), fixed-step RK4 and RK8.
DOP853, RK4, RK8 = 0, 1, 2
#: The most wheels the kernels take (their wheel slots).
MAX_WHEELS = 6
#: The padded state's size (:func:`padded`): quaternion (4), omega (3), wheel slots, impulse (3).
N = 10 + MAX_WHEELS
#: Where the tables start in the kernels' parameter array (after the wheel slots; :func:`~tumble.dynamics.control.loop_terms.packed`).
TABLES = BODY + WHEEL * MAX_WHEELS
#: The steps' layout: a state of :data:`N` floats, the right-hand side ``rhs(t, y, P, u0, u1)``.
LAYOUT = Layout(N, "P", True)
#: Statuses (the engine's): done; the step fell below 10 ulp of t.
OK, STEP_COLLAPSED = _OK, _STEP_COLLAPSED

_rms = jit(rms, error_model="numpy")
_error_norm = jit(error_norm, error_model="numpy")
_next_step = jit(next_step, error_model="numpy")
_first_trial_step = jit(first_trial_step, error_model="numpy")
_initial_step = jit(initial_step, error_model="numpy")


@jit(error_model="numpy")
def _size(P: Any) -> int:  # pragma: no cover - compiled
    """The run's own state size ``10 + k`` (``k = P[20]`` wheels)."""
    return 10 + int(P[20])


def _sized_source() -> str:
    """The sources of size :data:`N`: the state from an array and with a new quaternion, the
    parameters with a new command, the right-hand side and the steps."""
    return "\n".join([
        f"def tuple_of(a):\n    return ({''.join(f'a[{i}], ' for i in range(N))})\n",
        f"def store(y, out):\n{''.join(f'    out[{i}] = y[{i}]' + chr(10) for i in range(N))}",
        f"def with_quaternion(y, x, yq, z, c):\n    return (x, yq, z, c, {''.join(f'y[{i}], ' for i in range(4, N))})\n",
        f"def axpy(y, a, f):\n    return ({''.join(f'y[{i}] + a * f[{i}], ' for i in range(N))})\n",
        rhs_source("rhs", MAX_WHEELS),
        dop853_sources(LAYOUT, step="dop853_step", errors="dop853_errors", atol="atol", dense=False),
        fixed_step_source("rk4_step", RK4_A, RK4_B, RK4_C, LAYOUT),
        fixed_step_source("rk8_step", DOP853_A[:12, :12], DOP853_B, DOP853_C[:12], LAYOUT),
        rotations_source("rk4_turns", RK4_C), rotations_source("rk8_turns", DOP853_C[:12]),
        rotations_source("dop853_turns", DOP853_C[:13]),
        dop853_accept_source(LAYOUT, "dop853_accept", "_size(P)")])


def _generated() -> dict[str, Callable[..., Any]]:
    """The sized sources compiled, by name: the small ones inlined by numba where they are called;
    the steps, and the right-hand side that each stage calls, compiled as functions of their own.
    Unlike the engine's (:func:`tumble.dynamics.engine.kernels._generated`), this right-hand side
    is not inlined at the stages: inlined, the loop compiled in 78 CPU-s and ran ~15 % faster;
    called, 17 CPU-s (MRP feedback with three wheels, 60 s: DOP853 783 -> 915 us, RK8 452 -> 504 us;
    measured on a loaded machine). What a call costs is its arguments: with the tables passed as a
    tuple of three arrays beside ``P`` the RK8 loop took 204 us, with one array 117 us, as fast as
    inlined (loop_terms' docstring). The right-hand side and the steps are compiled without numba's
    reference counting (``_nrt=False``): they make no array and return none, and each counted
    array argument cost two atomic operations a call. The steps have no wrapper for Python (only
    the loop calls them; the first closed loop's compile 14.6 -> 13.6 CPU-s, measured). The code
    object is named after this file, so numba's cache keys them on the sources (:func:`tumble.jit.jit`)."""
    namespace: dict[str, Any] = dict(rhs_namespace(), np=np, OK=OK, STEP_COLLAPSED=STEP_COLLAPSED, BUDGET_SPENT=BUDGET_SPENT,
                                     _error_norm=_error_norm, _next_step=_next_step, _size=_size)
    exec(compile(_sized_source(), __file__, "exec"), namespace)  # noqa: S102 - our own generated source
    inlined = ("tuple_of", "store", "with_quaternion", "axpy", "rk4_turns", "rk8_turns", "dop853_turns")
    for name in (*inlined, "rhs", "dop853_step", "dop853_errors", "rk4_step", "rk8_step"):  # the steps call them by name
        namespace[name] = jit(namespace[name], error_model="numpy", inline="always" if name in inlined else "never",
                              _nrt=False, no_cpython_wrapper=name not in ("rhs", *inlined))
    # DOP853's step control, the engine's one writing, copied into the hold interval by numba as the engine's
    # kernel takes it (engine.kernels._dop853_accept: as a function of its own, inlined by LLVM, the engine's
    # first dop853 compile took ~3 CPU-s longer)
    namespace["dop853_accept"] = jit(namespace["dop853_accept"], error_model="numpy", inline="always",
                                     no_cpython_wrapper=True)
    return namespace


_SIZED = _generated()
rhs, tuple_of, store, axpy = _SIZED["rhs"], _SIZED["tuple_of"], _SIZED["store"], _SIZED["axpy"]
with_quaternion = _SIZED["with_quaternion"]
dop853_step, dop853_errors, rk4_step, rk8_step = (_SIZED["dop853_step"], _SIZED["dop853_errors"], _SIZED["rk4_step"],
                                                  _SIZED["rk8_step"])
rk4_turns, rk8_turns, dop853_turns = _SIZED["rk4_turns"], _SIZED["rk8_turns"], _SIZED["dop853_turns"]
dop853_accept = _SIZED["dop853_accept"]


@jit(error_model="numpy")
def set_command(P: FloatArray, d0: float, d1: float, d2: float, u: FloatArray) -> None:  # pragma: no cover - compiled
    """Hold the dipole ``d`` (A m^2) and the wheels' commands ``u`` (N m, :data:`MAX_WHEELS`) in the
    kernels' parameter array ``P`` (:mod:`~tumble.dynamics.control.loop_terms`), in place.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.compiled_loop import MAX_WHEELS, TABLES, set_command
    >>> P = np.zeros(TABLES)
    >>> set_command(P, 0.1, 0.2, 0.3, np.arange(1.0, MAX_WHEELS + 1))
    >>> P[12:15].tolist(), P[[42, 52]].tolist()   # the first two wheels' slots end at 42 and 52
    ([0.1, 0.2, 0.3], [1.0, 2.0])
    """
    P[12], P[13], P[14] = d0, d1, d2
    for j in range(MAX_WHEELS):
        P[BODY + WHEEL * j + 9] = u[j]


@jit(error_model="numpy")
def _slot(i: int, k: int) -> int:  # pragma: no cover - compiled
    """The slot of the ``i``-th of a run's ``10 + k`` components in the padded state."""
    return i if i < 7 + k else i + MAX_WHEELS - k


@jit(error_model="numpy")
def _start(y: Any, f: Any, t0: float, t1: float, P: Any, rtol: float, atol: float) -> float:  # pragma: no cover
    """scipy's ``select_initial_step`` for an error estimator of order 7 (HNW sec. II.4), over the
    run's own ``10 + k`` components."""
    k = int(P[20])
    n = 10 + k
    ya, fa, scale = np.empty(n), np.empty(n), np.empty(n)
    for i in range(n):
        j = _slot(i, k)
        ya[i], fa[i] = y[j], f[j]
        scale[i] = atol + abs(y[j]) * rtol
    interval = abs(t1 - t0)
    d1 = _rms(fa, scale)
    h0 = _first_trial_step(_rms(ya, scale), d1, interval)
    u0, u1 = _direction(P[16], t0 + h0)
    f1 = rhs(t0 + h0, axpy(y, h0, f), P, u0, u1)
    for i in range(n):
        fa[i] = f1[_slot(i, k)] - fa[i]
    return _initial_step(h0, d1, _rms(fa, scale) / h0, interval)


@jit(error_model="numpy", inline="always")
def _put(R: FloatArray, at: int, values: Any) -> None:  # pragma: no cover - compiled
    """``R[at:at + len(values)] = values`` for a tuple of floats."""
    for j in range(len(values)):
        R[at + j] = values[j]


#: Where each method's turns start in the array of :func:`_turns` (RK8's and RK4's after the two steps
#: they were made for, DOP853's after its own, as its step control takes them,
#: :func:`~tumble.dynamics.engine.unrolled.dop853_accept_source`), two floats a stage node: RK8's 12,
#: RK4's 4, DOP853's 13; and the array's length.
_RK8_AT = 2
_RK4_AT = _RK8_AT + 2 * len(DOP853_C[:12])
_DOP853_AT = _RK4_AT + 2 * len(RK4_C) + 1
_TURNS = _DOP853_AT + 2 * len(DOP853_C[:13])


@jit(error_model="numpy")
def _turns() -> FloatArray:  # pragma: no cover - compiled
    """Room for the turns of a circular orbit's direction to the stage nodes of each method, kept
    from step to step while the step ``h`` (s) stays the same (the fixed steps of equal intervals):
    the steps ``h`` of RK8 and RK4 they were made for (NaN: none yet, so the first step makes them),
    their turns (from ``_RK8_AT``, ``_RK4_AT``), DOP853's step and turns (from ``_DOP853_AT - 1``). An
    array the steps read in place, not tuples passed to and returned from each interval (a third of
    an interval's call cost)."""
    R = np.empty(_TURNS)
    R[0], R[1], R[_DOP853_AT - 1] = math.nan, math.nan, math.nan
    return R


def method_flags(method: int) -> tuple[int | None, int | None, int | None]:
    """The hold interval's ``method`` (:data:`DOP853`, :data:`RK8`, :data:`RK4`) as the kernels take
    it: ``(dop853, rk8, rk4)``, 1 for the method that runs and None for the other two. numba compiles
    a kernel once for each kind of these arguments and drops, before it types them, the branches
    that ask ``x is not None`` of an ``x`` given as None: a run compiles its own method's steps, not
    the others' (measured in a fresh process with no cache: a first run along an ellipse with
    ``rk8`` 16.0 -> 8.0 s, a first closed loop with ``dop853``, MRP feedback and three wheels,
    12.1 -> 9.0 s). numba decides ``x is not None`` only for an ``x`` typed None, so each method's
    branch asks it of its own argument.

    Examples
    --------
    >>> from tumble.dynamics.control.compiled_loop import DOP853, RK4, RK8, method_flags
    >>> method_flags(DOP853), method_flags(RK8), method_flags(RK4)
    ((1, None, None), (None, 1, None), (None, None, 1))
    >>> method_flags(3)
    Traceback (most recent call last):
    ...
    ValueError: method = 3 is not a hold interval's method; allowed: DOP853 (0), RK4 (1), RK8 (2)
    """
    if method not in (DOP853, RK4, RK8):  # all None would run no method and report a collapsed step
        raise ValueError(f"method = {method!r} is not a hold interval's method; allowed: DOP853 ({DOP853}), "
                         f"RK4 ({RK4}), RK8 ({RK8})")
    return (1 if method == DOP853 else None), (1 if method == RK8 else None), (1 if method == RK4 else None)


@jit(error_model="numpy")
def _fixed_steps(y: Any, t0: float, t1: float, P: Any, step: float, R: FloatArray, rk8: Any,
                 rk4: Any) -> Any:  # pragma: no cover - compiled
    """RK8 (``rk8`` given, ``rk4`` None) or RK4 (the other way) from ``t0`` to ``t1`` (s) at equal steps
    no longer than ``step``: the state at ``t1``; ``R`` the turns to the stage nodes (:func:`_turns`)."""
    n = P[16]
    m, h = equal_steps(t1 - t0, step)
    if rk8 is not None:
        if h != R[0]:
            R[0] = h
            _put(R, _RK8_AT, rk8_turns(n, h))
        for j in range(m):
            cs, ss = _direction(n, t0 + j * h)
            y = rk8_step(t0 + j * h, y, h, P, cs, ss, R[_RK8_AT:_RK4_AT])
    if rk4 is not None:
        if h != R[1]:
            R[1] = h
            _put(R, _RK4_AT, rk4_turns(n, h))
        for j in range(m):
            cs, ss = _direction(n, t0 + j * h)
            y = rk4_step(t0 + j * h, y, h, P, cs, ss, R[_RK4_AT:_DOP853_AT])
    return y


@jit(error_model="numpy")
def _advance(y: Any, t0: float, t1: float, P: Any, rtol: float, atol: float, dop853: Any, rk8: Any, rk4: Any,
             step: float, h_abs: float, R: FloatArray) -> Any:  # pragma: no cover - compiled
    """One hold interval from ``t0`` to ``t1`` (s) (module docstring): ``(status, y, h_abs)`` with
    the step DOP853's error control proposes next (``h_abs <= 0``: choose the first, as scipy);
    ``(dop853, rk8, rk4)`` the method (:func:`method_flags`); ``R`` the turns to the stage nodes
    (:func:`_turns`), updated in place."""
    if rk8 is not None:
        return OK, _fixed_steps(y, t0, t1, P, step, R, rk8, None), h_abs
    if rk4 is not None:
        return OK, _fixed_steps(y, t0, t1, P, step, R, None, rk4), h_abs
    if dop853 is None:  # not reached (method_flags gives one method); the guard that keeps the
        return STEP_COLLAPSED, y, h_abs  # DOP853 steps below out of a fixed-step run's compile
    n = P[16]
    cs, ss = _direction(n, t0)
    f = rhs(t0, y, P, cs, ss)
    if h_abs <= 0.0:
        h_abs = _start(y, f, t0, t1, P, rtol, atol)
    t = t0
    while True:  # one accepted step (the engine's step control), until the interval's end
        status, t, y, K, h_abs, _ = dop853_accept(t, y, f, h_abs, t1, rtol, atol, P, cs, ss, n, R[_DOP853_AT - 1:], 0,
                                                  math.inf)
        if status != OK:
            return status, y, h_abs
        f = K[12]
        cs, ss = _direction(n, t)
        if t - t1 >= 0.0:
            return OK, y, h_abs


@jit(error_model="numpy")
def _interval(y0: FloatArray, t0: float, t1: float, P0: FloatArray, dipole: FloatArray, command: FloatArray, rtol: float,
              atol: float, dop853: Any, rk8: Any, rk4: Any, step: float, out: FloatArray) -> int:  # pragma: no cover - compiled
    """One hold interval of ``y0`` (an array of :data:`N`, :func:`padded`) with the dipole and the
    wheels' commands held (:data:`MAX_WHEELS` of them, the run's first), into ``out``; ``(dop853,
    rk8, rk4)`` the method (:func:`method_flags`)."""
    P = P0.copy()
    set_command(P, dipole[0], dipole[1], dipole[2], command)
    status, y, _ = _advance(tuple_of(y0), t0, t1, P, rtol, atol, dop853, rk8, rk4, step, 0.0, _turns())
    store(y, out)
    return int(status)


@jit(error_model="numpy")
def _loop(y0: FloatArray, grid: FloatArray, P0: FloatArray, law: Any, L: FloatArray, pinv: FloatArray, rods: FloatArray,
          limits: FloatArray, rtol: float, atol: float, dop853: Any, rk8: Any, rk4: Any, step: float, carry: bool,
          Y: FloatArray, D: FloatArray, U: FloatArray, F: FloatArray, REF: FloatArray) -> int:  # pragma: no cover - compiled
    """The closed loop over the control instants ``grid`` (s) from ``y0``: at each, the state (its
    quaternion normalised) into ``Y``, the ideal measurement, the law's command (``L`` its
    parameters, ``pinv`` the wheels' allocation ``G^+``), the dipole the rods (``rods`` their axes,
    ``limits`` theirs, A m^2) make into ``D``, the wheels' applied torque into ``U``, the field
    (T, body frame) into ``F``; then the hold interval. ``y0`` and ``Y``'s rows are padded states
    (:func:`padded`); ``REF`` a moving reference's rows at ``grid`` (:func:`~tumble.dynamics.control.loop_laws.law_command`); ``(dop853, rk8,
    rk4)`` the method (:func:`method_flags`); ``law`` None: no law (a free run, whose kernel then
    compiles none, as :func:`method_flags` says). Returns a status."""
    k = pinv.shape[0]
    steps = grid.shape[0] - 1
    y = tuple_of(y0)
    u = np.zeros(MAX_WHEELS)
    h_abs = 0.0
    turns = _turns()
    memory = NO_MEMORY
    P = P0.copy()  # the parameters with the command held (set_command)
    fp, ft, _ = tables(P0, TABLES)
    for i in range(steps + 1):
        t = grid[i]
        nq = math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3])
        y = with_quaternion(y, y[0] / nq, y[1] / nq, y[2] / nq, y[3] / nq)
        store(y, Y[i])
        x, yq, z, c, w0, w1, w2 = y[0], y[1], y[2], y[3], y[4], y[5], y[6]
        kind = int(P0[15])
        b0, b1, b2 = field_body(kind, fp, ft, x, yq, z, c, t) if kind != FIELD_NONE else (0.0, 0.0, 0.0)
        F[i, 0], F[i, 1], F[i, 2] = b0, b1, b2
        m0, m1, m2 = 0.0, 0.0, 0.0
        for j in range(k):
            u[j] = 0.0
        if law is not None and i < steps:
            m0, m1, m2, memory = law_command(law, L, pinv, P0, y, t, x, yq, z, c, w0, w1, w2, b0, b1, b2,
                                             kind != FIELD_NONE, memory, u, REF, i)
        d0, d1, d2 = held(rods, limits, m0, m1, m2, u, y, P0, D[i], U[i])
        if i == steps:
            break
        set_command(P, d0, d1, d2, u)
        status, y, h_abs = _advance(y, t, grid[i + 1], P, rtol, atol, dop853, rk8, rk4, step, h_abs if carry else 0.0, turns)
        if status != OK:
            return int(status)
    return OK


def padded(y: FloatArray) -> FloatArray:
    """The padded state of :data:`N` floats of the state ``(q, omega, s, impulse)`` of ``k`` wheels:
    the empty wheel slots between the spins and the impulse.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.compiled_loop import padded, unpadded
    >>> y = np.arange(13.0)   # three wheels
    >>> padded(y)[7:]
    array([ 7.,  8.,  9.,  0.,  0.,  0., 10., 11., 12.])
    >>> np.array_equal(unpadded(padded(y), 3), y)
    True
    """
    y = np.asarray(y, dtype=float)
    k = y.shape[-1] - 10
    out = np.zeros((*y.shape[:-1], N))
    out[..., :7 + k], out[..., N - 3:] = y[..., :7 + k], y[..., 7 + k:]
    return out


def unpadded(y: FloatArray, k: int) -> FloatArray:
    """The state ``(q, omega, s, impulse)`` of ``k`` wheels from a padded one (:func:`padded`).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.compiled_loop import N, unpadded
    >>> unpadded(np.arange(float(N)), 0)
    array([ 0.,  1.,  2.,  3.,  4.,  5.,  6., 13., 14., 15.])
    """
    return np.concatenate([y[..., :7 + k], y[..., N - 3:]], axis=-1)


def rhs_of(t: float, y: tuple[float, ...], P: Any, X: tuple[FloatArray, ...], u0: float,
           u1: float) -> tuple[float, ...]:
    """The compiled right-hand side at ``t`` (s) of the padded state ``y`` (a tuple of :data:`N`),
    the parameters ``P`` (:data:`TABLES` floats, :mod:`~tumble.dynamics.control.loop_terms`) and the
    tables ``X`` given apart, ``(u0, u1)`` a circular orbit's direction: ``dy/dt`` as a tuple.

    Examples
    --------
    A spin of 0.1 rad/s about z, no torque: ``q' = (0, 0, 0.05, 0)`` at the identity:

    >>> import numpy as np
    >>> from tumble.dynamics.control.compiled_loop import TABLES, padded, rhs_of, unpadded
    >>> P = np.zeros(TABLES)
    >>> P[:12] = (1.0, 2.0, 3.0, 1.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 1 / 3)
    >>> X = (np.zeros(16), np.zeros((4, 1, 3)), np.zeros((4, 1, 3)))
    >>> y = tuple(padded([0, 0, 0, 1.0, 0, 0, 0.1, 0, 0, 0]))
    >>> unpadded(np.array(rhs_of(0.0, y, P, X, 1.0, 0.0)), 0)[:4].tolist()
    [0.0, 0.0, 0.05, -0.0]
    """
    return rhs(float(t), y, packed(P, X), float(u0), float(u1))  # type: ignore[no-any-return]


_KERNELS: dict[str, Callable[..., Any]] = {"rhs": rhs_of, "_interval": _interval, "_loop": _loop}


def kernels() -> dict[str, Callable[..., Any]]:
    """The compiled kernels, for every wheel count up to :data:`MAX_WHEELS`: ``"rhs"``
    (:func:`rhs_of`), ``"_interval"`` (one hold interval) and ``"_loop"`` (the whole loop), on
    padded states (:func:`padded`) and the parameters and tables in one array
    (:func:`~tumble.dynamics.control.loop_terms.packed`).

    Examples
    --------
    A spin about a principal axis, no wheels, no torque: one interval of 10 s turns the body by
    ``0.1 t`` about z:

    >>> import numpy as np
    >>> from tumble.dynamics.control.compiled_loop import DOP853, N, TABLES, kernels, method_flags, padded, unpadded
    >>> from tumble.dynamics.control.loop_terms import packed
    >>> P = np.zeros(TABLES)
    >>> P[:12] = (1.0, 2.0, 3.0, 1.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 1 / 3)
    >>> P = packed(P, (np.zeros(16), np.zeros((4, 1, 3)), np.zeros((4, 1, 3))))
    >>> y, out = padded([0, 0, 0, 1.0, 0, 0, 0.1, 0, 0, 0]), np.empty(N)
    >>> kernels()["_interval"](y, 0.0, 10.0, P, np.zeros(3), np.zeros(6), 1e-10, 1e-12, *method_flags(DOP853), 0.0, out)
    0
    >>> np.allclose(unpadded(out, 0)[:4], [0.0, 0.0, np.sin(0.5), np.cos(0.5)], rtol=0, atol=1e-10)
    True
    """
    return _KERNELS
