"""Vectors tabulated in time as piecewise cubics on uniform knots: the form in which the compiled
closed-loop kernel (:mod:`~tumble.dynamics.control.control_kernel`) reads the IGRF field and an
orbit's position.

A :class:`CubicTable` holds, for each interval ``[t0 + i h, t0 + (i + 1) h)``, the four
coefficients of a cubic per component (scipy's ``PPoly`` layout, highest power first), so that

``f(t) = ((c0 d + c1) d + c2) d + c3``  with  ``i = floor((t - t0) / h)``,  ``d = t - (t0 + i h)``

(Horner's rule, :func:`horner`; ``i`` is clipped to the table, so the end intervals extrapolate).
The coefficients are those of scipy's ``CubicSpline`` through samples of the function
(not-a-knot ends, a few knots beyond each end of the span so that those ends lie outside it).
The same :func:`horner` and the same interval rule evaluate the table in numpy
(:meth:`CubicTable.__call__`) and in the compiled kernel.

**Orbit positions** (:func:`position_table`): the spline's error on ``r(t)`` is about
``(5/384) (h w)^4 |r|`` for an angular rate ``w`` (the cubic spline's bound
``(5/384) h^4 max |f^(4)|``: C. A. Hall & W. W. Meyer, "Optimal error bounds for cubic spline
interpolation", *J. Approx. Theory* 16, 105-122, 1976); the knots are ``h = 0.005 / w_max`` apart
(``w_max`` the rate at perigee, ``h_orbit / r_p^2 = n (1 + e)^2 / (1 - e^2)^(3/2)``), at most 10 s, so that the
relative error stays below 1e-11 (measured: 2e-12 along the ISS's orbit, at 4.4 s; 4e-11 at 10 s).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.interpolate import CubicSpline

from ...typing import ArrayLike, FloatArray
from ...validation import check_positive

__all__ = ["CubicTable", "horner", "position_table", "spline_table"]

#: Extra knots on each side of a spline's span, so that its not-a-knot ends lie outside it.
MARGIN = 4


def horner(c0: Any, c1: Any, c2: Any, c3: Any, d: Any) -> Any:
    """``((c0 d + c1) d + c2) d + c3``: a cubic at ``d`` from its coefficients, highest power first
    (numbers or arrays alike; the compiled kernel calls the same function).

    Examples
    --------
    >>> from tumble.dynamics.environment.tabulated import horner
    >>> horner(1.0, -2.0, 0.5, 3.0, 2.0)   # 8 - 8 + 1 + 3
    4.0
    """
    return ((c0 * d + c1) * d + c2) * d + c3


@dataclass(frozen=True, eq=False)
class CubicTable:
    """A vector function of time as cubics on uniform knots (module docstring).

    Attributes
    ----------
    t0 : float
        Start of the first interval, s.
    step : float
        Knot spacing ``h``, s.
    coefficients : ndarray, shape (4, m, 3)
        Per interval and component, the cubic's coefficients in powers of ``t - t_i`` (s),
        highest first (scipy's ``PPoly.c``).

    Examples
    --------
    ``f(t) = (t^3, t, 1)`` on two intervals of 1 s, the second's coefficients shifted to its knot:

    >>> import numpy as np
    >>> from tumble.dynamics.environment.tabulated import CubicTable
    >>> c = np.zeros((4, 2, 3))
    >>> c[0, :, 0], c[1, 1, 0], c[2, 1, 0], c[3, 1, 0] = 1.0, 3.0, 3.0, 1.0   # (1 + d)^3
    >>> c[2, :, 1], c[3, :, 1], c[3, :, 2] = 1.0, [0.0, 1.0], 1.0
    >>> CubicTable(0.0, 1.0, c)([0.5, 1.5]).tolist()
    [[0.125, 0.5, 1.0], [3.375, 1.5, 1.0]]
    """

    t0: float
    step: float
    coefficients: FloatArray

    def __post_init__(self) -> None:
        c = np.ascontiguousarray(self.coefficients, dtype=float)
        if c.ndim != 3 or c.shape[0] != 4 or c.shape[1] < 1 or c.shape[2] != 3:
            raise ValueError(f"coefficients has shape {c.shape}; it must be (4, m, 3) with m >= 1")
        c.setflags(write=False)
        object.__setattr__(self, "coefficients", c)
        object.__setattr__(self, "t0", float(self.t0))
        object.__setattr__(self, "step", check_positive("step", self.step, "s"))

    @property
    def t_end(self) -> float:
        """End of the last interval, s.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.environment.tabulated import CubicTable
        >>> CubicTable(10.0, 5.0, np.zeros((4, 3, 3))).t_end
        25.0
        """
        return float(self.t0 + self.coefficients.shape[1] * self.step)

    def __call__(self, t: ArrayLike) -> FloatArray:
        """The function at ``t`` (s); shape ``t.shape + (3,)``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.environment.tabulated import CubicTable
        >>> table = CubicTable(0.0, 2.0, np.ones((4, 1, 3)))   # 1 + d + d^2 + d^3
        >>> table(1.0).tolist()
        [4.0, 4.0, 4.0]
        """
        tt = np.asarray(t, float)
        flat = tt.reshape(-1)
        i = np.clip(np.floor((flat - self.t0) / self.step), 0, self.coefficients.shape[1] - 1).astype(int)
        d = (flat - (self.t0 + i * self.step))[:, None]
        c = self.coefficients[:, i, :]
        return np.asarray(horner(c[0], c[1], c[2], c[3], d), float).reshape(tt.shape + (3,))


def spline_table(samples: FloatArray, first: int, step: float) -> FloatArray:
    """Coefficients ``(4, m, 3)`` of scipy's ``CubicSpline`` through ``samples`` (shape
    ``(m + 1 + 2 MARGIN, 3)``) at knots ``(first - MARGIN + j) step`` (s), for the ``m`` intervals
    from knot ``first``: the margins' intervals dropped.

    Examples
    --------
    A cubic is reproduced exactly (not-a-knot ends):

    >>> import numpy as np
    >>> from tumble.dynamics.environment.tabulated import CubicTable, MARGIN, spline_table
    >>> step, first, m = 0.5, 2, 3
    >>> t = (first - MARGIN + np.arange(m + 1 + 2 * MARGIN)) * step
    >>> c = spline_table(np.stack([t**3, t, 0 * t], axis=-1), first, step)
    >>> np.allclose(CubicTable(first * step, step, c)([1.2, 2.0, 2.4]), [[1.728, 1.2, 0.0], [8.0, 2.0, 0.0],
    ...                                                                   [13.824, 2.4, 0.0]])
    True
    """
    knots = (first - MARGIN + np.arange(len(samples))) * float(step)
    return np.asarray(CubicSpline(knots, samples, axis=0).c[:, MARGIN:len(samples) - 1 - MARGIN, :], float)


def position_table(orbit: Any, t_end: float, step: float | None = None) -> CubicTable:
    """The orbit's ``position_world(t)`` (m) tabulated over ``[0, t_end]`` (s) (module docstring).

    Parameters
    ----------
    orbit : CircularOrbit, KeplerOrbit or TLEOrbit
        Gives ``position_world(t)`` (m, vectorised) and ``mean_motion`` (rad/s).
    t_end : float
        End of the span, s (> 0).
    step : float, optional
        Knot spacing, s (default ``0.005 / w_max``, at most 10 s).

    Examples
    --------
    >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
    >>> import numpy as np
    >>> from tumble.dynamics.environment.tabulated import position_table
    >>> orbit = KeplerOrbit(8000e3, 0.1, 1.0)
    >>> table = position_table(orbit, 6000.0)
    >>> t = np.array([0.0, 123.4, 5999.9])
    >>> bool(np.max(np.abs(table(t) - orbit.position_world(t))) < 1e-11 * 8000e3)
    True
    """
    T = check_positive("t_end", t_end, "s")
    n = check_positive("orbit.mean_motion", getattr(orbit, "mean_motion", None), "rad/s")
    e = float(getattr(orbit, "eccentricity", 0.0))
    if step is None:
        step = min(10.0, 0.005 * (1.0 - e * e) ** 1.5 / ((1.0 + e) ** 2 * n))
    h = check_positive("step", step, "s")
    m = max(1, math.ceil(T / h))
    t = (np.arange(m + 1 + 2 * MARGIN) - MARGIN) * h
    return CubicTable(0.0, h, spline_table(np.asarray(orbit.position_world(t), float).reshape(-1, 3), 0, h))
