"""The integration methods' names, without their integrators: what ``simulate``'s docstring and
the command line's help list (the command line imports no numpy to say them).

The registry, :data:`tumble.dynamics.methods.integrators.METHODS`, holds exactly these names in
this order (it refuses to load otherwise): a new method is named here and registered there.
"""

from __future__ import annotations

import textwrap

__all__ = ["DEFAULT", "METHOD_NAMES", "method_list"]

#: Every method ``simulate(method=...)`` accepts, in the registry's order.
METHOD_NAMES = ("exact", "dop853", "rk45", "seed", "geometric", "geometric2", "geometric6", "exact_split2",
                "exact_split4", "exact_split6", "rk4", "rk8")
#: The method of a torque-free run when none is named.
DEFAULT = "exact"


def method_list(quote: str = "", width: int | None = None, indent: str = "") -> str:
    """The names as a list for a reader: ``exact (default), dop853, ...``, each in ``quote``.

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
    'exact (default), dop853, rk45, seed, geo'
    >>> method_list("``").split(", ")[-1]
    '``rk8``'
    """
    text = ", ".join(f"{quote}{name}{quote}" + (" (default)" if name == DEFAULT else "") for name in METHOD_NAMES)
    if width is None:
        return text
    return textwrap.fill(text, width=width, subsequent_indent=indent, break_long_words=False, break_on_hyphens=False)
