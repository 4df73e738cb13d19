"""Rotors: a body carrying axisymmetric wheels that spin about fixed axes (the gyrostat).

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
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, cast

import numpy as np

from ...typing import ArrayLike, FloatArray, Vector3

if TYPE_CHECKING:
    from ...mass import Body, MassProperties, Rotor

__all__ = ["Rotors", "gyrostat_rate"]


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
    #: The last few :meth:`spins` of spins that are numbers (no function), by the times' bytes.
    _spins: dict[tuple[tuple[int, ...], bytes], FloatArray] = field(default_factory=dict, init=False, repr=False)

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
        return _rotors_of(body) if getattr(body, "rotors", ()) else None

    @classmethod
    def _build(cls, body: Body) -> Rotors:
        parts = tuple(body.rotors)
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

    @functools.cached_property
    def constant_rates(self) -> FloatArray | None:
        """The spins ``s_k`` (rad/s) where every one is constant (:attr:`constant`), else None:
        :meth:`spins`, :meth:`momentum` and :meth:`spin_energy` of a run's samples are then these
        numbers repeated, not evaluated sample by sample (a short run's fixed cost).

        Examples
        --------
        >>> import tumble
        >>> from tumble.dynamics.models.internal import Rotors
        >>> wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=100.0)
        >>> rotors = Rotors.of(tumble.Body([tumble.Sphere(mass=5.0, radius=0.5), wheel]))
        >>> rotors.constant_rates.tolist(), rotors.spins([0.0, 5.0]).tolist()
        ([100.0], [[100.0], [100.0]])
        """
        if not self.constant:
            return None
        return np.array([p.spin(0.0) for p in self.parts], dtype=float)  # the part's own check of the rate

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
        times = np.asarray(t, dtype=float)
        rates = self.constant_rates
        if rates is not None:  # constant spins: the rates themselves (``s + 0 t`` is ``s`` exactly)
            return _repeated(rates, times.shape)
        if times.size > _KEPT_SAMPLES or any(callable(p.spin_rate) for p in self.parts):  # a function: every call
            return np.stack([p.spin(t) for p in self.parts], axis=-1)
        key = (times.shape, times.tobytes())
        spins = self._spins.get(key)
        if spins is None:
            spins = np.stack([p.spin(times) for p in self.parts], axis=-1)
            if len(self._spins) >= _KEPT_SPINS:  # clear(): one step, safe between threads
                self._spins.clear()
            self._spins[key] = spins
        return spins.copy()

    def spin_derivatives(self, t: ArrayLike) -> FloatArray:
        """``ds_k/dt``, rad/s^2; shape ``np.shape(t) + (k,)`` (requires :attr:`derivative_known`).

        Examples
        --------
        >>> import tumble
        >>> from tumble.dynamics.models.rotors import Rotors
        >>> brake = tumble.Rotor(mass=2.0, radius=0.2, length=0.05, spin_rate=50.0, spin_acceleration=-3.0)
        >>> Rotors.of(tumble.Body([tumble.Sphere(mass=5.0, radius=0.5), brake])).spin_derivatives([0.0, 7.0]).tolist()
        [[-3.0], [-3.0]]
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
        if self.constant_rates is not None:
            return _repeated(self._constant_momentum, np.shape(t))
        return self.spins(t) @ (self.axial_moments[:, None] * self.axes)

    @functools.cached_property
    def _constant_momentum(self) -> Vector3:
        """``h`` of constant spins (:attr:`constant_rates`), kg m^2/s."""
        return cast(FloatArray, self.constant_rates) @ (self.axial_moments[:, None] * self.axes)

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
        if self.constant_rates is not None:
            return np.full(np.shape(t), self._constant_energy)
        s = self.spins(t)
        return cast(FloatArray, 0.5 * np.sum(self.axial_moments * s * s, axis=-1))

    @functools.cached_property
    def _constant_energy(self) -> float:
        """``sum_k J_k s_k^2 / 2`` of constant spins (:attr:`constant_rates`), J."""
        s = cast(FloatArray, self.constant_rates)
        return float(0.5 * np.sum(self.axial_moments * s * s))


def _repeated(row: FloatArray, shape: tuple[int, ...]) -> FloatArray:
    """``row`` repeated over ``shape``: an array of shape ``shape + row.shape``."""
    out = np.empty(shape + row.shape)
    out[...] = row
    return out


#: How many :meth:`Rotors.spins` a body's rotors keep (a run asks for three: the samples, t = 0
#: and the first sample).
_KEPT_SPINS = 4
#: Longest sample times whose spins are kept (the fixed cost matters in short runs only).
_KEPT_SAMPLES = 10_000


@functools.lru_cache(maxsize=64)
def _rotors_of(body: Body) -> Rotors:
    """:meth:`Rotors.of` a body with rotors, kept for its next runs (a Body is immutable and
    hashed by identity)."""
    return Rotors._build(body)


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
