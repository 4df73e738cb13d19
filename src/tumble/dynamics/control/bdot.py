"""B-dot detumbling with magnetorquers: the controller, its dipole and its gain.

**B-dot** (Stickler & Alfriend, "An elementary magnetic attitude control system", AIAA
Mechanics and Control of Flight Conference, 1974, AIAA 74-923): ``m = -k_b dB/dt`` with B the
field in the body frame. With the field's own motion along the orbit (~n) neglected against the
spin, ``dB/dt ~ -omega x B = B x omega``, so ``m = k_b omega x B`` and the torque
``m x B = -k_b |B|^2 (omega - (omega . b) b)`` (``b = B / |B|``) damps the spin across the field.
The *normalised* form ``m = (k / |B|^2) omega x B`` gives ``tau = -k omega_perp`` with ``k`` in
N m s; Avanzini & Giulietti ("Magnetic detumbling of a rigid spacecraft", J. Guid. Control Dyn.
35(4), 2012) choose ``k = 2 n (1 + sin xi_m) I_min`` (:func:`bdot_gain`), ``xi_m`` the inclination
of the orbit to the geomagnetic equator and ``I_min`` the smallest principal moment.
``dB/dt`` is taken either from the gyroscope (``B x omega``, derivative="gyro") or from the
difference of the last two magnetometer readings (derivative="difference"; zero at the first step).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..._html import field_repr
from ...typing import ArrayLike, FloatArray
from ...validation import check_positive
from ..models.actuators import Command
from ..models.sensors import Measurement
from .laws import bdot_components, gyro_field_rate_components

__all__ = ["BDot", "bdot_dipole", "bdot_gain"]


def _three(v: ArrayLike) -> tuple[float, float, float]:
    """A 3-vector's components as floats, for the laws' functions (:mod:`~tumble.dynamics.control.laws`)."""
    a = np.asarray(v, float)
    return float(a[0]), float(a[1]), float(a[2])


def bdot_gain(mean_motion: float, geomagnetic_inclination: float, min_moment: float) -> float:
    """Avanzini & Giulietti's B-dot gain ``k = 2 n (1 + sin xi_m) I_min``, N m s: the normalised
    form's, so give it to ``BDot(gain=..., form="normalized")`` (``BDot``'s default form, classic,
    reads a gain in A m^2 s/T, and this one would be ~1e9 times too weak there: ``|B|^2`` in low orbit).

    Parameters
    ----------
    mean_motion : float
        Orbital mean motion ``n``, rad/s.
    geomagnetic_inclination : float
        ``xi_m``, the orbit's inclination to the geomagnetic equator, rad.
    min_moment : float
        Smallest principal moment ``I_min``, kg m^2.

    Examples
    --------
    >>> import math
    >>> from tumble.dynamics.control.bdot import bdot_gain
    >>> round(bdot_gain(1.1e-3, math.pi / 2, 0.01), 9)
    4.4e-05
    """
    n = check_positive("mean_motion", mean_motion, "rad/s")
    i_min = check_positive("min_moment", min_moment, "kg m^2")
    return 2.0 * n * (1.0 + math.sin(float(geomagnetic_inclination))) * i_min


def bdot_dipole(b_dot: ArrayLike, field: ArrayLike, gain: ArrayLike, form: str = "classic") -> FloatArray:
    """The B-dot dipole ``m = -k dB/dt`` (A m^2), ``k = gain`` (classic, A m^2 s/T) or
    ``gain / |B|^2`` (normalized, gain in N m s); broadcast over leading axes (..., 3).

    Examples
    --------
    >>> from tumble.dynamics.control.bdot import bdot_dipole
    >>> (bdot_dipole([0.0, 0.0, -2e-6], [2e-5, 0.0, 0.0], 1e4) + 0.0).tolist()   # A m^2
    [0.0, 0.0, 0.02]
    """
    d, b = np.asarray(b_dot, float), np.asarray(field, float)
    return np.stack(np.broadcast_arrays(*bdot_components(d[..., 0], d[..., 1], d[..., 2], b[..., 0], b[..., 1], b[..., 2],
                                                         np.asarray(gain, float), form == "normalized")), axis=-1)


@dataclass
class BDot:
    """B-dot detumbling with magnetorquers.

    Parameters
    ----------
    gain : float
        ``k_b`` (A m^2 s/T) for form="classic", ``k`` (N m s) for form="normalized" (> 0).
    period : float
        Control period, s (> 0).
    form : {"classic", "normalized"}
        ``m = -k_b dB/dt`` or ``m = -(k / |B|^2) dB/dt`` (module docstring).
    derivative : {"gyro", "difference"}
        ``dB/dt`` from ``B x omega`` or from successive magnetometer readings.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.models.sensors import Measurement
    >>> c = BDot(gain=1e4, period=1.0)
    >>> m = Measurement(0.0, np.array([0.0, 0.0, 0.1]), np.array([2e-5, 0.0, 0.0]), None)
    >>> (c(0.0, m).dipole + 0.0).round(12).tolist()   # k_b omega x B, A m^2
    [0.0, 0.02, 0.0]
    """

    __repr__ = field_repr  # one line: arrays by value when short, by shape otherwise

    gain: float
    period: float
    form: str = "classic"
    derivative: str = "gyro"
    _last: tuple[float, FloatArray] | None = field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        check_positive("gain", self.gain, "A m^2 s/T or N m s")
        check_positive("period", self.period, "s")
        if self.form not in ("classic", "normalized"):
            raise ValueError(f"form = {self.form!r} is unknown; allowed: classic, normalized")
        if self.derivative not in ("gyro", "difference"):
            raise ValueError(f"derivative = {self.derivative!r} is unknown; allowed: gyro, difference")

    def reset(self) -> None:
        """Forget the last magnetometer reading (a new run).

        Examples
        --------
        With ``derivative="difference"`` the first step has no earlier reading and asks for no
        dipole; after a reset the next step is a first step again:

        >>> import numpy as np
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.models.sensors import Measurement
        >>> c = BDot(gain=1e4, period=1.0, derivative="difference")
        >>> def reading(t, bx):
        ...     return Measurement(t, np.zeros(3), np.array([bx, 0.0, 0.0]), None)
        >>> bool(c(0.0, reading(0.0, 2e-5)).dipole.any())
        False
        >>> np.allclose(c(1.0, reading(1.0, 3e-5)).dipole, [-0.1, 0.0, 0.0])   # -k_b dB/dt
        True
        >>> c.reset()
        >>> bool(c(2.0, reading(2.0, 4e-5)).dipole.any())
        False
        """
        self._last = None

    def __call__(self, t: float, measurement: Measurement) -> Command:
        """The dipole ``-k dB/dt`` (A m^2) for this reading; zero without a field reading.

        Examples
        --------
        A body spinning at 0.1 rad/s about z sees a fixed field turn the other way. The
        dipole opposes the field's change (``m . dB/dt < 0``), and the magnetometer difference
        over a short step agrees with the gyroscope's ``B x omega`` at the step's middle:

        >>> import numpy as np
        >>> from scipy.spatial.transform import Rotation
        >>> from tumble.dynamics.control.bdot import BDot
        >>> from tumble.dynamics.models.sensors import Measurement
        >>> omega, b0, dt = np.array([0.0, 0.0, 0.1]), np.array([2e-5, 0.0, 1e-5]), 0.01
        >>> def reading(t):   # the field in the body frame at t
        ...     return Measurement(t, omega, Rotation.from_rotvec(-omega * t).apply(b0), None)
        >>> gyro = BDot(gain=1e4, period=dt)(dt / 2, reading(dt / 2)).dipole
        >>> diff = BDot(gain=1e4, period=dt, derivative="difference")
        >>> _ = diff(0.0, reading(0.0))
        >>> m = diff(dt, reading(dt)).dipole
        >>> b_dot = (reading(dt).field - reading(0.0).field) / dt
        >>> bool(m @ b_dot < 0.0), np.allclose(m, gyro, rtol=1e-5, atol=1e-12)
        (True, True)

        The normalised form's torque is ``-k omega_perp`` whatever ``|B|``:

        >>> c = BDot(gain=1e-4, period=1.0, form="normalized")
        >>> b = np.array([0.0, 3e-5, 0.0])
        >>> dipole = c(0.0, Measurement(0.0, np.array([0.1, 0.2, 0.0]), b, None)).dipole
        >>> np.allclose(np.cross(dipole, b), [-1e-5, 0.0, 0.0])
        True
        >>> c(0.0, Measurement(0.0, omega, None, None)).dipole.tolist()   # no field reading
        [0.0, 0.0, 0.0]
        """
        b = measurement.field
        if b is None:
            return Command(dipole=np.zeros(3))
        if self.derivative == "gyro":
            b_ = _three(b)
            return Command(dipole=np.array(bdot_components(*gyro_field_rate_components(*b_, *_three(measurement.omega)), *b_,
                                                           self.gain, self.form == "normalized")))
        b_dot = np.zeros(3) if self._last is None else (b - self._last[1]) / (t - self._last[0])
        self._last = (float(t), b)
        return Command(dipole=bdot_dipole(b_dot, b, self.gain, self.form))
