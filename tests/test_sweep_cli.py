"""Sweep files and their output: cases.csv, cases.parquet, summary.json, resume after an interruption."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

import tumble.ensemble.sweep as sweep_module
from tumble.ensemble import success_lower_bound
from tumble.io.resume import ResumeWarning
from tumble.commands.sweep import run_sweep, run_sweep_command
from tumble.io.sweepfile import load_sweep

EXAMPLE = Path(__file__).resolve().parents[1] / "src" / "tumble" / "examples" / "sweeps" / "t_handle_dimensions.toml"

SMALL = """\
# A small sweep of the seed's T-handle spun near its crossbar
body = "t-handle"

[sweep]
cases = {cases}
seed = 5
sampling = "{sampling}"
chunk = {chunk}

[[dispersion]]
target = "preset"
field = "crossbar_length"
relative = 0.05
distribution = "uniform"

[[dispersion]]
target = "axes"
absolute = 0.01

[initial]
omega = [10.0, 0.1, 0.1]
frame = "design"
distribution = "normal"
spread = [0.0, 0.05, 0.05]

[simulation]
t_end = 15.0
samples = 300

[criterion]
column = "flips"
min = 1
"""


def write(folder: Path, *, cases=40, chunk=8, sampling="random", name="small.toml", text=SMALL) -> Path:
    path = folder / name
    path.write_text(text.format(cases=cases, chunk=chunk, sampling=sampling))
    return path


def read_cases(path: Path) -> tuple[list[str], dict[str, np.ndarray]]:
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    header, body = rows[0], rows[1:]
    cols = {}
    for j, name in enumerate(header):
        values = [r[j] for r in body]
        try:
            cols[name] = np.array([float(v) for v in values])
        except ValueError:
            cols[name] = np.array(values)
    return header, cols


def test_a_sweep_writes_its_cases_summary_and_figure(tmp_path):
    from tumble.viz import figure_sweep

    out = tmp_path / "out"
    data = run_sweep(write(tmp_path), out, figure=figure_sweep, argv=["sweep", "small.toml", "--out", "out"])
    try:
        import pyarrow  # noqa: F401
        table = ["cases.parquet"]
    except ImportError:
        table = []
    assert sorted(p.name for p in out.iterdir()) == ["cases.csv", *table, "summary.json", "sweep.png"]
    assert not (tmp_path / "out.resume").exists()  # removed once the output is in place
    header, cols = read_cases(out / "cases.csv")
    assert header[:7] == ["case", "I1 [kg m^2]", "I2 [kg m^2]", "I3 [kg m^2]", "omega0_1 [rad/s]",
                          "omega0_2 [rad/s]", "omega0_3 [rad/s]"]
    assert {"flips", "flip_period [s]", "crossbar_length [m]", "axes_rotvec_x [rad]"} <= set(header)
    assert cols["case"].tolist() == list(range(40))
    summary = json.loads((out / "summary.json").read_text())
    assert summary == json.loads(json.dumps(data))
    assert summary["provenance"]["command"] == "tumble sweep small.toml --out out"
    # the streaming statistics are those of the whole table (all 40 cases in the sample: exact)
    for name, column in (("flip_period", "flip_period [s]"), ("max_nutation", "max_nutation [rad]"),
                         ("I2", "I2 [kg m^2]")):
        x = cols[column][np.isfinite(cols[column])]
        s = summary["statistics"][name]
        assert s["count"] == len(x) and s["quantile_rank_error"] == 0.0
        assert s["mean"] == pytest.approx(x.mean(), rel=1e-13)
        assert s["std"] == pytest.approx(x.std(ddof=1), rel=1e-10)
        assert s["quantiles"]["0.5"] == pytest.approx(np.median(x), rel=1e-15)
        assert (s["min"], s["max"]) == (x.min(), x.max())
    c = summary["criterion"]
    failed = int(np.sum(~(cols["flips"] >= 1)))
    assert (c["passed"], c["failed"]) == (40 - failed, failed)
    assert c["success_lower_bound"] == success_lower_bound(40, failed, 0.9)
    assert summary["counts"]["predicted"] == {"unstable": 40}


def test_parquet_holds_the_same_table(tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    out = tmp_path / "out"
    run_sweep(write(tmp_path, cases=20), out)
    table = pq.read_table(out / "cases.parquet")
    header, cols = read_cases(out / "cases.csv")
    assert table.column_names == header
    for name in header:
        column = table.column(name).to_numpy()
        if column.dtype.kind in "fi":
            assert np.array_equal(column.astype(float), cols[name], equal_nan=True), name
        else:
            assert column.tolist() == cols[name].tolist()


@pytest.mark.filterwarnings("ignore:cases = 37 is not a power of 2")  # 37: a count no chunk size divides
@pytest.mark.parametrize("sampling", ["random", "lhs", "sobol"])
def test_cases_csv_is_byte_for_byte_the_same_whatever_the_chunk_size(tmp_path, sampling):
    texts, stats = [], []
    for chunk in (3, 16, 64):
        folder = tmp_path / f"c{chunk}"
        folder.mkdir()
        data = run_sweep(write(folder, cases=37, chunk=chunk, sampling=sampling), folder / "out")
        texts.append((folder / "out" / "cases.csv").read_bytes())
        stats.append((data["statistics"], data["counts"], data["criterion"]))
    assert texts[0] == texts[1] == texts[2]
    assert stats[0] == stats[1] == stats[2]


def test_an_interrupted_sweep_resumes_from_its_finished_chunks_byte_for_byte(tmp_path, monkeypatch):
    path = write(tmp_path, cases=40, chunk=8)
    computed = []
    original = sweep_module.compute_chunk

    def interrupted(sweep, start, stop):
        if len(computed) == 2:
            raise KeyboardInterrupt  # Ctrl-C during the third chunk
        computed.append(start)
        return original(sweep, start, stop)

    monkeypatch.setattr(sweep_module, "compute_chunk", interrupted)
    with pytest.raises(KeyboardInterrupt):
        run_sweep(path, tmp_path / "out")
    assert not (tmp_path / "out").exists()  # nothing half-written
    resume = tmp_path / "out.resume"
    assert sorted(p.name for p in resume.glob("chunk-*.npz")) == ["chunk-000000.npz", "chunk-000001.npz"]

    def counting(sweep, start, stop):
        computed.append(start)
        return original(sweep, start, stop)

    monkeypatch.setattr(sweep_module, "compute_chunk", counting)
    data = run_sweep(path, tmp_path / "out")
    assert computed == [0, 8, 16, 24, 32] and data["resumed_chunks"] == 2  # three more chunks
    assert not resume.exists()
    fresh = tmp_path / "fresh"
    fresh.mkdir()
    run_sweep(write(fresh, cases=40, chunk=8), fresh / "out")
    assert (tmp_path / "out" / "cases.csv").read_bytes() == (fresh / "out" / "cases.csv").read_bytes()


def test_chunks_of_another_sweep_are_not_resumed(tmp_path, monkeypatch):
    path = write(tmp_path, cases=16, chunk=8)
    original = sweep_module.compute_chunk

    def once(sweep, start, stop):
        if start:
            raise KeyboardInterrupt
        return original(sweep, start, stop)

    monkeypatch.setattr(sweep_module, "compute_chunk", once)
    with pytest.raises(KeyboardInterrupt):
        run_sweep(path, tmp_path / "out")
    assert len(list((tmp_path / "out.resume").glob("chunk-*.npz"))) == 1
    monkeypatch.undo()
    write(tmp_path, cases=16, chunk=8, text=SMALL.replace("seed = 5", "seed = 6"))  # another sweep, same file
    with pytest.warns(ResumeWarning, match=r"out\.resume held 1 chunk\(s\) of another sweep"):
        data = run_sweep(path, tmp_path / "out")
    assert data["resumed_chunks"] == 0 and data["seed"] == 6


def test_the_command_prints_one_line(tmp_path, capsys):
    assert run_sweep_command(write(tmp_path), tmp_path / "out") == 0
    line = capsys.readouterr().out
    assert line.count("\n") == 1
    assert line.startswith("40 cases (exact): 40 predicted unstable; 40 flipped (100 %, 95 % interval 91.19 to 100 %); "
                           "flip period median ")  # the fraction that flips with its interval (issue 27 item 9)
    assert f"wrote {tmp_path / 'out'}/" in line and "success probability >= " in line


@pytest.mark.parametrize(("change", "message"), [
    (("[sweep]", "[sweep]\nworkers = 2"), r"small\.toml: sweep: unknown key 'workers'; allowed: cases, chunk, max_resamples, "
                                          r"sampling, seed$"),
    (("target = \"axes\"", "target = \"tilt\""), r"small\.toml: dispersion\[1\]: target = 'tilt' is unknown; allowed: "),
    (("absolute = 0.01", "absolute = 0.01\nrelative = 0.1"), r"small\.toml: dispersion\[1\]: give relative = "),
    (("field = \"crossbar_length\"", "field = \"bar_length\""),
     r"small\.toml: dispersion\[0\] \(bar_length\): preset 't-handle' has no parameter 'bar_length'; allowed: "),
    (("sampling = \"{sampling}\"", "sampling = \"grid\""),
     r"small\.toml: sweep: sampling = 'grid' is unknown; allowed: random, lhs, sobol$"),
    (("samples = 300", "samples = 1"), r"small\.toml: simulation: samples = 1 must be a whole number from 2 to "),
    (("[criterion]\ncolumn = \"flips\"", "[criterion]\ncolumn = \"flops\""),
     r"small\.toml: criterion: column = 'flops' is not a column of the cases; allowed: case, "),
    (("t_end = 15.0", "t_end = 15.0\nmethod = \"autoo\""), r"small\.toml: simulation: method = 'autoo' is unknown; "),
    (("t_end = 15.0", "t_end = 15.0\nmethod = \"geometric\""), r"small\.toml: simulation: method = 'geometric' needs a "
                                                               r"step \(s\) in a sweep"),
    (("chunk = {chunk}", "chunk = 0"), r"small\.toml: sweep: chunk = 0 must be a whole number >= 1 \(cases per chunk\)$"),
    (("t_end = 15.0", "t_end = 15.0\nmethod = \"geometric\"\nstep = 0.0"),
     r"small\.toml: simulation: step = 0\.0 must be a positive finite number \(s\)$"),
    (("min = 1", "min = 5\nmax = 1"),
     r"small\.toml: criterion: min = 5 is above max = 1: no case could succeed; allowed: min <= max$"),
    (("distribution = \"normal\"\nspread", "spread"),
     r"small\.toml: initial: spread = \[0\.0, 0\.05, 0\.05\] needs distribution = \(one of normal, uniform\): "),
    (("cases = {cases}", "cases = 1000000000000000000"),
     r"small\.toml: sweep: cases = 1000000000000000000 must be a whole number from 1 to 100000000$"),
    (("cases = {cases}", "cases = 1e3"), r"small\.toml: sweep: cases = 1000\.0 must be a whole number from 1 to 100000000$"),
    # 5 for 5 %: it ran, redrawing tens of thousands of lengths drawn negative (seen 2026-11-30)
    (("relative = 0.05", "relative = 5"), r"small\.toml: dispersion\[0\]: relative = 5 is a relative spread of 500 %, "
                                          r"which draws the quantity at zero or with the other sign: give a fraction "
                                          r"\(0\.05 for 5 %\), below 1$"),
])
def test_bad_sweep_files_are_refused_in_one_line_before_anything_is_written(tmp_path, change, message):
    old, new = change
    assert old in SMALL
    path = write(tmp_path, text=SMALL.replace(old, new))
    with pytest.raises(ValueError, match=message) as info:
        run_sweep(path, tmp_path / "out")
    assert "\n" not in str(info.value)
    assert not (tmp_path / "out").exists() and not (tmp_path / "out.resume").exists()


def test_an_impossible_dispersion_is_refused_naming_the_case(tmp_path):
    text = SMALL.replace('target = "axes"\nabsolute = 0.01', 'target = "moments"\nrelative = 0.05')
    text = text.replace("[sweep]", "[sweep]\nmax_resamples = 0")
    with pytest.raises(ValueError, match=r"small\.toml: case 0: no physical body in 1 draw\(s\)|case \d+: no physical"):
        run_sweep(write(tmp_path, text=text), tmp_path / "out")


def test_the_example_sweep_runs_and_every_flip_matches_the_elliptic_period(tmp_path):
    parsed = load_sweep(EXAMPLE)
    assert parsed.sweep.ensemble.cases == 4096 and parsed.sweep.ensemble.sampling == "sobol"
    data = run_sweep(EXAMPLE, tmp_path / "out")   # ~4 s on one core (benchmarks/, not a test, times it)
    _, cols = read_cases(tmp_path / "out" / "cases.csv")
    assert len(cols["case"]) == 4096 and data["redraws"] == 0
    # every dimension within +-5 % of the nominal (uniform), the masses following (density)
    for name, nominal in (("shaft_length [m]", 0.08), ("crossbar_radius [m]", 0.006)):
        assert np.all(np.abs(cols[name] / nominal - 1) <= 0.05)
    # a case spun about its intermediate axis flips at the exact elliptic interval, to the sampling
    both = np.isfinite(cols["flip_period [s]"]) & np.isfinite(cols["flip_period_exact [s]"])
    assert both.sum() > 3900
    ratio = cols["flip_period [s]"][both] / cols["flip_period_exact [s]"][both]
    assert np.max(np.abs(ratio - 1)) < 0.01
    # where the dimensions make the shaft the minor axis the spin is stable: no flip period
    stable = cols["predicted"] == "stable"
    assert np.all(cols["axis"][stable] != 2) and np.all(np.isnan(cols["flip_period_exact [s]"][stable]))
    assert data["counts"]["predicted"]["stable"] == int(stable.sum())
    assert math.isclose(data["criterion"]["success_lower_bound"],
                        success_lower_bound(4096, data["criterion"]["failed"], 0.9))


# --- the Dask backend (pip install 'tumble[cluster]') ----------------------------------------

def test_without_dask_workers_are_refused_in_one_line(monkeypatch):
    import sys

    from tumble.ensemble import make_backend

    monkeypatch.setitem(sys.modules, "dask.distributed", None)  # as if not installed
    with pytest.raises(ImportError, match=r"^a Dask backend \(workers/scheduler\) needs dask: pip install 'tumble\[cluster\]'$"):
        make_backend(workers=2)
    with pytest.raises(ValueError, match=r"^give workers \(a local Dask cluster\) or scheduler \(a running one\), not both$"):
        make_backend(workers=2, scheduler="tcp://127.0.0.1:8786")


def test_a_local_dask_cluster_writes_the_same_cases(tmp_path):
    pytest.importorskip("dask.distributed")
    path = write(tmp_path, cases=40, chunk=8, sampling="lhs")
    here = run_sweep(path, tmp_path / "here")
    there = run_sweep(path, tmp_path / "there", workers=2)
    assert there["backend"] == "dask local cluster of 2 workers" and here["backend"] == "in-process"
    assert (tmp_path / "here" / "cases.csv").read_bytes() == (tmp_path / "there" / "cases.csv").read_bytes()
    assert here["statistics"] == there["statistics"]


@pytest.mark.filterwarnings("ignore:cases = 24 is not a power of 2")
def test_a_running_dask_scheduler_writes_the_same_cases(tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    path = write(tmp_path, cases=24, chunk=5, sampling="sobol")
    here = run_sweep(path, tmp_path / "here")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster:
        there = run_sweep(path, tmp_path / "there", scheduler=cluster.scheduler_address)
    assert there["backend"] == f"dask scheduler {cluster.scheduler_address}"
    assert (tmp_path / "here" / "cases.csv").read_bytes() == (tmp_path / "there" / "cases.csv").read_bytes()
    assert here["criterion"] == there["criterion"]


def test_the_sweep_and_map_commands(tmp_path, capsys, monkeypatch):
    """`tumble sweep` runs the shipped example through the CLI (one line, exit 0, the files);
    `tumble map` draws the map; bad options are one line and exit 2."""
    from tumble.cli import main

    out = tmp_path / "sweep"
    assert main(["sweep", str(EXAMPLE), "--out", str(out)]) == 0
    line = capsys.readouterr().out
    assert line.startswith("4096 cases") and "success probability" in line
    assert {"cases.csv", "summary.json", "sweep.png"} <= {p.name for p in out.iterdir()}
    assert not (tmp_path / "sweep.resume").exists()
    assert main(["map", "--out", str(tmp_path / "map.png"), "--resolution", "40"]) == 0
    assert (tmp_path / "map.png").stat().st_size > 5_000
    assert capsys.readouterr().out.rstrip().endswith("perturbation 0.01, 0.01 rad/s")
    # what it says is what it draws: 0.01 rad/s about the minor and major axes of a 10 rad/s spin, a tenth of a
    # percent of the spin (the map's own perturbation is in fractions of the spin); a zero one is allowed
    import matplotlib.pyplot as plt

    from tumble.viz import figure_stability_map

    drawn = {}
    real = figure_stability_map

    def spy(spin, perturbation, **kw):
        drawn.update(spin=spin, perturbation=perturbation)
        return real(spin, perturbation, **kw)

    import tumble.viz

    monkeypatch.setattr(tumble.viz, "figure_stability_map", spy)
    assert main(["map", "--out", str(tmp_path / "m0.png"), "--resolution", "20", "--perturbation", "0", "0.02"]) == 0
    assert drawn == {"spin": 10.0, "perturbation": (0.0, 0.002)}
    plt.close("all")
    for argv in (["map", "--out", str(tmp_path / "m.png"), "--spin", "-1"],
                 ["map", "--out", str(tmp_path / "m.png"), "--perturbation", "0", "0"],
                 ["sweep", str(EXAMPLE), "--out", str(tmp_path / "s2"), "--workers", "2", "--scheduler", "tcp://x:1"]):
        capsys.readouterr()
        assert main(argv) == 2
        assert capsys.readouterr().err.count("\n") == 1


def test_the_map_names_both_figure_suffixes_it_writes(tmp_path, capsys):
    """--out map.pdf was told "written as one .png file" where --help says .png or .svg (seen 2026-12-02)."""
    from tumble.cli import main

    assert main(["map", "--out", str(tmp_path / "map.pdf")]) == 2
    assert capsys.readouterr().err.rstrip("\n").endswith(
        "map.pdf: the output is written as one .png or .svg file; give a name ending in .png or .svg")
    assert list(tmp_path.iterdir()) == []


def test_a_geometric_sweep_is_byte_for_byte_the_same_whatever_the_chunk_size(tmp_path):
    text = SMALL.replace("t_end = 15.0\nsamples = 300", 't_end = 1.0\nsamples = 20\nmethod = "geometric"\nstep = 0.01')
    texts = []
    for chunk in (10, 512):
        folder = tmp_path / f"c{chunk}"
        folder.mkdir()
        run_sweep(write(folder, cases=512, chunk=chunk, text=text.replace("[criterion]\ncolumn = \"flips\"\nmin = 1\n", "")),
                  folder / "out")
        texts.append((folder / "out" / "cases.csv").read_bytes())
    assert texts[0] == texts[1]


def test_torque_tables_in_a_sweep_act_as_their_sum(tmp_path):
    """Two [[torque]] tables run the cases as the one [torque] of their sum does (byte for byte: a sum of
    constant body torques is one vector for the engine), and not as the torque-free sweep."""
    from tumble.dynamics import TorqueSum

    method = 't_end = 15.0\nmethod = "dop853"'
    base = SMALL.replace("t_end = 15.0", method).replace('frame = "design"', 'frame = "principal"').replace(
        "omega = [10.0, 0.1, 0.1]", "omega = [0.1, 10.0, 0.1]")   # a body-frame torque: principal axes
    two = base + '[[torque]]\nvector = [0.0, 0.0, 0.25]\n[[torque]]\nvector = [0.5, 0.0, 0.0]\n'
    one = base + "[torque]\nvector = [0.5, 0.0, 0.25]\n"
    paths = [write(tmp_path, cases=8, name=f"{name}.toml", text=text)
             for name, text in (("two", two), ("one", one), ("free", base))]
    assert isinstance(load_sweep(paths[0]).sweep.settings.torque, TorqueSum)
    tables = []
    for path in paths:
        run_sweep(path, tmp_path / path.stem, argv=["sweep", path.name, "--out", path.stem])
        tables.append((tmp_path / path.stem / "cases.csv").read_bytes())
    assert tables[0] == tables[1] and tables[0] != tables[2]


def test_a_sweep_file_takes_method_auto_its_default(tmp_path):
    """method = "auto", the key reference's default, was refused as unknown in a sweep file."""
    auto = load_sweep(write(tmp_path, text=SMALL.replace("t_end = 15.0", "t_end = 15.0\nmethod = \"auto\"")))
    assert auto.sweep.settings.method == load_sweep(write(tmp_path, name="default.toml")).sweep.settings.method == "exact"


def test_a_sobol_sweep_of_other_than_a_power_of_two_is_said_to_be(tmp_path):
    """4000 Sobol' cases ran without a word, though the example file says 4096 = 2^12 is balanced."""
    said = []
    run_sweep(write(tmp_path, cases=12, chunk=4, sampling="sobol"), tmp_path / "out", warn=said.append)
    assert said == ["cases = 12 is not a power of 2: a Sobol' set is balanced at 8 or 16 cases, and 12 cover the "
                    "space less evenly"]
    said.clear()
    run_sweep(write(tmp_path, cases=16, chunk=4, sampling="sobol", name="b.toml"), tmp_path / "out16", warn=said.append)
    assert said == []


def test_a_sweep_refuses_a_chunk_too_big_for_its_samples_before_it_starts_and_warns_of_axes_in_degrees(tmp_path):
    """A walkthrough of the sweep docs (2026-12-03): samples = 100000 failed after the run began, naming
    "the batch" and leaving DIR.resume behind; an axes spread of 5 (meant as degrees) ran silently,
    the flip rate 98.7 % -> 44 %."""
    import warnings

    from tumble.ensemble.dispersions import Dispersion
    from tumble.io.sweepfile import sweep_from_table
    from tumble.mass import UnitSlipWarning

    table = {"body": "t-handle", "sweep": {"cases": 2048}, "simulation": {"t_end": 20.0, "samples": 100000},
             "initial": {"omega": [0.1, 10.0, 0.1], "distribution": "normal", "spread": [0.01, 0.0, 0.01]}}
    with pytest.raises(ValueError, match=r"^simulation: 100000 samples a case with sweep.chunk = 1024 is 102,400,000 "
                                         r"samples a chunk, more than 50,000,000; give chunk = 500 or less"):
        sweep_from_table(table)
    assert sweep_from_table({**table, "sweep": {"cases": 2048, "chunk": 500}}).chunk == 500
    with pytest.warns(UnitSlipWarning, match=r'^target "axes": absolute spread = 5.0 rad is past 1 rad \(57 deg\), '
                                             r"principal axes not known at all: is it in degrees\? Write radians "
                                             r"\(5.0 deg is 0.08727 rad\)"):
        Dispersion("axes", 5.0, relative=False)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Dispersion("axes", 0.02, relative=False)


def test_a_long_sweep_says_after_its_first_chunk_how_long_the_rest_will_take(monkeypatch, capsys, tmp_path):
    """67 million cases ran silently towards ~27 h (a walkthrough, 2026-12-03): after the first chunk,
    a sweep whose rest takes more than LONG_SWEEP_S says how long, and how to stop and resume it."""
    import tumble.commands.sweep as module

    clock = iter([0.0, 1.5, 3.0, 4.5])
    monkeypatch.setattr(module.time, "perf_counter", lambda: next(clock))
    written = []
    passed = module._timed(written.append, 1000, 1024, tmp_path / "o.resume")
    passed({"case": [0]})
    passed({"case": [1]})
    assert written == [{"case": [0]}, {"case": [1]}]
    err = capsys.readouterr().err
    assert err == (f"note: a chunk of 1024 cases took 1.5 s: the other 999 take about 25 min more; Ctrl-C keeps the "
                   f"finished chunks in {tmp_path / 'o.resume'}/, and the same command resumes\n")
    clock = iter([0.0, 1.5])
    module._timed(written.append, 10, 1024, tmp_path / "o.resume")({"case": [0]})   # 13.5 s more: nothing said
    assert capsys.readouterr().err == ""


def test_a_sweep_takes_the_tolerances_a_scenario_takes():
    """A sweep's [simulation] refused rtol ("unknown key"), leaving no way to set a dop853 sweep's
    accuracy (a walkthrough, 2026-12-03): rtol and atol are taken, run by every case and part of
    the fingerprint a resumed sweep is matched by."""
    import numpy as np

    from tumble import t_handle
    from tumble.ensemble import BodySampler, Ensemble, InitialRates
    from tumble.io.sweepfile import sweep_from_table

    table = {"body": "t-handle", "sweep": {"cases": 1}, "initial": {"omega": [0.1, 10.0, 0.1]},
             "simulation": {"t_end": 2.0, "samples": 5, "method": "dop853", "rtol": 1e-6, "atol": 1e-6},
             "torque": {"kind": "constant", "vector": [0.0, 0.0, 0.01]}}
    loose = sweep_from_table(table)
    assert (loose.sweep.settings.rtol, loose.sweep.settings.atol) == (1e-6, 1e-6)
    tight = sweep_from_table({**table, "simulation": {**table["simulation"], "rtol": 1e-12, "atol": 1e-12}})
    assert loose.fingerprint() != tight.fingerprint()
    inputs = Ensemble(BodySampler(t_handle()), InitialRates(omega=(0.1, 10.0, 0.1)), cases=2).inputs()
    a, b = loose.sweep.settings.run(inputs), tight.sweep.settings.run(inputs)
    assert 1e-9 < float(np.max(np.abs(a.omega - b.omega))) < 1e-3  # the tolerance reaches the integration


def test_a_sweep_sampled_too_coarsely_for_its_flips_says_so(tmp_path, capsys):
    """A walkthrough of the sweeps (2026-12-03): spun 57 times faster (573 rad/s, a deg/s number typed as rad/s), the
    seed's T-handle flips every ~0.03 s, and 300 samples over 15 s (0.05 s apart) counted a fraction of the flips and a
    flip period twice too long without a word, where tumble simulate says "too few samples to count flips". Each case's
    samples_per_flip is written (the exact interval over the spacing) and the line and summary.json count the cases
    below 4; the flips they counted are indeed not the elliptic interval's."""
    path = write(tmp_path, text=SMALL.replace("omega = [10.0, 0.1, 0.1]", "omega = [573.0, 5.7, 5.7]"))
    assert run_sweep_command(path, tmp_path / "out") == 0
    line = capsys.readouterr().out
    data = json.loads((tmp_path / "out" / "summary.json").read_text())
    _, cols = read_cases(tmp_path / "out" / "cases.csv")
    spacing = 15.0 / 299
    np.testing.assert_allclose(cols["samples_per_flip"], cols["flip_period_exact [s]"] / spacing, rtol=1e-9)
    assert np.all(cols["samples_per_flip"] < 4) and data["flipped"]["aliased"] == 40
    assert "40 cases sampled fewer than 4 times a flip" in line and "may be miscounted, give more samples" in line, line
    assert "but 40 of the 40 cases were sampled fewer than 4 times a flip" in data["flipped"]["statement"]
    assert np.all(np.abs(cols["flips"] - 15.0 / cols["flip_period_exact [s]"]) > 5)  # miscounted indeed
    assert run_sweep_command(write(tmp_path, name="slow.toml"), tmp_path / "slow") == 0  # 36 samples a flip: no word
    assert "miscounted" not in capsys.readouterr().out
    assert json.loads((tmp_path / "slow" / "summary.json").read_text())["flipped"]["aliased"] == 0


def _elliptic_flip_interval(I: np.ndarray, w: np.ndarray) -> np.ndarray:
    """The torque-free time between flips, s, written here: T/2 = 2 K(m) / p with p and m from the
    energy and momentum (Landau & Lifshitz, Mechanics, sec. 37), for spins that circulate either axis."""
    from scipy.special import ellipk

    I1, I2, I3 = I.T
    L2, E2 = np.sum((I * w) ** 2, axis=1), np.sum(I * w * w, axis=1)
    major = L2 > E2 * I2   # circulating the major axis: L&L's case; else 1 and 3 swap
    a, c = np.where(major, I3, I1), np.where(major, I1, I3)
    p = np.sqrt((a - I2) * (L2 - c * E2) / (I1 * I2 * I3))
    m = (I2 - c) * (a * E2 - L2) / ((a - I2) * (L2 - c * E2))
    return 2.0 * ellipk(m) / p


def test_a_torqued_sweep_sampled_too_coarsely_says_so(tmp_path, capsys):
    """A walkthrough of the sweeps (2026-12-03): the T-handles under a small body torque, 2 samples over 20 s,
    "9 flipped (56.25 %)" with no word, where each flipped 10-13 times (its DOP853): under a torque only a
    counted interval was judged, and aliased samples count none. The start's torque-free interval (computed
    here) now bounds it: every case is said to be aliased."""
    text = (SMALL.replace("samples = 300", "samples = 2").replace("t_end = 15.0", "t_end = 20.0")
            .replace('frame = "design"', 'frame = "principal"').replace("omega = [10.0, 0.1, 0.1]", "omega = [0.1, 10.0, 0.1]")
            + '\n[torque]\nvector = [0.0, 0.0, 1e-4]\nframe = "body"\n')
    path = write(tmp_path, cases=16, text=text)
    assert run_sweep_command(path, tmp_path / "out") == 0
    line = capsys.readouterr().out
    _, cols = read_cases(tmp_path / "out" / "cases.csv")
    I = np.column_stack([cols[f"I{k} [kg m^2]"] for k in (1, 2, 3)])
    w = np.column_stack([cols[f"omega0_{k} [rad/s]"] for k in (1, 2, 3)])
    free = _elliptic_flip_interval(I, w)
    assert np.all(20.0 / free > 9)   # each flips ~10 times in the run: 2 samples cannot count them
    assert np.all(cols["samples_per_flip"] <= free / 20.0 * (1 + 1e-9))
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["flipped"]["aliased"] == 16
    assert "16 cases sampled fewer than 4 times a flip" in line, line


def test_a_body_at_rest_is_not_predicted_unstable(tmp_path, capsys):
    """omega = 0 came out "predicted unstable" about axis 1 (stability_report: at rest, no spin axis)."""
    text = SMALL.replace("omega = [10.0, 0.1, 0.1]", "omega = [0.0, 0.0, 0.0]").replace(
        'distribution = "normal"\nspread = [0.0, 0.05, 0.05]\n', "")
    assert run_sweep_command(write(tmp_path, cases=8, text=text), tmp_path / "out") != 2
    line = capsys.readouterr().out
    _, cols = read_cases(tmp_path / "out" / "cases.csv")
    assert cols["predicted"].tolist() == ["at rest"] * 8 and np.all(cols["axis"] == 0) and np.all(cols["circulation"] == 0)
    assert line.startswith("8 cases (exact): 0 predicted unstable (8 at rest)"), line


def test_copies_of_a_deterministic_run_are_not_counted_as_trials(tmp_path):
    """A walkthrough of the sweeps (2026-12-03): a grid of 2 points with cases = 1000 and nothing dispersed
    reported "95 % interval 99.63 to 100 %" over 1000 copies of 2 runs; refused, naming what to give."""
    text = SMALL.replace("omega = [10.0, 0.1, 0.1]", "grid = [[10.0], [0.01, 0.5], [0.01]]").replace(
        'distribution = "normal"\nspread = [0.0, 0.05, 0.05]\n', "")
    text = text.split("[[dispersion]]")[0] + "[initial]" + text.split("[initial]")[1]
    with pytest.raises(ValueError, match=r"sweep: cases = 1000 repeats the 2 initial rate\(s\) with nothing dispersed: "
                                         r"copies of one deterministic run are not trials.*give cases = 2"):
        load_sweep(write(tmp_path, cases=1000, text=text))
    assert load_sweep(write(tmp_path, cases=2, text=text, name="two.toml")).sweep.ensemble.cases == 2


def test_a_body_frame_torque_in_design_axes_is_refused(tmp_path):
    """A sweep's body-frame vector acts along each case's principal axes, which its dispersions turn and
    reorder; initial.frame = "design" made a scenario file read it in design axes, and the sweep did not:
    a thruster along design x in one case pushed along the shaft in another (a walkthrough, 2026-12-03)."""
    torque = '\n[torque]\nvector = [0.0, 0.0, 1e-4]\nframe = "body"\n'
    with pytest.raises(ValueError, match=r'torque: a body-frame vector in a sweep acts along each case\'s principal axes'):
        load_sweep(write(tmp_path, text=SMALL + torque))
    load_sweep(write(tmp_path, text=SMALL + torque.replace('"body"', '"world"'), name="world.toml"))
    load_sweep(write(tmp_path, text=SMALL.replace('frame = "design"', 'frame = "principal"') + torque, name="p.toml"))


def test_a_criterion_on_a_text_column_is_refused_naming_it(tmp_path):
    """column = "predicted" (stable / unstable) failed with numpy's "could not convert string to float:
    np.str_('unstable')"."""
    text = SMALL.replace('column = "flips"', 'column = "predicted"')
    with pytest.raises(ValueError, match=r"column = 'predicted' holds text \(unstable\), not numbers to bound with min "
                                         r"and max; allowed: .*flips"):
        run_sweep(write(tmp_path, cases=4, text=text), tmp_path / "out", argv=["sweep"])
    assert not (tmp_path / "out").exists()


def test_the_map_takes_what_stability_map_takes_and_no_perturbation_beyond_the_spin(tmp_path, capsys):
    """--perturbation 20 0.01 on a 10 rad/s spin was mapped and titled "spin 10 rad/s about the intermediate
    axis"; --resolution took 20 to 2000 where stability_map takes 10 to 2000 (a walkthrough, 2026-12-03)."""
    from tumble.cli import main
    from tumble.ensemble.reductions import stability_map

    assert main(["map", "--out", str(tmp_path / "m.png"), "--perturbation", "20", "0.01"]) == 2
    assert "--perturbation[0] = 20 is beyond 9.99 rad/s" in capsys.readouterr().err
    assert not (tmp_path / "m.png").exists()
    with pytest.raises(ValueError, match="must be fractions of the spin below 1"):
        stability_map(10.0, (2.0, 0.001))
    assert main(["map", "--out", str(tmp_path / "m.png"), "--resolution", "10"]) == 0 and (tmp_path / "m.png").is_file()


def test_a_sweep_refused_before_its_first_chunk_leaves_no_resume_folder(tmp_path, capsys):
    """A refused scheduler (exit 2, "nothing written") left DIR.resume/ with its fingerprint and lock behind
    (a QA walkthrough, 2026-12-03); with finished chunks, the folder stays for the next run."""
    from tumble.cli import main

    path = write(tmp_path, cases=8)
    assert main(["sweep", str(path), "--out", str(tmp_path / "y"), "--scheduler", "nonsense"]) == 2
    capsys.readouterr()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["small.toml"]
