"""The figure of a fitted tumble: the measured angular velocity against the fitted model.

Three panels (the sensor's x, y, z), the samples as dots and the model
(:attr:`tumble.analysis.fit.RotationFit.omega_model`, bias included) as a line, and below them
the residuals; the title gives the fitted ratios with their uncertainties.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..typing import ArrayLike
from ._backend import legend_outside, new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..analysis.fit import RecordingFit, RotationFit

__all__ = ["figure_fit", "figure_recording", "skip_label"]


def figure_fit(fit: RotationFit, omega_measured: ArrayLike, *, fig: Figure | None = None) -> Figure:
    """Measured angular velocity against the fit (:func:`tumble.analysis.fit.fit_rotation`).

    Parameters
    ----------
    fit : RotationFit
        The fit.
    omega_measured : array_like, shape (n, 3)
        The samples that were fitted, sensor axes, rad/s.
    fig : matplotlib Figure, optional
        An empty figure to draw the four panels on (a new one by default).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> from tumble.analysis.fit import fit_rotation
    >>> from tumble.dynamics.methods.exact import FreeRotation
    >>> import numpy as np
    >>> from tumble.viz.fit import figure_fit
    >>> t = np.linspace(0.0, 2.0, 201)  # s
    >>> w = FreeRotation([0.3, 0.7, 1.0], [0.2, 5.0, 0.3], Rotation.identity()).omega(t)  # rad/s, exact
    >>> fit = fit_rotation(t, w, sensor_rotation="identity", bias=False, drag="none")
    >>> fig = figure_fit(fit, w)
    >>> [ax.get_ylabel() for ax in fig.axes][3], fig.get_suptitle().startswith("I1/I3 = 0.30000")  # the truth
    ('residual (rad/s)', True)
    >>> measured, model = fig.axes[1].lines  # omega_y: the samples as dots, the fit as a line
    >>> bool(np.array_equal(measured.get_ydata(), w[:, 1])), bool(np.array_equal(model.get_ydata(), fit.omega_model[:, 1]))
    (True, True)
    """
    w = np.asarray(omega_measured, float)
    t = fit.t - fit.t[0]
    fig = fig if fig is not None else new_figure((10, 8))
    axes = fig.subplots(4, 1, sharex=True, gridspec_kw={"height_ratios": [2, 2, 2, 1.3]})
    for k, (ax, name) in enumerate(zip(axes[:3], "xyz")):
        ax.plot(t, w[:, k], ".", ms=2, color="0.5", label="measured")
        ax.plot(t, fit.omega_model[:, k], "-", lw=1.0, color=f"C{k}", label="fit")
        ax.set_ylabel(rf"$\omega_{name}$ (rad/s)")
        legend_outside(ax, fontsize=8)
    for k, name in enumerate("xyz"):
        axes[3].plot(t, w[:, k] - fit.omega_model[:, k], ".", ms=1.5, color=f"C{k}", label=name)
    axes[3].set_ylabel("residual (rad/s)")
    axes[3].set_xlabel(f"t - t0 (s), from the first sample at t0 = {fit.t[0]:.3g} s")
    legend_outside(axes[3], fontsize=8, markerscale=6)
    (x, y), (sx, sy) = fit.ratios, fit.ratios_std
    fig.suptitle(f"I1/I3 = {x:.5f} \u00b1 {sx:.1g},  I2/I3 = {y:.5f} \u00b1 {sy:.1g},  "
                 f"residual RMS {fit.residual_rms:.3g} rad/s ({fit.samples} samples)", fontsize=10)
    return fig


def skip_label(reason: str) -> str:
    """The few words of a skipped flight's reason that the figure writes at it.

    Examples
    --------
    >>> from tumble.viz.fit import skip_label
    >>> skip_label("too short (0.21 s, 21 samples; a flight needs 0.3 s and 30 samples)")
    'too short'
    >>> skip_label("not a rigid body: its angular momentum |L| rose by 12 % during the flight")
    'not a rigid body'
    """
    return reason.split(":")[0].split(" (")[0].strip() or "skipped"


#: The size of :func:`figure_recording`'s figure, inches.
FIGURE_SIZE = (12.0, 8.0)
#: Its margins, inches: left, right (the legend), top (the titles), bottom, between the rows (the
#: top panel's axis label), between the columns (the triangle's tick labels and axis label).
LAYOUT = (0.8, 0.9, 0.62, 0.5, 0.65, 0.9)


def figure_recording(rec: RecordingFit, *, fig: Figure | None = None, max_flights: int = 12) -> Figure:
    """A whole recording fitted (:func:`tumble.analysis.fit.fit_recording`).

    Top: the recording (each axis and ``|omega|``), its flights shaded (green: used; grey:
    skipped, with the reason in a few words, :func:`skip_label`; "used in the joint fit only"
    written at a flight that does not determine the ratios alone). Bottom left: the used
    flights side by side (the first ``max_flights``), samples as dots and the joint fit as lines.
    Bottom right: the ratios of each flight that determines them, with their standard
    uncertainties, in the triangle of inertia ratios, the pooled value in black, and the
    triangle's planar edge.

    Parameters
    ----------
    rec : RecordingFit
    fig : matplotlib Figure, optional
    max_flights : int
        Most flights drawn in the middle panel.

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from tumble.analysis.fit import fit_recording
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> import numpy as np
    >>> from tumble.viz.fit import figure_recording
    >>> rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))  # a phone's recording of two tosses
    >>> fit = fit_recording(rec.t, rec.omega, events=rec.events)
    >>> top, flights, triangle = figure_recording(fit).axes
    >>> top.get_title(), len(flights.lines)  # each flight: 3 components, samples and joint fit
    ('2 flights found, 2 used (green), 0 skipped (grey)', 12)
    >>> pooled = next(c for c in triangle.containers if c.get_label() == "pooled")
    >>> bool(np.allclose(pooled.lines[0].get_xydata(), [fit.pooled.ratios]))  # the pooled (I1/I3, I2/I3)
    True
    """
    title_y = None
    if fig is None:  # laid out by hand (constrained layout draws the figure twice when it is saved)
        fig = new_figure(FIGURE_SIZE, layout="none")
        width, height = FIGURE_SIZE
        left, right, top, bottom, between_rows, between_columns = LAYOUT
        grid = fig.add_gridspec(2, 3, height_ratios=[1, 1.2], left=left / width, right=1 - right / width,
                                top=1 - top / height, bottom=bottom / height,
                                hspace=between_rows / (0.5 * (height - top - bottom - between_rows)),
                                wspace=between_columns / ((width - left - right - 2 * between_columns) / 3))
        title_y = 1 - 0.08 / height
    else:
        grid = fig.add_gridspec(2, 3, height_ratios=[1, 1.2])
    top = fig.add_subplot(grid[0, :])
    t0 = rec.t[0]
    series = rec.recordings or ((rec.t, rec.omega),)
    shift, pos = [], 0.0  # several recordings: drawn one after another
    for r, (t_r, w_r) in enumerate(series):
        shift.append(pos - t_r[0])
        for k, name in enumerate("xyz"):
            top.plot(t_r + shift[r], w_r[:, k], lw=0.5, color=f"C{k}", label=rf"$\omega_{name}$" if r == 0 else None)
        if len(series) > 1:
            top.axvline(pos, color="0.3", lw=0.8)
            top.text(pos, 1.0, f" recording {r + 1}", transform=top.get_xaxis_transform(), fontsize=7, va="bottom")
        pos = t_r[-1] + shift[r] + 0.05 * (t_r[-1] - t_r[0])
    for r, (t_r, w_r) in enumerate(series):
        top.plot(t_r + shift[r], np.linalg.norm(w_r, axis=1), lw=0.6, color="0.15",
                 label=r"$|\omega|$" if r == 0 else None)
    for toss in rec.tosses:
        off = shift[toss.recording]
        top.axvspan(toss.start + off, toss.end + off, color="tab:green" if toss.status == "ok" else "0.6", alpha=0.25,
                    lw=0)
        if toss.reason:  # why it was left out, or that it is used in the joint fit only, in a few words
            top.text(0.5 * (toss.start + toss.end) + off, 0.98, skip_label(toss.reason), rotation=90, fontsize=6,
                     ha="center", va="top", color="0.25", transform=top.get_xaxis_transform())
    top.set_xlabel(f"t - t0 (s), from the first sample at t0 = {t0:.3g} s" if len(series) == 1 else
                   "time since each recording's first sample, the recordings one after another (s)")
    top.set_ylabel("angular velocity, sensor axes (rad/s)")
    top.set_title(f"{len(rec.tosses)} flights found, {rec.tosses_used} used (green), "
                  f"{len(rec.tosses) - rec.tosses_used} skipped (grey)", fontsize=9)
    legend_outside(top, fontsize=8)
    mid = fig.add_subplot(grid[1, :2])
    used = [toss for toss in rec.tosses if toss.status == "ok"]
    offset = 0.0
    for j, (toss, model) in enumerate(zip(used[:max_flights], rec.omega_models)):
        t_r, w_r = series[toss.recording]
        sel = (t_r >= toss.start) & (t_r <= toss.end)
        x = t_r[sel] - toss.start + offset
        for k in range(3):
            mid.plot(x, w_r[sel, k], ".", ms=1.5, color="0.45")
            mid.plot(x, model[:len(x), k], "-", lw=0.9, color=f"C{k}")
        mid.text(offset, 1.0, str(j + 1), transform=mid.get_xaxis_transform(), fontsize=7, va="bottom")
        offset = x[-1] + 0.15
    mid.set_xlabel("flights side by side (s within each)")
    mid.set_ylabel("omega (rad/s): samples dots, joint fit lines")
    tri = fig.add_subplot(grid[1, 2])
    fits = [toss.fit for toss in used if toss.fit is not None and not toss.reason]  # not those of the joint fit only
    if fits:
        r = np.array([f.ratios for f in fits])
        s = np.array([f.ratios_std for f in fits])
        tri.errorbar(r[:, 0], r[:, 1], xerr=s[:, 0], yerr=s[:, 1], fmt="o", ms=3, color="tab:green", alpha=0.7,
                     lw=0.8, label="each flight")
    p = rec.pooled
    tri.errorbar([p.ratios[0]], [p.ratios[1]], xerr=[p.ratios_std[0]], yerr=[p.ratios_std[1]], fmt="s", ms=5,
                 color="k", lw=1.5, label="pooled", zorder=5)
    lo_x, hi_x = tri.get_xlim()
    xs = np.linspace(max(0.0, lo_x), min(0.5, hi_x), 50)
    tri.plot(xs, 1 - xs, "--", color="0.3", lw=0.8, label="planar: I1 + I2 = I3")
    tri.set_xlim(lo_x, hi_x)
    tri.set_xlabel("I1/I3")
    tri.set_ylabel("I2/I3")
    tri.legend(fontsize=7, loc="best")
    chi = f", chi2/dof {rec.chi2_dof:.2g}" if np.isfinite(rec.chi2_dof) else ""
    fig.suptitle(f"pooled I1/I3 = {p.ratios[0]:.4f} \u00b1 {p.ratios_std[0]:.2g},  I2/I3 = {p.ratios[1]:.4f} "
                 f"\u00b1 {p.ratios_std[1]:.2g}  ({rec.tosses_used} flights{chi}; drag {p.drag})", fontsize=10,
                 **({} if title_y is None else {"y": title_y, "va": "top"}))
    return fig
