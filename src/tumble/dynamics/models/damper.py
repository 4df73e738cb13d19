"""The spherical nutation damper: a sphere in a viscous spherical cavity of the body.

A sphere of moment of inertia ``J`` about its centre turns freely in a concentric spherical
cavity of the body and is coupled to it by a viscous torque ``c (w_d - w)`` on the body (and
its opposite on the sphere); ``w_d`` is the sphere's inertial angular velocity in body
components. For creeping flow of a fluid of viscosity ``mu`` between a sphere of radius ``a`` and
a cavity of radius ``b``, ``c = 8 pi mu a^3 b^3 / (b^3 - a^3)`` (the torque between concentric
rotating spheres, Landau & Lifshitz, *Fluid Mechanics*, section on flow at small Reynolds
numbers). The equations are Euler's law for each of the two bodies (L&L *Mechanics* sec. 36):

    ``I w' + w x (I w + h) = tau - h' + c (w_d - w)``,
    ``J (w_d' + w x w_d) = -c (w_d - w)``,

so ``L = I w + h + J w_d`` is conserved and the kinetic energy falls by the dissipation
``c |w_d - w|^2`` (Likins, *Effects of energy dissipation on the free body motions of
spacecraft*, JPL TR 32-860, 1966: the energy-sink argument for the major-axis rule). The end
state is a rigid spin about the major axis, ``|w| = |L| / (I3 + J)`` (``h = 0``).
The damper's moment ``J`` is *not* part of the body's inertia ``I``: the body's parts hold the
sphere's mass (its centre's parallel-axis term) but not its own ``J``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ...typing import ArrayLike, FloatArray, Vector3
from ...validation import MAX_INERTIA, MAX_RATE, check_at_most, check_positive

__all__ = ["MAX_DAMPER_RATIO", "SphericalDamper", "damper_rate_components"]

#: Largest damper inertia relative to the body's smallest moment: the body's rate
#: ``w = (L - h - J w_d) / I`` loses ``log10(J / I1)`` digits to cancellation (6 here).
MAX_DAMPER_RATIO = 1e6


@dataclass(frozen=True)
class SphericalDamper:
    """A spherical nutation damper: a sphere of moment ``inertia`` in a viscous spherical cavity.

    Parameters
    ----------
    inertia : float
        ``J``, the sphere's moment of inertia about its centre, kg m^2 (> 0). Not included in
        the body's parts.
    damping : float
        ``c``, the viscous coupling, N m s (>= 0): the torque on the body is ``c (w_d - w)``.
        ``J`` is at most :data:`~tumble.validation.MAX_INERTIA` (1e50 kg m^2) and the
        relaxation rate ``c / J`` at most :data:`~tumble.validation.MAX_RATE` (1e15 1/s);
        with a body, ``J`` is at most :data:`MAX_DAMPER_RATIO` times its smallest moment.

    Notes
    -----
    The sphere starts turning with the body (``w_d(0) = w(0)``). See the module docstring for the
    equations and their sources.

    Examples
    --------
    >>> import tumble
    >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 2.5])
    >>> damper = tumble.SphericalDamper(inertia=0.3, damping=0.3)
    >>> traj = tumble.simulate(body, [1.0, 0.05, 0.0], t_end=300.0, samples=5, damper=damper)
    >>> traj.nutation_angle.round(2).tolist()   # from a spin about the minor axis to a flat spin about the major one
    [1.57, 1.13, 0.45, 0.13, 0.01]
    >>> bool(traj.dissipated[-1] > 0)   # energy the damper took out, J
    True
    """

    inertia: float
    damping: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "inertia", check_positive("inertia", self.inertia, "kg m^2", at_most=MAX_INERTIA))
        object.__setattr__(self, "damping", check_positive("damping", self.damping, "N m s", allow_zero=True))
        check_at_most(f"damping = {self.damping!r} N m s with inertia = {self.inertia!r} kg m^2 relaxes at c / J",
                      self.damping / self.inertia, "1/s", MAX_RATE)

    def rates(self, moments: ArrayLike) -> Vector3:
        """Relaxation rates ``k_i = (c / J)(1 + J / I_i)`` of ``w_d`` at fixed L, 1/s; shape of moments.

        Examples
        --------
        >>> from tumble.dynamics.models.internal import SphericalDamper
        >>> SphericalDamper(inertia=0.5, damping=2.0).rates([1.0, 2.0, 5.0]).tolist()   # (c / J)(1 + J / I_i)
        [6.0, 5.0, 4.4]
        """
        return self.damping / self.inertia * (1.0 + self.inertia / np.asarray(moments, float))

    def relax(self, free: FloatArray, omega_d: FloatArray, moments: FloatArray, dt: float) -> tuple[FloatArray, FloatArray]:
        """Exact flow of the viscous coupling alone for ``dt`` s (L and the attitude fixed).

        With ``w = (free - J w_d) / I`` (``free = L - h``) the coupling
        ``w_d' = -(c / J)(w_d - w)`` separates by component:
        ``w_d,i -> w_inf,i + (w_d,i - w_inf,i) exp(-k_i dt)``, ``w_inf,i = free_i / (I_i + J)``,
        and the energy dissipated, ``integral c |w_d - w|^2 dt``, is
        ``sum_i J (1 + J / I_i) (w_d,i - w_inf,i)^2 (1 - exp(-2 k_i dt)) / 2``.

        Parameters
        ----------
        free, omega_d, moments : ndarray, shape (3, ...)
            ``L - h`` (kg m^2/s), ``w_d`` (rad/s) and ``I`` (kg m^2), components first.
        dt : float
            Duration, s (negative steps of a composition run the flow backwards).

        Returns
        -------
        omega_d : ndarray, shape (3, ...)
        dissipated : ndarray, shape (...)
            J.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import SphericalDamper
        >>> damper = SphericalDamper(inertia=0.5, damping=2.0)
        >>> I, free, wd = np.array([1.0, 2.0, 5.0]), np.array([1.0, 0.0, 3.0]), np.zeros(3)
        >>> wd_long, lost = damper.relax(free, wd, I, 100.0)   # long after: w_d = w = free / (I + J)
        >>> wd_long.round(12).tolist()
        [0.666666666667, 0.0, 0.545454545455]
        >>> energy = lambda wd: 0.5 * np.sum((free - 0.5 * wd) ** 2 / I) + 0.5 * 0.5 * wd @ wd   # body + sphere
        >>> wd_1, lost_1 = damper.relax(free, wd, I, 0.1)
        >>> bool(np.isclose(energy(wd) - energy(wd_1), lost_1))   # what the energy lost, the damper dissipated
        True
        """
        J = self.inertia
        k = self.rates(moments)
        w_inf = free / (moments + J)
        delta = omega_d - w_inf
        e1 = -np.expm1(-2.0 * k * dt)  # 1 - exp(-2 k dt), accurate for small k dt
        lost = 0.5 * J * np.sum((1.0 + J / moments) * delta * delta * e1, axis=0)
        return w_inf + delta * np.exp(-k * dt), lost


def damper_rate_components(d0: Any, d1: Any, d2: Any, w0: Any, w1: Any, w2: Any, damping: Any,
                           inertia: Any) -> tuple[Any, Any, Any, Any]:
    """The sphere's equation ``w_d' = w_d x w - (c / J)(w_d - w)`` and the dissipation rate
    ``c |w_d - w|^2`` (W), component by component (module docstring: Euler's law for the sphere,
    L&L *Mechanics* sec. 36, in the body's frame; Likins 1966 for the energy sink).

    ``w_d`` the sphere's inertial rate and ``w`` the body's (rad/s, body frame), ``c`` the damping
    (N m s), ``J`` the sphere's moment (kg m^2). The one writing of the damper's equations, over
    floats (the compiled engine, :mod:`tumble.dynamics.engine.damped`) or arrays of one shape
    (:meth:`tumble.dynamics.models.internal.InternalModel.rhs`).

    Examples
    --------
    >>> from tumble.dynamics.models.damper import damper_rate_components
    >>> damper_rate_components(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 0.5)   # w_d x w = (0, -1, 0), slip (1, 0, -1), c / J = 4
    (-4.0, -1.0, 4.0, 4.0)
    """
    k = damping / inertia
    s0, s1, s2 = d0 - w0, d1 - w1, d2 - w2
    return (d1 * w2 - d2 * w1 - k * s0, d2 * w0 - d0 * w2 - k * s1, d0 * w1 - d1 * w0 - k * s2,
            damping * (s0 * s0 + s1 * s1 + s2 * s2))
