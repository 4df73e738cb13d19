"""Maps over the triangle of inertia ratios, and the figure of a sweep.

- :func:`figure_stability_map`: the exact flip interval of a perturbed spin about the
  intermediate axis over ``(I1/I3, I2/I3)``, and which axis omega then circulates about
  (:func:`tumble.ensemble.stability_map`; Landau & Lifshitz sec. 37). Every body lies in the
  triangle ``I1 <= I2 <= I3``, ``I1 + I2 >= I3``: its lower-left edge is the triangle
  inequality (planar bodies), the diagonal the oblate symmetric bodies (``I1 = I2``: a disc), the
  top edge the prolate ones (``I2 = I3``: a rod).
- :func:`figure_sweep`: what a sweep's cases did (its bounded sample,
  :meth:`tumble.ensemble.SweepSummary.sample_columns`): the distribution of flip periods and the
  cases on the inertia-ratio plane.

Both draw on a given ``ax`` (``fig``) or a new figure and return the Figure
(:func:`tumble.viz.save_figure` writes it); legends sit outside the axes.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..ensemble import stability_map
from ._backend import figure_and_axes, legend_outside, new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["figure_stability_map", "figure_sweep"]

#: The edges of the triangle of inertia ratios: (label, x pair, y pair, line width).
_EDGES = (
    (r"$I_1 + I_2 = I_3$: planar bodies (triangle inequality)", (0.0, 0.5), (1.0, 0.5), 1.6),
    (r"$I_1 = I_2$: oblate symmetric", (0.5, 1.0), (0.5, 1.0), 0.8),
    (r"$I_2 = I_3$: prolate symmetric", (0.0, 1.0), (1.0, 1.0), 0.8),
)
_RATIO_LABELS = (r"$I_1 / I_3$ (dimensionless)", r"$I_2 / I_3$ (dimensionless)")


def _triangle(ax) -> None:
    """Draw the edges of the triangle of physical bodies, labelled, and set the labels."""
    for (label, xs, ys, lw), style in zip(_EDGES, ("-", "--", ":")):
        ax.plot(xs, ys, color="k", lw=lw, ls=style, label=label)
    ax.set_xlabel(_RATIO_LABELS[0])
    ax.set_ylabel(_RATIO_LABELS[1])


def figure_stability_map(spin: float = 10.0, perturbation: tuple[float, float] = (0.01, 0.01), *, ax: Axes | None = None,
                         resolution: int = 300, points: dict | None = None) -> Figure:
    """The flip interval and the circulation axis over the triangle of inertia ratios.

    Parameters
    ----------
    spin : float
        Spin about the intermediate axis, rad/s.
    perturbation : (float, float)
        Components along the minor and major axes, as fractions of ``spin``.
    ax : matplotlib Axes, optional
        Draw on these axes instead of a new figure (the colour bar goes below them).
    resolution : int
        Cells along ``I1/I3`` (:func:`tumble.ensemble.stability_map`).
    points : dict of str to (float, float), optional
        Bodies to mark, label -> ``(I1/I3, I2/I3)``.

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble import stability_map
    >>> from tumble.viz.maps import figure_stability_map
    >>> fig = figure_stability_map(10.0, (0.01, 0.01), resolution=40, points={"T-handle": (2 / 7, 5 / 7)})
    >>> ax, colorbar = fig.axes
    >>> ax.get_xlabel(), colorbar.get_xlabel(), [text.get_text() for text in ax.texts][-1]
    ('$I_1 / I_3$ (dimensionless)', 'flip interval (s)', 'T-handle')
    >>> m = stability_map(10.0, (0.01, 0.01), resolution=40)  # what is coloured: the exact flip interval, s
    >>> bool(np.array_equal(np.ma.filled(ax.collections[0].get_array(), np.nan), m.flip_interval, equal_nan=True))
    True
    >>> [text.get_text().replace("\\n", " ") for text in ax.texts][:2]  # either side of the separatrix
    ['circulates about the minor axis', 'circulates about the major axis']
    """
    from matplotlib.colors import LogNorm

    m = stability_map(spin, perturbation, resolution=resolution)
    if ax is None:  # "compressed": constrained layout that sizes the margins after the equal aspect (no label cut)
        fig = new_figure((8.8, 4.6), layout="compressed")
        ax = fig.add_subplot()
    fig = ax.figure
    values = np.ma.masked_invalid(m.flip_interval)
    mesh = ax.pcolormesh(m.x, m.y, values, shading="nearest", cmap="viridis", rasterized=True,
                         norm=LogNorm(vmin=float(values.min()), vmax=float(values.max())))
    fig.colorbar(mesh, ax=ax, label="flip interval (s)", shrink=0.6, location="bottom", aspect=40)
    X, Y = np.meshgrid(m.x, m.y)
    ax.contour(X, Y, m.separatrix_gap, levels=[0.0], colors="w", linewidths=1.2)
    ax.plot([], [], color="w", lw=1.2, label="separatrix ($L^2 = 2 E I_2$)")
    for axis, name in ((1, "minor"), (3, "major")):
        where = m.inside & (m.circulation == axis)
        if np.any(where):
            cx, cy = float(np.median(X[where])), float(np.median(Y[where]))
            ax.text(cx, cy, f"circulates about\nthe {name} axis", ha="center", va="center", fontsize=8, color="w")
    _triangle(ax)
    for label, (x, y) in (points or {}).items():
        ax.plot([x], [y], "r*", ms=9, zorder=5)
        ax.annotate(label, (x, y), xytext=(5, 4), textcoords="offset points", fontsize=8, color="r")
    ax.set_xlim(0.0, 1.0)
    ax.set_ylim(0.5, 1.005)  # the top edge in view
    ax.set_aspect("equal")
    p1, p3 = m.omega0[0] / m.omega0[1], m.omega0[2] / m.omega0[1]
    ax.set_title(f"Exact flip interval, spin {spin:g} rad/s about the intermediate axis\n"
                 f"perturbed by ({p1:g}, {p3:g}) of it along the minor and major axes", fontsize=9)
    legend_outside(ax, facecolor="0.85")
    return fig


def _column(columns: dict, name: str) -> np.ndarray | None:
    """The values of the column named ``name`` (without its unit), or None."""
    for key, values in columns.items():
        if key.split(" [", 1)[0] == name:
            return np.asarray(values, dtype=float)
    return None


def figure_sweep(columns: dict, *, fig: Figure | None = None, title: str | None = None,
                 cases: int | None = None) -> Figure:
    """What a sweep's cases did: their flip periods, and where they lie among the inertia ratios.

    Left: the histogram of the measured and the exact flip period (or, when no case flips, of
    the largest nutation angle). Right: the cases on the ``(I1/I3, I2/I3)`` plane, coloured by
    their exact flip period (or by their number of flips), with the triangle's edges in view.

    Parameters
    ----------
    columns : dict of str to array
        Columns of ``cases.csv`` (names with units), e.g. a sweep's bounded sample
        (:meth:`tumble.ensemble.SweepSummary.sample_columns`).
    fig : matplotlib Figure, optional
        An empty figure to draw the two panels on (a new one by default).
    title : str, optional
        The figure's title.
    cases : int, optional
        How many cases the sweep had, when ``columns`` hold a sample of them (said in the title).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import tumble
    >>> from tumble.ensemble import BodySampler, Dispersion, Ensemble, InitialRates, RunSettings, Sweep, compute_chunk
    >>> import numpy as np
    >>> from tumble.viz.maps import figure_sweep
    >>> box = tumble.Body((tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0)),))  # kg, m
    >>> spread = Ensemble(BodySampler(box, (Dispersion("moments", 0.02),)), InitialRates(omega=(0.01, 1.0, 0.01)), 6)
    >>> columns = compute_chunk(Sweep(spread, RunSettings(t_end=80.0, samples=800)), 0, 6)  # 6 cases, 3 flips each
    >>> fig = figure_sweep(columns, title="box, moments spread 2 %", cases=100)
    >>> fig.get_suptitle(), [text.get_text() for text in fig.axes[0].get_legend().get_texts()]
    ('box, moments spread 2 % (6 of 100 cases)', \
['measured (mean between flips) (s): 6 cases', 'exact (elliptic K) (s): 6 cases'])
    >>> ratios = np.column_stack([columns["I1 [kg m^2]"], columns["I2 [kg m^2]"]]) / columns["I3 [kg m^2]"][:, None]
    >>> bool(np.array_equal(fig.axes[1].collections[0].get_offsets(), ratios))  # each case at (I1/I3, I2/I3)
    True
    """
    fig = fig if fig is not None else new_figure((12.5, 4.4))
    left, right = fig.subplots(1, 2)
    I1, I2, I3 = (_column(columns, f"I{j}") for j in (1, 2, 3))
    measured, exact = _column(columns, "flip_period"), _column(columns, "flip_period_exact")
    shown = len(I1)
    finite = [v[np.isfinite(v)] for v in (measured, exact)]
    if any(v.size for v in finite):
        both = np.concatenate(finite)
        lo, hi = float(both.min()), float(both.max())
        wide = hi > 3 * lo  # a long tail (bodies near a symmetric one): logarithmic bins
        bins = (np.geomspace if wide else np.linspace)(lo, hi, 41) if hi > lo else 10
        if wide:
            from matplotlib.ticker import LogLocator, NullFormatter, ScalarFormatter

            left.set_xscale("log")
            left.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
            left.xaxis.set_major_formatter(ScalarFormatter())
            left.xaxis.set_minor_formatter(NullFormatter())  # no crowded 2x10^0, 3x10^0 labels
        # the exact periods as a step line, the measured ones dashed on top: they nearly coincide
        for values, label, color, style in zip(finite, ("measured (mean between flips)", "exact (elliptic K)"),
                                               ("tab:blue", "tab:orange"), ("--", "-")):
            if values.size:
                left.hist(values, bins=bins, histtype="step", lw=1.4, ls=style, color=color,
                          label=f"{label} (s): {values.size} cases", zorder=3 if style == "--" else 2)
        left.set_xlabel("flip period (s)")
        left.legend(fontsize=7, loc="lower center", bbox_to_anchor=(0.5, 1.01), borderaxespad=0.0)
    else:
        nutation = _column(columns, "max_nutation")
        left.hist(nutation[np.isfinite(nutation)], bins=40, color="tab:blue")
        left.set_xlabel("largest nutation angle (rad): no case flips")
    left.set_ylabel("cases")
    x, y = I1 / I3, I2 / I3
    colour = exact if np.any(np.isfinite(exact)) else _column(columns, "flips")
    what = "exact flip period (s)" if colour is exact else "flips"
    dots = right.scatter(x, y, c=colour, s=6, cmap="viridis", rasterized=True, zorder=3)  # over the edges
    fig.colorbar(dots, ax=right, label=what, location="bottom", aspect=40)  # the legend goes right
    pad = max(0.01, 0.1 * max(np.ptp(x), np.ptp(y)))
    _triangle(right)
    right.set_xlim(x.min() - pad, x.max() + pad)
    right.set_ylim(y.min() - pad, min(y.max() + pad, 1.0 + pad))
    legend_outside(right, fontsize=6)
    right.set_title("cases among the inertia ratios", fontsize=9)
    sampled = f" ({shown} of {cases} cases)" if cases is not None and cases > shown else f" ({shown} cases)"
    fig.suptitle((title or "sweep") + sampled, fontsize=10)
    return fig
