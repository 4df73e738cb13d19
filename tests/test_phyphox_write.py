"""Writing a phyphox export from the synthetic generator (issue 40, item 4): what
:func:`tumble.io.phyphoxwrite.write_phyphox` writes, the readers read back as written, and
``tumble fit`` fits as it fits the app's; written whole or not at all."""

from __future__ import annotations

import json
import zipfile
from pathlib import Path

import numpy as np
import pytest

from tumble.analysis.fit.synthetic import synthetic_recording
from tumble.cli import main
from tumble.io.gyrodata import load_recording
from tumble.io.phyphoxwrite import phyphox_files, write_phyphox


@pytest.fixture(scope="module")
def rec():
    return synthetic_recording(4, body="phone", tosses=3, accel=True, pauses=1)


@pytest.mark.parametrize("name", ["export", "export.zip"])
def test_an_export_reads_back_as_written(tmp_path, rec, name):
    path = write_phyphox(tmp_path / name, rec.t, rec.omega, accel=rec.accel.f, events=rec.events)
    assert path == tmp_path / name
    again = load_recording(path)
    np.testing.assert_allclose(again.t, rec.t, rtol=1e-9, atol=0)
    np.testing.assert_allclose(again.omega, rec.omega, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(again.accel, rec.accel.f, rtol=1e-9, atol=1e-12)
    assert [n for n, _ in again.events] == [n for n, _ in rec.events] == ["START", "PAUSE", "START"]
    np.testing.assert_allclose([te for _, te in again.events], [te for _, te in rec.events], rtol=1e-9)
    assert again.read.accel == tuple(f"Accelerometer.csv: Acceleration {axis} (m/s^2)" for axis in "xyz")
    names = sorted(zipfile.ZipFile(path).namelist() if name.endswith(".zip") else
                   [p.relative_to(path).as_posix() for p in path.rglob("*") if p.is_file()])
    assert names == ["Accelerometer.csv", "Gyroscope.csv", "meta/time.csv"]


def test_without_an_accelerometer_the_export_is_the_gyroscope_experiments(tmp_path, rec):
    path = write_phyphox(tmp_path / "gyro", rec.t, rec.omega)
    assert sorted(p.relative_to(path).as_posix() for p in path.rglob("*") if p.is_file()) == [
        "Raw Data.csv", "meta/time.csv"]
    again = load_recording(path)
    assert again.accel is None and again.events == (("START", 0.0),)
    np.testing.assert_allclose(again.omega, rec.omega, rtol=1e-9, atol=1e-15)
    # the fifth column is |omega|, which the reader checks against the rates and leaves out
    assert again.read.ignored == ("Absolute (rad/s)",)


def test_an_accelerometer_on_its_own_times_is_read_onto_the_gyroscopes(tmp_path, rec):
    ta = np.arange(rec.t[0], rec.t[-1], 0.004)   # 250 Hz, its own clock
    f = np.column_stack([np.sin(ta), np.cos(ta), 9.8 + 0.0 * ta])
    again = load_recording(write_phyphox(tmp_path / "two.zip", rec.t, rec.omega, accel=f, accel_t=ta))
    inside = rec.t <= ta[-1]
    np.testing.assert_allclose(again.accel[inside, 1], np.cos(rec.t[inside]), atol=1e-5)   # linear interpolation


def test_tumble_fit_fits_a_written_export_as_the_apps(tmp_path, rec, capsys):
    path = write_phyphox(tmp_path / "tosses.zip", rec.t, rec.omega, events=rec.events)
    assert main(["fit", str(path), "--out", str(tmp_path / "fitted")]) == 0
    line = capsys.readouterr().out
    assert "from 3 of 3 flights" in line, line
    fit = json.loads((tmp_path / "fitted" / "fit.json").read_text(encoding="utf-8"))
    ratios = np.array([fit["I1_over_I3"], fit["I2_over_I3"]])
    stds = np.array([fit["I1_over_I3_std"], fit["I2_over_I3_std"]])
    assert np.all(np.abs(ratios - rec.ratios) < 4 * stds), (ratios, rec.ratios, stds)


def test_a_folder_is_never_overwritten_and_bad_samples_write_nothing(tmp_path, rec):
    folder = tmp_path / "taken"
    folder.mkdir()
    (folder / "mine.txt").write_text("keep")
    with pytest.raises(ValueError, match="exists and is not an empty folder"):
        write_phyphox(folder, rec.t, rec.omega)
    assert [p.name for p in folder.iterdir()] == ["mine.txt"]
    (tmp_path / "empty").mkdir()
    assert load_recording(write_phyphox(tmp_path / "empty", rec.t, rec.omega)).omega.shape == rec.omega.shape
    for t, omega, kwargs, words in [
        (rec.t[::-1], rec.omega, {}, "the times must increase"),
        (rec.t, rec.omega[:, :2], {}, "values of shape \\(n, 3\\)"),
        (rec.t, np.where(rec.omega > 1, np.nan, rec.omega), {}, "not a finite number"),
        (rec.t, rec.omega, {"events": [("STOP", 1.0)]}, "START and PAUSE"),
        (rec.t, rec.omega, {"accel": rec.accel.f[:-1]}, "the accelerometer's record"),
    ]:
        with pytest.raises(ValueError, match=words):
            write_phyphox(tmp_path / "bad.zip", t, omega, **kwargs)
        with pytest.raises(ValueError, match=words):
            write_phyphox(tmp_path / "bad", t, omega, **kwargs)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["empty", "taken"]


def test_a_failure_while_writing_a_folder_leaves_nothing(tmp_path, rec, monkeypatch):
    calls = []
    original = Path.write_bytes

    def failing(self, data):
        calls.append(self.name)
        if len(calls) == 2:
            raise OSError("disk full")
        return original(self, data)

    monkeypatch.setattr(Path, "write_bytes", failing)
    with pytest.raises(OSError, match="disk full"):
        write_phyphox(tmp_path / "export", rec.t, rec.omega, accel=rec.accel.f)
    assert list(tmp_path.iterdir()) == []   # neither the folder nor its temporary one


def test_the_files_are_phyphoxs_layout():
    files = phyphox_files([0.0, 0.5], [[0.0, 3.0, 4.0], [0.0, 0.0, 0.0]], accel=[[0, 0, 9.8], [0, 0, 0]],
                          events=[("START", 0.0), ("PAUSE", 0.5)])
    gyro = files["Gyroscope.csv"].decode().splitlines()
    assert gyro[1] == "0.000000000E+00,0.000000000E+00,3.000000000E+00,4.000000000E+00,5.000000000E+00"
    assert files["Accelerometer.csv"].decode().splitlines()[0] == (
        '"Time (s)","Acceleration x (m/s^2)","Acceleration y (m/s^2)","Acceleration z (m/s^2)",'
        '"Absolute acceleration (m/s^2)"')
    assert [line.split(",")[0] for line in files["meta/time.csv"].decode().splitlines()] == [
        '"event"', '"START"', '"PAUSE"']
