"""Orbits beyond the circle: a Keplerian ellipse from its elements and a two-line element set
through SGP4 (the gravity-gradient torque along either is
:func:`~tumble.dynamics.models.orbit_gravity.gravity_gradient_of`).

**Keplerian orbit** (Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed., 2013):
the mean anomaly ``M = M0 + n t`` with ``n = sqrt(mu / a^3)``; Kepler's equation
``M = E - e sin E`` solved for the eccentric anomaly ``E`` by Newton's method (sec. 2.2,
algorithm 2); the position and velocity in the perifocal frame

``r = a (cos E - e, sqrt(1 - e^2) sin E, 0)``,  ``v = sqrt(mu a) / |r| (-sin E, sqrt(1 - e^2) cos E, 0)``

(sec. 2.2, eqs. 2-35 and 2-36), turned into ECI by ``R3(-raan) R1(-i) R3(-argp)`` (sec. 2.6,
algorithm 10, COE2RV). The orbit is two-body: no J2, no drag.

**TLE orbits** come from SGP4 (Vallado, Crawford, Hujsak & Kelso, "Revisiting Spacetrack Report
#3", AIAA 2006-6753) through the ``sgp4`` package (``pip install tumble[orbit]``); SGP4 gives
positions in its TEME frame, used here as the inertial frame (TEME differs from J2000 by
precession and nutation, a few tenths of a degree, and turns into the Earth-fixed frame by
the sidereal angle below, to polar motion).

**World frame.** For these orbits the world frame of a control run is the inertial frame itself
(ECI or TEME): ``eci_from_world`` is the identity and ``position_world`` is ``position_eci``
(a :class:`~tumble.dynamics.environment.orbit.CircularOrbit` keeps its orbit-plane frame).

The dates and the Earth's sidereal angle are :mod:`~tumble.dynamics.environment.sidereal`.
"""

from __future__ import annotations

import datetime as _dt
import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from ..._optional import optional_import
from ...typing import ArrayLike, FloatArray, Vector3
from ...validation import check_number, check_positive
from .earth import MU_EARTH, R_EARTH, check_mu, is_earth
from .sidereal import J2000

__all__ = ["MAX_TLE_AGE", "KeplerOrbit", "TLEAgeWarning", "TLEOrbit"]

#: How far from its epoch (s, either way) a TLE is propagated without a warning: 30 days. SGP4's
#: error grows from ~1 km at the epoch by ~1-3 km a day (Vallado, Crawford, Hujsak & Kelso, "Revisiting
#: Spacetrack Report #3", AIAA 2006-6753), and the drag terms of an element set hold for days.
MAX_TLE_AGE = 30 * 86400.0


class TLEAgeWarning(UserWarning):
    """A TLE propagated more than :data:`MAX_TLE_AGE` from its epoch: the orbit is SGP4's extrapolation,
    its position off by ~1-3 km a day; a newer element set gives the orbit of that time. The command line
    says it in one line.

    Examples
    --------
    >>> import warnings
    >>> from tumble.dynamics.environment.ephemeris import TLEAgeWarning, TLEOrbit
    >>> iss = TLEOrbit("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
    ...                "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537")
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     _ = iss.position_eci(90 * 86400.0)   # 90 days on
    >>> caught[0].category is TLEAgeWarning, str(caught[0].message)[:50]
    (True, 'the TLE is propagated 90 days from its epoch 2008-')
    """

    cli_one_line = True


def _kepler_eccentric(M: FloatArray, e: float) -> FloatArray:
    """``E`` with ``E - e sin E = M`` by Newton's method (Vallado algorithm 2), to round-off."""
    E = np.where(e < 0.8, M, math.pi * np.sign(np.sin(M)) + 0.0 * M)
    for _ in range(60):
        step = (E - e * np.sin(E) - M) / (1.0 - e * np.cos(E))
        E = E - step
        if np.all(np.abs(step) <= 4e-16 * np.maximum(1.0, np.abs(E))):
            break
    return np.asarray(E, float)


@dataclass(frozen=True)
class KeplerOrbit:
    """A two-body Keplerian orbit from its classical elements (m, rad) about ``mu`` (m^3/s^2).

    Parameters
    ----------
    semi_major_axis : float
        ``a``, m (> 0); the perigee ``a (1 - e)`` must lie above the Earth's equatorial radius
        when ``mu`` is the Earth's.
    eccentricity : float
        ``e`` in [0, 1).
    inclination : float
        ``i``, rad, in [0, pi].
    raan, arg_perigee, mean_anomaly : float
        Right ascension of the ascending node, argument of perigee, mean anomaly at t = 0; rad.
    mu : float
        Gravitational parameter, m^3/s^2 (default the Earth's).

    Examples
    --------
    A Molniya orbit: 12 h, perigee 500 km, apogee near 39,900 km:

    >>> import math
    >>> import numpy as np
    >>> from tumble.dynamics.environment.earth import R_EARTH
    >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
    >>> orbit = KeplerOrbit(26_600e3, 0.74, math.radians(63.4), arg_perigee=math.radians(270.0))
    >>> round(orbit.period / 3600, 2)   # h
    11.99
    >>> r = np.linalg.norm(orbit.position_eci([0.0, orbit.period / 2]), axis=1)
    >>> np.round((r - R_EARTH) / 1e3).tolist()   # km above the equatorial radius: perigee, apogee
    [538.0, 39906.0]
    """

    semi_major_axis: float
    eccentricity: float = 0.0
    inclination: float = 0.0
    raan: float = 0.0
    arg_perigee: float = 0.0
    mean_anomaly: float = 0.0
    mu: float = MU_EARTH

    def __post_init__(self) -> None:
        a = check_positive("semi_major_axis", self.semi_major_axis, "m")
        e = check_number("eccentricity", self.eccentricity, "")
        if not 0.0 <= e < 1.0:
            raise ValueError(f"eccentricity = {self.eccentricity!r} must lie in [0, 1) (an ellipse)")
        inc = check_number("inclination", self.inclination, "rad")
        if not 0.0 <= inc <= math.pi:
            raise ValueError(f"inclination = {self.inclination!r} must lie in [0, pi] (rad)")
        for name in ("raan", "arg_perigee", "mean_anomaly"):
            check_number(name, getattr(self, name), "rad")
        if is_earth(check_mu(self.mu)) and a * (1.0 - e) <= R_EARTH:
            raise ValueError(f"semi_major_axis = {a!r} m with eccentricity = {e!r} puts the perigee at "
                             f"{a * (1 - e):.6g} m, inside the Earth (R_E = {R_EARTH:g} m)")

    @property
    def mean_motion(self) -> float:
        """``n = sqrt(mu / a^3)``, rad/s.

        Examples
        --------
        >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
        >>> round(KeplerOrbit(7000e3).mean_motion, 9)
        0.001078008
        """
        a = float(self.semi_major_axis)
        return math.sqrt(self.mu / a) / a

    @property
    def period(self) -> float:
        """``2 pi / n``, s.

        Examples
        --------
        >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
        >>> round(KeplerOrbit(7000e3, 0.05).period)   # s: the same for every e
        5829
        """
        return 2.0 * math.pi / self.mean_motion

    @property
    def eci_from_world(self) -> Rotation:
        """The identity: the world frame of a run on this orbit is ECI (module docstring).

        Examples
        --------
        >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
        >>> KeplerOrbit(7000e3).eci_from_world.as_quat().tolist()
        [0.0, 0.0, 0.0, 1.0]
        """
        return Rotation.identity()

    def _perifocal(self, t: ArrayLike) -> tuple[FloatArray, FloatArray]:
        a, e = float(self.semi_major_axis), float(self.eccentricity)
        M = float(self.mean_anomaly) + self.mean_motion * np.asarray(t, float)
        E = _kepler_eccentric(np.mod(M + math.pi, 2.0 * math.pi) - math.pi, e)
        c, s, b = np.cos(E), np.sin(E), math.sqrt(1.0 - e * e)
        r = np.stack([a * (c - e), a * b * s, np.zeros_like(E)], axis=-1)
        speed = math.sqrt(self.mu * a) / (a * (1.0 - e * c))
        v = speed[..., None] * np.stack([-s, b * c, np.zeros_like(E)], axis=-1)
        return r, v

    def _to_eci(self, x: FloatArray) -> Vector3:
        frame = Rotation.from_euler("ZXZ", [self.raan, self.inclination, self.arg_perigee])
        return np.asarray(frame.apply(x.reshape(-1, 3)), float).reshape(x.shape)

    def position_eci(self, t: ArrayLike) -> Vector3:
        """Position in ECI at ``t`` (s from the epoch of the elements), m; shape ``t.shape + (3,)``.

        Examples
        --------
        With ``e = 0`` the ellipse is the circle of
        :class:`~tumble.dynamics.environment.orbit.CircularOrbit` (argument of latitude ``argp + M0``):

        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> import numpy as np
        >>> from tumble.dynamics.environment.earth import R_EARTH
        >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
        >>> k = KeplerOrbit(7000e3, 0.0, 1.0, raan=0.5, arg_perigee=0.2, mean_anomaly=0.3)
        >>> c = CircularOrbit(7000e3 - R_EARTH, 1.0, raan=0.5, arg_latitude=0.5)
        >>> np.allclose(k.position_eci([0.0, 1234.5]), c.position_eci([0.0, 1234.5]), rtol=0, atol=1e-6)
        True
        """
        return self._to_eci(self._perifocal(t)[0])

    def velocity_eci(self, t: ArrayLike) -> Vector3:
        """Velocity in ECI at ``t`` (s), m/s; shape ``t.shape + (3,)``.

        Examples
        --------
        Vis-viva, ``v^2 = mu (2 / r - 1 / a)``:

        >>> import math
        >>> import numpy as np
        >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
        >>> k = KeplerOrbit(9000e3, 0.2, 0.7)
        >>> r, v = np.linalg.norm(k.position_eci(900.0)), np.linalg.norm(k.velocity_eci(900.0))
        >>> math.isclose(v**2, k.mu * (2 / r - 1 / 9000e3), rel_tol=1e-13)
        True
        """
        return self._to_eci(self._perifocal(t)[1])

    def position_world(self, t: ArrayLike) -> Vector3:
        """Position in the world frame of a run, which is ECI here: :meth:`position_eci`, m.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
        >>> k = KeplerOrbit(7000e3, 0.01)
        >>> bool(np.array_equal(k.position_world([0.0, 60.0]), k.position_eci([0.0, 60.0])))
        True
        """
        return self.position_eci(t)

    def velocity_world(self, t: ArrayLike) -> Vector3:
        """Velocity in the world frame of a run, which is ECI here: :meth:`velocity_eci`, m/s.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
        >>> k = KeplerOrbit(7000e3, 0.01)
        >>> bool(np.array_equal(k.velocity_world(60.0), k.velocity_eci(60.0)))
        True
        """
        return self.velocity_eci(t)

    def acceleration_world(self, t: ArrayLike) -> Vector3:
        """Acceleration in the world frame (ECI): ``-mu r / |r|^3``, the two-body problem's (Vallado
        sec. 1.3), m/s^2; shape ``t.shape + (3,)``.

        Examples
        --------
        >>> import math
        >>> import numpy as np
        >>> from tumble.dynamics.environment.ephemeris import KeplerOrbit
        >>> k = KeplerOrbit(7000e3, 0.01)
        >>> r, a = k.position_world(60.0), k.acceleration_world(60.0)
        >>> math.isclose(float(np.linalg.norm(a)), k.mu / float(np.linalg.norm(r))**2, rel_tol=1e-14)
        True
        """
        r = self.position_world(t)
        return np.asarray(-self.mu * r / np.linalg.norm(r, axis=-1, keepdims=True) ** 3, dtype=np.float64)



def _check_tle_line(name: str, value: object, number: int) -> None:
    """A TLE's line ``number`` (1 or 2) as NORAD's format fixes it: 69 characters in fixed columns,
    starting with its number, the last its checksum (the sum of the digits of the first 68, each
    ``-`` counting 1, modulo 10; CelesTrak, "FAQs: Two-Line Element Set Format"). sgp4 checks
    neither: a TLE edited by hand (an inclination's digit, a space added) flew with exit 0, or
    failed with scipy's "`y` must contain only finite values"."""
    which = "first" if number == 1 else "second"
    if not isinstance(value, str) or len(value.strip()) < 60:
        raise ValueError(f"{name} = {value!r} must be the {which} line of a TLE (a string of 69 characters)")
    line = value.strip()
    if len(line) != 69 or line[0] != str(number) or not line[68].isdigit():
        raise ValueError(f"{name} = {value!r} has {len(line)} characters; the {which} line of a TLE has 69 in fixed "
                         f"columns, starting with {number} and ending with its checksum digit (a space added or lost?)")
    checksum = sum(int(c) if c.isdigit() else c == "-" for c in line[:68]) % 10
    if checksum != int(line[68]):
        raise ValueError(f"{name}: checksum {line[68]}, its digits give {checksum}: the line was changed after it was "
                         "published (give it exactly as published)")


@dataclass(frozen=True, eq=False)
class TLEOrbit:
    """An Earth orbit from a two-line element set, propagated by SGP4 (module docstring).

    Needs the ``sgp4`` package: ``pip install tumble[orbit]``. Time ``t`` counts from the TLE's
    epoch (:attr:`epoch`), s.

    Parameters
    ----------
    line1, line2 : str
        The two lines of the element set, as published (e.g. by CelesTrak).

    Examples
    --------
    The ISS on 2008-09-20 (Vallado et al. 2006's test set format):

    >>> import numpy as np
    >>> from tumble.dynamics.environment.earth import R_EARTH
    >>> from tumble.dynamics.environment.ephemeris import TLEOrbit
    >>> iss = TLEOrbit("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
    ...                "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537")
    >>> iss.epoch.isoformat(timespec="seconds"), round(iss.period / 60, 2)   # UTC, min
    ('2008-09-20T12:25:40+00:00', 91.6)
    >>> round(float(np.linalg.norm(iss.position_eci(0.0)) - R_EARTH) / 1e3)   # km above the equator's radius
    342
    """

    line1: str
    line2: str
    _satrec: Any = field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        Satrec = optional_import("sgp4.api", "orbit", "a TLE orbit (TLEOrbit)").Satrec
        for number, name in enumerate(("line1", "line2"), start=1):
            _check_tle_line(name, getattr(self, name), number)
            object.__setattr__(self, name, getattr(self, name).strip())  # sgp4 reads fixed columns: a leading space
            # shifted them, and the positions came out NaN with no error
        if self.line1[2:7] != self.line2[2:7]:
            raise ValueError(f"line1's satellite number {self.line1[2:7].strip()!r} is not line2's "
                             f"{self.line2[2:7].strip()!r}: the two lines of one TLE name one satellite")
        try:
            sat = Satrec.twoline2rv(self.line1, self.line2)
        except (ValueError, IndexError) as exc:
            raise ValueError(f"the TLE does not parse ({exc}); give its two lines exactly as published") from None
        if sat.error != 0:
            raise ValueError(f"the TLE's elements are out of SGP4's range (sgp4 error {sat.error})")
        object.__setattr__(self, "_satrec", sat)

    @property
    def epoch(self) -> _dt.datetime:
        """The TLE's epoch, UTC.

        Examples
        --------
        >>> from tumble.dynamics.environment.ephemeris import TLEOrbit
        >>> TLEOrbit("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
        ...          "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537").epoch.year
        2008
        """
        days = (self._satrec.jdsatepoch - 2451545.0) + self._satrec.jdsatepochF
        return J2000 + _dt.timedelta(days=float(days))

    @property
    def mean_motion(self) -> float:
        """SGP4's mean motion (Kozai), rad/s.

        Examples
        --------
        >>> import math
        >>> from tumble.dynamics.environment.ephemeris import TLEOrbit
        >>> iss = TLEOrbit("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
        ...                "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537")
        >>> round(iss.mean_motion * 86400 / (2 * math.pi), 6)   # revolutions a day, as in line 2
        15.721254
        """
        return float(self._satrec.no_kozai) / 60.0

    @property
    def period(self) -> float:
        """``2 pi / n``, s.

        Examples
        --------
        >>> from tumble.dynamics.environment.ephemeris import TLEOrbit
        >>> iss = TLEOrbit("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
        ...                "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537")
        >>> round(iss.period)
        5496
        """
        return 2.0 * math.pi / self.mean_motion

    @property
    def inclination(self) -> float:
        """Mean inclination at the epoch, rad.

        Examples
        --------
        >>> import math
        >>> from tumble.dynamics.environment.ephemeris import TLEOrbit
        >>> iss = TLEOrbit("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
        ...                "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537")
        >>> round(math.degrees(iss.inclination), 4)
        51.6416
        """
        return float(self._satrec.inclo)

    @property
    def eci_from_world(self) -> Rotation:
        """The identity: the world frame of a run on this orbit is TEME (module docstring).

        Examples
        --------
        >>> from tumble.dynamics.environment.ephemeris import TLEOrbit
        >>> iss = TLEOrbit("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
        ...                "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537")
        >>> float(iss.eci_from_world.magnitude())
        0.0
        """
        return Rotation.identity()

    def _state(self, t: ArrayLike) -> tuple[FloatArray, FloatArray]:
        tt = np.asarray(t, float)
        flat = tt.reshape(-1)
        if not np.all(np.isfinite(flat)):
            raise ValueError(f"t = {t!r} must be finite times, s from the TLE epoch")
        sat = self._satrec
        far = float(np.max(np.abs(flat))) if flat.size else 0.0
        if far > MAX_TLE_AGE:
            warnings.warn(TLEAgeWarning(
                f"the TLE is propagated {far / 86400:.3g} days from its epoch {self.epoch.date().isoformat()}: SGP4's "
                f"position drifts ~1-3 km a day from an element set's epoch (more than {MAX_TLE_AGE / 86400:g} days here); "
                "give a TLE of the run's time"), stacklevel=3)
        days = flat / 86400.0 + sat.jdsatepochF
        whole = np.floor(days)
        err, r, v = sat.sgp4_array(np.full_like(flat, sat.jdsatepoch) + whole, days - whole)
        if np.any(err != 0):
            bad = int(np.argmax(err != 0))
            raise RuntimeError(f"SGP4 failed at t = {flat[bad]!r} s (sgp4 error {int(err[bad])}: e.g. 6, the orbit decayed)")
        return r.reshape(tt.shape + (3,)) * 1e3, v.reshape(tt.shape + (3,)) * 1e3

    def position_eci(self, t: ArrayLike) -> Vector3:
        """Position in TEME at ``t`` (s from the epoch), m; shape ``t.shape + (3,)``.

        Examples
        --------
        >>> from tumble.dynamics.environment.ephemeris import TLEOrbit
        >>> iss = TLEOrbit("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
        ...                "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537")
        >>> iss.position_eci([0.0, 60.0, 120.0]).shape
        (3, 3)
        """
        return self._state(t)[0]

    def velocity_eci(self, t: ArrayLike) -> Vector3:
        """Velocity in TEME at ``t`` (s from the epoch), m/s; shape ``t.shape + (3,)``.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.environment.ephemeris import TLEOrbit
        >>> iss = TLEOrbit("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
        ...                "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537")
        >>> round(float(np.linalg.norm(iss.velocity_eci(0.0))))   # m/s
        7705
        """
        return self._state(t)[1]

    def position_world(self, t: ArrayLike) -> Vector3:
        """Position in the world frame of a run, which is TEME here: :meth:`position_eci`, m.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.environment.ephemeris import TLEOrbit
        >>> iss = TLEOrbit("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
        ...                "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537")
        >>> bool(np.array_equal(iss.position_world(30.0), iss.position_eci(30.0)))
        True
        """
        return self.position_eci(t)

    def velocity_world(self, t: ArrayLike) -> Vector3:
        """Velocity in the world frame of a run, which is TEME here: :meth:`velocity_eci`, m/s.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.environment.ephemeris import TLEOrbit
        >>> iss = TLEOrbit("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
        ...                "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537")
        >>> bool(np.array_equal(iss.velocity_world(30.0), iss.velocity_eci(30.0)))
        True
        """
        return self.velocity_eci(t)

