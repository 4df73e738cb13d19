"""A lead for a model-error term: how far the ratios move between the linear and the quadratic drag law.

``python benchmarks/fit_dragspread.py [BODY] [KIND] [--recordings N] [--jobs N]``: the recordings of
one cell of :mod:`fit_coverage` (seeds from 1000), fitted whole; each found flight that states its
own ratios is fitted again on its window with ``drag="linear"`` and ``drag="quadratic"``, and the
coverage of the 95 % intervals is printed as stated and with ``k |linear - quadratic|`` added to
the standard uncertainty in quadrature (k = 1, 0.5). A drag that neither law describes (the
synthetic racquet's plate) moves the ratios between them; a weak one (the phone's) does not
(benchmarks/results/fit_coverage.md, "The racquet, one toss per file"). Not in tumble's
uncertainty: a lead, measured.
"""

from __future__ import annotations

import argparse
import sys
import warnings
from concurrent.futures import ProcessPoolExecutor

import numpy as np
from fit_coverage import KINDS, stated_flights

from tumble.analysis.fit import fit_rotation


def _flights(seed: int, body: str, kind: str) -> list[dict]:
    """Each found flight's ratios, standard uncertainties, the truth, and its window refitted with each drag law."""
    rec, _, found = stated_flights(seed, body, kind)
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for toss in found:
            sel = (rec.t >= toss.start) & (rec.t <= toss.end)
            laws = {law: fit_rotation(rec.t[sel], rec.omega[sel], drag=law).ratios for law in ("linear", "quadratic")}
            rows.append({"fit": toss.fit.ratios, "std": toss.fit.ratios_std, "true": rec.ratios,
                         "spread": np.abs(laws["linear"] - laws["quadratic"])})
    return rows


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("body", nargs="?", default="racquet")
    parser.add_argument("kind", nargs="?", default="one toss", choices=list(KINDS))
    parser.add_argument("--recordings", type=int, default=100)
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    seeds = range(1000, 1000 + args.recordings)
    with ProcessPoolExecutor(args.jobs) as pool:
        rows = [r for part in pool.map(_flights, seeds, [args.body] * len(seeds), [args.kind] * len(seeds)) for r in part]
    fit, std, true, spread = (np.array([r[k] for r in rows]) for k in ("fit", "std", "true", "spread"))
    print(f"{args.body}, {args.kind}: {len(rows)} flights; median |linear - quadratic| / std "
          f"{np.median(spread / std, axis=0).round(2).tolist()}")
    for k in (0.0, 0.5, 1.0):
        held = np.abs(fit - true) <= 1.96 * np.sqrt(std ** 2 + (k * spread) ** 2)
        print(f"k = {k}: 95 % intervals hold I1/I3 in {held.mean(0)[0]:.1%}, I2/I3 in {held.mean(0)[1]:.1%}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
