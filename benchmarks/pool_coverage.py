"""The pooled answer of whole recordings: its 95 % interval's coverage and its width (a few minutes).

``python benchmarks/pool_coverage.py [RECORDINGS] [--first-seed N] [--json PATH]``: for each body
(racquet, phone) and each kind of recording, ``RECORDINGS`` synthetic recordings (default 40,
seeds from 1000), each with its own gyroscope (scale errors of 0.5 % per axis, bias, coloured
noise, flex, drag), fitted whole (:func:`tumble.analysis.fit.fit_recording`). Of the files whose
answer pools two or more flights, printed per row:

- **holds**: the share whose pooled 95 % interval holds the true I1/I3 and I2/I3, with its exact
  (Clopper-Pearson) 95 % interval;
- **width**: the pooled standard uncertainty over the smallest of its flights' own (each ratio;
  median and 90th percentile): pooling flights of one gyroscope should not be wider than its best
  flight, and an interval is honest only when it is also narrow enough to use;
- **wider than 2x**: the files whose pooled uncertainty exceeds twice the best flight's;
- **chi2/dof**: the median Birge statistic of the flights' own ratios about one another.

The kinds: ``tidy`` and ``many`` as in ``benchmarks/fit_coverage.py``, and ``slow``: three tosses
at 100 Hz spun at 6-10 rad/s (a walkthrough's recording, whose three consistent tosses pooled to
``0.201 +- 0.17`` when the flights' scatter by the common scale error counted as disagreement).
"""

from __future__ import annotations

import sys
import time
import warnings
from pathlib import Path

import numpy as np

from tumble.analysis.fit import fit_recording
from tumble.analysis.fit.synthetic import synthetic_recording

sys.path.insert(0, str(Path(__file__).parent))
from fit_coverage import KINDS as FIT_KINDS  # noqa: E402  (the benchmarks' own module)

#: The kinds of recording, as synthetic_recording's arguments (a callable draws per seed).
KINDS = {"tidy": FIT_KINDS["tidy"], "many": FIT_KINDS["many"],
         "slow": lambda rng: dict(tosses=3, rate=100.0, spin=(6.0, 10.0))}


def recording(body: str, kind: str, seed: int):
    """The synthetic recording of a cell's seed (:data:`KINDS`), each seed with its own gyroscope."""
    return synthetic_recording(seed, body=body, **KINDS[kind](np.random.default_rng(seed)))


def quietly(fit, rec):
    """``fit(t, omega, events=...)`` of ``rec`` with its warnings silenced, or None where it finds no flight."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            return fit(rec.t, rec.omega, events=rec.events)
        except ValueError:  # no usable flight
            return None


def _one_recording(body: str, kind: str, seed: int) -> dict | None:
    """The pooled answer of one recording against the truth, or None when it pools fewer than two flights."""
    rec = recording(body, kind, seed)
    fit = quietly(fit_recording, rec)
    if fit is None:
        return None
    own = [toss.fit.ratios_std for toss in fit.tosses if toss.status == "ok" and toss.fit is not None and not toss.reason]
    if fit.tosses_used < 2 or not own:
        return None
    iv = fit.pooled.ratios_interval
    return {"holds": [bool(iv[0, 0] <= rec.ratios[0] <= iv[0, 1]), bool(iv[1, 0] <= rec.ratios[1] <= iv[1, 1])],
            "width": (fit.pooled.ratios_std / np.min(own, axis=0)).tolist(), "chi2_dof": float(fit.chi2_dof)}


def cell(body: str, kind: str, recordings: int = 40, first_seed: int = 1000) -> dict:
    """One row: a body, a kind of recording, ``recordings`` seeds from ``first_seed``."""
    from scipy.stats import binomtest

    t0 = time.perf_counter()
    parts = [p for p in (_one_recording(body, kind, s) for s in range(first_seed, first_seed + recordings)) if p]
    holds = np.array([p["holds"] for p in parts], bool).reshape(-1, 2)
    width = np.array([p["width"] for p in parts]).reshape(-1, 2)
    held = holds.sum(axis=0)
    ci = [binomtest(int(k), len(parts)).proportion_ci(0.95, method="exact") for k in held] if parts else []
    return {"body": body, "kind": kind, "files": recordings, "pooled": len(parts), "held": held.tolist(),
            "coverage_ci": [[c.low, c.high] for c in ci],
            "width_median": np.median(width, axis=0).tolist(), "width_p90": np.percentile(width, 90, axis=0).tolist(),
            "wider_than_2x": int(np.sum(np.any(width > 2.0, axis=1))),
            "chi2_dof_median": float(np.nanmedian([p["chi2_dof"] for p in parts])), "seconds": time.perf_counter() - t0}


def main(argv=None) -> int:
    """``pool_coverage.py [RECORDINGS] [--first-seed N] [--json PATH]``."""
    import argparse
    import json

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recordings", nargs="?", type=int, default=40, help="recordings per cell (default 40)")
    parser.add_argument("--first-seed", type=int, default=1000, help="the first seed (default 1000)")
    parser.add_argument("--json", help="also write the rows to this JSON file")
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    print("| body | recordings | pooled files | 95 % interval holds I1/I3 | holds I2/I3 | width I1/I3 (median, p90) | "
          "width I2/I3 (median, p90) | wider than 2x | chi2/dof (median) | time (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for body in ("racquet", "phone"):
        for kind in KINDS:
            r = cell(body, kind, args.recordings, args.first_seed)
            rows.append(r)
            n = r["pooled"]
            held = [f"{k / n:.1%} ({k}/{n}; {lo:.0%}-{hi:.0%})" for k, (lo, hi) in zip(r["held"], r["coverage_ci"])]
            width = [f"{m:.2f}, {p:.2f}" for m, p in zip(r["width_median"], r["width_p90"])]
            print(f"| {body} | {kind} | {n} of {r['files']} | {held[0]} | {held[1]} | {width[0]} | {width[1]} | "
                  f"{r['wider_than_2x']} | {r['chi2_dof_median']:.2f} | {r['seconds']:.0f} |", flush=True)
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
