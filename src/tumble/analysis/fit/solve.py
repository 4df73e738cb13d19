"""The least-squares solution of a :class:`~tumble.analysis.fit.model.Model` and what it determines.

:func:`scipy.optimize.least_squares` (the dogbox trust region, box bounds for the triangle's
square and the drag's signs, ``x_scale="jac"``) on the residuals ``model - data`` of the
samples kept by a mask (a saturated axis is left out, not the whole sample). At the optimum:

- **undetermined parameters**: the Jacobian's columns scaled to unit norm; while the smallest
  eigenvalue of their normal matrix is below ``RANK_TOL^2`` of the largest, the parameter with
  the largest share of its eigenvector is named undetermined and left at its value (e.g. the
  sensor's rotation about a symmetric body's axis); the rest keep their uncertainties;
- **covariance**: :mod:`tumble.analysis.fit.uncertainty` (the statistical part from the
  residuals, plus the systematic part of the gyroscope's scale-factor tolerance);
- **drag**: with ``drag="auto"`` the models ``none`` and ``quadratic`` (per axis,
  :mod:`tumble.dynamics.models.drag`; see :data:`AUTO_DRAG` for why not ``linear``) are fitted
  and the one of least Bayesian information criterion ``m ln(SSR/m) + n ln m`` kept (Schwarz,
  Ann. Stat. 6 (1978) 461);
- **the drag law's model error** (:func:`with_drag_law_error`): a fitted drag law is an
  approximation (a plate's drag couples its in-plane rates, which neither per-axis law can
  follow), and the parameters absorb what it misses where the residuals, from which the
  statistical part is estimated, do not show it. The solution is solved again with the other
  law (``linear`` for ``quadratic`` and back), and the parameters' shift ``d`` is taken as one
  standard uncertainty of the model, ``d d^T`` added to the covariance as a systematic part
  (on model differences as systematic errors: Barlow, "Systematic errors: facts and fictions",
  arXiv:hep-ex/0207026, 2002). The whole difference, the conservative end of the conventions:
  the half-difference of a two-model average (Burnham & Anderson, *Model Selection and
  Multimodel Inference*, 2002, sec. 4.3.2) left the synthetic racquet's intervals at 89-90 %.
  It does not shrink with more samples, as the statistical part does
  (benchmarks/results/fit_coverage.md: without it, the 95 % intervals of the synthetic racquet
  sampled at 200-500 Hz held its ratios in 81-87 %).
  It is a flight's own: the joint fit of many flights (:mod:`~tumble.analysis.fit.joint`) leaves
  it out, and the pooled ratios' uncertainty is widened instead by the flights' scatter about
  them (the Birge ratio, :mod:`~tumble.analysis.fit.recording`), which holds the part of the
  model error that differs from flight to flight.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from scipy.optimize import least_squares

from ..._html import headline_html, headline_repr
from ...typing import ArrayLike
from .model import DRAG_MODELS, Model
from .uncertainty import effective_covariance, scale_effect

__all__ = ["RANK_TOL", "Solution", "check_drag", "solve", "solve_drag", "with_drag_law_error", "without_drag_law_error"]

#: Scaled singular values below this fraction of the largest mark undetermined parameters.
RANK_TOL = 1e-7
#: The drag models ``drag="auto"`` chooses from. A hand-tossed body of 0.1-0.7 m at 5-25 rad/s
#: meets the air at a Reynolds number ``w L^2 / nu`` of 1e4-1e5, where drag is quadratic
#: (Hoerner, *Fluid-Dynamic Drag*, ch. 3); a linear (viscous) drag needs ``Re < ~1``. Offered
#: as a choice, the linear model's per-axis rates also absorb errors of the ratios (measured on
#: the synthetic racquet: a wrong I1/I3 by 3 sigma with a fitted drag about the plate's normal),
#: so "auto" weighs only none against quadratic; "linear" is there to be asked for.
AUTO_DRAG = ("none", "quadratic")
#: Parameters that may be named undetermined, in the order they are tried on a tie.
_FIXABLE = ("drag_3", "drag_1", "drag_2", "rotvec_x", "rotvec_y", "rotvec_z", "g", "s", "bias_x", "bias_y", "bias_z")


@dataclass
class Solution:
    """A solved model: parameters, their covariance (undetermined ones with NaN; ``cov_stat``
    without the systematic parts: the gyroscope's scale factor and, in ``cov_drag_law``, the drag
    law's model error), residuals.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.model import Model
    >>> from tumble.analysis.fit.solve import solve
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t) + np.random.default_rng(0).normal(0.0, 0.01, (1, 201, 3))
    >>> model = Model([t], rotation=False, bias=False)
    >>> sol = solve(model, w, np.ones(w.shape, bool), model.pack(0.65, 0.45, None, None, [[2.8, 1.1, 6.2]]))
    >>> sol.m, bool(np.isclose(sol.ssr, sol.residuals @ sol.residuals)), sol.cov.shape, sol.undetermined
    (603, True, (5, 5), ())
    """

    HEADLINE = (("m", "residuals", ""), ("rms", "RMS residual", "rad/s"), ("nfev", "model evaluations", ""),
                ("autocorrelation_time", "autocorrelation", "samples"), ("undetermined", "undetermined", ""))
    __repr__ = headline_repr
    _repr_html_ = headline_html

    model: Model
    P: np.ndarray
    cov: np.ndarray
    cov_stat: np.ndarray
    residuals: np.ndarray
    omega_model: np.ndarray
    undetermined: tuple
    nfev: int
    autocorrelation_time: float  # of the residuals, samples
    ssr: float
    m: int
    cov_drag_law: np.ndarray | None = None  # the part of ``cov`` that is the drag law's model error (with_drag_law_error)
    #: the parameters' shift per standard uncertainty of each gyroscope axis's scale factor, shape (n, 3)
    #: (:func:`~tumble.analysis.fit.uncertainty.scale_effect`; NaN rows undetermined): ``cov``'s scale part is ``B B^T``
    scale_effect: np.ndarray | None = None

    @property
    def rms(self) -> float:
        """The root mean square of the residuals, rad/s.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.model import Model
        >>> from tumble.analysis.fit.solve import solve
        >>> from tumble.dynamics.methods.exact_omega import free_omega
        >>> t = np.linspace(0.0, 2.0, 201)
        >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t) + np.random.default_rng(0).normal(0.0, 0.01, (1, 201, 3))
        >>> model = Model([t], rotation=False, bias=False)
        >>> sol = solve(model, w, np.ones(w.shape, bool), model.pack(0.65, 0.45, None, None, [[2.8, 1.1, 6.2]]))
        >>> round(sol.rms, 3), bool(np.isclose(sol.rms ** 2, sol.ssr / sol.m))   # the white noise's 0.01 rad/s
        (0.01, True)
        """
        return float(np.sqrt(np.mean(self.residuals ** 2)))

    @property
    def bic(self) -> float:
        """Schwarz's Bayesian information criterion ``m ln(SSR / m) + n ln m`` (``n`` the parameters determined): the smaller, the better.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.model import Model
        >>> from tumble.analysis.fit.solve import solve
        >>> from tumble.dynamics.methods.exact_omega import free_omega
        >>> t = np.linspace(0.0, 2.0, 201)
        >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t) + np.random.default_rng(0).normal(0.0, 0.01, (1, 201, 3))
        >>> model = Model([t], rotation=False, bias=False)
        >>> sol = solve(model, w, np.ones(w.shape, bool), model.pack(0.65, 0.45, None, None, [[2.8, 1.1, 6.2]]))
        >>> bool(np.isclose(sol.bic, sol.m * np.log(sol.ssr / sol.m) + 5 * np.log(sol.m)))
        True
        """
        kept = self.model.n - len(self.undetermined)
        return self.m * np.log(max(self.ssr, 1e-300) / self.m) + kept * np.log(self.m)


def _least_squares(model: Model, data, mask, P, max_nfev, bounds=None, tol=1e-8):
    def fun(Q):
        return (model.sensor(Q) - data)[mask]

    def jac(Q):
        return model.jacobian(Q, mask)

    bounds = model.bounds if bounds is None else bounds
    P = np.clip(P, *bounds)
    kw = {"tr_solver": "lsmr"} if model.F > 1 else {}
    with np.errstate(all="ignore"):
        return least_squares(fun, P, jac=jac, bounds=bounds, method="dogbox", x_scale="jac",
                             max_nfev=max_nfev, ftol=tol, xtol=tol, **kw)


def _undetermined(J, names) -> list[int]:
    """Indices of the columns to fix (module docstring)."""
    JtJ = J.T @ J
    JtJ = JtJ.toarray() if hasattr(JtJ, "toarray") else np.asarray(JtJ)
    keep = list(range(len(names)))
    fixed = []
    while keep:
        A = JtJ[np.ix_(keep, keep)]
        d = np.sqrt(np.diag(A))
        zero = [keep[i] for i in np.flatnonzero(d == 0)]
        if zero:
            fixed += zero
            keep = [k for k in keep if k not in zero]
            continue
        vals, vecs = np.linalg.eigh(A / np.outer(d, d))
        if vals[0] >= RANK_TOL ** 2 * vals[-1]:
            break
        v = np.abs(vecs[:, 0])
        base = [names[k].split("[")[0] for k in keep]  # "bias_x[rec 1]": another recording's bias_x
        cand = [i for i in range(len(keep)) if base[i] in _FIXABLE or base[i].startswith("omega0")]
        i = max(cand, key=lambda i: (v[i], -_FIXABLE.index(base[i]) if base[i] in _FIXABLE else -99))
        fixed.append(keep.pop(i))
    return fixed


def solve(model: Model, data: np.ndarray, mask: np.ndarray, P0: np.ndarray, *, max_nfev: int = 100, scale_uncertainty: float = 0.0,
          covariance: bool = True, pin: tuple | None = None) -> Solution:
    """Solve from ``P0`` and characterise the optimum (module docstring); ``covariance=False``
    skips that (NaN covariance), for intermediate solves; ``pin = (index, value)`` holds one
    coordinate at a bound of the box.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.model import Model
    >>> from tumble.analysis.fit.solve import solve
    >>> from tumble.analysis.fit.triangle import square
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t) + np.random.default_rng(0).normal(0.0, 0.01, (1, 201, 3))
    >>> model = Model([t], rotation=False, bias=False)
    >>> sol = solve(model, w, np.ones(w.shape, bool), model.pack(0.65, 0.45, None, None, [[2.8, 1.1, 6.2]]))
    >>> truth = np.array([*square(0.5, 0.8), 3.0, 1.0, 6.0])   # I1/I3 = 0.5, I2/I3 = 0.8 as (s, g)
    >>> bool(np.all(np.abs(sol.P - truth) < 3 * np.sqrt(np.diag(sol.cov))))   # within 3 sigma
    True
    >>> round(float(np.sqrt(np.mean(sol.residuals**2))), 3)   # the noise left
    0.01
    """
    bounds = None
    if pin is not None:
        lo, hi = (b.copy() for b in model.bounds)
        i, v = pin
        lo[i], hi[i] = (v, v + 1e-12) if v <= lo[i] else (v - 1e-12, v)
        bounds = (lo, hi)
    # intermediate solves (no covariance wanted) stop at a relative change of 1e-5
    res = _least_squares(model, data, mask, P0, max_nfev, bounds, 1e-8 if covariance else 1e-5)
    P = res.x
    wp = model.principal(P)
    omega_model = model.sensor(P, wp)
    r = (omega_model - data)[mask]
    if not covariance:
        nan = np.full((model.n, model.n), np.nan)
        return Solution(model, P, nan, nan, r, omega_model, (), int(res.nfev), 0.0, float(r @ r), int(r.size))
    J = model.jacobian(P, mask, wp)
    fixed = _undetermined(J, model.names)
    keep = [k for k in range(model.n) if k not in fixed]
    sample_index = np.cumsum(np.r_[0, model.lengths])
    Jk = J[:, keep]
    # the residuals as (samples, 3), flights one after another (a left-out axis counts as 0)
    full = np.zeros(data.shape)
    full[mask] = r
    per_sample = np.concatenate([full[j, :n] for j, n in enumerate(model.lengths)])
    cov_k, S = effective_covariance(Jk, r, per_sample, sample_index)
    cov_stat = np.full((model.n, model.n), np.nan)
    cov_stat[np.ix_(keep, keep)] = cov_k
    B = np.full((model.n, 3), np.nan)
    B[keep] = scale_effect(Jk, data, mask, scale_uncertainty) if scale_uncertainty else 0.0
    cov = np.full((model.n, model.n), np.nan)
    cov[np.ix_(keep, keep)] = cov_k + B[keep] @ B[keep].T
    return Solution(model, P, cov, cov_stat, r, omega_model, tuple(model.names[k] for k in fixed), int(res.nfev), S,
                    float(r @ r), int(r.size), scale_effect=B)


def check_drag(drag: str) -> None:
    """Raise a ValueError unless ``drag`` names a drag model or ``"auto"``.

    Examples
    --------
    >>> from tumble.analysis.fit.solve import check_drag
    >>> check_drag("quadratic")
    >>> check_drag("cubic")
    Traceback (most recent call last):
    ...
    ValueError: drag = 'cubic' must be 'auto', 'none', 'linear' or 'quadratic'
    """
    if drag not in ("auto", *DRAG_MODELS):
        raise ValueError(f"drag = {drag!r} must be 'auto', 'none', 'linear' or 'quadratic'")


def _with_drag(model: Model, drag: str) -> Model:
    taus = [model.tau[j, :n] for j, n in enumerate(model.lengths)]
    return Model(taus, model.rotation, model.bias, drag, model.speeds)


def _convert(P, src: Model, dst: Model, drag) -> np.ndarray:
    rv = P[src.index["rotvec_x"]:src.index["rotvec_x"] + 3] if src.rotation else np.zeros(3)
    return dst.pack(P[0], P[1], rv, src.bias_vector(P), src.omega0(P), drag)


def solve_drag(model: Model, data: np.ndarray, mask: np.ndarray, P0: np.ndarray, drag: str, *,
               drag0: ArrayLike | None = None, max_nfev: int = 100,
               scale_uncertainty: float = 0.0, covariance: bool = True) -> Solution:
    """:func:`solve` with the drag model named, or chosen by the BIC with ``drag="auto"``.

    ``model`` is the drag-free layout and ``P0`` its parameters; ``drag0`` (3 numbers, for the
    quadratic model) starts the drag where an earlier fit left it: a strong drag left out of a
    long flight's start sends the solve to another basin.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.model import Model
    >>> from tumble.analysis.fit.solve import solve_drag
    >>> from tumble.analysis.fit.triangle import square
    >>> from tumble.dynamics.models.drag import drag_omega
    >>> t = np.linspace(0.0, 1.0, 101)   # a flight slowed by a quadratic drag, b_i / I3 = 0.02, 0.03, 0.04
    >>> w = drag_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t, quadratic=[[0.02, 0.03, 0.04]])
    >>> w = w + np.random.default_rng(0).normal(0.0, 0.002, w.shape)
    >>> model = Model([t], rotation=False, bias=False, speeds=[7.0])
    >>> sol = solve_drag(model, w, np.ones(w.shape, bool), model.pack(*square(0.5, 0.8), None, None, w[:, 0]), "auto")
    >>> sol.model.drag, sol.model.drag_vector(sol.P).round(3).tolist()   # the BIC picks the drag, and finds it
    ('quadratic', [0.02, 0.03, 0.04])
    """
    check_drag(drag)
    kw = {"max_nfev": max_nfev, "scale_uncertainty": scale_uncertainty, "covariance": covariance}
    zero = (0.0, 0.0, 0.0)
    best = free = None
    if drag not in ("auto", "none") and drag0 is None and covariance:
        # a named law's final fit starts from the drag-free optimum too, as "auto"'s does: from the
        # given start alone the linear law settled in another basin on a racquet's plate drag (SSR
        # 36 against 4.3, tests/test_fit_drag_law.py). Not for the finder's seed fits (covariance
        # False), which are grown and fitted again from where they end
        free = solve(model, data, mask, P0, max_nfev=max_nfev, scale_uncertainty=scale_uncertainty, covariance=False)
    for name in (AUTO_DRAG if drag == "auto" else (drag,)):
        mk = model if name == model.drag else _with_drag(model, name)
        start = drag0 if (drag0 is not None and name == "quadratic") else zero
        P = P0 if mk is model else _convert(P0, model, mk, start)
        trial = solve(mk, data, mask, P, **kw)
        other = best if best is not None else free
        if name != "none" and other is not None and drag0 is None:
            # from the drag-free optimum too (on the drag's bound), when no better start was given
            again = solve(mk, data, mask, _convert(other.P, other.model, mk, zero), **kw)
            trial = again if again.ssr < trial.ssr else trial
        if best is None or trial.bic < best.bic:
            best = trial
    if not covariance:
        return best
    return with_drag_law_error(snap_to_edges(best, data, mask, **kw), data, mask, max_nfev=max_nfev)


#: The other drag law, whose fit measures the model error of each (:func:`with_drag_law_error`).
_OTHER_LAW = {"linear": "quadratic", "quadratic": "linear"}


def with_drag_law_error(sol: Solution, data: np.ndarray, mask: np.ndarray, *, max_nfev: int = 100) -> Solution:
    """``sol`` with its drag law's model error added to the covariance (module docstring).

    The model is solved again with the other per-axis law, from ``sol``'s parameters (the drag
    carried over at the flight's mean rate about each axis, ``a_i = b_i <|w_i|>``); the shift
    ``d`` of every parameter but the drag's adds ``d d^T`` to ``cov`` (not to ``cov_stat``). A
    coordinate held on an edge of the triangle is held there again. A solution without drag is
    returned as it is, and so is one whose other law fails to solve.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.model import Model
    >>> from tumble.analysis.fit.solve import solve, with_drag_law_error
    >>> from tumble.analysis.fit.synthetic import TOSS_BODIES, plate_drag_torque
    >>> from scipy.integrate import solve_ivp
    >>> from tumble.dynamics.euler import euler_rhs
    >>> body = TOSS_BODIES["racquet"]; I = np.array(body.moments)
    >>> def rate(t, w):   # Euler's equations with the racquet's plate drag, a drag neither law describes
    ...     return euler_rhs(w, I, plate_drag_torque(body, w))
    >>> t = np.linspace(0.0, 1.0, 401)
    >>> w = solve_ivp(rate, (0.0, 1.0), [0.3, 12.0, 0.4], t_eval=t, method="DOP853", rtol=1e-10, atol=1e-10).y.T
    >>> w = w + np.random.default_rng(1).normal(0.0, 0.005, w.shape)
    >>> model = Model([t], rotation=False, bias=False, drag="quadratic", speeds=[12.0])
    >>> data, mask = w[None], np.ones((1, 401, 3), bool)
    >>> sol = solve(model, data, mask, model.pack(0.07, 0.94, None, None, [w[0]]))
    >>> both = with_drag_law_error(sol, data, mask)
    >>> from tumble.analysis.fit.result import ratio_summary
    >>> std, wider = ratio_summary(sol)[1], ratio_summary(both)[1]   # the ratios' standard uncertainties
    >>> bool(np.all(wider > 1.1 * std)), bool(np.array_equal(both.cov_stat, sol.cov_stat))   # the statistical part kept
    (True, True)
    """
    law = _OTHER_LAW.get(sol.model.drag)
    if law is None:
        return sol
    model = sol.model
    other = _with_drag(model, law)
    rates = np.where(mask & model.valid[..., None], np.abs(model.principal(sol.P)), np.nan)
    mean = np.nan_to_num(np.nanmean(rates.reshape(-1, 3), axis=0), nan=1.0) + 1e-9
    drag = model.drag_vector(sol.P)
    drag = drag * mean if law == "linear" else drag / mean
    P0 = _convert(sol.P, model, other, drag)
    pin = next(((i, b) for i, b in _EDGE_FACES if abs(sol.P[i] - b) <= 1e-12), None)
    try:
        alt = solve(other, data, mask, P0, max_nfev=max_nfev, covariance=False, pin=pin)
    except (ValueError, np.linalg.LinAlgError):  # the other law does not solve: no measure of its error
        return sol
    d = alt.P - sol.P
    d[[model.names.index(n) for n in DRAG_MODELS[model.drag]]] = 0.0
    return replace(sol, cov=sol.cov + np.outer(d, d), cov_drag_law=np.outer(d, d))


def without_drag_law_error(sol: Solution) -> Solution:
    """``sol`` without the drag law's model error in its covariance (:func:`with_drag_law_error`):
    what a flight's ratios are pooled and compared with (module docstring).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.analysis.fit.solve import without_drag_law_error
    >>> from tumble.dynamics.models.drag import drag_omega
    >>> t = np.linspace(0.0, 1.0, 201)   # a flight slowed by a quadratic drag
    >>> w = drag_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t, quadratic=[[0.02, 0.03, 0.04]])[0]
    >>> w = w + np.random.default_rng(0).normal(0.0, 0.002, w.shape)
    >>> sol = fit_solution(t, w, np.ones(w.shape, bool), rotation=False, bias=False, drag="quadratic")
    >>> bare = without_drag_law_error(sol)
    >>> bool(np.allclose(bare.cov + sol.cov_drag_law, sol.cov)), bare.cov_drag_law is None
    (True, True)
    """
    if sol.cov_drag_law is None:
        return sol
    return replace(sol, cov=sol.cov - sol.cov_drag_law, cov_drag_law=None)


#: The box faces that are edges of the triangle: (coordinate index, bound).
_EDGE_FACES = ((1, 1.0), (0, 1.0))


def snap_to_edges(sol: Solution, data: np.ndarray, mask: np.ndarray, **kw: Any) -> Solution:
    """Move an optimum near an edge of the triangle onto it when the data allow.

    For each edge whose coordinate lies within one standard uncertainty of its bound (or
    is undetermined), the fit is repeated with the coordinate held on the edge; the edge wins
    when its Bayesian information criterion (one parameter fewer) is not larger. A body that
    is symmetric or planar within the data's resolution is so reported, and what the edge
    leaves undetermined (a symmetric body's rotation about its axis) is named instead of
    spoiling the other parameters' uncertainties."""
    best = sol
    for i, bound in _EDGE_FACES:
        sd = np.sqrt(sol.cov_stat[i, i]) if np.isfinite(sol.cov_stat[i, i]) else np.inf
        gap = abs(sol.P[i] - bound)
        if gap == 0.0 or gap > sd:
            continue
        P0 = sol.P.copy()
        P0[i] = bound
        trial = solve(sol.model, data, mask, P0, pin=(i, bound), **kw)
        if trial.bic - np.log(trial.m) <= best.bic:
            best = trial
    return best
