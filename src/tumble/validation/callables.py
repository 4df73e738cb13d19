"""The check that an argument is a function that can be called as asked. It raises ``ValueError``
whose message names the field, the value and the call. Re-exported by :mod:`tumble.validation`.
"""

from __future__ import annotations

import inspect

from .values import short_repr

__all__ = ["check_callable"]


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
        raise ValueError(f"{name} = {label}{signature} cannot be called as {call}: it must take those {count} "
                         "arguments") from None

