"""The integration methods' names, without their integrators: what ``simulate``'s docstring and
the command line's help list (the command line imports no numpy to say them).

The registry, :data:`tumble.dynamics.methods.integrators.METHODS`, holds exactly these names in
this order (it refuses to load otherwise): a new method is named here and registered there.
"""

from __future__ import annotations

import textwrap

__all__ = ["ALLOWED", "AUTO", "DEFAULT", "METHOD_NAMES", "method_list", "unknown_method"]

#: Every method ``simulate(method=...)`` accepts, in the registry's order.
METHOD_NAMES = ("exact", "dop853", "rk45", "seed", "geometric", "geometric2", "geometric6", "exact_split2",
                "exact_split4", "exact_split6", "rk4", "rk8")
#: The name that lets ``simulate`` choose (:mod:`tumble.dynamics.methods.auto`): not a method of the
#: registry, a rule over it.
AUTO = "auto"
#: The method when none is named: the choice.
DEFAULT = AUTO
#: Every name ``simulate(method=...)`` accepts: the choice, then the registry's methods.
ALLOWED = (AUTO, *METHOD_NAMES)


def method_list(quote: str = "", width: int | None = None, indent: str = "") -> str:
    """The names as a list for a reader: ``auto (default), exact, dop853, ...``, each in ``quote``.

    Parameters
    ----------
    quote : str
        Written either side of each name (``"``"`` for reStructuredText).
    width : int, optional
        Wrap the text to this many characters, later lines starting with ``indent``.
    indent : str
        The indent of the wrapped lines.

    Examples
    --------
    >>> from tumble.dynamics.methods.names import method_list
    >>> method_list()[:40]
    'auto (default), exact, dop853, rk45, see'
    >>> method_list("``").split(", ")[-1]
    '``rk8``'
    """
    text = ", ".join(f"{quote}{name}{quote}" + (" (default)" if name == DEFAULT else "") for name in ALLOWED)
    if width is None:
        return text
    return textwrap.fill(text, width=width, subsequent_indent=indent, break_long_words=False, break_on_hyphens=False)


def unknown_method(method: object) -> str:
    """The message refusing ``method``, a name ``simulate`` does not know: the names it does, and
    for ``"radau"`` (a run's label where ``dop853`` handed a stiff damper to scipy's Radau) or a
    label copied whole (``"rk8 (auto)"``) the name to give instead.

    Examples
    --------
    >>> from tumble.dynamics.methods.names import unknown_method
    >>> unknown_method("radau")
    "method = 'radau' is unknown: it is what dop853 runs a stiff damper with (a run's label); give method dop853 or auto"
    >>> unknown_method("rk8 (auto)")
    "method = 'rk8 (auto)' is unknown: a run's label; give method 'rk8', or 'auto' to let simulate choose again"
    >>> unknown_method("rk5")[:60]
    "method = 'rk5' is unknown; allowed: auto, exact, dop853, rk4"
    """
    if method == "radau" or method == "radau (auto)":
        return (f"method = {method!r} is unknown: it is what dop853 runs a stiff damper with (a run's label); "
                "give method dop853 or auto")
    if isinstance(method, str) and method.endswith(" (auto)") and method[:-7] in METHOD_NAMES:
        return (f"method = {method!r} is unknown: a run's label; give method {method[:-7]!r}, or 'auto' to let "
                "simulate choose again")
    return f"method = {method!r} is unknown; allowed: {', '.join(ALLOWED)}"
