"""The interactive page of a fit: the fitted body replaying a chosen flight (``tumble view DIR``).

The page is :mod:`tumble.viz.page`'s (one self-contained HTML file, plotly.js inlined), its
first run the first flight; ``assets/fitview.js`` adds a selector of the used flights and plays
the chosen one (``tumbleViewer.setRun``): the fitted body as a uniform box of the fitted ratios
(:func:`tumble.commands.view_fit.fit_box`) in the ground frame and the body frame, omega(t) of
the fit's model (lines) with the measured rates (dots), both in the principal frame, and the
polhode on the momentum sphere: the sphere ``|L| = |L(start)|``, the energy ellipsoid of the
flight's start, their intersection (the torque-free polhode through the start,
:func:`tumble.viz.phase.polhode`), the separatrices, and the flight's L in the body frame
traced on the sphere (its direction; with drag ``|L|`` falls, by the share the page states).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from .._html import fmt
from ..analysis.fit.flightmodel import FlightModel
from ..dynamics import Trajectory
from ..io.atomic import atomic_write_text
from ..mass import Body
from .page import DIGITS, _rounded, page_html
from .phase import polhode, separatrices

__all__ = ["fit_page_data", "write_fit_page"]

#: Points of the drawn polhode and of each separatrix.
POLHODE_POINTS = 240
#: The drawn box is at least this share of its longest edge thick (a planar body is a plate).
MIN_THICKNESS = 0.01


class FlightReplayLike(Protocol):
    """What the page needs of a replayed flight (:class:`tumble.commands.view_fit.FlightReplay`)."""

    model: FlightModel
    input: str
    body: Body
    run: Trajectory
    t: np.ndarray
    measured: np.ndarray | None
    note: str


def _flight(r: FlightReplayLike, number: int, frames: int) -> dict[str, Any]:
    m, run = r.model, r.run
    I = np.asarray(run.moments, float)
    L = I * run.omega  # body frame, units of I3 rad/s
    L0 = float(np.linalg.norm(L[0]))
    size = np.array(r.body.parts[0].size, float) / 2.0  # half-sizes along the principal axes (the box is built so)
    drawn = np.maximum(size, MIN_THICKNESS * size.max())
    norms = np.linalg.norm(L, axis=1)
    trace = L * (L0 / np.where(norms > 0, norms, 1.0))[:, None]
    where = f"{r.input}, {m.start:.2f} to {m.end:.2f} s" + ("" if m.toss is None else f" (toss {m.toss + 1})")
    return {
        "label": f"flight {number}: {where}", "input": r.input, "toss": m.toss,
        "start": m.start, "end": m.end, "ratios": m.ratios.tolist(), "drag": m.drag,
        "drag_coefficients": m.drag_coefficients.tolist(), "moments": I.tolist(), "box": drawn.tolist(),
        "frames": int(frames), "torque_free": bool(run.torque_free),
        "t": _rounded(run.t, 10), "quat": _rounded(run.quat, 9), "omega": _rounded(run.omega, 9),
        "measured": None if r.measured is None else _rounded(r.measured, DIGITS + 1),
        "residual_rms": None if r.measured is None else float(np.sqrt(np.mean((r.measured - run.omega) ** 2))),
        "L_norm": L0, "L_drop": float(1.0 - norms[-1] / L0) if L0 > 0 else 0.0,
        "energy2": float(np.sum(I * run.omega[0] ** 2)),
        "polhode": _rounded(polhode(I, run.omega[0], POLHODE_POINTS), 9),
        "separatrices": [_rounded(c, 7) for c in separatrices(I, L0, POLHODE_POINTS)] if L0 > 0 and I[0] < I[1] < I[2]
        else [],
        "trace": _rounded(trace, 9),
        "note": r.note,
    }


def fit_page_data(replays: Sequence[FlightReplayLike], frames: int = 150) -> dict[str, Any]:
    """What ``assets/fitview.js`` plays, JSON-ready: ``flights``, one entry per replayed flight.

    Each entry: ``label``, ``input``, ``toss``, ``start``/``end`` (s, the recording's clock),
    ``ratios``, ``drag``, ``drag_coefficients``, ``moments`` (``(I1/I3, I2/I3, 1)`` kg m^2 of the
    drawn box), ``box`` (its drawn half-sizes along the principal axes, m; at least
    :data:`MIN_THICKNESS` of the longest edge thick), ``frames``, ``torque_free``; at the flight's
    sample times ``t`` (s from its first sample): ``quat`` (principal -> world), ``omega`` (the
    fit's model, principal frame, rad/s) and ``measured`` (the gyroscope's samples, principal
    frame, bias removed, or None), ``residual_rms`` (rad/s); the polhode picture: ``L_norm``
    (``|L|`` at the start, kg m^2/s with ``I3 = 1 kg m^2``), ``energy2`` (twice the kinetic
    energy at the start, J), ``polhode`` (the torque-free polhode through the start: on the
    sphere and the ellipsoid), ``separatrices``, ``trace`` (L(t), body frame, scaled onto the
    sphere) and ``L_drop`` (the share of ``|L|`` lost over the flight); ``note``.

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> from tumble.analysis.fit.flightmodel import FlightModel
    >>> from tumble.commands.view_fit import fit_box, replay_flight
    >>> from tumble.viz.fit_page import fit_page_data
    >>> m = FlightModel(2.0, 3.0, 2.0, [0.3, 0.8], [0.5, 9.0, 0.4], "none", [0.0] * 3, [0.0] * 3, [0.0] * 3)
    >>> t = np.linspace(2.0, 3.0, 101)
    >>> r = SimpleNamespace(model=m, input="toss.csv", body=fit_box(m.ratios), run=replay_flight(m, t), t=t,
    ...                     measured=None, note="measured rates not shown: not found")
    >>> flight, = fit_page_data([r])["flights"]
    >>> flight["label"], len(flight["t"]), flight["omega"][0], flight["L_drop"] < 1e-9
    ('flight 1: toss.csv, 2.00 to 3.00 s', 101, [0.5, 9.0, 0.4], True)
    >>> P, I = np.array(flight["polhode"]), np.array(flight["moments"])
    >>> bool(np.allclose(np.linalg.norm(P, axis=1), flight["L_norm"])), bool(np.allclose(np.sum(P**2 / I, axis=1), flight["energy2"]))
    (True, True)
    """
    if not replays:
        raise ValueError("replays = []: a fit's page needs at least one flight")
    return {"flights": [_flight(r, k + 1, frames) for k, r in enumerate(replays)]}


def _title(replays: Sequence[FlightReplayLike]) -> str:
    inputs = list(dict.fromkeys(r.input for r in replays))
    x, y = replays[0].model.ratios
    shared = all(np.allclose(r.model.ratios, (x, y)) for r in replays)
    ratios = f"I1/I3 = {fmt(x)}, I2/I3 = {fmt(y)}" if shared else "each flight's own ratios"
    where = inputs[0] if len(inputs) == 1 else f"{len(inputs)} recordings"
    n = len(replays)
    return f"fit of {where}: {n} flight{'' if n == 1 else 's'} replayed by the fitted body ({ratios})"


def write_fit_page(replays: Sequence[FlightReplayLike], path: str | os.PathLike[str], *, frames: int = 150,
                   title: str | None = None) -> Path:
    """Write the fit's page (module docstring) to ``path``, whole or not at all; returns the path.

    ``frames``: most animation frames per flight (2 to :data:`tumble.viz.scene.MAX_FRAMES`);
    the omega(t) curves keep every sample.

    Examples
    --------
    >>> import json, re, tempfile
    >>> import numpy as np
    >>> from pathlib import Path
    >>> from types import SimpleNamespace
    >>> from tumble.analysis.fit.flightmodel import FlightModel
    >>> from tumble.commands.view_fit import fit_box, replay_flight
    >>> from tumble.viz.fit_page import write_fit_page
    >>> m = FlightModel(2.0, 3.0, 2.0, [0.3, 0.8], [0.5, 9.0, 0.4], "none", [0.0] * 3, [0.0] * 3, [0.0] * 3)
    >>> t = np.linspace(2.0, 3.0, 101)
    >>> r = SimpleNamespace(model=m, input="toss.csv", body=fit_box(m.ratios), run=replay_flight(m, t), t=t,
    ...                     measured=None, note="")
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     html = write_fit_page([r], Path(folder) / "toss.html", frames=20).read_text(encoding="utf-8")
    >>> data = json.loads(re.search(r'<script type="application/json" id="tumble-data">(.*?)</script>', html, re.S).group(1))
    >>> len(data["fit"]["flights"]), data["title"]
    (1, 'fit of toss.csv: 1 flight replayed by the fitted body (I1/I3 = 0.3, I2/I3 = 0.8)')
    """
    fit = fit_page_data(replays, frames)
    first = replays[0]
    html = page_html(first.body, first.run, frames=frames, title=title or _title(replays), live=False, fit=fit)
    path = Path(path)
    atomic_write_text(path, html)
    return path
