"""The suite passes on a busy machine: no test times the code, and every wait that guards
against a hang takes its limit from :mod:`limits` (issue 40: 33 docs tests failed with
``TimeoutExpired`` at load 8-12 under a fixed 600 s)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from limits import BUILD_S, HANG_MS, HANG_S

TESTS = Path(__file__).resolve().parent
#: Calls that wait on a child, a page or a socket: their ``timeout`` guards against a hang.
WAITS = {"run", "Popen", "check_output", "communicate", "wait", "wait_for", "wait_for_function",
         "wait_for_selector", "NotebookClient", "urlopen"}
#: Clocks a test would read to time the code under test.
CLOCKS = {"perf_counter", "perf_counter_ns", "process_time"}


def _name(func: ast.expr) -> str:
    return func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")


def _offences(source: str) -> list[str]:
    found = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.Call):
            continue
        name = _name(node.func)
        if name in CLOCKS:
            found.append(f"line {node.lineno}: {name}() (time the code in benchmarks/, not in a test)")
        if name in WAITS:
            for kw in node.keywords:
                if kw.arg == "timeout" and isinstance(kw.value, ast.Constant):
                    found.append(f"line {node.lineno}: {name}(timeout={kw.value.value!r}) (use limits.HANG_S, HANG_MS "
                                 "or BUILD_S)")
    return found


@pytest.mark.parametrize("path", sorted(TESTS.glob("*.py")), ids=lambda p: p.name)
def test_no_test_times_the_code_or_waits_on_a_number_of_its_own(path):
    assert _offences(path.read_text(encoding="utf-8")) == [], path.name


def test_the_check_finds_a_fixed_wait_and_a_clock():
    bad = ("import subprocess, time\nt = time.perf_counter()\nsubprocess.run(['x'], timeout=60)\n"
           "page.wait_for_function('x', timeout=10_000)\n")
    assert [line.split(":")[0] for line in _offences(bad)] == ["line 2", "line 3", "line 4"]
    assert _offences("subprocess.run(['x'], timeout=HANG_S)\n") == []


def test_the_limits_leave_a_busy_machine_room():
    # a quarter of an hour for a child or a page, an hour for a build; the browser's in ms
    assert HANG_S >= 900 and BUILD_S >= 3600 and HANG_MS == 1000 * HANG_S
