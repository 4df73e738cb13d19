"""The compiled kernel of the geometric splitting under built-in torques against the numpy path
(which calls the torque model from Python at every kick), and against DOP853."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tumble.dynamics import simulate
from tumble.dynamics.methods import geometric
from tumble.dynamics.methods.compiled import compiled_model
from tumble.dynamics.models.gravity import GravityGradient
from tumble.dynamics.models.torques import ConstantTorque, FunctionTorque
from tumble.mass import MassProperties

RNG = np.random.default_rng(12)
N = 20
I = np.sort(RNG.uniform(1.0, 3.0, (N, 3)), axis=1)
I[:, 2] = np.minimum(I[:, 2], I[:, 0] + I[:, 1])  # bodies that exist: I3 <= I1 + I2
W = RNG.normal(size=(N, 3))
Q = Rotation.random(N, random_state=4).as_quat()
T = np.linspace(0.0, 3.0, 4)
MODELS = {
    "body": ConstantTorque([0.1, -0.2, 0.05]),
    "world": ConstantTorque([0.1, -0.2, 0.05], frame="world"),
    "gravity": GravityGradient(orbit_period=20.0, mu=1.0, moments=I),  # a fast orbit: a strong torque
}


@pytest.mark.parametrize("order", [2, 4, 6])
@pytest.mark.parametrize("name", list(MODELS))
def test_the_compiled_and_numpy_paths_agree_to_round_off(name, order):
    fast = geometric.propagate(I, W, Q, T, order=order, step=0.01, torque=MODELS[name])
    slow = geometric.propagate(I, W, Q, T, order=order, step=0.01, torque=MODELS[name], compiled=False)
    # measured: at most 1.3e-13 rad/s and 2e-14 in the quaternion after 300 composed steps
    np.testing.assert_allclose(fast[0], slow[0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(fast[1], slow[1], rtol=0, atol=1e-12)


def test_a_body_runs_alone_as_in_its_batch():
    torque = MODELS["world"]
    batch = geometric.propagate(I, W, Q, T, order=4, step=0.02, torque=torque)
    for i in (0, 7, N - 1):
        alone = geometric.propagate(I[i], W[i], Q[i], T, order=4, step=0.02, torque=torque)
        np.testing.assert_array_equal(alone[0][:, 0], batch[0][:, i])
        np.testing.assert_array_equal(alone[1][:, 0], batch[1][:, i])


def test_simulate_runs_a_constant_torque_without_calling_python_per_kick(monkeypatch):
    calls = []
    original = geometric.body_torque
    monkeypatch.setattr(geometric, "body_torque", lambda *a: calls.append(1) or original(*a))
    props = MassProperties.from_moments([0.0021, 0.0043, 0.0059])
    torque = ConstantTorque([1e-4, -2e-4, 3e-4])
    run = simulate(props, [0.1, 10.0, 0.05], t_end=2.0, samples=5, method="geometric6", torque=torque, step=0.002)
    assert calls == []
    ref = simulate(props, [0.1, 10.0, 0.05], t_end=2.0, samples=5, method="dop853", torque=torque, rtol=1e-13,
                   atol=1e-13)
    np.testing.assert_allclose(run.omega, ref.omega, rtol=0, atol=1e-8)


def test_only_the_built_in_models_are_compiled():
    assert compiled_model(ConstantTorque([0.0, 0.0, 1.0])) == ((0.0, 0.0, 1.0) + (0.0,) * 7, 0.0)  # its slot of the terms
    assert compiled_model(FunctionTorque(lambda t, w, R: -0.1 * w)) is None
    assert compiled_model(GravityGradient(orbit_period=6000.0)) is None  # not bound to a body yet


# --- the exact free flow in double precision (methods.compiled_flow) ----------------------------

def test_carlson_and_jacobi_functions_match_scipy():
    from scipy.special import ellipj, ellipk, elliprf, elliprj

    from tumble.dynamics.methods import compiled_flow as cf

    rng = np.random.default_rng(7)
    for x, y, z, p in rng.uniform(0.0, 3.0, (50, 4)):
        assert abs(cf._rf(x, y, z) / elliprf(x, y, z) - 1.0) < 1e-15
        assert abs(cf._rj(x, y, z, p + 0.01) / elliprj(x, y, z, p + 0.01) - 1.0) < 2e-15
        rf, rj = cf._rf_rj(x, y, z, p + 0.01)  # both from one duplication
        assert abs(rf / elliprf(x, y, z) - 1.0) < 1e-15 and abs(rj / elliprj(x, y, z, p + 0.01) - 1.0) < 2e-15
    for m in (0.0, 0.3, 0.9, 0.999999):
        K = ellipk(m)
        for v in np.linspace(-K, K, 9):
            np.testing.assert_allclose(cf._jacobi(v, m, np.sqrt(1.0 - m), np.empty(cf.WORK)), ellipj(v, m)[:3], rtol=0, atol=4e-16)


def test_the_compiled_free_flow_matches_the_double_double_kernel():
    """One step of any length and sign, from random states, against free_rotation_batch (itself
    checked against mpmath): measured 1.0e-13 at most over 300 steps."""
    from tumble.dynamics.methods.compiled_flow import free_flow
    from tumble.dynamics.methods.exact_batch import free_rotation_batch

    flow = free_flow
    rng = np.random.default_rng(1)
    for trial in range(300):
        I = np.sort(rng.uniform(0.5, 3.0, 3))
        w = rng.normal(size=3) * 3.0
        q = Rotation.random(random_state=trial).as_quat()
        h = rng.choice([-1.0, 1.0]) * 10.0 ** rng.uniform(-3.0, 2.0)
        L, qq = I * w, q.copy()
        flow(I, L, qq, h)
        omega, quat = free_rotation_batch(I[None], w[None], q[None], np.array([h]))
        assert np.max(np.abs(L / I - omega[0, 0])) <= 1e-12 * np.max(np.abs(w))
        assert (Rotation.from_quat(qq).inv() * Rotation.from_quat(quat[0, 0])).magnitude() <= 1e-12
        if trial < 20:  # the same code run by Python, uncompiled, agrees to round-off
            L2, q2 = I * w, q.copy()
            _uncompiled(free_flow)(I, L2, q2, h)  # the Python functions under numba's
            np.testing.assert_allclose(L2, L, rtol=0, atol=1e-13 * np.max(np.abs(L)))


def _uncompiled(kernel):
    """A kernel's Python function with every compiled function of its module that it calls
    swapped for its Python function too (numba's ``py_func``), so that it runs as plain Python."""
    import types

    scope = {k: getattr(v, "py_func", v) for k, v in kernel.py_func.__globals__.items()}
    return types.FunctionType(kernel.py_func.__code__, scope)


@pytest.mark.parametrize("name", list(MODELS))
def test_compiled_exact_split_agrees_with_the_double_double_path(name):
    from tumble.dynamics.methods import exact_split

    fast = exact_split.propagate(I[:5], W[:5], Q[:5], T, order=6, step=0.1, torque=_for_five(MODELS[name]))
    slow = exact_split.propagate(I[:5], W[:5], Q[:5], T, order=6, step=0.1, torque=_for_five(MODELS[name]),
                                 compiled=False)
    # measured: 2.7e-14 rad/s and 5e-14 rad
    np.testing.assert_allclose(fast[0], slow[0], rtol=0, atol=1e-12)
    angle = (Rotation.from_quat(fast[1].reshape(-1, 4)).inv() * Rotation.from_quat(slow[1].reshape(-1, 4))).magnitude()
    assert np.max(angle) < 1e-12


def _for_five(model):
    return GravityGradient(orbit_period=20.0, mu=1.0, moments=I[:5]) if isinstance(model, GravityGradient) else model


def test_the_compiled_free_flow_turns_a_steady_spin_about_its_axis():
    from tumble.dynamics.methods.compiled_flow import free_flow

    L, q = np.array([0.0, 0.0, 3.0]), np.array([0.0, 0.0, 0.0, 1.0])
    free_flow(np.array([1.0, 2.0, 3.0]), L, q, np.pi)  # half a turn about the major axis
    np.testing.assert_allclose(q, [0.0, 0.0, 1.0, 0.0], atol=1e-15)
    np.testing.assert_array_equal(L, [0.0, 0.0, 3.0])


def test_a_batch_on_every_core_gives_each_body_the_one_thread_arithmetic(monkeypatch):
    """The parallel kernel (numba.prange over bodies, for large batches) and the one-thread kernel
    run the same arithmetic per body: bit for bit the same samples."""
    from tumble.dynamics.methods import compiled

    torque = MODELS["world"]
    serial = geometric.propagate(I, W, Q, T, order=4, step=0.02, torque=torque)
    monkeypatch.setattr(compiled, "PARALLEL_BODIES", 1)
    monkeypatch.setattr(compiled, "cores", lambda: 2)
    parallel = geometric.propagate(I, W, Q, T, order=4, step=0.02, torque=torque)
    np.testing.assert_array_equal(parallel[0], serial[0])
    np.testing.assert_array_equal(parallel[1], serial[1])


def test_wheels_at_constant_rates_run_compiled_and_agree_with_the_numpy_path():
    """A body with a constant wheel momentum under a built-in torque: the compiled kernel (rates
    (L - h) / I) against the numpy path, and against DOP853."""
    from pathlib import Path

    import tumble
    from tumble.dynamics.methods.geometric import propagate_internal
    from tumble.dynamics.models.internal import InternalModel, Rotors

    body = tumble.load_body(Path(__file__).resolve().parents[1] / "examples" / "bodies" / "t_handle_wheel.toml")
    props = body.properties
    model = InternalModel(props.principal_moments, Rotors.of(body), None)
    torque = ConstantTorque([1e-3, -2e-3, 5e-4], frame="world")
    w0, q0, t = np.array([0.1, 10.0, 0.05]), np.array([0.0, 0.0, 0.0, 1.0]), np.linspace(0.0, 2.0, 5)
    fast = propagate_internal(model, w0, q0, t, order=6, step=0.002, torque=torque)
    slow = propagate_internal(model, w0, q0, t, order=6, step=0.002, torque=torque, compiled=False)
    np.testing.assert_allclose(fast.omega, slow.omega, rtol=0, atol=1e-11)
    np.testing.assert_allclose(fast.quat, slow.quat, rtol=0, atol=1e-11)
    ref = simulate(body, w0, times=t, method="dop853", torque=torque, rtol=1e-12, atol=1e-12)
    run = simulate(body, w0, times=t, method="geometric6", torque=torque, step=0.002)
    np.testing.assert_allclose(run.omega, ref.omega, rtol=0, atol=1e-7)


def test_the_compiled_free_flow_takes_components_whose_squares_underflow_as_steady():
    """omega = (1e-200, 0, 5): the off-axis energy underflows; the flow is the turn about omega
    (the double-double kernel agrees to 5e-16 rad) instead of a division by zero."""
    from tumble.dynamics.methods.compiled_flow import free_flow
    from tumble.dynamics.methods.exact_batch import free_rotation_batch

    I, w = np.array([1.0, 2.0, 3.0]), np.array([1e-200, 0.0, 5.0])
    L, q = I * w, np.array([0.0, 0.0, 0.0, 1.0])
    free_flow(I, L, q, 0.7)
    omega, quat = free_rotation_batch(I[None], w[None], q[None] * 0 + [0.0, 0.0, 0.0, 1.0], np.array([0.7]))
    assert np.max(np.abs(L / I - omega[0, 0])) <= 1e-15 * 5.0
    assert (Rotation.from_quat(q).inv() * Rotation.from_quat(quat[0, 0])).magnitude() <= 1e-15


def test_the_kernels_compile_at_import_of_modules_imported_on_first_use():
    """One compile mechanism (issue 38 item 3): the kernels modules decorate their functions
    with tumble.jit.jit at import; no module of methods/ or engine/ rebinds its globals to compile, copies
    a function's code for a parallel twin or dispatches on ``type(x) is``; and ``import tumble``
    with the methods' fronts imports no numba (a fresh interpreter)."""
    import ast
    import subprocess
    import sys
    from pathlib import Path

    dynamics = Path(__file__).resolve().parents[1] / "src" / "tumble" / "dynamics"
    folder = dynamics / "methods"
    for path in sorted([*folder.glob("*.py"), *(dynamics / "engine").glob("*.py")]):
        text = path.read_text(encoding="utf-8")
        assert "globals()" not in text and "FunctionType" not in text, path.name
        tree = ast.parse(text)
        for node in ast.walk(tree):
            if isinstance(node, ast.Compare) and isinstance(node.ops[0], ast.Is):
                left = node.left
                assert not (isinstance(left, ast.Call) and getattr(left.func, "id", "") == "type"), path.name
    for path in [folder / f"{name}.py" for name in ("compiled_flow", "compiled_split", "compiled_exact")]:
        name = path.stem
        tree = ast.parse(path.read_text(encoding="utf-8"))
        functions = [n for n in tree.body if isinstance(n, ast.FunctionDef)]
        assert functions and all(any("jit" in ast.unparse(d) for d in f.decorator_list) for f in functions), name
    code = ("import sys, tumble, tumble.dynamics.methods.compiled, tumble.dynamics.methods.exact_batch, "
            "tumble.dynamics.methods.exact_split; print('numba' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False"]
