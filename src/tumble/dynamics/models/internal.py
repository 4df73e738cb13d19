"""Internal models: rotors (the gyrostat) and a spherical nutation damper.

Both exchange angular momentum with the body through internal torques only, so the total
angular momentum is conserved without an external torque. Every vector is in the body's
principal frame (``I1 <= I2 <= I3``); units kg m^2, rad/s, kg m^2/s, N m, J, W.

Gyrostat
--------
A body carrying axisymmetric rotors that spin relative to it about fixed axes ``n_k`` at
``s_k(t)`` (Hughes, *Spacecraft Attitude Dynamics*, Wiley 1986, the chapters on gyrostats and
multi-spin vehicles; Hall, "Momentum transfer in two-rotor gyrostats", J. Guid. Control Dyn.
19(5), 1996). With ``I`` the inertia of the whole, rotors locked, and the internal momentum
``h = sum_k J_k s_k n_k`` (axial moments ``J_k``), the total momentum is ``L = I w + h`` and
Euler's law ``dL/dt|inertial = tau`` in the rotating body frame (Landau & Lifshitz, *Mechanics*,
sec. 36) reads

    ``I w' + w x (I w + h) = tau - h'``.

tumble integrates it in the momentum form ``L' = L x w + tau``, ``w = I^-1 (L - h(t))``, which
needs no ``h'`` and keeps ``L = 0`` exactly when it starts at 0 (a wheel spun up from rest:
``I w = -h`` at every instant).

Energy: the total kinetic energy of body and rotors (each rotor's absolute angular velocity is
``w + s_k n_k``) is ``T = w.I w / 2 + w.h + sum_k J_k s_k^2 / 2``. The motors do work on the
rotors at the rate ``P = sum_k J_k s_k (n_k.w' + s_k')`` (axial torque ``J_k d(n_k.w + s_k)/dt``
times the relative rate ``s_k``), and ``dT/dt = tau.w + P``. Integrating by parts,
``W(t) = [w.h + sum_k J_k s_k^2 / 2]_0^t - integral_0^t h'.w dt``. For constant spins the
conserved quantity is the gyrostat Hamiltonian ``H = sum_i (L_i - h_i)^2 / (2 I_i) = w.I w / 2``
(its rate ``w.I w' = -w.(w x (I w + h)) = 0`` when ``h' = 0`` and ``tau = 0``), while ``T``
itself changes by exactly the motor work.

Linearised about a spin ``W`` about axis 2 with ``h = h e2`` (``h`` along ``W`` when positive),
the perturbation ``w = (x, W + y, z)`` obeys ``I1 x' = -((I3 - I2) W - h) z``,
``I3 z' = -((I2 - I1) W + h) x`` (``y`` decouples), so perturbations grow at
``lambda = sqrt(((I3 - I2) W - h) ((I2 - I1) W + h) / (I1 I3))`` when the product is positive
and wobble at ``sqrt(-product / (I1 I3))`` when it is negative: a wheel with
``h > (I3 - I2) W`` stabilises the intermediate axis (:func:`gyrostat_rate`).

Spherical damper
----------------
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

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple, cast

import numpy as np

from ...typing import ArrayLike, FloatArray, Matrix3, Quaternion, Vector3
from ...validation import MAX_INERTIA, MAX_RATE, check_at_most, check_positive
from ..special.quaternion import quaternion_rate

if TYPE_CHECKING:
    from ...mass import Body, MassProperties, Rotor

__all__ = ["MAX_DAMPER_RATIO", "STIFF_RATIO", "InternalModel", "InternalSamples", "Rotors", "SphericalDamper", "gyrostat_rate"]

#: Largest damper inertia relative to the body's smallest moment: the body's rate
#: ``w = (L - h - J w_d) / I`` loses ``log10(J / I1)`` digits to cancellation (6 here).
MAX_DAMPER_RATIO = 1e6

#: A damper that relaxes faster than this many times the run's spin rate makes the equations
#: stiff: an explicit method's step is then set by the relaxation (stability), not by the
#: rotation. Measured on the (1, 2, 3) kg m^2 tumble at 1.6 rad/s and rtol 1e-12: once stiff,
#: DOP853 takes about 2 k right-hand sides per second of run (``k`` the relaxation rate, 1/s),
#: Radau about 1,200 per radian of rotation whatever ``k``; they cost the same near k / spin = 500.
STIFF_RATIO = 500.0


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


@dataclass(frozen=True, eq=False)
class Rotors:
    """The rotors of a body as the dynamics sees them, in its principal frame.

    Attributes
    ----------
    parts : tuple of Rotor
        The rotor parts (their spin functions).
    axial_moments : ndarray, shape (k,)
        ``J_k``, kg m^2.
    axes : ndarray, shape (k, 3)
        Unit spin axes ``n_k``, principal frame.

    Examples
    --------
    >>> import tumble
    >>> from tumble.dynamics.models.internal import Rotors
    >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, axis=(0, 0, 1), spin_rate=100.0)
    >>> rotors = Rotors.of(tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), wheel]))
    >>> rotors.axial_moments.round(12).tolist(), rotors.axes.tolist()   # design z is principal axis 1 (I1's)
    ([0.005], [[1.0, 0.0, 0.0]])
    """

    parts: tuple[Rotor, ...]
    axial_moments: FloatArray
    axes: FloatArray

    @classmethod
    def of(cls, body: Body | MassProperties) -> Rotors | None:
        """The rotors of a :class:`~tumble.mass.Body` (None without any; a bare
        :class:`~tumble.mass.MassProperties` has none).

        Examples
        --------
        >>> import tumble
        >>> from tumble.dynamics.models.internal import Rotors
        >>> wheel = tumble.Rotor(mass=2.0, radius=0.1, length=0.02, axis=(0, 0, 1), spin_rate=50.0)
        >>> box = tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0))
        >>> Rotors.of(tumble.Body([box, wheel])).axial_moments.round(6).tolist(), Rotors.of(tumble.Body([box]))
        ([0.01], None)
        """
        parts = tuple(getattr(body, "rotors", ()))
        if not parts:
            return None
        A = body.principal_axes  # principal -> design (a Body: it has rotors)
        return cls(parts, np.array([p.axial_moment for p in parts]), np.array([A.T @ p.axis for p in parts]))

    @property
    def constant(self) -> bool:
        """Whether every spin is constant (then ``h`` is, and ``H`` is conserved).

        Examples
        --------
        >>> import tumble
        >>> from tumble.dynamics.models.internal import Rotors
        >>> box = tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0))
        >>> steady = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0)
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0, spin_acceleration=2.0)
        >>> Rotors.of(tumble.Body([box, steady])).constant, Rotors.of(tumble.Body([box, ramp])).constant
        (True, False)
        """
        return all(p.constant_spin for p in self.parts)

    @property
    def derivative_known(self) -> bool:
        """Whether every ``ds/dt`` is known (needed for the motor's work only).

        Examples
        --------
        >>> import math
        >>> import tumble
        >>> from tumble.dynamics.models.internal import Rotors
        >>> box = tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0))
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0, spin_acceleration=2.0)
        >>> wave = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=math.sin)   # no ds/dt given
        >>> Rotors.of(tumble.Body([box, ramp])).derivative_known, Rotors.of(tumble.Body([box, wave])).derivative_known
        (True, False)
        """
        return all(p.constant_spin or not callable(p.spin_rate) or p.spin_acceleration is not None
                   for p in self.parts)

    def spins(self, t: ArrayLike) -> FloatArray:
        """Relative spins ``s_k(t)``, rad/s; shape ``np.shape(t) + (k,)``.

        Examples
        --------
        >>> import tumble
        >>> from tumble.dynamics.models.internal import Rotors
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0, spin_acceleration=2.0)
        >>> rotors = Rotors.of(tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), ramp]))
        >>> rotors.spins([0.0, 1.0, 2.5]).tolist()   # s(t) = 100 + 2 t, one column per rotor
        [[100.0], [102.0], [105.0]]
        """
        return np.stack([p.spin(t) for p in self.parts], axis=-1)

    def spin_derivatives(self, t: ArrayLike) -> FloatArray:
        """``ds_k/dt``, rad/s^2; shape ``np.shape(t) + (k,)`` (requires :attr:`derivative_known`).

        Examples
        --------
        >>> import tumble
        >>> from tumble.dynamics.models.internal import Rotors
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0, spin_acceleration=2.0)
        >>> rotors = Rotors.of(tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), ramp]))
        >>> rotors.spin_derivatives([0.0, 7.0]).tolist()
        [[2.0], [2.0]]
        """
        return np.stack([cast(FloatArray, p.spin_derivative(t)) for p in self.parts], axis=-1)

    def momentum(self, t: ArrayLike) -> Vector3:
        """``h(t) = sum_k J_k s_k(t) n_k``, kg m^2/s; shape ``np.shape(t) + (3,)``.

        Examples
        --------
        >>> import tumble
        >>> from tumble.dynamics.models.internal import Rotors
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, axis=(0, 0, 1), spin_rate=100.0, spin_acceleration=2.0)
        >>> rotors = Rotors.of(tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), ramp]))
        >>> rotors.momentum(1.0).round(12).tolist()   # J s n = 0.005 kg m^2 x 102 rad/s along principal axis 1
        [0.51, 0.0, 0.0]
        """
        return self.spins(t) @ (self.axial_moments[:, None] * self.axes)

    def momentum_rate(self, t: ArrayLike) -> Vector3:
        """``h'(t)``, N m; shape ``np.shape(t) + (3,)``.

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.internal import Rotors
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0, spin_acceleration=2.0)
        >>> rotors = Rotors.of(tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), ramp]))
        >>> dt = 1e-3   # h' against a central difference of h
        >>> bool(np.allclose(rotors.momentum_rate(1.0), (rotors.momentum(1.0 + dt) - rotors.momentum(1.0 - dt)) / (2 * dt)))
        True
        """
        return self.spin_derivatives(t) @ (self.axial_moments[:, None] * self.axes)

    def spin_energy(self, t: ArrayLike) -> FloatArray:
        """``sum_k J_k s_k^2 / 2``, J; shape ``np.shape(t)``.

        Examples
        --------
        >>> import tumble
        >>> from tumble.dynamics.models.internal import Rotors
        >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0)
        >>> rotors = Rotors.of(tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), wheel]))
        >>> round(float(rotors.spin_energy(0.0)), 12)   # J s^2 / 2 = 0.005 x 100^2 / 2
        25.0
        """
        s = self.spins(t)
        return cast(FloatArray, 0.5 * np.sum(self.axial_moments * s * s, axis=-1))


def gyrostat_rate(moments: ArrayLike, spin: ArrayLike, momentum: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Linearised rate about a spin about the intermediate axis with a rotor along it.

    Parameters
    ----------
    moments : array_like, shape (..., 3)
        ``I1 <= I2 <= I3`` of the whole (rotors locked), kg m^2.
    spin : array_like
        ``W``, the body's spin about axis 2, rad/s.
    momentum : array_like
        ``h``, the rotors' momentum along axis 2 (positive along ``W``), kg m^2/s.

    Returns
    -------
    growth, wobble : ndarray
        ``sqrt(p / (I1 I3))`` for ``p = ((I3 - I2) W - h)((I2 - I1) W + h) > 0`` (1/s, else 0)
        and ``sqrt(-p / (I1 I3))`` for ``p < 0`` (rad/s, else 0); derived in the module
        docstring.

    Examples
    --------
    >>> from tumble.dynamics.models.internal import gyrostat_rate
    >>> I = [1.0, 2.0, 3.0]
    >>> [round(float(x), 12) for x in gyrostat_rate(I, 1.0, 0.0)]   # no wheel: the intermediate axis is unstable
    [0.57735026919, 0.0]
    >>> [round(float(x), 12) for x in gyrostat_rate(I, 1.0, 2.0)]   # h > (I3 - I2) W: it wobbles instead
    [0.0, 1.0]
    """
    I = np.asarray(moments, float)
    W, h = np.asarray(spin, float), np.asarray(momentum, float)
    p = ((I[..., 2] - I[..., 1]) * W - h) * ((I[..., 1] - I[..., 0]) * W + h) / (I[..., 0] * I[..., 2])
    return np.sqrt(np.maximum(p, 0.0)), np.sqrt(np.maximum(-p, 0.0))


class InternalSamples(NamedTuple):
    """What an integrator returns for a run with internal models, at the sample times.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.geometric import propagate_internal
    >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
    >>> model = InternalModel(np.array([1.0, 2.0, 3.0]), damper=SphericalDamper(inertia=0.1, damping=0.5))
    >>> run = propagate_internal(model, [0.1, 1.0, 0.1], [0.0, 0.0, 0.0, 1.0], np.linspace(0.0, 10.0, 6))
    >>> run._fields
    ('omega', 'quat', 'damper_omega', 'dissipated', 'work_integral')
    >>> run.omega.shape, run.damper_omega.shape, run.work_integral is None   # no rotors: no motor work
    ((6, 3), (6, 3), True)
    >>> bool(np.all(np.diff(run.dissipated) > 0))
    True
    """

    omega: Vector3  # (n, 3) rad/s
    quat: Quaternion  # (n, 4) body -> world, scalar last
    damper_omega: Vector3 | None  # (n, 3) rad/s
    dissipated: FloatArray | None  # (n,) J
    work_integral: FloatArray | None  # (n,) J: integral of h'.w dt


@dataclass(frozen=True, eq=False)
class InternalModel:
    """Rotors and/or a damper on a body of principal ``moments``: the equations every
    integrator that supports them uses.

    ODE state (DOP853, RK45): ``[L (3), q (4), w_d (3, with a damper), A (1, with varying spins
    of known rate), D (1, with a damper)]``: total momentum, attitude, the damper's rate, the
    integral ``A = integral h'.w dt`` and the energy dissipated.

    Examples
    --------
    >>> import numpy as np
    >>> import tumble
    >>> from tumble.dynamics.models.internal import InternalModel, Rotors
    >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0)
    >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), wheel])
    >>> model = InternalModel(body.principal_moments, Rotors.of(body))
    >>> y0 = model.initial_state([0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0])
    >>> dy = model.rhs(0.0, y0, None)   # L' = L x w: the total momentum only turns in the body frame
    >>> bool(np.isclose(dy[:3] @ y0[:3], 0.0))
    True
    """

    moments: Vector3
    rotors: Rotors | None = None
    damper: SphericalDamper | None = None

    def __post_init__(self) -> None:
        I1 = float(np.min(self.moments))
        if self.damper is not None and not self.damper.inertia <= MAX_DAMPER_RATIO * I1:
            raise ValueError(f"damper: inertia = {self.damper.inertia!r} kg m^2 is more than {MAX_DAMPER_RATIO:g} times "
                             f"the body's smallest moment {I1:.6g} kg m^2; the body's rate would lose "
                             f"{np.log10(self.damper.inertia / I1):.0f} digits")

    @property
    def tracks_work(self) -> bool:
        """Whether ``A = integral h'.w dt`` must be integrated (spins that vary at a known rate).

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> box = tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0))
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0, spin_acceleration=2.0)
        >>> body = tumble.Body([box, ramp])
        >>> InternalModel(body.principal_moments, Rotors.of(body)).tracks_work, InternalModel(np.ones(3)).tracks_work
        (True, False)
        """
        return self.rotors is not None and not self.rotors.constant and self.rotors.derivative_known

    @property
    def damper_inertia(self) -> float:
        """The damper sphere's moment of inertia ``J``, kg m^2 (0 without a damper).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
        >>> InternalModel(np.ones(3), damper=SphericalDamper(inertia=0.2, damping=1.0)).damper_inertia, InternalModel(np.ones(3)).damper_inertia
        (0.2, 0.0)
        """
        return 0.0 if self.damper is None else self.damper.inertia

    @property
    def relaxation_rate(self) -> float:
        """The damper's fastest relaxation rate ``max_i k_i``, 1/s (0 without a damper).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
        >>> model = InternalModel(np.array([1.0, 2.0, 5.0]), damper=SphericalDamper(inertia=0.5, damping=2.0))
        >>> model.relaxation_rate   # (c / J)(1 + J / I1), the largest rate
        6.0
        """
        return 0.0 if self.damper is None else float(np.max(self.damper.rates(self.moments)))

    def stiffness(self, spin: float, t_end: float) -> tuple[float, float]:
        """The damper's stiffness ratio and the rate it is measured against.

        Parameters
        ----------
        spin : float
            The fastest spin of the run, rad/s (:meth:`spin_bound`, plus what a torque adds).
        t_end : float
            The run's duration, s: ``1 / t_end`` stands for the spin of a body at rest.

        Returns
        -------
        ratio : float
            ``max_i k_i / max(spin, 1 / t_end)``: 0 without a damper; above :data:`STIFF_RATIO`
            the run is stiff.
        slow : float
            ``max(spin, 1 / t_end)``, rad/s.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
        >>> model = InternalModel(np.array([1.0, 2.0, 5.0]), damper=SphericalDamper(inertia=0.5, damping=2.0))
        >>> model.stiffness(spin=3.0, t_end=100.0)   # 6 / s against 3 rad/s
        (2.0, 3.0)
        >>> model.stiffness(spin=0.0, t_end=0.5)   # at rest: 1 / t_end stands for the spin
        (3.0, 2.0)
        """
        slow = max(float(spin), 1.0 / float(t_end))
        return self.relaxation_rate / slow, slow

    def spin_bound(self, omega0: ArrayLike, t: ArrayLike) -> float:
        """An estimate of the fastest body spin of a run, rad/s: ``|w0| + 2 max |h| / I1`` over
        the sample times ``t`` (the rotors can hand the body their momentum and reverse it).

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0)
        >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), wheel])
        >>> model = InternalModel(body.principal_moments, Rotors.of(body))
        >>> I1 = body.principal_moments[0]
        >>> bool(np.isclose(model.spin_bound([0.0, 0.0, 1.0], [0.0, 1.0]), 1.0 + 2 * 0.5 / I1))   # |w0| + 2 |h| / I1
        True
        """
        spin = float(np.linalg.norm(omega0))
        if self.rotors is None:
            return spin
        h = np.linalg.norm(self.rotors.momentum(np.asarray(t, float)), axis=-1)
        return spin + 2.0 * float(np.max(h)) / float(np.min(self.moments))

    def momentum(self, t: ArrayLike) -> Vector3:
        """``h(t)``, kg m^2/s, shape ``np.shape(t) + (3,)`` (zeros without rotors).

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0)
        >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), wheel])
        >>> InternalModel(body.principal_moments, Rotors.of(body)).momentum(0.0).round(12).tolist()   # J s along axis 1
        [0.5, 0.0, 0.0]
        >>> InternalModel(np.ones(3)).momentum([0.0, 1.0]).tolist()
        [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
        """
        if self.rotors is None:
            return np.zeros(np.shape(t) + (3,))
        return self.rotors.momentum(t)

    def momentum_rate(self, t: ArrayLike) -> Vector3:
        """``h'(t)``, N m, shape ``np.shape(t) + (3,)`` (zeros unless :attr:`tracks_work`).

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0, spin_acceleration=2.0)
        >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), ramp])
        >>> InternalModel(body.principal_moments, Rotors.of(body)).momentum_rate(3.0).round(12).tolist()   # J s' along axis 1
        [0.01, 0.0, 0.0]
        """
        return cast(Rotors, self.rotors).momentum_rate(t) if self.tracks_work else np.zeros(np.shape(t) + (3,))

    def initial_state(self, omega0: ArrayLike, quat0: ArrayLike) -> FloatArray:
        """The ODE state at t = 0 (the damper turning with the body).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
        >>> model = InternalModel(np.array([1.0, 2.0, 3.0]), damper=SphericalDamper(inertia=0.5, damping=1.0))
        >>> model.initial_state([1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]).tolist()   # L = (I + J) w, q, w_d = w, D = 0
        [1.5, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0]
        """
        w0 = np.asarray(omega0, float)
        J = self.damper_inertia
        parts: list[ArrayLike] = [self.moments * w0 + self.momentum(0.0) + J * w0, quat0]
        if self.damper is not None:
            parts.append(w0)
        parts += [[0.0]] * (int(self.tracks_work) + int(self.damper is not None))
        return np.concatenate(parts)

    def atol(self, atol: float, spin: float) -> FloatArray:
        """Absolute tolerances per state component for a relative ``atol`` and a spin scale (rad/s).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel
        >>> InternalModel(np.array([1.0, 2.0, 4.0])).atol(1e-9, 2.0).tolist()   # L to atol spin I3, q to atol
        [8e-09, 8e-09, 8e-09, 1e-09, 1e-09, 1e-09, 1e-09]
        """
        I = float(np.max(self.moments)) + self.damper_inertia
        n_energy = int(self.tracks_work) + int(self.damper is not None)
        wd = [atol * spin] * (3 if self.damper is not None else 0)
        return np.array([atol * spin * I] * 3 + [atol] * 4 + wd + [atol * spin * spin * I] * n_energy)

    def rhs(self, t: float, y: FloatArray, torque: Callable[[float, Vector3, Quaternion], Vector3] | None) -> FloatArray:
        """``dy/dt``; ``torque(t, w, q)`` returns the external torque in the body frame (N m).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel
        >>> I, w = np.array([1.0, 2.0, 3.0]), np.array([0.3, 1.0, 0.2])
        >>> model = InternalModel(I)
        >>> dy = model.rhs(0.0, model.initial_state(w, [0.0, 0.0, 0.0, 1.0]), None)
        >>> bool(np.allclose(dy[:3], np.cross(I * w, w)))   # no rotor, no damper: Euler's L' = L x w
        True
        """
        damper = cast(SphericalDamper, self.damper)  # read only where wd is set, i.e. with a damper
        L, q = y[:3], y[3:7]
        h = self.momentum(t)
        wd = y[7:10] if self.damper is not None else None
        free = L - h
        w = (free if wd is None else free - damper.inertia * wd) / self.moments
        dL = _cross(L, w)
        if torque is not None:
            dL = dL + torque(t, w, q)
        out: list[ArrayLike] = [dL, quaternion_rate(q, w)]
        if wd is not None:
            slip = wd - w
            out.append(_cross(wd, w) - (damper.damping / damper.inertia) * slip)
        if self.tracks_work:
            out.append([self.momentum_rate(t) @ w])
        if wd is not None:
            out.append([damper.damping * (slip @ slip)])
        return np.concatenate(out)

    def jacobian(self, t: float, y: FloatArray) -> FloatArray:
        """``d(rhs)/dy`` of the torque-free part of :meth:`rhs`, shape (m, m), for implicit methods.

        With ``M = diag(1 / I)``, ``w = M (L - h - J w_d)`` and the slip ``s = w_d - w``:
        ``d(L x w) = -[w]x dL + [L]x dw``; the quaternion rate ``v' = (s_q w + v x w) / 2``,
        ``s_q' = -v.w / 2`` is bilinear in ``q`` and ``w``; ``w_d' = w_d x w - (c / J) s``; the
        work and dissipation rates ``h'.w`` and ``c |s|^2``. An external torque's own dependence
        on the state is left out (the Newton iterations of an implicit method converge with it
        all the same; only the step's error estimate decides the accuracy).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
        >>> model = InternalModel(np.array([1.0, 2.0, 3.0]), damper=SphericalDamper(inertia=0.2, damping=0.5))
        >>> y = model.initial_state([0.3, 1.0, 0.2], [0.1, 0.2, 0.3, 0.927])
        >>> y[7:10] += [0.05, -0.02, 0.01]   # the sphere slipping
        >>> eps = 1e-6   # against central differences of rhs
        >>> numeric = np.array([(model.rhs(0.0, y + e, None) - model.rhs(0.0, y - e, None)) / (2 * eps) for e in eps * np.eye(len(y))]).T
        >>> bool(np.allclose(model.jacobian(0.0, y), numeric, atol=1e-8))
        True
        """
        L, q = y[:3], y[3:7]
        m = len(y)
        M = np.diag(1.0 / self.moments)
        damper = cast(SphericalDamper, self.damper)  # read only where wd is set, i.e. with a damper
        wd = y[7:10] if self.damper is not None else None
        free = L - self.momentum(t)
        w = (free if wd is None else free - damper.inertia * wd) / self.moments
        dw = np.zeros((3, m))  # dw/dy
        dw[:, :3] = M
        if wd is not None:
            dw[:, 7:10] = -damper.inertia * M
        out = np.zeros((m, m))
        out[:3] = _cross_matrix(L) @ dw
        out[:3, :3] -= _cross_matrix(w)
        v, s = q[:3], q[3]
        out[3:6] = 0.5 * (s * np.eye(3) + _cross_matrix(v)) @ dw
        out[3:6, 3:6] -= 0.5 * _cross_matrix(w)
        out[3:6, 6] = 0.5 * w
        out[6] = -0.5 * (v @ dw)
        out[6, 3:6] -= 0.5 * w
        if wd is not None:
            k0 = damper.damping / damper.inertia
            ds = -dw
            ds[:, 7:10] += np.eye(3)  # d(slip)/dy
            out[7:10] = _cross_matrix(wd) @ dw - k0 * ds
            out[7:10, 7:10] -= _cross_matrix(w)
            out[-1] = 2.0 * damper.damping * ((wd - w) @ ds)
        if self.tracks_work:
            out[10 if wd is not None else 7] = self.momentum_rate(t) @ dw
        return out

    def samples(self, t: FloatArray, Y: FloatArray) -> InternalSamples:
        """Unpack ODE states ``Y`` (shape (n, m)) at the times ``t`` (shape (n,)).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.internal import InternalModel, SphericalDamper
        >>> model = InternalModel(np.array([1.0, 2.0, 3.0]), damper=SphericalDamper(inertia=0.5, damping=1.0))
        >>> Y = model.initial_state([1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 2.0])[None, :]   # one state, q not unit
        >>> run = model.samples(np.zeros(1), Y)
        >>> run.omega.tolist(), run.quat.tolist(), run.dissipated.tolist()   # w = (L - J w_d) / I; q normalised
        ([[1.0, 0.0, 0.0]], [[0.0, 0.0, 0.0, 1.0]], [0.0])
        """
        L, q = Y[:, :3], Y[:, 3:7]
        wd = Y[:, 7:10] if self.damper is not None else None
        k = 10 if self.damper is not None else 7
        A = Y[:, k] if self.tracks_work else None
        D = Y[:, -1] if self.damper is not None else None
        return InternalSamples(self.omega(t, L, wd), q / np.linalg.norm(q, axis=1, keepdims=True), wd, D, A)

    def omega(self, t: ArrayLike, L: Vector3, omega_d: Vector3 | None = None) -> Vector3:
        """``w = I^-1 (L - h(t) - J w_d)``, rad/s; ``L`` and ``w_d`` of shape (n, 3).

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0)
        >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), wheel])
        >>> model = InternalModel(body.principal_moments, Rotors.of(body))
        >>> model.omega(0.0, np.array([[0.5, 0.0, 0.0]])).round(12).tolist() == [[0.0, 0.0, 0.0]]   # L = h: the body at rest
        True
        """
        free = L - self.momentum(t)
        if omega_d is not None:
            free = free - cast(SphericalDamper, self.damper).inertia * omega_d
        return free / self.moments

    def trajectory_fields(self, t: FloatArray, run: InternalSamples) -> dict[str, Any]:
        """The optional :class:`~tumble.dynamics.trajectory.Trajectory` fields of a run.

        Examples
        --------
        >>> import numpy as np
        >>> import tumble
        >>> from tumble.dynamics.methods.geometric import propagate_internal
        >>> from tumble.dynamics.models.internal import InternalModel, Rotors
        >>> ramp = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=0.0, spin_acceleration=10.0)
        >>> body = tumble.Body([tumble.Box(mass=10.0, size=(1.0, 2.0, 3.0)), ramp])
        >>> model = InternalModel(body.principal_moments, Rotors.of(body))
        >>> t = np.linspace(0.0, 2.0, 3)
        >>> fields = model.trajectory_fields(t, propagate_internal(model, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0], t))
        >>> sorted(fields)
        ['internal_momentum', 'motor_work', 'rotor_axial_moments', 'rotor_spin']
        >>> J, I1, s = 0.005, body.principal_moments[0], 20.0   # spun up from rest: I w = -h, so the work is
        >>> bool(np.isclose(fields["motor_work"][-1], 0.5 * J * s**2 * (1.0 - J / I1)))   # T = J s^2 / 2 - (J s)^2 / (2 I1)
        True
        """
        fields: dict[str, Any] = {}
        if self.rotors is not None:
            h = self.rotors.momentum(t)
            fields.update(internal_momentum=h, rotor_spin=self.rotors.spins(t),
                          rotor_axial_moments=self.rotors.axial_moments)
            if self.rotors.derivative_known:
                # W(t) = [w.h + sum J s^2 / 2]_0^t - integral h'.w dt (module docstring)
                boundary = np.sum(run.omega * h, axis=1) + self.rotors.spin_energy(t)
                boundary = boundary - (np.sum(run.omega[0] * h[0]) + self.rotors.spin_energy(t[:1])[0])
                A = np.zeros(len(t)) if run.work_integral is None else run.work_integral - run.work_integral[0]
                fields["motor_work"] = boundary - A
        if self.damper is not None:
            fields.update(damper_inertia=self.damper.inertia, damper_omega=run.damper_omega,
                          dissipated=cast(FloatArray, run.dissipated) - cast(FloatArray, run.dissipated)[0])
        return fields


def _cross(a: Vector3, b: Vector3) -> Vector3:
    """``a x b`` of two 3-vectors (np.cross costs ten times more on single vectors, and the
    right-hand side is called hundreds of thousands of times)."""
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def _cross_matrix(v: Vector3) -> Matrix3:
    """``[v]x``, the matrix of ``u -> v x u``."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])
