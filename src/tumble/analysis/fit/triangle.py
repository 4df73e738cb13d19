"""The closed triangle of inertia ratios and the coordinates the fit moves in.

Every rigid body has ``I1 <= I2 <= I3`` and ``I1 + I2 >= I3`` (the triangle inequality of the
principal moments: Landau & Lifshitz, *Mechanics*, sec. 32, problem 1), so
``(x, y) = (I1/I3, I2/I3)`` lies in the closed triangle ``1/2 <= y <= 1``, ``1 - y <= x <= y``.
Its edges are bodies that people toss: ``x = 1 - y`` the **planar** ones (a thin plate, a phone,
a racquet, a book: ``I1 + I2 = I3`` within a few per cent), ``x = y`` the symmetric tops with
``I1 = I2`` and ``y = 1`` those with ``I2 = I3``.

The fit works on coordinates ``(s, g)`` of a square, spanned from the triangle's rod corner
``B = (0, 1)`` (a body with ``I1 = 0``, which does not exist) towards the other two::

    (x, y) = B + s ((1 - g) (A - B) + g (C - B)),   A = (1/2, 1/2) the disc, C = (1, 1) the sphere,
    x = s (1 + g) / 2,   y = 1 - s (1 - g) / 2,     s = (I1 + I3 - I2) / I3,  g = 1 - 2 (1 - y) / s,

with box bounds ``S_MIN <= s <= 1``, ``0 <= g <= 1`` (:func:`scipy.optimize.least_squares`),
so that every point of the closed triangle but a sliver at the rod corner is reachable, edges
included, each edge a face of the box: ``g = 0`` the planar edge, ``g = 1`` the edge
``I2 = I3``, ``s = 1`` the edge ``I1 = I2``. The map's Jacobian determinant is ``s / 2``: it is
regular everywhere in the box (the corner ``s = 0``, where Euler's equations degenerate to
0/0 for the rod's axis, is left out). The uncertainties are carried to ``(x, y)`` by the chain
rule (:func:`ratio_jacobian`).
"""

from __future__ import annotations

import math

import numpy as np

from ...typing import ArrayLike

__all__ = ["EDGES", "S_MIN", "at_rod_limit", "edge_of", "ratio_jacobian", "ratios", "square"]

#: Names of the triangle's edges, in the terms a user knows.
EDGES = {"planar": "planar (I1 + I2 = I3)", "I1=I2": "symmetric (I1 = I2)", "I2=I3": "symmetric (I2 = I3)",
         "rod": "rod limit ((I1 + I3 - I2) / I3 at its floor)"}
#: Smallest ``s = (I1 + I3 - I2) / I3`` fitted: bodies thinner than this are rods to the fit.
S_MIN = 1e-2
#: A coordinate within this of its bound is on the edge.
_ON_EDGE = 1e-7


def ratios(s: ArrayLike, g: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Square coordinates ``(s, g)`` -> ``(I1/I3, I2/I3)``; broadcasts.

    Examples
    --------
    >>> from tumble.analysis.fit.triangle import ratios
    >>> [tuple(float(v) for v in ratios(s, g)) for s, g in [(1.0, 0.0), (1.0, 1.0), (0.5, 0.0)]]   # disc, sphere, planar
    [(0.5, 0.5), (1.0, 1.0), (0.25, 0.75)]
    """
    s, g = np.asarray(s, float), np.asarray(g, float)
    return 0.5 * s * (1.0 + g), 1.0 - 0.5 * s * (1.0 - g)


def square(x: ArrayLike, y: ArrayLike, inset: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """``(I1/I3, I2/I3)`` in the closed triangle -> ``(s, g)``, clipped into the box.

    ``inset`` > 0 keeps the point that far inside the box's faces (a start for the fit: scipy's
    dogbox, started exactly on a face, can take a first step that the face cuts to nothing and
    stop there on its ``xtol`` test, far from the optimum).

    Examples
    --------
    >>> from tumble.analysis.fit.triangle import ratios, square
    >>> square(0.25, 0.75)   # a planar body, I1 + I2 = I3: g = 0
    (0.5, 0.0)
    >>> s, g = square(0.4, 0.8)
    >>> [round(float(v), 12) for v in ratios(s, g)]   # and back
    [0.4, 0.8]
    >>> square(0.25, 0.75, inset=0.01)   # kept off the face, a start for the fit
    (0.5, 0.01)
    """
    x, y = float(x), float(y)
    s = min(max(x + 1.0 - y, S_MIN + inset), 1.0 - inset)
    g = 1.0 - 2.0 * (1.0 - y) / s
    return s, min(max(g, inset), 1.0 - inset)


def ratio_jacobian(s: float, g: float) -> np.ndarray:
    """``d(I1/I3, I2/I3) / d(s, g)``, 2 x 2.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.triangle import ratio_jacobian, ratios
    >>> s, g, h = 0.6, 0.3, 1e-6
    >>> numeric = np.array([np.subtract(ratios(s + h, g), ratios(s - h, g)), np.subtract(ratios(s, g + h), ratios(s, g - h))]).T / (2 * h)
    >>> J = ratio_jacobian(s, g)
    >>> bool(np.allclose(J, numeric)), round(float(np.linalg.det(J)), 12)   # determinant s / 2
    (True, 0.3)
    """
    return np.array([[0.5 * (1.0 + g), 0.5 * s], [-0.5 * (1.0 - g), 0.5 * s]])


def edge_of(s: float, g: float) -> str | None:
    """The edge ``(s, g)`` lies on (:data:`EDGES`' value), or None inside.

    Examples
    --------
    >>> from tumble.analysis.fit.triangle import edge_of
    >>> edge_of(0.5, 0.0), edge_of(1.0, 0.4), edge_of(0.6, 1.0), edge_of(0.5, 0.5)
    ('planar (I1 + I2 = I3)', 'symmetric (I1 = I2)', 'symmetric (I2 = I3)', None)
    """
    if g <= _ON_EDGE:
        return EDGES["planar"]
    if g >= 1.0 - _ON_EDGE:
        return EDGES["I2=I3"]
    if s >= 1.0 - _ON_EDGE:
        return EDGES["I1=I2"]
    if s <= S_MIN * (1 + 1e-6):
        return EDGES["rod"]
    return None


def at_rod_limit(s: float, variance: float) -> bool:
    """Whether a fit's ``s = (I1 + I3 - I2) / I3`` (its statistical ``variance``) lies within one
    standard uncertainty of the rod limit's floor :data:`S_MIN`: the data cannot tell it from the
    rod, as the solver judges its other edges (:func:`~tumble.analysis.fit.solve.snap_to_edges`).
    A fit stopped just short of the floor (a short racquet toss: I1/I3 = 0.006 +- 0.05, where the
    same flight's solve reached the floor when the model's last digits fell otherwise) is no more
    determined than one held on it. An undetermined ``s`` (NaN variance) is not judged here.

    Examples
    --------
    >>> from tumble.analysis.fit.triangle import S_MIN, at_rod_limit
    >>> at_rod_limit(S_MIN + 1e-5, 0.05 ** 2), at_rod_limit(0.13, 0.01 ** 2), at_rod_limit(S_MIN, float("nan"))
    (True, False, False)
    """
    return not math.isnan(variance) and s - S_MIN <= math.sqrt(variance)
