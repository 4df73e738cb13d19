"""What a fit reports: :class:`RotationFit`, and its making from a solved model.

The ratios, their covariance and 95 % intervals and the verdicts on the fit are computed in
:mod:`tumble.analysis.fit.summary` (re-exported here): the covariance carried from the fit's
square coordinates to ``(I1/I3, I2/I3)`` by the chain rule
(:func:`tumble.analysis.fit.triangle.ratio_jacobian`), the intervals of :func:`ratio_summary`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.spatial.transform import Rotation

from .. import _display
from .solve import Solution
from .summary import DETERMINED_STD, determination, public_covariance, ratio_summary, solution_adequacy
from .uncertainty import noise_floor

__all__ = ["DETERMINED_STD", "RotationFit", "determination", "public_covariance", "ratio_summary", "rotation_fit", "solution_adequacy"]


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
        Number of time samples (of every flight used, for a recording's pooled fit).
    saturated : int
        Sample axes left out because they lie at the sensor's rail (of every flight used, for a
        recording's pooled fit).
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
