"""The closed loop's right-hand side under the built-in models, compiled: its terms and its source.

Imported only when a compiled closed loop is asked for (by
:mod:`~tumble.dynamics.control.control_kernel` and :mod:`~tumble.dynamics.control.compiled_loop`);
every function is compiled at import by :func:`tumble.jit.jit` (``cache=True``).

**The state** ``y = (q, omega, s, impulse)`` of :mod:`~tumble.dynamics.control.controlled`, a tuple
of ``10 + k`` floats for ``k`` wheel slots (the run's wheels, then the slots it leaves empty): the
attitude quaternion (body to world, scalar last), the angular velocity (rad/s, principal frame),
the wheels' spins relative to the body (rad/s) and the external angular impulse (N m s, world
frame). Its equations

``(I - sum J_j g_j g_j^T) omega' = tau + L x omega - G u``,  ``L = I omega + h``,
``J_j s_j' = u_j - J_j g_j . omega'``,  ``q' = q (x) (omega, 0) / 2``,  ``impulse' = R tau``

are each model's own formula, compiled: the momentum form of Euler's equations
(:func:`~tumble.dynamics.euler.momentum_rate_components`), the kinematics
(:func:`~tumble.dynamics.special.quaternion.quaternion_rate_components`), the rotations
(:func:`~tumble.dynamics.special.quaternion.to_body` in its homogeneous form, ``R^T v`` and, as the
conjugate's, ``R v``: the quaternion is not normalised at the stages, the results divided by
``|q|^2``, which runs beside the rotation instead of before it: ``bench_closed_loop``'s MRP feedback with
three wheels, 60 s, RK8, 112 -> 104 us),
the gravity gradient (:func:`~tumble.dynamics.models.gravity.gradient_components`), the wheels'
applied torque (:func:`~tumble.dynamics.models.actuators.wheel_torque`: limits and friction) and
the fields below.

**The parameters** ``P``, one array of floats held through a hold interval: ``P[0:3]`` the
principal moments ``I`` (kg m^2); ``P[3:12]`` ``(I - sum J g g^T)^-1`` row by row (1/(kg m^2));
``P[12:15]`` the magnetorquers' dipole held (A m^2); ``P[15]`` the field's kind (:data:`FIELD_NONE`
...); ``P[16:20]`` the gravity gradient ``(n, mu, t0, h)``: a circle's mean motion (rad/s) or
``mu`` (m^3/s^2) with the start and spacing (s) of the orbit's position table; ``P[20]`` the
number of wheels; ``P[21:24]`` a constant disturbance torque in the body frame and ``P[24:27]`` one
fixed in the world (N m; the engine's terms of the run's ``torque``,
:func:`~tumble.dynamics.models.torque_protocols.kernel_terms`); ``P[27:30]`` a residual dipole
fixed in the body (A m^2, :class:`~tumble.dynamics.models.dipole.ResidualDipole`), in the
field beside the held one; ``P[30:33]`` the constant momentum ``h_r`` (kg m^2/s, principal frame) of
rotors spinning at constant rates relative to the body, ``L = I omega + h + h_r`` (the gyrostat,
Hughes, *Spacecraft Attitude Dynamics*, sec. 3.4; zero in a controlled run); then ten a wheel (:data:`WHEEL`), in as many slots as the kernel has: its axis (3), inertia ``J`` (kg m^2), torque and speed limits (N m, rad/s),
viscous (N m s) and Coulomb (N m) friction, the Coulomb law's linear band (rad/s) and the
commanded torque held (N m). **The tables** ``X = (fp, ft, gt)``: the field's 16 parameters
(the field's own ``loop_form()``, :func:`~tumble.dynamics.environment.magnetic.field_form`), the IGRF table's and the orbit
position table's coefficients, ``(4, m, 3)`` each; they follow the wheel slots in the same array
(:func:`packed`, :func:`tables`), so that a right-hand side takes one array, not four: a tuple
of three arrays passed to each of a step's stages cost more than the right-hand side itself
(the closed loop's kernel ran in 204 us with ``(P, X)``, 123 us with ``P`` alone; MRP feedback
with three wheels, 60 s, RK8).

**The fields** (one formula each; tests/test_controlled_compiled.py checks each against the
model): :class:`~tumble.dynamics.environment.magnetic.UniformField`; the tilted dipole of
:class:`~tumble.dynamics.environment.magnetic.DipoleField`, ``B = (a/r)^3 (3 (g . r^) r^ - g)`` in the
Earth-fixed frame at the orbit's position, turned to the world frame; and
:class:`~tumble.dynamics.environment.igrf.IGRFField`'s spline blocks
(:meth:`~tumble.dynamics.environment.igrf.IGRFField.tabulate`).

Examples
--------
>>> from tumble.dynamics.control.loop_terms import rhs_source
>>> print(rhs_source("rhs_0", 0).splitlines()[0])
def rhs_0(t, y, P, u0, u1):
"""

from __future__ import annotations

import math

import numpy as np

from ...jit import jit
from ...typing import FloatArray
from ..environment.earth import earth_angle
from ..environment.magnetic import FIELD_DIPOLE, FIELD_NONE, FIELD_TABLE, FIELD_UNIFORM, dipole_components
from ..environment.tabulated import horner
from ..models.actuators import rod_dipole_components, wheel_torque
from ..models.gravity import gradient_components
from ..euler import momentum_rate_components
from ..special.quaternion import quaternion_rate_components, to_body

__all__ = ["BODY", "FIELD_DIPOLE", "FIELD_NONE", "FIELD_TABLE", "FIELD_UNIFORM", "WHEEL", "external_torque",
           "field_body", "field_world", "packed", "rhs_source", "tables"]

#: Floats of ``P`` before the wheels', and a wheel's (module docstring).
BODY, WHEEL = 33, 10

# The models' formulas compiled as ordinary functions, which LLVM inlines where they are called (as
# the engine's kernels do, tumble.dynamics.engine.kernels): the loop ran as fast, and its first
# compile for 3 wheels took 39 CPU-s instead of 59 (measured, loaded machine).
# The functions below that take arrays are compiled without numba's reference counting
# (``_nrt=False``): they read their arrays and make none, and the caller holds them; counted, each
# call to them from a right-hand side stage paid two atomic operations an array.
_horner = jit(horner, error_model="numpy")
_dipole_field = jit(dipole_components, error_model="numpy")
_gravity_gradient = jit(gradient_components, error_model="numpy")
# The wheel law's np.minimum and np.maximum compiled as plain compares (fastmath "nnan", which
# allows nothing else: no reassociation, no contraction, so the same results for every input but
# a NaN): numba's NaN-keeping min and max cost 11 % of the right-hand side (63 -> 56 us for the
# 1452 calls of a 60 s loop with three wheels, measured alternating in one process).
_wheel_torque = jit(wheel_torque, error_model="numpy", fastmath={"nnan"})
#: The rods' dipole for a command (:func:`~tumble.dynamics.models.actuators.rod_dipole_components`), compiled.
rod_dipole = jit(rod_dipole_components, error_model="numpy", inline="always")


@jit(error_model="numpy", _nrt=False)
def table_value(c: FloatArray, t0: float, h: float, t: float) -> tuple[float, float, float]:  # pragma: no cover
    """A :class:`~tumble.dynamics.environment.tabulated.CubicTable` (coefficients ``c``, start ``t0``,
    spacing ``h``, s) at ``t`` (s), by its rule: interval ``floor((t - t0) / h)`` clipped, Horner."""
    i = int(min(max(math.floor((t - t0) / h), 0.0), c.shape[1] - 1.0))
    d = t - (t0 + i * h)
    return (_horner(c[0, i, 0], c[1, i, 0], c[2, i, 0], c[3, i, 0], d),
            _horner(c[0, i, 1], c[1, i, 1], c[2, i, 1], c[3, i, 1], d),
            _horner(c[0, i, 2], c[1, i, 2], c[2, i, 2], c[3, i, 2], d))


@jit(error_model="numpy", _nrt=False)
def dipole(p: FloatArray, e0: float, e1: float, e2: float, c: float,
           s: float) -> tuple[float, float, float]:  # pragma: no cover - compiled
    """The dipole's B (T, world frame) at ``r_eci = (e0, e1, e2)`` (m) with ``(c, s)`` the cosine
    and sine of the Earth's angle: ``r_ecef = R3(theta)^T r_eci``,
    ``B = (a/r)^3 (3 (g . r^) r^ - g)`` there (:func:`~tumble.dynamics.environment.magnetic.dipole_components`),
    turned back to ECI and world."""
    b0, b1, b2 = _dipole_field(p[9], p[10], p[11], c * e0 + s * e1, -s * e0 + c * e1, e2)
    e0, e1, e2 = c * b0 - s * b1, s * b0 + c * b1, b2
    return p[0] * e0 + p[1] * e1 + p[2] * e2, p[3] * e0 + p[4] * e1 + p[5] * e2, p[6] * e0 + p[7] * e1 + p[8] * e2


@jit(error_model="numpy", _nrt=False)
def field_world(kind: int, p: FloatArray, table: FloatArray, t: float) -> tuple[float, float, float]:  # pragma: no cover
    """B (T) in the world frame at ``t`` (s): ``p`` the field's parameters (the Earth's angle at t = 0
    in ``p[12]``), ``table`` the coefficients of a tabulated field (start ``p[0]``, spacing ``p[1]``).

    The dipole: ``r_eci = W^T r_world``, ``r_ecef = R3(theta)^T r_eci``, B in ECEF, then back
    (:meth:`~tumble.dynamics.environment.magnetic.DipoleField.world`, with ``world_from_ecef = W R3(theta)`` applied in two factors)."""
    if kind == FIELD_NONE:
        return 0.0, 0.0, 0.0
    if kind == FIELD_UNIFORM:
        return p[0], p[1], p[2]
    if kind == FIELD_TABLE:
        return table_value(table, p[0], p[1], t)
    nt = p[15] * t
    r0, r1 = p[14] * math.cos(nt), p[14] * math.sin(nt)  # the orbit's position, world frame (z = 0)
    theta = earth_angle(p[12], t * p[13])  # p[13]: 1 if the Earth turns, else 0
    return dipole(p, p[0] * r0 + p[3] * r1, p[1] * r0 + p[4] * r1, p[2] * r0 + p[5] * r1, math.cos(theta), math.sin(theta))


@jit(error_model="numpy", _nrt=False)
def field_body(kind: int, p: FloatArray, table: FloatArray, x: float, y: float, z: float, s: float,
               t: float) -> tuple[float, float, float]:  # pragma: no cover
    """B (T) in the body frame of the quaternion ``(x, y, z, s)`` at ``t`` (s): ``R^T B_world``, times
    ``|q|^2`` where the quaternion is not normalised (:func:`~tumble.dynamics.special.quaternion.to_body`'s
    homogeneous form)."""
    b0, b1, b2 = field_world(kind, p, table, t)
    return to_body(x, y, z, s, b0, b1, b2)


def packed(P: FloatArray, X: tuple[FloatArray, ...]) -> FloatArray:
    """The parameters ``P`` and the tables ``X = (fp, ft, gt)`` in one array (module docstring):
    ``P``, then the sizes ``(len(fp), m_ft, m_gt)``, then ``fp``, ``ft`` and ``gt`` flattened
    (:func:`tables` takes them back).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.loop_terms import packed, tables
    >>> X = (np.arange(16.0), np.ones((4, 2, 3)), np.zeros((4, 1, 3)))
    >>> flat = packed(np.zeros(27), X)
    >>> flat.shape, [a.shape for a in tables(flat, 27)]
    ((82,), [(16,), (4, 2, 3), (4, 1, 3)])
    """
    fp, ft, gt = (np.asarray(a, dtype=float) for a in X)
    sizes = (len(fp), ft.shape[1], gt.shape[1])
    return np.concatenate([np.asarray(P, dtype=float).ravel(), sizes, fp, ft.ravel(), gt.ravel()])


@jit(error_model="numpy", inline="always")
def tables(P: FloatArray, at: int) -> tuple[FloatArray, FloatArray, FloatArray]:  # pragma: no cover - compiled
    """The tables ``(fp, ft, gt)`` of a parameter array :func:`packed` made, whose tables start at
    ``at`` (after ``P``): views, not copies. Inlined where it is called, so that its views are
    counted as the caller counts (not at all in a right-hand side)."""
    nf, m1, m2 = int(P[at]), int(P[at + 1]), int(P[at + 2])
    a = at + 3
    b = a + nf
    c = b + 12 * m1
    return P[a:b], P[b:c].reshape((4, m1, 3)), P[c:c + 12 * m2].reshape((4, m2, 3))


@jit(error_model="numpy", inline="always", _nrt=False)
def external_torque(t: float, x: float, y: float, z: float, s: float, inverse: float, P: FloatArray, at: int,
                    u0: float, u1: float) -> tuple[float, float, float]:  # pragma: no cover
    """The external torque (N m, body frame) at ``t`` (s) on the attitude quaternion ``(x, y, z,
    s)``, not necessarily normalised, ``inverse`` being ``1 / |q|^2``: the held dipole's ``m x B``
    and the gravity gradient ``3 n^2 r_b x (I r_b)`` (module docstring), a circular orbit's
    direction being ``(u0, u1, 0) = (cos n t, sin n t, 0)``; the tables from ``P[at]`` on
    (:func:`tables`). ``R^T v`` is read through :func:`~tumble.dynamics.special.quaternion.to_body`'s
    homogeneous form, ``|q|^2`` times the unit quaternion's, so the dipole's torque is multiplied
    by ``inverse`` and the gradient, quadratic in ``r_b``, by its square (as the engine's,
    :func:`tumble.dynamics.engine.kernels.external_torque`); and the constant disturbances of
    ``P[21:27]``, in the body and turned from the world as the engine turns them, and the
    residual dipole ``P[27:30]`` beside the held one."""
    a0, a1, a2 = P[21], P[22], P[23]
    if P[24] != 0.0 or P[25] != 0.0 or P[26] != 0.0:
        v0, v1, v2 = to_body(x, y, z, s, P[24], P[25], P[26])
        a0, a1, a2 = a0 + v0 * inverse, a1 + v1 * inverse, a2 + v2 * inverse
    if P[15] != FIELD_NONE:
        fp, ft, _ = tables(P, at)
        b0, b1, b2 = field_body(int(P[15]), fp, ft, x, y, z, s, t)
        m0, m1, m2 = (P[12] + P[27]) * inverse, (P[13] + P[28]) * inverse, (P[14] + P[29]) * inverse
        a0, a1, a2 = a0 + (m1 * b2 - m2 * b1), a1 + (m2 * b0 - m0 * b2), a2 + (m0 * b1 - m1 * b0)
    if P[16] > 0.0:  # a circle: r_b = R^T (cos n t, sin n t, 0)
        v0, v1, v2 = to_body(x, y, z, s, u0, u1, 0.0)
        g0, g1, g2 = _gravity_gradient(P[16] * P[16] * (inverse * inverse), P[0], P[1], P[2], v0, v1, v2)
        a0, a1, a2 = a0 + g0, a1 + g1, a2 + g2
    elif P[17] > 0.0:  # along a table of positions: r_b = R^T r / |r|, rate sqrt(mu / r^3)
        v0, v1, v2 = table_value(tables(P, at)[2], P[18], P[19], t)
        rn = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
        v0, v1, v2 = to_body(x, y, z, s, v0 / rn, v1 / rn, v2 / rn)
        n_r = math.sqrt(P[17] / rn) / rn
        g0, g1, g2 = _gravity_gradient(n_r * n_r * (inverse * inverse), P[0], P[1], P[2], v0, v1, v2)
        a0, a1, a2 = a0 + g0, a1 + g1, a2 + g2
    return a0, a1, a2


def rhs_source(name: str, k: int) -> str:
    """The source of ``name(t, y, P, u0, u1)``: the closed loop's right-hand side (module
    docstring) with ``k`` wheel slots, its tables after them in ``P`` (:func:`packed`), written out wheel by wheel, ``(u0, u1)`` a circular orbit's
    direction ``(cos n t, sin n t)``; it returns ``dy/dt`` as a tuple of ``10 + k`` floats. The
    slots past the run's wheel count ``P[20]`` are skipped (their spins' rates are 0), so one
    source serves every count up to ``k``.

    Examples
    --------
    >>> from tumble.dynamics.control.loop_terms import rhs_source
    >>> rhs_source("rhs_3", 3).count("_wheel_torque(")
    3
    """
    lines = [f"def {name}(t, y, P, u0, u1):",
             "    x, yq, z, c = y[0], y[1], y[2], y[3]",
             "    inverse = 1.0 / (x * x + yq * yq + z * z + c * c)",
             "    w0, w1, w2 = y[4], y[5], y[6]",
             f"    t0, t1, t2 = external_torque(t, x, yq, z, c, inverse, P, {BODY + WHEEL * k}, u0, u1)",
             "    a0, a1, a2 = t0, t1, t2",
             "    L0, L1, L2 = P[0] * w0 + P[30], P[1] * w1 + P[31], P[2] * w2 + P[32]",
             "    count = P[20]"]
    for j in range(k):
        b = BODY + WHEEL * j
        lines += [f"    u{j} = 0.0",
                  f"    if count > {j}:",
                  f"        u{j} = _wheel_torque(P[{b + 9}], y[{7 + j}], P[{b + 4}], P[{b + 5}], P[{b + 6}], P[{b + 7}], "
                  f"P[{b + 8}])",
                  f"        js = P[{b + 3}] * y[{7 + j}]",
                  f"        L0, L1, L2 = L0 + js * P[{b}], L1 + js * P[{b + 1}], L2 + js * P[{b + 2}]",
                  f"        a0, a1, a2 = a0 - u{j} * P[{b}], a1 - u{j} * P[{b + 1}], a2 - u{j} * P[{b + 2}]"]
    lines += ["    a0, a1, a2 = momentum_rate_components(L0, L1, L2, w0, w1, w2, a0, a1, a2)",
              "    d0 = P[3] * a0 + P[4] * a1 + P[5] * a2",
              "    d1 = P[6] * a0 + P[7] * a1 + P[8] * a2",
              "    d2 = P[9] * a0 + P[10] * a1 + P[11] * a2",
              "    q0, q1, q2, q3 = quaternion_rate_components(x, yq, z, c, w0, w1, w2)",
              "    i0, i1, i2 = to_body(-x, -yq, -z, c, t0, t1, t2)",  # R t: the conjugate's R^T, times |q|^2
              "    i0, i1, i2 = i0 * inverse, i1 * inverse, i2 * inverse"]
    for j in range(k):
        b = BODY + WHEEL * j
        lines += [f"    s{j} = 0.0",
                  f"    if count > {j}:",
                  f"        s{j} = u{j} / P[{b + 3}] - (P[{b}] * d0 + P[{b + 1}] * d1 + P[{b + 2}] * d2)"]
    lines.append(f"    return (q0, q1, q2, q3, d0, d1, d2, {''.join(f's{j}, ' for j in range(k))}i0, i1, i2)")
    return "\n".join(lines) + "\n"


def rhs_namespace() -> dict[str, object]:
    """What a generated right-hand side calls, by name (its globals once compiled).

    Examples
    --------
    >>> from tumble.dynamics.control.loop_terms import rhs_namespace
    >>> sorted(rhs_namespace())[:3]
    ['__name__', '_wheel_torque', 'external_torque']
    """
    return {"__name__": __name__, "math": math, "np": np, "external_torque": external_torque, "_wheel_torque": _wheel_torque,
            "momentum_rate_components": momentum_rate_components,
            "quaternion_rate_components": quaternion_rate_components, "to_body": to_body}
