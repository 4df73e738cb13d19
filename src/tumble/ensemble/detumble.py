"""Monte Carlo of B-dot detumbling: the distribution of detumble time over dispersed initial
rates, inertias, field epochs and sensor errors (issue 21), on the ensemble backends (in process
or Dask), and the numbers a design review asks of it (:meth:`DetumbleMonteCarlo.summary`).

The cases are drawn up front from one seed (so the result does not depend on the chunking or
the backend): the initial rate ``|omega0|`` uniform in ``[rate_min, rate_max]`` (rad/s) about a
direction uniform on the sphere; each principal moment ``I_j (1 + s z_j)``, ``z_j`` uniform on
[-1, 1] (``s`` = ``moment_spread``, relative); the field epoch ``gmst0`` (the Earth's sidereal
angle at t = 0, rad) uniform on [0, 2 pi); the initial attitude uniform on SO(3); a constant
gyro bias per case, Gaussian with ``gyro_bias_sigma`` (rad/s) on each axis; and each case's
own noise seed. Chunks of cases run through :func:`tumble.dynamics.control.detumble.detumble_batch` (a
compiled kernel, parallel over the cases of a chunk), with the gravity gradient of the orbit and
the sensors' noise if asked: case ``i`` reads its gyro and magnetometer with the noise levels of
the ``sensors`` given, its own bias added to theirs and its own seed, so that it is exactly
``simulate_controlled(..., sensors=mc.case_sensors(i))`` (:meth:`DetumbleMonteCarlo.case_sensors`)
whatever chunk or worker runs it.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from ..dynamics.control.detumble import detumble_batch
from ..dynamics.models.actuators import Magnetorquers
from ..dynamics.models.gravity import GravityGradient
from ..dynamics.environment.magnetic import DipoleField
from ..dynamics.models.sensors import Sensors
from ..typing import ArrayLike, FloatArray
from ..validation import breaks_triangle, check_moments, check_positive
from . import _display
from .backends import InProcess

__all__ = ["DetumbleCases", "DetumbleMonteCarlo", "detumble_cases", "detumble_monte_carlo"]


@dataclass(frozen=True, eq=False)
class DetumbleCases:
    """The dispersed inputs: moments (N, 3) kg m^2, omega0 (N, 3) rad/s, quat0 (N, 4), gmst0 (N,) rad,
    gyro_bias (N, 3) rad/s (None: none) and noise_seed (N,) (None: the case's index).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.detumble import detumble_cases
    >>> c = detumble_cases(3, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3, seed=2)
    >>> c.moments.shape, c.quat0.shape, c.gmst0.shape, c.gyro_bias.shape, c.noise_seed.shape
    ((3, 3), (3, 4), (3,), (3, 3), (3,))
    >>> c.case(1)["rate0"] == float(np.linalg.norm(c.omega0[1]))
    True
    """

    moments: FloatArray
    omega0: FloatArray
    quat0: FloatArray
    gmst0: FloatArray
    gyro_bias: FloatArray | None = None
    noise_seed: np.ndarray | None = None

    def __repr__(self) -> str:
        return _display.cases_repr(self)

    def _repr_html_(self) -> str:
        return _display.cases_html(self)

    def __len__(self) -> int:
        return len(self.moments)

    def biases(self) -> FloatArray:
        """Each case's gyro bias (N, 3), rad/s (zeros when none was drawn).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.detumble import DetumbleCases
        >>> c = DetumbleCases(np.ones((2, 3)), np.zeros((2, 3)), np.tile([0.0, 0.0, 0.0, 1.0], (2, 1)), np.zeros(2))
        >>> c.biases().tolist(), c.seeds().tolist()
        ([[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]], [0, 1])
        """
        return np.zeros((len(self), 3)) if self.gyro_bias is None else np.asarray(self.gyro_bias, float)

    def seeds(self) -> np.ndarray:
        """Each case's noise seed (N,): the drawn ones, or the case's index when none were drawn.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.detumble import detumble_cases
        >>> c = detumble_cases(2, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3, seed=2)
        >>> bool(np.all(c.seeds() >= 0)), c.seeds().dtype.kind
        (True, 'i')
        """
        return np.arange(len(self)) if self.noise_seed is None else np.asarray(self.noise_seed)

    def case(self, i: int) -> dict[str, Any]:
        """The inputs of case ``i`` as plain numbers (SI units; for reports and JSON).

        Examples
        --------
        >>> from tumble.ensemble.detumble import detumble_cases
        >>> c = detumble_cases(2, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3, seed=2)
        >>> sorted(c.case(0))
        ['gmst0', 'gyro_bias', 'index', 'moments', 'noise_seed', 'omega0', 'quat0', 'rate0']
        """
        i = int(i)
        return {"index": i, "moments": self.moments[i].tolist(), "omega0": self.omega0[i].tolist(),
                "rate0": float(np.linalg.norm(self.omega0[i])), "quat0": self.quat0[i].tolist(),
                "gmst0": float(self.gmst0[i]), "gyro_bias": self.biases()[i].tolist(),
                "noise_seed": int(self.seeds()[i])}


#: Rounds of redrawing the moments of cases that break the triangle inequality (detumble_cases).
MAX_REDRAWS = 200


def detumble_cases(n: int, *, moments: ArrayLike, rate_min: float, rate_max: float, moment_spread: float = 0.1,
                   gyro_bias_sigma: float = 0.0, seed: int = 0) -> DetumbleCases:
    """Draw ``n`` dispersed cases (module docstring).

    Parameters
    ----------
    n : int
        Number of cases (>= 1).
    moments : array_like, shape (3,)
        Nominal principal moments, kg m^2.
    rate_min, rate_max : float
        Range of the initial rate ``|omega0|``, rad/s.
    moment_spread : float
        Relative spread of each moment (uniform within +-, below 1). A case whose moments would
        break the triangle inequality (a body that cannot exist) is drawn again.
    gyro_bias_sigma : float
        Standard deviation of each axis of a case's constant gyro bias, rad/s (>= 0).
    seed : int
        Seed of the draws (numpy's default generator); the cases' noise seeds are drawn from it too.

    Returns
    -------
    DetumbleCases

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.detumble import detumble_cases
    >>> c = detumble_cases(4, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3, seed=1)
    >>> c.omega0.shape, bool(np.all(np.abs(np.linalg.norm(c.omega0, axis=1) - 0.2) <= 0.1))
    ((4, 3), True)
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n = {n!r} must be a whole number of cases >= 1")
    I = check_moments("moments", moments)  # a body that exists: within the triangle inequality
    lo = check_positive("rate_min", rate_min, "rad/s", allow_zero=True)
    hi = check_positive("rate_max", rate_max, "rad/s")
    if hi < lo:
        raise ValueError(f"rate_max = {rate_max!r} must be >= rate_min = {rate_min!r} (rad/s)")
    s = check_positive("moment_spread", moment_spread, "relative", allow_zero=True)
    if s >= 1.0:
        raise ValueError(f"moment_spread = {moment_spread!r} must be below 1 (relative): moments stay positive")
    rng = np.random.default_rng(seed)
    direction = rng.standard_normal((n, 3))
    direction /= np.linalg.norm(direction, axis=1)[:, None]
    omega0 = direction * rng.uniform(lo, hi, n)[:, None]
    moments_n = I * (1.0 + s * rng.uniform(-1.0, 1.0, (n, 3)))
    gmst0 = rng.uniform(0.0, 2.0 * math.pi, n)
    quat0 = Rotation.random(n, random_state=rng).as_quat()
    sigma = check_positive("gyro_bias_sigma", gyro_bias_sigma, "rad/s", allow_zero=True)
    bias = sigma * rng.standard_normal((n, 3))  # after the draws above: the same cases as before
    noise_seed = rng.integers(0, 2**63 - 1, n, dtype=np.int64)
    # Bodies that cannot exist (the spread can break the triangle inequality: the 3U CubeSat's
    # I1 + I2 exceeds I3 by only 16 %) are drawn again, after every other draw, so the other cases
    # stay as they were (at spread 0.9 most draws of that CubeSat break it; 200 rounds leave none).
    for _ in range(MAX_REDRAWS):
        bad = breaks_triangle(moments_n)
        if not bad.any():
            break
        moments_n[bad] = I * (1.0 + s * rng.uniform(-1.0, 1.0, (int(bad.sum()), 3)))
    else:
        raise RuntimeError(f"moments = {I.tolist()} with moment_spread = {moment_spread!r}: {int(bad.sum())} cases still "
                           f"break the triangle inequality after {MAX_REDRAWS} draws")
    return DetumbleCases(moments_n, omega0, np.asarray(quat0, float), gmst0, bias, noise_seed)


def _sensors(template: Sensors | None, cases: DetumbleCases, lo: int, hi: int) -> list[Sensors] | None:
    """Cases ``lo:hi``'s sensors: the template's noise levels and biases, the case's gyro bias added
    and its own seed (None: ideal sensors and no bias anywhere)."""
    bias = cases.biases()[lo:hi]
    if template is None:
        if not np.any(bias):
            return None
        template = Sensors()
    seeds = cases.seeds()[lo:hi]
    base = np.asarray(template.gyro_bias, float)
    return [dataclasses.replace(template, gyro_bias=tuple((base + b).tolist()), seed=int(s))
            for b, s in zip(bias, seeds)]


@dataclass(frozen=True, eq=False)
class DetumbleMonteCarlo:
    """Detumble times of every case (s, NaN: not detumbled by ``t_end``), the inputs, the wall time (s),
    and optionally the model and a decimated history of each case's ``|omega|``.

    Attributes
    ----------
    times : ndarray, shape (N,)
        Detumble time of each case, s (NaN: never).
    cases : DetumbleCases
    threshold, t_end, seconds : float
        The detumbled threshold (rad/s), the run's length (s) and the wall time it took (s).
    history_t : ndarray, shape (m,), optional
        Instants of the rate history, s (the first and last control steps among them).
    history : ndarray, shape (N, m), optional
        ``|omega|`` of each case at ``history_t``, rad/s (true rates, not the gyro's).
    sensors : Sensors, optional
        The sensor template the cases ran with (:meth:`case_sensors`); None: ideal.
    gravity_gradient : bool
        Whether the gravity gradient acted.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.detumble import DetumbleMonteCarlo, detumble_cases
    >>> c = detumble_cases(3, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3, seed=2)
    >>> mc = DetumbleMonteCarlo(times=np.array([100.0, 300.0, np.nan]), cases=c, threshold=0.01, t_end=600.0,
    ...                         seconds=0.1)
    >>> round(mc.detumbled, 3), mc.percentile(50)
    (0.667, 300.0)
    """

    times: FloatArray
    cases: DetumbleCases
    threshold: float
    t_end: float
    seconds: float
    history_t: FloatArray | None = None
    history: FloatArray | None = None
    sensors: Sensors | None = None
    gravity_gradient: bool = False

    def __repr__(self) -> str:
        return _display.monte_carlo_repr(self)

    def _repr_html_(self) -> str:
        return _display.monte_carlo_html(self)

    @property
    def detumbled(self) -> float:
        """Fraction of cases below the threshold for good by ``t_end``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.detumble import DetumbleMonteCarlo, detumble_cases
        >>> c = detumble_cases(2, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3)
        >>> DetumbleMonteCarlo(times=np.array([50.0, np.nan]), cases=c, threshold=0.01, t_end=60.0,
        ...                    seconds=0.0).detumbled
        0.5
        """
        return float(np.mean(np.isfinite(self.times)))

    def percentile(self, p: float) -> float:
        """The ``p``-th percentile of detumble time, s, counting a case that never detumbled as
        longer than any (NaN if more than ``100 - p`` % never did).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.detumble import DetumbleMonteCarlo, detumble_cases
        >>> c = detumble_cases(4, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3)
        >>> mc = DetumbleMonteCarlo(times=np.array([10.0, 20.0, 30.0, np.nan]), cases=c, threshold=0.01,
        ...                         t_end=60.0, seconds=0.0)
        >>> mc.percentile(50), mc.percentile(95)  # "higher": a sample, never between; the undetumbled last
        (30.0, nan)
        """
        t = np.where(np.isfinite(self.times), self.times, np.inf)
        value = float(np.percentile(t, p, method="higher"))
        return value if math.isfinite(value) else math.nan

    def worst(self, k: int = 5) -> list[int]:
        """The ``k`` slowest cases' indices, slowest first: those never detumbled (by their final
        rate, highest first, when the history holds it), then by detumble time.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.detumble import DetumbleMonteCarlo, detumble_cases
        >>> c = detumble_cases(4, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3)
        >>> DetumbleMonteCarlo(times=np.array([10.0, np.nan, 30.0, 20.0]), cases=c, threshold=0.01,
        ...                    t_end=60.0, seconds=0.0).worst(3)
        [1, 2, 3]
        """
        final = self.history[:, -1] if self.history is not None else np.zeros(len(self.times))
        key = np.where(np.isfinite(self.times), self.times, np.inf)
        order = np.lexsort((-final, -key))  # the last key sorts first
        return [int(i) for i in order[:max(0, int(k))]]

    def case_sensors(self, i: int) -> Sensors | None:
        """The sensors case ``i`` ran with (None: ideal): run it alone with
        ``simulate_controlled(..., sensors=mc.case_sensors(i))`` to see it in full.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.models.sensors import Sensors
        >>> from tumble.ensemble.detumble import DetumbleMonteCarlo, detumble_cases
        >>> c = detumble_cases(2, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3,
        ...                    gyro_bias_sigma=1e-3, seed=4)
        >>> mc = DetumbleMonteCarlo(times=np.array([10.0, 20.0]), cases=c, threshold=0.01, t_end=60.0, seconds=0.0,
        ...                         sensors=Sensors(gyro_noise=1e-4))
        >>> s = mc.case_sensors(1)
        >>> s.gyro_noise, bool(np.allclose(s.gyro_bias, c.gyro_bias[1])), s.seed == int(c.noise_seed[1])
        (0.0001, True, True)
        """
        sensors = _sensors(self.sensors, self.cases, int(i), int(i) + 1)
        return None if sensors is None else sensors[0]

    def rate_percentiles(self, percentiles: ArrayLike = (50.0, 95.0, 99.0)) -> FloatArray:
        """Percentiles of ``|omega|`` over the cases at each instant of :attr:`history_t`, rad/s,
        shape ``(len(percentiles), m)`` (the envelopes of the design-review plot).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.detumble import DetumbleMonteCarlo, detumble_cases
        >>> c = detumble_cases(3, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3)
        >>> mc = DetumbleMonteCarlo(times=np.full(3, np.nan), cases=c, threshold=0.01, t_end=1.0, seconds=0.0,
        ...                         history_t=np.array([0.0, 1.0]), history=np.array([[3.0, 1.0], [2.0, 0.5], [1.0, 0.2]]))
        >>> mc.rate_percentiles([0.0, 50.0, 100.0]).tolist()
        [[1.0, 0.2], [2.0, 0.5], [3.0, 1.0]]
        """
        if self.history is None:
            raise ValueError("this Monte Carlo kept no rate history: run it with history > 0")
        return np.asarray(np.percentile(self.history, np.asarray(percentiles, float), axis=0), float)

    def summary(self, worst: int = 5) -> dict[str, Any]:
        """What a design review asks: the detumble time's median, 95th and 99th percentiles and
        maximum (s; :meth:`percentile`, NaN where too many cases never detumbled; the maximum over
        those that did), the fraction and count detumbled, the model, the wall time, and the
        ``worst`` slowest cases' inputs (:meth:`DetumbleCases.case`) with their detumble time
        (None: never) and final rate (rad/s).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.ensemble.detumble import DetumbleMonteCarlo, detumble_cases
        >>> c = detumble_cases(4, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3)
        >>> mc = DetumbleMonteCarlo(times=np.array([10.0, 20.0, 30.0, np.nan]), cases=c, threshold=0.01,
        ...                         t_end=60.0, seconds=0.5)
        >>> s = mc.summary(worst=2)
        >>> s["median_s"], s["max_s"], s["detumbled"], s["not_detumbled"], [w["index"] for w in s["worst"]]
        (30.0, 30.0, 0.75, 1, [3, 2])
        >>> s["worst"][0]["detumble_time"] is None
        True
        """
        finite = self.times[np.isfinite(self.times)]
        sensors = self.sensors
        worst_cases = []
        for i in self.worst(worst):
            row = self.cases.case(i)
            row["detumble_time"] = float(self.times[i]) if math.isfinite(self.times[i]) else None
            row["final_rate"] = float(self.history[i, -1]) if self.history is not None else None
            worst_cases.append(row)
        return {
            "cases": len(self.times), "detumbled": self.detumbled,
            "not_detumbled": int(np.sum(~np.isfinite(self.times))),
            "median_s": self.percentile(50.0), "p95_s": self.percentile(95.0), "p99_s": self.percentile(99.0),
            "max_s": float(finite.max()) if finite.size else math.nan,
            "threshold_rad_s": self.threshold, "t_end_s": self.t_end, "seconds": self.seconds,
            "gravity_gradient": self.gravity_gradient,
            "gyro_noise_rad_s": sensors.gyro_noise if sensors is not None else 0.0,
            "magnetometer_noise_T": sensors.magnetometer_noise if sensors is not None else 0.0,
            "gyro_bias_std_rad_s": float(np.std(self.cases.biases())) if self.cases.gyro_bias is not None else 0.0,
            "worst": worst_cases,
        }


def _chunk(field: DipoleField, cases: DetumbleCases, lo: int, hi: int, gain: float, magnetorquers: Magnetorquers,
           period: float, t_end: float, threshold: float, substeps: int, gravity_gradient: GravityGradient | None,
           sensors: Sensors | None, history: int) -> tuple[FloatArray, FloatArray | None, FloatArray | None]:
    """Cases ``lo:hi``: detumble times (s), and the history's instants (s) and rates (rad/s)."""
    out = detumble_batch(cases.moments[lo:hi], cases.omega0[lo:hi], cases.quat0[lo:hi], field=field,
                         gmst0=cases.gmst0[lo:hi], gain=gain, magnetorquers=magnetorquers, period=period,
                         t_end=t_end, substeps=substeps, gravity_gradient=gravity_gradient,
                         sensors=_sensors(sensors, cases, lo, hi))
    if history == 0:
        return out.detumble_time(threshold), None, None
    keep = np.unique(np.linspace(0, len(out.t) - 1, history).round().astype(int))
    return out.detumble_time(threshold), out.t[keep], out.rate[:, keep]


def detumble_monte_carlo(cases: DetumbleCases, *, field: DipoleField, gain: float, magnetorquers: Magnetorquers,
                         period: float, t_end: float, threshold: float, substeps: int = 2, chunk: int = 2000,
                         backend: object | None = None, gravity_gradient: GravityGradient | None = None,
                         sensors: Sensors | None = None, history: int = 0) -> DetumbleMonteCarlo:
    """Detumble every case with normalised B-dot (gain ``k``, N m s) and collect the detumble times.

    Parameters
    ----------
    cases : DetumbleCases
        From :func:`detumble_cases`.
    field : DipoleField
        The orbit and the dipole (its ``gmst0`` is replaced by each case's).
    gain : float
        ``k`` of ``m = (k / |B|^2) omega x B``, N m s (e.g. :func:`~tumble.dynamics.control.bdot.bdot_gain`).
    magnetorquers : Magnetorquers
        The rods and their limits.
    period, t_end, threshold : float
        Control period (s), duration (s), and the rate (rad/s) below which a case counts as detumbled.
    substeps : int
        RK4 steps per period (:func:`~tumble.dynamics.control.detumble.detumble_batch`).
    chunk : int
        Cases per task.
    backend : InProcess or DaskBackend, optional
        Where the chunks run (default in process).
    gravity_gradient : GravityGradient, optional
        The gravity gradient of the field's orbit (``gravity_gradient_of(field.orbit)``); default none.
    sensors : Sensors, optional
        Gyro and magnetometer noise (rad/s, T, 1 sigma) and biases common to every case; each case
        adds its own gyro bias and uses its own noise seed (module docstring). Default: ideal sensors
        (with the cases' gyro biases, if any were drawn).
    history : int
        How many instants of each case's ``|omega|`` to keep (evenly spread over the control
        steps, the first and last among them; 0: none), for the rate envelopes.

    Returns
    -------
    DetumbleMonteCarlo

    Examples
    --------
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> from tumble.dynamics.models.orbit_gravity import gravity_gradient_of
    >>> from tumble.dynamics.environment.magnetic import DipoleField
    >>> from tumble.dynamics.models.actuators import Magnetorquers
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> from tumble.ensemble.detumble import detumble_cases, detumble_monte_carlo
    >>> orbit = CircularOrbit(altitude=500e3, inclination=1.7)
    >>> cases = detumble_cases(3, moments=[0.0067, 0.0419, 0.0419], rate_min=0.03, rate_max=0.05,
    ...                        gyro_bias_sigma=1e-4, seed=2)
    >>> mc = detumble_monte_carlo(cases, field=DipoleField(orbit), gain=3e-5, magnetorquers=Magnetorquers(0.2),
    ...                           period=5.0, t_end=6000.0, threshold=0.0087, history=11,
    ...                           gravity_gradient=gravity_gradient_of(orbit),
    ...                           sensors=Sensors(gyro_noise=1e-4, magnetometer_noise=1e-7))
    >>> mc.detumbled, mc.history.shape, float(mc.history_t[-1])
    (1.0, (3, 11), 6000.0)
    """
    n = len(cases.moments)
    if isinstance(chunk, bool) or not isinstance(chunk, (int, np.integer)) or chunk < 1:
        raise ValueError(f"chunk = {chunk!r} must be a whole number of cases >= 1")
    if isinstance(history, bool) or not isinstance(history, (int, np.integer)) or history < 0 or history == 1:
        raise ValueError(f"history = {history!r} must be 0 (none) or a whole number of instants >= 2")
    if sensors is not None and not isinstance(sensors, Sensors):
        raise ValueError(f"sensors = {sensors!r} must be a Sensors (noise levels and common biases) or None")
    check_positive("gain", gain, "N m s")
    check_positive("threshold", threshold, "rad/s")
    runner = backend if backend is not None else InProcess()
    bounds = [(lo, min(lo + chunk, n)) for lo in range(0, n, chunk)]
    tasks = [(field, cases, lo, hi, float(gain), magnetorquers, float(period), float(t_end), float(threshold),
              int(substeps), gravity_gradient, sensors, int(history)) for lo, hi in bounds]
    t0 = time.perf_counter()
    times = np.empty(n)
    history_t: FloatArray | None = None
    rates = np.empty((n, 0))
    for position, result in runner.map(_chunk, tasks):  # type: ignore[attr-defined]
        lo, hi = bounds[position]
        chunk_times, chunk_t, chunk_rates = result
        times[lo:hi] = np.asarray(chunk_times)
        if chunk_t is not None:
            if history_t is None:
                history_t, rates = np.asarray(chunk_t, float), np.empty((n, len(chunk_t)))
            rates[lo:hi] = chunk_rates
    return DetumbleMonteCarlo(times, cases, float(threshold), float(t_end), time.perf_counter() - t0, history_t,
                              rates if history_t is not None else None, sensors, gravity_gradient is not None)
