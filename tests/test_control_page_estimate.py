"""The interactive page of a run with the attitude filter in the loop: the estimated principal axes
beside the body and the knowledge error on the time plot (``tumble.viz.control_page`` and
``assets/control.js``), in Python and in Chromium."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from test_page import open_viewer, page_json

from tumble.cli import main
from tumble.commands import run_scenario
from tumble.io.scenario import load_scenario
from tumble.viz.control_page import control_page_data
from limits import HANG_MS

EXAMPLE = Path(__file__).resolve().parents[1] / "src" / "tumble" / "examples" / "control" / "estimate_point.toml"


@pytest.fixture(scope="module")
def estimate_page(tmp_path_factory):
    out = tmp_path_factory.mktemp("estimate") / "estimate.html"
    assert main(["view", str(EXAMPLE), "--t-end", "60", "--frames", "21", "--out", str(out)]) == 0
    return out


def test_the_turn_is_the_knowledge_error_at_each_frame():
    """Frames fall on control steps here (every 3 s of a 1 s period): each frame's turn from the
    body to the estimate is the filter's error at that step, undone, and the curve is the error's size."""
    scenario = load_scenario(EXAMPLE).override({"t_end": 60.0})
    c = scenario.controller()
    run = run_scenario(scenario, c)
    k = c.knowledge()
    data = control_page_data(run, frames=21, wheel_axes=scenario.wheels.axes, knowledge=k)["estimate"]
    error = k.error(run)
    for frame in (0, 7, 19):
        row = int(np.searchsorted(k.t, 3.0 * frame))
        turn = Rotation.from_matrix(np.array(data["turn"][frame]))
        assert np.allclose(turn.as_rotvec(), -error[row], atol=1e-8)   # A_true^T A_est = exp(-e)
    assert np.allclose(data["curve"]["y"], np.linalg.norm(error, axis=1), rtol=1e-4)   # 5 digits on the page
    assert control_page_data(run, frames=21, wheel_axes=scenario.wheels.axes).get("estimate") is None


def test_the_page_draws_the_estimate_in_chromium(estimate_page, new_page):
    watched = open_viewer(new_page, estimate_page.as_uri())
    page = watched.page
    name = "estimated principal axes (the filter's attitude), red dashed"
    for plot in ("tumble-ground", "tumble-body"):
        assert name in page.evaluate(f"document.getElementById('{plot}').data.map(t => t.name)")
    assert "knowledge error (rad)" in page.evaluate("document.getElementById('tumble-error').data.map(t => t.name)")
    data = page_json(estimate_page.read_text())
    page.locator("#tumble-slider").fill("12")
    page.wait_for_function("tumbleViewer.state().frame === 12", timeout=HANG_MS)
    drawn = np.array(page.evaluate(
        "(() => { const d = document.getElementById('tumble-body').data.find(t => t.name.startsWith('estimated'));"
        " return [Array.from(d.x), Array.from(d.y), Array.from(d.z)]; })()"), dtype=float).T
    # in the body view: the estimated principal axes in the drawn (design) frame, 1.3 sizes long
    turn, A = np.array(data["control"]["estimate"]["turn"][12]), np.array(data["principal_axes"])
    tips = drawn[1::3]
    expected = (A @ turn).T * 1.3 * data["size"]
    assert np.allclose(tips, expected, rtol=1e-6, atol=1e-9 * data["size"])
    assert watched.errors == [] and watched.outside == []
