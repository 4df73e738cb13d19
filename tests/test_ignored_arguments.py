"""An argument the method does not read (``rtol``/``atol`` given to a splitting, ``rtol`` beside a
``step`` or ``atol`` to ``rk4``/``rk8``, ``step`` to an adaptive method or to ``"auto"``) has no
effect: ``simulate`` says so (IgnoredArgumentWarning, one ``warning:`` line from the command line)
and the run is the one without it, to the bit."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import tumble
from tumble.cli import main
from tumble.dynamics.methods.arguments import IgnoredArgumentWarning

BODY = tumble.MassProperties.from_moments([1.0, 2.0, 3.0])
TORQUE = tumble.ConstantTorque((0.01, 0.02, -0.01))
W0 = [0.1, 1.0, 0.1]


def _run(**kw):
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        traj = tumble.simulate(BODY, W0, t_end=2.0, samples=21, **kw)
    return traj, [w for w in seen if issubclass(w.category, IgnoredArgumentWarning)]


@pytest.mark.parametrize(("kw", "plain", "named"), [
    ({"method": "rk4", "torque": TORQUE, "rtol": 1e-12, "step": 0.01}, {"method": "rk4", "torque": TORQUE, "step": 0.01},
     "rtol = 1e-12 has no effect with method = 'rk4', which steps by step (s) and takes from rtol alone"),
    ({"method": "rk8", "torque": TORQUE, "atol": 1e-9}, {"method": "rk8", "torque": TORQUE}, "atol = 1e-09 has"),
    ({"method": "rk8", "torque": TORQUE, "step": 0.05, "rtol": 1e-5, "atol": 1e-9},
     {"method": "rk8", "torque": TORQUE, "step": 0.05}, "rtol = 1e-05 and atol = 1e-09 have"),
    ({"method": "geometric", "atol": 1e-9}, {"method": "geometric"}, "atol = 1e-09 has"),
    ({"method": "dop853", "torque": TORQUE, "step": 0.1}, {"method": "dop853", "torque": TORQUE}, "step = 0.1"),
    ({"torque": TORQUE, "step": 0.1}, {"torque": TORQUE}, "method = 'auto'"),
    ({"step": 0.1}, {}, "method = 'auto'"),
])
def test_what_a_method_does_not_read_warns_and_changes_nothing(kw, plain, named):
    traj, seen = _run(**kw)
    assert len(seen) == 1 and named in str(seen[0].message), [str(w.message) for w in seen]
    assert seen[0].filename == __file__   # the user's line, not tumble's
    ref, quiet = _run(**plain)
    assert not quiet and traj.method == ref.method
    assert np.array_equal(traj.omega, ref.omega) and np.array_equal(traj.quat, ref.quat)


@pytest.mark.parametrize("kw", [
    {"method": "rk8", "torque": TORQUE, "step": 0.05}, {"method": "dop853", "torque": TORQUE, "rtol": 1e-8},
    {"method": "rk4", "torque": TORQUE, "rtol": 1e-6},   # the step that meets it (test_simulate_auto.py)
    {"torque": TORQUE, "rtol": 1e-8, "atol": 1e-9}, {"method": "rk45", "torque": TORQUE, "rtol": 1e-8},
    {"method": "exact", "rtol": 1e-6, "step": 0.1},   # exact meets any tolerance and takes no steps
])
def test_what_a_method_reads_is_taken_without_a_word(kw):
    assert _run(**kw)[1] == []


def test_the_command_line_says_it_in_one_line(tmp_path, capsys):
    scenario = tmp_path / "s.toml"
    scenario.write_text('body = "t-handle"\n[initial]\nomega = [0.1, 10.0, 0.1]\n'
                        '[simulation]\nt_end = 1.0\nmethod = "rk8"\nstep = 0.01\nrtol = 1e-12\n', encoding="utf-8")
    assert main(["simulate", str(scenario), "--out", str(tmp_path / "out")]) == 0
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if "rtol = 1e-12 has no effect" in line]
    assert len(lines) == 1 and lines[0].startswith("warning: ") and "Traceback" not in err, err


def test_a_batch_reads_what_a_lone_run_reads_and_says_the_rest_once():
    """simulate_batch's rk8 given an rtol takes each body's step that meets it, as simulate does (each
    row the lone run's to round-off: the batch steps bodies in vector lanes), not the default step;
    what a method does not read warns once for the batch, also where it loops over simulate."""
    I = np.array([[1.0, 2.0, 3.0], [0.125, 0.3125, 0.4375], [10.0, 12.0, 15.0]])
    w0 = np.array([[0.1, 1.0, 0.1], [0.1, 10.0, 0.1], [0.05, 1.0, 0.05]])
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        batch = tumble.simulate_batch(I, w0, t_end=2.0, samples=21, method="rk8", torque=TORQUE, rtol=1e-6)
        plain = tumble.simulate_batch(I, w0, t_end=2.0, samples=21, method="rk8", torque=TORQUE)
    assert not [w for w in seen if issubclass(w.category, IgnoredArgumentWarning)]
    for i in range(len(I)):
        lone = tumble.simulate(tumble.MassProperties.from_moments(I[i]), w0[i], t_end=2.0, samples=21, method="rk8",
                               torque=TORQUE, rtol=1e-6)
        assert np.max(np.abs(batch.omega[i] - lone.omega)) <= 1e-12 * np.max(np.abs(lone.omega))
    assert np.max(np.abs(batch.omega[1] - plain.omega[1])) > 1e-10   # not the default step
    for torque in (TORQUE, lambda t, w, R: np.array([0.01, 0.02, -0.01])):   # the engine; the loop of simulate
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            tumble.simulate_batch(I, w0, t_end=2.0, samples=21, method="dop853", torque=torque, step=0.1)
        said = [str(w.message) for w in seen if issubclass(w.category, IgnoredArgumentWarning)]
        assert said == ["step = 0.1 has no effect with method = 'dop853', which chooses its steps to meet rtol: a "
                        "fixed-step method (rk4, rk8, geometric...) takes step"], said
    with pytest.raises(ValueError, match=r"^rtol = 1e-13 is below what rk8's fixed steps meet"):
        tumble.simulate_batch(I, w0, t_end=2.0, samples=21, method="rk8", torque=TORQUE, rtol=1e-13)
