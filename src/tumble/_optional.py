"""Optional dependencies (the extras of pyproject.toml), imported only when a feature asks for one.

One rule for all of them (issue 27): a missing extra is the user's setup, not a bad input, so it
is an ``ImportError`` (``name`` the package) whose message says what needed it and the line that
installs it, ``pip install 'tumble[EXTRA]'``; the command line prints that line and exits 2.
Imports nothing from tumble, so every layer may use it.
"""

from __future__ import annotations

import importlib
from types import ModuleType

__all__ = ["optional_import"]


def optional_import(module: str, extra: str, feature: str) -> ModuleType:
    """Import ``module`` of an optional dependency, or raise ``ImportError`` with the install hint.

    Parameters
    ----------
    module : str
        Dotted module name, e.g. ``"sgp4.api"``.
    extra : str
        The extra of tumble that installs it (pyproject's ``optional-dependencies``), e.g. ``"orbit"``.
    feature : str
        What needs it, for the message, e.g. ``"a TLE orbit (TLEOrbit)"``.

    Returns
    -------
    module
        The imported module.

    Raises
    ------
    ImportError
        When the package is not installed (or is blocked), with ``name`` its top-level package and
        the message ``FEATURE needs PACKAGE: pip install 'tumble[EXTRA]'``.

    Examples
    --------
    >>> from tumble._optional import optional_import
    >>> optional_import("json", "none", "this example").__name__
    'json'
    >>> optional_import("no_such_package.api", "orbit", "a TLE orbit (TLEOrbit)")
    Traceback (most recent call last):
    ...
    ImportError: a TLE orbit (TLEOrbit) needs no_such_package: pip install 'tumble[orbit]'
    """
    try:
        return importlib.import_module(module)
    except ImportError:
        package = module.partition(".")[0]
        raise ImportError(f"{feature} needs {package}: pip install 'tumble[{extra}]'", name=package) from None
