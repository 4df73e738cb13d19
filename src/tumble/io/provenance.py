"""Where a result came from: versions, the command, the inputs' content hashes, the time.

Written into ``summary.json`` (key ``provenance``) and into the NPZ (a JSON string under the
same name), so a file found later can be traced to the code and the inputs that made it.
"""

from __future__ import annotations

import datetime
import hashlib
import os
import platform
import shlex
from collections.abc import Iterable, Sequence
from pathlib import Path

__all__ = ["file_sha256", "input_sha256", "provenance"]


def file_sha256(path: str | os.PathLike[str]) -> str:
    """SHA-256 of a file's bytes, hex.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from tumble.io.provenance import file_sha256
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "empty")
    ...     path.touch()
    ...     print(file_sha256(path))   # the SHA-256 of no bytes
    e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855
    """
    digest = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def input_sha256(path: str | os.PathLike[str]) -> str:
    """SHA-256 of an input as ``tumble fit`` records it: a file's bytes (:func:`file_sha256`), or
    of a folder (phyphox's export) its files' names and hashes, in name order, and
    ``meta/time.csv``'s.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from tumble.io.provenance import file_sha256, input_sha256
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "Raw Data.csv")
    ...     _ = path.write_text("t,x,y,z\\n")
    ...     same = input_sha256(path) == file_sha256(path)
    ...     of_folder = input_sha256(folder)
    ...     _ = path.write_text("t,x,y,z\\n0,1,2,3\\n")
    ...     changed = input_sha256(folder) != of_folder
    >>> same, changed
    (True, True)
    """
    if not os.path.isdir(path):
        return file_sha256(path)
    h = hashlib.sha256()
    for name in sorted(os.listdir(path)):
        full = os.path.join(path, name)
        if os.path.isfile(full):
            h.update(name.encode() + b"\0" + file_sha256(full).encode())
    meta = os.path.join(path, "meta", "time.csv")
    if os.path.isfile(meta):
        h.update(b"meta/time.csv\0" + file_sha256(meta).encode())
    return h.hexdigest()


def provenance(argv: Sequence[str] | None = None, inputs: Iterable[tuple[str, str]] = ()) -> dict:
    """The provenance record of a run.

    Parameters
    ----------
    argv : list of str, optional
        The command's arguments after ``tumble`` (None from the Python API).
    inputs : iterable of (str, str)
        ``(path, sha256)`` of every input file read (scenario, body file).

    Returns
    -------
    dict
        ``tumble``, ``numpy``, ``scipy``, ``python`` versions, ``platform``, ``command`` (the
        command line, or None), ``inputs`` (path -> sha256) and ``created`` (UTC, ISO 8601).

    Examples
    --------
    >>> from tumble.io.provenance import provenance
    >>> record = provenance(["simulate", "spin.toml"], inputs=[("spin.toml", "ab12")])
    >>> record["command"], record["inputs"], sorted(record)[:3]   # doctest: +ELLIPSIS
    (..., {'spin.toml': 'ab12'}, ['command', 'created', 'inputs'])
    """
    import numpy
    import scipy

    from .._version import __version__

    return {
        "tumble": __version__,
        "numpy": numpy.__version__,
        "scipy": scipy.__version__,
        "python": platform.python_version(),
        "platform": platform.platform(terse=True),
        "command": None if argv is None else shlex.join(["tumble", *map(str, argv)]),
        "inputs": {str(Path(p)): h for p, h in inputs},
        "created": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
    }
