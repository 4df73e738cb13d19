"""The closed-loop equations under the built-in models, compiled: one hold interval in numba.

:meth:`ControlKernel.advance` integrates one zero-order-hold interval of the controlled
equations of :mod:`tumble.dynamics.control.controlled` (quaternion, omega, wheel spins, external impulse)
for :func:`~tumble.dynamics.control.controlled.simulate_controlled`, over plain arrays, compiled by numba
on first use (``cache=True``). The B-dot batch's kernel, which shares the field with it, is
:mod:`~tumble.dynamics.control.compiled_detumble`.

**Why compiled, and which scheme.** The Python path calls scipy's ``solve_ivp`` once per control
period, ~1 ms of Python overhead per interval and ~0.1 ms per right-hand side: a two-orbit
detumble (11,400 one-second periods) took 41 s. No library offers an ODE solver callable from
numba's compiled code, so :meth:`ControlKernel.advance` is scipy's DOP853 written out: the Dormand-Prince 8(5,3)
pair of Hairer, Norsett & Wanner, *Solving Ordinary Differential Equations I*, 2nd ed., sec. II.10
(coefficients taken from :class:`scipy.integrate.DOP853`, which copies them from Hairer's
Fortran code), with scipy's error norm (the 5th- and 3rd-order estimates combined, RMS norm with
``scale = atol + rtol max(|y|, |y_new|)``), its step control (safety 0.9, factors in [0.2, 10],
no growth after a rejection) and its starting step (``select_initial_step``, HNW sec. II.4).
So both paths take the same steps and agree to round-off, not only to the tolerance (tested);
an adaptive scheme also follows the wheels' Coulomb friction through zero speed (linear below
``limit_cycle_speed``, as in the Python path).

**The built-in models written out** (one formula each; the numpy versions are the references,
and tests/test_controlled_compiled.py checks each against it to round-off):

- the field: :class:`~tumble.dynamics.environment.magnetic.UniformField`, or the tilted dipole of
  :class:`~tumble.dynamics.environment.magnetic.DipoleField`, ``B = (a/r)^3 (3 (g . r^) r^ - g)`` in the
  Earth-fixed frame at the orbit's position, turned to the world frame (:func:`field_params`), or
  :class:`~tumble.dynamics.environment.igrf.IGRFField`'s spline blocks (:meth:`~tumble.dynamics.environment.igrf.IGRFField.tabulate`);
- the gravity gradient ``3 n^2 r_b x (I r_b)`` of a circular orbit
  (:class:`~tumble.dynamics.models.gravity.GravityGradient`), or with ``n^2 = mu / r^3`` along a
  Keplerian or TLE orbit (:class:`~tumble.dynamics.models.orbit_gravity.OrbitGravityGradient`), ``r(t)``
  from :func:`~tumble.dynamics.environment.tabulated.position_table` (~1e-12 of r: the paths agree to
  ~1e-11 there); with the field's ``m x B`` the external torque whose world-frame value is the impulse's rate;
- the wheels' applied torque (:meth:`~tumble.dynamics.models.actuators.ReactionWheels.applied_torque`:
  torque limit, speed limit, viscous and Coulomb friction).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from typing import Any, cast

import numpy as np

from ...typing import FloatArray
from ..environment.earth import OMEGA_EARTH
from ..environment.magnetic import IGRF_RADIUS
from ..engine.stepsize import error_norm as _error_norm  # the engine's step control, compiled in _compiled()
from ..engine.stepsize import first_trial_step as _first_trial_step
from ..engine.stepsize import initial_step as _initial_step
from ..engine.stepsize import next_step as _next_step
from ..engine.stepsize import rms as _rms
from ..models.actuators import wheel_torque as _wheel_torque  # the model's formula, compiled in _compiled()
from ..models.gravity import gradient_components as _gravity_gradient  # the model's formula, compiled in _compiled()
from ..environment.tabulated import horner as _horner
from ..special.quaternion import to_body as _to_body  # compiled in _compiled()

__all__ = ["FIELD_DIPOLE", "FIELD_NONE", "FIELD_TABLE", "FIELD_UNIFORM", "ControlKernel", "compiled_control_models",
           "field_params"]

#: Kinds of field the kernels evaluate: none, uniform, the tilted dipole, a CubicTable (IGRF).
FIELD_NONE, FIELD_UNIFORM, FIELD_DIPOLE, FIELD_TABLE = 0, 1, 2, 3
#: An empty table (the kernels' argument where there is none).
_NO_TABLE = np.zeros((4, 1, 3))


def field_params(field: Any) -> tuple[int, FloatArray]:
    """``(kind, parameters)`` of a built-in field for the kernels (ValueError for any other).

    The parameters (16 floats): for a uniform field ``B`` (T) in the first three; for the dipole
    the world-from-ECI matrix (9, row by row), the Gauss vector ``g`` (3, T), ``gmst0`` (rad),
    1 if the Earth turns else 0, the orbit radius (m) and mean motion (rad/s); for an
    :class:`~tumble.dynamics.environment.igrf.IGRFField` the start (0 s) and knot spacing (s) of its
    table (:meth:`~tumble.dynamics.environment.igrf.IGRFField.tabulate`, passed apart).

    Examples
    --------
    >>> from tumble.dynamics.environment.magnetic import UniformField
    >>> from tumble.dynamics.control.compiled_control import FIELD_UNIFORM, field_params
    >>> kind, p = field_params(UniformField((0.0, 0.0, 3e-5)))
    >>> kind == FIELD_UNIFORM, p[:3].tolist()
    (True, [0.0, 0.0, 3e-05])
    """
    from ..environment.igrf import IGRFField
    from ..environment.magnetic import DipoleField, UniformField

    p = np.zeros(16)
    if field is None:
        return FIELD_NONE, p
    if type(field) is UniformField:
        p[:3] = field.vector
        return FIELD_UNIFORM, p
    if type(field) is DipoleField:
        p[:9] = field.world_from_eci.reshape(9)
        p[9:12] = field.gauss_vector
        p[12:16] = (field.gmst0, 1.0 if field.earth_rotation else 0.0, field.orbit.radius, field.orbit.mean_motion)
        return FIELD_DIPOLE, p
    if type(field) is IGRFField:
        p[:2] = (0.0, field.step)
        return FIELD_TABLE, p
    raise ValueError(f"field = {field!r} is not a built-in field (DipoleField, UniformField, IGRFField): the compiled path "
                     "cannot evaluate it; use compiled=False")


def _table(c: FloatArray, t0: float, h: float, t: float) -> tuple[float, float, float]:  # pragma: no cover
    """A :class:`~tumble.dynamics.environment.tabulated.CubicTable` (coefficients ``c``, start ``t0``,
    spacing ``h``, s) at ``t`` (s), by its rule: interval ``floor((t - t0) / h)`` clipped, Horner."""
    i = int(min(max(math.floor((t - t0) / h), 0.0), c.shape[1] - 1.0))
    d = t - (t0 + i * h)
    return (_horner(c[0, i, 0], c[1, i, 0], c[2, i, 0], c[3, i, 0], d),
            _horner(c[0, i, 1], c[1, i, 1], c[2, i, 1], c[3, i, 1], d),
            _horner(c[0, i, 2], c[1, i, 2], c[2, i, 2], c[3, i, 2], d))


def _field_world(kind: int, p: FloatArray, table: FloatArray, gmst0: float, t: float,
                 out: FloatArray) -> None:  # pragma: no cover
    """B (T) in the world frame at ``t`` (s) into ``out``; ``gmst0`` the Earth's angle at t = 0 (rad),
    ``table`` the coefficients of a tabulated field (start ``p[0]``, spacing ``p[1]``).

    The dipole: ``r_eci = W^T r_world``, ``r_ecef = R3(theta)^T r_eci``, B in ECEF, then back
    (:meth:`DipoleField.world`, with ``world_from_ecef = W R3(theta)`` applied in two factors)."""
    if kind == FIELD_NONE:
        out[0], out[1], out[2] = 0.0, 0.0, 0.0
        return
    if kind == FIELD_UNIFORM:
        out[0], out[1], out[2] = p[0], p[1], p[2]
        return
    if kind == FIELD_TABLE:
        out[0], out[1], out[2] = _table(table, p[0], p[1], t)
        return
    nt = p[15] * t
    r0, r1 = p[14] * math.cos(nt), p[14] * math.sin(nt)  # the orbit's position, world frame (z = 0)
    theta = gmst0 + OMEGA_EARTH * t * p[13]
    out[0], out[1], out[2] = _dipole(p, p[0] * r0 + p[3] * r1, p[1] * r0 + p[4] * r1, p[2] * r0 + p[5] * r1,
                                     math.cos(theta), math.sin(theta))


def _dipole(p: FloatArray, e0: float, e1: float, e2: float, c: float,
            s: float) -> tuple[float, float, float]:  # pragma: no cover - compiled
    """The dipole's B (T, world frame) at ``r_eci = (e0, e1, e2)`` (m) with ``(c, s)`` the cosine
    and sine of the Earth's angle: ``r_ecef = R3(theta)^T r_eci``,
    ``B = (a/r)^3 (3 (g . r^) r^ - g)`` there (:meth:`DipoleField.ecef`), turned back to ECI and world."""
    x0, x1, x2 = c * e0 + s * e1, -s * e0 + c * e1, e2
    rn = math.sqrt(x0 * x0 + x1 * x1 + x2 * x2)
    u0, u1, u2 = x0 / rn, x1 / rn, x2 / rn
    g0, g1, g2 = p[9], p[10], p[11]
    f = IGRF_RADIUS / rn
    f = f * f * f
    gu = 3.0 * (u0 * g0 + u1 * g1 + u2 * g2)
    b0, b1, b2 = f * (gu * u0 - g0), f * (gu * u1 - g1), f * (gu * u2 - g2)
    e0, e1, e2 = c * b0 - s * b1, s * b0 + c * b1, b2
    return p[0] * e0 + p[1] * e1 + p[2] * e2, p[3] * e0 + p[4] * e1 + p[5] * e2, p[6] * e0 + p[7] * e1 + p[8] * e2


def _field_body(kind: int, p: FloatArray, table: FloatArray, q: FloatArray, t: float,
                out: FloatArray) -> None:  # pragma: no cover
    """B (T) in the body frame of the unit quaternion ``q`` at ``t`` (s) into ``out``: ``R^T B_world``."""
    _field_world(kind, p, table, p[12], t, out)
    out[0], out[1], out[2] = _to_body(q[0], q[1], q[2], q[3], out[0], out[1], out[2])


def _rhs(t: float, y: FloatArray, I: FloatArray, I_rw_inv: FloatArray, wheels: FloatArray, dipole: FloatArray,
         command: FloatArray, field_kind: int, fp: FloatArray, ft: FloatArray, gp: FloatArray, gt: FloatArray,
         u: FloatArray, out: FloatArray) -> None:  # pragma: no cover - compiled
    """The controlled equations (module docstring of :mod:`tumble.dynamics.control.controlled`) into ``out``.

    ``y = (q, omega, s, impulse)``; ``wheels`` rows ``(g (3), J, u_max, s_max, c_v, c_c)``; ``ft``
    the field's table; ``gp = (n, mu, t0, h)`` the gravity gradient: a circle's mean motion
    (rad/s, > 0) or ``mu`` (m^3/s^2, > 0) with the position table ``gt`` (m; start, spacing, s)."""
    k = wheels.shape[0]
    nq = math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3])
    x, yq, z, c = y[0] / nq, y[1] / nq, y[2] / nq, y[3] / nq
    # R (body to world), Shuster 1993 eq. 161, as controlled._matrix
    r00, r01, r02 = 1.0 - 2.0 * (yq * yq + z * z), 2.0 * (x * yq - z * c), 2.0 * (x * z + yq * c)
    r10, r11, r12 = 2.0 * (x * yq + z * c), 1.0 - 2.0 * (x * x + z * z), 2.0 * (yq * z - x * c)
    r20, r21, r22 = 2.0 * (x * z - yq * c), 2.0 * (yq * z + x * c), 1.0 - 2.0 * (x * x + yq * yq)
    w0, w1, w2 = y[4], y[5], y[6]
    t0, t1, t2 = 0.0, 0.0, 0.0  # external torque, body frame
    if field_kind != FIELD_NONE:
        _field_world(field_kind, fp, ft, fp[12], t, out)  # out as scratch
        v0, v1, v2 = out[0], out[1], out[2]
        b0 = r00 * v0 + r10 * v1 + r20 * v2
        b1 = r01 * v0 + r11 * v1 + r21 * v2
        b2 = r02 * v0 + r12 * v1 + r22 * v2
        t0 += dipole[1] * b2 - dipole[2] * b1
        t1 += dipole[2] * b0 - dipole[0] * b2
        t2 += dipole[0] * b1 - dipole[1] * b0
    if gp[0] > 0.0:  # r_b = R^T (cos n t, sin n t, 0)
        v0, v1 = math.cos(gp[0] * t), math.sin(gp[0] * t)
        g0, g1, g2 = _gravity_gradient(gp[0] * gp[0], I[0], I[1], I[2], r00 * v0 + r10 * v1, r01 * v0 + r11 * v1,
                                       r02 * v0 + r12 * v1)
        t0 += g0
        t1 += g1
        t2 += g2
    elif gp[1] > 0.0:  # r_b = R^T r / |r|, rate sqrt(mu / r^3)
        v0, v1, v2 = _table(gt, gp[2], gp[3], t)
        rn = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
        v0, v1, v2 = v0 / rn, v1 / rn, v2 / rn
        n_r = math.sqrt(gp[1] / rn) / rn  # sqrt(mu / r^3)
        g0, g1, g2 = _gravity_gradient(n_r * n_r, I[0], I[1], I[2], r00 * v0 + r10 * v1 + r20 * v2,
                                       r01 * v0 + r11 * v1 + r21 * v2, r02 * v0 + r12 * v1 + r22 * v2)
        t0 += g0
        t1 += g1
        t2 += g2
    h0, h1, h2 = I[0] * w0, I[1] * w1, I[2] * w2
    a0, a1, a2 = t0, t1, t2
    for j in range(k):
        s = y[7 + j]
        u[j] = _wheel_torque(command[j], s, wheels[j, 4], wheels[j, 5], wheels[j, 6], wheels[j, 7], wheels[j, 8])
        js = wheels[j, 3] * s
        h0 += js * wheels[j, 0]
        h1 += js * wheels[j, 1]
        h2 += js * wheels[j, 2]
        a0 -= u[j] * wheels[j, 0]
        a1 -= u[j] * wheels[j, 1]
        a2 -= u[j] * wheels[j, 2]
    a0 -= w1 * h2 - w2 * h1
    a1 -= w2 * h0 - w0 * h2
    a2 -= w0 * h1 - w1 * h0
    d0 = I_rw_inv[0, 0] * a0 + I_rw_inv[0, 1] * a1 + I_rw_inv[0, 2] * a2
    d1 = I_rw_inv[1, 0] * a0 + I_rw_inv[1, 1] * a1 + I_rw_inv[1, 2] * a2
    d2 = I_rw_inv[2, 0] * a0 + I_rw_inv[2, 1] * a1 + I_rw_inv[2, 2] * a2
    out[0] = 0.5 * (c * w0 + yq * w2 - z * w1)
    out[1] = 0.5 * (c * w1 + z * w0 - x * w2)
    out[2] = 0.5 * (c * w2 + x * w1 - yq * w0)
    out[3] = 0.5 * -(x * w0 + yq * w1 + z * w2)
    out[4], out[5], out[6] = d0, d1, d2
    for j in range(k):
        out[7 + j] = u[j] / wheels[j, 3] - (wheels[j, 0] * d0 + wheels[j, 1] * d1 + wheels[j, 2] * d2)
    out[7 + k] = r00 * t0 + r01 * t1 + r02 * t2
    out[8 + k] = r10 * t0 + r11 * t1 + r12 * t2
    out[9 + k] = r20 * t0 + r21 * t1 + r22 * t2


def _advance(y: FloatArray, t_start: float, t_end: float, rtol: float, atol: float, I: FloatArray,
             I_rw_inv: FloatArray, wheels: FloatArray, dipole: FloatArray, command: FloatArray, field_kind: int,
             fp: FloatArray, ft: FloatArray, gp: FloatArray, gt: FloatArray, A: FloatArray, B: FloatArray, C: FloatArray, E3: FloatArray,
             E5: FloatArray) -> int:  # pragma: no cover - compiled
    """DOP853 from ``t_start`` to ``t_end`` (s) as scipy's ``solve_ivp`` runs it, ``y`` in place;
    0 on success, 1 if the step fell below scipy's smallest (10 ulp of t)."""
    n = y.shape[0]
    stages = B.shape[0]
    u = np.empty(wheels.shape[0])
    K = np.empty((stages + 1, n))
    f, f1, y1, scale = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    err5, err3 = np.empty(n), np.empty(n)
    _rhs(t_start, y, I, I_rw_inv, wheels, dipole, command, field_kind, fp, ft, gp, gt, u, f)
    # the starting step (scipy's select_initial_step, HNW sec. II.4; order 7 of the error estimate)
    interval = abs(t_end - t_start)
    for i in range(n):
        scale[i] = atol + abs(y[i]) * rtol
    d1 = _rms(f, scale)
    h0 = _first_trial_step(_rms(y, scale), d1, interval)
    for i in range(n):
        y1[i] = y[i] + h0 * f[i]
    _rhs(t_start + h0, y1, I, I_rw_inv, wheels, dipole, command, field_kind, fp, ft, gp, gt, u, f1)
    for i in range(n):
        f1[i] -= f[i]
    h_abs = _initial_step(h0, d1, _rms(f1, scale) / h0, interval)
    t = t_start
    while True:  # one accepted step (scipy's RungeKutta._step_impl)
        min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
        h_abs = max(h_abs, min_step)
        rejected = False
        while True:
            if h_abs < min_step:
                return 1
            t_new = t + h_abs
            if t_new - t_end > 0.0:
                t_new = t_end
            h = t_new - t
            h_abs = abs(h)
            for i in range(n):
                K[0, i] = f[i]
            for s in range(1, stages):
                for i in range(n):
                    acc = 0.0
                    for r in range(s):
                        acc += K[r, i] * A[s, r]
                    y1[i] = y[i] + acc * h
                _rhs(t + C[s] * h, y1, I, I_rw_inv, wheels, dipole, command, field_kind, fp, ft, gp, gt, u, K[s])
            for i in range(n):
                acc = 0.0
                for r in range(stages):
                    acc += K[r, i] * B[r]
                y1[i] = y[i] + h * acc
            _rhs(t_new, y1, I, I_rw_inv, wheels, dipole, command, field_kind, fp, ft, gp, gt, u, K[stages])
            for i in range(n):
                scale[i] = atol + max(abs(y[i]), abs(y1[i])) * rtol
                a5, a3 = 0.0, 0.0
                for r in range(stages + 1):
                    a5 += K[r, i] * E5[r]
                    a3 += K[r, i] * E3[r]
                err5[i], err3[i] = a5 / scale[i], a3 / scale[i]
            e5, e3 = 0.0, 0.0
            for i in range(n):
                e5 += err5[i] * err5[i]
                e3 += err3[i] * err3[i]
            accepted, h_abs = _next_step(_error_norm(e5, e3, h_abs, n), h_abs, rejected)
            if accepted:
                break
            rejected = True
        t = t_new
        for i in range(n):
            y[i] = y1[i]
            f[i] = K[stages, i]
        if t - t_end >= 0.0:
            return 0


_HELPERS = ("_horner", "_table", "_dipole", "_field_world", "_field_body", "_gravity_gradient", "_wheel_torque", "_rhs", "_rms",
            "_to_body", "_error_norm", "_next_step", "_first_trial_step", "_initial_step")


@functools.cache
def _compiled(name: str) -> Callable[..., Any]:
    """The function ``name`` compiled by numba on first use, with every helper (the helpers are
    compiled first so that the kernels call compiled code)."""
    from ...jit import jit

    if not _compiled.__dict__.get("helpers"):
        for helper in _HELPERS:
            globals()[helper] = jit(error_model="numpy")(globals()[helper])
        _compiled.__dict__["helpers"] = True
    function = globals()[name]
    return cast("Callable[..., Any]", function if name in _HELPERS else jit(error_model="numpy")(function))


def compiled_control_models(field: Any, gravity_gradient: Any, magnetorquers: Any, wheels: Any) -> str | None:
    """None if every model is a built-in one the kernel evaluates, else the first other one's description.

    Examples
    --------
    >>> from tumble.dynamics.environment.magnetic import UniformField
    >>> from tumble.dynamics.control.compiled_control import compiled_control_models
    >>> compiled_control_models(UniformField((0.0, 0.0, 3e-5)), None, None, None) is None
    True
    >>> compiled_control_models(None, lambda t, w, R: w, None, None)
    'gravity_gradient = <lambda> (a GravityGradient or OrbitGravityGradient)'
    """
    from ..environment.ephemeris import KeplerOrbit, TLEOrbit
    from ..environment.igrf import IGRFField
    from ..environment.magnetic import DipoleField, UniformField
    from ..environment.orbit import CircularOrbit
    from ..models.actuators import Magnetorquers, ReactionWheels
    from ..models.gravity import GravityGradient
    from ..models.orbit_gravity import OrbitGravityGradient

    if type(gravity_gradient) is OrbitGravityGradient and \
            type(gravity_gradient.orbit) not in (CircularOrbit, KeplerOrbit, TLEOrbit):
        return f"gravity_gradient's orbit = {type(gravity_gradient.orbit).__name__} (a CircularOrbit, KeplerOrbit or TLEOrbit)"
    for name, model, kinds in (("field", field, (DipoleField, UniformField, IGRFField)),
                               ("gravity_gradient", gravity_gradient, (GravityGradient, OrbitGravityGradient)),
                               ("magnetorquers", magnetorquers, (Magnetorquers,)),
                               ("wheels", wheels, (ReactionWheels,))):
        if model is not None and type(model) not in kinds:
            label = getattr(model, "__name__", None) or type(model).__name__
            names = [k.__name__ for k in kinds]
            return f"{name} = {label} (a {' or '.join([', '.join(names[:-1]), names[-1]] if names[:-1] else names)})"
    return None


class ControlKernel:
    """The compiled hold-interval integrator with the run's fixed parameters bound.

    Parameters
    ----------
    moments : ndarray, shape (3,)
        Principal moments, kg m^2 (wheels locked).
    I_rw_inv : ndarray, shape (3, 3)
        ``(I - sum J g g^T)^-1``, 1/(kg m^2).
    wheels : ReactionWheels or None
    field : DipoleField, UniformField, IGRFField or None
    gravity_gradient : GravityGradient, OrbitGravityGradient (bound to the moments) or None
    rtol, atol : float
        DOP853's tolerances.
    t_end : float, optional
        End of the run, s: the span of the tables of an IGRF field and of an orbit's position
        (needed with those models).

    Examples
    --------
    A spin about a principal axis, no torque: the rate stays, the attitude turns by ``0.1 t``:

    >>> import numpy as np
    >>> from tumble.dynamics.control.compiled_control import ControlKernel
    >>> kernel = ControlKernel(np.array([1.0, 2.0, 3.0]), np.diag([1.0, 0.5, 1 / 3]), None, None, None, 1e-10, 1e-12)
    >>> y = np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0])
    >>> y = kernel.advance(y, 0.0, 10.0, np.zeros(3), np.zeros(0))
    >>> np.allclose(y[:4], [0.0, 0.0, np.sin(0.5), np.cos(0.5)], rtol=0, atol=1e-10)
    True
    """

    def __init__(self, moments: FloatArray, I_rw_inv: FloatArray, wheels: Any, field: Any, gravity_gradient: Any,
                 rtol: float, atol: float, t_end: float | None = None) -> None:
        from scipy.integrate import DOP853

        from ..environment.tabulated import position_table
        from ..models.orbit_gravity import OrbitGravityGradient

        self.I = np.ascontiguousarray(moments, dtype=float)
        self.I_rw_inv = np.ascontiguousarray(I_rw_inv, dtype=float)
        self.wheels = np.zeros((0, 9)) if wheels is None else np.ascontiguousarray(np.column_stack([
            wheels.axes, wheels.inertia, wheels.max_torque, wheels.max_speed, wheels.viscous, wheels.coulomb,
            wheels.limit_cycle_speed]),
            dtype=float)
        self.field_kind, self.fp = field_params(field)
        tables = self.field_kind == FIELD_TABLE or isinstance(gravity_gradient, OrbitGravityGradient)
        if tables and (t_end is None or not t_end > 0.0):
            raise ValueError(f"t_end = {t_end!r} must be given (s, > 0) with an IGRF field or an orbit's gravity gradient")
        self.ft = field.tabulate(cast(float, t_end)).coefficients if self.field_kind == FIELD_TABLE else _NO_TABLE
        self.gp, self.gt = np.zeros(4), _NO_TABLE
        if isinstance(gravity_gradient, OrbitGravityGradient):
            table = position_table(gravity_gradient.orbit, cast(float, t_end))
            self.gp[1:], self.gt = (gravity_gradient.mu, table.t0, table.step), table.coefficients
        elif gravity_gradient is not None:
            self.gp[0] = gravity_gradient.mean_motion
        # scipy raises rtol below 100 eps to that (with a warning): the same tolerance here
        self.rtol, self.atol = max(float(rtol), 100 * np.finfo(float).eps), float(atol)
        self.tableau = tuple(np.ascontiguousarray(a, dtype=float) for a in
                             (DOP853.A, DOP853.B, DOP853.C, DOP853.E3, DOP853.E5))
        self.kernel = _compiled("_advance")
        self.field_kernel = _compiled("_field_body")

    def field_body(self, q: FloatArray, t: float) -> FloatArray:
        """B (T) in the body frame of the unit quaternion ``q`` (body to world, scalar last) at ``t`` (s).

        Examples
        --------
        A field along world x seen from a body turned by 90 deg about z: along body -y.

        >>> from tumble.dynamics.environment.magnetic import UniformField
        >>> import numpy as np
        >>> from tumble.dynamics.control.compiled_control import ControlKernel
        >>> kernel = ControlKernel(np.ones(3), np.eye(3), None, UniformField((3e-5, 0.0, 0.0)), None, 1e-10, 1e-12)
        >>> c = np.sqrt(0.5)
        >>> np.allclose(kernel.field_body(np.array([0.0, 0.0, c, c]), 0.0), [0.0, -3e-5, 0.0], rtol=0, atol=1e-20)
        True
        """
        out = np.empty(3)
        self.field_kernel(self.field_kind, self.fp, self.ft, np.ascontiguousarray(q, dtype=float), float(t), out)
        return out

    def advance(self, y: FloatArray, t_start: float, t_end: float, dipole: FloatArray, command: FloatArray) -> FloatArray:
        """The state ``(q, omega, s, impulse)`` at ``t_end`` (s) from ``y`` at ``t_start``, the dipole
        (A m^2) and the wheels' commanded torques (N m) held; RuntimeError if the step collapses.

        Examples
        --------
        A dipole of 0.1 A m^2 along x in 3e-5 T along y: 3e-6 N m about z, held for 10 s on a body
        at rest with I3 = 3 kg m^2 (it barely turns): omega_3 = 1e-5 rad/s and the impulse 3e-5 N m s:

        >>> from tumble.dynamics.environment.magnetic import UniformField
        >>> import numpy as np
        >>> from tumble.dynamics.control.compiled_control import ControlKernel
        >>> kernel = ControlKernel(np.array([1.0, 2.0, 3.0]), np.diag([1.0, 0.5, 1 / 3]), None,
        ...                        UniformField((0.0, 3e-5, 0.0)), None, 1e-10, 1e-12)
        >>> y = kernel.advance(np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]), 0.0, 10.0,
        ...                    np.array([0.1, 0.0, 0.0]), np.zeros(0))
        >>> np.allclose(y[4:7], [0.0, 0.0, 1e-5], rtol=1e-6, atol=1e-15), np.allclose(y[7:], [0.0, 0.0, 3e-5], rtol=1e-6)
        (True, True)
        """
        out = np.array(y, dtype=float)
        status = self.kernel(out, float(t_start), float(t_end), self.rtol, self.atol, self.I, self.I_rw_inv,
                             self.wheels, np.ascontiguousarray(dipole, dtype=float),
                             np.ascontiguousarray(command, dtype=float), self.field_kind, self.fp, self.ft,
                             self.gp, self.gt,
                             *self.tableau)
        if status != 0:
            raise RuntimeError(f"the integration failed at t = {t_start} s: the step size fell below 10 ulp of t")
        return out
