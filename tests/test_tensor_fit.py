"""The absolute inertia tensor from throws with a rotor device (issue #30): tumble.analysis.tensor.

Each claim is checked against an independent route: the compiled momentum-form kernel against
scipy's DOP853 on the angular-velocity form; the parallel-axis subtraction against a direct sum
over point masses; the principal moments' uncertainty against a Monte Carlo; the fits against
the synthetic truth (integrated independently of the fit's model), and their uncertainties by
coverage over seeded trials.
"""

from __future__ import annotations

import functools
import json

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

import tumble
from tumble.analysis.tensor import Device, NoThrowError, Proof, Throw, calibrate_device, fit_tensor
from tumble.analysis.tensor.estimate import mass_estimate, principal_uncertainty, subtract_body, vector_of
from tumble.analysis.tensor.flight import find_flight
from tumble.analysis.tensor.model import ThrowModel, cholesky_of, inertia_of, rotor_input
from tumble.analysis.tensor.synthetic import (
    ROTOR_AXIS,
    ROTOR_INERTIA,
    box,
    calibrated_device,
    combine,
    drawn_device,
    example_object,
    random_object,
    release_and_catch,
    synthetic_throw,
    true_device,
    true_proof,
)
from tumble.analysis.tensor.throw import fit_flown
from tumble.dynamics.models.gyrostat import gyrostat_omega

FLOWN = combine(true_device(), example_object())


@functools.cache
def throw(seed: int):
    return synthetic_throw(seed, FLOWN, input=f"throw{seed}.csv")


@functools.cache
def flown_fit(seed: int):
    return fit_flown(throw(seed), np.array(ROTOR_AXIS), ROTOR_INERTIA)


def test_kernel_matches_dop853_on_the_angular_velocity_form():
    """RK4 on L' = L x w - b|w|w, w = I^-1 (L - h), against DOP853 on I w' = -w x (I w + h) - h' - b|w|w."""
    I = np.array([[2.0e-3, 1.5e-4, -5e-5], [1.5e-4, 3.0e-3, 2e-4], [-5e-5, 2e-4, 3.5e-3]])
    a = np.array([0.3, -0.2, 0.9]) / np.linalg.norm([0.3, -0.2, 0.9])
    drag = np.array([1e-6, 2e-6, 5e-7])
    speed = lambda s: 1500.0 * (1 - np.exp(-s / 0.03))  # noqa: E731
    rate = lambda s: 1500.0 / 0.03 * np.exp(-s / 0.03)  # noqa: E731
    J = 1.7e-6

    def rhs(s, w):
        h, hdot = J * speed(s) * a, J * rate(s) * a
        return np.linalg.solve(I, -np.cross(w, I @ w + h) - hdot - drag * np.abs(w) * w)

    rng = np.random.default_rng(3)
    t = np.cumsum(250e-6 * rng.uniform(0.5, 1.5, 2000)) - 250e-6
    t[0] = 0.0
    w0 = np.array([3.0, -8.0, 12.0])
    truth = solve_ivp(rhs, (0.0, t[-1]), w0, method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True).sol(t).T
    h = J * speed(t)[:, None] * a
    mid = 0.5 * (t[1:] + t[:-1])
    w = gyrostat_omega(I[None], (I @ w0)[None], t, h, J * speed(mid)[:, None] * a, drag[None])[0]
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


def test_flight_found_from_the_data():
    for seed in range(1, 7):
        t_r, t_c = release_and_catch(seed)
        win = find_flight(throw(seed), np.ones(throw(seed).omega.shape, bool))
        assert win.reason == ""
        assert abs(win.t_release - t_r) < 0.002  # the accelerometer's free fall
        assert -0.012 < win.t_end - t_c < 0.002  # the catch, a few ms early
        assert throw(seed).t[win.first] > t_r  # the fitted samples are all free


def test_one_throw_gives_the_flown_moments_within_one_percent():
    truth = np.linalg.eigvalsh(FLOWN.inertia)
    errors = []
    for seed in range(1, 7):
        f = flown_fit(seed)
        assert f.reason == "" and f.adequacy.adequate
        m, std, _ = principal_uncertainty(f.inertia, f.inertia_cov)
        errors.append(m / truth - 1)
        assert np.all(np.abs(m - truth) < 4 * std)
    assert np.all(np.median(np.abs(errors), axis=0) < 0.01)


def test_centre_of_mass_from_the_accelerometer():
    for seed in range(1, 7):
        f = flown_fit(seed)
        err, std = np.abs(f.center - FLOWN.center), np.sqrt(np.diag(f.center_cov))
        assert np.all(err < 3 * std)
        assert err.max() < (5e-3 if std.max() > 1e-3 else 1e-3)  # a mm, a few where the spin stays near an axis


def test_fit_tensor_gives_the_object_and_its_json():
    obj = example_object()
    fit = fit_tensor([throw(s) for s in (1, 2, 3)], calibrated_device(), obj.mass)
    truth = np.linalg.eigvalsh(obj.inertia)
    assert fit.adequate and [t.status for t in fit.throws] == ["used"] * 3
    assert np.all(np.abs(fit.object.principal_moments / truth - 1) < 0.01)
    assert np.all(np.abs(fit.object.principal_moments - truth) < 3 * fit.object.principal_moments_std)
    assert np.abs(fit.object.center_of_mass - obj.center).max() < 1e-3
    assert fit.flown.mass == pytest.approx(obj.mass + 0.10067)
    d = json.loads(json.dumps(fit.as_dict()))
    assert set(d) == {"object", "flown", "throws", "adequate", "chi2_dof"}
    assert set(d["object"]) == {"mass", "inertia", "inertia_cov", "principal_moments", "principal_moments_std",
                                "principal_axes", "center_of_mass", "center_of_mass_std"}
    assert [t["input"] for t in d["throws"]] == ["throw1.csv", "throw2.csv", "throw3.csv"]
    assert tumble.fit_tensor is fit_tensor and tumble.calibrate_device is calibrate_device


def test_the_rotor_inertia_scales_the_whole_tensor():
    """The gyrostat's equations are unchanged when I and J_r scale together: a J_r 10 % high gives
    a tensor 10 % high (and so the rotor's uncertainty is a systematic part common to all throws)."""
    f = flown_fit(1)
    g = fit_flown(throw(1), np.array(ROTOR_AXIS), 1.1 * ROTOR_INERTIA)
    assert np.allclose(g.inertia, 1.1 * f.inertia, rtol=1e-4, atol=1e-4 * np.abs(f.inertia).max())


def test_scale_is_undetermined_without_the_rotors_reaction():
    """Without a rotor (h = 0) scaling I and L together leaves every prediction unchanged: the
    Jacobian has that null direction; with the rotor spinning up it has not."""
    t = np.arange(2000) / 4000.0
    data = np.zeros((2000, 3))
    keep = np.ones((2000, 3), bool)
    P = np.r_[cholesky_of(FLOWN.inertia), FLOWN.inertia @ [3.0, -8.0, 12.0], np.zeros(6)]
    scale = np.r_[0.5 * P[:6], P[6:9], np.zeros(6)]  # d/dk of (sqrt(k) C, k L) at k = 1
    for speed, null in ((np.zeros(2000), True), (np.where(t > 0.01, 1500 * (1 - np.exp(-(t - 0.01) / 0.03)), 0.0), False)):
        model = ThrowModel(t, data, keep, rotor_input(t, speed + 1e-9 * (speed == 0), 0, ROTOR_INERTIA, ROTOR_AXIS))
        J = model.jacobian(P)
        ratio = np.linalg.norm(J @ scale) / (np.linalg.norm(J, axis=0) @ np.abs(scale))
        assert (ratio < 1e-4) == null
    dead = [synthetic_throw(s, FLOWN, rotor_top=0.0, input=f"dead{s}.csv") for s in (1, 2)]
    with pytest.raises(NoThrowError, match="scale is undetermined"):
        fit_tensor(dead, calibrated_device(), 0.6)


def test_calibration_recovers_the_rotor_and_the_device():
    proof, placed = true_proof()
    dev = true_device()
    alone = [synthetic_throw(s, dev, rotor_top=300.0, spin=(3.0, 6.0)) for s in (11, 12, 13)]
    with_proof = [synthetic_throw(s, combine(dev, placed)) for s in (14, 15, 16)]
    cal = calibrate_device(Device(0.10067, ROTOR_AXIS), alone, with_proof, proof)
    assert cal.calibrated
    assert abs(cal.rotor_inertia / ROTOR_INERTIA - 1) < 0.01
    assert abs(cal.rotor_inertia - ROTOR_INERTIA) < 4 * cal.rotor_inertia_std
    assert np.all(np.abs(np.linalg.eigvalsh(cal.inertia) / np.linalg.eigvalsh(dev.inertia) - 1) < 0.03)
    assert np.abs(cal.center_of_mass - dev.center).max() < 1e-3
    assert np.all(np.abs(cal.inertia - dev.inertia) < 4 * cal.inertia_std + 1e-9)


def _trial(k: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One seeded trial: a random box on the device (its calibration off by draws from its stated
    std), two throws pooled; returns the object's moments, their std and the truth."""
    rng = np.random.default_rng(1000 + k)
    obj = random_object(rng)
    fit = fit_tensor([synthetic_throw(100 * k + j, combine(true_device(), obj)) for j in range(2)], drawn_device(rng),
                     obj.mass)
    return fit.object.principal_moments, fit.object.principal_moments_std, np.linalg.eigvalsh(obj.inertia)


def test_pooled_intervals_cover_the_truth():
    """20 seeded trials: the pooled 95 % intervals of the three moments hold the truth 95 % of the time
    (57 of 60 expected; fewer than 51 has probability < 0.5 % for a right uncertainty)."""
    covered = 0
    errors = []
    for k in range(20):
        m, s, truth = _trial(k)
        covered += int(np.sum(np.abs(m - truth) <= 1.96 * s))
        errors.append(np.abs(m / truth - 1))
    assert covered >= 51
    assert np.all(np.median(errors, axis=0) < 0.01)


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
