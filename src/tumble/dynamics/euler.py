"""Euler's equations for a rigid body and the quantities they conserve.

Pure functions over numpy arrays; each broadcasts over leading batch axes (``omega`` of shape
``(..., 3)``). Angular velocity and momentum are in the body's principal frame unless a name
ends in ``_world``. Units: rad/s, kg m^2, N m, J, kg m^2/s.

References
----------
- Seed study sec. 3: ``tau = I omega' + omega x (I omega)`` in the principal frame.
- Landau & Lifshitz, *Mechanics*, 3rd ed., sec. 36, eq. (36.5); Goldstein, Poole & Safko,
  *Classical Mechanics*, 3rd ed., eq. (5.39').
- Quaternion kinematics (``quaternion_rate``): :mod:`tumble.dynamics.special.quaternion`.
- The momentum form ``L' = L x w + tau`` (:func:`momentum_rate_components`, the gyrostat's):
  Hughes, *Spacecraft Attitude Dynamics*, Wiley 1986, ch. 7.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, cast

import numpy as np

from ..jit import formula
from ..typing import ArrayLike, FloatArray, Vector3

__all__ = [
    "angular_momentum",
    "cross",
    "energy_momentum_gaps",
    "euler_components",
    "euler_rhs",
    "euler_rhs_tensor",
    "kinetic_energy",
    "momentum_rate_components",
    "relative_drift",
]


def euler_rhs(omega: ArrayLike, moments: ArrayLike, torque: ArrayLike = 0.0) -> Vector3:
    """Angular acceleration from Euler's equations in the principal frame.

    ``I_1 w1' = (I_2 - I_3) w2 w3 + tau_1`` and cyclic (seed sec. 3, rearranged).

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity in the principal frame, rad/s.
    moments : array_like, shape (..., 3)
        Principal moments ``(I1, I2, I3)``, kg m^2.
    torque : array_like, shape (..., 3), optional
        External torque about the COM in the principal frame, N m.

    Returns
    -------
    ndarray, shape (..., 3)
        ``d omega / dt`` in the principal frame, rad/s^2.

    Examples
    --------
    >>> from tumble.dynamics.euler import euler_rhs
    >>> euler_rhs([1.0, 1.0, 1.0], [1.0, 2.0, 3.0]).tolist()   # ((I2 - I3) w2 w3 / I1, ...)
    [-1.0, 1.0, -0.3333333333333333]
    >>> euler_rhs([0.0, 0.0, 2.0], [1.0, 2.0, 3.0], torque=[0.0, 0.0, 3.0]).tolist()   # tau / I
    [0.0, 0.0, 1.0]
    """
    w = np.asarray(omega, dtype=float)
    I = np.asarray(moments, dtype=float)
    tau = np.asarray(torque, dtype=float)
    if w.shape == I.shape == (3,) and tau.shape in ((3,), ()):
        # one body at one instant, a Python right-hand side's every call: the same formula over plain
        # floats, the same IEEE operations, bit for bit (18 -> 1.5 us a call, numpy's broadcasting left
        # out); the reciprocals still numpy's, which answer a zero moment with inf and its warning
        (w0, w1, w2), (I0, I1, I2), (r0, r1, r2) = w.tolist(), I.tolist(), (1.0 / I).tolist()
        t0, t1, t2 = tau.tolist() if tau.ndim else (float(tau),) * 3
        return cast(Vector3, np.array(euler_components(w0, w1, w2, I0, I1, I2, t0, t1, t2, r0, r1, r2)))
    w, I, tau = np.broadcast_arrays(w, I, tau if tau.ndim else np.full(3, float(tau)))
    r = 1.0 / I
    return cast(Vector3, np.stack(euler_components(w[..., 0], w[..., 1], w[..., 2], I[..., 0], I[..., 1], I[..., 2],
                                                   tau[..., 0], tau[..., 1], tau[..., 2], r[..., 0], r[..., 1], r[..., 2]),
                                  axis=-1))


def euler_components(w0: Any, w1: Any, w2: Any, I0: Any, I1: Any, I2: Any, t0: Any, t1: Any, t2: Any, r0: Any, r1: Any,
                     r2: Any) -> tuple[Any, Any, Any]:
    """Euler's equations component by component: the one writing of the formula, over floats or arrays.

    ``w1' = ((I2 - I3) w2 w3 + tau_1) / I1`` and cyclic (Goldstein, *Classical Mechanics*, 3rd ed.,
    eq. 5.39'), with ``1 / I1`` given as ``r0``: a run computes the reciprocals once and
    multiplies (three divisions per right-hand side were a fifth of the compiled RK8 step,
    measured). The difference ``I2 - I3`` is exact for close moments (Sterbenz), so a nearly
    symmetric body loses no digits to it. Arguments are floats (the compiled engine calls it,
    :mod:`tumble.dynamics.engine`) or arrays of one shape (:func:`euler_rhs` calls it on columns):
    one formula for both paths.

    Parameters
    ----------
    w0, w1, w2 : float or ndarray
        Angular velocity, principal frame, rad/s.
    I0, I1, I2 : float or ndarray
        Principal moments, kg m^2.
    t0, t1, t2 : float or ndarray
        External torque, principal frame, N m.
    r0, r1, r2 : float or ndarray
        The reciprocal moments ``1 / I0, 1 / I1, 1 / I2``, 1/(kg m^2).

    Returns
    -------
    tuple of three floats or ndarrays
        ``d omega / dt``, rad/s^2.

    Examples
    --------
    >>> from tumble.dynamics.euler import euler_components
    >>> euler_components(1.0, 1.0, 1.0, 1.0, 2.0, 3.0, 0.0, 0.0, 0.0, 1.0, 0.5, 1.0 / 3.0)
    (-1.0, 1.0, -0.3333333333333333)
    """
    return ((I1 - I2) * w1 * w2 + t0) * r0, ((I2 - I0) * w2 * w0 + t1) * r1, ((I0 - I1) * w0 * w1 + t2) * r2


def euler_rhs_tensor(omega: ArrayLike, inertia: ArrayLike, torque: ArrayLike = 0.0) -> Vector3:
    """Euler's equations with a full tensor, in any frame fixed to the body.

    ``I omega' = tau - omega x (I omega)`` (Goldstein eq. 5.39'); used to check the principal
    form and for bodies described in their design frame.

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity in that body frame, rad/s.
    inertia : array_like, shape (..., 3, 3)
        Inertia tensor about the COM in that frame, kg m^2.
    torque : array_like, shape (..., 3), optional
        External torque in that frame, N m.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.euler import euler_rhs, euler_rhs_tensor
    >>> bool(np.allclose(euler_rhs_tensor([1.0, 1.0, 1.0], np.diag([1.0, 2.0, 3.0])),
    ...                  euler_rhs([1.0, 1.0, 1.0], [1.0, 2.0, 3.0])))   # a diagonal tensor: the principal form
    True
    """
    w = np.asarray(omega, dtype=float)
    I = np.asarray(inertia, dtype=float)
    L = np.einsum("...ij,...j->...i", I, w)
    rhs = torque - np.cross(w, L)
    return cast(Vector3, np.linalg.solve(I, rhs[..., None])[..., 0])


def cross(a: Sequence[float] | FloatArray, b: Sequence[float] | FloatArray) -> Vector3:
    """``a x b`` of two 3-vectors (shape (3,)), written out over Python floats.

    For the right-hand sides that scipy's integrators call at every stage with one state (a
    closed loop with a model of one's own, the fits' synthetic rotor flights): numpy's ``cross``
    costs ~30 us a call on one pair, in its checks and broadcasting; this ~1 us. The same
    products and differences in the same order, so the same bits. Arrays of many vectors: ``np.cross``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.euler import cross
    >>> a, b = np.array([0.3, -1.2, 2.5]), np.array([4.0, 0.7, -0.9])
    >>> cross([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]).tolist(), bool(np.array_equal(cross(a, b), np.cross(a, b)))
    ([0.0, 0.0, 1.0], True)
    """
    a0, a1, a2 = float(a[0]), float(a[1]), float(a[2])
    b0, b1, b2 = float(b[0]), float(b[1]), float(b[2])
    return cast(Vector3, np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0]))


def angular_momentum(omega: ArrayLike, moments: ArrayLike) -> Vector3:
    """``L = I omega`` in the principal frame, kg m^2/s.

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity, principal frame, rad/s.
    moments : array_like, shape (..., 3)
        Principal moments ``[I1, I2, I3]``, kg m^2.

    Returns
    -------
    ndarray, shape (..., 3)
        Angular momentum, principal frame, kg m^2/s.

    Examples
    --------
    >>> from tumble.dynamics.euler import angular_momentum
    >>> angular_momentum([1.0, 1.0, 2.0], [1.0, 2.0, 3.0]).tolist()
    [1.0, 2.0, 6.0]
    """
    return cast(Vector3, np.asarray(moments, float) * np.asarray(omega, float))


def kinetic_energy(omega: ArrayLike, moments: ArrayLike) -> FloatArray:
    """Rotational kinetic energy ``T = omega @ I @ omega / 2``, J.

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity, principal frame, rad/s.
    moments : array_like, shape (..., 3)
        Principal moments ``[I1, I2, I3]``, kg m^2.

    Returns
    -------
    ndarray, shape (...)
        Kinetic energy, J.

    Examples
    --------
    >>> from tumble.dynamics.euler import kinetic_energy
    >>> float(kinetic_energy([1.0, 1.0, 2.0], [1.0, 2.0, 3.0]))   # (1 + 2 + 12) / 2
    7.5
    """
    w = np.asarray(omega, float)
    return cast(FloatArray, 0.5 * np.sum(np.asarray(moments, float) * w * w, axis=-1))


def relative_drift(energy: ArrayLike, momentum_norm: ArrayLike, momentum_world: ArrayLike) -> dict[str, FloatArray]:
    """The largest relative departure of a run's invariants from their first sample.

    ``energy``: max_t |E - E0| / E0; ``L_norm``: max_t ||L| - |L0|| / |L0|; ``L_world``:
    max_t |L_world - L_world(0)| / |L0|. Conserved without an external torque (Landau &
    Lifshitz, *Mechanics*, sec. 35-36), so for a torque-free run these are the integration's errors.

    Parameters
    ----------
    energy : array_like, shape (..., T)
        The energy (or energy balance) at each sample, J.
    momentum_norm : array_like, shape (..., T)
        ``|L|`` at each sample, kg m^2/s.
    momentum_world : array_like, shape (..., T, 3)
        ``L`` in the world frame at each sample, kg m^2/s.

    Returns
    -------
    dict of str to ndarray, shape (...)
        NaN where the first value is zero (a body at rest: no relative drift) or a sample is not finite.

    Examples
    --------
    >>> from tumble.dynamics.euler import relative_drift
    >>> d = relative_drift([2.0, 2.2, 1.9], [1.0, 1.0, 1.01], [[0, 0, 1.0], [0, 0, 1.0], [0, 0.02, 1.0]])
    >>> {k: round(float(v), 6) for k, v in d.items()}
    {'energy': 0.1, 'L_norm': 0.01, 'L_world': 0.02}
    """
    E, Ln = np.asarray(energy, float), np.asarray(momentum_norm, float)
    Lw = np.asarray(momentum_world, float)

    def rel(dev: FloatArray, ref: FloatArray) -> FloatArray:
        with np.errstate(invalid="ignore", divide="ignore"):
            worst = np.max(dev, axis=-1) / ref
        return cast(FloatArray, np.where((ref > 0) & np.all(np.isfinite(dev), axis=-1), worst, np.nan))

    return {
        "energy": rel(np.abs(E - E[..., :1]), E[..., 0]),
        "L_norm": rel(np.abs(Ln - Ln[..., :1]), Ln[..., 0]),
        "L_world": rel(np.linalg.norm(Lw - Lw[..., :1, :], axis=-1), Ln[..., 0]),
    }


def energy_momentum_gaps(omega: ArrayLike, moments: ArrayLike) -> Vector3:
    """``L^2 - 2 E I_j`` for j = 1, 2, 3, computed without cancellation.

    ``L^2 - 2 E I_j = sum_i I_i (I_i - I_j) omega_i^2``: each term carries its own sign, so the
    difference of two nearly equal large numbers is never formed (Celledoni et al., SIAM J.
    Sci. Comput. 30 (2008) 2084, sec. 2).

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity, principal frame, rad/s.
    moments : array_like, shape (..., 3)
        Principal moments ``[I1, I2, I3]``, kg m^2.

    Returns
    -------
    ndarray, shape (..., 3)
        ``L^2 - 2 E I_j`` for j = 1, 2, 3, (kg m^2/s)^2.

    Examples
    --------
    >>> from tumble.dynamics.euler import energy_momentum_gaps
    >>> gaps = energy_momentum_gaps([1.0, 0.0, 0.0], [1.0, 2.0, 3.0])   # spin about the minor axis
    >>> gaps.shape
    (3,)
    """
    w2 = np.asarray(omega, float)[..., None, :] ** 2
    I = np.asarray(moments, float)
    return cast(Vector3, np.sum(I[..., None, :] * (I[..., None, :] - I[..., :, None]) * w2, axis=-1))


@formula
def momentum_rate_components(L0: Any, L1: Any, L2: Any, w0: Any, w1: Any, w2: Any, t0: Any, t1: Any,
                             t2: Any) -> tuple[Any, Any, Any]:
    """Euler's equation in momentum form, ``L' = L x w + tau``, component by component.

    ``L`` the angular momentum of the whole (body and rotors, kg m^2/s) and ``w`` the body's
    angular velocity (rad/s), both in a frame fixed to the body, ``tau`` the external torque
    (N m): the gyrostat's equation (Hughes, *Spacecraft Attitude Dynamics*, 1986, ch. 7;
    :mod:`tumble.dynamics.models.gyrostat`), and the rigid body's when ``L = I w``. The one
    writing of this form, over floats (the compiled kernels of
    :mod:`tumble.dynamics.models.fit_kernels` and :mod:`tumble.dynamics.control.loop_terms`) or
    arrays of one shape (:mod:`tumble.dynamics.models.internal`); the angular-velocity form is
    :func:`euler_components`.

    Examples
    --------
    >>> from tumble.dynamics.euler import momentum_rate_components
    >>> momentum_rate_components(1.0, 2.0, 3.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.5)   # L x w + tau
    (-1.0, 2.0, -0.5)
    """
    return L1 * w2 - L2 * w1 + t0, L2 * w0 - L0 * w2 + t1, L0 * w1 - L1 * w0 + t2
