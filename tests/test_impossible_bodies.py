"""Issue 27 item 4 beyond the detumble Monte Carlo: every function that takes principal moments
refuses moments no body has (``I1 + I2 < I3``, Goldstein sec. 5.4), naming the field, the value as
written and the rule, through the one validator ``tumble.validation.check_moments``. On main the
stability, period and gravity-gradient functions (and the MRP controller) took ``[1, 1, 3]``,
whose formulas hold for any positive triple, and answered for a body that cannot exist."""

from __future__ import annotations

import numpy as np
import pytest

from tumble.analysis import periods, stability
from tumble.analysis.gravity_stability import gravity_gradient_ratios
from tumble.dynamics import CircularOrbit, KeplerOrbit, OrbitGravityGradient, gravity_gradient_of
from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.bdot import BDot
from tumble.dynamics.control.controllers import MRPFeedback
from tumble.dynamics.models.actuators import ReactionWheels
from tumble.dynamics.models.gravity import GravityGradient
from tumble.validation import breaks_triangle

IMPOSSIBLE = [1.0, 1.0, 3.0]  # an oblate "top" with I3 > I1 + I2: no distribution of positive mass
W = [0.3, 0.0, 1.0]

CALLS = {
    "flip_interval": lambda I: stability.flip_interval(W, I),
    "flip_interval_asymptotic": lambda I: stability.flip_interval_asymptotic(W, I),
    "circulation_axis": lambda I: stability.circulation_axis(W, I),
    "perturbation_exponent": lambda I: stability.perturbation_exponent(I, 3, 1.0),
    "linearised_rate": lambda I: stability.linearised_rate(I, 3, 1.0),
    "stable_spin_range": lambda I: stability.stable_spin_range([1.0, 1.5, 3.0] if I == IMPOSSIBLE else I, 1.0),
    "period": lambda I: periods.period(W, I),
    "montgomery_angle": lambda I: periods.montgomery_angle(W, I),
    "polhode_solid_angle": lambda I: periods.polhode_solid_angle(W, I),
    "precession_per_period": lambda I: periods.precession_per_period(W, I),
    "symmetric_top_rates": lambda I: periods.symmetric_top_rates(W, I),
    "npa_periods": lambda I: periods.npa_periods(W, I),
    "gravity_gradient_ratios": lambda I: gravity_gradient_ratios(I),
    "GravityGradient(moments=)": lambda I: GravityGradient(orbit_period=5400.0, moments=I),
    "GravityGradient.bind": lambda I: GravityGradient(orbit_period=5400.0).bind(I),
    "gravity_gradient_of(circular).bind": lambda I: gravity_gradient_of(CircularOrbit(altitude=500e3)).bind(I),
    "gravity_gradient_of(kepler).bind": lambda I: gravity_gradient_of(KeplerOrbit(7000e3, 0.01)).bind(I),
    "OrbitGravityGradient(moments=)": lambda I: OrbitGravityGradient(KeplerOrbit(7000e3), moments=I),
    "MRPFeedback(moments=)": lambda I: MRPFeedback(K=1e-3, P=2e-2, period=0.5, moments=I,
                                                   wheels=ReactionWheels(np.eye(3), inertia=1e-5)),
    "simulate_controlled": lambda I: simulate_controlled(I, [0.0, 0.0, 0.1], t_end=1.0, controller=BDot(gain=1e4, period=1.0)),
}


@pytest.mark.parametrize("name", CALLS)
def test_moments_no_body_has_are_refused_with_the_value_as_written(name):
    assert breaks_triangle(IMPOSSIBLE)
    written = [1.0, 1.5, 3.0] if name == "stable_spin_range" else IMPOSSIBLE  # one with an intermediate axis
    with pytest.raises(ValueError, match=r"^moments = \[" + ", ".join(map(str, written)) + r"\] breaks the triangle "
                                         r"inequality I1 \+ I2 >= I3 \(kg m\^2\): no distribution of positive mass has them"):
        CALLS[name](IMPOSSIBLE)


@pytest.mark.parametrize("name", ["flip_interval", "period", "montgomery_angle", "npa_periods", "gravity_gradient_ratios"])
def test_a_batch_names_its_first_impossible_body(name):
    batch = [[1.0, 2.0, 3.0], [2.0, 2.0, 3.0], [1.0, 2.0, 3.5], [1.0, 1.0, 3.0]]
    with pytest.raises(ValueError, match=r"^moments\[2\] = \[1.0, 2.0, 3.5\] breaks the triangle inequality"):
        CALLS[name](batch)


@pytest.mark.parametrize("moments", [[1.0, 1.0, 2.0], [2.0, 2.5, 4.5], [1.0, 3.0, 3.0]])
def test_the_planar_limit_and_prolate_tops_are_bodies(moments):
    """A thin disc (I3 = 2 I1), a flat plate (I3 = I1 + I2) and a rod-like prolate top are taken:
    the limit of the triangle inequality is a body (to 1e-9 of the trace)."""
    assert np.isfinite(periods.period(W, moments))
    assert np.all(np.isfinite(gravity_gradient_ratios(moments)))
    assert GravityGradient(orbit_period=5400.0).bind(moments).moments == tuple(moments)
