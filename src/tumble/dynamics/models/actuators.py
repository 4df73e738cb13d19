"""Actuators with limits: magnetorquers and reaction wheels, and the command a controller sends.

Every vector is in the body's principal frame (``I1 <= I2 <= I3``); SI units.

**Magnetorquers.** Rods along the unit axes ``a_j`` make the dipole ``m = sum_j m_j a_j``
(A m^2), each ``|m_j| <= m_max,j``; in the field ``B`` (body frame, T) the body feels
``tau = m x B`` (Wertz, *Spacecraft Attitude Determination and Control*, sec. 17.2). A commanded
dipole is projected on the rods (``m_j = a_j . m_cmd`` for orthonormal rods) and each clipped.

**Reaction wheels.** Axisymmetric wheels ``k`` of axial moment ``J_k`` spin at ``s_k`` (rad/s)
relative to the body about fixed axes ``g_k``; the body's inertia ``I`` holds the wheels'
mass locked (as :mod:`~tumble.dynamics.models.internal`), the wheels' relative momentum is
``h = sum_k J_k s_k g_k`` and the total ``L = I w + h``. The motor torque ``u_k`` on wheel k
changes its absolute axial momentum, ``d/dt [J_k (g_k . w + s_k)] = u_k``, so
``(I - sum_k J_k g_k g_k^T) w' = tau_ext - w x (I w + h) - sum_k u_k g_k``
(Schaub & Junkins, *Analytical Mechanics of Space Systems*, 4th ed., sec. 4.5, the reaction
wheel equations of motion, with ``[I_RW] = I - sum J_k g_k g_k^T``). The applied ``u_k`` is the
command clipped to ``|u_k| <= u_max``; where it drives ``|s_k|`` outwards it falls linearly to
zero over the last 1 % below ``s_max`` (:data:`SPEED_LIMIT_BAND`, as a motor's torque falls at its
no-load speed; a step there made the adaptive integrator crawl), less the bearing friction ``c_v s_k + c_c sat(s_k / s_lc)`` (viscous N m s/rad, Coulomb N m; an
internal torque, so ``L`` is untouched by it). The Coulomb part is ``c_c sign(s_k)`` above a small
speed ``s_lc`` (``limit_cycle_speed``, default 1e-4 rad/s) and linear below it, as Basilisk's
``reactionWheelStateEffector`` does with its ``omegaLimitCycle`` (Schaub & Junkins, the Basilisk
reaction-wheel model): a pure ``sign`` flips at every crossing of zero, so a wheel held near rest
chatters and an adaptive integrator crawls (600 s of pointing took over ten minutes); the linear
region is the usual regularisation of Coulomb friction (Karnopp, "Computer simulation of
stick-slip friction in mechanical dynamic systems", J. Dyn. Syst. Meas. Control 107, 1985).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..._html import field_repr
from ...typing import ArrayLike, FloatArray, Matrix3, Vector3
from ...validation import check_positive, check_vectors

__all__ = ["MAX_WHEEL_SPEED", "SPEED_LIMIT_BAND", "Command", "Magnetorquers", "ReactionWheels", "check_wheels", "rod_dipole_components",
           "wheel_torque"]


@dataclass(frozen=True)
class Command:
    """What a controller asks of the actuators until its next step (held: zero-order hold).

    Parameters
    ----------
    dipole : array_like, shape (3,), optional
        Magnetorquer dipole, principal frame, A m^2 (None: magnetorquers off).
    wheel_torque : array_like, shape (k,), optional
        Motor torque on each wheel, N m (None: motors off).

    Examples
    --------
    >>> from tumble.dynamics.models.actuators import Command
    >>> Command(dipole=[0.0, 0.1, 0.0]).dipole.tolist()
    [0.0, 0.1, 0.0]
    """

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    dipole: FloatArray | None = None
    wheel_torque: FloatArray | None = None

    def __post_init__(self) -> None:
        if self.dipole is not None:
            object.__setattr__(self, "dipole", check_vectors("dipole", self.dipole, "A m^2").reshape(3))
        if self.wheel_torque is not None:
            object.__setattr__(self, "wheel_torque",
                               np.atleast_1d(check_vectors("wheel_torque", self.wheel_torque, "N m", size=None)))


def _axes(name: str, axes: ArrayLike) -> FloatArray:
    a = check_vectors(name, axes, "a direction, any length")
    if a.ndim != 2 or len(a) == 0:
        raise ValueError(f"{name} has shape {a.shape}; allowed: (k, 3), one row per axis")
    norms = np.linalg.norm(a, axis=1)
    if np.any(norms == 0.0):
        raise ValueError(f"{name}[{int(np.argmin(norms))}] = [0, 0, 0] must be a non-zero direction")
    return np.asarray(a / norms[:, None], float)


def _per_axis(name: str, value: ArrayLike, k: int, unit: str, *, allow_zero: bool = False) -> FloatArray:
    v = np.broadcast_to(check_vectors(name, value, unit, size=None), (k,)) if np.ndim(value) == 0 else \
        check_vectors(name, value, unit, size=k)
    for i, x in enumerate(v):
        check_positive(f"{name}[{i}]", float(x), unit, allow_zero=allow_zero)
    return np.array(v, dtype=float)


@dataclass(frozen=True)
class Magnetorquers:
    """Magnetic torque rods with a dipole limit per rod.

    Parameters
    ----------
    max_dipole : float or array_like, shape (k,)
        Largest dipole of each rod, A m^2 (> 0).
    axes : array_like, shape (k, 3)
        Rod directions, principal frame (normalised); default the three principal axes.

    Examples
    --------
    >>> from tumble.dynamics.models.actuators import Magnetorquers
    >>> mtq = Magnetorquers(0.2)
    >>> mtq.saturate([0.5, -0.1, 0.0]).tolist()
    [0.2, -0.1, 0.0]
    >>> mtq.torque([0.2, 0.0, 0.0], [0.0, 3e-5, 0.0]).tolist()   # m x B, N m
    [0.0, 0.0, 6e-06]
    """

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    max_dipole: FloatArray | float = 0.2
    axes: FloatArray = field(default_factory=lambda: np.eye(3))

    def __post_init__(self) -> None:
        axes = _axes("axes", self.axes)
        object.__setattr__(self, "axes", axes)
        object.__setattr__(self, "max_dipole", _per_axis("max_dipole", self.max_dipole, len(axes), "A m^2"))

    @functools.cached_property
    def rods(self) -> FloatArray:
        """The rods as the compiled loops take them, shape (k, 6): each rod's axis, then its row of the
        allocation ``G^+`` (:func:`rod_dipole_components`); made once, as :meth:`saturate` runs at every
        control step of the Python path (writeable, as numba's kernels take their arrays: not to be changed).

        Examples
        --------
        >>> from tumble.dynamics.models.actuators import Magnetorquers
        >>> Magnetorquers(1.0, axes=[[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]).rods.round(12).tolist()   # two rods on x share it
        [[1.0, 0.0, 0.0, 0.5, 0.0, 0.0], [1.0, 0.0, 0.0, 0.5, 0.0, 0.0]]
        """
        a = self.axes  # G^T; G^+ (k x 3): the least-norm rod dipoles that make m; for orthonormal rods G^T itself
        allocation = a if np.array_equal(a @ a.T, np.eye(len(a))) else np.linalg.pinv(a.T)
        return np.ascontiguousarray(np.hstack([self.axes, allocation]), dtype=float)

    def saturate(self, dipole: ArrayLike) -> Vector3:
        """The dipole the rods make for a command (A m^2): allocated to the rods by ``G^+``, each clipped to
        its limit (:func:`rod_dipole_components`); shape (..., 3).

        Examples
        --------
        Each rod clips on its own (the direction of the dipole may change); a batch of commands
        at once:

        >>> from tumble.dynamics.models.actuators import Magnetorquers
        >>> mtq = Magnetorquers([0.2, 0.2, 0.1])
        >>> mtq.saturate([[0.5, -0.1, 0.3], [0.05, 0.0, -0.05]]).tolist()
        [[0.2, -0.1, 0.1], [0.05, 0.0, -0.05]]

        Two rods only: no dipole along the missing axis:

        >>> Magnetorquers(1.0, axes=[[1.0, 0.0, 0.0], [0.0, 2.0, 0.0]]).saturate([0.5, 0.5, 0.5]).tolist()
        [0.5, 0.5, 0.0]

        Rods skewed or doubled make the dipole asked for, within their limits:

        >>> Magnetorquers(10.0, axes=[[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).saturate([1.0, 0.0, 0.0]).round(12) + 0.0
        array([1., 0., 0.])
        """
        m = np.asarray(dipole, float)
        d = rod_dipole_components(self.rods, np.asarray(self.max_dipole, float), m[..., 0], m[..., 1], m[..., 2])
        return np.stack(np.broadcast_arrays(*d), axis=-1)

    def torque(self, dipole: ArrayLike, field_body: ArrayLike) -> Vector3:
        """``tau = m x B`` (N m) for the dipole ``m`` (A m^2) in ``B`` (T), both principal frame.

        Examples
        --------
        The torque is square to the field (a magnetorquer cannot torque about B) and largest,
        ``|m| |B|``, for a dipole square to it:

        >>> import numpy as np
        >>> from tumble.dynamics.models.actuators import Magnetorquers
        >>> mtq = Magnetorquers(0.2)
        >>> b = np.array([1e-5, -2e-5, 2e-5])
        >>> tau = mtq.torque([0.0, 0.2, 0.2], b)
        >>> bool(abs(tau @ b) < 1e-25), np.allclose(tau, [8e-6, 2e-6, -2e-6])
        (True, True)
        >>> mtq.torque(0.1 * b / np.linalg.norm(b), b).tolist()   # dipole along B: no torque
        [0.0, 0.0, 0.0]
        """
        return np.asarray(np.cross(np.asarray(dipole, float), np.asarray(field_body, float)), float)

    def loop_form(self) -> tuple[FloatArray, FloatArray] | None:
        """The compiled closed loop's form: the rods' axes (k, 3) and dipole limits (k,), A m^2,
        which the loop clips by :meth:`saturate`'s rule; None for a subclass with rules of its own.

        Examples
        --------
        >>> from tumble.dynamics.models.actuators import Magnetorquers
        >>> axes, limits = Magnetorquers(0.2).loop_form()
        >>> axes.shape, limits.tolist()
        ((3, 3), [0.2, 0.2, 0.2])
        """
        if type(self).saturate is not Magnetorquers.saturate or type(self).torque is not Magnetorquers.torque:
            return None
        return np.ascontiguousarray(self.axes, dtype=float), np.asarray(self.max_dipole, dtype=float).copy()


#: The fastest finite ``max_speed`` taken, rad/s (~24,000 rpm): reaction wheels turn at most
#: ~6,000 rpm (spacecraft) to ~15,000 rpm (CubeSats'), so a limit past it is most likely in rpm.
MAX_WHEEL_SPEED = 2500.0
#: The part of ``max_speed`` over which a wheel's outward motor torque falls to zero: the last
#: 1 %. A DC motor's available torque falls linearly to zero at its no-load speed, by its back-EMF
#: (the steady-state torque-speed line: Hughes & Drury, *Electric Motors and Drives*, 4th ed.,
#: ch. 3), not in a step; a step made the closed loop's adaptive integrator crawl (issue 27: 30 s
#: of a wheel at its limit took 90 s). This ramp is a regularisation in that spirit (as the linear
#: Coulomb region is, Karnopp 1985), not a model of a particular drive: it keeps the right-hand
#: side continuous, its relaxation rate ``u_max / (J band s_max)`` well within an explicit step.
SPEED_LIMIT_BAND = 0.01


def rod_dipole_components(rods: FloatArray, limits: FloatArray, m0: Any, m1: Any, m2: Any) -> tuple[Any, Any, Any]:
    """The dipole (A m^2) magnetorquer rods make for a command ``m``: the one writing, over floats (the
    compiled closed loop and B-dot batch) or arrays of one shape (:meth:`Magnetorquers.saturate`).

    Each rod's share is its row of the allocation ``G^+ m`` (``G`` the 3 x k matrix of the rods' axes:
    the least-norm dipoles that make ``m``, or its projection on the rods' span; for orthonormal rods
    the projection on each), clipped to its limit, then summed along its axis: the Moore-Penrose
    allocation the wheels' torques have here (``u = -G^+ L_r``, :class:`ReactionWheels`). ``rods`` (k, 6): each rod's axis, then its row of ``G^+``
    (:attr:`Magnetorquers.rods`). Skewed or doubled rods projected one by one made another dipole
    than the one asked for (twice it for two rods on one axis; a walkthrough, issue 40).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.actuators import Magnetorquers, rod_dipole_components
    >>> rods = Magnetorquers(1.0, axes=[[1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]).rods
    >>> [round(float(d), 12) for d in rod_dipole_components(rods, np.array([1.0, 1.0, 1.0]), 1.5, 0.0, 3.0)]
    [1.5, 0.0, 1.0]
    """
    d0 = d1 = d2 = 0.0 * m0
    for r in range(rods.shape[0]):
        p = np.minimum(np.maximum(m0 * rods[r, 3] + m1 * rods[r, 4] + m2 * rods[r, 5], -limits[r]), limits[r])
        d0, d1, d2 = d0 + p * rods[r, 0], d1 + p * rods[r, 1], d2 + p * rods[r, 2]
    return d0, d1, d2


def wheel_torque(command: Any, speed: Any, max_torque: Any, max_speed: Any, viscous: Any, coulomb: Any,
                 limit_cycle: Any) -> Any:
    """One wheel's applied torque (N m): the one writing, over floats (the compiled closed loop)
    or arrays of one shape (:meth:`ReactionWheels.applied_torque`).

    The command (N m) clipped to ``max_torque``; pushing ``|speed|`` outwards it falls linearly to
    zero over the last :data:`SPEED_LIMIT_BAND` of ``max_speed`` (rad/s), and is zero beyond;
    less the viscous friction ``viscous speed`` and the Coulomb friction ``coulomb
    sat(speed / limit_cycle)``, linear below ``limit_cycle`` (Basilisk's ``omegaLimitCycle``).
    Arithmetic and ``np.minimum``/``np.maximum`` only, so numba compiles it as it is.

    Examples
    --------
    >>> from tumble.dynamics.models.actuators import wheel_torque
    >>> round(float(wheel_torque(1e-3, 597.0, 2e-3, 600.0, 0.0, 0.0, 1e-4)), 12)   # half-way down the ramp: half
    0.0005
    >>> float(wheel_torque(-1e-3, 600.0, 2e-3, 600.0, 0.0, 0.0, 1e-4))   # inwards: all of it
    -0.001
    """
    u = np.minimum(np.maximum(command, -max_torque), max_torque)
    taper = np.minimum(np.maximum((1.0 - np.abs(speed) / max_speed) / SPEED_LIMIT_BAND, 0.0), 1.0)
    u = u * (1.0 - (1.0 - taper) * (u * speed > 0.0))
    return u - viscous * speed - coulomb * np.minimum(np.maximum(speed / limit_cycle, -1.0), 1.0)


@dataclass(frozen=True)
class ReactionWheels:
    """Reaction wheels driven by a commanded motor torque, with torque and speed limits.

    Parameters
    ----------
    axes : array_like, shape (k, 3)
        Spin axes ``g_k``, principal frame (normalised).
    inertia : float or array_like, shape (k,)
        Axial moments ``J_k``, kg m^2 (> 0).
    max_torque : float or array_like, shape (k,)
        Motor torque limit ``u_max``, N m (> 0).
    max_speed : float or array_like, shape (k,)
        Spin limit ``s_max`` relative to the body, rad/s (> 0): the motor's outward torque falls
        to zero over its last 1 % (:data:`SPEED_LIMIT_BAND`).
    viscous : float or array_like, shape (k,)
        Viscous friction ``c_v``, N m s/rad (>= 0).
    coulomb : float or array_like, shape (k,)
        Coulomb friction ``c_c``, N m (>= 0).
    limit_cycle_speed : float or array_like, shape (k,)
        ``s_lc``, rad/s (> 0, default 1e-4 as Basilisk's ``omegaLimitCycle``): below it the
        Coulomb friction is linear in the speed, ``c_c s / s_lc`` (module docstring).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.actuators import ReactionWheels
    >>> rw = ReactionWheels(np.eye(3), inertia=1e-5, max_torque=1e-3, max_speed=600.0)
    >>> rw.applied_torque([2e-3, -5e-4, 0.0], np.zeros(3)).tolist()
    [0.001, -0.0005, 0.0]
    >>> rw.momentum([100.0, 0.0, 0.0]).tolist()   # h = sum J s g, kg m^2/s
    [0.001, 0.0, 0.0]
    """

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    axes: FloatArray
    inertia: FloatArray | float
    max_torque: FloatArray | float = np.inf
    max_speed: FloatArray | float = np.inf
    viscous: FloatArray | float = 0.0
    coulomb: FloatArray | float = 0.0
    limit_cycle_speed: FloatArray | float = 1e-4

    def __post_init__(self) -> None:
        axes = _axes("axes", self.axes)
        k = len(axes)
        object.__setattr__(self, "axes", axes)
        object.__setattr__(self, "inertia", _per_axis("inertia", self.inertia, k, "kg m^2"))
        for name, unit in (("max_torque", "N m"), ("max_speed", "rad/s")):
            value = getattr(self, name)
            v = np.broadcast_to(np.asarray(value, float), (k,)) if np.ndim(value) == 0 else np.asarray(value, float)
            if v.shape != (k,) or np.any(~(v > 0)):
                raise ValueError(f"{name} = {value!r} must be a positive number or {k} of them ({unit}); inf: no limit")
            object.__setattr__(self, name, np.array(v))
        object.__setattr__(self, "viscous", _per_axis("viscous", self.viscous, k, "N m s/rad", allow_zero=True))
        object.__setattr__(self, "coulomb", _per_axis("coulomb", self.coulomb, k, "N m", allow_zero=True))
        object.__setattr__(self, "limit_cycle_speed", _per_axis("limit_cycle_speed", self.limit_cycle_speed, k, "rad/s"))
        speed = np.asarray(self.max_speed, float)
        fast = np.flatnonzero(np.isfinite(speed) & (speed > MAX_WHEEL_SPEED))
        if len(fast):  # a walkthrough's 6000 (rpm) ran as 6000 rad/s, the wheels far past what saturated them
            top = float(speed[int(fast[0])])
            raise ValueError(f"max_speed[{int(fast[0])}] = {top:g} rad/s ({top * 30 / np.pi:.3g} rpm) is faster than a "
                             f"reaction wheel turns; allowed: up to {MAX_WHEEL_SPEED:g} rad/s, or inf for no limit: is it "
                             f"in rpm? Give rad/s ({top:g} rpm = {top * np.pi / 30:.4g} rad/s)")
        coulomb, motor = np.asarray(self.coulomb, float), np.asarray(self.max_torque, float)
        stuck = np.flatnonzero(coulomb >= motor)
        if len(stuck):  # the motor can never turn it (a walkthrough's 1e-2 N m against 2e-3 crawled, stiff, in silence)
            j = int(stuck[0])
            raise ValueError(f"coulomb[{j}] = {coulomb[j]:g} N m is at least max_torque[{j}] = {motor[j]:g} "
                             f"N m: the motor could never turn the wheel against its friction; give a friction below "
                             f"the motor's torque (typically a few % of it)")

    @property
    def count(self) -> int:
        """Number of wheels ``k``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> ReactionWheels(np.eye(3)[:2], inertia=1e-5).count
        2
        """
        return len(self.axes)

    def momentum(self, speed: ArrayLike) -> Vector3:
        """The wheels' relative momentum ``h = sum_k J_k s_k g_k``, kg m^2/s, principal frame.

        Examples
        --------
        Four wheels in a pyramid: equal spins on the two wheels of one face add along their
        common component and cancel across it:

        >>> import numpy as np
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> c = 1 / np.sqrt(2)
        >>> rw = ReactionWheels([[c, 0, c], [-c, 0, c], [0, c, c], [0, -c, c]], inertia=2e-5)
        >>> h = rw.momentum([100.0, 100.0, 0.0, 0.0])
        >>> np.allclose(h, [0.0, 0.0, 2 * 2e-5 * 100.0 * c])
        True
        """
        return np.asarray((np.asarray(self.inertia) * np.asarray(speed, float)) @ self.axes, float)

    def locked_axial(self) -> Matrix3:
        """``sum_k J_k g_k g_k^T``, kg m^2: subtracted from ``I`` in the equations of motion.

        Examples
        --------
        Three wheels on the principal axes: ``diag(J_1, J_2, J_3)``; its trace is ``sum_k J_k`` whatever the axes:

        >>> import numpy as np
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> ReactionWheels(np.eye(3), inertia=[1e-5, 2e-5, 4e-5]).locked_axial().diagonal().tolist()
        [1e-05, 2e-05, 4e-05]
        >>> rw = ReactionWheels([[1.0, 1.0, 0.0], [0.0, 1.0, 1.0]], inertia=[1e-5, 3e-5])
        >>> bool(np.isclose(np.trace(rw.locked_axial()), 4e-5))
        True
        """
        return np.asarray(np.einsum("k,ki,kj->ij", np.asarray(self.inertia), self.axes, self.axes), float)

    def applied_torque(self, command: ArrayLike, speed: ArrayLike) -> FloatArray:
        """The motor torque on each wheel (N m) for a command at spins ``speed`` (rad/s):
        clipped to ``u_max``, falling to zero at ``s_max`` where it pushes ``|s|`` outwards, less
        the friction (:func:`wheel_torque`).

        Examples
        --------
        A wheel at its speed limit may slow down but not speed up; friction opposes the spin:

        >>> import numpy as np
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> rw = ReactionWheels(np.eye(3)[:2], inertia=1e-5, max_torque=1e-3, max_speed=600.0)
        >>> rw.applied_torque([5e-4, -5e-4], [600.0, 600.0]).tolist()
        [0.0, -0.0005]
        >>> rub = ReactionWheels(np.eye(3)[:1], inertia=1e-5, viscous=1e-7, coulomb=1e-5)
        >>> bool(np.isclose(rub.applied_torque([0.0], [100.0])[0], -(1e-7 * 100.0 + 1e-5)))
        True

        Below ``limit_cycle_speed`` (1e-4 rad/s) the Coulomb part is linear, so it is zero at rest
        and continuous through it:

        >>> [round(float(rub.applied_torque([0.0], [s])[0]), 12) for s in (0.0, 5e-5, -2e-4)]   # N m
        [0.0, -5.000005e-06, 1.000002e-05]
        """
        return np.asarray(wheel_torque(np.asarray(command, float), np.asarray(speed, float), np.asarray(self.max_torque),
                                       np.asarray(self.max_speed), np.asarray(self.viscous), np.asarray(self.coulomb),
                                       np.asarray(self.limit_cycle_speed)), float)

    def loop_form(self) -> FloatArray | None:
        """The compiled closed loop's form, a row of 9 floats per wheel: the axis (3), ``J``
        (kg m^2), ``u_max`` (N m), ``s_max`` (rad/s), ``c_v`` (N m s/rad), ``c_c`` (N m) and
        ``s_lc`` (rad/s), which the loop applies by :func:`wheel_torque`; None for a subclass with
        a law of its own.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> ReactionWheels(np.eye(3)[:1], inertia=2e-5, max_torque=1e-3).loop_form().tolist()
        [[1.0, 0.0, 0.0, 2e-05, 0.001, inf, 0.0, 0.0, 0.0001]]
        """
        if type(self).applied_torque is not ReactionWheels.applied_torque or \
                type(self).momentum is not ReactionWheels.momentum:
            return None
        form = np.empty((self.count, 9))
        form[:, :3] = self.axes
        for column, value in enumerate((self.inertia, self.max_torque, self.max_speed, self.viscous, self.coulomb,
                                        self.limit_cycle_speed), start=3):
            form[:, column] = value
        return form


def check_wheels(moments: ArrayLike, wheels: ReactionWheels, *, inertia: str = "wheels.inertia") -> None:
    """Refuse ``wheels`` that cannot be part of a body of principal ``moments`` (kg m^2); the message
    names the field ``inertia`` as the caller's user wrote it.

    The body's moments hold its wheels (Hughes, *Spacecraft Attitude Dynamics*, ch. 3: the
    gyrostat's ``I``), so the body less its wheels' axial moments, ``I - sum_k J_k g_k g_k^T``, is
    a body too: positive definite. A wheel of 0.5 kg m^2 in a 3U CubeSat of 0.04 kg m^2 (a unit
    slip) made energy from nothing (4.5e-6 J to 6e-4 J, the motors doing -3e-4 J), exit 0. (A wheel
    started past its ``max_speed`` is physical: its motor brings it down, issue 27.)

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.actuators import ReactionWheels, check_wheels
    >>> rw = ReactionWheels(np.eye(3), inertia=1e-5)
    >>> check_wheels([0.0067, 0.0419, 0.0419], rw)   # fine: nothing said
    >>> check_wheels([0.0067, 0.0419, 0.0419], ReactionWheels(np.eye(3), inertia=0.5))
    Traceback (most recent call last):
    ...
    ValueError: wheels.inertia = [0.5, 0.5, 0.5] kg m^2 is more than the body's moments [0.0067, 0.0419, 0.0419] kg m^2 hold: the body less its wheels would have a moment of -0.493 kg m^2; the body's moments include its wheels, each wheel's far below them (a moment in g cm^2?)
    """
    k = wheels.count
    J = np.broadcast_to(np.asarray(wheels.inertia, float), (k,))
    I = np.asarray(moments, float)
    low = float(np.linalg.eigvalsh(np.diag(I) - (wheels.axes.T * J) @ wheels.axes)[0])
    if not low > 0.0:
        raise ValueError(f"{inertia} = {J.tolist()} kg m^2 is more than the body's moments {I.round(6).tolist()} kg m^2 "
                         f"hold: the body less its wheels would have a moment of {low:.3g} kg m^2; the body's moments "
                         "include its wheels, each wheel's far below them (a moment in g cm^2?)")
