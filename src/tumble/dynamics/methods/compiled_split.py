"""The compiled kernels of the splittings under the built-in torques: whole runs inside numba.

Imported only on first compiled use (by :func:`tumble.dynamics.methods.compiled.run_split`), so
that ``import tumble`` does not import numba; every function here is compiled at import by
:func:`tumble.jit.jit` (``cache=True``: once per machine and per version of the sources), as
the engine's kernels are (:mod:`tumble.dynamics.engine.kernels`).

The composed splitting is that of :func:`tumble.dynamics.methods.geometric.propagate`
(McLachlan 1993; Yoshida 1990; the torque as two half kicks around the Strang step, Celledoni
et al. 2008, sec. 5), over plain floats; the free part is the Strang step of exact rotations or
the exact free flow (:func:`tumble.dynamics.methods.compiled_flow.free_flow_into`). The built-in
torques, and any sum of them, are the engine's torque terms ``P`` on an orbit of mean motion
``n`` (:func:`~tumble.dynamics.models.torque_protocols.kernel_terms`), evaluated by the engine's own
:func:`~tumble.dynamics.engine.kernels.external_torque` (the constant body and world torques, the
gravity gradient of a circular orbit ``3 n^2 r_b x (I r_b)`` with ``r_b = R^T (cos n t, sin n t,
0)``, Hughes, *Spacecraft Attitude Dynamics*, ch. 8): one writing of each, here and in the engine.

One body's run is :func:`run_body`; :func:`run_serial` and :func:`run_parallel` run it over
the bodies, on one thread or on every core (``numba.prange``): the same arithmetic per body.
"""

from __future__ import annotations

import math

import numpy as np
from numba import prange

from ...jit import jit
from ...typing import FloatArray
from ..engine.kernels import _direction, external_torque
from ..engine.stepsize import equal_steps
from .compiled_flow import WORK, free_flow_into

__all__ = ["kick_torque", "run_body", "run_parallel", "run_serial"]


# The Strang step as (axis, fraction of the step), as in geometric._STRANG.
_AXES = np.array([0, 1, 2, 1, 0], dtype=np.int64)
_FRACTIONS = np.array([0.5, 0.5, 1.0, 0.5, 0.5])


@jit(inline="always")
def kick_torque(body: tuple[float, ...], q: FloatArray, t: float, P: tuple[float, ...], n: float, out: FloatArray) -> None:
    """The torque terms ``P`` on an orbit of mean motion ``n`` (rad/s) at time ``t`` (s), on a body
    ``(I1, I2, I3, 1/I1, 1/I2, 1/I3)`` (kg m^2) at attitude ``q`` (body to world, scalar last): N m,
    principal frame, into ``out`` (:func:`~tumble.dynamics.engine.kernels.external_torque`, the
    engine's). The rotors' slots of ``P`` are 0 here: a splitting carries wheels in its free flow.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_split import kick_torque
    >>> out, q = np.empty(3), np.array([0.0, 0.0, np.sqrt(0.5), np.sqrt(0.5)])   # 90 degrees about z
    >>> P = (0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)   # a world torque along x, N m
    >>> kick_torque((1.0, 1.0, 1.0, 1.0, 1.0, 1.0), q, 0.0, P, 0.0, out)
    >>> np.round(out, 12) + 0.0   # the world's x is the body's -y
    array([ 0., -1.,  0.])
    """
    u0, u1 = _direction(n, t)  # the circular orbit's direction, the engine's
    a0, a1, a2 = external_torque(body, 0.0, 0.0, 0.0, q[0], q[1], q[2], q[3], u0, u1, P)
    out[0], out[1], out[2] = a0, a1, a2


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
             P: tuple[float, ...], n: float, exact: bool, offset: FloatArray, omega_out: FloatArray,
             quat_out: FloatArray) -> None:
    """Body ``b`` through every sample interval: equal steps no longer than ``step``, each the
    Yoshida composition ``gammas`` of the Strang step (or of the exact free flow, ``exact``)
    with half kicks of the torque terms ``P`` (all 0: none). Arguments as :func:`run_serial`.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_split import run_body
    >>> omega, quat = np.empty((2, 1, 3)), np.empty((2, 1, 4))
    >>> run_body(0, np.array([[1.0, 2.0, 3.0]]), np.array([[0.0, 0.0, 3.0]]), np.array([[0.0, 0.0, 0.0, 1.0]]),
    ...          np.array([0.0, 1.0]), 0.1, np.array([1.0]), (0.0,) * 10, 0.0, False, np.zeros((1, 3)), omega, quat)
    >>> omega[1, 0].tolist()   # a spin about a principal axis stays
    [0.0, 0.0, 1.0]
    """
    Ib, L, q, hb = I[b].copy(), L0[b].copy(), q0[b].copy(), offset[b].copy()
    inv_I = 1.0 / Ib
    body = (Ib[0], Ib[1], Ib[2], inv_I[0], inv_I[1], inv_I[2])
    torqued = False
    for i in range(len(P)):
        torqued = torqued or P[i] != 0.0
    kick = np.empty(3)
    work = np.empty(WORK)  # the exact flow's scratch space, once per body
    for i in range(3):
        omega_out[0, b, i] = (L[i] - hb[i]) * inv_I[i]
    for i in range(4):
        quat_out[0, b, i] = q[i]
    for s in range(1, t.shape[0]):
        m, h = equal_steps(t[s] - t[s - 1], step)
        for stepno in range(m):
            tc = t[s - 1] + stepno * h
            for g in range(gammas.shape[0]):
                hg = gammas[g] * h
                if torqued:
                    kick_torque(body, q, tc, P, n, kick)
                    for i in range(3):
                        L[i] += 0.5 * hg * kick[i]
                if exact:  # the exact free flow (exact-flow splitting)
                    free_flow_into(Ib, L, q, hg, work)
                else:  # the Strang step of exact rotations (geometric splitting)
                    for r in range(_AXES.shape[0]):
                        _rotate(L, q, _AXES[r], _FRACTIONS[r] * hg, inv_I, hb)
                tc += hg
                if torqued:
                    kick_torque(body, q, tc, P, n, kick)
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
               P: tuple[float, ...], n: float, exact: bool, offset: FloatArray, omega_out: FloatArray,
               quat_out: FloatArray) -> None:
    """Every body (:func:`run_body`) on one thread: moments ``I`` and momenta ``L0`` (N, 3),
    attitudes ``q0`` (N, 4), samples ``t`` (n,), into ``omega_out`` (n, N, 3) and ``quat_out``
    (n, N, 4); the torque terms ``P`` (10 floats, :mod:`~tumble.dynamics.engine.kernels`) on an orbit of
    mean motion ``n`` (rad/s); the wheels'
    momentum ``offset`` (N, 3).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_split import run_serial
    >>> omega, quat = np.empty((2, 1, 3)), np.empty((2, 1, 4))
    >>> run_serial(np.array([[1.0, 2.0, 3.0]]), np.array([[0.0, 0.0, 3.0]]), np.array([[0.0, 0.0, 0.0, 1.0]]),
    ...            np.array([0.0, np.pi]), 0.1, np.array([1.0]), (0.0,) * 10, 0.0, True, np.zeros((1, 3)), omega, quat)
    >>> np.round(quat[1, 0], 12) + 0.0   # half a turn about the major axis
    array([0., 0., 1., 0.])
    """
    for b in range(I.shape[0]):
        run_body(b, I, L0, q0, t, step, gammas, P, n, exact, offset, omega_out, quat_out)


@jit(parallel=True)
def run_parallel(I: FloatArray, L0: FloatArray, q0: FloatArray, t: FloatArray, step: float, gammas: FloatArray,
                 P: tuple[float, ...], n: float, exact: bool, offset: FloatArray, omega_out: FloatArray,
                 quat_out: FloatArray) -> None:
    """:func:`run_serial` with the bodies spread over every core (``numba.prange``).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_split import run_parallel, run_serial
    >>> I, L = np.array([[1.0, 2.0, 3.0]] * 4), np.array([[0.1, 2.0, 0.3]] * 4)
    >>> q, t, args = np.tile([0.0, 0.0, 0.0, 1.0], (4, 1)), np.linspace(0.0, 1.0, 3), (np.array([1.0]), (0.0,) * 10, 0.0)
    >>> a, b = (np.empty((3, 4, 3)), np.empty((3, 4, 4))), (np.empty((3, 4, 3)), np.empty((3, 4, 4)))
    >>> run_serial(I, L, q, t, 0.1, *args, False, np.zeros((4, 3)), *a)
    >>> run_parallel(I, L, q, t, 0.1, *args, False, np.zeros((4, 3)), *b)
    >>> bool(np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1]))   # the same arithmetic per body
    True
    """
    for b in prange(I.shape[0]):  # prange's index is unsigned: as int64, run_body compiles once
        run_body(np.int64(b), I, L0, q0, t, step, gammas, P, n, exact, offset, omega_out, quat_out)
