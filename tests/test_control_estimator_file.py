"""The ``[estimator]``, ``[sensors.sun]`` and ``[sensors.star_tracker]`` tables of a control file
through ``tumble simulate``: the controller fed the estimate, summary.json's knowledge keys and
the knowledge figure; bad keys and values refused in one line naming the key, the value as
written and what is allowed."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tumble.cli import main
from tumble.dynamics.control.estimated import Estimated
from tumble.dynamics.control.mission import DetumbleThenPoint
from tumble.dynamics.models.vector_sensors import CoarseSunSensor
from tumble.io import load_scenario

EXAMPLE = Path(__file__).resolve().parents[1] / "src" / "tumble" / "examples" / "control" / "estimate_point.toml"


def test_the_example_loads_with_its_estimator():
    scenario = load_scenario(EXAMPLE)
    c = scenario.controller()
    assert isinstance(c, Estimated) and isinstance(c.controller, DetumbleThenPoint)
    assert isinstance(scenario.sensors.sun_sensor, CoarseSunSensor) and scenario.sensors.attitude == "none"
    assert c.field is scenario.field and c.sensors is scenario.sensors


def test_simulate_writes_the_knowledge(tmp_path, capsys):
    """Five minutes of the example (detumbling, sunlit): the summary's knowledge error is the
    figure's, and the filter found the gyroscope's bias to a tenth of it."""
    assert main(["simulate", str(EXAMPLE), "--t-end", "300", "--out", str(tmp_path / "run")]) == 0
    line = capsys.readouterr().out
    assert "knowledge error" in line and "deg RMS" in line
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert 0.0 < summary["knowledge_error_rms_deg"] < 1.0 and summary["knowledge_error_final_deg"] < 1.0
    assert summary["knowledge_start"] == 0.0 and summary["sensors_used"]["sun"] == 1.0
    assert summary["sensors_used"]["magnetometer"] == 1.0 and summary["sensors_used"]["star_tracker"] == 0.0
    # the file's gyro_bias [2e-4, -1e-4, 1.5e-4] is in the design frame; the estimate about the principal
    # axes, the first of which is the long axis, design z (it was added unturned: a walkthrough, 2026-12-03)
    assert summary["bias_estimate_final"] == pytest.approx([1.5e-4, 2e-4, -1e-4], abs=3e-5)
    assert (tmp_path / "run" / "knowledge.png").stat().st_size > 10_000
    pointing = summary.get("pointing_error_final")  # in deg beside the knowledge's, where there is one (not rad and deg)
    assert ("(pointing " in line) == (pointing is not None)
    assert pointing is None or f"(pointing {math.degrees(pointing):.3g} deg)" in line


@pytest.mark.parametrize(("old", "new", "message"), [
    ('kind = "mekf"', 'kind = "ukf"', r"estimator: kind = 'ukf' is unknown; allowed: mekf"),
    ("bias_sigma = 1e-3", "bias_sigm = 1e-3",
     r"estimator: unknown key 'bias_sigm' \(did you mean 'bias_sigma'\?\); allowed: attitude_sigma, bias_sigma, bias_walk, kind, magnetometer_period"),
    ("bias_sigma = 1e-3", "bias_sigma = -1e-3", r"estimator: bias_sigma = -0.001 must be a positive"),
    ("bias_sigma = 1e-3", "bias_walk = -1.0", r"estimator: bias_walk = -1.0 must be"),
    ('sun = { kind = "coarse", noise = 2e-3, epoch = "2026-03-20T14:46:00" }', 'sun = { kind = "coarse", noise = 2e-3 }',
     r"sensors.sun: missing key 'epoch' \(UTC at t = 0"),
    ('sun = { kind = "coarse", noise = 2e-3, epoch = "2026-03-20T14:46:00" }',
     'sun = { kind = "fine", axes = [[1, 0, 0]], epoch = "2026-03-20T14:46:00" }',
     r"sensors.sun: key 'axes' does not go with kind = 'fine'; allowed: epoch, fov, frame, kind, noise, period, shadow"),
    ('sun = { kind = "coarse", noise = 2e-3, epoch = "2026-03-20T14:46:00" }', 'sun = { kind = "half", epoch = "2026-03-20T14:46:00" }',
     r"sensors.sun: kind = 'half' is unknown; allowed: coarse, fine"),
    ('noise = 2e-3, epoch = "2026-03-20T14:46:00"', 'noise = -2e-3, epoch = "2026-03-20T14:46:00"', r"sensors.sun: noise = -0.002 must be"),
    ('epoch = "2026-03-20T14:46:00"', 'epoch = "spring"', r"sensors.sun: epoch = 'spring' is not an ISO 8601"),
    ('noise = 2e-3, epoch', 'shadow = "cone", noise = 2e-3, epoch',
     r"sensors.sun: shadow = 'cone' is unknown; allowed: conical, cylindrical, none"),
    ("seed = 1", "seed = 1\nstar_tracker = { cross = -1.0 }", r"sensors.star_tracker: cross = -1.0 must be"),
    ("seed = 1", "seed = 1\nstar_tracker = { frame = [0, 0, 0, 0] }", r"sensors.star_tracker: frame = \[0, 0, 0, 0\]"),
    ('sun = { kind = "coarse", noise = 2e-3, epoch = "2026-03-20T14:46:00" }', "",
     r"estimator: the filter needs \[sensors.star_tracker\], or \[sensors.sun\] and an \[orbit\]"),
    # the [sensors] attitude reading is not the filter's star tracker: written so, it ran with no tracker at all
    # (sensors_used.star_tracker 0; a GNC walkthrough, 2026-12-03)
    ('attitude = "none"', 'attitude = "star_tracker"\nattitude_noise = 1e-5',
     r"sensors: attitude = 'star_tracker' is not read with an \[estimator\]: the filter takes a star tracker from "
     r"\[sensors.star_tracker\] \(cross, roll, period\); write attitude = \"none\""),
])
def test_bad_input_one_line(tmp_path, capsys, old, new, message):
    text = EXAMPLE.read_text()
    assert old in text
    path = tmp_path / "bad.toml"
    path.write_text(text.replace(old, new, 1))
    code = main(["simulate", str(path), "--out", str(tmp_path / "run")])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1, err
    assert re.search(message, err) and "bad.toml" in err, err
    assert not (tmp_path / "run").exists()


def test_an_epoch_outside_the_suns_formulas_is_said_in_one_line(tmp_path, capsys):
    """A sun epoch of 2300 ran silently, where the low-precision formulas state 0.01 deg for 1950-2050 only
    (a walkthrough, 2026-12-02): one line says how far the precession alone moves the Sun there (50.29"/yr)."""
    text = EXAMPLE.read_text().replace('epoch = "2026-03-20T14:46:00"', 'epoch = "2300-03-20T14:46:00"')
    assert "2300-03-20" in text
    path = tmp_path / "late.toml"
    path.write_text(text)
    assert main(["simulate", str(path), "--t-end", "20", "--out", str(tmp_path / "run")]) == 0
    warned = [line for line in capsys.readouterr().err.splitlines() if line.startswith("warning: ")]
    years = 300.0
    assert warned == [f"warning: epoch = 2300-03-20T14:46:00 lies outside 1950-2050, the span of the Sun's low-precision "
                      f"formulas (0.01 deg); the precession of the equinoxes, which this ECI leaves in, adds about "
                      f"{years * 50.29 / 3600:.2g} deg to the Sun's direction there"], warned


@pytest.mark.parametrize("size", [[0.1, 0.1, 0.34], [0.34, 0.1, 0.12]])
def test_the_sensor_biases_are_given_in_the_design_frame(tmp_path, size):
    """A control file's vectors are in the body's design frame (docs/formats/control.md); the gyroscope's
    and magnetometer's biases were added unturned to the principal-frame rates and field (a walkthrough,
    2026-12-03: gyro_bias = [5e-4, 0, 0], design x, landed on the long axis, design z). Each bias, taken
    to the world by the run's attitude, is the design vector taken there by the design attitude."""
    text = EXAMPLE.read_text().replace("size = [0.1, 0.1, 0.34]", f"size = {size}")
    text = text.replace("gyro_bias = [2e-4, -1e-4, 1.5e-4]", "gyro_bias = [5e-4, 0.0, 0.0]\nmagnetometer_bias = [0.0, 0.0, 3e-7]")
    assert f"size = {size}" in text and "magnetometer_bias" in text
    path = tmp_path / "biased.toml"
    path.write_text(text)
    scenario = load_scenario(path)
    design_to_world = scenario.attitude0 * Rotation.from_matrix(scenario.body.principal_axes).inv()
    for name, design in (("gyro_bias", [5e-4, 0.0, 0.0]), ("magnetometer_bias", [0.0, 0.0, 3e-7])):
        principal = np.array(getattr(scenario.sensors, name))
        np.testing.assert_allclose(scenario.attitude0.apply(principal), design_to_world.apply(design), atol=1e-20)


def test_attitude_sigma_raises_the_starts_uncertainty(tmp_path):
    """``[estimator] attitude_sigma`` was checked and documented but read by nothing (a walkthrough,
    2026-12-03: 1e-6 and 3.0 gave the same summary): it is now the least standard deviation of the
    start's attitude about any axis, TRIAD's covariance raised to it; without it TRIAD's is taken."""
    from tumble.dynamics.control.controlled import simulate_controlled

    path = tmp_path / "wide.toml"
    path.write_text(EXAMPLE.read_text().replace("[estimator]\n", "[estimator]\nattitude_sigma = 0.3\n", 1))
    first = {}
    for name, file in (("as TRIAD's", EXAMPLE), ("raised", path)):
        scenario = load_scenario(file)
        c = scenario.controller()
        simulate_controlled(**{**scenario.arguments(c), "t_end": 20.0})
        first[name] = c.knowledge().sigma[0, :3]
    assert load_scenario(path).controller().attitude_sigma == 0.3 and load_scenario(EXAMPLE).controller().attitude_sigma is None
    assert np.all(first["as TRIAD's"] < 0.01) and np.all(first["raised"] > 3 * first["as TRIAD's"]), first


def test_estimated_refuses_the_attitude_reading_it_would_not_read():
    """In Python as in the file: ``Sensors(attitude="star_tracker")`` under :class:`Estimated` fed no
    filter; the MRP law's complaint then blamed ``sensors.attitude = 'none'``, which it was not."""
    from tumble.dynamics.control.bdot import BDot
    from tumble.dynamics.models.sensors import Sensors

    with pytest.raises(ValueError, match=r"^sensors.attitude = 'star_tracker' is not read by Estimated: .*StarTracker"):
        Estimated(BDot(gain=1e-3, period=0.5), Sensors(gyro_noise=1e-4, attitude="star_tracker", attitude_noise=1e-5))
    Estimated(BDot(gain=1e-3, period=0.5), Sensors(attitude="none"))  # the filter's own sensors: fine
