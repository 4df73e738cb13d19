"""Write files so that a failure never leaves one half-written."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

__all__ = ["atomic_path", "atomic_write_bytes", "atomic_write_text"]


@contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary path beside ``path`` (same suffix, so writers infer the format); on
    success rename it into place, on any failure delete it. Nothing is ever half-written.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from tumble.io.atomic import atomic_path
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     target = pathlib.Path(folder, "out.txt")
    ...     try:
    ...         with atomic_path(target) as tmp:
    ...             _ = tmp.write_text("half")
    ...             raise RuntimeError("the writer failed")
    ...     except RuntimeError:
    ...         pass
    ...     print(target.exists(), sorted(p.name for p in pathlib.Path(folder).iterdir()))   # nothing left behind
    False []
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=f".tmp{path.suffix}", dir=path.parent)
    os.close(fd)
    tmp = Path(tmp)
    try:
        yield tmp
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes 0600; give the usual permissions
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> Path:
    """Write ``data`` to a temporary file beside ``path``, then rename it into place.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from tumble.io.atomic import atomic_write_bytes
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = atomic_write_bytes(pathlib.Path(folder, "sub", "data.bin"), b"\\x00\\x01")
    ...     print(path.name, path.read_bytes())
    data.bin b'\\x00\\x01'
    """
    with atomic_path(path) as tmp:
        tmp.write_bytes(data)
    return Path(path)


def atomic_write_text(path: str | os.PathLike[str], text: str) -> Path:
    """Text version of :func:`atomic_write_bytes` (UTF-8).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from tumble.io.atomic import atomic_write_text
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     print(atomic_write_text(pathlib.Path(folder, "note.txt"), "I1 <= I2 <= I3").read_text())
    I1 <= I2 <= I3
    """
    return atomic_write_bytes(path, text.encode("utf-8"))


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask
