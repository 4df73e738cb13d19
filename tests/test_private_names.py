"""No private name crosses a subpackage of tumble (issue #17, item 3).

A name or a module whose last part starts with ``_`` is private to its subpackage:
``tumble.mass``, ``tumble.dynamics``, ``tumble.analysis``, ``tumble.ensemble``, ``tumble.io``,
``tumble.viz``, and each top-level module (``tumble.cli``, ``tumble.validation``, ...) on its own.
Every module under ``src/tumble`` is parsed with :mod:`ast`; the test collects

- ``from X import _name`` and ``from X._mod import name`` / ``import X._mod``,
- attribute access ``alias._name`` on a name bound to a tumble module by an import,

where X lies in another subpackage than the importing module, and asserts that none is found.
"""

from __future__ import annotations

import ast
from pathlib import Path

import tumble

SRC = Path(tumble.__file__).resolve().parent

#: Private top-level modules meant as shared infrastructure of the whole package.
ALLOWED_MODULES = {
    "tumble._html": "escaping and the small text and table helpers shared by every repr, display and page",
    "tumble._optional": "importing an optional extra with the install hint, for every layer that has one",
    "tumble._lazy": "a package's public names loaded on first use, for the packages whose modules are imported alone",
    "tumble._version": "the version string, written by the build, read by cli, io provenance and __init__",
}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _owner(module: str) -> str:
    """The subpackage (``tumble.mass``) or top-level module (``tumble.cli``) a module belongs to."""
    return ".".join(module.split(".")[:2])


def _resolve(importer: str, is_package: bool, module: str | None, level: int) -> str:
    if level == 0:
        return module or ""
    base = importer.split(".")
    if not is_package:
        base = base[:-1]
    if level > 1:
        base = base[: len(base) - (level - 1)]
    return ".".join(base + ([module] if module else []))


def _is_private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def _private_module(module: str) -> str | None:
    """The first private part of a tumble module path, as a dotted prefix, or None."""
    parts = module.split(".")
    for i, part in enumerate(parts):
        if _is_private(part):
            return ".".join(parts[: i + 1])
    return None


def _violations_in(path: Path) -> list[str]:
    importer = _module_name(path)
    is_package = path.name == "__init__.py"
    mine = _owner(importer)
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found: list[str] = []
    aliases: dict[str, str] = {}  # local name -> tumble module it is bound to

    def foreign(target: str) -> bool:
        return target.split(".")[0] == "tumble" and _owner(target) != mine

    def check_module(target: str, line: int) -> None:
        private = _private_module(target)
        if private and foreign(private) and private not in ALLOWED_MODULES:
            found.append(f"{importer}:{line} imports private module {private}")

    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            target = _resolve(importer, is_package, node.module, node.level)
            if not target.startswith("tumble"):
                continue
            check_module(target, node.lineno)
            for alias in node.names:
                full = f"{target}.{alias.name}"
                if _is_private(alias.name) and foreign(target) and full not in ALLOWED_MODULES:
                    found.append(f"{importer}:{node.lineno} imports {alias.name} from {target}")
                aliases[alias.asname or alias.name] = full
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("tumble"):
                    check_module(alias.name, node.lineno)
                    aliases[alias.asname or alias.name] = alias.name if alias.asname else "tumble"
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
            target = aliases.get(node.value.id)
            name = node.attr
            if target and _is_private(name) and foreign(target) and f"{target}.{name}" not in ALLOWED_MODULES:
                found.append(f"{importer}:{node.lineno} uses {node.value.id}.{name} ({target})")
    return found


def private_crossings() -> list[str]:
    found: list[str] = []
    for path in sorted(SRC.rglob("*.py")):
        found.extend(_violations_in(path))
    return found


def test_no_private_name_crosses_a_subpackage():
    assert private_crossings() == []


def test_the_scan_sees_a_crossing(monkeypatch):
    """The scanner flags each kind of crossing and lets same-subpackage and allowed ones pass."""
    import tumble.dynamics as dyn

    fake = Path(dyn.__file__).resolve().parent / "zz_scan_probe.py"
    source = (
        "from ..mass.tensor import _hidden\n"
        "from ..mass import _display\n"
        "import tumble.mass._display\n"
        "from .. import _html, _version\n"
        "from . import _display as mine\n"
        "from ..mass import tensor\n"
        "x = tensor._scale\n"
    )
    monkeypatch.setattr(Path, "read_text", lambda self, encoding=None: source)
    found = _violations_in(fake)
    assert any("imports _hidden from tumble.mass.tensor" in f for f in found)
    assert any("private module tumble.mass._display" in f for f in found)
    assert any("tensor._scale" in f for f in found)
    assert not any("_html" in f or "_version" in f or "tumble.dynamics._display" in f for f in found)
    assert len(found) == 4, found  # _hidden, _display (from ... import), import ..._display, _scale
