"""B-dot detumbling of many bodies at once: the closed loop of :func:`~tumble.dynamics.control.controlled.simulate_controlled`,
vectorised over N bodies with numpy and integrated by fixed-step RK4 between control steps.

The model is the magnetorquer case of :mod:`~tumble.dynamics.control.controlled` with the gyro form of
the B-dot law (:class:`~tumble.dynamics.control.bdot.BDot`, ``derivative="gyro"``) and no wheels:
for each body ``i`` (principal moments ``I_i``)

``I_i omega' = m_i x B_i + tau_gg,i - omega x I_i omega``,  ``q' = q (x) (omega, 0) / 2``,

``B_i`` the tilted dipole (:class:`~tumble.dynamics.environment.magnetic.DipoleField`) along one
shared circular orbit, seen from an Earth whose sidereal angle at t = 0 is ``gmst0_i`` (the
*field epoch*: where the dipole points when the run starts), turned into the body frame;
``tau_gg`` the gravity-gradient torque ``3 n^2 r_b x (I r_b)`` of the same orbit
(:class:`~tumble.dynamics.models.gravity.GravityGradient`, optional). At every control step
``t_k = k period`` the sensors are read as :meth:`~tumble.dynamics.models.sensors.Sensors.sample`
reads them (gyro ``omega + bias + noise``, magnetometer ``B + bias + noise``, the noise white and
Gaussian, drawn anew each step from the body's own seed), the dipole ``m_i = -k dB/dt`` with
``dB/dt = B x omega`` of the readings is computed, clipped rod by rod, and held. Between steps,
``substeps`` classical RK4 steps of ``h = period / substeps`` (the field and the orbit's radius
direction are evaluated at every stage): the engine's step, written out from the tableau
(:func:`~tumble.dynamics.engine.unrolled.fixed_step_source`) and run on both paths, compiled on
one, by Python over arrays of the bodies on the other.

**The noise is the single-body loop's.** Body ``i`` with sensors ``S_i`` draws from
``numpy.random.default_rng(S_i.seed)`` in the order ``Sensors.sample`` does (three gyro numbers,
three magnetometer numbers, and three more that a star tracker would use, at each step), so
body ``i`` of the batch sees the readings that ``simulate_controlled(..., sensors=S_i)`` sees,
whatever the other bodies, the batch's size or the path (tested). The noise is drawn a segment of
steps at a time (a few tens of MB), and the kernel runs segment by segment.

**Two paths.** By default each body runs through a compiled kernel
(:func:`~tumble.dynamics.control.detumble_kernels.detumble_run`: the same arithmetic, body by
body, on every core for a large batch); ``compiled=False`` runs the numpy path, vectorised over
the bodies, which is the reference (the two agree to round-off, tests/test_controlled_compiled.py).
In numpy one RK4 stage is some fifty operations on arrays of N, and the batch is bound by memory
traffic; compiled, a body's state stays in registers. **Accuracy.** RK4's error is ``O(h^4)``; with the default
four substeps a step and rates up to ~0.5 rad/s it agrees with :func:`~tumble.dynamics.control.controlled.simulate_controlled`
(DOP853, rtol 1e-10) to ~1e-9 rad/s, gravity gradient and sensor noise included (tested).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any, cast

import numpy as np

from ...typing import ArrayLike, FloatArray
from ...validation import check_positive
from . import _display
from .bdot import bdot_dipole
from ..models.actuators import Magnetorquers
from ..models.gravity import GravityGradient, gradient_torque
from ..environment.earth import earth_angle
from ..euler import euler_components
from ..environment.magnetic import DipoleField
from ..environment.orbit import plane_direction
from ..engine.tableau import RK4_A, RK4_B, RK4_C
from ..engine.unrolled import fixed_step_source, state_layout
from ..models.sensors import Sensors
from ..special.quaternion import quaternion_rate_components, to_body

__all__ = ["DetumbleBatch", "detumble_batch"]


@dataclass(frozen=True, eq=False)
class DetumbleBatch:
    """N detumbling runs sampled at every control step.

    Attributes
    ----------
    t : ndarray, shape (n,)
        Control instants, s.
    rate : ndarray, shape (N, n)
        ``|omega|`` of each body at each instant, rad/s.
    omega : ndarray, shape (N, 3)
        Final angular velocities, principal frames, rad/s.
    quat : ndarray, shape (N, 4)
        Final attitudes (principal frame to world), scalar last.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.detumble import DetumbleBatch
    >>> out = DetumbleBatch(t=np.array([0.0, 1.0, 2.0]), rate=np.array([[0.3, 0.1, 0.05]]),
    ...                     omega=np.zeros((1, 3)), quat=np.array([[0.0, 0.0, 0.0, 1.0]]))
    >>> out.rate.shape
    (1, 3)
    """

    t: FloatArray
    rate: FloatArray
    omega: FloatArray
    quat: FloatArray

    def __repr__(self) -> str:
        return _display.batch_repr(self)

    def _repr_html_(self) -> str:
        """The batch's size and final rates as an HTML table (Jupyter's rich display)."""
        return _display.batch_html(self)

    def detumble_time(self, threshold: float) -> FloatArray:
        """When each ``|omega|`` drops below ``threshold`` (rad/s) and stays there, s (NaN: never),
        as :meth:`~tumble.dynamics.control.controlled.ControlledRun.detumble_time`.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.control.detumble import DetumbleBatch
        >>> out = DetumbleBatch(t=np.array([0.0, 1.0, 2.0]), rate=np.array([[0.3, 0.1, 0.05], [0.3, 0.05, 0.2]]),
        ...                     omega=np.zeros((2, 3)), quat=np.tile([0.0, 0.0, 0.0, 1.0], (2, 1)))
        >>> out.detumble_time(0.08)  # the second body rose above the threshold again
        array([ 2., nan])
        """
        above = self.rate >= check_positive("threshold", threshold, "rad/s")
        n = above.shape[1]
        last = np.where(above.any(axis=1), n - 1 - np.argmax(above[:, ::-1], axis=1), -1)
        times = np.where(last < n - 1, self.t[np.minimum(last + 1, n - 1)], np.nan)
        return np.asarray(times, float)


Vec = tuple[FloatArray, FloatArray, FloatArray]


def _field_world(field: DipoleField, t: float, gmst0: FloatArray) -> Vec:
    """B (T) in the world frame at ``t`` for each Earth angle ``gmst0 + omega_E t``, by component."""
    w2e = field.world_from_eci  # the orbit-plane frame of the same field
    r_eci = w2e.T @ field.orbit.position_world(t)
    theta = earth_angle(gmst0, t)
    c, s = np.cos(theta), np.sin(theta)
    r_ecef = np.stack([c * r_eci[0] + s * r_eci[1], -s * r_eci[0] + c * r_eci[1], np.full_like(c, r_eci[2])], axis=-1)
    b = field.ecef(r_ecef)
    b_eci = (c * b[:, 0] - s * b[:, 1], s * b[:, 0] + c * b[:, 1], b[:, 2])
    return (w2e[0, 0] * b_eci[0] + w2e[0, 1] * b_eci[1] + w2e[0, 2] * b_eci[2],
            w2e[1, 0] * b_eci[0] + w2e[1, 1] * b_eci[1] + w2e[1, 2] * b_eci[2],
            w2e[2, 0] * b_eci[0] + w2e[2, 1] * b_eci[1] + w2e[2, 2] * b_eci[2])


def _to_body(q: FloatArray, b: Vec) -> Vec:
    """``R^T b`` for the quaternions ``q`` (4, N) (:func:`~tumble.dynamics.special.quaternion.to_body`)."""
    return to_body(q[0], q[1], q[2], q[3], b[0], b[1], b[2])


def _rhs(b_world: Vec, I: FloatArray, m: FloatArray, q: FloatArray, w: FloatArray,
         gg: tuple[float, float, float] | None) -> tuple[FloatArray, FloatArray]:
    """``(q', omega')`` (4, N) and (3, N) of ``I omega' = m x B + tau_gg - omega x I omega``;
    ``gg = (n, cos n t, sin n t)`` for the gravity gradient of the circular orbit (or None)."""
    bx, by, bz = _to_body(q, b_world)
    g: FloatArray | float = 0.0
    if gg is not None:
        n, c_t, s_t = gg
        r_b = np.stack(_to_body(q, (np.full_like(bx, c_t), np.full_like(bx, s_t), np.zeros_like(bx))), axis=-1)
        g = gradient_torque(r_b, I.T, n * n).T
    g = np.broadcast_to(g, (3, len(bx)))
    w0, w1, w2 = w
    t0, t1, t2 = m[1] * bz - m[2] * by + g[0], m[2] * bx - m[0] * bz + g[1], m[0] * by - m[1] * bx + g[2]  # m x B + gg
    dw = np.array(euler_components(w0, w1, w2, I[0], I[1], I[2], t0, t1, t2, 1.0 / I[0], 1.0 / I[1], 1.0 / I[2]))
    return np.array(quaternion_rate_components(q[0], q[1], q[2], q[3], w0, w1, w2)), dw


#: Sensor-noise numbers held at once (8 bytes each): the noise is drawn and the kernel run a
#: segment of steps at a time, so that a long run of many noisy bodies needs ~32 MB for it.
NOISE_VALUES = 1 << 22


@dataclass(frozen=True, eq=False)
class _SensorErrors:
    """Each body's sensor biases (N, 6: gyro rad/s, magnetometer T), noise sigmas (N, 2), seeds
    (N,) and numbers drawn a step (6, or 9 with a star tracker), from :class:`Sensors`."""

    bias: FloatArray
    sigma: FloatArray
    seeds: list[int]
    draws: list[int]

    @property
    def noisy(self) -> bool:
        return bool(np.any(self.sigma > 0.0))

    def segments(self, steps: int) -> Iterator[tuple[int, int, FloatArray | None]]:
        """``(i0, i1, noise)``: the steps ``i0 <= i < i1`` and their noise (N, i1 - i0, 6), or None
        without any; each body's numbers drawn from its own generator in ``Sensors.sample``'s order.

        The bodies' draws are spread over threads (numpy draws without the interpreter's lock),
        and the next segment is drawn while the caller integrates this one; each generator is
        used by one thread at a time and draws its segments in order, so the numbers do not
        depend on the threads."""
        n = len(self.seeds)
        if not self.noisy:
            yield 0, steps, None
            return
        from concurrent.futures import ThreadPoolExecutor

        from ...jit import cores

        rngs = {int(i): np.random.default_rng(self.seeds[i]) for i in np.flatnonzero(np.any(self.sigma > 0.0, axis=1))}
        scale = np.repeat(self.sigma, 3, axis=1)  # (N, 6): the gyro's sigma thrice, the magnetometer's thrice
        size = max(1, NOISE_VALUES // (6 * n))
        groups = [g for g in np.array_split(np.array(sorted(rngs), dtype=int), min(cores(), 8)) if len(g)]

        def fill(noise: FloatArray, group: FloatArray) -> None:
            for i in group:
                z = rngs[int(i)].standard_normal((noise.shape[1], self.draws[int(i)]))
                np.multiply(scale[i], z[:, :6], out=noise[i])  # sigma z, as Sensors.sample

        with ThreadPoolExecutor(len(groups)) as pool, ThreadPoolExecutor(1) as producer:
            def draw(i0: int) -> FloatArray:
                noise = np.zeros((n, min(i0 + size, steps) - i0, 6))
                for future in [pool.submit(fill, noise, g) for g in groups]:
                    future.result()
                return noise

            ahead = producer.submit(draw, 0)
            for i0 in range(0, steps, size):
                noise = ahead.result()
                if i0 + size < steps:
                    ahead = producer.submit(draw, i0 + size)
                yield i0, min(i0 + size, steps), noise


def _sensor_errors(sensors: Sensors | Sequence[Sensors] | None, n: int) -> _SensorErrors:
    """The sensors of each of ``n`` bodies: one for all (body ``i`` with ``seed + i``) or one each."""
    if sensors is None:
        return _SensorErrors(np.zeros((n, 6)), np.zeros((n, 2)), [0] * n, [6] * n)
    if isinstance(sensors, Sensors):
        each = [sensors] * n
        seeds = [int(sensors.seed) + i for i in range(n)]
    else:
        each = list(sensors)
        if len(each) != n or not all(isinstance(s, Sensors) for s in each):
            raise ValueError(f"sensors must be one Sensors or a sequence of {n} (one per body); got {len(each)} "
                             "items" + ("" if all(isinstance(s, Sensors) for s in each) else " that are not all Sensors"))
        seeds = [int(s.seed) for s in each]
    bias = np.array([[*s.gyro_bias, *s.magnetometer_bias] for s in each], float).reshape(n, 6)
    sigma = np.array([[s.gyro_noise, s.magnetometer_noise] for s in each], float).reshape(n, 2)
    draws = [9 if s.attitude == "star_tracker" else 6 for s in each]
    return _SensorErrors(bias, sigma, seeds, draws)


def _gravity_gradient(gravity_gradient: GravityGradient | None, field: DipoleField) -> float:
    """The mean motion of the gravity gradient's orbit, rad/s (0: none), checked to be the field's orbit."""
    if gravity_gradient is None:
        return 0.0
    if not isinstance(gravity_gradient, GravityGradient) or gravity_gradient.loop_form() is None:
        raise ValueError(f"gravity_gradient = {gravity_gradient!r} must be a GravityGradient (the circular orbit's, "
                         "gravity_gradient_of(orbit)) or None")
    if gravity_gradient.moments is not None:
        raise ValueError("gravity_gradient holds moments; leave them out: each body's own moments are used")
    n, n_field = gravity_gradient.mean_motion, field.orbit.mean_motion
    if abs(n - n_field) > 1e-9 * n_field:
        raise ValueError(f"gravity_gradient has mean motion {n!r} rad/s, the field's orbit {n_field!r} rad/s: the "
                         "batch has one circular orbit; pass gravity_gradient_of(field.orbit)")
    return float(n)


def detumble_batch(moments: ArrayLike, omega0: ArrayLike, attitude0: ArrayLike, *, field: DipoleField,
                   gmst0: ArrayLike, gain: ArrayLike, magnetorquers: Magnetorquers, period: float, t_end: float,
                   form: str = "normalized", substeps: int = 4, gravity_gradient: GravityGradient | None = None,
                   sensors: Sensors | Sequence[Sensors] | None = None, compiled: bool = True) -> DetumbleBatch:
    """B-dot detumbling of N bodies at once (module docstring).

    Parameters
    ----------
    moments : array_like, shape (N, 3)
        Principal moments of each body, kg m^2 (positive).
    omega0 : array_like, shape (N, 3)
        Initial angular velocities, principal frames, rad/s.
    attitude0 : array_like, shape (N, 4)
        Initial attitudes, principal frame to world (the orbit-plane frame), scalar last.
    field : DipoleField
        The orbit and the dipole's coefficients; its own ``gmst0`` is not used.
    gmst0 : array_like, shape (N,) or scalar
        Each run's Greenwich sidereal angle at t = 0, rad (the field epoch).
    gain : array_like, shape (N,) or scalar
        B-dot gain: N m s (form="normalized") or A m^2 s/T (form="classic"), > 0.
    magnetorquers : Magnetorquers
        The rods and their dipole limits (the same for every body).
    period : float
        Control period, s (> 0).
    t_end : float
        Duration, s: a whole number of periods is run (the last one may end past ``t_end``).
    form : {"normalized", "classic"}
        The B-dot law (:class:`~tumble.dynamics.control.bdot.BDot`).
    substeps : int
        RK4 steps per control period (>= 1).
    gravity_gradient : GravityGradient, optional
        The gravity-gradient torque of the field's circular orbit (``gravity_gradient_of(field.orbit)``;
        as in :func:`~tumble.dynamics.control.controlled.simulate_controlled`, without moments: each body's own act); default none.
    sensors : Sensors or sequence of N Sensors, optional
        Gyro and magnetometer noise (rad/s, T, 1 sigma) and biases (rad/s, T), as in
        :func:`~tumble.dynamics.control.controlled.simulate_controlled`: one for every body (body ``i`` then draws its noise from
        seed ``sensors.seed + i``) or one per body (its own seed and biases). Default: ideal sensors.
    compiled : bool
        The compiled kernel (True) or the numpy reference path (False); module docstring.

    Returns
    -------
    DetumbleBatch

    Examples
    --------
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> from tumble.dynamics.models.orbit_gravity import gravity_gradient_of
    >>> import numpy as np
    >>> from tumble.dynamics.control.detumble import detumble_batch
    >>> from tumble.dynamics.environment.magnetic import DipoleField
    >>> from tumble.dynamics.models.actuators import Magnetorquers
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> orbit = CircularOrbit(altitude=500e3, inclination=1.7)
    >>> out = detumble_batch([[0.0067, 0.0419, 0.0419]] * 2, [[0.2, -0.2, 0.2], [0.1, 0.1, -0.2]],
    ...                      [[0.0, 0.0, 0.0, 1.0]] * 2, field=DipoleField(orbit), gmst0=[0.0, 1.0], gain=5e-5,
    ...                      magnetorquers=Magnetorquers(0.2), period=1.0, t_end=60.0)
    >>> out.rate.shape, bool(np.all(out.rate[:, -1] < out.rate[:, 0]))
    ((2, 61), True)

    With the gravity gradient and noisy sensors (1e-4 rad/s and 100 nT, a 2e-4 rad/s gyro bias):

    >>> noisy = detumble_batch([[0.0067, 0.0419, 0.0419]] * 2, [[0.2, -0.2, 0.2], [0.1, 0.1, -0.2]],
    ...                        [[0.0, 0.0, 0.0, 1.0]] * 2, field=DipoleField(orbit), gmst0=[0.0, 1.0], gain=5e-5,
    ...                        magnetorquers=Magnetorquers(0.2), period=1.0, t_end=60.0,
    ...                        gravity_gradient=gravity_gradient_of(orbit),
    ...                        sensors=Sensors(gyro_noise=1e-4, gyro_bias=(2e-4, 0.0, 0.0), magnetometer_noise=1e-7))
    >>> bool(0.0 < np.max(np.abs(noisy.rate - out.rate)) < 1e-3)
    True
    """
    I = np.atleast_2d(np.asarray(moments, float))
    n = len(I)
    w = np.array(np.broadcast_to(np.asarray(omega0, float), (n, 3)))
    q = np.array(np.broadcast_to(np.asarray(attitude0, float), (n, 4)))
    if I.shape != (n, 3) or not np.all(np.isfinite(I)) or np.any(I <= 0.0):
        raise ValueError(f"moments has shape {I.shape} or non-positive entries; allowed: (N, 3) positive (kg m^2)")
    if not (np.all(np.isfinite(w)) and np.all(np.isfinite(q))):
        raise ValueError("omega0 (rad/s) and attitude0 must be finite")
    norms = np.linalg.norm(q, axis=1)
    if np.any(np.abs(norms - 1.0) > 1e-6):
        raise ValueError(f"attitude0[{int(np.argmax(np.abs(norms - 1.0)))}] must be a unit quaternion [x, y, z, w]")
    q /= norms[:, None]
    theta0 = np.array(np.broadcast_to(np.asarray(gmst0, float), (n,)))
    k = np.array(np.broadcast_to(np.asarray(gain, float), (n,)))
    if not np.all(k > 0.0) or not np.all(np.isfinite(k)):
        raise ValueError(f"gain = {gain!r} must be positive (N m s or A m^2 s/T)")
    if form not in ("normalized", "classic"):
        raise ValueError(f"form = {form!r} is unknown; allowed: normalized, classic")
    if not isinstance(field, DipoleField):
        raise ValueError(f"field = {field!r} must be a DipoleField")  # noqa: TRY004 - one error type for bad input
    if isinstance(substeps, bool) or not isinstance(substeps, (int, np.integer)) or substeps < 1:
        raise ValueError(f"substeps = {substeps!r} must be a whole number >= 1")
    D = check_positive("period", period, "s")
    steps = max(1, math.ceil(check_positive("t_end", t_end, "s") / D - 1e-9))
    n_gg = _gravity_gradient(gravity_gradient, field)
    errors = _sensor_errors(sensors, n)
    rates = np.empty((n, steps + 1))
    if compiled:
        from .detumble_kernels import detumble_run

        field_form = field.loop_form()
        if field_form is None:
            raise ValueError(f"field = {field!r} has a law of its own: the compiled batch cannot evaluate it; use compiled=False")
        fp = field_form[1]
        for i0, i1, noise in errors.segments(steps):
            part, w, q = detumble_run(
                I, q, w, theta0, k, normalized=form == "normalized", axes=magnetorquers.rods,
                limit=np.asarray(magnetorquers.max_dipole, float), fp=fp, period=float(D), steps=i1 - i0,
                substeps=int(substeps), n_gg=n_gg, bias=errors.bias, noise=noise, step0=i0)
            rates[:, i0:i1 + 1] = part
    else:
        w, q = _detumble_numpy(I, q, w, field, theta0, k, magnetorquers, float(D), steps, int(substeps), form, n_gg,
                               errors, rates)
    return DetumbleBatch(np.arange(steps + 1, dtype=float) * float(D), rates, w, q)


@functools.cache
def _numpy_rk4() -> Callable[..., tuple[FloatArray, ...]]:
    """The engine's RK4 step, written out by its generator from the tableau
    (:func:`~tumble.dynamics.engine.unrolled.fixed_step_source`, the compiled batch's step too:
    :mod:`~tumble.dynamics.control.detumble_kernels`), run by Python on a state whose components
    are arrays over the bodies, its right-hand side :func:`_numpy_rhs`."""
    namespace: dict[str, Any] = {"rhs": _numpy_rhs, "__name__": __name__}
    exec(compile(fixed_step_source("rk4_step", RK4_A, RK4_B, RK4_C, state_layout(7)), __file__, "exec"),  # noqa: S102
         namespace)
    return cast("Callable[..., tuple[FloatArray, ...]]", namespace["rk4_step"])


#: The step's turns of an orbit's direction: none here (:func:`_numpy_rhs` computes the gravity gradient's).
_NO_TURNS = (1.0, 0.0) * 4


def _numpy_rhs(t: float, y: tuple[FloatArray, ...], P: tuple[()], X: tuple[Any, ...], u0: float,
               u1: float) -> tuple[FloatArray, ...]:
    """``(q', omega')`` of every body by component (arrays of N) at the stage time ``t`` (s), the
    state ``y = (q, omega)`` by component (:func:`_rhs`), for the generated step (:func:`_numpy_rk4`);
    ``X = (field, I, m, gmst0, n_gg, node)``: the field, the moments (3, N), the held dipoles (3, N),
    the Earth angles, the gravity gradient's mean motion (0: none) and the last node's field and
    radius direction (the two middle stages share their node). ``P``, ``u0``, ``u1`` unused."""
    field, I, m, theta0, n_gg, node = X
    if node[0] != t:
        node[:] = [t, _field_world(field, t, theta0),
                   (n_gg, *plane_direction(n_gg, t)) if n_gg > 0.0 else None]
    kq, kw = _rhs(node[1], I, m, np.array(y[:4]), np.array(y[4:]), node[2])
    return (*kq, *kw)


def _detumble_numpy(I: FloatArray, q: FloatArray, w: FloatArray, field: DipoleField, theta0: FloatArray,
                    k: FloatArray, magnetorquers: Magnetorquers, D: float, steps: int, substeps: int,
                    form: str, n_gg: float, errors: _SensorErrors, rates: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The numpy path of :func:`detumble_batch`, vectorised over the bodies: rates (N, steps + 1)
    into ``rates``; returns the final omega (N, 3) and quaternions (N, 4)."""
    h = D / substeps
    I, q, w = I.T.copy(), q.T.copy(), w.T.copy()  # by component: (3, N), (4, N), (3, N)
    bias = errors.bias.T
    step = _numpy_rk4()
    for i0, i1, noise in errors.segments(steps):
        for i in range(i0, i1 + 1):
            t = i * D
            rates[:, i] = np.sqrt(w[0] ** 2 + w[1] ** 2 + w[2] ** 2)
            if i == i1:
                break
            b = np.array(_to_body(q, _field_world(field, t, theta0))) + bias[3:]  # the readings (Sensors.sample)
            w_read = w + bias[:3]
            if noise is not None:
                w_read, b = w_read + noise[:, i - i0, :3].T, b + noise[:, i - i0, 3:].T
            m = magnetorquers.saturate(bdot_dipole(np.cross(b.T, w_read.T), b.T, k, form)).T.copy()
            X = (field, I, m, theta0, n_gg, [None, None, None])
            for j in range(substeps):
                y = step(t + j * h, (*q, *w), h, (), X, 1.0, 0.0, _NO_TURNS)
                q, w = np.array(y[:4]), np.array(y[4:])
                q /= np.sqrt(np.sum(q * q, axis=0))
    return w.T.copy(), q.T.copy()
