"""The reference tables of the input files and their parsers agree (#28, item 1).

Each format's tables (:mod:`tumble.io.keys`) are what its page shows (docs/formats/, rendered
by docs/_ext/tumble_keys.py) and what its parser checks keys against. Here, with the real
loaders on real files:

- every key of every example file under src/tumble/examples is in its table;
- a key not in a table is refused, and the message lists exactly the table's keys;
- every key of a table is taken (not refused as unknown) with its example value;
- a required key left out is refused, naming it;
- every bound and every choice a table states is the parser's: a value just outside is refused,
  naming the key and the value as written;
- the page lists every key of every table.
"""

from __future__ import annotations

import copy
import json
import math
import re
import sys
import tomllib
from pathlib import Path

import pytest

from tumble.io.bodyfile import BODY_FORMAT, PART_TABLES, PRESET_TABLES, load_body
from tumble.io.controlfile import CONTROL_FORMAT
from tumble.io.devicefile import DEVICE_FORMAT, load_device
from tumble.io.gyrocolumns import RATE_PREFIXES, RATE_UNITS, RECORDING_FORMAT, TIME_NAMES, TIME_UNITS
from tumble.io.gyrodata import parse_gyro_table
from tumble.io.keys import Key, Table
from tumble.io.scenario import SCENARIO_FORMAT, load_scenario
from tumble.io.sweepfile import SWEEP_FORMAT, load_sweep

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "src" / "tumble" / "examples"
MESH = str(EXAMPLES / "bodies" / "meshes" / "torus.stl")


# -- writing TOML (the loaders read files) -------------------------------------------------------

def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return repr(v) if math.isfinite(v) else ("inf" if v > 0 else "-inf")
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(v)


def _write(path: Path, data: dict) -> Path:
    path.write_text("".join(f"{json.dumps(k)} = {_value(v)}\n" for k, v in data.items()), encoding="utf-8")
    return path


# -- each table: a valid document, where the table sits in it, and the loader --------------------

_SPHERE = {"kind": "sphere", "mass": 1.0, "radius": 0.1, "center": [0.0, 0.0, 0.3]}
_PARTS = {
    "rod": {"mass": 1.0, "length": 1.0}, "cylinder": {"mass": 1.0, "radius": 0.1, "length": 1.0},
    "tube": {"mass": 1.0, "inner_radius": 0.04, "outer_radius": 0.05, "length": 1.0},
    "cone": {"mass": 1.0, "radius": 0.1, "height": 0.3}, "box": {"mass": 1.0, "size": [0.1, 0.2, 0.3]},
    "ellipsoid": {"mass": 1.0, "semi_axes": [0.1, 0.2, 0.3]}, "sphere": {"mass": 1.0, "radius": 0.1},
    "shell": {"mass": 1.0, "radius": 0.1}, "point": {"mass": 1.0}, "mesh": {"mass": 1.0, "mesh": MESH},
    "rotor": {"mass": 1.0, "radius": 0.1, "length": 0.05, "spin_rate": 10.0},
}
_SPIN = {"body": "t-handle", "initial": {"omega": [0.1, 5.0, 0.1]},
         "simulation": {"t_end": 1.0, "samples": 11, "method": "dop853"}}
_ORBITING = {"body": "t-handle", "initial": {"orbit_frame": {"pitch": 0.01}},
             "torque": {"kind": "gravity_gradient", "orbit_period": 5400.0},
             "simulation": {"t_end": 1.0, "samples": 11, "method": "dop853"}}
_SWEEP = {"body": "t-handle", "sweep": {"cases": 4}, "initial": {"omega": [0.1, 5.0, 0.1]},
          "dispersion": [{"target": "moments", "relative": 0.01}],   # cases of one run are refused
          "simulation": {"t_end": 1.0, "method": "dop853"}}
_PROOF = {"mass": 0.346, "inertia": [1.675805e-4, 1.300972e-4, 2.450833e-4]}
_DEVICE = {"device": {"mass": 0.10067, "rotor_axis": [0.0, 0.0, -1.0]}, "proof": _PROOF}
#: A calibrated device (as ``tumble calibrate`` writes it): each uncertainty with its value.
_CALIBRATED = {"device": {"mass": 0.10067, "rotor_axis": [0.0, 0.0, -1.0], "rotor_inertia": 1.7e-6,
                          "rotor_inertia_std": 2e-8, "inertia": [[3e-5, 0.0, 0.0], [0.0, 3e-5, 0.0], [0.0, 0.0, 5e-5]],
                          "inertia_std": [[1e-7, 0.0, 0.0], [0.0, 1e-7, 0.0], [0.0, 0.0, 1e-7]],
                          "center_of_mass": [0.001, 0.0, 0.002], "center_of_mass_std": [1e-4, 1e-4, 1e-4]},
               "proof": _PROOF}


def _control(name: str) -> dict:
    data = tomllib.loads((EXAMPLES / "control" / f"{name}.toml").read_text(encoding="utf-8"))
    if isinstance(data["body"], str):
        data["body"] = str((EXAMPLES / "control" / data["body"]).resolve())
    return data


def cases() -> list[tuple[str, Table, list[tuple[dict, tuple]], object]]:
    """``(format, table, [(valid document, path of the table in it), ...], loader)``; more than
    one document where a table's keys depend on its kind (a constant torque or the gravity
    gradient)."""
    body = lambda part: {"body": {"name": "b", "parts": [part, _SPHERE]}}  # noqa: E731
    found = [("body", BODY_FORMAT.table("top level"), [(body(_SPHERE), ())], load_body),
             ("body", BODY_FORMAT.table("[body]"), [(body(_SPHERE), ("body",))], load_body)]
    solid = {"preset": "t-handle", "shaft_radius": 0.01, "crossbar_radius": 0.01}  # density needs the radii
    given = {"moments": {"moments": [1.0, 2.0, 3.0]}}  # the parameters a preset needs (its required keys)
    found += [("body", PRESET_TABLES[p], [({"body": {"preset": p}}, ("body",)), ({"body": solid}, ("body",))]
               if p == "t-handle" else [({"body": {"preset": p, **given.get(p, {})}}, ("body",))], load_body)
              for p in PRESET_TABLES]
    found += [("body", PART_TABLES[k], [(body({"kind": k, **_PARTS[k]}), ("body", "parts", 0))], load_body)
              for k in PART_TABLES]
    torque = [({**_SPIN, "torque": {"vector": [0.0, 0.0, 0.01]}}, ("torque",)), (_ORBITING, ("torque",)),
              ({**_ORBITING, "torque": {"kind": "gravity_gradient", "orbit_radius": 6.78e6}}, ("torque",))]
    timed = {**_SPIN, "simulation": {"t_end": 1.0, "method": "dop853"}}
    found += [("scenario", SCENARIO_FORMAT.table(t), docs, load_scenario) for t, docs in (
        ("top level", [(_SPIN, ())]), ("[initial]", [(_SPIN, ("initial",))]),
        ("[initial.orbit_frame]", [(_ORBITING, ("initial", "orbit_frame"))]),
        ("[simulation]", [(_SPIN, ("simulation",)), (timed, ("simulation",))]), ("[torque]", torque),
        ("[damper]", [({**_SPIN, "damper": {"inertia": 0.01, "damping": 0.05}}, ("damper",))]))]
    found += [("sweep", SWEEP_FORMAT.table(t), docs, load_sweep) for t, docs in (
        ("top level", [(_SWEEP, ())]), ("[sweep]", [(_SWEEP, ("sweep",))]),
        ("[[dispersion]]", [({**_SWEEP, "dispersion": [{"target": "moments", "relative": 0.02}]}, ("dispersion", 0)),
                            ({**_SWEEP, "dispersion": [{"target": "axes", "absolute": 1e-3}]}, ("dispersion", 0))]),
        ("[initial]", [(_SWEEP, ("initial",))]), ("[simulation]", [(_SWEEP, ("simulation",))]),
        ("[torque]", [({**_SWEEP, "torque": {"vector": [0.0, 0.0, 0.01]}}, ("torque",)),
                      ({**_SWEEP, "torque": {"kind": "gravity_gradient", "orbit_period": 5400.0}}, ("torque",)),
                      ({**_SWEEP, "torque": {"kind": "gravity_gradient", "orbit_radius": 6.78e6}}, ("torque",))]),
        ("[criterion]", [({**_SWEEP, "criterion": {"column": "flips", "min": 1}}, ("criterion",))]))]
    bdot, mrp, mission = _control("detumble"), _control("point"), _control("detumble_point")
    found += [("control", CONTROL_FORMAT.table(t), docs, load_scenario) for t, docs in (
        ("top level", [(bdot, ())]), ("[initial]", [(bdot, ("initial",))]), ("[simulation]", [(bdot, ("simulation",))]),
        ("[orbit]", [(bdot, ("orbit",)), ({**mrp, "orbit": {"semi_major_axis": 7.2e6, "field": "igrf",
                                                               "epoch": "2026-11-25T00:00:00"}}, ("orbit",))]),
        ("[actuators]", [(mission, ("actuators",))]),
        ("[actuators.magnetorquers]", [(bdot, ("actuators", "magnetorquers"))]),
        ("[actuators.wheels]", [(mrp, ("actuators", "wheels"))]), ("[sensors]", [(bdot, ("sensors",))]),
        ('[control] kind = "bdot"', [(bdot, ("control",))]), ('[control] kind = "mrp_pd"', [(mrp, ("control",))]),
        ('[control] kind = "detumble_point"', [(mission, ("control",))]),
        ("[control.detumble]", [({**mission, "control": {**mission["control"], "detumble": {}}}, ("control", "detumble"))]),
        ("[control.point]", [(mission, ("control", "point"))]))]
    est = _control("estimate_point")
    fine = {**est, "sensors": {**est["sensors"], "sun": {"kind": "fine", "epoch": "2026-03-20T14:46:00"}}}
    tracked = {**est, "sensors": {**est["sensors"], "star_tracker": {"cross": 2e-5}}}
    found += [("control", CONTROL_FORMAT.table(t), docs, load_scenario) for t, docs in (
        ("[sensors.sun]", [(est, ("sensors", "sun")), (fine, ("sensors", "sun"))]),
        ("[sensors.star_tracker]", [(tracked, ("sensors", "star_tracker"))]), ("[estimator]", [(est, ("estimator",))]))]
    found += [("device", DEVICE_FORMAT.table(t), docs, load_device) for t, docs in (
        ("top level", [(_DEVICE, ())]), ("[device]", [(_DEVICE, ("device",)), (_CALIBRATED, ("device",))]),
        ("[proof]", [(_DEVICE, ("proof",))]))]
    return found


CASES = cases()
IDS = [f"{fmt}:{table.title}" for fmt, table, _, _ in CASES]


def _at(doc: dict, path: tuple):
    for step in path:
        doc = doc[step]
    return doc


def _error(tmp_path: Path, loader, doc: dict) -> str | None:
    """The loader's message for the document written to a file, or None when it loads."""
    try:
        loader(_write(tmp_path / "input.toml", doc))
    except ValueError as exc:
        return str(exc)
    return None


def _with(doc: dict, path: tuple, key: str, value=None, *, drop: bool = False) -> dict:
    doc = copy.deepcopy(doc)
    table = _at(doc, path)
    if drop:
        table.pop(key, None)
    else:
        table[key] = value
    return doc


def _refused_as_unknown(message: str | None, key: str) -> bool:
    return message is not None and bool(re.search(rf"(unknown( top-level)? key|key) {re.escape(repr(key))}"
                                                   rf"(;| does not go| for preset)", message))


def _home(tmp_path, loader, table: Table, docs, key: Key) -> tuple[dict, tuple]:
    """The first document that loads with ``key`` at its example value, else the first in which
    the table at least takes ``key`` (another key may conflict with it)."""
    taken = []
    for doc, path in docs:
        message = _error(tmp_path, loader, _with(doc, path, key.name, _example(key)))
        if message is None:
            return doc, path
        if not _refused_as_unknown(message, key.name):
            taken.append((doc, path))
    if taken:
        return taken[0]
    pytest.fail(f"{table.title}: {key.name} = {key.example} is refused in every document")


def _example(key: Key):
    if key.name == "mesh":
        return MESH
    if key.name == "epoch":
        return "2026-11-25T00:00:00"
    return tomllib.loads(f"v = {key.example}")["v"] if key.example else 1.0


# -- the tests -----------------------------------------------------------------------------------

@pytest.mark.parametrize(("fmt", "table", "docs", "loader"), CASES, ids=IDS)
def test_the_base_documents_load(tmp_path, fmt, table, docs, loader):
    for doc, _ in docs:
        assert _error(tmp_path, loader, doc) is None


@pytest.mark.parametrize(("fmt", "table", "docs", "loader"), CASES, ids=IDS)
def test_a_key_not_in_the_table_is_refused_and_the_message_lists_the_tables_keys(tmp_path, fmt, table, docs, loader):
    doc, path = docs[0]
    message = _error(tmp_path, loader, _with(doc, path, "no_such_key", 1.0))
    assert message is not None and "'no_such_key'" in message, message
    kinds = [t for t in CONTROL_FORMAT.tables if t.title.startswith("[control] kind")]
    if table in kinds:  # the section takes every kind's keys; each kind refuses the others'
        other = next(k for t in kinds for k in t.keys if k.name not in table.names())
        message = _error(tmp_path, loader, _with(doc, path, other.name, _example(other)))
        assert message is not None and "does not go with" in message, message
    allowed = {a.strip() for a in message.rpartition("allowed: ")[2].split(",")}
    if table.title.startswith("[body] preset"):
        allowed |= {"preset"}
    if table.title == "top level" and fmt != "body":
        allowed = {a.split(" ")[-1] for a in allowed}  # "allowed in a control scenario: body, ..."
    assert allowed == set(table.names()), (table.title, message)


# the keys' examples put together: a mesh part's scale (0.001, a mm file's) on the shipped torus, in metres,
# is a 0.04 mm solid, which the body file rightly warns of
@pytest.mark.filterwarnings("ignore::tumble.io.meshfile.MeshScaleWarning")
@pytest.mark.filterwarnings("ignore::tumble.dynamics.methods.arguments.IgnoredArgumentWarning")  # a key alone: step with dop853
@pytest.mark.parametrize(("fmt", "table", "docs", "loader"), CASES, ids=IDS)
def test_every_key_of_the_table_is_taken(tmp_path, fmt, table, docs, loader):
    for key in table.keys:
        _home(tmp_path, loader, table, docs, key)


@pytest.mark.parametrize(("fmt", "table", "docs", "loader"), CASES, ids=IDS)
def test_a_required_key_left_out_is_refused_naming_it(tmp_path, fmt, table, docs, loader):
    for key in table.keys:
        if key.required:
            doc, path = docs[0]
            if key.name not in _at(doc, path):
                continue  # the other of two ways (omega or grid; parts or preset) is the one given
            left = _with(doc, path, key.name, drop=True)
            if not left:
                continue  # an empty file: refused as such
            message = _error(tmp_path, loader, left)
            assert message is not None and key.name in message, (key.name, message)


def _outside(key: Key) -> list:
    whole = "whole" in key.type
    values = []
    if key.low is not None:
        low = key.low
        values.append((int(low) - 1 if whole else (-1.0 if low <= 0 else low / 10)) if key.low_included
                      else (int(low) if whole else float(low)))
    if key.high is not None:
        high = key.high
        values.append((int(high) + 1 if whole else float(high) * 2) if key.high_included
                      else (int(high) if whole else float(high)))
    if key.choices:
        values.append("no_such_choice")
    return values


# the keys' examples put together: a mesh part's scale (0.001, a mm file's) on the shipped torus, in metres,
# is a 0.04 mm solid, which the body file rightly warns of
@pytest.mark.filterwarnings("ignore::tumble.io.meshfile.MeshScaleWarning")
@pytest.mark.filterwarnings("ignore::tumble.dynamics.methods.arguments.IgnoredArgumentWarning")  # a key alone: step with dop853
@pytest.mark.parametrize(("fmt", "table", "docs", "loader"), CASES, ids=IDS)
def test_every_stated_bound_and_choice_is_the_parsers(tmp_path, fmt, table, docs, loader):
    checked = 0
    for key in table.keys:
        for value in _outside(key):
            doc, path = _home(tmp_path, loader, table, docs, key)
            message = _error(tmp_path, loader, _with(doc, path, key.name, value))
            shown = repr(value) if not isinstance(value, str) else value
            assert message is not None and key.name in message and shown in message, (key.name, value, message)
            checked += 1
    assert checked or not any(_outside(k) for k in table.keys)


def _example_keys(data: dict, fmt: str) -> list[tuple[str, str]]:
    """``(table title, key)`` of every key a parsed example file writes."""
    found = []

    def table(title, keys):
        found.extend((title, k) for k in keys)

    def body(b):
        if "preset" in b:
            table(f'[body] preset = "{b["preset"]}"', b)
        else:
            table("[body]", b)
        for p in b.get("parts", []):
            table(f'[[body.parts]] kind = "{p["kind"]}"', p)

    if fmt == "body":
        table("top level", data)
        body(data["body"])
        return found
    table("top level", data)
    if isinstance(data.get("body"), dict):
        body(data["body"])
    for name, sub in data.items():
        if name == "body" or not isinstance(sub, (dict, list)):
            continue
        if name == "control":
            table(f'[control] kind = "{sub["kind"]}"', sub)
            for s in ("detumble", "point"):
                if isinstance(sub.get(s), dict):
                    table(f"[control.{s}]", sub[s])
        elif name == "actuators":
            table("[actuators]", sub)
            for s, t in sub.items():
                table(f"[actuators.{s}]", t)
        elif name == "dispersion":
            for t in sub:
                table("[[dispersion]]", t)
        else:
            table(f"[{name}]", sub)
            for s, t in sub.items():
                if isinstance(t, dict):
                    table(f"[{name}.{s}]", t)
    return found


def _kind(path: Path, data: dict) -> str:
    if path.parent.name == "sweeps":
        return "sweep"
    if path.parent.name == "devices":
        return "device"
    if set(data) == {"body"}:
        return "body"
    return "control" if "control" in data else "scenario"


def test_every_key_of_every_example_file_is_in_its_table():
    formats = {"body": BODY_FORMAT, "scenario": SCENARIO_FORMAT, "control": CONTROL_FORMAT, "sweep": SWEEP_FORMAT,
               "device": DEVICE_FORMAT}
    files = sorted(EXAMPLES.rglob("*.toml"))
    assert len(files) >= 20
    seen = set()
    for path in files:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
        fmt = _kind(path, data)
        for title, key in _example_keys(data, fmt):
            tables = [t for t in (formats[fmt].tables + BODY_FORMAT.tables) if t.title == title]
            assert tables and key in tables[0].names(), f"{path.relative_to(EXAMPLES)}: {title} {key}"
            seen.add((fmt, title, key))
    assert len(seen) > 100
    assert {fmt for fmt, _, _ in seen} == set(formats)   # every format has an example file


def test_the_pages_list_every_key_of_every_table():
    pytest.importorskip("sphinx")
    sys.path.insert(0, str(ROOT / "docs" / "_ext"))
    import tumble_keys

    for page, fmt in (("body", BODY_FORMAT), ("scenario", SCENARIO_FORMAT), ("control", CONTROL_FORMAT),
                      ("sweep", SWEEP_FORMAT), ("recording", RECORDING_FORMAT), ("device", DEVICE_FORMAT)):
        source = (ROOT / "docs" / "formats" / f"{page}.md").read_text(encoding="utf-8")
        path = re.search(r"```\{tumble-keys\} (\S+)", source).group(1)
        assert tumble_keys.load_format(path) is fmt, page
        text = tumble_keys.render_format(fmt)
        for table in fmt.tables:
            assert f".. rubric:: {tumble_keys._plain(table.title)}\n" in text
            for key in table.keys:
                assert f"   * - ``{key.name}``\n" in text, (page, table.title, key.name)
        rows = text.count("   * - ``")
        assert rows == sum(len(t.keys) for t in fmt.tables)


# -- recordings: the column names and units of the table are the parser's -----------------------

def _header(time: str, rate: str) -> bytes:
    return (f"{time}, {rate.format(axis='x')}, {rate.format(axis='y')}, {rate.format(axis='z')}\n"
            "0, 1, 2, 3\n1, 1, 2, 3\n").encode()


@pytest.mark.parametrize("name", TIME_NAMES)
@pytest.mark.parametrize("unit", TIME_UNITS)
def test_every_time_name_and_unit_of_the_table_is_read(name, unit):
    t, _, read = parse_gyro_table(_header(f"{name.upper()} ({unit})", "w{axis}"), "r.csv")
    assert read.time_unit == unit and t[1] == pytest.approx(TIME_UNITS[unit])


@pytest.mark.parametrize("prefix", ("", *RATE_PREFIXES))
@pytest.mark.parametrize("unit", [u for u in RATE_UNITS if u.isascii()])
def test_every_rate_name_and_unit_of_the_table_is_read(prefix, unit):
    rate = f"{prefix.replace(' ', '_')}_{{axis}} [{unit}]" if prefix else f"{{axis}} [{unit}]"
    _, omega, read = parse_gyro_table(_header("t", rate), "r.csv")
    assert omega[0] == pytest.approx([RATE_UNITS[unit], 2 * RATE_UNITS[unit], 3 * RATE_UNITS[unit]])


def test_a_column_name_not_in_the_table_is_not_the_time_nor_a_rate():
    with pytest.raises(ValueError, match="no time column; allowed: time: t, time"):
        parse_gyro_table(_header("clock", "w{axis}"), "r.csv")
    with pytest.raises(ValueError, match="no rate column for x"):
        parse_gyro_table(_header("t", "spin_{axis}"), "r.csv")
    with pytest.raises(ValueError, match=r"unknown unit 'h' in header"):
        parse_gyro_table(_header("t (h)", "w{axis}"), "r.csv")
    keys = RECORDING_FORMAT.table("header columns")
    assert keys.key("time").choices == TIME_NAMES and all(p in keys.key("x").allowed for p in RATE_PREFIXES)
