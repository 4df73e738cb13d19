"""The ``[orbit]`` table of a control scenario: which orbit, which magnetic field.

One of three orbits::

    [orbit]
    altitude = 500e3               # m: a circular orbit (inclination, raan, arg_latitude, rad)
    # semi_major_axis = 7.2e6      # m: a Keplerian ellipse (eccentricity; inclination, raan, arg_perigee, mean_anomaly, rad)
    # tle = ["1 25544U ...", "2 25544 ..."]   # SGP4 from a two-line element set (pip install tumble[orbit])
    field = "dipole"               # or "igrf": IGRF-14 to igrf_degree (default 13; pip install tumble[orbit])
    # epoch = "2026-11-25T00:00:00"  # UTC at t = 0, for "igrf" (a TLE's own epoch by default)
    # gmst0 = 0.0                  # rad, for "dipole": the Earth's sidereal angle at t = 0
    gravity_gradient = true        # the gravity-gradient torque along this orbit

The world frame of the run is the orbit-plane frame for a circular orbit and the inertial frame
(ECI, or TEME for a TLE) for the others (:mod:`tumble.dynamics.environment.ephemeris`). The built-in
dipole (IGRF-13, 2020.0) needs no package and no date but only a circular orbit.
"""

from __future__ import annotations

import datetime
import math
from typing import Any

import numpy as np

from ..dynamics.environment.ephemeris import KeplerOrbit, TLEOrbit
from ..dynamics.environment.igrf import IGRFField
from ..dynamics.environment.magnetic import DipoleField
from ..dynamics.environment.orbit import CircularOrbit
from .keys import Key, Table

__all__ = ["ORBIT_KEYS", "ORBIT_TABLE", "Field", "Orbit", "geomagnetic_inclination", "orbit_from_table", "orbit_of",
           "orbit_summary"]

Orbit = CircularOrbit | KeplerOrbit | TLEOrbit
Field = DipoleField | IGRFField

_CIRCULAR = ("altitude", "inclination", "raan", "arg_latitude")
_KEPLER = ("semi_major_axis", "eccentricity", "inclination", "raan", "arg_perigee", "mean_anomaly")
#: The ``[orbit]`` table of a control scenario.
ORBIT_TABLE = Table("[orbit]", (
    Key("altitude", "number", "m", example="500e3", low=100e3, low_included=True,
        doc="a circular orbit: its height above the Earth's radius, in metres (100 km at least)"),
    Key("semi_major_axis", "number", "m", example="7.2e6", doc="a Keplerian ellipse (needs field = \"igrf\")"),
    Key("tle", "list of 2 strings", example='["1 25544U ...", "2 25544 ..."]',
        doc="SGP4 from a two-line element set (pip install tumble[orbit])"),
    Key("eccentricity", "number", "", "0.0", allowed=">= 0 and < 1", example="0.01", doc="with semi_major_axis"),
    Key("inclination", "number", "rad", "0.0", example="1.7", doc="to the Earth's equator"),
    Key("raan", "number", "rad", "0.0", example="0.5", doc="right ascension of the ascending node"),
    Key("arg_latitude", "number", "rad", "0.0", example="0.0", doc="with altitude: the argument of latitude at t = 0"),
    Key("arg_perigee", "number", "rad", "0.0", example="0.3", doc="with semi_major_axis"),
    Key("mean_anomaly", "number", "rad", "0.0", example="0.0", doc="with semi_major_axis: at t = 0"),
    Key("field", "string", "", '"dipole" on a circular orbit; none on an ellipse or a TLE', choices=("dipole", "igrf"),
        example='"igrf"',
        doc="the IGRF-13 2020.0 tilted dipole (circular orbits), or IGRF-14 (pip install tumble[orbit])"),
    Key("epoch", "string", "", "(a TLE's own epoch)", allowed="an ISO 8601 date and time, UTC",
        example='"2026-11-25T00:00:00"', doc='field = "igrf": the date at t = 0'),
    Key("igrf_degree", "whole number", "", "13", example="13", low=1, low_included=True, high=13,
        doc='field = "igrf": the highest degree of the expansion'),
    Key("gmst0", "number", "rad", "0.0", example="1.2", doc='field = "dipole": the Earth\'s sidereal angle at t = 0'),
    Key("earth_rotation", "true or false", "", "true", example="false", doc='field = "dipole": the Earth turns under the orbit'),
    Key("gravity_gradient", "true or false", "", "false", example="true", doc="the gravity-gradient torque along this orbit"),
), "One of ``altitude`` (circular), ``semi_major_axis`` (Keplerian) or ``tle``; the magnetic field; "
   "the gravity-gradient torque. Needed by magnetorquers and a nadir target.")
#: The keys of ``[orbit]``.
ORBIT_KEYS = set(ORBIT_TABLE.names())


def orbit_of(table: dict[str, Any]) -> Orbit:
    """The orbit of a table's keys: ``altitude`` (a circle), ``semi_major_axis`` (a Keplerian
    ellipse) or ``tle`` (two lines), each with its own elements (module docstring); other keys are
    not read. The one reading of an orbit's keys, for ``[orbit]`` and for a scenario's ``[torque]``.

    Examples
    --------
    >>> from tumble.io.controlorbit import orbit_of
    >>> orbit = orbit_of({"semi_major_axis": 12e6, "eccentricity": 0.4})
    >>> type(orbit).__name__, round(orbit.period)
    ('KeplerOrbit', 13082)
    >>> orbit_of({"semi_major_axis": 12e6, "arg_latitude": 0.3})
    Traceback (most recent call last):
    ...
    ValueError: arg_latitude does not go with semi_major_axis; allowed with semi_major_axis: semi_major_axis, eccentricity, inclination, raan, arg_perigee, mean_anomaly
    """
    given = [key for key in ("altitude", "semi_major_axis", "tle") if key in table]
    if len(given) != 1:
        raise ValueError("give exactly one of altitude (m, a circular orbit), semi_major_axis (m, a Keplerian "
                         "ellipse) and tle (two lines)" + (f", not {' and '.join(given)}" if given else ""))
    kind = given[0]
    allowed = {"altitude": _CIRCULAR, "semi_major_axis": _KEPLER, "tle": ("tle",)}[kind]
    stray = sorted(k for k in table if k in {*_CIRCULAR, *_KEPLER} and k not in allowed)
    if stray:
        raise ValueError(f"{stray[0]} does not go with {kind}; allowed with {kind}: {', '.join(allowed)}")
    if kind == "tle":
        lines = table["tle"]
        if not isinstance(lines, list) or len(lines) != 2 or not all(isinstance(line, str) for line in lines):
            raise ValueError(f"tle = {lines!r} must be a list of the two lines of a TLE (strings)")
        try:
            return TLEOrbit(lines[0], lines[1])
        except ValueError as exc:  # the constructor's line1/line2 are the file's tle[0]/tle[1]
            text = str(exc)
            for i, name in enumerate(("line1", "line2")):
                text = f"tle[{i}]" + text.removeprefix(name) if text.startswith(name) else text
            raise ValueError(text) from None
    elements = {k: v for k, v in table.items() if k in allowed}
    return CircularOrbit(**elements) if kind == "altitude" else KeplerOrbit(**elements)


def orbit_from_table(table: dict[str, Any]) -> tuple[Orbit, Field | None]:
    """The orbit and the field of an ``[orbit]`` table (module docstring); errors name the key. The field
    is the dipole by default, on a circular orbit; an ellipse or a TLE has none unless ``field`` names one
    (a wheels-only run there needs none, and was refused for the default it did not use).

    Examples
    --------
    >>> from tumble.io.controlorbit import orbit_from_table
    >>> orbit, field = orbit_from_table({"altitude": 500e3, "inclination": 1.7})
    >>> type(orbit).__name__, type(field).__name__
    ('CircularOrbit', 'DipoleField')
    >>> orbit_from_table({"semi_major_axis": 7.2e6, "eccentricity": 0.01})[1] is None   # an ellipse: no field unless asked
    True
    >>> orbit_from_table({"semi_major_axis": 7.2e6, "eccentricity": 0.01, "field": "dipole"})
    Traceback (most recent call last):
    ...
    ValueError: field = "dipole" needs a circular orbit (altitude); with semi_major_axis or tle use field = "igrf" and an epoch
    """
    orbit = orbit_of(table)
    kind = table.get("field", "dipole")
    if kind == "dipole":
        extra = sorted(k for k in ("epoch", "igrf_degree") if k in table)
        if extra:
            raise ValueError(f'{extra[0]} goes with field = "igrf", not "dipole"')
        if not isinstance(orbit, CircularOrbit):
            if "field" not in table:  # no field asked for: none, for a run that uses none (wheels alone on a TLE)
                return orbit, None
            raise ValueError('field = "dipole" needs a circular orbit (altitude); with semi_major_axis '
                             'or tle use field = "igrf" and an epoch')
        return orbit, DipoleField(orbit, gmst0=table.get("gmst0", 0.0),
                                  earth_rotation=table.get("earth_rotation", True))
    if kind == "igrf":
        dipole_keys = sorted(key for key in ("gmst0", "earth_rotation") if key in table)
        if dipole_keys:
            raise ValueError(f'{dipole_keys[0]} goes with field = "dipole"; for "igrf" the epoch sets the Earth\'s angle')
        try:
            return orbit, IGRFField(orbit, table.get("epoch"), max_degree=table.get("igrf_degree", 13))
        except ValueError as exc:  # the constructor's argument is the file's igrf_degree
            text = str(exc)
            raise ValueError("igrf_degree" + text.removeprefix("max_degree") if text.startswith("max_degree")
                             else text) from None
    raise ValueError(f"field = {kind!r} is unknown; allowed: dipole, igrf")


def geomagnetic_inclination(orbit: Orbit, field: Field) -> float:
    """The orbit's inclination to the field's dipole equator at t = 0, rad: the angle between
    the orbit normal ``r x v`` and the dipole axis, folded into [0, pi/2] (the ``xi_m`` of
    Avanzini & Giulietti's B-dot gain).

    Examples
    --------
    An equatorial orbit under an axial dipole lies in the magnetic equator:

    >>> from tumble.dynamics.environment.magnetic import DipoleField
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> from tumble.io.controlorbit import geomagnetic_inclination
    >>> orbit = CircularOrbit(altitude=500e3)
    >>> geomagnetic_inclination(orbit, DipoleField(orbit, coefficients=(-3e-5, 0.0, 0.0)))
    0.0
    """
    g10, g11, h11 = field.coefficients if isinstance(field, DipoleField) else field.gauss_degree1()
    g = np.array([g11, h11, g10]) / math.sqrt(g10 * g10 + g11 * g11 + h11 * h11)
    c, s = math.cos(field.gmst0), math.sin(field.gmst0)
    axis = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]) @ g  # ECI
    normal = orbit.eci_from_world.apply(np.cross(orbit.position_world(0.0), orbit.velocity_world(0.0)))
    return math.acos(min(1.0, abs(float(normal @ axis)) / float(np.linalg.norm(normal))))


def orbit_summary(orbit: Orbit, field: Field) -> dict[str, Any]:
    """The orbit and field as summary.json reports them (m, s, rad).

    Examples
    --------
    >>> from tumble.io.controlorbit import orbit_from_table, orbit_summary
    >>> orbit, field = orbit_from_table({"altitude": 500e3, "inclination": 1.7})
    >>> s = orbit_summary(orbit, field)
    >>> s["kind"], s["altitude"], round(s["period"]), s["field"]
    ('circular', 500000.0, 5677, 'dipole')
    """
    out: dict[str, Any] = {"period": orbit.period, "inclination": orbit.inclination}
    if isinstance(orbit, CircularOrbit):
        out.update(kind="circular", altitude=orbit.altitude)
    elif isinstance(orbit, KeplerOrbit):
        out.update(kind="kepler", semi_major_axis=orbit.semi_major_axis, eccentricity=orbit.eccentricity)
    else:
        out.update(kind="tle", tle=[orbit.line1, orbit.line2], epoch=orbit.epoch.isoformat())
    if isinstance(field, IGRFField):
        epoch = field.epoch
        out.update(field="igrf", igrf_degree=field.max_degree,
                   epoch=epoch.isoformat() if isinstance(epoch, datetime.datetime) else epoch)
    else:
        out.update(field="dipole", gmst0=field.gmst0)
    return out
