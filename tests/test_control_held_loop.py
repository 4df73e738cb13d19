"""MRP feedback held between control steps: the sampled-data loop's stability (tumble.dynamics.control.sampled).

A walkthrough's 3U CubeSat held for 2.5 s tumbled at 0.38 rad/s without a word, and an integral
gain past the stated bound Ki < P / I pointed 3 rad off (issue 40). The check's bound is held to
the closed loop itself: a little inside it the pointing settles, a little outside it diverges.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tumble.dynamics import MRPFeedback, simulate_controlled
from tumble.dynamics.control.sampled import UnstableLoopWarning, check_held_loop, held_loop_radius
from tumble.dynamics.models.actuators import ReactionWheels
from tumble.io.scenario import load_scenario
from pathlib import Path

MOMENTS = np.array([4.0 * 0.02 / 12, 4.0 * 0.1256 / 12, 4.0 * 0.1256 / 12])  # the 3U CubeSat of point.toml, kg m^2
WHEELS = ReactionWheels(np.eye(3), inertia=2e-5, max_torque=1.0, max_speed=np.inf)  # no limit: the loop alone
K, P = 1.1e-3, 6e-3
CONTROL = Path(__file__).resolve().parents[1] / "examples" / "control"


def _longest_stable(Ki=0.0):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_held_loop(MOMENTS, K, P, 2.5, Ki)
    return float(str(caught[0].message).rsplit("period is ", 1)[1].split(" s")[0])


def _final_angle(period, Ki=0.0, t_end=300.0, axis=0):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnstableLoopWarning)
        c = MRPFeedback(K=K, P=P, period=period, moments=MOMENTS, wheels=WHEELS, Ki=Ki, gyroscopic=False)
    off = np.eye(3)[axis]
    run = simulate_controlled(MOMENTS, 1e-3 * off, t_end=t_end, controller=c, wheels=WHEELS,
                              attitude0=Rotation.from_rotvec(0.01 * off))
    return float(run.pointing_error(Rotation.identity())[-1])


def test_the_bound_is_the_closed_loops():
    """About the long axis the rate loop overshoots past P T / I = 2 (2.22 s): at 0.95 of the bound the
    loop settles from 10 mrad, at 1.05 of it the error grows."""
    bound = _longest_stable()
    assert 2 * MOMENTS[0] / P * 0.98 < bound < 2 * MOMENTS[0] / P  # the rate loop's, less a little for K
    assert _final_angle(0.95 * bound) < 1e-4
    assert _final_angle(1.05 * bound) > 0.05
    assert held_loop_radius(MOMENTS, K, P, 0.95 * bound).max() < 1 < held_loop_radius(MOMENTS, K, P, 1.05 * bound)[0]


def test_an_integral_gain_past_p_over_i_is_named():
    """Ki < P / I (Routh-Hurwitz of I s^3 + P s^2 + K s / 4 + K Ki / 4), tightest about the major axes: at
    0.5 s the loop with Ki at twice P / I3 diverges, and the warning names Ki and the bound; at half of it, stable."""
    limit = P / MOMENTS[2]
    with pytest.warns(UnstableLoopWarning, match=rf"^Ki = {2 * limit:g} 1/s: MRP feedback's integral term makes the "
                                                 rf"loop unstable about principal axis 2 .* it needs Ki < P / I = {limit:.3g} 1/s"):
        MRPFeedback(K=K, P=P, period=0.5, moments=MOMENTS, wheels=WHEELS, Ki=2 * limit)
    assert _final_angle(0.5, Ki=2 * limit, t_end=600.0, axis=2) > 0.05
    assert _final_angle(0.5, Ki=0.5 * limit, t_end=600.0, axis=2) < 1e-3
    assert held_loop_radius(MOMENTS, K, P, 0.05, 0.5 * limit).max() < 1


def test_an_integral_gain_and_a_period_both_past_their_bounds_are_both_named():
    """Ki = 5 and period = 100 s: the warning named Ki alone, and the run with Ki fixed would still have
    diverged (a walkthrough of docs/control.md, 2026-12-02). The period is judged without the integral
    term too, and its bound is the one the period alone gives."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_held_loop(MOMENTS, K, P, 100.0, 5.0)
    message = str(caught[0].message)
    assert len(caught) == 1 and message.startswith("Ki = 5 1/s: MRP feedback's integral term makes the loop unstable")
    assert message.endswith(f"; and period = 100 s is unstable even without it about principal axis 1 (the longest "
                            f"stable period without it is {_longest_stable():.3g} s)")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_held_loop(MOMENTS, K, P, 0.5, 5.0)  # a stable period: Ki alone is named
    assert "and period" not in str(caught[0].message)


def test_the_shipped_examples_are_stable_and_the_command_says_it_in_one_line(tmp_path, capsys):
    from tumble.cli import main

    with warnings.catch_warnings():
        warnings.simplefilter("error", UnstableLoopWarning)
        for path in sorted(CONTROL.glob("*.toml")):
            scenario = load_scenario(path)
            scenario.controller()
    text = (CONTROL / "point.toml").read_text().replace("period = 0.5 ", "period = 2.5 ")
    (tmp_path / "slow.toml").write_text(text)
    assert main(["simulate", str(tmp_path / "slow.toml"), "--t-end", "10", "--out", str(tmp_path / "run")]) == 0
    err = capsys.readouterr().err
    assert err.startswith("warning: period = 2.5 s: MRP feedback held that long is unstable about principal axis 1")
    assert err.count("\n") == 1


def test_a_proportional_gain_in_mn_m_written_as_n_m_is_named_by_its_own_ratio():
    """K = 1.1 (1.1 mN m written as N m) held 0.5 s: the warning said "a pole of magnitude 2.39 > 1: P T / I = 0.45",
    the cause K not in it (a walkthrough of docs/control.md, 2026-12-03). It gives K T^2 / I beside P T / I."""
    with pytest.warns(UnstableLoopWarning, match=r"a pole of magnitude \d\.\d+ > 1: P T / I = 0\.\d+, K T\^2 / I = "
                                                 r"(\d+\.?\d*)\); the longest stable period is") as caught:
        check_held_loop(MOMENTS, 1.1, P, 0.5)
    ratio = float(str(caught[0].message).split("K T^2 / I = ")[1].split(")")[0])
    assert ratio == pytest.approx(1.1 * 0.5**2 / MOMENTS[0], rel=1e-2)
