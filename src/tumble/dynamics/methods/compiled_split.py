"""The compiled kernels of the splittings under the built-in torques: whole runs inside numba.

Imported only on first compiled use (by :func:`tumble.dynamics.methods.compiled.run_split`), so
that ``import tumble`` does not import numba; every function here is compiled at import by
:func:`tumble.jit.jit` (``cache=True``: once per machine and per version of the sources), as
the engine's kernels are (:mod:`tumble.dynamics.engine.kernels`).

The composed splitting is that of :func:`tumble.dynamics.methods.geometric.propagate`
(McLachlan 1993; Yoshida 1990; the torque as two half kicks around the Strang step, Celledoni
et al. 2008, sec. 5), over plain floats; the free part is the Strang step of exact rotations or
the exact free flow (:func:`tumble.dynamics.methods.compiled_flow.free_flow_into`). The built-in
torques are evaluated inline (:func:`body_torque`): a constant torque in the principal frame or
in the world frame (turned into the body by ``R^T``), and the gravity gradient of a circular
orbit ``3 n^2 r_b x (I r_b)`` with ``r_b = R^T (cos n t, sin n t, 0)`` (Hughes, *Spacecraft
Attitude Dynamics*, ch. 8), each the model's own formula compiled here.

One body's run is :func:`run_body`; :func:`run_serial` and :func:`run_parallel` run it over
the bodies, on one thread or on every core (``numba.prange``): the same arithmetic per body.
"""

from __future__ import annotations

import math

import numpy as np
from numba import prange

from ...jit import jit
from ...typing import FloatArray
from ..engine.stepsize import equal_steps
from ..models.gravity import gradient_components
from ..models.torques import KERNEL_BODY, KERNEL_WORLD
from ..special.quaternion import rotate_components
from .compiled_flow import WORK, free_flow_into

__all__ = ["body_torque", "run_body", "run_parallel", "run_serial"]

_equal_steps = jit(equal_steps, inline="always")
_gravity_gradient = jit(gradient_components, inline="always")
_rotate_vector = jit(rotate_components, inline="always")

# The Strang step as (axis, fraction of the step), as in geometric._STRANG.
_AXES = np.array([0, 1, 2, 1, 0], dtype=np.int64)
_FRACTIONS = np.array([0.5, 0.5, 1.0, 0.5, 0.5])


@jit(inline="always")
def body_torque(kind: int, tau: FloatArray, n: float, I: FloatArray, q: FloatArray, t: float,
                out: FloatArray) -> None:
    """The built-in torque of ``kind`` on one body in its principal frame (N m), into ``out``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_split import body_torque
    >>> from tumble.dynamics.models.torques import KERNEL_WORLD
    >>> out, q = np.empty(3), np.array([0.0, 0.0, np.sqrt(0.5), np.sqrt(0.5)])   # 90 degrees about z
    >>> body_torque(KERNEL_WORLD, np.array([1.0, 0.0, 0.0]), 0.0, np.ones(3), q, 0.0, out)
    >>> np.round(out, 12) + 0.0   # the world's x is the body's -y
    array([ 0., -1.,  0.])
    """
    x, y, z, w = q[0], q[1], q[2], q[3]
    if kind == KERNEL_BODY:
        out[0], out[1], out[2] = tau[0], tau[1], tau[2]
        return
    if kind == KERNEL_WORLD:
        v0, v1, v2 = tau[0], tau[1], tau[2]
    else:
        v0, v1, v2 = math.cos(n * t), math.sin(n * t), 0.0
    # R^T v: v turned by the conjugate quaternion, as the numpy path's body_torque turns it
    b0, b1, b2 = _rotate_vector(-x, -y, -z, w, v0, v1, v2)
    if kind == KERNEL_WORLD:
        out[0], out[1], out[2] = b0, b1, b2
        return
    out[0], out[1], out[2] = _gravity_gradient(n * n, I[0], I[1], I[2], b0, b1, b2)  # 3 n^2 r_b x (I r_b)


@jit(inline="always")
def _rotate(L: FloatArray, q: FloatArray, axis: int, tau: float, inv_I: FloatArray, h: FloatArray) -> None:
    """The exact flow of ``H_axis`` for time ``tau`` (geometric._rotate), in place; ``h`` the
    wheels' constant momentum (body frame), so the rate is ``(L_axis - h_axis) / I_axis``."""
    j, k = (axis + 1) % 3, (axis + 2) % 3
    half = (L[axis] - h[axis]) * (0.5 * tau * inv_I[axis])
    ch, sh = math.cos(half), math.sin(half)
    c, s = 1.0 - 2.0 * sh * sh, 2.0 * sh * ch
    Lj, Lk = L[j], L[k]
    L[j], L[k] = c * Lj + s * Lk, c * Lk - s * Lj
    qa, qj, qk, qw = q[axis], q[j], q[k], q[3]
    q[axis], q[j], q[k], q[3] = ch * qa + sh * qw, ch * qj + sh * qk, ch * qk - sh * qj, ch * qw - sh * qa


@jit
def run_body(b: int | np.int64, I: FloatArray, L0: FloatArray, q0: FloatArray, t: FloatArray, step: float, gammas: FloatArray,
             kind: int, tau: FloatArray, n: float, exact: bool, offset: FloatArray, omega_out: FloatArray,
             quat_out: FloatArray) -> None:
    """Body ``b`` through every sample interval: equal steps no longer than ``step``, each the
    Yoshida composition ``gammas`` of the Strang step (or of the exact free flow, ``exact``)
    with half kicks of the torque ``kind`` (0: none). Arguments as :func:`run_serial`.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_split import run_body
    >>> omega, quat = np.empty((2, 1, 3)), np.empty((2, 1, 4))
    >>> run_body(0, np.array([[1.0, 2.0, 3.0]]), np.array([[0.0, 0.0, 3.0]]), np.array([[0.0, 0.0, 0.0, 1.0]]),
    ...          np.array([0.0, 1.0]), 0.1, np.array([1.0]), 0, np.zeros(3), 0.0, False, np.zeros((1, 3)), omega, quat)
    >>> omega[1, 0].tolist()   # a spin about a principal axis stays
    [0.0, 0.0, 1.0]
    """
    Ib, L, q, hb = I[b].copy(), L0[b].copy(), q0[b].copy(), offset[b].copy()
    inv_I = 1.0 / Ib
    kick = np.empty(3)
    work = np.empty(WORK)  # the exact flow's scratch space, once per body
    for i in range(3):
        omega_out[0, b, i] = (L[i] - hb[i]) * inv_I[i]
    for i in range(4):
        quat_out[0, b, i] = q[i]
    for s in range(1, t.shape[0]):
        m, h = _equal_steps(t[s] - t[s - 1], step)
        for stepno in range(m):
            tc = t[s - 1] + stepno * h
            for g in range(gammas.shape[0]):
                hg = gammas[g] * h
                if kind != 0:
                    body_torque(kind, tau, n, Ib, q, tc, kick)
                    for i in range(3):
                        L[i] += 0.5 * hg * kick[i]
                if exact:  # the exact free flow (exact-flow splitting)
                    free_flow_into(Ib, L, q, hg, work)
                else:  # the Strang step of exact rotations (geometric splitting)
                    for r in range(_AXES.shape[0]):
                        _rotate(L, q, _AXES[r], _FRACTIONS[r] * hg, inv_I, hb)
                tc += hg
                if kind != 0:
                    body_torque(kind, tau, n, Ib, q, tc, kick)
                    for i in range(3):
                        L[i] += 0.5 * hg * kick[i]
        norm = math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
        for i in range(4):
            q[i] /= norm
            quat_out[s, b, i] = q[i]
        for i in range(3):
            omega_out[s, b, i] = (L[i] - hb[i]) * inv_I[i]


@jit
def run_serial(I: FloatArray, L0: FloatArray, q0: FloatArray, t: FloatArray, step: float, gammas: FloatArray,
               kind: int, tau: FloatArray, n: float, exact: bool, offset: FloatArray, omega_out: FloatArray,
               quat_out: FloatArray) -> None:
    """Every body (:func:`run_body`) on one thread: moments ``I`` and momenta ``L0`` (N, 3),
    attitudes ``q0`` (N, 4), samples ``t`` (n,), into ``omega_out`` (n, N, 3) and ``quat_out``
    (n, N, 4); the torque's ``kind`` with its vector ``tau`` and mean motion ``n``; the wheels'
    momentum ``offset`` (N, 3).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_split import run_serial
    >>> omega, quat = np.empty((2, 1, 3)), np.empty((2, 1, 4))
    >>> run_serial(np.array([[1.0, 2.0, 3.0]]), np.array([[0.0, 0.0, 3.0]]), np.array([[0.0, 0.0, 0.0, 1.0]]),
    ...            np.array([0.0, np.pi]), 0.1, np.array([1.0]), 0, np.zeros(3), 0.0, True, np.zeros((1, 3)), omega, quat)
    >>> np.round(quat[1, 0], 12) + 0.0   # half a turn about the major axis
    array([0., 0., 1., 0.])
    """
    for b in range(I.shape[0]):
        run_body(b, I, L0, q0, t, step, gammas, kind, tau, n, exact, offset, omega_out, quat_out)


@jit(parallel=True)
def run_parallel(I: FloatArray, L0: FloatArray, q0: FloatArray, t: FloatArray, step: float, gammas: FloatArray,
                 kind: int, tau: FloatArray, n: float, exact: bool, offset: FloatArray, omega_out: FloatArray,
                 quat_out: FloatArray) -> None:
    """:func:`run_serial` with the bodies spread over every core (``numba.prange``).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_split import run_parallel, run_serial
    >>> I, L = np.array([[1.0, 2.0, 3.0]] * 4), np.array([[0.1, 2.0, 0.3]] * 4)
    >>> q, t, args = np.tile([0.0, 0.0, 0.0, 1.0], (4, 1)), np.linspace(0.0, 1.0, 3), (np.array([1.0]), 0, np.zeros(3))
    >>> a, b = (np.empty((3, 4, 3)), np.empty((3, 4, 4))), (np.empty((3, 4, 3)), np.empty((3, 4, 4)))
    >>> run_serial(I, L, q, t, 0.1, *args, 0.0, False, np.zeros((4, 3)), *a)
    >>> run_parallel(I, L, q, t, 0.1, *args, 0.0, False, np.zeros((4, 3)), *b)
    >>> bool(np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1]))   # the same arithmetic per body
    True
    """
    for b in prange(I.shape[0]):  # prange's index is unsigned: as int64, run_body compiles once
        run_body(np.int64(b), I, L0, q0, t, step, gammas, kind, tau, n, exact, offset, omega_out, quat_out)
