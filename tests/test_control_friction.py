"""Reaction-wheel friction: Coulomb friction linear below the limit-cycle speed (as Basilisk's
omegaLimitCycle), checked against the closed-form spin-down on both integration paths."""

import numpy as np
import pytest

from tumble.dynamics import Command, ReactionWheels, simulate_controlled


class Idle:
    """Commands no motor torque: the wheel only feels its bearing friction."""

    period = 1.0

    def __call__(self, t, measurement):
        return Command(wheel_torque=np.zeros(1))


@pytest.mark.parametrize("compiled", [True, False])
def test_coulomb_spin_down_follows_the_closed_form(compiled):
    """One wheel on principal axis 3, body at rest, no command: ``(I3 - J) w3' = -u`` and
    ``J (s' + w3') = u`` give ``s' = k u`` with ``k = I3 / (J (I3 - J))``. With ``u = -c_c`` the
    spin falls linearly to ``s_lc``, then, with ``u = -c_c s / s_lc``, exponentially at the rate
    ``k c_c / s_lc``."""
    I, J, cc, slc, s0 = np.array([0.02, 0.03, 0.04]), 1e-3, 2e-5, 0.5, 3.0
    wheels = ReactionWheels([[0.0, 0.0, 1.0]], inertia=J, coulomb=cc, limit_cycle_speed=slc)
    run = simulate_controlled(I, [0.0, 0.0, 0.0], t_end=20.0, controller=Idle(), wheels=wheels,
                              wheel_speed0=[s0], compiled=compiled)
    k = I[2] / (J * (I[2] - J))
    t1 = (s0 - slc) / (cc * k)   # 3.04 s
    expected = np.where(run.t <= t1, s0 - cc * k * run.t, slc * np.exp(-(cc * k / slc) * (run.t - t1)))
    np.testing.assert_allclose(run.wheel_speed[:, 0], expected, rtol=1e-9, atol=1e-12)
    assert run.budget_error().max() < 1e-17   # friction is internal: L_world stays put


def test_a_wheel_held_near_rest_does_not_stall_the_integrator():
    """Coulomb friction larger than the command at zero speed: with a pure sign the wheel chatters
    across zero and the adaptive step collapses; with the linear region the run is quick and the
    wheel creeps at the speed where friction balances the command, u s_lc / c_c."""
    wheels = ReactionWheels([[0.0, 0.0, 1.0]], inertia=2e-5, coulomb=1e-7)

    class Small:
        period = 1.0

        def __call__(self, t, measurement):
            return Command(wheel_torque=np.array([5e-8]))

    run = simulate_controlled([0.02, 0.03, 0.04], [0.0, 0.0, 0.0], t_end=200.0, controller=Small(),
                              wheels=wheels, compiled=False)
    # s' = k (u - c_c s / s_lc), k = I3 / (J (I3 - J)): s settles at u s_lc / c_c = 5e-5 rad/s at the
    # rate k c_c / s_lc = 50 /s (with sign(s) it chatters about 0 instead, and takes minutes)
    np.testing.assert_allclose(run.wheel_speed[1:, 0], 5e-8 * 1e-4 / 1e-7, rtol=0, atol=1e-12)   # DOP853 atol


CUBESAT = np.array([0.0067, 0.0419, 0.0419])  # the issue's 3U CubeSat, kg m^2
LIMITED = ReactionWheels(np.eye(3), inertia=2e-5, max_torque=2e-3, max_speed=630.0, viscous=1e-9, coulomb=1e-7)


def _counted_run(t_end, controller, wheel_speed0=None, limit=60_000):
    """The scipy path's run (its right-hand sides counted, stopped past ``limit``) and the compiled one."""
    from tumble.dynamics.control import controlled

    calls = [0]
    original = controlled.solve_ivp

    def counted(fun, *args, **kwargs):
        def rhs(t, y, *a):
            calls[0] += 1
            if calls[0] > limit:  # far above what ordinary steps take: the crawl is back (stop early)
                raise AssertionError("the integrator crawls at the wheels' speed limit")
            return fun(t, y, *a)
        return original(rhs, *args, **kwargs)

    kw = dict(t_end=t_end, controller=controller, wheels=LIMITED, wheel_speed0=wheel_speed0)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(controlled, "solve_ivp", counted)  # the scipy path: its right-hand sides can be counted
        slow = simulate_controlled(CUBESAT, [0.5, -0.5, 0.5], compiled=False, **kw)
    fast = simulate_controlled(CUBESAT, [0.5, -0.5, 0.5], **kw)
    return slow, fast, calls[0]


def test_a_wheel_driven_into_its_speed_limit_costs_ordinary_steps():
    """Issue 27, item 1: a 3U CubeSat under MRP feedback whose wheels reach max_speed (the issue's
    numbers). The motor torque switched off and on at the limit, so DOP853 took tiny steps (30 s
    simulated took 90 s). The torque now falls to zero over the last 1 % of max_speed (a motor's
    torque-speed line), continuous: the scipy path's right-hand sides are counted over 12 s, with
    the wheels at the limit from about 6.5 s (now 2,388; at the step it crawled past 60,000),
    and the compiled path agrees with it and holds the wheel there."""
    from tumble.dynamics import MRPFeedback

    controller = MRPFeedback(K=1.1e-3, P=6e-3, period=0.5, moments=CUBESAT, wheels=LIMITED)
    slow, fast, calls = _counted_run(12.0, controller)
    assert np.abs(slow.wheel_speed).max() >= 0.99 * 630.0  # the wheels did reach their limit
    assert np.abs(fast.wheel_speed[-1]).max() == pytest.approx(630.0, rel=0.01)  # and are held there
    np.testing.assert_allclose(fast.wheel_speed, slow.wheel_speed, rtol=0, atol=1e-6 * 630.0)
    assert calls < 10_000
    # the wheels exchange momentum with the body, no more: the budget to the integration's error (measured 1.2e-11)
    assert fast.budget_error().max() < 1e-10 * np.linalg.norm(fast.momentum_world[0])


@pytest.mark.filterwarnings("ignore::tumble.dynamics.control.sampled.UnstableLoopWarning")  # unstable as meant
@pytest.mark.filterwarnings("ignore::tumble.dynamics.control.sampled.OneStepWarning")  # one command, as meant
@pytest.mark.parametrize("period, speed0, Ki", [(40.0, None, 0.0), (0.5, [700.0, -700.0, 700.0], 0.0), (0.5, None, 100.0)],
                         ids=["period longer than t_end", "speed0 above max_speed", "Ki = 100"])
def test_the_issues_other_saturating_runs_cost_ordinary_steps(period, speed0, Ki):
    """Issue 27, item 1, "the same with period longer than t_end, speed0 above max_speed, or Ki =
    100": 30 s simulated at the limit each take a few thousand right-hand sides on the scipy path
    (measured 30 s: under 1 s of wall time on either path), the compiled path agrees, the wheels
    end at their limit (a wheel started above it is brought down to it) and the momentum budget
    closes."""
    from tumble.dynamics import MRPFeedback

    controller = MRPFeedback(K=1.1e-3, P=6e-3, period=period, moments=CUBESAT, wheels=LIMITED, Ki=Ki)
    slow, fast, calls = _counted_run(30.0, controller, wheel_speed0=speed0)
    assert calls < 10_000
    np.testing.assert_allclose(fast.wheel_speed, slow.wheel_speed, rtol=0, atol=1e-6 * 630.0)
    end = np.abs(fast.wheel_speed[-1])
    assert np.any(np.abs(end - 630.0) < 0.01 * 630.0) and np.all(end < 1.01 * 630.0)  # held at the limit, none beyond
    assert fast.budget_error().max() < 1e-10 * np.linalg.norm(fast.momentum_world[0])


class Push:
    """Commands a constant torque on the one wheel, outwards."""

    period = 1.0

    def __init__(self, u):
        self.u = u

    def __call__(self, t, measurement):
        return Command(wheel_torque=np.array([self.u]))


@pytest.mark.parametrize("compiled", [True, False])
def test_the_speed_limit_ramp_follows_its_closed_form(compiled):
    """One wheel on axis 3, body at rest, a constant outward command u, no friction, the wheel
    inside the last SPEED_LIMIT_BAND of max_speed: ``s' = k u (1 - s / s_max) / band`` (``k`` as
    for the spin-down above), so ``s_max - s`` decays as ``exp(-k u t / (band s_max))``: the
    wheel approaches its limit and never passes it."""
    from tumble.dynamics.models.actuators import SPEED_LIMIT_BAND

    I, J, u, s_max = np.array([0.02, 0.03, 0.04]), 1e-3, 2e-5, 100.0
    s0 = s_max * (1.0 - 0.5 * SPEED_LIMIT_BAND)  # half-way down the ramp: the motor gives half of u
    wheels = ReactionWheels([[0.0, 0.0, 1.0]], inertia=J, max_torque=1e-4, max_speed=s_max)
    run = simulate_controlled(I, [0.0, 0.0, 0.0], t_end=20.0, controller=Push(u), wheels=wheels,
                              wheel_speed0=[s0], compiled=compiled)
    k = I[2] / (J * (I[2] - J))
    expected = s_max - (s_max - s0) * np.exp(-k * u * run.t / (SPEED_LIMIT_BAND * s_max))
    np.testing.assert_allclose(run.wheel_speed[:, 0], expected, rtol=1e-10, atol=0.0)
    assert np.all(run.wheel_speed[:, 0] < s_max)
    assert run.budget_error().max() < 1e-15   # the motor is internal: L_world stays put
