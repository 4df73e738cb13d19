"""Jacobi elliptic functions and Legendre's integrals that keep their accuracy near m = 1.

Why not ``scipy.special.ellipj`` alone: it takes the parameter ``m`` only. Near the separatrix
of the free rigid body ``m = 1 - m1`` with ``m1`` as small as 1e-20, and ``1 - m`` cannot hold
``m1`` in double precision, so the period ``K ~ log(4 / sqrt(m1))`` and everything after it
would lose most of their digits. Here every function takes both ``m`` and ``m1 = 1 - m``,
formed by the caller without cancellation:

- the Jacobi functions by the arithmetic-geometric mean and descending Landen transformation
  started from ``b0 = sqrt(m1)`` (Abramowitz & Stegun 16.4; the algorithm of Cephes' ``ellpj``),
  with ``dn = sqrt(m1 + m cn^2)``;
- ``K``, ``F`` and ``Pi`` through Carlson's symmetric integrals ``R_F``, ``R_J`` from scipy
  (DLMF 19.25.5, 19.25.14), with ``Delta^2 = 1 - m sin^2 = cos^2 + m1 sin^2``.

All functions broadcast over ``u`` / ``phi``; ``m``, ``m1`` and ``n`` are scalars.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import elliprf, elliprj

__all__ = ["amplitude", "ellipf", "ellipk", "ellippi", "jacobi"]


def _agm_sequence(m: float, m1: float) -> tuple[list[float], list[float]]:
    """The a_n and c_n of the AGM of (1, sqrt(m1)) down to |c_N| < 2^-53 a_N."""
    a, b, c = 1.0, math.sqrt(m1), math.sqrt(m)
    As, Cs = [a], [c]
    while abs(c) > 1.1e-16 * a and len(As) < 60:
        a, b, c = 0.5 * (a + b), math.sqrt(a * b), 0.5 * (a - b)
        As.append(a)
        Cs.append(c)
    return As, Cs


def ellipk(m: float, m1: float) -> float:
    """Complete elliptic integral of the first kind ``K(m) = pi / (2 AGM(1, sqrt(m1)))``."""
    if m1 == 0.0:
        return math.inf
    As, _ = _agm_sequence(m, m1)
    return math.pi / (2.0 * As[-1])


def amplitude(u, m: float, m1: float) -> np.ndarray:
    """Jacobi amplitude ``am(u | m)``, any real u (A&S 16.4 with periodic reduction)."""
    u = np.asarray(u, dtype=float)
    if m1 == 0.0:  # m = 1: am(u) = gd(u), the Gudermannian
        return 2.0 * np.arctan(np.tanh(0.5 * u))
    if m == 0.0:
        return u.copy()
    K = ellipk(m, m1)
    # am(u + 2K j) = am(u) + j pi: reduce to |u_r| <= K, where the AGM recursion is accurate
    j = np.rint(u / (2.0 * K))
    ur = u - 2.0 * K * j
    As, Cs = _agm_sequence(m, m1)
    N = len(As) - 1
    phi = (2.0**N) * As[N] * ur
    for n in range(N, 0, -1):
        phi = 0.5 * (phi + np.arcsin(np.clip(Cs[n] / As[n] * np.sin(phi), -1.0, 1.0)))
    return phi + j * np.pi


def jacobi(u, m: float, m1: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``sn, cn, dn, am`` of ``u`` for parameter ``m`` (``m1 = 1 - m`` given separately)."""
    phi = amplitude(u, m, m1)
    if m1 == 0.0:
        sech = 1.0 / np.cosh(np.asarray(u, float))
        return np.tanh(u), sech, sech, phi
    sn, cn = np.sin(phi), np.cos(phi)
    dn = np.sqrt(m1 + m * cn * cn)  # = sqrt(1 - m sn^2) without cancellation
    return sn, cn, dn, phi


def _reduce(phi):
    """phi = phi_r + j pi with |phi_r| <= pi/2."""
    phi = np.asarray(phi, float)
    j = np.rint(phi / np.pi)
    return phi - j * np.pi, j


def ellipf(phi, m: float, m1: float) -> np.ndarray:
    """Incomplete integral of the first kind ``F(phi | m)``, any real phi (DLMF 19.25.5)."""
    pr, j = _reduce(phi)
    s, c = np.sin(pr), np.cos(pr)
    F = s * elliprf(c * c, c * c + m1 * s * s, 1.0)
    if np.any(j != 0):
        F = F + 2.0 * j * ellipk(m, m1)
    return F


def ellippi(n: float, phi, m: float, m1: float) -> np.ndarray:
    """Incomplete integral of the third kind, ``Pi(n; phi | m)``, any real phi.

    ``Pi(n; phi | m) = int_0^phi d theta / ((1 - n sin^2 theta) sqrt(1 - m sin^2 theta))``
    (DLMF 19.2.7 with ``alpha^2 = n``), by DLMF 19.25.14:
    ``s R_F(c^2, Delta^2, 1) + (n / 3) s^3 R_J(c^2, Delta^2, 1, 1 - n s^2)``, and
    ``Pi(n; phi + j pi) = Pi(n; phi) + 2 j Pi(n | m)``. Requires ``n < 1``.
    """
    pr, j = _reduce(phi)
    s, c = np.sin(pr), np.cos(pr)
    c2, d2 = c * c, c * c + m1 * s * s
    P = s * elliprf(c2, d2, 1.0) + (n / 3.0) * s**3 * elliprj(c2, d2, 1.0, 1.0 - n * s * s)
    if np.any(j != 0):
        complete = elliprf(0.0, m1, 1.0) + (n / 3.0) * elliprj(0.0, m1, 1.0, 1.0 - n)
        P = P + 2.0 * j * complete
    return P
