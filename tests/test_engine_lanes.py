"""The fixed-step batch in vector lanes (:mod:`tumble.dynamics.engine.lanes`) against the one-body kernels.

Each body of a block takes the same steps as alone with the same sums in the same order, so the
samples agree to round-off: the compiler may fuse the multiply-adds of a vector differently from
a scalar's (``fastmath={"contract"}``), an ulp here and there, which a tumbling body then carries.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tumble.dynamics.engine import front, kernels, lanes
from tumble.dynamics.engine.status import NON_FINITE, OK
from tumble.dynamics.engine.tableau import DOP853_A, DOP853_B, DOP853_C
from tumble.dynamics.engine.unrolled import fixed_step_source, lane_step_source

#: The torque terms of every kind at once (kernels' module docstring): body and world torques, a
#: circular orbit's gravity gradient (n = 1e-3 rad/s) and rotors' momentum.
ALL_TERMS = ((0.01, -0.02, 0.015, 0.003, 0.0, -0.004, 1e-6, 0.02, -0.01, 0.03), 1e-3)
BODY_TORQUE = ((0.01, -0.02, 0.015, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0), 0.0)


def _bodies(n: int, seed: int = 3) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    I = np.sort(rng.uniform(0.5, 1.0, (n, 3)), axis=1)
    y0 = np.concatenate([rng.normal(size=(n, 3)) * 3.0, Rotation.random(n, random_state=seed).as_quat()], axis=1)
    return I, y0


def _alone(method: str, y0, t, I, P, n, h):
    run = kernels.fixed_rk4 if method == "rk4" else kernels.fixed_rk8
    omega, quat = np.empty((len(I), len(t), 3)), np.empty((len(I), len(t), 4))
    for b in range(len(I)):
        assert run(y0[b], t, I[b], P, n, h[b], omega[b], quat[b]) == OK
    return omega, quat


def _lanes(method: str, y0, t, I, P, n, h):
    omega, quat = np.empty((len(I), len(t), 3)), np.empty((len(I), len(t), 4))
    status = np.zeros(len(I), dtype=np.int64)
    front._in_lanes(method, y0, t, I, P, n, h, omega, quat, status)
    assert not status.any()
    return omega, quat


@pytest.mark.parametrize("method", ["rk4", "rk8"])
@pytest.mark.parametrize(("terms", "steps"), [(BODY_TORQUE, "one"), (ALL_TERMS, "one"), (ALL_TERMS, "each its own")])
def test_lanes_agree_with_each_body_alone_to_round_off(method, terms, steps):
    """37 bodies (two full blocks and a part, whose last lanes repeat its last body), one step for
    all or each body its own (sorted into blocks; a block whose bodies split an interval differently
    runs again body by body): every torque term of the kernels in lanes."""
    assert lanes.LANES == 16  # the blocks below
    I, y0 = _bodies(37)
    t = np.linspace(0.0, 2.0, 11)
    rng = np.random.default_rng(4)
    # each its own: 17 bodies at 6 steps an interval, 20 at 4 (the steps a little over 0.2 s / m, each body's
    # own): sorted, a block of 16 at 6, a block that mixes them (body by body), 5 at 4
    h = np.full(37, 0.05) if steps == "one" else 0.2 / np.repeat([6, 4], [17, 20]) * (1.0 + rng.uniform(0, 0.01, 37))
    rng.shuffle(h)
    omega, quat = _lanes(method, y0, t, I, *terms, h)
    omega_alone, quat_alone = _alone(method, y0, t, I, *terms, h)
    np.testing.assert_allclose(omega, omega_alone, rtol=0, atol=1e-13 * np.abs(omega_alone).max())
    np.testing.assert_allclose(quat, quat_alone, rtol=0, atol=1e-13)


def test_a_block_whose_bodies_split_an_interval_differently_ends_non_finite():
    """Steps of 0.1 s and 0.06 s split a 0.2 s interval into 2 and 4: the block cannot step them
    together and says so (the front then runs its bodies one by one)."""
    I, y0 = _bodies(lanes.LANES)
    t = np.array([0.0, 0.2])
    h = np.full(lanes.LANES, 0.1)
    h[-1] = 0.06
    status = np.zeros(1, dtype=np.int64)
    lanes.lanes_rk8(y0, t, I, *BODY_TORQUE, h, np.arange(lanes.LANES), np.empty((lanes.LANES, 2, 3)),
                    np.empty((lanes.LANES, 2, 4)), status)
    assert status.tolist() == [NON_FINITE]
    h[-1] = 0.09  # 3 steps where 0.1 gives 2: still split
    lanes.lanes_rk8(y0, t, I, *BODY_TORQUE, h, np.arange(lanes.LANES), np.empty((lanes.LANES, 2, 3)),
                    np.empty((lanes.LANES, 2, 4)), status)
    assert status.tolist() == [NON_FINITE]
    h[-1] = 0.11  # 2 steps, as 0.1: one block
    lanes.lanes_rk8(y0, t, I, *BODY_TORQUE, h, np.arange(lanes.LANES), np.empty((lanes.LANES, 2, 3)),
                    np.empty((lanes.LANES, 2, 4)), status)
    assert status.tolist() == [OK]


def test_an_overflowing_body_in_lanes_is_named():
    I, y0 = _bodies(12)
    P = (0.0, 0.0, np.inf) + (0.0,) * 7
    status = np.zeros(12, dtype=np.int64)
    front._in_lanes("rk8", y0, np.array([0.0, 1.0]), I, P, 0.0, np.full(12, 0.1), np.empty((12, 2, 3)),
                    np.empty((12, 2, 4)), status)
    assert (status == NON_FINITE).all()


def test_the_lane_step_is_the_tableau_s_step_written_over_lanes():
    """Each stage's state sums the tableau's nonzero weights of the slopes before it, in stage order
    (as the one-body step sums them), with the weights as written in the tableau; one right-hand
    side for all stages."""
    A, B, C = DOP853_A[:12, :12], DOP853_B, DOP853_C[:12]
    one, source = fixed_step_source("step", A, B, C), lane_step_source("step", A, B, C, 8)
    assert source.count("rhs(") == 1 and one.count("rhs(") == 12
    states = re.findall(r"^ +z = (.*)$", source, flags=re.M)
    assert len(states) == 12 and states[0] == "y"
    for s in range(1, 12):  # stage s's state, component 0: y[0] + h * (w_r * k_r[0] + ...)
        terms = re.findall(r"(-?[0-9.e+-]+) \* k(\d+)\[0\]", states[s].split(", y[1]")[0])
        assert [(float(w), int(r)) for w, r in terms] == [(float(A[s, r]), r) for r in range(s) if A[s, r] != 0.0]
