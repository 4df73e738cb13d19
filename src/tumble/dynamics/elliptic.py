"""Jacobi elliptic functions and Legendre's integrals that keep their accuracy near m = 1.

Why not ``scipy.special.ellipj`` / ``ellipkinc``: they take the parameter ``m`` only. Near the
separatrix of the free rigid body ``m = 1 - m1`` with ``m1`` as small as 1e-20, and ``1 - m``
cannot hold ``m1`` in double precision (at m1 = 1e-15 ``ellipj`` is off by O(1)). They also go
through the amplitude ``am(u)``, which is ill-conditioned exactly where the body lingers near a
saddle: ``cn = cos(am)`` is then tiny and loses its relative accuracy. So here

- every function takes both ``m`` and ``m1 = 1 - m``, formed by the caller without
  cancellation;
- ``u`` is reduced to ``|v| <= K/2`` about the nearest multiple of the quarter period ``K``,
  and the shift formulas ``sn(v + K) = cd v``, ``cn(v + K) = -sqrt(m1) sd v``,
  ``dn(v + K) = sqrt(m1) nd v`` (DLMF 22.4.3) give cn and dn with full *relative* accuracy near
  their zeros;
- the Jacobi functions of ``v`` come from the arithmetic-geometric mean and the descending Landen
  transformation started at ``b0 = sqrt(m1)`` (Abramowitz & Stegun 16.4, as Cephes' ``ellpj``),
  with ``dn = sqrt(m1 + m cn^2)``;
- ``K`` = pi / (2 AGM(1, sqrt(m1))); ``F`` and ``Pi`` come from Carlson's symmetric integrals
  (scipy's ``elliprf``, ``elliprj``; DLMF 19.25.5, 19.25.14) fed with ``sin``, ``cos`` and
  ``Delta`` directly, never with an angle.

Accuracy (tests/test_exact.py, against mpmath): a few ulps, except that at ``|v|`` near ``K/2``
the arcsin of the Landen recursion sees an argument ``1 - O(m1^(1/4))`` and the absolute error
grows to about ``1e-16 m1^(-1/4)``: 2e-12 at ``m1 = 1e-22``, far below what the rigid body
needs. The reduction ``u - j K`` carries the rounding of ``u`` and ``K`` (inherent).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import elliprf, elliprj

__all__ = ["carlson_f", "carlson_pi", "ellipk", "jacobi", "jacobi_reduced", "pi_complete"]


def _agm_sequence(m: float, m1: float) -> tuple[list[float], list[float]]:
    """The a_n and c_n of the AGM of (1, sqrt(m1)) until |c_N| < 1.1e-16 a_N."""
    a, b, c = 1.0, math.sqrt(m1), math.sqrt(m)
    As, Cs = [a], [c]
    while abs(c) > 1.1e-16 * a and len(As) < 60:
        a, b, c = 0.5 * (a + b), math.sqrt(a * b), 0.5 * (a - b)
        As.append(a)
        Cs.append(c)
    return As, Cs


def ellipk(m: float, m1: float) -> float:
    """Complete elliptic integral of the first kind, ``K(m) = pi / (2 AGM(1, sqrt(m1)))``."""
    if m1 == 0.0:
        return math.inf
    As, _ = _agm_sequence(m, m1)
    return math.pi / (2.0 * As[-1])


def _landen(v, m: float, m1: float):
    """sn, cn, dn for |v| <= K/2 by the AGM and descending Landen transformation (A&S 16.4)."""
    As, Cs = _agm_sequence(m, m1)
    N = len(As) - 1
    phi = (2.0**N) * As[N] * v
    for n in range(N, 0, -1):
        phi = 0.5 * (phi + np.arcsin(np.clip(Cs[n] / As[n] * np.sin(phi), -1.0, 1.0)))
    sn, cn = np.sin(phi), np.cos(phi)
    return sn, cn, np.sqrt(m1 + m * cn * cn)


def jacobi_reduced(u, m: float, m1: float):
    """Half-period index ``j`` and ``sn, cn, dn`` of ``u_r = u - 2 K j``, ``|u_r| <= K``.

    ``cn(u_r) >= 0``, i.e. ``am(u_r)`` lies in [-pi/2, pi/2]; ``sn(u) = (-1)^j sn(u_r)``,
    ``cn(u) = (-1)^j cn(u_r)``, ``dn(u) = dn(u_r)``. For ``m1 = 0`` (the separatrix) ``j = 0``
    and the functions are ``tanh`` and ``sech``.
    """
    u = np.asarray(u, dtype=float)
    if m1 == 0.0:
        sech = 1.0 / np.cosh(u)
        return np.zeros_like(u), np.tanh(u), sech, sech
    if m == 0.0:
        j = np.rint(u / np.pi)
        ur = u - np.pi * j
        return j, np.sin(ur), np.cos(ur), np.ones_like(ur)
    K = ellipk(m, m1)
    j = np.rint(u / (2.0 * K))
    ur = u - 2.0 * K * j
    k = np.rint(ur / K)  # -1, 0 or 1: nearest quarter period
    v = ur - K * k
    s, c, d = _landen(v, m, m1)
    rk = math.sqrt(m1)
    sn = np.where(k == 0, s, k * c / d)
    cn = np.where(k == 0, c, -k * rk * s / d)
    dn = np.where(k == 0, d, rk / d)
    return j, sn, cn, dn


def jacobi(u, m: float, m1: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``sn, cn, dn`` of ``u`` for parameter ``m`` (``m1 = 1 - m`` given separately)."""
    j, sn, cn, dn = jacobi_reduced(u, m, m1)
    sign = 1.0 - 2.0 * (np.abs(j) % 2)
    return sign * sn, sign * cn, dn


def carlson_f(s, c, m1: float) -> np.ndarray:
    """``F(phi | m)`` for ``|phi| <= pi/2`` from ``s = sin phi``, ``c = cos phi >= 0``."""
    s, c = np.asarray(s, float), np.asarray(c, float)
    return s * elliprf(c * c, c * c + m1 * s * s, 1.0)


def carlson_pi(n: float, s, c, d) -> np.ndarray:
    """``Pi(n; phi | m)`` for ``|phi| <= pi/2`` from ``sin phi``, ``cos phi`` and
    ``Delta = sqrt(1 - m sin^2 phi)`` (DLMF 19.25.14 with ``alpha^2 = n``); ``n < 1``.

    ``Pi(n; phi | m) = int_0^phi d theta / ((1 - n sin^2 theta) sqrt(1 - m sin^2 theta))``.
    """
    s, c, d = (np.asarray(x, float) for x in (s, c, d))
    c2, d2 = c * c, d * d
    return s * elliprf(c2, d2, 1.0) + (n / 3.0) * s**3 * elliprj(c2, d2, 1.0, 1.0 - n * s * s)


def carlson_pi_excess(n: float, s, c, d) -> np.ndarray:
    """``Pi(n; phi | m) - F(phi | m) = (n / 3) sin^3 phi R_J(c^2, Delta^2, 1, 1 - n sin^2 phi)``.

    The second term of DLMF 19.25.14 alone: ``O(n)``, so a caller that knows ``F`` exactly
    (``F(am u) = u``) loses nothing to the cancellation ``Pi - F`` when ``n`` is small.
    """
    s, c, d = (np.asarray(x, float) for x in (s, c, d))
    return (n / 3.0) * s**3 * elliprj(c * c, d * d, 1.0, 1.0 - n * s * s)


def pi_excess_complete(n: float, m1: float) -> float:
    """``Pi(n | m) - K(m) = (n / 3) R_J(0, m1, 1, 1 - n)`` (DLMF 19.25.14 at phi = pi/2)."""
    return float((n / 3.0) * elliprj(0.0, m1, 1.0, 1.0 - n))


def pi_complete(n: float, m1: float) -> float:
    """Complete integral of the third kind ``Pi(n | m)`` (DLMF 19.25.14 at phi = pi/2), ``n < 1``."""
    return float(elliprf(0.0, m1, 1.0) + (n / 3.0) * elliprj(0.0, m1, 1.0, 1.0 - n))
