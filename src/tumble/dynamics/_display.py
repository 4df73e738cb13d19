"""Short plain repr and Jupyter's rich HTML display of a trajectory.

The HTML is a summary table and a small omega(t) plot drawn as inline SVG with numpy alone:
the physics layers may not import matplotlib (the import-linter contract in pyproject.toml).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Protocol

import numpy as np

from .._html import escape_text, fmt, html_table, result_html, short_name, vec
from ..typing import ArrayLike, FloatArray, IntArray

__all__ = ["SVG_POINTS", "batch_html", "batch_repr", "omega_svg", "subsample", "trajectory_html", "trajectory_repr"]

#: Most points per curve in the omega(t) plot: enough for the eye, small in a notebook file.
SVG_POINTS = 300
#: The matplotlib default colours, as in tumble's figures and page (omega_1, omega_2, omega_3).
COLORS = ("#1f77b4", "#ff7f0e", "#2ca02c")


class _Batch(Protocol):
    """What the display reads of a :class:`~tumble.dynamics.batch.BatchTrajectory`: its samples
    ``t`` (s), its method and whether it ran torque-free.

    A protocol, not the class: :mod:`tumble.dynamics.batch` and :mod:`tumble.dynamics.trajectory`
    import this module, and the import graph has no circles.
    """

    @property
    def t(self) -> FloatArray: ...
    @property
    def method(self) -> str: ...
    @property
    def torque_free(self) -> bool: ...
    @property
    def auto(self) -> bool: ...
    def __len__(self) -> int: ...


class _Bodies(_Batch, Protocol):
    """What :func:`batch_html` reads besides: each body's principal moments (kg m^2) and ``omega``."""

    @property
    def moments(self) -> FloatArray: ...
    @property
    def omega(self) -> FloatArray: ...


class _Run(_Batch, Protocol):
    """What the display reads of a :class:`~tumble.dynamics.trajectory.Trajectory` (SI units)."""

    @property
    def body_name(self) -> str: ...
    @property
    def omega(self) -> FloatArray: ...
    @property
    def energy(self) -> FloatArray: ...
    @property
    def angular_momentum_norm(self) -> FloatArray: ...
    @property
    def drift(self) -> Mapping[str, float | None]: ...
    @property
    def rigid(self) -> bool: ...
    @property
    def method_label(self) -> str: ...
    @property
    def rotor_axial_moments(self) -> FloatArray | None: ...
    @property
    def damper_inertia(self) -> float | None: ...
    @property
    def damper_omega(self) -> FloatArray | None: ...
    @property
    def dissipated(self) -> FloatArray | None: ...


def _extras(traj: _Run) -> list[str]:
    extras: list[str] = []
    if traj.rotor_axial_moments is not None:
        k = len(traj.rotor_axial_moments)
        extras.append(f"{k} rotor{'' if k == 1 else 's'}")
    if traj.damper_omega is not None:
        extras.append("damper")
    return extras


def _run_repr(
    kind: str, first: str, t: FloatArray, method: object, torque_free: bool, extras: Sequence[str] = ()
) -> str:
    """``Kind(first, method, n samples, t = a..b s, torque-free, extras...)``."""
    n = len(t)
    span = f"t = {fmt(t[0])}..{fmt(t[-1])} s" if n else "no samples"
    parts = [first, str(method)[:20], f"{n} sample{'' if n == 1 else 's'}", span,
             "torque-free" if torque_free else "torqued", *extras]
    return f"{kind}({', '.join(parts)})"


def trajectory_repr(traj: _Run) -> str:
    """``Trajectory('T-handle', dop853, 500 samples, t = 0..20 s, torque-free)``.

    Examples
    --------
    >>> import tumble
    >>> from tumble.dynamics._display import trajectory_repr
    >>> trajectory_repr(tumble.simulate(tumble.t_handle(), [0.0, 0.0, 1.0], t_end=20.0, samples=500))
    "Trajectory('T-handle', exact (auto), 500 samples, t = 0..20 s, torque-free)"
    """
    return _run_repr("Trajectory", short_name(traj.body_name), traj.t, traj.method_label,
                     traj.torque_free, _extras(traj))


def batch_repr(batch: _Batch) -> str:
    """``BatchTrajectory(1000 bodies, exact (auto), 500 samples, t = 0..20 s, torque-free)``.

    Examples
    --------
    >>> import tumble
    >>> from tumble.dynamics._display import batch_repr
    >>> batch_repr(tumble.simulate_batch([1.0, 2.0, 3.0], [[1.0, 0.0, 0.0]] * 3, t_end=2.0, samples=5))
    'BatchTrajectory(3 bodies, exact (auto), 5 samples, t = 0..2 s, torque-free)'
    """
    n = len(batch)
    return _run_repr("BatchTrajectory", f"{n} bod{'y' if n == 1 else 'ies'}", batch.t,
                     f"{batch.method} (auto)" if batch.auto else batch.method, batch.torque_free)


def batch_html(batch: _Bodies) -> str:
    """A batch's size, method and ranges as an HTML table (Jupyter's ``_repr_html_``).

    Examples
    --------
    >>> import tumble
    >>> from tumble.dynamics._display import batch_html
    >>> page = batch_html(tumble.simulate_batch([1.0, 2.0, 3.0], [[1.0, 0.0, 0.0]] * 3, t_end=2.0, samples=5))
    >>> page.startswith("<div><table"), "0 to 2 s" in page
    (True, True)
    """
    n, t = len(batch), batch.t
    rows: list[tuple[str, object]] = [("bodies", n), ("method", batch.method), ("samples", len(t))]
    if len(t):
        rows.append(("time span", f"{fmt(t[0])} to {fmt(t[-1])} s"))
    rows.append(("external torque", "none (torque-free)" if batch.torque_free else "yes"))
    if n:
        moments = np.asarray(batch.moments, float).reshape(n, -1)
        rows.append(("principal moments, smallest to largest", f"{fmt(moments.min())} to {fmt(moments.max())} kg m^2"))
        if len(t):
            rate = np.linalg.norm(np.asarray(batch.omega, float)[:, 0], axis=-1)
            rows.append(("|omega(0)|, smallest to largest", f"{fmt(rate.min())} to {fmt(rate.max())} rad/s"))
    return result_html("BatchTrajectory", rows)


def subsample(n: int, points: int = SVG_POINTS) -> IntArray:
    """At most ``points`` sample indices spread evenly over ``range(n)``, first and last included.

    Examples
    --------
    >>> from tumble.dynamics._display import subsample
    >>> subsample(5).tolist(), subsample(1001, points=5).tolist()
    ([0, 1, 2, 3, 4], [0, 250, 500, 750, 1000])
    """
    if n <= points:
        return np.arange(n)
    return np.unique(np.linspace(0, n - 1, points).round().astype(int))


def _span(lo: float, hi: float) -> tuple[float, float]:
    """A drawable range: a zero-width one (a body at rest, one sample) widened around its value."""
    if hi > lo:
        return lo, hi
    pad = abs(lo) * 0.5 or 1.0
    return lo - pad, hi + pad


def omega_svg(t: ArrayLike, omega: ArrayLike, *, width: int = 420, height: int = 150, points: int = SVG_POINTS) -> str:
    """omega_1, omega_2, omega_3 against t as an inline SVG picture (one polyline each).

    Parameters
    ----------
    t : array_like, shape (n,)
        Times, s.
    omega : array_like, shape (n, 3)
        Angular velocity, principal frame, rad/s.
    width, height : int
        Size of the picture in pixels.
    points : int
        Most points per polyline (the samples are thinned evenly, first and last kept).

    Returns
    -------
    str
        An ``<svg>`` element: the three curves, the line omega = 0 when in range, and the
        ranges of t and omega written at the axes.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics._display import omega_svg
    >>> t = np.linspace(0.0, 1.0, 50)
    >>> svg = omega_svg(t, np.column_stack([np.sin(t), np.cos(t), t]))
    >>> svg.startswith("<svg"), svg.count("<polyline")   # one line per component
    (True, 3)
    """
    t, omega = np.asarray(t, dtype=float), np.asarray(omega, dtype=float)
    idx = subsample(len(t), points)
    ts, ws = t[idx], omega[idx]
    left, right, top, bottom = 46.0, 8.0, 8.0, 20.0
    t0, t1 = _span(float(ts[0]), float(ts[-1])) if len(ts) else (0.0, 1.0)
    values = ws[np.isfinite(ws)]
    w0, w1 = _span(float(values.min()), float(values.max())) if values.size else (-1.0, 1.0)
    # fractions of the ranges first, pixels after: no overflow for tiny (subnormal) ranges; a value
    # beyond double range (never a physical one) is left out instead of warning
    with np.errstate(over="ignore", invalid="ignore"):
        px = left + (ts - t0) / (t1 - t0) * (width - left - right)
        py = top + (w1 - ws) / (w1 - w0) * (height - top - bottom)
        y_zero = top + w1 / (w1 - w0) * (height - top - bottom)
    shown = np.isfinite(py) & np.isfinite(px)[:, None]

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'viewBox="0 0 {width} {height}" font-size="10" font-family="sans-serif">',
           f'<rect x="{left}" y="{top}" width="{width - left - right}" height="{height - top - bottom}" '
           f'fill="none" stroke="#bbb"/>']
    if w0 < 0 < w1 and np.isfinite(y_zero):
        out.append(f'<line x1="{left}" x2="{width - right}" y1="{y_zero:.2f}" y2="{y_zero:.2f}" stroke="#ccc"/>')
    for j, color in enumerate(COLORS):
        ok = shown[:, j]
        xy = " ".join(f"{a:.2f},{b:.2f}" for a, b in zip(px[ok], py[ok, j]))
        out.append(f'<polyline fill="none" stroke="{color}" stroke-width="1.2" points="{xy}">'
                   f"<title>omega_{j + 1} (rad/s)</title></polyline>")
    labels = (
        (left - 3, top + 8, "end", f"{fmt(w1, 3)}"),
        (left - 3, height - bottom, "end", f"{fmt(w0, 3)}"),
        (left, height - 6, "start", f"t = {fmt(t0, 3)} s"),
        (width - right, height - 6, "end", f"{fmt(t1, 3)} s"),
    )
    out += [f'<text x="{x:.1f}" y="{yy:.1f}" text-anchor="{anchor}">{escape_text(text)}</text>'
            for x, yy, anchor, text in labels]
    key = "".join(f'<tspan fill="{color}">omega_{j + 1}</tspan>, ' for j, color in enumerate(COLORS))
    out.append(f'<text x="{(left + width - right) / 2:.1f}" y="{height - 6:.1f}" text-anchor="middle">'
               f'{key}rad/s, principal frame</text>')
    out.append("</svg>")
    return "".join(out)


def _drift_text(value: float | None) -> str:
    return "n/a (starts at zero)" if value is None else f"{value:.2e}"


def trajectory_html(traj: _Run) -> str:
    """A run's summary table and its omega(t) as HTML (Jupyter's ``_repr_html_``).

    Examples
    --------
    >>> import tumble
    >>> from tumble.dynamics._display import trajectory_html
    >>> html = trajectory_html(tumble.simulate(tumble.t_handle(), [0.1, 5.0, 0.1], t_end=2.0, samples=50))
    >>> "<svg" in html, "T-handle" in html
    (True, True)
    """
    n = len(traj)
    rows = [("body", traj.body_name), ("method", traj.method_label), ("samples", n)]
    if n:
        rows += [
            ("time span", f"{fmt(traj.t[0])} to {fmt(traj.t[-1])} s"),
            ("external torque", "none (torque-free)" if traj.torque_free else "yes"),
            ("omega(0), principal frame", f"{vec(traj.omega[0])} rad/s"),
            ("energy E(0)", f"{fmt(traj.energy[0], 6)} J"),
            ("|L|(0)", f"{fmt(traj.angular_momentum_norm[0], 6)} kg m^2/s"),
        ]
        word = "drift" if traj.torque_free else "change (a torque acts)"
        drift = traj.drift
        # with rotors or a damper the balance E - motor work + dissipated is what is conserved (Trajectory.drift)
        energy = "energy" if traj.rigid else "energy balance E - W_motor + E_dissipated"
        rows += [(f"{energy} {word}, max |E - E0| / E0", _drift_text(drift["energy"])),
                 (f"|L| {word}, max ||L| - |L0|| / |L0|", _drift_text(drift["L_norm"])),
                 (f"L_world {word}, max |L_w - L_w(0)| / |L0|", _drift_text(drift["L_world"]))]
    if traj.rotor_axial_moments is not None:
        rows.append(("rotors, axial moments", f"{vec(traj.rotor_axial_moments)} kg m^2"))
    if traj.damper_inertia is not None:
        rows.append(("damper moment J", f"{fmt(traj.damper_inertia, 6)} kg m^2"))
        if traj.dissipated is not None and n:
            rows.append(("energy dissipated by the damper", f"{fmt(traj.dissipated[-1], 6)} J"))
    table = html_table(rows, caption=f"Trajectory: {traj.body_name}")
    return f'<div>{table}{omega_svg(traj.t, traj.omega) if n else ""}</div>'
