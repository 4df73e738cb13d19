"""Run what a scenario file describes: an open-loop run or a closed-loop (control) run.

:func:`tumble.load_scenario` reads the file (:mod:`tumble.io.scenario`,
:mod:`tumble.io.controlfile`); :func:`run_scenario` runs it here, in the command layer, so that
the file layer only reads and writes.
"""

from __future__ import annotations

import os
from typing import overload

from ..dynamics import Trajectory, simulate
from ..dynamics.control.controlled import ControlledRun, simulate_controlled
from ..dynamics.control.controllers import Controller
from ..io.controlfile import ControlScenario
from ..io.scenario import Scenario, load_scenario

__all__ = ["run_scenario"]


@overload
def run_scenario(scenario: Scenario, controller: None = None) -> Trajectory: ...


@overload
def run_scenario(scenario: str | os.PathLike[str], controller: Controller | None = None) -> Trajectory | ControlledRun: ...


@overload
def run_scenario(scenario: ControlScenario, controller: Controller | None = None) -> ControlledRun: ...


def run_scenario(scenario: Scenario | ControlScenario | str | os.PathLike[str],
                 controller: Controller | None = None) -> Trajectory | ControlledRun:
    """Run a scenario: :func:`tumble.simulate` for a :class:`~tumble.io.scenario.Scenario`,
    :func:`~tumble.dynamics.control.controlled.simulate_controlled` for a
    :class:`~tumble.io.controlfile.ControlScenario`.

    Parameters
    ----------
    scenario : Scenario, ControlScenario, str or path-like
        What :func:`tumble.load_scenario` returns (or one built in Python), or the file's path, which
        it reads.
    controller : Controller, optional
        A closed-loop run's controller (default a fresh ``scenario.controller()``); pass one to
        read what it keeps after the run, such as a ``detumble_point`` mission's switch time. An
        open-loop scenario takes none.

    Returns
    -------
    Trajectory or ControlledRun
        The trajectory (SI units: s, rad/s; attitude body to world).

    Raises
    ------
    TypeError
        For a ``scenario`` that is neither kind, or a controller given to an open-loop scenario.

    Examples
    --------
    >>> import tumble
    >>> from tumble.io.scenario import Scenario
    >>> torque = tumble.ConstantTorque((0.0, 0.0, 0.4375))   # N m about the major axis, I3 = 0.4375 kg m^2
    >>> scenario = Scenario(body=tumble.t_handle(), omega=(0.0, 0.0, 0.0), t_end=2.0, samples=3, torque=torque)
    >>> tumble.run_scenario(scenario).omega[:, 2].round(6).tolist()   # omega_3 = tau t / I3
    [0.0, 1.0, 2.0]
    >>> import pathlib, tempfile
    >>> with tempfile.TemporaryDirectory() as folder:   # a file's path: read first
    ...     path = pathlib.Path(folder) / "spin.toml"
    ...     _ = path.write_text('body = "t-handle"\\n[initial]\\nomega = [0.0, 0.0, 2.0]\\n[simulation]\\nt_end = 1.0\\n')
    ...     tumble.run_scenario(path)
    Trajectory('T-handle', exact (auto), 500 samples, t = 0..1 s, torque-free)
    """
    if isinstance(scenario, (str, os.PathLike)):
        scenario = load_scenario(scenario)
    if isinstance(scenario, ControlScenario):
        return simulate_controlled(**scenario.arguments(controller))
    if not isinstance(scenario, Scenario):
        raise TypeError(f"scenario = {type(scenario).__name__} is not a scenario; allowed: a Scenario or "
                        f"ControlScenario (tumble.load_scenario reads one from a file)")
    if controller is not None:
        raise TypeError(f"controller = {type(controller).__name__}: scenario {scenario.name!r} is an open-loop run; "
                        f"allowed: no controller (a closed-loop run is a scenario file with a [control] table)")
    return simulate(**scenario.arguments())
