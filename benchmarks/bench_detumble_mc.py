"""Monte Carlo of B-dot detumbling (issue 21): detumble time over dispersed cases, and its figure.

The 3U CubeSat of ``examples/control/detumble.toml`` (moments (0.0067, 0.0419, 0.0419) kg m^2,
0.2 A m^2 rods, normalised B-dot at Avanzini & Giulietti's gain, a 1 s control period,
threshold 0.5 deg/s) in the 500 km sun-synchronous orbit, for two orbits (11,400 s), without
gravity gradient or sensor noise. Dispersed: the initial rate uniform in 5-20 deg/s in a
uniform direction, each moment +-10 % (uniform), the field epoch (Earth angle) uniform, the
attitude uniform. ``tumble.ensemble.detumble_monte_carlo`` (RK4 over chunks of cases, two
substeps a period, each case compiled: ``tumble.dynamics.methods.compiled_detumble``);
``--quick`` runs 500 cases. Writes the table, the JSON and ``detumble_mc.png`` (histogram and CDF, with the median and the 95th percentile).
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import numpy as np

CASES = int(os.environ.get("TUMBLE_DETUMBLE_MC_CASES", "10000"))


def run(out: Path, quick: bool = False) -> str:
    """Run the Monte Carlo, write the JSON and the figure, return the markdown."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from tumble.dynamics.controllers import bdot_gain
    from tumble.dynamics.models.actuators import Magnetorquers
    from tumble.dynamics.models.magnetic import DipoleField
    from tumble.dynamics.models.orbit import CircularOrbit
    from tumble.ensemble.detumble import detumble_cases, detumble_monte_carlo

    n = 500 if quick else CASES
    orbit = CircularOrbit(altitude=500e3, inclination=1.69995)
    moments = (0.0067, 0.0419, 0.0419)
    gain = bdot_gain(orbit.mean_motion, orbit.inclination, moments[0])
    threshold = math.radians(0.5)
    cases = detumble_cases(n, moments=moments, rate_min=math.radians(5.0), rate_max=math.radians(20.0),
                           moment_spread=0.1, seed=2024)
    mc = detumble_monte_carlo(cases, field=DipoleField(orbit), gain=gain, magnetorquers=Magnetorquers(0.2),
                              period=1.0, t_end=11400.0, threshold=threshold, substeps=2, chunk=2500)
    median, p95 = mc.percentile(50.0), mc.percentile(95.0)
    row = {"cases": n, "seconds": mc.seconds, "seconds_per_case": mc.seconds / n, "detumbled": mc.detumbled,
           "median_s": median, "p95_s": p95, "max_s": float(np.nanmax(mc.times)), "gain_N_m_s": gain,
           "t_end_s": 11400.0, "threshold_rad_s": threshold}
    (out / "bench_detumble_mc.json").write_text(json.dumps(row, indent=2) + "\n")
    t = np.sort(mc.times[np.isfinite(mc.times)]) / 60.0
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    ax1.hist(t, bins=50, color="tab:blue")
    ax1.set_xlabel("detumble time (min)")
    ax1.set_ylabel("cases")
    ax2.plot(t, np.arange(1, len(t) + 1) / n, color="tab:blue")
    for value, label in ((median, "median"), (p95, "95th percentile")):
        if math.isfinite(value):
            for ax in (ax1, ax2):
                ax.axvline(value / 60.0, color="k", ls="--" if label == "median" else ":", lw=1)
            ax2.annotate(f"{label} {value / 60:.0f} min", (value / 60.0, 0.05 if label == "median" else 0.15))
    ax2.set_xlabel("detumble time (min)")
    ax2.set_ylabel("fraction detumbled")
    ax2.set_ylim(0, 1)
    fig.suptitle(f"B-dot detumble of a 3U CubeSat, {n} dispersed cases (5-20 deg/s, moments +-10 %, field epoch)")
    fig.tight_layout()
    fig.savefig(out / "detumble_mc.png", dpi=110)
    plt.close(fig)
    return "\n".join([
        "# bench_detumble_mc", "",
        "| cases | wall time (s) | per case (ms) | detumbled | median (s) | 95th percentile (s) | max (s) |",
        "|---|---|---|---|---|---|---|",
        (f"| {n} | {mc.seconds:.1f} | {1e3 * mc.seconds / n:.2f} | {mc.detumbled:.4f} | {median:.0f} | {p95:.0f} "
        f"| {row['max_s']:.0f} |"), ""])
