"""Monte Carlo of B-dot detumbling: the distribution of detumble time over dispersed initial
rates, inertias and field epochs (issue 21), on the ensemble backends (in process or Dask).

The cases are drawn up front from one seed (so the result does not depend on the chunking or
the backend): the initial rate ``|omega0|`` uniform in ``[rate_min, rate_max]`` (rad/s) about a
direction uniform on the sphere; each principal moment ``I_j (1 + s z_j)``, ``z_j`` uniform on
[-1, 1] (``s`` = ``moment_spread``, relative); the field epoch ``gmst0`` (the Earth's sidereal
angle at t = 0, rad) uniform on [0, 2 pi); the initial attitude uniform on SO(3). Chunks of
cases run through :func:`tumble.dynamics.detumble.detumble_batch` (a compiled kernel, parallel over the cases of a chunk).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from ..dynamics.detumble import detumble_batch
from ..dynamics.models.actuators import Magnetorquers
from ..dynamics.models.magnetic import DipoleField
from ..typing import ArrayLike, FloatArray
from ..validation import check_moments, check_positive
from .backends import InProcess

__all__ = ["DetumbleCases", "DetumbleMonteCarlo", "detumble_cases", "detumble_monte_carlo"]


@dataclass(frozen=True, eq=False)
class DetumbleCases:
    """The dispersed inputs: moments (N, 3) kg m^2, omega0 (N, 3) rad/s, quat0 (N, 4), gmst0 (N,) rad.

    Examples
    --------
    >>> c = detumble_cases(3, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3, seed=2)
    >>> c.moments.shape, c.quat0.shape, c.gmst0.shape
    ((3, 3), (3, 4), (3,))
    """

    moments: FloatArray
    omega0: FloatArray
    quat0: FloatArray
    gmst0: FloatArray


def detumble_cases(n: int, *, moments: ArrayLike, rate_min: float, rate_max: float, moment_spread: float = 0.1,
                   seed: int = 0) -> DetumbleCases:
    """Draw ``n`` dispersed cases (module docstring).

    Examples
    --------
    >>> c = detumble_cases(4, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3, seed=1)
    >>> c.omega0.shape, bool(np.all(np.abs(np.linalg.norm(c.omega0, axis=1) - 0.2) <= 0.1))
    ((4, 3), True)
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n = {n!r} must be a whole number of cases >= 1")
    I = check_moments("moments", moments, physical=False)
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
    return DetumbleCases(moments_n, omega0, np.asarray(quat0, float), gmst0)


@dataclass(frozen=True, eq=False)
class DetumbleMonteCarlo:
    """Detumble times of every case (s, NaN: not detumbled by ``t_end``), the inputs, the wall time (s).

    Examples
    --------
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

    @property
    def detumbled(self) -> float:
        """Fraction of cases below the threshold for good by ``t_end``.

        Examples
        --------
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
        >>> c = detumble_cases(4, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3)
        >>> mc = DetumbleMonteCarlo(times=np.array([10.0, 20.0, 30.0, np.nan]), cases=c, threshold=0.01,
        ...                         t_end=60.0, seconds=0.0)
        >>> mc.percentile(50), mc.percentile(95)  # "higher": a sample, never between; the undetumbled last
        (30.0, nan)
        """
        t = np.where(np.isfinite(self.times), self.times, np.inf)
        value = float(np.percentile(t, p, method="higher"))
        return value if math.isfinite(value) else math.nan


def _chunk(field: DipoleField, cases: DetumbleCases, lo: int, hi: int, gain: float, magnetorquers: Magnetorquers,
           period: float, t_end: float, threshold: float, substeps: int) -> FloatArray:
    out = detumble_batch(cases.moments[lo:hi], cases.omega0[lo:hi], cases.quat0[lo:hi], field=field,
                         gmst0=cases.gmst0[lo:hi], gain=gain, magnetorquers=magnetorquers, period=period,
                         t_end=t_end, substeps=substeps)
    return out.detumble_time(threshold)


def detumble_monte_carlo(cases: DetumbleCases, *, field: DipoleField, gain: float, magnetorquers: Magnetorquers,
                         period: float, t_end: float, threshold: float, substeps: int = 2, chunk: int = 2000,
                         backend: object | None = None) -> DetumbleMonteCarlo:
    """Detumble every case with normalised B-dot (gain ``k``, N m s) and collect the detumble times.

    Parameters
    ----------
    cases : DetumbleCases
        From :func:`detumble_cases`.
    field : DipoleField
        The orbit and the dipole (its ``gmst0`` is replaced by each case's).
    gain : float
        ``k`` of ``m = (k / |B|^2) omega x B``, N m s (e.g. :func:`~tumble.dynamics.controllers.bdot_gain`).
    magnetorquers : Magnetorquers
        The rods and their limits.
    period, t_end, threshold : float
        Control period (s), duration (s), and the rate (rad/s) below which a case counts as detumbled.
    substeps : int
        RK4 steps per period (:func:`~tumble.dynamics.detumble.detumble_batch`).
    chunk : int
        Cases per task.
    backend : InProcess or DaskBackend, optional
        Where the chunks run (default in process).

    Returns
    -------
    DetumbleMonteCarlo

    Examples
    --------
    >>> from tumble.dynamics.models.orbit import CircularOrbit
    >>> field = DipoleField(CircularOrbit(altitude=500e3, inclination=1.7))
    >>> cases = detumble_cases(3, moments=[0.0067, 0.0419, 0.0419], rate_min=0.03, rate_max=0.05, seed=2)
    >>> mc = detumble_monte_carlo(cases, field=field, gain=3e-5, magnetorquers=Magnetorquers(0.2),
    ...                           period=5.0, t_end=6000.0, threshold=0.0087)
    >>> mc.detumbled
    1.0
    """
    n = len(cases.moments)
    if isinstance(chunk, bool) or not isinstance(chunk, (int, np.integer)) or chunk < 1:
        raise ValueError(f"chunk = {chunk!r} must be a whole number of cases >= 1")
    check_positive("gain", gain, "N m s")
    check_positive("threshold", threshold, "rad/s")
    runner = backend if backend is not None else InProcess()
    bounds = [(lo, min(lo + chunk, n)) for lo in range(0, n, chunk)]
    tasks = [(field, cases, lo, hi, float(gain), magnetorquers, float(period), float(t_end), float(threshold),
              int(substeps)) for lo, hi in bounds]
    t0 = time.perf_counter()
    times = np.empty(n)
    for position, result in runner.map(_chunk, tasks):  # type: ignore[attr-defined]
        lo, hi = bounds[position]
        times[lo:hi] = np.asarray(result)
    return DetumbleMonteCarlo(times, cases, float(threshold), float(t_end), time.perf_counter() - t0)
