"""The accelerometer of a recording (#29, items 1 and 6): the synthetic one's physics, the sensor
offset's fit, and free fall cutting the flights.

The generator's specific force in free flight is checked against an independent route: Euler's
equations (torque-free, no air) from the gyroscope's own samples, not the generator's rates.
"""

from __future__ import annotations

import numpy as np
import pytest

from tumble.analysis.fit.freefall import fit_offset, free_span, rate_derivative, rigid_acceleration
from tumble.analysis.fit.synthetic import synthetic_recording
from tumble.dynamics.environment.earth import STANDARD_GRAVITY


def _inside(rec, a, b, margin=0.02):
    return (rec.t > a + margin) & (rec.t < b - margin)


@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_free_flight_reads_rigid_body_kinematics(seed):
    """In free flight without air the accelerometer reads omega' x r + omega x (omega x r) (plus
    its bias), with omega' from Euler's equations of the body's true moments and omega the
    gyroscope's samples turned to the principal axes: the residual is the two sensors' noise and
    scale errors, a few per cent of a signal of several m/s^2."""
    rec = synthetic_recording(seed, tosses=3, accel=True, drag=0.0, flex=False)
    R = rec.sensor_rotation.as_matrix()
    I = np.array(rec.body.moments)
    w = (rec.omega - rec.bias) @ R.T  # principal axes
    wd = np.cross(I * w, w) / I  # Euler's equations, torque-free (Landau & Lifshitz sec. 36)
    f = rigid_acceleration(w, wd, R @ rec.accel.offset) @ R + rec.accel.bias
    for a, b in rec.flights:
        sel = _inside(rec, a, b)
        signal = np.sqrt(np.mean(np.sum(f[sel] ** 2, axis=1)))
        error = np.sqrt(np.mean(np.sum((rec.accel.f[sel] - f[sel]) ** 2, axis=1)))
        assert signal > 0.5
        assert error < 4 * rec.accel.noise + 0.02 * signal


@pytest.mark.parametrize("seed", [5, 6])
def test_held_reads_g_and_contact_spikes(seed):
    """Held, the accelerometer reads about g (the hand carries the weight); a catch is a jolt of
    tens of m/s^2; a landing an impact above 2 g (in flight: the test above)."""
    rec = synthetic_recording(seed, tosses=2, accel=True)
    a = np.linalg.norm(rec.accel.f, axis=1)
    first_hold = rec.t < rec.flights[0, 0] - 0.35
    assert abs(np.median(a[first_hold]) - STANDARD_GRAVITY) < 1.0
    for _, end in rec.flights:
        catch = (rec.t >= end) & (rec.t < end + 0.15)
        assert a[catch].max() > 15.0
    land = synthetic_recording(seed, tosses=1, accel=True, ending="landing", body="phone")
    a = np.linalg.norm(land.accel.f, axis=1)
    impact = (land.t >= land.flights[0, 1]) & (land.t < land.flights[0, 1] + 0.05)
    assert a[impact].max() > 2 * STANDARD_GRAVITY
    assert np.max(np.abs(land.accel.f)) <= 16 * STANDARD_GRAVITY  # clipped at the full scale


@pytest.mark.parametrize("kwargs", [dict(), dict(ending="mixed", hand=(3.0, 10.0), tosses=3, pauses=1),
                                    dict(body="phone", rotor=0.2, ending="landing", rate=400.0, tosses=2)])
def test_without_accel_unchanged(kwargs):
    """The accelerometer's draws come from their own stream: the gyroscope's record is the same,
    sample for sample, with or without it."""
    for seed in (0, 7):
        a = synthetic_recording(seed, **kwargs)
        b = synthetic_recording(seed, accel=True, **kwargs)
        assert a.accel is None and b.accel is not None and b.accel.f.shape == b.omega.shape
        for name in ("t", "omega", "flights", "omega0", "bias"):
            np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
        assert a.events == b.events and a.endings == b.endings


def test_offset_fit_recovers_the_sensor_position():
    """The offset fitted from each flight's samples (the gyroscope's rates and their central
    difference) holds the generator's true offset within 4 standard uncertainties plus 3 mm,
    over seeded recordings; and the coverage is not bought with huge uncertainties."""
    hits = []
    for seed in range(10, 20):
        rec = synthetic_recording(seed, tosses=2, accel=True)
        for a, b in rec.flights:
            sel = _inside(rec, a, b, 0.05)
            w = rec.omega[sel]
            r, _, r_std = fit_offset(rec.accel.f[sel], w, rate_derivative(rec.t[sel], w))
            hits.append(np.all(np.abs(r - rec.accel.offset) < 4 * r_std + 0.003))
            assert np.all(r_std < 0.01)
    assert np.mean(hits) >= 0.9


def test_free_span_finds_release_and_catch():
    """Given the whole stretch from the hold before to the hold after, the free fall's residual
    cuts each flight within 30 ms of its true release and catch."""
    for seed in (21, 22, 23):
        rec = synthetic_recording(seed, tosses=2, accel=True)
        for start, end in rec.flights:
            a = int(np.searchsorted(rec.t, start - 0.3))
            b = int(np.searchsorted(rec.t, end + 0.3))
            span = free_span(rec.t, rec.accel.f, rec.omega, a, b)
            assert span.free
            assert abs(rec.t[span.first] - start) < 0.03
            assert abs(rec.t[span.stop - 1] - end) < 0.03


def test_hand_held_is_not_free():
    """A phone swung about in the hand at several rad/s is not in free fall."""
    refused = []
    for seed in range(30, 36):
        rec = synthetic_recording(seed, tosses=1, accel=True, hand=(3.0, 10.0))
        hold = np.flatnonzero(rec.t < rec.flights[0, 0] - 0.3)
        if len(hold) < 60:
            continue
        refused.append(not free_span(rec.t, rec.accel.f, rec.omega, int(hold[0]), int(hold[-1]) + 1).free)
    assert refused and all(refused)


@pytest.mark.parametrize("as_zip", [False, True])
def test_phyphox_export_with_accelerometer(tmp_path, as_zip):
    """A phyphox export with "Gyroscope.csv" and "Accelerometer.csv" (the accelerometer at its
    own, coarser times): the specific force is read and interpolated onto the gyroscope's times,
    matching the generator's samples there to within the interpolation's error; what was read
    names the accelerometer's columns."""
    import zipfile

    from tumble.analysis.fit.accelsynth import phyphox_accel_csv
    from tumble.io.gyrodata import load_recording

    rec = synthetic_recording(41, tosses=1, accel=True, rate=200.0)
    files = {"Gyroscope.csv": rec.csv_text(), "Accelerometer.csv": phyphox_accel_csv(rec.t[::2], rec.accel.f[::2]),
             "meta/time.csv": rec.time_csv_text()}
    if as_zip:
        path = tmp_path / "export.zip"
        with zipfile.ZipFile(path, "w") as z:
            for name, text in files.items():
                z.writestr(name, text)
    else:
        path = tmp_path / "export"
        (path / "meta").mkdir(parents=True)
        for name, text in files.items():
            (path / name).write_text(text, encoding="utf-8")
    got = load_recording(path)
    assert got.read.accel[0].endswith("Accelerometer.csv: Acceleration x (m/s^2)")
    assert "Acceleration x" in got.read.brief()
    np.testing.assert_allclose(got.accel[::2][:-1], rec.accel.f[::2][:-1], atol=1e-6)  # the samples themselves
    w = (rec.t[1:-1:2] - rec.t[:-2:2]) / (rec.t[2::2] - rec.t[:-2:2])
    expected = rec.accel.f[:-2:2] + w[:, None] * (rec.accel.f[2::2] - rec.accel.f[:-2:2])
    np.testing.assert_allclose(got.accel[1:-1:2], expected, atol=1e-6)
    assert np.ptp(expected) > 1.0  # a signal that varies
