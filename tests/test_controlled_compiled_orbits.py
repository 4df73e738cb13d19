"""The compiled closed loop with the IGRF field and along Keplerian and TLE orbits
(control/control_kernel.py, environment/tabulated.py): the tables against the models they stand for,
the compiled evaluation against numpy's, and whole runs against scipy's solve_ivp path."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tumble.dynamics.control import controlled
from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.bdot import BDot
from tumble.dynamics.control.controllers import MRPFeedback
from tumble.dynamics.control import control_kernel as cc
from tumble.dynamics.control import loop_terms
from tumble.dynamics.control.compiled_loop import padded, unpadded
from tumble.dynamics.models.actuators import Magnetorquers, ReactionWheels
from tumble.dynamics.models.orbit_gravity import OrbitGravityGradient, gravity_gradient_of
from tumble.dynamics.environment.ephemeris import KeplerOrbit, TLEOrbit
from tumble.dynamics.environment.igrf import _BLOCK, IGRFField
from tumble.dynamics.environment.tabulated import CubicTable, position_table

ISS_2019 = ("1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991",
            "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482")
CUBESAT = [0.0067, 0.0419, 0.0419]  # kg m^2
MOLNIYA = KeplerOrbit(26_600e3, 0.74, 1.1065, arg_perigee=4.71, mean_anomaly=-0.05)


def _iss():
    pytest.importorskip("sgp4")
    return TLEOrbit(*ISS_2019)


def _igrf(orbit, epoch=None, step=5.0):
    pytest.importorskip("ppigrf")
    return IGRFField(orbit, epoch, step=step)


def _compiled_table(table, t):
    f = loop_terms.table_value
    return np.array([f(table.coefficients, table.t0, table.step, float(x)) for x in t])


def _close(a, b, rel):
    """max |a - b| <= rel * max |b| (the scale of the quantity)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    assert np.max(np.abs(a - b)) <= rel * np.max(np.abs(b)), np.max(np.abs(a - b)) / np.max(np.abs(b))


def test_the_igrf_table_is_the_fields_own_interpolation_also_compiled():
    field = _igrf(_iss())
    T = 1.5 * _BLOCK * field.step  # two blocks
    table = field.tabulate(T)
    assert (table.t0, table.step, table.coefficients.shape) == (0.0, 5.0, (4, 2 * _BLOCK, 3))
    edge = _BLOCK * field.step
    t = np.concatenate([np.random.default_rng(4).uniform(0.0, T, 40), [0.0, 5.0, edge, np.nextafter(edge, 0.0),
                                                                       np.nextafter(edge, T), 2.5, edge + 2.5, T]])
    B = field.world(t)
    np.testing.assert_array_equal(table(t), B)  # the same coefficients, interval and Horner sums
    _close(_compiled_table(table, t), B, 1e-15)
    # and the interpolation is the field's: between knots, the full model to the spline's accuracy
    _close(table(t), field.world_direct(t), 1e-9)
    # the block edge is a knot of both blocks' splines: they meet there to round-off
    below, above = field.world([np.nextafter(edge, 0.0), edge])
    _close(below, above, 1e-14)


@pytest.mark.parametrize("orbit", ["iss", "molniya", "ellipse"])
def test_position_tables_hold_the_orbit_to_1e_11_and_compile_to_round_off(orbit):
    o = {"iss": _iss, "molniya": lambda: MOLNIYA, "ellipse": lambda: KeplerOrbit(9000e3, 0.2, 0.7, 0.3, 1.0, 2.0)}[orbit]()
    table = position_table(o, 12000.0)
    t = np.concatenate([np.random.default_rng(5).uniform(0.0, 12000.0, 3000), [0.0, table.step, 12000.0]])
    r = np.asarray(o.position_world(t), float)
    assert np.max(np.linalg.norm(table(t) - r, axis=1) / np.linalg.norm(r, axis=1)) < 1e-11
    _close(_compiled_table(table, t[:200]), table(t[:200]), 1e-15)


def test_cubic_table_rejects_a_bad_shape():
    with pytest.raises(ValueError, match=r"coefficients has shape \(4, 3\); it must be \(4, m, 3\)"):
        CubicTable(0.0, 1.0, np.zeros((4, 3)))
    with pytest.raises(ValueError, match="step"):
        CubicTable(0.0, 0.0, np.zeros((4, 1, 3)))


def test_the_kernels_orbit_gravity_gradient_is_the_models():
    gg = OrbitGravityGradient(MOLNIYA).bind(CUBESAT)
    kernel = cc.ControlKernel(np.array(CUBESAT), np.diag(1 / np.array(CUBESAT)), None, None, gg, 1e-10, 1e-12, 8000.0)
    rhs = kernel.kernels["rhs"]
    rng = np.random.default_rng(6)
    for t in (0.0, 600.0, 7777.7):  # near perigee (M0 = -0.05) and far from it
        att = Rotation.from_rotvec(rng.normal(size=3))
        w = rng.normal(size=3) * 0.1
        out = unpadded(np.array(rhs(t, tuple(padded(np.concatenate([att.as_quat(), w, np.zeros(3)]))), kernel.P,
                                     kernel.X, 1.0, 0.0)), 0)
        _close(out[7:], gg(t, w, att), 1e-10)  # the table's position error, ~1e-12 of r, times 3


def test_compiled_control_models_accepts_igrf_and_orbit_gravity_gradients_only_on_known_orbits():
    class Wobble:
        mean_motion = 1e-3

        def position_world(self, t):
            return np.array([7e6, 0.0, 1e3 * np.sin(1e-3 * t)])

    assert cc.compiled_control_models(None, gravity_gradient_of(MOLNIYA), None, None) is None
    assert cc.compiled_control_models(None, OrbitGravityGradient(Wobble()), None, None) == \
        "gravity_gradient's orbit = Wobble (a CircularOrbit, KeplerOrbit or TLEOrbit)"
    assert cc.compiled_control_models(_igrf(MOLNIYA, "2026-01-01T00:00:00"), None, None, None) is None
    with pytest.raises(ValueError, match="t_end = None must be given"):
        cc.ControlKernel(np.array(CUBESAT), np.eye(3), None, None, gravity_gradient_of(MOLNIYA).bind(CUBESAT),
                         1e-10, 1e-12)


def _both(**kw):
    return simulate_controlled(compiled=True, **kw), simulate_controlled(compiled=False, **kw)


def _agree(fast, slow, rel):
    assert np.array_equal(fast.t, slow.t)
    q1, q2 = fast.attitude.as_quat(), slow.attitude.as_quat()
    for a, b in ((fast.omega, slow.omega), (q1 * np.sign(np.sum(q1 * q2, axis=1))[:, None], q2),
                 (fast.impulse_world, slow.impulse_world), (fast.momentum_world, slow.momentum_world),
                 (fast.dipole, slow.dipole), (fast.field, slow.field), (fast.wheel_speed, slow.wheel_speed)):
        if b.size:
            _close(a, b, rel)


def test_bdot_in_igrf_along_a_tle_orbit_with_its_gravity_gradient_agrees_with_scipy(monkeypatch):
    iss = _iss()
    field = _igrf(iss)
    kw = {"moments": CUBESAT, "omega0": [0.05, -0.05, 0.05], "t_end": 40.0, "field": field,
          "controller": BDot(gain=3e-5, period=1.0, form="normalized"), "gravity_gradient": gravity_gradient_of(iss),
          "magnetorquers": Magnetorquers(0.2), "attitude0": Rotation.from_rotvec([0.3, -0.2, 1.0])}
    fast, slow = _both(**kw)
    _agree(fast, slow, 1e-10)
    assert fast.rate[-1] < fast.rate[0]
    # the default takes the compiled path with these models
    monkeypatch.setattr(controlled, "solve_ivp", lambda *a, **k: (_ for _ in ()).throw(AssertionError("solve_ivp")))
    np.testing.assert_array_equal(simulate_controlled(**kw).omega, fast.omega)


def test_wheel_pointing_on_an_eccentric_orbit_with_its_gravity_gradient_agrees_with_scipy():
    # near the perigee of a Molniya orbit the gravity gradient is ~(1 - e)^-3 = 57 times the
    # circle's; a large body so that it moves the wheels and the impulse
    moments = [30.0, 40.0, 50.0]
    rw = ReactionWheels(np.eye(3), inertia=2e-2, max_torque=0.05)
    c = MRPFeedback(K=2.0, P=20.0, period=0.5, moments=moments, wheels=rw)
    fast, slow = _both(moments=moments, omega0=[0.001, -0.002, 0.0015], t_end=30.0, controller=c, wheels=rw,
                       gravity_gradient=gravity_gradient_of(MOLNIYA), attitude0=Rotation.from_rotvec([0.4, -0.3, 0.2]))
    _agree(fast, slow, 1e-10)
    assert np.abs(fast.impulse_world).max() > 1e-4  # N m s: the gravity gradient did act
    assert fast.budget_error().max() < 1e-12 * np.abs(fast.momentum_world).max()
