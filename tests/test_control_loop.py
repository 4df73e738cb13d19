"""The whole closed loop in one compiled call (control/compiled_loop.py) against the Python
controller's path (the same compiled interval, the controller called in Python): the same results
to round-off, for each compiled law; the paths it must not take; the fixed-step and carried-step
methods against the reference within their tolerance."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tumble.dynamics.control import control_kernel as cc
from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.bdot import BDot
from tumble.dynamics.control.controllers import MomentumDumping, MRPFeedback
from tumble.dynamics.environment.magnetic import DipoleField, UniformField
from tumble.dynamics.environment.orbit import CircularOrbit
from tumble.dynamics.models.actuators import Magnetorquers, ReactionWheels
from tumble.dynamics.models.gravity import GravityGradient
from tumble.dynamics.models.orbit_gravity import gravity_gradient_of
from tumble.dynamics.models.sensors import Sensors

ORBIT = CircularOrbit(altitude=500e3, inclination=1.2, raan=0.4, arg_latitude=1.1)
CUBESAT = np.array([0.0067, 0.0419, 0.0419])  # kg m^2
BIG = np.array([10.0, 12.0, 15.0])
C = 1 / np.sqrt(2)


class InPython:
    """A controller of one's own that calls a built-in one: the loop calls it in Python."""

    def __init__(self, controller):
        self.controller, self.period = controller, controller.period

    def reset(self):
        self.controller.reset()

    def __call__(self, t, measurement):
        return self.controller(t, measurement)


def _paths(controller, **kw):
    """The run on the whole-loop kernel and on the Python controller's path (asserting which ran)."""
    calls = []
    original = cc.ControlKernel.run

    def spy(self, *args, **kwargs):
        calls.append(1)
        return original(self, *args, **kwargs)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(cc.ControlKernel, "run", spy)
        whole = simulate_controlled(controller=controller, **kw)
        assert calls == [1], "the whole loop did not run compiled"
        python = simulate_controlled(controller=InPython(controller), **kw)
        assert calls == [1], "the Python controller's path ran the compiled loop"
    return whole, python


def _same(a, b, rel=1e-12):
    for name in ("omega", "wheel_speed", "wheel_torque", "dipole", "field", "momentum_world", "impulse_world"):
        x, y = getattr(a, name), getattr(b, name)
        assert x.shape == y.shape, name
        if y.size:
            assert np.max(np.abs(x - y)) <= rel * max(np.max(np.abs(y)), 1e-300), (name, np.max(np.abs(x - y)))
    q1, q2 = a.attitude.as_quat(), b.attitude.as_quat()
    assert np.max(np.abs(q1 - q2)) <= rel
    assert np.array_equal(a.t, b.t)


def test_mrp_feedback_with_three_wheels_in_the_gravity_gradient_is_the_python_controllers_run():
    rw = ReactionWheels(np.eye(3), inertia=0.05, max_torque=1.0, max_speed=600.0, viscous=1e-5)
    c = MRPFeedback(K=0.5, P=1.7, period=0.5, moments=BIG, wheels=rw)
    whole, python = _paths(c, moments=BIG, omega0=[0.3, -0.5, 0.4], t_end=30.0, wheels=rw,
                           wheel_speed0=[100.0, -50.0, 30.0], gravity_gradient=GravityGradient(orbit_period=5400.0),
                           attitude0=Rotation.from_rotvec([0.5, 0.8, -0.4]), rtol=1e-9)
    _same(whole, python)
    assert whole.budget_error().max() < 1e-9 * np.abs(whole.momentum_world).max()


class SpinUp:
    """A reference turning about world z with a constant angular acceleration ``alpha`` (rad/s^2)
    from ``w0`` (rad/s): its attitude ``R_z(w0 t + alpha t^2 / 2)``, rate and rate derivative."""

    def __init__(self, w0, alpha):
        self.w0, self.alpha = w0, alpha

    def attitude(self, t):
        t = np.asarray(t, float)
        return Rotation.from_rotvec(np.multiply.outer(self.w0 * t + 0.5 * self.alpha * t * t, [0.0, 0.0, 1.0]))

    def rate(self, t):
        t = np.asarray(t, float)
        return np.multiply.outer(self.w0 + self.alpha * t, [0.0, 0.0, 1.0])

    def rate_derivative(self, t):
        return np.multiply.outer(np.full(np.shape(t), self.alpha), [0.0, 0.0, 1.0])


class OneAtATime(SpinUp):
    """The same reference, its methods taking one time only (a float), as a user's own may."""

    def attitude(self, t):
        return Rotation.from_rotvec([0.0, 0.0, self.w0 * float(t) + 0.5 * self.alpha * float(t) ** 2])

    def rate(self, t):
        return np.array([0.0, 0.0, self.w0 + self.alpha * float(t)])

    def rate_derivative(self, t):
        return np.array([0.0, 0.0, self.alpha + 0.0 * float(t)])


@pytest.mark.parametrize("reference", ["nadir", "spin-up", "one time at a time"])
def test_mrp_feedback_tracking_a_moving_reference_is_the_python_controllers_run(reference):
    """The tracking law (Schaub & Junkins sec. 8.3: the rate error against the reference's rate in
    the body, the feed-forward ``I_RW (omega_r' - omega x omega_r)``) on the compiled loop, the
    reference tabulated at the control instants: nadir on a circular orbit in the gravity
    gradient, and a reference that speeds up (its rate derivative in the feed-forward); the
    Python controller's run to round-off, and the body on the reference at the end."""
    from tumble.dynamics.control.pointing import NadirTarget, tracking_error

    rw = ReactionWheels(np.eye(3), inertia=2e-5, max_torque=5e-3)
    target = {"nadir": NadirTarget(ORBIT), "spin-up": SpinUp(0.002, 2e-5), "one time at a time": OneAtATime(0.002, 2e-5)}[reference]
    c = MRPFeedback(K=2e-3, P=2e-2, period=0.5, moments=CUBESAT, wheels=rw, target=target)
    whole, python = _paths(c, moments=CUBESAT, omega0=[0.01, -0.02, 0.015], t_end=300.0, wheels=rw,
                           gravity_gradient=gravity_gradient_of(ORBIT), attitude0=Rotation.from_rotvec([1.0, 0.5, -0.5]))
    _same(whole, python, rel=1e-10)
    end = tracking_error(target, float(whole.t[-1]), whole.attitude[-1], whole.omega[-1])
    start = tracking_error(target, 0.0, whole.attitude[0], whole.omega[0])
    assert np.linalg.norm(end.sigma) < 1e-3 * np.linalg.norm(start.sigma)
    assert np.linalg.norm(end.delta_omega) < 1e-3 * np.linalg.norm(start.delta_omega)


def test_mrp_feedback_with_an_integral_term_and_a_pyramid_is_the_python_controllers_run():
    # no Coulomb friction: through its linear band a round-off in the command may flip one of DOP853's
    # accept-or-reject decisions, and the runs then agree to the tolerance, not to round-off
    rw = ReactionWheels([[C, 0, C], [-C, 0, C], [0, C, C], [0, -C, C]], inertia=1e-4, max_torque=2e-3, viscous=1e-7)
    target = Rotation.from_rotvec([0.1, -0.2, 0.3])
    c = MRPFeedback(K=1e-3, P=1e-2, period=0.25, moments=CUBESAT, wheels=rw, target=target, Ki=0.05,
                    integral_limit=2e-5)
    whole, python = _paths(c, moments=CUBESAT, omega0=[0.01, -0.02, 0.015], t_end=40.0, wheels=rw,
                           attitude0=Rotation.from_rotvec([1.0, 0.5, -0.5]), gravity_gradient=gravity_gradient_of(ORBIT))
    _same(whole, python)


@pytest.mark.parametrize("form, derivative", [("normalized", "gyro"), ("classic", "gyro"), ("classic", "difference")])
def test_bdot_in_the_dipole_field_is_the_python_controllers_run(form, derivative):
    gain = 3e-5 if form == "normalized" else 2e4
    c = BDot(gain=gain, period=1.0, form=form, derivative=derivative)
    rods = Magnetorquers([0.2, 0.1, 0.15], axes=[[1.0, 0.0, 0.0], [0.0, 1.0, 1.0], [0.0, -1.0, 1.0]])
    whole, python = _paths(c, moments=CUBESAT, omega0=[0.2, -0.2, 0.2], t_end=60.0, field=DipoleField(ORBIT, gmst0=0.3),
                           magnetorquers=rods, gravity_gradient=gravity_gradient_of(ORBIT),
                           attitude0=Rotation.from_rotvec([0.3, -0.2, 1.0]))
    _same(whole, python)
    assert np.abs(whole.dipole).max() > 0.0


def test_momentum_dumping_is_the_python_controllers_run():
    rw = ReactionWheels(np.eye(3), inertia=0.01, max_torque=0.05)
    c = MomentumDumping(MRPFeedback(K=0.5, P=1.7, period=1.0, moments=BIG, wheels=rw), gain=1e-3, h_target=[0.1, 0.0, 0.0])
    whole, python = _paths(c, moments=BIG, omega0=[0.001, 0.0, -0.002], t_end=100.0, wheels=rw,
                           wheel_speed0=[50.0, 0.0, 20.0], field=UniformField((1e-5, 2e-5, -3e-5)),
                           magnetorquers=Magnetorquers(5.0))
    _same(whole, python)


def test_noisy_sensors_a_moving_target_and_other_wheels_keep_the_python_path(monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError("the compiled loop ran")

    monkeypatch.setattr(cc.ControlKernel, "run", refuse)
    rw = ReactionWheels(np.eye(3), inertia=1e-4)
    c = MRPFeedback(K=1e-3, P=1e-2, period=0.5, moments=CUBESAT, wheels=rw)
    simulate_controlled(CUBESAT, [0.01, 0.0, 0.0], t_end=2.0, controller=c, wheels=rw, sensors=Sensors(gyro_noise=1e-5))
    other = ReactionWheels(np.eye(3), inertia=2e-4)  # the controller's wheels are not the run's
    simulate_controlled(CUBESAT, [0.01, 0.0, 0.0], t_end=2.0, controller=c, wheels=other)
    bdot = BDot(gain=1e4, period=1.0)
    simulate_controlled(CUBESAT, [0.01, 0.0, 0.0], t_end=2.0, controller=bdot, field=UniformField((0.0, 0.0, 3e-5)),
                        magnetorquers=Magnetorquers(0.2), compiled=False)


def test_fixed_steps_and_carried_steps_meet_the_reference():
    rw = ReactionWheels(np.eye(3), inertia=0.05, max_torque=1.0, max_speed=600.0, viscous=1e-5)
    kw = dict(moments=BIG, omega0=[0.3, -0.5, 0.4], t_end=20.0, wheels=rw, wheel_speed0=[100.0, -50.0, 30.0],
              gravity_gradient=GravityGradient(orbit_period=5400.0), attitude0=Rotation.from_rotvec([0.5, 0.8, -0.4]))
    c = MRPFeedback(K=0.5, P=1.7, period=0.5, moments=BIG, wheels=rw)
    reference = simulate_controlled(controller=c, rtol=1e-13, atol=1e-15, **kw)
    for extra, tol in (({"method": "rk8", "step": 0.25}, 1e-10), ({"method": "rk4", "step": 0.01}, 1e-8),
                       ({"carry_step": True, "rtol": 1e-10}, 1e-8)):
        run = simulate_controlled(controller=c, **kw, **extra)
        assert np.max(np.abs(run.omega - reference.omega)) < tol * np.abs(reference.omega).max(), extra
        assert run.budget_error().max() < 1e-9 * np.abs(run.momentum_world).max(), extra
    with pytest.raises(ValueError, match="need the compiled path"):
        simulate_controlled(controller=c, compiled=False, method="rk8", step=0.1, **kw)
    with pytest.raises(ValueError, match="step = None must be given"):
        simulate_controlled(controller=c, method="rk8", **kw)
