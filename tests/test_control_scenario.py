"""Control scenario files (``[control]``) through ``tumble simulate``: summary.json and trajectory."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from tumble.cli import main
from tumble.io.examples import copy_examples, list_examples
from tumble.io.scenario import load_scenario

CONTROL = Path(__file__).resolve().parents[1] / "examples" / "control"


def test_control_examples_are_listed_and_load_from_a_copy(tmp_path):
    listed = {e.path: e.kind for e in list_examples()}
    kinds = {"detumble": "bdot", "point": "mrp_pd", "detumble_point": "detumble_point"}
    assert {listed[f"control/{name}.toml"] for name in kinds} == {"control"}
    copy_examples(tmp_path / "ex")
    for name, kind in kinds.items():
        scenario = load_scenario(tmp_path / "ex" / "control" / f"{name}.toml")
        assert scenario.kind == kind


def test_detumble_example_reports_its_rates_and_the_gain_of_avanzini_and_giulietti(tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["simulate", str(CONTROL / "detumble.toml"), "--t-end", "30", "--out", str(out), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary == json.loads((out / "summary.json").read_text())
    scenario = load_scenario(CONTROL / "detumble.toml")
    n, i_min = scenario.orbit.mean_motion, float(np.min(scenario.body.principal_moments))
    assert 2 * n * i_min < summary["gain"] <= 4 * n * i_min  # k = 2 n (1 + sin xi_m) I_min
    assert summary["initial_rate"] == pytest.approx(math.radians(20.0), rel=1e-3)
    assert summary["final_rate"] < summary["initial_rate"] and summary["detumble_time"] is None
    assert summary["max_dipole"] == pytest.approx(0.2)  # the rods saturate at 20 deg/s
    assert summary["momentum_budget_error"] < 1e-12 * summary["initial_rate"] * i_min
    data = np.load(out / "trajectory.npz")
    rows = np.loadtxt(out / "trajectory.csv", delimiter=",", skiprows=1)
    assert rows.shape == (31, 1 + 3 + 4 + 3 + 3 + 3 + 3)
    np.testing.assert_array_equal(rows[:, 1:4], data["omega"])
    assert np.linalg.norm(rows[-1, 1:4]) == pytest.approx(summary["final_rate"], rel=1e-15)
    assert (out / "omega.png").stat().st_size > 0


def test_detumble_time_is_when_the_rate_stays_below_the_threshold(tmp_path, capsys):
    text = (CONTROL / "detumble.toml").read_text().replace("threshold = 0.0087", "threshold = 0.345")
    path = tmp_path / "fast.toml"
    path.write_text(text)
    assert main(["simulate", str(path), "--t-end", "40", "--out", str(tmp_path / "run"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    data = np.load(tmp_path / "run" / "trajectory.npz")
    rate = np.linalg.norm(data["omega"], axis=1)
    assert summary["detumble_time"] is not None
    stays = data["t"] >= summary["detumble_time"]
    assert np.all(rate[stays] < 0.345) and rate[~stays][-1] >= 0.345


def test_point_example_drives_the_pointing_error_down_with_the_wheels(tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["simulate", str(CONTROL / "point.toml"), "--t-end", "40", "--out", str(out), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["pointing_error_initial"] == pytest.approx(math.radians(60.0), rel=1e-12)
    assert summary["pointing_error_final"] < 0.3 * summary["pointing_error_initial"]
    assert 0 < summary["max_wheel_torque"] <= 2e-3 and summary["max_wheel_speed"] > 0
    data = np.load(out / "trajectory.npz")
    assert data["wheel_speed"].shape == (81, 3) and data["wheel_torque"].shape == (81, 3)
    L = data["L_world"] - data["impulse_world"]  # body + wheels less the gravity-gradient impulse
    np.testing.assert_allclose(L, L[[0] * len(L)], rtol=0, atol=1e-12 * np.abs(data["L_world"]).max())


@pytest.mark.parametrize(("old", "new", "message"), [
    ('kind = "bdot"', 'kind = "pid"', r"control: kind = 'pid' is unknown; allowed: bdot, mrp_pd"),
    ("max_dipole = 0.2 ", "max_dipole = -1.0 ", r"actuators.magnetorquers: max_dipole\[0\] = -1.0 must be a positive"),
    ("period = 1.0 ", "perio = 1.0 ", r"control: unknown key 'perio' \(did you mean 'period'\?\); allowed with kind = "
                                      r"'bdot': derivative, form, gain, kind, period, threshold$"),
    ("period = 1.0 ", "K = 1.0\nperiod = 1.0 ", r"control: key 'K' does not go with kind = 'bdot'; allowed: derivative, form"),
    ("altitude = 500e3", "altitude = -5.0", r"orbit: altitude = -5.0 must be a positive"),
])
def test_bad_control_files_get_one_line_and_write_nothing(tmp_path, capsys, old, new, message):
    text = (CONTROL / "detumble.toml").read_text()
    assert old in text
    path = tmp_path / "bad.toml"
    path.write_text(text.replace(old, new, 1))
    code = main(["simulate", str(path), "--out", str(tmp_path / "run")])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert re_search(message, err) and "bad.toml" in err
    assert not (tmp_path / "run").exists()


def test_plot_refuses_a_control_scenario_in_one_line(tmp_path, capsys):
    assert main(["plot", str(CONTROL / "point.toml"), "--out", str(tmp_path / "p")]) == 2
    assert "control scenario" in capsys.readouterr().err


def re_search(pattern: str, text: str) -> bool:
    import re

    return re.search(pattern, text) is not None


def test_a_run_that_never_detumbles_says_so(tmp_path, capsys):
    """Issue 27, item 10: a detumble run that ended above its threshold said nothing about it; the
    line says it did not detumble, and summary.json has "detumbled": false (true once it does)."""
    assert main(["simulate", str(CONTROL / "detumble.toml"), "--t-end", "30", "--out", str(tmp_path / "run")]) == 0
    line = capsys.readouterr().out
    assert line.count("\n") == 1 and "not below the threshold 0.0087 rad/s by the end: not detumbled" in line
    assert json.loads((tmp_path / "run" / "summary.json").read_text())["detumbled"] is False
    text = (CONTROL / "detumble.toml").read_text().replace("threshold = 0.0087", "threshold = 0.345")
    path = tmp_path / "fast.toml"
    path.write_text(text)
    assert main(["simulate", str(path), "--t-end", "40", "--out", str(tmp_path / "fast")]) == 0
    assert "below 0.345 rad/s from t = " in capsys.readouterr().out
    assert json.loads((tmp_path / "fast" / "summary.json").read_text())["detumbled"] is True


def test_a_bdot_run_writes_no_empty_wheels_or_attitude_error_figures(tmp_path):
    """Issue 27 item 10(a): a run without wheels or target wrote an empty wheels.png and
    attitude_error.png. A B-dot run writes neither, and those of an earlier run (with wheels and a
    target) into the same folder go with the rest of its files."""
    out = tmp_path / "run"
    assert main(["simulate", str(CONTROL / "point.toml"), "--t-end", "2", "--out", str(out)]) == 0
    figures = {"omega.png", "rates.png", "momentum.png"}
    assert {p.name for p in out.iterdir()} >= figures | {"wheels.png", "attitude_error.png"}
    assert main(["simulate", str(CONTROL / "detumble.toml"), "--t-end", "5", "--out", str(out)]) == 0
    assert {p.name for p in out.iterdir()} == figures | {"dipole.png", "trajectory.csv", "trajectory.npz", "summary.json"}


def test_a_run_without_magnetorquers_writes_no_empty_dipole_figure(tmp_path):
    """Issue 27 item 10(a), the dipole: a wheels-only pointing run (point.toml, no magnetorquers)
    wrote a dipole.png that said only "no magnetorquer dipole in this run". It writes none, and
    one left by an earlier B-dot run into the same folder goes with that run's files; the B-dot
    run's dipole.png draws its dipole, and the pointing run's momentum.png has no wheels' line
    only where there are no wheels."""
    import matplotlib.pyplot as plt

    from tumble.commands import run_scenario
    from tumble.io.scenario import resolve_run
    from tumble.viz import control_figures

    out = tmp_path / "run"
    assert main(["simulate", str(CONTROL / "detumble.toml"), "--t-end", "5", "--out", str(out)]) == 0
    assert (out / "dipole.png").is_file() and not (out / "wheels.png").exists()
    assert main(["simulate", str(CONTROL / "point.toml"), "--t-end", "2", "--out", str(out)]) == 0
    names = {p.name for p in out.iterdir()}
    assert "dipole.png" not in names and {"wheels.png", "attitude_error.png", "momentum.png"} <= names
    for name, dipole, wheels in (("detumble", True, False), ("point", False, True)):
        run = run_scenario(resolve_run(str(CONTROL / f"{name}.toml"), t_end=2.0))
        figures = control_figures(run)
        assert ("dipole.png" in figures) == dipole == bool(np.any(run.dipole))
        if dipole:
            (ax,) = figures["dipole.png"].axes
            assert [line.get_label() for line in ax.lines] == ["m_1", "m_2", "m_3"]
        labels = [line.get_label() for line in figures["momentum.png"].axes[0].lines]
        assert ("wheels |h|" in labels) == wheels and "body |I omega|" in labels
        for fig in figures.values():
            plt.close(fig)


def test_torque_tables_are_the_disturbance_of_the_python_run(tmp_path):
    """[[torque]] tables in a control file: their sum, a body-frame vector read in the design frame
    (principal axis 1 is design z for this box), a world one as it is; the run is simulate_controlled's
    with the same models, and its budget closes with their impulse."""
    import tumble
    from tumble.commands import run_scenario
    from tumble.dynamics import ConstantTorque
    from tumble.dynamics.control.controlled import simulate_controlled

    text = ('body = { name = "box", parts = [{ kind = "box", mass = 4.0, size = [0.1, 0.2, 0.3] }] }\n'
            "[initial]\nomega = [0.0, 0.0, 0.01]\n[simulation]\nt_end = 60.0\n"
            "[[torque]]\nvector = [0.0, 0.0, 1e-6]\n[[torque]]\nvector = [1e-6, 0.0, 0.0]\nframe = \"world\"\n"
            "[actuators.wheels]\ninertia = 1e-5\n"
            '[control]\nkind = "mrp_pd"\nperiod = 0.5\nK = 1e-3\nP = 6e-3\n')
    path = tmp_path / "leak.toml"
    path.write_text(text)
    scenario = load_scenario(path)
    body = scenario.body
    P = body.principal_axes  # principal -> design
    body_term, world_term = scenario.torque.terms
    np.testing.assert_allclose(body_term.vector, P.T @ [0.0, 0.0, 1e-6], rtol=0, atol=1e-22)
    assert world_term == ConstantTorque((1e-6, 0.0, 0.0), "world")
    run = run_scenario(scenario)
    args = scenario.arguments()
    args["torque"] = [ConstantTorque(tuple(P.T @ [0.0, 0.0, 1e-6])), ConstantTorque((1e-6, 0.0, 0.0), "world")]
    ref = simulate_controlled(**args)
    np.testing.assert_array_equal(run.omega, ref.omega)
    assert np.linalg.norm(run.impulse_world[-1]) > 5e-5  # the torques acted
    L = run.momentum_world - run.impulse_world
    np.testing.assert_allclose(L, L[[0] * len(L)], rtol=0, atol=1e-9 * np.abs(run.impulse_world).max())
    assert isinstance(tumble.io.load_scenario(path).torque, tumble.TorqueSum)


def test_a_residual_dipole_table_is_the_disturbance_in_the_orbits_field(tmp_path, loop_runs):
    """[torque] kind = "residual_dipole" in a control file: the dipole read in the design frame (the
    box's principal axis 1 is design z), in the [orbit]'s own field; the run is compiled and is
    simulate_controlled's with the same ResidualDipole, and its budget closes with the impulse."""
    from tumble.commands import run_scenario
    from tumble.dynamics import ResidualDipole
    from tumble.dynamics.control.controlled import simulate_controlled

    text = ('body = { name = "box", parts = [{ kind = "box", mass = 4.0, size = [0.1, 0.2, 0.3] }] }\n'
            "[initial]\nomega = [0.0, 0.0, 0.05]\n[simulation]\nt_end = 300.0\n"
            "[orbit]\naltitude = 500e3\ninclination = 1.2\n"
            '[torque]\nkind = "residual_dipole"\ndipole = [0.0, 0.02, 0.05]\n'
            "[actuators.magnetorquers]\nmax_dipole = 0.2\n"
            '[control]\nkind = "bdot"\nperiod = 1.0\ngain = 3e-3\nform = "normalized"\n')
    path = tmp_path / "magnetic.toml"
    path.write_text(text)
    scenario = load_scenario(path)
    P = scenario.body.principal_axes  # principal -> design
    assert isinstance(scenario.torque, ResidualDipole) and scenario.torque.field is scenario.field
    np.testing.assert_allclose(scenario.torque.dipole, P.T @ [0.0, 0.02, 0.05], rtol=0, atol=1e-18)
    run = run_scenario(scenario)
    assert len(loop_runs) == 1   # compiled: a disturbance in the run's own field
    args = scenario.arguments()
    args["torque"] = ResidualDipole(tuple(P.T @ [0.0, 0.02, 0.05]), scenario.field)
    ref = simulate_controlled(**args)
    np.testing.assert_array_equal(run.omega, ref.omega)
    assert np.linalg.norm(run.impulse_world[-1]) > 1e-4 * np.linalg.norm(run.momentum_world[0])   # it acted
    L = run.momentum_world - run.impulse_world
    np.testing.assert_allclose(L, L[[0] * len(L)], rtol=0, atol=1e-9 * np.abs(run.momentum_world).max())


@pytest.mark.parametrize(("text", "message"), [
    ('[torque]\nkind = "residual_dipole"\ndipole = [0.0, 0.0, 0.05]\n',
     r'bad.toml: torque: kind = "residual_dipole" needs an \[orbit\] \(its magnetic field\)$'),
    ('[orbit]\naltitude = 500e3\n[torque]\nkind = "residual_dipole"\n', r"bad.toml: torque: missing key 'dipole' \(A m\^2\)$"),
    ('[orbit]\naltitude = 500e3\n[torque]\nkind = "residual_dipole"\ndipole = [0.0, 0.05]\n',
     r"bad.toml: torque: dipole = \[0.0, 0.05\] must be"),
    ('[orbit]\naltitude = 500e3\n[torque]\nkind = "residual_dipole"\ndipole = [0.0, 0.0, 0.05]\nvector = [0.0, 0.0, 1e-6]\n',
     r"bad.toml: torque: key 'vector' does not go with kind = 'residual_dipole'"),
])
def test_a_residual_dipole_table_that_cannot_be_run_is_refused_in_one_line(tmp_path, text, message):
    body = 'body = { name = "box", parts = [{ kind = "box", mass = 4.0, size = [0.1, 0.2, 0.3] }] }\n'
    path = tmp_path / "bad.toml"
    path.write_text(body + "[initial]\nomega = [0.0, 0.0, 0.05]\n[simulation]\nt_end = 10.0\n" + text
                    + "[actuators.wheels]\ninertia = 1e-5\n" + '[control]\nkind = "mrp_pd"\nperiod = 0.5\nK = 1e-3\nP = 6e-3\n')
    with pytest.raises(ValueError, match=message):
        load_scenario(path)


def test_a_scenario_file_says_where_a_residual_dipole_is_taken(tmp_path):
    path = tmp_path / "spin.toml"
    path.write_text('body = "t-handle"\n[initial]\nomega = [0.1, 10.0, 0.1]\n[simulation]\nt_end = 1.0\n'
                    '[torque]\nkind = "residual_dipole"\n')
    with pytest.raises(ValueError, match=r"kind = 'residual_dipole' is not taken here; allowed: constant, gravity_gradient "
                                         r"\(control files take a residual_dipole, in their \[orbit\]'s magnetic field\)"):
        load_scenario(path)


@pytest.mark.parametrize(("table", "message"), [
    ('[torque]\nkind = "gravity_gradient"\norbit_period = 5400.0\n',
     r"torque: kind = 'gravity_gradient' is not taken here; allowed: constant, residual_dipole \(the orbit's gravity gradient: "
     r"\[orbit\] gravity_gradient = true\)$"),
    ("[[torque]]\nvector = [0.0, 0.0, 1e-6]\n[[torque]]\nvector = [1e-6]\n",
     r"torque\[1\]: torque vector = \[1e-06\] must be a list of 3 numbers \(N m\)"),
])
def test_bad_torque_tables_in_a_control_file(tmp_path, capsys, table, message):
    text = (CONTROL / "point.toml").read_text()
    path = tmp_path / "bad.toml"
    path.write_text(text.replace("[actuators.wheels]", table + "[actuators.wheels]", 1))
    assert main(["simulate", str(path), "--out", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and re_search(message, err), err


def test_point_examples_steady_error_is_its_wheels_coulomb_friction(tmp_path):
    """point.toml's comment: "the wheels' Coulomb friction leaves a steady error of ~ 4 tau_c / K per
    axis (no integral term)". With no integral term the loop holds where K |sigma_i| meets the
    friction tau_c, an angle 4 sigma per axis (MRP, small angles; Schaub & Junkins ch. 8): at most
    sqrt(3) 4 tau_c / K over three axes. Without the friction the error is a fraction of it, and
    without the gravity gradient (the comment's earlier, wrong culprit) it is the same."""
    import tumble
    from tumble.io.controlrun import control_summary

    text = (CONTROL / "point.toml").read_text()
    assert "coulomb = 1e-7" in text and "K = 1.1e-3" in text and "gravity_gradient = true" in text
    bound = math.sqrt(3) * 4 * 1e-7 / 1.1e-3

    def final_error(changed: str) -> float:
        path = tmp_path / "point.toml"
        path.write_text(changed)
        scenario = load_scenario(path)
        return control_summary(scenario, tumble.run_scenario(scenario))["pointing_error_final"]

    shipped = final_error(text)
    assert 0.5 * bound < shipped < 1.2 * bound
    assert final_error(text.replace("coulomb = 1e-7", "coulomb = 0.0")) < 0.25 * shipped
    assert final_error(text.replace("gravity_gradient = true", "gravity_gradient = false")) == pytest.approx(shipped, rel=0.01)


def test_a_control_runs_csv_names_each_columns_unit_as_a_free_runs_does(tmp_path):
    """A walkthrough read `t,omega1,...,m1,B1,Lx_world,Jx_world`: no units, another naming than the free
    run's `t [s],omega_1 [rad/s],...` and the conventions'; `Jx_world` was the impulse, said nowhere."""
    from tumble.io.export import CSV_COLUMNS

    assert main(["simulate", str(CONTROL / "point.toml"), "--t-end", "2", "--out", str(tmp_path / "run")]) == 0
    header = (tmp_path / "run" / "trajectory.csv").read_text().splitlines()[0].split(",")
    assert header[:8] == list(CSV_COLUMNS[:8])
    assert all(name.startswith("q_") or name.endswith("]") for name in header)
    assert {"impulse_world_x [kg m^2/s]", "dipole_1 [A m^2]", "B_1 [T]", "wheel3_torque [N m]"} <= set(header)
    # the summary gives the principal axes (it did not), which take the file's design-frame omega to the CSV's
    axes = np.array(json.loads((tmp_path / "run" / "summary.json").read_text())["principal_axes"])
    first = np.loadtxt(tmp_path / "run" / "trajectory.csv", delimiter=",", skiprows=1)[0]
    np.testing.assert_allclose(first[1:4], axes.T @ [0.01, -0.01, 0.01], rtol=1e-12, atol=1e-15)
