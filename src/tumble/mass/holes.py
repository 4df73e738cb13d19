"""A body's holes: a subtracted part removes material only where its solid parts have some.

A hole (a solid part with ``subtract=True``) counts as negative mass of its own density in the
sums of seed eqs. (1) and (4). That is the body's mass distribution only where the hole lies in
solid material at least as dense as itself; elsewhere the sums remove mass that was never there
and give a body no one can build, with no sign of it in the numbers (a walkthrough's hole beside
its plate, issue 40). So before the sums, :func:`check_holes` refuses

- a hole that removes material where there is none: at quasi-random points inside each hole, the
  material it is cut from (the solids' densities less the other holes') must be there over all
  but :data:`HOLE_OUTSIDE_TOLERANCE` of its volume. This catches a hole outside every solid, one
  that sticks out of its solid (a drilled hole drawn longer than the plate is thick), and two
  holes over the same material; and
- a hole denser than the material it is cut from (over more than that share of its mass):
  where solids overlap, their densities add, so a bore through a steel insert pressed into
  plastic is a hole of the two densities' sum;

and warns (:class:`HoleFillWarning`) of a hole lighter than the material it is cut from, which
leaves the difference in it: a 1000 kg/m^3 sphere cut from steel leaves 6850 kg/m^3 of phantom
material (a walkthrough, 2026-12-03). That is a fill of another material, allowed (a steel core
replaced by plastic is a hole of the difference), but more often a slip.

The points are a scrambled Halton sequence with a fixed seed (:mod:`scipy.stats.qmc`), so a body
gives the same verdict every time; each part kind says where its own material is
(``Part._inside``).
"""

from __future__ import annotations

import functools
import warnings
from typing import cast

import numpy as np

from ..typing import FloatArray
from .part_base import Part

__all__ = ["HOLE_OUTSIDE_TOLERANCE", "HOLE_POINTS", "HoleFillWarning", "check_holes"]

#: The share of a hole's mass that may fall where there is no material (the points' resolution:
#: at :data:`HOLE_POINTS` quasi-random points the share is found to ~0.2 %).
HOLE_OUTSIDE_TOLERANCE = 0.01

#: Quasi-random points sampled in each hole's bounding box (fewer for a mesh of many triangles,
#: whose inside test costs points x triangles; never fewer than 128).
HOLE_POINTS = 1024


class HoleFillWarning(UserWarning):
    """A hole (``subtract = true``) lighter than the material it is cut from: the difference stays in
    it, a fill of another material (:func:`check_holes`); a command prints it in one line and goes on.

    Examples
    --------
    >>> import warnings
    >>> import tumble
    >>> from tumble.mass.holes import HoleFillWarning
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always", HoleFillWarning)
    ...     body = tumble.Body([tumble.Box(density=7850.0, size=(1.0, 1.0, 1.0)),
    ...                         tumble.Sphere(density=1000.0, radius=0.2, subtract=True)])
    >>> round(body.mass, 1), str(caught[0].message)[:74]
    (7816.5, 'parts[1] (a sphere, subtract = true) leaves 6850 kg/m^3 of the 7850 kg/m^3')
    """

    cli_one_line = True  # a command prints it as one line, "warning: ..." (tumble.cli)


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
        Naming the hole (``parts[i]``) that removes more than :data:`HOLE_OUTSIDE_TOLERANCE` of
        its mass where there is none (outside the solids, or where another hole already took the
        material), with that share, or that is denser than the material it is cut from.

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
    triangles = max(p._triangles for p in parts)
    n = HOLE_POINTS if triangles == 0 else int(np.clip(4_000_000 // triangles, 128, HOLE_POINTS))
    signed = [(p, -_density(p) if p.subtract else _density(p)) for p in parts if p.solid and p.volume > 0]
    for i in holes:
        hole = parts[i]
        rho = _density(hole)
        x = _points_in(hole, n)
        if len(x) == 0:  # no point fell inside (a sliver): nothing to judge it by
            continue
        lo, hi = hole._local_bounds()
        slack = 1e-9 * float(np.max(hi - lo))  # a point on a face the hole shares with its solid is inside both
        there = np.full(len(x), rho)  # the material this hole is cut from: every part's but its own, kg/m^3
        for part, signed_rho in signed:
            there += signed_rho * part._inside(x, slack)
        absent = there <= 1e-9 * rho  # no solid there, or another hole took it
        for j, part in enumerate(parts):  # a spinning wheel's momentum is its whole wheel's: a hole in it is refused
            if part.kind == "rotor" and not part.subtract and np.mean(part._inside(x, slack)) > HOLE_OUTSIDE_TOLERANCE:
                raise ValueError(f"parts[{i}] (a {hole.kind}, subtract = true) is cut from parts[{j}], a rotor: the rotor's "
                                 "spin momentum is its whole wheel's (J = m r^2 / 2 about its axis), so the hole would leave "
                                 "the wheel spinning as if uncut (a walkthrough's bored wheel carried 6.7 % too much momentum); "
                                 "a Rotor is a solid disc: give one whose m r^2 / 2 is the bored wheel's axial moment")
        outside = float(np.mean(absent))
        short = float(np.mean(np.where(absent, 0.0, np.maximum(rho - there, 0.0)))) / rho
        left = float(np.mean(np.maximum(there - rho, 0.0)))
        cut_from = float(np.mean(there[~absent])) if not np.all(absent) else 0.0
        if outside > HOLE_OUTSIDE_TOLERANCE:
            raise ValueError(
                f"parts[{i}] (a {hole.kind}, subtract = true) removes material where there is none: {100 * outside:.0f} % of "
                f"its mass lies outside the solid parts (or where another hole already took it); a hole removes mass only "
                f"from the solid it is cut in: make it fit inside (a hole through a plate is as long as the plate is thick)")
        if short > HOLE_OUTSIDE_TOLERANCE:
            raise ValueError(f"parts[{i}] (a {hole.kind}, subtract = true) is {rho:.6g} kg/m^3, denser than the "
                             f"{cut_from:.6g} kg/m^3 it is cut from: a hole removes the material it is cut from; give it "
                             f"that material's density")
        if left > HOLE_OUTSIDE_TOLERANCE * cut_from:
            warnings.warn(f"parts[{i}] (a {hole.kind}, subtract = true) leaves {left:.4g} kg/m^3 of the {cut_from:.4g} kg/m^3 "
                          f"it is cut from ({rho:.4g} removed): a hole is empty only with that material's density; a "
                          f"lighter one is a fill of another material", HoleFillWarning, stacklevel=4)
