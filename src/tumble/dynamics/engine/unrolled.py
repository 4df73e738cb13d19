"""The engine's Runge-Kutta steps written out from their tableaux: source text, one generator.

A step of an explicit Runge-Kutta method over the rigid body's 7-float state is fastest as
straight-line code over tuples, every coefficient a literal: the compiler keeps the stages in
registers, drops the zero coefficients and fuses the rest (measured 1.3-1.5x the same step as
loops over a stage array; the reference peer of ``../shared/peers`` is written so). Writing the
12-stage DOP853 step out by hand would be ~300 lines to keep right; instead this module writes
its source from the tableau (:mod:`~tumble.dynamics.engine.tableau`), the one place the
coefficients live, and :mod:`~tumble.dynamics.engine.kernels` compiles it. A sum of three slopes or
more is written as a short loop over a tuple of the slopes and one of their literal weights
(:data:`LOOPED_TERMS`), which LLVM unrolls into the same straight-line code: numba types its one
line instead of every term, the larger part of a kernel's first compile. Imports no numba.

Every generated function takes the state ``y`` (a 7-tuple: omega in rad/s, then the quaternion),
the step ``h`` (s), the body ``I`` (a 3-tuple of principal moments, kg m^2), the torque terms
``P`` and the orbit's direction at the step's start ``cs, ss`` (cos and sin of ``n t``),
turned to each stage by ``rot`` (cos and sin of ``n c_s h`` for the stage nodes ``c_s``,
:func:`rotations_source`): the circular orbit's direction at every stage with two trigonometric
calls per step, not two per stage. It calls ``rhs(y, I, P, u0, u1)``, the kernels' one
right-hand side. A state that carries more than the body (the closed loop's wheel spins and
external impulse, :mod:`~tumble.dynamics.control.compiled_loop`) gets the same steps from the
same lines over its own size, with a right-hand side that takes the time, ``rhs(t, y, P, X, u0,
u1)`` (:class:`Layout`, :func:`state_layout`).

Examples
--------
>>> from tumble.dynamics.engine.unrolled import fixed_step_source
>>> from tumble.dynamics.engine.tableau import RK4_A, RK4_B, RK4_C
>>> print(fixed_step_source("rk4_step", RK4_A, RK4_B, RK4_C).splitlines()[0])
def rk4_step(y, h, I, P, cs, ss, rot):
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Union

import numpy as np

Coefficients = Union[Sequence[float], np.ndarray]

from .tableau import DOP853_A, DOP853_B, DOP853_C, DOP853_D, DOP853_E3, DOP853_E5

__all__ = ["LANE_ROWS", "LOOPED_TERMS", "RIGID_BODY", "STATE", "Layout", "dop853_accept_source", "dop853_errors_lines",
           "dop853_sources", "fixed_loop_source",
           "fixed_step_source", "lane_rows", "lane_step_source", "rotations_source", "state_layout"]

#: Size of the rigid body's state ``(omega, q)``.
STATE = 7


@dataclass(frozen=True)
class Layout:
    """How a state's steps are written: its ``size`` (floats), the right-hand side's arguments
    after the state (``params``), and whether it takes the stage's time first (``timed``).

    Examples
    --------
    >>> from tumble.dynamics.engine.unrolled import RIGID_BODY, state_layout
    >>> RIGID_BODY.header("step", "h"), state_layout(10).header("step", "h")
    ('def step(y, h, I, P, cs, ss, rot):', 'def step(t, y, h, P, X, cs, ss, rot):')
    """

    size: int
    params: str
    timed: bool

    def header(self, name: str, middle: str) -> str:
        """A step's first line: ``name`` taking the (time and) state, ``middle``, the parameters and the turns.

        Examples
        --------
        >>> from tumble.dynamics.engine.unrolled import RIGID_BODY
        >>> RIGID_BODY.header("rk4_step", "h")
        'def rk4_step(y, h, I, P, cs, ss, rot):'
        """
        return f"def {name}({'t, ' if self.timed else ''}y, {middle}, {self.params}, cs, ss, rot):"

    def call(self, node: str, state: str) -> str:
        """The right-hand side at ``state`` and the stage's time ``node``.

        Examples
        --------
        >>> from tumble.dynamics.engine.unrolled import RIGID_BODY, state_layout
        >>> RIGID_BODY.call("t + 0.5 * h", "y"), state_layout(10).call("t + 0.5 * h", "y")
        ('rhs(y, I, P, u0, u1)', 'rhs(t + 0.5 * h, y, P, X, u0, u1)')
        """
        return f"rhs({node + ', ' if self.timed else ''}{state}, {self.params}, u0, u1)"


#: The rigid body's layout: ``rhs(y, I, P, u0, u1)`` over ``(omega, q)``.
RIGID_BODY = Layout(STATE, "I, P", False)


def state_layout(n: int) -> Layout:
    """The layout of a state of ``n`` floats whose right-hand side is ``rhs(t, y, P, X, u0, u1)``:
    the time (s), the state, the run's parameters ``P`` (a tuple of floats) and tables ``X`` (a
    tuple of arrays), and a circular orbit's direction at the stage.

    Examples
    --------
    >>> from tumble.dynamics.engine.unrolled import state_layout
    >>> state_layout(13).call("t", "y")
    'rhs(t, y, P, X, u0, u1)'
    """
    return Layout(n, "P, X", True)


#: Sums over slopes of this many nonzero weights or more are written as a loop over the slopes
#: (:func:`_sums`), fewer as expressions. The loop is over a tuple of the slopes and one of the
#: weights, its body one multiply-add a component: numba types it once instead of once a term, and
#: LLVM unrolls it back to the written-out sums with the weights as literals, the same operations
#: in the same order. Where a kernel fuses multiply-adds (``fastmath`` contract) the written-out
#: sum fused its first two terms the other way round, so results move by round-off (1e-13 of
#: |omega| on the T-handle's runs); without it they are the same bits (the closed loop's). The
#: first ``dop853`` call compiled in ~4.5 CPU-s instead of ~4.9 (its dense output 0.72 instead of
#: 1.27), the first closed loop ~13.1 instead of ~14.3, the runs as fast (the T-handle, 20 s: 167
#: against 167 us with 101 samples, 253 against 253 us with 2,000, alternating; 2026-11-30).
LOOPED_TERMS = 3


def _weighted(weights: Coefficients, stages: Sequence[str], i: int) -> str:
    """``w_0 k0[i] + w_1 k1[i] + ...`` over the nonzero weights, summed in stage order (as
    scipy's ``np.dot(K.T, w)``); ``0.0`` when all are zero."""
    terms = [f"{float(w)!r} * {k}[{i}]" for w, k in zip(weights, stages) if w != 0.0]
    return " + ".join(terms) if terms else "0.0"


def _sums(n: int, weights: Coefficients, stages: Sequence[str], name: str,
          looped: bool = True) -> tuple[list[str], list[str]]:
    """The weighted sums ``w_0 k0[i] + w_1 k1[i] + ...`` of each component ``i < n`` (nonzero
    weights, stage order, as :func:`_weighted`): the lines that compute them, and an expression of
    each. With :data:`LOOPED_TERMS` terms or more (and ``looped``), a loop over the slopes into the
    locals ``{name}0``, ``{name}1``, ...; else no line and the written-out sums.

    Examples
    --------
    >>> from tumble.dynamics.engine.unrolled import _sums
    >>> _sums(2, [0.5, 0.0], ["k0", "k1"], "a")
    ([], ['0.5 * k0[0]', '0.5 * k0[1]'])
    >>> lines, sums = _sums(2, [0.5, 0.25, 0.125], ["k0", "k1", "k2"], "a")
    >>> [line.strip() for line in lines][:4], sums
    (['a_slopes, a_weights = (k0, k1, k2), (0.5, 0.25, 0.125)', 'a0, a1 = 0.0, 0.0', 'for a_j in range(3):', 'a_k, a_w = a_slopes[a_j], a_weights[a_j]'], ['a0', 'a1'])
    >>> lines[-1]
    '        a1 += a_w * a_k[1]'
    """
    used = [(float(w), k) for w, k in zip(weights, stages) if w != 0.0]
    if not looped or len(used) < LOOPED_TERMS:
        return [], [_weighted(weights, stages, i) for i in range(n)]
    lines = [f"    {name}_slopes, {name}_weights = ({', '.join(k for _, k in used)}), "
             f"({', '.join(repr(w) for w, _ in used)})",
             f"    {', '.join(f'{name}{i}' for i in range(n))} = {', '.join('0.0' for _ in range(n))}",
             f"    for {name}_j in range({len(used)}):",
             f"        {name}_k, {name}_w = {name}_slopes[{name}_j], {name}_weights[{name}_j]",
             *[f"        {name}{i} += {name}_w * {name}_k[{i}]" for i in range(n)]]
    return lines, [f"{name}{i}" for i in range(n)]


def _advanced(layout: Layout, weights: Coefficients, stages: Sequence[str], y: str = "y",
              looped: bool = True) -> tuple[list[str], str]:
    """The state ``y + h sum_r w_r k_r``: the lines computing its sums (:func:`_sums`; none
    without ``looped``) and the state as a tuple literal."""
    lines, sums = _sums(layout.size, weights, stages, "z", looped)
    return lines, "(" + ", ".join(f"{y}[{i}] + h * ({v})" for i, v in enumerate(sums)) + ")"


def _stage(layout: Layout, s: int, A: np.ndarray, C: Coefficients, state: str = "") -> list[str]:
    """Lines computing stage ``s``: the orbit's direction at its node, and its slope ``k{s}`` at
    ``state`` (by default, from the slopes before it)."""
    node = "t" if C[s] == 0.0 else f"t + {float(C[s])!r} * h"
    lines: list[str] = []
    if not state:
        lines, state = ([], "y") if s == 0 else _advanced(layout, A[s, :s], [f"k{r}" for r in range(s)])
    return [*lines, f"    u0 = cs * rot[{2 * s}] - ss * rot[{2 * s + 1}]",
            f"    u1 = ss * rot[{2 * s}] + cs * rot[{2 * s + 1}]",
            f"    k{s} = {layout.call(node, state)}"]


def fixed_step_source(name: str, A: np.ndarray, B: np.ndarray, C: np.ndarray, layout: Layout = RIGID_BODY) -> str:
    """The source of one step of the explicit tableau ``(A, B, C)`` (module docstring): returns the
    new state.

    Examples
    --------
    >>> from tumble.dynamics.engine.unrolled import fixed_step_source
    >>> from tumble.dynamics.engine.tableau import RK4_A, RK4_B, RK4_C
    >>> source = fixed_step_source("rk4_step", RK4_A, RK4_B, RK4_C)
    >>> source.count("rhs(")   # four stages
    4
    """
    stages = len(B)
    lines = [layout.header(name, "h")]
    for s in range(stages):
        lines += _stage(layout, s, A, C)
    final, state = _advanced(layout, B, [f"k{r}" for r in range(stages)])
    lines += [*final, f"    return {state}"]
    return "\n".join(lines) + "\n"


def rotations_source(name: str, C: Coefficients) -> str:
    """The source of ``name(n, h)``: the tuple ``(cos n c_0 h, sin n c_0 h, cos n c_1 h, ...)`` over
    the nodes ``C``, the turns of the orbit's direction from a step's start to its stages (all
    ``(1, 0)`` without an orbit, ``n = 0``, with no trigonometric call).

    Examples
    --------
    >>> from tumble.dynamics.engine.unrolled import rotations_source
    >>> print(rotations_source("turns", [0.0, 0.5]))
    def turns(n, h):
        if n == 0.0:
            return (1.0, 0.0, 1.0, 0.0)
        return (1.0, 0.0, math.cos(0.5 * n * h), math.sin(0.5 * n * h))
    <BLANKLINE>
    """
    idle = ", ".join("1.0, 0.0" for _ in C)
    turns = ", ".join("1.0, 0.0" if c == 0.0 else f"math.cos({float(c)!r} * n * h), math.sin({float(c)!r} * n * h)"
                      for c in C)
    return f"def {name}(n, h):\n    if n == 0.0:\n        return ({idle})\n    return ({turns})\n"


def dop853_errors_lines(name: str, n: int, atol: str) -> list[str]:
    """The lines of ``name(K, y, y_new, rtol, atol)``: DOP853's 5th- and 3rd-order error sums
    (``sum (e_i / scale_i)^2``, ``scale_i = atol_i + rtol max(|y_i|, |y_new_i|)``, HNW sec. II.10,
    as scipy's ``DOP853._estimate_error_norm``) over a state of ``n`` floats; ``atol`` the
    expression of ``atol_i`` with ``{i}`` for the index (``"atol[{i}]"`` or ``"atol"``).

    Examples
    --------
    >>> from tumble.dynamics.engine.unrolled import dop853_errors_lines
    >>> lines = dop853_errors_lines("errors", 2, "atol")
    >>> lines[0], lines[-1], sum("scale = atol +" in line for line in lines)
    ('def errors(K, y, y_new, rtol, atol):', '    return e5, e3', 2)
    """
    slopes = [f"k{r}" for r in range(13)]
    fifth, fifths = _sums(n, DOP853_E5, slopes, "p")
    third, thirds = _sums(n, DOP853_E3, slopes, "q")
    lines = [f"def {name}(K, y, y_new, rtol, atol):", f"    {', '.join(slopes)} = K", *fifth, *third,
             "    e5 = 0.0", "    e3 = 0.0"]
    for i in range(n):
        lines += [f"    scale = {atol.format(i=i)} + max(abs(y[{i}]), abs(y_new[{i}])) * rtol",
                  f"    a = ({fifths[i]}) / scale",
                  f"    b = ({thirds[i]}) / scale",
                  "    e5 += a * a", "    e3 += b * b"]
    return [*lines, "    return e5, e3"]


def dop853_sources(layout: Layout = RIGID_BODY, step: str = "dop853_step", errors: str = "dop853_errors",
                   atol: str = "atol[{i}]", dense: bool = True) -> str:
    """The sources of DOP853's pieces (Hairer, Norsett & Wanner, *Solving ODEs I*, 2nd ed.,
    sec. II.10, in scipy's arrangement, :class:`scipy.integrate.DOP853`):

    - ``dop853_step(y, k0, h, I, P, cs, ss, rot)``: from the slope ``k0`` at ``y`` (the
      last step's final one: first same as last), the 11 other stages and the new state's slope:
      returns ``(y_new, K)`` with ``K`` the 13 slopes;
    - ``dop853_errors(K, y, y_new, rtol, atol)``: the sums of squares of the scaled 5th- and
      3rd-order error estimates, ``scale = atol + rtol max(|y|, |y_new|)``;
    - ``dop853_dense(y, y_new, K, h, I, P, cs, ss, rot)``: the three extra stages and the
      7th-order interpolant's seven coefficient rows (scipy's ``Dop853DenseOutput``);
    - ``dop853_interpolate(F, y, x)``: the interpolant at the fraction ``x`` of the step.

    Over another ``layout``, the step under the name ``step`` (its arguments those of the layout)
    and the errors under ``errors``, ``atol`` the expression of each component's absolute
    tolerance (``"atol"``: one float), and the dense output only with ``dense``.

    Examples
    --------
    >>> from tumble.dynamics.engine.unrolled import dop853_sources
    >>> source = dop853_sources()
    >>> source.count("rhs(")   # 11 stages (the first is the last step's), the new state's slope, 3 dense
    15
    """
    A, B, C = DOP853_A, DOP853_B, DOP853_C
    slopes = [f"k{r}" for r in range(13)]
    lines = [layout.header(step, "k0, h")]
    for s in range(1, 12):
        lines += _stage(layout, s, A, C)
    final, state = _advanced(layout, B, slopes[:12])
    lines += [*final, f"    y_new = {state}"]
    lines += _stage(layout, 12, A, C, "y_new")
    lines.append(f"    return y_new, ({', '.join(slopes)})")
    error_lines = dop853_errors_lines(errors, layout.size, atol)
    if not dense:
        return "\n".join([*lines, "", *error_lines]) + "\n"

    n = layout.size
    dense_lines = [layout.header("dop853_dense", "y_new, K, h"), f"    {', '.join(slopes)} = K"]
    extra = [f"k{r}" for r in range(16)]
    for s in range(13, 16):
        dense_lines += _stage(layout, s, A, C)
    rows = [f"    f0 = ({', '.join(f'y_new[{i}] - y[{i}]' for i in range(n))})",
            f"    f1 = ({', '.join(f'h * k0[{i}] - f0[{i}]' for i in range(n))})",
            f"    f2 = ({', '.join(f'2.0 * f0[{i}] - h * (k12[{i}] + k0[{i}])' for i in range(n))})"]
    for r in range(4):
        row, sums = _sums(n, DOP853_D[r], extra, "d")
        rows += [*row, f"    f{3 + r} = ({', '.join(f'h * ({v})' for v in sums)})"]
    dense_lines += rows + ["    return (f0, f1, f2, f3, f4, f5, f6)"]

    # scipy's Dop853DenseOutput._call_impl: y = 0; for j, f in enumerate(reversed(F)): y += f;
    # y *= x if j even else 1 - x; y += y_old
    interpolate = ["def dop853_interpolate(F, y, x):", "    f0, f1, f2, f3, f4, f5, f6 = F", "    u = 1.0 - x"]
    for i in range(n):
        v = "0.0"
        for j, f in enumerate(["f6", "f5", "f4", "f3", "f2", "f1", "f0"]):
            v = f"({v} + {f}[{i}]) * {'x' if j % 2 == 0 else 'u'}"
        interpolate.append(f"    v{i} = {v} + y[{i}]")
    interpolate.append(f"    return ({', '.join(f'v{i}' for i in range(n))})")
    return "\n".join(["\n".join(lines), "\n".join(error_lines), "\n".join(dense_lines), "\n".join(interpolate)]) + "\n"


def dop853_accept_source(layout: Layout = RIGID_BODY, name: str = "dop853_accept", size: str = str(STATE)) -> str:
    """The source of one accepted DOP853 step with its rejections, as scipy's ``RungeKutta._step_impl``
    takes it: the one writing of DOP853's step control, for every state the engine steps by it (the
    rigid body's; the closed loop's, :mod:`~tumble.dynamics.control.compiled_loop`). Hairer, Norsett &
    Wanner, *Solving ODEs I*, 2nd ed., sec. II.4.

    ``name(t, y, f, h_abs, t_bound, rtol, atol, <params>, cs, ss, n, R, evaluations, budget)``: from
    ``y`` at ``t`` (s) with its slope ``f``, the step ``h_abs`` (s) proposed, not past ``t_bound``;
    ``cs, ss`` the circular orbit's direction at ``t`` and ``n`` its mean motion (rad/s); ``R`` an
    array holding the step the turns to the stage nodes were made for (``R[0]``, NaN: none yet)
    and the turns (``R[1:]``), remade only when the step changes (a closed loop's equal hold
    intervals take one step each); ``evaluations`` the right-hand sides spent, at most ``budget``.
    Returns ``(status, t_new, y_new, K, h_abs, evaluations)``: ``OK`` and the accepted step's
    end, state, 13 slopes (``K[12]`` the new slope) and the next step proposed; or
    ``STEP_COLLAPSED`` (the step fell below 10 ulp of t) or ``BUDGET_SPENT`` with the state as it
    was. It calls ``dop853_step``, ``dop853_errors`` and ``dop853_turns`` (:func:`dop853_sources`,
    :func:`rotations_source`) and the step size's helpers ``_error_norm`` and ``_next_step``
    (:mod:`~tumble.dynamics.engine.stepsize`), the error norm over ``size`` components (an
    expression: a padded state's own count).

    Examples
    --------
    >>> from tumble.dynamics.engine.unrolled import dop853_accept_source
    >>> source = dop853_accept_source()
    >>> source.splitlines()[0]
    'def dop853_accept(t, y, f, h_abs, t_bound, rtol, atol, I, P, cs, ss, n, R, evaluations, budget):'
    >>> source.count("dop853_step(")   # one step a try, tried until one is accepted
    1
    """
    slopes = "(" + ", ".join("f" for _ in range(13)) + ")"  # a K of the right type where none was made
    return f"""def {name}(t, y, f, h_abs, t_bound, rtol, atol, {layout.params}, cs, ss, n, R, evaluations, budget):
    min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
    h_abs = max(h_abs, min_step)
    rejected = False
    while True:
        if h_abs < min_step:
            return STEP_COLLAPSED, t, y, {slopes}, h_abs, evaluations
        if evaluations > budget:
            return BUDGET_SPENT, t, y, {slopes}, h_abs, evaluations
        t_new = t + h_abs
        if t_new - t_bound > 0.0:
            t_new = t_bound
        h = t_new - t
        h_abs = abs(h)
        if h != R[0]:  # the turns to the stage nodes, once per step length
            R[0] = h
            rot = dop853_turns(n, h)
            for j in range(len(rot)):
                R[1 + j] = rot[j]
        y_new, K = dop853_step({'t, ' if layout.timed else ''}y, f, h, {layout.params}, cs, ss, R[1:])
        evaluations += 12
        e5, e3 = dop853_errors(K, y, y_new, rtol, atol)
        accepted, h_abs = _next_step(_error_norm(e5, e3, h_abs, {size}), h_abs, rejected)
        if accepted:
            return OK, t_new, y_new, K, h_abs, evaluations
        rejected = True
"""


def fixed_loop_source(name: str, step: str, turns: str, load: str, store: str, outputs: str) -> str:
    """The source of a fixed-step run ``name(y0, t_eval, I, P, n, step, <outputs>)``: from the state
    array ``y0`` at ``t_eval[0]`` through each sample interval in equal steps of the step function
    ``step`` no longer than ``step`` (s), the orbit's turns ``turns`` (:func:`rotations_source`) once
    per step length; ``load(y0, I)`` gives the state tuple and the body's tuple the step takes,
    ``store(y, I, <outputs>, k)`` writes sample ``k``. Returns a status (``OK``, ``NON_FINITE``). The one
    writing of the fixed-step loop, for every state the engine steps (the rigid body's, the damped body's, the
    dragged body's of the fits).

    Examples
    --------
    >>> from tumble.dynamics.engine.unrolled import fixed_loop_source
    >>> source = fixed_loop_source("run", "rk4_step", "rk4_turns", "_load", "_store", "omega, quat")
    >>> print(source.splitlines()[0])
    def run(y0, t_eval, I, P, n, step, omega, quat):
    """
    # one call of store, its index a loop variable: with a literal 0 for the first sample numba compiled
    # it twice (for Literal[int](0) and for int64)
    return f"""def {name}(y0, t_eval, I, P, n, step, {outputs}):
    y, body = {load}(y0, I)
    h_turns = -1.0
    rot = {turns}(0.0, 0.0)
    for k in range(t_eval.shape[0]):
        if k > 0:
            m, h = _equal_steps(t_eval[k] - t_eval[k - 1], step)
            if h != h_turns:  # the turns from a step's start to its stages, once per step length
                h_turns = h
                rot = {turns}(n, h)
            for j in range(m):
                cs, ss = _direction(n, t_eval[k - 1] + j * h)
                y = {step}(y, h, body, P, cs, ss, rot)
            if not _finite(y):
                return NON_FINITE
        {store}(y, I, {outputs}, k)
    return OK
"""


#: The rows of a lane step's work array (:func:`lane_step_source`), each ``lanes`` floats long: the
#: state ``(omega, q)``, the body ``(I, 1 / I)``, a stage's state, its slope, then the stages' slopes.
LANE_ROWS = {"state": 0, "body": STATE, "stage": STATE + 6, "slope": 2 * STATE + 6, "slopes": 3 * STATE + 6}


def lane_rows(stages: int) -> int:
    """The rows of a lane step's work array over ``stages`` stages (:data:`LANE_ROWS`).

    Examples
    --------
    >>> from tumble.dynamics.engine.unrolled import lane_rows
    >>> lane_rows(4)
    48
    """
    return LANE_ROWS["slopes"] + STATE * (stages - 1)


def lane_step_source(name: str, A: np.ndarray, B: Coefficients, C: Coefficients, lanes: int) -> str:
    """The source of one step of the explicit tableau ``(A, B, C)`` over ``lanes`` rigid bodies at
    once, ``name(W, h, body, P, cs, ss, rot)``: the bodies' states in the flat work array ``W``
    (:data:`LANE_ROWS`, ``lanes`` floats a row: structure of arrays), stepped in place (``W`` is
    returned; ``body`` unused, the bodies are in ``W``). Each stage is two loops over the lanes
    with no branch and constant offsets into ``W``, which the compiler turns into vector
    instructions (a lane each): the stage's state from the slopes before it, as
    :func:`fixed_step_source` writes it (the same sums in the same order), and the right-hand side
    ``rhs(y, I, P, u0, u1)`` there, written once for all stages (a loop over the stages), so the
    step compiles one right-hand side, not one a stage.

    Examples
    --------
    >>> from tumble.dynamics.engine.unrolled import lane_step_source
    >>> from tumble.dynamics.engine.tableau import RK4_A, RK4_B, RK4_C
    >>> source = lane_step_source("rk4_lanes", RK4_A, RK4_B, RK4_C, 8)
    >>> source.splitlines()[0], source.count("rhs(")
    ('def rk4_lanes(W, h, body, P, cs, ss, rot):', 1)
    """
    stages = len(B)

    def rows(first: int, n: int = STATE) -> str:
        return "(" + ", ".join(f"W[{(first + i) * lanes} + j]" for i in range(n)) + ")"

    def put(first: int, value: str, indent: str) -> list[str]:
        return [f"{indent}W[{(first + i) * lanes} + j] = {value}[{i}]" for i in range(STATE)]

    def slopes(s: int, weights: Coefficients, indent: str) -> list[str]:
        """Load the slopes ``k_r`` (r < s) that ``weights`` take, the last, ``k_{s-1}``, from the slope
        row, keeping it among the stages' slopes for the stages after ``s``."""
        lines = [f"{indent}k{s - 1} = {rows(LANE_ROWS['slope'])}"]
        if s < stages:
            lines += put(LANE_ROWS["slopes"] + STATE * (s - 1), f"k{s - 1}", indent)
        return lines + [f"{indent}k{r} = {rows(LANE_ROWS['slopes'] + STATE * r)}" for r in range(s - 1) if weights[r] != 0.0]

    lines = [f"def {name}(W, h, body, P, cs, ss, rot):", f"    for s in range({stages}):"]
    for s in range(stages):
        lines += [f"        {'if' if s == 0 else 'elif'} s == {s}:", f"            for j in range({lanes}):",
                  f"                y = {rows(LANE_ROWS['state'])}"]
        if s:
            lines += slopes(s, A[s, :s], " " * 16)
        state = "y" if s == 0 else _advanced(RIGID_BODY, A[s, :s], [f"k{r}" for r in range(s)], looped=False)[1]
        lines += [f"                z = {state}", *put(LANE_ROWS["stage"], "z", " " * 16)]
    lines += ["        u0 = cs * rot[2 * s] - ss * rot[2 * s + 1]", "        u1 = ss * rot[2 * s] + cs * rot[2 * s + 1]",
              f"        for j in range({lanes}):",
              f"            d = rhs({rows(LANE_ROWS['stage'])}, {rows(LANE_ROWS['body'], 6)}, P, u0, u1)",
              *put(LANE_ROWS["slope"], "d", " " * 12),
              f"    for j in range({lanes}):", f"        y = {rows(LANE_ROWS['state'])}", *slopes(stages, B, " " * 8),
              f"        y = {_advanced(RIGID_BODY, B, [f'k{r}' for r in range(stages)], looped=False)[1]}",
              *put(LANE_ROWS["state"], "y", " " * 8), "    return W"]
    return "\n".join(lines) + "\n"
