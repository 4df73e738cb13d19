"""The animations' blitted frames (tumble.viz.animate._blit_layer) are the full draw's, pixel for pixel.

After the first frame the still part of the 3D axes (panes, ticks, labels) is drawn once and
restored; only the front (the moving lines, the time stamp, the titles and the legend over them)
is drawn again (only the moving artists, over a background with the legend and titles, where no
moving artist reaches those). Both ways go through the same Agg drawing of the same artists onto
the same pixels, in the same order where they touch the same pixels, so the frames are equal
exactly (tolerance 0), not only up to anti-aliasing.
"""

from __future__ import annotations

import io

import numpy as np
import pytest
from matplotlib.animation import AbstractMovieWriter

import tumble
from tumble.viz import animate


class Frames(AbstractMovieWriter):
    """A writer that keeps each frame as an RGBA array (taken as the writers take theirs: savefig rgba)."""

    def setup(self, fig, outfile, dpi=None):
        super().setup(fig, outfile, dpi)
        self.frames = []

    def grab_frame(self, **savefig_kwargs):
        buffer = io.BytesIO()
        self.fig.savefig(buffer, format="rgba", dpi=self.dpi)
        width, height = self.frame_size
        self.frames.append(np.frombuffer(buffer.getvalue(), np.uint8).reshape(height, width, 4))

    def finish(self):
        with open(self.outfile, "wb"):  # the file atomic_path renames into place
            pass


@pytest.fixture(scope="module")
def run():
    return tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=4.0, samples=41)


def _frames(monkeypatch, make, run, folder, blit: bool) -> np.ndarray:
    writers = []
    monkeypatch.setattr(animate, "writer_for", lambda path, fps: writers.append(Frames(fps=fps)) or writers[-1])
    monkeypatch.setattr(animate, "_BLIT", blit)
    make(tumble.t_handle(), run, folder / "a.gif", max_frames=4, dpi=30)
    return np.array(writers[0].frames)


@pytest.mark.parametrize("make", [animate.animate_ground_frame, animate.animate_body_frame])
@pytest.mark.filterwarnings("ignore::tumble.viz.plots.AliasedSamplesWarning")   # 4 frames: the pixels are the test
def test_blitted_frames_are_the_full_draws(monkeypatch, tmp_path, run, make):
    full = _frames(monkeypatch, make, run, tmp_path, blit=False)
    blitted = _frames(monkeypatch, make, run, tmp_path, blit=True)
    assert full.shape == blitted.shape == (4, 162, 162, 4)
    assert len({frame.tobytes() for frame in full}) == 4  # the frames differ: something moves
    difference = np.abs(full.astype(int) - blitted.astype(int))
    assert difference.max() == 0, f"frames {np.nonzero(difference.reshape(4, -1).max(1))[0].tolist()} differ"


def _rgba(fig, dpi: int) -> np.ndarray:
    buffer = io.BytesIO()
    fig.savefig(buffer, format="rgba", dpi=dpi)
    width, height = (fig.get_size_inches() * dpi).astype(int)
    return np.frombuffer(buffer.getvalue(), np.uint8).reshape(height, width, 4)


def test_the_legend_stays_over_a_line_that_crosses_it():
    """z-order: a moving line under the legend, blitted as drawn in full; and away from it, too."""
    fig, ax = animate.scene_axes(1.0, "spin")
    ax.plot([-1.0, 1.0], [-1.0, -1.0], [0.0, 0.0], color="0.5")  # still, under the moving line
    line, = ax.plot([], [], [], color="tab:red", lw=3.0, label="omega")
    stamp = ax.text2D(0.02, 0.95, "", transform=ax.transAxes, fontsize=9)
    legend = ax.legend(loc="center", fontsize=20)
    fig.set_layout_engine(None)
    ends = [(1.0, 1.0), (1.0, 0.8), (-0.6, -0.9)]  # through the middle (under the legend) twice; then not

    def frame(k: int) -> None:
        line.set_data_3d([-1.0, ends[k][0]], [-1.0, ends[k][1]], [-1.0, ends[k][0]])
        stamp.set_text(f"t = {k}")

    full = []
    for k in range(3):
        frame(k)
        full.append(_rgba(fig, 30))
    layer = animate._blit_layer([line, stamp], dpi=30)
    legend_draws = []
    legend.draw = lambda renderer, draw=legend.draw: legend_draws.append(draw(renderer))
    for k in range(3):
        frame(k)
        assert np.array_equal(_rgba(fig, 30), full[k]), k
    assert len(legend_draws) == 2  # drawn again where the line reaches it, not where it does not
    layer.front.reverse()  # the legend under the line: the test sees the order
    frame(0)
    assert not np.array_equal(_rgba(fig, 30), full[0])
    assert not ax.get_visible()


def test_a_renderer_of_another_size_gets_the_full_draw():
    """The layer's fallback: drawn at another dpi than its background's, the axes is drawn in full."""
    fig, ax = animate.scene_axes(1.0, "spin")
    line, = ax.plot([0.0, 1.0], [0.0, 1.0], [0.0, 1.0], color="tab:red", label="omega")
    ax.legend()
    fig.set_layout_engine(None)
    before = _rgba(fig, 30), _rgba(fig, 20)
    animate._blit_layer([line], dpi=30)
    after = _rgba(fig, 30), _rgba(fig, 20)  # blitted; the full draw
    assert not ax.get_visible()
    assert np.array_equal(before[0], after[0]) and np.array_equal(before[1], after[1])
