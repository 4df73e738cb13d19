"""Poinsot's picture of free rotation: polhodes on the momentum sphere and the herpolhode.

- **Polhode** (Landau & Lifshitz, *Mechanics*, sec. 37; Goldstein sec. 5.6): in the body frame,
  L moves on the intersection of the momentum sphere ``|L| = const`` with the energy ellipsoid
  ``L1^2/I1 + L2^2/I2 + L3^2/I3 = 2 E``. The family of such curves through one |L| circles the
  minor and the major axis; the two great circles ``L3 = +-k L1``,
  ``k^2 = (1/I1 - 1/I2) / (1/I2 - 1/I3)`` (energy ``|L|^2 / (2 I2)``) are the separatrices that
  divide them and meet at the unstable intermediate axis.
- **Herpolhode**: in the ground frame the tip of omega stays in the invariable plane
  ``omega . L = 2 E`` (at distance ``2 E / |L|`` from the fixed point) and traces the herpolhode.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..analysis import flip_interval
from ..dynamics import Trajectory
from ..dynamics.methods.exact import FreeRotation
from ..mass import moment_degeneracy
from ..typing import ArrayLike
from .plots import MAX_POINTS
from ._backend import figure_and_axes, legend_outside, new_figure, note_only
from .scene import check_run

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["PHASE_PORTRAITS", "figure_herpolhode", "figure_polhode", "phase_portrait_problem", "polhode", "polhode_family",
           "separatrices"]

#: The figures that picture a torque-free motion (a fixed L and energy).
PHASE_PORTRAITS = ("polhode", "herpolhode")


def phase_portrait_problem(traj: Trajectory) -> str | None:
    """Why the polhode and herpolhode cannot be drawn for ``traj``, or None if they can.

    Both picture the torque-free motion: the polhode lies on the momentum sphere and the energy
    ellipsoid, the herpolhode in the invariable plane normal to the fixed L. Under a torque L
    and the energy change, and a body at rest has no L to draw them about.

    Examples
    --------
    >>> import tumble
    >>> from tumble.viz.phase import phase_portrait_problem
    >>> body = tumble.t_handle()
    >>> phase_portrait_problem(tumble.simulate(body, [0.1, 10.0, 0.1], t_end=1.0, samples=5)) is None
    True
    >>> phase_portrait_problem(tumble.simulate(body, [0.0, 0.0, 0.0], t_end=1.0, samples=5))
    'the body is at rest (L = 0): there is no motion to picture'
    >>> push = tumble.ConstantTorque((0.0, 0.0, 0.1), "body")  # N m
    >>> phase_portrait_problem(tumble.simulate(body, [0.1, 10.0, 0.1], t_end=1.0, samples=5, torque=push))
    'a torque acts, so L and the energy change: they picture torque-free motion only'
    """
    if not traj.torque_free:
        return "a torque acts, so L and the energy change: they picture torque-free motion only"
    if not traj.rigid:
        return "rotors or a damper move inside the body: they picture a single rigid body only"
    if not traj.angular_momentum_norm[0] > 0:
        return "the body is at rest (L = 0): there is no motion to picture"
    return None


def polhode_family(moments: ArrayLike, L_norm: float, count: int = 9, points: int = 240) -> list[np.ndarray]:
    """Closed polhodes through one |L| (kg m^2/s), body frame; each of shape (points, 3).

    Starting points ``|L| (cos b, 0, sin b)`` sweep the energy from ``|L|^2/(2 I1)`` (b = 0) to
    ``|L|^2/(2 I3)`` (b = pi/2); each curve is one period of the exact motion, drawn with its
    mirror image ``-L``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.viz.phase import polhode_family
    >>> I = np.array([0.125, 0.3125, 0.4375])  # the T-handle, kg m^2
    >>> curves = polhode_family(I, 2.0, count=4, points=60)  # |L| = 2 kg m^2/s
    >>> len(curves), curves[0].shape, bool(np.allclose(np.linalg.norm(curves, axis=2), 2.0))  # on the sphere
    (8, (60, 3), True)
    >>> energy = [np.sum(c**2 / I, axis=1) / 2 for c in curves]  # J
    >>> bool(np.allclose([np.ptp(e) for e in energy], 0.0, atol=1e-12)), [np.allclose(c[0], c[-1]) for c in curves[:2]]
    (True, [True, True])
    >>> [bool(e[0] > 2.0**2 / (2 * I[1])) for e in energy]  # above the separatrix: round the minor axis
    [True, True, True, True, False, False, False, False]
    """
    I = np.asarray(moments, float)
    k = np.sqrt((1 / I[0] - 1 / I[1]) / (1 / I[1] - 1 / I[2]))
    b_sep = np.arctan(k)  # the start point on the separatrix
    curves = []
    betas = np.concatenate([np.linspace(0.08, b_sep - 0.06, count // 2), np.linspace(b_sep + 0.06, np.pi / 2 - 0.08, count - count // 2)])
    for b in betas:
        L = polhode(I, L_norm * np.array([np.cos(b), 0.0, np.sin(b)]) / I, points)
        curves += [L, -L]
    return curves


def polhode(moments: ArrayLike, omega0: ArrayLike, points: int = 240) -> np.ndarray:
    """The polhode through ``omega0``: L = I omega in the body frame over one period of the exact
    torque-free motion (kg m^2/s, shape (points, 3)); it lies on the momentum sphere and the
    energy ellipsoid of ``omega0`` (module docstring).

    ``moments`` in kg m^2, ascending; ``omega0`` principal frame, rad/s. The period is twice
    :func:`tumble.analysis.flip_interval`; where it is infinite (on the separatrix, a spin about
    the intermediate axis, a sphere) twenty turns of ``|omega0|`` are drawn instead.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.viz.phase import polhode
    >>> I, w0 = np.array([0.3, 0.8, 1.0]), np.array([1.0, 9.0, 0.5])  # a toss about the intermediate axis
    >>> L = polhode(I, w0, points=50)
    >>> bool(np.allclose(np.linalg.norm(L, axis=1), np.linalg.norm(I * w0)))  # on the momentum sphere
    True
    >>> bool(np.allclose(np.sum(L**2 / I, axis=1), np.sum(I * w0**2))), bool(np.allclose(L[0], L[-1]))  # 2 E; closed
    (True, True)
    """
    from scipy.spatial.transform import Rotation

    I, w0 = np.asarray(moments, float), np.asarray(omega0, float)
    period = 2.0 * float(flip_interval(w0, I))
    if not np.isfinite(period) or period <= 0.0:
        period = 40.0 * np.pi / max(float(np.linalg.norm(w0)), 1e-300)
    t = np.linspace(0.0, period, points)
    return np.asarray(I * FreeRotation(I, w0, Rotation.identity()).omega(t), float)


def separatrices(moments: ArrayLike, L_norm: float, points: int = 361) -> list[np.ndarray]:
    """The two separatrix great circles on the momentum sphere, each of shape (points, 3).

    They lie on the energy ellipsoid of ``E = |L|^2 / (2 I2)``, J, and cross at ``+-|L| e2``,
    the intermediate axis (``L_norm`` in kg m^2/s, ``moments`` in kg m^2).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.viz.phase import separatrices
    >>> I = np.array([0.125, 0.3125, 0.4375])  # the T-handle, kg m^2
    >>> plus, minus = separatrices(I, 2.0, points=5)  # |L| = 2 kg m^2/s, a quarter turn apart
    >>> plus.round(4).tolist()
    [[0.0, 2.0, 0.0], [0.8, 0.0, 1.833], [0.0, -2.0, 0.0], [-0.8, -0.0, -1.833], [-0.0, 2.0, -0.0]]
    >>> [np.round(np.sum(c**2 / I, axis=1) / 2, 12).tolist() for c in (plus, minus)]  # 2^2 / (2 I2) = 6.4 J
    [[6.4, 6.4, 6.4, 6.4, 6.4], [6.4, 6.4, 6.4, 6.4, 6.4]]
    """
    I = np.asarray(moments, float)
    k = np.sqrt((1 / I[0] - 1 / I[1]) / (1 / I[1] - 1 / I[2]))
    s = np.linspace(0.0, 2.0 * np.pi, points)[:, None]
    e2 = np.array([0.0, 1.0, 0.0])
    out = []
    for sign in (1.0, -1.0):
        n = np.array([1.0, 0.0, sign * k]) / np.hypot(1.0, k)
        out.append(L_norm * (np.cos(s) * e2 + np.sin(s) * n))
    return out


def _first_samples(traj: Trajectory) -> tuple[int, str]:
    """How many samples a phase portrait draws (the first :data:`MAX_POINTS`) and the note if not all.

    A long run would fill its curve's region solid (the herpolhode is quasi-periodic); the
    first stretch shows the curve and how it winds.
    """
    n = min(len(traj), MAX_POINTS)
    if n == len(traj):
        return n, ""
    return n, f"\nthe first {traj.t[n - 1] - traj.t[0]:.4g} s of {traj.t[-1] - traj.t[0]:.4g} s ({n} of {len(traj)} samples)"


def _axes_3d(ax):
    """``(figure, ax)`` with ``ax`` a 3D axes: a new figure, the given 3D axes, or a 3D axes put in
    place of a given 2D one (same figure, same slot)."""
    if ax is None:
        fig = new_figure((7.4, 6.0))
        return fig, fig.add_subplot(projection="3d")
    if ax.name == "3d":
        return ax.figure, ax
    fig, spec = ax.figure, ax.get_subplotspec()
    if spec is None:
        raise ValueError("ax: the polhode is drawn in 3D; give an axes made with projection='3d'")
    ax.remove()
    return fig, fig.add_subplot(spec, projection="3d")


def figure_polhode(traj: Trajectory, *, ax: Axes | None = None, title: str | None = None) -> Figure:
    """L in the body frame on the momentum sphere (kg m^2/s), with its family of polhodes and separatrices.

    For a run that is not a torque-free motion of one rigid body, or a body at rest
    (:func:`phase_portrait_problem`), the figure says so in one line instead.

    Parameters
    ----------
    traj : Trajectory
    ax : matplotlib Axes, optional
        Draw here instead of on a new figure; a 2D axes is replaced by a 3D one in its place.
    title : str, optional
        The title (default: body and |L|).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import tumble
    >>> import numpy as np
    >>> from tumble.viz.phase import figure_polhode
    >>> run = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=2.0, samples=101)  # a flip
    >>> ax = figure_polhode(run).axes[0]
    >>> ax.name, ax.get_title(), [text.get_text() for text in ax.get_legend().get_texts()]
    ('3d', 'T-handle: polhodes on the momentum sphere |L| = 3.125 kg m$^2$/s', \
['polhodes through this |L|', 'separatrix', 'this run (exact)', 't = 0'])
    >>> line = next(line for line in ax.lines if line.get_label() == "this run (exact)")
    >>> bool(np.array_equal(np.array(line.get_data_3d()).T, run.angular_momentum))  # L in the body frame
    True
    >>> push = tumble.ConstantTorque((0.0, 0.0, 0.1), "body")  # N m: no polhode, a note instead
    >>> pushed = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=1.0, samples=5, torque=push)
    >>> [text.get_text()[:35] for text in figure_polhode(pushed).axes[0].texts]
    ['no polhode for this run: a torque a']
    """
    check_run(traj)
    fig, ax = _axes_3d(ax)
    problem = phase_portrait_problem(traj)
    if problem:
        note_only(ax, f"no polhode for this run: {problem}", title or f"{traj.body_name}: polhode")
        return fig
    I = traj.moments
    count, shown = _first_samples(traj)
    L = traj.angular_momentum[:count]
    R = float(traj.angular_momentum_norm[0])
    ax.computed_zorder = False  # draw in the order given: sphere, curves, this run, markers
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 37), np.linspace(0, np.pi, 19))
    ax.plot_wireframe(R * np.cos(u) * np.sin(v), R * np.sin(u) * np.sin(v), R * np.cos(v), color="0.88", lw=0.5,
                      zorder=0)
    if moment_degeneracy(I) == "asymmetric":
        for k, c in enumerate(polhode_family(I, R)):
            ax.plot(*c.T, color="tab:gray", lw=0.8, zorder=1, label="polhodes through this |L|" if k == 0 else None)
        for k, c in enumerate(separatrices(I, R)):
            ax.plot(*c.T, color="tab:red", lw=1.4, ls="--", zorder=2, label="separatrix" if k == 0 else None)
    ax.plot(*L.T, color="tab:blue", lw=2.4, zorder=3, label=f"this run ({traj.method})")
    ax.scatter(*L[0], color="k", edgecolor="w", s=40, zorder=5, depthshade=False, label="t = 0")
    for j, name in enumerate(("minor", "intermediate", "major")):
        tip = np.zeros(3)
        tip[j] = 1.25 * R
        ax.plot(*np.stack([-tip, tip]).T, color="k", lw=0.6, zorder=1)
        ax.text(*tip, f"$L_{j + 1}$ ({name})", fontsize=8, zorder=6)
    ax.set_box_aspect((1, 1, 1))
    for axis, j in zip("xyz", range(3)):
        getattr(ax, f"set_{axis}label")(rf"$L_{j + 1}$ (kg m$^2$/s)", fontsize=8)
        ax.locator_params(axis=axis, nbins=4)
    ax.tick_params(labelsize=7)
    ax.set_title((title or f"{traj.body_name}: polhodes on the momentum sphere |L| = {R:.4g} kg m$^2$/s") + shown,
                 fontsize=9)
    # in the corner, over the empty panes: a 3D axes' layout box leaves out a legend outside it
    ax.legend(loc="upper left", bbox_to_anchor=(-0.02, 1.0), fontsize=7, framealpha=0.9)
    return fig


def figure_herpolhode(traj: Trajectory, *, ax: Axes | None = None, title: str | None = None) -> Figure:
    """The tip of omega (rad/s) in the invariable plane, ground frame: Poinsot's construction.

    For a run that is not a torque-free motion of one rigid body, or a body at rest
    (:func:`phase_portrait_problem`), the figure says so in one line instead: under a torque
    there is no invariable plane.

    Parameters
    ----------
    traj : Trajectory
    ax : matplotlib Axes, optional
        Draw here instead of on a new figure.
    title : str, optional
        The title (default: body and the plane's height).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import tumble
    >>> from tumble.viz.phase import figure_herpolhode
    >>> run = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=2.0, samples=101)
    >>> ax = figure_herpolhode(run).axes[0]
    >>> ax.get_title().splitlines()[0], len(ax.lines[0].get_xdata())  # the tip of omega at every sample
    ('T-handle: herpolhode in the invariable plane', 101)
    >>> [text.get_text() for text in ax.get_legend().get_texts()][1:]
    ['t = 0', 'foot of L']
    >>> height = 2 * run.energy[0] / run.angular_momentum_norm[0]  # the plane's distance, 2 E / |L|, rad/s
    >>> f"omega . L/|L| = {height:.6g} rad/s" in ax.get_title()
    True
    """
    check_run(traj)
    fig, ax = figure_and_axes(ax, figsize=(7.4, 5.4))
    problem = phase_portrait_problem(traj)
    if problem:
        note_only(ax, f"no herpolhode for this run: {problem}", title or f"{traj.body_name}: herpolhode")
        return fig
    Lw = traj.angular_momentum_world[0]
    n = Lw / np.linalg.norm(Lw)
    across = "x" if abs(n[0]) < 0.9 else "y"  # a world axis not near L
    u = np.cross(n, [1.0, 0.0, 0.0] if across == "x" else [0.0, 1.0, 0.0])
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    height = traj.omega_world @ n  # = 2 E / |L|, constant without torque (over the whole run)
    count, shown = _first_samples(traj)
    w = traj.omega_world[:count]
    ax.plot(w @ u, w @ v, color="tab:purple", lw=1.0, zorder=2, label=r"tip of $\omega$ (rad/s)")
    ax.scatter([w[0] @ u], [w[0] @ v], color="k", edgecolor="w", s=40, zorder=5, label="t = 0")
    ax.scatter([0.0], [0.0], marker="+", color="k", s=80, linewidths=1.5, zorder=5, label="foot of L")
    ax.set_aspect("equal", adjustable="datalim")
    # u, v: two world axes in the invariable plane (u normal to L and the world x, or y where L is near x; v = L x u),
    # named on the axes (a teacher's walkthrough: u and v were defined nowhere)
    ax.set_xlabel(rf"$\omega \cdot u$, $u$ normal to $L$ and to the world {across} axis (rad/s)")
    ax.set_ylabel(r"$\omega \cdot v$, $v = \hat{L} \times u$ (rad/s)")
    spread = float(np.ptp(height))
    ax.set_title((title or f"{traj.body_name}: herpolhode in the invariable plane\n"
                  f"(plane at omega . L/|L| = {height[0]:.6g} rad/s, varies by {spread:.1e} rad/s)") + shown, fontsize=9)
    legend_outside(ax)
    return fig
