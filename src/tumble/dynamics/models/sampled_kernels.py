"""The models' integrations over given sample times, compiled: per-axis drag and the gyrostat
with a measured rotor.

Imported only when one of them runs (:func:`~tumble.dynamics.models.drag.drag_omega`,
:func:`~tumble.dynamics.models.gyrostat.gyrostat_omega`: importing numba costs half a second,
which every ``tumble`` command would pay at start otherwise); every function is compiled at
import by :func:`tumble.jit.jit` (``cache=True``: once per machine and per version of the
sources), as the engine's kernels are (:mod:`tumble.dynamics.engine.kernels`).

The equations are the models' own formulas, compiled here: the momentum form of the gyrostat's
Euler equation (:func:`~tumble.dynamics.models.gyrostat.momentum_rate_components`) and the drag law
(:func:`~tumble.dynamics.models.drag.drag_component`). The drag body's rate keeps its own writing of
Euler's equations, ``((I2 - I3) w2 w3 + tau1) / I1``, until the fits run on the engine: with
:func:`~tumble.dynamics.euler.euler_components` (a reciprocal, an ulp apart) a fit that hangs on
round-off changes (tests/test_formulas_once.py says which). Each integration is the classical
fourth-order Runge-Kutta method (Hairer, Norsett & Wanner, *Solving ODEs I*, 2nd ed., sec. II.1)
on a step count that depends only on the times, so that the result is a smooth function of the
parameters (finite differences of it are clean, as a least-squares fit needs); the models'
docstrings say why a fixed step, and why hand-written (no library integrates many small systems
from compiled code).

Examples
--------
>>> import numpy as np
>>> from tumble.dynamics.models.sampled_kernels import drag_integrate
>>> I, w0 = np.array([[1.0, 2.0, 3.0]]), np.array([[0.0, 0.0, 2.0]])
>>> out = drag_integrate(I, w0, np.zeros((1, 3)), np.array([[0.0, 0.0, 1.5]]), np.array([[0.0, 1.0]]), np.array([0.02]))
>>> bool(np.isclose(out[0, 1, 2], 2.0 / (1.0 + 1.5 * 2.0 / 3.0)))   # w' = -(b/I) w^2
True
"""

from __future__ import annotations

import numpy as np

from ...jit import jit
from ...typing import FloatArray
from .drag import drag_component
from .gyrostat import momentum_rate_components

__all__ = ["drag_integrate", "gyrostat_integrate"]

_drag = jit(drag_component, inline="always")
_momentum_rate = jit(momentum_rate_components, inline="always")


@jit
def _drag_rate(I: FloatArray, r: FloatArray, lin: FloatArray, quad: FloatArray, w: FloatArray,
               out: FloatArray) -> None:  # pragma: no cover - compiled
    """``omega'`` (rad/s^2) of a body of moments ``I`` under per-axis drag (Euler's equations,
    Goldstein eq. 5.39'; ``r`` the reciprocal moments, unused: see the module docstring)."""
    out[0] = ((I[1] - I[2]) * w[1] * w[2] + _drag(lin[0], quad[0], w[0])) / I[0]
    out[1] = ((I[2] - I[0]) * w[2] * w[0] + _drag(lin[1], quad[1], w[1])) / I[1]
    out[2] = ((I[0] - I[1]) * w[0] * w[1] + _drag(lin[2], quad[2], w[2])) / I[2]


@jit
def _drag_advance(I: FloatArray, r: FloatArray, lin: FloatArray, quad: FloatArray, w: FloatArray, dt: float, n: int,
                  k1: FloatArray, k2: FloatArray, k3: FloatArray, k4: FloatArray,
                  tmp: FloatArray) -> None:  # pragma: no cover - compiled
    """``w`` advanced in place over ``dt`` (s) by ``n`` equal RK4 steps."""
    h = dt / n
    for _ in range(n):
        _drag_rate(I, r, lin, quad, w, k1)
        for c in range(3):
            tmp[c] = w[c] + 0.5 * h * k1[c]
        _drag_rate(I, r, lin, quad, tmp, k2)
        for c in range(3):
            tmp[c] = w[c] + 0.5 * h * k2[c]
        _drag_rate(I, r, lin, quad, tmp, k3)
        for c in range(3):
            tmp[c] = w[c] + h * k3[c]
        _drag_rate(I, r, lin, quad, tmp, k4)
        for c in range(3):
            w[c] += h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c])


@jit
def drag_integrate(I: FloatArray, w0: FloatArray, lin: FloatArray, quad: FloatArray, tau: FloatArray,
                   hmax: FloatArray) -> FloatArray:  # pragma: no cover - compiled
    """The angular velocities (rad/s, ``(K, T, 3)``) of ``K`` bodies under per-axis drag
    (:func:`~tumble.dynamics.models.drag.drag_omega`) at their times ``tau`` (K, T), forward from
    ``t = 0`` for ``t >= 0`` and backward for ``t < 0``, with ``ceil(|dt| / hmax)`` equal steps
    between consecutive times."""
    K, T = tau.shape
    out = np.empty((K, T, 3))
    k1, k2, k3, k4, tmp = np.empty(3), np.empty(3), np.empty(3), np.empty(3), np.empty(3)
    w, r = np.empty(3), np.empty(3)
    for b in range(K):
        for c in range(3):
            r[c] = 1.0 / I[b, c]
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
                    _drag_advance(I[b], r, lin[b], quad[b], w, dt, n, k1, k2, k3, k4, tmp)
                    t = tau[b, j]
                for c in range(3):
                    out[b, j, c] = w[c]
    return out


@jit
def _gyrostat_rate(Iinv: FloatArray, quad: FloatArray, L: FloatArray, h: FloatArray, g: FloatArray, k: float,
                   w: FloatArray, out: FloatArray) -> None:  # pragma: no cover - compiled
    """``L'`` (N m) of the gyrostat: ``w = I^-1 (L - h)`` into ``w``, then ``L x w`` and the
    torques (drag and ``k g``)."""
    for i in range(3):
        w[i] = Iinv[i, 0] * (L[0] - h[0]) + Iinv[i, 1] * (L[1] - h[1]) + Iinv[i, 2] * (L[2] - h[2])
    d0, d1, d2 = _momentum_rate(L[0], L[1], L[2], w[0], w[1], w[2], _drag(0.0, quad[0], w[0]),
                                _drag(0.0, quad[1], w[1]), _drag(0.0, quad[2], w[2]))
    out[0], out[1], out[2] = d0 + k * g[0], d1 + k * g[1], d2 + k * g[2]


@jit
def gyrostat_integrate(Iinv: FloatArray, L0: FloatArray, quad: FloatArray, t: FloatArray, h: FloatArray,
                       hmid: FloatArray, g: FloatArray, gmid: FloatArray,
                       scale: FloatArray) -> FloatArray:  # pragma: no cover - compiled
    """The angular velocities (rad/s, ``(K, T, 3)``) of ``K`` gyrostats
    (:func:`~tumble.dynamics.models.gyrostat.gyrostat_omega`) at the times ``t``, one RK4 step
    per interval, the rotor's momentum ``h`` and the torque's profile ``g`` given at the samples
    and the midpoints."""
    K = Iinv.shape[0]
    T = t.shape[0]
    out = np.empty((K, T, 3))
    k1, k2, k3, k4 = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
    L, tmp, w = np.empty(3), np.empty(3), np.empty(3)
    for b in range(K):
        for c in range(3):
            L[c] = L0[b, c]
        k = scale[b]
        for j in range(T):
            if j > 0:
                dt = t[j] - t[j - 1]
                _gyrostat_rate(Iinv[b], quad[b], L, h[j - 1], g[j - 1], k, w, k1)
                for c in range(3):
                    tmp[c] = L[c] + 0.5 * dt * k1[c]
                _gyrostat_rate(Iinv[b], quad[b], tmp, hmid[j - 1], gmid[j - 1], k, w, k2)
                for c in range(3):
                    tmp[c] = L[c] + 0.5 * dt * k2[c]
                _gyrostat_rate(Iinv[b], quad[b], tmp, hmid[j - 1], gmid[j - 1], k, w, k3)
                for c in range(3):
                    tmp[c] = L[c] + dt * k3[c]
                _gyrostat_rate(Iinv[b], quad[b], tmp, h[j], g[j], k, w, k4)
                for c in range(3):
                    L[c] += dt / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c])
            for i in range(3):
                out[b, j, i] = (Iinv[b, i, 0] * (L[0] - h[j, 0]) + Iinv[b, i, 1] * (L[1] - h[j, 1])
                                + Iinv[b, i, 2] * (L[2] - h[j, 2]))
    return out
