"""Parameters of the torque-free motion through one omega: in double-double, free of underflow.

The formulas are those of :mod:`tumble.dynamics.methods.exact` (Landau & Lifshitz, *Mechanics*, sec.
37), with ``g_j = L^2 - 2 E I_j = sum_{i != j} I_i (I_i - I_j) w_i^2`` (without cancellation,
Celledoni, Fasso, Safstrom & Zanna, SIAM J. Sci. Comput. 30 (2008) 2084, sec. 2). What is
added here is only how they are evaluated:

- ``g_j`` does not contain ``w_j``, and it is homogeneous of degree 2 in omega: each is formed
  from omega scaled by the power of two ``2^e_j`` nearest above its largest *other* component,
  ``g_j = 4^e_j gt_j`` exactly, so that no square underflows (``omega = (0, 1, 1e-160)`` has
  ``g2 ~ 1e-320``, below the normal range, but ``gt2`` is of order 1); the moments are scaled by
  a power of two too (every parameter is homogeneous of degree 0 in them);
- the products and quotients are taken in double-double (:mod:`tumble.dynamics.special.ddouble`) with
  the moment differences formed exactly, so that ``p``, ``k'``, ``n`` and the rates are good to
  ~1e-31, as the phase of a long run needs (``u = u0 + p t`` with ``p t`` up to 1e20);
- ``k = sqrt(m)`` and ``k' = sqrt(1 - m)`` are formed as ``2^(e_a - e_b) sqrt(ratio)``:
  ``k' = 1e-160`` stays representable where ``1 - m = 1e-320`` is not even a normal double,
  and ``k'`` is also returned as a double-double mantissa and a binary exponent, from which
  ``K`` is found however small ``k'`` is (:func:`tumble.dynamics.special.carlson.complete_integrals`).
"""

from __future__ import annotations

import contextvars
import functools
import math
import os
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from types import ModuleType
from typing import Any, NamedTuple, TypeAlias, TypedDict, cast

import numpy as np

from ...jit import PARALLEL_BODIES, cores
from ...typing import ArrayLike, BoolArray, FloatArray, FloatOrArray, IntArray
from ..special import ddouble as dd
from ..special.ddouble import DoubleDouble

__all__ = ["COMPILED_BODIES", "EllipticParameters", "compiled_kernels", "elliptic_parameters"]

#: Motions from which the batches run compiled (:mod:`tumble.dynamics.methods.compiled_exact`:
#: :func:`elliptic_parameters` here, :func:`tumble.dynamics.methods.exact_batch.free_rotation_batch`),
#: in double precision with the double-double path taking the motions the kernel marks. The
#: first compiled call of a process costs ~0.6 s (numba's import, the cached kernels' load, the
#: threads' start; measured), the compiled path saves ~2 us a body with its attitude: from
#: 65,536 bodies a batch pays it back within a few calls (the first compile after an edit of the
#: sources, ~8 s, once per machine).
COMPILED_BODIES = 1 << 16


@functools.cache
def compiled_kernels() -> ModuleType:
    """The compiled kernels of the exact motion (:mod:`tumble.dynamics.methods.compiled_exact`),
    imported on first use: that import imports numba and compiles (or loads from numba's cache)
    every kernel, which ``import tumble`` never does.

    Examples
    --------
    >>> from tumble.dynamics.methods.exact_parameters import compiled_kernels
    >>> compiled_kernels().__name__
    'tumble.dynamics.methods.compiled_exact'
    """
    from . import compiled_exact

    return compiled_exact


#: Motions that :func:`elliptic_parameters` takes at once: its double-double temporaries stay in
#: cache (measured on a million motions: 0.57 s in chunks of this size against 1.1-2.0 s at once).
_CHUNK = 1 << 14
#: Threads over such chunks (here and in :mod:`tumble.dynamics.methods.exact_batch`): the cores
#: this process may use. numpy releases the GIL within each operation on a chunk, so the chunks
#: share the cores; each chunk's arithmetic is the same whichever thread runs it.
THREADS = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)


def run_chunks(function: Callable[[int], Any], starts: range) -> list[Any]:
    """``[function(s) for s in starts]``, the calls spread over :data:`THREADS` threads when
    there are several, each in a copy of the caller's context (so numpy's ``errstate`` holds
    in them as in the caller).

    Examples
    --------
    >>> from tumble.dynamics.methods.exact_parameters import run_chunks
    >>> run_chunks(lambda s: s * s, range(0, 10, 3))
    [0, 9, 36, 81]
    """
    workers = min(THREADS, len(starts))
    if workers <= 1:
        return [function(s) for s in starts]
    with ThreadPoolExecutor(workers) as pool:
        return list(pool.map(lambda task: task[0].run(function, task[1]),
                             [(contextvars.copy_context(), s) for s in starts]))


class EllipticParameters(NamedTuple):
    """Parameters of the torque-free motion through one omega (module docstring); arrays (...).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.exact_parameters import elliptic_parameters
    >>> par = elliptic_parameters([0.1, 1.0, 0.1], [1.0, 2.0, 3.0])
    >>> par._fields
    ('upper', 'p', 'm', 'm1', 'amplitudes', 'k', 'kp')
    >>> bool(par.upper), round(float(par.m + par.m1), 15), round(float(par.k**2 + par.kp**2), 15)
    (True, 1.0, 1.0)
    """

    upper: np.ndarray  # L^2 >= 2 E I2: omega circulates about axis 3 (else about axis 1)
    p: np.ndarray  # rate of the elliptic argument u = u0 + p t, 1/s
    m: np.ndarray  # parameter k^2 (may underflow where k does not)
    m1: np.ndarray  # 1 - k^2, formed directly (may underflow where k' does not)
    amplitudes: np.ndarray  # a1, a2, a3 (rad/s), shape (..., 3)
    k: np.ndarray  # sqrt(m), formed directly
    kp: np.ndarray  # k' = sqrt(1 - m), formed directly


#: A double-double mantissa and a power of two: ``x = mantissa 2^exponent`` (floats and an
#: int for one motion, arrays elementwise for a batch).
Scaled: TypeAlias = tuple[DoubleDouble, "int | IntArray"]


class ScaledCore(TypedDict):
    """What :func:`scaled_core` returns (its docstring says what each entry is)."""

    upper: bool | BoolArray
    moments: FloatArray
    p: DoubleDouble
    k: Scaled
    kp: Scaled
    amplitudes: FloatArray
    n: DoubleDouble


# Scalars (one motion: FreeRotation) go through Python floats and only the branch taken, which
# is several times faster than numpy's 0-d arrays; arrays (a batch) through numpy. Same code.
def _exponent(x: FloatOrArray) -> int | IntArray:
    """``e`` with ``x = f 2^e``, ``1/2 <= |f| < 1`` (0 for x = 0)."""
    return math.frexp(x)[1] if isinstance(x, float) else np.frexp(x)[1]


def _ldexp(x: FloatOrArray, e: int | IntArray) -> FloatOrArray:
    if isinstance(x, float) and isinstance(e, int):  # not for numpy exponents (0-d arrays)
        return math.ldexp(x, e)  # OverflowError is caught by scaled_core
    with np.errstate(over="ignore"):
        return np.ldexp(x, e)


def _branch(cond: bool | BoolArray, upper: Callable[[], Scaled], lower: Callable[[], Scaled]) -> Scaled:
    """``upper()`` where ``cond``, else ``lower()``; both, selected, for arrays."""
    if isinstance(cond, bool):
        return upper() if cond else lower()
    x, y = upper(), lower()
    pick: Callable[[ArrayLike, ArrayLike], Any] = (lambda a, b: np.where(cond, a, b))
    return (pick(x[0][0], y[0][0]), pick(x[0][1], y[0][1])), pick(x[1], y[1])


def _scaled_root(num: DoubleDouble, den: DoubleDouble, exponent: int | IntArray) -> Scaled:
    """``sqrt(num / den)`` (double-doubles) as a double-double mantissa and ``2^exponent``."""
    return dd.sqrt(dd.div(num, den)), exponent


def scaled_core(omega: ArrayLike, moments: ArrayLike) -> ScaledCore:
    """Everything the exact solution needs, in double-double and in scaled form (module
    docstring); broadcasts over (..., 3). Keys: ``upper``, ``moments`` (scaled, ``I3`` in
    [1/2, 1)), ``p`` (double-double, 1/s), ``k``, ``kp`` (each ``(mantissa dd, exponent)``),
    ``amplitudes`` (double, rad/s), ``n`` (double-double: the characteristic of the attitude's
    Pi). Moments must be ascending; degenerate ones give inf or nan (never an exception)."""
    w = np.asarray(omega, float)
    I = np.asarray(moments, float)
    if w.shape == (3,) and I.shape == (3,):
        try:
            return _core([float(x) for x in w], [float(x) for x in I])
        except (ZeroDivisionError, OverflowError):  # degenerate moments: as numpy would
            pass
    w, I = np.broadcast_arrays(w, I)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
        return _core([w[..., i] for i in range(3)], [I[..., i] for i in range(3)])


def _core(w: list[FloatOrArray], I: list[FloatOrArray]) -> ScaledCore:
    eI = _exponent(I[2])
    I = [_ldexp(x, -eI) for x in I]
    I1, I2, I3 = I
    gaps, exps = [], []
    scalar = isinstance(w[0], float)
    for j in range(3):
        a, b = (i for i in range(3) if i != j)
        # Scale by the larger component whose coefficient I_i - I_j is not zero: a component with
        # a zero coefficient (a symmetric top) adds nothing, and scaling by it would underflow
        # the other one's square (moments (1, 2, 2), omega (3e-178, 1, 1)); it is left out.
        live = [I[i] != I[j] for i in (a, b)]
        size = [cast(FloatOrArray, abs(w[i])) if scalar else np.abs(w[i]) for i in (a, b)]
        if scalar:
            big = max((x for x, on in zip(size, live) if on), default=max(size))
        else:
            big = np.maximum(np.where(live[0], size[0], 0.0), np.where(live[1], size[1], 0.0))
            big = np.where(live[0] | live[1], big, np.maximum(size[0], size[1]))
        e = _exponent(big)
        g: DoubleDouble = (0.0, 0.0)
        for i, on in zip((a, b), live):
            x = _ldexp(w[i], -e) if (not scalar or on) else 0.0
            if not scalar:
                x = np.where(on, x, 0.0)
            term = dd.mul(dd.mul_d(dd.two_sum(I[i], -I[j]), I[i]), dd.two_prod(x, x))
            g = dd.add(g, term)
        gaps.append(g)
        exps.append(e)
    (g1, g2, g3), (e1, e2, e3) = gaps, exps
    upper = g2[0] >= 0  # the separatrix is taken from this side
    d21, d31, d32 = dd.two_sum(I2, -I1), dd.two_sum(I3, -I1), dd.two_sum(I3, -I2)
    prod = dd.mul_d(dd.two_prod(I1, I2), I3)
    p = _branch(upper, lambda: _scaled_root(dd.mul(d32, g1), prod, e1),
                lambda: _scaled_root(dd.mul(d21, dd.neg(g3)), prod, e3))
    k = _branch(upper, lambda: _scaled_root(dd.mul(d21, dd.neg(g3)), dd.mul(d32, g1), e3 - e1),
                lambda: _scaled_root(dd.mul(d32, g1), dd.mul(d21, dd.neg(g3)), e1 - e3))
    kp = _branch(upper, lambda: _scaled_root(dd.mul(d31, g2), dd.mul(d32, g1), e2 - e1),
                 lambda: _scaled_root(dd.mul(d31, dd.neg(g2)), dd.mul(d21, dd.neg(g3)), e2 - e3))
    a2 = _branch(upper, lambda: _scaled_root(dd.neg(g3), dd.mul_d(d32, I2), e3),
                 lambda: _scaled_root(g1, dd.mul_d(d21, I2), e1))
    n, _ = _branch(upper, lambda: (dd.neg(dd.div(dd.mul_d(d21, I3), dd.mul_d(d32, I1))), 0),
                   lambda: (dd.neg(dd.div(dd.mul_d(d32, I1), dd.mul_d(d21, I3))), 0))
    a1 = _scaled_root(dd.neg(g3), dd.mul_d(d31, I1), e3)
    a3 = _scaled_root(g1, dd.mul_d(d31, I3), e1)
    amps = [_ldexp(x[0][0], x[1]) for x in (a1, a2, a3)]
    return {"upper": upper, "moments": np.stack(I, axis=-1), "p": (_ldexp(p[0][0], p[1]), _ldexp(p[0][1], p[1])),
            "k": k, "kp": kp, "amplitudes": np.stack(amps, axis=-1), "n": n}


def elliptic_parameters(omega: ArrayLike, moments: ArrayLike) -> EllipticParameters:
    """``p``, ``m``, ``1 - m``, the amplitudes, ``k`` and ``k'`` of the motion through
    ``omega``, for ascending moments (:mod:`tumble.dynamics.methods.exact`); broadcasts over (..., 3).

    ``1 - m`` is formed from the energy-momentum gaps directly, never as ``1 - m``; nothing
    underflows that the answer does not (module docstring).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.methods.exact_parameters import elliptic_parameters
    >>> I, w = np.array([1.0, 2.0, 3.0]), np.array([0.1, 1.0, 0.1])
    >>> L2, E2 = np.sum((I * w) ** 2), np.sum(I * w**2)   # |L|^2 and 2 E; L^2 > 2 E I2: about axis 3
    >>> m = (I[1] - I[0]) * (E2 * I[2] - L2) / ((I[2] - I[1]) * (L2 - E2 * I[0]))   # Landau & Lifshitz sec. 37
    >>> p = np.sqrt((I[2] - I[1]) * (L2 - E2 * I[0]) / np.prod(I))
    >>> par = elliptic_parameters(w, I)
    >>> bool(par.upper), bool(np.isclose(par.m, m, rtol=1e-14)), bool(np.isclose(par.p, p, rtol=1e-14))
    (True, True, True)
    >>> elliptic_parameters(np.array([w, [1.0, 0.1, 0.1]]), I).m1.shape   # broadcasts over (..., 3)
    (2,)
    """
    w, I = np.asarray(omega, float), np.asarray(moments, float)
    if w.ndim > 1 or I.ndim > 1:
        w, I = np.broadcast_arrays(w, I)
        if w[..., 0].size >= COMPILED_BODIES:
            return _compiled_parameters(w, I)
    return _parameters(w, I)


def _parameters(w: FloatArray, I: FloatArray) -> EllipticParameters:
    """:func:`elliptic_parameters` in double-double (moments and omega broadcast already)."""
    if w.ndim > 1 and w[..., 0].size > _CHUNK:  # many motions: in chunks that stay in cache, each as alone
        flat_w, flat_I = w.reshape(-1, 3), I.reshape(-1, 3)
        parts = run_chunks(lambda s: _parameters(flat_w[s:s + _CHUNK], flat_I[s:s + _CHUNK]),
                           range(0, len(flat_w), _CHUNK))
        return EllipticParameters(*(np.concatenate(x).reshape(w.shape[:-1] + np.shape(x[0])[1:])
                                    for x in zip(*parts)))
    c = scaled_core(w, I)

    def value(x: Scaled, power: int = 1) -> FloatOrArray:
        (hi, _), e = x
        with np.errstate(over="ignore", invalid="ignore"):
            return np.clip(np.ldexp(hi**power, power * e), 0.0, 1.0)

    fields = (c["upper"], c["p"][0], value(c["k"], 2), value(c["kp"], 2), c["amplitudes"], value(c["k"]), value(c["kp"]))
    return EllipticParameters(*(np.asarray(x)[()] for x in fields))  # numpy types, as numpy math gives


def _compiled_parameters(w: FloatArray, I: FloatArray) -> EllipticParameters:
    """:func:`elliptic_parameters` of many motions by the compiled kernel
    (:func:`tumble.dynamics.methods.compiled_exact.parameters_body`, double precision, every
    core), the motions it marks (next to the separatrix, steady, out of range) in double-double."""
    shape = w.shape[:-1]
    flat_w, flat_I = (np.ascontiguousarray(a.reshape(-1, 3)) for a in (w, I))
    N = len(flat_w)
    out, done = np.empty((9, N)), np.empty(N, dtype=np.bool_)  # a row a field: no copies
    kernels = compiled_kernels()
    kernel = kernels.parameters_parallel if N >= PARALLEL_BODIES and cores() > 1 else kernels.parameters_serial
    kernel(flat_I, flat_w, out, done)
    fields = [out[0] != 0.0, out[1], out[2], out[3], out[4:7].T, out[7], out[8]]
    left = np.flatnonzero(~done)
    if left.size:
        for field, rest in zip(fields, _parameters(flat_w[left], flat_I[left])):
            field[left] = rest
    return EllipticParameters(*(np.ascontiguousarray(f).reshape(shape + f.shape[1:]) for f in fields))
