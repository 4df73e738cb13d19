"""Figures of the spacecraft models: energy budget, nutation angle, attitude in the orbiting frame.

- :func:`figure_energy`: the total kinetic energy of body, rotors and damper against t, with its
  budget ``E0 + motor work - dissipated`` (:mod:`tumble.dynamics.models.internal`), J.
- :func:`figure_nutation`: the angle between the total angular momentum L and the major axis,
  which an energy sink drives to 0 (the major-axis rule; Likins, JPL TR 32-860, 1966).
- :func:`figure_orbit_angles`: roll, pitch and yaw relative to the orbiting (LVLH) frame of a
  gravity-gradient run (:func:`tumble.dynamics.models.gravity.orbit_frame_angles`), rad, against t in
  orbits.
- :func:`figure_omega_panels`: omega(t) of several runs in panels one above the other (a run
  with and without a wheel).
- :func:`spacecraft_figures`: which of these apply to a run, for the command line.

:func:`figure_energy`, :func:`figure_nutation` and :func:`figure_orbit_angles` take the
trajectory and an optional matplotlib ``ax`` (drawn there instead of on a new figure) and return
the Figure (:func:`tumble.viz.save_figure` writes it). Legends sit outside the axes, so they never
cover the data.
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING, Any

import numpy as np

from ..dynamics import Trajectory
from ..dynamics.models.gravity import GravityGradient, gravity_gradient_in, orbit_frame_angles
from ..dynamics.models.torques import TorqueLike
from .plots import COLORS, figure_omega_grid
from ._backend import figure_and_axes, legend_outside, new_figure, note_only
from .scene import check_run

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["figure_energy", "figure_nutation", "figure_omega_panels", "figure_orbit_angles", "spacecraft_figures"]


def _has_internal_models(traj: Trajectory) -> bool:
    return traj.dissipated is not None or traj.internal_momentum is not None


def figure_energy(traj: Trajectory, *, ax: Axes | None = None, log: bool = False) -> Figure:
    """Total kinetic energy and its budget against t, J.

    Draws ``traj.energy`` (body, rotors and damper) and, where the run has rotors or a damper,
    the budget ``E0 + W - D`` (``W`` the motors' work, when known; ``D`` the energy the damper
    dissipated): the two coincide, to the integrator's error, when the books balance. The title
    gives the largest difference relative to ``E0``.

    Parameters
    ----------
    traj : Trajectory
    ax : matplotlib Axes, optional
        Draw on these axes instead of a new figure.
    log : bool
        A logarithmic energy axis (for a run whose energy falls by orders of magnitude).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import tumble
    >>> import numpy as np
    >>> from tumble.viz.spacecraft import figure_energy
    >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 2.5])  # kg m^2
    >>> damper = tumble.SphericalDamper(inertia=0.3, damping=0.3)
    >>> run = tumble.simulate(body, [1.0, 0.05, 0.0], t_end=300.0, samples=5, damper=damper)  # minor-axis spin
    >>> ax = figure_energy(run).axes[0]
    >>> [line.get_label() for line in ax.lines], ax.get_title().split(";")[0]
    (['kinetic energy T (J)', '$E_0$ - dissipated (J)'], 'body: energy, rk8')
    >>> T, budget = (line.get_ydata() for line in ax.lines)
    >>> bool(np.array_equal(T, run.energy)), bool(np.array_equal(budget, run.energy[0] - run.dissipated))
    (True, True)
    >>> bool(np.allclose(T, budget, rtol=1e-9)), bool(T[-1] < T[0])  # the books balance; the damper took energy out
    (True, True)
    """
    check_run(traj)
    fig, ax = figure_and_axes(ax)
    E = traj.energy
    ax.plot(traj.t, E, color=COLORS[0], lw=1.4, label="kinetic energy T (J)")
    budget, terms = np.full_like(E, E[0]), []
    if traj.motor_work is not None:
        budget, terms = budget + traj.motor_work, terms + ["+ motor work"]
    if traj.dissipated is not None:
        budget, terms = budget - traj.dissipated, terms + ["- dissipated"]
    title = f"{traj.body_name}: energy, {traj.method}"
    if terms:
        ax.plot(traj.t, budget, color=COLORS[1], lw=1.2, ls="--", label=r"$E_0$ " + " ".join(terms) + " (J)")
        scale = max(abs(float(E[0])), float(np.max(np.abs(E))))
        if scale > 0:
            title += f"; budget closes to {np.max(np.abs(E - budget)) / scale:.1e} of max T"
    if log:
        ax.set_yscale("log")
    else:  # the energy's own digits on the axis, not "+6.6822e2" above it and 0.0005 on the ticks
        ax.ticklabel_format(axis="y", useOffset=False)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("energy (J)")
    ax.set_xlim(traj.t[0], traj.t[-1])
    ax.set_title(title, fontsize=9)
    legend_outside(ax)
    return fig


def figure_nutation(traj: Trajectory, *, ax: Axes | None = None, degrees: bool = True, log: bool = False) -> Figure:
    """The nutation angle between L and the major axis against t
    (:attr:`~tumble.dynamics.Trajectory.nutation_angle`).

    0 is a rigid spin about the major axis, the end state an energy sink drives any spin to.
    When L is 0 (to round-off) at every sample (a body at rest, or a slew from rest) there is no
    angle: the figure says so in one line.

    Parameters
    ----------
    traj : Trajectory
    ax : matplotlib Axes, optional
        Draw here instead of on a new figure.
    degrees : bool
        Degrees (default) or radians.
    log : bool
        A logarithmic angle axis (zeros are not drawn).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import tumble
    >>> import numpy as np
    >>> from tumble.viz.spacecraft import figure_nutation
    >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 2.5])  # kg m^2
    >>> damper = tumble.SphericalDamper(inertia=0.3, damping=0.3)
    >>> run = tumble.simulate(body, [1.0, 0.05, 0.0], t_end=300.0, samples=5, damper=damper)  # minor-axis spin
    >>> ax = figure_nutation(run).axes[0]
    >>> angle = ax.lines[0].get_ydata()  # deg: from a spin about the minor axis to one about the major axis
    >>> ax.get_ylabel(), round(float(angle[0]), 6), bool(angle[-1] < 2.0), bool(np.all(np.diff(angle) < 0))
    ('nutation angle (deg)', 90.0, True, True)
    >>> figure_nutation(run, degrees=False).axes[0].lines[0].get_ydata().tolist() == run.nutation_angle.tolist()
    True
    """
    check_run(traj)
    angle = traj.nutation_angle
    fig, ax = figure_and_axes(ax)
    if not np.any(np.isfinite(angle)):
        note_only(ax, "no nutation angle for this run: its angular momentum L is 0 at every sample",
                  f"{traj.body_name}: nutation, {traj.method}")
        return fig
    unit = "deg" if degrees else "rad"
    values = np.degrees(angle) if degrees else angle
    if log:
        values = np.where(values > 0, values, np.nan)
        ax.set_yscale("log")
    ax.plot(traj.t, values, color=COLORS[2], lw=1.4, label=f"angle between L and the major axis ({unit})")
    ax.set_xlabel("t (s)")
    ax.set_ylabel(f"nutation angle ({unit})")
    ax.set_xlim(traj.t[0], traj.t[-1])
    ax.set_title(f"{traj.body_name}: nutation, {traj.method}", fontsize=9)
    legend_outside(ax)
    return fig


def figure_orbit_angles(traj: Trajectory, gravity: GravityGradient, *, ax: Axes | None = None,
                        **axes: int | str) -> Figure:
    """Roll, pitch and yaw relative to the orbiting (LVLH) frame against t in orbits, rad.

    Parameters
    ----------
    traj : Trajectory
        A run under ``gravity`` (its ``t``, s, and ``attitude``).
    gravity : GravityGradient
        The orbit the run followed (bound to the body or not: only the orbit is used).
    ax : matplotlib Axes, optional
        Draw here instead of on a new figure.
    **axes
        ``pitch_axis``, ``yaw_axis`` as in :func:`tumble.dynamics.models.gravity.orbit_frame_angles`
        (default 3 and 1).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import tumble
    >>> import numpy as np
    >>> from tumble.viz.spacecraft import figure_orbit_angles
    >>> body, gg = tumble.t_handle(), tumble.GravityGradient(orbit_period=5400.0)  # s
    >>> s = tumble.lvlh_state(gg, body, pitch=0.01)  # 0.01 rad of pitch from the orbiting frame
    >>> run = tumble.simulate(body, s.omega0, attitude0=s.attitude0, torque=gg, t_end=600.0, samples=3)
    >>> ax = figure_orbit_angles(run, gg).axes[0]
    >>> ax.get_xlabel(), [line.get_label().split()[0] for line in ax.lines[:3]]
    ('t (orbits of 5400 s)', ['roll', 'pitch', 'yaw'])
    >>> ax.lines[1].get_xdata().round(4).tolist(), bool(np.array_equal(ax.lines[1].get_ydata(), tumble.orbit_frame_angles(run, gg).pitch))
    ([0.0, 0.0556, 0.1111], True)
    """
    check_run(traj)
    angles = orbit_frame_angles(traj, gravity, **axes)
    fig, ax = figure_and_axes(ax)
    orbits = traj.t / gravity.period
    for name, symbol, values, color in zip(("roll", "pitch", "yaw"), (r"\phi", r"\theta", r"\psi"), angles, COLORS):
        ax.plot(orbits, values, color=color, lw=1.2, label=rf"{name} ${symbol}$ (rad)")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel(f"t (orbits of {gravity.period:.6g} s)")
    ax.set_ylabel("angle from the orbiting frame (rad)")
    ax.set_xlim(orbits[0], orbits[-1])
    ax.set_title(f"{traj.body_name}: attitude in the orbiting frame, {traj.method}", fontsize=9)
    legend_outside(ax)
    return fig


def figure_omega_panels(cases: list[tuple[str, Trajectory]], *, fig: Figure | None = None,
                        sharey: bool = True) -> Figure:
    """omega(t) of several runs, principal frame, rad/s: one panel per run, one above the other.

    Parameters
    ----------
    cases : list of (str, Trajectory)
        Panel titles and runs (e.g. a body with its wheel spinning and with it stopped).
    fig : matplotlib Figure, optional
        An empty figure to draw the panels on (a new one by default).
    sharey : bool
        One omega scale for every panel (default), so the runs compare at a glance.

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import tumble
    >>> from tumble.viz.spacecraft import figure_omega_panels
    >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])  # kg m^2
    >>> cases = [(f"spin {w:g} rad/s", tumble.simulate(body, [0.01, w, 0.0], t_end=3.0, samples=31)) for w in (1.0, 4.0)]
    >>> fig = figure_omega_panels(cases)
    >>> [ax.get_title() for ax in fig.axes], fig.get_size_inches().tolist()  # one above the other
    (['spin 1 rad/s', 'spin 4 rad/s'], [8.6, 5.2])
    >>> fig.axes[0].get_ylim() == fig.axes[1].get_ylim()  # one omega scale
    True
    """
    cases = list(cases)
    fig = fig if fig is not None else new_figure((8.6, 2.6 * max(len(cases), 1)))
    return figure_omega_grid(cases, fig=fig, ncols=1, sharey=sharey)


def spacecraft_figures(traj: Trajectory, torque: TorqueLike | GravityGradient | None = None, **axes: Any) -> list[tuple[str, object]]:
    """The spacecraft figures that apply to a run, in drawing order: ``[(name, maker), ...]``.

    ``name`` is a file stem (``"energy"``, ``"nutation"``, ``"orbit_angles"``); ``maker(ax=None)``
    draws that figure of this run and returns the Figure, i.e. the figure function with the run
    bound.

    - ``"energy"`` (:func:`figure_energy`): the run has a damper (``traj.dissipated`` is not None)
      or rotors (``traj.internal_momentum`` is not None);
    - ``"nutation"`` (:func:`figure_nutation`): the same, and L is not 0 (to round-off,
      :data:`~tumble.dynamics.trajectory.ZERO_MOMENTUM_RTOL`) at every sample: a slew from rest has no nutation;
    - ``"orbit_angles"`` (:func:`figure_orbit_angles`): ``torque`` is a
      :class:`~tumble.dynamics.models.gravity.GravityGradient`, or a sum with one among its terms;
      ``axes`` (``pitch_axis``, ``yaw_axis``) go to it.

    An empty list for a rigid body under no torque or a constant one.

    Examples
    --------
    >>> import tumble
    >>> from tumble.viz.spacecraft import spacecraft_figures
    >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 2.5])  # kg m^2
    >>> damper = tumble.SphericalDamper(inertia=0.3, damping=0.3)
    >>> run = tumble.simulate(body, [1.0, 0.05, 0.0], t_end=300.0, samples=5, damper=damper)  # minor-axis spin
    >>> figures = spacecraft_figures(run)
    >>> [name for name, _ in figures], figures[1][1]().axes[0].get_ylabel()
    (['energy', 'nutation'], 'nutation angle (deg)')
    >>> spacecraft_figures(tumble.simulate(body, [1.0, 0.05, 0.0], t_end=1.0, samples=5))  # rigid, torque-free
    []
    >>> gg = tumble.GravityGradient(orbit_period=5400.0)
    >>> [name for name, _ in spacecraft_figures(tumble.simulate(body, [0.0, 0.0, 0.001], t_end=60.0, samples=3, torque=gg), gg)]
    ['orbit_angles']
    """
    makers: list[tuple[str, object]] = []
    if _has_internal_models(traj):
        makers.append(("energy", functools.partial(figure_energy, traj)))
        if not np.all(traj.momentum_is_zero):
            makers.append(("nutation", functools.partial(figure_nutation, traj)))
    orbit = gravity_gradient_in(torque)
    if orbit is not None:  # alone, or among the terms of a sum
        makers.append(("orbit_angles", functools.partial(figure_orbit_angles, traj, orbit, **axes)))
    return makers
