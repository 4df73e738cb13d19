"""Which tests hang on the last digits of the fits' models: the suite rerun with them changed.

A test that passes on this machine and fails where the numbers round otherwise (another CPU's
fused multiply-adds, another scipy's optimizer, a reordered sum in a kernel) tests round-off, not
tumble: its seed sits on a knife edge of some discrete decision (a flight's boundary, a limit on an
uncertainty, the basin a least-squares solve settles in). This script finds them. Each run k
(1, 2, ...) runs the given tests in a fresh pytest process with the fits' model functions
changed by about 1e-13 (relative), deterministically (``w (1 + 1e-13 sin(k 1e7 w))``: the same
inputs give the same outputs, so tests that compare two runs of one fit still hold):

- :func:`tumble.dynamics.methods.exact_omega.free_omega` (the torque-free motion of the fits),
- :func:`tumble.dynamics.models.fit_kernels.drag_integrate` (the dragged body),
- :func:`tumble.dynamics.models.fit_kernels.gyrostat_integrate` (the gyrostat with a rotor).

A test that fails in some run is printed with the runs it failed in. Round-off of 1e-13 is what a
change of machine or of the kernels' operation order makes (the fits' drag kernel moved onto the
engine's RK4 changed them by 1e-13 to 1e-12 and turned three scenario tests, issue 38).

    .venv/bin/python benchmarks/roundoff_audit.py                      # the fit and tensor tests, 3 runs
    .venv/bin/python benchmarks/roundoff_audit.py --runs 5 tests/test_fit_whole.py

Not part of ``make test`` (each run is a whole pass of the tests given: ~3 CPU-minutes for the
default set).
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: The tests run by default: those whose data go through the fits' models.
DEFAULT = ["tests/test_fit*.py", "tests/test_tensor*.py", "tests/test_calibration_stats.py", "tests/test_example_throws.py"]

#: The relative size of the change.
SIZE = 1e-13


def perturbed(function, k: int):
    """``function`` with its output ``w`` changed to ``w (1 + SIZE sin(k 1e7 w))``.

    Examples
    --------
    >>> import numpy as np
    >>> f = perturbed(lambda x: np.asarray(x, float), 1)
    >>> w = np.array([1.0, 2.0, 3.0])
    >>> bool(np.all(np.abs(f(w) / w - 1.0) <= 1e-13)), bool(np.array_equal(f(w), f(w)))
    (True, True)
    """
    import numpy as np

    def changed(*args, **kwargs):
        w = function(*args, **kwargs)
        return w * (1.0 + SIZE * np.sin(k * 1e7 * w))

    return changed


def pytest_configure(config) -> None:
    """The pytest plugin (``-p roundoff_audit``): change the models for run ``ROUNDOFF_RUN``."""
    k = int(os.environ.get("ROUNDOFF_RUN", "0"))
    if k == 0:
        return
    import tumble.analysis.fit.model as fit_model
    from tumble.dynamics.methods import exact_omega
    from tumble.dynamics.models import fit_kernels

    exact_omega.free_omega = fit_model.free_omega = perturbed(exact_omega.free_omega, k)
    fit_kernels.drag_integrate = perturbed(fit_kernels.drag_integrate, k)
    fit_kernels.gyrostat_integrate = perturbed(fit_kernels.gyrostat_integrate, k)


def selected(tests: list[str]) -> list[str]:
    """The pytest arguments of ``tests``: each a glob of test files from the repository root, with
    or without a test's node id after it (``tests/test_fit.py::test_x``); a node id of a file given
    whole is left out (pytest would run that test twice). A pattern that names no file is an error
    (pytest given nothing would run the whole suite).

    Examples
    --------
    >>> selected(["tests/test_fit_whole.py::test_a", "tests/test_fit_whol?.py", "tests/test_fit.py::test_b"])
    ['tests/test_fit.py::test_b', 'tests/test_fit_whole.py']
    """
    chosen = set()
    for pattern in tests:
        files, _, node = pattern.partition("::")
        found = [str(p.relative_to(ROOT)) for p in ROOT.glob(files)]
        if not found:
            raise SystemExit(f"roundoff_audit: no test file matches {files!r}")
        chosen |= {f"{f}::{node}" if node else f for f in found}
    return sorted(c for c in chosen if c.partition("::")[0] not in chosen or "::" not in c)


def failures(k: int, tests: list[str]) -> list[str]:
    """The node ids of the tests that fail in run ``k`` (0: the models as they are)."""
    env = {**os.environ, "ROUNDOFF_RUN": str(k), "PYTHONPATH": os.pathsep.join(
        filter(None, [str(ROOT / "benchmarks"), os.environ.get("PYTHONPATH", "")]))}
    files = selected(tests)
    proc = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "roundoff_audit", "-p", "no:cacheprovider",
                           "-n", "auto", "--dist", "loadfile", "-rf", *files], cwd=ROOT, env=env, capture_output=True,
                          text=True, check=False)
    return re.findall(r"^FAILED (\S+)", proc.stdout, flags=re.MULTILINE)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("tests", nargs="*", default=DEFAULT, help="test files (globs, from the repository root)")
    parser.add_argument("--runs", type=int, default=3, help="runs with the models changed (default 3)")
    args = parser.parse_args(argv)
    failed: dict[str, list[int]] = {}
    for k in range(args.runs + 1):
        for node in failures(k, args.tests):
            failed.setdefault(node, []).append(k)
        print(f"run {k}{' (the models as they are)' if k == 0 else ''}: "
              f"{sum(k in runs for runs in failed.values())} failed", flush=True)
    for node, runs in sorted(failed.items()):
        print(f"  {node}: failed in run{'s' if len(runs) > 1 else ''} {', '.join(map(str, runs))} of 0..{args.runs}")
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
