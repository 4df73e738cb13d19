"""The fit's statistics on realistic synthetic recordings, as a table (about a minute).

``python benchmarks/fit_coverage.py [RECORDINGS] [TOSSES]``: the campaign of
``tests/test_fit_recording.py`` (60 recordings of 2 tosses per body by default, each recording
with its own gyroscope), printed per body: the share of true flights found (intersection over
union >= 0.5), the share fitted, the coverage of the 95 % intervals of each ratio, the share of
recordings whose pooled ratios lie within two pooled standard uncertainties, and the reasons of
the skipped flights. The test asserts the issue's bounds; this prints the numbers.
"""

from __future__ import annotations

import sys
import time
from collections import Counter

import numpy as np

from tumble.analysis.fit import find_flights, fit_recording
from tumble.analysis.fit.synthetic import synthetic_recording


def _iou(a, b, start, end):
    return max(0.0, min(b, end) - max(a, start)) / (max(b, end) - min(a, start))


def campaign(body: str, recordings: int = 60, tosses: int = 2) -> dict:
    found = used = total = 0
    inside, pooled, reasons = [], [], Counter()
    t0 = time.perf_counter()
    for seed in range(1000, 1000 + recordings):
        rec = synthetic_recording(seed, body=body, tosses=tosses, pauses=1)
        try:
            fit = fit_recording(rec.t, rec.omega, events=rec.events)
            flights = fit.tosses
        except ValueError:  # no usable flight
            fit, flights = None, find_flights(rec.t, rec.omega, events=rec.events)
        for a, b in rec.flights:
            total += 1
            best = max(flights, key=lambda f: _iou(a, b, f.start, f.end))
            if _iou(a, b, best.start, best.end) < 0.5:
                continue
            found += 1
            if fit is not None and best.status == "ok":
                used += 1
                iv = best.fit.ratios_interval
                inside.append([iv[0, 0] <= rec.ratios[0] <= iv[0, 1], iv[1, 0] <= rec.ratios[1] <= iv[1, 1]])
            else:
                reasons[best.reason.split(":")[0].split(" (")[0]] += 1
        if fit is not None:
            p = fit.pooled
            pooled.append(bool(np.all(np.abs(p.ratios - rec.ratios) <= 2 * p.ratios_std)))
    cover = np.mean(inside, axis=0)
    return {"body": body, "flights": total, "found": found / total, "fitted": used / total,
            "coverage_I1_over_I3": float(cover[0]), "coverage_I2_over_I3": float(cover[1]),
            "pooled_within_2_sigma": float(np.mean(pooled)), "recordings_pooled": len(pooled),
            "skipped": dict(reasons), "seconds": time.perf_counter() - t0}


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    recordings = int(argv[0]) if argv else 60
    tosses = int(argv[1]) if len(argv) > 1 else 2
    print("| body | flights | found | fitted | 95 % interval holds I1/I3 | holds I2/I3 | pooled within 2 sigma "
          "| skipped | time (s) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for body in ("racquet", "phone"):
        r = campaign(body, recordings, tosses)
        print(f"| {body} | {r['flights']} | {r['found']:.1%} | {r['fitted']:.1%} | {r['coverage_I1_over_I3']:.1%} "
              f"| {r['coverage_I2_over_I3']:.1%} | {r['pooled_within_2_sigma']:.1%} of {r['recordings_pooled']} "
              f"| {r['skipped']} | {r['seconds']:.0f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
