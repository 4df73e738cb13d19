"""Attitude controllers that the controlled run calls at their period: their interface, MRP feedback
and momentum dumping (B-dot: :mod:`~tumble.dynamics.control.bdot`).

A controller is any object with a ``period`` (s) and a call ``controller(t, measurement) ->
Command`` (:class:`Controller`); the run samples the sensors every ``period``, calls it, and
holds the command until the next step (zero-order hold). An optional ``reset()`` is called
at the start of every run (for controllers with memory).

**B-dot**: :mod:`~tumble.dynamics.control.bdot`.

**MRP feedback** (Schaub & Junkins, *Analytical Mechanics of Space Systems*, 4th ed., sec.
8.3-8.4): to hold an attitude fixed in the world (``omega_r = 0``) the body torque is
``L_r = -K sigma - P omega + omega x (I_RW omega + G h_s)``, ``sigma`` the MRPs of the body
relative to the target and ``h_s`` the wheels' absolute axial momenta, so that
``I_RW omega + G h_s = I omega + h`` is the total momentum; the wheels make it with ``G u = -L_r`` (least squares). Linearised about
the target, one principal axis obeys ``I_RW theta'' + P theta' + (K / 4) theta = 0``
(``sigma ~ theta / 4``): natural frequency ``omega_n = sqrt(K / (4 I_RW))`` and damping ratio
``zeta = P / sqrt(K I_RW)`` (:func:`pd_response`), ``I_RW`` the moment with the wheels' axial
moments taken out (:mod:`~tumble.dynamics.models.actuators`). A moving reference (nadir:
sec. 8.3's tracking law) and the integral term (sec. 8.4; ``Ki``, ``integral_limit``):
:mod:`~tumble.dynamics.control.pointing`.

**Momentum dumping** (the cross-product law: Camillo & Markley, "Orbit-averaged behavior of
magnetic control laws for momentum unloading", J. Guid. Control 3(6), 1980; Sidi, *Spacecraft
Dynamics and Control*, 1997, sec. 7.5): while MRP feedback holds the attitude with the wheels,
the magnetorquers are asked for the torque ``tau_d = -k_d (h - h_target)`` on the wheels'
momentum ``h``; a dipole can only make torque across the field, and
``m = B x tau_d / |B|^2`` gives ``m x B = tau_d - (tau_d . b) b``, its part across ``b = B / |B|``.
The attitude loop keeps the body still, so the wheels take up that external torque:
``dh/dt ~ -k_d (h - h_target)_perp``, and as the field turns along the orbit every component of
``h`` decays (:class:`MomentumDumping`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple, Protocol, runtime_checkable

import numpy as np
from scipy.spatial.transform import Rotation

from ..._html import field_repr
from ...typing import ArrayLike, FloatArray
from ...validation import (
    check_bool,
    check_moments,
    check_positive,
    check_rotation,
    check_vector,
)
from ..models.actuators import Command, ReactionWheels
from ..models.sensors import Measurement
from .bdot import _three
from .laws import dumping_dipole_components, feedback_torque_components, tracking_feedforward_components
from .pointing import Reference, is_reference, tracking_error
from .sampled import check_held_loop
from ..special.mrp import mrp_from_quat

__all__ = ["Controller", "MRPFeedback", "MomentumDumping", "PDResponse", "pd_response"]


@runtime_checkable
class Controller(Protocol):
    """The controller interface: a period (s) and ``controller(t, measurement) -> Command``.

    Examples
    --------
    >>> from tumble.dynamics.control.controllers import Controller
    >>> from tumble.dynamics.models.actuators import Command
    >>> class Off:
    ...     period = 1.0
    ...     def __call__(self, t, measurement):
    ...         return Command()
    >>> isinstance(Off(), Controller)
    True
    """

    period: float

    def __call__(self, t: float, measurement: Measurement) -> Command:
        """The command to hold from ``t`` (s) until the next step.

        Examples
        --------
        A controller that always asks for the same dipole; :class:`BDot` and
        :class:`MRPFeedback` are controllers too:

        >>> import numpy as np
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.controllers import Controller
        >>> from tumble.dynamics.models.actuators import Command
        >>> from tumble.dynamics.models.sensors import Measurement
        >>> class Hold:
        ...     period = 2.0
        ...     def __call__(self, t, measurement):
        ...         return Command(dipole=[0.0, 0.0, 0.05])
        >>> m = Measurement(0.0, np.zeros(3), np.array([2e-5, 0.0, 0.0]), None)
        >>> Hold()(0.0, m).dipole.tolist(), Hold()(0.0, m).wheel_torque is None
        ([0.0, 0.0, 0.05], True)
        >>> isinstance(BDot(gain=1e4, period=1.0), Controller)
        True
        """
        ...


@dataclass
class MRPFeedback:
    """MRP proportional-derivative pointing to an attitude fixed in the world, with reaction wheels.

    Parameters
    ----------
    K : float
        Attitude gain, N m (> 0).
    P : float
        Rate gain, N m s (> 0).
    period : float
        Control period, s (> 0).
    moments : array_like, shape (3,)
        The body's principal moments ``I`` (kg m^2), wheels locked.
    wheels : ReactionWheels
        The wheels that make the torque.
    target : scipy Rotation, quaternion [x, y, z, w] or Reference
        The target frame to world, fixed, or a moving reference (``attitude(t)``, ``rate(t)``:
        :class:`~tumble.dynamics.control.pointing.NadirTarget`); the principal frame is driven onto it.
    gyroscopic : bool
        Whether to add the feed-forward ``omega x (I omega + h)``.
    Ki : float
        Integral gain, 1/s (>= 0; 0, the default, is the PD law).
    integral_limit : float
        Largest magnitude of each component of the integral term, N m (> 0; default no limit).

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.control.controllers import MRPFeedback
    >>> from tumble.dynamics.models.actuators import ReactionWheels
    >>> from tumble.dynamics.models.sensors import Measurement
    >>> rw = ReactionWheels(np.eye(3), inertia=1e-5)
    >>> c = MRPFeedback(K=1e-3, P=2e-2, period=0.5, moments=[0.007, 0.04, 0.04], wheels=rw)
    >>> m = Measurement(0.0, np.zeros(3), None, Rotation.from_rotvec([0.0, 0.0, 0.1]), np.zeros(3))
    >>> (c(0.0, m).wheel_torque * 1e6).round(3).tolist()   # -L_r = K sigma, sigma_3 = tan(0.1 / 4)
    [0.0, 0.0, 25.005]
    """

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    K: float
    P: float
    period: float
    moments: FloatArray
    wheels: ReactionWheels
    target: Rotation | ArrayLike | Reference = field(default_factory=lambda: Rotation.identity())
    gyroscopic: bool = True
    Ki: float = 0.0
    integral_limit: float = math.inf
    _integral: FloatArray = field(default_factory=lambda: np.zeros(3), init=False, repr=False)

    def __post_init__(self) -> None:
        check_positive("K", self.K, "N m")
        check_positive("P", self.P, "N m s")
        check_positive("period", self.period, "s")
        self.moments = check_moments("moments", self.moments)
        if not isinstance(self.wheels, ReactionWheels):
            raise ValueError(f"wheels = {self.wheels!r} must be ReactionWheels")  # noqa: TRY004 - one error type for bad input
        if not is_reference(self.target):
            self.target = Rotation.from_quat(check_rotation("target", self.target))
        self.Ki = check_positive("Ki", self.Ki, "1/s", allow_zero=True)
        self.gyroscopic = check_bool("gyroscopic", self.gyroscopic)
        if self.integral_limit != math.inf:
            self.integral_limit = check_positive("integral_limit", self.integral_limit, "N m")
        G = self.wheels.axes.T
        if np.linalg.matrix_rank(G) < 3:
            raise ValueError(f"wheels: the {self.wheels.count} wheel axes span fewer than 3 directions; "
                             "MRP feedback needs torque about every axis")
        self._pinv = np.linalg.pinv(G)
        self._I_rw = np.diag(np.asarray(self.moments, float)) - self.wheels.locked_axial()
        check_held_loop(self.moments, self.K, self.P, self.period, self.Ki)  # warns where the held loop diverges

    def reset(self) -> None:
        """Clear the integral term (a new run; :func:`~tumble.dynamics.control.controlled.simulate_controlled` calls it).

        Examples
        --------
        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.control.controllers import MRPFeedback
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> from tumble.dynamics.models.sensors import Measurement
        >>> rw = ReactionWheels(np.eye(3), inertia=1e-5)
        >>> c = MRPFeedback(K=1e-3, P=2e-2, period=0.5, moments=[0.03, 0.04, 0.05], wheels=rw, Ki=0.1)
        >>> m = Measurement(0.0, np.zeros(3), None, Rotation.from_rotvec([0.0, 0.0, 0.4]), np.zeros(3))
        >>> first = c(0.0, m).wheel_torque
        >>> bool(c(0.5, m).wheel_torque[2] > first[2])   # the integral has grown
        True
        >>> c.reset()
        >>> np.array_equal(c(1.0, m).wheel_torque, first)
        True
        """
        self._integral = np.zeros(3)

    def error(self, attitude: Rotation, t: float = 0.0) -> FloatArray:
        """The MRPs ``sigma`` of the body relative to the target at ``t`` (s) (short set, ``|sigma| <= 1``).

        Examples
        --------
        A turn of ``theta`` about x from the target gives ``sigma = tan(theta / 4) x``; a turn
        of 300 deg is the short way round, -60 deg (the shadow set, ``|sigma| <= 1``):

        >>> import math
        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.control.controllers import MRPFeedback
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> rw = ReactionWheels(np.eye(3), inertia=1e-5)
        >>> target = Rotation.from_rotvec([0.0, 0.0, 0.3])
        >>> c = MRPFeedback(K=1e-3, P=2e-2, period=0.5, moments=[0.03, 0.04, 0.05], wheels=rw, target=target)
        >>> np.allclose(c.error(target), 0.0)
        True
        >>> np.allclose(c.error(target * Rotation.from_euler("x", 60, degrees=True)), [math.tan(math.radians(15)), 0, 0])
        True
        >>> np.allclose(c.error(target * Rotation.from_euler("x", 300, degrees=True)), [-math.tan(math.radians(15)), 0, 0])
        True
        """
        if is_reference(self.target):
            return tracking_error(self.target, t, attitude, np.zeros(3)).sigma
        target = self.target if isinstance(self.target, Rotation) else Rotation.from_quat(self.target)
        return np.asarray(mrp_from_quat((target.inv() * attitude).as_quat()), float)

    def __call__(self, t: float, measurement: Measurement) -> Command:
        """The wheel torques ``u = -G^+ L_r`` (N m) for this reading.

        Examples
        --------
        On target and spinning, without the feed-forward: the wheels take ``u = P omega``, so
        the body feels ``-P omega`` (rate damping); with three wheels on the axes ``G = 1``:

        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.control.controllers import MRPFeedback
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> from tumble.dynamics.models.sensors import Measurement
        >>> rw = ReactionWheels(np.eye(3), inertia=1e-5)
        >>> c = MRPFeedback(K=1e-3, P=2e-2, period=0.5, moments=[0.03, 0.04, 0.05], wheels=rw, gyroscopic=False)
        >>> m = Measurement(0.0, np.array([0.01, -0.02, 0.0]), None, Rotation.identity(), np.zeros(3))
        >>> np.allclose(c(0.0, m).wheel_torque, 2e-2 * m.omega)
        True

        Without an attitude reading it cannot point:

        >>> c(0.0, Measurement(0.0, np.zeros(3), None, None, np.zeros(3)))
        Traceback (most recent call last):
        ...
        ValueError: MRP feedback needs an attitude reading and got none (sensors.attitude = 'none' gives none; an estimator none before its filter starts)
        """
        if measurement.attitude is None:
            raise ValueError("MRP feedback needs an attitude reading and got none (sensors.attitude = 'none' gives none; an estimator none before its filter starts)")
        w = measurement.omega
        z = self._integral if self.Ki > 0.0 else np.zeros(3)  # z of the earlier steps
        # I_RW w + G h_s = I w + h: the total momentum, body frame, for the feed-forward
        L = self.moments * w + self.wheels.momentum(measurement.wheel_speed) if self.gyroscopic else np.zeros(3)
        if is_reference(self.target):  # the tracking law (module docstring)
            e = tracking_error(self.target, t, measurement.attitude, w)
            sigma = e.sigma
            L_r = np.array(feedback_torque_components(*_three(sigma), *_three(e.delta_omega), *_three(w), self.K, self.P,
                                                      *_three(z), *_three(L))) \
                + np.array(tracking_feedforward_components(self._I_rw, *_three(e.omega_r), *_three(e.omega_r_dot), *_three(w)))
        else:
            sigma = self.error(measurement.attitude)
            L_r = np.array(feedback_torque_components(*_three(sigma), *_three(w), *_three(w), self.K, self.P, *_three(z),
                                                      *_three(L)))
        if self.Ki > 0.0:  # then advanced by this one's sigma
            lim = self.integral_limit
            self._integral = np.clip(self._integral + self.Ki * self.K * self.period * sigma, -lim, lim)
        return Command(wheel_torque=-self._pinv @ L_r)


@dataclass
class MomentumDumping:
    """MRP feedback pointing with the wheels while the magnetorquers unload them (module docstring).

    Parameters
    ----------
    pointing : MRPFeedback
        The attitude loop; its period is this controller's.
    gain : float
        ``k_d`` of ``tau_d = -k_d (h - h_target)``, 1/s (> 0).
    h_target : array_like, shape (3,)
        The wheels' momentum to keep, body frame, kg m^2/s (default 0).

    Examples
    --------
    The dipole is across the field and its torque opposes the wheels' momentum across it:

    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.control.controllers import MRPFeedback, MomentumDumping
    >>> from tumble.dynamics.models.actuators import ReactionWheels
    >>> from tumble.dynamics.models.sensors import Measurement
    >>> rw = ReactionWheels(np.eye(3), inertia=0.01)
    >>> c = MomentumDumping(MRPFeedback(K=0.5, P=1.7, period=1.0, moments=[10.0, 12.0, 15.0], wheels=rw), gain=1e-3)
    >>> m = Measurement(0.0, np.zeros(3), np.array([0.0, 0.0, 3e-5]), Rotation.identity(), np.array([50.0, 0.0, 20.0]))
    >>> cmd = c(0.0, m)
    >>> float(cmd.dipole @ m.field)   # across the field
    0.0
    >>> np.round(np.cross(cmd.dipole, m.field), 12).tolist()   # tau = -k_d h_perp: h = (0.5, 0, 0.2)
    [-0.0005, 0.0, 0.0]
    """

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    pointing: MRPFeedback
    gain: float
    h_target: FloatArray = field(default_factory=lambda: np.zeros(3))

    def __post_init__(self) -> None:
        if not isinstance(self.pointing, MRPFeedback):
            raise ValueError(f"pointing = {self.pointing!r} must be an MRPFeedback")  # noqa: TRY004 - one error type
        check_positive("gain", self.gain, "1/s")
        self.h_target = np.array(check_vector("h_target", self.h_target, "kg m^2/s"))

    def reset(self) -> None:
        """Reset the attitude loop (its integral term).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.control.controllers import MRPFeedback, MomentumDumping
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> rw = ReactionWheels(np.eye(3), inertia=0.01)
        >>> c = MomentumDumping(MRPFeedback(K=0.5, P=1.7, period=1.0, moments=[10.0, 12.0, 15.0], wheels=rw), 1e-3)
        >>> c.reset()
        """
        self.pointing.reset()

    @property
    def period(self) -> float:
        """The control period, s: the attitude loop's.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.control.controllers import MRPFeedback, MomentumDumping
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> rw = ReactionWheels(np.eye(3), inertia=0.01)
        >>> MomentumDumping(MRPFeedback(K=0.5, P=1.7, period=2.0, moments=[10.0, 12.0, 15.0], wheels=rw), 1e-3).period
        2.0
        """
        return float(self.pointing.period)

    def __call__(self, t: float, measurement: Measurement) -> Command:
        """The wheel torques of the attitude loop and the dipole ``m = B x tau_d / |B|^2`` (A m^2).

        Examples
        --------
        Without a magnetometer reading there is no field to push against:

        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.control.controllers import MRPFeedback, MomentumDumping
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> from tumble.dynamics.models.sensors import Measurement
        >>> rw = ReactionWheels(np.eye(3), inertia=0.01)
        >>> c = MomentumDumping(MRPFeedback(K=0.5, P=1.7, period=1.0, moments=[10.0, 12.0, 15.0], wheels=rw), 1e-3)
        >>> c(0.0, Measurement(0.0, np.zeros(3), None, Rotation.identity(), np.zeros(3)))
        Traceback (most recent call last):
        ...
        ValueError: momentum dumping needs a magnetometer reading (an [orbit] with its field)
        """
        wheels = self.pointing(t, measurement)
        B = measurement.field
        if B is None:
            raise ValueError("momentum dumping needs a magnetometer reading (an [orbit] with its field)")
        h = self.pointing.wheels.momentum(measurement.wheel_speed)
        dipole = dumping_dipole_components(*_three(B), *_three(h), self.gain, *_three(self.h_target))
        return Command(dipole=np.array(dipole), wheel_torque=wheels.wheel_torque)


class PDResponse(NamedTuple):
    """The linearised one-axis closed loop of MRP feedback (:func:`pd_response`): the natural
    frequency ``omega_n = sqrt(K / (4 I))`` (rad/s), the damping ratio ``zeta = P / sqrt(K I)``,
    the overshoot (a fraction of ``theta_0``; 0 when ``zeta >= 1``) and the 2 % settling time
    (s; NaN when ``zeta >= 1``).

    Examples
    --------
    ``zeta = 0.5``: overshoot ``exp(-pi / sqrt(3)) = 16.3 %``, settling
    ``-ln(0.02 sqrt(0.75)) / (0.5 omega_n)``:

    >>> import math
    >>> from tumble.dynamics.control.controllers import PDResponse, pd_response
    >>> r = pd_response(K=4e-4, P=1e-3, moment=0.01)
    >>> isinstance(r, PDResponse), r.damping_ratio, round(r.overshoot, 4)
    (True, 0.5, 0.163)
    >>> wn, zeta, overshoot, settling = r
    >>> math.isclose(settling, -math.log(0.02 * math.sqrt(0.75)) / (0.5 * 0.1))
    True
    """

    natural_frequency: float
    damping_ratio: float
    overshoot: float
    settling_time: float


def pd_response(K: float, P: float, moment: float) -> PDResponse:
    """Natural frequency (rad/s), damping ratio, overshoot and 2 % settling time (s) of
    ``I theta'' + P theta' + (K / 4) theta = 0`` released from rest at ``theta_0``.

    ``omega_n = sqrt(K / (4 I))``, ``zeta = P / sqrt(K I)``; for ``zeta < 1`` the response
    ``theta_0 e^(-zeta omega_n t) (cos omega_d t + zeta / sqrt(1 - zeta^2) sin omega_d t)`` swings
    past zero by ``exp(-pi zeta / sqrt(1 - zeta^2))`` of ``theta_0`` at ``t = pi / omega_d``
    (``omega_d = omega_n sqrt(1 - zeta^2)``), and its envelope falls to 2 % by
    ``-ln(0.02 sqrt(1 - zeta^2)) / (zeta omega_n)`` (~ 4 / (zeta omega_n); Wie, *Space Vehicle
    Dynamics and Control*, 2nd ed., sec. 2.4). Overdamped or critical: overshoot 0, settling NaN.

    Examples
    --------
    >>> from tumble.dynamics.control.controllers import pd_response
    >>> r = pd_response(K=4e-4, P=2e-3, moment=0.01)
    >>> round(r.natural_frequency, 6), round(r.damping_ratio, 6), round(r.overshoot, 6)
    (0.1, 1.0, 0.0)
    """
    I = check_positive("moment", moment, "kg m^2")
    wn = math.sqrt(check_positive("K", K, "N m") / (4.0 * I))
    zeta = check_positive("P", P, "N m s") / math.sqrt(K * I)
    if zeta >= 1.0:
        return PDResponse(wn, zeta, 0.0, math.nan)
    root = math.sqrt(1.0 - zeta * zeta)
    return PDResponse(wn, zeta, math.exp(-math.pi * zeta / root), -math.log(0.02 * root) / (zeta * wn))
