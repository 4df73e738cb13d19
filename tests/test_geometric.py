"""Splitting integrators: order, invariants to round-off, bounded energy, batches, torques."""

from __future__ import annotations

import numpy as np
import pytest

import tumble
from tumble.dynamics import ConstantTorque, FunctionTorque, simulate
from tumble.dynamics.methods.geometric import free_flow_substeps, propagate
from tumble.mass import MassProperties

BODY = tumble.iss_t_handle()
W0 = [1.0, 8.0, -2.0]


@pytest.mark.parametrize(("method", "order", "h"), [("geometric2", 2, 4e-3), ("geometric", 4, 4e-3), ("geometric6", 6, 2e-2)])
def test_order_of_convergence(method, order, h):
    exact = simulate(BODY, W0, t_end=2.0, samples=5)
    errors = []
    for h in (h, h / 2):
        g = simulate(BODY, W0, t_end=2.0, samples=5, method=method, step=h)
        errors.append(np.max(np.abs(g.omega - exact.omega)))
    assert errors[0] / errors[1] == pytest.approx(2.0**order, rel=0.2)


def test_substeps_merge_and_sum_to_one():
    for order in (2, 4, 6):
        seq = free_flow_substeps(order)
        for axis in range(3):
            assert sum(f for a, f in seq if a == axis) == pytest.approx(1.0, abs=1e-14)
        assert all(a != b for (a, _), (b, _) in zip(seq, seq[1:]))


def test_invariants_to_round_off_and_energy_bounded():
    """50,000 steps of the 2nd-order method: |L| and L_world to round-off; the energy error
    oscillates (symplectic map) instead of drifting, so the first tenth of the run already
    shows its largest size."""
    steps, h = 50_000, 2e-3
    g = simulate(BODY, W0, t_end=steps * h, samples=1001, method="geometric2", step=h)
    assert g.drift["L_norm"] < 1e-13
    assert g.drift["L_world"] < 1e-13
    dE = np.abs(g.energy / g.energy[0] - 1)
    assert dE.max() < 1.5 * dE[: len(dE) // 10].max()
    assert dE.max() < 1e-3


def test_a_batch_equals_single_runs(rng):
    I = np.sort(rng.uniform(1.0, 2.0, size=(5, 3)), axis=1)
    w = rng.normal(size=(5, 3))
    q = np.tile([0.0, 0.0, 0.0, 1.0], (5, 1))
    t = np.linspace(0.0, 1.0, 11)
    wb, qb = propagate(I, w, q, t, order=4, step=0.01)
    for k in range(5):
        w1, q1 = propagate(I[k], w[k], q[k], t, order=4, step=0.01)
        np.testing.assert_array_equal(wb[:, k], w1[:, 0])
        np.testing.assert_array_equal(qb[:, k], q1[:, 0])


def test_body_torque_from_rest_is_exact():
    tau = np.array([0.0, 2e-5, 0.0])
    g = simulate(BODY, [0, 0, 0], t_end=2.0, samples=21, method="geometric", step=0.05,
                 torque=ConstantTorque(tuple(tau)))
    np.testing.assert_allclose(g.omega, np.outer(g.t, tau / BODY.principal_moments), atol=1e-12)


def test_world_torque_changes_L_world_linearly():
    tau = np.array([1e-5, -2e-5, 3e-5])
    g = simulate(BODY, W0, t_end=3.0, samples=31, method="geometric", step=1e-3, torque=ConstantTorque(tuple(tau), "world"))
    L0 = g.angular_momentum_world[0]
    np.testing.assert_allclose(g.angular_momentum_world, L0 + np.outer(g.t, tau), atol=1e-13)


def test_time_dependent_torque_keeps_fourth_order():
    torque = FunctionTorque(lambda t, w, att: np.array([1e-4 * np.sin(3 * t), 0.0, 5e-5 * np.cos(t)]), "body")
    ref = simulate(BODY, W0, t_end=1.0, samples=3, method="dop853", torque=torque, rtol=1e-13)
    errors = [
        np.max(np.abs(simulate(BODY, W0, t_end=1.0, samples=3, method="geometric", step=h, torque=torque).omega - ref.omega))
        for h in (1e-2, 5e-3)
    ]
    assert errors[0] / errors[1] == pytest.approx(16.0, rel=0.25)


def test_geometric_needs_no_positive_definite_trick_for_symmetric_bodies():
    top = MassProperties.from_moments([1.0, 1.0, 1.5])
    w0 = [0.3, 0.4, 2.0]
    g = simulate(top, w0, t_end=5.0, samples=11, method="geometric6", step=5e-3)
    e = simulate(top, w0, t_end=5.0, samples=11)
    np.testing.assert_allclose(g.omega, e.omega, atol=1e-10)


@pytest.mark.parametrize(
    ("kwargs", "pattern"),
    [
        (dict(moments=[1.0, 0.0, 2.0]), "moments must be finite and positive"),
        (dict(omega0=[np.nan, 0.0, 0.0]), "omega0 and quat0 must be finite"),
        (dict(quat0=[0.0, 0.0, 0.0, 0.0]), "not zero"),
        (dict(t=[0.0, 1.0, 0.5]), r"t must increase strictly; t\[2\] = 0.5 follows 1.0"),
        (dict(step=-0.1), r"step = -0.1 must be a positive"),
    ],
)
def test_propagate_refuses_bad_input(kwargs, pattern):
    args = dict(moments=[1.0, 2.0, 3.0], omega0=[0.1, 1.0, 0.0], quat0=[0.0, 0.0, 0.0, 1.0], t=[0.0, 1.0])
    args.update(kwargs)
    with pytest.raises(ValueError, match=pattern):
        propagate(args["moments"], args["omega0"], args["quat0"], args["t"], step=args.get("step"))


@pytest.mark.parametrize("order", [2, 4, 6])
def test_a_body_runs_bit_for_bit_the_same_alone_or_in_any_batch(order):
    """A body's run does not depend on the batch it is in (a sweep's rows on its chunks): the
    same operations for 1, 10 or 100 bodies (there was another path up to 16 bodies)."""
    rng = np.random.default_rng(11)
    n = 100
    moments = np.sort(rng.uniform(0.5, 3.0, (n, 3)), axis=1)
    omega0 = rng.normal(0.0, 1.0, (n, 3)) + [0.0, 8.0, 0.0]
    quat0 = rng.normal(size=(n, 4))
    t = np.linspace(0.0, 2.0, 21)
    omega, quat = propagate(moments, omega0, quat0, t, order=order, step=0.01)
    for lo, hi in ((0, 1), (37, 38), (99, 100), (10, 20), (50, 66)):
        w, q = propagate(moments[lo:hi], omega0[lo:hi], quat0[lo:hi], t, order=order, step=0.01)
        assert np.array_equal(w, omega[:, lo:hi]) and np.array_equal(q, quat[:, lo:hi]), (lo, hi)


def test_a_body_under_a_world_frame_torque_runs_the_same_alone_or_in_a_batch():
    """A torque fixed in the world is turned into the body's frame; scipy's
    Rotation.apply takes other arithmetic for one rotation than for a stack (1e-15 apart a
    step, 1e-11 after a sweep's run), so the rotations are written out."""
    rng = np.random.default_rng(5)
    n = 16
    moments = np.sort(rng.uniform(1.0, 2.0, (n, 3)), axis=1)  # within the triangle inequality
    omega0 = rng.normal(0.0, 0.5, (n, 3)) + [0.0, 5.0, 0.0]
    quat0 = rng.normal(size=(n, 4))
    quat0 /= np.linalg.norm(quat0, axis=1, keepdims=True)
    torque = ConstantTorque([0.0, 0.001, 0.002], frame="world")
    kw = {"t_end": 5.0, "samples": 11, "method": "geometric", "torque": torque, "step": 0.01}
    batch = tumble.simulate_batch(moments, omega0, attitude0=quat0, **kw)
    for k in range(n):  # one body alone, as a sweep's chunk of one runs it
        one = tumble.simulate_batch(moments[k], omega0[k], attitude0=quat0[k], **kw)
        assert np.array_equal(one.omega[0], batch.omega[k]) and np.array_equal(one.quat[0], batch.quat[k]), k
