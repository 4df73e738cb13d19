"""Inertia-tensor operations: rotation, parallel-axis shift, validation, principal frame."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation
from strategies import ANY_SIZE, bodies, rotations, vectors

from tumble.mass import (
    Body,
    Cylinder,
    check_inertia,
    inertia_about_point,
    parallel_axis,
    point_mass_inertia,
    principal_frame,
    rotate_inertia,
)


def test_point_mass_inertia_matches_definition():
    # I_ij = m (|r|^2 delta_ij - r_i r_j), seed sec. 2.1, written out by hand for r = (1, 2, 3)
    m, r = 2.0, np.array([1.0, 2.0, 3.0])
    expected = 2.0 * np.array([[13.0, -2.0, -3.0], [-2.0, 10.0, -6.0], [-3.0, -6.0, 5.0]])
    np.testing.assert_allclose(point_mass_inertia(m, r), expected)


def test_parallel_axis_textbook_rod_about_its_end():
    # a rod of length L about its end: m L^2 / 3 (Meriam & Kraige Table D/4)
    m, L = 3.0, 2.0
    I_com = np.diag([m * L**2 / 12, m * L**2 / 12, 0.0])
    I_end = parallel_axis(I_com, m, [0.0, 0.0, L / 2])
    np.testing.assert_allclose(np.diag(I_end), [m * L**2 / 3, m * L**2 / 3, 0.0])


@ANY_SIZE
@given(bodies(), vectors)
def test_shift_to_a_point_and_back_is_identity(body, point):
    I_p = body.inertia_about(point)
    back = parallel_axis(I_p, -body.mass, np.asarray(body.com) - point)  # remove the shift
    np.testing.assert_allclose(back, body.inertia, atol=1e-9 * np.trace(I_p))


@ANY_SIZE
@given(bodies(), rotations())
def test_rotation_preserves_invariants(body, rot):
    I = body.inertia
    J = rotate_inertia(I, rot)
    np.testing.assert_allclose(np.trace(J), np.trace(I), rtol=1e-12)
    np.testing.assert_allclose(np.linalg.eigvalsh(J), np.linalg.eigvalsh(I), atol=1e-10 * np.trace(I))
    np.testing.assert_allclose(rotate_inertia(J, rot.inv()), I, atol=1e-10 * np.trace(I))


@ANY_SIZE
@given(bodies())
# A symmetric top whose plane of equal moments is 4e-5 rad off holding the frame's z axis: the
# projection of y onto it is 1e-5 long, and Gram-Schmidt on it left the axes 3e-12 off orthogonal.
@example(Body(parts=(Cylinder(mass=1.0, axis=(0.707106780528003, 0.707106780528003, 4.315837283496112e-05),
                              radius=1.0, length=1.0),)))
def test_principal_frame_rebuilds_tensor_and_is_right_handed(body):
    """Rebuilt to 1e-10 of the trace, and beyond it only by the gap principal_frame declares degenerate (its
    docstring: moments within INERTIA_RTOL of the trace are returned as their mean): a body whose I2 and I3 were
    4.8e-10 of the trace apart was rebuilt 4.1e-7 off (make test, 2026-12-03), within that gap."""
    from tumble.mass import INERTIA_RTOL

    moments, axes = principal_frame(body.inertia)
    assert np.all(np.diff(moments) >= 0)
    np.testing.assert_allclose(axes.T @ axes, np.eye(3), atol=1e-12)
    assert np.linalg.det(axes) == pytest.approx(1.0, abs=1e-12)
    snapped = float(np.max(np.abs(np.linalg.eigvalsh(body.inertia) - moments)))  # what the mean moved, kg m^2
    assert snapped <= INERTIA_RTOL * moments.sum()
    np.testing.assert_allclose(axes @ np.diag(moments) @ axes.T, body.inertia, atol=1e-10 * moments.sum() + snapped)


@ANY_SIZE
@given(st.lists(bodies(max_parts=3), min_size=2, max_size=4))
def test_functions_broadcast_over_a_batch(batch):
    I = np.stack([b.inertia for b in batch])
    moments, axes = principal_frame(I)
    for k, b in enumerate(batch):
        m1, a1 = principal_frame(b.inertia)
        np.testing.assert_allclose(moments[k], m1)
        np.testing.assert_allclose(axes[k], a1)
    assert check_inertia(I).shape == I.shape


def test_sign_convention_is_deterministic_and_frame_independent():
    # the same tensor given with eigenvectors of either sign yields the same axes
    rot = Rotation.from_euler("xyz", [0.3, -0.7, 1.1])
    I = rotate_inertia(np.diag([1.0, 2.0, 2.5]), rot)
    _, axes = principal_frame(I)
    for sign in ([1, 1, 1], [-1, 1, -1], [1, -1, -1]):
        vecs = rot.as_matrix() * np.array(sign)
        _, again = principal_frame(vecs @ np.diag([1.0, 2.0, 2.5]) @ vecs.T)
        np.testing.assert_allclose(again, axes, atol=1e-12)
    for j in (0, 1):
        assert axes[np.argmax(np.abs(axes[:, j])), j] > 0


def test_degenerate_moments_get_frame_axes():
    # symmetric top along z: the degenerate plane is spanned by x, y
    moments, axes = principal_frame(np.diag([2.0, 2.0, 1.0]))
    np.testing.assert_allclose(moments, [1.0, 2.0, 2.0])
    np.testing.assert_allclose(axes, [[0, 1, 0], [0, 0, 1], [1, 0, 0]], atol=1e-15)
    # sphere: the input frame itself
    _, axes = principal_frame(3.0 * np.eye(3))
    np.testing.assert_allclose(axes, np.eye(3))


def test_triangle_inequality_violation_message():
    with pytest.raises(ValueError, match=r"\(1, 1, 3\) kg m\^2 violate the triangle inequality I1 \+ I2 >= I3"):
        check_inertia(np.diag([1.0, 1.0, 3.0]))


def test_planar_body_on_the_triangle_boundary_is_accepted():
    # I1 + I2 == I3 exactly for a planar body; round-off must not reject it
    rot = Rotation.from_rotvec([0.2, 0.5, -0.3])
    check_inertia(rotate_inertia(np.diag([0.125, 0.3125, 0.4375]), rot))


@pytest.mark.parametrize(
    ("tensor", "pattern"),
    [
        (np.diag([-1.0, 2.0, 2.0]), "negative principal moment"),
        ([[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], "not symmetric"),
        (np.diag([1.0, np.nan, 1.0]), "non-finite"),
        (np.ones((2, 2)), r"shape \(\.\.\., 3, 3\)"),
    ],
)
def test_impossible_tensors_are_refused(tensor, pattern):
    with pytest.raises(ValueError, match=pattern):
        check_inertia(tensor)


def test_batch_error_names_the_index():
    batch = np.stack([np.eye(3), np.eye(3), np.diag([1.0, 1.0, 3.0])])
    with pytest.raises(ValueError, match=r"at index \(2,\)"):
        check_inertia(batch)


def test_inertia_about_point_for_point_masses():
    # independent route: sum of m (|r - p|^2 E - (r - p)(r - p)^T) over the masses
    rng = np.random.default_rng(1)
    m, r, p = rng.uniform(0.1, 2, 5), rng.normal(size=(5, 3)), rng.normal(size=3)
    com = (m[:, None] * r).sum(0) / m.sum()
    I_com = point_mass_inertia(m, r - com).sum(0)
    direct = sum(mi * ((ri - p) @ (ri - p) * np.eye(3) - np.outer(ri - p, ri - p)) for mi, ri in zip(m, r))
    np.testing.assert_allclose(inertia_about_point(I_com, m.sum(), com, p), direct, rtol=1e-12, atol=1e-12)


def test_inertia_about_point_names_the_bad_argument_and_index():
    I_com, m = np.diag([1.0, 2.0, 2.5]), 2.0
    with pytest.raises(ValueError, match=r"^point = \[nan, 0.0, 0.0\] must be finite numbers \(m\)"):
        inertia_about_point(I_com, m, [0.0, 0.0, 0.0], [np.nan, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"^point\[1, 0\] = \[0.0, 0.0, inf\] must be finite"):
        inertia_about_point(I_com, m, [0.0, 0.0, 0.0], [[[0.0, 0.0, 0.0]], [[0.0, 0.0, np.inf]]])
    with pytest.raises(ValueError, match=r"^com = \[0.0, 0.0\] must be real numbers of shape \(\.\.\., 3\)"):
        inertia_about_point(I_com, m, [0.0, 0.0], [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"^point = \[True, False, True\] must be real numbers"):
        inertia_about_point(I_com, m, [0.0, 0.0, 0.0], [True, False, True])


@given(st.one_of(
    st.dictionaries(st.integers(0, 2), st.floats(), min_size=3, max_size=3),
    st.sets(st.floats(allow_nan=False), min_size=3, max_size=3),
    st.text(),
    st.lists(st.floats(), min_size=0, max_size=2),
    st.lists(st.floats(), min_size=4, max_size=6),
    st.tuples(st.floats(), st.floats(), st.floats()).filter(lambda v: not np.all(np.isfinite(v))),
))
def test_inertia_about_point_never_returns_nan(point):
    with pytest.raises(ValueError, match=r"^point"):
        inertia_about_point(np.eye(3), 1.0, [0.0, 0.0, 0.0], point)
