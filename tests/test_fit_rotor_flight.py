"""Issue #30 item 5: the ratio fit (tumble fit, fit_recording) on a throw whose rotor spins up
inside, with no rotor input, says the flight is not a rigid body's rather than fit ratios.

The device of the issue on a 0.6 kg box (tumble.analysis.tensor.synthetic, taken at 500 Hz: the
4 kHz log takes the ratio fit minutes): its rotor idles, spins up to ~1300 rad/s within 0.1 s,
holds 0.2 s and brakes back to idle inside the flight. The rigid fit follows that within 1 % of
the rates (bent ratios, a strong drag), the budgets of rigid_body_check see no rise beyond what
drag and flex show, and the gyrostat whose rotor spins up steadily (tumble.analysis.fit.rotor)
finds no net gain (seeds 0 and 2: 9.5 +- 5.6 % and 4.9 +- 21 % of |L|). What refuses them is the
world-frame momentum budget with an internal momentum that steps (tumble.analysis.fit.budget):
it finds the spin-up and the brake, 0.19 s apart, along one body axis.
"""

from __future__ import annotations

import functools
import warnings

import numpy as np
import pytest

import tumble.analysis.fit.budget as budget
from tumble.analysis.fit import NoFlightError, find_flights, fit_recording
from tumble.analysis.fit.budget import momentum_steps
from tumble.analysis.fit.single import fit_solution
from tumble.analysis.fit.synthetic import synthetic_recording
from tumble.analysis.tensor.synthetic import combine, example_object, synthetic_throw, throw_times, true_device


@functools.cache
def _throw(seed: int, **kwargs):
    """The throw at 500 Hz, made once a run for each seed and options (read-only: seeds 0 and 2
    serve two tests each, ~0.3 s a throw)."""
    throw = synthetic_throw(seed, combine(true_device(), example_object()), **kwargs)
    t, w = throw.t[::8].copy(), throw.omega[::8].copy()
    t.flags.writeable = w.flags.writeable = False
    return t, w


def _verdicts(seed: int, **kwargs) -> list[tuple[str, str]]:
    """Each flight's status and reason, as find_flights (fit_recording's search) gives them."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return [(f.status, f.reason) for f in find_flights(*_throw(seed, **kwargs))]


def test_rotor_throws_that_are_refused_say_why():
    """Seed 1: the ratio fit finds no rigid flight in a rotor throw (the model does not fit)."""
    assert all(status != "ok" for status, _ in _verdicts(1))


@pytest.mark.parametrize("seed", [0, 5])
def test_a_rotor_spun_up_and_braked_within_the_flight_is_refused_naming_it(seed):
    """Seeds 0 and 5 hold in 5 of 5 runs with the fits' models changed by 1e-13
    (benchmarks/roundoff_audit.py). Seed 2 held in 4 of 5: where the finder cut its flight to
    0.22-0.84 s (0.20-0.91 s otherwise), the budget with the gyroscope's scale errors found the
    steps at 2.0 +- 0.36 % of |L|: 1.3 % less two sigma, under the 1.5 % it must pass (issue 38's note)."""
    verdicts = _verdicts(seed)
    assert all(status != "ok" for status, _ in verdicts)
    assert any(reason.startswith("not a rigid body: a rotor spun up or braked inside") for _, reason in verdicts), verdicts


def test_fit_recording_makes_no_answer_of_a_rotor_throw():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(NoFlightError, match="not a rigid body"):
            fit_recording(*_throw(0))


def test_the_same_throw_with_its_rotor_at_rest_is_fitted():
    """Seed 0 with the rotor never started: the same device, flight and sensors, fitted "ok"."""
    assert [status for status, _ in _verdicts(0, rotor_top=0.0)] == ["ok"]


def test_the_steps_found_are_the_rotors_spin_up_and_brake():
    """On seed 2's free flight the two steps lie within 30 ms of the firmware's spin-up and brake
    (0.16-0.17 s and ~0.36 s after the rotor's start, each a first-order change with a time
    constant of 29-38 ms: tumble.analysis.tensor.firmware), and the change is beyond the limit."""
    t, w = _throw(2)
    tt = throw_times(2)
    sel = (t > tt.release) & (t < tt.end - 0.01)
    keep = np.ones((sel.sum(), 3), bool)
    sol = fit_solution(t[sel], w[sel], keep, drag="quadratic", t0=t[sel][0])
    fit = momentum_steps(t[sel], w[sel], keep, sol)
    up, brake = tt.rotor + 0.165, tt.rotor + 0.36
    assert abs(fit.times[0] - up) < 0.03 and abs(fit.times[1] - brake) < 0.03, (fit.times, up, brake)
    assert fit.change - budget.K_SIGMA * fit.change_std > budget.MIN_CHANGE


def test_a_rigid_phone_whose_gyroscope_has_one_percent_scale_errors_is_no_rotor():
    """The flight of the synthetic recordings whose budget is the worst before the change was
    measured against the body's |I w| (phone, "many", seed 18, the toss at 9.4 s: scale errors
    -0.9, +0.3, +1.2 % turn the integrated attitude, and the budget's own |L| traded with them):
    its change stays far below the limit."""
    rec = synthetic_recording(18, body="phone", tosses=4, ending="mixed", hand=(3.0, 10.0))
    a, b = rec.flights[2]
    sel = (rec.t > a + 0.02) & (rec.t < b - 0.02)
    t, w = rec.t[sel], rec.omega[sel]
    keep = np.ones(w.shape, bool)
    fit = momentum_steps(t, w, keep, fit_solution(t, w, keep, drag="quadratic", t0=t[0]))
    assert fit.change - budget.K_SIGMA * fit.change_std < 0.5 * budget.MIN_CHANGE


def test_a_rigid_phone_with_a_gap_in_its_samples_is_no_rotor():
    """fit_coverage's phone "one toss", seed 1052 (400 Hz, the phone swung about, a landing): a
    0.16 s gap in the samples in flight; the budget with the scale errors' columns trades them
    with steps around the gap (13 +- 2 % of |L|), the budget without them sees none (0.4 %):
    the flight is fitted, not refused."""
    rec = synthetic_recording(1052, body="phone", tosses=1, ending="mixed", hand=(3.0, 10.0), rate=400.0)
    (a, b), = rec.flights
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        found = [f for f in find_flights(rec.t, rec.omega, events=rec.events) if f.start < b and f.end > a]
    assert [f.status for f in found] == ["ok"], [f.reason for f in found]
    f = found[0]
    assert np.max(np.diff(rec.t[f.first:f.stop])) > 0.1  # the gap
    t, w, keep = rec.t[f.first:f.stop], rec.omega[f.first:f.stop], np.ones((f.samples, 3), bool)
    with_scale, without = (momentum_steps(t, w, keep, f.solution, scale_errors=x) for x in (True, False))
    assert with_scale.change - budget.K_SIGMA * with_scale.change_std > budget.MIN_CHANGE
    assert without.change - budget.K_SIGMA * without.change_std < 0.5 * budget.MIN_CHANGE
