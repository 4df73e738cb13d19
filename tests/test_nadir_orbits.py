"""Nadir along an ellipse and a TLE's orbit: the target frame, its rate and its angular acceleration
against the two-body closed forms computed here, and the closed loop holding it.

Before, ``NadirTarget(KeplerOrbit(...))`` took the orbit's mean motion and turned a circle's frame
in the orbit's ECI world frame: 36-62 deg off nadir on an ellipse of e = 0.1.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.spatial.transform import Rotation

from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.controllers import MRPFeedback
from tumble.dynamics.control.pointing import NadirTarget
from tumble.dynamics.environment.earth import R_EARTH
from tumble.dynamics.environment.ephemeris import KeplerOrbit
from tumble.dynamics.environment.orbit import CircularOrbit
from tumble.dynamics.models.actuators import ReactionWheels
from tumble.dynamics.models.orbit_gravity import gravity_gradient_of

ELLIPSE = KeplerOrbit(8000e3, 0.1, 0.9, raan=0.4, arg_perigee=0.3, mean_anomaly=0.2)
TIMES = np.linspace(0.0, ELLIPSE.period, 37)
ISS_2019 = ("1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991",
            "2 25544  51.6434 242.2052 0007185  10.4577  96.9855 15.50103472202483")


def _true_anomaly(orbit: KeplerOrbit, t: float) -> float:
    """f at t from Kepler's equation solved by bracketing (not the orbit's Newton iteration)."""
    e = orbit.eccentricity
    M = math.remainder(orbit.mean_anomaly + orbit.mean_motion * t, 2 * math.pi)
    E = brentq(lambda E: E - e * math.sin(E) - M, -math.pi - 1, math.pi + 1, xtol=1e-15, rtol=1e-15)
    return 2 * math.atan2(math.sqrt(1 + e) * math.sin(E / 2), math.sqrt(1 - e) * math.cos(E / 2))


def test_on_an_ellipse_the_target_is_nadir_and_turns_at_the_true_anomalys_rate():
    """Two-body closed forms (Vallado sec. 2.2): ``f' = n (1 + e cos f)^2 / (1 - e^2)^(3/2)`` about the
    orbit normal, ``f'' = -2 f'^2 e sin f / (1 + e cos f)``; the nadir axis on -r, the normal on r x v."""
    nadir = NadirTarget(ELLIPSE)
    r, v = ELLIPSE.position_world(TIMES), ELLIPSE.velocity_world(TIMES)
    normal = np.cross(r, v) / np.linalg.norm(np.cross(r, v), axis=1)[:, None]
    R = nadir.attitude(TIMES)
    assert np.allclose(R.apply([1.0, 0.0, 0.0]), -r / np.linalg.norm(r, axis=1)[:, None], rtol=0, atol=1e-14)
    assert np.allclose(R.apply([0.0, 0.0, 1.0]), normal, rtol=0, atol=1e-14)
    e, n = ELLIPSE.eccentricity, ELLIPSE.mean_motion
    f = np.array([_true_anomaly(ELLIPSE, t) for t in TIMES])
    f_dot = n * (1 + e * np.cos(f)) ** 2 / (1 - e * e) ** 1.5
    f_ddot = -2 * f_dot**2 * e * np.sin(f) / (1 + e * np.cos(f))
    assert np.allclose(nadir.rate(TIMES), f_dot[:, None] * normal, rtol=0, atol=1e-12 * n)
    # the central difference's truncation, ~1e-8 of the peak n^2 e
    assert np.allclose(nadir.rate_derivative(TIMES), f_ddot[:, None] * normal, rtol=0, atol=1e-7 * n * n * e)
    assert np.abs(f_ddot).max() > 0.1 * n * n   # the feed-forward is not nothing here


def test_on_a_circle_the_orbits_frame_is_the_circles_closed_form():
    """A Keplerian orbit of e = 0 (world frame ECI) against the circle's R_z(n t) R(0) in its
    orbit-plane frame, turned into ECI: the same frame, rate n about the normal, no acceleration."""
    kepler = KeplerOrbit(7000e3, 0.0, 1.0, raan=0.5, arg_perigee=0.2, mean_anomaly=0.3)
    circle = CircularOrbit(7000e3 - R_EARTH, 1.0, raan=0.5, arg_latitude=0.5)
    axes = {"nadir_axis": [1.0, 1.0, 0.0], "normal_axis": [1.0, -1.0, 0.5]}
    followed, closed = NadirTarget(kepler, **axes), NadirTarget(circle, **axes)
    to_eci = circle.eci_from_world
    t = np.linspace(0.0, 6000.0, 13)
    gap = (followed.attitude(t).inv() * to_eci * closed.attitude(t)).magnitude()
    assert gap.max() < 1e-12
    assert np.allclose(followed.rate(t), to_eci.apply(closed.rate(t)), rtol=0, atol=1e-15)
    assert np.abs(followed.rate_derivative(t)).max() < 1e-9 * kepler.mean_motion**2


def test_a_torque_model_on_an_orbit_gives_its_orbit():
    nadir = NadirTarget(gravity_gradient_of(ELLIPSE))
    assert nadir.mean_motion == ELLIPSE.mean_motion
    assert (nadir.attitude(TIMES).inv() * NadirTarget(ELLIPSE).attitude(TIMES)).magnitude().max() == 0.0


def test_along_a_tles_orbit_the_rate_is_the_frames_own_turn_with_the_normals_drift():
    """SGP4's orbit is perturbed (J2): the normal turns about the radius at ``|r| (a . h) / |h|^2``,
    ~1e-3 of n. The rate is the turn of the target frame between nearby times (an independent
    route), to ~2e-6 of n: SGP4's velocity is not quite its position's derivative (they differ by
    1-2 cm/s for the ISS), and the frame's normal is ``r x v``. Without the radial term it would
    be 1e-3 off."""
    pytest.importorskip("sgp4")
    from tumble.dynamics.environment.ephemeris import TLEOrbit
    iss = TLEOrbit(*ISS_2019)
    nadir = NadirTarget(iss, nadir_axis="major", normal_axis="minor")
    t, h = np.linspace(0.0, iss.period, 25), 0.5
    turned = (nadir.attitude(t + h / 2) * nadir.attitude(t - h / 2).inv()).as_rotvec() / h
    rate = nadir.rate(t)
    n = iss.mean_motion
    assert np.abs(turned - rate).max() < 1e-5 * n
    r, v = iss.position_world(t), iss.velocity_world(t)
    in_plane = np.cross(r, v) / np.sum(r * r, axis=1)[:, None]
    assert np.abs(rate - in_plane).max() > 1e-4 * n   # the normal's drift is there, and measured
    r_hat = r / np.linalg.norm(r, axis=1)[:, None]
    assert np.allclose(R := nadir.attitude(t).apply([0.0, 0.0, 1.0]), -r_hat, rtol=0, atol=1e-14), R


def test_the_loop_holds_nadir_along_an_ellipse_with_the_gravity_gradient():
    """Started on the reference with omega = omega_r, in the ellipse's gravity gradient, the tracking
    law's feed-forward (omega_r' included) keeps the body on nadir; the gradient exerts no torque
    there (principal axes on the orbit's frame), so the momentum of body and wheels keeps its
    world direction and size, and the wheels take up ``I3 (omega_r(0) - omega_r(t))`` about the
    normal as the frame speeds up and slows down (Schaub & Junkins sec. 8.3)."""
    I = np.array([0.03, 0.04, 0.05])
    wheels = ReactionWheels(np.eye(3), inertia=1e-5)
    nadir = NadirTarget(ELLIPSE)
    R0 = nadir.attitude(0.0)
    c = MRPFeedback(K=1e-3, P=2e-2, period=0.5, moments=I, wheels=wheels, target=nadir)
    run = simulate_controlled(I, R0.inv().apply(nadir.rate(0.0)), t_end=1500.0, controller=c, wheels=wheels,
                              attitude0=R0, gravity_gradient=gravity_gradient_of(ELLIPSE))
    assert run.pointing_error(nadir).max() < 1e-7   # rad (8.8e-9): the zero-order hold's error
    H = run.momentum_world
    assert np.abs(H - H[0]).max() < 1e-7 * np.linalg.norm(H[0])
    w_r = np.linalg.norm(nadir.rate(run.t), axis=1)
    stored = np.linalg.norm(run.momentum_world - run.attitude.apply(I * run.omega), axis=1)
    assert np.allclose(stored, I[2] * np.abs(w_r[0] - w_r), rtol=0, atol=1e-5 * I[2] * np.ptp(w_r))
    assert np.ptp(w_r) > 0.2 * ELLIPSE.mean_motion


def test_without_its_angular_acceleration_the_loop_lags():
    """The same run with a reference that gives no ``rate_derivative``: the feed-forward misses
    ``I omega_r'`` and the error grows to the size K sigma ~ I omega_r' (an independent check that
    the derivative is used and right): 3.3e-5 rad against 8.8e-9."""

    class NoAcceleration:
        def __init__(self, target):
            self.attitude, self.rate = target.attitude, target.rate

    I = np.array([0.03, 0.04, 0.05])
    wheels = ReactionWheels(np.eye(3), inertia=1e-5)
    nadir = NadirTarget(ELLIPSE)
    R0 = nadir.attitude(0.0)
    errors = []
    for target in (nadir, NoAcceleration(nadir)):
        c = MRPFeedback(K=1e-3, P=2e-2, period=0.5, moments=I, wheels=wheels, target=target)
        run = simulate_controlled(I, R0.inv().apply(nadir.rate(0.0)), t_end=1500.0, controller=c, wheels=wheels,
                                  attitude0=R0, gravity_gradient=gravity_gradient_of(ELLIPSE))
        errors.append(run.pointing_error(nadir).max())
    assert errors[1] > 300 * errors[0]
