"""The result of a simulation: a sampled rigid-body motion and what it conserves.

With rotors (a gyrostat) or a damper (:mod:`tumble.dynamics.models.internal`) the trajectory carries
their state per sample, and ``energy``, ``angular_momentum`` and ``angular_momentum_world`` are
the totals of body, rotors and damper.
"""

from __future__ import annotations

import functools
from dataclasses import MISSING, dataclass
from dataclasses import fields as dataclass_fields
from typing import Any, cast

import numpy as np
from scipy.spatial.transform import Rotation

from ..mass import INERTIA_RTOL
from ..typing import ArrayLike, FloatArray
from ..validation import short_repr
from . import _display
from .euler import angular_momentum, kinetic_energy, relative_drift

__all__ = ["Trajectory"]


_OPTIONAL_ARRAYS = ("internal_momentum", "rotor_spin", "rotor_axial_moments", "motor_work", "damper_omega",
                    "dissipated")


#: Relative size under which a total angular momentum counts as zero (round-off of a sum).
ZERO_MOMENTUM_RTOL = 1e-12


def _array(a: ArrayLike) -> FloatArray:
    # writeable on purpose: scipy's Rotation.apply refuses read-only arrays (see mass.body)
    return np.asarray(a, dtype=float)


class _LazyRotation:
    """A field of scipy Rotations that may be given as unit quaternions, (n, 4) scalar last, and
    is made a Rotation on first use: building one costs ~10 us, more than a compiled run of a
    few hundred steps (issue 31), and :attr:`Trajectory.quat` reads the quaternions without it.

    A data descriptor, set on the class after the dataclass is made (so the field keeps no
    default): the generated ``__init__`` stores through :meth:`__set__`.
    """

    def __set_name__(self, owner: type, name: str) -> None:
        self.slot = f"_{name}_value"

    def __get__(self, obj: object, owner: type | None = None) -> Any:
        if obj is None:  # on the class: the descriptor itself, as a property
            return self
        value = obj.__dict__[self.slot]
        if not isinstance(value, Rotation):
            value = Rotation.from_quat(value)
            obj.__dict__[self.slot] = value
        return value

    def __set__(self, obj: object, value: Rotation | FloatArray) -> None:
        obj.__dict__[self.slot] = value if isinstance(value, Rotation) else _array(value)

    @staticmethod
    def quaternions(obj: object, name: str) -> FloatArray:
        """The field's quaternions, without building the Rotation if it was given as quaternions."""
        value = obj.__dict__[f"_{name}_value"]
        return value if not isinstance(value, Rotation) else _array(value.as_quat())


@dataclass(frozen=True, eq=False)
class Trajectory:
    """A sampled motion of a rigid body. Frozen; derived quantities are computed once, so
    its arrays must not be modified in place.

    Attributes
    ----------
    t : ndarray, shape (n,)
        Sample times, s.
    omega : ndarray, shape (n, 3)
        Angular velocity in the principal frame, rad/s.
    attitude : scipy.spatial.transform.Rotation, n rotations
        Body (principal) frame to world: ``x_world = attitude[k].apply(x_body)``. May be given
        as unit quaternions (n, 4), scalar last: the Rotation is then built on first use.
    moments : ndarray, shape (3,)
        Principal moments ``I1 <= I2 <= I3``, kg m^2.
    principal_axes : ndarray, shape (3, 3)
        Principal -> design rotation of the body (columns are the axes in the design frame).
    method : str
        Name of the integration method that ran: the one asked for, or the one ``"auto"`` chose
        (then :attr:`auto` is True), except ``"radau"`` where ``"dop853"`` handed a stiff damper
        to scipy's Radau IIA (:data:`~tumble.dynamics.models.internal.STIFF_RATIO`).
    torque_free : bool
        Whether no external torque acted (then energy, |L| and L_world are conserved).
    body_name : str
        Label of the body.
    internal_momentum : ndarray, shape (n, 3), optional
        The rotors' internal angular momentum ``h``, principal frame, kg m^2/s (None: no rotors).
    rotor_spin : ndarray, shape (n, k), optional
        Each rotor's spin relative to the body, rad/s.
    rotor_axial_moments : ndarray, shape (k,), optional
        Each rotor's axial moment ``J_k``, kg m^2.
    motor_work : ndarray, shape (n,), optional
        Work done by the rotors' motors since t = 0, J (None without rotors, or for a
        spin function given without its derivative).
    damper_inertia : float, optional
        The spherical damper's moment ``J``, kg m^2 (None: no damper).
    damper_omega : ndarray, shape (n, 3), optional
        The damper sphere's inertial angular velocity in principal-frame components, rad/s.
    dissipated : ndarray, shape (n,), optional
        Energy dissipated by the damper since t = 0, J.
    auto : bool
        Whether ``method`` was chosen by ``simulate(method="auto")``, the default; the repr and
        the summary then say ``"dop853 (auto)"`` (:attr:`method_label`).

    Examples
    --------
    >>> import tumble
    >>> traj = tumble.simulate(tumble.t_handle(), [0.0, 0.0, 2.0], t_end=3.0, samples=4)   # about the major axis
    >>> traj
    Trajectory('T-handle', exact (auto), 4 samples, t = 0..3 s, torque-free)
    >>> len(traj), traj.moments.round(6).tolist()
    (4, [0.125, 0.3125, 0.4375])
    >>> traj.omega[-1].round(6).tolist()   # a steady spin
    [0.0, 0.0, 2.0]
    """

    t: np.ndarray
    omega: np.ndarray
    attitude: Rotation  # made a _LazyRotation after the class (below): it has no default
    moments: np.ndarray
    principal_axes: np.ndarray
    method: str
    torque_free: bool = True
    body_name: str = "body"
    internal_momentum: np.ndarray | None = None
    rotor_spin: np.ndarray | None = None
    rotor_axial_moments: np.ndarray | None = None
    motor_work: np.ndarray | None = None
    damper_inertia: float | None = None
    damper_omega: np.ndarray | None = None
    dissipated: np.ndarray | None = None
    auto: bool = False

    def __post_init__(self) -> None:
        fields = self.__dict__  # the instance's own values: float arrays already are kept as they are
        for name in ("t", "omega", "moments", "principal_axes", *_OPTIONAL_ARRAYS):
            value = fields[name]
            if value is not None and not (type(value) is np.ndarray and value.dtype == np.float64):
                fields[name] = _array(value)

    @classmethod
    def of_samples(cls, t: FloatArray, omega: FloatArray, quat: FloatArray, moments: FloatArray,
                   principal_axes: FloatArray, method: str, torque_free: bool = True, body_name: str = "body",
                   auto: bool = False, **internal: Any) -> Trajectory:
        """A trajectory of float64 arrays as an integrator returns them (the quaternions ``quat``, (n, 4),
        scalar last, made a Rotation when first asked for), without the checks of ``__init__``:
        the fields set directly, ~1.5 us less a run (issue 38). ``internal``: the optional fields.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.trajectory import Trajectory
        >>> traj = Trajectory.of_samples(np.array([0.0, 1.0]), np.zeros((2, 3)), np.tile([0.0, 0.0, 0.0, 1.0], (2, 1)),
        ...                              np.array([1.0, 2.0, 3.0]), np.eye(3), "rk8")
        >>> traj.attitude.as_rotvec().tolist()
        [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
        """
        if internal:  # rotors or a damper: the checked path
            return cls(t=t, omega=omega, attitude=quat, moments=moments, principal_axes=principal_axes,
                       method=method, torque_free=torque_free, body_name=body_name, auto=auto, **internal)
        traj = object.__new__(cls)
        traj.__dict__.update(_FIELD_DEFAULTS)
        traj.__dict__.update(t=t, omega=omega, _attitude_value=quat, moments=moments, principal_axes=principal_axes,
                             method=method, torque_free=torque_free, body_name=body_name, auto=auto)
        return traj

    @property
    def method_label(self) -> str:
        """The method as the repr, the summary and the command line name it: ``"rk8 (auto)"`` where
        ``"auto"`` chose it, else :attr:`method`.

        Examples
        --------
        >>> import tumble
        >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])
        >>> tumble.simulate(body, [0.0, 0.0, 2.0], t_end=1.0, samples=2).method_label
        'exact (auto)'
        >>> tumble.simulate(body, [0.0, 0.0, 2.0], t_end=1.0, samples=2, method="exact").method_label
        'exact'
        """
        return f"{self.method} (auto)" if self.auto else self.method

    @property
    def rigid(self) -> bool:
        """Whether this is one rigid body: no rotors and no damper.

        Examples
        --------
        >>> import tumble
        >>> tumble.simulate(tumble.t_handle(), [0.0, 0.0, 2.0], t_end=1.0, samples=2).rigid
        True
        """
        return self.internal_momentum is None and self.damper_omega is None

    def __len__(self) -> int:
        return len(self.t)

    def __getitem__(self, index: slice | ArrayLike) -> Trajectory:
        """The trajectory at some of its samples: a slice (``traj[::10]``, ``traj[-1:]``), a boolean
        mask (``traj[traj.t >= 5.0]``) or sample numbers, in a new Trajectory with every per-sample
        array taken the same way. A single number is refused: ``traj.omega[-1]`` is one sample's value.

        Examples
        --------
        >>> import tumble
        >>> traj = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=20.0, samples=201)
        >>> late = traj[traj.t >= 10.0]
        >>> len(late), float(late.t[0]), bool((late.omega == traj.omega[100:]).all())
        (101, 10.0, True)
        >>> traj[::50].t.tolist()
        [0.0, 5.0, 10.0, 15.0, 20.0]
        >>> traj[-1]
        Traceback (most recent call last):
        ...
        TypeError: traj[-1]: a Trajectory is indexed by a slice, a boolean mask or a list of samples (traj[-1:] keeps the sample; traj.omega[-1] is its omega)
        >>> traj[traj.t > 100.0]
        Traceback (most recent call last):
        ...
        IndexError: the mask selects no sample of 201 (t = 0..20 s)
        >>> traj[0.5]
        Traceback (most recent call last):
        ...
        TypeError: traj[0.5]: a Trajectory is indexed by a slice, a boolean mask or a list of sample numbers (whole numbers from 0 to 200; the samples after a time t0: traj[traj.t >= t0])
        """
        n = len(self.t)
        if isinstance(index, slice):
            what = f"traj[{'' if index.start is None else index.start}:{'' if index.stop is None else index.stop}" \
                   f"{'' if index.step is None else f':{index.step}'}]"
        else:
            if isinstance(index, (int, np.integer)) and -n <= index < n:
                raise TypeError(f"traj[{index!r}]: a Trajectory is indexed by a slice, a boolean mask or a list of "
                                f"samples (traj[{index!r}:] keeps the sample; traj.omega[{index!r}] is its omega)")
            if np.ndim(index) != 1:
                raise TypeError(f"traj[{short_repr(index)}]: a Trajectory is indexed by a slice, a boolean mask or a list "
                                f"of sample numbers (whole numbers from 0 to {n - 1}; the samples after a time t0: "
                                f"traj[traj.t >= t0])")
            index = np.asarray(index)
            if index.size and index.dtype.kind not in "biu":
                raise TypeError(f"traj[{short_repr(index.tolist())}]: a Trajectory is indexed by a slice, a boolean mask "
                                f"or a list of sample numbers (whole numbers from 0 to {n - 1})")
            index = index if index.size else index.astype(int)
            if index.dtype == bool and len(index) != n:
                raise IndexError(f"the mask has {len(index)} entries; the trajectory has {n} samples")
            what = "the mask" if index.dtype == bool else f"traj[{short_repr(index.tolist())}]"
        try:
            t = self.t[index]
        except IndexError:  # a sample number beyond the run
            raise IndexError(f"{what}: a sample number beyond the {n} samples (0 to {n - 1})") from None
        if len(t) == 0:
            raise IndexError(f"{what} selects no sample of {n} (t = {self.t[0]:g}..{self.t[-1]:g} s)")
        if not np.all(np.diff(t) > 0):  # a reversed slice, numbers out of order or twice: time would not increase
            raise IndexError(f"{what}: a Trajectory keeps its samples in time order, each once; the arrays reverse "
                             f"(traj.omega[::-1])")
        per_sample = {name: None if getattr(self, name) is None else getattr(self, name)[index]
                      for name in ("internal_momentum", "rotor_spin", "motor_work", "damper_omega", "dissipated")}
        return Trajectory(t=t, omega=self.omega[index], attitude=self.quat[index], moments=self.moments,
                          principal_axes=self.principal_axes, method=self.method, torque_free=self.torque_free,
                          body_name=self.body_name, rotor_axial_moments=self.rotor_axial_moments,
                          damper_inertia=self.damper_inertia, auto=self.auto, **per_sample)

    def __iter__(self) -> Any:
        raise TypeError("a Trajectory is not iterable: its arrays are (traj.t, traj.omega, traj.quat, ...); "
                        "traj[::k] takes every k-th sample")

    def __repr__(self) -> str:
        return _display.trajectory_repr(self)

    def _repr_html_(self) -> str:
        """A summary table and a small omega(t) plot (inline SVG): Jupyter's rich display."""
        return _display.trajectory_html(self)

    @functools.cached_property
    def quat(self) -> np.ndarray:
        """Attitude quaternions ``[x, y, z, w]`` (scalar last), body to world; shape (n, 4).

        Examples
        --------
        >>> import numpy as np, tumble
        >>> traj = tumble.simulate(tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [0.0, 0.0, np.pi], t_end=1.0, samples=2)
        >>> traj.quat.round(6).tolist()   # half a turn about z in one second
        [[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 0.0]]
        """
        return _LazyRotation.quaternions(self, "attitude")

    @functools.cached_property
    def angular_momentum(self) -> np.ndarray:
        """Total ``L = I omega + h + J omega_d`` (body, rotors, damper) in the principal frame,
        kg m^2/s; shape (n, 3). ``I omega`` for a rigid body.

        Examples
        --------
        >>> import tumble
        >>> traj = tumble.simulate(tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [1.0, 1.0, 1.0], t_end=1.0, samples=2)
        >>> traj.angular_momentum[0].round(6).tolist()   # I omega at t = 0
        [1.0, 2.0, 3.0]
        """
        L = angular_momentum(self.omega, self.moments)
        if self.internal_momentum is not None:
            L = L + self.internal_momentum
        if self.damper_omega is not None:
            L = L + self.damper_inertia * self.damper_omega
        return _array(L)

    @functools.cached_property
    def angular_momentum_world(self) -> np.ndarray:
        """Total L in the world frame, kg m^2/s; constant without external torque (rotors and
        dampers exchange momentum with the body only); shape (n, 3).

        Examples
        --------
        >>> import numpy as np, tumble
        >>> traj = tumble.simulate(tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [1.0, 1.0, 1.0], t_end=10.0, samples=50)
        >>> bool(np.allclose(traj.angular_momentum_world, [1.0, 2.0, 3.0]))   # fixed in space, torque-free
        True
        """
        return _array(self.attitude.apply(self.angular_momentum))

    @functools.cached_property
    def momentum_is_zero(self) -> np.ndarray:
        """Per sample: whether the total L is 0 to round-off, at most ``ZERO_MOMENTUM_RTOL`` of
        the momenta it is the sum of (a wheel spun up from rest: ``I w + h`` cancels to ~1e-17);
        shape (n,).

        Examples
        --------
        >>> import tumble
        >>> traj = tumble.simulate(tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [1.0, 0.0, 0.0], t_end=1.0, samples=2)
        >>> traj.momentum_is_zero.tolist()
        [False, False]
        """
        scale = float(np.max(np.linalg.norm(self.moments * self.omega, axis=1)))
        if self.internal_momentum is not None:
            scale += float(np.max(np.linalg.norm(self.internal_momentum, axis=1)))
        if self.damper_omega is not None:
            scale += cast(float, self.damper_inertia) * float(np.max(np.linalg.norm(self.damper_omega, axis=1)))
        return self.angular_momentum_norm <= ZERO_MOMENTUM_RTOL * scale

    @functools.cached_property
    def nutation_angle(self) -> np.ndarray:
        """Angle between the total L and the nearest major axis, rad, in [0, pi/2]; shape (n,).

        0 for a flat spin about a major axis (either way round), what a damper drives towards.
        The major axes are the eigenspace of the largest moment: for ``I2 < I3`` the line of axis
        3, ``arctan(hypot(L1, L2) / |L3|)``; for a prolate symmetric body (``I2 = I3``, equal
        within :data:`tumble.mass.INERTIA_RTOL` of the trace, the principal frame's rule; Explorer
        1) every axis normal to axis 1 is a major axis and the angle is that between L and their
        plane, ``arctan(|L1| / hypot(L2, L3))``; for a sphere 0. NaN where L is 0 to round-off
        (:attr:`momentum_is_zero`).

        Examples
        --------
        >>> import numpy as np, tumble
        >>> traj = tumble.simulate(tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [1.0, 0.0, 1.0], t_end=1.0, samples=2)
        >>> round(float(traj.nutation_angle[0]), 6) == round(float(np.arctan2(1.0, 3.0)), 6)   # atan(|L1| / |L3|)
        True
        """
        I, L = self.moments, self.angular_momentum
        tol = INERTIA_RTOL * float(np.sum(I))
        if I[2] - I[0] <= tol:  # spherical: every axis is a major axis
            angle = np.zeros(len(L))
        elif I[2] - I[1] <= tol:  # prolate symmetric: the major axes fill the plane normal to axis 1
            angle = np.arctan2(np.abs(L[:, 0]), np.hypot(L[:, 1], L[:, 2]))
        else:
            angle = np.arctan2(np.hypot(L[:, 0], L[:, 1]), np.abs(L[:, 2]))
        return _array(np.where(self.momentum_is_zero, np.nan, angle))

    @functools.cached_property
    def omega_world(self) -> np.ndarray:
        """Angular velocity in the world frame, rad/s; shape (n, 3).

        Examples
        --------
        >>> import tumble
        >>> traj = tumble.simulate(tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [0.0, 0.0, 2.0], t_end=1.0, samples=2)
        >>> traj.omega_world.round(6).tolist()   # a steady spin about z stays along world z
        [[0.0, 0.0, 2.0], [0.0, 0.0, 2.0]]
        """
        return _array(self.attitude.apply(self.omega))

    @functools.cached_property
    def energy(self) -> np.ndarray:
        """Total rotational kinetic energy, J; shape (n,).

        ``omega.I omega / 2`` for a rigid body; with rotors ``+ omega.h + sum_k J_k s_k^2 / 2``
        (each rotor turns at ``omega + s_k n_k``); with a damper ``+ J |omega_d|^2 / 2``
        (:mod:`tumble.dynamics.models.internal`). Changes by the motors' work and the damper's
        dissipation (and the work of an external torque): see :attr:`drift`.

        Examples
        --------
        >>> import numpy as np, tumble
        >>> traj = tumble.simulate(tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [1.0, 1.0, 1.0], t_end=5.0, samples=11)
        >>> bool(np.allclose(traj.energy, 3.0))   # (1 + 2 + 3) / 2 J throughout
        True
        """
        E = kinetic_energy(self.omega, self.moments)
        if self.internal_momentum is not None:
            s = cast(FloatArray, self.rotor_spin)  # set with internal_momentum
            E = E + np.sum(self.omega * self.internal_momentum, axis=1)
            E = E + 0.5 * np.sum(cast(FloatArray, self.rotor_axial_moments) * s * s, axis=1)
        if self.damper_omega is not None:
            E = E + 0.5 * cast(float, self.damper_inertia) * np.sum(self.damper_omega**2, axis=1)
        return _array(E)

    @functools.cached_property
    def hamiltonian(self) -> np.ndarray:
        """The gyrostat Hamiltonian ``sum_i (L_i - h_i)^2 / (2 I_i) = omega.I omega / 2``, J;
        shape (n,). ``L = I omega + h`` is the momentum of body and rotors; conserved for constant
        rotor spins without damper or external torque (:mod:`tumble.dynamics.models.internal`). Equal to :attr:`energy` for a
        rigid body.

        Examples
        --------
        >>> import numpy as np, tumble
        >>> traj = tumble.simulate(tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [1.0, 1.0, 1.0], t_end=1.0, samples=3)
        >>> bool(np.array_equal(traj.hamiltonian, traj.energy))   # a rigid body: the same
        True
        """
        return _array(kinetic_energy(self.omega, self.moments))

    @functools.cached_property
    def angular_momentum_norm(self) -> np.ndarray:
        """|L|, kg m^2/s; shape (n,).

        Examples
        --------
        >>> import numpy as np, tumble
        >>> traj = tumble.simulate(tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [1.0, 1.0, 1.0], t_end=1.0, samples=3)
        >>> bool(np.allclose(traj.angular_momentum_norm, np.sqrt(14.0)))   # |(1, 2, 3)|
        True
        """
        return _array(np.linalg.norm(self.angular_momentum, axis=1))

    @functools.cached_property
    def drift(self) -> dict[str, float | None]:
        """Largest relative departure from the initial value over the run.

        ``energy``: max |E - E0| / E0 of the energy balance ``E = energy - motor_work +
        dissipated`` (the kinetic energy for a rigid body); ``L_norm``: max ||L| - |L0|| / |L0|;
        ``L_world``: max |L_world - L_world(0)| / |L0|, all totals. Meaningful as errors only
        when ``torque_free``. None where the initial value is zero (a body starting at rest): no
        relative drift; ``energy`` is None too when the motors' work is unknown.

        Examples
        --------
        >>> import tumble
        >>> for method in ("rk45", "dop853"):   # the adaptive methods at their default tolerances
        ...     traj = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=5.0, samples=50, method=method)
        ...     print(method, {k: f"{v:.0e}" for k, v in traj.drift.items()})
        rk45 {'energy': '6e-03', 'L_norm': '3e-03', 'L_world': '2e-02'}
        dop853 {'energy': '4e-12', 'L_norm': '2e-12', 'L_world': '6e-12'}
        """
        E, Ln, Lw = self.energy, self.angular_momentum_norm, self.angular_momentum_world
        if self.internal_momentum is not None:
            E = E - self.motor_work if self.motor_work is not None else np.full_like(E, np.nan)
        if self.dissipated is not None:
            E = E + self.dissipated

        return {k: float(v) if np.isfinite(v) else None for k, v in relative_drift(E, Ln, Lw).items()}

    def design_attitude(self) -> Rotation:
        """Rotation of the *design* frame to world: ``attitude * principal_axes^T``.

        Examples
        --------
        >>> import tumble
        >>> traj = tumble.simulate(tumble.t_handle(), [0.0, 0.0, 1.0], t_end=1.0, samples=2)
        >>> traj.design_attitude()[0].as_matrix().round(6).tolist()   # the body starts as it was designed
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
        """
        return self.attitude * Rotation.from_matrix(self.principal_axes).inv()


_ATTITUDE = _LazyRotation()
_ATTITUDE.__set_name__(Trajectory, "attitude")
setattr(Trajectory, "attitude", _ATTITUDE)  # noqa: B010 - the field, stored lazily (_LazyRotation)
#: The fields' defaults, for :meth:`Trajectory.of_samples`.
_FIELD_DEFAULTS = {f.name: f.default for f in dataclass_fields(Trajectory) if f.default is not MISSING}
