"""The resume store of a sweep: its finished chunks in ``DIR.resume/``, checked before reuse.

``tumble sweep SWEEP.toml --out DIR`` keeps each finished chunk in ``DIR.resume/`` so that a
run after an interruption computes only the missing ones (:mod:`tumble.commands.sweep`). What is
taken back must be exactly what this sweep would compute, so the folder is guarded four ways:

- **one run at a time**: a run holds an exclusive lock (:func:`tumble.io.lock.lock_fd`: ``fcntl.flock``, or ``msvcrt.locking`` on Windows) on ``DIR.resume/lock``
  from start to end; a second run into the same ``--out`` is refused in one line while the
  first runs (it never mixes its chunks with the first's, nor deletes the folder under it);
- **the sweep's fingerprint** (``fingerprint.json``): everything that changes a result (the
  content hashes of the sweep file, the body file and the mesh files, the settings of the run,
  the chunk size, the versions of tumble, numpy and scipy). A folder holding another sweep's
  chunks is emptied first, with a warning; nothing of it is reused;
- **each chunk records what it holds**: the cases ``start`` to ``stop - 1``, the fingerprint's
  hash and a SHA-256 of its arrays. A chunk that cannot be read, belongs to another sweep or
  other cases, holds another number of rows or fails its checksum (a copied, cut or truncated
  file) is named in a warning line, deleted and computed again;
- **no links**: a ``DIR.resume`` that is a symbolic link (or not a folder) is refused in one
  line, so nothing outside the output's folder is ever written or deleted.

The folder is removed, under the lock, once the output is in place. Written by hand: the
standard library has the pieces (``fcntl.flock``/``msvcrt.locking``, ``hashlib``) but no such store.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np

from .atomic import atomic_path, atomic_write_text
from .lock import lock_fd

__all__ = ["ChunkFolder", "ResumeWarning", "chunk_checksum"]

#: The lock file inside the resume folder.
LOCK = "lock"
#: The fingerprint of the sweep whose chunks the folder holds.
MARK = "fingerprint.json"

#: Open flags POSIX has and Windows lacks (a symbolic link is refused; the lock is not inherited).
_NO_FOLLOW = getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)


class ResumeWarning(UserWarning):
    """A resume folder's chunk (or whole content) was not reused: it is computed again.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.io.resume import ChunkFolder
    >>> import tempfile, warnings
    >>> with tempfile.TemporaryDirectory() as folder, warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     old = ChunkFolder(f"{folder}/out.resume", {"sweep": 1}, cases=2, chunk=2)
    ...     old.save(0, {"case": np.arange(2)})
    ...     old.close()
    ...     new = ChunkFolder(f"{folder}/out.resume", {"sweep": 2}, cases=2, chunk=2)  # another sweep
    ...     new.close()
    >>> [w.category.__name__ for w in caught], new.has(0)
    (['ResumeWarning'], False)
    """


def _warn(message: str) -> None:
    warnings.warn(message, ResumeWarning, stacklevel=3)


def chunk_checksum(columns: dict) -> str:
    """SHA-256 (hex) of a chunk's columns: names, dtypes, shapes and bytes, in order.

    Examples
    --------
    >>> from tumble.io.resume import chunk_checksum
    >>> import numpy as np
    >>> a = chunk_checksum({"case": np.arange(3)})
    >>> a == chunk_checksum({"case": np.arange(3)}), a == chunk_checksum({"case": np.arange(1, 4)})
    (True, False)
    """
    digest = hashlib.sha256()
    for name, values in columns.items():
        array = np.ascontiguousarray(values)
        digest.update(json.dumps([str(name), array.dtype.str, list(array.shape)]).encode("utf-8"))
        digest.update(array.tobytes())
    return digest.hexdigest()


class _BadChunk(Exception):
    """Why a stored chunk cannot be reused."""


class ChunkFolder:
    """Finished chunks in a folder (``chunk-000012.npz``) with the fingerprint of their sweep.

    Parameters
    ----------
    folder : str or Path
        The resume folder (``DIR.resume``); created if missing. A symbolic link or a file
        there is refused.
    fingerprint : dict
        Everything that changes a result (JSON-ready). A folder holding another
        fingerprint's chunks is emptied first.
    cases, chunk : int
        The sweep's cases and cases per chunk: chunk ``k`` must hold cases ``k * chunk`` to
        ``min((k + 1) * chunk, cases) - 1``.
    warn : callable, optional
        ``warn(message)`` for a chunk (or a folder) not reused; default a :class:`ResumeWarning`.

    Raises
    ------
    ValueError
        When the folder is a link or not a folder, or another run holds its lock (one line,
        naming the folder).

    Examples
    --------
    >>> from tumble.io.resume import ChunkFolder
    >>> import tempfile, numpy as np
    >>> root = tempfile.mkdtemp()
    >>> store = ChunkFolder(f"{root}/out.resume", {"sweep": 1}, cases=3, chunk=2)
    >>> store.save(1, {"case": np.array([2])})
    >>> store.has(0), store.has(1), store.load(1)["case"].tolist()
    (False, True, [2])
    >>> store.remove()
    """

    def __init__(self, folder: str | os.PathLike[str], fingerprint: dict, *, cases: int, chunk: int,
                 warn: Callable[[str], None] | None = None) -> None:
        self.folder = Path(folder)
        self.cases, self.chunk = int(cases), int(chunk)
        self._warn = _warn if warn is None else warn
        text = json.dumps(fingerprint, sort_keys=True, default=str)
        self.digest = hashlib.sha256(text.encode("utf-8")).hexdigest()
        self._good: set[int] = set()
        self._fd = self._lock()
        try:
            mark = self.folder / MARK
            held = mark.read_text(encoding="utf-8") if mark.is_file() and not mark.is_symlink() else None
            if held != text:
                old = sorted(self.folder.glob("chunk-*.npz"))
                if old:
                    self._warn(f"{self.folder} held {len(old)} chunk(s) of another sweep (or another version of "
                               f"this one: another fingerprint); discarded, starting over")
                for entry in self.folder.iterdir():
                    if entry.name != LOCK:
                        _delete(entry)
                atomic_write_text(mark, text)
        except BaseException:
            self.close()
            raise

    # --- the lock ------------------------------------------------------------------------
    def _check(self) -> None:
        if self.folder.is_symlink():
            raise ValueError(f"{self.folder} is a symbolic link; tumble writes its resume chunks only into a "
                             f"folder of its own beside --out: remove the link")
        if self.folder.exists() and not self.folder.is_dir():
            raise ValueError(f"{self.folder} exists and is not a folder; tumble keeps a sweep's resume chunks "
                             f"there: move it away")

    def _lock(self) -> int:
        """Hold the folder's lock: refuse when another run holds it; retry when the folder
        was removed (by the run that held it) between opening the lock file and locking it."""
        while True:
            self._check()
            self.folder.mkdir(parents=True, exist_ok=True)
            self._check()
            try:
                fd = os.open(self.folder / LOCK, os.O_RDWR | os.O_CREAT | _NO_FOLLOW, 0o666)
            except FileNotFoundError:
                continue  # the folder went away: make it again
            except OSError as exc:
                raise ValueError(f"{self.folder / LOCK}: cannot open the resume folder's lock "
                                 f"({exc.strerror}); it must be a plain file") from None
            try:
                lock_fd(fd, wait=False)
            except BlockingIOError:
                os.close(fd)
                raise ValueError(f"{self.folder} is locked: another sweep is running into the same --out; wait "
                                 f"for it to finish or give another --out") from None
            try:
                now = os.stat(self.folder / LOCK, follow_symlinks=False)
            except FileNotFoundError:
                now = None
            mine = os.fstat(fd)
            if now is not None and (now.st_ino, now.st_dev) == (mine.st_ino, mine.st_dev):
                return fd
            os.close(fd)  # locked a file that was removed meanwhile: start again

    def close(self) -> None:
        """Release the lock (the chunks stay for a later run).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.io.resume import ChunkFolder
        >>> import tempfile
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     store = ChunkFolder(f"{folder}/out.resume", {"sweep": 1}, cases=2, chunk=2)
        ...     store.save(0, {"case": np.arange(2)})
        ...     store.close()  # the lock is released, the chunk stays for the next run
        ...     again = ChunkFolder(f"{folder}/out.resume", {"sweep": 1}, cases=2, chunk=2)
        ...     print(again.has(0))
        ...     again.close()
        True
        """
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None

    def remove(self) -> None:
        """Delete the folder and its chunks (under the lock), then release the lock.

        Examples
        --------
        >>> from tumble.io.resume import ChunkFolder
        >>> import tempfile
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     store = ChunkFolder(f"{folder}/out.resume", {"sweep": 1}, cases=2, chunk=2)
        ...     store.remove()
        ...     print(store.folder.exists())
        False
        """
        try:
            if not self.folder.is_symlink():
                shutil.rmtree(self.folder, ignore_errors=True)
        finally:
            self.close()

    # --- the chunks ----------------------------------------------------------------------
    @property
    def chunks(self) -> int:
        """How many chunks the sweep has.

        Examples
        --------
        >>> import tempfile
        >>> from tumble.io.resume import ChunkFolder
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     store = ChunkFolder(f"{folder}/out.resume", {"sweep": 1}, cases=10, chunk=4)
        ...     store.close()
        >>> store.chunks  # 4 + 4 + 2 cases
        3
        """
        return -(-self.cases // self.chunk)

    def range(self, number: int) -> tuple[int, int]:
        """``(start, stop)``: the cases chunk ``number`` holds (stop excluded).

        Examples
        --------
        >>> from tumble.io.resume import ChunkFolder
        >>> import tempfile
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     store = ChunkFolder(f"{folder}/out.resume", {"sweep": 1}, cases=10, chunk=4)
        ...     store.close()
        >>> store.range(0), store.range(2)  # the last chunk is shorter
        ((0, 4), (8, 10))
        """
        return number * self.chunk, min((number + 1) * self.chunk, self.cases)

    def _path(self, number: int) -> Path:
        return self.folder / f"chunk-{number:06d}.npz"

    def _read(self, number: int) -> dict:
        """Chunk ``number``'s columns, checked; raises :class:`_BadChunk` saying why not."""
        path = self._path(number)
        if path.is_symlink() or not path.is_file():
            raise _BadChunk("not a plain file")
        try:
            with open(path, "rb") as fh, np.load(fh, allow_pickle=False) as data:  # fh closed on any failure
                names = data["names"].tolist()
                meta = json.loads(str(data["meta"])) if "meta" in data.files else None
                columns = {name: data[f"c{k}"] for k, name in enumerate(names)}
        except Exception as exc:  # noqa: BLE001 - any unreadable file (BadZipFile, EOFError, ...) is recomputed
            raise _BadChunk(f"cannot be read ({type(exc).__name__}: {' '.join(str(exc).split())})") from None
        if not isinstance(meta, dict):
            raise _BadChunk("records no cases and no checksum (an older tumble wrote it)")
        start, stop = self.range(number)
        if meta.get("sweep") != self.digest:
            raise _BadChunk("belongs to another sweep (another fingerprint)")
        if (meta.get("start"), meta.get("stop")) != (start, stop):
            raise _BadChunk(f"holds cases {meta.get('start')} to {meta.get('stop')} (stop excluded), "
                            f"not {start} to {stop}")
        if meta.get("sha256") != chunk_checksum(columns):
            raise _BadChunk("its arrays do not match its checksum (changed or cut)")
        rows = {len(v) for v in columns.values()}
        case = columns.get("case")
        if rows != {stop - start} or case is None or not np.array_equal(case, np.arange(start, stop)):
            raise _BadChunk(f"holds {sorted(rows)} rows, not cases {start} to {stop - 1}")
        return columns

    def has(self, number: int) -> bool:
        """Whether chunk ``number`` is there and sound; a bad one is named in a warning and
        deleted (it is computed again).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.io.resume import ChunkFolder
        >>> import tempfile
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     store = ChunkFolder(f"{folder}/out.resume", {"sweep": 1}, cases=4, chunk=2)
        ...     store.save(0, {"case": np.array([0, 1])})
        ...     print(store.has(0), store.has(1))
        ...     store.remove()
        True False
        """
        if number in self._good:
            return True
        path = self._path(number)
        if not (path.exists() or path.is_symlink()):
            return False
        try:
            self._read(number)
        except _BadChunk as why:
            self._warn(f"{path}: {why}; computing it again")
            _delete(path)
            return False
        self._good.add(number)
        return True

    def load(self, number: int) -> dict:
        """Chunk ``number``'s columns (checked again as read).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.io.resume import ChunkFolder
        >>> import tempfile
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     store = ChunkFolder(f"{folder}/out.resume", {"sweep": 1}, cases=2, chunk=2)
        ...     store.save(0, {"case": np.array([0, 1]), "flips": np.array([3, 5])})
        ...     print(store.load(0)["flips"].tolist())
        ...     store.remove()
        [3, 5]
        """
        try:
            return self._read(number)
        except _BadChunk as why:
            raise ValueError(f"{self._path(number)}: {why} (changed during the run); run the sweep again") from None

    def save(self, number: int, columns: dict) -> None:
        """Keep chunk ``number``'s columns with its cases and checksum (written atomically).

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.io.resume import ChunkFolder
        >>> import tempfile
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     store = ChunkFolder(f"{folder}/out.resume", {"sweep": 1}, cases=2, chunk=2)
        ...     store.save(0, {"case": np.array([0, 1])})
        ...     print(sorted(p.name for p in store.folder.iterdir()))
        ...     store.remove()
        ['chunk-000000.npz', 'fingerprint.json', 'lock']
        """
        start, stop = self.range(number)
        columns = {k: np.asarray(v) for k, v in columns.items()}
        meta = {"start": start, "stop": stop, "sweep": self.digest, "sha256": chunk_checksum(columns)}
        arrays = {f"c{k}": v for k, v in enumerate(columns.values())}
        with atomic_path(self._path(number)) as tmp:
            np.savez(tmp, names=np.array(list(columns)), meta=np.array(json.dumps(meta)), **arrays)
        self._good.add(number)


def _delete(entry: Path) -> None:
    """Remove a file, a link (not its target) or a folder inside the resume folder."""
    if entry.is_dir() and not entry.is_symlink():
        shutil.rmtree(entry, ignore_errors=True)
    else:
        entry.unlink(missing_ok=True)
