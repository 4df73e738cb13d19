"""One self-contained interactive HTML page of a tumbling body (plotly.js inlined, works offline).

Top: play / pause, a time slider and speed buttons, and (live mode) a form to run a new motion
in the browser. Left: the body, shaded, in the ground frame with its omega (red) and L (blue)
arrows over an orientation grid (the invariable plane's direction, normal to L, for a torque-free
run; else the ground); right: the same seen from the body, with the path of omega's tip; below:
omega(t) with a moving time marker.

The body's triangles (:mod:`tumble.viz.surfaces`) are stored once; each frame holds only the
time, the design-frame attitude quaternion and the world-frame omega and L, as compact JSON in
``<script id="tumble-data">``. A small hand-written script (``assets/viewer.js``) turns the
vertices frame by frame with ``Plotly.restyle``. Live mode inlines ``assets/splitting.js`` and
``assets/live.js`` (when installed) before ``viewer.js``; see the head of ``viewer.js`` for the
interface they use (``window.tumbleViewer``, the ``tumble:ready`` event). A closed-loop run
(``control``: :mod:`tumble.viz.control_page`) inlines ``assets/control.js`` there instead: the
reaction wheels on the body, the commanded torque and dipole arrows, a readout and a time plot
of the attitude error or ``|omega|`` (``window.tumbleExtra``, also described in ``viewer.js``).
A fit's flights (``fit``: :mod:`tumble.viz.fit_page`) inline ``assets/fitview.js``: a flight
selector that plays each with ``tumbleViewer.setRun``, the measured rates, the polhode.
"""

from __future__ import annotations

import os
from importlib import resources
from pathlib import Path

import numpy as np

from .._html import escape_text, script_json
from .._optional import optional_import
from ..dynamics import Trajectory
from ..io.atomic import atomic_write_text
from ..mass import Body, Box, t_handle
from .scene import check_body_and_run, frame_indices
from .surfaces import body_surfaces

__all__ = ["BRODY_RACKET_MOMENTS", "CURVE_POINTS", "live_presets", "page_data", "page_html", "write_page"]

#: Most points drawn per omega(t) curve (and in the omega path); longer runs are subsampled.
CURVE_POINTS = 4000
#: Vertices are stored as integers in units of the body's size / GRID (m).
GRID = 20000
#: Significant digits of the per-frame numbers and of the curves.
DIGITS = 5


def _rounded(a, digits: int = DIGITS):
    """Nested lists of floats with at most ``digits`` significant digits (compact JSON)."""
    a = np.asarray(a, dtype=float)
    flat = [float(f"{x:.{digits}g}") for x in a.ravel()]
    return np.array(flat).reshape(a.shape).tolist()


def _curve_indices(samples: int) -> tuple[int, np.ndarray]:
    """The stride and the kept indices of a curve of ``samples`` samples: every ``stride``-th, at
    most about :data:`CURVE_POINTS`, the last one kept."""
    stride = max(1, -(-samples // CURVE_POINTS))
    return int(stride), np.unique(np.append(np.arange(0, samples, stride), samples - 1))


def _merged(surfaces, unit: float):
    """One triangle list of several surfaces: integer vertices (units of ``unit``), flat faces."""
    if not surfaces:
        return None
    verts, faces, offset = [], [], 0
    for v, f in surfaces:
        verts.append(v)
        faces.append(f + offset)
        offset += len(v)
    v = np.rint(np.concatenate(verts) / unit).astype(np.int64)
    return {"v": v.ravel().tolist(), "f": np.concatenate(faces).ravel().tolist()}


#: Brody's measured tennis racket, kg m^2 (1985, as quoted by Ashbaugh, Chicone & Cushman,
#: J. Dyn. Diff. Eq. 3 (1991) 67, footnote 4; docs/gallery/tennis-racket-twist.md).
BRODY_RACKET_MOMENTS = (0.00121, 0.01638, 0.01748)


def _tidy(values) -> list[float]:
    return [float(f"{x:.12g}") for x in values]  # readable in the form; round-off of the sums dropped


def live_presets() -> list[dict]:
    """The live mode's fixed presets: ``name``, ``moments`` (kg m^2), ``omega0`` (principal frame,
    rad/s) and ``mass`` (kg, sets only the size of the uniform box drawn for them).

    Examples
    --------
    >>> from tumble.viz.page import BRODY_RACKET_MOMENTS, live_presets
    >>> handle, plate, racket = live_presets()
    >>> handle["moments"], handle["omega0"], handle["mass"]  # the T-handle spun about its intermediate axis
    ([0.125, 0.3125, 0.4375], [0.1, 10.0, 0.1], 3.0)
    >>> racket["moments"] == list(BRODY_RACKET_MOMENTS), all(p["moments"] == sorted(p["moments"]) for p in (handle, plate, racket))
    (True, True)
    """
    handle = t_handle()
    plate = Body([Box(mass=1.0, size=(0.300, 0.295, 0.060))])
    return [
        {"name": "T-handle flip: the seed's handle about its intermediate axis (examples/seed_flip.toml)",
         "moments": _tidy(handle.principal_moments), "omega0": [0.1, 10.0, 0.1], "mass": float(handle.mass)},
        # illustrative: I1 and I2 3 % apart, spun 18 degrees off axis 3
        {"name": "near-symmetric body: a 1 kg plate 300 x 295 x 60 mm, tilted spin",
         "moments": _tidy(plate.principal_moments), "omega0": [2.0, 0.0, 6.0], "mass": 1.0},
        # handle along the minor axis, tossed about the in-plane axis across it; the racket's mass
        # is not given in the source: 0.35 kg is assumed, for the size of the box drawn only
        {"name": "tennis racket (Brody's measured moments): toss about the intermediate axis",
         "moments": list(BRODY_RACKET_MOMENTS), "omega0": [0.2, 12.0, 0.2], "mass": 0.35},
    ]


def _constant_rotor_momentum(traj: Trajectory) -> list[float] | None:
    """The rotors' momentum (principal frame, kg m^2/s) when live mode can integrate with it."""
    h = traj.internal_momentum
    if h is None or traj.dissipated is not None or not traj.torque_free or np.any(h != h[0]):
        return None
    return np.asarray(h[0], float).tolist()


def page_data(body: Body, traj: Trajectory, frames: int = 150, title: str | None = None) -> dict:
    """What the page's viewer plays, as JSON-ready data.

    Keys (SI units): ``moments`` (kg m^2), ``omega0`` (principal frame, rad/s), ``quat0``
    (principal -> world at t = 0, scalar last), ``principal_axes`` (principal -> design, rows
    as in ``summary.json``) and its quaternion ``principal_axes_quat``, ``t_end`` (s), ``method``,
    ``body_name``, ``title``, ``torque_free``, ``rigid``, ``rotor_momentum`` (the rotors' momentum
    h, principal frame, kg m^2/s, when it is constant over a torque-free run without a damper:
    live mode integrates the gyrostat with it; else None), ``size`` (largest distance of the body
    from its COM, m); ``geometry`` (``unit`` in m; ``solid`` and ``removed``: ``v`` flat integer
    vertex coordinates in units of ``unit``, design frame about the COM, ``f`` flat vertex indices,
    three per triangle; ``removed`` is None without subtracted material); ``frames`` (``t``; ``q``
    design -> world quaternions; ``w`` omega_world, rad/s; ``L`` L_world, kg m^2/s; one row per
    frame, no geometry); ``curves`` (omega(t) in the principal frame, every ``stride``-th of
    ``samples`` samples, ``t`` and ``omega`` as three rows); ``presets`` (:func:`live_presets`).

    Examples
    --------
    >>> import tumble
    >>> import numpy as np
    >>> from tumble.viz.page import page_data
    >>> body = tumble.t_handle()
    >>> run = tumble.simulate(body, [0.1, 10.0, 0.1], t_end=2.0, samples=101)  # a flip, 2 s
    >>> data = page_data(body, run, frames=5)
    >>> data["title"], data["frames"]["t"], data["curves"]["samples"], data["geometry"]["removed"]
    ('T-handle: exact, 2 s', [0.0, 0.5, 1.0, 1.5, 2.0], 101, None)
    >>> q = run.design_attitude()[[0, 25, 50, 75, 100]].as_quat()  # design -> world at the frames' samples
    >>> bool(np.allclose(data["frames"]["q"], q, atol=1e-4)), len(data["geometry"]["solid"]["f"]) // 3  # two rods
    (True, 128)
    >>> import json
    >>> json.loads(json.dumps(data)) == data  # JSON-ready
    True
    """
    from scipy.spatial.transform import Rotation

    check_body_and_run(body, traj)
    idx = frame_indices(len(traj), frames)
    surfaces = body_surfaces(body)
    size = float(max(np.max(np.linalg.norm(v, axis=1)) for v, _, _ in surfaces)) or 1.0
    unit = size / GRID
    stride, keep = _curve_indices(len(traj))
    return {
        "title": title or f"{traj.body_name}: {traj.method}, {traj.t[-1]:g} s",
        "body_name": traj.body_name,
        "method": traj.method,
        "t_end": float(traj.t[-1]),
        "torque_free": bool(traj.torque_free),
        "rigid": bool(traj.rigid),
        "rotor_momentum": _constant_rotor_momentum(traj),
        "moments": np.asarray(traj.moments, float).tolist(),
        "omega0": np.asarray(traj.omega[0], float).tolist(),
        "quat0": np.asarray(traj.quat[0], float).tolist(),
        "principal_axes": np.asarray(traj.principal_axes, float).tolist(),
        "principal_axes_quat": Rotation.from_matrix(traj.principal_axes).as_quat().tolist(),
        "size": size,
        "geometry": {
            "unit": unit,
            "solid": _merged([(v, f) for v, f, removed in surfaces if not removed], unit),
            "removed": _merged([(v, f) for v, f, removed in surfaces if removed], unit),
        },
        "frames": {
            "t": _rounded(traj.t[idx], 8),
            "q": _rounded(traj.design_attitude()[idx].as_quat()),
            "w": _rounded(traj.omega_world[idx]),
            "L": _rounded(traj.angular_momentum_world[idx]),
        },
        "curves": {"t": _rounded(traj.t[keep], 8), "omega": _rounded(traj.omega[keep].T),
                   "stride": stride, "samples": len(traj)},
        "presets": live_presets(),
    }


def _asset(name: str) -> str:
    """The text of ``assets/<name>`` (package data, installed with tumble)."""
    return resources.files("tumble.viz").joinpath("assets", name).read_text(encoding="utf-8")


def _script(text: str) -> str:
    return "<script>" + text.replace("</script", "<\\/script") + "</script>"


_STYLE = """
body { font-family: system-ui, sans-serif; margin: 8px 14px; color: #222; }
h1 { font-size: 19px; margin: 4px 0 6px; }
#tumble-controls { display: flex; align-items: center; gap: 8px; flex-wrap: wrap; margin-bottom: 4px; }
#tumble-controls button { padding: 3px 10px; }
#tumble-controls button.active { background: #333; color: #fff; }
#tumble-slider { flex: 1; min-width: 200px; }
#tumble-time { min-width: 170px; font-variant-numeric: tabular-nums; }
#tumble-scenes { display: flex; gap: 6px; }
.tumble-scene { flex: 1; height: 560px; min-width: 0; }
#tumble-omega { height: 300px; }
#tumble-note, #tumble-control-note { color: #555; font-size: 13px; margin: 2px 0; }
#tumble-readout { font-variant-numeric: tabular-nums; margin: 4px 0; }
#tumble-error { height: 260px; }
#tumble-fit { margin: 4px 0; } #tumble-flight { max-width: 100%; }
#tumble-fit-readout, #tumble-fit-note { font-size: 13px; margin: 2px 0; color: #333; }
#tumble-polhode { height: 560px; }
"""

_SPEEDS = (0.25, 0.5, 1, 2, 4)
#: A closed-loop run's readout, time plot and notes (filled by assets/control.js).
_CONTROL_DIVS = ('<div id="tumble-control"><p id="tumble-readout"></p><div id="tumble-error"></div>'
                 '<p id="tumble-control-note"></p></div>')
#: A fit's flight selector and readout (above the scenes), its polhode plot and notes (below omega(t)),
#: filled by assets/fitview.js.
_FIT_TOP = ('<div id="tumble-fit"><label for="tumble-flight">flight </label><select id="tumble-flight"></select>'
            '<p id="tumble-fit-readout"></p></div>')
_FIT_BOTTOM = '<div id="tumble-polhode"></div><p id="tumble-fit-note"></p>'


def page_html(body: Body, traj: Trajectory, *, frames: int = 150, title: str | None = None, live: bool = True,
              control: dict | None = None, fit: dict | None = None) -> str:
    """The interactive page as one HTML document (str), plotly.js and the data inlined.

    Parameters
    ----------
    body : Body
        The body whose triangles are drawn (design frame).
    traj : Trajectory
        Its motion; at most ``frames`` evenly spread samples become animation frames.
    frames : int
        Animation frames, 2 to :data:`tumble.viz.scene.MAX_FRAMES`.
    title : str, optional
        Page heading (default: body, method, duration).
    live : bool
        Include live mode (``assets/splitting.js`` and ``assets/live.js``, where installed); never
        with ``control`` (live mode integrates a free body, which a closed-loop run is not).
    control : dict, optional
        A closed-loop run's wheels, commanded torque and error curve
        (:func:`tumble.viz.control_page.control_page_data` of the run behind ``traj``, with the same
        ``frames``), drawn by ``assets/control.js``.
    fit : dict, optional
        A fit's flights (:func:`tumble.viz.fit_page.fit_page_data`, ``body`` and ``traj`` its
        first flight's), played by ``assets/fitview.js``: a flight selector, the measured rates
        and the polhode (no live mode).

    Examples
    --------
    >>> import json, re
    >>> import tumble
    >>> from tumble.viz.page import page_html
    >>> body = tumble.t_handle()
    >>> run = tumble.simulate(body, [0.1, 10.0, 0.1], t_end=2.0, samples=101)  # a flip, 2 s
    >>> html = page_html(body, run, frames=5, title="T-handle flip")
    >>> html.splitlines()[0], "<title>T-handle flip</title>" in html, '<h1 id="tumble-title">T-handle flip</h1>' in html
    ('<!DOCTYPE html>', True, True)
    >>> len(html) > 1_000_000  # plotly.js inside: the page works offline
    True
    >>> data = re.search(r'<script type="application/json" id="tumble-data">(.*?)</script>', html, re.S).group(1)
    >>> json.loads(data)["frames"]["t"]  # the frames the viewer plays
    [0.0, 0.5, 1.0, 1.5, 2.0]
    """
    get_plotlyjs = optional_import("plotly.offline", "view", "the interactive page").get_plotlyjs
    data = page_data(body, traj, frames, title)
    if control is not None:
        if control.get("frames", {}).get("t") != data["frames"]["t"]:
            raise ValueError("control = the closed-loop data of another run or frame count: its frames' times "
                             "differ from the page's (make it with control_page_data(run, frames=frames))")
        data["control"], live = control, False
    if fit is not None:
        if control is not None:
            raise ValueError("control and fit: a page plays a closed-loop run or a fit's flights, not both")
        data["fit"], live = fit, False
    title = escape_text(data["title"])
    names = ("splitting.js", "live.js") if live else ("control.js",) if control is not None else \
        ("fitview.js",) if fit is not None else ()
    scripts = [_asset(name) for name in names]
    speeds = "".join(f'<button class="tumble-speed" data-speed="{s:g}">x{s:g}</button>' for s in _SPEEDS)
    parts = [
        "<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
        f"<title>{title}</title>", f"<style>{_STYLE}</style>",
        _script(get_plotlyjs()), "</head><body>",
        f'<h1 id="tumble-title">{title}</h1>',
        '<div id="tumble-controls"><button id="tumble-play">Play</button>'
        '<input id="tumble-slider" type="range" min="0" max="0" step="1" value="0" aria-label="frame">'
        f'<span id="tumble-time"></span><span>speed</span>{speeds}</div>',
        '<div id="tumble-live"></div>',
        *([_FIT_TOP] if fit is not None else []),
        '<div id="tumble-scenes"><div id="tumble-ground" class="tumble-scene"></div>'
        '<div id="tumble-body" class="tumble-scene"></div></div>',
        *([_CONTROL_DIVS] if control is not None else []),
        '<div id="tumble-omega"></div><p id="tumble-note"></p>',
        *([_FIT_BOTTOM] if fit is not None else []),
        f'<script type="application/json" id="tumble-data">{script_json(data)}</script>',
        *(_script(text) for text in scripts),
        _script(_asset("viewer.js")),
        "</body></html>",
    ]
    return "\n".join(parts)


def write_page(body: Body, traj: Trajectory, path: str | os.PathLike[str], *, frames: int = 150, title: str | None = None,
               live: bool = True, control: dict | None = None) -> Path:
    """Write :func:`page_html` to ``path`` whole or not at all (temporary file, then renamed).

    Returns the path written (UTF-8 HTML).

    Examples
    --------
    >>> import tempfile
    >>> import tumble
    >>> from pathlib import Path
    >>> from tumble.viz.page import page_html, write_page
    >>> body = tumble.t_handle()
    >>> run = tumble.simulate(body, [0.1, 10.0, 0.1], t_end=2.0, samples=101)  # a flip, 2 s
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_page(body, run, Path(folder) / "flip.html", frames=5, title="T-handle flip")
    ...     text = path.read_text(encoding="utf-8")
    ...     path.name, sorted(p.name for p in Path(folder).iterdir())  # no temporary file left
    ('flip.html', ['flip.html'])
    >>> text == page_html(body, run, frames=5, title="T-handle flip")
    True
    """
    path = Path(path)
    atomic_write_text(path, page_html(body, traj, frames=frames, title=title, live=live, control=control))
    return path
