"""A controller whose period is not shorter than the run acts once and leaves two samples: a
likely unit slip (a period in ms written as s), said in one warning (one line from a command)."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

import tumble
from tumble.cli import main
from tumble.dynamics.control.bdot import BDot
from tumble.dynamics.control.controlled import simulate_controlled
from tumble.dynamics.control.sampled import OneStepWarning
from tumble.dynamics.environment.magnetic import UniformField
from tumble.dynamics.models.actuators import Magnetorquers

I = np.array([0.03, 0.04, 0.05])
FIELD = UniformField((2e-5, 0.0, 0.0))


def _run(period, t_end=10.0):
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        run = simulate_controlled(I, [0.1, 0.2, 0.3], t_end=t_end, controller=BDot(gain=1e-3, period=period),
                                  magnetorquers=Magnetorquers(0.2), field=FIELD)
    return run, [w for w in seen if issubclass(w.category, OneStepWarning)]


@pytest.mark.parametrize("period", [10.0, 500.0])
def test_a_period_as_long_as_the_run_warns(period):
    run, seen = _run(period)
    assert len(run.t) == 2 and len(seen) == 1 and seen[0].filename == __file__
    assert f"controller.period = {period:g} s is not shorter than t_end = 10 s" in str(seen[0].message)


def test_a_shorter_period_says_nothing():
    run, seen = _run(9.0)
    assert len(run.t) == 3 and not seen


def test_the_command_line_says_it_in_one_line(tmp_path, capsys):
    """The shipped detumble file with its period written 1e6 times too long."""
    source = Path(tumble.__file__).parent / "examples" / "control" / "detumble.toml"
    text = source.read_text(encoding="utf-8")
    assert text.count("\nperiod = 1.0 ") == 1
    path = tmp_path / "slow.toml"
    path.write_text(text.replace("\nperiod = 1.0 ", "\nperiod = 1e6 "), encoding="utf-8")
    assert main(["simulate", str(path), "--out", str(tmp_path / "out")]) == 0
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if "is not shorter than t_end" in line]
    assert len(lines) == 1 and lines[0].startswith("warning: controller.period = 1e+06 s"), err
