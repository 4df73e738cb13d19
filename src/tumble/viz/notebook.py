"""The interactive page inside a Jupyter notebook.

:func:`show` embeds the page of :mod:`tumble.viz.page` (plotly, bundled, offline) in an
``<iframe srcdoc=...>``: the page runs in a document of its own, so its scripts and styles
neither touch the notebook nor depend on the notebook front end's plotly, and the output
plays again when the saved notebook is opened without a kernel.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from .._html import escape_text
from .._optional import optional_import
from ..dynamics import Trajectory
from ..mass import Body
from .scene import check_body_and_run

if TYPE_CHECKING:
    from IPython.display import HTML

__all__ = ["DEFAULT_HEIGHT", "show"]

#: Height of the frame, pixels: the page's controls, live-mode form and figure (about 1040 px in
#: Chromium at widths from 900 px up).
DEFAULT_HEIGHT = 1060


def _ipython_html():
    return optional_import("IPython.display", "notebook", "tumble.viz.show (a display in Jupyter)").HTML


def _check(trajectory, body, height) -> None:
    check_body_and_run(body, trajectory)
    if isinstance(height, bool) or not isinstance(height, int) or height <= 0:
        raise ValueError(f"height = {height!r} must be a whole number of pixels > 0")


def show(trajectory: Trajectory, body: Body, *, frames: int = 150, height: int = DEFAULT_HEIGHT, title: str | None = None) -> HTML:
    """The interactive page of a run, for display in a Jupyter notebook.

    Parameters
    ----------
    trajectory : Trajectory
        The run (:func:`tumble.simulate`).
    body : Body
        The body that was simulated: the page draws its parts, which a trajectory does not hold.
    frames : int
        Animation frames (fewer make a smaller notebook).
    height : int
        Height of the frame, pixels.
    title : str, optional
        The page's title; by default the body's name, the method and the duration.

    Returns
    -------
    IPython.display.HTML
        The page in an ``<iframe>`` (its ``srcdoc``, escaped), with plotly.js inside it: the
        output plays without a network, and without a kernel once saved.

    Raises
    ------
    ImportError
        Without IPython (``pip install 'tumble[notebook]'``).
    ValueError
        If ``body`` is not a Body whose principal moments are the trajectory's, or ``height`` is
        not a positive whole number; and as the page raises it (``frames``, missing plotly).

    Examples
    --------
    >>> import html
    >>> import tumble
    >>> from tumble.viz.notebook import show
    >>> body = tumble.t_handle()
    >>> run = tumble.simulate(body, [0.1, 10.0, 0.1], t_end=2.0, samples=101)
    >>> frame = show(run, body, frames=5, height=600, title="T-handle flip")  # in a notebook: the page, playing
    >>> frame.data.startswith('<div><iframe srcdoc="'), 'height="600"' in frame.data, 'title="tumble: T-handle, exact"' in frame.data
    (True, True, True)
    >>> "<title>T-handle flip</title>" in html.unescape(frame.data)  # the page, escaped into srcdoc
    True
    >>> show(run, tumble.iss_t_handle())  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: body = ... is not the body of this trajectory: ...
    """
    HTML = _ipython_html()
    _check(trajectory, body, height)
    from .page import page_html

    page = page_html(body, trajectory, frames=frames, title=title)
    label = escape_text(f"tumble: {trajectory.body_name}, {trajectory.method}")
    # in a <div>: IPython's HTML warns about a bare <iframe> (it suggests IFrame, which takes a URL only)
    return HTML(f'<div><iframe srcdoc="{escape_text(page)}" title="{label}" width="100%" '
                f'height="{height}" style="border:none" sandbox="allow-scripts"></iframe></div>')
