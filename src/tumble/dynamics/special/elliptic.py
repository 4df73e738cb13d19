"""Jacobi elliptic functions and Legendre's integrals that keep their accuracy near m = 1,
at any argument, and down to ``1 - m`` below the smallest double.

Why not ``scipy.special.ellipj`` / ``ellipkinc``: they take the parameter ``m`` only. Near the
separatrix of the free rigid body ``m = 1 - m1`` with ``m1`` as small as 1e-320, and ``1 - m``
cannot hold ``m1`` in double precision (at m1 = 1e-15 ``ellipj`` is off by O(1)). They also go
through the amplitude ``am(u)``, which is ill-conditioned exactly where the body lingers near a
saddle: ``cn = cos(am)`` is then tiny and loses its relative accuracy. So here

- a :class:`Modulus` carries ``k = sqrt(m)`` and ``k' = sqrt(m1)`` (each representable where
  ``m1`` or ``m`` is not: ``k' = 1e-160`` for ``m1 = 1e-320``) and ``K`` in double-double;
- ``u`` is reduced to ``|v| <= K/2`` about the nearest multiple of the quarter period ``K``, in
  double-double (:mod:`tumble.dynamics.special.ddouble`), so the reduced argument is right and lies in
  that range at *any* ``u``, and the shift formulas ``sn(v + K) = cd v``,
  ``cn(v + K) = -k' sd v``, ``dn(v + K) = k' nd v`` (DLMF 22.4.3) give cn and dn with full
  *relative* accuracy near their zeros;
- for ``m <= 1/2`` the functions of ``v`` come from the AGM of ``(1, k')`` and the descending
  Landen transformation (Abramowitz & Stegun 16.4, as Cephes' ``ellpj``), whose arcsin sees an
  argument below ``(c_1 / a_1) <= 0.172``; ``dn = hypot(k', k cn)``;
- for ``m > 1/2`` (where that arcsin's argument would approach 1 and cost cn its relative
  accuracy near ``|v| = K/2``) from Jacobi's imaginary transformation (DLMF 22.6.iv:
  ``sn(iz, k) = i sc(z, k')``, ``cn(iz, k) = nc(z, k')``, ``dn(iz, k) = dc(z, k')``) with the
  descending Landen transformation of the complementary modulus: the AGM of ``(1, k)`` with
  ``c_0 = k'``, ``psi_N = 2^N a_N v``, ``psi_{n-1} = (psi_n + asinh((c_n / a_n) sinh psi_n)) / 2``
  (the amplitude stays imaginary, ``phi = -i psi``), and ``sn = tanh psi_0``,
  ``cn = sech psi_0``, ``dn = hypot(1, k' sinh psi_0) / cosh psi_0``: real, with
  ``c_1 / a_1 = (1 - k) / (1 + k) <= 0.172`` and a well-conditioned asinh;
- the AGM's ``c_{n+1} = c_n^2 / (4 a_{n+1})`` (equal to ``(a_n - b_n) / 2``) avoids cancellation;
- ``K``, ``F`` and ``Pi`` come from :mod:`tumble.dynamics.special.carlson`.

Accuracy (tests/test_exact.py and tests/test_exact_hardening.py, against mpmath at 40 digits):
sn, cn, dn to a few ulps *relative*, also near the zeros of cn and dn and at ``|v| = K/2``, for
``1 - m`` from 1 down to 0, given the argument; ``sn^2 + cn^2 = 1`` and ``dn^2 + m sn^2 = 1`` to
round-off at any argument.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, cast

import numpy as np

from ...typing import ArrayLike, BoolArray, FloatArray, FloatOrArray, IntArray
from . import ddouble as dd
from .carlson import complete_integrals, legendre_f, legendre_pi_excess
from .ddouble import DoubleDouble

__all__ = [
    "Modulus",
    "agm_tables",
    "carlson_pi",
    "ellipk",
    "ellipk_kp",
    "jacobi",
    "jacobi_reduced",
]


def agm_tables(b0: ArrayLike, c0: ArrayLike) -> tuple[FloatArray, FloatArray, IntArray]:
    """The ``a_n`` and ``c_n`` of the AGM of ``(1, b0)``, ``c0^2 = 1 - b0^2``, for each element,
    each stopping once ``c_N <= 1.1e-16 a_N`` (A&S 16.4); ``c_{n+1} = c_n^2 / (4 a_{n+1})``
    without cancellation.

    Returns arrays ``a`` and ``c`` of shape ``(L,) + shape(b0)`` (an element that stopped keeps
    its last values) and the number of steps ``N`` each element took.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.special.elliptic import agm_tables
    >>> a, c, steps = agm_tables([0.6], [0.8])   # the AGM of (1, 0.6), c0^2 = 1 - 0.6^2
    >>> int(steps[0]), a.shape
    (5, (6, 1))
    >>> bool(np.isclose(np.pi / (2 * a[steps[0], 0]), 1.9953027776647294))   # K(m = 0.64) = pi / (2 AGM)
    True
    """
    b0, c0 = np.asarray(b0, float), np.asarray(c0, float)
    a, b, c = np.ones_like(b0), b0, c0
    As, Cs = [a], [c]
    count = np.zeros(b0.shape, int)
    for _ in range(59):
        go = c > 1.1e-16 * a
        if not np.any(go):
            break
        a2 = 0.5 * (a + b)
        a, b, c = np.where(go, a2, a), np.where(go, np.sqrt(a * b), b), np.where(go, c * c / (4.0 * a2), c)
        As.append(a)
        Cs.append(c)
        count += go
    return np.array(As), np.array(Cs), count


@dataclass(frozen=True)
class Modulus:
    """The modulus of a family of Jacobi functions: ``k = sqrt(m)``, ``k' = sqrt(1 - m)``.

    One modulus (floats) or one per body (arrays of shape (N,)): the same code serves the one
    motion and the batch (:mod:`tumble.dynamics.methods.exact_kernel`).

    Parameters
    ----------
    k, kp : float or ndarray, shape (N,)
        ``k`` and ``k'``, in [0, 1], ``k^2 + k'^2 = 1`` to round-off; ``k'`` may be 0 (or
        underflow) while ``K`` stays finite, see ``K``.
    K : tuple of float or of ndarray
        The quarter period as a double-double; infinite for the separatrix ``k' = 0``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.special.elliptic import Modulus
    >>> (j1, j2), odd, sn, cn, dn = Modulus.from_parameter(0.5, 0.5).reduce((np.array([0.3]), np.zeros(1)))
    >>> bool(np.isclose(sn[0] ** 2 + cn[0] ** 2, 1.0))
    True
    """

    k: FloatOrArray
    kp: FloatOrArray
    K: DoubleDouble
    #: Set by ``__post_init__``: whether ``m > 1/2`` (the imaginary transformation), and the
    #: :func:`agm_tables` of the modulus taken (``k`` there, ``k'`` otherwise).
    _route: tuple[BoolArray, FloatArray, FloatArray, IntArray] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        big = np.asarray(self.k > self.kp)  # m > 1/2: the imaginary transformation
        As, Cs, count = agm_tables(np.where(big, self.k, self.kp), np.where(big, self.kp, self.k))
        object.__setattr__(self, "_route", (big, As, Cs, count))

    @classmethod
    def from_parameter(cls, m: float, m1: float) -> Modulus:
        """From ``m`` and ``m1 = 1 - m``, each formed by the caller without cancellation.

        ``K`` is that of ``m1`` as given (``k'`` taken in double-double), so that the
        reduction of a large argument adds no error of its own.

        Examples
        --------
        >>> import math
        >>> from scipy.special import ellipk
        >>> from tumble.dynamics.special.elliptic import Modulus
        >>> mod = Modulus.from_parameter(0.75, 0.25)
        >>> round(mod.k ** 2 + mod.kp ** 2, 15), round(float(mod.K[0] - ellipk(0.75)), 14)   # k^2 + k'^2 = 1; K as scipy's
        (1.0, 0.0)
        >>> K = Modulus.from_parameter(1.0, 1e-300).K   # m1 = 1e-300, k' = 1e-150: K = ln(4 / k'), finite
        >>> round(K[0], 6), round(math.log(4e150), 6)
        (346.774058, 346.774058)
        """
        if not m1 > 0:
            return cls(math.sqrt(m), 0.0, (math.inf, 0.0))
        e = math.frexp(m1)[1] // 2  # m1 = x 4^e: its root 2^e sqrt(x), however small m1
        kp = dd.sqrt((math.ldexp(m1, -2 * e), 0.0))
        return cls(math.sqrt(m), math.sqrt(m1), complete_integrals(0.0, kp, e)[0])

    def _column(self, ndim: int) -> Callable[[FloatOrArray | BoolArray], Any]:
        """Shape one value per body to broadcast against arrays of ``ndim`` dimensions whose
        first axis runs over the bodies (a single modulus: unchanged)."""
        if np.ndim(self.k) == 0:
            return lambda x: x
        return lambda x: np.reshape(x, np.shape(x) + (1,) * (ndim - np.ndim(x)))

    # -- v in [-K/2, K/2] ----------------------------------------------------------------
    def _landen(self, v: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        big, As, Cs, count = self._route
        col = self._column(np.ndim(v))
        x = col(np.ldexp(1.0, count) * np.take_along_axis(As, count[None, ...], axis=0)[0]) * v
        # one modulus (or a batch all on one side of m = 1/2, all with as many steps) takes one
        # branch and no masks: the one-body path keeps its speed
        route = "hyper" if np.all(big) else "circ" if not np.any(big) else "mixed"
        least, bigc = (int(count.min()) if count.size else 0), col(big)
        for n in range(len(As) - 1, 0, -1):
            ratio = col(Cs[n] / As[n])
            if route != "circ":
                hyper = 0.5 * (x + np.arcsinh(ratio * np.sinh(x)))
            if route != "hyper":
                circ = 0.5 * (x + np.arcsin(np.clip(ratio * np.sin(x), -1.0, 1.0)))
            step = hyper if route == "hyper" else circ if route == "circ" else np.where(bigc, hyper, circ)
            x = step if n <= least else np.where(col(n <= count), step, x)
        kp, k = col(self.kp), col(self.k)
        if route == "hyper":
            ch = np.cosh(x)
            return np.tanh(x), 1.0 / ch, np.hypot(1.0, kp * np.sinh(x)) / ch
        cn = np.cos(x)
        if route == "circ":
            return np.sin(x), cn, np.hypot(kp, k * cn)
        ch = np.cosh(x)
        return (np.where(bigc, np.tanh(x), np.sin(x)), np.where(bigc, 1.0 / ch, cn),
                np.where(bigc, np.hypot(1.0, kp * np.sinh(x)) / ch, np.hypot(kp, k * cn)))

    # -- any u --------------------------------------------------------------------------
    def reduce(self, u: DoubleDouble) -> tuple[tuple[FloatArray, FloatArray], BoolArray, FloatArray, FloatArray, FloatArray]:
        """Exact reduction of ``u`` (a double-double ``(hi, lo)`` of arrays) by half periods.

        Returns ``(j1, j2)`` (the number of half periods ``j = j1 + j2``, as two integral
        floats, since beyond 2^53 their sum is not exact), ``odd`` (whether ``j`` is odd), and
        ``sn, cn, dn`` of ``u_r = u - 2 K j`` with ``|u_r| <= K``, ``cn(u_r) >= 0``. The phase
        is kept to ~1e-32 of ``u``; beyond ``|u| = 1e30``, where that is no longer below 0.01,
        ``u`` is first reduced by ``fmod(u, 4 K)`` (exact, but with ``K`` rounded to double):
        the functions then keep their identities only. On the separatrix (``K`` infinite: no
        period) ``j = 0`` and the functions are ``tanh`` and ``sech``. With one modulus per
        body, ``u`` has one row per body.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.special.elliptic import Modulus
        >>> mod = Modulus.from_parameter(0.75, 0.25)
        >>> u = 7.0 * mod.K[0] + 0.1   # three and a half periods 2K, and 0.1
        >>> (j1, j2), odd, sn, cn, dn = mod.reduce((np.array([u]), np.zeros(1)))
        >>> int(j1[0] + j2[0]), bool(odd[0]), bool(cn[0] >= 0)   # u - 2 K j lies in [-K, K]
        (4, False, True)
        >>> round(float(sn[0] ** 2 + cn[0] ** 2), 14), round(float(dn[0] ** 2 + 0.75 * sn[0] ** 2), 14)
        (1.0, 1.0)
        """
        u = (np.asarray(u[0], float), np.asarray(u[1], float))
        col = self._column(u[0].ndim)
        K = (col(self.K[0]), col(self.K[1]))
        separatrix = np.isinf(K[0])
        with np.errstate(over="ignore"):
            sech = 1.0 / np.cosh(u[0]) if np.any(separatrix) else None
        if np.all(separatrix):
            zero = np.zeros_like(u[0])
            sech_all = cast(FloatArray, sech)  # not None: every row is on the separatrix
            return (zero, zero), np.zeros(u[0].shape, bool), np.tanh(u[0]), sech_all, sech_all
        twoK = (2.0 * K[0], 2.0 * K[1])
        lost = np.abs(u[0]) > 1e30  # no phase left to keep: stay on the curve, at least
        if np.any(lost):
            u = (np.where(lost, np.fmod(u[0], 4.0 * K[0]), u[0]), np.where(lost, 0.0, u[1]))
        with np.errstate(invalid="ignore"):  # nan on the separatrix rows, replaced below
            j1 = np.rint(u[0] / twoK[0])
            r = dd.add(u, dd.neg(dd.mul_d(twoK, j1)))
            j2 = np.rint(r[0] / twoK[0])  # 0 but at the rounding edge, or where j1 > 2^53
            r = dd.add(r, dd.neg(dd.mul_d(twoK, j2)))
            q = np.rint(r[0] / K[0])  # -1, 0 or 1: the nearest quarter period
            v = dd.add(r, dd.neg(dd.mul_d(K, q)))
            s, c, d = self._landen(cast(FloatArray, v[0] + v[1]))
        kp = col(self.kp)
        with np.errstate(divide="ignore", invalid="ignore"):
            sn = np.where(q == 0, s, q * c / d)
            cn = np.where(q == 0, c, -q * kp * s / d)
            dn = np.where(q == 0, d, kp / d)
        odd = (np.fmod(np.abs(j1), 2.0) + np.abs(j2)) % 2.0 == 1.0
        dn = np.where(np.isfinite(dn), dn, 0.0)
        if sech is not None:  # some bodies on the separatrix, the others periodic
            zero = np.zeros_like(u[0])
            j1, j2 = np.where(separatrix, zero, j1), np.where(separatrix, zero, j2)
            odd = odd & ~separatrix
            sn, cn, dn = np.where(separatrix, np.tanh(u[0]), sn), np.where(separatrix, sech, cn), np.where(separatrix, sech, dn)
        return (j1, j2), odd, sn, cn, dn


def ellipk(m: float, m1: float) -> float:
    """Complete elliptic integral of the first kind ``K(m)`` (Bulirsch's ``cel``, via
    :func:`tumble.dynamics.special.carlson.complete_integrals`); ``m1 = 1 - m`` given separately.

    Examples
    --------
    >>> import math
    >>> from scipy.special import ellipk as scipy_ellipk
    >>> from tumble.dynamics.special.elliptic import ellipk
    >>> math.isclose(ellipk(0.3, 0.7), scipy_ellipk(0.3), rel_tol=1e-15), ellipk(0.0, 1.0) == math.pi / 2
    (True, True)
    >>> round(ellipk(1.0, 1e-20), 6), round(math.log(4.0 / 1e-10), 6)   # near m = 1: K ~ ln(4 / k')
    (24.412145, 24.412145)
    """
    if m1 == 0.0:
        return math.inf
    return cast(float, complete_integrals(0.0, (math.sqrt(m1), 0.0))[0][0])  # floats in, floats out


def ellipk_kp(kp: ArrayLike) -> FloatArray:
    """``K(m)`` from ``k' = sqrt(1 - m)`` (array_like, in [0, 1]), vectorised:
    ``pi / (2 AGM(1, k'))`` (Abramowitz & Stegun 17.6); ``inf`` for ``k' = 0``.

    For callers that hold ``k'`` (:class:`tumble.dynamics.methods.exact.EllipticParameters` ``.kp``),
    which stays representable where ``1 - m = k'^2`` underflows: ``k' = 1e-200`` gives
    ``K = ln(4 / k') = 461.9`` where ``1 - m`` is 0 in double precision.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.special import ellipk
    >>> from tumble.dynamics.special.elliptic import ellipk_kp
    >>> K = ellipk_kp([1.0, 0.5, 1e-200, 0.0])
    >>> bool(np.isclose(K[1], ellipk(0.75))), round(float(K[2]), 1), float(K[3])
    (True, 461.9, inf)
    >>> bool(np.isclose(K[0], np.pi / 2))
    True
    """
    kp = np.asarray(kp, float)
    a, b = np.ones_like(kp), kp
    for _ in range(12):  # converged to round-off for every k' > 0 a double holds
        a, b = 0.5 * (a + b), np.sqrt(a * b)
    return np.where(kp > 0, np.pi / (a + b), np.inf)


def jacobi_reduced(u: ArrayLike, m: float, m1: float) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Half-period index ``j`` and ``sn, cn, dn`` of ``u_r = u - 2 K j``, ``|u_r| <= K``.

    ``cn(u_r) >= 0``, i.e. ``am(u_r)`` lies in [-pi/2, pi/2]; ``sn(u) = (-1)^j sn(u_r)``,
    ``cn(u) = (-1)^j cn(u_r)``, ``dn(u) = dn(u_r)``. For ``m1 = 0`` (the separatrix) ``j = 0``
    and the functions are ``tanh`` and ``sech``. The reduction is exact (double-double), so the
    three functions stay on their curves (``sn^2 + cn^2 = 1``) at any ``u``.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.special import ellipj, ellipk
    >>> from tumble.dynamics.special.elliptic import jacobi_reduced
    >>> u = 3.0 * ellipk(0.5) + 0.2   # nearest multiple of 2K: 4K, so j = 2
    >>> j, sn, cn, dn = jacobi_reduced(u, 0.5, 0.5)
    >>> int(j), bool(cn >= 0)
    (2, True)
    >>> s, c, d, _ = ellipj(u, 0.5)   # sn(u) = (-1)^j sn(u_r)
    >>> bool(np.allclose([sn, cn, dn], [s, c, d], atol=1e-13))
    True
    """
    u = np.asarray(u, dtype=float)
    (j1, j2), _, sn, cn, dn = Modulus.from_parameter(m, m1).reduce((u, np.zeros_like(u)))
    return j1 + j2, sn, cn, dn


def jacobi(u: ArrayLike, m: float, m1: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    """``sn, cn, dn`` of ``u`` for parameter ``m`` (``m1 = 1 - m`` given separately).

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.special import ellipj
    >>> from tumble.dynamics.special.elliptic import jacobi
    >>> u = np.linspace(-5.0, 5.0, 11)
    >>> sn, cn, dn = jacobi(u, 0.8, 0.2)
    >>> bool(np.allclose(np.array([sn, cn, dn]), np.array(ellipj(u, 0.8)[:3]), atol=1e-14))   # scipy's
    True
    >>> bool(np.allclose(sn**2 + cn**2, 1.0) and np.allclose(dn**2 + 0.8 * sn**2, 1.0))
    True
    >>> sn, cn, dn = jacobi([1e20], 0.8, 0.2)   # any argument: still on the curves
    >>> round(float(sn[0] ** 2 + cn[0] ** 2), 14)
    1.0
    >>> sn, cn, dn = jacobi([2.0], 1.0, 0.0)   # the separatrix: tanh and sech
    >>> bool(np.isclose(sn[0], np.tanh(2.0)) and np.isclose(cn[0], 1 / np.cosh(2.0)))
    True
    """
    u = np.asarray(u, dtype=float)
    _, odd, sn, cn, dn = Modulus.from_parameter(m, m1).reduce((u, np.zeros_like(u)))
    sign = np.where(odd, -1.0, 1.0)
    return sign * sn, sign * cn, dn


def carlson_pi(n: float, s: ArrayLike, c: ArrayLike, d: ArrayLike) -> FloatArray:
    """``Pi(n; phi | m)`` for ``|phi| <= pi/2`` from ``sin phi``, ``cos phi`` and
    ``Delta = sqrt(1 - m sin^2 phi)`` (DLMF 19.25.14 with ``alpha^2 = n``); ``n <= 0``.

    ``Pi(n; phi | m) = int_0^phi d theta / ((1 - n sin^2 theta) sqrt(1 - m sin^2 theta))``.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.integrate import quad
    >>> from tumble.dynamics.special.elliptic import carlson_pi
    >>> n, m, phi = -2.0, 0.4, 1.0
    >>> s, c = np.sin(phi), np.cos(phi)
    >>> value = carlson_pi(n, s, c, np.sqrt(1 - m * s * s))
    >>> integrand = lambda t: 1 / ((1 - n * np.sin(t) ** 2) * np.sqrt(1 - m * np.sin(t) ** 2))
    >>> bool(np.isclose(value, quad(integrand, 0, phi)[0], rtol=1e-13))
    True
    """
    return legendre_f(s, c, d) + legendre_pi_excess(n, s, c, d)
