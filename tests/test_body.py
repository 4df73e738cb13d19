"""Composite bodies: the seed T-handle, the space-station handle, and physical properties."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from hypothesis import given
from scipy.spatial.transform import Rotation
from strategies import ANY_SIZE, bodies, rotations, vectors

import tumble


def test_seed_t_handle_closed_form():
    """Seed parameters (thin rods, 1 m, 1.5 kg, crossbar centred on the shaft's top end).

    By hand: COM at z = (1.5 * 0 + 1.5 * 0.5) / 3 = 0.25 m. About the COM each rod is 0.25 m away
    along z, so I_x = 1.5/12 + 1.5 * 0.25^2 (shaft) + 0 + 1.5 * 0.25^2 (crossbar) = 0.3125;
    I_y = 1.5/12 + 1.5/16 + 1.5/12 + 1.5/16 = 0.4375; I_z = 0 + 1.5/12 = 0.125 kg m^2.
    """
    body = tumble.t_handle()
    assert body.mass == 3.0
    np.testing.assert_allclose(body.com, [0, 0, 0.25], atol=1e-15)
    np.testing.assert_allclose(body.inertia, np.diag([0.3125, 0.4375, 0.125]), atol=1e-15)
    np.testing.assert_allclose(body.principal_moments, [0.125, 0.3125, 0.4375], atol=1e-15)
    # shaft (z) minor, crossbar (x) intermediate, normal to the T (y) major
    np.testing.assert_allclose(body.principal_axes, [[0, 1, 0], [0, 0, 1], [1, 0, 0]], atol=1e-15)
    np.testing.assert_allclose(body.properties.intermediate_axis, [1, 0, 0], atol=1e-15)


def test_seed_printed_formula_differs():
    """The seed's sec. 2.4 total omits the shaft's own parallel-axis term (docs/seed-errata.md)."""
    m, L = 1.5, 1.0
    d_x, d_z = 0.25, 0.25  # the seed's offsets read as the crossbar's distance from the COM
    seed = np.diag([m * L**2 / 12 + m * d_x**2, m * L**2 / 12 + m * L**2 / 12, m * L**2 / 12 + m * d_z**2])
    assert not np.allclose(seed, tumble.t_handle().inertia)


def test_the_seed_codes_geometry_and_what_its_formula_says_of_each():
    """docs/seed-errata.md secs. 2-3 (corrected after a walkthrough, 2026-12-03, which found "an L" to be a T on its
    side): the seed's code has the crossbar along x centred at (L_s/2, 0, 0), its end at the shaft's middle. By hand:
    COM (0.25, 0, 0); the shaft's 1/8 about x and y plus 1.5 * 0.25^2 about y and z, the crossbar's 1/8 about y and
    z plus the same: diag(0.125, 0.4375, 0.3125): x minor (the seed's runs stable), z intermediate. The seed's
    formula makes x intermediate there and minor in the derivation's T: wrong in both."""
    m, L = 1.5, 1.0
    code = tumble.Body([tumble.Rod(mass=m, length=L, axis=(0, 0, 1)), tumble.Rod(mass=m, length=L, center=(L / 2, 0, 0),
                                                                               axis=(1, 0, 0))])
    np.testing.assert_allclose(code.com, [0.25, 0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(code.inertia, np.diag([0.125, 0.4375, 0.3125]), atol=1e-15)
    np.testing.assert_allclose(code.properties.intermediate_axis, [0, 0, 1], atol=1e-15)

    def seed_formula(d_x, d_z):
        return np.array([m * L**2 / 12 + m * d_x**2, m * L**2 / 12 + m * L**2 / 12, m * L**2 / 12 + m * d_z**2])

    assert np.argsort(seed_formula(0.25, 0.0))[1] == 0 != np.argsort(np.diag(code.inertia))[1]  # x "intermediate"
    assert np.argsort(seed_formula(0.0, 0.25))[0] == 0  # x "minor" in the derivation's T, where it is intermediate
    np.testing.assert_allclose(tumble.t_handle().properties.intermediate_axis, [1, 0, 0], atol=1e-15)


def test_iss_handle_shaft_is_intermediate():
    body = tumble.iss_t_handle()
    np.testing.assert_allclose(body.properties.intermediate_axis, [0, 0, 1], atol=1e-12)
    # steel 8050 kg/m^3: pi (0.004^2 * 0.05 + 0.0075^2 * 0.1) * 8050
    assert body.mass == pytest.approx(np.pi * (0.004**2 * 0.05 + 0.0075**2 * 0.1) * 8050, rel=1e-14)


def test_iss_handle_against_a_mesh_of_the_same_solid():
    body = tumble.iss_t_handle()
    shaft = trimesh.creation.cylinder(radius=0.004, height=0.05, sections=256)
    bar = trimesh.creation.cylinder(radius=0.0075, height=0.1, sections=256)
    bar.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]))
    bar.apply_translation([0, 0, 0.025 + 0.0075])  # touching, as the preset documents
    both = trimesh.util.concatenate([shaft, bar])
    assert both.is_watertight
    props = both.mass_properties
    np.testing.assert_allclose(props.center_mass, body.com, atol=1e-6)
    I = props.inertia * 8050
    np.testing.assert_allclose(I, body.inertia, atol=5e-4 * np.trace(I))


def test_t_handle_with_radii_accepts_density_or_masses_not_both():
    with pytest.raises(ValueError, match="either 'density' or the masses"):
        tumble.t_handle(shaft_radius=0.01, crossbar_radius=0.01, density=1000.0, shaft_mass=1.0)
    with pytest.raises(ValueError, match="shaft: .*thin rod has no volume"):
        tumble.t_handle(density=1000.0)


@ANY_SIZE
@given(bodies(), rotations(), vectors)
def test_moving_a_body_rotates_its_tensor(body, rot, shift):
    """Independent route: move every part, recompute; equals R I R^T and R com + t."""
    moved = body.moved(rot, shift)
    R = rot.as_matrix()
    scale = np.trace(body.inertia_about([0.0, 0.0, 0.0]))  # m r^2 of the parts: round-off scale
    np.testing.assert_allclose(moved.inertia, R @ body.inertia @ R.T, atol=1e-9 * scale)
    np.testing.assert_allclose(moved.com, R @ body.com + shift, atol=1e-9 * (1 + np.abs(body.com).max()))
    assert moved.mass == pytest.approx(body.mass, rel=1e-14)


@given(bodies(planar=True))
def test_perpendicular_axis_theorem_for_planar_bodies(body):
    # for a lamina in the xy plane, I_zz = I_xx + I_yy (Goldstein sec. 5.3)
    I = body.inertia
    assert I[2, 2] == pytest.approx(I[0, 0] + I[1, 1], rel=1e-9, abs=1e-12)


@ANY_SIZE
@given(bodies())
def test_every_constructed_body_satisfies_the_triangle_inequality(body):
    I1, I2, I3 = body.principal_moments
    assert I1 >= -1e-12 * I3
    assert I1 + I2 >= I3 * (1 - 1e-9)


def test_body_needs_positive_total_mass():
    with pytest.raises(ValueError, match="total mass .* not positive"):
        tumble.Body([tumble.Sphere(density=1.0, radius=1.0), tumble.Sphere(density=1.0, radius=1.0, subtract=True)])
    with pytest.raises(ValueError, match="at least one part"):
        tumble.Body([])


def test_hole_that_makes_the_body_unphysical_is_refused():
    # a small central hole is fine
    tumble.Body([tumble.Sphere(density=1.0, radius=1.0), tumble.Cylinder(density=1.0, radius=0.1, length=0.5, subtract=True)])
    # removing a wide disc from a small ball removes more axial inertia than there was: the disc
    # sticks out of the ball (96 % of it), which tumble.mass.holes refuses before the sums
    with pytest.raises(ValueError, match=r"^parts\[1\] \(a cylinder, subtract = true\) removes material where there is none: 96 %"):
        tumble.Body([tumble.Sphere(mass=1.0, radius=0.1), tumble.Cylinder(mass=0.5, radius=0.5, length=0.01, subtract=True)])


def test_a_body_is_immutable():
    body = tumble.t_handle()
    with pytest.raises(AttributeError):
        body.name = "x"
    with pytest.raises(AttributeError):
        body.properties = None


def test_symmetric_body_has_no_intermediate_axis():
    top = tumble.Body([tumble.Cylinder(mass=1.0, radius=0.3, length=2.0)])
    assert top.properties.degeneracy == "symmetric"
    assert top.properties.intermediate_axis is None
    ball = tumble.Body([tumble.Sphere(mass=1.0, radius=0.3)])
    assert ball.properties.degeneracy == "spherical"


def test_inertia_about_another_point():
    body = tumble.t_handle()
    # about the shaft's bottom end (0, 0, -0.5): x-moment = 0.3125 + 3 * 0.75^2
    assert body.inertia_about([0, 0, -0.5])[0, 0] == pytest.approx(0.3125 + 3 * 0.75**2)


def test_rotation_of_a_rotated_box_composes():
    r1, r2 = Rotation.from_rotvec([0.1, 0.2, 0.3]), Rotation.from_rotvec([-1.0, 0.5, 0.0])
    box = tumble.Box(mass=1.0, size=(1, 2, 3), rotation=r1)
    moved = box.moved(r2)
    np.testing.assert_allclose(moved.orientation.as_matrix(), (r2 * r1).as_matrix(), atol=1e-15)


def test_moving_takes_any_rotation_form_and_refuses_reflections():
    body = tumble.t_handle()
    a = body.moved(Rotation.from_rotvec([0, 0, np.pi / 2]), (1, 0, 0))
    b = body.moved(Rotation.from_rotvec([0, 0, np.pi / 2]).as_matrix(), (1, 0, 0))
    np.testing.assert_allclose(a.inertia, b.inertia, atol=1e-15)
    with pytest.raises(ValueError, match="rotoreflection"):
        body.moved(np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(ValueError, match="translation = "):
        body.moved(Rotation.identity(), (0.0, 1.0))


@pytest.mark.parametrize("point, message", [
    ([np.nan, 0.0, 0.0], r"^point = \[nan, 0.0, 0.0\] must be finite numbers \(m\)"),
    ([0.0, np.inf, 0.0], r"^point = \[0.0, inf, 0.0\] must be finite numbers \(m\)"),
    ([0.0, 0.0], r"^point = \[0.0, 0.0\] must be real numbers of shape \(\.\.\., 3\) \(m\), not shape \(2,\)"),
    (1.0, r"^point = 1.0 must be real numbers of shape \(\.\.\., 3\) \(m\), not shape \(\)"),
    ("xyz", r"^point = 'xyz' must be real numbers"),
    ({0: 0.0, 1: 0.0, 2: 0.0}, r"^point = \{0: 0.0, 1: 0.0, 2: 0.0\} must be real numbers"),
    ([[0.0, 0.0, 0.0], [0.0, np.nan, 1.0]], r"^point\[1\] = \[0.0, nan, 1.0\] must be finite numbers \(m\)"),
])
def test_inertia_about_refuses_a_bad_point(point, message):
    body = tumble.t_handle()
    for inertia_about in (body.inertia_about, body.properties.inertia_about):
        with pytest.raises(ValueError, match=message):
            inertia_about(point)


def test_inertia_about_a_batch_of_points():
    body = tumble.t_handle()
    points = np.array([[0.0, 0.0, -0.5], [1.0, 2.0, 3.0], [0.0, 0.0, 0.25]])
    stack = body.inertia_about(points)
    assert stack.shape == (3, 3, 3)
    for point, tensor in zip(points, stack):
        np.testing.assert_array_equal(tensor, body.inertia_about(tuple(point)))
    np.testing.assert_allclose(stack[2], body.inertia, atol=1e-15)  # about the COM itself


def test_mass_properties_from_moments_is_the_body_of_those_moments():
    """The seed T-handle's moments (kg m^2) give the T-handle's tensor in its principal frame:
    its principal moments, inertia about any point and degeneracy, with the design axes as the
    principal ones (so from_inertia of the same diagonal tensor agrees)."""
    handle = tumble.t_handle().properties
    props = tumble.MassProperties.from_moments(handle.principal_moments, mass=handle.mass, com=[0.1, -0.2, 0.3])
    assert props.mass == 3.0 and props.com.tolist() == [0.1, -0.2, 0.3]
    np.testing.assert_array_equal(props.principal_moments, [0.125, 0.3125, 0.4375])
    np.testing.assert_array_equal(props.principal_axes, np.eye(3))
    np.testing.assert_array_equal(props.inertia, np.diag([0.125, 0.3125, 0.4375]))
    # parallel axis about the origin: I + m (|c|^2 E - c c^T), c = the COM
    c = props.com
    np.testing.assert_allclose(props.inertia_about([0, 0, 0]), props.inertia + 3.0 * (c @ c * np.eye(3) - np.outer(c, c)),
                               rtol=1e-15)
    R = handle.principal_axes  # the handle's own tensor, turned into its principal frame
    np.testing.assert_allclose(props.inertia, R.T @ handle.inertia @ R, atol=1e-15)
    again = tumble.MassProperties.from_inertia(3.0, c, np.diag([0.125, 0.3125, 0.4375]))
    np.testing.assert_array_equal(again.principal_moments, props.principal_moments)
    assert tumble.MassProperties.from_moments([1.0, 1.0, 2.0]).degeneracy == "symmetric"
    assert tumble.MassProperties.from_moments([2.0, 3.0, 4.0]).mass == 1.0


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"moments": [0.3, 0.2, 0.1]}, r"moments = \[0.3, 0.2, 0.1\] must be ascending, I1 <= I2 <= I3"),
    ({"moments": [0.1, 0.2, 0.4]}, r"moments = \[0.1, 0.2, 0.4\] breaks the triangle inequality I1 \+ I2 >= I3"),
    ({"moments": [0.0, 0.2, 0.2]}, r"moments = \[0.0, 0.2, 0.2\] must be positive"),
    ({"moments": [[1, 2, 3], [1, 2, 3]]}, r"moments = \[\[1, 2, 3\], \[1, 2, 3\]\] must be three numbers"),
    ({"moments": [1, 2, 3], "mass": -1.0}, r"mass = -1.0 must be a positive finite number \(kg\)"),
    ({"moments": [1, 2, 3], "com": [0, 0]}, r"com = \[0, 0\] must be a list of 3 numbers \(m\)"),
])
def test_mass_properties_from_moments_refuses_a_body_that_cannot_be(kwargs, message):
    with pytest.raises(ValueError, match=message):
        tumble.MassProperties.from_moments(**kwargs)
