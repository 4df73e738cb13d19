"""The budgets of a torqued run against its torque (analysis.torque_summary.torque_budget, and the line and
summary.json of ``tumble simulate``): closed where the samples resolve the torque, open for a torque
that is not the run's, and flagged where the samples are too coarse to tell."""

from __future__ import annotations

import json

import numpy as np
import pytest

import tumble
from tumble.analysis.torque_summary import BUDGET_TURN, torque_budget
from tumble.cli import main
from tumble.dynamics.models.torques import as_torque, bind_to_body

BODY = tumble.t_handle()
SUM = [tumble.GravityGradient(orbit_period=60.0, mu=1.0), tumble.ConstantTorque((0.0, 0.0, 2e-3)),
       tumble.ConstantTorque((1e-3, 0.0, 0.0), "world")]


def _run(samples):
    return tumble.simulate(BODY, [0.1, 2.0, 0.05], t_end=30.0, samples=samples, torque=SUM, rtol=1e-12)


def test_the_budgets_of_a_sum_close_to_the_quadratures_accuracy():
    run = _run(3001)
    budget = torque_budget(run, bind_to_body(as_torque(SUM), BODY))
    assert budget["resolved"] and budget["turn_per_sample"] < BUDGET_TURN
    for name in ("momentum", "energy"):
        b = budget[name]
        assert b["change"] > 1e-3  # the torques moved L and did work: not 0 = 0
        assert b["gap"] < 1e-8 * b["change"] and b["gap"] < 3 * b["quadrature"] + 1e-14 * b["change"], (name, b)


def test_a_torque_that_is_not_the_runs_leaves_the_budget_open():
    """The check can fail: the same run held against a torque 1 % stronger is off by ~1 % of the change."""
    run = _run(3001)
    wrong = bind_to_body(as_torque([*SUM, tumble.ConstantTorque((0.0, 0.0, 2e-5))]), BODY)
    b = torque_budget(run, wrong)["momentum"]
    assert b["gap"] > 1e3 * b["quadrature"] and b["gap"] > 1e-3 * b["change"]


def test_coarse_samples_are_flagged_not_judged():
    """30 samples of a 2 rad/s spin over 30 s: 2 rad between samples, more than the quadrature resolves."""
    budget = torque_budget(_run(30), bind_to_body(as_torque(SUM), BODY))
    assert not budget["resolved"] and budget["turn_per_sample"] > BUDGET_TURN


def test_a_body_with_rotors_has_no_energy_budget_here():
    """The motors' work is the rotors' budget (summary "rotors"); L_world, body and rotors together, is checked."""
    wheel = tumble.Rotor(mass=0.05, radius=0.1, length=0.01, axis=(1.0, 0.0, 0.0), center=(0.0, 0.0, 0.5),
                         spin_rate=100.0)
    body = tumble.Body([*BODY.parts, wheel])
    push = tumble.ConstantTorque((0.0, 0.0, 1e-3), "world")
    run = tumble.simulate(body, [0.1, 2.0, 0.05], t_end=10.0, samples=2001, torque=push, rtol=1e-12)
    budget = torque_budget(run, push)
    assert "energy" not in budget and budget["momentum"]["change"] == pytest.approx(1e-2, rel=1e-12)
    assert budget["momentum"]["gap"] < 1e-9 * budget["momentum"]["change"]


@pytest.mark.parametrize(("samples", "words"), [
    (3001, "torque acted: L_world followed the impulse to "),
    (30, "torque acted (the samples, up to 2"),
])
def test_the_simulate_line_and_summary_say_it(tmp_path, capsys, samples, words):
    scenario = tmp_path / "s.toml"
    scenario.write_text('body = "t-handle"\n[initial]\nomega = [0.1, 2.0, 0.05]\n'
                        f"[simulation]\nt_end = 30.0\nsamples = {samples}\nrtol = 1e-12\n"
                        '[[torque]]\nkind = "gravity_gradient"\norbit_period = 60.0\nmu = 1.0\n'
                        "[[torque]]\nvector = [0.0, 0.0, 2e-3]\n"
                        '[[torque]]\nvector = [1e-3, 0.0, 0.0]\nframe = "world"\n')
    assert main(["simulate", str(scenario), "--out", str(tmp_path / "run")]) == 0
    line = capsys.readouterr().out
    assert words in line, line
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    budget = summary["torque_budget"]
    assert set(budget) == {"momentum", "energy", "turn_per_sample", "resolved"}
    assert budget["resolved"] == (samples == 3001)
    if budget["resolved"]:
        assert budget["momentum"]["gap"] < 1e-8 * budget["momentum"]["change"]
    # the gravity gradient among other torques: its orbit's angles, but no Jacobi integral (not conserved here)
    assert summary["gravity_gradient"]["jacobi_drift"] is None and summary["gravity_gradient"]["orbits"] == 0.5
    assert "0.5 orbits, largest angle from the orbiting frame" in line and "Jacobi" not in line


def test_a_sum_with_the_gravity_gradient_draws_the_orbits_angles():
    from tumble.viz.spacecraft import spacecraft_figures

    run = _run(31)
    assert [name for name, _ in spacecraft_figures(run, SUM)] == ["orbit_angles"]
    assert [name for name, _ in spacecraft_figures(run, SUM[1:])] == []


def test_fewer_than_three_samples_have_no_budget_not_an_empty_one():
    """One sample (times = [5.0]) has no change to check: None, and the line does not say it closed."""
    push = tumble.ConstantTorque((0.0, 0.0, 0.01))
    run = tumble.simulate(BODY, [0.1, 2.0, 0.1], times=[5.0], torque=push)
    assert len(run) == 1 and torque_budget(run, push) is None
