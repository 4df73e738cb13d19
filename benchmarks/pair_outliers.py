"""The joint fit's gross-outlier test on flights that agree, three ways (a few minutes).

``python benchmarks/pair_outliers.py [RECORDINGS] [--json PATH]``: for each body (racquet, phone)
and kind of recording (``tidy``, ``many``, ``slow`` as ``benchmarks/pool_coverage.py``),
``RECORDINGS`` synthetic recordings (default 15, seeds from 1000), each with its own gyroscope;
every pair of flights of one recording that states its own ratios. All are tosses of one rigid
body, so every pair agrees: ``chi^2 = dv^T C^-1 dv`` of their ratios' difference ``dv`` follows
chi^2 with 2 degrees of freedom (median 1.39; beyond 25, the test's five standard uncertainties,
4e-6) when ``C`` is right. ``C`` three ways:

- **statistical**: the two flights' statistical covariances (the noise alone);
- **independent scale**: with each flight's share of the gyroscope's scale error, ``B_a B_a^T +
  B_b B_b^T`` (:func:`~tumble.analysis.fit.summary.ratio_scale_effect`), what
  :func:`tumble.analysis.fit.joint.joint_solution` uses;
- **common scale**: the scale error is the same for both (one gyroscope), so its share of the
  difference is ``(B_a - B_b) (B_a - B_b)^T``.

Writes ``benchmarks/results/pair_outliers.md``.
"""

from __future__ import annotations

import json
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

from tumble.analysis.fit import find_flights
from tumble.analysis.fit.solve import without_drag_law_error
from tumble.analysis.fit.summary import public_covariance, ratio_scale_effect

sys.path.insert(0, str(Path(__file__).parent))
from pool_coverage import KINDS, quietly, recording  # noqa: E402  (the benchmarks' own module)

WAYS = ("statistical", "independent scale (the test's)", "common scale")


def _pairs(job: tuple[str, str, int]) -> list[list[float]]:
    """chi^2 of every pair of one recording's flights, the three ways."""
    flights = quietly(find_flights, recording(*job)) or []
    sols = [f.solution for f in flights if f.solution is not None and f.status == "ok" and not f.joinable]
    out = []
    for i, a in enumerate(sols):
        for b in sols[i + 1:]:
            dv = public_covariance(a)[1][:2] - public_covariance(b)[1][:2]
            stat = sum(public_covariance(s, statistical=True)[2][:2, :2] for s in (a, b))
            independent = sum(public_covariance(without_drag_law_error(s))[2][:2, :2] for s in (a, b))
            d = ratio_scale_effect(a) - ratio_scale_effect(b)
            if np.all(np.isfinite(stat)) and np.all(np.isfinite(dv)):
                out.append([float(dv @ np.linalg.pinv(C) @ dv) for C in (stat, independent, stat + d @ d.T)])
    return out


def main(argv: list[str] | None = None) -> int:
    """``pair_outliers.py [RECORDINGS] [--json PATH]``."""
    args = list(sys.argv[1:] if argv is None else argv)
    out = Path(args.pop(args.index("--json") + 1)) if "--json" in args else None
    if "--json" in args:
        args.remove("--json")
    n = int(args[0]) if args else 15
    jobs = [(body, kind, 1000 + s) for body in ("racquet", "phone") for kind in KINDS for s in range(n)]
    start = time.perf_counter()
    with ProcessPoolExecutor(2) as pool:
        chi2 = np.array([p for pairs in pool.map(_pairs, jobs) for p in pairs])
    lines = [f"# The outlier test's covariance on pairs of agreeing flights ({len(chi2)} pairs, {len(jobs)} recordings)", "",
             f"`python benchmarks/pair_outliers.py {n}` ({time.perf_counter() - start:.0f} s). chi^2 with 2 degrees of "
             "freedom: median 1.39, beyond 9.21 1 %, beyond 25 4e-6.", "",
             "| covariance | median chi^2 | beyond 9.21 | beyond 25 (rejected) |", "|---|---|---|---|"]
    lines += [f"| {way} | {np.median(col):.2f} | {np.mean(col > 9.21):.1%} | {np.mean(col > 25):.1%} |"
              for way, col in zip(WAYS, chi2.T)]
    text = "\n".join(lines) + "\n"
    print(text)
    (Path(__file__).parent / "results" / "pair_outliers.md").write_text(text, encoding="utf-8")
    if out is not None:
        out.write_text(json.dumps({w: c.tolist() for w, c in zip(WAYS, chi2.T)}), encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
