"""The attitude-knowledge tables of a control scenario: the sun sensor, the star tracker and the estimator.

::

    [sensors.sun]                  # a sun sensor (nothing in the Earth's shadow)
    kind = "coarse"                # cosine cells in opposed pairs along axes (design frame), or "fine"
    noise = 2e-3                   # coarse: of a full-Sun current; fine: rad on each angle
    period = 1.0                   # s between readings (0: every control step)
    epoch = "2026-06-01T00:00:00"  # UTC at t = 0: where the Sun is (default the [orbit]'s epoch)
    # fov = 1.047, frame = [x, y, z, w]: a fine head's field of view (rad) and sensor-to-design turn

    [sensors.star_tracker]         # cross, roll (rad), period (s), frame = [x, y, z, w] (sensor to design)

    [estimator]                    # the controller sees the MEKF's estimate instead of the truth
    kind = "mekf"
    # magnetometer_period (s), attitude_sigma (rad), bias_sigma (rad/s), bias_walk (rad/s^1.5)

The estimator is :class:`~tumble.dynamics.control.estimated.Estimated` around the file's
controller; its references are the run's field (``[orbit]``) and the Sun along the orbit
(:class:`~tumble.dynamics.environment.sun.Sunlight`). It reads the gyroscope, the magnetometer,
``[sensors.sun]`` and ``[sensors.star_tracker]``; the ``[sensors]`` ``attitude`` reading (ideal or
``"star_tracker"`` with ``attitude_noise``) is not used by it (write ``attitude = "none"``). Every value is checked by the constructor it
feeds; a bad one is refused in one line naming the table, the key, the value and what is allowed.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from ..dynamics.environment.sun import Sunlight
from ..dynamics.models.sensors import Sensors
from ..dynamics.models.vector_sensors import CoarseSunSensor, FineSunSensor, StarTracker
from ..validation import check_rotation, check_vectors
from .controlorbit import Field, Orbit
from .keys import Key, Table

__all__ = ["ESTIMATOR_TABLE", "STAR_TRACKER_TABLE", "SUN_TABLE", "estimator_from_table", "sensor_heads"]

_COARSE_ONLY, _FINE_ONLY = ("axes",), ("fov", "frame")

#: ``[sensors.sun]``.
SUN_TABLE = Table("[sensors.sun]", (
    Key("kind", "string", "", '"coarse"', choices=("coarse", "fine"), example='"fine"',
        doc="cosine cells in opposed pairs, or a two-axis head"),
    Key("noise", "number", "coarse: of a full-Sun current; fine: rad", "0.0", example="2e-3", low=0.0, low_included=True,
        doc="white noise of each cell's current (coarse) or each angle (fine)"),
    Key("period", "number", "s", "0.0", example="1.0", low=0.0, low_included=True,
        doc="time between readings (0: every control step; else a multiple of the control period)"),
    Key("epoch", "string", "", "(the [orbit]'s epoch)", allowed="an ISO 8601 date and time, UTC",
        example='"2026-06-01T00:00:00"', doc="UTC at t = 0, where the Sun is; needed unless the [orbit] has one"),
    Key("shadow", "string", "", '"conical"', choices=("conical", "cylindrical", "none"), example='"cylindrical"',
        doc="the Earth's shadow: conical with the penumbra, cylindrical, or none"),
    Key("axes", "list of 3-number lists", "", "the design axes", example="[[1, 0, 0], [0, 1, 0], [0, 0, 1]]",
        doc='kind = "coarse": the pairs\' axes, design frame (at least 3, spanning space)'),
    Key("fov", "number", "rad", "1.047", example="0.5", low=0.0, high=math.pi / 2 - 1e-6,
        doc='kind = "fine": half-angle of the field of view'),
    Key("frame", "4 numbers", "", "[0, 0, 0, 1]", allowed="a unit quaternion [x, y, z, w]", example="[0.0, 0.0, 0.0, 1.0]",
        doc='kind = "fine": sensor to design frame (the boresight is the sensor\'s z)'),
), "A sun sensor (:mod:`tumble.dynamics.models.vector_sensors`); needs an ``[orbit]``. Nothing in the Earth's shadow.")

#: ``[sensors.star_tracker]``.
STAR_TRACKER_TABLE = Table("[sensors.star_tracker]", (
    Key("cross", "number", "rad", "0.0", example="2e-5", low=0.0, low_included=True, high=0.1,
        doc="noise about each axis across the boresight"),
    Key("roll", "number", "rad", "0.0", example="2e-4", low=0.0, low_included=True, high=0.1,
        doc="noise about the boresight"),
    Key("period", "number", "s", "0.0", example="10.0", low=0.0, low_included=True,
        doc="time between readings (0: every control step)"),
    Key("frame", "4 numbers", "", "[0, 0, 0, 1]", allowed="a unit quaternion [x, y, z, w]", example="[0.0, 0.0, 0.0, 1.0]",
        doc="sensor to design frame (the boresight is the sensor's z)"),
), "A star tracker with its own frame, rate and noise.")

#: ``[estimator]``.
ESTIMATOR_TABLE = Table("[estimator]", (
    Key("kind", "string", "", required=True, choices=("mekf",), example='"mekf"',
        doc="the multiplicative extended Kalman filter (attitude and gyroscope bias)"),
    Key("magnetometer_period", "number", "s", "0.0", example="1.0", low=0.0, low_included=True,
        doc="time between the magnetometer's updates (0: every control step)"),
    Key("attitude_sigma", "number", "rad", "TRIAD's or the tracker's", example="0.05", low=0.0, high=math.pi,
        doc="the least standard deviation of the start's attitude about any axis (raises TRIAD's or the tracker's)"),
    Key("bias_sigma", "number", "rad/s", "1e-3", example="1e-3", low=0.0, doc="the first bias guess's (zero's)"),
    Key("bias_walk", "number", "rad/s^1.5", "1e-7", example="1e-6", low=0.0, low_included=True,
        doc="the gyroscope bias's random walk the filter assumes"),
), "The controller sees the filter's estimate instead of the truth (needs ``[sensors.star_tracker]``, or "
   "``[sensors.sun]`` and an ``[orbit]``).")


def _frame(where: str, value: object, principal_to_design: Rotation) -> Rotation:
    try:
        sensor_to_design = Rotation.from_quat(check_rotation("frame", value))
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None
    return principal_to_design.inv() * sensor_to_design


def sensor_heads(table: dict[str, Any], *, orbit: Orbit | None, field: Field | None,
                 principal_to_design: Rotation) -> dict[str, Any]:
    """``sun_sensor``, ``sunlight`` and ``star_tracker`` of :class:`~tumble.dynamics.models.sensors.Sensors`
    from the ``sun`` and ``star_tracker`` sub-tables of ``[sensors]`` (module docstring).

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.io.controlestimator import sensor_heads
    >>> from tumble.io.controlorbit import orbit_from_table
    >>> orbit, field = orbit_from_table({"altitude": 500e3})
    >>> heads = sensor_heads({"sun": {"noise": 2e-3, "epoch": "2026-06-01T00:00:00"}, "star_tracker": {"cross": 1e-5}},
    ...                      orbit=orbit, field=field, principal_to_design=Rotation.identity())
    >>> type(heads["sun_sensor"]).__name__, heads["star_tracker"].cross
    ('CoarseSunSensor', 1e-05)
    >>> sensor_heads({"sun": {"kind": "fine", "axes": [[1, 0, 0]]}}, orbit=orbit, field=field,
    ...              principal_to_design=Rotation.identity())
    Traceback (most recent call last):
    ...
    ValueError: sensors.sun: key 'axes' does not go with kind = 'fine'; allowed: epoch, fov, frame, kind, noise, period, shadow
    """
    out: dict[str, Any] = {}
    if "sun" in table:
        where = "sensors.sun"
        sun = dict(SUN_TABLE.check(where, table["sun"]))
        kind = sun.pop("kind", "coarse")
        if kind not in ("coarse", "fine"):
            raise ValueError(f"{where}: kind = {kind!r} is unknown; allowed: coarse, fine")
        wrong = sorted(k for k in sun if k in (_FINE_ONLY if kind == "coarse" else _COARSE_ONLY))
        if wrong:
            allowed = sorted(k for k in SUN_TABLE.names() if k not in (_FINE_ONLY if kind == "coarse" else _COARSE_ONLY))
            raise ValueError(f"{where}: key {wrong[0]!r} does not go with kind = {kind!r}; allowed: {', '.join(allowed)}")
        if orbit is None:
            raise ValueError(f"{where}: a sun sensor needs an [orbit] (where the Sun and the Earth's shadow are)")
        epoch = sun.pop("epoch", None) or getattr(field, "epoch", None) or getattr(orbit, "epoch", None)
        if epoch is None:
            raise ValueError(f"{where}: missing key 'epoch' (UTC at t = 0, e.g. \"2026-06-01T00:00:00\"): "
                             "the [orbit] has no epoch of its own")
        shadow = sun.pop("shadow", "conical")
        try:
            out["sunlight"] = Sunlight(orbit, epoch, shadow)
            if kind == "coarse":
                axes = check_vectors("axes", sun.pop("axes", np.eye(3).tolist()), "design frame")
                out["sun_sensor"] = CoarseSunSensor(axes=axes @ principal_to_design.as_matrix(), **sun)
            else:
                frame = _frame(where, sun.pop("frame", [0.0, 0.0, 0.0, 1.0]), principal_to_design)
                out["sun_sensor"] = FineSunSensor(frame=frame, **sun)
        except ValueError as exc:
            raise ValueError(exc if str(exc).startswith(where) else f"{where}: {exc}") from None
    if "star_tracker" in table:
        where = "sensors.star_tracker"
        st = dict(STAR_TRACKER_TABLE.check(where, table["star_tracker"]))
        frame = _frame(where, st.pop("frame", [0.0, 0.0, 0.0, 1.0]), principal_to_design)
        try:
            out["star_tracker"] = StarTracker(frame=frame, **st)
        except ValueError as exc:
            raise ValueError(f"{where}: {exc}") from None
    return out


def sensors_from_table(table: dict[str, Any], *, orbit: Orbit | None, field: Field | None,
                       principal_to_design: Rotation) -> tuple[Sensors, dict[str, Any]]:
    """The run's :class:`~tumble.dynamics.models.sensors.Sensors` of a ``[sensors]`` table and its
    heads (:func:`sensor_heads`). The biases, given like the file's other vectors in the body's
    design frame, are turned into the principal frame the run adds them in.

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.io.controlestimator import sensors_from_table
    >>> principal_to_design = Rotation.from_matrix([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    >>> sensors, heads = sensors_from_table({"gyro_bias": [5e-4, 0.0, 0.0]}, orbit=None, field=None,
    ...                                     principal_to_design=principal_to_design)
    >>> (sensors.gyro_bias, heads)   # principal axes design y, z, x (the columns): design x is the third
    ((0.0, 0.0, 0.0005), {})
    """
    heads = sensor_heads(table, orbit=orbit, field=field, principal_to_design=principal_to_design)
    try:
        sensors = Sensors(**{k: v for k, v in table.items() if k not in ("sun", "star_tracker")}, **heads)
    except (ValueError, TypeError) as exc:
        raise ValueError(f"sensors: {exc}") from None
    design_to_principal = principal_to_design.inv()
    return dataclasses.replace(sensors, **{k: tuple(design_to_principal.apply(getattr(sensors, k)).tolist())
                                           for k in ("gyro_bias", "magnetometer_bias")}), heads


def estimator_from_table(table: dict[str, Any], *, heads: dict[str, Any], field: Field | None,
                         attitude: object = None) -> dict[str, Any]:
    """The keyword arguments of :class:`~tumble.dynamics.control.estimated.Estimated` (besides the
    controller, the sensors and the field) of an ``[estimator]`` table, checked; ``attitude``, the
    ``[sensors]`` table's ``attitude`` as written (None where left out): the filter does not read
    it, so any other than ``"none"`` is refused (a walkthrough's ``attitude = "star_tracker"`` ran
    with no tracker at all, its readings counted 0).

    Examples
    --------
    >>> from tumble.io.controlestimator import estimator_from_table
    >>> estimator_from_table({"kind": "mekf", "bias_walk": 1e-6}, heads={"star_tracker": object()}, field=None)
    {'bias_walk': 1e-06}
    >>> estimator_from_table({"kind": "ukf"}, heads={}, field=None)
    Traceback (most recent call last):
    ...
    ValueError: estimator: kind = 'ukf' is unknown; allowed: mekf
    >>> estimator_from_table({"kind": "mekf"}, heads={"star_tracker": object()}, field=None, attitude="star_tracker")
    Traceback (most recent call last):
    ...
    ValueError: sensors: attitude = 'star_tracker' is not read with an [estimator]: the filter takes a star tracker from [sensors.star_tracker] (cross, roll, period); write attitude = "none"
    """
    if attitude is not None and attitude != "none":
        raise ValueError(f"sensors: attitude = {attitude!r} is not read with an [estimator]: the filter takes a star "
                         'tracker from [sensors.star_tracker] (cross, roll, period); write attitude = "none"')
    where = "estimator"
    args = dict(ESTIMATOR_TABLE.check(where, table))
    if "kind" not in args:
        raise ValueError(f"{where}: missing key 'kind' (\"mekf\")")
    kind = args.pop("kind")
    if kind != "mekf":
        raise ValueError(f"{where}: kind = {kind!r} is unknown; allowed: mekf")
    if "star_tracker" not in heads and ("sun_sensor" not in heads or field is None):
        raise ValueError(f"{where}: the filter needs [sensors.star_tracker], or [sensors.sun] and an [orbit] (the field) "
                         "to start from")
    from ..dynamics.control.estimated import Estimated
    from ..dynamics.models.sensors import Sensors

    class _Hold:
        period = 1.0

    try:
        Estimated(_Hold(), Sensors(), **args)  # type: ignore[arg-type]  # the checks of the constructor
    except (ValueError, TypeError) as exc:
        raise ValueError(f"{where}: {exc}") from None
    return args
