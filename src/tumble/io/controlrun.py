"""What ``tumble simulate`` keeps of a control run: ``summary.json``'s numbers and the trajectory files.

:func:`control_summary` gives the final rate, the detumble time (when ``|omega|`` drops below the
scenario's threshold and stays there), the pointing error against the target, the momentum
budget, the largest commands, for a ``detumble_point`` mission the switch time and, with an
``[estimator]``, the knowledge error (:func:`knowledge_summary`);
:func:`write_control_run` writes ``trajectory.csv`` and ``trajectory.npz``.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from ..dynamics.control.controlled import ControlledRun
from ..dynamics.control.controllers import Controller
from ..dynamics.control.estimated import Estimated
from ..dynamics.control.mission import DetumbleThenPoint
from .controlorbit import Field, Orbit, orbit_summary

if TYPE_CHECKING:
    from scipy.spatial.transform import Rotation

    from ..dynamics.control.pointing import NadirTarget
    from ..mass import Body

__all__ = ["control_summary", "knowledge_summary", "write_control_run"]


class _Scenario(Protocol):
    """What :func:`control_summary` reads of a :class:`~tumble.io.controlfile.ControlScenario`.

    A protocol, not the class: :mod:`tumble.io.controlfile` imports this module, and the import
    graph has no circles.
    """

    @property
    def body(self) -> Body: ...
    @property
    def kind(self) -> str: ...
    @property
    def controller_args(self) -> Mapping[str, Any]: ...
    @property
    def threshold(self) -> float: ...
    @property
    def target(self) -> Rotation | NadirTarget | None: ...
    @property
    def orbit(self) -> Orbit | None: ...
    @property
    def field(self) -> Field | None: ...
    @property
    def name(self) -> str: ...


def control_summary(scenario: _Scenario, run: ControlledRun, controller: Controller | None = None) -> dict[str, Any]:
    """The numbers of a run: final rate, detumble time, final pointing error, budgets, commands.

    ``controller`` is the one the run used (``tumble.run_scenario(scenario, controller)``): a ``detumble_point``
    mission's switch time is kept by it (``switch_time``, s, None when it never switched).

    Examples
    --------
    >>> import math
    >>> from tumble.io.bodyfile import body_from_table
    >>> from tumble.io.controlfile import control_scenario_from_table
    >>> import numpy as np
    >>> from tumble.io.controlrun import control_summary
    >>> body = body_from_table({"name": "box", "parts": [{"kind": "box", "mass": 4.0, "size": [0.1, 0.2, 0.3]}]})
    >>> table = {"initial": {"omega": [0.0, 0.0, 0.01], "attitude": [0.0, 0.5, 0.0, math.sqrt(0.75)]},
    ...          "simulation": {"t_end": 10.0}, "control": {"kind": "mrp_pd", "period": 0.5, "K": 1e-3, "P": 6e-3},
    ...          "actuators": {"wheels": {"axes": np.eye(3).tolist(), "inertia": 2e-5, "max_torque": 2e-3}}}
    >>> scenario = control_scenario_from_table(table, body, name="point")
    >>> import tumble
    >>> summary = control_summary(scenario, tumble.run_scenario(scenario))
    >>> summary["kind"], summary["samples"], summary["initial_rate"], summary["external_impulse"]
    ('mrp_pd', 21, 0.01, 0.0)
    >>> math.isclose(summary["pointing_error_initial"], math.pi / 3), summary["max_wheel_torque"] <= 2e-3
    (True, True)
    """
    summary: dict[str, Any] = {
        "body": scenario.body.name, "kind": scenario.kind, "t_end": float(run.t[-1]),
        "period": float(scenario.controller_args["period"]), "samples": len(run.t),
        "principal_moments": run.moments.tolist(),
        # principal -> design (columns: the principal axes in the design frame), as a free run's summary: the
        # file's vectors are design-frame, the run's principal
        "principal_axes": np.asarray(scenario.body.principal_axes).tolist(),
        "final_rate": float(run.rate[-1]), "initial_rate": float(run.rate[0]),
        "threshold": scenario.threshold, "detumble_time": run.detumble_time(scenario.threshold),
        "detumbled": run.detumble_time(scenario.threshold) is not None,  # whether |omega| got below the threshold and stayed
        "momentum_budget_error": float(run.budget_error().max()),
        "external_impulse": float(np.linalg.norm(run.impulse_world[-1])), **command_summary(run),
    }
    if scenario.kind == "bdot":
        summary["gain"] = float(scenario.controller_args["gain"])
        summary["form"] = scenario.controller_args.get("form", "classic")
    if isinstance(controller, Estimated):
        summary.update(knowledge_summary(controller, run))
        controller = controller.controller
    if scenario.kind == "detumble_point":
        if not isinstance(controller, DetumbleThenPoint):
            raise ValueError(f"{scenario.name}: the switch time of a detumble_point run is its controller's: "
                             "pass the controller the run used")
        args = scenario.controller_args
        summary["switch_time"] = controller.switch_time
        summary.update(switch_rate=float(args["switch_rate"]), dwell=float(args["dwell"]),
                       gain=float(args["detumble"]["gain"]), form=args["detumble"].get("form", "classic"),
                       dumping_gain=args.get("dumping_gain"))
    if scenario.target is not None:
        err = run.pointing_error(scenario.target)
        summary["pointing_error_final"] = float(err[-1])
        summary["pointing_error_initial"] = float(err[0])
        switch = summary.get("switch_time")
        if switch is not None:  # a mission's start is not what it points from: the tumble it detumbled is
            summary["pointing_error_switch"] = float(err[min(int(np.searchsorted(run.t, switch)), len(err) - 1)])
    if scenario.orbit is not None and scenario.field is not None:
        summary["orbit"] = orbit_summary(scenario.orbit, scenario.field)
    return summary


def knowledge_summary(estimated: Estimated, run: ControlledRun) -> dict[str, Any]:
    """The estimate's error against the truth over a run: RMS and final angle (deg), the final 3-sigma
    (deg, the largest axis's), the final bias estimate (rad/s), when the filter started (s) and the
    share of the steps at which each sensor updated it.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.control.estimated import Estimated
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> from tumble.dynamics.models.vector_sensors import StarTracker
    >>> from tumble.io.controlrun import knowledge_summary
    >>> sensors = Sensors(gyro_noise=1e-4, star_tracker=StarTracker(cross=1e-5, roll=1e-4, period=2.0))
    >>> c = Estimated(BDot(gain=1e-3, period=0.5), sensors)
    >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.05], t_end=20.0, controller=c, sensors=sensors)
    >>> k = knowledge_summary(c, run)
    >>> bool(k["knowledge_error_rms_deg"] < 0.05), k["knowledge_start"], k["sensors_used"]
    (True, 0.0, {'magnetometer': 0.0, 'sun': 0.0, 'star_tracker': 0.25})
    """
    k = estimated.knowledge()
    angle = np.degrees(np.linalg.norm(k.error(run), axis=1))
    return {"knowledge_error_rms_deg": float(np.sqrt(np.mean(angle**2))), "knowledge_error_final_deg": float(angle[-1]),
            "knowledge_3sigma_final_deg": float(3.0 * np.degrees(k.sigma[-1, :3].max())),
            "bias_estimate_final": k.bias[-1].tolist(), "knowledge_start": float(k.t[0]),
            "sensors_used": {name: float(k.used[:, i].mean()) for i, name in enumerate(("magnetometer", "sun", "star_tracker"))}}


def write_control_run(run: ControlledRun, folder: Path) -> None:
    """``trajectory.csv`` and ``trajectory.npz`` of a control run into ``folder``: time, omega,
    quaternion, wheel speeds and torques, dipole, field, world momentum and external impulse (SI; each
    CSV column's unit in its header, the body's vectors in the principal frame).

    Examples
    --------
    >>> import math, tempfile
    >>> from tumble.io.bodyfile import body_from_table
    >>> from tumble.io.controlfile import control_scenario_from_table
    >>> import numpy as np
    >>> from pathlib import Path
    >>> from tumble.io.controlrun import write_control_run
    >>> body = body_from_table({"name": "box", "parts": [{"kind": "box", "mass": 4.0, "size": [0.1, 0.2, 0.3]}]})
    >>> table = {"initial": {"omega": [0.0, 0.0, 0.01], "attitude": [0.0, 0.5, 0.0, math.sqrt(0.75)]},
    ...          "simulation": {"t_end": 10.0}, "control": {"kind": "mrp_pd", "period": 0.5, "K": 1e-3, "P": 6e-3},
    ...          "actuators": {"wheels": {"axes": np.eye(3).tolist(), "inertia": 2e-5, "max_torque": 2e-3}}}
    >>> scenario = control_scenario_from_table(table, body, name="point")
    >>> import tumble
    >>> run = tumble.run_scenario(scenario)
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write_control_run(run, Path(tmp))
    ...     header = (Path(tmp) / "trajectory.csv").read_text().splitlines()[0].split(",")
    ...     rows = np.loadtxt(Path(tmp) / "trajectory.csv", delimiter=",", skiprows=1)
    ...     with np.load(Path(tmp) / "trajectory.npz") as npz:
    ...         same = np.array_equal(npz["omega"], run.omega) and np.array_equal(npz["L_world"], run.momentum_world)
    >>> len(header), header[8:11], rows.shape, same
    (26, ['wheel1_speed [rad/s]', 'wheel2_speed [rad/s]', 'wheel3_speed [rad/s]'], (21, 26), True)
    >>> np.array_equal(rows[:, 1:4], run.omega)   # 17 significant digits: exact
    True
    >>> with tempfile.TemporaryDirectory() as tmp:   # the times one-dimensional, as a free run's
    ...     write_control_run(run, Path(tmp))
    ...     with np.load(Path(tmp) / "trajectory.npz") as npz:
    ...         print(npz["t"].shape, npz["omega"].shape)
    (21,) (21, 3)
    """
    k = run.wheel_speed.shape[1]
    columns = {"t": run.t[:, None], "omega": run.omega, "quat": run.attitude.as_quat(), "wheel_speed": run.wheel_speed,
               "wheel_torque": run.wheel_torque, "dipole": run.dipole, "field": run.field,
               "L_world": run.momentum_world, "impulse_world": run.impulse_world}
    # each with its SI unit, as the free run's (tumble.io.export.CSV_COLUMNS); the body's vectors in its principal frame
    names = ["t [s]", "omega_1 [rad/s]", "omega_2 [rad/s]", "omega_3 [rad/s]", "q_x", "q_y", "q_z", "q_w",
             *[f"wheel{i + 1}_speed [rad/s]" for i in range(k)], *[f"wheel{i + 1}_torque [N m]" for i in range(k)],
             "dipole_1 [A m^2]", "dipole_2 [A m^2]", "dipole_3 [A m^2]", "B_1 [T]", "B_2 [T]", "B_3 [T]",
             "L_world_x [kg m^2/s]", "L_world_y [kg m^2/s]", "L_world_z [kg m^2/s]",
             "impulse_world_x [kg m^2/s]", "impulse_world_y [kg m^2/s]", "impulse_world_z [kg m^2/s]"]
    table = np.hstack(list(columns.values()))
    np.savetxt(folder / "trajectory.csv", table, delimiter=",", header=",".join(names), comments="", fmt="%.17g")
    columns["t"] = run.t  # shape (n,), as a free run's trajectory.npz (it was (n, 1): a walkthrough's polyfit broke)
    np.savez_compressed(folder / "trajectory.npz", **{k_: np.asarray(v) for k_, v in columns.items()})


def command_summary(run: ControlledRun) -> dict[str, Any]:
    """Largest dipole (A m^2), wheel torque (N m) and wheel speed (rad/s) of a run, for reports.

    Examples
    --------
    >>> from tumble.dynamics import BDot, Magnetorquers, UniformField, simulate_controlled
    >>> from tumble.io.controlrun import command_summary
    >>> run = simulate_controlled([0.01, 0.02, 0.02], [0.0, 0.0, 0.1], t_end=4.0, controller=BDot(gain=1e4, period=1.0),
    ...                           field=UniformField((3e-5, 0.0, 0.0)), magnetorquers=Magnetorquers(0.2))
    >>> summary = command_summary(run)
    >>> summary["max_wheel_speed"], 0.0 < summary["max_dipole"] <= 0.2   # no wheels; dipoles within the rods' limit
    (0.0, True)
    """
    return {
        "max_dipole": float(np.max(np.abs(run.dipole))) if run.dipole.size else 0.0,
        "max_wheel_torque": float(np.max(np.abs(run.wheel_torque))) if run.wheel_torque.size else 0.0,
        "max_wheel_speed": float(np.max(np.abs(run.wheel_speed))) if run.wheel_speed.size else 0.0,
    }
