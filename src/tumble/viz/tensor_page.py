"""The interactive page of a ``tumble tensor`` output folder (``tumble view DIR``).

One self-contained HTML file (plotly.js inlined, as :mod:`tumble.viz.page`'s pages; it works
offline), drawn by ``assets/tensorview.js`` from the folder's tensor.json and throws.npz
(:func:`tumble.io.tensorfolder.read_tensor_folder`):

- a throw selector; the chosen throw's gyroscope samples (dots) against the fitted model (lines,
  bias included) over the fitted window, time from its release (s), sensor frame, rad/s; below
  it the rotor's logged speed over the same window (rad/s);
- the object's principal moments ``I1 <= I2 <= I3`` (kg m^2), one panel each: every used
  throw's own estimate with its standard uncertainty as an error bar, and the pooled value as a
  line with its 95 % interval (+- 1.96 standard uncertainties) shaded, as tensor.png draws them;
- the object's **equivalent uniform box** in the sensor frame (mm): the box of the object's
  mass whose principal moments are the estimated ones (:func:`equivalent_box`), centred on the
  estimated centre of mass along the estimated principal axes, with the axes drawn and the
  sensor frame's origin (the accelerometer) marked;
- a summary (mass, centre of mass and moments with their standard uncertainties, ``chi2/dof``,
  ``adequate``) and the skipped throws with their reasons.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np

from .._html import escape_text, script_json
from .._optional import optional_import
from ..io.atomic import atomic_write_text
from ..io.tensorfolder import TensorFolder
from ..typing import ArrayLike
from .page import _asset, _rounded, _script

__all__ = ["THROW_POINTS", "Z95", "equivalent_box", "tensor_page_data", "tensor_page_html", "write_tensor_page"]

#: Most samples drawn of a throw (every ``stride``-th kept, the last one too): 12 throws of 0.65 s
#: at 4 kHz add ~1.5 MB to the page, not ~4.
THROW_POINTS = 1500
#: The factor of a 95 % interval of a normal distribution, +- 1.96 standard uncertainties (as tensor.png's).
Z95 = 1.959963984540054
#: The box's 12 triangles, as indices into its corners ``(+-a/2, +-b/2, +-c/2)`` numbered by the
#: bits ``4 (x > 0) + 2 (y > 0) + (z > 0)``.
_FACES = ((0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
          (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3))


def equivalent_box(mass: float, moments: ArrayLike) -> np.ndarray:
    """The edges (m) of the uniform box of ``mass`` (kg) whose principal moments are ``moments``
    (kg m^2), the edge ``k`` along the axis of moment ``k``.

    A box of edges ``a, b, c`` has ``I1 = m (b^2 + c^2) / 12`` and its cyclic companions (Meriam
    & Kraige, *Engineering Mechanics: Dynamics*, Table D/4), so ``a^2 = 6 (I2 + I3 - I1) / m``,
    ``b^2 = 6 (I3 + I1 - I2) / m``, ``c^2 = 6 (I1 + I2 - I3) / m``; the triangle inequality makes
    them non-negative (a square that breaks it by its uncertainty is taken as 0).

    Examples
    --------
    >>> from tumble.viz.tensor_page import equivalent_box
    >>> m, (a, b, c) = 12.0, (1.0, 2.0, 3.0)
    >>> moments = [m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12]
    >>> equivalent_box(m, moments).round(12).tolist()
    [1.0, 2.0, 3.0]
    """
    I1, I2, I3 = (float(x) for x in np.asarray(moments, float))
    squares = 6.0 / float(mass) * np.array([I2 + I3 - I1, I3 + I1 - I2, I1 + I2 - I3])
    return np.sqrt(np.maximum(squares, 0.0))


def _box(obj: dict[str, Any]) -> dict[str, Any]:
    """The equivalent box's corners and triangles in the sensor frame, mm."""
    edges = equivalent_box(obj["mass"], obj["principal_moments"])
    axes = np.asarray(obj["principal_axes"], float)  # columns: the principal axes, sensor frame
    signs = np.array([[(k >> 2) & 1, (k >> 1) & 1, k & 1] for k in range(8)], float) * 2.0 - 1.0
    corners = np.asarray(obj["center_of_mass"], float) + (signs * edges / 2.0) @ axes.T
    return {"edges": _rounded(1e3 * edges), "corners": _rounded(1e3 * corners), "faces": [list(f) for f in _FACES]}


def _throw(k: int, entry: dict[str, Any], series: Any) -> dict[str, Any]:
    t = np.asarray(series.t, float)
    release = entry.get("t_release")
    start = float(release) if isinstance(release, (int, float)) else (float(t[0]) if t.size else 0.0)
    stride = max(1, -(-t.size // THROW_POINTS))
    keep = np.unique(np.append(np.arange(0, t.size, stride), t.size - 1)) if t.size else np.zeros(0, int)
    obj = entry.get("object")
    return {
        "number": k + 1, "input": entry["input"], "status": entry["status"], "reason": entry.get("reason") or "",
        "t_release": release, "t_end": entry.get("t_end"), "residual_rms": entry.get("residual_rms"),
        "samples": int(t.size), "stride": stride,
        "t": _rounded(t[keep] - start, 7),
        "measured": _rounded(np.asarray(series.omega_measured, float)[keep].T),
        "model": _rounded(np.asarray(series.omega_model, float)[keep].T),
        "rotor": _rounded(np.asarray(series.rotor, float)[keep]),
        "moments": None if obj is None else obj["principal_moments"],
        "moments_std": None if obj is None else obj["principal_moments_std"],
    }


def tensor_page_data(folder: TensorFolder, title: str | None = None) -> dict[str, Any]:
    """What ``assets/tensorview.js`` draws, JSON-ready.

    Keys: ``title``; ``object`` (tensor.json's: ``mass`` kg, ``inertia`` kg m^2,
    ``principal_moments`` and ``principal_moments_std`` kg m^2, ``principal_axes`` (columns),
    ``center_of_mass`` and ``center_of_mass_std`` m); ``adequate``, ``chi2_dof`` (None for one
    throw); ``z95``; ``box`` (:func:`equivalent_box`'s ``edges``, its 8 ``corners`` in the sensor
    frame and 12 triangles ``faces``, mm); ``throws``, one per throw of tensor.json: ``number``
    (from 1), ``input``, ``status``, ``reason``, ``t_release``, ``t_end`` (s, the file's clock),
    ``residual_rms`` (rad/s), ``samples`` and ``stride`` (every ``stride``-th sample kept and the
    last, at most about :data:`THROW_POINTS`), ``t`` (s from the release), ``measured`` and
    ``model`` (three rows, rad/s), ``rotor`` (rad/s), ``moments`` and ``moments_std`` (its own
    estimate of the object's principal moments, kg m^2, None when skipped).

    Examples
    --------
    >>> import numpy as np
    >>> from pathlib import Path
    >>> from tumble.io.tensorfolder import TensorFolder, ThrowSeries
    >>> from tumble.viz.tensor_page import tensor_page_data
    >>> obj = {"mass": 12.0, "inertia": np.diag([5.0, 10.0, 13.0]).tolist(), "principal_moments": [5.0, 10.0, 13.0],
    ...        "principal_moments_std": [0.1] * 3, "principal_axes": np.eye(3).tolist(),
    ...        "center_of_mass": [0.0, 0.0, 0.0], "center_of_mass_std": [1e-3] * 3}
    >>> t = np.linspace(1.0, 1.5, 101)
    >>> w = np.column_stack([np.cos(t), 5 + 0 * t, np.sin(t)])
    >>> record = {"object": obj, "adequate": True, "chi2_dof": None,
    ...           "throws": [{"input": "o1.csv", "status": "used", "reason": "", "object": obj, "t_release": 1.0,
    ...                       "t_end": 1.5, "residual_rms": 0.01}]}
    >>> data = tensor_page_data(TensorFolder(Path("box"), record, (ThrowSeries(t, w, w, 1500 + 0 * t),)))
    >>> data["box"]["edges"], data["throws"][0]["t"][:2], len(data["throws"][0]["measured"])   # mm; s from release
    ([3000.0, 2000.0, 1000.0], [0.0, 0.005], 3)
    """
    record = folder.record
    obj = record["object"]
    throws = [_throw(k, entry, series) for k, (entry, series) in enumerate(zip(record["throws"], folder.series))]
    used = sum(1 for th in throws if th["status"] == "used")
    name = folder.path.name or os.fspath(folder.path)
    keys = ("mass", "inertia", "principal_moments", "principal_moments_std", "principal_axes", "center_of_mass",
            "center_of_mass_std")
    chi2 = record.get("chi2_dof")
    return {
        "title": title or f"tensor of {name}: a {obj['mass']:.4g} kg object from {used} of {len(throws)} throws",
        "object": {key: obj[key] for key in keys},
        "adequate": bool(record.get("adequate", False)),
        "chi2_dof": chi2 if isinstance(chi2, (int, float)) else None,
        "z95": Z95,
        "box": _box(obj),
        "throws": throws,
    }


_STYLE = """
body { font-family: system-ui, sans-serif; margin: 8px 14px; color: #222; }
h1 { font-size: 19px; margin: 4px 0 6px; }
#tumble-summary, #tumble-throw-readout, #tumble-notes { font-size: 13px; margin: 2px 0; color: #333; }
#tumble-summary { font-variant-numeric: tabular-nums; }
#tumble-throw-bar { margin: 6px 0 2px; } #tumble-throw { max-width: 100%; }
#tumble-rates { height: 380px; } #tumble-rotor { height: 210px; }
#tumble-moments { height: 320px; } #tumble-shape { height: 520px; }
"""


def tensor_page_html(folder: TensorFolder, *, title: str | None = None) -> str:
    """The tensor folder's page (module docstring) as one HTML document (str), plotly.js and the data inlined.

    Examples
    --------
    >>> import json, re
    >>> import numpy as np
    >>> from pathlib import Path
    >>> from tumble.io.tensorfolder import TensorFolder, ThrowSeries
    >>> from tumble.viz.tensor_page import tensor_page_html
    >>> obj = {"mass": 0.5, "inertia": np.diag([1e-3, 2e-3, 2.5e-3]).tolist(), "principal_moments": [1e-3, 2e-3, 2.5e-3],
    ...        "principal_moments_std": [1e-5] * 3, "principal_axes": np.eye(3).tolist(),
    ...        "center_of_mass": [0.01, 0.0, 0.03], "center_of_mass_std": [1e-3] * 3}
    >>> empty = ThrowSeries(np.zeros(0), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0))
    >>> record = {"object": obj, "adequate": True, "chi2_dof": None,
    ...           "throws": [{"input": "o1.csv", "status": "skipped", "reason": "no flight", "object": None}]}
    >>> html = tensor_page_html(TensorFolder(Path("box"), record, (empty,)), title="a <box>")
    >>> html.splitlines()[0], "<title>a &lt;box&gt;</title>" in html, len(html) > 1_000_000   # plotly.js inside
    ('<!DOCTYPE html>', True, True)
    >>> data = re.search(r'<script type="application/json" id="tumble-data">(.*?)</script>', html, re.S).group(1)
    >>> json.loads(data)["throws"][0]["reason"]
    'no flight'
    """
    get_plotlyjs = optional_import("plotly.offline", "view", "the interactive page").get_plotlyjs
    data = tensor_page_data(folder, title)
    heading = escape_text(data["title"])
    parts = [
        "<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
        f"<title>{heading}</title>", f"<style>{_STYLE}</style>",
        _script(get_plotlyjs()), "</head><body>",
        f'<h1 id="tumble-title">{heading}</h1>',
        '<p id="tumble-summary"></p>',
        '<div id="tumble-throw-bar"><label for="tumble-throw">throw </label><select id="tumble-throw"></select>'
        '<p id="tumble-throw-readout"></p></div>',
        '<div id="tumble-rates"></div><div id="tumble-rotor"></div>',
        '<div id="tumble-moments"></div><div id="tumble-shape"></div>',
        '<p id="tumble-notes"></p>',
        f'<script type="application/json" id="tumble-data">{script_json(data)}</script>',
        _script(_asset("tensorview.js")),
        "</body></html>",
    ]
    return "\n".join(parts)


def write_tensor_page(folder: TensorFolder, path: str | os.PathLike[str], *, title: str | None = None) -> Path:
    """Write :func:`tensor_page_html` to ``path`` whole or not at all; returns the path.

    Examples
    --------
    >>> import tempfile
    >>> import numpy as np
    >>> from pathlib import Path
    >>> from tumble.io.tensorfolder import TensorFolder, ThrowSeries
    >>> from tumble.viz.tensor_page import write_tensor_page
    >>> obj = {"mass": 0.5, "inertia": np.diag([1e-3, 2e-3, 2.5e-3]).tolist(), "principal_moments": [1e-3, 2e-3, 2.5e-3],
    ...        "principal_moments_std": [1e-5] * 3, "principal_axes": np.eye(3).tolist(),
    ...        "center_of_mass": [0.01, 0.0, 0.03], "center_of_mass_std": [1e-3] * 3}
    >>> empty = ThrowSeries(np.zeros(0), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0))
    >>> record = {"object": obj, "throws": [{"input": "o1.csv", "status": "skipped", "reason": "no flight"}]}
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_tensor_page(TensorFolder(Path("box"), record, (empty,)), Path(folder) / "box.html")
    ...     sorted(p.name for p in Path(folder).iterdir())   # no temporary file left
    ['box.html']
    """
    path = Path(path)
    atomic_write_text(path, tensor_page_html(folder, title=title))
    return path
