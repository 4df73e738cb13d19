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

evaluated as a secular part plus a bounded one (see :mod:`tumble.dynamics.methods.exact_kernel`): for
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
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, FloatArray, Quaternion, Vector3
from ..special import ddouble as dd
from .exact_kernel import EllipticMotion, Reduced, is_steady, steady_attitude
from .exact_parameters import EllipticParameters, elliptic_parameters

__all__ = ["MAX_PHASE", "EllipticParameters", "FreeRotation", "check_phase_limit", "elliptic_parameters"]

#: Largest phase (rad) the exact solution follows: the elliptic argument ``u = u0 + p t`` and
#: the precession angle are carried in double-double, with an error of ~3e-32 of the phase
#: (measured against mpmath: 2e-11 rad at 6.6e20 rad), so ~3e-8 rad here; 1e-6 rad would be
#: reached at ~3e25 rad.
MAX_PHASE = 1e24


def check_phase_limit(moments: ArrayLike, omega0: ArrayLike, t_end: float) -> None:
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

    Examples
    --------
    >>> from tumble.dynamics.methods.exact import check_phase_limit
    >>> check_phase_limit([1.0, 2.0, 3.0], [0.1, 1.0, 0.1], 100.0)  # far below: nothing to say
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


@dataclass(frozen=True, eq=False)
class FreeRotation:
    """The torque-free motion of a rigid body from ``omega0`` and ``attitude0``, exactly.

    The one-body front of the exact solution's kernel
    (:class:`tumble.dynamics.methods.exact_kernel.EllipticMotion` at N = 1, the same code as
    :func:`tumble.dynamics.methods.exact_batch.free_rotation_batch` below its compiled size); its parameters are built
    once, and the reduced phase of the last times asked for is kept, as ``omega(t)`` and
    ``attitude(t)`` are usually asked for the same times.

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
    >>> from tumble.dynamics.methods.exact import FreeRotation
    >>> motion = FreeRotation(np.array([1.0, 2.0, 3.0]), np.array([0.1, 1.0, 0.1]), Rotation.identity())
    >>> w, R = motion.omega([0.0, 1.0]), motion.attitude([0.0, 1.0])
    >>> bool(np.allclose(w[0], [0.1, 1.0, 0.1])), len(R)
    (True, 2)
    """

    moments: Vector3
    omega0: Vector3
    attitude0: Rotation
    # Set by __post_init__ (not parameters): whether omega is constant (is_steady), the fastest
    # rate of any phase (1/s), 1 - m (nan for a steady motion), the attitude at t = 0 as a
    # (1, 4) quaternion, the kernel (elliptic motions only) and the last times asked for with
    # their reduced phases and omega.
    steady: bool = field(init=False, repr=False)
    phase_rate: float = field(init=False, repr=False)
    m1: float = field(init=False, repr=False)
    _quat0: Quaternion = field(init=False, repr=False)
    _motion: EllipticMotion = field(init=False, repr=False)
    _last: tuple[FloatArray, tuple[Reduced, Vector3]] = field(init=False, repr=False)

    if TYPE_CHECKING:  # the generated __init__ takes array_like; __post_init__ makes the arrays

        def __init__(self, moments: ArrayLike, omega0: ArrayLike, attitude0: Rotation) -> None: ...

    def __post_init__(self) -> None:
        I = np.asarray(self.moments, float)
        w = np.asarray(self.omega0, float)
        object.__setattr__(self, "moments", I)
        object.__setattr__(self, "omega0", w)
        if not (I.shape == (3,) and np.all(I > 0) and np.all(np.diff(I) >= 0)):
            raise ValueError(f"moments = {I.tolist()} must be three positive numbers in ascending order (kg m^2)")
        if not (w.shape == (3,) and np.all(np.isfinite(w))):
            raise ValueError(f"omega0 = {w.tolist()} must be three finite numbers (rad/s)")
        steady = bool(is_steady(I, w))
        object.__setattr__(self, "steady", steady)
        object.__setattr__(self, "_quat0", self.attitude0.as_quat()[None, :])
        if steady:
            spin, e = dd.norm([(x, 0.0) for x in w])
            object.__setattr__(self, "phase_rate", float(np.ldexp(spin[0], e)))
            object.__setattr__(self, "m1", math.nan)
            return
        motion = EllipticMotion(I[None, :], w[None, :])
        object.__setattr__(self, "_motion", motion)
        object.__setattr__(self, "phase_rate", float(motion.phase_rate[0]))
        object.__setattr__(self, "m1", float(motion.m1[0]))

    @property
    def max_time(self) -> float:
        """Longest ``|t|`` (s) before a phase of the motion exceeds :data:`MAX_PHASE`.

        Examples
        --------
        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.methods.exact import MAX_PHASE, FreeRotation
        >>> motion = FreeRotation([1.0, 2.0, 3.0], [0.1, 1.0, 0.1], Rotation.identity())
        >>> bool(np.isclose(motion.max_time * motion.phase_rate, MAX_PHASE))
        True
        >>> motion.omega(2.0 * motion.max_time)
        Traceback (most recent call last):
        ...
        ValueError: t_end = ... s takes this motion to a phase of ... rad, beyond the ... rad up to which the exact solution keeps its phase error below 1e-6 rad; at most ... s
        """
        return MAX_PHASE / self.phase_rate if self.phase_rate > 0 else math.inf

    def _check_time(self, t: ArrayLike) -> None:
        t_max = float(np.max(np.abs(t))) if np.size(t) else 0.0
        if not t_max <= self.max_time:
            raise ValueError(
                f"t_end = {t_max:g} s takes this motion to a phase of {t_max * self.phase_rate:.3g} rad, beyond "
                f"the {MAX_PHASE:g} rad up to which the exact solution keeps its phase error below 1e-6 rad; "
                f"at most {self.max_time:.6g} s"
            )

    def _reduced(self, t: FloatArray) -> tuple[Reduced, Vector3]:
        """The kernel's reduced phases and omega at times ``t`` (1-D), kept for the next call."""
        last: tuple[FloatArray, tuple[Reduced, Vector3]] | None = self.__dict__.get("_last")
        if last is not None and last[0].shape == t.shape and np.array_equal(last[0], t):
            return last[1]
        self._check_time(t)
        reduced = self._motion.reduce(t)
        answer = reduced, self._motion.omega(reduced)
        object.__setattr__(self, "_last", (t.copy(), answer))
        return answer

    def omega(self, t: ArrayLike) -> Vector3:
        """Angular velocity at times ``t`` (s), principal frame, rad/s; shape (..., 3).

        Examples
        --------
        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from scipy.special import ellipk
        >>> from tumble.dynamics.methods.exact import FreeRotation, elliptic_parameters
        >>> I, w0 = np.array([1.0, 2.0, 3.0]), np.array([0.1, 1.0, 0.1])
        >>> motion = FreeRotation(I, w0, Rotation.identity())
        >>> par = elliptic_parameters(w0, I)
        >>> period = 4.0 * ellipk(par.m) / par.p   # omega's period 4 K / p
        >>> bool(np.allclose(motion.omega(period), w0, atol=1e-12))
        True
        >>> w = motion.omega(np.linspace(0.0, 50.0, 6))   # energy and |L| hold (no torque)
        >>> bool(np.allclose((I * w**2).sum(-1), I @ w0**2) and np.allclose(np.linalg.norm(I * w, axis=-1), np.linalg.norm(I * w0)))
        True
        """
        t = np.asarray(t, float)
        if self.steady:
            return np.broadcast_to(self.omega0, t.shape + (3,)).copy()
        omega: Vector3 = self._reduced(t.ravel())[1][0].reshape(t.shape + (3,))
        omega[t == 0.0] = self.omega0  # the start as given, not the closed form's few ulps off it
        return omega

    def attitude(self, t: ArrayLike) -> Rotation:
        """Body (principal) to world at times ``t`` (s, 1-D), as a Rotation stack.

        Examples
        --------
        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.methods.exact import FreeRotation
        >>> I, w0 = np.array([1.0, 2.0, 3.0]), np.array([0.1, 1.0, 0.1])
        >>> motion = FreeRotation(I, w0, Rotation.identity())
        >>> t = np.array([0.0, 10.0, 1000.0])
        >>> L_world = motion.attitude(t).apply(I * motion.omega(t))   # the angular momentum is fixed in space
        >>> L_world.round(12).tolist()
        [[0.1, 2.0, 0.3], [0.1, 2.0, 0.3], [0.1, 2.0, 0.3]]
        """
        t = np.atleast_1d(np.asarray(t, float))
        self._check_time(t)
        if self.steady:
            return Rotation.from_quat(steady_attitude(self.omega0[None, :], self._quat0, t)[0])
        reduced, omega = self._reduced(t)
        quat = self._motion.attitude(self._quat0, t, reduced, omega)[0]
        quat[t == 0.0] = self._quat0  # the start as given (the closed form's is within ~1e-16 of it)
        return Rotation.from_quat(quat)
