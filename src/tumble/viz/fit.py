"""The figure of a fitted tumble: the measured angular velocity against the fitted model.

Three panels (the sensor's x, y, z), the samples as dots and the model
(:attr:`tumble.analysis.fit.RotationFit.omega_model`, bias included) as a line, and below them
the residuals; the title gives the fitted ratios with their uncertainties.
"""

from __future__ import annotations

import numpy as np

from ._backend import legend_outside, new_figure

__all__ = ["figure_fit"]


def figure_fit(fit, omega_measured, *, fig=None):
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
    axes[3].set_xlabel(f"time since the first sample, t - {fit.t[0]:.3g} s (s)")
    legend_outside(axes[3], fontsize=8, markerscale=6)
    (x, y), (sx, sy) = fit.ratios, fit.ratios_std
    fig.suptitle(f"I1/I3 = {x:.5f} \u00b1 {sx:.1g},  I2/I3 = {y:.5f} \u00b1 {sy:.1g},  "
                 f"residual RMS {fit.residual_rms:.3g} rad/s ({fit.samples} samples)", fontsize=10)
    return fig
