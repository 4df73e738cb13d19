"""Plain reprs and Jupyter's HTML display of bodies, mass properties and trajectories."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import tumble
from tumble.commands import run_scenario
from tumble.dynamics._display import SVG_POINTS, omega_svg
from tumble.io.scenario import resolve_run

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SVG = "{http://www.w3.org/2000/svg}"


def parse(html_text: str) -> ET.Element:
    """The HTML parsed as XML: every tag closed, every attribute quoted, every '<' and '&' escaped."""
    return ET.fromstring(html_text)


def rows(table: ET.Element) -> dict[str, str]:
    """The first two cells of each body row of a table, as {first: second}."""
    out = {}
    for tr in table.iter("tr"):
        cells = ["".join(td.itertext()) for td in tr.findall("td")]
        if len(cells) >= 2:
            out[cells[0]] = cells[1]
    return out


def polylines(svg: ET.Element) -> list[np.ndarray]:
    return [np.array([[float(v) for v in p.split(",")] for p in line.get("points").split()]).reshape(-1, 2)
            for line in svg.iter(f"{SVG}polyline")]


@pytest.fixture(scope="module")
def body():
    return tumble.t_handle()


@pytest.fixture(scope="module")
def flip(body):
    return tumble.simulate(body, [0.1, 10.0, 0.1], t_end=20.0)  # 500 samples about the intermediate axis


# Bodies and mass properties ---------------------------------------------------------------

def test_body_repr_is_one_short_line_with_the_numbers(body):
    text = repr(body)
    assert text == "Body('T-handle', 2 parts, m = 3 kg, I = (0.125, 0.3125, 0.4375) kg m^2)"
    assert str(body) == text


def test_mass_properties_repr_and_html(body):
    assert repr(body.properties) == "MassProperties(m = 3 kg, COM = (0, 0, 0.25) m, I = (0.125, 0.3125, 0.4375) kg m^2)"
    table = parse(body.properties._repr_html_())
    assert table.find("caption").text == "MassProperties"
    assert rows(table) == rows(parse(body._repr_html_()).find("table"))  # the body's first table


def test_reprs_stay_short_for_long_names_and_many_parts():
    parts = [tumble.PointMass(mass=0.01 * (k + 1), center=(k % 7, k % 5, k % 3)) for k in range(200)]
    body = tumble.Body(parts, name="a body with a very long name " * 20)
    assert len(repr(body)) < 200 and "\n" not in repr(body)
    assert "200 parts" in repr(body)
    traj = tumble.simulate(body, [0.1, 0.2, 0.3], t_end=1.0, samples=11)
    assert len(repr(traj)) < 200 and "\n" not in repr(traj)
    html_text = body._repr_html_()
    tables = parse(html_text).findall("table")
    body_rows = tables[1].findall("tbody/tr")
    assert len(body_rows) == 21  # 20 parts listed, then one row counting the other 180
    assert "and 180 more parts" in "".join(body_rows[-1].itertext())


def test_body_html_is_a_mass_properties_table(body):
    root = parse(body._repr_html_())
    props, parts = root.findall("table")
    assert "T-handle" in props.find("caption").text
    cells = rows(props)
    assert cells["mass"] == "3 kg"
    assert cells["centre of mass (design frame)"] == "(0, 0, 0.25) m"
    # I1 along the shaft (+z), I2 along the crossbar (+x), I3 normal to the T (+y): seed sec. 2.4 corrected
    assert cells["I1 (minor), axis in the design frame"] == "0.125 kg m^2 along (0, 0, 1)"
    assert cells["I2 (intermediate), axis in the design frame"] == "0.3125 kg m^2 along (1, 0, 0)"
    assert cells["I3 (major), axis in the design frame"] == "0.4375 kg m^2 along (0, 1, 0)"
    assert cells["intermediate axis"].startswith("(1, 0, 0): spin about it is unstable")
    listed = [["".join(td.itertext()) for td in tr.findall("td")] for tr in parts.findall("tbody/tr")]
    assert listed == [["0", "rod", "1.5", "(0, 0, 0)", ""], ["1", "rod", "1.5", "(0, 0, 0.5)", ""]]


def test_body_html_marks_removed_parts_and_symmetric_bodies():
    body = tumble.Body([tumble.Sphere(density=1000.0, radius=0.1),
                        tumble.Sphere(density=1000.0, radius=0.02, subtract=True)], name="hollowed")
    root = parse(body._repr_html_())
    props, parts = root.findall("table")
    assert rows(props)["intermediate axis"] == "none: a spherical body does not flip"
    kinds = [[td.text for td in tr.findall("td")] for tr in parts.findall("tbody/tr")]
    assert kinds[0][4] is None and kinds[1][4] == "removed"
    assert float(kinds[1][2]) == pytest.approx(1000.0 * 4 / 3 * np.pi * 0.02**3, rel=1e-5)


def test_names_are_escaped():
    name = "<script>alert('x') & co</script>"
    body = tumble.Body([tumble.Rod(mass=1.0, length=1.0), tumble.PointMass(mass=0.5, center=(0.3, 0.1, 0.0))],
                       name=name)
    traj = tumble.simulate(body, [1.0, 2.0, 3.0], t_end=1.0, samples=21)
    for html_text in (body._repr_html_(), traj._repr_html_()):
        assert "<script" not in html_text and "&lt;script&gt;" in html_text
        root = parse(html_text)  # well formed despite the name
        assert name in "".join(root.find("table/caption").itertext())


def test_every_shipped_body_displays():
    for path in sorted((EXAMPLES / "bodies").glob("*.toml")):
        body = tumble.load_body(path)
        assert len(repr(body)) < 200
        parse(body._repr_html_())


# Trajectories -----------------------------------------------------------------------------

def test_trajectory_repr(flip):
    assert repr(flip) == "Trajectory('T-handle', exact (auto), 500 samples, t = 0..20 s, torque-free)"
    assert "array(" not in repr(flip)


def test_batch_trajectory_repr_is_one_line():
    """A batch of bodies prints as one line, not its arrays (28 kB for 4 bodies x 50 samples)."""
    moments = [[1.0, 2.0, 3.0], [0.125, 0.3125, 0.4375], [1.0, 1.5, 2.0], [2.0, 2.5, 4.0]]
    batch = tumble.simulate_batch(moments, [[0.1, 1.0, 0.1]] * 4, t_end=5.0, samples=50)
    assert repr(batch) == "BatchTrajectory(4 bodies, exact (auto), 50 samples, t = 0..5 s, torque-free)"  # as simulate's
    assert batch[0].method_label == "exact (auto)" and batch.auto
    named = tumble.simulate_batch(moments, [[0.1, 1.0, 0.1]] * 4, t_end=5.0, samples=50, method="exact")
    assert repr(named).startswith("BatchTrajectory(4 bodies, exact, ") and not named[0].auto
    one = tumble.simulate_batch(moments[:1], [[0.1, 1.0, 0.1]], times=[2.0])
    assert repr(one).startswith("BatchTrajectory(1 body, ") and "1 sample, t = 2..2 s" in repr(one)


def test_trajectory_html_summary(flip):
    root = parse(flip._repr_html_())
    cells = rows(root.find("table"))
    assert cells["samples"] == "500"
    assert cells["method"] == "exact (auto)"
    assert cells["time span"] == "0 to 20 s"
    assert cells["omega(0), principal frame"] == "(0.1, 10, 0.1) rad/s"
    # E = sum I w^2 / 2 and |L| = |I w| for the moments (0.125, 0.3125, 0.4375) kg m^2
    w, I = np.array([0.1, 10.0, 0.1]), np.array([0.125, 0.3125, 0.4375])
    assert float(cells["energy E(0)"].removesuffix(" J")) == pytest.approx(0.5 * np.sum(I * w**2), rel=1e-5)
    assert float(cells["|L|(0)"].removesuffix(" kg m^2/s")) == pytest.approx(np.linalg.norm(I * w), rel=1e-5)
    drift = float(cells["energy drift, max |E - E0| / E0"])
    assert drift == pytest.approx(flip.drift["energy"], rel=1e-2) and drift < 1e-13


def test_omega_plot_follows_the_data(flip):
    svg = parse(flip._repr_html_()).find(f"{SVG}svg")
    assert svg is not None
    lines = polylines(svg)
    assert len(lines) == 3 and all(len(p) == SVG_POINTS for p in lines)
    width, height = float(svg.get("width")), float(svg.get("height"))
    box = svg.find(f"{SVG}rect")
    x0, y0 = float(box.get("x")), float(box.get("y"))
    x1, y1 = x0 + float(box.get("width")), y0 + float(box.get("height"))
    assert 0 < x0 < x1 <= width and 0 < y0 < y1 <= height
    # the curves span the box: time from edge to edge, the largest and smallest omega at top and bottom
    pts = np.vstack(lines)
    assert pts[:, 0].min() == pytest.approx(x0) and pts[:, 0].max() == pytest.approx(x1)
    assert pts[:, 1].min() == pytest.approx(y0) and pts[:, 1].max() == pytest.approx(y1)
    # read the values back through the axis mapping: they are the samples, to the pixel rounding
    idx = np.unique(np.linspace(0, len(flip) - 1, SVG_POINTS).round().astype(int))
    lo, hi = flip.omega.min(), flip.omega.max()
    for j, p in enumerate(lines):
        t_read = flip.t[0] + (p[:, 0] - x0) / (x1 - x0) * (flip.t[-1] - flip.t[0])
        w_read = hi - (p[:, 1] - y0) / (y1 - y0) * (hi - lo)
        np.testing.assert_allclose(t_read, flip.t[idx], atol=0.01 * 20.0 / (x1 - x0))
        np.testing.assert_allclose(w_read, flip.omega[idx, j], atol=0.01 * (hi - lo) / (y1 - y0))


def test_short_runs_keep_every_sample():
    traj = tumble.simulate(tumble.t_handle(), [1.0, 0.0, 0.5], t_end=2.0, samples=37)
    assert [len(p) for p in polylines(parse(traj._repr_html_()).find(f"{SVG}svg"))] == [37, 37, 37]


def test_run_from_rest(body):
    # omega = 0: a flat plot and no relative drift, without division warnings (errors under pytest's config)
    rest = tumble.simulate(body, [0.0, 0.0, 0.0], t_end=5.0)
    root = parse(rest._repr_html_())
    cells = rows(root.find("table"))
    assert cells["energy drift, max |E - E0| / E0"] == "n/a (starts at zero)"
    lines = polylines(root.find(f"{SVG}svg"))
    ys = np.concatenate([p[:, 1] for p in lines])
    assert np.all(np.isfinite(ys)) and np.ptp(ys) == 0.0
    zero = root.find(f"{SVG}svg/{SVG}line")
    assert float(zero.get("y1")) == pytest.approx(ys[0])  # the curves lie on the line omega = 0


@pytest.mark.parametrize("n", [1, 2])
def test_omega_svg_with_one_or_two_samples(n):
    t = np.linspace(0.0, 1.0, n)
    svg = parse(omega_svg(t, np.full((n, 3), 2.0)))
    assert all(len(p) == n and np.all(np.isfinite(p)) for p in polylines(svg))


@given(n=st.integers(1, 2 * SVG_POINTS), data=st.data())
def test_omega_svg_stays_in_its_box(n, data):
    t = np.cumsum(data.draw(arrays(float, n, elements=st.floats(0.0, 10.0))))
    omega = data.draw(arrays(float, (n, 3), elements=st.floats(-1e6, 1e6)))
    svg = parse(omega_svg(t, omega))
    box = svg.find(f"{SVG}rect")
    x0, y0 = float(box.get("x")), float(box.get("y"))
    x1, y1 = x0 + float(box.get("width")), y0 + float(box.get("height"))
    lines = polylines(svg)
    assert [len(p) for p in lines] == [min(n, SVG_POINTS)] * 3
    pts = np.vstack(lines)
    assert np.all((pts[:, 0] >= x0 - 0.01) & (pts[:, 0] <= x1 + 0.01) & (pts[:, 1] >= y0 - 0.01) & (pts[:, 1] <= y1 + 0.01))
    drawn = omega[np.unique(np.linspace(0, n - 1, min(n, SVG_POINTS)).round().astype(int))]
    if np.ptp(drawn) > 1e-9 * np.max(np.abs(drawn)):  # a range to fill: the extremes drawn touch the box
        assert pts[:, 1].min() == pytest.approx(y0, abs=0.01) and pts[:, 1].max() == pytest.approx(y1, abs=0.01)


@pytest.mark.parametrize("t, w", [
    ([5e-324, 1e-323], 1.0),  # a subnormal time span
    ([0.0], 1.1125369292536007e-308),  # one sample of a subnormal-sized omega
    ([0.0, 1.0], 1e308),  # values whose range overflows a double
])
def test_omega_svg_at_the_ends_of_double_range(t, w):
    omega = np.array([[w, -w, 0.5 * w]] * len(t))
    lines = polylines(parse(omega_svg(t, omega)))  # no overflow or invalid-value warning (errors here)
    assert all(np.all(np.isfinite(p)) for p in lines)


def test_gyrostat_run():
    traj = run_scenario(resolve_run(EXAMPLES / "wheel_t_handle.toml", t_end=2.0, samples=41))
    assert repr(traj) == "Trajectory('T-handle with wheel', dop853, 41 samples, t = 0..2 s, torque-free, 1 rotor)"
    cells = rows(parse(traj._repr_html_()).find("table"))
    J = traj.rotor_axial_moments
    assert cells["rotors, axial moments"] == "(" + f"{J[0]:.4g}" + ") kg m^2"
    # dop853 at rtol 1e-12; the work of the motor that holds the wheel's rate is counted
    assert float(cells["energy balance E - W_motor + E_dissipated drift, max |E - E0| / E0"]) < 1e-8


def test_damper_run():
    traj = run_scenario(resolve_run(EXAMPLES / "explorer1.toml", t_end=4.0, samples=21))
    assert repr(traj) == "Trajectory('Explorer 1', geometric, 21 samples, t = 0..4 s, torque-free, damper)"
    cells = rows(parse(traj._repr_html_()).find("table"))
    assert cells["damper moment J"] == "0.02 kg m^2"  # examples/explorer1.toml
    dissipated = float(cells["energy dissipated by the damper"].removesuffix(" J"))
    assert dissipated == pytest.approx(traj.dissipated[-1], rel=1e-5) and dissipated > 0


def test_torqued_run_reports_change_not_drift(body):
    traj = tumble.simulate(body, [0.0, 0.0, 1.0], t_end=2.0, samples=21, torque=tumble.ConstantTorque((0.0, 0.0, 0.01)))
    assert repr(traj).endswith(", torqued)")
    cells = rows(parse(traj._repr_html_()).find("table"))
    assert cells["external torque"] == "yes"
    # spun up about principal axis 3 by 0.01 N m along it for 2 s: dL/dt = tau (seed sec. 3), so |L| grows
    # from I3 * 1 rad/s = 0.4375 kg m^2/s by 0.02 kg m^2/s
    change = float(cells["|L| change (a torque acts), max ||L| - |L0|| / |L0|"])
    assert change == pytest.approx(0.02 / 0.4375, rel=1e-3)
    assert not re.search(r"drift", "".join(k for k in cells))
