"""Triangle-mesh parts: loading, placement, refusal of meshes that enclose no volume."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh
from scipy.spatial.transform import Rotation

import tumble

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def test_torus_file_against_closed_form():
    """Torus, major radius R, minor r: I_axial = m (R^2 + 3 r^2 / 4), I_perp = m (R^2 / 2 + 5 r^2 / 8)
    (Meriam & Kraige Table D/4). The shipped mesh has 48 x 16 sections, so the polygonal
    under-estimate is ~ (2 pi / 16)^2 / 6 = 2.6e-2 of the minor-circle part; allow 1e-2 overall."""
    R, r = 0.04, 0.01
    part = tumble.Mesh(mesh=EXAMPLES / "bodies" / "meshes" / "torus.stl", mass=1.0)
    np.testing.assert_allclose(np.diag(part.inertia), [R**2 / 2 + 5 * r**2 / 8] * 2 + [R**2 + 3 * r**2 / 4], rtol=1e-2)
    np.testing.assert_allclose(part.center, 0.0, atol=1e-12)


def test_mesh_part_equals_the_primitive_it_meshes(tmp_path):
    rot = Rotation.from_rotvec([0.4, 0.1, -0.9])
    box = trimesh.creation.box(extents=(0.1, 0.2, 0.4))
    box.apply_translation([0.05, 0.0, 0.0])  # mesh origin is not its centre
    path = tmp_path / "box.stl"
    box.export(path)
    part = tumble.Mesh(mesh=path, density=1000.0, origin=(1.0, 2.0, 3.0), rotation=rot)
    ref = tumble.Box(density=1000.0, size=(0.1, 0.2, 0.4), rotation=rot, center=rot.apply([0.05, 0, 0]) + [1, 2, 3])
    f32 = 1e-6  # binary STL stores float32 coordinates (eps 6e-8), a few eps of error
    assert part.mass == pytest.approx(ref.mass, rel=f32)
    np.testing.assert_allclose(part.center, ref.center, atol=f32)
    np.testing.assert_allclose(part.inertia, ref.inertia, atol=f32 * np.trace(ref.inertia))
    moved = part.moved(Rotation.from_rotvec([0, 0, 1.0]), (0, 0, 1))
    assert moved.mass == pytest.approx(part.mass, rel=1e-12)


def test_scale_converts_millimetres(tmp_path):
    mesh = trimesh.creation.box(extents=(10.0, 20.0, 30.0))  # mm
    path = tmp_path / "box_mm.stl"
    mesh.export(path)
    part = tumble.Mesh(mesh=path, scale=1e-3, density=1000.0)
    assert part.volume == pytest.approx(6e-6, rel=1e-6)  # float32 in the file


def test_open_mesh_is_refused(tmp_path):
    mesh = trimesh.creation.box(extents=(1, 1, 1))
    mesh.update_faces(np.arange(len(mesh.faces)) != 0)  # knock out one triangle
    path = tmp_path / "open.stl"
    mesh.export(path)
    with pytest.raises(ValueError, match="not watertight"):
        tumble.Mesh(mesh=path, mass=1.0)


def test_inside_out_mesh_is_refused():
    mesh = trimesh.creation.box(extents=(1, 1, 1))
    mesh.invert()
    with pytest.raises(ValueError, match="negative volume means its faces point inward"):
        tumble.Mesh(mesh=mesh, mass=1.0)


@pytest.mark.parametrize("content", [b"", b"\x00\x01\x02 junk", b"solid x\nendsolid x\n"])
def test_malformed_mesh_files(tmp_path, content):
    path = tmp_path / "bad.stl"
    path.write_bytes(content)
    with pytest.raises(ValueError, match="bad.stl"):
        tumble.Mesh(mesh=path, mass=1.0)


def test_missing_mesh_file():
    with pytest.raises(ValueError, match="no such file"):
        tumble.Mesh(mesh="does/not/exist.stl", mass=1.0)


def test_missing_trimesh_is_an_import_error_with_the_install_hint(monkeypatch):
    """Issue 27 item 10(b): an extra to install is ImportError (name "trimesh"), not ValueError."""
    monkeypatch.setitem(sys.modules, "trimesh", None)  # `import trimesh` now raises ImportError
    with pytest.raises(ImportError, match=r"pip install 'tumble\[mesh\]'") as info:
        tumble.Mesh(mesh=EXAMPLES / "bodies" / "meshes" / "torus.stl", mass=1.0)
    assert not isinstance(info.value, ValueError) and info.value.name == "trimesh"


def test_a_mesh_of_several_shells_is_one_solid_or_refused():
    """A walkthrough (2026-12-03): a box with a cube beside it wound inward passed trimesh's per-edge
    winding check, and the cube's volume was taken away (0.092 kg for 0.108, the centre of mass on the
    wrong side); a sphere inside a sphere, both outward, counted the inner twice. Each shell is judged by
    the others' winding number at it: an inward shell must be a cavity, an outward one not inside solid."""
    trimesh = pytest.importorskip("trimesh")
    from tumble import Mesh

    def cube(size, at, inward=False):
        m = trimesh.creation.box(extents=(size,) * 3)
        m.apply_translation(at)
        if inward:
            m.invert()
        return m

    box = trimesh.creation.box(extents=(0.1, 0.05, 0.02))   # 1e-4 m^3
    with pytest.raises(ValueError, match=r"^mesh mesh: shell 2 of 2 is wound inside out \(its volume -8e-06 m\^3 is "
                                         r"negative\) and is no cavity inside another shell"):
        Mesh(mesh=trimesh.util.concatenate([box, cube(0.02, (0.07, 0.0, 0.0), inward=True)]), density=1000.0)
    with pytest.raises(ValueError, match=r"^mesh mesh: shell 2 of 2 lies inside another shell \(nested or overlapping\)"):
        Mesh(mesh=trimesh.util.concatenate([box, cube(0.01, (0.02, 0.0, 0.0))]), density=1000.0)
    # a cavity wound inward is right, and a cube loose in it too: the closed forms of their sum (Meriam & Kraige)
    block = trimesh.creation.box(extents=(0.1, 0.1, 0.1))
    hollow = Mesh(mesh=trimesh.util.concatenate([block, cube(0.06, (0.0, 0.0, 0.0), inward=True)]), density=1000.0)
    assert hollow.mass == pytest.approx(1000.0 * (1e-3 - 0.06**3), rel=1e-12)
    loose = Mesh(mesh=trimesh.util.concatenate([block, cube(0.06, (0.0, 0.0, 0.0), inward=True), cube(0.02, (0.01, 0.0, 0.0))]),
                 density=1000.0)
    assert loose.mass == pytest.approx(1000.0 * (1e-3 - 0.06**3 + 0.02**3), rel=1e-12)
    side = 1000.0 * np.array([1e-3, -0.06**3, 0.02**3])   # masses of block, cavity, cube; I = m a^2 / 6 (+ m d^2)
    Izz = side[0] * 0.1**2 / 6 + side[1] * 0.06**2 / 6 + side[2] * (0.02**2 / 6 + 0.01**2)
    com_x = side[2] * 0.01 / side.sum()
    assert loose.center[0] == pytest.approx(com_x, rel=1e-9)
    assert loose.inertia[2, 2] == pytest.approx(Izz - side.sum() * com_x**2, rel=1e-9)


def test_two_solids_on_one_edge_are_called_what_they_are():
    """Two cubes sharing an edge were refused as "not watertight (it has open edges)": they have no open
    edge; the shared edge has four faces (a walkthrough, 2026-12-03)."""
    from tumble import Mesh

    a = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    b = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    b.apply_translation((1.0, 1.0, 0.0))   # touching a along the edge x = y = 0.5
    joined = trimesh.Trimesh(np.vstack([a.vertices, b.vertices]), np.vstack([a.faces, b.faces + 8]), process=True)
    with pytest.raises(ValueError, match=r"^mesh mesh is not a manifold: 1 of its edges have more than two faces"):
        Mesh(mesh=joined, density=1.0)
    open_box = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    open_box.update_faces(np.arange(len(open_box.faces)) != 0)   # one triangle taken out: 3 open edges
    with pytest.raises(ValueError, match=r"^mesh mesh is not watertight \(it has 3 open edges\)"):
        Mesh(mesh=open_box, density=1.0)


@pytest.mark.parametrize(("text", "suffix", "says"), [
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 nan\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n", ".obj",
     "has vertices that are not finite numbers"),   # it was "not watertight (it has 3 open edges)"
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 9\nf 1 4 3\nf 2 3 4\n", ".obj",
     "a face names a vertex the file does not have"),   # it was numpy's "index 8 is out of bounds"
    ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nelement face 1\nproperty list uchar int vertex_indices\n"
     "end_header\n0\n1\n2\n3 0 1 2\n", ".ply", "a vertex lacks the coordinate 'y'"),   # it was "could not be read: 'y'"
])
def test_a_malformed_mesh_file_is_named_for_what_is_wrong(tmp_path, text, suffix, says):
    """A QA walkthrough (2026-12-03): trimesh's own words named its internals, and a NaN vertex, dropped in
    processing, was called an open edge."""
    path = tmp_path / f"bad{suffix}"
    path.write_text(text)
    with pytest.raises(ValueError, match=re.escape(says)):
        tumble.Mesh(mesh=str(path), density=1000.0)
