"""docs/architecture.md, the contributors' page: its example runs and does what its comment
says, and the rooms it names are the package's."""

from __future__ import annotations

import ast
import contextlib
import importlib
import io
import re
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tumble
from tumble.dynamics.environment import earth
from tumble.dynamics.environment.ephemeris import KeplerOrbit
from tumble.dynamics.environment.orbit import CircularOrbit
from tumble.dynamics.models.gravity import GravityGradient
from tumble.dynamics.models.orbit_gravity import OrbitGravityGradient, gravity_gradient_of

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
                          "models": ["torques", "internal", "rotors", "damper", "gravity", "lvlh", "orbit_gravity", "drag",
                                     "actuators", "sensors"],
                          "environment": ["earth", "orbit", "ephemeris", "magnetic", "igrf", "sidereal", "tabulated"],
                          "methods": ["integrators", "exact", "exact_batch", "geometric"],
                          "engine": ["kernels", "front", "tableau"],
                          "control": ["controllers", "controlled", "mission", "pointing", "detumble", "control_kernel",
                                      "detumble_kernels", "compiled_loop"]}.items():
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
           "run_chunks", "summarize", "run_sweep", "fit_rotation", "fit_recording", "find_flights", "fit_tensor",
           "calibrate_device"}


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
    import tumble.analysis.tensor
    import tumble.commands
    import tumble.commands.sweep
    import tumble.dynamics
    import tumble.dynamics.control.detumble
    import tumble.ensemble
    import tumble.ensemble.detumble

    homes = [tumble.dynamics, tumble.dynamics.control.detumble, tumble.ensemble, tumble.ensemble.detumble, tumble.analysis.fit,
             tumble.analysis.tensor, tumble.commands, tumble.commands.sweep]
    for name in RUNNERS:
        assert any(callable(getattr(m, name, None)) for m in homes), name


SRC = Path(tumble.__file__).resolve().parent


def test_the_earths_constants_have_one_home():
    """MU_EARTH, R_EARTH and OMEGA_EARTH are written once, in dynamics/environment/earth.py: no
    other module of the package holds their values, as a number in its code or as text in a
    docstring or a comment (every other module imports them)."""
    home = SRC / "dynamics" / "environment" / "earth.py"
    values = {"MU_EARTH": earth.MU_EARTH, "R_EARTH": earth.R_EARTH, "OMEGA_EARTH": earth.OMEGA_EARTH}
    spellings = {name: {repr(v), f"{v:e}", f"{v:g}", f"{v:.6e}".rstrip("0")} for name, v in values.items()}
    spellings["MU_EARTH"] |= {"3.986004418e14", "3.986004418e+14", "398600.4418"}
    spellings["R_EARTH"] |= {"6.3781e6", "6.3781e+06", "6378.1e3", "6378100"}
    spellings["OMEGA_EARTH"] |= {"7.292115e-5", "7.292115e-05", "7.292115"}
    found = []
    for path in sorted(SRC.rglob("*.py")):
        if path == home:
            continue
        text = path.read_text(encoding="utf-8")
        for name, forms in spellings.items():
            found += [f"{path.relative_to(SRC)}: {form} ({name})" for form in sorted(forms) if form in text]
        for node in ast.walk(ast.parse(text)):  # a float written any other way (63781e2, ...)
            if isinstance(node, ast.Constant) and isinstance(node.value, float):
                found += [f"{path.relative_to(SRC)}:{node.lineno}: {node.value!r} ({name})"
                          for name, v in values.items() if node.value == v]
    assert not found, "the Earth's constants belong in dynamics/environment/earth.py only:\n" + "\n".join(found)
    text = home.read_text(encoding="utf-8")
    assert all(f"{name} = " in text for name in values)


def _torque(model, moments=(1.0, 2.0, 3.0)):
    """The world-frame torques (N m) of ``model`` bound to ``moments`` at a few times and attitudes."""
    bound = model.bind(list(moments))
    attitudes = Rotation.from_rotvec([[0.3, -0.2, 0.5], [1.1, 0.4, -0.7], [0.0, 0.9, 0.2]])
    return np.array([bound(t, np.zeros(3), attitudes[i]) for i, t in enumerate((0.0, 123.4, 2500.0))])


def test_gravity_gradient_of_a_circular_orbit_is_the_circles_model():
    orbit = CircularOrbit(altitude=600e3, inclination=1.2, raan=0.4, mu=3.9e14)
    gg = gravity_gradient_of(orbit)
    assert type(gg) is GravityGradient
    expected = GravityGradient(orbit_radius=orbit.radius, mu=orbit.mu)
    assert gg == expected
    tau = _torque(gg)
    np.testing.assert_array_equal(tau, _torque(expected))
    assert np.abs(tau).max() > 1e-8   # not an empty comparison: ~3 n^2 (I3 - I1) ~ 1e-6 N m
    assert tumble.gravity_gradient_of is gravity_gradient_of
    assert tumble.dynamics.gravity_gradient_of is gravity_gradient_of


def test_gravity_gradient_of_a_circular_kepler_orbit_is_the_circles():
    """A Keplerian orbit with e = 0 in the plane of the circle (i = 0, the world frame ECI) gives
    the torque of the circle of the same radius (world frame the orbit plane, x along r at t = 0)."""
    kepler = gravity_gradient_of(KeplerOrbit(7000e3, 0.0))
    assert type(kepler) is OrbitGravityGradient
    circle = gravity_gradient_of(CircularOrbit(altitude=7000e3 - earth.R_EARTH))
    np.testing.assert_allclose(_torque(kepler), _torque(circle), rtol=1e-12, atol=1e-22)


@pytest.mark.parametrize("bad", [7000e3, "leo", GravityGradient(orbit_period=5400.0), None])
def test_gravity_gradient_of_names_what_it_takes(bad):
    with pytest.raises(TypeError) as info:
        gravity_gradient_of(bad)
    message = str(info.value)
    assert message.startswith(f"orbit = {bad!r} is a {type(bad).__name__}")
    assert "CircularOrbit, KeplerOrbit or TLEOrbit" in message
