"""tumble.analysis.periods: the body-frame period, Montgomery's rotation per period, the symmetric
top's rates and the periods of tumbling rotation, each against an independent route: closed
forms (Landau & Lifshitz secs. 33, 37), DOP853 runs, and mpmath quadrature of the polhode's solid
angle with mpmath's own Jacobi functions (no tumble code)."""

from __future__ import annotations

import functools

import mpmath as mp
import numpy as np
import pytest

import tumble
from tumble.analysis import periods as P
from tumble.analysis import flip_interval


def body(moments):
    return tumble.MassProperties.from_moments(moments)


# Bodies on both sides of the separatrix (SAM: circulation about the major axis; LAM: minor),
# symmetric tops both ways, the seed T-handle, and signs of omega that reverse the branches. All
# are bodies that exist (I1 + I2 >= I3, issue 27): [2, 2.5, 4.5] is a flat plate (the limit).
CASES = [
    ([1.0, 2.0, 3.0], [0.1, 1.0, 0.3], "SAM"),
    ([1.0, 2.0, 3.0], [1.0, 0.5, 0.1], "LAM"),
    ([1.0, 2.0, 3.0], [0.2, 0.3, 1.0], "SAM"),
    ([1.0, 2.0, 3.0], [-1.0, 0.5, -0.4], "LAM"),
    ([1.0, 2.0, 3.0], [0.3, -0.9, -0.5], "SAM"),
    ([2.0, 2.5, 4.5], [0.7, -0.2, 0.05], "LAM"),
    ([0.125, 0.3125, 0.4375], [0.1, 10.0, 0.1], "SAM"),
    ([0.125, 0.3125, 0.4375], [-0.3, 10.0, 0.1], "LAM"),
    ([2.0, 2.0, 3.0], [0.3, 0.0, 1.0], "SAM"),
    ([1.0, 3.0, 3.0], [1.0, 0.3, 0.1], "LAM"),
]


def test_period_is_twice_the_flip_interval_and_2pi_over_p_for_a_top():
    I = np.array([c[0] for c in CASES])
    w = np.array([c[1] for c in CASES])
    np.testing.assert_array_equal(P.period(w, I), 2.0 * flip_interval(w, I))
    # oblate top: p = (I3 - I1) w3 / I1 (Landau & Lifshitz sec. 36), T = 2 pi / p
    assert P.period([0.3, 0.0, 1.0], [2.0, 2.0, 3.0]) == pytest.approx(2 * np.pi / ((3.0 - 2.0) * 1.0 / 2.0), rel=1e-15)
    # prolate top: p = (I_perp - I1) |w1| / I_perp
    assert P.period([1.0, 0.3, 0.1], [1.0, 3.0, 3.0]) == pytest.approx(2 * np.pi / (2.0 / 3.0), rel=1e-15)
    # the separatrix, exactly in doubles: g2 = 3 (3 - 4) 2^2 + 6 (6 - 4) 1^2 = 0; and rest
    assert P.period([2.0, 0.5, 1.0], [3.0, 4.0, 6.0]) == np.inf
    assert np.isnan(P.montgomery_angle([2.0, 0.5, 1.0], [3.0, 4.0, 6.0]))
    assert P.period([[0.0, 0.0, 0.0]] * 2, [1.0, 2.0, 3.0]).tolist() == [np.inf, np.inf]  # rest (batch)
    assert P.period([[0.0, 1.0, 0.0]] * 2, [1.0, 1.0, 1.0]).tolist() == [np.inf, np.inf]  # a sphere (batch)


def test_period_at_rest_single():
    assert P.period([0.0, 0.0, 0.0], [1.0, 2.0, 3.0]) == np.inf


def test_vectorised_over_batches_and_validated():
    I = np.array([c[0] for c in CASES])
    w = np.array([c[1] for c in CASES])
    for f in (P.period, P.montgomery_angle, P.polhode_solid_angle, P.precession_per_period):
        batch = f(w, I)
        assert batch.shape == (len(CASES),)
        single = [float(f(wi, Ii)) for wi, Ii in zip(w, I)]
        np.testing.assert_allclose(batch, single, rtol=1e-14, atol=1e-14)
        assert f(w.reshape(2, 5, 3), I.reshape(2, 5, 3)).shape == (2, 5)
    P_phi, P_psi, mode = P.npa_periods(w, I)
    assert P_phi.shape == P_psi.shape == mode.shape == (len(CASES),)
    assert list(mode) == [c[2] for c in CASES]
    with pytest.raises(ValueError, match=r"moments\[1\].*ascending"):
        P.period(w[:2], [[1.0, 2.0, 3.0], [1.0, 3.0, 2.0]])
    with pytest.raises(ValueError, match="omega"):
        P.montgomery_angle([np.nan, 1.0, 0.0], [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="broadcast"):
        P.npa_periods(np.ones((4, 3)), np.ones((3, 3)) * [1.0, 2.0, 3.0])


@pytest.mark.parametrize("moments, omega, mode", CASES)
def test_montgomery_closed_form_against_dop853(moments, omega, mode):
    """Closed form (complete Pi) vs the rotation measured on a DOP853 run over one period."""
    T = float(P.period(omega, moments))
    traj = tumble.simulate(body(moments), omega, times=[0.0, T], method="dop853")
    measured = P.rotation_per_period(traj)
    closed = float(P.montgomery_angle(omega, moments))
    diff = (measured - closed + np.pi) % (2 * np.pi) - np.pi
    assert abs(diff) < 1e-8  # measured: at most 9.2e-12 rad over these cases


@pytest.mark.parametrize("moments, omega, mode", CASES[:4])
def test_rotation_per_period_of_the_exact_solution(moments, omega, mode):
    """The exact solution's attitude (Carlson's incomplete Pi, its own route) agrees too."""
    T = float(P.period(omega, moments))
    traj = tumble.simulate(body(moments), omega, times=[0.0, 0.3 * T, T], method="exact")
    diff = P.rotation_per_period(traj) - float(P.montgomery_angle(omega, moments))
    assert abs((diff + np.pi) % (2 * np.pi) - np.pi) < 1e-12  # measured: at most 2.4e-14 rad


def _solid_angle_mpmath(moments, omega, dps=30):
    """``oint (1 - cos theta) d alpha`` of the polhode, by mpmath quadrature over one period of
    the elliptic argument with mpmath's sn, cn, dn (Landau & Lifshitz sec. 37 amplitudes),
    oriented as :func:`tumble.analysis.periods.polhode_solid_angle`. Each case's quadrature once
    a run (a float, cached): test_montgomery_formula_holds_by_its_terms and
    test_solid_angle_against_mpmath_quadrature read the same six (~0.4 s each)."""
    return _solid_angle_quadrature(tuple(map(float, moments)), tuple(map(float, omega)), dps)


@functools.cache
def _solid_angle_quadrature(moments, omega, dps):
    with mp.workdps(dps):
        I1, I2, I3 = (mp.mpf(x) for x in moments)
        w = [abs(mp.mpf(x)) for x in omega]  # the signs do not change the oriented area
        L2 = sum((I * x) ** 2 for I, x in zip((I1, I2, I3), w))
        E2 = sum(I * x * x for I, x in zip((I1, I2, I3), w))
        g1, g2, g3 = L2 - E2 * I1, L2 - E2 * I2, L2 - E2 * I3
        Ln = mp.sqrt(L2)
        a1 = mp.sqrt(-g3 / (I1 * (I3 - I1)))
        a3 = mp.sqrt(g1 / (I3 * (I3 - I1)))
        if g2 > 0:  # about axis 3: w = (a1 cn, a2 sn, a3 dn)
            a2 = mp.sqrt(-g3 / (I2 * (I3 - I2)))
            m = (I2 - I1) * (-g3) / ((I3 - I2) * g1)

            def f(u):
                sn, cn, dn = (mp.ellipfun(k, u, m=m) for k in ("sn", "cn", "dn"))
                La, Lb, Lr = I1 * a1 * cn, I2 * a2 * sn, I3 * a3 * dn
                return (1 - Lr / Ln) * I1 * I2 * a1 * a2 * dn / (La**2 + Lb**2)

            sign = 1
        else:  # about axis 1: w = (a1 dn, a2 sn, a3 cn); azimuth atan2(L3, L2) turns backwards
            a2 = mp.sqrt(g1 / (I2 * (I2 - I1)))
            m = (I3 - I2) * g1 / ((I2 - I1) * (-g3))

            def f(u):
                sn, cn, dn = (mp.ellipfun(k, u, m=m) for k in ("sn", "cn", "dn"))
                La, Lb, Lr = I2 * a2 * sn, I3 * a3 * cn, I1 * a1 * dn
                return (1 - Lr / Ln) * I2 * I3 * a2 * a3 * dn / (La**2 + Lb**2)

            sign = -1
        K = mp.ellipk(m)
        return float(sign * mp.quad(f, [0, K, 2 * K, 3 * K, 4 * K]))


@pytest.mark.parametrize("moments, omega, mode", [c for c in CASES if c[0][0] != c[0][1] and c[0][1] != c[0][2]])
def test_solid_angle_against_mpmath_quadrature(moments, omega, mode):
    Omega = float(P.polhode_solid_angle(omega, moments))
    assert Omega == pytest.approx(_solid_angle_mpmath(moments, omega), abs=1e-12)  # measured: at most 3.1e-14 sr
    assert (Omega > 0) == (mode == "SAM") and abs(Omega) < 2 * np.pi


def test_solid_angle_of_a_symmetric_top_is_a_cap():
    """``2 pi sigma (1 - |cos theta|)``: the polhode of a top is a circle of latitude."""
    for moments, omega, sigma, s in (([2.0, 2.0, 3.0], [0.3, 0.4, 1.0], 1, 2), ([1.0, 3.0, 3.0], [1.0, 0.3, 0.1], -1, 0)):
        L = np.multiply(moments, omega)
        cos = abs(L[s]) / np.linalg.norm(L)
        expected = 2 * np.pi * sigma * (1 - cos)
        assert float(P.polhode_solid_angle(omega, moments)) == pytest.approx(expected, rel=1e-13)


def test_montgomery_formula_holds_by_its_terms():
    """``Delta theta = 2 E T / |L| - Omega (mod 2 pi)`` with Omega from mpmath quadrature."""
    for moments, omega, _ in CASES[:6]:
        I, w = np.array(moments), np.array(omega)
        T = float(P.period(w, I))
        E, Ln = 0.5 * float(np.sum(I * w * w)), float(np.linalg.norm(I * w))
        rhs = (2 * E * T / Ln - _solid_angle_mpmath(moments, omega)) % (2 * np.pi)
        diff = float(P.montgomery_angle(w, I)) - rhs
        assert abs((diff + np.pi) % (2 * np.pi) - np.pi) < 1e-12


def test_rotation_per_period_refuses_a_trajectory_without_the_sample():
    traj = tumble.simulate(body([1.0, 2.0, 3.0]), [0.1, 1.0, 0.3], t_end=5.0, samples=11, method="dop853")
    with pytest.raises(ValueError, match="no sample at t0 \\+ T"):
        P.rotation_per_period(traj)
    with pytest.raises(TypeError, match="Trajectory"):
        P.rotation_per_period(np.zeros(3))


def _azimuth_rate(traj, axis_body):
    """Mean rate of the azimuth of a body axis about L_world over the run (unwrapped), rad/s."""
    z = traj.angular_momentum_world[0] / traj.angular_momentum_norm[0]
    x = np.cross(z, [0.0, 1.0, 0.0])
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    a = traj.attitude.apply(np.asarray(axis_body, float))
    az = np.unwrap(np.arctan2(a @ y, a @ x))
    return (az[-1] - az[0]) / (traj.t[-1] - traj.t[0])


@pytest.mark.parametrize("moments, omega, s", [([2.0, 2.0, 3.0], [0.3, 0.4, 1.0], 2), ([2.0, 5.0, 5.0], [-1.0, 0.3, 0.2], 0),
                                               ([2.0, 2.0, 3.0], [0.3, 0.4, -1.0], 2)])
def test_symmetric_top_rates_against_dop853(moments, omega, s):
    """Precession of the symmetry axis about L and the rate of omega about the symmetry axis in
    the body (Landau & Lifshitz secs. 33, 36), measured on a DOP853 run."""
    precession, body_rate = P.symmetric_top_rates(omega, moments)
    traj = tumble.simulate(body(moments), omega, t_end=20.0, samples=4001, method="dop853")
    axis = np.eye(3)[s]
    # the symmetry axis keeps its angle to L and precesses uniformly: its azimuth rate is exact
    assert _azimuth_rate(traj, axis) == pytest.approx(float(precession), rel=1e-9)  # measured: at most 4.7e-13
    i, j = (s + 1) % 3, (s + 2) % 3  # right-handed about the symmetry axis
    ang = np.unwrap(np.arctan2(traj.omega[:, j], traj.omega[:, i]))
    measured = (ang[-1] - ang[0]) / traj.t[-1]
    assert measured == pytest.approx(float(body_rate), rel=1e-9)
    assert float(body_rate) == pytest.approx((moments[s] - moments[1]) * omega[s] / moments[1], rel=1e-15)


def test_symmetric_top_rates_refuse_an_asymmetric_body():
    with pytest.raises(ValueError, match=r"moments\[1\].*symmetric top"):
        P.symmetric_top_rates([[0.0, 0.0, 1.0]] * 2, [[1.0, 1.0, 2.0], [1.0, 2.0, 3.0]])


@pytest.mark.parametrize("moments, omega, mode", [c for c in CASES if c[0][0] != c[0][1] and c[0][1] != c[0][2]])
def test_npa_periods_closed_form_against_measured(moments, omega, mode):
    P_phi, P_psi, m = P.npa_periods(omega, moments)
    assert str(m) == mode
    traj = tumble.simulate(body(moments), omega, t_end=12.3 * float(P_psi), samples=20001, method="dop853")
    phi_m, psi_m, mode_m = P.npa_periods_measured(traj)
    assert mode_m == mode
    assert psi_m == pytest.approx(float(P_psi), rel=1e-8)  # measured: at most 4.4e-10
    assert phi_m == pytest.approx(float(P_phi), rel=1e-8)  # measured: at most 6.9e-11


def test_npa_mode_is_the_side_of_the_separatrix():
    """SAM where ``L^2 > 2 E I2``, LAM where ``L^2 < 2 E I2`` (computed here from omega and the
    moments directly); ``P_phi`` itself is checked against DOP853 runs above."""
    I = np.array([1.0, 2.0, 3.0])
    for w in ([1.0, 0.5, 0.1], [0.2, 0.3, 1.0], [0.3, -0.9, -0.5], [1.0, 0.3, 0.2]):
        w = np.array(w)
        L2, twoE = np.sum((I * w) ** 2), np.sum(I * w * w)
        assert str(P.npa_periods(w, I)[2]) == ("SAM" if L2 > twoE * I[1] else "LAM")


def test_npa_in_sam_the_long_axis_turns_once_per_period_less():
    """In SAM the long axis's mean precession period is ``1 / (1/P_phi - 1/P_psi)``: measured on a
    DOP853 run from the unwrapped azimuth of axis 1 about L over whole periods."""
    for bad in (0, 4, True, "x", 2.0):
        with pytest.raises(ValueError, match=r"axis = .* must be 1, 2 or 3"):
            P.axis_precession_period(None, bad)
    with pytest.raises(ValueError, match=r"axis = \[1, 3\] must be one axis"):
        P.axis_precession_period(None, [1, 3])
    I, w = [1.0, 2.0, 3.0], [0.2, 0.3, 1.0]
    P_phi, P_psi = (float(v) for v in P.npa_periods(w, I)[:2])
    traj = tumble.simulate(body(I), w, t_end=8.2 * P_psi, samples=20001, method="dop853")
    long_axis = P.axis_precession_period(traj, "minor")
    assert P.axis_precession_period(traj, 3) == pytest.approx(P_phi, rel=1e-8)
    assert long_axis == pytest.approx(1 / (1 / P_phi - 1 / P_psi), rel=1e-8)
