"""The ``[control]`` table of a control scenario: its kinds, their keys, and the controller each builds.

Three kinds (:mod:`tumble.io.controlfile` for the rest of the file)::

    [control]
    kind = "bdot"               # B-dot with the magnetorquers (needs [orbit] and [actuators.magnetorquers])
    period = 1.0                # s
    # gain (default Avanzini & Giulietti's k = 2 n (1 + sin xi_m) I_min with form = "normalized"),
    # form, derivative, threshold (rad/s, for the detumble time)

    kind = "mrp_pd"             # MRP feedback with the wheels (needs [actuators.wheels])
    # K (N m), P (N m s), target = [x, y, z, w] (design frame to world) or "nadir" (along the
    # [orbit], circular, Keplerian or a TLE's; nadir_axis, default "minor", and normal_axis, default "major": principal axis labels
    # 1, 2, 3, minor, intermediate, major or design-frame vectors), gyroscopic,
    # Ki (1/s, integral term; default 0), integral_limit (N m)

    kind = "detumble_point"     # B-dot, then MRP feedback (tumble.dynamics.control.mission.DetumbleThenPoint)
    switch_rate = 0.0175        # rad/s: the gyroscope's |omega| must stay below it ...
    dwell = 60.0                # s: ... for this long, then the wheels point; never back
    # threshold (rad/s, for the detumble time of the summary)
    [control.detumble]          # the B-dot keys: gain, form, derivative (period: the mission's)
    [control.point]             # the MRP keys: K, P, target, ..., Ki; dumping_gain (1/s): the
                                # magnetorquers unload the wheels while they point (MomentumDumping)

The sub-tables may be written inline (``point = {K = 1.1e-3, P = 6e-3}``). Each value is checked
by the constructor it feeds; errors are one line naming the table and the key.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from ..dynamics.control.bdot import BDot, bdot_gain
from ..dynamics.control.controllers import MomentumDumping, MRPFeedback
from ..dynamics.control.mission import DetumbleThenPoint
from ..dynamics.control.sampled import check_period_in_orbit
from ..dynamics.models.actuators import Magnetorquers, ReactionWheels
from ..dynamics.models.sensors import Sensors
from ..dynamics.control.pointing import NadirTarget, axis_direction, check_square
from ..mass import Body
from ..validation import check_direction, check_positive, check_rotation, unknown_name
from .controlorbit import Field, Orbit, geomagnetic_inclination
from .keys import Key, Table

__all__ = ["CONTROL_KEYS", "CONTROL_KINDS", "CONTROL_TABLES", "DEFAULT_THRESHOLD", "ControlSpec", "build_controller", "parse_control"]

#: Rate under which a run counts as detumbled when the file does not say, rad/s (0.5 deg/s).
DEFAULT_THRESHOLD = math.radians(0.5)

_AXIS = 'a principal axis, 1, 2, 3, "minor", "intermediate", "major", or a design-frame vector'
_COMMON = (
    Key("kind", "string", required=True, choices=("bdot", "mrp_pd", "detumble_point"), example='"bdot"',
        doc="B-dot with the magnetorquers, MRP feedback with the wheels, or B-dot then MRP feedback"),
    Key("period", "number", "s", required=True, example="1.0", low=0.0, doc="the control period"),
    Key("threshold", "number", "rad/s", f"{DEFAULT_THRESHOLD:.6g} (0.5 deg/s)", example="0.01", low=0.0,
        doc="the rate under which the run counts as detumbled (the summary's detumble time)"),
)
_BDOT = (
    Key("gain", "number", "A m^2 s/T (classic) or N m s (normalized)",
        "Avanzini & Giulietti's 2 n (1 + sin xi_m) I_min, normalized", example="1e4", low=0.0, doc="the B-dot gain"),
    Key("form", "string", "", '"normalized" with the default gain; required with a gain given', choices=("classic", "normalized"),
        example='"normalized"', doc="m = -k dB/dt or m = -(k / |B|^2) dB/dt"),
    Key("derivative", "string", "", '"gyro"', choices=("gyro", "difference"), example='"difference"',
        doc="dB/dt from B x omega or from successive magnetometer readings"),
)
_MRP = (
    Key("K", "number", "N m", required=True, example="1.1e-3", low=0.0, doc="the attitude gain"),
    Key("P", "number", "N m s", required=True, example="6e-3", low=0.0, doc="the rate gain"),
    Key("target", "4 numbers or string", "", "[0, 0, 0, 1]", allowed='a quaternion [x, y, z, w] or "nadir"',
        example='"nadir"', doc="the target frame to world (design frame), or nadir along the [orbit]"),
    Key("gyroscopic", "true or false", "", "true", example="false", doc="add the feed-forward omega x (I omega + h)"),
    Key("Ki", "number", "1/s", "0.0", example="0.01", low=0.0, low_included=True, doc="the integral gain (0: the PD law)"),
    Key("integral_limit", "number", "N m", "(no limit)", example="1e-4", low=0.0,
        doc="the largest magnitude of each component of the integral term"),
    Key("nadir_axis", "string or 3 numbers", "", '"minor"', allowed=_AXIS, example='"minor"',
        doc='target = "nadir": the body axis pointed at the Earth'),
    Key("normal_axis", "string or 3 numbers", "", '"major"', allowed=_AXIS, example='"major"',
        doc='target = "nadir": the body axis along the orbit normal'),
)
_MISSION = (
    Key("switch_rate", "number", "rad/s", required=True, example="0.0175", low=0.0,
        doc="the gyroscope's |omega| must stay below it ..."),
    Key("dwell", "number", "s", required=True, example="60.0", low=0.0, low_included=True,
        doc="... for this long, then the wheels point; never back"),
    Key("detumble", "table", example="{form = \"normalized\"}", doc="[control.detumble]: the B-dot keys"),
    Key("point", "table", required=True, example="{K = 1.1e-3, P = 6e-3}", doc="[control.point]: the MRP keys"),
)
#: The tables of ``[control]``: its keys for each kind, then the sub-tables of "detumble_point".
CONTROL_TABLES = (
    Table('[control] kind = "bdot"', _COMMON + _BDOT,
          "B-dot (needs ``[orbit]`` and ``[actuators.magnetorquers]``)."),
    Table('[control] kind = "mrp_pd"', _COMMON + _MRP, "MRP feedback (needs ``[actuators.wheels]``)."),
    Table('[control] kind = "detumble_point"', _COMMON + _MISSION,
          "B-dot, then MRP feedback (:class:`tumble.dynamics.control.DetumbleThenPoint`)."),
    Table("[control.detumble]", _BDOT, "The B-dot keys of the detumble mode (its period is the mission's)."),
    Table("[control.point]", _MRP + (
        Key("dumping_gain", "number", "1/s", example="1e-3", low=0.0,
            doc="the magnetorquers unload the wheels while they point (MomentumDumping)"),),
          "The MRP keys of the pointing mode; may be written inline, ``point = {K = 1.1e-3, P = 6e-3}``."),
)
#: The keys of each kind of ``[control]``.
CONTROL_KINDS = {t.title.split('"')[1]: set(t.names()) for t in CONTROL_TABLES[:3]}
#: Every key ``[control]`` may hold (those of its kind are checked after).
CONTROL_KEYS = set().union(*CONTROL_KINDS.values())
_SUB_TABLES = {"detumble": CONTROL_TABLES[3], "point": CONTROL_TABLES[4]}


@dataclass(frozen=True, eq=False)
class ControlSpec:
    """A parsed ``[control]`` table: the kind, the controller's arguments (SI), the target
    (principal frame to world; None for B-dot) and the detumble threshold (rad/s).

    Examples
    --------
    >>> from tumble.io.controlspec import ControlSpec
    >>> ControlSpec("bdot", {"gain": 1e4, "period": 1.0}, None, 0.01).kind
    'bdot'
    """

    kind: str
    args: dict[str, Any]
    target: Rotation | NadirTarget | None
    threshold: float


def _sub(where: str, table: object, keys: Table) -> dict[str, Any]:
    return keys.check(where, table)


def _missing(keys: Table, table: dict[str, Any]) -> None:
    """Refuse a table without one of its required keys, naming it and its unit."""
    for key in keys.keys:
        if key.required and key.name not in table:
            raise ValueError(f"missing key {key.name!r}" + (f" ({key.unit})" if key.unit else f" ({key.doc})"))


def _bdot_args(args: dict[str, Any], body: Body, orbit: Orbit | None, field: Field | None,
               magnetorquers: Magnetorquers | None, kind: str) -> dict[str, Any]:
    """B-dot's arguments, the gain defaulting to Avanzini & Giulietti's (normalised form)."""
    if magnetorquers is None or orbit is None or field is None:
        raise ValueError(f'kind = "{kind}" needs [actuators.magnetorquers] and an [orbit] (the field)')
    args = dict(args)
    if "gain" in args and "form" not in args:  # the two forms' gains differ by |B|^2, ~1e-9 T^2 in low orbit
        raise ValueError(f"gain = {args['gain']!r} needs its form: form = \"normalized\" for a gain in N m s (Avanzini & "
                         f"Giulietti's, the default gain's form) or form = \"classic\" for one in A m^2 s/T; the two "
                         f"differ by |B|^2, some 1e-9 T^2 in low orbit, and the published gain taken as classic is "
                         f"~1e9 times too weak to detumble")
    if "gain" not in args:  # Avanzini & Giulietti 2012, xi_m the orbit's inclination to the dipole's equator
        args["gain"] = bdot_gain(orbit.mean_motion, geomagnetic_inclination(orbit, field),
                                 float(np.min(body.principal_moments)))
        args.setdefault("form", "normalized")
    BDot(**args)
    return args


def _mrp_args(args: dict[str, Any], body: Body, wheels: ReactionWheels | None, principal_to_design: Rotation,
              kind: str, orbit: Orbit | None) -> tuple[dict[str, Any], Rotation | NadirTarget]:
    """MRP feedback's arguments without the target, and the target (principal frame to world, or nadir)."""
    if wheels is None:
        raise ValueError(f'kind = "{kind}" needs [actuators.wheels]')
    axes = {k: args[k] for k in ("nadir_axis", "normal_axis") if k in args}
    args = {k: v for k, v in args.items() if k not in ("target", "nadir_axis", "normal_axis")}
    given = args.pop("_target", None)
    if isinstance(given, str):
        if given != "nadir":
            raise ValueError(f'target = {given!r} is unknown; allowed: "nadir" or a quaternion [x, y, z, w]')
        if orbit is None:
            raise ValueError('target = "nadir" needs an [orbit] (altitude, semi_major_axis or tle): there is none')
        to_principal = principal_to_design.inv()  # vectors are given in the design frame
        written = {"nadir_axis": "minor", "normal_axis": "major", **axes}  # as the file has them (or the defaults)
        axes = {k: v if np.ndim(v) == 0 else to_principal.apply(check_direction(k, v))
                for k, v in axes.items()}
        # squareness is checked here, on the vectors as written, so the message echoes them (design frame)
        turned = {k: axis_direction(k, v) for k, v in {"nadir_axis": "minor", "normal_axis": "major", **axes}.items()}
        check_square(turned["nadir_axis"], turned["normal_axis"], written["nadir_axis"], written["normal_axis"])
        return args, NadirTarget(orbit, **axes)
    if axes:
        raise ValueError(f'{min(axes)} goes with target = "nadir" only')
    target = Rotation.from_quat(check_rotation("target", given if given is not None else [0, 0, 0, 1]))
    return args, target * principal_to_design


def parse_control(control: dict[str, Any], *, body: Body, orbit: Orbit | None, field: Field | None,
                  magnetorquers: Magnetorquers | None, wheels: ReactionWheels | None, sensors: Sensors,
                  principal_to_design: Rotation) -> ControlSpec:
    """Check a ``[control]`` table against the file's actuators and build its :class:`ControlSpec`.

    Raises
    ------
    ValueError
        One line starting ``control:`` (or ``control.point:``, ``control.detumble:``) naming the
        key, the value and what is allowed.

    Examples
    --------
    >>> from tumble.mass import MassProperties
    >>> from tumble.dynamics import CircularOrbit, DipoleField
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.models.actuators import Magnetorquers, ReactionWheels
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> from tumble.io.controlspec import build_controller, parse_control
    >>> body = MassProperties.from_moments([0.0067, 0.0419, 0.0419])
    >>> wheels = ReactionWheels(np.eye(3), inertia=2e-5)
    >>> orbit = CircularOrbit(altitude=500e3, inclination=1.7)
    >>> spec = parse_control({"kind": "detumble_point", "period": 1.0, "switch_rate": 0.0175, "dwell": 60.0,
    ...                       "point": {"K": 1e-3, "P": 6e-3, "dumping_gain": 1e-3}}, body=body, orbit=orbit,
    ...                      field=DipoleField(orbit), magnetorquers=Magnetorquers(0.2), wheels=wheels,
    ...                      sensors=Sensors(), principal_to_design=Rotation.identity())
    >>> spec.kind, spec.args["detumble"]["form"], spec.args["point"], spec.args["dumping_gain"]
    ('detumble_point', 'normalized', {'K': 0.001, 'P': 0.006, 'period': 1.0}, 0.001)
    >>> type(build_controller(spec, body, wheels)).__name__
    'DetumbleThenPoint'
    >>> parse_control({"kind": "detumble_point", "period": 1.0, "switch_rate": 0.0175, "dwell": 60.0,
    ...                "point": {"K": 1e-3, "P": 6e-3, "Kd": 1.0}}, body=body, orbit=orbit, field=DipoleField(orbit),
    ...               magnetorquers=Magnetorquers(0.2), wheels=wheels, sensors=Sensors(), principal_to_design=Rotation.identity())
    Traceback (most recent call last):
    ...
    ValueError: control.point: unknown key 'Kd' (did you mean 'K'?); allowed: K, Ki, P, dumping_gain, gyroscopic, integral_limit, nadir_axis, normal_axis, target
    """
    kind = control.get("kind")
    if "kind" not in control:
        raise ValueError(f"control: missing key 'kind' (one of {', '.join(CONTROL_KINDS)})")
    if not isinstance(kind, str) or kind not in CONTROL_KINDS:
        raise ValueError(f"control: kind = {kind!r} is unknown; allowed: {', '.join(CONTROL_KINDS)}")
    bad = sorted(set(control) - CONTROL_KINDS[kind])
    if bad:
        mine = sorted(CONTROL_KINDS[kind])
        if not any(bad[0] in keys for keys in CONTROL_KINDS.values()):  # no kind's key: a typo, named with its nearest
            raise ValueError(unknown_name("control", bad[0], mine, allowed_label=f"allowed with kind = {kind!r}"))
        raise ValueError(f"control: key {bad[0]!r} does not go with kind = {kind!r}; allowed: {', '.join(mine)}")
    args: dict[str, Any] = {k: v for k, v in control.items() if k not in ("kind", "threshold", "target")}
    target = None
    where = "control"
    try:
        _missing(CONTROL_TABLES[list(CONTROL_KINDS).index(kind)], control)
        threshold = check_positive("threshold", control.get("threshold", DEFAULT_THRESHOLD), "rad/s")
        if kind != "bdot" and wheels is not None and sensors.attitude == "none":
            raise ValueError(f'kind = "{kind}" points with the wheels and needs an attitude sensor; '
                             'sensors.attitude = "none" gives none')
        if kind == "bdot":
            args = _bdot_args(args, body, orbit, field, magnetorquers, kind)
        elif kind == "mrp_pd":
            args, target = _mrp_args({**args, "_target": control.get("target")}, body, wheels, principal_to_design,
                                     kind, orbit)
            MRPFeedback(**args, moments=body.principal_moments, wheels=wheels, target=target)  # type: ignore[arg-type]
        else:
            if wheels is None:
                raise ValueError(f'kind = "{kind}" needs [actuators.wheels]')
            period = check_positive("period", control["period"], "s")  # the mission's own key, checked as such
            where = "control.detumble"
            detumble = _bdot_args({**_sub(where, control.get("detumble", {}), _SUB_TABLES["detumble"]),
                                   "period": period}, body, orbit, field, magnetorquers, kind)
            where = "control.point"
            point_t = _sub(where, control.get("point", {}), _SUB_TABLES["point"])
            _missing(_SUB_TABLES["point"], point_t)
            point, target = _mrp_args({**{k: v for k, v in point_t.items() if k != "dumping_gain"},
                                       "_target": point_t.get("target"), "period": period},
                                      body, wheels, principal_to_design, kind, orbit)
            dumping = point_t.get("dumping_gain")
            if dumping is not None:
                dumping = check_positive("dumping_gain", dumping, "1/s")
            args = {"period": period, "switch_rate": control["switch_rate"], "dwell": control["dwell"],
                    "detumble": detumble, "point": point, "dumping_gain": dumping}
            where = "control"
            build_controller(ControlSpec(kind, args, target, threshold), body, wheels)
    except (ValueError, TypeError) as exc:
        text = str(exc)
        raise ValueError(text if text.startswith(("control:", "control.")) else f"{where}: {text}") from None
    if orbit is not None:
        check_period_in_orbit(float(args["period"]), orbit.period)
    return ControlSpec(kind, args, target, threshold)


def build_controller(spec: ControlSpec, body: Body, wheels: ReactionWheels | None
                     ) -> BDot | MRPFeedback | DetumbleThenPoint:
    """A fresh controller of a parsed ``[control]`` table, for ``body`` and its ``wheels``.

    Examples
    --------
    >>> from tumble.mass import MassProperties
    >>> from tumble.io.controlspec import ControlSpec, build_controller
    >>> c = build_controller(ControlSpec("bdot", {"gain": 1e4, "period": 1.0}, None, 0.01),
    ...                      MassProperties.from_moments([1.0, 2.0, 3.0]), None)
    >>> type(c).__name__, c.gain
    ('BDot', 10000.0)
    """
    target = spec.target if spec.target is not None else Rotation.identity()
    if spec.kind == "bdot":
        return BDot(**spec.args)
    assert wheels is not None  # checked when the file was read
    if spec.kind == "mrp_pd":
        return MRPFeedback(**spec.args, moments=body.principal_moments, wheels=wheels, target=target)
    a = spec.args
    mrp = MRPFeedback(**a["point"], moments=body.principal_moments, wheels=wheels, target=target)
    point = mrp if a.get("dumping_gain") is None else MomentumDumping(mrp, gain=a["dumping_gain"])
    return DetumbleThenPoint(BDot(**a["detumble"]), point, switch_rate=a["switch_rate"], dwell=a["dwell"])
