"""The checks of numbers, vectors, principal moments and axes: the cleaned value, or one message.

Each checker returns the cleaned value or raises ``ValueError`` whose message names the field,
the value and what is allowed, e.g. ``radius = -0.1 must be a positive finite number (m)``. The
triangle inequality on principal moments is written here once (:func:`triangle_excess`); every
other check of it calls that. Units are SI. Re-exported by :mod:`tumble.validation`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from numbers import Real
from typing import cast

import numpy as np

from ..typing import ArrayLike, BoolArray, FloatArray, IntArray, Vector3
from .messages import short_repr

__all__ = [
    "AXES_ALLOWED",
    "AXIS_ROLES",
    "BOUND_REASONS",
    "INERTIA_RTOL",
    "MAX_INERTIA",
    "MAX_RATE",
    "axis_index",
    "breaks_triangle",
    "check_at_most",
    "check_bool",
    "check_direction",
    "check_increasing",
    "check_moments",
    "check_noise",
    "check_number",
    "check_positive",
    "check_vector",
    "check_vectors",
    "is_body",
    "refuse_body",
    "refuse_first",
    "triangle_excess",
]

#: Names of the principal axes in ascending order of moment.
AXIS_ROLES = ("minor", "intermediate", "major")

#: Relative tolerance of the physical-validity checks: a condition such as ``I1 + I2 >= I3``
#: may be violated by at most ``INERTIA_RTOL * trace(I)``. Planar bodies (thin rods, point
#: masses in one plane) sit exactly *on* the triangle inequality, so round-off alone can
#: violate it by a few ulps; 1e-9 of the trace is far above round-off (~1e-16) and far below
#: any physical violation worth catching.
INERTIA_RTOL = 1e-9


def refuse_first(field: str, values: ArrayLike, bad: ArrayLike, rule: str) -> None:
    """Raise ``ValueError`` for the first entry of a batch where ``bad`` holds, else nothing.

    The message names the index as scipy does, e.g. ``moments[3] = [1.0, 3.0, 2.0] must be
    ascending``: the whole batch is checked at once, and only the report looks at one entry.

    Parameters
    ----------
    field : str
        Name of the argument.
    values : ndarray, shape (...) + trailing
        The checked values; ``values[index]`` is quoted.
    bad : array_like of bool, shape (...)
        Where the rule is broken (the leading axes of ``values``).
    rule : str
        What is allowed, e.g. ``"must be positive (kg m^2)"``.

    Examples
    --------
    >>> from tumble.validation import refuse_first
    >>> refuse_first("moments", [[1, 2, 3], [1, 3, 2]], [False, True], "must be ascending")
    Traceback (most recent call last):
    ...
    ValueError: moments[1] = [1, 3, 2] must be ascending
    """
    mask: BoolArray = np.asarray(bad, bool)
    if not np.any(mask):
        return
    index = tuple(int(i) for i in np.argwhere(mask)[0])
    where = f"[{', '.join(map(str, index))}]" if index else ""
    raise ValueError(f"{field}{where} = {np.asarray(values)[index].tolist()!r} {rule}")


def check_vectors(field: str, value: ArrayLike, unit: str, *, size: int | None = 3) -> FloatArray:
    """Finite real numbers of shape ``(..., size)`` (any shape with ``size=None``), as floats.

    The checker of batched numeric arguments (points, angular velocities, moments, rates):
    integers and floats, in nested lists or arrays, are accepted; booleans, complex numbers,
    strings, dicts, sets, generators and ragged lists are refused, as are NaN and infinities.

    Parameters
    ----------
    field : str
        Name of the argument, for the message.
    value : array_like, shape (..., size)
        The input.
    unit : str
        Its unit, for the message (e.g. ``"m"``).
    size : int or None
        Length of the last axis; None for any shape, scalars included.

    Returns
    -------
    ndarray of float, shape of ``value``

    Raises
    ------
    ValueError
        Naming ``field``, the value (or the first non-finite entry, by index) and what is
        allowed, e.g. ``point = [nan, 0.0, 0.0] must be finite numbers (m)``.

    Examples
    --------
    >>> from tumble.validation import check_vectors
    >>> check_vectors("omega", [[0, 0, 1], [1, 2, 3]], "rad/s").shape
    (2, 3)
    >>> check_vectors("point", [0.0, float("nan"), 0.0], "m")
    Traceback (most recent call last):
    ...
    ValueError: point = [0.0, nan, 0.0] must be finite numbers (m)
    """
    shape = "real numbers" if size is None else f"real numbers of shape (..., {size})"
    try:
        a = np.asarray(value)
    except (TypeError, ValueError):  # ragged nested sequences
        a = np.empty((), dtype=object)
    if a.dtype.kind not in "iuf":
        raise ValueError(f"{field} = {short_repr(value)} must be {shape} ({unit})")
    if size is not None and (a.ndim == 0 or a.shape[-1] != size):
        raise ValueError(f"{field} = {short_repr(value)} must be {shape} ({unit}), not shape {a.shape}")
    a = a.astype(float)
    finite = np.isfinite(a) if size is None else np.all(np.isfinite(a), axis=-1)
    refuse_first(field, a, ~finite, f"must be {'a finite number' if size is None else 'finite numbers'} ({unit})")
    return a


#: Largest rate accepted, rad/s (spins) or 1/s (relaxation): above any rotation of matter
#: (optically levitated nanorotors reach ~6e9 rad/s, molecules ~1e13 rad/s), and far enough
#: below the float range (1.8e308) that energies, momenta and phases of a run stay finite.
MAX_RATE = 1e15
#: Largest moment of inertia accepted, kg m^2: above any star's (the Sun's is ~6e46 kg m^2);
#: with :data:`MAX_RATE` a kinetic energy stays below 1e80 J.
MAX_INERTIA = 1e50

#: Why a bound holds, for the messages that refuse a value beyond it.
BOUND_REASONS = {MAX_RATE: "faster than any rotation of matter", MAX_INERTIA: "more than any star's"}


def check_bool(field: str, value: object) -> bool:
    """``value`` if it is a boolean (``true``/``false`` in TOML), else one ValueError naming ``field``.

    A string such as ``"no"`` is refused rather than read as true.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.validation import check_bool
    >>> check_bool("gravity_gradient", True), check_bool("gravity_gradient", np.bool_(False))
    (True, False)
    >>> check_bool("gravity_gradient", "no")
    Traceback (most recent call last):
    ...
    ValueError: gravity_gradient = 'no' must be true or false
    """
    if not isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{field} = {short_repr(value)} must be true or false")  # noqa: TRY004 - one error type for bad input
    return bool(value)


def check_number(field: str, value: object, unit: str, at_most: float | None = None) -> float:
    """A real finite number (no boolean, complex number or string), at most ``at_most`` in
    magnitude if given, as a float.

    Examples
    --------
    >>> from tumble.validation import check_number
    >>> check_number("mass", 2, "kg")
    2.0
    >>> check_number("mass", True, "kg")
    Traceback (most recent call last):
    ...
    ValueError: mass = True must be a number (kg)
    """
    if isinstance(value, bool) or not isinstance(value, (Real, np.floating, np.integer)):
        raise ValueError(f"{field} = {value!r} must be a number" + (f" ({unit})" if unit else ""))
    try:
        x = float(value)
    except OverflowError:  # a Python int beyond any float, e.g. 10**400
        x = math.inf
    if not math.isfinite(x):
        raise ValueError(f"{field} = {value!r} must be a finite number" + (f" ({unit})" if unit else ""))
    # a Python float shown as given (the command line's keep their text), numpy's as the plain float
    check_at_most(field, value if isinstance(value, float) and not isinstance(value, np.floating) else x, unit, at_most)
    return x


def check_at_most(field: str, value: float, unit: str, at_most: float | None) -> None:
    """Refuse ``|value| > at_most`` (nothing when ``at_most`` is None), saying why the bound
    holds for :data:`MAX_RATE` and :data:`MAX_INERTIA`.

    Examples
    --------
    >>> from tumble.validation import MAX_RATE, check_at_most
    >>> check_at_most("omega", 1e3, "rad/s", MAX_RATE)  # within the bound: nothing
    >>> check_at_most("omega", 1e16, "rad/s", MAX_RATE)
    Traceback (most recent call last):
    ...
    ValueError: omega = 1e+16 is beyond 1e+15 rad/s: faster than any rotation of matter
    """
    if at_most is not None and not abs(value) <= at_most:
        why = f": {BOUND_REASONS[at_most]}" if at_most in BOUND_REASONS else ""
        raise ValueError(f"{field} = {value!r} is beyond {at_most:g} {unit}{why}")


def check_noise(field: str, value: object, unit: str, at_most: float, what: str, hint: str) -> float:
    """A noise ``>= 0``, refused past ``at_most`` (no sensor of ``what``) with ``hint`` (a unit slip).

    Examples
    --------
    >>> from tumble.validation import check_noise
    >>> check_noise("noise", 2e-3, "rad", 0.1, "a sun sensor", "is it in deg?")
    0.002
    >>> check_noise("noise", 10.0, "rad", 0.1, "a sun sensor", "is it in arcsec?")
    Traceback (most recent call last):
    ...
    ValueError: noise = 10.0 rad is more than a sun sensor spreads; allowed: 0 to 0.1 rad: is it in arcsec?
    """
    x = check_positive(field, value, unit, allow_zero=True)
    if x > at_most:
        raise ValueError(f"{field} = {value!r} {unit} is more than {what} spreads; allowed: 0 to {at_most:g} {unit}: {hint}")
    return x


def check_increasing(field: str, t: FloatArray, unit: str = "s") -> None:
    """Refuse samples that do not increase strictly, naming the first pair out of order.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.validation import check_increasing
    >>> check_increasing("times", np.array([0.0, 1.0, 0.5]))
    Traceback (most recent call last):
    ...
    ValueError: times must increase strictly; times[2] = 0.5 follows 1.0 (s)
    """
    bad = np.flatnonzero(~(np.diff(t) > 0))
    if bad.size:
        k = int(bad[0]) + 1
        raise ValueError(f"{field} must increase strictly; {field}[{k}] = {float(t[k])!r} follows "
                         f"{float(t[k - 1])!r} ({unit})")


def check_moments(field: str, value: ArrayLike) -> Vector3:
    """Principal moments ``(..., 3)``, kg m^2, as floats: real and finite (no booleans, complex
    numbers or strings), positive and ascending ``I1 <= I2 <= I3``, within the triangle
    inequality ``I1 + I2 >= I3`` (to :data:`INERTIA_RTOL` of the trace; Goldstein sec. 5.4: no
    distribution of positive mass breaks it) and at most :data:`MAX_INERTIA`. Every function of
    moments takes only those of a body that can exist, formulas that would hold for any positive
    ascending triple included (the stability, period and gravity-gradient functions; issue 27).

    Raises ``ValueError`` naming the first bad entry by index, e.g.
    ``moments[2] = [0.1, 0.2, 1.0] breaks the triangle inequality I1 + I2 >= I3 ...``.

    Examples
    --------
    >>> from tumble.validation import check_moments
    >>> check_moments("moments", [1, 2, 3]).tolist()
    [1.0, 2.0, 3.0]
    >>> check_moments("moments", [[1, 2, 3], [2, 1, 3]])
    Traceback (most recent call last):
    ...
    ValueError: moments[1] = [2.0, 1.0, 3.0] must be ascending, I1 <= I2 <= I3 (kg m^2)
    """
    if type(value) is np.ndarray and value.shape == (3,) and value.dtype == np.float64:  # one body's, plain floats
        a, b, c = value.tolist()  # the checks below in float arithmetic (a NaN fails them): ~8 us, not ~25
        if 0.0 < a <= b <= c <= MAX_INERTIA and not breaks_triangle(value):
            return value.copy()
    refuse_body(field, value)
    I = check_vectors(field, value, "kg m^2")
    refuse_first(field, I, ~np.all(I > 0, axis=-1), "must be positive (kg m^2)")
    refuse_first(field, I, np.any(np.diff(I, axis=-1) < 0, axis=-1), "must be ascending, I1 <= I2 <= I3 (kg m^2)")
    refuse_first(field, I, breaks_triangle(I),
                 "breaks the triangle inequality I1 + I2 >= I3 (kg m^2): no distribution of positive mass has them")
    refuse_first(field, I, np.any(I > MAX_INERTIA, axis=-1), f"is beyond {MAX_INERTIA:g} kg m^2: {BOUND_REASONS[MAX_INERTIA]}")
    return I


def triangle_excess(moments: ArrayLike) -> FloatArray:
    """How far principal moments ``(..., 3)``, in any order, exceed the triangle inequality: the
    largest minus the sum of the other two, ``2 max(I) - trace`` (kg m^2, or the moments' unit).

    The one writing of the triangle inequality ``I1 + I2 >= I3`` (Goldstein sec. 5.4: it follows
    from ``I_a + I_b - I_c = 2 integral rho r_c^2 dV >= 0``): zero for a planar body, negative
    inside, positive for moments no distribution of positive mass has. Every check of it calls
    this (:func:`breaks_triangle`, :func:`tumble.mass.check_inertia`, the fits' and the maps'
    triangles of ratios ``(I1/I3, I2/I3, 1)``).

    Examples
    --------
    >>> from tumble.validation import triangle_excess
    >>> triangle_excess([[1.0, 2.0, 3.0], [0.1, 1.0, 0.2], [3.0, 4.0, 5.0]]).tolist()   # planar, broken, inside
    [0.0, 0.7, -2.0]
    """
    I = np.asarray(moments, dtype=float)
    return cast(FloatArray, 2.0 * np.max(I, axis=-1) - np.sum(I, axis=-1))


def breaks_triangle(moments: ArrayLike) -> BoolArray:
    """Whether principal moments ``(..., 3)``, in any order, break the triangle inequality: the
    largest exceeds the sum of the other two (:func:`triangle_excess`) by more than
    :data:`INERTIA_RTOL` of the trace (Goldstein sec. 5.4: no distribution of positive mass has
    such moments).

    Examples
    --------
    >>> from tumble.validation import breaks_triangle
    >>> breaks_triangle([[1.0, 2.0, 3.0], [0.1, 1.0, 0.2], [1.0, 1.0, 2.0]]).tolist()   # the last is planar
    [False, True, False]
    """
    I = np.asarray(moments, dtype=float)
    return cast(BoolArray, triangle_excess(I) > INERTIA_RTOL * np.sum(I, axis=-1))


#: What an axis may be, as the error messages say it.
AXES_ALLOWED = "1, 2 or 3 (principal axes, ascending moments) or 'minor', 'intermediate' or 'major'"


def axis_index(field: str, value: object) -> IntArray:
    """0-based indices (0, 1, 2) of public axis labels: 1, 2, 3 or a name of :data:`AXIS_ROLES`,
    or arrays of them.

    Raises ``ValueError`` for anything else (0, -1, 4, 2.5, True, 'x', a dict ...), naming the
    first bad entry of an array.

    Examples
    --------
    >>> from tumble.validation import axis_index
    >>> axis_index("axis", 3).tolist(), axis_index("axis", ["minor", "major"]).tolist()
    (2, [0, 2])
    """
    try:
        a = np.asarray(value)
    except (TypeError, ValueError):  # ragged nested sequences
        a = np.empty((), dtype=object)
    if a.dtype.kind == "U":
        index = np.full(a.shape, -1)
        for k, name in enumerate(AXIS_ROLES):
            index[a == name] = k
    elif a.dtype.kind in "iu":
        index = np.where((a >= 1) & (a <= 3), a, 0).astype(np.intp) - 1  # uint-safe
    else:
        raise ValueError(f"{field} = {short_repr(value)} must be {AXES_ALLOWED}")
    refuse_first(field, a, index < 0, f"must be {AXES_ALLOWED}")
    return index


def check_positive(field: str, value: object, unit: str, *, allow_zero: bool = False, at_most: float | None = None) -> float:
    """A finite number > 0 (or >= 0 with ``allow_zero``), at most ``at_most`` if given.

    Examples
    --------
    >>> from tumble.validation import check_positive
    >>> check_positive("radius", 0.25, "m")
    0.25
    >>> check_positive("radius", -0.1, "m")
    Traceback (most recent call last):
    ...
    ValueError: radius = -0.1 must be a positive finite number (m)
    """
    if type(value) is float and 0.0 < value < math.inf and at_most is None:  # a plain float: ~0.1 us, not ~1
        return value
    x = check_number(field, value, unit, at_most)
    if x < 0 or (x == 0 and not allow_zero):
        allowed = "a non-negative" if allow_zero else "a positive"
        raise ValueError(f"{field} = {value!r} must be {allowed} finite number ({unit})")
    return x


def _three_floats(value: object) -> list[float] | None:
    """The three numbers of a float64 array of shape (3,) or of a list or tuple of three Python
    floats, else None (then the full checks decide)."""
    if type(value) is np.ndarray and value.shape == (3,) and value.dtype == np.float64:
        return cast("list[float]", value.tolist())
    if type(value) in (tuple, list):
        items = cast("list[object]", value)
        if len(items) == 3 and all(type(v) is float for v in items):
            return cast("list[float]", list(items))
    return None


def check_vector(field: str, value: object, unit: str, *, at_most: float | None = None) -> tuple[float, float, float]:
    """Three finite numbers, given as a list, a tuple (any sequence) or a numpy array of shape (3,),
    each at most ``at_most`` in magnitude if given.

    Anything else is refused, not converted: a dict or a set (whose keys or members have no
    meaningful order), a generator, a string, a nested list or an array of another shape.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.validation import check_vector
    >>> check_vector("offset", np.array([1, 2, 3]), "m")
    (1.0, 2.0, 3.0)
    >>> check_vector("offset", {1, 2, 3}, "m")
    Traceback (most recent call last):
    ...
    ValueError: offset = {1, 2, 3} must be a list of 3 numbers (m)
    """
    plain = _three_floats(value)
    if plain is not None:  # the plain case first, in float arithmetic; anything it does not pass gets the full checks
        x0, x1, x2 = plain
        top = math.inf if at_most is None else at_most
        if abs(x0) <= top and abs(x1) <= top and abs(x2) <= top and math.isfinite(x0 + x1 + x2):
            return x0, x1, x2
    if isinstance(value, np.ndarray):
        ok = value.shape == (3,)
    else:
        ok = isinstance(value, Sequence) and not isinstance(value, (str, bytes, bytearray)) and len(value) == 3
    if not ok:
        raise ValueError(f"{field} = {short_repr(value)} must be a list of 3 numbers ({unit})")
    items = cast("Sequence[object]", value)  # a sequence or an array of shape (3,), checked above
    return tuple(check_number(f"{field}[{i}]", v, unit, at_most) for i, v in enumerate(items))  # type: ignore[return-value]


def check_direction(field: str, value: object) -> tuple[float, float, float]:
    """A non-zero finite 3-vector, returned as a unit vector (a direction has no length).

    Examples
    --------
    >>> from tumble.validation import check_direction
    >>> check_direction("axis", [0, 3, 4])
    (0.0, 0.6, 0.8)
    """
    v = np.array(check_vector(field, value, "a direction, any length"))
    big = float(np.max(np.abs(v)))
    if big == 0.0:
        raise ValueError(f"{field} = {value!r} must be a non-zero vector (a direction)")
    v = v / big  # scale first, so that the norm of [1e308, 1e308, 0] does not overflow
    return tuple(float(x) for x in v / np.linalg.norm(v))  # type: ignore[return-value]


def refuse_body(field: str, value: object) -> None:
    """Refuse a body (a ``Body`` or ``MassProperties``: anything with ``principal_moments``) where
    principal moments are asked for, saying which of its attributes to give.

    Examples
    --------
    >>> import tumble
    >>> from tumble.validation import refuse_body
    >>> refuse_body("moments", tumble.t_handle())
    Traceback (most recent call last):
    ...
    ValueError: moments = Body('T-handle', 2 parts, m = 3 kg, I = (0.125, 0.3125, 0.4375) kg m^2) is a body: give its principal moments, body.principal_moments (kg m^2)
    """
    if is_body(value):
        raise ValueError(f"{field} = {short_repr(value)} is a body: give its principal moments, "
                         "body.principal_moments (kg m^2)")


def is_body(value: object) -> bool:
    """Whether ``value`` is a body (a ``Body`` or ``MassProperties``: it has ``principal_moments``),
    told without importing :mod:`tumble.mass`, which sits above this layer.

    Examples
    --------
    >>> import tumble
    >>> from tumble.validation import is_body
    >>> is_body(tumble.t_handle()), is_body(tumble.t_handle().properties), is_body([1.0, 2.0, 3.0])
    (True, True, False)
    """
    return hasattr(value, "principal_moments")
