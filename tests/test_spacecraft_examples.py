"""The spacecraft examples show their physics, checked against closed forms; their figures.

- explorer1.toml: the flat spin (Likins 1966, the major-axis rule): from spin about the minor
  axis to a rigid spin about a major axis at |L| / (I3 + J), the energy budget closed;
- wheel_t_handle.toml: a wheel with h > (I3 - I2) W stops the Dzhanibekov flip (the gyrostat's
  linearisation, tumble.dynamics.models.internal); stopped, the same body flips;
- reaction_wheel_slew.toml: L = I w + h = 0 from rest, so the body turns at w = -h / I;
- gravity_boom.toml: Lagrange-stable libration about the local vertical at
  n sqrt(3 (I_roll - I_yaw) / I_pitch) (docs/gravity-gradient.md).
"""

from __future__ import annotations

import dataclasses
import functools
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure
from scipy.special import ellipk

import tumble
from tumble.commands import run_scenario
from tumble.io.scenario import load_scenario
from tumble.viz import spacecraft
from tumble.viz.spacecraft import spacecraft_figures
from limits import HANG_S

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def crossings(t, x):
    """Times at which ``x`` changes sign, linearly interpolated between samples."""
    i = np.nonzero(np.sign(x[:-1]) * np.sign(x[1:]) < 0)[0]
    return t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i])


@functools.cache
def run(name: str):
    """``(scenario, trajectory)`` of an example scenario, run once per test session."""
    scenario = load_scenario(EXAMPLES / f"{name}.toml")
    return scenario, run_scenario(scenario)


# --- Explorer 1 ---------------------------------------------------------------------------------


def test_explorer1_body_is_the_published_cylinder():
    """13.97 kg, 205.1 cm x 15.2 cm (NSSDCA 1958-001A); the antennas in a cross keep it prolate
    symmetric: I1 about the long axis, I2 = I3 = (cylinder) m (3 r^2 + l^2) / 12 + the rods'."""
    explorer = run("explorer1")
    body = explorer[0].body
    assert body.mass == pytest.approx(13.97, rel=1e-12)
    m, r, l = 13.77, 0.076, 2.051
    ma, la, d = 0.05, 0.5, 0.326  # each antenna: mass, length, centre's distance from the axis
    I1 = m * r**2 / 2 + 4 * ma * (la**2 / 12 + d**2)
    It = m * (3 * r**2 + l**2) / 12 + 2 * ma * (la**2 / 12 + d**2)  # two rods across each transverse axis
    np.testing.assert_allclose(body.principal_moments, [I1, It, It], rtol=1e-12)
    np.testing.assert_allclose(np.abs(body.principal_axes[:, 0]), [0, 0, 1], atol=1e-15)  # minor = long axis


def test_explorer1_starts_about_the_minor_axis_with_the_damper_turning_along():
    scenario, traj = run("explorer1")
    I, J = traj.moments, scenario.damper.inertia
    w0 = traj.omega[0]
    np.testing.assert_allclose(np.abs(w0), [78.54, 0.05, 0.0], atol=1e-12)  # design z is axis 1, x axis 2
    np.testing.assert_allclose(traj.damper_omega[0], w0, rtol=0, atol=1e-12)
    L0 = (I + J) * w0  # body and sphere turning together
    np.testing.assert_allclose(traj.angular_momentum[0], L0, rtol=1e-14)
    np.testing.assert_allclose(traj.energy[0], 0.5 * np.sum((I + J) * w0**2), rtol=1e-14)
    nutation0 = np.arctan2((I[1] + J) * 0.05, (I[0] + J) * 78.54)  # L's angle from the long axis
    assert np.degrees(nutation0) == pytest.approx(2.09, abs=0.01)
    assert traj.nutation_angle[0] == pytest.approx(np.pi / 2 - nutation0, rel=1e-12)


def test_explorer1_ends_in_the_flat_spin():
    """|w| = |L| / (I3 + J) about a major axis (measured 2.8e-14 relative with |L| at the start, as
    docs/tour.md quotes it: round-off), L at 4.3e-10 rad from the major-axis plane, the sphere locked
    to the body, E = |L|^2 / (2 (I3 + J))."""
    scenario, traj = run("explorer1")
    I, J = traj.moments, scenario.damper.inertia
    L = traj.angular_momentum[-1]
    Ln = np.linalg.norm(L)
    assert Ln == pytest.approx(traj.angular_momentum_norm[0], rel=1e-12)  # |L| conserved
    assert np.linalg.norm(traj.omega[-1]) == pytest.approx(traj.angular_momentum_norm[0] / (I[2] + J), rel=1e-13)
    assert np.arcsin(abs(L[0]) / Ln) < 1e-6  # L in the plane of the major axes (I2 = I3)
    assert traj.nutation_angle[-1] < 1e-6
    np.testing.assert_allclose(traj.damper_omega[-1], traj.omega[-1], rtol=0, atol=1e-6)
    assert traj.energy[-1] == pytest.approx(Ln**2 / (2 * (I[2] + J)), rel=1e-6)
    # the energy fell by the ratio of the moments: (I1 + J) / (I3 + J) for a start near the minor axis
    assert traj.energy[-1] / traj.energy[0] == pytest.approx((I[0] + J) / (I[2] + J), rel=2e-3)


def test_explorer1_energy_budget_closes():
    """E + dissipated = E0 to 6e-8, as docs/tour.md and the example say (measured 5.4e-8 of E0 with
    the example's 0.015 s step, the splitting's own error: 9.1e-9 at 0.01 s); L_world fixed."""
    _, traj = run("explorer1")
    E0 = traj.energy[0]
    assert np.max(np.abs(traj.energy + traj.dissipated - E0)) / E0 < 6e-8
    assert np.all(np.diff(traj.dissipated) >= -1e-14 * E0)  # never gives energy back (to round-off)
    assert traj.drift["L_world"] < 1e-12


# --- the T-handle with a wheel -------------------------------------------------------------------


def stopped(scenario):
    """The same scenario with every rotor's spin set to 0 (a rigid body)."""
    parts = tuple(dataclasses.replace(p, spin_rate=0.0) if isinstance(p, tumble.Rotor) else p
                  for p in scenario.body.parts)
    return dataclasses.replace(scenario, body=tumble.Body(parts, name=scenario.body.name))


def test_wheel_t_handle_satisfies_the_gyrostat_criterion():
    """The wheel (1 kg, r = 0.1 m, 3 cm thick, at the crossbar's middle) keeps the crossbar the
    intermediate axis; parallel axes about the COM at z = (1.5 x 0.5 + 1 x 0.5) / 4 = 0.3125 m."""
    scenario, traj = run("wheel_t_handle")
    zc, J, Jt = 0.3125, 0.5 * 0.1**2, (3 * 0.1**2 + 0.03**2) / 12  # wheel: axial and transverse moments
    shaft = 1.5 / 12 + 1.5 * zc**2  # about x or y
    bar, wheel = 1.5 * (0.5 - zc) ** 2, (0.5 - zc) ** 2  # offsets of the crossbar and the wheel
    Ix, Iy, Iz = shaft + bar + J + wheel, shaft + 1.5 / 12 + bar + Jt + wheel, 1.5 / 12 + Jt
    np.testing.assert_allclose(traj.moments, [Iz, Ix, Iy], rtol=1e-12)  # 0.1276, 0.3644, 0.4870 kg m^2
    I, W = traj.moments, 10.0
    h = 0.5 * 1.0 * 0.1**2 * 500.0  # J s, J = m r^2 / 2 of the file's wheel
    np.testing.assert_allclose(traj.internal_momentum, [[0.0, h, 0.0]] * len(traj), rtol=1e-15)
    assert h > (I[2] - I[1]) * W  # 2.5 > 1.23 kg m^2/s


def test_wheel_t_handle_does_not_flip_and_wobbles_at_the_linearised_frequency():
    """omega_2 (the crossbar) keeps its sign (stays within 5e-4 of 10 rad/s); omega_1 wobbles at
    sqrt(-((I3 - I2) W - h)((I2 - I1) W + h) / (I1 I3)) (measured 8e-6 off)."""
    _, traj = run("wheel_t_handle")
    I, W, h = traj.moments, 10.0, 2.5
    assert np.all(traj.omega[:, 1] > 0) and np.max(np.abs(traj.omega[:, 1] - W)) < 1e-3
    wobble = np.sqrt(-((I[2] - I[1]) * W - h) * ((I[1] - I[0]) * W + h) / (I[0] * I[2]))
    t = crossings(traj.t, traj.omega[:, 0])
    assert np.pi / np.mean(np.diff(t)) == pytest.approx(wobble, rel=1e-4)


def test_the_same_t_handle_with_the_wheel_stopped_flips():
    """Stopped, the wheel is rigid ballast: omega_2 changes sign 11 times in 20 s, every
    flip_interval (the elliptic closed form, 1.7527 s)."""
    scenario, _ = run("wheel_t_handle")
    traj = run_scenario(stopped(scenario))
    assert traj.internal_momentum is not None and np.all(traj.internal_momentum == 0)
    t = crossings(traj.t, traj.omega[:, 1])
    assert len(t) >= 10
    assert np.mean(np.diff(t)) == pytest.approx(tumble.flip_interval(traj.omega[0], traj.moments), rel=1e-4)


# --- the reaction-wheel slew ---------------------------------------------------------------------


def test_slew_keeps_I_omega_equal_to_minus_h():
    """L = I w + h = 0 at every sample (measured 3e-17 kg m^2/s), w = -J a t / I3 about the wheel's axis."""
    scenario, traj = run("reaction_wheel_slew")
    I, h = traj.moments, traj.internal_momentum
    wheel = 1.0 * (3 * 0.05**2 + 0.03**2) / 12  # the wheel's transverse moment
    box = 60.0 * np.array([0.5**2 + 0.4**2, 0.6**2 + 0.4**2, 0.6**2 + 0.5**2]) / 12
    np.testing.assert_allclose(I, box + [wheel, wheel, 0.5 * 0.05**2], rtol=1e-12)
    assert np.max(np.abs(I * traj.omega + h)) <= 1e-12 * np.max(np.abs(h))
    J, a = 0.5 * 1.0 * 0.05**2, 10.0  # the file's wheel: m r^2 / 2, spin_acceleration
    np.testing.assert_allclose(traj.omega[:, 2], -J * a * traj.t / I[2], rtol=1e-12, atol=0)
    assert np.all(traj.omega[:, :2] == 0)


def test_slew_angle_and_motor_work_are_the_closed_forms():
    """The bus turns through -J a t^2 / (2 I3) (-1.84 rad at 30 s); the motor's work is the
    kinetic energy, J s^2 (1 - J / I3) / 2."""
    _, traj = run("reaction_wheel_slew")
    I3 = traj.moments[2]
    J, a = 0.5 * 1.0 * 0.05**2, 10.0
    angle = traj.attitude.as_rotvec()
    np.testing.assert_allclose(angle[:, 2], -J * a * traj.t**2 / (2 * I3), rtol=0, atol=1e-9)
    assert angle[-1, 2] == pytest.approx(-1.8435, abs=1e-4)
    s = a * traj.t
    np.testing.assert_allclose(traj.motor_work, 0.5 * J * s**2 * (1 - J / I3), rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(traj.energy, traj.motor_work, rtol=1e-10, atol=1e-14)


# --- the gravity-gradient boom -------------------------------------------------------------------


def test_gravity_boom_is_in_the_lagrange_region():
    scenario, _ = run("gravity_boom")
    I = scenario.body.principal_moments  # pitch = 3 (major), yaw = 1 (minor): I_pitch > I_roll > I_yaw
    zc = (1.0 * 3.2 + 2.0 * 6.2) / 53.0  # COM: bus 50 kg at 0, boom 1 kg at 3.2 m, tip 2 kg at 6.2 m
    offsets = 50.0 * zc**2 + 1.0 * (6.0**2 / 12 + (3.2 - zc) ** 2) + 2.0 * (6.2 - zc) ** 2
    roll, pitch = 50.0 * (0.4**2 + 0.4**2) / 12 + offsets, 50.0 * (0.6**2 + 0.4**2) / 12 + offsets
    np.testing.assert_allclose(I, [50.0 * (0.6**2 + 0.4**2) / 12, roll, pitch], rtol=1e-12)
    assert I[2] > I[1] > I[0]
    kr, kp, ky = tumble.analysis.gravity_stability.gravity_gradient_ratios(I)
    assert tumble.gravity_gradient_stability(kr, kp, ky).region == "lagrange"
    np.testing.assert_allclose(np.abs(scenario.body.principal_axes[:, 0]), [0, 0, 1], atol=1e-15)  # the boom


def test_gravity_boom_stays_near_the_local_vertical():
    """The boom (minor axis) stays within 0.054 rad of the radius over 10 orbits (started 0.054
    rad off); the Jacobi integral holds (measured 1.3e-12 of n^2 trace I)."""
    scenario, traj = run("gravity_boom")
    gg = scenario.torque.bind(scenario.body)
    boom_axis = traj.attitude.apply([1.0, 0.0, 0.0])
    off = np.arccos(np.minimum(np.abs(np.sum(boom_axis * gg.radial_direction(traj.t), axis=1)), 1.0))
    assert off[0] == pytest.approx(0.0539, abs=1e-3) and np.max(off) < 0.06
    assert traj.t[-1] == pytest.approx(10 * gg.period)
    jacobi = gg.jacobi_integral(traj.t, traj.omega, traj.attitude)
    assert np.max(np.abs(jacobi - jacobi[0])) < 1e-9 * gg.mean_motion**2 * np.sum(traj.moments)


def test_gravity_boom_pitch_librates_at_the_predicted_frequency():
    """Period from the zero crossings of pitch: 2 pi / (n sqrt(3 k_P)) to 6.5e-4 (the amplitude's
    effect), the pendulum's 4 K(sin^2 theta0) / (n sqrt(3 k_P)) to 3e-5."""
    scenario, traj = run("gravity_boom")
    gg = scenario.torque
    I = traj.moments
    k_pitch = (I[1] - I[0]) / I[2]  # (I_roll - I_yaw) / I_pitch
    omega_p = gg.mean_motion * np.sqrt(3 * k_pitch)
    pitch = tumble.orbit_frame_angles(traj, gg).pitch
    t = crossings(traj.t, pitch)
    assert len(t) >= 30
    period = 2 * np.mean(np.diff(t))
    assert period == pytest.approx(2 * np.pi / omega_p, rel=1e-2)
    assert period == pytest.approx(4 * ellipk(np.sin(0.05) ** 2) / omega_p, rel=1e-4)


# --- figures -------------------------------------------------------------------------------------


def test_spacecraft_figures_says_which_apply():
    expected = {"explorer1": ["energy", "nutation"], "wheel_t_handle": ["energy", "nutation"],
                "reaction_wheel_slew": ["energy"], "gravity_boom": ["orbit_angles"]}  # a slew has L = 0
    for name, figures in expected.items():
        scenario, traj = run(name)
        assert [figure for figure, _ in spacecraft_figures(traj, scenario.torque)] == figures, name
    rigid = tumble.simulate(tumble.t_handle(), [0.1, 5.0, 0.1], t_end=1.0, samples=20)
    assert spacecraft_figures(rigid) == []


def _legend_outside(ax) -> bool:
    """The legend's box does not overlap the axes' box (in display units)."""
    fig = ax.figure
    fig.canvas.draw()
    legend = ax.get_legend().get_window_extent()
    return not legend.overlaps(ax.get_window_extent())


@pytest.mark.parametrize("name", ["explorer1", "reaction_wheel_slew", "gravity_boom"])
def test_every_applicable_figure_is_written_with_units(name, tmp_path):
    scenario, traj = run(name)
    for figure, maker in spacecraft_figures(traj, scenario.torque):
        fig = maker()
        (ax,) = fig.axes
        assert ax.get_xlabel().endswith(("(s)", "s)")) and ax.get_ylabel().endswith(("(J)", "(deg)", "(rad)"))
        assert all(text.get_text().endswith(")") for text in ax.get_legend().get_texts())  # a unit each
        assert _legend_outside(ax)
        path = tmp_path / f"{figure}.png"
        tumble.viz.save_figure(fig, path)
        assert path.stat().st_size > 0


def test_figure_functions_draw_on_given_axes():
    explorer = run("explorer1")
    boom = run("gravity_boom")
    fig = Figure()
    a1, a2, a3 = fig.subplots(3, 1)
    assert spacecraft.figure_energy(explorer[1], ax=a1, log=True) is fig and a1.get_yscale() == "log"
    assert spacecraft.figure_nutation(explorer[1], ax=a2, degrees=False) is fig and a2.get_ylabel() == "nutation angle (rad)"
    assert spacecraft.figure_orbit_angles(boom[1], boom[0].torque, ax=a3) is fig and len(a3.lines) == 4


def test_nutation_of_a_run_without_angular_momentum_is_a_note():
    """A slew from rest has L = 0 throughout: no angle to draw, and the figure says why."""
    slew = run("reaction_wheel_slew")
    (ax,) = spacecraft.figure_nutation(slew[1]).axes
    assert not ax.lines and not ax.axison
    assert [t.get_text() for t in ax.texts] == ["no nutation angle for this run: its angular momentum L is 0 at every sample"]


def test_the_nutation_angle_is_measured_from_the_nearest_major_axis():
    """Asymmetric (the wheel T-handle): the angle between L and the line of axis 3; prolate
    (Explorer 1, I2 = I3): the angle between L and the plane of axes 2 and 3, by arccos and
    arcsin of the unit momentum."""
    _, traj = run("wheel_t_handle")
    l = traj.angular_momentum / traj.angular_momentum_norm[:, None]
    np.testing.assert_allclose(traj.nutation_angle, np.arccos(np.abs(l[:, 2])), atol=1e-7)
    _, traj = run("explorer1")
    assert traj.moments[1] == traj.moments[2]
    l = traj.angular_momentum / traj.angular_momentum_norm[:, None]
    np.testing.assert_allclose(traj.nutation_angle, np.arcsin(np.abs(l[:, 0])), atol=1e-7)


def test_omega_panels(tmp_path):
    scenario, traj = run("wheel_t_handle")
    fig = spacecraft.figure_omega_panels([("with", traj), ("also with", traj)])
    tumble.viz.save_figure(fig, tmp_path / "w.png")
    assert len(fig.axes) == 2 and (tmp_path / "w.png").stat().st_size > 0
    with pytest.raises(ValueError, match="cases is empty"):
        spacecraft.figure_omega_panels([])


def test_the_readme_wheel_figure_has_a_command_that_makes_it(tmp_path):
    """The tour's "spinning and stopped" figure: the command the README and the tour show writes it."""
    root = Path(__file__).resolve().parents[1]
    command = "python docs/figures/make_wheel_figure.py --out figures"
    assert command in (root / "README.md").read_text(encoding="utf-8")
    assert command in (root / "docs" / "tour.md").read_text(encoding="utf-8")
    proc = subprocess.run([sys.executable, str(root / "docs" / "figures" / "make_wheel_figure.py"), "--out",
                           str(tmp_path)], capture_output=True, text=True, check=False, timeout=HANG_S)
    assert proc.returncode == 0, proc.stderr
    png = tmp_path / "wheel_t_handle.png"
    assert proc.stdout.strip() == f"wrote {png}" and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
