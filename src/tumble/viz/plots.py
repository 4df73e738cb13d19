"""Static figures: omega(t) per case and the combined figure like the seed's Figure 1.

matplotlib is imported here only (never by the physics) and with the non-interactive Agg
backend, so figures are written to files on machines without a screen.
"""

from __future__ import annotations

import numpy as np

from ..dynamics import Trajectory
from ..mass import AXIS_ROLES
from ._backend import pyplot, save_figure

__all__ = ["figure_drift", "figure_omega", "figure_omega_grid", "plot_omega"]

COLORS = ("tab:blue", "tab:orange", "tab:green")



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
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 3.6), layout="constrained")
    plot_omega(traj, ax, title)
    save_figure(fig, path, dpi=110)


def figure_omega_grid(cases: list[tuple[str, Trajectory]], path, ncols: int = 3, suptitle: str | None = None) -> None:
    """Several runs side by side (the seed's Figure 1, for every case of the study)."""
    plt = pyplot()
    nrows = int(np.ceil(len(cases) / ncols))
    fig, axes = plt.subplots(nrows, ncols, figsize=(5.0 * ncols, 3.2 * nrows), layout="constrained", squeeze=False)
    for ax, (title, traj) in zip(axes.flat, cases):
        plot_omega(traj, ax, title)
    for ax in list(axes.flat)[len(cases):]:
        ax.set_visible(False)
    if suptitle:
        fig.suptitle(suptitle)
    save_figure(fig, path, dpi=100)


def figure_drift(traj: Trajectory, path, title: str | None = None) -> None:
    """Relative error of energy, |L| and L_world against time, on a log scale.

    ``|E - E0| / E0``, ``||L| - |L0|| / |L0|`` and ``|L_world - L_world(0)| / |L0|``: zero
    for the exact motion, round-off (~1e-16) for the best methods. Zeros are drawn at 1e-17.
    """
    plt = pyplot()
    E, Ln, Lw = traj.energy, traj.angular_momentum_norm, traj.angular_momentum_world
    ref_E, ref_L = (E[0] if E[0] > 0 else 1.0), (Ln[0] if Ln[0] > 0 else 1.0)
    series = {
        "energy": np.abs(E - E[0]) / ref_E,
        "|L|": np.abs(Ln - Ln[0]) / ref_L,
        r"$L_{world}$": np.linalg.norm(Lw - Lw[0], axis=1) / ref_L,
    }
    fig, ax = plt.subplots(figsize=(7.5, 3.6), layout="constrained")
    for (label, values), color in zip(series.items(), COLORS):
        ax.semilogy(traj.t, np.maximum(values, 1e-17), color=color, lw=1.1, label=label)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("relative drift")
    ax.set_xlim(traj.t[0], traj.t[-1])
    note = "" if traj.torque_free else " (a torque acts: these change physically)"
    ax.set_title(title or f"{traj.body_name}: drift of the invariants, {traj.method}{note}", fontsize=10)
    ax.legend(fontsize=8)
    save_figure(fig, path, dpi=110)
