"""1e6 torque-free bodies: final omega and attitude at 20 s and the flip interval (issue 38 item 7).

The target: at most 1 s on 2 cores, at most 1e-12 relative error. What a user calls::

    batch = tumble.simulate_batch(I, w, times=[20.0], attitude0=q)   # method "exact" (the default)
    T = tumble.flip_interval(w, I)

Timed end to end (median and range over ``--repeat`` runs, wall clock and the process's CPU
time), and in parts: ``simulate_batch``'s input checks (``check_batch``), the exact flow
(``free_rotation_batch``: the compiled kernel, ``tumble/dynamics/methods/compiled_exact.py``,
and the double-double path for the bodies it leaves), ``flip_interval``; beside them the
double-double path alone on the same bodies (what the batch ran before). Bodies as
benchmarks/bench_batch.py draws them: moments uniform in [0.1, 1] kg m^2 within the triangle
inequality, omega ~ N(0, 1) rad/s per component, random attitudes.

The error is measured on a subsample of the bodies and on bodies next to the separatrix
(k'^2 from 1e-4 to 0.3) against the double-double path
(:class:`tumble.dynamics.methods.exact_kernel.EllipticMotion`, checked against mpmath in
tests/test_exact.py): omega relative to |omega|, the attitude as the angle between the two
rotations (rad), the flip interval relative; and the flip interval of a few hundred bodies
against mpmath (``ellipk`` at 40 digits from the moments and omega as exact rationals).

Run: ``python benchmarks/bench_exact_batch.py [--bodies 1000000] [--repeat 5]``.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import time
from collections.abc import Iterator
from fractions import Fraction

import numpy as np
from scipy.spatial.transform import Rotation

import tumble
from tumble.dynamics.batch import check_batch
from tumble.dynamics.methods import exact_batch, exact_parameters
from tumble.dynamics.methods.exact_parameters import _parameters, compiled_kernels
from tumble.dynamics.special.elliptic import ellipk_kp


def bodies(n: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Moments (n, 3), omega (n, 3), attitudes (n, 4) as bench_batch draws them."""
    rng = np.random.default_rng(seed)
    I = np.sort(rng.uniform(0.1, 1.0, (n, 3)), axis=1)
    bad = I[:, 2] > I[:, 0] + I[:, 1]
    while np.any(bad):
        I[bad] = np.sort(rng.uniform(0.1, 1.0, (int(bad.sum()), 3)), axis=1)
        bad = I[:, 2] > I[:, 0] + I[:, 1]
    return I, rng.normal(size=(n, 3)), Rotation.random(n, random_state=seed).as_quat()


def near_separatrix(n: int, seed: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Spins off the intermediate axis by 1e-2 to 0.3 of it: k'^2 from ~1e-4 to ~0.3."""
    rng = np.random.default_rng(seed)
    I = np.sort(rng.uniform(0.1, 1.0, (n, 3)), axis=1)
    I[:, 2] = np.minimum(I[:, 2], I[:, 0] + I[:, 1])
    eps = 10.0 ** rng.uniform(-2.0, -0.5, n)
    w = np.stack([eps * rng.normal(size=n), rng.choice([-1.0, 1.0], n), eps * rng.normal(size=n)], axis=1)
    return I, w, Rotation.random(n, random_state=seed).as_quat()


def timed(function) -> tuple[float, float]:
    """Wall-clock and CPU seconds of one call."""
    wall, cpu = time.perf_counter(), time.process_time()
    function()
    return time.perf_counter() - wall, time.process_time() - cpu


def summary(values: list[float]) -> str:
    a = np.array(values)
    return f"{np.median(a):.3f} s [{a.min():.3f}, {a.max():.3f}]"


@contextlib.contextmanager
def compiled_always() -> Iterator[None]:
    """The batches through the compiled kernels whatever their size (a sample is smaller than
    ``COMPILED_BODIES``)."""
    sizes = exact_batch.COMPILED_BODIES, exact_parameters.COMPILED_BODIES
    exact_batch.COMPILED_BODIES = exact_parameters.COMPILED_BODIES = 0
    try:
        yield
    finally:
        exact_batch.COMPILED_BODIES, exact_parameters.COMPILED_BODIES = sizes


def errors(I: np.ndarray, w: np.ndarray, q: np.ndarray, t: np.ndarray) -> dict[str, float]:
    """The largest errors of the batch as a large batch gets it (free_rotation_batch and
    flip_interval through the compiled kernels, whatever the sample's size) against the
    double-double path."""
    with compiled_always():
        omega, quat = exact_batch.free_rotation_batch(I, w, q, t)
        T = tumble.flip_interval(w, I)
    ref_w, ref_q = exact_batch._double_double(I, w, q, t, True)
    err_w = np.linalg.norm(omega - ref_w, axis=-1) / np.linalg.norm(ref_w, axis=-1)
    angle = (Rotation.from_quat(quat.reshape(-1, 4)).inv() * Rotation.from_quat(ref_q.reshape(-1, 4))).magnitude()
    par = _parameters(w, I)
    with np.errstate(divide="ignore", invalid="ignore"):
        ref_T = np.where(par.kp > 0, 2.0 * ellipk_kp(par.kp) / par.p, np.inf)
    finite = np.isfinite(ref_T)
    kernels = compiled_kernels()
    done = np.empty(len(I), dtype=np.bool_)
    kernels.motion_serial(I, w, q, t, True, np.empty(ref_w.shape), np.empty(ref_q.shape), done)
    return {"omega": float(np.max(err_w)), "attitude_rad": float(np.max(angle)),
            "flip_interval": float(np.max(np.abs(T[finite] / ref_T[finite] - 1.0))),
            "left_to_double_double": float(1.0 - np.mean(done))}


def mpmath_periods(I: np.ndarray, w: np.ndarray) -> float:
    """Largest relative error of flip_interval (compiled) against mpmath at 40 digits."""
    import mpmath

    mpmath.mp.dps = 40
    with compiled_always():
        T = tumble.flip_interval(w, I)
    worst = 0.0
    for (I1, I2, I3), (w1, w2, w3), got in zip(I, w, T):
        I1, I2, I3, w1, w2, w3 = (Fraction(float(x)) for x in (I1, I2, I3, w1, w2, w3))
        L2 = (I1 * w1) ** 2 + (I2 * w2) ** 2 + (I3 * w3) ** 2
        E2 = I1 * w1 ** 2 + I2 * w2 ** 2 + I3 * w3 ** 2
        if L2 > E2 * I2:
            p2, m = (I3 - I2) * (L2 - E2 * I1) / (I1 * I2 * I3), (I2 - I1) * (E2 * I3 - L2) / ((I3 - I2) * (L2 - E2 * I1))
        else:
            p2, m = (I2 - I1) * (E2 * I3 - L2) / (I1 * I2 * I3), (I3 - I2) * (L2 - E2 * I1) / ((I2 - I1) * (E2 * I3 - L2))
        ref = 2 * mpmath.ellipk(mpmath.mpf(m.numerator) / m.denominator) / mpmath.sqrt(mpmath.mpf(p2.numerator) / p2.denominator)
        worst = max(worst, abs(float(got / ref - 1)))
    return worst


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bodies", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--sample", type=int, default=20_000, help="bodies whose error is measured")
    args = parser.parse_args()
    I, w, q = bodies(args.bodies)
    t = np.array([20.0])
    print(f"{args.bodies:,} bodies, {os.cpu_count()} cores (affinity {len(os.sched_getaffinity(0))}), "
          f"numba threads {os.environ.get('NUMBA_NUM_THREADS', 'default')}")

    def user() -> None:
        tumble.simulate_batch(I, w, times=t, attitude0=q)
        tumble.flip_interval(w, I)

    parts = {
        "simulate_batch + flip_interval (the user's calls)": user,
        "  check_batch (simulate_batch's input checks)": lambda: check_batch(I, w, q),
        "  free_rotation_batch (compiled + double-double for the rest)": lambda: exact_batch.free_rotation_batch(I, w, q, t),
        "  flip_interval": lambda: tumble.flip_interval(w, I),
    }
    user()  # the kernels' import and the cache's load, once per process
    wall: dict[str, list[float]] = {name: [] for name in parts}
    cpu: dict[str, list[float]] = {name: [] for name in parts}
    for _ in range(args.repeat):
        for name, function in parts.items():
            a, b = timed(function)
            wall[name].append(a)
            cpu[name].append(b)
    for name in parts:
        print(f"{name:66s} wall {summary(wall[name])}  cpu {summary(cpu[name])}")
    n_old = min(args.bodies, 100_000)
    a, b = timed(lambda: exact_batch._double_double(I[:n_old], w[:n_old], q[:n_old], t, True))
    scale = args.bodies / n_old
    print(f"{'  the double-double path alone (before), scaled from ' + format(n_old, ',') + ' bodies':66s} "
          f"wall {a * scale:.3f} s  cpu {b * scale:.3f} s")
    sample = min(args.sample, args.bodies)
    for title, (Is, ws, qs) in (("random bodies", (I[:sample], w[:sample], q[:sample])),
                                ("next to the separatrix", near_separatrix(max(sample // 4, 1000)))):
        for t_end in (20.0, 100.0):
            e = errors(Is, ws, qs, np.array([0.0, t_end]))
            print(f"error, {title}, t = 0 and {t_end:g} s: omega {e['omega']:.2e} (relative), attitude "
                  f"{e['attitude_rad']:.2e} rad, flip interval {e['flip_interval']:.2e} (relative); "
                  f"{100 * e['left_to_double_double']:.2f} % left to double-double")
    print(f"flip interval against mpmath (300 bodies): {mpmath_periods(I[:300], w[:300]):.2e} (relative)")


if __name__ == "__main__":
    main()
