"""Reading a file the user named: a regular file of bounded size, or one line that says why not.

Re-exported by :mod:`tumble.validation`.
"""

from __future__ import annotations

import json
import os

__all__ = [
    "NoSuchFileError",
    "json_object",
    "read_input_file",
]


class NoSuchFileError(FileNotFoundError, ValueError):
    """A file the user named does not exist: ``PATH: no such file``.

    A ``FileNotFoundError``, what a program catches for a missing file, and a
    ``ValueError``, as every other refusal of a file tumble reads (the command line says it
    in one line and exits with 2). Its text is the message alone (no ``[Errno 2]``).

    Examples
    --------
    >>> from tumble.validation import NoSuchFileError, read_input_file
    >>> try:
    ...     read_input_file("no-such.toml", limit=1024, what="a body file")
    ... except FileNotFoundError as exc:
    ...     print(exc, "/", isinstance(exc, ValueError))
    no-such.toml: no such file / True
    """


def read_input_file(path: str | os.PathLike[str], *, limit: int, what: str, label: str | None = None) -> bytes:
    """The bytes of an input file, refusing anything but a regular file of at most ``limit`` bytes.

    The file is checked with :func:`os.stat` before it is opened, so a FIFO is never opened
    (opening one for reading would wait forever for a writer) and ``/dev/zero`` is never read.
    It is then opened without blocking, checked again on the open descriptor (the path may have
    been replaced meanwhile), and read up to ``limit + 1`` bytes, so a file that grows while it is
    read cannot exhaust memory.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    limit : int
        The largest size allowed, bytes.
    what : str
        What the file is, for the messages, e.g. ``"a body or scenario file (TOML)"``.
    label : str, optional
        How the messages name the file; default the path itself.

    Returns
    -------
    bytes
        The whole content of the file.

    Raises
    ------
    NoSuchFileError
        A ``FileNotFoundError`` (and ``ValueError``): ``PATH: no such file``.
    ValueError
        One line naming the file and the rule: not a regular file (directory, FIFO, socket,
        device), unreadable, or larger than ``limit``.

    Examples
    --------
    >>> import tempfile
    >>> import os
    >>> from tumble.validation import read_input_file
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = os.path.join(folder, "body.toml")
    ...     with open(path, "w") as f:
    ...         _ = f.write("mass = 1.0")
    ...     read_input_file(path, limit=1024, what="a body file")
    b'mass = 1.0'
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     read_input_file(folder, limit=1024, what="a body file", label="bodies/")
    Traceback (most recent call last):
    ...
    ValueError: bodies/: is a directory; a body file must be a regular file
    """
    import stat

    label = os.fspath(path) if label is None else label

    def _refuse(mode: int) -> None:
        if stat.S_ISREG(mode):
            return
        kinds = [(stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
                 (stat.S_ISSOCK, "a socket"), (stat.S_ISCHR, "a character device"),
                 (stat.S_ISBLK, "a block device")]
        kind = next((name for test, name in kinds if test(mode)), "not a regular file")
        raise ValueError(f"{label}: is {kind}; {what} must be a regular file")

    def _size(size: int, how: str) -> None:
        if size > limit:
            raise ValueError(
                f"{label}: {how}; {what} may be at most {limit:,} bytes ({limit / 2**20:g} MiB)"
            )

    try:
        info = os.stat(path)
    except FileNotFoundError:
        raise NoSuchFileError(f"{label}: no such file") from None
    except OSError as exc:
        raise ValueError(f"{label}: cannot be read: {exc.strerror}") from None
    _refuse(info.st_mode)
    _size(info.st_size, f"is {info.st_size:,} bytes")
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        raise ValueError(f"{label}: cannot be read: {exc.strerror}") from None
    with os.fdopen(fd, "rb") as file:
        _refuse(os.fstat(fd).st_mode)  # the path may have been swapped since the stat
        try:
            data = file.read(limit + 1)
        except OSError as exc:
            raise ValueError(f"{label}: cannot be read: {exc.strerror}") from None
    _size(len(data), f"grew past {limit:,} bytes while being read")
    return data


def json_object(raw: bytes, file: str | os.PathLike[str], *, writer: str) -> dict:
    """The JSON object in ``raw``, a result file that ``writer`` wrote (``"tumble fit"``), or one line
    that says how it is damaged and to run ``writer`` again: one home for every result folder's
    reader.

    Examples
    --------
    >>> from tumble.validation import json_object
    >>> json_object(b'{"a": 1}', "fit.json", writer="tumble fit")
    {'a': 1}
    >>> json_object(b'{"a": ', "fit.json", writer="tumble fit")
    Traceback (most recent call last):
    ...
    ValueError: fit.json: damaged: not JSON (Expecting value at line 1, column 7); run tumble fit again
    """
    try:
        record = json.loads(raw.decode("utf-8"))
    except UnicodeDecodeError:
        why = "not UTF-8 text"
    except json.JSONDecodeError as err:
        why = f"not JSON ({err.msg.removesuffix(' at')} at line {err.lineno}, column {err.colno})"
    else:
        if isinstance(record, dict):
            return record
        why = f"a JSON {type(record).__name__}, not the object {writer} writes"
    raise ValueError(f"{os.fspath(file)}: damaged: {why}; run {writer} again")
