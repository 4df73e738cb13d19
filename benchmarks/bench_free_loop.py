"""Torques the engine's terms do not hold, compiled on the closed loop's kernel (``dynamics/control/free_loop.py``)
against the same models called from Python on scipy's DOP853 (what ``simulate`` ran before).

Two cases, one orbit each, ``simulate``'s default (``auto``: dop853 at rtol 1e-10), 500 samples:

- the gravity gradient along an ellipse (``KeplerOrbit(8000 km, e = 0.1)``), a body of moments
  (10, 12, 15) kg m^2 tumbling at 0.1 rad/s;
- a residual dipole of (0.3, -0.1, 0.2) A m^2 in the tilted dipole field along a 500 km circular
  orbit, beside that orbit's gravity gradient, a small satellite (0.03, 0.04, 0.05) kg m^2 at
  0.1 rad/s.

The baseline is the same model wrapped in a ``FunctionTorque`` (a Python function: scipy's path).
Both meet the same tolerance; their samples agree to ~1e-8 relative over an orbit (the tables of
the orbit's position and of the field: 1e-11). There is no peer for these models in
``../shared/peers``: the ratio is against tumble's own earlier path, not a competitor.
"""

from __future__ import annotations

import numpy as np

import tumble
from tumble.dynamics import (CircularOrbit, DipoleField, FunctionTorque, GravityGradient, KeplerOrbit,
                             OrbitGravityGradient, ResidualDipole)


def _cases():
    ellipse = KeplerOrbit(8000e3, 0.1)
    big = tumble.MassProperties.from_moments((10.0, 12.0, 15.0))
    gg = OrbitGravityGradient(ellipse).bind(big)
    circle = CircularOrbit(altitude=500e3, inclination=1.2)
    small = tumble.MassProperties.from_moments((0.03, 0.04, 0.05))
    dipole = ResidualDipole((0.3, -0.1, 0.2), DipoleField(circle, gmst0=0.4)) + \
        GravityGradient(orbit_radius=circle.radius).bind(small)
    python_gg = FunctionTorque(gg, "world")
    python_dipole = FunctionTorque(lambda t, w, R: dipole(t, w, R))  # the sum is in the body frame

    def run(body, torque, period):
        return lambda: tumble.simulate(body, [0.05, 0.1, 0.02], t_end=period, torque=torque)

    return [
        ("gravity gradient along an ellipse (e = 0.1), one orbit, compiled loop", run(big, gg, ellipse.period),
         run(big, python_gg, ellipse.period), "the model from Python (scipy DOP853)", None),
        ("residual dipole in the dipole field + gravity gradient, one orbit, compiled loop",
         run(small, dipole, circle.period), run(small, python_dipole, circle.period),
         "the models from Python (scipy DOP853)", None),
    ]


def cases():
    """``(title, candidate, baseline, baseline name, target)`` per case, for ``benchmarks/run.py``."""
    candidates = _cases()
    for _, fast, slow, _, _ in candidates:  # compile, and check that both paths give the same motion
        a, b = fast(), slow()
        assert np.abs(a.omega - b.omega).max() < 1e-6 * np.abs(b.omega).max()
    return candidates


if __name__ == "__main__":
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from run import paired_times

    for title, fast, slow, name, _ in cases():
        stats = paired_times(fast, slow, repeat=3)
        print(f"{title}: {stats['seconds'] * 1e3:.1f} ms [{stats['seconds_range'][0] * 1e3:.1f}-"
              f"{stats['seconds_range'][1] * 1e3:.1f}] against {name} {stats['baseline_seconds']:.2f} s: "
              f"{1 / stats['ratio']:.0f}x")
