"""The Earth's constants, in one place: its gravitational parameter, equatorial radius, rotation rate
and standard gravity; and the Earth's turn, the angle of the Earth-fixed frame at a time.

Every orbit, field and torque model of tumble reads them from here (``tests/test_architecture.py``
checks that their values are written nowhere else in the package):

- :data:`MU_EARTH`, the gravitational parameter ``GM`` (IERS Conventions 2010, Technical Note
  36, table 1.1; the WGS 84 value);
- :data:`R_EARTH`, the equatorial radius (IERS Conventions 2010, table 1.1: 6378136.6 m,
  rounded to 0.1 km);
- :data:`OMEGA_EARTH`, the mean angular velocity of the Earth's rotation (IERS Conventions
  2010, sec. 1.2), the rate at which the Earth-fixed frame turns about ECI z;
- :data:`STANDARD_GRAVITY`, the conventional ``g_n`` (3rd CGPM, 1901; ISO 80000-3), the unit
  ``g`` of an accelerometer's readings.

:func:`earth_angle` is the one writing of the Earth's turn, ``theta = theta0 + OMEGA_EARTH t``:
the fields (:mod:`~tumble.dynamics.environment.magnetic`, :mod:`~tumble.dynamics.environment.igrf`)
call it, over floats or arrays.

Examples
--------
A circular orbit of one sidereal day's period (2 pi / OMEGA_EARTH) lies at the geostationary
radius, Kepler's third law ``r^3 = mu / n^2``:

>>> import math
>>> from tumble.dynamics.environment.earth import MU_EARTH, OMEGA_EARTH
>>> round(math.cbrt(MU_EARTH / OMEGA_EARTH**2) / 1e3)   # km
42164
"""

from __future__ import annotations

from typing import Any

from ...jit import formula

__all__ = ["MU_EARTH", "OMEGA_EARTH", "R_EARTH", "STANDARD_GRAVITY", "earth_angle"]

#: The Earth's gravitational parameter GM, m^3/s^2 (IERS Conventions 2010, table 1.1; WGS 84).
MU_EARTH = 3.986004418e14
#: The Earth's equatorial radius, m (IERS Conventions 2010: 6378136.6 m, rounded): with
#: ``mu = MU_EARTH`` an orbit must have a larger radius.
R_EARTH = 6.3781e6
#: The Earth's rotation rate, rad/s (IERS Conventions 2010, sec. 1.2).
OMEGA_EARTH = 7.292115e-5
#: Standard gravity ``g_n``, m/s^2, exact by definition (3rd CGPM, 1901; ISO 80000-3): the unit
#: ``g`` in which accelerometers report, not the local gravity.
STANDARD_GRAVITY = 9.80665


@formula
def earth_angle(theta0: Any, t: Any) -> Any:
    """The Earth's angle about ECI z at ``t`` (s), rad: ``theta0 + OMEGA_EARTH t``.

    The Earth-fixed frame (ECEF) turns at :data:`OMEGA_EARTH` about ECI z; ``theta0`` is its
    angle at t = 0 (the Greenwich sidereal angle of the epoch,
    :func:`~tumble.dynamics.environment.sidereal.greenwich_sidereal_angle`), and
    ``r_ecef = R3(theta) r_eci`` (Vallado, *Fundamentals of Astrodynamics and Applications*,
    4th ed., sec. 3.5). Floats (a compiled kernel) or arrays that broadcast: the one writing of
    the Earth's turn.

    Examples
    --------
    >>> import math
    >>> from tumble.dynamics.environment.earth import OMEGA_EARTH, earth_angle
    >>> math.isclose(earth_angle(0.5, 2 * math.pi / OMEGA_EARTH), 0.5 + 2 * math.pi)   # one sidereal day: a turn
    True
    """
    return theta0 + OMEGA_EARTH * t
