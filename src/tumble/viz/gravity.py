"""The gravity-gradient stability diagram over the gravity-gradient ratios (k_R, k_Y).

The classification is :func:`tumble.analysis.gravity_stability.gravity_gradient_stability` (Hughes,
*Spacecraft Attitude Dynamics*, ch. 9; DeBra & Delp, J. Astronaut. Sci. 8 (1961) 14); this
module only draws it, on a given ``ax`` or a new figure, and returns the Figure.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..analysis.gravity_stability import STABILITY_REGIONS, gravity_gradient_stability
from ..validation import short_repr
from ._backend import figure_and_axes

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["figure_gravity_stability"]

#: One colour per region of :data:`~tumble.analysis.gravity_stability.STABILITY_REGIONS`, in its order.
REGION_COLORS = ("#4daf4a", "#377eb8", "#fbb4ae", "#fed9a6", "#d9d9d9")
REGION_LABELS = ("Lagrange (stable)", "DeBra-Delp (stable)", "pitch unstable", "roll-yaw unstable",
                 "pitch and roll-yaw unstable")


def _draw_regions(ax, kr_range, ky_range, n: int) -> None:
    """Fill the regions on an ``n`` x ``n`` grid over the ranges and draw their boundaries."""
    from matplotlib.colors import ListedColormap

    def centres(lo, hi, at):  # cell centres, k_Y's a quarter cell off k_R's: never on the lines k_R = 0, k_Y = 0
        return lo + (hi - lo) * (np.arange(n) + at) / n  # and k_R = k_Y (k_P = 0), nor the corners, where k_P is 0/0

    kr, ky = np.meshgrid(centres(*kr_range, 0.5), centres(*ky_range, 0.25))
    region = gravity_gradient_stability(kr, (kr - ky) / (1.0 - kr * ky), ky).region
    filled = STABILITY_REGIONS[:len(REGION_COLORS)]  # "symmetric" lies on those lines, drawn as boundaries
    code = np.select([region == name for name in filled], range(len(filled)))
    ax.pcolormesh(kr, ky, code, cmap=ListedColormap(REGION_COLORS), vmin=-0.5,
                  vmax=len(filled) - 0.5, shading="nearest", rasterized=True)
    with np.errstate(invalid="ignore"):  # the roll-yaw boundary, where k_R k_Y > 0
        prod = kr * ky
        margin = np.where(prod > 0, 1.0 + 3.0 * kr + prod - 4.0 * np.sqrt(np.abs(prod)), np.nan)
    ax.contour(kr, ky, margin, levels=[0.0], colors="0.25", linewidths=0.8)
    ax.plot(kr_range, kr_range, color="0.25", lw=0.8)  # k_R = k_Y: the pitch boundary
    ax.axhline(0.0, color="0.25", lw=0.8)
    ax.axvline(0.0, color="0.25", lw=0.8)
    ax.set_xlim(*kr_range)
    ax.set_ylim(*ky_range)


def figure_gravity_stability(*, ax: Axes | None = None,
                             points: dict[str, tuple[float, float]] | None = None) -> Figure:
    """Linear gravity-gradient stability of a body at rest in the orbiting frame, over (k_R, k_Y).

    ``k_R = (I_pitch - I_yaw) / I_roll`` (horizontal) and ``k_Y = (I_pitch - I_roll) / I_yaw``
    (vertical); every real body lies in the square [-1, 1]^2. Pitch is stable below the diagonal
    (``k_R > k_Y``); roll-yaw where ``k_R k_Y > 0`` and ``1 + 3 k_R + k_R k_Y > 4
    sqrt(k_R k_Y)``. The Lagrange region is the triangle ``k_R > k_Y > 0``; the DeBra-Delp region
    the thin sliver ``k_Y < k_R < 0`` near ``k_R = 0``, shown enlarged in the inset.

    Parameters
    ----------
    ax : matplotlib Axes, optional
        Draw on these axes instead of a new figure.
    points : dict of str to (float, float), optional
        Bodies to mark, label -> ``(k_R, k_Y)`` (:func:`tumble.analysis.gravity_stability.gravity_gradient_ratios`).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from tumble.analysis.gravity_stability import gravity_gradient_ratios
    >>> from tumble.viz.gravity import figure_gravity_stability
    >>> k_R, _, k_Y = gravity_gradient_ratios([5.0, 10.0, 13.0])  # 12 kg box, 1 x 2 x 3 m; pitch major, yaw minor
    >>> ax = figure_gravity_stability(points={"box": (float(k_R), float(k_Y))}).axes[0]
    >>> ax.get_title(), ax.get_xlim() == ax.get_ylim() == (-1.0, 1.0)  # the square of every real body
    ('Gravity-gradient stability in a circular orbit (linearised)', True)
    >>> [text.get_text() for text in ax.get_legend().get_texts()][:2]  # the two stable regions
    ['Lagrange (stable)', 'DeBra-Delp (stable)']
    >>> [text.get_text() for text in ax.texts], [line.get_xydata().tolist() for line in ax.lines if line.get_marker() == "*"]
    (['Lagrange', 'DeBra-Delp', 'box'], [[[0.8, 0.6]]])
    >>> [inset.get_title() for inset in ax.child_axes]
    ['DeBra-Delp, enlarged']
    """
    from matplotlib.patches import Patch

    if points is not None and not isinstance(points, dict):  # a list of pairs had no label to write
        raise ValueError(f"points = {short_repr(points)} must be a dict of a label to its (k_R, k_Y), e.g. "
                         "{'my body': (0.8, 0.6)}")
    for label, pair in (points or {}).items():  # gravity_gradient_ratios' three: "too many values to unpack"
        if np.shape(pair) != (2,):
            raise ValueError(f"points[{label!r}] = {short_repr(pair)} must be two numbers, (k_R, k_Y); of "
                             "gravity_gradient_ratios' three (k_R, k_P, k_Y) give the first and the last")
    fig, ax = figure_and_axes(ax, figsize=(7.6, 5.6))
    _draw_regions(ax, (-1.0, 1.0), (-1.0, 1.0), 600)
    ax.set_aspect("equal")
    ax.set_xlabel(r"$k_R = (I_{pitch} - I_{yaw}) / I_{roll}$ (dimensionless)")
    ax.set_ylabel(r"$k_Y = (I_{pitch} - I_{roll}) / I_{yaw}$ (dimensionless)")
    ax.set_title("Gravity-gradient stability in a circular orbit (linearised)", fontsize=10)
    ax.text(0.55, 0.2, "Lagrange", ha="center", fontsize=9)
    ax.annotate("DeBra-Delp", xy=(-0.02, -0.6), xytext=(-0.75, -0.85), fontsize=9,
                arrowprops={"arrowstyle": "->", "lw": 0.8})
    inset = ax.inset_axes([0.04, 0.42, 0.28, 0.5])
    _draw_regions(inset, (-0.1, 0.02), (-1.0, 0.0), 241)
    inset.set_xticks([-0.1, -0.05, 0.0])
    inset.set_yticks([-1.0, -0.5, 0.0])
    inset.tick_params(labelsize=6)
    inset.set_title("DeBra-Delp, enlarged", fontsize=7)
    for label, (kr, ky) in (points or {}).items():
        for axes in (ax, inset):
            axes.plot([kr], [ky], "k*", ms=7, zorder=5)
        right = kr > 0.5  # keep the label inside the square
        ax.annotate(label, (kr, ky), xytext=(-5 if right else 5, -10 if ky > 0.9 else 4),
                    textcoords="offset points", ha="right" if right else "left", fontsize=8)
    handles = [Patch(color=c, label=lbl) for c, lbl in zip(REGION_COLORS, REGION_LABELS)]
    ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    return fig
