"""Scenario files with the spacecraft models: gravity gradient (and starting in the orbiting
frame), the spherical damper, rotors in body files; each checked against the Python API and its
physics, and every bad table refused with one line naming the key."""

from __future__ import annotations

import numpy as np
import pytest

import tumble
from tumble.cli import main
from tumble.commands import run_scenario
from tumble.io.scenario import load_scenario

GG = '[torque]\nkind = "gravity_gradient"\norbit_period = 5400.0\n'


def scenario(tmp_path, text):
    path = tmp_path / "s.toml"
    path.write_text('body = "t-handle"\n' + text)
    return path


def test_a_gravity_gradient_scenario_starting_in_the_orbit_frame_is_the_python_run(tmp_path):
    path = scenario(tmp_path, GG + "[initial.orbit_frame]\npitch = 0.05\n[simulation]\nt_end = 10800.0\n"
                    "samples = 50\nmethod = \"dop853\"\n")
    traj = run_scenario(load_scenario(path))
    body = tumble.t_handle()
    gg = tumble.GravityGradient(orbit_period=5400.0)
    start = tumble.lvlh_state(gg, body, pitch=0.05)
    ref = tumble.simulate(body, start.omega0, t_end=10800.0, samples=50, torque=gg, attitude0=start.attitude0,
                          method="dop853")
    np.testing.assert_allclose(traj.omega, ref.omega, rtol=0, atol=1e-15)
    pitch = tumble.orbit_frame_angles(traj, gg.bind(body)).pitch
    assert abs(pitch[0] - 0.05) < 1e-12 and np.max(np.abs(pitch)) < 0.06  # librates, Lagrange region


def test_several_torque_tables_act_together(tmp_path):
    """[[torque]] tables: their sum, the Python API's run with the same models in a list (the sum's
    own checks: tests/test_torque_sum.py); the orbiting frame found among them."""
    text = ('[[torque]]\nkind = "gravity_gradient"\norbit_period = 5400.0\n'
            '[[torque]]\nvector = [0.0, 0.0, 1e-6]\nframe = "world"\n'
            "[initial.orbit_frame]\npitch = 0.05\n[simulation]\nt_end = 5400.0\nsamples = 20\nmethod = \"dop853\"\n")
    traj = run_scenario(load_scenario(scenario(tmp_path, text)))
    body = tumble.t_handle()
    gg = tumble.GravityGradient(orbit_period=5400.0)
    start = tumble.lvlh_state(gg, body, pitch=0.05)
    torque = [gg, tumble.ConstantTorque((0.0, 0.0, 1e-6), "world")]
    ref = tumble.simulate(body, start.omega0, t_end=5400.0, samples=20, torque=torque, attitude0=start.attitude0,
                          method="dop853")
    np.testing.assert_array_equal(traj.omega, ref.omega)
    alone = tumble.simulate(body, start.omega0, t_end=5400.0, samples=20, torque=gg, attitude0=start.attitude0,
                            method="dop853")
    assert np.max(np.abs(traj.omega - alone.omega)) > 1e-8  # the second torque acted


def test_a_damper_scenario_ends_in_the_flat_spin(tmp_path):
    """From spin about the minor axis, the damped T-handle ends spinning about its major axis
    at |L| / (I3 + J) (the major-axis rule), with the energy budget closed."""
    path = scenario(tmp_path, "[initial]\nomega = [10.0, 0.3, 0.2]\n[simulation]\nt_end = 400.0\nsamples = 200\n"
                    "method = \"dop853\"\n[damper]\ninertia = 0.01\ndamping = 0.01\n")
    traj = run_scenario(load_scenario(path))
    I3 = traj.moments[2]
    L = traj.angular_momentum_norm[0]
    assert abs(traj.omega[-1, 2]) == pytest.approx(L / (I3 + 0.01), rel=1e-6)
    assert traj.drift["energy"] < 1e-9 and traj.dissipated[-1] > 0.5 * traj.energy[0]


@pytest.mark.parametrize(
    ("text", "pattern"),
    [
        ('[torque]\nkind = "magnetic"\n[initial]\nomega = [1, 0, 0]\n', "torque: kind = 'magnetic' is unknown"),
        (GG + "vector = [1, 0, 0]\n[initial]\nomega = [1, 0, 0]\n", "torque: key 'vector' does not go with kind = 'gravity_gradient'"),
        ('[torque]\nkind = "gravity_gradient"\n[initial]\nomega = [1, 0, 0]\n', "torque: missing key 'orbit_period'"),
        ('[torque]\nkind = "gravity_gradient"\norbit_radius = 6.0e6\n[initial]\nomega = [1, 0, 0]\n', "orbit_radius"),
        ("[initial.orbit_frame]\npitch = 0.1\n", "initial.orbit_frame needs the orbit"),
        (GG + "[initial]\nomega = [1, 0, 0]\n[initial.orbit_frame]\n", "give omega \\(and frame\\) or \\[initial.orbit_frame\\], not both"),
        (GG + "[initial.orbit_frame]\nspin = 1\n", "initial.orbit_frame: unknown key 'spin'"),
        ("[initial]\nomega = [1, 0, 0]\n[damper]\ninertia = 0.01\n", "damper: missing key 'damping' \\(the viscous coupling, N m s: >= 0\\)"),
        ('[[torque]]\nvector = [0, 0, 1]\n[[torque]]\nkind = "gravity_gradient"\n[initial]\nomega = [1, 0, 0]\n',
         "torque\\[1\\]: missing key 'orbit_period'"),
        ('[[torque]]\nvector = [0, 0, 1]\n[[torque]]\nvector = [0, 1]\n[initial]\nomega = [1, 0, 0]\n',
         "torque\\[1\\]: torque vector = \\[0, 1\\] must be a list of 3 numbers"),
        ('torque = 5\n[initial]\nomega = [1, 0, 0]\n', "torque must be a table \\[torque\\], not 5"),
        ("[initial]\nomega = [1, 0, 0]\n[damper]\ninertia = -1.0\ndamping = 0.1\n", "damper: inertia = -1.0 must be a positive"),
        ("[initial]\nomega = [1, 0, 0]\n[damper]\ninertia = 0.1\ndamping = 0.1\nmass = 2\n", "damper: unknown key 'mass'"),
    ],
)
def test_bad_model_tables_are_one_line_exit_2(tmp_path, capsys, text, pattern):
    import re

    path = scenario(tmp_path, text)
    assert main(["simulate", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and re.search(pattern, err), err
    assert not (tmp_path / "out").exists()


def test_summary_and_files_of_a_damped_run(tmp_path, capsys):
    """The summary states the major-axis rule and the budget; the CSV and NPZ carry the damper."""
    import json

    path = scenario(tmp_path, "[initial]\nomega = [10.0, 0.3, 0.2]\n[simulation]\nt_end = 400.0\nsamples = 200\n"
                    "[damper]\ninertia = 0.01\ndamping = 0.01\n")
    out = tmp_path / "run"
    assert main(["simulate", str(path), "--out", str(out), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    s, d = summary["stability"], summary["damper"]
    assert (s["theory"], s["predicted"], s["flip_period_exact"]) == ("energy sink", "unstable", None)
    assert d["final_spin_rate"] == pytest.approx(d["flat_spin_rate"], rel=1e-6)
    assert d["nutation_angle"][0] > 1.4 and d["nutation_angle"][1] < 1e-3  # still relaxing, exponentially
    assert summary["drift"]["energy"] < 1e-9  # energy + dissipated, the budget
    header = (out / "trajectory.csv").read_text().splitlines()[0].split(",")
    assert header[-1] == "dissipated [J]"
    table = np.loadtxt(out / "trajectory.csv", delimiter=",", skiprows=1)
    np.testing.assert_allclose(table[:, 11] + table[:, 12], table[0, 11], rtol=1e-9)
    npz = np.load(out / "trajectory.npz")
    assert npz["damper_omega"].shape == (200, 3) and npz["nutation_angle"][-1] < 1e-3


@pytest.mark.parametrize(("factor", "flips", "predicted"), [(0.0, True, "unstable"), (2.0, False, "stable")])
def test_a_wheel_along_the_intermediate_axis_stops_the_flip(factor, flips, predicted):
    """The gyrostat's linearised theory, stated in the summary, agrees with the run: a wheel with
    h = 2 (I3 - I2) W along the intermediate axis stops the T-handle's flip."""
    from tumble.analysis import trajectory_summary

    rods = tumble.t_handle().parts
    wheel = tumble.Rotor(mass=0.05, radius=0.1, length=0.01, axis=(1.0, 0.0, 0.0), center=(0.0, 0.0, 0.5), spin_rate=1.0)
    body = tumble.Body([*rods, wheel])
    I = body.principal_moments
    W = 10.0
    J = wheel.axial_moment
    rate = factor * (I[2] - I[1]) * W / J
    body = tumble.Body([*rods, tumble.Rotor(mass=0.05, radius=0.1, length=0.01, axis=(1.0, 0.0, 0.0),
                                            center=(0.0, 0.0, 0.5), spin_rate=rate)])
    traj = tumble.simulate(body, [0.1, W, 0.1], t_end=20.0, samples=2000)
    s = trajectory_summary(traj)["stability"]
    assert s["theory"] == "gyrostat"  # a wheel at rest is still a rotor of the body
    assert s["predicted"] == predicted
    assert (s["flips"] > 0) == flips


def test_a_gravity_gradient_run_reports_its_jacobi_integral(tmp_path, capsys):
    import json

    path = scenario(tmp_path, GG + "[initial.orbit_frame]\npitch = 0.05\n[simulation]\nt_end = 54000.0\n"
                    "samples = 400\nmethod = \"dop853\"\n")
    assert main(["simulate", str(path), "--out", str(tmp_path / "run"), "--json"]) == 0
    g = json.loads(capsys.readouterr().out)["gravity_gradient"]
    assert g["orbits"] == 10.0 and g["jacobi_drift"] < 1e-10
    assert g["max_angle"]["pitch"] == pytest.approx(0.05, rel=1e-9)  # a libration's amplitude is its start
    assert g["max_angle"]["roll"] < 1e-9 and g["max_angle"]["yaw"] < 1e-9
    assert main(["simulate", str(path), "--out", str(tmp_path / "run")]) == 0
    assert "10 orbits, Jacobi integral drift" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("example", "figures"),
    [("explorer1", {"omega", "drift", "energy", "nutation"}), ("gravity_boom", {"omega", "drift", "orbit_angles"}),
     ("seed_flip", {"omega", "polhode", "herpolhode", "drift"})],
)
def test_plot_draws_the_figures_that_apply_to_the_run(tmp_path, capsys, example, figures):
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "examples" / f"{example}.toml"
    out = tmp_path / "fig"
    assert main(["plot", str(path), "--out", str(out), "--format", "png", "--t-end", "60"
                 if example != "gravity_boom" else "10800"]) == 0
    assert {p.stem for p in out.iterdir()} == figures
    assert all(p.stat().st_size > 5_000 for p in out.iterdir())


# -- finite but extreme values (issue 19): refused at input, naming the field ---------------------

@pytest.mark.parametrize(
    ("text", "pattern"),
    [
        ("[initial]\nomega = [1e300, 0, 0]\n", r"omega\[0\] = 1e\+300 is beyond 1e\+15 rad/s: faster than any rotation"),
        ("[initial]\nomega = [0, 2e15, 0]\n", r"omega\[1\] = 2000000000000000.0 is beyond 1e\+15 rad/s"),
        ("[initial]\nomega = [1, 0, 0]\n[damper]\ninertia = 1e300\ndamping = 0.1\n",
         r"damper: inertia = 1e\+300 is beyond 1e\+50 kg m\^2: more than any star's"),
        ("[initial]\nomega = [1, 0, 0]\n[damper]\ninertia = 1.0\ndamping = 1e300\n",
         r"damper: damping = 1e\+300 N m s with inertia = 1.0 kg m\^2 relaxes at c / J = 1e\+300 is beyond 1e\+15 1/s"),
        ("[initial]\nomega = [1, 0, 0]\n[damper]\ninertia = 1e10\ndamping = 0.1\n",
         r"damper: inertia = 10000000000.0 kg m\^2 is more than 1e\+06 times the body's smallest moment"),
    ],
)
def test_extreme_values_are_one_line_exit_2(tmp_path, capsys, text, pattern):
    """Before: "computation failed: RuntimeWarning: overflow" or a silently wrong result (a
    damper of 1e300 kg m^2 gave omega = 0)."""
    import re

    path = scenario(tmp_path, text)
    assert main(["simulate", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and re.search(pattern, err), err


def test_a_rotor_spinning_beyond_the_rate_bound_is_refused(tmp_path, capsys):
    body = tmp_path / "wheel.toml"
    body.write_text('[body]\nname = "wheel"\n[[body.parts]]\nkind = "box"\nmass = 3.0\nsize = [0.6, 0.4, 0.2]\n'
                    '[[body.parts]]\n'
                    'kind = "rotor"\nmass = 0.2\nradius = 0.05\nlength = 0.01\naxis = [1, 0, 0]\nspin_rate = 1e300\n')
    path = tmp_path / "s.toml"
    path.write_text('body = "wheel.toml"\n[initial]\nomega = [0.1, 1.0, 0.0]\n')
    assert main(["simulate", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "spin_rate = 1e+300 is beyond 1e+15 rad/s" in err, err
    with pytest.raises(ValueError, match=r"^the rotor's spin_rate at t = 10 s = 1100000000000000.0 is beyond 1e\+15 rad/s"):
        wheel = tumble.Rotor(mass=0.2, radius=0.05, length=0.01, axis=(1, 0, 0), spin_rate=1e14, spin_acceleration=1e14)
        tumble.simulate(tumble.Body([tumble.Box(mass=3.0, size=(0.6, 0.4, 0.2)), wheel]), [0.1, 1, 0], t_end=10.0,
                        method="dop853")
    with pytest.raises(ValueError, match=r"^the rotor's spin_rate function's value at t = 0 s = 1e\+300 is beyond"):
        wheel = tumble.Rotor(mass=0.2, radius=0.05, length=0.01, axis=(1, 0, 0), spin_rate=lambda t: 1e300)
        tumble.simulate(tumble.Body([tumble.Box(mass=3.0, size=(0.6, 0.4, 0.2)), wheel]), [0.1, 1, 0], t_end=1.0,
                        method="dop853")


@pytest.mark.filterwarnings("ignore::tumble.mass.UnitSlipWarning")  # 1e300 kg in a box: past osmium, as meant
def test_simulate_refuses_a_body_beyond_the_inertia_bound():
    heavy = tumble.Body([tumble.Box(mass=1e300, size=(0.6, 0.4, 0.2))])
    with pytest.raises(ValueError, match=r"^principal moments \[.*\] kg m\^2: beyond 1e\+50 kg m\^2, more than any star's"):
        tumble.simulate(heavy, [0.1, 1.0, 0.0], t_end=1.0)


@pytest.mark.parametrize(("axes", "words"), [("", "(pitch axis 3, yaw axis 1), linearly stable there (the Lagrange region)"),
                                             ("yaw_axis = 2\n", "(pitch axis 3, yaw axis 2), unstable there in pitch")])
def test_a_run_started_in_the_orbit_frame_is_judged_with_its_own_axes(tmp_path, capsys, axes, words):
    """``tumble simulate`` on a run started in the orbiting frame with yaw_axis = 2 said "largest angle from the
    orbiting frame 1.56 rad" for a body 0.01 rad off that barely moved (the angles taken about the default axes
    3 and 1), and "predicted stable, 12 flips" of a body the page says tumbles in pitch (a walkthrough, 2026-12-02).
    The angles are now the run's own axes', and the verdict the orbiting frame's: with yaw along the intermediate
    axis, k_P = (I_roll - I_yaw) / I_pitch = (I1 - I2) / I3 < 0, pitch unstable (Hughes ch. 9)."""
    import json

    path = scenario(tmp_path, GG + f"[initial.orbit_frame]\npitch = 0.01\n{axes}[simulation]\nt_end = 100.0\n")
    assert main(["simulate", str(path), "--out", str(tmp_path / "run")]) == 0
    line = capsys.readouterr().out
    assert f"started turning with the orbiting frame {words};" in line and "flip" not in line
    g = json.loads((tmp_path / "run" / "summary.json").read_text())["gravity_gradient"]
    traj = run_scenario(load_scenario(path))
    yaw_axis = 2 if axes else 1
    angles = tumble.orbit_frame_angles(traj, tumble.GravityGradient(orbit_period=5400.0).bind(traj.moments),
                                       pitch_axis=3, yaw_axis=yaw_axis)
    assert g["max_angle"]["pitch"] == pytest.approx(np.max(np.abs(angles.pitch)), rel=1e-9)
    assert 0.01 - 1e-12 <= g["max_angle"]["pitch"] < 0.011 and f"largest angle from the orbiting frame {g['max_angle']['pitch']:.3g} rad" in line
    roll, yaw = (0, 1) if axes else (1, 0)  # the third axis of the right-handed triple (pitch 3)
    k_pitch = (traj.moments[roll] - traj.moments[yaw]) / traj.moments[2]
    assert g["region"] == ("pitch unstable" if axes else "lagrange") and (k_pitch < 0) == bool(axes)


def test_an_orbit_frame_angle_past_half_a_turn_is_asked_about(tmp_path, capsys):
    """pitch = 5.0 (meant as 5 deg) ran 286 deg off the orbiting frame without a word (a walkthrough,
    2026-12-02): one line asks whether it is in degrees; the run is the one asked for."""
    path = scenario(tmp_path, GG + "[initial.orbit_frame]\npitch = 5.0\n[simulation]\nt_end = 10.0\nsamples = 3\n")
    assert main(["simulate", str(path), "--out", str(tmp_path / "run")]) == 0
    err = capsys.readouterr().err
    assert err == ("warning: initial.orbit_frame: pitch = 5.0 rad is past half a turn: is it in degrees? Write radians "
                   "(5.0 deg is 0.08727 rad)\n")
    assert main(["simulate", str(scenario(tmp_path, GG + "[initial.orbit_frame]\npitch = 3.0\n[simulation]\n"
                                                       "t_end = 10.0\nsamples = 3\n")), "--out", str(tmp_path / "b")]) == 0
    assert capsys.readouterr().err == ""  # within half a turn: as written


@pytest.mark.parametrize(("direction", "over_n", "free_body"), [
    ((0.25, 1.0, 0.3), 2.0, False), ((0.25, 1.0, 0.3), 30.0, True), ((0.01, 1.0, 0.01), 10.02, False)])
def test_a_spin_slow_beside_the_orbit_rate_is_not_given_the_free_bodys_verdict(tmp_path, capsys, direction, over_n,
                                                                               free_body):
    """A T-handle spun near its intermediate axis under the gravity gradient: ``tumble simulate`` said "predicted
    unstable" at any spin, the free body's theory (a walkthrough, 2026-12-02). At twice the orbit rate the
    gradient's torque, some 3 (n / omega)^2 of the gyroscopic terms (Hughes 1986, sec. 8.1), is 75 % of them:
    the line says so beside the free body's verdict, and the summary holds |omega0| / n and whether the free body's
    prediction applies. Checked against the free body's closed form: the run's mean flip interval over eleven
    orbits is within 2 % of the elliptic interval at thirty times the orbit rate, and more than 5 % off at twice.
    At ten times the rate but 0.01 rad from the intermediate axis (a walkthrough of docs/gravity-gradient.md,
    2026-12-03), the spin starts 3.2e-5 from the separatrix and the gradient's 3 % moves it: called a free body,
    it flipped 31 % faster than one. The summary's separatrix_offset says so and free_body is false."""
    import json

    gg = tumble.GravityGradient(orbit_period=5400.0)
    omega0 = np.array(direction) / np.linalg.norm(direction) * over_n * gg.mean_motion
    path = scenario(tmp_path, GG + f"[initial]\nomega = {omega0.tolist()}\n[simulation]\nt_end = 60000.0\nsamples = 6001\n")
    assert main(["simulate", str(path), "--out", str(tmp_path / "run")]) == 0
    line = capsys.readouterr().out
    g = json.loads((tmp_path / "run" / "summary.json").read_text())["gravity_gradient"]
    assert g["spin_over_n"] == pytest.approx(over_n, rel=1e-12) and g["free_body"] is free_body
    slow = f"a free body would be unstable, but at {over_n:.2g} times the orbit rate the gravity gradient is not small"
    assert (slow in line) is not free_body and ("predicted unstable" in line) is free_body, line
    near = "times the spin's distance from the separatrix, 3.2e-05, which it moves" in line
    assert near is (direction[0] == 0.01) and (g["separatrix_offset"] < 1e-4) is near, (line, g["separatrix_offset"])
    report = tumble.stability_report(run_scenario(load_scenario(path)))
    closed_form = float(tumble.flip_interval(omega0, tumble.t_handle().principal_moments))
    off = abs(report["flip_period"] - closed_form) / closed_form
    assert off < 0.02 if free_body else off > 0.05, off


def test_an_ellipses_slow_spin_is_not_given_the_free_bodys_verdict_either(tmp_path, capsys):
    """On an ellipse (12,000 km, e = 0.4) a body spun at twice its mean motion got the free body's bare "predicted
    stable" and no gravity_gradient entry in summary.json (a walkthrough of docs/gravity-gradient.md, 2026-12-02),
    where the circle said the gradient was not small. The ellipse's line says it too, its n the orbit's mean motion
    (Kepler: sqrt(mu / a^3)); the summary holds the period, the orbits, |omega0| / n and no Jacobi integral (none
    on an orbit whose radius changes)."""
    import json

    from tumble.dynamics.environment.earth import MU_EARTH

    n = (MU_EARTH / 12e6**3) ** 0.5
    text = ('[torque]\nkind = "gravity_gradient"\nsemi_major_axis = 12e6\neccentricity = 0.4\n'
            f"inclination = 0.9\n[initial]\nomega = [0.0, 0.0, {2 * n!r}]\n[simulation]\nt_end = 3000.0\nsamples = 301\n")
    path = scenario(tmp_path, text)
    assert main(["simulate", str(path), "--out", str(tmp_path / "run")]) == 0
    line = capsys.readouterr().out
    g = json.loads((tmp_path / "run" / "summary.json").read_text())["gravity_gradient"]
    assert g["spin_over_n"] == pytest.approx(2.0, rel=1e-9) and g["free_body"] is False and g["jacobi_drift"] is None
    assert g["orbit_period"] == pytest.approx(2 * np.pi / n, rel=1e-9) and g["orbits"] == pytest.approx(3000 * n / (2 * np.pi))
    assert "a free body would be stable, but at 2 times the orbit rate the gravity gradient is not small" in line, line


def test_the_earths_mu_in_km3_s2_and_a_list_of_points_are_refused_naming_what_is_needed(tmp_path, capsys):
    """mu = 398600.4418 (the Earth's in km^3/s^2) ran an orbit of 5.7 years with exit 0; both orbit keys were
    refused without their values; figure_gravity_stability(points=[(k_R, k_Y)]) raised an AttributeError about
    a list's items (a walkthrough of docs/gravity-gradient.md, 2026-12-02)."""
    from tumble.viz.gravity import figure_gravity_stability

    path = scenario(tmp_path, GG.replace("orbit_period = 5400.0", "orbit_radius = 6.9e6\nmu = 398600.4418")
                    + "[simulation]\nt_end = 10.0\n")
    assert main(["simulate", str(path), "--out", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "mu = 398600.4418 m^3/s^2 is the Earth's in km^3/s^2; give m^3/s^2 (3.986004418e+14)" in err
    with pytest.raises(ValueError, match=r"not both: orbit_period = 5400.0, orbit_radius = 6900000.0$"):
        tumble.GravityGradient(orbit_period=5400.0, orbit_radius=6.9e6)
    tumble.GravityGradient(orbit_radius=6.9e6, mu=4.9048695e12)  # the Moon's, in m^3/s^2: taken
    with pytest.raises(ValueError, match=r"^points = \[\(0.8, 0.6\)\] must be a dict of a label to its \(k_R, k_Y\)"):
        figure_gravity_stability(points=[(0.8, 0.6)])
