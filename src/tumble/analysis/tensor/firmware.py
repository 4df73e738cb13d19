"""What the real device does in a throw, as its logs show it (issue #42): the rotor's schedule and
the imperfections of its sensors, for the synthetic throws of :mod:`~tumble.analysis.tensor.synthetic`.

**The rotor's schedule** (the firmware of the device of Blaha, Kuijper, Pop & Smeur,
arXiv:2503.13137, read off its real logs; times from the rotor's start ``s = t - t_s``, which
comes 0.06-0.12 s after the firmware senses the release):

1. a ramp to an **idle** of ~200 rad/s over ~0.1 s, ``idle (1 - exp(-s / tau_1))``;
2. at ``s`` = 0.16-0.17 s the **spin-up** to a plateau of 1230-1360 rad/s, a first-order rise
   (``tau_2`` ~ 38 ms: ~1000 rad/s 50 ms on, ~1200 after 0.1 s);
3. at ``s`` ~ 0.36 s the **brake** back to ~210 rad/s (``tau_3`` ~ 29 ms: ~470 rad/s 40 ms on,
   ~280 after 80 ms);
4. the **log stops** 0.55-0.59 s after the start, still in flight.

The motor's torque ripple rides on the speed (three tones of 20-80 Hz, 0.3 % in all). The
logged speed is the motor's electrical RPM (eRPM, its telemetry) quantised to
:data:`ERPM_STEP` and turned into the rotor's speed with the motor's pole count, its time stamps
a fraction of a millisecond off the gyroscope's.

**The imperfections** (:class:`Imperfections`, drawn once per device by :func:`draw_imperfections`):
the gyroscope's scale factor and misalignment per axis (a small matrix ``S`` with ``omega_read =
S omega``; sensitivity errors of a few 0.1 % and misalignments of a few tenths of a degree,
assumed, inside the +-1 % limits MEMS data sheets state), the rotor's axis a little off its
nominal (the motor's mount), the motor's pole count and the accelerometer's scale and bias.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, FloatArray

__all__ = ["ERPM_STEP", "Imperfections", "RotorSchedule", "draw_imperfections", "draw_schedule", "logged_speed"]

#: The eRPM telemetry's resolution, electrical rev/min (the flight controller logs eRPM / 100).
ERPM_STEP = 100.0


@dataclass(frozen=True)
class RotorSchedule:
    """One throw's rotor speed, closed form, from its start (module docstring); times in s,
    speeds in rad/s.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.firmware import draw_schedule
    >>> sched = draw_schedule(np.random.default_rng(0))
    >>> speed, _ = sched.speed_and_rate(np.array([-0.01, 0.12, sched.t_up + 0.1, sched.t_brake + 0.15]))
    >>> speed.round(-1).tolist()   # at rest, idling, spun up, braked
    [0.0, 200.0, 1260.0, 220.0]
    """

    idle: float
    tau_idle: float
    t_up: float
    plateau: float
    tau_up: float
    t_brake: float
    idle_after: float
    tau_brake: float
    log_end: float
    ripple: FloatArray = field(repr=False)

    def speed_and_rate(self, s: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """The true speed and its rate at ``s`` s from the start, rad/s and rad/s^2 (0 before it):
        floats for a float, arrays for an array (:meth:`speed_and_rate_at`, element by element).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.firmware import draw_schedule
        >>> sched = draw_schedule(np.random.default_rng(3))
        >>> s = np.linspace(0.01, 0.5, 20001)
        >>> speed, rate = sched.speed_and_rate(s)
        >>> num = np.gradient(speed, s)   # the rate against a numerical derivative, away from the switches
        >>> ok = (np.abs(s - sched.t_up) > 1e-3) & (np.abs(s - sched.t_brake) > 1e-3)
        >>> bool(np.allclose(rate[ok][1:-1], num[ok][1:-1], rtol=0, atol=5.0))
        True
        """
        if np.ndim(s) == 0:
            return self.speed_and_rate_at(float(s))
        # element by element (numpy's vectorize): the samples of a throw, a few thousand, once
        speed, rate = np.vectorize(self.speed_and_rate_at, otypes=[float, float])(np.asarray(s, float))
        return speed, rate

    def speed_and_rate_at(self, s: float) -> tuple[float, float]:
        """:meth:`speed_and_rate` at one time, in plain floats (module docstring; the rotor's
        speed is evaluated at every stage of a synthetic flight's integration, ~6,000 times a
        throw, where numpy's cost per call on a single value was 27 us and this costs ~3 us).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.firmware import draw_schedule
        >>> sched = draw_schedule(np.random.default_rng(0))
        >>> [round(sched.speed_and_rate_at(x)[0], -1) for x in (-0.01, 0.12, sched.t_up + 0.1, sched.t_brake + 0.15)]
        [0.0, 200.0, 1260.0, 220.0]
        """
        if s < 0.0:
            return 0.0, 0.0
        w1, rise, fall, tones = self._constants
        if s < self.t_up:  # the ramp to the idle
            e = math.exp(-s / self.tau_idle)
            speed, rate = self.idle * (1.0 - e), self.idle * e / self.tau_idle
        elif s < self.t_brake:  # the spin-up
            e = math.exp(-(s - self.t_up) / self.tau_up)
            speed, rate = w1 + rise * (1.0 - e), rise * e / self.tau_up
        else:  # the brake
            e = math.exp(-(s - self.t_brake) / self.tau_brake)
            speed, rate = self.idle_after + fall * e, -fall * e / self.tau_brake
        wave, dwave = 1.0, 0.0  # the torque ripple: 1 + sum a (sin(2 pi f s + phi) - sin phi)
        for a, omega, phi, sin_phi in tones:
            wave += a * (math.sin(omega * s + phi) - sin_phi)
            dwave += a * omega * math.cos(omega * s + phi)
        return speed * wave, rate * wave + speed * dwave

    @functools.cached_property
    def _constants(self) -> tuple:
        """What :meth:`speed_and_rate_at` needs that does not depend on the time, worked out once:
        the speed at the spin-up, the rise to the plateau and the fall from the brake's speed to
        the idle after it, rad/s, and each tone of the ripple as (amplitude, angular frequency
        rad/s, phase, its sine)."""
        w1 = self.idle * (1 - math.exp(-self.t_up / self.tau_idle))
        w2 = w1 + (self.plateau - w1) * (1 - math.exp(-(self.t_brake - self.t_up) / self.tau_up))
        tones = tuple((float(a), 2 * math.pi * float(f), float(phi), math.sin(float(phi))) for a, f, phi in self.ripple)
        return w1, self.plateau - w1, w2 - self.idle_after, tones

    @property
    def switches(self) -> tuple[float, float, float]:
        """The start, spin-up and brake, s from the start: where the rate jumps.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor.firmware import draw_schedule
        >>> draw_schedule(np.random.default_rng(0)).switches[0]
        0.0
        """
        return 0.0, self.t_up, self.t_brake


def draw_schedule(rng: np.random.Generator, plateau: float | None = None) -> RotorSchedule:
    """One throw's schedule, its variations drawn (module docstring); ``plateau`` rad/s overrides.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.firmware import draw_schedule
    >>> s = draw_schedule(np.random.default_rng(1))
    >>> 0.16 <= s.t_up <= 0.17, 0.35 <= s.t_brake <= 0.37, 0.55 <= s.log_end <= 0.59
    (True, True, True)
    """
    t_up = rng.uniform(0.16, 0.17)
    ripple = np.column_stack([np.full(3, 0.003 / np.sqrt(3)), rng.uniform(20.0, 80.0, 3), rng.uniform(0, 2 * np.pi, 3)])
    return RotorSchedule(idle=rng.uniform(185.0, 215.0), tau_idle=rng.uniform(0.035, 0.05), t_up=t_up,
                         plateau=rng.uniform(1230.0, 1360.0) if plateau is None else float(plateau),
                         tau_up=rng.uniform(0.034, 0.042), t_brake=t_up + rng.uniform(0.19, 0.2),
                         idle_after=rng.uniform(200.0, 220.0), tau_brake=rng.uniform(0.026, 0.032),
                         log_end=rng.uniform(0.55, 0.59), ripple=ripple)


def logged_speed(speed: ArrayLike, poles: int, rng: np.random.Generator) -> FloatArray:
    """The speed as the flight controller logs it, rad/s: the motor's eRPM (``speed x poles / 2``
    in electrical rev/min, with 0.2 % telemetry noise) quantised to :data:`ERPM_STEP`, turned back
    with the pole count.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.firmware import logged_speed
    >>> step = 100.0 / 7 * 2 * np.pi / 60   # 14 poles: one eRPM step is 1.5 rad/s of the rotor
    >>> x = logged_speed(np.array([0.0, 1000.0]), 14, np.random.default_rng(0))
    >>> float(x[0]), bool(abs(x[1] - 1000.0) < 3 * step), bool(np.allclose(x / step, np.round(x / step)))
    (0.0, True, True)
    """
    speed = np.asarray(speed, float)
    to_erpm = 0.5 * poles * 60.0 / (2 * np.pi)
    erpm = speed * to_erpm * (1.0 + 0.002 * rng.normal(size=speed.shape))
    return np.round(erpm / ERPM_STEP) * ERPM_STEP / to_erpm


@dataclass(frozen=True)
class Imperfections:
    """One device's sensors and rotor as built: ``gyro`` (3 x 3, ``omega_read = gyro @ omega``:
    scale factors on the diagonal, misalignment off it), the rotor's true axis (unit, sensor
    frame), the motor's pole count, and the accelerometer's scale factors and bias (m/s^2; one
    sensor's, the same in every throw).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.firmware import Imperfections
    >>> Imperfections.none([0, 0, -1]).gyro.tolist() == np.eye(3).tolist()
    True
    """

    gyro: FloatArray
    rotor_axis: FloatArray
    poles: int = 14
    accel_scale: FloatArray = field(default_factory=lambda: np.ones(3))
    accel_bias: FloatArray = field(default_factory=lambda: np.zeros(3))

    @classmethod
    def none(cls, rotor_axis: ArrayLike, poles: int = 14) -> Imperfections:
        """A perfect device: an ideal gyroscope and accelerometer, the rotor on its nominal axis.

        Examples
        --------
        >>> from tumble.analysis.tensor.firmware import Imperfections
        >>> Imperfections.none([0, 0, 2]).rotor_axis.tolist()
        [0.0, 0.0, 1.0]
        """
        a = np.asarray(rotor_axis, float)
        return cls(np.eye(3), a / np.linalg.norm(a), int(poles))


def draw_imperfections(rng: np.random.Generator, rotor_axis: ArrayLike, *, scale_std: float = 0.003,
                       misalignment_std: float = np.deg2rad(0.3), axis_std: float = np.deg2rad(1.0),
                       poles: int = 14) -> Imperfections:
    """A device's imperfections drawn (module docstring): scale factors ``1 + N(0, scale_std)``,
    each axis misaligned by ``N(0, misalignment_std)`` rad toward each other axis, the rotor's
    axis turned by ``N(0, axis_std)`` rad about each axis from its nominal ``rotor_axis``; the
    accelerometer's scale factors ``1 + N(0, 0.01)`` and bias up to 0.1 m/s^2 per axis (a levelled
    flight controller's).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.firmware import draw_imperfections
    >>> imp = draw_imperfections(np.random.default_rng(0), [0, 0, -1])
    >>> bool(np.abs(imp.gyro - np.eye(3)).max() < 0.03), bool(np.degrees(np.arccos(-imp.rotor_axis[2])) < 5)
    (True, True)
    """
    gyro = np.eye(3) + np.diag(scale_std * rng.normal(size=3))
    off = misalignment_std * rng.normal(size=(3, 3))
    gyro += off - np.diag(np.diag(off))
    a = np.asarray(rotor_axis, float)
    a = Rotation.from_rotvec(axis_std * rng.normal(size=3)).apply(a / np.linalg.norm(a))
    return Imperfections(gyro, a, int(poles), 1.0 + 0.01 * rng.normal(size=3), rng.uniform(-0.1, 0.1, 3))
