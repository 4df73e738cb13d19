"""Rotors and the gyrostat: the Rotor part, the internal momentum, Euler's equations of a
gyrostat against closed forms and an independently written system, the energy budget of the
motors, the wheel that stops the Dzhanibekov flip, and every integrator that takes rotors.

Closed forms used here:
- a wheel spun up from rest (L = 0): ``I w = -h`` at every instant, so the body turns about the
  wheel's (principal) axis by ``-integral h dt / I_k``;
- the linearised rate about a spin W about axis 2 with ``h e2``, derived in the test from the
  Jacobian of ``I w' = -w x (I w + h)`` (not from tumble);
- the motors' power ``P = sum_k J_k s_k (n_k.w' + s_k')``, with ``w'`` from the test's own
  gyrostat equation ``I w' = -w x (I w + h) - h'``.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import cumulative_simpson, solve_ivp
from scipy.spatial.transform import Rotation

import tumble
from tumble.analysis import flip_interval, stable_spin_range
from tumble.dynamics import METHODS, gyrostat_rate, simulate
from tumble.io.bodyfile import load_body
from tumble.io.report import mass_properties_dict, mass_properties_table

BOX = tumble.Box(mass=3.0, size=(0.6, 0.4, 0.2))  # principal axes 1, 2, 3 = design x, y, z
SPLITTING = [name for name, m in METHODS.items() if m.fixed_step and m.supports_internal]  # into exact rotations
#: The methods that take rotors, and those that refuse them.
INTERNAL = [name for name, m in METHODS.items() if m.supports_internal]
NO_INTERNAL = [name for name in METHODS if name not in INTERNAL]
S, NU = 300.0, 3.0  # a commanded wheel: s(t) = S sin(NU t), rad/s


def wheel_body(axis=(0.0, 1.0, 0.0), *, mass=0.2, radius=0.05, center=(0.0, 0.0, 0.0), **spin) -> tumble.Body:
    return tumble.Body([BOX, tumble.Rotor(mass=mass, radius=radius, length=0.01, axis=axis, center=center, **spin)])


def commanded(axis=(1.0, 1.0, 1.0), center=(0.1, 0.0, 0.0), derivative=True) -> tumble.Body:
    extra = {"spin_acceleration": lambda t: S * NU * np.cos(NU * t)} if derivative else {}
    return wheel_body(axis, center=center, spin_rate=lambda t: S * np.sin(NU * t), **extra)


def gyrostat_omega_form(body, *, rtol=1e-13):
    """An independent right-hand side: ``I w' = -w x (I w + h) - h'`` and ``R' = R [w]_x``
    (rotation matrix, 9 components), in the principal frame."""
    I = body.principal_moments
    rotor = body.rotors[0]
    n = body.principal_axes.T @ np.array(rotor.axis)
    J = 0.5 * rotor.mass * rotor.radius**2

    def h(t):
        return J * rotor.spin(t) * n

    def hdot(t):
        return J * rotor.spin_derivative(t) * n

    def rhs(t, y):
        w, R = y[:3], y[3:].reshape(3, 3)
        wx = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        return np.concatenate([(-np.cross(w, I * w + h(t)) - hdot(t)) / I, (R @ wx).ravel()])

    def solve(w0, R0, t):
        sol = solve_ivp(rhs, (t[0], t[-1]), np.concatenate([w0, np.ravel(R0)]), method="DOP853", t_eval=t,
                        rtol=rtol, atol=1e-14)
        return sol.y[:3].T, sol.y[3:].T.reshape(-1, 3, 3), h, hdot

    return solve


# -- the part and the body ----------------------------------------------------------------------

def test_a_rotor_weighs_like_its_cylinder():
    kw = dict(density=7850.0, radius=0.05, length=0.02, axis=(1.0, 2.0, 2.0), center=(0.1, -0.2, 0.3))
    rotor, cyl = tumble.Rotor(spin_rate=100.0, **kw), tumble.Cylinder(**kw)
    assert rotor.mass == cyl.mass == pytest.approx(7850.0 * np.pi * 0.05**2 * 0.02, rel=1e-15)
    np.testing.assert_array_equal(rotor.inertia, cyl.inertia)
    assert rotor.axial_moment == pytest.approx(0.5 * rotor.mass * 0.05**2, rel=1e-15)
    body = tumble.Body([BOX, rotor])
    np.testing.assert_allclose(body.inertia, tumble.Body([BOX, cyl]).inertia, rtol=0, atol=0)
    assert body.rotors == (rotor,)


def test_internal_momentum_in_the_principal_frame():
    """A wheel along the T-handle's crossbar (design x) lies on principal axis 2."""
    th = tumble.t_handle()
    wheel = tumble.Rotor(mass=0.3, radius=0.08, length=0.02, axis=(-1, 0, 0), center=(0, 0, 0.25),
                         spin_rate=100.0, spin_acceleration=-20.0)
    body = tumble.Body([*th.parts, wheel], name="T-handle with wheel")
    J = 0.5 * 0.3 * 0.08**2
    t = np.array([0.0, 0.5, 2.0, 7.5])
    h = body.internal_momentum(t)
    expected = np.zeros((4, 3))
    expected[:, 1] = -J * (100.0 - 20.0 * t)  # the axis points along -x = -e2
    np.testing.assert_allclose(h, expected, rtol=1e-15, atol=1e-18)
    assert body.internal_momentum(1.0).shape == (3,)
    np.testing.assert_array_equal(th.internal_momentum([0.0, 1.0]), np.zeros((2, 3)))
    assert th.rotors == ()


def test_oblique_rotor_momentum_has_the_right_length_and_direction():
    body = wheel_body((1.0, 2.0, -2.0), spin_rate=50.0)
    h = body.internal_momentum(0.0)
    J = 0.5 * 0.2 * 0.05**2
    assert np.linalg.norm(h) == pytest.approx(50.0 * J, rel=1e-14)
    np.testing.assert_allclose(body.principal_axes @ h, 50.0 * J * np.array([1.0, 2.0, -2.0]) / 3.0, rtol=1e-13)


@pytest.mark.parametrize(
    ("kwargs", "pattern"),
    [
        (dict(spin_rate="fast"), r"^spin_rate = 'fast' must be a number \(rad/s\) or a function of time"),
        (dict(spin_rate=float("nan")), r"^spin_rate = nan must be a finite number \(rad/s\)$"),
        (dict(spin_rate=True), r"^spin_rate = True must be a number"),
        (dict(spin_rate=1.0, spin_acceleration=float("inf")), r"^spin_acceleration = inf must be a finite number \(rad/s\^2\)$"),
        (dict(spin_rate=1.0, spin_acceleration=lambda t: 0.0), r"^spin_acceleration = .* is a function but spin_rate = 1.0 is a number"),
        (dict(spin_rate=lambda t: t, spin_acceleration=2.0), r"^spin_acceleration = 2.0 must be a function of time"),
        (dict(spin_rate=1.0, subtract=True), r"^subtract = True is not allowed for a rotor"),
        (dict(), r"spin_rate"),
    ],
)
def test_rotor_refuses_bad_spins(kwargs, pattern):
    with pytest.raises((ValueError, TypeError), match=pattern):
        tumble.Rotor(mass=1.0, radius=0.1, length=0.02, **kwargs)


def test_a_spin_function_returning_nonsense_is_named():
    rotor = tumble.Rotor(mass=1.0, radius=0.1, length=0.02, spin_rate=lambda t: float("nan") if t > 1 else 1.0)
    with pytest.raises(ValueError, match=r"^the rotor's spin_rate function returned nan at t = 2 s"):
        rotor.spin([0.0, 2.0])


def test_rotor_in_a_body_file(tmp_path):
    path = tmp_path / "wheel.toml"
    path.write_text(
        '[body]\nname = "box with wheel"\n'
        '[[body.parts]]\nkind = "box"\nmass = 3.0\nsize = [0.6, 0.4, 0.2]\n'
        '[[body.parts]]\nkind = "rotor"\nmass = 0.2\nradius = 0.05\nlength = 0.01\naxis = [0.0, 1.0, 0.0]\n'
        'spin_rate = 100.0\nspin_acceleration = 5.0\n'
    )
    body = tumble.load_body(path)
    expected = wheel_body(spin_rate=100.0, spin_acceleration=5.0)
    np.testing.assert_array_equal(body.inertia, expected.inertia)
    np.testing.assert_allclose(body.internal_momentum([0.0, 2.0]), expected.internal_momentum([0.0, 2.0]), rtol=1e-15)
    path.write_text(path.read_text().replace("spin_rate = 100.0", 'spin_rate = "fast"'))
    with pytest.raises(ValueError, match=r"parts\[1\] \(rotor\): spin_rate = 'fast' must be a number \(rad/s\)"):
        tumble.load_body(path)


# -- a reaction wheel spun up from rest --------------------------------------------------------

@pytest.mark.parametrize("method", INTERNAL)
@pytest.mark.parametrize("axis", [1, 2, 3])
def test_wheel_spun_up_from_rest_turns_the_body_the_other_way(axis, method):
    """L stays 0: ``I_k w_k = -h_k`` to round-off, and the body turns about the wheel's axis by
    ``-J a t^2 / (2 I_k)`` (a linear ramp of the wheel, a = 10 rad/s^2; up to 1.8 rad): to
    round-off with the splitting methods (the midpoint rule is exact for a linear h; measured
    4e-15), to DOP853's tolerance (measured 5e-12)."""
    e = np.eye(3)[axis - 1]
    a = 10.0
    body = wheel_body(tuple(e), mass=1.0, radius=0.1, spin_rate=0.0, spin_acceleration=a)
    I = body.principal_moments
    J = 0.5 * 1.0 * 0.1**2
    traj = simulate(body, [0.0, 0.0, 0.0], t_end=2.0, samples=21, method=method)
    h = J * a * traj.t[:, None] * e
    np.testing.assert_allclose(traj.internal_momentum, h, rtol=1e-15, atol=0)
    np.testing.assert_allclose(I * traj.omega, -h, rtol=0, atol=1e-15 * J * a * 2.0)
    np.testing.assert_allclose(traj.angular_momentum_world, 0.0, atol=1e-15 * J * a * 2.0)
    turned = (traj.attitude[0].inv() * traj.attitude).as_rotvec()
    np.testing.assert_allclose(turned, -J * a * traj.t[:, None] ** 2 / (2 * I[axis - 1]) * e,
                               rtol=0, atol={"rk45": 1e-3, "dop853": 1e-11}.get(method, 1e-14))


@pytest.mark.parametrize(("method", "kwargs", "tol"), [("dop853", {}, 1e-10), ("geometric", {"step": 1e-3}, 1e-10)])
def test_commanded_wheel_turns_the_body_by_the_integral_of_h(method, kwargs, tol):
    """A wheel commanded ``s = S sin(NU t)`` along axis 2 of a body at rest: the body turns by
    ``-J S (1 - cos NU t) / (NU I2)``."""
    body = wheel_body(spin_rate=lambda t: S * np.sin(NU * t), spin_acceleration=lambda t: S * NU * np.cos(NU * t))
    I2 = body.principal_moments[1]
    J = 0.5 * 0.2 * 0.05**2
    traj = simulate(body, [0.0, 0.0, 0.0], t_end=3.0, samples=31, method=method, **kwargs)
    np.testing.assert_allclose(traj.omega[:, 1], -J * S * np.sin(NU * traj.t) / I2, rtol=0, atol=1e-15)
    angle = (traj.attitude[0].inv() * traj.attitude).as_rotvec()
    np.testing.assert_allclose(angle[:, 1], -J * S * (1 - np.cos(NU * traj.t)) / (NU * I2), rtol=0, atol=tol)
    np.testing.assert_allclose(angle[:, [0, 2]], 0.0, atol=1e-15)


# -- Euler's equations of the gyrostat ----------------------------------------------------------

def test_dop853_matches_an_independently_written_gyrostat():
    """A tumbling body, an oblique commanded wheel off the centre of mass: simulate's momentum
    form against the test's own omega form with a rotation matrix, both DOP853."""
    body = commanded()
    w0 = np.array([1.0, 8.0, -2.0])
    traj = simulate(body, w0, t_end=3.0, samples=61, method="dop853", rtol=1e-13)
    omega, R, h, _ = gyrostat_omega_form(body)(w0, traj.attitude[0].as_matrix(), traj.t)
    np.testing.assert_allclose(traj.omega, omega, rtol=0, atol=1e-10 * np.linalg.norm(w0))
    assert np.max((traj.attitude * Rotation.from_matrix(R).inv()).magnitude()) < 1e-10
    np.testing.assert_allclose(traj.internal_momentum, h(traj.t[:, None]), rtol=1e-15)
    L_world = np.einsum("nij,nj->ni", R, body.principal_moments * omega + h(traj.t[:, None]))
    np.testing.assert_allclose(traj.angular_momentum_world, L_world, atol=1e-10)
    assert traj.drift["L_world"] < 1e-10  # measured 9e-12 (DOP853 at rtol 1e-13 over 3 s)


# one adaptive and one splitting method (the 4th-order default) at the tolerances stated below
@pytest.mark.parametrize("method", ["dop853", "geometric"])
def test_motor_power_is_the_rate_of_the_total_kinetic_energy(method):
    """``T = w.I w / 2 + w.h + J s^2 / 2`` changes by the integral of the motor power
    ``P = J s (n.w' + s')`` (w' from the test's own gyrostat equation), to 1e-9 of T0 (measured
    8.6e-11 with DOP853, 2.3e-10 with the 4th-order splitting at 1 ms; T changes by 3.2 T0)."""
    body = commanded()
    I, rotor = body.principal_moments, body.rotors[0]
    n = body.principal_axes.T @ np.array(rotor.axis)
    J = 0.5 * rotor.mass * rotor.radius**2
    w0 = np.array([1.0, 8.0, -2.0])
    traj = simulate(body, w0, t_end=2.0, samples=2001, method=method, **({"step": 1e-3} if method != "dop853" else {}))
    w, t = traj.omega, traj.t
    s, sdot = S * np.sin(NU * t), S * NU * np.cos(NU * t)
    h, hdot = J * s[:, None] * n, J * sdot[:, None] * n
    T = 0.5 * np.sum(I * w * w, axis=1) + np.sum(w * h, axis=1) + 0.5 * J * s**2
    np.testing.assert_allclose(traj.energy, T, rtol=1e-14)
    wdot = (-np.cross(w, I * w + h) - hdot) / I
    power = J * s * (wdot @ n + sdot)
    work = np.concatenate([[0.0], cumulative_simpson(power, x=t)])
    scale = T[0]
    np.testing.assert_allclose(T - T[0], work, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(traj.motor_work, work, rtol=0, atol=1e-9 * scale)
    assert abs(T[-1] - T[0]) > 0.01 * scale  # the motor did change the energy
    assert traj.drift["energy"] < (1e-11 if method == "dop853" else 1e-9)
    np.testing.assert_allclose(traj.hamiltonian, 0.5 * np.sum(I * w * w, axis=1), rtol=1e-15)


# rk45 left out: at scipy's default tolerances (rtol 1e-3) it conserves H to no useful bound
@pytest.mark.parametrize("method", ["dop853", *SPLITTING])
def test_constant_spin_keeps_the_gyrostat_hamiltonian(method):
    """Constant h: ``H = sum (L_i - h_i)^2 / (2 I_i)`` and |L| are conserved; the total kinetic
    energy is not, but changes by the motor work ``h.(w - w0)``."""
    body = wheel_body((1.0, 1.0, 1.0), center=(0.1, 0.0, 0.0), spin_rate=400.0)
    w0 = np.array([1.0, 8.0, -2.0])
    traj = simulate(body, w0, t_end=20.0, samples=401, method=method)
    L, h = traj.angular_momentum, traj.internal_momentum
    H = np.sum((L - h) ** 2 / (2 * traj.moments), axis=1)
    np.testing.assert_allclose(traj.hamiltonian, H, rtol=1e-14)
    dH = np.max(np.abs(H / H[0] - 1))
    # measured 9.9e-12 (DOP853, ~1e-11 per 20 s as for a rigid body), 2.5e-5, 1.7e-8, 3.2e-13
    assert dH < {"dop853": 2e-11, "geometric2": 1e-4, "geometric": 1e-7, "geometric6": 2e-12}[method]
    np.testing.assert_allclose(traj.motor_work, np.sum((traj.omega - w0) * h, axis=1), rtol=0, atol=1e-13 * H[0])
    assert np.ptp(traj.energy) > 0.1 * H[0]
    if method != "dop853":
        assert traj.drift["L_norm"] < 1e-13 and traj.drift["L_world"] < 1e-13  # round-off over 4,000 steps


@pytest.mark.parametrize(("method", "order", "h"), [("geometric2", 2, 4e-3), ("geometric", 4, 4e-3), ("geometric6", 6, 2e-2)])
def test_splitting_keeps_its_order_with_a_commanded_wheel(method, order, h):
    """h(t) frozen at the middle of each Strang stage keeps the composition's order (measured
    2: 4.00, 4: 16.0, 6: 63.5)."""
    body = commanded()
    w0 = [1.0, 8.0, -2.0]
    ref = simulate(body, w0, t_end=1.0, samples=3, method="dop853", rtol=1e-13)
    errors = []
    for step in (h, h / 2):
        g = simulate(body, w0, t_end=1.0, samples=3, method=method, step=step)
        errors.append(np.max(np.abs(g.omega - ref.omega)))
        assert g.drift["L_world"] < 1e-14
    assert errors[0] / errors[1] == pytest.approx(2.0**order, rel=0.2)


# -- the intermediate axis with a wheel along it -----------------------------------------------

def linearised_by_the_test(I, W, h):
    """Eigenvalues of the Jacobian of ``w' = -(w x (I w + h e2)) / I`` at ``w = W e2``, by
    central differences: (largest real part, largest imaginary part)."""
    he = np.array([0.0, h, 0.0])

    def f(w):
        return -np.cross(w, I * w + he) / I

    w_star, eps = np.array([0.0, W, 0.0]), 1e-6
    jac = np.column_stack([(f(w_star + eps * e) - f(w_star - eps * e)) / (2 * eps) for e in np.eye(3)])
    ev = np.linalg.eigvals(jac)
    return float(np.max(ev.real)), float(np.max(ev.imag))


@pytest.mark.parametrize("frac", [0.0, 0.3, 0.9, -0.5, 1.5, 3.0, -1.2])
def test_gyrostat_rate_is_the_linearisation(frac):
    I = np.array([0.05, 0.1, 0.13])
    W = 2.0
    h = frac * (I[2] - I[1]) * W
    growth, wobble = gyrostat_rate(I, W, h)
    real, imag = linearised_by_the_test(I, W, h)
    assert float(growth) == pytest.approx(max(real, 0.0), abs=1e-7)
    assert float(wobble) == pytest.approx(imag, abs=1e-7)
    unstable = -(I[1] - I[0]) * W < h < (I[2] - I[1]) * W
    assert (growth > 0) == unstable and (wobble > 0) == (not unstable)


@pytest.mark.parametrize("frac", [0.3, -0.5])
def test_growth_rate_fitted_from_a_run(frac):
    """Start on the unstable eigenvector, 1e-7 W off the axis; fit log|w1| between 1e-6 W and
    1e-4 W: the slope is the closed-form rate to 1e-6 (measured 7e-10 and 2e-10)."""
    probe = wheel_body(spin_rate=0.0)
    I, J = probe.principal_moments, probe.rotors[0].axial_moment
    W = 2.0
    h = frac * (I[2] - I[1]) * W
    body = wheel_body(spin_rate=h / J)
    lam = float(gyrostat_rate(I, W, h)[0])
    X = 1e-7 * W
    Z = -lam * I[0] * X / ((I[2] - I[1]) * W - h)  # I1 x' = -((I3 - I2) W - h) z
    traj = simulate(body, [X, W, Z], t_end=14 / lam, samples=2001)
    x = np.abs(traj.omega[:, 0])
    window = (x > 1e-6 * W) & (x < 1e-4 * W) & (traj.t < traj.t[np.argmax(x > 1e-3 * W)])
    slope = np.polyfit(traj.t[window], np.log(x[window]), 1)[0]
    assert slope == pytest.approx(lam, rel=1e-6)


def test_a_strong_wheel_makes_the_intermediate_axis_wobble():
    """h = 1.5 (I3 - I2) W: w1 oscillates at the closed-form frequency and stays small."""
    probe = wheel_body(spin_rate=0.0)
    I, J = probe.principal_moments, probe.rotors[0].axial_moment
    W = 2.0
    h = 1.5 * (I[2] - I[1]) * W
    nu = float(gyrostat_rate(I, W, h)[1])
    traj = simulate(wheel_body(spin_rate=h / J), [1e-6 * W, W, 0.0], t_end=20 * 2 * np.pi / nu, samples=20001)
    x = traj.omega[:, 0]
    k = np.flatnonzero(np.diff(np.sign(x)) != 0)
    crossings = traj.t[k] - x[k] * (traj.t[k + 1] - traj.t[k]) / (x[k + 1] - x[k])  # linear interpolation
    half_period = np.mean(np.diff(crossings))
    assert np.pi / half_period == pytest.approx(nu, rel=1e-6)
    assert np.max(np.abs(traj.omega[:, [0, 2]])) < 1e-5 * W


# one adaptive and one splitting method: 30 flip periods each (a slow test)
@pytest.mark.parametrize("method", ["dop853", "geometric"])
def test_a_wheel_in_the_t_handle_stops_the_flip(method):
    """The seed's T-handle with a wheel in its crossbar (principal axis 2), spun at 10 rad/s
    with 0.1 rad/s off-axis: with the wheel still, 30 flips in 30 flip periods; with
    h = 2 (I3 - I2) W, none, and the wobble stays within 0.15 rad/s."""
    th = tumble.t_handle()

    def body(spin):
        wheel = tumble.Rotor(mass=0.3, radius=0.08, length=0.02, axis=(1, 0, 0), center=(0, 0, 0.25), spin_rate=spin)
        return tumble.Body([*th.parts, wheel], name="T-handle with wheel")

    still = body(0.0)
    I, J = still.principal_moments, still.rotors[0].axial_moment
    np.testing.assert_allclose(still.principal_axes[:, 1], [1.0, 0.0, 0.0], atol=1e-15)
    W, w0 = 10.0, [0.1, 10.0, 0.1]
    period = flip_interval(w0, I)
    h = 2.0 * (I[2] - I[1]) * W
    assert gyrostat_rate(I, W, h)[0] == 0.0
    for spin, flips in ((0.0, 30), (h / J, 0)):
        traj = simulate(body(spin), w0, t_end=30 * period, samples=6001, method=method)
        assert np.count_nonzero(np.diff(np.sign(traj.omega[:, 1])) != 0) == flips
    assert np.max(np.abs(traj.omega[:, [0, 2]])) < 0.15
    assert traj.drift["L_world"] < 1e-10


# -- methods, defaults, refusals -------------------------------------------------------------

def test_rotors_default_to_the_engine_and_exact_and_seed_refuse_them():
    body = wheel_body(spin_rate=100.0)
    run = simulate(body, [0.1, 1.0, 0.1], t_end=1.0, samples=3)  # "auto": rotors at constant spin, on the engine
    assert run.auto and run.method in ("dop853", "rk8")
    assert set(NO_INTERNAL) >= {"exact", "seed"}
    steady = [name for name, m in METHODS.items() if m.supports_internal or m.constant_rotors_only]
    assert set(steady) - set(INTERNAL) == {"rk4", "rk8"}  # the engine's: rotors at constant spin, as a term
    for method in set(NO_INTERNAL) - set(steady):
        with pytest.raises(ValueError, match=rf"^method = '{method}' cannot take rotors \(1 in this body\); "
                                             rf"use one of: {', '.join(steady)}$"):
            simulate(body, [0.1, 1.0, 0.1], t_end=1.0, method=method)


def test_a_spin_function_without_its_derivative_runs_without_the_motor_budget():
    """The same motion (two DOP853 runs whose states differ by the work integral, so their
    steps differ: agreement to the tolerance), without the motor work."""
    traj = simulate(commanded(derivative=False), [1.0, 8.0, -2.0], t_end=1.0, samples=11)
    ref = simulate(commanded(), [1.0, 8.0, -2.0], t_end=1.0, samples=11)
    np.testing.assert_allclose(traj.omega, ref.omega, rtol=0, atol=1e-10)
    assert traj.motor_work is None and traj.drift["energy"] is None
    assert traj.drift["L_world"] < 1e-10  # measured 2.6e-11 (DOP853, rtol 1e-12, 1 s)


def test_rotor_spin_counts_in_the_work_bound():
    body = wheel_body(spin_rate=1e9)
    with pytest.raises(ValueError, match=r"^t_end = 100 s with \|omega0\| \+ 2 max\|h\| / I1 = .* rad/s is up to .* rad"):
        simulate(body, [0.0, 1.0, 0.0], t_end=100.0, method="dop853")


def test_times_after_zero_report_the_budget_from_zero():
    body = commanded()
    full = simulate(body, [1.0, 8.0, -2.0], t_end=1.0, samples=11)
    late = simulate(body, [1.0, 8.0, -2.0], times=full.t[5:])
    np.testing.assert_allclose(late.motor_work, full.motor_work[5:], rtol=0, atol=1e-12 * full.energy[0])
    np.testing.assert_allclose(late.energy, full.energy[5:], rtol=1e-11)


def test_a_rigid_trajectory_has_no_internal_fields():
    traj = simulate(BOX_BODY, [1.0, 2.0, 3.0], t_end=1.0, samples=5)
    assert traj.internal_momentum is None and traj.damper_omega is None and traj.motor_work is None
    np.testing.assert_array_equal(traj.energy, traj.hamiltonian)


BOX_BODY = tumble.Body([BOX])


# -- what `tumble inertia` says of a body with a wheel ---------------------------------------

WHEEL_BODY = Path(__file__).resolve().parents[1] / "examples" / "bodies" / "t_handle_wheel.toml"


def test_the_stable_spin_range_is_what_runs_do():
    """Inside ``stable_spin_range`` (either sense of spin) the wheel-stabilised T-handle, nudged
    by 0.1 rad/s, keeps its spin (off-axis rates below a tenth of it); a quarter beyond either
    end it tumbles (off-axis rates above half of it; with a wheel omega_2 need not change sign):
    the linearised range against dop853 runs."""
    body = load_body(WHEEL_BODY)
    h = body.internal_momentum(0.0)
    assert h[1] == pytest.approx(2.5) and np.allclose(h[[0, 2]], 0.0)
    low, high = stable_spin_range(body.principal_moments, h[1])
    I = body.principal_moments
    assert (low, high) == pytest.approx((-h[1] / (I[1] - I[0]), h[1] / (I[2] - I[1])), rel=1e-15)
    for W, stable in ((0.85 * high, True), (1.25 * high, False), (0.85 * low, True), (1.25 * low, False)):
        off_axis = np.max(np.abs(simulate(body, [0.1, W, 0.1], t_end=5.0, samples=2001).omega[:, [0, 2]]))
        assert off_axis < 0.1 * abs(W) if stable else off_axis > 0.5 * abs(W), (W, off_axis)
    assert stable_spin_range(I, 0.0) == (0.0, 0.0)
    with pytest.raises(ValueError, match="no intermediate axis"):
        stable_spin_range([1.0, 2.0, 2.0], 1.0)


def test_tumble_inertia_reports_what_the_wheel_does_to_the_intermediate_axis(capsys):
    from tumble.cli import main

    assert main(["inertia", str(WHEEL_BODY)]) == 0
    text = capsys.readouterr().out
    assert "spin about it stable from -10.56 to 20.4 rad/s" in text and "unstable" not in text
    assert main(["inertia", str(WHEEL_BODY), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    body = load_body(WHEEL_BODY)
    assert data["rotor_momentum"] == pytest.approx(body.internal_momentum(0.0).tolist())
    assert data["intermediate_stable_spin"] == pytest.approx(list(stable_spin_range(body.principal_moments, 2.5)))
    # the same wheel stopped, and no wheel: the tennis-racket theorem as before
    stopped = tumble.Body([*body.parts[:2], tumble.Rotor(mass=1.0, radius=0.1, length=0.03, axis=(1, 0, 0),
                                                          center=(0, 0, 0.5), spin_rate=0.0)])
    for plain in (stopped, tumble.t_handle()):
        assert "spin about it is unstable" in mass_properties_table(plain)
    assert mass_properties_dict(stopped)["intermediate_stable_spin"] is None
    assert "intermediate_stable_spin" not in mass_properties_dict(tumble.t_handle())


# -- rotors at constant spin on the compiled engine ------------------------------------------------

@pytest.mark.parametrize(("method", "kw"), [("dop853", {"rtol": 1e-12}), ("rk8", {"step": 0.01}),
                                            ("rk4", {"step": 0.0005})])
def test_constant_rotors_run_on_the_engine_against_an_independent_route(method, kw):
    """A rotor at constant spin is the term ``h x omega`` of the engine's Euler's equations
    (KERNEL_ROTOR_MOMENTUM): dop853, rk8 and rk4 under a constant body torque against scipy's
    DOP853 on the rotation-matrix right-hand side written in this file, near the intermediate axis."""
    body = wheel_body((1.0, 1.0, 0.0), spin_rate=300.0)
    w0 = np.array([0.1, 5.0, 0.1])
    traj = simulate(body, w0, t_end=5.0, samples=51, method=method, torque=tumble.ConstantTorque((0.01, -0.02, 0.015)),
                    **kw)
    tau = np.array([0.01, -0.02, 0.015])
    I = body.principal_moments
    rotor = body.rotors[0]
    h = 0.5 * rotor.mass * rotor.radius**2 * 300.0 * (body.principal_axes.T @ np.array(rotor.axis))

    def rhs(t, y):
        w, R = y[:3], y[3:].reshape(3, 3)
        wx = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        return np.concatenate([(tau - np.cross(w, I * w + h)) / I, (R @ wx).ravel()])

    R0 = traj.attitude[0].as_matrix()
    sol = solve_ivp(rhs, (0.0, 5.0), np.concatenate([traj.omega[0], R0.ravel()]), method="DOP853", t_eval=traj.t,
                    rtol=1e-13, atol=1e-14)
    assert np.max(np.abs(traj.omega - sol.y[:3].T)) / 5.0 < 1e-9
    angle = (traj.attitude * Rotation.from_matrix(sol.y[3:].T.reshape(-1, 3, 3)).inv()).magnitude()
    assert np.max(angle) < 1e-8
    np.testing.assert_allclose(traj.internal_momentum, np.tile(h, (51, 1)), rtol=0, atol=1e-15)


def test_the_fixed_steppers_name_what_they_cannot_take():
    """rk4 and rk8 take rotors at constant spin and a damper: a changing spin is refused, naming it and
    the methods that take it, and a stiff damper, naming the one that follows it."""
    with pytest.raises(ValueError, match=r"^method = 'rk8' cannot take rotors whose spin changes \(1 in this body\); "
                                         r"use one of: dop853, rk45, geometric"):
        simulate(commanded(), [0.1, 1.0, 0.1], t_end=1.0, method="rk8")
    with pytest.raises(ValueError, match=r"^damper: .*\(stiff above 500\): method 'rk4' cannot follow it .*; use method dop853"):
        simulate(tumble.Body([BOX]), [0.1, 1.0, 0.1], t_end=1.0, method="rk4",
                 damper=tumble.SphericalDamper(inertia=0.01, damping=1e3))
