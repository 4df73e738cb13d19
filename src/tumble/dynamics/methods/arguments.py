"""Which of ``rtol``, ``atol`` and ``step`` a method reads, and the warning when one it does not is given.

A fixed-step method steps by ``step``: the splittings (``geometric*``, ``exact_split*``) never look
at a tolerance, and the engine's ``rk4`` and ``rk8`` take from ``rtol`` only the step that meets it
(:func:`~tumble.dynamics.methods.auto.rk_angle`), when no ``step`` is given; before, their
``rtol`` was dropped: ``simulate(method="rk4", rtol=1e-12)`` ran at the default step and returned
1.5e-11 without a word. An adaptive method (``dop853``, ``rk45``, ``seed``) and ``"auto"`` choose
their own steps from ``rtol``: a ``step`` given to them was dropped as silently. scipy's
``solve_ivp`` warns of options a solver does not take ("The following arguments have no effect for
a chosen solver"); so does :func:`~tumble.simulate`, naming the argument, its value and what reads
it (:class:`IgnoredArgumentWarning`). ``exact`` is exempt: it meets any tolerance and takes no
steps, so nothing given to it is lost.
"""

from __future__ import annotations

import warnings
from typing import Protocol

__all__ = ["IgnoredArgumentWarning", "ignored_arguments", "ignored_message", "warn_ignored"]


class IgnoredArgumentWarning(UserWarning):
    """An argument was given that the chosen method does not read (a tolerance to a splitting,
    ``rtol`` beside a ``step`` or ``atol`` to ``rk4``/``rk8``, a ``step`` to an adaptive method or
    to ``"auto"``); the run goes on without it. The command line prints it as one ``warning:`` line.

    Examples
    --------
    >>> import warnings
    >>> import tumble
    >>> from tumble.dynamics.methods.arguments import IgnoredArgumentWarning
    >>> with warnings.catch_warnings(record=True) as seen:
    ...     warnings.simplefilter("always")
    ...     run = tumble.simulate(tumble.t_handle(), [0.1, 10.0, 0.1], t_end=1.0, method="geometric", rtol=1e-12)
    >>> [w.category is IgnoredArgumentWarning for w in seen], run.method
    ([True], 'geometric')
    """

    cli_one_line = True


class _Kind(Protocol):
    """What is read of a method (:class:`~tumble.dynamics.methods.integrators.Method`, frozen)."""

    @property
    def name(self) -> str: ...
    @property
    def fixed_step(self) -> bool: ...
    @property
    def closed_form(self) -> bool: ...
    @property
    def engine(self) -> bool: ...


def ignored_arguments(method: _Kind, *, auto: bool = False, rtol: float | None = None, atol: float | None = None,
                      step: float | None = None) -> dict[str, float]:
    """The arguments given (not None) that ``method`` does not read, by name.

    Parameters
    ----------
    method : Method
        The registry's method (:data:`~tumble.dynamics.methods.integrators.METHODS`).
    auto : bool
        Whether ``"auto"`` chose it: the choice reads ``rtol`` and ``atol``, never ``step``.
    rtol, atol, step : float, optional
        As given to :func:`~tumble.simulate`.

    Examples
    --------
    >>> from tumble.dynamics import METHODS
    >>> from tumble.dynamics.methods.arguments import ignored_arguments
    >>> ignored_arguments(METHODS["rk8"], rtol=1e-12, step=0.01)   # the step given: rtol would only choose one
    {'rtol': 1e-12}
    >>> ignored_arguments(METHODS["rk8"], rtol=1e-12), ignored_arguments(METHODS["geometric"], rtol=1e-12)
    ({}, {'rtol': 1e-12})
    >>> ignored_arguments(METHODS["dop853"], rtol=1e-12, step=0.01)
    {'step': 0.01}
    >>> ignored_arguments(METHODS["exact"], rtol=1e-12, step=0.01)   # exact meets any rtol, takes no steps
    {}
    """
    if method.closed_form and not auto:
        return {}
    if method.fixed_step and not auto:  # the engine's rk4 and rk8 read rtol for their step, when none is given
        given = {"atol": atol} if method.engine and step is None else {"rtol": rtol, "atol": atol}
    else:
        given = {"step": step}
    return {name: value for name, value in given.items() if value is not None}


def ignored_message(method: _Kind, ignored: dict[str, float], *, auto: bool = False) -> str:
    """One line saying what was ignored and what reads it.

    Examples
    --------
    >>> from tumble.dynamics import METHODS
    >>> from tumble.dynamics.methods.arguments import ignored_message
    >>> ignored_message(METHODS["geometric6"], {"rtol": 1e-12})
    "rtol = 1e-12 has no effect with method = 'geometric6', which steps by step (s): give step, or method 'auto' or 'dop853' to meet an rtol"
    >>> ignored_message(METHODS["rk8"], {"rtol": 1e-12})
    "rtol = 1e-12 has no effect with method = 'rk8', which steps by step (s) and takes from rtol alone, without a step, the step that meets it"
    >>> ignored_message(METHODS["dop853"], {"step": 0.01})
    "step = 0.01 has no effect with method = 'dop853', which chooses its steps to meet rtol: a fixed-step method (rk4, rk8, geometric...) takes step"
    """
    said = " and ".join(f"{name} = {value!r}" for name, value in ignored.items())
    verb = "have" if len(ignored) > 1 else "has"
    name = "auto" if auto else method.name
    if "step" in ignored:
        return (f"{said} {verb} no effect with method = {name!r}, which chooses its steps to meet rtol: a fixed-step "
                f"method (rk4, rk8, geometric...) takes step")
    if method.engine:
        return (f"{said} {verb} no effect with method = {name!r}, which steps by step (s) and takes from rtol alone, "
                f"without a step, the step that meets it")
    return (f"{said} {verb} no effect with method = {name!r}, which steps by step (s): give step, or method 'auto' "
            f"or 'dop853' to meet an rtol")


def warn_ignored(method: _Kind, *, auto: bool = False, stacklevel: int = 2, rtol: float | None = None,
                 atol: float | None = None, step: float | None = None) -> None:
    """Warn (:class:`IgnoredArgumentWarning`) of what of ``rtol``, ``atol`` and ``step`` ``method``
    does not read (:func:`ignored_arguments`); nothing when it reads them all. ``stacklevel`` as
    :func:`warnings.warn`'s, counted from the caller of this function.

    Examples
    --------
    >>> import warnings
    >>> from tumble.dynamics import METHODS
    >>> from tumble.dynamics.methods.arguments import warn_ignored
    >>> with warnings.catch_warnings(record=True) as seen:
    ...     warnings.simplefilter("always")
    ...     warn_ignored(METHODS["dop853"], rtol=1e-9)   # read: nothing said
    ...     warn_ignored(METHODS["dop853"], step=0.5)
    >>> [str(w.message)[:47] for w in seen]
    ["step = 0.5 has no effect with method = 'dop853'"]
    """
    ignored = ignored_arguments(method, auto=auto, rtol=rtol, atol=atol, step=step)
    if ignored:
        warnings.warn(ignored_message(method, ignored, auto=auto), IgnoredArgumentWarning, stacklevel=stacklevel + 1)
