"""Every public result reads well (issue 40, item 3): a plain repr of one short line that says
what the result is, its size and its headline numbers (the object's own values, never its
arrays), and a Jupyter table (``_repr_html_``) that parses and holds the same numbers."""

from __future__ import annotations

import dataclasses
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import tumble
from tumble._html import REPR_CHARS, fmt, with_std

# Results small enough to make in a fraction of a second each --------------------------------


def controlled_run():
    from tumble.dynamics.control.controlled import simulate_controlled
    from tumble.dynamics.control.controllers import MRPFeedback
    from tumble.dynamics.models.actuators import ReactionWheels
    from scipy.spatial.transform import Rotation

    rw = ReactionWheels(np.eye(3), inertia=1e-4, max_torque=1e-3)
    c = MRPFeedback(K=1e-3, P=1e-2, period=0.5, moments=[0.03, 0.04, 0.05], wheels=rw)
    return simulate_controlled([0.03, 0.04, 0.05], [0.01, 0.0, 0.0], t_end=10.0, controller=c, wheels=rw,
                               attitude0=Rotation.from_rotvec([0.2, 0.0, 0.0]))


def detumble_batch():
    from tumble.dynamics.control.detumble import DetumbleBatch

    return DetumbleBatch(t=np.array([0.0, 1.0, 2.0]), rate=np.array([[0.3, 0.1, 0.05], [0.3, 0.05, 0.2]]),
                         omega=np.zeros((2, 3)), quat=np.tile([0.0, 0.0, 0.0, 1.0], (2, 1)))


def rotation_fit():
    from tumble.analysis.fit.result import rotation_fit
    from tumble.analysis.fit.single import fit_solution
    from tumble.dynamics.methods.exact_omega import free_omega

    t = np.linspace(0.0, 2.0, 201)
    w = free_omega([[0.5, 0.8, 1.0]], [[3.0, 1.0, 6.0]], t)[0] + np.random.default_rng(0).normal(0.0, 0.01, (201, 3))
    keep = np.ones(w.shape, bool)
    return rotation_fit(fit_solution(t, w, keep, rotation=False, bias=False, drag="none"), t, w, keep)


@pytest.fixture(scope="module")
def recording_fit():
    from tumble.analysis.fit.recording import fit_recording
    from tumble.analysis.fit.synthetic import synthetic_recording

    rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
    return fit_recording(rec.t, rec.omega, events=rec.events)


def estimate():
    from tumble.analysis.tensor.estimate import mass_estimate

    return mass_estimate(0.5, np.diag([2e-4, 1e-4, 3e-4]), np.eye(6) * 1e-14, [0.01, 0.002, 0.0], np.eye(3) * 1e-8)


def tensor_fit():
    from tumble.analysis.tensor import TensorFit, ThrowFit

    e = estimate()
    used = ThrowFit("a.csv", "used", "", e, e, np.zeros(0), np.zeros((0, 3)), np.zeros((0, 3)), 0.1, 0.9, 0.0123)
    skipped = ThrowFit("b.csv", "skipped", "no free flight found", None, None, np.zeros(0), np.zeros((0, 3)),
                       np.zeros((0, 3)))
    return TensorFit(object=e, flown=e, throws=(used, skipped), adequate=True, chi2_dof=1.37)


def calibration():
    from tumble.analysis.tensor import Device
    from tumble.analysis.tensor.calibrate import Calibration

    return Calibration(Device(0.1, [0, 0, 1], rotor_inertia=1.7e-6, rotor_inertia_std=2e-8), 9.25, 1.1, 0.8, 3, 4,
                       0.0217, ("c.csv: no flight",), ("the proof turned",))


def monte_carlo():
    from tumble.ensemble.detumble import DetumbleMonteCarlo, detumble_cases

    c = detumble_cases(3, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3, seed=2)
    return DetumbleMonteCarlo(times=np.array([100.0, 300.0, np.nan]), cases=c, threshold=0.01, t_end=600.0, seconds=0.1)


def sweep_summary():
    from tumble.ensemble.summary import SweepSummary

    cols = {"case": np.arange(4), "axis": np.array([2, 2, 2, 3]), "predicted": np.array(["unstable"] * 3 + ["stable"]),
            "circulation": np.array([1, 3, 3, 3]), "flips": np.array([2, 4, 6, 0]), "resampled": np.zeros(4, int)}
    return SweepSummary.of(cols, seed=0)


def stability_map():
    from tumble.ensemble.reductions import stability_map

    return stability_map(10.0, resolution=20)


def period_family():
    from tumble.analysis.period_inversion import PeriodFamily

    return PeriodFamily(np.array([[0.2, 0.5], [0.3, 0.6], [0.25, 0.55]]), np.ones(3), np.ones(3),
                        np.array(["SAM", "LAM", "SAM"]))


def synthetic():
    from tumble.analysis.fit.synthetic import synthetic_recording

    return synthetic_recording(11, tosses=2, flight=(0.5, 0.8))


def flight():
    from tumble.analysis.fit.flights import Flight

    return Flight(start=1.25, end=1.75, first=125, stop=175, status="skipped", reason="too short")


def detumble_cases():
    from tumble.ensemble.detumble import detumble_cases

    return detumble_cases(3, moments=[0.0067, 0.0419, 0.0419], rate_min=0.1, rate_max=0.3, seed=2)


def knowledge_cases():
    from tumble.ensemble.knowledge import knowledge_cases

    return knowledge_cases(5, gyro_bias_sigma=1e-4, noise_spread=0.2, seed=1)


def pointing():
    from tumble.dynamics.models.sensors import Sensors
    from tumble.ensemble.knowledge import PointingMonteCarlo

    e = np.radians([0.1, 0.2, 0.3, 0.4, 1.5])
    return PointingMonteCarlo(knowledge_cases(), e / 3, e / 4, e, e / 2, Sensors(gyro_noise=1e-4), 60.0)


def gyro_recording():
    from importlib import resources

    from tumble.io.gyrodata import load_recording

    return load_recording(resources.files("tumble") / "examples/data/phone_toss.csv")


def orbit_angles():
    from tumble.dynamics.models.lvlh import OrbitAngles

    return OrbitAngles(roll=np.radians([0.0, 1.0, -2.0]), pitch=np.radians([5.0, 0.0, -5.5]), yaw=np.radians([10.0, 11.0, 12.0]))


def spin():
    from tumble.analysis.stability import spin_prediction

    return spin_prediction([0.01, 1.0, 0.0], [1.0, 2.0, 3.0])


def spins():
    from tumble.analysis.stability import spin_prediction

    return spin_prediction([[0.01, 1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 2.0]], [1.0, 2.0, 3.0])


def regions():
    from tumble.analysis.gravity_stability import gravity_gradient_ratios, gravity_gradient_stability

    moments = np.array([[1.0, 2.0, 3.0], [1.0, 2.9, 3.0], [2.0, 2.5, 3.0]])
    return gravity_gradient_stability(*gravity_gradient_ratios(moments, pitch_axis=2, yaw_axis=1))


def region():
    from tumble.analysis.gravity_stability import gravity_gradient_ratios, gravity_gradient_stability

    return gravity_gradient_stability(*gravity_gradient_ratios([1.0, 2.0, 3.0]))


def _spread(x) -> list[str]:
    return [fmt(np.min(x), 3), fmt(np.max(x), 3)]


def headline_numbers(obj) -> list[str]:
    """The numbers a result's repr must show, as :func:`fmt` writes them, from its own attributes."""
    name = type(obj).__name__
    if name == "ControlledRun":
        return [f"{len(obj.t)} samples", fmt(obj.t[-1] - obj.t[0]), fmt(math.degrees(obj.rate[-1]), 3),
                fmt(np.abs(obj.wheel_speed).max(), 3), f"{obj.wheel_speed.shape[1]} wheels"]
    if name == "DetumbleBatch":
        return [f"{obj.rate.shape[0]} bodies", fmt(math.degrees(np.median(obj.rate[:, -1])), 3),
                fmt(math.degrees(obj.rate[:, -1].max()), 3)]
    if name == "RotationFit":
        return [f"{obj.samples} samples", with_std(obj.ratios[0], obj.ratios_std[0]),
                with_std(obj.ratios[1], obj.ratios_std[1]), fmt(obj.residual_rms, 3)]
    if name == "RecordingFit":
        return [f"{obj.tosses_used} of {len(obj.tosses)}", with_std(obj.pooled.ratios[0], obj.pooled.ratios_std[0]),
                fmt(obj.chi2_dof, 2)]
    if name in ("MassEstimate", "TensorFit"):
        e = obj if name == "MassEstimate" else obj.object
        return [with_std(m, s) for m, s in zip(e.principal_moments, e.principal_moments_std)] + [fmt(e.center_of_mass[0] * 1e3)]
    if name == "Calibration":
        return [fmt(obj.chi2_dof, 2), f"{obj.alone_used} + {obj.proof_used}", fmt(obj.max_bias, 3), "1 problem"]
    if name == "DetumbleMonteCarlo":
        return [f"{len(obj.times)} cases", fmt(100 * obj.detumbled, 3), fmt(obj.percentile(50))]
    if name == "SweepSummary":
        return [f"{obj.cases} cases", f"{obj.flipped} flipped"]
    if name == "StabilityMap":
        return [f"{len(obj.x)} x {len(obj.y)}", f"{int(obj.inside.sum())} inside", fmt(obj.omega0[1])]
    if name == "SyntheticRecording":
        return [f"{len(obj.t)} samples", f"{len(obj.flights)} flights", fmt(obj.ratios[0]), fmt(obj.ratios[1])]
    if name == "Flight":
        return [fmt(obj.start), fmt(obj.end), f"{obj.first}..{obj.stop}", obj.reason]
    if name == "PeriodFamily":
        return [f"{len(obj.mode)} motions", "2 SAM", fmt(obj.ratios[:, 0].max(), 3)]
    if name == "DetumbleCases":
        return [f"{len(obj)} cases", *_spread(np.degrees(np.linalg.norm(obj.omega0, axis=1)))]
    if name == "KnowledgeCases":
        return [f"{len(obj)} cases", *_spread(np.degrees(np.linalg.norm(obj.gyro_bias, axis=1))),
                *_spread(obj.noise_scale), f"{obj.noise_seed[0]}..{obj.noise_seed[-1]}"]
    if name == "PointingMonteCarlo":
        point, know = np.degrees(obj.pointing_rms), np.degrees(obj.knowledge_rms)
        return [f"{len(obj.cases)} cases", fmt(obj.settle), fmt(np.median(point), 3), fmt(np.percentile(point, 95), 3),
                fmt(np.median(know), 3), fmt(np.percentile(know, 95), 3)]
    if name == "GyroRecording":
        return ["phone_toss.csv", f"{len(obj.t)} samples", fmt(obj.t[-1] - obj.t[0], 3), fmt(obj.read.sample_rate, 3),
                fmt(np.linalg.norm(obj.omega, axis=1).max(), 3), f"{len(obj.events)} events"]
    if name == "SpinPrediction" and np.ndim(obj.axis) == 0:
        return [f"spin axis {obj.axis}", f"about axis {obj.circulation}", "unstable", fmt(obj.growth)]
    if name == "SpinPrediction":
        return [f"{len(obj.axis)} motions", f"{int(np.sum(obj.stable))} stable", f"{int(np.sum(~obj.stable))} unstable"]
    if name == "StabilityClass" and np.ndim(obj.region) == 0:
        return [str(obj.region), "pitch stable", "roll-yaw stable"]
    if name == "StabilityClass":
        return [f"{len(obj.region)} bodies", f"{len(obj.region)} {obj.region[0]}"]
    if name == "OrbitAngles":
        return ["3 samples", *(number for angle in obj for number in _spread(np.degrees(angle)))]
    raise AssertionError(name)


MAKERS = [controlled_run, detumble_batch, rotation_fit, estimate, tensor_fit, calibration, monte_carlo, sweep_summary,
          stability_map, period_family, synthetic, flight, detumble_cases, knowledge_cases, pointing, gyro_recording,
          orbit_angles, spin, spins, region, regions]


@pytest.fixture(scope="module", params=MAKERS, ids=lambda f: f.__name__)
def result(request):
    return request.param()


def check_repr(obj) -> str:
    text = repr(obj)
    assert text.startswith(type(obj).__name__ + "("), text
    assert len(text) <= REPR_CHARS and "\n" not in text, (len(text), text)
    assert "array(" not in text and "[[" not in text, text  # no arrays
    for number in headline_numbers(obj):
        assert number in text, (number, text)
    return text


def test_repr_is_short_and_shows_the_objects_numbers(result):
    check_repr(result)


def test_recording_fit_repr(recording_fit):
    check_repr(recording_fit)
    assert "2 of 2 flights" in repr(recording_fit)
    for toss in recording_fit.tosses:
        assert repr(toss).startswith("Toss(") and len(repr(toss)) <= REPR_CHARS and fmt(toss.start) in repr(toss)
    for model in recording_fit.flight_models:
        text = repr(model)
        assert text.startswith("FlightModel(") and len(text) <= REPR_CHARS and "array" not in text
        assert fmt(model.ratios[0]) in text and fmt(model.start) in text and f"recording {model.recording}" in text


def test_html_parses_and_holds_the_headline(result, recording_fit):
    for obj in (result, recording_fit):
        page = obj._repr_html_()
        root = ET.fromstring(page)  # every tag closed, every '<' and '&' escaped
        assert root.tag == "div" and root.find("table/caption").text.startswith(type(obj).__name__)
        text = "".join(root.itertext())
        for headline in headline_numbers(obj):  # the repr's numbers, in the table too
            for number in re.findall(r"\d[\d.e+-]*\d|\d", headline):
                assert number in text, (number, headline, text)


@pytest.mark.parametrize("maker, field, value, shown", [
    (detumble_batch, "rate", np.array([[0.3, 0.1, math.radians(2.5)]]), "2.5 deg/s"),
    (rotation_fit, "residual_rms", 0.0417, "residual 0.0417 rad/s"),
    (rotation_fit, "adequate", False, "NOT adequate"),
    (tensor_fit, "chi2_dof", 7.25, "chi2/dof 7.2"),
    (calibration, "problems", (), "Calibration(adequate,"),
    (calibration, "max_bias", 0.125, "max bias 0.125 rad/s"),
    (pointing, "settle", 120.0, "after 120 s"),
    (pointing, "pointing_rms", np.radians([2.0] * 5), "pointing RMS median 2 deg, 95 % 2 deg"),
    (knowledge_cases, "noise_scale", np.array([0.5, 1.0, 1.0, 1.0, 2.0]), "noise scale 0.5..2"),
    (detumble_cases, "omega0", np.radians([[1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 30.0]]), "|omega0| 1..30 deg/s"),
    (gyro_recording, "events", (("START", 0.0), ("PAUSE", 5.0)), "2 events"),
    (orbit_angles, "yaw", np.radians([-40.0, 0.0, 40.0]), "yaw -40..40 deg"),
    (spin, "growth", np.float64(2.5), "growth exponent 2.5 1/s"),
    (region, "pitch", np.False_, "pitch unstable"),
    (regions, "region", np.array(["lagrange", "unstable", "unstable"]), "2 unstable, 1 lagrange"),
])
def test_a_changed_value_changes_the_repr(maker, field, value, shown):
    """The numbers are read from the object, not written into the repr: change one, the repr follows."""
    before = maker()
    assert shown not in repr(before)
    after = before._replace(**{field: value}) if hasattr(before, "_replace") else dataclasses.replace(before, **{field: value})
    assert shown in repr(after)


def test_long_messages_and_names_stay_within_the_bound():
    from tumble.analysis.fit.tosses import Toss
    from tumble.analysis.tensor import ThrowFit

    toss = Toss(start=1.0, end=1.8, samples=81, status="skipped", reason="the model does not fit\n" * 40)
    throw = ThrowFit("x" * 500 + ".csv", "skipped", "why " * 200, None, None, np.zeros(0), np.zeros((0, 3)),
                     np.zeros((0, 3)))
    for text in (repr(toss), repr(throw), repr(dataclasses.replace(calibration(), left_out=("a",) * 1000))):
        assert len(text) <= REPR_CHARS and "\n" not in text, text


def test_batch_trajectory_html():
    batch = tumble.simulate_batch([[1.0, 2.0, 3.0], [1.0, 2.5, 3.0]], [[1.0, 0.1, 0.0], [0.0, 2.0, 0.1]], t_end=2.0,
                                  samples=5)
    root = ET.fromstring(batch._repr_html_())
    cells = {tr[0].text: tr[1].text for tr in root.iter("tr")}
    assert cells["bodies"] == "2" and cells["samples"] == "5"
    assert cells["|omega(0)|, smallest to largest"] == f"{fmt(np.hypot(1.0, 0.1))} to {fmt(np.hypot(2.0, 0.1))} rad/s"


def test_period_family_and_cases_tables_hold_their_counts():
    """The tables say what the reprs leave out: the motions by mode, the cases' spread."""
    family = ET.fromstring(period_family()._repr_html_())
    cells = {tr[0].text: tr[1].text for tr in family.iter("tr")}
    assert cells["motions"] == "3" and cells["short-axis modes (SAM)"] == "2" and cells["long-axis modes (LAM)"] == "1"
    assert cells["I1/I3"] == "0.2 to 0.3"
    mc = ET.fromstring(pointing()._repr_html_())
    header = [th.text for th in mc.iter("th")]
    assert header == ["error, deg", "median", "95 %", "largest"]
    largest = {tr[0].text: tr[3].text for tr in mc.iter("tr") if len(tr) == 4 and tr[0].tag == "td"}
    assert largest["pointing RMS"] == "1.5" and largest["final knowledge"] == fmt(1.5 / 4, 3)


# --- every result of a public function, listed ---------------------------------------------------

#: Classes that public functions return but that are not results to read: what a user writes or
#: loads to set a run up (bodies' parts, devices, scenarios, settings, models), records
#: unpacked at once, and machinery.
NOT_RESULTS = {
    "Device", "Proof", "Imperfections", "RotorSchedule", "Rigid", "ThrowTimes", "RotorInput",  # a device and its throws' set-up
    "BDot", "MRPFeedback", "DetumbleThenPoint", "Reference", "PDResponse",  # controllers and their gains
    "CubicTable", "Method", "GravityGradient", "OrbitGravityGradient", "TorqueModel", "RunInputs",  # models, settings
    "LVLHState", "EllipticParameters", "InternalSamples", "Adjusted",  # tuples unpacked where they are made
    "DaskBackend", "InProcess", "ChunkRanges", "Layout", "FreeTerms",  # machinery
    "ControlScenario", "ControlSpec", "Scenario", "SweepFile", "Example", "Part",  # files a user writes
    "ColumnsRead", "ThrowRead",  # what a reader took from a file: brief() and summary() say it
    "FitFolder", "TensorFolder", "FlightReplay",  # a command's output read back, for its page
}

#: Results in folders that other work is changing (src/tumble/analysis/fit, analysis/tensor,
#: dynamics/control and dynamics/methods): to be given a short repr and a table there. A class that
#: gets both fails the test until it is moved off this list.
WAITING: set[str] = set()


def _returned_classes() -> dict[type, list[str]]:
    """Every tumble class that a public function's return annotation names, with the functions."""
    import importlib
    import inspect
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "docs" / "_ext"))
    import tumble_api

    found: dict[type, list[str]] = {}
    for module_name in tumble_api.api_modules():
        module = importlib.import_module(module_name)
        for name in getattr(module, "__all__", []):
            func = getattr(module, name, None)
            if not inspect.isfunction(func):
                continue
            annotation = func.__annotations__.get("return")
            scope = vars(importlib.import_module(func.__module__))
            for word in re.findall(r"[A-Za-z_][\w.]*", annotation if isinstance(annotation, str) else ""):
                obj = scope.get(word.split(".")[0])
                for attr in word.split(".")[1:]:
                    obj = getattr(obj, attr, None)
                if inspect.isclass(obj) and obj.__module__.startswith("tumble."):
                    found.setdefault(obj, []).append(f"{func.__module__}.{name}")
    return found


def test_every_result_of_a_public_function_reads_well():
    """A class a public function returns is a result that has its own short repr and a Jupyter
    table, or is listed above as not a result (with its reason) or as waiting."""
    found = _returned_classes()
    names = {cls.__name__ for cls in found}
    assert {"Trajectory", "BatchTrajectory", "RecordingFit", "TensorFit", "PointingMonteCarlo", "GyroRecording"} <= names
    assert not NOT_RESULTS - names, "listed but no public function returns it"
    missing, done = [], []
    for cls, functions in sorted(found.items(), key=lambda item: item[0].__name__):
        code = getattr(cls.__repr__, "__code__", None)
        reads_well = code is not None and "tumble" in Path(code.co_filename).parts and hasattr(cls, "_repr_html_")
        if cls.__name__ in WAITING and reads_well:
            done.append(cls.__name__)
        elif cls.__name__ not in NOT_RESULTS | WAITING and not reads_well:
            missing.append(f"{cls.__module__}.{cls.__name__} (from {functions[0]})")
    assert not missing, "results without their own repr and _repr_html_:\n" + "\n".join(missing)
    assert not done, f"move off WAITING: {done}"


def _settings():
    """The models and settings a user makes and prints: actuators, controllers, a mission, a filter, sensors."""
    from scipy.spatial.transform import Rotation

    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.control.controllers import MomentumDumping, MRPFeedback
    from tumble.dynamics.control.mission import DetumbleThenPoint
    from tumble.dynamics.estimation.mekf import MEKF
    from tumble.dynamics.models.actuators import Command, Magnetorquers, ReactionWheels

    from tumble.dynamics.control.estimated import Estimated
    from tumble.dynamics.models.sensors import Sensors
    from tumble.dynamics.models.vector_sensors import StarTracker

    tracker = StarTracker(cross=1e-5, roll=1e-4, period=1.0, frame=Rotation.from_rotvec([0.0, 0.1, 0.0]))
    sensors = Sensors(gyro_noise=1e-4, star_tracker=tracker)
    wheels = ReactionWheels(np.eye(4, 3) + 0.1, inertia=1e-4, max_torque=1e-3, max_speed=600.0)
    point = MRPFeedback(K=0.01, P=0.1, period=1.0, moments=[1.0, 2.0, 3.0], wheels=wheels,
                        target=Rotation.from_rotvec([0.0, 0.0, 0.5]))
    return [wheels, Magnetorquers(1.0), point, MomentumDumping(point, gain=0.01), BDot(gain=1e-3, period=1.0),
            DetumbleThenPoint(BDot(gain=1e-3, period=1.0), point, switch_rate=0.01, dwell=60.0),
            MEKF.start([0.0, 0.0, 0.0, 1.0], attitude_sigma=0.1, bias_sigma=0.01, gyro_noise=1e-4, bias_walk=1e-6),
            Command(wheel_torque=np.zeros(4)), tracker, sensors, Estimated(BDot(gain=1e-3, period=0.5), sensors)]


@pytest.mark.parametrize("setting", _settings(), ids=lambda s: type(s).__name__)
def test_a_settings_repr_is_one_line_of_its_values(setting):
    """A walkthrough printed ReactionWheels, MRPFeedback, DetumbleThenPoint and MEKF as pages of numpy
    arrays (dataclass reprs): each is now one line, short vectors by value and matrices by shape."""
    shown = repr(setting)
    assert "\n" not in shown and "array(" not in shown and len(shown) <= REPR_CHARS, shown
    assert shown.startswith(type(setting).__name__ + "(")
    for name in ("inertia", "K", "gain", "covariance", "wheel_torque"):  # a field shown by its value or its shape
        if hasattr(setting, name) and f"{name}=" in shown:
            value = getattr(setting, name)
            expected = f"<{' x '.join(map(str, np.shape(value)))} array>" if np.ndim(value) > 1 or np.size(value) > 6 \
                else fmt(value) if np.ndim(value) == 0 else "(" + ", ".join(fmt(v) for v in np.ravel(value)) + ")"
            assert f"{name}={expected}" in shown, (name, shown)


def test_a_pooled_fit_counts_every_flights_samples(recording_fit):
    """The pooled RotationFit said "56 samples" for a joint fit of 12 flights: the first flight's count
    (its times and model are that flight's view). It counts the samples of every flight used."""
    fit = recording_fit
    used = [toss for toss in fit.tosses if toss.status == "ok"]
    assert len(used) == fit.tosses_used == 2
    assert fit.pooled.samples == sum(toss.samples for toss in used) > len(fit.pooled.t)
    assert f"{fit.pooled.samples} samples" in repr(fit.pooled) and fit.pooled.summary()["samples"] == fit.pooled.samples
