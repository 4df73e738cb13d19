"""The Sun's ephemeris and the Earth's shadow (tumble.dynamics.environment.sun) against
independent values: published worked examples and a shadow computed another way."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tumble.dynamics.environment.earth import R_EARTH
from tumble.dynamics.environment.orbit import CircularOrbit
from tumble.dynamics.environment.sidereal import julian_date
from tumble.dynamics.environment.sun import AU, R_SUN, shadow_fraction, sun_direction_eci, sun_position_eci


def test_meeus_example_25a():
    """Meeus, *Astronomical Algorithms*, 2nd ed., example 25.a (1992 Oct 13.0 TD): apparent
    longitude 199.90895 deg, R = 0.99766 AU, right ascension 198.38083 deg, declination
    -7.78507 deg; the low-precision formula is good to 0.01 deg."""
    r = sun_position_eci(2448908.5)
    ra = math.degrees(math.atan2(r[1], r[0])) % 360.0
    dec = math.degrees(math.asin(r[2] / np.linalg.norm(r)))
    assert np.linalg.norm(r) / AU == pytest.approx(0.99766, abs=2e-5)
    assert ra == pytest.approx(198.38083, abs=0.01)
    assert dec == pytest.approx(-7.78507, abs=0.01)


def test_vallado_example_5_1():
    """Vallado, 4th ed., example 5-1 (2006-04-02 00:00 UTC): 0.9771945 I + 0.1924424 J + 0.0834308 K AU."""
    r = sun_position_eci(julian_date("2006-04-02T00:00:00")) / AU
    assert np.allclose(r, [0.9771945, 0.1924424, 0.0834308], atol=2e-5)
    assert np.allclose(np.linalg.norm(sun_direction_eci([2451545.0, 2453827.5]), axis=-1), 1.0)


def _disc_fraction(r_sat: np.ndarray, r_sun: np.ndarray, n: int = 801) -> float:
    """Visible fraction of the Sun's disc by counting points of a grid over it (no closed form):
    a point of the disc is hidden when its line of sight from the satellite passes within R_EARTH
    of the Earth's centre, in front of the satellite."""
    d = r_sun - r_sat
    dn = np.linalg.norm(d)
    u = d / dn
    e1 = np.cross(u, [0.0, 0.0, 1.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(u, e1)
    g = np.linspace(-1.0, 1.0, n)
    X, Y = np.meshgrid(g, g)
    inside = X**2 + Y**2 <= 1.0
    pts = r_sun + R_SUN * (X[inside, None] * e1 + Y[inside, None] * e2)
    rays = pts - r_sat
    rays /= np.linalg.norm(rays, axis=1, keepdims=True)
    tc = -(rays @ r_sat)   # closest approach of each ray to the Earth's centre
    miss = np.linalg.norm(r_sat + np.maximum(tc, 0.0)[:, None] * rays, axis=1)
    return float(np.mean(miss >= R_EARTH))


@pytest.mark.parametrize("offset_km", [-40.0, -15.0, 0.0, 10.0, 30.0])
def test_penumbra_against_counted_disc(offset_km):
    """Across the penumbra at 7,000 km the conical model's fraction is the counted disc's (to the grid's 0.5 %)."""
    r_sun = np.array([AU, 0.0, 0.0])
    x = -math.sqrt(7.0e6**2 - R_EARTH**2)
    # the penumbra's centre line at this distance lies a little outside R_EARTH
    r = np.array([x, R_EARTH + 18e3 + offset_km * 1e3, 0.0])
    r *= 7.0e6 / np.linalg.norm(r)
    assert float(shadow_fraction(r, r_sun)) == pytest.approx(_disc_fraction(r, r_sun), abs=5e-3)


def test_eclipse_fraction_of_an_equatorial_orbit():
    """Sun in the orbit plane (beta = 0): the cylindrical shadow covers ``asin(R_E / r) / pi`` of
    the orbit (plane geometry); the conical umbra is a little shorter, umbra plus penumbra a little longer."""
    orbit = CircularOrbit(altitude=500e3)
    t = np.linspace(0.0, orbit.period, 200001)
    r = orbit.position_eci(t)
    sun = np.array([AU, 0.0, 0.0])
    cyl = np.mean(shadow_fraction(r, sun, "cylindrical") == 0.0)
    con = shadow_fraction(r, sun)
    expected = math.asin(R_EARTH / orbit.radius) / math.pi
    assert cyl == pytest.approx(expected, abs=2e-5)
    assert np.mean(con == 0.0) < expected < np.mean(con < 1.0)
    # the penumbra lasts seconds in LEO (about 8 s at 500 km), each side
    assert 4.0 < np.mean((con > 0.0) & (con < 1.0)) * orbit.period / 2.0 < 20.0


def test_bad_model():
    with pytest.raises(ValueError, match="model = 'cone' is unknown; allowed: conical, cylindrical"):
        shadow_fraction([7e6, 0.0, 0.0], [AU, 0.0, 0.0], "cone")
