"""The engine's fixed-step batch in vector lanes: many bodies stepped together, one in each lane.

:func:`~tumble.dynamics.engine.kernels.fixed_batch` steps each body on its own, a scalar loop a
core. A fixed-step batch steps every body in lockstep, with the same step where their steps agree,
so a block of :data:`LANES` bodies can take each step together: their states laid out as a
structure of arrays (a row of ``LANES`` floats per component,
:data:`~tumble.dynamics.engine.unrolled.LANE_ROWS`), each stage computed as loops over the lanes
that LLVM turns into vector instructions (512-bit registers of 8 doubles, checked in the assembly of
``inspect_asm``: ``vfmadd...pd`` on ``zmm``), and the blocks spread over the cores with ``prange``. The steps are written out from the tableaux by
:func:`~tumble.dynamics.engine.unrolled.lane_step_source` and call the kernels' one right-hand side
(:func:`~tumble.dynamics.engine.kernels.rhs`); the loop through the samples is the engine's one
fixed-step loop (:func:`~tumble.dynamics.engine.unrolled.fixed_loop_source`). Each body takes the
same steps of the same length as alone, with the same sums in the same order: the samples agree
with :func:`~tumble.dynamics.engine.kernels.fixed_batch` to round-off (the compiler fuses
multiply-adds, ``fastmath={"contract"}``, as it may in the scalar kernel: tests/test_engine_lanes.py).

A block whose bodies would split a sample interval into different numbers of steps (their largest
steps differ; the front sorts the bodies by step so that a block's mostly agree) poisons its state
with a NaN; so does a body that overflows. Such a block ends with
:data:`~tumble.dynamics.engine.status.NON_FINITE`, and the front runs its bodies again one by one
(:func:`~tumble.dynamics.engine.front.run_bodies`).

Measured (benchmarks/bench_engine.py, 2,000 bodies under a constant torque, RK8 at 6 steps a 0.2 s
sample, 20 s, both on 2 cores, alternating in one process): 28.5 ms against the reference peer's 75.4 ms
(``../shared/peers/numba_peer.py``, a scalar loop a body over ``prange``), 2.7x; the one-body kernels
over ``prange`` had taken 67.5 ms against its 75.8 ms (1.12x). A body's step costs 35-45 ns here against 105 ns alone (one core): a
lone body's step is a chain of dependent stages, which the lanes fill. The first compile of the RK8
batch is 7-12 CPU-s (RK4: 2.4-3.8), cached after.

Imported only when a compiled batch runs (it compiles with numba, :func:`tumble.jit.jit`).
"""

from __future__ import annotations

import math
from typing import Any, cast

import numpy as np
from numba import prange

from ...jit import jit
from .kernels import _direction, _rk4_turns, _rk8_turns, _store, generated, rhs
from .status import NON_FINITE, OK
from .stepsize import equal_steps
from .tableau import DOP853_A, DOP853_B, DOP853_C, RK4_A, RK4_B, RK4_C
from .unrolled import LANE_ROWS, STATE, fixed_loop_source, lane_rows, lane_step_source

__all__ = ["LANES", "lanes_rk4", "lanes_rk8"]

#: Bodies a block steps together: two 512-bit registers of doubles, so that the core has a second
#: register's work while the first waits on its latencies (measured: a step 1.2-1.4x faster a body
#: than with 8 lanes, 2x than with 4; 24 no better, 32 slower).
LANES = 16
#: The rows of a block's work array (the largest tableau's, 12 stages).
ROWS = lane_rows(12)
_BODY = LANE_ROWS["body"]

@jit(error_model="numpy")
def _load(y0: np.ndarray, I: np.ndarray) -> tuple[np.ndarray, float]:
    """A block's work array from its bodies' states ``y0`` (n, 7) and moments ``I`` (n, 3), n <= :data:`LANES`:
    the lanes past the last body repeat it."""
    W = np.empty(ROWS * LANES)
    n = y0.shape[0]
    for j in range(LANES):
        b = min(j, n - 1)
        for c in range(STATE):
            W[c * LANES + j] = y0[b, c]
        for c in range(3):
            W[(_BODY + c) * LANES + j] = I[b, c]
            W[(_BODY + 3 + c) * LANES + j] = 1.0 / I[b, c]
    return W, 0.0


@jit(error_model="numpy")
def _sample(W: np.ndarray, I: np.ndarray, omega: np.ndarray, quat: np.ndarray, index: np.ndarray, k: int) -> None:
    """Sample ``k`` of each body ``index[j]`` of the block, as the one-body kernels store it."""
    for j in range(index.shape[0]):
        y = (W[j], W[LANES + j], W[2 * LANES + j], W[3 * LANES + j], W[4 * LANES + j], W[5 * LANES + j],
             W[6 * LANES + j])
        _store(y, omega[index[j], k], quat[index[j], k])


@jit(error_model="numpy")
def _finite(W: np.ndarray) -> bool:
    """Whether every lane's state is finite (one sum)."""
    total = 0.0
    for i in range(STATE * LANES):
        total += W[i]
    return math.isfinite(total)


@jit(error_model="numpy")
def _block_steps(interval: float, step: np.ndarray) -> tuple[int, float]:
    """The block's equal steps through a sample ``interval`` (s), each body's largest step in ``step``:
    :func:`~tumble.dynamics.engine.stepsize.equal_steps` where all bodies agree, else a NaN step."""
    m, h = equal_steps(interval, step[0])
    for j in range(1, step.shape[0]):
        if equal_steps(interval, step[j])[0] != m:
            return m, math.nan
    return m, h


#: The kernels' rhs inlined by numba in the loop over the lanes, where LLVM vectorises it: called
#: there and inlined by LLVM (its ``alwaysinline``), the batch ran 15-20 % slower (2,000 bodies, one
#: thread, measured alternating). The same function with rhs's own options (numba keys its cache on
#: the function, not the options: ``tests/test_jit_cache.py``), inlined by numba instead.
_IN_LANES = jit(cast(Any, rhs).py_func, error_model="numpy", inline="always", forceinline=True)

_STEPS = generated(lane_step_source("rk4_lanes", RK4_A, RK4_B, RK4_C, LANES)
                   + lane_step_source("rk8_lanes", DOP853_A[:12, :12], DOP853_B, DOP853_C[:12], LANES),
                   __file__, __name__, inner=True, rhs=_IN_LANES)
_RUNS = generated(fixed_loop_source("run_rk4", "rk4_lanes", "rk4_turns", "_load", "_sample", "omega, quat, index")
                  + fixed_loop_source("run_rk8", "rk8_lanes", "rk8_turns", "_load", "_sample", "omega, quat, index"),
                  __file__, __name__, rk4_lanes=_STEPS["rk4_lanes"], rk8_lanes=_STEPS["rk8_lanes"], rk4_turns=_rk4_turns,
                  rk8_turns=_rk8_turns, _load=_load, _sample=_sample, _equal_steps=_block_steps, _direction=_direction,
                  _finite=_finite, OK=OK, NON_FINITE=NON_FINITE)
_run_rk4, _run_rk8 = _RUNS["run_rk4"], _RUNS["run_rk8"]


# The batches: RK4 and RK8 over blocks of LANES bodies on every core, ``run(y0, t_eval, I, P, n, step, index,
# omega, quat, status)``: the bodies in the order of the rows of ``y0``, ``I`` and ``step``, body ``b`` of them
# written to ``omega[index[b]]``, ``quat[index[b]]``; each block's status in ``status``. One kernel a method, so
# that a run compiles only its own step.
_BATCH = """def {name}(y0, t_eval, I, P, n, step, index, omega, quat, status):
    for block in prange(status.shape[0]):
        lo = block * LANES
        hi = min(lo + LANES, y0.shape[0])
        status[block] = {run}(y0[lo:hi], t_eval, I[lo:hi], P, n, step[lo:hi], omega, quat, index[lo:hi])
"""
_BATCHES = generated(_BATCH.format(name="lanes_rk4", run="run_rk4") + _BATCH.format(name="lanes_rk8", run="run_rk8"),
                     __file__, __name__, parallel=True, prange=prange, LANES=LANES, run_rk4=_run_rk4, run_rk8=_run_rk8)
#: The batches of RK4 and RK8 in lanes (on every core).
lanes_rk4, lanes_rk8 = _BATCHES["lanes_rk4"], _BATCHES["lanes_rk8"]
