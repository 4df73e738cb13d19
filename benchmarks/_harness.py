"""The one home of the peer comparisons' machinery (``bench_engine``, ``bench_models``,
``bench_control_peer``, ``bench_call``, ``bench_work_precision``).

- **The peers**: ``../shared/peers/numba_peer.py`` and ``../shared/peers/models/*.py``, imported
  unchanged from the shared folder beside the repository (``peers()``); a missing folder is a
  clear error, never a silent fallback to a copy of our own.
- **The reference**: scipy's ``solve_ivp(method="DOP853", rtol=1e-13)`` on a numpy right-hand side
  that each benchmark writes itself (not tumble's), and its own error bound: the difference from
  the same solve at rtol 1e-12.
- **The errors**: omega relative to max |omega| of the reference, attitude in rad (the angle of
  ``q q_ref^-1``), the max over the samples.
- **The searches**: the peer's (and tumble's fixed-step) smallest steps per sample that meet a
  target in BOTH errors, tumble's largest rtol of a ladder that meets it.
- **The timing**: every contender once per repeat, in turn (a load that comes and goes hits all
  alike); medians and ranges; ratio = the peer's best / tumble's best, per repeat.
"""

from __future__ import annotations

import importlib
import os
import platform
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

#: The shared peers: the folder ``shared/peers`` beside the repository (/work/main -> /work/shared).
PEERS = Path(__file__).resolve().parents[1].parent / "shared" / "peers"
RTOLS = [1e-3, 1e-4, 1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 3e-10, 1e-10, 3e-11, 1e-11, 3e-12, 1e-12, 3e-13, 1e-13]


def peers():
    """``(numba_peer, peer_models, peer_control)``, imported unchanged from :data:`PEERS`."""
    wanted = [PEERS / "numba_peer.py", PEERS / "models" / "peer_models.py", PEERS / "models" / "peer_control.py"]
    missing = [str(p) for p in wanted if not p.is_file()]
    if missing:
        raise SystemExit(
            "the benchmarks compare tumble with the shared reference peers, imported unchanged from "
            f"{PEERS} (the folder shared/peers beside the repository); missing: {', '.join(missing)}")
    for folder in (PEERS, PEERS / "models"):  # peer_control imports peer_models by its bare name
        if str(folder) not in sys.path:
            sys.path.insert(0, str(folder))
    return tuple(importlib.import_module(n) for n in ("numba_peer", "peer_models", "peer_control"))


def machine() -> str:
    """The machine in words: Python, CPU, cores we may use, load average."""
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    load = os.getloadavg() if hasattr(os, "getloadavg") else (float("nan"),) * 3
    return (f"Python {platform.python_version()}, {cpu}, {len(os.sched_getaffinity(0))} cores, "
            f"load average {load[0]:.2f} at the start")


# ---------------------------------------------------------------------------- reference, errors

def reference(rhs: Callable, y0, times, rtol: float = 1e-13) -> np.ndarray:
    """scipy DOP853 on a numpy ``rhs(t, y)``: the states at ``times``, shape (len(times), len(y0))."""
    sol = solve_ivp(rhs, (0.0, float(times[-1])), np.asarray(y0, float), method="DOP853", t_eval=times,
                    rtol=rtol, atol=1e-16)
    if not sol.success:
        raise RuntimeError(f"the reference failed: {sol.message}")
    return sol.y.T


def quat_rate(q, w) -> np.ndarray:
    """``q' = 1/2 q (x) (w, 0)``, scalar last: written here, not tumble's."""
    x, y, z, s = q
    return 0.5 * np.array([s * w[0] + y * w[2] - z * w[1], s * w[1] + z * w[0] - x * w[2],
                           s * w[2] + x * w[1] - y * w[0], -(x * w[0] + y * w[1] + z * w[2])])


def body_from_world(q) -> np.ndarray:
    """R^T for the body-to-world quaternion q (scalar last), from scipy."""
    return Rotation.from_quat(q).as_matrix().T


def errors(omega, quat, w_ref, q_ref) -> tuple[float, float]:
    """(max |omega - omega_ref| / max |omega_ref|, max attitude angle in rad) over the samples
    (and bodies: leading axes are flattened)."""
    w, wr = np.asarray(omega).reshape(-1, 3), np.asarray(w_ref).reshape(-1, 3)
    ew = float(np.max(np.linalg.norm(w - wr, axis=-1)) / np.max(np.linalg.norm(wr, axis=-1)))
    ea = float(np.max((Rotation.from_quat(np.reshape(quat, (-1, 4))) * Rotation.from_quat(np.reshape(q_ref, (-1, 4))).inv()).magnitude()))
    return ew, ea


def meets(e, target: dict) -> bool:
    return e is not None and e[0] <= target["omega"] and e[1] <= target["attitude"]


# -------------------------------------------------------------------------------------- searches

def search_k(error_of: Callable[[int], tuple], target: dict, k_max: int = 4096):
    """The smallest k meeting ``target``: doubling, then bisection (errors fall with k).
    Returns (k or None, {k: errors})."""
    seen: dict = {}

    def ok(k):
        if k not in seen:
            try:
                seen[k] = error_of(k)
            except (ValueError, RuntimeError) as exc:  # refused (too many steps) or failed
                print(f"  k = {k}: {exc}", file=sys.stderr)
                seen[k] = None
        return meets(seen[k], target)

    hi = 1
    while not ok(hi):
        if hi >= k_max:
            return None, seen
        hi *= 2
    lo = hi // 2
    while hi - lo > 1:
        mid = (lo + hi) // 2
        lo, hi = (lo, mid) if ok(mid) else (mid, hi)
    return hi, seen


def search_rtol(error_of: Callable[[float], tuple], target: dict, rtols=RTOLS):
    """The largest rtol of the ladder meeting ``target``. Returns (rtol or None, {rtol: errors})."""
    seen: dict = {}
    for r in rtols:
        try:
            seen[r] = error_of(r)
        except (ValueError, RuntimeError) as exc:
            print(f"  rtol = {r:g}: {exc}", file=sys.stderr)
            seen[r] = None
        if meets(seen[r], target):
            return r, seen
    return None, seen


# ---------------------------------------------------------------------------------------- timing

def time_call(f: Callable, min_seconds: float = 0.05) -> float:
    """Seconds per call of ``f()``: calls doubled until they take ``min_seconds`` (one warm-up call)."""
    f()
    n = 1
    while True:
        t0 = time.perf_counter()
        for _ in range(n):
            f()
        t = time.perf_counter() - t0
        if t >= min_seconds:
            return t / n
        n *= 2


def paired(candidates: dict, repeat: int, min_seconds: float = 0.05) -> dict:
    """Every candidate timed once per repeat, in turn: {name: array of seconds}."""
    times: dict = {name: [] for name in candidates}
    for _ in range(repeat):
        for name, f in candidates.items():
            times[name].append(time_call(f, min_seconds))
    return {name: np.array(v) for name, v in times.items()}


class Contest:
    """The contenders of one case: each a search's answer and, where one met the target, the call
    to time. ``info`` collects what the report needs (JSON-ready)."""

    def __init__(self, target: dict, **info):
        self.target, self.info, self.calls = target, dict(info, target=target), {}

    def add(self, name: str, knob: str, found, make: Callable) -> None:
        """Record ``found = (value, {value: errors})``; ``make(value)`` gives the call to time."""
        value, seen = found
        self.info[name] = {"knob": knob, knob: value, "errors": seen.get(value),
                           "tried": {f"{k:g}": e for k, e in seen.items()},
                           "refused": bool(seen) and all(e is None for e in seen.values())}
        if value is not None:
            self.calls[name] = make(value)

    def add_k(self, name: str, error_of: Callable, make: Callable, k_max: int = 4096) -> None:
        self.add(name, "k", search_k(error_of, self.target, k_max), make)

    def add_rtol(self, name: str, error_of: Callable, make: Callable, rtols=RTOLS) -> None:
        self.add(name, "rtol", search_rtol(error_of, self.target, rtols), make)

    def add_fixed(self, name: str, errors_: tuple, call: Callable, knob: str = "default") -> None:
        """A contender with no knob (a default call), kept whatever its errors."""
        self.info[name] = {"knob": knob, knob: "-", "errors": errors_, "tried": {}}
        self.calls[name] = call

    def run(self, repeat: int, target_ratio: float, min_seconds: float = 0.05) -> dict:
        """Time every contender, alternating; ratio = the peer's best / tumble's best, per repeat."""
        times = paired(self.calls, repeat, min_seconds)
        for c, v in times.items():
            self.info[c].update({"seconds": float(np.median(v)), "seconds_range": [float(v.min()), float(v.max())]})
        peer_t = [v for c, v in times.items() if c.startswith("peer")]
        tumble_t = [v for c, v in times.items() if c.startswith("tumble")]
        if peer_t and tumble_t:
            ratio = np.min(peer_t, axis=0) / np.min(tumble_t, axis=0)
            self.info.update({"ratio": float(np.median(ratio)), "ratio_range": [float(ratio.min()), float(ratio.max())],
                              "target_ratio": target_ratio, "meets_target": bool(np.median(ratio) >= target_ratio)})
        else:  # one side met nothing: no ratio
            self.info.update({"ratio": None, "ratio_range": None, "target_ratio": target_ratio, "meets_target": False})
        self.info["repeats"] = repeat
        return self.info


# -------------------------------------------------------------------------------------- problems

@dataclass
class Problem:
    """One case: how each side runs it and how far each side's answer is from the reference.

    ``peer(method, k)`` runs the peer (``"rk4"`` or ``"rk8"``, ``k`` steps per interval);
    ``tumble(**kw)`` runs tumble's public call with extra keywords (``method``, ``rtol``, ``step``);
    ``*_errors(output)`` give (omega, attitude) errors; ``interval`` is the peer's sample interval
    or control period (s), so that tumble's ``step = interval / k``; ``methods`` are tumble's
    methods that take this problem, each with its knob (``"rtol"`` or ``"step"``).
    """

    name: str
    target: dict
    peer: Callable[[str, int], Any]
    peer_errors: Callable[[Any], tuple]
    tumble: Callable[..., Any]
    tumble_errors: Callable[[Any], tuple]
    interval: float
    methods: dict
    info: dict = field(default_factory=dict)


def methods_for(kind: str) -> dict:
    """tumble's methods with their knob: ``"torque"`` (one body or a batch with a torque) or
    ``"internal"`` (rotors, a damper: every method that steps, for some take constant rotors only
    and refuse the rest, which the searches report); ``auto`` where the registry has it."""
    import tumble

    out = {}
    for name, m in tumble.METHODS.items():
        ok = m.supports_torque or (kind == "internal" and getattr(m, "supports_internal", False))
        if ok or name == "auto":
            out[name] = "step" if m.fixed_step else "rtol"
    return out


def contest(problem: Problem, timed=("dop853", "rk8", "rk4", "auto"), k_max: int = 4096,
            peer_methods=("rk4", "rk8")) -> Contest:
    """The peer's ``peer_methods`` at their smallest k, and tumble's ``timed`` methods that take the
    problem at their cheapest knob meeting its target."""
    p = problem
    c = Contest(p.target, case=p.name, **p.info)
    for m in peer_methods:
        c.add_k(f"peer {m}", lambda k, m=m: p.peer_errors(p.peer(m, k)), lambda k, m=m: (lambda: p.peer(m, k)), k_max)
    for m in timed:
        knob = p.methods.get(m)
        if knob == "rtol":
            c.add_rtol(f"tumble {m}", lambda r, m=m: p.tumble_errors(p.tumble(method=m, rtol=r)),
                       lambda r, m=m: (lambda: p.tumble(method=m, rtol=r)))
        elif knob == "step":
            c.add_k(f"tumble {m}", lambda k, m=m: p.tumble_errors(p.tumble(method=m, step=p.interval / k)),
                    lambda k, m=m: (lambda: p.tumble(method=m, step=p.interval / k)), k_max)
    return c


# -------------------------------------------------------------------------------------- reporting

def cell(c: dict | None) -> str:
    """One contender: its knob, time [range] and errors."""
    if c is None:
        return "-"
    knob = c["knob"]
    if c.get(knob) is None:
        return "refused" if c.get("refused") else "none meets it"
    value = f"{knob} {c[knob]:g}" if isinstance(c[knob], (int, float)) else knob
    e = c["errors"]
    if "seconds" not in c:
        return f"{value}, errors {e[0]:.1e} / {e[1]:.1e} (not timed)"
    lo, hi = c["seconds_range"]
    return f"{value}: {_t(c['seconds'])} [{_t(lo)}-{_t(hi)}], errors {e[0]:.1e} / {e[1]:.1e}"


def _t(s: float) -> str:
    return f"{s * 1e3:.3g} ms" if s >= 1e-3 else f"{s * 1e6:.3g} us"


def ratio_cell(c: dict) -> str:
    if c.get("ratio") is None:
        return "-"
    lo, hi = c["ratio_range"]
    met = "yes" if c["meets_target"] else "**no**"
    return f"{c['ratio']:.3g} [{lo:.3g}-{hi:.3g}] | >= {c['target_ratio']:g} | {met}"


def table(rows: list[dict], names: list[str], label: Callable[[dict], str], head: str = "case") -> list[str]:
    """A markdown table: one row per case, a column per contender, then ratio, target, met."""
    lines = [f"| {head} | " + " | ".join(names) + " | ratio | target | met |",
             "|---|" + "---|" * len(names) + "---|---|---|"]
    for r in rows:
        lines.append(f"| {label(r)} | " + " | ".join(cell(r.get(n)) for n in names) + f" | {ratio_cell(r)} |")
    return lines


def preamble(title: str, repeat: int, what: str) -> list[str]:
    return [f"# {title}", "", f"{machine()}; {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; medians over "
            f"{repeat} alternating repeats, ranges in brackets; errors omega (relative to max |omega|) / "
            "attitude (rad) against scipy DOP853 rtol 1e-13 on a right-hand side written in the "
            f"benchmark. Peers: {PEERS} (unchanged). Ratio = the peer's best time / tumble's best. {what}", ""]
