"""The exact torque-free motion at its edges: degenerate bodies, underflow, near-separatrix
accuracy, huge phases. Each case against an independent reference (DOP853 at rtol 1e-12, or
arbitrary-precision mpmath) and the invariants of the motion."""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

import tumble
from tumble.dynamics import simulate
from tumble.dynamics.special.carlson import legendre_f, legendre_pi_excess
from tumble.dynamics.special.elliptic import carlson_pi, ellipk_kp, jacobi
from tumble.dynamics.methods.exact import FreeRotation, check_phase_limit, elliptic_parameters
from tumble.mass import MassProperties, principal_frame

from test_exact import _mp_reference  # Taylor-series integration at arbitrary precision

SETTINGS = settings(max_examples=25, deadline=None, derandomize=True)


def _rotation(q) -> Rotation:
    return Rotation.from_quat(np.asarray(q) / np.linalg.norm(q))


quaternions = st.tuples(*[st.floats(-1.0, 1.0)] * 4).filter(lambda q: np.linalg.norm(q) > 0.1)
# components of ordinary size or exactly zero (tiny ones are the underflow tests' business)
components = st.floats(-1.0, 1.0).map(lambda x: x if abs(x) > 1e-6 else 0.0)
directions = st.tuples(*[components] * 3).filter(lambda v: np.linalg.norm(v) > 0.1)
sizes = st.floats(1e-3, 1e3)
speeds = st.floats(0.3, 3.0)


def _body(moments, q) -> MassProperties:
    """A body whose design-frame tensor is ``R diag(moments) R^T`` (round-off included)."""
    R = _rotation(q).as_matrix()
    return MassProperties.from_inertia(1.0, np.zeros(3), R @ np.diag(moments) @ R.T)


def _check_against_dop853(body, w0, frame="design", t_end=5.0):
    """Exact against DOP853 (rtol 1e-12), and the exact motion's invariants to ~1e-12."""
    att0 = Rotation.from_rotvec([0.4, -0.3, 1.2])
    ex = simulate(body, w0, frame=frame, t_end=t_end, samples=101, attitude0=att0)
    ref = simulate(body, w0, frame=frame, t_end=t_end, samples=101, attitude0=att0, method="dop853")
    assert ex.method == "exact"
    scale = np.max(np.abs(ref.omega))
    np.testing.assert_allclose(ex.omega, ref.omega, atol=1e-9 * scale, rtol=0)
    assert np.max((ex.attitude * ref.attitude.inv()).magnitude()) < 1e-9
    for name, value in ex.drift.items():
        assert value is None or value < 1e-12, (name, value)  # None: nothing to drift (at rest)


# -- 2b: spheres, symmetric tops, nearly symmetric bodies ------------------------------------

def test_the_audited_sphere_simulates():
    body = MassProperties.from_inertia(1.0, [0, 0, 0], 0.0794 * np.eye(3))
    _check_against_dop853(body, [2.12, -1.84, -0.83], frame="principal", t_end=10.0)


@SETTINGS
@given(sizes, quaternions, directions, speeds)
def test_random_spheres(size, q, direction, speed):
    body = _body([size] * 3, q)
    assert body.principal_moments[0] == body.principal_moments[2]  # declared spherical, exactly
    w0 = speed * np.asarray(direction) / np.linalg.norm(direction)
    _check_against_dop853(body, w0)


@SETTINGS
@given(sizes, st.sampled_from([0.55, 0.8, 0.95, 1.05, 1.4, 1.9]), quaternions, directions, speeds,
       st.sampled_from(["random", "along", "perpendicular"]))
def test_random_symmetric_tops(size, ratio, q, direction, speed, kind):
    """Oblate (ratio > 1: the odd moment is the largest) and prolate tops, omega random, along
    the symmetry axis or perpendicular to it (in the design frame, so to round-off only)."""
    body = _body([size, size, ratio * size], q)
    I = body.principal_moments
    axis_index = 2 if ratio > 1 else 0
    assert I[1] == I[2 - axis_index]  # declared symmetric, exactly
    axis = body.principal_axes[:, axis_index]
    d = np.asarray(direction) / np.linalg.norm(direction)
    if kind == "along":
        d = axis
    elif kind == "perpendicular":
        d = np.cross(axis, d)
        d /= np.linalg.norm(d)
    _check_against_dop853(body, speed * d)


@SETTINGS
@given(sizes, st.floats(-12.0, -6.0), st.booleans(), quaternions, directions, speeds,
       st.sampled_from(["random", "perpendicular"]))
def test_nearly_symmetric_bodies(size, log_gap, oblate, q, direction, speed, kind):
    """Relative gaps of 1e-12..1e-6: below and above the degeneracy tolerance 1e-9 * trace."""
    gap = 10.0**log_gap
    moments = [size, size * (1 + gap), 1.5 * size] if oblate else [0.6 * size, size, size * (1 + gap)]
    body = _body(moments, q)
    I = body.principal_moments
    pair = (0, 1) if oblate else (1, 2)
    declared = I[pair[0]] == I[pair[1]]
    assert declared == (I[pair[1]] - I[pair[0]] <= 1e-9 * np.sum(I))
    d = np.asarray(direction) / np.linalg.norm(direction)
    if kind == "perpendicular":
        d = np.cross(body.principal_axes[:, 2 if oblate else 0], d)
        d /= np.linalg.norm(d)
    _check_against_dop853(body, speed * d)


@pytest.mark.parametrize(
    ("moments", "w0"),
    [
        ((1.0, 1.0, 1.5), (0.3, -0.4, 0.0)),   # oblate top spinning in its degenerate plane
        ((1.0, 1.5, 1.5), (0.0, 0.3, -0.4)),   # prolate top, the same
        ((1.0, 1.0, 1.5), (0.0, 0.0, 2.0)),    # along the symmetry axis, exactly
        ((1.0, 1.5, 1.5), (-2.0, 0.0, 0.0)),
        ((1.0, 2.0, 2.5), (0.0, 0.0, 0.0)),    # at rest
    ],
)
def test_steady_cases_decided_exactly(moments, w0):
    motion = FreeRotation(np.array(moments), np.array(w0), Rotation.identity())
    assert motion.steady
    _check_against_dop853(MassProperties.from_moments(moments), w0, frame="principal")


def test_principal_frame_returns_degenerate_moments_equal():
    R = Rotation.from_rotvec([0.3, -1.1, 0.7]).as_matrix()
    for moments, equal in [([2.0, 2.0, 2.0], (0, 1, 2)), ([1.0, 1.0, 1.7], (0, 1)), ([1.0, 1.7, 1.7], (1, 2))]:
        I, _ = principal_frame(R @ np.diag(moments) @ R.T)
        assert len({float(I[k]) for k in equal}) == 1
        np.testing.assert_allclose(I, sorted(moments), rtol=1e-15)
    # batched, with the cluster's mean
    I, _ = principal_frame(np.stack([np.diag([1.0, 1.0 + 1e-12, 3.0]), np.diag([1.0, 2.0, 3.0])]))
    assert I[0, 0] == I[0, 1] == 0.5 * (1.0 + (1.0 + 1e-12)) and I[1].tolist() == [1.0, 2.0, 3.0]


# -- 2: underflow (components 1e-300 .. 1e-160, 1 - m below the smallest double) -------------

def _mp_closed_form(moments, w0, times, dps):
    """omega(t) of Landau & Lifshitz sec. 37 evaluated by mpmath alone (its ``ellipf`` and
    ``ellipfun``) with the parameters formed exactly at ``dps`` digits, the half period
    ``2 K / p``, the first time at which ``w2`` changes sign (s) and ``p`` (1/s). Not on the
    separatrix."""
    mp.mp.dps = dps
    I = [mp.mpf(x) for x in moments]
    w = [mp.mpf(x) for x in w0]
    I1, I2, I3 = I
    g1, g2, g3 = (sum(I[i] * (I[i] - I[j]) * w[i] ** 2 for i in range(3)) for j in range(3))
    if g2 >= 0:  # circulating about axis 3
        r, c = 2, 0
        p = mp.sqrt((I3 - I2) * g1 / (I1 * I2 * I3))
        m = (I2 - I1) * -g3 / ((I3 - I2) * g1)
        a2 = mp.sqrt(-g3 / (I2 * (I3 - I2)))
    else:
        r, c = 0, 2
        p = mp.sqrt((I2 - I1) * -g3 / (I1 * I2 * I3))
        m = (I3 - I2) * g1 / ((I2 - I1) * -g3)
        a2 = mp.sqrt(g1 / (I2 * (I2 - I1)))
    a = [mp.sqrt(-g3 / (I1 * (I3 - I1))), a2, mp.sqrt(g1 / (I3 * (I3 - I1)))]
    s = 1 if w[r] >= 0 else -1
    u0 = mp.ellipf(mp.atan2(w[1] / a[1], w[c] / (s * a[c])), m)
    rows = []
    for t in times:
        u = u0 + p * mp.mpf(t)
        sn, cn, dn = (mp.ellipfun(k, u, m=m) for k in ("sn", "cn", "dn"))
        row = [0, 0, 0]
        row[c], row[1], row[r] = s * a[c] * cn, a[1] * sn, s * a[r] * dn
        rows.append([float(x) for x in row])
    twoK = 2 * mp.ellipk(m)
    first_flip = (twoK * mp.floor(u0 / twoK + 1) - u0) / p
    return np.array(rows), float(twoK / p), float(first_flip), float(p)


UNDERFLOW_BODIES = {
    "t_handle": (0.125, 0.3125, 0.4375),
    "box": (1.0, 2.0, 2.5),
    "flat": (0.3, 2.0, 2.2),
}
UNDERFLOW_OMEGAS = [(0.0, 1.0, 1e-160), (1e-200, 1.0, 0.0), (1e-170, 1.0, 1e-170), (0.0, -2.0, -1e-300)]


def _digits(w0) -> int:
    return 40 + 2 * int(-np.log10(min(abs(x) for x in w0 if x)))


@pytest.mark.parametrize("name", list(UNDERFLOW_BODIES))
@pytest.mark.parametrize("w0", UNDERFLOW_OMEGAS)
def test_underflow_spin_flips_as_dop853_says(name, w0):
    """A steady spin for ~ln(4 / k') / lambda seconds, then a flip: through the first flip
    DOP853 (rtol 1e-12) is a reference; not much further, as its energy error (~1e-12) puts it
    on an orbit with k' ~ 1e-6, which leaves the next saddle a thousand seconds early."""
    moments = UNDERFLOW_BODIES[name]
    body = MassProperties.from_moments(moments)
    _, half, first, p = _mp_closed_form(moments, w0, [], _digits(w0))
    assert half > 800.0  # k' ~ 1e-160 and below: a long stay near the saddle
    t_end = first + 20.0 / p
    ex = simulate(body, w0, t_end=t_end, samples=300)
    ref = simulate(body, w0, t_end=t_end, samples=300, method="dop853")
    assert np.count_nonzero(np.diff(np.sign(ex.omega[:, 1]))) == 1  # it flipped, once
    np.testing.assert_allclose(ex.omega, ref.omega, atol=1e-6 * max(abs(x) for x in w0), rtol=0)
    assert np.max((ex.attitude * ref.attitude.inv()).magnitude()) < 1e-6
    assert max(ex.drift.values()) < 1e-13


@pytest.mark.parametrize("w0", UNDERFLOW_OMEGAS)
def test_underflow_against_mpmath_over_two_periods(w0):
    """Every component to 1e-12 relative (where it is a normal double) against mpmath's own
    elliptic functions with exact parameters, across two full periods and four flips."""
    moments = UNDERFLOW_BODIES["t_handle"]
    _, half, _, _ = _mp_closed_form(moments, w0, [], _digits(w0))
    times = np.linspace(0.0, 4.4 * half, 23)
    ref, _, _, _ = _mp_closed_form(moments, w0, times, _digits(w0))
    w = FreeRotation(np.array(moments), np.array(w0), Rotation.identity()).omega(times)
    normal = np.abs(ref) > 1e-290
    np.testing.assert_allclose(w[normal], ref[normal], rtol=1e-12, atol=0)
    np.testing.assert_allclose(w[~normal], ref[~normal], rtol=0, atol=1e-300)
    flips = np.count_nonzero(np.diff(np.sign(w[:, 1])))
    assert flips == np.count_nonzero(np.diff(np.sign(ref[:, 1]))) >= 4


@pytest.mark.parametrize(("kp", "c"), [(1e-170, 1e-170), (1e-160, 3e-161), (1e-300, 2e-300), (1e-20, 1e-150)])
def test_integrals_where_squares_underflow(kp, c):
    """F and Pi - F near phi = pi/2 with cos phi and Delta both below 1e-150 (their squares,
    Carlson's arguments, underflow), against mpmath."""
    mp.mp.dps = 900
    KP, C = mp.mpf(kp), mp.mpf(c)
    M = 1 - KP**2
    S = mp.sqrt(1 - C**2)
    D = mp.sqrt(C**2 + KP**2 * S**2)
    phi, n = mp.acos(C), -5.25
    f = legendre_f(float(S), float(C), float(D))
    excess = legendre_pi_excess(n, float(S), float(C), float(D), m=1.0)
    ref_f, ref_pi = mp.ellipf(phi, M), mp.ellippi(n, phi, M)
    assert float(f) == pytest.approx(float(ref_f), rel=1e-14)
    assert float(excess) == pytest.approx(float(ref_pi - ref_f), rel=1e-14)
    assert float(carlson_pi(n, float(S), float(C), float(D))) == pytest.approx(float(ref_pi), rel=1e-14)


def test_quarter_period_from_the_complementary_modulus():
    """``K`` from ``k'`` where ``1 - m = k'^2`` is below the smallest double (for callers of
    EllipticParameters.kp, e.g. the flip interval), against mpmath."""
    kp = np.array([1.0, 0.7, 1e-3, 1e-20, 1e-100, 1e-200, 1e-300, 5e-324])
    mp.mp.dps = 900
    ref = [float(mp.ellipk(1 - mp.mpf(x) ** 2)) for x in kp]
    np.testing.assert_allclose(ellipk_kp(kp), ref, rtol=5e-16)
    assert ellipk_kp(0.0) == np.inf
    e = elliptic_parameters([1e-200, 1.0, 0.0], UNDERFLOW_BODIES["t_handle"])
    assert e.m1 == 0.0 and e.kp == pytest.approx(1e-200, rel=1e-15)  # sqrt(1 - m), formed directly


tiny = st.builds(lambda e, s: s * 10.0**-e, st.floats(20.0, 310.0), st.sampled_from([-1.0, 1.0]))


@SETTINGS
@given(st.sampled_from(list(UNDERFLOW_BODIES.values())), st.permutations([0, 1, 2]), tiny, tiny | st.just(0.0),
       st.floats(0.2, 3.0))
def test_tiny_components_any_body(moments, order, a, b, big):
    """One ordinary component and two tiny (or zero) ones, in any order: the motion is right
    (DOP853 over a short run) and keeps its invariants."""
    w0 = np.zeros(3)
    w0[order[0]], w0[order[1]], w0[order[2]] = big, a, b
    body = MassProperties.from_moments(moments)
    _check_against_dop853(body, w0, frame="principal", t_end=5.0)


# -- 1: accuracy near the intermediate axis, 1 - m -> 0 ---------------------------------------

@pytest.mark.parametrize(("eps", "times"), [(1e-12, [5.0, 26.03, 40.0]), (1e-14, [29.9, 40.0])])
def test_near_the_intermediate_axis_against_34_digit_integration(eps, times):
    """I = (1, 2, 3), omega0 = (e, 1, e): 1 - m ~ 2 e^2. Against a Taylor-series integration of
    Euler's equations and the quaternion kinematics at 34 digits: every omega component to
    1e-12 *relative* (the small ones too, ~1e-7 at these times) and the attitude to 1e-12 rad.
    The audit found 1.3e-3 and 7.8e-4 rad here: at |u - j K| ~ K/2 the Landen recursion of m
    left cn with a relative error ~1e-16 / sqrt(1 - m)."""
    moments, w0 = (1.0, 2.0, 3.0), (eps, 1.0, eps)
    ref = _mp_reference(moments, w0, times, dps=34)
    motion = FreeRotation(np.array(moments), np.array(w0), Rotation.identity())
    w = motion.omega(times)
    np.testing.assert_allclose(w, ref[:, :3], rtol=1e-12, atol=0)
    err = (motion.attitude(times) * Rotation.from_quat(ref[:, 3:]).inv()).magnitude()
    assert np.max(err) < 1e-12


# -- 3: huge phases ---------------------------------------------------------------------------

@pytest.mark.parametrize("m1", [0.5, 1e-3, 1e-12, 1e-200])
def test_jacobi_functions_stay_on_their_curves_at_any_argument(m1):
    m = 1.0 - m1
    u = np.array([1e15, -1e17, 3.3e20, 1e25, 7e40, 1e100, -1e300, 1.7e308])
    sn, cn, dn = jacobi(u, m, m1)
    np.testing.assert_allclose(sn**2 + cn**2, 1.0, rtol=0, atol=5e-16)
    np.testing.assert_allclose(dn**2 + m * sn**2, 1.0, rtol=0, atol=5e-16)
    assert np.all(dn > 0)
    # and where the phase is still kept (~1e-32 |u|), the values themselves, against mpmath
    mp.mp.dps = 60 - int(np.log10(m1))
    M = mp.mpf(1) - mp.mpf(m1)
    for x, s, c, d in zip(u[:3], sn, cn, dn):
        ref = [float(mp.ellipfun(k, mp.mpf(x), m=M)) for k in ("sn", "cn", "dn")]
        np.testing.assert_allclose([s, c, d], ref, rtol=0, atol=1e-14 + 3e-32 * abs(x))


@pytest.mark.parametrize(("w0", "t_end"), [((1e8, 1e7, 1e7), 1e9), ((1e5, 1.0, 1.0), 1e12)])
def test_invariants_hold_at_huge_phases(w0, t_end):
    """The audit's cases: energy drift 1.9 and 2e-8, with no error, before the reduction was
    exact; now the motion stays on its energy surface whatever the phase (~6.6e16 here)."""
    traj = simulate(tumble.t_handle(), w0, t_end=t_end, samples=2001)
    for name, value in traj.drift.items():
        assert value < 1e-13, (name, value)


def _mp_period(moments, w0, dps):
    """The period ``T = 4 K / p`` of omega and the precession ``dphi`` about L over one period
    (``rate0 T + (rate1 / p) 4 Pi(n | m)``, Landau & Lifshitz sec. 37), by mpmath alone."""
    mp.mp.dps = dps
    I = [mp.mpf(x) for x in moments]
    w = [mp.mpf(x) for x in w0]
    I1, I2, I3 = I
    g1, g2, g3 = (sum(I[i] * (I[i] - I[j]) * w[i] ** 2 for i in range(3)) for j in range(3))
    if g2 >= 0:
        r, o = 2, 0
        p, m = mp.sqrt((I3 - I2) * g1 / (I1 * I2 * I3)), (I2 - I1) * -g3 / ((I3 - I2) * g1)
    else:
        r, o = 0, 2
        p, m = mp.sqrt((I2 - I1) * -g3 / (I1 * I2 * I3)), (I3 - I2) * g1 / ((I2 - I1) * -g3)
    n = -I[r] * (I2 - I[o]) / (I[o] * (I[r] - I2))
    L = mp.sqrt(sum((I[i] * w[i]) ** 2 for i in range(3)))
    T = 4 * mp.ellipk(m) / p
    return T, L / I[r] * T + L * (I[r] - I[o]) / (I1 * I3) / p * 4 * mp.ellippi(n, m)


@pytest.mark.parametrize(
    ("moments", "w0", "t", "dps"),
    [
        ((0.125, 0.3125, 0.4375), (1e8, 1e7, 1e7), 1e9 + 0.123, 60),     # phase 6.6e16
        ((0.125, 0.3125, 0.4375), (1e5, 1.0, 1.0), 1e12, 60),            # phase 6.6e16
        ((0.125, 0.3125, 0.4375), (0.1, 10.0, 0.1), 1e12, 60),           # near the separatrix
        ((0.125, 0.3125, 0.4375), (3.0, 1.0, 1e-3), 1e11, 60),           # about the minor axis
        ((1.0, 1.0, 1.5), (0.3, 0.4, 2.0), 1e12, 60),                    # symmetric tops
        ((1.0, 1.5, 1.5), (2.0, 0.4, -0.3), 1e12, 60),
        ((0.125, 0.3125, 0.4375), (1e-150, 1e9, 1e-150), 1e11, 700),     # 1 - m ~ 1e-300, phase 1e20
        ((0.125, 0.3125, 0.4375), (1e10, 1e9, 1e9), 1e11, 60),           # phase 6.6e20
    ],
)
def test_huge_phases_against_mpmath(moments, w0, t, dps):
    """omega against mpmath's closed form at the exact phase; the attitude by the period: after
    N periods T the body is back, turned about L_world by N dphi (both from mpmath), so
    ``R(N T + tau) = Rot(l, N dphi) R(tau)``. Error budget: ~3e-32 of the phase (double-double)."""
    T, dphi = _mp_period(moments, w0, dps)
    N = mp.floor(mp.mpf(t) / T)
    tau = float(mp.mpf(t) - N * T)
    angle = float(mp.fmod(N * dphi, 2 * mp.pi))
    motion = FreeRotation(np.array(moments), np.array(w0), Rotation.identity())
    L = np.array(moments) * np.array(w0)
    phase = np.max(np.abs(w0)) * max(moments) / min(moments) * t
    ref_R = Rotation.from_rotvec(angle * L / np.linalg.norm(L)) * motion.attitude([tau])
    assert (motion.attitude([t]) * ref_R.inv()).magnitude()[0] < 2e-14 + 1e-31 * phase
    ref_w, _, _, _ = _mp_closed_form(moments, w0, [t], dps)
    np.testing.assert_allclose(motion.omega([t]), ref_w, rtol=0, atol=(1e-15 + 1e-31 * phase) * np.max(np.abs(w0)))


def test_steady_spin_at_huge_phase():
    """A steady spin turns by |omega| t: 0.3 rad/s x 1e12 s is 3e11 rad, which as a rounded
    double is off by up to ~3e-5 rad; the product is carried in double-double."""
    body = MassProperties.from_moments([1.0, 2.0, 2.5])
    t = 1e12 - 0.1
    traj = simulate(body, [0.0, 0.0, 0.3], t_end=t, samples=2)
    mp.mp.dps = 50
    angle = float(mp.fmod(mp.mpf(0.3) * mp.mpf(t), 2 * mp.pi))
    assert (traj.attitude[-1] * Rotation.from_rotvec([0.0, 0.0, angle]).inv()).magnitude() < 1e-15


def test_beyond_the_phase_limit_is_refused():
    """Never a silently wrong motion: beyond MAX_PHASE (1e24 rad) a clear ValueError."""
    I, w0 = np.array([0.125, 0.3125, 0.4375]), np.array([1e13, 1e12, 1e12])
    motion = FreeRotation(I, w0, Rotation.identity())
    assert motion.max_time < 1e12
    with pytest.raises(ValueError, match=r"t_end = 1e\+12 s takes this motion to a phase of .* rad, beyond the 1e\+24 rad"):
        motion.attitude([0.0, 1e12])
    with pytest.raises(ValueError, match=r"t_end = 1e\+12 s"):
        check_phase_limit(I, w0, 1e12)
    with pytest.raises(ValueError, match="phase"):
        simulate(MassProperties.from_moments(I), w0, t_end=1e12)
    check_phase_limit(I, w0, 1e10)  # 6.6e22 rad: allowed
    with pytest.raises(ValueError, match="phase"):  # a steady spin too
        check_phase_limit(I, [0.0, 0.0, 1e13], 1e12)


@pytest.mark.parametrize("eps", [1e-160, 3e-178, 1e-200, 1e-300])
@pytest.mark.parametrize(("moments", "axis"), [((1.0, 2.0, 2.0), 0), ((1.0, 1.0, 2.0), 2)])
def test_a_symmetric_top_with_a_vanishing_axial_spin(moments, axis, eps):
    """A prolate (I2 = I3) or oblate (I1 = I2) top whose spin along its symmetry axis is
    1e-160..1e-300 of the rest: its square underflowed when the energy-momentum gaps were scaled
    by the component whose coefficient is zero, and the run divided by zero. The motion is a
    steady rotation about omega to within |Omega| t ~ eps t: R(t) = R0 exp(t [omega])."""
    from scipy.spatial.transform import Rotation

    w0 = np.array([1.0, 1.0, 1.0])
    w0[axis] = eps
    body = MassProperties.from_moments(moments)
    traj = tumble.simulate(body, w0, t_end=1000.0, samples=11)
    np.testing.assert_allclose(traj.omega, np.broadcast_to(w0, traj.omega.shape), rtol=1e-15, atol=0)
    expected = traj.attitude[0] * Rotation.from_rotvec(np.outer(traj.t, w0))
    assert np.max((traj.attitude * expected.inv()).magnitude()) < 1e-12
