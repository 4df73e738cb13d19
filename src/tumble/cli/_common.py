"""What the command modules share: the exit statuses, the options' number type and the spinner."""

from __future__ import annotations

import sys

#: The command line's exit status when the command did what it was asked.
EXIT_OK = 0
#: The exit status of a computation that failed (the input was valid).
EXIT_FAILURE = 1
#: The exit status of bad input: one line naming the field, the value and what is allowed.
EXIT_USAGE = 2


class Written(float):
    """A number of the command line that shows itself as it was written: a message about it reads
    ``--t-end = -5`` (the value as the user wrote it), not ``-5.0``; a float everywhere else
    (arithmetic, numpy, numba, JSON and ``str`` see the float). Made by :func:`number`.

    Examples
    --------
    >>> from tumble.cli._common import number
    >>> t = number("1e3")
    >>> repr(t), str(t), t + 1.0, f"{t:g}"
    ('1e3', '1000.0', 1001.0, '1000')
    """

    text: str

    def __new__(cls, text: str) -> Written:
        value = super().__new__(cls, text)
        value.text = str(text)
        return value

    def __repr__(self) -> str:
        return self.text

    __str__ = float.__repr__


def number(text: str) -> float:
    """argparse's type of a numeric option: the float of ``text`` that shows itself as written
    (:class:`Written`); a ValueError (argparse: "invalid number value") for text that is no number."""
    return Written(text.strip())


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
