"""One self-contained interactive HTML page of a tumbling body (plotly, bundled, works offline).

Left: the body in the ground frame with its omega (red) and L (blue) arrows; right: the same
seen from the body, with the path of omega's tip; below: omega(t) with a moving time marker.
Play / pause, a time slider and speed buttons. The body is drawn from the scene description
(:mod:`tumble.viz.scene`) that the GIF animations use, so page and animation show the same body
(subtracted material dashed in both).
plotly.js is embedded in the file (no CDN): the page opens without a network.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..dynamics import Trajectory
from ..mass import AXIS_ROLES, Body
from ..io.atomic import atomic_path
from .scene import arrow_scale, body_lines, body_size, frame_indices

__all__ = ["write_page"]

_W, _L, _BODY = "#d62728", "#1f77b4", "#333333"


def _polyline(lines, R=None):
    """Concatenate polylines into x, y, z lists with None between them (one plotly trace)."""
    xs, ys, zs = [], [], []
    for pts in lines:
        q = pts if R is None else pts @ R.T
        xs += q[:, 0].tolist() + [None]
        ys += q[:, 1].tolist() + [None]
        zs += q[:, 2].tolist() + [None]
    return xs, ys, zs


def _arrow(tip):
    return [0.0, float(tip[0])], [0.0, float(tip[1])], [0.0, float(tip[2])]


def write_page(body: Body, traj: Trajectory, path, *, frames: int = 150, title: str | None = None) -> Path:
    """Write the interactive page to ``path`` (written to a temporary file, then renamed)."""
    try:
        import plotly.graph_objects as go
        from plotly.subplots import make_subplots
    except ImportError:  # pragma: no cover - depends on the environment
        raise ValueError("the interactive page needs plotly: pip install 'tumble[view]'") from None

    path = Path(path)
    drawn = body_lines(body)
    lines = [pts for pts, removed in drawn if not removed]
    holes = [pts for pts, removed in drawn if removed]  # subtracted material: dashed
    size = 1.25 * body_size(body)
    idx = frame_indices(len(traj), frames)
    rot = traj.design_attitude().as_matrix()
    w_world, L_world = traj.omega_world, traj.angular_momentum_world
    A = traj.principal_axes
    w_body, L_body = traj.omega @ A.T, traj.angular_momentum @ A.T  # design axes of the body
    sw, sL = arrow_scale(w_world, size), arrow_scale(L_world, size)

    fig = make_subplots(
        rows=2, cols=2, row_heights=[0.66, 0.34], horizontal_spacing=0.02, vertical_spacing=0.08,
        specs=[[{"type": "scene"}, {"type": "scene"}], [{"type": "xy", "colspan": 2}, None]],
        subplot_titles=("ground frame: the body tumbles, L stays fixed", "body frame: omega wanders, L with it",
                        "omega in the principal frame (rad/s)"),
    )
    k0 = int(idx[0])

    def dynamic(k):
        """The traces that change from frame to frame, in a fixed order."""
        tr = []
        x, y, z = _polyline(lines, rot[k])
        tr.append(go.Scatter3d(x=x, y=y, z=z, mode="lines", line=dict(color=_BODY, width=5), name="body", showlegend=False))
        x, y, z = _polyline(holes, rot[k])
        tr.append(go.Scatter3d(x=x, y=y, z=z, mode="lines", line=dict(color=_BODY, width=3, dash="dash"),
                               name="removed", showlegend=False))
        for vec, s, color, name in ((w_world[k], sw, _W, "omega"), (L_world[k], sL, _L, "L")):
            x, y, z = _arrow(vec * s)
            tr.append(go.Scatter3d(x=x, y=y, z=z, mode="lines+markers", marker=dict(size=[0, 5], color=color),
                                   line=dict(color=color, width=8), name=name, showlegend=False))
        for vec, s, color, name in ((w_body[k], sw, _W, "omega"), (L_body[k], sL, _L, "L")):
            x, y, z = _arrow(vec * s)
            tr.append(go.Scatter3d(x=x, y=y, z=z, mode="lines+markers", marker=dict(size=[0, 5], color=color),
                                   line=dict(color=color, width=8), name=name, showlegend=False))
        stride = max(1, len(traj) // 400)  # keep each frame small: at most ~400 path points
        path_tip = np.vstack([w_body[: k + 1 : stride], w_body[k]]) * sw
        tr.append(go.Scatter3d(x=path_tip[:, 0], y=path_tip[:, 1], z=path_tip[:, 2], mode="lines",
                               line=dict(color=_W, width=2), opacity=0.5, name="omega path", showlegend=False))
        t = float(traj.t[k])
        lim = float(np.max(np.abs(traj.omega))) * 1.05 or 1.0
        tr.append(go.Scatter(x=[t, t], y=[-lim, lim], mode="lines", line=dict(color="black", width=1), name="now", showlegend=False))
        return tr

    where = [(1, 1), (1, 1), (1, 1), (1, 1), (1, 2), (1, 2), (1, 2), (2, 1)]
    for trace, (r, c) in zip(dynamic(k0), where):
        fig.add_trace(trace, row=r, col=c)
    dynamic_indices = list(range(len(where)))
    for group, style in ((lines, dict(width=4)), (holes, dict(width=3, dash="dash"))):
        x, y, z = _polyline(group)
        fig.add_trace(go.Scatter3d(x=x, y=y, z=z, mode="lines", line=dict(color="#999999", **style), showlegend=False),
                      row=1, col=2)
    for j, color in enumerate(("#1f77b4", "#ff7f0e", "#2ca02c")):  # as in the matplotlib figures
        fig.add_trace(go.Scatter(x=traj.t, y=traj.omega[:, j], mode="lines", line=dict(color=color),
                                 name=f"omega_{j + 1} ({AXIS_ROLES[j]})"), row=2, col=1)

    fig.frames = [go.Frame(data=dynamic(int(k)), traces=dynamic_indices, name=str(n)) for n, k in enumerate(idx)]

    def play(duration):
        return [None, {"frame": {"duration": duration, "redraw": True}, "transition": {"duration": 0},
                       "fromcurrent": True, "mode": "immediate"}]

    axis = dict(range=[-size, size], autorange=False, showbackground=False)
    scene = dict(xaxis=dict(axis, title="x"), yaxis=dict(axis, title="y"), zaxis=dict(axis, title="z"), aspectmode="cube")
    fig.update_layout(
        title=dict(text=title or f"{traj.body_name}: {traj.method}, {traj.t[-1]:g} s", y=0.985),
        height=900, margin=dict(l=10, r=10, t=170, b=10), scene=scene, scene2=scene,
        legend=dict(orientation="h", x=0.0, y=0.3),
        updatemenus=[dict(type="buttons", direction="left", x=0.0, y=1.2, xanchor="left", yanchor="top", showactive=True, buttons=[
            dict(label="Play", method="animate", args=play(60)),
            dict(label="Pause", method="animate", args=[[None], {"frame": {"duration": 0, "redraw": False}, "mode": "immediate"}]),
            dict(label="speed x0.5", method="animate", args=play(120)),
            dict(label="x1", method="animate", args=play(60)),
            dict(label="x2", method="animate", args=play(30)),
            dict(label="x4", method="animate", args=play(15)),
        ])],
        sliders=[dict(active=0, x=0.36, y=1.24, yanchor="top", len=0.64, currentvalue=dict(prefix="t = ", suffix=" s"),
                      steps=[dict(label=f"{traj.t[k]:.2f}", method="animate",
                                  args=[[str(n)], {"mode": "immediate", "frame": {"duration": 0, "redraw": True}}])
                             for n, k in enumerate(idx)])],
    )
    fig.update_xaxes(title_text="t (s)", row=2, col=1)
    with atomic_path(path) as tmp:
        fig.write_html(tmp, include_plotlyjs=True, full_html=True, auto_play=False,
                       config={"displaylogo": False, "topojsonURL": ""})
    return path
