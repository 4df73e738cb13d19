"""Static figures: omega(t) per case and the combined figure like the seed's Figure 1.

matplotlib is imported here only (never by the physics) and with the non-interactive Agg
backend, so figures are written to files on machines without a screen.
"""

from __future__ import annotations

import numpy as np

from ..dynamics import Trajectory
from ..mass import AXIS_ROLES

__all__ = ["figure_omega", "figure_omega_grid", "plot_omega"]

COLORS = ("tab:blue", "tab:orange", "tab:green")


def _plt():
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def plot_omega(traj: Trajectory, ax, title: str | None = None) -> None:
    """Draw omega_1, omega_2, omega_3 (principal frame, rad/s) against t on ``ax``."""
    for j in range(3):
        ax.plot(traj.t, traj.omega[:, j], color=COLORS[j], lw=1.2,
                label=rf"$\omega_{j + 1}$ ({AXIS_ROLES[j]}, $I_{j + 1}$ = {traj.moments[j]:.4g})")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("t (s)")
    ax.set_ylabel(r"$\omega$ (rad/s), principal frame")
    ax.set_xlim(traj.t[0], traj.t[-1])
    if title:
        ax.set_title(title, fontsize=10)
    ax.legend(fontsize=7, loc="best", framealpha=0.85)


def figure_omega(traj: Trajectory, path, title: str | None = None) -> None:
    """omega(t) of one run, written to ``path`` (PNG or SVG by its suffix)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.5, 3.6), layout="constrained")
    plot_omega(traj, ax, title)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def figure_omega_grid(cases: list[tuple[str, Trajectory]], path, ncols: int = 3, suptitle: str | None = None) -> None:
    """Several runs side by side (the seed's Figure 1, for every case of the study)."""
    plt = _plt()
    nrows = int(np.ceil(len(cases) / ncols))
    fig, axes = plt.subplots(nrows, ncols, figsize=(5.0 * ncols, 3.2 * nrows), layout="constrained", squeeze=False)
    for ax, (title, traj) in zip(axes.flat, cases):
        plot_omega(traj, ax, title)
    for ax in list(axes.flat)[len(cases):]:
        ax.set_visible(False)
    if suptitle:
        fig.suptitle(suptitle)
    fig.savefig(path, dpi=100)
    plt.close(fig)
