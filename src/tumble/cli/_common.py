"""What the command modules share: the exit statuses and the spinner."""

from __future__ import annotations

import sys

#: The command line's exit status when the command did what it was asked.
EXIT_OK = 0
#: The exit status of a computation that failed (the input was valid).
EXIT_FAILURE = 1
#: The exit status of bad input: one line naming the field, the value and what is allowed.
EXIT_USAGE = 2


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
