"""Using the result of ``tumble tensor`` (issue #42 item 8): the simulator snippets it writes
(``inertial.urdf``, ``inertial.xml``), the throws' time series (``throws.npz``) and ``tumble view
DIR`` of its folder.

Checked against independent routes: the snippets parsed with ElementTree against tensor.json;
MuJoCo (the ``bench`` extra) compiling them, and a box geom whose tensor MuJoCo computes itself,
for the sign of the off-diagonal entries; the time series against the throw files read here with
the csv module; the equivalent box against the closed form of a box's moments. One tensor
output of two synthetic throws is made once for the module (the generator may change: nothing
here asserts the fit's accuracy, only that the files and the page say what tensor.json says).
"""

from __future__ import annotations

import csv
import json
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from test_page import MAX_PAGE_BYTES, page_json

from tumble.analysis.tensor.model import sample_means
from tumble.cli import main
from tumble.commands.tensor import TENSOR_WRITES
from tumble.io.devicefile import write_device
from tumble.io.inertial import mjcf_inertial, urdf_inertial
from tumble.io.throwfile import write_throw
from tumble.mass import Body, Box
from limits import HANG_MS

#: tumble.io.inertial writes 15 significant digits.
DIGITS = 1e-14


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    """``tumble tensor`` of two synthetic throws of a turned box, then ``tumble view`` of its folder:
    (folder, tensor.json, the throw files, the page's text, its data, what the commands printed)."""
    from tumble.analysis.tensor.synthetic import box, calibrated_device, combine, synthetic_throw, true_device

    root = tmp_path_factory.mktemp("tensor")
    bracket = box(0.482, (0.16, 0.09, 0.04), center=(0.012, -0.008, 0.035), rotvec=(0.2, -0.1, 0.35))
    throws = [write_throw(root / f"o{k}.csv", synthetic_throw(30 + k, combine(true_device(), bracket))) for k in (1, 2)]
    device = write_device(root / "calibrated.toml", calibrated_device())
    out, page = root / "bracket", root / "bracket.html"
    code = main(["tensor", *map(str, throws), "--device", str(device), "--mass", "0.482", "--out", str(out),
                 "--accept-inadequate"])
    assert code == 0
    assert main(["view", str(out), "--out", str(page)]) == 0
    html = page.read_text(encoding="utf-8")
    record = json.loads((out / "tensor.json").read_text(encoding="utf-8"))
    return out, record, throws, html, page_json(html)


def _one_line(capsys) -> str:
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("tumble: error: "), err
    return err


# --- the folder and the snippets ------------------------------------------------------------------

def test_the_folder_holds_the_files_the_command_lists(made):
    out = made[0]
    assert sorted(p.name for p in out.iterdir()) == sorted(TENSOR_WRITES)
    assert set(TENSOR_WRITES) == {"tensor.json", "tensor.png", "throws.npz", "inertial.urdf", "inertial.xml"}


def _entries(inertia) -> dict[str, float]:
    I = np.asarray(inertia, float)
    return {"ixx": I[0, 0], "iyy": I[1, 1], "izz": I[2, 2], "ixy": I[0, 1], "ixz": I[0, 2], "iyz": I[1, 2]}


def test_the_urdf_snippet_holds_tensor_json_object(made):
    out, record = made[:2]
    obj = record["object"]
    text = (out / "inertial.urdf").read_text(encoding="utf-8")
    inertial = ET.fromstring(text)
    assert inertial.tag == "inertial" and [c.tag for c in inertial] == ["origin", "mass", "inertia"]
    origin = inertial.find("origin")
    assert origin.get("rpy") == "0 0 0"
    np.testing.assert_allclose([float(x) for x in origin.get("xyz").split()], obj["center_of_mass"], rtol=DIGITS)
    assert float(inertial.find("mass").get("value")) == pytest.approx(obj["mass"], rel=DIGITS)
    written = inertial.find("inertia").attrib
    assert sorted(written) == ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"]
    for name, value in _entries(obj["inertia"]).items():  # the tensor's own entries, signs kept
        assert float(written[name]) == pytest.approx(value, rel=DIGITS, abs=1e-300), name
    # the comment names the frame and the uncertainties (a few of them, as printed there)
    comment = text[: text.index("-->")]
    assert "sensor frame, origin at the accelerometer" in comment and "ixy = -sum m x y" in comment
    assert f"{obj['principal_moments_std'][2]:.2g}" in comment and f"{obj['center_of_mass_std'][0]:.2g}" in comment
    assert f"{obj['principal_moments'][0]:.6g}" in comment
    assert "from 2 of 2 throws" in comment


def test_the_mjcf_snippet_holds_tensor_json_object_in_mujocos_order(made):
    out, record = made[:2]
    obj = record["object"]
    inertial = ET.fromstring((out / "inertial.xml").read_text(encoding="utf-8"))
    assert inertial.tag == "inertial" and sorted(inertial.attrib) == ["fullinertia", "mass", "pos"]
    np.testing.assert_allclose([float(x) for x in inertial.get("pos").split()], obj["center_of_mass"], rtol=DIGITS)
    assert float(inertial.get("mass")) == pytest.approx(obj["mass"], rel=DIGITS)
    e = _entries(obj["inertia"])
    full = [float(x) for x in inertial.get("fullinertia").split()]
    np.testing.assert_allclose(full, [e[k] for k in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")], rtol=DIGITS)


def _mujoco_tensor(model, name: str) -> tuple[np.ndarray, np.ndarray]:
    """A body's tensor about its centre of mass in its frame, as MuJoCo compiled it
    (``R diag(body_inertia) R^T``, R of ``body_iquat``), and its centre ``body_ipos``."""
    import mujoco

    body = model.body(name)
    R = np.zeros(9)
    mujoco.mju_quat2Mat(R, body.iquat)
    R = R.reshape(3, 3)
    return R @ np.diag(body.inertia) @ R.T, np.array(body.ipos)


def test_mujoco_compiles_both_snippets_to_the_principal_moments_and_centre(made):
    mujoco = pytest.importorskip("mujoco", reason="MuJoCo is in the bench extra: pip install 'tumble[bench]'")
    out, record = made[:2]
    obj = record["object"]
    mjcf = (out / "inertial.xml").read_text(encoding="utf-8")
    urdf = (out / "inertial.urdf").read_text(encoding="utf-8")
    models = {
        "mjcf": mujoco.MjModel.from_xml_string(f'<mujoco><worldbody><body name="object"><freejoint/>{mjcf}</body>'
                                               "</worldbody></mujoco>"),
        # MuJoCo reads URDF too; fusestatic off, or the lone link is fused into the world
        "urdf": mujoco.MjModel.from_xml_string(f'<robot name="r"><mujoco><compiler fusestatic="false"/></mujoco>'
                                               f'<link name="object">{urdf}</link></robot>'),
    }
    for route, model in models.items():
        body = model.body("object")
        np.testing.assert_allclose(np.sort(body.inertia), obj["principal_moments"], rtol=1e-9, err_msg=route)
        np.testing.assert_allclose(body.ipos, obj["center_of_mass"], rtol=1e-12, err_msg=route)
        assert float(body.mass[0]) == pytest.approx(obj["mass"], rel=1e-12)
        tensor, _ = _mujoco_tensor(model, "object")
        np.testing.assert_allclose(tensor, obj["inertia"], rtol=0, atol=1e-9 * np.trace(obj["inertia"]), err_msg=route)


def test_the_off_diagonal_sign_is_mujocos_own(tmp_path):
    """A turned box: MuJoCo computes its tensor from a box geom itself; tumble's tensor of the same
    box (tumble.mass), written by mjcf_inertial and urdf_inertial, compiles to the same tensor. With
    the products of inertia (+sum m x y) written instead, the axes would be mirrored."""
    mujoco = pytest.importorskip("mujoco", reason="MuJoCo is in the bench extra: pip install 'tumble[bench]'")
    turn = Rotation.from_rotvec([0.4, -0.7, 0.9])
    size, mass, center = (0.16, 0.09, 0.04), 0.482, (0.012, -0.008, 0.035)
    body = Body([Box(mass=mass, size=size, center=center, rotation=tuple(turn.as_quat()))])
    assert np.abs(body.inertia - np.diag(np.diag(body.inertia))).max() > 0.1 * np.trace(body.inertia) / 3  # turned
    estimate = {"mass": body.mass, "center_of_mass": body.com, "inertia": body.inertia}
    x, y, z, w = turn.as_quat()
    geom = (f'<geom type="box" size="{size[0] / 2} {size[1] / 2} {size[2] / 2}" mass="{mass}" '
            f'pos="{center[0]} {center[1]} {center[2]}" quat="{w} {x} {y} {z}"/>')
    model = mujoco.MjModel.from_xml_string(
        f'<mujoco><worldbody><body name="geom"><freejoint/>{geom}</body>'
        f'<body name="mjcf"><freejoint/>{mjcf_inertial(estimate)}</body></worldbody></mujoco>')
    urdf = mujoco.MjModel.from_xml_string(f'<robot name="r"><mujoco><compiler fusestatic="false"/></mujoco>'
                                          f'<link name="urdf">{urdf_inertial(estimate)}</link></robot>')
    reference, reference_center = _mujoco_tensor(model, "geom")
    np.testing.assert_allclose(reference, body.inertia, rtol=0, atol=1e-12)  # tumble's tensor is MuJoCo's
    for tensor, c in (_mujoco_tensor(model, "mjcf"), _mujoco_tensor(urdf, "urdf")):
        np.testing.assert_allclose(tensor, reference, rtol=0, atol=1e-12)
        np.testing.assert_allclose(c, reference_center, rtol=0, atol=1e-12)


# --- the throws' time series --------------------------------------------------------------------

def _read_csv(path: Path) -> np.ndarray:
    with open(path, newline="", encoding="utf-8") as fh:
        rows = [r for r in csv.reader(line for line in fh if not line.startswith("#"))][1:]
    return np.array([[float(v) for v in r] for r in rows])


def test_throws_npz_holds_each_throws_samples_as_the_files_hold_them(made):
    out, record, throws = made[:3]
    with np.load(out / "throws.npz", allow_pickle=False) as npz:
        arrays = {key: npz[key] for key in npz.files}
    assert int(arrays["count"]) == len(record["throws"]) == 2
    for k, (entry, path) in enumerate(zip(record["throws"], throws)):
        t = arrays[f"t_{k}"]
        assert t.ndim == 1 and arrays[f"omega_measured_{k}"].shape == arrays[f"omega_model_{k}"].shape == (t.size, 3)
        assert arrays[f"rotor_{k}"].shape == (t.size,)
        if entry["status"] != "used":
            continue
        assert t.size > 100
        assert entry["t_release"] - 1e-3 <= t[0] and t[-1] <= entry["t_end"] + 1e-3  # the flight, the file's clock
        rows = _read_csv(path)  # t, wx, wy, wz, rotor, ax, ay, az as the file writes them (SI)
        first = int(np.searchsorted(rows[:, 0], entry["t_release"] - 1e-9))
        stop = int(np.searchsorted(rows[:, 0], entry["t_end"] + 1e-9))
        tm, wm = sample_means(rows[first:stop, 0], rows[first:stop, 1:4])   # the fit's 1 ms means of the file's samples
        np.testing.assert_allclose(t, tm, rtol=0, atol=1e-12)
        np.testing.assert_allclose(arrays[f"omega_measured_{k}"], wm, rtol=1e-6, atol=1e-6)  # float32
        np.testing.assert_allclose(arrays[f"rotor_{k}"], np.interp(t, rows[:, 0], rows[:, 4]), rtol=1e-6, atol=1e-4)


# --- the page -------------------------------------------------------------------------------------

def test_the_page_says_what_tensor_json_says(made):
    out, record, _, html, data = made
    assert html.startswith("<!DOCTYPE html>") and html.rstrip().endswith("</html>")
    assert "<script src=" not in html and len(html.encode()) < MAX_PAGE_BYTES  # plotly inlined, nothing fetched
    obj = record["object"]
    for key, value in data["object"].items():
        assert value == obj[key], key
    assert data["adequate"] == record["adequate"] and data["chi2_dof"] == record["chi2_dof"]
    with np.load(out / "throws.npz") as npz:
        for k, (th, entry) in enumerate(zip(data["throws"], record["throws"], strict=True)):
            assert (th["number"], th["input"], th["status"], th["reason"]) == (k + 1, entry["input"], entry["status"],
                                                                                entry["reason"])
            assert th["moments"] == (entry["object"] or {}).get("principal_moments")
            t = npz[f"t_{k}"]
            assert th["samples"] == t.size
            kept = np.unique(np.append(np.arange(0, t.size, th["stride"]), t.size - 1))
            np.testing.assert_allclose(th["t"], t[kept] - entry["t_release"], rtol=1e-6, atol=1e-7)
            np.testing.assert_allclose(np.array(th["model"]).T, npz[f"omega_model_{k}"][kept], rtol=1e-4, atol=1e-4)
            np.testing.assert_allclose(th["rotor"], npz[f"rotor_{k}"][kept], rtol=1e-4)
    # the equivalent box: a uniform box of the object's mass and these edges has its moments
    # (m (b^2 + c^2) / 12 and cyclic, the edge k along axis k), here from the edges the page draws
    a, b, c = np.array(data["box"]["edges"]) / 1e3
    m = obj["mass"]
    np.testing.assert_allclose(m / 12 * np.array([b * b + c * c, a * a + c * c, a * a + b * b]),
                               obj["principal_moments"], rtol=5e-4)
    corners = np.array(data["box"]["corners"]) / 1e3
    # centred on the centre of mass, to the corners' rounding (the page's significant digits, in mm)
    from tumble.viz.page import DIGITS

    np.testing.assert_allclose(corners.mean(axis=0), obj["center_of_mass"], atol=np.abs(corners).max() * 10.0 ** (1 - DIGITS))
    assert len(data["box"]["faces"]) == 12


def test_the_page_draws_the_throws_in_chromium(made, tmp_path, new_page):
    data = made[4]
    page_file = tmp_path / "bracket.html"
    page_file.write_text(made[3], encoding="utf-8")
    watched = new_page(viewport={"width": 1300, "height": 1000})
    page = watched.page
    page.goto(page_file.as_uri())
    page.wait_for_function("window.tumbleTensor && window.tumbleTensor.ready", timeout=HANG_MS)
    rates = "document.getElementById('tumble-rates')"
    shown = [k for k, th in enumerate(data["throws"]) if th["samples"]]
    assert page.evaluate("document.getElementById('tumble-throw').options.length") == len(shown) == 2
    traces = page.evaluate(f"{rates}.data.map(d => [d.mode, d.name, d.x.length])")
    n = len(data["throws"][0]["t"])
    assert sorted(traces) == sorted([["markers", f"measured w{a}", n] for a in "xyz"] +
                                    [["lines", f"model w{a}", n] for a in "xyz"])
    assert page.evaluate(f"{rates}.querySelectorAll('.scatterlayer .trace').length") == 6  # drawn, not only data
    assert page.evaluate("document.getElementById('tumble-rotor').data[0].y.length") == n
    page.select_option("#tumble-throw", "1")
    page.wait_for_function("window.tumbleTensor.shown === 1", timeout=HANG_MS)
    assert page.evaluate(f"{rates}.data[0].x.length") == len(data["throws"][1]["t"])
    assert page.evaluate(f"{rates}.layout.title.text").startswith("throw 2: ")
    moments = page.evaluate("document.getElementById('tumble-moments').data.map(d => d.name)")
    assert moments.count("pooled") == 3 and "I1 of each throw" in moments
    assert page.evaluate("document.getElementById('tumble-shape').data[0].type") == "mesh3d"
    summary = page.evaluate("document.getElementById('tumble-summary').textContent")
    assert summary.startswith("object 0.482 kg") and "2 of 2 throws used" in summary
    assert watched.clean(), watched.errors


# --- bad input: one line, exit 2, nothing written -------------------------------------------------

def test_a_folder_of_neither_kind_or_a_damaged_one_is_one_line_and_exit_2(made, tmp_path, capsys):
    out = made[0]
    page = tmp_path / "page.html"
    empty = tmp_path / "empty"
    empty.mkdir()
    assert main(["view", str(empty), "--out", str(page)]) == 2
    assert f"{empty}: a folder without fit.json or tensor.json; give the output folder of tumble fit" in _one_line(capsys)
    folder = tmp_path / "copy"
    folder.mkdir()
    for name in ("tensor.json", "throws.npz"):
        (folder / name).write_bytes((out / name).read_bytes())
    assert main(["view", str(folder), "--out", str(page), "--omega", "1", "2", "3"]) == 2
    assert f"{folder}: a tensor's output folder shows its throws; --omega applies to a scenario" in _one_line(capsys)
    # a tensor's page has no animation: --frames was ignored without a word (a walkthrough, 2026-12-03)
    assert main(["view", str(folder), "--out", str(page), "--frames", "10"]) == 2
    assert (f"{folder}: a tensor's output folder shows its throws; --frames applies to a scenario, a body or a fit's "
            "folder (a tensor's page has no animation)") in _one_line(capsys)
    npz = (folder / "throws.npz").read_bytes()
    (folder / "throws.npz").write_bytes(npz[: len(npz) // 2])
    assert main(["view", str(folder), "--out", str(page)]) == 2
    assert f"{folder / 'throws.npz'}: damaged: not a NumPy .npz file" in _one_line(capsys)
    (folder / "throws.npz").unlink()
    assert main(["view", str(folder), "--out", str(page)]) == 2
    assert f"{folder}: no throws.npz beside tensor.json: the folder was written by an older tumble" in _one_line(capsys)
    record = json.loads((out / "tensor.json").read_text(encoding="utf-8"))
    record["object"]["principal_moments"] = [1.0, 2.0]
    (folder / "tensor.json").write_text(json.dumps(record), encoding="utf-8")
    assert main(["view", str(folder), "--out", str(page)]) == 2
    assert "tensor.json: damaged: object.principal_moments = [1.0, 2.0] must be finite numbers of shape (3,)" in \
        _one_line(capsys)
    (folder / "fit.json").write_text("{}", encoding="utf-8")
    assert main(["view", str(folder), "--out", str(page)]) == 2
    assert f"{folder}: holds both fit.json and tensor.json" in _one_line(capsys)
    assert not page.exists()
