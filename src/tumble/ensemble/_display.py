"""Short plain reprs and Jupyter's HTML tables of the ensembles' results: a detumbling Monte
Carlo (:class:`~tumble.ensemble.detumble.DetumbleMonteCarlo` and its
:class:`~tumble.ensemble.detumble.DetumbleCases`), a Monte Carlo of pointing on an estimate
(:class:`~tumble.ensemble.knowledge.PointingMonteCarlo` and its
:class:`~tumble.ensemble.knowledge.KnowledgeCases`), a sweep's streaming summary
(:class:`~tumble.ensemble.summary.SweepSummary`) and the stability map
(:class:`~tumble.ensemble.reductions.StabilityMap`).

Each repr says what the result is, its size and its headline numbers on one line (never its
arrays). The results are read by their attributes: the modules that define them import this
one, and the import graph has no circles.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._html import fmt, html_table, plural, result_html, result_repr, vec

__all__ = ["cases_html", "cases_repr", "knowledge_html", "knowledge_repr", "map_html", "map_repr", "monte_carlo_html",
           "monte_carlo_repr", "pointing_html", "pointing_repr", "sweep_html", "sweep_repr"]


def cases_repr(cases: Any) -> str:
    """``DetumbleCases(3 cases, |omega0| 5.73..17.2 deg/s, gyro bias)``.

    Examples
    --------
    >>> from tumble.ensemble.detumble import detumble_cases
    >>> detumble_cases(3, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3, seed=2)  # doctest: +ELLIPSIS
    DetumbleCases(3 cases, |omega0| ... deg/s, gyro biases)
    """
    parts = [plural(len(cases), "case")]
    if len(cases):
        rate = np.degrees(np.linalg.norm(cases.omega0, axis=1))
        parts.append(f"|omega0| {fmt(rate.min(), 3)}..{fmt(rate.max(), 3)} deg/s")
    if cases.gyro_bias is not None:
        parts.append("gyro biases")
    return result_repr("DetumbleCases", parts)


def _range(x: Any, digits: int = 3) -> str:
    x = np.asarray(x, float)
    lo, hi = fmt(x.min(), digits), fmt(x.max(), digits)
    return lo if lo == hi else f"{lo}..{hi}"


def cases_html(cases: Any) -> str:
    """The detumbling cases' spread (moments, starting rates, biases) as an HTML table.

    Examples
    --------
    >>> from tumble.ensemble.detumble import detumble_cases
    >>> page = detumble_cases(3, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3, seed=2)._repr_html_()
    >>> "|omega0|, smallest to largest" in page, "gyro bias" in page
    (True, True)
    """
    rows: list[tuple[str, str]] = [("cases", str(len(cases)))]
    if len(cases):
        m = np.asarray(cases.moments, float)
        rows += [(f"I{j + 1}", f"{_range(m[:, j], 4)} kg m^2") for j in range(3)]
        rate = np.degrees(np.linalg.norm(cases.omega0, axis=1))
        rows.append(("|omega0|, smallest to largest", f"{_range(rate)} deg/s"))
        rows.append(("GMST at the start", f"{_range(np.degrees(cases.gmst0))} deg"))
        if cases.gyro_bias is not None:
            bias = np.degrees(np.linalg.norm(cases.gyro_bias, axis=1))
            rows.append(("|gyro bias|, smallest to largest", f"{_range(bias)} deg/s"))
    return result_html("DetumbleCases", rows)


def _knowledge_parts(cases: Any) -> list[tuple[str, str]]:
    """(what, value) of the pointing cases' spread: biases, noise scales and seeds."""
    n = len(cases)
    if not n:
        return []
    bias = np.degrees(np.linalg.norm(cases.gyro_bias, axis=1))
    seeds = np.asarray(cases.noise_seed)
    return [("|gyro bias|", f"{_range(bias)} deg/s"), ("noise scale", _range(cases.noise_scale)),
            ("noise seeds", f"{seeds.min()}..{seeds.max()}" if n > 1 else str(seeds[0]))]


def knowledge_repr(cases: Any) -> str:
    """``KnowledgeCases(4 cases, |gyro bias| 0.00216..0.0182 deg/s, noise scale 0.846..1.19, ...)``.

    Examples
    --------
    >>> from tumble.ensemble.knowledge import knowledge_cases
    >>> knowledge_cases(4, gyro_bias_sigma=1e-4, noise_spread=0.2, seed=1)
    KnowledgeCases(4 cases, |gyro bias| 0.00216..0.0182 deg/s, noise scale 0.846..1.19, noise seeds 2000..2003)
    """
    return result_repr("KnowledgeCases", [plural(len(cases), "case")] + [f"{k} {v}" for k, v in _knowledge_parts(cases)])


def knowledge_html(cases: Any) -> str:
    """The pointing cases' spread as an HTML table.

    Examples
    --------
    >>> from tumble.ensemble.knowledge import knowledge_cases
    >>> "noise scale" in knowledge_cases(4, noise_spread=0.2, seed=1)._repr_html_()
    True
    """
    return result_html("KnowledgeCases", [("cases", str(len(cases))), *_knowledge_parts(cases)])


_ERRORS = (("pointing_rms", "pointing RMS"), ("pointing_final", "final pointing"),
           ("knowledge_rms", "knowledge RMS"), ("knowledge_final", "final knowledge"))


def pointing_repr(mc: Any) -> str:
    """``PointingMonteCarlo(4 cases, pointing RMS median 0.25 deg, 95 % 0.385 deg, ...)``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> from tumble.ensemble.knowledge import PointingMonteCarlo, knowledge_cases
    >>> e = np.radians([0.1, 0.2, 0.3, 0.4])
    >>> PointingMonteCarlo(knowledge_cases(4), e, e / 2, e, e / 2, Sensors(), 60.0)
    PointingMonteCarlo(4 cases, after 60 s: pointing RMS median 0.25 deg, 95 % 0.385 deg; knowledge RMS median 0.25 deg, 95 % 0.385 deg)
    """
    parts = [plural(len(mc.cases), "case")]
    if len(mc.cases):
        s = mc.summary()
        point, know = s["pointing_rms_deg"], s["knowledge_rms_deg"]
        parts.append(f"after {fmt(mc.settle)} s: pointing RMS median {fmt(point['median'], 3)} deg, "
                     f"95 % {fmt(point['p95'], 3)} deg; knowledge RMS median {fmt(know['median'], 3)} deg, "
                     f"95 % {fmt(know['p95'], 3)} deg")
    return result_repr("PointingMonteCarlo", parts)


def pointing_html(mc: Any) -> str:
    """Each error's median, 95th percentile and largest (deg), and the cases' spread, as HTML tables.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.dynamics.models.sensors import Sensors
    >>> from tumble.ensemble.knowledge import PointingMonteCarlo, knowledge_cases
    >>> page = PointingMonteCarlo(knowledge_cases(4), *[np.radians([0.1, 0.2, 0.3, 0.4])] * 4, Sensors(), 60.0)._repr_html_()
    >>> page.count("<table"), "final pointing" in page
    (2, True)
    """
    rows: list[tuple[str, str]] = [("cases", str(len(mc.cases))), ("errors from", f"{fmt(mc.settle)} s")]
    rows += _knowledge_parts(mc.cases)
    more = []
    if len(mc.cases):
        s = mc.summary()
        more.append(html_table([(label, *(fmt(s[f"{name}_deg"][k], 3) for k in ("median", "p95", "max")))
                                for name, label in _ERRORS], header=["error, deg", "median", "95 %", "largest"]))
    return result_html("PointingMonteCarlo", rows, *more)


def _time(x: float) -> str:
    return "never" if not math.isfinite(x) else f"{fmt(x)} s"


def monte_carlo_repr(mc: Any) -> str:
    """``DetumbleMonteCarlo(3 cases, 66.7 % detumbled by 600 s, median 300 s, 95 % never)``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.detumble import DetumbleMonteCarlo, detumble_cases
    >>> c = detumble_cases(3, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3, seed=2)
    >>> DetumbleMonteCarlo(times=np.array([100.0, 300.0, np.nan]), cases=c, threshold=0.01, t_end=600.0, seconds=0.1)
    DetumbleMonteCarlo(3 cases, 66.7 % below 0.573 deg/s by 600 s, median 300 s, 95 % never)
    """
    parts = [plural(len(mc.times), "case")]
    if len(mc.times):
        parts += [f"{fmt(100 * mc.detumbled, 3)} % below {fmt(math.degrees(mc.threshold), 3)} deg/s by {fmt(mc.t_end)} s",
                  f"median {_time(mc.percentile(50))}", f"95 % {_time(mc.percentile(95))}"]
    return result_repr("DetumbleMonteCarlo", parts)


def monte_carlo_html(mc: Any) -> str:
    """The Monte Carlo's settings, detumble times and worst cases as an HTML table.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.detumble import DetumbleMonteCarlo, detumble_cases
    >>> c = detumble_cases(3, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3, seed=2)
    >>> page = DetumbleMonteCarlo(times=np.array([100.0, 300.0, np.nan]), cases=c, threshold=0.01, t_end=600.0,
    ...                           seconds=0.1)._repr_html_()
    >>> "66.7 %" in page, "worst cases" in page
    (True, True)
    """
    rows: list[tuple[str, str]] = [("cases", str(len(mc.times))),
                                   ("threshold", f"{fmt(math.degrees(mc.threshold))} deg/s ({fmt(mc.threshold)} rad/s)"),
                                   ("run length", f"{fmt(mc.t_end)} s"), ("wall time", f"{fmt(mc.seconds, 3)} s")]
    if len(mc.times):
        rows += [("detumbled by the end", f"{fmt(100 * mc.detumbled, 3)} %")]
        rows += [(f"detumble time, {p} % of the cases", _time(mc.percentile(p))) for p in (50, 95, 99)]
        rows.append(("worst cases (index)", ", ".join(str(i) for i in mc.worst(5))))
    rows += [("sensors", "ideal" if mc.sensors is None else "noisy"),
             ("gravity gradient", "yes" if mc.gravity_gradient else "no")]
    return result_html("DetumbleMonteCarlo", rows)


def _pass_rate(s: Any) -> list[str]:
    judged = s.passed + s.failed
    return [f"{s.passed} of {judged} passed the criterion"] if judged else []


def sweep_repr(s: Any) -> str:
    """``SweepSummary(4 cases, 3 flipped, 2 columns)``.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.summary import SweepSummary
    >>> cols = {"case": np.arange(4), "axis": np.array([2, 2, 2, 3]), "predicted": np.array(["unstable"] * 3 + ["stable"]),
    ...         "circulation": np.array([1, 3, 3, 3]), "flips": np.array([2, 4, 6, 0]), "resampled": np.zeros(4, int)}
    >>> SweepSummary.of(cols, seed=0)
    SweepSummary(4 cases, 3 flipped, 2 columns: flips, resampled)
    """
    names = ", ".join(s.columns)
    parts = [plural(s.cases, "case"), f"{s.flipped} flipped", *_pass_rate(s),
             f"{plural(len(s.columns), 'column')}: {names if len(names) <= 80 else names[:77] + '...'}"]
    if s.redraws:
        parts.append(f"{s.redraws} bodies redrawn")
    return result_repr("SweepSummary", parts)


def sweep_html(s: Any) -> str:
    """Every column's count, mean, spread and extremes as an HTML table.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.ensemble.summary import SweepSummary
    >>> cols = {"case": np.arange(4), "axis": np.array([2, 2, 2, 3]), "predicted": np.array(["unstable"] * 3 + ["stable"]),
    ...         "circulation": np.array([1, 3, 3, 3]), "flips": np.array([2, 4, 6, 0]), "resampled": np.zeros(4, int)}
    >>> page = SweepSummary.of(cols, seed=0)._repr_html_()
    >>> page.count("<table"), "flips: mean" in page
    (1, True)
    """
    m = s.moments
    rows: list[tuple[str, str]] = [("cases", str(s.cases)), ("flipped at least once", str(s.flipped))]
    if s.passed + s.failed:
        rows.append(("passed / failed the criterion", f"{s.passed} / {s.failed}"))
    for j, name in enumerate(s.columns):
        rows.append((f"{name}: mean +- std [min, max]",
                     f"{fmt(m.mean[j])} +- {fmt(m.std[j], 2)} "
                     f"[{fmt(m.minimum[j])}, {fmt(m.maximum[j])}]"))
    return result_html("SweepSummary", rows)


def map_repr(m: Any) -> str:
    """``StabilityMap(40 x 20 cells, 380 inside the triangle, omega0 = (0.1, 10, 0.1) rad/s, ...)``.

    Examples
    --------
    >>> from tumble.ensemble.reductions import stability_map
    >>> stability_map(10.0, resolution=40)   # I1/I3 by I2/I3
    StabilityMap(40 x 20 cells, 380 inside the triangle, omega0 = (0.1, 10, 0.1) rad/s, flip interval 1.71..64.6 s)
    """
    inside = np.asarray(m.inside, bool)
    parts = [f"{len(m.x)} x {len(m.y)} cells", f"{int(inside.sum())} inside the triangle", f"omega0 = {vec(m.omega0)} rad/s"]
    flips = np.asarray(m.flip_interval, float)[inside]
    flips = flips[np.isfinite(flips)]
    if flips.size:
        parts.append(f"flip interval {fmt(flips.min(), 3)}..{fmt(flips.max(), 3)} s")
    return result_repr("StabilityMap", parts)


def map_html(m: Any) -> str:
    """The map's grid, spin and ranges as an HTML table.

    Examples
    --------
    >>> from tumble.ensemble.reductions import stability_map
    >>> "circulating about the major axis" in stability_map(10.0, resolution=20)._repr_html_()
    True
    """
    inside = np.asarray(m.inside, bool)
    circ = np.asarray(m.circulation)[inside]
    flips = np.asarray(m.flip_interval, float)[inside]
    flips = flips[np.isfinite(flips)]
    rows = [("cells (I1/I3 x I2/I3)", f"{len(m.x)} x {len(m.y)}"), ("inside the triangle", str(int(inside.sum()))),
            ("omega0, principal frame", f"{vec(m.omega0)} rad/s"),
            ("circulating about the major axis", str(int(np.sum(circ == 3)))),
            ("circulating about the minor axis", str(int(np.sum(circ == 1))))]
    if flips.size:
        rows.append(("flip interval, shortest to longest", f"{fmt(flips.min())} to {fmt(flips.max())} s"))
    return result_html("StabilityMap", rows)
