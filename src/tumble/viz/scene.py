"""One scene description of a body, shared by every picture of it.

A body is drawn as wireframe polylines in its design frame, relative to its centre of mass,
built from its parts (so a figure always shows the body whose physics was computed). The
animations transform these lines by the attitude; numpy only, no plotting here.
"""

from __future__ import annotations

import math

import numpy as np

from ..dynamics import Trajectory
from ..mass import INERTIA_RTOL, Body
from ..mass.parts import Box, Cone, Cylinder, Ellipsoid, Part, PointMass, Rod, Shell, Sphere, Tube
from ..typing import ArrayLike

__all__ = ["MAX_FRAME_TURN", "arrow_scale", "body_lines", "body_size", "check_body_and_run", "check_run", "frame_indices",
           "frame_turn", "frames_advice", "part_lines"]


def _circle(radius: float, n: int) -> np.ndarray:
    a = np.linspace(0.0, 2.0 * np.pi, n + 1)
    return np.column_stack([radius * np.cos(a), radius * np.sin(a), np.zeros_like(a)])


def _local_lines(part: Part, n: int) -> list[np.ndarray]:
    """Polylines in the part's own frame (axis of symmetry = local z), about its centre."""
    if isinstance(part, Rod):
        h = part.length / 2
        return [np.array([[0, 0, -h], [0, 0, h]], float)]
    if isinstance(part, (Cylinder, Tube)):
        h = part.length / 2
        radii = [part.radius] if isinstance(part, Cylinder) else [part.inner_radius, part.outer_radius]
        lines = []
        for r in radii:
            if r <= 0:
                continue
            ring = _circle(r, n)
            lines += [ring + [0, 0, -h], ring + [0, 0, h]]
            lines += [np.array([[r * np.cos(a), r * np.sin(a), -h], [r * np.cos(a), r * np.sin(a), h]])
                      for a in np.linspace(0, 2 * np.pi, 4, endpoint=False)]
        return lines
    if isinstance(part, Cone):
        base, apex = cone_span(part)
        ring = _circle(part.radius, n) + [0, 0, base]
        spokes = [np.array([ring[k], [0, 0, apex]]) for k in range(0, n, max(n // 6, 1))]
        return [ring, *spokes]
    if isinstance(part, Box):
        a, b, c = np.array(part.size) / 2
        corners = np.array([[x, y, z] for x in (-a, a) for y in (-b, b) for z in (-c, c)])
        edges = [(i, j) for i in range(8) for j in range(i + 1, 8) if bin(i ^ j).count("1") == 1]
        return [corners[[i, j]] for i, j in edges]
    if isinstance(part, (Sphere, Shell, Ellipsoid)):
        s = np.array(part.semi_axes) if isinstance(part, Ellipsoid) else np.full(3, part.radius)
        ring = _circle(1.0, n)
        return [ring * s, ring[:, [2, 0, 1]] * s, ring[:, [1, 2, 0]] * s]
    if isinstance(part, PointMass):
        return [np.zeros((1, 3))]
    return _mesh_lines(part)


def _mesh_lines(part, max_edges: int = 400) -> list[np.ndarray]:
    mesh = part.mesh
    edges = mesh.edges_unique
    if len(edges) > max_edges:
        edges = edges[np.linspace(0, len(edges) - 1, max_edges).astype(int)]
    verts = mesh_vertices_about_com(part)
    return [verts[e] for e in edges]


def cone_span(part: Cone) -> tuple[float, float]:
    """Base and apex of a solid cone along its axis from its centre of mass, m: the centroid lies a
    quarter of the height above the base (as :class:`tumble.mass.Cone` places it; Meriam &
    Kraige, *Engineering Mechanics: Dynamics*, Table D/4)."""
    return -part.height / 4, 3 * part.height / 4


def mesh_vertices_about_com(part: Part) -> np.ndarray:
    """A mesh part's vertices in its own frame about its own centre of mass, m."""
    return np.asarray(part.mesh.vertices, float) - part._com_local


def to_design(part: Part, points: np.ndarray) -> np.ndarray:
    """Points of a part's own frame (about its centre of mass) in the design frame, m."""
    return points @ part.orientation.as_matrix().T + np.asarray(part.com)


def part_lines(part: Part, n: int = 32) -> list[np.ndarray]:
    """Polylines of a part in the design frame (m), each an array of shape (k, 3).

    Examples
    --------
    >>> import tumble
    >>> from tumble.viz.scene import part_lines
    >>> crossbar = tumble.t_handle().parts[1]  # a rod of 1 m along x, its centre 0.5 m up
    >>> part_lines(crossbar)[0].round(12).tolist()
    [[-0.5, 0.0, 0.5], [0.5, 0.0, 0.5]]
    """
    return [to_design(part, pts) for pts in _local_lines(part, n)]


def body_lines(body: Body, n: int = 32) -> list[tuple[np.ndarray, bool]]:
    """Polylines of every part, design frame, relative to the body's COM (m).

    Returns ``(points, removed)`` pairs; ``removed`` marks subtracted material (drawn dashed).

    Examples
    --------
    >>> import tumble
    >>> from tumble.viz.scene import body_lines
    >>> lines = body_lines(tumble.t_handle())  # about the COM, 0.25 m up the shaft
    >>> len(lines), lines[0][0].tolist(), lines[0][1]
    (2, [[0.0, 0.0, -0.75], [0.0, 0.0, 0.25]], False)
    """
    com = np.asarray(body.com)
    return [(pts - com, p.subtract) for p in body.parts for pts in part_lines(p, n)]


def body_size(body: Body) -> float:
    """Largest distance of a drawn point from the COM, m (for axis limits and arrow lengths).

    Examples
    --------
    >>> import tumble
    >>> from tumble.viz.scene import body_size
    >>> body_size(tumble.t_handle())  # the shaft's foot, 0.75 m below the COM
    0.75
    """
    pts = np.concatenate([pts for pts, _ in body_lines(body, 8)])
    return float(np.max(np.linalg.norm(pts, axis=1))) or 1.0


def arrow_scale(vectors: ArrayLike, size: float) -> float:
    """Factor that draws the longest of ``vectors`` (shape (n, 3)) at 0.9 ``size``; 0 if all zero.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.viz.scene import arrow_scale
    >>> arrow_scale([[0.0, 3.0, 4.0], [1.0, 0.0, 0.0]], size=1.0)  # the longest (5) drawn 0.9 long
    0.18
    >>> arrow_scale(np.zeros((2, 3)), 1.0)
    0.0
    """
    peak = float(np.max(np.linalg.norm(vectors, axis=-1)))
    return 0.9 * size / peak if peak > 0 else 0.0


def frame_indices(samples: int, frames: int, name: str = "frames") -> np.ndarray:
    """At most ``frames`` sample indices, evenly spread, first and last included (``name``: the
    argument's name in the error).

    Examples
    --------
    >>> from tumble.viz.scene import frame_indices
    >>> frame_indices(101, 5).tolist()
    [0, 25, 50, 75, 100]
    >>> frame_indices(3, 10).tolist()  # never more than the samples
    [0, 1, 2]
    """
    if isinstance(frames, bool) or not isinstance(frames, (int, np.integer)) or not 2 <= frames <= MAX_FRAMES:
        raise ValueError(f"{name} = {frames!r} must be a whole number from 2 to {MAX_FRAMES}")
    return np.unique(np.linspace(0, samples - 1, min(frames, samples)).astype(int))


#: Most animation frames of a GIF or the page (each frame is stored).
MAX_FRAMES = 2000

#: The largest turn between two frames (rad) an animation shows as the motion: past half a turn the eye
#: takes the other way round, and the body seems to stand or spin backwards (a stroboscope's aliasing).
MAX_FRAME_TURN = np.pi


def frame_turn(t: np.ndarray, omega: np.ndarray, indices: np.ndarray) -> float:
    """The largest angle (rad) the body turns between consecutive frames ``indices``: ``int |omega| dt``
    over the samples between them (the trapezoid rule). Not the angle between the frames' attitudes,
    which is at most pi however far it turned. Above :data:`MAX_FRAME_TURN` an animation of them shows
    another motion than the run's.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.viz.scene import frame_turn
    >>> t = np.linspace(0.0, 10.0, 101)
    >>> omega = np.tile([0.0, 0.0, 2.0], (101, 1))   # 2 rad/s: 0.2 rad a sample
    >>> round(frame_turn(t, omega, np.arange(0, 101, 10)), 6), round(frame_turn(t, omega, np.arange(0, 101, 25)), 6)
    (2.0, 5.0)
    """
    rate = np.linalg.norm(np.asarray(omega, float), axis=1)
    turned = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(np.asarray(t, float)))])
    at = turned[np.asarray(indices)]
    return float(np.max(np.diff(at))) if len(at) >= 2 else 0.0


def check_run(traj: object, name: str = "trajectory") -> None:
    """Refuse, in one line, anything but a :class:`~tumble.dynamics.Trajectory` with samples.

    Examples
    --------
    >>> import tumble
    >>> from tumble.viz.scene import check_run
    >>> check_run(tumble.simulate(tumble.t_handle(), [0.0, 0.0, 1.0], t_end=1.0, samples=5))  # fine: nothing
    >>> check_run(tumble.t_handle())
    Traceback (most recent call last):
    ...
    ValueError: trajectory = Body object must be a tumble Trajectory (what tumble.simulate returns)
    """
    if not isinstance(traj, Trajectory):
        raise ValueError(f"{name} = {type(traj).__name__} object must be a tumble Trajectory (what tumble.simulate "
                         "returns)")
    if len(traj) == 0:
        raise ValueError(f"{name} has no samples: there is nothing to draw")


def check_body_and_run(body: object, traj: object) -> None:
    """Refuse a body that is not the one simulated: the pictures draw the body's parts moved by
    the run's attitude, so they must share their principal moments (within
    :data:`~tumble.mass.INERTIA_RTOL` of the trace).

    Examples
    --------
    >>> import tumble
    >>> from tumble.viz.scene import check_body_and_run
    >>> run = tumble.simulate(tumble.t_handle(), [0.0, 0.0, 1.0], t_end=1.0, samples=5)
    >>> check_body_and_run(tumble.t_handle(), run)  # the body simulated: nothing
    >>> check_body_and_run(tumble.iss_t_handle(), run)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: body = ... is not the body of this trajectory: its principal moments ... kg m^2 differ from the run's [0.125, 0.3125, 0.4375]
    """
    check_run(traj)
    if not isinstance(body, Body):
        raise ValueError(f"body = {type(body).__name__} object must be the tumble Body that was simulated: a "
                         "Trajectory holds the motion and the principal moments, not the parts drawn")
    tol = INERTIA_RTOL * float(np.sum(traj.moments))
    if not np.allclose(body.principal_moments, traj.moments, rtol=0.0, atol=tol):
        raise ValueError(f"body = {body!r} is not the body of this trajectory: its principal moments "
                         f"{body.principal_moments.tolist()} kg m^2 differ from the run's {traj.moments.tolist()}")


def frames_advice(t: np.ndarray, omega: np.ndarray) -> str:
    """What gives a page of a run sampled at ``t`` (s) with rates ``omega`` (rad/s, shape ``(n, 3)``)
    frames less than :data:`MAX_FRAME_TURN` apart: a frame is a sample, so every ``k``-th sample with
    ``k`` samples' turn under it (5 % to spare), more samples where one sample's turn passes it, and a
    shorter ``--t-end`` where that takes more than :data:`MAX_FRAMES` (the command line's words).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.viz.scene import frames_advice
    >>> t = np.linspace(0.0, 20.0, 500)
    >>> frames_advice(t, np.tile([0.0, 57.0, 0.0], (500, 1)))   # 2.3 rad a sample: every sample, one frame each
    'give --frames 500 or more'
    >>> frames_advice(t, np.tile([0.0, 573.0, 0.0], (500, 1)))[:73]
    'the page holds at most 2000 frames: give a shorter --t-end (at most about'
    """
    n = len(t)
    per_sample = frame_turn(t, omega, np.arange(n)) * 1.05
    if per_sample < MAX_FRAME_TURN:
        samples, frames = n, math.ceil((n - 1) / math.floor(MAX_FRAME_TURN / per_sample)) + 1
    else:
        samples = frames = math.ceil((n - 1) * per_sample / MAX_FRAME_TURN) + 1
    if frames <= MAX_FRAMES:
        return f"give --frames {frames}{f' and --samples {samples}' if samples > n else ''} or more"
    span = float(t[-1] - t[0]) * (MAX_FRAMES - 1) / ((n - 1) * per_sample / MAX_FRAME_TURN)  # the turn: ~ span
    # a frame a sample: more samples than frames leave uneven gaps of two or three samples between them
    return (f"the page holds at most {MAX_FRAMES} frames: give a shorter --t-end (at most about {span:.3g} s with "
            f"--frames {MAX_FRAMES}{f' and --samples {MAX_FRAMES}' if n != MAX_FRAMES else ''})")
