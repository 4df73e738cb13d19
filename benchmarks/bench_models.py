"""tumble's internal models against the shared peer ``../shared/peers/models/peer_models.py``
(imported unchanged), at equal accuracy in omega AND attitude (issue 38 item 8, cases 3 and 4).

- **The gyrostat**: a box (3 kg, 0.6 x 0.4 x 0.2 m) with a rotor (0.2 kg, radius 5 cm, along the
  intermediate axis) spinning at a constant 300 rad/s relative to the body, so its momentum ``h``
  is constant; the body starts at (0.1, 5, 0.1) rad/s near the intermediate axis; 20 s, 101
  samples; torque-free, and under the constant body torque (0.01, -0.02, 0.015) N m.
- **The damper**: Explorer 1 (``examples/bodies/explorer1.toml``'s moments, 0.0652 and 4.86
  kg m^2) spun at 78.54 rad/s about its long axis with a 0.05 rad/s nutation, with the example's
  spherical nutation damper (J = 0.02 kg m^2, c = 0.02 N m s); 10 s, 101 samples.

Targets: omega <= 2e-9 (relative) and attitude <= 2e-8 rad for the gyrostat (the one-body
case's), omega <= 1e-8 and attitude <= 1e-7 rad for the damper (785 rad of spin in 10 s);
target ratio >= 1. The peer: RK4 and RK8 at the smallest ``k`` steps per 0.2 s / 0.1 s sample
interval; tumble: ``dop853`` at the largest rtol of a ladder, ``geometric`` and ``geometric6`` (the
splitting methods, compiled), ``rk8`` and ``rk4`` (which take constant rotors and a damper that is
not stiff) at the smallest ``k``, and ``auto``. The reference: scipy DOP853 at
rtol 1e-13 on the numpy right-hand sides below, in omega form (the peer is in momentum form).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
from _harness import Problem, contest, errors, methods_for, peers, preamble, quat_rate, reference, table
from scipy.spatial.transform import Rotation

import tumble

peer_models = peers()[1]

SAMPLES = 101
QUAT0 = Rotation.from_euler("xyz", [0.3, -0.2, 0.5]).as_quat()
TAU = np.array([0.01, -0.02, 0.015])
GYRO = {"omega": 2e-9, "attitude": 2e-8}
DAMPER = {"omega": 1e-8, "attitude": 1e-7}
ROTOR = dict(mass=0.2, radius=0.05, length=0.01, axis=(0.0, 1.0, 0.0), spin_rate=300.0)
EXPLORER = Path(__file__).resolve().parents[1] / "examples" / "bodies" / "explorer1.toml"
#: tumble's methods searched (geometric2, second order, never wins here); rk8 and rk4 take constant
#: rotors and a damper
TIMED = ("dop853", "rk8", "rk4", "geometric", "geometric6", "auto")
NAMES = ["peer rk4", "peer rk8", *(f"tumble {m}" for m in TIMED)]


def gyro_rhs(I, h, tau):
    """``I w' = tau - w x (I w + h)``, ``q' = 1/2 q (x) w``: written here."""
    def rhs(t, y):
        w = y[:3]
        return np.concatenate([(tau - np.cross(w, I * w + h)) / I, quat_rate(y[3:7], w)])
    return rhs


def damper_rhs(I, J, c):
    """``I w' = -w x I w + c (w_d - w)``, ``J (w_d' + w x w_d) = -c (w_d - w)`` (tumble's damper
    docstring, Landau & Lifshitz), ``q' = 1/2 q (x) w``: written here."""
    def rhs(t, y):
        w, wd = y[:3], y[7:10]
        return np.concatenate([(-np.cross(w, I * w) + c * (wd - w)) / I, quat_rate(y[3:7], w),
                               -np.cross(w, wd) - c / J * (wd - w)])
    return rhs


def _ref(rhs, y0, times, rtol=1e-13):
    y = reference(rhs, y0, times, rtol)
    return y[:, :3], y[:, 3:7] / np.linalg.norm(y[:, 3:7], axis=1, keepdims=True)


def gyrostat_problem(torqued: bool) -> Problem:
    body = tumble.Body([tumble.Box(mass=3.0, size=(0.6, 0.4, 0.2)), tumble.Rotor(**ROTOR)])
    assert np.allclose(body.principal_axes, np.eye(3)), "the principal frame must be the design frame here"
    I = body.principal_moments
    J = 0.5 * ROTOR["mass"] * ROTOR["radius"] ** 2  # the rotor's axial moment (a solid cylinder)
    h = J * ROTOR["spin_rate"] * np.array(ROTOR["axis"])
    w0, t_end = np.array([0.1, 5.0, 0.1]), 20.0
    tau = TAU if torqued else np.zeros(3)
    times = np.linspace(0.0, t_end, SAMPLES)
    ref = _ref(gyro_rhs(I, h, tau), np.concatenate([w0, QUAT0]), times)
    bound = errors(*_ref(gyro_rhs(I, h, tau), np.concatenate([w0, QUAT0]), times, 1e-12), *ref)
    p = np.concatenate([I, h, tau])
    y0 = np.concatenate([I * w0 + h, QUAT0])

    def peer(method, k):
        return peer_models.run("gyro", y0, p, t_end=t_end, samples=SAMPLES, k=k, method=method)

    def tumble_run(**kw):
        return tumble.simulate(body, w0, t_end=t_end, samples=SAMPLES, attitude0=QUAT0,
                               torque=tumble.ConstantTorque(tuple(TAU)) if torqued else None, **kw)

    name = "gyrostat, " + (f"constant body torque {TAU.tolist()} N m" if torqued else "torque-free")
    return Problem(name, GYRO, peer, lambda Y: errors((Y[:, :3] - h) / I, Y[:, 3:7], *ref), tumble_run,
                   lambda tr: errors(tr.omega, tr.quat, *ref), t_end / (SAMPLES - 1), methods_for("internal"),
                   {"reference_bound": bound, "t_end": t_end})


def damper_problem() -> Problem:
    I = tumble.load_body(EXPLORER).principal_moments
    props = tumble.MassProperties.from_moments(I)
    J, c = 0.02, 0.02
    w0, t_end = np.array([78.54, 0.05, 0.0]), 10.0
    times = np.linspace(0.0, t_end, SAMPLES)
    ref = _ref(damper_rhs(I, J, c), np.concatenate([w0, QUAT0, w0]), times)
    bound = errors(*_ref(damper_rhs(I, J, c), np.concatenate([w0, QUAT0, w0]), times, 1e-12), *ref)
    y0 = np.concatenate([I * w0 + J * w0, QUAT0, w0, [0.0]])
    p = np.array([*I, J, c])

    def peer(method, k):
        return peer_models.run("damper", y0, p, t_end=t_end, samples=SAMPLES, k=k, method=method)

    def tumble_run(**kw):
        return tumble.simulate(props, w0, t_end=t_end, samples=SAMPLES, attitude0=QUAT0,
                               damper=tumble.SphericalDamper(inertia=J, damping=c), **kw)

    return Problem("Explorer 1 with its nutation damper, 78.54 rad/s", DAMPER, peer,
                   lambda Y: errors((Y[:, :3] - J * Y[:, 7:10]) / I, Y[:, 3:7], *ref), tumble_run,
                   lambda tr: errors(tr.omega, tr.quat, *ref), t_end / (SAMPLES - 1), methods_for("internal"),
                   {"reference_bound": bound, "t_end": t_end})


def to_markdown(r: dict) -> str:
    lines = preamble("bench_models", r["repeats"], "Peer: peer_models.run (k fixed steps per sample interval, "
                     "momentum form); tumble: the whole simulate call (a Body with a Rotor part; a SphericalDamper).")
    lines += table(r["cases"], NAMES, lambda c: f"{c['case']}, {c['t_end']:g} s (omega <= {c['target']['omega']:g}, "
                   f"attitude <= {c['target']['attitude']:g} rad)")
    bound = max(max(c["reference_bound"]) for c in r["cases"])
    lines += ["", f"Reference: its difference from rtol 1e-12 is at most {bound:.1e} (omega or attitude) over the cases."]
    return "\n".join(lines) + "\n"


def run(out, quick: bool = False) -> str:
    """Measure, write ``bench_models.json`` into ``out``, return the markdown."""
    repeat = 3 if quick else 11
    cases = []
    for make in (lambda: gyrostat_problem(False), lambda: gyrostat_problem(True), damper_problem):
        cases.append(contest(make(), timed=TIMED, k_max=16384).run(repeat, 1.0))
        print(f"bench_models: {cases[-1]['case']}: ratio {cases[-1]['ratio']}", file=sys.stderr, flush=True)
    r = {"repeats": repeat, "cases": cases}
    (out / "bench_models.json").write_text(json.dumps(r, indent=2) + "\n")
    return to_markdown(r)
