"""Attitude knowledge in the loop: a controller fed the MEKF's estimate instead of the truth.

:class:`Estimated` wraps any controller (:class:`~tumble.dynamics.control.controllers.Controller`).
At each control step it takes the sensors' readings (:class:`~tumble.dynamics.models.sensors.Measurement`),
propagates a multiplicative extended Kalman filter (:class:`~tumble.dynamics.estimation.mekf.MEKF`)
from the previous step with the mean of the two gyroscope readings (the rate changes over a
step when the wheels slew the body: holding the first reading would err by half the angular
acceleration times the step squared), updates it with whatever read
this step (the magnetometer at its period, the sun sensor when lit and in view, the star
tracker at its period), and hands the controller a measurement whose attitude is the estimate
and whose rate is the gyroscope's less the estimated bias. The true attitude the sensors were
given is never read.

**Compiled.** With built-in parts (a law the compiled loop knows, or a
:class:`~tumble.dynamics.control.mission.DetumbleThenPoint` of two, coarse sun cells, a
:class:`~tumble.dynamics.models.vector_sensors.StarTracker`, the run's own field model and
sensors), :func:`~tumble.dynamics.control.controlled.simulate_controlled` runs this wrapper's
whole loop in one compiled call (:mod:`~tumble.dynamics.control.estimated_loop`), the same
formulas and the same noise: the Python path's run to round-off; :meth:`Estimated.knowledge`
gives its rows alike.

**Start.** The filter starts at the first step with a star tracker reading, or with the Sun and
the field both read (TRIAD, :func:`~tumble.dynamics.estimation.static.triad`, with its
covariance); until then the controller sees no attitude (B-dot needs none, so a detumbling
mission starts at once; a pointing law refuses to run without one).

**References.** The flight software's models of the world directions are the simulation's own:
the field model given here (the world-frame field of the run) and the sensors'
:class:`~tumble.dynamics.environment.sun.Sunlight`. A mismatch between model and truth (IGRF
against a dipole, say) is not represented.

**Noise.** The filter is told the sensors' noise: the gyroscope's per-sample deviation ``s`` at
the control period ``dt`` is the angle random walk ``s sqrt(dt)``; the magnetometer's direction
noise is ``magnetometer_noise / |B|``; each sun reading carries its own; the star tracker's
covariance is its own. A floor ``min_sigma`` (rad) keeps ideal sensors from a singular filter.
The sensors' constant biases other than the gyroscope's are not estimated: a magnetometer bias
makes the filter overconfident.

Examples
--------
Point a small body at a fixed target with wheels, from a magnetometer, six coarse sun cells and
a gyroscope; the estimate's error stays within a degree:

>>> import numpy as np
>>> from scipy.spatial.transform import Rotation
>>> from tumble.dynamics.control.controlled import simulate_controlled
>>> from tumble.dynamics.control.controllers import MRPFeedback
>>> from tumble.dynamics.control.estimated import Estimated
>>> from tumble.dynamics.environment.magnetic import DipoleField
>>> from tumble.dynamics.environment.orbit import CircularOrbit
>>> from tumble.dynamics.environment.sun import Sunlight
>>> from tumble.dynamics.models.actuators import ReactionWheels
>>> from tumble.dynamics.models.sensors import Sensors
>>> from tumble.dynamics.models.vector_sensors import CoarseSunSensor
>>> orbit = CircularOrbit(altitude=500e3, inclination=1.7)
>>> sensors = Sensors(gyro_noise=1e-4, gyro_bias=(2e-4, 0.0, -1e-4), magnetometer_noise=2e-7, attitude="none",
...                   sun_sensor=CoarseSunSensor(noise=2e-3), sunlight=Sunlight(orbit, "2026-06-01T00:00:00"), seed=1)
>>> rw = ReactionWheels(np.eye(3), inertia=1e-5, max_torque=2e-3)
>>> moments = [0.02, 0.03, 0.04]
>>> c = Estimated(MRPFeedback(K=1e-3, P=1e-2, period=0.5, moments=moments, wheels=rw), sensors, DipoleField(orbit))
>>> run = simulate_controlled(moments, [0.0, 0.0, 0.0], t_end=120.0, controller=c, field=DipoleField(orbit),
...                           wheels=rw, sensors=sensors, attitude0=Rotation.from_rotvec([0.3, 0.0, 0.0]))
>>> k = c.knowledge()
>>> bool(np.degrees(k.error(run)[-1]).max() < 1.0), k.used.sum(axis=0).tolist()   # magnetometer, sun, tracker
(True, [240, 240, 0])
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from ..._html import field_repr, fmt, result_html, result_repr, vec
from ...typing import FloatArray
from ...validation import check_positive
from ..environment.magnetic import MagneticField
from ..estimation.mekf import MEKF
from ..estimation.static import triad
from ..models.actuators import Command
from ..models.sensors import Measurement, Sensors
from ..models.vector_sensors import on_period
from .controllers import Controller

__all__ = ["Estimated", "Knowledge"]


@dataclass(frozen=True, eq=False)
class Knowledge:
    """What the filter knew at each control step from its start.

    Attributes
    ----------
    t : ndarray, shape (n,)
        Times of the steps, s.
    attitude : scipy Rotation, n rotations
        The estimate after the step's updates, body (principal) to world.
    bias : ndarray, shape (n, 3)
        The estimated gyroscope bias, rad/s.
    sigma : ndarray, shape (n, 6)
        Standard deviations of the attitude error about the body axes (rad) and of the bias (rad/s).
    used : ndarray of bool, shape (n, 3)
        Which sensors updated the filter at each step: magnetometer, sun sensor, star tracker.

    Examples
    --------
    :meth:`Estimated.knowledge` makes one, a row a control step (here a star tracker every 1 s):

    >>> import numpy as np
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.control.estimated import Estimated
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> from tumble.dynamics.models.vector_sensors import StarTracker
    >>> sensors = Sensors(gyro_noise=1e-4, star_tracker=StarTracker(cross=1e-5, roll=1e-4, period=1.0))
    >>> c = Estimated(BDot(gain=1e-3, period=0.5), sensors)
    >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.05], t_end=5.0, controller=c, sensors=sensors)
    >>> k = c.knowledge()
    >>> len(k.t), k.used[:3].tolist()
    (10, [[False, False, True], [False, False, False], [False, False, True]])
    >>> repr(k).startswith("Knowledge(steps 10 over 4.5 s, attitude sigma at the end ("), repr(k).endswith("star tracker 5)")
    (True, True)
    """

    t: FloatArray
    attitude: Rotation
    bias: FloatArray
    sigma: FloatArray
    used: np.ndarray

    def _rows(self) -> list[tuple[str, str]]:
        n = len(self.t)
        rows = [("steps", f"{n} over {fmt(self.t[-1] - self.t[0]) if n else 0} s")]
        if n:
            rows += [("attitude sigma at the end", f"{vec(self.sigma[-1, :3])} rad"),
                     ("bias sigma at the end", f"{vec(self.sigma[-1, 3:])} rad/s")]
        counts = np.sum(self.used, axis=0).tolist() if n else [0, 0, 0]
        rows.append(("updates", ", ".join(f"{name} {c}" for name, c in zip(("magnetometer", "sun sensor", "star tracker"),
                                                                               counts))))
        return rows

    def __repr__(self) -> str:
        return result_repr("Knowledge", [f"{label} {value}" for label, value in self._rows()])

    def _repr_html_(self) -> str:
        return result_html("Knowledge", self._rows())

    def error(self, run: object) -> FloatArray:
        """The estimate's error about the body axes at each step, ``A_true = A_est exp([e x])``, rad, shape (n, 3).

        ``run`` is the :class:`~tumble.dynamics.control.controlled.ControlledRun` the filter
        rode in (its true attitude at the same steps).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.control.controlled import simulate_controlled
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.estimated import Estimated
        >>> from tumble.dynamics.models.sensors import Sensors
        >>> from tumble.dynamics.models.vector_sensors import StarTracker
        >>> sensors = Sensors(gyro_noise=1e-4, star_tracker=StarTracker(cross=1e-5, roll=1e-4, period=1.0))
        >>> c = Estimated(BDot(gain=1e-3, period=0.5), sensors)
        >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.05], t_end=5.0, controller=c, sensors=sensors)
        >>> bool(np.degrees(np.linalg.norm(c.knowledge().error(run), axis=1)).max() < 0.05)   # the roll noise: 0.006 deg
        True
        """
        t_run = np.asarray(getattr(run, "t"))
        idx = np.searchsorted(t_run, self.t - 1e-9)
        truth: Rotation = getattr(run, "attitude")[idx]
        return np.asarray((self.attitude.inv() * truth).as_rotvec(), float)


@dataclass
class Estimated:
    """A controller that sees the MEKF's estimate of the attitude (module docstring).

    Parameters
    ----------
    controller : Controller
        The law fed the estimate; its period is this one's.
    sensors : Sensors
        The sensors of the run (their noise tells the filter what to expect; their
        ``sunlight`` gives the Sun's reference direction).
    field : MagneticField, optional
        The flight software's field model (world frame): the magnetometer's reference. Without
        it the magnetometer is not used.
    magnetometer_period : float
        Seconds between the magnetometer's updates (0: every step).
    attitude_sigma : float, optional
        The least standard deviation of the start's attitude about any axis, rad (at most pi):
        TRIAD's or the tracker's covariance, whose axes keep theirs, raised to it where smaller
        (a start one trusts less than the sensors' noise says, for errors they do not model).
        None (the default): theirs as it is.
    bias_sigma : float
        The first bias guess's (zero's) standard deviation, rad/s.
    bias_walk : float
        The bias's random walk density the filter assumes, rad/s^1.5.
    min_sigma : float
        Floor of the vector sensors' angular noise, rad.

    Examples
    --------
    A B-dot law fed the estimate of a gyroscope and a star tracker (the module docstring has a
    pointing run on a magnetometer and sun sensors):

    >>> import numpy as np
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.control.estimated import Estimated
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> from tumble.dynamics.models.vector_sensors import StarTracker
    >>> sensors = Sensors(gyro_noise=1e-4, star_tracker=StarTracker(cross=1e-5, roll=1e-4, period=1.0))
    >>> c = Estimated(BDot(gain=1e-3, period=0.5), sensors)
    >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.05], t_end=5.0, controller=c, sensors=sensors)
    >>> c.period, len(c.knowledge().t)
    (0.5, 10)
    """

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    controller: Controller
    sensors: Sensors
    field: MagneticField | None = None
    magnetometer_period: float = 0.0
    attitude_sigma: float | None = None
    bias_sigma: float = 1e-3
    bias_walk: float = 1e-7
    min_sigma: float = 1e-5
    _filter: MEKF | None = dataclasses.field(default=None, init=False, repr=False)
    _last: tuple[float, FloatArray] | None = dataclasses.field(default=None, init=False, repr=False)
    _rows: list[tuple[float, FloatArray, FloatArray, FloatArray, tuple[bool, bool, bool]]] = \
        dataclasses.field(default_factory=list, init=False, repr=False)
    _table: Knowledge | None = dataclasses.field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        if not isinstance(self.sensors, Sensors):
            raise ValueError(f"sensors = {self.sensors!r} must be the run's Sensors")  # noqa: TRY004
        if self.sensors.attitude == "star_tracker":  # read by no one here: the filter's tracker is sensors.star_tracker
            raise ValueError("sensors.attitude = 'star_tracker' is not read by Estimated: the filter takes a star "
                             "tracker as Sensors(star_tracker=StarTracker(cross=..., roll=..., period=...))")
        check_positive("magnetometer_period", self.magnetometer_period, "s", allow_zero=True)
        if self.attitude_sigma is not None:
            check_positive("attitude_sigma", self.attitude_sigma, "rad", at_most=math.pi)
        check_positive("bias_sigma", self.bias_sigma, "rad/s")
        check_positive("bias_walk", self.bias_walk, "rad/s^1.5", allow_zero=True)
        check_positive("min_sigma", self.min_sigma, "rad")
        check_positive("controller.period", getattr(self.controller, "period", None), "s")

    @property
    def period(self) -> float:
        """The control period, s: the wrapped controller's.

        Examples
        --------
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.estimated import Estimated
        >>> from tumble.dynamics.models.sensors import Sensors
        >>> Estimated(BDot(gain=1e-3, period=0.25), Sensors()).period
        0.25
        """
        return float(self.controller.period)

    def reset(self) -> None:
        """Forget the filter and its history (and reset the wrapped controller), for a fresh run.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.control.controlled import simulate_controlled
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.estimated import Estimated
        >>> from tumble.dynamics.models.sensors import Sensors
        >>> from tumble.dynamics.models.vector_sensors import StarTracker
        >>> sensors = Sensors(gyro_noise=1e-4, star_tracker=StarTracker(cross=1e-5, roll=1e-4, period=1.0))
        >>> c = Estimated(BDot(gain=1e-3, period=0.5), sensors)
        >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.05], t_end=5.0, controller=c, sensors=sensors)
        >>> c.reset()
        >>> c.knowledge()
        Traceback (most recent call last):
        ...
        ValueError: the filter never started: no star tracker reading, nor the Sun and the field together
        """
        self._filter, self._last, self._rows, self._table = None, None, [], None
        if hasattr(self.controller, "reset"):
            self.controller.reset()

    def start(self, t: float, m: Measurement) -> MEKF | None:
        """The filter started from the readings ``m`` at ``t`` (s), or None when they cannot start it
        (module docstring: a star tracker's reading, else TRIAD on the Sun and the field).

        Examples
        --------
        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.estimated import Estimated
        >>> from tumble.dynamics.models.sensors import Measurement, Sensors
        >>> from tumble.dynamics.models.vector_sensors import StarTracker
        >>> c = Estimated(BDot(gain=1e-3, period=0.5), Sensors(star_tracker=StarTracker(cross=1e-5, roll=1e-4)))
        >>> f = c.start(0.0, Measurement(0.0, np.zeros(3), None, None, star_tracker=Rotation.identity()))
        >>> f.sigma.round(6).tolist()
        [1.4e-05, 1.4e-05, 0.0001, 0.001, 0.001, 0.001]
        >>> c = Estimated(BDot(gain=1e-3, period=0.5), c.sensors, attitude_sigma=5e-5)   # a start trusted less
        >>> c.start(0.0, Measurement(0.0, np.zeros(3), None, None, star_tracker=Rotation.identity())).sigma.round(6).tolist()
        [5e-05, 5e-05, 0.0001, 0.001, 0.001, 0.001]
        >>> c.start(0.0, Measurement(0.0, np.zeros(3), None, None)) is None
        True
        """
        gyro_noise = self.sensors.gyro_noise * math.sqrt(self.period)
        if m.star_tracker is not None and self.sensors.star_tracker is not None:
            P = self.sensors.star_tracker.covariance + self.min_sigma**2 * np.eye(3)
            q = m.star_tracker.as_quat()
        elif m.sun is not None and m.field is not None and self.field is not None and self.sensors.sunlight is not None:
            sun_world, field_world = self.sensors.sunlight.world(t), self.field.world(t)
            sigmas = (min(max(m.sun_sigma, self.min_sigma), math.pi), min(self._mag_sigma(m), math.pi))  # pi: no direction
            att, P = triad([m.sun, m.field], [sun_world, field_world], sigmas)
            q = att.as_quat()
        else:
            return None
        if self.attitude_sigma is not None:  # each of its axes' variances at least attitude_sigma^2
            w, V = np.linalg.eigh(P)
            P = (V * np.maximum(w, self.attitude_sigma**2)) @ V.T
        cov = np.zeros((6, 6))
        cov[:3, :3], cov[3:, 3:] = P, self.bias_sigma**2 * np.eye(3)
        return MEKF(q, np.zeros(3), cov, gyro_noise, self.bias_walk)

    def _mag_sigma(self, m: Measurement) -> float:
        b = float(np.linalg.norm(m.field)) if m.field is not None else 0.0
        return max(self.sensors.magnetometer_noise / b if b > 0.0 else math.inf, self.min_sigma)

    def __call__(self, t: float, measurement: Measurement) -> Command:
        """Propagate and update the filter with this step's readings, then call the controller with the estimate.

        Examples
        --------
        A star tracker's reading starts the filter; the law sees the estimate:

        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.control.estimated import Estimated
        >>> from tumble.dynamics.models.actuators import Command
        >>> from tumble.dynamics.models.sensors import Measurement, Sensors
        >>> from tumble.dynamics.models.vector_sensors import StarTracker
        >>> class Spy:
        ...     period = 1.0
        ...     def __call__(self, t, m):
        ...         self.seen = m.attitude
        ...         return Command()
        >>> c = Estimated(Spy(), Sensors(star_tracker=StarTracker(cross=1e-5, roll=1e-4)))
        >>> reading = Rotation.from_rotvec([0.0, 0.0, 0.3])
        >>> _ = c(0.0, Measurement(0.0, np.zeros(3), None, None, star_tracker=reading))
        >>> round(float((c.controller.seen * reading.inv()).magnitude()), 12)
        0.0
        """
        m = measurement
        f = self._filter
        used = (False, False, False)
        if f is None:
            f = self.start(t, m)
            if f is not None:
                used = (m.star_tracker is None, m.star_tracker is None, m.star_tracker is not None)
        else:
            assert self._last is not None
            t0, gyro = self._last
            if t > t0:  # the rate over the step: the mean of its two readings (the trapezoid rule)
                f = f.propagate(0.5 * (gyro + np.asarray(m.omega, float)), t - t0)
            mag = sun = tracker = False
            if m.field is not None and self.field is not None and on_period(t, self.magnetometer_period):
                f, _ = f.update_vector(m.field, self.field.world(t), self._mag_sigma(m))
                mag = True
            if m.sun is not None and self.sensors.sunlight is not None:
                f, _ = f.update_vector(m.sun, self.sensors.sunlight.world(t), max(m.sun_sigma, self.min_sigma))
                sun = True
            if m.star_tracker is not None and self.sensors.star_tracker is not None:
                f, _ = f.update_attitude(m.star_tracker, self.sensors.star_tracker.covariance + self.min_sigma**2 * np.eye(3))
                tracker = True
            used = (mag, sun, tracker)
        self._filter, self._last = f, (float(t), np.asarray(m.omega, float))
        if f is None:
            return self.no_attitude(t, m)
        self._rows.append((float(t), f.quaternion.copy(), f.bias.copy(), f.sigma, used))
        seen = dataclasses.replace(m, attitude=f.attitude, omega=np.asarray(m.omega - f.bias, float))
        return self.controller(t, seen)

    def no_attitude(self, t: float, m: Measurement) -> Command:
        """The controller's command before the filter starts: fed the readings ``m`` with no
        attitude (B-dot needs none); a law that needs one raises, saying why there is none.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.estimated import Estimated
        >>> from tumble.dynamics.models.sensors import Measurement, Sensors
        >>> c = Estimated(BDot(gain=1e4, period=0.5), Sensors())
        >>> (c.no_attitude(0.0, Measurement(0.0, np.array([0.0, 0.0, 0.1]), np.array([2e-5, 0.0, 0.0]), None)).dipole.round(12) + 0.0).tolist()
        [0.0, 0.02, 0.0]
        """
        try:
            return self.controller(t, dataclasses.replace(m, attitude=None))
        except ValueError as exc:  # a law that needs an attitude: say why there is none
            raise ValueError(f"t = {t:g} s: the attitude filter has not started (it needs a star tracker reading, "
                             f"or the Sun and the field read together), and the controller needs an attitude: "
                             f"{exc}") from None

    def record(self, t: FloatArray, q: FloatArray, bias: FloatArray, sigma: FloatArray, used: np.ndarray) -> None:
        """Keep the filter's rows of a run made elsewhere (the compiled loop,
        :mod:`~tumble.dynamics.control.estimated_loop`): :meth:`knowledge` returns them.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.estimated import Estimated
        >>> from tumble.dynamics.models.sensors import Sensors
        >>> c = Estimated(BDot(gain=1e4, period=0.5), Sensors())
        >>> c.record(np.zeros(1), np.array([[0.0, 0.0, 0.0, 1.0]]), np.zeros((1, 3)), np.ones((1, 6)), np.ones((1, 3), bool))
        >>> c.knowledge().t.tolist()
        [0.0]
        """
        self._rows = []
        self._table = Knowledge(np.asarray(t, float), Rotation.from_quat(q), np.asarray(bias, float),
                                np.asarray(sigma, float), np.asarray(used, bool)) if len(t) else None

    def knowledge(self) -> Knowledge:
        """The filter's estimates from its start to the last step (:class:`Knowledge`).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.control.controlled import simulate_controlled
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.control.estimated import Estimated
        >>> from tumble.dynamics.models.sensors import Sensors
        >>> from tumble.dynamics.models.vector_sensors import StarTracker
        >>> sensors = Sensors(gyro_noise=1e-4, star_tracker=StarTracker(cross=1e-5, roll=1e-4, period=1.0))
        >>> c = Estimated(BDot(gain=1e-3, period=0.5), sensors)
        >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.05], t_end=5.0, controller=c, sensors=sensors)
        >>> k = c.knowledge()
        >>> k.t[:3].tolist(), k.sigma.shape, k.bias.shape
        ([0.0, 0.5, 1.0], (10, 6), (10, 3))
        """
        if self._table is not None:
            return self._table
        if not self._rows:
            raise ValueError("the filter never started: no star tracker reading, nor the Sun and the field together")
        t, q, b, s, u = zip(*self._rows)
        return Knowledge(np.array(t), Rotation.from_quat(np.array(q)), np.array(b), np.array(s), np.array(u, bool))
