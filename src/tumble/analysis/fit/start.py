"""Starting values of a fit: the principal axes and the ratios from the samples alone.

1. Principal axes. Along a torque-free motion two quadratic forms of omega are constant,
   ``omega^T J omega`` (twice the energy) and ``omega^T J^2 omega`` (``|L|^2``), with ``J`` the
   inertia tensor in the sensor frame; both, and every combination, share ``J``'s eigenvectors.
   The null space of the samples' quadratic monomials ``[wx^2, wy^2, wz^2, 2 wx wy, 2 wx wz,
   2 wy wz, -1]`` (its two smallest right singular vectors) gives two such forms; their joint
   eigenvectors are the principal axes in the sensor frame. (A drag torque along ``L`` scales
   both forms alike: the axes come out the same to first order.)
2. Euler's equations in the sensor frame, ``J omega' = (J omega) x omega``, are linear in the
   six entries of the sensor-frame inertia tensor ``J``: with ``omega'`` from central
   differences of the samples, ``J`` (up to its scale) is the null vector of the stacked
   equations, and its eigenvalues and eigenvectors give the ratios and the principal axes at
   once (:func:`euler_regression`; tried first, the forms of 1 and 3 after it). Unlike 1, it
   needs no more than one stretch of the polhode: on a one-second flight of a near-planar body
   the quadratic monomials have three small singular values, not two, and 1 mixes the axes.
3. Ratios. In the principal frame ``d(omega_i^2)/dt = 2 omega_1 omega_2 omega_3 (I_j - I_k) / I_i``
   (Euler's equations, ``(i, j, k)`` cyclic), so the samples' ``omega_i^2`` lie on a line with
   direction ``d = ((I2 - I3)/I1, (I3 - I1)/I2, (I1 - I2)/I3)``, which fixes both ratios. The
   line's direction (the first principal component of the squared components) is matched
   against a grid over the closed triangle (edges included), for each of the six labellings of
   the axes.
"""

from __future__ import annotations

import numpy as np

from ...typing import ArrayLike
from .triangle import ratios, square

__all__ = ["START_INSET", "candidates", "euler_regression", "first_value", "principal_axes"]

#: How far inside the square's faces (:func:`~.triangle.square`) Euler's regression puts its
#: ratios: a plate's estimate, clipped exactly onto the planar edge, had stalled the first solve
#: (scipy's dogbox cut its first step to nothing at the face and stopped on ``xtol``), on some
#: platforms and not others.
START_INSET = 1e-3

_PERMUTATIONS = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]


def principal_axes(omega: np.ndarray) -> np.ndarray:
    """Columns: the principal axes in the sensor frame, from two conserved quadratic forms.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.analysis.fit.start import principal_axes
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], np.linspace(0.0, 2.0, 400))[0]
    >>> R = Rotation.from_rotvec([0.3, -0.2, 0.5]).as_matrix()   # sensor to principal
    >>> V = principal_axes(w @ R)   # the samples on the sensor's axes
    >>> np.abs(R @ V).max(axis=0).round(6).tolist()   # each column one of R's rows (up to order and sign)
    [1.0, 1.0, 1.0]
    """
    wx, wy, wz = omega.T
    Q = np.column_stack([wx * wx, wy * wy, wz * wz, 2 * wx * wy, 2 * wx * wz, 2 * wy * wz, -np.ones_like(wx)])
    scale = np.linalg.norm(Q, axis=0)
    scale = np.where(scale > 0, scale, 1.0)
    _, _, Vt = np.linalg.svd(Q / scale, full_matrices=False)
    forms = []
    for row in Vt[-2:]:
        c = row / scale
        forms.append(np.array([[c[0], c[3], c[4]], [c[3], c[1], c[5]], [c[4], c[5], c[2]]]))
    best, best_gap = np.eye(3), -1.0
    for mu in (-3.0, -1.0, -0.3, 0.0, 0.3, 1.0, 3.0, 1e3):
        M = forms[0] / np.linalg.norm(forms[0]) + mu * forms[1] / np.linalg.norm(forms[1])
        vals, vecs = np.linalg.eigh(M)
        gap = np.min(np.diff(vals)) / (np.max(np.abs(vals)) or 1.0)
        if gap > best_gap:
            best, best_gap = vecs, gap
    return best


def euler_regression(t: np.ndarray, omega: np.ndarray) -> tuple[float, float, np.ndarray] | None:
    """Ratios and principal axes from Euler's equations, linear in the inertia tensor (docstring).

    Parameters
    ----------
    t : ndarray, shape (n,)
        Times, s (uneven spacing allowed; samples next to a gap are left out).
    omega : ndarray, shape (n, 3)
        Samples, sensor axes, rad/s.

    Returns
    -------
    (x, y, R) or None
        ``I1/I3``, ``I2/I3`` (inside the triangle, :data:`START_INSET` from its edges) and ``R`` (sensor to principal), or
        None when the equations do not single out a positive-definite tensor.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.analysis.fit.start import euler_regression
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 1.0, 1000)
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0]
    >>> R = Rotation.from_rotvec([0.3, -0.2, 0.5]).as_matrix()
    >>> x, y, R_fit = euler_regression(t, w @ R)   # I1/I3 = 0.5, I2/I3 = 0.8 back
    >>> round(x, 4), round(y, 4), bool(np.allclose(np.abs(R_fit @ R.T), np.eye(3), atol=1e-4))
    (0.5, 0.8, True)
    >>> euler_regression(t[:4], w[:4]) is None   # too few samples
    True
    """
    if len(t) < 5:
        return None
    dt = np.diff(t)
    step = np.median(dt)
    wdot = np.gradient(omega, t, axis=0)
    ok = np.ones(len(t), bool)
    gap = np.flatnonzero(dt > 1.8 * step)
    ok[gap], ok[np.minimum(gap + 1, len(t) - 1)] = False, False
    ok[0] = ok[-1] = False
    w, a = omega[ok], wdot[ok]
    # J = [[j0, j3, j4], [j3, j1, j5], [j4, j5, j2]]; rows: (J a - (J w) x w) per axis
    E = np.zeros((3, 3, 6))
    for k, (i, j) in enumerate([(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]):
        E[i, j, k] = E[j, i, k] = 1.0
    Ja = np.einsum("ijk,nj->nik", E, a)            # d(J a)/dj, (n, 3, 6)
    Jw = np.einsum("ijk,nj->nik", E, w)            # d(J w)/dj
    cross = np.cross(Jw, w[:, :, None], axisa=1, axisb=1, axisc=1)
    A = (Ja - cross).reshape(-1, 6)
    scale = np.linalg.norm(A, axis=0)
    if not np.all(scale > 0):
        return None
    _, _, Vt = np.linalg.svd(A / scale, full_matrices=False)
    j = Vt[-1] / scale
    J = np.einsum("ijk,k->ij", E, j)
    vals, vecs = np.linalg.eigh(J)
    if vals[-1] < 0:
        vals, vecs = -vals[::-1], vecs[:, ::-1]
    if not vals[0] > 0:
        return None
    if np.linalg.det(vecs) < 0:
        vecs[:, 2] *= -1.0
    x, y = ratios(*square(vals[0] / vals[2], vals[1] / vals[2], START_INSET))
    return float(x), float(y), vecs.T


def _direction_grid(n: int = 120):
    """Points of the closed triangle and the unit direction of the line of omega_i^2 at each."""
    y = np.linspace(0.5, 1.0, n)[1:]
    frac = np.linspace(0.0, 1.0, n)
    Y, F = np.meshgrid(y, frac, indexing="ij")
    X = 1.0 - Y + (2 * Y - 1) * F
    X, Y = X.ravel(), Y.ravel()
    keep = X > 1e-3  # the rod corner (I1 = 0) is no body
    X, Y = X[keep], Y[keep]
    d = np.stack([(Y - 1.0) / X, (1.0 - X) / Y, X - Y], axis=1)
    norm = np.linalg.norm(d, axis=1)
    keep = norm > 0  # the sphere-like corner has no direction
    return X[keep], Y[keep], d[keep] / norm[keep, None]


_GRID = None


def candidates(omega: np.ndarray, fit_rotation: bool, keep: int = 2, t: np.ndarray | None = None) -> list[tuple[float, float, np.ndarray]]:
    """Starting ``(I1/I3, I2/I3, R)`` triples (``R`` sensor to principal): Euler's regression
    first (when ``t`` is given), then the conserved forms' axes with the likeliest ratios.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.start import candidates
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 1.0, 1000)
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0]
    >>> starts = candidates(w, fit_rotation=False, t=t)
    >>> x, y, R = starts[0]   # Euler's regression first
    >>> round(x, 4), round(y, 4), R.tolist() == np.eye(3).tolist(), len(starts)   # then the two likeliest grid points
    (0.5, 0.8, True, 3)
    """
    global _GRID
    first = []
    if t is not None:
        est = euler_regression(t, omega)
        if est is not None:
            x, y, R = est
            first = [(x, y, R if fit_rotation else np.eye(3))]
    if _GRID is None:
        _GRID = _direction_grid()
    if fit_rotation:
        V, perms = principal_axes(omega), _PERMUTATIONS
    else:
        V, perms = np.eye(3), [(0, 1, 2)]
    X, Y, D = _GRID
    out = []
    for p in perms:
        A = V[:, list(p)].copy()
        if np.linalg.det(A) < 0:
            A[:, 2] *= -1.0
        R = A.T
        sq = (omega @ R.T) ** 2
        sq = sq - sq.mean(axis=0)
        _, _, vt = np.linalg.svd(sq, full_matrices=False)
        score = np.abs(D @ vt[0])
        for i in np.argsort(-score)[:keep]:
            out.append((1.0 - score[i], X[i], Y[i], R))
    out.sort(key=lambda c: c[0])
    return first + [(x, y, R) for _, x, y, R in out]


def first_value(tau: np.ndarray, omega: ArrayLike) -> np.ndarray:
    """omega at tau = 0: the first sample (a polynomial through several samples is worse once a
    sample interval turns the body by a tenth of a radian or more, as a fast toss at 100 Hz does).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.start import first_value
    >>> first_value(np.array([0.0, 0.01]), [[1.0, 2.0, 3.0], [1.1, 2.0, 2.9]]).tolist()
    [1.0, 2.0, 3.0]
    """
    return np.asarray(omega[0], float)
