"""tumble against Basilisk (``pip install bsk``, the bench extra): the comparison of
``benchmarks/bench_basilisk.py`` is itself tested, frames and conventions included.

Skipped when Basilisk is not installed (the test extra does not have it). Each run is a
short tumble of the spacecraft the benchmark uses; Basilisk's RK4 at 5 ms and tumble's DOP853 at
rtol 1e-12 are both accurate far below the tolerances here, so any disagreement in the frames
(MRP against quaternion, body against world, the orbit's phase or mu) fails by orders of magnitude.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tumble

pytest.importorskip("Basilisk", reason="Basilisk (pip install bsk) is not installed")

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from basilisk_runner import (
    earth_mu,
    mrp_from_quat,
    quat_from_mrp,
    run_basilisk,
    wheel_setup,
)

MOMENTS = (10.0, 12.0, 15.0)  # kg m^2
OMEGA0 = (0.05, 1.0, 0.05)  # rad/s, near the intermediate axis
QUAT0 = Rotation.from_euler("xyz", [0.3, -0.2, 0.5]).as_quat()
DT_NS, STEPS, SAMPLES = 5_000_000, 40, 11  # 5 ms steps, a sample every 0.2 s, 2 s


def _tumble(model, times):
    props = tumble.MassProperties.from_moments(MOMENTS)
    return tumble.simulate(props, OMEGA0, times=times, attitude0=QUAT0, method="dop853", rtol=1e-12,
                           atol=1e-14, torque=model)


def _compare(run, tr):
    assert np.allclose(run.times, np.arange(SAMPLES) * 0.2, rtol=0, atol=1e-12)
    np.testing.assert_allclose(run.omega, tr.omega, rtol=0, atol=1e-8)  # rad/s, |omega| ~ 1
    angle = (Rotation.from_quat(run.quat) * Rotation.from_quat(tr.quat).inv()).magnitude()
    assert np.max(angle) < 1e-8  # rad


def test_mrp_round_trip():
    q = Rotation.random(20, random_state=1).as_quat()
    back = quat_from_mrp(np.array([np.ravel(mrp_from_quat(x)) for x in q]))
    angle = (Rotation.from_quat(back) * Rotation.from_quat(q).inv()).magnitude()
    assert np.max(angle) < 1e-14


def test_constant_body_torque_agrees():
    tau = (0.01, -0.02, 0.015)  # N m, body frame
    run = run_basilisk(MOMENTS, OMEGA0, QUAT0, dt_ns=DT_NS, sample_steps=STEPS, samples=SAMPLES, torque=tau)
    _compare(run, _tumble(tumble.ConstantTorque(tau), run.times))
    # the torque acts: without it the motion differs by far more than the tolerance
    free = _tumble(None, run.times)
    assert np.max(np.abs(free.omega - run.omega)) > 1e-3


def test_gravity_gradient_agrees():
    # a 90-minute orbit puts the gravity gradient at ~1e-5 N m: too small to tell the frames
    # apart in 2 s, so a low, fast orbit (a point mass of Basilisk's mu, r = 1000 km: n = 0.02 rad/s)
    # makes the torque ~1e-2 N m, and a mismatch of the orbit's phase or plane would show
    mu = earth_mu()
    r = 1.0e6
    gg = tumble.GravityGradient(orbit_radius=r, mu=mu)
    run = run_basilisk(MOMENTS, OMEGA0, QUAT0, dt_ns=DT_NS, sample_steps=STEPS, samples=SAMPLES, orbit_radius=r)
    _compare(run, _tumble(gg, run.times))
    free = _tumble(None, run.times)
    assert np.max(np.abs(free.omega - run.omega)) > 1e-4


def test_free_reaction_wheel_agrees_with_the_rotor_gyrostat():
    """A Basilisk wheel without motor torque (its absolute axial momentum kept) set up by
    ``wheel_setup`` moves the hub as tumble's body with a constant-spin Rotor: the same gyrostat."""
    from tumble.dynamics.models.rotors import Rotors

    spin = 200.0  # rad/s relative to the body: 4.5 N m s
    body = tumble.Body([tumble.Box(mass=120.0, size=(1.2, 1.0, 0.8)),
                        tumble.Rotor(mass=2.0, radius=0.15, length=0.05, axis=(0, 0, 1), spin_rate=spin)])
    rotors = Rotors.of(body)
    I = body.principal_moments
    hub, wheel = wheel_setup(I, rotors.axes[0], float(rotors.axial_moments[0]), spin, OMEGA0)
    assert np.isclose(wheel.js * (rotors.axes[0] @ OMEGA0 + wheel.omega), rotors.axial_moments[0] * spin)
    tau = (0.01, -0.02, 0.015)  # N m, body frame
    run = run_basilisk(I, OMEGA0, QUAT0, dt_ns=DT_NS, sample_steps=STEPS, samples=SAMPLES, torque=tau,
                       hub_inertia=hub, wheel=wheel)
    ref = tumble.simulate(body, OMEGA0, times=run.times, attitude0=QUAT0, method="dop853", rtol=1e-12, atol=1e-14,
                          torque=tumble.ConstantTorque(tau))
    _compare(run, ref)
    fast = tumble.simulate(body, OMEGA0, times=run.times, attitude0=QUAT0, method="geometric6", step=0.05,
                           torque=tumble.ConstantTorque(tau))  # the compiled kernel the benchmark times
    np.testing.assert_allclose(fast.omega, run.omega, rtol=0, atol=1e-8)
    # the wheel acts: the same hub without it moves otherwise, by far more than the tolerance
    bare = run_basilisk(I, OMEGA0, QUAT0, dt_ns=DT_NS, sample_steps=STEPS, samples=SAMPLES, torque=tau)
    assert np.max(np.abs(bare.omega - run.omega)) > 1e-2
