"""A disturbance torque in the closed loop (``simulate_controlled(..., torque=...)``): the steady
errors of PD and PID pointing against their closed forms, the momentum budget and the impulse of a
world torque, the compiled and scipy paths step for step, and what runs where."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from tumble.dynamics import ConstantTorque
from tumble.dynamics.control.controllers import MRPFeedback
from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.models.actuators import ReactionWheels

I = np.array([0.03, 0.04, 0.05])
RW = ReactionWheels(np.eye(3), inertia=1e-5)
K = 4e-3
TAU = 2e-6  # N m about the major axis, fixed in the body: a thruster's leak, a residual dipole's mean


def _pointing(Ki: float = 0.0, limit: float = math.inf) -> MRPFeedback:
    return MRPFeedback(K=K, P=math.sqrt(K * I[2]), period=0.5, moments=I, wheels=RW, Ki=Ki, integral_limit=limit)


def _error_about(c: MRPFeedback, run, axis: int) -> float:
    """The final error angle about one principal axis, 4 atan(sigma_axis), rad."""
    return 4.0 * math.atan(c.error(run.attitude[-1], float(run.t[-1]))[axis])


@pytest.mark.parametrize(("Ki", "limit"), [(0.0, math.inf), (0.05, math.inf), (0.05, 1e-6)])
def test_pointing_under_a_constant_body_torque_settles_where_the_law_says(Ki, limit):
    """MRP feedback (Schaub & Junkins, Analytical Mechanics of Space Systems, sec. 8.4) holds
    tau + u = 0 at rest, with u = -K sigma - z: PD settles where K tan(theta / 4) = tau
    (theta ~ 4 tau / K); the integral term z takes the error to zero; an integral held at L below
    tau leaves K tan(theta / 4) = tau - L."""
    c = _pointing(Ki, limit)
    run = simulate_controlled(I, np.zeros(3), t_end=800.0, controller=c, wheels=RW,
                              torque=ConstantTorque((0.0, 0.0, TAU)))
    theta = _error_about(c, run, 2)
    held = 0.0 if Ki == 0.0 else min(limit, TAU)
    expected = brentq(lambda th: K * math.tan(th / 4) - (TAU - held), -1.0, 1.0, xtol=1e-16)
    if held < TAU:
        assert expected == pytest.approx(4 * (TAU - held) / K, rel=1e-6)
        assert theta == pytest.approx(expected, rel=1e-7)
    else:
        assert abs(theta) < 1e-6 * 4 * TAU / K
    assert abs(run.omega[-1]).max() < 1e-9  # at rest: the wheels hold the torque
    # at rest the major-axis wheel holds the whole impulse about z: J s = tau t (measured 1e-15 off)
    assert run.wheel_speed[-1, 2] == pytest.approx(TAU * 800.0 / 1e-5, rel=1e-9)


def test_world_torque_impulse_and_budget():
    """A world-fixed torque's impulse is tau t exactly; L_world changes by the impulse alone (the
    wheels' momentum counted), here also under a body torque and the controller."""
    world, body = (1e-6, -2e-6, 5e-7), (0.0, 1e-6, 0.0)
    run = simulate_controlled(I, [0.01, -0.02, 0.03], t_end=60.0, controller=_pointing(), wheels=RW,
                              torque=[ConstantTorque(world, "world"), ConstantTorque(body)])
    free = simulate_controlled(I, [0.01, -0.02, 0.03], t_end=60.0, controller=_pointing(), wheels=RW,
                               torque=ConstantTorque(world, "world"))
    np.testing.assert_allclose(free.impulse_world[-1], np.array(world) * 60.0, rtol=1e-9)
    for r in (run, free):
        budget = r.momentum_world - r.momentum_world[0] - r.impulse_world
        assert np.max(np.abs(budget)) < 1e-9 * np.max(np.abs(r.impulse_world))
    assert np.max(np.abs(run.impulse_world[-1] - free.impulse_world[-1])) > 1e-5  # the body torque acted too


def test_compiled_and_scipy_paths_take_the_same_steps():
    """The compiled loop's disturbance terms and scipy's right-hand side (every term from Python):
    the same steps, so round-off apart, not the tolerance."""
    kw = dict(t_end=30.0, controller=_pointing(), wheels=RW,
              torque=[ConstantTorque((1e-6, 0.0, -1e-6)), ConstantTorque((0.0, 2e-6, 0.0), "world")])
    fast = simulate_controlled(I, [0.01, -0.02, 0.03], compiled=True, **kw)
    slow = simulate_controlled(I, [0.01, -0.02, 0.03], compiled=False, **kw)
    np.testing.assert_allclose(fast.omega, slow.omega, rtol=0, atol=1e-12 * np.max(np.abs(slow.omega)))
    np.testing.assert_allclose(fast.impulse_world, slow.impulse_world, rtol=0,
                               atol=1e-12 * np.max(np.abs(slow.impulse_world)))


def test_a_python_disturbance_runs_on_scipys_path():
    """A torque of one's own (here viscous, -c omega) is called from Python; compiled=True names it.
    The energy it takes out: the budget L_world - impulse still closes."""
    drag = lambda t, omega, attitude: -1e-4 * np.asarray(omega)  # noqa: E731
    run = simulate_controlled(I, [0.01, -0.02, 0.03], t_end=20.0, controller=_pointing(), wheels=RW, torque=drag)
    budget = run.momentum_world - run.momentum_world[0] - run.impulse_world
    assert np.max(np.abs(run.impulse_world[-1])) > 1e-7
    assert np.max(np.abs(budget)) < 1e-8 * np.max(np.abs(run.impulse_world))
    with pytest.raises(ValueError, match=r"^compiled=True needs built-in models; torque = FunctionTorque "
                                         r"\(ConstantTorque in the body or the world frame, a ResidualDipole in the run's "
                                         r"field, or their sum\)"):
        simulate_controlled(I, [0.01, -0.02, 0.03], t_end=1.0, controller=_pointing(), wheels=RW, torque=drag,
                            compiled=True)


def test_a_disturbance_acts_beside_the_magnetorquers_dipole():
    """With a field the compiled loop's m x B term replaced the disturbance instead of adding to it:
    B-dot's run in a field took no disturbance compiled (the same run with and without it) while
    scipy's path took it (0.09 rad/s apart after 60 s). Now both take it, step for step, and the
    momentum budget closes with it."""
    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.environment.magnetic import UniformField
    from tumble.dynamics.models.actuators import Magnetorquers

    moments = [0.0067, 0.0419, 0.0419]
    kw = dict(t_end=60.0, controller=BDot(gain=3e-5, period=1.0, form="normalized"), field=UniformField((2e-5, 1e-5, -3e-5)),
              magnetorquers=Magnetorquers(0.2), torque=[ConstantTorque((1e-5, 0.0, 0.0)),
                                                        ConstantTorque((0.0, -4e-6, 2e-6), "world")])
    fast = simulate_controlled(moments, [0.05, -0.02, 0.03], compiled=True, **kw)
    slow = simulate_controlled(moments, [0.05, -0.02, 0.03], compiled=False, **kw)
    free = simulate_controlled(moments, [0.05, -0.02, 0.03], compiled=True, **{**kw, "torque": None})
    np.testing.assert_allclose(fast.omega, slow.omega, rtol=0, atol=1e-12 * np.max(np.abs(slow.omega)))
    assert np.max(np.abs(fast.omega - free.omega)) > 1e-2
    budget = fast.momentum_world - fast.momentum_world[0] - fast.impulse_world
    assert np.max(np.abs(budget)) < 1e-9 * np.max(np.abs(fast.impulse_world))


def test_a_residual_dipole_in_the_runs_field_runs_compiled_beside_b_dot():
    """A ResidualDipole in the run's own field is a disturbance of the compiled loop (its
    ``P[27:30]``, beside the rods' dipole in ``m x B``): step for step scipy's path, and it acts
    (B-dot's detumble ends elsewhere without it). In another field it runs on scipy's path, and
    ``compiled=True`` names it."""
    from tumble.dynamics import ResidualDipole
    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.environment.magnetic import UniformField
    from tumble.dynamics.models.actuators import Magnetorquers

    moments, w0 = [0.0067, 0.0419, 0.0419], [0.05, -0.02, 0.03]
    field = UniformField((2e-5, 1e-5, -3e-5))
    kw = dict(t_end=60.0, controller=BDot(gain=3e-5, period=1.0, form="normalized"), field=field, magnetorquers=Magnetorquers(0.2))
    residual = ResidualDipole((0.05, -0.02, 0.01), field)
    fast = simulate_controlled(moments, w0, compiled=True, torque=residual, **kw)
    slow = simulate_controlled(moments, w0, compiled=False, torque=residual, **kw)
    free = simulate_controlled(moments, w0, compiled=True, **kw)
    np.testing.assert_allclose(fast.omega, slow.omega, rtol=0, atol=1e-12 * np.max(np.abs(slow.omega)))
    assert np.max(np.abs(fast.omega - free.omega)) > 1e-3
    budget = fast.momentum_world - fast.momentum_world[0] - fast.impulse_world
    assert np.max(np.abs(budget)) < 1e-9 * np.max(np.abs(fast.impulse_world))
    elsewhere = ResidualDipole((0.05, -0.02, 0.01), UniformField((0.0, 3e-5, 0.0)))
    with pytest.raises(ValueError, match=r"^compiled=True needs built-in models; torque = ResidualDipole \(.*a ResidualDipole "
                                         r"in the run's field"):
        simulate_controlled(moments, w0, compiled=True, torque=elsewhere, **kw)
