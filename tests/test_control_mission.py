"""Detumble, then point (issue 21): the mode switch of DetumbleThenPoint against its closed form,
each mode against the same controller run alone, the ``detumble_point`` scenario through
``tumble simulate`` and the figures it writes."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tumble.cli import CONTROL_WRITES, main
from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.bdot import BDot
from tumble.dynamics.control.controllers import MomentumDumping, MRPFeedback
from tumble.dynamics.control.mission import DetumbleThenPoint
from tumble.dynamics.models.actuators import Magnetorquers, ReactionWheels
from tumble.dynamics.environment.magnetic import UniformField
from tumble.dynamics.models.sensors import Measurement
from tumble.io.examples import list_examples
from tumble.io.scenario import load_scenario
from tumble.viz.control import CONTROL_FIGURES, control_figures, wheel_momentum

CONTROL = Path(__file__).resolve().parents[1] / "examples" / "control"

# A spin about principal axis 3, square to a uniform field along x: normalised B-dot gives the
# torque -k omega held over each step, so |omega| falls by (1 - k dt / I3) a step and stays about
# axis 3 (the closed form of tests/test_control.py). The mission switches at the first step k
# with w0 (1 - k dt / I3)^j < switch_rate for every j in k - dwell/dt .. k.
I = np.array([0.01, 0.02, 0.03])  # kg m^2
W0, K, DT, B = 0.1, 2e-3, 0.5, 3e-5  # rad/s, N m s, s, T
SWITCH, DWELL = 0.03, 5.0  # rad/s, s
TARGET = Rotation.from_rotvec([0.0, 0.0, 0.4])
WHEELS = ReactionWheels(np.eye(3), inertia=1e-4, max_torque=1e-2)


def _mission(dumping: bool = False) -> DetumbleThenPoint:
    point = MRPFeedback(K=8e-3, P=1.4e-2, period=DT, moments=I, wheels=WHEELS, target=TARGET)
    return DetumbleThenPoint(BDot(gain=K, period=DT, form="normalized"),
                             MomentumDumping(point, gain=1e-2) if dumping else point,
                             switch_rate=SWITCH, dwell=DWELL)


def _run(controller, t_end=80.0, **kw):
    return simulate_controlled(I, [0.0, 0.0, W0], t_end=t_end, controller=controller, field=UniformField((B, 0.0, 0.0)),
                               magnetorquers=Magnetorquers(10.0), wheels=WHEELS, **kw)


@pytest.fixture(scope="module")
def mission_run():
    mission = _mission()
    return mission, _run(mission)


def test_the_switch_comes_when_the_closed_form_rate_has_stayed_below_for_the_dwell(mission_run):
    mission, run = mission_run
    below = math.ceil(math.log(SWITCH / W0) / math.log(1.0 - K * DT / I[2]))  # first step with w < SWITCH
    assert mission.switch_time == pytest.approx((below + DWELL / DT) * DT, abs=1e-12)
    k = round(mission.switch_time / DT)
    assert run.rate[k - round(DWELL / DT) - 1] >= SWITCH > run.rate[k - round(DWELL / DT)]
    # before the switch: B-dot's dipole and no wheel torque; from it on: the wheels and no dipole
    assert np.all(run.wheel_torque[:k] == 0.0) and np.all(run.dipole[k:] == 0.0)
    assert np.all(np.abs(run.dipole[:k, 1]) > 0.0) and np.all(np.linalg.norm(run.wheel_torque[k:-1], axis=1) > 0.0)


def test_each_mode_is_the_controller_run_alone(mission_run):
    mission, run = mission_run
    k = round(mission.switch_time / DT)
    alone = _run(BDot(gain=K, period=DT, form="normalized"), t_end=mission.switch_time)
    np.testing.assert_array_equal(alone.omega, run.omega[:k + 1])
    # from the switch's state, MRP feedback alone (the field makes no torque: no dipole is asked)
    point = MRPFeedback(K=8e-3, P=1.4e-2, period=DT, moments=I, wheels=WHEELS, target=TARGET)
    rest = simulate_controlled(I, run.omega[k], t_end=float(run.t[-1] - run.t[k]), controller=point,
                               attitude0=run.attitude[k], wheels=WHEELS, wheel_speed0=run.wheel_speed[k])
    np.testing.assert_allclose(rest.omega, run.omega[k:], rtol=0, atol=1e-12)
    np.testing.assert_allclose(rest.pointing_error(TARGET), run.pointing_error(TARGET)[k:], rtol=0, atol=1e-10)
    error = run.pointing_error(TARGET)
    assert error[-1] < 0.05 * error[k]  # it points
    assert run.budget_error().max() < 1e-15  # the field's torque is on the body: the impulse closes it


@pytest.mark.parametrize("dumping", [False, True])
def test_the_compiled_mission_is_the_python_one(dumping):
    """The mission on the compiled loop (each mode's law compiled, the switch found between:
    DetumbleThenPoint.compiled_run) switches at the same step as the controller called in Python
    (scipy's path, compiled=False), and the two runs agree to round-off."""
    compiled, python = _mission(dumping), _mission(dumping)
    fast, slow = _run(compiled, t_end=40.0), _run(python, t_end=40.0, compiled=False)
    assert compiled.switch_time is not None and compiled.switch_time == python.switch_time
    np.testing.assert_allclose(fast.omega, slow.omega, rtol=0, atol=1e-12)
    np.testing.assert_allclose(fast.wheel_speed, slow.wheel_speed, rtol=0, atol=1e-9)
    np.testing.assert_allclose(fast.dipole, slow.dipole, rtol=0, atol=1e-12)
    np.testing.assert_allclose(fast.wheel_torque, slow.wheel_torque, rtol=0, atol=1e-12)
    assert np.max((fast.attitude * slow.attitude.inv()).magnitude()) < 1e-10


def test_it_never_switches_back_and_a_new_run_starts_over(mission_run):
    mission, run = mission_run
    k = round(mission.switch_time / DT)
    assert run.rate[k:].max() > SWITCH  # the slew to the target raises the rate again: still pointing
    assert mission.mode == "point"
    again = _mission()
    _run(again, t_end=30.0)
    assert again.mode == "point"
    _run(again, t_end=10.0)  # the run calls reset(): detumbling again, and 10 s is too short to switch
    assert (again.mode, again.switch_time) == ("detumble", None)


def test_momentum_dumping_after_the_switch_pushes_across_the_field():
    mission = _mission(dumping=True)
    run = _run(mission, t_end=40.0)
    k = round(mission.switch_time / DT)
    after = run.dipole[k:-1]
    assert np.all(np.linalg.norm(after, axis=1) > 0.0)
    np.testing.assert_allclose(np.sum(after * run.field[k:-1], axis=1), 0.0, rtol=0, atol=1e-18)  # B x tau_d / |B|^2


def test_the_dwell_window_starts_again_when_the_rate_goes_back_up():
    mission = _mission()
    rates = [0.02, 0.02, 0.04] + [0.02] * 12  # below at 0 and 0.5 s, above at 1 s, below from 1.5 s
    for i, rate in enumerate(rates):
        mission(i * DT, Measurement(i * DT, np.array([rate, 0.0, 0.0]), np.array([B, 0.0, 0.0]), TARGET, np.zeros(3)))
    assert mission.switch_time == pytest.approx(1.5 + DWELL)


@pytest.mark.parametrize(("make", "message"), [
    (lambda: DetumbleThenPoint(BDot(gain=K, period=1.0), _mission().point, SWITCH, DWELL),
     "detumble.period = 1 s and point.period = 0.5 s differ"),
    (lambda: DetumbleThenPoint(_mission().point, _mission().point, SWITCH, DWELL), "must be a BDot controller"),
    (lambda: DetumbleThenPoint(BDot(gain=K, period=DT), BDot(gain=K, period=DT), SWITCH, DWELL),
     "must be an MRPFeedback or a MomentumDumping"),
    (lambda: DetumbleThenPoint(BDot(gain=K, period=DT), _mission().point, -1.0, DWELL), r"switch_rate = -1.0 must be"),
    (lambda: DetumbleThenPoint(BDot(gain=K, period=DT), _mission().point, SWITCH, -2.0), r"dwell = -2.0 must be"),
])
def test_bad_missions_are_refused_in_one_line(make, message):
    with pytest.raises(ValueError, match=message) as info:
        make()
    assert "\n" not in str(info.value)


def test_the_figures_carry_the_run(mission_run):
    mission, run = mission_run
    figures = control_figures(run, target=TARGET, switch_time=mission.switch_time, title="mission")
    assert tuple(figures) == CONTROL_FIGURES == CONTROL_WRITES
    (error_ax,) = figures["attitude_error.png"].axes
    np.testing.assert_array_equal(error_ax.lines[0].get_ydata(), np.degrees(run.pointing_error(TARGET)))
    rates_top, rates_bottom = figures["rates.png"].axes
    np.testing.assert_array_equal(rates_top.lines[2].get_ydata(), np.degrees(run.omega[:, 2]))
    np.testing.assert_array_equal(rates_bottom.lines[0].get_ydata(), np.degrees(run.rate))
    speeds, torques = figures["wheels.png"].axes
    for i in range(3):
        np.testing.assert_array_equal(speeds.lines[i].get_ydata(), run.wheel_speed[:, i])
        np.testing.assert_array_equal(torques.lines[i].get_ydata(), run.wheel_torque[:, i])
    (dipole_ax,) = figures["dipole.png"].axes
    np.testing.assert_array_equal(dipole_ax.lines[1].get_ydata(), run.dipole[:, 1])
    top, bottom = figures["momentum.png"].axes
    h = np.linalg.norm(WHEELS.momentum(run.wheel_speed), axis=1)  # sum J s g, from the wheels' own model
    np.testing.assert_allclose(top.lines[0].get_ydata(), h, rtol=0, atol=1e-15)
    np.testing.assert_allclose(wheel_momentum(run), WHEELS.momentum(run.wheel_speed), rtol=0, atol=1e-15)
    gap = run.budget_error()
    np.testing.assert_array_equal(bottom.lines[0].get_ydata(), gap[gap > 0.0])
    # the switch is marked on every panel
    for fig in figures.values():
        for ax in fig.axes:
            marks = [line for line in ax.lines if line.get_label() == "switch to pointing"]
            assert len(marks) == 1 and list(marks[0].get_xdata()) == [mission.switch_time] * 2


def _fast_mission(tmp_path: Path) -> Path:
    """The example from 2 deg/s with 5 A m^2 rods and a 70x B-dot gain: it switches within a minute."""
    text = (CONTROL / "detumble_point.toml").read_text()
    for old, new in (("[0.2016, -0.2016, 0.2016]", "[0.02, -0.02, 0.02]"), ("max_dipole = 0.2", "max_dipole = 5.0"),
                     ("switch_rate = 0.0175", "switch_rate = 0.025"), ("dwell = 60.0", "dwell = 10.0"),
                     ('kind = "detumble_point"', 'kind = "detumble_point"\ndetumble = { gain = 2e-3, form = "normalized" }')):
        assert old in text
        text = text.replace(old, new)
    path = tmp_path / "fast_mission.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("table", ['detumble = { gain = 2.95e-5 }', 'gain = 2.95e-5'])
def test_a_bdot_gain_without_its_form_is_refused_naming_both(tmp_path, capsys, table):
    """Avanzini & Giulietti's gain written into the mission's file (2.95e-5 N m s, the default's value) ran as the
    classic form's A m^2 s/T, commanded 4.8e-10 A m^2 of the 0.2 the rods have, never detumbled and exited 0 (a
    walkthrough of control.md, 2026-12-02): a gain given needs its form, in one line naming both units."""
    if table.startswith("gain"):  # a B-dot run of its own (detumble.toml): the gain in [control], its form left out
        text = (CONTROL / "detumble.toml").read_text()
        assert 'form = "normalized"' in text
        text = text.replace('form = "normalized"', table, 1)
    else:
        text = (CONTROL / "detumble_point.toml").read_text().replace('kind = "detumble_point"',
                                                                      'kind = "detumble_point"\n' + table)
    path = tmp_path / "mission.toml"
    path.write_text(text)
    assert main(["simulate", str(path), "--out", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "gain = 2.95e-05 needs its form: form = \"normalized\" for a gain in N m s" in err
    assert "form = \"classic\" for one in A m^2 s/T" in err and not (tmp_path / "run").exists()


def test_a_mission_that_never_switched_says_so(tmp_path, capsys):
    """The mission cut at 600 s, long before its switch (8258 s): the line gave "pointing error 2.77 rad" as though
    the pointing had begun (a walkthrough of control.md, 2026-12-02). It says the mission never switched and that
    the body was not detumbled, and gives no pointing error."""
    assert main(["simulate", str(CONTROL / "detumble_point.toml"), "--t-end", "600", "--out", str(tmp_path / "run")]) == 0
    line = capsys.readouterr().out
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["switch_time"] is None and summary["detumble_time"] is None
    assert "never switched to pointing" in line and "not detumbled" in line and "pointing error" not in line, line


def test_a_mission_that_started_below_its_switch_rate_says_so(tmp_path, capsys):
    """A switch_rate above the body's initial rate (a walkthrough of control.md, 2026-12-02): the mission points
    as soon as the dwell has passed and B-dot never acts; the line says it started below switch_rate, as a
    detumbling that started below its threshold does."""
    text = (CONTROL / "detumble_point.toml").read_text()
    path = tmp_path / "mission.toml"
    path.write_text(re.sub(r"switch_rate = [0-9.e-]+", "switch_rate = 10.0", text, count=1))
    assert main(["simulate", str(path), "--t-end", "200", "--out", str(tmp_path / "run")]) == 0
    line = capsys.readouterr().out
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["initial_rate"] < 10.0 and summary["switch_time"] is not None
    assert "(it started below switch_rate: nothing was detumbled)" in line, line
    assert main(["simulate", str(CONTROL / "detumble_point.toml"), "--t-end", "200", "--out", str(tmp_path / "b")]) == 0
    assert "started below" not in capsys.readouterr().out  # a mission that detumbles first: no such words


def test_the_mission_example_is_short_listed_and_runs_through_simulate(tmp_path, capsys):
    text = (CONTROL / "detumble_point.toml").read_text()
    assert len([line for line in text.splitlines() if line.strip() and not line.lstrip().startswith("#")]) <= 20
    assert {e.path: e.kind for e in list_examples()}["control/detumble_point.toml"] == "control"
    scenario = load_scenario(CONTROL / "detumble_point.toml")
    assert scenario.kind == "detumble_point" and type(scenario.controller()).__name__ == "DetumbleThenPoint"
    assert scenario.omega == pytest.approx(np.array(scenario.body.principal_axes).T @ [0.2016, -0.2016, 0.2016])
    out = tmp_path / "run"
    assert main(["simulate", str(_fast_mission(tmp_path)), "--t-end", "200", "--out", str(out), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert {"final_rate", "detumble_time", "pointing_error_final", "switch_time"} <= set(summary)
    assert summary["kind"] == "detumble_point" and summary["switch_rate"] == 0.025 and summary["gain"] == 2e-3
    data = np.load(out / "trajectory.npz")
    t, torque = data["t"], data["wheel_torque"]
    k = int(np.flatnonzero(np.any(torque != 0.0, axis=1))[0])  # wheels without friction: idle until the switch
    assert summary["switch_time"] == t[k] > 10.0
    rate = np.linalg.norm(data["omega"], axis=1)
    assert np.all(rate[k - 10:k + 1] < 0.025 + 5e-4)  # the gyroscope read below (noise 1e-4 rad/s)
    after, field = data["dipole"][k:-1], data["field"][k:-1]  # dumping: across the field (read with 100 nT noise)
    cosine = np.sum(after * field, axis=1) / np.linalg.norm(after, axis=1) / np.linalg.norm(field, axis=1)
    assert np.abs(cosine).max() < 0.02
    assert summary["pointing_error_final"] < math.radians(1.0)
    # where the pointing starts: the angle of the principal frame (the file's quaternion) from the target
    # at the switch; the start's error is the initial attitude's, not what the wheels had to turn through
    target = load_scenario(_fast_mission(tmp_path)).target
    at_switch = (target.inv() * Rotation.from_quat(data["quat"][k])).magnitude()
    assert summary["pointing_error_switch"] == pytest.approx(at_switch, rel=1e-6)
    assert summary["pointing_error_switch"] > 10 * summary["pointing_error_final"]
    for name in ("omega.png", *CONTROL_WRITES):
        assert (out / name).stat().st_size > 0, name


@pytest.mark.parametrize(("old", "new", "message"), [
    ("wheels = {", "# wheels = {", r'control: kind = "detumble_point" needs \[actuators.wheels\]'),
    ('attitude = "star_tracker"', 'attitude = "none"', r"control: kind = \"detumble_point\" points with the wheels"),
    ("dumping_gain = 1e-3", "Kd = 1e-3", r"control.point: unknown key 'Kd' \(did you mean 'K'\?\); allowed: K, Ki, P, dumping_gain"),
    ("dumping_gain = 1e-3", "dumping_gain = -1.0", r"control.point: dumping_gain = -1.0 must be a positive finite number \(1/s\)"),
    ("switch_rate = 0.0175 ", "", r"control: missing key 'switch_rate' \(rad/s\)"),
    ("dwell = 60.0 ", "dwell = -1.0 ", r"control: dwell = -1.0 must be"),
    ('kind = "detumble_point"', 'kind = "detumble_point"\ndetumble = { form = "fancy" }',
     r"control.detumble: form = 'fancy' is unknown"),
    # a missing key said "= None" (a walkthrough of docs/formats/control.md, 2026-12-03)
    ('kind = "detumble_point"', '', r"control: missing key 'kind' \(one of bdot, mrp_pd, detumble_point\)$"),
    ("simulation = { t_end = 10800.0 }", "simulation = { }", r"simulation: missing key 't_end' \(s\)$"),
])
def test_bad_mission_files_get_one_line_naming_the_table(tmp_path, capsys, old, new, message):
    text = (CONTROL / "detumble_point.toml").read_text()
    assert old in text
    path = tmp_path / "bad.toml"
    path.write_text(text.replace(old, new, 1))
    code = main(["simulate", str(path), "--out", str(tmp_path / "run")])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1, err
    assert __import__("re").search(message, err), err
    assert not (tmp_path / "run").exists()
