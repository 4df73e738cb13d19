"""When a spin under the gravity gradient follows the free body's flips (docs/gravity-gradient.md).

The T-handle in a 5,400 s circular orbit, spun at ``k n`` (``n`` the mean motion) along three
directions near its intermediate axis, run 60,000 s (18,000 s at ``100 n``) with dop853; its mean
flip interval (:func:`tumble.stability_report`) against the free body's closed form
(:func:`tumble.flip_interval`), beside the gradient's ``3 (n / omega)^2`` over the spin's distance
from the separatrix (:func:`tumble.analysis.gravity_stability.separatrix_offset`): the ratio
:data:`~tumble.analysis.gravity_stability.SEPARATRIX_REACH` bounds, and the summary's
``free_body``.

Run: ``python benchmarks/gravity_free_body.py`` (about a minute); results in
benchmarks/results/gravity_free_body.md.
"""

from __future__ import annotations

import numpy as np

import tumble
from tumble.analysis.gravity_stability import separatrix_offset, spin_beside_orbit


def main() -> None:
    gg = tumble.GravityGradient(orbit_period=5400.0)
    n, body = gg.mean_motion, tumble.t_handle()
    I = np.asarray(body.principal_moments)
    print("| direction | spin / n | offset | 3 (n/omega)^2 / offset | flips | off the closed form | free_body |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for direction in ((0.25, 1.0, 0.3), (0.05, 1.0, 0.05), (0.01, 1.0, 0.01)):
        for k in (10, 30, 100):
            w0 = np.array(direction) / np.linalg.norm(direction) * k * n
            t_end = 60000.0 if k <= 30 else 18000.0
            run = tumble.simulate(body, w0, torque=gg, t_end=t_end, samples=int(t_end * k * n * 20) + 1, method="dop853")
            report = tumble.stability_report(run)
            off = separatrix_offset(I, w0)
            closed = float(tumble.flip_interval(w0, I))
            print(f"| {direction} | {k} | {off:.2g} | {3 / k**2 / off:.2g} | {report['flips']} | "
                  f"{100 * (report['flip_period'] / closed - 1):+.1f} % | {spin_beside_orbit(I, w0, n)['free_body']} |")


if __name__ == "__main__":
    main()
