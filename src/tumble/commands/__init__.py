"""The command layer: running what a file describes and writing what it gives.

Each ``tumble`` command that computes has its Python function here; :mod:`tumble.io` only reads
and writes files, and :mod:`tumble.cli` only parses the command line and prints.

- :mod:`~tumble.commands.scenario`: :func:`run_scenario`, an open-loop or closed-loop scenario
  (``tumble simulate``, ``plot``, ``view``).
- :mod:`~tumble.commands.sweep`: :func:`~tumble.commands.sweep.run_sweep`, a sweep file
  (``tumble sweep``).
- :mod:`~tumble.commands.fit`: :func:`~tumble.commands.fit.run_fit_command`, a gyroscope
  recording (``tumble fit``).
"""

from .scenario import run_scenario

__all__ = ["run_scenario"]
