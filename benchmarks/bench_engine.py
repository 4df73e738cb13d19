"""tumble's engine against the shared reference peer (``../shared/peers/numba_peer.py``, imported
unchanged), at equal accuracy in omega AND attitude (issue 38 item 8, cases 1 and 2).

- **One body, 20 s, 101 samples**, the four Basilisk cases of ``bench_basilisk`` (a spacecraft
  (10, 12, 15) kg m^2 at 1 rad/s and the seed's T-handle at 10 rad/s, each under the constant
  body torque (0.01, -0.02, 0.015) N m and under the gravity gradient of a 5400 s circular orbit),
  omega error <= 2e-9 (relative to max |omega|) AND attitude error <= 2e-8 rad: the whole
  ``tumble.simulate`` call against the peer's whole ``simulate`` call; target ratio >= 1.
- **2,000 bodies**, constant body torque, 20 s, omega <= 1e-10 and attitude <= 1e-9 rad:
  ``tumble.simulate_batch`` against the peer's ``prange`` loop, both on every core; target >= 2.

Each side searches its own knobs (``_harness``): the peer RK4 and RK8 at the smallest ``k`` steps
per 0.2 s sample interval; tumble ``dop853`` at the largest rtol of a ladder, ``rk8`` and ``rk4``
at the smallest ``k`` (``step = 0.2 / k``), and ``auto`` where the registry has it. The reference:
scipy DOP853 at rtol 1e-13 on the numpy right-hand side below (errors: max over samples, and over
the first 8 bodies of the batch).
"""

from __future__ import annotations

import json
import os
import sys

import numpy as np
from _harness import Problem, body_from_world, contest, errors, methods_for, peers, preamble, quat_rate, reference, table
from scipy.spatial.transform import Rotation

import tumble

numba_peer = peers()[0]

T_END, SAMPLES = 20.0, 101
INTERVAL = T_END / (SAMPLES - 1)
TAU = np.array([0.01, -0.02, 0.015])
ORBIT_PERIOD = 5400.0
N_ORBIT = 2 * np.pi / ORBIT_PERIOD
QUAT0 = Rotation.from_euler("xyz", [0.3, -0.2, 0.5]).as_quat()
ONE = {"omega": 2e-9, "attitude": 2e-8}
BATCH = {"omega": 1e-10, "attitude": 1e-9}
BODIES, N_REF = 2000, 8
CASES = {
    "spacecraft (10, 12, 15) kg m^2, 1 rad/s": ((10.0, 12.0, 15.0), (0.05, 1.0, 0.05)),
    "seed T-handle, 10 rad/s": ((0.125, 0.3125, 0.4375), (0.1, 10.0, 0.1)),
}
TIMES = np.linspace(0.0, T_END, SAMPLES)
NAMES = ["peer rk4", "peer rk8", "tumble dop853", "tumble rk8", "tumble rk4", "tumble auto"]


def rigid_rhs(I, gravity: bool, tau=TAU):
    """Euler's equations and the quaternion kinematics in numpy, written here (not tumble's)."""
    I = np.asarray(I, float)

    def rhs(t, y):
        w, q = y[:3], y[3:] / np.linalg.norm(y[3:])
        torque = tau
        if gravity:
            r = body_from_world(q) @ np.array([np.cos(N_ORBIT * t), np.sin(N_ORBIT * t), 0.0])
            torque = 3 * N_ORBIT**2 * np.cross(r, I * r)
        return np.concatenate([(torque + np.cross(I * w, w)) / I, quat_rate(y[3:], w)])

    return rhs


def rigid_reference(I, w0, q0, gravity: bool, times=TIMES, rtol=1e-13):
    y = reference(rigid_rhs(I, gravity), np.concatenate([w0, q0]), times, rtol)
    return y[:, :3], y[:, 3:] / np.linalg.norm(y[:, 3:], axis=1, keepdims=True)


def one_body_problems() -> list[Problem]:
    """The four one-body cases."""
    out = []
    for body_name, (moments, w0) in CASES.items():
        I, w0 = np.array(moments), np.array(w0)
        props = tumble.MassProperties.from_moments(moments)
        for gravity in (False, True):
            torque_name = "gravity gradient, 5400 s orbit" if gravity else f"constant body torque {TAU.tolist()} N m"
            model = tumble.GravityGradient(orbit_period=ORBIT_PERIOD) if gravity else tumble.ConstantTorque(tuple(TAU))
            ref = rigid_reference(I, w0, QUAT0, gravity)
            bound = errors(*rigid_reference(I, w0, QUAT0, gravity, rtol=1e-12), *ref)
            out.append(Problem(
                f"{body_name}, {torque_name}", ONE,
                lambda m, k, I=I, w0=w0, gravity=gravity: numba_peer.simulate(
                    I, w0, QUAT0, method=m, k=k, torque=(0.0, 0.0, 0.0) if gravity else TAU,
                    gravity_n=N_ORBIT if gravity else None, t_end=T_END, samples=SAMPLES),
                lambda out, ref=ref: errors(*out, *ref),
                lambda props=props, w0=w0, model=model, **kw: tumble.simulate(
                    props, w0, t_end=T_END, samples=SAMPLES, attitude0=QUAT0, torque=model, **kw),
                lambda traj, ref=ref: errors(traj.omega, traj.quat, *ref),
                INTERVAL, methods_for("torque"), {"reference_bound": bound}))
    return out


def batch_problem(bodies: int = BODIES) -> Problem:
    """``bodies`` bodies under a constant body torque; errors over the first 8."""
    rng = np.random.default_rng(0)  # bench_torqued's bodies: moments in [0.5, 1] kg m^2, |omega| ~ 10 rad/s
    I = np.sort(rng.uniform(0.5, 1.0, (BODIES, 3)), axis=1)[:bodies]
    w = (rng.normal(size=(BODIES, 3)) * 6.0)[:bodies]
    q = Rotation.random(BODIES, random_state=0).as_quat()[:bodies]
    refs = [rigid_reference(I[b], w[b], q[b], False) for b in range(N_REF)]
    ref = (np.stack([r[0] for r in refs]), np.stack([r[1] for r in refs]))
    loose = [rigid_reference(I[b], w[b], q[b], False, rtol=1e-12) for b in range(N_REF)]
    bound = errors(np.stack([r[0] for r in loose]), np.stack([r[1] for r in loose]), *ref)
    model = tumble.ConstantTorque(tuple(TAU))
    return Problem(
        f"{bodies} bodies, constant body torque", BATCH,
        lambda m, k: numba_peer.simulate(I, w, q, method=m, k=k, torque=TAU, t_end=T_END, samples=SAMPLES),
        lambda out: errors(out[0][:N_REF], out[1][:N_REF], *ref),
        lambda **kw: tumble.simulate_batch(I, w, t_end=T_END, samples=SAMPLES, attitude0=q, torque=model, **kw),
        lambda b: errors(b.omega[:N_REF], b.quat[:N_REF], *ref),
        INTERVAL, methods_for("torque"), {"bodies": bodies, "cores": len(os.sched_getaffinity(0)), "reference_bound": bound})


def one_body(repeat: int) -> list[dict]:
    rows = []
    for problem in one_body_problems():
        rows.append(contest(problem).run(repeat, 1.0))
        print(f"bench_engine: {problem.name}: ratio {rows[-1]['ratio']}", file=sys.stderr, flush=True)
    return rows


def batch(repeat: int, quick: bool) -> dict:
    # RK4 needs ~350 steps a sample here, 20 times RK8's work: searched in the full run only
    rk4 = () if quick else ("rk4",)
    info = contest(batch_problem(), timed=("dop853", "rk8", *rk4, "auto"),
                   peer_methods=(*rk4, "rk8")).run(repeat, 2.0, min_seconds=0.2)
    print(f"bench_engine: batch of {BODIES}: ratio {info['ratio']}", file=sys.stderr, flush=True)
    return info


def to_markdown(r: dict) -> str:
    lines = preamble("bench_engine", r["repeats"], "Peer: numba_peer.simulate (k fixed steps per 0.2 s sample "
                     "interval); tumble: the whole simulate / simulate_batch call.")
    lines += ["## One body, 20 s, 101 samples: omega <= 2e-9 and attitude <= 2e-8 rad", ""]
    lines += table(r["one_body"], NAMES, lambda c: c["case"])
    lines += ["", f"## {BODIES} bodies, constant body torque, 20 s: omega <= 1e-10 and attitude <= 1e-9 rad "
              f"(both on {r['batch']['cores']} cores)", ""]
    lines += table([r["batch"]], NAMES, lambda c: f"{c['bodies']} bodies")
    bound = max(max(c["reference_bound"]) for c in r["one_body"])
    lines += ["", f"Reference: its difference from rtol 1e-12 is at most {bound:.1e} (omega or attitude) over the "
              "one-body cases, {:.1e} / {:.1e} over the batch's first {} bodies.".format(*r["batch"]["reference_bound"], N_REF)]
    return "\n".join(lines) + "\n"


def run(out, quick: bool = False) -> str:
    """Measure, write ``bench_engine.json`` into ``out``, return the markdown."""
    repeat = 3 if quick else 11
    r = {"repeats": repeat, "one_body": one_body(repeat), "batch": batch(repeat, quick)}
    (out / "bench_engine.json").write_text(json.dumps(r, indent=2) + "\n")
    return to_markdown(r)
