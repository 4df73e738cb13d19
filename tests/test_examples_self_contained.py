"""Every docstring example runs as copied into a fresh interpreter (issue 28 item 6).

The doctests run in their module's globals, so an example may use a name its module imports
(``Ensemble``, ``np``) without importing it, and then fails with a NameError when a reader copies
it. This test reads every example in ``src/tumble`` (doctest's own finder, every module of the
package) and checks its names statically: each name an example loads must be bound by that
docstring's examples up to there (imported, assigned, defined, a loop or ``with`` target, ...) or
be a builtin. That is exactly the set of names that would raise NameError in empty globals, at
the cost of parsing, not running, the examples; whether they give the right output is the normal
doctest run's business.
"""

from __future__ import annotations

import ast
import builtins
import doctest
import importlib
import pkgutil

import pytest

import tumble

#: Examples allowed to lack names: each entry a doctest name (``module.object``) and the names it
#: lacks; an entry that no longer lacks exactly these names fails the test, so the list only
#: shrinks. Empty: every example imports what it uses.
ALLOWED: dict[str, set[str]] = {}

BUILTINS = set(dir(builtins))


def _modules() -> list[str]:
    names = ["tumble"]
    for info in pkgutil.walk_packages(tumble.__path__, prefix="tumble."):
        if not info.name.endswith(".__main__"):  # importing it runs the command line
            names.append(info.name)
    return sorted(names)


def _bound(tree: ast.AST) -> set[str]:
    """Every name a piece of code binds anywhere in it (conservative: scopes are not told apart)."""
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Name) and isinstance(node.ctx, (ast.Store, ast.Del)):
            names.add(node.id)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            for alias in node.names:
                names.add(alias.asname or alias.name.split(".")[0])
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.arg):
            names.add(node.arg)
        elif isinstance(node, ast.ExceptHandler) and node.name:
            names.add(node.name)
        elif isinstance(node, (ast.MatchAs, ast.MatchStar)) and node.name:
            names.add(node.name)
        elif isinstance(node, ast.MatchMapping) and node.rest:
            names.add(node.rest)
        elif isinstance(node, (ast.Global, ast.Nonlocal)):
            names.update(node.names)
    return names


def _loaded(tree: ast.AST) -> set[str]:
    return {node.id for node in ast.walk(tree) if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load)}


def unbound_names(sources: list[str]) -> set[str]:
    """The names that examples run in order in empty globals would find unbound (NameError)."""
    bound: set[str] = set()
    missing: set[str] = set()
    for source in sources:
        tree = ast.parse(source)
        bound |= _bound(tree)
        missing |= _loaded(tree) - bound - BUILTINS
    return missing


def _collect() -> dict[str, set[str]]:
    finder = doctest.DocTestFinder(exclude_empty=True)
    found: dict[str, set[str]] = {}
    for name in _modules():
        module = importlib.import_module(name)
        for test in finder.find(module, name):
            if not test.examples:
                continue
            missing = unbound_names([example.source for example in test.examples])
            if missing:
                found[test.name] = missing
    return found


def test_the_check_catches_a_name_that_is_not_imported():
    assert unbound_names(["x = np.zeros(3)\n"]) == {"np"}
    assert unbound_names(["import numpy as np\n", "x = np.zeros(3)\n", "print(len(x))\n"]) == set()
    assert unbound_names(["y = x + 1\n", "x = 1\n"]) == {"x"}  # used before it is bound
    assert unbound_names(["for i in range(3):\n    j = i\n", "with open(f) as g:\n    pass\n"]) == {"f"}
    assert unbound_names(["[k for k in (1, 2)]\n", "lambda a: a\n", "try:\n    1\nexcept E as e:\n    e\n"]) == {"E"}


def test_the_walk_sees_every_module():
    names = _modules()
    assert "tumble.io.bodyfile" in names and "tumble.dynamics.special.carlson" in names
    assert len(names) > 50


def test_every_docstring_example_imports_what_it_uses():
    found = _collect()
    assert len(doctest.DocTestFinder().find(importlib.import_module("tumble.io.bodyfile"))) > 5
    unexpected = {name: sorted(missing) for name, missing in found.items() if ALLOWED.get(name) != missing}
    assert not unexpected, "examples that use names they do not import:\n" + "\n".join(
        f"  {name}: {', '.join(missing)}" for name, missing in sorted(unexpected.items()))
    stale = sorted(set(ALLOWED) - set(found))
    assert not stale, f"allowed examples that are now self-contained (drop them from ALLOWED): {stale}"


if __name__ == "__main__":  # pragma: no cover - list the offenders
    for name, missing in sorted(_collect().items()):
        print(f"{name}: {', '.join(sorted(missing))}")
    pytest.main([__file__])
