"""Figures that fit (issue 40, item 5): no label, title, tick label or legend of any figure tumble
draws lies outside its canvas, where a saved file would cut it ("...planar bodies (triangle
inequalit").

Every figure function of :mod:`tumble.viz` (the demo's grid of runs and the animations' frames
among them) is drawn from a small input, rendered by Agg at the size it is saved, and every text drawn (tick
labels out of view are not drawn, so not counted) must lie inside the canvas to a pixel.
"""

from __future__ import annotations

import matplotlib.text
import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

import tumble
import tumble.viz as viz

#: A text may touch the canvas's edge: anti-aliasing and rounding, pixels.
TOLERANCE = 1.0


def texts_outside(fig) -> list[str]:
    """The texts drawn (when ``fig`` is rendered as a saved file is) that reach outside the canvas."""
    drawn = []
    original = matplotlib.text.Text.draw

    def draw(self, renderer):
        result = original(self, renderer)
        if self.get_visible() and self.get_text().strip():  # measured here: a 3-d text is placed only while drawn
            drawn.append((self.get_text(), self.get_window_extent(renderer)))
        return result

    matplotlib.text.Text.draw = draw
    try:
        canvas = FigureCanvasAgg(fig)
        canvas.draw()
    finally:
        matplotlib.text.Text.draw = original
    width, height = fig.bbox.width, fig.bbox.height
    out = []
    for text, box in drawn:
        if box.x0 < -TOLERANCE or box.y0 < -TOLERANCE or box.x1 > width + TOLERANCE or box.y1 > height + TOLERANCE:
            out.append(f"{text!r} at {np.round(box.extents).tolist()} on a {width:.0f} x {height:.0f} canvas")
    return out


def test_the_check_sees_a_clipped_label():
    fig = viz.figure_omega(tumble.simulate(tumble.t_handle(), [0.1, 5.0, 0.1], t_end=2.0, samples=50))
    assert texts_outside(fig) == []
    fig.axes[0].set_ylabel("a label far too long to fit beside the axes " * 6)
    fig.set_layout_engine("none")
    assert any("far too long" in t for t in texts_outside(fig))


# Small inputs --------------------------------------------------------------------------------

def _run(t_end=20.0, samples=400, **kw):
    return tumble.simulate(tumble.t_handle(), [0.1, 5.0, 0.1], t_end=t_end, samples=samples, **kw)


def _control_figures():
    from scipy.spatial.transform import Rotation

    from tumble.dynamics.control.controlled import simulate_controlled
    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.control.controllers import MRPFeedback
    from tumble.dynamics.environment.magnetic import UniformField
    from tumble.dynamics.models.actuators import Magnetorquers, ReactionWheels

    rw = ReactionWheels(np.eye(3), inertia=1e-4, max_torque=1e-3)
    c = MRPFeedback(K=1e-3, P=1e-2, period=0.5, moments=[0.03, 0.04, 0.05], wheels=rw)
    pointing = simulate_controlled([0.03, 0.04, 0.05], [0.01, 0.0, 0.0], t_end=10.0, controller=c, wheels=rw,
                                   attitude0=Rotation.from_rotvec([0.2, 0.0, 0.0]))
    detumbling = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.1], t_end=10.0, controller=BDot(gain=1e-3, period=1.0,
                                     form="normalized"), field=UniformField((3e-5, 0.0, 0.0)), magnetorquers=Magnetorquers(0.2))
    figures = {**viz.control_figures(pointing, target=Rotation.identity(), switch_time=4.0, title="point"),
               **{f"bdot {name}": fig for name, fig in viz.control_figures(detumbling, title="detumble").items()}}
    assert {name.split()[-1] for name in figures} == {"attitude_error.png", "rates.png", "wheels.png", "dipole.png",
                                                      "momentum.png"}
    return list(figures.values())


def _damped():
    body = tumble.MassProperties.from_moments([1.0, 2.0, 2.5])
    return tumble.simulate(body, [1.0, 0.05, 0.0], t_end=300.0, samples=50,
                           damper=tumble.SphericalDamper(inertia=0.3, damping=0.3))


def _gravity():
    body, gg = tumble.t_handle(), tumble.GravityGradient(orbit_period=5400.0)
    s = tumble.lvlh_state(gg, body, pitch=0.01)
    run = tumble.simulate(body, s.omega0, attitude0=s.attitude0, torque=gg, t_end=600.0, samples=30)
    return [viz.figure_orbit_angles(run, gg), *(make() for _, make in viz.spacecraft_figures(run, gg))]


def _sweep():
    from tumble.ensemble import BodySampler, Dispersion, Ensemble, InitialRates, RunSettings, Sweep, compute_chunk

    box = tumble.Body((tumble.Box(mass=12.0, size=(1.0, 2.0, 3.0)),))
    spread = Ensemble(BodySampler(box, (Dispersion("moments", 0.02),)), InitialRates(omega=(0.01, 1.0, 0.01)), 6)
    columns = compute_chunk(Sweep(spread, RunSettings(t_end=80.0, samples=800)), 0, 6)
    return viz.figure_sweep(columns, title="box, moments spread 2 %", cases=100)


def _detumble_mc():
    from tumble.ensemble.detumble import DetumbleMonteCarlo, detumble_cases

    cases = detumble_cases(5, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3)
    rates = np.array([[0.2, 0.05, 0.001], [0.3, 0.1, 0.002], [0.1, 0.02, 0.001], [0.25, 0.2, 0.1], [0.15, 0.01, 0.003]])
    mc = DetumbleMonteCarlo(times=np.array([60.0, 120.0, 60.0, np.nan, 120.0]), cases=cases, threshold=0.01,
                            t_end=120.0, seconds=1.0, history_t=np.array([0.0, 60.0, 120.0]), history=rates)
    return viz.figure_detumble_mc(mc, title="B-dot, 5 cases")


def _fits():
    from tumble.analysis.fit import fit_recording, fit_rotation
    from tumble.analysis.fit.synthetic import synthetic_recording
    from tumble.dynamics.methods.exact import FreeRotation
    from scipy.spatial.transform import Rotation

    rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
    t = np.linspace(0.0, 2.0, 201)
    w = FreeRotation([0.3, 0.7, 1.0], [0.2, 5.0, 0.3], Rotation.identity()).omega(t)
    return [viz.figure_recording(fit_recording(rec.t, rec.omega, events=rec.events)),
            viz.figure_fit(fit_rotation(t, w, sensor_rotation="identity", bias=False, drag="none"), w)]


def _tensor():
    from tumble.analysis.tensor import TensorFit, ThrowFit
    from tumble.analysis.tensor.estimate import mass_estimate

    def estimate(moments, std):
        return mass_estimate(0.5, np.diag(moments), np.diag(np.square(std * 2)), [0.0, 0.0, 0.02], np.eye(3) * 1e-8)

    t = np.linspace(0.0, 0.5, 200)
    w = np.stack([np.cos(9 * t), 8 + 0 * t, np.sin(9 * t)], axis=1)
    throws = tuple(ThrowFit(f"throw_{k}_of_a_long_name.csv", "used", "", estimate(m, [2e-6] * 3), None, t, w + 0.01, w,
                            0.0, 0.5, 0.01) for k, m in enumerate([[1.0e-3, 2.0e-3, 2.9e-3], [1.02e-3, 1.98e-3, 2.91e-3]]))
    skipped = ThrowFit("skipped.csv", "skipped", "no free flight found", None, None, np.zeros(0), np.zeros((0, 3)),
                       np.zeros((0, 3)))
    pooled = estimate([1.01e-3, 1.99e-3, 2.905e-3], [1.5e-6] * 3)
    return viz.figure_tensor(TensorFit(pooled, pooled, (*throws, skipped), True, 0.8))


def _grid():
    body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])
    cases = [(f"omega_2 = {w:g} rad/s, a long panel title", tumble.simulate(body, [0.01, w, 0.0], t_end=3.0, samples=31))
             for w in (1.0, 2.0, 4.0, 8.0)]
    return [viz.figure_omega_grid(cases, ncols=3, suptitle="the seed's Figure 1"),
            viz.figure_omega_panels(cases[:2])]


def _animation_frames():
    """Each animation's figure (ground and body frame) as its writer saw it, after its last frame."""
    import contextlib
    import tempfile
    from pathlib import Path

    import tumble.viz.animate as animate

    grabbed = []

    class Grab:  # a writer that keeps the figure instead of encoding its frames
        @contextlib.contextmanager
        def saving(self, fig, outfile, dpi):
            grabbed.append(fig)
            yield self

        def grab_frame(self):
            pass

    original = animate.writer_for
    animate.writer_for = lambda path, fps: Grab()
    try:
        run = _run(t_end=2.0, samples=20)
        with tempfile.TemporaryDirectory() as folder:
            for make in (viz.animate_ground_frame, viz.animate_body_frame):
                make(tumble.t_handle(), run, Path(folder) / "a.gif", max_frames=2, title="T-handle, spin about axis 2")
    finally:
        animate.writer_for = original
    assert len(grabbed) == 2
    return grabbed


def _knowledge():
    """The estimation figure of a short B-dot run fed the MEKF's estimate (star tracker and gyroscope)."""
    from tumble.dynamics.control.controlled import simulate_controlled
    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.control.estimated import Estimated
    from tumble.dynamics.models.sensors import Sensors
    from tumble.dynamics.models.vector_sensors import StarTracker

    sensors = Sensors(gyro_noise=1e-4, gyro_bias=(1e-4, 0.0, 0.0),
                      star_tracker=StarTracker(cross=1e-5, roll=1e-4, period=2.0))
    c = Estimated(BDot(gain=1e-3, period=0.5), sensors)
    run = simulate_controlled([0.01, 0.02, 0.03], [0.0, 0.0, 0.05], t_end=20.0, controller=c, sensors=sensors)
    return viz.figure_knowledge(run, c.knowledge(), bias=sensors.gyro_bias, title="attitude knowledge")


FIGURES = {
    "omega": lambda: viz.figure_omega(_run(), title="T-handle, exact"),
    "omega (detail)": lambda: viz.figure_omega(
        tumble.simulate(tumble.MassProperties.from_moments([1.0, 2.0, 3.0]), [0.1, 0.0, 10.0], t_end=25.0, samples=1001)),
    "polhode": lambda: viz.figure_polhode(_run(), title="polhode"),
    "herpolhode": lambda: viz.figure_herpolhode(_run(), title="herpolhode"),
    "drift": lambda: viz.figure_drift(_run(), title="drift"),
    "grid and panels": _grid,
    "energy and nutation": lambda: [viz.figure_energy(_damped()), viz.figure_nutation(_damped())],
    "orbit angles": _gravity,
    "stability map": lambda: viz.figure_stability_map(10.0, (0.01, 0.01), resolution=30,
                                                      points={"T-handle": (2 / 7, 5 / 7)}),
    "gravity stability": lambda: viz.figure_gravity_stability(points={"box": (0.5, -0.3)}),
    "sweep": _sweep,
    "detumble Monte Carlo": _detumble_mc,
    "control": _control_figures,
    "fits": _fits,
    "tensor": _tensor,
    "animation frames": _animation_frames,
    "knowledge": _knowledge,
}


def test_every_figure_function_is_drawn_here():
    """A new figure function of tumble.viz joins this test (or says why not, here)."""
    drawn = {"figure_omega", "figure_polhode", "figure_herpolhode", "figure_drift", "figure_omega_grid",
             "figure_omega_panels", "figure_energy", "figure_nutation", "figure_orbit_angles", "spacecraft_figures",
             "figure_stability_map", "figure_gravity_stability", "figure_sweep", "figure_detumble_mc", "control_figures",
             "figure_attitude_error", "figure_body_rates", "figure_wheels", "figure_dipole", "figure_momentum_budget",
             "figure_recording", "figure_fit", "figure_tensor", "figure_knowledge"}
    makers = {n for n in viz.__all__ if n.startswith("figure_") or n.endswith("_figures")}
    assert makers <= drawn, f"{sorted(makers - drawn)}: draw it in FIGURES (tests/test_figures_fit.py) and name it here"
    assert drawn <= makers, f"{sorted(drawn - makers)}: no longer in tumble.viz"


@pytest.mark.parametrize("name", FIGURES)
@pytest.mark.filterwarnings("ignore::tumble.viz.plots.AliasedSamplesWarning")   # 2 frames of a flip: the text's the test
def test_no_text_outside_the_canvas(name):
    made = FIGURES[name]()
    for fig in made if isinstance(made, list) else [made]:
        assert texts_outside(fig) == [], name
