"""A slow body carrying a large wheel: the examples' T-handle with its wheel (bodies/t_handle_wheel.toml,
``|h| = 2.5 kg m^2/s``) turning at 0.02 rad/s, so that its nutation, ``~|h| / I``, is a thousand
times its own spin. ``atol`` is relative to the body's own spin
(:meth:`~tumble.dynamics.models.internal.InternalModel.tolerance_spin`), not to the nutation's rate;
``auto`` takes the closed loop's ``rk8`` along an ellipse where it is the cheaper. Against the
reference of tests/rigid_reference.py (scipy's DOP853 at rtol 1e-13) with the gyrostat's
``h x omega`` written here beside the torques (Hughes, *Spacecraft Attitude Dynamics*, sec. 3.4).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tumble
from rigid_reference import errors, reference_run
from tumble.dynamics.environment.ephemeris import KeplerOrbit
from tumble.dynamics.models.internal import InternalModel, Rotors
from tumble.dynamics.models.orbit_gravity import OrbitGravityGradient

#: bodies/t_handle_wheel.toml: the seed's two rods (1.5 kg, 1 m) and a 1 kg wheel of 0.1 m radius at
#: 500 rad/s on the crossbar.
BODY = tumble.Body([
    tumble.Rod(mass=1.5, length=1.0, axis=(0.0, 0.0, 1.0)),
    tumble.Rod(mass=1.5, length=1.0, center=(0.0, 0.0, 0.5), axis=(1.0, 0.0, 0.0)),
    tumble.Rotor(mass=1.0, radius=0.1, length=0.03, center=(0.0, 0.0, 0.5), axis=(1.0, 0.0, 0.0), spin_rate=500.0),
])
I = BODY.principal_moments
MODEL = InternalModel(I, Rotors.of(BODY))
H = MODEL.momentum(0.0)  # kg m^2/s, principal frame
W0 = np.array([0.02, 0.001, 0.001])  # rad/s, principal frame
Q0 = Rotation.from_rotvec([0.3, -0.5, 0.8]).as_quat()  # principal to world
ATTITUDE0 = (Rotation.from_quat(Q0) * Rotation.from_matrix(BODY.principal_axes).inv()).as_quat()  # design to world
T = np.linspace(0.0, 20.0, 201)  # s
ELLIPSE = KeplerOrbit(12_000e3, 0.4, 0.9, raan=0.4, arg_perigee=1.1, mean_anomaly=0.2)


def _python_push(time, w, R):
    """A torque written in Python (N m, body frame): scipy's path."""
    return np.array([0.0, 0.0, 1e-4 * np.sin(0.1 * time)])


def _gradient(time, w, R):
    """Hughes's ``3 mu / r^5 r_b x (I r_b)`` along the ellipse, ``r`` the orbit's own position."""
    r = R.T @ ELLIPSE.position_world(time)
    return 3.0 * ELLIPSE.mu / np.linalg.norm(r) ** 5 * np.cross(r, I * r)


#: The cases by name: the torque simulate gets, and the reference's torque beside ``h x omega``.
CASES = {"free": (None, None), "ellipse": (OrbitGravityGradient(ELLIPSE), _gradient),
         "python": (_python_push, _python_push)}


@pytest.fixture(scope="module")
def references():
    cache = {}

    def reference(case):
        if case not in cache:
            extra = CASES[case][1]
            cache[case] = reference_run(I, W0, Q0, T, lambda time, w, R: np.cross(H, w) + (
                0.0 if extra is None else extra(time, w, R)))
        return cache[case]

    return reference


def test_the_tolerance_spin_bounds_the_bodys_spin_far_below_the_nutations_rate(references):
    omega, _ = references("free")
    bound = MODEL.tolerance_spin(W0, T)
    # the body's energy is an integral of the torque-free gyrostat: |omega| stays under sqrt(2E / I1)
    assert np.linalg.norm(omega, axis=1).max() <= bound * (1.0 + 1e-9)
    assert np.linalg.norm(omega, axis=1).max() > 0.5 * bound  # and it is not loose
    assert bound < MODEL.spin_bound(W0, T) / 500.0  # 0.04 against 39 rad/s


@pytest.mark.parametrize("case", list(CASES))
def test_dop853_keeps_its_accuracy_on_a_slow_body_with_a_large_wheel(references, loop_runs, case):
    """The engine (free), the closed loop's kernel (ellipse), scipy's path (a Python torque), each at
    dop853's default rtol 1e-12: its atol relative to the nutation's 39 rad/s left 4.4e-8, 2.3e-9 and
    5.6e-8 in omega (measured before); relative to the body's own spin 7.3e-11, 7.9e-11, 1.2e-10."""
    omega, quat = references(case)
    run = tumble.simulate(BODY, W0, times=T, attitude0=ATTITUDE0, frame="principal", method="dop853",
                          torque=CASES[case][0])
    assert run.method == "dop853" and loop_runs == ([1] if case == "ellipse" else [])
    e_omega, e_angle = errors(run, omega, quat)
    assert e_omega < 1e-9 and e_angle < 1e-11, (e_omega, e_angle)


def test_auto_takes_the_loops_rk8_along_an_ellipse_and_meets_its_rtol(references, loop_runs):
    """Along an ellipse ``auto`` prices the closed loop's ``rk8`` against its ``dop853`` as it does
    the engine's (it ran dop853 there always: 9.4e-10 in omega at rtol 1e-10, measured before;
    rk8 2.9e-12)."""
    omega, quat = references("ellipse")
    run = tumble.simulate(BODY, W0, times=T, attitude0=ATTITUDE0, frame="principal",
                          torque=OrbitGravityGradient(ELLIPSE))
    assert run.auto and run.method == "rk8" and loop_runs == [1]
    e_omega, e_angle = errors(run, omega, quat)
    assert e_omega < 1e-10 and e_angle < 1e-10, (e_omega, e_angle)
