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
from tumble.ensemble.sampling import case_uniforms
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
    assert abs(total - n) < 4 * math.sqrt(2 * n), total  # measured: 1960
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


def test_the_streams_of_many_cases_at_once_are_their_generators_draws():
    # case_uniforms rebuilds SeedSequence + PCG64 over arrays: bit for bit the generators'
    # draws, for seeds of one and two 32-bit words and case numbers of one and two words.
    index = np.r_[0:40, 4095, 2**31, 2**32 - 1, 2**32, 2**33 + 7]
    for seed in (0, 7, 2**32 - 1, 2**32, 2**64 - 1):
        many = case_uniforms(seed, index, 9)
        alone = np.array([case_generator(seed, int(i)).random(9) for i in index])
        assert np.array_equal(many, alone), seed


def _case_alone(e: Ensemble, i: int):
    """Case i made alone the slow way: its own generator, BodySampler.sample one draw at a time."""
    k = e.rates.dims
    row = case_generator(e.seed, i).random(e.design.dims) if e.sampling == "random" else e.design.rows(i, i + 1)[0]
    drawn, resampled = e._body(i, row[k:])
    return drawn.moments, drawn.axes, e.rates.rate(i, row[:k]), drawn.values, resampled


BOX = tumble.Body((tumble.Box(mass=1.0, size=(0.1, 0.2, 0.3)),), "box")  # I1 + I2 - I3 = 8 % of I3


@pytest.mark.parametrize("dispersions", [
    [Dispersion("moments", 0.05)],
    [Dispersion("axes", 0.05, relative=False)],
    [Dispersion("moments", 0.02, distribution="uniform"), Dispersion("axes", 0.1, relative=False),
     Dispersion("moments", 0.03)],
    [],
], ids=["moments", "axes", "both", "none"])
@pytest.mark.parametrize("sampling", ["random", "lhs", "sobol"])
def test_a_chunk_made_with_arrays_is_each_case_made_alone(dispersions, sampling):
    # The chunk is made with arrays (moments and axes dispersions, rates); each row must be
    # bit for bit the case made alone by the one-draw-at-a-time path, redraws included (the
    # box sits 8 % from the triangle inequality: 5 % moment spreads get refused now and then).
    rates = (RATES if dispersions else InitialRates(grid=((0.1, 0.2), (5.0, 6.0, 7.0), (0.0, 0.1))))
    e = ensemble(dispersions, 400, body=BOX, rates=rates, seed=42, sampling=sampling)
    x = e.inputs()
    for i in range(400):
        moments, axes, omega, values, resampled = _case_alone(e, i)
        assert np.array_equal(x.moments[i], moments) and np.array_equal(x.axes[i], axes), i
        assert np.array_equal(x.values[i], values) and x.resampled[i] == resampled, i
        assert np.array_equal(x.omega0[i], omega), i
    if dispersions == [Dispersion("moments", 0.05)]:
        assert x.resampled.sum() > 0  # the refused draws went through the redraw path


def test_design_frame_rates_made_with_arrays_are_each_case_made_alone():
    rates = InitialRates(omega=(0.1, 10.0, 0.1), frame="design", distribution="normal", spread=(0.1, 0.5, 0.1))
    e = ensemble([Dispersion("axes", 0.1, relative=False)], 50, body=BOX, rates=rates, seed=3)
    x = e.inputs()
    for i in range(50):
        alone = e.inputs(i, i + 1)
        for field in ("moments", "axes", "omega0", "quat0", "values", "resampled"):
            assert np.array_equal(getattr(alone, field)[0], getattr(x, field)[i]), (i, field)


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
    (dict(sampling="lhs", seed=1, cases=0, dims=1), r"^cases = 0 must be a whole number from 1 to 100000000$"),
    (dict(sampling="random", seed=1, cases=10**8 + 1, dims=1), r"^cases = 100000001 must be a whole number from 1 to 100000000$"),
])
def test_bad_designs_are_refused_in_one_line(kwargs, message):
    with pytest.raises(ValueError, match=message):
        Design(**kwargs)


def test_bad_rates_are_refused_in_one_line():
    with pytest.raises(ValueError, match=r"^initial rates need omega = \[w1, w2, w3\] \(rad/s\) or a grid of them, not both$"):
        InitialRates(omega=(1, 2, 3), grid=([1], [2], [3]))
    with pytest.raises(ValueError, match=r"^initial rates need omega = \[w1, w2, w3\] \(rad/s\) or a grid of them, and "
                                         r"neither is given$"):
        InitialRates()
    with pytest.raises(ValueError, match=r"^frame = 'world' is unknown; allowed: principal, design$"):
        InitialRates(omega=(1, 2, 3), frame="world")
    with pytest.raises(ValueError, match=r"^grid\[1\] = \[\] must be a non-empty list of rates \(rad/s\)$"):
        InitialRates(grid=([1.0], [], [3.0]))


# --- per-case results against the one-trajectory analysis -----------------------------------------

from tumble.analysis import flip_interval, stability_report  # noqa: E402
from tumble.ensemble import (  # noqa: E402
    Counts,
    Criterion,
    KeyedSample,
    RunningMoments,
    RunSettings,
    Sweep,
    case_keys,
    compute_chunk,
    nutation_angle,
    reduce_cases,
    run_chunks,
    runs_needed,
    stability_map,
    success_lower_bound,
    SweepSummary,
    summarize,
)
from tumble.mass import MassProperties  # noqa: E402

T_HANDLE_SPREAD = (Dispersion("preset", 0.05, field="shaft_length", distribution="uniform"),
                   Dispersion("preset", 0.05, field="crossbar_length", distribution="uniform"),
                   Dispersion("axes", 0.02, relative=False))
NEAR_INTERMEDIATE = InitialRates(omega=(10.0, 0.1, 0.1), frame="design", distribution="normal",
                                 spread=(0.0, 0.05, 0.05))


def t_handle_sweep(cases=24, *, seed=7, settings=None, criterion=None, sampling="random") -> Sweep:
    e = ensemble(T_HANDLE_SPREAD, cases, preset="t-handle", rates=NEAR_INTERMEDIATE, seed=seed, sampling=sampling)
    return Sweep(e, settings or RunSettings(t_end=20.0, samples=400), criterion)


def props_of(moments, axes) -> MassProperties:
    return MassProperties(1.0, np.zeros(3), axes @ np.diag(moments) @ axes.T, moments, axes)


def test_a_sweep_of_two_samples_asks_the_exact_method_for_t_end_alone():
    # samples = 2 (t = 0 and t_end): the exact method is evaluated at t_end only, and the
    # t = 0 sample is the initial state itself. Every column is bit for bit what the kernel's
    # two samples give, but max_nutation, whose t = 0 term is now that of the initial state
    # exactly (the kernel's own t = 0 omega differs from it in the last bit: measured 2.2e-16).
    sweep = Sweep(ensemble([Dispersion("moments", 0.05)], 300, body=BOX, rates=RATES, seed=5),
                  RunSettings(t_end=20.0, samples=2))
    fast = compute_chunk(sweep, 0, 300)
    x = sweep.ensemble.inputs()
    full = reduce_cases(x, tumble.simulate_batch(x.moments, x.omega0, t_end=20.0, samples=2, attitude0=x.quat0),
                        sweep.ensemble.names)
    assert list(fast) == list(full)
    for k in full:
        if k != "max_nutation [rad]":
            assert np.array_equal(fast[k], full[k], equal_nan=fast[k].dtype.kind == "f"), k
    ends = np.stack([x.omega0, np.column_stack([fast[f"omega_end_{j} [rad/s]"] for j in (1, 2, 3)])], axis=1)
    assert np.array_equal(fast["max_nutation [rad]"], np.max(nutation_angle(ends, x.moments), axis=1))
    assert np.max(np.abs(fast["max_nutation [rad]"] - full["max_nutation [rad]"])) <= 4.5e-16
    assert np.all(np.isnan(fast["flip_period [s]"])) and np.all(np.isfinite(fast["flip_period_exact [s]"]))


def test_each_row_is_what_the_trajectory_of_that_case_reports():
    sweep = t_handle_sweep(6)
    cols = compute_chunk(sweep, 0, 6)
    x = sweep.ensemble.inputs(0, 6)
    for i in range(6):
        traj = tumble.simulate(props_of(x.moments[i], x.axes[i]), x.omega0[i], t_end=20.0, samples=400)
        report = stability_report(traj)
        assert cols["axis"][i] == report["axis"] == 2
        assert cols["predicted"][i] == report["predicted"] == "unstable"
        assert cols["flips"][i] == report["flips"] >= 8
        assert cols["flip_period [s]"][i] == pytest.approx(report["flip_period"], rel=1e-12)
        assert cols["flip_period_exact [s]"][i] == pytest.approx(report["flip_period_exact"], rel=1e-12)
        assert cols["growth_rate [1/s]"][i] == pytest.approx(report["growth_rate"], rel=1e-12)
        assert cols["max_nutation [rad]"][i] == pytest.approx(np.max(traj.nutation_angle), rel=1e-12)
        q = [cols[f"q_end_{c}"][i] for c in "xyzw"]
        assert np.allclose(q, traj.design_attitude()[-1].as_quat(canonical=True), atol=1e-12)
        w = [cols[f"omega_end_{j} [rad/s]"][i] for j in (1, 2, 3)]
        assert np.allclose(w, traj.omega[-1], rtol=0, atol=1e-12)
        # the measured period is the exact one to the sampling's resolution (dt = 0.05 s)
        assert abs(cols["flip_period [s]"][i] / cols["flip_period_exact [s]"][i] - 1) < 1e-3
    assert np.all(np.abs(cols["energy_change"]) < 1e-14) and np.all(cols["L_world_angle [rad]"] < 1e-14)


def test_a_stable_spin_does_not_flip_and_has_no_flip_period():
    rates = InitialRates(omega=(0.1, 0.1, 10.0), frame="design", distribution="normal", spread=(0.05, 0.05, 0.0))
    sweep = Sweep(ensemble(T_HANDLE_SPREAD, 8, preset="t-handle", rates=rates, seed=2), RunSettings(t_end=10.0))
    cols = compute_chunk(sweep, 0, 8)  # about the shaft: the minor axis
    assert set(cols["predicted"]) == {"stable"} and set(cols["axis"]) == {1} and set(cols["circulation"]) == {1}
    assert np.all(cols["flips"] == 0) and np.all(np.isnan(cols["flip_period [s]"]))
    assert np.all(np.isnan(cols["flip_period_exact [s]"]))
    assert np.all(cols["wobble_frequency [rad/s]"] > 0)


def test_nutation_follows_the_trajectory_rule_for_prolate_and_asymmetric_bodies():
    rng = np.random.default_rng(0)
    for moments in ([1.0, 3.0, 3.0], [1.0, 2.0, 2.5], [2.0, 2.0, 2.0]):
        w = rng.normal(size=(1, 50, 3))
        body = MassProperties.from_moments(moments)
        traj = tumble.simulate(body, w[0, 0], times=np.linspace(0, 1, 50))
        batch = nutation_angle(traj.omega[None], np.array([moments], float))
        assert np.allclose(batch[0], traj.nutation_angle, rtol=1e-14, atol=0)


def test_with_a_torque_the_energy_grows_by_the_work_done():
    # spin W0 about the major axis and a torque tau along it: omega_3 = W0 + tau t / I3, so
    # E(t) / E0 = (1 + tau t / (I3 W0))^2 and L keeps its direction
    tau, W0, t_end = 0.02, 2.0, 5.0
    rates = InitialRates(omega=(0.0, 0.0, W0))
    e = ensemble([Dispersion("preset", 0.05, field="crossbar_length", distribution="uniform")], 4,
                 preset="t-handle", rates=rates, seed=1)
    settings = RunSettings(t_end=t_end, samples=50, torque=tumble.ConstantTorque((0.0, 0.0, tau)))
    assert settings.method == "dop853"
    cols = compute_chunk(Sweep(e, settings), 0, 4)
    I3 = cols["I3 [kg m^2]"]
    assert np.allclose(cols["energy_change"], (1 + tau * t_end / (I3 * W0)) ** 2 - 1, rtol=1e-9)
    assert np.allclose(cols["omega_end_3 [rad/s]"], W0 + tau * t_end / I3, rtol=1e-10)
    assert np.all(cols["L_world_angle [rad]"] < 1e-12) and np.all(np.isnan(cols["flip_period_exact [s]"]))


def test_a_fixed_step_method_needs_its_step_in_a_sweep():
    with pytest.raises(ValueError, match=r"^method = 'geometric' needs a step \(s\) in a sweep"):
        RunSettings(t_end=1.0, method="geometric")


# --- the stability map -------------------------------------------------------------------------

def test_the_stability_map_is_the_simulated_flip_period_at_sample_points():
    m = stability_map(10.0, (0.01, 0.01), resolution=40)
    assert m.flip_interval.shape == (20, 40) and m.inside.sum() > 150
    X, Y = np.meshgrid(m.x, m.y)
    assert np.all(np.isnan(m.flip_interval[~m.inside])) and np.all(np.isfinite(m.flip_interval[m.inside]))
    assert np.all((X + Y > 1) == (m.inside | (X >= Y) | (Y >= 1)))
    points = [(i, j) for i, j in zip(*np.nonzero(m.inside))][::41][:4]
    for i, j in points:
        moments = np.array([m.x[j], m.y[i], 1.0])
        T = m.flip_interval[i, j]
        traj = tumble.simulate(MassProperties.from_moments(moments), m.omega0,
                               t_end=6.5 * T, samples=6000, method="dop853", rtol=1e-11)
        report = stability_report(traj)
        assert report["flips"] == 6
        assert report["flip_period"] == pytest.approx(T, rel=1e-6), (moments, T)  # measured: 1.3e-9
        # omega_3 keeps its sign iff omega circulates about the major axis
        assert (np.all(np.sign(traj.omega[:, 2]) == np.sign(traj.omega[0, 2]))) == (m.circulation[i, j] == 3)


def test_the_map_circulates_about_the_axis_nearer_in_energy():
    # L^2 > 2 E I2 (circulation about axis 3) iff I1 (I2 - I1) w1^2 < I3 (I3 - I2) w3^2 for
    # w2 the intermediate spin (Landau & Lifshitz sec. 37): the boundary is a curve in (x, y)
    m = stability_map(5.0, (0.02, 0.01), resolution=60)
    X, Y = np.meshgrid(m.x, m.y)
    upper = X * (Y - X) * 0.02**2 < (1 - Y) * 0.01**2
    assert np.array_equal(m.circulation[m.inside] == 3, upper[m.inside])


# --- streaming statistics ----------------------------------------------------------------------

def test_running_moments_of_one_to_n_have_the_closed_form_mean_and_variance():
    n = 10_001
    values = np.arange(1.0, n + 1)[:, None]
    blocks = np.array_split(values, 13)
    total = RunningMoments.of(blocks[0])
    for b in blocks[1:]:
        total = total.merge(RunningMoments.of(b))
    assert total.count[0] == n and total.mean[0] == (n + 1) / 2
    assert total.variance[0] == pytest.approx(n * (n + 1) / 12, rel=1e-14)  # sample variance of 1..n
    assert total.minimum[0] == 1 and total.maximum[0] == n


def test_merging_in_any_order_gives_the_same_moments_to_round_off():
    rng = np.random.default_rng(1)
    data = np.column_stack([rng.lognormal(3.0, 1.0, 5000), rng.normal(1e6, 1.0, 5000)])
    data[rng.random(5000) < 0.1, 0] = np.nan  # NaN is left out
    cuts = np.sort(rng.choice(np.arange(1, 5000), 20, replace=False))
    parts = [RunningMoments.of(b) for b in np.split(data, cuts)]
    results = []
    for _ in range(5):
        order = rng.permutation(len(parts))
        total = parts[order[0]]
        for k in order[1:]:
            total = total.merge(parts[k])
        results.append(total)
    finite = [data[np.isfinite(data[:, j]), j] for j in range(2)]
    for r in results:
        assert r.count.tolist() == [len(f) for f in finite]
        assert np.allclose(r.mean, [f.mean() for f in finite], rtol=1e-14, atol=0)
        assert np.allclose(r.variance, [f.var(ddof=1) for f in finite], rtol=1e-11, atol=0)


def test_the_keyed_sample_is_the_same_in_any_order_and_exact_when_it_holds_everything():
    rng = np.random.default_rng(2)
    n, size = 3000, 500
    values = rng.random((n, 2))
    keys = case_keys(42, np.arange(n))
    assert len(set(keys.tolist())) == n
    parts = [KeyedSample.of(keys[s], values[s], size) for s in np.array_split(rng.permutation(n), 7)]
    a, b = parts[0], parts[-1]
    for p in parts[1:]:
        a = a.merge(p)
    for p in parts[-2::-1]:
        b = b.merge(p)
    assert np.array_equal(a.keys, b.keys) and np.array_equal(a.values, b.values)
    assert a.seen == n and not a.exact and len(a.keys) == size
    # Uniform(0, 1) values: the quantile estimates are within the stated rank error (95 %)
    q = np.array([0.05, 0.5, 0.95])
    assert np.all(np.abs(a.quantiles(q) - q[:, None]) <= a.rank_error(0.05)[None, :])
    whole = KeyedSample.of(keys[:1000], values[:1000], n).merge(KeyedSample.of(keys[1000:], values[1000:], n))
    assert whole.exact and np.all(whole.rank_error() == 0)
    assert np.array_equal(whole.quantiles(q), np.quantile(values, q, axis=0))


def test_counts_add_up():
    a = Counts.of({"axis": np.array([1, 2, 2]), "predicted": np.array(["stable", "unstable", "unstable"])})
    b = Counts.of({"axis": np.array([3, 2]), "predicted": np.array(["unstable", "unstable"])})
    assert a.merge(b).as_dict() == {"axis": {"1": 1, "2": 3, "3": 1}, "predicted": {"stable": 1, "unstable": 4}}


def test_the_order_statistics_statement_of_hanson_and_beard():
    # NASA/TP-2010-216447: with no failure, success >= (1 - c)^(1/n)
    assert success_lower_bound(852, 0, 0.90) == pytest.approx(0.9973, abs=5e-5)
    assert runs_needed(0.9973, 0.90) == 852
    assert runs_needed(0.999, 0.95) == 2995 and runs_needed(0.99, 0.95) == 299
    assert runs_needed(0.99, 0.95, failures=1) == 473  # the one-failure row of the usual table
    # with k failures the bound p makes n - k or more successes exactly 1 - c probable
    for n, k, c in ((100, 3, 0.9), (1000, 10, 0.95), (50, 49, 0.5)):
        p = success_lower_bound(n, k, c)
        assert stats.binom.sf(n - k - 1, n, p) == pytest.approx(1 - c, rel=1e-9)
    assert success_lower_bound(10, 10, 0.9) == 0.0
    with pytest.raises(ValueError, match=r"^confidence = 1.0 must be a number strictly between 0 and 1$"):
        success_lower_bound(10, 0, 1.0)
    with pytest.raises(ValueError, match=r"^failures = 11 must be at most cases = 10$"):
        success_lower_bound(10, 11, 0.9)


# --- chunks: the results do not depend on them ---------------------------------------------------

def _frozen(chunks) -> dict:
    cols = list(chunks)
    return {k: np.concatenate([c[k] for c in cols]) for k in cols[0]}


@pytest.mark.parametrize("sampling", ["random", "lhs"])
def test_rows_and_statistics_are_the_same_whatever_the_chunk_size(sampling, monkeypatch):
    import tumble.ensemble.sweep as module

    monkeypatch.setattr(module, "STATS_BLOCK", 16)  # several statistics blocks in 37 cases
    criterion = Criterion("flips", minimum=1)
    sweep = t_handle_sweep(37, sampling=sampling, criterion=criterion)
    runs = {}
    for chunk in (5, 16, 37, 100):
        seen = []
        summary = summarize(run_chunks(sweep, chunk=chunk), 7, criterion, sample_size=20, on_chunk=seen.append)
        runs[chunk] = (_frozen(seen), summary.as_dict(criterion))
    first_cols, first_summary = runs[5]
    assert first_summary["criterion"]["passed"] + first_summary["criterion"]["failed"] == 37
    for cols, summary in runs.values():
        assert cols.keys() == first_cols.keys()
        for k in cols:
            assert np.array_equal(cols[k], first_cols[k]), k
        assert summary == first_summary


def test_run_chunks_resumes_from_a_store_and_computes_only_what_is_missing():
    class Store:
        def __init__(self):
            self.chunks = {}

        def has(self, k):
            return k in self.chunks

        def load(self, k):
            return self.chunks[k]

        def save(self, k, columns):
            self.chunks[k] = columns

    class Counting:
        calls = 0

        def map(self, fn, tasks):
            for k, task in enumerate(tasks):
                Counting.calls += 1
                yield k, fn(*task)

    sweep = t_handle_sweep(20)
    store = Store()
    partial = run_chunks(sweep, chunk=4, store=store, backend=Counting())
    next(partial), next(partial)
    partial.close()  # interrupted after two of five chunks
    assert sorted(store.chunks) == [0, 1] and Counting.calls == 2
    resumed = _frozen(run_chunks(sweep, chunk=4, store=store, backend=Counting()))
    assert Counting.calls == 5  # three more
    fresh = _frozen(run_chunks(sweep, chunk=4))
    assert all(np.array_equal(resumed[k], fresh[k]) for k in fresh)


def test_the_stability_map_figure_draws_the_triangle_with_units(tmp_path):
    from matplotlib.figure import Figure

    from tumble.viz import figure_stability_map, save_figure

    path = tmp_path / "map.png"
    fig = figure_stability_map(10.0, (0.01, 0.01), resolution=60, points={"T-handle": (2 / 7, 5 / 7)})
    save_figure(fig, path)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    ax = fig.axes[0]
    assert ax.get_xlabel() == r"$I_1 / I_3$ (dimensionless)" and ax.get_ylabel() == r"$I_2 / I_3$ (dimensionless)"
    assert fig.axes[1].get_xlabel() == "flip interval (s)"  # the colour bar, below the map
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert r"$I_1 + I_2 = I_3$: planar bodies (triangle inequality)" in labels
    edge = next(line for line in ax.get_lines() if line.get_label().startswith(r"$I_1 + I_2"))
    assert np.allclose(np.sum(edge.get_xydata(), axis=1), 1.0)  # x + y = 1
    ax = Figure().subplots()
    assert figure_stability_map(ax=ax, resolution=20) is ax.figure


def test_the_sweep_figure_shows_flip_periods_or_nutation(tmp_path):
    from tumble.viz import figure_sweep, save_figure

    flipping = compute_chunk(t_handle_sweep(12), 0, 12)
    fig = figure_sweep(flipping, title="T-handle", cases=100)
    save_figure(fig, tmp_path / "sweep.png")
    assert (tmp_path / "sweep.png").stat().st_size > 0
    assert fig.axes[0].get_xlabel() == "flip period (s)" and fig.axes[2].get_xlabel() == "exact flip period (s)"
    assert fig._suptitle.get_text() == "T-handle (12 of 100 cases)"
    rates = InitialRates(omega=(0.1, 0.1, 10.0), frame="design")
    stable = compute_chunk(Sweep(ensemble(T_HANDLE_SPREAD, 6, preset="t-handle", rates=rates), RunSettings(t_end=5.0)), 0, 6)
    fig = figure_sweep(stable)
    assert fig.axes[0].get_xlabel() == "largest nutation angle (rad): no case flips"
    assert fig.axes[2].get_xlabel() == "flips"


def test_chunks_finishing_out_of_order_are_put_back_in_order():
    class Reversed:  # a backend whose chunks finish last to first, as a cluster's may
        def map(self, fn, tasks):
            done = [(k, fn(*task)) for k, task in enumerate(tasks)]
            yield from reversed(done)

    sweep = t_handle_sweep(21)
    saved = []

    class Store:
        def has(self, k):
            return False

        def save(self, k, columns):
            saved.append(k)

    shuffled = _frozen(run_chunks(sweep, chunk=4, store=Store(), backend=Reversed()))
    assert saved == [5, 4, 3, 2, 1, 0]  # each kept as soon as it finished
    plain = _frozen(run_chunks(sweep, chunk=4))
    assert shuffled["case"].tolist() == list(range(21))
    assert all(np.array_equal(shuffled[k], plain[k]) for k in plain)


def test_chunk_ranges_of_1e8_cases_are_not_a_list_of_1e8_ranges():
    """Issue 27 item 10(e): chunk = 1 over 1e8 cases is a lazy sequence, not 1e8 tuples in memory."""
    import sys

    from tumble.ensemble.sweep import chunk_ranges

    ranges = chunk_ranges(10**8, 1)
    assert not isinstance(ranges, list) and sys.getsizeof(ranges) < 1000
    assert len(ranges) == 10**8 and ranges[0] == (0, 1) and ranges[12345] == (12345, 12346)
    assert ranges[-1] == (10**8 - 1, 10**8) and next(iter(ranges)) == (0, 1)
    with pytest.raises(IndexError):
        ranges[10**8]
    assert list(chunk_ranges(10, 4)) == [(0, 4), (4, 8), (8, 10)] and list(chunk_ranges(8, 4)) == [(0, 4), (4, 8)]
    assert len(chunk_ranges(0, 4)) == 0 and list(chunk_ranges(0, 4)) == [] and chunk_ranges(10, 4)[1:] == [(4, 8), (8, 10)]


def test_case_0_of_a_random_t_handle_sweep_is_classified_by_its_circulation():
    """Issue 27 item 9: omega0 = (8.3, 8.2, 7.5) rad/s on the T-handle has its largest component on
    axis 1 but circulates about the major axis (L^2 > 2 E I2). It was "axis 1, predicted stable"
    with 45 flips (of omega_1); the columns now describe the motion and agree with each other."""
    sweep = Sweep(Ensemble(BodySampler(tumble.t_handle()), InitialRates(omega=(8.3, 8.2, 7.5)), 1),
                  RunSettings(t_end=20.0, samples=2000))
    cols = compute_chunk(sweep, 0, 1)
    I, w = cols_moments(cols), np.array([8.3, 8.2, 7.5])
    assert np.sum((I * w) ** 2) > np.sum(I * w * w) * I[1]  # L^2 > 2 E I2: about the major axis
    assert cols["circulation"][0] == cols["axis"][0] == 3 and cols["predicted"][0] == "stable"
    assert cols["flips"][0] == 0 and np.isnan(cols["flip_period [s]"][0]) and np.isnan(cols["flip_period_exact [s]"][0])
    assert cols["wobble_frequency [rad/s]"][0] > 0 and cols["growth_rate [1/s]"][0] == 0


def test_the_stability_report_classifies_case_0_as_the_sweep_does():
    """Issue 27 (item 9, the one-run report): ``stability_report`` named the axis with the largest
    omega component, so omega0 = (8.3, 8.2, 7.5) rad/s on the T-handle was "axis 1, predicted
    stable" there while omega_1 flipped; it now classifies by the circulation, as the sweep."""
    from tumble.analysis import flip_times

    w0 = (8.3, 8.2, 7.5)
    sweep = Sweep(Ensemble(BodySampler(tumble.t_handle()), InitialRates(omega=w0), 1), RunSettings(t_end=20.0, samples=2000))
    cols = compute_chunk(sweep, 0, 1)
    traj = tumble.simulate(tumble.t_handle(), w0, t_end=20.0, samples=2000)  # principal frame, as the sweep's rates
    report = stability_report(traj)
    assert report["axis"] == cols["axis"][0] == 3 and report["circulation"] == cols["circulation"][0] == 3
    assert report["role"] == "major" and report["predicted"] == cols["predicted"][0] == "stable"
    assert report["flips"] == cols["flips"][0] == 0 and report["flip_period"] is None and report["flip_period_exact"] is None
    assert report["wobble_frequency"] == pytest.approx(cols["wobble_frequency [rad/s]"][0], rel=1e-15)
    assert report["growth_rate"] is None and cols["growth_rate [1/s]"][0] == 0
    assert np.all(traj.omega[:, 2] > 0) and len(flip_times(traj.t, traj.omega[:, 0])) >= 40  # omega_1 flips, omega_3 never


def test_each_row_of_a_random_rate_sweep_is_what_its_run_reports():
    """The one-run report and the sweep's columns follow one rule (spin_prediction) for rates far
    from every axis: axis, circulation, prediction, linearised rates and flips agree case by case."""
    rates = InitialRates(omega=(0.0, 0.0, 0.0), distribution="normal", spread=(5.0, 5.0, 5.0))
    sweep = Sweep(Ensemble(BodySampler(tumble.t_handle()), rates, 16, seed=3), RunSettings(t_end=20.0, samples=4000))
    cols = compute_chunk(sweep, 0, 16)
    x = sweep.ensemble.inputs(0, 16)
    kinds = set()
    for i in range(16):
        report = stability_report(tumble.simulate(props_of(x.moments[i], x.axes[i]), x.omega0[i], t_end=20.0, samples=4000))
        for key in ("axis", "circulation", "predicted", "flips"):
            assert report[key] == cols[key][i], (i, key)
        for key, column in (("growth_rate", "growth_rate [1/s]"), ("wobble_frequency", "wobble_frequency [rad/s]")):
            value = cols[column][i]
            assert report[key] == (pytest.approx(value, rel=1e-12) if value > 0 else None), (i, key)
        kinds.add((report["axis"], report["predicted"]))
    assert {p for _, p in kinds} == {"stable", "unstable"} and len(kinds) >= 3
    assert any(a != 2 and p == "unstable" for a, p in kinds)  # far from every axis: axis 1 or 3 turns over


def cols_moments(cols):
    return np.array([cols[f"I{j} [kg m^2]"][0] for j in (1, 2, 3)])


def test_the_columns_of_a_random_rate_sweep_agree_with_each_other():
    """Issue 27 item 9: rates far from any axis. Torque-free, a case flips (its spin axis, the one
    nearest L, reverses relative to L) exactly when it is predicted unstable, i.e. when its spin axis
    is not its circulation axis; the summary states the fraction that flips with its interval."""
    rates = InitialRates(omega=(0.0, 0.0, 0.0), distribution="normal", spread=(5.0, 5.0, 5.0))
    sweep = Sweep(Ensemble(BodySampler(tumble.t_handle()), rates, 200, seed=3), RunSettings(t_end=20.0, samples=4000))
    cols = compute_chunk(sweep, 0, 200)
    stable = cols["predicted"] == "stable"
    assert 0 < stable.sum() < 200
    assert np.array_equal(stable, cols["axis"] == cols["circulation"])
    assert np.all(cols["flips"][stable] == 0) and np.all(np.isnan(cols["flip_period_exact [s]"][stable]))
    # every unstable case whose exact interval fits the run flips, at that interval
    seen = ~stable & (cols["flip_period_exact [s]"] < 5.0)
    assert seen.sum() > 0.8 * (~stable).sum() and np.all(cols["flips"][seen] >= 2)
    both = seen & np.isfinite(cols["flip_period [s]"])
    assert np.allclose(cols["flip_period [s]"][both], cols["flip_period_exact [s]"][both], rtol=0.02)
    assert np.all(np.isfinite(cols["growth_rate [1/s]"][cols["axis"] == 2]))
    summary = SweepSummary.of(cols, seed=3).as_dict()
    k = int(np.sum(cols["flips"] >= 1))
    assert summary["flipped"]["cases"] == k and summary["flipped"]["fraction"] == k / 200
    low, high = summary["flipped"]["interval"]
    assert low < k / 200 < high and summary["flipped"]["confidence"] == 0.95


def test_a_preset_dispersion_of_a_body_not_made_so_is_refused():
    """A walkthrough of the sweeps (2026-12-03): a 0.5 m by 1.2 m T-handle given with preset="t-handle" but
    without its parameters was swept as the default 1 m handle (moments ~0.125, 0.3125, 0.4375 for
    0.078, 0.18, 0.258 kg m^2), and a Box as a T-handle, without a word."""
    body = tumble.t_handle(shaft_length=0.5, crossbar_length=1.2)
    spread = (Dispersion("preset", 0.01, field="crossbar_length"),)
    with pytest.raises(ValueError, match=r"body = 'T-handle' \(mass 3 kg, moments 0.078125, 0.18, 0.258125 kg m\^2\) is "
                                         r"not preset 't-handle' made with parameters = \{\}"):
        BodySampler(body, spread, preset="t-handle")
    with pytest.raises(ValueError, match="is not preset 't-handle'"):
        BodySampler(tumble.Body([tumble.Box(mass=3.0, size=(1.0, 2.0, 3.0))]), (), preset="t-handle")
    given = BodySampler(body, spread, preset="t-handle", parameters={"shaft_length": 0.5, "crossbar_length": 1.2})
    moments = Ensemble(given, InitialRates(omega=(10.0, 0.1, 0.1)), cases=64, seed=1).inputs().moments
    # a 1 % spread of the crossbar about 1.2 m: the moments spread about the body's own, 2 % for those it enters
    assert np.all(np.abs(np.median(moments, axis=0) / body.principal_moments - 1) < 0.01)


@pytest.mark.parametrize("resolution", [40, 200])
def test_the_maps_cells_on_the_diagonal_are_symmetric_bodies_left_out(resolution):
    """At an even resolution cells fall on the diagonal I1 = I2 (to an ulp) and were mapped with flip intervals
    up to 8.7e3 s, stretching the colour scale (a walkthrough, 2026-12-03): such a body is symmetric, with no
    intermediate axis; the interval off the diagonal grows only as the log of the distance to it."""
    from tumble.ensemble.reductions import stability_map

    m = stability_map(10.0, resolution=resolution)
    X, Y = np.meshgrid(m.x, m.y)
    assert np.all(Y[m.inside] - X[m.inside] > 1e-6) and np.any(np.isclose(X, Y, rtol=0, atol=1e-12))
    assert np.nanmax(m.flip_interval) < 400.0   # s: the cells nearest the edges, 10 rad/s spins
