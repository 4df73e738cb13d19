"""The design-review figure of a detumble Monte Carlo
(:func:`tumble.ensemble.detumble.detumble_monte_carlo`).

Three panels: the histogram of the detumble times; their empirical distribution function over
*all* cases (so it levels off at the fraction detumbled), with the median, the 95th and the
99th percentiles marked (:meth:`~tumble.ensemble.detumble.DetumbleMonteCarlo.percentile`: a
percentile that falls among the cases never detumbled is not drawn, and the panel says so); and,
when the Monte Carlo kept a rate history, the envelopes of ``|omega|`` over time: the median and
the 5-95 % and 1-99 % bands over the cases, the largest rate and the threshold. Times in minutes,
rates in deg/s.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ._backend import new_figure, note_only

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..ensemble.detumble import DetumbleMonteCarlo

__all__ = ["figure_detumble_mc"]

#: The percentiles marked on the distribution, and their line styles.
MARKS = ((50.0, "--"), (95.0, "-."), (99.0, ":"))


def _model(mc: DetumbleMonteCarlo) -> str:
    """One line: the cases and what the model included."""
    parts = [f"{len(mc.times)} cases", "gravity gradient" if mc.gravity_gradient else "no gravity gradient"]
    s = mc.sensors
    if s is not None and (s.gyro_noise > 0.0 or s.magnetometer_noise > 0.0):
        parts.append(f"gyro noise {math.degrees(s.gyro_noise):.2g} deg/s, magnetometer {s.magnetometer_noise * 1e9:.3g} nT")
    else:
        parts.append("ideal sensors")
    if mc.cases.gyro_bias is not None and np.any(mc.cases.gyro_bias):
        parts.append(f"gyro bias {math.degrees(float(np.std(mc.cases.gyro_bias))):.2g} deg/s (std over the cases)")
    return ", ".join(parts)


def figure_detumble_mc(mc: DetumbleMonteCarlo, *, title: str | None = None, fig: Figure | None = None) -> Figure:
    """Histogram, distribution with the 50/95/99 % marks, and rate envelopes of a detumble Monte Carlo.

    Parameters
    ----------
    mc : DetumbleMonteCarlo
        The Monte Carlo (with ``history`` for the third panel).
    title : str, optional
        The figure's title (default: the cases and the model).
    fig : matplotlib Figure, optional
        An empty figure to draw the panels on (a new one by default).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from tumble.ensemble.detumble import DetumbleMonteCarlo, detumble_cases
    >>> import numpy as np
    >>> from tumble.viz.montecarlo import figure_detumble_mc
    >>> cases = detumble_cases(5, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3)
    >>> t = np.array([0.0, 60.0, 120.0])
    >>> rates = np.array([[0.2, 0.05, 0.001], [0.3, 0.1, 0.002], [0.1, 0.02, 0.001], [0.25, 0.2, 0.1],
    ...                   [0.15, 0.01, 0.003]])
    >>> mc = DetumbleMonteCarlo(times=np.array([60.0, 120.0, 60.0, np.nan, 120.0]), cases=cases, threshold=0.01,
    ...                         t_end=120.0, seconds=1.0, history_t=t, history=rates)
    >>> fig = figure_detumble_mc(mc)
    >>> [ax.get_xlabel() for ax in fig.axes]
    ['detumble time (min)', 'detumble time (min)', 'time (min)']
    >>> cdf = fig.axes[1].lines[0]   # the fraction detumbled by each time, over all five cases
    >>> cdf.get_xdata().tolist(), cdf.get_ydata().tolist()   # a step of 1/5 at each time, to t_end
    ([0.0, 1.0, 1.0, 2.0, 2.0, 2.0], [0.0, 0.2, 0.4, 0.6, 0.8, 0.8])
    >>> median = fig.axes[2].lines[0]   # |omega|'s median over the cases, deg/s
    >>> bool(np.allclose(median.get_ydata(), np.degrees(np.median(rates, axis=0))))
    True
    >>> print(fig.axes[1].texts[-1].get_text())   # one case in five never detumbled: the 95th percentile is it
    not detumbled: 1 of 5 (20.00 %)
    by 2 min
    95 %, 99 % percentile: among them
    >>> [text.get_text() for text in fig.axes[0].get_legend().get_texts()]
    ['median: 2 min']
    """
    fig = fig if fig is not None else new_figure((13.0, 4.0))
    ax_hist, ax_cdf, ax_rate = fig.subplots(1, 3)
    n = len(mc.times)
    done = np.sort(mc.times[np.isfinite(mc.times)]) / 60.0
    never = n - len(done)
    if len(done):
        ax_hist.hist(done, bins=min(50, max(5, int(math.sqrt(len(done))))), color="tab:blue", alpha=0.85)
    ax_hist.set_xlabel("detumble time (min)")
    ax_hist.set_ylabel("cases")
    ax_hist.set_title("detumble time")
    # the empirical distribution over all n cases: a step up by 1/n at each detumble time
    x = np.concatenate([[0.0], done, [mc.t_end / 60.0]])
    y = np.concatenate([[0.0], np.arange(1, len(done) + 1) / n, [len(done) / n]])
    ax_cdf.step(x, y, where="post", color="tab:blue")
    missing = []
    for p, style in MARKS:
        value = mc.percentile(p)
        if not math.isfinite(value):
            missing.append(f"{p:g} %")
            continue
        label = f"{'median' if p == 50.0 else f'{p:g} %'}: {value / 60.0:.0f} min"
        ax_hist.axvline(value / 60.0, color="k", ls=style, lw=1.0, label=label)
        ax_cdf.axvline(value / 60.0, color="k", ls=style, lw=1.0)
    if len(done) or not missing:
        ax_hist.legend(fontsize=7, loc="upper left")
    note = f"not detumbled: {never} of {n} ({100.0 * never / n:.2f} %)\nby {mc.t_end / 60.0:.0f} min"
    if missing:
        note += f"\n{', '.join(missing)} percentile: among them"
    ax_cdf.text(0.03, 0.97, note, transform=ax_cdf.transAxes, ha="left", va="top", fontsize=8)
    ax_cdf.set_xlabel("detumble time (min)")
    ax_cdf.set_ylabel("fraction detumbled")
    ax_cdf.set_ylim(0.0, 1.02)
    ax_cdf.set_title(f"below {math.degrees(mc.threshold):.2g} deg/s for good")
    if mc.history is None or mc.history_t is None:
        note_only(ax_rate, "no rate history kept (detumble_monte_carlo(..., history=200))", "|omega| over the cases")
    else:
        t = mc.history_t / 60.0
        bands = np.degrees(mc.rate_percentiles([50.0, 1.0, 99.0, 5.0, 95.0]))
        ax_rate.plot(t, bands[0], color="tab:blue", lw=1.5, label="median")
        ax_rate.fill_between(t, bands[1], bands[2], color="tab:blue", alpha=0.15, lw=0, label="1-99 %")
        ax_rate.fill_between(t, bands[3], bands[4], color="tab:blue", alpha=0.3, lw=0, label="5-95 %")
        ax_rate.plot(t, np.degrees(mc.history.max(axis=0)), color="tab:red", lw=0.8, label="largest")
        ax_rate.axhline(math.degrees(mc.threshold), color="k", ls="--", lw=1.0, label="threshold")
        ax_rate.set_yscale("log")
        ax_rate.set_xlabel("time (min)")
        ax_rate.set_ylabel("|omega| (deg/s)")
        ax_rate.set_title("|omega| over the cases")
        ax_rate.legend(fontsize=7, loc="upper right")
    fig.suptitle(title if title is not None else f"B-dot detumble Monte Carlo: {_model(mc)}", fontsize=10)
    return fig
