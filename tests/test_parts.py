"""Every part's closed-form tensor against independent routes.

Route 1: trimesh's exact integration over a fine mesh of the same solid. An inscribed polygon
with n sides under-estimates r^2-weighted integrals by a relative O((2 pi / n)^2 / 6); for
n = 256 that is 1.0e-4, so the mass-normalised tensors are compared at rtol 5e-4. An icosphere of
5 subdivisions has a volume deficit of 5.4e-4, so spheres and ellipsoids are compared at 2e-3.
Route 2: direct numerical quadrature of the seed study's definition (sec. 2.1, docs/seed-study.md), I_ij = integral rho (r^2 d_ij - r_i r_j) dV.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import trimesh
from scipy import integrate
from scipy.spatial.transform import Rotation

import tumble

POLYGON_RTOL = 5e-4
ICOSPHERE_RTOL = 2e-3
SECTIONS = 256


def mesh_unit_inertia(mesh: trimesh.Trimesh):
    """Mass-normalised tensor about the COM and the COM, from trimesh."""
    assert mesh.is_watertight, "test mesh must be watertight or its mass properties are garbage"
    props = mesh.mass_properties
    return props.inertia / props.volume, props.center_mass


def part_unit_inertia(part):
    return part.inertia / part.mass


def assert_tensor_close(actual, expected, rtol):
    scale = np.trace(expected)
    np.testing.assert_allclose(actual, expected, atol=rtol * scale, rtol=0)


# -- route 1: closed form vs mesh ----------------------------------------------------------

def test_cylinder_against_mesh():
    part = tumble.Cylinder(mass=1.0, radius=0.3, length=1.7)
    mesh = trimesh.creation.cylinder(radius=0.3, height=1.7, sections=SECTIONS)
    assert_tensor_close(part_unit_inertia(part), mesh_unit_inertia(mesh)[0], POLYGON_RTOL)


def test_tube_against_mesh():
    part = tumble.Tube(mass=1.0, inner_radius=0.2, outer_radius=0.5, length=0.8)
    mesh = trimesh.creation.annulus(r_min=0.2, r_max=0.5, height=0.8, sections=SECTIONS)
    assert_tensor_close(part_unit_inertia(part), mesh_unit_inertia(mesh)[0], POLYGON_RTOL)


def test_cone_against_mesh_including_its_centre_of_mass():
    part = tumble.Cone(mass=1.0, radius=0.4, height=1.2, center=(0, 0, 0.3))
    mesh = trimesh.creation.cone(radius=0.4, height=1.2, sections=SECTIONS)  # base at z = 0
    I, com = mesh_unit_inertia(mesh)
    assert_tensor_close(part_unit_inertia(part), I, POLYGON_RTOL)
    np.testing.assert_allclose(com, part.center, atol=1e-12)  # COM a quarter up from the base
    np.testing.assert_allclose(part.base_center, [0, 0, 0], atol=1e-15)


def test_box_against_mesh_rotated():
    rot = Rotation.from_rotvec([0.3, -1.1, 0.4])
    part = tumble.Box(mass=1.0, size=(0.3, 0.7, 1.9), rotation=rot)
    mesh = trimesh.creation.box(extents=(0.3, 0.7, 1.9))
    mesh.apply_transform(np.block([[rot.as_matrix(), np.zeros((3, 1))], [np.zeros((1, 3)), 1.0]]))
    # a box mesh is exact: only round-off separates the two
    assert_tensor_close(part_unit_inertia(part), mesh_unit_inertia(mesh)[0], 1e-12)


def test_sphere_against_mesh():
    part = tumble.Sphere(mass=1.0, radius=0.6)
    mesh = trimesh.creation.icosphere(subdivisions=5, radius=0.6)
    assert_tensor_close(part_unit_inertia(part), mesh_unit_inertia(mesh)[0], ICOSPHERE_RTOL)


def test_ellipsoid_against_mesh():
    part = tumble.Ellipsoid(mass=1.0, semi_axes=(0.2, 0.5, 1.1))
    mesh = trimesh.creation.icosphere(subdivisions=5, radius=1.0)
    mesh.apply_scale((0.2, 0.5, 1.1))
    assert_tensor_close(part_unit_inertia(part), mesh_unit_inertia(mesh)[0], ICOSPHERE_RTOL)


def test_rod_is_the_thin_limit_of_a_cylinder_mesh():
    # a cylinder of radius r differs from the thin rod by m r^2 / 4 across, m r^2 / 2 along
    r, L = 1e-3, 1.0
    mesh = trimesh.creation.cylinder(radius=r, height=L, sections=64)
    I_mesh = mesh_unit_inertia(mesh)[0]
    rod = tumble.Rod(mass=1.0, length=L)
    np.testing.assert_allclose(np.diag(part_unit_inertia(rod)), np.diag(I_mesh), atol=r**2)


def test_thin_shell_is_the_limit_of_a_hollow_sphere_mesh():
    # hollow sphere (outer R, inner R - t, as one mesh with the inner surface inverted):
    # its unit moment 2/5 (R^5 - r^5)/(R^3 - r^3) tends to 2/3 R^2 as t -> 0
    R, t = 1.0, 1e-3
    outer = trimesh.creation.icosphere(subdivisions=5, radius=R)
    inner = trimesh.creation.icosphere(subdivisions=5, radius=R - t)
    inner.invert()
    hollow = trimesh.util.concatenate([outer, inner])
    props = hollow.mass_properties
    shell = tumble.Shell(mass=1.0, radius=R)
    np.testing.assert_allclose(
        np.diag(part_unit_inertia(shell)), np.diag(props.inertia / props.volume), rtol=ICOSPHERE_RTOL + 2 * t
    )


def test_point_mass_has_no_inertia_of_its_own():
    p = tumble.PointMass(mass=2.0, center=(1, 2, 3))
    np.testing.assert_array_equal(p.inertia, np.zeros((3, 3)))


# -- route 2: quadrature of the seed's sec. 2.1 definition ---------------------------------------

def test_cone_by_quadrature_of_the_definition():
    """Integrate rho (r^2 delta_ij - r_i r_j) over a cone in cylindrical coordinates."""
    R, H, m = 0.5, 1.3, 2.0
    rho = m / (np.pi * R**2 * H / 3)
    zc = H / 4  # COM above the base, from the mesh test; integration measures from the COM

    def component(i, j):
        def f(phi, s, z):  # s: radial coordinate, z: height above base
            x = np.array([s * np.cos(phi), s * np.sin(phi), z - zc])
            return rho * (x @ x * (i == j) - x[i] * x[j]) * s

        val, _ = integrate.tplquad(
            f, 0, H, lambda z: 0, lambda z: R * (1 - z / H), lambda z, s: 0, lambda z, s: 2 * np.pi,
            epsabs=1e-12, epsrel=1e-10,
        )
        return val

    I_quad = np.array([[component(i, j) for j in range(3)] for i in range(3)])
    cone = tumble.Cone(mass=m, radius=R, height=H)
    np.testing.assert_allclose(cone.inertia, I_quad, atol=1e-9)


# -- mass from density, orientation, hole ------------------------------------------------

@pytest.mark.parametrize(
    ("part", "volume"),
    [
        (tumble.Cylinder(density=2.0, radius=0.5, length=2.0), np.pi * 0.25 * 2.0),
        (tumble.Tube(density=2.0, inner_radius=0.1, outer_radius=0.5, length=2.0), np.pi * 0.24 * 2.0),
        (tumble.Cone(density=2.0, radius=0.5, height=3.0), np.pi * 0.25),
        (tumble.Box(density=2.0, size=(1.0, 2.0, 3.0)), 6.0),
        (tumble.Ellipsoid(density=2.0, semi_axes=(1.0, 2.0, 3.0)), 8.0 * np.pi),
        (tumble.Sphere(density=2.0, radius=3.0), 36.0 * np.pi),
    ],
)
def test_density_times_volume(part, volume):
    assert part.volume == pytest.approx(volume, rel=1e-14)
    assert part.mass == pytest.approx(2.0 * volume, rel=1e-14)


def test_axis_orientation_rotates_the_tensor():
    # a cylinder along (1, 1, 0) equals the z-cylinder's tensor rotated into that direction
    z = tumble.Cylinder(mass=1.0, radius=0.2, length=1.0)
    d = tumble.Cylinder(mass=1.0, radius=0.2, length=1.0, axis=(1, 1, 0))
    rot, _ = Rotation.align_vectors([[1, 1, 0]], [[0, 0, 1]])
    np.testing.assert_allclose(d.inertia, rot.as_matrix() @ z.inertia @ rot.as_matrix().T, atol=1e-15)


def test_subtracted_sphere_gives_the_thick_shell():
    # sphere R minus sphere r, same density: I = 2/5 M (R^5 - r^5) / (R^3 - r^3)
    R, r, rho = 1.0, 0.7, 1000.0
    body = tumble.Body([tumble.Sphere(density=rho, radius=R), tumble.Sphere(density=rho, radius=r, subtract=True)])
    M = rho * 4 / 3 * np.pi * (R**3 - r**3)
    assert body.mass == pytest.approx(M, rel=1e-14)
    np.testing.assert_allclose(np.diag(body.inertia), 0.4 * M * (R**5 - r**5) / (R**3 - r**3), rtol=1e-13)


@pytest.mark.parametrize("hole", [dict(density=7850.0), dict(mass=0.5)], ids=["steel", "by mass"])
def test_a_hole_denser_than_the_solid_it_is_cut_from_is_refused(hole):
    """A box of water's density less a sphere of steel's (or of 0.5 kg in 34 cm^3, 14,900 kg/m^3) weighed
    0.74 or 0.5 kg: more was removed than was there. A hole of the box's own density is what subtract means."""
    box = tumble.Box(density=1000.0, size=(0.1, 0.1, 0.1))
    with pytest.raises(ValueError, match=r"^parts\[1\] \(a sphere, subtract = true\) is .* kg/m\^3, denser than the "
                                         r"1000 kg/m\^3 it is cut from: .*give it that material's density$"):
        tumble.Body([box, tumble.Sphere(radius=0.02, subtract=True, **hole)])
    cut = tumble.Body([box, tumble.Sphere(radius=0.02, density=1000.0, subtract=True)])
    assert cut.mass == pytest.approx(1.0 - 1000.0 * 4.0 / 3.0 * math.pi * 0.02**3, rel=1e-12)
