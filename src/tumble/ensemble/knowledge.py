"""Monte Carlo of pointing on an estimate: the pointing and knowledge errors of a controller fed
the MEKF's estimate (:class:`~tumble.dynamics.control.estimated.Estimated`) over dispersed
sensors and starting attitudes, on the ensemble backends (in process or Dask).

The cases are drawn up front from one seed, so that the result does not depend on the chunking
or the backend: the starting attitude uniform on SO(3); a constant gyroscope bias per case,
Gaussian with ``gyro_bias_sigma`` (rad/s) on each axis; a noise scale per case, uniform in
``[1 - noise_spread, 1 + noise_spread]``, multiplying every noise level of the ``sensors`` given
(the gyroscope's, the magnetometer's, the sun sensor's and the star tracker's: a batch of parts
that differ); and each case's own noise seed. Case ``i`` is exactly
``simulate_controlled(..., controller=Estimated(controller, s, field), sensors=s)`` with
``s = mc.case_sensors(i)`` (:meth:`PointingMonteCarlo.case_sensors`), whatever chunk or worker
runs it. After ``settle`` s (the slew and the filter's start behind), each case gives its RMS and
final pointing error against the controller's target and its RMS and final knowledge error.
"""

from __future__ import annotations

import copy
import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from ..dynamics.control.controlled import simulate_controlled
from ..dynamics.control.estimated import Estimated
from ..dynamics.models.sensors import Sensors
from ..typing import ArrayLike, FloatArray
from ..validation import check_moments, check_positive
from . import _display
from .backends import InProcess

__all__ = ["KnowledgeCases", "PointingMonteCarlo", "knowledge_cases", "pointing_monte_carlo"]


@dataclass(frozen=True, eq=False)
class KnowledgeCases:
    """The dispersed inputs: ``quat0`` (N, 4) starting attitudes, ``gyro_bias`` (N, 3) rad/s,
    ``noise_scale`` (N,) and ``noise_seed`` (N,).

    Examples
    --------
    >>> from tumble.ensemble.knowledge import knowledge_cases
    >>> c = knowledge_cases(4, gyro_bias_sigma=1e-4, noise_spread=0.2, seed=1)
    >>> c.quat0.shape, c.gyro_bias.shape, bool((abs(c.noise_scale - 1.0) <= 0.2).all()), c.noise_seed.tolist()
    ((4, 4), (4, 3), True, [2000, 2001, 2002, 2003])
    """

    quat0: FloatArray
    gyro_bias: FloatArray
    noise_scale: FloatArray
    noise_seed: np.ndarray

    def __len__(self) -> int:
        return len(self.noise_seed)

    def __repr__(self) -> str:
        return _display.knowledge_repr(self)

    def _repr_html_(self) -> str:
        return _display.knowledge_html(self)


def knowledge_cases(n: int, *, gyro_bias_sigma: float = 0.0, noise_spread: float = 0.0, seed: int = 0) -> KnowledgeCases:
    """Draw ``n`` cases (module docstring) from ``seed``.

    Examples
    --------
    The same seed, the same cases:

    >>> import numpy as np
    >>> from tumble.ensemble.knowledge import knowledge_cases
    >>> a, b = knowledge_cases(3, seed=5), knowledge_cases(3, seed=5)
    >>> np.array_equal(a.quat0, b.quat0), a.gyro_bias.tolist() == [[0.0] * 3] * 3
    (True, True)
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n = {n!r} must be a whole number of cases >= 1")
    check_positive("gyro_bias_sigma", gyro_bias_sigma, "rad/s", allow_zero=True)
    check_positive("noise_spread", noise_spread, "relative", allow_zero=True, at_most=1.0)
    rng = np.random.default_rng(seed)
    quat0 = Rotation.random(int(n), random_state=rng).as_quat()
    bias = gyro_bias_sigma * rng.standard_normal((int(n), 3))
    scale = 1.0 + noise_spread * rng.uniform(-1.0, 1.0, int(n))
    return KnowledgeCases(quat0, bias, scale, 1000 * (int(seed) + 1) + np.arange(int(n)))


@dataclass(frozen=True, eq=False)
class _Setup:
    moments: FloatArray
    controller: Any
    field: Any
    sensors: Sensors
    wheels: Any
    magnetorquers: Any
    t_end: float
    settle: float
    estimator: dict[str, Any]


def _case_sensors(sensors: Sensors, cases: KnowledgeCases, i: int) -> Sensors:
    s = float(cases.noise_scale[i])
    heads: dict[str, Any] = {}
    if sensors.sun_sensor is not None:
        heads["sun_sensor"] = dataclasses.replace(sensors.sun_sensor, noise=sensors.sun_sensor.noise * s)
    if sensors.star_tracker is not None:
        tracker = sensors.star_tracker
        heads["star_tracker"] = dataclasses.replace(tracker, cross=tracker.cross * s, roll=tracker.roll * s)
    return dataclasses.replace(sensors, gyro_noise=sensors.gyro_noise * s, magnetometer_noise=sensors.magnetometer_noise * s,
                               attitude_noise=sensors.attitude_noise * s,
                               gyro_bias=tuple(np.asarray(sensors.gyro_bias) + cases.gyro_bias[i]),
                               seed=int(cases.noise_seed[i]), **heads)


def _run_chunk(setup: _Setup, cases: KnowledgeCases, indices: list[int]) -> FloatArray:
    """Rows ``(knowledge RMS, knowledge final, pointing RMS, pointing final)`` (rad) of the cases ``indices``."""
    rows = []
    target = setup.controller.target
    for i in indices:
        sensors = _case_sensors(setup.sensors, cases, i)
        c = Estimated(copy.deepcopy(setup.controller), sensors, setup.field, **setup.estimator)
        run = simulate_controlled(setup.moments, np.zeros(3), t_end=setup.t_end, controller=c, field=setup.field,
                                  wheels=setup.wheels, magnetorquers=setup.magnetorquers, sensors=sensors,
                                  attitude0=cases.quat0[i])
        k = c.knowledge()
        late = k.t >= setup.settle
        know = np.linalg.norm(k.error(run), axis=1)[late]
        point = run.pointing_error(target)[run.t >= setup.settle]
        rows.append((np.sqrt(np.mean(know**2)), know[-1], np.sqrt(np.mean(point**2)), point[-1]))
    return np.array(rows, float).reshape(-1, 4)


@dataclass(frozen=True, eq=False)
class PointingMonteCarlo:
    """The per-case errors of :func:`pointing_monte_carlo`, rad, each shape (N,).

    Examples
    --------
    :func:`pointing_monte_carlo` makes one from its runs; by hand, from drawn cases:

    >>> from tumble.dynamics.models.sensors import Sensors
    >>> from tumble.ensemble.knowledge import PointingMonteCarlo, knowledge_cases
    >>> cases = knowledge_cases(2, gyro_bias_sigma=1e-4, noise_spread=0.5, seed=3)
    >>> mc = PointingMonteCarlo(cases, *([cases.noise_scale] * 4), Sensors(gyro_noise=1e-4), 0.0)
    >>> mc.pointing_rms.shape
    (2,)
    """

    cases: KnowledgeCases
    knowledge_rms: FloatArray
    knowledge_final: FloatArray
    pointing_rms: FloatArray
    pointing_final: FloatArray
    sensors: Sensors
    settle: float

    def __repr__(self) -> str:
        return _display.pointing_repr(self)

    def _repr_html_(self) -> str:
        return _display.pointing_html(self)

    def case_sensors(self, i: int) -> Sensors:
        """The sensors case ``i`` flew with (its noise scale, bias and seed).

        Examples
        --------
        >>> from tumble.dynamics.models.sensors import Sensors
        >>> from tumble.ensemble.knowledge import PointingMonteCarlo, knowledge_cases
        >>> cases = knowledge_cases(2, gyro_bias_sigma=1e-4, noise_spread=0.5, seed=3)
        >>> mc = PointingMonteCarlo(cases, *([cases.noise_scale] * 4), Sensors(gyro_noise=1e-4), 0.0)
        >>> s = mc.case_sensors(1)
        >>> bool(abs(s.gyro_noise - 1e-4 * cases.noise_scale[1]) < 1e-18), s.seed
        (True, 4001)
        """
        return _case_sensors(self.sensors, self.cases, i)

    def summary(self) -> dict[str, Any]:
        """Median, 95th percentile and largest of each error, deg, with the number of cases.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.sensors import Sensors
        >>> from tumble.ensemble.knowledge import PointingMonteCarlo, knowledge_cases
        >>> cases = knowledge_cases(4)
        >>> e = np.radians([0.1, 0.2, 0.3, 0.4])
        >>> s = PointingMonteCarlo(cases, e, e, e, e, Sensors(), 60.0).summary()
        >>> s["cases"], s["pointing_rms_deg"]["median"], s["pointing_rms_deg"]["max"]
        (4, 0.25, 0.4)
        """
        out: dict[str, Any] = {"cases": len(self.cases), "settle": self.settle}
        for name in ("knowledge_rms", "knowledge_final", "pointing_rms", "pointing_final"):
            x = np.degrees(getattr(self, name))
            out[f"{name}_deg"] = {"median": float(np.median(x)), "p95": float(np.percentile(x, 95)), "max": float(x.max())}
        return out


def pointing_monte_carlo(cases: KnowledgeCases, *, moments: ArrayLike, controller: Any, field: Any, sensors: Sensors,
                         t_end: float, settle: float = 0.0, wheels: Any = None, magnetorquers: Any = None,
                         estimator: dict[str, Any] | None = None, chunk: int = 4,
                         backend: object | None = None) -> PointingMonteCarlo:
    """Fly every case (module docstring) and collect its pointing and knowledge errors.

    Parameters
    ----------
    cases : KnowledgeCases
        From :func:`knowledge_cases`.
    moments : array_like, shape (3,)
        Principal moments, kg m^2.
    controller : controller with a ``target``
        The pointing law (an :class:`~tumble.dynamics.control.controllers.MRPFeedback`); copied
        for each case.
    field : MagneticField
        The run's field, and the filter's reference for the magnetometer.
    sensors : Sensors
        The nominal sensors (their noise levels are scaled per case).
    t_end : float
        Each run's duration, s.
    settle : float
        From when the errors count, s (>= 0, < ``t_end``).
    wheels, magnetorquers : optional
        The actuators.
    estimator : dict, optional
        Further keywords of :class:`~tumble.dynamics.control.estimated.Estimated`.
    chunk : int
        Cases a task (>= 1).
    backend : InProcess or DaskBackend, optional
        Where the chunks run (default: here, in order).

    Returns
    -------
    PointingMonteCarlo

    Examples
    --------
    Three cases of a small body pointing with wheels on a magnetometer and six sun cells:

    >>> import numpy as np
    >>> from tumble.dynamics.control.controllers import MRPFeedback
    >>> from tumble.dynamics.environment.magnetic import DipoleField
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> from tumble.dynamics.environment.sun import Sunlight
    >>> from tumble.dynamics.models.actuators import ReactionWheels
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> from tumble.dynamics.models.vector_sensors import CoarseSunSensor
    >>> from tumble.ensemble.knowledge import knowledge_cases, pointing_monte_carlo
    >>> orbit = CircularOrbit(altitude=500e3, inclination=1.7)
    >>> rw = ReactionWheels(np.eye(3), inertia=1e-5, max_torque=2e-3)
    >>> law = MRPFeedback(K=4e-3, P=1.2e-2, period=1.0, moments=[0.02, 0.03, 0.04], wheels=rw)
    >>> sensors = Sensors(gyro_noise=1e-4, magnetometer_noise=2e-7, attitude="none",
    ...                   sun_sensor=CoarseSunSensor(noise=2e-3), sunlight=Sunlight(orbit, "2026-06-01T00:00:00"))
    >>> mc = pointing_monte_carlo(knowledge_cases(3, gyro_bias_sigma=2e-4, seed=1), moments=[0.02, 0.03, 0.04],
    ...                           controller=law, field=DipoleField(orbit), sensors=sensors, wheels=rw,
    ...                           t_end=120.0, settle=60.0)
    >>> bool(mc.summary()["pointing_rms_deg"]["max"] < 1.0), mc.knowledge_rms.shape
    (True, (3,))
    """
    I = check_moments("moments", moments)
    T = check_positive("t_end", t_end, "s")
    settle = check_positive("settle", settle, "s", allow_zero=True)
    if settle >= T:
        raise ValueError(f"settle = {settle!r} must be less than t_end = {T!r} (s)")
    if isinstance(chunk, bool) or not isinstance(chunk, (int, np.integer)) or chunk < 1:
        raise ValueError(f"chunk = {chunk!r} must be a whole number of cases >= 1")
    if not hasattr(controller, "target"):
        raise ValueError(f"controller = {type(controller).__name__} has no target: give a pointing law such as MRPFeedback")
    setup = _Setup(I, controller, field, sensors, wheels, magnetorquers, T, settle, dict(estimator or {}))
    n = len(cases)
    starts = list(range(0, n, int(chunk)))
    tasks = [(setup, cases, list(range(s, min(s + int(chunk), n)))) for s in starts]
    rows = np.empty((n, 4))
    for position, result in (backend if backend is not None else InProcess()).map(_run_chunk, tasks):  # type: ignore[attr-defined]
        s = starts[position]
        rows[s:s + len(result)] = result
    return PointingMonteCarlo(cases, rows[:, 0], rows[:, 1], rows[:, 2], rows[:, 3], sensors, settle)
