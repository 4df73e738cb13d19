"""Operations on inertia tensors: rotate, shift, validate, decompose.

Pure functions over numpy arrays. Every function broadcasts over leading batch axes, so the
same code serves one tensor of shape ``(3, 3)`` or a stack of shape ``(..., 3, 3)``.

Units are SI throughout: masses in kg, lengths in m, inertia tensors in kg m^2.

References
----------
- Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed. (2002), sections 5.3-5.4: the
  inertia tensor, its transformation under rotation, principal axes.
- Seed study, eq. (4) (docs/seed-study.md): the parallel-axis theorem in tensor form.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, SupportsFloat, SupportsInt, cast

import numpy as np

from ..typing import ArrayLike, BoolArray, FloatArray, Matrix3, Vector3
from ..validation import AXIS_ROLES, INERTIA_RTOL, check_vectors, refuse_first, triangle_excess

if TYPE_CHECKING:
    from scipy.spatial.transform import Rotation

__all__ = [
    "AXIS_ROLES",
    "INERTIA_RTOL",
    "check_inertia",
    "check_vectors",
    "inertia_about_point",
    "moment_degeneracy",
    "parallel_axis",
    "point_mass_inertia",
    "principal_frame",
    "refuse_first",
    "rotate_inertia",
]

def _as_tensor(inertia: ArrayLike) -> Matrix3:
    I = np.asarray(inertia, dtype=float)
    if I.shape[-2:] != (3, 3):
        raise ValueError(f"inertia tensor must have shape (..., 3, 3), got {I.shape}")
    return I


def point_mass_inertia(mass: ArrayLike, offset: ArrayLike) -> Matrix3:
    """Inertia tensor of point masses about the origin: ``m (|d|^2 E - d d^T)``.

    This is the parallel-axis term of the seed's eq. (4) (Goldstein sec. 5.3, for one point).

    Parameters
    ----------
    mass : array_like, shape (...)
        Masses in kg.
    offset : array_like, shape (..., 3)
        Positions of the masses relative to the reference point, in m.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        Inertia tensor in kg m^2.

    Examples
    --------
    >>> from tumble.mass.tensor import point_mass_inertia
    >>> point_mass_inertia(2.0, (0.0, 0.0, 1.0)).tolist()   # m (|d|^2 E - d d^T)
    [[2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 0.0]]
    >>> point_mass_inertia([1.0, 1.0], [(1, 0, 0), (0, 1, 0)]).shape
    (2, 3, 3)
    """
    d = np.asarray(offset, dtype=float)
    m = np.asarray(mass, dtype=float)[..., None, None]
    dd: FloatArray = np.einsum("...i,...i->...", d, d)[..., None, None]
    return cast(Matrix3, m * (dd * np.eye(3) - d[..., :, None] * d[..., None, :]))


def parallel_axis(inertia_com: ArrayLike, mass: ArrayLike, offset: ArrayLike) -> Matrix3:
    """Shift an inertia tensor from the centre of mass to another point.

    ``I_P = I_com + m (|d|^2 E - d d^T)`` with ``d`` the position of the COM relative to P
    (seed eq. 4; Goldstein sec. 5.3). The shift is only valid *from* the COM; to move between
    two arbitrary points go through the COM (see :func:`inertia_about_point`).

    Parameters
    ----------
    inertia_com : array_like, shape (..., 3, 3)
        Tensor about the centre of mass, kg m^2.
    mass : array_like, shape (...)
        Mass, kg.
    offset : array_like, shape (..., 3)
        Position of the centre of mass relative to the new reference point, m.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        Tensor about the new point, kg m^2.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.mass.tensor import parallel_axis
    >>> parallel_axis(np.diag([1.0, 1.0, 1.0]), 2.0, (3.0, 0.0, 0.0)).tolist()   # + m d^2 = 18 across x
    [[1.0, 0.0, 0.0], [0.0, 19.0, 0.0], [0.0, 0.0, 19.0]]
    """
    return _as_tensor(inertia_com) + point_mass_inertia(mass, offset)


def inertia_about_point(inertia_com: ArrayLike, mass: ArrayLike, com: ArrayLike, point: ArrayLike) -> Matrix3:
    """Inertia tensor about an arbitrary ``point`` given the tensor about the COM.

    Parameters
    ----------
    inertia_com : array_like, shape (..., 3, 3)
        Tensor about the centre of mass, kg m^2.
    mass : array_like, shape (...)
        Mass, kg.
    com, point : array_like, shape (..., 3)
        Centre of mass and the new reference point, same frame, m; finite real numbers.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        Tensor about ``point``, kg m^2.

    Raises
    ------
    ValueError
        If ``com`` or ``point`` is not an array of finite numbers of shape (..., 3), naming the
        argument and, for a batch, the first bad index (see :func:`check_vectors`).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.mass.tensor import inertia_about_point
    >>> inertia_about_point(np.zeros((3, 3)), 1.0, com=(1, 0, 0), point=(0, 0, 0)).tolist()
    [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    """
    d = check_vectors("com", com, "m") - check_vectors("point", point, "m")
    return parallel_axis(inertia_com, mass, d)


def rotate_inertia(inertia: ArrayLike, rotation: Rotation | ArrayLike) -> Matrix3:
    """Express a tensor given in frame A in frame B: ``I_B = R I_A R^T``.

    ``R`` maps A-coordinates to B-coordinates (``x_B = R @ x_A``), Goldstein sec. 5.3.

    Parameters
    ----------
    inertia : array_like, shape (..., 3, 3)
        Tensor in frame A, kg m^2.
    rotation : array_like, shape (..., 3, 3) or scipy.spatial.transform.Rotation
        Rotation matrix from A to B.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.mass.tensor import rotate_inertia
    >>> R = Rotation.from_euler("z", 90, degrees=True)   # x of frame A is y of frame B
    >>> rotate_inertia(np.diag([1.0, 2.0, 3.0]), R).round(6).diagonal().tolist()
    [2.0, 1.0, 3.0]
    """
    R: Matrix3 = rotation.as_matrix() if hasattr(rotation, "as_matrix") else np.asarray(rotation, float)
    I = _as_tensor(inertia)
    return R @ I @ np.swapaxes(R, -1, -2)


def _scale(I: Matrix3) -> FloatArray:
    """A non-negative size of each tensor (its trace, or its largest entry if trace <= 0)."""
    tr: FloatArray = np.abs(np.trace(I, axis1=-2, axis2=-1))
    big = np.max(np.abs(I), axis=(-2, -1))
    return cast(FloatArray, np.maximum(tr, big))


def check_inertia(inertia: ArrayLike, *, rtol: float = INERTIA_RTOL, what: str = "inertia tensor") -> Matrix3:
    """Check that a tensor can be the inertia tensor of a real body and return it as an array.

    The conditions (Goldstein sec. 5.4; the triangle inequality follows from
    ``I_a + I_b - I_c = 2 * integral rho r_c^2 dV >= 0`` in the principal frame):

    1. finite and symmetric, ``|I - I^T| <= rtol * trace``;
    2. positive semidefinite: every principal moment ``>= -rtol * trace``;
    3. triangle inequality on the principal moments: ``I1 + I2 >= I3 - rtol * trace``.

    Parameters
    ----------
    inertia : array_like, shape (..., 3, 3)
        Tensor in kg m^2 (any frame; any reference point).
    rtol : float
        Relative tolerance, see :data:`INERTIA_RTOL`.
    what : str
        Name used in error messages.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        The tensor, symmetrised ``(I + I^T) / 2``.

    Raises
    ------
    ValueError
        Naming the broken condition, the offending values and, for a batch, the index.

    Examples
    --------
    >>> from tumble.mass.tensor import check_inertia
    >>> check_inertia([[1, 0, 0], [0, 1, 0], [0, 0, 1.5]]).diagonal().tolist()
    [1.0, 1.0, 1.5]
    >>> check_inertia([[1, 0, 0], [0, 1, 0], [0, 0, 3]])   # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: ...triangle inequality...
    """
    I = _as_tensor(inertia)
    batch = I.shape[:-2]

    def where(idx: Iterable[SupportsInt]) -> str:
        return f" (at index {tuple(int(i) for i in idx)})" if batch else ""

    bad = ~np.all(np.isfinite(I), axis=(-2, -1))
    if np.any(bad):
        idx = np.argwhere(bad)[0] if batch else ()
        raise ValueError(f"{what}{where(idx)} has non-finite entries: {I[tuple(idx)].tolist()}")

    scale = _scale(I)
    tol = rtol * scale
    asym = np.max(np.abs(I - np.swapaxes(I, -1, -2)), axis=(-2, -1))
    bad = asym > tol
    if np.any(bad):
        idx = np.argwhere(bad)[0] if batch else ()
        raise ValueError(
            f"{what}{where(idx)} is not symmetric (largest |I_ij - I_ji| = {asym[tuple(idx)]:.6g} "
            f"kg m^2); an inertia tensor is symmetric by definition"
        )
    I = 0.5 * (I + np.swapaxes(I, -1, -2))
    moments = np.linalg.eigvalsh(I)

    bad = moments[..., 0] < -tol
    if np.any(bad):
        idx = tuple(np.argwhere(bad)[0]) if batch else ()
        raise ValueError(
            f"{what}{where(idx)} has a negative principal moment: moments "
            f"{_fmt(moments[idx])} kg m^2; a moment of inertia is an integral of "
            f"mass x distance^2 and cannot be negative"
        )
    excess = triangle_excess(moments)
    bad = excess > tol
    if np.any(bad):
        idx = tuple(np.argwhere(bad)[0]) if batch else ()
        m = moments[idx]
        raise ValueError(
            f"{what}{where(idx)}: principal moments {_fmt(m)} kg m^2 violate the triangle "
            f"inequality I1 + I2 >= I3 ({m[0]:.6g} + {m[1]:.6g} < {m[2]:.6g}); no distribution "
            f"of positive mass has them"
        )
    return I


def _fmt(values: ArrayLike) -> str:
    return "(" + ", ".join(f"{v:.6g}" for v in np.asarray(values).ravel()) + ")"


def moment_degeneracy(moments: Iterable[SupportsFloat], *, rtol: float = INERTIA_RTOL) -> str:
    """``"asymmetric"``, ``"symmetric"`` (two equal moments) or ``"spherical"`` (three).

    Ascending moments count as equal when they differ by at most ``rtol * (I1 + I2 + I3)``, the
    rule :func:`principal_frame` uses. Only an asymmetric body has an intermediate axis.

    Examples
    --------
    >>> from tumble.mass.tensor import moment_degeneracy
    >>> moment_degeneracy([1.0, 2.0, 3.0]), moment_degeneracy([1.0, 1.0, 2.0]), moment_degeneracy([1.0, 1.0, 1.0])
    ('asymmetric', 'symmetric', 'spherical')
    """
    I1, I2, I3 = (float(x) for x in moments)
    tol = rtol * max(I1 + I2 + I3, 0.0)
    return ("asymmetric", "symmetric", "spherical")[int(I2 - I1 <= tol) + int(I3 - I2 <= tol)]


def principal_frame(inertia: ArrayLike, *, rtol: float = INERTIA_RTOL) -> tuple[Vector3, Matrix3]:
    """Principal moments and axes, with tumble's deterministic conventions.

    Conventions (docs/conventions.md):

    - moments ascending, ``I1 <= I2 <= I3``;
    - axes are the *columns* of a proper rotation matrix ``A`` (``det A = +1``) that maps
      principal coordinates to the input frame: ``inertia = A @ diag(I) @ A.T``;
    - sign: the component of largest magnitude of axes 1 and 2 is positive (the first such
      component on a tie); axis 3 is ``e1 x e2`` so the frame is right-handed;
    - degenerate moments (equal within ``rtol * trace``) are returned *exactly* equal, as their
      mean, so that a body declared symmetric or spherical is exactly so downstream (the free
      motion classifies its case by exact comparisons); the axes of the degenerate subspace are
      the input frame's x, y, z axes projected onto it and orthonormalised in that order, so a
      symmetric top along z gets axes x, y and a sphere gets the identity. The tensor is then
      rebuilt to within the gap that was declared degenerate, as any choice of axes in a
      nearly degenerate subspace would have it.

    Parameters
    ----------
    inertia : array_like, shape (..., 3, 3)
        Symmetric tensor, kg m^2.
    rtol : float
        Relative tolerance under which two moments count as equal.

    Returns
    -------
    moments : ndarray, shape (..., 3)
        Principal moments ascending, kg m^2; degenerate ones exactly equal.
    axes : ndarray, shape (..., 3, 3)
        Rotation matrices whose columns are the principal axes, in the input frame.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.mass.tensor import principal_frame
    >>> I = np.array([[2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.0, 5.0]])
    >>> moments, axes = principal_frame(I)
    >>> moments.round(6).tolist()
    [1.0, 3.0, 5.0]
    >>> bool(np.allclose(axes @ np.diag(moments) @ axes.T, I)), round(float(np.linalg.det(axes)), 6)
    (True, 1.0)
    """
    I = _as_tensor(inertia)
    I = 0.5 * (I + np.swapaxes(I, -1, -2))
    moments, vecs = np.linalg.eigh(I)  # ascending eigenvalues

    tol = (rtol * _scale(I))[..., None]
    gaps = np.diff(moments, axis=-1) <= tol  # (..., 2): 1~2 and 2~3 degenerate
    moments = _equalise(moments, gaps)
    flat_vecs = vecs.reshape(-1, 3, 3).copy()
    flat_gaps = gaps.reshape(-1, 2)
    for k in np.flatnonzero(flat_gaps.any(axis=-1)):
        flat_vecs[k] = _degenerate_axes(flat_vecs[k], flat_gaps[k])
    vecs = flat_vecs.reshape(vecs.shape)

    # Sign rule on axes 1 and 2: largest-magnitude component positive.
    for j in (0, 1):
        col = vecs[..., :, j]
        pivot = np.argmax(np.abs(col) > np.max(np.abs(col), axis=-1, keepdims=True) - 1e-12, axis=-1)
        sign = np.sign(np.take_along_axis(col, pivot[..., None], axis=-1))
        sign[sign == 0] = 1.0
        vecs[..., :, j] = col * sign
    vecs[..., :, 2] = np.cross(vecs[..., :, 0], vecs[..., :, 1])
    return moments, vecs


def _equalise(moments: Vector3, gaps: BoolArray) -> Vector3:
    """Ascending moments with each degenerate cluster replaced by its mean (stays ascending)."""
    out = moments.copy()
    pair = [(0, 1), (1, 2)]
    for g, (a, b) in enumerate(pair):
        only = gaps[..., g] & ~gaps[..., 1 - g]
        mean = 0.5 * (moments[..., a] + moments[..., b])
        out[..., a] = np.where(only, mean, out[..., a])
        out[..., b] = np.where(only, mean, out[..., b])
    three = gaps[..., 0] & gaps[..., 1]  # a chain 1~2~3: the sphere rule of _degenerate_axes
    out = np.where(three[..., None], np.mean(moments, axis=-1, keepdims=True), out)
    return out


def _degenerate_axes(vecs: Matrix3, gaps: BoolArray) -> Matrix3:
    """Replace the eigenvectors of a degenerate cluster by projected frame axes."""
    out = vecs.copy()
    if gaps.all():  # three equal moments: any frame is principal; take the input frame
        return np.eye(3)
    cluster = [0, 1] if gaps[0] else [1, 2]
    normal = vecs[:, 2 if gaps[0] else 0]  # the plane's normal: the moment that is not degenerate
    chosen: list[Vector3] = []
    for e in np.eye(3):
        v = e - (normal @ e) * normal  # e projected onto the degenerate plane
        for c in chosen:
            v = v - (c @ v) * c
        n = np.linalg.norm(v)
        if n > 1e-6:
            # The second axis is normal x first, signed as e's residual: a residual of 1e-5 divided
            # by its norm would lose 11 digits of orthogonality (Gram-Schmidt's cancellation).
            w = np.cross(normal, chosen[0]) if chosen else v / n
            chosen.append(w * np.sign(w @ v) if chosen else w)
        if len(chosen) == 2:
            break
    out[:, cluster[0]], out[:, cluster[1]] = chosen
    return out
