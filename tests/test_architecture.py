"""docs/architecture.md, the contributors' page: its example runs and does what its comment
says, and the rooms it names are the package's."""

from __future__ import annotations

import contextlib
import importlib
import io
import re
from pathlib import Path

import numpy as np

PAGE = Path(__file__).resolve().parents[1] / "docs" / "architecture.md"


def test_the_torque_model_example_keeps_l_along_the_field():
    code = re.search(r"```python\n(.*?)```", PAGE.read_text(encoding="utf-8"), re.S).group(1)
    out = io.StringIO()
    scope: dict = {}
    with contextlib.redirect_stdout(out):
        exec(compile(code, str(PAGE), "exec"), scope)
    assert out.getvalue().split() == ["True"]
    L = scope["L_world"]
    # the claim is not empty: the dipole torque turns L about the field (x, y change by ~1e-4
    # of |L|, ten thousand times the bound the page checks along the field)
    assert np.linalg.norm(L[-1, :2] - L[0, :2]) > 1e-5 * np.linalg.norm(L[0])


def test_the_rooms_named_on_the_page_hold_the_modules_it_names():
    text = PAGE.read_text(encoding="utf-8")
    for room, modules in {"special": ["elliptic", "carlson", "ddouble", "quaternion"],
                          "models": ["torques", "internal", "rotors", "damper", "gravity", "lvlh", "drag"],
                          "methods": ["integrators", "exact", "exact_batch", "geometric"],
                          "engine": ["kernels", "front", "tableau"],
                          "control": ["controllers", "controlled", "mission", "pointing", "detumble", "compiled_control",
                                      "compiled_detumble"]}.items():
        assert f"`dynamics/{room}/`" in text
        for name in modules:
            importlib.import_module(f"tumble.dynamics.{room}.{name}")


def test_the_dynamics_front_room_is_small():
    """The front room of tumble.dynamics holds the fronts and the results (simulate, simulate_batch,
    the trajectories, Euler's equations, their display): at most six modules; the rest has a room."""
    folder = Path(__file__).resolve().parents[1] / "src" / "tumble" / "dynamics"
    modules = sorted(p.stem for p in folder.glob("*.py") if p.stem != "__init__")
    assert len(modules) <= 6, modules


#: What computes a motion, a sweep or a fit: the file layer calls none of them (issue #31, item 5).
RUNNERS = {"simulate", "simulate_batch", "simulate_controlled", "run_scenario", "detumble_batch",
           "detumble_monte_carlo", "compute_chunk",
           "run_chunks", "summarize", "run_sweep", "fit_rotation", "fit_recording", "find_flights"}


def _calls_and_imports(path: Path) -> tuple[set[str], set[str]]:
    """The names a module calls (``f(...)`` and ``x.f(...)``) and the names it imports."""
    import ast

    tree = ast.parse(path.read_text(encoding="utf-8"))
    calls, imports = set(), set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            func = node.func
            calls.add(func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else "")
        elif isinstance(node, ast.ImportFrom):
            imports.update(alias.name for alias in node.names)
    return calls, imports


def test_the_file_layer_only_reads_and_writes():
    """io/ never runs a simulation, a sweep or a fit: the command layer (tumble.commands) does.
    The check sees the code, not the docstrings' examples."""
    folder = Path(__file__).resolve().parents[1] / "src" / "tumble" / "io"
    found = {}
    for path in sorted(folder.glob("*.py")):
        calls, imports = _calls_and_imports(path)
        if (calls | imports) & RUNNERS:
            found[path.name] = sorted((calls | imports) & RUNNERS)
    assert found == {}
    # the check can fail: the command layer's sweep calls them
    calls, imports = _calls_and_imports(folder.parent / "commands" / "sweep.py")
    assert {"run_chunks", "summarize", "compute_chunk"} <= calls & imports


def test_every_runner_named_is_a_public_function():
    """The list above names real functions (a renamed one would make the check pass vacuously)."""
    import tumble.analysis.fit
    import tumble.commands
    import tumble.commands.sweep
    import tumble.dynamics
    import tumble.dynamics.control.detumble
    import tumble.ensemble
    import tumble.ensemble.detumble

    homes = [tumble.dynamics, tumble.dynamics.control.detumble, tumble.ensemble, tumble.ensemble.detumble, tumble.analysis.fit,
             tumble.commands, tumble.commands.sweep]
    for name in RUNNERS:
        assert any(callable(getattr(m, name, None)) for m in homes), name
