"""A command's output as a set: it appears whole or not at all.

A command that writes several files (``tumble simulate``, ``plot``, ``demo``) writes them into
a temporary folder beside ``--out`` and, once everything is written, swaps that folder into
place under an exclusive lock on the parent folder. So

- a failure, a full disk, Ctrl-C or SIGTERM midway leaves the previous output untouched and no
  temporary folder behind (the CLI turns SIGTERM into an exception so this cleanup runs);
- two runs into the same ``--out`` at once each swap in a whole folder: the last one wins,
  never a mix;
- the output path is checked before anything is computed (:func:`check_output_dir`,
  :func:`check_output_file`).

An existing folder is updated, not emptied: files that do not belong to the command (the glob
patterns ``owns``, e.g. ``omega.*`` for ``tumble plot``) are carried over into the new folder as
hard links, so ``tumble plot --out run`` beside ``tumble simulate --out run`` keeps both; the
command's own files from an earlier run are replaced as a set (a stale ``polhode.svg`` never
sits beside a new ``polhode.png``). A folder holding sub-folders or links is refused (``--out .``
in a project, say): only folders of plain files are replaced. A SIGKILL (which no program can
catch) may leave a ``.NAME.tmp-*`` folder beside the output.

Written by hand: the standard library has the pieces (``os.rename``, a lock (:mod:`tumble.io.lock`),
``tempfile``) but no "replace a folder as a whole" operation.
"""

from __future__ import annotations

import contextlib
import fnmatch
import os
import shutil
import tempfile
from collections.abc import Iterable, Iterator
from pathlib import Path

from .atomic import _umask, staging_folder
from .lock import locked_folder

__all__ = ["FIGURE_DPI", "check_output_dir", "check_output_file", "check_parent", "output_dir"]

#: Resolution of the raster figures the commands write, dots per inch.
FIGURE_DPI = 110


def _refuse(path: Path, why: str, option: str = "--out") -> ValueError:
    return ValueError(f"{option} {path}: {why}")


def check_parent(path: Path, option: str = "--out") -> None:
    """The nearest existing ancestor of ``path`` must be a writable folder: a file on the way, a
    folder that cannot be written or a broken link is refused, the message naming ``option``.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from tumble.io.output import check_parent
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     (Path(folder) / "afile").write_text("x")
    ...     try:
    ...         check_parent(Path(folder) / "afile" / "sub", "--copy")
    ...     except ValueError as exc:
    ...         print(str(exc).replace(folder, "F"))
    1
    --copy F/afile/sub: F/afile is a file, not a folder
    """
    for parent in path.parents:
        if parent.exists():
            if not parent.is_dir():
                raise _refuse(path, f"{parent} is a file, not a folder", option)
            if not os.access(parent, os.W_OK | os.X_OK):
                raise _refuse(path, f"cannot write in {parent} (permission denied)", option)
            try:  # a name the file system cannot hold failed after the run ("File name too long", exit 1)
                longest = os.pathconf(parent, "PC_NAME_MAX")
            except (OSError, ValueError):
                longest = 255
            # the staging names add a prefix and a suffix of ~16 characters (output_dir, atomic_path)
            if (long := next((n for n in path.relative_to(parent).parts if len(os.fsencode(n)) + 16 > longest), None)):
                raise _refuse(path, f"the name {long[:40]!r}... is {len(os.fsencode(long))} bytes, more than this file "
                              f"system's {longest} (less {16} for the files written beside it)", option)
            return
        if parent.is_symlink():  # a dangling link on the way
            raise _refuse(path, f"{parent} is a broken symbolic link", option)


def check_output_dir(path: str | os.PathLike[str]) -> Path:
    """Check before computing that ``path`` can receive a command's output folder.

    Allowed: a path that does not exist yet (its parents are created) or a folder of plain
    files. Raises ``ValueError`` naming the path and the rule.

    Examples
    --------
    >>> from pathlib import Path
    >>> from tumble.io.output import check_output_dir
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     print(check_output_dir(Path(folder) / "run").name)  # new: fine
    run
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = (Path(folder) / "taken").write_text("x")
    ...     check_output_dir(Path(folder) / "taken")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: --out ...taken: exists and is not a folder
    """
    path = Path(path)
    if Path(os.path.abspath(path)).name == "" or path.name in ("", ".", ".."):  # "/", ".", "x/..": no name to write under
        raise _refuse(path, "does not name a folder of its own (it is the root or ends in '.' or '..'); give a new folder's name")
    check_parent(path)  # first: a name too long for the file system fails path.exists() itself
    if path.exists() or path.is_symlink():
        if path.is_symlink() or not path.is_dir():
            raise _refuse(path, "exists and is not a folder" if not path.is_dir() else "is a symbolic link; give the folder itself")
        if not os.access(path, os.W_OK | os.X_OK):  # the swap renames it, which needs its write permission
            raise _refuse(path, "is a folder this user cannot write to (its permissions); give another folder")
        _check_plain(path)
    return path


def _check_plain(path: Path) -> None:
    odd = next((e for e in sorted(path.iterdir()) if e.is_symlink() or not e.is_file()), None)
    if odd is not None:
        raise _refuse(path, f"holds {odd.name!r}, not a plain file; tumble updates folders of plain files only: "
                      "give a new or empty folder")


def check_output_file(path: str | os.PathLike[str], suffix: str | tuple[str, ...]) -> Path:
    """Check before computing that the single file ``path`` (with ``suffix``, or one of the
    suffixes of a tuple) can be written.

    Examples
    --------
    >>> from tumble.io.output import check_output_file
    >>> check_output_file("run/figure.png", ".png").name
    'figure.png'
    >>> check_output_file("figure.svg", ".png")
    Traceback (most recent call last):
    ...
    ValueError: --out figure.svg: the output is written as one .png file; give a name ending in .png
    >>> check_output_file("map.pdf", (".png", ".svg"))
    Traceback (most recent call last):
    ...
    ValueError: --out map.pdf: the output is written as one .png or .svg file; give a name ending in .png or .svg
    """
    path = Path(path)
    allowed = (suffix,) if isinstance(suffix, str) else suffix
    if path.suffix.lower() not in allowed:
        names = " or ".join(allowed)
        raise _refuse(path, f"the output is written as one {names} file; give a name ending in {names}")
    check_parent(path)  # first: a name too long for the file system fails path.is_dir() itself
    if path.is_dir():
        raise _refuse(path, "is a folder; give a file name")
    return path


@contextlib.contextmanager
def output_dir(path: str | os.PathLike[str], owns: Iterable[str] = ()) -> Iterator[Path]:
    """Yield an empty staging folder; on success swap it in as ``path``, on failure delete it.

    Parameters
    ----------
    path : str or Path
        The output folder (checked again here with :func:`check_output_dir`).
    owns : iterable of str
        Glob patterns of the files that belong to the command: an earlier run's files that
        match are dropped, all others in the folder are kept.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from tumble.io.output import output_dir
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     out = Path(folder) / "run"
    ...     with output_dir(out) as stage:
    ...         _ = (stage / "summary.json").write_text("{}")
    ...         print(out.exists())  # nothing in place before the end
    ...     print(sorted(p.name for p in out.iterdir()))
    False
    ['summary.json']
    """
    path = Path(path).absolute()
    check_output_dir(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with staging_folder(path, f".{path.name}.tmp-") as stage:
        yield stage
        os.chmod(stage, 0o777 & ~_umask())  # mkdtemp makes 0700; give the usual permissions
        with locked_folder(path.parent):
            _swap_in(stage, path, tuple(owns))


def _swap_in(stage: Path, path: Path, owns: tuple[str, ...]) -> None:
    """Put ``stage`` in place of ``path``, carrying over the files the command does not own."""
    if not path.exists():
        os.rename(stage, path)
        return
    if not path.is_dir():
        raise _refuse(path, "was replaced by a file meanwhile; nothing written")
    _check_plain(path)  # again, under the lock
    for entry in path.iterdir():
        if not any(fnmatch.fnmatch(entry.name, pattern) for pattern in owns) and not (stage / entry.name).exists():
            try:
                os.link(entry, stage / entry.name)
            except OSError:  # a file system without hard links
                shutil.copy2(entry, stage / entry.name)
    mode = path.stat().st_mode & 0o7777  # given to the new folder once in place: a stage without write
    # permission could not be removed after a failed swap (a read-only --out left .run.tmp-* folders behind)
    old = Path(tempfile.mkdtemp(prefix=f".{path.name}.old-", dir=path.parent))
    try:
        os.rename(path, old / "previous")
    except BaseException:
        os.rmdir(old)
        raise
    try:
        os.rename(stage, path)
    except BaseException:
        os.rename(old / "previous", path)  # put the previous output back
        os.rmdir(old)
        raise
    os.chmod(path, mode)
    shutil.rmtree(old, ignore_errors=True)
