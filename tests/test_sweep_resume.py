"""The resume folder of a sweep (DIR.resume/): fingerprint, lock, checked chunks, no links."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

import tumble.ensemble.sweep as sweep_module
from tumble.io.provenance import file_sha256
from tumble.io.resume import ResumeWarning
from tumble.commands.sweep import run_sweep, run_sweep_command
from limits import HANG_S

SWEEP = """\
# A small sweep of {body_comment}
body = {body}

[sweep]
cases = {cases}
seed = {seed}
chunk = {chunk}

[[dispersion]]
target = "moments"
relative = 0.02

[initial]
omega = [0.1, 5.0, 0.1]

[simulation]
t_end = 2.0
samples = 40
"""


def sweep_file(folder: Path, *, name="s.toml", cases=32, chunk=8, seed=3, body='"t-handle"') -> Path:
    path = folder / name
    path.write_text(SWEEP.format(body_comment=body.strip('"'), body=body, cases=cases, seed=seed, chunk=chunk))
    return path


def fresh_csv(path: Path, folder: Path) -> bytes:
    """cases.csv of an uninterrupted run of ``path`` (into its own folder)."""
    run_sweep(path, folder / "fresh")
    return (folder / "fresh" / "cases.csv").read_bytes()


def interrupt_after(monkeypatch, chunks: int) -> list:
    """Ctrl-C as the chunk after ``chunks`` computed ones starts; returns the starts computed."""
    original, computed = sweep_module.compute_chunk, []

    def interrupted(sweep, start, stop):
        if len(computed) == chunks:
            raise KeyboardInterrupt
        computed.append(start)
        return original(sweep, start, stop)

    monkeypatch.setattr(sweep_module, "compute_chunk", interrupted)
    return computed


def interrupted_run(monkeypatch, path: Path, out: Path, chunks: int) -> None:
    interrupt_after(monkeypatch, chunks)
    with pytest.raises(KeyboardInterrupt):
        run_sweep(path, out)
    monkeypatch.undo()


# --- 1. every input that changes a result is in the fingerprint and the provenance ----------

def box_stl(path: Path, extents) -> None:
    trimesh = pytest.importorskip("trimesh")
    trimesh.creation.box(extents=extents).export(path)


def test_a_changed_mesh_file_is_not_resumed_and_is_in_the_provenance(tmp_path, monkeypatch):
    box_stl(tmp_path / "box.stl", (0.1, 0.2, 0.4))
    body = '{ name = "brick", parts = [{ kind = "mesh", mesh = "box.stl", mass = 2.0 }] }'
    path = sweep_file(tmp_path, cases=16, chunk=2, body=body)
    interrupted_run(monkeypatch, path, tmp_path / "out", 7)  # 7 of 8 chunks
    assert len(list((tmp_path / "out.resume").glob("chunk-*.npz"))) == 7
    box_stl(tmp_path / "box.stl", (0.1, 0.25, 0.4))  # the STL changes, the sweep file does not
    with pytest.warns(ResumeWarning, match="another sweep"):
        data = run_sweep(path, tmp_path / "out")
    assert data["resumed_chunks"] == 0
    assert (tmp_path / "out" / "cases.csv").read_bytes() == fresh_csv(path, tmp_path)
    inputs = data["provenance"]["inputs"]
    assert inputs[str(tmp_path / "box.stl")] == file_sha256(tmp_path / "box.stl")
    assert inputs[str(path)] == file_sha256(path)


def test_a_mesh_in_a_body_file_is_in_the_provenance(tmp_path):
    (tmp_path / "bodies").mkdir()
    box_stl(tmp_path / "bodies" / "box.stl", (0.1, 0.2, 0.4))
    (tmp_path / "bodies" / "brick.toml").write_text(
        '[body]\nname = "brick"\n[[body.parts]]\nkind = "mesh"\nmesh = "box.stl"\nmass = 2.0\n')
    data = run_sweep(sweep_file(tmp_path, cases=4, chunk=4, body='"bodies/brick.toml"'), tmp_path / "out")
    assert set(data["provenance"]["inputs"]) == {str(tmp_path / "s.toml"), str(tmp_path / "bodies" / "brick.toml"),
                                                 str(tmp_path / "bodies" / "box.stl")}


# --- 2. one run at a time per --out; another sweep's chunks never reused -----------------------

@pytest.mark.parametrize("other", ["the same sweep", "another sweep"])
def test_a_second_run_into_the_same_out_is_refused_while_the_first_runs(tmp_path, monkeypatch, other):
    path = sweep_file(tmp_path)
    second = path if other == "the same sweep" else sweep_file(tmp_path, name="t.toml", seed=4)
    original, refusals = sweep_module.compute_chunk, []

    def meanwhile(sweep, start, stop):  # while the first run computes chunk 2, the second starts
        if start == 16:
            with pytest.raises(ValueError) as info:
                run_sweep(second, tmp_path / "out")
            refusals.append(str(info.value))
        return original(sweep, start, stop)

    monkeypatch.setattr(sweep_module, "compute_chunk", meanwhile)
    run_sweep(path, tmp_path / "out")
    monkeypatch.undo()
    (message,) = refusals
    assert message == (f"{tmp_path / 'out.resume'} is locked: another sweep is running into the same --out; "
                       "wait for it to finish or give another --out")
    assert (tmp_path / "out" / "cases.csv").read_bytes() == fresh_csv(path, tmp_path)
    assert not (tmp_path / "out.resume").exists()
    run_sweep(second, tmp_path / "out")  # once the first is done, the second runs
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["seed"] == (3 if second == path else 4)


def test_the_command_refuses_a_locked_resume_folder_in_one_line(tmp_path, capsys):
    import fcntl
    import os

    from tumble.cli import main

    path = sweep_file(tmp_path, cases=4, chunk=4)
    (tmp_path / "out.resume").mkdir()
    fd = os.open(tmp_path / "out.resume" / "lock", os.O_RDWR | os.O_CREAT)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)  # another run holds it
        assert main(["sweep", str(path), "--out", str(tmp_path / "out")]) == 2
    finally:
        os.close(fd)
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "out.resume is locked: another sweep is running" in err
    assert not (tmp_path / "out").exists()


def test_chunks_of_two_sweeps_mixed_in_one_folder_are_not_reused(tmp_path, monkeypatch):
    a, b = sweep_file(tmp_path, name="a.toml", seed=3), sweep_file(tmp_path, name="b.toml", seed=4)
    interrupted_run(monkeypatch, a, tmp_path / "out", 2)
    kept = {p.name: p.read_bytes() for p in (tmp_path / "out.resume").glob("chunk-*.npz")}
    with pytest.warns(ResumeWarning, match=r"out\.resume held 2 chunk\(s\) of another sweep"):
        interrupted_run(monkeypatch, b, tmp_path / "out", 1)  # b starts over: a's chunks discarded
    for name, content in kept.items():  # as two runs at once without a lock would have left it
        if name != "chunk-000000.npz":
            (tmp_path / "out.resume" / name).write_bytes(content)
    with pytest.warns(ResumeWarning, match=r"chunk-000001\.npz: belongs to another sweep"):
        data = run_sweep(b, tmp_path / "out")
    assert data["resumed_chunks"] == 1 and data["seed"] == 4
    assert (tmp_path / "out" / "cases.csv").read_bytes() == fresh_csv(b, tmp_path)


# --- 3. chunks are checked before they are reused ---------------------------------------------

def _copy(folder: Path) -> None:
    shutil.copy(folder / "chunk-000000.npz", folder / "chunk-000001.npz")


def _cut(folder: Path) -> None:  # the same file with 3 of its 8 rows, its record kept
    path = folder / "chunk-000001.npz"
    with np.load(path) as data:
        arrays = {k: (data[k][:3] if k.startswith("c") else data[k]) for k in data.files}
    np.savez(path, **arrays)


def _truncate(folder: Path) -> None:
    path = folder / "chunk-000001.npz"
    path.write_bytes(path.read_bytes()[:500])


@pytest.mark.parametrize(("tamper", "why"), [
    (_copy, r"holds cases 0 to 8 \(stop excluded\), not 8 to 16"),
    (_cut, r"its arrays do not match its checksum \(changed or cut\)"),
    (_truncate, r"cannot be read \(BadZipFile: File is not a zip file\)"),
])
def test_a_bad_chunk_is_named_and_computed_again(tmp_path, monkeypatch, tamper, why):
    path = sweep_file(tmp_path)
    interrupted_run(monkeypatch, path, tmp_path / "out", 3)  # 3 of 4 chunks
    tamper(tmp_path / "out.resume")
    computed = interrupt_after(monkeypatch, 99)
    with pytest.warns(ResumeWarning, match=rf"out\.resume/chunk-000001\.npz: {why}; computing it again"):
        data = run_sweep(path, tmp_path / "out")
    monkeypatch.undo()
    assert computed == [8, 24] and data["resumed_chunks"] == 2
    assert (tmp_path / "out" / "cases.csv").read_bytes() == fresh_csv(path, tmp_path)


def test_the_command_names_a_bad_chunk_in_one_warning_line(tmp_path, monkeypatch, capsys):
    path = sweep_file(tmp_path)
    interrupted_run(monkeypatch, path, tmp_path / "out", 3)
    _truncate(tmp_path / "out.resume")
    assert run_sweep_command(path, tmp_path / "out") == 0
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert err.startswith(f"warning: {tmp_path / 'out.resume' / 'chunk-000001.npz'}: cannot be read (BadZipFile")


# --- 4. nothing outside the output's folder is written or deleted -----------------------------

def test_a_resume_folder_that_is_a_symbolic_link_is_refused(tmp_path, capsys):
    from tumble.cli import main

    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "chunk-000000.npz").write_bytes(b"someone else's")
    (tmp_path / "out.resume").symlink_to(elsewhere)
    path = sweep_file(tmp_path, cases=4, chunk=4)
    with pytest.raises(ValueError, match=r"out\.resume is a symbolic link; tumble writes its resume chunks only "):
        run_sweep(path, tmp_path / "out")
    assert main(["sweep", str(path), "--out", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err.count("\n") == 1
    assert sorted(p.name for p in elsewhere.iterdir()) == ["chunk-000000.npz"]
    assert (elsewhere / "chunk-000000.npz").read_bytes() == b"someone else's"
    assert not (tmp_path / "out").exists()


def test_an_out_that_names_no_folder_is_refused_before_the_resume_folder_is_made(tmp_path, capsys):
    """``--out x/..`` was refused only at the end, after ``x/`` and ``x/...resume/`` were made."""
    path = sweep_file(tmp_path)
    before = sorted(p.name for p in tmp_path.rglob("*"))
    with pytest.raises(ValueError, match="does not name a folder of its own"):
        run_sweep(path, tmp_path / "x" / "..")
    assert sorted(p.name for p in tmp_path.rglob("*")) == before


WITHOUT_FCNTL = """
import os, subprocess, sys, types  # subprocess first: it reads a msvcrt as Windows
sys.modules["fcntl"] = None  # as on Windows: `import fcntl` raises ImportError
held = {}  # a stand-in for Windows's msvcrt: one lock per file, refused to a second open file

def locking(fd, mode, nbytes):
    st = os.fstat(fd)
    key = (st.st_dev, st.st_ino)
    if held.get(key, fd) != fd:
        raise PermissionError(13, "Permission denied")
    held[key] = fd

sys.modules["msvcrt"] = types.SimpleNamespace(locking=locking, LK_NBLCK=2, LK_LOCK=1)
import tumble.io.resume, tumble.io.output
from tumble.io.resume import ChunkFolder
folder = sys.argv[1]
store = ChunkFolder(folder + "/out.resume", {"sweep": 1}, cases=2, chunk=2)
try:
    ChunkFolder(folder + "/out.resume", {"sweep": 1}, cases=2, chunk=2)
except ValueError as exc:
    print("refused:", exc)
with tumble.io.output.output_dir(folder + "/out", owns=("a.txt",)) as stage:
    (stage / "a.txt").write_text("x")
print("fcntl" in sys.modules and sys.modules["fcntl"] is None, sorted(os.listdir(folder)))
"""


def test_resume_and_output_import_and_lock_without_fcntl(tmp_path):
    """Issue 27 item 10(d): no `fcntl` (Windows) -- the modules import and lock through msvcrt."""
    import subprocess
    import sys

    done = subprocess.run([sys.executable, "-c", WITHOUT_FCNTL, str(tmp_path)], capture_output=True, text=True,
                          timeout=HANG_S)
    assert done.returncode == 0, done.stderr
    refused, listing = done.stdout.splitlines()
    assert refused.startswith("refused: ") and "is locked: another sweep is running" in refused
    assert listing == "True ['.tumble-lock', 'out', 'out.resume']"


def test_a_full_disk_says_where_the_finished_chunks_are_kept(tmp_path, monkeypatch, capsys):
    """Issue 27, item 6: a sweep that fails writing its results keeps its finished chunks in
    DIR.resume/ for the next run; the line said "nothing written" and no more. It says where they
    are, and the same sweep run again resumes from them."""
    import errno
    import os

    import tumble.commands.sweep as command
    from tumble.cli import main

    path, out = sweep_file(tmp_path), tmp_path / "out"
    original = command.write_json

    def full(data, where):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))  # as f.write() raises it: no filename

    monkeypatch.setattr(command, "write_json", full)
    assert main(["sweep", str(path), "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "No space left on device; nothing written" in err
    assert err.rstrip().endswith(f"the finished chunks are kept in {tmp_path / 'out.resume'}/: the same sweep run "
                                 "again resumes")
    assert not out.exists() and len(list((tmp_path / "out.resume").glob("chunk-*"))) == 4
    monkeypatch.setattr(command, "write_json", original)
    computed = interrupt_after(monkeypatch, 0)  # any chunk computed again would be interrupted
    assert main(["sweep", str(path), "--out", str(out)]) == 0
    assert computed == []
    monkeypatch.undo()
    assert (out / "cases.csv").read_bytes() == fresh_csv(path, tmp_path)
