"""Control scenario files (TOML): a body, its orbit, actuators, sensors and controller.

A scenario file with a ``[control]`` table is a closed-loop run (:func:`tumble.dynamics.control.controlled.simulate_controlled`)::

    body = "../bodies/cubesat_3u.toml"   # a preset, a body file (relative to this file) or a [body] table

    [initial]
    omega = [0.2, -0.2, 0.2]    # rad/s, in the design frame of the body file (frame = "principal" for the principal one)
    # attitude = [0, 0, 0, 1]   # design frame to world, quaternion [x, y, z, w]

    [simulation]
    t_end = 6000.0              # s
    # rtol = 1e-10, atol = 1e-12 (DOP853 between control steps)

    [orbit]                     # circular; the world frame is the orbit-plane frame (x: radius at t = 0, z: orbit normal)
    altitude = 500e3            # m
    inclination = 1.7           # rad; raan, arg_latitude (rad) too
    # gmst0 = 0.0               # rad: the Earth's sidereal angle at t = 0 (for the IGRF-13 2020 tilted dipole)
    gravity_gradient = true     # the gravity-gradient torque of this orbit
    # Keplerian (semi_major_axis, eccentricity, ...) or TLE orbits and the IGRF-14 field: tumble.io.controlorbit

    [actuators.magnetorquers]
    max_dipole = 0.2            # A m^2 per rod; rods along the design axes (axes = [[...], ...] to change)

    [actuators.wheels]          # reaction wheels
    axes = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]   # design frame (default: one wheel on each design axis)
    inertia = 1e-5              # kg m^2 (axial); max_torque (N m), max_speed (rad/s), viscous, coulomb, speed0

    # [torque]                  # a disturbance: vector = [0, 0, 1e-6] (N m), frame = "body" (initial.frame's) or "world";
                                # several act together as a [[torque]] table each

    [sensors]                   # gyro_noise, gyro_bias, magnetometer_noise, magnetometer_bias, attitude, attitude_noise, seed
    # [sensors.sun], [sensors.star_tracker] and [estimator] (the controller fed the MEKF's estimate):
    # tumble.io.controlestimator

    [control]
    kind = "bdot"               # or "mrp_pd", or "detumble_point" (B-dot, then MRP feedback)
    period = 1.0                # s
    # the keys of each kind: tumble.io.controlspec

Every value is checked by the constructor it feeds; errors are one line naming the table and key.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from ..dynamics import Trajectory
from ..dynamics.control.controlled import ControlledRun
from ..dynamics.control.bdot import BDot
from ..dynamics.control.controllers import Controller, MRPFeedback
from ..dynamics.control.estimated import Estimated
from ..dynamics.control.mission import DetumbleThenPoint
from ..dynamics import TorqueModel
from ..dynamics.methods.bounds import design_torque
from ..dynamics.models.actuators import Magnetorquers, ReactionWheels, check_wheels
from ..dynamics.models.orbit_gravity import gravity_gradient_of
from ..dynamics.models.sensors import Sensors
from ..dynamics.control.pointing import NadirTarget
from ..dynamics.engine.stepsize import check_atol, check_rtol
from ..mass import Body
from ..validation import check_bool, check_positive, check_rotation, check_vector, check_vectors, unknown_name
from .controlestimator import ESTIMATOR_TABLE, STAR_TRACKER_TABLE, SUN_TABLE, estimator_from_table, sensors_from_table
from .controlorbit import ORBIT_KEYS, ORBIT_TABLE, Field, Orbit, orbit_from_table
from .controlrun import control_summary, write_control_run
from .torquetables import CONTROL_TORQUE_TABLE, torque_of
from .keys import FileFormat, Key, Table
from .controlspec import (
    CONTROL_KEYS,
    CONTROL_KINDS,
    CONTROL_TABLES,
    DEFAULT_THRESHOLD,
    ControlSpec,
    _sub,
    build_controller,
    parse_control,
)

__all__ = ["CONTROL_FORMAT", "CONTROL_SECTIONS", "ControlScenario", "control_scenario_from_table", "control_summary", "write_control_run"]

_VECTORS = "list of 3-number lists"
_TABLES = (
    Table("top level", (
        Key("body", "string or table", required=True, allowed="a preset name, a body file or a [body] table",
            example='"../bodies/explorer1.toml"', doc="the body: a preset, a body file (relative to this file) or a [body] table"),
        *(Key(name, "table", required=name in ("initial", "simulation"), example=example,
              doc="[control]: what makes a scenario file a control scenario" if name == "control" else f"[{name}]")
          for name, example in (("initial", "{omega = [0.2, -0.2, 0.2]}"), ("simulation", "{t_end = 6000.0}"),
                                ("orbit", "{altitude = 500e3}"), ("actuators", "{wheels = {inertia = 1e-5}}"),
                                ("sensors", "{gyro_noise = 1e-4}"), ("control", '{kind = "bdot", period = 1.0}'),
                                ("estimator", '{kind = "mekf"}'))),
        Key("torque", "table", example="{vector = [0.0, 0.0, 1e-6]}",
            doc="[torque]: a constant disturbance, or a [[torque]] table for each of several"),
    ), "A scenario file with a ``[control]`` table is a closed-loop run."),
    Table("[initial]", (
        Key("omega", "3 numbers", "rad/s", required=True, example="[0.2, -0.2, 0.2]", doc="the initial angular velocity"),
        Key("frame", "string", "", '"design"', choices=("design", "principal"), example='"principal"',
            doc="the frame of omega: the body file's design frame or the principal axes"),
        Key("attitude", "4 numbers", "", "[0, 0, 0, 1]", allowed="a unit quaternion [x, y, z, w]",
            example="[0.0, 0.0, 0.0, 1.0]", doc="design frame to world at t = 0"),
    )),
    Table("[simulation]", (
        Key("t_end", "number", "s", required=True, example="6000.0", low=0.0, doc="duration of the run"),
        Key("rtol", "number", "", "1e-10", example="1e-9", low=2.22e-14, low_included=True, high=0.1,
            doc="relative tolerance of DOP853 between control steps"),
        Key("atol", "number", "", "1e-12", example="1e-11", low=0.0, high=0.1,
            doc="absolute tolerance: rad/s for omega and the wheels, 1 for the quaternion"),
    )),
    ORBIT_TABLE,
    CONTROL_TORQUE_TABLE,
    Table("[actuators]", (
        Key("magnetorquers", "table", example="{max_dipole = 0.2}", doc="[actuators.magnetorquers]"),
        Key("wheels", "table", example="{inertia = 1e-5}", doc="[actuators.wheels]: reaction wheels"),
    )),
    Table("[actuators.magnetorquers]", (
        Key("max_dipole", "number", "A m^2", "0.2", example="0.2", low=0.0, doc="the largest dipole of each rod"),
        Key("axes", _VECTORS, "", "the design axes", example="[[1, 0, 0], [0, 1, 0], [0, 0, 1]]",
            doc="the rods' axes, design frame"),
    ), "Needs an ``[orbit]`` (its magnetic field)."),
    Table("[actuators.wheels]", (
        Key("axes", _VECTORS, "", "the design axes", example="[[1, 0, 0], [0, 1, 0], [0, 0, 1]]",
            doc="one wheel along each axis, design frame"),
        Key("inertia", "number", "kg m^2", required=True, example="1e-5", low=0.0, doc="axial moment of each wheel"),
        Key("max_torque", "number", "N m", "inf", example="2e-3", low=0.0, doc="the largest motor torque"),
        Key("max_speed", "number", "rad/s", "inf", example="600.0", low=0.0, doc="the wheel speed limit"),
        Key("viscous", "number", "N m s", "0.0", example="1e-8", low=0.0, low_included=True, doc="viscous friction"),
        Key("coulomb", "number", "N m", "0.0", example="1e-6", low=0.0, low_included=True, doc="Coulomb friction"),
        Key("limit_cycle_speed", "number", "rad/s", "1e-4", example="1e-3", low=0.0,
            doc="the speed over which Coulomb friction is smoothed"),
        Key("speed0", "number, or one per wheel", "rad/s", "0.0", example="[0.0, 0.0, 100.0]",
            doc="the wheels' speeds at t = 0"),
    )),
    Table("[sensors]", (
        Key("gyro_noise", "number", "rad/s", "0.0", example="1e-4", low=0.0, low_included=True, high=0.2,
            doc="standard deviation of each gyroscope axis"),
        Key("gyro_bias", "3 numbers", "rad/s", "[0, 0, 0]", example="[1e-4, 0.0, 0.0]",
            doc="constant gyroscope bias, design frame"),
        Key("magnetometer_noise", "number", "T", "0.0", example="1e-7", low=0.0, low_included=True, high=1e-4,
            doc="standard deviation of each magnetometer axis"),
        Key("magnetometer_bias", "3 numbers", "T", "[0, 0, 0]", example="[0.0, 1e-7, 0.0]",
            doc="constant magnetometer bias, design frame"),
        Key("attitude", "string", "", '"ideal"', choices=("ideal", "star_tracker", "none"), example='"star_tracker"',
            doc="the attitude sensor: exact, noisy, or none fitted"),
        Key("attitude_noise", "number", "rad", "0.0", example="1e-4", low=0.0, low_included=True, high=math.pi,
            doc="star tracker noise about each axis"),
        Key("seed", "whole number", "", "0", example="7", doc="seed of the noise: a run is reproducible"),
        Key("sun", "table", example='{noise = 2e-3, epoch = "2026-06-01T00:00:00"}', doc="[sensors.sun]: a sun sensor"),
        Key("star_tracker", "table", example="{cross = 2e-5, roll = 2e-4}", doc="[sensors.star_tracker]"),
    ), "What the controller reads; all optional (default: exact readings)."),
    SUN_TABLE,
    STAR_TRACKER_TABLE,
    *CONTROL_TABLES,
    ESTIMATOR_TABLE,
)
#: The tables of a control scenario and their keys.
CONTROL_FORMAT = FileFormat("control scenario", _TABLES,
                            "A body, its orbit, actuators, sensors and controller: ``tumble simulate`` runs it in "
                            "closed loop (:func:`tumble.commands.run_scenario`).")
#: The tables of a control scenario and their keys.
CONTROL_SECTIONS = {
    "initial": set(CONTROL_FORMAT.table("[initial]").names()),
    "simulation": set(CONTROL_FORMAT.table("[simulation]").names()),
    "orbit": ORBIT_KEYS,
    "actuators": set(CONTROL_FORMAT.table("[actuators]").names()),
    "sensors": set(CONTROL_FORMAT.table("[sensors]").names()),
    "control": CONTROL_KEYS,
    "estimator": set(ESTIMATOR_TABLE.names()),
}
_MTQ = CONTROL_FORMAT.table("[actuators.magnetorquers]")
_WHEELS = CONTROL_FORMAT.table("[actuators.wheels]")


@dataclass(frozen=True, eq=False)
class ControlScenario:
    """A parsed control scenario; :func:`tumble.commands.run_scenario` runs it.

    Made by :func:`control_scenario_from_table` (or ``tumble.io.load_scenario`` from a file);
    vectors are in the body's principal frame.

    Examples
    --------
    A box (principal axis 1 along the design z axis) turned 60 deg about design y, three
    wheels; the spin given about design z is about principal axis 1:

    >>> from tumble.io.bodyfile import body_from_table
    >>> import math
    >>> import numpy as np
    >>> from tumble.io.controlfile import control_scenario_from_table
    >>> body = body_from_table({"name": "box", "parts": [{"kind": "box", "mass": 4.0, "size": [0.1, 0.2, 0.3]}]})
    >>> table = {"initial": {"omega": [0.0, 0.0, 0.01], "attitude": [0.0, 0.5, 0.0, math.sqrt(0.75)]},
    ...          "simulation": {"t_end": 10.0}, "control": {"kind": "mrp_pd", "period": 0.5, "K": 1e-3, "P": 6e-3},
    ...          "actuators": {"wheels": {"axes": np.eye(3).tolist(), "inertia": 2e-5, "max_torque": 2e-3}}}
    >>> scenario = control_scenario_from_table(table, body, name="point")
    >>> scenario.kind, scenario.omega, scenario.wheels.count, scenario.orbit is None
    ('mrp_pd', (0.01, 0.0, 0.0), 3, True)
    """

    body: Body
    omega: tuple[float, float, float]
    attitude0: Rotation
    t_end: float
    kind: str
    controller_args: dict[str, Any]
    orbit: Orbit | None = None
    field: Field | None = None
    gravity_gradient: bool = False
    magnetorquers: Magnetorquers | None = None
    wheels: ReactionWheels | None = None
    speed0: tuple[float, ...] | None = None
    sensors: Sensors = dataclasses.field(default_factory=Sensors)
    threshold: float = DEFAULT_THRESHOLD
    target: Rotation | NadirTarget | None = None
    rtol: float = 1e-10
    atol: float = 1e-12
    name: str = "scenario"
    sources: tuple[tuple[str, str], ...] = ()
    estimator: dict[str, Any] | None = None
    torque: TorqueModel | None = None  # a disturbance, principal frame

    def controller(self) -> BDot | MRPFeedback | DetumbleThenPoint | Estimated:
        """A fresh controller of this scenario.

        Examples
        --------
        >>> from tumble.io.bodyfile import body_from_table
        >>> import math
        >>> import numpy as np
        >>> from tumble.io.controlfile import control_scenario_from_table
        >>> body = body_from_table({"name": "box", "parts": [{"kind": "box", "mass": 4.0, "size": [0.1, 0.2, 0.3]}]})
        >>> table = {"initial": {"omega": [0.0, 0.0, 0.01], "attitude": [0.0, 0.5, 0.0, math.sqrt(0.75)]},
        ...          "simulation": {"t_end": 10.0}, "control": {"kind": "mrp_pd", "period": 0.5, "K": 1e-3, "P": 6e-3},
        ...          "actuators": {"wheels": {"axes": np.eye(3).tolist(), "inertia": 2e-5, "max_torque": 2e-3}}}
        >>> scenario = control_scenario_from_table(table, body, name="point")
        >>> c = scenario.controller()
        >>> type(c).__name__, c.K, c.P, c.period, c is scenario.controller()
        ('MRPFeedback', 0.001, 0.006, 0.5, False)

        B-dot without a gain gets Avanzini & Giulietti's ``2 n (1 + sin xi_m) I_min``, between
        ``2 n I_min`` and ``4 n I_min``:

        >>> bdot = control_scenario_from_table({"initial": {"omega": [0.1, 0.1, 0.1]}, "simulation": {"t_end": 10.0},
        ...     "orbit": {"altitude": 500e3, "inclination": 1.7}, "actuators": {"magnetorquers": {"max_dipole": 0.2}},
        ...     "control": {"kind": "bdot", "period": 1.0}}, body)
        >>> c = bdot.controller()
        >>> low = 2 * bdot.orbit.mean_motion * body.principal_moments[0]
        >>> c.form, bool(low < c.gain < 2 * low)
        ('normalized', True)
        """
        law = build_controller(ControlSpec(self.kind, self.controller_args, self.target, self.threshold), self.body,
                               self.wheels)
        return law if self.estimator is None else Estimated(law, self.sensors, self.field, **self.estimator)

    def arguments(self, controller: Controller | None = None) -> dict[str, Any]:
        """The keyword arguments of :func:`~tumble.dynamics.control.controlled.simulate_controlled`
        that run this scenario in closed loop, with ``controller`` (default a fresh :meth:`controller`).

        Running it belongs to the command layer, :func:`tumble.commands.run_scenario`; this file
        layer only reads and describes it.

        Examples
        --------
        >>> from tumble.io.bodyfile import body_from_table
        >>> import math
        >>> import numpy as np
        >>> from tumble.io.controlfile import control_scenario_from_table
        >>> body = body_from_table({"name": "box", "parts": [{"kind": "box", "mass": 4.0, "size": [0.1, 0.2, 0.3]}]})
        >>> table = {"initial": {"omega": [0.0, 0.0, 0.01], "attitude": [0.0, 0.5, 0.0, math.sqrt(0.75)]},
        ...          "simulation": {"t_end": 10.0}, "control": {"kind": "mrp_pd", "period": 0.5, "K": 1e-3, "P": 6e-3},
        ...          "actuators": {"wheels": {"axes": np.eye(3).tolist(), "inertia": 2e-5, "max_torque": 2e-3}}}
        >>> scenario = control_scenario_from_table(table, body, name="point")
        >>> given = scenario.arguments()
        >>> type(given["controller"]).__name__, given["t_end"], given["gravity_gradient"] is None
        ('MRPFeedback', 10.0, True)
        """
        return dict(
            moments=self.body.principal_moments, omega0=self.omega, t_end=self.t_end,
            controller=controller if controller is not None else self.controller(),
            attitude0=self.attitude0, field=self.field,
            gravity_gradient=gravity_gradient_of(self.orbit) if (self.gravity_gradient and self.orbit) else None,
            magnetorquers=self.magnetorquers, wheels=self.wheels, wheel_speed0=self.speed0, sensors=self.sensors,
            rtol=self.rtol, atol=self.atol, torque=self.torque)

    def trajectory(self, run: ControlledRun) -> Trajectory:
        """The run as a :class:`~tumble.dynamics.Trajectory` (wheels as rotors), for the figures.

        Examples
        --------
        >>> from tumble.io.bodyfile import body_from_table
        >>> import math
        >>> import numpy as np
        >>> from tumble.io.controlfile import control_scenario_from_table
        >>> body = body_from_table({"name": "box", "parts": [{"kind": "box", "mass": 4.0, "size": [0.1, 0.2, 0.3]}]})
        >>> table = {"initial": {"omega": [0.0, 0.0, 0.01], "attitude": [0.0, 0.5, 0.0, math.sqrt(0.75)]},
        ...          "simulation": {"t_end": 10.0}, "control": {"kind": "mrp_pd", "period": 0.5, "K": 1e-3, "P": 6e-3},
        ...          "actuators": {"wheels": {"axes": np.eye(3).tolist(), "inertia": 2e-5, "max_torque": 2e-3}}}
        >>> scenario = control_scenario_from_table(table, body, name="point")
        >>> import tumble
        >>> run = tumble.run_scenario(scenario)
        >>> traj = scenario.trajectory(run)
        >>> traj.method, np.array_equal(traj.t, run.t), np.array_equal(traj.omega, run.omega)
        ('dop853, mrp_pd every 0.5 s', True, True)
        >>> np.allclose(traj.internal_momentum, scenario.wheels.momentum(run.wheel_speed))   # h = sum J s g
        True
        """
        h = None if self.wheels is None else run.wheel_speed * np.asarray(self.wheels.inertia) @ self.wheels.axes
        return Trajectory(
            t=run.t, omega=run.omega, attitude=run.attitude, moments=run.moments,
            principal_axes=self.body.principal_axes, method=f"dop853, {self.kind} every "
            f"{self.controller_args['period']:g} s", torque_free=False, body_name=self.body.name, internal_momentum=h,
            rotor_spin=None if self.wheels is None else run.wheel_speed,
            rotor_axial_moments=None if self.wheels is None else np.asarray(self.wheels.inertia))

    def override(self, given: dict[str, Any]) -> ControlScenario:
        """This scenario with the command line's ``t_end``; other options do not apply.

        Examples
        --------
        >>> from tumble.io.bodyfile import body_from_table
        >>> import math
        >>> import numpy as np
        >>> from tumble.io.controlfile import control_scenario_from_table
        >>> body = body_from_table({"name": "box", "parts": [{"kind": "box", "mass": 4.0, "size": [0.1, 0.2, 0.3]}]})
        >>> table = {"initial": {"omega": [0.0, 0.0, 0.01], "attitude": [0.0, 0.5, 0.0, math.sqrt(0.75)]},
        ...          "simulation": {"t_end": 10.0}, "control": {"kind": "mrp_pd", "period": 0.5, "K": 1e-3, "P": 6e-3},
        ...          "actuators": {"wheels": {"axes": np.eye(3).tolist(), "inertia": 2e-5, "max_torque": 2e-3}}}
        >>> scenario = control_scenario_from_table(table, body, name="point")
        >>> scenario.override({"t_end": 2.5}).t_end, scenario.t_end
        (2.5, 10.0)
        >>> scenario.override({"t_end": 2.5, "rtol": 1e-8})
        Traceback (most recent call last):
        ...
        ValueError: point: --rtol does not apply to a control scenario; allowed: --t-end
        """
        other = sorted(set(given) - {"t_end"})
        if other:
            raise ValueError(f"{self.name}: --{other[0].replace('_', '-')} does not apply to a control scenario; "
                             "allowed: --t-end")
        return dataclasses.replace(self, t_end=check_positive("--t-end", given["t_end"], "s"))


def _table(data: dict[str, Any], section: str) -> dict[str, Any]:
    return Table(f"[{section}]", tuple(Key(k, "") for k in CONTROL_SECTIONS[section])).check(section, data.get(section, {}))


def _design_axes(value: object, body: Body, where: str) -> np.ndarray:
    """Axes given in the body's design frame, in principal components (``P^T d``); the rows'
    count and norms are checked by the actuator they feed."""
    try:
        a = check_vectors("axes", value, "design frame")  # type: ignore[arg-type]
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None
    return np.asarray(a @ np.asarray(body.principal_axes), float)


def control_scenario_from_table(data: dict[str, Any], body: Body, *, name: str = "scenario") -> ControlScenario:
    """Build a control scenario from parsed TOML (the body already built from its ``body`` key).

    Parameters
    ----------
    data : dict
        The file's tables (module docstring); its ``body`` key is not read here.
    body : Body
        The body, built from the file's ``body`` key.
    name : str
        The scenario's name (the file's stem), used in messages.

    Raises
    ------
    ValueError
        One line naming the table, the key, the value and what is allowed.

    Examples
    --------
    Vectors given in the body's design frame come out in its principal frame (here principal
    axis 1 is design z, axis 3 design x):

    >>> from tumble.io.bodyfile import body_from_table
    >>> import math
    >>> import numpy as np
    >>> from tumble.io.controlfile import control_scenario_from_table
    >>> body = body_from_table({"name": "box", "parts": [{"kind": "box", "mass": 4.0, "size": [0.1, 0.2, 0.3]}]})
    >>> table = {"initial": {"omega": [0.0, 0.0, 0.01], "attitude": [0.0, 0.5, 0.0, math.sqrt(0.75)]},
    ...          "simulation": {"t_end": 10.0}, "control": {"kind": "mrp_pd", "period": 0.5, "K": 1e-3, "P": 6e-3},
    ...          "actuators": {"wheels": {"axes": np.eye(3).tolist(), "inertia": 2e-5, "max_torque": 2e-3}}}
    >>> scenario = control_scenario_from_table(table, body, name="point")
    >>> scenario.omega, scenario.name
    ((0.01, 0.0, 0.0), 'point')
    >>> np.allclose(scenario.wheels.axes @ body.principal_axes.T, np.eye(3))   # the design axes, in principal components
    True
    >>> control_scenario_from_table({**table, "control": {"kind": "mrp_pd", "K": 1e-3, "P": 6e-3}}, body)
    Traceback (most recent call last):
    ...
    ValueError: control: missing key 'period' (s)
    """
    unknown = sorted(set(data) - {"body", "torque", *CONTROL_SECTIONS})
    if unknown:
        raise ValueError(unknown_name("", unknown[0], ["body", *CONTROL_SECTIONS, "torque"],
                                      allowed_label="allowed in a control scenario"))
    kind = data["control"].get("kind") if isinstance(data.get("control"), dict) else None  # a known kind's keys: parse_control
    t = {s: dict(data[s]) if s == "control" and isinstance(kind, str) and kind in CONTROL_KINDS else _table(data, s)
         for s in CONTROL_SECTIONS}
    P = np.asarray(body.principal_axes)
    initial, sim, orbit_t, act, control = t["initial"], t["simulation"], t["orbit"], t["actuators"], t["control"]
    try:
        if "omega" not in initial:
            raise ValueError("missing key 'omega' (rad/s)")
        frame = initial.get("frame", "design")
        if frame not in ("design", "principal"):
            raise ValueError(f"frame = {frame!r} is unknown; allowed: design, principal")
        omega = np.array(check_vector("omega", initial["omega"], "rad/s"))
        design_to_world = Rotation.from_quat(check_rotation("attitude", initial.get("attitude", [0, 0, 0, 1])))
    except ValueError as exc:
        raise ValueError(f"initial: {exc}") from None
    orbit: Orbit | None = None
    field: Field | None = None
    gravity_gradient = False
    if "orbit" in data:  # an empty [orbit] is refused by the parser, not read as no orbit
        try:
            gravity_gradient = check_bool("gravity_gradient", orbit_t.get("gravity_gradient", False))
            orbit, field = orbit_from_table(orbit_t)
        except ValueError as exc:
            raise ValueError(f"orbit: {exc}") from None
    torque = torque_of(data.get("torque"), ("constant", "residual_dipole"),
                       "the orbit's gravity gradient: [orbit] gravity_gradient = true", field=field)
    if frame == "design":
        omega = P.T @ omega
        if torque is not None and torque.frame == "body":  # a sum's frame is "body": it turns its body terms only
            torque = design_torque(torque, P)
    principal_to_design = Rotation.from_matrix(P)
    attitude0 = design_to_world * principal_to_design
    mtq = wheels = None
    speed0 = None
    where = "actuators"
    try:
        if "magnetorquers" in act:
            where = "actuators.magnetorquers"
            m = _sub("actuators.magnetorquers", act["magnetorquers"], _MTQ)
            mtq = Magnetorquers(m.get("max_dipole", 0.2),
                                _design_axes(m.get("axes", np.eye(3)), body, "actuators.magnetorquers"))
        if "wheels" in act:
            where = "actuators.wheels"
            w = _sub("actuators.wheels", act["wheels"], _WHEELS)
            if "inertia" not in w:
                raise ValueError("actuators.wheels: missing key 'inertia' (kg m^2)")
            wheels = ReactionWheels(_design_axes(w.get("axes", np.eye(3)), body, "actuators.wheels"),
                                    **{k: v for k, v in w.items() if k not in ("axes", "speed0")})
            s0 = w.get("speed0", [0.0] * wheels.count)
            s0 = check_vectors("actuators.wheels: speed0", [s0] if isinstance(s0, (int, float)) else s0, "rad/s",
                               size=None)
            if s0.shape != (wheels.count,):
                raise ValueError(f"actuators.wheels: speed0 = {w['speed0']!r} must be {wheels.count} numbers (rad/s), "
                                 "one per wheel")
            speed0 = tuple(float(x) for x in s0)
            check_wheels(body.principal_moments, wheels, inertia="inertia")
    except ValueError as exc:
        raise ValueError(exc if str(exc).startswith("actuators") else f"{where}: {exc}") from None
    if mtq is not None and field is None:
        raise ValueError('actuators.magnetorquers need a field: a circular [orbit] (its dipole) or field = "igrf"')
    sensors, heads = sensors_from_table(t["sensors"], orbit=orbit, field=field, principal_to_design=principal_to_design)
    estimator = (estimator_from_table(t["estimator"], heads=heads, field=field, attitude=t["sensors"].get("attitude"))
                 if "estimator" in data else None)
    spec = parse_control(control, body=body, orbit=orbit, field=field, magnetorquers=mtq, wheels=wheels,
                         # with an estimator the law has an attitude whatever sensors.attitude says
                         sensors=sensors if estimator is None else dataclasses.replace(sensors, attitude="ideal"),
                         principal_to_design=principal_to_design)
    if "t_end" not in sim:
        raise ValueError("simulation: missing key 't_end' (s)")
    try:
        t_end = check_positive("t_end", sim["t_end"], "s")
    except ValueError:
        raise ValueError(f"simulation: t_end = {sim['t_end']!r} must be a positive number (s)") from None
    return ControlScenario(
        body=body, omega=tuple(float(x) for x in omega), attitude0=attitude0, t_end=t_end, kind=spec.kind,  # type: ignore[arg-type]
        controller_args=spec.args, orbit=orbit, field=field, gravity_gradient=gravity_gradient,
        magnetorquers=mtq, wheels=wheels, speed0=speed0, sensors=sensors, threshold=spec.threshold, target=spec.target,
        rtol=check_rtol("simulation.rtol", sim.get("rtol", 1e-10)),
        atol=check_atol("simulation.atol", sim.get("atol", 1e-12), "absolute: rad/s for omega and the wheels, 1 for the quaternion"), name=name, estimator=estimator,
        torque=torque)


def is_control_file(data: dict[str, Any]) -> bool:
    """Whether parsed TOML is a control scenario (it has a ``[control]`` table)."""
    return "control" in data


def load_control_scenario(path: Path, data: dict[str, Any], body: Body) -> ControlScenario:
    """:func:`control_scenario_from_table` with errors prefixed by the file's name."""
    try:
        return control_scenario_from_table(data, body, name=Path(path).stem)
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None
