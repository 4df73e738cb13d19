"""Bad values in a control scenario: one ValueError naming the key (the CLI's one line and exit 2)."""

from __future__ import annotations

import copy
import re
from pathlib import Path

import numpy as np
import pytest

from tumble.cli import main
from tumble.io.bodyfile import body_from_table
from tumble.io.controlfile import control_scenario_from_table

BODY = {"name": "box", "parts": [{"kind": "box", "mass": 4.0, "size": [0.1, 0.2, 0.3]}]}
POINT = {"initial": {"omega": [0.0, 0.0, 0.01]}, "simulation": {"t_end": 1.0},
         "control": {"kind": "mrp_pd", "period": 0.5, "K": 1e-3, "P": 6e-3},
         "actuators": {"wheels": {"inertia": 2e-5, "max_torque": 2e-3}}}
DETUMBLE = {"initial": {"omega": [0.1, 0.1, 0.1]}, "simulation": {"t_end": 1.0},
            "orbit": {"altitude": 500e3, "inclination": 1.7}, "actuators": {"magnetorquers": {"max_dipole": 0.2}},
            "control": {"kind": "bdot", "period": 1.0}}


def _build(base: dict, section: str, **changes: object):
    table = copy.deepcopy(base)
    table[section].update(changes)
    return control_scenario_from_table(table, body_from_table(BODY))


@pytest.mark.parametrize("kind", [[1], {"a": 1}, 3])
def test_a_kind_that_is_not_a_string_is_refused_by_name(kind):
    with pytest.raises(ValueError, match=r"^control: kind = .* is unknown; allowed: bdot, mrp_pd, detumble_point$"):
        _build(POINT, "control", kind=kind)


@pytest.mark.parametrize(("section", "base", "key"), [("orbit", DETUMBLE, "gravity_gradient"),
                                                      ("orbit", DETUMBLE, "earth_rotation"),
                                                      ("control", POINT, "gyroscopic")])
def test_a_switch_given_as_a_string_is_refused_not_read_as_true(section, base, key):
    with pytest.raises(ValueError, match=rf"^{section}: {key} = 'no' must be true or false$"):
        _build(base, section, **{key: "no"})
    on = _build(base, section, **{key: True})
    off = _build(base, section, **{key: False})
    value = {"gravity_gradient": lambda s: s.gravity_gradient, "earth_rotation": lambda s: s.field.earth_rotation,
             "gyroscopic": lambda s: s.controller().gyroscopic}[key]
    assert (value(on), value(off)) == (True, False)


def test_the_cli_gives_one_line_and_exit_2_and_writes_nothing(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text('body = { name = "b", parts = [{ kind = "box", mass = 4.0, size = [0.1, 0.2, 0.3] }] }\n'
                    "initial = { omega = [0.0, 0.0, 0.01] }\nsimulation = { t_end = 1.0 }\n"
                    "[actuators.wheels]\ninertia = 2e-5\n[control]\nkind = [1]\nperiod = 0.5\n")
    out = tmp_path / "out"
    assert main(["simulate", str(path), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "control: kind = [1] is unknown" in err
    assert not out.exists()


@pytest.mark.parametrize(("table", "axes", "message"), [
    ("magnetorquers", [[1, 0], [0, 1]], (r"^actuators\.magnetorquers: axes = \[\[1, 0\], \[0, 1\]\] must be real "
                                         r"numbers of shape \(\.\.\., 3\) \(design frame\), not shape \(2, 2\)$")),
    ("wheels", "x", r"^actuators\.wheels: axes = 'x' must be real numbers of shape \(\.\.\., 3\) \(design frame\)$")])
def test_actuator_axes_of_the_wrong_shape_are_named_not_a_numpy_error(table, axes, message):
    base = DETUMBLE if table == "magnetorquers" else POINT
    with pytest.raises(ValueError, match=message):
        _build(base, "actuators", **{table: {**base["actuators"][table], "axes": axes}})


@pytest.mark.parametrize("speed0", [[1.0, 2.0], "x", [[1.0, 2.0, 3.0]]])
def test_wheel_speed0_must_hold_one_speed_per_wheel(speed0):
    with pytest.raises(ValueError, match=r"^actuators\.wheels: speed0 = .* must be "):
        _build(POINT, "actuators", wheels={**POINT["actuators"]["wheels"], "speed0": speed0})
    one = {"axes": [[0.0, 0.0, 1.0]], "inertia": 2e-5}
    one_wheel = _build(DETUMBLE, "actuators", wheels={**one, "speed0": 5})
    assert one_wheel.speed0 == (5.0,)  # one wheel: a number will do
    three = _build(POINT, "actuators", wheels={**POINT["actuators"]["wheels"], "speed0": [1, 2, 3]})
    assert three.speed0 == (1.0, 2.0, 3.0)


@pytest.mark.parametrize("degree", [True, "13", 13.5, 0])
def test_igrf_degree_errors_name_the_file_key(degree):
    with pytest.raises(ValueError, match=r"^orbit: igrf_degree = .* must be a whole number from 1 to 13$"):
        _build(DETUMBLE, "orbit", field="igrf", epoch="2026-11-25T00:00:00", igrf_degree=degree)


def test_a_nadir_axis_vector_of_the_wrong_length_is_named():
    with pytest.raises(ValueError, match=r"^control: nadir_axis = \[1, 0\] must be a list of 3 numbers"):
        _build({**POINT, "orbit": {"altitude": 500e3}}, "control", target="nadir", nadir_axis=[1, 0])
    with pytest.raises(ValueError, match=r"^control: nadir_axis = \[0, 0, 0\] must be a non-zero vector"):  # as given
        _build({**POINT, "orbit": {"altitude": 500e3}}, "control", target="nadir", nadir_axis=[0, 0, 0])


def test_an_empty_orbit_table_is_refused_not_read_as_no_orbit():
    with pytest.raises(ValueError, match=r"^orbit: give exactly one of altitude"):
        control_scenario_from_table({**POINT, "orbit": {}}, body_from_table(BODY))


#: The ISS's TLE of docs/control.md's example (examples/control/detumble_tle.toml), as published.
ISS = ("1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991",
       "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482")


@pytest.mark.parametrize(("tle", "message"), [
    ([1, 2], r"^orbit: tle = \[1, 2\] must be a list of the two lines of a TLE \(strings\)$"),
    (["a", "b"], r"^orbit: tle\[0\] = 'a' must be the first line of a TLE \(a string of 69 characters\)$"),
    # a walkthrough (2026-12-03): sgp4 checks neither; an edited digit flew with exit 0, a space added failed
    # with scipy's "`y` must contain only finite values"
    ([ISS[0], ISS[1][:-1] + "9"], r"^orbit: tle\[1\]: checksum 9, its digits give 2: the line was changed after it "
                                  r"was published \(give it exactly as published\)$"),
    ([ISS[0].replace("25544U", "25544U "), ISS[1]], r"^orbit: tle\[0\] = '1 25544U  98067A .*' has 70 characters; the "
                                                     r"first line of a TLE has 69 in fixed columns, starting with 1 "
                                                     r"and ending with its checksum digit \(a space added or lost\?\)$")])
def test_tle_lines_that_are_not_two_strings_are_named_by_the_file_key(tle, message):
    pytest.importorskip("sgp4")
    orbit = {"tle": tle, "field": "igrf"}
    with pytest.raises(ValueError, match=message):
        control_scenario_from_table({**DETUMBLE, "orbit": orbit}, body_from_table(BODY))


def test_a_control_run_that_fails_while_writing_leaves_the_folder_as_it_was(tmp_path, monkeypatch, capsys):
    import tumble.viz

    path = tmp_path / "point.toml"
    path.write_text('body = { name = "b", parts = [{ kind = "box", mass = 4.0, size = [0.1, 0.2, 0.3] }] }\n'
                    "initial = { omega = [0.0, 0.0, 0.01] }\nsimulation = { t_end = 1.0 }\n"
                    "[actuators.wheels]\ninertia = 2e-5\n[control]\nkind = \"mrp_pd\"\nperiod = 0.5\nK = 1e-3\nP = 6e-3\n")
    out = tmp_path / "out"
    real = tumble.viz.save_figure

    def failing(fig, file, *args, **kwargs):
        if file.name == "wheels.png":  # after trajectory.*, omega.png and two figures are staged
            raise OSError("disk full")
        return real(fig, file, *args, **kwargs)

    monkeypatch.setattr(tumble.viz, "save_figure", failing)
    assert main(["simulate", str(path), "--out", str(out)]) == 1
    assert "disk full" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["point.toml"]  # no folder, no staging left
    monkeypatch.setattr(tumble.viz, "save_figure", real)
    assert main(["simulate", str(path), "--out", str(out)]) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    assert set(before) == {"trajectory.csv", "trajectory.npz", "summary.json", "omega.png", "attitude_error.png",
                           "rates.png", "wheels.png", "momentum.png"}  # no magnetorquers: no dipole.png
    monkeypatch.setattr(tumble.viz, "save_figure", failing)
    assert main(["simulate", str(path), "--t-end", "0.5", "--out", str(out)]) == 1
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before  # the earlier run, whole


@pytest.mark.parametrize("speed", [0, -1.0])
def test_an_actuator_error_names_its_table(speed):
    with pytest.raises(ValueError, match=rf"^actuators\.wheels: limit_cycle_speed\[0\] = {float(speed)} must be a "
                                         r"positive finite number \(rad/s\)$"):
        _build(POINT, "actuators", wheels={**POINT["actuators"]["wheels"], "limit_cycle_speed": speed})
    with pytest.raises(ValueError, match=r"^actuators\.magnetorquers: max_dipole = 'x' must be real numbers"):
        _build(DETUMBLE, "actuators", magnetorquers={"max_dipole": "x"})


@pytest.mark.parametrize("rtol", [1e-20, 5.0])
def test_a_relative_tolerance_out_of_range_is_refused_by_the_file_and_by_simulate_controlled(rtol):
    from tumble.dynamics.control.controlled import simulate_controlled
    from tumble.dynamics.control.bdot import BDot

    with pytest.raises(ValueError, match=rf"^simulation\.rtol = {rtol!r} must be from 2\.22e-14 to 0\.1 \(relative\)$"):
        _build(POINT, "simulation", rtol=rtol)
    with pytest.raises(ValueError, match=rf"^rtol = {rtol!r} must be from "):
        simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=1.0, controller=BDot(gain=1e-3, period=1.0),
                            rtol=rtol)
    with pytest.raises(ValueError, match=r"^atol = -1\.0 must be a positive finite number \(absolute: rad/s for omega "
                                         r"and the wheels, 1 for the quaternion\)$"):
        simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=1.0, controller=BDot(gain=1e-3, period=1.0),
                            atol=-1.0)


def test_mrp_pd_without_an_attitude_sensor_is_refused_when_the_file_is_read():
    with pytest.raises(ValueError, match=r'^control: kind = "mrp_pd" points with the wheels and needs an attitude '
                                         r'sensor; sensors.attitude = "none" gives none$'):
        _build({**POINT, "sensors": {}}, "sensors", attitude="none")


def test_magnetorquers_without_an_orbit_are_refused_when_the_file_is_read():
    table = copy.deepcopy(POINT)
    table["actuators"]["magnetorquers"] = {"max_dipole": 0.2}
    with pytest.raises(ValueError, match=r'^actuators\.magnetorquers need a field: a circular \[orbit\] \(its dipole\) or field = "igrf"$'):
        control_scenario_from_table(table, body_from_table(BODY))


def test_axes_that_are_not_square_are_echoed_as_written():
    """Issue 27, item 7: a nadir/normal pair that is not square was reported in the principal frame
    with numpy's repr (``normal_axis = array([0.70710678, 0., 0.70710678])``); the message echoes the
    design-frame vectors (or labels) as the file has them."""
    with pytest.raises(ValueError, match=(r"^control: normal_axis = \[1, 0, 1\] must be square to nadir_axis = "
                                          r"\[1, 0, 0\] \(their angle is 45 deg\)$")):
        _build({**POINT, "orbit": {"altitude": 500e3}}, "control", target="nadir", nadir_axis=[1, 0, 0],
               normal_axis=[1, 0, 1])
    # a label and a vector, each as given: the box's long design axis z is its minor principal axis
    with pytest.raises(ValueError, match=r"^control: normal_axis = \[0.0, 0.0, 1.0\] must be square to nadir_axis = "
                                         r"'minor' \(their angle is 0 deg\)$"):
        _build({**POINT, "orbit": {"altitude": 500e3}}, "control", target="nadir", nadir_axis="minor",
               normal_axis=[0.0, 0.0, 1.0])


def test_a_misspelt_control_key_lists_its_kinds_keys_and_its_nearest():
    """A typo in [control] listed every kind's keys (switch_rate, dwell, gain, ... for an mrp_pd run); it
    lists the kind's own, with the nearest; a key of another kind still says it does not go with this one."""
    with pytest.raises(ValueError, match=r"^control: unknown key 'perido' \(did you mean 'period'\?\); allowed with "
                                         r"kind = 'mrp_pd': K, Ki, P, gyroscopic, integral_limit, kind, nadir_axis, "
                                         r"normal_axis, period, target, threshold$"):
        _build(POINT, "control", perido=0.5)
    with pytest.raises(ValueError, match=r"^control: key 'dwell' does not go with kind = 'mrp_pd'; allowed: K, "):
        _build(POINT, "control", dwell=60.0)


@pytest.mark.parametrize(("rename", "said"), [
    ("controll", r"unknown table 'controll': did you mean \[control\]"),
    (None, r"\[actuators\] belongs to a control scenario, which needs a \[control\] table"),
])
def test_a_control_scenario_without_its_control_table_is_told_so(tmp_path, capsys, rename, said):
    """Without [control] (left out, or misspelt) a control scenario was read as a plain one and refused
    as "unknown key 'actuators'", naming neither the table nor its misspelling."""
    text = ('body = { name = "b", parts = [{ kind = "box", mass = 4.0, size = [0.1, 0.2, 0.3] }] }\n'
            "initial = { omega = [0.0, 0.0, 0.01] }\nsimulation = { t_end = 1.0 }\n[actuators.wheels]\ninertia = 2e-5\n")
    if rename is not None:
        text += f"[{rename}]\nkind = \"mrp_pd\"\nperiod = 0.5\nK = 1e-3\nP = 6e-3\n"
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert main(["simulate", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and re.search(said, err), err


def test_a_missions_period_is_named_as_its_key():
    """detumble_point's period = 0 was said as "control.detumble: period = 0.0 ...", a table the file has not."""
    mission = {"initial": {"omega": [0.1, 0.1, 0.1]}, "simulation": {"t_end": 1.0},
               "orbit": {"altitude": 500e3, "inclination": 1.7},
               "actuators": {"magnetorquers": {"max_dipole": 0.2}, "wheels": {"inertia": 2e-5, "max_torque": 2e-3}},
               "control": {"kind": "detumble_point", "period": 0.0, "switch_rate": 0.0175, "dwell": 60.0,
                           "point": {"K": 1e-3, "P": 6e-3}}}
    with pytest.raises(ValueError, match=r"^control: period = 0\.0 must be a positive finite number \(s\)$"):
        control_scenario_from_table(mission, body_from_table(BODY))


def test_wheel_friction_the_motor_cannot_overcome_is_refused(tmp_path, capsys):
    """Coulomb friction of 1e-2 N m on a motor of 2e-3 N m: the wheel can never turn, and the run
    crawled through its stiff linear zone (killed after 100 s; a walkthrough, issue 40)."""
    from tumble.cli import main
    from tumble.dynamics.models.actuators import ReactionWheels

    with pytest.raises(ValueError, match=r"^coulomb\[1\] = 0.01 N m is at least max_torque\[1\] = 0.002 N m: the motor "
                                         r"could never turn the wheel"):
        ReactionWheels(np.eye(3), inertia=2e-5, max_torque=2e-3, coulomb=[1e-7, 1e-2, 1e-7])
    ReactionWheels(np.eye(3), inertia=2e-5, max_torque=2e-3, coulomb=1e-4)  # a few % of it: taken
    text = (Path(__file__).resolve().parents[1] / "examples" / "control" / "point.toml").read_text()
    (tmp_path / "stuck.toml").write_text(text.replace("coulomb = 1e-7", "coulomb = 1e-2"))
    assert main(["simulate", str(tmp_path / "stuck.toml"), "--out", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "the motor could never turn the wheel" in err and not (tmp_path / "run").exists()


@pytest.mark.parametrize(("key", "value", "words"), [
    ("magnetometer_noise", 100.0, r"magnetometer_noise = 100.0 T is more than the Earth's field .* is it in nT\?"),
    ("magnetometer_bias", [100.0, 0.0, 0.0], r"magnetometer_bias = \[100.0, 0.0, 0.0\] T is more than the Earth's field "
                                             r".* is it in nT\?"),
    ("attitude_noise", 4.0, r"attitude_noise = 4.0 rad: a spread past pi says nothing of an angle; .* arcsec or deg\?"),
])
def test_sensor_noise_no_sensor_has_is_refused_as_a_likely_unit_slip(key, value, words):
    """100 'T' of magnetometer noise (meant 100 nT) hid the field and B-dot did nothing; 4 rad of star
    tracker noise ran; both without a word (a walkthrough, issue 40). A bias of 100 'T' ran too, until
    a walkthrough of docs/control.md (2026-12-03)."""
    from tumble.dynamics.models.sensors import MAX_MAGNETOMETER_NOISE, Sensors

    with pytest.raises(ValueError, match=rf"^{words}"):
        Sensors(**{key: value})
    Sensors(magnetometer_noise=MAX_MAGNETOMETER_NOISE, attitude_noise=np.pi,   # the bounds themselves: taken
            magnetometer_bias=[0.0, -MAX_MAGNETOMETER_NOISE, 0.0])


@pytest.mark.parametrize(("old", "new", "words"), [
    ("gyro_noise = 1e-4", "gyro_noise = 5.0", r"gyro_noise = 5.0 rad/s is more than a gyroscope spreads; allowed: "
                                              r"0 to 0.2 rad/s: is it in deg/s\?"),
    ("gyro_bias = [2e-4, -1e-4, 1.5e-4]", "gyro_bias = [2.0, -1.0, 1.5]",
     r"gyro_bias = \[2.0, -1.0, 1.5\] rad/s is more than any gyroscope's bias .* is it in deg/s\?"),
    ('kind = "coarse", noise = 2e-3', 'kind = "fine", noise = 10.0',
     r"noise = 10.0 rad is more than a fine sun sensor spreads; .* is it in arcsec or deg\?"),
    ('kind = "coarse", noise = 2e-3', 'kind = "coarse", noise = 2.0',
     r"noise = 2.0 is more than a cell's full-Sun current; allowed: 0 to 1 \(a fraction of it: 0.01 is 1 %\)"),
    ('attitude = "none"', 'attitude = "none"\nstar_tracker = { cross = 5.0, roll = 40.0 }',
     r"cross = 5.0 rad is more than a star tracker spreads; .* is it in arcsec or deg\?"),
])
def test_a_gyroscope_or_direction_sensor_noise_no_sensor_has_is_refused(tmp_path, capsys, old, new, words):
    """A walkthrough of docs/estimation.md (2026-12-02) gave the example's sensors values in deg/s, arcsec or
    per cent written as rad/s, rad or a fraction: a gyroscope bias of 2 'rad/s', 5 rad/s of noise, a fine sun
    sensor of 10 rad, coarse cells at 200 % of their current, a star tracker of 5 and 40 rad; each ran, exit
    0, the knowledge 50-122 deg off. Each is refused in one line naming the key, the value and the likely
    unit, nothing written; the bounds' own values are taken."""
    from tumble.dynamics.models.sensors import MAX_GYRO_ERROR, Sensors
    from tumble.dynamics.models.vector_sensors import MAX_ANGLE_NOISE, CoarseSunSensor, FineSunSensor, StarTracker

    text = (Path(__file__).resolve().parents[1] / "examples" / "control" / "estimate_point.toml").read_text()
    assert old in text
    (tmp_path / "slip.toml").write_text(text.replace(old, new, 1))
    assert main(["simulate", str(tmp_path / "slip.toml"), "--t-end", "5", "--out", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and re.search(words, err), err
    assert not (tmp_path / "run").exists()
    Sensors(gyro_noise=MAX_GYRO_ERROR, gyro_bias=(MAX_GYRO_ERROR, 0.0, -MAX_GYRO_ERROR))  # the bounds: taken
    FineSunSensor(noise=MAX_ANGLE_NOISE), StarTracker(cross=MAX_ANGLE_NOISE, roll=MAX_ANGLE_NOISE), CoarseSunSensor(noise=1.0)


def test_a_filter_started_with_an_attitude_spread_past_pi_is_refused():
    """MEKF.start(attitude_sigma=5.0) was taken (a walkthrough, 2026-12-02): a spread past pi says nothing of an
    angle. Refused in the filter and in the estimator's own start, naming the argument; pi itself is taken."""
    from scipy.spatial.transform import Rotation

    from tumble.dynamics.estimation.mekf import MEKF

    with pytest.raises(ValueError, match=r"^attitude_sigma = 5.0 is beyond 3.14159 rad"):
        MEKF.start(Rotation.identity(), attitude_sigma=5.0, bias_sigma=1e-3, gyro_noise=1e-4, bias_walk=1e-7)
    MEKF.start(Rotation.identity(), attitude_sigma=np.pi, bias_sigma=1e-3, gyro_noise=1e-4, bias_walk=1e-7)

def test_an_estimator_started_with_an_attitude_spread_past_pi_is_refused(tmp_path, capsys):
    text = (Path(__file__).resolve().parents[1] / "examples" / "control" / "estimate_point.toml").read_text()
    assert "attitude_sigma" not in text
    (tmp_path / "wide.toml").write_text(text.replace("[estimator]\n", "[estimator]\nattitude_sigma = 5.0\n", 1))
    assert main(["simulate", str(tmp_path / "wide.toml"), "--t-end", "5", "--out", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "attitude_sigma = 5.0 is beyond 3.14159 rad" in err, err


def test_wheels_heavier_than_the_body_are_refused():
    """A walkthrough of docs/control.md (2026-12-03): wheels of 0.5 kg m^2 in a body of 0.04 ran with
    exit 0, the kinetic energy growing 130 times with the motors doing negative work (the body less its
    wheels has a negative moment). Refused, in the file's words and in simulate_controlled's."""
    from tumble.dynamics.control.controlled import simulate_controlled
    from tumble.dynamics.control.controllers import MRPFeedback
    from tumble.dynamics.models.actuators import ReactionWheels

    with pytest.raises(ValueError, match=r"^actuators.wheels: inertia = \[0.5, 0.5, 0.5\] kg m\^2 is more than the body's "
                                         r"moments .* hold: the body less its wheels would have a moment of -0\.\d+ kg m\^2"):
        _build(POINT, "actuators", wheels={"inertia": 0.5, "max_torque": 2e-3})
    moments = [0.0067, 0.0419, 0.0419]
    big = ReactionWheels(np.eye(3), inertia=0.5, max_torque=2e-3)
    with pytest.raises(ValueError, match=r"^wheels.inertia = \[0.5, 0.5, 0.5\] kg m\^2 is more than the body's moments"):
        simulate_controlled(moments, [0.0, 0.0, 0.01], t_end=1.0, wheels=big,
                            controller=MRPFeedback(K=1e-3, P=6e-3, period=0.5, moments=moments, wheels=big))


def test_an_unstable_bdot_gain_is_warned_of_and_a_stable_one_is_not():
    """Normalised B-dot with gain 300 N m s held 1 s on a 3U CubeSat spun it from 0.017 to 92 rad/s,
    reported only as "not detumbled" (a walkthrough of docs/control.md, 2026-12-03): its held loop
    overshoots past k T / I = 2, and the run says so as MRP feedback's does."""
    import warnings

    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.control.controlled import simulate_controlled
    from tumble.dynamics.control.sampled import UnstableLoopWarning
    from tumble.dynamics.environment.magnetic import UniformField
    from tumble.dynamics.models.actuators import Magnetorquers

    moments = [0.00667, 0.0419, 0.0419]
    kw = dict(t_end=3.0, magnetorquers=Magnetorquers(1e6), field=UniformField((2e-5, 0.0, 1e-5)))
    with pytest.warns(UnstableLoopWarning, match=r"^gain = 300 N m s: B-dot held for period = 1 s is unstable about "
                                                 r"principal axis 1 .*give a gain below 0.0133 N m s"):
        simulate_controlled(moments, [0.01, 0.01, 0.01], controller=BDot(gain=300.0, period=1.0, form="normalized"), **kw)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        simulate_controlled(moments, [0.01, 0.01, 0.01], controller=BDot(gain=1e-4, period=1.0, form="normalized"), **kw)


def test_an_unstable_classic_bdot_gain_is_warned_of_and_it_is_unstable():
    """Classic B-dot's torque m x B = -k_b |B|^2 omega_perp is the normalised loop with k = k_b |B|^2:
    past k_b |B|^2 T / I = 2 (|B| the largest along the run) it overshoots. Only the normalised form
    was checked; a classic gain just past the bound spun a 3U CubeSat from 0.017 to over 1 rad/s in a
    minute without a word, while one just below it damps."""
    import warnings

    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.control.controlled import simulate_controlled
    from tumble.dynamics.control.sampled import UnstableLoopWarning
    from tumble.dynamics.environment.magnetic import UniformField
    from tumble.dynamics.models.actuators import Magnetorquers

    moments, B = [0.00667, 0.0419, 0.0419], 3e-5
    bound = 2.0 * moments[0] / B**2  # A m^2 s/T, period 1 s
    kw = dict(t_end=60.0, magnetorquers=Magnetorquers(1e6), field=UniformField((0.0, 0.0, B)))
    with pytest.warns(UnstableLoopWarning, match=r"^gain = 1\.55633e\+07 A m\^2 s/T: classic B-dot held for period = 1 s "
                                                 r"is unstable about principal axis 1 \(I = 0\.00667 kg m\^2: k_b \|B\|\^2 "
                                                 r"T / I = 2\.1 > 2 with \|B\| up to 3e-05 T along the run\).*below 1\.48e\+07"):
        past = simulate_controlled(moments, [0.01, 0.01, 0.01], controller=BDot(gain=1.05 * bound, period=1.0), **kw)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        below = simulate_controlled(moments, [0.01, 0.01, 0.01], controller=BDot(gain=0.95 * bound, period=1.0), **kw)
    assert np.linalg.norm(past.omega[-1]) > 1.0 > 0.02 > np.linalg.norm(below.omega[-1])


def test_a_normalised_gain_taken_as_classic_is_warned_of_and_a_short_run_of_a_right_gain_is_not(tmp_path, capsys):
    """A walkthrough of docs/control.md (2026-12-03): Avanzini & Giulietti's gain (bdot_gain, N m s) given to BDot
    without its form is read as classic (A m^2 s/T): in a 500 km, 97.4 deg orbit it commanded 2.4e-10 A m^2 and left
    10 deg/s at 10 deg/s, without a word. Its time constant I3 / (k_b |B|^2), ~1e12 s, says so; the same gain in its
    form detumbles, and a few seconds of a right gain (time constant ~1e3 s) say nothing."""
    import warnings

    from tumble.dynamics import CircularOrbit, DipoleField
    from tumble.dynamics.control.bdot import BDot, bdot_gain
    from tumble.dynamics.control.controlled import simulate_controlled
    from tumble.dynamics.control.sampled import WeakLoopWarning
    from tumble.dynamics.models.actuators import Magnetorquers

    moments = [0.00667, 0.0419, 0.0419]
    orbit = CircularOrbit(altitude=500e3, inclination=np.radians(97.4))
    k = bdot_gain(orbit.mean_motion, orbit.inclination, moments[0])
    w0 = np.radians([10.0, -8.0, 6.0])
    kw = dict(t_end=3000.0, field=DipoleField(orbit), magnetorquers=Magnetorquers(0.2))
    with pytest.warns(WeakLoopWarning, match=rf"^gain = {k:g} A m\^2 s/T: classic B-dot changes the rate about principal "
                                             r"axis 3 \(I = 0\.0419 kg m\^2\) with a time constant of \d\.\d+e\+1[1-3] s or "
                                             r"more .*it leaves the rate as it was; a normalised gain .*form = \"normalized\""):
        slip = simulate_controlled(moments, w0, controller=BDot(gain=k, period=1.0), **kw)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        right = simulate_controlled(moments, w0, controller=BDot(gain=k, period=1.0, form="normalized"), **kw)
        simulate_controlled(moments, w0, controller=BDot(gain=k, period=1.0, form="normalized"), **{**kw, "t_end": 5.0})
    assert np.linalg.norm(slip.omega[-1]) == pytest.approx(np.linalg.norm(w0), rel=1e-3)
    assert np.linalg.norm(right.omega[-1]) < 0.5 * np.linalg.norm(w0)


def test_a_wheel_speed_limit_in_rpm_is_refused(tmp_path, capsys):
    """A walkthrough of docs/control.md (2026-12-03): point.toml's max_speed = 630 (rad/s) written as 6000 (rpm) ran,
    and the wheels that saturated at 630 rad/s (3.08 rad off the target) reached 1210 rad/s and pointed, without a
    word. A limit past any reaction wheel's is refused in one line, naming rpm; inf (no limit) is taken."""
    from tumble.dynamics.models.actuators import MAX_WHEEL_SPEED, ReactionWheels

    with pytest.raises(ValueError, match=r"^max_speed\[0\] = 6000 rad/s \(5.73e\+04 rpm\) is faster than a reaction wheel "
                                         r"turns; allowed: up to 2500 rad/s, or inf for no limit: is it in rpm\? Give "
                                         r"rad/s \(6000 rpm = 628.3 rad/s\)$"):
        ReactionWheels(np.eye(3), inertia=2e-5, max_speed=6000.0)
    ReactionWheels(np.eye(3), inertia=2e-5, max_speed=[MAX_WHEEL_SPEED, np.inf, 630.0])  # taken
    text = (Path(__file__).resolve().parents[1] / "examples" / "control" / "point.toml").read_text()
    assert "max_speed = 630.0" in text
    (tmp_path / "rpm.toml").write_text(text.replace("max_speed = 630.0", "max_speed = 6000.0"))
    assert main(["simulate", str(tmp_path / "rpm.toml"), "--out", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "is it in rpm?" in err and not (tmp_path / "run").exists()


def test_a_quaternion_written_scalar_first_is_warned_of(tmp_path, capsys):
    """A walkthrough of docs/formats/control.md (2026-12-03): target = [1.0, 0.0, 0.0, 0.0], the identity written scalar
    first, was read without a word as a half turn about x (tumble's quaternions are scalar last, as scipy's). [+-1, 0, 0, 0]
    is warned of wherever a quaternion is read; a quaternion in scalar-last order is not."""
    import warnings

    from tumble.validation import check_rotation
    from tumble.validation.rotations import ScalarFirstWarning

    for written in ([1.0, 0.0, 0.0, 0.0], np.array([-1.0, 0.0, 0.0, 0.0]), (1, 0, 0, 0)):
        with pytest.warns(ScalarFirstWarning, match=r"^attitude = \[-?1, 0, 0, 0\] is a half turn about x in tumble's "
                                                    r"scalar-last order \[x, y, z, w\] \(scipy's\); the identity is "
                                                    r"\[0, 0, 0, 1\]: written scalar first\?$"):
            check_rotation("attitude", written)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for fine in ([0.0, 0.0, 0.0, 1.0], [0.7071067811865476, 0.0, 0.0, 0.7071067811865476], np.eye(3)):
            check_rotation("attitude", fine)
    text = (Path(__file__).resolve().parents[1] / "examples" / "control" / "point.toml").read_text()
    target = next(line for line in text.splitlines() if line.startswith("target = "))
    (tmp_path / "sf.toml").write_text(text.replace(target, "target = [1.0, 0.0, 0.0, 0.0]"))
    assert main(["simulate", str(tmp_path / "sf.toml"), "--out", str(tmp_path / "run")]) == 0
    err = capsys.readouterr().err
    assert err.startswith("warning: target = [1, 0, 0, 0] is a half turn about x") and err.count("\n") == 1


def test_a_control_period_that_is_a_large_share_of_the_orbit_is_warned_of(tmp_path, capsys):
    """A walkthrough of docs/control.md (2026-12-03): detumble.toml with period = 6000 s on its 5677 s orbit and a small
    gain ran with no word but the figure's. A period past a tenth of the orbit warns, in one line naming the orbit."""
    text = (Path(__file__).resolve().parents[1] / "examples" / "control" / "detumble.toml").read_text()
    period = next(line for line in text.splitlines() if line.startswith("period = "))
    (tmp_path / "long.toml").write_text(text.replace(period, "period = 6000.0"))
    assert main(["simulate", str(tmp_path / "long.toml"), "--out", str(tmp_path / "run")]) == 0
    err = capsys.readouterr().err
    assert "warning: period = 6000 s is more than a tenth of the orbit (5677 s): the field and an orbiting target turn " \
           "through 380 deg of the orbit between commands" in err
    (tmp_path / "right.toml").write_text(text)
    assert main(["simulate", str(tmp_path / "right.toml"), "--out", str(tmp_path / "run3")]) == 0
    assert "tenth of the orbit" not in capsys.readouterr().err
