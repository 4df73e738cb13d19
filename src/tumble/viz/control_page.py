"""What the interactive page adds for a closed-loop (control) run: wheels, commanded torque, error.

:func:`control_page_data` turns a :class:`~tumble.dynamics.control.controlled.ControlledRun` into the
JSON-ready numbers that ``assets/control.js`` draws on top of the page's body
(:mod:`tumble.viz.page`): each reaction wheel as a disc on the body along its axis, turned by its
angle relative to the body (the trapezoid integral of its speed), with its speed in a readout;
the commanded body torque as an arrow (the wheels' reaction ``-sum u_k g_k`` plus the
magnetorquers' ``m x B``); the magnetorquer dipole where there is one; and a small time plot of
the attitude error to the target (pointing runs) or of ``|omega|`` (detumbling runs). With the
attitude filter in the loop (:class:`~tumble.dynamics.control.estimated.Estimated`) the page also
draws the estimated body axes beside the body, and the knowledge error on the time plot.

The frames are the page's own (:func:`tumble.viz.scene.frame_indices`: evenly spread samples,
first and last included), so the page plays the body, the wheels and the arrows together.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy.integrate import cumulative_trapezoid
from scipy.spatial.transform import Rotation

from ..dynamics.control.controlled import ControlledRun
from ..dynamics.control.estimated import Knowledge
from ..dynamics.control.pointing import Reference, is_reference
from ..typing import ArrayLike
from .page import _curve_indices, _rounded
from .scene import frame_indices

__all__ = ["commanded_torque", "control_page_data", "estimate_page_data", "wheel_angle"]


def wheel_angle(t: ArrayLike, speed: ArrayLike) -> np.ndarray:
    """Each wheel's angle relative to the body at each sample, rad: the trapezoid integral of its
    speed (rad/s) over the times ``t`` (s), zero at the first sample.

    Examples
    --------
    >>> from tumble.viz.control_page import wheel_angle
    >>> wheel_angle([0.0, 1.0, 3.0], [[2.0, 0.0], [2.0, 1.0], [4.0, 1.0]]).tolist()
    [[0.0, 0.0], [2.0, 0.5], [8.0, 2.5]]
    """
    return np.asarray(cumulative_trapezoid(np.asarray(speed, float), np.asarray(t, float), axis=0, initial=0.0), float)


def commanded_torque(run: ControlledRun, wheel_axes: ArrayLike | None = None) -> np.ndarray:
    """The torque the actuators put on the body at each sample, principal frame, N m: the wheels'
    reaction ``-sum_k u_k g_k`` (``u_k`` the applied motor torque, N m; ``g_k`` the unit wheel
    axes, principal frame, shape (k, 3)) plus the magnetorquers' ``m x B`` (A m^2 x T).

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.viz.control_page import commanded_torque
    >>> from tumble.dynamics.control.controllers import MRPFeedback
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.models.actuators import ReactionWheels
    >>> rw = ReactionWheels(np.eye(3), inertia=1e-4, max_torque=1e-3)
    >>> c = MRPFeedback(K=1e-3, P=1e-2, period=0.5, moments=[0.03, 0.04, 0.05], wheels=rw)
    >>> run = simulate_controlled([0.03, 0.04, 0.05], [0.01, 0.0, 0.0], t_end=2.0, controller=c,
    ...                           wheels=rw, attitude0=Rotation.from_rotvec([0.2, 0.0, 0.0]))
    >>> bool(np.array_equal(commanded_torque(run, rw.axes), -run.wheel_torque))  # wheels along the axes
    True
    """
    k = run.wheel_speed.shape[1]
    axes = _axes(wheel_axes, k)
    return np.asarray(np.cross(run.dipole, run.field) - run.wheel_torque @ axes, float)


def _axes(wheel_axes: ArrayLike | None, k: int) -> np.ndarray:
    """The wheel axes as k unit rows (principal frame); one line naming the argument if not."""
    if wheel_axes is None:
        if k:
            raise ValueError(f"wheel_axes = None, but the run has {k} wheels: give their axes (principal frame), "
                             f"shape ({k}, 3)")
        return np.zeros((0, 3))
    axes = np.asarray(wheel_axes, dtype=float)
    if axes.shape != (k, 3) or not np.all(np.isfinite(axes)) or (k and np.any(np.linalg.norm(axes, axis=1) == 0)):
        raise ValueError(f"wheel_axes = {np.asarray(wheel_axes).tolist()!r} must be {k} nonzero finite "
                         "3-vectors (principal frame), one per wheel of the run")
    return axes / np.linalg.norm(axes, axis=1, keepdims=True) if k else np.zeros((0, 3))


def control_page_data(run: ControlledRun, *, frames: int = 150, wheel_axes: ArrayLike | None = None,
                      target: Rotation | Reference | None = None, threshold: float | None = None,
                      knowledge: Knowledge | None = None) -> dict[str, Any]:
    """What the page draws of a closed-loop run, as JSON-ready data (SI units).

    Parameters
    ----------
    run : ControlledRun
        The closed-loop run (:func:`tumble.commands.run_scenario`).
    frames : int
        Animation frames, as the page's (2 to :data:`tumble.viz.scene.MAX_FRAMES`).
    wheel_axes : array_like, shape (k, 3), optional
        The reaction wheels' axes, principal frame (``ReactionWheels.axes``); needed when the run
        has wheels. Normalised here.
    target : scipy Rotation or Reference, optional
        The pointing target (target frame to world, the run's principal frame), fixed or moving
        (:mod:`tumble.dynamics.control.pointing`, the error to it at each time): the time plot shows the
        attitude error to it; without, ``|omega|``.
    threshold : float, optional
        Drawn as a line on the ``|omega|`` plot, rad/s (the detumble threshold).
    knowledge : Knowledge, optional
        What the attitude filter knew (:meth:`~tumble.dynamics.control.estimated.Estimated.knowledge`):
        adds ``estimate`` (:func:`estimate_page_data`).

    Returns
    -------
    dict
        ``wheel_axes`` (unit rows, principal frame); ``dipole`` (whether any dipole was
        commanded); ``frames``: ``t`` (s), ``angle`` (each wheel's angle relative to the body,
        rad, wrapped into [0, 2 pi)), ``speed`` (rad/s), ``torque`` (:func:`commanded_torque`,
        principal frame, N m), ``dipole`` (A m^2, principal frame, or None); ``aliased`` (a wheel
        turns more than half a revolution between two frames: the discs' motion is stroboscopic);
        ``curve``: ``name``, ``unit``, ``t`` (s), ``y``, ``threshold``, ``stride`` and ``samples``
        (the curve keeps every ``stride``-th of ``samples`` samples and the last one).

    Examples
    --------
    >>> import math
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.viz.control_page import control_page_data
    >>> from tumble.viz.control_page import wheel_angle
    >>> from tumble.dynamics.control.controllers import MRPFeedback
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.models.actuators import ReactionWheels
    >>> rw = ReactionWheels(np.eye(3), inertia=1e-4, max_torque=1e-3)
    >>> c = MRPFeedback(K=1e-3, P=1e-2, period=0.5, moments=[0.03, 0.04, 0.05], wheels=rw)
    >>> run = simulate_controlled([0.03, 0.04, 0.05], [0.01, 0.0, 0.0], t_end=10.0, controller=c,
    ...                           wheels=rw, attitude0=Rotation.from_rotvec([0.2, 0.0, 0.0]))
    >>> data = control_page_data(run, frames=5, wheel_axes=rw.axes, target=Rotation.identity())
    >>> data["frames"]["t"], data["curve"]["name"], data["frames"]["dipole"]
    ([0.0, 2.5, 5.0, 7.5, 10.0], 'attitude error', None)
    >>> turn = np.abs(np.diff(wheel_angle(run.t, run.wheel_speed)[::5], axis=0)).max()  # rad in 2.5 s
    >>> data["aliased"], bool(turn > math.pi)   # more than half a turn between frames: stroboscopic
    (True, True)
    >>> np.shape(data["frames"]["angle"]), data["frames"]["angle"][0]   # 5 frames, 3 wheels, from 0
    ((5, 3), [0.0, 0.0, 0.0])
    >>> import json
    >>> json.loads(json.dumps(data)) == data  # JSON-ready
    True
    """
    n, k = len(run.t), run.wheel_speed.shape[1]
    axes = _axes(wheel_axes, k)
    idx = frame_indices(n, frames)
    angle = wheel_angle(run.t, run.wheel_speed)
    turns = np.abs(np.diff(angle[idx], axis=0))
    has_dipole = bool(np.any(run.dipole != 0.0))
    if target is not None:
        if not is_reference(target) and (not isinstance(target, Rotation) or not target.single):
            raise ValueError(f"target = {target!r} must be one scipy Rotation (target frame to world) "
                             "or a moving reference (attitude(t), rate(t))")
        name, unit, y = "attitude error", "rad", run.pointing_error(target)
    else:
        name, unit, y = "|omega|", "rad/s", run.rate
    stride, keep = _curve_indices(n)
    out = {
        "wheel_axes": _rounded(axes, 12),
        "dipole": has_dipole,
        "aliased": bool(turns.size and turns.max() > math.pi),
        "frames": {
            "t": _rounded(run.t[idx], 8),
            "angle": _rounded(np.mod(angle[idx], 2.0 * math.pi)),
            "speed": _rounded(run.wheel_speed[idx]),
            "torque": _rounded(commanded_torque(run, axes)[idx]),
            "dipole": _rounded(run.dipole[idx]) if has_dipole else None,
        },
        "curve": {"name": name, "unit": unit, "t": _rounded(run.t[keep], 8), "y": _rounded(y[keep]),
                  "threshold": None if threshold is None or target is not None else float(threshold),
                  "stride": stride, "samples": n},
    }
    if knowledge is not None:
        out["estimate"] = estimate_page_data(run, knowledge, idx)
    return out


def estimate_page_data(run: ControlledRun, knowledge: Knowledge, idx: ArrayLike) -> dict[str, Any]:
    """The estimate on the page: at each page frame ``idx`` (sample indices of ``run``), ``turn``,
    the estimated principal axes as the columns of a matrix in the true principal frame (``A_true^T
    A_est``; null before the filter starts), and ``curve``, the knowledge error (rad) against time (s).

    The filter's last estimate before a frame's time is drawn (it runs at the control steps; the
    run's last sample, at ``t_end``, has none of its own).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.control.estimated import Estimated
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> from tumble.dynamics.models.vector_sensors import StarTracker
    >>> from tumble.viz.control_page import estimate_page_data
    >>> sensors = Sensors(gyro_noise=1e-4, star_tracker=StarTracker(cross=1e-5, roll=1e-4, period=1.0))
    >>> c = Estimated(BDot(gain=1e-3, period=0.5), sensors)
    >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.05], t_end=5.0, controller=c, sensors=sensors)
    >>> e = estimate_page_data(run, c.knowledge(), [0, 5, 10])
    >>> turn = np.array(e["turn"][2])
    >>> bool(np.allclose(turn @ turn.T, np.eye(3), atol=1e-6)), e["curve"]["name"], len(e["curve"]["t"])
    (True, 'knowledge error', 10)
    """
    rows = np.searchsorted(knowledge.t, run.t[np.asarray(idx)] + 1e-9, side="right") - 1
    turns = (run.attitude[np.asarray(idx)].inv() * knowledge.attitude[np.maximum(rows, 0)]).as_matrix()
    error = np.linalg.norm(knowledge.error(run), axis=1)
    stride, keep = _curve_indices(len(knowledge.t))
    return {"turn": [_rounded(m, 9) if r >= 0 else None for m, r in zip(turns, rows)],
            "curve": {"name": "knowledge error", "unit": "rad", "t": _rounded(knowledge.t[keep], 8),
                      "y": _rounded(error[keep])}}

