"""Input files that are not what they seem: devices, FIFOs, directories, huge or deeply nested files.

Each is refused at once with one line naming the file and the rule, through the Python API
(``ValueError``) and through the CLI (exit status 2, one line on stderr). The checks run before
the file is opened, so none of these tests can hang or exhaust memory when the code is right; when
it is wrong they fail within their time limit instead of hanging (a FIFO) or eating the machine
(``/dev/zero``: the child process runs under a memory limit).
"""

from __future__ import annotations

import os
import re
import resource
import subprocess
import sys
import threading
from pathlib import Path

import pytest

import tumble
from tumble.io import read_toml
from tumble.io.bodyfile import MAX_TOML_BYTES
from tumble.mass.mesh import MAX_MESH_BYTES

from limits import HANG_S  # a child blocked on a FIFO hangs: it fails here

MEMORY = 3 << 30  # bytes of address space for a child process: reading /dev/zero hits it at once

RULES = {
    "dev_zero": "is a character device",
    "fifo": r"is a FIFO \(named pipe\)",
    "directory": "is a directory",
    "oversize": "may be at most",
}


def _special(kind: str, tmp_path: Path, suffix: str, size: int) -> Path:
    """A path of the given kind: /dev/zero, a FIFO, a directory or a sparse file of ``size`` + 1 bytes."""
    if kind == "dev_zero":
        return Path("/dev/zero")
    path = tmp_path / f"{kind}{suffix}"
    if kind == "fifo":
        os.mkfifo(path)
    elif kind == "directory":
        path.mkdir()
    else:
        with open(path, "wb") as f:
            f.truncate(size + 1)  # sparse: no disk used
    return path


def _in_thread(fn, path: Path, seconds: float = HANG_S):
    """Call ``fn()`` with a deadline; if it is still blocked (a FIFO opened for reading), fail."""
    outcome = {}

    def target():
        try:
            outcome["value"] = fn()
        except BaseException as exc:  # noqa: BLE001 - handed to the test
            outcome["error"] = exc

    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    thread.join(seconds)
    if thread.is_alive():
        if path.is_fifo():  # unblock the reader: a writer appears and goes away (EOF)
            os.close(os.open(path, os.O_WRONLY | os.O_NONBLOCK))
        thread.join(seconds)
        pytest.fail(f"reading {path} blocked for {seconds} s instead of being refused")
    if "error" in outcome:
        raise outcome["error"]
    return outcome.get("value")


def _limit_memory():  # pragma: no cover - runs in the child
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY, MEMORY))


def _child(code: str | None = None, cli: list[str] | None = None) -> subprocess.CompletedProcess:
    """Run Python code or ``tumble CLI...`` in a child with a time and memory limit."""
    args = [sys.executable, "-c", code] if code is not None else [sys.executable, "-m", "tumble", *cli]
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
    try:
        return subprocess.run(args, capture_output=True, text=True, timeout=HANG_S,
                              preexec_fn=_limit_memory, env=env)
    except subprocess.TimeoutExpired:
        pytest.fail(f"{' '.join(args[1:])} did not finish in {HANG_S} s (blocked on a FIFO?)")


def _assert_one_line_error(proc: subprocess.CompletedProcess, path: Path, rule: str):
    assert proc.returncode == 2, (proc.returncode, proc.stderr)
    assert proc.stdout == ""
    lines = proc.stderr.splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("tumble: error: ") and str(path) in lines[0]
    assert re.search(rule, lines[0]), lines[0]


# --- body and scenario files (TOML) --------------------------------------------------------------

@pytest.mark.parametrize("kind", ["fifo", "directory", "oversize"])
@pytest.mark.parametrize("loader", [read_toml, tumble.load_body, tumble.load_scenario], ids=lambda f: f.__name__)
def test_toml_special_files_refused_by_the_api(tmp_path, kind, loader):
    path = _special(kind, tmp_path, ".toml", MAX_TOML_BYTES)
    with pytest.raises(ValueError, match=RULES[kind]) as info:
        _in_thread(lambda: loader(path), path)
    message = str(info.value)
    assert message.startswith(str(path)) and "\n" not in message
    assert "regular file" in message or f"{MAX_TOML_BYTES:,} bytes (1 MiB)" in message


def test_toml_file_at_the_limit_is_read(tmp_path):
    path = tmp_path / "big.toml"
    text = "[body]\npreset = 't-handle'\n"
    path.write_text(text + "#" * (MAX_TOML_BYTES - len(text) - 1) + "\n")
    assert path.stat().st_size == MAX_TOML_BYTES
    assert tumble.load_body(path).mass == pytest.approx(3.0)


@pytest.mark.parametrize("kind", ["dev_zero", "fifo", "directory", "oversize"])
@pytest.mark.parametrize("command", ["inertia", "simulate"])
def test_toml_special_files_refused_by_the_cli(tmp_path, kind, command):
    path = _special(kind, tmp_path, ".toml", MAX_TOML_BYTES)
    out = tmp_path / "out"
    cli = [command, str(path)] + (["--out", str(out)] if command == "simulate" else [])
    _assert_one_line_error(_child(cli=cli), path, RULES[kind])
    assert not out.exists()


# --- mesh files ------------------------------------------------------------------------------------

@pytest.mark.parametrize("kind", ["fifo", "directory", "oversize"])
def test_mesh_special_files_refused_by_the_api(tmp_path, kind):
    path = _special(kind, tmp_path, ".stl", MAX_MESH_BYTES)
    with pytest.raises(ValueError, match=RULES[kind]) as info:
        _in_thread(lambda: tumble.Mesh(mesh=path, mass=1.0), path)
    message = str(info.value)
    assert message.startswith(f"mesh = {str(path)!r}: ") and "\n" not in message
    assert "a mesh file must be a regular file" in message or "(200 MiB)" in message


@pytest.mark.parametrize(("call", "expected"), [
    ("tumble.io.read_toml('/dev/zero')",
     "/dev/zero: is a character device; a body or scenario file (TOML) must be a regular file"),
    ("tumble.Mesh(mesh='/dev/zero', mass=1.0)",
     "mesh = '/dev/zero': is a character device; a mesh file must be a regular file"),
], ids=["toml", "mesh"])
def test_dev_zero_refused_by_the_api(call, expected):
    proc = _child(f"import tumble, tumble.io\ntry:\n    {call}\nexcept ValueError as exc:\n    print(exc)\n")
    assert proc.returncode == 0, proc.stderr[-500:]
    assert proc.stdout.strip() == expected


@pytest.mark.parametrize("kind", ["dev_zero", "fifo", "directory", "oversize"])
def test_mesh_special_files_refused_by_the_cli(tmp_path, kind):
    mesh = _special(kind, tmp_path, ".stl", MAX_MESH_BYTES)
    body = tmp_path / "body.toml"
    body.write_text(f"[body]\n[[body.parts]]\nkind = 'mesh'\nmesh = '{mesh}'\nmass = 1.0\n")
    _assert_one_line_error(_child(cli=["inertia", str(body)]), body, RULES[kind])


# --- deeply nested TOML ----------------------------------------------------------------------------

NESTED = {
    "arrays": "a = " + "[" * 10000 + "]" * 10000 + "\n",
    "inline_tables": "a = " + "{b = " * 10000 + "1" + "}" * 10000 + "\n",
    "arrays_in_a_part": "[body]\n[[body.parts]]\nkind = 'box'\nmass = 1.0\nsize = " + "[" * 5000 + "]" * 5000 + "\n",
}


@pytest.mark.parametrize("form", NESTED)
def test_deeply_nested_toml_refused_by_the_api(tmp_path, form):
    path = tmp_path / "deep.toml"
    path.write_text(NESTED[form])
    for loader in (read_toml, tumble.load_body, tumble.load_scenario):
        with pytest.raises(ValueError, match="nested too deeply") as info:
            loader(path)
        assert str(info.value).startswith(f"{path}: ") and "\n" not in str(info.value)


@pytest.mark.parametrize("form", NESTED)
@pytest.mark.parametrize("command", ["inertia", "simulate"])
def test_deeply_nested_toml_refused_by_the_cli(tmp_path, capsys, form, command):
    from tumble.cli import main

    path = tmp_path / "deep.toml"
    path.write_text(NESTED[form])
    out = tmp_path / "out"
    assert main([command, str(path)] + (["--out", str(out)] if command == "simulate" else [])) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err == f"tumble: error: {path}: nested too deeply (arrays or inline tables inside each other); a body or scenario file needs at most a few levels\n"
    assert not out.exists()
