"""A Betaflight flight controller's blackbox CSV read as a throw (issue #42, item 7).

The logs are written here from synthetic throws (:mod:`tumble.analysis.tensor.synthetic`) as
``blackbox_decode`` and Blackbox Explorer write them: the log's integer counts (the gyroscope in
counts of the device's ``gyro_lsb``, the accelerometer at 2048 per g, the motor's eRPM / 100),
in the log's axes (the device's ``sensor_axes`` turned back), with the columns Betaflight logs
besides. Read back by :func:`tumble.io.throwfile.load_throw`, every value is the throw's within
half a count (the rounding to whole counts, and nothing else); bad logs are refused in one line.
No fit accuracy is asserted here: the synthetic generator is not this reader's to pin down.
"""

from __future__ import annotations

import json
import math
import re
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from tumble.analysis.tensor import Device, Throw
from tumble.analysis.tensor.device import axes_matrix
from tumble.analysis.tensor.synthetic import calibrated_device, combine, example_object, synthetic_throw, true_device
from tumble.cli import main
from tumble.dynamics.environment.earth import STANDARD_GRAVITY
from tumble.io.blackbox import ACC_COUNTS_PER_G, BLACKBOX_FORMAT, ERPM_PER_COUNT
from tumble.io.devicefile import device_toml, load_device, write_device
from tumble.io.throwfile import load_throw, read_throw, write_throw

ROOT = Path(__file__).resolve().parents[1]
#: The log's clock at the first sample: the flight controller's time since it started, us.
T0_US = 35_000_000
#: Columns Betaflight logs before the gyroscope (their values are noise to the reader).
BEFORE = ("loopIteration", "time", "axisP[0]", "axisP[1]", "axisP[2]", "axisI[0]", "axisI[1]", "axisI[2]",
          "axisD[0]", "axisD[1]", "axisF[0]", "axisF[1]", "axisF[2]", "rcCommand[0]", "rcCommand[1]",
          "rcCommand[2]", "rcCommand[3]", "setpoint[0]", "setpoint[1]", "setpoint[2]", "setpoint[3]",
          "vbatLatest", "amperageLatest")
#: Blackbox Explorer's header block: the log's header as ``"key",value`` lines.
EXPLORER_HEADER = ('"Product","Blackbox flight data recorder by Nicholas Sherlock"', '"firmwareType",3',
                   '"Firmware revision","Betaflight 4.5.1 (77d01ba3b) STM32F7X2"', '"looptime",125',
                   '"gyro_scale",1', '"motorOutput","48,2047"', '"acc_1G",2048', '"motor_poles",14')

_THROWS: dict[int, Throw] = {}


def _throw(seed: int) -> Throw:
    """A synthetic throw of the device with the example object (made once a seed)."""
    if seed not in _THROWS:
        _THROWS[seed] = synthetic_throw(seed, combine(true_device(), example_object()))
    return _THROWS[seed]


def _device(**keys) -> Device:
    return replace(calibrated_device(), **keys)


def blackbox_csv(throw: Throw, device: Device, *, explorer: bool = False, motors: int = 4) -> str:
    """The log a flight controller mounted as ``device.sensor_axes`` says would write of ``throw``:
    counts in the log's axes (``v_log = R^T v``), the rotor on ``eRPM[device.motor_index]``, the
    other motors and fields random counts; as blackbox_decode (``", "``, ``time (us)``) or Blackbox
    Explorer (its header block, quoted names, ``time``) writes it."""
    rng = np.random.default_rng(5)
    n = throw.t.size
    R = axes_matrix(device.sensor_axes)
    gyro = np.round(np.rad2deg(throw.omega @ R) / device.gyro_lsb)   # (R^T w)^T = w^T R
    acc = np.round(throw.accel @ R * ACC_COUNTS_PER_G / STANDARD_GRAVITY)
    erpm = np.round(throw.rotor * 60.0 / (2 * math.pi) * (device.motor_poles / 2) / ERPM_PER_COUNT)
    columns = {name: rng.integers(-500, 500, n) for name in BEFORE}
    columns["loopIteration"] = np.arange(n)
    columns["time"] = T0_US + np.round(throw.t * 1e6)
    columns.update({f"gyroADC[{k}]": gyro[:, k] for k in range(3)})
    columns.update({f"gyroUnfilt[{k}]": gyro[:, k] + rng.integers(-9, 9, n) for k in range(3)})
    columns.update({f"accSmooth[{k}]": acc[:, k] for k in range(3)})
    columns.update({f"debug[{k}]": rng.integers(-30000, 30000, n) for k in range(4)})
    columns.update({f"motor[{k}]": rng.integers(48, 2047, n) for k in range(motors)})
    columns.update({f"eRPM[{k}]": rng.integers(0, 3000, n) for k in range(motors)})
    columns[f"eRPM[{device.motor_index}]"] = erpm
    names = list(columns)
    data = np.column_stack([columns[c] for c in names]).astype(np.int64)
    if explorer:
        head = [*EXPLORER_HEADER, ",".join(f'"{c}"' for c in names)]
        return "\n".join(head + [",".join(str(x) for x in row) for row in data]) + "\n"
    names[1] = "time (us)"
    return ", ".join(names) + "\n" + "".join(", ".join(f"{x:3d}" for x in row) + "\n" for row in data)


def _half_counts(device: Device) -> dict[str, float]:
    """Half a count of each quantity, in SI: the rounding to whole counts (+ a double's rounding)."""
    return {"t": 0.5e-6 + 1e-11, "omega": 0.5 * math.radians(device.gyro_lsb) * (1 + 1e-12),
            "rotor": 0.5 * ERPM_PER_COUNT / (device.motor_poles / 2) * 2 * math.pi / 60 * (1 + 1e-12),
            "accel": 0.5 * STANDARD_GRAVITY / ACC_COUNTS_PER_G * (1 + 1e-12)}


def _cli(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


# --- reading: the throw's values within half a count --------------------------------------------

@pytest.mark.parametrize(("explorer", "keys"), [
    (False, {}),   # the defaults: 14 poles, eRPM[0], 2000 deg/s in 16-bit counts, the log's axes
    (False, {"motor_poles": 12, "sensor_axes": ("y", "-x", "z")}),   # a board turned a quarter about z
    (True, {"motor_poles": 12, "sensor_axes": ("x", "-y", "-z")}),   # Blackbox Explorer's; upside down
    (False, {"motor_poles": 28, "motor_index": 2, "gyro_resolution": 1.0, "sensor_axes": ("z", "x", "y")}),
], ids=["defaults", "turned-12-poles", "explorer-upside-down", "whole-deg-s-motor-2"])
def test_a_blackbox_log_reads_back_within_half_a_count(tmp_path, explorer, keys):
    throw, device = _throw(7), _device(**keys)
    path = tmp_path / "b1.csv"
    path.write_text(blackbox_csv(throw, device, explorer=explorer))
    again, read = load_throw(path, device)
    half = _half_counts(device)
    assert again.input == str(path) and again.t.size == throw.t.size
    assert np.abs(again.t - (T0_US * 1e-6 + throw.t)).max() <= half["t"]
    for key in ("omega", "rotor", "accel"):
        error = np.abs(getattr(again, key) - getattr(throw, key)).max()
        assert error <= half[key], (key, error, half[key])
    # the log's own gyroscope in the sensor frame: the axes really were turned back
    assert np.abs(again.omega).max() > 100 * half["omega"]
    # what was read, for tensor.json
    assert read.columns[1:4] == ("gyroADC[0]", "gyroADC[1]", "gyroADC[2]")
    assert read.columns[4] == f"eRPM[{device.motor_index}]" and read.columns[5:] == tuple(
        f"accSmooth[{k}]" for k in range(3))
    assert read.columns[0] == ("time" if explorer else "time (us)") and read.units[0] == "us"
    assert read.units[4] == f"100 eRPM, {device.motor_poles} poles" and read.units[5] == "1/2048 g"
    assert {"loopIteration", "axisP[0]", "motor[0]", "debug[3]", "gyroUnfilt[2]"} <= set(read.ignored)
    summary = json.loads(json.dumps(read.summary()))
    assert summary["sensor_axes"] == list(device.sensor_axes) and summary["rows"] == throw.t.size
    assert summary["rotor"] == {"column": f"eRPM[{device.motor_index}]", "unit": read.units[4]}
    assert ("sensor axes" in read.brief()) == (device.sensor_axes != ("x", "y", "z"))


def test_without_a_device_the_defaults_read_it_and_a_throw_file_is_never_turned(tmp_path):
    throw = _throw(7)
    path = tmp_path / "b1.csv"
    path.write_text(blackbox_csv(throw, Device(0.1, [0, 0, 1])))
    again = read_throw(path)   # 14 poles, eRPM[0], 2000 deg/s full scale, the log's axes
    assert np.abs(again.omega - throw.omega).max() <= _half_counts(Device(0.1, [0, 0, 1]))["omega"]
    # a throw file is in the sensor frame already: the device's mounting does not turn it
    plain = write_throw(tmp_path / "a1.csv", throw)
    turned = read_throw(plain, _device(sensor_axes=("y", "-x", "z"), motor_poles=2))
    np.testing.assert_array_equal(turned.omega, read_throw(plain).omega)
    np.testing.assert_array_equal(turned.rotor, read_throw(plain).rotor)


def test_a_log_without_its_accelerometer_reads_without_one(tmp_path):
    device = _device()
    text = blackbox_csv(_throw(7), device)
    lines = [line.split(", ") for line in text.splitlines()]
    keep = [j for j, name in enumerate(lines[0]) if not name.startswith("accSmooth")]
    path = tmp_path / "b1.csv"
    path.write_text("".join(", ".join(row[j] for j in keep) + "\n" for row in lines))
    again, read = load_throw(path, device)
    assert again.accel is None and read.summary()["accel"] is None and "no accelerometer" in read.brief()


# --- the device file's keys ----------------------------------------------------------------------

def test_the_keys_of_how_a_log_is_read_round_trip_through_the_device_file(tmp_path):
    device = _device(motor_poles=12, motor_index=3, gyro_full_scale=1000.0, gyro_resolution=0.1,
                     sensor_axes=["-y", "x", "z"])
    assert device.sensor_axes == ("-y", "x", "z") and device.gyro_lsb == 0.1
    path = write_device(tmp_path / "c.toml", device)
    text = path.read_text()
    assert 'sensor_axes = ["-y", "x", "z"]' in text and "motor_poles = 12" in text
    again, _ = load_device(path)
    for key in ("motor_poles", "motor_index", "gyro_full_scale", "gyro_resolution", "sensor_axes"):
        assert getattr(again, key) == getattr(device, key), key
    np.testing.assert_array_equal(again.sensor_rotation, [[0, -1, 0], [1, 0, 0], [0, 0, 1]])
    # the defaults are not written: a device file without the keys reads the same
    plain = device_toml(calibrated_device())
    assert not any(k in plain for k in ("motor_poles", "motor_index", "gyro_", "sensor_axes"))
    default, _ = load_device(write_device(tmp_path / "d.toml", calibrated_device()))
    assert (default.motor_poles, default.motor_index, default.gyro_full_scale, default.gyro_resolution,
            default.sensor_axes) == (14, 0, 2000.0, None, ("x", "y", "z"))


DEVICE = "[device]\nmass = 0.10067\nrotor_axis = [0.0, 0.0, -1.0]\n"
#: (the key as written, the one line after the file's name)
KEY_BAD = {
    "odd poles": ("motor_poles = 13", "[device] motor_poles = 13 must be an even whole number >= 2 (the motor's "
                  "magnet poles: 14 on most small brushless motors)"),
    "poles as a float": ("motor_poles = 14.0", "[device] motor_poles = 14.0 must be an even whole number >= 2"),
    "no motor 8": ("motor_index = 8", "[device] motor_index = 8 must be a whole number from 0 to 7 (eRPM[0] to "
                   "eRPM[7] of the log)"),
    "negative full scale": ("gyro_full_scale = -2000", "[device] gyro_full_scale = -2000 must be a positive finite "
                            "number (deg/s)"),
    "count beyond the full scale": ("gyro_resolution = 2500.0", "[device] gyro_resolution = 2500.0 must be at most "
                                    "the full scale gyro_full_scale = 2000 (deg/s per count)"),
    "a mirror": ('sensor_axes = ["x", "y", "-z"]', "[device] sensor_axes = ['x', 'y', '-z'] is a mirror image "
                 "(determinant -1), not a rotation; allowed: 3 of"),
    "an axis twice": ('sensor_axes = ["x", "x", "z"]', "[device] sensor_axes = ['x', 'x', 'z'] names a log axis "
                      "twice; allowed: 3 of"),
    "not an axis": ('sensor_axes = ["x", "y", "w"]', "[device] sensor_axes = ['x', 'y', 'w']: 'w' is not an axis; "
                    'allowed: 3 of "x", "-x", "y", "-y", "z", "-z"'),
    "a matrix": ("sensor_axes = [[1, 0, 0], [0, 1, 0]]", "[device] sensor_axes = [[1, 0, 0], [0, 1, 0]] must be a "
                 "list of 3 axes; allowed: 3 of"),
}


@pytest.mark.parametrize("case", sorted(KEY_BAD))
def test_a_bad_key_is_refused_in_one_line_naming_the_file_the_key_and_the_value(tmp_path, case):
    written, words = KEY_BAD[case]
    path = tmp_path / "device.toml"
    path.write_text(DEVICE + written + "\n")
    with pytest.raises(ValueError) as info:
        load_device(path)
    message = str(info.value)
    assert "\n" not in message and message.startswith(f"{path}: {words}"), message


# --- bad logs: one line, exit 2, nothing written ---------------------------------------------------

def _edited(text: str, row: int, column: str, value: str) -> str:
    """The log with one cell (data row ``row``, the named column) replaced."""
    lines = text.splitlines()
    head = lines[0].split(", ")
    cells = lines[1 + row].split(", ")
    cells[head.index(column)] = value
    lines[1 + row] = ", ".join(cells)
    return "\n".join(lines) + "\n"


def _renamed(text: str, old: str, new: str) -> str:
    head, rest = text.split("\n", 1)
    return head.replace(old, new) + "\n" + rest


#: (how the log is spoiled, the words the one line holds after "b1.csv")
LOG_BAD = {
    "no eRPM": (lambda t: _renamed(t, "eRPM[", "rpm["), ", line 1: header 'loopIteration, time (us), "),
    "only other motors": (lambda t: _renamed(t, "eRPM[0]", "eRPM[9]"), "has no eRPM[0] column (the rotor's speed, "
                          "motor_index = 0); it has eRPM[9], eRPM[1], eRPM[2], eRPM[3]: name the rotor's motor with "
                          "motor_index in the device file"),
    "an infinite time": (lambda t: _edited(t, 5, "time (us)", "inf"), ", line 7, column 2: time (us) = inf is not a "
                         "finite number"),
    "time goes back": (lambda t: _edited(t, 5, "time (us)", "35000000"), ", line 7: time 35 s goes back before the "
                       "time"),
    "gyro beyond full scale": (lambda t: _edited(t, 3, "gyroADC[1]", "40000"), ", line 5, column 25: gyroADC[1] = "
                               "40000 is beyond the gyroscope's full scale; allowed: -32768 to 32768 counts (2000 "
                               "deg/s at 0.0610352 deg/s per count"),
    "gyro not a number": (lambda t: _edited(t, 3, "gyroADC[2]", "NaN"), ", line 5, column 26: gyroADC[2] = NaN is not "
                          "a finite number"),
    "a fraction of a count": (lambda t: _edited(t, 3, "gyroADC[0]", "12.5"), ", line 5, column 24: gyroADC[0] = 12.5 "
                              "is not a whole number"),
    "negative eRPM": (lambda t: _edited(t, 3, "eRPM[0]", "-4"), ", line 5, column 41: eRPM[0] = -4 is beyond an eRPM "
                      "count's range; allowed: 0 to 65535"),
    "half an accelerometer": (lambda t: _renamed(t, "accSmooth[2]", "accRaw[2]"), "has no accSmooth[2] column; "
                              "allowed: accSmooth[0], accSmooth[1], accSmooth[2] together, or none"),
    "rates in deg/s": (lambda t: _renamed(t, "gyroADC[0]", "gyroADC[0] (deg/s)"), ", line 1, column 24: 'gyroADC[0] "
                       "(deg/s)' is converted to a unit; a blackbox CSV is read in the log's counts"),
    # inside the log; a half-written last line is a log stopped in flight (below)
    "short row": (lambda t: "\n".join(t.splitlines()[:6] + ["1, 2, 3"] + t.splitlines()[6:]) + "\n",
                  ": 3 columns; expected 44 as the header"),
}


@pytest.mark.parametrize("case", sorted(LOG_BAD))
def test_tensor_refuses_a_bad_log_in_one_line(tmp_path, capsys, case):
    spoil, words = LOG_BAD[case]
    device = write_device(tmp_path / "calibrated.toml", _device())
    path = tmp_path / "b1.csv"
    path.write_text(spoil(blackbox_csv(_throw(7), _device())))
    out = tmp_path / "out"
    code, stdout, err = _cli(capsys, "tensor", str(path), "--device", str(device), "--mass", "0.6", "--out", str(out))
    assert code == 2, err
    assert err.count("\n") == 1 and err.startswith(f"tumble: error: {path}"), err
    assert words in err, err
    assert not out.exists() and stdout == ""


def test_calibrate_reads_the_logs_with_the_device_files_motor(tmp_path, capsys):
    """tumble calibrate hands the device to the reader: a device whose rotor is motor 1 refuses a
    log without eRPM[1] (before any fit), naming the key."""
    device = _device(motor_index=1)
    text = blackbox_csv(_throw(7), _device(), motors=1)   # motor 0 alone
    path = tmp_path / "a1.csv"
    path.write_text(text)
    toml = tmp_path / "device.toml"
    toml.write_text(device_toml(device) + "\n[proof]\nmass = 0.346\ninertia = [1.675805e-4, 1.300972e-4, 2.450833e-4]\n")
    out = tmp_path / "c.toml"
    code, _, err = _cli(capsys, "calibrate", str(toml), "--alone", str(path), "--proof", str(path), "--out", str(out))
    assert code == 2 and err.count("\n") == 1, err
    assert "has no eRPM[1] column (the rotor's speed, motor_index = 1); it has eRPM[0]" in err
    assert not out.exists()


# --- the command on blackbox logs, end to end ------------------------------------------------------

def test_tensor_runs_on_blackbox_logs_with_a_calibrated_device_file(tmp_path, capsys):
    """Two logs of the example object, the board turned and a 12-pole motor, read with the calibrated
    device file's keys and fitted (exit 0, or 1 for a fit the model does not describe: the fit's
    accuracy is the generator's business, not the reader's)."""
    device = _device(motor_poles=12, sensor_axes=("y", "-x", "z"))
    toml = write_device(tmp_path / "calibrated.toml", device)
    paths = []
    for k, seed in enumerate((31, 32)):
        path = tmp_path / f"o{k + 1}.csv"
        path.write_text(blackbox_csv(_throw(seed), device, explorer=k == 1))
        paths.append(str(path))
    out = tmp_path / "object"
    code, stdout, err = _cli(capsys, "tensor", *paths, "--device", str(toml), "--mass", repr(example_object().mass),
                             "--out", str(out))
    assert code in (0, 1), err
    if code == 0:
        assert stdout.startswith("tensor: principal moments ") and str(out) in stdout
    if out.exists():   # written (exit 0, or 1 for an inadequate fit)
        record = json.loads((out / "tensor.json").read_text())
        assert record["input"] == paths and [r["file"] for r in record["read"]] == paths
        assert all(r["sensor_axes"] == ["y", "-x", "z"] for r in record["read"])
        assert record["read"][0]["rotor"] == {"column": "eRPM[0]", "unit": "100 eRPM, 12 poles"}
    else:   # none of the throws fitted: one line naming them
        assert code == 1 and "o1.csv" in err


# --- the page ------------------------------------------------------------------------------------

def test_the_page_lists_every_column_and_the_tensor_guide_points_to_it():
    pytest.importorskip("sphinx")
    sys.path.insert(0, str(ROOT / "docs" / "_ext"))
    import tumble_keys

    page = (ROOT / "docs" / "formats" / "blackbox.md").read_text(encoding="utf-8")
    assert "```{tumble-keys} tumble.io.blackbox.BLACKBOX_FORMAT" in page
    text = tumble_keys.render_format(BLACKBOX_FORMAT)
    for key in BLACKBOX_FORMAT.tables[0].keys:
        assert f"   * - ``{key.name}``\n" in text, key.name
    for key in ("motor_poles", "motor_index", "gyro_full_scale", "gyro_resolution", "sensor_axes"):
        assert key in page, key
    assert "\nblackbox\n" in (ROOT / "docs" / "formats" / "index.md").read_text(encoding="utf-8")
    assert "formats/blackbox.md" in (ROOT / "docs" / "tensor.md").read_text(encoding="utf-8")


def test_the_rotor_on_another_motor_than_motor_index_names_it(tmp_path, capsys):
    """A walkthrough of docs/formats/blackbox.md (2026-12-03): Betaflight logs every motor's eRPM, so with the flywheel
    on motor 2 and the device file's motor_index = 0, eRPM[0] is there and stays 0, and tumble tensor said "the rotor
    did not spin up (it never reached 50 rad/s)" with no word of motor_index. It names the motor that turns."""
    text = blackbox_csv(_throw(7), _device(motor_index=2))  # one motor turns, the flywheel's: the others log 0
    head, *rows = text.splitlines()
    idle = {j for j, c in enumerate(head.split(",")) if c.strip() in ("eRPM[0]", "eRPM[1]", "eRPM[3]")}
    rows = [", ".join("0" if k in idle else cell.strip() for k, cell in enumerate(row.split(","))) for row in rows]
    path = tmp_path / "b1.csv"
    path.write_text("\n".join([head, *rows]) + "\n")
    device = write_device(tmp_path / "calibrated.toml", _device(motor_index=0))
    top = max(int(row.split(", ")[[c.strip() for c in head.split(",")].index("eRPM[2]")]) for row in rows)
    code, _, err = _cli(capsys, "tensor", str(path), "--device", str(device), "--mass", "0.6", "--out", str(tmp_path / "o"))
    assert code == 2 and err.count("\n") == 1, err
    assert err == (f"tumble: error: {path}: eRPM[0] (the rotor's, motor_index = 0) never turns while eRPM[2] reaches "
                   f"{top} counts ({100 * top} eRPM): the flywheel on that motor? Set motor_index = 2 in the device file\n")


def test_the_logs_own_acc_1g_scales_the_accelerometer():
    """A walkthrough of docs/formats/blackbox.md (2026-12-03): an accelerometer at +-8 g logs 4096 counts per g, which
    Blackbox Explorer's header block states ("acc_1G",4096); read at 2048 its specific force came out twice too large
    and every throw was refused as no body's, the accelerometer never named. The log's own acc_1G is taken."""
    from tumble.io.blackbox import parse_blackbox_csv

    text = blackbox_csv(_throw(7), _device(), explorer=True)
    assert '"acc_1G",2048' in text
    at_2048, read_2048 = parse_blackbox_csv(text.encode(), "b.csv", _device())
    at_4096, read_4096 = parse_blackbox_csv(text.replace('"acc_1G",2048', '"acc_1G",4096').encode(), "b.csv", _device())
    np.testing.assert_array_equal(at_4096["accel"], 0.5 * at_2048["accel"])
    np.testing.assert_array_equal(at_4096["omega"], at_2048["omega"])
    assert read_4096.units[-1] == "1/4096 g" and read_2048.units[-1] == "1/2048 g"
    with pytest.raises(ValueError, match=r"^b\.csv, line 7: acc_1G = 0 is not an accelerometer's counts per g; allowed: "):
        parse_blackbox_csv(text.replace('"acc_1G",2048', '"acc_1G",0').encode(), "b.csv", _device())


def test_a_half_written_last_line_is_left_out_as_in_a_throw_file(tmp_path, capsys):
    """A walkthrough of docs/formats/blackbox.md (2026-12-03): a blackbox log whose last line was cut while written
    (the device's log stops in flight) was refused whole, exit 2, where a throw file leaves the line out with a
    warning. Both now leave it out, saying so in one line, and read the rest."""
    from tumble.io.throwfile import CutLogWarning, load_throw

    text = blackbox_csv(_throw(7), _device())
    lines = text.splitlines()
    path = tmp_path / "b1.csv"
    path.write_text("\n".join(lines[:-1] + [lines[-1][:30]]) + "\n")
    with pytest.warns(CutLogWarning, match=rf"^{re.escape(str(path))}, line {len(lines)}: the last line holds \d+ of 44 "
                                           r"columns, a log cut while it was written: left out$"):
        throw, _ = load_throw(path, _device())
    assert throw.t.size == len(lines) - 2
    np.testing.assert_array_equal(throw.t, load_throw(_written(tmp_path, "\n".join(lines[:-1]) + "\n"), _device())[0].t)


def _written(folder: Path, text: str) -> Path:
    path = folder / "whole.csv"
    path.write_text(text)
    return path


def test_a_log_in_whole_deg_s_read_at_16_bit_counts_names_gyro_resolution():
    """A walkthrough of docs/formats/blackbox.md (2026-12-03): a Betaflight 4.x log (gyroADC in whole deg/s) read
    without gyro_resolution = 1.0 had rates 16.4 times too slow, and calibrate failed as "a gyroscope bias of 0.742
    rad/s", tumble tensor as "rates in another unit", the key never named. A log whose gyroscope never passes a
    throw's 2 rad/s says which key to set; read with it, nothing is said, and the default log says nothing either."""
    import warnings

    from tumble.io.blackbox import GyroResolutionWarning, parse_blackbox_csv

    whole = blackbox_csv(_throw(7), _device(gyro_resolution=1.0)).encode()
    with pytest.warns(GyroResolutionWarning, match=r"^b\.csv: the gyroscope reads at most 0\.\d+ rad/s in the whole log, "
                                                   r"slower than a throw spins .*needs gyro_resolution = 1\.0 in the device"):
        slow, _ = parse_blackbox_csv(whole, "b.csv", _device())
    with warnings.catch_warnings():
        warnings.simplefilter("error", GyroResolutionWarning)
        right, _ = parse_blackbox_csv(whole, "b.csv", _device(gyro_resolution=1.0))
        parse_blackbox_csv(blackbox_csv(_throw(7), _device()).encode(), "b.csv", _device())
    assert np.linalg.norm(right["omega"], axis=1).max() > 10.0
    np.testing.assert_allclose(slow["omega"] * (1.0 / _device().gyro_lsb), right["omega"], rtol=1e-12)


@pytest.mark.parametrize(("before", "after", "says"), [
    (4294967000, 500, r"\(a 32-bit microsecond clock wraps at 4294\.967296 s: add it to the times from this line on\)$"),
    (None, 0, r"\(a second log section from this line on\? Give each its own file\)$"),
])
def test_a_clock_that_wraps_or_a_log_that_restarts_is_named(tmp_path, capsys, before, after, says):
    """A walkthrough of docs/formats/blackbox.md (2026-12-03): a time that wrapped at 2^32 us or restarted (a new log
    section) was refused as "goes back before the time ..." with no hint of why. The line says which it likely is."""
    text = blackbox_csv(_throw(7), _device())
    if before is not None:
        text = _edited(text, 5, "time (us)", str(before))
    path = tmp_path / "b1.csv"
    path.write_text(_edited(text, 6, "time (us)", str(after)))
    device = write_device(tmp_path / "calibrated.toml", _device())
    code, _, err = _cli(capsys, "tensor", str(path), "--device", str(device), "--mass", "0.6", "--out", str(tmp_path / "o"))
    assert code == 2 and err.count("\n") == 1 and re.search(says, err.strip()), err


@pytest.mark.parametrize("mounted", [("x", "-y", "-z"), ("z", "x", "y")], ids=["upside-down", "turned-about-a-diagonal"])
def test_a_board_mounted_otherwise_than_sensor_axes_names_the_key(tmp_path, capsys, mounted):
    """A walkthrough's finding (2026-12-03): logs of a board mounted upside down, read with the device file's default
    sensor_axes, failed as "its tensor came out degenerate: the rotor's axis or the sign of its speed may be wrong", and
    a board turned a third about a diagonal as residuals 15-87 times the noise; sensor_axes was never named. The line
    names it; read with the mounting they were logged in, the same logs answer."""
    paths = []
    for k, seed in enumerate((31, 32)):
        path = tmp_path / f"o{k + 1}.csv"
        path.write_text(blackbox_csv(_throw(seed), _device(sensor_axes=mounted)))
        paths.append(str(path))
    mass = repr(example_object().mass)
    plain = write_device(tmp_path / "plain.toml", _device())
    code, _, err = _cli(capsys, "tensor", *paths, "--device", str(plain), "--mass", mass, "--out", str(tmp_path / "o"))
    assert code == 1 and err.count("\n") == 1 and "rotor" in err, err
    assert err.endswith("; the blackbox logs were turned by the device file's sensor_axes = [\"x\", \"y\", \"z\"]: a board "
                        "mounted otherwise turns the rotor's axis too; nothing written\n"), err
    assert not (tmp_path / "o").exists()
    right = write_device(tmp_path / "right.toml", _device(sensor_axes=mounted))
    code, out, err = _cli(capsys, "tensor", *paths, "--device", str(right), "--mass", mass, "--out", str(tmp_path / "r"))
    assert code == 0 and out.startswith("tensor: principal moments ") and "from 2 of 2 throws" in out, err
