"""Least squares for the tensor's models: :func:`fit_held`, Levenberg-Marquardt with some
parameters held (the drags at their bound), one home for the single throw's fit
(:mod:`~tumble.analysis.tensor.throw`) and the joint one (:mod:`~tumble.analysis.tensor.joint`).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.optimize import least_squares

from ...typing import FloatArray

__all__ = ["finite", "fit_held"]


def finite(x: FloatArray, fill: float = 1e3) -> FloatArray:
    """``x`` with its non-finite entries replaced by ``fill``: a step of Levenberg-Marquardt into a
    tensor with no motion (a rod: no inverse) gets residuals far too large (rad/s), so the
    damping takes it back, rather than NaN, which MINPACK cannot step from.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.solve import finite
    >>> finite(np.array([0.1, np.nan, np.inf])).tolist()
    [0.1, 1000.0, 1000.0]
    """
    return np.where(np.isfinite(x), x, fill)


def fit_held(problem: Any, P0: FloatArray, free: np.ndarray, nonnegative: np.ndarray,
             max_nfev: int = 300) -> tuple[FloatArray, np.ndarray]:
    """The least-squares optimum of ``problem`` (its ``residuals(P)`` and ``jacobian(P)``) over the
    ``free`` parameters (the others held at ``P0``'s), by Levenberg-Marquardt (MINPACK's,
    ``x_scale="jac"``), the parameters ``nonnegative`` (indices) held at 0 where they come out
    negative and the rest fitted again (the active set of the bound-constrained problem; Nocedal &
    Wright, *Numerical Optimization*, 2nd ed., sec. 16.5); returns the optimum and the parameters
    left free.

    Examples
    --------
    A line through the origin ``y = a x + b``, ``b`` held non-negative where the data want it below 0:

    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> from tumble.analysis.tensor.solve import fit_held
    >>> x = np.linspace(0.0, 1.0, 11)
    >>> line = SimpleNamespace(residuals=lambda P: P[0] * x + P[1] - (2 * x - 0.1),
    ...                        jacobian=lambda P: np.column_stack([x, np.ones_like(x)]))
    >>> P, free = fit_held(line, np.array([1.0, 0.5]), np.ones(2, bool), np.array([1]))
    >>> P.round(6).tolist(), free.tolist()
    ([1.857143, 0.0], [True, False])
    """
    free = np.asarray(free, bool).copy()

    def solve(start: FloatArray) -> FloatArray:
        P = np.asarray(start, float).copy()

        def full(x: FloatArray) -> FloatArray:
            P[free] = x
            return P

        with np.errstate(all="ignore"):
            sol = least_squares(lambda x: finite(problem.residuals(full(x))), start[free],
                                jac=lambda x: finite(problem.jacobian(full(x))[:, free], 0.0), method="lm",
                                x_scale="jac", max_nfev=max_nfev, ftol=1e-10, xtol=1e-10, gtol=1e-10)
        return full(np.asarray(sol.x)).copy()

    P = solve(np.asarray(P0, float))
    for _ in range(3):
        negative = nonnegative[P[nonnegative] < 0]
        if negative.size == 0:
            break
        free[negative] = False
        P[negative] = 0.0
        P = solve(P)
    return P, free
