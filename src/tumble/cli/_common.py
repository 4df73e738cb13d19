"""What the command modules share: the exit statuses and the spinner."""

from __future__ import annotations

import sys

EXIT_OK, EXIT_FAILURE, EXIT_USAGE = 0, 1, 2


def _working(message: str):
    """A spinner on stderr while a long computation runs on a terminal; silent when piped."""
    import contextlib

    if not sys.stderr.isatty():
        return contextlib.nullcontext()
    from rich.console import Console

    return Console(stderr=True).status(message)


def _run_title(scenario, traj) -> str:
    """``scenario: body, method``, without the body when the scenario is named after it."""
    name = scenario.name if scenario.name != traj.body_name else None
    return ", ".join(filter(None, (f"{name}: {traj.body_name}" if name else traj.body_name,
                                getattr(traj, "method_label", traj.method))))
