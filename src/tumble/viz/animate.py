"""Animations of a tumbling body: in the ground frame and in the body frame.

Both are built from the scene description (:mod:`tumble.viz.scene`) and update their artists
in place (``set_data_3d``) instead of redrawing. GIF through Pillow (a matplotlib dependency);
MP4 when matplotlib finds an ffmpeg.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..dynamics import Trajectory
from ..mass import Body
from ..io.atomic import atomic_path
from .scene import arrow_scale, body_lines, body_size, frame_indices
from ._backend import pyplot

__all__ = ["animate_body_frame", "animate_ground_frame", "writer_for"]



def writer_for(path: Path, fps: int):
    """A matplotlib writer for the suffix of ``path`` (``.gif`` or ``.mp4``)."""
    from matplotlib import animation

    if path.suffix == ".mp4":
        if not animation.writers.is_available("ffmpeg"):
            raise ValueError(f"{path}: writing MP4 needs ffmpeg; write a .gif instead")
        return animation.FFMpegWriter(fps=fps)
    if path.suffix == ".gif":
        return animation.PillowWriter(fps=fps)
    raise ValueError(f"{path}: animations are written as .gif or .mp4")


def _setup_axes(ax, size: float, title: str) -> None:
    ax.set_xlim(-size, size)
    ax.set_ylim(-size, size)
    ax.set_zlim(-size, size)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.set_title(title, fontsize=9)


def animate_ground_frame(body: Body, traj: Trajectory, path, *, max_frames: int = 100, fps: int = 20,
                         title: str | None = None, dpi: int = 72) -> Path:
    """The body tumbling in the ground (world) frame with its omega and L arrows.

    L is fixed in space for a torque-free run; omega wanders. Arrow lengths are scaled to the
    body's size (each vector by its own largest magnitude over the run).
    """
    plt = pyplot()
    path = Path(path)
    lines = body_lines(body)
    size = 1.25 * body_size(body)
    rot = traj.design_attitude()  # design frame -> world
    w, L = traj.omega_world, traj.angular_momentum_world
    sw, sL = arrow_scale(w, size), arrow_scale(L, size)

    fig = plt.figure(figsize=(4.8, 4.8))
    ax = fig.add_subplot(projection="3d")
    _setup_axes(ax, size, title or f"{traj.body_name}: ground frame")
    artists = [ax.plot([], [], [], color="0.2", lw=1.6, ls="--" if removed else "-", marker="o" if len(p) == 1 else None)[0]
               for p, removed in lines]
    w_line, = ax.plot([], [], [], color="tab:red", lw=2.2, label=r"$\omega$")
    L_line, = ax.plot([], [], [], color="tab:blue", lw=2.2, label="L")
    stamp = ax.text2D(0.02, 0.95, "", transform=ax.transAxes, fontsize=8)
    ax.legend(loc="upper right", fontsize=8)

    def draw(k: int):
        R = rot[k].as_matrix()
        for artist, (pts, _) in zip(artists, lines):
            q = pts @ R.T
            artist.set_data_3d(q[:, 0], q[:, 1], q[:, 2])
        for line, vec, s in ((w_line, w[k], sw), (L_line, L[k], sL)):
            tip = vec * s
            line.set_data_3d([0, tip[0]], [0, tip[1]], [0, tip[2]])
        stamp.set_text(f"t = {traj.t[k]:.2f} s")

    _save(fig, draw, frame_indices(len(traj), max_frames), path, fps, dpi)
    return path


def animate_body_frame(body: Body, traj: Trajectory, path, *, max_frames: int = 100, fps: int = 20,
                       title: str | None = None, dpi: int = 72) -> Path:
    """omega and L seen from the body (design axes), with the path of omega's tip (polhode)."""
    plt = pyplot()
    path = Path(path)
    lines = body_lines(body)
    size = 1.25 * body_size(body)
    A = traj.principal_axes  # principal -> design
    w, L = traj.omega @ A.T, traj.angular_momentum @ A.T
    sw, sL = arrow_scale(w, size), arrow_scale(L, size)

    fig = plt.figure(figsize=(4.8, 4.8))
    ax = fig.add_subplot(projection="3d")
    _setup_axes(ax, size, title or f"{traj.body_name}: body frame")
    for pts, removed in lines:
        ax.plot(pts[:, 0], pts[:, 1], pts[:, 2], color="0.55", lw=0.9, ls="--" if removed else "-",
                marker="o" if len(pts) == 1 else None)
    trace, = ax.plot([], [], [], color="tab:red", lw=0.8, alpha=0.6)
    w_line, = ax.plot([], [], [], color="tab:red", lw=2.2, label=r"$\omega$")
    L_line, = ax.plot([], [], [], color="tab:blue", lw=2.2, label="L")
    stamp = ax.text2D(0.02, 0.95, "", transform=ax.transAxes, fontsize=8)
    ax.legend(loc="upper right", fontsize=8)
    tips = w * sw

    def draw(k: int):
        trace.set_data_3d(tips[: k + 1, 0], tips[: k + 1, 1], tips[: k + 1, 2])
        for line, tip in ((w_line, tips[k]), (L_line, L[k] * sL)):
            line.set_data_3d([0, tip[0]], [0, tip[1]], [0, tip[2]])
        stamp.set_text(f"t = {traj.t[k]:.2f} s")

    _save(fig, draw, frame_indices(len(traj), max_frames), path, fps, dpi)
    return path


def _save(fig, draw, frames, path: Path, fps: int, dpi: int) -> None:
    """Render every frame into a temporary file, then rename it into place."""
    plt = pyplot()
    writer = writer_for(path, fps)
    try:
        with atomic_path(path) as tmp:
            with writer.saving(fig, str(tmp), dpi):
                for k in frames:
                    draw(int(k))
                    writer.grab_frame()
    finally:
        plt.close(fig)
