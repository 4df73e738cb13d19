"""``tumble inertia`` on a mesh file (STL, OBJ, PLY) directly (issue 28 item 4)."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

import tumble
from tumble.cli import main
from tumble.io.bodyfile import body_from_mesh, is_mesh_file

# a box 0.1 x 0.2 x 0.4 (file units) about the origin: its corners and outward-wound triangles
SIZE = (0.1, 0.2, 0.4)
CORNERS = [(x, y, z) for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)]  # index = x + 2 y + 4 z (0/1 bits)
FACES = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4),
         (1, 3, 7), (1, 7, 5), (3, 2, 6), (3, 6, 7), (2, 0, 4), (2, 4, 6)]


def _vertices(size=SIZE):
    return [tuple(s / 2 * c for s, c in zip(size, corner)) for corner in CORNERS]


def _obj(faces=FACES, size=SIZE) -> str:
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in _vertices(size)]
    return "\n".join(lines + [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces]) + "\n"


def _stl(faces=FACES, size=SIZE) -> str:
    v = np.array(_vertices(size))
    lines = ["solid box"]
    for a, b, c in faces:
        n = np.cross(v[b] - v[a], v[c] - v[a])
        n /= np.linalg.norm(n)
        lines += [f"  facet normal {n[0]:.1f} {n[1]:.1f} {n[2]:.1f}", "    outer loop"]
        lines += [f"      vertex {float(v[i][0])!r} {float(v[i][1])!r} {float(v[i][2])!r}" for i in (a, b, c)]
        lines += ["    endloop", "  endfacet"]
    return "\n".join(lines + ["endsolid box"]) + "\n"


def _ply(faces=FACES, size=SIZE) -> str:
    head = ["ply", "format ascii 1.0", "element vertex 8", "property double x", "property double y",
            "property double z", f"element face {len(faces)}", "property list uchar int vertex_indices", "end_header"]
    return "\n".join(head + [f"{x!r} {y!r} {z!r}" for x, y, z in _vertices(size)]
                     + [f"3 {a} {b} {c}" for a, b, c in faces]) + "\n"


WRITERS = {"stl": _stl, "obj": _obj, "ply": _ply}
F32 = 1e-6  # trimesh reads STL coordinates as float32 (eps 6e-8), even from ASCII: a few eps of error


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def _box_moments(mass, a, b, c):
    """A solid cuboid of sides a, b, c about its centre: m (b^2 + c^2) / 12 and cyclic."""
    return np.array([b * b + c * c, a * a + c * c, a * a + b * b]) * mass / 12


@pytest.mark.parametrize("suffix", ["stl", "obj", "ply", "STL"])
def test_mesh_file_against_the_closed_form_of_a_box(tmp_path, capsys, suffix):
    path = tmp_path / f"brick.{suffix}"
    path.write_text(WRITERS[suffix.lower()]())
    code, out, err = run(capsys, "inertia", path, "--density", "1000", "--json")
    assert code == 0 and err == ""
    data = json.loads(out)
    mass = 1000 * math.prod(SIZE)
    rtol = F32 if suffix.lower() == "stl" else 1e-12
    assert data["name"] == "brick"
    assert data["mass"] == pytest.approx(mass, rel=rtol)
    np.testing.assert_allclose(data["com"], 0.0, atol=rtol)
    np.testing.assert_allclose(data["inertia"], np.diag(_box_moments(mass, *SIZE)), rtol=rtol, atol=1e-15)
    np.testing.assert_allclose(data["principal_moments"], sorted(_box_moments(mass, *SIZE)), rtol=rtol)


@pytest.mark.parametrize(("options", "factor"), [(["--units", "mm"], 1e-3), (["--units", "cm"], 1e-2),
                                                 (["--units", "in"], 0.0254), (["--scale", "0.5"], 0.5),
                                                 (["--units", "m"], 1.0)])
def test_units_and_scale_convert_to_metres(tmp_path, capsys, options, factor):
    path = tmp_path / "brick.obj"
    path.write_text(_obj(size=(10.0, 20.0, 40.0)))
    code, out, _ = run(capsys, "inertia", path, "--mass", "3", *options, "--json")
    assert code == 0
    data = json.loads(out)
    assert data["mass"] == 3.0
    np.testing.assert_allclose(data["principal_moments"],
                               sorted(_box_moments(3.0, *(factor * s for s in (10.0, 20.0, 40.0)))), rtol=1e-12)


def test_json_equals_an_equivalent_body_file(tmp_path, capsys):
    """The same body as a body file: exactly with a mesh part, to float32 rounding with a box part."""
    (tmp_path / "brick.stl").write_text(_stl())
    mesh_part = tmp_path / "mesh_part.toml"
    mesh_part.write_text('[body]\nname = "brick"\n[[body.parts]]\nkind = "mesh"\nmesh = "brick.stl"\ndensity = 1000.0\n')
    box_part = tmp_path / "box_part.toml"
    box_part.write_text('[body]\nname = "brick"\n[[body.parts]]\nkind = "box"\ndensity = 1000.0\nsize = [0.1, 0.2, 0.4]\n')
    direct = json.loads(run(capsys, "inertia", tmp_path / "brick.stl", "--density", "1000", "--json")[1])
    assert direct == json.loads(run(capsys, "inertia", mesh_part, "--json")[1])
    boxed = json.loads(run(capsys, "inertia", box_part, "--json")[1])
    assert direct.keys() == boxed.keys()
    for key, value in direct.items():
        if isinstance(value, (str, dict)) or value is None:
            assert value == boxed[key], key
        else:
            np.testing.assert_allclose(value, boxed[key], rtol=F32, atol=F32 * 1e-3, err_msg=key)


def test_the_table_is_the_body_files_table(tmp_path, capsys):
    (tmp_path / "brick.obj").write_text(_obj())
    code, out, _ = run(capsys, "inertia", tmp_path / "brick.obj", "--mass", "8")
    assert code == 0
    assert out.startswith("brick: 1 part") and "intermediate axis +y" in out


def test_body_from_mesh_in_python(tmp_path):
    path = tmp_path / "brick.ply"
    path.write_text(_ply())
    body = body_from_mesh(path, mass=8.0)
    assert isinstance(body, tumble.Body) and body.name == "brick"
    np.testing.assert_allclose(body.inertia, np.diag(_box_moments(8.0, *SIZE)), rtol=1e-12, atol=1e-15)
    assert is_mesh_file(path) and is_mesh_file("A.Obj") and not is_mesh_file("a.toml")
    with pytest.raises(ValueError, match="exactly one of density"):
        body_from_mesh(path)
    with pytest.raises(ValueError, match="units = 'ft' is unknown; allowed: m, cm, mm, in"):
        body_from_mesh(path, mass=1.0, units="ft")


@pytest.mark.parametrize(
    ("argv", "says"),
    [
        (["{obj}"], "needs --density (kg/m^3) or --mass (kg)"),
        (["{obj}", "--density", "1000", "--mass", "2"], "--density = 1000 (kg/m^3) or --mass = 2 (kg), not both"),
        (["{obj}", "--mass", "-1"], "--mass = -1 must be a positive finite number (kg)"),
        (["{obj}", "--density", "heavy"], "--density = heavy must be a positive finite number"),
        (["{obj}", "--mass", "nan"], "--mass = nan must be"),
        (["{obj}", "--mass", "1", "--scale", "0"], "--scale = 0 must be"),
        (["{obj}", "--mass", "1", "--scale", "2", "--units", "mm"], "--scale = 2 or --units = mm, not both"),
        (["{obj}", "--mass", "1", "--units", "ft"], "invalid choice: 'ft' (choose from 'm', 'cm', 'mm', 'in')"),
        (["t-handle", "--mass", "1"], "--mass = 1 applies to a mesh file (.stl, .obj, .ply) only"),
        (["t-handle", "--units", "mm"], "--units = mm applies to a mesh file"),
        (["{open}", "--mass", "1"], "is not watertight"),
        (["{garbage}", "--mass", "1"], "garbage.stl"),
        (["{text}", "--mass", "1"], "notes.stl"),
        (["{missing}", "--mass", "1"], "no such file"),
        (["{folder}", "--mass", "1"], "is a directory"),
    ],
)
def test_bad_options_and_bad_meshes_are_one_line_and_exit_2(tmp_path, capsys, argv, says):
    files = {"obj": tmp_path / "brick.obj", "open": tmp_path / "open.obj", "garbage": tmp_path / "garbage.stl",
             "text": tmp_path / "notes.stl", "missing": tmp_path / "missing.ply", "folder": tmp_path / "dir.stl"}
    files["obj"].write_text(_obj())
    files["open"].write_text(_obj(faces=FACES[:-1]))
    files["garbage"].write_bytes(b"\x00\xff garbage" * 7)
    files["text"].write_text("not a mesh at all\n")
    files["folder"].mkdir()
    try:
        code = main(["inertia"] + [a.format(**files) for a in argv])
    except SystemExit as exc:  # argparse's own errors
        code = exc.code
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and "Traceback" not in err
    assert says in err


@pytest.mark.parametrize(("options", "says"), [
    (("--units", "mm", "--mass", "16000"), r"^warning: a mesh of 1\.6e\+04 kg in 0\.008 m\^3 is 2e\+06 kg/m\^3, more than "
                                            r"osmium's .*is its mass in grams\?"),
    (("--units", "mm", "--density", "7.85"), r"^warning: density = 7\.85 kg/m\^3 is below any solid's .*is it in g/cm\^3\?"),
    (("--mass", "16"), r"^warning: .*brick\.stl: the solid is 200 m across .*give units = \"mm\""),
    (("--units", "mm", "--mass", "16"), None),
])
def test_a_mesh_files_mass_and_density_are_checked_as_a_parts(tmp_path, capsys, options, says):
    """A walkthrough of docs/formats/body.md (2026-12-03): a mesh file on the command line, or a mesh part given by
    its mass, was never density-checked (2 kg written as 2000: 3.3e5 kg/m^3; 7.85 g/cm^3 written as kg/m^3: 0.047
    kg), though a box part was. Each slip is said once: a mesh read in the wrong unit has a density no solid has
    too, and only its size is named then. A 100 x 200 x 400 mm brick of 16 kg (2000 kg/m^3) is said nothing of."""
    (tmp_path / "brick.stl").write_text(_stl(size=(100.0, 200.0, 400.0)))
    code, _, err = run(capsys, "inertia", tmp_path / "brick.stl", *options, "--json")
    warned = [line for line in err.splitlines() if line.startswith("warning:")]
    assert code == 0 and len(warned) == (0 if says is None else 1), err
    assert says is None or re.search(says, warned[0]), warned
    # the same mesh as a body file's part, in grams: named where it is written
    (tmp_path / "b.toml").write_text('[body]\nname = "b"\nparts = [{kind = "mesh", mesh = "brick.stl", scale = 0.001, '
                                     'mass = 16000.0}]\n')
    code, _, err = run(capsys, "inertia", tmp_path / "b.toml", "--json")
    assert code == 0 and re.search(r"^warning: .*b\.toml.*parts\[0\].*: a mesh of 1\.6e\+04 kg .*grams\?", err, re.M), err
