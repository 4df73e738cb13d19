"""Closed-loop attitude control (issue 21): closed forms of B-dot and MRP feedback, the
momentum budget, the environment's models and their input checks."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.spatial.transform import Rotation

import tumble
from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.bdot import BDot, bdot_gain
from tumble.dynamics.control.controllers import Controller, MRPFeedback, pd_response
from tumble.dynamics.models.actuators import Command, Magnetorquers, ReactionWheels
from tumble.dynamics.models.orbit_gravity import gravity_gradient_of
from tumble.dynamics.environment.magnetic import IGRF13_2020, DipoleField, UniformField
from tumble.dynamics.environment.orbit import CircularOrbit
from tumble.dynamics.models.sensors import Measurement, Sensors
from tumble.dynamics.special.mrp import mrp_angle, mrp_from_quat

# --- B-dot: the closed form ---------------------------------------------------------------------
# A body spinning at w about its principal axis 3 in a field B fixed in the world and normal to
# that axis: the dipole m = k_b w x B gives the torque m x B = -k_b |B|^2 w (w is normal to B),
# along the spin axis, so the spin stays about axis 3 and I3 w' = -k_b B^2 w:
# w(t) = w0 exp(-a t), a = k_b B^2 / I3 (Stickler & Alfriend 1974). With the dipole held for a
# period D while the field turns by w D in the body, the mean torque over a step is the sinc of
# w D times the sampled one, and one step multiplies w by (1 - a D sinc(w D)) rather than
# exp(-a D): the log-decay differs from -a t by at most (w0 D)^2 / 6 + a D / 2 relative.

I_BDOT = np.array([0.01, 0.02, 0.02])  # kg m^2
B0, K_B, W0, PERIOD = 3e-5, 1e4, 0.35, 0.1  # T, A m^2 s/T, rad/s (20 deg/s), s


def _bdot_run(t_end, form="classic", gain=K_B):
    return simulate_controlled(I_BDOT, [0.0, 0.0, W0], t_end=t_end, controller=BDot(gain=gain, period=PERIOD, form=form),
                               field=UniformField((B0, 0.0, 0.0)), magnetorquers=Magnetorquers(10.0))


def test_bdot_rate_decays_exponentially_with_time_constant_I_over_k_B2():
    T = 60.0
    run = _bdot_run(T)
    a = K_B * B0**2 / I_BDOT[2]
    np.testing.assert_allclose(run.omega[:, :2], 0.0, atol=1e-15)  # the spin stays about axis 3
    rate_constant = -math.log(run.rate[-1] / W0) / T
    bound = (W0 * PERIOD) ** 2 / 6 + a * PERIOD / 2
    assert abs(rate_constant / a - 1.0) < bound
    assert abs(rate_constant / a - 1.0) > 0.1 * bound  # the held dipole's effect is seen, not hidden
    # the sampled recursion w_{k+1} = w_k (1 - a D sinc(w_k D)) to second order in a D
    w = W0
    for _ in range(len(run.t) - 1):
        w *= 1.0 - a * PERIOD * math.sin(w * PERIOD) / (w * PERIOD)
    assert abs(run.rate[-1] / w - 1.0) < 10 * (a * PERIOD) ** 2 * len(run.t)


def test_normalized_bdot_damps_at_k_over_I_whatever_the_field():
    k = 2e-4  # N m s: tau = -k w across the field, time constant I3 / k = 100 s
    run = _bdot_run(30.0, form="normalized", gain=k)
    a = k / I_BDOT[2]
    assert abs(-math.log(run.rate[-1] / W0) / 30.0 / a - 1.0) < (W0 * PERIOD) ** 2 / 6 + a * PERIOD / 2


def test_bdot_gain_of_avanzini_and_giulietti():
    n = CircularOrbit(500e3).mean_motion
    assert bdot_gain(n, 0.0, 0.01) == pytest.approx(2 * n * 0.01, rel=1e-15)
    assert bdot_gain(n, math.pi / 2, 0.01) == pytest.approx(4 * n * 0.01, rel=1e-15)


# --- MRP feedback: the closed form ---------------------------------------------------------------
# One principal axis, the wheel on it, released at theta0 from rest: (I3 - J) theta'' = -K sigma -
# P theta' with sigma = tan(theta / 4) ~ theta / 4: omega_n = sqrt(K / 4 I_RW), zeta = P / sqrt(K I_RW)
# (Schaub & Junkins ch. 8). With the command held for D the loop sees the torque half a step late:
# to first order in D, P -> P - K D / 8 and I_RW -> I_RW - P D / 2.

I_PD = np.array([0.01, 0.02, 0.03])
J_WHEEL, WN, ZETA, D_PD, TH0 = 1e-4, 0.1, 0.4, 0.2, 0.01


@pytest.fixture(scope="module")
def pd_run():
    rw = ReactionWheels(np.eye(3), inertia=J_WHEEL)
    i_rw = I_PD[2] - J_WHEEL
    K = 4 * i_rw * WN**2
    P = ZETA * math.sqrt(K * i_rw)
    run = simulate_controlled(I_PD, [0.0, 0.0, 0.0], t_end=110.0, attitude0=Rotation.from_rotvec([0.0, 0.0, TH0]),
                              controller=MRPFeedback(K=K, P=P, period=D_PD, moments=I_PD, wheels=rw), wheels=rw)
    return run, K, P, i_rw


def test_mrp_feedback_overshoot_and_settling_match_the_linearised_closed_form(pd_run):
    run, K, P, i_rw = pd_run
    theta = run.attitude.as_rotvec()[:, 2]
    continuous = pd_response(K, P, i_rw)
    assert continuous.natural_frequency == pytest.approx(WN, rel=1e-12)
    assert continuous.damping_ratio == pytest.approx(ZETA, rel=1e-12)
    held = pd_response(K, P - K * D_PD / 8, i_rw - P * D_PD / 2)
    overshoot = -theta.min() / TH0
    assert overshoot == pytest.approx(held.overshoot, rel=(WN * D_PD) ** 2)
    assert abs(overshoot / continuous.overshoot - 1.0) > 0.5 * (WN * D_PD)  # the hold's delay is real
    # 2 % settling: last exceedance of the analytic response vs the simulated one (within a step)
    t = np.linspace(0.0, 110.0, 110001)
    wn, z = held.natural_frequency, held.damping_ratio
    wd = wn * math.sqrt(1 - z * z)
    x = TH0 * np.exp(-z * wn * t) * (np.cos(wd * t) + z / math.sqrt(1 - z * z) * np.sin(wd * t))
    settle_analytic = t[np.nonzero(np.abs(x) > 0.02 * TH0)[0][-1]]
    settle_sim = run.t[np.nonzero(np.abs(theta) > 0.02 * TH0)[0][-1] + 1]
    assert settle_analytic <= settle_sim <= settle_analytic + D_PD
    assert settle_sim < continuous.settling_time  # within the envelope's 2 % time


def test_mrp_feedback_matches_the_exact_sampled_linear_loop(pd_run):
    """The zero-order-hold discretisation of the linearised loop, by the matrix exponential: the
    run differs from it by the MRP's nonlinearity (theta0^2 / 48 relative) and the integrator's error."""
    run, K, P, i_rw = pd_run
    M = expm(np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0 / i_rw], [0.0, 0.0, 0.0]]) * D_PD)
    x, xs = np.array([TH0, 0.0]), []
    for _ in run.t:
        xs.append(x[0])
        x = M[:2, :2] @ x + M[:2, 2] * (-K / 4 * x[0] - P * x[1])
    theta = run.attitude.as_rotvec()[:, 2]
    assert np.max(np.abs(theta - xs)) < 10 * TH0**2 / 48 * TH0


def test_wheels_alone_keep_the_total_momentum_in_the_world(pd_run):
    run = pd_run[0]
    rw = ReactionWheels(np.eye(3), inertia=J_WHEEL, max_torque=1e-4, max_speed=50.0, viscous=1e-7, coulomb=1e-6)
    i_rw = I_PD - J_WHEEL
    K, P = 4 * i_rw[2] * 0.01, 0.4 * math.sqrt(4 * i_rw[2] * 0.01 * i_rw[2])
    tumbling = simulate_controlled(I_PD, [0.05, -0.1, 0.2], t_end=20.0, attitude0=Rotation.from_rotvec([0.3, -0.2, 1.0]),
                                   controller=MRPFeedback(K=K, P=P, period=0.5, moments=I_PD, wheels=rw), wheels=rw,
                                   wheel_speed0=[10.0, -20.0, 5.0])
    L = tumbling.momentum_world
    assert np.abs(tumbling.wheel_torque).max() > 0  # the wheels work (with limits and friction)
    np.testing.assert_allclose(L, L[[0] * len(L)], rtol=0, atol=1e-11 * np.linalg.norm(L[0]))
    np.testing.assert_array_equal(tumbling.impulse_world, 0.0)
    assert np.max(np.abs(run.momentum_world)) < 1e-15  # started at rest: L = 0 throughout


def test_external_impulse_closes_the_budget_with_magnetorquers_and_gravity_gradient():
    orbit = CircularOrbit(500e3, math.radians(97.4), raan=0.3, arg_latitude=1.0)
    I = np.array([0.006, 0.04, 0.042])
    run = simulate_controlled(I, [0.2, -0.1, 0.25], t_end=60.0, controller=BDot(gain=1e5, period=1.0),
                              field=DipoleField(orbit), gravity_gradient=gravity_gradient_of(orbit),
                              magnetorquers=Magnetorquers(0.2), attitude0=Rotation.from_rotvec([0.1, 0.2, 0.3]))
    L0 = np.linalg.norm(run.momentum_world[0])
    assert np.linalg.norm(run.impulse_world[-1]) > 1e-3 * L0  # the torques change L ...
    assert run.budget_error().max() < 1e-10 * L0  # ... by exactly their impulse
    assert np.max(np.abs(run.dipole)) == pytest.approx(0.2)  # the rods saturate


# --- environment ----------------------------------------------------------------------------------

def test_dipole_field_against_its_closed_form_at_the_poles_and_equator():
    """An axial dipole (g11 = h11 = 0): at the equator B = (a/r)^3 |g10| northwards, over a pole
    twice that along the radius (Griffiths eq. 5.89)."""
    g10 = IGRF13_2020[0]
    polar = CircularOrbit(500e3, inclination=math.pi / 2)
    field = DipoleField(polar, coefficients=(g10, 0.0, 0.0))
    a_r3 = (6371.2e3 / polar.radius) ** 3
    quarter = polar.period / 4  # over the north pole
    b_pole = polar.eci_from_world.apply(field.world(quarter))
    np.testing.assert_allclose(b_pole, [0.0, 0.0, 2 * a_r3 * g10], atol=1e-15)  # g10 < 0: into the Earth
    b_eq = polar.eci_from_world.apply(field.world(0.0))
    np.testing.assert_allclose(b_eq, [0.0, 0.0, -a_r3 * g10], atol=1e-15)
    assert math.degrees(DipoleField(polar).dipole_tilt()) == pytest.approx(9.41, abs=0.01)


def test_orbit_elements_give_a_circular_orbit_of_the_right_plane():
    orbit = CircularOrbit(500e3, inclination=0.9, raan=0.4, arg_latitude=0.2)
    t = np.linspace(0.0, orbit.period, 7)
    r, v = orbit.position_eci(t), orbit.velocity_eci(t)
    np.testing.assert_allclose(np.linalg.norm(r, axis=1), orbit.radius, rtol=1e-14)
    h = np.cross(r, v) / np.linalg.norm(np.cross(r, v), axis=1)[:, None]
    np.testing.assert_allclose(h, [[math.sin(0.4) * math.sin(0.9), -math.cos(0.4) * math.sin(0.9), math.cos(0.9)]] * 7,
                               atol=1e-14)  # Vallado: the orbit normal from i and raan
    np.testing.assert_allclose(r[0] / orbit.radius, r[-1] / orbit.radius, atol=1e-12)


def test_mrp_from_quaternion_short_set():
    rot = Rotation.from_rotvec([[0.0, 0.0, 1.0], [0.0, 3.0, 0.0], [2.0, 2.0, 1.0]])
    sigma = mrp_from_quat(rot.as_quat())
    np.testing.assert_allclose(mrp_angle(sigma), rot.magnitude(), rtol=1e-14)
    assert np.all(np.linalg.norm(sigma, axis=1) <= 1.0)


def test_sensors_add_bias_and_seeded_noise():
    s = Sensors(gyro_noise=1e-3, gyro_bias=(1e-2, 0.0, 0.0), attitude="star_tracker", attitude_noise=1e-4, seed=7)
    draws = [s.sample(0.0, np.zeros(3), Rotation.identity(), None, np.zeros(0), s.rng()) for _ in range(2)]
    np.testing.assert_array_equal(draws[0].omega, draws[1].omega)  # reproducible
    many = np.array([s.sample(0.0, np.zeros(3), Rotation.identity(), None, np.zeros(0), rng).omega
                     for rng in [s.rng()] for _ in range(2000)])
    np.testing.assert_allclose(many.mean(axis=0), [1e-2, 0.0, 0.0], atol=5 * 1e-3 / math.sqrt(2000))
    assert np.std(many[:, 1]) == pytest.approx(1e-3, rel=0.1)
    assert draws[0].attitude.magnitude() < 1e-3


def test_a_user_controller_implements_the_interface():
    class Spin:
        period = 0.5

        def __call__(self, t: float, measurement: Measurement) -> Command:
            return Command(wheel_torque=[0.0, 0.0, 1e-4])

    assert isinstance(Spin(), Controller)
    rw = ReactionWheels(np.eye(3), inertia=1e-4)
    run = simulate_controlled(I_PD, [0.0, 0.0, 0.0], t_end=2.0, controller=Spin(), wheels=rw)
    # I_RW w3' = -u: the body turns the other way, w3 = -u t / (I3 - J)
    assert run.omega[-1, 2] == pytest.approx(-1e-4 * 2.0 / (I_PD[2] - 1e-4), rel=1e-10)


@pytest.mark.filterwarnings("ignore::tumble.dynamics.control.sampled.UnstableLoopWarning")  # gains of no loop
@pytest.mark.parametrize(("make", "message"), [
    (lambda: Magnetorquers(-0.2), r"max_dipole\[0\] = -0.2 must be a positive"),
    (lambda: ReactionWheels(np.eye(3), inertia=1e-4, max_speed=0.0), r"max_speed = 0.0 must be a positive number"),
    (lambda: ReactionWheels([[0.0, 0.0, 0.0]], inertia=1e-4), r"axes\[0\] = \[0, 0, 0\] must be a non-zero"),
    (lambda: BDot(gain=1.0, period=1.0, form="fast"), r"form = 'fast' is unknown; allowed: classic, normalized"),
    (lambda: CircularOrbit(500e3, inclination=4.0), r"inclination = 4.0 must lie in \[0, pi\]"),
    # 500 for 500 km (seen 2026-11-30): it ran an "orbit" 500 m up
    (lambda: CircularOrbit(500.0), r"^altitude = 500.0 m is below 100 km, where no orbit lasts \(the air brings it down "
                                   r"within hours\): give metres, 500000 for 500 km$"),
    (lambda: Sensors(attitude="sun"), r"attitude = 'sun' is unknown; allowed: ideal, star_tracker, none"),
    (lambda: MRPFeedback(K=1.0, P=1.0, period=1.0, moments=[1, 2, 3], wheels=ReactionWheels([[1, 0, 0]], inertia=1.0)),
     r"span fewer than 3 directions"),
    (lambda: simulate_controlled([1, 2, 3], [0, 0, 1], t_end=1.0, controller=BDot(1.0, 1.0), magnetorquers=Magnetorquers()),
     r"magnetorquers need a magnetic field"),
    # what a new user tries (seen 2026-11-30): the controller's actuator left out of the run (the
    # wheels failed in numpy's broadcasting; B-dot's dipoles were dropped without a word), a
    # function for a controller, a body for the moments
    (lambda: simulate_controlled(I_PD, [0, 0, 0.1], t_end=1.0, controller=MRPFeedback(
        K=1.0, P=1.0, period=0.5, moments=I_PD, wheels=ReactionWheels(np.eye(3), inertia=1e-4))),
     r"^controller = MRPFeedback drives 3 reaction wheels \(its wheels=\); the run is given none: give "
     r"simulate_controlled\(..., wheels=\) the controller's ReactionWheels$"),
    (lambda: simulate_controlled(I_PD, [0, 0, 0.1], t_end=1.0, controller=MRPFeedback(
        K=1.0, P=1.0, period=0.5, moments=I_PD, wheels=ReactionWheels(np.eye(3), inertia=1e-4)),
        wheels=ReactionWheels(np.eye(3)[:2], inertia=1e-4)), r"drives 3 reaction wheels .* the run is given 2"),
    (lambda: simulate_controlled([1, 2, 3], [0, 0, 1], t_end=2.0, controller=BDot(1.0, 1.0),
                                 field=UniformField((3e-5, 0.0, 0.0))),
     r"^controller = BDot commands magnetic dipoles in the field: give magnetorquers=Magnetorquers\(...\)"),
    (lambda: simulate_controlled([1, 2, 3], [0, 0, 1], t_end=1.0, controller=lambda t, m: Command()),
     r"^controller = <lambda> is not a controller: one has a period \(s\) and is called as controller\(t, measurement\)"),
    (lambda: simulate_controlled(tumble.t_handle(), [0, 0, 1], t_end=1.0, controller=BDot(1.0, 1.0)),
     r"^moments = Body\(.*\) is a body: give its principal moments, body.principal_moments \(kg m\^2\)$"),
])
def test_bad_input_is_refused_with_one_clear_message(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_magnetorquers_unload_the_wheels_while_the_attitude_is_held():
    """The cross-product law (Camillo & Markley 1980): in a 500 km polar orbit the wheels' momentum
    falls as the field turns, while MRP feedback keeps the attitude; the total momentum changes by
    exactly the magnetic impulse (the budget closes)."""
    from tumble.dynamics.control.controllers import MomentumDumping

    I = np.array([10.0, 12.0, 15.0])
    wheels = ReactionWheels(np.eye(3), inertia=0.01)
    pointing = MRPFeedback(K=0.5, P=1.7, period=5.0, moments=I, wheels=wheels)
    orbit = CircularOrbit(500e3, math.radians(90.0))
    run = simulate_controlled(I, [0.0, 0.0, 0.0], t_end=3000.0, controller=MomentumDumping(pointing, gain=2e-3),
                              field=DipoleField(orbit), magnetorquers=Magnetorquers(20.0), wheels=wheels,
                              wheel_speed0=[30.0, -20.0, 25.0])
    h = np.linalg.norm(run.wheel_speed * 0.01, axis=1)  # kg m^2/s, three wheels on the axes
    # measured: 0.439 -> 0.0149 kg m^2/s in 3000 s, pointing within 0.34 deg, budget 6e-16
    assert h[-1] < 0.1 * h[0]
    assert np.degrees(np.max(run.pointing_error(Rotation.identity()))) < 1.0  # the attitude held
    assert float(run.budget_error().max()) < 1e-8 * h[0]
    # the claim is not empty: the attitude loop alone keeps the wheels' momentum
    alone = simulate_controlled(I, [0.0, 0.0, 0.0], t_end=3000.0, controller=pointing, field=DipoleField(orbit),
                                magnetorquers=Magnetorquers(20.0), wheels=wheels, wheel_speed0=[30.0, -20.0, 25.0])
    assert np.linalg.norm(alone.wheel_speed[-1] * 0.01) == pytest.approx(h[0], rel=1e-6)


def test_momentum_dumping_refuses_a_bad_target_momentum_in_one_line():
    from tumble.dynamics.control.controllers import MomentumDumping

    wheels = ReactionWheels(np.eye(3), inertia=0.01)
    pointing = MRPFeedback(K=0.5, P=1.7, period=1.0, moments=[10.0, 12.0, 15.0], wheels=wheels)
    with pytest.raises(ValueError, match=r"h_target = .* \(kg m\^2/s\)"):
        MomentumDumping(pointing, gain=1e-3, h_target=[1.0, 2.0])
    with pytest.raises(ValueError, match=r"gain = -1"):
        MomentumDumping(pointing, gain=-1.0)


def test_the_control_guides_comment_on_the_gains_inclination_holds():
    """docs/control.md: xi_m taken as the orbit's inclination, where a control file takes the magnetic equator's, "the
    dipole's tilt, 9.4 deg (IGRF-13 2020) ... its gain 0.4 % apart here" (it said "~11 deg at most" and "0.1 %",
    against tilt 9.41 deg and 0.40 %: a walkthrough, 2026-12-03)."""
    import math
    from pathlib import Path

    from tumble.dynamics import CircularOrbit, DipoleField
    from tumble.dynamics.control.bdot import bdot_gain
    from tumble.io.controlorbit import geomagnetic_inclination

    guide = (Path(__file__).resolve().parents[1] / "docs" / "control.md").read_text(encoding="utf-8")
    assert "the dipole's tilt, 9.4 deg (IGRF-13 2020): a control file uses that one, its gain 0.4 % apart here" in guide
    orbit = CircularOrbit(altitude=500e3, inclination=math.radians(97.4))
    field = DipoleField(orbit)
    assert math.degrees(field.dipole_tilt()) == pytest.approx(9.4, abs=0.05)
    apart = bdot_gain(orbit.mean_motion, geomagnetic_inclination(orbit, field), 1.0) / bdot_gain(
        orbit.mean_motion, orbit.inclination, 1.0) - 1.0
    assert apart == pytest.approx(0.004, abs=0.0005)
