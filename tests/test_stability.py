"""The tennis-racket theorem shown, not asserted: theory against simulation."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import tumble
from tumble.analysis import (
    energy_momentum_gaps,
    flip_interval,
    flip_times,
    linearised_rate,
    stability_report,
)
from tumble.dynamics import simulate
from tumble.mass import MassProperties


def free_body(moments):
    return MassProperties.from_inertia(1.0, np.zeros(3), np.diag(moments))


@st.composite
def asymmetric_moments(draw):
    """I1 < I2 < I3 with gaps of at least 15% and the triangle inequality."""
    I1 = draw(st.floats(0.1, 10.0))
    I2 = I1 * draw(st.floats(1.15, 3.0))
    I3 = min(I2 * draw(st.floats(1.15, 3.0)), 0.999 * (I1 + I2))
    if not I3 > 1.15 * I2:
        I3 = None
    return None if I3 is None else np.array([I1, I2, I3])


@settings(max_examples=25)
@given(asymmetric_moments(), st.sampled_from([0, 1, 2]), st.floats(0.5, 5.0))
def test_flips_happen_exactly_for_the_intermediate_axis(moments, axis, spin):
    if moments is None:
        return
    eps = 1e-3 * spin
    w0 = np.full(3, eps)
    w0[axis] = spin
    growth, wobble = linearised_rate(moments, axis, spin)
    assert (growth > 0) == (axis == 1) and (wobble > 0) == (axis != 1)
    # long enough for several flips if the axis is unstable: a flip interval is about
    # ln(1/eps)/lambda; take 4 of the exact ones (or 40 wobble periods for stable axes)
    t_end = 4 * flip_interval(w0, moments) if axis == 1 else 40 * 2 * np.pi / wobble
    traj = simulate(free_body(moments), w0, t_end=float(t_end), samples=4000, method="dop853", rtol=1e-10)
    report = stability_report(traj)
    assert report["predicted"] == ("unstable" if axis == 1 else "stable")
    if axis == 1:
        assert report["flips"] >= 3
    else:
        assert report["flips"] == 0


@pytest.mark.parametrize("preset", ["t-handle", "iss-t-handle"])
def test_linearised_growth_rate_matches_simulation(preset):
    """Fit the exponential growth of a 1e-9 perturbation of intermediate-axis spin."""
    body = tumble.load_body(preset)
    W = 5.0
    w0 = np.array([1e-9, W, 1e-9]) * [1, 1, 1]
    lam, _ = linearised_rate(body.principal_moments, 1, W)
    t_end = np.log(1e7) / lam  # grows ~1e7 fold, still < 1e-2 of W
    traj = simulate(body, w0, t_end=float(t_end), samples=400, method="dop853", rtol=1e-13, atol=1e-20)
    amp = np.hypot(traj.omega[:, 0] * np.sqrt(body.principal_moments[0]), traj.omega[:, 2] * np.sqrt(body.principal_moments[2]))
    late = traj.t > 0.3 * t_end  # after the decaying mode has died out
    slope = np.polyfit(traj.t[late], np.log(amp[late]), 1)[0]
    assert slope == pytest.approx(lam, rel=2e-3)


@pytest.mark.parametrize("axis", [0, 2])
def test_wobble_frequency_matches_simulation(axis):
    body = tumble.iss_t_handle()
    W = 10.0
    w0 = np.full(3, 1e-4)
    w0[axis] = W
    _, wobble = linearised_rate(body.principal_moments, axis, W)
    traj = simulate(body, w0, t_end=float(20 * 2 * np.pi / wobble), samples=4000, method="dop853")
    other = (axis + 1) % 3
    crossings = flip_times(traj.t, traj.omega[:, other])
    assert np.mean(np.diff(crossings)) == pytest.approx(np.pi / wobble, rel=1e-6)


@pytest.mark.parametrize("w0", [[0.1, 10.0, 0.1], [0.3, 2.0, -0.1], [1.0, 0.1, 0.1], [0.0, 1.0, 0.5]])
def test_exact_flip_interval_matches_simulated_flips(w0):
    body = tumble.t_handle()
    T = flip_interval(w0, body.principal_moments)
    traj = simulate(body, w0, t_end=float(6.5 * T), samples=20000, method="dop853")
    gaps = energy_momentum_gaps(w0, body.principal_moments)
    flipping = 0 if gaps[1] > 0 else 2  # the axis that is not the circulation axis nor axis 2
    crossings = flip_times(traj.t, traj.omega[:, 1])
    np.testing.assert_allclose(np.diff(crossings), T, rtol=1e-6)
    assert len(flip_times(traj.t, traj.omega[:, flipping])) >= 5


def test_flip_interval_limits():
    I = np.array([1.0, 2.0, 2.5])
    # near a stable axis the interval tends to half the linearised wobble period
    for axis in (0, 2):
        w = np.full(3, 1e-7)
        w[axis] = 3.0
        _, wobble = linearised_rate(I, axis, 3.0)
        assert flip_interval(w, I) == pytest.approx(np.pi / wobble, rel=1e-9)
    # on the separatrix it is infinite; near it each flip lingers at a saddle, approaching and
    # leaving it, so the interval grows like 2 log(1/eps) / lambda
    assert flip_interval([0.0, 1.0, 0.0], I) == np.inf
    lam, _ = linearised_rate(I, 1, 1.0)
    t1 = flip_interval([1e-6, 1.0, 1e-6], I)
    t2 = flip_interval([1e-8, 1.0, 1e-8], I)
    assert t2 - t1 == pytest.approx(2 * np.log(100) / lam, rel=1e-3)


def test_energy_momentum_gaps_match_the_naive_formula(rng):
    I = np.array([1.0, 2.0, 3.0])
    w = rng.normal(size=(10, 3))
    L2 = np.sum((I * w) ** 2, axis=1)
    E2 = np.sum(I * w * w, axis=1)
    np.testing.assert_allclose(energy_momentum_gaps(w, I), L2[:, None] - E2[:, None] * I, rtol=1e-12, atol=1e-12)


def test_flip_times_interpolates_zero_crossings():
    t = np.linspace(0, 10, 1001)
    np.testing.assert_allclose(flip_times(t, np.sin(t)), [np.pi, 2 * np.pi, 3 * np.pi], atol=1e-5)
