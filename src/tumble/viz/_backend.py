"""Figures without pyplot: every figure function returns a :class:`matplotlib.figure.Figure`.

Why not pyplot: ``pyplot.subplots`` registers each figure in pyplot's global list (it stays in
memory until closed, and a notebook's inline backend shows it again at the end of the cell) and
needs a backend, which would mean choosing one for the user (``matplotlib.use("Agg")`` switches
a notebook's inline backend off). A bare ``Figure`` needs none: it renders through Agg when it is
saved, whatever backend the user chose, and is freed like any other object.

One catch, checked by running a notebook (nbclient, ipykernel with matplotlib-inline): Jupyter
shows a bare ``Figure`` as a picture only once pyplot has been imported (matplotlib-inline then
registers a PNG formatter for ``Figure``); before that it prints ``<Figure size ... with 1
Axes>``. ``TumbleFigure`` adds ``_repr_png_`` so the figure displays either way; where a
formatter is registered, IPython uses that one instead (both give the same PNG).

Saving is a separate step, :func:`save_figure`, atomic through :mod:`tumble.io.atomic`.
"""

from __future__ import annotations

import io
import os
from typing import TYPE_CHECKING, Any

from ..io.output import FIGURE_DPI

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["TumbleFigure", "figure_and_axes", "legend_outside", "new_figure", "note_only", "save_figure"]


def _repr_png_(self) -> bytes:
    buffer = io.BytesIO()
    self.savefig(buffer, format="png", dpi=100)
    return buffer.getvalue()


#: The docstring of ``TumbleFigure`` (the class is made on first use, by :func:`__getattr__`).
_TUMBLE_FIGURE_DOC = """A matplotlib Figure with ``_repr_png_`` (see the module).

    Examples
    --------
    >>> from tumble.viz._backend import TumbleFigure, new_figure
    >>> fig = new_figure()
    >>> isinstance(fig, TumbleFigure), fig.get_size_inches().tolist()
    (True, [7.5, 3.6])
    >>> fig._repr_png_()[1:4]  # what a notebook shows: a PNG, without pyplot
    b'PNG'
    """
#: doctest collects the example even before the class is made (``--doctest-modules`` looks only
#: at what the module holds when it is collected).
__test__ = {"TumbleFigure": _TUMBLE_FIGURE_DOC}


def __getattr__(name: str) -> type:
    """``TumbleFigure``: a matplotlib Figure that a notebook displays as a PNG without pyplot.

    Made on first use, so that importing :mod:`tumble.viz` does not import matplotlib.
    """
    if name != "TumbleFigure":
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    if "TumbleFigure" in globals():  # called directly by new_figure
        return globals()["TumbleFigure"]
    from matplotlib.figure import Figure

    cls = type("TumbleFigure", (Figure,), {"__module__": __name__, "_repr_png_": _repr_png_,
                                           "__doc__": _TUMBLE_FIGURE_DOC})
    globals()["TumbleFigure"] = cls
    return cls


def new_figure(figsize: tuple[float, float] = (7.5, 3.6), **kwargs: Any) -> Figure:
    """A new ``TumbleFigure`` (constrained layout unless ``layout`` is given), not registered with pyplot.

    ``figsize`` is (width, height) in inches.

    Examples
    --------
    >>> from tumble.viz._backend import new_figure
    >>> fig = new_figure((4.0, 3.0))
    >>> fig.get_size_inches().tolist(), type(fig.get_layout_engine()).__name__, fig.axes
    ([4.0, 3.0], 'ConstrainedLayoutEngine', [])
    """
    kwargs.setdefault("layout", "constrained")
    return __getattr__("TumbleFigure")(figsize=figsize, **kwargs)


def figure_and_axes(ax: Axes | None = None, figsize: tuple[float, float] = (7.5, 3.6),
                    **subplot_kw: Any) -> tuple[Figure, Axes]:
    """``(figure, ax)``: ``ax`` and its figure when given, else a new figure with one axes.

    Examples
    --------
    >>> from tumble.viz._backend import figure_and_axes
    >>> fig, ax = figure_and_axes()
    >>> len(fig.axes), ax.figure is fig, fig.get_size_inches().tolist()
    (1, True, [7.5, 3.6])
    >>> figure_and_axes(ax) == (fig, ax)  # axes given: drawn there, no new figure
    True
    >>> figure_and_axes(projection="3d")[1].name  # keywords go to add_subplot
    '3d'
    """
    if ax is not None:
        return ax.figure, ax
    fig = new_figure(figsize)
    return fig, fig.add_subplot(**subplot_kw)


def legend_outside(ax: Axes, **kwargs: Any) -> None:
    """The legend to the right of the axes, outside them: it never covers the data. On axes of a
    figure with no layout engine (``plt.subplots()``'s, given as ``ax=``) nothing makes room for it
    there, and a saved figure cut it off: it goes inside, where it covers least.

    Nothing labelled, no legend. ``kwargs`` go to ``ax.legend`` (over the defaults).

    Examples
    --------
    >>> from tumble.viz._backend import figure_and_axes, legend_outside
    >>> fig, ax = figure_and_axes()
    >>> legend_outside(ax)
    >>> ax.get_legend() is None
    True
    >>> _ = ax.plot([0.0, 1.0], [0.0, 1.0], label="omega_1")
    >>> legend_outside(ax)
    >>> legend = ax.get_legend()
    >>> [text.get_text() for text in legend.get_texts()], bool(legend.get_bbox_to_anchor().x0 > ax.bbox.x1)  # right of the axes
    (['omega_1'], True)
    """
    handles, _ = ax.get_legend_handles_labels()
    if not handles:
        return
    if ax.figure.get_layout_engine() is None:  # the user's own figure, with no layout to make room: inside
        ax.legend(**{"fontsize": 7, "loc": "best", "framealpha": 0.9, **kwargs})
        return
    ax.legend(**{"fontsize": 7, "loc": "upper left", "bbox_to_anchor": (1.01, 1.0), "borderaxespad": 0.0,
                 "framealpha": 0.9, **kwargs})


def note_only(ax: Axes, note: str, title: str | None = None) -> None:
    """An empty panel that says, in one line, why there is nothing to draw.

    Examples
    --------
    >>> from tumble.viz._backend import figure_and_axes, note_only
    >>> fig, ax = figure_and_axes()
    >>> note_only(ax, "no polhode for this run: a torque acts", "polhode")
    >>> ax.axison, [text.get_text() for text in ax.texts], ax.get_title()
    (False, ['no polhode for this run: a torque acts'], 'polhode')
    """
    ax.set_axis_off()
    text = ax.text2D if ax.name == "3d" else ax.text
    text(0.5, 0.5, note, ha="center", va="center", wrap=True, fontsize=9, transform=ax.transAxes)
    if title:
        ax.set_title(title, fontsize=9)


def save_figure(fig: Figure, path: str | os.PathLike[str], dpi: int = FIGURE_DPI) -> None:
    """Write ``fig`` to ``path`` (format from the suffix: PNG, SVG, PDF, ...), whole or not at all.

    The figure is written to a temporary name in the same folder and renamed into place
    (:func:`tumble.io.atomic.atomic_path`), so a failure midway leaves no half-written file.
    The figure stays open: it can be shown or saved again.

    Parameters
    ----------
    fig : matplotlib Figure
        What a ``figure_*`` function returned (or any Figure).
    path : str or Path
        The file to write.
    dpi : int
        Dots per inch of a raster format.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from tumble.viz._backend import figure_and_axes, save_figure
    >>> fig, ax = figure_and_axes(figsize=(4.0, 3.0))
    >>> _ = ax.plot([0.0, 1.0], [1.0, 0.0])
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     save_figure(fig, Path(folder) / "line.png", dpi=50)
    ...     png = Path(folder, "line.png").read_bytes()
    ...     sorted(p.name for p in Path(folder).iterdir())  # no temporary file left behind
    ['line.png']
    >>> png[1:4], int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")  # 4 x 3 inches at 50 dpi
    (b'PNG', 200, 150)
    >>> save_figure(fig, "line.txt")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: line.txt: a figure is written as ... (by the suffix), not '.txt'
    """
    from pathlib import Path

    from ..io.atomic import atomic_path

    if not hasattr(fig, "savefig") or not hasattr(fig, "canvas"):
        raise ValueError(f"fig = {type(fig).__name__} object must be a matplotlib Figure (what a figure_* function returns)")
    if isinstance(dpi, bool) or not isinstance(dpi, (int, float)) or not 1 <= dpi <= 2000:
        raise ValueError(f"dpi = {dpi!r} must be a number from 1 to 2000")
    path = Path(path)
    kinds = fig.canvas.get_supported_filetypes()
    kind = path.suffix[1:].lower()
    if kind not in kinds:
        raise ValueError(f"{path}: a figure is written as {', '.join('.' + k for k in sorted(kinds))} (by the "
                         f"suffix), not {path.suffix or 'no suffix'!r}")
    with atomic_path(path) as tmp:  # the temporary name has its own suffix: the format is given
        fig.savefig(tmp, dpi=dpi, format=kind)
