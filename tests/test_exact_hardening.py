"""The exact torque-free motion at its edges: degenerate bodies, underflow, near-separatrix
accuracy, huge phases. Each case against an independent reference (DOP853 at rtol 1e-12, or
arbitrary-precision mpmath) and the invariants of the motion."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

import tumble
from tumble.dynamics import simulate
from tumble.dynamics.exact import FreeRotation
from tumble.mass import MassProperties, principal_frame

SETTINGS = settings(max_examples=25, deadline=None, derandomize=True)


def _rotation(q) -> Rotation:
    return Rotation.from_quat(np.asarray(q) / np.linalg.norm(q))


quaternions = st.tuples(*[st.floats(-1.0, 1.0)] * 4).filter(lambda q: np.linalg.norm(q) > 0.1)
# components of ordinary size or exactly zero (tiny ones are the underflow tests' business)
components = st.floats(-1.0, 1.0).map(lambda x: x if abs(x) > 1e-6 else 0.0)
directions = st.tuples(*[components] * 3).filter(lambda v: np.linalg.norm(v) > 0.1)
sizes = st.floats(1e-3, 1e3)
speeds = st.floats(0.3, 3.0)


def _body(moments, q) -> MassProperties:
    """A body whose design-frame tensor is ``R diag(moments) R^T`` (round-off included)."""
    R = _rotation(q).as_matrix()
    return MassProperties.from_inertia(1.0, np.zeros(3), R @ np.diag(moments) @ R.T)


def _check_against_dop853(body, w0, frame="design", t_end=5.0):
    """Exact against DOP853 (rtol 1e-12), and the exact motion's invariants to ~1e-12."""
    att0 = Rotation.from_rotvec([0.4, -0.3, 1.2])
    ex = simulate(body, w0, frame=frame, t_end=t_end, samples=101, attitude0=att0)
    ref = simulate(body, w0, frame=frame, t_end=t_end, samples=101, attitude0=att0, method="dop853")
    assert ex.method == "exact"
    scale = np.max(np.abs(ref.omega))
    np.testing.assert_allclose(ex.omega, ref.omega, atol=1e-9 * scale, rtol=0)
    assert np.max((ex.attitude * ref.attitude.inv()).magnitude()) < 1e-9
    for name, value in ex.drift.items():
        assert value is None or value < 1e-12, (name, value)  # None: nothing to drift (at rest)


# -- 2b: spheres, symmetric tops, nearly symmetric bodies ------------------------------------

def test_the_audited_sphere_simulates():
    body = MassProperties.from_inertia(1.0, [0, 0, 0], 0.0794 * np.eye(3))
    _check_against_dop853(body, [2.12, -1.84, -0.83], frame="principal", t_end=10.0)


@SETTINGS
@given(sizes, quaternions, directions, speeds)
def test_random_spheres(size, q, direction, speed):
    body = _body([size] * 3, q)
    assert body.principal_moments[0] == body.principal_moments[2]  # declared spherical, exactly
    w0 = speed * np.asarray(direction) / np.linalg.norm(direction)
    _check_against_dop853(body, w0)


@SETTINGS
@given(sizes, st.sampled_from([0.55, 0.8, 0.95, 1.05, 1.4, 1.9]), quaternions, directions, speeds,
       st.sampled_from(["random", "along", "perpendicular"]))
def test_random_symmetric_tops(size, ratio, q, direction, speed, kind):
    """Oblate (ratio > 1: the odd moment is the largest) and prolate tops, omega random, along
    the symmetry axis or perpendicular to it (in the design frame, so to round-off only)."""
    body = _body([size, size, ratio * size], q)
    I = body.principal_moments
    axis_index = 2 if ratio > 1 else 0
    assert I[1] == I[2 - axis_index]  # declared symmetric, exactly
    axis = body.principal_axes[:, axis_index]
    d = np.asarray(direction) / np.linalg.norm(direction)
    if kind == "along":
        d = axis
    elif kind == "perpendicular":
        d = np.cross(axis, d)
        d /= np.linalg.norm(d)
    _check_against_dop853(body, speed * d)


@SETTINGS
@given(sizes, st.floats(-12.0, -6.0), st.booleans(), quaternions, directions, speeds,
       st.sampled_from(["random", "perpendicular"]))
def test_nearly_symmetric_bodies(size, log_gap, oblate, q, direction, speed, kind):
    """Relative gaps of 1e-12..1e-6: below and above the degeneracy tolerance 1e-9 * trace."""
    gap = 10.0**log_gap
    moments = [size, size * (1 + gap), 1.5 * size] if oblate else [0.6 * size, size, size * (1 + gap)]
    body = _body(moments, q)
    I = body.principal_moments
    pair = (0, 1) if oblate else (1, 2)
    declared = I[pair[0]] == I[pair[1]]
    assert declared == (I[pair[1]] - I[pair[0]] <= 1e-9 * np.sum(I))
    d = np.asarray(direction) / np.linalg.norm(direction)
    if kind == "perpendicular":
        d = np.cross(body.principal_axes[:, 2 if oblate else 0], d)
        d /= np.linalg.norm(d)
    _check_against_dop853(body, speed * d)


@pytest.mark.parametrize(
    ("moments", "w0"),
    [
        ((1.0, 1.0, 1.5), (0.3, -0.4, 0.0)),   # oblate top spinning in its degenerate plane
        ((1.0, 1.5, 1.5), (0.0, 0.3, -0.4)),   # prolate top, the same
        ((1.0, 1.0, 1.5), (0.0, 0.0, 2.0)),    # along the symmetry axis, exactly
        ((1.0, 1.5, 1.5), (-2.0, 0.0, 0.0)),
        ((1.0, 2.0, 2.5), (0.0, 0.0, 0.0)),    # at rest
    ],
)
def test_steady_cases_decided_exactly(moments, w0):
    motion = FreeRotation(np.array(moments), np.array(w0), Rotation.identity())
    assert motion.steady
    _check_against_dop853(MassProperties.from_inertia(1.0, np.zeros(3), np.diag(moments)), w0, frame="principal")


def test_principal_frame_returns_degenerate_moments_equal():
    R = Rotation.from_rotvec([0.3, -1.1, 0.7]).as_matrix()
    for moments, equal in [([2.0, 2.0, 2.0], (0, 1, 2)), ([1.0, 1.0, 1.7], (0, 1)), ([1.0, 1.7, 1.7], (1, 2))]:
        I, _ = principal_frame(R @ np.diag(moments) @ R.T)
        assert len({float(I[k]) for k in equal}) == 1
        np.testing.assert_allclose(I, sorted(moments), rtol=1e-15)
    # batched, with the cluster's mean
    I, _ = principal_frame(np.stack([np.diag([1.0, 1.0 + 1e-12, 3.0]), np.diag([1.0, 2.0, 3.0])]))
    assert I[0, 0] == I[0, 1] == 0.5 * (1.0 + (1.0 + 1e-12)) and I[1].tolist() == [1.0, 2.0, 3.0]
