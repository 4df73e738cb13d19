"""The interactive page of a closed-loop run: wheels turning on the body, the commanded torque,
the error curve (``tumble.viz.control_page`` and ``assets/control.js``), in Python and in Chromium."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from test_page import open_viewer, page_json

from tumble.cli import main
from tumble.commands import run_scenario
from tumble.dynamics.control.controlled import ControlledRun
from tumble.io.scenario import load_scenario
from tumble.viz.control_page import commanded_torque, control_page_data, wheel_angle
from tumble.viz.page import CURVE_POINTS, page_html
from limits import HANG_MS

CONTROL = Path(__file__).resolve().parents[1] / "examples" / "control"


def synthetic_run(t, wheel_speed, *, wheel_torque=None, dipole=None, field=None, omega=None) -> ControlledRun:
    """A ControlledRun made of given arrays (no simulation): the page data only reads them."""
    t = np.asarray(t, float)
    n, k = len(t), np.shape(wheel_speed)[1]
    zeros = np.zeros((n, 3))
    return ControlledRun(
        t=t, omega=zeros + 0.1 if omega is None else np.asarray(omega, float),
        attitude=Rotation.from_rotvec(np.outer(t, [0.0, 0.0, 0.01])), moments=np.array([1.0, 2.0, 3.0]),
        wheel_speed=np.asarray(wheel_speed, float), wheel_torque=np.zeros((n, k)) if wheel_torque is None else wheel_torque,
        dipole=zeros if dipole is None else dipole, field=zeros if field is None else field,
        momentum_world=zeros, impulse_world=zeros)


def angle_gap(a, b) -> np.ndarray:
    """The smallest angles between ``a`` and ``b`` (rad), modulo a turn."""
    d = np.mod(np.asarray(a) - np.asarray(b), 2 * math.pi)
    return np.minimum(d, 2 * math.pi - d)


def test_the_wheel_angle_is_the_integral_of_a_constant_speed():
    t = np.sort(np.concatenate([[0.0, 30.0], np.random.default_rng(3).uniform(0, 30, 200)]))  # uneven steps
    speeds = np.array([2.0, -0.7, 13.0])  # rad/s
    run = synthetic_run(t, np.tile(speeds, (len(t), 1)))
    data = control_page_data(run, frames=40, wheel_axes=np.eye(3))
    frame_t = np.array(data["frames"]["t"])
    assert np.all(angle_gap(data["frames"]["angle"], np.outer(frame_t, speeds)) < 1e-4)  # 5 digits of [0, 2 pi)
    assert np.all((np.array(data["frames"]["angle"]) >= 0) & (np.array(data["frames"]["angle"]) < 2 * math.pi + 1e-4))
    np.testing.assert_array_equal(data["frames"]["speed"], np.tile(speeds, (40, 1)))
    # A speed linear in time: the trapezoid is exact, a t + b t^2 / 2.
    np.testing.assert_allclose(wheel_angle(t, (1.5 + 0.2 * t)[:, None])[:, 0], 1.5 * t + 0.1 * t**2, rtol=1e-13)


def test_the_commanded_torque_is_the_wheels_reaction_plus_m_cross_b():
    rng = np.random.default_rng(7)
    n = 30
    axes = rng.normal(size=(4, 3))  # four wheels, not unit length: normalised
    u, m, b = rng.normal(size=(n, 4)) * 1e-3, rng.normal(size=(n, 3)) * 0.1, rng.normal(size=(n, 3)) * 3e-5
    run = synthetic_run(np.arange(n, dtype=float), np.zeros((n, 4)), wheel_torque=u, dipole=m, field=b)
    g = axes / np.linalg.norm(axes, axis=1)[:, None]
    expected = np.array([[m[i, 1] * b[i, 2] - m[i, 2] * b[i, 1], m[i, 2] * b[i, 0] - m[i, 0] * b[i, 2],
                          m[i, 0] * b[i, 1] - m[i, 1] * b[i, 0]] - sum(u[i, j] * g[j] for j in range(4))
                         for i in range(n)])
    np.testing.assert_allclose(commanded_torque(run, axes), expected, rtol=1e-12, atol=1e-20)
    data = control_page_data(run, frames=n, wheel_axes=axes)
    np.testing.assert_allclose(data["frames"]["torque"], expected, rtol=1e-4)  # stored to 5 digits
    np.testing.assert_allclose(data["frames"]["dipole"], m, rtol=1e-4)
    np.testing.assert_allclose(data["wheel_axes"], g, rtol=1e-11)
    assert data["dipole"] is True


def test_decimation_keeps_the_first_and_last_samples_and_spreads_the_rest():
    n = 11_401  # detumble.toml's samples
    t = np.linspace(0.0, 11_400.0, n)
    run = synthetic_run(t, np.zeros((n, 0)), omega=np.outer(np.exp(-t / 3000.0), [0.2, -0.2, 0.2]))
    data = control_page_data(run, frames=150, threshold=0.0087)
    frame_t = data["frames"]["t"]
    assert len(frame_t) == 150 and frame_t[0] == 0.0 and frame_t[-1] == 11_400.0
    assert np.ptp(np.diff(frame_t)) <= 1.0 + 1e-9  # evenly spread (whole samples of 1 s)
    assert data["frames"]["angle"] == [[]] * 150 and data["frames"]["dipole"] is None and not data["aliased"]
    curve = data["curve"]
    assert curve["name"] == "|omega|" and curve["unit"] == "rad/s" and curve["threshold"] == 0.0087
    assert curve["stride"] == -(-n // CURVE_POINTS) == 3 and curve["t"][0] == 0.0 and curve["t"][-1] == 11_400.0
    np.testing.assert_allclose(curve["y"], run.rate[::3][: len(curve["y"])], rtol=1e-4)


def test_a_wheel_faster_than_half_a_turn_a_frame_is_marked_aliased():
    t = np.linspace(0.0, 10.0, 101)
    slow = control_page_data(synthetic_run(t, np.full((101, 1), 0.5)), frames=11, wheel_axes=[[0, 0, 1]])
    fast = control_page_data(synthetic_run(t, np.full((101, 1), 4.0)), frames=11, wheel_axes=[[0, 0, 1]])
    assert (slow["aliased"], fast["aliased"]) == (False, True)  # 0.5 and 4 rad a frame against pi


def test_the_error_curve_is_the_pointing_error_to_the_target():
    scenario = load_scenario(CONTROL / "point.toml").override({"t_end": 10.0})
    run = run_scenario(scenario)
    data = control_page_data(run, frames=5, wheel_axes=scenario.wheels.axes, target=scenario.target, threshold=0.01)
    assert data["curve"]["name"] == "attitude error" and data["curve"]["threshold"] is None
    np.testing.assert_allclose(data["curve"]["y"], run.pointing_error(scenario.target), rtol=1e-4)
    assert data["curve"]["y"][0] == pytest.approx(math.radians(60.0), rel=1e-4)


@pytest.mark.parametrize(("kwargs", "message"), [
    ({}, r"wheel_axes = None, but the run has 3 wheels"),
    ({"wheel_axes": np.eye(2)}, r"wheel_axes = \[\[1.0, 0.0\], \[0.0, 1.0\]\] must be 3 nonzero finite 3-vectors"),
    ({"wheel_axes": [[1, 0, 0], [0, 0, 0], [0, 0, 1]]}, r"must be 3 nonzero finite"),
    ({"wheel_axes": np.eye(3), "target": [0, 0, 0, 1]}, r"target = \[0, 0, 0, 1\] must be one scipy Rotation"),
    ({"wheel_axes": np.eye(3), "frames": 1}, r"frames = 1 must be a whole number from 2 to 2000"),
])
def test_bad_arguments_get_one_line(kwargs, message):
    run = synthetic_run([0.0, 1.0, 2.0], np.zeros((3, 3)))
    with pytest.raises(ValueError, match=message):
        control_page_data(run, **kwargs)


def test_the_page_refuses_control_data_of_other_frames():
    scenario = load_scenario(CONTROL / "point.toml").override({"t_end": 5.0})
    run = run_scenario(scenario)
    control = control_page_data(run, frames=5, wheel_axes=scenario.wheels.axes, target=scenario.target)
    with pytest.raises(ValueError, match="its frames' times differ from the page's"):
        page_html(scenario.body, scenario.trajectory(run), frames=6, control=control)
    html = page_html(scenario.body, scenario.trajectory(run), frames=5, control=control)  # live mode never with control
    assert page_json(html)["control"] == control and "tumbleSplitting" not in html and "window.tumbleExtra" in html


@pytest.fixture(scope="module")
def point_page(tmp_path_factory):
    out = tmp_path_factory.mktemp("control") / "point.html"
    assert main(["view", str(CONTROL / "point.toml"), "--t-end", "20", "--frames", "41", "--out", str(out)]) == 0
    return out


def test_view_writes_a_control_page(point_page):
    html = point_page.read_text()
    data = page_json(html)
    assert len(data["frames"]["t"]) == 41 and data["frames"]["t"][-1] == 20.0
    assert np.shape(data["control"]["frames"]["angle"]) == (41, 3) and data["control"]["frames"]["dipole"] is None
    assert '<p id="tumble-readout"></p>' in html and '<div id="tumble-error"></div>' in html
    assert "tumbleSplitting" not in html and "window.tumbleExtra = {" in html  # control.js, not live mode
    assert "<script src=" not in html


def test_view_of_the_detumble_example_draws_the_dipole(tmp_path):
    out = tmp_path / "detumble.html"
    assert main(["view", str(CONTROL / "detumble.toml"), "--t-end", "5", "--out", str(out)]) == 0
    control = page_json(out.read_text())["control"]
    assert control["wheel_axes"] == [] and control["dipole"] and control["curve"]["name"] == "|omega|"
    assert control["curve"]["threshold"] == 0.0087 and np.shape(control["frames"]["dipole"]) == (6, 3)


@pytest.mark.parametrize(("args", "message"), [
    (["--samples", "10"], "--samples does not apply to a control scenario; allowed: --t-end"),
    (["--t-end", "-1"], "--t-end"),
    (["--frames", "1"], "error: --frames = 1 must be a whole number from 2 to 2000"),  # the option as written
])
def test_view_of_a_control_scenario_with_bad_input_says_one_line(tmp_path, capsys, args, message):
    out = tmp_path / "page.html"
    assert main(["view", str(CONTROL / "point.toml"), "--out", str(out), *args]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and message in err
    assert not out.exists()


def _wheel_rim(page, frame):
    """Body-frame (design) vertices of the wheel mesh at ``frame``, one row per vertex."""
    page.evaluate(f"tumbleViewer.show({frame})")
    return np.array(page.evaluate(
        "(() => { const d = document.getElementById('tumble-body').data.find(t => t.name.startsWith('reaction wheels'));"
        " return [Array.from(d.x), Array.from(d.y), Array.from(d.z)]; })()")).T


def test_control_page_turns_the_wheels_in_chromium(point_page, new_page):
    watched = open_viewer(new_page, point_page.as_uri())
    page = watched.page
    names = page.evaluate("document.getElementById('tumble-ground').data.map(t => t.name)")
    assert any(n.startswith("reaction wheels (3)") for n in names)
    assert any(n.startswith("commanded torque, green (N m)") for n in names)
    control = page_json(point_page.read_text())["control"]
    readouts, rims = [], []
    for frame in (5, 30):
        page.locator("#tumble-slider").fill(str(frame))
        page.wait_for_function(f"tumbleViewer.state().frame === {frame}", timeout=HANG_MS)
        readouts.append(page.text_content("#tumble-readout"))
        rims.append(_wheel_rim(page, frame))
    assert readouts[0] != readouts[1] and "rpm" in readouts[0]
    speed = control["frames"]["speed"][30][0] * 60 / (2 * math.pi)
    assert f"wheel 1: {speed:.0f} rpm" in readouts[1]
    # Wheel 1's first rim point about its top centre (vertex 0) turns by the angle in the data.
    per = 2 * (24 + 1)
    for w, axis in enumerate(control["wheel_axes"]):
        g = np.asarray(axis) @ np.asarray(page_json(point_page.read_text())["principal_axes"]).T
        a, b = (rim[w * per + 1] - rim[w * per] for rim in rims)
        turned = math.atan2(float(np.cross(a, b) @ g), float(a @ b))
        expected = control["frames"]["angle"][30][w] - control["frames"]["angle"][5][w]
        assert angle_gap(turned, expected) < 1e-3
    torque = page.evaluate("document.getElementById('tumble-body').data.find(t => t.name.startsWith('commanded')).x")
    assert torque[0] == 0 and torque[1] != 0
    assert watched.errors == [] and watched.outside == []
