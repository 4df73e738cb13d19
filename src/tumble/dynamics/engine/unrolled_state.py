"""Runge-Kutta steps written out from their tableaux for a state of any size: source text.

:mod:`~tumble.dynamics.engine.unrolled` writes the engine's steps for the rigid body's 7-float
state with the orbit's direction turned from stage to stage; a state that carries more than the
body (the closed loop's wheel spins and external impulse,
:mod:`~tumble.dynamics.control.compiled_loop`) needs the same steps over ``n`` floats and a
right-hand side that takes the time: the same generator writes them, over the state's layout
(:func:`~tumble.dynamics.engine.unrolled.state_layout`); these two functions name it for such a
state. Imports no numba.

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

import numpy as np

from . import unrolled
from .unrolled import Coefficients, state_layout

__all__ = ["dop853_sources", "fixed_step_source"]


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
    return unrolled.fixed_step_source(name, A, B, np.asarray(C), state_layout(n))


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
    return unrolled.dop853_sources(state_layout(n), step=step, errors=errors, atol="atol", dense=False)
