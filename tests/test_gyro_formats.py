"""Gyroscope files people have (issue #29 item 4): any delimited text with a time column and three
rate columns found by their header names, other columns ignored by theirs, ``#`` comments, units
in the headers, irregular sampling up to 500 Hz; what was read named (tumble.io.gyrodata,
tumble.io.gyrocolumns, tumble.commands.fit).

The numbers are a synthetic phone recording's (:func:`tumble.analysis.fit.synthetic.synthetic_recording`:
a jittered clock, dropped samples, a phone gyroscope's noise and quantisation), written out in
the formats below.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from tumble.analysis.fit.synthetic import synthetic_recording
from tumble.cli import main
from tumble.io.gyrodata import load_recording, read_gyro_csv, read_recording


@pytest.fixture(scope="module")
def rec():
    return synthetic_recording(5, body="phone", tosses=1)


def _table(t, omega, sep=",", extra=None, scale=(1.0, 1.0)) -> list[str]:
    """Rows of ``t, wx, wy, wz`` (times and rates multiplied by ``scale``) and extra columns."""
    rows = []
    for k in range(len(t)):
        cells = [f"{t[k] * scale[0]:.9g}"] + [f"{w * scale[1]:.9g}" for w in omega[k]]
        if extra is not None:
            cells += [f"{v:.9g}" for v in extra[k]]
        rows.append(sep.join(cells))
    return rows


def test_a_plain_text_export_with_omega_magnitude_and_comments_is_read(tmp_path, rec):
    """The Done-when of item 4: five header-less columns, the fifth |omega|, ``#`` comment lines
    (also between the data) and a trailing separator; refused on main as "5 columns; expected 4"."""
    norm = np.linalg.norm(rec.omega, axis=1)[:, None]
    rows = _table(rec.t, rec.omega, sep="\t", extra=norm)
    rows.insert(300, "# the phone was turned over here")
    text = "# Gyroscope export\n# t wx wy wz |w|\n\n" + "\n".join(r + "\t" for r in rows) + "\n"
    path = tmp_path / "export.txt"
    path.write_text(text, encoding="utf-8")
    got = load_recording(path)
    assert np.allclose(got.t, rec.t, rtol=0, atol=1e-8) and np.allclose(got.omega, rec.omega, rtol=1e-8, atol=1e-9)
    assert got.read.ignored == ("column 5 (|omega|)",) and got.read.rows == len(rec.t)
    assert got.read.time == "column 1" and got.read.rates == ("column 2", "column 3", "column 4")
    # a fifth column that is not |omega| is something else: refused, naming the line
    rows[10] = rows[10].rsplit("\t", 1)[0] + "\t12.5"
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    with pytest.raises(ValueError, match=r"export\.txt, line 11: 5 columns without a header, and the fifth") as err:
        read_gyro_csv(path)
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("header, sep, scale", [
    (["t", "wx", "wy", "wz"], ",", (1.0, 1.0)),
    (["time (s)", "gyro_x (rad/s)", "gyro_y (rad/s)", "gyro_z (rad/s)", "|omega| (rad/s)"], ",", (1.0, 1.0)),
    (["timestamp [ms]", "gx [deg/s]", "gy [deg/s]", "gz [deg/s]"], ";", (1e3, 180 / np.pi)),
    (['"Time (s)"', '"Gyroscope x (rad/s)"', '"Gyroscope y (rad/s)"', '"Gyroscope z (rad/s)"', '"Absolute (rad/s)"'], "\t",
     (1.0, 1.0)),
    (["Time", "omega_x", "omega_y", "omega_z", "norm"], " ", (1.0, 1.0)),
    (["time (us)", "x (rpm)", "y (rpm)", "z (rpm)", "abs"], ",", (1e6, 60 / (2 * np.pi))),
    (["elapsed time", "Angular Velocity X", "Angular Velocity Y", "Angular Velocity Z", "magnitude"], ",", (1.0, 1.0)),
])
def test_header_names_in_many_forms(tmp_path, rec, header, sep, scale):
    extra = np.linalg.norm(rec.omega, axis=1)[:, None] if len(header) == 5 else None
    lines = _table(rec.t, rec.omega, sep=sep, extra=extra, scale=scale)
    path = tmp_path / "rec.csv"
    path.write_text(sep.join(header) + "\n" + "\n".join(lines) + "\n", encoding="utf-8")
    got = load_recording(path)
    assert np.allclose(got.t, rec.t, rtol=1e-8, atol=1e-8) and np.allclose(got.omega, rec.omega, rtol=1e-7, atol=1e-8)
    assert got.read.time == header[0].strip('"') and len(got.read.ignored) == len(header) - 4
    assert abs(got.read.sample_rate - rec.rate) < 0.05 * rec.rate


PHYPHOX_HEADER = ['"Time (s)"', '"Gyroscope x (rad/s)"', '"Gyroscope y (rad/s)"', '"Gyroscope z (rad/s)"']


@pytest.mark.parametrize(("sep", "point"), [(",", "."), ("\t", "."), (";", "."), ("\t", ","), (";", ",")])
def test_phyphox_five_csv_exports_read_alike(tmp_path, rec, sep, point):
    """phyphox exports CSV five ways (its "Export data" menu: comma, tabulator or semicolon, decimal point or
    comma); "Tabulator, decimal comma" was refused ("'1,2008110e+01' is not a number", a walkthrough of
    fitting.md, 2026-12-02). Each reads as the numbers written."""
    lines = [line.replace(".", point) for line in _table(rec.t, rec.omega, sep=sep)]
    path = tmp_path / "Raw Data.csv"
    path.write_text(sep.join(PHYPHOX_HEADER) + "\n" + "\n".join(lines) + "\n", encoding="utf-8")
    got = load_recording(path)
    assert np.allclose(got.t, rec.t, rtol=0, atol=1e-8) and np.allclose(got.omega, rec.omega, rtol=1e-8, atol=1e-9)


@pytest.mark.parametrize("magic", [b"PK\x03\x04", b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1"])
def test_an_excel_export_is_named_and_csv_asked_for(tmp_path, magic):
    path = tmp_path / "Raw Data.xls"
    path.write_bytes(magic + bytes(range(128, 256)))
    with pytest.raises(ValueError, match=r"^.*Raw Data\.xls: an Excel workbook or a zip, not text: export the recording "
                                         r"as CSV$"):
        read_gyro_csv(path)


def test_accelerometer_read_and_other_sensors_columns_ignored_by_name(tmp_path, rec):
    """A raw accelerometer's columns are kept (#29: the specific force, for finding free fall); a
    phone's linear acceleration (its gravity estimate taken out) and the other sensors are ignored,
    and the summary of what was read says why the linear acceleration is not used."""
    header = ["time (s)", "acc_x (m/s^2)", "acc_y (m/s^2)", "acc_z (m/s^2)", "gyro_x (deg/s)", "gyro_y (deg/s)",
              "gyro_z (deg/s)", "linear acceleration x", "linear acceleration y", "linear acceleration z",
              "mag_x", "mag_y", "mag_z", "battery"]
    rng = np.random.default_rng(0)
    acc = rng.normal(0.0, 3.0, (len(rec.t), 3))
    rows = [",".join([f"{rec.t[k]:.9g}", *(f"{a:.5f}" for a in acc[k]), *(f"{w:.9g}" for w in np.degrees(rec.omega[k])),
                      *(f"{a:.5f}" for a in acc[k]), "20.1", "-3", "41", "87"]) for k in range(len(rec.t))]
    path = tmp_path / "logger.csv"
    path.write_text(",".join(header) + "\n" + "\n".join(rows) + "\n", encoding="utf-8")
    got = load_recording(path)
    assert np.allclose(got.omega, rec.omega, rtol=1e-7, atol=1e-8)
    assert got.read.rates == ("gyro_x (deg/s)", "gyro_y (deg/s)", "gyro_z (deg/s)") and got.read.rate_units == ("deg/s",) * 3
    assert got.read.ignored == tuple(h for h in header if not h.startswith(("time", "gyro", "acc_")))
    assert got.read.accel == ("acc_x (m/s^2)", "acc_y (m/s^2)", "acc_z (m/s^2)")
    assert np.allclose(got.accel, acc, atol=6e-6)  # written with 5 decimals
    note = got.read.summary()["not_specific_force"]
    assert note.startswith("linear acceleration x, linear acceleration y, linear acceleration z: ")


def test_sensor_loggers_gyroscope_file_is_read_by_its_seconds_elapsed(tmp_path, rec, capsys):
    """Sensor Logger (iOS and Android) writes ``Gyroscope.csv`` as ``time,seconds_elapsed,z,y,x``:
    the clock in ns since 1970, the seconds since the start, the rates in rad/s, z first. It was
    refused ("2 time columns; keep one"); the seconds elapsed are taken, the clock ignored, and
    ``tumble fit`` answers as for the same samples in the plain layout."""
    clock = 1_767_620_467_350_470_700 + np.round(rec.t * 1e9).astype(np.int64)  # what the app writes: int ns
    rows = [f"{clock[k]},{rec.t[k]:.6f},{rec.omega[k, 2]:.9g},{rec.omega[k, 1]:.9g},{rec.omega[k, 0]:.9g}"
            for k in range(len(rec.t))]
    logger = tmp_path / "Gyroscope.csv"
    logger.write_text("time,seconds_elapsed,z,y,x\n" + "\n".join(rows) + "\n", encoding="utf-8")
    got = load_recording(logger)
    assert got.read.time == "seconds_elapsed" and got.read.rates == ("x", "y", "z") and got.read.ignored == ("time",)
    assert np.allclose(got.t, rec.t, rtol=0, atol=5e-7) and np.allclose(got.omega, rec.omega, rtol=1e-8, atol=1e-9)
    plain = tmp_path / "plain.csv"
    plain.write_text("t,wx,wy,wz\n" + "\n".join(_table(np.round(rec.t, 6), rec.omega)) + "\n", encoding="utf-8")
    assert main(["fit", str(logger), "--out", str(tmp_path / "a")]) == 0
    assert main(["fit", str(plain), "--out", str(tmp_path / "b")]) == 0
    a, b = (json.loads((tmp_path / d / "fit.json").read_text()) for d in "ab")
    key = ("I1_over_I3", "I2_over_I3", "I1_over_I3_std", "I2_over_I3_std")
    assert [a["pooled"][k] for k in key] == [b["pooled"][k] for k in key]  # the same samples, the same answer


@pytest.mark.parametrize("packed", ["folder", "zip"])
def test_sensor_loggers_export_is_read_without_its_gravity_free_accelerometer(tmp_path, rec, packed):
    """Sensor Logger's export (a folder or a .zip): ``Gyroscope.csv`` beside ``Accelerometer.csv``,
    which has the phone's gravity estimate taken out (0 m/s^2 at rest, not 9.8), and
    ``TotalAcceleration.csv`` and ``Metadata.csv``. The gyroscope is read; the accelerometer is
    not taken for the specific force (it would read 9.8 m/s^2 in free fall, the flights cut
    wrong), and what was read says so."""
    import zipfile

    clock = 1_767_620_467_350_470_700 + np.round(rec.t * 1e9).astype(np.int64)
    axes = lambda v: [f"{clock[k]},{rec.t[k]:.6f},{v[k, 2]:.9g},{v[k, 1]:.9g},{v[k, 0]:.9g}" for k in range(len(rec.t))]  # noqa: E731
    files = {"Gyroscope.csv": axes(rec.omega), "Accelerometer.csv": axes(np.zeros_like(rec.omega)),
             "TotalAcceleration.csv": axes(np.tile([0.0, 0.0, 9.81], (len(rec.t), 1)))}
    texts = {n: "time,seconds_elapsed,z,y,x\n" + "\n".join(rows) + "\n" for n, rows in files.items()}
    texts["Metadata.csv"] = "version,device name,platform,sampleRateMs\n3,phone,android,10\n"
    where = tmp_path / "export"
    if packed == "folder":
        where.mkdir()
        for n, text in texts.items():
            (where / n).write_text(text, encoding="utf-8")
    else:
        where = tmp_path / "export.zip"
        with zipfile.ZipFile(where, "w") as archive:
            for n, text in texts.items():
                archive.writestr(n, text)
    got = load_recording(where)
    assert got.accel is None and got.read.accel == ()
    assert got.read.accel_left_out.startswith("Sensor Logger's Accelerometer.csv has gravity taken out")
    assert np.allclose(got.omega, rec.omega, rtol=1e-8, atol=1e-9) and got.read.time == "seconds_elapsed"
    if packed == "folder":  # exported with two sensors only: known by its Gyroscope.csv's layout, not read as phyphox's
        for n in ("Metadata.csv", "TotalAcceleration.csv"):
            (where / n).unlink()
        again = load_recording(where)
        assert again.accel is None and again.read.accel_left_out.startswith("Sensor Logger's Accelerometer.csv")


@pytest.mark.parametrize("header, message", [
    ("t,time,wx,wy,wz", r"has 2 time columns \('t', 'time'\); keep one; allowed: time: t, time, timestamp"),
    ("t,ax,ay,az", r"has no rate column for x; allowed:"),
    ("value,wx,wy,wz", r"has no time column; allowed:"),
    ("t,wx,gx,wy,wz", r"has 2 rate columns for x \('wx', 'gx'\)"),
    ("t,wx [furlong/s],wy,wz", r"line 1, column 2: unknown unit 'furlong/s' in header 'wx \[furlong/s\]'; use one of rad/s"),
])
def test_ambiguous_or_invalid_headers_are_one_line_errors(tmp_path, capsys, header, message):
    path = tmp_path / "bad.csv"
    width = header.count(",") + 1
    path.write_text(header + "\n" + "\n".join(",".join([str(0.01 * k)] + ["1"] * (width - 1)) for k in range(5)) + "\n",
                    encoding="utf-8")
    with pytest.raises(ValueError, match=message) as err:
        read_recording(path)
    assert "\n" not in str(err.value) and str(path) in str(err.value) and header.split(",")[1] in str(err.value)
    assert main(["fit", str(path), "--out", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err.count("\n") == 1 and not (tmp_path / "out").exists()


@pytest.mark.parametrize("times, line, word", [([0.0, 0.01, 0.01, 0.03], 5, "repeats"), ([0.0, 0.02, 0.01, 0.03], 5, "goes back")])
def test_a_time_that_repeats_or_goes_back_names_its_line(tmp_path, times, line, word):
    path = tmp_path / "order.csv"
    path.write_text("# comment\nt,wx,wy,wz\n" + "".join(f"{t},1,2,3\n" for t in times), encoding="utf-8")
    with pytest.raises(ValueError, match=rf"order\.csv, line {line}: time 0\.0\d+ s {word}.* of line {line - 1}; "
                       "times must increase"):
        read_gyro_csv(path)


def test_a_500_hz_irregular_recording_is_read_fitted_and_named_in_fit_json(tmp_path, capsys):
    rec = synthetic_recording(8, body="phone", tosses=1, rate=500.0)
    dt = np.diff(rec.t)
    assert dt.max() > 1.5 * np.median(dt)  # irregular: a jittered clock and dropped samples
    path = tmp_path / "fast.csv"
    path.write_text("t (ms),gx,gy,gz,|omega|\n" + "\n".join(_table(rec.t, rec.omega, extra=np.linalg.norm(
        rec.omega, axis=1)[:, None], scale=(1e3, 1.0))) + "\n", encoding="utf-8")
    out = tmp_path / "fit"
    assert main(["fit", str(path), "--out", str(out)]) == 0
    line = capsys.readouterr().out
    assert line.count("\n") == 1 and "read t (ms), gx, gy, gz (rad/s), 1 ignored" in line
    read = json.loads((out / "fit.json").read_text(encoding="utf-8"))["read"]
    assert read["time"] == {"column": "t (ms)", "unit": "ms"} and read["ignored"] == ["|omega|"]
    assert read["rows"] == len(rec.t) and abs(read["sample_rate_median_hz"] - 500.0) < 5.0


@pytest.mark.parametrize(("header", "scale", "unit"), [("timestamp,gx,gy,gz", 1e3, "ms"), ("t,gx,gy,gz", 1e6, "us"),
                                                       ("timestamp,gx,gy,gz", 1e9, "ns")])
def test_a_time_in_another_unit_than_seconds_is_named_with_the_likely_one(header, scale, unit):
    """A time column in ms with no unit (read as s) failed as "no usable flight among 357 found: 357 too
    short", exit 1 (a walkthrough of docs/fitting.md, 2026-12-03): samples 10 s apart are no gyroscope's,
    and the unit that puts them 10 ms apart is named."""
    from tumble.io.gyrodata import parse_gyro_csv

    t = (1.7e9 if unit == "ns" else 0.0) + np.arange(50) * 0.01
    text = header + "\n" + "".join(f"{x * scale:.0f},0.1,0.2,0.3\n" for x in t)
    name = header.split(",")[0]
    with pytest.raises(ValueError, match=rf"^rec.csv: the time column '{name}', read in s, puts the samples "
                                         rf"\S+ s apart .*; is it in {unit}\? Name its unit in the header: "
                                         rf"'{name} \({unit}\)'$"):
        parse_gyro_csv(text.encode(), "rec.csv")
