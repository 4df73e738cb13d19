"""Gravity-gradient torque in a circular orbit: each check against a closed form.

docs/gravity-gradient.md holds the equations: the torque ``3 n^2 r_b x (I r_b)`` (Hughes,
*Spacecraft Attitude Dynamics*, ch. 8), the linearised libration (ch. 9), the stability regions
(Lagrange; DeBra & Delp 1961) and the Jacobi integral (the orbiting-frame energy).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline
from scipy.spatial.transform import Rotation
from scipy.special import ellipk

import tumble
from tumble.analysis.gravity_stability import (
    STABILITY_REGIONS,
    gravity_gradient_ratios,
    gravity_gradient_stability,
)
from tumble.dynamics.methods.geometric import propagate
from tumble.dynamics.environment.earth import MU_EARTH, R_EARTH
from tumble.dynamics.models.gravity import (
    GravityGradient,
    lvlh_state,
    orbit_frame_angles,
    relative_attitude,
)
from tumble.dynamics.models.torques import body_torque
from tumble.io.scenario import gravity_gradient_from_table, lvlh_state_from_table
from tumble.mass import MassProperties

PERIOD = 5400.0  # s, a low Earth orbit
N = 2 * math.pi / PERIOD  # mean motion, rad/s
GG = GravityGradient(orbit_period=PERIOD)


def body_rpy(I_roll, I_pitch, I_yaw):
    """A body with these roll, pitch and yaw moments (kg m^2), and its pitch and yaw axes (1-3)."""
    I = np.array([I_roll, I_pitch, I_yaw], float)
    rank = np.empty(3, int)
    rank[np.argsort(I, kind="stable")] = np.arange(3)
    props = MassProperties.from_inertia(1.0, [0.0, 0.0, 0.0], np.diag(I))
    return props, int(rank[1]) + 1, int(rank[2]) + 1


def moments_from_ratios(k_roll, k_yaw):
    """(I_roll, I_pitch, I_yaw) with I_pitch = 1 kg m^2 from k_R and k_Y, solving
    k_R I_roll = I_pitch - I_yaw and k_Y I_yaw = I_pitch - I_roll by hand."""
    d = 1.0 - k_roll * k_yaw
    return (1.0 - k_yaw) / d, 1.0, (1.0 - k_roll) / d


def run(props, pitch_axis, yaw_axis, *, t_end, roll=0.0, pitch=0.0, yaw=0.0, gg=GG, **kwargs):
    """Start at rest in the orbiting frame, offset by the angles; return (trajectory, angles)."""
    start = lvlh_state(gg, props, roll=roll, pitch=pitch, yaw=yaw, pitch_axis=pitch_axis, yaw_axis=yaw_axis)
    kwargs.setdefault("method", "dop853")
    traj = tumble.simulate(props, start.omega0, attitude0=start.attitude0, torque=gg.bind(props), t_end=t_end, **kwargs)
    return traj, orbit_frame_angles(traj, gg, pitch_axis=pitch_axis, yaw_axis=yaw_axis)


def lvlh_matrix(t):
    """Orbiting frame to world, written out: columns velocity, orbit normal, radius."""
    c, s = math.cos(N * t), math.sin(N * t)
    return np.array([[-s, 0.0, c], [c, 0.0, s], [0.0, 1.0, 0.0]])


def jacobi(t, omega, attitude, moments, n=N):
    """The orbiting-frame energy h = T2 - T0 + V (Goldstein ch. 2), computed with matrices."""
    h = []
    for tk, w, R in zip(t, omega, attitude.as_matrix()):
        Iw = R @ np.diag(moments) @ R.T  # the inertia tensor in the world frame
        r = np.array([math.cos(n * tk), math.sin(n * tk), 0.0])
        Omega = np.array([0.0, 0.0, n])
        w_rel = R @ w - Omega
        h.append(0.5 * w_rel @ Iw @ w_rel - 0.5 * Omega @ Iw @ Omega + 1.5 * n**2 * r @ Iw @ r)
    return np.array(h)


def libration_period(t, angle):
    """Period of an oscillating angle from its zero crossings (cubic spline, least squares)."""
    roots = CubicSpline(t, angle).roots(extrapolate=False)
    return 2.0 * np.polyfit(np.arange(len(roots)), roots, 1)[0], len(roots)


# -- the orbit -----------------------------------------------------------------------------------

def test_period_radius_and_mean_motion_agree():
    r = (MU_EARTH * (PERIOD / (2 * math.pi)) ** 2) ** (1 / 3)  # Kepler's third law
    assert GG.radius == pytest.approx(r, rel=1e-14)
    assert GG.mean_motion == pytest.approx(N, rel=1e-15)
    other = GravityGradient(orbit_radius=r)
    assert other.period == pytest.approx(PERIOD, rel=1e-14)
    assert other.mean_motion == pytest.approx(math.sqrt(MU_EARTH / r**3), rel=1e-15)
    assert GravityGradient(orbit_radius=2.0, mu=32.0).mean_motion == 2.0  # sqrt(32 / 8)


def test_orbit_frame_is_the_lvlh_frame():
    for t in (0.0, 1234.5, 0.3 * PERIOD, 7.9 * PERIOD):
        np.testing.assert_allclose(GG.orbit_frame(t).as_matrix(), lvlh_matrix(t), atol=1e-15)
        np.testing.assert_allclose(GG.radial_direction(t), lvlh_matrix(t)[:, 2], atol=1e-15)
    ts = np.linspace(0.0, PERIOD, 7)
    np.testing.assert_allclose(GG.orbit_frame(ts).as_matrix(), [lvlh_matrix(t) for t in ts], atol=1e-15)


# -- the torque ----------------------------------------------------------------------------------

# (pitch_axis, yaw_axis) and the body's roll, pitch, yaw directions in principal coordinates,
# written out: (pitch 3, yaw 1) is an even permutation; (pitch 3, yaw 2) an odd one, whose roll
# direction is minus principal axis 1 so that roll x pitch = yaw.
# Each with the (I_roll, I_pitch, I_yaw) of MOMENTS.
MOMENTS = np.array([1.5, 2.0, 3.0])
AXES = {(3, 1): (np.array([[0, 0, 1], [1, 0, 0], [0, 1, 0]], float), (2.0, 3.0, 1.5)),
        (3, 2): (np.array([[-1, 0, 0], [0, 0, 1], [0, 1, 0]], float), (1.5, 3.0, 2.0))}


@pytest.mark.parametrize("axes", AXES)
def test_torque_about_one_axis_is_the_sin_cos_closed_form(axes):
    """Turned by an angle a about its pitch axis, the body feels -3 n^2 (I_roll - I_yaw) sin a cos a
    about it; about its roll axis 3 n^2 (I_yaw - I_pitch) sin a cos a; about yaw nothing."""
    P, (I_roll, I_pitch, I_yaw) = AXES[axes]
    gg = GG.bind(MOMENTS)
    for t in (0.0, 1000.0, 0.77 * PERIOD):
        for a in (1e-3, 0.1, 0.7, 2.0, -1.2):
            c, s = math.cos(a), math.sin(a)
            turns = {  # rotation of the body's roll-pitch-yaw frame relative to the orbit, torque in it
                "pitch": (np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]), [0.0, -3 * N**2 * (I_roll - I_yaw) * s * c, 0.0]),
                "roll": (np.array([[1, 0, 0], [0, c, -s], [0, s, c]]), [3 * N**2 * (I_yaw - I_pitch) * s * c, 0.0, 0.0]),
                "yaw": (np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]), [0.0, 0.0, 0.0]),
            }
            for name, (A, tau_rpy) in turns.items():
                R = Rotation.from_matrix(lvlh_matrix(t) @ A @ P.T)  # principal -> world
                tau = body_torque(gg, t, np.zeros(3), R)  # principal frame
                np.testing.assert_allclose(P.T @ tau, tau_rpy, rtol=0, atol=1e-15 * N**2 * MOMENTS.sum(), err_msg=name)


def test_torque_vanishes_with_a_principal_axis_along_the_radius(rng):
    gg = GG.bind(MOMENTS)
    scale = N**2 * MOMENTS.sum()
    for t in rng.uniform(0, 3 * PERIOD, 5):
        r = GG.radial_direction(t)
        for j in range(3):
            for spin in rng.uniform(-np.pi, np.pi, 3):  # any turn about the radius
                # principal axis j onto the radius (the shortest turn), then a turn about it
                R0, _ = Rotation.align_vectors([r], [np.eye(3)[j]])
                R = Rotation.from_rotvec(spin * r) * R0
                np.testing.assert_allclose(R.apply(np.eye(3)[j]), r, atol=1e-15)
                assert np.max(np.abs(gg(t, np.zeros(3), R))) < 1e-15 * scale


def test_world_frame_torque_is_the_body_torque_turned(rng):
    """The model answers in the world frame: 3 n^2 r x (I_world r), I_world = R diag(I) R^T."""
    gg = GG.bind(MOMENTS)
    assert gg.frame == "world"
    for R in Rotation.random(20, random_state=3):
        t = rng.uniform(0, 10 * PERIOD)
        r = GG.radial_direction(t)
        Iw = R.as_matrix() @ np.diag(MOMENTS) @ R.as_matrix().T
        expected = 3 * N**2 * np.cross(r, Iw @ r)
        np.testing.assert_allclose(gg(t, np.zeros(3), R), expected, rtol=0, atol=1e-15 * N**2 * MOMENTS.sum())
        np.testing.assert_allclose(body_torque(gg, t, np.zeros(3), R), R.inv().apply(expected),
                                   rtol=0, atol=1e-15 * N**2 * MOMENTS.sum())


def test_batched_torque_equals_a_loop(rng):
    R = Rotation.random(40, random_state=5)
    omega = rng.normal(size=(40, 3))
    gg = GG.bind(MOMENTS)
    batch = gg(123.0, omega, R)
    assert batch.shape == (40, 3)
    loop = np.array([gg(123.0, omega[k], R[k]) for k in range(40)])
    np.testing.assert_allclose(batch, loop, rtol=0, atol=1e-15 * N**2 * MOMENTS.sum())  # round-off of scipy's batch
    # N bodies of N moments
    I = np.sort(rng.uniform(1.0, 2.0, (40, 3)), axis=1)
    many = GravityGradient(orbit_period=PERIOD, moments=I)
    np.testing.assert_allclose(many(77.0, omega, R),
                               [GravityGradient(orbit_period=PERIOD, moments=I[k])(77.0, omega[k], R[k]) for k in range(40)],
                               rtol=1e-15, atol=1e-15 * N**2 * 6)


def test_geometric_splitting_runs_bodies_in_a_batch():
    """geometric.propagate calls the torque with N bodies at once; each agrees with DOP853."""
    props, pa, ya = body_rpy(2.0, 3.0, 1.5)
    pitches = np.array([0.02, 0.1, 0.3])
    start = lvlh_state(GG, props, roll=0.01, pitch=pitches, pitch_axis=pa, yaw_axis=ya)
    t = np.linspace(0.0, 2 * PERIOD, 41)
    omega, quat = propagate(props.principal_moments, start.omega0, start.attitude.as_quat(), t,
                            step=30.0, torque=GG.bind(props))
    assert omega.shape == (41, 3, 3)
    for k, pitch in enumerate(pitches):
        ref, _ = run(props, pa, ya, t_end=2 * PERIOD, samples=41, roll=0.01, pitch=pitch)
        np.testing.assert_allclose(omega[:, k], ref.omega, rtol=0, atol=1e-6 * N)  # measured 1.4e-7 n
        np.testing.assert_allclose(quat[:, k] * np.sign(quat[:, k, 3:]), ref.quat * np.sign(ref.quat[:, 3:]), atol=1e-6)


# -- starting in the orbiting frame -------------------------------------------------------------

@pytest.mark.parametrize("axes", [(3, 1), (3, 2), (1, 2), (2, 3), (1, 3), (2, 1)])
def test_lvlh_state_points_the_axes_and_turns_with_the_orbit(axes):
    pitch_axis, yaw_axis = axes
    body = tumble.iss_t_handle()  # its principal axes are not its design axes
    start = lvlh_state(GG, body, pitch_axis=pitch_axis, yaw_axis=yaw_axis)
    R = start.attitude.as_matrix()
    roll_axis = 6 - pitch_axis - yaw_axis
    np.testing.assert_allclose(R[:, yaw_axis - 1], [1, 0, 0], atol=1e-15)  # the radius at t = 0
    np.testing.assert_allclose(R[:, pitch_axis - 1], [0, 0, 1], atol=1e-15)  # the orbit normal
    sign = np.linalg.det(np.eye(3)[:, [roll_axis - 1, pitch_axis - 1, yaw_axis - 1]])
    np.testing.assert_allclose(sign * R[:, roll_axis - 1], [0, 1, 0], atol=1e-15)  # the velocity
    np.testing.assert_allclose(start.attitude.apply(start.omega0), [0, 0, N], atol=1e-18)
    # attitude0 is the design frame's: design -> world = principal -> world * (principal -> design)^-1
    np.testing.assert_allclose((start.attitude0 * Rotation.from_matrix(body.principal_axes)).as_matrix(), R, atol=1e-15)
    if axes == (3, 1):  # the energy minimum: the spin can never exceed n
        assert GG.bind(body).max_spin(0.0, start.omega0, start.attitude) == pytest.approx(N, rel=1e-12)
    # at rest in the orbiting frame, the torque is zero: the state is a relative equilibrium
    assert np.max(np.abs(GG.bind(body)(0.0, start.omega0, start.attitude))) < 1e-16 * N**2 * body.principal_moments.sum()


def test_a_body_started_in_the_orbiting_frame_stays_there():
    """Lagrange-stable T-handle at rest in the orbiting frame: five orbits later, still there."""
    body = tumble.t_handle()
    start = lvlh_state(GG, body)
    traj = tumble.simulate(body, start.omega0, attitude0=start.attitude0, torque=GG.bind(body), t_end=5 * PERIOD,
                           method="dop853")
    angles = orbit_frame_angles(traj, GG)
    assert max(np.max(np.abs(a)) for a in angles) < 1e-10
    np.testing.assert_allclose(traj.omega_world, np.tile([0, 0, N], (len(traj), 1)), rtol=0, atol=1e-11 * N)


def test_angles_round_trip(rng):
    for axes in [(3, 1), (3, 2), (1, 2), ("major", "minor")]:
        roll, pitch, yaw = rng.uniform(-1.2, 1.2, (3, 10))
        start = lvlh_state(GG, tumble.t_handle(), roll=roll, pitch=pitch, yaw=yaw, pitch_axis=axes[0], yaw_axis=axes[1])
        back = relative_attitude(GG, 0.0, start.attitude, pitch_axis=axes[0], yaw_axis=axes[1]).as_euler("YXZ")
        np.testing.assert_allclose(back, np.column_stack([pitch, roll, yaw]), atol=1e-14)


def test_design_frame_runs_agree_with_principal_frame_runs():
    """The torque is given in the world frame, so simulate's frame="design" leaves it alone."""
    body = tumble.iss_t_handle()
    start = lvlh_state(GG, body, pitch=0.2, roll=0.05)
    common = dict(attitude0=start.attitude0, torque=GG.bind(body), t_end=PERIOD, samples=50, method="dop853")
    principal = tumble.simulate(body, start.omega0, **common)
    design = tumble.simulate(body, body.principal_axes @ start.omega0, frame="design", **common)
    np.testing.assert_allclose(design.omega, principal.omega, rtol=0, atol=1e-12 * N)


# -- libration: the linearised equations ---------------------------------------------------------

def test_small_pitch_libration_has_the_linear_frequency():
    """I_pitch theta'' + 3 n^2 (I_roll - I_yaw) theta = 0 (Hughes ch. 9): for 0.01 rad, the period
    of pitch(t) over ten librations is 2 pi / (n sqrt(3 (I_roll - I_yaw) / I_pitch)) to 1e-4
    (the nonlinear correction, sin^2(0.01) / 4 = 2.5e-5, is the rest: next test)."""
    I_roll, I_pitch, I_yaw = 2.0, 3.0, 1.5
    props, pa, ya = body_rpy(I_roll, I_pitch, I_yaw)
    w_lin = N * math.sqrt(3 * (I_roll - I_yaw) / I_pitch)
    T_lin = 2 * math.pi / w_lin
    traj, angles = run(props, pa, ya, t_end=10 * T_lin, dt=T_lin / 200, pitch=0.01)
    T, crossings = libration_period(traj.t, angles.pitch)
    assert crossings >= 19
    assert abs(T / T_lin - 1) < 1e-4  # measured 2.5001e-5
    assert abs(T / T_lin - 1 - math.sin(0.01) ** 2 / 4) < 1e-7  # the first nonlinear term
    assert np.max(np.abs(angles.roll)) < 1e-12 and np.max(np.abs(angles.yaw)) < 1e-12  # a planar motion


@pytest.mark.parametrize("amplitude", [0.01, 0.5, 1.2])
def test_pitch_libration_period_is_the_pendulum_period(amplitude):
    """Exactly, theta'' = -(3/2) n^2 k_P sin 2 theta: a pendulum in 2 theta, whose period is
    4 K(sin^2 theta0) / (n sqrt(3 k_P)) (complete elliptic integral K)."""
    I_roll, I_pitch, I_yaw = 2.0, 3.0, 1.5
    props, pa, ya = body_rpy(I_roll, I_pitch, I_yaw)
    T_exact = 4 * ellipk(math.sin(amplitude) ** 2) / (N * math.sqrt(3 * (I_roll - I_yaw) / I_pitch))
    traj, angles = run(props, pa, ya, t_end=10 * T_exact, dt=T_exact / 200, pitch=amplitude)
    T, _ = libration_period(traj.t, angles.pitch)
    assert abs(T / T_exact - 1) < 1e-9  # measured 1.1e-10, 1.2e-12, 2.7e-10
    assert np.max(np.abs(angles.pitch)) == pytest.approx(amplitude, rel=1e-6)


def roll_yaw_roots(k_roll, k_yaw):
    """Roots s^2 (in units of n^2) of s^4 + (1 + 3 k_R + k_R k_Y) s^2 + 4 k_R k_Y = 0."""
    b, c = 1 + 3 * k_roll + k_roll * k_yaw, 4 * k_roll * k_yaw
    d = np.sqrt(complex(b * b - 4 * c))
    return (-b - d) / 2, (-b + d) / 2


@pytest.mark.parametrize("ratios", [(0.5, 1 / 6), (-0.03, -0.3)], ids=["lagrange", "debra-delp"])
def test_roll_yaw_libration_has_the_two_linear_frequencies(ratios):
    """Small roll and yaw are sums of two sinusoids at n sqrt(-s^2), s^2 the roots of the roll-yaw
    characteristic equation: a least-squares fit with those two frequencies leaves < 1e-5 of the
    amplitude (measured 2.5e-7 and 9e-8), while frequencies 1e-4 off leave far more."""
    k_roll, k_yaw = ratios
    props, pa, ya = body_rpy(*moments_from_ratios(k_roll, k_yaw))
    w = N * np.sqrt([-s.real for s in roll_yaw_roots(k_roll, k_yaw)])
    amp = 1e-4
    traj, angles = run(props, pa, ya, t_end=10 * PERIOD, dt=PERIOD / 200, roll=amp, yaw=-0.5 * amp)

    def misfit(freqs, y):
        M = np.column_stack([f(wk * traj.t) for wk in freqs for f in (np.cos, np.sin)])
        coef = np.linalg.lstsq(M, y, rcond=None)[0]
        return np.max(np.abs(M @ coef - y)) / amp

    for y in (angles.roll, angles.yaw):
        assert misfit(w, y) < 1e-5
        assert misfit(w * (1 + 1e-4), y) > 1e-3


@pytest.mark.parametrize("ratios", [(0.5, -0.3), (0.2, -0.5)])
def test_roll_yaw_divergence_has_the_linear_growth_rate(ratios):
    """k_R k_Y < 0: one root s^2 > 0, and roll and yaw grow as exp(n sqrt(s^2) t) (fit where
    1e-6 < |angle| < 1e-4, from 1e-9 rad: agreement < 1e-3, measured 6e-5)."""
    k_roll, k_yaw = ratios
    props, pa, ya = body_rpy(*moments_from_ratios(k_roll, k_yaw))
    rate = N * math.sqrt(roll_yaw_roots(k_roll, k_yaw)[1].real)
    traj, angles = run(props, pa, ya, t_end=6 * PERIOD, dt=PERIOD / 200, roll=1e-9)
    for y in (angles.roll, angles.yaw):
        k = (np.abs(y) > 1e-6) & (np.abs(y) < 1e-4)
        assert k.sum() > 100
        assert np.polyfit(traj.t[k], np.log(np.abs(y[k])), 1)[0] == pytest.approx(rate, rel=1e-3)


# -- stability -----------------------------------------------------------------------------------

def test_lagrange_body_stays_near_the_vertical_and_a_swapped_one_does_not():
    """The T-handle (I1 = 0.125, I2 = 0.3125, I3 = 0.4375 kg m^2) pitch = major, yaw = minor:
    Lagrange, 20 orbits from 0.01 rad offsets stay within 0.05 rad (measured 0.0117); with
    yaw = intermediate (I_yaw > I_roll) the pitch libration is unstable and the body leaves the
    vertical (pitch reaches 3.13 rad)."""
    body = tumble.t_handle()
    offsets = dict(roll=0.01, pitch=0.01, yaw=0.01)
    _, stable = run(body, 3, 1, t_end=20 * PERIOD, dt=PERIOD / 50, rtol=1e-10, **offsets)
    assert max(np.max(np.abs(a)) for a in stable) < 0.05
    _, unstable = run(body, 3, 2, t_end=20 * PERIOD, dt=PERIOD / 50, rtol=1e-10, **offsets)
    assert np.max(np.abs(unstable.pitch)) > 1.0


# (k_R, k_Y), the region they are in, by hand from the conditions
SAMPLES = {
    (0.6, 0.3): "lagrange",
    (0.3, 0.1): "lagrange",
    (-0.02, -0.5): "debra-delp",
    (-0.03, -0.3): "debra-delp",
    (0.3, 0.6): "pitch unstable",  # k_R < k_Y; 1 + 0.9 + 0.18 > 4 sqrt(0.18)
    (0.5, -0.3): "roll-yaw unstable",  # k_R k_Y < 0
    (-0.2, -0.6): "roll-yaw unstable",  # 1 - 0.6 + 0.12 < 4 sqrt(0.12)
    (-0.3, 0.4): "unstable",
}


@pytest.mark.parametrize("ratios", SAMPLES)
def test_stability_classification_agrees_with_simulation(ratios):
    """20 orbits from 0.01 rad in roll, pitch and yaw: a stable body stays within 0.1 rad, an
    unstable one passes 0.5 rad, and the first angle to pass 0.1 rad is of the unstable mode."""
    k_roll, k_yaw = ratios
    I_roll, I_pitch, I_yaw = moments_from_ratios(k_roll, k_yaw)
    props, pa, ya = body_rpy(I_roll, I_pitch, I_yaw)
    cls = gravity_gradient_stability(*gravity_gradient_ratios(props.principal_moments, pitch_axis=pa, yaw_axis=ya))
    assert str(cls.region) == SAMPLES[ratios]
    _, angles = run(props, pa, ya, t_end=20 * PERIOD, dt=PERIOD / 50, rtol=1e-10, roll=0.01, pitch=0.01, yaw=0.01)
    A = np.abs(np.stack(angles))  # roll, pitch, yaw
    if cls.pitch and cls.roll_yaw:
        assert A.max() < 0.1
        return
    assert A.max() > 0.5
    first = {name: int(np.argmax(A[i] > 0.1)) for i, name in enumerate(("roll", "pitch", "yaw"))}
    leader = min(first, key=first.get)
    if not cls.pitch and cls.roll_yaw:
        assert leader == "pitch"
    if cls.pitch and not cls.roll_yaw:
        assert leader in ("roll", "yaw")


def test_gravity_gradient_ratios_by_hand():
    k = gravity_gradient_ratios([1.0, 2.0, 2.5], pitch_axis=3, yaw_axis=1)  # roll 2, pitch 2.5, yaw 1
    np.testing.assert_allclose(k, [(2.5 - 1) / 2, (2 - 1) / 2.5, (2.5 - 2) / 1])
    k = gravity_gradient_ratios([[1.0, 2.0, 2.5]] * 2, pitch_axis="minor", yaw_axis="major")  # roll 2, pitch 1, yaw 2.5
    np.testing.assert_allclose(np.transpose(k), [[(1 - 2.5) / 2, (2 - 2.5) / 1, (1 - 2) / 2.5]] * 2)


def test_ratios_of_real_bodies_fill_the_square_and_are_consistent(rng):
    I = np.sort(rng.uniform(0.0, 1.0, (2000, 3)), axis=1)
    I = I[I[:, 0] + I[:, 1] >= I[:, 2]]  # the triangle inequality
    for pitch_axis, yaw_axis in [(3, 1), (3, 2), (1, 2), (2, 3), (1, 3), (2, 1)]:
        kr, kp, ky = gravity_gradient_ratios(I, pitch_axis=pitch_axis, yaw_axis=yaw_axis)
        assert np.all(np.abs([kr, kp, ky]) <= 1)
        np.testing.assert_allclose(kp * (1 - kr * ky), kr - ky, atol=1e-12)
        roll_axis = 6 - pitch_axis - yaw_axis
        cls = gravity_gradient_stability(kr, kp, ky)
        np.testing.assert_array_equal(cls.pitch, I[:, roll_axis - 1] > I[:, yaw_axis - 1])  # I_roll > I_yaw
    kr, kp, ky = gravity_gradient_ratios(I, pitch_axis=2, yaw_axis=3)
    # round trip through moments_from_ratios (I_pitch = 1)
    Ir, Ip, Iy = moments_from_ratios(kr, ky)
    np.testing.assert_allclose(np.column_stack([Ir, Iy]), np.column_stack([I[:, 0], I[:, 2]]) / I[:, 1:2], rtol=1e-9)


def test_classification_on_the_boundaries_and_in_batches():
    cls = gravity_gradient_stability([0.5, 0.5, 0.0, -0.05], [0.0, 0.3 / 0.9, 0.0, -0.05], [0.5, 0.2, 0.0, 0.0])
    # k_R = k_Y: pitch marginal, counted unstable (but k_P = 0 exactly with roll-yaw stable is a body symmetric
    # about pitch: "symmetric"); k_Y = 0 or k_R = 0: roll-yaw marginal, unstable where pitch is; a sphere: symmetric
    np.testing.assert_array_equal(cls.pitch, [False, True, False, False])
    np.testing.assert_array_equal(cls.roll_yaw, [True, True, False, False])
    np.testing.assert_array_equal(cls.region, ["symmetric", "lagrange", "symmetric", "unstable"])
    assert str(gravity_gradient_stability(0.5, 1e-3, (0.5 - 1e-3) / (1 - 0.5e-3)).region) == "lagrange"  # off the line
    # on k_Y = -1, 1 + 3 k_R + k_R k_Y = 4 sqrt(k_R k_Y) reads, with k_R = -u^2,
    # 2 u^2 + 4 u - 1 = 0: the boundary is k_R = -0.0505 (and k_P = 1 all along k_Y = -1)
    u = (-4 + math.sqrt(24)) / 4
    k_b = -(u**2)
    for kr, expected in ((k_b + 1e-9, True), (k_b - 1e-9, False)):
        assert bool(gravity_gradient_stability(kr, (kr + 1) / (1 + kr), -1.0).roll_yaw) is expected
    # a planar body, I_pitch = I_roll + I_yaw, sits at the corner (1, 1): k_P alone decides pitch
    for I_roll, I_yaw, stable in ((2.0, 1.0, True), (1.0, 2.0, False)):
        props, pa, ya = body_rpy(I_roll, I_roll + I_yaw, I_yaw)
        kr, kp, ky = gravity_gradient_ratios(props.principal_moments, pitch_axis=pa, yaw_axis=ya)
        assert (kr, ky) == pytest.approx((1.0, 1.0))
        assert bool(gravity_gradient_stability(kr, kp, ky).pitch) is stable
    assert set(STABILITY_REGIONS) >= set(SAMPLES.values())


@pytest.mark.parametrize(("moments", "free"), [((87.32, 87.32, 2.25), "yaw"), ((1.0, 1.5, 1.0), "pitch"),
                                               ((1.5, 1.0, 1.0), "roll")], ids=["boom", "disk-to-normal", "disk-to-velocity"])
def test_a_body_symmetric_about_an_axis_keeps_that_axis_and_turns_freely_about_it(moments, free):
    """A walkthrough of docs/gravity-gradient.md (2026-12-03): a boom with a cylindrical bus (I_pitch = I_roll >
    I_yaw) was reported "unstable there in roll and yaw", its largest angle 1.24 rad, though the boom never left
    the vertical by more than 0.054 rad: the 1.24 rad was the free turn about its own axis. And moments equal
    within 1e-9 of the trace gave the other verdict. Such a body is "symmetric": its symmetry axis, taken to the
    world and measured against the orbiting frame written out by hand, stays within its start's offsets while the
    turn about it drifts; the summary's tilt is that angle."""
    from tumble.analysis.torque_summary import gravity_gradient_summary

    props, pa, ya = body_rpy(*moments)
    kr, kp, ky = gravity_gradient_ratios(props.principal_moments, pitch_axis=pa, yaw_axis=ya)
    assert str(gravity_gradient_stability(kr, kp, ky).region) == "symmetric"
    nudged = props.principal_moments + np.array([0.0, 0.0, 1e-10]) * np.sum(props.principal_moments)
    assert str(gravity_gradient_stability(*gravity_gradient_ratios(np.sort(nudged), pitch_axis=pa, yaw_axis=ya)).region) \
        == "symmetric"
    traj, _ = run(props, pa, ya, t_end=5 * PERIOD, samples=501, roll=0.02, pitch=0.05, yaw=0.02)
    g = gravity_gradient_summary(traj, GG, pitch_axis=pa, yaw_axis=ya)
    assert g["region"] == "symmetric" and g["symmetry_axis"] == free
    k = ("roll", "pitch", "yaw").index(free)
    principal = {"roll": 6 - pa - ya, "pitch": pa, "yaw": ya}[free] - 1
    axis = traj.attitude.apply(np.eye(3)[principal])  # the symmetry axis in the world
    where = np.array([lvlh_matrix(t)[:, k] for t in traj.t])  # its place: velocity, orbit normal or radius
    tilt = np.arccos(np.clip(np.abs(np.sum(axis * where, axis=1)), 0.0, 1.0))
    assert g["symmetry_axis_tilt"] == pytest.approx(float(np.max(tilt)), abs=1e-9)
    assert np.max(tilt) < 0.1, np.max(tilt)


# -- the energy budget ---------------------------------------------------------------------------

@pytest.mark.parametrize("ratios", [(0.6, 0.3), (0.3, 0.6)], ids=["lagrange-body", "pitch-unstable-body"])
def test_jacobi_integral_is_conserved(ratios):
    """h = T2 - T0 + V in the orbiting frame is constant along DOP853: to 1e-10 of
    n^2 (I1 + I2 + I3) over 10 orbits of large motion (0.3, 0.6, -0.4 rad offsets: both bodies
    tumble through every pitch angle; measured 1.5e-11 and 2.5e-11), while the kinetic energy
    itself swings by 57 % and 74 % of that scale."""
    props, pa, ya = body_rpy(*moments_from_ratios(*ratios))
    traj, angles = run(props, pa, ya, t_end=10 * PERIOD, dt=PERIOD / 20, roll=0.3, pitch=0.6, yaw=-0.4)
    scale = N**2 * props.principal_moments.sum()
    h = jacobi(traj.t, traj.omega, traj.attitude, props.principal_moments)
    assert np.max(np.abs(h - h[0])) < 1e-10 * scale
    assert np.ptp(traj.energy) > 0.5 * scale
    # the same integral bounds the spin for ever (a bound simulate can use for its work check)
    bound = GG.bind(props).max_spin(0.0, traj.omega[0], traj.attitude[0])
    assert np.max(np.linalg.norm(traj.omega, axis=1)) <= bound
    np.testing.assert_allclose(GG.bind(props).jacobi_integral(traj.t, traj.omega, traj.attitude), h, rtol=0, atol=1e-14 * scale)


def test_jacobi_integral_of_the_splitting_and_of_rk45():
    """The geometric method (step 30 s, 0.035 rad of orbit) keeps h to 1e-7 over 5 orbits
    (measured 2.1e-8); RK45 at its default tolerances does not (measured 4e-4): the gravity
    gradient is an ordinary torque, and no method follows it exactly."""
    props, pa, ya = body_rpy(2.0, 3.0, 1.5)
    scale = N**2 * props.principal_moments.sum()
    errors = {}
    for method, kw in (("geometric", {"step": 30.0}), ("rk45", {})):
        traj, _ = run(props, pa, ya, t_end=5 * PERIOD, dt=PERIOD / 20, roll=0.3, pitch=0.5, method=method, **kw)
        h = jacobi(traj.t, traj.omega, traj.attitude, props.principal_moments)
        errors[method] = np.max(np.abs(h - h[0])) / scale
    assert errors["geometric"] < 1e-7
    assert errors["rk45"] > 1e-6


# -- bad input -----------------------------------------------------------------------------------

@pytest.mark.parametrize(("kwargs", "pattern"), [
    (dict(orbit_radius=6.0e6), r"orbit_radius = 6000000.0 puts the orbit at radius .* inside the Earth .*6.3781e\+06 m"),
    (dict(orbit_period=3000.0), r"orbit_period = 3000.0 .* inside the Earth"),
    (dict(orbit_period=-5400.0), r"orbit_period = -5400.0 must be a positive finite number \(s\)"),
    (dict(orbit_period=0.0), r"orbit_period = 0.0 must be a positive"),
    (dict(orbit_period=float("nan")), r"orbit_period = nan must be a finite number \(s\)"),
    (dict(orbit_radius=float("inf")), r"orbit_radius = inf must be a finite number \(m\)"),
    (dict(orbit_period=True), r"orbit_period = True must be a number"),
    (dict(orbit_period="5400"), r"orbit_period = '5400' must be a number"),
    (dict(orbit_period=5400.0, mu=0.0), r"mu = 0.0 must be a positive finite number \(m\^3/s\^2\)"),
    (dict(orbit_period=5400.0, mu=-1.0), r"mu = -1.0 must be a positive"),
    (dict(orbit_period=5400.0, mu=float("nan")), r"mu = nan must be a finite number"),
    (dict(), r"give exactly one of orbit_period \(s\) and orbit_radius \(m\)$"),
    (dict(orbit_period=5400.0, orbit_radius=7e6), r"give exactly one of .*, not both"),
    (dict(orbit_radius=1e300, mu=1.0), r"orbit_radius = 1e\+300 gives a mean motion of 0.0 rad/s"),
    (dict(orbit_period=5400.0, moments=[3.0, 2.0, 1.0]), r"moments = \[3.0, 2.0, 1.0\] must be ascending"),
    (dict(orbit_period=5400.0, moments=[0.0, 2.0, 3.0]), r"moments = \[0.0, 2.0, 3.0\] must be positive"),
    (dict(orbit_period=5400.0, moments=[1.0, 2.0]), r"moments .* 3"),
])
def test_bad_orbits_are_refused(kwargs, pattern):
    with pytest.raises(ValueError, match=pattern):
        GravityGradient(**kwargs)


def test_other_central_bodies_may_have_small_orbits():
    gg = GravityGradient(orbit_radius=1.0e6, mu=4.9048695e12)  # the Moon's GM; 1000 km
    assert gg.period == pytest.approx(2 * math.pi * math.sqrt(1e18 / 4.9048695e12))
    assert GravityGradient(orbit_radius=R_EARTH * 1.0000001).radius > R_EARTH


def test_unbound_and_mismatched_models_are_refused():
    with pytest.raises(ValueError, match=r"has no moments: use gg.bind\(body\)"):
        GG(0.0, np.zeros(3), Rotation.identity())
    bound = GG.bind(tumble.t_handle())
    assert bound.bind(tumble.t_handle()) is bound
    with pytest.raises(ValueError, match=r"holds moments \[0.125, 0.3125, 0.4375\] kg m\^2, not the body's"):
        bound.bind(tumble.iss_t_handle())


@pytest.mark.parametrize(("kwargs", "pattern"), [
    (dict(pitch_axis=3, yaw_axis=3), r"pitch_axis = 3 and yaw_axis = 3 must be different principal axes"),
    (dict(pitch_axis=0), r"pitch_axis = 0 must be 1, 2 or 3"),
    (dict(yaw_axis=-1), r"yaw_axis = -1 must be 1, 2 or 3"),
    (dict(yaw_axis=2.0), r"yaw_axis = 2.0 must be 1, 2 or 3"),
    (dict(pitch_axis=True), r"pitch_axis = True must be 1, 2 or 3"),
    (dict(pitch_axis="x"), r"pitch_axis = 'x' must be 1, 2 or 3 .* or 'minor', 'intermediate' or 'major'"),
    (dict(roll=float("nan")), r"roll"),
    (dict(pitch=[[0.1]]), r"pitch has shape \(1, 1\)"),
])
def test_bad_lvlh_arguments_are_refused(kwargs, pattern):
    with pytest.raises(ValueError, match=pattern):
        lvlh_state(GG, tumble.t_handle(), **kwargs)


def test_bad_ratios_are_refused():
    with pytest.raises(ValueError, match=r"k_roll = 1.5 must be from -1 to 1"):
        gravity_gradient_stability(1.5, 0.0, 0.0)
    with pytest.raises(ValueError, match=r"k_yaw\[1\] = nan"):
        gravity_gradient_stability([0.1, 0.2], [0.0, 0.0], [0.1, float("nan")])
    with pytest.raises(ValueError, match=r"k_pitch = 0.5 does not belong with k_roll = 0.3 and k_yaw = 0.1"):
        gravity_gradient_stability(0.3, 0.5, 0.1)
    with pytest.raises(ValueError, match=r"must broadcast together"):
        gravity_gradient_stability([0.1, 0.2], [0.0, 0.0, 0.0], [0.1, 0.2])


# -- scenario tables -----------------------------------------------------------------------------

def test_gravity_gradient_from_table():
    gg = gravity_gradient_from_table({"kind": "gravity_gradient", "orbit_period": 5400.0})
    assert gg == GG
    gg = gravity_gradient_from_table({"orbit_radius": 7e6, "mu": 4e14})
    assert (gg.orbit_radius, gg.mu) == (7e6, 4e14)
    for table, pattern in [
        ({"orbit_period": 5400.0, "radius": 1}, r"^torque: unknown key 'radius' \(did you mean 'orbit_radius'\?\); allowed: kind, orbit_period, orbit_radius, mu, semi_major_axis, eccentricity, "
         r"inclination, raan, arg_perigee, mean_anomaly, tle$"),
        ({"mu": 4e14}, r"^torque: missing key 'orbit_period' \(s\) or 'orbit_radius' \(m\)"),
        ({"kind": "constant", "orbit_period": 5400.0}, r"^torque: kind = 'constant' is not 'gravity_gradient'$"),
        ({"orbit_period": 5400.0, "orbit_radius": 7e6}, r"^torque: give exactly one"),
        ({"orbit_radius": 6e6}, r"^torque: orbit_radius = 6000000.0 puts the orbit .* inside the Earth"),
        ({"orbit_period": 5400.0, "mu": "earth"}, r"^torque: mu = 'earth' must be a number"),
        ([1, 2], r"^torque must be a table"),
    ]:
        with pytest.raises(ValueError, match=pattern):
            gravity_gradient_from_table(table)


def test_lvlh_state_from_table():
    body = tumble.t_handle()
    start = lvlh_state_from_table({"pitch": 0.01, "pitch_axis": 3, "yaw_axis": "minor"}, GG, body)
    np.testing.assert_allclose(start.attitude.as_quat(), lvlh_state(GG, body, pitch=0.01).attitude.as_quat())
    assert lvlh_state_from_table({}, GG, body).attitude.approx_equal(lvlh_state(GG, body).attitude)
    for table, pattern in [
        ({"pitch": 0.01, "omega": [0, 0, 1]}, r"^initial.orbit_frame: unknown key 'omega'; allowed: roll, pitch, yaw, pitch_axis, yaw_axis$"),
        ({"roll": [0.1, 0.2]}, r"^initial.orbit_frame: roll = \[0.1, 0.2\] must be a number \(rad\)$"),
        ({"yaw_axis": 4}, r"^initial.orbit_frame: yaw_axis = 4 must be 1, 2 or 3"),
    ]:
        with pytest.raises(ValueError, match=pattern):
            lvlh_state_from_table(table, GG, body)


# -- the figure ----------------------------------------------------------------------------------

def test_stability_figure(tmp_path):
    from matplotlib.figure import Figure

    from tumble.viz import figure_gravity_stability, save_figure

    path = tmp_path / "stability.png"
    fig = figure_gravity_stability(points={"T-handle": (1.0, 1.0)})
    save_figure(fig, path)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert labels[:2] == ["Lagrange (stable)", "DeBra-Delp (stable)"]
    ax = Figure().subplots()
    assert figure_gravity_stability(ax=ax) is ax.figure
    # the three ratios where the pair goes (a walkthrough, 2026-12-03: "too many values to unpack")
    with pytest.raises(ValueError, match=r"^points\['boom'\] = \(0.75, 0.4, 0.5\) must be two numbers, \(k_R, k_Y\); "
                                         r"of gravity_gradient_ratios' three \(k_R, k_P, k_Y\) give the first and the last$"):
        figure_gravity_stability(points={"boom": tuple(float(k) for k in gravity_gradient_ratios([1.0, 2.0, 2.5]))})


def test_stability_lives_in_analysis_and_the_ratios_have_their_own_name():
    """Issue #17: the stability classification is analysis, not the torque model, and its ratios
    (k_R, k_P, k_Y) are not called inertia ratios (which mean I1/I3, I2/I3 elsewhere)."""
    import tumble.analysis
    import tumble.dynamics
    from tumble.dynamics.models import gravity

    assert tumble.gravity_gradient_stability is tumble.analysis.gravity_gradient_stability
    assert tumble.analysis.gravity_gradient_ratios is gravity_gradient_ratios
    for name in ("inertia_ratios", "gravity_gradient_stability", "STABILITY_REGIONS"):
        assert not hasattr(gravity, name)
        assert name not in tumble.dynamics.__all__
    # the roll, pitch, yaw axes are the frame's: (roll, pitch, yaw) = (2, 3, 1) is even, so +roll
    (a, b, c), P = gravity.rpy_axes(3, 1)
    assert (a, b, c) == (1, 2, 0)
    np.testing.assert_array_equal(P, [[0, 0, 1], [1, 0, 0], [0, 1, 0]])
    (a, b, c), P = gravity.rpy_axes(1, 3)  # (2, 1, 3) is odd: roll along minus axis 2
    assert (a, b, c) == (1, 0, 2) and P[1, 0] == -1.0
    assert np.linalg.det(P) == 1.0


@pytest.mark.parametrize("pitch_axis, yaw_axis", [(1, 2), (1, 3), (2, 1), (3, 1)])
def test_a_flat_plates_ratios_as_computed_are_classified(pitch_axis, yaw_axis):
    """A plate, I3 = I1 + I2: its ratio of 1 came out of gravity_gradient_ratios as 1 + 2e-16 and
    gravity_gradient_stability refused it ("k_pitch = 1.0000000000000002 must be from -1 to 1"), the call
    the guide shows for the planar bodies at the triangle's edge; the verdict is the edge's, computed here."""
    moments = [1 / 3, 2 / 3, 1.0]
    k = gravity_gradient_ratios(moments, pitch_axis=pitch_axis, yaw_axis=yaw_axis)
    cls = gravity_gradient_stability(*k)
    exact = {name: np.clip(float(v), -1.0, 1.0) for name, v in zip(("kr", "kp", "ky"), k)}
    # Hughes, Spacecraft Attitude Dynamics, ch. 9: pitch needs k_P > 0; roll-yaw k_R k_Y > 0 and
    # 1 + 3 k_R + k_R k_Y > 4 sqrt(k_R k_Y)
    prod = exact["kr"] * exact["ky"]
    assert bool(cls.pitch) == (exact["kp"] > 0)
    assert bool(cls.roll_yaw) == (prod > 0 and 1 + 3 * exact["kr"] + prod > 4 * math.sqrt(prod))
    with pytest.raises(ValueError, match="k_pitch = 1.01 must be from -1 to 1"):
        gravity_gradient_stability(0.5, 1.01, 0.5)


def test_orbit_frame_angles_of_an_ellipse_is_refused_naming_the_model():
    from tumble.dynamics import KeplerOrbit, OrbitGravityGradient, orbit_frame_angles

    run = tumble.simulate(tumble.t_handle(), [0.1, 2.0, 0.1], t_end=1.0, samples=3)
    with pytest.raises(ValueError, match=r"gg = .* must be a GravityGradient \(a circular orbit's\)"):
        orbit_frame_angles(run, OrbitGravityGradient(KeplerOrbit(8e6, 0.1)))
