"""A dipole fixed in the body in a magnetic field (``ResidualDipole``, models/dipole.py) and its
compiled runs (control/free_loop.py): the compass needle's energy ``T - m . B_b`` and its small
swing's period in a uniform field, runs against scipy's DOP853 at rtol 1e-13 on ``m x R^T B``
written out here, beside the gravity gradient and constant torques, and which path ran."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tumble
from rigid_reference import errors, reference_run
from tumble.dynamics import (CircularOrbit, ConstantTorque, DipoleField, GravityGradient, ResidualDipole,
                             UniformField)

I = np.array([0.03, 0.04, 0.05])  # kg m^2: a small satellite
BODY = tumble.MassProperties.from_moments(I)
M = np.array([0.3, -0.1, 0.2])  # A m^2
B = np.array([2e-5, -1e-5, 3e-5])  # T
W0 = np.array([0.01, -0.02, 0.015])  # rad/s
Q0 = Rotation.from_rotvec([0.3, -0.5, 0.8]).as_quat()


def _reference(t, field, extra=None):
    """The reference (tests/rigid_reference.py) under ``m x R^T B(t)`` and ``extra(t, w, R)`` (body frame)."""
    return reference_run(I, W0, Q0, t, lambda time, w, R: np.cross(M, R.T @ field.world(time))
                         + (0.0 if extra is None else extra(time, w, R)))


def test_the_compass_needle_keeps_its_energy_and_swings_at_its_period(loop_runs):
    """In a uniform field the torque comes from the potential ``-m . B_b``: ``T - m . B_b`` is
    conserved. A dipole along axis 1 set along B and turned by 0.01 rad about axis 3 swings about
    it at ``sqrt(|m| |B| / I3)`` (the pendulum's small-angle frequency, to ``theta0^2 / 16``)."""
    field = UniformField(tuple(B))
    torque = ResidualDipole(tuple(M), field)
    t = np.linspace(0.0, 600.0, 3001)
    run = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=torque)
    assert loop_runs == [1] and run.method == "dop853"
    B_b = run.attitude.inv().apply(B)
    energy = 0.5 * np.sum(I * run.omega**2, axis=1) - B_b @ M
    swing = np.ptp(B_b @ M)
    assert swing > 0.2 * np.linalg.norm(M) * np.linalg.norm(B)  # the needle swung through much of its range
    assert np.abs(energy - energy[0]).max() < 1e-9 * swing

    m, b = 0.3, np.linalg.norm(B)
    needle = ResidualDipole((m, 0.0, 0.0), field)
    along_B = Rotation.align_vectors([B], [[1.0, 0.0, 0.0]])[0]  # body x along B
    theta0 = 0.01
    start = along_B * Rotation.from_rotvec([0.0, 0.0, theta0])
    period = 2 * math.pi / math.sqrt(m * b / I[2]) * (1 + theta0**2 / 16)
    t = np.linspace(0.0, 3 * period, 3001)
    swing = tumble.simulate(BODY, np.zeros(3), times=t, attitude0=start, torque=needle)
    angle = np.arctan2(-(swing.attitude.inv().apply(B) @ [0.0, 1.0, 0.0]), swing.attitude.inv().apply(B) @ [1.0, 0.0, 0.0])
    up = np.flatnonzero((angle[:-1] < 0.0) & (angle[1:] >= 0.0))  # upward crossings of zero
    crossings = t[up] - angle[up] * (t[up + 1] - t[up]) / (angle[up + 1] - angle[up])
    assert len(crossings) >= 2
    assert np.diff(crossings).mean() == pytest.approx(period, rel=1e-6)


def test_along_a_circular_orbit_in_the_dipole_field_beside_the_gravity_gradient(loop_runs):
    orbit = CircularOrbit(altitude=500e3, inclination=1.2)
    field = DipoleField(orbit, gmst0=0.4)
    gg = GravityGradient(orbit_radius=orbit.radius).bind(I)
    push = np.array([1e-7, 0.0, -2e-7])
    t = np.linspace(0.0, 3000.0, 151)

    def extra(time, w, R):
        return R.T @ gg(time, w, Rotation.from_matrix(R)) + push  # the gradient's torque is the world's

    omega, quat = _reference(t, field, extra)
    torque = ResidualDipole(tuple(M), field) + gg + ConstantTorque(tuple(push))
    run = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=torque)
    assert loop_runs == [1]
    e_omega, e_angle = errors(run, omega, quat)
    assert e_omega < 1e-9 and e_angle < 1e-9, (e_omega, e_angle)
    alone = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=gg + ConstantTorque(tuple(push)))
    assert np.abs(alone.omega - omega).max() > 1e3 * np.abs(run.omega - omega).max()  # the dipole acted


def test_along_an_orbit_in_the_igrf_field(loop_runs):
    pytest.importorskip("ppigrf")
    from tumble.dynamics import IGRFField, KeplerOrbit

    orbit = KeplerOrbit(6_900e3, 0.01, 1.7, raan=0.3)
    field = IGRFField(orbit, "2026-11-30T00:00:00")
    t = np.linspace(0.0, 2000.0, 101)
    omega, quat = _reference(t, field)
    run = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=ResidualDipole(tuple(M), field))
    assert loop_runs == [1]
    e_omega, e_angle = errors(run, omega, quat)
    assert e_omega < 1e-8 and e_angle < 1e-8, (e_omega, e_angle)  # the field's table, 5 s knots


def test_a_field_of_ones_own_keeps_the_python_path(loop_runs):
    class Ramp:
        def world(self, t):
            return B * (1.0 + 1e-3 * t)

    t = np.linspace(0.0, 300.0, 31)
    omega, quat = _reference(t, Ramp())
    run = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=ResidualDipole(tuple(M), Ramp()))
    assert loop_runs == []
    e_omega, e_angle = errors(run, omega, quat)
    assert e_omega < 1e-9 and e_angle < 1e-9, (e_omega, e_angle)


def test_a_dipole_given_in_the_design_frame_is_the_bodys_own(loop_runs):
    """``simulate(..., frame="design")`` reads the dipole, as omega0, in the body's design frame:
    the run is the reference's of the same body in its principal frame, the dipole turned by
    ``A^T`` (A principal -> design). Before 2026-11-30 the design-frame model was wrapped so that
    omega and the torque were turned but the attitude it read was the principal one: 0.78 rad/s off
    the right run of a T-handle in 2000 s, silently."""
    body = tumble.t_handle()
    A = body.properties.principal_axes
    moments = body.properties.principal_moments
    m_design, w_design = np.array([0.0, 2.0, 5.0]), np.array([0.3, 0.2, -0.4])
    field = UniformField(tuple(B))
    t = np.linspace(0.0, 200.0, 41)
    run = tumble.simulate(body, w_design, times=t, frame="design", torque=ResidualDipole(tuple(m_design), field))
    assert len(loop_runs) == 1   # compiled, the dipole turned once
    m, w0 = A.T @ m_design, A.T @ w_design
    q0 = run.attitude[0].as_quat()
    omega, quat = reference_run(moments, w0, q0, t, lambda time, w, R: np.cross(m, R.T @ B))
    e_omega, e_angle = errors(run, omega, quat)
    assert e_omega < 1e-9 and e_angle < 1e-9, (e_omega, e_angle)


@pytest.mark.parametrize(("args", "message"), [
    (((1.0, 0.0), UniformField((0.0, 3e-5, 0.0))), r"^dipole = \(1.0, 0.0\)"),
    (((1.0, 0.0, 0.0), (0.0, 3e-5, 0.0)), r"^field = \(0.0, 3e-05, 0.0\) must give world\(t\)"),
    (((1.0, 0.0, 0.0), type("Flat", (), {"world": lambda self, t: [1e-5, 2e-5]})()),
     r"^field.world\(0.0\) = \[1e-05, 2e-05\] must be 3 finite numbers \(T, world frame\)$"),
])
def test_bad_input_is_named(args, message):
    with pytest.raises(ValueError, match=message):
        ResidualDipole(*args)
