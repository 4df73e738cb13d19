"""Compiling tumble's kernels with numba: one function, and an on-disk cache that tells the truth.

Every compiled kernel of tumble goes through :func:`jit`. It is numba's ``njit(cache=True)``
with two things numba does not do by itself:

- **A cache keyed on every source a kernel may call.** numba keys a cached kernel on its own
  file only: a kernel that calls a compiled function of another file keeps running the old
  machine code after that file is edited, until the cache files are deleted (reported in
  issue 27). Here the key (numba's "source stamp") is a SHA-256 of every ``.py`` file of
  ``tumble.dynamics``, where all the kernels and the model functions they call live, so an edit
  anywhere there recompiles every kernel on its next use. The hash reads ~1 MB once per process,
  a few ms, and only when a kernel is compiled or loaded.
- **A cache that never stops a run.** The cache goes beside the sources (``__pycache__``, as
  numba does) where that folder is writable, else under ``$NUMBA_CACHE_DIR`` or the user's cache
  folder (``$XDG_CACHE_HOME`` or ``~/.cache``, ``tumble/numba``), else in a temporary folder of the
  process: an install whose package and cache folders are read-only compiles on first use and
  runs, with no error (numba alone fails with "cannot cache function ...: no locator available").

The locator is registered with numba's ``CacheImpl._locator_classes`` (numba's hook for where a
function's cache lives; numba >= 0.59) and answers only for functions of ``tumble`` modules.
Written by hand because no library keys numba's cache on more than one file.

Examples
--------
>>> from tumble.jit import jit, source_stamp
>>> def twice(x):
...     return 2.0 * x
>>> jit(twice)(1.5)
3.0
>>> len(source_stamp())   # hex SHA-256 of tumble.dynamics' sources
64
"""

from __future__ import annotations

import functools
import hashlib
import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar, cast, overload

if TYPE_CHECKING:
    import numpy as np

__all__ = ["PARALLEL_BODIES", "cache_root", "cores", "formula", "jit", "kernel_array", "kernel_cache_folder", "source_stamp"]

F = TypeVar("F", bound=Callable[..., Any])

#: Bodies from which a batch kernel runs on every core (``numba.prange``): the parallel kernel's
#: first call in a process starts numba's threads (about a second, measured), which only a large
#: batch pays back. Every batch kernel of tumble reads it here.
PARALLEL_BODIES = 256

#: The package folder (``tumble/``) and the sources whose hash keys every kernel.
PACKAGE = Path(__file__).resolve().parent
SOURCES = PACKAGE / "dynamics"


def cores() -> int:
    """The cores this process may run on (its affinity where the system tells it), for choosing
    a batch kernel's parallel form.

    Examples
    --------
    >>> from tumble.jit import cores
    >>> cores() >= 1
    True
    """
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)


@functools.cache
def source_stamp() -> str:
    """The SHA-256 (hex) of every ``.py`` file under ``tumble/dynamics``, paths and contents.

    Computed once per process: a process sees the sources it imported.

    Examples
    --------
    >>> from tumble.jit import source_stamp
    >>> source_stamp() == source_stamp()
    True
    """
    digest = hashlib.sha256()
    for path in sorted(SOURCES.rglob("*.py")):
        digest.update(path.relative_to(PACKAGE).as_posix().encode())
        digest.update(b"\0")
        digest.update(path.read_bytes())
    return digest.hexdigest()


def _writable(folder: Path) -> bool:
    """Whether ``folder`` exists or can be made, and takes a file (numba's own test)."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        tempfile.TemporaryFile(dir=folder).close()
    except OSError:
        return False
    return True


@functools.cache
def cache_root() -> Path | None:
    """Where kernels are cached when the package's own folders are read-only: ``$NUMBA_CACHE_DIR``
    or the user's cache folder (``tumble/numba`` under ``$XDG_CACHE_HOME`` or ``~/.cache``), else
    a temporary folder of this process; None when not even that can be written (then no cache).

    Examples
    --------
    >>> from tumble.jit import cache_root
    >>> root = cache_root()
    >>> root is None or root.is_dir()
    True
    """
    candidates = []
    if os.environ.get("NUMBA_CACHE_DIR"):
        candidates.append(Path(os.environ["NUMBA_CACHE_DIR"]) / "tumble")
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    candidates.append(Path(base) / "tumble" / "numba")
    for folder in candidates:
        if _writable(folder):
            return folder
    try:
        return Path(tempfile.mkdtemp(prefix="tumble-numba-"))
    except OSError:
        return None


def _folder_for(source: Path) -> Path | None:
    """The cache folder of a kernel defined in ``source``: its ``__pycache__`` when writable,
    else the same relative place under :func:`cache_root`."""
    beside = source.parent / "__pycache__"
    if _writable(beside):
        return beside
    root = cache_root()
    if root is None:
        return None
    try:
        relative = source.parent.relative_to(PACKAGE.parent)
    except ValueError:
        relative = Path(hashlib.sha1(str(source.parent).encode()).hexdigest())
    folder = root / relative
    return folder if _writable(folder) else None


def kernel_cache_folder() -> Path | None:
    """The folder that holds the engine's compiled kernels (``tumble/dynamics/engine``'s, and each
    kernels module's likewise beside its own source): its ``__pycache__`` where writable, else the
    same place under :func:`cache_root`; None where no folder can hold a cache (then every
    process compiles its kernels).

    Examples
    --------
    >>> from tumble.jit import kernel_cache_folder
    >>> folder = kernel_cache_folder()
    >>> folder is None or folder.is_dir()
    True
    """
    return _folder_for((SOURCES / "engine" / "kernels.py").resolve())


@functools.cache
def _install_locator() -> bool:
    """Register the locator with numba (once); False where numba's hook is missing (then the
    kernels compile without a cache, see :func:`jit`)."""
    from numba.core import caching

    base = getattr(caching, "_CacheLocator", None)
    impl = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl", None)
    if base is None or impl is None or not hasattr(impl, "_locator_classes"):
        return False

    class SourceTreeLocator(base):  # type: ignore[misc, valid-type]
        """Caches a tumble kernel in :func:`_folder_for`, stamped with :func:`source_stamp`."""

        def __init__(self, py_func: Callable[..., Any], py_file: str, folder: Path) -> None:
            self._lineno = py_func.__code__.co_firstlineno
            self._py_file = py_file  # numba names it in its warning about a kernel it cannot cache
            self._folder = str(folder)

        def ensure_cache_path(self) -> None:
            os.makedirs(self._folder, exist_ok=True)

        def get_cache_path(self) -> str:
            return self._folder

        def get_source_stamp(self) -> str:
            return source_stamp()

        def get_disambiguator(self) -> str:
            return str(self._lineno)

        @classmethod
        def from_function(cls, py_func: Callable[..., Any], py_file: str) -> SourceTreeLocator | None:
            module = getattr(py_func, "__module__", "") or ""
            if not (module == "tumble" or module.startswith("tumble.")) or not os.path.exists(py_file):
                return None
            folder = _folder_for(Path(py_file).resolve())
            return None if folder is None else cls(py_func, py_file, folder)

    impl._locator_classes.insert(0, SourceTreeLocator)
    return True


@functools.cache
def _counter_class() -> type:
    """The class of :func:`compile_counter`, made once: a subclass of numba's ``event.Listener``
    (numba asks for one), which exists only once numba is imported."""
    import time

    from numba.core import event

    class CompileCounter(event.Listener):  # type: ignore[misc]
        """Counts the kernels numba compiles and sums the time of the outermost compiles (a
        kernel's callees compile inside it), s."""

        def __init__(self) -> None:
            self.kernels = 0
            self.seconds = 0.0
            self._depth = 0
            self._start = 0.0

        def on_start(self, event: Any) -> None:
            if self._depth == 0:
                self._start = time.perf_counter()
            self._depth += 1
            self.kernels += 1

        def on_end(self, event: Any) -> None:
            if self._depth == 0:  # the end of a compile that began before this listener was installed
                return
            self._depth -= 1
            if self._depth == 0:
                self.seconds += time.perf_counter() - self._start

    return CompileCounter


def compile_counter() -> Any:
    """A new listener for numba's ``"numba:compile"`` events (``numba.core.event``) with
    ``kernels``, the kernels compiled, and ``seconds``, the wall time of the outermost compiles,
    while it is installed (``event.install_listener``) or registered.

    Examples
    --------
    >>> from numba.core import event
    >>> from tumble.jit import compile_counter, jit
    >>> counter = compile_counter()
    >>> with event.install_listener("numba:compile", counter):
    ...     jit(lambda x: x + 1.0)(1.0)   # a lambda typed here: compiled, not cached
    2.0
    >>> counter.kernels, counter.seconds > 0.0
    (1, True)
    """
    return _counter_class()()


#: The process's own counter (:func:`compile_seconds`), registered when tumble first compiles.
_CLOCK: list[Any] = []


def _start_clock() -> None:
    if not _CLOCK:
        from numba.core import event

        _CLOCK.append(compile_counter())
        event.register("numba:compile", _CLOCK[0])


def compile_seconds() -> float:
    """The seconds this process has waited for numba to compile (the outermost compiles since
    tumble's first kernel was made, :func:`jit`); 0 where none was. The command line names it
    where a run waited long (:func:`tumble.cli.main`: ``tumble compile`` does it ahead).

    Examples
    --------
    >>> from tumble.jit import compile_seconds
    >>> compile_seconds() >= 0.0
    True
    """
    return float(_CLOCK[0].seconds) if _CLOCK else 0.0


@overload
def jit(function: F, **options: Any) -> F: ...


@overload
def jit(function: None = None, **options: Any) -> Callable[[F], F]: ...


def jit(function: F | None = None, **options: Any) -> F | Callable[[F], F]:
    """``numba.njit(cache=True, **options)`` with tumble's cache (module docstring).

    Use as ``jit(f)``, ``jit(f, parallel=True)`` or as a decorator, ``@jit`` or ``@jit(inline="always")``.
    numba is imported on the first call, so a module that only defines kernels costs nothing
    until one is compiled. Where no folder can hold a cache, the kernel compiles without one.

    Examples
    --------
    >>> from tumble.jit import jit
    >>> @jit(error_model="numpy")
    ... def ratio(a, b):
    ...     return a / b
    >>> ratio(1.0, 0.0)   # numpy's error model: inf, not ZeroDivisionError
    inf
    """
    if function is None:
        return lambda f: jit(f, **options)
    from numba import njit

    _register_formulas()
    _start_clock()

    source = Path(function.__code__.co_filename)
    # a function typed at a prompt or in a doctest has no file to key a cache on
    cache = source.is_file() and _install_locator() and _folder_for(source.resolve()) is not None
    return cast(F, njit(cache=cache, **_known_options(options))(function))


#: The plain functions over floats marked :func:`formula`, and how many numba knows yet.
_FORMULAS: list[Callable[..., Any]] = []
_REGISTERED = [0]


def formula(function: F) -> F:
    """Mark a formula written as a plain function over floats (or arrays, element by element) as one
    that compiled code may call by its name: a kernel, or another formula that a kernel compiles,
    calls it as it is, and numba compiles it inline there (``numba.extending.register_jitable``,
    numba's hook for a Python function that jitted code may call). So a formula that uses another
    (``turned_by`` uses the Hamilton product) is written once for Python and compiled code alike.
    Registered when :func:`jit` first imports numba: a module of formulas does not import it.

    A formula has no compiled form and no cache entry of its own: numba compiles it in the process
    (numpy's error model) and links it into each kernel that calls it, whose cache holds it. A function that
    several kernels modules compiled standalone (``jit(f)``) had one cache entry, and which module
    wrote it first changed the machine code of the others' kernels (their bits: issue 38's fits).

    Examples
    --------
    >>> from tumble.jit import formula, jit
    >>> @formula
    ... def half(x):
    ...     return 0.5 * x
    >>> def quarter(x):
    ...     return half(half(x))
    >>> half(3.0), jit(quarter)(3.0)   # called from Python, and from a kernel
    (1.5, 0.75)
    """
    _FORMULAS.append(function)
    return function


def _register_formulas() -> None:
    """Tell numba of the formulas marked since the last call (:func:`formula`)."""
    if _REGISTERED[0] == len(_FORMULAS):
        return
    from numba.extending import register_jitable

    for function in _FORMULAS[_REGISTERED[0]:]:
        register_jitable(error_model="numpy")(function)  # as tumble's kernels: a float division by 0 is inf
    _REGISTERED[0] = len(_FORMULAS)


#: numba options that only make a kernel faster, or its first compile shorter, and that numba keeps
#: among its target options without documenting them: ``forceinline`` (LLVM's ``alwaysinline``),
#: ``_nrt=False`` (no reference counting) and ``no_cpython_wrapper=True`` (for a function that only
#: compiled code calls: numba builds, for every compile, a wrapper that lets Python call it, whose
#: boxing and unboxing of tuples was ~11 % of the first torque ``simulate``'s compile where ``auto``
#: takes ``dop853``, 5.59 -> 4.95 CPU-s measured; numba's own sorts use it; Python calling such a
#: function crashes the interpreter, so only the generated steps take it,
#: :func:`tumble.dynamics.engine.kernels.generated`). numba refuses an option it does not know (KeyError),
#: so a release without one of these would stop tumble importing; :func:`_known_options` leaves them
#: out there instead.
_SPEED_ONLY = ("forceinline", "_nrt", "no_cpython_wrapper")


def _known_options(options: dict[str, Any]) -> dict[str, Any]:
    """``options`` less those of :data:`_SPEED_ONLY` that the installed numba does not know (its
    ``CPUTargetOptions``): the kernel compiles as before, only without that speed-up.

    Examples
    --------
    >>> from tumble.jit import _known_options
    >>> _known_options({"error_model": "numpy", "forceinline": True})   # numba 0.68 knows both
    {'error_model': 'numpy', 'forceinline': True}
    """
    try:
        from numba.core.cpu import CPUTargetOptions
    except ImportError:  # numba moved its options: none of the undocumented ones is assumed
        return {k: v for k, v in options.items() if k not in _SPEED_ONLY}
    return {k: v for k, v in options.items() if k not in _SPEED_ONLY or hasattr(CPUTargetOptions, k)}


#: The numpy dtype of each ``dtype`` :func:`kernel_array` was given (its fast path compares them by identity).
_DTYPES: dict[Any, Any] = {}


def kernel_array(a: Any, shape: tuple[int, ...] | None = None, dtype: Any = float) -> np.ndarray[Any, Any]:
    """``a`` as the one kind of array tumble's kernels are compiled for: ``dtype``, C-contiguous
    and writable, broadcast to ``shape`` where given; ``a`` itself where it is that already, else a copy.

    numba types an array argument by its dtype, dimensions, layout *and* whether it is read-only,
    and compiles a kernel once for each: a read-only array (``np.broadcast_to``'s view, even where
    the shape is unchanged, or a column read by pyarrow) compiled each kernel a second time. In a
    cold run of the test suite 30 kernels were compiled twice or more that way (``fixed_rk8``,
    ``dop853``, the exact flow's, the fits'), 10-16 CPU-s for each of the largest. A copy of a
    few numbers costs under a microsecond; the check ~0.1 us.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.jit import kernel_array
    >>> a = np.ones(3)
    >>> kernel_array(a) is a
    True
    >>> view = np.broadcast_to(a, (3,))   # read-only, though the shape is the same
    >>> b = kernel_array(view)
    >>> b is view, b.flags.writeable, kernel_array([1, 2], (2, 2)).tolist()
    (False, True, [[1.0, 2.0], [1.0, 2.0]])
    """
    want = _DTYPES.get(dtype)
    if want is None:  # numpy's dtypes of native byte order are singletons: compared by identity below
        import numpy as np

        want = _DTYPES[dtype] = np.dtype(dtype)
    try:  # ~0.1 us where ``a`` is such an array already
        flags = a.flags
        if flags.writeable and flags.c_contiguous and a.dtype is want and (shape is None or a.shape == shape):
            return cast("np.ndarray[Any, Any]", a)
    except AttributeError:  # a list, a float
        pass
    import numpy as np

    b = np.asarray(a, dtype=dtype)
    if shape is not None and b.shape != shape:
        b = np.broadcast_to(b, shape)
    return np.array(b, dtype=dtype, order="C")
