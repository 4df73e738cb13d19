"""Estimated mass properties with their uncertainties: :class:`MassEstimate`, the principal
moments' uncertainty and the parallel-axis subtraction of one body from another.

A tensor's six independent entries are ordered ``xx, yy, zz, xy, xz, yz`` (:data:`ENTRIES`) in
every covariance. Uncertainties are propagated to first order (the law of propagation of
uncertainty, JCGM 100:2008, the GUM, sec. 5.1): ``cov_y = J cov_x J^T`` with ``J`` the
Jacobian of the map.

- **Principal moments**: for a symmetric tensor with distinct eigenvalues, the first-order change
  of eigenvalue ``k`` is ``d lambda_k = v_k^T dI v_k`` (Hellmann-Feynman; Magnus & Neudecker,
  *Matrix Differential Calculus*, 3rd ed., 2019, ch. 8, thm. 7), so its gradient in the six
  entries is ``(v_x^2, v_y^2, v_z^2, 2 v_x v_y, 2 v_x v_z, 2 v_y v_z)``.
- **Subtraction** (:func:`subtract_body`): a whole of mass ``M``, centre ``c`` and tensor ``I``
  about ``c`` holds a part ``(m_p, c_p, I_p)``; the rest has ``m = M - m_p``,
  ``c_r = (M c - m_p c_p) / m`` and, about the origin, ``I + M S(c) = I_p + m_p S(c_p) +
  I_r + m S(c_r)`` with ``S(d) = |d|^2 E - d d^T`` (the parallel-axis theorem, Steiner's;
  Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed., sec. 5.3, and
  :func:`tumble.mass.tensor.parallel_axis`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...mass.tensor import parallel_axis
from ...typing import ArrayLike, FloatArray, Matrix3, Vector3
from ...validation import triangle_excess
from .. import _display

__all__ = ["ENTRIES", "NOT_A_BODY", "TRIANGLE_SIGMA", "MassEstimate", "mass_estimate", "not_physical", "onto_triangle",
           "principal_uncertainty", "subtract_body", "tensor_of", "vector_of"]

#: An estimate whose moments break the triangle inequality by more than this many standard
#: uncertainties (of ``I1 + I2 - I3``) is no body's.
TRIANGLE_SIGMA = 3.0

#: The order of a tensor's six independent entries in every covariance.
ENTRIES = ("xx", "yy", "zz", "xy", "xz", "yz")
_ROW = np.array([0, 1, 2, 0, 0, 1])
_COL = np.array([0, 1, 2, 1, 2, 2])


def vector_of(inertia: ArrayLike) -> FloatArray:
    """The six entries ``xx, yy, zz, xy, xz, yz`` of symmetric tensors ``(..., 3, 3)``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.estimate import vector_of
    >>> vector_of([[1.0, 4.0, 5.0], [4.0, 2.0, 6.0], [5.0, 6.0, 3.0]]).tolist()
    [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
    """
    I = np.asarray(inertia, float)
    return I[..., _ROW, _COL]


def tensor_of(entries: ArrayLike) -> Matrix3:
    """The symmetric tensors ``(..., 3, 3)`` of six entries ``xx, yy, zz, xy, xz, yz``.

    Examples
    --------
    >>> from tumble.analysis.tensor.estimate import tensor_of, vector_of
    >>> vector_of(tensor_of([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])).tolist()
    [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
    """
    v = np.asarray(entries, float)
    I = np.zeros(v.shape[:-1] + (3, 3))
    I[..., _ROW, _COL] = v
    I[..., _COL, _ROW] = v
    return I


def principal_uncertainty(inertia: ArrayLike, inertia_cov: ArrayLike) -> tuple[Vector3, Vector3, Matrix3]:
    """Principal moments (ascending), their standard uncertainties and the axes (columns).

    First-order perturbation of a symmetric tensor's eigenvalues (module docstring): exact for
    distinct moments as the uncertainty goes to 0; for nearly equal moments the std is a lower
    bound.

    Parameters
    ----------
    inertia : array_like, shape (3, 3)
        kg m^2.
    inertia_cov : array_like, shape (6, 6)
        Covariance of its entries :data:`ENTRIES`, (kg m^2)^2.

    Returns
    -------
    moments, std : ndarray, shape (3,)
        kg m^2.
    axes : ndarray, shape (3, 3)
        Unit principal axes as columns, right-handed.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.estimate import principal_uncertainty
    >>> cov = np.diag([1.0, 4.0, 9.0, 0.0, 0.0, 0.0]) * 1e-12   # the diagonal entries' variances
    >>> I, s, R = principal_uncertainty(np.diag([3e-4, 1e-4, 2e-4]), cov)
    >>> I.tolist(), (s * 1e6).round(9).tolist()   # a diagonal tensor: each moment is one entry
    ([0.0001, 0.0002, 0.0003], [2.0, 3.0, 1.0])
    """
    I = np.asarray(inertia, float)
    moments, axes = np.linalg.eigh(0.5 * (I + I.T))
    if np.linalg.det(axes) < 0:
        axes[:, 2] *= -1.0
    v = axes
    G = np.stack([v[0] ** 2, v[1] ** 2, v[2] ** 2, 2 * v[0] * v[1], 2 * v[0] * v[2], 2 * v[1] * v[2]], axis=1)
    var = np.einsum("ki,ij,kj->k", G, np.asarray(inertia_cov, float), G)
    return moments, np.sqrt(np.maximum(var, 0.0)), axes


@dataclass(frozen=True)
class MassEstimate:
    """A body's estimated mass properties, sensor frame.

    Attributes
    ----------
    mass : float
        kg (given, not estimated).
    inertia : ndarray, shape (3, 3)
        About the body's centre of mass, kg m^2.
    inertia_cov : ndarray, shape (6, 6)
        Covariance of the entries :data:`ENTRIES`, statistical and systematic parts, (kg m^2)^2.
    principal_moments, principal_moments_std : ndarray, shape (3,)
        Ascending, kg m^2 (:func:`principal_uncertainty`).
    principal_axes : ndarray, shape (3, 3)
        Unit axes as columns, in the order of the moments.
    center_of_mass, center_of_mass_std : ndarray, shape (3,)
        From the accelerometer (the sensor frame's origin), m.
    center_of_mass_cov : ndarray, shape (3, 3)
        m^2 (not in :meth:`as_dict`).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.estimate import mass_estimate
    >>> e = mass_estimate(0.5, np.diag([2e-4, 1e-4, 3e-4]), np.eye(6) * 1e-14, [0.01, 0.0, 0.0], np.eye(3) * 1e-8)
    >>> e.principal_moments.tolist(), sorted(e.as_dict())
    ([0.0001, 0.0002, 0.0003], ['center_of_mass', 'center_of_mass_std', 'inertia', 'inertia_cov', 'mass', 'principal_axes', 'principal_moments', 'principal_moments_std'])
    """

    mass: float
    inertia: Matrix3 = field(repr=False)
    inertia_cov: FloatArray = field(repr=False)
    principal_moments: Vector3
    principal_moments_std: Vector3
    principal_axes: Matrix3 = field(repr=False)
    center_of_mass: Vector3
    center_of_mass_std: Vector3
    center_of_mass_cov: FloatArray = field(repr=False)

    def __repr__(self) -> str:
        return _display.estimate_repr(self)

    def _repr_html_(self) -> str:
        return _display.estimate_html(self)

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready: the attributes (but the centre's covariance) as floats and nested lists.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.estimate import mass_estimate
        >>> d = mass_estimate(0.5, np.diag([1e-4, 2e-4, 3e-4]), np.zeros((6, 6)), [0, 0, 0], np.zeros((3, 3))).as_dict()
        >>> d["mass"], len(d["inertia_cov"]), d["principal_moments"]
        (0.5, 6, [0.0001, 0.0002, 0.0003])
        """
        return {"mass": float(self.mass), "inertia": self.inertia.tolist(), "inertia_cov": self.inertia_cov.tolist(),
                "principal_moments": self.principal_moments.tolist(),
                "principal_moments_std": self.principal_moments_std.tolist(),
                "principal_axes": self.principal_axes.tolist(), "center_of_mass": self.center_of_mass.tolist(),
                "center_of_mass_std": self.center_of_mass_std.tolist()}


def mass_estimate(mass: float, inertia: ArrayLike, inertia_cov: ArrayLike, center_of_mass: ArrayLike,
                  center_of_mass_cov: ArrayLike) -> MassEstimate:
    """A :class:`MassEstimate` from the tensor, the centre and their covariances.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.estimate import mass_estimate
    >>> e = mass_estimate(1.0, np.diag([1.0, 2.0, 3.0]), np.zeros((6, 6)), [0.0, 0.0, 0.1], np.diag([1e-6, 1e-6, 4e-6]))
    >>> e.center_of_mass_std.tolist()
    [0.001, 0.001, 0.002]
    """
    I = np.asarray(inertia, float)
    I = 0.5 * (I + I.T)
    C = np.asarray(inertia_cov, float)
    C = 0.5 * (C + C.T)
    c = np.asarray(center_of_mass, float)
    Cc = np.asarray(center_of_mass_cov, float)
    moments, std, axes = principal_uncertainty(I, C)
    return MassEstimate(float(mass), I, C, moments, std, axes, c, np.sqrt(np.maximum(np.diag(Cc), 0.0)), Cc)


#: How :func:`not_physical`'s refusals begin (the pooled fit reads it: every throw refused so points at the device).
NOT_A_BODY = "not a body's tensor"


def not_physical(estimate: MassEstimate) -> str:
    """Why an estimated tensor is no body's, or ``""``: a principal moment not positive, or the
    triangle inequality ``I1 + I2 >= I3`` (Goldstein sec. 5.4; :func:`tumble.mass.tensor.check_inertia`)
    broken by more than :data:`TRIANGLE_SIGMA` of its standard uncertainty (a flat body lies on
    its edge, and its estimate on either side of it).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.estimate import mass_estimate, not_physical
    >>> flat = mass_estimate(0.1, np.diag([1e-4, 2e-4, 3.001e-4]), np.eye(6) * 1e-14, np.zeros(3), np.eye(3))
    >>> not_physical(flat)   # 1e-7 over the edge, its std 1.7e-7
    ''
    >>> print(not_physical(mass_estimate(0.1, np.diag([-1e-5, 2e-4, 2e-4]), np.eye(6) * 1e-14, np.zeros(3), np.eye(3))))
    not a body's tensor: principal moments -1e-05, 0.0002, 0.0002 kg m^2, the smallest not positive
    """
    m = estimate.principal_moments
    shown = ", ".join(f"{x:.3g}" for x in m)
    if m[0] <= 0:
        return f"{NOT_A_BODY}: principal moments {shown} kg m^2, the smallest not positive"
    gap, G = _triangle_gap(estimate.principal_moments, estimate.principal_axes)
    std = float(np.sqrt(max(G @ estimate.inertia_cov @ G, 0.0)))
    if gap < -TRIANGLE_SIGMA * std:
        return (f"{NOT_A_BODY}: principal moments {shown} kg m^2 break the triangle inequality "
                f"(I1 + I2 - I3 = {gap:.3g}, {(-gap / std) if std > 0 else float('inf'):.3g} standard uncertainties "
                f"below 0)")
    return ""


def _triangle_gap(moments: FloatArray, axes: FloatArray) -> tuple[float, FloatArray]:
    """``I1 + I2 - I3`` (kg m^2) and its gradient with respect to the six entries (xx, yy, zz, xy, xz,
    yz): ``d lambda_k / d I = a_k a_k^T`` for the unit eigenvector ``a_k`` (first-order perturbation of
    a symmetric matrix's eigenvalue)."""
    g = np.array([1.0, 1.0, -1.0])  # d(I1 + I2 - I3) / d(I1, I2, I3)
    G = sum(gk * np.array([a[0] ** 2, a[1] ** 2, a[2] ** 2, 2 * a[0] * a[1], 2 * a[0] * a[2], 2 * a[1] * a[2]])
            for gk, a in zip(g, np.asarray(axes, float).T))
    return -float(triangle_excess(moments)), np.asarray(G, float)


def onto_triangle(estimate: MassEstimate) -> tuple[MassEstimate, float]:
    """The estimate, where its moments keep the triangle inequality ``I1 + I2 >= I3``; else the
    nearest tensor on its edge ``I1 + I2 = I3`` in the metric of the estimate's covariance ``C`` (the
    least-squares estimate under the constraint: ``x = x0 - C G mu``, ``mu`` from the constraint
    linearised anew at each iterate, Newton's way; Nocedal & Wright, *Numerical Optimization*, sec.
    18.1), its covariance ``C - C G G^T C / (G^T C G)``; and how many standard uncertainties of the gap
    it moved (0 where it did not). An estimate of a flat body lies on either side of the edge; not
    physical as written, it was written as adequate (a 40 g box 1.8 standard uncertainties over it:
    a walkthrough, 2026-12-03). One beyond :data:`TRIANGLE_SIGMA` is :func:`not_physical`'s, refused.

    Examples
    --------
    A flat body's estimate 2e-7 kg m^2 over the edge, its gap's standard uncertainty 1.7e-7: moved on
    to the edge, its trace's share of the move even (equal variances), its gap now known exactly:

    >>> import numpy as np
    >>> from tumble.analysis.tensor.estimate import mass_estimate, onto_triangle
    >>> flat = mass_estimate(0.1, np.diag([1e-4, 2e-4, 3.002e-4]), np.eye(6) * 1e-14, np.zeros(3), np.eye(3))
    >>> edge, moved = onto_triangle(flat)
    >>> round(moved, 3), edge.principal_moments.round(9).tolist()
    (1.155, [0.000100067, 0.000200067, 0.000300133])
    >>> onto_triangle(edge)[1], bool(np.isclose(edge.principal_moments_std[0] ** 2 + edge.principal_moments_std[1] ** 2
    ...                                         - edge.principal_moments_std[2] ** 2, -2e-14, rtol=1e-6))
    (0.0, True)
    """
    m, axes = estimate.principal_moments, estimate.principal_axes
    gap, G = _triangle_gap(m, axes)
    if not (m[0] > 0 and gap < -1e-12 * float(np.sum(m))):  # on the edge to round-off: as it is
        return estimate, 0.0
    C = np.asarray(estimate.inertia_cov, float)
    std = float(np.sqrt(max(G @ C @ G, 0.0)))
    if std == 0.0:
        return estimate, 0.0
    x0 = vector_of(estimate.inertia)
    x = x0.copy()
    for _ in range(8):  # the gap is an eigenvalue sum: curved in the entries; a few Newton steps meet it
        mu = (gap + G @ (x0 - x)) / (G @ C @ G)
        x = x0 - C @ G * mu
        moments, vectors = np.linalg.eigh(tensor_of(x))
        gap, G = _triangle_gap(moments, vectors)
        if abs(gap) <= 1e-12 * float(np.sum(moments)):
            break
    C1 = C - np.outer(C @ G, C @ G) / (G @ C @ G)
    moved = float(np.sqrt(max((x - x0) @ np.linalg.pinv(C) @ (x - x0), 0.0)))
    edge = mass_estimate(estimate.mass, tensor_of(x), 0.5 * (C1 + C1.T), estimate.center_of_mass,
                         estimate.center_of_mass_cov)
    return edge, moved


def _rest(x: FloatArray, M: float, m_p: float) -> FloatArray:
    """``(I_r entries, c_r)`` of the rest from ``x = (I entries, c, I_p entries, c_p)``."""
    I, c, Ip, cp = tensor_of(x[:6]), x[6:9], tensor_of(x[9:15]), x[15:18]
    m = M - m_p
    cr = (M * c - m_p * cp) / m
    about_origin = parallel_axis(I, M, c) - parallel_axis(Ip, m_p, cp)
    Ir = about_origin - parallel_axis(np.zeros((3, 3)), m, cr)
    return np.concatenate([vector_of(Ir), cr])


def subtract_body(whole: MassEstimate, part_mass: float, part_inertia: ArrayLike, part_inertia_cov: ArrayLike,
                  part_center: ArrayLike, part_center_cov: ArrayLike) -> MassEstimate:
    """The rest of ``whole`` once a part of known mass properties is taken away (module docstring).

    The part's and the whole's uncertainties are taken independent and propagated with the
    map's Jacobian (central differences: the map is quadratic in the centres and linear in the
    tensors, so they are exact but for rounding).

    Parameters
    ----------
    whole : MassEstimate
        The whole (e.g. the flown body: object and device).
    part_mass : float
        kg, less than ``whole.mass``.
    part_inertia : array_like, shape (3, 3)
        About the part's own centre of mass, kg m^2.
    part_inertia_cov : array_like, shape (6, 6)
    part_center : array_like, shape (3,)
        m, same frame.
    part_center_cov : array_like, shape (3, 3)

    Returns
    -------
    MassEstimate
        The rest, about its own centre of mass.

    Examples
    --------
    Two point-like halves 0.2 m apart: the whole's tensor about its centre is ``2 m (0.1)^2``
    across the line; taking one half away leaves a point (zero tensor) at 0.1 m:

    >>> import numpy as np
    >>> from tumble.analysis.tensor.estimate import mass_estimate, subtract_body
    >>> whole = mass_estimate(2.0, np.diag([0.0, 0.02, 0.02]), np.zeros((6, 6)), [0.0, 0.0, 0.0], np.zeros((3, 3)))
    >>> rest = subtract_body(whole, 1.0, np.zeros((3, 3)), np.zeros((6, 6)), [-0.1, 0.0, 0.0], np.zeros((3, 3)))
    >>> bool(np.abs(rest.inertia).max() < 1e-15), rest.center_of_mass.round(12).tolist(), rest.mass
    (True, [0.1, 0.0, 0.0], 1.0)
    """
    M, m_p = float(whole.mass), float(part_mass)
    if not m_p < M:
        raise ValueError(f"the part's mass {m_p!r} kg must be less than the whole's {M!r} kg")
    x = np.concatenate([vector_of(whole.inertia), whole.center_of_mass, vector_of(part_inertia), part_center])
    cov = np.zeros((18, 18))
    cov[:6, :6] = whole.inertia_cov
    cov[6:9, 6:9] = whole.center_of_mass_cov
    cov[9:15, 9:15] = part_inertia_cov
    cov[15:, 15:] = part_center_cov
    y = _rest(x, M, m_p)
    scale = np.concatenate([np.full(6, max(np.abs(x[:6]).max(), 1e-30)), np.full(3, 0.01),
                            np.full(6, max(np.abs(x[:6]).max(), 1e-30)), np.full(3, 0.01)])
    J = np.empty((9, 18))
    for k in range(18):
        d = np.zeros(18)
        d[k] = 1e-3 * scale[k]
        J[:, k] = (_rest(x + d, M, m_p) - _rest(x - d, M, m_p)) / (2 * d[k])
    cy = J @ cov @ J.T
    return mass_estimate(M - m_p, tensor_of(y[:6]), cy[:6, :6], y[6:], cy[6:, 6:])
