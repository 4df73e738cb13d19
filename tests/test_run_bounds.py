"""What simulate() accepts and how much work it agrees to do: sample times, tolerances, the
rotation a torque can build up, the default step of the splitting methods under a torque."""

from __future__ import annotations

import contextlib
import re

import numpy as np
import pytest

import tumble
from tumble import ConstantTorque, simulate
from tumble.dynamics.methods import integrators
from tumble.dynamics.methods.integrators import METHODS
from tumble.dynamics.models.torques import FunctionTorque

BODY = tumble.t_handle()


# -- sample times -----------------------------------------------------------------------

def test_times_give_the_motion_at_exactly_those_times():
    """Uneven times, starting after 0: the same motion as a fine uniform run, at those times."""
    times = np.array([0.25, 0.3, 1.7, 4.0, 9.99])
    traj = simulate(BODY, [0.1, 10.0, 0.1], times=times)
    np.testing.assert_array_equal(traj.t, times)
    fine = simulate(BODY, [0.1, 10.0, 0.1], t_end=9.99, samples=999 + 1)
    k = [25, 30, 170, 400, 999]
    np.testing.assert_allclose(traj.t, fine.t[k], rtol=1e-15)
    np.testing.assert_allclose(traj.omega, fine.omega[k], atol=1e-12)
    assert max((traj.attitude * fine.attitude[k].inv()).magnitude()) < 1e-12


# One method of each kind (adaptive, fixed step, the seed's sampled attitude); "exact" is the reference.
@pytest.mark.parametrize("method", ["dop853", "geometric", "seed"])
def test_times_with_every_kind_of_method(method):
    times = [0.0, 0.1, 0.15, 1.0]
    traj = simulate(BODY, [0.1, 10.0, 0.1], times=times, method=method)
    ref = simulate(BODY, [0.1, 10.0, 0.1], times=times)
    np.testing.assert_array_equal(traj.t, times)
    np.testing.assert_allclose(traj.omega, ref.omega, atol=5e-2 if method == "seed" else 1e-4)


def test_dt_samples_every_dt_up_to_t_end():
    traj = simulate(BODY, [1.0, 2.0, 3.0], t_end=2.0, dt=0.1)
    assert len(traj) == 21 and traj.t[-1] == 2.0
    np.testing.assert_allclose(np.diff(traj.t), 0.1, rtol=1e-12)
    short = simulate(BODY, [1.0, 2.0, 3.0], t_end=1.05, dt=0.1)  # t_end not a multiple of dt
    assert len(short) == 11 and short.t[-1] == pytest.approx(1.0)


@pytest.mark.parametrize(
    ("kwargs", "pattern"),
    [
        (dict(times=[0.0, 1.0], t_end=1.0), "times = \\[...\\] replaces t_end"),
        (dict(times=[1.0, 0.5]), r"times must increase strictly; times\[1\] = 0.5 follows 1.0"),
        (dict(times=[-1.0, 0.5]), r"times\[0\] = -1.0 must be >= 0"),
        (dict(times=[0.0, np.nan]), r"times\[1\] is not a finite number"),
        (dict(times=[0.0]), r"times\[-1\] = 0.0 must be after 0"),
        (dict(times=[[0.0, 1.0]]), r"must be a list of sample times"),
        (dict(times={0.0, 1.0}), r"must be a list of sample times"),
        (dict(times="0 1"), r"must be a list of sample times"),
        (dict(), r"t_end \(s\) or times = \[...\] is needed"),
        (dict(t_end=1.0, dt=0.1, samples=10), "give samples or dt, not both"),
        (dict(t_end=1.0, dt=0.0), r"dt = 0.0 must be a positive"),
        (dict(t_end=1.0, dt=2.0), r"dt = 2.0 s gives 1 sample over 1 s"),
        (dict(t_end=1e6, dt=1e-9), r"dt = 1e-09 s gives 1000001 samples"),
        (dict(t_end=1.0, rtol=10), r"rtol = 10.0 must be from 2.22e-14 to 0.1"),
        (dict(t_end=1.0, rtol=1e-20, method="dop853"), r"rtol = 1e-20 must be from"),
        (dict(t_end=1.0, atol=1e3, method="rk45"), r"^atol = 1000.0 must be above 0 and at most 0.1 \(rad/s, "),
        (dict(t_end=1.0, atol=1e10, torque=ConstantTorque((0.0, 0.0, 0.01))), r"^atol = 10000000000.0 must be above 0 and "),
        (dict(t_end=1.0, atol=0.5, method="dop853"), r"^atol = 0.5 must be above 0 and at most 0.1 "),
        (dict(t_end=1.0, atol=0.0, method="dop853"), r"^atol = 0.0 must be a positive finite number"),
    ],
)
def test_bad_sampling_and_tolerances_are_refused(kwargs, pattern):
    with pytest.raises(ValueError, match=pattern):
        simulate(BODY, [1.0, 0.0, 0.0], **kwargs)


# -- work bounds -------------------------------------------------------------------------

@pytest.mark.parametrize("magnitude", [1e5, 1e200])
@pytest.mark.parametrize("method", [name for name, m in METHODS.items() if m.supports_torque])
def test_a_torque_that_spins_the_body_up_without_bound_is_refused_at_once(magnitude, method):
    """1e5 N m on the T-handle for 20 s: up to 1.6e7 rad/s, 1.6e8 rad of rotation (it hung)."""
    with pytest.raises(ValueError, match=r"rad of rotation, more than method .* follows"):
        simulate(BODY, [0.0, 1.0, 0.0], t_end=20.0, torque=ConstantTorque((magnitude, 0.0, 0.0)), method=method)


def test_a_run_just_past_the_rotation_bound_says_so_in_digits_that_differ():
    """1e6 rad and a hair: three digits read "up to 1e+06 rad of rotation ... (at most 1e+06 rad)"
    (seen 2026-12-02); the digits that tell the two apart are given."""
    w = 10.0
    t_end = 1.0001e6 / w  # rad/s and s: 1.0001e6 rad at a steady spin about the major axis
    with pytest.raises(ValueError, match=r"is up to 1\.0001e\+06 rad of rotation, more than method 'dop853' follows "
                                         r"\(at most 1e\+06 rad;"):  # a Python torque: scipy's DOP853
        simulate(BODY, [0.0, 0.0, w], t_end=t_end, method="dop853", torque=lambda t, omega, R: [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"is up to 1\.0001e\+06 rad of rotation"):
        tumble.simulate_batch([BODY.principal_moments], [[0.0, 0.0, w]], t_end=t_end, method="dop853")


def test_the_compiled_engine_follows_more_rotation_than_the_python_path():
    """1e6 rad was refused to every stepping method as "about half an hour of DOP853", which is the
    Python path's time; the compiled engine took 1.0 s for it (seen 2026-12-02). A compiled run
    follows up to MAX_COMPILED_ROTATION (here 1.5e6 rad, torque-free dop853: the energy and |L|
    kept to 1e-7), a Python torque's run is still refused past MAX_ROTATION, naming the engine."""
    from tumble.dynamics.simulate import MAX_COMPILED_ROTATION, MAX_ROTATION

    assert MAX_COMPILED_ROTATION > MAX_ROTATION
    traj = simulate(BODY, [0.0, 10.0, 0.01], t_end=1.5e5, samples=2, method="dop853")
    assert traj.drift["energy"] < 1e-7 and traj.drift["L_norm"] < 1e-7
    with pytest.raises(ValueError, match=r"is up to 1\.5e\+06 rad of rotation, more than method 'dop853' follows \(at "
                                         r"most 1e\+06 rad; 1e\+08 on the compiled engine"):
        simulate(BODY, [0.0, 10.0, 0.01], t_end=1.5e5, samples=2, method="dop853", torque=lambda t, w, R: [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"is up to 1\.5e\+08 rad of rotation, more than method 'dop853' follows \(at "
                                         r"most 1e\+08 rad\)"):
        simulate(BODY, [0.0, 10.0, 0.01], t_end=1.5e7, samples=2, method="dop853")


def test_a_torque_that_grows_later_hits_the_work_budget(monkeypatch):
    """A torque that is zero at t = 0 escapes the bound computed before the run: the adaptive
    integrator then gives up with a clear message after its budget of evaluations."""
    monkeypatch.setattr(integrators, "MAX_EVALUATIONS", 2000)
    growing = FunctionTorque(lambda t, w, att: np.array([1e3 * t**6, 0.0, 0.0]), "body")
    with pytest.raises(RuntimeError, match=r"DOP853 gave up after 2,000 evaluations at t = .* of 20 s"):
        simulate(BODY, [0.0, 1.0, 0.0], t_end=20.0, torque=growing)


def test_the_geometric_default_step_follows_the_torque():
    """100 N m in the world frame on the T-handle for 1 s (omega grows ~100-fold): with a step
    chosen from |omega0| alone the splitting was off by 170 %; now its default step counts the
    spin the torque adds, and the error is that of a torque-free run."""
    torque = ConstantTorque((100.0, 0.0, 0.0), "world")
    w0 = [0.1, 1.0, 0.1]
    ref = simulate(BODY, w0, t_end=1.0, samples=11, torque=torque, method="dop853", rtol=1e-13)
    scale = np.linalg.norm(ref.omega, axis=1)[:, None]

    def error(method, **kw):
        traj = simulate(BODY, w0, t_end=1.0, samples=11, torque=torque, method=method, **kw)
        return np.max(np.abs(traj.omega - ref.omega) / scale)

    assert error("geometric", step=0.05 / np.linalg.norm(w0)) > 1.0  # the old default
    assert error("geometric") < 1e-3
    assert error("geometric6") < 1e-7


@pytest.mark.parametrize("axis", [(0.0, 0.0, 1.0), (1.0, 1.0, 0.3), (0.2, -0.7, 0.1)])
@pytest.mark.parametrize("method", list(METHODS))
def test_a_thin_rod_in_any_direction_has_a_zero_moment(axis, method):
    """A lone thin rod off the design axes gets I1 ~ 1e-17 from the eigen-solver, not 0: it is
    refused like the exact zero (with dop853 it hung), by the validity checks' tolerance."""
    rod = tumble.Body([tumble.Rod(mass=1.0, length=1.0, axis=axis)])
    with pytest.raises(ValueError, match="a body with a zero moment"):
        simulate(rod, [1.0, 0.0, 0.0], t_end=1.0, method=method)


def test_the_exact_phase_limit_is_checked_before_the_run(monkeypatch):
    """A run past MAX_PHASE is refused by the input checks (scenario files and the CLI use
    them before anything is computed), not from inside the integration."""
    from tumble.dynamics.methods.exact import FreeRotation
    from tumble.io.scenario import resolve_run

    for name in ("omega", "attitude"):
        monkeypatch.setattr(FreeRotation, name, lambda self, t: pytest.fail("evaluated before checking"))
    with pytest.raises(ValueError, match=r"--t-end = 1e\+12 s takes this motion to a phase of 6.58e\+24 rad"):
        resolve_run("t-handle", omega=[1e13, 1e12, 1e12], t_end=1e12)


def test_simulate_binds_the_gravity_gradient_and_bounds_its_spin_by_the_jacobi_integral():
    """simulate() gives the model the body's moments; a 2000-orbit run from near the local
    vertical is within the work bound (its |omega| stays below the Jacobi-integral bound,
    where |tau(0)| t_end / I1 grows with t_end^2 and refused it)."""
    from tumble.dynamics.simulate import check_inputs

    gg = tumble.GravityGradient(orbit_period=5400.0)
    start = tumble.lvlh_state(gg, BODY, pitch=0.3, roll=0.2)
    run = check_inputs(BODY, start.omega0, t_end=2000 * 5400.0, torque=gg, attitude0=start.attitude0, method="dop853")
    assert run.torque.moments is not None
    np.testing.assert_array_equal(run.torque.moments, BODY.principal_moments)
    traj = simulate(BODY, start.omega0, t_end=5400.0, samples=5, torque=gg, attitude0=start.attitude0)
    assert np.all(np.linalg.norm(traj.omega, axis=1) <= gg.bind(BODY).max_spin(0.0, start.omega0, start.attitude))


def test_an_atol_of_0_1_is_taken_and_the_batch_and_the_closed_loop_refuse_one_above():
    assert simulate(BODY, [1.0, 0.0, 0.0], t_end=1.0, method="rk45", atol=0.1).method == "rk45"
    with pytest.raises(ValueError, match=r"^atol = 2.0 must be above 0 and at most 0.1 \(rad/s, "):
        tumble.simulate_batch([[1.0, 2.0, 3.0]], [[1.0, 0.0, 0.0]], t_end=1.0, torque=ConstantTorque((0.0, 0.0, 0.01)),
                              atol=2.0)
    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.control.controlled import simulate_controlled

    with pytest.raises(ValueError, match=r"^atol = 1.0 must be above 0 and at most 0.1 \(absolute: rad/s for omega"):
        simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=1.0, controller=BDot(gain=1e-3, period=1.0),
                            atol=1.0)


@pytest.mark.parametrize("rtol", [1e-10, 1e-12])
def test_auto_runs_rk8_only_down_to_the_rtol_rk8_meets(rtol):
    from tumble.dynamics.methods.auto import RK_LOWEST_RTOL

    # a spacecraft at 10 rad/s, samples 0.2 s apart: far apart next to rk8's step, so rk8 at 1e-10
    traj = simulate(tumble.MassProperties.from_moments([10.0, 12.0, 15.0]), [0.5, 10.0, 0.5], t_end=20.0,
                    samples=101, torque=ConstantTorque((0.01, -0.02, 0.015)), rtol=rtol)
    assert traj.auto
    assert traj.method == ("rk8" if rtol >= RK_LOWEST_RTOL["rk8"] else "dop853")
    with pytest.raises(ValueError, match="is below what rk8's fixed steps meet") if rtol < RK_LOWEST_RTOL["rk8"] else (
            contextlib.nullcontext()):
        simulate(tumble.MassProperties.from_moments([10.0, 12.0, 15.0]), [0.5, 10.0, 0.5], t_end=1.0,
                 torque=ConstantTorque((0.01, -0.02, 0.015)), method="rk8", rtol=rtol)


def test_an_rtol_given_alone_to_dop853_brings_its_atol_down_with_it():
    """dop853's atol (1e-12 of the spin) held a run at rtol 1e-13 to 2e-10 on the T-handle: an rtol
    below it, given alone, is the atol too, in simulate and in the batch."""
    torque = ConstantTorque((0.01, -0.02, 0.015))
    body = tumble.MassProperties.from_moments([0.125, 0.3125, 0.4375])
    kw = dict(t_end=2.0, samples=5, torque=torque, method="dop853")
    alone = simulate(body, [0.1, 10.0, 0.1], rtol=1e-13, **kw)
    assert np.array_equal(alone.omega, simulate(body, [0.1, 10.0, 0.1], rtol=1e-13, atol=1e-13, **kw).omega)
    assert not np.array_equal(alone.omega, simulate(body, [0.1, 10.0, 0.1], rtol=1e-13, atol=1e-12, **kw).omega)
    loose = simulate(body, [0.1, 10.0, 0.1], rtol=1e-8, **kw)  # above its atol: the atol stays 1e-12
    assert np.array_equal(loose.omega, simulate(body, [0.1, 10.0, 0.1], rtol=1e-8, atol=1e-12, **kw).omega)

    def batch(**extra):
        return tumble.simulate_batch([[0.125, 0.3125, 0.4375]], [[0.1, 10.0, 0.1]], rtol=1e-13, **kw, **extra).omega
    assert np.array_equal(batch(), batch(atol=1e-13)) and not np.array_equal(batch(), batch(atol=1e-12))


@pytest.mark.parametrize(("method", "instead"), [("radau", "give method dop853 or auto"),
                                                 ("radau (auto)", "give method dop853 or auto"),
                                                 ("rk8 (auto)", "give method 'rk8', or 'auto'")])
def test_a_runs_label_given_as_its_method_says_which_name_to_give(method, instead):
    """The repr and the command line's line say "radau (auto)" or "rk8 (auto)"; given back as a method,
    the refusal names the method that asks for it (simulate and the batch alike)."""
    with pytest.raises(ValueError, match=rf"^method = {re.escape(repr(method))} is unknown: .*{re.escape(instead)}"):
        simulate(BODY, [1.0, 0.0, 0.0], t_end=1.0, method=method)
    with pytest.raises(ValueError, match=rf"^method = {re.escape(repr(method))} is unknown: .*{re.escape(instead)}"):
        tumble.simulate_batch([[1.0, 2.0, 3.0]], [[1.0, 0.0, 0.0]], t_end=1.0, method=method)
