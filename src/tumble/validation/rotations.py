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

from ..typing import ArrayLike, FloatArray, Vector3
from .messages import short_repr
from .values import check_vector, check_vectors

if TYPE_CHECKING:
    from scipy.spatial.transform import Rotation

__all__ = [
    "MATRIX_ORTHO_TOL",
    "QUAT_NORM_TOL",
    "ScalarFirstWarning",
    "check_covariance",
    "check_motion",
    "check_quaternions",
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


def check_quaternions(field: str, value: ArrayLike) -> FloatArray:
    """Quaternions, scalar last, of shape ``(..., 4)``, normalised: finite, none of them zero; a
    ``[+-1, 0, 0, 0]`` among them warned of (:class:`~tumble.validation.rotations.ScalarFirstWarning`,
    as :func:`~tumble.validation.check_rotation` does for one). The batched form, for the filters' states and measurements.

    Examples
    --------
    >>> from tumble.validation import check_quaternions
    >>> check_quaternions("attitude", [[0.0, 0.0, 0.0, 2.0], [0.0, 0.0, 1.0, 1.0]]).round(4).tolist()
    [[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.7071, 0.7071]]
    >>> check_quaternions("attitude", [0.0, 0.0, 0.0, 0.0])
    Traceback (most recent call last):
    ...
    ValueError: attitude = [0.0, 0.0, 0.0, 0.0] must be a rotation's quaternion [x, y, z, w], scalar last: not zero
    """
    q = check_vectors(field, value, "scalar last", size=4)
    norm = np.linalg.norm(q, axis=-1, keepdims=True)
    if np.any(norm == 0.0):
        at = np.argwhere(norm[..., 0] == 0.0)[0] if q.ndim > 1 else ()
        where = f"{field}[{', '.join(str(int(i)) for i in at)}]" if q.ndim > 1 else field
        raise ValueError(f"{where} = {short_repr(q[tuple(at)].tolist())} must be a rotation's quaternion [x, y, z, w], scalar last: "
                         "not zero")
    first = np.all(q[..., 1:] == 0.0, axis=-1) & (np.abs(q[..., 0]) == 1.0)
    if np.any(first):
        _scalar_first(field, *q[tuple(np.argwhere(first)[0])] if q.ndim > 1 else q)
    return np.asarray(q / norm, float)


def check_covariance(field: str, value: ArrayLike, size: int, unit: str) -> FloatArray:
    """Covariances of shape ``(..., size, size)``: finite, symmetric (to 1e-9 of the largest entry)
    and positive semidefinite (no eigenvalue below -1e-12 of the largest entry: a zero variance is
    a quantity known exactly), as floats.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.validation import check_covariance
    >>> check_covariance("covariance", np.eye(3) * 1e-6, 3, "rad^2").shape
    (3, 3)
    >>> check_covariance("covariance", -np.eye(3) * 1e-6, 3, "rad^2")
    Traceback (most recent call last):
    ...
    ValueError: covariance = [[-1e-06, -0.0, -0.0], [-0.0, -1e-06, -0.0], [-0.0, -0.0, -1e-06]] must be a symmetric positive-semidefinite 3 x 3 matrix (rad^2): a negative eigenvalue (a variance is the square of a standard deviation)
    """
    try:
        R = np.asarray(value, float)
    except (TypeError, ValueError):
        R = np.full((1,), np.nan)
    allowed = f"must be a symmetric positive-semidefinite {size} x {size} matrix ({unit})"
    if R.shape[-2:] != (size, size) or not np.all(np.isfinite(R)):
        raise ValueError(f"{field} = {short_repr(value)} {allowed}: finite numbers of shape (..., {size}, {size})")
    scale = np.max(np.abs(R), axis=(-2, -1), keepdims=True)
    bad = ~np.all(np.abs(R - np.swapaxes(R, -1, -2)) <= 1e-9 * scale, axis=(-2, -1))
    why = "not symmetric"
    if not np.any(bad):
        try:
            np.linalg.cholesky(R)
        except np.linalg.LinAlgError:  # singular (a state known exactly: a zero variance) or not positive
            lowest = np.linalg.eigvalsh(R)[..., 0]
            bad = lowest < -1e-12 * scale[..., 0, 0]
            why = "a negative eigenvalue (a variance is the square of a standard deviation)"
    if np.any(bad):
        at = tuple(int(i) for i in np.argwhere(np.atleast_1d(bad))[0]) if R.ndim > 2 else ()
        where = f"{field}[{', '.join(map(str, at))}]" if R.ndim > 2 else field
        raise ValueError(f"{where} = {short_repr(R[at].tolist())} {allowed}: {why}")
    return R
