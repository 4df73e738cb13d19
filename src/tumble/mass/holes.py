"""A body's holes: a subtracted part removes material only where its solid parts have some.

A hole (a solid part with ``subtract=True``) counts as negative mass of its own density in the
sums of seed eqs. (1) and (4). That is the body's mass distribution only where the hole lies in
solid material at least as dense as itself; elsewhere the sums remove mass that was never there
and give a body no one can build, with no sign of it in the numbers (a walkthrough's hole beside
its plate, issue 40). So before the sums, :func:`check_holes` refuses

- a hole denser than every solid part it could be cut from (exact, from the densities), and
- a hole that removes material where there is none: the net density of the parts (solids' less
  holes') at quasi-random points inside each hole must not be negative, over all but
  :data:`HOLE_OUTSIDE_TOLERANCE` of the hole's mass. This catches a hole outside every solid, one
  that sticks out of its solid (a drilled hole drawn longer than the plate is thick), and two
  holes over the same material.

The points are a scrambled Halton sequence with a fixed seed (:mod:`scipy.stats.qmc`), so a body
gives the same verdict every time; each part kind says where its own material is
(``Part._inside``).
"""

from __future__ import annotations

import functools
from typing import cast

import numpy as np

from ..typing import FloatArray
from .part_base import Part

__all__ = ["HOLE_OUTSIDE_TOLERANCE", "HOLE_POINTS", "check_holes"]

#: The share of a hole's mass that may fall where there is no material (the points' resolution:
#: at :data:`HOLE_POINTS` quasi-random points the share is found to ~0.2 %).
HOLE_OUTSIDE_TOLERANCE = 0.01

#: Quasi-random points sampled in each hole's bounding box (fewer for a mesh of many triangles,
#: whose inside test costs points x triangles; never fewer than 128).
HOLE_POINTS = 1024


def _density(p: Part) -> float:
    return cast(float, p.mass) / p.volume


@functools.cache
def _unit_points(n: int) -> FloatArray:
    """``n`` scrambled Halton points in the unit cube, the same every time (made once: ~5 ms)."""
    from scipy.stats import qmc

    points = qmc.Halton(3, rng=np.random.default_rng(0)).random(n)
    points.flags.writeable = False
    return cast(FloatArray, points)


def _points_in(hole: Part, n: int) -> FloatArray:
    """Quasi-random points inside ``hole``, design frame, m."""
    lo, hi = hole._local_bounds()
    local = lo + (hi - lo) * _unit_points(n)
    local = local[hole._inside_local(local, 0.0)]
    return cast(FloatArray, hole.orientation.apply(local) + hole._frame_origin)


def check_holes(parts: tuple[Part, ...]) -> None:
    """Refuse subtracted parts that remove material where the solid parts have none.

    Parameters
    ----------
    parts : tuple of Part
        A body's parts, in the design frame.

    Raises
    ------
    ValueError
        Naming the hole (``parts[i]``) that is denser than every solid it could be cut from, or
        that removes more than :data:`HOLE_OUTSIDE_TOLERANCE` of its mass where there is none
        (outside the solids, or where another hole already took the material), with that share.

    Examples
    --------
    >>> import tumble
    >>> from tumble.mass.holes import check_holes
    >>> plate = tumble.Box(density=2700.0, size=(0.2, 0.2, 0.01))
    >>> check_holes((plate, tumble.Cylinder(density=2700.0, radius=0.02, length=0.01, subtract=True)))
    >>> check_holes((plate, tumble.Cylinder(density=2700.0, radius=0.02, length=0.03, subtract=True)))
    Traceback (most recent call last):
    ...
    ValueError: parts[1] (a cylinder, subtract = true) removes material where there is none: 67 % of its mass lies outside the solid parts (or where another hole already took it); a hole removes mass only from the solid it is cut in: make it fit inside (a hole through a plate is as long as the plate is thick)
    """
    holes = [i for i, p in enumerate(parts) if p.subtract and p.volume > 0]
    if not holes:
        return
    solids = [p for p in parts if p.solid and not p.subtract and p.volume > 0]
    densest = max((_density(p) for p in solids), default=0.0)
    for i in holes:
        p = parts[i]
        if _density(p) > densest * (1.0 + 1e-9):
            where = f"the densest is {densest:.6g} kg/m^3" if solids else "there is none"
            raise ValueError(f"parts[{i}] (a {p.kind}, subtract = true) is {_density(p):.6g} kg/m^3, denser than every solid "
                             f"part it could be cut from ({where}): a hole removes the material it is cut from; give "
                             f"it that part's density")
    triangles = max(p._triangles for p in parts)
    n = HOLE_POINTS if triangles == 0 else int(np.clip(4_000_000 // triangles, 128, HOLE_POINTS))
    signed = [(p, -_density(p) if p.subtract else _density(p)) for p in parts if p.solid and p.volume > 0]
    for i in holes:
        hole = parts[i]
        x = _points_in(hole, n)
        if len(x) == 0:  # no point fell inside (a sliver): nothing to judge it by
            continue
        lo, hi = hole._local_bounds()
        slack = 1e-9 * float(np.max(hi - lo))  # a point on a face the hole shares with its solid is inside both
        net = np.zeros(len(x))
        for part, rho in signed:
            net += rho * part._inside(x, slack)
        missing = float(np.mean(np.maximum(-net, 0.0))) / _density(hole)
        if missing > HOLE_OUTSIDE_TOLERANCE:
            raise ValueError(
                f"parts[{i}] (a {hole.kind}, subtract = true) removes material where there is none: {100 * missing:.0f} % of "
                f"its mass lies outside the solid parts (or where another hole already took it); a hole removes mass only "
                f"from the solid it is cut in: make it fit inside (a hole through a plate is as long as the plate is thick)")
