"""The compiled engine (tumble.dynamics.engine): against scipy's DOP853 on the Python path, against
closed forms, its orders, its budgets, and a body alone against its batch."""

from __future__ import annotations

import re

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tumble
from rigid_reference import reference_run
from tumble.dynamics import simulate, simulate_batch
from tumble.dynamics.engine import run_bodies, run_body
from tumble.dynamics.engine.status import STEP_COLLAPSED
from tumble.jit import PARALLEL_BODIES
from tumble.dynamics.models.gravity import GravityGradient
from tumble.dynamics.models.torques import ConstantTorque, FunctionTorque, kernel_form
from tumble.dynamics.trajectory import Trajectory
from tumble.mass import MassProperties

SPACECRAFT = MassProperties.from_moments([10.0, 12.0, 15.0])
Q0 = Rotation.from_euler("xyz", [0.3, -0.2, 0.5])
TAU = (0.01, -0.02, 0.015)
MODELS = {
    "body": ConstantTorque(TAU),
    "world": ConstantTorque(TAU, "world"),
    "gravity": GravityGradient(orbit_period=60.0, mu=1.0),  # a fast orbit about a small mass: a strong gradient
}


def _as_python(model, props):
    """The same torque as a Python function: the model's kernel form is gone, scipy runs it."""
    bound = model.bind(props) if hasattr(model, "bind") else model
    return FunctionTorque(lambda t, w, R: bound(t, w, R), bound.frame)


@pytest.mark.parametrize("name", list(MODELS))
def test_compiled_dop853_takes_scipys_steps(name):
    """Step for step scipy's DOP853 (same starting step, error norm, control, dense output): the two
    paths differ by round-off (fused multiply-adds, sums in another order), not by the tolerance."""
    model = MODELS[name]
    assert kernel_form(model.bind(SPACECRAFT) if hasattr(model, "bind") else model) is not None
    kw = dict(t_end=20.0, samples=101, attitude0=Q0, method="dop853", rtol=1e-9)
    fast = simulate(SPACECRAFT, [0.05, 1.0, 0.05], torque=model, **kw)
    slow = simulate(SPACECRAFT, [0.05, 1.0, 0.05], torque=_as_python(model, SPACECRAFT), **kw)
    # measured: 3e-15 relative; the tolerance's own scale is 1e-9
    assert np.max(np.abs(fast.omega - slow.omega)) / np.max(np.abs(slow.omega)) < 1e-13
    assert np.max(np.abs(fast.quat - slow.quat)) < 1e-13


@pytest.mark.parametrize(("method", "order", "steps"), [("rk4", 4, (0.02, 0.01)), ("rk8", 8, (0.1, 0.05))])
def test_fixed_step_orders(method, order, steps):
    """Halving the step divides the global error by at least 2^p: a torque-free spacecraft at
    10 rad/s against the closed form (elliptic functions, an independent route). Measured: 4.02
    for RK4, 8.51 for RK8 (its leading error term is small on this motion, as DOP853's designers
    tuned it)."""
    w0 = [3.0, 10.0, 1.0]
    exact = simulate(SPACECRAFT, w0, t_end=20.0, samples=11, method="exact")
    errors = [np.max(np.abs(simulate(SPACECRAFT, w0, t_end=20.0, samples=11, method=method, step=h).omega
                            - exact.omega)) for h in steps]
    measured = np.log2(errors[0] / errors[1])
    assert order - 0.2 < measured < order + 0.8, (errors, measured)


@pytest.mark.parametrize("method", ["dop853", "rk8"])
def test_against_an_independent_reference(method):
    """The T-handle at 10 rad/s under a constant body torque for 20 s, against scipy's DOP853 on a
    right-hand side written in this test: omega and attitude."""
    props = MassProperties.from_moments([0.125, 0.3125, 0.4375])
    kw = {"rtol": 1e-12} if method == "dop853" else {"step": 0.2 / 16}
    traj = simulate(props, [0.1, 10.0, 0.1], t_end=20.0, samples=101, attitude0=Q0, method=method,
                    torque=ConstantTorque(TAU), **kw)
    w_ref, q_ref = reference_run(props.principal_moments, traj.omega[0], traj.quat[0], traj.t,
                                 lambda time, w, R: np.asarray(TAU))  # tests/rigid_reference.py
    assert np.max(np.linalg.norm(traj.omega - w_ref, axis=1)) / np.max(np.linalg.norm(w_ref, axis=1)) < 1e-9
    assert np.max((traj.attitude * Rotation.from_quat(q_ref).inv()).magnitude()) < 1e-8


def test_spin_up_about_a_principal_axis_is_the_closed_form():
    """omega_3(t) = omega_3(0) + tau_3 t / I3 and the attitude turns by the integral of it."""
    for method in ("dop853", "rk4", "rk8"):
        traj = simulate(SPACECRAFT, [0.0, 0.0, 0.2], t_end=10.0, samples=6, method=method,
                        torque=ConstantTorque((0.0, 0.0, 1.5)))
        np.testing.assert_allclose(traj.omega[:, 2], 0.2 + 1.5 * traj.t / 15.0, rtol=1e-12)
        angle = 0.2 * traj.t + 0.5 * 1.5 / 15.0 * traj.t**2  # rad, the integral of omega_3
        wrapped = angle - 2 * np.pi * np.round(angle / (2 * np.pi))  # as a rotation vector gives it, in (-pi, pi]
        np.testing.assert_allclose(traj.attitude.as_rotvec()[:, 2], wrapped, atol=1e-10)


def test_world_torque_impulse_and_energy_budget():
    """A constant world torque adds tau t to L_world; the kinetic energy changes by the work
    integral of tau . omega (trapezoid over a fine sampling)."""
    traj = simulate(SPACECRAFT, [0.3, 1.0, -0.2], t_end=20.0, samples=4001, attitude0=Q0, method="dop853",
                    torque=ConstantTorque(TAU, "world"), rtol=1e-12)
    np.testing.assert_allclose(traj.angular_momentum_world - traj.angular_momentum_world[0],
                               np.outer(traj.t, TAU), rtol=0, atol=1e-10)
    tau_body = traj.attitude.inv().apply(np.tile(TAU, (len(traj), 1)))
    power = np.sum(tau_body * traj.omega, axis=1)
    work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(traj.t))])
    np.testing.assert_allclose(traj.energy - traj.energy[0], work, rtol=0, atol=1e-7 * traj.energy[0])


def test_gravity_gradient_keeps_its_jacobi_integral():
    gg = GravityGradient(orbit_period=600.0, mu=1.0).bind(SPACECRAFT)
    for method, kw in (("dop853", {"rtol": 1e-12}), ("rk8", {"step": 0.5})):
        traj = simulate(SPACECRAFT, [0.05, 0.02, 0.04], t_end=1200.0, samples=25, attitude0=Q0, method=method,
                        torque=gg, **kw)
        h = gg.jacobi_integral(traj.t, traj.omega, traj.attitude)
        assert np.max(np.abs(h - h[0])) < 1e-9 * abs(h[0])


def test_a_body_alone_equals_its_row_in_a_batch_on_every_core():
    """The batch from PARALLEL_BODIES bodies runs the same arithmetic per body on every core: DOP853
    to the last bit; RK8 in vector lanes (tumble.dynamics.engine.lanes), the same steps and sums, to
    round-off (the multiply-adds fused differently in a vector: tests/test_engine_lanes.py)."""
    rng = np.random.default_rng(5)
    n = PARALLEL_BODIES + 4
    I = np.sort(rng.uniform(0.5, 1.0, (n, 3)), axis=1)
    w = rng.normal(size=(n, 3)) * 3.0
    q = Rotation.random(n, random_state=5).as_quat()
    for method, kw in (("dop853", {"rtol": 1e-10}), ("rk8", {"step": 0.05})):
        batch = simulate_batch(I, w, t_end=5.0, samples=11, attitude0=q, method=method, torque=ConstantTorque(TAU),
                               **kw)
        for b in (0, 17, n - 1):
            alone = simulate(MassProperties.from_moments(I[b]), w[b], t_end=5.0, samples=11, attitude0=q[b],
                             method=method, torque=ConstantTorque(TAU), **kw)
            if method == "dop853":
                np.testing.assert_array_equal(batch.omega[b], alone.omega)
                np.testing.assert_array_equal(batch.quat[b], alone.quat)
            else:
                np.testing.assert_allclose(batch.omega[b], alone.omega, rtol=0, atol=1e-13 * np.abs(alone.omega).max())
                np.testing.assert_allclose(batch.quat[b], alone.quat, rtol=0, atol=1e-13)


def test_fixed_steppers_refuse_a_python_torque_naming_the_alternatives():
    with pytest.raises(ValueError, match=r"method = 'rk8' runs compiled .* use one of: dop853"):
        simulate(SPACECRAFT, [0.0, 1.0, 0.0], t_end=1.0, method="rk8", torque=lambda t, w, R: -0.1 * w)


def test_status_becomes_a_clear_error():
    """A torque that cannot be followed (infinite here) ends the run in a status, never a hang or a
    NaN trajectory, and the front turns the status into one RuntimeError naming the method."""
    from tumble.dynamics.engine import kernels

    y0 = np.array([0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0])
    torque = (0.0, 0.0, np.inf) + (0.0,) * 7  # the kernels' terms: an infinite body torque
    status = kernels.dop853(y0, np.array([0.0, 1.0]), np.ones(3), torque, 0.0, 1e-10, np.full(7, 1e-12),
                            np.empty((2, 3)), np.empty((2, 4)))
    assert status == STEP_COLLAPSED
    with pytest.raises(RuntimeError, match="dop853 integration failed: the step size fell below 10 ulp"):
        run_body("dop853", np.ones(3), y0[:3], y0[3:], np.array([0.0, 1.0]), (1, (0.0, 0.0, np.inf)), rtol=1e-10,
                 atol=np.full(7, 1e-12))


def test_a_failing_body_of_a_batch_is_named():
    omega0, quat0 = np.array([[0.0, 0.0, 1.0]] * 2), np.array([[0.0, 0.0, 0.0, 1.0]] * 2)
    with pytest.raises(RuntimeError, match="for body 0"):
        run_bodies("dop853", np.ones((2, 3)), omega0, quat0, np.array([0.0, 1.0]), (1, (0.0, 0.0, np.inf)),
                   rtol=1e-10, atol=np.full((2, 7), 1e-12))


def test_the_trajectory_builds_its_rotation_only_when_asked():
    traj = simulate(SPACECRAFT, [0.05, 1.0, 0.05], t_end=2.0, samples=5, method="rk8", torque=ConstantTorque(TAU))
    assert not isinstance(traj.__dict__["_attitude_value"], Rotation)  # quaternions so far
    quat = traj.quat
    assert not isinstance(traj.__dict__["_attitude_value"], Rotation)
    np.testing.assert_allclose(traj.attitude.as_quat(), quat, rtol=0, atol=1e-15)
    assert isinstance(traj.__dict__["_attitude_value"], Rotation)  # built once, kept
    given = Trajectory(t=traj.t, omega=traj.omega, attitude=traj.attitude, moments=traj.moments,
                       principal_axes=traj.principal_axes, method="rk8")
    np.testing.assert_allclose(given.quat, quat, rtol=0, atol=1e-15)


def test_design_frame_constant_torque_stays_compiled():
    """A body-frame constant torque given in the design frame is turned once into the principal
    frame (a ConstantTorque again), so it runs compiled, and equals the Python wrapper's result."""
    from tumble.dynamics.simulate import check_inputs

    body = tumble.t_handle()
    run = check_inputs(body, [0.0, 1.0, 10.0], t_end=1.0, frame="design", torque=ConstantTorque(TAU))
    assert kernel_form(run.torque) is not None
    fast = simulate(body, [0.0, 1.0, 10.0], t_end=1.0, samples=11, frame="design", torque=ConstantTorque(TAU),
                    rtol=1e-12)
    slow = simulate(body, [0.0, 1.0, 10.0], t_end=1.0, samples=11, frame="design",
                    torque=FunctionTorque(lambda t, w, R: np.array(TAU)), rtol=1e-12)
    np.testing.assert_allclose(fast.omega, slow.omega, rtol=0, atol=1e-11)


@pytest.mark.parametrize(("step", "message"), [(-1.0, "step = -1.0 must be a positive finite number"),
                                               (float("nan"), "step = nan must be a finite number"),
                                               (0.0, "step = 0.0 must be a positive finite number"),
                                               ("x", "step = 'x' must be a number")])
def test_a_batchs_bad_step_is_refused_not_run(step, message):
    """simulate_batch passed a fixed-step engine method's step on unchecked: -1 and nan ran one step
    per sample interval (a silently coarse run), 0 divided by zero, a string gave a numpy error."""
    with pytest.raises(ValueError, match=re.escape(message)):
        simulate_batch([1.0, 2.0, 3.0], [[0.1, 1.0, 0.0]], t_end=1.0, samples=3, method="rk8", step=step,
                       torque=ConstantTorque(TAU))


@pytest.mark.parametrize("scale", [1.0 + 3e-9, 1.0 - 2e-6, 0.7, 2.5])
def test_the_torques_of_a_quaternion_not_normalised_are_the_unit_quaternions(scale):
    """A step's quaternion is a unit one only to the integration's accuracy: the world torque and
    the gravity gradient read it through to_body's homogeneous form (|q|^2 times the rotation)
    divided by |q|^2 and |q|^4, so they equal the normalised quaternion's to round-off, and the
    direction in the body is scipy's."""
    from tumble.dynamics.engine import kernels
    from tumble.dynamics.special.quaternion import to_body

    q = Rotation.from_euler("xyz", [0.3, -0.2, 0.5]).as_quat()
    I = (10.0, 12.0, 15.0, 0.1, 1.0 / 12.0, 1.0 / 15.0)
    u0, u1 = np.cos(0.4), np.sin(0.4)
    for P in ((0.0, 0.0, 0.0, 0.01, -0.02, 0.015, 0.0, 0.0, 0.0, 0.0),      # a constant world torque
              (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2.5e-3, 0.0, 0.0, 0.0)):       # the gravity gradient, n^2
        unit = kernels.external_torque.py_func(I, 0.1, 1.0, 0.1, *q, u0, u1, P)
        scaled = kernels.external_torque.py_func(I, 0.1, 1.0, 0.1, *(scale * q), u0, u1, P)
        # round-off: a few units in the last place of the largest component (the sums cancel)
        np.testing.assert_allclose(scaled, unit, rtol=0.0, atol=2e-15 * np.max(np.abs(unit)))
    b = to_body(*(scale * q), u0, u1, 0.0)
    np.testing.assert_allclose(np.array(b) / scale**2, Rotation.from_quat(q).inv().apply([u0, u1, 0.0]),
                               rtol=0, atol=1e-15)
