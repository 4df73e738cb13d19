"""The fit's statistics on realistic synthetic recordings, as a table (a few minutes).

``python benchmarks/fit_coverage.py [RECORDINGS] [KIND ...]``: for each body (racquet, phone) and
each kind of recording (all, or those named), ``RECORDINGS`` synthetic recordings (default 40, seeds from 1000), each with its
own gyroscope, fitted whole as a user would (:func:`tumble.analysis.fit.fit_recording`):

- **tidy**: 2 tosses per file at 100 Hz, each caught and held (the spin killed in the hand), a
  phyphox pause;
- **hand**: 2 tosses per file, each caught and turned on in the hand at 5-20 rad/s for 0.3-1 s;
- **landing**: 2 tosses per file, each landing with bounces and rolling for 0.3-1 s;
- **one toss**: one toss per file at 100-500 Hz (drawn), the phone swung about at 3-10 rad/s
  before and after, the end drawn among catch, hand and landing;
- **many**: 4 tosses per file, ends drawn, the phone swung about at 3-10 rad/s between them;
- **one toss + accel**, **many + accel**: the same recordings (the same seeds: the gyroscope's
  samples are the same) with the phone's accelerometer (``synthetic_recording(accel=True)``),
  which the fit is given (#29: the flights cut to its free fall).

Printed per row:

- **found**: the share of the true flights that a fitted flight matches (intersection over union
  >= 0.5 with the true release-to-impact interval), the issue's ">= 95 % found and fitted";
- **of the fittable**: the same share among the flights that are fittable at all: those that
  :func:`~tumble.analysis.fit.find_flights` fits when given exactly the true interval (a flight
  too short or too little of a tumble to determine both ratios is not, whoever cuts it);
- **false**: the share of fitted flights that match no true flight;
- **joint only**: of the found flights, how many are used in the joint fit only (a free motion
  whose ratios it does not determine alone; ``Toss.reason`` starts with "used in the joint fit
  only"): found and fitted, since they are fitted, jointly with the recording's other flights;
- **coverage**: the share of the found flights whose 95 % intervals hold the true ratio (the
  flights used in the joint fit only state no interval of their own: left out);
- **skipped**: the reasons of the true flights not found and fitted;
- **release, impact error**: the median distance of the found flights' first and last sample
  from the true release and impact, ms.
"""

from __future__ import annotations

import sys
import time
import warnings
from collections import Counter

import numpy as np

from tumble.analysis.fit import InadequateFitWarning, find_flights, fit_recording
from tumble.analysis.fit.recording import JOINT_ONLY
from tumble.analysis.fit.synthetic import synthetic_recording

#: The kinds of recording, as synthetic_recording's arguments (a callable draws per seed).
KINDS = {
    "tidy": lambda rng: dict(tosses=2, pauses=1),
    "hand": lambda rng: dict(tosses=2, ending="hand"),
    "landing": lambda rng: dict(tosses=2, ending="landing"),
    "one toss": lambda rng: dict(tosses=1, ending="mixed", hand=(3.0, 10.0), rate=float(rng.choice([100, 200, 400, 500]))),
    "many": lambda rng: dict(tosses=4, ending="mixed", hand=(3.0, 10.0)),
    "one toss + accel": lambda rng: dict(KINDS["one toss"](rng), accel=True),
    "many + accel": lambda rng: dict(KINDS["many"](rng), accel=True),
}


def _iou(a, b, start, end):
    return max(0.0, min(b, end) - max(a, start)) / (max(b, end) - min(a, start))


def _fittable(rec, a, b) -> bool:
    """Whether the flight fits when cut exactly at its true release and impact."""
    sel = (rec.t >= a) & (rec.t <= b)
    flights = find_flights(rec.t[sel], rec.omega[sel])
    return bool(flights) and flights[0].status == "ok"


def campaign(body: str, kind: str, recordings: int = 40) -> dict:
    total = found = fittable = found_fittable = fitted = false = joint_only = 0
    inside, reasons, ends = [], Counter(), []
    t0 = time.perf_counter()
    for seed in range(1000, 1000 + recordings):
        rec = synthetic_recording(seed, body=body, **KINDS[kind](np.random.default_rng(seed)))
        accel = None if rec.accel is None else rec.accel.f
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", InadequateFitWarning)
            try:
                flights = fit_recording(rec.t, rec.omega, events=rec.events, accel=accel).tosses
            except ValueError:  # no usable flight
                flights = find_flights(rec.t, rec.omega, events=rec.events, accel=accel)
        ok = [f for f in flights if f.status == "ok"]
        fitted += len(ok)
        false += sum(max(_iou(a, b, f.start, f.end) for a, b in rec.flights) < 0.5 for f in ok)
        for a, b in rec.flights:
            total += 1
            can = _fittable(rec, a, b)
            fittable += can
            match = [f for f in ok if _iou(a, b, f.start, f.end) >= 0.5]
            if match:
                found += 1
                ends.append((abs(match[0].start - a), abs(match[0].end - b)))
                found_fittable += can
                if match[0].reason.startswith(JOINT_ONLY):  # its own ratios are not determined: no interval to test
                    joint_only += 1
                    continue
                iv = match[0].fit.ratios_interval
                inside.append([iv[0, 0] <= rec.ratios[0] <= iv[0, 1], iv[1, 0] <= rec.ratios[1] <= iv[1, 1]])
            else:
                best = max(flights, key=lambda f: _iou(a, b, f.start, f.end), default=None)
                reason = "nothing found" if best is None or _iou(a, b, best.start, best.end) < 0.5 else \
                    best.reason.split(":")[0].split(" (")[0]
                reasons[reason + ("" if can else " [unfittable]")] += 1
    cover = np.mean(inside, axis=0) if inside else np.full(2, np.nan)
    return {"body": body, "kind": kind, "flights": total, "found": found / total,
            "found_of_fittable": found_fittable / max(fittable, 1), "fittable": fittable / total,
            "false": false / max(fitted, 1), "fitted": fitted, "joint_only": joint_only,
            "coverage_I1_over_I3": float(cover[0]), "coverage_I2_over_I3": float(cover[1]),
            "skipped": dict(reasons), "seconds": time.perf_counter() - t0,
            "end_error_ms": (1e3 * np.median(ends, axis=0)).tolist() if ends else [np.nan, np.nan]}


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    recordings = int(argv[0]) if argv else 40
    kinds = argv[1:] or list(KINDS)
    unknown = [k for k in kinds if k not in KINDS]
    if unknown:
        print(f"unknown kind {unknown[0]!r}; allowed: {', '.join(map(repr, KINDS))}", file=sys.stderr)
        return 2
    print("| body | recordings | true flights | found and fitted | of the fittable | fittable | false | joint only | "
          "95 % interval holds I1/I3 | holds I2/I3 | not found | time (s) | release, impact error (ms) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for body in ("racquet", "phone"):
        for kind in kinds:
            r = campaign(body, kind, recordings)
            rows.append(r)
            print(f"| {body} | {kind} | {r['flights']} | {r['found']:.1%} | {r['found_of_fittable']:.1%} | "
                  f"{r['fittable']:.1%} | {r['false']:.1%} of {r['fitted']} | {r['joint_only']} | {r['coverage_I1_over_I3']:.1%} | "
                  f"{r['coverage_I2_over_I3']:.1%} | {r['skipped']} | {r['seconds']:.0f} | "
                  f"{r['end_error_ms'][0]:.1f}, {r['end_error_ms'][1]:.1f} |", flush=True)
    total = sum(r["flights"] for r in rows)
    found = sum(r["found"] * r["flights"] for r in rows) / total
    fittable = sum(r["fittable"] * r["flights"] for r in rows)
    of_fittable = sum(r["found_of_fittable"] * r["fittable"] * r["flights"] for r in rows) / fittable
    fitted = sum(r["fitted"] for r in rows)
    false = sum(r["false"] * r["fitted"] for r in rows) / fitted
    print(f"\nall: {total} true flights, {found:.1%} found and fitted ({of_fittable:.1%} of the {fittable:.0f} fittable), "
          f"{false:.1%} of {fitted} fitted flights false")
    return 0


if __name__ == "__main__":
    sys.exit(main())
