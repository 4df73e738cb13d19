"""Animations of a tumbling body: in the ground frame and in the body frame, as MP4 or GIF.

Both are built from the scene description (:mod:`tumble.viz.scene`) and update their artists
in place (``set_data_3d``) instead of redrawing. MP4 goes through matplotlib's ``FFMpegWriter``
when an ffmpeg binary is found (:func:`ffmpeg_path`: on ``PATH``, else the one the optional
``imageio-ffmpeg`` package ships, ``pip install tumble[video]``); GIF through Pillow (a
matplotlib dependency). Asked for an MP4 without ffmpeg, they write the GIF instead and say so
(:func:`animation_path`).
"""

from __future__ import annotations

import os
import shutil
import warnings
from pathlib import Path
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from ..dynamics import Trajectory
from ..io.atomic import atomic_path
from ..mass import Body
from ._backend import new_figure
from .scene import arrow_scale, body_lines, body_size, check_body_and_run, frame_indices, frame_turn

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["ANIMATION_SUFFIXES", "SMOOTH_TURN", "animate_body_frame", "animate_ground_frame", "animation_path", "ffmpeg_path",
           "scene_axes", "writer_for"]

#: The formats the animations are written in, by suffix.
ANIMATION_SUFFIXES = (".mp4", ".gif")
#: The most an animated body turns between two frames, rad (30 deg), without a warning: beyond it the eye no
#: longer follows it as one motion, though below :data:`~tumble.viz.scene.MAX_FRAME_TURN` it is not yet aliased
#: (the demo's 100 frames over 20 s at 10 rad/s turned it up to 160 deg a frame).
SMOOTH_TURN = np.pi / 6


def ffmpeg_path() -> str | None:
    """The ffmpeg binary MP4s are written with: ``ffmpeg`` on ``PATH``, else imageio-ffmpeg's, else None.

    Examples
    --------
    >>> import os
    >>> from tumble.viz.animate import ffmpeg_path
    >>> found = ffmpeg_path()
    >>> found is None or (os.path.isfile(found) and os.access(found, os.X_OK))  # an executable, if any
    True
    """
    found = shutil.which("ffmpeg")
    if found:
        return found
    try:
        import imageio_ffmpeg
    except ImportError:
        return None
    try:
        return imageio_ffmpeg.get_ffmpeg_exe()
    except RuntimeError:  # the package without its binary
        return None


def animation_path(path: str | os.PathLike[str]) -> tuple[Path, str | None]:
    """Where an animation asked for at ``path`` is written, and a one-line note if not there.

    ``.gif`` and ``.mp4`` with ffmpeg available are kept; ``.mp4`` without ffmpeg becomes the
    ``.gif`` of the same name, with a note saying why. Any other suffix is a ``ValueError``.

    Examples
    --------
    >>> from tumble.viz.animate import animation_path, ffmpeg_path
    >>> path, note = animation_path("out/flip.gif")
    >>> path.as_posix(), note
    ('out/flip.gif', None)
    >>> path, note = animation_path("out/flip.mp4")
    >>> path.suffix == (".gif" if ffmpeg_path() is None else ".mp4"), (note is None) == (ffmpeg_path() is not None)
    (True, True)
    >>> animation_path("flip.avi")
    Traceback (most recent call last):
    ...
    ValueError: flip.avi: animations are written as .mp4 or .gif, not '.avi'
    """
    path = Path(path)
    if path.suffix not in ANIMATION_SUFFIXES:
        raise ValueError(f"{path}: animations are written as .mp4 or .gif, not {path.suffix or 'no suffix'!r}")
    if path.suffix == ".mp4" and ffmpeg_path() is None:
        gif = path.with_suffix(".gif")
        return gif, "no ffmpeg found (install tumble[video] or put ffmpeg on PATH): GIF written instead of MP4"
    return path, None


def writer_for(path: Path, fps: int) -> Any:
    """A matplotlib writer for the suffix of ``path`` (``.gif``, or ``.mp4`` with ffmpeg found).

    ``fps``: frames per second of the file written.

    Examples
    --------
    >>> from pathlib import Path
    >>> from tumble.viz.animate import writer_for
    >>> writer = writer_for(Path("flip.gif"), fps=20)
    >>> type(writer).__name__, writer.fps
    ('PillowWriter', 20)
    >>> type(writer_for(Path("flip.mp4"), 20)).__name__  # doctest: +SKIP
    'FFMpegWriter'
    >>> writer_for(Path("flip.png"), 20)
    Traceback (most recent call last):
    ...
    ValueError: flip.png: animations are written as .mp4 or .gif
    """
    from matplotlib import animation

    path = Path(path)
    if path.suffix == ".mp4":
        if ffmpeg_path() is None:
            raise ValueError(f"{path}: writing MP4 needs ffmpeg (tumble[video]); write a .gif instead")
        return animation.FFMpegWriter(fps=fps, codec="h264", extra_args=["-pix_fmt", "yuv420p"])
    if path.suffix == ".gif":
        return animation.PillowWriter(fps=fps)
    raise ValueError(f"{path}: animations are written as .mp4 or .gif")


def scene_axes(size: float, title: str, figsize: tuple[float, float] = (5.4, 5.4)) -> tuple[Figure, Axes]:
    """A new figure with one 3D axes of half-width ``size`` (m), labelled for a small frame.

    At most three ticks per axis and 8-point labels keep the tick labels apart at GIF sizes.
    ``figsize`` in inches.

    Examples
    --------
    >>> from tumble.viz.animate import scene_axes
    >>> fig, ax = scene_axes(0.5, "T-handle")
    >>> ax.name, ax.get_title(), ax.get_xlim() == ax.get_zlim() == (-0.5, 0.5), ax.get_zlabel()
    ('3d', 'T-handle', True, 'z (m)')
    >>> fig.axes == [ax], fig.get_size_inches().tolist()
    (True, [5.4, 5.4])
    """
    from matplotlib.ticker import MaxNLocator

    fig = new_figure(figsize)
    ax = fig.add_subplot(projection="3d")
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(nbins=2, symmetric=True))
    for axis in "xyz":
        getattr(ax, f"set_{axis}lim")(-size, size)
        getattr(ax, f"set_{axis}label")(f"{axis} (m)", fontsize=9, labelpad=2)
    ax.tick_params(labelsize=8, pad=0)
    ax.set_box_aspect((1, 1, 1))
    ax.set_title(title, fontsize=10)
    return fig, ax


def _legend(ax) -> None:
    ax.legend(loc="upper right", fontsize=8, bbox_to_anchor=(1.0, 1.0))


def animate_ground_frame(body: Body, traj: Trajectory, path: str | os.PathLike[str], *, max_frames: int = 100, fps: int = 20,
                         title: str | None = None, dpi: int = 90) -> Path:
    """The body tumbling in the ground (world) frame with its omega and L arrows; returns the file written.

    L is fixed in space for a torque-free run; omega wanders. Arrow lengths are scaled to the
    body's size (each vector by its own largest magnitude over the run). ``path`` ends in
    ``.mp4`` or ``.gif``; an MP4 without ffmpeg is written as the GIF of the same name
    (:func:`animation_path`), whose path is returned.

    Examples
    --------
    >>> import tempfile
    >>> import tumble
    >>> from PIL import Image
    >>> from pathlib import Path
    >>> from tumble.viz.animate import animate_ground_frame
    >>> body = tumble.t_handle()
    >>> run = tumble.simulate(body, [0.1, 10.0, 0.1], t_end=0.1, samples=101)   # 0.5 rad of spin a frame
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     gif = animate_ground_frame(body, run, Path(folder) / "flip.gif", max_frames=3, dpi=20)
    ...     with Image.open(gif) as image:
    ...         gif.name, image.format, image.n_frames, image.size  # 3 of the 101 samples; 5.4 in at 20 dpi
    ('flip.gif', 'GIF', 3, (108, 108))
    >>> with tempfile.TemporaryDirectory() as folder:  # doctest: +SKIP
    ...     animate_ground_frame(body, run, Path(folder) / "flip.mp4").suffix  # through ffmpeg: slower
    '.mp4'
    """
    path, frames = _prepare(body, traj, path, max_frames, fps, dpi)
    lines = body_lines(body)
    size = 1.25 * body_size(body)
    rot = traj.design_attitude()  # design frame -> world
    w, L = traj.omega_world, traj.angular_momentum_world
    sw, sL = arrow_scale(w, size), arrow_scale(L, size)

    fig, ax = scene_axes(size, title or f"{traj.body_name}: ground frame")
    artists = [ax.plot([], [], [], color="0.2", lw=1.6, ls="--" if removed else "-", marker="o" if len(p) == 1 else None)[0]
               for p, removed in lines]
    w_line, = ax.plot([], [], [], color="tab:red", lw=2.2, label=r"$\omega$ (rad/s, scaled)")
    L_line, = ax.plot([], [], [], color="tab:blue", lw=2.2, label="L (kg m$^2$/s, scaled)")
    stamp = ax.text2D(0.02, 0.95, "", transform=ax.transAxes, fontsize=9)
    _legend(ax)

    def draw(k: int):
        R = rot[k].as_matrix()
        for artist, (pts, _) in zip(artists, lines):
            q = pts @ R.T
            artist.set_data_3d(q[:, 0], q[:, 1], q[:, 2])
        for line, vec, s in ((w_line, w[k], sw), (L_line, L[k], sL)):
            tip = vec * s
            line.set_data_3d([0, tip[0]], [0, tip[1]], [0, tip[2]])
        stamp.set_text(f"t = {traj.t[k]:.2f} s")

    _save(fig, draw, frames, path, fps, dpi, [*artists, w_line, L_line, stamp])
    return path


def animate_body_frame(body: Body, traj: Trajectory, path: str | os.PathLike[str], *, max_frames: int = 100, fps: int = 20,
                       title: str | None = None, dpi: int = 90) -> Path:
    """omega and L seen from the body (design axes), with the path of omega's tip; returns the file written.

    ``path`` as for :func:`animate_ground_frame`.

    Examples
    --------
    >>> import tempfile
    >>> import tumble
    >>> from PIL import Image
    >>> from pathlib import Path
    >>> from tumble.viz.animate import animate_body_frame
    >>> body = tumble.t_handle()
    >>> run = tumble.simulate(body, [0.1, 10.0, 0.1], t_end=0.1, samples=101)   # 0.5 rad of spin a frame
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     gif = animate_body_frame(body, run, Path(folder) / "flip.gif", max_frames=3, dpi=20)
    ...     with Image.open(gif) as image:
    ...         gif.name, image.format, image.n_frames  # 3 of the 101 samples
    ('flip.gif', 'GIF', 3)
    >>> animate_body_frame(tumble.iss_t_handle(), run, "flip.gif")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: body = ... is not the body of this trajectory: ...
    """
    path, frames = _prepare(body, traj, path, max_frames, fps, dpi)
    lines = body_lines(body)
    size = 1.25 * body_size(body)
    A = traj.principal_axes  # principal -> design
    w, L = traj.omega @ A.T, traj.angular_momentum @ A.T
    sw, sL = arrow_scale(w, size), arrow_scale(L, size)

    fig, ax = scene_axes(size, title or f"{traj.body_name}: body frame")
    for pts, removed in lines:
        ax.plot(pts[:, 0], pts[:, 1], pts[:, 2], color="0.55", lw=0.9, ls="--" if removed else "-",
                marker="o" if len(pts) == 1 else None)
    trace, = ax.plot([], [], [], color="tab:red", lw=0.8, alpha=0.6)
    w_line, = ax.plot([], [], [], color="tab:red", lw=2.2, label=r"$\omega$ (rad/s, scaled)")
    L_line, = ax.plot([], [], [], color="tab:blue", lw=2.2, label="L (kg m$^2$/s, scaled)")
    stamp = ax.text2D(0.02, 0.95, "", transform=ax.transAxes, fontsize=9)
    _legend(ax)
    tips = w * sw

    def draw(k: int):
        trace.set_data_3d(tips[: k + 1, 0], tips[: k + 1, 1], tips[: k + 1, 2])
        for line, tip in ((w_line, tips[k]), (L_line, L[k] * sL)):
            line.set_data_3d([0, tip[0]], [0, tip[1]], [0, tip[2]])
        stamp.set_text(f"t = {traj.t[k]:.2f} s")

    _save(fig, draw, frames, path, fps, dpi, [trace, w_line, L_line, stamp])
    return path


def _prepare(body: Body, traj: Trajectory, path, max_frames: int, fps: int, dpi: int) -> tuple[Path, np.ndarray]:
    """The checked inputs of an animation: the path it is written to (an MP4 without ffmpeg
    becomes a GIF, with a warning that says so) and the frames drawn."""
    check_body_and_run(body, traj)
    for name, value in (("fps", fps), ("dpi", dpi)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 1 <= value <= 1000:
            raise ValueError(f"{name} = {value!r} must be a whole number from 1 to 1000")
    frames = frame_indices(len(traj), max_frames, "max_frames")
    turn = frame_turn(traj.t, traj.omega, frames) if len(frames) >= 2 else 0.0
    if turn > SMOOTH_TURN:  # a body that turns far between frames seems to jump, or turn the other way
        from .plots import AliasedSamplesWarning

        warnings.warn(AliasedSamplesWarning(
            f"the body turns up to {np.degrees(turn):.0f} deg between the animation's frames (more than "
            f"{np.degrees(SMOOTH_TURN):.0f}): it will seem to jump; animate a shorter run or give more frames "
            f"(max_frames) and samples"), stacklevel=3)
    path, note = animation_path(path)
    if note:
        warnings.warn(f"{path.with_suffix('.mp4')}: {note}", stacklevel=3)
    return path, frames


def _save(fig: Figure, draw: Callable[[int], None], frames: np.ndarray, path: Path, fps: int, dpi: int,
          moving: Sequence[Artist]) -> None:
    """Render every frame into a temporary file, then rename it into place.

    The constrained layout is worked out for the first frame and then kept (no layout engine
    after it): only the lines and the time stamp change from frame to frame, inside the axes,
    and laying out the 3D axes again for every frame was 40 % of the demo's time (cProfile of
    ``tumble demo``: 14.8 of 36 s in ``do_constrained_layout`` for 400 frames). The frames
    also cannot shift by a pixel from one to the next. No engine at all, not the placeholder
    ``"none"`` leaves: with any engine ``savefig`` draws the figure twice, once without output.
    After the first frame, the axes is drawn by a :func:`_blit_layer`: its still part once,
    then mostly only the artists of ``moving``: ~4 ms a frame instead of ~36 (CPU time, 100
    frames of 486 x 486 pixels; an MP4's encoding by ffmpeg adds ~3.5 ms, a GIF's by Pillow ~16).
    """
    import matplotlib

    writer = writer_for(path, fps)
    settings = {"animation.ffmpeg_path": ffmpeg_path()} if path.suffix == ".mp4" else {}
    with matplotlib.rc_context(settings), atomic_path(path) as tmp:
        with writer.saving(fig, str(tmp), dpi):
            _grab_frames(fig, draw, frames, writer, dpi, moving)


def _grab_frames(fig: Figure, draw: Callable[[int], None], frames: np.ndarray, writer: Any, dpi: int,
                 moving: Sequence[Artist]) -> None:
    """Each frame drawn by ``draw`` and handed to ``writer`` (set up, at ``dpi``), the first in
    full, the others through a :func:`_blit_layer` when ``_BLIT`` (False: every frame in full, the
    reference the blitted frames are compared with, tests/test_animate_frames.py)."""
    import matplotlib

    for i, k in enumerate(frames):
        draw(int(k))
        writer.grab_frame()
        if i == 0:  # the first frame's layout, kept: no layout engine from now on
            with matplotlib.rc_context({"figure.autolayout": False, "figure.constrained_layout.use": False}):
                fig.set_layout_engine(None)  # not "none": savefig draws twice with any engine, even a placeholder
            if _BLIT and moving:
                _blit_layer(moving, dpi)


#: Whether frames after the first are blitted (False: every frame a full draw, as a reference).
_BLIT = True


def _blit_layer(moving: Sequence[Artist], dpi: float) -> Artist:
    """Make the axes of ``moving`` cheap to draw again at ``dpi``: a layer that stands in for it.

    Every frame of an animation goes through a full ``savefig`` (the writers' public way to take
    a frame): panes, ticks, labels, title and legend of the 3D axes, though only ``moving``
    changes. This is matplotlib's blitting, for a file: the *front* (the moving artists and
    every artist the axes draws after the first of them, as ``Axes.draw`` sorts them by z-order:
    the time stamp, the titles, the legend over the lines) is marked animated, which a draw
    outside ``savefig`` leaves out (a hidden title would be misplaced); the figure is drawn so
    once, at ``dpi`` on an Agg canvas, and kept (``copy_from_bbox``): ``under``; then the still
    part of the front (titles, legend) drawn over it and kept too: ``over``. The layer, added to
    the figure in place of the axes (hidden), restores ``over`` and draws the moving artists;
    where one of them reaches a still front artist (their boxes, padded by the line width and
    3 pixels of anti-aliasing, overlap: a line under the legend), it restores ``under`` instead
    and draws the whole front, in the axes' order. Either way the pixels of a full draw, exactly
    (tests/test_animate_frames.py): the drawing that is left out or reordered touches pixels
    nothing else drawn after ``under`` touches. The writers' ``savefig`` is unchanged; only the
    figure's draw is cheaper. A renderer that cannot restore (not Agg) or of another size gets
    the axes drawn in full.

    Examples
    --------
    >>> from tumble.viz.animate import _blit_layer, scene_axes
    >>> fig, ax = scene_axes(1.0, "spin")
    >>> line, = ax.plot([0, 1], [0, 1], [0, 1], label="omega")
    >>> legend = ax.legend()
    >>> layer = _blit_layer([line], dpi=20)
    >>> ax.get_visible(), layer in fig.get_children(), layer.front[0] is line, legend in layer.front
    (False, True, True, True)
    >>> layer.under.get_extents(), layer.size  # 5.4 in at 20 dpi
    ((0, 0, 108, 108), (108.0, 108.0))
    """
    from matplotlib.artist import Artist
    from matplotlib.axis import Axis
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.legend import Legend
    from matplotlib.lines import Line2D
    from matplotlib.spines import Spine
    from matplotlib.text import Text

    ax: Any = moving[0].axes  # Any: matplotlib's hints leave the axes and figure optional
    fig: Any = ax.get_figure(root=True)
    # the axes' draw order (Axes.draw sorts its children by zorder; the patch it draws first, the
    # axis objects and the spines of a 3D axes apart or not at all), from the first moving artist on
    order = sorted((a for a in ax.get_children() if a is not ax.patch and not isinstance(a, (Axis, Spine))),
                   key=lambda a: a.get_zorder())
    front = order[min(order.index(a) for a in moving):]
    still = [a for a in front if a not in moving]
    for a in front:
        a.set_animated(True)
    canvas: Any = FigureCanvasAgg(fig)  # the figure's canvas from now on (savefig would make one a frame)
    own_dpi = fig.get_dpi()
    fig.set_dpi(dpi)
    try:
        canvas.draw()  # not saving: without the animated front
        under = canvas.copy_from_bbox(fig.bbox)
        renderer = canvas.get_renderer()
        for a in still:
            a.draw(renderer)
        over = canvas.copy_from_bbox(fig.bbox)
        boxes: list[Any] | None = [a.get_window_extent(renderer).padded(3.0) for a in still  # an empty title draws nothing
                                    if a.get_visible() and not (isinstance(a, Text) and not a.get_text())]
    finally:
        fig.set_dpi(own_dpi)
    # boxes only where they bound what is drawn: lines (but for their width) and texts, a legend
    if not (all(isinstance(a, (Line2D, Text)) for a in moving) and all(isinstance(a, (Text, Legend)) for a in still)):
        boxes = None

    def reaches(artist: Any, renderer: Any) -> bool:
        """Whether ``artist``, as just drawn, may touch a pixel of a still front artist."""
        box = artist.get_window_extent(renderer)
        pad = 3.0 + (renderer.points_to_pixels(artist.get_linewidth()) if isinstance(artist, Line2D) else 0.0)
        return not np.isfinite(box.extents).all() or box.padded(pad).count_overlaps(boxes) > 0

    class BlitLayer(Artist):
        front: list[Artist]  # the axes' front, in its order
        under: Any  # the Agg renderer's BufferRegion: the figure without the front
        over: Any  # with the still front
        size: tuple[float, float]  # of the renderer they fit

        def draw(self, renderer: Any) -> None:
            if (renderer.get_canvas_width_height() == self.size and hasattr(renderer, "restore_region")):
                if boxes is not None:
                    renderer.restore_region(self.over)
                    drawn = [a for a in self.front if a in moving]
                    for a in drawn:
                        a.draw(renderer)
                    if not any(a.get_visible() and reaches(a, renderer) for a in drawn):
                        return
                renderer.restore_region(self.under)
            else:  # the full draw, for another renderer
                ax.set_visible(True)
                try:
                    ax.draw(renderer)
                finally:
                    ax.set_visible(False)
                if fig.canvas.is_saving():  # the front was drawn with the rest
                    return
            for a in self.front:
                a.draw(renderer)

    layer = BlitLayer()
    layer.front, layer.under, layer.over = front, under, over
    x0, y0, x1, y1 = under.get_extents()
    layer.size = float(x1 - x0), float(y1 - y0)
    layer.set_zorder(ax.get_zorder())
    ax.set_visible(False)
    fig.add_artist(layer)
    return layer
