"""Keplerian and TLE orbits, the sidereal angle, the gravity gradient along an orbit, IGRF along an
orbit: each against an independent route (a two-body DOP853 run, the sgp4 package's own calls
and sidereal time, the closed-form dipole, direct evaluation without the spline)."""

import datetime as dt
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from tumble.dynamics import (
    BDot,
    CircularOrbit,
    DipoleField,
    IGRFField,
    KeplerOrbit,
    Magnetorquers,
    TLEOrbit,
    gravity_gradient_of,
    simulate_controlled,
)
from tumble.dynamics.environment.earth import MU_EARTH, R_EARTH
from tumble.dynamics.models.gravity import GravityGradient
from tumble.dynamics.models.orbit_gravity import OrbitGravityGradient
from tumble.dynamics.environment.sidereal import greenwich_sidereal_angle, julian_date

ISS_2019 = ("1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991",
            "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482")


def test_julian_date_and_sidereal_angle_agree_with_sgp4():
    sgp4_api = pytest.importorskip("sgp4.api")
    from sgp4.propagation import gstime
    rng = np.random.default_rng(3)
    for seconds in rng.uniform(-30 * 365.25 * 86400, 30 * 365.25 * 86400, 25):
        when = dt.datetime(2000, 1, 1, 12) + dt.timedelta(seconds=float(seconds))
        jd, fr = sgp4_api.jday(when.year, when.month, when.day, when.hour, when.minute,
                               when.second + when.microsecond * 1e-6)
        assert julian_date(when) == pytest.approx(jd + fr, abs=1e-8)   # days: under a millisecond
        assert float(greenwich_sidereal_angle(jd + fr)) == pytest.approx(gstime(jd + fr), abs=1e-10)


def test_kepler_orbit_is_the_two_body_motion():
    """DOP853 on r'' = -mu r / |r|^3 from the orbit's own r(0), v(0) (an independent route)."""
    orbit = KeplerOrbit(12_000e3, 0.45, 1.1, raan=2.0, arg_perigee=0.7, mean_anomaly=2.5)
    y0 = np.concatenate([orbit.position_eci(0.0), orbit.velocity_eci(0.0)])

    def two_body(t, y):
        r = y[:3]
        return np.concatenate([y[3:], -MU_EARTH * r / np.linalg.norm(r) ** 3])

    t = np.linspace(0.0, 1.7 * orbit.period, 9)
    sol = solve_ivp(two_body, (0.0, t[-1]), y0, method="DOP853", t_eval=t, rtol=3e-14, atol=1e-9)
    # DOP853's own error: 5 mm at rtol 1e-11, 0.5 mm at 1e-12, 0.04 mm at 3e-14 (it converges on the ellipse)
    np.testing.assert_allclose(sol.y[:3].T, orbit.position_eci(t), rtol=0, atol=2e-4)   # m, of 1e7
    np.testing.assert_allclose(sol.y[3:].T, orbit.velocity_eci(t), rtol=0, atol=2e-7)   # m/s
    h = np.cross(orbit.position_eci(t), orbit.velocity_eci(t))
    expected = math.sqrt(MU_EARTH * 12_000e3 * (1 - 0.45**2))
    np.testing.assert_allclose(np.linalg.norm(h, axis=1), expected, rtol=1e-13)


def test_kepler_equation_solved_to_round_off_at_high_eccentricity():
    orbit = KeplerOrbit(140_000e3, 0.95)
    t = np.linspace(0.0, orbit.period, 2001)
    r = np.linalg.norm(orbit.position_eci(t), axis=1)
    v = np.linalg.norm(orbit.velocity_eci(t), axis=1)
    np.testing.assert_allclose(v**2, MU_EARTH * (2 / r - 1 / 140_000e3), rtol=1e-11)   # vis-viva
    assert r.min() == pytest.approx(140_000e3 * 0.05, rel=1e-12)   # perigee at t = 0


def test_kepler_orbit_orientation_is_the_textbook_one():
    """The orbit normal and the perigee direction in closed form from the classical elements (the
    perifocal-to-inertial rotation written out: Vallado 4th ed. sec. 2.6; Curtis, *Orbital
    Mechanics for Engineering Students*, ch. 4), not the module's composition of scipy rotations."""
    a, e, inc, raan, argp = 12_000e3, 0.45, 1.1, 2.0, 0.7
    orbit = KeplerOrbit(a, e, inc, raan=raan, arg_perigee=argp, mean_anomaly=0.0)
    normal = [math.sin(inc) * math.sin(raan), -math.sin(inc) * math.cos(raan), math.cos(inc)]
    perigee = [math.cos(raan) * math.cos(argp) - math.sin(raan) * math.sin(argp) * math.cos(inc),
               math.sin(raan) * math.cos(argp) + math.cos(raan) * math.sin(argp) * math.cos(inc),
               math.sin(argp) * math.sin(inc)]
    t = np.linspace(0.0, orbit.period, 7)
    h = np.cross(orbit.position_eci(t), orbit.velocity_eci(t))
    np.testing.assert_allclose(h / np.linalg.norm(h, axis=1)[:, None], np.tile(normal, (7, 1)), rtol=0, atol=1e-14)
    np.testing.assert_allclose(orbit.position_eci(0.0), a * (1 - e) * np.array(perigee), rtol=0, atol=1e-8)   # m, of 7e6


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"semi_major_axis": 7000e3, "eccentricity": 1.0}, "eccentricity = 1.0 must lie in"),
    ({"semi_major_axis": 7000e3, "eccentricity": 0.2}, "perigee at 5.6e\\+06 m, inside the Earth"),
    ({"semi_major_axis": -1.0}, "semi_major_axis"),
    ({"semi_major_axis": 7000e3, "inclination": 4.0}, "inclination = 4.0 must lie in"),
])
def test_kepler_orbit_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        KeplerOrbit(**kwargs)


def test_tle_orbit_wraps_sgp4():
    sgp4_api = pytest.importorskip("sgp4.api")
    iss = TLEOrbit(*ISS_2019)
    sat = sgp4_api.Satrec.twoline2rv(*ISS_2019)
    assert iss.epoch == dt.datetime(2019, 12, 9, 16, 38, 29, 363424, tzinfo=dt.UTC)
    t = np.array([0.0, 1234.5, 86400.0 * 3 + 17.25])
    for ti, r, v in zip(t, iss.position_eci(t), iss.velocity_eci(t)):
        days = sat.jdsatepochF + ti / 86400.0
        err, r_km, v_kms = sat.sgp4(sat.jdsatepoch + math.floor(days), days - math.floor(days))
        assert err == 0
        np.testing.assert_allclose(r, np.array(r_km) * 1e3, rtol=0, atol=1e-6)
        np.testing.assert_allclose(v, np.array(v_kms) * 1e3, rtol=0, atol=1e-9)
    altitude = np.linalg.norm(iss.position_eci(np.linspace(0, iss.period, 50)), axis=1) - R_EARTH
    assert 380e3 < altitude.min() < altitude.max() < 440e3   # the ISS in December 2019
    assert iss.period == pytest.approx(86400 / 15.50103472, rel=1e-9)


def test_tle_orbit_bad_input():
    pytest.importorskip("sgp4")
    with pytest.raises(ValueError, match="line1 = 'nonsense' must be"):
        TLEOrbit("nonsense", ISS_2019[1])


def test_orbit_gravity_gradient_follows_the_radius():
    """At perigee and apogee of an ellipse the torque scales as (a / r)^3 against the circle of radius a."""
    I = [1.0, 2.0, 3.0]
    att = Rotation.from_rotvec([0.2, -0.4, 0.3])
    e, a = 0.3, 20_000e3
    ellipse = gravity_gradient_of(KeplerOrbit(a, e)).bind(I)
    circle = gravity_gradient_of(KeplerOrbit(a)).bind(I)
    half = KeplerOrbit(a).period / 2
    np.testing.assert_allclose(ellipse(0.0, np.zeros(3), att), circle(0.0, np.zeros(3), att) / (1 - e) ** 3,
                               rtol=1e-12, atol=1e-20)
    np.testing.assert_allclose(ellipse(half, np.zeros(3), att), circle(half, np.zeros(3), att) / (1 + e) ** 3,
                               rtol=1e-9, atol=1e-20)


def test_igrf_degree_one_is_the_dipole_and_the_spline_is_faithful():
    pytest.importorskip("ppigrf")
    orbit = CircularOrbit(altitude=550e3, inclination=math.radians(53.0), raan=1.0, arg_latitude=0.4)
    f1 = IGRFField(orbit, "2024-06-01T06:00:00", max_degree=1)
    dipole = DipoleField(orbit, gmst0=f1.gmst0, coefficients=f1.gauss_degree1())
    t = np.random.default_rng(5).uniform(0.0, 4 * orbit.period, 40)
    np.testing.assert_allclose(f1.world(t), [dipole.world(x) for x in t], rtol=0, atol=1e-14)   # T, of ~3e-5
    full = IGRFField(orbit, "2024-06-01T06:00:00")
    direct = full.world_direct(t)
    assert np.max(np.abs(full.world(t) - direct)) < 1e-9 * np.linalg.norm(direct, axis=1).min()
    gap = np.linalg.norm(direct - f1.world(t), axis=1) / np.linalg.norm(direct, axis=1)
    assert 0.02 < np.median(gap) < 0.5   # the non-dipole part: tens of per cent of the field, not zero


def test_igrf_along_a_tle_uses_its_epoch_and_frame():
    pytest.importorskip("sgp4")
    pytest.importorskip("ppigrf")
    iss = TLEOrbit(*ISS_2019)
    field = IGRFField(iss)
    assert field.epoch == iss.epoch
    t = np.linspace(0.0, iss.period, 40)
    b = np.linalg.norm(field.world(t), axis=1)
    assert 18e-6 < b.min() < b.max() < 60e-6   # 400 km, +-52 deg latitude


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"epoch": "1850-01-01T00:00:00"}, "outside the model's years"),
    ({"epoch": "yesterday"}, "epoch = 'yesterday' is not an ISO 8601"),
    ({"epoch": "2024-01-01T00:00:00", "max_degree": 14}, "max_degree = 14 must be"),
    ({"epoch": "2024-01-01T00:00:00", "step": 0.0}, "step"),
    ({}, "epoch is needed"),
])
def test_igrf_bad_input(kwargs, match):
    pytest.importorskip("ppigrf")
    with pytest.raises(ValueError, match=match):
        IGRFField(CircularOrbit(altitude=500e3), **kwargs)


def test_bdot_detumbles_in_igrf_on_an_elliptic_orbit():
    """A closed-loop run with the full field and the gravity gradient along an ellipse: the rate
    falls, and the momentum budget (body + external impulse) closes."""
    pytest.importorskip("ppigrf")
    orbit = KeplerOrbit(R_EARTH + 900e3, 0.05, math.radians(80.0))
    run = simulate_controlled([0.0067, 0.0419, 0.0419], [0.05, -0.04, 0.03], t_end=600.0,
                              controller=BDot(gain=3e-4, period=2.0, form="normalized"),
                              field=IGRFField(orbit, "2026-11-25T00:00:00"), magnetorquers=Magnetorquers(0.2),
                              gravity_gradient=gravity_gradient_of(orbit))
    assert run.rate[-1] < 0.6 * run.rate[0]
    assert run.budget_error().max() < 1e-12 * np.linalg.norm(run.momentum_world[0]) + 1e-15


# -- a walkthrough of the orbits by a spacecraft engineer (2026-12-03) ---------------------------

def _with_checksum(line: str) -> str:
    """``line`` with its last digit the checksum of the first 68 (CelesTrak's rule, computed here)."""
    return line[:68] + str(sum(int(c) if c.isdigit() else c == "-" for c in line[:68]) % 10)


def test_a_tle_line_with_a_leading_space_flies_as_without_it():
    """sgp4 reads fixed columns: a line pasted with a leading space passed the checks (which strip it)
    and every position came out NaN, a scenario then failing with "`y` must contain only finite values"."""
    pytest.importorskip("sgp4")
    clean = TLEOrbit(*ISS_2019).position_eci([0.0, 60.0])
    for lines in ((" " + ISS_2019[0], ISS_2019[1]), (ISS_2019[0], ISS_2019[1] + " \n")):
        np.testing.assert_array_equal(TLEOrbit(*lines).position_eci([0.0, 60.0]), clean)
    assert np.all(np.isfinite(clean)) and 6.6e6 < np.linalg.norm(clean[0]) < 6.9e6   # m: the ISS's ~420 km


def test_a_tle_of_two_satellites_lines_is_refused():
    pytest.importorskip("sgp4")
    other = _with_checksum(ISS_2019[1].replace("25544", "25545", 1))
    with pytest.raises(ValueError, match="line1's satellite number '25544' is not line2's '25545'"):
        TLEOrbit(ISS_2019[0], other)


def test_a_field_epoch_other_than_the_tles_is_refused():
    """The orbit's t = 0 is the TLE's epoch; an IGRF field given another epoch read the Earth's angle 6 h
    off (the field's direction up to 25 degrees off over an orbit) and summary.json wrote that epoch as
    the orbit's."""
    pytest.importorskip("sgp4")
    pytest.importorskip("ppigrf")
    tle = TLEOrbit(*ISS_2019)
    later = (tle.epoch + dt.timedelta(hours=6)).replace(tzinfo=None).isoformat(timespec="seconds")
    with pytest.raises(ValueError, match=r"epoch = '2019-12-09T22:38:29' is not the TLE's own epoch 2019-12-09T16:38:29"):
        IGRFField(tle, epoch=later)
    assert IGRFField(tle, epoch=tle.epoch.isoformat()).epoch == IGRFField(tle).epoch == tle.epoch


@pytest.mark.parametrize("mu", [3.986e14, 3.986008e14])   # a rounded value, SGP4's WGS 72
def test_an_orbit_inside_the_earth_is_refused_for_any_earth_mu(mu):
    """The checks held only for mu == MU_EARTH exactly: mu = 3.986e14 put a circle 930 km underground."""
    with pytest.raises(ValueError, match="inside the Earth"):
        KeplerOrbit(6.0e6, 0.0, mu=mu)
    with pytest.raises(ValueError, match="inside the Earth"):
        GravityGradient(orbit_period=4000.0, mu=mu)
    with pytest.raises(ValueError, match="below 100 km"):
        CircularOrbit(altitude=10.0, mu=mu)
    moon = 4.9048695e12   # another body's mu leaves the Earth's radius out
    assert KeplerOrbit(2.0e6, 0.0, mu=moon).mean_motion == pytest.approx(math.sqrt(moon / 2.0e6**3), rel=1e-15)


@pytest.mark.parametrize("make", [
    lambda mu: CircularOrbit(500e3, mu=mu), lambda mu: KeplerOrbit(8e6, 0.1, mu=mu),
    lambda mu: GravityGradient(orbit_radius=7e6, mu=mu), lambda mu: OrbitGravityGradient(KeplerOrbit(8e6, 0.1), mu=mu),
])
def test_the_earths_mu_in_km3_s2_is_refused_everywhere(make):
    """398600.4418 (km^3/s^2) was refused by GravityGradient only: a circle's period came out 1.8e8 s, an
    ellipse's gravity-gradient torque 1e9 times too weak."""
    with pytest.raises(ValueError, match=r"mu = 398600.4418 m\^3/s\^2 is the Earth's in km\^3/s\^2"):
        make(398600.4418)


def test_a_torque_mu_other_than_its_orbits_is_refused():
    with pytest.raises(ValueError, match="differs from the orbit's mu"):
        OrbitGravityGradient(KeplerOrbit(8e6, 0.1), mu=3.9e14)
    assert gravity_gradient_of(KeplerOrbit(8e6, 0.1, mu=3.986e14)).mu == 3.986e14


def test_an_altitude_in_metres_below_the_karman_line_is_not_told_to_be_km():
    with pytest.raises(ValueError, match=r"below 100 km, where no orbit lasts \(the air brings it down within hours\)$"):
        CircularOrbit(altitude=50e3)   # 50 km, written in metres
    with pytest.raises(ValueError, match="give metres, 500000 for 500 km"):
        CircularOrbit(altitude=500)


def test_a_tle_propagated_far_from_its_epoch_is_warned_of():
    """A TLE run ten years past its epoch gave positions with no word (SGP4's error grows ~1-3 km a day)."""
    import warnings

    from tumble.dynamics.environment.ephemeris import MAX_TLE_AGE, TLEAgeWarning

    pytest.importorskip("sgp4")
    tle = TLEOrbit(*ISS_2019)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tle.position_eci([0.0, MAX_TLE_AGE * 0.99, -MAX_TLE_AGE * 0.99])
    with pytest.warns(TLEAgeWarning, match=r"the TLE is propagated 40 days from its epoch 2019-12-09"):
        tle.position_eci(-40 * 86400.0)
