"""Magnetic fields for magnetorquers and magnetometers: the Earth's tilted dipole, a uniform field.

**The tilted dipole.** The degree-1 terms of the International Geomagnetic Reference Field,
IGRF-13 (Alken et al., *Earth, Planets and Space* 73:49, 2021), epoch 2020.0:
``g10 = -29404.8 nT``, ``g11 = -1450.9 nT``, ``h11 = 4652.5 nT``, reference radius
``a = 6371.2 km``. The degree-1 potential ``V = a (a/r)^2 (g10 cos th + (g11 cos ph + h11 sin ph) sin th)``
is that of a dipole at the Earth's centre with moment
``m = (4 pi / mu0) a^3 (g11, h11, g10)`` (A m^2, Earth-fixed frame, ECEF), and ``B = -grad V`` is

``B = (mu0 / 4 pi) (3 (m . r^) r^ - m) / r^3 = (a / r)^3 (3 (g . r^) r^ - g)``,  ``g = (g11, h11, g10)``

(Wertz, *Spacecraft Attitude Determination and Control*, Reidel 1978, appendix H; Griffiths,
*Introduction to Electrodynamics*, eq. 5.89). The moment points to the south (``g10 < 0``) and is
tilted by ``acos(|g10| / |g|) = 9.4 deg`` from the spin axis. The Earth-fixed frame turns about
ECI z at ``omega_E`` (:data:`~tumble.dynamics.environment.earth.OMEGA_EARTH`, IERS Conventions
2010): ECEF = ``R3(theta)`` ECI with
``theta = gmst0 + omega_E t`` (``gmst0`` the Greenwich sidereal angle at t = 0, rad).

Every field here is a callable ``field.world(t) -> B`` (T) in the world frame of the control run
(the orbit-plane frame of :class:`~tumble.dynamics.environment.orbit.CircularOrbit`). A field the
compiled closed loop evaluates itself declares its form, ``loop_form()``: a kind from ``FIELD_*``
and the parameters that kind's formula reads (:func:`field_form`); any other field is called in Python.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np

from ...typing import FloatArray, Vector3
from ...validation import check_bool, check_number, check_vector
from .earth import earth_angle
from .orbit import CircularOrbit

__all__ = ["FIELD_DIPOLE", "FIELD_NONE", "FIELD_TABLE", "FIELD_UNIFORM", "IGRF13_2020", "IGRF_RADIUS", "DipoleField",
           "MagneticField", "UniformField", "dipole_components", "field_form"]

#: Kinds of field the compiled closed loop evaluates (``loop_form()``): none, uniform, the tilted
#: dipole, a tabulated field (:class:`~tumble.dynamics.environment.igrf.IGRFField`'s cubic table).
FIELD_NONE, FIELD_UNIFORM, FIELD_DIPOLE, FIELD_TABLE = 0, 1, 2, 3
#: Floats of a field's compiled parameters.
FIELD_PARAMETERS = 16

#: IGRF-13 degree-1 Gauss coefficients at epoch 2020.0 (g10, g11, h11), T (Alken et al. 2021).
IGRF13_2020 = (-29404.8e-9, -1450.9e-9, 4652.5e-9)
#: IGRF reference radius, m.
IGRF_RADIUS = 6371.2e3


def dipole_components(g0: Any, g1: Any, g2: Any, x0: Any, x1: Any, x2: Any) -> tuple[Any, Any, Any]:
    """The dipole's field ``B = (a/r)^3 (3 (g·r^) r^ - g)`` at ``r = (x0, x1, x2)`` (m), T.

    ``g = (g0, g1, g2)`` the Gauss vector ``(g11, h11, g10)`` (T) in the frame of ``r`` (the
    Earth-fixed frame), ``a`` :data:`IGRF_RADIUS` (module docstring). The one writing of the
    dipole, component by component: floats (a compiled kernel) or arrays of one shape
    (:meth:`DipoleField.ecef` calls it on columns).

    Examples
    --------
    >>> from tumble.dynamics.environment.magnetic import IGRF_RADIUS, dipole_components
    >>> r = 2 * IGRF_RADIUS   # an axial dipole over its pole: 2 |g| (a/r)^3, along the axis
    >>> [round(float(b) * 8 / 3e-5, 12) + 0.0 for b in dipole_components(0.0, 0.0, -3e-5, 0.0, 0.0, r)]   # + 0.0: no -0.0
    [0.0, 0.0, -2.0]
    """
    rn = np.sqrt(x0 * x0 + x1 * x1 + x2 * x2)
    u0, u1, u2 = x0 / rn, x1 / rn, x2 / rn
    f = IGRF_RADIUS / rn
    f = f * f * f
    gu = 3.0 * (u0 * g0 + u1 * g1 + u2 * g2)
    return f * (gu * u0 - g0), f * (gu * u1 - g1), f * (gu * u2 - g2)


@runtime_checkable
class MagneticField(Protocol):
    """A magnetic field along the orbit: ``world(t)`` is B in the world frame, T.

    Examples
    --------
    Any object with a ``world(t)`` method is one (the protocol is checked at run time):

    >>> from tumble.dynamics.environment.magnetic import DipoleField, MagneticField, UniformField
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> isinstance(UniformField((0.0, 0.0, 3e-5)), MagneticField)
    True
    >>> isinstance(DipoleField(CircularOrbit(altitude=500e3)), MagneticField), isinstance(3e-5, MagneticField)
    (True, False)
    """

    def world(self, t: float) -> Vector3:
        """B at time ``t`` (s) in the world frame, T; shape (3,).

        Examples
        --------
        A field of one's own only needs this method; here one that grows linearly in time (T):

        >>> import numpy as np
        >>> from tumble.dynamics.environment.magnetic import MagneticField
        >>> class Ramp:
        ...     def world(self, t):
        ...         return np.array([0.0, 0.0, 3e-5 + 1e-6 * t])
        >>> isinstance(Ramp(), MagneticField), Ramp().world(0.0).tolist()
        (True, [0.0, 0.0, 3e-05])
        >>> np.allclose(Ramp().world(10.0) - Ramp().world(0.0), [0.0, 0.0, 1e-5])
        True
        """
        ...


@dataclass(frozen=True)
class UniformField:
    """A field fixed in the world frame, ``B`` (T): the closed-form checks' field.

    Examples
    --------
    >>> from tumble.dynamics.environment.magnetic import UniformField
    >>> UniformField((2e-5, 0.0, 0.0)).world(10.0).tolist()
    [2e-05, 0.0, 0.0]
    """

    vector: tuple[float, float, float]

    def __post_init__(self) -> None:
        object.__setattr__(self, "vector", check_vector("vector", self.vector, "T"))

    def world(self, t: float) -> Vector3:
        """The same B at every ``t``, T.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.environment.magnetic import UniformField
        >>> field = UniformField((0.0, -2e-5, 4e-5))
        >>> np.array_equal(field.world(0.0), field.world(5400.0)), field.world(1.0).tolist()
        (True, [0.0, -2e-05, 4e-05])
        """
        return np.array(self.vector, dtype=float)

    def loop_form(self) -> tuple[int, FloatArray] | None:
        """The compiled loop's form (:func:`field_form`): :data:`FIELD_UNIFORM` and ``B`` (T) in the
        first three of the parameters; None for a subclass with a ``world`` of its own.

        Examples
        --------
        >>> from tumble.dynamics.environment.magnetic import FIELD_UNIFORM, UniformField
        >>> kind, p = UniformField((0.0, 0.0, 3e-5)).loop_form()
        >>> kind == FIELD_UNIFORM, p[:3].tolist()
        (True, [0.0, 0.0, 3e-05])
        """
        if type(self).world is not UniformField.world:
            return None
        p = np.zeros(FIELD_PARAMETERS)
        p[:3] = self.vector
        return FIELD_UNIFORM, p


@dataclass(frozen=True)
class DipoleField:
    """The Earth's tilted dipole (IGRF-13, 2020.0) seen along a circular orbit.

    Parameters
    ----------
    orbit : CircularOrbit
        Where the spacecraft is; B is returned in its world (orbit-plane) frame.
    gmst0 : float
        Greenwich sidereal angle at t = 0, rad (where the Earth-fixed x axis points in ECI).
    coefficients : tuple of 3 floats
        ``(g10, g11, h11)``, T; default :data:`IGRF13_2020`.
    earth_rotation : bool
        Whether the dipole turns with the Earth (True) or stays fixed in ECI at ``gmst0``.

    Examples
    --------
    >>> from tumble.dynamics.environment.magnetic import DipoleField
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> orbit = CircularOrbit(altitude=500e3, inclination=0.0)
    >>> b = DipoleField(orbit, coefficients=(-29404.8e-9, 0.0, 0.0)).world(0.0)
    >>> round(float(b[2]) * 1e9, 1)   # nT: an axial dipole above the equator points north, (a/r)^3 |g10|
    23371.0
    """

    orbit: CircularOrbit
    gmst0: float = 0.0
    coefficients: tuple[float, float, float] = IGRF13_2020
    earth_rotation: bool = True
    _world_from_eci: FloatArray = field(default_factory=lambda: np.eye(3), init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if not isinstance(self.orbit, CircularOrbit):
            raise ValueError(f"orbit = {self.orbit!r} must be a CircularOrbit")  # noqa: TRY004 - one error type for bad input
        check_number("gmst0", self.gmst0, "rad")
        object.__setattr__(self, "earth_rotation", check_bool("earth_rotation", self.earth_rotation))
        object.__setattr__(self, "coefficients", check_vector("coefficients", self.coefficients, "T"))
        object.__setattr__(self, "_world_from_eci", self.orbit.eci_from_world.inv().as_matrix())

    @property
    def world_from_eci(self) -> FloatArray:
        """The rotation matrix from ECI to the orbit's world (orbit-plane) frame, shape (3, 3): the
        inverse of the orbit's ``eci_from_world``, computed once (the compiled loops read it).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.dynamics.environment.magnetic import DipoleField
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> orbit = CircularOrbit(altitude=500e3, inclination=1.0, raan=0.3)
        >>> m = DipoleField(orbit).world_from_eci
        >>> np.allclose(m @ orbit.position_eci(100.0), orbit.position_world(100.0))
        True
        """
        return self._world_from_eci

    @property
    def gauss_vector(self) -> Vector3:
        """``g = (g11, h11, g10)``, T: the dipole's direction and strength, Earth-fixed frame.

        Examples
        --------
        IGRF-13's degree-1 field is about 29,806 nT at the reference radius's equator, pointing south:

        >>> import numpy as np
        >>> from tumble.dynamics.environment.magnetic import DipoleField
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> g = DipoleField(CircularOrbit(altitude=500e3)).gauss_vector
        >>> np.round(g * 1e9, 1).tolist(), round(float(np.linalg.norm(g)) * 1e9)   # nT
        ([-1450.9, 4652.5, -29404.8], 29806)
        """
        g10, g11, h11 = self.coefficients
        return np.array([g11, h11, g10])

    def ecef(self, r_ecef: Vector3) -> Vector3:
        """``B = (a/r)^3 (3 (g . r^) r^ - g)`` at ``r_ecef`` (m, Earth-fixed), T; shape (..., 3).

        Examples
        --------
        An axial dipole ``g10`` at radius ``r``: ``B0 (a/r)^3`` north on the magnetic equator,
        twice that (pointing down) over the pole, with ``B0 = |g10|``:

        >>> import numpy as np
        >>> from tumble.dynamics.environment.magnetic import DipoleField, IGRF_RADIUS
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> field = DipoleField(CircularOrbit(altitude=500e3), coefficients=(-3e-5, 0.0, 0.0))
        >>> r = 2 * IGRF_RADIUS
        >>> b = field.ecef([[r, 0.0, 0.0], [0.0, 0.0, r]])
        >>> np.allclose(b, [[0.0, 0.0, 3e-5 / 8], [0.0, 0.0, -2 * 3e-5 / 8]])
        True
        """
        r = np.asarray(r_ecef, float)
        g10, g11, h11 = self.coefficients
        return np.stack(dipole_components(g11, h11, g10, r[..., 0], r[..., 1], r[..., 2]), axis=-1)

    def world(self, t: float) -> Vector3:
        """B at ``t`` (s) in the world (orbit-plane) frame, T.

        Examples
        --------
        An axial dipole along a polar orbit: ``B0 (a/r)^3`` over the equator (t = 0, the
        ascending node), ``2 B0 (a/r)^3`` over the north pole a quarter of a period later:

        >>> import math
        >>> import numpy as np
        >>> from tumble.dynamics.environment.magnetic import DipoleField, IGRF_RADIUS
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> orbit = CircularOrbit(altitude=500e3, inclination=math.pi / 2)
        >>> field = DipoleField(orbit, coefficients=(-29404.8e-9, 0.0, 0.0))
        >>> b0 = 29404.8e-9 * (IGRF_RADIUS / orbit.radius) ** 3
        >>> equator = np.linalg.norm(field.world(0.0))
        >>> pole = np.linalg.norm(field.world(orbit.period / 4))
        >>> math.isclose(equator, b0), math.isclose(pole, 2 * b0)
        (True, True)
        """
        theta = earth_angle(self.gmst0, float(t)) if self.earth_rotation else self.gmst0
        c, s = math.cos(theta), math.sin(theta)
        eci_from_ecef = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        world_from_ecef = self._world_from_eci @ eci_from_ecef
        r_ecef = world_from_ecef.T @ self.orbit.position_world(float(t))
        return np.asarray(world_from_ecef @ self.ecef(r_ecef), float)

    def loop_form(self) -> tuple[int, FloatArray] | None:
        """The compiled loop's form (:func:`field_form`): :data:`FIELD_DIPOLE` and the world-from-ECI
        matrix (9, row by row), the Gauss vector ``g`` (3, T), ``gmst0`` (rad), 1 if the Earth turns
        else 0, the orbit's radius (m) and mean motion (rad/s); None for a subclass with a ``world``
        of its own.

        Examples
        --------
        >>> from tumble.dynamics.environment.magnetic import FIELD_DIPOLE, DipoleField
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> kind, p = DipoleField(CircularOrbit(altitude=500e3), gmst0=0.5).loop_form()
        >>> kind == FIELD_DIPOLE, p[12:14].tolist()
        (True, [0.5, 1.0])
        """
        if type(self).world is not DipoleField.world:
            return None
        p = np.zeros(FIELD_PARAMETERS)
        p[:9] = self.world_from_eci.reshape(9)
        p[9:12] = self.gauss_vector
        p[12:16] = (self.gmst0, 1.0 if self.earth_rotation else 0.0, self.orbit.radius, self.orbit.mean_motion)
        return FIELD_DIPOLE, p

    def dipole_tilt(self) -> float:
        """Angle between the dipole and the Earth's spin axis, rad (9.4 deg for IGRF-13 2020).

        Examples
        --------
        >>> import math
        >>> from tumble.dynamics.environment.magnetic import DipoleField
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> orbit = CircularOrbit(altitude=500e3)
        >>> round(math.degrees(DipoleField(orbit).dipole_tilt()), 1)
        9.4
        >>> DipoleField(orbit, coefficients=(-3e-5, 0.0, 0.0)).dipole_tilt()   # an axial dipole
        0.0
        """
        g = self.gauss_vector
        return math.acos(abs(g[2]) / float(np.linalg.norm(g)))


def field_form(field: Any) -> tuple[int, FloatArray] | None:
    """``(kind, parameters)`` of a field for the compiled closed loop: the field's own
    ``loop_form()`` (:meth:`UniformField.loop_form`, :meth:`DipoleField.loop_form`,
    :meth:`~tumble.dynamics.environment.igrf.IGRFField.loop_form`), :data:`FIELD_NONE` for no field,
    None for a field that declares none (then the loop calls it in Python).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.environment.magnetic import FIELD_NONE, UniformField, field_form
    >>> field_form(None)[0] == FIELD_NONE, float(field_form(UniformField((0.0, 3e-5, 0.0)))[1][1])
    (True, 3e-05)
    >>> class Ramp:
    ...     def world(self, t):
    ...         return np.array([0.0, 0.0, 3e-5 + 1e-6 * t])
    >>> field_form(Ramp()) is None
    True
    """
    if field is None:
        return FIELD_NONE, np.zeros(FIELD_PARAMETERS)
    form = getattr(field, "loop_form", None)
    return form() if callable(form) else None
