"""The fixed cost of :func:`~tumble.dynamics.control.controlled.simulate_controlled`: its input checks
and the arrays it builds before the loop, each kept or short-cut for repeated runs.

A benchmark's closed loop (60 s, 121 control steps, the whole loop compiled) runs in ~100 us;
the Python around it took ~60 us, a third of the call. What a repeated run of the same inputs
needs again is kept here, keyed by the inputs' values (never by the identity of an object whose
arrays may change in place): the moments' checks by their bytes, the control instants by
``(t_end, period)``; the compiled kernel's parameters by their models' forms
(:func:`~tumble.dynamics.control.control_kernel._kernel_for`). A bad input still meets the full
checks, with their messages.
"""

from __future__ import annotations

import functools
import math
import warnings
from typing import Any

import numpy as np

from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, FloatArray
from ..models.actuators import check_wheels
from ...validation import check_moments, check_positive, check_rotation, check_vector, short_repr
from ..engine.stepsize import check_atol, check_rtol
from .bdot import BDot
from .controllers import MomentumDumping, MRPFeedback
from .estimated import Estimated
from .mission import DetumbleThenPoint
from .sampled import OneStepWarning, check_bdot_loop

__all__ = ["check_actuators", "checked", "control_instants", "field_max", "locked_inverse", "moments_checked"]


def checked(moments: ArrayLike, omega0: ArrayLike, t_end: float, rtol: float, atol: float, controller: Any,
            attitude0: Rotation | ArrayLike | None, field: Any, magnetorquers: Any, wheels: Any,
            wheel_speed0: ArrayLike | None) -> tuple[FloatArray, float, float, float, float, FloatArray]:
    """:func:`~tumble.dynamics.control.controlled.simulate_controlled`'s inputs checked, in its
    order: ``(moments, t_end, rtol, atol, period, y0)``, ``y0`` the initial state
    ``(q, omega, s, impulse = 0)``; a ValueError naming the first bad one. Float64 arrays and
    Python floats are checked once for their values (kept; copies returned).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control._front import checked
    >>> from tumble.dynamics.control.bdot import BDot
    >>> I, T, rtol, atol, period, y0 = checked([1.0, 2.0, 3.0], [0.0, 0.0, 0.1], 10.0, 1e-10, 1e-12,
    ...                                        BDot(gain=1.0, period=0.5), None, None, None, None, None)
    >>> T, period, y0.tolist()
    (10.0, 0.5, [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0])
    >>> checked(np.ones(3), np.zeros(3), -1.0, 1e-10, 1e-12, BDot(gain=1.0, period=0.5), None, None, None, None, None)
    Traceback (most recent call last):
    ...
    ValueError: t_end = -1.0 must be a positive finite number (s)
    """
    period = getattr(controller, "period", None)
    if period is None and not hasattr(controller, "period"):
        raise ValueError(f"controller = {getattr(controller, '__name__', None) or short_repr(controller)} is not a "
                         "controller: one has a period (s) and is called as controller(t, measurement) -> Command "
                         "(tumble.dynamics.control: BDot, MRPFeedback, MomentumDumping, DetumbleThenPoint, Estimated)")
    lone_rods = magnetorquers is not None and field is None
    k = 0 if wheels is None else wheels.count
    raw = (_raw(moments), _raw(omega0), _raw(attitude0), _raw(wheel_speed0))
    floats = type(t_end) is float and type(rtol) is float and type(atol) is float and type(period) is float
    if None in raw or not floats:
        I, T, rtol, atol, period, y0 = _checked(moments, omega0, t_end, rtol, atol, period, attitude0, lone_rods, k,
                                                wheel_speed0)
    else:
        I, T, rtol, atol, period, y0 = _checked_raw(raw, t_end, rtol, atol, period, lone_rods, k)
        I, y0 = I.copy(), y0.copy()
    if wheels is not None:
        check_wheels(I, wheels)
    for law in (controller, getattr(controller, "detumble", None)) if magnetorquers is not None else ():
        # a B-dot alone or a mission's (without magnetorquers the run is refused: nothing to say of its gain)
        if isinstance(law, BDot) and law.form == "normalized":
            check_bdot_loop(I, law.gain, law.period, t_end=T)
        elif isinstance(law, BDot) and field is not None and (largest := field_max(field, T)) is not None:
            check_bdot_loop(I, law.gain, law.period, largest, T)  # classic: its gain is k_b |B|^2
    if period >= T:  # the samples are the control instants: two, and one command
        warnings.warn(f"controller.period = {period:g} s is not shorter than t_end = {T:g} s: the controller acts "
                      "once, at t = 0, and the run has two samples (a period in ms written as s?)", OneStepWarning,
                      stacklevel=3)
    return I, T, rtol, atol, period, y0


#: Where :func:`field_max` looks at the field: this many instants over the run (at most one
#: orbit's worth of them are needed; the dipole's |B| varies twofold from the equator to a pole).
FIELD_LOOKS = 25


def field_max(field: Any, t_end: float) -> float | None:
    """The largest ``|B|`` (T) of ``field`` (``world(t)``) at :data:`FIELD_LOOKS` instants over
    ``[0, t_end]`` s; None where the field cannot say (a user's field that fails here fails the run
    with its own message).

    Examples
    --------
    >>> from tumble.dynamics.control._front import field_max
    >>> from tumble.dynamics.environment.magnetic import UniformField
    >>> field_max(UniformField((3e-5, 0.0, 4e-5)), 60.0)
    5e-05
    """
    try:
        return max(float(np.linalg.norm(field.world(float(t)))) for t in np.linspace(0.0, t_end, FIELD_LOOKS))
    except Exception:  # noqa: BLE001 - the run calls the field again and reports what it raises
        return None


def _raw(value: object) -> tuple[tuple[int, ...], bytes] | tuple[()] | None:
    """A float64 array's shape and bytes, ``()`` for None, else None (not kept)."""
    if value is None:
        return ()
    if type(value) is np.ndarray and value.dtype == np.float64:
        return value.shape, value.tobytes()
    return None


def _array(raw: tuple[tuple[int, ...], bytes] | tuple[()]) -> FloatArray | None:
    """The array of :func:`_raw`'s ``raw`` (None for ``()``)."""
    return np.frombuffer(raw[1]).reshape(raw[0]).copy() if raw else None


@functools.lru_cache(maxsize=64)
def _checked_raw(raw: tuple[Any, ...], t_end: float, rtol: float, atol: float, period: float, lone_rods: bool,
                 k: int) -> tuple[FloatArray, float, float, float, float, FloatArray]:
    """:func:`_checked` of the arrays of :func:`_raw`'s bytes, kept (a bad input is not)."""
    moments, omega0, attitude0, wheel_speed0 = (_array(r) for r in raw)
    return _checked(moments, omega0, t_end, rtol, atol, period, attitude0, lone_rods, k, wheel_speed0)


def _checked(moments: Any, omega0: Any, t_end: float, rtol: float, atol: float, period: Any, attitude0: Any,
             lone_rods: bool, k: int, wheel_speed0: Any) -> tuple[FloatArray, float, float, float, float, FloatArray]:
    """:func:`checked`'s checks, ``lone_rods`` magnetorquers without a field, ``k`` wheels."""
    I = moments_checked(moments)
    w0 = check_vector("omega0", omega0, "rad/s")
    T = check_positive("t_end", t_end, "s")
    rtol = check_rtol("rtol", rtol)
    atol = check_atol("atol", atol, "absolute: rad/s for omega and the wheels, 1 for the quaternion")
    period = check_positive("controller.period", period, "s")
    q0 = check_rotation("attitude0", attitude0) if attitude0 is not None else (0.0, 0.0, 0.0, 1.0)
    if lone_rods:
        raise ValueError("magnetorquers need a magnetic field: give field=DipoleField(orbit) or UniformField(B)")
    s0 = np.zeros(k) if wheel_speed0 is None else np.atleast_1d(np.asarray(wheel_speed0, float))
    if s0.shape != (k,) or not all(map(math.isfinite, s0.tolist())):  # floats: ~0.3 us, not 3
        raise ValueError(f"wheel_speed0 = {wheel_speed0!r} must be {k} finite numbers (rad/s), one per wheel")
    return I, T, rtol, atol, period, np.concatenate([q0, w0, s0, np.zeros(3)])


def moments_checked(value: ArrayLike) -> FloatArray:
    """:func:`~tumble.validation.check_moments` of ``value`` (a copy), the checks of a float64
    array of shape (3,) done once for its values.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control._front import moments_checked
    >>> moments_checked(np.array([10.0, 12.0, 15.0])).tolist()
    [10.0, 12.0, 15.0]
    >>> moments_checked(np.array([1.0, 2.0, 4.0]))
    Traceback (most recent call last):
    ...
    ValueError: moments = [1.0, 2.0, 4.0] breaks the triangle inequality I1 + I2 >= I3 (kg m^2): no distribution of positive mass has them
    """
    if type(value) is np.ndarray and value.shape == (3,) and value.dtype == np.float64:
        _moments_of(value.tobytes())
        return value.copy()
    return check_moments("moments", value)


@functools.lru_cache(maxsize=64)
def _moments_of(raw: bytes) -> None:
    """Check the moments of these float64 bytes (raises; a bad value is not kept)."""
    check_moments("moments", np.frombuffer(raw).copy())


def control_instants(t_end: float, period: float) -> FloatArray:
    """The control instants ``k period`` from 0, the last ``t_end`` (s): a new array each call.

    Examples
    --------
    >>> from tumble.dynamics.control._front import control_instants
    >>> control_instants(1.2, 0.5).tolist()
    [0.0, 0.5, 1.0, 1.2]
    """
    return _instants(t_end, period).copy()


@functools.lru_cache(maxsize=64)
def _instants(t_end: float, period: float) -> FloatArray:
    """:func:`control_instants`, kept (callers get a copy)."""
    steps = max(1, math.ceil(t_end / period - 1e-9))
    return np.asarray(np.minimum(np.arange(steps + 1) * period, t_end), float)


def locked_inverse(moments: FloatArray, wheels: Any) -> FloatArray:
    """``(I - sum_k J_k g_k g_k^T)^-1``, 1/(kg m^2): the body's inertia with the wheels' axial
    inertia taken out (the wheels spin freely about their axes), inverted.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control._front import locked_inverse
    >>> from tumble.dynamics.models.actuators import ReactionWheels
    >>> locked_inverse(np.array([1.0, 2.0, 2.5]), ReactionWheels(np.eye(3), inertia=0.5)).diagonal().tolist()
    [2.0, 0.6666666666666666, 0.5]
    >>> locked_inverse(np.array([1.0, 2.0, 2.5]), None).diagonal().tolist()
    [1.0, 0.5, 0.4]
    """
    return np.asarray(np.linalg.inv(np.diag(moments) - (wheels.locked_axial() if wheels is not None else 0.0)), float)


def check_actuators(controller: Any, field: Any, magnetorquers: Any, wheels: Any) -> None:
    """Refuse a run whose built-in controller commands an actuator the run lacks: B-dot and momentum
    dumping in a field without ``magnetorquers`` (their dipoles were dropped without a word: the
    "detumbling" did nothing), MRP feedback without its ``wheels``, or with another number of
    them (a failure in numpy's broadcasting). A ValueError naming the missing argument. B-dot with
    neither field nor magnetorquers asks for nothing (a free body's run, as the examples use
    it); controllers of the user's own pass.

    Examples
    --------
    >>> from tumble.dynamics.control._front import check_actuators
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.environment.magnetic import UniformField
    >>> check_actuators(BDot(gain=1e4, period=1.0), UniformField((3e-5, 0.0, 0.0)), None, None)
    Traceback (most recent call last):
    ...
    ValueError: controller = BDot commands magnetic dipoles in the field: give magnetorquers=Magnetorquers(...) to make them
    """
    inner = controller.controller if isinstance(controller, Estimated) else controller
    parts = (inner.detumble, inner.point) if isinstance(inner, DetumbleThenPoint) else (inner,)
    for part in parts:
        name = type(part).__name__
        if isinstance(part, (BDot, MomentumDumping)) and magnetorquers is None and field is not None:
            raise ValueError(f"controller = {name} commands magnetic dipoles in the field: give "
                             "magnetorquers=Magnetorquers(...) to make them")
        own = part.pointing.wheels if isinstance(part, MomentumDumping) else part.wheels \
            if isinstance(part, MRPFeedback) else None
        if own is not None and (wheels is None or wheels.count != own.count):
            given = "none" if wheels is None else f"{wheels.count}"
            raise ValueError(f"controller = {name} drives {own.count} reaction wheels (its wheels=); the run is given "
                             f"{given}: give simulate_controlled(..., wheels=) the controller's ReactionWheels")
