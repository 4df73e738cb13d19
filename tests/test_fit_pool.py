"""Many recordings, one body (issue #29 item 2): ``tumble fit A.csv B/ C.zip`` pools every flight
of every recording in one joint fit, the ratios and the drag shared, the sensor's mount and bias
each recording's own (tumble.analysis.fit.recording, joint, model; tumble.commands.fit).

The recordings are :func:`tumble.analysis.fit.synthetic.synthetic_recording`'s (each seed its
own phone mount, bias, scale errors and noise), written as a CSV, a phyphox folder and a zip.
"""

from __future__ import annotations

import csv
import json
import warnings
import zipfile

import numpy as np
import pytest

from tumble.analysis.fit import InadequateFitWarning, fit_recording
from tumble.analysis.fit.flights import find_flights
from tumble.analysis.fit.model import Model
from tumble.analysis.fit.synthetic import synthetic_recording
from tumble.cli import main
from tumble.io.gyrodata import load_recording
from made_once import made_once

SEEDS = (41, 42, 43)


def _recorded_search(t, omega, **kwargs):
    """The real fit_recording's search of a recording, with the progress calls it made and the
    warnings it gave (message, category, file, line), for :func:`found_once` to replay."""
    calls = []
    with warnings.catch_warnings(record=True) as caught:
        found = find_flights(t, omega, progress=lambda *args: calls.append(args), **kwargs)
    return found, calls, [(w.message, w.category, w.filename, w.lineno) for w in caught]


_search_once = made_once(_recorded_search)


@pytest.fixture
def found_once(monkeypatch):
    """fit_recording's search of a recording made once: the tests below fit the same numbers
    (read back from the three files) by the command, apart and jointly, and find_flights is
    deterministic in the samples and options (:func:`made_once`). Each call replays the search's
    progress calls and its warnings, as the search itself would make them."""
    import tumble.analysis.fit.recording as module

    def once(t, omega, *, progress=None, **kwargs):
        found, calls, caught = _search_once(np.asarray(t), np.asarray(omega), **kwargs)
        for args in calls:
            if progress is not None:
                progress(*args)
        for message, category, filename, lineno in caught:
            warnings.warn_explicit(message, category, filename, lineno)
        return found

    monkeypatch.setattr(module, "find_flights", once)


@pytest.fixture(scope="module")
def three(tmp_path_factory):
    """Three recordings of the racquet, three tosses each: a CSV, a phyphox folder, a zip."""
    root = tmp_path_factory.mktemp("pool")
    recs = [synthetic_recording(seed, tosses=3) for seed in SEEDS]
    a = root / "A.csv"
    a.write_text(recs[0].csv_text("first recording"), encoding="utf-8")
    b = root / "B"
    (b / "meta").mkdir(parents=True)
    (b / "Raw Data.csv").write_text(recs[1].csv_text(), encoding="utf-8")
    (b / "meta" / "time.csv").write_text(recs[1].time_csv_text(), encoding="utf-8")
    c = root / "C.zip"
    with zipfile.ZipFile(c, "w") as z:
        z.writestr("Raw Data.csv", recs[2].csv_text())
        z.writestr("meta/time.csv", recs[2].time_csv_text())
    return recs, [a, b, c], root


def test_three_recordings_pooled_by_the_command_agree_with_the_three_fitted_apart(three, capsys, found_once):
    recs, paths, root = three
    out = root / "fit"
    assert main(["fit", *map(str, paths), "--out", str(out)]) == 0
    line = capsys.readouterr().out
    assert line.count("\n") == 1 and "in 3 recordings (sensor mount and bias per recording)" in line
    data = json.loads((out / "fit.json").read_text(encoding="utf-8"))
    labels = [str(p) for p in paths]
    assert data["input"] == labels and [r["file"] for r in data["read"]] == [
        labels[0], str(paths[1] / "Raw Data.csv"), f"{labels[2]}/Raw Data.csv"]
    pooled = data["pooled"]
    assert pooled["recordings"] == 3 and pooled["shared"] == ["I1_over_I3", "I2_over_I3", "drag"]
    assert pooled["per_recording"] == ["sensor_rotation", "bias"] and pooled["per_flight"] == ["omega0"]
    assert [toss["input"] for toss in data["tosses"]] == [labels[0]] * 3 + [labels[1]] * 3 + [labels[2]] * 3
    assert set(data["provenance"]["inputs"]) == set(labels) and all(len(h) == 64 for h in data["provenance"]["inputs"].values())
    with open(out / "tosses.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert [row["input"] for row in rows] == [toss["input"] for toss in data["tosses"]]
    assert (out / "fit.png").stat().st_size > 10_000

    # the three fitted apart: the pooled ratios are their inverse-variance mean, within its uncertainty,
    # and more precise than any one of them
    read = [load_recording(p) for p in paths]  # the numbers as written in the files
    apart = [fit_recording(r.t, r.omega, events=list(r.events)) for r in read]
    assert all(fit.tosses_used == 3 for fit in apart) and pooled["tosses_used"] == 9
    values = np.array([fit.pooled.ratios for fit in apart])
    var = np.array([fit.pooled.ratios_std for fit in apart]) ** 2
    mean = np.sum(values / var, axis=0) / np.sum(1 / var, axis=0)
    std_mean = 1 / np.sqrt(np.sum(1 / var, axis=0))
    got = np.array([pooled["I1_over_I3"], pooled["I2_over_I3"]])
    std = np.array([pooled["I1_over_I3_std"], pooled["I2_over_I3_std"]])
    assert np.all(np.abs(got - mean) < 2 * std_mean), (got, mean, std_mean)
    assert np.all(std < np.sqrt(var).min(axis=0))
    truth = recs[0].ratios
    assert np.all(np.abs(got - truth) < 3 * std)

    # the joint likelihood: the pooled model is the three models held to one body (shared
    # ratios and drag), so its least squares cost no less than theirs together, and sharing
    # costs little when the body is one (a different body costs more: next test)
    joint = fit_recording([(r.t, r.omega, list(r.events)) for r in read])
    assert np.allclose(joint.pooled.ratios, got, rtol=0, atol=1e-12) and joint.residuals == sum(f.residuals for f in apart)
    cost, apart_cost = joint.ssr, sum(f.ssr for f in apart)
    assert apart_cost * (1 - 1e-6) <= cost < 1.25 * apart_cost, (cost, apart_cost)


def test_a_recording_of_another_body_is_named_and_left_out():
    racquets = [synthetic_recording(seed, tosses=3) for seed in SEEDS[:2]]
    phone = synthetic_recording(44, body="phone", tosses=3)
    with pytest.warns(InadequateFitWarning, match="more than one body"):
        fit = fit_recording([(r.t, r.omega, r.events) for r in (*racquets, phone)])
    left = [toss for toss in fit.tosses if toss.status != "ok"]
    assert {toss.recording for toss in left} == {2} and all("disagrees" in toss.reason for toss in left)
    assert fit.tosses_used == 6 and not fit.pooled.adequate


def test_start_and_end_need_one_recording_and_a_bad_input_is_named(three, capsys, tmp_path):
    _, paths, _ = three
    assert main(["fit", str(paths[0]), str(paths[1]), "--start", "1", "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--start/--end select one flight of one recording; 2 recordings given" in err
    bad = tmp_path / "bad.csv"
    bad.write_text("t,ax,ay,az\n0,1,2,3\n0.01,1,2,3\n", encoding="utf-8")
    assert main(["fit", str(paths[0]), str(bad), "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "bad.csv, line 1" in err and not (tmp_path / "x").exists()


def test_the_single_input_output_is_unchanged_apart_from_the_new_keys(three, capsys, found_once):
    recs, paths, root = three
    out = root / "one"
    assert main(["fit", str(paths[0]), "--out", str(out)]) == 0
    data = json.loads((out / "fit.json").read_text(encoding="utf-8"))
    assert data["input"] == str(paths[0]) and data["read"]["rows"] == len(recs[0].t)
    assert data["read"]["rates"] == ["Gyroscope x (rad/s)", "Gyroscope y (rad/s)", "Gyroscope z (rad/s)"]
    keys = ["input", "start", "end", "samples", "I1_over_I3", "I2_over_I3", "I1_over_I3_std", "I2_over_I3_std",
            "edge", "residual_rms", "status", "reason"]
    assert all(list(toss) == keys for toss in data["tosses"])
    assert (out / "tosses.csv").read_text(encoding="utf-8").splitlines()[0] == ",".join(keys)
    assert data["pooled"]["per_recording"] == [] and data["pooled"]["recordings"] == 1
    read = load_recording(paths[0])
    fit = fit_recording(read.t, read.omega, events=list(read.events))
    summary = json.loads(json.dumps(fit.summary()))
    tosses = [{k: v for k, v in toss.items() if k != "input"} for toss in data.pop("tosses")]
    assert tosses == summary.pop("tosses")  # each toss as before, and the recording it came from
    models = [{k: v for k, v in m.items() if k != "input"} for m in data.pop("flight_models")]
    assert models == summary.pop("flight_models")  # each used flight's model, and its recording
    assert {k: data[k] for k in summary} == summary  # the fit's own numbers, as before
    assert list(json.loads(json.dumps(data["provenance"]["inputs"]))) == [str(paths[0])]


def test_one_recording_in_a_list_is_the_recording():
    rec = synthetic_recording(11, tosses=2, flight=(0.5, 0.8))
    one = fit_recording(rec.t, rec.omega, events=rec.events)
    listed = fit_recording([(rec.t, rec.omega, rec.events)])
    assert np.array_equal(one.pooled.ratios, listed.pooled.ratios) and one.ssr == listed.ssr


@pytest.mark.parametrize("args, kwargs, message", [
    (([],), {}, "an empty list of recordings"),
    (([(np.zeros(3),)],), {}, r"recording 0: expected \(t, omega\), \(t, omega, events\) or \(t, omega, events, accel\), got tuple of 1 items"),
    (([(np.zeros(3), np.zeros((3, 3)))],), {"events": []}, "events go with each recording"),
    (([(np.arange(300) * 0.01, np.zeros((299, 3))), (np.arange(300) * 0.01, np.zeros((300, 3)))],), {},
     r"recording 0: omega_measured must have shape \(300, 3\)"),
    # a file's name, as a new user tries first (was "recording 0: expected (t, omega) ..., got str")
    (("tosses.csv",), {}, r"^t = 'tosses.csv' is a file's name: read it first, t, omega, events = "
                          r"tumble.io.gyrodata.read_recording\(path\)"),
])
def test_a_bad_list_of_recordings_is_refused(args, kwargs, message):
    with pytest.raises(ValueError, match=message):
        fit_recording(*args, **kwargs)


def test_the_model_s_per_recording_mount_and_bias_and_their_jacobian():
    taus = [np.linspace(0.0, 1.0, 40), np.linspace(0.0, 0.8, 30), np.linspace(0.0, 0.9, 35)]
    model = Model(taus, True, True, "quadratic", [7.0, 7.0, 7.0], groups=[0, 1, 1])
    P = model.pack(0.7, 0.4, [[0.1, 0.2, 0.3], [0.3, -0.2, 0.5]], [[0.01, 0.0, 0.0], [0.0, 0.02, -0.01]],
                   [[3.0, 1.0, 6.0], [2.0, 5.0, 1.0], [1.0, 1.0, 6.0]], [0.01, 0.02, 0.03])
    wp = model.principal(P)
    w = model.sensor(P, wp)
    for j, r in enumerate(model.groups):  # each flight: its recording's R^T omega + b
        assert np.allclose(w[j], wp[j] @ model.rotation_matrix(P, r) + model.bias_vector(P, r))
    mask = np.repeat(model.valid[:, :, None], 3, axis=2)
    J = model.jacobian(P, mask).toarray()
    central = np.empty_like(J)
    for i in range(model.n):
        h = np.zeros(model.n)
        h[i] = 1e-6
        central[:, i] = (model.sensor(P + h) - model.sensor(P - h))[mask] / 2e-6
    assert np.max(np.abs(J - central)) < 1e-5 * np.max(np.abs(central))
    # recording 1's mount acts on its flights only
    k = model.names.index("rotvec_x[rec 1]")
    assert not np.any(J[:int(mask[0].sum()), k])
    warnings.simplefilter("default")


def test_a_flight_that_does_not_fix_the_ratios_alone_is_used_in_the_joint_fit():
    """A short racquet toss (0.5 s, 0.7 turns) follows a free motion but leaves the ratios
    undetermined alone; its recording's other toss determines them, and the ratios are the
    body's: the joint fit uses both (issue #29: "found and fitted")."""
    from tumble.analysis.fit import NoFlightError
    from tumble.analysis.fit.recording import JOINT_ONLY

    rec = synthetic_recording(1009, body="racquet", tosses=2, pauses=1)
    (a, b), _ = rec.flights
    alone = (rec.t >= a - 1.0) & (rec.t <= b + 0.8)  # the short toss and the holds around it
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InadequateFitWarning)
        # not determined alone: too little recorded, or (scipy >= 1.17's optimizer) run to the rod limit
        with pytest.raises(NoFlightError, match="too little of the tumble recorded|ratios not determined"):
            fit_recording(rec.t[alone], rec.omega[alone])
        fit = fit_recording(rec.t, rec.omega, events=rec.events)
    short, long = fit.tosses
    assert (short.status, long.status, fit.tosses_used) == ("ok", "ok", 2)
    assert short.reason.startswith((f"{JOINT_ONLY}: too little of the tumble recorded",
                                    f"{JOINT_ONLY}: ratios not determined")) and long.reason == ""
    assert abs(short.start - a) < 0.05 and abs(short.end - b) < 0.05  # the true release and catch
    # its own fit: not determined (wide, or run to the rod limit where no racquet lies)
    assert np.max(short.fit.ratios_std) > 0.1 or "rod limit" in short.reason
    assert np.all(np.abs(fit.pooled.ratios - rec.ratios) < 3 * fit.pooled.ratios_std)  # the truth
    assert np.isnan(fit.chi2_dof)  # one flight states its own ratios: no scatter among flights to measure


def test_a_recording_in_deg_s_read_as_rad_s_fails_naming_the_unit(tmp_path, capsys):
    """deg/s numbers under a header that names no unit are read as rad/s, 57 times too fast: no
    flight follows a free motion, and the failure said only that (a walkthrough, issue 40). Rates
    past any MEMS gyroscope's 4000 deg/s now name the likely unit: the command warns at once, as
    soon as the file is read, not only when the fit fails some 20 s later."""
    from tumble.analysis.fit import NoFlightError
    from tumble.analysis.fit.recording import DEG_S_HINT_RATE

    rec = synthetic_recording(3, tosses=2)
    assert np.max(np.linalg.norm(rec.omega, axis=1)) < DEG_S_HINT_RATE < np.max(np.linalg.norm(np.degrees(rec.omega), axis=1))
    with pytest.raises(NoFlightError, match=r"; the rates reach [\d.]+ rad/s, beyond any MEMS gyroscope's range "
                                            r"\(4000 deg/s = 69.81 rad/s\): are they in deg/s\? Name the unit in the header"):
        fit_recording(rec.t, np.degrees(rec.omega))
    path = tmp_path / "gyro.csv"
    rows = np.column_stack([rec.t, np.degrees(rec.omega)])
    path.write_text("t,wx,wy,wz\n" + "\n".join(",".join(f"{v:.6g}" for v in row) for row in rows) + "\n")
    assert main(["fit", str(path), "--out", str(tmp_path / "fit")]) == 1
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith(f"warning: {path}: the rates reach ") and "are they in deg/s?" in err[0]  # at once
    assert "are they in deg/s?" in err[-1]  # and in the failure
    path.write_text("t,wx (deg/s),wy (deg/s),wz (deg/s)\n" + path.read_text().split("\n", 1)[1])  # the unit named
    read = load_recording(path)
    np.testing.assert_allclose(read.omega, rec.omega, rtol=1e-5, atol=1e-6)  # read back as the rad/s they are


def test_deg_s_read_as_rad_s_that_fits_a_flight_is_not_adequate():
    """At 14-16 rad/s a phone's rates in deg/s reach ~900 'rad/s', and a flight or two of them fit within
    the 3 % relative misfit a flexing body is allowed: a walkthrough's file gave I1/I3 = 0.98 for 0.20,
    "adequate", exit 0. Past any MEMS gyroscope's range the fit is now not adequate and says why."""
    rec = synthetic_recording(4, body="phone", tosses=2, spin=(14.0, 16.0), rate=200.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InadequateFitWarning)
        wrong = fit_recording(rec.t, np.degrees(rec.omega))
        right = fit_recording(rec.t, rec.omega)
    assert wrong.tosses_used >= 1 and abs(wrong.pooled.ratios[0] - rec.ratios[0]) > 0.5  # fitted, and wrong
    assert not wrong.pooled.adequate and "are they in deg/s?" in wrong.pooled.adequacy
    assert right.pooled.adequate and "deg/s" not in (right.pooled.adequacy or "")


def test_a_recording_none_of_whose_flights_entered_the_pool_is_named(tmp_path, capsys):
    """A phone's recording pooled with two of a racquet: its flights disagree with the others and are
    left out, and the fit said nothing of it, exit 0 (a walkthrough, 2026-12-02). A warning names the
    recording whose every flight was left out, with the first reason."""
    from tumble.analysis.fit.synthetic import synthetic_recording
    from tumble.commands.fit import run_fit_command

    paths = []
    for i, (seed, body, tosses) in enumerate([(3, "racquet", 4), (4, "racquet", 4), (5, "phone", 2)]):
        paths.append(tmp_path / f"rec{i}.csv")
        paths[-1].write_text(synthetic_recording(seed, body=body, tosses=tosses).csv_text(), encoding="utf-8")
    assert run_fit_command(paths, tmp_path / "out") == 1  # and the pooled value is no answer: next test
    said = capsys.readouterr()
    err = said.err
    # the line on stdout says so too: read without the warnings it looked like an answer (a walkthrough, 2026-12-03)
    assert said.out.startswith("fit 3 recordings (not adequate: see the warning): I1/I3 = ")
    assert f"warning: {paths[2]}: none of its 2 flights entered the pooled fit (disagrees with the other flights" in err
    assert "the recordings disagree: every fitted flight of recordings[2] lies" in err
    assert str(paths[0]) not in err and str(paths[1]) not in err


def test_a_racquet_and_a_phone_pooled_are_no_answer():
    """The shipped racquet's tosses pooled with the shipped phone's toss, as a user would try them:
    the phone's flight made the joint fit fail, and the flights' weighted mean, I1/I3 = 0.20 (the
    phone's) for the racquet's 0.06 at chi2/dof 943, was written as adequate with a correlation of
    -2.6 (a walkthrough, 2026-12-02). The phone's flight is now left out as disagreeing, the pooled
    ratios are the racquet flights', and the fit is not adequate, naming the recording that
    disagrees. The racquet's first 12 s (three tosses) keep the test short; the whole file fails
    alike."""
    from pathlib import Path

    data = Path(__file__).resolve().parents[1] / "examples" / "data"
    racquet, phone = load_recording(data / "racquet_tosses.csv"), load_recording(data / "phone_toss.csv")
    k = racquet.t < 12.0
    with pytest.warns(InadequateFitWarning, match=r"the recordings disagree: every fitted flight of recordings\[1\]"):
        fit = fit_recording([(racquet.t[k], racquet.omega[k], [e for e in racquet.events if e[0] < 12.0]),
                             (phone.t, phone.omega, list(phone.events))])
    assert not fit.pooled.adequate and "fit each recording apart" in fit.pooled.adequacy
    [left] = [toss for toss in fit.tosses if toss.recording == 1]
    assert left.status == "skipped" and left.reason.startswith("disagrees with the other flights")
    own = np.array([toss.fit.ratios for toss in fit.tosses if toss.status == "ok"])
    assert len(own) >= 2 and np.all(own[:, 0] < 0.12) and abs(left.fit.ratios[0] - 0.20) < 0.01  # racquet, phone
    assert np.all(np.abs(fit.pooled.ratios - np.median(own, axis=0)) < 5 * fit.pooled.ratios_std)
    assert -1.0 <= fit.summary()["ratios_correlation"] <= 1.0


def test_an_accelerometers_file_given_as_the_gyroscope_is_pointed_at(tmp_path, capsys):
    """A phone's accelerometer on a table (9.81 on z) given as the gyroscope failed as "1 steady spin"
    (a walkthrough of docs/fitting.md, 2026-12-03); the warning and the failure now name the likely cause."""
    rng = np.random.default_rng(1)
    t = np.arange(3000) * 0.01
    a = np.array([0.01, -0.02, 9.81]) + rng.normal(0.0, 0.02, (3000, 3))
    path = tmp_path / "table.csv"
    path.write_text("t (s),x,y,z\n" + "".join(f"{x:.3f},{r[0]:.4f},{r[1]:.4f},{r[2]:.4f}\n" for x, r in zip(t, a)))
    assert main(["fit", str(path), "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err.splitlines()
    hint = ("|omega| stays within 0.5 of 9.81 in 100 % of the samples, as an accelerometer reads gravity at rest: is "
            "this the accelerometer's file? Give the gyroscope's")
    assert err[0] == f"warning: {path}: {hint}"
    assert err[1].startswith("tumble: fit failed: ") and f"; {hint}; nothing written" in err[1]


def test_the_pooled_fit_counts_the_rail_of_every_flight_it_used():
    """fit.json's ``saturated`` counted the first flight's sample axes at the rail only: 0 for a pool whose
    second flight had 70 (a walkthrough, 2026-12-03). It is now the sum over the flights used."""
    rec = synthetic_recording(7, body="phone", tosses=3, spin=(14.0, 16.0), saturation=15.0)  # the 2nd flight clips
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InadequateFitWarning)
        fit = fit_recording(rec.t, rec.omega, events=rec.events)
    own = [toss.fit.saturated for toss in fit.tosses if toss.status == "ok"]
    assert fit.tosses_used == len(own) >= 2 and sum(own) > 0
    assert own[0] == 0 and fit.pooled.saturated == sum(own) > 0   # the first flight, whose view the pool is, clips not
