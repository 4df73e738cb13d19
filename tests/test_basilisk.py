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
from basilisk_runner import earth_mu, mrp_from_quat, quat_from_mrp, run_basilisk

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
