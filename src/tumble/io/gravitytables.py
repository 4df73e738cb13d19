"""The gravity gradient in a scenario file: its ``[torque]`` table and ``[initial.orbit_frame]``.

``kind = "gravity_gradient"`` in ``[torque]`` gives the circular orbit (its period or radius, and
``mu``), :class:`~tumble.dynamics.models.gravity.GravityGradient`, or an ellipse's or a TLE's
(:class:`~tumble.dynamics.models.orbit_gravity.OrbitGravityGradient`); ``[initial.orbit_frame]``
starts the body at rest in the orbiting (LVLH) frame, turned by roll, pitch and yaw
(:func:`~tumble.dynamics.models.gravity.lvlh_state`). Each bad key or value is refused in one
line that names the table. :mod:`tumble.io.scenario` reads the rest of the file.
"""

from __future__ import annotations

import math
import warnings

from ..dynamics.environment.earth import MU_EARTH
from ..dynamics.models.gravity import GravityGradient, LVLHState, lvlh_state
from ..dynamics.models.orbit_gravity import OrbitGravityGradient
from ..mass import Body, MassProperties, UnitSlipWarning
from ..validation import short_repr, unknown_name
from .controlorbit import orbit_of
from .keys import Key, Table

__all__ = ["ORBIT_FRAME_TABLE", "gravity_gradient_from_table", "lvlh_state_from_table"]

#: The ``[initial.orbit_frame]`` table of a scenario file.
ORBIT_FRAME_TABLE = Table("[initial.orbit_frame]", (
    Key("roll", "number", "rad", "0.0", example="0.01", doc="offset from the orbiting frame"),
    Key("pitch", "number", "rad", "0.0", example="0.01", doc="offset from the orbiting frame"),
    Key("yaw", "number", "rad", "0.0", example="0.01", doc="offset from the orbiting frame"),
    Key("pitch_axis", "whole number or string", "", "3", allowed='1, 2, 3, "minor", "intermediate", "major"',
        example="3", doc="the principal axis along the orbit normal"),
    Key("yaw_axis", "whole number or string", "", "1", allowed='1, 2, 3, "minor", "intermediate", "major"',
        example="1", doc="the principal axis along the radius (the third is the roll axis)"),
), "A body at rest in the orbiting (LVLH) frame of the ``[torque]`` orbit, turned by pitch, roll, yaw.")


_CIRCLE_KEYS = ("orbit_period", "orbit_radius", "mu")
_TORQUE_KEYS = ("kind", *_CIRCLE_KEYS, "semi_major_axis", "eccentricity", "inclination", "raan", "arg_perigee",
                "mean_anomaly", "tle")
_LVLH_KEYS = ORBIT_FRAME_TABLE.names()


def _check_keys(where: str, table, allowed) -> None:
    if not isinstance(table, dict):
        raise ValueError(f"{where} must be a table, not {short_repr(table)}")
    for key in table:
        if key not in allowed:
            raise ValueError(unknown_name(where, key, allowed))


def gravity_gradient_from_table(table: dict, where: str = "torque") -> GravityGradient | OrbitGravityGradient:
    """The gravity gradient of a scenario file's ``[torque]`` table: a circle's
    (:class:`GravityGradient`), or an ellipse's or a TLE's
    (:class:`~tumble.dynamics.models.orbit_gravity.OrbitGravityGradient`, world frame ECI or TEME).

    Keys: ``kind = "gravity_gradient"`` (optional here); for a circle exactly one of
    ``orbit_period`` (s) and ``orbit_radius`` (m), and optionally ``mu`` (m^3/s^2, default the
    Earth's); for an ellipse about the Earth ``semi_major_axis`` (m) with ``eccentricity``,
    ``inclination``, ``raan``, ``arg_perigee`` and ``mean_anomaly`` (rad), or ``tle`` (two lines),
    read as a control file's ``[orbit]`` reads them (:func:`~tumble.io.controlorbit.orbit_of`). An
    unknown or missing key, or a bad value, raises ``ValueError`` with one line starting ``where``
    (``torque:``, or ``torque[1]:`` for a file's second ``[[torque]]``).

    Examples
    --------
    >>> import math
    >>> from tumble.io.gravitytables import gravity_gradient_from_table
    >>> gg = gravity_gradient_from_table({"kind": "gravity_gradient", "orbit_period": 5400.0})
    >>> math.isclose(gg.mean_motion, 2 * math.pi / 5400.0)  # n = 2 pi / T, rad/s
    True
    >>> gravity_gradient_from_table({"orbit_period": 5400.0, "altitude": 4e5})
    Traceback (most recent call last):
    ...
    ValueError: torque: unknown key 'altitude'; allowed: kind, orbit_period, orbit_radius, mu, semi_major_axis, eccentricity, inclination, raan, arg_perigee, mean_anomaly, tle
    >>> type(gravity_gradient_from_table({"semi_major_axis": 12e6, "eccentricity": 0.4})).__name__
    'OrbitGravityGradient'
    """
    _check_keys(where, table, _TORQUE_KEYS)
    if "kind" in table and table["kind"] != "gravity_gradient":
        raise ValueError(f"{where}: kind = {table['kind']!r} is not 'gravity_gradient'")
    other = [key for key in ("semi_major_axis", "tle") if key in table]
    if other:
        circle = [key for key in _CIRCLE_KEYS if key in table]
        if circle:
            raise ValueError(f"{where}: {circle[0]} goes with a circle, not with {other[0]}: give orbit_period or "
                             "orbit_radius (a circle), semi_major_axis (an ellipse about the Earth) or tle")
        try:
            return OrbitGravityGradient(orbit_of({key: value for key, value in table.items() if key != "kind"}))
        except ValueError as exc:
            raise ValueError(f"{where}: {exc}") from None
    if "orbit_period" not in table and "orbit_radius" not in table:
        raise ValueError(f"{where}: missing key 'orbit_period' (s) or 'orbit_radius' (m), a circle's (give exactly one); "
                         "or semi_major_axis (m) or tle for an ellipse or a TLE's orbit")
    try:
        return GravityGradient(orbit_period=table.get("orbit_period"), orbit_radius=table.get("orbit_radius"),
                               mu=table.get("mu", MU_EARTH))
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None


def lvlh_state_from_table(table: dict, gg: GravityGradient, body: Body | MassProperties) -> LVLHState:
    """:func:`lvlh_state` from a scenario file's ``[initial.orbit_frame]`` table.

    Keys, all optional: ``roll``, ``pitch``, ``yaw`` (rad, default 0), ``pitch_axis`` (default 3)
    and ``yaw_axis`` (default 1). An unknown key or a bad value raises ``ValueError`` with one
    line starting ``initial.orbit_frame:``.

    Examples
    --------
    >>> import tumble
    >>> from tumble.io.gravitytables import gravity_gradient_from_table, lvlh_state_from_table
    >>> gg = gravity_gradient_from_table({"orbit_period": 5400.0})
    >>> state = lvlh_state_from_table({"pitch": 0.1}, gg, tumble.t_handle())
    >>> import numpy as np
    >>> bool(np.allclose(state.omega0, [0.0, 0.0, 2 * np.pi / 5400.0]))  # once per orbit about pitch axis 3, rad/s
    True
    >>> round(float(state.attitude.magnitude()), 12)  # pitched by 0.1 rad from the orbit frame
    0.1
    """
    _check_keys("initial.orbit_frame", table, _LVLH_KEYS)
    for key in ("roll", "pitch", "yaw"):
        if key in table and (isinstance(table[key], bool) or not isinstance(table[key], (int, float))):
            raise ValueError(f"initial.orbit_frame: {key} = {table[key]!r} must be a number (rad)")
        if key in table and abs(table[key]) > math.pi:  # pitch = 5 meant as 5 deg ran 286 deg off without a word
            warnings.warn(f"initial.orbit_frame: {key} = {table[key]!r} rad is past half a turn: is it in degrees? "
                          f"Write radians ({table[key]!r} deg is {math.radians(table[key]):.4g} rad)", UnitSlipWarning,
                          stacklevel=2)
    try:
        return lvlh_state(gg, body, **table)
    except ValueError as exc:
        raise ValueError(f"initial.orbit_frame: {exc}") from None
