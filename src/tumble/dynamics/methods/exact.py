"""The exact torque-free motion of a rigid body: omega(t) and the attitude in closed form.

Angular velocity (Landau & Lifshitz, *Mechanics*, sec. 37), principal
moments ``I1 <= I2 <= I3``, ``g_j = L^2 - 2 E I_j`` (computed as ``sum_i I_i (I_i - I_j) w_i^2``,
without cancellation, as Celledoni, Fasso, Safstrom & Zanna advise):

- ``g2 > 0`` (omega circulates about the major axis 3)::

      w1 = s a1 cn(u),  w2 = a2 sn(u),  w3 = s a3 dn(u),   u = u0 + p t
      a1^2 = -g3 / (I1 (I3 - I1)),  a2^2 = -g3 / (I2 (I3 - I2)),  a3^2 = g1 / (I3 (I3 - I1))
      p^2 = (I3 - I2) g1 / (I1 I2 I3),  m = (I2 - I1)(-g3) / ((I3 - I2) g1),
      1 - m = (I3 - I1) g2 / ((I3 - I2) g1)

- ``g2 < 0`` (about the minor axis 1): the same with axes 1 and 3 exchanged (``w3 = s a3 cn``,
  ``w1 = s a1 dn``);
- ``g2 = 0``, the separatrix: ``m = 1``, so ``sn = tanh``, ``cn = dn = sech``.

The sign ``s`` is that of the component that never changes sign (the dn one); Euler's equations
fix the other signs (``I2 a2 p = (I3 - I1) a1 a3``); on the separatrix, where cn = sech keeps
its sign, the branches with ``w_c w_r < 0`` take ``w2 = -a2 sn(u)``, ``w_c = -s a_c cn(u)``.

The case is decided by exact comparisons of the moments and of the components of omega, never
by evaluating ``w x I w`` (round-off): a sphere, omega along a principal axis, or a symmetric
top spinning in its degenerate plane (``I1 == I2, w3 == 0`` or ``I2 == I3, w1 == 0``) rotate
steadily; any other symmetric top (``I1 == I2`` or ``I2 == I3``) falls out of the formulas
above with ``m = 0``: circular functions, the regular precession of Landau & Lifshitz sec. 33.
Bodies built by :func:`tumble.mass.principal_frame` have degenerate moments exactly equal.

Attitude (``R`` maps body to world). With the fixed unit vector ``l`` along L_world and Euler
angles ``z-x-z`` about it (Landau & Lifshitz sec. 35), ``R(t) = G Rz(phi(t)) Rx(theta(t))
Rz(psi(t)) P``, where ``P`` cyclically relabels the body axes so that the reference axis ``r``
(3 if ``g2 >= 0``, else 1: the dn axis, never perpendicular to L) comes last; ``theta`` and
``psi`` are read off ``L_body(t)`` (``cos theta = L_r / |L|``, ``tan psi = L_i / L_j``); ``G``
is fixed by ``R(0)``; and the precession about L obeys (Landau & Lifshitz sec. 37)
``phi' = |L| (I_i w_i^2 + I_j w_j^2) / (L_i^2 + L_j^2)``, which on the motion above is
``|L| / I_r + |L| (I_r - I_o) / (I1 I3) / (1 - n sn^2 u)`` with ``I_o`` the other extreme moment
and ``n = -I_r (I2 - I_o) / (I_o (I_r - I2))`` (derived by substituting ``dn^2 = 1 - m sn^2``;
``n <= 0`` always, so the integrand has no pole). Hence

    phi(t) = |L| t / I_r + |L| (I_r - I_o) / (I1 I3 p) [Pi(n; am u | m) - Pi(n; am u0 | m)],

evaluated as a secular part plus a bounded one (see ``FreeRotation.__post_init__``): for
``|n| <= 1`` through ``Pi = F + (Pi - F)`` with ``F(am u) = u`` exact, so that a tiny ``p``
(a symmetric top spun almost perpendicular to its axis) costs no accuracy; for the symmetric
top ``n = 0`` and ``phi = |L| t / I_perp`` exactly (Landau & Lifshitz sec. 33),

with Legendre's incomplete integral of the third kind (the construction of Celledoni, Fasso,
Safstrom & Zanna, SIAM J. Sci. Comput. 30 (2008) 2084, sec. 3, whose printed signs are reported
to be wrong; the form here is derived directly from Landau & Lifshitz and checked against DOP853
on all six orderings of the design axes and against arbitrary-precision integration near the
separatrix, in tests/test_exact.py).

Accuracy and limits (tests/test_exact.py, tests/test_exact_hardening.py). The parameters come
from :mod:`tumble.dynamics.methods.exact_parameters` (double-double, scaled: nothing underflows that the
answer does not, so ``omega0 = (0, 1, 1e-160)`` stays a steady spin for ~370 / lambda seconds,
then flips). The phase ``u = u0 + p t``, its reduction by ``2 K`` and the secular part of
``phi`` (``A t + B j``, reduced mod 2 pi) are carried in double-double, so every angle of the
motion is good to ~3e-32 of the phase reached, on top of round-off (measured against
mpmath: 3e-15 rad at a phase of 6.6e16 rad, 2e-11 rad at 6.6e20 rad, 7e-10 rad at 6.6e22). The functions of the
reduced phase are evaluated in double precision (:mod:`tumble.dynamics.special.elliptic`): omega to a
few ulps relative per component, the attitude to ~5e-14 rad, also at ``1 - m`` down to 0;
energy, ``|L|`` and ``L_world`` hold to round-off at any phase. Beyond :data:`MAX_PHASE`
(1e24 rad, where the phase error is ~3e-8 rad; it would reach 1e-6 rad at ~3e25 rad) the
motion refuses to answer with a ``ValueError`` (:func:`check_phase_limit` checks a run before
it starts); ``t_end = 1e12`` s reaches it only at ``|omega| ~ 1e12`` rad/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from ..special import ddouble as dd
from ..special.carlson import complete_integrals, legendre_f, legendre_pi_excess
from ..special.elliptic import Modulus
from .exact_parameters import EllipticParameters, elliptic_parameters, scaled_core

__all__ = ["MAX_PHASE", "EllipticParameters", "FreeRotation", "check_phase_limit", "elliptic_parameters"]

#: Largest phase (rad) the exact solution follows: the elliptic argument ``u = u0 + p t`` and
#: the precession angle are carried in double-double, with an error of ~3e-32 of the phase
#: (measured against mpmath: 2e-11 rad at 6.6e20 rad), so ~3e-8 rad here; 1e-6 rad would be
#: reached at ~3e25 rad.
MAX_PHASE = 1e24


def check_phase_limit(moments, omega0, t_end: float) -> None:
    """Refuse a run whose phase would exceed :data:`MAX_PHASE`.

    Parameters
    ----------
    moments : array_like, shape (3,)
        Principal moments ``I1 <= I2 <= I3``, kg m^2.
    omega0 : array_like, shape (3,)
        Initial angular velocity, principal frame, rad/s.
    t_end : float
        Duration, s.

    Raises
    ------
    ValueError
        Naming ``t_end``, the phase it reaches and the limit.
    """
    I, w = np.asarray(moments, float), np.asarray(omega0, float)
    # Every rate of the motion (p, the precession, a steady spin) is at most |L| / I1 (p^2 <=
    # L^2 / (I1 I2) from its formula; Landau & Lifshitz sec. 37 for the precession): far from the
    # limit that suffices, and the solution is only built (as the run will build it) near it.
    with np.errstate(over="ignore"):
        bound = float(np.linalg.norm(I * w)) / float(I[0]) * abs(float(t_end))
    if bound <= 1e-3 * MAX_PHASE:
        return
    FreeRotation(I, w, Rotation.identity())._check_time(t_end)


def is_steady(I, w) -> np.ndarray:
    """Whether ``omega`` is constant: ``w x I w = 0`` decided by exact comparisons.

    Not by evaluating ``cross(L, w) == 0``, which depends on round-off. The cases
    (Landau & Lifshitz sec. 33, 37): a sphere (``I1 == I3``); omega along a principal axis (two
    components zero); a symmetric top spinning in its degenerate plane (``I1 == I2`` with
    ``w3 == 0``, ``I2 == I3`` with ``w1 == 0``), where every axis of the plane is principal.
    Moments that are equal only to round-off are not equal here: a body declared symmetric is
    made exactly so by :func:`tumble.mass.principal_frame`. ``I`` (ascending, kg m^2) and ``w``
    (rad/s) of shape (..., 3); a bool array of shape (...), for one body as for a batch
    (:func:`tumble.dynamics.methods.exact_batch.free_rotation_batch`).
    """
    I, w = np.asarray(I), np.asarray(w)
    zeros = np.count_nonzero(w == 0.0, axis=-1)
    return ((I[..., 0] == I[..., 2]) | (zeros >= 2) | ((I[..., 0] == I[..., 1]) & (w[..., 2] == 0.0))
            | ((I[..., 1] == I[..., 2]) & (w[..., 0] == 0.0)))


def _dd_float(x) -> tuple[float, float]:
    return float(x[0]), float(x[1])


# Cyclic relabellings of the body axes that put the reference axis last: (i, j, r).
_CYCLE = {2: (0, 1, 2), 0: (1, 2, 0)}


@dataclass(frozen=True, eq=False)
class FreeRotation:
    """The torque-free motion of a rigid body from ``omega0`` and ``attitude0``, exactly.

    Parameters
    ----------
    moments : array_like, shape (3,)
        Principal moments ``I1 <= I2 <= I3``, kg m^2, all positive.
    omega0 : array_like, shape (3,)
        Angular velocity at t = 0, principal frame, rad/s.
    attitude0 : scipy Rotation
        Body (principal) to world at t = 0.

    Notes
    -----
    Times with ``|t| > max_time`` (where a phase would exceed :data:`MAX_PHASE`) raise
    ``ValueError``.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> motion = FreeRotation(np.array([1.0, 2.0, 3.0]), np.array([0.1, 1.0, 0.1]), Rotation.identity())
    >>> w, R = motion.omega([0.0, 1.0]), motion.attitude([0.0, 1.0])
    """

    moments: np.ndarray
    omega0: np.ndarray
    attitude0: Rotation

    def __post_init__(self) -> None:
        I = np.asarray(self.moments, float)
        w = np.asarray(self.omega0, float)
        object.__setattr__(self, "moments", I)
        object.__setattr__(self, "omega0", w)
        if not (I.shape == (3,) and np.all(I > 0) and np.all(np.diff(I) >= 0)):
            raise ValueError(f"moments = {I.tolist()} must be three positive numbers in ascending order (kg m^2)")
        if not (w.shape == (3,) and np.all(np.isfinite(w))):
            raise ValueError(f"omega0 = {w.tolist()} must be three finite numbers (rad/s)")
        self._set(steady=bool(is_steady(I, w)))
        if self.steady:
            spin, e = dd.norm([(x, 0.0) for x in w])
            self._set(spin=dd.ldexp(spin, e), axis=np.ldexp(w, -e) / spin[0] if spin[0] > 0 else w)
            self._set(phase_rate=self.spin[0])
            return
        self._elliptic(I, w)

    def _elliptic(self, I: np.ndarray, w: np.ndarray) -> None:
        core = scaled_core(w, I)
        upper = bool(core["upper"])
        p = _dd_float(core["p"])
        (k_m, k_e), (kp_m, kp_e) = core["k"], core["kp"]
        kp_m, kp_e = _dd_float(kp_m), int(kp_e)
        n = _dd_float(core["n"])
        separatrix = kp_m[0] == 0.0  # g2 == 0 exactly
        k, kp = min(math.ldexp(float(k_m[0]), int(k_e)), 1.0), min(math.ldexp(kp_m[0], kp_e), 1.0)
        if k == 0.0:  # a symmetric top: circular functions, exactly
            kp_m, kp_e, kp = (1.0, 0.0), 0, 1.0
        if separatrix:
            k, K, Pi = 1.0, (math.inf, 0.0), (math.inf, 0.0)
        else:
            K, Pi = complete_integrals(n, kp_m, kp_e)
        modulus = Modulus(k, kp, K)
        r, c = (2, 0) if upper else (0, 2)  # dn axis, cn axis
        amp = core["amplitudes"]
        sign = 1.0 if w[r] >= 0 else -1.0
        # On the separatrix cn = sech > 0 never changes sign, so the two branches on which w_c
        # and w_r have opposite signs need sn's sign reversed (Euler's equations then still
        # hold: I2 a2 p = (I3 - I1) a1 a3 with sign2 * sign_c * sign_r = +1).
        sign2 = -1.0 if (separatrix and w[c] * sign < 0) else 1.0
        sign_c = sign * sign2
        # phase at t = 0 from sn(u0) = w2 / (sign2 a2) and cn(u0) = w_c / (sign_c a_c), taken
        # straight into Carlson's integrals (no angle): u0 = 2 K j0 + F(phi_r), |phi_r| <= pi/2
        s0, c0 = w[1] / (sign2 * amp[1]), w[c] / (sign_c * amp[c])
        h = math.hypot(s0, c0)
        s0, c0 = s0 / h, c0 / h
        j0 = 0.0
        if c0 < 0 and not separatrix:  # am(u0) beyond +-pi/2: one half period further
            j0 = 1.0 if s0 >= 0 else -1.0
            s0, c0 = -s0, -c0
        c0 = max(c0, 0.0)
        d0 = math.hypot(c0, kp * s0)
        u0 = dd.add(dd.mul_d((2.0 * K[0], 2.0 * K[1]), j0) if j0 else (0.0, 0.0), self._initial_phase(s0, c0, d0, kp, K))
        # Rates of the precession about L (module docstring), from the scaled moments and omega
        Is = [float(x) for x in core["moments"]]
        Ir, Io = Is[r], Is[2 - r]
        Ln, e = dd.norm([dd.two_prod(x, float(y)) for x, y in zip(Is, w)])  # |L| for the scaled moments
        Ln = dd.ldexp(Ln, e)
        rate0 = dd.div(Ln, (Ir, 0.0))
        rate1 = dd.div(dd.mul(Ln, dd.two_sum(Ir, -Io)), dd.two_prod(Is[0], Is[2]))
        # n = 0 exactly for a symmetric top about its symmetry axis (I2 equal to the other
        # extreme moment): Pi(0; phi | m) = F(phi | m), the excess vanishes, and rate1 / p (huge
        # for a vanishing axial spin, 1e300 at 1e-300 rad/s) must not be formed
        scale = dd.div(rate1, p) if n != (0.0, 0.0) else (0.0, 0.0)
        one_n = dd.add((1.0, 0.0), dd.neg(n))
        # phi(t) = rate0 t + (rate1 / p) [Pi(u) - Pi(u0)] (module docstring), split into a secular
        # part A t + B j and a bounded one b(u_r) - b(u0_r) that is evaluated without cancellation:
        # - m1 = 0: Pi(n; am u | 1) = (u + a atan(a tanh u)) / (1 - n), a = sqrt(-n) (integrate
        #   1 / ((1 - n x^2)(1 - x^2)) in x = sin theta by partial fractions);
        # - |n| <= 1: Pi = F + (Pi - F) with F(am u) = u exactly, so only the O(n) excess is
        #   evaluated: when p is tiny (a nearly symmetric body, a symmetric top spun almost
        #   perpendicular to its axis) rate1 / p is huge and Pi(u) - Pi(u0) would lose it all;
        # - |n| > 1: Pi itself, which is then O(1 / sqrt(-n)).
        zero = (0.0, 0.0)
        if separatrix:
            mode, A, B = "separatrix", dd.add(rate0, dd.div(rate1, one_n)), zero
        elif abs(n[0]) <= 1.0:
            mode, A = "excess", dd.add(rate0, rate1)
            B = dd.mul(dd.mul_d(scale, 2.0), dd.add(Pi, dd.neg(K)))
        else:
            mode, A, B = "pi", rate0, dd.mul(dd.mul_d(scale, 2.0), Pi)
        excess_c = dd.add(Pi, dd.neg(K))[0] if not separatrix else -math.inf
        self._set(r=r, c=c, sign=sign, sign2=sign2, sign_c=sign_c, amp=amp, p=p, m=k * k,
                  m1=math.ldexp(kp_m[0] ** 2, 2 * kp_e) if kp_e > -600 else 0.0, k=k, kp=kp,
                  modulus=modulus, u0=u0, j0=j0, n=n[0], Lnorm=float(np.linalg.norm(I * w)),
                  rate0=rate0[0], rate1=rate1[0], mode=mode, secular=(A, B),
                  _scale=scale[0], _complete=(K[0], excess_c), _one_n=one_n[0])
        self._set(b0=float(self._bounded(*(np.array(x) for x in (s0, c0, d0)))))
        half = 2.0 * K[0] / p[0] if not separatrix else math.inf
        self._set(phase_rate=max(p[0], abs(A[0]) + abs(B[0]) / half))
        perm = Rotation.from_matrix(np.eye(3)[list(_CYCLE[r])])  # body -> relabelled coordinates
        B0 = self._tilt((I * w)[None, :])[0]
        # R0 = G Rz(0) B0 P  =>  G = R0 P^-1 B0^-1
        self._set(perm=perm, G=self.attitude0 * perm.inv() * B0.inv())

    @staticmethod
    def _initial_phase(s0: float, c0: float, d0: float, kp: float, K) -> tuple[float, float]:
        """``u_r = F(phi | m)``, ``|phi| <= pi/2``, as a double-double; past the midpoint
        ``|u_r| = K/2`` measured from ``+-K`` instead, by the co-amplitude of ``u' = K - |u_r|``:
        ``sn u' = cd u_r``, ``cn u' = k' sd |u_r|``, ``dn u' = k' nd u_r`` (DLMF 22.4.3), so that a
        start near ``cn = 0`` carries no error of size eps K (relative accuracy of cn there)."""
        if kp > 0 and abs(s0) * d0 > c0 and not math.isinf(K[0]):
            u1 = float(legendre_f(c0 / d0, kp * abs(s0) / d0, kp / d0)) if d0 > 0 else 0.0
            far = dd.add(K, (-u1, 0.0))
            return (far[0], far[1]) if s0 > 0 else dd.neg(far)
        return float(legendre_f(s0, c0, d0, K=K[0])), 0.0

    def _set(self, **values) -> None:
        for k, v in values.items():
            object.__setattr__(self, k, v)

    @property
    def max_time(self) -> float:
        """Longest ``|t|`` (s) before a phase of the motion exceeds :data:`MAX_PHASE`."""
        return MAX_PHASE / self.phase_rate if self.phase_rate > 0 else math.inf

    def _check_time(self, t) -> None:
        t_max = float(np.max(np.abs(t))) if np.size(t) else 0.0
        if not t_max <= self.max_time:
            raise ValueError(
                f"t_end = {t_max:g} s takes this motion to a phase of {t_max * self.phase_rate:.3g} rad, beyond "
                f"the {MAX_PHASE:g} rad up to which the exact solution keeps its phase error below 1e-6 rad; "
                f"at most {self.max_time:.6g} s"
            )

    # -- angular velocity ---------------------------------------------------------------
    def _reduced(self, t):
        """Half-period counts ``(j1, j2)``, parity, and ``sn, cn, dn`` of the reduced phase;
        the last answer is kept, as ``omega(t)`` and ``attitude(t)`` are asked for the same t."""
        t = np.asarray(t, float)
        last = self.__dict__.get("_last")
        if last is not None and last[0].shape == t.shape and np.array_equal(last[0], t):
            return last[1]
        self._check_time(t)
        u = dd.add(dd.mul_scaled(self.p, t), self.u0)
        reduced = self.modulus.reduce(u)
        object.__setattr__(self, "_last", (t.copy(), reduced))
        return reduced

    def omega(self, t) -> np.ndarray:
        """Angular velocity at times ``t`` (s), principal frame, rad/s; shape (..., 3)."""
        t = np.asarray(t, float)
        if self.steady:
            return np.broadcast_to(self.omega0, t.shape + (3,)).copy()
        return self._omega(t, self._reduced(t))

    def _omega(self, t, reduced) -> np.ndarray:
        _, odd, sn, cn, dn = reduced
        sign = np.where(odd, -1.0, 1.0)
        w = np.empty(t.shape + (3,))
        w[..., self.c] = self.sign_c * self.amp[self.c] * sign * cn
        w[..., 1] = self.sign2 * self.amp[1] * sign * sn
        w[..., self.r] = self.sign * self.amp[self.r] * dn
        return w

    # -- attitude ------------------------------------------------------------------------
    def _tilt_angles(self, L) -> tuple[np.ndarray, np.ndarray]:
        """``theta, psi`` of ``Rx(theta) Rz(psi)``, which takes relabelled L_body to |L| e_z."""
        i, j, r = _CYCLE[self.r]
        Li, Lj, Lr = L[..., i], L[..., j], L[..., r]
        return np.arctan2(np.hypot(Li, Lj), Lr), np.arctan2(Li, Lj)

    def _tilt(self, L) -> Rotation:
        return Rotation.from_euler("XZ", np.stack(self._tilt_angles(L), axis=-1))

    def _bounded(self, sn, cn, dn) -> np.ndarray:
        """The bounded part of ``phi`` at reduced phases (``sn, cn, dn`` of ``u_r``), rad."""
        n, scale = self.n, self._scale
        if self.mode == "separatrix":
            a = math.sqrt(-n)
            return scale * a * np.arctan(a * sn) / self._one_n  # sn = tanh u
        excess = legendre_pi_excess(n, sn, cn, dn, m=self.m, excess_complete=self._complete[1])
        if self.mode == "excess":
            return scale * excess
        return scale * (legendre_f(sn, cn, dn, K=self._complete[0]) + excess)

    def _precession(self, t, reduced=None):
        """``phi(t)`` as its secular part (double-double) and its bounded part (double)."""
        (j1, j2), _, sn, cn, dn = self._reduced(t) if reduced is None else reduced
        A, B = self.secular
        secular = dd.add(dd.mul_scaled(A, t), dd.add(dd.mul_scaled(B, j1), dd.mul_scaled(B, j2 - self.j0)))
        return secular, self._bounded(sn, cn, dn) - self.b0

    def attitude(self, t) -> Rotation:
        """Body (principal) to world at times ``t`` (s, 1-D), as a Rotation stack."""
        t = np.atleast_1d(np.asarray(t, float))
        if self.steady:
            self._check_time(t)
            angle = dd.reduce_2pi(dd.mul_scaled(self.spin, t))
            return self.attitude0 * Rotation.from_rotvec(np.outer(angle, self.axis))
        reduced = self._reduced(t)
        L = self.moments * self._omega(t, reduced)
        theta, psi = self._tilt_angles(L)
        secular, bounded = self._precession(t, reduced)
        phi = dd.reduce_2pi(secular) + bounded
        # Rz(phi) Rx(theta) Rz(psi) in one call: intrinsic z-x-z Euler angles
        euler = Rotation.from_euler("ZXZ", np.stack([phi, theta, psi], axis=-1))
        return self.G * euler * self.perm
