"""Figures: the geometry they draw is the physics (polhodes, separatrices, herpolhode), and
they are readable: units on every axis, legends off the data, markers on top, long runs as
envelopes, runs under a torque or at rest drawn without a crash."""

from __future__ import annotations

import json
import math
import subprocess
import sys
import warnings
from io import BytesIO
from pathlib import Path

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import PathCollection, PolyCollection
from matplotlib.figure import Figure

import tumble
from tumble import viz
from tumble.cli import main
from tumble.viz import body_lines, polhode_family, separatrices

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
I = np.array([0.125, 0.3125, 0.4375])


def test_polhodes_lie_on_the_sphere_and_keep_their_energy():
    R = 3.0
    for L in polhode_family(I, R):
        np.testing.assert_allclose(np.linalg.norm(L, axis=1), R, rtol=1e-12)
        E = 0.5 * np.sum(L**2 / I, axis=1)
        np.testing.assert_allclose(E, E[0], rtol=1e-12)
        # each closed curve stays on one side of the separatrix energy |L|^2 / (2 I2)
        assert np.all(E > R**2 / (2 * I[1])) or np.all(E < R**2 / (2 * I[1]))
        np.testing.assert_allclose(L[-1], L[0], atol=1e-9 * R)  # one whole period


def test_separatrices_have_the_intermediate_energy_and_pass_through_its_axis():
    R = 2.0
    for C in separatrices(I, R):
        np.testing.assert_allclose(np.linalg.norm(C, axis=1), R, rtol=1e-12)
        np.testing.assert_allclose(0.5 * np.sum(C**2 / I, axis=1), R**2 / (2 * I[1]), rtol=1e-12)
        assert np.min(np.linalg.norm(C - [0, R, 0], axis=1)) < 1e-9


def test_a_simulated_intermediate_spin_runs_along_the_separatrix():
    """Its L stays (to the size of the perturbation) in one of the two separatrix planes."""
    traj = tumble.simulate(tumble.t_handle(), [1e-4, 5.0, 1e-4], t_end=10.0)
    R = traj.angular_momentum_norm[0]
    C1, C2 = separatrices(I, R)
    normals = [np.cross(C[0], C[90]) / R**2 for C in (C1, C2)]  # planes of the two great circles
    off = np.min([np.abs(traj.angular_momentum @ n) for n in normals], axis=0)
    assert np.max(off) < 1e-3 * R


def test_herpolhode_plane_is_invariable():
    traj = tumble.simulate(tumble.iss_t_handle(), [1.0, 8.0, -2.0], t_end=5.0, samples=400)
    n = traj.angular_momentum_world[0] / traj.angular_momentum_norm[0]
    height = traj.omega_world @ n
    np.testing.assert_allclose(height, 2 * traj.energy[0] / traj.angular_momentum_norm[0], rtol=1e-12)


def test_scene_is_drawn_from_the_parts():
    body = tumble.load_body(EXAMPLES / "bodies" / "every_part.toml")
    lines = body_lines(body)
    assert any(removed for _, removed in lines)  # the hole is drawn, marked as removed
    pts = np.concatenate([p for p, _ in lines])
    assert np.all(np.isfinite(pts))
    rod = body_lines(tumble.Body([tumble.Rod(mass=1.0, length=2.0, axis=(1, 0, 0)), tumble.PointMass(mass=1.0, center=(0, 1, 0))]))
    np.testing.assert_allclose(rod[0][0], [[-1, -0.5, 0], [1, -0.5, 0]], atol=1e-15)  # about the COM


def test_plot_command_writes_every_figure(tmp_path, capsys):
    assert main(["plot", str(EXAMPLES / "seed_flip.toml"), "--out", str(tmp_path), "--format", "png", "svg"]) == 0
    for name in ("omega", "polhode", "herpolhode", "drift"):
        for fmt in ("png", "svg"):
            assert (tmp_path / f"{name}.{fmt}").stat().st_size > 5_000
    assert not list(tmp_path.glob(".*"))


@pytest.mark.parametrize("command", ["inertia", "simulate", "plot", "view", "demo"])
def test_every_subcommand_has_help_with_an_example(command, capsys):
    with pytest.raises(SystemExit) as info:
        main([command, "--help"])
    assert info.value.code == 0
    assert "Example" in capsys.readouterr().out


# -- the figure functions: signature, units, legends, markers ------------------------------------

@pytest.fixture(scope="module")
def flip():
    return tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=10.0, samples=800)


def _one_run_figures():
    """Every figure of one run: name -> function(traj, ax=...)."""
    return {"omega": viz.figure_omega, "drift": viz.figure_drift, "polhode": viz.figure_polhode,
            "herpolhode": viz.figure_herpolhode}


def test_every_figure_function_returns_its_figure_and_writes_nothing(flip, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for name, figure in _one_run_figures().items():
        fig = figure(flip)
        assert isinstance(fig, Figure) and fig.axes, name
        given = Figure()
        assert figure(flip, ax=given.subplots()) is given, name  # drawn where asked (polhode: in 3D there)
    assert isinstance(viz.figure_omega_grid([("a", flip), ("b", flip)]), Figure)
    given = Figure()
    assert viz.figure_omega_grid([("a", flip)], fig=given) is given and len(given.axes) == 1
    assert list(tmp_path.iterdir()) == []  # saving is a separate step
    viz.save_figure(viz.figure_omega(flip), tmp_path / "omega.svg")
    assert (tmp_path / "omega.svg").read_text().lstrip().startswith("<?xml")
    assert [p.name for p in tmp_path.iterdir()] == ["omega.svg"]  # no temporary left


def test_the_polhode_replaces_a_flat_axes_by_a_3d_one_in_its_place(flip):
    fig = Figure()
    left, right = fig.subplots(1, 2)
    viz.figure_polhode(flip, ax=right)
    assert len(fig.axes) == 2 and fig.axes[0] is left and fig.axes[1].name == "3d"
    assert fig.axes[1].get_subplotspec().colspan == right.get_subplotspec().colspan


def test_omega_axes_and_legend_carry_units_and_the_moments(flip):
    (ax,) = viz.figure_omega(flip).axes
    assert ax.get_xlabel() == "t (s)" and ax.get_ylabel().endswith("(rad/s)")
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    for j, label in enumerate(labels):  # the moments of the seed's T-handle, with their unit
        assert f"$I_{j + 1}$ = {[0.125, 0.3125, 0.4375][j]:.4g} kg m$^2$" in label
    (ax,) = viz.figure_drift(flip).axes
    assert ax.get_xlabel() == "t (s)" and ax.get_ylabel() == "relative drift (dimensionless)"
    (ax,) = viz.figure_herpolhode(flip).axes
    assert ax.get_xlabel().endswith("(rad/s)") and ax.get_ylabel().endswith("(rad/s)")
    ax = viz.figure_polhode(flip).axes[0]
    assert all(label.endswith("(kg m$^2$/s)") for label in (ax.get_xlabel(), ax.get_ylabel(), ax.get_zlabel()))


def test_a_run_of_many_oscillations_gets_a_detail_panel(flip):
    """About 560 flips in 1000 s are a block of colour at any resolution: a second panel shows the
    first few. The detail ends at the sign change with index 2 DETAIL_SHOWN (the 11th) of the
    busiest component; its span is held against the closed-form period (flip_interval), an
    independent route."""
    handle = tumble.t_handle()
    long_run = tumble.simulate(handle, [0.1, 10.0, 0.1], t_end=1000.0, samples=20001)
    fig = viz.figure_omega(long_run)
    whole, detail = fig.axes
    end = detail.get_xlim()[1]
    period = 2 * float(tumble.flip_interval([0.1, 10.0, 0.1], handle.principal_moments))
    assert viz.plots.DETAIL_SHOWN * period / 2 <= end <= (viz.plots.DETAIL_SHOWN + 1) * period  # a few periods
    assert whole.get_xlim() == (0.0, 1000.0) and whole.get_legend() is not None
    assert len(viz.figure_omega(flip).axes) == 1  # 20 s, a handful of flips: one panel
    given = Figure()
    assert len(viz.figure_omega(long_run, ax=given.subplots()).axes) == 1  # drawn where asked, no panel added
    assert viz.plots.detail_window(tumble.simulate(handle, [0.0, 0.0, 10.0], t_end=1000.0)) is None  # steady: no sign change


def _legend_clear_of_axes(ax) -> bool:
    """The legend's box and the axes' box (display units, after layout) do not overlap."""
    ax.figure.draw_without_rendering()  # the layout done
    return not ax.get_legend().get_window_extent().overlaps(ax.get_window_extent())


@pytest.mark.parametrize("name", ["omega", "drift", "herpolhode"])
def test_legends_never_cover_the_data(flip, name):
    (ax,) = _one_run_figures()[name](flip).axes
    assert _legend_clear_of_axes(ax)


def test_the_grid_keeps_every_legend_off_its_panel(flip):
    fig = viz.figure_omega_grid([("a", flip), ("b", flip), ("c", flip), ("d", flip)], ncols=3)
    visible = [ax for ax in fig.axes if ax.get_visible()]
    assert len(visible) == 4 and all(_legend_clear_of_axes(ax) for ax in visible)


def test_markers_are_drawn_above_the_curves(flip):
    (ax,) = viz.figure_herpolhode(flip).axes
    markers = [c for c in ax.collections if isinstance(c, PathCollection)]
    assert len(markers) == 2  # t = 0 and the foot of L
    assert min(m.get_zorder() for m in markers) > max(line.get_zorder() for line in ax.lines)
    ax = viz.figure_polhode(flip).axes[0]
    assert not ax.computed_zorder  # mplot3d would otherwise re-sort by depth and hide the marker
    (start,) = [c for c in ax.collections if isinstance(c, PathCollection)]
    assert start.get_zorder() > max(line.get_zorder() for line in ax.lines)


# -- long runs: envelopes -------------------------------------------------------------------------

def test_the_envelope_holds_every_sample_between_its_bounds():
    rng = np.random.default_rng(1)
    t = np.sort(rng.uniform(0.0, 50.0, 10_007))
    y = rng.normal(size=(10_007, 3))
    times, low, high = viz.envelope(t, y, bins=97)
    assert times.shape == (194,) and low.shape == high.shape == (194, 3)
    for k in range(97):  # bin k is held from times[2k] to times[2k+1]
        inside = (t >= times[2 * k]) & (t <= times[2 * k + 1])
        np.testing.assert_array_equal(low[2 * k], y[inside].min(axis=0))
        np.testing.assert_array_equal(high[2 * k], y[inside].max(axis=0))
    assert np.all(np.diff(times) >= 0) and times[0] == t[0] and times[-1] == t[-1]
    covered = np.zeros(len(t), bool)
    for k in range(97):
        covered |= (t >= times[2 * k]) & (t <= times[2 * k + 1])
    assert covered.all()


def test_a_long_run_is_drawn_as_an_envelope_with_a_note():
    long = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=1000.0, samples=100_000)
    ax, _ = viz.figure_omega(long, title="1000 s").axes  # the whole run; the detail panel is tested below
    assert max(len(line.get_xdata()) for line in ax.lines) <= viz.plots.MAX_POINTS
    bands = [c for c in ax.collections if isinstance(c, PolyCollection)]
    assert len(bands) == 3
    for j, band in enumerate(bands):  # each band spans the component's whole range
        (verts,) = [p.vertices for p in band.get_paths()]
        assert verts[:, 1].min() == pytest.approx(long.omega[:, j].min())
        assert verts[:, 1].max() == pytest.approx(long.omega[:, j].max())
    assert ax.get_title().splitlines()[0] == "1000 s" and "100000 samples" in ax.get_title()
    (ax,) = viz.figure_drift(long).axes
    assert max(len(line.get_xdata()) for line in ax.lines) <= viz.plots.MAX_POINTS
    # the phase portraits draw the first stretch (the herpolhode would fill its annulus solid)
    first = long.t[viz.plots.MAX_POINTS - 1]
    for name in ("polhode", "herpolhode"):
        ax = _one_run_figures()[name](long).axes[0]
        this_run = max(ax.lines, key=lambda line: len(line.get_xdata()))
        assert len(this_run.get_xdata()) == viz.plots.MAX_POINTS
        assert ax.get_title().endswith(f"the first {first:.4g} s of 1000 s ({viz.plots.MAX_POINTS} of 100000 samples)")
    short = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=10.0, samples=viz.plots.MAX_POINTS)
    (ax,) = viz.figure_omega(short).axes
    assert not ax.collections and ax.get_title() == ""  # every sample drawn, nothing to say


# -- runs under a torque and from rest ------------------------------------------------------------

def test_phase_portraits_of_a_torqued_run_say_why_they_are_empty():
    traj = tumble.simulate(tumble.t_handle(), [0.1, 5.0, 0.1], t_end=2.0, torque=tumble.ConstantTorque((0.0, 0.0, 0.1)))
    for name in ("polhode", "herpolhode"):
        ax = _one_run_figures()[name](traj).axes[0]
        assert not ax.lines and not ax.axison
        (note,) = [t.get_text() for t in ax.texts]
        assert note == f"no {name} for this run: a torque acts, so L and the energy change: they picture torque-free motion only"
    assert "a torque acts" in viz.figure_drift(traj).axes[0].get_title()


@pytest.mark.parametrize("torque", [None, (0.0, 0.0, 0.1)])
def test_a_run_from_rest_draws_every_figure_without_a_warning(torque):
    body = tumble.t_handle()
    traj = tumble.simulate(body, [0.0, 0.0, 0.0], t_end=1.0, samples=50,
                           torque=None if torque is None else tumble.ConstantTorque(torque))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # every warning, not only RuntimeWarning
        figures = [f(traj) for f in _one_run_figures().values()]
        figures += [viz.figure_omega_grid([("rest", traj)]), viz.figure_omega_panels([("rest", traj)]),
                    viz.figure_energy(traj), viz.figure_nutation(traj)]
        for fig in figures:
            fig.savefig(BytesIO(), format="png")
    drift = figures[1].axes[0]
    if torque is not None:  # measured against the largest value: it starts at 0
        assert all("max" in t.get_text() for t in drift.get_legend().get_texts())
        assert np.all(np.isfinite(np.concatenate([line.get_ydata() for line in drift.lines])))


# -- animations: readable axes, MP4 with ffmpeg, GIF without ---------------------------------------

def test_animation_tick_labels_do_not_overlap():
    body = tumble.t_handle()
    fig, ax = viz.animate.scene_axes(1.25 * tumble.viz.body_size(body), "T-handle")
    canvas = FigureCanvasAgg(fig)
    fig.set_dpi(90)  # the GIF's
    canvas.draw()
    renderer = canvas.get_renderer()
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        lo, hi = sorted(axis.get_view_interval())
        labels = [t for loc, t in zip(axis.get_majorticklocs(), axis.get_ticklabels()) if lo <= loc <= hi]
        assert 2 <= len(labels) <= 3 and all(t.get_fontsize() >= 8 for t in labels)
        boxes = [t.get_window_extent(renderer) for t in labels]
        assert not any(a.overlaps(b) for i, a in enumerate(boxes) for b in boxes[i + 1:])
    assert all(label.endswith("(m)") for label in (ax.get_xlabel(), ax.get_ylabel(), ax.get_zlabel()))


@pytest.fixture(scope="module")
def short_flip():
    return tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=0.15, samples=20)   # ~0.4 rad of spin a frame of 5


@pytest.mark.skipif(viz.ffmpeg_path() is None, reason="no ffmpeg (tumble[video])")
def test_an_mp4_is_written_where_ffmpeg_is_found(short_flip, tmp_path):
    path = viz.animate_ground_frame(tumble.t_handle(), short_flip, tmp_path / "g.mp4", max_frames=5)
    assert path == tmp_path / "g.mp4" and path.read_bytes()[4:8] == b"ftyp"  # an MP4 (ISO media) file
    assert [p.name for p in tmp_path.iterdir()] == ["g.mp4"]


def test_without_ffmpeg_the_gif_is_written_and_said(short_flip, tmp_path, monkeypatch):
    monkeypatch.setattr(viz.animate, "ffmpeg_path", lambda: None)
    path, note = viz.animation_path(tmp_path / "b.mp4")
    assert path == tmp_path / "b.gif" and note.startswith("no ffmpeg found") and "\n" not in note
    with pytest.warns(UserWarning, match=r"b.mp4: no ffmpeg found .*GIF written instead"):
        written = viz.animate_body_frame(tumble.t_handle(), short_flip, tmp_path / "b.mp4", max_frames=5)
    assert written == tmp_path / "b.gif" and written.read_bytes()[:6] == b"GIF89a"
    assert [p.name for p in tmp_path.iterdir()] == ["b.gif"]
    from tumble.demo import animation_suffix

    assert animation_suffix("auto") == (".gif", note) and animation_suffix("gif") == (".gif", None)
    with pytest.raises(ValueError, match=r"animation_format = 'mp4' needs ffmpeg and none was found"):
        animation_suffix("mp4")
    with pytest.raises(ValueError, match="mp4 or .gif"):
        viz.animation_path(tmp_path / "b.avi")


def test_figures_refuse_what_is_not_a_run_and_save_by_a_known_suffix(flip, tmp_path):
    for figure in (*_one_run_figures().values(), viz.figure_energy, viz.figure_nutation):
        with pytest.raises(ValueError, match="trajectory = str object must be a tumble Trajectory"):
            figure("x")
    for grid in (viz.figure_omega_grid, viz.figure_omega_panels):
        with pytest.raises(ValueError, match=r"cases\[0\] = Trajectory object must be a \(title, trajectory\) pair"):
            grid([flip])
        with pytest.raises(ValueError, match=r"cases\[1\]\[1\] = str object must be a tumble Trajectory"):
            grid([("a", flip), ("b", "x")])
    fig = viz.figure_omega(flip)
    with pytest.raises(ValueError, match=r"omega: a figure is written as .*\.png.*\.svg.* not 'no suffix'"):
        viz.save_figure(fig, tmp_path / "omega")
    with pytest.raises(ValueError, match=r"not '\.docx'"):
        viz.save_figure(fig, tmp_path / "omega.docx")
    with pytest.raises(ValueError, match="fig = str object must be a matplotlib Figure"):
        viz.save_figure("x", tmp_path / "omega.png")
    with pytest.raises(ValueError, match="dpi = 0 must be a number"):
        viz.save_figure(fig, tmp_path / "omega.png", dpi=0)
    assert list(tmp_path.iterdir()) == []
    viz.save_figure(fig, tmp_path / "omega.PDF")  # the suffix in any case
    assert (tmp_path / "omega.PDF").read_bytes()[:5] == b"%PDF-"


def test_animations_refuse_bad_input_in_one_line(short_flip, tmp_path):
    body = tumble.t_handle()
    cases = [(dict(fps=0), "fps = 0 must be a whole number"), (dict(dpi=2.5), "dpi = 2.5 must be a whole number"),
             (dict(max_frames=1), "max_frames = 1 must be a whole number")]
    for options, message in cases:
        with pytest.raises(ValueError, match=message):
            viz.animate_ground_frame(body, short_flip, tmp_path / "g.gif", **options)
    box = tumble.Body([tumble.Box(mass=1.0, size=(1.0, 2.0, 3.0))])
    with pytest.raises(ValueError, match="is not the body of this trajectory"):
        viz.animate_body_frame(box, short_flip, tmp_path / "b.gif")
    with pytest.raises(ValueError, match="trajectory = str object must be a tumble Trajectory"):
        viz.animate_body_frame(body, "x", tmp_path / "b.gif")
    assert list(tmp_path.iterdir()) == []


# -- notebooks --------------------------------------------------------------------------------------

def test_a_figure_displays_in_a_notebook_without_pyplot(flip):
    """Jupyter shows a bare Figure as text unless pyplot was imported; ours carries its PNG."""
    fig = viz.figure_omega(flip)
    assert fig._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"
    code = "import sys, tumble.viz; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"  # importing tumble.viz does not import matplotlib


# -- what a new user read off the figures and the summary line (issue 20) -----------------------

def _legend_texts(fig) -> list[str]:
    return [t.get_text() for ax in fig.axes if ax.get_legend() for t in ax.get_legend().get_texts()]


def test_a_drift_at_round_off_is_said_not_drawn_as_noise(flip):
    """The exact method's drift (~1e-16) is one dashed line per invariant at its largest value and
    the words "at round-off"; DOP853's (~1e-11) is drawn as it is."""
    fig = viz.figure_drift(flip)
    assert flip.method == "exact" and max(flip.drift.values()) < viz.plots.ROUND_OFF
    labels = _legend_texts(fig)
    assert len(labels) == 3 and all("at round-off (max " in label for label in labels)
    assert any("at round-off" in t.get_text() for t in fig.axes[0].texts)
    ax = fig.axes[0]
    assert all(len(set(line.get_ydata())) == 1 for line in ax.get_lines())  # flat lines, no noise band
    assert ax.get_yscale() == "log"
    coarse = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=10.0, samples=800, method="dop853")
    assert max(coarse.drift.values()) > viz.plots.ROUND_OFF
    fig = viz.figure_drift(coarse)
    assert not any("round-off" in label for label in _legend_texts(fig))
    assert not fig.axes[0].texts


def test_the_energy_axis_shows_the_energy_not_an_offset():
    """A wheel's energy varies in its 6th digit: the axis reads 668.22 J, not "+6.6822e2" and 0.0005."""
    wheel = tumble.Rotor(mass=1.0, radius=0.1, length=0.03, axis=(1, 0, 0), center=(0, 0, 0.5), spin_rate=500.0)
    traj = tumble.simulate(tumble.Body([*tumble.t_handle().parts, wheel]), [0.1, 10, 0.1], t_end=5.0)
    fig = viz.figure_energy(traj)
    FigureCanvasAgg(fig).draw()
    ax = fig.axes[0]
    assert ax.yaxis.get_offset_text().get_text() == ""
    ticks = [float(t.get_text().replace("\u2212", "-")) for t in ax.get_yticklabels() if t.get_text()]
    assert ticks and all(600 < t < 700 for t in ticks)


def test_titles_name_the_body_once(tmp_path, capsys):
    """A scenario named after its body (a body file run with --omega) is titled "phone, exact",
    not "phone: phone, exact"."""
    body = tmp_path / "phone.toml"
    body.write_text('[body]\nname = "phone"\n[[body.parts]]\nkind = "box"\nmass = 0.2\nsize = [0.15, 0.075, 0.008]\n')
    page = tmp_path / "p.html"
    assert main(["view", str(body), "--omega", "0.1", "10", "0.1", "--t-end", "1", "--samples", "20",
                 "--out", str(page)]) == 0
    text = page.read_text(encoding="utf-8")
    assert "phone, exact" in text and "phone: phone" not in text
    capsys.readouterr()


def test_the_simulate_line_gives_the_flip_period_and_no_dashes(tmp_path, capsys):
    """Torque-free with flips: their period as the run measured it, the closed form beside it where they differ; a slew from rest, whose energy and L
    start at 0: says so and gives the motors' work instead of "energy -, L_norm -, L_world -"."""
    examples = Path(tumble.__file__).parent / "examples"
    assert main(["simulate", str(examples / "seed_flip.toml"), "--out", str(tmp_path / "a")]) == 0
    line = capsys.readouterr().out
    exact = tumble.flip_interval([0.1, 10.0, 0.1], tumble.t_handle().principal_moments)  # seed_flip, principal frame
    assert f"11 flips every {exact:.4g} s" in line and "closed form" not in line  # dop853: measured as the closed form
    # rk45 at its defaults flips 0.9 % early: the line gives what the run did, and the closed form beside it
    assert main(["simulate", str(examples / "seed_rk45.toml"), "--out", str(tmp_path / "c"), "--json"]) == 0
    stability = json.loads(capsys.readouterr().out)["stability"]
    assert stability["flip_period"] < 0.995 * exact
    assert main(["simulate", str(examples / "seed_rk45.toml"), "--out", str(tmp_path / "d")]) == 0
    line = capsys.readouterr().out
    assert f"11 flips every {stability['flip_period']:.4g} s (the closed form: {exact:.4g} s)" in line
    assert main(["simulate", str(examples / "reaction_wheel_slew.toml"), "--out", str(tmp_path / "b")]) == 0
    line = capsys.readouterr().out
    assert " -," not in line and "no relative drift" in line and "the motors did 56.2 J of work" in line


def test_a_figure_drawn_on_the_users_own_axes_keeps_its_legend_on_the_canvas():
    """``figure_omega(traj, ax=ax)`` on a plain figure of the user's (no layout engine) put the legend
    outside the axes, where nothing made room for it, and the saved PNG cut it ("ω1 (m..."): on such
    axes it goes inside; on tumble's own figures (constrained layout) it stays outside."""
    traj = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=5.0, samples=200)
    fig = Figure(figsize=(6.0, 4.0))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    tumble.viz.figure_omega(traj, ax=ax)
    fig.savefig(BytesIO(), format="png")
    box, canvas = ax.get_legend().get_window_extent(), fig.bbox
    assert canvas.x0 <= box.x0 and box.x1 <= canvas.x1 and canvas.y0 <= box.y0 and box.y1 <= canvas.y1
    own = tumble.viz.figure_omega(traj)
    own.savefig(BytesIO(), format="png")
    assert own.axes[0].get_legend().get_window_extent().x0 > own.axes[0].bbox.x1  # right of the axes


# --- samples too far apart to show the motion (tumble.viz.sample_phase) ---------------------------------------------

@pytest.mark.parametrize("moments, spin, axis", [((2.0, 2.0, 3.0), 10.0, 2), ((3.0, 4.0, 4.0), 25.0, 0),
                                                  ((1.2, 1.2, 2.0), 4.0, 2)])
def test_sample_phase_is_a_symmetric_tops_nutation_per_sample(moments, spin, axis):
    """A free symmetric top: omega turns about the symmetry axis in the body at Omega = (I_a - I_t) / I_t
    omega_a (Landau & Lifshitz, Mechanics, sec. 36), so the phase between samples dt apart is Omega dt,
    for an oblate and a prolate top, finely and sparsely sampled."""
    I = np.array(moments)
    transverse = I[(axis + 1) % 3]
    rate = abs(I[axis] - transverse) / transverse * spin  # rad/s
    omega0 = np.full(3, 0.02 * spin)
    omega0[axis] = spin
    body = tumble.MassProperties.from_moments(moments)
    for per_sample in (0.05, 0.2, 2.0):
        dt = per_sample / rate
        run = tumble.simulate(body, omega0, t_end=400 * dt, dt=dt)
        # fine: max |sin| over the samples and the sampled range miss by (Omega dt)^2 / 8 at most;
        # sparse (2 rad a sample), the samples still find the peaks within a few per cent
        assert abs(viz.sample_phase(run) / per_sample - 1.0) < (0.01 if per_sample <= 0.2 else 0.05), per_sample


def test_figure_omega_warns_where_the_samples_alias():
    """2 rad of nutation a sample draws a faithful (coarse) wobble, without a word; 4 rad draws a slower
    one than the body's, and figure_omega says so (AliasedSamplesWarning)."""
    top = tumble.MassProperties.from_moments([2.0, 2.0, 3.0])  # Omega = 0.5 omega_3 = 5 rad/s
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        viz.figure_omega(tumble.simulate(top, [0.1, 0.0, 10.0], t_end=40.0, dt=0.4))
    with pytest.warns(viz.AliasedSamplesWarning, match=r"up to 4\.\d+ rad between samples, past pi.*; give more samples$"):
        viz.figure_omega(tumble.simulate(top, [0.1, 0.0, 10.0], t_end=40.0, dt=0.8))


def test_a_control_runs_aliased_omega_figure_names_the_controller_period():
    """A control run's samples are its control instants: "give more samples" could not be followed (a walkthrough of
    docs/control.md, 2026-12-03, whose omega in deg/s was read as rad/s). Its warning names the period."""
    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.control.controlled import simulate_controlled
    from tumble.dynamics.environment.magnetic import UniformField
    from tumble.dynamics.models.actuators import Magnetorquers

    run = simulate_controlled([0.03, 0.04, 0.05], [11.55, -11.55, 11.55], t_end=20.0, controller=BDot(gain=1e-5, period=1.0,
                              form="normalized"), magnetorquers=Magnetorquers(0.2), field=UniformField((2e-5, 0.0, 1e-5)))
    traj = tumble.Trajectory.of_samples(run.t, run.omega, run.attitude.as_quat(), run.moments, np.eye(3),
                                        "dop853, bdot every 1 s")
    with pytest.warns(viz.AliasedSamplesWarning, match=r"past pi: .*; give a shorter controller period than 1 s \(its "
                                                       r"samples are the control instants\); or is omega in deg/s\?$"):
        viz.figure_omega(traj, control_period=1.0)


def test_simulate_says_in_one_line_where_its_omega_png_aliases(tmp_path, capsys):
    """573 rad/s over 20 s on the default 500 samples: the omega.png would show another motion; the
    command writes it and says so in one line (exit 0); the seed's flip says nothing."""
    out = tmp_path / "fast"
    assert main(["simulate", "t-handle", "--omega", "5.7", "573", "5.7", "--t-end", "20", "--out", str(out)]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("warning: omega oscillates by up to "), err
    assert float(err[0].split("up to ")[1].split(" rad")[0]) > np.pi and (out / "omega.png").is_file()
    assert main(["simulate", "t-handle", "--omega", "10", "0.1", "0.1", "--t-end", "20", "--out", str(tmp_path / "flip")]) == 0
    assert "warning" not in capsys.readouterr().err


def test_sample_phase_refuses_what_is_not_a_run_in_one_line():
    with pytest.raises(ValueError, match=r"^trajectory = list object must be a tumble Trajectory"):
        viz.sample_phase([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0]])


def test_the_maps_edges_name_a_disc_oblate_and_a_rod_prolate():
    """The legend called I1 = I2 prolate and I2 = I3 oblate (a teacher's walkthrough, 2026-12-03). A disc
    (flat cylinder) has I1 = I2 < I3, an oblate top; a rod (long cylinder) I1 < I2 = I3, a prolate one: each
    edge's label is checked on the ratios of the body drawn on it (moments from the cylinder's formulas)."""
    from tumble.ensemble.reductions import stability_map
    from tumble.viz import figure_stability_map

    def edge_of(r: float, h: float) -> str:   # m r^2 / 2 about the axis, m (3 r^2 + h^2) / 12 across it
        moments = np.sort([0.5 * r**2, (3 * r**2 + h**2) / 12, (3 * r**2 + h**2) / 12])
        x, y = moments[0] / moments[2], moments[1] / moments[2]
        fig = figure_stability_map(10.0, (0.001, 0.001), resolution=20)
        lines = [line for line in fig.axes[0].get_lines() if line.get_label().startswith("$I")]
        def off(line) -> float:   # the point's distance from the line through the edge's two ends (2D cross product)
            (x0, y0), (x1, y1) = line.get_xydata()[:2]
            return abs((x1 - x0) * (y - y0) - (y1 - y0) * (x - x0))

        on = [line.get_label() for line in lines if off(line) < 1e-9]
        return on[0]

    assert "oblate" in edge_of(0.2, 0.01) and "prolate" in edge_of(0.01, 0.5)
    assert stability_map(10.0, resolution=20).x.size == 20


def test_a_damped_wobble_drawn_from_too_few_samples_is_warned_of():
    """The tour's damped T-handle at the default 500 samples over 400 s (0.8 s apart) drew a wobble of ~4.6 s
    where the body's is 0.96 s (a teacher's walkthrough, 2026-12-03): the phase estimate took each component's
    range over the whole run, which the damper's turning of the spin widens (2.85 rad a sample). The wobble
    about the minor axis, counted here on a dense run, is Omega = w1 sqrt((I2 - I1)(I3 - I1) / (I2 I3))
    (Landau & Lifshitz sec. 37): 6.55 rad/s, 5.2 rad a sample."""
    from tumble.viz.plots import AliasedSamplesWarning, sample_phase

    body, w0 = tumble.t_handle(), [10.0, 0.3, 0.2]
    damper = tumble.SphericalDamper(inertia=0.01, damping=0.01)
    sparse = tumble.simulate(body, w0, t_end=400.0, damper=damper)
    dense = tumble.simulate(body, w0, t_end=20.0, samples=20001, damper=damper)
    crossings = np.sum(np.diff(np.sign(dense.omega[:, 1])) != 0)   # two a wobble
    I1, I2, I3 = body.principal_moments
    assert math.isclose(np.pi * crossings / 20.0, 10.0 * math.sqrt((I2 - I1) * (I3 - I1) / (I2 * I3)), rel_tol=0.05)
    assert sample_phase(sparse) > np.pi > sample_phase(dense)
    with pytest.warns(AliasedSamplesWarning):
        tumble.viz.figure_omega(sparse)
