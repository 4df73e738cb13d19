"""``simulate`` with the gravity gradient along an ellipse or a TLE's orbit, compiled
(control/free_loop.py): the run against scipy's DOP853 at rtol 1e-13 on a right-hand side written
here from the formulas (Euler's equations, the quaternion kinematics, Hughes's
``3 mu / r^5 r_b x (I r_b)`` with ``r`` the orbit's own position), the momentum budget, and which
path ran."""

from __future__ import annotations

import re

import numpy as np
import pytest
from scipy.integrate import cumulative_simpson
from scipy.spatial.transform import Rotation

import tumble
from rigid_reference import errors, reference_run
from tumble.dynamics import ConstantTorque
from tumble.dynamics.environment.earth import MU_EARTH
from tumble.dynamics.environment.ephemeris import KeplerOrbit, TLEOrbit
from tumble.dynamics.models.orbit_gravity import OrbitGravityGradient

I = np.array([10.0, 12.0, 15.0])  # kg m^2
BODY = tumble.MassProperties.from_moments(I)
#: An ellipse of e = 0.4 (perigee 7,200 km), inclined, with every angle set.
ELLIPSE = KeplerOrbit(12_000e3, 0.4, 0.9, raan=0.4, arg_perigee=1.1, mean_anomaly=0.2)
ISS_2019 = ("1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991",
            "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482")
W0 = np.array([0.02, -0.03, 0.015])  # rad/s: a slow tumble, so that the gradient steers it
Q0 = Rotation.from_rotvec([0.3, -0.5, 0.8]).as_quat()
BODY_PUSH, WORLD_PUSH = np.array([0.0, 2e-6, 0.0]), np.array([1e-6, 0.0, -1e-6])  # N m


def _reference(orbit, t, body_push=np.zeros(3), world_push=np.zeros(3), extra=None):
    """The reference (tests/rigid_reference.py) under the gravity gradient written out (Hughes,
    Spacecraft Attitude Dynamics, ch. 8: ``3 mu / r^5 r_b x (I r_b)``, ``r`` the orbit's own
    position), the pushes and ``extra(t, omega, R)`` (body frame)."""
    mu = getattr(orbit, "mu", MU_EARTH)  # a TLE's is the Earth's

    def torque(time, w, R):
        r = R.T @ orbit.position_world(time)
        rn = np.linalg.norm(r)
        tau = 3.0 * mu / rn**5 * np.cross(r, I * r) + body_push + R.T @ world_push
        return tau if extra is None else tau + extra(time, w, R)

    return reference_run(I, W0, Q0, t, torque)


def test_an_ellipses_gravity_gradient_runs_compiled_to_the_tolerance_asked(loop_runs):
    t = np.linspace(0.0, ELLIPSE.period, 201)  # one orbit, 13,082 s: perigee and apogee
    omega, quat = _reference(ELLIPSE, t)
    run = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=OrbitGravityGradient(ELLIPSE))
    assert loop_runs == [1] and run.method == "dop853" and run.auto
    e_omega, e_angle = errors(run, omega, quat)
    assert e_omega < 1e-10 and e_angle < 1e-9, (e_omega, e_angle)  # auto's rtol 1e-10 (measured: 1e-12, 3e-12)
    # the torque changed the spin: a run without it is far off
    free = tumble.simulate(BODY, W0, times=t, attitude0=Q0)
    assert np.abs(free.omega - omega).max() > 1e3 * np.abs(run.omega - omega).max()


def test_a_sum_with_constant_torques_runs_compiled_too(loop_runs):
    t = np.linspace(0.0, 3000.0, 151)
    omega, quat = _reference(ELLIPSE, t, BODY_PUSH, WORLD_PUSH)
    torque = OrbitGravityGradient(ELLIPSE) + ConstantTorque(BODY_PUSH) + ConstantTorque(WORLD_PUSH, "world")
    run = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=torque, method="dop853", rtol=1e-11)
    assert loop_runs == [1]
    e_omega, e_angle = errors(run, omega, quat)
    assert e_omega < 1e-10 and e_angle < 1e-9, (e_omega, e_angle)


def test_a_python_term_beside_it_keeps_the_python_path(loop_runs):
    t = np.linspace(0.0, 600.0, 31)

    def damping(time, w, R):
        return -1e-4 * w

    omega, quat = _reference(ELLIPSE, t, extra=damping)
    run = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=[OrbitGravityGradient(ELLIPSE), damping])
    assert loop_runs == []
    e_omega, e_angle = errors(run, omega, quat)
    assert e_omega < 1e-9 and e_angle < 1e-9, (e_omega, e_angle)


def test_a_subclass_with_its_own_law_is_called_from_python(loop_runs):
    class Halved(OrbitGravityGradient):
        def __call__(self, t, omega, attitude):
            return 0.5 * super().__call__(t, omega, attitude)

    t = np.linspace(0.0, 600.0, 31)
    run = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=Halved(ELLIPSE))
    whole = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=OrbitGravityGradient(ELLIPSE))
    assert loop_runs == [1]  # the plain model's run only
    assert np.abs(run.omega - whole.omega).max() > 1e-9  # its own law ran, not the plain one's


def test_along_a_tle_orbit():
    pytest.importorskip("sgp4")
    iss = TLEOrbit(*ISS_2019)
    t = np.linspace(0.0, 2000.0, 101)
    omega, quat = _reference(iss, t)
    run = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=OrbitGravityGradient(iss))
    e_omega, e_angle = errors(run, omega, quat)
    assert e_omega < 1e-9 and e_angle < 1e-9, (e_omega, e_angle)  # the position's table: 1e-11 of r


@pytest.mark.parametrize("method", ["auto", "rk8"])
def test_the_momentum_budget_closes(method):
    """``L_world(t) - L_world(0)`` against the impulse of the world torque over the samples
    (Simpson's rule, 0.25 s apart): what is left is the quadrature's, ~1e-9 of the change (it falls
    as the spacing's 4th power: 3.5e-7 at 1 s), where a torque 1 % off would leave 1e-2; at the
    loop's DOP853 (auto) and at RK8's fixed steps, its default."""
    gg = OrbitGravityGradient(ELLIPSE).bind(I)
    t = np.linspace(0.0, 1000.0, 4001)
    run = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=gg, method=method)
    assert run.method == ("dop853" if method == "auto" else method)
    R = run.attitude.as_matrix()
    L_world = np.einsum("nij,nj->ni", R, I * run.omega)
    tau_world = np.array([gg(ti, wi, Rotation.from_matrix(Ri)) for ti, wi, Ri in zip(t, run.omega, R)])
    impulse = cumulative_simpson(tau_world, x=t, axis=0, initial=0.0)
    change = L_world - L_world[0]
    assert np.abs(change).max() > 1e-4 * np.abs(L_world).max()  # the torque moved it
    assert np.abs(change - impulse).max() < 1e-8 * np.abs(change).max()


def test_a_batch_takes_it_body_by_body_and_a_splitting_with_the_bodies_together(loop_runs):
    """The gravity gradient bound to a batch's moments (N, 3): ``simulate_batch``'s default runs
    each body as ``simulate`` does (compiled); ``geometric6`` calls the model with all the bodies."""
    moments = np.array([[10.0, 12.0, 15.0], [5.0, 9.0, 11.0], [1.0, 1.0, 1.5]])
    w = np.array([W0, -W0, [0.0, 0.01, 0.03]])
    t = np.linspace(0.0, 600.0, 31)
    gg = OrbitGravityGradient(ELLIPSE)
    batch = tumble.simulate_batch(moments, w, times=t, torque=gg)
    assert loop_runs == [1, 1, 1] and batch.method == "dop853"
    split = tumble.simulate_batch(moments, w, times=t, torque=gg, method="geometric6", step=1.0)
    for i in range(3):
        lone = tumble.simulate(tumble.MassProperties.from_moments(moments[i]), w[i], times=t, torque=gg)
        assert np.array_equal(batch.omega[i], lone.omega)
        assert np.abs(split.omega[i] - lone.omega).max() < 1e-10 * np.abs(lone.omega).max()
    with pytest.raises(ValueError, match=r"^moments has shape \(1, 3, 3\); it must be \(3,\) or \(N, 3\)"):
        gg.bind(moments[None])
    torques = gg.bind(moments)(0.0, w, Rotation.identity(3))
    assert torques.shape == (3, 3) and np.allclose(torques[2], gg.bind(moments[2])(0.0, w[2], Rotation.identity()))


SCENARIO = """body = "t-handle"
[initial]
omega = [0.02, -0.03, 0.015]
[simulation]
t_end = 3000.0
samples = 601
[torque]
kind = "gravity_gradient"
semi_major_axis = 12e6
eccentricity = 0.4
inclination = 0.9
raan = 0.4
arg_perigee = 1.1
mean_anomaly = 0.2
"""


def test_a_scenario_files_ellipse_runs_as_the_python_call_does(tmp_path, capsys, loop_runs):
    """``tumble simulate`` with the ellipse in ``[torque]``: the Python call's samples, the budget closed."""
    import json

    from tumble.cli import main

    path = tmp_path / "ellipse.toml"
    path.write_text(SCENARIO, encoding="utf-8")
    assert main(["simulate", str(path), "--out", str(tmp_path / "run"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    npz = np.load(tmp_path / "run" / "trajectory.npz")
    run = tumble.simulate(tumble.t_handle(), [0.02, -0.03, 0.015], t_end=3000.0, samples=601,
                          torque=OrbitGravityGradient(ELLIPSE))
    assert np.array_equal(npz["omega"], run.omega) and loop_runs == [1, 1]
    budget = summary["torque_budget"]
    momentum = budget["momentum"]
    # closed to what the samples' quadrature can tell (2.6e-9 against its 2.8e-9), 4e-5 of the change
    assert budget["resolved"] and momentum["gap"] < 3.0 * momentum["quadrature"] < 1e-3 * momentum["change"], budget


@pytest.mark.parametrize(("extra", "message"), [
    ("orbit_period = 5400.0\n", r"^.*torque: orbit_period goes with a circle, not with semi_major_axis"),
    ("arg_latitude = 0.3\n", r"^.*torque: unknown key 'arg_latitude'"),
    ("eccentricity = 1.2\n", r"^.*torque: eccentricity = 1.2 must lie in \[0, 1\)"),
    ("[initial.orbit_frame]\npitch = 0.1\n", r"^.*initial.orbit_frame needs a circular orbit"),
])
def test_a_bad_ellipse_is_refused_in_one_line(tmp_path, capsys, extra, message):
    from tumble.cli import main

    text = SCENARIO.replace("eccentricity = 0.4\n", "") + extra
    if extra.startswith("[initial.orbit_frame]"):
        text = SCENARIO.replace("omega = [0.02, -0.03, 0.015]\n", "") + extra
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    assert main(["simulate", str(path), "--out", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and re.match(message, err), err
    assert not (tmp_path / "run").exists()


@pytest.mark.parametrize(("method", "order", "step"), [("rk8", 8, 20.0), ("rk4", 4, 10.0)])
def test_rk8_and_rk4_take_the_ellipse_on_the_loop_at_their_order(loop_runs, method, order, step):
    """The engine's fixed steps on the loop's kernel: against the reference, the error falls as
    the step's ``order``-th power (halved step, ratio 2^order within a factor 2), and the run's
    default step (``engine_rk.RK_STEP_ANGLE``) is as accurate as dop853's default."""
    t = np.linspace(0.0, 3000.0, 11)
    omega, quat = _reference(ELLIPSE, t)
    gg = OrbitGravityGradient(ELLIPSE)
    coarse, fine = (tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=gg, method=method, step=h)
                    for h in (step, step / 2))
    assert loop_runs == [1, 1] and coarse.method == method
    (e1, a1), (e2, a2) = errors(coarse, omega, quat), errors(fine, omega, quat)
    assert 1e-14 < e2 < e1 < 1e-4 and 2.0 ** order / 2 < e1 / e2 < 2.0 ** order * 2, (e1, e2)  # rk8: 218, rk4: 18
    assert 2.0 ** order / 2 < a1 / a2 < 2.0 ** order * 2, (a1, a2)
    default = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=gg, method=method)
    e_omega, e_angle = errors(default, omega, quat)
    assert e_omega < 1e-10 and e_angle < 1e-9, (e_omega, e_angle)


def test_a_dipole_in_a_field_takes_rk4_on_the_loop(loop_runs):
    """A residual dipole in a uniform field at RK4's fixed steps: ``m x R^T B`` written out here."""
    from tumble.dynamics import ResidualDipole, UniformField

    m, B = np.array([0.3, -0.1, 0.2]), np.array([2e-5, -1e-5, 3e-5])  # A m^2, T
    t = np.linspace(0.0, 600.0, 13)
    omega, quat = reference_run(I, W0, Q0, t, lambda time, w, R: np.cross(m, R.T @ B))
    run = tumble.simulate(BODY, W0, times=t, attitude0=Q0, torque=ResidualDipole(m, UniformField(B)), method="rk4",
                          step=0.25)
    assert loop_runs == [1] and run.method == "rk4"
    e_omega, e_angle = errors(run, omega, quat)
    assert e_omega < 1e-10 and e_angle < 1e-9, (e_omega, e_angle)  # RK4 at 0.01 rad a step (measured 3e-13, 1e-10)
    free = tumble.simulate(BODY, W0, times=t, attitude0=Q0)  # the torque moved it
    assert np.abs(free.omega - omega).max() > 1e4 * np.abs(run.omega - omega).max()


def test_the_fixed_steps_refuse_a_python_term_or_a_spinning_up_rotor_beside_the_ellipse():
    gg = OrbitGravityGradient(ELLIPSE)
    with pytest.raises(ValueError, match=r"^method = 'rk8' runs compiled and takes only the built-in torque models "
                                         r"\(ConstantTorque, GravityGradient, OrbitGravityGradient, ResidualDipole"):
        tumble.simulate(BODY, W0, t_end=10.0, torque=[gg, lambda t, w, R: -1e-4 * w], method="rk8")
    ramp = tumble.Body([tumble.Box(mass=30.0, size=(1.0, 0.8, 0.6)),
                        tumble.Rotor(mass=1.0, radius=0.1, length=0.02, axis=(0.0, 0.0, 1.0), spin_rate=0.0,
                                     spin_acceleration=5.0)])
    with pytest.raises(ValueError, match=r"^method = 'rk4' takes an ellipse's or a TLE's gravity gradient and a "
                                         r"ResidualDipole with rotors at constant spin, not with a damper or rotors "
                                         r"whose spin changes; use method dop853$"):
        tumble.simulate(ramp, W0, t_end=10.0, torque=gg, method="rk4", step=0.1)


def test_a_batch_at_fixed_steps_is_each_body_alone(loop_runs):
    moments = np.array([[10.0, 12.0, 15.0], [5.0, 9.0, 11.0]])
    w = np.array([W0, [0.0, 0.01, 0.03]])
    t = np.linspace(0.0, 600.0, 31)
    gg = OrbitGravityGradient(ELLIPSE)
    batch = tumble.simulate_batch(moments, w, times=t, torque=gg, method="rk8", step=2.0)
    assert batch.method == "rk8" and loop_runs == [1, 1]
    for i in range(2):
        lone = tumble.simulate(tumble.MassProperties.from_moments(moments[i]), w[i], times=t, torque=gg, method="rk8",
                               step=2.0)
        assert np.array_equal(batch.omega[i], lone.omega)


@pytest.mark.parametrize(("method", "rtol", "bound"), [("dop853", 1e-11, 1e-9), ("rk8", None, 1e-10)])
def test_a_gyrostat_takes_the_ellipse_on_the_loop(loop_runs, method, rtol, bound):
    """A box carrying a rotor at constant spin (its momentum ``h`` constant in the body) along an
    ellipse: the gyrostat's ``I omega' = (I omega + h) x omega + tau`` (Hughes sec. 3.4) with
    the gradient, against the reference with ``h x omega`` written here beside it; before, it
    ran on scipy's path, calling the model from Python at every stage."""
    from tumble.dynamics.models.internal import InternalModel, Rotors

    body = tumble.Body([tumble.Box(mass=30.0, size=(1.0, 0.8, 0.6)),
                        tumble.Rotor(mass=1.0, radius=0.1, length=0.02, axis=(0.0, 0.0, 1.0), spin_rate=50.0)])
    I_body = body.principal_moments
    h = InternalModel(I_body, Rotors.of(body)).momentum(0.0)
    # the rotor along the box's axis 3: the design frame is the principal one (attitude0 is Q0 in both)
    assert np.allclose(body.principal_axes, np.eye(3)) and np.linalg.norm(h) > 0.1 * np.linalg.norm(I_body * W0)
    t = np.linspace(0.0, 3000.0, 31)
    mu = ELLIPSE.mu

    def torque(time, w, R):
        r = R.T @ ELLIPSE.position_world(time)
        return 3.0 * mu / np.linalg.norm(r) ** 5 * np.cross(r, I_body * r) + np.cross(h, w)

    omega, quat = reference_run(I_body, W0, Q0, t, torque)
    run = tumble.simulate(body, W0, times=t, attitude0=Q0, torque=OrbitGravityGradient(ELLIPSE), method=method,
                          rtol=rtol)
    assert loop_runs == [1] and run.method == method
    e_omega, e_angle = errors(run, omega, quat)
    # measured: rk8's default step 1.6e-12 and 5.5e-12 rad; dop853 at rtol 1e-11 3.1e-10 and 1.9e-9 rad, where
    # scipy's path (a Python term beside the gradient) leaves 3.7e-10 and 2.4e-9
    assert e_omega < bound and e_angle < 10 * bound, (e_omega, e_angle)
    rigid = tumble.simulate(tumble.MassProperties.from_moments(I_body), W0, times=t, attitude0=Q0,
                            torque=OrbitGravityGradient(ELLIPSE))
    assert np.abs(rigid.omega - omega).max() > 1e3 * np.abs(run.omega - omega).max()  # the rotor's term acted
