"""The shaded page's triangle surfaces: closed, outward, the right volume, in the right place."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from tumble.io.bodyfile import load_body
from tumble.mass import Body
from tumble.mass.parts import Box, Cone, Cylinder, Ellipsoid, PointMass, Rod, Shell, Sphere, Tube
from strategies import ANY_SIZE
from tumble.viz.surfaces import MAX_MESH_FACES, body_surfaces, decimate, part_surface, surface_volume

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
N = 32
#: Area of the regular N-gon inscribed in the unit circle over the circle's: (N/2) sin(2 pi/N) / pi.
POLYGON = N / 2 * math.sin(2 * math.pi / N) / math.pi
TURN = Rotation.from_rotvec([0.3, -1.1, 0.7])
AXIS = tuple(TURN.apply([0.0, 0.0, 1.0]))
CENTER = (0.3, -0.2, 1.5)

# (part, volume of its triangulation): solids of revolution are prisms / pyramids over the inscribed
# N-gon, so their volumes are the analytic ones times POLYGON exactly; a box is exact.
EXACT = [
    (Cylinder(mass=1.0, radius=0.2, length=0.7, center=CENTER, axis=AXIS), POLYGON * math.pi * 0.2**2 * 0.7),
    (Tube(mass=1.0, inner_radius=0.1, outer_radius=0.25, length=0.4, center=CENTER, axis=AXIS),
     POLYGON * math.pi * (0.25**2 - 0.1**2) * 0.4),
    (Cone(mass=1.0, radius=0.3, height=0.9, center=CENTER, axis=AXIS), POLYGON * math.pi * 0.3**2 * 0.9 / 3),
    (Box(mass=1.0, size=(0.3, 0.5, 0.7), center=CENTER, rotation=TURN.as_quat()), 0.3 * 0.5 * 0.7),
]
ROUND = [
    Sphere(mass=1.0, radius=0.4, center=CENTER),
    Ellipsoid(mass=1.0, semi_axes=(0.1, 0.3, 0.5), center=CENTER, rotation=TURN.as_quat()),
]


def centroid(v, f):
    """Volume centroid of a closed surface: tetrahedra from the origin, each at (a+b+c)/4."""
    a, b, c = (v[f[:, k]] for k in range(3))
    vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6
    return (vol[:, None] * (a + b + c) / 4).sum(axis=0) / vol.sum()


def assert_closed(v, f):
    """Every edge, with vertices merged by position, is used once in each direction."""
    _, ids = np.unique(np.round(v, 9), axis=0, return_inverse=True)
    f = ids.ravel()[f]
    f = f[(f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])]
    edges = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    forward = {tuple(e) for e in edges.tolist()}
    assert len(forward) == len(edges), "an edge is used twice in the same direction"
    assert forward == {(b, a) for a, b in forward}, "an edge has no opposite: the surface is open"


@pytest.mark.parametrize(("part", "volume"), EXACT, ids=lambda x: getattr(x, "kind", ""))
def test_polyhedral_volume_is_the_inscribed_solids(part, volume):
    v, f = part_surface(part, N)
    assert_closed(v, f)
    assert surface_volume(v, f) == pytest.approx(volume, rel=1e-12)
    np.testing.assert_allclose(centroid(v, f), part.com, atol=1e-12)  # the cone's COM: h/4 above the base


@pytest.mark.parametrize("part", ROUND, ids=lambda p: p.kind)
def test_round_parts_converge_to_their_volume_at_second_order(part):
    errors = []
    for n in (16, 32, 64):
        v, f = part_surface(part, n)
        assert_closed(v, f)
        np.testing.assert_allclose(centroid(v, f), part.com, atol=1e-12)
        errors.append(1 - surface_volume(v, f) / part.volume)  # inscribed: a little less than the solid
    assert 0 < errors[2] < errors[1] < errors[0] < 0.1
    assert errors[0] / errors[1] == pytest.approx(4, rel=0.1) and errors[1] / errors[2] == pytest.approx(4, rel=0.1)


def _local(part, v):
    return (v - part.com) @ part.orientation.as_matrix()


@pytest.mark.parametrize("part", [p for p, _ in EXACT] + ROUND, ids=lambda p: p.kind)
def test_vertices_lie_on_or_inside_the_part(part):
    x, y, z = _local(part, part_surface(part, N)[0]).T
    r, eps = np.hypot(x, y), 1e-12
    if isinstance(part, (Cylinder, Tube)):
        inner = part.inner_radius if isinstance(part, Tube) else 0.0
        outer = part.outer_radius if isinstance(part, Tube) else part.radius
        assert np.all(np.abs(z) <= part.length / 2 + eps)
        assert np.all((r <= outer + eps) & (r >= inner - eps))
    elif isinstance(part, Cone):
        base, apex = -part.height / 4, 3 * part.height / 4
        assert np.all((z >= base - eps) & (z <= apex + eps))
        assert np.all(r <= part.radius * (apex - z) / part.height + eps)
    elif isinstance(part, Box):
        assert np.all(np.abs(np.column_stack([x, y, z])) <= np.array(part.size) / 2 + eps)
    else:
        s = np.array(part.semi_axes) if isinstance(part, Ellipsoid) else np.full(3, part.radius)
        np.testing.assert_allclose(np.sum((np.column_stack([x, y, z]) / s) ** 2, axis=1), 1.0, atol=1e-12)


def test_thin_parts_get_their_drawn_thickness():
    rod = Rod(mass=1.0, length=2.0, center=CENTER, axis=AXIS)
    v, f = part_surface(rod, N, thin=0.05)
    x, y, z = _local(rod, v).T
    assert np.abs(z).max() == pytest.approx(1.0) and np.hypot(x, y).max() == pytest.approx(0.05)
    assert surface_volume(v, f) > 0
    for part in (PointMass(mass=1.0, center=CENTER), Shell(mass=1.0, radius=0.3, center=CENTER)):
        v, f = part_surface(part, N, thin=0.05)
        assert_closed(v, f)
        radius = 0.05 if isinstance(part, PointMass) else 0.3
        np.testing.assert_allclose(np.linalg.norm(v - CENTER, axis=1), radius, rtol=1e-12)


def test_mesh_part_is_drawn_from_its_own_triangles():
    body = load_body(EXAMPLES / "bodies" / "every_part.toml")
    mesh = next(p for p in body.parts if p.kind == "mesh")
    v, f = part_surface(mesh)
    assert len(f) == len(mesh.mesh.faces) <= MAX_MESH_FACES
    assert surface_volume(v, f) == pytest.approx(mesh.volume, rel=1e-9)
    np.testing.assert_allclose(centroid(v, f), mesh.com, atol=1e-9)


def test_decimation_keeps_a_big_mesh_under_the_limit_and_its_shape():
    v, f = part_surface(Sphere(mass=1.0, radius=1.0), 400)  # 160 000 triangles
    assert len(f) > 100_000
    small_v, small_f = decimate(v, f, 5000)
    assert 1000 < len(small_f) <= 5000
    assert surface_volume(small_v, small_f) == pytest.approx(4 / 3 * math.pi, rel=0.05)
    assert np.all(np.linalg.norm(small_v, axis=1) <= 1 + 1e-12)  # averages of points on the sphere
    assert np.array_equal(np.unique(small_f), np.arange(len(small_v)))  # every vertex used, none dangling
    few = f[:5]
    assert decimate(v, few, 5000) == (v, few)  # small enough: unchanged
    point, faces = np.zeros((3, 3)), np.array([[0, 1, 2]] * 10)
    kept_v, kept_f = decimate(point, faces, 5)  # zero extent: nothing to cluster (and no 0/0 warning)
    assert kept_v is point and kept_f is faces


def test_body_surfaces_are_about_the_com_and_mark_removed_material():
    body = load_body(EXAMPLES / "bodies" / "every_part.toml")
    surfaces = body_surfaces(body)
    assert [removed for _, _, removed in surfaces] == [p.subtract for p in body.parts]
    # The parts' surface centroids, weighted by their signed masses, give the body's COM: 0 here.
    com = sum(p.signed_mass * centroid(v, f) for p, (v, f, _) in zip(body.parts, surfaces)) / body.mass
    np.testing.assert_allclose(com, 0.0, atol=1e-9)


def test_a_point_mass_body_is_drawn_with_a_size():
    body = Body([PointMass(mass=1.0, center=(1.0, 0.0, 0.0)), PointMass(mass=1.0, center=(-1.0, 0.0, 0.0)),
                 PointMass(mass=1.0, center=(0.0, 0.5, 0.0))])
    for v, f, _ in body_surfaces(body):
        assert surface_volume(v, f) > 0 and np.ptp(v, axis=0).max() > 0


lengths = st.floats(0.01, 10.0)


@ANY_SIZE
@settings(max_examples=40, deadline=None)
@given(kind=st.sampled_from(["cylinder", "tube", "cone", "box"]), a=lengths, b=lengths, c=lengths,
       n=st.integers(3, 64), rotvec=st.tuples(*[st.floats(-3.0, 3.0)] * 3))
def test_any_prism_or_pyramid_encloses_its_polygonal_volume(kind, a, b, c, n, rotvec):
    """Over shapes, sizes, step counts and orientations: closed, outward, and the volume of the
    solid over the inscribed n-gon ((n/2) sin(2 pi/n) r^2 for the disc)."""
    turn = Rotation.from_rotvec(rotvec)
    axis, polygon = tuple(turn.apply([0.0, 0.0, 1.0])), n / 2 * math.sin(2 * math.pi / n)
    if kind == "cylinder":
        part, volume = Cylinder(mass=1.0, radius=a, length=b, axis=axis), polygon * a**2 * b
    elif kind == "tube":
        inner, outer = sorted((a, a + b))
        part, volume = Tube(mass=1.0, inner_radius=inner, outer_radius=outer, length=c, axis=axis), \
            polygon * (outer**2 - inner**2) * c
    elif kind == "cone":
        part, volume = Cone(mass=1.0, radius=a, height=b, axis=axis), polygon * a**2 * b / 3
    else:
        part, volume = Box(mass=1.0, size=(a, b, c), rotation=turn.as_quat()), a * b * c
    v, f = part_surface(part, n)
    assert_closed(v, f)
    assert surface_volume(v, f) == pytest.approx(volume, rel=1e-9)
    np.testing.assert_allclose(centroid(v, f), part.com, atol=1e-9 * max(a, b, c))
