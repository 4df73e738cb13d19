"""Figures of a closed-loop run (:class:`~tumble.dynamics.control.controlled.ControlledRun`): what the
controller did and what it cost.

One function per figure, each returning its Figure (:func:`tumble.viz.save_figure` writes it):
the attitude error against the target (deg, log scale), the body rates (deg/s: components, and
``|omega|`` on a log scale), the wheels (speeds, rad/s, and applied torques, N m), the
magnetorquer dipole (A m^2) and the momentum budget (kg m^2/s: the wheels' ``|h|``, the body's
``|I omega|``, the external impulse, and ``|L_world - L_world(0) - impulse|``, which is zero in
exact arithmetic). Asked for directly, a figure of what the run lacks (wheels, dipole, target) is a
panel that says so. A mission's switch from detumbling to pointing
(:class:`~tumble.dynamics.control.mission.DetumbleThenPoint`) is marked by a dashed vertical line in
every panel. :func:`control_figures` gives the figures the run has something to show in, by the
file name ``tumble simulate`` writes each under: no ``wheels.png`` without wheels, no
``attitude_error.png`` without a target.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, cast

import numpy as np

from ..dynamics.control.controlled import ControlledRun
from ._backend import legend_outside, new_figure, note_only

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from scipy.spatial.transform import Rotation

    from ..dynamics.control.pointing import Reference

__all__ = ["CONTROL_FIGURES", "control_figures", "figure_attitude_error", "figure_body_rates", "figure_dipole",
           "figure_momentum_budget", "figure_wheels", "wheel_momentum"]

#: The files of :func:`control_figures`, in the order they are drawn (a run without wheels has no
#: ``wheels.png``, one without a target no ``attitude_error.png``, one whose magnetorquers never
#: act, or that has none, no ``dipole.png``).
CONTROL_FIGURES = ("attitude_error.png", "rates.png", "wheels.png", "dipole.png", "momentum.png")
COLORS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown")
SWITCH_LABEL = "switch to pointing"


def _check(run: object) -> ControlledRun:
    if not isinstance(run, ControlledRun):
        raise ValueError(f"run = {type(run).__name__} object must be a ControlledRun (what simulate_controlled returns)")  # noqa: TRY004
    return run


def _mark_switch(ax: Axes, switch_time: float | None) -> None:
    if switch_time is not None:
        ax.axvline(switch_time, color="k", ls="--", lw=0.8, label=SWITCH_LABEL)


def _finish(ax: Axes, ylabel: str, switch_time: float | None, xlabel: bool = True) -> None:
    _mark_switch(ax, switch_time)
    ax.set_ylabel(ylabel)
    if xlabel:
        ax.set_xlabel("t (s)")
    ax.grid(True, lw=0.3)
    legend_outside(ax)


def _figure(title: str | None, rows: int) -> tuple[Figure, list[Axes]]:
    fig = new_figure((7.5, 2.2 + 1.8 * rows))
    axes = list(np.atleast_1d(fig.subplots(rows, 1, sharex=True)))
    if title:
        fig.suptitle(title, fontsize=10)
    return fig, axes


def wheel_momentum(run: ControlledRun) -> np.ndarray:
    """The wheels' momentum ``h = R^T L_world - I omega`` at each sample, body frame, kg m^2/s, shape (n, 3).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.viz.control import wheel_momentum
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.control.controllers import MRPFeedback
    >>> from tumble.dynamics.models.actuators import ReactionWheels
    >>> rw = ReactionWheels(np.eye(3), inertia=1e-4)
    >>> c = MRPFeedback(K=1e-3, P=1e-2, period=0.5, moments=[0.03, 0.04, 0.05], wheels=rw)
    >>> run = simulate_controlled([0.03, 0.04, 0.05], [0.01, 0.0, 0.0], t_end=5.0, controller=c, wheels=rw,
    ...                           attitude0=Rotation.from_rotvec([0.2, 0.0, 0.0]))
    >>> np.allclose(wheel_momentum(run), rw.momentum(run.wheel_speed), rtol=0, atol=1e-15)   # sum J s g
    True
    """
    run = _check(run)
    return np.asarray(run.attitude.inv().apply(run.momentum_world) - run.moments * run.omega, float).reshape(-1, 3)


def figure_attitude_error(run: ControlledRun, target: Rotation | Reference | None, *, switch_time: float | None = None,
                          title: str | None = None, ax: Axes | None = None) -> Figure:
    """The angle from the target to the body's principal frame (deg, log scale) against time (s).

    ``target`` is fixed (a scipy Rotation, target frame to world) or a moving reference
    (:mod:`tumble.dynamics.control.pointing`: the error to it at each time).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.viz.control import figure_attitude_error
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.control.bdot import BDot
    >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=10.0, controller=BDot(gain=1e-3, period=1.0))
    >>> ax = figure_attitude_error(run, Rotation.from_rotvec([0.0, 0.0, 1.0])).axes[0]
    >>> line = ax.lines[0]
    >>> ax.get_yscale(), line.get_label(), bool(np.allclose(line.get_ydata(), np.degrees(np.abs(1.0 - 0.1 * run.t))))
    ('log', 'attitude error', True)
    >>> figure_attitude_error(run, None).axes[0].texts[0].get_text()
    'no target: this run does not point'
    """
    run = _check(run)
    if ax is None:
        fig, (ax,) = _figure(title, 1)
    else:
        fig = cast("Figure", ax.figure)
    if target is None:
        note_only(ax, "no target: this run does not point", "attitude error")
        return fig
    ax.plot(run.t, np.degrees(run.pointing_error(target)), color=COLORS[0], lw=1.0, label="attitude error")
    ax.set_yscale("log")
    _finish(ax, "attitude error (deg)", switch_time)
    return fig


def figure_body_rates(run: ControlledRun, *, switch_time: float | None = None, title: str | None = None,
                      fig: Figure | None = None) -> Figure:
    """The body rates: ``omega_1..3`` (deg/s, principal frame) above, ``|omega|`` (deg/s, log scale) below.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.viz.control import figure_body_rates
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.control.bdot import BDot
    >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=10.0, controller=BDot(gain=1e-3, period=1.0))
    >>> top, bottom = figure_body_rates(run, switch_time=4.0).axes
    >>> [line.get_label() for line in top.lines]
    ['omega_1', 'omega_2', 'omega_3', 'switch to pointing']
    >>> bottom.get_yscale(), bool(np.allclose(bottom.lines[0].get_ydata(), np.degrees(0.1)))
    ('log', True)
    """
    run = _check(run)
    fig, axes = _figure(title, 2) if fig is None else (fig, list(np.atleast_1d(fig.subplots(2, 1, sharex=True))))
    top, bottom = axes
    for j in range(3):
        top.plot(run.t, np.degrees(run.omega[:, j]), color=COLORS[j], lw=0.8, label=f"omega_{j + 1}")
    _finish(top, "omega (deg/s)", switch_time, xlabel=False)
    bottom.plot(run.t, np.degrees(run.rate), color="k", lw=1.0, label="|omega|")
    bottom.set_yscale("log")
    _finish(bottom, "|omega| (deg/s)", switch_time)
    return fig


def figure_wheels(run: ControlledRun, *, switch_time: float | None = None, title: str | None = None,
                  fig: Figure | None = None) -> Figure:
    """The wheels: spins relative to the body (rad/s) above, applied motor torques (N m) below.

    Examples
    --------
    >>> from tumble.viz.control import figure_wheels
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.control.bdot import BDot
    >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=10.0, controller=BDot(gain=1e-3, period=1.0))
    >>> figure_wheels(run).axes[0].texts[0].get_text()
    'no reaction wheels in this run'
    """
    run = _check(run)
    k = run.wheel_speed.shape[1]
    if k == 0:
        fig, (ax,) = _figure(title, 1) if fig is None else (fig, [fig.add_subplot()])
        note_only(ax, "no reaction wheels in this run", "wheels")
        return fig
    fig, axes = _figure(title, 2) if fig is None else (fig, list(np.atleast_1d(fig.subplots(2, 1, sharex=True))))
    top, bottom = axes
    for i in range(k):
        top.plot(run.t, run.wheel_speed[:, i], color=COLORS[i % len(COLORS)], lw=0.8, label=f"wheel {i + 1}")
        bottom.step(run.t, run.wheel_torque[:, i], where="post", color=COLORS[i % len(COLORS)], lw=0.8,
                    label=f"wheel {i + 1}")
    _finish(top, "wheel speed (rad/s)", switch_time, xlabel=False)
    _finish(bottom, "wheel torque (N m)", switch_time)
    return fig


def figure_dipole(run: ControlledRun, *, switch_time: float | None = None, title: str | None = None,
                  ax: Axes | None = None) -> Figure:
    """The magnetorquers' dipole held from each step, ``m_1..3`` (A m^2, principal frame).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.viz.control import figure_dipole
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.models.actuators import Magnetorquers
    >>> from tumble.dynamics.environment.magnetic import UniformField
    >>> run = simulate_controlled([0.01, 0.02, 0.02], [0.0, 0.0, 0.1], t_end=5.0, controller=BDot(gain=1e4, period=1.0),
    ...                           field=UniformField((3e-5, 0.0, 0.0)), magnetorquers=Magnetorquers(0.2))
    >>> ax = figure_dipole(run).axes[0]
    >>> [line.get_label() for line in ax.lines], np.array_equal(ax.lines[1].get_ydata(), run.dipole[:, 1])
    (['m_1', 'm_2', 'm_3'], True)
    """
    run = _check(run)
    if ax is None:
        fig, (ax,) = _figure(title, 1)
    else:
        fig = cast("Figure", ax.figure)
    if not np.any(run.dipole):
        note_only(ax, "no magnetorquer dipole in this run", "dipole")
        return fig
    for j in range(3):
        ax.step(run.t, run.dipole[:, j], where="post", color=COLORS[j], lw=0.8, label=f"m_{j + 1}")
    _finish(ax, "dipole (A m^2)", switch_time)
    return fig


def figure_momentum_budget(run: ControlledRun, *, switch_time: float | None = None, title: str | None = None,
                           fig: Figure | None = None) -> Figure:
    """Where the angular momentum is (kg m^2/s) above, and how well the budget closes below.

    Above: the wheels' ``|h|`` (``tumble.viz.control.wheel_momentum``; with wheels only), the body's ``|I omega|`` and the external
    angular impulse ``|int tau_world dt|``. Below (log scale): ``|L_world(t) - L_world(0) -
    impulse(t)|`` (:meth:`~tumble.dynamics.control.controlled.ControlledRun.budget_error`), zero in exact
    arithmetic; samples where it is exactly zero are left out of the log axis.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.viz.control import figure_momentum_budget
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.control.controllers import MRPFeedback
    >>> from tumble.dynamics.models.actuators import ReactionWheels
    >>> rw = ReactionWheels(np.eye(3), inertia=1e-4)
    >>> c = MRPFeedback(K=1e-3, P=1e-2, period=0.5, moments=[0.03, 0.04, 0.05], wheels=rw)
    >>> run = simulate_controlled([0.03, 0.04, 0.05], [0.01, 0.0, 0.0], t_end=5.0, controller=c, wheels=rw,
    ...                           attitude0=Rotation.from_rotvec([0.2, 0.0, 0.0]))
    >>> top, bottom = figure_momentum_budget(run).axes
    >>> [line.get_label() for line in top.lines], bottom.get_yscale()
    (['wheels |h|', 'body |I omega|', 'external impulse'], 'log')
    >>> bool(np.all(np.asarray(bottom.lines[0].get_ydata()) < 1e-15))
    True
    """
    run = _check(run)
    fig, axes = _figure(title, 2) if fig is None else (fig, list(np.atleast_1d(fig.subplots(2, 1, sharex=True))))
    top, bottom = axes
    if run.wheel_speed.shape[1] > 0:  # no line of zeros for wheels a run does not have
        top.plot(run.t, np.linalg.norm(wheel_momentum(run), axis=1), color=COLORS[0], lw=1.0, label="wheels |h|")
    top.plot(run.t, np.linalg.norm(run.moments * run.omega, axis=1), color=COLORS[1], lw=1.0, label="body |I omega|")
    top.plot(run.t, np.linalg.norm(run.impulse_world, axis=1), color=COLORS[2], lw=1.0, label="external impulse")
    _finish(top, "momentum (kg m^2/s)", switch_time, xlabel=False)
    gap = run.budget_error()
    keep = gap > 0.0
    bottom.plot(run.t[keep], gap[keep], color="k", lw=0.8, label="|L - L(0) - impulse|")
    bottom.set_yscale("log")
    _finish(bottom, "budget error (kg m^2/s)", switch_time)
    return fig


def control_figures(run: ControlledRun, *, target: Rotation | Reference | None = None, switch_time: float | None = None,
                    title: str | None = None) -> dict[str, Figure]:
    """The figures of a control run, by the file name it is written under (``tumble.viz.control.CONTROL_FIGURES``).

    A figure with nothing to show is left out: ``wheels.png`` of a run without reaction wheels,
    ``attitude_error.png`` of a run without a target (a B-dot detumbling), ``dipole.png`` of a run
    whose magnetorquer dipole is zero throughout (none, as in a wheels-only pointing). The others
    are always there.

    Parameters
    ----------
    run : ControlledRun
        The run.
    target : scipy Rotation or Reference, optional
        The target frame to world, fixed or moving, for the attitude error (None: no
        ``attitude_error.png``).
    switch_time : float, optional
        The mission's switch from detumbling to pointing, s, marked in every panel.
    title : str, optional
        A title over each figure.

    Examples
    --------
    >>> from tumble.viz.control import control_figures
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.models.actuators import Magnetorquers
    >>> from tumble.dynamics.environment.magnetic import UniformField
    >>> bdot = BDot(gain=1e-3, period=1.0, form="normalized")   # N m s
    >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=10.0, controller=bdot,
    ...                           field=UniformField((3e-5, 0.0, 0.0)), magnetorquers=Magnetorquers(0.2))
    >>> figures = control_figures(run, title="spin")   # no wheels, no target
    >>> list(figures), figures["rates.png"].get_suptitle()
    (['rates.png', 'dipole.png', 'momentum.png'], 'spin')
    >>> list(control_figures(run, target=Rotation.identity()))
    ['attitude_error.png', 'rates.png', 'dipole.png', 'momentum.png']
    >>> coasting = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=10.0, controller=BDot(gain=1e-3, period=1.0))
    >>> list(control_figures(coasting))   # no magnetorquers either: no dipole.png
    ['rates.png', 'momentum.png']
    """
    run = _check(run)
    figures: dict[str, Figure] = {}
    if target is not None:
        figures["attitude_error.png"] = figure_attitude_error(run, target, switch_time=switch_time, title=title)
    figures["rates.png"] = figure_body_rates(run, switch_time=switch_time, title=title)
    if run.wheel_speed.shape[1] > 0:
        figures["wheels.png"] = figure_wheels(run, switch_time=switch_time, title=title)
    if np.any(run.dipole):
        figures["dipole.png"] = figure_dipole(run, switch_time=switch_time, title=title)
    figures["momentum.png"] = figure_momentum_budget(run, switch_time=switch_time, title=title)
    return figures
