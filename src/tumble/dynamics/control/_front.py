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
from typing import Any

import numpy as np

from ...typing import ArrayLike, FloatArray
from ...validation import check_moments, check_positive

__all__ = ["control_instants", "locked_inverse", "moments_checked", "positive"]


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


def positive(field: str, value: object, unit: str) -> float:
    """:func:`~tumble.validation.check_positive` of ``value``, a positive finite Python float
    passed straight through.

    Examples
    --------
    >>> from tumble.dynamics.control._front import positive
    >>> positive("t_end", 60.0, "s"), positive("t_end", 60, "s")
    (60.0, 60.0)
    >>> positive("t_end", -1.0, "s")
    Traceback (most recent call last):
    ...
    ValueError: t_end = -1.0 must be a positive finite number (s)
    """
    if type(value) is float and 0.0 < value < math.inf:
        return value
    return check_positive(field, value, unit)


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
