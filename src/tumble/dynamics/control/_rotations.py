"""The Python path's rotation matrix (from the one writing, ``to_body``) on 3-vectors: what the closed loop's
right-hand side (:func:`~tumble.dynamics.control.controlled.simulate_controlled` with a model of
one's own) calls at every evaluation, where numpy's and scipy's general routines cost tens of
microseconds a call.
"""

from __future__ import annotations

import numpy as np

from ...typing import ArrayLike, FloatArray
from ..special.quaternion import to_body

__all__ = ["Matrix", "matrix"]


def matrix(q: FloatArray) -> FloatArray:
    """Rotation matrix (body to world) of a unit quaternion ``(x, y, z, w)``: its rows are the
    world axes in the body frame, :func:`~tumble.dynamics.special.quaternion.to_body` (the one
    writing of Shuster 1993, eq. 161, which the compiled loop calls too); scipy's ``Rotation``
    costs tens of microseconds a call.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.control._rotations import matrix
    >>> q = Rotation.from_rotvec([0.3, -0.2, 0.5]).as_quat()
    >>> np.allclose(matrix(q), Rotation.from_quat(q).as_matrix(), rtol=0, atol=1e-15)
    True
    """
    x, y, z, w = (float(c) for c in q)
    return np.array([to_body(x, y, z, w, 1.0, 0.0, 0.0), to_body(x, y, z, w, 0.0, 1.0, 0.0),
                     to_body(x, y, z, w, 0.0, 0.0, 1.0)])


class Matrix:
    """A rotation held as its matrix, with the two calls a torque model makes of a scipy
    ``Rotation`` (``apply`` and ``inv``): the right-hand side builds one per call, and a
    ``Rotation`` costs ~100 us to build and apply.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control._rotations import Matrix
    >>> quarter = Matrix(np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]))   # 90 deg about z
    >>> quarter.apply([1.0, 0.0, 0.0]).tolist(), quarter.inv().apply([0.0, 1.0, 0.0]).tolist()
    ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0])
    """

    def __init__(self, matrix: FloatArray) -> None:
        self.matrix = matrix

    def apply(self, v: ArrayLike) -> FloatArray:
        """The vector ``v`` turned: ``R v``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.control._rotations import Matrix
        >>> Matrix(np.diag([1.0, -1.0, -1.0])).apply([1.0, 2.0, 3.0]).tolist()   # half a turn about x
        [1.0, -2.0, -3.0]
        """
        return np.asarray(self.matrix @ np.asarray(v, float), float)

    def inv(self) -> Matrix:
        """The inverse rotation, ``R^T``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.control._rotations import Matrix
        >>> Matrix(np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])).inv().matrix[0].tolist()
        [0.0, 1.0, 0.0]
        """
        return Matrix(self.matrix.T)

