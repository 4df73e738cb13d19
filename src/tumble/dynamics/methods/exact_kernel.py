"""The one kernel of the exact torque-free motion: N bodies (N = 1 included) at common times.

The mathematics is stated in :mod:`tumble.dynamics.methods.exact` (Landau & Lifshitz,
*Mechanics*, sec. 37, 35; read its module docstring); here it is evaluated on arrays of bodies,
once, for both fronts: :class:`tumble.dynamics.methods.exact.FreeRotation` (one body, any times)
and :func:`tumble.dynamics.methods.exact_batch.free_rotation_batch` (N bodies; from
:data:`~tumble.dynamics.methods.exact_parameters.COMPILED_BODIES` only for the bodies its
compiled double-precision kernel, :mod:`tumble.dynamics.methods.compiled_exact`, leaves). The front picks
the path by N, as scipy's ``Rotation`` picks its backend: for one body the parameters go
through Python floats (:func:`~tumble.dynamics.methods.exact_parameters.scaled_core` and
:func:`~tumble.dynamics.special.carlson.complete_integrals` take floats as floats, several times
faster than numpy on single values), for many through numpy, with the same arithmetic; from
there on every step is written once, over arrays of shape (N,) and (N, T):

- the parameters ``p``, ``k``, ``k'``, the amplitudes and the characteristic ``n``
  (:func:`~tumble.dynamics.methods.exact_parameters.scaled_core`), the complete integrals ``K``
  and ``Pi(n | m)`` in double-double (:func:`~tumble.dynamics.special.carlson.complete_integrals`);
- the phase ``u = u0 + p t`` and its reduction by half periods in double-double, and ``sn, cn,
  dn`` of the reduced phase (:class:`tumble.dynamics.special.elliptic.Modulus`, one modulus per
  body; the separatrix ``k' = 0``, with no period, gives ``tanh`` and ``sech``);
- the attitude ``R(t) = G Rz(phi) Rx(theta) Rz(psi) P`` with quaternion algebra written out
  (Hamilton product, scalar last, as scipy: :mod:`tumble.dynamics.special.quaternion`), the
  precession ``phi`` from Legendre's integrals (:mod:`tumble.dynamics.special.carlson`), its
  secular part in double-double.

Steady rotations (:func:`is_steady`) are rotations about the fixed omega by ``|omega| t``
(:func:`steady_attitude`); they never reach :class:`EllipticMotion`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TypeAlias, cast

import numpy as np

from ...typing import ArrayLike, BoolArray, FloatArray, IntArray, Quaternion, Vector3
from ..special import ddouble as dd
from ..special.carlson import complete_integrals, legendre_f, legendre_pi_excess
from ..special.ddouble import DoubleDouble
from ..special.elliptic import Modulus
from ..special.quaternion import quat_conjugate, quat_multiply, quat_zxz
from .exact_parameters import ScaledCore, scaled_core

__all__ = ["EllipticMotion", "is_steady", "steady_attitude"]

#: A double-double of arrays: one value per body (N,), or per body and time (N, T).
DDArray: TypeAlias = tuple[FloatArray, FloatArray]

#: What :meth:`EllipticMotion.reduce` returns, each of shape (N, T): the half-period counts
#: ``(j1, j2)``, the parity of ``j1 + j2``, and ``sn, cn, dn`` of the reduced phase.
Reduced: TypeAlias = tuple[tuple[FloatArray, FloatArray], BoolArray, FloatArray, FloatArray, FloatArray]


def is_steady(I: ArrayLike, w: ArrayLike) -> BoolArray:
    """Whether ``omega`` is constant: ``w x I w = 0`` decided by exact comparisons.

    Not by evaluating ``cross(L, w) == 0``, which depends on round-off. The cases
    (Landau & Lifshitz sec. 33, 37): a sphere (``I1 == I3``); omega along a principal axis (two
    components zero); a symmetric top spinning in its degenerate plane (``I1 == I2`` with
    ``w3 == 0``, ``I2 == I3`` with ``w1 == 0``), where every axis of the plane is principal.
    Moments that are equal only to round-off are not equal here: a body declared symmetric is
    made exactly so by :func:`tumble.mass.principal_frame`.

    Parameters
    ----------
    I : array_like, shape (..., 3)
        Principal moments, ascending, kg m^2.
    w : array_like, shape (..., 3)
        Angular velocity, principal frame, rad/s.

    Returns
    -------
    ndarray of bool, shape (...)

    Examples
    --------
    >>> from tumble.dynamics.methods.exact_kernel import is_steady
    >>> bool(is_steady([1.0, 2.0, 3.0], [0.0, 0.0, 5.0])), bool(is_steady([1.0, 2.0, 3.0], [0.1, 0.0, 5.0]))
    (True, False)
    """
    I, w = np.asarray(I), np.asarray(w)
    zeros = np.count_nonzero(w == 0.0, axis=-1)
    return cast(BoolArray, ((I[..., 0] == I[..., 2]) | (zeros >= 2) | ((I[..., 0] == I[..., 1]) & (w[..., 2] == 0.0))
            | ((I[..., 1] == I[..., 2]) & (w[..., 0] == 0.0))))


def steady_attitude(w: Vector3, q0: Quaternion, t: FloatArray) -> Quaternion:
    """``q0 (x) exp(|w| t e_w)``: the turn about a fixed omega, its angle in double-double.

    Parameters
    ----------
    w : ndarray, shape (N, 3)
        The constant angular velocity, principal frame, rad/s.
    q0 : ndarray, shape (N, 4)
        Attitude at t = 0, principal frame to world, scalar last.
    t : ndarray, shape (T,)
        Times, s.

    Returns
    -------
    ndarray, shape (N, T, 4)
        Principal frame to world, scalar last.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.exact_kernel import steady_attitude
    >>> q = steady_attitude(np.array([[0.0, 0.0, np.pi]]), np.array([[0.0, 0.0, 0.0, 1.0]]), np.array([1.0]))
    >>> np.round(q[0, 0], 12) + 0.0  # half a turn about z
    array([0., 0., 1., 0.])
    """
    spin, e = cast(tuple[DDArray, IntArray], dd.norm([(x, np.zeros_like(x)) for x in w.T]))  # arrays in, out
    axis = np.where(spin[0][:, None] > 0, np.ldexp(w, -e[:, None]) / np.where(spin[0] > 0, spin[0], 1.0)[:, None], w)
    angle = 0.5 * dd.reduce_2pi(dd.mul_scaled(_column(dd.ldexp(spin, e)), t))
    turn = np.concatenate([np.sin(angle)[..., None] * axis[:, None, :], np.cos(angle)[..., None]], axis=-1)
    return quat_multiply(q0[:, None, :], turn)


def _column(x: DoubleDouble) -> DDArray:
    """A double-double of shape (N,) as (N, 1), to broadcast against times (T,)."""
    return cast(FloatArray, x[0])[:, None], cast(FloatArray, x[1])[:, None]  # arrays here


def _lift(x: ArrayLike) -> FloatArray:
    return np.atleast_1d(np.asarray(x, float))


def _lift_dd(x: DoubleDouble) -> DDArray:
    return _lift(x[0]), _lift(x[1])


class EllipticMotion:
    """The elliptic (non-steady) torque-free motions of N rigid bodies.

    Parameters
    ----------
    moments : ndarray, shape (N, 3)
        Principal moments, ascending, positive, kg m^2.
    omega0 : ndarray, shape (N, 3)
        Angular velocity at t = 0, principal frame, rad/s; none steady (:func:`is_steady`).

    Notes
    -----
    The parameters are built once; :meth:`reduce` gives the reduced phases at times ``t``, from
    which :meth:`omega` and :meth:`attitude` read the motion without building anything again.
    The precession's parameters, needed by the attitude and by :attr:`phase_rate` only, are
    built on first use.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.exact_kernel import EllipticMotion
    >>> motion = EllipticMotion(np.array([[1.0, 2.0, 3.0]]), np.array([[0.1, 1.0, 0.1]]))
    >>> w = motion.omega(motion.reduce(np.array([0.0, 1.0])))
    >>> w.shape, bool(np.allclose(w[0, 0], [0.1, 1.0, 0.1]))
    ((1, 2, 3), True)
    """

    def __init__(self, moments: ArrayLike, omega0: ArrayLike) -> None:
        I, w = np.asarray(moments, float), np.asarray(omega0, float)
        self.I, self.w = I, w
        with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
            self._parameters(I, w)

    # -- parameters ------------------------------------------------------------------
    def _core(self, I: FloatArray, w: FloatArray) -> tuple[
        ScaledCore, BoolArray, FloatArray, FloatArray, FloatArray, DDArray, DDArray, DDArray
    ]:
        """The motion's parameters and complete integrals, through floats for one body."""
        one = len(I) == 1
        core = scaled_core(w[0], I[0]) if one else scaled_core(w, I)
        (k_m, k_e), (kp_m, kp_e) = core["k"], core["kp"]
        k_m, kp_m, n = _lift_dd(k_m), _lift_dd(kp_m), _lift_dd(core["n"])
        k_e, kp_e = np.atleast_1d(k_e).astype(int), np.atleast_1d(kp_e).astype(int)
        separatrix = kp_m[0] == 0.0  # g2 == 0 exactly
        k = np.minimum(np.ldexp(k_m[0], k_e), 1.0)
        top = k == 0.0  # a symmetric top: circular functions, exactly
        kp_m = (np.where(top, 1.0, kp_m[0]), np.where(top, 0.0, kp_m[1]))
        kp_e = np.where(top, 0, kp_e)
        kp = np.minimum(np.ldexp(kp_m[0], kp_e), 1.0)
        K = (np.full(len(I), math.inf), np.zeros(len(I)))
        Pi = (K[0].copy(), K[1].copy())
        live = np.flatnonzero(~separatrix)
        if one and live.size:
            K1, Pi1 = complete_integrals((float(n[0][0]), float(n[1][0])), (float(kp_m[0][0]), float(kp_m[1][0])), int(kp_e[0]))
            K, Pi = _lift_dd(K1), _lift_dd(Pi1)
        elif live.size:
            Kl, Pil = complete_integrals((n[0][live], n[1][live]), (kp_m[0][live], kp_m[1][live]), kp_e[live])
            for full, part in ((K, Kl), (Pi, Pil)):
                full[0][live], full[1][live] = part
        k = np.where(separatrix, 1.0, k)
        m1 = np.where(kp_e > -600, np.ldexp(kp_m[0] ** 2, 2 * kp_e), 0.0)
        return core, separatrix, k, kp, m1, n, K, Pi

    def _parameters(self, I: FloatArray, w: FloatArray) -> None:
        core, separatrix, k, kp, m1, n, K, Pi = self._core(I, w)
        upper = np.atleast_1d(core["upper"])
        amp = np.atleast_2d(core["amplitudes"])
        rows = np.arange(len(I))
        r = np.where(upper, 2, 0)  # the dn axis
        c = 2 - r  # the cn axis
        sign = np.where(w[rows, r] >= 0, 1.0, -1.0)
        # On the separatrix cn = sech > 0 never changes sign, so the two branches on which w_c
        # and w_r have opposite signs need sn's sign reversed (Euler's equations then still
        # hold: I2 a2 p = (I3 - I1) a1 a3 with sign2 * sign_c * sign_r = +1).
        sign2 = np.where(separatrix & (w[rows, c] * sign < 0), -1.0, 1.0)
        sign_c = sign * sign2
        # phase at t = 0 from sn(u0) = w2 / (sign2 a2) and cn(u0) = w_c / (sign_c a_c), taken
        # straight into Carlson's integrals (no angle): u0 = 2 K j0 + F(phi_r), |phi_r| <= pi/2
        s0, c0 = w[:, 1] / (sign2 * amp[:, 1]), w[rows, c] / (sign_c * amp[rows, c])
        h = np.hypot(s0, c0)
        s0, c0 = s0 / h, c0 / h
        back = (c0 < 0) & ~separatrix  # am(u0) beyond +-pi/2: one half period further
        j0 = np.where(back, np.where(s0 >= 0, 1.0, -1.0), 0.0)
        s0, c0 = np.where(back, -s0, s0), np.maximum(np.where(back, -c0, c0), 0.0)
        d0 = np.hypot(c0, kp * s0)
        start = _initial_phase(s0, c0, d0, kp, K)
        u0 = dd.where(j0 != 0.0, dd.add(dd.mul_d((2.0 * K[0], 2.0 * K[1]), j0), start), start)
        self.upper, self.separatrix, self.rows, self.r, self.c = upper, separatrix, rows, r, c
        self.p, self.k, self.kp, self.m1, self.n, self.K, self.Pi = _lift_dd(core["p"]), k, kp, m1, n, K, Pi
        self.amp, self.sign, self.sign2, self.sign_c, self.u0, self.j0 = amp, sign, sign2, sign_c, u0, j0
        self.modulus = Modulus(k, kp, K)
        self._start = (np.atleast_2d(core["moments"]), (s0, c0, d0))

    def _precession_parameters(self) -> None:
        """Rates of the precession about L (exact.py's module docstring), from the scaled
        moments: ``phi(t) = A t + B j + b(u_r) - b(u0_r)``."""
        if hasattr(self, "A"):
            return
        Is, start = self._start
        K, Pi, p, n, rows = self.K, self.Pi, self.p, self.n, self.rows
        Ir, Io = Is[rows, self.r], Is[rows, 2 - self.r]
        Ln, e = dd.norm([dd.two_prod(Is[:, i], self.w[:, i]) for i in range(3)])  # |L|, scaled moments
        Ln = dd.ldexp(Ln, e)
        rate0 = dd.div(Ln, (Ir, np.zeros_like(Ir)))
        rate1 = dd.div(dd.mul(Ln, dd.two_sum(Ir, -Io)), dd.two_prod(Is[:, 0], Is[:, 2]))
        # n = 0 exactly for a symmetric top about its symmetry axis (I2 equal to the other
        # extreme moment): Pi(0; phi | m) = F(phi | m), the excess vanishes, and rate1 / p (huge
        # for a vanishing axial spin, 1e300 at 1e-300 rad/s) must not be formed
        zero = (np.zeros_like(Ir), np.zeros_like(Ir))
        scale = dd.where(n[0] != 0.0, dd.div(rate1, p), zero)
        one_n = dd.add((np.ones_like(Ir), np.zeros_like(Ir)), dd.neg(n))
        # phi(t) = rate0 t + (rate1 / p) [Pi(u) - Pi(u0)] (exact.py), split into a secular part
        # A t + B j and a bounded one b(u_r) - b(u0_r) evaluated without cancellation:
        # - the separatrix: Pi(n; am u | 1) = (u + a atan(a tanh u)) / (1 - n), a = sqrt(-n)
        #   (integrate 1 / ((1 - n x^2)(1 - x^2)) in x = sin theta by partial fractions);
        # - |n| <= 1: Pi = F + (Pi - F) with F(am u) = u exactly, so only the O(n) excess is
        #   evaluated: when p is tiny (a nearly symmetric body, a symmetric top spun almost
        #   perpendicular to its axis) rate1 / p is huge and Pi(u) - Pi(u0) would lose it all;
        # - |n| > 1: Pi itself, which is then O(1 / sqrt(-n)).
        sep = self.separatrix
        pi_mode = (np.abs(n[0]) > 1.0) & ~sep
        excess = dd.add(Pi, dd.neg(K))
        A = dd.where(sep, dd.add(rate0, dd.div(rate1, one_n)), dd.where(pi_mode, rate0, dd.add(rate0, rate1)))
        B = dd.where(sep, zero, dd.mul(dd.mul_d(scale, 2.0), dd.where(pi_mode, Pi, excess)))
        self.A, self.B, self.pi_mode, self.scale = A, B, pi_mode, cast(FloatArray, scale[0])  # arrays here
        self.excess_c, self.one_n = np.where(sep, -np.inf, excess[0]), cast(FloatArray, one_n[0])
        self.b0 = self._bounded(*start)
        half = np.where(sep, np.inf, 2.0 * K[0] / p[0])
        self.rate = np.maximum(p[0], np.abs(A[0]) + np.abs(B[0]) / half)

    @property
    def phase_rate(self) -> FloatArray:
        """The fastest rate of any phase of each motion (1/s): ``p`` or the precession's.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.methods.exact_kernel import EllipticMotion
        >>> I, w0 = np.array([1.0, 2.0, 3.0]), np.array([0.1, 1.0, 0.1])
        >>> motion = EllipticMotion(I[None, :], w0[None, :])
        >>> period = 4.0 * motion.K[0][0] / motion.p[0][0]   # omega's period 4 K / p
        >>> t = np.linspace(0.0, period, 401)[:-1]
        >>> w = motion.omega(motion.reduce(t))[0]
        >>> L = np.linalg.norm(I * w0)   # the precession rate about L, averaged over a period (Landau & Lifshitz sec. 37)
        >>> precession = L * (I[0] * w[:, 0]**2 + I[1] * w[:, 1]**2) / ((I[0] * w[:, 0])**2 + (I[1] * w[:, 1])**2)
        >>> bool(np.isclose(motion.phase_rate[0], precession.mean(), rtol=1e-12)), bool(motion.phase_rate[0] > motion.p[0][0])
        (True, True)
        """
        with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
            self._precession_parameters()
        return self.rate

    # -- evaluation ------------------------------------------------------------------
    def reduce(self, t: ArrayLike) -> Reduced:
        """Half-period counts ``(j1, j2)``, parity and ``sn, cn, dn`` of the reduced phase of
        every body at times ``t`` (s, shape (T,)): arrays of shape (N, T).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.methods.exact_kernel import EllipticMotion
        >>> motion = EllipticMotion(np.array([[1.0, 2.0, 3.0]]), np.array([[0.1, 1.0, 0.1]]))
        >>> period = 4.0 * motion.K[0][0] / motion.p[0][0]   # 4 K / p: two half periods of u
        >>> (j1, j2), odd, sn, cn, dn = motion.reduce(np.array([0.0, period, 1e6 * period]))
        >>> (j1 + j2 - (j1 + j2)[:, :1]).tolist(), sn.shape
        ([[0.0, 2.0, 2000000.0]], (1, 3))
        >>> bool(np.allclose(sn**2 + cn**2, 1.0))
        True
        """
        u = dd.add(dd.mul_scaled(_column(self.p), np.asarray(t, float)), _column(self.u0))
        with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
            return self.modulus.reduce(u)

    def omega(self, reduced: Reduced) -> Vector3:
        """Angular velocity (rad/s, principal frame), shape (N, T, 3), from :meth:`reduce`.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.methods.exact_kernel import EllipticMotion
        >>> I = np.array([[1.0, 2.0, 3.0], [2.0, 2.5, 4.0]])   # two bodies
        >>> w0 = np.array([[0.1, 1.0, 0.1], [1.0, -0.5, 0.3]])
        >>> motion = EllipticMotion(I, w0)
        >>> w = motion.omega(motion.reduce(np.linspace(0.0, 100.0, 5)))
        >>> w.shape
        (2, 5, 3)
        >>> bool(np.allclose((I[:, None] * w**2).sum(-1), (I * w0**2).sum(-1)[:, None]))   # energy of each body
        True
        """
        _, odd, sn, cn, dn = reduced
        flip = np.where(odd, -1.0, 1.0)
        rows = self.rows
        a_c, a_r = (self.sign_c * self.amp[rows, self.c])[:, None], (self.sign * self.amp[rows, self.r])[:, None]
        wc, wr = a_c * flip * cn, a_r * dn
        up = self.upper[:, None]
        return np.stack([np.where(up, wc, wr), (self.sign2 * self.amp[:, 1])[:, None] * flip * sn, np.where(up, wr, wc)], axis=-1)

    def attitude(self, q0: ArrayLike, t: ArrayLike, reduced: Reduced, omega: Vector3) -> Quaternion:
        """Principal frame to world, shape (N, T, 4), scalar last: ``G Rz(phi) Rx(theta) Rz(psi)
        P`` with ``G`` fixed by ``q0`` (shape (N, 4)), from :meth:`reduce` and :meth:`omega`.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.methods.exact_kernel import EllipticMotion
        >>> I, w0 = np.array([[1.0, 2.0, 3.0]]), np.array([[0.1, 1.0, 0.1]])
        >>> motion = EllipticMotion(I, w0)
        >>> t = np.array([0.0, 10.0, 1000.0])
        >>> reduced = motion.reduce(t)
        >>> w = motion.omega(reduced)
        >>> q = motion.attitude(np.array([[0.0, 0.0, 0.0, 1.0]]), t, reduced, w)
        >>> from tumble.dynamics.special.quaternion import rotate_by_quaternion
        >>> rotate_by_quaternion(q, I[:, None] * w).round(12).tolist()   # L is fixed in space
        [[[0.1, 2.0, 0.3], [0.1, 2.0, 0.3], [0.1, 2.0, 0.3]]]
        """
        with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
            self._precession_parameters()
            (j1, j2), _, sn, cn, dn = reduced
            A, B, t = _column(self.A), _column(self.B), np.asarray(t, float)
            secular = dd.add(dd.mul_scaled(A, t), dd.add(dd.mul_scaled(B, j1), dd.mul_scaled(B, j2 - self.j0[:, None])))
            phi = dd.reduce_2pi(secular) + (self._bounded(sn, cn, dn) - self.b0[:, None])
            theta, psi = self._tilt(self.I[:, None, :] * omega)
            theta0, psi0 = self._tilt(self.I * self.w)
        # R = q0 P^-1 B0^-1 E P with B0 = Rx(theta0) Rz(psi0), E = Rz(phi) Rx(theta) Rz(psi); the
        # conjugation P^-1 X P of X = B0^-1 E keeps its scalar part and turns its vector part by
        # P^-1: the identity for reference axis 3, (x, y, z) -> (z, x, y) for axis 1
        X = quat_multiply(quat_conjugate(quat_zxz(0.0, theta0, psi0))[:, None, :], quat_zxz(phi, theta, psi))
        lower = ~self.upper
        X[lower] = X[lower][..., [2, 0, 1, 3]]
        return quat_multiply(np.asarray(q0, float)[:, None, :], X)

    def _tilt(self, L: Vector3) -> tuple[FloatArray, FloatArray]:
        """``theta, psi`` of ``Rx(theta) Rz(psi)``, which takes the relabelled ``L_body`` (the
        reference axis last: (1, 2, 3) or (2, 3, 1)) to ``|L| e_z``."""
        up = self.upper if L.ndim == 2 else self.upper[:, None]
        Li = np.where(up, L[..., 0], L[..., 1])
        Lj = np.where(up, L[..., 1], L[..., 2])
        Lr = np.where(up, L[..., 2], L[..., 0])
        return np.arctan2(np.hypot(Li, Lj), Lr), np.arctan2(Li, Lj)

    def _bounded(self, sn: FloatArray, cn: FloatArray, dn: FloatArray) -> FloatArray:
        """The bounded part of ``phi`` at reduced phases (``sn, cn, dn`` of ``u_r``, shape (N,)
        or (N, T)), rad."""
        col: Callable[[FloatArray], FloatArray] = (lambda x: x) if np.ndim(sn) == 1 else (lambda x: x[:, None])
        excess = np.empty(np.shape(sn))
        sep = self.separatrix
        if np.any(sep):
            a = np.sqrt(-self.n[0][sep])
            excess[sep] = col(a) * np.arctan(col(a) * sn[sep]) / col(self.one_n[sep])  # sn = tanh u
        # legendre_pi_excess takes 0, 1 or 3 duplication steps as all its arguments need: taken
        # for each body's own samples (other steps change the round-off of an excess that
        # reaches ~100 next to the separatrix: 2e-13 rad)
        small = np.minimum(cn, dn).reshape(len(sn), -1)
        need = np.where(np.all(small > 1e-50, axis=1), 0, np.where(np.all((cn + dn).reshape(len(sn), -1) > 1e-90, axis=1), 1, 3))
        for steps in np.unique(need[~sep]):
            g = (need == steps) & ~sep
            excess[g] = legendre_pi_excess(col(self.n[0][g]), sn[g], cn[g], dn[g], m=col(self.k[g] ** 2),
                                           excess_complete=col(self.excess_c[g]))
        g = self.pi_mode  # |n| > 1: Pi itself, F + (Pi - F)
        if np.any(g):
            excess[g] = legendre_f(sn[g], cn[g], dn[g], K=col(self.K[0][g])) + excess[g]
        return col(self.scale) * excess


def _initial_phase(s0: FloatArray, c0: FloatArray, d0: FloatArray, kp: FloatArray, K: DDArray) -> DDArray:
    """``u_r = F(phi | m)``, ``|phi| <= pi/2``, as a double-double; past the midpoint
    ``|u_r| = K/2`` measured from ``+-K`` instead, by the co-amplitude of ``u' = K - |u_r|``:
    ``sn u' = cd u_r``, ``cn u' = k' sd |u_r|``, ``dn u' = k' nd u_r`` (DLMF 22.4.3), so that a
    start near ``cn = 0`` carries no error of size eps K (relative accuracy of cn there)."""
    far = (kp > 0) & (np.abs(s0) * d0 > c0) & np.isfinite(K[0])
    hi, lo = np.empty_like(s0), np.zeros_like(s0)
    g = far & (d0 > 0)  # F of the co-amplitude, measured from K with the sign of s0
    dg = d0[g]
    u1 = np.zeros_like(s0)
    u1[g] = legendre_f(c0[g] / dg, kp[g] * np.abs(s0[g]) / dg, kp[g] / dg)
    shifted = dd.add(K, (-u1, np.zeros_like(u1)))
    shifted = cast(DDArray, dd.where(s0 > 0, shifted, dd.neg(shifted)))
    hi[far], lo[far] = shifted[0][far], shifted[1][far]
    hi[~far] = legendre_f(s0[~far], c0[~far], d0[~far], K=K[0][~far])
    return hi, lo
