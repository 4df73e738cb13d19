"""One rigid spacecraft in Basilisk, the frames and conventions matched to tumble's.

Used by ``benchmarks/bench_basilisk.py`` and ``tests/test_basilisk.py``. Basilisk (``pip install
bsk``, import name ``Basilisk``; https://hanspeterschaub.info/basilisk) is imported on the first
call, so importing this module never needs it.

The model: a ``spacecraft.Spacecraft`` hub with the body's principal moments (kg m^2) as
``IHubPntBc_B`` (the hub's body frame B is tumble's principal frame), mass ``MASS`` at the hub
origin; the integrator is the spacecraft's default, ``svIntegratorRK4`` (fixed step = the task
rate ``dt``). Torques, each a dynamic effector evaluated at every RK4 stage:

- ``extForceTorque.ExtForceTorque`` with ``extTorquePntB_B``: a constant body-frame torque (N m);
- ``GravityGradientEffector`` with a point-mass Earth from ``simIncludeGravBody.gravBodyFactory``
  (central body, no SPICE, so the Earth sits at the origin of N): the hub starts at
  ``r_CN_N = (r, 0, 0)`` with ``v_CN_N = (0, sqrt(mu / r), 0)``, a circular orbit in the x-y plane
  with normal +z, whose radius direction is ``(cos n t, sin n t, 0)``: tumble's
  :class:`tumble.GravityGradient` orbit, when that is built with Basilisk's ``mu``
  (:func:`earth_mu`) and ``orbit_radius = r``. (Basilisk integrates the orbit too, with the same
  RK4; on a circle over 20 s its deviation is far below the attitude errors compared here.)

A reaction wheel (``wheel=``): one ``reactionWheelStateEffector`` wheel, ``BalancedWheels``, at
the hub's origin, no friction, no speed or torque limit, and no motor torque (no command
message: ``u = 0``), made with ``simIncludeRW.rwFactory().create("custom", ...)``. Without a
motor torque the wheel keeps its absolute axial momentum ``a = Js (g . omega + Omega)``
(``Omega`` its speed relative to the hub), so the hub moves as a gyrostat with the constant
internal momentum ``a g`` and the inertia ``[I_RW] = I - Js g g^T`` (Schaub & Junkins, sec. 4.5,
the reaction wheel equations with ``u = 0``): ``L = [I_RW] omega + a g``. That is tumble's
gyrostat of a :class:`tumble.Rotor` at a constant relative spin ``s``, ``L = I omega + J s g``
(:mod:`tumble.dynamics.models.rotors`), when tumble's locked inertia ``I`` is Basilisk's
``[I_RW]`` and ``J s = a``: :func:`wheel_setup` makes the Basilisk wheel from tumble's body so.

Attitude: tumble's quaternion ``[x, y, z, w]`` (principal frame to world, active) is the
rotation ``[NB]``; Basilisk's MRP ``sigma_BN`` describes the same rotation of B relative to N,
``sigma = (x, y, z) / (1 + w)``, and back ``q = (2 sigma, 1 - s^2) / (1 + s^2)`` with
``s^2 = |sigma|^2`` (Schaub & Junkins, *Analytical Mechanics of Space Systems*, sec. 3.7). The
angular velocity ``omega_BN_B`` is tumble's ``omega`` (rad/s, body frame).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

#: Hub mass, kg: enters the translation only (the orbit), not the rotation.
MASS = 100.0


@dataclass
class BasiliskRun:
    """Samples of one Basilisk run: times (s), omega (rad/s, body), quat ([x, y, z, w]),
    the wall time of ``ExecuteSimulation`` alone and of the whole run with its set-up (s)."""

    times: np.ndarray
    omega: np.ndarray
    quat: np.ndarray
    seconds_execute: float
    seconds_total: float


def earth_mu() -> float:
    """The Earth's gravitational parameter that Basilisk's ``gravBodyFactory`` uses, m^3/s^2."""
    from Basilisk.utilities import simIncludeGravBody

    return float(simIncludeGravBody.gravBodyFactory().createEarth().mu)


def mrp_from_quat(q) -> list[list[float]]:
    """Basilisk's ``sigma_BN`` (a column) from tumble's quaternion ``[x, y, z, w]``."""
    q = np.asarray(q, dtype=float)
    q = q if q[3] >= 0 else -q  # the short MRP (|sigma| <= 1)
    return [[float(v / (1.0 + q[3]))] for v in q[:3]]


def quat_from_mrp(sigma) -> np.ndarray:
    """Quaternions ``[x, y, z, w]`` from MRPs of shape (n, 3)."""
    sigma = np.asarray(sigma, dtype=float)
    s2 = np.sum(sigma**2, axis=1)
    return np.column_stack([2.0 * sigma / (1.0 + s2)[:, None], (1.0 - s2) / (1.0 + s2)])


@dataclass(frozen=True)
class Wheel:
    """One Basilisk reaction wheel: spin axis ``g`` (unit, hub frame), ``Js`` (kg m^2), initial
    speed relative to the hub ``Omega`` (rad/s)."""

    axis: tuple[float, float, float]
    js: float
    omega: float


def wheel_setup(moments, axis, axial_moment: float, spin: float, omega0) -> tuple[np.ndarray, Wheel]:
    """The Basilisk hub inertia (kg m^2, 3x3) and wheel whose free-wheel gyrostat is tumble's.

    tumble: principal moments ``moments`` (the whole, the rotor locked in), a rotor of axial
    moment ``J = axial_moment`` along the unit ``axis`` (principal frame) at the constant relative
    spin ``s = spin`` (rad/s); the body starts at ``omega0`` (rad/s). Basilisk (bsk 2.12: a
    ``BalancedWheels`` wheel adds no mass properties, so the spacecraft's inertia is the hub's):
    a wheel with ``Js = J`` whose ``[I_RW] = I_hub - Js g g^T`` equals ``diag(moments)``, so
    ``I_hub = diag(moments) + J g g^T``, and whose absolute axial momentum
    ``Js (g . omega0 + Omega0)`` equals ``J s``: ``Omega0 = s - g . omega0``.
    """
    g = np.asarray(axis, dtype=float)
    g = g / np.linalg.norm(g)
    hub = np.diag(np.asarray(moments, dtype=float)) + float(axial_moment) * np.outer(g, g)
    w0 = float(g @ np.asarray(omega0, dtype=float))
    return hub, Wheel(tuple(float(v) for v in g), float(axial_moment), float(spin) - w0)


def run_basilisk(moments, omega0, quat0, *, dt_ns: int, sample_steps: int, samples: int,
                 torque=None, orbit_radius: float | None = None, hub_inertia=None,
                 wheel: Wheel | None = None) -> BasiliskRun:
    """Integrate one spacecraft with Basilisk's RK4.

    Parameters
    ----------
    moments : array_like, shape (3,)
        Principal moments, kg m^2 (the hub's inertia, diagonal).
    omega0 : array_like, shape (3,)
        Initial angular velocity, body frame, rad/s.
    quat0 : array_like, shape (4,)
        Initial attitude, tumble's quaternion ``[x, y, z, w]``.
    dt_ns : int
        Integration step (the task rate), ns: Basilisk's clock counts whole nanoseconds.
    sample_steps : int
        Steps between recorded samples; ``samples`` samples from t = 0, so the run lasts
        ``(samples - 1) * sample_steps * dt_ns`` ns.
    torque : array_like, shape (3,), optional
        A constant body-frame torque, N m (``extForceTorque``).
    orbit_radius : float, optional
        The gravity gradient of a circular orbit of this radius, m, about a point-mass Earth.
    hub_inertia : array_like, shape (3, 3), optional
        The hub's inertia, kg m^2, instead of ``diag(moments)`` (with a wheel: :func:`wheel_setup`).
    wheel : Wheel, optional
        A free reaction wheel on the hub (no motor torque).

    Returns
    -------
    BasiliskRun
    """
    from Basilisk.simulation import GravityGradientEffector, extForceTorque, spacecraft
    from Basilisk.utilities import SimulationBaseClass, simIncludeGravBody

    t0 = time.perf_counter()
    sim = SimulationBaseClass.SimBaseClass()
    sim.CreateNewProcess("dyn").addTask(sim.CreateNewTask("task", int(dt_ns)))
    sc = spacecraft.Spacecraft()
    sc.ModelTag = "hub"
    sc.hub.mHub = MASS
    hub = np.diag(np.asarray(moments, dtype=float)) if hub_inertia is None else np.asarray(hub_inertia, dtype=float)
    sc.hub.IHubPntBc_B = hub.tolist()
    sc.hub.sigma_BNInit = mrp_from_quat(quat0)
    sc.hub.omega_BN_BInit = [[float(v)] for v in omega0]
    sim.AddModelToTask("task", sc)
    keep = []  # the effectors must outlive the run (SWIG does not hold them)
    if torque is not None:
        ext = extForceTorque.ExtForceTorque()
        ext.ModelTag = "torque"
        ext.extTorquePntB_B = [[float(v)] for v in torque]
        sc.addDynamicEffector(ext)
        sim.AddModelToTask("task", ext)
        keep.append(ext)
    if wheel is not None:
        from Basilisk.architecture import messaging
        from Basilisk.simulation import reactionWheelStateEffector
        from Basilisk.utilities import macros, simIncludeRW

        factory = simIncludeRW.rwFactory()
        rw = factory.create("custom", list(wheel.axis), Js=wheel.js, Omega=wheel.omega / macros.RPM,
                            useMaxTorque=False, RWModel=messaging.BalancedWheels)
        effector = reactionWheelStateEffector.ReactionWheelStateEffector()
        factory.addToSpacecraft("wheels", effector, sc)
        sim.AddModelToTask("task", effector)
        keep += [factory, rw, effector]
    if orbit_radius is not None:
        grav = simIncludeGravBody.gravBodyFactory()
        earth = grav.createEarth()
        earth.isCentralBody = True
        grav.addBodiesTo(sc)
        r = float(orbit_radius)
        sc.hub.r_CN_NInit = [[r], [0.0], [0.0]]
        sc.hub.v_CN_NInit = [[0.0], [float(np.sqrt(earth.mu / r))], [0.0]]
        gg = GravityGradientEffector.GravityGradientEffector()
        gg.ModelTag = "gravityGradient"
        gg.addPlanetName(earth.planetName)
        sc.addDynamicEffector(gg)
        sim.AddModelToTask("task", gg)
        keep += [grav, earth, gg]
    rec = sc.scStateOutMsg.recorder(int(dt_ns) * int(sample_steps))
    sim.AddModelToTask("task", rec)
    sim.InitializeSimulation()
    sim.ConfigureStopTime(int(dt_ns) * int(sample_steps) * (samples - 1))
    t1 = time.perf_counter()
    sim.ExecuteSimulation()
    t2 = time.perf_counter()
    times = np.asarray(rec.times(), dtype=float) * 1e-9
    omega = np.array(rec.omega_BN_B, dtype=float)
    quat = quat_from_mrp(rec.sigma_BN)
    t3 = time.perf_counter()
    del keep
    if len(times) != samples:
        raise RuntimeError(f"Basilisk recorded {len(times)} samples, expected {samples}")
    return BasiliskRun(times, omega, quat, t2 - t1, t3 - t0)
