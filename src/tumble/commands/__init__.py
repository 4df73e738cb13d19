"""The command layer: running what a file describes and writing what it gives.

Each ``tumble`` command that computes has its Python function here; :mod:`tumble.io` only reads
and writes files, and :mod:`tumble.cli` only parses the command line and prints.

- :mod:`~tumble.commands.scenario`: :func:`run_scenario`, an open-loop or closed-loop scenario
  (``tumble simulate``, ``plot``, ``view``).
- :mod:`~tumble.commands.sweep`: :func:`~tumble.commands.sweep.run_sweep`, a sweep file
  (``tumble sweep``).
- :mod:`~tumble.commands.fit`: :func:`~tumble.commands.fit.run_fit_command`, a gyroscope
  recording (``tumble fit``).
- :mod:`~tumble.commands.compile_ahead`: :func:`~tumble.commands.compile_ahead.compile_ahead`, the
  kernels compiled ahead into numba's cache (``tumble compile``).

``run_scenario`` is loaded on first use (PEP 562), so that ``tumble fit`` does not import the
simulation's compiled kernels.
"""

import importlib as _importlib
from typing import Any as _Any

__all__ = ["run_scenario"]


def __getattr__(name: str) -> _Any:
    if name == "run_scenario":
        value = _importlib.import_module("tumble.commands.scenario").run_scenario
        globals()[name] = value
        return value
    raise AttributeError(f"module 'tumble.commands' has no attribute {name!r}")
