"""The centre of mass's solve (tumble.analysis.tensor.center) against independent computations:
the block-by-block reduction against one dense least squares of the stacked design, the sensors'
columns against the whole estimate's own differences."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tumble.analysis.tensor.center as C
from tumble.analysis.tensor.model import ThrowModel, cholesky_of, rotor_input


def _throw(seed: int, L, r=(0.03, -0.01, 0.02), noise=0.3):
    """A torque-free tumble (no rotor) at 4 kHz for 0.5 s and its accelerometer at ``r`` (m) from the centre."""
    t = np.arange(2000) / 4000.0
    m = ThrowModel(t, np.zeros((2000, 3)), np.ones((2000, 3), bool), rotor_input(t, np.zeros(2000), 0, 1e-6, [0, 0, 1]))
    P = np.r_[cholesky_of(np.diag([2e-4, 3e-4, 4e-4])), L, np.zeros(8)]
    w = m.omega(P[None])[0]
    f = np.cross(w, np.cross(w, r)) + np.random.default_rng(seed).normal(0.0, noise, (2000, 3))
    return m, w, f


def test_the_reduced_solve_is_the_dense_least_squares():
    """Eliminating each throw's air unknowns (Bjorck's block-angular least squares) gives the
    stacked problem's answer with its prior rows, to round-off."""
    throws = [_throw(s, L) for s, L in ((1, [3e-3, 2e-3, 4e-3]), (2, [-2e-3, 4e-3, 1e-3]), (3, [1e-3, -1e-3, 5e-3]))]
    rows = [C._rows(C._geometry(w, m.t, f), 150.0) for m, w, f in throws]
    rhs = [C._geometry(w, m.t, f).rhs for m, w, f in throws]
    weights = C._priors(3, 2e-3)
    x = C._lsq(rows, rhs, weights)[0]
    K = len(rows)
    A = np.zeros((sum(3 * len(R) for R in rows), 6 + 6 * K))
    at = 0
    for k, R in enumerate(rows):
        n = 3 * len(R)
        A[at:at + n, :6] = R[:, :, :6].reshape(n, 6)
        A[at:at + n, 6 + 6 * k:12 + 6 * k] = R[:, :, 6:].reshape(n, 6)
        at += n
    y = np.concatenate([v.ravel() for v in rhs])
    dense = np.linalg.lstsq(np.vstack([A, np.diag(weights)]), np.r_[y, np.zeros(weights.size)], rcond=None)[0]
    np.testing.assert_allclose(x[:6], dense[:6], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(x, dense, rtol=1e-7, atol=1e-9)


@pytest.mark.parametrize("noise", [0.05, 0.3])
def test_the_sensor_columns_are_the_estimates_own_response(noise):
    """Each column (one solve) is the whole estimate's change (jolts trimmed, priors' weights from
    the residuals, all made again) for a small scale factor of one accelerometer axis or a small
    turn of the rates, by central differences, within 0.5 % of the largest column entry."""
    m, w, f = _throw(4, [3e-3, 2e-3, 4e-3], noise=noise)
    S = C.sensor_columns([m], [w], [f], np.inf, 1.0)
    eps = 1e-5

    def centre(rates, reading):
        return C.center_of_mass([m], [rates], [reading], np.inf, covariance=False, trim=True)[0]

    cols = []
    for k in range(3):
        up, down = np.ones(3), np.ones(3)
        up[k], down[k] = 1 + eps, 1 - eps
        cols.append((centre(w, f * up) - centre(w, f * down)) / (2 * eps) * C.ACCEL_SCALE_STD)
    for k in range(3):
        R = Rotation.from_rotvec(eps * np.eye(3)[k]).as_matrix()
        cols.append((centre(w @ R.T, f) - centre(w @ R, f)) / (2 * eps))
    np.testing.assert_allclose(S, np.array(cols).T, rtol=0, atol=5e-3 * np.abs(S).max())
