"""The geometric splitting under the built-in torques, compiled: whole runs inside numba.

The same composed splitting as :func:`tumble.dynamics.methods.geometric.propagate` (McLachlan
1993; Yoshida 1990; the torque as two half kicks around the Strang step, Celledoni et al. 2008,
sec. 5; read that module's docstring), written once more over plain floats so that numba
compiles a whole run, every step of every body, with no Python call per step. Why a second
writing: the numpy path calls the torque model once per kick from Python (a user's function
must be called so), which costs ~10 us per kick for one body, 1000 times the kick itself; the
built-in models are known in advance and evaluated here inline:

- ``CONSTANT_BODY``: a constant torque in the principal frame, N m;
- ``CONSTANT_WORLD``: a constant torque in the world frame, turned into the body by ``R^T``
  (the conjugate quaternion, :func:`tumble.dynamics.special.quaternion.rotate_components`, as the
  numpy path's :func:`tumble.dynamics.models.torques.body_torque` turns it);
- ``GRAVITY_GRADIENT``: ``3 n^2 r_b x (I r_b)`` with ``r_b = R^T (cos n t, sin n t, 0)``, the
  circular orbit of :class:`tumble.dynamics.models.gravity.GravityGradient` (Hughes, *Spacecraft
  Attitude Dynamics*, ch. 8).

The compiled and numpy paths agree to round-off (tests/test_compiled.py). A batch of at least
:data:`~tumble.jit.PARALLEL_BODIES` runs its bodies on every core (``numba.prange``); smaller ones on one
thread, since the parallel kernel made the first call of a process 2.3 s against 0.96 s (the
threading layer's start, measured). Each body gets the same arithmetic either way. Compiled on
first use with ``cache=True``, so once per machine: importing numba costs half a
second, which a command that never needs the kernel would pay otherwise.
"""

from __future__ import annotations

import functools
import math
import types
from collections.abc import Callable
from typing import Any, cast

import numpy as np

from ...typing import FloatArray
from ...jit import PARALLEL_BODIES, cores
from ..engine.stepsize import equal_steps as _equal_steps  # _run calls it; compiled in _compiled()
from ..models.gravity import gradient_components as _gravity_gradient  # _body_torque calls it; compiled in _compiled()
from ..models.torques import KERNEL_BODY, KERNEL_CIRCULAR_GRAVITY, KERNEL_NONE, KERNEL_WORLD, kernel_form
from ..special.quaternion import rotate_components as _rotate_vector  # _body_torque calls it; compiled in _compiled()
from .compiled_flow import (  # free_flow_into: _run calls it; compiled in _compiled()
    WORK,
    compiled_free_flow,
    free_flow_into,
)

__all__ = ["CONSTANT_BODY", "CONSTANT_WORLD", "GRAVITY_GRADIENT", "compiled_model", "run_split"]

#: Kinds of built-in torque the kernel evaluates itself.
#: (the models' own kinds, :class:`~tumble.dynamics.models.torques.KernelForm`)
CONSTANT_BODY, CONSTANT_WORLD, GRAVITY_GRADIENT = KERNEL_BODY, KERNEL_WORLD, KERNEL_CIRCULAR_GRAVITY

# The Strang step as (axis, fraction of the step), as in geometric._STRANG.
_AXES = np.array([0, 1, 2, 1, 0], dtype=np.int64)
_FRACTIONS = np.array([0.5, 0.5, 1.0, 0.5, 0.5])


def compiled_model(torque: Any) -> tuple[int, FloatArray, float] | None:
    """``(kind, vector, mean motion)`` of a torque model the kernel evaluates itself, or None
    for any other (a user's function, a torque depending on omega): those keep the numpy path.

    Examples
    --------
    >>> from tumble.dynamics.models.torques import ConstantTorque
    >>> from tumble.dynamics.methods.compiled import CONSTANT_BODY, compiled_model
    >>> compiled_model(ConstantTorque([0.0, 0.0, 1.0]))[0] == CONSTANT_BODY
    True
    >>> compiled_model(lambda t, w, R: w) is None   # a function: the numpy path calls it
    True
    """
    form = kernel_form(torque)  # the model's declared compiled form: no list of classes here
    if form is None or form[0] == KERNEL_NONE:
        return None
    kind, params = form
    if kind == GRAVITY_GRADIENT:
        return kind, np.zeros(3), float(params[0])
    return kind, np.array(params, dtype=float), 0.0


def _body_torque(kind: int, tau: FloatArray, n: float, I: FloatArray, q: FloatArray, t: float,
                 out: FloatArray) -> None:  # pragma: no cover - compiled
    """The built-in torque on one body in its principal frame, into ``out``."""
    x, y, z, w = q[0], q[1], q[2], q[3]
    if kind == CONSTANT_BODY:
        out[0], out[1], out[2] = tau[0], tau[1], tau[2]
        return
    if kind == CONSTANT_WORLD:
        v0, v1, v2 = tau[0], tau[1], tau[2]
    else:
        v0, v1, v2 = math.cos(n * t), math.sin(n * t), 0.0
    # R^T v: v turned by the conjugate quaternion, as the numpy path's body_torque turns it
    b0, b1, b2 = _rotate_vector(-x, -y, -z, w, v0, v1, v2)
    if kind == CONSTANT_WORLD:
        out[0], out[1], out[2] = b0, b1, b2
        return
    out[0], out[1], out[2] = _gravity_gradient(n * n, I[0], I[1], I[2], b0, b1, b2)  # 3 n^2 r_b x (I r_b)


def _rotate(L: FloatArray, q: FloatArray, axis: int, tau: float, inv_I: FloatArray,
            h: FloatArray) -> None:  # pragma: no cover
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


def _run(I: FloatArray, L0: FloatArray, q0: FloatArray, t: FloatArray, step: float, gammas: FloatArray, kind: int,
         tau: FloatArray, n: float, exact: bool, offset: FloatArray, omega_out: FloatArray,
         quat_out: FloatArray) -> None:  # pragma: no cover
    """Every body through every sample interval: equal steps no longer than
    ``step``, each the Yoshida composition ``gammas`` of the Strang step with half kicks."""
    N = I.shape[0]
    for b in prange(N):  # independent bodies: threads where the parallel kernel is used
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
                        _body_torque(kind, tau, n, Ib, q, tc, kick)
                        for i in range(3):
                            L[i] += 0.5 * hg * kick[i]
                    if exact:  # the exact free flow (exact-flow splitting)
                        free_flow_into(Ib, L, q, hg, work)
                    else:  # the Strang step of exact rotations (geometric splitting)
                        for r in range(_AXES.shape[0]):
                            _rotate(L, q, _AXES[r], _FRACTIONS[r] * hg, inv_I, hb)
                    tc += hg
                    if kind != 0:
                        _body_torque(kind, tau, n, Ib, q, tc, kick)
                        for i in range(3):
                            L[i] += 0.5 * hg * kick[i]
            norm = math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
            for i in range(4):
                q[i] /= norm
                quat_out[s, b, i] = q[i]
            for i in range(3):
                omega_out[s, b, i] = (L[i] - hb[i]) * inv_I[i]



prange = range  # the uncompiled kernel's loop over bodies; numba's prange once compiled


@functools.cache
def _compiled(parallel: bool = False) -> Callable[..., None]:
    """The kernel compiled by numba on first use (see the module docstring): one thread, or
    one per core over the bodies (``parallel``); the same arithmetic for each body."""
    from ...jit import jit
    from numba import prange as numba_prange

    if not _compiled.__dict__.get("helpers"):
        compiled_free_flow()
        from . import compiled_flow

        globals()["free_flow_into"] = compiled_flow.free_flow_into
        globals()["_gravity_gradient"] = jit(inline="always")(globals()["_gravity_gradient"])
        globals()["_rotate_vector"] = jit(inline="always")(globals()["_rotate_vector"])
        globals()["_equal_steps"] = jit(inline="always")(globals()["_equal_steps"])
        for name in ("_body_torque", "_rotate"):
            globals()[name] = jit(inline="always")(globals()[name])
        globals()["prange"] = numba_prange
        _compiled.__dict__["helpers"] = True
    # the parallel kernel is a copy of _run under its own name, so that numba's cache keeps the two
    # compiled versions apart (its cache files are named after the function)
    run = _run
    if parallel:
        run = types.FunctionType(_run.__code__, globals(), "_run_parallel")
        run.__qualname__ = "_run_parallel"
    return cast("Callable[..., None]", jit(parallel=parallel)(run))


def run_split(I: FloatArray, L: FloatArray, q: FloatArray, t: FloatArray, step: float, gammas: tuple[float, ...],
              model: tuple[int, FloatArray, float] | None, *, exact: bool = False,
              offset: FloatArray | None = None) -> tuple[FloatArray, FloatArray]:
    """The composed splitting of N bodies under a built-in torque (or none), compiled.

    Parameters
    ----------
    I, L : ndarray, shape (N, 3)
        Principal moments (kg m^2) and body-frame angular momentum (kg m^2/s) at ``t[0]``.
    q : ndarray, shape (N, 4)
        Unit quaternions, body to world, scalar last.
    t : ndarray, shape (n,)
        Sample times, s, increasing.
    step : float
        Largest step, s.
    gammas : tuple of float
        The composition's coefficients (:data:`tumble.dynamics.methods.geometric.COMPOSITIONS`).
    model : tuple or None
        :func:`compiled_model`'s answer; None for no torque.
    offset : ndarray, shape (N, 3) or (1, 3), optional
        Constant internal momentum ``h`` of wheels spinning at constant rates (kg m^2/s, body
        frame), with ``L = I omega + h``: the Strang step's rates are ``(L_i - h_i) / I_i``
        (:mod:`tumble.dynamics.methods.geometric`). Not with ``exact``.
    exact : bool
        The free part by the exact flow (:func:`tumble.dynamics.methods.compiled_flow.free_flow`,
        the exact-flow splitting) instead of the Strang step of rotations.

    Returns
    -------
    omega, quat : ndarray, shapes (n, N, 3) and (n, N, 4)
        As :func:`tumble.dynamics.methods.geometric.propagate` returns them.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled import CONSTANT_BODY, run_split
    >>> I, L = np.array([[1.0, 2.0, 3.0]]), np.array([[0.0, 0.0, 3.0]])
    >>> omega, quat = run_split(I, L, np.array([[0.0, 0.0, 0.0, 1.0]]), np.array([0.0, 1.0]), 0.1, (1.0,),
    ...                         (CONSTANT_BODY, np.array([0.0, 0.0, 0.3]), 0.0))
    >>> round(float(omega[-1, 0, 2]), 12)  # d omega3 / dt = 0.3 / 3 about a principal axis
    1.1
    """
    kind, tau, n = model if model is not None else (0, np.zeros(3), 0.0)
    N = len(I)
    h = np.zeros((N, 3)) if offset is None else np.ascontiguousarray(np.broadcast_to(offset, (N, 3)), dtype=float)
    if exact and np.any(h):
        raise ValueError("the exact free flow has no internal momentum: a body with wheels is a gyrostat")
    omega_out, quat_out = np.empty((len(t), N, 3)), np.empty((len(t), N, 4))
    kernel = _compiled(parallel=N >= PARALLEL_BODIES and cores() > 1)
    kernel(np.ascontiguousarray(I, dtype=float), np.ascontiguousarray(L, dtype=float),
                np.ascontiguousarray(q, dtype=float), np.ascontiguousarray(t, dtype=float), float(step),
                np.asarray(gammas, dtype=float), kind, np.asarray(tau, dtype=float), float(n), bool(exact), h, omega_out,
                quat_out)
    return omega_out, quat_out
