"""Sweeps: dispersions that stay physical, reproducible sampling, per-case results, statistics.

Statistical claims are checked against closed forms with bounds of four standard deviations
(or a Kolmogorov-Smirnov p-value above 1e-3) on fixed seeds, so each test is deterministic and
would fail for a wrong distribution, not by chance.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats
from scipy.spatial.transform import Rotation

import tumble
from tumble.ensemble import (
    BodySampler,
    Design,
    Dispersion,
    Ensemble,
    InitialRates,
    case_generator,
)
from tumble.mass import INERTIA_RTOL

SPIN = InitialRates(omega=(0.1, 10.0, 0.1))


def ensemble(dispersions, cases, *, body=None, rates=SPIN, preset=None, parameters=None, **kw) -> Ensemble:
    body = tumble.t_handle() if body is None else body
    return Ensemble(BodySampler(body, tuple(dispersions), preset, parameters), rates, cases, **kw)


# --- dispersions stay physical ----------------------------------------------------------------

def test_moments_of_a_planar_body_are_redrawn_half_the_time():
    # The thin-rod T-handle is planar: I1 + I2 = I3 exactly. Perturbing each moment by an
    # independent normal factor keeps the triangle inequality iff I1 z1 + I2 z2 - I3 z3 >= 0,
    # a symmetric normal variable: probability 1/2. Redraws per case are then geometric with
    # p = 1/2: mean 1, variance (1 - p) / p^2 = 2.
    n = 2000
    x = ensemble([Dispersion("moments", 0.01)], n, seed=11).inputs()
    I = x.moments
    assert np.all(I > 0) and np.all(np.diff(I, axis=1) >= 0)
    assert np.all(I[:, 0] + I[:, 1] - I[:, 2] >= -INERTIA_RTOL * I.sum(axis=1))
    total = int(x.resampled.sum())
    assert abs(total - n) < 4 * math.sqrt(2 * n), total  # measured: 2001
    assert abs(x.resampled.var() - 2.0) < 0.4


def test_a_case_that_stays_unphysical_is_refused_with_its_number():
    e = ensemble([Dispersion("moments", 0.01)], 50, seed=11, max_resamples=0)
    with pytest.raises(ValueError, match=r"^case \d+: no physical body in 1 draw\(s\) \(last: .*triangle inequality.*"
                                         r"raise max_resamples = 0$"):
        e.inputs()


def test_a_part_by_density_keeps_its_density_and_one_by_mass_its_mass():
    rho, r, L, m = 2700.0, 0.02, 0.3, 1.2
    body = tumble.Body([tumble.Cylinder(density=rho, radius=r, length=L, axis=(0, 0, 1)),  # coaxial, along z
                        tumble.Cylinder(mass=m, radius=r, length=L, axis=(0, 0, 1), center=(0, 0, 0.5))])
    radius = [Dispersion("part", 0.05, field="radius", part=k, distribution="uniform") for k in (0, 1)]
    x = ensemble(radius, 400, body=body, seed=5).inputs()
    r0, r1 = x.values[:, 0], x.values[:, 1]
    assert np.all(np.abs(r0 / r - 1) <= 0.05) and np.all(np.abs(r1 / r - 1) <= 0.05)
    assert stats.kstest(r0, stats.uniform(0.95 * r, 0.1 * r).cdf).pvalue > 1e-3
    # The axial moment (along z, the minor axis here) is the sum of m_k r_k^2 / 2 (Meriam &
    # Kraige, Table D/4): by density m_0 = rho pi r_0^2 L; by mass m_1 = m.
    axial = 0.5 * rho * math.pi * L * r0**4 + 0.5 * m * r1**2
    assert np.allclose(x.moments[:, 0], axial, rtol=1e-12)


def test_an_absolute_normal_spread_of_a_centre_has_its_mean_and_deviation():
    sigma, n = 0.002, 1000
    body = tumble.Body([tumble.Sphere(mass=1.0, radius=0.05, center=(0.3, 0, 0)),
                        tumble.Sphere(mass=1.0, radius=0.05, center=(-0.3, 0, 0)),
                        tumble.Sphere(mass=0.5, radius=0.05, center=(0, 0.2, 0))])
    d = Dispersion("part", sigma, field="center", part=0, relative=False)
    e = ensemble([d], n, body=body, seed=9, sampling="lhs")
    assert e.names == ("parts[0].center[0] [m]", "parts[0].center[1] [m]", "parts[0].center[2] [m]")
    centre = e.inputs().values
    dev = centre - [0.3, 0.0, 0.0]
    assert np.all(np.abs(dev.mean(axis=0)) < 4 * sigma / math.sqrt(n))
    assert np.all(np.abs(dev.std(axis=0, ddof=1) / sigma - 1) < 4 / math.sqrt(2 * n))


def test_the_axes_turn_by_the_drawn_rotation_whose_angle_is_chi_distributed():
    sigma = 0.01
    body = tumble.iss_t_handle()
    x = ensemble([Dispersion("axes", sigma, relative=False)], 600, body=body, seed=3).inputs()
    assert np.all(x.resampled == 0)
    nominal = body.principal_axes
    for axes, rotvec in zip(x.axes[:20], x.values[:20]):
        assert np.allclose(axes, Rotation.from_rotvec(rotvec).as_matrix() @ nominal, atol=1e-9)
    assert np.allclose(x.moments, body.principal_moments, rtol=1e-12)  # a rotation keeps the moments
    # |rotvec|^2 / sigma^2 is chi-squared with 3 degrees of freedom
    angle2 = np.sum(x.values**2, axis=1) / sigma**2
    assert stats.kstest(angle2, stats.chi2(3).cdf).pvalue > 1e-3


def test_preset_parameters_rebuild_the_preset():
    spread = Dispersion("preset", 0.05, field="crossbar_length", distribution="uniform")
    e = ensemble([spread], 50, preset="t-handle", seed=2)
    x = e.inputs()
    length = x.values[:, 0]
    # thin rods, 1.5 kg each: I1 = m L_c^2 / 12 about the shaft (Meriam & Kraige Table D/4)
    assert np.allclose(x.moments[:, 0], 1.5 * length**2 / 12, rtol=1e-12)


@pytest.mark.parametrize(("dispersion", "message"), [
    (dict(target="mass", spread=0.1), r"^target = 'mass' is unknown; allowed: preset, part, moments, axes$"),
    (dict(target="part", spread=0.1, field="length", part=5),
     r"^dispersions\[0\] \(parts\[5\]\.length\): part = 5 is out of range; the body has parts 0 to 1$"),
    (dict(target="part", spread=0.1, field="axis", part=0),
     r"^dispersions\[0\] \(parts\[0\]\.axis\): a rod has no number 'axis' to perturb; allowed: mass, center, length$"),
    (dict(target="preset", spread=0.1, field="shaft_mass"),
     r"^dispersions\[0\] \(shaft_mass\): preset parameter shaft_mass = None has no number to perturb"),
    (dict(target="moments", spread=0.1, relative=False), r"^target 'moments' takes a relative spread only"),
    (dict(target="axes", spread=-0.1, relative=False), r"^spread = -0.1 must be a finite number >= 0$"),
    (dict(target="part", spread=0.1, field="density", part=0),
     r"^dispersions\[0\] \(parts\[0\]\.density\): a rod has no number 'density'"),
])
def test_bad_dispersions_are_refused_in_one_line(dispersion, message):
    with pytest.raises(ValueError, match=message):
        BodySampler(tumble.t_handle(), (Dispersion(**dispersion),), "t-handle")


# --- sampling: reproducible, stratified ----------------------------------------------------------

RATES = InitialRates(omega=(0.1, 10.0, 0.1), distribution="uniform", spread=(0.05, 0.5, 0.05))


@pytest.mark.parametrize("sampling", ["random", "lhs", "sobol"])
def test_any_case_made_alone_is_the_same_row(sampling):
    dispersions = [Dispersion("preset", 0.05, field="shaft_length", distribution="uniform"),
                   Dispersion("moments", 0.01)]
    def make():
        return ensemble(dispersions, 40, preset="t-handle", rates=RATES, seed=1234, sampling=sampling)
    whole = make().inputs()
    for i in (0, 17, 39):
        alone = make().inputs(i, i + 1)  # a fresh ensemble: nothing carried over
        for field in ("moments", "axes", "omega0", "quat0", "values", "resampled"):
            assert np.array_equal(getattr(alone, field)[0], getattr(whole, field)[i]), (i, field)
    assert whole.resampled.sum() > 0  # the redraws are reproduced too
    other = ensemble(dispersions, 40, preset="t-handle", rates=RATES, seed=1235, sampling=sampling).inputs()
    assert not np.array_equal(other.omega0, whole.omega0)


def test_a_case_generator_is_the_spawned_child():
    children = np.random.SeedSequence(99).spawn(8)
    for i in (0, 5, 7):
        assert np.array_equal(case_generator(99, i).random(4), np.random.default_rng(children[i]).random(4))


@pytest.mark.parametrize("sampling", ["lhs", "sobol"])
def test_latin_hypercube_and_sobol_put_one_case_in_each_stratum(sampling):
    n = 64  # a power of two: a scrambled Sobol' net is stratified in every coordinate
    x = ensemble([], n, rates=RATES, seed=8, sampling=sampling).inputs()
    u = (x.omega0 - RATES.omega) / (2 * np.array(RATES.spread)) + 0.5  # back to the unit cube
    for j in range(3):
        assert sorted(np.floor(u[:, j] * n).astype(int)) == list(range(n))
    random = ensemble([], n, rates=RATES, seed=8).inputs()
    u = (random.omega0 - RATES.omega) / (2 * np.array(RATES.spread)) + 0.5
    assert len(set(np.floor(u[:, 0] * n).astype(int))) < n  # plain random sampling is not stratified


def test_normal_rates_have_their_mean_and_deviation():
    rates = InitialRates(omega=(0.1, 10.0, 0.1), distribution="normal", spread=(0.02, 0.3, 0.0))
    n = 2000
    w = ensemble([], n, rates=rates, seed=4, sampling="sobol").inputs().omega0
    assert np.all(w[:, 2] == 0.1)
    for j, s in ((0, 0.02), (1, 0.3)):
        assert abs(w[:, j].mean() - rates.omega[j]) < 4 * s / math.sqrt(n)
        assert abs(w[:, j].std(ddof=1) / s - 1) < 4 / math.sqrt(2 * n)
    assert stats.kstest((w[:, 1] - 10.0) / 0.3, "norm").pvalue > 1e-3


def test_a_grid_of_rates_is_run_through_with_the_third_component_fastest():
    rates = InitialRates(grid=([0.1], [9.0, 10.0], [0.0, 0.1, 0.2]))
    w = ensemble([], 12, rates=rates).inputs().omega0
    expected = [[0.1, a, b] for a in (9.0, 10.0) for b in (0.0, 0.1, 0.2)]
    assert w.tolist() == expected + expected


def test_design_frame_rates_follow_the_turned_axes():
    body = tumble.t_handle()
    rates = InitialRates(omega=(10.0, 0.0, 0.0), frame="design")  # about the crossbar
    x = ensemble([Dispersion("axes", 0.05, relative=False)], 5, body=body, rates=rates, seed=1).inputs()
    for axes, w in zip(x.axes, x.omega0):
        assert np.allclose(axes @ w, [10.0, 0.0, 0.0], atol=1e-12)
        assert abs(w[1]) > 9.9 and np.hypot(w[0], w[2]) > 0  # mostly the intermediate axis, not only


@pytest.mark.parametrize(("kwargs", "message"), [
    (dict(sampling="halton", seed=1, cases=4, dims=1), r"^sampling = 'halton' is unknown; allowed: random, lhs, sobol$"),
    (dict(sampling="lhs", seed=-1, cases=4, dims=1), r"^seed = -1 must be a whole number from 0 to 2\^64 - 1$"),
    (dict(sampling="lhs", seed=1, cases=0, dims=1), r"^cases = 0 must be a whole number >= 1$"),
])
def test_bad_designs_are_refused_in_one_line(kwargs, message):
    with pytest.raises(ValueError, match=message):
        Design(**kwargs)


def test_bad_rates_are_refused_in_one_line():
    with pytest.raises(ValueError, match=r"^initial rates need omega = \[w1, w2, w3\] \(rad/s\) or a grid of them, not both$"):
        InitialRates(omega=(1, 2, 3), grid=([1], [2], [3]))
    with pytest.raises(ValueError, match=r"^frame = 'world' is unknown; allowed: principal, design$"):
        InitialRates(omega=(1, 2, 3), frame="world")
    with pytest.raises(ValueError, match=r"^grid\[1\] = \[\] must be a non-empty list of rates \(rad/s\)$"):
        InitialRates(grid=([1.0], [], [3.0]))
