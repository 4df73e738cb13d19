"""The interactive page: one self-contained HTML file that plays in a real, offline browser."""

from __future__ import annotations

import dataclasses
import io
import json
from importlib import resources
from pathlib import Path

import numpy as np
import pytest
from conftest import BrowserMissingWarning, browser_or_skip, find_browser
from scipy.spatial.transform import Rotation

from tumble.cli import main
from tumble.commands import run_scenario
from tumble.io.scenario import load_scenario
from tumble.viz.page import page_html
from tumble.viz.scene import frame_indices
from tumble.viz.surfaces import body_surfaces
from limits import HANG_MS

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
#: The page's size limit, plotly.js (about 4.8 MB) included.
MAX_PAGE_BYTES = 6_000_000


def page_json(html: str) -> dict:
    """The page's ``tumble-data`` (all it plays: geometry once, then per-frame numbers)."""
    start = html.index('<script type="application/json" id="tumble-data">')
    start = html.index(">", start) + 1
    return json.loads(html[start : html.index("</script>", start)])


@pytest.fixture(scope="module")
def flip():
    scenario = load_scenario(EXAMPLES / "seed_flip.toml")
    return scenario, run_scenario(scenario)


@pytest.fixture(scope="module")
def page_file(tmp_path_factory):
    out = tmp_path_factory.mktemp("page") / "flip.html"
    assert main(["view", str(EXAMPLES / "seed_flip.toml"), "--out", str(out), "--frames", "60"]) == 0
    return out


def test_page_is_one_self_contained_file(page_file):
    html = page_file.read_text()
    assert "<script src=" not in html  # no CDN, nothing to fetch (the browser test watches requests)
    assert "Plotly.react" in html and "window.tumbleViewer" in html  # viewer.js inlined
    assert len(html) > 1_000_000  # the plotly.js bundle is inside
    assert '<div id="tumble-live"></div>' in html
    assert not list(page_file.parent.glob(".*tmp*"))


def test_live_scripts_come_before_the_viewer_and_only_in_live_mode(flip):
    scenario, traj = flip
    live, still = page_html(scenario.body, traj, frames=10), page_html(scenario.body, traj, frames=10, live=False)
    viewer = live.index("window.tumbleViewer = {")
    for name in ("splitting.js", "live.js"):
        first_line = resources.files("tumble.viz").joinpath("assets", name).read_text().splitlines()[1]
        assert live.index(first_line) < viewer and first_line not in still
    assert "window.tumbleViewer = {" in still


def test_the_data_holds_what_live_mode_needs(flip):
    scenario, traj = flip
    data = page_json(page_html(scenario.body, traj, frames=40))
    np.testing.assert_array_equal(data["moments"], traj.moments)
    np.testing.assert_array_equal(data["omega0"], traj.omega[0])
    np.testing.assert_array_equal(data["quat0"], traj.quat[0])
    np.testing.assert_array_equal(data["principal_axes"], traj.principal_axes)
    axes = Rotation.from_quat(data["principal_axes_quat"]).as_matrix()
    np.testing.assert_allclose(axes, traj.principal_axes, atol=1e-12)
    assert data["t_end"] == traj.t[-1] and data["method"] == traj.method and data["body_name"] == traj.body_name


def test_per_frame_data_is_attitude_and_arrows_only(flip):
    """The geometry is stored once; a frame is t, a quaternion and two vectors (11 numbers)."""
    scenario, traj = flip
    data = page_json(page_html(scenario.body, traj, frames=60))
    frames = data["frames"]
    assert set(frames) == {"t", "q", "w", "L"}
    assert len(frames["t"]) == 60
    assert np.shape(frames["q"]) == (60, 4) and np.shape(frames["w"]) == np.shape(frames["L"]) == (60, 3)
    assert len(json.dumps(frames)) < 60 * 11 * 16  # at most ~16 characters a number
    vertices = sum(len(v) for v, _, removed in body_surfaces(scenario.body) if not removed)
    assert len(data["geometry"]["solid"]["v"]) == 3 * vertices  # once, not once a frame
    # The stored attitude turns the design frame: design -> world applied to omega in design
    # coordinates (A omega) gives omega_world, which the trajectory computes the other way round.
    idx = frame_indices(len(traj), 60)
    omega_design = traj.omega[idx] @ traj.principal_axes.T
    np.testing.assert_allclose(Rotation.from_quat(frames["q"]).apply(omega_design), traj.omega_world[idx],
                               atol=1e-4 * np.abs(traj.omega).max())
    np.testing.assert_allclose(frames["L"], traj.angular_momentum_world[idx], rtol=1e-4)
    # Vertices to 1/20000 of the body's size.
    unit = data["geometry"]["unit"]
    stored = np.array(data["geometry"]["solid"]["v"]).reshape(-1, 3) * unit
    drawn = np.concatenate([v for v, _, removed in body_surfaces(scenario.body) if not removed])
    np.testing.assert_allclose(stored, drawn, atol=unit / 2 + 1e-15)


def test_long_runs_subsample_the_curves(flip):
    scenario, traj = flip
    long = dataclasses.replace(traj, t=np.linspace(0, 1, 9001), omega=np.ones((9001, 3)),
                               attitude=Rotation.identity(9001))
    curves = page_json(page_html(scenario.body, long, frames=10))["curves"]
    assert curves["stride"] == 3 and curves["samples"] == 9001
    assert len(curves["t"]) == 3001 and curves["t"][-1] == 1.0  # every 3rd sample, the last one kept
    assert np.shape(curves["omega"]) == (3, 3001)


@pytest.mark.parametrize("scenario", sorted(EXAMPLES.glob("*.toml")), ids=lambda p: p.stem)
def test_view_works_for_every_example_within_the_size_limit(scenario, tmp_path):
    out = tmp_path / "page.html"
    assert main(["view", str(scenario), "--out", str(out)]) == 0  # the view defaults: 150 frames
    assert 1_000_000 < out.stat().st_size <= MAX_PAGE_BYTES
    data = page_json(out.read_text())
    assert len(data["frames"]["t"]) == min(150, load_scenario(scenario).sample_count)


def test_view_says_where_its_frames_are_too_far_apart_to_show_the_motion(tmp_path, capsys):
    """omega in deg/s numbers (573 rad/s) over 20 s on 150 frames: ~77 rad between frames, and the page
    showed another motion than the run's, without a word (a walkthrough, issue 40). The seed's own
    flip (10 rad/s, 1.3 rad a frame) is shown without a note."""
    assert main(["view", "t-handle", "--omega", "5.7", "573", "5.7", "--t-end", "20", "--out", str(tmp_path / "a.html")]) == 0
    err = capsys.readouterr().err
    turn = float(err.split("turns up to ", 1)[1].split(" rad")[0])
    assert 573 * 20 / 149 * 0.95 < turn < 573 * 20 / 149 * 1.3
    # more than the 2000 frames a page holds (it said "give more --frames", and --frames 5000 was refused): the
    # t_end it names, at 2000 frames, is shown without a note
    t_end = float(err.split("give a shorter --t-end (at most about ", 1)[1].split(" s")[0])
    assert 0.5 < t_end / (1999 * np.pi / 573) < 1.0  # half a turn a frame at 573 rad/s, 2000 frames: 10.96 s
    assert "with --frames 2000 and --samples 2000)" in err
    assert main(["view", "t-handle", "--omega", "5.7", "573", "5.7", "--t-end", str(t_end), "--frames", "2000",
                 "--samples", "2000", "--out", str(tmp_path / "c.html")]) == 0
    assert "note:" not in capsys.readouterr().err
    # within them: the frames it names are enough
    assert main(["view", "t-handle", "--omega", "0.57", "57", "0.57", "--t-end", "20", "--out", str(tmp_path / "d.html")]) == 0
    err = capsys.readouterr().err
    frames = int(err.split("give --frames ", 1)[1].split(" ")[0])
    assert 150 < frames <= 500 and "--samples" not in err  # the run's 500 samples are enough
    assert main(["view", "t-handle", "--omega", "0.57", "57", "0.57", "--t-end", "20", "--frames", str(frames),
                 "--out", str(tmp_path / "e.html")]) == 0
    assert "note:" not in capsys.readouterr().err
    assert main(["view", str(EXAMPLES / "seed_flip.toml"), "--out", str(tmp_path / "b.html")]) == 0
    assert "note:" not in capsys.readouterr().err


@pytest.mark.parametrize("frames", ["1", "-3", "5000"])
def test_view_refuses_a_bad_frame_count_before_integrating(tmp_path, capsys, frames):
    out = tmp_path / "page.html"
    assert main(["view", str(EXAMPLES / "seed_flip.toml"), "--out", str(out), "--frames", frames]) == 2
    assert "must be a whole number from 2 to 2000" in capsys.readouterr().err
    assert not out.exists()


def test_view_refuses_other_suffixes(tmp_path, capsys):
    assert main(["view", str(EXAMPLES / "seed_flip.toml"), "--out", str(tmp_path / "x.png")]) == 2
    assert "written as one .html file" in capsys.readouterr().err


def _fake_browser(folder: Path, name: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    path.write_text("#!/bin/sh\n")
    path.chmod(0o755)
    return path


def test_browser_found_by_env_var_then_on_path(tmp_path):
    bin_dir = tmp_path / "bin"
    chrome = _fake_browser(bin_dir, "google-chrome")
    own = _fake_browser(tmp_path / "opt", "my-chromium")
    assert find_browser({"PATH": str(bin_dir)}) == str(chrome)
    assert find_browser({"PATH": str(bin_dir), "TUMBLE_CHROMIUM": str(own)}) == str(own)
    assert find_browser({"PATH": str(tmp_path / "empty")}) is None
    _fake_browser(bin_dir, "chromium-browser")
    assert find_browser({"PATH": str(bin_dir)}) == str(bin_dir / "chromium-browser")  # before google-chrome


def test_a_wrong_env_var_fails_instead_of_falling_back(tmp_path):
    _fake_browser(tmp_path, "chromium")
    with pytest.raises(pytest.fail.Exception, match="TUMBLE_CHROMIUM='/nowhere/chromium' is not an executable"):
        find_browser({"PATH": str(tmp_path), "TUMBLE_CHROMIUM": "/nowhere/chromium"})


def test_missing_browser_skips_loudly_but_fails_in_ci(tmp_path):
    empty = {"PATH": str(tmp_path)}
    with pytest.warns(BrowserMissingWarning, match=r"apt-get install chromium.*TUMBLE_CHROMIUM"):
        with pytest.raises(pytest.skip.Exception, match=r"apt-get install chromium.*TUMBLE_CHROMIUM"):
            browser_or_skip(empty)
    with pytest.raises(pytest.fail.Exception, match="CI must run the browser test: .*apt-get install chromium"):
        browser_or_skip({**empty, "CI": "true"})


def open_viewer(new_page, url, init=None):
    """A watched page of the shared Chromium (conftest's ``new_page``: console errors and refused
    outside requests recorded) at ``url``, after the viewer's ``tumble:ready`` event; ``init``, a
    script run in the page before its own."""
    watched = new_page(viewport={"width": 1300, "height": 1000})
    page = watched.page
    if init:
        page.add_init_script(init)
    page.add_init_script("document.addEventListener('tumble:ready', () => { window.readyEvents = (window.readyEvents || 0) + 1; })")
    page.goto(url)
    page.wait_for_function("window.readyEvents === 1 && window.tumbleViewer.ready", timeout=HANG_MS)
    return watched


def painted(page) -> None:
    """Wait until the browser has painted what the page last drew: two animation frames. The viewer's
    state moves on before its WebGL canvas is drawn again; on a busy machine a screenshot taken at once
    showed the frame before (both of this file's screenshots equal: "the body does not move")."""
    page.evaluate("() => new Promise(done => requestAnimationFrame(() => requestAnimationFrame(() => done(true))))")


def pixels(png) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)


@pytest.fixture(scope="module")
def flip_page(module_page, page_file):
    """The seed flip's page, loaded once for this file's tests of it (:func:`flip_viewer`)."""
    return open_viewer(module_page, page_file.as_uri())


@pytest.fixture
def flip_viewer(flip_page):
    """The seed flip's page showing its own run, paused at frame 0, as loaded."""
    flip_page.page.evaluate("Promise.resolve(tumbleViewer.reset()).then(() => tumbleViewer.show(0))")
    return flip_page


def test_page_plays_offline_in_chromium_with_a_shaded_body(flip_viewer):
    watched = flip_viewer
    page = watched.page
    assert page.evaluate("tumbleViewer.state()") == {"playing": False, "frame": 0, "frames": 60}
    # the "now" line dashed: black and solid it was taken for the zero line at t = 0 (a teacher's walkthrough)
    assert page.evaluate("(() => { const d = document.getElementById('tumble-omega').data[3];"
                         " return [d.name, d.line.dash]; })()") == ["now", "dash"]
    page.click("#tumble-play")
    page.wait_for_function("tumbleViewer.state().frame >= 5", timeout=HANG_MS)
    page.wait_for_function("tumbleViewer.state().frame >= 20", timeout=HANG_MS)
    assert page.evaluate("tumbleViewer.state().playing")
    page.click("#tumble-play")
    assert not page.evaluate("tumbleViewer.state().playing")
    shots = []
    for frame in (5, 20):  # two frames it played, each drawn again and painted before its screenshot
        page.evaluate(f"tumbleViewer.show({frame})")
        painted(page)
        shots.append(page.locator("#tumble-ground").screenshot())
    first, later = shots
    page.locator("#tumble-slider").fill("59")  # the slider moves to the last frame
    page.wait_for_function("tumbleViewer.state().frame === 59", timeout=HANG_MS)
    assert "t = 20.00 s" in page.text_content("#tumble-time")
    assert watched.errors == [] and watched.outside == []

    a, b = pixels(first), pixels(later)
    red = ((a[..., 0] > 150) & (a[..., 1] < 90) & (a[..., 2] < 90)).sum()
    blue = ((a[..., 2] > 150) & (a[..., 0] < 90) & (a[..., 1] < 160)).sum()
    assert red + blue > 100, "no omega / L arrows drawn: blank WebGL canvas?"
    # The body's colour is a blue grey (blue above red); lit, its pixels range from dark to light.
    body = a[(a[..., 2] - a[..., 0] > 12) & (a[..., 2] < 235) & (a[..., 0] > 40)]
    assert len(body) > 300, "no shaded body in the ground-frame scene"
    brightness = body.sum(axis=1) / 3
    assert np.percentile(brightness, 95) - np.percentile(brightness, 5) > 40, "the body is flat, not lit"
    moved = np.any(np.abs(a - b) > 60, axis=-1).sum()
    assert moved > 300, "the body is drawn the same at frames 5 and 20 of the run it plays"


def _ground_vertices(page, frame):
    page.evaluate(f"tumbleViewer.show({frame})")
    return np.array(page.evaluate("(() => { const d = document.getElementById('tumble-ground').data[0];"
                                  " return [Array.from(d.x), Array.from(d.y), Array.from(d.z)]; })()")).T


def test_set_run_turns_the_body_or_a_box_as_python_does(flip, flip_viewer):
    """setRun's principal -> design conversion gives the vertices the page's own frames give;
    a box run draws the box turned by the principal attitude; reset restores the run."""
    _, traj = flip
    idx = frame_indices(len(traj), 60)
    run = {"t": traj.t[idx].tolist(), "quat": traj.quat[idx].tolist(), "omega": traj.omega[idx].tolist(),
           "moments": traj.moments.tolist(), "box": None}
    watched = flip_viewer
    page = watched.page
    own = _ground_vertices(page, 37)
    page.evaluate(f"tumbleViewer.setRun({json.dumps(run)})")
    assert page.evaluate("tumbleViewer.state()") == {"playing": False, "frame": 0, "frames": 60}
    np.testing.assert_allclose(_ground_vertices(page, 37), own, atol=1e-4)
    page.evaluate(f"tumbleViewer.setRun({json.dumps({**run, 'box': [0.3, 0.2, 0.1]})})")
    box = _ground_vertices(page, 37)
    half = traj.attitude[idx[37]].inv().apply(box)  # back to the principal frame
    assert len(box) == 24
    np.testing.assert_allclose(np.abs(half), np.tile([0.3, 0.2, 0.1], (24, 1)), atol=1e-9)
    with pytest.raises(Exception, match="run.omega must hold 60 rows"):
        page.evaluate(f"tumbleViewer.setRun({json.dumps({**run, 'omega': run['omega'][:5]})})")
    page.evaluate("tumbleViewer.reset()")
    np.testing.assert_allclose(_ground_vertices(page, 37), own, atol=1e-12)
    assert watched.errors == [] and watched.outside == []


def test_the_offline_rule_refuses_and_records_every_outside_request(new_page):
    """conftest's one offline rule: a request that would leave the machine is aborted (the image
    does not load) and recorded, while file: and data: URLs load."""
    watched = new_page()
    watched.page.set_content('<img id="far" src="http://example.invalid/a.png">'
                             '<img id="near" src="data:image/gif;base64,R0lGODlhAQABAAAAACH5BAEAAAAALAAAAAABAAEAAAIBAAA=">')
    watched.page.wait_for_function("document.images[0].complete && document.images[1].complete")
    assert watched.page.evaluate("[document.images[0].naturalWidth, document.images[1].naturalWidth]") == [0, 1]
    assert watched.outside == ["http://example.invalid/a.png"]
    watched.outside.clear()  # seen: the fixture would fail the test for it


def test_a_run_with_more_samples_than_frames_is_told_a_frame_a_sample(tmp_path, capsys):
    """docs/page.md's long run (4001 samples over 1000 s) at --frames 2000 was told "at most about 526 s
    with --frames 2000", and at 500 s the note came back (frames two or three samples apart, 4 rad): the
    advice adds --samples 2000 (a frame a sample), and following it, no note (a walkthrough, 2026-12-03)."""
    long_run = str(EXAMPLES / "long_run_geometric.toml")
    assert main(["view", long_run, "--frames", "2000", "--out", str(tmp_path / "a.html")]) == 0
    err = capsys.readouterr().err
    assert "with --frames 2000 and --samples 2000)" in err
    t_end = float(err.split("give a shorter --t-end (at most about ", 1)[1].split(" s")[0])
    assert main(["view", long_run, "--frames", "2000", "--samples", "2000", "--t-end", str(t_end),
                 "--out", str(tmp_path / "b.html")]) == 0
    assert "note:" not in capsys.readouterr().err


def test_view_of_a_name_that_is_nothing_names_the_folders_it_also_takes(tmp_path, capsys):
    """'tumble view nothere' named scenario files, body files and presets, not the fit's and the tensor's
    folders view also takes (a walkthrough of docs/tensor.md, 2026-12-03)."""
    assert main(["view", str(tmp_path / "nothere"), "--out", str(tmp_path / "x.html")]) == 2
    assert ("is not a scenario file, a body file, a preset, or the folder a tumble fit or tumble tensor wrote"
            in capsys.readouterr().err)
