"""The closed loop with attitude knowledge in one compiled call: the sensors, the MEKF and the law;
or the sensors' readings fed to the law as they are, the filter left out (:func:`plan_readings`).

:class:`~tumble.dynamics.control.estimated.Estimated` runs in Python once per control period
(readings, filter, law, then a compiled hold interval). When everything it wraps is built in
(:func:`plan`: a law the compiled loop knows, :func:`~tumble.dynamics.control.control_kernel.compiled_law`;
a magnetometer, coarse sun cells, a star tracker and a gyroscope; the flight software's field
model the run's own), the whole loop runs here instead, in one call, with the same formulas:

- **the noise** is drawn up front by numpy from the sensors' seeded generator in the order the
  Python path draws it at each step (gyroscope 3, magnetometer 3, the ``"star_tracker"``
  attitude 3, the coarse cells 2 k when they read and are lit, the star tracker 3 when it
  reads): the same numbers, so both paths agree to round-off;
- **what does not depend on the state** is tabulated per control instant in numpy: the Sun's
  direction (world), the light fraction, which sensor reads when;
- **the readings** are the sensors' own plain functions
  (:func:`~tumble.dynamics.models.vector_sensors.cell_currents`,
  :func:`~tumble.dynamics.models.vector_sensors.coarse_reading`,
  :func:`~tumble.dynamics.models.vector_sensors.tracker_noise` and
  :func:`~tumble.dynamics.special.quaternion.turned_by`);
- **the filter** is the compiled MEKF's (:mod:`~tumble.dynamics.estimation.mekf_kernels`:
  propagation with the mean of two gyroscope readings, the vector and attitude updates);
- **the law** is :func:`~tumble.dynamics.control.loop_laws.law_command`, fed the estimate;
- **the start** (a star tracker reading, or TRIAD on the Sun and the field) stays Python's
  (:meth:`~tumble.dynamics.control.estimated.Estimated.start`): the loop pauses at the step
  whose readings can start the filter, Python starts it, the loop goes on from that step.

Examples
--------
A pointing run from a magnetometer, coarse sun cells and a gyroscope takes this path (the
docstring of :mod:`~tumble.dynamics.control.estimated` has the run):

>>> import numpy as np
>>> from tumble.dynamics.control.controllers import MRPFeedback
>>> from tumble.dynamics.control.estimated import Estimated
>>> from tumble.dynamics.control.estimated_loop import plan
>>> from tumble.dynamics.models.actuators import ReactionWheels
>>> from tumble.dynamics.models.sensors import Sensors
>>> rw = ReactionWheels(np.eye(3), inertia=1e-5, max_torque=2e-3)
>>> sensors = Sensors(gyro_noise=1e-4, magnetometer_noise=2e-7, attitude="none")
>>> c = Estimated(MRPFeedback(K=1e-3, P=1e-2, period=0.5, moments=[0.02, 0.03, 0.04], wheels=rw), sensors)
>>> plan(c, sensors, np.array([0.02, 0.03, 0.04]), rw, None) is not None
True
"""

from __future__ import annotations

import math
from typing import Any, cast

import numpy as np
from scipy.spatial.transform import Rotation

from ...jit import jit
from ...typing import FloatArray
from ..estimation.mekf_kernels import propagate as _propagate
from ..estimation.mekf_kernels import update as _update
from ..models.sensors import Measurement, Sensors
from ..models.vector_sensors import (CoarseSunSensor, FineSunSensor, StarTracker, cell_currents, coarse_reading, fine_reading,
                                     fine_view, on_periods, tracker_noise)
from ..special.quaternion import to_body, turned_by
from . import compiled_loop as _cl
from .loop_laws import LAW_BDOT, Law, held, law_command
from .loop_terms import FIELD_NONE, FIELD_TABLE, field_body, field_world, tables
from .pointing import reference_table

__all__ = ["NEEDS_START", "NO_ATTITUDE", "SWITCH", "plan", "plan_readings", "run"]

#: Statuses beyond the compiled loop's: the filter can start at the step ``mem[15]``; the law
#: needs an attitude and the filter has not started.
NEEDS_START, NO_ATTITUDE = 2, 3
#: The loop paused where it was asked to (``stop``): a mission's switch to its pointing law.
SWITCH = 4

_cells = jit(cell_currents, error_model="numpy")
_coarse = jit(coarse_reading, error_model="numpy")
_fine_view = jit(fine_view, error_model="numpy")
_fine = jit(fine_reading, error_model="numpy")
_tracker = jit(tracker_noise, error_model="numpy")
_turned = jit(turned_by, error_model="numpy")


@jit(error_model="numpy")
def _knowledge_loop(y0: FloatArray, i0: int, fresh: bool, grid: FloatArray, P0: FloatArray, law: int, L: FloatArray,
                    pinv: FloatArray, rods: FloatArray, limits: FloatArray, rtol: float, atol: float, dop853: Any,
                    rk8: Any, rk4: Any, step: float, carry: bool, S: FloatArray, A: FloatArray, Apinv: FloatArray, Agram: FloatArray,
                    C: FloatArray, Rt: FloatArray, noise: FloatArray, offs: np.ndarray, flags: np.ndarray,
                    sun_world: FloatArray, light: FloatArray, fq: FloatArray, fb: FloatArray, fP: FloatArray,
                    mem: FloatArray, used0: np.ndarray, Y: FloatArray, D: FloatArray, U: FloatArray, F: FloatArray,
                    KQ: FloatArray, KB: FloatArray, KS: FloatArray, KU: np.ndarray, KV: np.ndarray,
                    RD: FloatArray, stop: int, KW: FloatArray, REF: FloatArray,
                    Cf: FloatArray) -> int:  # pragma: no cover - compiled
    """The loop from step ``i0`` of ``grid`` (s) (module docstring; :func:`run` says what each
    argument holds); ``fresh``: the filter started at ``i0`` (its updates skipped there, ``used0``
    its row's sensors); ``(dop853, rk8, rk4)`` the hold interval's method
    (:func:`~tumble.dynamics.control.compiled_loop.method_flags`). Returns a status; on a pause, what was read into ``RD`` and the memory
    into ``mem``. It pauses (:data:`SWITCH`) at the start of the step ``stop`` (none if negative),
    before anything of that step but the state in ``Y`` is done, and writes into ``KW`` the rate
    (rad/s, body) the law is given at each step: the gyroscope's reading, less the filter's bias
    once it has started; ``REF`` a moving reference's rows at ``grid``
    (:func:`~tumble.dynamics.control.loop_laws.law_command`); ``Cf`` a fine sun sensor's frame
    (sensor to body), which draws its noise only at the steps that it sees the Sun: the draws after
    are ``extra`` further on than ``offs`` says (kept in ``mem[16]`` over a pause)."""
    steps = grid.shape[0] - 1
    y = _cl.tuple_of(y0)
    u = np.zeros(_cl.MAX_WHEELS)
    h_abs = mem[8]
    extra = int(mem[16])  # the fine sun sensor's draws so far
    turns = _cl._turns()
    memory = (mem[0], mem[1], mem[2], mem[3], mem[4], mem[5], mem[6], mem[7] != 0.0)
    kind = int(P0[15])
    P = P0.copy()  # the parameters with the command held (set_command)
    fp, ft, _ = tables(P0, _cl.TABLES)
    has_field = kind != FIELD_NONE
    kc = A.shape[0]
    cur = np.empty((kc, 2))
    yv, Hv, Rv, vec = np.empty((1, 2)), np.empty((1, 2, 6)), np.empty((1, 2, 2)), np.empty((1, 7))
    ya, Ha, Ra, qm = np.empty((1, 3)), np.empty((1, 3, 6)), np.empty((1, 3, 3)), np.empty((1, 4))
    ok, nis, gyro = np.ones(1, np.bool_), np.empty(1), np.empty((1, 3))
    for i in range(i0, steps + 1):
        t = grid[i]
        nq = math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3])
        y = _cl.with_quaternion(y, y[0] / nq, y[1] / nq, y[2] / nq, y[3] / nq)
        _cl.store(y, Y[i])
        if i == stop:
            mem[8], mem[16] = h_abs, float(extra)
            return SWITCH
        x, yq, z, c, w0, w1, w2 = y[0], y[1], y[2], y[3], y[4], y[5], y[6]
        b0, b1, b2 = field_body(kind, fp, ft, x, yq, z, c, t) if has_field else (0.0, 0.0, 0.0)
        F[i, 0], F[i, 1], F[i, 2] = b0, b1, b2
        m0, m1, m2 = 0.0, 0.0, 0.0
        for j in range(_cl.MAX_WHEELS):
            u[j] = 0.0
        if i < steps:
            o = offs[i] + extra  # the readings (Sensors.sample, in its order of draws)
            extra_before = extra
            g0, g1, g2 = w0 + S[0] + S[6] * noise[o], w1 + S[1] + S[6] * noise[o + 1], w2 + S[2] + S[6] * noise[o + 2]
            o += 3
            n0, n1, n2 = 0.0, 0.0, 0.0
            if has_field:
                n0, n1, n2 = b0 + S[3] + S[7] * noise[o], b1 + S[4] + S[7] * noise[o + 1], b2 + S[5] + S[7] * noise[o + 2]
                o += 3
            ax, ay, az, aw = x, yq, z, c  # the attitude the law is given without a filter
            if S[8] != 0.0:
                if S[16] != 0.0:  # the attitude sensor's reading: the truth turned by its noise
                    ax, ay, az, aw = _turned(x, yq, z, c, S[17] * noise[o], S[17] * noise[o + 1], S[17] * noise[o + 2])
                o += 3
            has_sun, v0, v1, v2, sg = False, 0.0, 0.0, 0.0, 0.0
            if flags[i] & 2:
                s0, s1, s2 = to_body(x, yq, z, c, sun_world[i, 0], sun_world[i, 1], sun_world[i, 2])
                _cells(A, light[i], s0, s1, s2, S[9], noise[o:o + 2 * kc], cur)
                v0, v1, v2, sg = _coarse(Apinv, Agram, S[9], cur)
                o += 2 * kc
                has_sun = sg >= 0.0
            if flags[i] & 8:  # a fine sun sensor, lit on its period: it draws only when it sees the Sun
                s0, s1, s2 = to_body(x, yq, z, c, sun_world[i, 0], sun_world[i, 1], sun_world[i, 2])
                a0, a1, a2, seen = _fine_view(Cf, S[18], s0, s1, s2, light[i])
                if seen:
                    v0, v1, v2 = _fine(Cf, S[9], a0, a1, a2, noise[o], noise[o + 1])
                    has_sun, sg, o, extra = True, S[9], o + 2, extra + 2
            has_trk, t0, t1, t2, t3 = False, 0.0, 0.0, 0.0, 0.0
            if flags[i] & 4:
                r0, r1, r2 = _tracker(C, S[10], S[11], noise[o], noise[o + 1], noise[o + 2])
                t0, t1, t2, t3 = _turned(x, yq, z, c, r0, r1, r2)
                has_trk = True
            if mem[9] == 0.0 and S[16] == 0.0 and (has_trk or (has_sun and has_field and S[15] != 0.0) or law != LAW_BDOT):
                RD[0], RD[1], RD[2], RD[3], RD[4], RD[5], RD[6], RD[7] = t, g0, g1, g2, n0, n1, n2, (1.0 if has_field else 0.0)
                RD[8], RD[9], RD[10], RD[11], RD[12] = v0, v1, v2, sg, (1.0 if has_sun else 0.0)
                RD[13], RD[14], RD[15], RD[16], RD[17] = t0, t1, t2, t3, (1.0 if has_trk else 0.0)
                mem[0], mem[1], mem[2], mem[3], mem[4], mem[5], mem[6] = memory[0], memory[1], memory[2], memory[3], \
                    memory[4], memory[5], memory[6]
                mem[7], mem[8], mem[15], mem[16] = (1.0 if memory[7] else 0.0), h_abs, float(i), float(extra_before)
                return NEEDS_START if has_trk or (has_sun and has_field and S[15] != 0.0) else NO_ATTITUDE
            if mem[9] == 0.0:  # the readings themselves: no filter, or B-dot before its start
                KW[i, 0], KW[i, 1], KW[i, 2] = g0, g1, g2
                m0, m1, m2, memory = law_command(law, L, pinv, P0, y, t, ax, ay, az, aw, g0, g1, g2, n0, n1, n2,
                                                 has_field, memory, u, REF, i)
            else:
                used_mag, used_sun, used_trk = used0[0], used0[1], used0[2]
                if not (fresh and i == i0):
                    if t > mem[10]:  # the rate over the step: the mean of its two readings
                        gyro[0, 0], gyro[0, 1], gyro[0, 2] = 0.5 * (mem[11] + g0), 0.5 * (mem[12] + g1), 0.5 * (mem[13] + g2)
                        _propagate(fq, fb, fP, gyro, t - mem[10], S[13], S[14])
                    used_mag = has_field and S[15] != 0.0 and (flags[i] & 1) != 0
                    if used_mag:
                        bn = math.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
                        r0, r1, r2 = field_world(kind, fp, ft, t)
                        vec[0, 0], vec[0, 1], vec[0, 2], vec[0, 3], vec[0, 4], vec[0, 5] = n0, n1, n2, r0, r1, r2
                        vec[0, 6] = max(S[7] / bn if bn > 0.0 else math.inf, S[12])
                        _update(fq, fb, fP, yv, Hv, Rv, ok, nis, vec)
                    used_sun = has_sun
                    if has_sun:
                        vec[0, 0], vec[0, 1], vec[0, 2] = v0, v1, v2
                        vec[0, 3], vec[0, 4], vec[0, 5] = sun_world[i, 0], sun_world[i, 1], sun_world[i, 2]
                        vec[0, 6] = max(sg, S[12])
                        _update(fq, fb, fP, yv, Hv, Rv, ok, nis, vec)
                    used_trk = has_trk
                    if has_trk:
                        qm[0, 0], qm[0, 1], qm[0, 2], qm[0, 3] = t0, t1, t2, t3
                        for r in range(3):  # element by element: a slice's assignment compiles numba's
                            for j in range(3):  # broadcast checks and their messages (~0.5 s of a first run)
                                Ra[0, r, j] = Rt[r, j]
                        _update(fq, fb, fP, ya, Ha, Ra, ok, nis, qm)
                for j in range(4):
                    KQ[i, j] = fq[0, j]
                for j in range(3):
                    KB[i, j] = fb[0, j]
                for j in range(6):
                    KS[i, j] = math.sqrt(fP[0, j, j])
                KU[i, 0], KU[i, 1], KU[i, 2], KV[i] = used_mag, used_sun, used_trk, True
                KW[i, 0], KW[i, 1], KW[i, 2] = g0 - fb[0, 0], g1 - fb[0, 1], g2 - fb[0, 2]
                m0, m1, m2, memory = law_command(law, L, pinv, P0, y, t, fq[0, 0], fq[0, 1], fq[0, 2], fq[0, 3],
                                                 g0 - fb[0, 0], g1 - fb[0, 1], g2 - fb[0, 2], n0, n1, n2,
                                                 has_field, memory, u, REF, i)
            mem[10], mem[11], mem[12], mem[13] = t, g0, g1, g2
        d0, d1, d2 = held(rods, limits, m0, m1, m2, u, y, P0, D[i], U[i])
        if i == steps:
            break
        _cl.set_command(P, d0, d1, d2, u)
        status, y, h_abs = _cl._advance(y, t, grid[i + 1], P, rtol, atol, dop853, rk8, rk4, step, h_abs if carry else 0.0,
                                        turns)
        if status != _cl.OK:
            return int(status)
    return _cl.OK


def plan(controller: Any, sensors: Any, moments: FloatArray, wheels: Any, field: Any) -> tuple[Law, ...] | None:
    """The laws of an :class:`~tumble.dynamics.control.estimated.Estimated` that this loop runs
    (each :data:`Law` of :func:`~tumble.dynamics.control.control_kernel.compiled_law`: the wrapped
    law's, or a :class:`~tumble.dynamics.control.mission.DetumbleThenPoint`'s two modes'), or None
    for the Python path: the run's ``sensors`` those the filter is told of and sampled as
    ``Sensors.sample`` samples them, coarse cells, a fine sun sensor or none, a
    :class:`~tumble.dynamics.models.vector_sensors.StarTracker` or none, the flight software's field
    the run's (or none), and the wrapped law (each mode's) a built-in one.

    Examples
    --------
    A fine sun sensor runs here; sensors other than the filter's keep the Python path:

    >>> import numpy as np
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.control.estimated import Estimated
    >>> from tumble.dynamics.control.estimated_loop import plan
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> from tumble.dynamics.environment.sun import Sunlight
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> from tumble.dynamics.models.vector_sensors import FineSunSensor
    >>> s = Sensors(sun_sensor=FineSunSensor(), sunlight=Sunlight(CircularOrbit(altitude=5e5), "2026-03-20T14:46:00"))
    >>> len(plan(Estimated(BDot(gain=1.0, period=1.0), s), s, np.ones(3), None, None))
    1
    >>> plan(Estimated(BDot(gain=1.0, period=1.0), s), Sensors(), np.ones(3), None, None) is None
    True
    """
    from ..environment.magnetic import field_form
    from .estimated import Estimated

    if not isinstance(controller, Estimated) or type(controller).__call__ is not Estimated.__call__:
        return None
    s = controller.sensors
    if sensors is not s or type(s).sample is not Sensors.sample \
            or not (s.sun_sensor is None or isinstance(s.sun_sensor, (CoarseSunSensor, FineSunSensor))) \
            or not (s.star_tracker is None or isinstance(s.star_tracker, StarTracker)):
        return None
    own = controller.field
    if own is not None and own is not field:
        if field is None:
            return None
        form, own_form = field_form(field), field_form(own)
        if form is None or own_form is None:
            return None
        (kind, p), (own_kind, own_p) = form, own_form
        if kind == FIELD_TABLE or kind != own_kind or not np.array_equal(p, own_p):
            return None
    return _laws(controller.controller, moments, wheels, field)


def _laws(controller: Any, moments: FloatArray, wheels: Any, field: Any) -> tuple[Law, ...] | None:
    """:func:`~tumble.dynamics.control.control_kernel.compiled_law` of ``controller``, or of each
    mode of a :class:`~tumble.dynamics.control.mission.DetumbleThenPoint`; None where one has none."""
    from .control_kernel import _plain, compiled_law
    from .mission import DetumbleThenPoint

    modes = (controller.detumble, controller.point) if _plain(controller, DetumbleThenPoint) else (controller,)
    laws = tuple(compiled_law(mode, None, moments, wheels, field) for mode in modes)
    return None if any(law is None for law in laws) else cast("tuple[Law, ...]", laws)


def plan_readings(controller: Any, sensors: Any, moments: FloatArray, wheels: Any, field: Any) -> tuple[Law, ...] | None:
    """The laws that this loop runs fed the readings of ``sensors`` as they are, with no filter (each
    :data:`Law` of :func:`~tumble.dynamics.control.control_kernel.compiled_law`: the controller's, or
    a :class:`~tumble.dynamics.control.mission.DetumbleThenPoint`'s two modes'), or None for the
    Python path: a built-in law (each mode's), sensors sampled as ``Sensors.sample`` samples them,
    coarse cells, a fine sun sensor or none, a
    :class:`~tumble.dynamics.models.vector_sensors.StarTracker` or none, and an attitude sensor
    where a law points (without one the Python path says why it cannot).

    Examples
    --------
    B-dot on a noisy gyroscope and magnetometer runs here; MRP feedback with no attitude sensor
    does not:

    >>> import numpy as np
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.control.controllers import MRPFeedback
    >>> from tumble.dynamics.control.estimated_loop import plan_readings
    >>> from tumble.dynamics.models.actuators import ReactionWheels
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> noisy = Sensors(gyro_noise=1e-4, magnetometer_noise=1e-7, attitude="none")
    >>> len(plan_readings(BDot(gain=1.0, period=1.0), noisy, np.ones(3), None, None))
    1
    >>> rw = ReactionWheels(np.eye(3), inertia=1e-5)
    >>> plan_readings(MRPFeedback(K=1e-3, P=1e-2, period=1.0, moments=np.ones(3), wheels=rw), noisy, np.ones(3), rw, None) is None
    True
    """
    if not isinstance(sensors, Sensors) or type(sensors).sample is not Sensors.sample \
            or not (sensors.sun_sensor is None or isinstance(sensors.sun_sensor, (CoarseSunSensor, FineSunSensor))) \
            or not (sensors.star_tracker is None or isinstance(sensors.star_tracker, StarTracker)):
        return None  # the sensors' own sampling, or a sensor the loop does not draw for
    laws = _laws(controller, moments, wheels, field)
    if laws is None or (sensors.attitude == "none" and any(law[0] != LAW_BDOT for law in laws)):
        return None
    return laws


def run(controller: Any, kernel: Any, laws: tuple[Law, ...], grid: FloatArray, y0: FloatArray,
        rods: FloatArray, limits: FloatArray, carry: bool,
        sensors: Sensors | None = None) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """The whole loop of the :class:`~tumble.dynamics.control.estimated.Estimated` ``controller``
    (``laws``: what :func:`plan` said) on the :class:`~tumble.dynamics.control.control_kernel.ControlKernel`
    ``kernel``: as :meth:`~tumble.dynamics.control.control_kernel.ControlKernel.run`, the states,
    dipoles, wheel torques and fields at ``grid`` (s); the filter's rows left in the controller
    (:meth:`~tumble.dynamics.control.estimated.Estimated.knowledge`). With ``sensors`` (and ``laws``
    what :func:`plan_readings` said), ``controller`` is the law itself, fed these sensors' readings
    as they are, with no filter.

    A :class:`~tumble.dynamics.control.mission.DetumbleThenPoint` runs as its Python path does with
    the same rule: the loop runs the whole time detumbling and gives the rates the law was handed
    at each step (the gyroscope's, less the filter's bias once it has started); the mission's own
    :meth:`~tumble.dynamics.control.mission.DetumbleThenPoint.observe` finds the switch in them (and
    sets its ``switch_time``); where it switches, the loop runs again, the same to that step (the
    noise is drawn up front), and from it on with the pointing law, nothing in its memory.

    Examples
    --------
    :func:`~tumble.dynamics.control.controlled.simulate_controlled` calls it; the module
    docstring of :mod:`~tumble.dynamics.control.estimated` has a run.

    >>> from tumble.dynamics.control.estimated_loop import run
    >>> run.__name__
    'run'
    """
    filtered = sensors is None
    if sensors is None:
        sensors = controller.sensors
    steps = len(grid) - 1
    t = np.asarray(grid[:-1], float)
    has_field = int(kernel.P[15]) != FIELD_NONE
    sun = sensors.sun_sensor   # plan: coarse cells, a fine sensor or none
    css = sun if isinstance(sun, CoarseSunSensor) else None
    fss = sun if isinstance(sun, FineSunSensor) else None
    trk = sensors.star_tracker
    kc = 0 if css is None else len(np.asarray(css.axes))
    lit, light, sun_world = np.zeros(steps, bool), np.zeros(steps), np.zeros((steps, 3))
    A, Apinv, Agram, Cf = np.zeros((0, 3)), np.zeros((3, 0)), np.zeros((3, 3)), np.eye(3)
    if sun is not None and sensors.sunlight is not None:
        on = on_periods(t, sun.period)
        if on.any():
            light[on] = sensors.sunlight.fraction(t[on])
            sun_world[on] = sensors.sunlight.world(t[on])
        lit = on & (light > 0.0)
        if css is not None:
            A = np.ascontiguousarray(css.axes, dtype=float)
            Apinv, Agram = css.tables()
        else:
            Cf = np.ascontiguousarray(fss.frame.as_matrix())  # type: ignore[union-attr]
    tracked = on_periods(t, trk.period) if trk is not None else np.zeros(steps, bool)
    counts = 3 + 3 * has_field + 3 * (sensors.attitude == "star_tracker") + 2 * kc * lit + 3 * tracked
    offs = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    seeing = int(lit.sum()) if fss is not None else 0  # the most steps the fine sensor may draw at (2 each)
    noise = sensors.rng().standard_normal(int(offs[-1]) + 2 * seeing)
    updates = on_periods(t, controller.magnetometer_period) if filtered else np.zeros(steps, bool)
    flags = (updates * 1 + lit * (2 if css is not None else 8) + tracked * 4).astype(np.int64)
    min_sigma = controller.min_sigma if filtered else 0.0
    S = np.array([*sensors.gyro_bias, *sensors.magnetometer_bias, sensors.gyro_noise, sensors.magnetometer_noise,
                  sensors.attitude == "star_tracker", sun.noise if sun is not None else 0.0,
                  trk.cross if trk is not None else 0.0, trk.roll if trk is not None else 0.0, min_sigma,
                  sensors.gyro_noise * math.sqrt(controller.period) if filtered else 0.0,
                  controller.bias_walk if filtered else 0.0, filtered and controller.field is not None,
                  not filtered, sensors.attitude_noise, math.cos(fss.fov) if fss is not None else 0.0], dtype=float)
    C = trk.frame.as_matrix() if trk is not None else np.eye(3)  # type: ignore[union-attr]
    Rt = trk.covariance + min_sigma**2 * np.eye(3) if trk is not None else np.eye(3)
    n = steps + 1
    Y, D, U, F = np.empty((n, _cl.N)), np.zeros((n, 3)), np.zeros((n, kernel.k)), np.zeros((n, 3))
    KW = np.zeros((n, 3))
    loop = _kernels()["_knowledge_loop"]
    head = (np.ascontiguousarray(grid, dtype=float), kernel.packed)
    tail = (np.ascontiguousarray(rods, dtype=float), np.ascontiguousarray(limits, dtype=float), kernel.rtol,
             kernel.atol, *_cl.method_flags(kernel.method), kernel.step, bool(carry), S, A, Apinv, Agram, np.ascontiguousarray(C),
             np.ascontiguousarray(Rt), noise, offs, flags, sun_world, light)

    def through(law: Law, stop: int, after: Law | None) -> tuple[FloatArray, ...]:
        """The loop from the start with ``law``, and from the step ``stop`` on with ``after``: the
        filter's rows (quaternion, bias, sigmas, sensors used, whether the filter ran)."""
        fq, fb, fP = np.zeros((1, 4)), np.zeros((1, 3)), np.zeros((1, 6, 6))
        mem, used0, RD = np.zeros(17), np.zeros(3, bool), np.zeros(18)
        KQ, KB, KS, KU, KV = np.zeros((n, 4)), np.zeros((n, 3)), np.zeros((n, 6)), np.zeros((n, 3), bool), np.zeros(n, bool)
        y, i0, fresh = _cl.padded(y0), 0, False
        while True:
            status = loop(y, i0, fresh, *head, law[0], law[1], law[2], *tail, fq, fb, fP, mem, used0, Y, D, U, F,
                          KQ, KB, KS, KU, KV, RD, stop, KW, reference_table(law[3], grid), Cf)
            if status in (NEEDS_START, NO_ATTITUDE):
                i = int(mem[15])
                m = Measurement(float(RD[0]), RD[1:4].copy(), RD[4:7].copy() if RD[7] else None, None,
                                _cl.unpadded(Y[i], kernel.k)[7:7 + kernel.k], RD[8:11].copy() if RD[12] else None,
                                float(RD[11]) if RD[12] else 0.0, Rotation.from_quat(RD[13:17]) if RD[17] else None)
                if status == NO_ATTITUDE:
                    controller.no_attitude(float(grid[i]), m)   # raises the Python path's error
                f = controller.start(float(grid[i]), m)
                fq[0], fb[0], fP[0] = f.quaternion, f.bias, f.covariance
                used0[:] = (m.star_tracker is None, m.star_tracker is None, m.star_tracker is not None)
                mem[9] = 1.0
                y, i0, fresh = Y[i].copy(), i, True
                continue
            if status == SWITCH and after is not None:  # the pointing law from here, nothing in its memory
                mem[:8] = 0.0
                y, i0, fresh = Y[stop].copy(), stop, False
                law, after, stop = after, None, -1
                continue
            if status != _cl.OK:
                raise RuntimeError("the integration failed: the step size fell below 10 ulp of t")
            return KQ, KB, KS, KU, KV

    rows = through(laws[0], -1, None)
    if len(laws) == 2:  # a mission: the switch found from the rates its law was given, then the run again to it
        mission = controller.controller if filtered else controller
        mission.reset()
        switch = next((i for i in range(steps) if mission.observe(float(grid[i]), float(np.linalg.norm(KW[i])))), -1)
        if switch >= 0:
            rows = through(laws[0], switch, laws[1])
    KQ, KB, KS, KU, KV = rows
    if filtered:
        controller.record(grid[KV], KQ[KV], KB[KV], KS[KV], KU[KV])
    return _cl.unpadded(Y, kernel.k), D, U, F


_KERNELS: dict[str, Any] = {"_knowledge_loop": _knowledge_loop}


def _kernels() -> dict[str, Any]:
    """The compiled kernel, by name (looked up at call time)."""
    return _KERNELS
