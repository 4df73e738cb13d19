"""See your toss (issue #29 item 5): ``tumble view DIR`` of a ``tumble fit`` output folder.

The page replays each used flight with the fitted body (tumble.commands.view_fit,
tumble.viz.fit_page, assets/fitview.js) from fit.json's ``"flight_models"``
(tumble.analysis.fit.flightmodel). Checked against independent routes: Euler's equations
integrated here with scipy's solve_ivp from each flight's fitted ``omega0`` at its ``t0``; the
recording read here with the csv module and turned by the fitted rotation; the residual of the
whole joint fit as fit.json states it; the sphere and the ellipsoid from the page's own start.
"""

from __future__ import annotations

import csv
import json
import shutil
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation
from test_page import MAX_PAGE_BYTES, open_viewer, page_json

from tumble.analysis.fit.synthetic import synthetic_recording
from tumble.cli import main
from limits import HANG_MS

RACQUET_EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "data" / "racquet_tosses.csv"


def fit_and_view(root, recordings, *options):
    """``tumble fit`` then ``tumble view`` of its folder: (fit.json, the page's data, the page's text)."""
    out, page = root / "fit", root / "tosses.html"
    assert main(["fit", *map(str, recordings), "--out", str(out), "--accept-inadequate", *options]) == 0
    assert main(["view", str(out), "--out", str(page), "--frames", "40"]) == 0
    html = page.read_text(encoding="utf-8")
    return json.loads((out / "fit.json").read_text(encoding="utf-8")), page_json(html), html


@pytest.fixture(scope="module")
def racquet(tmp_path_factory):
    """The packaged racquet recording (12 tosses), fitted as tumble fit chooses (quadratic drag)."""
    return fit_and_view(tmp_path_factory.mktemp("racquet"), [RACQUET_EXAMPLE])


@pytest.fixture(scope="module")
def racquet_free(tmp_path_factory):
    """A synthetic racquet recording without air or flexing (three tosses), fitted torque-free (--drag none)."""
    root = tmp_path_factory.mktemp("free")
    path = root / "free.csv"
    path.write_text(synthetic_recording(61, tosses=3, drag=0.0, flex=False).csv_text("no air"), encoding="utf-8")
    return fit_and_view(root, [path], "--drag", "none")


@pytest.fixture(scope="module")
def pooled(tmp_path_factory):
    """Two synthetic recordings of the racquet, pooled: each its own phone mount and bias."""
    root = tmp_path_factory.mktemp("pooled")
    paths = [root / "A.csv", root / "B.csv"]
    for seed, path in zip((51, 52), paths):
        path.write_text(synthetic_recording(seed, tosses=2).csv_text(f"seed {seed}"), encoding="utf-8")
    return (*fit_and_view(root, paths), paths)


def euler(moments, drag, coefficients):
    """Euler's equations with per-axis drag, principal frame, moments in units of I3 (Landau &
    Lifshitz sec. 36; the drag law of tumble.dynamics.models.drag), written out here."""
    I = np.asarray(moments, float)
    c = np.asarray(coefficients, float)
    lin, quad = (c, 0 * c) if drag == "linear" else (0 * c, c) if drag == "quadratic" else (0 * c, 0 * c)

    def rate(_t, w):
        gyro = np.array([(I[1] - I[2]) * w[1] * w[2], (I[2] - I[0]) * w[2] * w[0], (I[0] - I[1]) * w[0] * w[1]])
        return (gyro - (lin + quad * np.abs(w)) * w * I[2]) / I

    return rate


def integrated(model, times):
    """omega at ``times`` (s, the recording's clock) from the model's omega0 at its t0, both ways."""
    rate = euler([model["I1_over_I3"], model["I2_over_I3"], 1.0], model["drag"], model["drag_coefficients"])
    t0, out = model["t0"], np.empty((len(times), 3))
    for side in (times < t0, times >= t0):
        ts = times[side]
        if not ts.size:
            continue
        away = ts if ts[0] >= t0 else ts[::-1]  # from t0 outwards
        if away[-1] == t0:
            out[side] = model["omega0"]
            continue
        y = solve_ivp(rate, (t0, away[-1]), model["omega0"], t_eval=away, method="DOP853", rtol=1e-11, atol=1e-11).y.T
        out[side] = y if ts[0] >= t0 else y[::-1]
    return out


def test_fit_json_t0_is_where_omega0_holds(racquet):
    """fit.json's top-level ``omega0`` (the pooled fit's view of its first flight) holds at its
    ``t0``, the flight's anchor: integrated from there it meets the first flight's own model;
    the flight's first sample lies before that anchor (it was written as ``t0`` before)."""
    fit = racquet[0]
    first = fit["flight_models"][0]
    assert fit["t0"] == pytest.approx(first["t0"], abs=1e-12)
    assert fit["omega0"] == pytest.approx(first["omega0"], rel=1e-9, abs=1e-12)
    assert fit["tosses"][0]["start"] < first["t0"]


def test_the_page_is_written_whole_with_one_entry_per_used_flight(racquet, tmp_path):
    fit, data, html = racquet
    flights = data["fit"]["flights"]
    used = [k for k, toss in enumerate(fit["tosses"]) if toss["status"] == "ok"]
    assert len(flights) == len(fit["flight_models"]) == fit["pooled"]["tosses_used"] == len(used) >= 11
    assert [f["toss"] for f in flights] == used
    for f, toss in zip(flights, (fit["tosses"][k] for k in used)):
        assert (f["start"], f["end"]) == (toss["start"], toss["end"]) and len(f["t"]) == toss["samples"]
        assert len(f["omega"]) == len(f["measured"]) == len(f["quat"]) == toss["samples"]
    assert html.startswith("<!DOCTYPE html>") and html.rstrip().endswith("</html>")
    assert "<script src=" not in html and len(html.encode()) < MAX_PAGE_BYTES  # plotly inlined, nothing fetched
    assert html.count('id="tumble-flight"') == 1 and "window.tumbleViewer" in html and "tumble:ready" in html
    assert data["title"].startswith(f"fit of {RACQUET_EXAMPLE}: {len(used)} flights replayed by the fitted body")
    # the box drawn has the fitted ratios
    x, y = fit["I1_over_I3"], fit["I2_over_I3"]
    for f in flights:
        assert f["moments"] == pytest.approx([x, y, 1.0], rel=1e-12)
        a, b, c = 2 * np.array(f["box"])  # full edges; I1 = m (b^2 + c^2) / 12 and cyclic
        assert (b**2 + c**2) / (a**2 + b**2) == pytest.approx(x, rel=1e-9)
        assert (a**2 + c**2) / (a**2 + b**2) == pytest.approx(y, rel=1e-9)


@pytest.mark.parametrize("which", ["racquet", "racquet_free", "pooled"])
def test_the_replayed_rates_are_the_fit_model_at_the_sample_times(which, request):
    fit, data, _ = request.getfixturevalue(which)[:3]
    models = fit["flight_models"]
    assert ({m["drag"] for m in models} == {"none"}) == (which == "racquet_free")  # drag fitted where there is air
    for f, model in zip(data["fit"]["flights"], models, strict=True):
        times = np.array(f["t"]) + f["start"]
        assert times[0] == pytest.approx(model["start"], abs=1e-9) and times[-1] == pytest.approx(model["end"], abs=1e-9)
        expected = integrated(model, times)
        w = np.array(f["omega"])
        assert np.max(np.abs(w - expected)) < 1e-6 * np.max(np.abs(expected)), f["label"]
        if model["drag"] == "none":  # torque-free: |L| and the energy hold along the replay
            I = np.array(f["moments"])
            assert np.ptp(np.linalg.norm(I * w, axis=1)) < 1e-7 * f["L_norm"]
            assert np.ptp(np.sum(I * w**2, axis=1)) < 1e-7 * f["energy2"]


@pytest.mark.parametrize("which", ["racquet", "pooled"])
def test_the_measured_rates_are_the_recording_turned_into_the_principal_frame(which, request):
    """Each flight's measured rates: the recording's samples read here, the bias removed and the
    fitted rotation applied; their residual against the replay is the joint fit's own residual."""
    fit, data, _, *paths = request.getfixturevalue(which)
    files = {str(RACQUET_EXAMPLE): RACQUET_EXAMPLE} if which == "racquet" else \
        {str(path): path for path in paths[0]}
    rows = {}
    for label, path in files.items():
        with open(path, newline="", encoding="utf-8") as fh:
            table = [r for r in csv.reader(line for line in fh if not line.startswith("#"))][1:]
        rows[label] = np.array([[float(v) for v in r[:4]] for r in table])
    squares, count = 0.0, 0
    for f, model in zip(data["fit"]["flights"], fit["flight_models"], strict=True):
        rec = rows[model["input"]]
        sel = (rec[:, 0] >= model["start"]) & (rec[:, 0] <= model["end"])
        turned = Rotation.from_rotvec(model["sensor_rotation_rotvec"]).apply(rec[sel, 1:] - model["bias"])
        measured = np.array(f["measured"])
        np.testing.assert_allclose(measured, turned, rtol=1e-5, atol=1e-5)  # the page keeps 6 digits
        squares += float(np.sum((turned - np.array(f["omega"])) ** 2))
        count += turned.size
    if which == "pooled":  # each recording its own mount: the two differ
        first, second = ({tuple(m["sensor_rotation_rotvec"]) for m in fit["flight_models"] if m["recording"] == r}
                         for r in (0, 1))
        assert len(first) == len(second) == 1 and first != second
    assert fit["saturated"] == 0
    assert np.sqrt(squares / count) == pytest.approx(fit["residual_rms"], rel=1e-4)


@pytest.mark.parametrize("which", ["racquet", "racquet_free"])
def test_the_polhode_points_lie_on_the_momentum_sphere_and_the_energy_ellipsoid(which, request):
    _, data, _ = request.getfixturevalue(which)
    for f in data["fit"]["flights"]:
        I, w0 = np.array(f["moments"]), np.array(f["omega"][0])
        assert f["L_norm"] == pytest.approx(np.linalg.norm(I * w0), rel=1e-8)  # of the flight's start
        assert f["energy2"] == pytest.approx(np.sum(I * w0**2), rel=1e-8)
        P = np.array(f["polhode"])
        assert len(P) > 100 and np.allclose(P[0], P[-1], atol=1e-6 * f["L_norm"])  # one closed period
        np.testing.assert_allclose(np.linalg.norm(P, axis=1), f["L_norm"], rtol=1e-7)  # the sphere
        np.testing.assert_allclose(np.sum(P**2 / I, axis=1), f["energy2"], rtol=1e-7)  # the ellipsoid
        trace = np.array(f["trace"])
        np.testing.assert_allclose(np.linalg.norm(trace, axis=1), f["L_norm"], rtol=1e-7)  # drawn on the sphere
        if which == "racquet_free":  # torque-free: the flight's L runs along that polhode, on the ellipsoid too
            np.testing.assert_allclose(np.sum(trace**2 / I, axis=1), f["energy2"], rtol=1e-6)
            assert f["L_drop"] < 1e-7
        else:
            assert 0 < f["L_drop"] < 0.5  # drag takes some of |L|
        for c in f["separatrices"]:  # on the sphere and the ellipsoid of energy |L|^2 / (2 I2)
            np.testing.assert_allclose(np.linalg.norm(c, axis=1), f["L_norm"], rtol=1e-6)
            np.testing.assert_allclose(np.sum(np.array(c) ** 2 / I, axis=1), f["L_norm"] ** 2 / I[1], rtol=1e-5)


def test_a_missing_or_changed_recording_leaves_the_model_and_says_so(racquet, tmp_path, capsys, monkeypatch):
    src = tmp_path / "src"
    src.mkdir()
    shutil.copy(RACQUET_EXAMPLE, src / "tosses.csv")
    monkeypatch.chdir(src)
    assert main(["fit", "tosses.csv", "--out", "fit"]) == 0
    monkeypatch.chdir(tmp_path)  # tosses.csv is no longer where it was given: found beside the fit's folder
    assert main(["view", "src/fit", "--out", "beside.html"]) == 0
    assert all(f["measured"] is not None for f in page_json((tmp_path / "beside.html").read_text())["fit"]["flights"])
    capsys.readouterr()
    with open(src / "tosses.csv", "a", encoding="utf-8") as fh:
        fh.write("1000.0,0.0,0.0,0.0,0.0\n")  # the recording changed since the fit
    assert main(["view", "src/fit", "--out", "changed.html"]) == 0
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "tosses.csv has changed since the fit" in err
    flights = page_json((tmp_path / "changed.html").read_text())["fit"]["flights"]
    assert flights and all(f["measured"] is None and "has changed" in f["note"] for f in flights)


def _one_line(capsys):
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("tumble: error: ")
    return err


def test_bad_input_exits_2_with_the_path_in_one_line(racquet, tmp_path, capsys):
    empty = tmp_path / "empty"
    empty.mkdir()
    page = tmp_path / "page.html"
    assert main(["view", str(empty), "--out", str(page)]) == 2
    assert f"{empty}: a folder without fit.json" in _one_line(capsys)
    folder = tmp_path / "fit"
    folder.mkdir()
    fit = json.dumps(racquet[0])
    cases = {
        "damaged": (fit[: len(fit) // 2], "fit.json: damaged: not JSON"),
        "older": (json.dumps({k: v for k, v in racquet[0].items() if k != "flight_models"}),
                  'fit.json has no "flight_models": it was written by an older tumble; run tumble fit again'),
        "bad entry": (json.dumps({**racquet[0], "flight_models": [{**racquet[0]["flight_models"][0], "omega0": "fast"}]}),
                      "flight_models[0].omega0 = 'fast' must be a list of 3 numbers (rad/s)"),
        "not a list": (json.dumps({**racquet[0], "flight_models": {}}), 'damaged: "flight_models" = {} must be a list'),
    }
    for text, expected in cases.values():
        (folder / "fit.json").write_text(text, encoding="utf-8")
        assert main(["view", str(folder), "--out", str(page)]) == 2
        err = _one_line(capsys)
        assert str(folder) in err and expected in err, err
    assert main(["view", str(folder), "--out", str(page), "--omega", "1", "2", "3"]) == 2
    assert f"{folder}: a fit's output folder replays its fitted flights; --omega" in _one_line(capsys)
    assert not page.exists()


#: Counts the page's whole draws of each plot (``Plotly.react`` and ``newPlot``) in ``window.draws``.
DRAWS_COUNTED = """window.draws = {}; let plotly;
Object.defineProperty(window, 'Plotly', {configurable: true, get() { return plotly; }, set(v) {
  plotly = v;
  for (const name of ['react', 'newPlot']) {
    const draw = v[name];
    v[name] = function (gd, ...rest) { const id = typeof gd === 'string' ? gd : gd.id;
      window.draws[id] = (window.draws[id] || 0) + 1; return draw.call(this, gd, ...rest); };
  }
}});"""


def test_the_page_plays_the_chosen_flight_in_chromium(racquet, tmp_path, new_page):
    _, data, html = racquet
    page_file = tmp_path / "tosses.html"
    page_file.write_text(html, encoding="utf-8")
    watched = open_viewer(new_page, page_file.as_uri(), init=DRAWS_COUNTED)
    page = watched.page
    flights = data["fit"]["flights"]
    # drawn once on load, the first flight with its measured rates and polhode (it was drawn twice)
    assert page.evaluate("window.draws") == {"tumble-ground": 1, "tumble-body": 1, "tumble-omega": 1, "tumble-polhode": 1}
    assert page.evaluate("document.getElementById('tumble-title').textContent").endswith(flights[0]["label"])
    assert page.evaluate("document.getElementById('tumble-omega').data.length") == 4 + 3
    assert page.evaluate("document.getElementById('tumble-flight').options.length") == len(flights)
    assert page.evaluate("tumbleViewer.state().frames") == min(40, len(flights[0]["t"]))
    assert page.evaluate("document.getElementById('tumble-omega').data.length") == 4 + 3  # model, now, measured
    page.select_option("#tumble-flight", "2")
    page.wait_for_function(f"document.getElementById('tumble-title').textContent.endsWith({json.dumps(flights[2]['label'])})",
                           timeout=HANG_MS)
    page.click("#tumble-play")
    page.wait_for_function("tumbleViewer.state().frame >= 10", timeout=HANG_MS)
    page.click("#tumble-play")
    readout = page.evaluate("document.getElementById('tumble-fit-readout').textContent")
    assert readout.startswith("I1/I3 = ") and "measured (" in readout
    assert watched.clean(), watched.errors
