"""Every public function and method of tumble carries type hints (issue 17 item 6).

Walks ``tumble.__all__`` and the ``__all__`` of every subpackage and module; for each function, and for
each method, property and classmethod a public class defines itself (``__init__`` and
``__call__`` included, other dunders not), every parameter but ``self``/``cls`` must be annotated
and so must the return. Read from ``__annotations__`` (strings under ``from __future__ import
annotations``), so nothing is evaluated.
"""

from __future__ import annotations

import functools
import importlib
import inspect
import pkgutil

import pytest

import tumble

_METHOD_DUNDERS = {"__init__", "__call__"}


def _modules() -> list[str]:
    """tumble, its subpackages and their modules (private modules too: their ``__all__`` is
    what the packages re-export); ``__main__`` (which runs the CLI on import) left out."""
    names = ["tumble"]
    for info in pkgutil.walk_packages(tumble.__path__, "tumble."):
        if not info.name.endswith("__main__"):
            names.append(info.name)
    return names


def _missing(fn: object) -> list[str]:
    """What ``fn`` lacks: the names of unannotated parameters and ``return``."""
    fn = inspect.unwrap(fn)  # functools.wraps, cached_property's function
    if not inspect.isfunction(fn):
        return []
    annotations = fn.__annotations__
    params = list(inspect.signature(fn).parameters.values())
    if params and params[0].name in ("self", "cls"):
        params = params[1:]
    lacking = [p.name for p in params if p.name not in annotations]
    if "return" not in annotations:
        lacking.append("return")
    return lacking


def _members(cls: type) -> list[tuple[str, object]]:
    out = []
    for name, attr in vars(cls).items():
        if name.startswith("_") and name not in _METHOD_DUNDERS:
            continue
        if isinstance(attr, (staticmethod, classmethod)):
            attr = attr.__func__
        elif isinstance(attr, property):
            attr = attr.fget
        elif hasattr(attr, "func") and type(attr).__name__ == "cached_property":
            attr = attr.func
        if inspect.isfunction(attr) and attr.__module__.startswith("tumble"):
            out.append((name, attr))
    return out


@functools.cache
def _public_objects() -> tuple[tuple[str, object, type | None, str | None], ...]:
    """Every public function and class reachable from an ``__all__``, and every member of those
    classes: ``(dotted name, object, owning class or None, member name or None)``."""
    found: dict[str, tuple[str, object, type | None, str | None]] = {}
    for module_name in _modules():
        module = importlib.import_module(module_name)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if not getattr(obj, "__module__", "").startswith("tumble"):
                continue
            where = f"{obj.__module__}.{getattr(obj, '__qualname__', name)}"
            if inspect.isfunction(obj) or inspect.isclass(obj):
                found[where] = (where, obj, None, None)
            if inspect.isclass(obj):
                for member, fn in _members(obj):
                    found[f"{where}.{member}"] = (f"{where}.{member}", fn, obj, member)
    return tuple(found.values())


@functools.cache
def _public_callables() -> dict[str, object]:
    """The functions and methods among :func:`_public_objects` (classes left out)."""
    return {where: obj for where, obj, owner, _ in _public_objects() if owner is not None or inspect.isfunction(obj)}


def test_the_walk_sees_the_api():
    found = _public_callables()
    assert "tumble.dynamics.simulate.simulate" in found
    assert "tumble.dynamics.methods.exact.FreeRotation.omega" in found
    assert "tumble.dynamics.special.carlson.complete_integrals" in found
    assert len(found) > 400


def test_a_function_without_hints_is_caught():
    def bare(x, y: int = 1):
        return x

    assert _missing(bare) == ["x", "return"]


@pytest.mark.parametrize("name", sorted(_public_callables()))
def test_public_signature_is_annotated(name):
    assert _missing(_public_callables()[name]) == [], f"{name} lacks type hints"
