"""The figure of ``tumble tensor`` (tensor.png): the throws against the fitted model, and the
object's principal moments throw by throw with the pooled value.

Top: the used throws side by side from their release, the gyroscope's samples as dots and the
fitted gyrostat model (bias included) as lines. Bottom, one panel a principal moment (ascending,
``I1 <= I2 <= I3``): each throw's own estimate of the object's moment with its standard
uncertainty (a skipped throw's place marked), and the pooled value (:attr:`tumble.analysis.tensor.TensorFit.object`) as a line
with its 95 % interval (+- 1.96 standard uncertainties, statistical and systematic parts
together) shaded.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ._backend import new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..analysis.tensor import TensorFit

__all__ = ["figure_tensor"]

#: The factor of a 95 % interval of a normal distribution, +- 1.96 standard uncertainties.
Z95 = 1.959963984540054


def figure_tensor(fit: TensorFit, *, fig: Figure | None = None, max_throws: int = 12) -> Figure:
    """The throws and the object's principal moments (module docstring).

    Parameters
    ----------
    fit : TensorFit
        :func:`tumble.analysis.tensor.fit_tensor`'s result.
    fig : matplotlib Figure, optional
        An empty figure to draw the four panels on (a new one by default).
    max_throws : int
        Most throws drawn in the top panel (all are in the bottom ones).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import TensorFit, ThrowFit
    >>> from tumble.analysis.tensor.estimate import mass_estimate
    >>> from tumble.viz.tensor import figure_tensor
    >>> def estimate(moments, std):   # a diagonal tensor, kg m^2, and its entries' std
    ...     cov = np.diag(np.r_[np.square(std), np.square(std)])
    ...     return mass_estimate(0.5, np.diag(moments), cov, [0.0, 0.0, 0.02], np.eye(3) * 1e-8)
    >>> t = np.linspace(0.0, 0.5, 200)   # s
    >>> w = np.stack([np.cos(9 * t), 8 + 0 * t, np.sin(9 * t)], axis=1)   # rad/s
    >>> throws = tuple(ThrowFit(f"o{k}.csv", "used", "", estimate(m, [2e-6] * 3), None, t, w + 0.01, w, 0.0, 0.5, 0.01)
    ...                for k, m in enumerate([[1.0e-3, 2.0e-3, 2.9e-3], [1.02e-3, 1.98e-3, 2.91e-3]]))
    >>> pooled = estimate([1.01e-3, 1.99e-3, 2.905e-3], [1.5e-6] * 3)
    >>> fig = figure_tensor(TensorFit(pooled, pooled, throws, True, 0.8))
    >>> rates, *moments = fig.axes
    >>> len(rates.lines), [ax.get_ylabel() for ax in moments]   # 2 throws x 3 axes, samples and model
    (12, ['I1 (kg m^2)', 'I2 (kg m^2)', 'I3 (kg m^2)'])
    >>> [float(ax.lines[-1].get_ydata()[0]) for ax in moments] == pooled.principal_moments.tolist()   # the pooled line
    True
    """
    fig = fig if fig is not None else new_figure((12, 8))
    grid = fig.add_gridspec(2, 3, height_ratios=[1.1, 1])
    top = fig.add_subplot(grid[0, :])
    used = [(k, th) for k, th in enumerate(fit.throws) if th.status == "used"]
    offset, gap = 0.0, 0.0
    for k, th in used[:max_throws]:
        t = np.asarray(th.t, float)
        if t.size == 0:
            continue
        start = th.t_release if np.isfinite(th.t_release) else t[0]
        x = t - start + offset
        gap = gap or 0.08 * (x[-1] - x[0])
        every = max(1, x.size // 40)  # 4 kHz of samples hid under the line: some 40 a throw, open, drawn over it
        for j in range(3):
            top.plot(x, th.omega_model[:, j], "-", lw=0.9, color=f"C{j}",
                     label=rf"fit $\omega_{'xyz'[j]}$" if offset == 0.0 else None)
            top.plot(x[::every], th.omega_measured[::every, j], "o", ms=2.6, mfc="white", mec=f"C{j}", mew=0.7,
                     zorder=3, label=f"samples (1 in {every})" if offset == 0.0 and j == 2 else None)
        top.text(x[0], 0.02, f"throw {k + 1}", transform=top.get_xaxis_transform(), fontsize=7, va="bottom")
        offset = x[-1] + gap
    skipped = [f"{k + 1} ({th.reason})" for k, th in enumerate(fit.throws) if th.status != "used"]
    shown = f"the first {max_throws} of {len(used)}" if len(used) > max_throws else f"{len(used)}"
    title = f"{shown} used throw{'s' if len(used) != 1 else ''} from release, side by side: samples (circles), fit (lines)"
    if skipped:
        text = "; ".join(skipped)
        title += f"\nskipped: {text if len(text) < 110 else text[:107] + '...'}"
    top.set_title(title, fontsize=9)
    top.set_xlabel("time since each throw's release, the throws one after another (s)")
    top.set_ylabel("angular velocity, sensor axes (rad/s)")
    if used:
        top.legend(fontsize=7, loc="upper right")
    obj = fit.object
    number = np.array([k + 1 for k, th in used if th.object is not None])
    each = np.array([th.object.principal_moments for _, th in used if th.object is not None]).reshape(-1, 3)
    each_std = np.array([th.object.principal_moments_std for _, th in used if th.object is not None]).reshape(-1, 3)
    for j in range(3):
        ax = fig.add_subplot(grid[1, j])
        if number.size:
            ax.errorbar(number, each[:, j], yerr=each_std[:, j], fmt="o", ms=3.5, lw=0.9, color=f"C{j}",
                        label="each throw +- 1 std")
        for k, th in enumerate(fit.throws):
            if th.status != "used":  # a skipped throw's place, marked (its reason is in the title above)
                ax.text(k + 1, 0.5, "skipped", rotation=90, ha="center", va="center", fontsize=7, color="0.5",
                        transform=ax.get_xaxis_transform())
        value, std = float(obj.principal_moments[j]), float(obj.principal_moments_std[j])
        ax.axhspan(value - Z95 * std, value + Z95 * std, color="0.3", alpha=0.15, lw=0, label="pooled 95 % interval")
        ax.axhline(value, color="k", lw=1.2, label="pooled")
        ax.set_xlabel("throw")
        ax.set_ylabel(f"I{j + 1} (kg m^2)")
        ax.set_title(f"I{j + 1} = {value:.5g} \u00b1 {std:.2g} kg m^2", fontsize=9)
        ax.set_xlim(0.4, max(len(fit.throws), 1) + 0.6)
        ax.xaxis.get_major_locator().set_params(integer=True)
        ax.ticklabel_format(axis="y", style="sci", scilimits=(-2, 3))
        if j == 0:
            ax.legend(fontsize=7, loc="best")
    chi = f", chi2/dof {fit.chi2_dof:.2g}" if np.isfinite(fit.chi2_dof) else ""
    com = ", ".join(f"{1e3 * c:.3g}" for c in obj.center_of_mass)
    fig.suptitle(f"object {obj.mass:.4g} kg: principal moments about its centre of mass ({com}) mm, sensor frame "
                 f"({len(used)} of {len(fit.throws)} throws{chi}{'' if fit.adequate else '; NOT ADEQUATE'})",
                 fontsize=10)
    return fig
