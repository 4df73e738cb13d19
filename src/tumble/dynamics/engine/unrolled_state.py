"""Runge-Kutta steps written out from their tableaux for a state of any size: source text.

:mod:`~tumble.dynamics.engine.unrolled` writes the engine's steps for the rigid body's 7-float
state with the orbit's direction turned from stage to stage; a state that carries more than the
body (the closed loop's wheel spins and external impulse,
:mod:`~tumble.dynamics.control.compiled_loop`) needs the same steps over ``n`` floats and a
right-hand side that takes the time. This module writes them, with the same pieces (the
weighted sums of :func:`~tumble.dynamics.engine.unrolled._weighted`, in scipy's stage order)
from the same tableaux (:mod:`~tumble.dynamics.engine.tableau`): straight-line code over
tuples, every coefficient a literal, which numba keeps in registers. Imports no numba.

Every generated function calls ``rhs(t, y, P, X, u0, u1)``: the time (s), the state (an
``n``-tuple), the run's parameters ``P`` (a tuple of floats), its tables ``X`` (a tuple of
arrays) and a circular orbit's direction ``(u0, u1) = (cos n t, sin n t)`` at the stage: turned
from the step's start ``(cs, ss)`` by ``rot`` (the turns to the stage nodes,
:func:`~tumble.dynamics.engine.unrolled.rotations_source`), as the engine's steps do, so that a
step makes no trigonometric call of its own.

Examples
--------
>>> from tumble.dynamics.engine.tableau import RK4_A, RK4_B, RK4_C
>>> from tumble.dynamics.engine.unrolled_state import fixed_step_source
>>> print(fixed_step_source("rk4_step", 2, RK4_A, RK4_B, RK4_C).splitlines()[0])
def rk4_step(t, y, h, P, X, cs, ss, rot):
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .tableau import DOP853_A, DOP853_B, DOP853_C
from .unrolled import Coefficients, _weighted, dop853_errors_lines

__all__ = ["dop853_sources", "fixed_step_source"]


def _advanced(n: int, weights: Coefficients, stages: Sequence[str], y: str = "y") -> str:
    """The state ``y + h sum_r w_r k_r`` over ``n`` components, as a tuple literal."""
    return "(" + ", ".join(f"{y}[{i}] + h * ({_weighted(weights, stages, i)})" for i in range(n)) + ",)"


def _stage(n: int, s: int, A: np.ndarray, C: Coefficients, state: str = "") -> str:
    """The lines of stage ``s``: the orbit's direction at its node, and its slope ``k{s}`` there from
    the slopes before it (or at ``state``)."""
    node = "t" if C[s] == 0.0 else f"t + {float(C[s])!r} * h"
    state = state or ("y" if s == 0 else _advanced(n, A[s, :s], [f"k{r}" for r in range(s)]))
    return (f"    u0 = cs * rot[{2 * s}] - ss * rot[{2 * s + 1}]\n    u1 = ss * rot[{2 * s}] + cs * rot[{2 * s + 1}]\n"
            f"    k{s} = rhs({node}, {state}, P, X, u0, u1)")


def fixed_step_source(name: str, n: int, A: np.ndarray, B: np.ndarray, C: Coefficients) -> str:
    """The source of ``name(t, y, h, P, X, cs, ss, rot)``: one step of the explicit tableau
    ``(A, B, C)`` from ``t`` (s) over a state of ``n`` floats; returns the new state.

    Examples
    --------
    >>> from tumble.dynamics.engine.tableau import DOP853_A, DOP853_B, DOP853_C
    >>> from tumble.dynamics.engine.unrolled_state import fixed_step_source
    >>> fixed_step_source("rk8_step", 13, DOP853_A[:12, :12], DOP853_B, DOP853_C[:12]).count("rhs(")   # 12 stages
    12
    """
    lines = [f"def {name}(t, y, h, P, X, cs, ss, rot):"] + [_stage(n, s, A, C) for s in range(len(B))]
    lines.append(f"    return {_advanced(n, B, [f'k{r}' for r in range(len(B))])}")
    return "\n".join(lines) + "\n"


def dop853_sources(step: str, errors: str, n: int) -> str:
    """The sources of DOP853's step and error estimate over ``n`` floats (Hairer, Norsett &
    Wanner, *Solving ODEs I*, 2nd ed., sec. II.10, in scipy's arrangement,
    :class:`scipy.integrate.DOP853`), as :func:`~tumble.dynamics.engine.unrolled.dop853_sources`
    writes them for the rigid body:

    - ``step(t, y, k0, h, P, X, cs, ss, rot)``: from the slope ``k0`` at ``y``, the 11 other stages
      and the new state's slope; returns ``(y_new, K)`` with ``K`` the 13 slopes;
    - ``errors(K, y, y_new, rtol, atol)``: the sums of squares of the scaled 5th- and 3rd-order
      error estimates, ``scale = atol + rtol max(|y|, |y_new|)`` (``atol`` one float).

    Examples
    --------
    >>> from tumble.dynamics.engine.unrolled_state import dop853_sources
    >>> source = dop853_sources("step", "errors", 10)
    >>> source.count("rhs(")   # 11 stages (the first is the last step's), the new state's slope
    12
    """
    slopes = [f"k{r}" for r in range(13)]
    lines = [f"def {step}(t, y, k0, h, P, X, cs, ss, rot):"] + [_stage(n, s, DOP853_A, DOP853_C) for s in range(1, 12)]
    lines += [f"    y_new = {_advanced(n, DOP853_B, slopes[:12])}", _stage(n, 12, DOP853_A, DOP853_C, "y_new"),
              f"    return y_new, ({', '.join(slopes)})", "", *dop853_errors_lines(errors, n, "atol")]
    return "\n".join(lines) + "\n"
