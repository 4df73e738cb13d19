"""A user's call against the shared peer (``../shared/peers/numba_peer.py``, unchanged): the default
``tumble.simulate`` with a torque, and the fixed cost of a call (issue 38 item 8, cases 6 and 7).

- **The default call**: ``tumble.simulate(body, omega0, t_end=20.0, torque=model, attitude0=q0)``,
  nothing else (its default method, ``"auto"`` at rtol 1e-10, which names what it chose, and 500
  samples), on ``bench_engine``'s four one-body cases. Its errors against the reference are the accuracy asked of the peer (RK4 and
  RK8 at the smallest ``k`` steps per sample interval that meet both, at the same 500 samples),
  no finer than the reference can tell (twice its difference from the solve at rtol 1e-12).
  Target: within 1.5x of the peer, ratio = the peer's best / tumble's >= 0.667.
- **The fixed cost**: a 2-sample run of one step (``method="rk8"``, ``step = t_end = 0.01`` s, a
  constant body torque; and the gravity gradient), the whole call, less the kernel's time, taken
  as the marginal cost of a step (the same call at 1,001 steps, less the 1-step call, / 1,000).
  The peer's whole call at one step is timed beside it. Target: <= 10 us.
- **The floor**: an RK8 step's floating-point operations (12 right-hand sides of the peer's
  ``FLOPS_RHS``, plus the stage sums: for each of the 7 components, 2 flops for each non-zero
  weight of DOP853's 12-stage tableau and 2 for ``y + h sum`` in each of the 12 stages) over this machine's rate of independent
  multiply-adds on one core (a numba loop of 8 accumulators), beside the marginal step times above.
"""

from __future__ import annotations

import json
import sys

import numpy as np
from _harness import Contest, errors, paired, preamble, table, time_call
from bench_engine import CASES, N_ORBIT, ORBIT_PERIOD, QUAT0, TAU, numba_peer, rigid_reference

import tumble

T_END, DEFAULT_SAMPLES = 20.0, 500
NAMES = ["peer rk4", "peer rk8", "tumble default"]


def _model(gravity: bool):
    return tumble.GravityGradient(orbit_period=ORBIT_PERIOD) if gravity else tumble.ConstantTorque(tuple(TAU))


def _peer(I, w0, gravity, t_end, samples, **kw):
    return numba_peer.simulate(I, w0, QUAT0, torque=(0.0, 0.0, 0.0) if gravity else TAU,
                               gravity_n=N_ORBIT if gravity else None, t_end=t_end, samples=samples, **kw)


def default_calls(repeat: int) -> list[dict]:
    rows = []
    times = np.linspace(0.0, T_END, DEFAULT_SAMPLES)
    for body_name, (moments, w0) in CASES.items():
        I, w0 = np.array(moments), np.array(w0)
        props = tumble.MassProperties.from_moments(moments)
        for gravity in (False, True):
            ref = rigid_reference(I, w0, QUAT0, gravity, times=times)

            def mine(props=props, w0=w0, gravity=gravity):
                return tumble.simulate(props, w0, t_end=T_END, torque=_model(gravity), attitude0=QUAT0)

            traj = mine()
            assert traj.omega.shape == (DEFAULT_SAMPLES, 3), "the default sample count changed: update the bench"
            e = errors(traj.omega, traj.quat, *ref)
            bound = errors(*rigid_reference(I, w0, QUAT0, gravity, times=times, rtol=1e-12), *ref)
            # the peer must match the default call's accuracy (a hair looser: round-off in the last digit),
            # but no finer than the reference can tell: below twice its difference from rtol 1e-12 the
            # peer's errors are noise, not monotone in k (the T-handle in the gravity gradient: ~1e-10)
            target = {"omega": max(e[0] * 1.01, 2 * bound[0]), "attitude": max(e[1] * 1.01, 2 * bound[1])}
            contest = Contest(target, body=body_name, method=traj.method_label, reference_bound=bound,
                              torque="gravity gradient, 5400 s orbit" if gravity else "constant body torque")
            for m in ("rk4", "rk8"):
                contest.add_k(f"peer {m}", lambda k, m=m, I=I, w0=w0, gravity=gravity, ref=ref: errors(
                    *_peer(I, w0, gravity, T_END, DEFAULT_SAMPLES, method=m, k=k), *ref),
                    lambda k, m=m, I=I, w0=w0, gravity=gravity: (
                        lambda: _peer(I, w0, gravity, T_END, DEFAULT_SAMPLES, method=m, k=k)))
            contest.add_fixed("tumble default", e, mine, knob=f"default ({traj.method_label})")
            rows.append(contest.run(repeat, 1 / 1.5))
            print(f"bench_call: default call, {body_name}, {contest.info['torque']}: ratio {rows[-1]['ratio']}",
                  file=sys.stderr, flush=True)
    return rows


def fixed_cost(repeat: int) -> list[dict]:
    rows = []
    I, w0 = np.array([10.0, 12.0, 15.0]), np.array([0.05, 1.0, 0.05])
    props = tumble.MassProperties.from_moments(I)
    h = 0.01
    for gravity in (False, True):
        model = _model(gravity)
        calls = {
            "tumble, 1 step": lambda model=model: tumble.simulate(props, w0, t_end=h, samples=2, method="rk8", step=h,
                                                                  torque=model, attitude0=QUAT0),
            "tumble, 1,001 steps": lambda model=model: tumble.simulate(props, w0, t_end=1001 * h, samples=2, method="rk8",
                                                                       step=h, torque=model, attitude0=QUAT0),
            "peer, 1 step": lambda gravity=gravity: _peer(I, w0, gravity, h, 2, method="rk8", k=1),
            "peer, 1,001 steps": lambda gravity=gravity: _peer(I, w0, gravity, 1001 * h, 2, method="rk8", k=1001),
        }
        t = paired(calls, repeat, min_seconds=0.1)
        step = (t["tumble, 1,001 steps"] - t["tumble, 1 step"]) / 1000
        peer_step = (t["peer, 1,001 steps"] - t["peer, 1 step"]) / 1000
        fixed = t["tumble, 1 step"] - step
        peer_fixed = t["peer, 1 step"] - peer_step
        med = {k: float(np.median(v)) for k, v in t.items()}
        rows.append({"torque": "gravity gradient" if gravity else "constant body torque", "seconds": med,
                     "step_seconds": float(np.median(step)), "peer_step_seconds": float(np.median(peer_step)),
                     "fixed_seconds": float(np.median(fixed)), "fixed_range": [float(fixed.min()), float(fixed.max())],
                     "peer_fixed_seconds": float(np.median(peer_fixed)), "target_seconds": 10e-6,
                     "meets_target": bool(np.median(fixed) <= 10e-6)})
        print(f"bench_call: fixed cost, {rows[-1]['torque']}: {rows[-1]['fixed_seconds'] * 1e6:.3g} us",
              file=sys.stderr, flush=True)
    return rows


def flop_rate(n: int = 20_000_000) -> float:
    """Floating-point operations per second on one core: 8 independent multiply-add chains."""
    from numba import njit

    @njit(cache=False)
    def chains(n, a, b):
        x0 = x1 = x2 = x3 = x4 = x5 = x6 = x7 = 1.0
        for _ in range(n):
            x0 = x0 * a + b
            x1 = x1 * a + b
            x2 = x2 * a + b
            x3 = x3 * a + b
            x4 = x4 * a + b
            x5 = x5 * a + b
            x6 = x6 * a + b
            x7 = x7 * a + b
        return x0 + x1 + x2 + x3 + x4 + x5 + x6 + x7

    chains(10, 0.999999, 1e-7)
    best = min(time_call(lambda: chains(n, 0.999999, 1e-7), 0.2) for _ in range(3))
    return 16.0 * n / best


def floor(fixed: list[dict]) -> dict:
    """An RK8 step's flops (the peer's FLOPS_RHS) over the measured rate, beside the step times."""
    from scipy.integrate._ivp import dop853_coefficients as dc

    weights = int(np.count_nonzero(dc.A[:12, :12]) + np.count_nonzero(dc.B))
    rate = flop_rate()
    out = {"flops_per_second": rate, "weights": weights}
    for kind, row in zip(("constant", "gravity"), fixed):
        flops = 12 * numba_peer.FLOPS_RHS[kind] + 7 * (2 * weights + 12)  # sums, then y + h sum per stage
        out[kind] = {"flops_per_step": flops, "floor_seconds": flops / rate, "tumble_step_seconds": row["step_seconds"],
                     "peer_step_seconds": row["peer_step_seconds"]}
    return out


def to_markdown(r: dict) -> str:
    lines = preamble("bench_call", r["repeats"], "Peer: numba_peer.simulate; tumble: the whole simulate call.")
    lines += ["## The default call with a torque (20 s, 500 samples): the peer at the default call's accuracy", ""]
    lines += table(r["default"], NAMES, lambda c: f"{c['body']}, {c['torque']}")
    lines += ["", "## The fixed cost of a call (rk8, step 0.01 s): the 1-step call less one step's marginal cost", "",
              "| torque | tumble, 1 step | tumble per step | tumble fixed cost [range] | peer, 1 step | peer per step "
              "| peer fixed cost | target | met |", "|---|---|---|---|---|---|---|---|---|"]
    for c in r["fixed"]:
        s = c["seconds"]
        lo, hi = c["fixed_range"]
        lines.append(f"| {c['torque']} | {s['tumble, 1 step'] * 1e6:.3g} us | {c['step_seconds'] * 1e9:.3g} ns "
                     f"| {c['fixed_seconds'] * 1e6:.3g} us [{lo * 1e6:.3g}-{hi * 1e6:.3g}] | {s['peer, 1 step'] * 1e6:.3g} us "
                     f"| {c['peer_step_seconds'] * 1e9:.3g} ns | {c['peer_fixed_seconds'] * 1e6:.3g} us | <= 10 us "
                     f"| {'yes' if c['meets_target'] else '**no**'} |")
    f = r["floor"]
    lines += ["", f"## The floor: flops per RK8 step over {f['flops_per_second'] / 1e9:.3g} GFLOP/s (one core, "
              "8 independent multiply-add chains)", "",
              "| torque | flops per step | floor | tumble's step | peer's step | tumble / floor | peer / floor |",
              "|---|---|---|---|---|---|---|"]
    for kind in ("constant", "gravity"):
        c = f[kind]
        lines.append(f"| {kind} | {c['flops_per_step']} | {c['floor_seconds'] * 1e9:.3g} ns | "
                     f"{c['tumble_step_seconds'] * 1e9:.3g} ns | {c['peer_step_seconds'] * 1e9:.3g} ns | "
                     f"{c['tumble_step_seconds'] / c['floor_seconds']:.3g} | {c['peer_step_seconds'] / c['floor_seconds']:.3g} |")
    return "\n".join(lines) + "\n"


def run(out, quick: bool = False) -> str:
    """Measure, write ``bench_call.json`` into ``out``, return the markdown."""
    repeat = 3 if quick else 11
    r = {"repeats": repeat, "default": default_calls(repeat), "fixed": fixed_cost(repeat)}
    r["floor"] = floor(r["fixed"])
    (out / "bench_call.json").write_text(json.dumps(r, indent=2) + "\n")
    return to_markdown(r)
