"""Scenario files and `tumble simulate`: every example runs; bad files write nothing."""

from __future__ import annotations

import csv
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import tumble
from tumble.cli import main
from tumble.commands import run_scenario
from tumble.io.export import CSV_BUDGET_COLUMNS, CSV_COLUMNS
from tumble.io.scenario import load_scenario

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SCENARIOS = sorted(EXAMPLES.glob("*.toml"))  # scenarios; body files live in examples/bodies/


def test_there_are_example_scenarios():
    assert len(SCENARIOS) >= 4


@pytest.mark.parametrize("path", SCENARIOS, ids=lambda p: p.stem)
def test_every_example_scenario_runs(path, tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["simulate", str(path), "--out", str(out), "--json"]) == 0
    printed = capsys.readouterr()
    summary = json.loads(printed.out)
    assert "warning:" not in printed.err  # its omega.png shows its motion: no aliased samples (tumble.viz.sample_phase)
    assert summary == json.loads((out / "summary.json").read_text())
    for key in ("principal_moments", "method", "drift", "stability"):
        assert key in summary
    assert set(summary["drift"]) == {"energy", "L_norm", "L_world"}
    assert set(summary["stability"]) >= {"axis", "predicted", "flips", "flip_period"}
    with open(out / "trajectory.csv") as fh:
        rows = list(csv.reader(fh))
    assert tuple(rows[0][: len(CSV_COLUMNS)]) == CSV_COLUMNS
    assert set(rows[0][len(CSV_COLUMNS):]) <= set(CSV_BUDGET_COLUMNS.values())  # damper, rotors
    assert len(rows) - 1 == summary["samples"]
    data = np.load(out / "trajectory.npz")
    np.testing.assert_allclose(data["omega"][:, 0], [float(r[1]) for r in rows[1:]], rtol=1e-15)
    assert (out / "omega.png").stat().st_size > 0


def test_csv_round_trip_is_exact(tmp_path):
    scenario = load_scenario(EXAMPLES / "seed_flip.toml")
    traj = run_scenario(scenario)
    from tumble.io.export import write_csv

    write_csv(traj, tmp_path / "t.csv")
    table = np.loadtxt(tmp_path / "t.csv", delimiter=",", skiprows=1)
    np.testing.assert_array_equal(table[:, 1:4], traj.omega)
    np.testing.assert_array_equal(table[:, 4:8], traj.quat)
    # L_world is constant in a torque-free run
    np.testing.assert_allclose(table[:, 8:11], table[[0] * len(table), 8:11], rtol=0, atol=1e-10 * np.linalg.norm(table[0, 8:11]))


def test_seed_flip_scenario_matches_the_numbers_the_tests_check(tmp_path, capsys):
    main(["simulate", str(EXAMPLES / "seed_flip.toml"), "--out", str(tmp_path), "--json"])
    s = json.loads(capsys.readouterr().out)
    assert s["stability"]["axis"] == 2 and s["stability"]["predicted"] == "unstable"
    assert s["stability"]["flips"] == 11
    assert s["stability"]["flip_period"] == pytest.approx(s["stability"]["flip_period_exact"], rel=1e-4)
    np.testing.assert_allclose(s["principal_moments"], [0.125, 0.3125, 0.4375])


def test_inline_body_and_torque():
    scenario = load_scenario(EXAMPLES / "torqued_box.toml")
    traj = run_scenario(scenario)
    I3 = scenario.body.principal_moments[2]
    np.testing.assert_allclose(traj.omega[:, 2], 0.01 * traj.t / I3, rtol=1e-9)


BODY = 'body = "t-handle"\n'
INITIAL = '[initial]\nomega = [0.1, 1.0, 0.1]\n'

BAD = [
    ("", "the file is empty"),
    ("body = \n", "not valid TOML"),
    (INITIAL, "missing key 'body'"),
    ('body = "cube"\n' + INITIAL, "body = 'cube' is neither a preset"),
    ('body = "bodies/none.toml"\n' + INITIAL, r"body = 'bodies/none.toml' is neither a preset .* nor a file: no .*/bodies/none\.toml$"),
    ("body = 3\n" + INITIAL, "body = 3 must be a preset name"),
    (BODY, "initial: missing key 'omega'"),
    (BODY + "[initial]\nomega = [1, 2]\n", r"initial.omega = \[1, 2\] must be a list of 3 numbers"),
    (BODY + "[initial]\nomega = [1, nan, 2]\n", r"initial.omega\[1\] = nan must be a finite number"),
    (BODY + "[initial]\nomega = [1, 2, 3]\nframe = 'world'\n", r"initial.frame = 'world' is not allowed"),
    (BODY + INITIAL + "[simulation]\nt_end = -1.0\n", r"simulation.t_end = -1.0 must be a positive"),
    (BODY + INITIAL + "[simulation]\nt_end = inf\n", r"simulation.t_end = inf must be a finite"),
    (BODY + INITIAL + "[simulation]\nsamples = 1\n", r"simulation.samples = 1 must be a whole number"),
    (BODY + INITIAL + "[simulation]\nsamples = 1e12\n", r"simulation.samples = 1000000000000.0 must be a whole number"),
    (BODY + INITIAL + "[simulation]\nmethod = 'magic'\n", r"simulation.method = 'magic' is unknown"),
    (BODY + INITIAL + "[simulation]\nduration = 3\n", r"simulation: unknown key 'duration'"),
    (BODY + INITIAL + "[simulation]\nrtol = 0\n", r"simulation.rtol = 0 must be a positive"),
    (BODY + INITIAL + "[simulation]\nmethod = 'geometric'\nstep = -1.0\n", r"simulation.step = -1.0 must be a positive"),
    (BODY + INITIAL + "[torque]\nframe = 'body'\n", r"torque: missing key 'vector'"),
    (BODY + INITIAL + "[torque]\nvector = [0, 0, 1]\nframe = 'lab'\n", r"torque: torque frame = 'lab' is not allowed"),
    (BODY + INITIAL + "[simulation]\nmethod = 'seed'\n[torque]\nvector = [0, 0, 1]\n", r"simulation.method = 'seed' cannot take a torque"),
    (BODY + INITIAL + "[simulation]\nmethod = 'exact'\n[torque]\nvector = [0, 0, 1]\n", r"simulation.method = 'exact' cannot take a torque; use one of: auto \(the default\), dop853, rk45, geometric"),
    (BODY + INITIAL + "[extra]\n", r"unknown key 'extra'"),
    ("[body]\n[[body.parts]]\nkind = 'rod'\nmass = 1\nlength = 1\n" + INITIAL, r"zero moment"),
    ("[body]\n[[body.parts]]\nkind = 'rod'\nmass = -1\nlength = 1\n" + INITIAL, r"body.parts\[0\] \(rod\): mass = -1"),
]


@pytest.mark.parametrize(("text", "pattern"), BAD)
def test_bad_scenarios_get_one_line_exit_2_and_write_nothing(tmp_path, capsys, text, pattern):
    path = tmp_path / "s.toml"
    path.write_text(text)
    out = tmp_path / "out"
    code = main(["simulate", str(path), "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2
    assert err.count("\n") == 1 and "Traceback" not in err
    import re

    assert re.search(pattern, err), err
    assert not out.exists()


def test_failure_midway_leaves_no_half_written_file(tmp_path, monkeypatch, capsys):
    """A crash while writing the plot leaves nothing: no folder, no temporary files beside it."""
    import tumble.viz

    def boom(*args, **kwargs):
        raise RuntimeError("disk on fire")

    monkeypatch.setattr(tumble.viz, "figure_omega", boom)
    out = tmp_path / "out"
    code = main(["simulate", str(EXAMPLES / "seed_flip.toml"), "--out", str(out)])
    assert code == 1
    assert "computation failed" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_simulate_help_has_an_example():
    proc = subprocess.run([sys.executable, "-m", "tumble", "simulate", "--help"], capture_output=True, text=True)
    assert proc.returncode == 0 and "Examples: tumble simulate" in proc.stdout


def test_both_samples_and_dt_in_a_file_name_the_files_keys(tmp_path):
    """'give samples or dt, not both' named neither the table nor the file's keys (a walkthrough, 2026-12-03)."""
    from tumble.io.scenario import load_scenario

    path = tmp_path / "both.toml"
    path.write_text('[body]\npreset = "t-handle"\n[initial]\nomega = [0.1, 10, 0.1]\n'
                    "[simulation]\nt_end = 1.0\nsamples = 10\ndt = 0.1\n")
    with pytest.raises(ValueError, match=r"both.toml: give simulation.samples or simulation.dt, not both$"):
        load_scenario(path)
