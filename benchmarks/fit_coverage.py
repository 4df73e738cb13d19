"""The fit's statistics on realistic synthetic recordings, as a table (a few minutes).

``python benchmarks/fit_coverage.py [RECORDINGS] [KIND ...] [--first-seed N] [--jobs N] [--json PATH]``:
for each body (racquet, phone) and each kind of recording (all, or those named), ``RECORDINGS``
synthetic recordings (default 40, seeds from 1000), each with its own gyroscope, fitted whole as
a user would (:func:`tumble.analysis.fit.fit_recording`):

- **tidy**: 2 tosses per file at 100 Hz, each caught and held (the spin killed in the hand), a
  phyphox pause;
- **hand**: 2 tosses per file, each caught and turned on in the hand at 5-20 rad/s for 0.3-1 s;
- **landing**: 2 tosses per file, each landing with bounces and rolling for 0.3-1 s;
- **one toss**: one toss per file at 100-500 Hz (drawn), the phone swung about at 3-10 rad/s
  before and after, the end drawn among catch, hand and landing;
- **many**: 4 tosses per file, ends drawn, the phone swung about at 3-10 rad/s between them;
- **one toss, turned**, **one toss, table** (issue #39): one toss per file at 100-500 Hz, caught
  and turned on smoothly in the fingers (a motion a torque-free model with drag follows, of
  another body) or landed flat and spun on a table;
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
- **files without a false flight**: the share of the files in which no fitted flight lies off
  the true flights (a stretch after a catch or a landing counted as a flight: issue #39's
  ">= 99 %");
- **answer is the toss's**: of the one-toss files with an answer, the share whose answer equals
  the toss's own fit within a tenth of its standard uncertainty (issue #39's ">= 98 %");
- **release, impact error**: the median distance of the found flights' first and last sample
  from the true release and impact, ms.
"""

from __future__ import annotations

import sys
import time
import warnings
from collections import Counter
from pathlib import Path

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
    "one toss, turned": lambda rng: dict(tosses=1, ending="turn", rate=float(rng.choice([100, 200, 400, 500]))),
    "one toss, table": lambda rng: dict(tosses=1, ending="table", rate=float(rng.choice([100, 200, 400, 500]))),
    "one toss + accel": lambda rng: dict(KINDS["one toss"](rng), accel=True),
    "many + accel": lambda rng: dict(KINDS["many"](rng), accel=True),
}


def _iou(a, b, start, end):
    return max(0.0, min(b, end) - max(a, start)) / (max(b, end) - min(a, start))


def stated_flights(seed: int, body: str, kind: str, **extra):
    """A cell's recording for ``seed`` (``extra``: more arguments of the generator), fitted whole,
    and for each true flight found the toss that states its own ratios (not used in the joint fit
    only); returns ``(recording, its draw, [toss, ...])``. For the scans beside this campaign
    (fit_zscan)."""
    draw = dict(KINDS[kind](np.random.default_rng(seed)), **extra)
    rec = synthetic_recording(seed, body=body, **draw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            tosses = fit_recording(rec.t, rec.omega, events=rec.events).tosses
        except ValueError:  # no usable flight
            return rec, draw, []
    found = []
    for a, b in rec.flights:
        match = [f for f in tosses if f.status == "ok" and _iou(a, b, f.start, f.end) >= 0.5]
        if match and not match[0].reason:
            found.append(match[0])
    return rec, draw, found


def _fittable(rec, a, b) -> bool:
    """Whether the flight fits when cut exactly at its true release and impact."""
    sel = (rec.t >= a) & (rec.t <= b)
    flights = find_flights(rec.t[sel], rec.omega[sel])
    return bool(flights) and flights[0].status == "ok"


def campaign(body: str, kind: str, recordings: int = 40, first_seed: int = 1000, jobs: int = 1) -> dict:
    """One cell (a body, a kind of recording) over ``recordings`` seeds from ``first_seed``."""
    t0 = time.perf_counter()
    seeds = range(first_seed, first_seed + recordings)
    if jobs > 1:
        from concurrent.futures import ProcessPoolExecutor

        with ProcessPoolExecutor(jobs) as pool:
            parts = list(pool.map(_one_recording, [body] * len(seeds), [kind] * len(seeds), seeds))
    else:
        parts = [_one_recording(body, kind, seed) for seed in seeds]
    return _cell(body, kind, parts, time.perf_counter() - t0)


def _one_recording(body: str, kind: str, seed: int) -> dict:
    """The counts of one synthetic recording (a process pool's task)."""
    total = found = fittable = found_fittable = fitted = false = joint_only = 0
    inside, reasons, ends = [], Counter(), []
    rec = synthetic_recording(seed, body=body, **KINDS[kind](np.random.default_rng(seed)))
    accel = None if rec.accel is None else rec.accel.f
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InadequateFitWarning)
        try:
            fit = fit_recording(rec.t, rec.omega, events=rec.events, accel=accel)
            flights = fit.tosses
        except ValueError:  # no usable flight
            fit, flights = None, find_flights(rec.t, rec.omega, events=rec.events, accel=accel)
    ok = [f for f in flights if f.status == "ok"]
    own = [f for f in ok if _iou(*rec.flights[0], f.start, f.end) >= 0.5 and not f.reason]
    # one toss a file: is the file's answer its toss's own fit (within a tenth of its std)?
    answered = int(len(rec.flights) == 1 and fit is not None and bool(own))
    same = int(answered and bool(np.all(np.abs(fit.pooled.ratios - own[0].fit.ratios) <= 0.1 * own[0].fit.ratios_std)))
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
    return {"total": total, "found": found, "fittable": fittable, "found_fittable": found_fittable,
            "fitted": fitted, "false": false, "joint_only": joint_only, "inside": inside, "reasons": reasons,
            "ends": ends, "answered": answered, "same": same, "clean": int(false == 0)}


def _cell(body: str, kind: str, parts: list[dict], seconds: float) -> dict:
    """A cell's shares from its recordings' counts, with each coverage's 95 % Clopper-Pearson interval."""
    from scipy.stats import binomtest

    add = {k: sum(p[k] for p in parts) for k in ("total", "found", "fittable", "found_fittable", "fitted", "false",
                                                  "joint_only", "answered", "same", "clean")}
    inside = np.array([row for p in parts for row in p["inside"]], bool).reshape(-1, 2)
    reasons = sum((p["reasons"] for p in parts), Counter())
    ends = [e for p in parts for e in p["ends"]]
    held = inside.sum(axis=0)
    cover = held / len(inside) if len(inside) else np.full(2, np.nan)
    ci = [binomtest(int(k), len(inside)).proportion_ci(0.95, method="exact") if len(inside) else None for k in held]
    return {"body": body, "kind": kind, "flights": add["total"], "found": add["found"] / add["total"],
            "found_of_fittable": add["found_fittable"] / max(add["fittable"], 1), "fittable": add["fittable"] / add["total"],
            "false": add["false"] / max(add["fitted"], 1), "fitted": add["fitted"], "joint_only": add["joint_only"],
            "coverage_I1_over_I3": float(cover[0]), "coverage_I2_over_I3": float(cover[1]),
            "held": held.tolist(), "intervals": len(inside),
            "coverage_ci": [[c.low, c.high] if c is not None else None for c in ci],
            "skipped": dict(reasons), "seconds": seconds, "files": len(parts), "files_clean": add["clean"],
            "answered": add["answered"], "answer_is_the_toss": add["same"],
            "end_error_ms": (1e3 * np.median(ends, axis=0)).tolist() if len(ends) else [np.nan, np.nan]}


def main(argv=None) -> int:
    """``fit_coverage.py [RECORDINGS] [--first-seed N] [--jobs N] [--json PATH]``."""
    import argparse
    import json

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recordings", nargs="?", type=int, default=40, help="recordings per cell (default 40)")
    parser.add_argument("kinds", nargs="*", metavar="KIND",
                        help=f"the kinds of recording (default all): {', '.join(map(repr, KINDS))}")
    parser.add_argument("--first-seed", type=int, default=1000, help="the first seed (default 1000)")
    parser.add_argument("--jobs", type=int, default=1, help="worker processes (default 1)")
    parser.add_argument("--json", help="also write the rows, with their counts, to this JSON file")
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    unknown = [k for k in args.kinds if k not in KINDS]
    if unknown:
        parser.error(f"unknown kind {unknown[0]!r}; allowed: {', '.join(map(repr, KINDS))}")
    print("| body | recordings | true flights | found and fitted | of the fittable | fittable | false | joint only | "
          "95 % interval holds I1/I3 | holds I2/I3 | not found | time (s) | start, end error (ms) | "
          "files without a false flight | answer is the toss's |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for body in ("racquet", "phone"):
        for kind in args.kinds or KINDS:
            r = campaign(body, kind, args.recordings, args.first_seed, args.jobs)
            rows.append(r)
            held = [f"{c:.1%} ({k}/{r['intervals']}; {lo:.0%}-{hi:.0%})" for c, k, (lo, hi) in
                    zip((r["coverage_I1_over_I3"], r["coverage_I2_over_I3"]), r["held"], r["coverage_ci"])]
            print(f"| {body} | {kind} | {r['flights']} | {r['found']:.1%} | {r['found_of_fittable']:.1%} | "
                  f"{r['fittable']:.1%} | {r['false']:.1%} of {r['fitted']} | {r['joint_only']} | {held[0]} | "
                  f"{held[1]} | {r['skipped']} | {r['seconds']:.0f} | "
                  f"{r['end_error_ms'][0]:.1f}, {r['end_error_ms'][1]:.1f} | {r['files_clean']}/{r['files']} | "
                  + (f"{r['answer_is_the_toss']}/{r['answered']} |" if r["answered"] else "- |"), flush=True)
    total = sum(r["flights"] for r in rows)
    found = sum(r["found"] * r["flights"] for r in rows) / total
    fittable = sum(r["fittable"] * r["flights"] for r in rows)
    of_fittable = sum(r["found_of_fittable"] * r["fittable"] * r["flights"] for r in rows) / fittable
    fitted = sum(r["fitted"] for r in rows)
    false = sum(r["false"] * r["fitted"] for r in rows) / fitted
    intervals = sum(r["intervals"] for r in rows)
    held_all = np.sum([r["held"] for r in rows], axis=0) / max(intervals, 1)
    print(f"\nall: {total} true flights, {found:.1%} found and fitted ({of_fittable:.1%} of the {fittable:.0f} fittable), "
          f"{false:.1%} of {fitted} fitted flights false; 95 % intervals hold I1/I3 in {held_all[0]:.1%}, I2/I3 in "
          f"{held_all[1]:.1%} of {intervals} flights")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
