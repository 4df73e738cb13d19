"""The B-dot batch of :func:`tumble.dynamics.control.detumble.detumble_batch`, compiled: each body's whole run in numba.

Imported only when the compiled batch is asked for; compiled at import by :func:`tumble.jit.jit`
(``cache=True``), as the engine's kernels are: one body's run (:func:`_body`), over the bodies on
one thread (:func:`detumble_serial`) or on every core (:func:`detumble_parallel`). Each step is
the engine's RK4 step, written out by its generator from the tableau
(:func:`~tumble.dynamics.engine.unrolled.fixed_step_source`, as the closed loop's steps are), not
a loop of its own; the control loop around it (readings, law, held dipole, the orbit's share of
the field computed once for the batch) is the batch's.

The numpy path of :func:`~tumble.dynamics.control.detumble.detumble_batch` is vectorised over the
bodies: one RK4 stage is some fifty numpy operations on arrays of N, bound by memory traffic.
Here each body runs through every control step in compiled code with its state in registers,
the bodies spread over every core from :data:`~tumble.jit.PARALLEL_BODIES`
(``numba.prange``; the same arithmetic for each body either way). The arithmetic is that of the
numpy path, step by step (the numpy path is the reference: tests/test_controlled_compiled.py
checks the two agree to round-off), with these formulas:

- the sensors: the gyro reads ``(omega + bias) + noise``, the magnetometer ``(B + bias) + noise``
  (:meth:`~tumble.dynamics.models.sensors.Sensors.sample`), the noise drawn in numpy and passed in
  a control step at a time;
- the gyro B-dot dipole ``-k (B x omega)`` of the readings, ``k = gain / |B|^2`` normalised
  (:func:`~tumble.dynamics.control.bdot.bdot_dipole`), clipped rod by rod
  (:meth:`~tumble.dynamics.models.actuators.Magnetorquers.saturate`), checked against them;
- ``I omega' = m x B + tau_gg - omega x I omega`` and ``q' = q (x) (omega, 0) / 2``: the one writing
  of each (:func:`~tumble.dynamics.euler.euler_components`,
  :func:`~tumble.dynamics.special.quaternion.quaternion_rate_components`), compiled here and
  called on arrays by the numpy path's ``_rhs``; the Earth's turn
  (:func:`~tumble.dynamics.environment.earth.earth_angle`) likewise;
- the gravity gradient ``3 n^2 r_b x (I r_b)`` of the circular orbit and the field: the
  functions of :mod:`~tumble.dynamics.control.loop_terms` (one compiled formula for the batch and
  the closed loop), with what all bodies share (the orbit's position in ECI and the
  Earth's turn since t = 0 at each RK4 node) computed once for the batch, and each body's
  sidereal angle ``gmst0 + omega_E t`` by the angle-addition formulas (a round-off apart from
  the numpy path's ``cos(gmst0 + omega_E t)``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, cast

import numpy as np
from numba import prange

from ...jit import PARALLEL_BODIES, cores, jit
from ...typing import FloatArray
from ..environment.earth import earth_angle
from ..euler import euler_components
from ..special.quaternion import quaternion_rate_components, to_body
from ..engine.tableau import RK4_A, RK4_B, RK4_C
from ..engine.unrolled import fixed_step_source, state_layout
from .loop_terms import _gravity_gradient, dipole as _dipole, rod_dipole

__all__ = ["detumble_parallel", "detumble_run", "detumble_serial"]

# the formulas, each the one writing its model's module holds, compiled
_euler = jit(euler_components, error_model="numpy")


@jit(error_model="numpy")
def _bdot(b0: float, b1: float, b2: float, w0: float, w1: float, w2: float, gain: float, normalized: bool,
          axes: FloatArray, limit: FloatArray) -> tuple[float, float, float]:  # pragma: no cover - compiled
    """The gyro B-dot dipole ``-k (B x omega)`` (``k = gain / |B|^2`` normalised), clipped rod by
    rod (:func:`bdot_dipole`, :meth:`Magnetorquers.saturate`), A m^2."""
    k = gain / (b0 * b0 + b1 * b1 + b2 * b2) if normalized else gain
    m0 = -k * (b1 * w2 - b2 * w1)
    m1 = -k * (b2 * w0 - b0 * w2)
    m2 = -k * (b0 * w1 - b1 * w0)
    return rod_dipole(axes, limit, m0, m1, m2)  # axes: the rods' (k, 6) rows, Magnetorquers.rods


@jit(error_model="numpy")
def _orbit_table(fp: FloatArray, n_gg: float, period: float, step0: int, steps: int,
                 substeps: int) -> FloatArray:  # pragma: no cover
    """What every body of a batch shares at each RK4 node: ``r_eci`` (m), ``cos, sin(omega_E t)``
    (the Earth always turns in the batch, whatever the field's ``earth_rotation``, as in the numpy path)
    and the gravity gradient's radius direction ``cos, sin(n_gg t)`` (world frame); node ``(i, 0)`` at
    ``t = (step0 + i) period``, ``(i, 2 j + 1)`` and ``(i, 2 j + 2)`` the middle and end of substep j."""
    h = period / substeps
    table = np.empty((steps, 2 * substeps + 1, 7))
    for i in range(steps):
        t = (step0 + i) * period
        for m in range(2 * substeps + 1):
            s = t + ((m - 1) // 2) * h
            tm = t if m == 0 else (s + h / 2 if m % 2 == 1 else s + h)
            nt = fp[15] * tm
            r0, r1 = fp[14] * math.cos(nt), fp[14] * math.sin(nt)
            table[i, m, 0] = fp[0] * r0 + fp[3] * r1
            table[i, m, 1] = fp[1] * r0 + fp[4] * r1
            table[i, m, 2] = fp[2] * r0 + fp[5] * r1
            table[i, m, 3] = math.cos(earth_angle(0.0, tm))
            table[i, m, 4] = math.sin(earth_angle(0.0, tm))
            table[i, m, 5] = math.cos(n_gg * tm)
            table[i, m, 6] = math.sin(n_gg * tm)
    return table


@jit(error_model="numpy")
def _batch_field(fp: Any, node: tuple[float, float, float, float, float, float, float], cg: float,
                 sg: float) -> tuple[float, float, float]:  # pragma: no cover - compiled
    """The dipole (T, world) at a table node (its seven numbers) for a body whose Earth angle at
    t = 0 has cosine ``cg`` and sine ``sg`` (``theta = gmst0 + omega_E t`` by the angle-addition
    formulas); ``fp`` the field's parameters (a tuple: the compiler then knows they stay put)."""
    c = cg * node[3] - sg * node[4]
    s = sg * node[3] + cg * node[4]
    return _dipole(fp, node[0], node[1], node[2], c, s)


def _batch_rhs(t: float, y: Any, P: Any, X: Any, u0: float, u1: float) -> Any:  # pragma: no cover - compiled
    """The right-hand side the engine's generated RK4 step calls (:func:`_rk4_step`): ``(q', omega')``
    of one body (:func:`_detumble_rhs`), with the field and the orbit's direction at the step's
    start, middle or end, told apart by the stage's time ``t`` (the step's start ``P[7]`` and end
    ``P[8]`` computed as the step computes its nodes); ``P`` the body's moments (3), dipole held
    (3), ``n_gg`` (rad/s), those two times (s), the fields at the three nodes (9, T, world) and the
    orbit's directions there (6). ``X``, ``u0`` and ``u1`` unused (the directions come from the
    batch's table, the same for every body)."""
    if t == P[7]:
        b0, b1, b2, rc, rs = P[9], P[10], P[11], P[18], P[19]
    elif t == P[8]:
        b0, b1, b2, rc, rs = P[15], P[16], P[17], P[22], P[23]
    else:
        b0, b1, b2, rc, rs = P[12], P[13], P[14], P[20], P[21]
    return _detumble_rhs(b0, b1, b2, P[0], P[1], P[2], P[3], P[4], P[5], P[6], rc, rs, y[0], y[1], y[2], y[3], y[4], y[5],
                         y[6])


def _step_source() -> str:
    """The classical RK4 step over the body's seven floats ``(q, omega)``, written out by the
    engine's generator from its tableau (:func:`~tumble.dynamics.engine.unrolled.fixed_step_source`)."""
    return fixed_step_source("rk4_step", RK4_A, RK4_B, RK4_C, state_layout(7))


#: The step's turns of the orbit's direction: unused (:func:`_batch_rhs` reads the batch's table).
_NO_TURNS = (1.0, 0.0) * 4


@jit(error_model="numpy", nogil=True)
def _body(b: int | np.int64, I: FloatArray, q0: FloatArray, w0: FloatArray, gmst0: FloatArray, gain: FloatArray,
          normalized: bool, axes: FloatArray, limit: FloatArray, fpt: Any, n_gg: float, bias: FloatArray,
          noise: FloatArray, table: FloatArray, period: float, steps: int, substeps: int, rates: FloatArray,
          w_out: FloatArray, q_out: FloatArray) -> None:  # pragma: no cover - compiled
    """Body ``b`` through ``steps`` control periods of B-dot with ``substeps`` steps of the engine's
    RK4 each (:func:`detumble_serial`): the arithmetic of
    :func:`tumble.dynamics.control.detumble.detumble_batch`'s numpy path but for the steps' weights
    (``h (k0 / 6 + k1 / 3 + ...)``, a round-off apart); ``table`` the orbit's share
    (:func:`_orbit_table`), ``fpt`` the field's parameters as a tuple."""
    noisy = noise.shape[1] > 0
    h = period / substeps
    cg, sg = math.cos(gmst0[b]), math.sin(gmst0[b])
    I0, I1, I2 = I[b, 0], I[b, 1], I[b, 2]
    y = (q0[b, 0], q0[b, 1], q0[b, 2], q0[b, 3], w0[b, 0], w0[b, 1], w0[b, 2])  # x, y, z, w of q, then omega
    X = (0.0,)
    for i in range(steps + 1):
        rates[b, i] = math.sqrt(y[4] ** 2 + y[5] ** 2 + y[6] ** 2)
        if i == steps:
            break
        node = (table[i, 0, 0], table[i, 0, 1], table[i, 0, 2], table[i, 0, 3], table[i, 0, 4], table[i, 0, 5],
                table[i, 0, 6])
        e0, e1, e2 = _batch_field(fpt, node, cg, sg)
        bx, by, bz = to_body(y[0], y[1], y[2], y[3], e0, e1, e2)
        z = bias[b]
        gx, gy, gz = y[4] + z[0], y[5] + z[1], y[6] + z[2]  # the readings (Sensors.sample)
        bx, by, bz = bx + z[3], by + z[4], bz + z[5]
        if noisy:
            z = noise[b, i]
            gx, gy, gz, bx, by, bz = gx + z[0], gy + z[1], gz + z[2], bx + z[3], by + z[4], bz + z[5]
        m0, m1, m2 = _bdot(bx, by, bz, gx, gy, gz, gain[b], normalized, axes, limit)
        for j in range(substeps):
            t = i * period + j * h  # the step's start in this segment: tells its stages apart (_batch_rhs)
            s0, s1, s2 = e0, e1, e2  # the last step's end is this one's start
            mid = (table[i, 2 * j + 1, 0], table[i, 2 * j + 1, 1], table[i, 2 * j + 1, 2], table[i, 2 * j + 1, 3],
                   table[i, 2 * j + 1, 4], table[i, 2 * j + 1, 5], table[i, 2 * j + 1, 6])
            end = (table[i, 2 * j + 2, 0], table[i, 2 * j + 2, 1], table[i, 2 * j + 2, 2], table[i, 2 * j + 2, 3],
                   table[i, 2 * j + 2, 4], table[i, 2 * j + 2, 5], table[i, 2 * j + 2, 6])
            c0, c1, c2 = _batch_field(fpt, mid, cg, sg)
            e0, e1, e2 = _batch_field(fpt, end, cg, sg)
            P = (I0, I1, I2, m0, m1, m2, n_gg, t, t + 1.0 * h, s0, s1, s2, c0, c1, c2, e0, e1, e2,
                 table[i, 2 * j, 5], table[i, 2 * j, 6], mid[5], mid[6], end[5], end[6])
            y = _rk4_step(t, y, h, P, X, 1.0, 0.0, _NO_TURNS)
            nq = math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3])
            y = (y[0] / nq, y[1] / nq, y[2] / nq, y[3] / nq, y[4], y[5], y[6])
    for k in range(3):
        w_out[b, k] = y[4 + k]
    for k in range(4):
        q_out[b, k] = y[k]


@jit(error_model="numpy")
def _shared(fp: FloatArray, n_gg: float, period: float, step0: int, steps: int,
            substeps: int) -> tuple[FloatArray, Any]:  # pragma: no cover - compiled
    """What every body reads: the orbit's table (:func:`_orbit_table`) and the field's first 12
    parameters as a tuple (the compiler then knows they stay put)."""
    fpt = (fp[0], fp[1], fp[2], fp[3], fp[4], fp[5], fp[6], fp[7], fp[8], fp[9], fp[10], fp[11])
    return _orbit_table(fp, n_gg, period, step0, steps, substeps), fpt


@jit(error_model="numpy", nogil=True)
def detumble_serial(I: FloatArray, q0: FloatArray, w0: FloatArray, gmst0: FloatArray, gain: FloatArray,
                    normalized: bool, axes: FloatArray, limit: FloatArray, fp: FloatArray, n_gg: float, bias: FloatArray,
                    noise: FloatArray, period: float, step0: int, steps: int, substeps: int, rates: FloatArray,
                    w_out: FloatArray, q_out: FloatArray) -> None:  # pragma: no cover - compiled
    """Every body through ``steps`` control periods of B-dot from ``t = step0 period``, body by
    body on one thread (:func:`_body`); the arguments as :func:`detumble_run`'s, ``bias`` (N, 6),
    ``noise`` (N, steps, 6) or (N, 0, 6) for none, the rates (N, steps + 1), final omega and
    quaternions into ``rates``, ``w_out`` and ``q_out``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.detumble_kernels import detumble_parallel, detumble_serial
    >>> from tumble.dynamics.environment.magnetic import DipoleField
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> fp = DipoleField(CircularOrbit(altitude=500e3)).loop_form()[1]
    >>> n = 40
    >>> I, w = np.tile([0.01, 0.02, 0.03], (n, 1)), np.tile([0.1, -0.1, 0.1], (n, 1))
    >>> q, one = np.tile([0.0, 0.0, 0.0, 1.0], (n, 1)), np.ones(n)
    >>> args = (I, q, w, 0.0 * one, 1e-4 * one, True, np.eye(3), np.ones(3), fp, 0.0, np.zeros((n, 6)),
    ...         np.zeros((n, 0, 6)), 1.0, 0, 5, 2)
    >>> a, b = [(np.empty((n, 6)), np.empty((n, 3)), np.empty((n, 4))) for _ in range(2)]
    >>> detumble_serial(*args, *a)
    >>> detumble_parallel(*args, *b)   # the same arithmetic for each body
    >>> all(bool(np.array_equal(x, y)) for x, y in zip(a, b))
    True
    """
    table, fpt = _shared(fp, n_gg, period, step0, steps, substeps)
    for b in range(I.shape[0]):
        _body(b, I, q0, w0, gmst0, gain, normalized, axes, limit, fpt, n_gg, bias, noise, table, period, steps,
               substeps, rates, w_out, q_out)


@jit(error_model="numpy", nogil=True, parallel=True)
def detumble_parallel(I: FloatArray, q0: FloatArray, w0: FloatArray, gmst0: FloatArray, gain: FloatArray,
                      normalized: bool, axes: FloatArray, limit: FloatArray, fp: FloatArray, n_gg: float,
                      bias: FloatArray, noise: FloatArray, period: float, step0: int, steps: int, substeps: int,
                      rates: FloatArray, w_out: FloatArray, q_out: FloatArray) -> None:  # pragma: no cover - compiled
    """:func:`detumble_serial` with the bodies spread over every core (``numba.prange``): the same
    arithmetic for each body.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.detumble_kernels import detumble_parallel
    >>> from tumble.dynamics.environment.magnetic import DipoleField
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> fp = DipoleField(CircularOrbit(altitude=500e3)).loop_form()[1]
    >>> rates, w, q = np.empty((1, 2)), np.empty((1, 3)), np.empty((1, 4))
    >>> detumble_parallel(np.ones((1, 3)), np.array([[0.0, 0.0, 0.0, 1.0]]), np.zeros((1, 3)), np.zeros(1), np.ones(1),
    ...                   True, np.eye(3), np.ones(3), fp, 0.0, np.zeros((1, 6)), np.zeros((1, 0, 6)), 1.0, 0, 1, 1,
    ...                   rates, w, q)
    >>> rates.tolist(), q.tolist()   # at rest: nothing moves
    ([[0.0, 0.0]], [[0.0, 0.0, 0.0, 1.0]])
    """
    table, fpt = _shared(fp, n_gg, period, step0, steps, substeps)
    for b in prange(I.shape[0]):  # prange's index is unsigned: as int64, _body compiles once
        _body(np.int64(b), I, q0, w0, gmst0, gain, normalized, axes, limit, fpt, n_gg, bias, noise, table, period, steps,
               substeps, rates, w_out, q_out)


@jit(error_model="numpy")
def _detumble_rhs(b0: float, b1: float, b2: float, I0: float, I1: float, I2: float, m0: float, m1: float, m2: float,
                  n_gg: float, rc: float, rs: float, x: float, y: float, z: float, c: float, w0: float, w1: float,
                  w2: float) -> tuple[float, float, float, float, float, float, float]:  # pragma: no cover
    """``(q', omega')`` of ``I omega' = m x B + tau_gg - omega x I omega`` for one body, B and the
    radius direction ``(rc, rs, 0)`` in the world frame turned to the body by the (unnormalised)
    quaternion, as the numpy path's ``_rhs``; ``n_gg`` 0: no gravity gradient."""
    bx, by, bz = to_body(x, y, z, c, b0, b1, b2)
    g0, g1, g2 = 0.0, 0.0, 0.0
    if n_gg > 0.0:
        r0, r1, r2 = to_body(x, y, z, c, rc, rs, 0.0)
        g0, g1, g2 = _gravity_gradient(n_gg * n_gg, I0, I1, I2, r0, r1, r2)
    a0, a1, a2 = _euler(w0, w1, w2, I0, I1, I2, m1 * bz - m2 * by + g0, m2 * bx - m0 * bz + g1, m0 * by - m1 * bx + g2,
                        1.0 / I0, 1.0 / I1, 1.0 / I2)
    d0, d1, d2, d3 = quaternion_rate_components(x, y, z, c, w0, w1, w2)
    return d0, d1, d2, d3, a0, a1, a2


def _compiled_step() -> Callable[..., Any]:
    """The generated step compiled, calling :func:`_batch_rhs` (compiled, called at its stages:
    inlined, it ran no faster). The code object is named after this file, so numba's cache keys
    it on the sources."""
    namespace: dict[str, Any] = {"rhs": jit(_batch_rhs, error_model="numpy"), "__name__": __name__}
    exec(compile(_step_source(), __file__, "exec"), namespace)  # noqa: S102 - our own generated source
    return cast("Callable[..., Any]", jit(namespace["rk4_step"], error_model="numpy"))


_rk4_step = _compiled_step()


def detumble_run(I: FloatArray, q0: FloatArray, w0: FloatArray, gmst0: FloatArray, gain: FloatArray, *,
                 normalized: bool, axes: FloatArray, limit: FloatArray, fp: FloatArray, period: float, steps: int,
                 substeps: int, n_gg: float = 0.0, bias: FloatArray | None = None, noise: FloatArray | None = None,
                 step0: int = 0) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The compiled B-dot batch of :func:`tumble.dynamics.control.detumble.detumble_batch` (checked inputs).

    Parameters
    ----------
    I, w0 : ndarray, shape (N, 3)
        Principal moments (kg m^2) and initial rates (rad/s).
    q0 : ndarray, shape (N, 4)
        Unit quaternions, principal frame to world, scalar last.
    gmst0, gain : ndarray, shape (N,)
        Each body's Earth angle at t = 0 (rad) and B-dot gain.
    normalized : bool
        The normalised law (gain in N m s) or the classic one (A m^2 s/T).
    axes, limit : ndarray, shapes (r, 6) and (r,)
        The rods' rows (unit axes, then their allocation:
        :attr:`~tumble.dynamics.models.actuators.Magnetorquers.rods`) and dipole limits, A m^2.
    fp : ndarray, shape (16,)
        The dipole's :meth:`~tumble.dynamics.environment.magnetic.DipoleField.loop_form` (its ``gmst0`` unused).
    period : float
        Control period, s.
    steps, substeps : int
        Control periods, RK4 steps per period.
    n_gg : float
        Mean motion of the gravity gradient's circular orbit, rad/s (0: no gravity gradient).
    bias : ndarray, shape (N, 6), optional
        Each body's gyro bias (rad/s) and magnetometer bias (T); default none.
    noise : ndarray, shape (N, steps, 6), optional
        The gyro (rad/s) and magnetometer (T) noise added to the readings at each step; default none.
    step0 : int
        The first step's index: the run starts at ``t = step0 period`` (a run in segments).

    Returns
    -------
    rates : ndarray, shape (N, steps + 1)
    omega, quat : ndarray, shapes (N, 3) and (N, 4)

    Examples
    --------
    No rate, no dipole: nothing moves.

    >>> from tumble.dynamics.environment.magnetic import DipoleField
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> import numpy as np
    >>> from tumble.dynamics.control.detumble_kernels import detumble_run
    >>> _, fp = DipoleField(CircularOrbit(altitude=500e3)).loop_form()
    >>> rates, w, q = detumble_run(np.ones((1, 3)), np.array([[0.0, 0.0, 0.0, 1.0]]), np.zeros((1, 3)),
    ...                            np.zeros(1), np.ones(1), normalized=True, axes=np.hstack([np.eye(3)] * 2), limit=np.ones(3),
    ...                            fp=fp, period=1.0, steps=3, substeps=2)
    >>> rates.tolist(), q.tolist()
    ([[0.0, 0.0, 0.0, 0.0]], [[0.0, 0.0, 0.0, 1.0]])
    """
    if axes.ndim != 2 or (len(axes) and axes.shape[1] != 6):  # the kernel reads columns 3-5 unchecked; none: no rods
        raise ValueError(f"axes has shape {axes.shape}; allowed: (r, 6), Magnetorquers.rods (axes, then G^+)")
    N = len(I)
    rates, w_out, q_out = np.empty((N, steps + 1)), np.empty((N, 3)), np.empty((N, 4))
    kernel: Callable[..., None] = detumble_parallel if N >= PARALLEL_BODIES and cores() > 1 else detumble_serial
    c = np.ascontiguousarray
    bias = np.zeros((N, 6)) if bias is None else bias
    noise = np.zeros((N, 0, 6)) if noise is None else noise
    kernel(c(I, dtype=float), c(q0, dtype=float), c(w0, dtype=float), c(gmst0, dtype=float), c(gain, dtype=float),
           bool(normalized), c(axes, dtype=float), c(limit, dtype=float), c(fp, dtype=float), float(n_gg),
           c(bias, dtype=float), c(noise, dtype=float), float(period), int(step0), int(steps), int(substeps), rates,
           w_out, q_out)
    return rates, w_out, q_out
