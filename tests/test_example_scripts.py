"""The example gallery's scripts (gallery/plot_*.py) run as written, in a folder of their own, and
what each one says it shows holds: checked on the names it leaves behind, against closed forms
computed here independently where there is one.

The docs build runs them too (sphinx-gallery); this is the check that they are right.
"""

from __future__ import annotations

import runpy
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from scipy.special import ellipk

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.figure import Figure

GALLERY = Path(__file__).resolve().parents[1] / "gallery"


@pytest.fixture
def run(tmp_path, monkeypatch):
    """Run one script as ``__main__`` in an empty folder; its globals, and the figures it drew."""

    def run_script(name: str) -> tuple[dict, int]:
        monkeypatch.chdir(tmp_path)
        plt.close("all")
        scope = runpy.run_path(str(GALLERY / name), run_name="__main__")
        # pyplot's figures, and tumble.viz's (bare Figures, bound to names: the docs' scraper
        # saves those)
        figures = len(plt.get_fignums()) + sum(
            isinstance(v, Figure) and v.canvas.manager is None for v in scope.values())
        plt.close("all")
        return scope, figures

    return run_script


def test_every_script_has_a_test_and_a_headline():
    scripts = sorted(GALLERY.glob("plot_*.py"))
    assert len(scripts) >= 10
    for script in scripts:
        assert f"test_{script.stem}" in globals(), f"{script.name} has no test here"
        doc = script.read_text(encoding="utf-8").split('"""')[1]
        title, underline = doc.strip().splitlines()[:2]
        assert set(underline) == {"="} and len(underline) == len(title), script.name


def test_plot_t_handle_flip(run):
    scope, figures = run("plot_t_handle_flip.py")
    # Landau & Lifshitz sec. 37: T/2 = 2 K(m) / p with p and m from E and |L| (computed here)
    I1, I2, I3 = scope["body"].principal_moments
    w = np.array(scope["omega0"])
    L2, E2 = np.sum((np.array([I1, I2, I3]) * w) ** 2), np.sum(np.array([I1, I2, I3]) * w**2)
    p = np.sqrt((I3 - I2) * (L2 - I1 * E2) / (I1 * I2 * I3))
    m = (I2 - I1) * (I3 * E2 - L2) / ((I3 - I2) * (L2 - I1 * E2))
    assert scope["closed"] == pytest.approx(2 * ellipk(m) / p, rel=1e-12)
    assert len(scope["flips"]) == 11  # in 20 s
    assert scope["measured"] == pytest.approx(scope["closed"], rel=1e-5)
    assert figures == 1


def test_plot_polhode_herpolhode(run):
    scope, figures = run("plot_polhode_herpolhode.py")
    traj = scope["traj"]
    L = np.linalg.norm(traj.angular_momentum, axis=1)
    assert np.ptp(L) / L[0] < 1e-14 and np.ptp(traj.energy) / traj.energy[0] < 1e-14
    assert figures == 2


def test_plot_montgomery_phase(run):
    scope, figures = run("plot_montgomery_phase.py")
    closed, measured = np.array(scope["closed"]), np.array(scope["measured"])
    gap = np.angle(np.exp(1j * (closed - measured)))  # the difference mod 2 pi
    assert np.abs(gap).max() < 1e-9
    assert np.ptp(closed) > 1.0  # the phase changes with the wobble: the check is not vacuous
    assert figures == 1


def test_plot_reaction_wheel(run):
    scope, figures = run("plot_reaction_wheel.py")
    assert scope["h"] == pytest.approx(1.0 * 0.1**2 / 2 * 500.0)  # J s for a disc: m r^2 / 2 s
    assert scope["h"] > scope["margin"]
    assert scope["flips"] == {"wheel at 500 rad/s": 0, "wheel stopped": scope["flips"]["wheel stopped"]}
    assert scope["flips"]["wheel stopped"] >= 5
    assert figures == 1


def test_plot_explorer1_flat_spin(run):
    scope, figures = run("plot_explorer1_flat_spin.py")
    traj = scope["traj"]
    assert traj.nutation_angle[0] > np.radians(80)  # starts about the minor axis
    assert traj.nutation_angle[-1] < 1e-4  # ends about the major axis
    assert np.linalg.norm(traj.omega[-1]) == pytest.approx(scope["flat"], rel=1e-6)
    assert traj.energy[-1] + traj.dissipated[-1] == pytest.approx(traj.energy[0], rel=1e-5)
    assert figures == 1


def test_plot_gravity_gradient_libration(run):
    scope, figures = run("plot_gravity_gradient_libration.py")
    pitch = scope["angles"].pitch
    assert np.abs(pitch).max() == pytest.approx(0.05, rel=0.05)
    assert np.mean(np.diff(scope["crossings"])) == pytest.approx(scope["predicted"], rel=0.01)
    assert figures == 1


def test_plot_stability_map(run):
    scope, figures = run("plot_stability_map.py")
    grid = scope["grid"]
    x, y = np.meshgrid(grid.x, grid.y)
    # asymmetric bodies: two moments equal to round-off (cells on the diagonal) have no intermediate axis
    tol = 1e-9 * (x + y + 1)
    np.testing.assert_array_equal(grid.inside, (y - x > tol) & (1 - y > tol) & (x + y > 1))
    assert np.isfinite(grid.flip_interval[grid.inside]).all()
    assert figures == 1
    # the spin its text states: 10 rad/s, and 0.01 rad/s about each other axis (the map takes fractions of the spin)
    np.testing.assert_allclose(grid.omega0, [0.01, 10.0, 0.01], rtol=1e-15)


def test_plot_dask_sweep(run):
    pytest.importorskip("dask.distributed")
    scope, figures = run("plot_dask_sweep.py")
    assert scope["summary"].cases == 64
    assert "dask" in scope["backend"].describe()
    # every case flips (a spin near the intermediate axis) at least 3 times in 12 s
    assert (np.asarray(scope["flips"]) >= 3).all()
    assert figures == 1


def test_plot_fit_phone_recording(run):
    scope, figures = run("plot_fit_phone_recording.py")
    true = np.array([0.2022756, 0.8022756])  # the file's header
    assert np.all(np.abs(scope["ratios"] - true) < 4 * scope["std"] + 1e-3)
    assert figures == 1


def test_plot_mesh_mass_properties(run):
    pytest.importorskip("trimesh")
    scope, figures = run("plot_mesh_mass_properties.py")
    # a faceted torus holds a little less than the solid one: mass and moments within 4 %
    R, r = 0.04, 0.01
    assert scope["m"] == pytest.approx(1000 * 2 * np.pi**2 * R * r**2, rel=0.04)
    np.testing.assert_allclose(scope["torus"].principal_moments, scope["closed"], rtol=0.01)
    np.testing.assert_allclose(scope["torus"].com, 0, atol=1e-12)
    assert figures == 1


def test_plot_detumble(run):
    scope, figures = run("plot_detumble.py")
    assert scope["detumbled"] == {1.0: 1.0, 2.0: 1.0}  # every case below 0.5 deg/s
    assert scope["medians"][2.0] < scope["medians"][1.0]  # more gain, faster
    mc, summary = scope["runs"][1.0], scope["summary"]
    assert mc.gravity_gradient and mc.sensors.gyro_noise == 1e-4 and mc.cases.gyro_bias.std() > 5e-5
    finite = np.sort(mc.times)
    assert summary["median_s"] <= summary["p95_s"] <= summary["p99_s"] <= summary["max_s"] == finite[-1]
    assert summary["worst"][0]["detumble_time"] == finite[-1]
    # the figure's distribution: a step of 1/200 at each detumble time (minutes)
    cdf = scope["fig"].axes[1].lines[0]
    assert np.array_equal(cdf.get_xdata()[1:-1], finite / 60.0)
    assert figures == 1


def test_plot_detumble_then_point(run):
    scope, figures = run("plot_detumble_then_point.py")
    mission, run_ = scope["mission"], scope["run"]
    k = round(mission.switch_time / mission.period)
    assert mission.switch_time is not None and np.all(run_.rate[k - 60:k + 1] < np.radians(1.0))  # a minute below
    assert np.all(run_.wheel_torque[:k] == 0.0) and np.any(run_.wheel_torque[k:] != 0.0)  # the wheels from the switch
    assert scope["error"][-1] < 0.5 and scope["error"][k] > 10 * scope["error"][-1]  # deg: it points
    assert scope["budget"] < 1e-14 * np.linalg.norm(run_.moments * run_.omega[0])  # round-off of the momentum
    assert figures == 5


def test_plot_estimate_then_point(run):
    scope, figures = run("plot_estimate_then_point.py")
    k, run_, switch, shadow = scope["knowledge"], scope["run"], scope["switch"], scope["shadow"]
    # the eclipse comes while it points, where the shadow model says the light ends
    assert switch + 200.0 < shadow < run_.t[-1] - 600.0
    assert shadow == k.t[scope["light"].fraction(k.t) == 0.0][0]
    # the filter's error inside its own 3-sigma bounds, the bias found
    inside = np.all(np.abs(k.error(run_)) < 3.0 * k.sigma[:, :3], axis=1)
    assert inside.mean() > 0.97
    assert np.allclose(k.bias[-1], scope["sensors"].gyro_bias, atol=3e-5)
    # fed the truth it converges; fed the estimate it points to its knowledge, worse in the shadow
    lit, dark = scope["lit"], scope["dark"]
    assert scope["error_truth"][-1] < 1e-6
    assert scope["error_estimate"][lit].max() < 0.2 < scope["error_estimate"][dark].max() < 1.0
    assert figures == 2


def test_plot_pointing(run):
    scope, figures = run("plot_pointing.py")
    start, target = scope["start"], scope["target"]
    assert scope["error"][0] == pytest.approx(np.degrees((target.inv() * start).magnitude()), abs=1e-9)
    assert scope["error"][-1] < 2.0
    assert scope["budget"] < 1e-9  # kg m^2/s of ~0.5: no external torque
    assert figures == 1


def test_plot_tensor_from_a_throw(run):
    scope, figures = run("plot_tensor_from_a_throw.py")
    assert figures == 1
    # the calibration: the rotor inertia (1.7e-6 kg m^2) and the device's true centre of mass
    device, truth = scope["device"], scope["truth"]
    assert abs(device.rotor_inertia / 1.7e-6 - 1) < 0.03
    np.testing.assert_allclose(device.center_of_mass, truth.center, atol=2e-3)
    # the object: a uniform box 16 x 9 x 4 cm of 0.482 kg, its moments m (b^2 + c^2) / 12 and cyclic
    a, b, c = 0.16, 0.09, 0.04
    true = np.sort(0.482 / 12 * np.array([b * b + c * c, a * a + c * c, a * a + b * b]))
    fit = scope["fit"]
    assert np.all(np.abs(fit.object.principal_moments / true - 1) < 0.03), (fit.object.principal_moments, true)
    assert all(t.status == "used" for t in fit.throws)
