"""A rotor that spins up and brakes inside the body, seen in the world frame's momentum budget.

A gyrostat's whole angular momentum, body and rotor, ``L = R(t) (I w + h)`` in the world frame
(``R`` the body-to-world attitude, ``h`` the rotor's momentum relative to the body), is constant
but for the air's torque (Hughes, *Spacecraft Attitude Dynamics*, 1986, ch. 7). A rigid body has
``h = 0``. A flywheel device whose rotor idles, spins up in a tenth of a second, holds and brakes
again within one flight (the device of :mod:`tumble.analysis.tensor`) moves 3-6 % of ``|L|`` into
the rotor and back: the rigid fit of :mod:`~tumble.analysis.fit.single` bends its ratios and its
drag to follow it (a misfit of 1 % of the rates, which the adequacy test allows), and the
gyrostat of :mod:`~tumble.analysis.fit.rotor`, whose rotor spins up at a constant rate, cannot
express a spin-up that is undone before the flight ends.

The budget needs no model of the rotor's speed. The attitude is integrated from the samples
themselves (the rigid fit's rates at the nodes of a fourth-order Magnus step, plus the samples'
residual interpolated: :func:`flight_attitude`), and then the budget is LINEAR in everything
unknown: the tensor ``I`` (sensor axes, trace 1), the world-frame ``L``, the drag (per-axis
``|w_i| w_i`` and ``|w| w_i`` along the rigid fit's principal axes: a plate's strip-theory drag
damps its wobble in proportion to ``|w|``), a constant internal momentum, and the first-order
attitude error of the gyroscope's scale factors and misalignment (``d eta / dt = R (M - 1) w``,
the world-frame attitude error of a left perturbation, Markley & Crassidis, *Fundamentals of
Spacecraft Attitude Determination and Control*, 2014, ch. 3; the cross product with ``L``
fitted from the rigid budget) and of a gap in the samples (a turn of the attitude after it)::

    R(t) I w(t) + sum_j d_j D_j(t) + R(t) u0 + eta(t) x L - L = - R(t) sum_k u_k S(t - t_k),

with the internal momentum as steps ``u_k`` (body axes) that rise over :data:`WIDTH`
(``S(x) = clip(x / WIDTH, 0, 1)``) at times ``t_k`` scanned on a grid. Each scan over one
step's time, the others held, adds three columns to a least squares whose other columns are
partialled out once (the Frisch-Waugh-Lovell theorem, Lovell, JASA 58 (1963) 993: the sum of
squares a candidate removes is ``s^T S^-1 s`` with its columns' Schur complement ``S``), so the
whole scan costs milliseconds. At the times found, the steps are then taken along one body axis,
``u_k = c_k a`` (one rotor: the axis that removes the most, searched over a hemisphere), and the
statistic is the largest change of the internal momentum between two of its levels (before,
between and after the steps), over the body's ``|I w|`` (the rigid fit's moments, the median over
the flight; the budget's own ``L`` is no unit to trust: its columns trade with it when the
gyroscope's scale errors are large), with its standard uncertainty from the least squares'
covariance widened for the residuals' autocorrelation (as
:func:`~tumble.analysis.fit.uncertainty.effective_covariance`).

The budget leaves out :data:`TRIM` at each end of the flight (a hand's last push, a catch's
first contact: an external torque that a step would stand in for) and puts no step within
:data:`EDGE` of the rest's ends or two within :data:`GAP` of each other, in time counted where
there are samples (a gap in them counts as three sample intervals: a level of the internal
momentum held only across a gap is held by no sample). Measured on every
flight of the synthetic recordings of :func:`~tumble.analysis.fit.synthetic.synthetic_recording`
that reached the rigidity checks (665 flights: racquet and phone, kinds "one toss", "many",
"hand", "landing", "tidy" of ``benchmarks/fit_coverage.py``, seeds 0-29, and the 44 of the 45-toss
racquet recording of ``benchmarks/bench_fit.py``; with the gyroscope's
scale errors, the racquet's flex, the plate's drag, gaps in the samples): the change less
:data:`K_SIGMA` standard uncertainties is at most 0.7 % of ``|L|`` (0.5 % on seeds 0-11). On
the flywheel throws of :func:`~tumble.analysis.tensor.synthetic.synthetic_throw` (500 Hz) that
the other checks take as rigid (seeds 0-15, 8 flights), 1.8-3.1 %, and 0.35 % on the one whose
flight is too short to hold both steps after the trim; the same throws with the rotor at rest, at
most 0.13 %. A flight is refused beyond :data:`MIN_CHANGE`: 7 of the 8 throws.

Each of the budget's nuisances can also fake a step: without the scale errors' columns a phone
whose gyroscope's scale factors differ by 2 % between axes (fit_coverage's phone "many", seed 18)
shows 2.6 % and two more over 1.5 %; with them, a flight with a 0.16 s gap in its samples (phone
"one toss", seed 1052) shows 13 +- 2 %, its columns trading with the steps around the gap (the
other, 0.4 %). So :func:`step_check` refuses a flight only when the budget holds the steps both
with and without them (the flywheel throws: 2.8-5.6 % without).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.spatial.transform import Rotation

from ..._html import headline_html, headline_repr
from ...dynamics.special.quaternion import quat_multiply
from .model import Model
from .solve import Solution
from .uncertainty import autocorrelation_time

__all__ = ["EDGE", "GAP", "K_SIGMA", "MIN_CHANGE", "StepFit", "TRIM", "WIDTH", "flight_attitude", "momentum_steps",
           "step_check"]

#: The internal momentum's change (less :data:`K_SIGMA` standard uncertainties) beyond which a
#: flight is not a rigid body's, as a fraction of ``|L|`` (module docstring: rigid flights at most
#: 0.7 %, the flywheel throws 1.8-3.1 %).
MIN_CHANGE = 0.015
#: Standard uncertainties taken off the change before it is compared with :data:`MIN_CHANGE`.
K_SIGMA = 2.0
#: The time over which a step of the internal momentum rises, s (a flywheel's motor spins up
#: with a time constant of ~40 ms, :mod:`tumble.analysis.tensor.firmware`).
WIDTH = 0.04
#: The grid of the steps' times, s.
GRID = 0.01
#: Left out of the budget at each end of the flight, s.
TRIM = 0.1
#: No step within this of the ends of the budget's samples, s.
EDGE = 0.05
#: No two steps closer than this, s.
GAP = 0.1
#: The number of steps, and the sweeps of the scan over them (each step's time found with the
#: others held).
STEPS, SWEEPS = 2, 2
#: The attitude's substeps keep ``|w| dt`` below this, rad.
TURN = 0.1


@dataclass(frozen=True)
class StepFit:
    """The internal momentum found in a flight's budget (:func:`momentum_steps`).

    Attributes
    ----------
    change, change_std : float
        The largest change of the internal momentum between two of its levels, over ``|L|``, and
        its standard uncertainty (dimensionless).
    times : tuple of float
        The steps' times, s.
    rms_rigid, rms : float
        The budget's residual RMS without and with the steps, over ``|L|``.

    Examples
    --------
    >>> from tumble.analysis.fit.budget import StepFit, K_SIGMA, MIN_CHANGE
    >>> fit = StepFit(0.04, 0.004, (0.49, 0.69), 0.006, 0.002)
    >>> fit.change - K_SIGMA * fit.change_std > MIN_CHANGE   # 4 +- 0.4 % of |L| moved in and out
    True
    """

    HEADLINE = (("change", "internal momentum change over |L|", ""), ("change_std", "its std", ""),
                ("times", "steps at", "s"), ("rms_rigid", "RMS without steps", ""), ("rms", "with", ""))
    __repr__ = headline_repr
    _repr_html_ = headline_html

    change: float
    change_std: float
    times: tuple
    rms_rigid: float
    rms: float


def flight_attitude(t: np.ndarray, omega: np.ndarray, sol: Solution) -> np.ndarray:
    """Body-to-world rotation matrices at ``t`` (the identity at ``t[0]``), shape ``(n, 3, 3)``.

    Each interval is cut into substeps of at most :data:`TURN` rad; each substep is the
    fourth-order Magnus step with two Gauss-Legendre nodes (Blanes, Casas, Oteo & Ros, "The Magnus
    expansion and some of its applications", Phys. Rep. 470 (2009) 151, sec. 5:
    ``Omega = h (A1 + A2) / 2 - sqrt(3) h^2 [A1, A2] / 12`` for ``Y' = A Y``); for body-frame rates,
    ``R' = R [w]x``, composed on the right, it reads ``h (w1 + w2) / 2 + sqrt(3) h^2 (w1 x w2) / 12``
    (the commutator's sign turns with the side; its error falls as the step's fourth power: the
    example's drift is 7e-8 of ``|L|``, 6e-4 with the sign turned). The rates at the nodes are the rigid fit's model there plus the samples' residual
    from it, interpolated linearly: a spline of the samples alone misses the turn across a gap in
    the recording or at 100 Hz.

    Parameters
    ----------
    t : ndarray, shape (n,)
        The flight's times, s (those of ``sol``).
    omega : ndarray, shape (n, 3)
        Its samples, sensor axes, rad/s.
    sol : Solution
        Its rigid fit.

    Examples
    --------
    A torque-free tumble sampled at 100 Hz: its world-frame momentum stays put.

    >>> import numpy as np
    >>> from tumble.analysis.fit.budget import flight_attitude
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.arange(0.0, 1.2, 0.01)
    >>> I = np.array([0.4, 0.85, 1.0])
    >>> w = free_omega([I], [[0.3, 18.0, 0.5]], t)[0]
    >>> sol = fit_solution(t, w, np.ones(w.shape, bool), rotation=False, bias=False, drag="none")
    >>> L = np.einsum("nab,nb->na", flight_attitude(t, w, sol), w * I)
    >>> bool(np.max(np.linalg.norm(L - L[0], axis=1)) < 1e-6 * np.linalg.norm(L[0]))
    True
    """
    m, P = sol.model, sol.P
    t, omega = np.asarray(t, float), np.asarray(omega, float)
    n = len(t)
    anchor = t[0] - m.tau[0, 0]
    R = m.rotation_matrix(P)
    residual = omega - (m.principal(P)[0, :n] @ R + m.bias_vector(P))
    dt = np.diff(t)
    speed = np.maximum(np.linalg.norm(omega[:-1], axis=1), np.linalg.norm(omega[1:], axis=1))
    k = np.maximum(1, np.ceil(speed * dt / TURN)).astype(int)
    h = np.repeat(dt / k, k)
    start = np.repeat(t[:-1], k) + np.concatenate([np.arange(j) for j in k]) * h
    g = (0.5 - np.sqrt(3.0) / 6.0) * h
    nodes = np.concatenate([start + g, start + h - g])
    order = np.argsort(nodes)
    probe = Model([nodes[order] - anchor], m.rotation, m.bias, m.drag, m.speeds)
    rates = np.empty((len(nodes), 3))
    rates[order] = probe.principal(P)[0] @ R
    rates += CubicSpline(t, residual)(nodes)
    w1, w2 = rates[:len(start)], rates[len(start):]
    turn = 0.5 * h[:, None] * (w1 + w2) + (np.sqrt(3.0) / 12.0) * h[:, None] ** 2 * np.cross(w1, w2)
    q = np.empty((len(turn) + 1, 4))
    q[0] = [0.0, 0.0, 0.0, 1.0]
    q[1:] = Rotation.from_rotvec(turn).as_quat()
    d = 1
    while d < len(q):  # the products of the steps as a prefix scan (as accelsynth.attitude_from_rates)
        q[d:] = quat_multiply(q[:-d], q[d:])
        d *= 2
    return Rotation.from_quat(q[np.r_[0, np.cumsum(k)]]).as_matrix()


def _integral(t: np.ndarray, f: np.ndarray) -> np.ndarray:
    """The trapezoidal running integral of ``f`` (n, 3) from ``t[0]``."""
    return np.r_[np.zeros((1, 3)), np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(t)[:, None], axis=0)]


def _budget(t, w, Rw, Rp, scale_errors: bool = True) -> tuple[np.ndarray, np.ndarray, int]:
    """The budget's columns, shape (n, 3, p), its right-hand side (n, 3) and the number of the
    rigid budget's own columns (the tensor, the drag and ``L``; ``L`` its last three)."""
    n = len(t)
    cols = []
    for i, j in ((0, 0), (1, 1), (0, 1), (0, 2), (1, 2)):  # I, its trace 1: I33 = 1 - I11 - I22
        v = np.zeros((n, 3))
        if i == j:
            v[:, i], v[:, 2] = w[:, i], -w[:, 2]
        else:
            v[:, i], v[:, j] = w[:, j], w[:, i]
        cols.append(np.einsum("nab,nb->na", Rw, v))
    wp = w @ Rp.T
    speed = np.linalg.norm(wp, axis=1)
    for law in (np.abs(wp), speed[:, None] * np.ones(3)):
        for j in range(3):
            cols.append(_integral(t, np.einsum("nab,b->na", Rw, Rp[j]) * (law[:, j] * wp[:, j])[:, None]))
    cols += [np.broadcast_to(-np.eye(3)[j], (n, 3)) for j in range(3)]
    rigid = len(cols)
    A = np.stack(cols, axis=2)
    y = -Rw[:, :, 2] * w[:, 2:3]
    x, *_ = np.linalg.lstsq(A.reshape(3 * n, rigid), y.ravel(), rcond=None)
    L = x[rigid - 3:rigid]
    cols += [Rw[:, :, j] for j in range(3)]  # a constant internal momentum
    for k, l in (((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)) if scale_errors else ()):  # scale, misalignment
        f = Rw[:, :, k] * w[:, l:l + 1] + (Rw[:, :, l] * w[:, k:k + 1] if k != l else 0.0)
        cols.append(np.cross(_integral(t, f), L))
    dts = np.diff(t)
    u = L / max(float(np.linalg.norm(L)), 1e-300)
    e1 = np.cross(u, [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    for gap in np.flatnonzero(dts > max(3.0 * float(np.median(dts)), 0.02)):  # the attitude's turn across a gap
        after = (np.arange(n) > gap)[:, None]
        cols += [after * np.cross(e, L) for e in (e1, np.cross(u, e1))]
    return np.stack(cols, axis=2), y, rigid


def momentum_steps(t: np.ndarray, omega: np.ndarray, keep: np.ndarray, sol: Solution, *,
                   scale_errors: bool = True) -> StepFit | None:
    """The internal momentum's steps that a flight's world-frame budget holds (module docstring).

    Parameters
    ----------
    t, omega, keep, sol
        The flight's times (s), gyroscope samples (sensor axes, rad/s), the sample axes fitted
        and its rigid fit, as for :func:`~tumble.analysis.fit.rotor.fit_rotor`; a saturated axis
        is taken from the rigid fit's model.
    scale_errors : bool
        Whether the budget has the columns of the gyroscope's scale errors and misalignment.

    Returns
    -------
    StepFit or None
        None for a flight too short to hold two steps once trimmed.

    Examples
    --------
    A body whose internal rotor takes 5 % of ``|L|`` within 40 ms at 0.4 s and gives it back at
    0.65 s (Euler's equations of the gyrostat, :func:`~tumble.dynamics.models.gyrostat.gyrostat_omega`;
    sampled at 200 Hz with 0.01 rad/s of noise), and its rigid twin:

    >>> import numpy as np
    >>> from tumble.analysis.fit.budget import momentum_steps
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.dynamics.models.gyrostat import gyrostat_omega
    >>> I = np.diag([0.4, 0.85, 1.0])
    >>> fine = np.arange(0.0, 1.0, 0.001)
    >>> step = lambda s: np.clip((s - 0.4) / 0.04, 0, 1) - np.clip((s - 0.65) / 0.04, 0, 1)
    >>> L0 = I @ [14.0, 1.0, 2.0]
    >>> noise = np.random.default_rng(1).normal(0.0, 0.01, (200, 3))
    >>> for share in (0.0, 0.05):
    ...     h = lambda s: np.outer(share * np.linalg.norm(L0) * step(s), [0.6, 0.0, 0.8])
    ...     w = gyrostat_omega(I[None], L0[None], fine, h(fine), h(fine[:-1] + 0.0005))[0, ::5] + noise
    ...     t, keep = fine[::5], np.ones(w.shape, bool)
    ...     fit = momentum_steps(t, w, keep, fit_solution(t, w, keep, drag="quadratic"))
    ...     print(share, round(fit.change, 3), np.round(fit.times, 2))
    0.0 0.004 [0.18 0.49]
    0.05 0.067 [0.4  0.65]

    The steps are where the rotor spun up and braked; the change, in units of the rigid fit's
    ``|I w|`` (whose ratios the rotor bent), is of the rotor's size, not its value.
    """
    m, P = sol.model, sol.P
    t = np.asarray(t, float)
    omega = np.where(np.asarray(keep, bool), np.asarray(omega, float), sol.omega_model[0, :len(t)])
    inside = (t >= t[0] + TRIM) & (t <= t[-1] - TRIM)
    if inside.sum() < 20 or t[inside][-1] - t[inside][0] < 2 * EDGE + WIDTH + GRID:
        return None
    bias = m.bias_vector(P)
    Rw = flight_attitude(t, omega, sol)
    t, w, Rw = t[inside], (omega - bias)[inside], Rw[inside]
    # time counted where there are samples (a gap counts as three sample intervals): a level of the
    # internal momentum between two steps must hold over samples, not over a gap in them
    dts = np.diff(t)
    sampled = np.r_[0.0, np.cumsum(np.minimum(dts, 3.0 * float(np.median(dts))))]
    candidates = np.arange(t[0], t[-1] - WIDTH, GRID)
    at = np.interp(candidates, t, sampled)
    candidates = candidates[(at >= EDGE) & (sampled[-1] - np.interp(candidates + WIDTH, t, sampled) >= EDGE)]
    at = np.interp(candidates, t, sampled)
    if len(candidates) < 2:
        return None
    A, y, rigid = _budget(t, w, Rw, m.rotation_matrix(P), scale_errors)
    n, _, p = A.shape
    A = A.reshape(3 * n, p)
    scale = np.sqrt(np.einsum("ip,ip->p", A, A))
    scale[scale == 0] = 1.0
    A = A / scale
    yf = y.ravel()
    # the Gram blocks, by einsum (no threaded LAPACK on the tall matrices: rotor.MAX_SAMPLES)
    S = np.clip((t[:, None] - candidates[None, :]) / WIDTH, 0.0, 1.0)
    GAA, gA = np.einsum("ip,iq->pq", A, A), np.einsum("ip,i->p", A, yf)
    GAS = np.einsum("npk,nc->pck", np.einsum("nap,nak->npk", A.reshape(n, 3, p), Rw), S)
    SS = np.einsum("nc,nd->cd", S, S)  # the step columns are R(t) e_k S: R^T R = 1
    gS = np.einsum("nk,nc->ck", np.einsum("nak,na->nk", Rw, y), S)

    def normal(idx):
        q = p + 3 * len(idx)
        G, g = np.zeros((q, q)), np.zeros(q)
        G[:p, :p], g[:p] = GAA, gA
        for a, c in enumerate(idx):
            rows = slice(p + 3 * a, p + 3 * a + 3)
            G[:p, rows], G[rows, :p], g[rows] = GAS[:, c], GAS[:, c].T, gS[c]
            for b, d in enumerate(idx):
                G[rows, p + 3 * b:p + 3 * b + 3] = SS[c, d] * np.eye(3)
        Ginv = np.linalg.pinv(G)
        return Ginv @ g, Ginv

    chosen: list[int | None] = [None] * STEPS
    diag = SS[np.arange(len(candidates)), np.arange(len(candidates))]
    for _ in range(SWEEPS):
        for s in range(STEPS):
            others = [c for i, c in enumerate(chosen) if i != s and c is not None]
            x, Ginv = normal(others)
            X = np.concatenate([GAS] + [np.einsum("d,kl->kdl", SS[c], np.eye(3)) for c in others])
            resid = gS - np.einsum("jck,j->ck", X, x)  # each candidate's columns against the residual
            schur = diag[:, None, None] * np.eye(3) - np.einsum("jck,jcl->ckl", X, np.einsum("ij,jck->ick", Ginv, X))
            gain = np.einsum("ck,ck->c", resid, np.linalg.solve(schur + 1e-12 * np.eye(3), resid[..., None])[..., 0])
            for c in others:
                gain[np.abs(at - at[c]) < GAP] = -np.inf
            chosen[s] = int(np.argmax(gain))
    idx = sorted(c for c in chosen if c is not None)
    x0 = np.linalg.pinv(GAA[:rigid, :rigid]) @ gA[:rigid]
    L = float(np.linalg.norm(x0[rigid - 3:rigid] / scale[rigid - 3:rigid]))
    r0 = yf - A[:, :rigid] @ x0
    axis = _axis(GAA, gA, GAS[:, idx], SS[np.ix_(idx, idx)], gS[idx])
    M = np.hstack([A, np.column_stack([(Rw @ axis * S[:, c][:, None]).ravel() for c in idx])])
    G = np.einsum("ip,iq->pq", M, M)
    Ginv = np.linalg.pinv(G)
    x = Ginv @ np.einsum("ip,i->p", M, yf)
    r = yf - M @ x
    cov = Ginv * float(r @ r) / max(3 * n - M.shape[1], 1) * max(autocorrelation_time(r.reshape(-1, 3), [0, n]), 1.0)
    moments = m.moments(P) / np.sum(m.moments(P))  # the rigid fit's, in the budget's unit (trace 1)
    L0, L = L, float(np.median(np.linalg.norm((w @ m.rotation_matrix(P).T) * moments, axis=1)))
    best = (0.0, 0.0)
    k = len(idx)
    for i in range(k + 1):
        for j in range(i + 1, k + 1):
            e = np.zeros(len(x))
            e[p + i:p + j] = 1.0  # the levels' difference: the steps between them, along the axis
            size, std = abs(float(e @ x)), float(np.sqrt(max(e @ cov @ e, 0.0)))
            if size - K_SIGMA * std > best[0] - K_SIGMA * best[1]:
                best = (size, std)
    return StepFit(best[0] / L, best[1] / L, tuple(float(candidates[c]) for c in idx),
                   float(np.sqrt(np.mean(r0 ** 2))) / L0, float(np.sqrt(np.mean(r ** 2))) / L)


def _directions(count: int = 600) -> np.ndarray:
    """Unit vectors spread evenly over a hemisphere (a Fibonacci lattice: Gonzalez, Math. Geosci. 42
    (2010) 49), shape (count, 3)."""
    i = np.arange(count) + 0.5
    z = 1.0 - i / count
    phi = np.pi * (1.0 + np.sqrt(5.0)) * i
    r = np.sqrt(1.0 - z * z)
    return np.column_stack([r * np.cos(phi), r * np.sin(phi), z])


def _axis(GAA, gA, GAS, SS, gS) -> np.ndarray:
    """The body axis along which the steps at the chosen times (their Gram blocks ``GAS`` (p, k, 3),
    ``SS`` (k, k), ``gS`` (k, 3)) remove the most of the sum of squares, all steps along it."""
    D = _directions()
    Ginv = np.linalg.pinv(GAA)
    GAk = np.einsum("pkj,mj->mpk", GAS, D)  # each direction's step columns against the base
    gk = np.einsum("kj,mj->mk", gS, D)
    s = gk - np.einsum("mpk,p->mk", GAk, Ginv @ gA)
    schur = SS[None] - np.einsum("mpk,pq,mql->mkl", GAk, Ginv, GAk)
    gain = np.einsum("mk,mk->m", s, np.linalg.solve(schur + 1e-12 * np.eye(len(SS)), s[..., None])[..., 0])
    return D[int(np.argmax(gain))]


def step_check(t: np.ndarray, omega: np.ndarray, keep: np.ndarray, sol: Solution) -> str:
    """The reason a flight is not a rigid body's, or an empty string: an internal momentum that
    steps (a rotor spun up or braked) explains its world-frame budget (:func:`momentum_steps`,
    refused by :data:`MIN_CHANGE` and :data:`K_SIGMA`: module docstring), with the gyroscope's
    scale errors in the budget and without them (module docstring: each alone fakes a step on a
    rigid flight, the two never on the same).

    Examples
    --------
    A body whose internal rotor takes 5 % of ``|L|`` within 40 ms at 0.4 s and gives it back at
    0.65 s (200 Hz, 0.01 rad/s of noise): the rigid fit follows it within 1 % of the rates, which
    the adequacy test allows; its momentum budget does not.

    >>> import numpy as np
    >>> from tumble.analysis.fit.budget import step_check
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.dynamics.models.gyrostat import gyrostat_omega
    >>> I = np.diag([0.4, 0.85, 1.0])
    >>> fine = np.arange(0.0, 1.0, 0.001)
    >>> L0 = I @ [14.0, 1.0, 2.0]
    >>> step = lambda s: np.clip((s - 0.4) / 0.04, 0, 1) - np.clip((s - 0.65) / 0.04, 0, 1)
    >>> h = lambda s: np.outer(0.05 * np.linalg.norm(L0) * step(s), [0.6, 0.0, 0.8])
    >>> w = gyrostat_omega(I[None], L0[None], fine, h(fine), h(fine[:-1] + 0.0005))[0, ::5]
    >>> w = w + np.random.default_rng(1).normal(0.0, 0.01, w.shape)
    >>> t, keep = fine[::5], np.ones(w.shape, bool)
    >>> sol = fit_solution(t, w, keep, drag="quadratic")
    >>> bool(sol.rms < 0.015 * np.sqrt(np.mean(w ** 2)))
    True
    >>> step_check(t, w, keep, sol)[:50]
    'not a rigid body: a rotor spun up or braked inside'
    """
    fits = []
    for scale_errors in (True, False):  # the second only when the first refuses
        fit = momentum_steps(t, omega, keep, sol, scale_errors=scale_errors)
        if fit is None or fit.change - K_SIGMA * fit.change_std <= MIN_CHANGE:
            return ""
        fits.append(fit)
    fit = min(fits, key=lambda f: f.change - K_SIGMA * f.change_std)
    return (f"not a rigid body: a rotor spun up or braked inside (its momentum changes by {100 * fit.change:.2g} "
            f"+- {100 * fit.change_std:.2g} % of |L| at {', '.join(f'{x:.2f}' for x in fit.times)} s in the "
            f"world-frame momentum budget, where a rigid body's drag, flex and sensor errors fake at most "
            f"{100 * MIN_CHANGE:.2g} %): an internal torque acts")
