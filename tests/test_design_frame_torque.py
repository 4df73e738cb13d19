"""A body-frame torque given in the design frame (``frame="design"``) works with every method:
the splitting methods pass omega as an (n, 3) stack, the others as one vector."""

import numpy as np
import pytest

import tumble
from tumble.dynamics import ResidualDipole, UniformField


@pytest.mark.parametrize("method", ["geometric", "geometric6", "exact_split6", "rk45"])
def test_design_frame_body_torque_is_the_principal_one_rotated(method):
    body = tumble.t_handle()
    A = np.asarray(body.principal_axes)   # principal -> design
    tau_design = np.array([0.01, 0.002, -0.003])   # N m
    w_design = np.array([0.0, 10.0, 0.1])           # rad/s
    design = tumble.simulate(body, w_design, t_end=1.0, frame="design", torque=tumble.ConstantTorque(tau_design),
                             method=method, rtol=1e-11, atol=1e-13) if method == "rk45" else \
        tumble.simulate(body, w_design, t_end=1.0, frame="design", torque=tumble.ConstantTorque(tau_design),
                        method=method)
    reference = tumble.simulate(body, A.T @ w_design, t_end=1.0, torque=tumble.ConstantTorque(A.T @ tau_design),
                                method="dop853", rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(design.omega, reference.omega, rtol=0, atol=5e-9 * 10.0)


def test_a_python_torque_in_the_design_frame_reads_omega_and_the_attitude_there():
    """A function given with ``frame="design"`` is called as on the design frame: omega in design
    coordinates and the design frame's attitude (it was handed the principal frame's attitude beside
    a design omega, and a magnet's torque m x B_body came out wrong: 0.81 rad/s off after 5 s).
    Checked against the built-in ResidualDipole with the same design-frame dipole, which the run turns
    to the principal frame itself, and against the attitude each call receives."""
    body = tumble.t_handle()
    m, B = np.array([0.0, 0.0, 50.0]), np.array([1e-3, 0.0, 0.0])  # A m^2 (design frame), T (world)
    seen = []

    def magnet(t, omega, attitude):  # N m, design frame: m x B with B read in the design frame
        seen.append((np.asarray(omega, float).copy(), attitude))
        return np.cross(m, attitude.inv().apply(B))

    w0 = [0.0, 0.5, 0.0]
    mine = tumble.simulate(body, w0, t_end=5.0, frame="design", torque=magnet, rtol=1e-11)
    built_in = tumble.simulate(body, w0, t_end=5.0, frame="design", torque=ResidualDipole(tuple(m), UniformField(B)),
                               method="dop853", rtol=1e-11)
    np.testing.assert_allclose(mine.omega, built_in.omega, rtol=0, atol=1e-8)
    omega, attitude = seen[0]  # the first call, at t = 0: the design frame starts as the world's (attitude0)
    np.testing.assert_allclose(omega, w0, atol=1e-15)
    np.testing.assert_allclose(attitude.as_matrix(), np.eye(3), atol=1e-12)
