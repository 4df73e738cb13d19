"""A circular Keplerian orbit for the control runs: elements in, position and velocity out.

The orbit has radius ``r`` (m) about a point mass ``mu`` (m^3/s^2), inclination ``i``, right
ascension of the ascending node ``raan`` and argument of latitude ``u0`` at t = 0 (rad), all
relative to an Earth-centred inertial frame (ECI: z the Earth's spin axis, x the vernal
equinox). The mean motion is ``n = sqrt(mu / r^3)`` and the argument of latitude
``u(t) = u0 + n t`` (Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed., sec.
2.6, the circular case of COE2RV):

``r_eci(t) = r R3(-raan) R1(-i) (cos u, sin u, 0)``, ``v_eci(t) = r n R3(-raan) R1(-i) (-sin u, cos u, 0)``.

**The world frame of a control run** is the *orbit-plane frame*: inertial, with x along the
radius at t = 0, z along the orbit normal (``r x v``), so that in it the radius is
``(cos n t, sin n t, 0)`` exactly as :class:`~tumble.dynamics.models.gravity.GravityGradient`
assumes (:func:`~tumble.dynamics.models.orbit_gravity.gravity_gradient_of` gives the orbit's
torque model); :attr:`CircularOrbit.eci_from_world` maps its vectors to ECI. The orbit is not
disturbed by the attitude (the restricted problem) and keeps its plane (no J2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike, Vector3
from ...validation import check_number, check_positive
from .earth import MU_EARTH, R_EARTH, check_mu, is_earth

__all__ = ["MIN_ALTITUDE", "CircularOrbit", "plane_direction"]


#: The lowest altitude of an orbit around the Earth, m: the Karman line. Below it the air brings a
#: satellite down within hours (the lowest held, SLATS's 167 km in 2019, took thrust against the drag).
MIN_ALTITUDE = 100e3
#: The highest altitude, m, that an altitude below :data:`MIN_ALTITUDE` read as km is taken to mean (a
#: little above the geostationary 35,786 km): ``altitude = 50e3`` is 50 km in metres, not 50,000 km.
_KM_HINT = 40e6


def plane_direction(n: float, t: float) -> tuple[float, float]:
    """The radius's direction in the orbit-plane frame, ``(cos n t, sin n t)``, at ``t`` (s) on a
    circular orbit of mean motion ``n`` (rad/s); ``(1, 0)`` without an orbit (``n = 0``).

    Over floats: the one writing, which the engine's kernels compile (:mod:`tumble.dynamics.engine.kernels`)
    and the numpy paths call.

    Examples
    --------
    >>> import math
    >>> from tumble.dynamics.environment.orbit import plane_direction
    >>> n = 2.0 * math.pi / 5400.0   # a 90-minute orbit
    >>> [round(x, 12) for x in plane_direction(n, 1350.0)], plane_direction(0.0, 10.0)   # a quarter on; no orbit
    ([0.0, 1.0], (1.0, 0.0))
    """
    if n == 0.0:
        return 1.0, 0.0
    return math.cos(n * t), math.sin(n * t)


@dataclass(frozen=True)
class CircularOrbit:
    """A circular orbit given by its elements (m, rad) about a central body ``mu`` (m^3/s^2).

    Parameters
    ----------
    altitude : float
        Height above the Earth's equatorial radius :data:`~tumble.dynamics.environment.earth.R_EARTH`, m (> 0);
        the radius is ``R_EARTH + altitude``.
    inclination : float
        Inclination ``i`` to the equator, rad, in [0, pi].
    raan : float
        Right ascension of the ascending node, rad.
    arg_latitude : float
        Argument of latitude ``u0`` at t = 0 (angle from the ascending node), rad.
    mu : float
        Gravitational parameter, m^3/s^2 (default the Earth's).

    Raises
    ------
    ValueError
        Naming the field, the value and what is allowed.

    Examples
    --------
    >>> import math
    >>> import numpy as np
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> orbit = CircularOrbit(altitude=500e3, inclination=math.radians(97.4))
    >>> round(orbit.period)   # s
    5677
    >>> np.allclose(np.linalg.norm(orbit.position_eci(100.0)), orbit.radius)
    True
    """

    altitude: float
    inclination: float = 0.0
    raan: float = 0.0
    arg_latitude: float = 0.0
    mu: float = MU_EARTH

    def __post_init__(self) -> None:
        altitude = check_positive("altitude", self.altitude, "m")
        mu = check_mu(self.mu)
        if altitude < MIN_ALTITUDE and is_earth(mu):  # 500 for 500 km: an "orbit" in the air
            raise ValueError(f"altitude = {self.altitude!r} m is below {MIN_ALTITUDE / 1e3:g} km, where no orbit lasts "
                             f"(the air brings it down within hours)" + (f": give metres, {altitude * 1e3:g} for "
                             f"{altitude:g} km" if MIN_ALTITUDE <= altitude * 1e3 <= _KM_HINT else ""))
        inc = check_number("inclination", self.inclination, "rad")
        if not 0.0 <= inc <= math.pi:
            raise ValueError(f"inclination = {self.inclination!r} must lie in [0, pi] (rad)")
        check_number("raan", self.raan, "rad")
        check_number("arg_latitude", self.arg_latitude, "rad")

    @property
    def radius(self) -> float:
        """Orbit radius ``R_EARTH + altitude``, m.

        Examples
        --------
        >>> from tumble.dynamics.environment.earth import R_EARTH
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> CircularOrbit(altitude=500e3).radius - R_EARTH   # m
        500000.0
        """
        return R_EARTH + float(self.altitude)

    @property
    def mean_motion(self) -> float:
        """Mean motion ``n = sqrt(mu / r^3)``, rad/s.

        Examples
        --------
        >>> import math
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> orbit = CircularOrbit(altitude=700e3)
        >>> math.isclose(orbit.mean_motion**2 * orbit.radius**3, orbit.mu)   # Kepler's third law
        True
        """
        return math.sqrt(self.mu / self.radius) / self.radius

    @property
    def period(self) -> float:
        """Orbital period ``2 pi / n``, s.

        Examples
        --------
        A geostationary orbit (radius 42,164.137 km) goes round once a sidereal day, 86,164.1 s:

        >>> from tumble.dynamics.environment.earth import R_EARTH
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> round(CircularOrbit(altitude=42164137.0 - R_EARTH).period)   # s
        86164
        """
        return 2.0 * math.pi / self.mean_motion

    @property
    def eci_from_world(self) -> Rotation:
        """The orbit-plane (world) frame to ECI: ``R3(-raan) R1(-i) R3(-u0)`` (module docstring).

        Examples
        --------
        A polar orbit with its node on ECI x: world x (the radius at t = 0) is ECI x, the orbit
        normal ``r x v`` (world z) is ECI -y:

        >>> import math
        >>> import numpy as np
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> frame = CircularOrbit(altitude=500e3, inclination=math.pi / 2).eci_from_world
        >>> np.round(frame.apply([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]), 12).tolist()
        [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0]]
        """
        return Rotation.from_euler("ZXZ", [self.raan, self.inclination, self.arg_latitude])

    def position_world(self, t: ArrayLike) -> Vector3:
        """Position in the world (orbit-plane) frame, ``r (cos n t, sin n t, 0)``, m; shape ``t.shape + (3,)``.

        Examples
        --------
        A quarter of a period after t = 0 the spacecraft is on world y:

        >>> import numpy as np
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> orbit = CircularOrbit(altitude=500e3)
        >>> r = orbit.position_world([0.0, orbit.period / 4])
        >>> r.shape, np.allclose(r, [[orbit.radius, 0, 0], [0, orbit.radius, 0]], atol=1e-6)
        ((2, 3), True)
        """
        nt = self.mean_motion * np.asarray(t, dtype=float)
        return self.radius * np.stack([np.cos(nt), np.sin(nt), np.zeros_like(nt)], axis=-1)

    def velocity_world(self, t: ArrayLike) -> Vector3:
        """Velocity in the world frame, ``r n (-sin n t, cos n t, 0)``, m/s.

        Examples
        --------
        The circular speed ``sqrt(mu / r)``, square to the radius:

        >>> import math
        >>> import numpy as np
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> orbit = CircularOrbit(altitude=700e3)
        >>> v, r = orbit.velocity_world(123.0), orbit.position_world(123.0)
        >>> math.isclose(np.linalg.norm(v), math.sqrt(orbit.mu / orbit.radius)), bool(abs(v @ r) < 1e-3)
        (True, True)
        >>> round(float(np.linalg.norm(v)), 1)   # m/s
        7504.3
        """
        nt = self.mean_motion * np.asarray(t, dtype=float)
        return self.radius * self.mean_motion * np.stack([-np.sin(nt), np.cos(nt), np.zeros_like(nt)], axis=-1)

    def position_eci(self, t: ArrayLike) -> Vector3:
        """Position in ECI, m; shape ``t.shape + (3,)``.

        Examples
        --------
        At the argument of latitude 90 deg the spacecraft is highest above the equator,
        ``z = r sin i``:

        >>> import math
        >>> import numpy as np
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> orbit = CircularOrbit(altitude=500e3, inclination=math.radians(51.6), raan=1.0)
        >>> r = orbit.position_eci(orbit.period / 4)
        >>> math.isclose(r[2], orbit.radius * math.sin(orbit.inclination)), math.isclose(np.linalg.norm(r), orbit.radius)
        (True, True)
        """
        return np.asarray(self.eci_from_world.apply(self.position_world(t).reshape(-1, 3)), float).reshape(
            np.shape(t) + (3,))

    def velocity_eci(self, t: ArrayLike) -> Vector3:
        """Velocity in ECI, m/s; shape ``t.shape + (3,)``.

        Examples
        --------
        A polar orbit crosses its ascending node going due north (ECI +z), at ``sqrt(mu / r)``:

        >>> import math
        >>> import numpy as np
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> orbit = CircularOrbit(altitude=500e3, inclination=math.pi / 2)
        >>> v = orbit.velocity_eci(0.0)
        >>> np.allclose(v, [0.0, 0.0, math.sqrt(orbit.mu / orbit.radius)])
        True
        >>> orbit.velocity_eci(np.zeros((4, 2))).shape
        (4, 2, 3)
        """
        return np.asarray(self.eci_from_world.apply(self.velocity_world(t).reshape(-1, 3)), float).reshape(
            np.shape(t) + (3,))
