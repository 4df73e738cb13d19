"""From a solved model to what a fit says: the ratios, their uncertainty and the verdicts.

:func:`public_covariance` carries the covariance from the fit's square coordinates to
``(I1/I3, I2/I3)`` by the chain rule (:func:`tumble.analysis.fit.triangle.ratio_jacobian`);
:func:`ratio_summary` gives the ratios with their 95 % intervals; :func:`solution_adequacy`
says whether the model describes the data and :func:`determination` whether the data determine
the ratios. :mod:`tumble.analysis.fit.result` builds the :class:`~tumble.analysis.fit.result.RotationFit` from them.
"""

from __future__ import annotations

import numpy as np

from .adequacy import Adequacy, judge, rigid_body_check
from .solve import Solution, without_drag_law_error
from .triangle import EDGES, S_MIN, edge_of, ratio_jacobian, ratios
from .uncertainty import effective_dof, interval, noise_floor

__all__ = ["DETERMINED_STD", "determination", "flight_budgets", "public_covariance", "ratio_scale_effect", "ratio_summary", "solution_adequacy"]

#: Largest standard uncertainties reported for I1/I3 and I2/I3: half their ranges in the triangle.
_STD_CAP = (0.5, 0.25)
#: A ratio whose standard uncertainty exceeds this is not determined by the data (dimensionless):
#: a fifth of the range of I1/I3, nothing a user can take away from a toss.
DETERMINED_STD = 0.1


def public_covariance(sol: Solution, statistical: bool = False) -> tuple[tuple[str, ...], np.ndarray, np.ndarray]:
    """The ratios, their covariance with everything else in the public order, and the names.

    ``statistical``: leave out the scale factor's systematic part. Returns ``(names, values, cov)`` with ``I1/I3``, ``I2/I3``, ``omega0_*``, ``rotvec_*``,
    ``bias_*``, drag; undetermined parameters keep NaN rows.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)   # I1/I3 = 0.5, I2/I3 = 0.8; white noise of 0.01 rad/s
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
    >>> keep = np.ones(w.shape, bool)
    >>> sol = fit_solution(t, w, keep, rotation=False, bias=False, drag="none")
    >>> from tumble.analysis.fit.summary import public_covariance
    >>> from tumble.analysis.fit.triangle import ratio_jacobian, ratios
    >>> names, values, cov = public_covariance(sol)
    >>> names, bool(np.allclose(values[:2], ratios(sol.P[0], sol.P[1])))
    (('I1/I3', 'I2/I3', 'omega0_1', 'omega0_2', 'omega0_3'), True)
    >>> G = ratio_jacobian(sol.P[0], sol.P[1])   # (s, g) carried to the ratios by the chain rule
    >>> bool(np.allclose(cov[:2, :2], G @ sol.cov[:2, :2] @ G.T))
    True
    """
    model, P = sol.model, sol.P
    per = list(model.names[model.ns:])
    rest = [n for n in model.shared if n not in ("s", "g")]
    names = ["I1/I3", "I2/I3"] + per + rest
    idx = {n: i for i, n in enumerate(model.names)}
    G = np.zeros((len(names), model.n))
    G[:2, :2] = ratio_jacobian(P[0], P[1])[:, [0, 1]]
    for i, n in enumerate(names[2:], start=2):
        G[i, idx[n]] = 1.0
    C = np.nan_to_num(sol.cov_stat if statistical else sol.cov, nan=0.0)
    cov = G @ C @ G.T
    bad = np.isnan(np.diag(sol.cov))
    for i, n in enumerate(names):
        if n in idx and bad[idx[n]]:
            cov[i, :] = cov[:, i] = np.nan
    if bad[0] and bad[1]:
        cov[:2, :] = cov[:, :2] = np.nan
    x, y = ratios(P[0], P[1])
    values = np.concatenate([[float(x), float(y)], P[model.ns:], [P[idx[n]] for n in rest]])
    return tuple(names), values, cov


def ratio_scale_effect(sol: Solution) -> np.ndarray:
    """The ratios' shift per standard uncertainty of each gyroscope axis's scale factor, shape (2, 3).

    The solution's :attr:`~tumble.analysis.fit.solve.Solution.scale_effect` carried to
    ``(I1/I3, I2/I3)`` by the chain rule, as :func:`public_covariance` carries the covariance;
    zero where the solution kept none. Flights of one gyroscope share the error and each answers
    it in its own way: their ratios are compared with it
    (:func:`~tumble.analysis.fit.uncertainty.birge_chi2`).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.analysis.fit.summary import public_covariance, ratio_scale_effect
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)   # I1/I3 = 0.5, I2/I3 = 0.8; white noise of 0.01 rad/s
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
    >>> sol = fit_solution(t, w, np.ones(w.shape, bool), rotation=False, bias=False, drag="none", scale_uncertainty=0.005)
    >>> B = ratio_scale_effect(sol)
    >>> total, stat = public_covariance(sol)[2][:2, :2], public_covariance(sol, statistical=True)[2][:2, :2]
    >>> B.shape, bool(np.allclose(B @ B.T, total - stat))   # the covariance's scale part, B B^T
    ((2, 3), True)
    """
    if sol.scale_effect is None:
        return np.zeros((2, 3))
    return ratio_jacobian(sol.P[0], sol.P[1])[:, [0, 1]] @ np.nan_to_num(sol.scale_effect[:2])


def ratio_summary(sol: Solution) -> tuple[np.ndarray, np.ndarray, np.ndarray, str | None]:
    """``(ratios, std, interval, edge)`` of a solution.

    The standard uncertainties are capped at half each ratio's range in the triangle. The 95 %
    intervals: inside the triangle, ``+- k std`` clipped to it (``k`` Student's for the
    Welch-Satterthwaite degrees of freedom of the statistical part, ``m / tau - n``, and the
    systematic one); on an edge, the interval of
    the square's coordinates (one-sided in the one normal to the edge,
    :func:`~tumble.analysis.fit.uncertainty.interval`) carried to the ratios through the map
    of :mod:`~tumble.analysis.fit.triangle` (``I1/I3`` grows with both coordinates, ``I2/I3``
    falls with ``s`` and grows with ``g``), so that an optimum held on the planar edge keeps an
    interval along the edge.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)   # I1/I3 = 0.5, I2/I3 = 0.8; white noise of 0.01 rad/s
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
    >>> keep = np.ones(w.shape, bool)
    >>> sol = fit_solution(t, w, keep, rotation=False, bias=False, drag="none")
    >>> from tumble.analysis.fit.summary import public_covariance, ratio_summary
    >>> rat, std, interval, edge = ratio_summary(sol)
    >>> rat.round(2).tolist(), edge, bool(np.allclose(std, np.sqrt(np.diag(public_covariance(sol)[2])[:2])))
    ([0.5, 0.8], None, True)
    >>> bool(np.all(interval[:, 0] < rat) and np.all(rat < interval[:, 1]))   # about +- 2 std
    True
    """
    _names, values, cov = public_covariance(sol)
    _, _, cov_stat = public_covariance(sol, statistical=True)
    x, y = values[0], values[1]
    sq, gq = float(sol.P[0]), float(sol.P[1])
    edge = edge_of(sq, gq)
    std = np.sqrt(np.abs(np.diag(cov)[:2]))
    std = np.where(np.isfinite(std), np.minimum(std, _STD_CAP), _STD_CAP)
    # the residuals hold m / tau independent values; n parameters were fitted to them
    dof_stat = max(sol.m / max(sol.autocorrelation_time, 1.0) - sol.model.n, 1.0)
    dof = [effective_dof(cov_stat[i, i], cov[i, i], dof_stat) for i in range(2)]
    if edge is None or edge == EDGES["rod"]:
        ix = interval(x, std[0], 0.0, 1.0, dof=dof[0])
        iy = interval(y, std[1], 0.5, 1.0, dof=dof[1])
        return np.array([x, y]), std, np.array([ix, iy]), edge
    c = np.nan_to_num(sol.cov[:2, :2], nan=np.inf)
    ss, sg = (float(np.sqrt(v)) if np.isfinite(v) else np.inf for v in np.diag(c))
    d = min(dof)
    s_lo, s_hi = interval(sq, ss, S_MIN, 1.0, on_high_edge=edge == EDGES["I1=I2"], dof=d)
    g_lo, g_hi = interval(gq, sg, 0.0, 1.0, on_low_edge=edge == EDGES["planar"], on_high_edge=edge == EDGES["I2=I3"],
                          dof=d)
    ix = (float(ratios(s_lo, g_lo)[0]), float(ratios(s_hi, g_hi)[0]))
    iy = (float(ratios(s_hi, g_lo)[1]), float(ratios(s_lo, g_hi)[1]))
    return np.array([x, y]), std, np.array([ix, iy]), edge


def solution_adequacy(sol: Solution, data: np.ndarray, mask: np.ndarray) -> Adequacy:
    """:func:`~tumble.analysis.fit.adequacy.judge` on a solution of one or many flights.

    ``data`` and ``mask`` are the samples and the kept axes as the solution's model lays them
    out, shape ``(F, T, 3)``; the noise is each flight's (:func:`noise_floor` of its residuals at
    the samples with all axes kept), combined over the flights weighted by their lengths. Then,
    where the ratios are determined (:func:`determination`), each flight's energy and momentum
    budgets (:func:`flight_budgets`); where they are not, the moments they would be computed with
    are not known, and a rigid flight recorded too briefly was accused of an internal torque
    (seed 71's flexing racquet: "its energy rose by 10.3 %", its ratios' uncertainties 0.5 and 0.25).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)   # I1/I3 = 0.5, I2/I3 = 0.8; white noise of 0.01 rad/s
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
    >>> keep = np.ones(w.shape, bool)
    >>> sol = fit_solution(t, w, keep, rotation=False, bias=False, drag="none")
    >>> from tumble.analysis.fit.summary import solution_adequacy
    >>> verdict = solution_adequacy(sol, w[None], keep[None])
    >>> verdict.adequate, verdict.misfit < 0.01   # residuals at the noise: the model describes the data
    (True, True)
    """
    data, mask = np.asarray(data, float), np.asarray(mask, bool)
    noise2, weight = 0.0, 0
    for j, n in enumerate(sol.model.lengths):
        n = int(n)
        rows = np.all(mask[j, :n], axis=1)
        noise2 += noise_floor((data[j, :n] - sol.omega_model[j, :n])[rows]) ** 2 * n
        weight += n
    verdict = judge(sol.rms, float(np.sqrt(noise2 / max(weight, 1))), float(np.sqrt(np.mean(data[mask] ** 2))),
                    sensor_rotation_fitted=sol.model.rotation)
    if not verdict.adequate or determination(sol, ratio_summary(sol)[1]):
        return verdict  # ratios not determined: the budgets, computed with its moments, say nothing
    for j in range(len(sol.model.lengths)):
        why = flight_budgets(sol, j, data[j], mask[j])
        if why:
            return Adequacy(False, verdict.misfit, why)
    return verdict


def flight_budgets(sol: Solution, j: int, data: np.ndarray, mask: np.ndarray) -> str:
    """:func:`~tumble.analysis.fit.adequacy.rigid_body_check` of flight ``j`` of a solution, its
    samples ``data`` and kept axes ``mask`` (shape ``(T, 3)``, as the model lays them out)
    turned to the principal frame with its recording's mount and bias, with the solution's
    moments: ``""``, or why a rigid body cannot move so. Only where the moments are determined
    (:func:`determination`) do its energy and momentum budgets say anything.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.analysis.fit.summary import flight_budgets
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
    >>> keep = np.ones(w.shape, bool)
    >>> sol = fit_solution(t, w, keep, rotation=False, bias=False, drag="none")
    >>> flight_budgets(sol, 0, w, keep)   # a free rigid body's: its energy and |L| stay
    ''
    >>> flight_budgets(sol, 0, w * (1.0 + 0.1 * np.sin(6.0 * t))[:, None], keep).split(":")[0]   # momentum in and out
    'not a rigid body'
    """
    m, P = sol.model, sol.P
    n, group = int(m.lengths[j]), int(m.groups[j])
    R, b = m.rotation_matrix(P, group), m.bias_vector(P, group)
    rows = np.all(mask[:n], axis=1)
    return rigid_body_check(m.tau[j, :n][rows], (data[:n][rows] - b) @ R.T, m.moments(P))


def determination(sol: Solution, std: np.ndarray, max_std: float = DETERMINED_STD) -> str:
    """Why a flight's ratios are not determined, or ``""`` when they are.

    Not determined: a ratio's coordinate is undetermined, or a ratio's standard uncertainty
    ``std`` exceeds ``max_std``. The reason names the air's drag when the drag law's model error
    alone (:func:`~tumble.analysis.fit.solve.with_drag_law_error`) takes ``std`` over
    ``max_std``, and otherwise tells a toss about a stable axis (the intermediate
    axis never carries half of ``|omega|``) from a tumble recorded too briefly, with the
    record's length in turns (``integral |omega| dt / 2 pi``).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)   # I1/I3 = 0.5, I2/I3 = 0.8; white noise of 0.01 rad/s
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
    >>> keep = np.ones(w.shape, bool)
    >>> sol = fit_solution(t, w, keep, rotation=False, bias=False, drag="none")
    >>> from tumble.analysis.fit.summary import determination, ratio_summary
    >>> std = ratio_summary(sol)[1]
    >>> determination(sol, std)   # both ratios known to better than 0.1: determined
    ''
    >>> print(determination(sol, std, max_std=0.001))   # a stricter limit: the reason says what is missing
    too little of the tumble recorded (2 s, 2.1 turns): the ratios are not both determined (uncertainties 0.0043, 0.0027 > 0.001; a longer or faster toss about the intermediate axis fixes both)
    """
    if not ({"s", "g"} & set(sol.undetermined) or np.max(std) > max_std):
        return ""
    if not {"s", "g"} & set(sol.undetermined) and sol.cov_drag_law is not None:
        bare = ratio_summary(without_drag_law_error(sol))[1]
        if np.max(bare) <= max_std:  # determined but for the drag law's part
            return (f"ratios not determined for the air's drag: with the shift of the ratios between the two drag "
                    f"laws their uncertainties are {std[0]:.2g}, {std[1]:.2g} > {max_std} ({bare[0]:.2g}, {bare[1]:.2g} "
                    "without it); a body the air slows less over its flight (heavier for its size) fixes both")
    n = int(sol.model.lengths[0])
    wp = sol.model.principal(sol.P)[0, :n]
    speed = np.linalg.norm(wp, axis=1)
    share = np.abs(wp[:, 1]) / np.maximum(speed, 1e-300)
    tau = sol.model.tau[0, :n]
    turns = float(np.sum(0.5 * (speed[1:] + speed[:-1]) * np.diff(tau)) / (2 * np.pi))
    what = ("stable-axis toss (spun about the minor or major axis)" if np.max(share) < 0.5 else
            f"too little of the tumble recorded ({tau[-1] - tau[0]:.2g} s, {turns:.2g} turns)")
    return (f"{what}: the ratios are not both determined (uncertainties {std[0]:.2g}, {std[1]:.2g} > {max_std}; "
            "a longer or faster toss about the intermediate axis fixes both)")
