"""Run many ``tumble`` commands of one installed environment, each in a process of its own, without
paying each one's interpreter start and imports (tests/test_wheel_commands.py).

A command line tool is run as ``tumble ARGS``: a new interpreter, which imports numpy, scipy,
matplotlib, numba and tumble, then runs the command. Of a short command's CPU time most is those
imports (``tumble simulate seed_flip.toml``: 1.3 CPU-s, 0.6 of them imports; measured
2026-12-01), and the wheel's test runs some 80 commands. So a :class:`ForkRunner` starts the
environment's Python once, imports those libraries and ``tumble.cli`` there (the *server*), and
for each command forks it: the child changes to the command's folder, sends its standard output
and error to files of its own, sets ``sys.argv`` as the console script does and runs
``tumble.cli.main`` as the console script does (``sys.exit(main())``); its exit status, or minus
the signal that ended it, comes back as a :class:`subprocess.CompletedProcess`. Each command
still starts from a state of its own (a fork copies the server; nothing a command does reaches
the next), with the same environment variables, and runs the installed ``tumble``'s code: only
the imports are done once.

The console script itself (``bin/tumble``) is run as a real process by the wheel test's other
tests (``--help`` of every command, ``tumble examples``). POSIX only (``os.fork``).
"""

from __future__ import annotations

import json
import os
import select
import signal
import subprocess
import tempfile
import threading
from pathlib import Path

#: The server, run by the environment's own Python: imports first, then one command per line of
#: its standard input (JSON: argv, cwd, out, err), answering the child's pid, then its status.
SERVER = r'''
import json, os, sys, traceback

import numpy, scipy.integrate, scipy.optimize, scipy.spatial.transform, scipy.special  # noqa: F401
import matplotlib.figure, matplotlib.pyplot  # noqa: F401
import numba  # noqa: F401
import tumble, tumble.cli  # noqa: F401
from tumble.cli import main

print(json.dumps({"ready": tumble.__file__}), flush=True)
for line in sys.stdin:
    job = json.loads(line)
    sys.stdout.flush(); sys.stderr.flush()
    pid = os.fork()
    if pid == 0:
        code = 1
        try:
            os.chdir(job["cwd"])
            for fd, path in ((1, job["out"]), (2, job["err"])):
                os.dup2(os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644), fd)
            os.dup2(os.open(os.devnull, os.O_RDONLY), 0)
            sys.stdin = open(0, closefd=False)
            sys.argv = [job["script"], *job["argv"]]
            try:
                code = main()
            except SystemExit as stop:  # as the interpreter reports sys.exit's argument
                code = stop.code
                if code is not None and not isinstance(code, int):
                    print(code, file=sys.stderr)
                    code = 1
            code = 0 if code is None else code
        except BaseException:
            traceback.print_exc()
            code = 1
        finally:
            try:
                sys.stdout.flush(); sys.stderr.flush()
            finally:
                os._exit(code & 0xFF)
    print(json.dumps({"pid": pid}), flush=True)
    _, status = os.waitpid(pid, 0)
    print(json.dumps({"status": os.waitstatus_to_exitcode(status)}), flush=True)
'''


class ForkRunner:
    """One server (module docstring) for one thread's commands, one command at a time.

    Parameters
    ----------
    python, tumble : Path
        The environment's Python and its ``tumble`` console script (``sys.argv[0]`` of each command).
    env : dict
        The environment variables of the server and so of every command.
    folder : Path
        Where the server's script and the commands' output files go.
    timeout : float
        s: a command not ended by then is killed and :class:`subprocess.TimeoutExpired` raised,
        as :func:`subprocess.run` does.
    """

    def __init__(self, python: Path, tumble: Path, env: dict, folder: Path, timeout: float) -> None:
        self.tumble, self.timeout = str(tumble), timeout
        self.folder = Path(tempfile.mkdtemp(dir=folder, prefix="fork"))
        script = self.folder / "server.py"
        script.write_text(SERVER, encoding="utf-8")
        self.log = self.folder / "server.err"
        with self.log.open("w") as log:
            self.server = subprocess.Popen([str(python), str(script)], cwd=self.folder, env=env, text=True,
                                           stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=log)
        self.count, self.pending = 0, b""
        ready = self._answer(timeout)
        if "ready" not in ready:
            raise RuntimeError(f"the fork server did not start: {ready}")
        self.imported = ready["ready"]  # the tumble/__init__.py the server imported: the test checks whose

    def _line(self, timeout: float) -> bytes | None:
        """The server's next line, None if none came in ``timeout`` s (read from the pipe's file
        descriptor: a buffered reader may hold a line that ``select`` then does not see)."""
        fd = self.server.stdout.fileno()
        while b"\n" not in self.pending:
            if not select.select([fd], [], [], timeout)[0]:
                return None
            chunk = os.read(fd, 65536)
            if not chunk:
                raise RuntimeError(f"the fork server ended (exit {self.server.wait()}): "
                                   f"{self.log.read_text(errors='replace')[-3000:]}")
            self.pending += chunk
        line, self.pending = self.pending.split(b"\n", 1)
        return line

    def _answer(self, timeout: float, pid: int | None = None, argv: tuple = ()) -> dict:
        """The server's next answer; ``pid``'s command killed if it takes longer than ``timeout``."""
        line = self._line(timeout)
        if line is None:
            if pid is None:
                self.server.kill()
                raise RuntimeError(f"the fork server said nothing in {timeout} s: "
                                   f"{self.log.read_text(errors='replace')[-3000:]}")
            os.kill(pid, signal.SIGKILL)
            self._line(timeout)  # its status
            raise subprocess.TimeoutExpired([self.tumble, *argv], timeout)
        return json.loads(line)

    def run(self, argv: list[str], cwd: Path) -> subprocess.CompletedProcess:
        """``tumble ARGV`` in ``cwd``: its exit status and what it wrote to stdout and stderr."""
        self.count += 1
        out, err = self.folder / f"{self.count:03d}.out", self.folder / f"{self.count:03d}.err"
        job = {"argv": list(argv), "cwd": str(cwd), "out": str(out), "err": str(err), "script": self.tumble}
        self.server.stdin.write(json.dumps(job) + "\n")
        self.server.stdin.flush()
        pid = self._answer(self.timeout)["pid"]
        status = self._answer(self.timeout, pid, tuple(argv))["status"]
        return subprocess.CompletedProcess([self.tumble, *argv], status, out.read_text(encoding="utf-8"),
                                           err.read_text(encoding="utf-8"))

    def close(self) -> None:
        self.server.stdin.close()
        try:
            self.server.wait(timeout=self.timeout)
        except subprocess.TimeoutExpired:
            self.server.kill()


class Forks:
    """A :class:`ForkRunner` for each thread that runs commands (started on its first command),
    all closed by :meth:`close`."""

    def __init__(self, python: Path, tumble: Path, env: dict, folder: Path, timeout: float) -> None:
        self.args = python, tumble, env, folder, timeout
        self.local = threading.local()
        self.lock = threading.Lock()
        self.runners: list[ForkRunner] = []

    def run(self, argv: list[str], cwd: Path) -> subprocess.CompletedProcess:
        """``tumble ARGV`` in ``cwd`` (:meth:`ForkRunner.run`) by this thread's server."""
        runner = getattr(self.local, "runner", None)
        if runner is None:
            runner = self.local.runner = ForkRunner(*self.args)
            with self.lock:
                self.runners.append(runner)
        return runner.run(argv, cwd)

    def close(self) -> None:
        for runner in self.runners:
            runner.close()
