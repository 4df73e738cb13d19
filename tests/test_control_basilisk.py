"""Closed-loop control against Basilisk (``pip install bsk``), side by side (issue 21).

Skipped without Basilisk. The same spacecraft, gains and initial conditions in both
(``benchmarks/basilisk_control.py`` builds the Basilisk side and says how its frames and its
timing are matched to tumble's zero-order hold):

(a) MRP feedback to an inertial target with three reaction wheels (``mrpFeedback``,
    ``rwMotorTorque``, ``reactionWheelStateEffector``, ``attTrackingError``/``inertial3D``):
    agreement to Basilisk's RK4 accuracy (~1e-14 rad/s at 10 ms steps). The initial error is
    60 deg, so neither attitude's MRPs reach the shadow-set switch at |sigma| = 1 (180 deg).
(b) B-dot with magnetorquers in the centred dipole (``MtbEffector``,
    ``magneticFieldCenteredDipole``, the law a Python ``SysModel``): Basilisk holds the field
    ``B_N`` over each dynamics step ``dt``, tumble evaluates it continuously, so the runs differ
    by a first-order term in ``dt``: halving ``dt`` halves the difference, and the Richardson
    extrapolation ``2 b(dt/2) - b(dt)`` of two Basilisk runs agrees with tumble to second order.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.bdot import BDot
from tumble.dynamics.control.controllers import MRPFeedback
from tumble.dynamics.models.actuators import Magnetorquers, ReactionWheels
from tumble.dynamics.environment.magnetic import IGRF13_2020, IGRF_RADIUS, DipoleField
from tumble.dynamics.environment.orbit import CircularOrbit

pytest.importorskip("Basilisk", reason="Basilisk (pip install bsk) is not installed")

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from basilisk_control import field_at, run_detumble, run_pointing
from basilisk_runner import earth_mu

# (a) a 10-15 kg m^2 spacecraft, 0.05 kg m^2 wheels spinning at 100, -50, 30 rad/s, 60 deg off target
MOMENTS = np.array([10.0, 12.0, 15.0])  # kg m^2, hub and wheels locked
JS, SPEED0 = 0.05, np.array([100.0, -50.0, 30.0])  # kg m^2, rad/s
OMEGA0 = np.array([0.01, -0.02, 0.015])  # rad/s
QUAT0 = Rotation.from_rotvec(math.radians(60.0) * np.array([1.0, 2.0, -1.0]) / math.sqrt(6.0)).as_quat()
TARGET = Rotation.from_rotvec([0.0, 0.0, 0.3]).as_quat()
K, P, PERIOD, T_POINT = 0.5, 1.7, 0.5, 60.0  # N m, N m s, s, s: omega_n ~ 0.1 rad/s, zeta ~ 0.7


def test_mrp_feedback_with_reaction_wheels_agrees_with_basilisk():
    b = run_pointing(MOMENTS, OMEGA0, QUAT0, js=JS, wheel_speed0=SPEED0, K=K, P=P, target_quat=TARGET,
                     period=PERIOD, dt=0.01, t_end=T_POINT)
    rw = ReactionWheels(np.eye(3), inertia=JS)
    ctrl = MRPFeedback(K=K, P=P, period=PERIOD, moments=MOMENTS, wheels=rw, target=TARGET)
    run = simulate_controlled(MOMENTS, OMEGA0, t_end=T_POINT, attitude0=QUAT0, wheels=rw, wheel_speed0=SPEED0,
                              controller=ctrl)
    np.testing.assert_allclose(b.times, run.t, rtol=0, atol=1e-12)
    # the commands of the first step, before any integration: the two control laws are the same
    np.testing.assert_allclose(b.motor_torque[0], run.wheel_torque[0], rtol=1e-13, atol=0)
    assert np.max(np.abs(b.omega - run.omega)) < 1e-12  # rad/s (measured 7e-14; |omega| up to 0.04)
    angle = (Rotation.from_quat(b.quat) * run.attitude.inv()).magnitude()
    assert np.max(angle) < 1e-11  # rad (measured 1e-12)
    assert np.max(np.abs(b.wheel_speed - run.wheel_speed)) < 1e-9  # rad/s of ~100 (measured 1.2e-10)
    # the loop does its work: 60 deg down to under 2 deg in 60 s
    error = run.pointing_error(Rotation.from_quat(TARGET))
    assert error[0] > math.radians(59.0) and error[-1] < math.radians(2.0)


# (b) a 3U CubeSat (I_min about its long axis) at 20 deg/s in a 500 km sun-synchronous orbit
I_CUBE = np.array([0.0067, 0.0419, 0.0419])  # kg m^2
W_CUBE = np.array([0.2, -0.15, 0.25])  # rad/s
GAIN, MAX_DIPOLE, T_DETUMBLE = 1e5, 0.5, 100.0  # A m^2 s/T, A m^2 (clips the first commands), s


@pytest.fixture(scope="module")
def detumble_setup():
    mu = earth_mu()
    orbit = CircularOrbit(altitude=500e3, inclination=math.radians(97.4), raan=0.5, arg_latitude=0.3, mu=mu)
    return orbit, DipoleField(orbit, earth_rotation=False), Rotation.from_euler("xyz", [0.3, -0.2, 0.5])


def test_centred_dipole_is_tumbles_igrf_dipole(detumble_setup):
    orbit, field, _ = detumble_setup
    for t in (0.0, 700.0, 2100.0):
        expected = orbit.eci_from_world.apply(field.world(t))
        np.testing.assert_allclose(field_at(orbit.position_eci(t), coefficients=IGRF13_2020, radius=IGRF_RADIUS),
                                   expected, rtol=1e-13, atol=0)


def test_bdot_detumble_agrees_with_basilisk_to_first_order_in_its_held_field(detumble_setup):
    orbit, field, att0 = detumble_setup
    run = simulate_controlled(I_CUBE, W_CUBE, t_end=T_DETUMBLE, attitude0=att0, controller=BDot(GAIN, period=1.0),
                              field=field, magnetorquers=Magnetorquers(MAX_DIPOLE))
    assert np.max(np.abs(run.dipole)) == pytest.approx(MAX_DIPOLE, rel=1e-12)  # the rods clip
    assert run.rate[-1] < 0.85 * run.rate[0]
    b = {dt: run_detumble(I_CUBE, W_CUBE, (orbit.eci_from_world * att0).as_quat(), r_eci=orbit.position_eci(0.0),
                          v_eci=orbit.velocity_eci(0.0), mu=orbit.mu, gain=GAIN, max_dipole=MAX_DIPOLE,
                          coefficients=IGRF13_2020, radius=IGRF_RADIUS, period=1.0, dt=dt, t_end=T_DETUMBLE)
         for dt in (0.02, 0.01)}
    coarse = np.max(np.abs(b[0.02].omega - run.omega))
    fine = np.max(np.abs(b[0.01].omega - run.omega))
    assert 1.9 < coarse / fine < 2.1  # first order in dt: the field held over each step
    assert fine < 2e-5 * np.max(np.abs(run.omega))  # the held field's 2 n dt / 2 ~ 1e-5 of the torque
    extrapolated = 2.0 * b[0.01].omega - b[0.02].omega
    assert np.max(np.abs(extrapolated - run.omega)) < 0.01 * fine  # the rest is second order
    angle = ((orbit.eci_from_world.inv() * Rotation.from_quat(b[0.01].quat)) * run.attitude.inv()).magnitude()
    assert np.max(angle) < 1e-4  # rad: the attitude, first order alike
