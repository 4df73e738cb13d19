"""The examples that ship inside the package: scenario, control, body and sweep files, a mesh,
gyroscope recordings, a throwing device and its throws, and a notebook.

They live in ``tumble/examples/`` (package data, so a ``pip install`` has them too; the
repository's ``examples/`` is a link to the same folder). Scenario files sit at the top and name
their bodies by relative paths (``body = "bodies/t_handle.toml"``), and body files name their
meshes the same way (``mesh = "meshes/torus.stl"``), so a copy of the whole tree runs as it is.

Examples
--------
>>> from tumble.io.examples import list_examples
>>> [e.path for e in list_examples() if e.name == "seed_flip"]
['seed_flip.toml']
"""

from __future__ import annotations

import json
import os
import re
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from ..validation import NoSuchFileError, read_input_file
from .atomic import atomic_folder
from .output import check_parent

__all__ = ["Example", "copy_examples", "example_hint", "list_examples"]

#: The folder of the body files, relative to the examples' root; every other ``.toml`` at the
#: root is a scenario.
BODIES = "bodies"
#: The folder of the sweep files (``tumble sweep``).
SWEEPS = "sweeps"
#: The folder of the closed-loop control scenarios (``tumble simulate``; :mod:`tumble.io.controlfile`).
CONTROL = "control"
#: The folder of the throwing devices (``tumble calibrate``, ``tumble tensor``; :mod:`tumble.io.devicefile`).
DEVICES = "devices"
#: The folder of the meshes that body files name (``mesh = "meshes/torus.stl"``).
MESHES = f"{BODIES}/meshes"
#: The folder of the gyroscope recordings (``tumble fit``).
DATA = "data"
#: The folder of the throws of the device of :data:`DEVICES` (``tumble calibrate``, ``tumble tensor``;
#: :mod:`tumble.io.throwfile`), made by the repository's ``tools/make_example_throws.py``.
THROWS = "throws"
#: The folder of the Jupyter notebooks.
NOTEBOOKS = "notebooks"
#: The kind of a ``.toml`` file by its folder (every other ``.toml`` at the root is a scenario).
_TOML_KINDS = {"": "scenario", BODIES: "body", SWEEPS: "sweep", CONTROL: "control", DEVICES: "device"}
#: The kind of any other file by its folder.
_FILE_KINDS = {MESHES: "mesh", DATA: "data", THROWS: "throw", NOTEBOOKS: "notebook"}


@dataclass(frozen=True)
class Example:
    """One example file.

    Attributes
    ----------
    name : str
        The file's stem, e.g. ``"seed_flip"``.
    path : str
        Its path relative to the examples' root, with ``/``, e.g. ``"bodies/t_handle.toml"``.
    kind : str
        ``"scenario"`` (for ``tumble simulate``, ``plot``, ``view``), ``"control"`` (a closed-loop
        scenario, for ``tumble simulate``), ``"body"`` (for ``tumble inertia``), ``"sweep"`` (for
        ``tumble sweep``), ``"device"`` (a throwing device, for ``tumble calibrate`` and
        ``tumble tensor``), ``"mesh"`` (a triangle mesh that a body file names), ``"data"`` (a
        gyroscope recording, for ``tumble fit``), ``"throw"`` (a throw of the device, for ``tumble
        calibrate`` and ``tumble tensor``), ``"notebook"`` (Jupyter) or ``"file"`` (anything else in
        the tree).
    description : str
        One line: a TOML file's first comment line, a recording's first sentence of its comment
        block, a notebook's title, the body files that use a mesh; the name if there is none.

    Examples
    --------
    >>> from tumble.io.examples import list_examples
    >>> [(e.path, e.kind) for e in list_examples() if e.name == "t_handle"]
    [('bodies/t_handle.toml', 'body')]
    """

    name: str
    path: str
    kind: str
    description: str


def _root():
    """The examples' root folder as an importlib.resources Traversable."""
    return resources.files("tumble").joinpath("examples")


def _walk(folder, prefix: str = ""):
    """Yield ``(relative path, Traversable)`` for every data file below ``folder``, sorted."""
    for entry in sorted(folder.iterdir(), key=lambda e: e.name):
        if entry.name.startswith((".", "__pycache__")):
            continue
        rel = f"{prefix}{entry.name}"
        if entry.is_dir():
            yield from _walk(entry, f"{rel}/")
        else:
            yield rel, entry


def _description(text: str, name: str) -> str:
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("#"):
            described = line.lstrip("#").strip()
            if described:
                return described
        elif line:
            break  # the comment block, if any, is over
    return name.replace("_", " ")


def _first_sentence(text: str, name: str) -> str:
    """The first sentence of a recording's leading ``#`` comment block."""
    lines = []
    for line in text.splitlines():
        if not line.startswith("#"):
            break
        lines.append(line.lstrip("#").strip())
    block = " ".join(" ".join(lines).split())
    match = re.match(r"(.+?[.!?])(\s|$)", block)
    return match.group(1) if match else block or name.replace("_", " ")


def _notebook_title(text: str, name: str) -> str:
    """A notebook's first Markdown heading."""
    try:
        cells = json.loads(text).get("cells", [])
    except (ValueError, AttributeError):
        cells = []
    for cell in cells:
        if cell.get("cell_type") == "markdown":
            source = "".join(cell.get("source", []))
            for line in source.splitlines():
                if line.startswith("#"):
                    return line.lstrip("#").strip()
    return name.replace("_", " ")


def _mesh_users(rel: str, tomls: dict[str, str]) -> str:
    """Which body files name the mesh ``rel`` (by its path relative to theirs)."""
    suffix = rel.rpartition(".")[2].upper()
    users = [path for path, text in tomls.items()
             if path.startswith(f"{BODIES}/") and f'"{rel[len(BODIES) + 1:]}"' in text]
    return f"A triangle mesh ({suffix}) " + (f"that {', '.join(users)} names" if users else "for a body file")


def list_examples() -> list[Example]:
    """Every file that ships with tumble's examples (all that :func:`copy_examples` copies), scenarios first.

    Returns
    -------
    list of Example
        Each with its name, relative path, kind (``"scenario"``, ``"control"``, ``"body"``,
        ``"sweep"``, ``"device"``, ``"mesh"``, ``"data"``, ``"throw"``, ``"notebook"`` or ``"file"``) and one-line
        description.

    Examples
    --------
    >>> from tumble.io.examples import list_examples
    >>> found = list_examples()
    >>> found[0].kind, sorted({e.kind for e in found})  # scenarios first
    ('scenario', ['body', 'control', 'data', 'device', 'mesh', 'notebook', 'scenario', 'sweep', 'throw'])
    >>> [e.description for e in found if e.kind == "mesh"]
    ['A triangle mesh (STL) that bodies/every_part.toml names']
    """
    files = list(_walk(_root()))
    tomls = {rel: entry.read_text(encoding="utf-8") for rel, entry in files if rel.endswith(".toml")}
    found = []
    for rel, entry in files:
        folder, _, filename = rel.rpartition("/")
        name = filename.rpartition(".")[0] or filename
        if rel in tomls and folder in _TOML_KINDS:
            kind, description = _TOML_KINDS[folder], _description(tomls[rel], name)
        elif folder == MESHES:
            kind, description = "mesh", _mesh_users(rel, tomls)
        elif folder in (DATA, THROWS):
            text = entry.read_text(encoding="utf-8", errors="replace")
            kind, description = _FILE_KINDS[folder], _first_sentence(text, name)
        elif folder == NOTEBOOKS and filename.endswith(".ipynb"):
            kind, description = "notebook", _notebook_title(entry.read_text(encoding="utf-8"), name)
        else:
            kind, description = _FILE_KINDS.get(folder, "file"), name.replace("_", " ")
        found.append(Example(name, rel, kind, description))
    return sorted(found, key=lambda e: (e.kind != "scenario", e.path))


def copy_examples(dest: str | os.PathLike[str]) -> list[Path]:
    """Copy the whole examples tree (every file :func:`list_examples` lists) into ``dest``, ready to run.

    A new ``dest`` is built in a temporary folder beside it and renamed into place, so it appears
    whole or not at all. An existing folder ``dest`` is filled, but no file in it is ever
    overwritten: every conflict is looked for before anything is written.

    Parameters
    ----------
    dest : str or os.PathLike
        The folder to create (its parents are created too), or an existing folder to fill.

    Returns
    -------
    list of pathlib.Path
        The files written, under ``dest``, sorted.

    Raises
    ------
    ValueError
        ``dest`` exists and is not a folder, or a file the examples would write already exists
        there (the message names it); nothing is written then.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from tumble.io.examples import copy_examples, list_examples
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     written = copy_examples(Path(folder) / "examples")
    ...     print(Path(folder, "examples", "bodies", "t_handle.toml") in written, len(written) == len(list_examples()))
    True True
    """
    if not os.fspath(dest).strip():  # Path("") is the current folder: --copy "" listed instead, or would copy there
        raise ValueError(f"--copy = {os.fspath(dest)!r} names no folder; give a folder's name, e.g. --copy examples")
    dest = Path(dest)
    files = list(_walk(_root()))
    check_parent(dest, "--copy")  # a file on the way: it was "File exists", exit 1 (a walkthrough)
    if dest.exists() or dest.is_symlink():
        if not dest.is_dir():
            raise ValueError(f"{dest}: exists and is not a folder; give a new or existing folder")
        for rel, _ in files:
            target = dest / rel
            if target.exists() or target.is_symlink():
                raise ValueError(f"{target}: already exists; the examples are never copied over a file: give a new folder")
        written = []
        for rel, entry in files:
            target = dest / rel
            target.parent.mkdir(parents=True, exist_ok=True)
            with open(target, "xb") as out:  # "x": fail rather than overwrite, even in a race
                out.write(entry.read_bytes())
            written.append(target)
        return sorted(written)
    with atomic_folder(dest, "nothing was copied") as stage:
        for rel, entry in files:
            target = stage / rel
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(entry.read_bytes())
    return sorted(dest / rel for rel, _ in files)


def example_hint(message: str) -> str:
    """The hint for an error about a missing ``examples/...`` path that names a packaged example.

    The README, ``--help`` and the guides run commands on ``examples/...`` paths, which exist in a
    checkout; an installed wheel has them inside the package, copied out by ``tumble examples
    --copy DIR``. Returns ``""`` when the message names no missing packaged example.

    Parameters
    ----------
    message : str
        An error message starting with the path it is about (``"PATH: no such file"``).

    Examples
    --------
    >>> import os, tempfile
    >>> from tumble.io.examples import example_hint
    >>> here = os.getcwd()
    >>> with tempfile.TemporaryDirectory() as folder:   # a folder without the checkout's examples/
    ...     os.chdir(folder)
    ...     hint = example_hint("examples/data/racquet_tosses.csv: no such file")
    ...     os.chdir(here)
    >>> hint
    "; it is one of tumble's examples: 'tumble examples --copy examples' copies them here"
    >>> example_hint("my_tosses.csv: no such file")
    ''
    """
    if _HINT in message:  # said already (by the reader, :func:`_read_input`)
        return ""
    path = message.split(": ", 1)[0].strip("'\"")
    parts = Path(path).parts
    if len(parts) < 2 or parts[0] != "examples" or Path(path).exists():
        return ""
    if not _root().joinpath(*parts[1:]).is_file():
        return ""
    return f"; it is one of tumble's examples: {_HINT}"


#: What :func:`example_hint` says to do.
_HINT = "'tumble examples --copy examples' copies them here"


def _read_input(path: str | os.PathLike[str], *, limit: int, what: str, label: str | None = None) -> bytes:
    """:func:`tumble.validation.read_input_file`, whose "no such file" says how to get an example.

    The readers of the files a user names (body, scenario, sweep and control files, recordings)
    read through this, so that ``read_recording("examples/data/racquet_tosses.csv")`` copied from a
    guide into a folder without the examples says ``tumble examples --copy examples``.
    """
    try:
        return read_input_file(path, limit=limit, what=what, label=label)
    except ValueError as exc:
        message = str(exc)
        hint = example_hint(message) if message.endswith(": no such file") else ""
        if not hint:
            raise
        # a missing file stays a FileNotFoundError
        raise (NoSuchFileError if isinstance(exc, FileNotFoundError) else ValueError)(f"{message}{hint}") from None
