"""The splittings under the built-in torques, compiled: the front of whole runs inside numba.

The composed splitting of :func:`tumble.dynamics.methods.geometric.propagate` (McLachlan 1993;
Yoshida 1990; the torque as two half kicks around the Strang step, Celledoni et al. 2008,
sec. 5) runs in numba, every step of every body, with no Python call per step: the numpy path
calls the torque model once per kick from Python (a user's function must be called so), ~10 us
per kick for one body, 1000 times the kick itself. The built-in models declare their compiled
form (:func:`~tumble.dynamics.models.torques.kernel_form`); the kernels take it, or a sum of them,
as the engine's torque terms ``P`` and the orbit's mean motion ``n``
(:func:`~tumble.dynamics.models.torque_protocols.kernel_terms`) and evaluate them with the engine's
own right-hand side of the torque (:func:`~tumble.dynamics.engine.kernels.external_torque`): a
constant torque in the principal or the world frame, the gravity gradient of a circular orbit,
any sum of them.

The kernels live in :mod:`tumble.dynamics.methods.compiled_split`, imported on first use
(:func:`_kernels`; it imports numba, which ``import tumble`` does not) and compiled at import
with ``cache=True``. The compiled and numpy paths agree to round-off (tests/test_compiled.py). A
batch of at least :data:`~tumble.jit.PARALLEL_BODIES` runs its bodies on every core
(``numba.prange``); smaller ones on one thread, since the parallel kernel made the first call of
a process 2.3 s against 0.96 s (the threading layer's start, measured). Each body gets the same
arithmetic either way.
"""

from __future__ import annotations

import functools
from types import ModuleType
from typing import Any

import numpy as np

from ...jit import PARALLEL_BODIES, cores, kernel_array
from ...typing import FloatArray
from ..models.torques import KERNEL_ROTOR_MOMENTUM, kernel_form
from ..models.torque_protocols import TERMS, kernel_terms

__all__ = ["compiled_model", "run_split"]


def compiled_model(torque: Any) -> tuple[tuple[float, ...], float] | None:
    """The engine's torque terms ``(P, n)`` (:func:`~tumble.dynamics.models.torque_protocols.kernel_terms`)
    of a torque model the kernels evaluate themselves, or None for any other (a user's function, a
    torque depending on omega, a gravity gradient not bound to a body): those keep the numpy path.

    Examples
    --------
    >>> from tumble.dynamics.models.torques import ConstantTorque
    >>> from tumble.dynamics.methods.compiled import compiled_model
    >>> compiled_model(ConstantTorque([0.0, 0.0, 1.0]) + ConstantTorque([1.0, 0.0, 0.0], "world"))   # body, world slots
    ((0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0), 0.0)
    >>> compiled_model(lambda t, w, R: w) is None   # a function: the numpy path calls it
    True
    """
    form = kernel_form(torque)  # the model's declared compiled form: no list of classes here
    if form is None or form[0] == KERNEL_ROTOR_MOMENTUM:  # wheels are the splitting's offset, not a torque
        return None
    return kernel_terms((form,))


@functools.cache
def _kernels() -> ModuleType:
    """The compiled kernels (:mod:`tumble.dynamics.methods.compiled_split`), imported on first
    use: importing them imports numba and compiles (or loads from the cache) every kernel."""
    from . import compiled_split

    return compiled_split


def run_split(I: FloatArray, L: FloatArray, q: FloatArray, t: FloatArray, step: float, gammas: tuple[float, ...],
              model: tuple[tuple[float, ...], float] | None, *, exact: bool = False,
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
        :func:`compiled_model`'s answer, the torque terms ``(P, n)``; None for no torque.
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
    >>> from tumble.dynamics.methods.compiled import compiled_model, run_split
    >>> from tumble.dynamics.models.torques import ConstantTorque
    >>> I, L = np.array([[1.0, 2.0, 3.0]]), np.array([[0.0, 0.0, 3.0]])
    >>> omega, quat = run_split(I, L, np.array([[0.0, 0.0, 0.0, 1.0]]), np.array([0.0, 1.0]), 0.1, (1.0,),
    ...                         compiled_model(ConstantTorque((0.0, 0.0, 0.3))))
    >>> round(float(omega[-1, 0, 2]), 12)  # d omega3 / dt = 0.3 / 3 about a principal axis
    1.1
    """
    P, n = model if model is not None else ((0.0,) * TERMS, 0.0)
    N = len(I)
    h = np.zeros((N, 3)) if offset is None else kernel_array(offset, (N, 3))
    if exact and np.any(h):
        raise ValueError("the exact free flow has no internal momentum: a body with wheels is a gyrostat")
    omega_out, quat_out = np.empty((len(t), N, 3)), np.empty((len(t), N, 4))
    kernels = _kernels()
    kernel = kernels.run_parallel if N >= PARALLEL_BODIES and cores() > 1 else kernels.run_serial
    kernel(kernel_array(I), kernel_array(L), kernel_array(q), kernel_array(t), float(step), kernel_array(gammas), P,
           float(n), bool(exact), h, omega_out, quat_out)
    return omega_out, quat_out
