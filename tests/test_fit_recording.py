"""Whole recordings of real-looking tosses (tumble.analysis.fit: flights, recording, synthetic;
tumble.commands.fit; tumble.dynamics.methods.exact_omega and drag).

The recordings come from :func:`tumble.analysis.fit.synthetic.synthetic_recording`: Euler's
equations by DOP853 with strip-theory plate drag (not the fit's per-axis drag model), flex,
throws, catches, holds, pauses, and a phone gyroscope's jitter, drops, bias, scale errors,
coloured noise, quantisation and clipping. The statistical claims are checked by coverage over
seeded trials; the kernels against independent routes (the double-double exact solution,
DOP853, scipy's Rotation, closed forms).
"""

from __future__ import annotations

import json
import re
import zipfile

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from tumble.analysis.fit import InadequateFitWarning, find_flights, fit_recording, fit_rotation, saturation_mask
from tumble.analysis.fit.model import rotvec_matrix
from tumble.analysis.fit.recording import JOINT_ONLY
from tumble.analysis.fit.synthetic import FULL_SCALE, TOSS_BODIES, example_recording, synthetic_recording
from tumble.analysis.fit.triangle import EDGES, S_MIN, ratios, square
from tumble.analysis.fit.uncertainty import autocorrelation_time, birge_chi2
from tumble.cli import main
from tumble.dynamics.models.drag import drag_omega
from tumble.dynamics.methods.exact_batch import free_rotation_batch
from tumble.dynamics.methods.exact_omega import free_omega
from tumble.io.gyrodata import read_recording

from test_fit import EXAMPLE

RACQUET_EXAMPLE = EXAMPLE.parent / "racquet_tosses.csv"


# --- kernels ---------------------------------------------------------------------------------------

def test_free_omega_agrees_with_the_double_double_batch_on_per_body_times():
    rng = np.random.default_rng(1)
    I = np.sort(rng.uniform(0.1, 1.0, (400, 3)), axis=1)
    w = rng.normal(size=(400, 3)) * rng.uniform(1, 25, (400, 1))
    t = np.sort(rng.uniform(-1.0, 2.0, (400, 60)), axis=1)
    mine = free_omega(I, w, t)
    q = np.tile([0.0, 0.0, 0.0, 1.0], (1, 1))
    for k in range(0, 400, 37):  # the batch takes common times: one body at a time
        ref, _ = free_rotation_batch(I[k:k + 1], w[k:k + 1], q, t[k], attitude=False)
        assert np.max(np.abs(mine[k] - ref[0])) < 1e-11 * np.linalg.norm(w[k])
    # symmetric tops and a steady spin
    I2 = np.array([[1.0, 1.0, 2.0], [1.0, 2.0, 2.0], [1.0, 2.0, 3.0]])
    w2 = np.array([[0.1, 1.0, 0.3], [0.1, 1.0, 0.3], [0.0, 0.0, 2.0]])
    ref = np.stack([free_rotation_batch(I2[i:i + 1], w2[i:i + 1], q, t[0], attitude=False)[0][0] for i in range(3)])
    assert np.max(np.abs(free_omega(I2, w2, t[0]) - ref)) < 1e-12


def _euler_drag(I, a, b):
    def rhs(_, w):
        return (np.cross(I * w, w) - (a + b * np.abs(w)) * w) / I
    return rhs


def test_drag_omega_agrees_with_dop853_both_ways_in_time_and_keeps_the_energy_budget():
    I = np.array([0.3, 0.7, 1.0])
    a, b = np.array([0.01, 0.02, 0.005]), np.array([0.02, 0.03, 0.001])
    w0 = np.array([0.3, 12.0, 0.4])
    t = np.linspace(-0.5, 1.5, 201)
    mine = drag_omega(I[None], w0[None], t, a[None], b[None], max_step=[0.002])[0]
    fwd = solve_ivp(_euler_drag(I, a, b), (0, 1.5), w0, method="DOP853", rtol=1e-12, atol=1e-12, dense_output=True)
    bwd = solve_ivp(_euler_drag(I, a, b), (0, -0.5), w0, method="DOP853", rtol=1e-12, atol=1e-12, dense_output=True)
    ref = np.where((t >= 0)[:, None], fwd.sol(np.maximum(t, 0)).T, bwd.sol(np.minimum(t, 0)).T)
    assert np.max(np.abs(mine - ref)) < 2e-7 * np.linalg.norm(w0)  # RK4 at |w| h = 0.024: (0.024)^4 ~ 3e-7
    # the energy budget: E(t) - E(0) = -int sum (a + b |w|) w^2 dt (the drag's power)
    E = 0.5 * np.sum(I * mine ** 2, axis=1)
    power = -np.sum((a + b * np.abs(mine)) * mine ** 2, axis=1)
    fwd_part = t >= 0
    lost = np.concatenate([[0.0], np.cumsum(0.5 * (power[fwd_part][1:] + power[fwd_part][:-1]) * np.diff(t[fwd_part]))])
    assert np.max(np.abs(E[fwd_part] - E[fwd_part][0] - lost)) < 1e-3 * E[fwd_part][0]  # trapezoid error
    # a spin about a principal axis under quadratic drag: w(t) = w0 / (1 + b w0 t / I)
    spin = drag_omega([[1.0, 2.0, 3.0]], [[0.0, 0.0, 2.0]], t[t >= 0], None, [[0.0, 0.0, 1.5]])[0, :, 2]
    assert np.max(np.abs(spin - 2.0 / (1.0 + 1.5 * 2.0 * t[t >= 0] / 3.0))) < 1e-9


def test_rotvec_matrix_is_scipys():
    rng = np.random.default_rng(2)
    for rv in [*rng.normal(size=(20, 3)), np.zeros(3), np.array([1e-10, -2e-10, 0.0]), np.array([np.pi, 0, 0])]:
        assert np.max(np.abs(rotvec_matrix(rv) - Rotation.from_rotvec(rv).as_matrix())) < 1e-15


def test_autocorrelation_time_of_first_order_autoregressive_noise():
    rng = np.random.default_rng(3)
    for rho in (0.0, 0.5, 0.9):
        x = np.empty(200_000)
        x[0] = 0.0
        e = rng.normal(size=len(x))
        for i in range(1, len(x)):
            x[i] = rho * x[i - 1] + e[i]
        tau = autocorrelation_time(np.repeat(x[:, None], 3, axis=1), np.array([0, len(x)]))  # three identical axes
        assert abs(tau - (1 + rho) / (1 - rho)) < 0.05 * (1 + rho) / (1 - rho)


def test_birge_chi2_counts_the_scatter_of_consistent_values():
    rng = np.random.default_rng(4)
    C = np.array([[1.0, 0.3], [0.3, 2.0]]) * 1e-4
    values = rng.multivariate_normal([0.2, 0.8], C, size=400)
    chi2, dof = birge_chi2(values, np.repeat(C[None], 400, axis=0), values.mean(axis=0))
    assert dof == 2 * 399 and abs(chi2 / dof - 1.0) < 0.1


def test_birge_chi2_counts_a_common_error_that_moves_each_flight_its_own_way():
    """Three flights of one gyroscope: each flight's ratios are nearly one number along a ridge
    (correlations -0.999, as a toss's are), and the gyroscope's common scale error ``e`` moves
    flight f by ``B_f e``, differently in each. With the common error in the covariance the
    statistic is chi^2 with 4 degrees of freedom (mean 4, beyond its 95 % point in 5 % of draws,
    over 4000 draws: the binomial's sd 0.34 points); without it, the same consistent flights look
    inconsistent by orders of magnitude (the pooled interval was then inflated to uselessness)."""
    from scipy.stats import chi2 as chi2_dist

    rng = np.random.default_rng(7)
    sd = np.array([0.02, 0.015])
    S = np.array([np.outer(sd, sd) * np.array([[1.0, -0.999], [-0.999, 1.0]]) * f for f in (1.0, 0.3, 2.0)])
    B = rng.normal(0.0, 0.01, (3, 2, 3))  # each flight's answer to the three axes' scale errors
    stats, bare = [], []
    for _ in range(4000):
        e = rng.normal(size=3)
        values = np.array([[0.2, 0.8] + B[f] @ e + rng.multivariate_normal([0, 0], S[f]) for f in range(3)])
        chi2, dof = birge_chi2(values, S, shared=B)
        stats.append(chi2)
        bare.append(birge_chi2(values, S)[0])
    stats = np.array(stats)
    assert dof == 4 and abs(np.mean(stats) / dof - 1.0) < 0.05
    assert abs(np.mean(stats > chi2_dist.ppf(0.95, dof)) - 0.05) < 0.012
    assert np.median(bare) / dof > 100


@given(st.floats(0.5, 1.0), st.floats(0.0, 1.0))
def test_the_triangle_map_is_onto_the_closed_triangle_and_inverts(y, f):
    x = 1.0 - y + (2.0 * y - 1.0) * f  # any point of the closed triangle
    s, g = square(x, y)
    if x + 1.0 - y >= S_MIN:  # all but the rod sliver
        assert np.allclose(ratios(s, g), (x, y), atol=1e-12)
    xx, yy = ratios(s, g)
    assert 1.0 - yy - 1e-12 <= xx <= yy + 1e-12 and 0.5 - 1e-12 <= yy <= 1.0 + 1e-12


# --- one flight: the closed triangle, drag, saturation ----------------------------------------------

def _toss(I, w0, duration, rate=100.0, seed=0, a=(0, 0, 0), b=(0, 0, 0), noise=0.004):
    rng = np.random.default_rng(seed)
    t = np.cumsum(np.r_[0.0, rng.uniform(0.9, 1.1, int(duration * rate) - 1)]) / rate
    sol = solve_ivp(_euler_drag(np.asarray(I, float), np.asarray(a, float), np.asarray(b, float)), (0, t[-1]), w0,
                    method="DOP853", rtol=1e-12, atol=1e-12, dense_output=True)
    R = Rotation.random(random_state=seed)
    w = R.inv().apply(sol.sol(t).T) + rng.normal(0, 0.01, 3) + rng.normal(0, noise, (len(t), 3))
    return t, w


def test_an_exactly_planar_body_is_fitted_on_its_edge_with_intervals_that_hold_the_truth():
    """A thin plate (I1 + I2 = I3 exactly) tossed about its intermediate axis for a second: the
    old fit failed on such bodies ('Jacobian singular') or reported 1e13 uncertainties. Seeds 1
    and 14 failed later: Euler's regression clipped seed 1's start onto the planar edge, where the
    first solve stalled (on some platforms), and seed 14's plateau about the intermediate axis
    was taken for a gyroscope's rail."""
    I = np.array([0.2, 0.8, 1.0])
    hits = []
    for seed in range(16):
        t, w = _toss(I, [0.4, 12.0, 0.3], 1.0, seed=seed)
        fit = fit_rotation(t, w, drag="none")
        assert np.all(fit.ratios_std <= 0.05) and 1.0 - 1e-9 <= fit.ratios.sum() + 1e-3
        (lo1, hi1), (lo2, hi2) = fit.ratios_interval
        hits.append(lo1 <= 0.2 <= hi1 and lo2 <= 0.8 <= hi2)
        if fit.edge is not None:
            assert fit.edge == EDGES["planar"] and abs(fit.ratios.sum() - 1.0) < 1e-9
    assert sum(hits) >= 14


def test_a_smooth_maximum_is_no_rail_but_a_clipped_one_is():
    """A plate's spin about its intermediate axis stays within 0.2 % of its maximum for a third
    of a second (seed 14: 31 samples); its samples differ in their noise. A gyroscope that clips
    repeats its full-scale code."""
    _, w = _toss(np.array([0.2, 0.8, 1.0]), [0.4, 12.0, 0.3], 1.0, seed=14)
    top = np.abs(w).max()
    assert np.count_nonzero(np.abs(w) >= 0.998 * top) >= 20  # the plateau the old test took for a rail
    keep, rail = saturation_mask(w)
    assert rail is None and keep.all()
    clipped = np.clip(w, -0.99 * top, 0.99 * top)
    keep, rail = saturation_mask(clipped)
    assert rail == pytest.approx(0.99 * top, rel=1e-12)
    assert np.array_equal(keep, np.abs(clipped) < 0.998 * rail) and not keep.all()
    keep, rail = saturation_mask(w, saturation=0.95 * top)  # a given full scale is used as given
    assert rail == 0.95 * top and not keep.all()


def test_a_known_per_axis_quadratic_drag_is_recovered_and_chosen():
    I = np.array([0.25, 0.78, 1.0])
    b = np.array([0.004, 0.03, 0.002])  # per I3, 1/rad: a racquet's strong drag about its axis 2
    t, w = _toss(I, [0.3, 15.0, 0.5], 1.2, seed=5, b=b)
    fit = fit_rotation(t, w, drag="auto", scale_uncertainty=0.0)
    assert fit.drag == "quadratic"
    (lo1, hi1), (lo2, hi2) = fit.ratios_interval
    assert lo1 <= 0.25 <= hi1 and lo2 <= 0.78 <= hi2
    assert abs(fit.drag_coefficients[1] - b[1]) < 3 * fit.drag_coefficients_std[1] + 1e-4
    with pytest.warns(InadequateFitWarning, match="the model does not fit"):
        none = fit_rotation(t, w, drag="none", scale_uncertainty=0.0)
    assert none.residual_rms > 5 * fit.residual_rms  # 25 % of the spin lost: no drag does not fit
    assert fit.adequate and not none.adequate


def test_saturated_samples_are_left_out_and_counted():
    t, w = _toss(np.array([0.3, 0.75, 1.0]), [0.5, 14.0, 0.6], 1.0, seed=6)
    rail = 0.8 * np.max(np.abs(w))
    clipped = np.clip(w, -rail, rail)
    fit = fit_rotation(t, clipped, drag="none")
    assert fit.saturated == np.count_nonzero(np.abs(clipped) >= 0.998 * rail) > 3
    (lo1, hi1), (lo2, hi2) = fit.ratios_interval
    assert lo1 <= 0.3 <= hi1 and lo2 <= 0.75 <= hi2
    given_rail = fit_rotation(t, clipped, drag="none", saturation=rail)
    assert given_rail.saturated == fit.saturated
    with pytest.raises(ValueError, match="saturation"):
        fit_rotation(t, clipped, saturation=-1.0)


# --- whole recordings: detection, coverage, pooling ------------------------------------------------

#: Four recordings of each body with 2 tosses and a pause (16 flights), each with its own
#: gyroscope. The statistics over many such recordings (found and fitted, the 95 % intervals'
#: coverage) are benchmarks/fit_coverage.py's "tidy" cell (100 recordings of each body; in
#: benchmarks/results/fit_coverage.md: 96.0 % and 97.5 % found and fitted, coverage 94-98 %);
#: here, seeded checks of what each fitted flight and each recording must show.
CAMPAIGN = [(body, seed) for body in ("racquet", "phone") for seed in range(1000, 1004)]


def _iou(a, b, start, end):
    inter = max(0.0, min(b, end) - max(a, start))
    return inter / (max(b, end) - min(a, start))


@pytest.fixture(scope="module")
def campaign():
    rows, pooled = [], []
    for body, seed in CAMPAIGN:
        rec = synthetic_recording(seed, body=body, tosses=2, pauses=1)
        try:
            fit = fit_recording(rec.t, rec.omega, events=rec.events)
        except ValueError as err:  # neither flight usable: said in one line; the flights found
            assert str(err).startswith("no usable flight among")
            fit, found = None, find_flights(rec.t, rec.omega, events=rec.events)
            assert all(f.status == "skipped" and f.reason for f in found)
        tosses = fit.tosses if fit is not None else found
        for a, b in rec.flights:
            best = max(tosses, key=lambda toss: _iou(a, b, toss.start, toss.end))
            rows.append((body, _iou(a, b, best.start, best.end), best if fit is not None else None, rec.ratios))
        if fit is not None:
            p = fit.pooled
            assert p.adequate, p.adequacy
            pooled.append(np.abs(p.ratios - rec.ratios) / p.ratios_std)
    return rows, pooled


def test_flights_are_found(campaign):
    rows, _ = campaign
    missed = [(body, iou) for body, iou, _, _ in rows if iou < 0.5]
    assert not missed, missed


def test_no_flight_fails_or_reports_an_uncertainty_above_a_tenth(campaign):
    rows, _ = campaign
    for _, _, toss, _ in rows:
        if toss is None:  # the recording had no usable flight: checked in the fixture
            continue
        assert toss.status in ("ok", "skipped")
        if toss.status == "ok":
            if toss.reason:  # used in the joint fit only: its own ratios are not determined, and it says so
                assert toss.reason.startswith(JOINT_ONLY), toss.reason
            else:
                assert np.all(toss.fit.ratios_std <= 0.1)
            # no spin of hundreds of rad/s hidden by the bias (seen on real data before the bounds)
            assert np.linalg.norm(toss.fit.omega0) <= 2 * np.max(np.abs(toss.fit.omega_model)) * np.sqrt(3) + 1.0
            assert np.all(np.abs(toss.fit.bias) <= 1.0)
            assert toss.fit.adequate, toss.fit.adequacy
        else:
            assert toss.reason  # skipped with its reason
    used = np.mean([toss is not None and toss.status == "ok" for _, _, toss, _ in rows])
    assert used >= 0.85, used


def test_each_fitted_flights_ratios_lie_within_their_uncertainties(campaign):
    """Each flight's own ratios against the truth, in its standard uncertainties, judged by
    counts so that a right interval fails the test rarely whichever way the round-off falls:
    at most one flight beyond three (a right interval misses by three in ~0.4 % of flights, two
    of 16 in ~0.2 % of runs), none beyond five, and the mean square of the deviations at most 2.5
    (a right interval: about 1, or less where it is conservative; above 2.5 by chance in ~0.2 %
    of runs, the two ratios of a flight counted as one). An interval too narrow by half misses
    by three in ~15 % of flights and has a mean square near 4: it fails both nearly always (the
    coverage itself: fit_coverage's "tidy" cell). It asked none beyond three, which a right
    interval fails by chance in ~5 % of runs (benchmarks/roundoff_audit.py found one at 3.29)."""
    rows, _ = campaign
    z = np.array([np.abs(toss.fit.ratios - truth) / toss.fit.ratios_std for _, iou, toss, truth in rows
                  if iou >= 0.5 and toss is not None and toss.status == "ok" and not toss.reason])
    worst = z.max(axis=1)
    assert len(z) >= 12, len(z)
    assert np.sum(worst > 3.0) <= 1 and worst.max() <= 5.0 and np.mean(z**2) <= 2.5, np.round(z, 2)


def test_pooled_ratios_lie_within_three_pooled_uncertainties(campaign):
    _, pooled = campaign
    assert len(pooled) == len(CAMPAIGN) and np.max(pooled) <= 3.0, np.round(pooled, 2)


def test_a_gyroscope_that_saturates_loses_axes_not_flights():
    """A 1000 deg/s gyroscope (17.5 rad/s) on tosses of 15-25 rad/s: the samples at the rail are
    left out axis by axis and counted; the flights are still fitted and their intervals hold."""
    rec = synthetic_recording(6, body="racquet", tosses=4, saturation=np.deg2rad(1000.0), spin=(15.0, 25.0))
    fit = fit_recording(rec.t, rec.omega, events=rec.events)
    used = [toss for toss in fit.tosses if toss.status == "ok"]
    assert len(used) == 4 and sum(toss.fit.saturated for toss in used) > 50
    for toss in used:
        (lo1, hi1), (lo2, hi2) = toss.fit.ratios_interval
        assert lo1 <= rec.ratios[0] <= hi1 and lo2 <= rec.ratios[1] <= hi2


def test_flights_of_another_body_are_named_and_left_out():
    """Two bodies in one recording (the user swapped the racquet for a phone half way): the
    flights that disagree grossly with the others are skipped with that reason, not averaged
    into a number between the two bodies with a shrunken uncertainty; and since a third or more
    of the flights disagree, the pooled value is no answer either: inadequate, "the flights
    disagree" (it had reported one body's ratios as a success, exit 0)."""
    a = synthetic_recording(7, body="racquet", tosses=3)
    b = synthetic_recording(8, body="phone", tosses=3)
    t = np.concatenate([a.t, a.t[-1] + 1.0 + b.t])
    w = np.concatenate([a.omega, b.omega @ (b.sensor_rotation.as_matrix().T @ a.sensor_rotation.as_matrix())])
    with pytest.warns(InadequateFitWarning, match="the flights disagree"):
        fit = fit_recording(t, w)
    assert not fit.pooled.adequate and "more than one body" in fit.pooled.adequacy
    assert fit.summary()["adequate"] is False
    flagged = [toss for toss in fit.tosses if toss.reason.startswith("disagrees with the other flights")]
    assert len(flagged) >= 2 and all(toss.status == "skipped" for toss in flagged)
    for toss in fit.tosses:
        if toss.status == "ok":
            assert np.all(np.abs(toss.fit.ratios - fit.pooled.ratios) < 5 * np.hypot(toss.fit.ratios_std,
                                                                                     fit.pooled.ratios_std))


def test_flights_that_scatter_inflate_the_pooled_uncertainty():
    """chi^2/dof above 1: the pooled covariance's statistical part is scaled by it (Birge).
    Three slow racquet tosses at 100 Hz, whose third flight's own I1/I3 lies 3.4 of its standard
    uncertainties from the truth (its residuals twice the others'): more scatter than their
    uncertainties and the common scale error allow."""
    rec = synthetic_recording(22, body="racquet", tosses=3, rate=100.0, spin=(8.0, 8.0))
    fit = fit_recording(rec.t, rec.omega, events=rec.events)
    assert fit.chi2_dof > 3
    # the flights that state their own ratios (one used in the joint fit only has none to trust)
    own = np.array([toss.fit.ratios for toss in fit.tosses if toss.status == "ok" and not toss.reason])
    scatter = np.std(own, axis=0, ddof=1) / np.sqrt(len(own))  # what the flights' spread says
    assert np.all(fit.pooled.ratios_std >= 0.5 * scatter), (fit.pooled.ratios_std, scatter)


@pytest.mark.parametrize("body, seed, kind", [("phone", 8, dict(tosses=4, rate=200.0)),
                                              ("phone", 27, dict(tosses=3, rate=100.0, spin=(8.0, 8.0)))])
def test_consistent_flights_of_one_gyroscope_pool_no_wider_than_the_best(body, seed, kind):
    """Flights of one gyroscope differ by its scale error, which each flight's motion answers in
    its own way; that is no disagreement. Counted as one (the flights' statistical covariances
    alone in the Birge chi^2), these recordings had chi^2/dof 449 and 727, and the slow phone's
    pooled I1/I3 was 0.198 +- 0.032 where its best flight gave +- 0.024 (now +- 0.0045). The
    pooled answer is no wider than the best flight's and holds the truth (the coverage over many
    recordings: benchmarks/pool_coverage.py)."""
    rec = synthetic_recording(seed, body=body, **kind)
    fit = fit_recording(rec.t, rec.omega, events=rec.events)
    own = np.array([toss.fit.ratios_std for toss in fit.tosses if toss.status == "ok" and not toss.reason])
    assert fit.tosses_used >= 2 and fit.chi2_dof < 3, fit
    assert np.all(fit.pooled.ratios_std <= own.min(axis=0)), (fit.pooled.ratios_std, own)
    (lo1, hi1), (lo2, hi2) = fit.pooled.ratios_interval
    assert lo1 <= rec.ratios[0] <= hi1 and lo2 <= rec.ratios[1] <= hi2


# --- files and the command ---------------------------------------------------------------------------

def test_the_example_recording_is_the_generator_s_output(tmp_path):
    rec, text = example_recording()
    fresh = tmp_path / "fresh.csv"
    fresh.write_text(text, encoding="utf-8")
    t0, w0, _ = read_recording(fresh)
    t1, w1, _ = read_recording(RACQUET_EXAMPLE)
    assert RACQUET_EXAMPLE.read_text(encoding="utf-8").startswith("# SYNTHETIC")
    assert np.allclose(t0, t1, rtol=0, atol=1e-8)
    # the rates are quantised to the gyroscope's least significant bit: a value that falls within
    # round-off of a rounding boundary lands in either code, depending on the platform's last
    # digit (5 of 14547 values on one machine); more than a few such would be another recording
    off = np.abs(w0 - w1) > 1e-7
    assert np.all(np.abs(w0 - w1)[off] <= FULL_SCALE / 32768 + 1e-7) and np.count_nonzero(off) <= 30


def _export(tmp_path, rec):
    folder = tmp_path / "export"
    (folder / "meta").mkdir(parents=True)
    (folder / "Raw Data.csv").write_text(rec.csv_text(), encoding="utf-8")
    (folder / "meta" / "time.csv").write_text(rec.time_csv_text(), encoding="utf-8")
    (folder / "meta" / "device.csv").write_text('"property","value"\n"deviceModel","synthetic"\n', encoding="utf-8")
    zipped = tmp_path / "export.zip"
    with zipfile.ZipFile(zipped, "w") as z:
        for name in ("Raw Data.csv", "meta/time.csv", "meta/device.csv"):
            z.write(folder / name, name)
    return folder, zipped


def test_phyphox_exports_are_read_with_their_pauses(tmp_path):
    rec = synthetic_recording(21, body="phone", tosses=2, pauses=1)
    folder, zipped = _export(tmp_path, rec)
    for source in (folder, zipped):
        t, w, events = read_recording(source)
        assert np.allclose(t, rec.t, atol=1e-8) and np.allclose(w, rec.omega, atol=1e-8)
        assert [name for name, _ in events] == ["START", "PAUSE", "START"]
    bad = tmp_path / "bad.zip"
    bad.write_bytes(b"not a zip")
    with pytest.raises(ValueError, match="not a zip archive"):
        read_recording(bad)
    empty = tmp_path / "empty.zip"
    with zipfile.ZipFile(empty, "w") as z:
        z.writestr("meta/time.csv", '"event","experiment time"\n')
    with pytest.raises(ValueError, match="Raw Data.csv"):
        read_recording(empty)


@pytest.mark.parametrize("damage", ["crc", "deflate"])
def test_a_damaged_phyphox_zip_is_bad_input_naming_the_file(tmp_path, capsys, damage):
    """Issue 27, item 5: a .zip whose data were damaged (a flipped byte: a bad CRC, or deflate
    data that do not decode) was "computation failed" (exit 1). It is bad input: one line naming
    the file and the member, exit 2, nothing written."""
    from tumble.cli import main

    rec = synthetic_recording(21, body="phone", tosses=1)
    folder = tmp_path / "export"
    folder.mkdir()
    (folder / "Raw Data.csv").write_text(rec.csv_text(), encoding="utf-8")
    zipped = tmp_path / "export.zip"
    method = zipfile.ZIP_STORED if damage == "crc" else zipfile.ZIP_DEFLATED
    with zipfile.ZipFile(zipped, "w", compression=method) as z:
        z.write(folder / "Raw Data.csv", "Raw Data.csv")
    raw = bytearray(zipped.read_bytes())
    start = 30 + len("Raw Data.csv")  # the local header, then the member's data
    for k in range(start + 40, start + 48):  # flip bytes inside the data, not in the headers
        raw[k] ^= 0x5A
    zipped.write_bytes(bytes(raw))
    with pytest.raises(ValueError, match=r"export\.zip: Raw Data\.csv cannot be unpacked, the archive is damaged"):
        read_recording(zipped)
    out = tmp_path / "fit"
    assert main(["fit", str(zipped), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "export.zip" in err and "damaged" in err
    assert not out.exists()


def test_a_pause_inside_a_stretch_splits_it():
    """phyphox's time carries on across a pause: the samples after it are another moment. A
    pause event in the middle of a flight must cut it (two stretches), not be fitted across."""
    rec = synthetic_recording(22, body="phone", tosses=1)
    a, b = rec.flights[0]
    mid = 0.5 * (a + b)
    flights = find_flights(rec.t, rec.omega, events=[("START", 0.0), ("PAUSE", mid), ("START", mid)])
    assert len(flights) >= 2 and all(f.end <= mid or f.start > mid for f in flights)
    whole = find_flights(rec.t, rec.omega)
    assert len(whole) == 1 and whole[0].start < mid < whole[0].end


def test_the_command_fits_the_example_recording(tmp_path, capsys):
    out = tmp_path / "fit"
    assert main(["fit", str(RACQUET_EXAMPLE), "--out", str(out), "--body", "t-handle"]) == 0
    line = capsys.readouterr().out
    used = int(re.search(r"from (\d+) of 12 flights", line).group(1))
    assert line.count("\n") == 1 and used >= 11 and "I1/I3 = 0.06" in line
    data = json.loads((out / "fit.json").read_text(encoding="utf-8"))
    truth = np.array(TOSS_BODIES["racquet"].moments[:2]) / TOSS_BODIES["racquet"].moments[2]
    pooled = data["pooled"]
    assert set(pooled) >= {"I1_over_I3", "I2_over_I3", "I1_over_I3_std", "I2_over_I3_std", "tosses_used", "chi2_dof"}
    assert abs(pooled["I1_over_I3"] - truth[0]) < 2 * pooled["I1_over_I3_std"]
    assert abs(pooled["I2_over_I3"] - truth[1]) < 2 * pooled["I2_over_I3_std"]
    assert data["I1_over_I3"] == pooled["I1_over_I3"]  # the one-flight keys hold the pooled values
    keys = ["input", "start", "end", "samples", "I1_over_I3", "I2_over_I3", "I1_over_I3_std", "I2_over_I3_std",
            "edge", "residual_rms", "status", "reason"]
    assert len(data["tosses"]) == 12 and all(list(toss) == keys for toss in data["tosses"])
    # a flight whose own optimum lies on the triangle's edge says so (its intervals are one-sided): the table gave
    # flight 3 (I1 + I2 = I3 to round-off, its intervals missing the truth) as a plain "ok" (a walkthrough, 2026-12-02)
    edged = [toss for toss in data["tosses"] if toss["edge"]]
    assert [toss["edge"] for toss in edged] == ["planar (I1 + I2 = I3)"]
    assert abs(edged[0]["I1_over_I3"] + edged[0]["I2_over_I3"] - 1.0) < 1e-9
    assert sum(toss["status"] == "ok" for toss in data["tosses"]) == used == pooled["tosses_used"]
    assert all(toss["reason"] for toss in data["tosses"] if toss["status"] != "ok")
    csv_lines = (out / "tosses.csv").read_text(encoding="utf-8").splitlines()
    assert csv_lines[0] == ",".join(keys) and len(csv_lines) == 13
    assert (out / "fit.png").stat().st_size > 10_000
    assert data["body"]["I1_over_I3"] == pytest.approx(2 / 7) and data["body"]["I1_over_I3_sigmas"] > 10
    b = data["body"]  # and the line says so, not fit.json alone (a walkthrough missed it there, 2026-12-02)
    assert (f"; t-handle predicts I1/I3 = 0.2857 ({b['I1_over_I3_sigmas']:+.1f} sigma), I2/I3 = 0.7143 "
            f"({b['I2_over_I3_sigmas']:+.1f} sigma); read ") in line


def test_a_recording_without_a_usable_flight_exits_1_and_writes_nothing(tmp_path, capsys):
    """No flight to fit in a readable recording is a failed fit (1); a bad option is bad input (2)."""
    held = tmp_path / "held.csv"
    rng = np.random.default_rng(9)
    held.write_text("".join(f"{k * 0.01:.2f},{a:.5f},{b:.5f},{c:.5f}\n" for k, (a, b, c) in
                            enumerate(rng.normal(0, 0.2, (3000, 3)))), encoding="utf-8")
    out = tmp_path / "none"
    assert main(["fit", str(held), "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "fit failed" in err and "no free flight found" in err and not out.exists()
    # flights found, none usable (spins too steady to fix the ratios): failed too
    steady = tmp_path / "steady.csv"
    steady.write_text("".join(f"{k * 0.01:.2f},0,0,5\n" for k in range(300)), encoding="utf-8")
    assert main(["fit", str(steady), "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "no usable flight among" in err and not out.exists()
    assert main(["fit", str(RACQUET_EXAMPLE), "--out", str(out), "--saturation", "-3"]) == 2
    assert "--saturation" in capsys.readouterr().err and not out.exists()

