"""One compile mechanism (issue 38, items 3 and the "done when"): a test over the package's sources.

Every kernel is compiled at import, by :func:`tumble.jit.jit`, in a module imported only when a
compiled path is asked for (the engine's kernels, the closed loop's, the fits', the B-dot
batch's). So the sources hold:

- no ``globals()[...]``: no module global rebound to its compiled version on first use (the
  package's lazy ``__getattr__`` in ``tumble/__init__.py`` and ``commands/__init__.py``, and the
  figure class made on first use in ``viz/_backend.py``, are lazy imports, not compilation);
- no ``types.FunctionType`` copy of a kernel (a serial and a parallel kernel are two functions
  over one compiled body, as :mod:`tumble.dynamics.methods.compiled_exact` and
  :mod:`tumble.dynamics.control.detumble_kernels` do);
- no ``type(x) is SomeModel`` (or ``in (...)``) dispatch: a model declares its compiled form
  itself (``kernel_form()`` for the engine, ``loop_form()`` for the closed loop). The fast paths'
  input checks, ``type(x) is float``, ``int``, ``tuple``, ``list`` or ``np.ndarray``, stay:
  they test a plain value, not choose a model;
- no module ``compiled_control`` or ``compiled_detumble``;
- no Runge-Kutta step written by hand (``k1 + 2 k2 + 2 k3 + k4``): the steps are the engine's,
  written out from the tableaux by :mod:`tumble.dynamics.engine.unrolled`, but for the copies of
  :data:`HAND_WRITTEN_RK`.

Each check is run on samples of what it must find, so it can fail.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest
from test_formulas_once import code_lines

import tumble

SRC = Path(tumble.__file__).resolve().parent

#: The modules whose ``globals()`` is a lazy import's, not a compiled kernel's.
LAZY = {"__init__.py", "commands/__init__.py", "viz/_backend.py"}

#: The plain types a fast path may test with ``type(x) is``.
PLAIN = r"(float|int|bool|str|tuple|list|dict|complex|np\.ndarray|np\.float64)"

#: The Runge-Kutta steps still written by hand: module -> why.
HAND_WRITTEN_RK: dict[str, str] = {}

GLOBALS = re.compile(r"\bglobals\(\)\[")
RK_BY_HAND = re.compile(r"2(\.0)?\*\w*[kK]\w*(\[[^\]]*\])?\+2(\.0)?\*\w*[kK]")
FUNCTION_COPY = re.compile(r"\bFunctionType\b")
#: ``type(x) is C``, ``is not C``, ``in (C, ...)``, ``not in (C, ...)`` with any C not a plain type.
DISPATCH = re.compile(r"(?:(?<![\w.])|(?<=if)|(?<=or)|(?<=and)|(?<=not)|(?<=return))type\([^()]*(\([^()]*\))?[^()]*\)"
                      r"(?>isnot|is|notin|in)(?!" + PLAIN + r")(?!\((" + PLAIN + r",?)+\))[\w.(]")


def _found(pattern: re.Pattern[str], skip: set[str] = frozenset()) -> list[str]:
    hits = []
    for path in sorted(SRC.rglob("*.py")):
        module = path.relative_to(SRC).as_posix()
        if module in skip:
            continue
        for n, line in code_lines(path).items():
            if pattern.search(line):
                hits.append(f"{module}:{n}: {line}")
    return hits


def _squeeze(code: str) -> str:
    return re.sub(r"\s+", "", code)


@pytest.mark.parametrize(("pattern", "finds", "passes"), [
    (GLOBALS, ['globals()["_drag"] = jit(inline="always")(drag_component)', "function = globals()[name]"],
     ["names = {n for n in globals() if n}"]),
    (RK_BY_HAND, ["q = q + h / 6 * (k1q + 2 * k2q + 2 * k3q + k4q)",
                  "w[c] += h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c])",
                  "S[c, r] = S[c, r] + e * (K[0, c, r] + 2 * K[1, c, r] + 2 * K[2, c, r] + K[3, c, r])"],
     ["twoK = (2.0 * K[0], 2.0 * K[1])", "y[0] + h * (0.16666666666666666 * k0[0] + 0.3333333333333333 * k1[0])"]),
    (FUNCTION_COPY, ['function = types.FunctionType(function.__code__, globals(), name + "_parallel")'], ["f = jit(g)"]),
    (DISPATCH, ["if type(field) is UniformField:", "if type(gravity_gradient) is not GravityGradient:",
                "if model is not None and type(model) not in kinds:",
                "type(gravity_gradient.orbit) not in (CircularOrbit, KeplerOrbit, TLEOrbit)"],
     ["if not (type(t_end) is float and 0.0 < t_end):", "datatype(x) is Model", "if type(samples) is not int and x:",
      "if type(value) is np.ndarray and value.shape == (4,):", "if type(value) in (tuple, list):",
      "all(type(v) is float for v in items)", "if type(self).world is not UniformField.world:",
      "type(controller).__call__ is cls.__call__"]),
])
def test_each_check_finds_what_it_was_written_against(pattern, finds, passes):
    for sample in finds:
        assert pattern.search(_squeeze(sample)), sample
    for sample in passes:
        assert not pattern.search(_squeeze(sample)), sample


def test_no_module_global_is_rebound_to_compile():
    assert _found(GLOBALS, LAZY) == []


def test_no_kernel_is_copied_to_compile_it_twice():
    assert _found(FUNCTION_COPY) == []


def test_no_model_is_chosen_by_its_exact_type():
    assert _found(DISPATCH) == []


def test_no_runge_kutta_step_is_written_by_hand_but_the_listed_ones():
    found = {hit.split(":")[0] for hit in _found(RK_BY_HAND)}
    assert found == set(HAND_WRITTEN_RK), found


def test_the_old_compile_rooms_are_gone():
    control = SRC / "dynamics" / "control"
    assert not (control / "compiled_control.py").exists()
    assert not (control / "compiled_detumble.py").exists()


def test_the_fronts_import_no_numba_their_kernels_do():
    """The fronts import their kernels modules only when a compiled path runs: importing them
    costs no numba (the kernels modules compile at import)."""
    fronts = ("tumble.dynamics.models.drag", "tumble.dynamics.models.gyrostat", "tumble.dynamics.control",
              "tumble.dynamics.control.detumble", "tumble.dynamics.control.controlled", "tumble.dynamics.estimation.mekf",
              "tumble.dynamics.environment.magnetic", "tumble.dynamics.environment.igrf", "tumble.analysis.fit")
    code = f"import sys, {', '.join(fronts)}; print('numba' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False"]
    code = "import sys, tumble.dynamics.models.fit_kernels; print('numba' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["True"]  # the check can fail: a kernels module does import numba
