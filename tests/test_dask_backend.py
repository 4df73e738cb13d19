"""Sweeps on Dask: when workers die only their chunks are lost and run again, the rows stay the
same; a clean run prints nothing from Dask, and an address where no scheduler answers fails fast.

A chunk function that kills its own worker process (SIGKILL, as an out-of-memory killer or a
lost node would) the first time it runs a given chunk, recorded through a file, so that the
re-run of that chunk on another worker finishes. Skipped without ``dask.distributed``.
"""

from __future__ import annotations

import contextlib
import functools
import json
import os
import signal
import socket
import socketserver
import sys
import threading
import time
from pathlib import Path

import pytest

distributed = pytest.importorskip("dask.distributed")
cloudpickle = pytest.importorskip("cloudpickle")

import tumble.commands.sweep as sweep_command  # noqa: E402
from tumble.cli import main  # noqa: E402
from tumble.ensemble import DaskBackend  # noqa: E402
from tumble.commands.sweep import run_sweep  # noqa: E402
from limits import HANG_S

DASK_CONNECT_DEFAULT_S = 30.0

# the workers unpickle this module's functions by value: they need not import the tests
cloudpickle.register_pickle_by_value(sys.modules[__name__])

SWEEP = """\
body = "t-handle"

[sweep]
cases = 48
seed = 21
chunk = 6

[[dispersion]]
target = "moments"
relative = 0.02

[[dispersion]]
target = "axes"
absolute = 0.01

[simulation]
samples = 200
t_end = 12.0

[initial]
spread = [0.05, 0.3, 0.05]
distribution = "uniform"
omega = [0.1, 8.0, 0.1]
"""


def kill_first_run(marks: str, doomed: tuple, fn, sweep, start, stop):
    """``fn(sweep, start, stop)``, but the first run of a chunk starting in ``doomed`` kills its worker."""
    mark = Path(marks) / f"chunk-{start}"
    if start in doomed and not mark.exists():
        mark.write_text(str(os.getpid()))
        os.kill(os.getpid(), signal.SIGKILL)
    (Path(marks) / f"done-{start}-{os.getpid()}").touch()
    return fn(sweep, start, stop)


class Killing:
    """A backend whose chunk function kills its worker on the first run of the ``doomed`` chunks."""

    def __init__(self, inner, marks: Path, doomed: tuple) -> None:
        self.inner, self.marks, self.doomed = inner, marks, doomed

    def map(self, fn, tasks):
        return self.inner.map(functools.partial(kill_first_run, str(self.marks), self.doomed, fn), tasks)

    def close(self) -> None:
        self.inner.close()

    def describe(self) -> str:
        return self.inner.describe()


def test_a_worker_killed_mid_sweep_costs_only_its_chunk_and_the_cases_are_the_same(tmp_path, monkeypatch):
    path = tmp_path / "kill.toml"
    path.write_text(SWEEP)
    here = run_sweep(path, tmp_path / "here")
    marks = tmp_path / "marks"
    marks.mkdir()
    doomed = (0, 24, 42)  # chunks 0, 4 and 7 of 8: the first, one in the middle, the last
    monkeypatch.setattr(sweep_command, "make_backend", lambda workers, scheduler: Killing(DaskBackend(workers=2),
                                                                                      marks, doomed))
    there = run_sweep(path, tmp_path / "there", workers=2)
    killed = sorted(int(p.read_text()) for p in marks.glob("chunk-*"))
    assert len(killed) == 3 and len(set(killed)) == 3  # three workers died, one per doomed chunk
    done = [p.name.split("-")[1] for p in marks.glob("done-*")]
    # every chunk ran to the end, the doomed ones on another worker after their kill; a death
    # loses the chunk it ran and any finished result the worker still held (measured: 1 chunk
    # run twice in 8), never the sweep: fewer re-runs than the 3 x 8 of starting over each time
    assert sorted(set(done), key=int) == [str(s) for s in range(0, 48, 6)]
    assert len(done) - 8 < 3 * 8
    assert there["backend"] == "dask local cluster of 2 workers"
    assert (tmp_path / "here" / "cases.csv").read_bytes() == (tmp_path / "there" / "cases.csv").read_bytes()
    assert here["statistics"] == there["statistics"]


def kill_always(fn, sweep, start, stop):
    os.kill(os.getpid(), signal.SIGKILL)


def test_a_chunk_that_kills_every_worker_is_refused_in_one_line():
    import dask

    with dask.config.set({"distributed.scheduler.allowed-failures": 0}):  # the scheduler gives up at once
        backend = DaskBackend(workers=1, retries=1)
    try:
        with pytest.raises(ValueError, match=r"^task 0: its workers kept dying; given up after 2 submission\(s\), "
                                             r"retries = 1 \(Dask: [^\n]*\)$"):
            list(backend.map(functools.partial(kill_always, None), [(None, 0, 1)]))
    finally:
        backend.close()


def test_retries_must_be_a_whole_number():
    with pytest.raises(ValueError, match=r"^retries = -1 must be a whole number >= 0$"):
        DaskBackend(workers=1, retries=-1)


@pytest.mark.parametrize("timeout", [0, -1.0, float("nan"), float("inf"), True, "5"])
def test_timeout_must_be_a_positive_number_of_seconds(timeout):
    with pytest.raises(ValueError, match=r"^timeout = .* must be a number of seconds > 0$"):
        DaskBackend(scheduler="tcp://127.0.0.1:8786", timeout=timeout)


# ---- a clean run prints nothing from Dask; a bad scheduler address fails in seconds -------------

#: Run in a fresh interpreter, so that its whole stderr (workers' included) can be read: a local
#: cluster of one worker, used, interrupted and closed; what it saw, as JSON on stdout.
QUIET = """\
import json, logging, os, signal, time, urllib.error, urllib.request
import distributed  # sets its loggers' levels
from tumble.ensemble import DaskBackend

levels = {name: logging.getLogger(name).level for name in ("distributed", "tornado")}
backend = DaskBackend(workers=1)
client, scheduler = backend._client, backend._cluster.scheduler
(pid,) = client.run(os.getpid).values()
ignores = list(client.run(lambda: signal.getsignal(signal.SIGINT) == signal.SIG_IGN).values())
client.run(lambda: logging.getLogger("distributed.worker").error("noise from the worker"))
logging.getLogger("distributed.client").error("noise from the client")
os.kill(pid, signal.SIGINT)  # as Ctrl-C does to every process of the terminal's group
time.sleep(0.5)
alive = list(client.run(os.getpid).values()) == [pid]
results = sorted(backend.map(pow, [(2, 10), (3, 4)]))
http = scheduler.http_server
try:
    status = urllib.request.urlopen(f"http://{http.address}:{http.port}/health", timeout=120).status
except urllib.error.HTTPError as exc:
    status = exc.code
backend.close()
after = {name: logging.getLogger(name).level for name in ("distributed", "tornado")}
print(json.dumps({"ignores": ignores, "alive": alive, "results": results, "address": http.address,
                  "port": http.port, "health": status, "levels_restored": after == levels}))
"""


def test_a_local_cluster_prints_nothing_serves_nothing_and_ignores_ctrl_c(tmp_path):
    """Port 8787 busy, noise logged in the worker and the client, SIGINT to the worker: stderr stays empty."""
    import subprocess

    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    with socket.socket() as held:
        with contextlib.suppress(OSError):  # already held by another process: busy all the same
            held.bind(("127.0.0.1", 8787))
            held.listen()
        done = subprocess.run([sys.executable, "-c", QUIET], check=False, capture_output=True, text=True, timeout=HANG_S,
                              env=env, cwd=tmp_path)
    assert done.stderr == "" and done.returncode == 0
    seen = json.loads(done.stdout)
    assert seen["ignores"] == [True] and seen["alive"]  # the worker ignores Ctrl-C: the parent decides
    assert seen["results"] == [[0, 1024], [1, 81]]
    assert seen["address"] == "127.0.0.1" and seen["port"] != 8787  # loopback only, a free port
    assert seen["health"] == 404  # no route served: nothing but the dashboard would need one
    assert seen["levels_restored"]


class _Answering(socketserver.BaseRequestHandler):
    """A server that is not Dask: it answers anything with an HTTP error at once."""

    def handle(self):
        self.request.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")
        self.request.recv(1 << 16)


class _Silent(socketserver.BaseRequestHandler):
    """A server that is not Dask and waits, as an HTTP server does, for a request line."""

    def handle(self):
        self.request.settimeout(10)
        with contextlib.suppress(OSError):
            while self.request.recv(1 << 16):
                pass


@contextlib.contextmanager
def _server(handler):
    server = socketserver.ThreadingTCPServer(("127.0.0.1", 0), handler)
    server.daemon_threads = True
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"tcp://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()


def _closed_port() -> str:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return f"tcp://127.0.0.1:{s.getsockname()[1]}"


@pytest.mark.parametrize(("handler", "why"), [(_Answering, "the server there does not speak Dask's protocol"),
                                              (_Silent, "connected, but no answer within 1 s"),
                                              (None, "cannot connect: [^)]")])
def test_a_scheduler_address_where_no_dask_answers_fails_in_seconds(handler, why):
    with contextlib.ExitStack() as stack:
        address = _closed_port() if handler is None else stack.enter_context(_server(handler))
        start = time.monotonic()
        with pytest.raises(ValueError, match=rf"^scheduler = '{address}': no Dask scheduler there \({why}[^\n]*$"):
            DaskBackend(scheduler=address, timeout=1.0)
        # Dask's own connect timeout (distributed.comm.timeouts.connect, 30 s) is what a backend that
        # ignored its 1 s would wait: far beyond what a busy machine adds to 1 s.
        assert time.monotonic() - start < DASK_CONNECT_DEFAULT_S


@pytest.mark.parametrize(("address", "why"), [("localhost", "missing port number"),
                                              ("http://127.0.0.1:8787", "unknown address scheme 'http'")])
def test_a_scheduler_address_dask_cannot_read_is_refused_at_once(address, why):
    with pytest.raises(ValueError, match=rf"^scheduler = '{address}': no Dask scheduler there \(not an address: {why}"):
        DaskBackend(scheduler=address, timeout=60.0)


def test_the_sweep_command_refuses_a_non_dask_scheduler_in_one_line(tmp_path, capfd):
    path = tmp_path / "sweep.toml"
    path.write_text(SWEEP)
    with _server(_Answering) as address:
        assert main(["sweep", str(path), "--out", str(tmp_path / "out"), "--scheduler", address]) == 2
    out, err = capfd.readouterr()
    assert out == "" and err.count("\n") == 1
    assert err.startswith(f"tumble: error: scheduler = '{address}': no Dask scheduler there")
    assert not (tmp_path / "out").exists()
