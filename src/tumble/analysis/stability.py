"""Stability of free rotation about the principal axes: the tennis-racket theorem, quantified.

Three routes that the tests hold against each other:

1. *Linearised* (Marion & Thornton, *Classical Dynamics*, 5th ed., sec. 11.12; Landau &
   Lifshitz, *Mechanics*, sec. 37, problem 1): spin ``W`` about principal axis ``a`` with small
   components along the other two axes ``b, c``. Euler's equations give
   ``eps_b'' = s eps_b`` with ``s = W^2 (I_a - I_b)(I_c - I_a) / (I_b I_c)``. For the
   intermediate axis ``s > 0``: the perturbation grows as ``exp(lambda t)``,
   ``lambda = sqrt(s)``; for the minor and major axes ``s < 0``: it wobbles at ``sqrt(-s)``.
2. *Exact* (Landau & Lifshitz sec. 37): omega(t) is a Jacobi elliptic motion
   whose period is ``4 K(k^2) / p``; the components that change sign do so every ``2 K / p``,
   the *flip interval* (:func:`flip_interval`).
3. *Measured*: sign changes of the spin component in a simulated trajectory
   (:func:`flip_times`).
"""

from __future__ import annotations

import numpy as np
from scipy.special import ellipkm1

from ..dynamics.euler import energy_momentum_gaps
from ..dynamics.exact import elliptic_parameters

__all__ = [
    "axis_of",
    "circulation_axis",
    "energy_momentum_gaps",
    "flip_interval",
    "flip_interval_asymptotic",
    "flip_times",
    "linearised_rate",
    "perturbation_exponent",
]


def axis_of(omega) -> np.ndarray:
    """Index 0, 1 or 2 of the principal axis carrying most of ``omega`` (largest |component|)."""
    return np.argmax(np.abs(np.asarray(omega, float)), axis=-1)


def perturbation_exponent(moments, axis, spin) -> np.ndarray:
    """``s = W^2 (I_a - I_b)(I_c - I_a) / (I_b I_c)`` of the linearised equations (see module).

    Parameters
    ----------
    moments : array_like, shape (..., 3)
        Principal moments, kg m^2.
    axis : int or array_like of int, shape (...)
        Spin axis ``a`` (0, 1, 2).
    spin : array_like, shape (...)
        Spin rate W about that axis, rad/s.

    Returns
    -------
    ndarray, shape (...)
        ``s`` in 1/s^2: positive means exponential growth, negative means a wobble.
    """
    I = np.asarray(moments, float)
    a = np.asarray(axis)
    Ia = np.take_along_axis(I, a[..., None], axis=-1)[..., 0]
    Ib = np.take_along_axis(I, ((a + 1) % 3)[..., None], axis=-1)[..., 0]
    Ic = np.take_along_axis(I, ((a + 2) % 3)[..., None], axis=-1)[..., 0]
    return np.asarray(spin, float) ** 2 * (Ia - Ib) * (Ic - Ia) / (Ib * Ic)


def linearised_rate(moments, axis, spin) -> tuple[np.ndarray, np.ndarray]:
    """Growth exponent (1/s) and wobble angular frequency (rad/s) for spin about ``axis``.

    Exactly one of the two is non-zero for an asymmetric body: the growth exponent for the
    intermediate axis, the wobble frequency for the minor and major axes.
    """
    s = perturbation_exponent(moments, axis, spin)
    return np.sqrt(np.maximum(s, 0.0)), np.sqrt(np.maximum(-s, 0.0))


def flip_interval(omega, moments) -> np.ndarray:
    """Exact time between sign changes of the oscillating components of omega, s.

    Torque-free motion with ``I1 < I2 < I3`` (Landau & Lifshitz sec. 37): for
    ``L^2 > 2 E I2`` omega circulates about axis 3 (``omega_3`` keeps its sign, ``omega_1`` and
    ``omega_2`` change sign); for ``L^2 < 2 E I2`` about axis 1. Either way the period of omega
    is ``4 K(k^2) / p`` and the sign changes come every ``2 K / p`` with

    - ``L^2 > 2 E I2``: ``p^2 = (I3 - I2)(L^2 - 2 E I1) / (I1 I2 I3)``,
      ``1 - k^2 = (I3 - I1)(L^2 - 2 E I2) / ((I3 - I2)(L^2 - 2 E I1))``;
    - ``L^2 < 2 E I2``: indices 1 and 3 exchanged.

    ``1 - k^2`` is formed directly (:func:`tumble.dynamics.exact.elliptic_parameters`) and fed to
    ``scipy.special.ellipkm1``, so the interval stays accurate as the motion nears the
    separatrix, where it diverges logarithmically.

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity at any instant (principal frame), rad/s.
    moments : array_like, shape (..., 3)
        Principal moments, strictly ascending, kg m^2.

    Returns
    -------
    ndarray, shape (...)
        The flip interval, s; ``inf`` on the separatrix (``L^2 = 2 E I2``). Near a stable
        axis it tends to half the wobble period, ``pi / sqrt(-s)``.
    """
    e = elliptic_parameters(omega, moments)
    p, m1 = e.p, e.m1
    with np.errstate(divide="ignore", invalid="ignore"):
        interval = 2.0 * ellipkm1(m1) / p
    return np.where((m1 == 0) | ~np.isfinite(interval) | ~(p > 0), np.inf, interval)


def flip_interval_asymptotic(omega, moments) -> np.ndarray:
    """Small-perturbation form of :func:`flip_interval`: ``ln(16 / (1 - k^2)) / p``, s.

    From ``K(k) = ln(4 / k') + O(k'^2 ln k')`` (Abramowitz & Stegun ch. 17, the limit m -> 1) with
    ``k'^2 = 1 - k^2``, which is proportional to the square of the perturbation of a spin about
    the intermediate axis: the interval grows like ``(2 / lambda) ln(1 / eps)`` as the spin
    nears the axis, with ``p -> lambda``, the linearised growth exponent. Relative error
    ``O(1 - k^2)``.
    """
    e = elliptic_parameters(omega, moments)
    with np.errstate(divide="ignore"):
        return np.log(16.0 / e.m1) / e.p


def circulation_axis(omega, moments) -> np.ndarray:
    """Index (0 or 2) of the principal axis about which omega circulates, whose component never
    changes sign (the dn component in Landau & Lifshitz sec. 37): 2 (major) when ``L^2 >= 2 E I2``, else 0."""
    return np.where(elliptic_parameters(omega, moments).upper, 2, 0)


def flip_times(t, component) -> np.ndarray:
    """Times at which a sampled component changes sign (linear interpolation), s.

    Parameters
    ----------
    t : array_like, shape (n,)
        Sample times, s.
    component : array_like, shape (n,)
        The sampled quantity, e.g. ``omega[:, axis]``.
    """
    t = np.asarray(t, float)
    y = np.asarray(component, float)
    k = np.flatnonzero(np.signbit(y[:-1]) != np.signbit(y[1:]))
    return t[k] - y[k] * (t[k + 1] - t[k]) / (y[k + 1] - y[k])
