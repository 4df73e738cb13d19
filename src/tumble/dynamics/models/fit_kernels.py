"""The fits' compiled integrations: a body under per-axis drag, and a gyrostat with a measured rotor.

Imported only when one is asked for (by :func:`tumble.dynamics.models.drag.drag_omega` and
:func:`tumble.dynamics.models.gyrostat.gyrostat_omega`, which say what they integrate and why by
hand); compiled at import by :func:`tumble.jit.jit` (``cache=True``: once per machine and
version of the sources), as the engine's kernels are: nothing is compiled, and numba not even
imported, until a fit needs it. The formulas are the models' own functions compiled here: the
drag law :func:`~tumble.dynamics.models.aero.drag_component`, Euler's equations
:func:`~tumble.dynamics.euler.euler_components` and their momentum form
:func:`~tumble.dynamics.euler.momentum_rate_components`.

Both integrate with the classical fourth-order Runge-Kutta method (Hairer, Norsett & Wanner,
*Solving ODEs I*, sec. II.1), the step count depending only on the times, so the result is a
smooth function of the parameters (a fit's finite differences are clean). The steps are the
engine's, written out by its generator from the tableau
(:func:`~tumble.dynamics.engine.unrolled.fixed_step_source`), and the dragged body's run is the
engine's fixed-step loop (:func:`~tumble.dynamics.engine.unrolled.fixed_loop_source`), as the
damped body's is (:mod:`tumble.dynamics.engine.damped`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, cast

import numpy as np

from ...jit import jit
from ...typing import FloatArray
from ..engine.kernels import _direction, _finite, generated
from ..engine.status import NON_FINITE, OK
from ..engine.stepsize import equal_steps
from ..engine.tableau import RK4_A, RK4_B, RK4_C
from ..engine.unrolled import Layout, fixed_loop_source, fixed_step_source, rotations_source, state_layout
from ..euler import euler_components, momentum_rate_components
from .aero import drag_component

__all__ = ["drag_integrate", "gyrostat_integrate"]

_drag = jit(error_model="numpy")(drag_component)
# inlined by numba, not compiled standalone: numba keeps one cache index per Python function, and
# the B-dot batch's module compiles Euler's equations standalone too; where its entry was written
# first, the drag step loaded it and compiled with other fused multiply-adds, and the fits' rates
# (and the flights the finder takes) differed in their last bits by the cache's history
# (tests/test_jit_cache.py)
_euler = jit(error_model="numpy", inline="always")(euler_components)

#: The dragged body's layout: ``rhs(w, B, D, u0, u1)`` over omega's three floats, ``B`` the body's
#: tuple ``(I, 1 / I)``, ``D`` the drag's ``(a, b)`` (:func:`drag_rhs`).
DRAG = Layout(3, "I, P", False)


@jit(error_model="numpy", forceinline=True)  # inlined by LLVM at the stages, as the engine's rhs
def drag_rhs(w: tuple[float, ...], B: tuple[float, ...], D: tuple[float, ...], u0: float,
             u1: float) -> tuple[float, float, float]:  # pragma: no cover - compiled
    """``w'`` (rad/s^2) of a body ``B = (I1, I2, I3, 1/I1, 1/I2, 1/I3)`` (kg m^2, 1/(kg m^2)) under the
    drag ``D = (a1, a2, a3, b1, b2, b3)`` (N m s, N m s^2): Euler's equations
    (:func:`~tumble.dynamics.euler.euler_components`) with the drag law
    (:func:`~tumble.dynamics.models.aero.drag_component`) as the torque. ``u0``, ``u1`` unused (no orbit)."""
    return _euler(w[0], w[1], w[2], B[0], B[1], B[2], _drag(D[0], D[3], w[0]), _drag(D[1], D[4], w[1]),
                  _drag(D[2], D[5], w[2]), B[3], B[4], B[5])


@jit(error_model="numpy")
def _load(w0: FloatArray, I: FloatArray) -> tuple[tuple[float, ...], tuple[float, ...]]:  # pragma: no cover
    """The state tuple of ``w0`` and the body's tuple of ``I`` (:func:`drag_rhs`)."""
    return (w0[0], w0[1], w0[2]), (I[0], I[1], I[2], 1.0 / I[0], 1.0 / I[1], 1.0 / I[2])


@jit(error_model="numpy")
def _sample(w: tuple[float, ...], I: FloatArray, W: FloatArray, k: int) -> None:  # pragma: no cover
    """omega at sample ``k`` into ``W`` (len(t_eval), 3)."""
    W[k, 0], W[k, 1], W[k, 2] = w[0], w[1], w[2]


_DRAG_STEPS = generated(fixed_step_source("drag_rk4_step", RK4_A, RK4_B, RK4_C, DRAG)
                        + rotations_source("drag_rk4_turns", RK4_C), __file__, __name__, inner=True,
                        rhs=drag_rhs)
#: The dragged body's fixed-step RK4 run (:func:`~tumble.dynamics.engine.unrolled.fixed_loop_source`):
#: ``run(w0, t_eval, I, D, n, step, W)``, omega at the samples into ``W`` (len(t_eval), 3).
fixed_drag_rk4 = generated(fixed_loop_source("fixed_drag_rk4", "drag_rk4_step", "drag_rk4_turns", "_load", "_sample", "W"),
                           __file__, __name__, _load=_load, _sample=_sample, _equal_steps=equal_steps,
                           _direction=_direction, _finite=_finite, OK=OK, NON_FINITE=NON_FINITE,
                           **_DRAG_STEPS)["fixed_drag_rk4"]


@jit()
def drag_integrate(I: FloatArray, w0: FloatArray, lin: FloatArray, quad: FloatArray, tau: FloatArray,
                   hmax: FloatArray) -> FloatArray:  # pragma: no cover - compiled
    """The angular velocity (K, T, 3) of :func:`~tumble.dynamics.models.drag.drag_omega` (checked,
    contiguous inputs): each body ``b`` from ``w0[b]`` at t = 0 to its times ``tau[b]``, forward
    and backward, by the engine's fixed-step RK4 run (:data:`fixed_drag_rk4`):
    ``ceil(|dt| / hmax[b])`` equal steps between consecutive times.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.fit_kernels import drag_integrate
    >>> w = drag_integrate(np.array([[1.0, 2.0, 3.0]]), np.array([[0.0, 0.0, 2.0]]), np.zeros((1, 3)),
    ...                    np.array([[0.0, 0.0, 1.5]]), np.array([[-1.0, 0.0, 1.0]]), np.array([0.01]))
    >>> bool(np.isclose(w[0, 2, 2], 2.0 / (1.0 + 1.5 * 2.0 / 3.0)))   # w' = -(b/I) w^2
    True
    """
    K, T = tau.shape
    out = np.empty((K, T, 3))
    times = np.empty(T + 1)
    W = np.empty((T + 1, 3))
    for b in range(K):
        D = (lin[b, 0], lin[b, 1], lin[b, 2], quad[b, 0], quad[b, 1], quad[b, 2])
        j0 = 0
        while j0 < T and tau[b, j0] < 0.0:
            j0 += 1
        # forward from t = 0 through tau[b, j0:], then backward through tau[b, j0 - 1::-1]
        # (a run that overflows stops, its later samples left NaN: backward in time, quadratic drag
        # grows the spin without bound in a finite time)
        times[0] = 0.0
        for j in range(j0, T):
            times[1 + j - j0] = tau[b, j]
        W[:] = np.nan
        fixed_drag_rk4(w0[b], times[:1 + T - j0], I[b], D, 0.0, hmax[b], W)
        for j in range(j0, T):  # rows element by element: an array's assignment compiles numba's
            for i in range(3):  # broadcast checks and their messages (~0.8 s of a first fit)
                out[b, j, i] = W[1 + j - j0, i]
        for j in range(j0):
            times[1 + j] = tau[b, j0 - 1 - j]
        W[:] = np.nan
        fixed_drag_rk4(w0[b], times[:1 + j0], I[b], D, 0.0, hmax[b], W)
        for j in range(j0):
            for i in range(3):
                out[b, j0 - 1 - j, i] = W[1 + j, i]
    return out


def _gyrostat_rhs(t: float, L: Any, P: Any, X: Any, u0: float, u1: float) -> Any:  # pragma: no cover - compiled
    """``L' = L x w + tau`` with ``w = I^-1 (L - h)``, the quadratic drag and ``k g``: the right-hand
    side the engine's generated RK4 step calls (:func:`gyrostat_integrate`). ``P``, 33 floats: the
    interval's ends (s, computed as the step computes its nodes: they tell the stages apart),
    ``k``, ``I^-1`` (9, row by row), ``b`` (3), then ``h`` and ``g`` at the start, the middle and
    the end of the interval (3 each). ``X``, ``u0`` and ``u1`` unused."""
    if t == P[0]:
        h0, h1, h2, g0, g1, g2 = P[15], P[16], P[17], P[24], P[25], P[26]
    elif t == P[1]:
        h0, h1, h2, g0, g1, g2 = P[21], P[22], P[23], P[30], P[31], P[32]
    else:
        h0, h1, h2, g0, g1, g2 = P[18], P[19], P[20], P[27], P[28], P[29]
    a0, a1, a2 = L[0] - h0, L[1] - h1, L[2] - h2
    w0 = P[3] * a0 + P[4] * a1 + P[5] * a2
    w1 = P[6] * a0 + P[7] * a1 + P[8] * a2
    w2 = P[9] * a0 + P[10] * a1 + P[11] * a2
    d0, d1, d2 = momentum_rate_components(L[0], L[1], L[2], w0, w1, w2, _drag(0.0, P[12], w0), _drag(0.0, P[13], w1),
                                _drag(0.0, P[14], w2))
    return d0 + P[2] * g0, d1 + P[2] * g1, d2 + P[2] * g2


def _gyrostat_step() -> Callable[..., Any]:
    """The classical RK4 step over the momentum's three floats, written out by the engine's generator
    from its tableau (:func:`~tumble.dynamics.engine.unrolled.fixed_step_source`), compiled with
    :func:`_gyrostat_rhs` inlined at its stages. The code object is named after this file, so numba's
    cache keys it on the sources."""
    namespace: dict[str, Any] = {"rhs": jit(_gyrostat_rhs, inline="always"), "__name__": __name__}
    exec(compile(fixed_step_source("rk4_step", RK4_A, RK4_B, RK4_C, state_layout(3)), __file__, "exec"),  # noqa: S102
         namespace)
    return cast("Callable[..., Any]", jit(namespace["rk4_step"]))


_rk4_gyrostat = _gyrostat_step()
#: The step's turns of an orbit's direction: none here.
_NO_TURNS = (1.0, 0.0) * 4


@jit()
def gyrostat_integrate(Iinv: FloatArray, L0: FloatArray, quad: FloatArray, t: FloatArray, h: FloatArray,
                       hmid: FloatArray, g: FloatArray, gmid: FloatArray, scale: FloatArray) -> FloatArray:  # pragma: no cover
    """The angular velocity (K, T, 3) of :func:`~tumble.dynamics.models.gyrostat.gyrostat_omega`
    (checked, contiguous inputs; ``Iinv`` the inverse tensors): one step of the engine's RK4 per
    sample interval (:func:`_gyrostat_rhs`).

    Examples
    --------
    A steady torque along z on a body at rest: ``L_z = k g t``.

    >>> import numpy as np
    >>> from tumble.dynamics.models.fit_kernels import gyrostat_integrate
    >>> t, z = np.linspace(0.0, 1.0, 11), np.zeros((11, 3))
    >>> g = np.tile([0.0, 0.0, 1.0], (11, 1))
    >>> w = gyrostat_integrate(np.eye(3)[None], np.zeros((1, 3)), np.zeros((1, 3)), t, z, z[:-1], g, g[:-1],
    ...                        np.array([0.5]))
    >>> bool(np.allclose(w[0, :, 2], 0.5 * t, atol=1e-14))
    True
    """
    K = Iinv.shape[0]
    T = t.shape[0]
    out = np.empty((K, T, 3))
    for b in range(K):
        L = (L0[b, 0], L0[b, 1], L0[b, 2])
        A, q = Iinv[b], quad[b]
        for j in range(T):
            if j > 0:
                dt = t[j] - t[j - 1]
                s, m, e = j - 1, j - 1, j  # h and g at the interval's start, middle and end
                P = (t[j - 1], t[j - 1] + 1.0 * dt, scale[b], A[0, 0], A[0, 1], A[0, 2], A[1, 0], A[1, 1], A[1, 2],
                     A[2, 0], A[2, 1], A[2, 2], q[0], q[1], q[2], h[s, 0], h[s, 1], h[s, 2], hmid[m, 0], hmid[m, 1],
                     hmid[m, 2], h[e, 0], h[e, 1], h[e, 2], g[s, 0], g[s, 1], g[s, 2], gmid[m, 0], gmid[m, 1],
                     gmid[m, 2], g[e, 0], g[e, 1], g[e, 2])
                L = _rk4_gyrostat(t[j - 1], L, dt, P, (0.0,), 1.0, 0.0, _NO_TURNS)
            for i in range(3):
                out[b, j, i] = (Iinv[b, i, 0] * (L[0] - h[j, 0]) + Iinv[b, i, 1] * (L[1] - h[j, 1])
                                + Iinv[b, i, 2] * (L[2] - h[j, 2]))
    return out
