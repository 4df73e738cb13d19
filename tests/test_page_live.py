"""Live mode of the interactive page, in headless Chromium.

The JavaScript port of tumble's splitting integrator (``assets/splitting.js``) against tumble's
own :func:`tumble.dynamics.methods.geometric.propagate` for the same input (to 1e-9 of |omega| over
20 s) and against the closed form (its order of convergence); then the form (``assets/live.js``)
on a page written by ``tumble view``: Run recomputes the motion in the browser, the viewer plays
it, bad input is shown in the form, nothing goes to the network and no console error appears.
"""

from __future__ import annotations

import io
import math
from pathlib import Path

import mpmath
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tumble
import tumble.viz
from test_page import painted
from tumble.cli import main
from tumble.dynamics.methods.exact import FreeRotation
from tumble.dynamics.methods.geometric import MAX_STEP_ANGLE, default_step, propagate
from tumble.io.scenario import load_scenario
from tumble.mass.presets import t_handle
from limits import HANG_MS

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SPLITTING = Path(tumble.viz.__file__).parent / "assets" / "splitting.js"
#: The issue's bound: browser and Python agree to this, relative to |omega| (and in rad of attitude).
AGREE = 1e-9
SEED = t_handle().properties.principal_moments.tolist()  # diag(0.125, 0.3125, 0.4375) kg m^2
SEED_FLIP = [0.1, 10.0, 0.1]  # examples/seed_flip.toml's omega in the principal frame: near axis 2
#: The T-handle spun 8 degrees off its intermediate axis: it flips every ~1 s, yet far enough from
#: the separatrix that a 1-ulp change of omega0 moves tumble's own 20 s run by ~3e-11 only. The
#: seed's 0.8 degrees is so close that 1 ulp moves it by up to 1.9e-9 (measured), more than the
#: issue's 1e-9: that case is held to its own round-off sensitivity instead (test_seed_flip_*).
FLIP = [1.0, 10.0, 1.0]
TWENTY = np.linspace(0.0, 20.0, 401)
VIEWPORT = {"width": 1300, "height": 1000}


@pytest.fixture(scope="module")
def splitting_page(module_page):
    """A blank page holding splitting.js alone (no viewer needed), shared: its functions keep no state."""
    w = module_page(viewport=VIEWPORT)
    w.page.set_content(f"<!DOCTYPE html><html><body><script>{SPLITTING.read_text()}</script></body></html>")
    return w


@pytest.fixture
def js(splitting_page):
    """The splitting page, with no console error or outside request after the test."""
    yield splitting_page
    assert splitting_page.clean(), (splitting_page.errors, splitting_page.outside)


def js_propagate(page, moments, omega0, quat0, t, order, step=None):
    return page.evaluate(
        "([I, w, q, t, order, step]) => tumbleSplitting.propagate(I, w, q, t, {order: order, step: step})",
        [list(moments), list(omega0), list(quat0), list(map(float, t)), order, step],
    )


def difference(run, omega, quat, scale):
    """Largest difference of omega (relative to ``scale``) and of the attitude (rad)."""
    d_omega = np.max(np.abs(np.asarray(run["omega"]) - np.asarray(omega))) / scale
    d_angle = np.max((Rotation.from_quat(run["quat"]).inv() * Rotation.from_quat(quat)).magnitude())
    return max(d_omega, d_angle)


def assert_as_tumble(run, moments, omega0, quat0, t, order, step=None):
    """The browser's run equals tumble's Python run of the same input, to AGREE."""
    omega, quat = propagate(moments, omega0, quat0, np.asarray(t), order=order, step=step)
    assert difference(run, omega[:, 0], quat[:, 0], np.linalg.norm(omega0)) <= AGREE


def ulp_sensitivity(moments, omega0, quat0, t, order) -> float:
    """How far tumble's own run moves when one component of omega0 moves by one ulp (either way):
    the round-off floor of the problem, which no port can beat."""
    omega, quat = propagate(moments, omega0, quat0, np.asarray(t), order=order)
    worst = 0.0
    for k in range(6):
        nudged = list(omega0)
        nudged[k % 3] = float(np.nextafter(nudged[k % 3], math.inf if k < 3 else -math.inf))
        w, q = propagate(moments, nudged, quat0, np.asarray(t), order=order)
        worst = max(worst, difference({"omega": w[:, 0], "quat": q[:, 0]}, omega[:, 0], quat[:, 0],
                                      np.linalg.norm(omega0)))
    return worst


def assert_within_round_off(run, moments, omega0, quat0, t, order):
    """The browser's run is as close to tumble's as tumble's is to itself after a 1-ulp change."""
    omega, quat = propagate(moments, omega0, quat0, np.asarray(t), order=order)
    got = difference(run, omega[:, 0], quat[:, 0], np.linalg.norm(omega0))
    assert got <= 2.0 * ulp_sensitivity(moments, omega0, quat0, t, order), got


CASES = {  # moments (kg m^2), omega0 (rad/s), quat0, times (s), order, step (s)
    "flip, order 4": (SEED, FLIP, [0, 0, 0, 1], TWENTY, 4, None),
    "flip, order 6, turned start": (SEED, FLIP, [0.1, -0.2, 0.3, 0.9], TWENTY, 6, None),
    "stable, minor axis, order 2": (SEED, [10.0, 0.1, 0.1], [0, 0, 0, 1], TWENTY, 2, None),
    "near-symmetric, tilted spin": ([0.0075520833, 0.0078, 0.0147520833], [2.0, 0.0, 6.0], [0, 0, 0, 1], TWENTY, 6,
                                    None),
    "uneven samples, given step": (SEED, [3.0, -4.0, 0.5], [0, 0, 0, 1], 20.0 * np.linspace(0, 1, 60) ** 2, 4, 0.004),
    "at rest": (SEED, [0.0, 0.0, 0.0], [0, 0, 0, 1], TWENTY[:5], 4, None),
}


@pytest.mark.parametrize("case", CASES.values(), ids=CASES.keys())
def test_splitting_js_follows_tumble(js, case):
    moments, omega0, quat0, t, order, step = case
    run = js_propagate(js.page, moments, omega0, quat0, t, order, step)
    assert len(run["omega"]) == len(t) == len(run["quat"])
    if np.any(omega0):
        assert_as_tumble(run, moments, omega0, quat0, t, order, step)
        expected = step or default_step(float(np.linalg.norm(omega0)))
        assert math.isclose(run["step"], expected, rel_tol=1e-15)
    else:  # a body at rest stays at rest, where it was
        assert np.all(np.asarray(run["omega"]) == 0) and np.all(np.asarray(run["quat"]) == np.asarray(quat0, float))


@pytest.mark.parametrize("order", [4, 6])
def test_seed_flip_agrees_to_its_round_off_floor(js, order):
    run = js_propagate(js.page, SEED, SEED_FLIP, [0, 0, 0, 1], TWENTY, order)
    assert_within_round_off(run, SEED, SEED_FLIP, [0, 0, 0, 1], TWENTY, order)


@pytest.mark.parametrize("order", [2, 4, 6])
def test_splitting_js_converges_at_its_order_to_the_closed_form(js, order):
    """Halving the step divides the error against the exact solution (Jacobi elliptic functions,
    :class:`tumble.dynamics.methods.exact.FreeRotation`) by 2^order: seed flip over 20 s, steps 4 and 2
    times the default (coarse enough to stay clear of round-off)."""
    exact = FreeRotation(SEED, SEED_FLIP, Rotation.identity()).omega(TWENTY)
    h = MAX_STEP_ANGLE / np.linalg.norm(SEED_FLIP)
    err = [np.max(np.abs(np.asarray(js_propagate(js.page, SEED, SEED_FLIP, [0, 0, 0, 1], TWENTY, order, k * h)["omega"])
                         - exact)) for k in (4, 2)]
    assert abs(math.log2(err[0] / err[1]) - order) < 0.25, err


def test_splitting_js_sin_cos_are_correctly_rounded(js):
    """The momentum's sub-flows use sin and cos rounded correctly (what lets the browser follow
    tumble's glibc-backed run bit for bit): checked against mpmath at 200 bits."""
    rng = np.random.default_rng(12)
    x = np.concatenate([rng.uniform(-0.05, 0.05, 5000), rng.uniform(-1.0, 1.0, 5000),
                        [0.0, 1e-9, -1.4901161193847656e-8, 1.5e-8, 1e-160, 5e-324, 1.0, -1.0]])
    got = js.page.evaluate("(xs) => xs.map((x) => [tumbleSplitting.sinCR(x), tumbleSplitting.cosCR(x)])", x.tolist())
    with mpmath.workprec(200):
        want = [[float(mpmath.sin(mpmath.mpf(v))), float(mpmath.cos(mpmath.mpf(v)))] for v in x.tolist()]
    assert got == want


BAD = {  # (moments, omega0, times, order) -> the message names the field and the rule
    "triangle": (([0.1, 0.2, 0.4], FLIP, [0, 1], 4), "triangle inequality I1 + I2 >= I3"),
    "descending": (([0.3, 0.2, 0.1], FLIP, [0, 1], 4), "must be ascending, I1 <= I2 <= I3"),
    "zero moment": (([0.0, 0.2, 0.2], FLIP, [0, 1], 4), "I1 = 0 must be positive"),
    "NaN moment": (([0.1, float("nan"), 0.2], FLIP, [0, 1], 4), "must be three finite numbers (kg m^2)"),
    "infinite omega": ((SEED, [0.0, float("inf"), 0.0], [0, 1], 4), "omega0 = [0, Infinity, 0] must be three finite"),
    "times backwards": ((SEED, FLIP, [0, 2, 1], 4), "times must increase strictly"),
    "one time": ((SEED, FLIP, [0], 4), "at least two sample times"),
    "order 5": ((SEED, FLIP, [0, 1], 5), "order = 5 is not available; allowed: 2, 4, 6"),
    "too much work": ((SEED, [0.0, 1e6, 0.0], [0, 1e3], 4), "steps of at most"),
}


@pytest.mark.parametrize("bad", BAD.values(), ids=BAD.keys())
def test_splitting_js_refuses_bad_input(js, bad):
    (moments, omega0, t, order), message = bad
    caught = js.page.evaluate(
        """([I, w, t, order]) => {
             try { tumbleSplitting.propagate(I, w, [0, 0, 0, 1], t, {order: order}); return null; }
             catch (e) { return [e.name, e.message]; }
           }""", [moments, omega0, t, order])
    assert caught is not None and caught[0] == "SplittingInputError" and message in caught[1], caught


# ---- the form on a page written by `tumble view` ------------------------------------------------

@pytest.fixture(scope="module")
def page_file(tmp_path_factory):
    out = tmp_path_factory.mktemp("live") / "flip.html"
    assert main(["view", str(EXAMPLES / "seed_flip.toml"), "--out", str(out), "--frames", "60"]) == 0
    return out


@pytest.fixture(scope="module")
def live_page(module_page, page_file):
    """The seed flip's page, loaded once for the tests of its form."""
    w = module_page(viewport=VIEWPORT)
    w.page.goto(page_file.as_uri())
    w.page.wait_for_function("window.tumbleViewer && window.tumbleViewer.ready === true", timeout=HANG_MS)
    return w


@pytest.fixture
def live(live_page):
    """The seed flip's page as loaded: after an earlier test the form's Reset puts back the page's
    own body and run (:func:`test_live_bad_input_is_shown_in_the_form` checks that it restores the
    fields), and the record of the last run is cleared."""
    page = live_page.page
    drawn = page.evaluate("window.tumbleLive.drawn")
    if drawn:  # an earlier test ran the form
        page.click("#tumble-live-reset")
        page.wait_for_function(f"window.tumbleLive.drawn > {drawn} && window.tumbleLive.error === ''", timeout=HANG_MS)
        page.evaluate("window.tumbleLive.lastRun = null; window.tumbleViewer.show(0)")  # the record of its last run
    return live_page


def run_form(page, moments=None, omega0=None, t_end=None, preset=None):
    """Pick a preset and/or type values, press Run, wait for the viewer; the run's record."""
    drawn = page.evaluate("window.tumbleLive.drawn")
    if preset is not None:
        index = page.evaluate("(s) => Array.from(document.querySelectorAll('#tumble-live-preset option'))"
                              ".findIndex((o) => o.textContent.includes(s))", preset)
        assert index >= 0, f"no preset {preset!r}"
        page.select_option("#tumble-live-preset", str(index))
    for i, v in enumerate(moments or ()):
        page.fill(f"#tumble-live-I{i + 1}", repr(v))
    for i, v in enumerate(omega0 or ()):
        page.fill(f"#tumble-live-w{i + 1}", repr(v))
    if t_end is not None:
        page.fill("#tumble-live-tend", repr(t_end))
    page.click("#tumble-live-run")
    page.wait_for_function(f"window.tumbleLive.drawn > {drawn}", timeout=HANG_MS)
    assert page.inner_text("#tumble-live-error") == ""
    return page.evaluate("window.tumbleLive.lastRun")


def ground(png):  # the ground-frame scene, left half below the form
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)[300:750, :650]


def test_live_run_of_a_flip_is_tumbles_and_plays(live):
    page = live.page
    run = run_form(page, moments=SEED, omega0=FLIP, t_end=20.0)
    assert run["t"][0] == 0 and run["t"][-1] == 20.0 and run["moments"] == SEED and run["omega0"] == FLIP
    assert run["box"] is None  # the page's own body: its own geometry is kept
    assert_as_tumble(run, run["moments"], run["omega0"], run["quat0"], run["t"], run["order"])
    w2 = np.asarray(run["omega"])[:, 1]
    assert w2.max() > 9.0 and w2.min() < -9.0, "the handle flips: omega_2 reverses"
    seed = run_form(page, preset="this body")  # the page's own flip, 0.8 degrees off axis 2
    assert seed["omega0"] == pytest.approx(SEED_FLIP, rel=1e-12) and seed["t"][-1] == 20.0
    assert_within_round_off(seed, seed["moments"], seed["omega0"], seed["quat0"], seed["t"], seed["order"])
    status = page.inner_text("#tumble-live-status")
    assert "energy" in status and "|L|" in status

    frames = page.evaluate("window.tumbleViewer.state().frames")
    page.evaluate("window.tumbleViewer.show(0)")
    painted(page)
    first = page.screenshot()
    page.evaluate(f"window.tumbleViewer.show({frames // 4})")  # 5 s on: the handle has turned
    painted(page)
    later = page.screenshot()
    a, b = ground(first), ground(later)
    grey_blue = (a[..., 2] - a[..., 0] > 12) & (a[..., 2] - a[..., 0] < 90) & (a[..., 0] > 40)  # the body, lit
    assert grey_blue.sum() > 1000 and len(np.unique(a[grey_blue] // 4, axis=0)) > 20, "no shaded body drawn"
    assert np.any(np.abs(a - b) > 60, axis=-1).sum() > 300, "the body does not move in the live run"
    assert live.clean(), (live.errors, live.outside)


def polhode_bound(moments, omega0, axis, other):
    """Largest |L_other| on the polhode about a stable axis (0 or 2), from the two invariants:
    L^2 - 2 E I_axis = sum_j L_j^2 (1 - I_axis / I_j) (Landau & Lifshitz, Mechanics, sec. 37)."""
    I, L = np.asarray(moments), np.asarray(moments) * np.asarray(omega0)
    c = np.sum(L**2 * (1 - I[axis] / I))
    return math.sqrt(c / (1 - I[axis] / I[other]))


def test_live_presets_near_symmetric_and_stable_axes(live):
    page = live.page
    plate = run_form(page, preset="near-symmetric")
    assert_as_tumble(plate, plate["moments"], plate["omega0"], plate["quat0"], plate["t"], plate["order"])
    # drawn as the uniform box with those moments: the 300 x 295 x 60 mm plate the preset names
    np.testing.assert_allclose(plate["box"], [0.150, 0.1475, 0.030], rtol=1e-9)
    w = np.asarray(plate["omega"])
    assert np.ptp(w[:, 2]) < 0.01 * abs(w[0, 2]), "near-symmetric: omega_3 stays nearly constant"

    for preset, axis in (("smallest axis", 0), ("largest axis", 2)):
        run = run_form(page, preset=preset)
        assert run["box"] is None and run["moments"] == pytest.approx(SEED, rel=1e-12)
        assert_as_tumble(run, run["moments"], run["omega0"], run["quat0"], run["t"], run["order"])
        w = np.asarray(run["omega"])
        L = w * np.asarray(run["moments"])
        for other in {0, 1, 2} - {axis}:
            bound = polhode_bound(run["moments"], run["omega0"], axis, other)
            assert np.max(np.abs(L[:, other])) <= bound * (1 + 1e-9)
        cosine = np.abs(w[:, axis]) / np.linalg.norm(w, axis=1)
        assert cosine.min() > 0.999, f"the spin about axis {axis + 1} stays near it"
    assert live.clean(), (live.errors, live.outside)


BAD_FORM = [  # (field, typed value, what the form says)
    ("#tumble-live-I3", "0.9", "violate the triangle inequality I1 + I2 >= I3"),
    ("#tumble-live-I1", "0.5", "must be ascending, I1 <= I2 <= I3"),
    ("#tumble-live-I2", "heavy", "I2 = 'heavy' must be a finite number (kg m^2)"),
    ("#tumble-live-w1", "", "omega_1 = '' must be a finite number (rad/s)"),
    ("#tumble-live-w3", "1e300", "is too large: the kinetic energy of this body overflows"),
    ("#tumble-live-tend", "0", "t_end = 0 s must be after 0 and at most 1000 s"),
    ("#tumble-live-tend", "5000", "t_end = 5000 s must be after 0 and at most 1000 s"),
]


def test_live_bad_input_is_shown_in_the_form(live):
    page = live.page
    own_t_end = page.input_value("#tumble-live-tend")
    for field, value, message in BAD_FORM:
        page.fill(field, value)
        page.click("#tumble-live-run")
        page.wait_for_function("window.tumbleLive.error !== ''", timeout=HANG_MS)
        assert message in page.inner_text("#tumble-live-error"), (field, value)
        assert page.evaluate("window.tumbleLive.lastRun") is None
        page.click("#tumble-live-reset")  # back to the page's body and run, error cleared
        page.wait_for_function("window.tumbleLive.error === ''", timeout=HANG_MS)
        assert page.input_value("#tumble-live-I3") == repr(SEED[2])
        # t_end back too (a t_end of 1e9 stayed after Reset: a teacher's walkthrough, 2026-12-03)
        assert page.input_value("#tumble-live-tend") == own_t_end, (field, value)
    # exactly on the intermediate axis the run does not flip: the status says why, as tumble's report does
    run_form(page, omega0=[0.0, 10.0, 0.0])
    assert "an unstable equilibrium, which flips only once perturbed" in page.inner_text("#tumble-live-status")
    run_form(page, omega0=[0.1, 10.0, 0.0])
    assert "unstable equilibrium" not in page.inner_text("#tumble-live-status")
    page.click("#tumble-live-reset")
    page.wait_for_function("window.tumbleLive.error === ''", timeout=HANG_MS)
    assert live.clean(), (live.errors, live.outside)


def test_live_mode_on_a_page_with_a_torque_runs_the_free_body(new_page, tmp_path):
    out = tmp_path / "gravity.html"  # a boom under the gravity-gradient torque
    assert main(["view", str(EXAMPLES / "gravity_boom.toml"), "--out", str(out), "--frames", "20"]) == 0
    w = new_page(viewport=VIEWPORT)
    w.page.goto(out.as_uri())
    w.page.wait_for_function("window.tumbleViewer && window.tumbleViewer.ready === true", timeout=HANG_MS)
    run = run_form(w.page, preset="this body")
    assert_as_tumble(run, run["moments"], run["omega0"], run["quat0"], run["t"], run["order"])
    assert "the live run is the free rigid body" in w.page.inner_text("#tumble-live-status")
    assert w.clean(), (w.errors, w.outside)


def test_live_mode_on_a_page_with_a_wheel_integrates_the_gyrostat(new_page, tmp_path):
    """The page of examples/wheel_t_handle.toml draws the T-handle with its spinning wheel: live
    mode runs Euler's equations with the wheel's momentum h (I w' + w x (I w + h) = 0), so the
    handle does not flip, and agrees with Python's run of the same body and start (DOP853 at
    rtol 1e-12) to AGREE of |omega| and in rad of the turn since t = 0. The same moments without
    h flip."""
    out = tmp_path / "wheel.html"
    assert main(["view", str(EXAMPLES / "wheel_t_handle.toml"), "--out", str(out), "--frames", "20"]) == 0
    w = new_page(viewport=VIEWPORT)
    w.page.goto(out.as_uri())
    w.page.wait_for_function("window.tumbleViewer && window.tumbleViewer.ready === true", timeout=HANG_MS)
    run = run_form(w.page, preset="this body")
    scenario = load_scenario(EXAMPLES / "wheel_t_handle.toml")
    h = scenario.body.internal_momentum(0.0)
    assert run["momentum"] == pytest.approx(h.tolist(), rel=1e-15) and h[1] == pytest.approx(2.5)
    omega = np.asarray(run["omega"])
    assert np.all(omega[:, 1] > 9.9), "the wheel keeps omega_2 at 10 rad/s: no flip"
    traj = tumble.simulate(scenario.body, run["omega0"], times=run["t"], method="dop853")
    turned = Rotation.from_quat(run["quat0"]).inv() * Rotation.from_quat(run["quat"])  # the turn since t = 0,
    mine = {"omega": run["omega"], "quat": turned.as_quat()}                         # in the principal frame
    assert difference(mine, traj.omega, (traj.attitude[0].inv() * traj.attitude).as_quat(),
                      np.linalg.norm(run["omega0"])) <= AGREE  # measured 4.1e-10
    assert "wheels' momentum h = [0, 2.5, 0]" in w.page.inner_text("#tumble-live-status")
    # the same moments as a free rigid body flip (what live mode ran before it took h)
    free = js_propagate(w.page, run["moments"], run["omega0"], run["quat0"], run["t"], run["order"])
    assert np.min(np.asarray(free["omega"])[:, 1]) < -9.0
    assert w.clean(), (w.errors, w.outside)


def test_toolbars_clear_the_titles_and_fields_show_every_digit(live):
    """Plotly's toolbar (shown on hover) does not cover a 3-D pane's title, and the moment and
    omega fields show the whole value a preset fills in (no digits cut)."""
    page = live.page
    for pane in ("#tumble-ground", "#tumble-body"):
        page.hover(pane)
        boxes = page.evaluate("""(pane) => {
            const root = document.querySelector(pane), r = (e) => e.getBoundingClientRect();
            return [r(root.querySelector('.modebar')), r(root.querySelector('.gtitle'))]
                .map((b) => [b.left, b.top, b.right, b.bottom]);
        }""", pane)
        (l1, t1, r1, b1), (l2, t2, r2, b2) = boxes
        assert r2 > l2 and b2 > t2, "the pane has a title"
        assert r1 <= l2 or r2 <= l1 or b1 <= t2 or b2 <= t1, f"{pane}: the toolbar covers the title"
    names = page.evaluate("Array.from(document.querySelectorAll('#tumble-live-preset option')).map((o) => o.textContent)")
    assert any("0.00755208333333" in str(p["moments"]) for p in tumble.viz.page.live_presets())  # 16 characters
    for preset in names:
        run_form(page, preset=preset, t_end=1.0)
        cut = page.evaluate("""() => Array.from(document.querySelectorAll('#tumble-live input'))
            .filter((i) => i.scrollWidth > i.clientWidth).map((i) => i.id + ' = ' + i.value)""")
        assert cut == [], cut
    assert live.clean(), (live.errors, live.outside)
