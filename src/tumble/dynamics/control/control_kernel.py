"""The compiled closed loop bound to a run: its parameters, one hold interval, the whole loop.

Beside the kernels it runs (:mod:`~tumble.dynamics.control.compiled_loop`, compiled at import),
imported with them only when a compiled run is asked for. Each model gives its parameters
itself through one method, ``loop_form()`` (the fields of
:mod:`~tumble.dynamics.environment.magnetic` and :mod:`~tumble.dynamics.environment.igrf`, the
gravity gradients, the magnetorquers and the wheels): a model that declares none, or a subclass
that changes a law, keeps the Python path (:func:`compiled_control_models`).

:class:`ControlKernel` binds a run's fixed parameters (the body, the wheels, the field, the
gravity gradient, the tolerances) for :func:`~tumble.dynamics.control.controlled.simulate_controlled`
and runs the compiled kernels of :mod:`~tumble.dynamics.control.compiled_loop` (the equations of
:mod:`~tumble.dynamics.control.loop_terms`): :meth:`ControlKernel.advance` integrates one
zero-order-hold interval for a controller of one's own, called in Python; :meth:`ControlKernel.run`
runs the whole loop in one compiled call for the built-in controllers that :func:`compiled_law`
recognises, with ideal sensors (noisy ones and the filter:
:mod:`~tumble.dynamics.control.estimated_loop`). Both take the same steps: the same kernel integrates each
interval, and the laws are :mod:`~tumble.dynamics.control.laws`' functions, which the Python
controllers call too, so the two paths agree to round-off (tests/test_control_loop.py).

**Why compiled, and which scheme.** The Python path calls scipy's ``solve_ivp`` once per control
period, ~1 ms of Python overhead per interval and ~0.1 ms per right-hand side: a two-orbit
detumble (11,400 one-second periods) took 41 s; with each interval compiled but the controller in
Python, the Python call (~100 us with scipy's ``Rotation``) was most of the rest. No library offers
an ODE solver callable from numba's compiled code, so the interval is scipy's DOP853 written out
from the engine's tableau (the Dormand-Prince 8(5,3) pair of Hairer, Norsett & Wanner, *Solving
Ordinary Differential Equations I*, 2nd ed., sec. II.10; coefficients from
:class:`scipy.integrate.DOP853`) with scipy's error norm, step control and starting step
(:mod:`~tumble.dynamics.engine.stepsize`). So the compiled and the scipy paths take the same steps
and agree to round-off, not only to the tolerance (tested); an adaptive scheme also follows the
wheels' Coulomb friction through zero speed (linear below ``limit_cycle_speed``, as in the Python path).
Fixed-step RK4 and RK8, and DOP853 continuing its step from one interval to the next
(``carry``), are the compiled path's alone.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, cast

import numpy as np

from ...jit import kernel_array
from ...typing import FloatArray
from . import compiled_loop as _loop
from . import loop_laws as _laws
from ._front import locked_inverse
from ..environment.magnetic import FIELD_NONE, FIELD_TABLE, field_form
from ..models.dipole import ResidualDipole
from ..models.torque_protocols import constant_terms, kernel_form
from ..models.torques import TorqueSum
from .bdot import BDot
from .controllers import MomentumDumping, MRPFeedback
from .loop_terms import WHEEL, packed
from .pointing import is_reference, reference_table

__all__ = ["ControlKernel", "compiled_control_models", "compiled_law", "disturbance_form"]

#: An empty table (the kernels' argument where there is none), and no field's parameters (in a key).
_NO_TABLE, _NO_FIELD = np.zeros((4, 1, 3)), np.zeros(0)
#: The methods of a hold interval, by name.
METHODS = {"dop853": _loop.DOP853, "rk4": _loop.RK4, "rk8": _loop.RK8}


def disturbance_form(torque: Any, field: Any = None) -> tuple[float, ...] | None:
    """The loop's terms ``P[21:30]`` (:mod:`~tumble.dynamics.control.loop_terms`) of a disturbance
    torque: its constant body and world torques (N m,
    :func:`~tumble.dynamics.models.torque_protocols.constant_terms`) and its residual dipoles
    (:class:`~tumble.dynamics.models.dipole.ResidualDipole`, A m^2, body frame; their sum) in the
    run's ``field``; zeros for None; None where it has other terms (a gravity gradient, which the
    loop takes as ``gravity_gradient``), no compiled form, or a dipole in another field than the run's.

    Examples
    --------
    >>> from tumble.dynamics import ConstantTorque, ResidualDipole, UniformField
    >>> from tumble.dynamics.control.control_kernel import disturbance_form
    >>> disturbance_form(ConstantTorque((0.0, 0.0, 1e-6)) + ConstantTorque((2e-6, 0.0, 0.0), "world"))
    (0.0, 0.0, 1e-06, 2e-06, 0.0, 0.0, 0.0, 0.0, 0.0)
    >>> field = UniformField((0.0, 3e-5, 0.0))
    >>> disturbance_form(ResidualDipole((0.2, 0.0, 0.0), field), field)[6:]
    (0.2, 0.0, 0.0)
    >>> disturbance_form(ResidualDipole((0.2, 0.0, 0.0), field)) is None   # not the run's field (it has none)
    True
    >>> disturbance_form(lambda t, omega, attitude: -1e-3 * omega) is None   # Python's to call
    True
    """
    terms = () if torque is None else getattr(torque, "terms", (torque,))
    dipoles = [term for term in terms if isinstance(term, ResidualDipole)]
    if dipoles:  # the rest as one torque
        others = [term for term in terms if not isinstance(term, ResidualDipole)]
        torque = TorqueSum(*others) if len(others) > 1 else others[0] if others else None
    constant = constant_terms(kernel_form(torque))
    if constant is None:
        return None
    m = [0.0, 0.0, 0.0]
    for dipole in dipoles:
        if type(dipole).__call__ is not ResidualDipole.__call__ or not _same_field(dipole.field, field):
            return None
        m = [a + b for a, b in zip(m, dipole.dipole)]
    return (*constant, *m)


def _same_field(a: Any, b: Any) -> bool:
    """Whether two fields are one the loop evaluates: the same compiled form (kind and parameters;
    None for a field that has none)."""
    one, other = (None, None) if a is None else (field_form(a), field_form(b))
    return one is not None and other is not None and one[0] == other[0] and np.array_equal(one[1], other[1])


def compiled_control_models(field: Any, gravity_gradient: Any, magnetorquers: Any, wheels: Any, *,
                            torque: Any = None) -> str | None:
    """None if every model declares the compiled loop's form (its ``loop_form()``: the built-in
    fields, gravity gradients, magnetorquers and wheels; a disturbance ``torque`` of constant body or
    world torques or residual dipoles in the run's field, :func:`disturbance_form`), else the first
    other one's description.

    Examples
    --------
    >>> from tumble.dynamics.environment.magnetic import UniformField
    >>> from tumble.dynamics.control.control_kernel import compiled_control_models
    >>> compiled_control_models(UniformField((0.0, 0.0, 3e-5)), None, None, None) is None
    True
    >>> compiled_control_models(None, lambda t, w, R: w, None, None)
    'gravity_gradient = <lambda> (a GravityGradient or OrbitGravityGradient)'
    """
    if wheels is not None and getattr(wheels, "count", 0) > _loop.MAX_WHEELS:
        return f"wheels = {wheels.count} wheels (at most {_loop.MAX_WHEELS} compiled)"
    orbit = getattr(gravity_gradient, "orbit", None)
    if orbit is not None and callable(getattr(gravity_gradient, "loop_form", None)) and gravity_gradient.loop_form() is None:
        return f"gravity_gradient's orbit = {type(orbit).__name__} (a CircularOrbit, KeplerOrbit or TLEOrbit)"
    for name, model, kinds in (("field", field, "DipoleField, UniformField or IGRFField"),
                               ("gravity_gradient", gravity_gradient, "GravityGradient or OrbitGravityGradient"),
                               ("magnetorquers", magnetorquers, "Magnetorquers"),
                               ("wheels", wheels, "ReactionWheels")):
        form = getattr(model, "loop_form", None)
        if model is not None and (not callable(form) or form() is None):
            label = getattr(model, "__name__", None) or type(model).__name__
            return f"{name} = {label} (a {kinds})"
    if disturbance_form(torque, field) is None:
        label = getattr(torque, "__name__", None) or type(torque).__name__
        return (f"torque = {label} (ConstantTorque in the body or the world frame, a ResidualDipole in the run's field, "
                "or their sum)")
    return None


def _plain(controller: Any, cls: type) -> bool:
    """Whether ``controller`` is a ``cls`` whose law is ``cls``'s own (a subclass may change it)."""
    return isinstance(controller, cls) and type(controller).__call__ is cls.__call__


def compiled_law(controller: Any, sensors: Any, moments: FloatArray, wheels: Any, field: Any) -> _laws.Law | None:
    """``(law, parameters, allocation, reference)`` of a built-in controller that the compiled loop
    runs (:mod:`~tumble.dynamics.control.compiled_loop`), or None for the Python path: B-dot; MRP
    feedback to a fixed target or tracking a moving reference (``reference``, tabulated at the
    control instants by :func:`~tumble.dynamics.control.pointing.reference_table`; None for a fixed
    target) and momentum dumping with it, on the run's own wheels and moments; all with ideal
    sensors (None, or with no noise, bias, star tracker or sun sensor).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.control_kernel import compiled_law
    >>> from tumble.dynamics.control.loop_laws import LAW_BDOT
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> law, L, pinv, reference = compiled_law(BDot(gain=1e4, period=1.0), Sensors(), np.ones(3), None, None)
    >>> law == LAW_BDOT, L.tolist(), pinv.shape, reference
    (True, [10000.0, 0.0, 0.0], (0, 3), None)
    >>> compiled_law(BDot(gain=1e4, period=1.0), Sensors(gyro_noise=1e-4), np.ones(3), None, None) is None
    True
    """
    if sensors is not None and (sensors.gyro_noise or sensors.magnetometer_noise or sensors.attitude != "ideal"
                                or any(sensors.gyro_bias) or any(sensors.magnetometer_bias) or sensors.attitude_noise
                                or sensors.sun_sensor is not None or sensors.star_tracker is not None
                                or sensors.sunlight is not None):
        return None
    k = 0 if wheels is None else wheels.count
    if _plain(controller, BDot):
        L = [controller.gain, controller.form == "normalized", controller.derivative == "difference"]
        return _laws.LAW_BDOT, np.array(L, dtype=float), np.zeros((k, 3)), None
    dumping = _plain(controller, MomentumDumping)
    pointing = controller.pointing if dumping else controller
    if not _plain(pointing, MRPFeedback) or wheels is None or (dumping and field is None):
        return None
    own = pointing.wheels  # the run's own wheels (most often the same object: no comparison, ~7 us)
    if not (_same(pointing.moments, moments) and (own is wheels or (
            np.array_equal(own.axes, wheels.axes)
            and np.array_equal(np.broadcast_to(own.inertia, (k,)), np.broadcast_to(wheels.inertia, (k,)))))):
        return None
    moving = is_reference(pointing.target)
    L = [pointing.K, pointing.P, pointing.Ki, pointing.integral_limit, pointing.gyroscopic, pointing.period,
         *((0.0, 0.0, 0.0, 1.0) if moving else pointing.target.as_quat()),
         *((controller.gain, *controller.h_target) if dumping else (0.0, 0.0, 0.0, 0.0)), *pointing._I_rw.ravel()]
    return (_laws.LAW_DUMPING if dumping else _laws.LAW_MRP, np.array(L, dtype=float),
            np.ascontiguousarray(pointing._pinv), pointing.target if moving else None)


def _same(a: Any, b: FloatArray) -> bool:
    """``np.array_equal(a, b)`` for checked moments ``b`` (positive, finite: no NaN, no -0): by
    their bytes where ``a`` is a float64 array too (~0.2 us, not 1.3)."""
    if type(a) is np.ndarray and a.dtype == np.float64 and a.shape == b.shape:
        return a.tobytes() == b.tobytes()
    return bool(np.array_equal(a, b))


def _kernel_for(compiled: bool | None, I: FloatArray, field: Any, gravity_gradient: Any, magnetorquers: Any,
                wheels: Any, rtol: float, atol: float, t_end: float, method: str = "dop853",
                step: float | None = None, torque: Any = None) -> ControlKernel | None:
    """The run's :class:`ControlKernel` for these models (its arguments), or None for scipy's path
    where one is not a built-in model and ``compiled`` is None (a ValueError naming it if True).
    Kept for repeated runs by the values it is built from (:func:`_kernel_key`).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.control_kernel import _kernel_for
    >>> _kernel_for(None, np.ones(3), None, lambda t, w, R: w, None, None, 1e-10, 1e-12, 1.0) is None
    True
    >>> kernel = _kernel_for(None, np.ones(3), None, None, None, None, 1e-10, 1e-12, 1.0)
    >>> kernel.k, _kernel_for(None, np.ones(3), None, None, None, None, 1e-10, 1e-12, 1.0) is kernel
    (0, True)
    """
    if compiled is not None and not isinstance(compiled, bool):
        raise ValueError(f"compiled = {compiled!r} must be True, False or None (compiled when the models allow)")
    key = _kernel_key(I, field, gravity_gradient, magnetorquers, wheels, rtol, atol, method, step, torque)
    kernel = _KEPT.get(key) if key is not None else None
    if kernel is not None:
        return kernel
    other = compiled_control_models(field, gravity_gradient, magnetorquers, wheels, torque=torque)
    if other is not None:
        if compiled:
            raise ValueError(f"compiled=True needs built-in models; {other} is not one: use compiled=False or None")
        return None
    kernel = ControlKernel(I, locked_inverse(I, wheels), wheels, field, gravity_gradient, rtol, atol, t_end, method,
                           step, checked=True, torque=torque)
    if key is not None:
        for old in list(_KEPT)[:max(0, len(_KEPT) + 1 - _KEEP)]:  # the oldest
            _KEPT.pop(old, None)
        _KEPT[key] = kernel
    return kernel


#: The kernels of recent runs (:func:`_kernel_for`), by :func:`_kernel_key`; at most :data:`_KEEP`.
_KEPT: dict[tuple[Any, ...], ControlKernel] = {}
_KEEP = 32


def _kernel_key(I: FloatArray, field: Any, gravity_gradient: Any, magnetorquers: Any, wheels: Any, rtol: float,
                atol: float, method: str, step: float | None, torque: Any = None) -> tuple[Any, ...] | None:
    """The values a run's :class:`ControlKernel` is built from: the moments, the models' loop forms
    (which are those :func:`compiled_control_models` asks for), the tolerances and the method; None
    where the kernel is not kept: a model that declares no loop form, too many wheels, or tables
    (an IGRF field, an orbit's gravity gradient: their span depends on ``t_end``).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.control_kernel import _kernel_key
    >>> _kernel_key(np.ones(3), None, None, None, None, 1e-10, 1e-12, "dop853", None) is not None
    True
    >>> _kernel_key(np.ones(3), None, lambda t, w, R: w, None, None, 1e-10, 1e-12, "dop853", None) is None
    True
    """
    if type(method) is not str or not (step is None or isinstance(step, (int, float))):
        return None  # ControlKernel says what is wrong
    disturbance = disturbance_form(torque, field) if torque is not None else ()
    if disturbance is None:
        return None
    key: list[Any] = [I.tobytes(), rtol, atol, method, step, disturbance]
    field_kind = (FIELD_NONE, _NO_FIELD) if field is None else field_form(field)
    if field_kind is None or field_kind[0] == FIELD_TABLE:
        return None
    key += [field_kind[0], np.asarray(field_kind[1], float).tobytes()]
    for model in (gravity_gradient, magnetorquers, wheels):
        loop_form = getattr(model, "loop_form", None)
        form = None if model is None else loop_form() if callable(loop_form) else False
        if form is False or (model is not None and form is None):
            return None
        key.append(form)
    gg, rods, slots = key[-3:]
    if (gg is not None and gg[2] is not None) or (slots is not None and len(slots) > _loop.MAX_WHEELS):
        return None
    key[-3:] = [gg, rods is not None, None if slots is None else slots.tobytes()]
    return tuple(key)


class ControlKernel:
    """The compiled closed loop with the run's fixed parameters bound.

    Parameters
    ----------
    moments : ndarray, shape (3,)
        Principal moments, kg m^2 (wheels locked).
    I_rw_inv : ndarray, shape (3, 3)
        ``(I - sum J g g^T)^-1``, 1/(kg m^2).
    wheels : ReactionWheels or None
    field : DipoleField, UniformField, IGRFField or None
    gravity_gradient : GravityGradient, OrbitGravityGradient (bound to the moments) or None
    rtol, atol : float
        DOP853's tolerances.
    t_end : float, optional
        End of the run, s: the span of the tables of an IGRF field and of an orbit's position
        (needed with those models).
    method : {"dop853", "rk4", "rk8"}
        The hold interval's method.
    step : float, optional
        The fixed-step methods' largest step, s (> 0; needed with them).
    checked : bool
        The models already found compiled by :func:`compiled_control_models` (the caller asked
        it): not asked again.
    torque : torque model, optional
        A disturbance of constant body and world torques and residual dipoles in ``field``
        (:func:`disturbance_form`).
    rotor_momentum : array_like, shape (3,), optional
        The constant momentum of rotors spinning at constant rates relative to the body, kg m^2/s,
        principal frame (``moments`` then hold their mass): a gyrostat's (:mod:`~tumble.dynamics.control.free_loop`).

    Examples
    --------
    A spin about a principal axis, no torque: the rate stays, the attitude turns by ``0.1 t``:

    >>> import numpy as np
    >>> from tumble.dynamics.control.control_kernel import ControlKernel
    >>> kernel = ControlKernel(np.array([1.0, 2.0, 3.0]), np.diag([1.0, 0.5, 1 / 3]), None, None, None, 1e-10, 1e-12)
    >>> y = np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0])
    >>> y = kernel.advance(y, 0.0, 10.0, np.zeros(3), np.zeros(0))
    >>> np.allclose(y[:4], [0.0, 0.0, np.sin(0.5), np.cos(0.5)], rtol=0, atol=1e-10)
    True
    """

    def __init__(self, moments: FloatArray, I_rw_inv: FloatArray, wheels: Any, field: Any, gravity_gradient: Any,
                 rtol: float, atol: float, t_end: float | None = None, method: str = "dop853",
                 step: float | None = None, *, checked: bool = False, torque: Any = None,
                 rotor_momentum: Any = None) -> None:
        from ..environment.tabulated import position_table

        if method not in METHODS:
            raise ValueError(f"method = {method!r} is unknown; allowed: {', '.join(METHODS)}")
        if method != "dop853" and not (step is not None and step > 0.0 and math.isfinite(step)):
            raise ValueError(f"step = {step!r} must be given (s, > 0) with method = {method!r}")
        self.method, self.step = METHODS[method], float(step or 0.0)
        self.k = 0 if wheels is None else wheels.count
        other = None if checked else compiled_control_models(field, gravity_gradient, None, wheels, torque=torque)
        if other is not None:
            raise ValueError(f"{other}: the compiled path cannot evaluate it; use compiled=False")
        field_kind, fp = cast("tuple[int, FloatArray]", field_form(field))
        n, mu, orbit = (0.0, 0.0, None) if gravity_gradient is None else gravity_gradient.loop_form()
        if (field_kind == FIELD_TABLE or orbit is not None) and (t_end is None or not t_end > 0.0):
            raise ValueError(f"t_end = {t_end!r} must be given (s, > 0) with an IGRF field or an orbit's gravity gradient")
        ft = field.tabulate(cast(float, t_end)).coefficients if field_kind == FIELD_TABLE else _NO_TABLE
        gp, gt = np.array([n, 0.0, 0.0, 0.0]), _NO_TABLE
        if orbit is not None:
            table = position_table(orbit, cast(float, t_end))
            gp[1:], gt = (mu, table.t0, table.step), table.coefficients
        slots = np.zeros((_loop.MAX_WHEELS, WHEEL))  # the wheels, then the empty slots (the kernels skip them)
        if wheels is not None:
            slots[:self.k, :9] = wheels.loop_form()
        disturbance = cast("tuple[float, ...]", disturbance_form(torque, field))
        rotor_momentum = np.zeros(3) if rotor_momentum is None else np.asarray(rotor_momentum, float).reshape(3)
        P = np.concatenate([np.asarray(moments, float), np.asarray(I_rw_inv, float).reshape(9), (0.0, 0.0, 0.0, field_kind),
                            gp, (self.k,), disturbance, rotor_momentum, slots.reshape(-1)])
        self.P = np.ascontiguousarray(P, dtype=float)  # an array, not a tuple passed by value at every stage: 4 % faster
        self.X = tuple(kernel_array(a) for a in (fp, ft, gt))  # a read-only table would compile the loop again
        self.packed = packed(self.P, self.X)  # what the kernels take: P and X in one array
        # scipy raises rtol below 100 eps to that (with a warning): the same tolerance here
        self.rtol, self.atol = max(float(rtol), 100 * np.finfo(float).eps), float(atol)
        self.kernels = _loop.kernels()

    def law(self, controller: Any, sensors: Any, wheels: Any, field: Any) -> _laws.Law | None:
        """:func:`compiled_law` for this run's moments.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.control.control_kernel import ControlKernel
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.models.sensors import Sensors
        >>> kernel = ControlKernel(np.ones(3), np.eye(3), None, None, None, 1e-10, 1e-12)
        >>> kernel.law(BDot(gain=1e4, period=1.0), Sensors(), None, None)[0]
        0
        """
        return compiled_law(controller, sensors, self.P[:3], wheels, field)  # read, not kept: a view

    def field_body(self, q: FloatArray, t: float) -> FloatArray:
        """B (T) in the body frame of the unit quaternion ``q`` (body to world, scalar last) at ``t`` (s).

        Examples
        --------
        A field along world x seen from a body turned by 90 deg about z: along body -y.

        >>> from tumble.dynamics.environment.magnetic import UniformField
        >>> import numpy as np
        >>> from tumble.dynamics.control.control_kernel import ControlKernel
        >>> kernel = ControlKernel(np.ones(3), np.eye(3), None, UniformField((3e-5, 0.0, 0.0)), None, 1e-10, 1e-12)
        >>> c = np.sqrt(0.5)
        >>> np.allclose(kernel.field_body(np.array([0.0, 0.0, c, c]), 0.0), [0.0, -3e-5, 0.0], rtol=0, atol=1e-20)
        True
        """
        from .loop_terms import field_body

        x, y, z, s = (float(v) for v in q)
        return np.array(field_body(int(self.P[15]), self.X[0], self.X[1], x, y, z, s, float(t)))

    def advance(self, y: FloatArray, t_start: float, t_end: float, dipole: FloatArray, command: FloatArray) -> FloatArray:
        """The state ``(q, omega, s, impulse)`` at ``t_end`` (s) from ``y`` at ``t_start``, the dipole
        (A m^2) and the wheels' commanded torques (N m) held; RuntimeError if the step collapses.

        Examples
        --------
        A dipole of 0.1 A m^2 along x in 3e-5 T along y: 3e-6 N m about z, held for 10 s on a body
        at rest with I3 = 3 kg m^2 (it barely turns): omega_3 = 1e-5 rad/s and the impulse 3e-5 N m s:

        >>> from tumble.dynamics.environment.magnetic import UniformField
        >>> import numpy as np
        >>> from tumble.dynamics.control.control_kernel import ControlKernel
        >>> kernel = ControlKernel(np.array([1.0, 2.0, 3.0]), np.diag([1.0, 0.5, 1 / 3]), None,
        ...                        UniformField((0.0, 3e-5, 0.0)), None, 1e-10, 1e-12)
        >>> y = kernel.advance(np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]), 0.0, 10.0,
        ...                    np.array([0.1, 0.0, 0.0]), np.zeros(0))
        >>> np.allclose(y[4:7], [0.0, 0.0, 1e-5], rtol=1e-6, atol=1e-15), np.allclose(y[7:], [0.0, 0.0, 3e-5], rtol=1e-6)
        (True, True)
        """
        out, held = np.empty(_loop.N), np.zeros(_loop.MAX_WHEELS)
        held[:self.k] = command
        status = self.kernels["_interval"](_loop.padded(y), float(t_start), float(t_end), self.packed,
                                           np.ascontiguousarray(dipole, dtype=float), held, self.rtol, self.atol,
                                           *_loop.method_flags(self.method), self.step, out)
        if status != 0:
            raise RuntimeError(f"the integration failed at t = {t_start} s: the step size fell below 10 ulp of t")
        return _loop.unpadded(out, self.k)

    def run(self, y0: FloatArray, grid: FloatArray, law: _laws.Law, rods: FloatArray,
            limits: FloatArray, carry: bool = False, *,
            padded: bool = False) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """The whole loop in one compiled call: the states at the control instants ``grid`` (s) from
        ``y0``, the dipoles held (A m^2), the wheels' applied torques (N m) and the fields (T, body
        frame); ``law`` from :func:`compiled_law`, ``rods`` the magnetorquers' rows (k, 6): axes and
        allocation, :attr:`~tumble.dynamics.models.actuators.Magnetorquers.rods`) and ``limits``
        their largest dipoles (A m^2); ``carry``: each DOP853 interval starts from the step the
        last proposed (:mod:`~tumble.dynamics.control.compiled_loop`); ``padded``: the states as the
        kernels keep them (:func:`~tumble.dynamics.control.compiled_loop.padded`), not unpadded.

        Examples
        --------
        B-dot on a spin about axis 3, square to a uniform field, normalised: ``|omega|`` falls by
        nearly ``1 - k dt / I3`` a step of ``dt``:

        >>> import numpy as np
        >>> from tumble.dynamics.control.control_kernel import ControlKernel
        >>> from tumble.dynamics.control.loop_laws import LAW_BDOT
        >>> from tumble.dynamics.environment.magnetic import UniformField
        >>> from tumble.dynamics.models.actuators import Magnetorquers
        >>> I = np.array([0.01, 0.02, 0.03])
        >>> kernel = ControlKernel(I, np.diag(1 / I), None, UniformField((3e-5, 0.0, 0.0)), None, 1e-10, 1e-12)
        >>> law = (LAW_BDOT, np.array([2e-3, 1.0, 0.0]), np.zeros((0, 3)), None)
        >>> y0 = np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0])
        >>> rods = Magnetorquers(10.0).rods   # three rods on the principal axes
        >>> Y, D, U, F = kernel.run(y0, np.arange(3) * 0.5, law, rods, np.full(3, 10.0))
        >>> np.allclose(np.linalg.norm(Y[:, 4:7], axis=1), 0.1 * (1 - 2e-3 * 0.5 / 0.03) ** np.arange(3), rtol=1e-3)
        True
        """
        rods = np.ascontiguousarray(rods, dtype=float)
        if rods.ndim != 2 or (len(rods) and rods.shape[1] != 6):  # the kernel reads columns 3-5 unchecked; none: no rods
            raise ValueError(f"rods has shape {rods.shape}; allowed: (k, 6), Magnetorquers.rods (axes, then G^+)")
        steps = len(grid)
        Y, D, U, F = np.empty((steps, _loop.N)), np.empty((steps, 3)), np.empty((steps, self.k)), np.empty((steps, 3))
        status = self.kernels["_loop"](_loop.padded(y0), np.ascontiguousarray(grid, dtype=float),
                                       self.packed, law[0], law[1], law[2], rods,
                                       np.ascontiguousarray(limits, dtype=float), self.rtol, self.atol,
                                       *_loop.method_flags(self.method), self.step, bool(carry), Y, D, U, F, reference_table(law[3], grid))
        if status != 0:
            raise RuntimeError("the integration failed: the step size fell below 10 ulp of t")
        return (Y if padded else _loop.unpadded(Y, self.k)), D, U, F
