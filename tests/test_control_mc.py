"""Monte Carlo of B-dot detumbling (issue 21): the batched kernel against the one-body closed
loop, and the distribution's response to the gain."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.bdot import BDot, bdot_gain
from tumble.dynamics.control.detumble import detumble_batch
from tumble.dynamics.models.actuators import Magnetorquers
from tumble.dynamics.environment.magnetic import DipoleField
from tumble.dynamics.environment.orbit import CircularOrbit
from tumble.ensemble.detumble import detumble_cases, detumble_monte_carlo

ORBIT = CircularOrbit(altitude=500e3, inclination=1.69995)
MOMENTS = (0.0067, 0.0419, 0.0419)  # kg m^2, a 3U CubeSat
GAIN = bdot_gain(ORBIT.mean_motion, ORBIT.inclination, MOMENTS[0])  # N m s, Avanzini & Giulietti
THRESHOLD = math.radians(0.5)  # rad/s


def test_batch_matches_simulate_controlled_case_by_case():
    """Two dispersed bodies at once against DOP853 one at a time: RK4 at 4 substeps agrees to
    ~1e-8 rad/s over 200 control steps, the dipole clipping (0.2 A m^2) included."""
    cases = detumble_cases(2, moments=MOMENTS, rate_min=0.2, rate_max=0.35, seed=5)
    moments = np.sort(cases.moments, axis=1)  # simulate_controlled wants I1 <= I2 <= I3
    mtq = Magnetorquers(0.2)
    batch = detumble_batch(moments, cases.omega0, cases.quat0, field=DipoleField(ORBIT), gmst0=cases.gmst0,
                           gain=4 * GAIN, magnetorquers=mtq, period=1.0, t_end=200.0)
    for i in range(2):
        run = simulate_controlled(moments[i], cases.omega0[i], t_end=200.0, attitude0=cases.quat0[i],
                                  controller=BDot(4 * GAIN, period=1.0, form="normalized"),
                                  field=DipoleField(ORBIT, gmst0=float(cases.gmst0[i])), magnetorquers=mtq)
        assert np.max(np.abs(batch.rate[i] - run.rate)) < 1e-7
        assert np.max(np.abs(run.dipole)) == pytest.approx(0.2, rel=1e-12)  # the rods clip
        assert run.rate[-1] < 0.9 * run.rate[0]


def test_detumble_time_matches_the_run_definition():
    """``DetumbleBatch.detumble_time`` is ``ControlledRun.detumble_time`` (last crossing + one step)."""
    from tumble.dynamics.control.detumble import DetumbleBatch

    t = np.arange(5.0)
    rate = np.array([[3.0, 2.0, 0.5, 2.0, 0.5], [0.5, 0.4, 0.3, 0.2, 0.1], [3.0, 3.0, 3.0, 3.0, 3.0]])
    out = DetumbleBatch(t, rate, np.zeros((3, 3)), np.zeros((3, 4))).detumble_time(1.0)
    assert out[0] == 4.0 and out[1] == 0.0 and math.isnan(out[2])


def test_monte_carlo_detumbles_faster_with_more_gain():
    """20 cases from 2-3.5 deg/s: at half A&G's gain some cases still tumble at 6000 s, at
    A&G's all are detumbled, and above it the 95th percentile falls (k scales the damping k / I)."""
    cases = detumble_cases(20, moments=MOMENTS, rate_min=0.03, rate_max=0.06, seed=3)
    fractions, p95 = [], []
    for scale in (0.5, 1.0, 2.0, 4.0):
        mc = detumble_monte_carlo(cases, field=DipoleField(ORBIT), gain=scale * GAIN, magnetorquers=Magnetorquers(0.2),
                                  period=5.0, t_end=6000.0, threshold=THRESHOLD)
        fractions.append(mc.detumbled)
        p95.append(mc.percentile(95.0))
    assert fractions[0] < fractions[1] == 1.0  # half A&G's gain leaves cases tumbling at 6000 s
    assert p95[1] > p95[2] > p95[3]
    assert math.isnan(p95[0])


def test_cases_do_not_depend_on_the_chunking():
    cases = detumble_cases(6, moments=MOMENTS, rate_min=0.05, rate_max=0.1, seed=7)
    kw = {"field": DipoleField(ORBIT), "gain": GAIN, "magnetorquers": Magnetorquers(0.2), "period": 5.0, "t_end": 300.0,
              "threshold": 0.06}
    a = detumble_monte_carlo(cases, chunk=6, **kw).times
    b = detumble_monte_carlo(cases, chunk=4, **kw).times
    np.testing.assert_array_equal(a, b)


def test_bad_inputs_name_the_field():
    with pytest.raises(ValueError, match="rate_max"):
        detumble_cases(3, moments=MOMENTS, rate_min=0.2, rate_max=0.1)
    with pytest.raises(ValueError, match="substeps"):
        detumble_batch([MOMENTS], [[0.1, 0.0, 0.0]], [[0.0, 0.0, 0.0, 1.0]], field=DipoleField(ORBIT), gmst0=0.0,
                       gain=GAIN, magnetorquers=Magnetorquers(0.2), period=1.0, t_end=10.0, substeps=0)


@pytest.mark.parametrize("spread", [0.1, 0.5, 0.9])
def test_the_monte_carlo_draws_only_bodies_that_exist(spread):
    """Issue 27, item 4: the docs' 3U CubeSat at the default spread kept 39 bodies in 1000 with
    I1 + I2 < I3 (173 of 200 at spread 0.9). Every case's moments now meet the triangle inequality,
    the cases that met it are the ones drawn before, and each moment stays within the spread."""
    from tumble.validation import breaks_triangle

    nominal = np.array([0.0067, 0.0419, 0.0419])
    cases = detumble_cases(1000, moments=nominal, rate_min=0.1, rate_max=0.3, moment_spread=spread, seed=3)
    assert not breaks_triangle(cases.moments).any()
    assert np.all(np.abs(cases.moments / nominal - 1.0) <= spread + 1e-12)
    # the redraws come after every other draw: the rates, attitudes and seeds are the ones drawn without them
    again = detumble_cases(1000, moments=nominal, rate_min=0.1, rate_max=0.3, moment_spread=spread, seed=3)
    np.testing.assert_array_equal(again.moments, cases.moments)
    rng = np.random.default_rng(3)
    direction = rng.standard_normal((1000, 3))
    direction /= np.linalg.norm(direction, axis=1)[:, None]
    np.testing.assert_array_equal(cases.omega0, direction * rng.uniform(0.1, 0.3, 1000)[:, None])
    first = nominal * (1.0 + spread * rng.uniform(-1.0, 1.0, (1000, 3)))
    kept = ~breaks_triangle(first)
    assert 0 < kept.sum() < 1000  # the spread does break some (the claim is not empty)
    np.testing.assert_array_equal(cases.moments[kept], first[kept])


def test_an_impossible_nominal_body_is_refused():
    with pytest.raises(ValueError, match="triangle inequality"):
        detumble_cases(10, moments=[0.01, 0.02, 0.05], rate_min=0.1, rate_max=0.3)
