"""One exclusive lock between processes, the same on POSIX and on Windows.

POSIX locks with ``fcntl.flock``; Windows, which has no ``fcntl``, with ``msvcrt.locking`` on
the file's first byte. Both locks belong to the open file and end when it is closed (a process
that dies releases them). The resume folder of a sweep (:mod:`tumble.io.resume`) and the output
folders (:mod:`tumble.io.output`) lock through this module only, so that importing them needs
neither ``fcntl`` nor ``msvcrt`` to be a particular one.

Written by hand: the standard library has the two calls but no portable lock.
"""

from __future__ import annotations

import contextlib
import errno
import os
import time
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

__all__ = ["lock_fd", "locked_folder"]

#: The file a folder is locked through where a folder cannot be opened (Windows): it stays.
FOLDER_LOCK = ".tumble-lock"


def _fcntl() -> ModuleType | None:
    """``fcntl`` where it exists (POSIX), else None (Windows: ``msvcrt`` instead)."""
    try:
        import fcntl
    except ImportError:
        return None
    return fcntl


def lock_fd(fd: int, *, wait: bool = True) -> None:
    """Lock the open file ``fd`` exclusively (released when ``fd`` is closed).

    Parameters
    ----------
    fd : int
        An open file descriptor (a folder's on POSIX; a regular file's everywhere).
    wait : bool, default True
        Wait for another process's lock to end; with False, raise at once.

    Raises
    ------
    BlockingIOError
        ``wait=False`` and another open file holds the lock.

    Examples
    --------
    >>> from tumble.io.lock import lock_fd
    >>> import os, tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     first = os.open(os.path.join(folder, "lock"), os.O_RDWR | os.O_CREAT)
    ...     second = os.open(os.path.join(folder, "lock"), os.O_RDWR)
    ...     lock_fd(first)
    ...     try:
    ...         lock_fd(second, wait=False)
    ...     except BlockingIOError:
    ...         print("held by the first")
    ...     os.close(first), os.close(second)
    held by the first
    (None, None)
    """
    fcntl = _fcntl()
    if fcntl is not None:
        fcntl.flock(fd, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
        return
    import msvcrt  # Windows

    # msvcrt locks bytes from the current position (the first byte here); its LK_LOCK gives up
    # after ten seconds, so waiting is a loop of LK_NBLCK tries: no end, as flock's has none
    while True:
        os.lseek(fd, 0, os.SEEK_SET)
        try:
            msvcrt.locking(fd, msvcrt.LK_NBLCK, 1)  # type: ignore[attr-defined]  # Windows only
            return
        except OSError as exc:
            if not wait:
                raise BlockingIOError(errno.EWOULDBLOCK, "the file is locked by another process") from exc
        time.sleep(0.1)


@contextlib.contextmanager
def locked_folder(folder: str | os.PathLike[str]) -> Iterator[None]:
    """Hold an exclusive lock on ``folder`` for the ``with`` block, waiting for it if need be.

    On POSIX the folder itself is locked, and nothing is left behind; Windows cannot open a
    folder, so there the lock is on a file ``.tumble-lock`` in it, which stays.

    Examples
    --------
    >>> import tempfile
    >>> from tumble.io.lock import locked_folder
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     with locked_folder(folder):
    ...         print("only this process writes here now")
    only this process writes here now
    """
    if _fcntl() is not None:
        fd = os.open(folder, os.O_RDONLY)
    else:
        fd = os.open(Path(folder) / FOLDER_LOCK, os.O_RDWR | os.O_CREAT, 0o666)
    try:
        lock_fd(fd)
        yield
    finally:
        os.close(fd)  # closing releases the lock
