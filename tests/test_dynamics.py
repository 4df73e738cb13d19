"""Euler's equations, attitude, torques: checked against closed forms and invariants."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import tumble
from tumble.dynamics import (
    METHODS,
    ConstantTorque,
    FunctionTorque,
    TorqueModel,
    euler_rhs,
    euler_rhs_tensor,
    kinetic_energy,
    simulate,
)
from tumble.dynamics.methods.bounds import spin_gain
from tumble.dynamics.models.torques import (
    BoundsSpin,
    NeedsBody,
    as_torque,
    bind_to_body,
)
from tumble.mass import MassProperties


def free_body(moments):
    """A body with given principal moments along the design axes (no parts needed)."""
    return MassProperties.from_moments(moments)


def test_principal_and_full_tensor_forms_agree(rng):
    # Euler's equations in the design frame with the full tensor, against the principal form
    body = tumble.load_body("iss-t-handle").moved(Rotation.from_rotvec([0.3, -0.2, 0.9]))
    A = body.principal_axes
    for _ in range(20):
        w_p, tau_p = rng.normal(size=3), rng.normal(size=3) * 1e-4
        rhs_design = euler_rhs_tensor(A @ w_p, body.inertia, A @ tau_p)
        np.testing.assert_allclose(rhs_design, A @ euler_rhs(w_p, body.principal_moments, tau_p), rtol=1e-9, atol=1e-9)


def test_euler_rhs_broadcasts(rng):
    w, I = rng.normal(size=(4, 5, 3)), rng.uniform(1, 2, size=(4, 5, 3))
    batch = euler_rhs(w, I)
    assert batch.shape == (4, 5, 3)
    np.testing.assert_allclose(batch[2, 3], euler_rhs(w[2, 3], I[2, 3]))
    # energy is conserved by the right-hand side: dE/dt = omega . I omega' = 0 without torque
    np.testing.assert_allclose(np.sum(I * w * batch, axis=-1), 0.0, atol=1e-12)


@pytest.mark.parametrize("torque", ["none", "scalar", "vector"])
def test_euler_rhs_of_one_sample_is_the_batchs_row_bit_for_bit(rng, torque):
    """One body at one instant takes plain floats (a Python right-hand side's every call), a batch
    numpy's columns: the same formula, so the same bits; a zero moment gives inf with numpy's warning."""
    w, I = rng.normal(size=(200, 3)) * 10.0, rng.uniform(0.01, 3.0, size=(200, 3))
    tau = {"none": np.zeros((200, 3)), "scalar": np.full((200, 3), 0.3), "vector": rng.normal(size=(200, 3))}[torque]
    batch = euler_rhs(w, I, tau)
    for k in range(200):
        one = euler_rhs(w[k], I[k], 0.3 if torque == "scalar" else tau[k])
        assert one.shape == (3,) and np.array_equal(one, batch[k]), k
    with pytest.warns(RuntimeWarning, match="divide by zero"):
        assert euler_rhs([1.0, 1.0, 1.0], [0.0, 1.0, 2.0])[0] == -np.inf


def test_quaternion_rate_of_one_instant_is_the_batchs_row_bit_for_bit(rng):
    from tumble.dynamics.special.quaternion import quaternion_rate

    q, w = rng.normal(size=(200, 4)), rng.normal(size=(200, 3)) * 10.0
    batch = quaternion_rate(q, w)
    assert all(np.array_equal(quaternion_rate(q[k], w[k]), batch[k]) for k in range(200))
    assert quaternion_rate(q[0], w[0]).shape == (4,)


# -- conservation ------------------------------------------------------------------------

@pytest.mark.parametrize("preset", ["t-handle", "iss-t-handle"])
@pytest.mark.parametrize("axis", [0, 1, 2])
def test_dop853_conserves_energy_L_and_L_world(preset, axis):
    """rtol 1e-12 per step over ~1e3-1e4 steps: bounded by 1e-9 relative (measured ~1e-11)."""
    w0 = np.full(3, 0.1)
    w0[axis] = 10.0
    traj = simulate(tumble.load_body(preset), w0, t_end=20.0, method="dop853")
    for key, value in traj.drift.items():
        assert value < 1e-9, (key, value)
    np.testing.assert_allclose(np.linalg.norm(traj.quat, axis=1), 1.0, atol=1e-15)


def test_rk45_at_default_tolerances_drifts_like_the_seed():
    """The seed's integrator (rtol 1e-3) on its own first case: energy drifts by ~1e-2 in 20 s."""
    traj = simulate(tumble.t_handle(), [10.0, 0.1, 0.1], frame="design", t_end=20.0, method="rk45")
    assert traj.drift["energy"] > 1e-3
    assert traj.drift["L_world"] > 1e-3
    tight = simulate(tumble.t_handle(), [10.0, 0.1, 0.1], frame="design", t_end=20.0, method="dop853")
    assert traj.drift["energy"] > 1e6 * tight.drift["energy"]


# -- torques -----------------------------------------------------------------------------

@pytest.mark.parametrize("axis", [0, 1, 2])
def test_constant_body_torque_from_rest(axis):
    """At rest with tau along principal axis k: omega_k = tau t / I_k, the others stay 0."""
    body = tumble.iss_t_handle()
    tau = np.zeros(3)
    tau[axis] = 1e-5
    traj = simulate(body, [0, 0, 0], t_end=2.0, samples=50, torque=ConstantTorque(tuple(tau)))
    expected = np.outer(traj.t, tau / body.principal_moments)
    np.testing.assert_allclose(traj.omega, expected, rtol=1e-10, atol=1e-12 * expected.max())


def test_constant_world_torque_changes_L_world_linearly():
    """dL_world/dt = tau_world (Euler's second law in the inertial frame)."""
    body = tumble.t_handle()
    tau = np.array([0.02, -0.01, 0.03])
    traj = simulate(body, [0.3, 2.0, -0.5], t_end=5.0, samples=100, torque=ConstantTorque(tuple(tau), "world"))
    L0 = traj.angular_momentum_world[0]
    np.testing.assert_allclose(traj.angular_momentum_world, L0 + np.outer(traj.t, tau), atol=1e-9)
    assert not traj.torque_free


def test_symmetric_top_precession():
    """Torque-free oblate top (I1 = I2 < I3), Landau & Lifshitz secs. 36 and 33:
    in the body, omega_perp turns at (I3 - I1) omega_3 / I1; in space, the symmetry axis
    precesses about L at |L| / I1."""
    body = tumble.Body([tumble.Cylinder(mass=2.0, radius=0.5, length=0.1)])
    I1, _, I3 = body.principal_moments
    w0 = np.array([0.4, 0.0, 3.0])
    traj = simulate(body, w0, t_end=4.0, samples=400)
    rate_body = (I3 - I1) * w0[2] / I1
    angle = np.unwrap(np.arctan2(traj.omega[:, 1], traj.omega[:, 0]))
    np.testing.assert_allclose(angle, rate_body * traj.t, atol=1e-9)
    # space: angle of the symmetry axis about L_world
    L = traj.angular_momentum_world[0]
    n = L / np.linalg.norm(L)
    e3 = traj.attitude.apply(np.array([0.0, 0.0, 1.0]))
    u = np.cross(n, [1.0, 0.0, 0.0])
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    phi = np.unwrap(np.arctan2(e3 @ v, e3 @ u))
    np.testing.assert_allclose(phi - phi[0], np.linalg.norm(L) / I1 * traj.t, atol=1e-8)


# -- attitude ----------------------------------------------------------------------------

def test_seed_update_converges_at_first_order():
    """R <- R exp([w] dt) from sampled w: attitude error halves when dt halves."""
    body = tumble.iss_t_handle()
    ref = {}
    errors = []
    for n in (201, 401, 801):
        exact = simulate(body, [1.0, 8.0, 0.5], t_end=2.0, samples=n, method="dop853", rtol=1e-13)
        seed = simulate(body, [1.0, 8.0, 0.5], t_end=2.0, samples=n, method="seed", rtol=1e-12, atol=1e-12)
        err = (seed.attitude[-1] * exact.attitude[-1].inv()).magnitude()
        errors.append(err)
        ref[n] = exact.attitude[-1]
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    np.testing.assert_allclose(ratios, 2.0, rtol=0.1)
    # and the accurate attitudes agree with each other whatever the sampling
    assert (ref[201] * ref[801].inv()).magnitude() < 1e-9


def test_design_frame_input_and_initial_attitude():
    body = tumble.t_handle()
    a = simulate(body, [10.0, 0.1, 0.1], frame="design", t_end=1.0, samples=20)
    b = simulate(body, [0.1, 10.0, 0.1], frame="principal", t_end=1.0, samples=20)
    np.testing.assert_allclose(a.omega, b.omega, rtol=1e-12)
    # at t = 0 the design frame coincides with the world frame (to the round-off of the
    # exact solution's four compositions of rotations)
    np.testing.assert_allclose(a.design_attitude()[0].as_matrix(), np.eye(3), atol=1e-14)
    rot = Rotation.from_rotvec([0.0, 0.0, 0.5])
    c = simulate(body, [10.0, 0.1, 0.1], frame="design", t_end=1.0, samples=20, attitude0=rot)
    np.testing.assert_allclose(c.angular_momentum_world, rot.apply(a.angular_momentum_world), atol=1e-9)


def test_energy_matches_definition():
    traj = simulate(tumble.t_handle(), [1.0, 2.0, 3.0], t_end=0.1, samples=3)
    I = traj.moments
    np.testing.assert_allclose(traj.energy[0], 0.5 * (I[0] * 1 + I[1] * 4 + I[2] * 9))
    np.testing.assert_allclose(kinetic_energy(traj.omega, I), traj.energy)


# -- bad input ---------------------------------------------------------------------------

@pytest.mark.parametrize(
    ("kwargs", "pattern"),
    [
        (dict(omega0=[1, 2]), r"omega0 = \[1, 2\] must be a list of 3 numbers \(rad/s\)"),
        (dict(omega0=[1, np.nan, 0]), r"omega0\[1\] = nan must be a finite"),
        (dict(t_end=-1.0), r"t_end = -1.0 must be a positive"),
        (dict(samples=1), r"samples = 1 must be a whole number from 2"),
        (dict(samples=2.5), r"samples = 2.5 must be a whole number"),
        (dict(method="euler"), r"method = 'euler' is unknown; allowed: auto, exact, dop853, rk45, seed, geometric"),
        (dict(frame="world"), r"frame = 'world' is not allowed; allowed: principal, design"),
        (dict(rtol=0.0), r"rtol = 0.0 must be a positive"),
        (dict(method="seed", torque=ConstantTorque((0, 0, 1.0))), r"method = 'seed' cannot take a torque"),
        # what a new user tries first (seen 2026-11-30): a vector for a constant torque, a function
        # of (t, omega), three moments for a body; each message says what to give instead
        (dict(torque=(0, 0, 1)), r"^torque = \(0, 0, 1\) is a vector, not a torque model: for a constant torque "
                                 r"give tumble.ConstantTorque\(\(0.0, 0.0, 1.0\)\) \(N m, body frame"),
        (dict(torque=lambda t, w: w), r"^torque = <lambda>\(t, w\) cannot be called as tau\(t, omega, attitude\)"),
        (dict(torque="gravity"), r"^torque = 'gravity' must be a function called as tau\(t, omega, attitude\)$"),
        # not three numbers: one line of tumble's, not numpy's ("inhomogeneous shape", "could not convert", len())
        # a list is a sum of torque models: its first item that is none is named
        (dict(torque=[1, [2, 3], 4]), r"^torque\[0\] = 1 must be a function called as tau\(t, omega, attitude\) "
                                      r"\(a list is the sum of its torque models\)$"),
        (dict(torque=("a", "b", "c")), r"^torque\[0\] = 'a' must be a function called as tau"),
        (dict(torque=[tumble.ConstantTorque((0.0, 0.0, 1.0)), (0.0, 1.0, 0.0)]),
         r"^torque\[1\] = \(0.0, 1.0, 0.0\) is a vector, not a torque model: for a constant torque give "
         r"tumble.ConstantTorque\(\(0.0, 1.0, 0.0\)\)"),
        (dict(torque=[]), r"^torque = \[\] is an empty sum: give a torque model, a list of them, or None$"),
        (dict(torque=np.array(2.0)), r"^torque = array\(2.0\) must be a function called as tau"),
        (dict(body=[1.0, 2.0, 3.0]), r"^body = \[1.0, 2.0, 3.0\] must be a tumble Body or MassProperties; for principal "
                                     r"moments alone: tumble.MassProperties.from_moments\(\[1.0, 2.0, 3.0\]\)$"),
        (dict(body=np.array([1.0, 2.0, 3.0])), r"from_moments\(\[1.0, 2.0, 3.0\]\)$"),
        (dict(body=np.array(5.0)), r"^body = .*5.0.* must be a tumble Body or MassProperties$"),  # was len()'s TypeError
    ],
)
def test_bad_simulate_input(kwargs, pattern):
    args = dict(body=tumble.t_handle(), omega0=[1.0, 0.0, 0.0], t_end=1.0)
    args.update(kwargs)
    body, omega0 = args.pop("body"), args.pop("omega0")
    with pytest.raises(ValueError, match=pattern):
        simulate(body, omega0, **args)


def test_a_body_with_a_zero_moment_is_refused():
    with pytest.raises(ValueError, match="zero moment"):
        simulate(tumble.Body([tumble.Rod(mass=1.0, length=1.0)]), [1, 0, 0], t_end=1.0)


def test_registry_names_every_method():
    assert set(METHODS) >= {"exact", "rk45", "dop853", "seed", "geometric", "geometric2", "geometric6"}


# the compiled-only steppers (rk4, rk8) refuse any Python torque before it is called (tests/test_engine.py)
@pytest.mark.parametrize("method", [name for name, m in METHODS.items() if m.supports_torque and not m.compiled_only])
def test_a_bad_torque_model_gets_a_clear_error_from_every_method(method):
    bad = FunctionTorque(lambda t, w, att: [1.0, 2.0], "body")
    with pytest.raises(ValueError, match=r"the torque model returned \[1.0, 2.0\] at t = 0 s; expected finite numbers"):
        simulate(tumble.t_handle(), [1.0, 0.0, 0.0], t_end=0.1, samples=3, method=method, torque=bad)


def test_body_torque_in_design_coordinates():
    """frame="design" reads a body-frame torque in design axes: a torque about the T-handle's
    crossbar (design x = principal axis 2) spins it up about that axis alone, w = tau t / I_x."""
    body = tumble.t_handle()
    traj = simulate(body, [0.0, 0.0, 0.0], frame="design", t_end=2.0, samples=11,
                    torque=ConstantTorque((0.03, 0.0, 0.0)))
    omega_design = traj.omega @ body.principal_axes.T
    np.testing.assert_allclose(omega_design, np.outer(traj.t, [0.03 / 0.3125, 0.0, 0.0]), atol=1e-12)


# -- the declared torque-model interface (tumble.dynamics.TorqueModel and its optional parts) ------

class _SpinAboutMajor:
    """A duck-typed model (no base class): ``tau = (0, 0, k I3)``, body frame; needs the moments."""

    frame = "body"

    def __init__(self, k, moments=None):
        self.k, self.moments = k, moments

    def bind(self, body):
        return type(self)(self.k, np.asarray(getattr(body, "principal_moments", body), float))

    def __call__(self, t, omega, attitude):
        if self.moments is None:
            raise AssertionError("called before bind")
        return self.k * self.moments[..., 2:3] * np.array([0.0, 0.0, 1.0])


def test_the_torque_interface_is_declared_and_checked_by_protocol():
    model = _SpinAboutMajor(0.5)
    assert isinstance(model, TorqueModel) and isinstance(model, NeedsBody) and not isinstance(model, BoundsSpin)
    assert as_torque(model) is model  # a model passes through; a plain function is wrapped, body frame
    assert not isinstance(lambda t, w, a: np.zeros(3), TorqueModel)
    assert as_torque(lambda t, w, a: np.zeros(3)).frame == "body"
    assert isinstance(tumble.dynamics.GravityGradient(orbit_period=5400.0), BoundsSpin)
    constant = ConstantTorque((0.0, 0.0, 1.0))
    assert bind_to_body(constant, [1.0, 2.0, 3.0]) is constant and bind_to_body(None, [1.0, 2.0, 3.0]) is None
    np.testing.assert_array_equal(bind_to_body(model, free_body([1.0, 2.0, 3.0])).moments, [1.0, 2.0, 3.0])


def test_simulate_and_simulate_batch_bind_a_model_that_needs_the_body():
    # from rest, tau = k I3 e3 spins the body about its major axis: omega3 = k t for any I3
    k, t = 0.5, np.linspace(0.0, 2.0, 5)
    run = simulate(free_body([1.0, 2.0, 3.0]), [0.0, 0.0, 0.0], times=t, torque=_SpinAboutMajor(k))
    np.testing.assert_allclose(run.omega[:, 2], k * t, rtol=1e-10, atol=1e-12)
    batch = tumble.simulate_batch([[1.0, 2.0, 3.0], [2.0, 2.5, 4.0]], [0.0, 0.0, 0.0], times=t,
                                  method="geometric", torque=_SpinAboutMajor(k))
    np.testing.assert_allclose(batch.omega[:, :, 2], np.broadcast_to(k * t, (2, len(t))), rtol=1e-12, atol=1e-12)


def test_a_model_that_bounds_its_spin_is_asked_for_the_bound():
    class Bounded(_SpinAboutMajor):
        def max_spin(self, t, omega, attitude):
            return np.full(np.shape(omega)[:-1], 7.0)  # rad/s, whatever the torque

    model = Bounded(0.5).bind([1.0, 2.0, 3.0])
    assert isinstance(model, BoundsSpin)
    w = np.array([0.0, 3.0, 4.0])  # |w| = 5 rad/s: the model can add at most 2 rad/s, for any duration
    assert spin_gain(model, 0.0, w, Rotation.identity(), [1.0, 2.0, 3.0], 1e6) == pytest.approx(2.0, rel=1e-15)
    # without max_spin: |tau| duration / I1 = 0.5 * 3 * 10 / 1
    assert spin_gain(_SpinAboutMajor(0.5, np.array([1.0, 2.0, 3.0])), 0.0, w, Rotation.identity(),
                     [1.0, 2.0, 3.0], 10.0) == pytest.approx(15.0, rel=1e-15)


# -- the methods' declared capabilities (what simulate and simulate_batch read, never a name) -------

@pytest.mark.parametrize("name", METHODS)
def test_every_method_declares_its_capabilities_consistently(name):
    m = METHODS[name]
    assert m.name == name
    assert isinstance(m.closed_form, bool) and isinstance(m.stiff_solver, bool)
    # the fixed-step methods: the splittings, and the engine's Runge-Kutta steppers (compiled only)
    assert (m.splitting_order is not None or m.compiled_only) == m.fixed_step
    assert m.splitting_order in (None, 2, 4, 6)
    assert m.batched == (m.closed_form or m.splitting_order is not None)
    if m.closed_form:  # no steps and no tolerances, so nothing to carry a torque, rotors or a damper
        assert not m.fixed_step and m.rtol is None and m.atol is None
        assert not m.supports_torque and not m.supports_internal
    if m.stiff_solver:  # an adaptive method that takes a damper
        assert m.supports_internal and not m.fixed_step and not m.closed_form and m.rtol is not None


@pytest.mark.parametrize("name", [name for name, m in METHODS.items() if m.closed_form])
def test_a_closed_form_method_takes_no_step_from_t_0(name):
    # asked for t = 7 s alone (not starting at 0), it gives what it gives at t = 7 s on a grid from 0
    I, w0, q0 = np.array([1.0, 2.0, 3.0]), np.array([0.3, 1.0, 0.2]), Rotation.from_rotvec([0.1, 0.2, 0.3]).as_quat()
    integrate = METHODS[name].integrate
    alone = integrate(I, w0, q0, np.array([7.0]), None, None, None)
    grid = integrate(I, w0, q0, np.array([0.0, 2.5, 7.0]), None, None, None)
    for a, b in zip(alone, grid):
        np.testing.assert_allclose(a[0], b[-1], rtol=0, atol=1e-14)
    np.testing.assert_allclose(grid[0][0], w0, rtol=0, atol=1e-15)  # and t = 0 is the initial state


def test_the_order_table_is_read_from_the_methods():
    # simulate_batch takes each splitting's composition order from its Method, not from its name
    assert {n: m.splitting_order for n, m in METHODS.items() if m.splitting_order} == {
        "geometric": 4, "geometric2": 2, "geometric6": 6, "exact_split2": 2, "exact_split4": 4, "exact_split6": 6}


@pytest.mark.parametrize("omega0", [[10**400, 0, 0], (0.0, 1.0, 10**400)])
def test_an_integer_beyond_any_float_is_refused_in_one_line(omega0):
    """A Python int too large for a float (10**400) raised OverflowError from float(); it is bad
    input, named by its index, like any other non-finite number."""
    with pytest.raises(ValueError, match=r"^omega0\[\d\] = 1000+ must be a finite number \(rad/s\)$"):
        simulate(tumble.t_handle(), omega0, t_end=1.0)


def test_rk45_honours_an_rtol_given_alone_on_a_slow_body():
    """scipy's default atol (1e-6 rad/s) would cap rk45's accuracy on a body turning at 1e-3 rad/s
    (issue 38: rtol 1e-10 gave 1.2e-5 relative); an rtol given alone brings atol down with it,
    relative to the spin. Against the closed form (elliptic functions), omega and attitude."""
    body = MassProperties.from_moments([1.0, 2.0, 3.0])
    w0 = [1e-4, 1e-3, 1e-4]
    exact = simulate(body, w0, t_end=2000.0, samples=11)
    run = simulate(body, w0, t_end=2000.0, samples=11, method="rk45", rtol=1e-10)
    assert np.max(np.abs(run.omega - exact.omega)) / 1e-3 < 1e-9
    assert np.max((run.attitude * exact.attitude.inv()).magnitude()) < 1e-8
    given = simulate(body, w0, t_end=2000.0, samples=11, method="rk45", rtol=1e-10, atol=1e-6)  # as asked
    assert np.max(np.abs(given.omega - exact.omega)) / 1e-3 > 1e-8
