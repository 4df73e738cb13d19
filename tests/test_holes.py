"""A hole removes material only where a solid part has some (tumble.mass.holes; issue 40 walkthrough).

A subtracted part is negative mass of its own density in the sums; outside its solid that is mass
removed from nothing. A walkthrough's hole beside its plate gave wrong mass properties with exit 0.
The share of a hole's mass that lies outside is checked against closed forms: half of any
centrally symmetric hole centred on a face; (3/4)^3 of a cone whose centre of mass sits on the face
(the part above it is a cone three quarters as tall); the lens of two spheres for a mesh sphere.
"""

from __future__ import annotations

import math
import warnings
import re

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tumble
from tumble.cli import main
from tumble.mass.holes import HOLE_OUTSIDE_TOLERANCE
from tumble.mass.mesh import winding_number

trimesh = pytest.importorskip("trimesh")

RHO = 1000.0
BLOCK = tumble.Box(density=RHO, size=(1.0, 1.0, 1.0))  # the faces at x, y, z = +-0.5 m
TURN = tuple(Rotation.from_euler("xyz", [30, 20, 10], degrees=True).as_quat())


def _holes(center):
    """One hole of each solid kind about ``center`` (m), each centrally symmetric but the cone."""
    return {
        "sphere": tumble.Sphere(density=RHO, radius=0.1, center=center, subtract=True),
        "cylinder": tumble.Cylinder(density=RHO, radius=0.1, length=0.3, axis=(1, 1, 0), center=center, subtract=True),
        "tube": tumble.Tube(density=RHO, inner_radius=0.05, outer_radius=0.1, length=0.2, axis=(1, 0, 0), center=center,
                            subtract=True),
        "box": tumble.Box(density=RHO, size=(0.1, 0.2, 0.15), rotation=TURN, center=center, subtract=True),
        "ellipsoid": tumble.Ellipsoid(density=RHO, semi_axes=(0.1, 0.2, 0.05), rotation=TURN, center=center, subtract=True),
        "mesh": tumble.Mesh(mesh=trimesh.creation.box(extents=(0.1, 0.2, 0.15)), density=RHO, rotation=TURN,
                            origin=center, subtract=True),
    }


def _share(message: str) -> float:
    return float(re.search(r"none: (\d+) % of its mass", message).group(1)) / 100


@pytest.mark.parametrize("kind", sorted(_holes((0, 0, 0))))
def test_a_hole_inside_its_solid_is_taken_with_the_closed_form_mass(kind):
    hole = _holes((0.1, -0.05, 0.2))[kind]
    body = tumble.Body([BLOCK, hole])
    assert body.mass == pytest.approx(RHO * (1.0 - hole.volume), rel=1e-12)


@pytest.mark.parametrize("kind", sorted(_holes((0, 0, 0))))
def test_a_hole_across_a_face_is_refused_with_the_share_outside(kind):
    """Centred on the face x = 0.5: half of it lies outside (central symmetry)."""
    with pytest.raises(ValueError, match=rf"^parts\[1\] \(a {kind}, subtract = true\) removes material where there is none") as e:
        tumble.Body([BLOCK, _holes((0.5, 0.0, 0.0))[kind]])
    assert _share(str(e.value)) == pytest.approx(0.5, abs=0.015)


def test_a_cone_across_a_face_is_refused_with_the_share_above_its_centre_of_mass():
    cone = tumble.Cone(density=RHO, radius=0.1, height=0.3, axis=(1, 0, 0), center=(0.5, 0.0, 0.0), subtract=True)
    with pytest.raises(ValueError, match=r"a cone, subtract = true\) removes material where there is none") as e:
        tumble.Body([BLOCK, cone])
    assert _share(str(e.value)) == pytest.approx((3 / 4) ** 3, abs=0.015)
    inside = tumble.Cone(density=RHO, radius=0.1, height=0.3, axis=(1, 0, 0), center=(0.5 - 0.75 * 0.3, 0.0, 0.0),
                         subtract=True)  # its apex on the face
    assert tumble.Body([BLOCK, inside]).mass == pytest.approx(RHO * (1.0 - inside.volume), rel=1e-12)


def test_a_hole_through_a_plate_is_as_long_as_the_plate_is_thick():
    plate = tumble.Box(density=2700.0, size=(0.2, 0.2, 0.01))
    flush = tumble.Cylinder(density=2700.0, radius=0.02, length=0.01, subtract=True)  # its faces on the plate's
    assert tumble.Body([plate, flush]).mass == pytest.approx(2700.0 * (0.2 * 0.2 * 0.01 - math.pi * 0.02**2 * 0.01))
    long = tumble.Cylinder(density=2700.0, radius=0.02, length=0.03, subtract=True)  # drawn 3x the thickness
    with pytest.raises(ValueError, match=r"a hole through a plate is as long as the plate is thick") as e:
        tumble.Body([plate, long])
    assert _share(str(e.value)) == pytest.approx(2 / 3, abs=0.015)


def test_a_hole_beside_its_solid_or_over_another_hole_is_refused():
    beside = tumble.Sphere(density=RHO, radius=0.1, center=(2.0, 0.0, 0.0), subtract=True)
    with pytest.raises(ValueError, match=r"none: 100 % of its mass lies outside the solid parts"):
        tumble.Body([BLOCK, beside])
    twice = tumble.Sphere(density=RHO, radius=0.1, subtract=True)
    with pytest.raises(ValueError, match=r"^parts\[1\] .* 100 % of its mass .* where another hole already took it"):
        tumble.Body([BLOCK, twice, twice])
    # two holes side by side, each in the block: taken
    side = tumble.Body([BLOCK, twice, twice.moved(np.eye(3), (0.25, 0.0, 0.0))])
    assert side.mass == pytest.approx(RHO * (1.0 - 2 * twice.volume))


def test_a_small_share_outside_is_within_the_tolerance_and_a_larger_one_is_not():
    """A sphere of radius r whose centre is d inside a face: a cap of height r - d sticks out, of
    volume pi (r - d)^2 (2 r + d) / 3."""
    r = 0.1

    def outside(d):
        return math.pi * (r - d) ** 2 * (2 * r + d) / 3 / (4 / 3 * math.pi * r**3)

    small, large = 0.95 * r, 0.5 * r
    assert outside(small) < HOLE_OUTSIDE_TOLERANCE / 2 < 4 * HOLE_OUTSIDE_TOLERANCE < outside(large)
    tumble.Body([BLOCK, tumble.Sphere(density=RHO, radius=r, center=(0.5 - small, 0, 0), subtract=True)])
    with pytest.raises(ValueError, match="removes material where there is none") as e:
        tumble.Body([BLOCK, tumble.Sphere(density=RHO, radius=r, center=(0.5 - large, 0, 0), subtract=True)])
    assert _share(str(e.value)) == pytest.approx(outside(large), abs=0.01)


def test_a_hole_in_a_mesh_solid_against_the_lens_of_two_spheres():
    R, r = 0.1, 0.05
    ball = tumble.Mesh(mesh=trimesh.creation.icosphere(subdivisions=4, radius=R), density=RHO)
    tumble.Body([ball, tumble.Sphere(density=RHO, radius=r, subtract=True)])
    d = R  # the hole's centre on the surface: the lens of the two spheres is what it can remove
    lens = math.pi * (R + r - d) ** 2 * (d * d + 2 * d * r - 3 * r * r + 2 * d * R + 6 * r * R - 3 * R * R) / (12 * d)
    with pytest.raises(ValueError, match="a sphere, subtract = true\\) removes material where there is none") as e:
        tumble.Body([ball, tumble.Sphere(density=RHO, radius=r, center=(d, 0.0, 0.0), subtract=True)])
    assert _share(str(e.value)) == pytest.approx(1 - lens / (4 / 3 * math.pi * r**3), abs=0.02)


def test_the_winding_number_is_one_inside_a_closed_surface_and_zero_outside():
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=1.0)
    rng = np.random.default_rng(7)
    x = rng.uniform(-1.5, 1.5, (400, 3))
    radius = np.linalg.norm(x, axis=1)
    clear = (radius < 0.95) | (radius > 1.05)  # off the facets' sag (< 1.3 % at 3 subdivisions)
    w = winding_number(sphere.triangles, x[clear])
    np.testing.assert_allclose(w, (radius[clear] < 1.0).astype(float), atol=1e-9)
    inverted = sphere.triangles[:, ::-1]  # inward normals: minus one inside
    np.testing.assert_allclose(winding_number(inverted, [[0.0, 0.0, 0.0]]), [-1.0], atol=1e-12)


def test_the_command_refuses_a_hole_beside_its_plate_in_one_line(tmp_path, capsys):
    path = tmp_path / "plate.toml"
    path.write_text('[[body.parts]]\nkind = "box"\ndensity = 2700.0\nsize = [0.2, 0.2, 0.01]\n'
                    '[[body.parts]]\nkind = "cylinder"\ndensity = 2700.0\nradius = 0.02\nlength = 0.01\n'
                    'center = [0.3, 0.0, 0.0]\nsubtract = true\n')
    assert main(["inertia", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "parts[1] (a cylinder, subtract = true) removes material where there is none: 100 %" in err


def test_a_hole_lighter_than_its_material_is_warned_of_and_a_bore_through_an_insert_takes_both_densities():
    """A walkthrough of docs/formats/body.md (2026-12-03): a hole of 1000 kg/m^3 cut from steel left 6850 kg/m^3 in
    it without a word, while a denser one was refused; and a bore through a steel insert pressed into plastic (their
    densities add where they overlap, 9050 kg/m^3) could not be one hole: 9050 was refused as denser than every
    part, 7850 left the plastic in the bore. The hole is judged by the material at its points: a lighter one is
    warned of (a fill of another material, allowed), the sum is the bore, and a denser one is refused."""
    from tumble.mass.holes import HoleFillWarning

    steel = tumble.Box(density=7850.0, size=(1.0, 1.0, 1.0))
    with pytest.warns(HoleFillWarning, match=r"^parts\[1\] \(a sphere, subtract = true\) leaves 6850 kg/m\^3 of the 7850 "
                                             r"kg/m\^3 it is cut from \(1000 removed\)"):
        light = tumble.Body([steel, tumble.Sphere(density=1000.0, radius=0.2, subtract=True)])
    assert light.mass == pytest.approx(7850.0 - 1000.0 * 4 / 3 * math.pi * 0.2**3, rel=1e-12)
    plastic, insert = tumble.Box(density=1200.0, size=(0.1, 0.1, 0.1)), tumble.Cylinder(density=7850.0, radius=0.01, length=0.1)
    bore = dict(radius=0.005, length=0.1, subtract=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        drilled = tumble.Body([plastic, insert, tumble.Cylinder(density=9050.0, **bore)])
    v_bore = math.pi * 0.005**2 * 0.1
    expected = 1200.0 * 1e-3 + 7850.0 * math.pi * 0.01**2 * 0.1 - 9050.0 * v_bore  # by hand: nothing left in the bore
    assert drilled.mass == pytest.approx(expected, rel=1e-12)
    with pytest.warns(HoleFillWarning, match=r"leaves 1200 kg/m\^3 of the 9050 kg/m\^3 it is cut from \(7850 removed\)"):
        tumble.Body([plastic, insert, tumble.Cylinder(density=7850.0, **bore)])
    with pytest.raises(ValueError, match=r"^parts\[2\] \(a cylinder, subtract = true\) is 10000 kg/m\^3, denser than the "
                                         r"9050 kg/m\^3 it is cut from"):
        tumble.Body([plastic, insert, tumble.Cylinder(density=10000.0, **bore)])


def test_a_hole_cut_from_a_rotor_is_refused():
    """A bore cut into a spinning Rotor took its mass from the locked body while the wheel's momentum stayed
    the whole disc's J s (3.70 kg m^2/s for the bored wheel's 3.47: a walkthrough, 2026-12-03). A hole in
    a rotor is refused; the same hole in the body beside it stays a hole."""
    rotor = tumble.Rotor(density=7850.0, radius=0.1, length=0.03, axis=(0, 0, 1), spin_rate=100.0)
    housing = tumble.Box(mass=10.0, size=(0.5, 0.5, 0.5), center=(0.0, 0.0, 0.5))
    with pytest.raises(ValueError, match=r"^parts\[2\] \(a cylinder, subtract = true\) is cut from parts\[1\], a rotor: "
                                         r"the rotor's spin momentum is its whole wheel's"):
        tumble.Body([housing, rotor, tumble.Cylinder(density=7850.0, radius=0.05, length=0.03, subtract=True)])
    hole = tumble.Cylinder(density=80.0, radius=0.05, length=0.1, center=(0.0, 0.0, 0.5), subtract=True)  # the housing's
    body = tumble.Body([housing, rotor, hole])
    assert body.mass == pytest.approx(10.0 + rotor.mass - 80.0 * np.pi * 0.05**2 * 0.1, rel=1e-12)
