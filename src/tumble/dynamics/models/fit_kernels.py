"""The fits' compiled integrations: a body under per-axis drag, and a gyrostat with a measured rotor.

Imported only when one is asked for (by :func:`tumble.dynamics.models.drag.drag_omega` and
:func:`tumble.dynamics.models.gyrostat.gyrostat_omega`, which say what they integrate and why by
hand); compiled at import by :func:`tumble.jit.jit` (``cache=True``: once per machine and
version of the sources), as the engine's kernels are: nothing is compiled, and numba not even
imported, until a fit needs it. The formulas are the models' own functions compiled here: the
drag law :func:`~tumble.dynamics.models.aero.drag_component` and the momentum form of Euler's
equation :func:`~tumble.dynamics.euler.momentum_rate_components`.

Both integrate with the classical fourth-order Runge-Kutta method (Hairer, Norsett & Wanner,
*Solving ODEs I*, sec. II.1), the step count depending only on the times, so the result is a
smooth function of the parameters (a fit's finite differences are clean). The gyrostat's step is
the engine's, written out by its generator from the tableau
(:func:`~tumble.dynamics.engine.unrolled.fixed_step_source`). The drag kernel keeps a loop of its
own, and its Euler right-hand side its own order of operations, ``((I2 - I3) w2 w3 + tau) / I1``:
the fits hang on its round-off (tests/test_formulas_once.py says why).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, cast

import numpy as np

from ...jit import jit
from ...typing import FloatArray
from ..engine.tableau import RK4_A, RK4_B, RK4_C
from ..engine.unrolled import fixed_step_source, state_layout
from ..euler import momentum_rate_components
from .aero import drag_component

__all__ = ["drag_integrate", "gyrostat_integrate"]

_drag = jit(inline="always")(drag_component)
_momentum_rate = jit(inline="always")(momentum_rate_components)


@jit()
def _drag_rate(I: FloatArray, lin: FloatArray, quad: FloatArray, w: FloatArray, out: FloatArray) -> None:  # pragma: no cover
    """Euler's equations with the drag torque, ``w'`` into ``out``."""
    out[0] = ((I[1] - I[2]) * w[1] * w[2] + _drag(lin[0], quad[0], w[0])) / I[0]
    out[1] = ((I[2] - I[0]) * w[2] * w[0] + _drag(lin[1], quad[1], w[1])) / I[1]
    out[2] = ((I[0] - I[1]) * w[0] * w[1] + _drag(lin[2], quad[2], w[2])) / I[2]


@jit()
def _drag_advance(I: FloatArray, lin: FloatArray, quad: FloatArray, w: FloatArray, dt: float, n: int, k1: FloatArray,
                  k2: FloatArray, k3: FloatArray, k4: FloatArray, tmp: FloatArray) -> None:  # pragma: no cover
    """``n`` equal RK4 steps over ``dt`` (s), ``w`` advanced in place."""
    h = dt / n
    for _ in range(n):
        _drag_rate(I, lin, quad, w, k1)
        for c in range(3):
            tmp[c] = w[c] + 0.5 * h * k1[c]
        _drag_rate(I, lin, quad, tmp, k2)
        for c in range(3):
            tmp[c] = w[c] + 0.5 * h * k2[c]
        _drag_rate(I, lin, quad, tmp, k3)
        for c in range(3):
            tmp[c] = w[c] + h * k3[c]
        _drag_rate(I, lin, quad, tmp, k4)
        for c in range(3):
            w[c] += h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c])


@jit()
def drag_integrate(I: FloatArray, w0: FloatArray, lin: FloatArray, quad: FloatArray, tau: FloatArray,
                   hmax: FloatArray) -> FloatArray:  # pragma: no cover - compiled
    """The angular velocity (K, T, 3) of :func:`~tumble.dynamics.models.drag.drag_omega` (checked,
    contiguous inputs): each body ``b`` from ``w0[b]`` at t = 0 to its times ``tau[b]``, forward
    and backward, ``ceil(|dt| / hmax[b])`` equal steps between consecutive times.

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
                    _drag_advance(I[b], lin[b], quad[b], w, dt, n, k1, k2, k3, k4, tmp)
                    t = tau[b, j]
                for c in range(3):
                    out[b, j, c] = w[c]
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
    d0, d1, d2 = _momentum_rate(L[0], L[1], L[2], w0, w1, w2, _drag(0.0, P[12], w0), _drag(0.0, P[13], w1),
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
