"""The figure of what the attitude filter knew in a closed-loop run: the estimate's error about
each body axis with the filter's own 3-sigma bounds, the gyroscope bias it estimated, and which
sensors updated it when (the sun sensor drops out in the Earth's shadow).

The run is a :class:`~tumble.dynamics.control.controlled.ControlledRun` whose controller was an
:class:`~tumble.dynamics.control.estimated.Estimated`; its
:meth:`~tumble.dynamics.control.estimated.Estimated.knowledge` gives the estimates.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..dynamics.control.controlled import ControlledRun
from ..dynamics.control.estimated import Knowledge
from ._backend import legend_outside, new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["figure_knowledge"]

_COLORS = ("tab:blue", "tab:orange", "tab:green")
_SENSORS = ("magnetometer", "sun sensor", "star tracker")


def figure_knowledge(run: ControlledRun, knowledge: Knowledge, *, switch_time: float | None = None,
                     title: str | None = None, bias: tuple[float, float, float] | None = None) -> Figure:
    """Three panels against time (s): the estimation error about each body axis (deg) inside its
    3-sigma bounds, the bias estimate (deg/s; dotted, the true bias when given, rad/s), and a band
    where each sensor updated the filter.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.control.controlled import simulate_controlled
    >>> from tumble.dynamics.control.bdot import BDot
    >>> from tumble.dynamics.control.estimated import Estimated
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> from tumble.dynamics.models.vector_sensors import StarTracker
    >>> from tumble.viz.knowledge import figure_knowledge
    >>> sensors = Sensors(gyro_noise=1e-4, gyro_bias=(1e-4, 0.0, 0.0), star_tracker=StarTracker(cross=1e-5, roll=1e-4, period=2.0))
    >>> c = Estimated(BDot(gain=1e-3, period=0.5), sensors)
    >>> run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.05], t_end=20.0, controller=c, sensors=sensors)
    >>> fig = figure_knowledge(run, c.knowledge(), bias=sensors.gyro_bias)
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['error (deg)', 'bias (deg/s)', 'sensor used']
    """
    err = np.degrees(knowledge.error(run))
    three = 3.0 * np.degrees(knowledge.sigma[:, :3])
    t = knowledge.t
    fig = new_figure((7.5, 7.0))
    axes = fig.subplots(3, 1, sharex=True)
    if title:
        fig.suptitle(title, fontsize=10)
    for i, c in enumerate(_COLORS):
        axes[0].plot(t, err[:, i], color=c, lw=0.8, label=f"axis {i + 1}")
        axes[0].plot(t, three[:, i], color=c, lw=0.6, ls="--")
        axes[0].plot(t, -three[:, i], color=c, lw=0.6, ls="--")
        axes[1].plot(t, np.degrees(knowledge.bias[:, i]), color=c, lw=0.9, label=f"axis {i + 1}")
        if bias is not None:
            axes[1].axhline(np.degrees(bias[i]), color=c, lw=0.6, ls=":")
        axes[2].fill_between(t, i + 0.15, i + 0.85, where=knowledge.used[:, i], step="post", color=c, lw=0.0)
    axes[0].plot([], [], color="k", lw=0.6, ls="--", label="3 sigma")
    axes[2].set_yticks([0.5, 1.5, 2.5], list(_SENSORS))
    axes[2].set_ylim(0.0, 3.0)
    for ax, label in zip(axes, ("error (deg)", "bias (deg/s)", "sensor used")):
        if switch_time is not None:
            ax.axvline(switch_time, color="k", ls="--", lw=0.8)
        ax.set_ylabel(label)
        ax.grid(True, lw=0.3)
    legend_outside(axes[0])
    legend_outside(axes[1])
    axes[2].set_xlabel("t (s)")
    return fig
