"""Write files so that a failure never leaves one half-written."""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

__all__ = ["atomic_folder", "atomic_path", "atomic_write_bytes", "atomic_write_text", "in_place", "staging_folder"]


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
    with _named(path):  # mkstemp's error names the temporary file, which the user never asked for
        fd, name = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=f".tmp{path.suffix}", dir=path.parent)
    os.close(fd)
    tmp = Path(name)
    try:
        with _named(path, tmp):
            yield tmp
            os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes 0600; give the usual permissions
            os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


@contextmanager
def atomic_folder(path: str | os.PathLike[str], nothing: str = "nothing was written") -> Iterator[Path]:
    """Yield an empty folder beside ``path`` to write into; on success rename it to ``path`` (new,
    or an empty folder), on any failure delete it. The folder appears whole or not at all.

    A ``path`` that could not be created (a folder that appeared meanwhile and is not empty) is a
    ValueError naming it and ending in ``nothing``; a write that fails names its file in place
    (:func:`in_place`).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from tumble.io.atomic import atomic_folder
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     target = pathlib.Path(folder, "set")
    ...     with atomic_folder(target) as stage:
    ...         _ = (stage / "a.txt").write_text("1")
    ...         print(target.exists())   # nothing in place before the end
    ...     print(sorted(p.name for p in pathlib.Path(folder).iterdir()), (target / "a.txt").read_text())
    False
    ['set'] 1
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with staging_folder(path, f".{path.name}.", ".tmp") as stage:
        yield stage
        os.chmod(stage, 0o777 & ~_umask())  # mkdtemp makes 0700; give the usual permissions
        try:
            os.rename(stage, path)  # atomic; onto an empty folder too; fails onto a folder with files
        except OSError as exc:
            raise ValueError(f"{path}: could not be created ({exc.strerror}); {nothing}") from None


@contextmanager
def staging_folder(path: Path, prefix: str, suffix: str = "") -> Iterator[Path]:
    """A new empty folder beside ``path`` (``prefix``, random letters, ``suffix``; mode 0700),
    removed when the block ends, whatever happens in it: where a staged output is written before
    it is moved into place. An OSError in the block, or in making the folder, names the file as
    the user will find it in ``path`` (:func:`in_place`), not in the staging folder.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from tumble.io.atomic import staging_folder
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     target = pathlib.Path(folder, "run")
    ...     try:
    ...         with staging_folder(target, ".run.tmp-") as stage:
    ...             _ = (stage / "omega.csv").write_text("t,w1")
    ...             open(stage / "sub" / "x.csv")   # no such folder
    ...     except FileNotFoundError as error:
    ...         print(error.filename == str(target / "sub" / "x.csv"), list(pathlib.Path(folder).iterdir()))
    True []
    """
    with _named(path):
        stage = Path(tempfile.mkdtemp(prefix=prefix, suffix=suffix, dir=path.parent))
    try:
        with _named(path, stage):
            yield stage
    finally:
        shutil.rmtree(stage, ignore_errors=True)


@contextmanager
def _named(final: Path, temporary: Path | None = None) -> Iterator[None]:
    """Re-raise an OSError of the block as :func:`in_place` names it; ``temporary`` None: the
    entry the block tried to make (mkdtemp's and mkstemp's errors name it)."""
    try:
        yield
    except OSError as exc:
        tried = Path(os.fsdecode(exc.filename)) if temporary is None and exc.filename else temporary
        named = in_place(exc, tried if tried is not None else final, final)
        if named is exc:
            raise
        raise named from exc


def in_place(exc: OSError, temporary: Path, final: Path) -> OSError:
    """``exc`` naming the file the user asked for where it names ``temporary`` (or a file in it):
    an error in a staged write should say ``run/omega.png``, not ``.run.tmp-x1y2/omega.png``.
    An error that names no file (a full disk fails in ``write()``, which names none) names
    ``final``; one that names another file, and a broken pipe, are returned as they are.

    Examples
    --------
    >>> import errno
    >>> from pathlib import Path
    >>> from tumble.io.atomic import in_place
    >>> exc = OSError(errno.ENOSPC, "No space left on device", "/data/.run.tmp-x1y2/omega.png")
    >>> in_place(exc, Path("/data/.run.tmp-x1y2"), Path("/data/run")).filename
    '/data/run/omega.png'
    """
    if exc.filename is None:  # a full disk fails in write(), which names no file: name the output
        if isinstance(exc, BrokenPipeError) or exc.errno is None:
            return exc
        return type(exc)(exc.errno, exc.strerror or str(exc), str(final))
    named = Path(os.fsdecode(exc.filename))
    if named == temporary:
        where = final
    elif named.is_relative_to(temporary):
        where = final / named.relative_to(temporary)
    else:
        return exc
    return type(exc)(exc.errno, exc.strerror, str(where)) if exc.errno is not None else exc


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
