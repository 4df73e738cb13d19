"""The command line: output formats, one-line errors with exit status 2, fast --help."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import tumble
from tumble.cli import main
from limits import HANG_S

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("source", ["t-handle", "iss-t-handle", str(EXAMPLES / "bodies" / "every_part.toml")])
def test_inertia_json(capsys, source):
    code, out, err = run(capsys, "inertia", source, "--json")
    assert code == 0 and err == ""
    data = json.loads(out)
    body = tumble.load_body(source)
    assert data["mass"] == pytest.approx(body.mass)
    np.testing.assert_allclose(data["com"], body.com)
    np.testing.assert_allclose(data["inertia"], body.inertia)
    I, A = np.array(data["principal_moments"]), np.array(data["principal_axes"])
    assert np.all(np.diff(I) >= 0)
    np.testing.assert_allclose(A @ np.diag(I) @ A.T, data["inertia"], atol=1e-12 * I.sum())
    np.testing.assert_allclose(data["intermediate_axis"], A[:, 1])


def test_inertia_json_seed_values(capsys):
    data = json.loads(run(capsys, "inertia", "t-handle", "--json")[1])
    np.testing.assert_allclose(data["principal_moments"], [0.125, 0.3125, 0.4375])
    np.testing.assert_allclose(data["intermediate_axis"], [1, 0, 0])  # the crossbar


def test_inertia_table(capsys):
    code, out, _ = run(capsys, "inertia", "iss-t-handle")
    assert code == 0
    assert "intermediate axis +z" in out


@pytest.mark.parametrize(
    "argv",
    [
        ["inertia", "no-such-thing"],
        ["inertia", "/nonexistent/body.toml"],
        ["inertia"],
        ["frobnicate"],
        ["inertia", "t-handle", "--bogus"],
    ],
)
def test_bad_input_is_one_line_and_exit_2(capsys, argv):
    with pytest.raises(SystemExit) as info:
        code = main(argv)
        raise SystemExit(code)
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err


@pytest.mark.parametrize(("argv", "said"), [
    # a scenario file's key spelt as an option (t_end = ... in TOML, --t-end on the line), a typo
    (["simulate", "seed_flip.toml", "--out", "r", "--t_end", "30"],
     "tumble simulate: error: unrecognized arguments: --t_end 30 (--t_end: did you mean --t-end?)"),
    (["simulate", "seed_flip.toml", "--out", "r", "--samplse=3", "--bogus"],
     "tumble simulate: error: unrecognized arguments: --samplse=3 --bogus (--samplse: did you mean --samples?)"),
    (["inertia", "t-handle", "--jsn"], "tumble inertia: error: unrecognized arguments: --jsn (--jsn: did you mean --json?)"),
    (["--jsn"], "tumble: error: unrecognized arguments: --jsn"),
    # the option misspelt is the one required: argparse said only that --out is missing (a walkthrough,
    # 2026-12-02); an unambiguous start of an option is argparse's, not misspelt
    (["fit", "rec.csv", "--otu", "x"], "tumble fit: error: unrecognized arguments: --otu (--otu: did you mean --out?); "
     "and the following arguments are required: --out"),
    # an option is taken whole: argparse read "--t-e" as --t-end (and "--mas" as --mass) without a word
    # (a walkthrough, 2026-12-03); a new option starting so would have changed what it meant
    (["simulate", "seed_flip.toml", "--t-e", "5"], "tumble simulate: error: unrecognized arguments: --t-e "
     "(--t-e: did you mean --t-end?); and the following arguments are required: --out"),
    (["inertia", "t-handle", "--jso"], "tumble inertia: error: unrecognized arguments: --jso (--jso: did you mean --json?)"),
])
def test_an_unknown_option_is_answered_by_the_commands_nearest(capsys, argv, said):
    with pytest.raises(SystemExit) as info:
        main(argv)
    assert info.value.code == 2
    assert capsys.readouterr().err == said + "\n"


@pytest.mark.parametrize(("word", "near"), [("simulat", "simulate"), ("Fit", "fit"), ("intertia", "inertia"), ("zzz", None)])
def test_a_misspelt_command_is_answered_by_the_nearest(capsys, word, near):
    """'tumble simulat' listed the twelve commands and named none of them (seen 2026-12-02)."""
    with pytest.raises(SystemExit) as info:
        main([word, "x"])
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"tumble: error: argument COMMAND: invalid choice: '{word}' (choose from")
    assert err.endswith(f"(did you mean {near}?)\n" if near else "'demo')\n")


def test_frame_written_for_frames_is_named(capsys):
    """'tumble view seed_flip.toml --frame 300' said "--frame = '300' is not allowed; allowed: principal, design"
    and named --frames nowhere (a walkthrough, 2026-12-02)."""
    assert main(["view", str(EXAMPLES / "seed_flip.toml"), "--out", "flip.html", "--frame", "300"]) == 2
    assert capsys.readouterr().err == (f"tumble: error: {EXAMPLES / 'seed_flip.toml'}: --frame = '300' is not allowed; "
                                       "allowed: principal, design (the page's number of frames is --frames)\n")


def test_a_result_file_given_for_its_folder_names_the_folder(tmp_path, capsys):
    """'tumble view fitted/fit.json' said "not valid TOML: Invalid statement (at line 1, column 1)" (a
    walkthrough, 2026-12-02): the folder is what the page shows."""
    (tmp_path / "fitted").mkdir()
    (tmp_path / "fitted" / "fit.json").write_text('{"I1_over_I3": 0.2}\n')
    assert main(["view", str(tmp_path / "fitted" / "fit.json"), "--out", str(tmp_path / "v.html")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.rstrip("\n").endswith(
        f"fit.json: a JSON file, not a body or scenario file (TOML); a fit's or a tensor's output folder is shown "
        f"whole: 'tumble view {tmp_path / 'fitted'}'"), err


@pytest.mark.parametrize(("argv", "said"), [
    (["view", str(EXAMPLES / "data" / "racquet_tosses.csv"), "--out", "{tmp}/v.html"],
     "racquet_tosses.csv: a table of samples, not a body or scenario file (TOML): a gyroscope recording is fitted "
     "with 'tumble fit FILE --out DIR' (then 'tumble view DIR'), a throw's log with 'tumble tensor'"),
    (["simulate", str(EXAMPLES / "sweeps" / "t_handle_dimensions.toml"), "--out", "{tmp}/run"],
     "t_handle_dimensions.toml: a sweep file ([sweep]): run it with 'tumble sweep FILE --out DIR'"),
    (["sweep", str(EXAMPLES / "seed_flip.toml"), "--out", "{tmp}/run"],
     "seed_flip.toml: no [sweep] table: a scenario is run with 'tumble simulate FILE --out DIR'; a sweep file adds "
     "[sweep] (cases = ...) and [[dispersion]] tables (see 'tumble examples')"),
    (["fit", str(EXAMPLES / "seed_flip.toml"), "--out", "{tmp}/run"],
     "seed_flip.toml: a TOML file (a scenario, body or device file), not a gyroscope recording: 'tumble simulate' "
     "runs a scenario; 'tumble fit' reads a CSV of the rates, or a phyphox or Sensor Logger export"),
    (["inertia", str(EXAMPLES / "seed_flip.toml")],
     "seed_flip.toml: a scenario file ([initial], [simulation]), not a body file; its body is 't-handle': try "
     "'tumble inertia t-handle'"),
    (["inertia", str(EXAMPLES / "explorer1.toml")],
     f"explorer1.toml: a scenario file ([initial], [simulation]), not a body file; its body is 'bodies/explorer1.toml': "
     f"try 'tumble inertia {EXAMPLES / 'bodies' / 'explorer1.toml'}'"),
    (["inertia", str(EXAMPLES / "sweeps" / "t_handle_dimensions.toml")],
     "t_handle_dimensions.toml: a sweep file ([sweep]), not a body file: a body file holds a [body] table alone (or "
     "give a preset: t-handle, iss-t-handle)"),
    (["inertia", str(EXAMPLES / "data" / "racquet_tosses.csv"), "--density", "1"],
     "racquet_tosses.csv: a table of samples, not a body or scenario file (TOML): a gyroscope recording is fitted "
     "with 'tumble fit FILE --out DIR' (then 'tumble view DIR'), a throw's log with 'tumble tensor'"),
])
def test_a_file_given_to_the_wrong_command_names_the_right_one(tmp_path, capsys, argv, said):
    """A recording given to 'tumble view' said "not valid TOML: Expected '=' after a key ... (at line 7,
    column 11)", a sweep file given to 'tumble simulate' "unknown key 'criterion'", a scenario given to
    'tumble sweep' "sweep: missing key 'cases'", to 'tumble fit' "header 'body, =, t-handle' has no
    time column" (seen 2026-11-30); a scenario or sweep file given to 'tumble inertia' "unknown top-level key
    'initial' (a body file has only [body])", a recording with --density "is a body file or preset" (2026-12-02)."""
    assert main([a.format(tmp=tmp_path) for a in argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.rstrip("\n").endswith(said), err
    assert list(tmp_path.iterdir()) == []


def test_bad_file_through_the_installed_command(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("[[body.parts]]\nkind = 'rod'\nmass = -1\nlength = 1\n")
    proc = subprocess.run([sys.executable, "-m", "tumble", "inertia", str(path)], capture_output=True, text=True)
    assert proc.returncode == 2
    assert proc.stdout == ""
    assert proc.stderr.strip() == f"tumble: error: {path}: body.parts[0] (rod): mass = -1 must be a positive finite number (kg)"


def test_debug_shows_the_traceback(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "tumble", "--debug", "inertia", "nope"], capture_output=True, text=True)
    assert proc.returncode != 0 and "Traceback" in proc.stderr


@pytest.mark.parametrize("argv", [["examples"], ["inertia", "t-handle", "--json"]])
def test_a_reader_that_closes_the_pipe_early_is_a_normal_end(argv):
    """``tumble examples | head -2``: the reader leaves before tumble writes; exit 0, nothing said."""
    proc = subprocess.Popen([sys.executable, "-m", "tumble", *argv], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.close()  # closed before the child writes a byte: its first write meets a broken pipe
    err = proc.stderr.read()
    assert proc.wait(timeout=HANG_S) == 0 and err == b""


def test_version(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0
    assert capsys.readouterr().out.strip() == f"tumble {tumble.__version__}"


def test_help_imports_no_heavy_module():
    """--help must answer at once: the CLI module loads neither numpy, scipy nor matplotlib."""
    code = "import sys, tumble.cli; print(sorted(m for m in ('numpy', 'scipy', 'matplotlib', 'trimesh') if m in sys.modules))"
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert proc.stdout.strip() == "[]"


def test_the_commands_machinery_imports_no_scipy_stats():
    """scipy.stats costs ~0.2 s to import (its distributions build their docstrings): the fit, the
    throw files and the tensor's pooling, which a throw file's reader imports, take the one
    quantile they need from scipy.special. The check can fail: the ensemble's confidence bounds
    do import it."""
    modules = ("tumble.commands.fit", "tumble.commands.tensor", "tumble.commands.scenario", "tumble.io.throwfile",
               "tumble.analysis.tensor")
    code = f"import sys, {', '.join(modules)}; print('scipy.stats' in sys.modules)"
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=HANG_S)
    assert proc.stdout.split() == ["False"]
    code = "import sys, tumble.ensemble.confidence as c; c.fraction_interval(10, 3); print('scipy.stats' in sys.modules)"
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=HANG_S)
    assert proc.stdout.split() == ["True"]


@pytest.mark.parametrize("argv", [
    ["simulate", "examples/seed_flip.toml", "--out", "run"],
    ["fit", "tosses.csv", "--body", "t-handle", "--out", "fitted"],
    ["fit", "examples/data/racquet_tosses.csv", "--body", "my_body.toml", "--out", "fitted"],
    ["calibrate", "device.toml", "--alone", "a1.csv", "--proof", "p1.csv", "--out", "calibrated.toml"],
    ["tensor", "o1.csv", "--device", "calibrated.toml", "--mass", "0.4", "--out", "bracket"],
    ["sweep", "sizes.toml", "--out", "runs"],
    ["inertia", "bracket.stl", "--density", "2700"],
])
def test_a_missing_input_file_is_refused_before_the_command_loads_its_machinery(tmp_path, argv):
    """A mistyped path is said at once: the file's own message, exit 2, and neither scipy nor numba
    imported (0.3-0.6 s before the message, the commands' imports). The first missing name is the one said."""
    code = ("import sys; from tumble.cli import main; status = main(sys.argv[1:]); "
            "print(status, sorted(m for m in ('scipy', 'numba', 'matplotlib') if m in sys.modules))")
    if "examples/data/racquet_tosses.csv" in argv:  # present: the missing --body is the one said
        (tmp_path / "examples" / "data").mkdir(parents=True)
        (tmp_path / "examples" / "data" / "racquet_tosses.csv").write_text("t,wx,wy,wz\n")
    proc = subprocess.run([sys.executable, "-c", code, *argv], cwd=tmp_path, capture_output=True, text=True,
                          timeout=HANG_S)
    k, missing = next((k, a) for k, a in enumerate(argv) if k and "." in a and not (tmp_path / a).exists())
    option = argv[k - 1] if argv[k - 1] in ("--body", "--device") else None  # an option's file named with it
    assert proc.stdout.strip() == "2 []", proc.stdout + proc.stderr
    said = f"{option}: {missing}" if option else missing
    assert proc.stderr.startswith(f"tumble: error: {said}: no such file") and proc.stderr.count("\n") == 1


def test_demo_cli_writes_its_folder(tmp_path, capsys, monkeypatch):
    import tumble.demo

    calls = {}
    monkeypatch.setattr(tumble.demo, "run_demo", lambda out, animate, animation_format, argv: calls.update(
        out=out, animate=animate, animation_format=animation_format))
    code, _, _ = run(capsys, "demo", "--out", str(tmp_path / "d"), "--no-animation")
    assert code == 0 and calls == {"out": str(tmp_path / "d"), "animate": False, "animation_format": "auto"}
    code, _, _ = run(capsys, "demo", "--out", str(tmp_path / "d"), "--animation-format", "gif")
    assert code == 0 and calls["animation_format"] == "gif" and calls["animate"]
    with pytest.raises(SystemExit) as info:
        main(["demo", "--out", str(tmp_path / "d"), "--animation-format", "avi"])
    assert info.value.code == 2 and "invalid choice: 'avi'" in capsys.readouterr().err


def test_examples_are_listed_and_copied_ready_to_run(tmp_path, capsys):
    code, out, _ = run(capsys, "examples")
    assert code == 0
    listed = [line.split()[0] for line in out.splitlines()[:-1]]
    assert "seed_flip.toml" in listed and "bodies/t_handle.toml" in listed
    code, out, _ = run(capsys, "examples", "--copy", str(tmp_path / "ex"))
    copied = sorted(p.relative_to(tmp_path / "ex").as_posix() for p in (tmp_path / "ex").rglob("*") if p.is_file())
    assert code == 0 and copied == sorted(listed)  # every file copied is listed (data, notebooks, the mesh too)
    assert {"data/racquet_tosses.csv", "notebooks/tennis_racket.ipynb", "bodies/meshes/torus.stl"} <= set(listed)
    assert run(capsys, "simulate", str(tmp_path / "ex" / "every_part_spin.toml"), "--t-end", "1", "--out", str(tmp_path / "r"))[0] == 0
    code, _, err = run(capsys, "examples", "--copy", str(tmp_path / "ex"))  # never overwrites
    assert code == 2 and "already exists" in err


def test_fit_command_on_the_shipped_record(tmp_path, capsys):
    """`tumble fit` on the synthetic phone toss (a box 15 x 7.5 x 0.8 cm: I1/I3 = 0.2023,
    I2/I3 = 0.8023 from its dimensions, Meriam & Kraige Table D/4) recovers the ratios."""
    a, b, c = 0.15, 0.075, 0.008
    I = np.sort([b * b + c * c, a * a + c * c, a * a + b * b])
    code, out, err = run(capsys, "fit", str(EXAMPLES / "data" / "phone_toss.csv"), "--out", str(tmp_path / "fit"))
    assert code == 0 and err == "", err
    data = json.loads((tmp_path / "fit" / "fit.json").read_text())
    assert "ratios" in json.dumps(data)
    from tumble.io.gyrodata import read_gyro_csv

    fit = tumble.fit_rotation(*read_gyro_csv(EXAMPLES / "data" / "phone_toss.csv"))
    np.testing.assert_allclose(fit.ratios, I[:2] / I[2], atol=1e-3)
    code, _, err = run(capsys, "fit", str(tmp_path / "missing.csv"), "--out", str(tmp_path / "f2"))
    assert code == 2 and err.count("\n") == 1


def test_missing_trimesh_is_one_line_with_the_install_hint_and_status_2(capsys, monkeypatch):
    """Issue 27 item 10(b): a missing extra is the user's setup: one line naming the pip install, exit 2."""
    monkeypatch.setitem(sys.modules, "trimesh", None)
    code, out, err = run(capsys, "inertia", str(EXAMPLES / "bodies" / "every_part.toml"))
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and "pip install 'tumble[mesh]'" in err and "Traceback" not in err


def test_a_run_that_waited_for_numba_says_so_at_a_terminal(monkeypatch, capsys):
    """A first run compiles its kernels (5-25 s in a fresh install): at a terminal the command says
    so and names ``tumble compile``; in a pipe or a script, below the threshold, or for ``tumble compile``
    itself, it says nothing."""
    import tumble.cli as cli

    def run(argv, waited, tty=True):
        clock = iter([10.0, 10.0 + waited])
        monkeypatch.setattr(cli, "_compile_seconds", lambda: next(clock))
        monkeypatch.setattr(sys.stderr, "isatty", lambda: tty)
        assert main(argv) == 0
        return capsys.readouterr().err

    said = run(["inertia", "t-handle", "--json"], 7.4)
    assert said == ("tumble: this run waited 7 s for numba to compile its kernels, once per install: "
                    "'tumble compile' compiles them all ahead\n")
    assert run(["inertia", "t-handle", "--json"], 7.4, tty=False) == ""
    assert run(["inertia", "t-handle", "--json"], 0.5 * cli.COMPILE_NOTE_S) == ""
    assert run(["compile", "--list"], 30.0) == ""


def test_the_process_clock_counts_what_numba_compiles():
    from tumble.jit import compile_seconds, jit

    def fresh(body: str):  # a function of no file: numba caches nothing of it, so each one compiles
        namespace: dict = {}
        exec(f"def f(x):\n    return {body}\n", namespace)  # noqa: S102 - the test's own text
        return jit(namespace["f"])

    fresh("x + 2.0")(1.0)  # the clock starts with tumble's first kernel
    before = compile_seconds()
    assert fresh("x * 3.0")(1.0) == 3.0  # compiled now
    assert compile_seconds() > before


@pytest.mark.parametrize(("example", "balance"), [
    ("explorer1", "energy + dissipated"), ("wheel_t_handle", "energy - motor work"), ("seed_flip", "energy")])
def test_the_printed_drift_names_the_energy_balance_it_measures(tmp_path, capsys, example, balance):
    """The drift's energy is the balance E - motor work + dissipated (Trajectory.drift): Explorer 1's
    line said "energy 8.9e-08" of a body whose energy fell 57-fold, the wheel's "energy 9.7e-15" where
    the kinetic energy moves by 4e-6 (seen 2026-12-02). The number printed is the balance's drift."""
    assert main(["simulate", str(EXAMPLES / f"{example}.toml"), "--out", str(tmp_path / "run")]) == 0
    line = capsys.readouterr().out.strip().splitlines()[-1]
    printed = float(line.split(f"relative drift: {balance} ")[1].split(",")[0])
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert printed == pytest.approx(summary["drift"]["energy"], rel=0.05)  # the .1e of the balance's drift


@pytest.mark.parametrize(("argv", "said"), [
    # a file on the way of --copy's folder: it was "tumble: failed: afile: File exists", exit 1
    (["examples", "--copy", "{tmp}/afile/sub"], "--copy {tmp}/afile/sub: {tmp}/afile is a file, not a folder"),
    # the calibrated device written over the device file: it ran, exit 0, the file's comments lost
    (["calibrate", "{tmp}/device.toml", "--alone", str(EXAMPLES / "throws" / "a1.csv"), "--proof",
      str(EXAMPLES / "throws" / "p1.csv"), "--out", "{tmp}/device.toml"],
     "--out {tmp}/device.toml: the device file itself; write the calibrated device to a new file"),
    # simulate's bound, which map did not share (1e20 rad/s was mapped)
    (["map", "--spin", "1e20", "--out", "{tmp}/map.png"], "--spin = 1e20 is beyond 1e+15 rad/s: faster than any rotation"),
    # a mesh given where a scenario or body file is read: it was "not a text file (not valid UTF-8)"
    (["simulate", str(EXAMPLES / "bodies" / "meshes" / "torus.stl"), "--omega", "1", "2", "3", "--out", "{tmp}/run"],
     f"{EXAMPLES / 'bodies' / 'meshes' / 'torus.stl'}: a mesh file, not a scenario or body file: name it in a body "
     "file's part"),
    (["inertia", "{tmp}/bracket.step", "--mass", "1"],
     "{tmp}/bracket.step: not a text file (not valid UTF-8), so not a body or scenario file (TOML) (.step files are "
     "not read: meshes are .stl, .obj, .ply)"),
    # a sweep's input named as a sweep file: it said "a body or scenario file (TOML) must be a regular file"
    (["sweep", "{tmp}", "--out", "{tmp}/out"], "{tmp}: is a directory; a sweep file (TOML) must be a regular file"),
    # a preset that needs parameters is not listed where a name is asked for
    (["view", "{tmp}/fitted", "--out", "{tmp}/x.html"], "(presets: t-handle, iss-t-handle); {tmp}/fitted: no such file"),
])
def test_a_walkthroughs_command_line_slips_exit_2_in_one_line(tmp_path, capsys, argv, said):
    """A walkthrough of the README and every command's --help (2026-12-03): each of these exited 1, ran, or named
    the wrong cause; each now exits 2 with one line, and nothing is written."""
    (tmp_path / "afile").write_text("x")
    (tmp_path / "device.toml").write_text((EXAMPLES / "devices" / "flywheel_device.toml").read_text())
    (tmp_path / "bracket.step").write_bytes(bytes(range(128, 256)) * 4)
    before = sorted(p.name for p in tmp_path.iterdir())
    device = (tmp_path / "device.toml").read_text()
    code = main([a.replace("{tmp}", str(tmp_path)) for a in argv])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1, err
    assert said.replace("{tmp}", str(tmp_path)) in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == before and (tmp_path / "device.toml").read_text() == device


@pytest.mark.parametrize(("written", "said"), [("1,5", "'1,5' is not a number: write a decimal point, 1.5"),
                                               ("abc", "'abc' is not a number (digits, a decimal point, an exponent")])
def test_a_number_that_is_not_one_says_what_a_number_is(tmp_path, capsys, written, said):
    """argparse said only "invalid number value: '1,5'" (a walkthrough of every --help, 2026-12-03): a decimal comma
    is answered with its decimal point, other text with what a number is; one line, exit 2, nothing written."""
    with pytest.raises(SystemExit) as exited:
        main(["simulate", "t-handle", "--omega", "0", "1", "0", "--t-end", written, "--out", str(tmp_path / "run")])
    err = capsys.readouterr().err
    assert exited.value.code == 2 and err.count("\n") == 1 and f"argument --t-end: {said}" in err, err
    assert not (tmp_path / "run").exists()


# -- a QA engineer's walkthrough of the command line (2026-12-03) --------------------------------

def test_no_command_is_one_line_on_stderr(capsys):
    """Without a command the whole help went to stdout (exit 2, stderr empty): bad input is one line."""
    assert main([]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and err.startswith("tumble: error: give a command: inertia, simulate")


def test_a_negative_number_with_an_exponent_is_a_number(tmp_path, capsys):
    """argparse read "-1e-2" as an option: "argument --omega: expected 3 arguments", though 3 were given."""
    assert main(["simulate", "t-handle", "--omega", "-1e-2", "10", "0.1", "--t-end", "1", "--out", str(tmp_path / "r")]) == 0
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert summary["omega0"] == [-0.01, 10.0, 0.1]
    assert main(["map", "--out", str(tmp_path / "m.png"), "--perturbation", "1e-2", "-1e-2"]) == 2   # rad/s >= 0
    assert "--perturbation[1] = -1e-2 must be a non-negative" in capsys.readouterr().err   # as written


def test_a_closed_or_full_stdout_is_not_taken_for_a_failed_run(tmp_path):
    """Standard output closed (>&-) gave exit 1 "AttributeError: 'NoneType' object has no attribute 'flush'",
    a full one (>/dev/full) "No space left on device; nothing written", both of runs whose files were written."""
    seed = str(Path(tumble.__file__).parent / "examples" / "seed_flip.toml")
    argv = [sys.executable, "-m", "tumble", "simulate", seed, "--t-end", "1", "--out"]
    closed = subprocess.run(["sh", "-c", 'exec "$@" >&-', "sh", *argv, str(tmp_path / "closed")],
                            capture_output=False, stderr=subprocess.PIPE, text=True, timeout=HANG_S)
    assert closed.returncode == 0 and closed.stderr == "" and (tmp_path / "closed" / "summary.json").is_file()
    if not Path("/dev/full").exists():
        return
    with open("/dev/full", "w") as full:
        proc = subprocess.run([*argv, str(tmp_path / "full")], stdout=full, stderr=subprocess.PIPE, text=True,
                              timeout=HANG_S)
    assert proc.returncode == 1 and (tmp_path / "full" / "summary.json").is_file()
    assert proc.stderr == "tumble: failed: standard output: No space left on device; the outputs were written\n"


def test_a_toml_file_with_a_byte_order_mark_is_read(tmp_path, capsys):
    """A scenario saved by a Windows editor with a UTF-8 byte-order mark was "not valid TOML: Invalid statement
    (at line 1, column 1)", where CSV files with one were read."""
    path = tmp_path / "bom.toml"
    path.write_bytes(b'\xef\xbb\xbfbody = "t-handle"\n[initial]\nomega = [0.1, 10.0, 0.1]\n[simulation]\nt_end = 1.0\n')
    assert main(["simulate", str(path), "--out", str(tmp_path / "r")]) == 0
    assert json.loads((tmp_path / "r" / "summary.json").read_text())["omega0"] == [0.1, 10.0, 0.1]


def test_a_mesh_given_as_a_body_file_says_where_a_mesh_goes(tmp_path, capsys):
    """It said "(.stl files are not read: meshes are .stl, .obj, .ply)", contradicting itself."""
    examples = Path(tumble.__file__).parent / "examples"
    mesh = examples / "bodies" / "meshes" / "torus.stl"
    assert main(["fit", str(examples / "data" / "phone_toss.csv"), "--body", str(mesh), "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "a mesh: give it to 'tumble inertia', or as a part of a body file" in err


def test_an_empty_copy_folder_and_a_mass_of_nothing_are_refused(tmp_path, capsys, monkeypatch):
    """--copy "" listed the examples and copied nothing, exit 0; tensor --mass 1e-300 said "the part's mass
    0.10067 kg must be less than the whole's 0.10067 kg" (a QA walkthrough, 2026-12-03)."""
    from tumble.analysis.tensor.device import check_thrown_mass

    monkeypatch.chdir(tmp_path)
    assert main(["examples", "--copy", ""]) == 2 and list(tmp_path.iterdir()) == []
    assert "--copy = '' names no folder" in capsys.readouterr().err
    with pytest.raises(ValueError, match=r"--mass = 1e-300 kg is below 0.001 kg \(a gram\)"):
        check_thrown_mass("--mass", 1e-300)
    assert check_thrown_mass("--mass", 0.482) == 0.482


def test_the_summary_records_omega_as_given_and_its_frame(tmp_path, capsys):
    """summary.json held omega0 in the principal frame only: a run given --frame design could not be told
    from one given its principal rates (a teacher's walkthrough, 2026-12-03)."""
    assert main(["simulate", "t-handle", "--omega", "10", "0.1", "0.1", "--frame", "design", "--t-end", "1",
                 "--out", str(tmp_path / "r")]) == 0
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert summary["frame"] == "design" and summary["omega0_given"] == [10.0, 0.1, 0.1]
    assert summary["omega0"] == [0.1, 10.0, 0.1]   # the crossbar (design x) is the T-handle's intermediate axis


def test_a_subprocess_stopped_by_the_same_ctrl_c_is_an_interruption(tmp_path, monkeypatch, capsys):
    """Ctrl-C during the demo's MP4s stopped ffmpeg too, whose failure came first: exit 1 "computation failed:
    CalledProcessError" (a QA walkthrough, 2026-12-03). A failure after a signal the run received is the
    signal's: 130 (or 143), one line."""
    import signal as signals

    import tumble.cli as cli
    import tumble.cli.parser as parser

    def stopped(args):
        cli._signalled.append(signals.SIGINT)   # what the handler records, before KeyboardInterrupt can show
        raise subprocess.CalledProcessError(255, ["ffmpeg"])

    real = parser.build_parser

    def build():
        p = real()
        for action in p._actions:
            if getattr(action, "choices", None) and "map" in action.choices:
                action.choices["map"].set_defaults(func=stopped)
        return p

    monkeypatch.setattr(cli, "build_parser", build)
    assert main(["map", "--out", str(tmp_path / "m.png")]) == 130
    assert capsys.readouterr().err == "tumble: interrupted; nothing written\n"
    assert main(["inertia", "t-handle"]) == 0   # the next run starts with no signal


@pytest.mark.parametrize("text", ["1_0", "\uff11", "\u0661"])   # an underscore, a full-width 1, an Arabic-Indic 1
def test_a_number_is_written_as_the_docs_write_one(text, tmp_path, capsys):
    """float() takes them; the command line took "--omega 1_0" as 10 (a QA walkthrough, 2026-12-03)."""
    with pytest.raises(SystemExit) as stopped:   # argparse's exit, in one line
        main(["simulate", "t-handle", "--omega", text, "0.1", "0.1", "--out", str(tmp_path / "r")])
    assert stopped.value.code == 2 and not (tmp_path / "r").exists()
    assert f"{text!r} is not a number" in capsys.readouterr().err
