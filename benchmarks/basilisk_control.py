"""Closed-loop attitude control in Basilisk, set up as tumble's :func:`simulate_controlled` runs.

Used by ``tests/test_control_basilisk.py`` and ``benchmarks/bench_basilisk_control.py``; Basilisk
(``pip install bsk``) is imported on the first call. Frames as in ``basilisk_runner.py``: the hub's
body frame B is tumble's principal frame, ``sigma_BN`` the MRPs of tumble's attitude.

Two processes: *dynamics* (priority 20, the spacecraft, its RK4 at step ``dt``) and *flight
software* (priority 10, every ``period``), so at a control instant ``t_k`` the dynamics have reached
``t_k`` before the controller reads the state, and the command it writes acts on the next
integration step, from ``t_k`` on: the zero-order hold of tumble.

**(a) MRP feedback with reaction wheels** (:func:`run_pointing`). ``reactionWheelStateEffector``
with balanced wheels along the body axes (``simIncludeRW``'s ``"custom"`` wheel: axial ``Js``,
no friction, no limits), placed *before* the spacecraft in the
dynamics process so that it picks up the command of ``t_k`` before the step that starts at ``t_k``.
A balanced wheel adds no mass properties to the spacecraft: the hub's ``IHubPntBc_B`` is the
inertia of hub and wheels locked, tumble's ``moments`` (measured: so set, one control step agrees to
1e-14 rad/s; with ``Js`` and the transverse ``Jt = Js / 2`` added to it, by 2e-5 rad/s). Flight software: ``simpleNav`` (no
noise) -> ``inertial3D`` (the target ``sigma_RN``) -> ``attTrackingError`` -> ``mrpFeedback``
(``Ki = -1``: no integral; ``controlLawType = 1``: the gyroscopic term ``omega x ([I] omega +
G_s h_s)`` with the body rate, as tumble's ``MRPFeedback(gyroscopic=True)``; ``[I] = I_RW`` of the
vehicle configuration, the locked inertia less the wheels' axial ``Js``, and ``h_s = Js (g . omega +
Omega)``, so ``[I] omega + G_s h_s`` is the total momentum as in tumble) -> ``rwMotorTorque``
(control axes the body axes: ``u = -G_s^+ L_r``).

**(b) B-dot with magnetorquers** (:func:`run_detumble`). Basilisk has no B-dot module: the law
``m = k_b omega x B_B`` (tumble's ``BDot(form="classic", derivative="gyro")``) is a Python
``sysModel.SysModel`` in the flight-software process that reads the spacecraft state and the
field message and writes ``MTBCmdMsg``; ``MtbEffector`` (three rods along the body axes, clipped
at ``max_dipole``) evaluates ``m x B_B`` at every RK4 stage with the current attitude.
The field: ``magneticFieldCenteredDipole`` with tumble's IGRF-13 2020 degree-1 coefficients and
reference radius; with no planet message it is fixed in N (tumble's ``DipoleField(...,
earth_rotation=False, gmst0=0)``). N is tumble's ECI: the hub starts at tumble's orbit position
and velocity in ECI (Basilisk's point-mass Earth, tumble's orbit built with the same ``mu``), and
``sigma_BN`` is the attitude relative to ECI, ``eci_from_world * attitude``. Basilisk evaluates the
field once per dynamics step (in the dynamics process, after the spacecraft) and holds ``B_N``
over the step, where tumble evaluates it continuously: a first-order difference in ``dt``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from basilisk_runner import MASS, mrp_from_quat, quat_from_mrp


@dataclass
class ControlRun:
    """Samples of a Basilisk closed-loop run: times (s), omega (rad/s, body), quat ([x, y, z, w],
    body to N), wheel speeds (rad/s, relative; (n, 0) without wheels), the wheels' motor torque
    commands (N m, (n, 0) without wheels)."""

    times: np.ndarray
    omega: np.ndarray
    quat: np.ndarray
    wheel_speed: np.ndarray
    motor_torque: np.ndarray


def _sim(dt_ns: int, period_ns: int):
    from Basilisk.utilities import SimulationBaseClass

    sim = SimulationBaseClass.SimBaseClass()
    sim.CreateNewProcess("dynamics", 20).addTask(sim.CreateNewTask("dyn", int(dt_ns)))
    sim.CreateNewProcess("fsw", 10).addTask(sim.CreateNewTask("fsw", int(period_ns)))
    return sim


def _hub(moments, omega0, quat0):
    from Basilisk.simulation import spacecraft

    sc = spacecraft.Spacecraft()
    sc.ModelTag = "hub"
    sc.hub.mHub = MASS
    sc.hub.IHubPntBc_B = np.diag(np.asarray(moments, dtype=float)).tolist()
    sc.hub.sigma_BNInit = mrp_from_quat(quat0)
    sc.hub.omega_BN_BInit = [[float(v)] for v in omega0]
    return sc


def run_pointing(moments, omega0, quat0, *, js: float, wheel_speed0, K: float, P: float,
                 target_quat, period: float, dt: float, t_end: float) -> ControlRun:
    """MRP feedback to an inertial target with three wheels along the body axes (module docstring).

    ``moments`` (kg m^2) are the locked inertia of hub and wheels; the wheels' ``js`` (kg m^2) and initial speeds
    (rad/s); gains ``K`` (N m), ``P`` (N m s); ``period`` and ``dt`` (s) must be whole multiples of
    a nanosecond, ``t_end`` a whole number of periods. Samples every period.
    """
    from Basilisk.architecture import messaging
    from Basilisk.fswAlgorithms import (
        attTrackingError,
        inertial3D,
        mrpFeedback,
        rwMotorTorque,
    )
    from Basilisk.simulation import reactionWheelStateEffector, simpleNav
    from Basilisk.utilities import macros, simIncludeRW

    dt_ns, period_ns = round(dt * 1e9), round(period * 1e9)
    sim = _sim(dt_ns, period_ns)
    sc = _hub(moments, omega0, quat0)
    factory = simIncludeRW.rwFactory()
    for axis, speed in zip(np.eye(3), wheel_speed0):
        factory.create("custom", axis.tolist(), Js=float(js), Omega=float(speed) / macros.RPM,
                       RWModel=messaging.BalancedWheels, useMaxTorque=False)
    rw = reactionWheelStateEffector.ReactionWheelStateEffector()
    factory.addToSpacecraft("wheels", rw, sc)
    sim.AddModelToTask("dyn", rw, 2)  # before the hub: it reads the command of t_k before stepping from t_k
    sim.AddModelToTask("dyn", sc, 1)
    rw_params = factory.getConfigMessage()

    nav = simpleNav.SimpleNav()
    nav.ModelTag = "nav"
    nav.scStateInMsg.subscribeTo(sc.scStateOutMsg)
    ref = inertial3D.inertial3D()
    ref.ModelTag = "ref"
    ref.sigma_R0N = np.ravel(mrp_from_quat(target_quat)).tolist()
    err = attTrackingError.attTrackingError()
    err.ModelTag = "error"
    err.attNavInMsg.subscribeTo(nav.attOutMsg)
    err.attRefInMsg.subscribeTo(ref.attRefOutMsg)
    ctrl = mrpFeedback.mrpFeedback()
    ctrl.ModelTag = "mrpFeedback"
    ctrl.K, ctrl.P, ctrl.Ki, ctrl.integralLimit = float(K), float(P), -1.0, 0.0
    ctrl.controlLawType = 1
    vehicle = messaging.VehicleConfigMsgPayload()
    vehicle.ISCPntB_B = np.diag(np.asarray(moments, float) - js).ravel().tolist()  # I_RW: the wheels' axial Js taken out
    vehicle_msg = messaging.VehicleConfigMsg().write(vehicle)
    ctrl.guidInMsg.subscribeTo(err.attGuidOutMsg)
    ctrl.vehConfigInMsg.subscribeTo(vehicle_msg)
    ctrl.rwParamsInMsg.subscribeTo(rw_params)
    ctrl.rwSpeedsInMsg.subscribeTo(rw.rwSpeedOutMsg)
    mapping = rwMotorTorque.rwMotorTorque()
    mapping.ModelTag = "rwMotorTorque"
    mapping.controlAxes_B = np.eye(3).ravel().tolist()
    mapping.vehControlInMsg.subscribeTo(ctrl.cmdTorqueOutMsg)
    mapping.rwParamsInMsg.subscribeTo(rw_params)
    rw.rwMotorCmdInMsg.subscribeTo(mapping.rwMotorTorqueOutMsg)
    for priority, model in enumerate((mapping, ctrl, err, ref, nav)):
        sim.AddModelToTask("fsw", model, priority + 1)  # nav first (highest), the mapping last
    state = sc.scStateOutMsg.recorder(period_ns)
    speeds = rw.rwSpeedOutMsg.recorder(period_ns)
    sim.AddModelToTask("dyn", state, 0)
    sim.AddModelToTask("dyn", speeds, 0)
    torques = mapping.rwMotorTorqueOutMsg.recorder(period_ns)
    sim.AddModelToTask("fsw", torques, 0)
    sim.InitializeSimulation()
    sim.ConfigureStopTime(round(t_end * 1e9))
    sim.ExecuteSimulation()
    keep = (factory, rw_params, vehicle_msg)  # noqa: F841 - the messages must outlive the run
    return ControlRun(np.asarray(state.times(), float) * 1e-9, np.array(state.omega_BN_B, float),
                      quat_from_mrp(state.sigma_BN), np.array(speeds.wheelSpeeds, float)[:, :3],
                      np.array(torques.motorTorque, float)[:, :3])


def run_detumble(moments, omega0, quat0_eci, *, r_eci, v_eci, mu: float, gain: float, max_dipole: float,
                 coefficients, radius: float, period: float, dt: float, t_end: float) -> ControlRun:
    """B-dot (``m = gain omega x B_B``, A m^2 s/T) with three rods along the body axes in a centred
    dipole fixed in N (module docstring). ``r_eci``, ``v_eci`` (m, m/s) start the orbit about a
    point mass ``mu`` (m^3/s^2) (which must be Basilisk's Earth's); ``coefficients`` are
    ``(g10, g11, h11)`` (T) and ``radius`` their reference radius (m). Samples every period."""
    from Basilisk.architecture import messaging, sysModel
    from Basilisk.simulation import MtbEffector, magneticFieldCenteredDipole
    from Basilisk.utilities import simIncludeGravBody

    dt_ns, period_ns = round(dt * 1e9), round(period * 1e9)
    sim = _sim(dt_ns, period_ns)
    sc = _hub(moments, omega0, quat0_eci)
    grav = simIncludeGravBody.gravBodyFactory()
    earth = grav.createEarth()
    earth.isCentralBody = True
    if abs(earth.mu / mu - 1.0) > 1e-15:
        raise ValueError(f"mu = {mu} must be Basilisk's Earth's, {earth.mu}")
    grav.addBodiesTo(sc)
    sc.hub.r_CN_NInit = [[float(v)] for v in r_eci]
    sc.hub.v_CN_NInit = [[float(v)] for v in v_eci]
    sim.AddModelToTask("dyn", sc, 2)
    field = magneticFieldCenteredDipole.MagneticFieldCenteredDipole()
    field.ModelTag = "dipole"
    field.g10, field.g11, field.h11 = (float(c) for c in coefficients)
    field.planetRadius = float(radius)
    field.addSpacecraftToModel(sc.scStateOutMsg)
    sim.AddModelToTask("dyn", field, 1)  # after the hub: B_N at the state just reached, held for the step

    mtb = MtbEffector.MtbEffector()
    mtb.ModelTag = "mtb"
    params = messaging.MTBArrayConfigMsgPayload()
    params.numMTB = 3
    params.GtMatrix_B = np.eye(3).ravel().tolist()
    params.maxMtbDipoles = [float(max_dipole)] * 3
    params_msg = messaging.MTBArrayConfigMsg().write(params)
    mtb.mtbParamsInMsg.subscribeTo(params_msg)
    mtb.magInMsg.subscribeTo(field.envOutMsgs[0])
    sc.addDynamicEffector(mtb)
    sim.AddModelToTask("dyn", mtb, 0)

    class BDot(sysModel.SysModel):
        """m = gain omega x B_B, B_B = [BN] B_N from the true attitude (ideal sensors)."""

        def __init__(self) -> None:
            super().__init__()
            self.state_in = messaging.SCStatesMsgReader()
            self.field_in = messaging.MagneticFieldMsgReader()
            self.cmd_out = messaging.MTBCmdMsg()

        def UpdateState(self, now: int) -> None:
            s = self.state_in()
            sigma = np.asarray(s.sigma_BN, float)
            q = quat_from_mrp(sigma[None, :])[0]  # body to N
            x, y, z, w = q
            body_to_n = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
            b_body = body_to_n.T @ np.asarray(self.field_in().magField_N, float)
            cmd = messaging.MTBCmdMsgPayload()
            cmd.mtbDipoleCmds = (gain * np.cross(np.asarray(s.omega_BN_B, float), b_body)).tolist()
            self.cmd_out.write(cmd, now, self.moduleID)

    bdot = BDot()
    bdot.ModelTag = "bdot"
    bdot.state_in.subscribeTo(sc.scStateOutMsg)
    bdot.field_in.subscribeTo(field.envOutMsgs[0])
    mtb.mtbCmdInMsg.subscribeTo(bdot.cmd_out)
    sim.AddModelToTask("fsw", bdot, 1)
    state = sc.scStateOutMsg.recorder(period_ns)
    sim.AddModelToTask("dyn", state, 0)
    sim.InitializeSimulation()
    sim.ConfigureStopTime(round(t_end * 1e9))
    sim.ExecuteSimulation()
    keep = (grav, earth, params_msg, bdot)  # noqa: F841 - they must outlive the run
    return ControlRun(np.asarray(state.times(), float) * 1e-9, np.array(state.omega_BN_B, float),
                      quat_from_mrp(state.sigma_BN), np.zeros((len(state.times()), 0)),
                      np.zeros((len(state.times()), 0)))


def field_at(r_eci, *, coefficients, radius: float) -> np.ndarray:
    """Basilisk's centred-dipole field (T, N frame) at one position (m, N frame): the frames check."""
    from Basilisk.architecture import messaging
    from Basilisk.simulation import magneticFieldCenteredDipole
    from Basilisk.utilities import SimulationBaseClass

    sim = SimulationBaseClass.SimBaseClass()
    sim.CreateNewProcess("p").addTask(sim.CreateNewTask("t", 1_000_000_000))
    state = messaging.SCStatesMsgPayload()
    state.r_BN_N = [float(v) for v in r_eci]
    msg = messaging.SCStatesMsg().write(state)
    field = magneticFieldCenteredDipole.MagneticFieldCenteredDipole()
    field.g10, field.g11, field.h11 = (float(c) for c in coefficients)
    field.planetRadius = float(radius)
    field.addSpacecraftToModel(msg)
    rec = field.envOutMsgs[0].recorder()
    sim.AddModelToTask("t", field)
    sim.AddModelToTask("t", rec)
    sim.InitializeSimulation()
    sim.ConfigureStopTime(0)
    sim.ExecuteSimulation()
    return np.array(rec.magField_N, float)[-1]
