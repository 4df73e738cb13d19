"""Every public callable of tumble shows an example that runs (issue 20 item 4).

Walks the same ``__all__`` as tests/test_annotations.py (``tumble`` and each of its packages and
modules): every public function and class, and every method, classmethod, staticmethod, property
and ``__call__`` a public class defines itself. ``__init__`` is left out: numpydoc documents the
constructor in the class's docstring, whose example builds the object. A name has an example when
its docstring holds a numpydoc ``Examples`` section and ``doctest`` (as ``--doctest-modules`` runs
it in ``make test``) finds at least one ``>>>`` line in it. The standard library's doctest skips a
``cached_property``'s docstring before Python 3.12, so this file runs those examples itself
(``test_cached_property_example``) and counts them too, whatever the Python and the pytest.

The names still without one are frozen in tests/examples_missing.txt (sorted, one a line). The
list may only shrink: a new public name without an example fails, and so does a name in the file
that has gained one (delete its line).
"""

from __future__ import annotations

import doctest
import functools
import importlib
import inspect
import re
from pathlib import Path

import pytest
from test_annotations import _modules, _public_objects

ALLOW_LIST = Path(__file__).with_name("examples_missing.txt")

#: A numpydoc section heading: the title, then a line of dashes (any indentation).
_EXAMPLES_HEADING = re.compile(r"^[ \t]*Examples[ \t]*\n[ \t]*-{3,}[ \t]*$", re.MULTILINE)


@functools.cache
def _cached_properties() -> frozenset[str]:
    """The public names that are a ``functools.cached_property`` (doctest skips them before 3.12)."""
    _public_names()
    return frozenset(_CACHED)


_CACHED: set[str] = set()


@functools.cache
def _public_names() -> dict[str, object]:
    """Dotted name (``module.qualname``) -> object, for every public callable (``__init__`` out)."""
    found: dict[str, object] = {}
    for where, obj, owner, member in _public_objects():
        if member == "__init__":
            continue
        found[where] = obj
        if owner is not None and isinstance(vars(owner)[member], functools.cached_property):
            _CACHED.add(where)
    return found


@functools.cache
def _doctested() -> frozenset[str]:
    """The names whose docstring doctest collects with at least one example, as ``make test`` does."""
    finder = doctest.DocTestFinder()
    modules = {name.rsplit(".", 1)[0] for name in _public_names()}
    names: set[str] = set()
    for module_name in _modules():
        module = importlib.import_module(module_name)
        if module_name not in modules and not any(m.startswith(module_name + ".") for m in modules):
            continue
        for test in finder.find(module, module_name):
            if test.examples:
                names.add(test.name)
    return frozenset(names)


def has_example(name: str) -> bool:
    """``name``'s docstring has an Examples section and doctest runs at least one line of it."""
    doc = inspect.getdoc(_public_names()[name]) or ""
    run = name in _doctested() or name in _cached_properties()
    return bool(_EXAMPLES_HEADING.search(doc)) and ">>>" in doc and run


def _cached_examples() -> list[str]:
    return sorted(name for name in _cached_properties() if has_example(name))


def _allowed() -> list[str]:
    lines = ALLOW_LIST.read_text(encoding="utf-8").splitlines()
    return [line.strip() for line in lines if line.strip() and not line.startswith("#")]


def test_the_walk_sees_the_api():
    found = _public_names()
    assert "tumble.dynamics.simulate.simulate" in found
    assert "tumble.mass.body.Body" in found
    assert "tumble.dynamics.methods.exact.FreeRotation.omega" in found
    assert not any(name.endswith(".__init__") for name in found)
    assert len(found) > 400


def test_the_check_tells_an_example_from_none():
    assert has_example("tumble.mass.body.Body")
    assert _EXAMPLES_HEADING.search("Summary.\n\nExamples\n--------\n>>> 1 + 1\n2\n")
    assert not _EXAMPLES_HEADING.search("Summary.\n\nSee Also\n--------\nExamples of use elsewhere.\n")


def test_the_allow_list_is_sorted_and_known():
    allowed = _allowed()
    assert allowed == sorted(set(allowed)), f"{ALLOW_LIST.name} must be sorted, one name a line, no repeats"
    unknown = sorted(set(allowed) - set(_public_names()))
    assert not unknown, f"no longer public names in {ALLOW_LIST.name} (delete their lines): {unknown}"


def test_every_public_name_has_an_example_or_is_allowed_without():
    missing = {name for name in _public_names() if not has_example(name)}
    new = sorted(missing - set(_allowed()))
    assert not new, (
        "public names without an Examples section that doctest runs (add one; the list in "
        f"{ALLOW_LIST.name} only shrinks): {new}"
    )


def test_the_allow_list_only_holds_names_still_missing():
    done = sorted(name for name in _allowed() if name in _public_names() and has_example(name))
    assert not done, f"these names have an example now: delete their lines from {ALLOW_LIST.name}: {done}"


@pytest.mark.parametrize("name", _cached_examples())
def test_cached_property_example(name):
    fn = _public_names()[name]
    module = importlib.import_module(fn.__module__)
    test = doctest.DocTestParser().get_doctest(fn.__doc__, dict(vars(module)), name, inspect.getsourcefile(fn), 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    runner.run(test)
    assert runner.summarize(verbose=False).failed == 0, f"the example of {name} fails (see the output above)"
