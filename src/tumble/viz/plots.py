"""Static figures of one run: omega(t), the seed's Figure 1 for every case, the drift of the invariants.

Every function draws on a given matplotlib ``ax`` (or ``fig`` for several panels), or on a new
figure, and returns the Figure; :func:`tumble.viz.save_figure` writes it. Legends sit outside
the axes, so they never cover the data. A run longer than :data:`MAX_POINTS` samples is drawn as
its envelope (the smallest and largest value in each of :data:`ENVELOPE_BINS` bins), said in
the title: drawn point by point it would be a solid block of colour. A run that oscillates more
than :data:`DETAIL_CYCLES` times is a block of colour however it is drawn, so :func:`figure_omega`
adds a second panel with its first few oscillations in detail.
"""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING

import numpy as np

from ..dynamics import Trajectory
from ..dynamics.euler import euler_rhs
from ..mass import AXIS_ROLES
from ..typing import ArrayLike
from ._backend import figure_and_axes, legend_outside, new_figure
from .scene import check_run

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["DETAIL_CYCLES", "ENVELOPE_BINS", "MAX_POINTS", "MAX_SAMPLE_PHASE", "ROUND_OFF", "AliasedSamplesWarning",
           "detail_window", "envelope", "figure_drift", "figure_omega", "figure_omega_grid", "plot_omega", "sample_phase"]

COLORS = ("tab:blue", "tab:orange", "tab:green")

#: Most samples drawn point by point per curve; a longer run is drawn as its envelope.
MAX_POINTS = 10_000
#: Bins of the envelope of a long run.
ENVELOPE_BINS = 500
#: More oscillations than this (of the busiest component) and :func:`figure_omega` adds a detail
#: panel of the first :data:`DETAIL_SHOWN` of them.
DETAIL_CYCLES = 30
DETAIL_SHOWN = 5
#: The largest phase (rad) omega's fastest oscillation may advance between two samples for a plot of
#: them to show it: past pi (Nyquist) the samples trace another, slower oscillation (aliasing).
MAX_SAMPLE_PHASE = np.pi
#: A relative drift below this (about 500 ulps of 1) is round-off: :func:`figure_drift` says so
#: instead of drawing its noise.
ROUND_OFF = 1e-13


def detail_window(traj: Trajectory) -> float | None:
    """The end time (s) of a window that holds the run's first :data:`DETAIL_SHOWN` oscillations, or
    None when no component oscillates more than :data:`DETAIL_CYCLES` times over the run.

    An oscillation is counted as two sign changes of a component of omega (a flip reverses
    omega_2, a wobble swings omega_1 and omega_2 through zero).

    Examples
    --------
    >>> import tumble
    >>> from tumble.viz.plots import detail_window
    >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])  # kg m^2
    >>> wobble = tumble.simulate(body, [0.1, 0.0, 10.0], t_end=25.0, samples=1001)  # near the major axis
    >>> round(detail_window(wobble), 9)  # omega_1 ~ cos(10 t) (nutation rate 10 sqrt(2 * 1 / 2)): 11th zero 1.05 pi s
    3.3
    >>> detail_window(tumble.simulate(body, [0.1, 0.0, 10.0], t_end=2.0, samples=81)) is None  # 3 oscillations
    True
    """
    w = np.asarray(traj.omega)
    changes = [np.flatnonzero(np.signbit(w[1:, j]) != np.signbit(w[:-1, j])) + 1 for j in range(3)]
    busiest = max(changes, key=len)
    if len(busiest) <= 2 * DETAIL_CYCLES:
        return None
    return float(traj.t[busiest[2 * DETAIL_SHOWN]])


class AliasedSamplesWarning(UserWarning):
    """A run's samples are too far apart for its figure to show its motion (:func:`sample_phase`
    past pi); the commands say it in one line.

    Examples
    --------
    >>> from tumble.viz import AliasedSamplesWarning
    >>> issubclass(AliasedSamplesWarning, UserWarning)
    True
    """

    cli_one_line = True


def sample_phase(traj: Trajectory) -> float:
    """The largest phase (rad) by which a component of omega oscillates between two consecutive
    samples, from Euler's equations' gyroscopic part (the oscillations of a free body's omega;
    Landau & Lifshitz, Mechanics, sec. 36-37): a component swinging over its range ``ptp`` with the
    rate ``|d omega_j / dt|`` turns at ``2 |d omega_j / dt| / ptp`` rad/s (``Omega`` for
    ``A cos(Omega t)``), times the sample spacing. Above pi (``MAX_SAMPLE_PHASE``) the samples
    alias: drawn, they show another motion than the run's. A torque's and rotors' parts are left
    out: the estimate is of the body's own oscillation, not of a gyrostat's.

    Examples
    --------
    A symmetric top's omega_1 and omega_2 turn at ``Omega = (I3 - I1) / I1 omega_3`` (Landau &
    Lifshitz sec. 36): here 0.5 x 10 = 5 rad/s, 0.05 rad between samples 0.01 s apart; 0.8 s apart,
    4 rad, and a plot of them shows a slower wobble than the body's.

    >>> import numpy as np
    >>> import tumble
    >>> from tumble.viz.plots import sample_phase
    >>> top = tumble.MassProperties.from_moments([2.0, 2.0, 3.0])   # kg m^2
    >>> round(sample_phase(tumble.simulate(top, [0.1, 0.0, 10.0], t_end=2.0, dt=0.01)), 4)
    0.05
    >>> sparse = sample_phase(tumble.simulate(top, [0.1, 0.0, 10.0], t_end=40.0, dt=0.8))
    >>> round(sparse, 1), bool(sparse > np.pi)
    (4.0, True)
    """
    check_run(traj)  # anything but a run: one line saying so, not an AttributeError
    w = np.asarray(traj.omega, float)
    if len(w) < 2:
        return 0.0
    rate = np.abs(euler_rhs(w, traj.moments))  # rad/s^2, principal frame
    span = np.ptp(w, axis=0)
    moving = span > 1e-9 * max(float(np.max(np.abs(w))), 1e-300)  # a component that stays put has no phase
    if not np.any(moving):
        return 0.0
    turn = np.max(2.0 * rate[:, moving] / span[moving], axis=1)  # rad/s, at each sample
    # and the local rate: Euler's equations linearised about each sample's omega, whose Jacobian's nonzero
    # eigenvalues are +-sqrt(s) to within the w1 w2 w3 term (at an axis the wobble frequency, s < 0, or the
    # growth rate, s > 0: Landau & Lifshitz sec. 37). The range over the whole run understates a wobble a damper
    # shrinks as it turns the spin (a walkthrough's damped T-handle: 2.85 rad a sample for a true 5.2)
    I1, I2, I3 = np.asarray(traj.moments, float)
    a1, a2, a3 = (I2 - I3) / I1, (I3 - I1) / I2, (I1 - I2) / I3
    local = np.sqrt(np.abs(a2 * a3 * w[:, 0] ** 2 + a1 * a3 * w[:, 1] ** 2 + a1 * a2 * w[:, 2] ** 2))
    turn = np.maximum(turn, local)
    dt = np.diff(np.asarray(traj.t, float))
    return float(np.max(np.maximum(turn[1:], turn[:-1]) * dt))


def envelope(t: ArrayLike, y: ArrayLike, bins: int = ENVELOPE_BINS) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The envelope of ``y(t)``: ``(t, low, high)``, each bin's first and last time with its min and max.

    ``t`` has shape (n,), ``y`` shape (n,) or (n, k); ``n`` samples are split into ``bins`` runs
    of (nearly) equal length. The outputs have ``2 * bins`` rows (each bin's value held over the
    bin), so a step-wise band drawn through them covers every sample.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.viz.plots import envelope
    >>> t, y = np.arange(6.0), np.array([0.0, 3.0, 1.0, 5.0, 2.0, 4.0])
    >>> times, low, high = envelope(t, y, bins=2)  # bins: samples 0-2 and 3-5
    >>> times.tolist(), low.tolist(), high.tolist()
    ([0.0, 2.0, 3.0, 5.0], [0.0, 0.0, 2.0, 2.0], [3.0, 3.0, 5.0, 5.0])
    """
    t, y = np.asarray(t, float), np.asarray(y, float)
    starts = np.linspace(0, len(t), min(bins, len(t)) + 1).astype(int)
    first, last = starts[:-1], starts[1:] - 1
    low, high = np.minimum.reduceat(y, first, axis=0), np.maximum.reduceat(y, first, axis=0)
    times = np.column_stack([t[first], t[last]]).ravel()
    return times, np.repeat(low, 2, axis=0), np.repeat(high, 2, axis=0)


def _inertia_label(traj: Trajectory, j: int) -> str:
    return rf"$\omega_{j + 1}$ ({AXIS_ROLES[j]}, $I_{j + 1}$ = {traj.moments[j]:.4g} kg m$^2$)"


def plot_omega(traj: Trajectory, ax: Axes, title: str | None = None) -> str | None:
    """Draw omega_1, omega_2, omega_3 (principal frame, rad/s) against t (s) on ``ax``.

    A run of more than :data:`MAX_POINTS` samples is drawn as its :func:`envelope`. Returns the
    note that says so (None when every sample is drawn); it is also the second line of the title.

    Examples
    --------
    >>> import tumble
    >>> from tumble.viz._backend import figure_and_axes
    >>> import numpy as np
    >>> from tumble.viz.plots import plot_omega
    >>> run = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=2.0, samples=101)
    >>> fig, ax = figure_and_axes()
    >>> plot_omega(run, ax, "T-handle") is None  # every sample drawn: no note
    True
    >>> [line.get_label().split("(")[1].split(",")[0] for line in ax.lines[:3]]  # each component's axis
    ['minor', 'intermediate', 'major']
    >>> ax.lines[1].get_label().endswith("$I_2$ = 0.3125 kg m$^2$)")  # and its moment
    True
    >>> bool(np.array_equal(ax.lines[1].get_ydata(), run.omega[:, 1])), ax.get_xlabel(), ax.get_title()
    (True, 't (s)', 'T-handle')
    """
    check_run(traj)
    note = None
    if len(traj) > MAX_POINTS:
        times, low, high = envelope(traj.t, traj.omega)
        for j in range(3):
            ax.fill_between(times, low[:, j], high[:, j], facecolor=COLORS[j], edgecolor=COLORS[j], alpha=0.3,
                            lw=0.8, label=_inertia_label(traj, j))
        note = (f"{len(traj)} samples: band = min to max of each component in {len(times) // 2} bins "
                f"of {(traj.t[-1] - traj.t[0]) / (len(times) // 2):.3g} s")
    else:
        for j in range(3):
            ax.plot(traj.t, traj.omega[:, j], color=COLORS[j], lw=1.2, label=_inertia_label(traj, j))
    ax.axhline(0.0, color="0.6", lw=0.6, zorder=0)
    ax.set_xlabel("t (s)")
    ax.set_ylabel(r"$\omega$, principal frame (rad/s)")
    if len(traj) > 1:
        ax.set_xlim(traj.t[0], traj.t[-1])
    heading = "\n".join(s for s in (title, note) if s)
    if heading:
        ax.set_title(heading, fontsize=9)
    legend_outside(ax)
    return note


def figure_omega(traj: Trajectory, *, ax: Axes | None = None, title: str | None = None,
                 control_period: float | None = None) -> Figure:
    """omega(t) of one run, principal frame (rad/s), against t (s).

    On a new figure, a run whose components oscillate more than :data:`DETAIL_CYCLES` times gets
    a second panel with its first :data:`DETAIL_SHOWN` oscillations (:func:`detail_window`), shaded
    on the first: the whole run shows the envelope, the detail the motion.

    Parameters
    ----------
    traj : Trajectory
        The run.
    ax : matplotlib Axes, optional
        Draw here instead of on a new figure (one panel, no detail).
    title : str, optional
        The axes' title.
    control_period : float, optional
        A control run's period, s (its samples are the control instants): where the samples alias
        (:class:`AliasedSamplesWarning`), the warning says to shorten it, not to give more samples.

    Returns
    -------
    matplotlib Figure
        ``ax.figure`` when ``ax`` was given; write it with :func:`tumble.viz.save_figure`.

    Examples
    --------
    >>> import tumble
    >>> from tumble.viz.plots import detail_window, figure_omega
    >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])  # kg m^2
    >>> len(figure_omega(tumble.simulate(body, [0.1, 0.0, 10.0], t_end=2.0, samples=81)).axes)  # 3 wobbles
    1
    >>> wobble = tumble.simulate(body, [0.1, 0.0, 10.0], t_end=25.0, samples=1001)  # 40 wobbles
    >>> whole, detail = figure_omega(wobble, title="near the major axis").axes
    >>> whole.get_title(), detail.get_xlim() == (0.0, detail_window(wobble)), detail.get_title()[:35]
    ('near the major axis', True, 'detail: the first 5 oscillations, t')
    """
    check_run(traj)
    phase = sample_phase(traj)
    if phase > MAX_SAMPLE_PHASE:  # a stroboscope: the curves would show a slower oscillation than the run's
        # a control run's samples are its control instants: more of them is a shorter period (a walkthrough's
        # "give more samples" could not be followed; its omega was in deg/s)
        fix = (f"give a shorter controller period than {control_period:g} s (its samples are the control instants); "
               "or is omega in deg/s?" if control_period is not None else "give more samples")
        warnings.warn(f"omega oscillates by up to {phase:.3g} rad between samples, past pi: the figure shows another "
                      f"motion than the run's; {fix}", AliasedSamplesWarning, stacklevel=2)
    end = detail_window(traj) if ax is None else None
    if end is None:
        fig, ax = figure_and_axes(ax, figsize=(8.6, 3.6))
        plot_omega(traj, ax, title)
        return fig
    fig = new_figure((8.6, 6.2))
    whole, detail = fig.subplots(2, 1)
    plot_omega(traj, whole, title)
    whole.axvspan(traj.t[0], end, color="0.8", alpha=0.6, zorder=0, lw=0)
    k = int(np.searchsorted(traj.t, end, side="right"))
    for j in range(3):
        detail.plot(traj.t[:k], traj.omega[:k, j], color=COLORS[j], lw=1.2, marker="." if k < 60 else None, ms=3)
    detail.axhline(0.0, color="0.6", lw=0.6, zorder=0)
    detail.set_xlim(traj.t[0], end)
    detail.set_xlabel("t (s)")
    detail.set_ylabel(r"$\omega$ (rad/s)")
    detail.set_title(f"detail: the first {DETAIL_SHOWN} oscillations, t = {traj.t[0]:.4g} to {end:.4g} s "
                     "(shaded above); colours as above", fontsize=9)
    return fig


def figure_omega_grid(cases: list[tuple[str, Trajectory]], *, fig: Figure | None = None, ncols: int = 3,
                      suptitle: str | None = None, sharey: bool = False) -> Figure:
    """Several runs side by side, one panel each (the seed's Figure 1, for every case of the study).

    Parameters
    ----------
    cases : list of (str, Trajectory)
        Panel titles and runs.
    fig : matplotlib Figure, optional
        An empty figure to draw the panels on (a new one by default).
    ncols : int
        Panels per row.
    suptitle : str, optional
        The figure's title.
    sharey : bool
        One omega scale for every panel.

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import tumble
    >>> import numpy as np
    >>> from tumble.viz.plots import figure_omega_grid
    >>> body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])  # kg m^2
    >>> cases = [(f"omega_2 = {w:g} rad/s", tumble.simulate(body, [0.01, w, 0.0], t_end=3.0, samples=31))
    ...          for w in (1.0, 2.0, 4.0)]
    >>> fig = figure_omega_grid(cases, ncols=2, suptitle="flip faster with more spin")
    >>> [ax.get_title() for ax in fig.axes], [ax.get_visible() for ax in fig.axes]  # 2 x 2, the 4th hidden
    (['omega_2 = 1 rad/s', 'omega_2 = 2 rad/s', 'omega_2 = 4 rad/s', ''], [True, True, True, False])
    >>> fig.get_suptitle(), bool(np.array_equal(fig.axes[2].lines[1].get_ydata(), cases[2][1].omega[:, 1]))
    ('flip faster with more spin', True)
    """
    cases = list(cases)
    if not cases:
        raise ValueError("cases is empty: give at least one (title, trajectory) pair")
    for k, case in enumerate(cases):
        if not (isinstance(case, (tuple, list)) and len(case) == 2):
            raise ValueError(f"cases[{k}] = {type(case).__name__} object must be a (title, trajectory) pair")
        check_run(case[1], f"cases[{k}][1]")
    if isinstance(ncols, bool) or not isinstance(ncols, (int, np.integer)) or ncols < 1:
        raise ValueError(f"ncols = {ncols!r} must be a whole number of at least 1")
    ncols = min(int(ncols), len(cases))
    nrows = int(np.ceil(len(cases) / ncols))
    fig = fig if fig is not None else new_figure((6.2 * ncols, 3.2 * nrows))
    axes = fig.subplots(nrows, ncols, squeeze=False, sharey=sharey)
    for ax, (title, traj) in zip(axes.flat, cases):
        plot_omega(traj, ax, title)
    for ax in list(axes.flat)[len(cases):]:
        ax.set_visible(False)
    if suptitle:
        fig.suptitle(suptitle)
    return fig


def _reference(size: np.ndarray) -> tuple[float, str]:
    """What a drift is measured against: the initial value, or the largest one if that is 0."""
    if size[0] > 0:
        return float(size[0]), "0"
    return (float(np.max(size)) or 1.0), "max"


def figure_drift(traj: Trajectory, *, ax: Axes | None = None, title: str | None = None) -> Figure:
    """Relative error of energy, |L| and L_world against time (s), on a log scale.

    ``|E - E0| / E0``, ``||L| - |L0|| / |L0|`` and ``|L_world - L_world(0)| / |L0|``
    (dimensionless): zero for the exact motion, round-off (~1e-16) for the best methods. Zeros
    are drawn at 1e-17. A run that starts at rest is measured against the largest value instead.
    A drift that stays below :data:`ROUND_OFF` is drawn as one dashed line at its largest value,
    labelled "at round-off", instead of a band of noise.

    Parameters
    ----------
    traj : Trajectory
        The run (its energy, |L| and L_world).
    ax : matplotlib Axes, optional
        Where to draw (default: on a new figure).
    title : str, optional
        The axes' title (default: body, method and, under a torque, that these change physically).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import tumble
    >>> import numpy as np
    >>> from tumble.viz.plots import figure_drift
    >>> rk45 = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=2.0, samples=101, method="rk45")
    >>> ax = figure_drift(rk45).axes[0]
    >>> ax.get_yscale(), ax.get_title(), [line.get_label().split(":")[0] for line in ax.lines]
    ('log', 'T-handle: drift of the invariants, rk45', ['energy', '|L|', '$L_{world}$'])
    >>> bool(np.isclose(ax.lines[0].get_ydata().max(), rk45.drift["energy"]))  # the run's largest energy error
    True
    >>> exact = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=2.0, samples=101)
    >>> [text.get_text() for text in figure_drift(exact).axes[0].texts]  # exact: one dashed line per invariant
    ['at round-off:\\nevery drift below 1e-13']
    """
    check_run(traj)
    fig, ax = figure_and_axes(ax, figsize=(8.6, 3.6))
    E, Ln, Lw = traj.energy, traj.angular_momentum_norm, traj.angular_momentum_world
    (ref_E, at_E), (ref_L, at_L) = _reference(np.abs(E)), _reference(Ln)
    series = [
        (np.abs(E - E[0]) / ref_E, rf"energy: |E - E$_0$| / E$_{{{at_E}}}$"),
        (np.abs(Ln - Ln[0]) / ref_L, rf"|L|: ||L| - |L$_0$|| / |L|$_{{{at_L}}}$"),
        (np.linalg.norm(Lw - Lw[0], axis=1) / ref_L, rf"$L_{{world}}$: |$L_w - L_{{w,0}}$| / |L|$_{{{at_L}}}$"),
    ]
    ax.set_yscale("log")
    tops = [float(np.max(values)) for values, _ in series]
    ax.set_ylim(5e-18, 3 * max(1e-13, *tops))  # set, not autoscaled: a flat line alone is singular
    for (values, label), color, top in zip(series, COLORS, tops):
        if top < ROUND_OFF:  # a band of round-off noise says nothing: one line at its largest value
            ax.axhline(max(top, 1e-17), color=color, lw=1.1, ls="--", label=f"{label}: at round-off (max {top:.1e})")
        elif len(traj) > MAX_POINTS:
            times, _, high = envelope(traj.t, values)
            ax.semilogy(times, np.maximum(high, 1e-17), color=color, lw=1.1, label=label + ", max per bin")
        else:
            ax.semilogy(traj.t, np.maximum(values, 1e-17), color=color, lw=1.1, label=label)
    if max(tops) < ROUND_OFF:
        # two lines: in a narrow panel (a notebook's half of 11 in) one ran over the tick labels
        ax.text(0.5, 0.8, f"at round-off:\nevery drift below {ROUND_OFF:.0e}", transform=ax.transAxes, ha="center",
                fontsize=10)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("relative drift (dimensionless)")
    if len(traj) > 1:
        ax.set_xlim(traj.t[0], traj.t[-1])
    note = "" if traj.torque_free else "\n(a torque acts: these change physically)"
    ax.set_title(title or f"{traj.body_name}: drift of the invariants, {traj.method}{note}", fontsize=9)
    legend_outside(ax)
    return fig
