"""The closed-loop run: continuous dynamics between control steps, commands held (zero-order hold).

State: the attitude quaternion ``q`` (principal frame to world, scalar last), the angular
velocity ``omega`` (principal frame, rad/s), the wheels' spins ``s`` (rad/s, relative to the
body) and the external angular impulse ``int tau_world dt`` (N m s), integrated with it so that
the momentum budget can be checked. Between steps ``t_k = k period`` the equations

``(I - sum J_k g_k g_k^T) omega' = tau - omega x (I omega + h) - G u``,  ``J_k s_k' = u_k - J_k g_k . omega'``,
``q' = q (x) (omega, 0) / 2``

(:mod:`~tumble.dynamics.models.actuators` for their source) are integrated by DOP853 with the
command held, ``u`` the wheels' applied torque and ``tau`` the body
torques: the magnetorquers' ``m x B``, the gravity gradient and a disturbance (``torque``). At each ``t_k`` the sensors are
read and the controller called.

**Three paths, the same steps.** With the built-in models only (``DipoleField``, ``UniformField``
or ``IGRFField``, ``GravityGradient`` or ``OrbitGravityGradient`` on a circular, Keplerian or TLE
orbit, ``Magnetorquers``, at most six ``ReactionWheels``) each interval is integrated by scipy's
DOP853 written out and compiled (:mod:`~tumble.dynamics.control.compiled_loop`: the same
steps); with a model of one's own by scipy's ``solve_ivp`` with a Python right-hand side. With
built-in controllers (``BDot``, ``MRPFeedback`` to a fixed or moving target, ``MomentumDumping``,
a ``DetumbleThenPoint`` of them) the whole loop runs in one compiled call, the laws the Python
controllers' functions (:mod:`~tumble.dynamics.control.laws`), the same results to round-off:
ideal sensors in :mod:`~tumble.dynamics.control.compiled_loop`, noisy ones or the MEKF in
:mod:`~tumble.dynamics.control.estimated_loop`. Otherwise (a controller of one's own, sensors
that sample in their own way) the controller and the sensors are Python, called once a period.

**Budget.** ``L_world = R (I omega + h)`` of body and wheels changes only by the external
impulse: ``L_world(t) - L_world(0) - int_0^t tau_world dt = 0`` to the integrator's accuracy;
with wheels only and no external torque ``L_world`` is constant.
"""

from __future__ import annotations

import math
from dataclasses import FrozenInstanceError
from typing import Any, cast

import numpy as np
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from ...jit import kernel_array
from ...typing import ArrayLike, FloatArray
from ...validation import check_positive
from . import _display
from ._front import check_actuators, checked, control_instants, locked_inverse
from ..euler import cross
from ._rotations import Matrix, matrix
from .controllers import Controller
from .estimated import Estimated
from .mission import DetumbleThenPoint
from ..environment.magnetic import MagneticField
from ..models.actuators import Command, Magnetorquers, ReactionWheels
from ..models.gravity import GravityGradient
from ..models.orbit_gravity import OrbitGravityGradient
from ..models.sensors import Sensors
from ..models.torques import TorqueLike, as_torque, bind_to_body, body_torque
from .pointing import Reference, target_attitude
from ..special.mrp import mrp_angle, mrp_from_quat
from ..euler import momentum_rate_components
from ..special.quaternion import quaternion_rate_components, rotate_by_quaternion

__all__ = ["ControlledRun", "simulate_controlled"]

#: No rows of three (no wheel or rod axes) and no values (no inertias, no dipole limits): empty, so shared.
_NO_ROWS, _NO_VALUES = np.zeros((0, 3)), np.zeros(0)


class ControlledRun:
    """A closed-loop run sampled at every control step (and at the end); read-only.

    Its ``attitude`` and ``momentum_world`` are built on first reading (~30 us, a tenth of a 60 s loop).

    Attributes
    ----------
    t : ndarray, shape (n,)
        Times, s.
    omega : ndarray, shape (n, 3)
        Angular velocity, principal frame, rad/s.
    attitude : scipy Rotation, n rotations
        Principal frame to world.
    moments : ndarray, shape (3,)
        Principal moments, kg m^2 (wheels locked).
    wheel_speed : ndarray, shape (n, k)
        Wheel spins relative to the body, rad/s (k = 0 without wheels).
    wheel_torque : ndarray, shape (n, k)
        Applied motor torque at each step's start (after limits and friction), N m.
    dipole : ndarray, shape (n, 3)
        Magnetorquer dipole held from each step, A m^2 (zeros without magnetorquers).
    field : ndarray, shape (n, 3)
        True magnetic field, principal frame, T (zeros without a field).
    momentum_world : ndarray, shape (n, 3)
        ``R (I omega + h)`` of body and wheels, world frame, kg m^2/s.
    impulse_world : ndarray, shape (n, 3)
        External angular impulse since t = 0, world frame, N m s.

    Examples
    --------
    :func:`simulate_controlled` makes one. A spin about a principal axis with no actuator
    (B-dot without a field asks for nothing) keeps its rate; one sample a control step:

    >>> from tumble.dynamics.control.bdot import BDot
    >>> import numpy as np
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=10.0,
    ...                           controller=BDot(gain=1e-3, period=1.0))
    >>> run.t.tolist() == [float(k) for k in range(11)], run.omega.shape, run.wheel_speed.shape
    (True, (11, 3), (11, 0))
    >>> np.allclose(run.omega[-1], [0.0, 0.0, 0.1]), bool(np.all(run.dipole == 0.0))
    (True, True)
    """

    t: FloatArray
    omega: FloatArray
    moments: FloatArray
    wheel_speed: FloatArray
    wheel_torque: FloatArray
    dipole: FloatArray
    field: FloatArray
    impulse_world: FloatArray
    _attitude: Rotation | None
    _momentum: FloatArray | None
    _quaternions: FloatArray
    _wheel_momentum: FloatArray | None
    _wheel_inertia_axes: tuple[FloatArray, FloatArray] | None

    def __init__(self, t: FloatArray, omega: FloatArray, attitude: Rotation | None, moments: FloatArray,
                 wheel_speed: FloatArray, wheel_torque: FloatArray, dipole: FloatArray, field: FloatArray,
                 momentum_world: FloatArray | None, impulse_world: FloatArray, *,
                 quaternions: FloatArray | None = None, wheel_momentum: FloatArray | None = None,
                 wheel_inertia_axes: tuple[FloatArray, FloatArray] | None = None) -> None:
        """The attributes; ``attitude`` and ``momentum_world`` None: built from ``quaternions``
        (n, 4) and ``wheel_momentum`` (``sum_k J_k s_k g_k``, n x 3, body frame; or from
        ``wheel_inertia_axes``, the wheels' ``J`` (k) and axes (k x 3)) on first reading."""
        vars(self).update(t=t, omega=omega, moments=moments, wheel_speed=wheel_speed, wheel_torque=wheel_torque,
                          dipole=dipole, field=field, impulse_world=impulse_world, _attitude=attitude,
                          _momentum=momentum_world, _quaternions=quaternions, _wheel_momentum=wheel_momentum,
                          _wheel_inertia_axes=wheel_inertia_axes)

    def __setattr__(self, name: str, value: Any) -> None:
        raise FrozenInstanceError(f"cannot assign to field {name!r}")

    @property
    def attitude(self) -> Rotation:
        """Principal frame to world at each sample, a scipy ``Rotation`` of n rotations.

        Examples
        --------
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.controlled import simulate_controlled
        >>> run = simulate_controlled([1.0, 2.0, 3.0], [0.0, 0.0, 0.1], t_end=10.0, controller=BDot(gain=1e-3, period=1.0))
        >>> len(run.attitude), round(float(run.attitude[-1].magnitude()), 9)   # 0.1 rad/s about axis 3 for 10 s
        (11, 1.0)
        """
        if self._attitude is None:
            object.__setattr__(self, "_attitude", Rotation.from_quat(self._quaternions))
        return cast(Rotation, self._attitude)

    @property
    def momentum_world(self) -> FloatArray:
        """``R (I omega + h)`` of body and wheels at each sample, world frame, kg m^2/s.

        Examples
        --------
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.controlled import simulate_controlled
        >>> run = simulate_controlled([1.0, 2.0, 3.0], [0.0, 0.1, 0.1], t_end=10.0, controller=BDot(gain=1e-3, period=1.0))
        >>> L = run.momentum_world   # no torque: conserved, |L| = |(0, 0.2, 0.3)|
        >>> L.shape, bool(abs(L - L[0]).max() < 1e-12), round(float((L[-1] ** 2).sum()) ** 0.5, 9) == round(0.13 ** 0.5, 9)
        ((11, 3), True, True)
        """
        if self._momentum is None:
            h = self._wheel_momentum
            if h is None:
                J, axes = cast("tuple[FloatArray, FloatArray]", self._wheel_inertia_axes)
                h = (J * self.wheel_speed) @ axes
            body = self.moments * self.omega + h
            object.__setattr__(self, "_momentum", np.asarray(rotate_by_quaternion(self._quaternions, body), float))
        return cast(FloatArray, self._momentum)

    def __repr__(self) -> str:
        return _display.run_repr(self)

    def _repr_html_(self) -> str:
        """The run's size and headline numbers as an HTML table (Jupyter's rich display)."""
        return _display.run_html(self)

    @property
    def rate(self) -> FloatArray:
        """``|omega|`` at each sample, rad/s.

        Examples
        --------
        Normalised B-dot on a spin about axis 3, square to a uniform field: the torque is
        ``-k omega`` held over each step ``dt``, so ``|omega|`` falls by ``1 - k dt / I3`` a step
        (nearly ``exp(-k t / I3)``):

        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.environment.magnetic import UniformField
        >>> import numpy as np
        >>> from tumble.dynamics.control.controlled import simulate_controlled
        >>> from tumble.dynamics.models.actuators import Magnetorquers
        >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=20.0,
        ...     controller=BDot(gain=2e-3, period=0.5, form="normalized"),
        ...     field=UniformField((3e-5, 0.0, 0.0)), magnetorquers=Magnetorquers(10.0))
        >>> np.allclose(run.rate, 0.1 * (1 - 2e-3 * 0.5 / 0.03) ** (run.t / 0.5), rtol=1e-3)
        True
        """
        return np.asarray(np.linalg.norm(self.omega, axis=1), float)

    def detumble_time(self, threshold: float) -> float | None:
        """When ``|omega|`` first drops below ``threshold`` (rad/s) and stays there, s; None if it never does.

        Examples
        --------
        Normalised B-dot (as in :attr:`rate`) takes the rate down by ``e`` in about
        ``I3 / k = 15 s``; the first sample below is at 15 s:

        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.environment.magnetic import UniformField
        >>> import math
        >>> from tumble.dynamics.control.controlled import simulate_controlled
        >>> from tumble.dynamics.models.actuators import Magnetorquers
        >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=20.0,
        ...     controller=BDot(gain=2e-3, period=0.5, form="normalized"),
        ...     field=UniformField((3e-5, 0.0, 0.0)), magnetorquers=Magnetorquers(10.0))
        >>> run.detumble_time(0.1 / math.e)
        15.0
        >>> run.detumble_time(1e-3) is None, run.detumble_time(1.0)   # never; from the start
        (True, 0.0)
        """
        above = np.nonzero(self.rate >= check_positive("threshold", threshold, "rad/s"))[0]
        if len(above) == 0:
            return float(self.t[0])
        last = int(above[-1])
        return None if last == len(self.t) - 1 else float(self.t[last + 1])

    def pointing_error(self, target: Rotation | Reference | ArrayLike) -> FloatArray:
        """Angle from the target frame (to world) to the body's principal frame at each sample, rad.

        ``target``: a fixed frame (a Rotation, quaternion or matrix) or a moving reference
        (:mod:`~tumble.dynamics.control.pointing`), then the angle to it at each sample's time.

        Examples
        --------
        An uncontrolled spin of 0.1 rad/s about a principal axis turns ``0.1 t`` from its start:

        >>> from tumble.dynamics.control.bdot import BDot
        >>> import numpy as np; from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.control.controlled import simulate_controlled
        >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=10.0,
        ...                           controller=BDot(gain=1e-3, period=1.0))
        >>> np.allclose(run.pointing_error(Rotation.identity()), 0.1 * run.t), np.allclose(
        ...     run.pointing_error([0.0, 0.0, 0.0, 1.0]), run.pointing_error(np.eye(3)))   # the same, as numbers
        (True, True)
        >>> np.allclose(run.pointing_error(Rotation.from_rotvec([0.0, 0.0, 1.0]))[-1], 0.0)
        True

        The same spin is on a reference turning at 0.1 rad/s about the major axis, minor axis to nadir:

        >>> from tumble.dynamics.control.pointing import NadirTarget
        >>> nadir = NadirTarget(0.1)
        >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=10.0,
        ...     controller=BDot(gain=1e-3, period=1.0), attitude0=nadir.attitude(0.0))
        >>> bool(run.pointing_error(nadir).max() < 1e-9)
        True
        """
        frame = target_attitude(target, self.t)
        return np.asarray(mrp_angle(mrp_from_quat((frame.inv() * self.attitude).as_quat())), float)

    def budget_error(self) -> FloatArray:
        """``|L_world(t) - L_world(0) - impulse(t)|`` at each sample, kg m^2/s (0 in exact arithmetic).

        Examples
        --------
        MRP feedback with wheels moves the body's momentum into the wheels; with no external
        torque the total stays put:

        >>> from tumble.dynamics.control.controllers import MRPFeedback
        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.control.controlled import simulate_controlled
        >>> from tumble.dynamics.models.actuators import ReactionWheels
        >>> rw = ReactionWheels(np.eye(3), inertia=1e-4, max_torque=1e-3)
        >>> c = MRPFeedback(K=1e-3, P=1e-2, period=0.5, moments=[0.03, 0.04, 0.05], wheels=rw)
        >>> run = simulate_controlled([0.03, 0.04, 0.05], [0.01, 0.0, 0.0], t_end=10.0, controller=c,
        ...                           wheels=rw, attitude0=Rotation.from_rotvec([0.2, 0.0, 0.0]))
        >>> bool(abs(run.wheel_speed[-1, 0]) > 1.0), bool(run.budget_error().max() < 1e-15)
        (True, True)
        """
        gap = self.momentum_world - self.momentum_world[0] - self.impulse_world
        return np.asarray(np.linalg.norm(gap, axis=1), float)


def simulate_controlled(
    moments: ArrayLike,
    omega0: ArrayLike,
    *,
    t_end: float,
    controller: Controller,
    attitude0: Rotation | ArrayLike | None = None,
    field: MagneticField | None = None,
    gravity_gradient: GravityGradient | OrbitGravityGradient | None = None,
    torque: TorqueLike | None = None,
    magnetorquers: Magnetorquers | None = None,
    wheels: ReactionWheels | None = None,
    wheel_speed0: ArrayLike | None = None,
    sensors: Sensors | None = None,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    compiled: bool | None = None,
    method: str = "dop853",
    step: float | None = None,
    carry_step: bool = False,
) -> ControlledRun:
    """Run a controller in closed loop; see the module docstring for the equations.

    Parameters
    ----------
    moments : array_like, shape (3,)
        Principal moments ``I1 <= I2 <= I3`` of body and wheels (locked), kg m^2.
    omega0 : array_like, shape (3,)
        Initial angular velocity, principal frame, rad/s.
    t_end : float
        Duration, s (> 0); the last step may be shorter than the period.
    controller : Controller
        Called every ``controller.period`` s from t = 0.
    attitude0 : scipy Rotation or quaternion, optional
        Principal frame to world at t = 0 (default identity).
    field : MagneticField, optional
        The field for the magnetorquers and the magnetometer (world frame).
    gravity_gradient : GravityGradient or OrbitGravityGradient, optional
        The gravity-gradient torque of the same orbit (bound to ``moments`` here): a circular
        orbit's, or one along a Keplerian or TLE orbit (``gravity_gradient_of(orbit)``).
    torque : torque model, callable or list of them, optional
        A disturbance torque beside the others, N m (:func:`~tumble.dynamics.models.torques.as_torque`):
        constant ones (``ConstantTorque`` in the body or the world frame, or their sum) run
        compiled; any other on scipy's path. In the external impulse and the budget like the rest.
    magnetorquers, wheels : optional
        The actuators.
    wheel_speed0 : array_like, shape (k,), optional
        Initial wheel spins, rad/s (default 0).
    sensors : Sensors, optional
        Noise and biases (default ideal sensors).
    rtol, atol : float
        DOP853's tolerances.
    compiled : bool, optional
        Integrate each interval in compiled code (True), by scipy's ``solve_ivp`` (False), or
        compiled when every model is a built-in one (None, the default; module docstring).
        True with a model of one's own is a ValueError naming it.
    method : {"dop853", "rk4", "rk8"}
        The hold interval's method: DOP853 with ``rtol`` and ``atol``, or fixed-step RK4 or RK8
        (DOP853's 8th-order weights) at equal steps no longer than ``step`` (s) in each
        interval; the fixed steps on the compiled path only.
    carry_step : bool
        Start each DOP853 interval from the step the last one's error control proposed (clipped
        to the interval) instead of scipy's starting step: half the evaluations where a step spans
        an interval, results within the tolerance rather than step for step scipy's (compiled
        path only; :mod:`~tumble.dynamics.control.compiled_loop`).

    Returns
    -------
    ControlledRun

    Examples
    --------
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.environment.magnetic import UniformField
    >>> import numpy as np
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.models.actuators import Magnetorquers
    >>> run = simulate_controlled([0.01, 0.02, 0.02], [0.0, 0.0, 0.1], t_end=20.0,
    ...     controller=BDot(gain=1e4, period=1.0), field=UniformField((3e-5, 0.0, 0.0)),
    ...     magnetorquers=Magnetorquers(0.2))
    >>> bool(run.rate[-1] < run.rate[0])
    True

    The compiled and the scipy path take the same steps:

    >>> slow = simulate_controlled([0.01, 0.02, 0.02], [0.0, 0.0, 0.1], t_end=20.0,
    ...     controller=BDot(gain=1e4, period=1.0), field=UniformField((3e-5, 0.0, 0.0)),
    ...     magnetorquers=Magnetorquers(0.2), compiled=False)
    >>> np.allclose(run.omega, slow.omega, rtol=1e-12, atol=1e-15)
    True
    """
    I, T, rtol, atol, period, y0 = checked(moments, omega0, t_end, rtol, atol, controller, attitude0, field,
                                           magnetorquers, wheels, wheel_speed0)
    check_actuators(controller, field, magnetorquers, wheels)
    k = 0 if wheels is None else wheels.count
    gg = gravity_gradient.bind(I) if gravity_gradient is not None else None
    disturbance = bind_to_body(as_torque(torque), I)
    if hasattr(controller, "reset"):
        controller.reset()
    axes = wheels.axes if wheels is not None else _NO_ROWS
    J = np.asarray(wheels.inertia) if wheels is not None else _NO_VALUES
    if compiled is False and (method != "dop853" or carry_step):
        raise ValueError(f"method = {method!r} and carry_step = {carry_step!r} need the compiled path; "
                         "scipy's is dop853 from scipy's starting step")
    kernel = None
    if compiled is not False:  # the compiled kernels imported only then
        from .control_kernel import _kernel_for

        kernel = _kernel_for(compiled, I, field, gg, magnetorquers, wheels, rtol, atol, T, method, step, disturbance)
    if kernel is None and (method != "dop853" or carry_step):
        raise ValueError(f"method = {method!r} and carry_step = {carry_step!r} need the built-in models (compiled path)")
    grid = control_instants(T, period)
    steps = len(grid) - 1
    law = None if kernel is None else kernel.law(controller, sensors, wheels, field)
    rods = magnetorquers.rods if magnetorquers is not None else _NO_ROWS
    limits = kernel_array(magnetorquers.max_dipole, (len(rods),)) if magnetorquers is not None else _NO_VALUES
    if kernel is not None and law is not None:  # the whole loop in one compiled call
        Y, D, U, F = kernel.run(y0, grid, law, rods, limits, carry_step, padded=True)
        return _run(grid, Y, I, J, axes, k, U, D, F)
    if kernel is not None and isinstance(controller, DetumbleThenPoint):  # each mode's law compiled, the switch between
        parts = controller.compiled_run(kernel, sensors, wheels, field, y0, grid, rods, limits, carry_step)
        if parts is not None:
            return _run(grid, parts[0], I, J, axes, k, parts[2], parts[1], parts[3])
    if kernel is not None and isinstance(controller, Estimated):  # the sensors, the filter and the law compiled too
        from . import estimated_loop

        laws = estimated_loop.plan(controller, sensors, I, wheels, field)
        if laws is not None:
            Y, D, U, F = estimated_loop.run(controller, kernel, laws, grid, y0, rods, limits, carry_step)
            return _run(grid, Y, I, J, axes, k, U, D, F)
    elif kernel is not None and sensors is not None:  # the law fed the sensors' readings, noise and all, compiled
        from . import estimated_loop

        laws = estimated_loop.plan_readings(controller, sensors, I, wheels, field)
        if laws is not None:
            Y, D, U, F = estimated_loop.run(controller, kernel, laws, grid, y0, rods, limits, carry_step, sensors)
            return _run(grid, Y, I, J, axes, k, U, D, F)
    sensors = sensors if sensors is not None else Sensors()
    rng = sensors.rng()
    I_rw_inv = locked_inverse(I, wheels)

    def rhs(t: float, y: FloatArray, dipole: FloatArray, u_cmd: FloatArray) -> FloatArray:
        q, w, s = y[:4] / math.sqrt(float(y[:4] @ y[:4])), y[4:7], y[7:7 + k]
        R = matrix(q)
        tau = np.zeros(3)  # external torque, body frame
        if magnetorquers is not None and field is not None:
            tau = tau + cross(dipole, R.T @ field.world(t))
        if gg is not None:
            tau = tau + R.T @ gg(t, w, cast(Rotation, Matrix(R)))
        if disturbance is not None:
            tau = tau + body_torque(disturbance, t, w, Rotation.from_quat(q))
        u = wheels.applied_torque(u_cmd, s) if wheels is not None else np.zeros(0)
        h = (J * s) @ axes
        x, y_, z, c = (float(v) for v in q)
        w0_, w1, w2 = (float(v) for v in w)
        L0, L1, L2 = (I * w + h).tolist()  # the whole's momentum; L' = L x w + tau - u (the loop's kernel's formulas)
        a0, a1, a2 = (tau - u @ axes).tolist()
        dw = I_rw_inv @ np.array(momentum_rate_components(L0, L1, L2, w0_, w1, w2, a0, a1, a2))
        ds = u / J - axes @ dw if k else np.zeros(0)
        dq = np.array(quaternion_rate_components(x, y_, z, c, w0_, w1, w2))
        return np.concatenate([dq, dw, ds, R @ tau])

    y = y0.copy()
    rows: list[FloatArray] = []
    dipoles, torques, fields = [], [], []
    for i in range(steps + 1):
        t = float(grid[i])
        q, w, s = y[:4] / np.linalg.norm(y[:4]), y[4:7], y[7:7 + k]
        y[:4] = q
        att = Rotation.from_quat(q)
        b_body = None if field is None else kernel.field_body(q, t) if kernel is not None else \
            rotate_by_quaternion(q * [-1.0, -1.0, -1.0, 1.0], field.world(t))
        command = controller(t, sensors.sample(t, w, att, b_body, s, rng)) if i < steps else Command()
        if not isinstance(command, Command):
            raise ValueError(f"the controller returned {command!r}; it must return a Command")  # noqa: TRY004
        dipole = magnetorquers.saturate(command.dipole) if (magnetorquers is not None and command.dipole is not None) \
            else np.zeros(3)
        u_cmd = np.zeros(k) if command.wheel_torque is None else np.asarray(command.wheel_torque, float)
        if u_cmd.shape != (k,):
            raise ValueError(f"the controller's wheel_torque has shape {u_cmd.shape}; there are {k} wheels")
        rows.append(y.copy())
        dipoles.append(dipole)
        torques.append(wheels.applied_torque(u_cmd, s) if wheels is not None else np.zeros(0))
        fields.append(b_body if b_body is not None else np.zeros(3))
        if i == steps:
            break
        if kernel is not None:
            y = kernel.advance(y, t, float(grid[i + 1]), dipole, u_cmd)
            continue
        sol = solve_ivp(rhs, (t, float(grid[i + 1])), y, method="DOP853", rtol=rtol, atol=atol, args=(dipole, u_cmd))
        if not sol.success:
            raise RuntimeError(f"the integration failed at t = {t} s: {sol.message}")
        y = np.asarray(sol.y[:, -1], float)
    return _run(grid, np.array(rows), I, J, axes, k, np.array(torques).reshape(len(grid), k), np.array(dipoles),
                np.array(fields))


def _run(grid: FloatArray, Y: FloatArray, I: FloatArray, J: FloatArray, axes: FloatArray, k: int, torques: FloatArray,
         dipoles: FloatArray, fields: FloatArray) -> ControlledRun:
    """The run from the states ``Y`` at the control instants (or the kernels' padded states: the
    impulse last) and what was held from each (its attitude and momentum built on first reading,
    from the wheels' ``J`` and axes as they are now: copies)."""
    return ControlledRun(np.asarray(grid, float), Y[:, 4:7], None, I, Y[:, 7:7 + k], torques, dipoles, fields, None,
                         Y[:, -3:], quaternions=Y[:, :4], wheel_inertia_axes=(J.copy(), axes.copy()))

