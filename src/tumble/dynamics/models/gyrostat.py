"""A gyrostat with a full inertia tensor and a rotor momentum given at sample times, compiled.

The body (rotor locked: tensor ``I`` in a body-fixed frame, not principal) carries a rotor
whose relative angular momentum ``h(t)`` is a measured input. The total momentum ``L = I w + h``
obeys Euler's equation of the gyrostat in the rotating frame (Hughes, *Spacecraft Attitude
Dynamics*, Wiley 1986, ch. 7; Wittenburg, *Dynamics of Multibody Systems*, 2nd ed., 2008,
sec. 5.3; :mod:`tumble.dynamics.models.rotors`)::

    L' = L x w + tau,     w = I^-1 (L - h(t)),

with a per-axis quadratic air drag ``tau_i = -b_i |w_i| w_i`` (:mod:`tumble.dynamics.models.drag`)
and, optionally, a torque whose profile ``g(t)`` is known and whose size ``k`` is a parameter,
``tau = k g(t)`` (the air's drag on a spinning rotor, ``-k Omega_r |Omega_r| a``, an external
torque on the whole: the motor holds the rotor's speed against it).
In this momentum form the rotor enters through ``h`` alone, never its derivative ``h'``: a
measured rotor speed need not be differentiated (its noise would be amplified by the inverse
of the sample interval).

:func:`gyrostat_omega` integrates it for a batch of ``K`` parameter sets (a fit's Jacobian by
finite differences is one call) over the same sample times, one classical Runge-Kutta step
(Hairer, Norsett & Wanner, *Solving ODEs I*, sec. II.1) per sample interval, with ``h`` given at
the samples and at the midpoints of the intervals (RK4's stages need it there). The step count
depends only on the times, so the result is a smooth function of the parameters. Local error
``~(|w| dt)^5``: 5e-11 at 35 rad/s and 4 kHz. The kernel is
:func:`tumble.dynamics.models.fit_kernels.gyrostat_integrate` (compiled when first imported); the
momentum form is :func:`tumble.dynamics.euler.momentum_rate_components`, re-exported here.
"""

from __future__ import annotations

import numpy as np

from ...jit import kernel_array
from ...typing import ArrayLike, FloatArray
from ..euler import momentum_rate_components

__all__ = ["gyrostat_omega", "momentum_rate_components"]


def gyrostat_omega(inertia: ArrayLike, momentum0: ArrayLike, t: ArrayLike, h: ArrayLike, h_mid: ArrayLike,
                   quadratic: ArrayLike | None = None, torque: tuple[ArrayLike, ArrayLike] | None = None,
                   torque_scale: ArrayLike | None = None) -> FloatArray:
    """Angular velocity of ``K`` gyrostats at the sample times (module docstring), body frame.

    Parameters
    ----------
    inertia : array_like, shape (K, 3, 3)
        Tensors (rotor locked), kg m^2, symmetric positive definite.
    momentum0 : array_like, shape (K, 3)
        Total angular momentum ``L = I w + h`` at ``t[0]``, kg m^2/s.
    t : array_like, shape (T,)
        Sample times, s, increasing (any spacing).
    h : array_like, shape (T, 3)
        The rotor's relative angular momentum at the samples, kg m^2/s.
    h_mid : array_like, shape (T - 1, 3)
        The same at the midpoints of the intervals.
    quadratic : array_like, shape (K, 3), optional
        Per-axis quadratic drag ``b_i``, N m s^2 (default 0).
    torque : (array_like, array_like), shapes (T, 3) and (T - 1, 3), optional
        A torque's profile ``g`` at the samples and the midpoints (its unit over that of ``k``).
    torque_scale : array_like, shape (K,), optional
        Its size ``k`` for each gyrostat: the torque is ``k g(t)``, N m (default 0).

    Returns
    -------
    ndarray, shape (K, T, 3)
        rad/s.

    Examples
    --------
    A wheel spun up from rest on a body at rest: the total momentum stays 0, so ``I w = -h``
    at every instant (:mod:`tumble.dynamics.models.rotors`):

    >>> import numpy as np
    >>> from tumble.dynamics.models.gyrostat import gyrostat_omega
    >>> I = np.array([[2.0, 0.1, 0.0], [0.1, 3.0, 0.0], [0.0, 0.0, 4.0]])
    >>> t = np.linspace(0.0, 1.0, 101)
    >>> h = np.outer(t ** 2, [0.0, 0.0, 1.0])
    >>> hm = np.outer((0.5 * (t[1:] + t[:-1])) ** 2, [0.0, 0.0, 1.0])
    >>> w = gyrostat_omega(I[None], np.zeros((1, 3)), t, h, hm)
    >>> bool(np.allclose(w[0] @ I, -h, atol=1e-14))
    True

    A steady torque ``k g`` along z on a body at rest with no rotor: ``L_z = k g t`` (RK4 is exact
    for a linear rise):

    >>> g = np.tile([0.0, 0.0, 1.0], (101, 1))
    >>> w = gyrostat_omega(I[None], np.zeros((1, 3)), t, 0 * h, 0 * hm, torque=(g, g[:-1]), torque_scale=[0.5])
    >>> bool(np.allclose((w[0] @ I)[:, 2], 0.5 * t, atol=1e-12))
    True
    """
    I = np.ascontiguousarray(np.asarray(inertia, float).reshape(-1, 3, 3))
    K = I.shape[0]
    L0 = kernel_array(momentum0, (K, 3))  # the one array type compiled (tumble.jit.kernel_array)
    quad = (np.zeros((K, 3)) if quadratic is None
            else kernel_array(quadratic, (K, 3)))
    times, hs, hm = kernel_array(t), kernel_array(h), kernel_array(h_mid)
    if hs.shape != (times.size, 3) or hm.shape != (max(times.size - 1, 0), 3):
        raise ValueError(f"h must have shape ({times.size}, 3) and h_mid ({times.size - 1}, 3), not {hs.shape} "
                         f"and {hm.shape}")
    if torque is None:
        g, gm, k = np.zeros_like(hs), np.zeros_like(hm), np.zeros(K)
    else:
        g, gm = (kernel_array(x) for x in torque)
        k = kernel_array(0.0 if torque_scale is None else torque_scale, (K,))
        if g.shape != hs.shape or gm.shape != hm.shape:
            raise ValueError(f"torque must have the shapes of h and h_mid, not {g.shape} and {gm.shape}")
    from .fit_kernels import gyrostat_integrate  # compiled at import: numba only when a fit needs it

    return gyrostat_integrate(np.linalg.inv(I), L0, quad, times, hs, hm, g, gm, k)
