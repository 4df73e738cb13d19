"""The exact torque-free motion of N rigid bodies at common times, vectorised over both.

The mathematics is that of :mod:`tumble.dynamics.methods.exact` (Landau & Lifshitz, *Mechanics*,
sec. 37; read its module docstring), evaluated step for step in the same floating-point
operations, on arrays of bodies instead of one body at a time:

- the parameters ``p``, ``k``, ``k'``, the amplitudes and the characteristic ``n`` from
  :func:`tumble.dynamics.methods.exact_parameters.scaled_core` (which broadcasts);
- the complete integrals ``K(m)`` and ``Pi(n | m)`` in double-double by the AGM (Abramowitz &
  Stegun 17.6) and Bulirsch's ``cel`` (Numer. Math. 13 (1969) 305), with the shift for
  ``k' < 2^-61`` of :mod:`tumble.dynamics.special.carlson`, whose kernels (:func:`~tumble.dynamics.
  carlson.agm_k`, :func:`~tumble.dynamics.special.carlson.cel`) take arrays: each body stops iterating
  where the one-body loop stops (a mask), so the values are the one-body ones;
- the phase ``u = u0 + p t`` and its reduction by half periods in double-double, and ``sn, cn,
  dn`` of the reduced phase by the AGM and descending Landen transformation (``m <= 1/2``) or
  Jacobi's imaginary transformation (``m > 1/2``) of :class:`tumble.dynamics.special.elliptic.Modulus`,
  each body with its own number of Landen steps;
- the attitude ``R(t) = G Rz(phi) Rx(theta) Rz(psi) P`` with quaternion algebra written out on
  arrays (Hamilton product, scalar last, as scipy), the precession ``phi`` from Legendre's
  integrals (:func:`tumble.dynamics.special.carlson.legendre_f`, :func:`~tumble.dynamics.special.carlson.
  legendre_pi_excess`, vectorised already), its secular part in double-double.

Steady rotations (spheres, spins about a principal axis, a symmetric top in its degenerate
plane) are rotations about the fixed omega by ``|omega| t`` (double-double, reduced mod 2 pi).
Bodies exactly on the separatrix (``k' = 0``: no period), and any whose parameters come out
non-finite, are handed to :class:`tumble.dynamics.methods.exact.FreeRotation` one by one.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from ..special import ddouble as dd
from ..special.carlson import agm_k, cel, legendre_f, legendre_pi_excess
from ..special.quaternion import quat_conjugate, quat_multiply, quat_zxz
from .exact import MAX_PHASE, FreeRotation, check_phase_limit, is_steady
from .exact_parameters import scaled_core

__all__ = ["free_rotation_batch"]

#: Bodies x samples evaluated at once: a few dozen arrays of this many doubles, which stay in
#: cache (measured here: 10% faster than 1 << 17), but at least _MIN_BODIES bodies per chunk,
#: so that each chunk's per-body work is not dominated by Python's overhead on many samples.
_CHUNK = 1 << 14
_MIN_BODIES = 64


def free_rotation_batch(moments, omega0, quat0, t, *, attitude: bool = True):
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
        rad/s, equal to :meth:`FreeRotation.omega` to a few ulps of each body's amplitudes.
    quat : ndarray, shape (N, T, 4) or None
        Principal frame to world, equal to :meth:`FreeRotation.attitude` to ~1e-15 rad.

    Raises
    ------
    ValueError
        If a body's phase would exceed :data:`tumble.dynamics.methods.exact.MAX_PHASE`, naming the body.
    """
    I, w, q0 = (np.asarray(a, float) for a in (moments, omega0, quat0))
    t = np.asarray(t, float)
    _check_phases(I, w, t)
    N, T = len(I), len(t)
    omega = np.empty((N, T, 3))
    quat = np.empty((N, T, 4)) if attitude else None
    steady = is_steady(I, w)
    idx = np.flatnonzero(steady)
    if len(idx):
        omega[idx] = w[idx, None, :]
        if attitude:
            quat[idx] = _steady_attitude(w[idx], q0[idx], t)
    rest = np.flatnonzero(~steady)
    step = max(_MIN_BODIES, _CHUNK // max(T, 1))
    single = []
    for start in range(0, len(rest), step):
        chunk = rest[start:start + step]
        motion = _Elliptic(I[chunk], w[chunk], t)
        ok = motion.ok
        omega[chunk[ok]] = motion.omega
        if attitude:
            quat[chunk[ok]] = motion.attitude(q0[chunk[ok]])
        single.extend(chunk[~ok].tolist())
    for i in single:  # the separatrix and anything the arrays could not hold
        one = FreeRotation(I[i], w[i], Rotation.from_quat(q0[i]))
        omega[i] = one.omega(t)
        if attitude:
            quat[i] = one.attitude(t).as_quat()
    return omega, quat


def _check_phases(I, w, t) -> None:
    """:func:`check_phase_limit` for the bodies that could come near it (a cheap bound first)."""
    if not t.size:
        return
    t_max = float(np.max(np.abs(t)))
    with np.errstate(over="ignore"):
        bound = np.linalg.norm(I * w, axis=1) / I[:, 0] * t_max
    for i in np.flatnonzero(~(bound <= 1e-3 * MAX_PHASE)):
        try:
            check_phase_limit(I[i], w[i], t_max)
        except ValueError as err:
            raise ValueError(f"omega0[{i}]: {err}") from None


def _times(x, t):
    """``x t`` for double-doubles ``x`` of shape (n,) and times ``t`` (n, T) or (T,), scaled by
    powers of two first (:func:`tumble.dynamics.special.ddouble.mul_scaled`, elementwise)."""
    e = np.frexp(x[0])[1][:, None]
    return dd.mul_d((np.ldexp(x[0][:, None], -e), np.ldexp(x[1][:, None], -e)), np.ldexp(t, e))


def _steady_attitude(w, q0, t) -> np.ndarray:
    """``q0 (x) exp(|w| t e_w)``: the turn about the fixed omega, its angle in double-double."""
    spin, e = dd.norm([(x, np.zeros_like(x)) for x in w.T])
    axis = np.where(spin[0][:, None] > 0, np.ldexp(w, -e[:, None]) / np.where(spin[0] > 0, spin[0], 1.0)[:, None], w)
    angle = 0.5 * dd.reduce_2pi(_times(dd.ldexp(spin, e), t))
    turn = np.concatenate([np.sin(angle)[..., None] * axis[:, None, :], np.cos(angle)[..., None]], axis=-1)
    return quat_multiply(q0[:, None, :], turn)


def _pick(cond, x, y):
    """``x`` where ``cond``, else ``y``, for double-doubles."""
    return np.where(cond, x[0], y[0]), np.where(cond, x[1], y[1])


def _complete_k(kp_m, kp_e):
    """``K`` (a double-double) for ``k' = kp_m 2^kp_e``, elementwise (carlson's
    ``complete_integrals``, with its shift for ``k' < 2^-61``); also the shifted ``k'`` and the
    shift, for :func:`_complete_pi`."""
    e = np.frexp(kp_m[0])[1] + kp_e
    shift = np.maximum(-61 - e, 0)
    kp = (np.ldexp(kp_m[0], kp_e + shift), np.ldexp(kp_m[1], kp_e + shift))
    K = agm_k(kp)
    log = dd.mul_d(dd.LN2, shift.astype(float))
    return _pick(shift > 0, dd.add(K, log), K), kp, shift


def _complete_pi(n, kp, shift, K):
    """``Pi(n | m)`` (a double-double), ``n <= 0``, from :func:`_complete_k`'s answers."""
    one_n = dd.add((np.ones_like(n[0]), np.zeros_like(n[0])), dd.neg(n))
    Pi = _pick(n[0] == 0.0, K, cel(kp, one_n))  # n = 0 (a symmetric top): Pi = K
    log = dd.mul_d(dd.LN2, shift.astype(float))
    return _pick(shift > 0, dd.add(Pi, dd.div(log, one_n)), Pi)


def _agm_tables(b0, c0):
    """The ``a_n``, ``c_n`` of the AGM of ``(1, b0)`` for each element (elliptic's ``_agm``):
    arrays of shape (L, n) and the number of steps each element takes."""
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


class _Elliptic:
    """The elliptic (non-steady) motions of a chunk of bodies at times ``t``; ``ok`` marks the
    bodies computed here (the rest go to :class:`FreeRotation`)."""

    def __init__(self, I, w, t):
        with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
            self._parameters(I, w)
            self._phase(t)

    def _parameters(self, I, w) -> None:
        core = scaled_core(w, I)
        upper = np.asarray(core["upper"])
        p = core["p"]
        (k_m, k_e), (kp_m, kp_e) = core["k"], core["kp"]
        k = np.minimum(np.ldexp(k_m[0], k_e), 1.0)
        top = k == 0.0  # a symmetric top: circular functions, exactly
        kp_m = (np.where(top, 1.0, kp_m[0]), np.where(top, 0.0, kp_m[1]))
        kp_e = np.where(top, 0, kp_e)
        kp = np.minimum(np.ldexp(kp_m[0], kp_e), 1.0)
        amp = core["amplitudes"]
        # k' = 0 is the separatrix (no period); the rest must have come out finite
        ok = (kp_m[0] > 0) & (p[0] > 0) & np.isfinite(p[0]) & np.all(amp > 0, axis=1) & np.all(np.isfinite(amp), axis=1)
        sel = np.flatnonzero(ok)
        self.ok = ok
        I, w, upper, p, k, kp, amp = I[sel], w[sel], upper[sel], (p[0][sel], p[1][sel]), k[sel], kp[sel], amp[sel]
        K, kp_shifted, shift = _complete_k((kp_m[0][sel], kp_m[1][sel]), kp_e[sel])
        rows = np.arange(len(sel))
        r = np.where(upper, 2, 0)
        sign = np.where(w[rows, r] >= 0, 1.0, -1.0)
        # phase at t = 0 (exact.py's _elliptic): sn(u0) = w2 / a2, cn(u0) = w_c / (sign a_c)
        s0, c0 = w[:, 1] / amp[:, 1], w[rows, 2 - r] / (sign * amp[rows, 2 - r])
        h = np.hypot(s0, c0)
        s0, c0 = s0 / h, c0 / h
        back = c0 < 0  # am(u0) beyond +-pi/2: one half period further
        j0 = np.where(back, np.where(s0 >= 0, 1.0, -1.0), 0.0)
        s0, c0 = np.where(back, -s0, s0), np.maximum(np.where(back, -c0, c0), 0.0)
        d0 = np.hypot(c0, kp * s0)
        u0 = dd.add(dd.mul_d((2.0 * K[0], 2.0 * K[1]), j0), self._initial_phase(s0, c0, d0, kp, K))
        self.I, self.w, self.upper, self.p, self.k, self.kp, self.K = I, w, upper, p, k, kp, K
        self.amp, self.sign, self.u0, self.j0 = amp, sign, u0, j0
        big = k > kp  # m > 1/2: Jacobi's imaginary transformation
        self.tables = _agm_tables(np.where(big, k, kp), np.where(big, kp, k))
        self.big = big
        # for the attitude only (_precession_parameters)
        self._later = (core["moments"][sel], (core["n"][0][sel], core["n"][1][sel]), kp_shifted, shift, (s0, c0, d0))

    def _precession_parameters(self) -> None:
        """Rates of the precession about L (exact.py's module docstring and ``_elliptic``), from
        the scaled moments: ``phi(t) = A t + B j + b(u_r) - b(u0_r)``."""
        Is, n, kp_shifted, shift, start = self._later
        K, p, rows = self.K, self.p, np.arange(len(Is))
        r = np.where(self.upper, 2, 0)
        Ir, Io = Is[rows, r], Is[rows, 2 - r]
        Ln, e = dd.norm([dd.two_prod(Is[:, i], self.w[:, i]) for i in range(3)])
        Ln = dd.ldexp(Ln, e)
        rate0 = dd.div(Ln, (Ir, np.zeros_like(Ir)))
        rate1 = dd.div(dd.mul(Ln, dd.two_sum(Ir, -Io)), dd.two_prod(Is[:, 0], Is[:, 2]))
        scale = dd.div(rate1, p)
        Pi = _complete_pi(n, kp_shifted, shift, K)
        pi_mode = np.abs(n[0]) > 1.0  # else the excess form: Pi - F with F(am u) = u exactly
        excess = dd.add(Pi, dd.neg(K))
        self.A = _pick(pi_mode, rate0, dd.add(rate0, rate1))
        self.B = dd.mul(dd.mul_d(scale, 2.0), _pick(pi_mode, Pi, excess))
        self.n, self.scale, self.pi_mode, self.excess_c = n[0], scale[0], pi_mode, excess[0]
        self.b0 = self._bounded(*start)

    @staticmethod
    def _initial_phase(s0, c0, d0, kp, K):
        """``u_r = F(phi | m)`` (exact.py's ``_initial_phase``): past ``|u_r| = K/2`` from ``+-K``
        by the co-amplitude, so that a start near ``cn = 0`` keeps its relative accuracy."""
        far = (kp > 0) & (np.abs(s0) * d0 > c0) & np.isfinite(K[0])
        hi, lo = np.empty_like(s0), np.zeros_like(s0)
        g = far & (d0 > 0)  # F of the co-amplitude, measured from K with the sign of s0
        dg = d0[g]
        u1 = np.zeros_like(s0)
        u1[g] = legendre_f(c0[g] / dg, kp[g] * np.abs(s0[g]) / dg, kp[g] / dg)
        shifted = dd.add(K, (-u1, np.zeros_like(u1)))
        shifted = _pick(s0 > 0, shifted, dd.neg(shifted))
        hi[far], lo[far] = shifted[0][far], shifted[1][far]
        hi[~far] = legendre_f(s0[~far], c0[~far], d0[~far], K=K[0][~far])
        return hi, lo

    def _phase(self, t) -> None:
        """``u = u0 + p t`` reduced by half periods (elliptic's ``Modulus.reduce``), and omega."""
        u = dd.add(_times(self.p, t), (self.u0[0][:, None], self.u0[1][:, None]))
        K = (self.K[0][:, None], self.K[1][:, None])
        twoK = (2.0 * K[0], 2.0 * K[1])
        j1 = np.rint(u[0] / twoK[0])
        r = dd.add(u, dd.neg(dd.mul_d(twoK, j1)))
        j2 = np.rint(r[0] / twoK[0])
        r = dd.add(r, dd.neg(dd.mul_d(twoK, j2)))
        q = np.rint(r[0] / K[0])
        v = dd.add(r, dd.neg(dd.mul_d(K, q)))
        s, c, d = self._landen(v[0] + v[1])
        kp = self.kp[:, None]
        sn = np.where(q == 0, s, q * c / d)
        cn = np.where(q == 0, c, -q * kp * s / d)
        dn = np.where(q == 0, d, kp / d)
        dn = np.where(np.isfinite(dn), dn, 0.0)
        odd = (np.fmod(np.abs(j1), 2.0) + np.abs(j2)) % 2.0 == 1.0
        self.t, self.j, self.sncndn = t, (j1, j2), (sn, cn, dn)
        flip = np.where(odd, -1.0, 1.0)
        a, sign, up = self.amp, self.sign[:, None], self.upper[:, None]
        wc = sign * np.where(up, a[:, None, 0], a[:, None, 2]) * flip * cn
        wr = sign * np.where(up, a[:, None, 2], a[:, None, 0]) * dn
        self.omega = np.stack([np.where(up, wc, wr), a[:, None, 1] * flip * sn, np.where(up, wr, wc)], axis=-1)

    def _landen(self, v):
        """``sn, cn, dn`` of ``|v| <= K/2`` (elliptic's ``Modulus._landen``), each body with its
        own AGM and number of Landen steps."""
        As, Cs, count = self.tables
        rows = np.arange(len(count))
        x = (np.ldexp(1.0, count) * As[count, rows])[:, None] * v
        big = self.big[:, None]
        for n in range(len(As) - 1, 0, -1):
            ratio = (Cs[n] / As[n])[:, None]
            go = (n <= count)[:, None]
            hyper = 0.5 * (x + np.arcsinh(ratio * np.sinh(x)))
            circ = 0.5 * (x + np.arcsin(np.clip(ratio * np.sin(x), -1.0, 1.0)))
            x = np.where(go, np.where(big, hyper, circ), x)
        kp, k = self.kp[:, None], self.k[:, None]
        ch = np.cosh(x)
        cn_c = np.cos(x)
        sn = np.where(big, np.tanh(x), np.sin(x))
        cn = np.where(big, 1.0 / ch, cn_c)
        dn = np.where(big, np.hypot(1.0, kp * np.sinh(x)) / ch, np.hypot(kp, k * cn_c))
        return sn, cn, dn

    def _bounded(self, sn, cn, dn):
        """The bounded part of ``phi`` at reduced phases, rad (exact.py's ``_bounded``)."""
        col = (lambda x: x) if np.ndim(sn) == 1 else (lambda x: x[:, None])
        excess = np.empty(np.shape(sn))
        # legendre_pi_excess takes 0, 1 or 3 duplication steps as all its arguments need: taken
        # for each body's own samples, as FreeRotation does (other steps change the round-off
        # of an excess that reaches ~100 next to the separatrix: 2e-13 rad)
        small = np.minimum(cn, dn).reshape(len(sn), -1)
        need = np.where(np.all(small > 1e-50, axis=1), 0, np.where(np.all((cn + dn).reshape(len(sn), -1) > 1e-90, axis=1), 1, 3))
        for steps in np.unique(need):
            g = need == steps
            excess[g] = legendre_pi_excess(col(self.n[g]), sn[g], cn[g], dn[g], m=col(self.k[g] ** 2),
                                           excess_complete=col(self.excess_c[g]))
        g = self.pi_mode  # |n| > 1: Pi itself, F + (Pi - F)
        excess[g] = legendre_f(sn[g], cn[g], dn[g], K=col(self.K[0][g])) + excess[g]
        return col(self.scale) * excess

    def attitude(self, q0) -> np.ndarray:
        """Body to world at every time: ``G Rz(phi) Rx(theta) Rz(psi) P``, G fixed by ``q0``."""
        with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
            self._precession_parameters()
            (j1, j2), (sn, cn, dn) = self.j, self.sncndn
            secular = dd.add(_times(self.A, self.t), dd.add(_times(self.B, j1), _times(self.B, j2 - self.j0[:, None])))
            phi = dd.reduce_2pi(secular) + (self._bounded(sn, cn, dn) - self.b0[:, None])
            theta, psi = self._tilt(self.I[:, None, :] * self.omega)
            theta0, psi0 = self._tilt(self.I * self.w)
        # R = q0 P^-1 B0^-1 E P with B0 = Rx(theta0) Rz(psi0), E = Rz(phi) Rx(theta) Rz(psi); the
        # conjugation P^-1 X P of X = B0^-1 E keeps its scalar part and turns its vector part by
        # P^-1: the identity for reference axis 3, (x, y, z) -> (z, x, y) for axis 1
        X = quat_multiply(quat_conjugate(quat_zxz(0.0, theta0, psi0))[:, None, :], quat_zxz(phi, theta, psi))
        lower = ~self.upper
        X[lower] = X[lower][..., [2, 0, 1, 3]]
        return quat_multiply(q0[:, None, :], X)

    def _tilt(self, L):
        """``theta, psi`` of ``Rx(theta) Rz(psi)``, which takes the relabelled L to ``|L| e_z``."""
        up = self.upper if L.ndim == 2 else self.upper[:, None]
        Li = np.where(up, L[..., 0], L[..., 1])
        Lj = np.where(up, L[..., 1], L[..., 2])
        Lr = np.where(up, L[..., 2], L[..., 0])
        return np.arctan2(np.hypot(Li, Lj), Lr), np.arctan2(Li, Lj)

