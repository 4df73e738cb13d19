"""Body files (TOML): the public format that describes a rigid body.

::

    [body]
    name = "T-handle"

    [[body.parts]]
    kind = "rod"
    mass = 1.5                 # kg
    length = 1.0               # m
    center = [0.0, 0.0, 0.0]   # m, design frame
    axis = [0.0, 0.0, 1.0]

A file may instead say ``preset = "t-handle"`` (or ``"iss-t-handle"``) with the preset's
keyword arguments. Keys are checked strictly: unknown and missing keys, wrong types and
non-finite numbers raise ``ValueError`` with one line naming the part's index and the field.
The part constructors do the physical validation, so Python and files give the same messages.
"""

from __future__ import annotations

import contextlib
import dataclasses
import json
import math
import os
import tomllib
import warnings
from collections.abc import Iterator
from typing import Any
from pathlib import Path

from ..mass import PART_KINDS, PRESETS, Body, Part, UnitSlipWarning
from ..mass.holes import HoleFillWarning
from ..validation import unknown_name
from .examples import _read_input
from .keys import FileFormat, Key, Table
from .meshfile import (LIGHTEST_WRITTEN, MESH_SUFFIXES, MESH_UNITS, MeshScaleWarning, body_from_mesh, is_mesh_file, mesh_part,
                       mesh_scale_note, written_density_note)

__all__ = [
    "BODY_FORMAT",
    "LARGEST_SPAN",
    "LIGHTEST_WRITTEN",
    "MAX_TOML_BYTES",
    "MESH_SUFFIXES",
    "MESH_UNITS",
    "MeshScaleWarning",
    "body_from_mesh",
    "body_from_table",
    "is_mesh_file",
    "body_path",
    "load_body",
    "named_presets",
    "preset_body",
    "mesh_part",
    "mesh_scale_note",
    "mesh_files",
    "PART_TABLES",
    "PRESET_TABLES",
    "part_from_table",
    "read_toml",
    "written_density_note",
]


#: The largest body or scenario file (TOML) that :func:`read_toml` reads, in bytes (1 MiB).
#: The largest real file is a few kB; a bigger one is almost surely a mistake (a mesh or a
#: device such as /dev/zero given in its place) and would only use memory.
MAX_TOML_BYTES = 1 << 20


def read_toml(path: str | os.PathLike[str], *, what: str = "a body or scenario file (TOML)") -> dict:
    """Read a body or scenario file (TOML), turning every way it can fail into one ``ValueError``.

    Parameters
    ----------
    path : str or os.PathLike
        The file. It must be a regular file (not a directory, FIFO, socket or device) of at most
        :data:`MAX_TOML_BYTES`; both are checked before it is opened, and it is read with a
        bounded read.
    what : str
        What the file is, for the messages (a device file's reader says so).

    Returns
    -------
    dict
        The parsed TOML, never empty.

    Raises
    ------
    ValueError
        One line starting with the path: missing, not a regular file, too large, not UTF-8, not
        valid TOML, nested too deeply, or empty.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from tumble.io.bodyfile import read_toml
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "brick.toml")
    ...     _ = path.write_text('[body]\\nname = "brick"\\n')
    ...     good = read_toml(path)
    ...     _ = path.write_text('[body\\n')
    ...     try:
    ...         read_toml(path)
    ...     except ValueError as exc:
    ...         error = str(exc)
    >>> good
    {'body': {'name': 'brick'}}
    >>> "brick.toml: not valid TOML" in error   # one line, naming the file
    True
    """
    path = Path(path)
    raw = _read_input(path, limit=MAX_TOML_BYTES, what=what)
    try:
        text = raw.decode("utf-8-sig")  # a byte-order mark, as Windows editors write it, is no TOML statement
    except UnicodeDecodeError:
        # a CAD or mesh file of another kind (.step, a binary .stl): its suffix said first (a walkthrough)
        other = "" if path.suffix.lower() in ("", ".toml") else f" ({path.suffix} files are not read: meshes are " \
            f"{', '.join(MESH_SUFFIXES)})" if path.suffix.lower() not in MESH_SUFFIXES else " (a mesh: give it to " \
            "'tumble inertia', or as a part of a body file, kind = \"mesh\")"
        raise ValueError(f"{path}: not a text file (not valid UTF-8), so not {what}{other}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        if path.suffix.lower() in (".csv", ".txt", ".tsv"):  # a recording or a log given where a TOML file is read
            raise ValueError(f"{path}: a table of samples, not {what}: a gyroscope recording is fitted with "
                             "'tumble fit FILE --out DIR' (then 'tumble view DIR'), a throw's log with 'tumble tensor'") \
                from None
        if path.suffix.lower() == ".json":  # a result file given where its folder is read (tumble view fitted/fit.json)
            raise ValueError(f"{path}: a JSON file, not {what}; a fit's or a tensor's output folder is shown whole: "
                             f"'tumble view {path.parent}'") from None
        raise ValueError(f"{path}: not valid TOML: {exc}") from None
    except RecursionError:
        raise ValueError(
            f"{path}: nested too deeply (arrays or inline tables inside each other); "
            f"{what.removesuffix(' (TOML)')} needs at most a few levels"
        ) from None
    if not data:
        raise ValueError(f"{path}: the file is empty")
    return data


_VECTOR = "3 numbers"
_K = {k.name: k for k in (
    Key("kind", "string", required=True, choices=tuple(PART_KINDS), example='"rod"', doc="the shape"),
    Key("mass", "number", "kg", allowed="> 0; mass or density, exactly one", example="1.5", doc="the part's mass"),
    Key("density", "number", "kg/m^3", allowed="> 0; mass or density, exactly one", example="2700.0",
        doc="uniform density, instead of mass"),
    Key("center", _VECTOR, "m", "[0, 0, 0]", example="[0.0, 0.0, 0.5]", doc="the centre of mass, design frame"),
    Key("subtract", "true or false", "", "false", example="true",
        doc="a hole: its mass is taken from the part it lies in"),
    Key("axis", _VECTOR, "", "[0, 0, 1]", allowed="not zero (its length does not matter)", example="[1.0, 0.0, 0.0]",
        doc="the symmetry axis, design frame"),
    Key("length", "number", "m", required=True, example="1.0", low=0.0, doc="along the axis"),
    Key("radius", "number", "m", required=True, example="0.05", low=0.0, doc="the radius"),
    Key("inner_radius", "number", "m", required=True, allowed=">= 0 and < outer_radius", example="0.04",
        doc="the bore"),
    Key("outer_radius", "number", "m", required=True, example="0.05", low=0.0, doc="the outside"),
    Key("height", "number", "m", required=True, example="0.3", low=0.0, doc="from the base to the apex, along the axis"),
    Key("size", _VECTOR, "m", required=True, allowed="> 0 each", example="[0.1, 0.2, 0.3]",
        doc="the edges along the part's own x, y, z"),
    Key("semi_axes", _VECTOR, "m", required=True, allowed="> 0 each", example="[0.1, 0.2, 0.3]",
        doc="along the part's own x, y, z"),
    Key("rotation", "4 numbers", "", "[0, 0, 0, 1]", allowed="a unit quaternion [x, y, z, w]",
        example="[0.0, 0.0, 0.3826834, 0.9238795]", doc="the part's own frame in the design frame"),
    Key("spin_rate", "number", "rad/s", required=True, example="100.0", doc="the spin relative to the body (at t = 0)"),
    Key("spin_acceleration", "number", "rad/s^2", "0.0", example="0.5", doc="a constant ds/dt: a linear ramp"),
    Key("mesh", "string", required=True, allowed="a closed triangle mesh: STL, OBJ, PLY", example='"meshes/bracket.stl"',
        doc="the mesh file, relative to the body file"),
    Key("scale", "number", "", "1.0", example="0.001", low=0.0, doc="factor from file units to metres"),
    Key("origin", _VECTOR, "m", "[0, 0, 0]", example="[0.0, 0.0, 0.1]",
        doc="where the mesh's own origin goes, design frame"),
)}
_MASS_ONLY = dataclasses.replace(_K["mass"], required=True, allowed="> 0")
_SOLID = ("mass", "density", "center", "subtract")
#: The keys of each kind of ``[[body.parts]]`` table.
PART_TABLES = {kind: Table(f'[[body.parts]] kind = "{kind}"', (_K["kind"], *keys)) for kind, keys in {
    "rod": (_MASS_ONLY, _K["center"], _K["axis"], _K["length"]),
    "cylinder": (*(_K[k] for k in (*_SOLID, "axis", "radius", "length")),),
    "tube": (*(_K[k] for k in (*_SOLID, "axis", "inner_radius", "outer_radius", "length")),),
    "cone": (*(_K[k] for k in (*_SOLID, "axis", "radius", "height")),),
    "box": (*(_K[k] for k in (*_SOLID, "rotation", "size")),),
    "ellipsoid": (*(_K[k] for k in (*_SOLID, "rotation", "semi_axes")),),
    "sphere": (*(_K[k] for k in (*_SOLID, "radius")),),
    "shell": (_MASS_ONLY, _K["center"], _K["radius"]),
    "point": (_MASS_ONLY, _K["center"]),
    "rotor": (*(_K[k] for k in ("mass", "density", "center")),
              dataclasses.replace(_K["subtract"], allowed="false (a hole cannot spin)"),
              *(_K[k] for k in ("axis", "radius", "length", "spin_rate", "spin_acceleration"))),
    "mesh": (*(_K[k] for k in ("mass", "density", "subtract", "rotation", "mesh", "scale", "origin")),),
}.items()}
_M = "kg, instead of density"
#: The keys of a ``[body]`` table that names a preset, for each preset.
PRESET_TABLES = {
    "t-handle": Table('[body] preset = "t-handle"', (
        Key("preset", "string", required=True, choices=tuple(PRESETS), example='"t-handle"', doc="the preset"),
        Key("shaft_length", "number", "m", "1.0", example="1.2", low=0.0, doc="the handle's shaft"),
        Key("crossbar_length", "number", "m", "1.0", example="0.8", low=0.0, doc="the crossbar"),
        Key("shaft_mass", "number", "kg", "1.5 (with no density)", example="2.0", low=0.0, doc="the shaft's mass"),
        Key("crossbar_mass", "number", "kg", "1.5 (with no density)", example="1.0", low=0.0, doc="the crossbar's mass"),
        Key("shaft_radius", "number", "m", "0.0 (a thin rod)", example="0.01", low=0.0, low_included=True,
            doc="a solid cylinder when > 0"),
        Key("crossbar_radius", "number", "m", "0.0 (a thin rod)", example="0.01", low=0.0, low_included=True,
            doc="a solid cylinder when > 0"),
        Key("density", "number", "kg/m^3", example="2700.0", low=0.0, doc="instead of the masses (needs the radii)"),
        Key("name", "string", "", '"T-handle"', example='"long handle"', doc="the body's name"),
    ), "The seed study's T-handle and its parameters."),
    "iss-t-handle": Table('[body] preset = "iss-t-handle"', (
        Key("preset", "string", required=True, choices=tuple(PRESETS), example='"iss-t-handle"', doc="the preset"),
        Key("name", "string", "", '"ISS T-handle"', example='"handle"', doc="the body's name"),
    ), "The space station's T-handle (Dzhanibekov's wing nut)."),
    "moments": Table('[body] preset = "moments"', (
        Key("preset", "string", required=True, choices=tuple(PRESETS), example='"moments"', doc="the preset"),
        Key("moments", "3 numbers", "kg m^2", required=True, example="[1.0, 2.0, 3.0]",
            allowed="positive, ascending, I1 + I2 >= I3",
            doc="the principal moments along design x, y, z (tumble.moments_body: three thin rods)"),
        Key("mass", "number", "kg", "1.0", example="0.35", low=0.0, doc="the body's mass"),
        Key("name", "string", "", '"body of given moments"', example='"book"', doc="the body's name"),
    ), "A body known only by its principal moments (a textbook's, a published inertia)."),
}
#: The tables of a body file and their keys.
BODY_FORMAT = FileFormat("body", (
    Table("top level", (Key("body", "table", required=True, example='{name = "T-handle", preset = "t-handle"}',
                            doc="[body]: the only table of a body file"),)),
    Table("[body]", (
        Key("name", "string", "", '"body"', example='"T-handle"', doc="the body's name, in reports and figures"),
        Key("parts", "list of tables", example='[{kind = "sphere", mass = 1.0, radius = 0.1}]',
            doc="[[body.parts]]: the parts, one table each (or preset)"),
        Key("preset", "string", choices=tuple(PRESETS), example='"t-handle"', doc="instead of parts: a preset body"),
    ), "``parts`` or ``preset``, one of them."),
    *PRESET_TABLES.values(),
    *PART_TABLES.values(),
), "A rigid body built from parts, or a preset: ``tumble inertia``, ``tumble simulate`` and the "
   "scenario, control and sweep files read it.")


def part_from_table(table: object, *, base_dir: Path | None = None, where: str = "part") -> Part:
    """Build a part from a TOML table (a dict); ``mesh`` paths are relative to ``base_dir``.

    Examples
    --------
    >>> from tumble.io.bodyfile import part_from_table
    >>> rod = part_from_table({"kind": "rod", "mass": 3.0, "length": 2.0, "axis": [1, 0, 0]})
    >>> type(rod).__name__, rod.inertia.round(6).diagonal().tolist()   # m L^2 / 12 across the x axis
    ('Rod', [0.0, 1.0, 1.0])
    >>> part_from_table({"kind": "rod", "mass": 3.0})   # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: ...length...
    """
    if not isinstance(table, dict):
        raise ValueError(f"{where} must be a table with a 'kind', got {type(table).__name__}")
    kind = table.get("kind")
    if kind is None:
        raise ValueError(f"{where}: missing key 'kind' (one of {', '.join(PART_KINDS)})")
    if not isinstance(kind, str) or kind not in PART_KINDS:
        raise ValueError(f"{where}: kind = {kind!r} is unknown; allowed: {', '.join(PART_KINDS)}")
    cls = PART_KINDS[kind]
    where = f"{where} ({kind})"
    keys = PART_TABLES[kind]
    kwargs = {k: v for k, v in table.items() if k != "kind"}
    unknown = sorted(set(kwargs) - set(keys.names()))
    if unknown:
        raise ValueError(unknown_name(where, unknown[0], ["kind", *sorted(keys.names()[1:])]))
    missing = [k.name for k in keys.keys[1:] if k.required and k.name not in kwargs and k.name != "mass"]
    if missing:
        raise ValueError(f"{where}: missing key {missing[0]!r}")
    if kind == "mesh":
        mesh = kwargs["mesh"]
        if not isinstance(mesh, str):
            raise ValueError(f"{where}: mesh = {mesh!r} must be a file path (a string)")
        kwargs["mesh"] = os.path.join(base_dir or ".", mesh)
    with _slips_named(where):  # a likely unit slip, named where it is written
        try:  # a mesh's size and density as tumble inertia checks a mesh file's (a part in mm weighed 6e9 kg)
            part = mesh_part(kwargs.pop("mesh"), key="scale", **kwargs) if kind == "mesh" else cls(**kwargs)
        except ValueError as exc:
            raise ValueError(f"{where}: {exc}") from None
        written = None if kind == "mesh" or part.density is None else written_density_note(part.density)
        if written:
            warnings.warn(written, UnitSlipWarning, stacklevel=2)
        return part


@contextlib.contextmanager
def _slips_named(where: object) -> Iterator[None]:
    """The block's :class:`~tumble.mass.UnitSlipWarning` and hole-fill warnings again, ``where: `` before each
    (the file, the part); other warnings as they came."""
    with warnings.catch_warnings(record=True) as slips:
        warnings.simplefilter("always", UnitSlipWarning)
        yield
    for slip in slips:
        named = f"{where}: " if issubclass(slip.category, (UnitSlipWarning, HoleFillWarning)) else ""
        warnings.warn(f"{named}{slip.message}", slip.category, stacklevel=3)


#: A body file's body under 1e6 kg whose radius of gyration passes this (m) is most likely sized in
#: mm or cm: the International Space Station's is ~30 m (4.2e5 kg); an asteroid's mass is far above.
LARGEST_SPAN = 100.0


def body_from_table(table: object, *, base_dir: Path | None = None, where: str = "body") -> Body:
    """Build a body from the contents of a ``[body]`` table.

    Examples
    --------
    >>> from tumble.io.bodyfile import body_from_table
    >>> body = body_from_table({"name": "dumbbell", "parts": [{"kind": "point", "mass": 1.0, "center": [0, 0, 1]},
    ...                                                      {"kind": "point", "mass": 1.0, "center": [0, 0, -1]}]})
    >>> body.name, body.principal_moments.tolist()
    ('dumbbell', [0.0, 2.0, 2.0])
    """
    if not isinstance(table, dict):
        raise ValueError(f"{where} must be a table, got {type(table).__name__}")
    name = table.get("name", "body")
    if not isinstance(name, str):
        raise ValueError(f"{where}.name = {name!r} must be a string")
    if "preset" in table:
        return _preset_from_table(table, where)
    unknown = sorted(set(table) - {"name", "parts"})
    if unknown:
        raise ValueError(unknown_name(where, unknown[0], ["name", "parts", "preset"]))
    parts = table.get("parts")
    if parts is None:
        raise ValueError(f"{where}: missing key 'parts' (a list of [[{where}.parts]] tables) or 'preset'")
    if not isinstance(parts, list) or not parts:
        raise ValueError(f"{where}.parts must be a non-empty list of [[{where}.parts]] tables")
    built = tuple(
        part_from_table(p, base_dir=base_dir, where=f"{where}.parts[{i}]") for i, p in enumerate(parts)
    )
    try:
        body = Body(built, name=name)
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None
    gyration = math.sqrt(body.principal_moments[2] / body.mass)
    if gyration > LARGEST_SPAN and body.mass < 1e6:  # a body file in mm: rods, spheres or points kilometres apart
        warnings.warn(f"{where}: {body.mass:.3g} kg with a radius of gyration of {gyration:.3g} m (sqrt(I3 / m)), as "
                      f"no spacecraft (the International Space Station's is ~30 m, at 4.2e5 kg): are its sizes in mm or "
                      f"cm? Write them in metres (SI units)", UnitSlipWarning, stacklevel=2)
    return body


def mesh_files(table: dict, base_dir: Path | None = None) -> list[Path]:
    """The mesh files a ``[body]`` table's parts read (paths relative to ``base_dir``), in order.

    What a body's mass properties depend on besides the table itself: their content hashes go
    into a sweep's fingerprint and every output's provenance.

    Examples
    --------
    >>> from pathlib import Path
    >>> from tumble.io.bodyfile import mesh_files
    >>> table = {"parts": [{"kind": "mesh", "mesh": "m/a.stl", "mass": 1.0},
    ...                    {"kind": "sphere", "mass": 1.0, "radius": 0.1}]}
    >>> [p.as_posix() for p in mesh_files(table, Path("bodies"))]
    ['bodies/m/a.stl']
    """
    parts = table.get("parts") if isinstance(table, dict) else None
    if not isinstance(parts, list):
        return []
    return [Path(os.path.join(base_dir or ".", p["mesh"])) for p in parts
            if isinstance(p, dict) and p.get("kind") == "mesh" and isinstance(p.get("mesh"), str)]


def _preset_from_table(table: dict, where: str) -> Body:
    preset = table["preset"]
    if not isinstance(preset, str) or preset not in PRESETS:
        raise ValueError(f"{where}.preset = {preset!r} is unknown; allowed: {', '.join(PRESETS)}")
    fn = PRESETS[preset]
    kwargs = {k: v for k, v in table.items() if k != "preset"}
    allowed = list(PRESET_TABLES[preset].names()[1:])
    unknown = sorted(set(kwargs) - set(allowed))
    if unknown:
        raise ValueError(unknown_name(where, unknown[0], allowed, after=f" for preset {preset!r}",
                                      listed=None if allowed else "no parameters besides 'preset'"))
    missing = [k for k in PRESET_TABLES[preset].keys[1:] if k.required and k.name not in kwargs]
    if missing:  # the moments preset's moments (a TypeError of the function's call otherwise)
        raise ValueError(f"{where}: missing key {missing[0].name!r} ({missing[0].unit}) for preset {preset!r}")
    try:
        return fn(**kwargs)
    except ValueError as exc:
        raise ValueError(f"{where} (preset {preset!r}): {exc}") from None


def named_presets() -> list[str]:
    """The presets a name alone gives (a command line's ``t-handle``), not those that need
    parameters of their own (``moments``).

    Examples
    --------
    >>> from tumble.io.bodyfile import named_presets
    >>> named_presets()
    ['t-handle', 'iss-t-handle']
    """
    return [name for name in PRESETS if not any(k.required for k in PRESET_TABLES[name].keys[1:])]


def preset_body(name: str) -> Body:
    """The preset ``name`` (:data:`tumble.mass.PRESETS`) with its defaults, as a command line or a
    run file's ``body = "NAME"`` names it; a ValueError for one that needs parameters of its own.

    Examples
    --------
    >>> from tumble.io.bodyfile import preset_body
    >>> preset_body("t-handle").name
    'T-handle'
    >>> preset_body("moments")
    Traceback (most recent call last):
    ...
    ValueError: preset 'moments' needs its moments, which a name cannot give: write a body file, [body] preset = "moments" with moments = [1.0, 2.0, 3.0]
    """
    if name not in named_presets():  # the moments preset's moments
        required = [k.name for k in PRESET_TABLES[name].keys[1:] if k.required]
        raise ValueError(f"preset {name!r} needs its {', '.join(required)}, which a name cannot give: write a body "
                         f"file, [body] preset = {json.dumps(name)} with {required[0]} = {PRESET_TABLES[name].keys[1].example}")
    return PRESETS[name]()


def body_path(spec: str, base_dir: Path | None) -> Path:
    """The file a run file's ``body = "..."`` names (not a preset), relative to the run file's
    folder ``base_dir``; a ValueError naming the path looked for where there is none.

    Examples
    --------
    >>> from pathlib import Path
    >>> from tumble.io.bodyfile import body_path
    >>> body_path("bodies/none.toml", Path("runs"))
    Traceback (most recent call last):
    ...
    ValueError: body = 'bodies/none.toml' is neither a preset (t-handle, iss-t-handle) nor a file: no runs/bodies/none.toml
    """
    path = Path(spec) if base_dir is None else base_dir / spec
    if not path.exists():
        raise ValueError(f"body = {spec!r} is neither a preset ({', '.join(named_presets())}) nor a file: no {path}")
    return path


def _refuse_a_run_file(path: Path, data: dict[str, Any]) -> None:
    """A sweep, scenario or control file where a body file was asked for: say what it is and where
    its body is (a scenario's ``body`` names a preset or a file beside it, or is a table of its own)."""
    if "sweep" in data:
        raise ValueError(f"{path}: a sweep file ([sweep]), not a body file: a body file holds a [body] table alone "
                         f"(or give a preset: {', '.join(named_presets())})")
    if not ({"initial", "simulation", "control"} & set(data)):
        return
    spec = data.get("body")
    if isinstance(spec, str):
        named = spec if spec in PRESETS and not (path.parent / spec).exists() else str(path.parent / spec)
        hint = f"; its body is {spec!r}: try 'tumble inertia {named}'"
    else:
        hint = "; its [body] table, in a file of its own, is a body file"
    raise ValueError(f"{path}: a scenario file ([initial], [simulation]), not a body file{hint}")


def load_body(source: str | os.PathLike[str]) -> Body:
    """A body from a body file (TOML) or a preset name (``"t-handle"``, ``"iss-t-handle"``).

    Parameters
    ----------
    source : str or os.PathLike
        A preset name or the path of a body file.

    Raises
    ------
    ValueError
        One line naming the file, the part's index and the field.

    Examples
    --------
    >>> import pathlib, tempfile, tumble
    >>> tumble.load_body("t-handle").principal_moments.tolist()   # a preset by name
    [0.125, 0.3125, 0.4375]
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "brick.toml")
    ...     _ = path.write_text('[body]\\nname = "brick"\\n[[body.parts]]\\nkind = "box"\\nmass = 12.0\\nsize = [1.0, 2.0, 3.0]\\n')
    ...     body = tumble.load_body(path)
    >>> body.name, body.principal_moments.round(6).tolist()   # m (b^2 + c^2) / 12 and cyclic, ascending
    ('brick', [5.0, 10.0, 13.0])
    """
    if isinstance(source, str) and source in PRESETS and not os.path.exists(source):
        return preset_body(source)
    path = Path(source)
    if not path.exists() and isinstance(source, str) and path.suffix == "":
        raise ValueError(
            f"{source!r} is neither a body file nor a preset; presets: {', '.join(named_presets())}"
        )
    data = read_toml(path)
    unknown = sorted(set(data) - {"body"})
    _refuse_a_run_file(path, data)
    if "body" not in data:
        raise ValueError(f"{path}: missing table [body]")
    if unknown:
        raise ValueError(f"{path}: unknown top-level key {unknown[0]!r} (a body file has only [body]); allowed: body")
    with _slips_named(path):
        try:
            return body_from_table(data["body"], base_dir=path.parent)
        except ValueError as exc:
            raise ValueError(f"{path}: {exc}") from None
