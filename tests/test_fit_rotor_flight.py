"""Issue #30 item 5: the ratio fit (tumble fit, fit_recording) on a throw whose rotor spins up
inside, with no rotor input, should say the flight is not a rigid body's rather than fit ratios.

Measured (benchmarks in the #30 report): of 12 such synthetic throws (the device of the issue on a
0.6 kg box, tumble.analysis.tensor.synthetic), find_flights fitted 8 as "ok" rigid flights. The
momentum and energy budgets of rigid_body_check see only rises, and the rotor taking momentum
from the body looks like drag; the fall of |L| within 0.1 s (17-31 %) and the head of the
flight the fit leaves out (0.1-0.17 s) lie inside what the ratio fit's own synthetic rigid
tosses show (up to 9 % of |L| and 21 % of 2E within 0.1 s, heads up to 0.39 s). Nor does the
bound that a dissipative per-axis drag puts on the whole flight's ``ln(E1/E0) / ln(L1/L0)``
(between ``2 I1/I3`` and ``2 I3/I1``): 13 of the 15 rotor throws fitted "ok" at 500 Hz lie inside
it. Issue #39's gyrostat comparison (tumble.analysis.fit.rotor: a rotor spinning up steadily
along a body axis) refuses the fit generator's slow spin-ups, but this device's rotor goes from
rest to its idle (~200 rad/s), up to ~1300 rad/s within 0.1 s, holds 0.2 s and brakes back to
idle inside the fitted flight, which a steady spin-up does not describe: the gain it fits on
seeds 0 and 2 is 9.5 +- 5.6 % and 4.9 +- 21 % of |L|, nothing a test can act on, and a rotor
with a free piecewise-linear profile (14 knots, tried) still leaves the residuals 4 times their
noise floor (measured). So this test is a strict expected failure until a test that separates
them is found.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from tumble.analysis.fit import NoFlightError, fit_recording
from tumble.analysis.tensor.synthetic import combine, example_object, synthetic_throw, true_device


def _verdicts(seed: int) -> list[str]:
    throw = synthetic_throw(seed, combine(true_device(), example_object()))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            fit = fit_recording(throw.t[::8], throw.omega[::8])  # 500 Hz: the 4 kHz log takes the ratio fit minutes
        except NoFlightError as error:
            return [str(error)]
    return [toss.status for toss in fit.tosses]


def test_rotor_throws_that_are_refused_say_why():
    """Seed 1: the ratio fit finds no rigid flight in a rotor throw (the model does not fit)."""
    assert "ok" not in _verdicts(1)


@pytest.mark.xfail(strict=True, reason="issue #30 item 5: a rotor spinning up with the body's |L| passes as a rigid "
                                       "flight (module docstring)")
def test_rotor_throws_are_never_fitted_as_rigid_bodies():
    assert all("ok" not in _verdicts(seed) for seed in (0, 2))
