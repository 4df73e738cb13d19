"""The integration methods' names, without their integrators: what ``simulate``'s docstring and
the command line's help list (the command line imports no numpy to say them).

The registry, :data:`tumble.dynamics.methods.integrators.METHODS`, holds exactly these names in
this order (it refuses to load otherwise): a new method is named here and registered there.
"""

from __future__ import annotations

import textwrap

__all__ = ["ALLOWED", "AUTO", "DEFAULT", "METHOD_NAMES", "method_list"]

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
