"""Whole recordings II (issue #39): the toss and nothing else, a verdict per flight, the same
recording given twice and absurd accelerometer values refused.

The recordings are :func:`~tumble.analysis.fit.synthetic.synthetic_recording`'s; the endings
``"turn"`` (the phone turned in the fingers after the catch, a motion a torque-free model with
drag follows) and ``"table"`` (landed flat and spun on a table) are
:mod:`tumble.analysis.fit.endings`'s. The seeds of the post-catch tests are those on which the
finder before issue #39 fitted the stretch after the catch as a flight (``AFTER_IMPACT = 0``
restores that finder).
"""

from __future__ import annotations

import os
import shutil
import warnings

import numpy as np
import pytest

import tumble.analysis.fit.flights as flights_module
from tumble.analysis.fit import InadequateFitWarning, fit_recording
from tumble.analysis.fit.endings import spun_on_table, turned_in_hand
from tumble.analysis.fit.synthetic import TOSS_BODIES, synthetic_recording
from tumble.cli import main


def _iou(a, b, start, end):
    return max(0.0, min(b, end) - max(a, start)) / (max(b, end) - min(a, start))


def _fit(rec):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InadequateFitWarning)
        return fit_recording(rec.t, rec.omega, events=rec.events)


@pytest.mark.parametrize(("seed", "body"), [(3000, "racquet"), (3040, "racquet"), (3001, "phone"), (3021, "racquet")])
def test_one_toss_a_file_its_answer_is_the_tosss_own(seed, body):
    """A phone or racquet caught and turned on in the fingers: the stretch after the catch
    follows a free motion (of another, symmetric body) and the finder before #39 pooled it with
    the toss (or kept it alone); now it is skipped as after an impact, and the file's answer is
    the toss's own fit, equal to it exactly.

    Each seed holds in 5 of 5 runs whose exact free motion was changed by 1e-13 (relative):
    seed 3005, used before for both bodies, held in 3 of 5 (its stretch after the catch was cut
    too short for a flight, or not followed, where the last digits fell otherwise; issue 38's note)."""
    rate = float(np.random.default_rng(seed).choice([100, 200, 400]))
    rec = synthetic_recording(seed, body=body, tosses=1, ending="turn", rate=rate)
    fit = _fit(rec)
    (release, impact), = rec.flights
    used = [toss for toss in fit.tosses if toss.status == "ok"]
    assert len(used) == 1 and _iou(release, impact, used[0].start, used[0].end) >= 0.5
    np.testing.assert_array_equal(fit.pooled.ratios, used[0].fit.ratios)
    after = [toss for toss in fit.tosses if toss.start > used[0].end]
    assert after and after[0].reason.startswith(flights_module.AFTER_IMPACT_REASON)
    assert after[0].start - used[0].end < flights_module.AFTER_IMPACT


def test_the_stretch_after_the_catch_was_taken_for_a_flight_before(monkeypatch):
    """The same file with the rule turned off (the finder of #29): the stretch after the catch is
    fitted "ok" beside the tosses or instead of one, and the pooled answer's caveat says that it lies outside its
    flights' own values exactly when it does (each flight that states its own ratios more than
    2 of its standard uncertainties away, all on one side), naming one flight.

    Where the pooled answer lands turns on the last digits of the drag model: under random 1e-13
    (relative) perturbations of it, seed 28's pooled answer lay outside in 1 of 6 runs, with the
    fits' old drag kernel as with the engine's (issue 38's note); so the caveat is checked
    against the flights' values whichever way it lands, and on values set outside in
    :func:`test_a_pooled_answer_outside_its_flights_values_names_the_flight_that_pulls_it`."""
    monkeypatch.setattr(flights_module, "AFTER_IMPACT", 0.0)
    rec = synthetic_recording(28, body="racquet", tosses=2, ending="turn")
    fit = _fit(rec)
    used = [toss for toss in fit.tosses if toss.status == "ok"]
    own = [toss for toss in used if not toss.reason]  # stating their own ratios
    caveat = fit.pooled.caveat
    values = np.array([toss.fit.ratios for toss in own]).reshape(-1, 2)
    std = np.array([toss.fit.ratios_std for toss in own]).reshape(-1, 2)
    z = (fit.pooled.ratios - values) / std
    outside = len(own) >= 2 and bool(np.any(np.all(z > 2.0, axis=0) | np.all(z < -2.0, axis=0)))
    assert ("lies outside its flights' own values" in caveat) == outside, (caveat, z)
    if outside:
        assert len([toss for toss in used if f"the flight at {toss.start:.2f}-" in caveat]) == 1


def test_a_pooled_answer_outside_its_flights_values_names_the_flight_that_pulls_it():
    """The caveat on its own (:func:`~tumble.analysis.fit.disagreement.outside_caveat`, the flights'
    weighted mean standing in for a joint fit): three fitted flights of one body, a pooled I1/I3
    set 3 of the flights' largest standard uncertainties beyond their largest value is said to lie
    outside and names one of them; 1.5 of them beyond, or the flights' mean, is not."""
    from types import SimpleNamespace

    from tumble.analysis.fit.disagreement import OUTSIDE_SIGMAS, outside_caveat as _outside
    from tumble.analysis.fit.summary import ratio_summary

    rec = synthetic_recording(4, tosses=3)
    used = [f for f in flights_module.find_flights(rec.t, rec.omega, events=rec.events) if f.status == "ok"]
    assert len(used) == 3 and not any(f.joinable for f in used)
    values = np.array([ratio_summary(f.solution)[0] for f in used])
    stds = np.array([ratio_summary(f.solution)[1] for f in used])

    def said(x: float) -> str:
        fit = SimpleNamespace(pooled=SimpleNamespace(ratios=np.array([x, values[:, 1].mean()])),
                              omega_models=[None] * len(used))
        return _outside(fit, used, [0, 1, 2], None, None, joint=False)

    far = values[:, 0].max() + 3.0 * stds[:, 0].max()
    caveat = said(far)
    assert caveat.startswith(f"the joint fit's I1/I3 = {far:.4f} lies outside its flights' own values "
                             f"({values[:, 0].min():.4f} to {values[:, 0].max():.4f}; each more than "
                             f"{OUTSIDE_SIGMAS:g} of its standard uncertainties away)"), caveat
    assert len([f for f in used if f"the flight at {f.start:.2f}-{f.end:.2f} s" in caveat]) == 1
    assert said(values[:, 0].max() + 1.5 * stds[:, 0].min()) == ""
    assert said(values[:, 0].mean()) == ""


def test_a_joint_fit_inside_its_flights_values_says_nothing():
    rec = synthetic_recording(11, tosses=3, flight=(0.6, 1.0))
    fit = _fit(rec)
    assert fit.tosses_used == 3 and "outside its flights" not in fit.pooled.caveat


def test_a_phone_spun_on_a_table_slows_at_the_tables_coulomb_friction():
    """Coulomb friction: a constant torque mu m g r, so the spin falls linearly, at 4 mu g / d
    for a plate (I3 = m d^2 / 12, r = d / 3), mu in 0.2-0.4; the rocking decays."""
    body = TOSS_BODIES["phone"]
    d = np.hypot(body.length, body.width)
    tau = np.arange(0.0, 1.0, 0.0025)
    for seed in range(8):
        w = spun_on_table(np.random.default_rng(seed), body, tau, 1.0, 14.0, np.zeros((len(tau), 3)))
        spinning = np.abs(w[:, 2]) > 0.5
        slope = np.polyfit(tau[spinning], np.abs(w[spinning, 2]), 1)[0]
        assert 4 * 0.2 * 9.81 / d - 1e-6 <= -slope <= 4 * 0.4 * 9.81 / d + 1e-6
        assert np.max(np.abs(w[tau > 0.5, :2])) < 0.01 * np.max(np.abs(w[tau < 0.05, :2]))


def test_a_phone_turned_in_the_fingers_cones_at_its_axial_rate_times_k():
    """The coning of a free symmetric body (Landau & Lifshitz sec. 33): once gripped, omega's
    direction keeps a constant angle to the axis (the directions lie on one circle: its plane's
    normal is the axis), and the spin only slows."""
    tau = np.arange(0.0, 0.8, 0.005)
    for seed in range(6):
        w = turned_in_hand(np.random.default_rng(seed), tau, 0.8, np.array([0.3, 12.0, 0.2]), 9.0, np.zeros((len(tau), 3)))
        held = (tau > 0.07) & (tau < 0.8 * 0.85)
        speed = np.linalg.norm(w[held], axis=1)
        u = w[held] / speed[:, None]
        axis = np.linalg.svd(u - u.mean(axis=0), full_matrices=False)[2][2]  # the circle's plane's normal
        cosines = np.abs(u @ axis)
        assert np.ptp(cosines) < 1e-6 and np.all(np.diff(speed) < 0)


@pytest.mark.parametrize("seed", [3, 4])
def test_a_table_after_the_landing_is_not_a_flight(seed):
    rec = synthetic_recording(seed, body="racquet", tosses=1, ending="table")
    fit = _fit(rec)
    for toss in fit.tosses:
        if toss.status == "ok":
            assert max(_iou(a, b, toss.start, toss.end) for a, b in rec.flights) >= 0.5


def test_a_flexing_racquets_file_of_25_tosses_exits_0(tmp_path, capsys):
    """Each flight judged on its own (its rigidity and adequacy by its own fit, the joint fit's
    residuals flight by flight): a file whose flights pass gives an answer, exit 0."""
    rec = synthetic_recording(101, body="racquet", tosses=25)
    path = tmp_path / "racquet.csv"
    path.write_text(rec.csv_text(), encoding="utf-8")
    assert main(["fit", str(path), "--out", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    assert " of 25 flights" in out or " of 26 flights" in out
    assert "skipped)" not in out  # a skip says why: "(1 skipped: too short)"
    fit = _fit(rec)
    assert fit.pooled.adequate and fit.pooled.adequacy.startswith(f"each of its {fit.tosses_used} flights described")
    assert np.all(np.abs(fit.pooled.ratios - rec.ratios) < 4 * fit.pooled.ratios_std)


def test_the_fit_line_says_in_brief_why_flights_were_skipped():
    """'3 of 4 flights (1 skipped)' left a user to open tosses.csv to learn that the fourth was a
    0.03 s fragment (seen 2026-12-02): the line gives each reason's head and its count."""
    from tumble.analysis.fit import RecordingFit, Toss

    tosses = (Toss(0.0, 1.0, 100, "ok", ""),
              Toss(2.0, 2.03, 3, "skipped", "too short (0.03 s, 3 samples; a flight needs 0.3 s and 30 samples)"),
              Toss(3.0, 4.0, 100, "skipped", "saturated: |omega| at the gyroscope's range for 12 samples"),
              Toss(5.0, 5.1, 10, "skipped", "too short (0.10 s of free flight, 10 samples)"))
    fit = RecordingFit(tosses, None, 1.0, 1, np.zeros(0), np.zeros((0, 3)))
    assert fit.flights_used() == "1 of 4 flights (3 skipped: 2 too short, 1 saturated)"  # the repr's and the command's
    alike = RecordingFit(tosses[:2] + tosses[3:], None, 1.0, 1, np.zeros(0), np.zeros((0, 3)))
    assert alike.flights_used() == "1 of 3 flights (2 skipped: too short)"


def _copies(tmp_path):
    rec = synthetic_recording(7, tosses=1, flight=(0.6, 0.8))
    a = tmp_path / "a.csv"
    a.write_text(rec.csv_text(), encoding="utf-8")
    b = tmp_path / "b.csv"
    shutil.copy(a, b)
    c = tmp_path / "c.csv"
    os.symlink(a, c)
    d = tmp_path / "d.csv"
    d.write_text(rec.csv_text("the same samples under another comment"), encoding="utf-8")
    return a, b, c, d


@pytest.mark.parametrize("other", ["a.csv", "b.csv", "c.csv", "d.csv"])
def test_the_same_recording_twice_is_refused_in_one_line(tmp_path, capsys, other):
    """By content, not name: the file again, a copy, a symlink, the samples under another header."""
    a = _copies(tmp_path)[0]
    assert main(["fit", str(a), str(tmp_path / other), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert err.startswith(f"tumble: error: {tmp_path / other}: ") and "give each recording once" in err
    assert ("given twice" if other == "a.csv" else f"the same recording as {a}") in err
    assert not (tmp_path / "out").exists()


def test_fit_recording_refuses_the_same_samples_twice():
    rec = synthetic_recording(7, tosses=1, flight=(0.6, 0.8))
    with pytest.raises(ValueError, match=r"^recording 1: the same samples as recording 0 \(SHA-256 [0-9a-f]{12}\); "):
        fit_recording([(rec.t, rec.omega), (rec.t.copy(), rec.omega.copy())])


@pytest.mark.parametrize("cell", ["1e300", "-2e4"])
def test_an_absurd_reading_in_a_recordings_own_accelerometer_columns_is_refused(tmp_path, capsys, cell):
    """The gyroscope CSV's own accelerometer columns, as phyphox's Accelerometer.csv (commit
    8e6545d): a reading beyond 1e4 m/s^2 is refused in one line, exit 2 (it was used)."""
    rec = synthetic_recording(7, tosses=1, flight=(0.6, 0.8), accel=True)
    lines = ["t,gx,gy,gz,ax,ay,az"]
    for i, (ti, w, f) in enumerate(zip(rec.t, rec.omega, rec.accel.f)):
        ax = cell if i == 50 else f"{f[0]:.6g}"
        lines.append(f"{ti:.6f},{w[0]:.6g},{w[1]:.6g},{w[2]:.6g},{ax},{f[1]:.6g},{f[2]:.6g}")
    path = tmp_path / "log.csv"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    assert main(["fit", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert f"accel[50] = [{float(cell)!r}" in err and "beyond an accelerometer's reading (at most 1e+04 m/s^2" in err
