"""``simulate(method="auto")``, the default (issue 38 item 6): it names the method it chose, and
that method meets ``rtol`` in omega and attitude against a reference written here (scipy's DOP853
at rtol 1e-13 on Euler's equations and the quaternion kinematics, none of tumble's code)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

import tumble
from tumble.dynamics import METHODS

Q0 = Rotation.from_euler("xyz", [0.3, -0.2, 0.5])  # design (= principal here) to world
ORBIT = 5400.0  # s


def reference(moments, omega0, t, torque=None, h=(0.0, 0.0, 0.0), q0=Q0):
    """omega (principal frame) and quaternions (body to world, scalar last) at ``t``.

    ``I w' = (I w + h) x w + tau`` (Euler's equations of a gyrostat whose rotors hold the constant
    momentum ``h``; Hughes, *Spacecraft Attitude Dynamics*, ch. 7), ``q' = q (x) (w, 0) / 2``;
    ``torque(t, w, R)`` in the body frame, N m."""
    I, h = np.asarray(moments, float), np.asarray(h, float)

    def rhs(time, y):
        w, q = y[:3], y[3:]
        tau = np.zeros(3) if torque is None else torque(time, w, Rotation.from_quat(q))
        dw = (np.cross(I * w + h, w) + tau) / I
        v, s = q[:3], q[3]
        return np.concatenate([dw, 0.5 * (s * w + np.cross(v, w)), [-0.5 * v @ w]])

    y0 = np.concatenate([omega0, q0.as_quat()])
    sol = solve_ivp(rhs, (0.0, t[-1]), y0, method="DOP853", t_eval=t, rtol=1e-13, atol=1e-16)
    assert sol.success
    q = sol.y[3:].T
    return sol.y[:3].T, q / np.linalg.norm(q, axis=1, keepdims=True)


def gravity(n, moments):
    """3 n^2 r x (I r), r the unit radius turning at n in the world's x-y plane (Hughes, ch. 8)."""
    I = np.asarray(moments, float)

    def tau(t, w, R):
        r = R.inv().apply([np.cos(n * t), np.sin(n * t), 0.0])
        return 3.0 * n * n * np.cross(r, I * r)

    return tau


def errors(traj, omega, quat):
    """omega: largest |error| over the largest |omega|; attitude: largest angle (rad) over the
    angle turned (at least 1 rad)."""
    e_omega = np.max(np.linalg.norm(traj.omega - omega, axis=1)) / np.max(np.linalg.norm(omega, axis=1))
    angle = np.max((Rotation.from_quat(traj.quat) * Rotation.from_quat(quat).inv()).magnitude())
    turned = float(np.sum(np.linalg.norm(omega[:-1], axis=1) * np.diff(traj.t)))
    return float(e_omega), float(angle / max(1.0, turned))


SPACECRAFT = (10.0, 12.0, 15.0)
T_HANDLE = (0.125, 0.3125, 0.4375)
TAU = (0.01, -0.02, 0.015)
CASES = {  # name: moments, omega0, t_end, samples, tumble's torque, the reference's
    "torque-free": (T_HANDLE, (0.1, 10.0, 0.1), 20.0, 201, None, None),
    "constant torque, fast spin": (T_HANDLE, (0.1, 10.0, 0.1), 20.0, 101, tumble.ConstantTorque(TAU),
                                   lambda t, w, R: np.array(TAU)),
    "constant torque, fast spin, 500 samples": (T_HANDLE, (0.1, 10.0, 0.1), 20.0, 500, tumble.ConstantTorque(TAU),
                                                lambda t, w, R: np.array(TAU)),
    "constant torque, slow spin": (SPACECRAFT, (0.05, 1.0, 0.05), 20.0, 500, tumble.ConstantTorque(TAU),
                                   lambda t, w, R: np.array(TAU)),
    "gravity gradient, fast spin": (SPACECRAFT, (0.5, 10.0, 0.5), 20.0, 101, tumble.GravityGradient(orbit_period=ORBIT),
                                    gravity(2 * np.pi / ORBIT, SPACECRAFT)),
    "gravity gradient, slow spin": (SPACECRAFT, (0.05, 1.0, 0.05), 60.0, 2000,
                                    tumble.GravityGradient(orbit_period=ORBIT), gravity(2 * np.pi / ORBIT, SPACECRAFT)),
}


_REFERENCES: dict[tuple, tuple] = {}


def case_reference(name, t):
    """:func:`reference` of ``CASES[name]`` at ``t``, computed once a run for each case and times
    (read-only): test_auto_meets_rtol_in_omega_and_attitude and the three rtols of
    test_auto_honours_other_tolerances ask for the same one (~0.6 s of scipy's DOP853 each)."""
    key = (name, np.asarray(t, float).tobytes())
    if key not in _REFERENCES:
        moments, w0, _, _, _, tau = CASES[name]
        omega, quat = reference(moments, np.array(w0), t, tau)
        omega.flags.writeable = quat.flags.writeable = False
        _REFERENCES[key] = omega, quat
    return _REFERENCES[key]


@pytest.mark.parametrize("name", CASES)
def test_auto_meets_rtol_in_omega_and_attitude(name):
    moments, w0, t_end, samples, model, tau = CASES[name]
    body = tumble.MassProperties.from_moments(moments)
    traj = tumble.simulate(body, w0, t_end=t_end, samples=samples, torque=model, attitude0=Q0)
    omega, quat = case_reference(name, traj.t)
    e = errors(traj, omega, quat)
    assert max(e) <= 1e-10, (traj.method, e)
    assert traj.auto and traj.method in METHODS and repr(traj).count(f"{traj.method} (auto)") == 1
    assert traj.method == ("exact" if model is None else traj.method)


def test_auto_chooses_both_engine_methods_and_says_which():
    """A fast spin with samples far apart goes to the fixed-step rk8, a slow one with samples close
    together to the adaptive dop853 (methods.auto.engine_choice)."""
    chosen = {}
    for name, (moments, w0, t_end, samples, model, _) in CASES.items():
        traj = tumble.simulate(tumble.MassProperties.from_moments(moments), w0, t_end=t_end, samples=samples,
                               torque=model, attitude0=Q0)
        chosen[name] = traj.method
    assert chosen["torque-free"] == "exact" and chosen["gravity gradient, fast spin"] == "rk8"
    assert chosen["constant torque, slow spin"] == "dop853" and chosen["gravity gradient, slow spin"] == "dop853"


@pytest.mark.parametrize("samples", [21, 400])
def test_auto_with_rotors_at_constant_spin(samples):
    """A wheel spinning at a constant rate: its momentum ``h = J s`` one more term of Euler's equations."""
    wheel = tumble.Rotor(mass=0.5, radius=0.1, length=0.02, axis=(0.0, 0.0, 1.0), spin_rate=200.0)
    body = tumble.Body([tumble.Box(mass=10.0, size=(0.4, 0.6, 0.8)), wheel], name="wheel")
    A = body.principal_axes  # principal -> design (columns: the principal axes in design coordinates)
    h = 0.5 * 0.5 * 0.1**2 * 200.0 * (A.T @ np.array([0.0, 0.0, 1.0]))  # J s along the axis, principal frame
    w_design = np.array([0.3, 2.0, -0.4])
    traj = tumble.simulate(body, w_design, t_end=10.0, samples=samples, torque=tumble.ConstantTorque(TAU),
                           attitude0=Q0, frame="design")
    tau_principal = A.T @ np.array(TAU)  # a body torque given in design coordinates, as omega0 is
    omega, quat = reference(body.principal_moments, A.T @ w_design, traj.t, lambda t, w, R: tau_principal, h,
                            Q0 * Rotation.from_matrix(A))
    e = errors(traj, omega, quat)
    assert max(e) <= 1e-10, (traj.method, e)
    assert traj.auto and traj.method in ("dop853", "rk8") and repr(traj).count(f"{traj.method} (auto)") == 1


def test_auto_for_what_only_dop853_takes():
    """A Python torque, or a stiff damper: dop853 (which hands the damper to Radau), and the run says
    it was chosen; a damper that is not stiff runs on the engine's rk8."""
    body = tumble.MassProperties.from_moments(SPACECRAFT)
    traj = tumble.simulate(body, [0.05, 1.0, 0.05], t_end=5.0, samples=11, torque=lambda t, w, R: -0.01 * w)
    assert (traj.method, traj.auto) == ("dop853", True)
    damped = tumble.simulate(body, [0.05, 1.0, 0.05], t_end=5.0, samples=11,
                             damper=tumble.SphericalDamper(inertia=0.1, damping=0.05))
    assert damped.method_label == "rk8 (auto)"
    stiff = tumble.simulate(body, [0.05, 1.0, 0.05], t_end=5.0, samples=11,
                            damper=tumble.SphericalDamper(inertia=0.1, damping=500.0))
    assert stiff.method_label == "radau (auto)"


def damped_reference(moments, J, c, omega0, t):
    """omega, the sphere's rate and quaternions at ``t``: Euler's law for the body and for the
    sphere in omega form, ``I w' = (I w) x w + c (w_d - w)``, ``J w_d' = J w_d x w - c (w_d - w)``
    (L&L *Mechanics* sec. 36), ``q' = q (x) (w, 0) / 2``, by scipy's DOP853 at rtol 1e-13."""
    I = np.asarray(moments, float)

    def rhs(_, y):
        w, wd, q = y[:3], y[3:6], y[6:]
        slip = wd - w
        v, s = q[:3], q[3]
        return np.concatenate([(np.cross(I * w, w) + c * slip) / I, np.cross(wd, w) - c / J * slip,
                               0.5 * (s * w + np.cross(v, w)), [-0.5 * v @ w]])

    sol = solve_ivp(rhs, (0.0, t[-1]), np.concatenate([omega0, omega0, Q0.as_quat()]), method="DOP853", t_eval=t,
                    rtol=1e-13, atol=1e-16)
    assert sol.success
    q = sol.y[6:].T
    return sol.y[:3].T, sol.y[3:6].T, q / np.linalg.norm(q, axis=1, keepdims=True)


@pytest.mark.parametrize(("moments", "omega0", "J", "c", "t_end"), [
    (T_HANDLE, (0.1, 10.0, 0.1), 0.05, 0.05, 20.0),   # a tumble near the intermediate axis, damped
    ((0.0652, 4.86, 4.87), (78.54, 0.05, 0.0), 0.02, 0.02, 10.0),   # Explorer 1's spin about its long axis
])
def test_auto_meets_rtol_with_a_damper(moments, omega0, J, c, t_end):
    """The engine's rk8 that auto runs a damper on meets rtol 1e-10 in omega and attitude, and in the
    sphere's rate, against the reference written above."""
    body = tumble.MassProperties.from_moments(moments)
    traj = tumble.simulate(body, omega0, t_end=t_end, samples=101, attitude0=Q0,
                           damper=tumble.SphericalDamper(inertia=J, damping=c))
    assert traj.method_label == "rk8 (auto)"
    omega, wd, quat = damped_reference(moments, J, c, np.array(omega0), traj.t)
    assert max(errors(traj, omega, quat)) <= 1e-10
    assert np.max(np.abs(traj.damper_omega - wd)) <= 1e-10 * np.max(np.abs(wd))


@pytest.mark.parametrize("rtol", [1e-6, 1e-8, 1e-11])
@pytest.mark.parametrize("name", ["constant torque, fast spin", "constant torque, fast spin, 500 samples",
                                  "gravity gradient, fast spin"])
def test_auto_honours_other_tolerances(name, rtol):
    """Down to 1e-11, the lowest rtol docs/methods.md says auto meets (below it round-off, and
    the reference's own error, ~1e-11 relative on the T-handle)."""
    moments, w0, t_end, samples, model, tau = CASES[name]
    body = tumble.MassProperties.from_moments(moments)
    traj = tumble.simulate(body, w0, t_end=t_end, samples=samples, torque=model, attitude0=Q0, rtol=rtol)
    e = errors(traj, *case_reference(name, traj.t))
    assert max(e) <= rtol, (traj.method, e)


def test_a_named_method_runs_as_before_and_is_not_marked():
    body = tumble.MassProperties.from_moments(SPACECRAFT)
    for method in ("dop853", "rk8", "exact"):
        torque = None if method == "exact" else tumble.ConstantTorque(TAU)
        traj = tumble.simulate(body, [0.05, 1.0, 0.05], t_end=2.0, samples=5, torque=torque, method=method)
        assert (traj.method, traj.auto, traj.method_label) == (method, False, method)
        assert "(auto)" not in repr(traj)
    same = [tumble.simulate(body, [0.05, 1.0, 0.05], t_end=2.0, samples=5, torque=tumble.ConstantTorque(TAU),
                            method=m) for m in ("auto", None)]
    assert np.array_equal(same[0].omega, same[1].omega) and same[0].method_label == same[1].method_label


@pytest.mark.parametrize("method", ["euler", "", "AUTO", 3, ["dop853"]])
def test_an_unknown_method_is_refused_naming_auto(method):
    body = tumble.MassProperties.from_moments(SPACECRAFT)
    with pytest.raises(ValueError, match=r"^method = .* is unknown; allowed: auto, exact, dop853, rk45"):
        tumble.simulate(body, [0.0, 1.0, 0.0], t_end=1.0, method=method)


@pytest.mark.parametrize("method", ["rk45", "auto"])
def test_an_rtol_is_honoured_on_a_slow_body(method):
    """rtol 1e-10 at 1e-3 rad/s: rk45's scipy default atol (1e-6 rad/s) would cap it near 1e-5 relative
    (issue 38); an rtol given alone brings its atol down with it, relative to the spin."""
    w0 = np.array([0.5e-3, 1e-3, 0.2e-3])
    body = tumble.MassProperties.from_moments(SPACECRAFT)
    torque = tumble.ConstantTorque((1e-6, 0.0, 0.0))
    traj = tumble.simulate(body, w0, t_end=2000.0, samples=50, torque=torque, attitude0=Q0, method=method, rtol=1e-10)
    e = errors(traj, *reference(SPACECRAFT, w0, traj.t, lambda t, w, R: np.array([1e-6, 0.0, 0.0])))
    assert max(e) <= 1e-10, (traj.method_label, e)


def test_a_scenario_file_takes_auto_and_names_what_ran(tmp_path):
    """``method = "auto"`` in a scenario file, as in simulate(): the run names the method it chose;
    a method the registry lacks is refused with the allowed names, auto among them."""
    from tumble.io.scenario import load_scenario

    path = tmp_path / "auto.toml"
    path.write_text('body = "t-handle"\ninitial = { omega = [0.1, 5.0, 0.1] }\n'
                    'simulation = { t_end = 1.0, method = "auto" }\n[torque]\nkind = "constant"\nvector = [0.0, 0.0, 0.01]\n')
    traj = tumble.run_scenario(load_scenario(path))
    assert traj.auto and traj.method in ("rk8", "dop853") and traj.method_label == f"{traj.method} (auto)"
    path.write_text('body = "t-handle"\ninitial = { omega = [0.1, 5.0, 0.1] }\nsimulation = { t_end = 1.0, method = "autox" }\n')
    with pytest.raises(ValueError, match=r"simulation\.method = 'autox' is unknown; allowed: auto, exact"):
        load_scenario(path)



@pytest.mark.parametrize("method", ["rk4", "rk8"])
@pytest.mark.parametrize("name", ["constant torque, fast spin", "gravity gradient, fast spin"])
def test_the_engines_fixed_steps_meet_an_rtol_given_without_a_step(name, method):
    """rk4 and rk8 given an rtol and no step take the step that meets it (rk_angle over the fastest spin
    the run reaches; issue 38: every method honours rtol); on the T-handle, where the steps' error
    is above round-off, a looser rtol gives a larger error (the rtol sets the step)."""
    moments, w0, t_end, samples, model, tau = CASES[name]
    body = tumble.MassProperties.from_moments(moments)
    worst = []
    for rtol in (1e-4, 1e-6, 1e-9):
        traj = tumble.simulate(body, w0, t_end=t_end, samples=samples, torque=model, attitude0=Q0, method=method,
                               rtol=rtol)
        worst.append(max(errors(traj, *case_reference(name, traj.t))))
        assert worst[-1] <= rtol, (rtol, worst[-1])
    if moments == T_HANDLE:
        assert worst[0] > worst[1] > worst[2], worst


@pytest.mark.parametrize(("method", "lowest"), [("rk4", 3e-11), ("rk8", 1e-11)])
def test_an_rtol_a_fixed_step_cannot_meet_is_refused_and_the_lowest_is_met(method, lowest):
    """Below RK_LOWEST_RTOL the round-off of the many short steps wins (rk4 at 1e-11 left 1.9e-11
    here): refused, naming the rtol, the method and what it meets; at it, met (the spacecraft at
    10 rad/s in the gravity gradient, whose reference is good to ~1e-14)."""
    name = "gravity gradient, fast spin"
    moments, w0, t_end, samples, model, tau = CASES[name]
    body = tumble.MassProperties.from_moments(moments)
    with pytest.raises(ValueError, match=rf"^rtol = {lowest / 3!r} is below what {method}'s fixed steps meet "):
        tumble.simulate(body, w0, t_end=t_end, samples=samples, torque=model, method=method, rtol=lowest / 3)
    traj = tumble.simulate(body, w0, t_end=t_end, samples=samples, torque=model, attitude0=Q0, method=method, rtol=lowest)
    assert max(errors(traj, *case_reference(name, traj.t))) <= lowest


@pytest.mark.parametrize(("name", "method", "claim"), [
    ("constant torque, fast spin", "dop853", 1e-10), ("constant torque, slow spin", "dop853", 1e-13),
    ("constant torque, fast spin", "rk4", 4e-10), ("constant torque, fast spin", "rk8", 3e-12),
    ("constant torque, slow spin", "rk4", 1e-13), ("constant torque, slow spin", "rk8", 2e-15)])
def test_the_methods_at_their_defaults_are_as_accurate_as_the_guide_says(name, method, claim):
    """docs/methods.md: dop853 leaves omega to ~1e-10 per 20 s on the T-handle at 10 rad/s, ~1e-13
    on the spacecraft at 1 rad/s; rk4 and rk8 at their default steps ~4e-10 and ~3e-12, ~1e-13 and
    ~2e-15 (~: within a factor of 10, as the guides' checked comments read it)."""
    moments, w0, t_end, samples, model, tau = CASES[name]
    traj = tumble.simulate(tumble.MassProperties.from_moments(moments), w0, t_end=t_end, samples=samples, torque=model,
                           attitude0=Q0, method=method)
    e_omega, _ = errors(traj, *case_reference(name, traj.t))
    assert claim / 10 <= e_omega <= claim * 10, e_omega
