"""tumble's closed loop against the shared peer ``../shared/peers/models/peer_control.py``
(imported unchanged), at equal accuracy in omega AND attitude (issue 38 item 8, case 5).

The scenario of ``tests/test_control_basilisk.py``, faster, pointed at the world frame (the peer's one
target): a spacecraft of locked moments (10, 12, 15) kg m^2 with three reaction wheels on the
principal axes (J = 0.05 kg m^2, starting at 100, -50, 30 rad/s; torque limit 1 N m, speed limit
600 rad/s, viscous friction 1e-5 N m s; no Coulomb friction: where a wheel crosses zero speed it
switches sign within 1e-4 rad/s, which no fixed step follows (from 0.02 rad/s, the third wheel
crossing, the peer's RK8 error stalled near 1e-7 from k = 16 on), so the case would measure the
kink, not the loop), MRP feedback K = 0.5 N m, P = 1.7 N m s with the gyroscopic feed-forward, every 0.5 s (zero-order hold), in the gravity
gradient of a 5400 s circular orbit, from 60 degrees off the target and tumbling at (0.3, -0.5, 0.4)
rad/s (the motors saturate at first; the wheels reach ~300 rad/s); 60 s, 121 control instants.
Target: omega <= 2e-9 (relative to max |omega|) and attitude <= 2e-8 rad; ratio >= 1.

The peer: RK4 and RK8 at the smallest ``k`` steps per control period; tumble: the whole
``simulate_controlled`` call (the loop in one compiled call: the law, the held command and the
integration) with DOP853 at the largest rtol of a ladder (from scipy's starting step each
period, or carrying the step over, ``carry_step=True``), and with fixed-step RK8 and RK4 at the
smallest ``k`` (``step = period / k``). The controller and the models are built once, outside
the timed call, as the peer's arrays are. The reference: scipy DOP853 at rtol 1e-13 over each
period, the command computed here (numpy, not tumble's).
"""

from __future__ import annotations

import json
import sys

import numpy as np
from _harness import Problem, body_from_world, contest, errors, peers, preamble, quat_rate, reference, table
from scipy.spatial.transform import Rotation

import tumble
from tumble.dynamics.control import MRPFeedback, simulate_controlled
from tumble.dynamics.models.actuators import ReactionWheels

peer_control = peers()[2]

MOMENTS = np.array([10.0, 12.0, 15.0])
JS, SPEED0 = 0.05, np.array([100.0, -50.0, 30.0])
OMEGA0 = np.array([0.3, -0.5, 0.4])  # rad/s: a tumble to stop (at 0.02 rad/s RK8 met round-off at k = 1)
QUAT0 = Rotation.from_rotvec(np.radians(60.0) * np.array([1.0, 2.0, -1.0]) / np.sqrt(6.0)).as_quat()
K, P, PERIOD, T_END = 0.5, 1.7, 0.5, 60.0
UMAX, SMAX, VISC, COUL, LC = 1.0, 600.0, 1e-5, 0.0, 1e-4  # Coulomb friction off: see the docstring
ORBIT_PERIOD = 5400.0
N_ORBIT = 2 * np.pi / ORBIT_PERIOD
TARGET = {"omega": 2e-9, "attitude": 2e-8}
NAMES = ["peer rk4", "peer rk8", "tumble dop853", "tumble dop853 carry", "tumble rk8", "tumble rk4"]


def wheel(u, s):
    """The applied torque of each wheel, written here (ReactionWheels' documented law)."""
    u = np.clip(u, -UMAX, UMAX)
    taper = np.clip((1.0 - np.abs(s) / SMAX) / 0.01, 0.0, 1.0)
    u = np.where(u * s > 0.0, u * taper, u)
    return u - VISC * s - COUL * np.clip(s / LC, -1.0, 1.0)


def command(y) -> np.ndarray:
    """MRP feedback to the world frame: ``u = K sigma + P w - w x (I w + h)`` (short MRP set)."""
    q = y[:4] / np.linalg.norm(y[:4])
    sigma = q[:3] / (1.0 + q[3]) if q[3] >= 0 else -q[:3] / (1.0 - q[3])
    w = y[4:7]
    return K * sigma + P * w - np.cross(w, MOMENTS * w + JS * y[7:10])


def loop_rhs(u):
    def rhs(t, y):
        q = y[:4] / np.linalg.norm(y[:4])
        w, s = y[4:7], y[7:10]
        r = body_from_world(q) @ np.array([np.cos(N_ORBIT * t), np.sin(N_ORBIT * t), 0.0])
        gg = 3 * N_ORBIT**2 * np.cross(r, MOMENTS * r)
        a = wheel(u, s)
        dw = (gg - np.cross(w, MOMENTS * w + JS * s) - a) / (MOMENTS - JS)
        return np.concatenate([quat_rate(q, w), dw, a / JS - dw])
    return rhs


def loop_reference(rtol: float = 1e-13):
    """The states at the control instants: each period integrated with the command held."""
    y = np.concatenate([QUAT0, OMEGA0, SPEED0])
    out = [y]
    steps = round(T_END / PERIOD)
    for i in range(steps):
        u = command(y)
        seg = reference(lambda t, z, u=u, i=i: loop_rhs(u)(t + i * PERIOD, z), y, np.array([0.0, PERIOD]), rtol)
        y = seg[-1].copy()
        y[:4] /= np.linalg.norm(y[:4])
        out.append(y)
    Y = np.array(out)
    return Y[:, 4:7], Y[:, :4]


def peer_errors(Y, ref) -> tuple[float, float]:
    return errors(Y[:, 4:7], Y[:, :4], *ref)


def tumble_errors(run, ref) -> tuple[float, float]:
    return errors(run.omega, run.attitude.as_quat(), *ref)


def problem() -> Problem:
    ref = loop_reference()
    bound = errors(*loop_reference(1e-12), *ref)
    rw = ReactionWheels(np.eye(3), inertia=JS, max_torque=UMAX, max_speed=SMAX, viscous=VISC, coulomb=COUL,
                        limit_cycle_speed=LC)
    gg = tumble.GravityGradient(orbit_period=ORBIT_PERIOD)

    def peer(m, k):
        return peer_control.run(MOMENTS, JS, N_ORBIT, UMAX, SMAX, VISC, COUL, LC, K, P, PERIOD, T_END,
                                QUAT0, OMEGA0, SPEED0, k, method=m)

    ctrl = MRPFeedback(K=K, P=P, period=PERIOD, moments=MOMENTS, wheels=rw, gyroscopic=True)  # reset by each run

    def mine(method="dop853", rtol=1e-10, step=None):  # compiled; "dop853 scipy": scipy's path
        fixed = method in ("rk8", "rk4")
        return simulate_controlled(MOMENTS, OMEGA0, t_end=T_END, controller=ctrl, attitude0=QUAT0, wheels=rw,
                                   wheel_speed0=SPEED0, gravity_gradient=gg, rtol=rtol, atol=min(1e-12, rtol * 1e-3),
                                   compiled=method != "dop853 scipy", method=method if fixed else "dop853", step=step,
                                   carry_step=method == "dop853 carry")

    return Problem("MRP feedback + 3 wheels, gravity gradient, 60 s", TARGET, peer,
                   lambda Y: errors(Y[:, 4:7], Y[:, :4], *ref), mine,
                   lambda run: errors(run.omega, run.attitude.as_quat(), *ref), PERIOD,
                   {"dop853": "rtol", "dop853 carry": "rtol", "rk8": "step", "rk4": "step", "dop853 scipy": "rtol"},
                   {"reference_bound": bound})


def to_markdown(r: dict) -> str:
    lines = preamble("bench_closed_loop", r["repeats"], "Peer: peer_control.run (k fixed steps per 0.5 s control "
                     "period); tumble: the whole simulate_controlled call (the loop in one compiled call).")
    lines += table([r["case"]], NAMES, lambda c: f"{c['case']} (omega <= 2e-9, attitude <= 2e-8 rad)")
    lines += ["", f"Reference: its difference from rtol 1e-12 is at most {max(r['case']['reference_bound']):.1e}."]
    return "\n".join(lines) + "\n"


def run(out, quick: bool = False) -> str:
    """Measure, write ``bench_closed_loop.json`` into ``out``, return the markdown."""
    repeat = 3 if quick else 11
    info = contest(problem(), timed=("dop853", "dop853 carry", "rk8", "rk4")).run(repeat, 1.0)
    print(f"bench_closed_loop: ratio {info['ratio']}", file=sys.stderr, flush=True)
    r = {"repeats": repeat, "case": info}
    (out / "bench_closed_loop.json").write_text(json.dumps(r, indent=2) + "\n")
    return to_markdown(r)
