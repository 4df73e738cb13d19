"""Short plain reprs and Jupyter's HTML tables of the analysis's results: the fits of a
recording (:class:`~tumble.analysis.fit.RotationFit`, :class:`~tumble.analysis.fit.RecordingFit`,
:class:`~tumble.analysis.fit.Toss`), the tensor's (:class:`~tumble.analysis.tensor.TensorFit`,
:class:`~tumble.analysis.tensor.ThrowFit`, :class:`~tumble.analysis.tensor.MassEstimate`), a
device's calibration (:class:`~tumble.analysis.tensor.calibrate.Calibration`), the motions
of two periods (:class:`~tumble.analysis.period_inversion.PeriodFamily`) and the predictions
of a spin's stability (:class:`~tumble.analysis.stability.SpinPrediction`) and of the
gravity gradient's (:class:`~tumble.analysis.gravity_stability.StabilityClass`).

Each repr says what the result is, its size and its headline numbers on one line (never its
arrays); each HTML table says more. The results are read by their attributes (duck typing): the
modules that define them import this one, and the import graph has no circles.
"""

from __future__ import annotations

from collections import Counter
from typing import Any

import numpy as np

from .._html import fmt, html_table, plural, result_html, result_repr, short_name, vec, with_std

__all__ = ["calibration_html", "calibration_repr", "estimate_html", "estimate_repr", "family_html", "family_repr", "flight_repr",
           "model_repr", "recording_html", "recording_repr", "regions_html", "regions_repr", "rotation_html", "rotation_repr",
           "spin_html", "spin_repr", "synthetic_repr", "tensor_html", "tensor_repr", "throw_repr", "toss_repr"]


def _ratios(fit: Any) -> list[str]:
    return [f"I1/I3 = {with_std(fit.ratios[0], fit.ratios_std[0])}", f"I2/I3 = {with_std(fit.ratios[1], fit.ratios_std[1])}"]


def _verdict(fit: Any) -> str:
    return ("adequate" if fit.adequate else "NOT adequate") + (f", on the edge {fit.edge}" if fit.edge else "")


def rotation_repr(fit: Any) -> str:
    """``RotationFit(201 samples, I1/I3 = 0.5 +- 0.0013, ..., residual 0.0099 rad/s, adequate)``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.analysis.fit.result import rotation_fit
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
    >>> keep = np.ones(w.shape, bool)
    >>> fit = rotation_fit(fit_solution(t, w, keep, rotation=False, bias=False, drag="none"), t, w, keep)
    >>> text = repr(fit)
    >>> text.startswith("RotationFit(201 samples, I1/I3 = 0.5"), text.endswith("rad/s, adequate)")
    (True, True)
    """
    parts = [plural(int(fit.samples), "sample"), *_ratios(fit), f"residual {fmt(fit.residual_rms, 3)} rad/s",
             _verdict(fit)]
    if fit.drag != "none":
        parts.append(f"{fit.drag} drag")
    if fit.caveat:
        parts.append("ratios not determined (see .caveat)")
    return result_repr("RotationFit", parts)


def _rotation_rows(fit: Any) -> list[tuple[str, str]]:
    rows = [("samples", f"{fit.samples} ({fit.saturated} sample axes at the rail left out)" if fit.saturated
             else str(fit.samples))]
    for j, name in enumerate(("I1/I3", "I2/I3")):
        interval = "" if fit.ratios_interval is None else f", 95 % interval {vec(fit.ratios_interval[j])}"
        rows.append((name, with_std(fit.ratios[j], fit.ratios_std[j]) + interval))
    rows += [("omega0, principal frame", f"{vec(fit.omega0)} rad/s"),
             ("residual RMS / noise", f"{fmt(fit.residual_rms)} / {fmt(fit.noise)} rad/s"),
             ("adequate", f"{fit.adequate}: {fit.adequacy}" if fit.adequacy else str(fit.adequate))]
    if fit.edge:
        rows.append(("on the triangle's edge", fit.edge))
    if fit.drag != "none":
        rows.append((f"{fit.drag} drag / I3", vec(fit.drag_coefficients)))
    if fit.bias_std is not None:
        rows.append(("gyroscope bias, sensor axes", f"{vec(fit.bias)} rad/s"))
    if fit.undetermined:
        rows.append(("not determined by the data", ", ".join(fit.undetermined)))
    if fit.caveat:
        rows.append(("caveat", fit.caveat))
    return rows


def rotation_html(fit: Any) -> str:
    """A fit's values, uncertainties and verdict as an HTML table (Jupyter's ``_repr_html_``).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.fit.single import fit_solution
    >>> from tumble.analysis.fit.result import rotation_fit
    >>> from tumble.dynamics.methods.exact_omega import free_omega
    >>> t = np.linspace(0.0, 2.0, 201)
    >>> w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0]
    >>> keep = np.ones(w.shape, bool)
    >>> page = rotation_fit(fit_solution(t, w, keep, rotation=False, bias=False, drag="none"), t, w, keep)._repr_html_()
    >>> page.startswith("<div><table"), "95 % interval" in page
    (True, True)
    """
    return result_html("RotationFit", _rotation_rows(fit))


def toss_repr(toss: Any) -> str:
    """``Toss(1..1.8 s, 81 samples, skipped: too short)``.

    Examples
    --------
    >>> from tumble.analysis.fit.tosses import Toss
    >>> Toss(start=1.0, end=1.8, samples=81, status="skipped", reason="too short")
    Toss(1..1.8 s, 81 samples, skipped: too short)
    """
    parts = [f"{fmt(toss.start)}..{fmt(toss.end)} s", plural(int(toss.samples), "sample")]
    if toss.fit is not None and toss.status == "ok":
        parts += _ratios(toss.fit)
    parts.append(f"{toss.status}: {toss.reason}" if toss.reason else toss.status)
    return result_repr("Toss", parts)


def flights_used(tosses: Any, used: int) -> str:
    """``3 of 4 flights (1 skipped: too short)``: each skipped flight's reason by its head (before a
    bracket, a colon or a semicolon), counted where there are several (:meth:`RecordingFit.flights_used`)."""
    heads = [str(t.reason).split(" (")[0].split(";")[0].split(":")[0] for t in tosses if t.status != "ok"]
    kinds = list(dict.fromkeys(heads))
    why = kinds[0] if len(kinds) == 1 else ", ".join(f"{heads.count(h)} {h}" for h in kinds)
    return f"{used} of {plural(len(tosses), 'flight')}" + (f" ({len(heads)} skipped: {why})" if heads else "")


def recording_repr(fit: Any) -> str:
    """``RecordingFit(2 of 2 flights, I1/I3 = ..., I2/I3 = ..., chi2/dof 0.5, residual 0.01 rad/s)``.

    Examples
    --------
    >>> from tumble.analysis.fit.recording import fit_recording
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
    >>> repr(fit_recording(rec.t, rec.omega, events=rec.events)).startswith("RecordingFit(2 of 2 flights, I1/I3 = ")
    True
    """
    p = fit.pooled
    parts = [flights_used(fit.tosses, fit.tosses_used), *_ratios(p), f"chi2/dof {fmt(fit.chi2_dof, 2)}",
             f"residual {fmt(p.residual_rms, 3)} rad/s", _verdict(p)]
    return result_repr("RecordingFit", parts)


def _toss_rows(tosses: Any) -> list[tuple[object, ...]]:
    rows: list[tuple[object, ...]] = []
    for k, toss in enumerate(tosses):
        f = toss.fit if toss.status == "ok" else None
        rows.append((k, f"{fmt(toss.start)} to {fmt(toss.end)}", toss.samples, toss.status,
                     with_std(f.ratios[0], f.ratios_std[0]) if f else "", with_std(f.ratios[1], f.ratios_std[1]) if f else "",
                     toss.reason))
    return rows


def recording_html(fit: Any) -> str:
    """The pooled fit and every flight as HTML tables (Jupyter's ``_repr_html_``).

    Examples
    --------
    >>> from tumble.analysis.fit.recording import fit_recording
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
    >>> page = fit_recording(rec.t, rec.omega, events=rec.events)._repr_html_()
    >>> page.count("<table"), "chi2/dof" in page
    (2, True)
    """
    rows = [("flights used", flights_used(fit.tosses, fit.tosses_used)),
            ("chi2/dof of the flights' ratios about the pooled ones", fmt(fit.chi2_dof)), *_rotation_rows(fit.pooled)]
    flights = html_table(_toss_rows(fit.tosses), header=("#", "time (s)", "samples", "status", "I1/I3", "I2/I3", "reason"),
                         caption="flights")
    return result_html("RecordingFit", rows, flights)


def estimate_repr(e: Any) -> str:
    """``MassEstimate(m = 0.5 kg, I = (...) kg m^2, COM = (10, 0, 0) mm)``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.estimate import mass_estimate
    >>> mass_estimate(0.5, np.diag([2e-4, 1e-4, 3e-4]), np.eye(6) * 1e-14, [0.01, 0.0, 0.0], np.eye(3) * 1e-8)
    MassEstimate(m = 0.5 kg, I = (0.0001 +- 1e-07, 0.0002 +- 1e-07, 0.0003 +- 1e-07) kg m^2, COM = (10, 0, 0) mm)
    """
    moments = ", ".join(with_std(m, s) for m, s in zip(e.principal_moments, e.principal_moments_std))
    return result_repr("MassEstimate", [f"m = {fmt(e.mass)} kg", f"I = ({moments}) kg m^2",
                                        f"COM = {vec(np.asarray(e.center_of_mass) * 1e3)} mm"])


def _estimate_rows(e: Any) -> list[tuple[str, str]]:
    rows = [("mass (given)", f"{fmt(e.mass, 6)} kg")]
    for j in range(3):
        rows.append((f"I{j + 1}, axis in the sensor frame",
                     f"{with_std(e.principal_moments[j], e.principal_moments_std[j])} kg m^2 along {vec(e.principal_axes[:, j])}"))
    rows.append(("centre of mass, sensor frame",
                 f"{vec(np.asarray(e.center_of_mass) * 1e3)} +- {vec(np.asarray(e.center_of_mass_std) * 1e3, 2)} mm"))
    return rows


def estimate_html(e: Any) -> str:
    """An estimate's moments, axes and centre as an HTML table (Jupyter's ``_repr_html_``).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor.estimate import mass_estimate
    >>> e = mass_estimate(0.5, np.diag([2e-4, 1e-4, 3e-4]), np.eye(6) * 1e-14, [0.01, 0.0, 0.0], np.eye(3) * 1e-8)
    >>> "0.0002 +- 1e-07 kg m^2" in e._repr_html_()
    True
    """
    return result_html("MassEstimate", _estimate_rows(e))


def throw_repr(f: Any) -> str:
    """``ThrowFit('b.csv', skipped: no free flight found)``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import ThrowFit
    >>> ThrowFit("b.csv", "skipped", "no free flight found", None, None, np.zeros(0), np.zeros((0, 3)), np.zeros((0, 3)))
    ThrowFit('b.csv', skipped: no free flight found)
    """
    parts = [short_name(f.input), f"{f.status}: {f.reason}" if f.reason else f.status]
    if np.isfinite(f.t_release):
        parts.append(f"flight {fmt(f.t_release)}..{fmt(f.t_end)} s")
    if np.isfinite(f.residual_rms):
        parts.append(f"residual {fmt(f.residual_rms, 3)} rad/s")
    return result_repr("ThrowFit", parts)


def tensor_repr(fit: Any) -> str:
    """``TensorFit(12 of 12 throws, I = (...) kg m^2, COM = (...) mm, chi2/dof 1.1, adequate)``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import TensorFit
    >>> from tumble.analysis.tensor.estimate import mass_estimate
    >>> e = mass_estimate(0.5, np.diag([1e-4, 2e-4, 3e-4]), np.eye(6) * 1e-14, [0.0, 0.0, 0.0], np.zeros((3, 3)))
    >>> TensorFit(object=e, flown=e, throws=(), adequate=True, chi2_dof=float("nan"))
    TensorFit(0 of 0 throws, I = (0.0001 +- 1e-07, 0.0002 +- 1e-07, 0.0003 +- 1e-07) kg m^2, COM = (0, 0, 0) mm, chi2/dof nan, adequate)
    """
    used = sum(t.status == "used" for t in fit.throws)
    e = fit.object
    moments = ", ".join(with_std(m, s) for m, s in zip(e.principal_moments, e.principal_moments_std))
    return result_repr("TensorFit", [f"{used} of {plural(len(fit.throws), 'throw')}", f"I = ({moments}) kg m^2",
                                     f"COM = {vec(np.asarray(e.center_of_mass) * 1e3)} mm",
                                     f"chi2/dof {fmt(fit.chi2_dof, 2)}", "adequate" if fit.adequate else "NOT adequate"])


def tensor_html(fit: Any) -> str:
    """The object's estimate and every throw as HTML tables (Jupyter's ``_repr_html_``).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import TensorFit
    >>> from tumble.analysis.tensor.estimate import mass_estimate
    >>> e = mass_estimate(0.5, np.diag([1e-4, 2e-4, 3e-4]), np.zeros((6, 6)), [0.0, 0.0, 0.0], np.zeros((3, 3)))
    >>> TensorFit(object=e, flown=e, throws=(), adequate=True, chi2_dof=1.0)._repr_html_().count("<table")
    2
    """
    used = sum(t.status == "used" for t in fit.throws)
    rows = [("throws used", f"{used} of {len(fit.throws)}"), ("adequate", str(fit.adequate)),
            ("chi2/dof of the throws about the joint tensor", fmt(fit.chi2_dof)), *_estimate_rows(fit.object)]
    throws = html_table([(t.input, t.status, fmt(t.residual_rms), t.reason) for t in fit.throws],
                        header=("throw", "status", "residual (rad/s)", "reason"), caption="throws")
    return result_html("TensorFit (the object alone)", rows, throws)


def calibration_repr(c: Any) -> str:
    """``Calibration(adequate, chi2/dof 1.2, 1 + 3 throws used, max bias 0.02 rad/s)``.

    Examples
    --------
    >>> from tumble.analysis.tensor import Device
    >>> from tumble.analysis.tensor.calibrate import Calibration
    >>> Calibration(Device(0.1, [0, 0, 1]), 1.2, float("nan"), 0.8, 1, 3, 0.02, (), ())
    Calibration(adequate, chi2/dof 1.2, 1 + 3 throws used (alone + proof), max bias 0.02 rad/s)
    """
    verdict = "adequate" if c.adequate else f"NOT adequate: {plural(len(c.problems), 'problem')}"
    parts = [verdict, f"chi2/dof {fmt(c.chi2_dof, 2)}", f"{c.alone_used} + {c.proof_used} throws used (alone + proof)",
             f"max bias {fmt(c.max_bias, 3)} rad/s"]
    if c.left_out:
        parts.append(f"{len(c.left_out)} left out")
    return result_repr("Calibration", parts)


def calibration_html(c: Any) -> str:
    """A calibration's checks, problems and the device's rotor as an HTML table.

    Examples
    --------
    >>> from tumble.analysis.tensor import Device
    >>> from tumble.analysis.tensor.calibrate import Calibration
    >>> page = Calibration(Device(0.1, [0, 0, 1]), 9.0, 1.0, 1.0, 3, 3, 0.01, ("a.csv: no flight",), ("the proof turned",))._repr_html_()
    >>> "the proof turned" in page, "a.csv: no flight" in page
    (True, True)
    """
    d = c.device
    rows = [("adequate", str(c.adequate)), ("chi2/dof of the parallel-axis equations", fmt(c.chi2_dof)),
            ("throws used, device alone (chi2/dof)", f"{c.alone_used} ({fmt(c.alone_chi2_dof)})"),
            ("throws used, with the proof body (chi2/dof)", f"{c.proof_used} ({fmt(c.proof_chi2_dof)})"),
            ("largest gyroscope bias", f"{fmt(c.max_bias, 3)} rad/s")]
    if d.rotor_inertia is not None:
        rows.append(("rotor's axial moment J_r", f"{with_std(d.rotor_inertia, d.rotor_inertia_std)} kg m^2"))
    rows += [("problem", p) for p in c.problems] + [("left out", p) for p in c.left_out]
    return result_html("Calibration", rows)


def family_repr(family: Any) -> str:
    """``PeriodFamily(12 motions (8 SAM, 4 LAM), I1/I3 0.2..0.4, I2/I3 0.3..0.9)``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.period_inversion import PeriodFamily
    >>> PeriodFamily(np.array([[0.2, 0.5], [0.3, 0.6]]), np.ones(2), np.ones(2), np.array(["SAM", "LAM"]))
    PeriodFamily(2 motions (1 LAM, 1 SAM), I1/I3 0.2..0.3, I2/I3 0.5..0.6)
    """
    n = len(family.mode)
    parts = [plural(n, "motion") + (" (" + ", ".join(f"{k} {m}" for m, k in sorted(Counter(map(str, family.mode)).items())) + ")"
                                    if n else "")]
    if n:
        r = np.asarray(family.ratios, float)
        parts += [f"I1/I3 {fmt(r[:, 0].min(), 3)}..{fmt(r[:, 0].max(), 3)}", f"I2/I3 {fmt(r[:, 1].min(), 3)}..{fmt(r[:, 1].max(), 3)}"]
    return result_repr("PeriodFamily", parts)


def _span(x: Any) -> str:
    x = np.asarray(x, float)
    return f"{fmt(x.min())} to {fmt(x.max())}"


def family_html(family: Any) -> str:
    """The motions' count by mode and the range of each of their numbers, as an HTML table.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.period_inversion import PeriodFamily
    >>> page = PeriodFamily(np.array([[0.2, 0.5], [0.3, 0.6]]), np.array([1.2, 1.5]), np.ones(2),
    ...                     np.array(["SAM", "LAM"]))._repr_html_()
    >>> "short-axis modes (SAM)" in page, "1.2 to 1.5" in page
    (True, True)
    """
    modes = Counter(map(str, family.mode))
    rows: list[tuple[str, str]] = [("motions", str(len(family.mode))),
                                   ("long-axis modes (LAM)", str(modes.get("LAM", 0))),
                                   ("short-axis modes (SAM)", str(modes.get("SAM", 0)))]
    if len(family.mode):
        r = np.asarray(family.ratios, float)
        rows += [("I1/I3", _span(r[:, 0])), ("I2/I3", _span(r[:, 1])), ("energy 2 E I3 / |L|^2", _span(family.energy)),
                 ("|L| / I3", f"{_span(family.L_over_I3)} rad/s")]
    return result_html("PeriodFamily", rows)


def flight_repr(flight: Any) -> str:
    """``Flight(1.28..2.05 s, samples 126..204, ok)``: a flight found in a recording.

    Examples
    --------
    >>> from tumble.analysis.fit.flights import Flight
    >>> Flight(start=1.0, end=1.5, first=100, stop=150, status="skipped", reason="too short")
    Flight(1..1.5 s, samples 100..150, skipped: too short)
    """
    status = f"{flight.status}: {flight.reason}" if flight.reason else flight.status
    return result_repr("Flight", [f"{fmt(flight.start)}..{fmt(flight.end)} s", f"samples {flight.first}..{flight.stop}",
                                  status])


def model_repr(model: Any) -> str:
    """``FlightModel(1.28..2.05 s, I1/I3 = 0.07333, I2/I3 = 0.9334, quadratic drag, recording 0)``.

    Examples
    --------
    >>> from tumble.analysis.fit.recording import fit_recording
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
    >>> repr(fit_recording(rec.t, rec.omega, events=rec.events).flight_models[0]).startswith("FlightModel(1.277..2.049 s, I1/I3")
    True
    """
    parts = [f"{fmt(model.start)}..{fmt(model.end)} s", f"I1/I3 = {fmt(model.ratios[0])}", f"I2/I3 = {fmt(model.ratios[1])}"]
    if model.drag != "none":
        parts.append(f"{model.drag} drag")
    parts.append(f"recording {model.recording}")
    return result_repr("FlightModel", parts)


def synthetic_repr(rec: Any) -> str:
    """``SyntheticRecording(1234 samples over 12.3 s at 100 Hz, 2 flights, I1/I3 = 0.07, I2/I3 = 0.93)``.

    Examples
    --------
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> repr(synthetic_recording(11, tosses=2, flight=(0.5, 0.8)))  # doctest: +ELLIPSIS
    'SyntheticRecording(... samples over ... s at 100 Hz, 2 flights, I1/I3 = ..., I2/I3 = ...)'
    """
    t = rec.t
    span = f"{plural(len(t), 'sample')} over {fmt(t[-1] - t[0], 3)} s at {fmt(rec.rate)} Hz" if len(t) else "no samples"
    return result_repr("SyntheticRecording", [span, plural(len(rec.flights), "flight"), f"I1/I3 = {fmt(rec.ratios[0])}",
                                              f"I2/I3 = {fmt(rec.ratios[1])}"])


def _counts(values: Any) -> str:
    """``3 stable, 1 unstable``: how many of each value, most first."""
    return ", ".join(f"{k} {v}" for v, k in Counter(map(str, np.ravel(values))).most_common())


def _axis_counts(axes: Any) -> str:
    """``axis 2: 3, axis 3: 1``: how many motions on each axis, in the axes' order."""
    return ", ".join(f"axis {a}: {n}" for a, n in sorted(Counter(np.ravel(axes).tolist()).items()))


def _verdict_word(stable: Any) -> Any:
    return np.where(np.asarray(stable, bool), "stable", "unstable")


def _spin_rows(p: Any) -> list[tuple[str, str]]:
    """(what, value) of one motion's prediction."""
    rows = [("spin axis", str(int(p.axis))), ("circulates about axis", str(int(p.circulation))),
            ("verdict", str(_verdict_word(p.stable)))]
    if np.isfinite(p.growth) and p.growth > 0:
        rows.append(("growth exponent", f"{fmt(p.growth)} 1/s"))
    if np.isfinite(p.wobble) and p.wobble > 0:
        rows.append(("wobble frequency", f"{fmt(p.wobble)} rad/s"))
    return rows


def spin_repr(p: Any) -> str:
    """``SpinPrediction(spin axis 2, circulates about axis 1, unstable, ...)``; for many motions,
    how many of each verdict.

    Examples
    --------
    >>> from tumble.analysis.stability import spin_prediction
    >>> spin_prediction([0.01, 1.0, 0.0], [1.0, 2.0, 3.0])
    SpinPrediction(spin axis 2, circulates about axis 1, unstable, growth exponent 0.5774 1/s)
    >>> spin_prediction([[0.01, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]], [1.0, 2.0, 3.0])
    SpinPrediction(3 motions: 2 stable, 1 unstable)
    """
    if np.ndim(p.axis) == 0:
        return result_repr("SpinPrediction", [v if k == "verdict" else f"{k} {v}" for k, v in _spin_rows(p)])
    return result_repr("SpinPrediction", [f"{plural(np.size(p.axis), 'motion')}: {_counts(_verdict_word(p.stable))}"])


def spin_html(p: Any) -> str:
    """The prediction as an HTML table: one motion's numbers, or the counts of many.

    Examples
    --------
    >>> from tumble.analysis.stability import spin_prediction
    >>> "growth exponent" in spin_prediction([0.01, 1.0, 0.0], [1.0, 2.0, 3.0])._repr_html_()
    True
    """
    if np.ndim(p.axis) == 0:
        return result_html("SpinPrediction", _spin_rows(p))
    return result_html("SpinPrediction", [("motions", str(np.size(p.axis))), ("verdicts", _counts(_verdict_word(p.stable))),
                                          ("spin axes", _axis_counts(p.axis)),
                                          ("circulation axes", _axis_counts(p.circulation))])


def regions_repr(c: Any) -> str:
    """``StabilityClass(lagrange: pitch stable, roll-yaw stable)``; for many bodies, how many in
    each region.

    Examples
    --------
    >>> import tumble
    >>> from tumble.analysis.gravity_stability import gravity_gradient_ratios, gravity_gradient_stability
    >>> gravity_gradient_stability(*gravity_gradient_ratios(tumble.t_handle().principal_moments))
    StabilityClass(lagrange: pitch stable, roll-yaw stable)
    """
    if np.ndim(c.region) == 0:
        return result_repr("StabilityClass", [f"{c.region}: pitch {_verdict_word(c.pitch)}",
                                              f"roll-yaw {_verdict_word(c.roll_yaw)}"])
    return result_repr("StabilityClass", [f"{plural(np.size(c.region), 'body', 'bodies')}: {_counts(c.region)}"])


def regions_html(c: Any) -> str:
    """The region and both verdicts as an HTML table, or how many bodies of each.

    Examples
    --------
    >>> import tumble
    >>> from tumble.analysis.gravity_stability import gravity_gradient_ratios, gravity_gradient_stability
    >>> "lagrange" in gravity_gradient_stability(*gravity_gradient_ratios(tumble.t_handle().principal_moments))._repr_html_()
    True
    """
    if np.ndim(c.region) == 0:
        return result_html("StabilityClass", [("region", str(c.region)), ("pitch", str(_verdict_word(c.pitch))),
                                              ("roll-yaw", str(_verdict_word(c.roll_yaw)))])
    return result_html("StabilityClass", [("bodies", str(np.size(c.region))), ("regions", _counts(c.region)),
                                          ("pitch", _counts(_verdict_word(c.pitch))),
                                          ("roll-yaw", _counts(_verdict_word(c.roll_yaw)))])
