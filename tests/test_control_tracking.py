"""MRP feedback to a moving (nadir) reference and its integral term: closed-form checks (issue 21, item 3)."""

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.spatial.transform import Rotation

from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.controllers import MomentumDumping, MRPFeedback, pd_response
from tumble.dynamics.models.actuators import Command, Magnetorquers, ReactionWheels
from tumble.dynamics.models.orbit_gravity import gravity_gradient_of
from tumble.dynamics.environment.magnetic import UniformField
from tumble.dynamics.environment.orbit import CircularOrbit
from tumble.dynamics.models.sensors import Measurement
from tumble.dynamics.control.pointing import NadirTarget
from tumble.dynamics.special.mrp import mrp_from_quat

ROOT = Path(__file__).resolve().parents[1]
ORBIT = CircularOrbit(altitude=500e3)
I = np.array([0.03, 0.04, 0.05])
RW = ReactionWheels(np.eye(3), inertia=1e-5)


def _signed_angle(c, run, axis):
    """Signed error angle about one principal axis, 4 atan(sigma_axis), rad."""
    return np.array([4.0 * math.atan(c.error(run.attitude[i], float(t))[axis]) for i, t in enumerate(run.t)])


def test_nadir_reference_frame():
    """R(t) = R_z(n t) R(0): the nadir axis on -radius, the normal axis on r x v, omega_r = n z."""
    nadir = NadirTarget(ORBIT, nadir_axis="minor", normal_axis="intermediate")
    t = np.linspace(0.0, ORBIT.period, 7)
    r = ORBIT.position_world(t)
    R = nadir.attitude(t)
    assert np.allclose(R.apply([1.0, 0.0, 0.0]), -r / ORBIT.radius, atol=1e-15)
    normal = np.cross(r, ORBIT.velocity_world(t))
    assert np.allclose(R.apply([0.0, 1.0, 0.0]), normal / np.linalg.norm(normal, axis=1)[:, None], atol=1e-15)
    # omega_r from the frame's own motion: (R(t + h) R(t)^T) ~ exp(omega_r h)
    h = 1e-2
    w = (nadir.attitude(t + h) * R.inv()).as_rotvec() / h
    assert np.allclose(w, nadir.rate(t), rtol=1e-9, atol=1e-15)
    with pytest.raises(ValueError, match="orbit.mean_motion"):
        NadirTarget(object())


def test_on_the_reference_it_stays_there():
    """(a) Started on the nadir reference (the minor axis down, the major on the orbit normal) with
    omega = omega_r, in the gravity gradient, it stays on it to the integrator's accuracy: the law
    damps delta_omega, not omega (a fixed-target law would brake the orbital rate)."""
    nadir = NadirTarget(ORBIT)
    R0 = nadir.attitude(0.0)
    c = MRPFeedback(K=1e-3, P=2e-2, period=0.5, moments=I, wheels=RW, target=nadir)
    run = simulate_controlled(I, R0.inv().apply(nadir.rate(0.0)), t_end=600.0, controller=c, wheels=RW,
                              attitude0=R0, gravity_gradient=gravity_gradient_of(ORBIT))
    assert run.pointing_error(nadir).max() < 1e-10
    assert np.abs(run.wheel_speed).max() < 1e-8   # the wheels did nothing


def test_on_a_reference_that_speeds_up_the_wheels_give_its_angular_acceleration():
    """(a'') On a reference whose rate grows (omega_r' != 0), turning with it, the errors are zero
    and the required torque is the feed-forward alone, ``L_r = I_RW omega_r' + omega x (I omega +
    h)`` with ``I_RW`` the body's inertia less the wheels' axial one (Schaub & Junkins sec. 8.3):
    the wheels' command ``-L_r``, written out here with numpy. On the compiled loop, started on the
    reference, the body keeps to it to the zero-order hold's error."""
    class SpinUp:   # R_z(w0 t + alpha t^2 / 2) R0, its rate and rate derivative about world z
        w0, alpha, R0 = 0.003, 4e-5, Rotation.from_rotvec([0.2, -0.1, 0.3])

        def attitude(self, t):
            t = np.asarray(t, float)
            return Rotation.from_rotvec(np.multiply.outer(self.w0 * t + 0.5 * self.alpha * t * t, [0.0, 0.0, 1.0])) * self.R0

        def rate(self, t):
            return np.multiply.outer(self.w0 + self.alpha * np.asarray(t, float), [0.0, 0.0, 1.0])

        def rate_derivative(self, t):
            return np.multiply.outer(np.full(np.shape(t), self.alpha), [0.0, 0.0, 1.0])

    ref, t = SpinUp(), 50.0
    R = ref.attitude(t)
    w = R.inv().apply(ref.rate(t))
    spin = np.array([3.0, -2.0, 1.0])   # rad/s: the wheels' momentum h = J spin
    c = MRPFeedback(K=1e-3, P=2e-2, period=0.5, moments=I, wheels=RW, target=ref)
    u = c(t, Measurement(t, w, None, R, spin)).wheel_torque
    I_rw = np.diag(I) - RW.locked_axial()
    h = RW.momentum(spin)
    expected = -(I_rw @ R.inv().apply(ref.rate_derivative(t)) + np.cross(w, I * w + h))
    np.testing.assert_allclose(u, expected, rtol=1e-12, atol=1e-18)
    assert np.linalg.norm(I_rw @ R.inv().apply(ref.rate_derivative(t))) > 10 * np.linalg.norm(np.cross(w, I * w + h))

    run = simulate_controlled(I, ref.attitude(0.0).inv().apply(ref.rate(0.0)), t_end=120.0, controller=c, wheels=RW,
                              attitude0=ref.attitude(0.0))
    lag = 4 * np.max(I) * ref.alpha / 1e-3   # rad: the steady error I alpha = K sigma, sigma ~ theta / 4, without omega_r'
    assert run.pointing_error(ref).max() < 1e-3 * lag


def test_feed_forward_off_the_principal_axes():
    """(a') Axes that are not principal: omega_r is not a principal axis and the wheels must make
    omega x I omega. With the feed-forward the error is the zero-order hold's alone (the wheels'
    momentum, and omega x h with it, changes within a period): it halves with the period; without
    it the error is ~ 4 |omega x I omega| / K."""
    nadir = NadirTarget(ORBIT, nadir_axis=[1.0, 1.0, 0.0], normal_axis=[1.0, -1.0, 1.0])
    R0 = nadir.attitude(0.0)
    w0 = R0.inv().apply(nadir.rate(0.0))
    final = {}
    for gyroscopic, period in ((True, 0.5), (True, 0.25), (False, 0.5)):
        c = MRPFeedback(K=1e-3, P=2e-2, period=period, moments=I, wheels=RW, target=nadir, gyroscopic=gyroscopic)
        run = simulate_controlled(I, w0, t_end=300.0, controller=c, wheels=RW, attitude0=R0)
        final[gyroscopic, period] = run.pointing_error(nadir)[-1]
    tau = np.linalg.norm(np.cross(w0, I * w0))
    zoh = 4 * np.linalg.norm(np.cross(w0, np.cross(w0, I * w0))) * 0.5 / 2 / 1e-3   # 4 |d(omega x h)/dt| dt / 2 / K
    assert final[True, 0.5] < 2 * zoh
    assert final[True, 0.5] / final[True, 0.25] == pytest.approx(2.0, rel=0.05)
    assert final[False, 0.5] == pytest.approx(4 * tau / 1e-3, rel=0.1)


def test_small_error_decays_like_the_linearised_pd_loop():
    """(b) 0.02 rad off the nadir reference about the orbit normal (the major axis, I3): the error
    follows I_RW theta'' + P theta' + (K / 4) theta = 0 (pd_response's overshoot and settling)."""
    nadir = NadirTarget(ORBIT)
    I_rw = I[2] - 1e-5
    K = 1e-3
    P = 0.5 * math.sqrt(K * I_rw)   # zeta = 0.5
    theta0 = 0.02
    R0 = nadir.attitude(0.0) * Rotation.from_rotvec([0.0, 0.0, theta0])
    c = MRPFeedback(K=K, P=P, period=0.05, moments=I, wheels=RW, target=nadir)
    run = simulate_controlled(I, R0.inv().apply(nadir.rate(0.0)), t_end=200.0, controller=c, wheels=RW, attitude0=R0)
    theta = _signed_angle(c, run, 2)
    r = pd_response(K, P, I_rw)
    zeta, wn = r.damping_ratio, r.natural_frequency
    wd = wn * math.sqrt(1 - zeta**2)
    linear = theta0 * np.exp(-zeta * wn * run.t) * (np.cos(wd * run.t) + zeta / math.sqrt(1 - zeta**2) * np.sin(wd * run.t))
    assert np.abs(theta - linear).max() < 5e-3 * theta0   # the zero-order hold's delay (wn dt / 2 ~ 0.4 %)
    assert -theta.min() / theta0 == pytest.approx(r.overshoot, rel=0.02)
    settled = run.t[np.nonzero(np.abs(theta) > 0.02 * theta0)[0][-1] + 1]
    assert settled <= r.settling_time + 0.05
    assert settled > 0.75 * r.settling_time   # the envelope bound is tight to within a half swing


class _ConstantDipole:
    """MRP feedback plus a constant magnetorquer dipole: a constant disturbance in a uniform field."""

    def __init__(self, mrp, dipole):
        self.mrp, self.dipole, self.period = mrp, np.asarray(dipole, float), mrp.period

    def reset(self):
        self.mrp.reset()

    def __call__(self, t, m):
        return Command(dipole=self.dipole, wheel_torque=self.mrp(t, m).wheel_torque)


@pytest.mark.parametrize(("Ki", "limit"), [(0.0, math.inf), (0.05, math.inf), (0.05, 1e-6)])
def test_integral_term_removes_the_steady_error(Ki, limit):
    """(c) A dipole m y in a field B x makes the torque -m B cos(theta) z at an error theta about z.
    PD settles where K tan(theta / 4) = -m B cos(theta); the integral term takes the error to zero;
    an integral limit L below m B leaves K tan(theta / 4) = -(m B cos(theta) - L)."""
    K, mB = 4e-3, 3e-6
    c = MRPFeedback(K=K, P=math.sqrt(K * I[2]), period=0.5, moments=I, wheels=RW, Ki=Ki, integral_limit=limit)
    run = simulate_controlled(I, np.zeros(3), t_end=800.0, controller=_ConstantDipole(c, [0.0, 0.1, 0.0]),
                              field=UniformField((3e-5, 0.0, 0.0)), magnetorquers=Magnetorquers(1.0), wheels=RW)
    theta = _signed_angle(c, run, 2)[-1]
    held = 0.0 if Ki == 0.0 else min(limit, mB)
    expected = brentq(lambda th: K * math.tan(th / 4) + mB * math.cos(th) - held, -1.0, 1.0, xtol=1e-16)
    pd = brentq(lambda th: K * math.tan(th / 4) + mB * math.cos(th), -1.0, 1.0, xtol=1e-16)
    assert pd == pytest.approx(-4 * mB / K, rel=1e-3)   # ~ tau / K' with K' = K / 4 per radian
    if Ki == 0.0 or limit < mB:
        assert theta == pytest.approx(expected, rel=1e-7)
    else:
        assert abs(theta) < 1e-6 * abs(pd)


def test_fixed_target_without_integral_is_todays_law_to_the_bit():
    """(d) Ki = 0 and a fixed target: u = -G^+ (-K sigma - P omega + omega x (I omega + h)), as before."""
    rng = np.random.default_rng(7)
    wheels = ReactionWheels(rng.normal(size=(4, 3)), inertia=2e-5)
    target = Rotation.random(random_state=3)
    c = MRPFeedback(K=1.1e-3, P=6e-3, period=0.5, moments=[0.0067, 0.0419, 0.0419], wheels=wheels, target=target)
    pinv = np.linalg.pinv(wheels.axes.T)
    for i in range(50):
        att = Rotation.random(random_state=100 + i)
        w, s = rng.normal(scale=0.05, size=3), rng.normal(scale=100.0, size=4)
        sigma = np.asarray(mrp_from_quat((target.inv() * att).as_quat()), float)
        L_r = -1.1e-3 * sigma - 6e-3 * w
        L_r = L_r + np.cross(w, np.asarray(c.moments) * w + wheels.momentum(s))
        got = c(float(i), Measurement(float(i), w, None, att, s)).wheel_torque
        assert np.array_equal(got, -pinv @ L_r)


def test_reset_reaches_the_integral_through_momentum_dumping():
    c = MRPFeedback(K=1e-3, P=2e-2, period=0.5, moments=I, wheels=RW, Ki=0.1)
    md = MomentumDumping(c, gain=1e-3)
    m = Measurement(0.0, np.zeros(3), np.array([0.0, 0.0, 3e-5]), Rotation.from_rotvec([0.1, 0.0, 0.0]), np.zeros(3))
    first = md(0.0, m).wheel_torque
    assert not np.array_equal(md(0.5, m).wheel_torque, first)
    md.reset()
    assert np.array_equal(md(1.0, m).wheel_torque, first)


def test_bad_gains_are_one_clear_error():
    with pytest.raises(ValueError, match="Ki"):
        MRPFeedback(K=1e-3, P=2e-2, period=0.5, moments=I, wheels=RW, Ki=-1.0)
    with pytest.raises(ValueError, match="integral_limit"):
        MRPFeedback(K=1e-3, P=2e-2, period=0.5, moments=I, wheels=RW, integral_limit=0.0)


def test_cli_runs_the_nadir_example_briefly(tmp_path, capsys):
    """examples/control/nadir.toml through the CLI: the summary's error is to the target at each time
    (30 deg at the start; after 60 s well under the n t = 3.8 deg the orbiting frame has turned)."""
    from tumble.cli import main

    code = main(["simulate", str(ROOT / "examples" / "control" / "nadir.toml"), "--t-end", "60", "--out", str(tmp_path)])
    assert code == 0, capsys.readouterr().err
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["pointing_error_initial"] == pytest.approx(math.radians(30.0), abs=1e-12)
    assert summary["pointing_error_final"] < 0.02 < ORBIT.mean_motion * 60.0
    assert (tmp_path / "attitude_error.png").exists()


def _scenario(control, orbit=None):
    from tumble.io.bodyfile import body_from_table
    from tumble.io.controlfile import control_scenario_from_table
    body = body_from_table({"name": "cube", "parts": [{"kind": "box", "mass": 4.0, "size": [0.1, 0.1, 0.34]}]})
    table = {"initial": {"omega": [0.0, 0.0, 0.0]}, "simulation": {"t_end": 10.0},
             "actuators": {"wheels": {"inertia": 2e-5}},
             "control": {"kind": "mrp_pd", "period": 0.5, "K": 1e-3, "P": 6e-3, **control}}
    if orbit is not None:
        table["orbit"] = orbit
    return control_scenario_from_table(table, body)


def test_scenario_keys_for_nadir_and_the_integral_term():
    s = _scenario({"target": "nadir", "Ki": 0.01, "integral_limit": 1e-5, "nadir_axis": [0.0, 0.0, 1.0],
                   "normal_axis": "intermediate"}, {"altitude": 500e3})
    c = s.controller()
    assert isinstance(c.target, NadirTarget) and s.target is c.target and (c.Ki, c.integral_limit) == (0.01, 1e-5)
    # design z is the minor (principal 1) axis of this body: on nadir at t = 0
    assert np.allclose(c.target.attitude(0.0).apply([1.0, 0.0, 0.0]), [-1.0, 0.0, 0.0])
    cases = [({"target": "nadir"}, None, 'control: target = "nadir" needs an \\[orbit\\]'),
             ({"target": "zenith"}, None, "control: target = 'zenith' is unknown"),
             ({"nadir_axis": "minor"}, None, 'control: nadir_axis goes with target = "nadir" only'),
             ({"Ki": -0.1}, None, "control: Ki = -0.1")]
    for control, orbit, message in cases:
        with pytest.raises(ValueError, match=message):
            _scenario(control, orbit)
    from tumble.dynamics import KeplerOrbit
    from tumble.dynamics.models.sensors import Sensors
    from tumble.io.controlspec import parse_control
    # along an ellipse nadir follows the orbit (its world frame ECI), not the circle of its mean motion
    orbit = KeplerOrbit(7.2e6, 0.05, 0.9, arg_perigee=0.4)
    spec = parse_control({"kind": "mrp_pd", "period": 0.5, "K": 1e-3, "P": 6e-3, "target": "nadir"}, body=s.body,
                         orbit=orbit, field=None, magnetorquers=None, wheels=s.wheels, sensors=Sensors(),
                         principal_to_design=Rotation.identity())
    r = orbit.position_world(1000.0)
    assert np.allclose(spec.target.attitude(1000.0).apply([1.0, 0.0, 0.0]), -r / np.linalg.norm(r), atol=1e-14)


def test_detumble_point_points_at_nadir_with_the_integral_term():
    from tumble.dynamics import DipoleField
    from tumble.dynamics.models.sensors import Sensors
    from tumble.io.controlspec import build_controller, parse_control
    s = _scenario({}, None)
    orbit = CircularOrbit(altitude=500e3, inclination=1.7)
    spec = parse_control({"kind": "detumble_point", "period": 1.0, "switch_rate": 0.0175, "dwell": 60.0,
                          "point": {"K": 1e-3, "P": 6e-3, "target": "nadir", "Ki": 0.01, "dumping_gain": 1e-3}},
                         body=s.body, orbit=orbit, field=DipoleField(orbit), magnetorquers=Magnetorquers(0.2),
                         wheels=s.wheels, sensors=Sensors(), principal_to_design=Rotation.identity())
    mission = build_controller(spec, s.body, s.wheels)
    assert isinstance(spec.target, NadirTarget) and spec.target.mean_motion == orbit.mean_motion
    assert mission.point.pointing.target is spec.target and mission.point.pointing.Ki == 0.01


def test_figures_and_page_measure_the_error_to_the_moving_target():
    """The attitude-error figure and the page's curve are run.pointing_error(nadir): zero on the
    reference, where the error to the frame it started in grows as n t."""
    pytest.importorskip("matplotlib")
    from tumble.viz.control import figure_attitude_error
    from tumble.viz.control_page import control_page_data
    nadir = NadirTarget(0.01)
    R0 = nadir.attitude(0.0)
    c = MRPFeedback(K=1e-3, P=2e-2, period=0.5, moments=I, wheels=RW, target=nadir)
    run = simulate_controlled(I, R0.inv().apply(nadir.rate(0.0)), t_end=20.0, controller=c, wheels=RW, attitude0=R0)
    assert np.allclose(run.pointing_error(R0), 0.01 * run.t, atol=1e-9)
    curve = control_page_data(run, frames=5, wheel_axes=RW.axes, target=nadir)["curve"]
    assert curve["name"] == "attitude error" and max(curve["y"]) < 1e-9
    line = figure_attitude_error(run, nadir).axes[0].lines[0]
    assert np.array_equal(line.get_ydata(), np.degrees(run.pointing_error(nadir)))
