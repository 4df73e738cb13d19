"""The smaller items of issue 40 (the first hour III), each held by a test that fails without it."""

from __future__ import annotations

import contextlib
import io
import pydoc
from pathlib import Path

import pytest

import tumble
from tumble.cli import main
from tumble.dynamics.methods.integrators import METHODS
from tumble.dynamics.methods.names import METHOD_NAMES


def _help(*argv: str) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out), pytest.raises(SystemExit):
        main([*argv, "--help"])
    return " ".join(out.getvalue().split())  # argparse wraps lines: a name is never cut, but may sit on the next


def test_the_help_lists_every_method_of_the_registry():
    """help(tumble.simulate) and the commands' --help named seven methods of twelve (no rk4, rk8,
    exact_split*); both now read the registry's names."""
    assert tuple(METHODS) == METHOD_NAMES  # the names the help texts read are the registry's
    doc = pydoc.render_doc(tumble.simulate, renderer=pydoc.plaintext)
    for text in (doc, _help("view"), _help("simulate"), _help("plot")):
        listed = {word.strip("`,.()") for word in text.split()}
        assert set(METHODS) <= listed, set(METHODS) - listed


def test_control_figures_do_not_repeat_the_name(tmp_path, monkeypatch, capsys):
    """A scenario named after its controller (detumble_point.toml, kind "detumble_point") titled its
    figures "detumble_point (detumble_point)"."""
    import tumble.viz

    source = (Path(tumble.__file__).parent / "examples" / "control" / "detumble.toml").read_text(encoding="utf-8")
    scenario = tmp_path / "bdot.toml"
    scenario.write_text(source.replace('name = "3U CubeSat"', "").replace("t_end = 11400.0", "t_end = 5.0"),
                        encoding="utf-8")
    titles = []
    real = tumble.viz.control_figures

    def spy(run, **kw):
        titles.append(kw["title"])
        return real(run, **kw)

    monkeypatch.setattr(tumble.viz, "control_figures", spy)
    assert main(["simulate", str(scenario), "--out", str(tmp_path / "run")]) == 0
    assert titles == ["bdot"], titles  # the body's name is the file's, the controller's kind the same


SWEEP = """\
body = "t-handle"

[sweep]
cases = 8
seed = 5

[initial]
omega = [0.1, 5.0, 0.1]
distribution = "normal"
spread = [0.01, 0.0, 0.01]

[simulation]
t_end = 10.0
samples = 200

[criterion]
column = "flips"
max = 0
"""


def test_sweep_names_the_criterion_its_failures_failed(tmp_path, capsys):
    """tumble sweep said '319 failures' and not of what."""
    path = tmp_path / "sweep.toml"
    path.write_text(SWEEP, encoding="utf-8")
    assert main(["sweep", str(path), "--out", str(tmp_path / "out")]) == 0
    line = capsys.readouterr().out
    assert "8 cases, 8 failures of the criterion flips <= 0: success probability" in line, line


def _readers():
    from tumble.io.devicefile import load_device
    from tumble.io.fitfolder import read_fit_folder
    from tumble.io.gyrodata import read_recording
    from tumble.io.scenario import resolve_run
    from tumble.io.sweepfile import load_sweep
    from tumble.io.throwfile import read_throw

    return {"load_body": lambda p: tumble.load_body(p / "b.toml"), "load_scenario": lambda p: tumble.load_scenario(p / "s.toml"),
            "read_recording": lambda p: read_recording(p / "r.csv"), "Mesh": lambda p: tumble.Mesh(mesh=p / "m.stl", mass=1.0),
            "load_sweep": lambda p: load_sweep(p / "w.toml"), "read_throw": lambda p: read_throw(p / "t.csv"),
            "load_device": lambda p: load_device(p / "d.toml"), "read_fit_folder": lambda p: read_fit_folder(p / "fit"),
            "resolve_run": lambda p: resolve_run(str(p / "nothing"), omega=[0.1, 5.0, 0.1])}


@pytest.mark.parametrize("reader", sorted(_readers()))
def test_a_missing_file_is_a_file_not_found_error(reader, tmp_path):
    """A missing file raised ValueError, not the FileNotFoundError users catch; it is both now."""
    with pytest.raises(FileNotFoundError, match="no such f") as info:
        _readers()[reader](tmp_path)
    assert isinstance(info.value, ValueError) and str(tmp_path) in str(info.value) and "Errno" not in str(info.value)


@pytest.mark.parametrize("argv", [["inertia", "{tmp}/m.stl", "--mass", "1"], ["simulate", "{tmp}/s.toml", "--out", "{tmp}/o"],
                                  ["fit", "{tmp}/r.csv", "--out", "{tmp}/o"], ["view", "{tmp}/fit", "--out", "{tmp}/v.html"]])
def test_the_command_line_says_a_missing_file_in_one_line_and_exits_2(argv, tmp_path, capsys):
    assert main([a.format(tmp=tmp_path) for a in argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("tumble: error: ") and "no such f" in err, err


@pytest.fixture(scope="module")
def boxes(tmp_path_factory):
    """A 5 cm box exported in metres and the same box in millimetres (STL)."""
    trimesh = pytest.importorskip("trimesh")
    folder = tmp_path_factory.mktemp("meshes")
    trimesh.creation.box(extents=(0.05, 0.05, 0.05)).export(folder / "in_metres.stl")
    trimesh.creation.box(extents=(50.0, 50.0, 50.0)).export(folder / "in_mm.stl")
    return folder


def test_a_mesh_read_in_the_wrong_unit_is_named(boxes, capsys):
    """A mesh whose mass came out 2e-10 kg with --units mm passed without a word."""
    assert main(["inertia", str(boxes / "in_metres.stl"), "--units", "mm", "--density", "1600"]) == 0
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("warning: ") and "0.05 mm across (the cube root of its volume; 2e-10 kg)" in err, err
    assert 'read it in metres (units = "m", or no --units)' in err
    assert main(["inertia", str(boxes / "in_mm.stl"), "--mass", "0.2"]) == 0  # 50 m across: millimetres?
    assert 'give units = "mm"' in capsys.readouterr().err
    for argv in (["in_mm.stl", "--units", "mm"], ["in_metres.stl"]):  # the right unit: no warning
        assert main(["inertia", str(boxes / argv[0]), *argv[1:], "--mass", "0.2"]) == 0
        assert capsys.readouterr().err == ""


def test_a_mesh_read_in_the_wrong_unit_warns_in_python(boxes):
    from tumble.io.bodyfile import MeshScaleWarning, body_from_mesh

    with pytest.warns(MeshScaleWarning, match="0.05 mm across"):
        body_from_mesh(boxes / "in_metres.stl", density=1600.0, units="mm")


@pytest.mark.parametrize("torque", [lambda t, omega, attitude: (0.0, 0.0, 0.01), tumble.ConstantTorque((0.0, 0.0, 0.01))],
                         ids=["python", "built-in"])
def test_the_methods_a_refusal_names_take_that_torque(torque):
    """A method that takes no torque names the ones that do take *this* torque: a Python function is
    not one for the compiled-only rk4 and rk8, which it used to name."""
    body = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="cannot take a torque; use one of: ") as info:
        tumble.simulate(body, [0.1, 1.0, 0.0], t_end=0.2, samples=3, method="exact", torque=torque)
    named = str(info.value).split("use one of: ")[1].split(", ")
    assert ("rk8" in named) == isinstance(torque, tumble.ConstantTorque) and named[0] == "auto (the default)"
    named[0] = "auto"  # the default, named first (a walkthrough: the list left it out)
    for method in named:  # each one runs it
        traj = tumble.simulate(body, [0.1, 1.0, 0.0], t_end=0.2, samples=3, method=method, torque=torque)
        assert traj.method == method or method == "auto" and traj.auto


def _walkthrough_mistakes():
    """Slips a Python user made in a walkthrough (issue 40), each of which raised from deep inside."""
    import numpy as np

    from tumble.analysis.fit import fit_recording
    from tumble.dynamics.estimation.mekf import MEKF
    from tumble.io.export import write_npz

    run = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=1.0, samples=5)
    mekf = MEKF.start([0.0, 0.0, 0.0, 1.0], attitude_sigma=0.1, bias_sigma=0.01, gyro_noise=1e-4, bias_walk=1e-6)
    return [
        (lambda: write_npz("run.npz", run), TypeError, r"^traj = 'run.npz' is not a Trajectory: write_npz\(traj, path\)"),
        (lambda: mekf.propagate([0.0, 0.1], 1.0), ValueError, r"^gyro = \[0.0, 0.1\] must be the gyroscope's rates"),
        (lambda: tumble.Body(tumble.t_handle().parts[0]), ValueError, r"^parts = Rod\(.*must be a list of parts"),
        (lambda: fit_recording(np.arange(100) * 0.01, np.zeros((100, 3)), events=[1, 2, 3]), ValueError,
         r"^events\[0\] = 1: each event is a \(name, time\) pair"),
    ]


@pytest.mark.parametrize("case", range(4))
def test_a_python_slip_is_named_where_it_was_made(case):
    call, error, said = _walkthrough_mistakes()[case]
    with pytest.raises(error, match=said):
        call()


def test_a_control_page_says_what_it_shows(tmp_path, capsys):
    """`tumble view` of the magnetorquer-only detumble said "closed loop: wheels, commanded torque": it
    names what the run has."""
    from importlib import resources

    scenario = resources.files("tumble") / "examples" / "control" / "detumble.toml"
    assert main(["view", str(scenario), "--out", str(tmp_path / "d.html")]) == 0
    line = capsys.readouterr().out
    assert "closed loop: dipole, live mode off" in line and "wheels" not in line


def test_tumble_plot_names_the_control_scenario_it_refuses_by_its_path(tmp_path, capsys):
    from importlib import resources

    scenario = str(resources.files("tumble") / "examples" / "control" / "point.toml")
    assert main(["plot", scenario, "--out", str(tmp_path / "p")]) == 2
    assert capsys.readouterr().err == (f"tumble: error: {scenario} is a control scenario ([control]); 'tumble plot' does "
                                       f"not take it yet: use 'tumble simulate {scenario} --out DIR'\n")


def test_a_detumble_that_starts_below_its_threshold_says_so(tmp_path, capsys):
    """A threshold of 0.5 (deg/s meant, read as rad/s) "detumbled" a 0.17 rad/s tumble at t = 0 s without
    a word: the line says the run started below it."""
    path = tmp_path / "d.toml"
    path.write_text('body = { name = "b", parts = [{ kind = "box", mass = 4.0, size = [0.1, 0.2, 0.3] }] }\n'
                    "initial = { omega = [0.1, 0.1, 0.1] }\nsimulation = { t_end = 2.0 }\n"
                    "orbit = { altitude = 500e3, inclination = 1.7 }\nactuators = { magnetorquers = { max_dipole = 0.2 } }\n"
                    "[control]\nkind = \"bdot\"\nperiod = 1.0\nthreshold = 0.5\n")
    assert main(["simulate", str(path), "--out", str(tmp_path / "out")]) == 0
    assert "below 0.5 rad/s from t = 0 s (it started below the threshold: nothing was detumbled)" in capsys.readouterr().out


def test_wheels_turned_past_their_limit_by_the_body_are_said_to_be(tmp_path, capsys):
    """A tumble of 20 rad/s (deg/s meant) turned the wheels of examples/control/point.toml to 632-686 rad/s
    against max_speed = 630, with no word (the speeds are relative to the tumbling body; the motors give no
    outward torque past the limit). The line says so, naming the speed and the limit."""
    import json
    from importlib import resources

    text = (resources.files("tumble") / "examples" / "control" / "point.toml").read_text()
    assert "omega = [0.01, -0.01, 0.01]" in text and "t_end = 300.0" in text
    path = tmp_path / "fast.toml"
    path.write_text(text.replace("omega = [0.01, -0.01, 0.01]", "omega = [20.0, -20.0, 20.0]")
                    .replace("t_end = 300.0", "t_end = 30.0"))
    assert main(["simulate", str(path), "--out", str(tmp_path / "out")]) == 0
    top = json.loads((tmp_path / "out" / "summary.json").read_text())["max_wheel_speed"]
    assert top > 630.0
    assert f"wheels up to {top:.6g} rad/s, past their 630 rad/s limit (the body's own turning" in capsys.readouterr().out
    # started there (speed0 past max_speed, issue 27's case): the line says the input put them there
    path.write_text(path.read_text().replace("[actuators.wheels]", "[actuators.wheels]\nspeed0 = [700.0, 0.0, 0.0]", 1))
    assert main(["simulate", str(path), "--out", str(tmp_path / "out2")]) == 0
    assert "wheels started at up to 700 rad/s, past their 630 rad/s limit (speed0;" in capsys.readouterr().out
