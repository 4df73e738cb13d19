"""A package's public names loaded on first use (PEP 562), so that importing one module of it
does not import all the others.

Python runs a package's ``__init__`` before any of its modules: with the names imported there
eagerly, ``import tumble.dynamics.models.drag`` (what the fit of a toss needs) also loaded the
integrators, the controllers, the orbit models and scipy.integrate, a tenth of a ``tumble fit``
that should take under 2 s (issue #29). A package that calls :func:`lazy_package` keeps its
imports as before, under ``if typing.TYPE_CHECKING:`` (what the type checker and the reader
see); each name's module is imported when the name is first used. The imports are read from the
package's own source (:mod:`ast`), so each name is written once, where it always was.

One catch, handled here: a public name that is also the name of one of the package's modules
(``tumble.dynamics.simulate``, the function, in the module ``simulate.py``). Importing that
module binds it on the package, over the function, so that ``from tumble.dynamics import
simulate`` would give the module; the package refuses that binding (the module stays in
``sys.modules``), as an eager ``__init__`` overwrote it with the function.
"""

from __future__ import annotations

import ast
import importlib
import importlib.abc
import sys
import types
from collections.abc import Mapping
from typing import Any

__all__ = ["lazy_package", "type_checking_imports"]


class _LazyPackage(types.ModuleType):
    """A package whose public names are imported on first use (the module docstring)."""

    _exports: Mapping[str, str]

    def __getattr__(self, name: str) -> Any:
        where = self.__dict__.get("_exports", {}).get(name)
        if where is None:
            if not name.startswith("__"):  # a module of the package (an eager __init__ had imported it)
                try:
                    return importlib.import_module(f"{self.__name__}.{name}")
                except ModuleNotFoundError as err:
                    if err.name != f"{self.__name__}.{name}":
                        raise
            raise AttributeError(f"module {self.__name__!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(where, self.__name__), name)
        self.__dict__[name] = value  # a second use costs nothing
        return value

    def __setattr__(self, name: str, value: Any) -> None:
        if (isinstance(value, types.ModuleType) and name in self.__dict__.get("_exports", {})
                and value.__name__ == f"{self.__name__}.{name}"):
            return  # the module of the same name as a public name: the name keeps its value
        super().__setattr__(name, value)

    def __dir__(self) -> list[str]:
        return sorted(set(self.__dict__) | set(self.__dict__.get("_exports", {})))


def type_checking_imports(source: str) -> dict[str, str]:
    """Each name that ``source`` imports under ``if TYPE_CHECKING:`` and the module it comes from.

    Parameters
    ----------
    source : str
        A module's Python source.

    Returns
    -------
    dict of str to str
        Name (as bound, after ``as``) to module, relative modules with their leading dots.

    Examples
    --------
    >>> from tumble._lazy import type_checking_imports
    >>> type_checking_imports('''
    ... from typing import TYPE_CHECKING
    ... if TYPE_CHECKING:
    ...     from .batch import simulate_batch
    ...     from .models.drag import Drag as AirDrag
    ... ''')
    {'simulate_batch': '.batch', 'AirDrag': '.models.drag'}
    """
    exports: dict[str, str] = {}
    for node in ast.parse(source).body:
        if isinstance(node, ast.If) and isinstance(node.test, ast.Name) and node.test.id == "TYPE_CHECKING":
            for stmt in node.body:
                if isinstance(stmt, ast.ImportFrom):
                    module = "." * stmt.level + (stmt.module or "")
                    exports.update({alias.asname or alias.name: module for alias in stmt.names})
    return exports


def lazy_package(package: str, exports: Mapping[str, str] | None = None) -> None:
    """Make ``package``'s public names load on first use.

    Parameters
    ----------
    package : str
        The package's name (its ``__name__``), already in ``sys.modules`` (call this from its
        ``__init__``).
    exports : mapping of str to str, optional
        Each public name and the module that defines it, relative to ``package`` (``".batch"``)
        or absolute. By default the imports under ``if TYPE_CHECKING:`` in the package's
        ``__init__`` (:func:`type_checking_imports`).

    Examples
    --------
    >>> import sys, types
    >>> from tumble._lazy import lazy_package
    >>> sys.modules["demo_package"] = types.ModuleType("demo_package")
    >>> lazy_package("demo_package", {"sqrt": "math", "dumps": "json"})
    >>> import demo_package
    >>> demo_package.sqrt(9.0)   # math imported now, on first use
    3.0
    >>> "sqrt" in dir(demo_package), "dumps" in dir(demo_package)   # listed before their first use
    (True, True)
    >>> try:
    ...     demo_package.no_such_name
    ... except AttributeError as error:
    ...     print(error)
    module 'demo_package' has no attribute 'no_such_name'
    >>> del sys.modules["demo_package"]
    """
    module = sys.modules[package]
    if exports is None:  # the loader's source: a file, or a zip's member (zipimport)
        loader = module.__spec__.loader if module.__spec__ else None
        source = loader.get_source(package) if isinstance(loader, importlib.abc.InspectLoader) else None
        if source is None:
            raise ImportError(f"{package}: its names load from its source, which is not shipped")
        exports = type_checking_imports(source)
    module.__class__ = _LazyPackage
    module.__dict__["_exports"] = dict(exports)
