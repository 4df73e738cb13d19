"""The joint fit of many flights of one body (:func:`joint_solution`), from one recording or several.

The flights share the body, so the joint model (:class:`~tumble.analysis.fit.model.Model` with
``F`` flights) shares the ratios and the drag, and gives each flight its own ``omega0``. The
sensor's rotation and bias are shared by the flights of one recording; flights of different
recordings (``groups``) each have their recording's own (a phone strapped on again, a gyroscope
started again, a bias that drifted between recordings). The start: the flight whose ratios are
nearest the flights' medians gives the ratios; in each recording its own flight nearest them gives
that recording's rotation and bias, the other flights' ``omega0`` turned into its principal
frame; the drag model is the one most flights chose.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from ...typing import ArrayLike
from .model import Model
from .result import public_covariance, ratio_summary
from .solve import Solution, solve, without_drag_law_error

if TYPE_CHECKING:
    from .flights import Flight

__all__ = ["joint_solution", "stack_flights"]


def joint_solution(used: Sequence[Flight], groups: ArrayLike, t: np.ndarray, omega: np.ndarray, keep: np.ndarray,
                   drag: str, scale_uncertainty: float) -> tuple[Solution | None, list[np.ndarray], list[int]]:
    """The joint solution over the used flights (module docstring), the joint model at each
    flight, and the indices of the flights that disagree grossly with the others (their own
    ratios more than five standard uncertainties from the reference flight's): left out.
    The solution is None when fewer than two flights agree or the joint fit went astray.

    ``used`` are :class:`~tumble.analysis.fit.flights.Flight` with their samples at
    ``t[first:stop]``, ``groups`` each one's recording (``0 .. G-1``, any labels: renumbered).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.flights import find_flights
    >>> from tumble.analysis.fit.joint import joint_solution
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
    >>> used = find_flights(rec.t, rec.omega, events=rec.events)
    >>> keep = np.ones(rec.omega.shape, bool)
    >>> sol, models, outliers = joint_solution(used, [0, 0], rec.t, rec.omega, keep, "auto", 0.0)
    >>> sol.model.F, len(models), outliers
    (2, 2, [])
    """
    groups = np.unique(np.asarray(groups, int), return_inverse=True)[1].reshape(-1)
    sols = [f.solution for f in used]
    rat = np.array([ratio_summary(s)[0] for s in sols])
    # the reference among the flights that determine the ratios (not one joined for the joint fit only)
    own = np.array([not getattr(f, "joinable", False) for f in used])
    own = own if own.any() else np.ones(len(used), bool)
    near = np.sum((rat - np.median(rat[own], axis=0)) ** 2, axis=1) + np.where(own, 0.0, np.inf)
    ref = int(np.argmin(near))
    # the gross outliers first, from the flights' own fits alone: left out before anything is
    # refitted, so that a joint fit that goes astray still names them (a phone's flight pooled with
    # a racquet's: the refit failed and the flights' weighted mean, I1/I3 0.20 for the racquet's
    # 0.06 and chi2/dof 593, was written as adequate; a walkthrough, 2026-12-02)
    agree = [bool(not own[j] or _agrees(sols[j], sols[ref])) for j in range(len(used))]
    keep_idx = [j for j, ok in enumerate(agree) if ok]
    if len(keep_idx) < len(used):
        if len(keep_idx) < 2:
            return None, [], [j for j in range(len(used)) if not agree[j]]
        sub = [used[j] for j in keep_idx]
        sol, models, _ = joint_solution(sub, groups[keep_idx], t, omega, keep, drag, scale_uncertainty)
        return sol, models, [j for j in range(len(used)) if not agree[j]]
    kinds = Counter(s.model.drag for s in sols)
    kind = drag if drag != "auto" else kinds.most_common(1)[0][0]
    m_ref, P_ref = sols[ref].model, sols[ref].P
    G = int(groups.max()) + 1
    # each recording's reference flight: its rotation and bias start that recording's
    refs = [int(min(np.flatnonzero(groups == r), key=lambda j: near[j])) for r in range(G)]
    R_refs = [sols[j].model.rotation_matrix(sols[j].P) for j in refs]
    taus, speeds = [], []
    for f in used:
        sl = slice(f.first, f.stop)
        taus.append(t[sl] - f.anchor)
        speeds.append(float(np.max(np.linalg.norm(omega[sl], axis=1))))
    model = Model(taus, m_ref.rotation, m_ref.bias, kind, speeds, groups=groups)
    data, mask = stack_flights(used, omega, keep)
    w0 = np.array([R_refs[groups[j]] @ s.model.rotation_matrix(s.P).T @ s.model.omega0(s.P)[0]
                   for j, s in enumerate(sols)])
    same = [s.model.drag_vector(s.P) for s in sols if s.model.drag == kind]
    drag0 = np.median(same, axis=0) if same and kind != "none" else np.zeros(3)
    rv = np.array([Rotation.from_matrix(R).as_rotvec() if m_ref.rotation else np.zeros(3) for R in R_refs])
    b = np.array([sols[j].model.bias_vector(sols[j].P) for j in refs])
    P0 = model.pack(P_ref[0], P_ref[1], rv, b, w0, drag0)
    # each flight's omega0 refitted under the shared parameters: near the separatrix another
    # flight's ratios move a flight onto another mode, and its own omega0 must follow
    for j, f in enumerate(used):
        n = f.stop - f.first
        one = Model([model.tau[j, :n]], model.rotation, model.bias, kind, model.speeds[j:j + 1])
        shared = P0[model.flight_parameters(j)[:-3]]

        def fun(w, one=one, j=j, n=n, shared=shared):
            return (one.sensor(np.concatenate([shared, w]))[0] - data[j, :n])[mask[j, :n]]

        try:
            with np.errstate(all="ignore"):
                fitted = least_squares(fun, P0[model.ns + 3 * j:model.ns + 3 * j + 3], max_nfev=50)
        except ValueError:  # not finite at the start: the shared drag, integrated back from this
            return None, [], []  # flight's anchor to its first samples, diverges: astray (caller pools)
        P0[model.ns + 3 * j:model.ns + 3 * j + 3] = fitted.x
    try:
        sol = solve(model, data, mask, P0, max_nfev=60, scale_uncertainty=scale_uncertainty)
    except (ValueError, np.linalg.LinAlgError):  # the solver failed numerically: astray, as below
        return None, [], []
    own = np.sqrt(sum(s.ssr for s in sols) / sum(s.m for s in sols))
    if np.sqrt(sol.ssr / sol.m) > 2.0 * own + 0.01 * np.sqrt(np.mean(data[mask] ** 2)):
        return None, [], []  # the joint fit went astray: the caller pools the flights' own fits
    return sol, [sol.omega_model[j, :f.stop - f.first] for j, f in enumerate(used)], []


def _agrees(sol: Solution, ref: Solution) -> bool:
    """Whether a flight's own ratios lie within five standard uncertainties (its own and the
    reference flight's) of the reference's: the others are gross outliers, left out of a joint fit;
    the Birge ratio deals with the rest.

    The uncertainties hold the gyroscope's scale-factor part: the scale errors are common to the
    flights of a recording, but each flight's motion maps them into its ratios differently, so they
    do not cancel in the difference. Taken as independent, which is a margin, not the covariance:
    on 684 pairs of agreeing synthetic flights (benchmarks/pair_outliers.py 40) the statistical part
    alone put 6.6 % beyond five (chi^2 > 25), the independent scale parts 0.7 % (median chi^2 0.40
    where 1.39 is right), the common error's own (B_a - B_b)(B_a - B_b)^T 2.3 % (median 1.00): the
    flights' covariances miss part of some flights' error, and the margin keeps those flights from
    being dropped as outliers. Not the drag law's model error: the flights are pooled without it
    (:mod:`tumble.analysis.fit.solve`), and a flight it alone brings within five sigma swells the
    pooled ratios' Birge ratio (50 racquet tosses: chi^2/dof 28 against 4). A flight joined for the
    joint fit only states no ratios of its own to compare (its residuals under the joint fit are its
    test: :func:`tumble.analysis.fit.recording._joined`); the caller passes it."""
    dv = ratio_summary(sol)[0] - ratio_summary(ref)[0]
    C = sum(public_covariance(without_drag_law_error(s))[2][:2, :2] for s in (sol, ref))
    return bool(dv @ np.linalg.pinv(C) @ dv <= 25.0)


def stack_flights(used: Sequence[Flight], omega: np.ndarray, keep: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The used flights' samples and kept axes laid out as a joint model's, shape ``(F, T, 3)``.

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> from tumble.analysis.fit.joint import stack_flights
    >>> omega = np.arange(30.0).reshape(10, 3)
    >>> data, mask = stack_flights([SimpleNamespace(first=0, stop=4), SimpleNamespace(first=6, stop=8)], omega, omega > 0)
    >>> data.shape, mask[1].sum(axis=0).tolist()   # the second flight: 2 samples, then padding
    ((2, 4, 3), [2, 2, 2])
    """
    T = max(f.stop - f.first for f in used)
    data = np.zeros((len(used), T, 3))
    mask = np.zeros((len(used), T, 3), bool)
    for j, f in enumerate(used):
        n = f.stop - f.first
        data[j, :n] = omega[f.first:f.stop]
        mask[j, :n] = keep[f.first:f.stop]
    return data, mask


def first_flight_view(sol: Solution) -> Solution:
    """The joint solution seen as a one-flight solution (its first flight's omega0, samples and
    recording's rotation and bias), so that :func:`~tumble.analysis.fit.result.rotation_fit`
    reports the shared parameters with their pooled covariance.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.flights import find_flights
    >>> from tumble.analysis.fit.joint import first_flight_view, joint_solution
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
    >>> used = find_flights(rec.t, rec.omega, events=rec.events)
    >>> sol = joint_solution(used, [0, 0], rec.t, rec.omega, np.ones(rec.omega.shape, bool), "auto", 0.0)[0]
    >>> one = first_flight_view(sol)
    >>> one.model.F, one.P.tolist() == sol.P[:one.model.n].tolist()
    (1, True)
    """
    m = sol.model
    keep = m.flight_parameters(0)
    n = int(m.lengths[0])
    one = Model([m.tau[0, :n]], m.rotation, m.bias, m.drag, m.speeds[:1])
    rename = {m.names[k]: one.names[i] for i, k in enumerate(keep)}
    undetermined = tuple(rename[name] for name in sol.undetermined if name in rename)
    return Solution(one, sol.P[keep], sol.cov[np.ix_(keep, keep)], sol.cov_stat[np.ix_(keep, keep)],
                    sol.residuals, sol.omega_model[:1, :n], undetermined, sol.nfev, sol.autocorrelation_time, sol.ssr, sol.m,
                    scale_effect=None if sol.scale_effect is None else sol.scale_effect[keep])
