"""The exact torque-free flow of one body over a step, in double precision, compiled by numba.

A kernels module: imported only on first compiled use (by the splittings' kernels,
:mod:`tumble.dynamics.methods.compiled_split`, and the batch's,
:mod:`tumble.dynamics.methods.compiled_exact`), every function compiled at import by
:func:`tumble.jit.jit` (``cache=True``), so that ``import tumble`` never imports numba.

The formulas are those of :mod:`tumble.dynamics.methods.exact` (Landau & Lifshitz, *Mechanics*,
sec. 37 for omega, sec. 35 and 37 for the attitude ``R = G Rz(phi) Rx(theta) Rz(psi) P`` and the
precession ``phi``; read its module docstring), evaluated for one step ``h`` from the state
``(L, q)``, as the exact-flow splitting (:mod:`tumble.dynamics.methods.exact_split`) needs it
thousands of times per run. Why a second evaluation of the same formulas: the double-double
kernel (:mod:`tumble.dynamics.methods.exact_kernel`) keeps every phase to ~1e-32 and follows
the motion to the separatrix and beyond ``1 - m = 1e-300``, at ~1.3 ms per call for one body
from Python; a splitting step needs neither (its error is far larger) but needs speed, and
numba cannot call scipy's special functions, so the pieces are written here over floats:

- Jacobi's ``sn, cn, dn`` by the AGM and the descending Landen transformation (Abramowitz &
  Stegun 16.4; as Cephes' ``ellpj``) of the phase reduced to ``|u_r| <= K`` by half periods;
- Carlson's ``R_F``, ``R_J``, ``R_C`` by duplication (Carlson, Numer. Algorithms 10 (1995) 13,
  algorithms 1-3 with his series), for ``F = s R_F(c^2, d^2, 1)`` and the excess
  ``Pi - F = (n / 3) s^3 R_J(c^2, d^2, 1, 1 - n s^2)`` (DLMF 19.25.5, 19.25.14);
- the precession ``phi(h) = (|L| / I_r + r1) h + (r1 / p) [x(u) - x(u0)]``, ``x`` the excess
  continued by ``2 j (Pi(n|m) - K)`` over ``j`` half periods, so that ``F(am u) = u`` is used
  exactly and no ``Pi(u) - Pi(u0)`` cancels; the complete ``Pi(n|m) - K`` is evaluated only
  for a step that crosses a half period.

Accuracy (tests/test_compiled.py): against the double-double kernel ~1e-13 in omega and the
attitude away from the separatrix; ``1 - m`` is clamped at 2^-52 (a motion closer to the
separatrix is evaluated as that one), where the phase's condition ``1 / (1 - m)`` costs
accuracy as in any double-precision evaluation.
"""

from __future__ import annotations

import math

import numpy as np

from ...jit import jit
from ...typing import FloatArray
from ..special.quaternion import hamilton_components

__all__ = ["WORK", "free_flow", "free_flow_into", "start_phase"]

_EPS = 2.0 ** -52
#: Doubles of scratch space :func:`free_flow_into` needs: the Landen sequence (2 x 40), omega (3),
#: two quaternions (2 x 4). A caller that flows many times allocates it once (measured: the six
#: small arrays each flow allocated were a quarter of its time).
WORK = 91


@jit(error_model="numpy")
def _rc1(e: float) -> float:
    """``R_C(1, 1 + e)`` (DLMF 19.2.18-19.2.19): atan or atanh of ``sqrt(|e|)`` over it; for
    ``|e| < 1e-3`` their series ``sum (-e)^k / (2k + 1)`` to ``e^5`` (the rest below 1e-19), as
    the later duplication steps of :func:`_rj` mostly ask."""
    if abs(e) < 1e-3:
        return 1.0 + e * (-1.0 / 3.0 + e * (1.0 / 5.0 + e * (-1.0 / 7.0 + e * (1.0 / 9.0 - e / 11.0))))
    if e > 0.0:
        r = math.sqrt(e)
        return math.atan(r) / r
    r = math.sqrt(-e)
    return math.atanh(r) / r


@jit(error_model="numpy")
def _rf(x: float, y: float, z: float) -> float:
    """Carlson's ``R_F(x, y, z)``, at most one argument zero (Carlson 1995, algorithm 1)."""
    a0 = (x + y + z) / 3.0
    q = (3.0 * _EPS) ** (-1.0 / 6.0) * max(abs(a0 - x), abs(a0 - y), abs(a0 - z)) + 1e-300
    a, fac = a0, 1.0
    while fac * q > abs(a):
        sx, sy, sz = math.sqrt(x), math.sqrt(y), math.sqrt(z)
        lam = sx * sy + sx * sz + sy * sz
        x, y, z, a = 0.25 * (x + lam), 0.25 * (y + lam), 0.25 * (z + lam), 0.25 * (a + lam)
        fac *= 0.25
    X, Y = (a - x) / a, (a - y) / a
    Z = -X - Y
    e2, e3 = X * Y - Z * Z, X * Y * Z
    return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) / math.sqrt(a)


@jit(error_model="numpy")
def _rj_series(X: float, Y: float, Z: float) -> float:
    """The series of Carlson's R_J in the last step's relative deviations (Carlson 1995, algorithm 3;
    ``P = -(X + Y + Z) / 2``), to the fifth order."""
    P = -0.5 * (X + Y + Z)
    e2 = X * Y + X * Z + Y * Z - 3.0 * P * P
    e3 = X * Y * Z + 2.0 * e2 * P + 4.0 * P * P * P
    e4 = (2.0 * X * Y * Z + e2 * P + 3.0 * P * P * P) * P
    e5 = X * Y * Z * P * P
    series = (1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0 - 3.0 * e4 / 22.0 - 9.0 * e2 * e3 / 52.0
              + 3.0 * e5 / 26.0)
    return float(series)


@jit(error_model="numpy")
def _rj(x: float, y: float, z: float, p: float) -> float:
    """Carlson's ``R_J(x, y, z, p)``, ``p > 0`` (Carlson 1995, algorithm 3)."""
    a0 = (x + y + z + 2.0 * p) / 5.0
    delta = (p - x) * (p - y) * (p - z)
    q = (0.25 * _EPS) ** (-1.0 / 6.0) * max(abs(a0 - x), abs(a0 - y), abs(a0 - z), abs(a0 - p)) + 1e-300
    a, fac, total = a0, 1.0, 0.0
    while fac * q > abs(a):
        sx, sy, sz, sp = math.sqrt(x), math.sqrt(y), math.sqrt(z), math.sqrt(p)
        lam = sx * sy + sx * sz + sy * sz
        d = (sp + sx) * (sp + sy) * (sp + sz)
        total += fac / d * _rc1(fac * fac * fac * delta / (d * d))
        x, y, z, p, a = 0.25 * (x + lam), 0.25 * (y + lam), 0.25 * (z + lam), 0.25 * (p + lam), 0.25 * (a + lam)
        fac *= 0.25
    return fac * _rj_series((a - x) / a, (a - y) / a, (a - z) / a) / (a * math.sqrt(a)) + 6.0 * total


@jit(error_model="numpy")
def _rf_rj(x: float, y: float, z: float, p: float) -> tuple[float, float]:
    """``R_F(x, y, z)`` and ``R_J(x, y, z, p)`` by one duplication: Carlson's algorithms 1 and 3
    step ``x, y, z`` alike, so both are taken from the same steps, as many as the stricter of
    their two stopping rules asks (:func:`_rf`, :func:`_rj`)."""
    af, aj = (x + y + z) / 3.0, (x + y + z + 2.0 * p) / 5.0
    delta = (p - x) * (p - y) * (p - z)
    qf = (3.0 * _EPS) ** (-1.0 / 6.0) * max(abs(af - x), abs(af - y), abs(af - z)) + 1e-300
    qj = (0.25 * _EPS) ** (-1.0 / 6.0) * max(abs(aj - x), abs(aj - y), abs(aj - z), abs(aj - p)) + 1e-300
    fac, total = 1.0, 0.0
    while fac * qj > abs(aj) or fac * qf > abs(af):
        sx, sy, sz, sp = math.sqrt(x), math.sqrt(y), math.sqrt(z), math.sqrt(p)
        lam = sx * sy + sx * sz + sy * sz
        d = (sp + sx) * (sp + sy) * (sp + sz)
        total += fac / d * _rc1(fac * fac * fac * delta / (d * d))
        x, y, z, p = 0.25 * (x + lam), 0.25 * (y + lam), 0.25 * (z + lam), 0.25 * (p + lam)
        af, aj = 0.25 * (af + lam), 0.25 * (aj + lam)
        fac *= 0.25
    X, Y = (af - x) / af, (af - y) / af
    Z = -X - Y
    e2, e3 = X * Y - Z * Z, X * Y * Z
    rf = (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) / math.sqrt(af)
    return rf, fac * _rj_series((aj - x) / aj, (aj - y) / aj, (aj - z) / aj) / (aj * math.sqrt(aj)) + 6.0 * total


@jit(error_model="numpy")
def _agm(k2: float, kp: float, work: FloatArray) -> int:
    """The AGM of ``(1, k')`` with ``c_i`` (A&S 16.4, 17.6) into ``work[:40]`` and ``work[40:80]``;
    returns its length ``n``: ``K = pi / (2 work[n])``."""
    a, b, c = 1.0, kp, math.sqrt(k2)
    work[0], work[40] = a, c
    n = 0
    while abs(c) > _EPS * a and n < 39:
        a, b, c = 0.5 * (a + b), math.sqrt(a * b), 0.5 * (a - b)
        n += 1
        work[n], work[40 + n] = a, c
    return n


@jit(error_model="numpy")
def _landen(v: float, n: int, kp: float, work: FloatArray) -> tuple[float, float, float]:
    """``sn, cn, dn`` of ``|v| <= K`` by the descending Landen transformation (A&S 16.4) over
    the sequence :func:`_agm` left in ``work``."""
    phi = (2.0 ** n) * work[n] * v
    for i in range(n, 0, -1):
        phi = 0.5 * (phi + math.asin(max(-1.0, min(1.0, work[40 + i] / work[i] * math.sin(phi)))))
    sn, cn = math.sin(phi), math.cos(phi)
    return sn, cn, math.sqrt(cn * cn + kp * kp * sn * sn)


@jit(error_model="numpy")
def _jacobi(v: float, k2: float, kp: float, work: FloatArray) -> tuple[float, float, float]:
    """``sn, cn, dn`` of ``|v| <= K`` for ``m = k2``, ``k' = kp`` (A&S 16.4, the AGM of
    ``(1, k')`` and the descending Landen transformation); ``work[:80]`` holds the sequence."""
    return _landen(v, _agm(k2, kp, work), kp, work)


@jit(error_model="numpy")
def _excess(n: float, s: float, c: float, d: float) -> float:
    """``Pi(n; phi | m) - F(phi | m)`` for ``|phi| <= pi/2`` from ``s, c >= 0, d`` (DLMF 19.25.14)."""
    if n == 0.0 or s == 0.0:
        return 0.0
    return n / 3.0 * s * s * s * _rj(c * c, d * d, 1.0, 1.0 - n * s * s)


@jit(error_model="numpy")
def start_phase(s0: float, c0: float, kp2: float) -> tuple[float, float, float, float]:
    """``sn, cn, dn`` of the reduced phase ``u_r`` (``|u_r| <= K``, so ``cn >= 0``) of a motion
    whose ``sn`` and ``cn`` are proportional to ``s0`` and ``c0``, and the half periods ``j0``
    (-1, 0 or 1) from ``u_r`` to its phase ``u = 2 K j0 + u_r``; ``kp2 = 1 - m``.

    Examples
    --------
    >>> from tumble.dynamics.methods.compiled_flow import start_phase
    >>> start_phase(0.0, -2.0, 0.5)   # cn = -1: one half period from u_r = 0
    (-0.0, 1.0, 1.0, 1.0)
    """
    hyp = math.hypot(s0, c0)
    s0, c0 = s0 / hyp, c0 / hyp
    j0 = 0.0
    if c0 < 0.0:
        j0 = 1.0 if s0 >= 0.0 else -1.0
        s0, c0 = -s0, -c0
    return s0, c0, math.sqrt(c0 * c0 + kp2 * s0 * s0), j0


@jit(error_model="numpy")
def _zxz(phi: float, theta: float, psi: float, out: FloatArray) -> None:
    """``Rz(phi) Rx(theta) Rz(psi)`` as a quaternion, scalar last (special.quaternion.quat_zxz)."""
    sa, ca = math.sin(0.5 * phi), math.cos(0.5 * phi)
    sb, cb = math.sin(0.5 * theta), math.cos(0.5 * theta)
    sc, cc = math.sin(0.5 * psi), math.cos(0.5 * psi)
    out[0], out[1] = sb * (ca * cc + sa * sc), sb * (sa * cc - ca * sc)
    out[2], out[3] = cb * (sa * cc + ca * sc), cb * (ca * cc - sa * sc)


@jit(error_model="numpy")
def _multiply(a: FloatArray, b: FloatArray, out: FloatArray) -> None:
    """Hamilton product ``a (x) b``, scalar last (special.quaternion.quat_multiply); ``out`` may be ``a``."""
    out[0], out[1], out[2], out[3] = hamilton_components(a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3])


@jit(error_model="numpy")
def _tilt(L: FloatArray, upper: bool) -> tuple[float, float]:
    """``theta, psi`` that take the relabelled L (reference axis last) to ``|L| e_z``."""
    if upper:
        li, lj, lr = L[0], L[1], L[2]
    else:
        li, lj, lr = L[1], L[2], L[0]
    return math.atan2(math.hypot(li, lj), lr), math.atan2(li, lj)


@jit(error_model="numpy")
def _steady(q: FloatArray, w0: float, w1: float, w2: float, h: float, turn: FloatArray) -> None:
    """``q <- q (x) exp(w h / 2)``: the turn about a fixed omega, in place (``turn``: 4 doubles of scratch)."""
    spin = math.sqrt(w0 * w0 + w1 * w1 + w2 * w2)
    if spin == 0.0:
        return
    half = 0.5 * spin * h
    s = math.sin(half) / spin
    turn[0], turn[1], turn[2], turn[3] = s * w0, s * w1, s * w2, math.cos(half)
    _multiply(q, turn, q)


@jit(error_model="numpy")
def _gap(I: FloatArray, w0: float, w1: float, w2: float, j: int) -> float:
    """``L^2 - 2 E I_j = sum_i I_i (I_i - I_j) w_i^2``, kg^2 m^4/s^2."""
    return float(I[0] * (I[0] - I[j]) * w0 * w0 + I[1] * (I[1] - I[j]) * w1 * w1 + I[2] * (I[2] - I[j]) * w2 * w2)


@jit(error_model="numpy")
def free_flow_into(I: FloatArray, L: FloatArray, q: FloatArray, h: float,
                   work: FloatArray) -> None:
    """:func:`free_flow` with its scratch space given: ``work``, :data:`WORK` doubles (any values).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_flow import WORK, free_flow, free_flow_into
    >>> I, work = np.array([1.0, 2.0, 3.0]), np.empty(WORK)
    >>> L, q = I * np.array([0.1, 1.0, 0.1]), np.array([0.0, 0.0, 0.0, 1.0])
    >>> free_flow_into(I, L, q, 5.0, work)
    >>> L2, q2 = I * np.array([0.1, 1.0, 0.1]), np.array([0.0, 0.0, 0.0, 1.0])
    >>> free_flow(I, L2, q2, 5.0)   # the same arithmetic, its scratch space its own
    >>> bool(np.array_equal(L, L2) and np.array_equal(q, q2))
    True
    """
    w0, w1, w2 = L[0] / I[0], L[1] / I[1], L[2] / I[2]
    zeros = int(w0 == 0.0) + int(w1 == 0.0) + int(w2 == 0.0)
    if (I[0] == I[2] or zeros >= 2 or (I[0] == I[1] and w2 == 0.0) or (I[1] == I[2] and w0 == 0.0)):
        _steady(q, w0, w1, w2, h, work[87:91])
        return
    w = (w0, w1, w2)
    g = (_gap(I, w0, w1, w2, 0), _gap(I, w0, w1, w2, 1), _gap(I, w0, w1, w2, 2))
    upper = g[1] >= 0.0
    r, c = (2, 0) if upper else (0, 2)  # the dn axis, the cn axis
    Ir, Ic, I2 = I[r], I[c], I[1]
    span = Ir - Ic
    a_c = math.sqrt(abs(g[r] / (Ic * span)))
    a_2 = math.sqrt(abs(g[r] / (I2 * (Ir - I2))))
    a_r = math.sqrt(abs(g[c] / (Ir * span)))
    p = math.sqrt(abs((Ir - I2) * g[c] / (I[0] * I[1] * I[2])))
    if not (a_c > 0.0 and a_2 > 0.0 and a_r > 0.0 and p > 0.0) or not math.isfinite(a_c * a_2 * a_r * p):
        # the components off a principal axis are so small that their squares underflow: the
        # motion is steady to double precision (the double-double kernel follows it further)
        _steady(q, w0, w1, w2, h, work[87:91])
        return
    k2 = min(abs((I2 - Ic) * g[r] / ((Ir - I2) * g[c])), 1.0 - _EPS)
    kp2 = max(abs(span * g[1] / ((Ir - I2) * g[c])), _EPS)
    kp = math.sqrt(kp2)
    sign = 1.0 if w[r] >= 0.0 else -1.0
    # K = pi / (2 AGM(1, k'))
    a, b = 1.0, kp
    while abs(a - b) > _EPS * a:
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    K = 0.5 * math.pi / a
    n = -Ir * (I2 - Ic) / (Ic * (Ir - I2))
    # the phase at the start: sn = w2 / a2, cn = w_c / (s a_c), reduced to cn >= 0
    s0, c0, d0, j0 = start_phase(w[1] / a_2, w[c] / (sign * a_c), kp2)
    u0 = 2.0 * K * j0 + s0 * _rf(c0 * c0, d0 * d0, 1.0)
    x0 = _excess(n, s0, c0, d0)
    # the phase at h, reduced by half periods
    u = u0 + p * h
    j = math.floor(u / (2.0 * K) + 0.5)
    sn, cn, dn = _jacobi(u - 2.0 * K * j, k2, kp, work)
    # the excess gained: its change within the half periods, plus 2 (j - j0) complete excesses
    # (n / 3) R_J(0, k'^2, 1, 1 - n), evaluated only when the step crosses one (a short step
    # of the splitting mostly does not: this R_J was a sixth of the flow's time)
    gained = _excess(n, sn, cn, dn) - x0
    if j != j0 and n != 0.0:
        gained += 2.0 * (j - j0) * (n / 3.0 * _rj(0.0, kp2, 1.0, 1.0 - n))
    if j % 2.0 != 0.0:
        sn, cn = -sn, -cn
    out = work[80:83]
    out[c], out[1], out[r] = sign * a_c * cn, a_2 * sn, sign * a_r * dn
    # the attitude: q <- q (x) P^-1 [B0^-1 Rz(dphi) Rx(theta) Rz(psi)] P
    Ln = math.sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2])
    rate1 = Ln * (Ir - Ic) / (I[0] * I[2])
    dphi = (Ln / Ir + rate1) * h + rate1 / p * gained
    theta0, psi0 = _tilt(L, upper)
    for i in range(3):
        L[i] = I[i] * out[i]
    theta, psi = _tilt(L, upper)
    b0, e = work[83:87], work[87:91]
    _zxz(0.0, theta0, psi0, b0)
    b0[0], b0[1], b0[2] = -b0[0], -b0[1], -b0[2]
    _zxz(dphi, theta, psi, e)
    _multiply(b0, e, e)
    if not upper:  # P^-1 X P turns the vector part: (x, y, z) -> (z, x, y)
        e[0], e[1], e[2] = e[2], e[0], e[1]
    _multiply(q, e, q)



@jit(error_model="numpy")
def free_flow(I: FloatArray, L: FloatArray, q: FloatArray, h: float) -> None:
    """Advance one body's ``L`` (principal frame, kg m^2/s) and ``q`` (body to world, scalar
    last) by the exact torque-free motion over ``h`` (s, any sign), in place.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_flow import free_flow
    >>> L, q = np.array([0.0, 0.0, 3.0]), np.array([0.0, 0.0, 0.0, 1.0])
    >>> free_flow(np.array([1.0, 2.0, 3.0]), L, q, np.pi)  # a half turn about the major axis
    >>> np.round(q, 12) + 0.0
    array([0., 0., 1., 0.])
    """
    free_flow_into(I, L, q, h, np.empty(WORK))
