"""The absolute inertia tensor from throws with a rotor device (issues #30, #42): tumble.analysis.tensor.

Each claim is checked against an independent route: the compiled momentum-form kernel against
scipy's DOP853 on the angular-velocity form; the parallel-axis subtraction against a direct sum
over point masses; the principal moments' uncertainty against a Monte Carlo; the fits against
the synthetic truth of the real device (tumble.analysis.tensor.synthetic: its firmware's rotor
schedule, a log ending in flight, the fingers' touch, the gyroscope's scale and misalignment, the
rotor axis off nominal, integrated independently of the fit's model), and their uncertainties
on a few seeded trials each (the coverage campaigns are benchmarks/tensor_coverage.py's).
"""

from __future__ import annotations

import functools
import json

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.integrate import solve_ivp
from scipy.linalg import sqrtm

import tumble
from tumble.analysis.tensor import Device, NoThrowError, Proof, Throw, calibrate_device, fit_tensor
from tumble.analysis.tensor.estimate import mass_estimate, principal_uncertainty, subtract_body, vector_of
from tumble.analysis.tensor.calibrate import calibrate
from tumble.analysis.tensor.fit import gyro_response, sensor_errors
from tumble.analysis.tensor.firmware import Imperfections
from tumble.analysis.tensor.sensors import GYRO_BASIS, SensorErrors
from tumble.analysis.tensor.model import ThrowModel, cholesky_of, inertia_of, rotor_input
from tumble.analysis.tensor.pool import pool_throws
from tumble.analysis.tensor.synthetic import (
    GYRO_RANGE,
    ROTOR_AXIS,
    ROTOR_INERTIA,
    box,
    calibrated_device,
    combine,
    drawn_device,
    example_object,
    random_object,
    synthetic_throw,
    throw_times,
    true_device,
    true_proof,
    typical_imperfections,
)
from tumble.analysis.tensor.throw import fit_flown
from tumble.dynamics.models.gyrostat import gyrostat_omega
from made_once import made_once

FLOWN = combine(true_device(), example_object())


@functools.cache
def throw(seed: int):
    return synthetic_throw(seed, FLOWN, input=f"throw{seed}.csv")


#: fit_flown's fits, made once for a throw and arguments (deterministic in them): several tests
#: and pool_throws (the ``flown_once`` fixture) fit the same throws alike.
fitted = made_once(fit_flown)


@pytest.fixture
def flown_once(monkeypatch):
    """pool_throws fits each throw through :data:`fitted`."""
    import tumble.analysis.tensor.pool as module

    monkeypatch.setattr(module, "fit_flown", fitted)


def flown_fit(seed: int):
    return fitted(throw(seed), np.array(ROTOR_AXIS), ROTOR_INERTIA, saturation=GYRO_RANGE, errors=SensorErrors())


PERFECT = Imperfections.none(ROTOR_AXIS)


@functools.cache
def perfect_throw(seed: int):
    """A throw of a perfect device, made once: two tests fit seed 1's alike."""
    return synthetic_throw(seed, FLOWN, imperfections=PERFECT)


def test_kernel_matches_dop853_on_the_angular_velocity_form():
    """RK4 on L' = L x w - b|w|w - k W|W| a, w = I^-1 (L - h), against DOP853 on
    I w' = -w x (I w + h) - h' - b|w|w - k W|W| a (the rotor's air drag an external torque)."""
    I = np.array([[2.0e-3, 1.5e-4, -5e-5], [1.5e-4, 3.0e-3, 2e-4], [-5e-5, 2e-4, 3.5e-3]])
    a = np.array([0.3, -0.2, 0.9]) / np.linalg.norm([0.3, -0.2, 0.9])
    drag = np.array([1e-6, 2e-6, 5e-7])
    speed = lambda s: 1500.0 * (1 - np.exp(-s / 0.03))  # noqa: E731
    rate = lambda s: 1500.0 / 0.03 * np.exp(-s / 0.03)  # noqa: E731
    J = 1.7e-6

    k = 5e-11

    def rhs(s, w):
        h, hdot = J * speed(s) * a, J * rate(s) * a
        return np.linalg.solve(I, -np.cross(w, I @ w + h) - hdot - drag * np.abs(w) * w - k * speed(s) ** 2 * a)

    rng = np.random.default_rng(3)
    t = np.cumsum(250e-6 * rng.uniform(0.5, 1.5, 2000)) - 250e-6
    t[0] = 0.0
    w0 = np.array([3.0, -8.0, 12.0])
    truth = solve_ivp(rhs, (0.0, t[-1]), w0, method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True).sol(t).T
    h = J * speed(t)[:, None] * a
    mid = 0.5 * (t[1:] + t[:-1])
    g = (-speed(t)[:, None] ** 2 * a, -speed(mid)[:, None] ** 2 * a)
    w = gyrostat_omega(I[None], (I @ w0)[None], t, h, J * speed(mid)[:, None] * a, drag[None], g, [k])[0]
    assert np.abs(w - truth).max() < 1e-8 * np.abs(truth).max()


@given(st.lists(st.floats(-1.0, 1.0), min_size=6, max_size=6))
def test_every_cholesky_factor_gives_a_physical_tensor(c):
    c = np.asarray(c)
    if np.abs(c[:3]).min() < 1e-3:
        return
    I = inertia_of(c)
    moments = np.linalg.eigvalsh(I)
    assert moments[0] >= -1e-12
    assert moments[2] <= moments[0] + moments[1] + 1e-12  # the triangle inequality
    second = np.linalg.eigvalsh(0.5 * np.trace(I) * np.eye(3) - I)  # S = C C^T
    if second[0] > 2e-3 * second[2]:  # inside the floor cholesky_of keeps
        assert np.allclose(inertia_of(cholesky_of(I)), I, atol=1e-12)


def test_principal_moments_std_against_monte_carlo():
    I = np.array([[2.0e-3, 1e-4, 0.0], [1e-4, 3.0e-3, 1e-4], [0.0, 1e-4, 4.0e-3]])
    A = np.random.default_rng(0).normal(size=(6, 6)) * 1e-6
    cov = A @ A.T
    _, std, _ = principal_uncertainty(I, cov)
    draws = np.random.default_rng(1).multivariate_normal(vector_of(I), cov, 20000)
    from tumble.analysis.tensor.estimate import tensor_of

    mc = np.linalg.eigvalsh(tensor_of(draws)).std(axis=0)
    assert np.allclose(std, mc, rtol=0.03)


def _points(mass, pts):
    """Tensor about the centre of mass and the centre of point masses, by the direct sum."""
    pts = np.asarray(pts, float)
    m = np.full(len(pts), mass / len(pts))
    c = m @ pts / mass
    d = pts - c
    I = np.einsum("k,kij->ij", m, np.einsum("ki,ki->k", d, d)[:, None, None] * np.eye(3) - d[:, :, None] * d[:, None, :])
    return I, c


def test_steiner_subtraction_against_the_direct_sum():
    """A box (as the 8 point masses at +-size/sqrt(12), which have its tensor exactly) on a device
    of point masses: the whole by the direct sum, the device taken away gives the box's closed form."""
    size, centre, m_box = np.array([0.2, 0.12, 0.05]), np.array([0.01, -0.005, 0.045]), 0.6
    corners = centre + np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * size / np.sqrt(12)
    device_pts = np.random.default_rng(5).normal(0.0, 0.02, (7, 3)) + [0.0, 0.0, -0.01]
    m_dev = 0.1
    # weights: the box's 8 corners m_box / 8 each, the device's 7 points m_dev / 7 each
    pts = np.vstack([corners, device_pts])
    m = np.r_[np.full(8, m_box / 8), np.full(7, m_dev / 7)]
    c_whole = m @ pts / m.sum()
    d = pts - c_whole
    I_whole = np.einsum("k,kij->ij", m, np.einsum("ki,ki->k", d, d)[:, None, None] * np.eye(3) - d[:, :, None] * d[:, None, :])
    I_dev, c_dev = _points(m_dev, device_pts)
    whole = mass_estimate(m_box + m_dev, I_whole, np.zeros((6, 6)), c_whole, np.zeros((3, 3)))
    rest = subtract_body(whole, m_dev, I_dev, np.zeros((6, 6)), c_dev, np.zeros((3, 3)))
    closed = m_box / 12 * np.diag([size[1] ** 2 + size[2] ** 2, size[0] ** 2 + size[2] ** 2, size[0] ** 2 + size[1] ** 2])
    assert np.allclose(rest.inertia, closed, rtol=0, atol=1e-12 * closed.max())
    assert np.allclose(rest.center_of_mass, centre, atol=1e-14)
    assert np.allclose(rest.inertia, box(m_box, size, centre).inertia, atol=1e-15)


def test_the_window_is_the_free_flight_to_the_logs_end():
    """The log ends in flight: the window reaches its end; it starts after the fingers' last touch
    (0-10 ms after the true release) though the accelerometer reads free fall 10-20 ms before."""
    for seed in range(1, 7):
        tt, f = throw_times(seed), flown_fit(seed)
        assert f.reason == ""
        assert abs(f.window.t_end - throw(seed).t[-1]) < 0.010
        assert 0.0 <= f.window.t_release - tt.release < 0.010, (seed, f.window.t_release - tt.release)


def test_a_caught_throw_ends_at_the_catch():
    """A logger that runs on through the catch: the window ends before the hand stops the body."""
    th = synthetic_throw(3, FLOWN, caught=True, imperfections=PERFECT)
    f = fit_flown(th, np.array(ROTOR_AXIS), ROTOR_INERTIA, saturation=GYRO_RANGE)
    assert f.reason == ""
    assert -0.03 < f.window.t_end - throw_times(3).end < 0.0


def test_a_perfect_devices_throw_gives_the_flown_moments_within_half_a_percent():
    truth = np.linalg.eigvalsh(FLOWN.inertia)
    for seed in (1, 2, 3):
        f = fitted(perfect_throw(seed), np.array(ROTOR_AXIS), ROTOR_INERTIA, saturation=GYRO_RANGE)
        assert np.all(np.abs(np.linalg.eigvalsh(f.inertia) / truth - 1) < 0.005)
        assert np.all(f.P[12:15] >= 0) and f.P[16] >= 0   # the drags never negative


def test_a_real_gyroscopes_lone_throw_is_within_its_stated_uncertainty():
    """The gyroscope's scale and misalignment shift a lone throw's tensor by up to several per cent:
    its stated uncertainty (the sensors' part, type B) holds it."""
    truth = np.linalg.eigvalsh(FLOWN.inertia)
    for seed in range(1, 7):
        m, std, _ = principal_uncertainty(flown_fit(seed).inertia, flown_fit(seed).inertia_cov)
        assert np.all(np.abs(m - truth) < 3 * std)


def test_the_joint_fit_finds_the_gyroscopes_distortion_and_the_tensor(flown_once):
    """Three throws of one mount: one tensor, the gyroscope's trace-free distortion and the rotor's
    tilt fitted with it; the tensor within 1 %, the distortion within 0.2 % of the truth."""
    pooled, fits = pool_throws([throw(s) for s in (1, 2, 3)], np.array(ROTOR_AXIS), ROTOR_INERTIA,
                               saturation=GYRO_RANGE, errors=SensorErrors())
    truth = np.linalg.eigvalsh(FLOWN.inertia)
    from tumble.analysis.tensor.estimate import tensor_of

    moments = np.linalg.eigvalsh(tensor_of(pooled.inertia))
    assert np.all(np.abs(moments / truth - 1) < 0.01), moments / truth - 1
    assert np.abs(pooled.center - FLOWN.center).max() < 1.5e-3


def test_centre_of_mass_from_the_accelerometer(flown_once):
    """The joint fit's centre of mass (three throws: the air's drag and the firmware's smoothing
    modelled, the rotor's jolts left out) within its stated uncertainty."""
    pooled, _ = pool_throws([throw(s) for s in (4, 5, 6)], np.array(ROTOR_AXIS), ROTOR_INERTIA,
                            saturation=GYRO_RANGE, errors=SensorErrors())
    err, std = np.abs(pooled.center - FLOWN.center), np.sqrt(np.diag(pooled.center_cov))
    assert np.all(err < 3 * std) and err.max() < 1.5e-3


def test_fit_tensor_gives_the_object_and_its_json():
    obj = example_object()
    fit = fit_tensor([throw(s) for s in (1, 2, 3)], calibrated_device(), obj.mass)
    truth = np.linalg.eigvalsh(obj.inertia)
    assert fit.adequate and [t.status for t in fit.throws] == ["used"] * 3
    assert np.all(np.abs(fit.object.principal_moments / truth - 1) < 0.02)
    assert np.all(np.abs(fit.object.principal_moments - truth) < 3 * fit.object.principal_moments_std)
    assert np.abs(fit.object.center_of_mass - obj.center).max() < 2e-3
    assert fit.flown.mass == pytest.approx(obj.mass + 0.10067)
    d = json.loads(json.dumps(fit.as_dict()))
    assert set(d) == {"object", "flown", "throws", "adequate", "chi2_dof", "on_edge"} and d["on_edge"] == 0.0
    assert set(d["object"]) == {"mass", "inertia", "inertia_cov", "principal_moments", "principal_moments_std",
                                "principal_axes", "center_of_mass", "center_of_mass_std"}
    assert [t["input"] for t in d["throws"]] == ["throw1.csv", "throw2.csv", "throw3.csv"]
    assert tumble.fit_tensor is fit_tensor and tumble.calibrate_device is calibrate_device


def test_the_rotor_inertia_scales_the_whole_tensor():
    """The gyrostat's equations are unchanged when I and J_r scale together: a J_r 10 % high gives
    a tensor 10 % high (and so the rotor's uncertainty is a systematic part common to all throws)."""
    th = perfect_throw(1)
    f = fitted(th, np.array(ROTOR_AXIS), ROTOR_INERTIA, saturation=GYRO_RANGE)
    g = fit_flown(th, np.array(ROTOR_AXIS), 1.1 * ROTOR_INERTIA, saturation=GYRO_RANGE)
    assert np.allclose(g.inertia, 1.1 * f.inertia, rtol=1e-4, atol=1e-4 * np.abs(f.inertia).max())


def test_scale_is_undetermined_without_the_rotors_reaction():
    """Without a rotor (h = 0) scaling I and L together leaves every prediction unchanged: the
    Jacobian has that null direction; with the rotor spinning up it has not."""
    t = np.arange(2000) / 4000.0
    data = np.zeros((2000, 3))
    keep = np.ones((2000, 3), bool)
    P = np.r_[cholesky_of(FLOWN.inertia), FLOWN.inertia @ [3.0, -8.0, 12.0], np.zeros(8)]
    scale = np.r_[0.5 * P[:6], P[6:9], np.zeros(8)]  # d/dk of (sqrt(k) C, k L) at k = 1
    for speed, null in ((np.zeros(2000), True), (np.where(t > 0.01, 1500 * (1 - np.exp(-(t - 0.01) / 0.03)), 0.0), False)):
        model = ThrowModel(t, data, keep, rotor_input(t, speed + 1e-9 * (speed == 0), 0, ROTOR_INERTIA, ROTOR_AXIS))
        J = model.jacobian(P)
        ratio = np.linalg.norm(J @ scale) / (np.linalg.norm(J, axis=0) @ np.abs(scale))
        assert (ratio < 1e-4) == null
    dead = [synthetic_throw(s, FLOWN, rotor_top=0.0, input=f"dead{s}.csv") for s in (1, 2)]
    with pytest.raises(NoThrowError, match="scale is undetermined"):
        fit_tensor(dead, calibrated_device(), 0.6)


@functools.cache
def _calibration():
    proof, placed = true_proof()
    alone = [synthetic_throw(s, true_device(), spin=(3.0, 8.0), input=f"a{s}.csv") for s in (11, 12, 13)]
    with_proof = [synthetic_throw(s, combine(true_device(), placed), input=f"p{s}.csv") for s in (14, 15, 16)]
    return calibrate(Device(0.10067, ROTOR_AXIS), alone, with_proof, proof), alone, with_proof


def test_calibration_recovers_the_rotor_and_the_device_and_checks_out():
    cal = _calibration()[0]
    dev = true_device()
    assert cal.problems == () and cal.alone_used == 3 and cal.proof_used == 3
    device = cal.device
    assert device.calibrated
    assert abs(device.rotor_inertia / ROTOR_INERTIA - 1) < 0.01
    assert abs(device.rotor_inertia - ROTOR_INERTIA) < 4 * device.rotor_inertia_std
    assert np.all(np.abs(np.linalg.eigvalsh(device.inertia) / np.linalg.eigvalsh(dev.inertia) - 1) < 0.03)
    assert np.abs(device.center_of_mass - dev.center).max() < 1e-3
    assert cal.max_bias < 0.1   # the joint fit's biases: the gyroscope's own (0.01 rad/s), not a distortion's


def _gyro_truth():
    """The typical device's gyroscope as a fit sees it: ``G = P R`` (left polar decomposition), the
    distortion ``P`` over its mean scale less the identity, and the rotor's axis in the frame the
    gyroscope's axes turn it to, ``R a``."""
    imp = typical_imperfections()
    P = np.real(sqrtm(imp.gyro @ imp.gyro.T))
    return P / (np.trace(P) / 3.0) - np.eye(3), np.linalg.solve(P, imp.gyro) @ imp.rotor_axis


def test_the_calibration_finds_the_gyroscopes_cross_axis_terms_and_the_rotors_axis():
    device = _calibration()[0].device
    D_true, axis_true = _gyro_truth()
    D, D_std = device.gyro_distortion, device.gyro_distortion_std
    off = ~np.eye(3, dtype=bool)
    # the cross-axis terms (0.1-0.8 %) to within 4 std; the diagonal, which trades with the tensor along
    # the rotor's axis, left at 0 with the stated scale's std (calibrated_sensors)
    assert np.all(np.abs(D - D_true)[off] <= 4 * D_std[off] + 1e-5), (D, D_true, D_std)
    assert np.abs(D_true[off]).max() > 10 * D_std[off].max()
    assert np.all(np.diag(D) == 0) and np.allclose(np.diag(D_std), 0.003 * np.sqrt(2 / 3))
    angle = np.degrees(np.arccos(np.clip(device.rotor_axis @ axis_true, -1.0, 1.0)))
    nominal = np.degrees(np.arccos(np.clip(np.array(ROTOR_AXIS) @ axis_true, -1.0, 1.0)))
    assert nominal > 0.5 and angle < 0.1 * nominal, (angle, nominal)
    assert device.rotor_axis_std < np.deg2rad(0.1)


def test_a_lone_throw_with_the_calibrated_gyroscope_is_within_a_percent_and_its_interval():
    """The calibration's cross-axis terms and axis correct every later throw (fit_flown's gyro): a
    lone throw's flown moments move from a few per cent off (the distortion unseen) to about a
    per cent, their stated std under 2 % (the scale factors' differences, left to their stated
    std, dominate them) and their 95 % intervals holding the truth (benchmarks/tensor_coverage.py:
    97.8 % of 900 on 25 calibrated devices)."""
    device = _calibration()[0].device
    truth = np.linalg.eigvalsh(FLOWN.inertia)
    raw, corrected, z = [], [], []
    for seed in (1, 2, 3, 4):
        plain = flown_fit(seed)
        fit = fit_flown(throw(seed), device.rotor_axis, ROTOR_INERTIA, saturation=GYRO_RANGE,
                        errors=sensor_errors(device), gyro=gyro_response(device))
        m, s, _ = principal_uncertainty(fit.inertia, fit.inertia_cov)
        assert np.all(s / m < 0.02)
        raw.append(np.abs(np.linalg.eigvalsh(plain.inertia) / truth - 1))
        corrected.append(np.abs(m / truth - 1))
        z.append(np.abs(m - truth) / s)
    # 12 moments: 10 or more inside their 95 % interval (fewer has probability 2 % when they are right)
    assert np.sum(np.array(z) <= 1.96) >= 10 and np.max(z) < 4, np.round(z, 2)
    assert np.max(corrected) < 0.025 and np.median(corrected) < 0.01
    assert np.median(corrected) < np.median(raw) / 2, (np.median(corrected), np.median(raw))


def _trial(k: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One seeded trial: a random box on the device (its calibration off by draws from its stated
    std), two throws pooled; returns the object's moments, their std and the truth."""
    rng = np.random.default_rng(1000 + k)
    obj = random_object(rng)
    fit = fit_tensor([synthetic_throw(100 * k + j, combine(true_device(), obj)) for j in range(2)], drawn_device(rng),
                     obj.mass)
    return fit.object.principal_moments, fit.object.principal_moments_std, np.linalg.eigvalsh(obj.inertia)


def test_pooled_estimates_are_within_their_uncertainty_and_narrow():
    """Three seeded trials of two throws (a real gyroscope's distortion, the calibration off by draws
    from its stated std): every moment within 3 of its stated std of the truth (an uncertainty
    stated 3 times too small fails this), the std under 3 % of the moment (an interval that holds
    only by being wide fails that) and the error under 3 %. The coverage itself (95 % intervals in
    90-98 % of 100 objects, 3 throws each, on 25 calibrated devices) is benchmarks/tensor_coverage.py's."""
    for k in range(3):
        m, s, truth = _trial(k)
        assert np.all(np.abs(m - truth) < 3 * s), (k, (m - truth) / s)
        assert np.all(s / m < 0.03) and np.all(np.abs(m / truth - 1) < 0.03), (k, s / m, m / truth - 1)


def test_bad_input_is_refused_with_the_field_named():
    with pytest.raises(ValueError, match="device.mass"):
        Device(0.0, ROTOR_AXIS)
    with pytest.raises(ValueError, match="device.rotor_axis"):
        Device(0.1, [0, 0, 0])
    with pytest.raises(ValueError, match="proof.inertia"):
        Proof(0.3, [1.0, 1.0, 3.0])  # breaks the triangle inequality
    t = np.arange(50) / 4000.0
    with pytest.raises(ValueError, match="throw a.csv rotor"):
        Throw(t, np.zeros((50, 3)), np.zeros(49), None, "a.csv")
    with pytest.raises(ValueError, match="must increase"):
        Throw(t[::-1], np.zeros((50, 3)), np.zeros(50))
    with pytest.raises(ValueError, match="not calibrated"):
        fit_tensor([throw(1)], Device(0.1, ROTOR_AXIS, 1.7e-6), 0.6)
    with pytest.raises(ValueError, match="mass"):
        fit_tensor([throw(1)], calibrated_device(), -1.0)
    with pytest.raises(ValueError, match="non-empty list of Throw"):
        fit_tensor([], calibrated_device(), 0.6)
    for names in ("o1.csv", ["o1.csv", "o2.csv"]):  # what a new user tries first: the files
        with pytest.raises(ValueError, match=r"^throws are Throw objects, not files' names: read each log with "
                                             r"tumble.io.throwfile.read_throw\(path, device\)$"):
            fit_tensor(names, calibrated_device(), 0.6)


def test_the_centres_sensor_columns_are_what_an_accelerometer_scale_does():
    """The pooled centre's accelerometer column (one ACCEL_SCALE_STD of the x axis's scale factor)
    against the centre's shift when the same throws are logged by an accelerometer whose x axis
    reads 1 % high (an independent simulation: the synthetic device's own scale factor)."""
    from dataclasses import replace

    from tumble.analysis.tensor.center import ACCEL_SCALE_STD

    flown = combine(true_device(), example_object())
    imp = Imperfections.none(ROTOR_AXIS)
    errors = SensorErrors()
    centres = []
    for scale in (1.0, 1.0 + ACCEL_SCALE_STD):
        logs = [synthetic_throw(s, flown, imperfections=replace(imp, accel_scale=np.array([scale, 1.0, 1.0])))
                for s in (1, 2)]
        pooled, _ = pool_throws(logs, np.array(ROTOR_AXIS), ROTOR_INERTIA, errors=errors)
        centres.append(pooled.center)
        if scale == 1.0:
            column = pooled.center_columns[:, 0]
    shift = centres[1] - centres[0]
    assert np.linalg.norm(shift) > 1e-4   # 1 % of the flown centre's ~40 mm moves it by a few 0.1 mm
    assert np.linalg.norm(shift - column) < 0.2 * np.linalg.norm(shift)


@pytest.mark.parametrize("seed", range(5))
def test_an_estimate_over_the_triangles_edge_is_written_on_it(seed):
    """A flat body's estimate lies on either side of the edge I1 + I2 = I3; one over it by less than
    TRIANGLE_SIGMA was written as it was, not physical, as adequate (a 40 g box, 1.8 sigma; a walkthrough,
    2026-12-03). onto_triangle puts it on the edge at the least Mahalanobis distance: checked against scipy's
    SLSQP minimising (x - x0)^T C^-1 (x - x0) under lambda1 + lambda2 - lambda3 = 0, an independent route."""
    from scipy.optimize import minimize
    from scipy.spatial.transform import Rotation

    from tumble.analysis.tensor.estimate import mass_estimate, not_physical, onto_triangle, tensor_of, vector_of
    from tumble.mass.tensor import check_inertia

    rng = np.random.default_rng(seed)
    R = Rotation.random(random_state=seed).as_matrix()
    moments = np.array([1.0, 2.0, 3.0]) * 1e-5 + np.array([-1.0, -1.0, 1.0]) * rng.uniform(0.5, 1.5) * 1e-7
    A = rng.normal(size=(6, 6)) * 1e-7
    C = A @ A.T + np.eye(6) * 1e-15
    est = mass_estimate(0.04, R @ np.diag(moments) @ R.T, C, np.zeros(3), np.eye(3) * 1e-8)
    edge, moved = onto_triangle(est)
    if not_physical(est):   # beyond TRIANGLE_SIGMA: refused before, never moved
        pytest.skip("this draw lies beyond the tolerance")
    m = edge.principal_moments
    assert m[0] + m[1] - m[2] >= -1e-12 * m.sum() and check_inertia(edge.inertia) is not None
    x0, x = vector_of(est.inertia), vector_of(edge.inertia)
    L = np.linalg.cholesky(C)   # x = x0 + L z: the distance is |z|, and SLSQP works on numbers of order 1

    def gap(z):
        w = np.linalg.eigvalsh(tensor_of(x0 + L @ z))
        return (w[0] + w[1] - w[2]) / np.sqrt(np.max(np.diag(C)))

    best = minimize(lambda z: z @ z, np.zeros(6), jac=lambda z: 2 * z, constraints=[{"type": "eq", "fun": gap}],
                    method="SLSQP", options={"ftol": 1e-14, "maxiter": 500})
    assert best.success and np.sqrt(best.fun) == pytest.approx(moved, rel=1e-4)
    np.testing.assert_allclose(x, x0 + L @ best.x, rtol=0, atol=1e-3 * np.sqrt(np.max(np.diag(C))))
    assert onto_triangle(edge)[1] == 0.0   # on the edge already: left as it is
