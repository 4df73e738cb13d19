"""The check that an argument is a function that can be called as asked. It raises ``ValueError``
whose message names the field, the value and the call. Re-exported by :mod:`tumble.validation`.
"""

from __future__ import annotations

import inspect
from typing import Any

import numpy as np

from .messages import short_repr

__all__ = ["check_callable", "check_torque_function", "is_vector"]


def check_callable(name: str, value: object, call: str) -> None:
    """Check that ``value`` can be called as ``call`` (``"tau(t, omega, attitude)"``: its
    arguments, positional, counted from the parentheses); a ValueError naming the field and the
    call otherwise. A callable whose signature Python cannot read (a builtin, a compiled
    function) is taken as it is.

    Examples
    --------
    >>> from tumble.validation import check_callable
    >>> check_callable("torque", lambda t, omega, attitude: omega, "tau(t, omega, attitude)")
    >>> check_callable("torque", lambda t, omega: omega, "tau(t, omega, attitude)")
    Traceback (most recent call last):
    ...
    ValueError: torque = <lambda>(t, omega) cannot be called as tau(t, omega, attitude): it must take those 3 arguments
    """
    if not callable(value):
        raise ValueError(f"{name} = {short_repr(value)} must be a function called as {call}")
    count = len([a for a in call[call.index("(") + 1:call.rindex(")")].split(",") if a.strip()])
    try:
        signature = inspect.signature(value)
    except (TypeError, ValueError):  # no signature to read: the call will tell
        return
    try:
        signature.bind(*range(count))
    except TypeError:
        label = getattr(value, "__name__", type(value).__name__)
        raise ValueError(f"{name} = {label}{signature} cannot be called as {call}: it must take "
                         f"{'that argument' if count == 1 else f'those {count} arguments'}") from None


def is_vector(given: Any) -> bool:
    """Whether ``given`` is three real numbers (a list, tuple or 1-d array), not booleans: a vector.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.validation import is_vector
    >>> is_vector((0, 0, 1)), is_vector(np.array([0.0, 1.0, 0.0])), is_vector([True, 0, 0]), is_vector([1, [2, 3], 4])
    (True, True, False, False)
    """
    return (isinstance(given, (list, tuple)) or getattr(given, "ndim", None) == 1) and len(given) == 3 and all(
        isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool) for v in given)


def check_torque_function(field: str, given: Any) -> None:
    """A ValueError naming ``field`` unless ``given`` can be called as ``tau(t, omega, attitude)``;
    three numbers are named as the :class:`~tumble.dynamics.ConstantTorque` meant.

    Examples
    --------
    >>> from tumble.validation import check_torque_function
    >>> check_torque_function("torque[1]", [0.0, 0.0, 1.0])
    Traceback (most recent call last):
    ...
    ValueError: torque[1] = [0.0, 0.0, 1.0] is a vector, not a torque model: for a constant torque give tumble.ConstantTorque((0.0, 0.0, 1.0)) (N m, body frame; frame="world" for a world-fixed one)
    """
    if is_vector(given):
        raise ValueError(f"{field} = {given!r} is a vector, not a torque model: for a constant torque give "
                         f"tumble.ConstantTorque({tuple(float(v) for v in given)}) (N m, body frame; "
                         'frame="world" for a world-fixed one)')  # three numbers: the constant torque meant
    check_callable(field, given, "tau(t, omega, attitude)")
