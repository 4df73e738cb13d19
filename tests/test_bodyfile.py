"""Body files (TOML): every kind parses; every malformed file gets one line naming the field."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

import tumble
from tumble.cli import main
from tumble.mass import PART_KINDS

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def test_example_t_handle_file_equals_the_preset():
    np.testing.assert_allclose(tumble.load_body(EXAMPLES / "bodies" / "t_handle.toml").inertia, tumble.t_handle().inertia)


def test_every_part_example_uses_every_kind():
    """Every rigid kind; a rotor would make the body a gyrostat, which the example's scenario
    (method exact) cannot run: rotor files are tested in test_gyrostat.py."""
    body = tumble.load_body(EXAMPLES / "bodies" / "every_part.toml")
    assert {p.kind for p in body.parts} == set(PART_KINDS) - {"rotor"}
    assert any(p.subtract for p in body.parts)


def test_preset_names_and_preset_files():
    np.testing.assert_allclose(tumble.load_body("iss-t-handle").inertia, tumble.iss_t_handle().inertia)
    np.testing.assert_allclose(tumble.load_body(EXAMPLES / "bodies" / "iss_t_handle.toml").inertia, tumble.iss_t_handle().inertia)
    alu = tumble.load_body(EXAMPLES / "bodies" / "wing_nut.toml")
    assert alu.name == "aluminium T-handle"


def write(tmp_path, text: str) -> Path:
    path = tmp_path / "body.toml"
    path.write_text(text)
    return path


ROD = 'kind = "rod"\nmass = 1.0\nlength = 1.0\n'

BAD_FILES = [
    ("", "the file is empty"),
    ("[body\n", "not valid TOML"),
    ("x = 1\n", "missing table \\[body\\]"),
    ("[body]\nname = 'a'\n", "missing key 'parts'"),
    ("[body]\nparts = []\n", "non-empty list"),
    ("[body]\nparts = 3\n", "non-empty list"),
    ("[body]\nname = 3\n[[body.parts]]\n" + ROD, "body.name = 3 must be a string"),
    ("[[body.parts]]\n" + ROD + "[other]\n", "unknown top-level key 'other'"),
    ("[body]\ncolour = 'red'\n[[body.parts]]\n" + ROD, "unknown key 'colour'"),
    ("[[body.parts]]\nmass = 1.0\n", r"body.parts\[0\]: missing key 'kind'"),
    ("[[body.parts]]\nkind = 'blob'\n", r"body.parts\[0\]: kind = 'blob' is unknown; allowed: rod"),
    ("[[body.parts]]\nkind = 'rod'\nmass = 1.0\n", r"body.parts\[0\] \(rod\): missing key 'length'"),
    ("[[body.parts]]\n" + ROD + "lenght = 2.0\n", r"body.parts\[0\] \(rod\): unknown key 'lenght' \(did you mean 'length'\?\); allowed: kind, axis, center, length, mass"),
    ("[[body.parts]]\n" + ROD + "[[body.parts]]\nkind = 'rod'\nmass = -1.0\nlength = 1.0\n", r"body.parts\[1\] \(rod\): mass = -1.0 must be a positive"),
    ("[[body.parts]]\nkind = 'rod'\nmass = nan\nlength = 1.0\n", r"mass = nan must be a finite number"),
    ("[[body.parts]]\nkind = 'rod'\nmass = inf\nlength = 1.0\n", r"mass = inf must be a finite number"),
    ("[[body.parts]]\nkind = 'rod'\nmass = '1'\nlength = 1.0\n", r"mass = '1' must be a number"),
    ("[[body.parts]]\nkind = 'sphere'\nmass = 1.0\nradius = 0.0\n", r"radius = 0.0 must be a positive"),
    ("[[body.parts]]\nkind = 'box'\nmass = 1.0\nsize = [1.0, 2.0]\n", r"size = \[1.0, 2.0\] must be a list of 3 numbers"),
    ("[[body.parts]]\nkind = 'box'\nmass = 1.0\nsize = [1, 1, 1]\nrotation = [0, 0, 0, 0]\n", r"quaternion of norm 0"),
    ("[[body.parts]]\nkind = 'rod'\nmass = 1.0\nlength = 1.0\naxis = [0, 0, 0]\n", r"axis = \[0, 0, 0\] must be a non-zero"),
    ("[[body.parts]]\nkind = 'point'\nmass = 1.0\ndensity = 1.0\n", r"unknown key 'density'"),
    ("[[body.parts]]\nkind = 'mesh'\nmesh = 'nope.stl'\nmass = 1.0\n", r"body.parts\[0\] \(mesh\): mesh = '.*nope.stl': no such file"),
    ("[[body.parts]]\nkind = 'mesh'\nmesh = 3\nmass = 1.0\n", r"mesh = 3 must be a file path"),
    (
        "[[body.parts]]\nkind = 'sphere'\ndensity = 1.0\nradius = 1.0\n[[body.parts]]\nkind = 'sphere'\ndensity = 1.0\nradius = 1.0\nsubtract = true\n",
        r"total mass 0 kg is not positive",
    ),
    ("[body]\npreset = 'cube'\n", r"preset = 'cube' is unknown; allowed: t-handle, iss-t-handle"),
    ("[body]\npreset = 't-handle'\nshaft_lenght = 2.0\n", r"unknown key 'shaft_lenght' for preset 't-handle'"),
    ("[body]\npreset = 't-handle'\nshaft_length = -2.0\n", r"shaft_length = -2.0 must be a positive"),
    ("[body]\npreset = 'iss-t-handle'\nradius = 1.0\n", r"unknown key 'radius' for preset 'iss-t-handle'"),
]


@pytest.mark.parametrize(("text", "pattern"), BAD_FILES)
def test_malformed_body_files(tmp_path, text, pattern):
    path = write(tmp_path, text)
    with pytest.raises(ValueError, match=pattern) as info:
        tumble.load_body(path)
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(str(path))


def test_binary_junk(tmp_path):
    path = tmp_path / "junk.toml"
    path.write_bytes(bytes(range(256)))
    with pytest.raises(ValueError, match="not a text file"):
        tumble.load_body(path)


def test_missing_file_and_unknown_preset(tmp_path):
    with pytest.raises(ValueError, match="no such file"):
        tumble.load_body(tmp_path / "none.toml")
    with pytest.raises(ValueError, match="neither a body file nor a preset"):
        tumble.load_body("cube")


MM_AS_METRES = '[body]\nname = "handle"\n[[body.parts]]\nkind = "cylinder"\nmass = 0.2\nradius = 6.0\nlength = 120.0\n'


def test_a_part_sized_in_mm_warns_naming_the_file_and_the_part(tmp_path):
    """A cylinder of 0.2 kg written 120 m long and 6 m thick (mm typed as metres: 1.7e-5 kg/m^3, a
    hundred-thousandth of air) loaded without a word; it warns, naming the file and the part."""
    path = tmp_path / "handle.toml"
    path.write_text(MM_AS_METRES)
    with pytest.warns(tumble.mass.UnitSlipWarning) as caught:
        tumble.load_body(path)
    assert len(caught) == 1
    assert str(caught[0].message) == (f"{path}: body.parts[0] (cylinder): a cylinder of 0.2 kg in 1.36e+04 m^3 is "
                                      "1.47e-05 kg/m^3, less than the lightest solid's (an aerogel, 0.16 kg/m^3): are "
                                      "its sizes in mm or cm? Write them in metres (SI units)")
    written = MM_AS_METRES.replace("6.0", "0.006").replace("120.0", "0.12")  # the same in metres: no word
    path.write_text(written)
    with warnings.catch_warnings():
        warnings.simplefilter("error", tumble.mass.UnitSlipWarning)
        assert tumble.load_body(path).mass == pytest.approx(0.2)


def test_the_command_says_a_unit_slip_in_one_line_and_goes_on(tmp_path, capsys):
    path = tmp_path / "handle.toml"
    path.write_text(MM_AS_METRES)
    assert main(["inertia", str(path)]) == 0
    err = capsys.readouterr().err
    assert err.startswith(f"warning: {path}: body.parts[0] (cylinder): a cylinder of 0.2 kg") and err.count("\n") == 1


def test_no_example_body_or_preset_warns_of_a_unit_slip():
    with warnings.catch_warnings():
        warnings.simplefilter("error", tumble.mass.UnitSlipWarning)
        for path in sorted(EXAMPLES.glob("bodies/*.toml")):
            tumble.load_body(path)
        for name in tumble.mass.PRESETS:
            if name != "moments":  # by name it has no moments (below)
                tumble.load_body(name)
    with pytest.raises(ValueError, match=r"^preset 'moments' needs its moments, which a name cannot give: write a body "
                                         r"file, \[body\] preset = \"moments\" with moments = \[1.0, 2.0, 3.0\]$"):
        tumble.load_body("moments")


def test_a_mesh_part_in_mm_in_a_body_file_is_named_with_the_key_that_fixes_it(tmp_path):
    """A 300 x 200 x 100 mm STL as a body file's mesh part at water's density weighed 6e9 kg without a word
    (the same file given to tumble inertia warned, naming --units, which a body file refuses): the part
    warns where it is written, naming scale."""
    import trimesh

    from tumble.io.bodyfile import load_body
    from tumble.io.meshfile import MeshScaleWarning

    trimesh.creation.box(extents=(300.0, 200.0, 100.0)).export(tmp_path / "box_mm.stl")
    path = tmp_path / "b.toml"
    path.write_text('[body]\nname = "bracket"\n[[body.parts]]\nkind = "mesh"\nmesh = "box_mm.stl"\ndensity = 1000.0\n')
    with pytest.warns(MeshScaleWarning, match=r"body\.parts\[0\] \(mesh\): .*box_mm\.stl: the solid is 182 m across .*"
                                              r"millimetres, give scale = 0\.001$"):
        assert load_body(path).mass == pytest.approx(6e9)
    path.write_text(path.read_text() + "scale = 0.001\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error", MeshScaleWarning)  # in metres now: no warning
        assert load_body(path).mass == pytest.approx(6.0)


@pytest.mark.parametrize(("sizes", "mass", "words"), [
    ([15.0, 7.5, 0.8], 0.2, "are its sizes in mm or cm?"),  # a phone in cm: 2.2e-3 kg/m^3
    ([0.15, 0.075, 0.008], 200.0, "is its mass in grams?"),  # a phone of 200 g written 200: 2.2e6 kg/m^3
])
def test_a_phone_in_cm_or_in_grams_warns(tmp_path, sizes, mass, words):
    """A walkthrough's phone in cm (10^4 times its moments) and in grams (a "200 kg phone", 100 times
    osmium's density) loaded without a word; in metres and kg, none."""
    text = f'[[body.parts]]\nkind = "box"\nmass = {mass}\nsize = {sizes}\n'
    path = tmp_path / "phone.toml"
    path.write_text(text)
    with pytest.warns(tumble.mass.UnitSlipWarning, match=words):
        tumble.load_body(path)
    path.write_text('[[body.parts]]\nkind = "box"\nmass = 0.2\nsize = [0.15, 0.075, 0.008]\n')
    with warnings.catch_warnings():
        warnings.simplefilter("error", tumble.mass.UnitSlipWarning)
        assert tumble.load_body(path).mass == 0.2


def test_a_body_file_in_mm_or_a_density_in_g_cm3_is_named_as_a_likely_unit_slip(tmp_path, capsys):
    """A T-handle written in mm (rods 1000 'm' long: I3 = 437500 kg m^2 for 3 kg) and a steel rod of density
    7.85 (g/cm^3) ran with exit 0 and no word (a walkthrough of docs/tour.md, 2026-12-02): rods and points have no
    volume to check a density by, and a density was not checked at all. Each is one warning line naming the file
    and the likely unit; the shipped bodies give none."""
    from tumble.cli import main

    handle = ("[body]\nname = 'in mm'\n[[body.parts]]\nkind = 'rod'\nmass = 1.5\nlength = 1000.0\naxis = [0, 0, 1]\n"
              "[[body.parts]]\nkind = 'rod'\nmass = 1.5\nlength = 1000.0\naxis = [1, 0, 0]\ncenter = [0, 0, 500.0]\n")
    steel = "[body]\nname = 'steel'\n[[body.parts]]\nkind = 'cylinder'\ndensity = 7.85\nradius = 0.005\nlength = 0.2\n"
    for name, text, said in (("mm.toml", handle, "body: 3 kg with a radius of gyration of 382 m (sqrt(I3 / m)), as no "
                                                 "spacecraft"),
                             ("rho.toml", steel, "body.parts[0] (cylinder): density = 7.85 kg/m^3 is below any solid's "
                                                 "but a foam's or an aerogel's")):
        (tmp_path / name).write_text(text)
        assert main(["inertia", str(tmp_path / name)]) == 0
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and err.startswith(f"warning: {tmp_path / name}: {said}"), err
    examples = Path(__file__).resolve().parents[1] / "examples" / "bodies"
    for path in sorted(examples.glob("*.toml")):
        assert main(["inertia", str(path)]) == 0
        assert capsys.readouterr().err == "", path


def test_a_body_of_given_moments_is_a_preset_of_a_body_file(tmp_path, capsys):
    """A teacher's walkthrough (2026-12-03): a body file could not say I = 1, 2, 3 ("body: unknown key 'moments'"), only
    Python's from_moments; a box had to be invented. The preset "moments" is three thin rods with those moments along
    the design axes, exactly, the flat plate's I1 + I2 = I3 (a box of no thickness) included; moments no body has are
    refused in one line."""
    path = tmp_path / "textbook.toml"
    path.write_text('[body]\nname = "textbook"\npreset = "moments"\nmoments = [1.0, 2.0, 3.0]\n')
    body = tumble.load_body(path)
    assert body.principal_moments.tolist() == pytest.approx([1.0, 2.0, 3.0], rel=1e-14)
    np.testing.assert_array_equal(body.principal_axes, np.eye(3))
    assert body.mass == 1.0 and body.name == "textbook"
    assert main(["simulate", str(path), "--omega", "0.1", "2", "0.1", "--t-end", "20", "--out", str(tmp_path / "run")]) == 0
    assert "predicted unstable" in capsys.readouterr().out
    bad = tmp_path / "bad.toml"
    bad.write_text('[body]\npreset = "moments"\nmoments = [1.0, 2.0, 3.5]\nmass = 2.0\n')
    assert main(["inertia", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "moments = [1.0, 2.0, 3.5] breaks the triangle inequality" in err


@pytest.mark.parametrize("moments", [(1.0, 2.0, 3.0), (0.125, 0.3125, 0.4375), (2.0, 2.0, 3.0), (1.0, 1.0, 1.0),
                                     (0.3, 0.4, 0.5), (1e-6, 0.5, 0.5)])
def test_moments_body_has_the_moments_and_the_mass_it_is_given(moments):
    """Its three rods' moments m l^2 / 12 (Meriam & Kraige Table D/4, written here) add to the given moments."""
    body = tumble.moments_body(moments, mass=2.5)
    assert body.mass == pytest.approx(2.5, rel=1e-15)
    across = np.zeros(3)
    for rod in body.parts:
        k = int(np.argmax(np.abs(rod.axis)))
        across += rod.mass * rod.length**2 / 12.0 * (1.0 - np.eye(3)[k])
    np.testing.assert_allclose(across, moments, rtol=1e-13)
    np.testing.assert_allclose(body.principal_moments, moments, rtol=1e-13, atol=1e-15)


def test_the_inertia_table_names_a_symmetric_bodys_axes_and_a_signs_reason(tmp_path, capsys):
    """Two walkthroughs (2026-12-03): tumble inertia of Explorer 1 (I2 = I3) labelled I2 "intermediate" and then said
    "symmetric body: no intermediate axis"; a racket's major axis came out "-x" with no word why. The roles are the
    stability report's (symmetry axis, transverse), and a negative axis is said to keep the frame right-handed."""
    assert main(["inertia", str(EXAMPLES / "bodies" / "explorer1.toml")]) == 0
    out = capsys.readouterr().out
    assert "minor, the symmetry axis" in out and "transverse, I2 = I3" in out and "kg m^2  intermediate" not in out
    flipped = tmp_path / "flipped.toml"  # a box turned a half turn about z: its axes come out signed
    flipped.write_text('[body]\nname = "turned"\n[[body.parts]]\nkind = "box"\nmass = 1.0\nsize = [0.1, 0.2, 0.3]\n'
                       'rotation = [0.0, 0.0, 1.0, 0.0]\n')
    assert main(["inertia", str(flipped)]) == 0
    out = capsys.readouterr().out
    negative = any(line.rstrip().endswith(("axis -x", "axis -y", "axis -z")) for line in out.splitlines())
    assert negative and "(an axis's sign keeps the principal frame right-handed)" in out  # z x y = -x
