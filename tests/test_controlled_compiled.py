"""The compiled closed-loop paths (control/control_kernel.py, compiled_loop.py, loop_terms.py): each built-in model written out
in numba against its numpy reference, the compiled DOP853 against scipy's (the same steps, so
round-off apart), the momentum budget, an exact relation of B-dot, and the compiled B-dot batch
against the numpy batch."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tumble.dynamics.control import controlled
from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.bdot import BDot, bdot_dipole
from tumble.dynamics.control.controllers import MRPFeedback
from tumble.dynamics.control.detumble import detumble_batch
from tumble.dynamics.control import control_kernel as cc
from tumble.dynamics.control import loop_terms
from tumble.dynamics.control.compiled_loop import padded, unpadded
from tumble.dynamics.control import detumble_kernels as cd
from tumble.dynamics.models.actuators import Magnetorquers, ReactionWheels
from tumble.dynamics.models.orbit_gravity import gravity_gradient_of
from tumble.dynamics.environment.magnetic import DipoleField, UniformField
from tumble.dynamics.environment.orbit import CircularOrbit

ORBIT = CircularOrbit(altitude=500e3, inclination=1.69995, raan=0.4, arg_latitude=1.1)
CUBESAT = [0.0067, 0.0419, 0.0419]  # kg m^2


def _close(a, b, rel):
    """max |a - b| <= rel * max |b| (the scale of the quantity)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    assert np.max(np.abs(a - b)) <= rel * max(np.max(np.abs(b)), 1e-300), np.max(np.abs(a - b))


def _agree(fast, slow, rel=1e-11):
    assert np.array_equal(fast.t, slow.t)
    _close(fast.omega, slow.omega, rel)
    q1, q2 = fast.attitude.as_quat(), slow.attitude.as_quat()
    _close(q1 * np.sign(np.sum(q1 * q2, axis=1))[:, None], q2, rel)
    _close(fast.impulse_world, slow.impulse_world, rel)
    _close(fast.momentum_world, slow.momentum_world, rel)
    if slow.wheel_speed.size:
        _close(fast.wheel_speed, slow.wheel_speed, rel)
        _close(fast.wheel_torque, slow.wheel_torque, rel)
    _close(fast.dipole, slow.dipole, rel)


# --- each formula against its numpy reference -----------------------------------------------------

@pytest.mark.parametrize("field", [DipoleField(ORBIT, gmst0=0.7), DipoleField(ORBIT, gmst0=2.0, earth_rotation=False),
                                   DipoleField(CircularOrbit(altitude=800e3, inclination=0.3)),
                                   UniformField((1e-5, -2e-5, 3e-5))])
def test_the_kernels_field_is_the_models_field(field):
    kind, p = field.loop_form()
    f = loop_terms.field_world
    for t in (0.0, 1.0, 1234.5, 11399.0):
        out = np.array(f(kind, p, cc._NO_TABLE, t))
        np.testing.assert_allclose(out, field.world(t), rtol=1e-13, atol=1e-13 * np.linalg.norm(field.world(t)))


def test_the_kernels_wheel_torque_is_applied_torque_exactly():
    rw = ReactionWheels([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 1.0]], inertia=2e-5,
                        max_torque=[1e-3, 2e-3, 1e-3, 5e-4], max_speed=[600.0, 500.0, np.inf, 600.0],
                        viscous=1e-7, coulomb=[1e-5, 0.0, 2e-5, 1e-5], limit_cycle_speed=[1e-4, 1e-4, 1e-3, 2e-4])
    rng = np.random.default_rng(3)
    f = loop_terms._wheel_torque
    for command, speed in [(rng.normal(size=4) * 2e-3, rng.normal(size=4) * 700.0),
                           ([5e-4, -5e-4, 1e-4, 2e-3], [600.0, -500.0, 0.0, -600.0]),
                           ([0.0, 0.0, 0.0, 0.0], [0.0, -0.0, 1e-300, -1e-300]),
                           (rng.normal(size=4) * 1e-5, rng.normal(size=4) * 3e-4)]:   # in and near the linear region
        expected = rw.applied_torque(command, speed)
        got = [f(float(command[j]), float(speed[j]), rw.max_torque[j], rw.max_speed[j], rw.viscous[j],
                 rw.coulomb[j], rw.limit_cycle_speed[j]) for j in range(4)]
        assert np.array_equal(got, expected)


def test_the_kernels_external_torque_is_the_models_m_x_b_and_gravity_gradient():
    # the impulse's rate in the kernel's right-hand side is R tau, tau = m x R^T B + R^T gg(t, R)
    rng = np.random.default_rng(8)
    field, gg = DipoleField(ORBIT, gmst0=0.2), gravity_gradient_of(ORBIT).bind(CUBESAT)
    kernel = cc.ControlKernel(np.array(CUBESAT), np.diag(1 / np.array(CUBESAT)), None, field, gg, 1e-10, 1e-12)
    rhs = kernel.kernels["rhs"]
    for t in (0.0, 777.0, 5000.0):
        att = Rotation.from_rotvec(rng.normal(size=3))
        dipole, w = rng.normal(size=3) * 0.1, rng.normal(size=3) * 0.2
        y = np.concatenate([att.as_quat(), w, np.zeros(3)])
        P = tuple(kernel.P[:12]) + tuple(dipole) + tuple(kernel.P[15:])
        n_t = gg.mean_motion * t
        out = unpadded(np.array(rhs(t, tuple(padded(y)), P, kernel.X, np.cos(n_t), np.sin(n_t))), 0)
        tau_world = att.apply(np.cross(dipole, att.inv().apply(field.world(t)))) + gg(t, w, att)
        np.testing.assert_allclose(out[7:], tau_world, rtol=1e-12, atol=1e-12 * np.abs(tau_world).max())
        w_dot = (np.cross(dipole, att.inv().apply(field.world(t))) + att.inv().apply(gg(t, w, att))
                 - np.cross(w, np.array(CUBESAT) * w)) / np.array(CUBESAT)  # Euler's equations
        np.testing.assert_allclose(out[4:7], w_dot, rtol=1e-12, atol=1e-12 * np.abs(w_dot).max())


@pytest.mark.parametrize("form", ["normalized", "classic"])
def test_the_kernels_bdot_dipole_is_the_controllers_clipped_by_the_rods(form):
    rods = Magnetorquers([0.2, 0.1], axes=[[1.0, 0.0, 0.0], [0.0, 1.0, 1.0]])
    rng = np.random.default_rng(5)
    f = cd._bdot
    gain = 3e-5 if form == "normalized" else 2e4
    for _ in range(20):
        b, w = rng.normal(size=3) * 3e-5, rng.normal(size=3) * 0.3
        out = f(*b, *w, gain, form == "normalized", rods.rods, rods.max_dipole)
        np.testing.assert_allclose(out, rods.saturate(bdot_dipole(np.cross(b, w), b, gain, form)), rtol=1e-14,
                                   atol=1e-16)


# --- the compiled DOP853 against scipy's: the same steps ------------------------------------------

def _both(**kw):
    return simulate_controlled(compiled=True, **kw), simulate_controlled(compiled=False, **kw)


def test_bdot_in_the_dipole_field_with_gravity_gradient_agrees_with_scipy():
    fast, slow = _both(moments=CUBESAT, omega0=[0.2, -0.2, 0.2], t_end=60.0,
                       controller=BDot(gain=3e-5, period=1.0, form="normalized"), field=DipoleField(ORBIT, gmst0=0.3),
                       gravity_gradient=gravity_gradient_of(ORBIT), magnetorquers=Magnetorquers(0.2),
                       attitude0=Rotation.from_rotvec([0.3, -0.2, 1.0]))
    _agree(fast, slow)
    _close(fast.field, slow.field, 1e-13)
    assert fast.budget_error().max() < 1e-9 * np.abs(fast.impulse_world).max()


def _pointing(**wheel_args):
    rw = ReactionWheels(np.eye(3), inertia=2e-5, **wheel_args)
    c = MRPFeedback(K=2e-3, P=2e-2, period=0.5, moments=[0.03, 0.04, 0.05], wheels=rw)
    return {"moments": [0.03, 0.04, 0.05], "controller": c, "wheels": rw, "attitude0": Rotation.from_rotvec([0.4, -0.3, 0.2])}


def test_mrp_pointing_with_limited_rubbing_wheels_agrees_with_scipy():
    # torque limit, speed limit and friction; the wheels start at rest, so Coulomb friction
    # switches on (sign(0) = 0) and one wheel's speed crosses zero on the way
    kw = _pointing(max_torque=2e-4, max_speed=300.0, viscous=1e-8, coulomb=2e-6)
    fast, slow = _both(omega0=[0.01, -0.02, 0.015], t_end=60.0, wheel_speed0=[0.0, 3.0, -50.0], **kw)
    _agree(fast, slow, rel=1e-10)
    assert np.any(np.abs(fast.wheel_torque) >= 2e-4 - 2e-6 - 1e-8 * 300.0)  # the torque limit was met
    assert np.any(np.diff(np.sign(fast.wheel_speed[:, 1])) != 0)  # a speed crossed zero
    # friction and motors are internal: the total momentum stays put to round-off
    assert fast.budget_error().max() < 1e-15


def test_a_wheel_held_at_its_speed_limit_agrees_with_scipy():
    kw = _pointing(max_torque=1e-3, max_speed=100.0)
    fast, slow = _both(omega0=[0.0, 0.0, 0.05], t_end=20.0, wheel_speed0=[0.0, 0.0, 100.0], **kw)
    _agree(fast, slow)
    # the controller asks wheel 3 to spin up (to take the body's spin); at its limit it may not, so
    # its motor stays off and its absolute axial rate omega_3 + s_3 keeps its value
    assert np.all(fast.wheel_torque[:, 2] == 0.0) and np.any(fast.wheel_torque[:, :2] != 0.0)
    np.testing.assert_allclose(fast.omega[:, 2] + fast.wheel_speed[:, 2], 100.05, rtol=1e-13)
    assert fast.budget_error().max() < 1e-15


def test_the_default_is_the_compiled_path_for_built_in_models(monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError("solve_ivp was called")

    monkeypatch.setattr(controlled, "solve_ivp", refuse)
    run = simulate_controlled(CUBESAT, [0.1, 0.0, 0.1], t_end=5.0, controller=BDot(gain=3e-5, period=1.0,
                              form="normalized"), field=DipoleField(ORBIT), magnetorquers=Magnetorquers(0.2))
    assert run.rate[-1] < run.rate[0]
    with pytest.raises(AssertionError, match="solve_ivp"):
        simulate_controlled(CUBESAT, [0.1, 0.0, 0.1], t_end=5.0, controller=BDot(gain=3e-5, period=1.0),
                            compiled=False)


class Ramp:
    """A field of one's own (T, world frame)."""

    def world(self, t):
        return np.array([3e-5, 1e-7 * t, 0.0])


def test_a_user_model_takes_scipys_path_and_compiled_true_names_it():
    kw = {"moments": CUBESAT, "omega0": [0.1, 0.0, 0.1], "t_end": 3.0, "controller": BDot(gain=3e-5, period=1.0, form="normalized"),
              "field": Ramp(), "magnetorquers": Magnetorquers(0.2)}
    with pytest.raises(ValueError, match=r"compiled=True needs built-in models; field = Ramp \(a DipoleField, "
                                         r"UniformField or IGRFField\) is not one"):
        simulate_controlled(compiled=True, **kw)
    np.testing.assert_array_equal(simulate_controlled(**kw).omega, simulate_controlled(compiled=False, **kw).omega)
    with pytest.raises(ValueError, match="compiled = 'yes' must be True, False or None"):
        simulate_controlled(compiled="yes", **kw)


def test_bdot_obeys_the_exact_energy_relation_of_a_held_dipole():
    # spin w about axis 3, B along world x (square to it), normalised B-dot: the held dipole
    # (k/B^2) w0 x B0 gives the torque -k w0 cos(phi) e3 while the body turns by phi from the
    # step's start, so I3 w dw/dphi = -k w0 cos(phi): w1^2 = w0^2 - 2 k w0 sin(dphi) / I3 exactly,
    # dphi the turn over the step (read from the attitude); roughly w0 (1 - k D / I3) a step
    k, D, I3 = 2e-3, 0.5, 0.03
    run = simulate_controlled([0.01, 0.02, I3], [0.0, 0.0, 0.1], t_end=20.0, compiled=True,
                              controller=BDot(gain=k, period=D, form="normalized"),
                              field=UniformField((3e-5, 0.0, 0.0)), magnetorquers=Magnetorquers(10.0))
    w = run.omega[:, 2]
    np.testing.assert_allclose(run.omega[:, :2], 0.0, atol=1e-17)
    quat = run.attitude.as_quat()
    dphi = np.diff(np.unwrap(2 * np.arctan2(quat[:, 2], quat[:, 3])))
    np.testing.assert_allclose(w[1:] ** 2, w[:-1] ** 2 - 2 * k * w[:-1] * np.sin(dphi) / I3, rtol=1e-11)
    np.testing.assert_allclose(run.rate, 0.1 * (1 - k * D / I3) ** (run.t / D), rtol=1e-3)


# --- the compiled B-dot batch against the numpy batch ---------------------------------------------

@pytest.mark.parametrize("form", ["normalized", "classic"])
def test_the_compiled_detumble_batch_is_the_numpy_batch(form):
    rng = np.random.default_rng(11)
    n = 7
    I = np.array(CUBESAT) * (1 + 0.1 * rng.uniform(-1, 1, (n, 3)))
    w = rng.normal(size=(n, 3)) * 0.2
    q = Rotation.random(n, random_state=4).as_quat()
    kw = {"field": DipoleField(ORBIT), "gmst0": rng.uniform(0, 2 * math.pi, n), "gain": 3e-5 if form == "normalized"
              else 2e4, "magnetorquers": Magnetorquers([0.2, 0.2, 0.1]), "period": 1.0, "t_end": 300.0, "form": form,
              "substeps": 3}
    fast = detumble_batch(I, w, q, **kw)
    slow = detumble_batch(I, w, q, compiled=False, **kw)
    assert np.array_equal(fast.t, slow.t)
    assert np.all(slow.rate[:, -1] < 0.9 * slow.rate[:, 0])  # the rods did work
    _close(fast.rate, slow.rate, 1e-12)
    _close(fast.omega, slow.omega, 1e-12)
    _close(fast.quat, slow.quat, 1e-11)


def test_the_parallel_batch_kernel_gives_each_body_the_same_arithmetic(monkeypatch):
    rng = np.random.default_rng(2)
    n = 40  # more than one block of bodies, the last one partial
    args = (np.array(CUBESAT) * (1 + 0.1 * rng.uniform(-1, 1, (n, 3))), rng.normal(size=(n, 3)) * 0.2,
            Rotation.random(n, random_state=1).as_quat())
    kw = {"field": DipoleField(ORBIT), "gmst0": rng.uniform(0, 2 * math.pi, n), "gain": 3e-5,
          "magnetorquers": Magnetorquers(0.2), "period": 1.0, "t_end": 20.0}
    serial = detumble_batch(*args, **kw)
    monkeypatch.setattr(cd, "PARALLEL_BODIES", 2)
    monkeypatch.setattr(cd, "cores", lambda: 2)
    parallel = detumble_batch(*args, **kw)
    assert np.array_equal(parallel.rate, serial.rate) and np.array_equal(parallel.quat, serial.quat)


@pytest.mark.parametrize(("method", "typed"), [
    ("DOP853", ["_start", "dop853_step"]), ("RK8", ["_fixed_steps", "rk8_step"]), ("RK4", ["_fixed_steps", "rk4_step"])])
def test_a_hold_interval_types_only_its_own_methods_steps(method, typed):
    """The loop's kernels take the hold interval's method as which of three arguments is not None
    (compiled_loop.method_flags): numba drops the other methods' branches before typing them, so a
    run compiles its own method's steps and not the others' (a first run along an ellipse with rk8
    compiled all three: 15.8 CPU-s, 7.7 without the DOP853 and RK4 steps). In a fresh process, an
    uncached compile of the interval, of DOP853's step control and of the fixed steps (the kernels' own may be in the cache,
    whose callees numba then never types): the steps it typed, what numba lists as compiled or loaded."""
    import subprocess
    import sys

    from limits import HANG_S

    code = (
        "import numpy as np\n"
        "from numba import njit\n"
        "from tumble.dynamics.control import compiled_loop as c\n"
        "from tumble.dynamics.control.loop_terms import packed\n"
        "c._fixed_steps = njit(error_model='numpy')(c._fixed_steps.py_func)\n"
        "c.dop853_accept = njit(error_model='numpy')(c.dop853_accept.py_func)\n"
        "advance = njit(error_model='numpy')(c._advance.py_func)\n"
        "P = np.zeros(c.TABLES)\n"
        "P[:12] = (1.0, 2.0, 3.0, 1.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 1 / 3)\n"
        "P = packed(P, (np.zeros(16), np.zeros((4, 1, 3)), np.zeros((4, 1, 3))))\n"
        "y = (0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.1) + (0.0,) * 9\n"
        f"status, y, _ = advance(y, 0.0, 10.0, P, 1e-10, 1e-12, *c.method_flags(c.{method}), 0.5, 0.0, c._turns())\n"
        "steps = ('_start', 'dop853_step', '_fixed_steps', 'rk8_step', 'rk4_step')\n"
        "print(status, round(2 * np.arcsin(y[2]), 6), sorted(n for n in steps if getattr(c, n).signatures))\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=HANG_S)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert proc.stdout == f"0 1.0 {typed}\n"  # 0.1 rad/s about z for 10 s: one radian, and what was typed


def test_skewed_or_doubled_rods_make_the_dipole_asked_for():
    """Rods projected one by one made another dipole than the one asked for where they are not
    orthonormal: [1.5, 0.5, 0] for [1, 0, 0] on rods along x, (x + y)/sqrt(2) and z; twice the command
    for two rods on x (a walkthrough, issue 40). Allocated by G^+ they make it, within their limits,
    in the numpy path and in the compiled B-dot alike."""
    rng = np.random.default_rng(11)
    m = rng.normal(size=(50, 3))
    for axes in ([[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                 [[1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                 [[1.0, 1.0, 0.0], [0.0, 1.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.0]]):
        rods = Magnetorquers(100.0, axes=axes)
        np.testing.assert_allclose(rods.saturate(m), m, rtol=0, atol=1e-13)
        b, w = rng.normal(size=3) * 3e-5, rng.normal(size=3) * 0.3
        asked = bdot_dipole(np.cross(b, w), b, 2e4, "classic")
        np.testing.assert_allclose(cd._bdot(*b, *w, 2e4, False, rods.rods, rods.max_dipole), rods.saturate(asked),
                                   rtol=1e-14, atol=1e-16)
    # two rods on x share a command of 1.5 A m^2 (0.75 each) within their 1 A m^2: the whole of it; 3 is clipped to 2
    double = Magnetorquers(1.0, axes=[[1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    np.testing.assert_allclose(double.saturate([[1.5, 0.0, 0.0], [3.0, 0.0, 0.0]]), [[1.5, 0.0, 0.0], [2.0, 0.0, 0.0]])
