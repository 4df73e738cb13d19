"""The [orbit] table of a control scenario: circular, Keplerian or TLE orbits; the dipole or IGRF field."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from tumble.commands import run_scenario
from tumble.dynamics import CircularOrbit, DipoleField, IGRFField, KeplerOrbit, TLEOrbit
from tumble.io.bodyfile import body_from_table
from tumble.io.controlfile import control_scenario_from_table
from tumble.io.controlorbit import geomagnetic_inclination, orbit_from_table

ISS = ["1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991",
       "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482"]
BODY = body_from_table({"name": "cube", "parts": [{"kind": "box", "mass": 4.0, "size": [0.1, 0.1, 0.34]}]})


def _table(orbit):
    return {"initial": {"omega": [0.05, -0.05, 0.05]}, "simulation": {"t_end": 20.0}, "orbit": orbit,
            "actuators": {"magnetorquers": {"max_dipole": 0.2}},
            "control": {"kind": "bdot", "period": 1.0, "form": "normalized"}}


def test_tle_orbit_with_igrf_runs_and_reports_its_orbit():
    pytest.importorskip("sgp4")
    pytest.importorskip("ppigrf")
    from tumble.io.controlrun import control_summary
    scenario = control_scenario_from_table(_table({"tle": ISS, "field": "igrf", "gravity_gradient": True}), BODY)
    assert isinstance(scenario.orbit, TLEOrbit) and isinstance(scenario.field, IGRFField)
    assert scenario.field.epoch == scenario.orbit.epoch
    controller = scenario.controller()
    run = run_scenario(scenario, controller)
    assert run.rate[-1] < run.rate[0]
    assert run.budget_error().max() < 1e-15
    orbit = control_summary(scenario, run, controller)["orbit"]
    assert orbit["kind"] == "tle" and orbit["field"] == "igrf" and orbit["igrf_degree"] == 13
    assert orbit["epoch"].startswith("2019-12-09T16:38:29")


def test_geomagnetic_inclination_is_the_same_for_the_dipole_and_igrf_degree_one():
    """Two routes to the B-dot gain's xi_m: the closed-form dipole's coefficients and IGRF-14's degree-1 part."""
    pytest.importorskip("ppigrf")
    orbit = CircularOrbit(altitude=500e3, inclination=math.radians(97.4), raan=0.4)
    igrf = IGRFField(orbit, "2025-03-01T00:00:00", max_degree=1)
    dipole = DipoleField(orbit, gmst0=igrf.gmst0, coefficients=igrf.gauss_degree1())
    xi = geomagnetic_inclination(orbit, igrf)
    assert xi == pytest.approx(geomagnetic_inclination(orbit, dipole), abs=1e-15)
    # the sun-synchronous orbit is within the dipole's 9.4 deg tilt of the magnetic poles' plane
    assert abs(math.degrees(xi) - (180 - 97.4)) < 9.5 + 1e-9


def test_kepler_orbit_normal_from_r_cross_v():
    """geomagnetic_inclination reads the orbit normal from r x v: a Keplerian ellipse in the
    equator under an axial dipole lies in the magnetic equator."""
    pytest.importorskip("ppigrf")
    orbit = KeplerOrbit(7.5e6, 0.05, 0.0, arg_perigee=1.0, mean_anomaly=2.0)
    igrf = IGRFField(orbit, "2025-03-01T00:00:00", max_degree=1)
    g10, g11, h11 = igrf.gauss_degree1()
    tilt = math.atan2(math.hypot(g11, h11), abs(g10))
    assert geomagnetic_inclination(orbit, igrf) == pytest.approx(tilt, abs=1e-12)


@pytest.mark.parametrize(("orbit", "match"), [
    ({"altitude": 500e3, "tle": ISS}, "give exactly one of altitude .*, not altitude and tle"),
    ({"semi_major_axis": 7.2e6, "arg_latitude": 0.1}, "arg_latitude does not go with semi_major_axis"),
    ({"semi_major_axis": 7.2e6, "field": "dipole"}, 'field = "dipole" needs a circular orbit'),
    ({"altitude": 500e3, "field": "wmm"}, "field = 'wmm' is unknown; allowed: dipole, igrf"),
    ({"altitude": 500e3, "epoch": "2025-01-01T00:00:00"}, 'epoch goes with field = "igrf"'),
    ({"altitude": 500e3, "field": "igrf"}, "epoch is needed"),
    ({"tle": ["1 2 3"]}, "tle = \\['1 2 3'\\] must be a list of the two lines"),
])
def test_orbit_table_errors_name_the_key(orbit, match):
    if orbit.get("field") == "igrf":
        pytest.importorskip("ppigrf")
    with pytest.raises(ValueError, match="^orbit: " + match):
        control_scenario_from_table(_table(orbit), BODY)


def test_orbit_from_table_kepler_with_igrf():
    pytest.importorskip("ppigrf")
    orbit, field = orbit_from_table({"semi_major_axis": 7.2e6, "eccentricity": 0.02, "inclination": 1.0,
                                     "field": "igrf", "epoch": "2026-01-01T00:00:00", "igrf_degree": 5})
    assert isinstance(orbit, KeplerOrbit) and field.max_degree == 5
    assert 15e-6 < np.linalg.norm(field.world(100.0)) < 60e-6


def test_cli_runs_the_shipped_tle_example_briefly(tmp_path, capsys):
    pytest.importorskip("sgp4")
    pytest.importorskip("ppigrf")
    from tumble.cli import main

    out = tmp_path / "run"
    code = main(["simulate", str(CONTROL / "detumble_tle.toml"), "--t-end", "30", "--out", str(out)])
    assert code == 0, capsys.readouterr().err
    summary = json.loads((out / "summary.json").read_text())
    assert summary["orbit"]["kind"] == "tle" and summary["orbit"]["field"] == "igrf"
    assert summary["final_rate"] < summary["initial_rate"]


CONTROL = Path(__file__).resolve().parents[1] / "examples" / "control"


def test_wheels_alone_on_a_tle_need_no_field(tmp_path, capsys):
    """A wheels-only pointing on a TLE orbit was refused for the default dipole field it did not use
    ('field = "dipole" (the default) needs a circular orbit'; a walkthrough, issue 40): an ellipse or a TLE
    has no field unless the file names one, and magnetorquers without one are refused naming the cure."""
    from tumble.cli import main

    point = (CONTROL / "point.toml").read_text()
    tle = (CONTROL / "detumble_tle.toml").read_text().split("[orbit]\n", 1)[1].split("field =", 1)[0]
    text = point.split("[orbit]\n", 1)[0] + "[orbit]\n" + tle + "gravity_gradient = true\n\n" + \
        "[actuators.wheels]" + point.split("[actuators.wheels]", 1)[1]
    (tmp_path / "tle_point.toml").write_text(text)
    assert main(["simulate", str(tmp_path / "tle_point.toml"), "--t-end", "60", "--out", str(tmp_path / "run")]) == 0
    assert "pointing error" in capsys.readouterr().out
    rods = text.replace("[actuators.wheels]", "[actuators.magnetorquers]\nmax_dipole = 0.2\n\n[actuators.wheels]")
    (tmp_path / "rods.toml").write_text(rods)
    assert main(["simulate", str(tmp_path / "rods.toml"), "--out", str(tmp_path / "r2")]) == 2
    assert 'magnetorquers need a field: a circular [orbit] (its dipole) or field = "igrf"' in capsys.readouterr().err
