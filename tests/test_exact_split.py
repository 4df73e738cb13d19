"""Exact-flow splitting (methods exact_split2/4/6): orders, budgets, and agreement with DOP853,
the closed form and the geometric methods (Celledoni, Fasso, Safstrom & Zanna 2008)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import cumulative_simpson, solve_ivp
from scipy.spatial.transform import Rotation

import tumble
from tumble.dynamics import simulate, simulate_batch
from tumble.dynamics.methods.exact_split import propagate
from tumble.dynamics.methods.integrators import METHODS
from tumble.dynamics.models.torques import ConstantTorque
from tumble.mass import MassProperties

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SPLIT = [name for name in METHODS if name.startswith("exact_split")]
I = np.array([0.0021, 0.0043, 0.0059])  # the seed's T-handle, kg m^2
W0 = np.array([0.1, 10.0, 0.05])  # rad/s: about the intermediate axis, it flips
TAU = np.array([1e-4, -2e-4, 3e-4])  # N m, fixed in the body


def _reference(t_end: float) -> np.ndarray:
    """omega(t_end) under the body torque TAU by DOP853 at rtol 1e-13: Euler's equations alone."""
    sol = solve_ivp(lambda t, L: np.cross(L, L / I) + TAU, (0.0, t_end), I * W0, method="DOP853", rtol=1e-13,
                    atol=1e-16)
    return sol.y[:, -1] / I


@pytest.mark.parametrize(("order", "steps"), [(2, (0.1, 0.05)), (4, (0.1, 0.05)), (6, (0.1, 0.05))])
def test_the_order_is_measured_by_halving_the_step(order, steps):
    # over 2 s (a flip) the error falls by 2^order when the step halves
    ref = _reference(2.0)
    errors = []
    for h in steps:
        omega, _ = propagate(I, W0, [0.0, 0.0, 0.0, 1.0], np.array([0.0, 2.0]), order=order, step=h,
                             torque=ConstantTorque(TAU))
        errors.append(np.max(np.abs(omega[-1, 0] - ref)))
    slope = np.log2(errors[0] / errors[1])
    assert abs(slope - order) < 0.35, (errors, slope)


def test_without_a_torque_it_is_the_closed_form_at_any_step():
    props = MassProperties.from_moments(I)
    exact = simulate(props, W0, t_end=20.0, samples=11, method="exact")
    for name in SPLIT:
        run = simulate(props, W0, t_end=20.0, samples=11, method=name)
        # restarted from each sample, the closed form meets its own round-off again, which the
        # flip (near the separatrix, k' ~ 0.01) amplifies: measured 1.1e-10 rad/s of 10
        np.testing.assert_allclose(run.omega, exact.omega, rtol=0, atol=1e-9 * np.max(np.abs(exact.omega)))
        angle = (Rotation.from_quat(run.quat).inv() * Rotation.from_quat(exact.quat)).magnitude()
        assert np.max(angle) < 1e-9


def test_a_world_torque_adds_its_impulse_to_l_world_to_round_off():
    """Each kick adds d tau_world to L_world exactly and each free flow keeps it: the momentum
    budget L_world(t) = L_world(0) + tau_world t holds to round-off at any step and order."""
    props = MassProperties.from_moments(I)
    tau = np.array([2e-4, -1e-4, 5e-5])
    for name in SPLIT:
        run = simulate(props, W0, t_end=3.0, samples=7, method=name, step=0.25,
                       torque=ConstantTorque(tau, frame="world"))
        budget = run.angular_momentum_world - run.angular_momentum_world[0] - run.t[:, None] * tau
        assert np.max(np.abs(budget)) < 1e-15 * 100, name


def test_the_energy_budget_under_a_body_torque_matches_the_work_done():
    """dE/dt = tau . omega: the work integral along the run (Simpson's rule on the samples)
    matches the energy change to the accuracy of the method and of the quadrature."""
    props = MassProperties.from_moments(I)
    run = simulate(props, W0, t_end=2.0, samples=401, method="exact_split4", torque=ConstantTorque(TAU))
    work = cumulative_simpson(run.omega @ TAU, x=run.t, initial=0.0)
    gap = run.energy - run.energy[0] - work
    # measured: 6.7e-11 of E, the quadrature's error and the method's together
    assert np.max(np.abs(gap)) < 1e-9 * abs(run.energy[0])


@pytest.mark.parametrize("name", SPLIT)
def test_it_agrees_with_dop853_and_the_geometric_methods(name):
    props = MassProperties.from_moments(I)
    torque = ConstantTorque(TAU)
    ref = simulate(props, W0, t_end=2.0, samples=5, method="dop853", torque=torque, rtol=1e-13, atol=1e-13)
    order = METHODS[name].splitting_order
    run = simulate(props, W0, t_end=2.0, samples=5, method=name, torque=torque, step={2: 0.001, 4: 0.02, 6: 0.05}[order])
    geo = simulate(props, W0, t_end=2.0, samples=5, method=f"geometric{'' if order == 4 else order}", torque=torque,
                   step=0.002)
    scale = np.max(np.abs(ref.omega))
    # mid-flip (t = 1.5 s, |d omega / dt| ~ 100 rad/s^2) a timing error shows most
    assert np.max(np.abs(run.omega - ref.omega)) < 1e-4 * scale
    assert np.max(np.abs(run.omega - geo.omega)) < 1e-4 * scale
    angle = (Rotation.from_quat(run.quat).inv() * Rotation.from_quat(ref.quat)).magnitude()
    assert np.max(angle) < 1e-5


def test_gravity_gradient_libration_matches_dop853():
    props = MassProperties.from_moments([100.0, 120.0, 150.0])
    gg = tumble.GravityGradient(orbit_period=5400.0)
    n = 2.0 * np.pi / 5400.0
    w0 = np.array([0.0, -n, 0.0]) + 1e-4  # near the LVLH rate: libration
    ref = simulate(props, w0, t_end=5400.0, samples=7, method="dop853", torque=gg, rtol=1e-12, atol=1e-14)
    run = simulate(props, w0, t_end=5400.0, samples=7, method="exact_split4", torque=gg, step=30.0)
    assert np.max(np.abs(run.omega - ref.omega)) < 1e-6 * np.max(np.abs(ref.omega))


def test_a_batch_runs_every_body_as_it_runs_alone():
    rng = np.random.default_rng(3)
    moments = np.sort(rng.uniform(1.0, 3.0, (4, 3)), axis=1)
    w0 = rng.normal(size=(4, 3))
    torque = ConstantTorque([0.01, 0.0, -0.02])
    batch = simulate_batch(moments, w0, t_end=1.0, samples=3, method="exact_split4", torque=torque, step=0.1)
    for i in range(4):
        one = simulate(MassProperties.from_moments(moments[i]), w0[i], t_end=1.0, samples=3, method="exact_split4",
                       torque=torque, step=0.1)
        np.testing.assert_allclose(batch.omega[i], one.omega, rtol=0, atol=1e-13 * np.max(np.abs(one.omega)))


def test_rotors_are_refused_with_the_methods_that_take_them():
    body = tumble.load_body(EXAMPLES / "bodies" / "t_handle_wheel.toml")
    with pytest.raises(ValueError, match=r"method = 'exact_split4' cannot take rotors .* use one of: .*geometric"):
        simulate(body, [0.1, 10.0, 0.0], t_end=1.0, method="exact_split4")


def test_moments_out_of_order_are_refused():
    with pytest.raises(ValueError, match=r"moments\[0\] = \[3.0, 2.0, 1.0\] must be ascending"):
        propagate([3.0, 2.0, 1.0], [0.1, 1.0, 0.1], [0.0, 0.0, 0.0, 1.0], np.array([0.0, 1.0]), step=0.1)
