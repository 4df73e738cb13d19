"""Attitude from vector observations at one instant: TRIAD and QUEST, with their covariances.

Both return the rotation ``A`` that maps body vectors to reference (world) vectors, ``r ~ A b``,
as a scipy ``Rotation`` (body to world, as everywhere in tumble), and the covariance of the
attitude error ``dtheta`` about the body axes, defined by ``A_true = A_est exp([dtheta x])``
(``A_true = A_est * Rotation.from_rotvec(dtheta)``), rad^2.

**Measurement model** (Shuster & Oh, "Three-axis attitude determination from vector
observations", *J. Guidance and Control* 4(1), 1981, 70-77; Shuster, "Maximum likelihood
estimation of spacecraft attitude", *J. Astronaut. Sci.* 37(1), 1989): a measured unit vector is
``b_i = A^T r_i + v_i`` with ``v_i`` perpendicular to ``A^T r_i`` and covariance
``sigma_i^2 (I - b_i b_i^T)``; ``sigma_i`` is the measurement's angular noise, rad.

**QUEST** (Shuster & Oh 1981) solves Wahba's problem ``min sum w_i |r_i - A b_i|^2``; here
through ``scipy.spatial.transform.Rotation.align_vectors``, which solves the same problem by the
SVD (Markley 1988, equivalent to Davenport's q method and to QUEST's optimum). With
``w_i = 1 / sigma_i^2`` its covariance about the body axes is
``P = [sum_i w_i (I - b_i b_i^T)]^{-1}`` (Shuster & Oh 1981, sec. IV; Markley & Crassidis,
*Fundamentals of Spacecraft Attitude Determination and Control*, Springer 2014, eq. 5.119).
The covariance is written by hand here: scipy's ``return_sensitivity`` gives the same matrix
about the reference axes and for weights divided by their mean.

**TRIAD** (Black 1964; Shuster & Oh 1981) takes ``b_1`` exactly and the plane of ``b_1, b_2``:
``t1 = b1``, ``t2 = b1 x b2 / |b1 x b2|``, ``t3 = t1 x t2`` in each frame and
``A = [t1r t2r t3r][t1b t2b t3b]^T``; its covariance (Shuster & Oh 1981, sec. III) is

``P = sigma_1^2 I + |b1 x b2|^{-2} [(sigma_2^2 - sigma_1^2) b1 b1^T + sigma_1^2 (b1 . b2)(b1 b2^T + b2 b1^T)]``.

TRIAD is written out because ``align_vectors`` has no batched form and its infinite-weight
("primary vector") path returns no covariance; the two agree to round-off (tests).

Examples
--------
The Sun and the field seen from a body turned 30 deg about z:

>>> import numpy as np
>>> from scipy.spatial.transform import Rotation
>>> from tumble.dynamics.estimation.static import quest, triad
>>> A = Rotation.from_euler("z", 30, degrees=True)
>>> r = np.array([[1.0, 0.0, 0.0], [0.0, 0.6, 0.8]])
>>> b = A.inv().apply(r)
>>> [round(float(e.magnitude()), 12) for e in (triad(b, r)[0] * A.inv(), quest(b, r, [1.0, 1.0])[0] * A.inv())]
[0.0, 0.0]
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, FloatArray
from ...validation import check_vectors, refuse_first

__all__ = ["quest", "triad"]


def _units(field: str, value: ArrayLike) -> FloatArray:
    v = check_vectors(field, value, "any length; taken as directions")
    n = np.linalg.norm(v, axis=-1)
    refuse_first(field, v, n == 0.0, "must not be zero: a direction is needed")
    return np.asarray(v / n[..., None], float)


def triad(body_vectors: ArrayLike, reference_vectors: ArrayLike, sigmas: ArrayLike = (1.0, 1.0)) -> tuple[Rotation, FloatArray]:
    """TRIAD: the attitude from two vector observations, and its covariance (module docstring).

    Parameters
    ----------
    body_vectors : array_like, shape (..., 2, 3)
        The two measured directions in the body frame (the first the more accurate; any
        length, normalised here).
    reference_vectors : array_like, shape (..., 2, 3)
        The same directions in the reference (world) frame.
    sigmas : array_like, shape (..., 2)
        The measurements' angular noise, rad (> 0, at most pi; default 1 rad, so that the
        covariance is per unit variance).

    Returns
    -------
    attitude : scipy Rotation
        Body to reference (one rotation, or a stack over the leading axes flattened).
    covariance : ndarray, shape (..., 3, 3)
        Of the attitude error about the body axes, rad^2.

    Raises
    ------
    ValueError
        For shapes other than (..., 2, 3), zero or non-finite vectors, parallel pairs or
        sigmas not in (0, pi] (QUEST's weights given as sigmas?), naming the argument and the first bad entry.

    Examples
    --------
    The first vector is kept exactly; an error in the second turns the body only about the first:

    >>> import numpy as np
    >>> from tumble.dynamics.estimation.static import triad
    >>> A, P = triad([[1.0, 0.0, 0.0], [0.0, 1.0, 0.01]], [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], sigmas=(1e-3, 1e-2))
    >>> np.round(A.as_rotvec(), 6).tolist()
    [-0.01, 0.0, 0.0]
    >>> np.round(np.sqrt(np.diag(P)), 6).tolist()   # about b1: sigma_2; across: sigma_1
    [0.01, 0.001, 0.001]
    """
    b = _units("body_vectors", body_vectors)
    r = _units("reference_vectors", reference_vectors)
    for name, v in (("body_vectors", b), ("reference_vectors", r)):
        if v.ndim < 2 or v.shape[-2] != 2:
            raise ValueError(f"{name} must have shape (..., 2, 3): two directions; got shape {v.shape}")
    s = np.asarray(sigmas, float)
    if s.shape[-1:] != (2,) or not np.all(np.isfinite(s) & (s > 0.0)):
        raise ValueError(f"sigmas = {s.tolist()!r} must be two positive finite numbers (rad) per pair")
    if np.any(s > math.pi):  # an angle's spread past pi says nothing of the direction
        raise ValueError(f"sigmas = {s.tolist()!r}: each at most pi rad (a direction's angular noise); QUEST's weights "
                         "1/sigma^2 given as TRIAD's sigmas?")

    def frame(v: FloatArray, name: str) -> FloatArray:
        c = np.cross(v[..., 0, :], v[..., 1, :])
        n = np.linalg.norm(c, axis=-1)
        refuse_first(name, v, n < 1e-12, "are parallel: TRIAD needs two distinct directions")
        t2 = c / n[..., None]
        return np.stack([v[..., 0, :], t2, np.cross(v[..., 0, :], t2)], axis=-1)

    Mb, Mr = frame(b, "body_vectors"), frame(r, "reference_vectors")
    b, r = np.broadcast_arrays(b, r)
    A = Mr @ np.swapaxes(Mb, -1, -2)
    b1, b2 = b[..., 0, :], b[..., 1, :]
    s1, s2 = s[..., 0, None, None], s[..., 1, None, None]
    cross2 = np.sum(np.cross(b1, b2) ** 2, axis=-1)[..., None, None]
    dot = np.sum(b1 * b2, axis=-1)[..., None, None]
    outer = b1[..., :, None] * b2[..., None, :]
    P = s1**2 * np.eye(3) + ((s2**2 - s1**2) * b1[..., :, None] * b1[..., None, :]
                             + s1**2 * dot * (outer + np.swapaxes(outer, -1, -2))) / cross2
    return Rotation.from_matrix(A.reshape(-1, 3, 3) if A.ndim > 3 else A), np.asarray(P, float)


def quest(body_vectors: ArrayLike, reference_vectors: ArrayLike, weights: ArrayLike) -> tuple[Rotation, FloatArray]:
    """QUEST: the optimal attitude from two or more vector observations, and its covariance.

    Parameters
    ----------
    body_vectors : array_like, shape (n, 3)
        Measured directions in the body frame (n >= 2; any length, normalised here).
    reference_vectors : array_like, shape (n, 3)
        The same directions in the reference (world) frame.
    weights : array_like, shape (n,)
        ``1 / sigma_i^2``, rad^-2, ``sigma_i`` each measurement's angular noise (at most pi rad,
        so each weight at least ``1 / pi^2``): the covariance is then in rad^2.

    Returns
    -------
    attitude : scipy Rotation
        Body to reference, from ``Rotation.align_vectors`` (module docstring).
    covariance : ndarray, shape (3, 3)
        ``[sum_i w_i (I - b_i b_i^T)]^{-1}``, of the error about the body axes, rad^2.

    Raises
    ------
    ValueError
        For fewer than two vectors, mismatched shapes, zero or non-finite vectors, weights below
        ``1 / pi^2`` (TRIAD's sigmas given as weights?), or directions all parallel (the attitude about them is then unobservable).

    Examples
    --------
    Three orthogonal directions each of 1 mrad noise: 0.71 mrad about each axis (each axis is
    seen by the two directions across it):

    >>> import numpy as np
    >>> from tumble.dynamics.estimation.static import quest
    >>> A, P = quest(np.eye(3), np.eye(3), [1e6, 1e6, 1e6])
    >>> float(A.magnitude()), np.round(np.sqrt(np.diag(P)) * 1e3, 3).tolist()
    (0.0, [0.707, 0.707, 0.707])
    """
    b = _units("body_vectors", body_vectors)
    r = _units("reference_vectors", reference_vectors)
    if b.ndim != 2 or b.shape[0] < 2 or r.shape != b.shape:
        raise ValueError(f"body_vectors and reference_vectors must both have shape (n, 3) with n >= 2; "
                         f"got {b.shape} and {r.shape}")
    w = np.asarray(weights, float)
    if w.shape != (b.shape[0],) or not np.all(np.isfinite(w) & (w > 0.0)):
        raise ValueError(f"weights = {w.tolist()!r} must be {b.shape[0]} positive finite numbers (1/sigma^2, rad^-2)")
    if np.any(w < 1.0 / math.pi**2):  # sigma past pi says nothing of the direction
        raise ValueError(f"weights = {w.tolist()!r}: each at least 1/pi^2 rad^-2 (1/sigma^2, sigma at most pi rad); "
                         "TRIAD's sigmas given as QUEST's weights?")
    F = np.einsum("i,ij,ik->jk", w, b, b)
    info = np.sum(w) * np.eye(3) - F
    if np.linalg.cond(info) > 1e12:
        raise ValueError("body_vectors are all parallel: the turn about them is unobservable; give two distinct directions")
    attitude, _ = Rotation.align_vectors(r, b, weights=w)
    return attitude, np.asarray(np.linalg.inv(info), float)
