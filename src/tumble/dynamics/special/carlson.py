"""Legendre's integrals of the first and third kind, safe against underflow, and their complete
values in double-double precision.

Incomplete integrals (double precision, vectorised) from ``s = sin phi``, ``c = cos phi >= 0`` and
``d = Delta = sqrt(1 - m s^2) = sqrt(c^2 + m1 s^2)``, never from ``phi`` itself (DLMF 19.25.5,
19.25.14 with ``z = 1``)::

    F(phi | m)              = s R_F(c^2, d^2, 1)
    Pi(n; phi | m) - F      = (n / 3) s^3 R_J(c^2, d^2, 1, 1 - n s^2)

Near ``phi = pi/2`` on a motion close to the separatrix ``c`` and ``d`` can both be below 1e-154,
so that ``c^2`` and ``d^2`` underflow and ``R_F(0, 0, 1)`` is infinite although the integral is
finite (~ ln(4 / (c + d))). So one duplication step is taken first, with its ``lambda`` formed
from ``c`` and ``d`` without squaring them (DLMF 19.26.18 and 19.26.20, the latter checked
against mpmath to 50 digits)::

    R_F(x, y, z)    = 2 R_F(x + l, y + l, z + l),     l = sqrt(xy) + sqrt(yz) + sqrt(zx)
    R_J(x, y, z, p) = 2 R_J(x + l, y + l, z + l, p + l) + (6 / D) R_C(1, 1 + (p-x)(p-y)(p-z) / D^2),
                      D = (sqrt p + sqrt x)(sqrt p + sqrt y)(sqrt p + sqrt z),

where, with ``p = 1 - n s^2``, ``(p - x)(p - y)(p - z) = -n (1 - n)(m - n) s^6`` exactly (no
cancellation for ``n <= 0 <= m``), and unchanged by the shift. For R_J three steps are taken,
since scipy's ``elliprj`` itself loses accuracy (1e-3 at ``x = y = 1e-170``, measured against
mpmath) when two arguments are below ~1e-150. Only ``c = d = 0`` (``phi = pi/2`` with ``m1``
below the smallest double) is left, and there the complete values are used.

Complete integrals ``K(m)`` and ``Pi(n | m)`` (double-double; the kernels take floats or
arrays): ``K = pi / (2 AGM(1, k'))`` (Abramowitz & Stegun 17.6), and ``Pi(n | m) = cel(k', 1 - n,
1, 1)`` by Bulirsch's ``cel`` (Bulirsch, "Numerical calculation of elliptic integrals and elliptic
functions III", Numer. Math. 13 (1969) 305; as in Press et al., *Numerical Recipes*, 2nd ed., sec.
6.11), quadratically convergent (a Gauss AGM in disguise) and without cancellation for ``n <= 0``.
For ``k' < 2^-60`` both are shifted from ``k'_60 = k' 2^(E + 60)`` (``k' = mantissa 2^E``): ``K(k') = K(k'_60) + (-60 - E)
ln 2`` and ``Pi(n | k') = Pi(n | k'_60) + (-60 - E) ln 2 / (1 - n)``, exact to ``O(k'^2 ln k')``
< 1e-34 (from ``K = ln(4 / k') + O(k'^2 ln k')``, DLMF 19.12.1, and the same logarithmic
singularity with weight 1 / (1 - n) in Pi; both checked against mpmath at 200 digits).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TypeAlias, cast

import numpy as np
from scipy.special import elliprc, elliprf, elliprj

from ...typing import ArrayLike, BoolArray, FloatArray, FloatOrArray, IntArray
from . import ddouble as dd
from .ddouble import DoubleDouble

__all__ = ["complete_integrals", "legendre_f", "legendre_pi_excess"]


def _duplicate(c: FloatArray, d: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Arguments of R_F(c^2, d^2, 1) after one duplication step, and the factor 2."""
    lam = c * d + c + d
    return c * c + lam, d * d + lam, 1.0 + lam


def legendre_f(s: ArrayLike, c: ArrayLike, d: ArrayLike, K: ArrayLike = np.inf) -> FloatArray:
    """``F(phi | m)`` for ``|phi| <= pi/2`` from ``s``, ``c >= 0``, ``d`` (module docstring);
    ``K`` (the complete value) is returned, with the sign of ``s``, where ``c = d = 0``.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.special import ellipkinc
    >>> from tumble.dynamics.special.carlson import legendre_f
    >>> phi, m = 0.9, 0.7
    >>> s, c = np.sin(phi), np.cos(phi)
    >>> f = legendre_f(s, c, np.sqrt(1.0 - m * s * s))
    >>> bool(np.isclose(f, ellipkinc(phi, m), rtol=1e-14))   # scipy's F(phi | m)
    True
    >>> float(legendre_f(1e-200, 0.0, 0.0, K=460.0))   # c = d = 0: the complete value K
    460.0
    """
    s, c, d = (np.asarray(x, float) for x in (s, c, d))
    x, y, z = _duplicate(c, d)
    with np.errstate(divide="ignore", invalid="ignore"):
        f = 2.0 * s * elliprf(x, y, z)
    return cast(FloatArray, np.where(d > 0, f, np.copysign(1.0, s) * K))


#: Duplication steps before scipy's R_J, whose accuracy fails (1e-3) when two of its arguments
#: are below ~1e-150 (and holds at 1e-100); each step takes a tiny argument x to ~sqrt(x):
#: three take 1e-320 to 1e-40. One suffices where ``c + d > 1e-90``, none where ``c, d > 1e-50``.
_RJ_STEPS = 3


def legendre_pi_excess(
    n: FloatOrArray, s: ArrayLike, c: ArrayLike, d: ArrayLike, m: FloatOrArray | None = None, excess_complete: ArrayLike = -np.inf
) -> FloatArray:
    """``Pi(n; phi | m) - F(phi | m)`` for ``|phi| <= pi/2`` and ``n <= 0`` (module docstring);
    ``excess_complete = Pi(n | m) - K(m)`` is returned, with the sign of ``s``, where
    ``c = d = 0``. Without ``m``, ``(m - n) s^2`` is formed as ``1 - n s^2 - d^2``: an absolute
    error of round-off in the small correction ``e`` to ``R_C(1, 1 + e)``, harmless.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.integrate import quad
    >>> from tumble.dynamics.special.carlson import legendre_pi_excess
    >>> n, m, phi = -0.5, 0.7, 1.2
    >>> s, c = np.sin(phi), np.cos(phi)
    >>> excess = legendre_pi_excess(n, s, c, np.sqrt(1.0 - m * s * s))
    >>> quadrature = quad(lambda t: (1 / (1 - n * np.sin(t) ** 2) - 1) / np.sqrt(1 - m * np.sin(t) ** 2), 0, phi)[0]
    >>> bool(np.isclose(excess, quadrature, rtol=1e-12))   # Pi(n; phi | m) - F(phi | m) by quadrature
    True
    """
    s, c, d = (np.asarray(x, float) for x in (s, c, d))
    s2 = s * s
    p = 1.0 - n * s2
    m_n = (m - n) * s2 if m is not None else np.maximum(p - d * d, 0.0)
    # (p - x)(p - y)(p - z), the same after every shift by lambda
    delta = (-n * (1.0 - n)) * m_n * (s2 * s2)
    roots = [c, d, np.ones_like(c), np.sqrt(p)]  # sqrt x, y, z, p
    args = [c * c, d * d, np.ones_like(c), p]
    rj = np.zeros_like(c)
    # none needed where c^2, d^2 > 1e-100; after one step every argument exceeds c + d
    steps = 0 if np.all(np.minimum(c, d) > 1e-50) else 1 if np.all(c + d > 1e-90) else _RJ_STEPS
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for step in range(steps):
            sx, sy, sz, sp = roots
            lam = sx * sy + sy * sz + sz * sx
            D = (sp + sx) * (sp + sy) * (sp + sz)
            rj = rj + 2.0**step * 6.0 / D * elliprc(1.0, 1.0 + delta / (D * D))
            args = [a + lam for a in args]
            roots = [np.sqrt(a) for a in args]
        rj = rj + 2.0**steps * elliprj(*args)
        value = (n / 3.0) * s * s2 * rj
    return cast(FloatArray, np.where(d > 0, value, np.copysign(1.0, s) * excess_complete))


#: The state of :func:`_iterate`: a tuple of double-doubles (floats, or arrays elementwise).
_State: TypeAlias = tuple[DoubleDouble, ...]
#: What a step of :func:`_iterate` returns: whether to stop (a bool, or a mask elementwise), the
#: state to leave with if so, and a function that gives the next state otherwise.
_StepResult: TypeAlias = tuple["bool | BoolArray", _State, Callable[[], _State]]
_Step: TypeAlias = Callable[[_State], _StepResult]


def _one_like(x: DoubleDouble) -> DoubleDouble:
    """The double-double 1 shaped as the double-double ``x``: floats stay Python floats (the
    one-body path, fast), arrays give arrays (the batched path)."""
    return (1.0, 0.0) if np.ndim(x[0]) == 0 else (np.ones_like(x[0]), np.zeros_like(x[0]))


def _iterate(state: _State, step: _Step, limit: int = 40) -> _State:
    """Iterate ``state = step(state)`` until it stops, at most ``limit`` times; ``state`` is a
    tuple of double-doubles, of floats (one value) or of arrays (elementwise).

    ``step(state)`` returns ``(stop, stopped, advance)``: whether to stop, the state to leave with
    if so, and a function that gives the next state otherwise. On floats this is the plain loop
    with its ``break`` (the one-body path, without numpy's overhead on single values); on arrays
    each element leaves the loop with the state it stopped in and only the others go on, so that
    every element gets the float loop's answer exactly (:mod:`tumble.dynamics.methods.exact_kernel`).
    """
    if np.ndim(state[0][0]) == 0:
        for _ in range(limit):
            stop, stopped, advance = step(state)
            if stop:
                return stopped
            state = advance()
        return state

    def take(x: _State, sel: int | BoolArray | IntArray) -> _State:  # arrays on this branch
        return tuple((cast(FloatArray, a)[sel], cast(FloatArray, b)[sel]) for a, b in x)

    def put(idx: IntArray, x: _State) -> None:
        for o, v in zip(out, x):
            o[0][idx], o[1][idx] = v

    out = tuple((cast(FloatArray, a).copy(), cast(FloatArray, b).copy()) for a, b in state)
    idx = np.arange(np.size(state[0][0]))
    for _ in range(limit):
        stop, stopped, advance = step(state)
        put(idx[stop], take(stopped, stop))
        go = ~stop
        idx, state = idx[go], take(advance(), go)
        if not idx.size:
            break
    put(idx, state)  # the limit reached: as the float loop leaves them
    return out


def cel(kc: DoubleDouble, pp: DoubleDouble) -> DoubleDouble:
    """Bulirsch's ``cel(kc, pp, 1, 1)`` in double-double for ``kc = k'`` (a double-double in
    (2^-61, 1]) and ``pp = 1 - n >= 1`` (a double-double), of floats or of arrays (elementwise,
    the same arithmetic: :func:`_iterate`). Numerical Recipes, 2nd ed., sec. 6.11."""
    one = _one_like(kc)
    p = dd.sqrt(pp)

    def step(state: _State) -> _StepResult:
        a, b, p, e, em, qc = state
        f, inv = a, dd.div((1.0, 0.0), p)
        a = dd.add(a, dd.mul(b, inv))
        g = dd.mul(e, inv)
        b = dd.add(b, dd.mul(f, g))
        b = (2.0 * b[0], 2.0 * b[1])
        p = dd.add(g, p)
        g, em = em, dd.add(qc, em)
        stop = cast(FloatOrArray, abs(g[0] - qc[0])) <= 1e-17 * g[0]  # quadratic: the last step gains the other half

        def advance() -> _State:
            qc = dd.sqrt(e)
            qc = (2.0 * qc[0], 2.0 * qc[1])
            return a, b, p, dd.mul(qc, em), em, qc

        return stop, (a, b, p, e, em, qc), advance

    a, b, p, _, em, _ = _iterate((one, dd.div(one, p), p, kc, one, kc), step)
    return dd.div(dd.mul(dd.PI_2, dd.add(b, dd.mul(a, em))), dd.mul(em, dd.add(em, p)))


def agm_k(kp: DoubleDouble) -> DoubleDouble:
    """``K = pi / (2 AGM(1, k'))`` in double-double (A&S 17.6) for ``k'`` a double-double of
    floats or of arrays (elementwise: :func:`_iterate`); quadratically convergent: once
    ``|a - b| <= 1e-17 a`` the mean is the limit to ~1e-34."""

    def step(state: _State) -> _StepResult:
        a, b = state
        return cast(FloatOrArray, abs(a[0] - b[0])) <= 1e-17 * a[0], state, lambda: (dd.mul_d(dd.add(a, b), 0.5), dd.sqrt(dd.mul(a, b)))

    a, b = _iterate((_one_like(kp), kp), step)
    return dd.div(dd.PI_2, dd.mul_d(dd.add(a, b), 0.5))


def complete_integrals(
    n: FloatOrArray | DoubleDouble, kp: DoubleDouble, exponent: int | IntArray = 0
) -> tuple[DoubleDouble, DoubleDouble]:
    """``K(m)`` and ``Pi(n | m)`` as double-doubles, ``n <= 0`` (a double or a double-double),
    for ``k' = sqrt(1 - m) = kp * 2^exponent`` (``kp`` a double-double, ``0 < k' <= 1``).

    ``exponent`` lets ``k'`` be far below the smallest double (module docstring). Floats give
    floats (one motion, at Python's speed); arrays give arrays, elementwise, with the same
    arithmetic (:func:`_iterate`): one body and a batch get the same values.

    Examples
    --------
    >>> import math
    >>> from scipy.special import ellipk
    >>> from tumble.dynamics.special.carlson import complete_integrals
    >>> K, Pi = complete_integrals(0.0, (math.sqrt(0.5), 0.0))   # m = 1/2, n = 0: Pi = K
    >>> math.isclose(K[0], ellipk(0.5), rel_tol=1e-15), K == Pi
    (True, True)
    >>> K, Pi = complete_integrals(-1.0, (1.0, 0.0))   # m = 0: K = pi / 2, Pi(n | 0) = pi / (2 sqrt(1 - n))
    >>> math.isclose(K[0], math.pi / 2), math.isclose(Pi[0], math.pi / (2 * math.sqrt(2)))
    (True, True)
    >>> K, _ = complete_integrals(0.0, (1.0, 0.0), -1000)   # k' = 2^-1000, far below a double's reach
    >>> math.isclose(K[0], math.log(4.0) + 1000 * math.log(2.0), rel_tol=1e-15)   # K = ln(4 / k')
    True
    """
    e: int | IntArray  # k' = mantissa 2^e
    shift: int | IntArray  # k' = k'_60 2^-shift
    scalar = np.ndim(kp[0]) == 0 and np.ndim(exponent) == 0 and np.ndim(n[0] if isinstance(n, tuple) else n) == 0
    if scalar:
        kp, exponent = (float(kp[0]), float(kp[1])), int(exponent)
        n = (float(n[0]), float(n[1])) if isinstance(n, tuple) else (float(n), 0.0)
        e = math.frexp(kp[0])[1] + exponent  # k' = mantissa 2^e, mantissa in [1/2, 1)
        shift = max(-61 - e, 0)  # k' = k'_60 2^-shift
        kp = (math.ldexp(kp[0], exponent + shift), math.ldexp(kp[1], exponent + shift))
    else:
        n = (np.asarray(n[0], float), np.asarray(n[1], float)) if isinstance(n, tuple) else (np.asarray(n, float), np.zeros(np.shape(n)))
        e = cast(IntArray, np.frexp(kp[0])[1] + exponent)
        shift = np.maximum(-61 - e, 0)
        kp = (np.ldexp(kp[0], exponent + shift), np.ldexp(kp[1], exponent + shift))
    one_n = dd.add(_one_like(kp), dd.neg(n))  # 1 - n, without rounding n first
    K = agm_k(kp)
    if scalar:
        Pi = K if n[0] == 0.0 else cel(kp, one_n)
    else:
        Pi = dd.where(n[0] == 0.0, K, cel(kp, one_n))  # n = 0 (a symmetric top): Pi = K
    if np.any(shift > 0):
        log = dd.mul_d(dd.LN2, cast(FloatOrArray, shift * 1.0))
        shifted = dd.add(K, log), dd.add(Pi, dd.div(log, one_n))
        K, Pi = shifted if scalar else (dd.where(shift > 0, shifted[0], K), dd.where(shift > 0, shifted[1], Pi))
    return K, Pi
