"""What a fit reports: :class:`RotationFit`, and its making from a solved model.

The ratios' covariance is carried from the fit's square coordinates to ``(I1/I3, I2/I3)`` by
the chain rule (:func:`tumble.analysis.fit.triangle.ratio_jacobian`); the 95 % intervals are those of
:func:`ratio_summary`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.spatial.transform import Rotation

from .. import _display
from .adequacy import Adequacy, judge, rigid_body_check
from .solve import Solution, without_drag_law_error
from .triangle import EDGES, S_MIN, edge_of, ratio_jacobian, ratios
from .uncertainty import effective_dof, interval, noise_floor

__all__ = ["DETERMINED_STD", "RotationFit", "determination", "public_covariance", "ratio_summary", "rotation_fit", "solution_adequacy"]

#: Largest standard uncertainties reported for I1/I3 and I2/I3: half their ranges in the triangle.
_STD_CAP = (0.5, 0.25)
#: A ratio whose standard uncertainty exceeds this is not determined by the data (dimensionless):
#: a fifth of the range of I1/I3, nothing a user can take away from a toss.
DETERMINED_STD = 0.1


@dataclass(frozen=True)
class RotationFit:
    """A torque-free (or uniformly damped) motion fitted to angular-velocity samples.

    Attributes
    ----------
    ratios : ndarray, shape (2,)
        ``I1/I3``, ``I2/I3`` (dimensionless, ascending, ``I3`` the largest moment).
    ratios_std : ndarray, shape (2,)
        Their standard uncertainties (:mod:`~tumble.analysis.fit.uncertainty`: the residuals'
        autocorrelation and the gyroscope's scale factor counted), at most half their range in
        the triangle.
    ratios_interval : ndarray, shape (2, 2)
        95 % intervals ``[[lo, hi], [lo, hi]]``, inside the triangle; one-sided on an edge.
    edge : str or None
        The triangle's edge the optimum lies on (e.g. ``"planar (I1 + I2 = I3)"``), or None.
    undetermined : tuple of str
        Parameters the data do not determine (left at their values, uncertainty NaN), e.g.
        ``rotvec_z`` for the sensor's rotation about a symmetric body's axis.
    omega0 : ndarray, shape (3,)
        Angular velocity at ``t0``, principal frame, rad/s.
    omega0_std : ndarray, shape (3,)
        Its standard uncertainties, rad/s.
    sensor_rotation : scipy Rotation
        Sensor axes to principal axes: ``omega_principal = sensor_rotation.apply(omega_sensor)``.
    rotvec_std : ndarray, shape (3,) or None
        Standard uncertainties of its rotation vector, rad (None when fixed to the identity).
    bias : ndarray, shape (3,)
        The sensor's constant bias, sensor axes, rad/s (zeros when not fitted).
    bias_std : ndarray, shape (3,) or None
        Its standard uncertainties (None when not fitted).
    drag : str
        The drag model fitted: ``"none"``, ``"linear"`` or ``"quadratic"``.
    drag_coefficients, drag_coefficients_std : ndarray, shape (3,)
        The drag about each principal axis divided by ``I3`` (:mod:`tumble.dynamics.models.drag`):
        ``a_i / I3`` in 1/s (linear) or ``b_i / I3`` in 1/rad (quadratic); zeros and NaN when
        no drag is fitted. Times ``I3`` (kg m^2) they are N m s or N m s^2.
    residual_rms : float
        Root mean square of the residuals over the samples and axes fitted, rad/s.
    noise : float
        The white noise per axis, rad/s: from the second differences of the residuals (the fitted
        motion removed first: at 100 Hz a fast spin's own second differences would swamp the
        noise's), robust (median absolute deviation).
    samples : int
        Number of time samples.
    saturated : int
        Sample axes left out because they lie at the sensor's rail.
    t : ndarray, shape (n,)
        The sample times, s.
    omega_model : ndarray, shape (n, 3)
        The fitted model at the sample times, sensor axes, bias included, rad/s.
    covariance : ndarray
        Covariance of the parameters in the order of :attr:`parameter_names`.
    parameter_names : tuple of str
        ``I1/I3``, ``I2/I3``, ``omega0_1..3``, then ``rotvec_x..z``, ``bias_x..z`` and the drag
        coefficient when fitted.
    iterations : int
        Function evaluations of the final least-squares run.
    autocorrelation_time : float
        The residuals' integrated autocorrelation time, samples: the textbook covariance is
        multiplied by it (:func:`~tumble.analysis.fit.uncertainty.autocorrelation_time`).
    adequate : bool
        Whether the model describes the data (:mod:`~tumble.analysis.fit.adequacy`): when False
        the ratios are not to be trusted, whatever their uncertainties say.
    adequacy : str
        What the residuals show against the noise, and for an inadequate fit what to check.
    misfit : float
        The model's error beyond the noise as a fraction of the rates (per axis, RMS).
    caveat : str
        Empty, or why the ratios of an adequate fit are not determined by the data
        (:func:`determination`: a stable-axis toss, or too little of the tumble recorded).
    t0 : float or None
        The time at which ``omega0`` holds, s; None: ``t[0]``. The flight search anchors a
        flight's ``omega0`` where it first fitted it, often after the flight's first sample.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)   # I1/I3 = 0.5, I2/I3 = 0.8; white noise of 0.01 rad/s
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
    >>> keep = np.ones(w.shape, bool)
    >>> sol = fit_solution(t, w, keep, rotation=False, bias=False, drag="none")
    >>> from tumble.analysis.fit.result import rotation_fit
    >>> fit = rotation_fit(sol, t, w, keep)
    >>> [bool(lo <= truth <= hi) for truth, (lo, hi) in zip([0.5, 0.8], fit.ratios_interval)]   # the 95 % intervals hold the truth
    [True, True]
    >>> fit.adequate, fit.edge, round(fit.noise, 2), fit.parameter_names
    (True, None, 0.01, ('I1/I3', 'I2/I3', 'omega0_1', 'omega0_2', 'omega0_3'))
    """

    ratios: np.ndarray
    ratios_std: np.ndarray
    omega0: np.ndarray
    omega0_std: np.ndarray
    sensor_rotation: Rotation
    rotvec_std: np.ndarray | None
    bias: np.ndarray
    bias_std: np.ndarray | None
    residual_rms: float
    samples: int
    t: np.ndarray = field(repr=False)
    omega_model: np.ndarray = field(repr=False)
    covariance: np.ndarray = field(repr=False)
    parameter_names: tuple = ()
    iterations: int = 0
    ratios_interval: np.ndarray = field(default=None, repr=False)
    edge: str | None = None
    undetermined: tuple = ()
    drag: str = "none"
    drag_coefficients: np.ndarray = field(default_factory=lambda: np.zeros(3))
    drag_coefficients_std: np.ndarray = field(default_factory=lambda: np.full(3, np.nan))
    noise: float = 0.0
    saturated: int = 0
    autocorrelation_time: float = 1.0
    adequate: bool = True
    adequacy: str = ""
    misfit: float = 0.0
    caveat: str = ""
    t0: float | None = None

    def __repr__(self) -> str:
        return _display.rotation_repr(self)

    def _repr_html_(self) -> str:
        return _display.rotation_html(self)

    @property
    def moments(self) -> np.ndarray:
        """Principal moments scaled so that ``I3 = 1`` (dimensionless), ascending.

        Examples
        --------
        >>> import numpy as np
        >>> from tumble.analysis.fit.single import fit_solution
        >>> from tumble.dynamics.methods.exact_omega import free_omega
        >>> t = np.linspace(0.0, 2.0, 201)   # I1/I3 = 0.5, I2/I3 = 0.8; white noise of 0.01 rad/s
        >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
        >>> keep = np.ones(w.shape, bool)
        >>> sol = fit_solution(t, w, keep, rotation=False, bias=False, drag="none")
        >>> from tumble.analysis.fit.result import rotation_fit
        >>> fit = rotation_fit(sol, t, w, keep)
        >>> fit.moments.round(2).tolist()   # I3 = 1
        [0.5, 0.8, 1.0]
        """
        return np.array([self.ratios[0], self.ratios[1], 1.0])

    def summary(self) -> dict:
        """The fitted values and their uncertainties as plain JSON-ready numbers (SI units);
        NaN (undetermined) is written as None.

        Examples
        --------
        >>> import json
        >>> import numpy as np
        >>> from tumble.analysis.fit.single import fit_solution
        >>> from tumble.dynamics.methods.exact_omega import free_omega
        >>> t = np.linspace(0.0, 2.0, 201)   # I1/I3 = 0.5, I2/I3 = 0.8; white noise of 0.01 rad/s
        >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
        >>> keep = np.ones(w.shape, bool)
        >>> sol = fit_solution(t, w, keep, rotation=False, bias=False, drag="none")
        >>> from tumble.analysis.fit.result import rotation_fit
        >>> fit = rotation_fit(sol, t, w, keep)
        >>> summary = fit.summary()
        >>> summary["I1_over_I3"] == float(fit.ratios[0]), summary["bias_std"], summary["units"]["omega0"]   # bias not fitted: None
        (True, None, 'rad/s')
        >>> json.loads(json.dumps(summary)) == summary   # plain JSON numbers
        True
        """
        def num(v):
            v = float(v)
            return v if np.isfinite(v) else None

        def listed(x):
            return None if x is None else [num(v) for v in np.ravel(x)]

        sx, sy = self.ratios_std
        corr = self.covariance[0, 1] / (sx * sy) if sx > 0 and sy > 0 else float("nan")
        return {
            "I1_over_I3": float(self.ratios[0]),
            "I2_over_I3": float(self.ratios[1]),
            "I1_over_I3_std": num(sx),
            "I2_over_I3_std": num(sy),
            "I1_over_I3_interval": listed(self.ratios_interval[0]),
            "I2_over_I3_interval": listed(self.ratios_interval[1]),
            "ratios_correlation": num(corr),
            "edge": self.edge,
            "undetermined": list(self.undetermined),
            "omega0": listed(self.omega0),
            "omega0_std": listed(self.omega0_std),
            "t0": float(self.t[0] if self.t0 is None else self.t0),
            "sensor_rotation_rotvec": listed(self.sensor_rotation.as_rotvec()),
            "sensor_rotation_rotvec_std": listed(self.rotvec_std),
            "sensor_rotation_matrix": [listed(row) for row in self.sensor_rotation.as_matrix()],
            "bias": listed(self.bias),
            "bias_std": listed(self.bias_std),
            "drag": self.drag,
            "drag_coefficients": listed(self.drag_coefficients),
            "drag_coefficients_std": listed(self.drag_coefficients_std),
            "residual_rms": float(self.residual_rms),
            "noise": float(self.noise),
            "samples": int(self.samples),
            "saturated": int(self.saturated),
            "parameters": list(self.parameter_names),
            "adequate": bool(self.adequate),
            "adequacy": self.adequacy,
            "misfit": num(self.misfit),
            "caveat": self.caveat or None,
            "covariance_method": ("(J^T J)^-1 s^2 times the residuals' integrated autocorrelation time "
                                  f"({self.autocorrelation_time:.1f} samples; Geyer's initial positive sequence), "
                                  "plus the gyroscope's scale-factor tolerance (GUM 5.1)"
                                  + ("" if self.drag == "none" else ", plus the drag law's model error (the parameters' "
                                     "shift when the other drag law is fitted, as one standard uncertainty)")),
            "units": {"ratios": "dimensionless", "omega0": "rad/s", "rotvec": "rad", "bias": "rad/s",
                      "residual_rms": "rad/s", "noise": "rad/s", "t0": "s", "ratios_correlation": "dimensionless",
                      "misfit": "dimensionless",
                      "drag_coefficients": {"none": "-", "linear": "1/s (a_i / I3)",
                                            "quadratic": "1/rad (b_i / I3)"}[self.drag]},
        }


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
    >>> from tumble.analysis.fit.result import public_covariance
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
    >>> from tumble.analysis.fit.result import public_covariance, ratio_summary
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


def rotation_fit(sol: Solution, t: np.ndarray, omega: np.ndarray, keep: np.ndarray, t0: float | None = None) -> RotationFit:
    """The public result of a solved flight, whose ``omega0`` holds at ``t0`` (s; default ``t[0]``:
    the flight search anchors it where the flight was first fitted, see ``fit_solution``).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)   # I1/I3 = 0.5, I2/I3 = 0.8; white noise of 0.01 rad/s
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
    >>> keep = np.ones(w.shape, bool)
    >>> sol = fit_solution(t, w, keep, rotation=False, bias=False, drag="none")
    >>> from tumble.analysis.fit.result import rotation_fit
    >>> fit = rotation_fit(sol, t, w, keep)
    >>> fit.ratios.round(2).tolist(), fit.samples, fit.omega_model.shape, fit.drag
    ([0.5, 0.8], 201, (201, 3), 'none')
    >>> bool(np.allclose(fit.omega0, [3.0, 1.0, 6.0], atol=3 * fit.omega0_std))
    True
    """
    model = sol.model
    names, values, cov = public_covariance(sol)
    rat, rstd, rint, edge = ratio_summary(sol)
    std = np.sqrt(np.abs(np.diag(cov)))
    std[np.isnan(np.diag(cov))] = np.nan
    std[:2] = rstd
    pos = {n: i for i, n in enumerate(names)}

    def block(prefix):
        ii = [pos[f"{prefix}_{c}"] for c in "xyz"]
        return values[ii], std[ii]

    R, rotvec_std = Rotation.identity(), None
    if model.rotation:
        rv, rotvec_std = block("rotvec")
        R = Rotation.from_rotvec(rv)
    b, bias_std = (block("bias") if model.bias else (np.zeros(3), None))
    if model.drag != "none":
        ii = [pos[f"drag_{k}"] for k in (1, 2, 3)]
        drag_c, drag_s = values[ii], std[ii]
    else:
        drag_c, drag_s = np.zeros(3), np.full(3, np.nan)
    r = sol.residuals
    rms = float(np.sqrt(np.mean(r ** 2)))
    noise = noise_floor((omega - sol.omega_model[0, :len(omega)])[np.all(keep, axis=1)])
    verdict = solution_adequacy(sol, omega[None], keep[None])
    return RotationFit(
        ratios=rat, ratios_std=rstd, omega0=values[2:5].copy(), omega0_std=std[2:5].copy(), sensor_rotation=R,
        rotvec_std=rotvec_std, bias=np.array(b, float), bias_std=bias_std,
        residual_rms=rms, samples=len(t), t=t.copy(), omega_model=sol.omega_model[0],
        covariance=cov, parameter_names=names, iterations=sol.nfev, ratios_interval=rint, edge=edge,
        undetermined=tuple(_public_name(n) for n in sol.undetermined), drag=model.drag,
        drag_coefficients=np.array(drag_c, float), drag_coefficients_std=np.array(drag_s, float),
        noise=noise, saturated=int(np.count_nonzero(~keep)), autocorrelation_time=float(sol.autocorrelation_time),
        adequate=verdict.adequate, adequacy=verdict.reason, misfit=verdict.misfit,
        caveat=determination(sol, rstd) if verdict.adequate else "", t0=None if t0 is None else float(t0))


def _public_name(name: str) -> str:
    return {"s": "(I1 + I3 - I2)/I3", "g": "I2/I3 (across the triangle)"}.get(name, name)


def solution_adequacy(sol: Solution, data: np.ndarray, mask: np.ndarray) -> Adequacy:
    """:func:`~tumble.analysis.fit.adequacy.judge` on a solution of one or many flights.

    ``data`` and ``mask`` are the samples and the kept axes as the solution's model lays them
    out, shape ``(F, T, 3)``; the noise is each flight's (:func:`noise_floor` of its residuals at
    the samples with all axes kept), combined over the flights weighted by their lengths.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)   # I1/I3 = 0.5, I2/I3 = 0.8; white noise of 0.01 rad/s
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
    >>> keep = np.ones(w.shape, bool)
    >>> sol = fit_solution(t, w, keep, rotation=False, bias=False, drag="none")
    >>> from tumble.analysis.fit.result import solution_adequacy
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
    if not verdict.adequate:
        return verdict
    m, P = sol.model, sol.P
    moments = m.moments(P)
    for j, n in enumerate(m.lengths):
        n, group = int(n), int(m.groups[j])
        R, b = m.rotation_matrix(P, group), m.bias_vector(P, group)
        rows = np.all(mask[j, :n], axis=1)
        why = rigid_body_check(m.tau[j, :n][rows], (data[j, :n][rows] - b) @ R.T, moments)
        if why:
            return Adequacy(False, verdict.misfit, why)
    return verdict


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
    >>> from tumble.analysis.fit.result import determination, ratio_summary
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
