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
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from scipy.spatial.transform import Rotation

from .elliptic import (
    carlson_f,
    carlson_pi,
    carlson_pi_excess,
    ellipk,
    jacobi,
    jacobi_reduced,
    pi_complete,
    pi_excess_complete,
)
from .euler import energy_momentum_gaps

__all__ = ["EllipticParameters", "FreeRotation", "elliptic_parameters"]

class EllipticParameters(NamedTuple):
    """Parameters of the torque-free motion through one omega (module docstring); arrays (...)."""

    upper: np.ndarray  # L^2 >= 2 E I2: omega circulates about axis 3 (else about axis 1)
    p: np.ndarray  # rate of the elliptic argument u = u0 + p t, 1/s
    m: np.ndarray  # parameter k^2
    m1: np.ndarray  # 1 - k^2, formed directly
    amplitudes: np.ndarray  # a1, a2, a3 (rad/s), shape (..., 3)


def elliptic_parameters(omega, moments) -> EllipticParameters:
    """``p``, ``m``, ``1 - m`` and the amplitudes of the motion through ``omega``, for
    ascending moments, by the formulas of the module docstring; broadcasts over (..., 3).

    The differences ``g_j = L^2 - 2 E I_j`` come from :func:`energy_momentum_gaps`, and
    ``1 - m`` is formed from them directly, never as ``1 - m``.
    """
    I = np.asarray(moments, float)
    g = energy_momentum_gaps(omega, I)
    I1, I2, I3 = I[..., 0], I[..., 1], I[..., 2]
    g1, g2, g3 = g[..., 0], g[..., 1], g[..., 2]
    upper = g2 >= 0  # the separatrix is taken from this side
    with np.errstate(divide="ignore", invalid="ignore"):
        p2 = np.where(upper, (I3 - I2) * g1, (I2 - I1) * -g3) / (I1 * I2 * I3)
        m = np.where(upper, (I2 - I1) * -g3 / ((I3 - I2) * g1), (I3 - I2) * g1 / ((I2 - I1) * -g3))
        m1 = np.where(upper, (I3 - I1) * g2 / ((I3 - I2) * g1), (I3 - I1) * -g2 / ((I2 - I1) * -g3))
        a2 = np.where(upper, -g3 / (I2 * (I3 - I2)), g1 / (I2 * (I2 - I1)))
        amps = np.stack([-g3 / (I1 * (I3 - I1)), a2, g1 / (I3 * (I3 - I1))], axis=-1)
    return EllipticParameters(upper, np.sqrt(p2), np.clip(m, 0.0, 1.0), np.clip(m1, 0.0, 1.0), np.sqrt(amps))


def _is_steady(I: np.ndarray, w: np.ndarray) -> bool:
    """Whether ``omega`` is constant: ``w x I w = 0`` decided by exact comparisons.

    Not by evaluating ``cross(L, w) == 0``, which depends on round-off. The cases
    (Landau & Lifshitz sec. 33, 37): a sphere (``I1 == I3``); omega along a principal axis (two
    components zero); a symmetric top spinning in its degenerate plane (``I1 == I2`` with
    ``w3 == 0``, ``I2 == I3`` with ``w1 == 0``), where every axis of the plane is principal.
    Moments that are equal only to round-off are not equal here: a body declared symmetric is
    made exactly so by :func:`tumble.mass.principal_frame`.
    """
    zeros = int(np.count_nonzero(w == 0.0))
    return bool(I[0] == I[2] or zeros >= 2 or (I[0] == I[1] and w[2] == 0.0) or (I[1] == I[2] and w[0] == 0.0))


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
        L = I * w
        self._set(steady=_is_steady(I, w))
        if self.steady:
            return
        e = elliptic_parameters(w, I)
        upper, m, m1 = bool(e.upper), float(e.m), float(e.m1)
        r, c = (2, 0) if upper else (0, 2)  # dn axis, cn axis
        amp = e.amplitudes
        sign = 1.0 if w[r] >= 0 else -1.0
        # On the separatrix cn = sech > 0 never changes sign, so the two branches on which w_c
        # and w_r have opposite signs need sn's sign reversed (Euler's equations then still
        # hold: I2 a2 p = (I3 - I1) a1 a3 with sign2 * sign_c * sign_r = +1).
        sign2 = -1.0 if (m1 == 0.0 and w[c] * sign < 0) else 1.0
        sign_c = sign * sign2
        # phase at t = 0 from sn(u0) = w2 / (sign2 a2) and cn(u0) = w_c / (sign_c a_c), taken
        # straight into Carlson's integrals (no angle): u0 = 2 K j0 + F(phi_r), |phi_r| <= pi/2
        s0, c0 = w[1] / (sign2 * amp[1]), w[c] / (sign_c * amp[c])
        h = np.hypot(s0, c0)
        s0, c0 = s0 / h, c0 / h
        j0 = 0.0
        if c0 < 0 and m1 > 0:  # am(u0) beyond +-pi/2: one half period further
            j0 = 1.0 if s0 >= 0 else -1.0
            s0, c0 = -s0, -c0
        c0 = max(c0, 0.0)
        d0 = np.sqrt(c0 * c0 + m1 * s0 * s0)
        Io = I[2] if r == 0 else I[0]
        Ir = I[r]
        n = -Ir * (I[1] - Io) / (Io * (Ir - I[1]))
        K = ellipk(m, m1) if m1 > 0 else np.inf
        u0 = float(carlson_f(s0, c0, m1)) + (2.0 * j0 * K if j0 else 0.0)
        Lnorm = float(np.linalg.norm(L))
        p = float(e.p)
        rate0, rate1 = Lnorm / Ir, Lnorm * (Ir - Io) / (I[0] * I[2])
        # phi(t) = rate0 t + (rate1 / p) [Pi(u) - Pi(u0)] (module docstring), split into a secular
        # part A t + B j and a bounded one b(u_r) - b(u0_r) that is evaluated without cancellation:
        # - m1 = 0: Pi(n; am u | 1) = (u + a atan(a tanh u)) / (1 - n), a = sqrt(-n) (integrate
        #   1 / ((1 - n x^2)(1 - x^2)) in x = sin theta by partial fractions);
        # - |n| <= 1: Pi = F + (Pi - F) with F(am u) = u exactly, so only the O(n) excess is
        #   evaluated: when p is tiny (a nearly symmetric body, a symmetric top spun almost
        #   perpendicular to its axis) rate1 / p is huge and Pi(u) - Pi(u0) would lose it all;
        # - |n| > 1: Pi itself, which is then O(1 / sqrt(-n)).
        if m1 == 0.0:
            mode, A, B = "separatrix", rate0 + rate1 / (1.0 - n), 0.0
        elif abs(n) <= 1.0:
            mode, A, B = "excess", rate0 + rate1, 2.0 * rate1 / p * pi_excess_complete(n, m1)
        else:
            mode, A, B = "pi", rate0, 2.0 * rate1 / p * pi_complete(n, m1)
        self._set(r=r, c=c, sign=sign, sign2=sign2, sign_c=sign_c, amp=amp, p=p, m=m, m1=m1, u0=u0, n=n,
                  Lnorm=Lnorm, rate0=rate0, rate1=rate1, mode=mode, secular=(A, B), j0=j0)
        self._set(b0=float(self._bounded(np.array(u0), *(np.array(x) for x in (s0, c0, d0)))))
        perm = Rotation.from_matrix(np.eye(3)[list(_CYCLE[r])])  # body -> relabelled coordinates
        B0 = self._tilt(L[None, :])[0]
        # R0 = G Rz(0) B0 P  =>  G = R0 P^-1 B0^-1
        self._set(perm=perm, G=self.attitude0 * perm.inv() * B0.inv())

    def _set(self, **values) -> None:
        for k, v in values.items():
            object.__setattr__(self, k, v)

    # -- angular velocity ---------------------------------------------------------------
    def _phase(self, t) -> np.ndarray:
        return self.u0 + self.p * np.asarray(t, float)

    def omega(self, t) -> np.ndarray:
        """Angular velocity at times ``t`` (s), principal frame, rad/s; shape (..., 3)."""
        t = np.asarray(t, float)
        if self.steady:
            return np.broadcast_to(self.omega0, t.shape + (3,)).copy()
        sn, cn, dn = jacobi(self._phase(t), self.m, self.m1)
        w = np.empty(t.shape + (3,))
        w[..., self.c] = self.sign_c * self.amp[self.c] * cn
        w[..., 1] = self.sign2 * self.amp[1] * sn
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

    def _bounded(self, u, sn, cn, dn) -> np.ndarray:
        """The bounded part of ``phi`` at reduced phases (``sn, cn, dn`` of ``u_r``), rad."""
        n, scale = self.n, self.rate1 / self.p
        if self.mode == "separatrix":
            a = np.sqrt(-n)
            return scale * a * np.arctan(a * np.tanh(u)) / (1.0 - n)
        if self.mode == "excess":
            return scale * carlson_pi_excess(n, sn, cn, dn)
        return scale * carlson_pi(n, sn, cn, dn)

    def precession_angle(self, t) -> np.ndarray:
        """The angle ``phi(t)`` turned about L since t = 0, rad (Landau & Lifshitz sec. 37)."""
        t = np.asarray(t, float)
        u = self._phase(t)
        j, sn, cn, dn = jacobi_reduced(u, self.m, self.m1)
        A, B = self.secular
        return A * t + B * (j - self.j0) + (self._bounded(u, sn, cn, dn) - self.b0)

    def attitude(self, t) -> Rotation:
        """Body (principal) to world at times ``t`` (s, 1-D), as a Rotation stack."""
        t = np.atleast_1d(np.asarray(t, float))
        if self.steady:
            return self.attitude0 * Rotation.from_rotvec(np.outer(t, self.omega0))
        L = self.moments * self.omega(t)
        theta, psi = self._tilt_angles(L)
        # Rz(phi) Rx(theta) Rz(psi) in one call: intrinsic z-x-z Euler angles
        euler = Rotation.from_euler("ZXZ", np.stack([self.precession_angle(t), theta, psi], axis=-1))
        return self.G * euler * self.perm
