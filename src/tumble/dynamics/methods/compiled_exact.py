"""The exact torque-free motion of many bodies at common times, compiled: the batch's fast path.

Imported only on first compiled use (by :func:`tumble.dynamics.methods.exact_batch.free_rotation_batch`
and :func:`tumble.dynamics.methods.exact_parameters.elliptic_parameters` for large batches), so
that ``import tumble`` does not import numba; every function is compiled at import by
:func:`tumble.jit.jit` (``cache=True``).

The formulas are those of :mod:`tumble.dynamics.methods.exact` (Landau & Lifshitz, *Mechanics*,
sec. 37 for omega, sec. 35 and 37 for the attitude ``R = G Rz(phi) Rx(theta) Rz(psi) P``),
evaluated as :class:`tumble.dynamics.methods.exact_kernel.EllipticMotion` evaluates them (the
phase ``u = u0 + p t`` reduced by half periods, the precession as a secular part
``A t + B j`` plus a bounded one ``b(u_r) - b(u0_r)``, Legendre's ``Pi`` itself where
``|n| > 1``), but per body in double precision, with the elliptic pieces of
:mod:`tumble.dynamics.methods.compiled_flow` (Carlson's ``R_F`` and ``R_J``); Jacobi's functions by
Bulirsch's descending Gauss transformation (:func:`_sncndn`), the complete ``Pi - K`` by his
``cel``. Each
body costs ~0.7 us of CPU time with its attitude, ~0.3 us without (one sample; measured).

**Where double precision is not enough.** Every angle of the motion carries a relative error of
a few ulps of the phase it reached (the rates ``p``, ``A`` and the half period ``K`` are good
to a few ulps, and ``u = u0 + p t`` multiplies their error by ``t``), and ``1 - m = k'^2``,
formed from the energy-momentum gap ``g2``, loses ``eps / k'^2`` to cancellation next to the
separatrix, which shifts the flips. A body is therefore evaluated here only when

- its fastest phase over the run, ``max(p, |L| / I_r + |L| |I_r - I_o| / (I1 I3)) max|t|``
  (``p`` and the bounds of the precession's rate, exact.py's module docstring; ``|omega| max|t|``
  for a steady spin), is at most :data:`PHASE_MAX` rad,
- ``k'^2 >= KP2_MIN`` (no closer to the separatrix), and
- its moments and ``|omega|`` lie within ``[1e-50, 1e50]`` (no square under- or overflows);

the others (a few in ten thousand for random spins over 20 s) are marked, and the caller
evaluates them in double-double (:class:`~tumble.dynamics.methods.exact_kernel.EllipticMotion`).
Measured against that path (benchmarks/bench_exact_batch.py, tests/test_exact_compiled.py): on
1e6 random bodies at 20 s at most 2.6e-13 relative in omega and 3.5e-13 rad in the attitude
(0.17 % left to double-double); at phases near :data:`PHASE_MAX` up to ~6e-13.
"""

from __future__ import annotations

import math

import numpy as np
from numba import prange

from ...jit import jit
from ...typing import FloatArray
from .compiled_flow import _excess, _multiply, _rf, _rf_rj, _tilt, _zxz, start_phase

__all__ = ["KP2_MIN", "PHASE_MAX", "motion_parallel", "motion_serial", "parameters_parallel", "parameters_serial"]

#: Largest phase (rad) a body reaches here; beyond, the double-double path (module docstring).
PHASE_MAX = 1000.0
#: Smallest ``k'^2 = 1 - m`` evaluated here; closer to the separatrix, the double-double path.
KP2_MIN = 1e-3
#: Magnitudes of the moments and of ``|omega|`` evaluated here (no square under- or overflows).
_TINY, _HUGE = 1e-50, 1e50
_TWO_PI = (6.283185307179586, 2.4492935982947064e-16)  # 2 pi as a double-double
#: Doubles of scratch space per body: the AGM's table (80), four quaternions (16).
WORK = 96


@jit(error_model="numpy")
def _steady(I: FloatArray, w: FloatArray) -> bool:
    """Whether omega is constant, by exact comparisons (exact_kernel.is_steady)."""
    zeros = int(w[0] == 0.0) + int(w[1] == 0.0) + int(w[2] == 0.0)
    return (I[0] == I[2] or zeros >= 2 or (I[0] == I[1] and w[2] == 0.0)
            or (I[1] == I[2] and w[0] == 0.0))


@jit(error_model="numpy")
def _complete_excess(kp: float, n: float) -> float:
    """``Pi(n | m) - K(m)`` for ``n <= 0``: Bulirsch's ``cel(k', 1 - n, 0, n)``, the integral of
    ``n sin^2 / ((1 - n sin^2) sqrt(1 - m sin^2))`` over a quarter period, by his AGM-like
    iteration (Bulirsch, Numer. Math. 13 (1969) 305; Press et al., *Numerical Recipes*, 2nd ed.,
    sec. 6.11, ``cel``), which converges quadratically: the tolerance on ``g`` is the square
    root of the result's."""
    if n == 0.0:
        return 0.0
    qc, a, p, e, em = kp, 0.0, math.sqrt(1.0 - n), kp, 1.0
    b = n / p
    for _ in range(40):
        f = a
        a += b / p
        g = e / p
        b += f * g
        b += b
        p += g
        g = em
        em += qc
        if abs(g - qc) <= g * 1e-9:
            break
        qc = 2.0 * math.sqrt(e)
        e = qc * em
    return 0.5 * math.pi * (b + a * em) / (em * (em + p))


@jit(error_model="numpy")
def _gauss(kp2: float, work: FloatArray) -> tuple[int, float]:
    """The AGM of ``(1, k')`` for :func:`_sncndn`: its means into ``work[:40]``, its geometric
    means into ``work[40:80]``; returns the levels and the final mean (``K = pi / 2 mean``)."""
    a, emc, c, levels = 1.0, kp2, 1.0, 0
    for i in range(39):
        levels = i + 1
        work[i] = a
        emc = math.sqrt(emc)
        work[40 + i] = emc
        c = 0.5 * (a + emc)
        if abs(a - emc) <= 1e-8 * a:  # quadratic convergence: the next step is below eps
            break
        emc *= a
        a = c
    return levels, c


@jit(error_model="numpy")
def _sncndn(u: float, levels: int, mean: float, work: FloatArray) -> tuple[float, float, float]:
    """``sn, cn, dn`` of ``|u| <= K`` by Bulirsch's descending Gauss transformation over the AGM
    of :func:`_gauss` (Bulirsch, Numer. Math. 7 (1965) 78; Press et al., *Numerical Recipes*,
    2nd ed., sec. 6.11, ``sncndn``): one sine and cosine and a division a level, no arcsine."""
    v = u * mean
    sn, cn, dn = math.sin(v), math.cos(v), 1.0
    if sn == 0.0:
        return sn, cn, dn
    a = cn / sn
    c = mean * a
    for i in range(levels - 1, -1, -1):
        b = work[i]
        a *= c
        c *= dn
        dn = (work[40 + i] + a) / (b + a)
        a = c / b
    a = 1.0 / math.sqrt(c * c + 1.0)
    sn = a if sn >= 0.0 else -a
    return sn, c * sn, dn


@jit(error_model="numpy")
def _parameters(I: FloatArray, w: FloatArray) -> tuple[bool, float, float, float, float, float, float, float]:
    """``upper, p, k^2, k'^2, a1, a2, a3`` of the motion through ``w`` (Landau & Lifshitz sec.
    37, exact.py's module docstring) and ``g2``, in double precision, the gaps
    ``g_j = sum_i I_i (I_i - I_j) w_i^2`` written without ``L^2 - 2 E I_j``'s cancellation."""
    w0, w1, w2 = w[0], w[1], w[2]
    g0 = I[1] * (I[1] - I[0]) * w1 * w1 + I[2] * (I[2] - I[0]) * w2 * w2
    g1 = I[0] * (I[0] - I[1]) * w0 * w0 + I[2] * (I[2] - I[1]) * w2 * w2
    g2 = I[0] * (I[0] - I[2]) * w0 * w0 + I[1] * (I[1] - I[2]) * w1 * w1
    upper = g1 >= 0.0
    if upper:  # about the major axis: r = 3 (dn), c = 1 (cn)
        gr, gc, Ir, Ic = g2, g0, I[2], I[0]
    else:
        gr, gc, Ir, Ic = g0, g2, I[0], I[2]
    span, rest = Ir - Ic, Ir - I[1]
    p = math.sqrt(abs(rest * gc / (I[0] * I[1] * I[2])))
    k2 = abs((I[1] - Ic) * gr / (rest * gc))
    kp2 = abs(span * g1 / (rest * gc))
    a_c = math.sqrt(abs(gr / (Ic * span)))
    a_2 = math.sqrt(abs(gr / (I[1] * rest)))
    a_r = math.sqrt(abs(gc / (Ir * span)))
    if upper:
        return upper, p, k2, kp2, a_c, a_2, a_r, g1
    return upper, p, k2, kp2, a_r, a_2, a_c, g1


@jit(error_model="numpy")
def _in_range(I: FloatArray, w: FloatArray) -> bool:
    """Whether the moments and ``|omega|`` lie within ``[_TINY, _HUGE]`` (no square under- or overflows)."""
    size = float(max(abs(w[0]), abs(w[1]), abs(w[2])))
    return bool(_TINY <= I[0] and I[2] <= _HUGE and _TINY <= size <= _HUGE)


@jit(error_model="numpy")
def _live(p: float, a1: float, a2: float, a3: float) -> bool:
    """Whether the rate and the amplitudes are positive and finite: a component so small that
    its square underflowed (omega = (1e-200, 1e-200, 1)) leaves the body to double-double."""
    return bool(p > 0.0 and a1 > 0.0 and a2 > 0.0 and a3 > 0.0 and math.isfinite(p * a1 * a2 * a3))


@jit(error_model="numpy")
def _turn(I: FloatArray, w: FloatArray, q0: FloatArray, t: FloatArray, t_max: float, omega: FloatArray,
          quat: FloatArray, work: FloatArray) -> bool:
    """A steady spin: ``q0 (x) exp(|w| t / 2 e_w)``, omega constant; False beyond PHASE_MAX."""
    spin = math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
    if not _in_range(I, w) or spin * t_max > PHASE_MAX:
        return False
    turn = work[80:84]
    for k in range(t.shape[0]):
        half = 0.5 * spin * t[k]
        s = math.sin(half) / spin
        turn[0], turn[1], turn[2], turn[3] = s * w[0], s * w[1], s * w[2], math.cos(half)
        _multiply(q0, turn, quat[k])
        for i in range(3):
            omega[k, i] = w[i]
    return True


@jit(error_model="numpy")
def motion_body(I: FloatArray, w: FloatArray, q0: FloatArray, t: FloatArray, t_max: float, attitude: bool,
                omega: FloatArray, quat: FloatArray, work: FloatArray) -> bool:
    """One body's omega (T, 3) and attitude (T, 4) at times ``t`` into ``omega`` and ``quat``;
    False (nothing written) for a body the double-double path must take (module docstring).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_exact import WORK, motion_body
    >>> I, w, q0, t = np.array([1.0, 2.0, 3.0]), np.array([0.1, 1.0, 0.1]), np.array([0.0, 0.0, 0.0, 1.0]), np.array([0.0, 5.0])
    >>> omega, quat = np.empty((2, 3)), np.empty((2, 4))
    >>> motion_body(I, w, q0, t, 5.0, True, omega, quat, np.empty(WORK))
    True
    >>> bool(np.allclose(omega[0], w)), bool(np.isclose(np.sum(I * omega[1]**2), np.sum(I * w**2)))   # energy kept
    (True, True)
    """
    if _steady(I, w):
        return _turn(I, w, q0, t, t_max, omega, quat, work)
    if not _in_range(I, w):
        return False
    upper, p, k2, kp2, a1, a2, a3, _ = _parameters(I, w)
    if not (kp2 >= KP2_MIN and _live(p, a1, a2, a3)):
        return False
    r, c = (2, 0) if upper else (0, 2)  # the dn axis, the cn axis
    Ir, Ic, Im = I[r], I[c], I[1]
    a_r, a_c = (a3, a1) if upper else (a1, a3)
    kp = math.sqrt(kp2)
    levels, mean = _gauss(kp2, work)  # the AGM of (1, k'), once: K, and sn, cn, dn at every sample
    K = 0.5 * math.pi / mean
    sign = 1.0 if w[r] >= 0.0 else -1.0
    n = -Ir * (Im - Ic) / (Ic * (Ir - Im))
    # the precession's rate lies between rate0 and rate0 + rate1 (n <= 0: 1 / (1 - n sn^2) in (0, 1])
    Ln = math.sqrt((I[0] * w[0]) ** 2 + (I[1] * w[1]) ** 2 + (I[2] * w[2]) ** 2)
    rate0 = Ln / Ir
    rate1 = Ln * (Ir - Ic) / (I[0] * I[2])
    if max(p, abs(rate0) + abs(rate1)) * t_max > PHASE_MAX:
        return False
    # the phase at t = 0: sn = w2 / a2, cn = w_c / (s a_c), beyond +-pi/2 one half period on;
    # u0_r = F and the excess Pi - F there from one duplication (omega alone takes the same F)
    s0, c0, d0, j0 = start_phase(w[1] / a2, w[c] / (sign * a_c), kp2)
    x0 = 0.0
    if n != 0.0 and s0 != 0.0:
        rf, rj = _rf_rj(c0 * c0, d0 * d0, 1.0, 1.0 - n * s0 * s0)
        x0 = n / 3.0 * s0 * s0 * s0 * rj  # as _excess(n, s0, c0, d0)
    else:
        rf = _rf(c0 * c0, d0 * d0, 1.0)
    f0 = s0 * rf
    u0 = 2.0 * K * j0 + f0
    # phi = A t + B (j - j0) + b(u_r) - b(u0_r) (exact_kernel's secular and bounded parts)
    A, B, b0, scale, pi_mode = 0.0, 0.0, 0.0, 0.0, False
    if attitude and n != 0.0:
        scale = rate1 / p
        excess_c = _complete_excess(kp, n)
        pi_mode = abs(n) > 1.0  # Pi itself, F + (Pi - F), so that rate1 t and the excess do not cancel
        if pi_mode:
            A, B, b0 = rate0, 2.0 * scale * (K + excess_c), scale * (f0 + x0)
        else:
            A, B, b0 = rate0 + rate1, 2.0 * scale * excess_c, scale * x0
    elif attitude:
        A = rate0 + rate1
    L, back, e = work[84:87], work[88:92], work[92:96]
    if attitude:
        for i in range(3):
            L[i] = I[i] * w[i]
        theta0, psi0 = _tilt(L, upper)
        _zxz(0.0, theta0, psi0, back)
        back[0], back[1], back[2] = -back[0], -back[1], -back[2]
    for k in range(t.shape[0]):
        u = u0 + p * t[k]
        j = math.floor(u / (2.0 * K) + 0.5)
        ur = u - 2.0 * K * j
        sn, cn, dn = _sncndn(ur, levels, mean, work)
        odd = j % 2.0 != 0.0
        omega[k, c] = sign * a_c * (-cn if odd else cn)
        omega[k, 1], omega[k, r] = a2 * (-sn if odd else sn), sign * a_r * dn
        if not attitude:
            continue
        bounded = scale * ((ur if pi_mode else 0.0) + _excess(n, sn, cn, dn)) if scale != 0.0 else 0.0
        secular = A * t[k] + B * (j - j0)
        turns = math.floor(secular / _TWO_PI[0] + 0.5)  # to [-pi, pi], as the double-double path reduces it
        phi = ((secular - turns * _TWO_PI[0]) - turns * _TWO_PI[1]) + (bounded - b0)
        for i in range(3):
            L[i] = I[i] * omega[k, i]
        theta, psi = _tilt(L, upper)
        _zxz(phi, theta, psi, e)
        _multiply(back, e, e)
        if not upper:  # P^-1 X P turns the vector part: (x, y, z) -> (z, x, y)
            e[0], e[1], e[2] = e[2], e[0], e[1]
        _multiply(q0, e, quat[k])
    return True


@jit(error_model="numpy")
def motion_serial(I: FloatArray, w: FloatArray, q0: FloatArray, t: FloatArray, attitude: bool, omega: FloatArray,
                  quat: FloatArray, done: np.ndarray) -> None:
    """:func:`motion_body` for every body on one thread: moments ``I`` and ``w`` (N, 3),
    attitudes ``q0`` (N, 4), times ``t`` (T,), into ``omega`` (N, T, 3), ``quat`` (N, T, 4) and
    ``done`` (N,), False where the double-double path must take the body.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_exact import motion_serial
    >>> I, w = np.array([[1.0, 2.0, 3.0], [1.0, 2.0, 3.0]]), np.array([[0.1, 1.0, 0.1], [1e-9, 1.0, 1e-9]])
    >>> omega, quat, done = np.empty((2, 1, 3)), np.empty((2, 1, 4)), np.empty(2, dtype=np.bool_)
    >>> motion_serial(I, w, np.tile([0.0, 0.0, 0.0, 1.0], (2, 1)), np.array([1.0]), True, omega, quat, done)
    >>> done.tolist()   # the second is next to the separatrix (k'^2 ~ 1e-18)
    [True, False]
    """
    t_max = 0.0
    for k in range(t.shape[0]):
        t_max = max(t_max, abs(t[k]))
    work = np.empty(WORK)
    for b in range(I.shape[0]):
        done[b] = motion_body(I[b], w[b], q0[b], t, t_max, attitude, omega[b], quat[b], work)


@jit(error_model="numpy", parallel=True)
def motion_parallel(I: FloatArray, w: FloatArray, q0: FloatArray, t: FloatArray, attitude: bool, omega: FloatArray,
                    quat: FloatArray, done: np.ndarray) -> None:
    """:func:`motion_serial` with the bodies spread over every core (``numba.prange``), in
    blocks of 256 bodies (one scratch space each): the same arithmetic per body.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_exact import motion_parallel, motion_serial
    >>> rng = np.random.default_rng(0)
    >>> I, w, q = np.sort(rng.uniform(1.0, 2.0, (600, 3)), axis=1), rng.normal(size=(600, 3)), np.tile([0.0, 0.0, 0.0, 1.0], (600, 1))
    >>> a = np.empty((600, 2, 3)), np.empty((600, 2, 4)), np.empty(600, dtype=np.bool_)
    >>> b = np.empty((600, 2, 3)), np.empty((600, 2, 4)), np.empty(600, dtype=np.bool_)
    >>> motion_serial(I, w, q, np.array([0.0, 3.0]), True, *a)
    >>> motion_parallel(I, w, q, np.array([0.0, 3.0]), True, *b)
    >>> all(bool(np.array_equal(x[a[2]], y[a[2]])) for x, y in zip(a, b))
    True
    """
    t_max = 0.0
    for k in range(t.shape[0]):
        t_max = max(t_max, abs(t[k]))
    N = I.shape[0]
    blocks = (N + 255) // 256
    for block in prange(blocks):
        work = np.empty(WORK)
        for b in range(256 * block, min(N, 256 * block + 256)):
            done[b] = motion_body(I[b], w[b], q0[b], t, t_max, attitude, omega[b], quat[b], work)


@jit(error_model="numpy")
def parameters_body(I: FloatArray, w: FloatArray, out: FloatArray, b: int | np.int64) -> bool:
    """``upper, p, m, 1 - m, a1, a2, a3, k, k'`` (:class:`~tumble.dynamics.methods.exact_parameters.EllipticParameters`'s
    fields) of one motion into the column ``out[:, b]`` (out of shape (9, N): each field a
    contiguous row); False where the double-double path must take it (``k'^2 < KP2_MIN``, a
    steady spin, magnitudes out of range).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_exact import parameters_body
    >>> out = np.empty((9, 1))
    >>> parameters_body(np.array([1.0, 2.0, 3.0]), np.array([0.1, 1.0, 0.1]), out, 0), round(float(out[2, 0] + out[3, 0]), 15)
    (True, 1.0)
    """
    if _steady(I, w) or not _in_range(I, w):
        return False
    upper, p, k2, kp2, a1, a2, a3, _ = _parameters(I, w)
    if not (kp2 >= KP2_MIN and _live(p, a1, a2, a3)):
        return False
    k2, kp2 = min(k2, 1.0), min(kp2, 1.0)
    out[0, b], out[1, b], out[2, b], out[3, b] = 1.0 if upper else 0.0, p, k2, kp2
    out[4, b], out[5, b], out[6, b], out[7, b], out[8, b] = a1, a2, a3, math.sqrt(k2), math.sqrt(kp2)
    return True


@jit(error_model="numpy")
def parameters_serial(I: FloatArray, w: FloatArray, out: FloatArray, done: np.ndarray) -> None:
    """:func:`parameters_body` for N motions, ``I`` and ``w`` (N, 3), into ``out`` (9, N) and ``done`` (N,).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_exact import parameters_serial
    >>> out, done = np.empty((9, 1)), np.empty(1, dtype=np.bool_)
    >>> parameters_serial(np.array([[1.0, 2.0, 3.0]]), np.array([[0.0, 0.0, 1.0]]), out, done)
    >>> done.tolist()   # a steady spin: the double-double path says what it has
    [False]
    """
    for b in range(I.shape[0]):
        done[b] = parameters_body(I[b], w[b], out, b)


@jit(error_model="numpy", parallel=True)
def parameters_parallel(I: FloatArray, w: FloatArray, out: FloatArray, done: np.ndarray) -> None:
    """:func:`parameters_serial` with the motions spread over every core (``numba.prange``).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.compiled_exact import parameters_parallel
    >>> out, done = np.empty((9, 2)), np.empty(2, dtype=np.bool_)
    >>> parameters_parallel(np.array([[1.0, 2.0, 3.0]] * 2), np.array([[0.1, 1.0, 0.1], [1.0, 0.1, 0.1]]), out, done)
    >>> done.tolist(), out[0].tolist()   # about the major axis, then about the minor one
    ([True, True], [1.0, 0.0])
    """
    for b in prange(I.shape[0]):  # prange's index is unsigned: as int64, parameters_body compiles once
        done[b] = parameters_body(I[b], w[b], out, np.int64(b))
