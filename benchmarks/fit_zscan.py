"""Where a coverage cell's misses come from: each found flight's z = (fitted - true) / stated std, by rate.

``python benchmarks/fit_zscan.py [BODY] [KIND] [--recordings N] [--no-flex] [--no-drag] [--jobs N]``:
the recordings of one cell of :mod:`fit_coverage` (seeds from 1000, the same draws), fitted whole;
printed per sample rate: the flights, the share whose 95 % intervals hold the true ratios, the mean
and the standard deviation of z for I1/I3 and I2/I3. A calibrated uncertainty gives mean z near 0
and sd z near 1; a model error that the parameters absorb shows as sd z above 1 and a mean off 0.
``--no-flex`` and ``--no-drag`` turn the generator's flexing body and its (strip-theory plate)
drag off, to see which one the fit does not hold (benchmarks/results/fit_coverage.md).
"""

from __future__ import annotations

import argparse
import sys
from collections import defaultdict
from concurrent.futures import ProcessPoolExecutor

import numpy as np
from fit_coverage import KINDS, stated_flights


def _flights(seed: int, body: str, kind: str, extra: dict) -> list[dict]:
    """The found flights of one recording that state their own ratios: rate, z, held."""
    rec, draw, found = stated_flights(seed, body, kind, **extra)
    rows = []
    for toss in found:
        fit, iv = toss.fit, toss.fit.ratios_interval
        rows.append({"rate": draw.get("rate", 100.0), "z": ((fit.ratios - rec.ratios) / fit.ratios_std).tolist(),
                     "held": [bool(iv[k, 0] <= rec.ratios[k] <= iv[k, 1]) for k in (0, 1)]})
    return rows


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("body", nargs="?", default="racquet")
    parser.add_argument("kind", nargs="?", default="one toss", choices=list(KINDS))
    parser.add_argument("--recordings", type=int, default=100)
    parser.add_argument("--no-flex", action="store_true", help="the generator's body does not flex")
    parser.add_argument("--no-drag", action="store_true", help="the generator's body feels no air drag")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    extra = {**({"flex": False} if args.no_flex else {}), **({"drag": 0.0} if args.no_drag else {})}
    seeds = range(1000, 1000 + args.recordings)
    with ProcessPoolExecutor(args.jobs) as pool:
        parts = pool.map(_flights, seeds, [args.body] * len(seeds), [args.kind] * len(seeds), [extra] * len(seeds))
        rows = [row for part in parts for row in part]
    by_rate = defaultdict(list)
    for row in rows:
        by_rate[row["rate"]].append(row)
    print("| rate (Hz) | flights | held I1/I3, I2/I3 | mean z | sd z |\n|---|---|---|---|---|")
    for rate, group in sorted(by_rate.items()) + [("all", rows)]:
        z, held = np.array([r["z"] for r in group]), np.array([r["held"] for r in group])
        print(f"| {rate} | {len(group)} | {held.mean(0)[0]:.0%}, {held.mean(0)[1]:.0%} | "
              f"{z.mean(0)[0]:+.2f}, {z.mean(0)[1]:+.2f} | {z.std(0)[0]:.2f}, {z.std(0)[1]:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
