"""A flight's window in a gyroscope's samples: grown from a seed's fit while the model, extrapolated,
follows the samples, trimmed of the end samples it does not follow, and fitted again
(:func:`~tumble.analysis.fit.flights.find_flights`'s steps, its module docstring)."""

from __future__ import annotations

import numpy as np

from .model import Model
from .solve import Solution, solve


def _extrapolate(sol: Solution, t, t0) -> np.ndarray:
    """The solved flight's model in sensor axes at times ``t`` (s), its time origin ``t0``; NaN
    where it does not exist: quadratic drag run backward in time, ``omega' = +c |omega| omega``,
    blows up in finite time (the growth takes such samples as not following the model)."""
    m = sol.model
    probe = Model([np.asarray(t, float) - t0], m.rotation, m.bias, m.drag, m.speeds)
    with np.errstate(over="ignore", invalid="ignore"):
        out = probe.sensor(sol.P)[0]
    out[~np.all(np.isfinite(out), axis=1)] = np.nan
    return out


def _grow(t, omega, keep, a, b, sol: Solution, lo, hi, anchor):
    """Grow ``[a, b)`` while the extrapolated model follows the samples (module docstring)."""
    rms = sol.rms
    new = [a, b]
    for side in (-1, 1):
        idx = np.arange(a - 1, max(lo, a - 400) - 1, -1) if side < 0 else np.arange(b, min(hi, b + 400))
        if not idx.size:
            continue
        pred = _extrapolate(sol, t[idx], anchor)
        err = np.abs(pred - omega[idx])
        tol = np.maximum(6.0 * rms, 0.03 * np.linalg.norm(pred, axis=1))[:, None]
        # the stretch's end counts as a bad sample: one bad sample just before it ends the flight
        bad = np.append(np.any((err > tol) & keep[idx], axis=1) | np.isnan(pred[:, 0]), True)
        pairs = np.flatnonzero(bad[:-1] & bad[1:])
        n_ok = int(pairs[0]) if pairs.size else len(idx)
        if side < 0:
            new[0] = a - n_ok
        else:
            new[1] = b + n_ok
    return new[0], new[1]


def _trim(omega, keep, a, b, sol: Solution, k: float = 5.0, rms: float | None = None):
    """Drop end samples of ``[a, b)`` whose residual exceeds ``k`` times the fit's RMS (or ``rms``,
    that of a fit without them): the last of the throw or the first of the catch that the
    growth's tolerance, or the accelerometer's free fall, let in."""
    model = sol.omega_model[0, :b - a]
    err = np.max(np.where(keep[a:b], np.abs(model - omega[a:b]), 0.0), axis=1)
    rms = sol.rms if rms is None else rms
    lo, hi = 0, b - a
    while hi - lo > 2 and err[lo] > k * rms:
        lo += 1
    while hi - lo > 2 and err[hi - 1] > k * rms:
        hi -= 1
    return a + lo, a + hi


def _refit(t, omega, keep, a: int, b: int, sol: Solution, anchor: float) -> Solution:
    """``sol``'s model fitted again on ``[a, b)`` from its parameters (a grown or trimmed window)."""
    m = sol.model
    window = Model([t[a:b] - anchor], m.rotation, m.bias, m.drag, [np.max(np.linalg.norm(omega[a:b], axis=1))])
    return solve(window, omega[None, a:b], keep[None, a:b], sol.P, max_nfev=40, covariance=False)


def _drag_free(sol: Solution) -> np.ndarray:
    """The parameters of ``sol`` in the drag-free layout (a start for the next window)."""
    m, P = sol.model, sol.P
    free = Model([np.zeros(2)], m.rotation, m.bias)
    rv = P[m.index["rotvec_x"]:m.index["rotvec_x"] + 3] if m.rotation else np.zeros(3)
    return free.pack(P[0], P[1], rv, m.bias_vector(P), m.omega0(P))
