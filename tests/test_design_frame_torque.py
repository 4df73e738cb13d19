"""A body-frame torque given in the design frame (``frame="design"``) works with every method:
the splitting methods pass omega as an (n, 3) stack, the others as one vector."""

import numpy as np
import pytest

import tumble


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
