"""A flown body's inertia tensor as the fit writes it: always that of some positive mass distribution.

**Physical tensors.** The flown body's tensor about its centre of mass is written
``I = tr(S) E - S`` with ``S = C C^T`` its second moment of mass (``S = integral rho r r^T dV``;
Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed., sec. 5.3) and ``C`` lower triangular
(6 numbers). A tensor is that of some positive mass distribution exactly when ``S`` is positive
semi-definite (Wensing, Kim & Slotine, "Linear matrix inequalities for physically consistent
inertial parameter identification", IEEE RA-L 3 (2018) 60), which gives the triangle
inequalities of the moments: every ``C`` gives a physical tensor, and the fit needs no bounds.
"""

from __future__ import annotations

import numpy as np

from ...typing import ArrayLike, FloatArray, Matrix3
from .estimate import vector_of

__all__ = ["cholesky_of", "inertia_jacobian", "inertia_of"]


def inertia_of(c: ArrayLike) -> Matrix3:
    """``I = tr(S) E - S``, ``S = C C^T`` from the six entries of ``C`` (module docstring), batched.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.physical import inertia_of
    >>> inertia_of([1.0, 1.0, 0.0, 0.0, 0.0, 0.0]).diagonal().tolist()   # a flat square: I3 = I1 + I2
    [1.0, 1.0, 2.0]
    """
    c = np.asarray(c, float)
    C = np.zeros(c.shape[:-1] + (3, 3))
    C[..., 0, 0], C[..., 1, 1], C[..., 2, 2] = c[..., 0], c[..., 1], c[..., 2]
    C[..., 1, 0], C[..., 2, 0], C[..., 2, 1] = c[..., 3], c[..., 4], c[..., 5]
    S = C @ np.swapaxes(C, -1, -2)
    return np.trace(S, axis1=-2, axis2=-1)[..., None, None] * np.eye(3) - S


def cholesky_of(inertia: ArrayLike, floor: float = 1e-3) -> FloatArray:
    """The ``C`` of a tensor (inverse of :func:`inertia_of`); a tensor just outside the physical
    set is brought in, each eigenvalue of ``S`` at least ``floor`` of the largest.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.physical import cholesky_of, inertia_of
    >>> I = np.array([[2.0, 0.1, 0.0], [0.1, 3.0, 0.2], [0.0, 0.2, 4.0]])
    >>> bool(np.allclose(inertia_of(cholesky_of(I)), I))
    True
    """
    I = np.asarray(inertia, float)
    S = 0.5 * np.trace(I) * np.eye(3) - 0.5 * (I + I.T)
    lam, V = np.linalg.eigh(S)
    lam = np.maximum(lam, floor * max(float(lam.max()), 1e-300))
    C = np.linalg.cholesky((V * lam) @ V.T)
    return np.array([C[0, 0], C[1, 1], C[2, 2], C[1, 0], C[2, 0], C[2, 1]])


def inertia_jacobian(c: ArrayLike) -> FloatArray:
    """``d(I_xx, I_yy, I_zz, I_xy, I_xz, I_yz) / dC``, shape (6, 6) (exact: ``I`` is quadratic in
    ``C``, so central differences are exact but for rounding).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.physical import inertia_jacobian
    >>> inertia_jacobian([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])[:3, :3].round(9).tolist()   # I_xx = c_yy^2 + c_zz^2 + ...
    [[0.0, 2.0, 2.0], [2.0, 0.0, 2.0], [2.0, 2.0, 0.0]]
    """
    c = np.asarray(c, float)
    step = 1e-4 * max(float(np.abs(c).max()), 1e-300)
    G = np.empty((6, 6))
    for k in range(6):
        d = np.zeros(6)
        d[k] = step
        G[:, k] = (vector_of(inertia_of(c + d)) - vector_of(inertia_of(c - d))) / (2 * step)
    return G
