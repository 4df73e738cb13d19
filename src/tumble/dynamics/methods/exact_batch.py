"""The exact torque-free motion of N rigid bodies at common times: the batch front.

The mathematics is that of :mod:`tumble.dynamics.methods.exact` (Landau & Lifshitz, *Mechanics*,
sec. 37; read its module docstring). Two evaluations, picked by the batch's size:

- below :data:`~tumble.dynamics.methods.exact_parameters.COMPILED_BODIES` bodies, the kernel
  :class:`tumble.dynamics.methods.exact_kernel.EllipticMotion` over chunks of bodies, phases in
  double-double: a body here gets what :class:`tumble.dynamics.methods.exact.FreeRotation` gives
  it, to a few ulps (the kernel picks its parameter path, floats or arrays, by the chunk's size).
  Steady rotations (spheres, spins about a principal axis, a symmetric top in its degenerate
  plane) are turns about the fixed omega by ``|omega| t`` (double-double, reduced mod 2 pi). The
  chunks run on every core (:func:`tumble.dynamics.methods.exact_parameters.run_chunks`: threads,
  since numpy releases the GIL within each operation);
- from that many, the compiled kernel (:mod:`tumble.dynamics.methods.compiled_exact`: numba,
  double precision, every core, ~0.7 CPU-us a body with its attitude), which leaves the bodies
  double precision cannot take (next to the separatrix, phases beyond 1000 rad) to the
  double-double path: within ~6e-13 of it in omega (relative) and the attitude (rad).
"""

from __future__ import annotations

from typing import Literal, cast, overload

import numpy as np

from ...jit import PARALLEL_BODIES, cores, kernel_array
from ...typing import ArrayLike, FloatArray, IntArray, Quaternion, Vector3
from .exact import MAX_PHASE, check_phase_limit
from .exact_kernel import EllipticMotion, is_steady, steady_attitude
from .exact_parameters import COMPILED_BODIES, compiled_kernels, run_chunks

__all__ = ["free_rotation_batch"]

#: Bodies x samples evaluated at once: a few dozen arrays of this many doubles, which stay in
#: cache (measured here: 10% faster than 1 << 17), but at least _MIN_BODIES bodies per chunk,
#: so that each chunk's per-body work is not dominated by Python's overhead on many samples.
_CHUNK = 1 << 14
_MIN_BODIES = 64


@overload
def free_rotation_batch(
    moments: ArrayLike, omega0: ArrayLike, quat0: ArrayLike, t: ArrayLike, *, attitude: Literal[True] = ...
) -> tuple[Vector3, Quaternion]: ...
@overload
def free_rotation_batch(
    moments: ArrayLike, omega0: ArrayLike, quat0: ArrayLike, t: ArrayLike, *, attitude: bool
) -> tuple[Vector3, Quaternion | None]: ...
def free_rotation_batch(
    moments: ArrayLike, omega0: ArrayLike, quat0: ArrayLike, t: ArrayLike, *, attitude: bool = True
) -> tuple[Vector3, Quaternion | None]:
    """Omega and attitude of N free rigid bodies at times ``t``, without a loop over bodies.

    Parameters
    ----------
    moments : ndarray, shape (N, 3)
        Principal moments, ascending, positive, kg m^2.
    omega0 : ndarray, shape (N, 3)
        Angular velocity at t = 0, principal frame, rad/s.
    quat0 : ndarray, shape (N, 4)
        Unit quaternions, principal frame to world at t = 0, scalar last.
    t : ndarray, shape (T,)
        Times, s.
    attitude : bool
        Whether to compute the attitude (``quat`` is None without).

    Returns
    -------
    omega : ndarray, shape (N, T, 3)
        rad/s, equal to :meth:`~tumble.dynamics.methods.exact.FreeRotation.omega` to a few ulps
        of each body's amplitudes (from ``COMPILED_BODIES`` bodies, to ~6e-13 of ``|omega|``:
        the module docstring).
    quat : ndarray, shape (N, T, 4) or None
        Principal frame to world, equal to
        :meth:`~tumble.dynamics.methods.exact.FreeRotation.attitude` to ~1e-15 rad (from
        ``COMPILED_BODIES`` bodies, to ~6e-13 rad).

    Raises
    ------
    ValueError
        If a body's phase would exceed :data:`tumble.dynamics.methods.exact.MAX_PHASE`, naming the body.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.exact_batch import free_rotation_batch
    >>> I = np.array([[1.0, 2.0, 3.0], [1.0, 2.0, 3.0]])
    >>> w0 = np.array([[0.1, 1.0, 0.1], [0.0, 0.0, 2.0]])
    >>> omega, quat = free_rotation_batch(I, w0, np.tile([0.0, 0.0, 0.0, 1.0], (2, 1)), np.linspace(0.0, 5.0, 6))
    >>> omega.shape, quat.shape
    ((2, 6, 3), (2, 6, 4))
    >>> bool(np.allclose(omega[1], [0.0, 0.0, 2.0]))  # a spin about the major axis stays
    True
    """
    I, w, q0 = (np.asarray(a, float) for a in (moments, omega0, quat0))
    t = np.asarray(t, float)
    if len(I) < COMPILED_BODIES:
        _check_phases(I, w, t, np.arange(len(I)))
        omega, quat = _double_double(I, w, q0, t, attitude)
    else:
        omega = np.empty((len(I), len(t), 3))
        quat = np.empty((len(I), len(t), 4))
        left = _compiled(I, w, q0, t, attitude, omega, quat)
        if left.size:  # the bodies double precision cannot take (compiled_exact's docstring)
            _check_phases(I[left], w[left], t, left)  # the kernel takes no phase beyond 1000 rad
            omega[left], rest = _double_double(I[left], w[left], q0[left], t, attitude)
            if attitude:
                quat[left] = rest
        quat = quat if attitude else None
    start = t == 0.0  # the start as given, as FreeRotation's, not the closed form's few ulps off it
    omega[:, start] = w[:, None, :]
    if quat is not None:
        quat[:, start] = q0[:, None, :]
    return omega, quat


def _compiled(I: Vector3, w: Vector3, q0: Quaternion, t: FloatArray, attitude: bool, omega: Vector3,
              quat: Quaternion) -> IntArray:
    """The compiled kernel over every body, on every core for a large batch, into ``omega`` and
    ``quat``; the indices of the bodies it left to the double-double path."""
    kernels = compiled_kernels()
    kernel = kernels.motion_parallel if len(I) >= PARALLEL_BODIES and cores() > 1 else kernels.motion_serial
    done = np.empty(len(I), dtype=np.bool_)
    kernel(kernel_array(I), kernel_array(w), kernel_array(q0), kernel_array(t), attitude, omega, quat, done)
    return np.flatnonzero(~done)


def _double_double(I: Vector3, w: Vector3, q0: Quaternion, t: FloatArray,
                   attitude: bool) -> tuple[Vector3, Quaternion | None]:
    """The double-double path (:class:`~tumble.dynamics.methods.exact_kernel.EllipticMotion`)
    for every body, in chunks on every core."""
    N, T = len(I), len(t)
    omega = np.empty((N, T, 3))
    quat = np.empty((N, T, 4)) if attitude else None
    steady = is_steady(I, w)
    idx = np.flatnonzero(steady)
    if len(idx):
        omega[idx] = w[idx, None, :]
        if attitude:
            cast(Quaternion, quat)[idx] = steady_attitude(w[idx], q0[idx], t)
    rest = np.flatnonzero(~steady)
    step = max(_MIN_BODIES, _CHUNK // max(T, 1))

    def run(start: int) -> None:
        chunk = rest[start:start + step]
        motion = EllipticMotion(I[chunk], w[chunk])
        reduced = motion.reduce(t)
        omega[chunk] = motion.omega(reduced)
        if attitude:
            cast(Quaternion, quat)[chunk] = motion.attitude(q0[chunk], t, reduced, omega[chunk])

    run_chunks(run, range(0, len(rest), step))  # on every core (numpy releases the GIL in each operation)
    return omega, quat


def _check_phases(I: Vector3, w: Vector3, t: FloatArray, index: IntArray) -> None:
    """:func:`check_phase_limit` for the bodies that could come near it (a cheap bound first);
    ``index`` the bodies' places in the batch, for the message."""
    if not t.size:
        return
    t_max = float(np.max(np.abs(t)))
    with np.errstate(over="ignore"):
        bound = np.linalg.norm(I * w, axis=1) / I[:, 0] * t_max
    for i in np.flatnonzero(~(bound <= 1e-3 * MAX_PHASE)):
        try:
            check_phase_limit(I[i], w[i], t_max)
        except ValueError as err:
            raise ValueError(f"omega0[{index[i]}]: {err}") from None
