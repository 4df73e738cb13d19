"""The ``[torque]`` tables of scenario, sweep and control files: one ``[torque]``, or a
``[[torque]]`` for each of several torques acting together (their sum,
:class:`~tumble.dynamics.TorqueSum`).

Examples
--------
>>> from tumble.io.torquetables import torque_of
>>> torque_of({"vector": [0.0, 0.0, 0.01], "frame": "world"})
ConstantTorque(vector=(0.0, 0.0, 0.01), frame='world')
"""

from __future__ import annotations

from ..dynamics import ConstantTorque, TorqueModel, TorqueSum
from ..dynamics.environment.earth import MU_EARTH
from .controlorbit import ORBIT_TABLE
from .gravitytables import gravity_gradient_from_table
from .keys import Key, Table

__all__ = ["TORQUE_KINDS", "TORQUE_TABLE", "torque_of"]

#: The ``[torque]`` table of scenario, sweep and control files.
TORQUE_TABLE = Table("[torque]", (
    Key("kind", "string", "", '"constant"', choices=("constant", "gravity_gradient"), example='"gravity_gradient"',
        doc="a constant torque, or the gravity gradient along an orbit: a circle, an ellipse or a TLE's"),
    Key("vector", "3 numbers", "N m", example="[0.0, 0.0, 0.01]", doc='the torque (kind = "constant": required)'),
    Key("frame", "string", "", '"body"', choices=("body", "world"), example='"world"',
        doc="the frame the vector is fixed in"),
    Key("orbit_period", "number", "s", example="5400.0", low=0.0,
        doc='kind = "gravity_gradient": the orbit\'s period (or orbit_radius)'),
    Key("orbit_radius", "number", "m", example="6.78e6", low=0.0, doc="the orbit's radius (or orbit_period)"),
    Key("mu", "number", "m^3/s^2", f"{MU_EARTH:.10g} (the Earth's)", example="4.9048695e12", low=0.0,
        doc="the central body's gravitational parameter (a circle's)"),
    Key("semi_major_axis", "number", "m", example="12e6",
        doc='kind = "gravity_gradient": a Keplerian ellipse about the Earth instead of a circle (world frame: ECI)'),
    *(ORBIT_TABLE.key(name) for name in ("eccentricity", "inclination", "raan", "arg_perigee", "mean_anomaly")),
    Key("tle", "list of 2 strings", example='["1 25544U ...", "2 25544 ..."]',
        doc="kind = \"gravity_gradient\": along a two-line element set's orbit, SGP4 (pip install tumble[orbit]; world frame: TEME)"),
), "Optional: a torque acting through the run; several act together (their sum, "
   ":class:`tumble.dynamics.TorqueSum`) as a ``[[torque]]`` table each.")
#: Keys of each kind of ``[torque]`` table.
TORQUE_KINDS = {"constant": {"kind", "vector", "frame"},
                "gravity_gradient": {"kind", "orbit_period", "orbit_radius", "mu", "semi_major_axis", "eccentricity",
                                     "inclination", "raan", "arg_perigee", "mean_anomaly", "tle"}}


def torque_of(value: object, kinds: tuple[str, ...] = tuple(TORQUE_KINDS), elsewhere: str = "") -> TorqueModel | None:
    """The model of a file's ``torque``: one ``[torque]`` table, or a list of them (``[[torque]]``),
    their :class:`~tumble.dynamics.TorqueSum`; None for none. ``kinds``: the kinds the file takes;
    ``elsewhere``: where the file takes the others (said when one is given).

    Examples
    --------
    >>> from tumble.io.torquetables import torque_of
    >>> both = torque_of([{"vector": [0.0, 0.0, 0.01]}, {"kind": "gravity_gradient", "orbit_period": 5400.0}])
    >>> [type(term).__name__ for term in both.terms]
    ['ConstantTorque', 'GravityGradient']
    >>> torque_of([{"vector": [0.0, 0.0, 0.01]}, {"vector": [1.0, 0.0]}])
    Traceback (most recent call last):
    ...
    ValueError: torque[1]: torque vector = [1.0, 0.0] must be a list of 3 numbers (N m)
    """
    if value is None or value == {}:
        return None
    if not isinstance(value, list):
        return _torque(TORQUE_TABLE.check("torque", value), "torque", kinds, elsewhere)
    if not value:
        raise ValueError("torque = [] has no [[torque]] table; leave it out for a torque-free run")
    return TorqueSum(*(_torque(TORQUE_TABLE.check(f"torque[{i}]", table), f"torque[{i}]", kinds, elsewhere)
                       for i, table in enumerate(value)))


def _torque(table: dict, where: str, kinds: tuple[str, ...], elsewhere: str = "") -> TorqueModel:
    """The model of one ``[torque]`` table (``where`` names it in errors): ``kind = "constant"``
    (the default) or ``"gravity_gradient"``, one of ``kinds``."""
    kind = table.get("kind", "constant")
    if not isinstance(kind, str) or kind not in kinds:
        known = kind in TORQUE_KINDS
        raise ValueError(f"{where}: kind = {kind!r} is {'not taken here' if known else 'unknown'}; "
                         f"allowed: {', '.join(kinds)}{f' ({elsewhere})' if known and elsewhere else ''}")
    Table("[torque]", tuple(k for k in TORQUE_TABLE.keys if k.name in TORQUE_KINDS[kind])).check(where, table, kind=kind)
    if kind == "gravity_gradient":
        return gravity_gradient_from_table(table, where)
    if "vector" not in table:
        raise ValueError(f"{where}: missing key 'vector' (N m)")
    try:
        return ConstantTorque(table["vector"], table.get("frame", "body"))
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None
