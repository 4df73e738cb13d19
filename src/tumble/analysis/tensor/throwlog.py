"""One throw's log in the sensor frame: :class:`Throw`, its times, rates, rotor speeds and
accelerations, checked as a logger writes them (the device's own description is
:mod:`~tumble.analysis.tensor.device`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..._html import headline_html, headline_repr
from ...typing import FloatArray
from ...validation import check_increasing, check_vectors, short_repr

__all__ = ["MAX_INTERVAL", "MIN_THROW_SAMPLES", "TOP_SPEED_SAMPLES", "Throw", "running_peak"]

#: The longest interval between a throw's samples, s: a logger writes hundreds a second.
MAX_INTERVAL = 1.0
#: What no throw's sensors read (far beyond a gyroscope's 2000 deg/s, a motor's 10^5 rpm, an
#: accelerometer's 16 g): rad/s, rad/s, m/s^2.
_PLAUSIBLE = {"omega": 1e3, "rotor": 1e5, "accel": 1e4}
#: The fewest samples a throw may have.
MIN_THROW_SAMPLES = 20
#: The running median's length of :func:`running_peak` (samples; 1.25 ms at 4 kHz).
TOP_SPEED_SAMPLES = 5


@dataclass(frozen=True)
class Throw:
    """One throw's log, sensor frame.

    Attributes
    ----------
    t : ndarray, shape (n,)
        Sample times, s, strictly increasing (irregular allowed).
    omega : ndarray, shape (n, 3)
        Gyroscope, rad/s.
    rotor : ndarray, shape (n,)
        The rotor's speed relative to the device, rad/s (positive about ``Device.rotor_axis``).
    accel : ndarray, shape (n, 3), or None
        Accelerometer's specific force, m/s^2 (needed for the centres of mass).
    input : str
        Where it came from (a file's path as given), for messages and reports.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import Throw
    >>> t = np.arange(100) / 4000.0
    >>> Throw(t, np.zeros((100, 3)), np.zeros(100), None, "a.csv").accel is None
    True
    >>> Throw(t, np.zeros((100, 2)), np.zeros(100))
    Traceback (most recent call last):
    ...
    ValueError: throw omega must have shape (100, 3) (rad/s), not (100, 2)
    """

    HEADLINE = (("input", "file", ""), ("samples", "samples", ""), ("duration", "over", "s"))
    __repr__ = headline_repr
    _repr_html_ = headline_html

    t: FloatArray = field(repr=False)
    omega: FloatArray = field(repr=False)
    rotor: FloatArray = field(repr=False)
    accel: FloatArray | None = field(default=None, repr=False)
    input: str = ""

    def __post_init__(self) -> None:
        where = f"throw {self.input}" if self.input else "throw"
        t = check_vectors(f"{where} t", self.t, "s", size=None)
        if t.ndim != 1 or t.size < MIN_THROW_SAMPLES:
            raise ValueError(f"{where} t must be a list of at least {MIN_THROW_SAMPLES} times (s), got shape {t.shape}")
        check_increasing(f"{where} t", t)
        jump = np.flatnonzero(np.diff(t) > MAX_INTERVAL)
        if jump.size:
            k = int(jump[0]) + 1
            raise ValueError(f"{where} t[{k}] = {float(t[k])!r} s comes {t[k] - t[k - 1]:.3g} s after the sample before it: a "
                             f"logger's samples are at most {MAX_INTERVAL:g} s apart (a time written wrongly)")
        n = t.size
        arrays = {"omega": ((n, 3), "rad/s", self.omega), "rotor": ((n,), "rad/s", self.rotor),
                  "accel": ((n, 3), "m/s^2", self.accel)}
        s = object.__setattr__
        s(self, "t", t)
        for name, (shape, unit, value) in arrays.items():
            if value is None and name == "accel":
                continue
            a = check_vectors(f"{where} {name}", value, unit, size=None)
            if a.shape != shape:
                raise ValueError(f"{where} {name} must have shape {shape} ({unit}), not {a.shape}")
            beyond = np.flatnonzero(np.any(np.abs(a.reshape(n, -1)) > _PLAUSIBLE[name], axis=1))
            if beyond.size:
                k = int(beyond[0])
                raise ValueError(f"{where} {name}[{k}] = {short_repr(a[k].tolist())} ({unit}) is beyond any sensor's "
                                 f"range (at most {_PLAUSIBLE[name]:g} {unit}; a value in other units or written wrongly)")
            s(self, name, a)


    @property
    def samples(self) -> int:
        """The log's number of samples.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor import Throw
        >>> Throw(np.arange(100) / 4000.0, np.zeros((100, 3)), np.zeros(100), None, "a.csv")
        Throw(file a.csv, samples 100, over 0.02475 s)
        """
        return len(self.t)

    @property
    def duration(self) -> float:
        """The log's span, s (its first sample to its last).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor import Throw
        >>> Throw(np.arange(100) / 4000.0, np.zeros((100, 3)), np.zeros(100)).duration
        0.02475
        """
        return float(self.t[-1] - self.t[0])

    @property
    def top_speed(self) -> float:
        """The rotor's top speed in the log, rad/s: the largest of its speeds' running median over
        :data:`TOP_SPEED_SAMPLES` samples (``scipy.ndimage.median_filter``), so that a telemetry
        glitch of a sample or two is not taken for it. On the real device, its plateau (1230-1360
        rad/s, docs/tensor.md), the same in every throw the firmware makes.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.tensor import Throw
        >>> t = np.arange(100) / 4000.0
        >>> rotor = np.where((t > 0.005) & (t < 0.02), 1300.0, 200.0)
        >>> rotor[3] = 9e4   # one glitch
        >>> Throw(t, np.zeros((100, 3)), rotor).top_speed
        1300.0
        """
        return running_peak(np.abs(self.rotor))


def running_peak(values: FloatArray) -> float:
    """The largest of ``values``' running median over :data:`TOP_SPEED_SAMPLES` samples
    (``scipy.ndimage.median_filter``): a log's peak that a glitch of a sample or two does not make
    (a rotor's top speed, an accelerometer's largest reading).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.throwlog import running_peak
    >>> running_peak(np.array([1.0, 1.0, 9.0, 1.0, 2.0, 2.0, 2.0]))   # the lone 9 is a glitch
    2.0
    """
    from scipy.ndimage import median_filter

    return float(np.max(median_filter(np.asarray(values, float), size=TOP_SPEED_SAMPLES, mode="nearest")))

