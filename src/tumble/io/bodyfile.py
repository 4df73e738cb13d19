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

import dataclasses
import inspect
import os
import tomllib
from pathlib import Path

from ..mass import PART_KINDS, PRESETS, Body, Mesh, Part
from ..validation import read_input_file

__all__ = [
    "MAX_TOML_BYTES",
    "MESH_SUFFIXES",
    "MESH_UNITS",
    "body_from_mesh",
    "body_from_table",
    "is_mesh_file",
    "load_body",
    "mesh_files",
    "part_from_table",
    "read_toml",
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
    raw = read_input_file(path, limit=MAX_TOML_BYTES, what=what)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise ValueError(f"{path}: not a text file (not valid UTF-8)") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{path}: not valid TOML: {exc}") from None
    except RecursionError:
        raise ValueError(
            f"{path}: nested too deeply (arrays or inline tables inside each other); "
            f"{what.removesuffix(' (TOML)')} needs at most a few levels"
        ) from None
    if not data:
        raise ValueError(f"{path}: the file is empty")
    return data


def _init_fields(cls) -> dict[str, dataclasses.Field]:
    return {f.name: f for f in dataclasses.fields(cls) if f.init}


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
    fields = _init_fields(cls)
    allowed = [k for k in fields if cls.solid or k not in ("density", "subtract")]
    kwargs = {k: v for k, v in table.items() if k != "kind"}
    unknown = sorted(set(kwargs) - set(allowed))
    if unknown:
        raise ValueError(
            f"{where}: unknown key {unknown[0]!r}; allowed: kind, {', '.join(sorted(allowed))}"
        )
    missing = [
        k
        for k, f in fields.items()
        if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING
        and k not in kwargs
    ]
    if missing:
        raise ValueError(f"{where}: missing key {missing[0]!r}")
    if kind == "mesh":
        mesh = kwargs["mesh"]
        if not isinstance(mesh, str):
            raise ValueError(f"{where}: mesh = {mesh!r} must be a file path (a string)")
        kwargs["mesh"] = os.path.join(base_dir or ".", mesh)
    try:
        return cls(**kwargs)
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None


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
        raise ValueError(f"{where}: unknown key {unknown[0]!r}; allowed: name, parts, preset")
    parts = table.get("parts")
    if parts is None:
        raise ValueError(f"{where}: missing key 'parts' (a list of [[{where}.parts]] tables) or 'preset'")
    if not isinstance(parts, list) or not parts:
        raise ValueError(f"{where}.parts must be a non-empty list of [[{where}.parts]] tables")
    built = tuple(
        part_from_table(p, base_dir=base_dir, where=f"{where}.parts[{i}]") for i, p in enumerate(parts)
    )
    try:
        return Body(built, name=name)
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None


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
    allowed = list(inspect.signature(fn).parameters)
    unknown = sorted(set(kwargs) - set(allowed))
    if unknown:
        allowed_text = ", ".join(allowed) if allowed else "no parameters besides 'preset'"
        raise ValueError(f"{where}: unknown key {unknown[0]!r} for preset {preset!r}; allowed: {allowed_text}")
    try:
        return fn(**kwargs)
    except ValueError as exc:
        raise ValueError(f"{where} (preset {preset!r}): {exc}") from None


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
        return PRESETS[source]()
    path = Path(source)
    if not path.exists() and isinstance(source, str) and path.suffix == "":
        raise ValueError(
            f"{source!r} is neither a body file nor a preset; presets: {', '.join(PRESETS)}"
        )
    data = read_toml(path)
    unknown = sorted(set(data) - {"body"})
    if "body" not in data:
        raise ValueError(f"{path}: missing table [body]")
    if unknown:
        raise ValueError(f"{path}: unknown top-level key {unknown[0]!r}; a body file has only [body]")
    try:
        return body_from_table(data["body"], base_dir=path.parent)
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None


#: The mesh files that :func:`body_from_mesh` (and ``tumble inertia``) read directly, by suffix
#: (any case): a solid whose whole surface is one closed triangle mesh.
MESH_SUFFIXES = (".stl", ".obj", ".ply")

#: The length units of a mesh file, as factors to metres (``tumble inertia part.stl --units mm``).
MESH_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254}


def is_mesh_file(source: str | os.PathLike[str]) -> bool:
    """Whether ``source`` names a mesh file (by its suffix, any case: .stl, .obj, .ply).

    Examples
    --------
    >>> from tumble.io.bodyfile import is_mesh_file
    >>> is_mesh_file("parts/bracket.STL"), is_mesh_file("bodies/t_handle.toml"), is_mesh_file("t-handle")
    (True, False, False)
    """
    return Path(source).suffix.lower() in MESH_SUFFIXES


def body_from_mesh(
    path: str | os.PathLike[str],
    *,
    density: float | None = None,
    mass: float | None = None,
    scale: float | None = None,
    units: str | None = None,
) -> Body:
    """A one-part body from a mesh file (STL, OBJ, PLY): a uniform solid, named after the file.

    The same body as a body file with one ``kind = "mesh"`` part, without writing that file.

    Parameters
    ----------
    path : str or os.PathLike
        The mesh file: a closed, consistently wound triangle mesh (see :class:`tumble.Mesh`).
    density, mass : float
        Uniform density (kg/m^3) or total mass (kg), exactly one.
    scale : float, optional
        Factor from file units to metres (e.g. 0.001 for a file in mm).
    units : {"m", "cm", "mm", "in"}, optional
        The file's length unit, instead of ``scale``. Default: metres.

    Raises
    ------
    ValueError
        One line: neither or both of ``density`` and ``mass``, both ``scale`` and ``units``, an
        unknown unit, or a mesh that cannot be read or encloses no volume (open, inconsistently
        wound, inside out), naming the file.

    Examples
    --------
    >>> import pathlib, tempfile, trimesh
    >>> from tumble.io.bodyfile import body_from_mesh
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "brick.stl")
    ...     _ = trimesh.creation.box(extents=(10.0, 20.0, 30.0)).export(path)   # in cm
    ...     body = body_from_mesh(path, mass=12.0, units="cm")
    >>> body.name, body.principal_moments.round(6).tolist()   # m (b^2 + c^2) / 12 and cyclic, ascending
    ('brick', [0.05, 0.1, 0.13])
    """
    given = [k for k, v in (("density", density), ("mass", mass)) if v is not None]
    if len(given) != 1:
        raise ValueError(
            f"{path}: a mesh needs exactly one of density (kg/m^3) or mass (kg), "
            f"got {' and '.join(given) if given else 'neither'}"
        )
    if scale is not None and units is not None:
        raise ValueError(f"{path}: give scale = {scale!r} or units = {units!r}, not both")
    if units is not None:
        if units not in MESH_UNITS:
            raise ValueError(f"{path}: units = {units!r} is unknown; allowed: {', '.join(MESH_UNITS)}")
        scale = MESH_UNITS[units]
    try:
        part = Mesh(mesh=os.fspath(path), scale=1.0 if scale is None else scale, density=density, mass=mass)
    except ValueError as exc:
        message = str(exc)
        raise ValueError(message if os.fspath(path) in message else f"{path}: {message}") from None
    return Body((part,), name=Path(path).stem)
