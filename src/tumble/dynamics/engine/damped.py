"""The engine's damped body: a rigid body with a spherical nutation damper (and rotors at constant spin), compiled.

Imported only when a compiled run with a damper is asked for (:func:`tumble.dynamics.engine.front.run_damped`).

**The state** is the internal model's ODE state (:class:`~tumble.dynamics.models.internal.InternalModel`),
11 floats: the total angular momentum ``L`` (kg m^2/s, principal frame), the attitude quaternion
(body to world, scalar last), the damper sphere's rate ``w_d`` (rad/s) and the energy it has
dissipated ``D`` (J). Its right-hand side (:func:`damped_rhs`) is the models' own formulas over
floats, compiled here: the body's rate ``w = (L - h - J w_d) / I``, Euler's equation in momentum
form (:func:`tumble.dynamics.euler.momentum_rate_components`) under the sum of the built-in torque
terms (:func:`tumble.dynamics.engine.kernels.external_torque`), the quaternion kinematics and the
sphere's equation with its dissipation (:func:`tumble.dynamics.models.damper.damper_rate_components`).

**The steppers** are the engine's: the RK4 and RK8 steps written out for this state by
:mod:`~tumble.dynamics.engine.unrolled` (its layout :data:`DAMPED`) and the one fixed-step loop
(:func:`~tumble.dynamics.engine.unrolled.fixed_loop_source`). A damper that relaxes much faster than the
body turns is stiff: ``simulate`` hands it to an implicit solver instead
(:data:`~tumble.dynamics.models.internal.STIFF_RATIO`).

Examples
--------
>>> import numpy as np
>>> from tumble.dynamics.engine.damped import fixed_damped_rk8
>>> y0 = np.array([0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0])   # L = (I3 + J) w, w_d = w = (0, 0, 1)
>>> body = np.array([1.0, 1.5, 1.5, 0.5, 0.2, 0.0, 0.0, 0.0])   # I, J, c, h
>>> Y = np.empty((2, 11))
>>> fixed_damped_rk8(y0, np.array([0.0, 1.0]), body, (0.0,) * 10, 0.0, 0.1, Y)   # a steady spin: nothing to damp
0
>>> round(float(Y[-1, 5]), 12), float(Y[-1, 10])   # turned 1 rad about z: sin(1/2); nothing dissipated
(0.479425538604, 0.0)
"""

from __future__ import annotations

import numpy as np

from ...jit import jit
from ..euler import momentum_rate_components
from ..models.damper import damper_rate_components
from ..special.quaternion import quaternion_rate_components
from .kernels import _direction, _finite, external_torque, generated
from .status import NON_FINITE, OK
from .stepsize import equal_steps
from .tableau import DOP853_A, DOP853_B, DOP853_C, RK4_A, RK4_B, RK4_C
from .unrolled import Layout, fixed_loop_source, fixed_step_source, rotations_source

__all__ = ["DAMPED", "damped_rhs", "fixed_damped_rk4", "fixed_damped_rk8"]

#: The damped body's layout: ``rhs(y, B, P, u0, u1)`` over ``(L, q, w_d, D)``, ``B`` the body's tuple.
DAMPED = Layout(11, "I, P", False)

_damper_rate = jit(damper_rate_components, error_model="numpy")


@jit(error_model="numpy", forceinline=True)  # inlined by LLVM at the stages, as kernels.rhs
def damped_rhs(y: tuple[float, ...], B: tuple[float, ...], P: tuple[float, ...], u0: float,
               u1: float) -> tuple[float, ...]:
    """``dy/dt`` of the state ``(L, q, w_d, D)`` (module docstring) of a body ``B = (I1, I2, I3, J, c,
    h1, h2, h3)`` (kg m^2, kg m^2, N m s, kg m^2/s) under the torque terms ``P``, the orbit's
    direction ``(u0, u1, 0)``."""
    L0, L1, L2, x, yq, z, s, d0, d1, d2, _ = y
    J = B[3]
    w0 = (L0 - B[5] - J * d0) / B[0]
    w1 = (L1 - B[6] - J * d1) / B[1]
    w2 = (L2 - B[7] - J * d2) / B[2]
    t0, t1, t2 = external_torque(B, w0, w1, w2, x, yq, z, s, u0, u1, P)
    a0, a1, a2 = momentum_rate_components(L0, L1, L2, w0, w1, w2, t0, t1, t2)
    q0, q1, q2, q3 = quaternion_rate_components(x, yq, z, s, w0, w1, w2)
    e0, e1, e2, e3 = _damper_rate(d0, d1, d2, w0, w1, w2, B[4], J)
    return a0, a1, a2, q0, q1, q2, q3, e0, e1, e2, e3


@jit(error_model="numpy")
def _load(y0: np.ndarray, B: np.ndarray) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """The state tuple of ``y0`` and the body's tuple of ``B`` (:func:`damped_rhs`)."""
    return ((y0[0], y0[1], y0[2], y0[3], y0[4], y0[5], y0[6], y0[7], y0[8], y0[9], y0[10]),
            (B[0], B[1], B[2], B[3], B[4], B[5], B[6], B[7]))


@jit(error_model="numpy")
def _sample(y: tuple[float, ...], B: np.ndarray, Y: np.ndarray, k: int) -> None:
    """The whole state at sample ``k`` (unpacked by :meth:`~tumble.dynamics.models.internal.InternalModel.samples`)."""
    for i in range(11):
        Y[k, i] = y[i]


_STEPS = generated(fixed_step_source("damped_rk4_step", RK4_A, RK4_B, RK4_C, DAMPED)
                   + rotations_source("damped_rk4_turns", RK4_C)
                   + fixed_step_source("damped_rk8_step", DOP853_A[:12, :12], DOP853_B, DOP853_C[:12], DAMPED)
                   + rotations_source("damped_rk8_turns", DOP853_C[:12]), __file__, __name__, inner=True,
                   rhs=damped_rhs)
_RUNS = generated(fixed_loop_source("fixed_damped_rk4", "damped_rk4_step", "damped_rk4_turns", "_load", "_sample", "Y")
                  + fixed_loop_source("fixed_damped_rk8", "damped_rk8_step", "damped_rk8_turns", "_load", "_sample", "Y"),
                  __file__, __name__, _load=_load, _sample=_sample, _equal_steps=equal_steps, _direction=_direction,
                  _finite=_finite, OK=OK, NON_FINITE=NON_FINITE, **_STEPS)
#: The damped body's fixed-step runs (:func:`~tumble.dynamics.engine.unrolled.fixed_loop_source`):
#: ``run(y0, t_eval, B, P, n, step, Y)``, the states at the samples into ``Y`` (len(t_eval), 11).
fixed_damped_rk4, fixed_damped_rk8 = _RUNS["fixed_damped_rk4"], _RUNS["fixed_damped_rk8"]
