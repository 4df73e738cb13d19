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

from typing import Any

from ..dynamics import ConstantTorque, ResidualDipole, TorqueModel, TorqueSum
from ..dynamics.environment.earth import MU_EARTH
from .controlorbit import ORBIT_TABLE
from .gravitytables import gravity_gradient_from_table
from .keys import Key, Table

__all__ = ["CONTROL_TORQUE_TABLE", "TORQUE_KINDS", "TORQUE_TABLE", "torque_of"]

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
#: The ``[torque]`` table of control files: constant torques, or a residual magnetic dipole in the
#: ``[orbit]``'s field (the orbit's gravity gradient is ``[orbit] gravity_gradient = true`` there).
CONTROL_TORQUE_TABLE = Table("[torque]", (
    Key("kind", "string", "", '"constant"', choices=("constant", "residual_dipole"), example='"residual_dipole"',
        doc="a constant torque, or a magnetic dipole fixed in the body in the [orbit]'s field"),
    *(TORQUE_TABLE.key(name) for name in ("vector", "frame")),
    Key("dipole", "3 numbers", "A m^2", example="[0.0, 0.0, 0.05]",
        doc='kind = "residual_dipole": the dipole, in initial.frame (required): its torque m x B '
            "(tumble.dynamics.ResidualDipole)"),
), "Optional: a disturbance torque, constant (:class:`tumble.dynamics.ConstantTorque`) or a residual magnetic "
   "dipole in the ``[orbit]``'s field (:class:`tumble.dynamics.ResidualDipole`); several act together as a "
   "``[[torque]]`` table each. A body-frame vector or a dipole is in ``initial.frame``; the orbit's gravity "
   "gradient is ``[orbit] gravity_gradient = true``.")
#: Keys of each kind of ``[torque]`` table.
TORQUE_KINDS = {"constant": {"kind", "vector", "frame"},
                "gravity_gradient": {"kind", "orbit_period", "orbit_radius", "mu", "semi_major_axis", "eccentricity",
                                     "inclination", "raan", "arg_perigee", "mean_anomaly", "tle"},
                "residual_dipole": {"kind", "dipole"}}
#: Every key of every kind, the tables' own (a kind's own keys are checked against them).
_KEYS = {key.name: key for table in (CONTROL_TORQUE_TABLE, TORQUE_TABLE) for key in table.keys}
#: A ``[torque]`` table of any kind: the first check, before its kind's.
_ANY = Table("[torque]", tuple(_KEYS.values()))


def torque_of(value: object, kinds: tuple[str, ...] = ("constant", "gravity_gradient"), elsewhere: str = "", *,
              field: Any = None) -> TorqueModel | None:
    """The model of a file's ``torque``: one ``[torque]`` table, or a list of them (``[[torque]]``),
    their :class:`~tumble.dynamics.TorqueSum`; None for none. ``kinds``: the kinds the file takes
    (with ``"residual_dipole"``, a control file's: the keys of every kind are known to it, so that a
    table of a kind taken elsewhere is named as such); ``elsewhere``: where the file takes the
    others (said when one is given); ``field``: the run's magnetic field, a residual dipole's (None:
    there is none).

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
    first = _ANY if "residual_dipole" in kinds else TORQUE_TABLE  # the keys the file's page lists, and more
    if not isinstance(value, list):
        return _torque(first.check("torque", value), "torque", kinds, elsewhere, field)
    if not value:
        raise ValueError("torque = [] has no [[torque]] table; leave it out for a torque-free run")
    return TorqueSum(*(_torque(first.check(f"torque[{i}]", one), f"torque[{i}]", kinds, elsewhere, field)
                       for i, one in enumerate(value)))


def _torque(table: dict, where: str, kinds: tuple[str, ...], elsewhere: str = "", field: Any = None) -> TorqueModel:
    """The model of one ``[torque]`` table (``where`` names it in errors): ``kind = "constant"``
    (the default), ``"gravity_gradient"`` or ``"residual_dipole"``, one of ``kinds``."""
    kind = table.get("kind", "constant")
    if not isinstance(kind, str) or kind not in kinds:
        known = kind in TORQUE_KINDS
        raise ValueError(f"{where}: kind = {kind!r} is {'not taken here' if known else 'unknown'}; "
                         f"allowed: {', '.join(kinds)}{f' ({elsewhere})' if known and elsewhere else ''}")
    Table("[torque]", tuple(_KEYS[name] for name in sorted(TORQUE_KINDS[kind]))).check(where, table, kind=kind)
    if kind == "gravity_gradient":
        return gravity_gradient_from_table(table, where)
    if kind == "residual_dipole":
        if "dipole" not in table:
            raise ValueError(f"{where}: missing key 'dipole' (A m^2)")
        if field is None:
            raise ValueError(f'{where}: kind = "residual_dipole" needs an [orbit] (its magnetic field)')
        try:
            return ResidualDipole(table["dipole"], field)
        except ValueError as exc:
            raise ValueError(f"{where}: {exc}") from None
    if "vector" not in table:
        raise ValueError(f"{where}: missing key 'vector' (N m)")
    try:
        return ConstantTorque(table["vector"], table.get("frame", "body"))
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None
