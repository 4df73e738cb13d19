"""tumble.jit: numba's on-disk cache keyed on every source a kernel may call, and a cache that never
stops a run (a read-only install, no writable cache folder)."""

from __future__ import annotations

import importlib.util
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import tumble
from tumble import jit as jit_module
from limits import HANG_S

PACKAGE = Path(tumble.__file__).resolve().parent

#: A compiled function whose answer depends on Euler's equations (dynamics/euler.py), which the
#: engine's right-hand side (dynamics/engine/kernels.py, the function every stepper inlines at its
#: stages) calls from another file. The right-hand side alone, not a whole stepper: the property is
#: the same and it compiles in a second, not the ~20 s of a stepper (twice per test, cold).
PROBE = textwrap.dedent("""
    import numpy as np
    from tumble.dynamics.engine import kernels
    I = (1.0, 2.0, 3.0, 1.0, 0.5, 1.0 / 3.0)   # the moments and their reciprocals
    P = (0.0,) * 10                              # no torque terms
    dw = kernels.rhs((0.3, 1.0, 0.2, 0.0, 0.0, 0.0, 1.0), I, P, 1.0, 0.0)
    print(repr(float(dw[0])), kernels.rhs.stats.cache_hits.total(), kernels.rhs.stats.cache_misses.total())
""")


def _copy_package(tmp_path: Path) -> Path:
    root = tmp_path / "site"
    shutil.copytree(PACKAGE, root / "tumble", ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc"))
    return root


def _run(root: Path, env_extra: dict[str, str] | None = None) -> tuple[float, int, int]:
    env = {**os.environ, "PYTHONPATH": str(root), **(env_extra or {})}
    out = subprocess.run([sys.executable, "-c", PROBE], env=env, capture_output=True, text=True, timeout=HANG_S,
                         check=True, cwd=root)
    value, hits, misses = out.stdout.split()
    return float(value), int(hits), int(misses)


def test_an_edited_callee_in_another_file_is_seen_by_the_next_run(tmp_path):
    """numba alone keys a kernel's cache on its own file: after euler.py is edited, the kernel in
    engine/kernels.py that calls it would keep the old machine code. tumble's stamp covers every
    source of tumble.dynamics, so the next run recompiles and sees the edit."""
    root = _copy_package(tmp_path)
    first, _, misses = _run(root)
    assert misses == 1  # compiled and cached
    again, hits, misses = _run(root)
    assert (again, hits, misses) == (first, 1, 0)  # loaded from the cache: same answer
    euler = root / "tumble" / "dynamics" / "euler.py"
    text = euler.read_text()
    old = "return ((I1 - I2) * w1 * w2 + t0) * r0,"
    assert old in text
    euler.write_text(text.replace(old, "return ((I1 - I2) * w1 * w2 + t0) * r0 + 1.0,"))  # d omega_1/dt + 1 rad/s^2
    edited, hits, misses = _run(root)
    assert misses == 1 and hits == 0  # the stale entry was not used
    assert edited == first + 1.0  # d omega_1/dt one rad/s^2 more: the old machine code would give `first`


#: Euler's equations compiled standalone by the B-dot batch's module (one of the modules that jit the formula).
OTHER_MODULE_FIRST = "from tumble.dynamics.control import detumble_kernels\n" \
    "detumble_kernels._euler(0.1, 0.2, 0.3, 1.0, 2.0, 3.0, 0.0, 0.0, 0.0, 1.0, 0.5, 1.0 / 3.0)\n"
#: A dragged body's rates through the fits' compiled drag step; prints their bytes' hash.
DRAG_PROBE = textwrap.dedent("""
    import hashlib
    import numpy as np
    from tumble.dynamics.models.drag import drag_omega
    w = drag_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], np.linspace(0.0, 2.0, 401), quadratic=[[0.02, 0.03, 0.04]])
    print(hashlib.sha256(np.ascontiguousarray(w).tobytes()).hexdigest())
""")


def _python(root: Path, code: str) -> str:
    out = subprocess.run([sys.executable, "-c", code], env={**os.environ, "PYTHONPATH": str(root)},
                         capture_output=True, text=True, timeout=HANG_S, check=True, cwd=root)
    return out.stdout.strip()


def test_a_kernels_bits_do_not_hang_on_which_module_compiled_a_formula_first(tmp_path):
    """numba keeps one cache index per Python function: Euler's equations, compiled standalone by
    another module first, were loaded from that entry when the fits' drag step compiled, and the step
    came out with other fused multiply-adds (``objdump``: ``vmulsd``/``vsubsd`` for ``vfmsub231sd``).
    The rates differed in their last bits, and the flight finder, which turns on them, took seed 71's
    first flight as samples 195-284 instead of 194-302, by the history of a checkout's cache. The fits'
    module inlines the formula (numba's ``inline="always"``): its code is its own."""
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    after, alone = _copy_package(tmp_path / "a"), _copy_package(tmp_path / "b")
    _python(after, OTHER_MODULE_FIRST)
    assert _python(after, DRAG_PROBE) == _python(alone, DRAG_PROBE)


def test_source_stamp_follows_the_sources(tmp_path, monkeypatch):
    (tmp_path / "dynamics").mkdir()
    source = tmp_path / "dynamics" / "a.py"
    source.write_text("x = 1\n")
    monkeypatch.setattr(jit_module, "PACKAGE", tmp_path)
    monkeypatch.setattr(jit_module, "SOURCES", tmp_path / "dynamics")
    jit_module.source_stamp.cache_clear()
    try:
        first = jit_module.source_stamp()
        source.write_text("x = 2\n")
        jit_module.source_stamp.cache_clear()
        assert jit_module.source_stamp() != first
    finally:
        jit_module.source_stamp.cache_clear()


def _probe_module(tmp_path: Path, name: str):
    """A module of the tumble package (so tumble's locator answers for it) from a file in tmp_path."""
    path = tmp_path / f"{name}.py"
    path.write_text("def triple(x):\n    return 3.0 * x\n")
    spec = importlib.util.spec_from_file_location(f"tumble.{name}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_no_writable_folder_compiles_without_a_cache(tmp_path, monkeypatch):
    """The package's folders and every cache folder read-only: the kernel compiles and runs, with
    no error (numba alone: "cannot cache function ...: no locator available")."""
    monkeypatch.setattr(jit_module, "_writable", lambda folder: False)
    monkeypatch.setattr(jit_module, "cache_root", lambda: None)
    module = _probe_module(tmp_path, "_probe_readonly")
    kernel = jit_module.jit(module.triple)
    assert kernel(2.0) == 6.0
    from numba.core.caching import NullCache

    assert isinstance(kernel._cache, NullCache)  # compiled without a cache: nothing is written anywhere
    assert not list(tmp_path.rglob("*.nbi")) and not list(tmp_path.rglob("*.nbc"))


def test_a_read_only_package_caches_under_the_users_folder(tmp_path, monkeypatch):
    """Beside the sources is read-only: the cache goes under cache_root(), the same relative place."""
    elsewhere = tmp_path / "cache"
    beside = tmp_path / "pkg"
    beside.mkdir()
    monkeypatch.setattr(jit_module, "_writable", lambda folder: not str(folder).startswith(str(beside)))
    monkeypatch.setattr(jit_module, "cache_root", lambda: elsewhere)
    module = _probe_module(beside, "_probe_userdir")
    kernel = jit_module.jit(module.triple)
    assert kernel(2.0) == 6.0
    assert list(elsewhere.rglob("*.nbi")) and not list(beside.rglob("*.nbi"))


def test_a_kernel_numba_cannot_cache_compiles_with_numbas_warning(tmp_path):
    """A kernel that holds a ctypes function pointer (numba's "dynamic globals") cannot be cached:
    numba warns, naming the kernel's file, and compiles it uncached. tumble's locator lacked the
    file numba names there, and the compile failed with an AttributeError instead (seen with
    NUMBA_OPT=0, where the engine's first kernel met the same check)."""
    import ctypes
    import ctypes.util
    import warnings

    from numba.core.errors import NumbaWarning

    libc = ctypes.CDLL(ctypes.util.find_library("c"))
    path = tmp_path / "_probe_pointer.py"
    path.write_text("def absolute(x):\n    return labs(x)\n")
    spec = importlib.util.spec_from_file_location("tumble._probe_pointer", path)
    module = importlib.util.module_from_spec(spec)
    module.labs = libc.labs
    module.labs.argtypes, module.labs.restype = [ctypes.c_long], ctypes.c_long
    spec.loader.exec_module(module)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert jit_module.jit(module.absolute)(-3) == 3
    said = [w for w in caught if issubclass(w.category, NumbaWarning) and "Cannot cache" in str(w.message)]
    assert said and said[0].filename == str(path), [str(w.message) for w in caught]
    assert not list(tmp_path.rglob("*.nbc"))  # nothing half-written


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders; the tests above cover it")
def test_a_read_only_install_runs_a_compiled_path(tmp_path):  # pragma: no cover - runs as a plain user
    root = _copy_package(tmp_path)
    for folder, _, files in os.walk(root):
        for f in files:
            os.chmod(os.path.join(folder, f), 0o444)
        os.chmod(folder, 0o555)
    blocked = tmp_path / "nocache"
    blocked.mkdir(mode=0o555)
    value, _, _ = _run(root, {"NUMBA_CACHE_DIR": str(blocked), "XDG_CACHE_HOME": str(blocked)})
    assert value == value  # ran, a number


def test_a_numba_without_the_undocumented_options_still_compiles(monkeypatch):
    """``forceinline`` and ``_nrt`` are numba target options that it does not document: where a
    release drops them (stood in for by deleting them from numba's options), numba refuses them
    and tumble's :func:`~tumble.jit.jit` compiles the kernel without them, with the same answer."""
    from numba import njit
    from numba.core.cpu import CPUTargetOptions

    for name in jit_module._SPEED_ONLY:
        owner = next(c for c in CPUTargetOptions.__mro__ if name in vars(c))  # this numba knows it
        monkeypatch.delattr(owner, name)
    scope: dict = {}
    exec("def f(x):\n    return x / 0.0", scope)  # no file: compiled without a cache
    with pytest.raises(KeyError, match="forceinline"):
        njit(forceinline=True)(scope["f"])(1.0)
    assert jit_module._known_options({"error_model": "numpy", "forceinline": True, "_nrt": False}) == {
        "error_model": "numpy"}
    assert jit_module.jit(scope["f"], error_model="numpy", forceinline=True, _nrt=False)(1.0) == float("inf")


#: Formulas that more than one kernels module compiles standalone (one shared cache index each), by
#: name -> the modules: where one module's entry is written first, the others' kernels compiled
#: after it may come out with other fused multiply-adds (the test above; issue 38's note). None: a
#: formula that kernels of several modules call is a :func:`tumble.jit.formula`, compiled into
#: each kernel that calls it, with no cache entry of its own.
SHARED_STANDALONE: dict[str, set[str]] = {}


def _standalone_formulas() -> dict[str, set[str]]:
    """Each function a kernels module of tumble.dynamics compiles standalone from another module
    (``_f = jit(formula, ...)`` or ``jit(...)(formula)`` without ``inline="always"``) -> those modules."""
    import re

    found: dict[str, set[str]] = {}
    for path in sorted((PACKAGE / "dynamics").rglob("*.py")):
        text = path.read_text(encoding="utf-8")
        own = set(re.findall(r"^def (\w+)", text, re.M))
        for line in text.splitlines():
            match = re.match(r"^_\w+ = jit\((\w+)[,)]", line) or re.match(r"^_\w+ = jit\([^()]*\)\((\w+)\)", line)
            if match and 'inline="always"' not in line and match[1] not in own:
                found.setdefault(match[1], set()).add(path.relative_to(PACKAGE / "dynamics").as_posix())
    return found


def test_no_more_formulas_are_compiled_standalone_by_two_modules():
    shared = {name: modules for name, modules in _standalone_formulas().items() if len(modules) > 1}
    assert shared == SHARED_STANDALONE, "formulas compiled standalone by several kernels modules (inline them)"
    assert "euler_components" not in shared  # the one that changed the fits' bits, inlined


def test_each_python_function_is_compiled_with_one_set_of_options():
    """numba's cache index is one per Python function, keyed on the argument types and the machine,
    not on the compile options: two ``jit`` of one function with other options (an error model, a
    fastmath flag, LLVM's ``alwaysinline``) share entries, and which was compiled first decides the
    code the other loads. Every kernel and formula of tumble.dynamics, found among the live numba
    dispatchers once every module is imported: one set of options per function (``inline``, which
    tells the caller to inline the function's IR and does not change its own compile, apart)."""
    import gc
    import importlib
    import pkgutil

    import tumble.dynamics
    from numba.core.caching import FunctionCache
    from numba.core.registry import CPUDispatcher

    for info in pkgutil.walk_packages(tumble.dynamics.__path__, "tumble.dynamics."):
        importlib.import_module(info.name)
    options: dict[tuple[str, str], set[tuple]] = {}
    for obj in gc.get_objects():
        # type(), not isinstance: some objects (weak proxies, numpy's lazy loaders) fail when asked
        # their __class__; cached ones: numba's own uncached dispatchers of a formula share no index
        if issubclass(type(obj), CPUDispatcher) and isinstance(obj._cache, FunctionCache) \
                and (obj.py_func.__module__ or "").startswith("tumble."):
            code = obj.py_func.__code__
            key = (f"{code.co_filename}:{code.co_firstlineno}", obj.py_func.__qualname__)
            options.setdefault(key, set()).add(tuple(sorted(
                (k, repr(v)) for k, v in obj.targetoptions.items() if k not in ("inline", "cache"))))
    assert len(options) > 100  # the kernels were found
    mixed = {name: sets for (_, name), sets in options.items() if len(sets) > 1}
    assert not mixed, mixed
