"""Modified Rodrigues parameters (MRPs), ``sigma = e tan(phi / 4)`` for a rotation by ``phi`` about ``e``.

From a scalar-last quaternion ``(v, s)``: ``sigma = v / (1 + s)``; taking the quaternion with
``s >= 0`` gives the short-rotation set ``|sigma| <= 1`` (the shadow set ``-sigma / |sigma|^2``
describes the same attitude; Schaub & Junkins, *Analytical Mechanics of Space Systems*, 4th
ed., sec. 3.7). Broadcast over leading axes.
"""

from __future__ import annotations

import numpy as np

from ...typing import ArrayLike, FloatArray, FloatOrArray, Vector3

__all__ = ["mrp_angle", "mrp_from_quat"]


def mrp_from_quat(quat: ArrayLike) -> Vector3:
    """The short-rotation MRPs (``|sigma| <= 1``) of unit quaternions ``[x, y, z, w]``; shape (..., 3).

    Examples
    --------
    >>> import math
    >>> from tumble.dynamics.special.mrp import mrp_from_quat
    >>> mrp_from_quat([0.0, 0.0, math.sin(0.5), math.cos(0.5)]).round(6).tolist()   # 1 rad about z
    [0.0, 0.0, 0.255342]
    """
    q = np.asarray(quat, float)
    q = np.where(q[..., 3:] < 0.0, -q, q)
    return np.asarray(q[..., :3] / (1.0 + q[..., 3:]), float)


def mrp_angle(sigma: ArrayLike) -> FloatOrArray:
    """The principal rotation angle ``phi = 4 atan |sigma|`` of MRPs, rad; shape (...).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.special.mrp import mrp_angle, mrp_from_quat
    >>> q = [0.0, np.sin(1.2), 0.0, np.cos(1.2)]   # 2.4 rad about y
    >>> round(float(mrp_angle(mrp_from_quat(q))), 12)
    2.4
    >>> round(float(mrp_angle([1.0, 0.0, 0.0])), 12) == round(np.pi, 12)   # |sigma| = 1: a half turn
    True
    """
    s: FloatArray = np.asarray(sigma, float)
    angle: FloatArray = 4.0 * np.arctan(np.linalg.norm(s, axis=-1))
    return angle
