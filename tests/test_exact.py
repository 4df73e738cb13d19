"""The exact torque-free motion: against DOP853, arbitrary precision, and its invariants."""

from __future__ import annotations

import itertools

import mpmath as mp
import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from scipy.special import ellipj
from scipy.special import ellipk as scipy_ellipk

import tumble
from tumble.analysis import flip_interval, flip_interval_asymptotic, linearised_rate
from tumble.dynamics import simulate
from tumble.dynamics.methods.exact import FreeRotation
from tumble.dynamics.special.elliptic import carlson_pi, ellipk, jacobi, jacobi_reduced
from tumble.mass import MassProperties


def free_body(moments):
    return MassProperties.from_moments(moments)


# -- the elliptic functions ------------------------------------------------------------------

@pytest.mark.parametrize("m1", [0.9, 0.5, 0.3, 1e-3, 1e-9, 1e-15, 1e-22, 1e-40, 1e-100, 1e-300])
def test_jacobi_functions_against_mpmath(m1):
    """sn, cn, dn to a few ulps *relative*, for 1 - m from 1 down to 1e-300: also at
    ``|u - j K| = K/2`` (where cn ~ m1^(1/4), and the descending Landen recursion of m would
    lose relative accuracy as m1^(-1/2); the imaginary transformation keeps it), near the zeros
    of cn and dn (``u = K + 0.01``), and at large arguments (the reduction is exact). The bound
    is the conditioning of the functions themselves, |d ln f / du| eps |u| <= ~eps K."""
    mp.mp.dps = 40 - int(np.log10(m1))
    m = 1.0 - m1
    M = mp.mpf(1) - mp.mpf(m1)
    K = float(mp.ellipk(M))
    u = np.array([0.1, 0.5 * K, 0.49 * K, 0.97 * K, K + 0.01, 1.5 * K, 1.9 * K, 3.3 * K, -2.2 * K, -2.5 * K,
                  41.0, 1e5, -3e7])
    sn, cn, dn = jacobi(u, m, m1)
    for k, ours in zip(("sn", "cn", "dn"), (sn, cn, dn)):
        ref = np.array([float(mp.ellipfun(k, mp.mpf(x), m=M)) for x in u])
        np.testing.assert_allclose(ours, ref, rtol=2e-14, atol=0)
    assert ellipk(m, m1) == pytest.approx(K, rel=1e-15)


def test_scipy_ellipj_fails_where_ours_holds():
    """Why tumble evaluates Jacobi functions itself: scipy's loses 1 - m near the separatrix."""
    m1 = 1e-15
    u = np.array([40.0, -17.0])
    mp.mp.dps = 40
    ref = np.array([float(mp.ellipfun("cn", mp.mpf(x), m=mp.mpf(1) - mp.mpf(m1))) for x in u])
    assert np.max(np.abs(ellipj(u, 1.0 - m1)[1] - ref)) > 1e-6
    assert np.max(np.abs(jacobi(u, 1.0 - m1, m1)[1] - ref)) < 1e-14


def test_incomplete_pi_against_mpmath():
    mp.mp.dps = 30
    for m1, n in [(0.5, -0.7), (1e-8, -2.5), (1e-14, -0.1)]:
        m = 1 - m1
        M = mp.mpf(1) - mp.mpf(m1)
        K = float(mp.ellipk(M))
        for u in (0.3, 0.8 * K, 0.999 * K, -0.6 * K):
            _, s, c, d = jacobi_reduced(np.array([u]), m, m1)
            phi = mp.asin(mp.ellipfun("sn", mp.mpf(u), m=M))
            ref = float(mp.ellippi(mp.mpf(n), phi, M))
            # the reduction u - K is exact (double-double), so near u = K too: a few ulps
            assert carlson_pi(n, s, c, d)[0] == pytest.approx(ref, rel=2e-15)
    assert scipy_ellipk(0.5) == pytest.approx(ellipk(0.5, 0.5), rel=1e-15)


# -- against DOP853 ----------------------------------------------------------------------------

CASES = [
    ((0.125, 0.3125, 0.4375), (0.1, 10.0, 0.1)),   # seed handle, intermediate axis (L^2 > 2 E I2)
    ((0.125, 0.3125, 0.4375), (0.3, -2.0, 1e-3)),  # L^2 < 2 E I2
    ((0.125, 0.3125, 0.4375), (10.0, 0.1, 0.1)),   # near the minor axis
    ((0.125, 0.3125, 0.4375), (0.1, 0.1, -10.0)),  # near the major axis, negative spin
    ((3.0, 4.0, 6.0), (2.0, 1.0, 1.0)),            # exactly on the separatrix (g2 = 0)
    ((3.0, 4.0, 6.0), (2.0, -1.0, -1.0)),          # the separatrix branch with w1 w3 < 0
    ((1.0, 1.0, 1.5), (0.3, 0.4, 2.0)),            # oblate symmetric top
    ((1.0, 1.5, 1.5), (2.0, 0.4, -0.3)),           # prolate symmetric top
    ((1.0, 1.0, 1.0), (1.0, 2.0, 3.0)),            # sphere
    ((1.0, 2.0, 2.5), (0.0, 1.0, 0.0)),            # steady spin about the intermediate axis
    ((1.0, 2.0, 2.5), (0.0, 0.0, 3.0)),            # steady spin about the major axis
]


@pytest.mark.parametrize(("moments", "w0"), CASES)
def test_exact_matches_tight_dop853(moments, w0):
    body = free_body(moments)
    att0 = Rotation.from_rotvec([0.4, -0.3, 1.2])
    ex = simulate(body, w0, t_end=10.0, samples=200, attitude0=att0)
    ref = simulate(body, w0, t_end=10.0, samples=200, attitude0=att0, method="dop853", rtol=1e-13)
    assert ex.method == "exact"
    scale = np.max(np.abs(ref.omega))
    np.testing.assert_allclose(ex.omega, ref.omega, atol=1e-9 * scale, rtol=0)
    assert np.max((ex.attitude * ref.attitude.inv()).magnitude()) < 1e-9


@pytest.mark.parametrize("order", list(itertools.permutations(range(3))))
def test_all_six_orderings_of_the_design_axes(order):
    """Sorting the design axes by moment can reverse handedness: the world-frame motion of a
    box must not depend on which design axis carries which moment."""
    P = np.eye(3)[list(order)]  # design coordinates of this box = P @ those of the base box
    size = P @ np.array([0.1, 0.25, 0.4])
    body = tumble.Body([tumble.Box(mass=2.0, size=tuple(size))])
    # omega is a pseudovector: under a relabelling of odd parity it also changes sign
    w_base = np.array([0.2, 3.0, -0.4])
    w_design = np.linalg.det(P) * P @ w_base
    ex = simulate(body, w_design, frame="design", t_end=6.0, samples=120)
    ref = simulate(body, w_design, frame="design", t_end=6.0, samples=120, method="dop853", rtol=1e-13)
    assert np.max((ex.design_attitude() * ref.design_attitude().inv()).magnitude()) < 1e-9
    np.testing.assert_allclose(ex.omega_world, ref.omega_world, atol=1e-9 * 3.0)
    # the same physical motion whatever the labelling
    base = tumble.Body([tumble.Box(mass=2.0, size=(0.1, 0.25, 0.4))])
    b = simulate(base, w_base, frame="design", t_end=6.0, samples=120)
    np.testing.assert_allclose(ex.omega_world, np.linalg.det(P) * b.omega_world @ P.T, atol=1e-11)


# -- against arbitrary precision, near the separatrix ------------------------------------------

def _mp_reference(moments, w0, times, dps=30):
    """Taylor-series integration of Euler's equations + quaternion kinematics at ``dps`` digits.

    The settings are mpmath.odefun's (degree ``3 + 3 dps / 2``, each series' tail below
    ``2^-(prec + 10)``, carried at ``prec + 40`` bits, a step half the radius estimated from its last
    coefficients); the coefficients are the exact ones, by Cauchy products of the quadratic right-hand
    side, where odefun takes them from finite differences at ``(degree + 1) prec`` bits: 6-50x less
    time for the same digits. On the four cases below (test_exact_near_the_separatrix_against_mpmath,
    test_exact_hardening's 34-digit ones) the floats returned were odefun's to the last bit;
    test_the_taylor_reference_is_mpmaths_odefun keeps one short case of it."""
    mp.mp.dps = dps
    prec = mp.mp.prec
    degree = 3 + int(3 * dps / 2.0)
    with mp.workprec(prec + 40):
        tol = mp.ldexp(1, -(prec + 10))
        I1, I2, I3 = (mp.mpf(x) for x in moments)
        a1, a2, a3 = (I2 - I3) / I1, (I3 - I1) / I2, (I1 - I2) / I3
        half = mp.mpf(1) / 2
        y = [mp.mpf(x) for x in w0] + [mp.mpf(0)] * 3 + [mp.mpf(1)]  # omega, then q = (v, s)
        t = mp.mpf(0)
        out = []
        for target in times:
            target = mp.mpf(target)
            while t < target:
                c = [[x] for x in y]  # c[d][k]: the k-th Taylor coefficient of component d at t

                def prod(i, j, k):  # the k-th coefficient of y_i y_j
                    return mp.fdot(c[i][: k + 1], c[j][k::-1])

                for k in range(degree):
                    p = [[prod(i, j, k) for j in range(3)] for i in (3, 4, 5, 6)]  # v_i w_j, s w_j
                    f = [a1 * prod(1, 2, k), a2 * prod(2, 0, k), a3 * prod(0, 1, k),  # Euler
                         (p[3][0] + p[1][2] - p[2][1]) * half,  # dv/dt = (s w + v x w) / 2
                         (p[3][1] + p[2][0] - p[0][2]) * half,
                         (p[3][2] + p[0][1] - p[1][0]) * half,
                         -(p[0][0] + p[1][1] + p[2][2]) * half]  # ds/dt = -(v . w) / 2
                    for d in range(7):
                        c[d].append(f[d] / (k + 1))
                h = target - t
                for cd in c:
                    for k in (degree - 1, degree):
                        if cd[k]:
                            h = min(h, mp.root(tol / abs(cd[k]), k) / 2)
                y = [mp.polyval(cd, h, asc=True) for cd in c]
                t += h
            out.append([float(x) for x in y])
    return np.array(out)


def test_the_taylor_reference_is_mpmaths_odefun():
    """The reference above against mpmath's own Taylor-series integrator (a short run: odefun takes
    ~20x as long), to the last bit of the floats returned."""
    moments, w0, times = (0.125, 0.3125, 0.4375), (2e-6, 10.0, 1e-7), [0.05, 0.3]
    mp.mp.dps = 30
    I = [mp.mpf(x) for x in moments]

    def rhs(t, y):
        w, (v1, v2, v3, s) = y[:3], y[3:]
        dw = [(I[1] - I[2]) * w[1] * w[2] / I[0], (I[2] - I[0]) * w[2] * w[0] / I[1], (I[0] - I[1]) * w[0] * w[1] / I[2]]
        cr = [v2 * w[2] - v3 * w[1], v3 * w[0] - v1 * w[2], v1 * w[1] - v2 * w[0]]
        dv = [(s * w[i] + cr[i]) / 2 for i in range(3)]
        return dw + dv + [-(v1 * w[0] + v2 * w[1] + v3 * w[2]) / 2]

    sol = mp.odefun(rhs, 0, [mp.mpf(x) for x in w0] + [0, 0, 0, 1])
    odefun = np.array([[float(x) for x in sol(mp.mpf(t))] for t in times])
    np.testing.assert_array_equal(_mp_reference(moments, w0, times), odefun)


@pytest.mark.parametrize(
    "w0",
    [
        (1e-6, 10.0, 1e-6),    # 1 - k^2 ~ 1e-14, circulating about the major axis
        (2e-6, 10.0, 1e-7),    # ... about the minor axis
    ],
)
def test_exact_near_the_separatrix_against_mpmath(w0):
    """DOP853 at rtol 1e-13 is good to ~1e-9 here; the exact solution to 1e-10 or better."""
    moments = (0.125, 0.3125, 0.4375)
    times = [0.7, 1.9, 3.1]
    ref = _mp_reference(moments, w0, times)
    motion = FreeRotation(np.array(moments), np.array(w0), Rotation.identity())
    assert motion.m1 < 1e-12
    w = motion.omega(times)
    q = motion.attitude(times).as_quat()
    q *= np.sign(np.sum(q * ref[:, 3:], axis=1))[:, None]
    np.testing.assert_allclose(w, ref[:, :3], atol=1e-10 * 10.0, rtol=0)
    np.testing.assert_allclose(q, ref[:, 3:], atol=1e-10, rtol=0)


def test_L_world_constant_over_ten_thousand_periods():
    body = tumble.iss_t_handle()
    w0 = [0.5, 10.0, -0.3]
    T = 2 * flip_interval(w0, body.principal_moments)
    traj = simulate(body, w0, t_end=float(1e4 * T), samples=20001)
    assert traj.drift["L_world"] < 1e-13
    assert traj.drift["energy"] < 1e-13 and traj.drift["L_norm"] < 1e-13


# -- flip period ---------------------------------------------------------------------------

def test_flip_interval_asymptotic_converges():
    I = np.array([0.125, 0.3125, 0.4375])
    lam, _ = linearised_rate(I, 2, 10.0)
    errors = []
    for eps in (1e-2, 1e-4, 1e-6):
        w = [eps, 10.0, eps]
        exact, approx = flip_interval(w, I), flip_interval_asymptotic(w, I)
        errors.append(abs(approx / exact - 1))
    assert errors[0] > errors[1] > errors[2]  # O(1 - k^2) = O(eps^2)
    assert errors[2] < 1e-9
    # and its leading behaviour is logarithmic: (2 / lambda) ln(1 / eps)
    d = flip_interval_asymptotic([1e-8, 10.0, 1e-8], I) - flip_interval_asymptotic([1e-6, 10.0, 1e-6], I)
    assert d == pytest.approx(2 * np.log(100) / lam, rel=1e-6)


def test_a_modulus_per_body_gives_each_body_the_values_of_its_own_modulus():
    """The batch's Modulus (one k, k', K per body: both sides of m = 1/2, different numbers of
    Landen steps, the separatrix) reduces each row exactly as that body's own Modulus does."""
    from tumble.dynamics.special.elliptic import Modulus

    params = [(0.3, 0.7), (0.9, 0.1), (1.0 - 1e-12, 1e-12), (1e-20, 1.0), (0.5, 0.5), (1.0, 0.0)]
    ones = [Modulus.from_parameter(m, m1) for m, m1 in params]
    rng = np.random.default_rng(4)
    u = rng.uniform(-50.0, 50.0, (len(params), 40)), rng.uniform(-1e-16, 1e-16, (len(params), 40))
    batch = Modulus(np.array([x.k for x in ones]), np.array([x.kp for x in ones]),
                    (np.array([x.K[0] for x in ones]), np.array([x.K[1] for x in ones])))
    (j1, j2), odd, sn, cn, dn = batch.reduce(u)
    for i, one in enumerate(ones):
        (a1, a2), o, s, c, d = one.reduce((u[0][i], u[1][i]))
        for x, y in ((j1, a1), (j2, a2), (odd, o), (sn, s), (cn, c), (dn, d)):
            np.testing.assert_array_equal(x[i], y)
    assert np.all(j1[-1] == 0) and np.allclose(sn[-1], np.tanh(u[0][-1]))  # the separatrix: no period


def test_one_body_and_the_batch_run_one_kernel():
    """FreeRotation (parameters through floats) and free_rotation_batch at N = 1 (through arrays
    when in a chunk with others) give one body the same motion to a few ulps, and a lone body
    bit for bit."""
    from tumble.dynamics.methods.exact_batch import free_rotation_batch

    I = np.array([[1.0, 2.0, 3.0], [0.4, 2.0, 2.1], [1.0, 2.0, 3.0]])
    w = np.array([[0.1, 1.0, 0.1], [1.0, 0.2, -0.3], [3.0, 1.0, -3.0]])  # the last on the separatrix
    q = Rotation.random(3, random_state=1).as_quat()
    t = np.linspace(0.0, 40.0, 81)
    omega, quat = free_rotation_batch(I, w, q, t)
    for i in range(3):
        one = FreeRotation(I[i], w[i], Rotation.from_quat(q[i]))
        lone = free_rotation_batch(I[i:i + 1], w[i:i + 1], one.attitude0.as_quat()[None, :], t)
        np.testing.assert_array_equal(lone[0][0], one.omega(t))
        # (Rotation normalises the kernel's quaternions: compared through it)
        np.testing.assert_array_equal(Rotation.from_quat(lone[1][0]).as_quat(), one.attitude(t).as_quat())
        np.testing.assert_allclose(omega[i], one.omega(t), rtol=0, atol=4e-16 * np.max(np.abs(omega[i])))
        assert np.max((Rotation.from_quat(quat[i]).inv() * one.attitude(t)).magnitude()) <= 1e-14


@pytest.mark.parametrize("omega0", [(0.05, 6.0, 0.05), (0.1, 1.0, 0.1), (0.3, -0.2, 0.1), (2.0, 0.0, 6.0), (0.0, 3.0, 0.0)])
def test_the_first_sample_is_the_start_as_given(omega0):
    """The closed form at t = 0 gave 6.000000000000001 for a given 6.0, which a scenario's summary.json then wrote
    as its omega0 (a walkthrough). The start is the initial state, bit for bit; a moment later the closed form's."""
    attitude0 = Rotation.from_rotvec([0.3, -1.0, 2.5])
    traj = simulate(MassProperties.from_moments((1.0, 2.0, 3.0)), omega0, t_end=3.0, method="exact", attitude0=attitude0)
    assert traj.omega[0].tolist() == list(omega0)
    assert traj.quat[0].tolist() == attitude0.as_quat().tolist()
    motion = FreeRotation(np.array([1.0, 2.0, 3.0]), np.array(omega0), attitude0)
    np.testing.assert_allclose(traj.omega[1], motion.omega(traj.t[1]), rtol=0, atol=1e-15 * np.linalg.norm(omega0))
