"""The checks of orientations and rigid motions: a scipy Rotation, a quaternion or a matrix.

A quaternion is scalar last, ``[x, y, z, w]``, as in scipy; a matrix must be orthonormal with
determinant +1 (a rotoreflection is refused, and said to be one). Re-exported by
:mod:`tumble.validation`.
"""

from __future__ import annotations

import functools
import math
import warnings
from typing import TYPE_CHECKING

import numpy as np

from ..typing import Vector3
from .values import check_vector

if TYPE_CHECKING:
    from scipy.spatial.transform import Rotation

__all__ = [
    "MATRIX_ORTHO_TOL",
    "QUAT_NORM_TOL",
    "ScalarFirstWarning",
    "check_motion",
    "check_rotation",
]


class ScalarFirstWarning(UserWarning):
    """A quaternion written ``[1, 0, 0, 0]`` (or its opposite): in tumble's scalar-last order
    ``[x, y, z, w]`` (scipy's) a half turn about x, though most likely the identity written scalar
    first (``[w, x, y, z]``, as Basilisk and many texts write it). A command prints it on one line.

    Examples
    --------
    >>> import warnings
    >>> from tumble.validation import check_rotation
    >>> from tumble.validation.rotations import ScalarFirstWarning
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     check_rotation("attitude", [1.0, 0.0, 0.0, 0.0])
    (1.0, 0.0, 0.0, 0.0)
    >>> caught[0].category is ScalarFirstWarning
    True
    """

    cli_one_line = True


def _scalar_first(field: str, x: float, y: float, z: float, w: float) -> None:
    """Warn (:class:`ScalarFirstWarning`) of ``[+-1, 0, 0, 0]``: a control file's ``target = [1.0,
    0.0, 0.0, 0.0]`` was read, without a word, as a half turn about x (a walkthrough)."""
    if abs(x) == 1.0 and y == 0.0 and z == 0.0 and w == 0.0:
        warnings.warn(f"{field} = [{x:g}, 0, 0, 0] is a half turn about x in tumble's scalar-last order [x, y, z, w] "
                      f"(scipy's); the identity is [0, 0, 0, 1]: written scalar first?", ScalarFirstWarning, stacklevel=3)


#: A quaternion given by hand, e.g. [0, 0, 0.7071, 0.7071], is accepted and renormalised if its
#: norm is within this of 1; anything further off is almost surely a mistake and is refused.
QUAT_NORM_TOL = 1e-3
#: A matrix given by hand must be orthonormal to this tolerance (|R^T R - E|).
MATRIX_ORTHO_TOL = 1e-6


@functools.lru_cache(maxsize=256)
def _unit_quaternion(raw: bytes) -> tuple[float, float, float, float]:
    """scipy's unit quaternion (its normalisation, its sign) for the float64 bytes of a quaternion,
    kept for the next call with the same one (``Rotation.from_quat`` costs ~10 us)."""
    from scipy.spatial.transform import Rotation

    return tuple(float(x) for x in Rotation.from_quat(np.frombuffer(raw)).as_quat())  # type: ignore[return-value]


def check_rotation(field: str, value: object) -> tuple[float, float, float, float]:
    """An orientation: a scipy Rotation, a quaternion [x, y, z, w] or a 3x3 rotation matrix.

    Returns the unit quaternion, scalar last (scipy's convention).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.validation import check_rotation
    >>> check_rotation("orientation", np.eye(3))
    (0.0, 0.0, 0.0, 1.0)
    >>> check_rotation("orientation", np.diag([1.0, 1.0, -1.0]))
    Traceback (most recent call last):
    ...
    ValueError: orientation has determinant -1, which should be +1; it is a rotoreflection (it mirrors the part), not a rotation
    """
    from scipy.spatial.transform import Rotation

    if isinstance(value, Rotation):
        if not value.single:
            raise ValueError(f"{field} must be a single rotation, got a stack of {len(value)}")
        return tuple(float(x) for x in value.as_quat())  # type: ignore[return-value]
    if type(value) is np.ndarray and value.shape == (4,) and value.dtype == np.float64:
        # the plain case first: a quaternion near unit norm, in float arithmetic
        x, y, z, w = value.tolist()
        if abs(math.sqrt(x * x + y * y + z * z + w * w) - 1.0) <= QUAT_NORM_TOL:
            _scalar_first(field, x, y, z, w)
            return _unit_quaternion(value.tobytes())
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(
            f"{field} = {value!r} must be a quaternion [x, y, z, w] or a 3x3 rotation matrix"
        ) from None
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{field} = {value!r} must contain only finite numbers")
    if arr.shape == (4,):
        n = float(np.linalg.norm(arr))
        if abs(n - 1.0) > QUAT_NORM_TOL:
            raise ValueError(
                f"{field} = {value!r} is a quaternion of norm {n:.6g}; a rotation needs a unit "
                f"quaternion [x, y, z, w] (scalar last)"
            )
        _scalar_first(field, *arr.tolist())
        return _unit_quaternion(arr.tobytes())
    if arr.shape == (3, 3):
        err = float(np.max(np.abs(arr.T @ arr - np.eye(3))))
        if err > MATRIX_ORTHO_TOL:
            raise ValueError(
                f"{field} is not an orthonormal matrix (max |R^T R - E| = {err:.3g}); "
                f"a rotation matrix has orthonormal columns"
            )
        det = float(np.linalg.det(arr))
        if det < 0:
            raise ValueError(
                f"{field} has determinant {det:.6g}, which should be +1; it is a rotoreflection "
                f"(it mirrors the part), not a rotation"
            )
        return tuple(float(x) for x in Rotation.from_matrix(arr).as_quat())  # type: ignore[return-value]
    raise ValueError(
        f"{field} must be a quaternion [x, y, z, w] or a 3x3 rotation matrix, got shape {arr.shape}"
    )


def check_motion(rotation: object, translation: object) -> tuple[Rotation, Vector3]:
    """A rigid motion ``x -> R x + t``: ``(scipy Rotation, ndarray (3,))`` from anything
    :func:`check_rotation` and :func:`check_vector` accept.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.validation import check_motion
    >>> R, t = check_motion([0, 0, np.sin(np.pi / 4), np.cos(np.pi / 4)], [1, 0, 0])
    >>> np.round(R.apply([1.0, 0.0, 0.0]) + t, 12).tolist()  # x -> R x + t: a quarter turn about z
    [1.0, 1.0, 0.0]
    """
    from scipy.spatial.transform import Rotation

    R = Rotation.from_quat(check_rotation("rotation", rotation))
    return R, np.array(check_vector("translation", translation, "m"))
