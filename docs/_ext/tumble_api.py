"""The API reference's listing, computed from the package: every public module, every name of its
``__all__``, and the one page each object is documented on.

docs/conf.py writes the reference's sources from it (:func:`write_api_pages`), the
cross-reference resolver (tumble_xref) links through it, and tests/test_docs_names.py checks with
it that every ``tumble.`` name the guides, the gallery and the README write has a page. A new
module or a new name in an ``__all__`` gets its page with no list to keep by hand.

- A public module is one of tumble's modules with an ``__all__`` and no ``_`` at the start of any
  part of its dotted name.
- Each object is documented once, on the page of the first public module (in :func:`public_modules`'
  order: the shallowest first, then by API page) whose ``__all__`` holds it; a function or class
  is recognised by identity wherever it is re-exported, a constant by the module that assigns it.
- Every module gets a page with its docstring, the names it documents and links to the names it
  re-exports from elsewhere. A function or class it documents gets a page of its own; a constant
  or a type alias is an entry of the module's page (:attr:`Entry.inline`).
"""

from __future__ import annotations

import ast
import functools
import importlib
import importlib.util
import inspect
import pkgutil
import re
import types
import typing
from dataclasses import dataclass
from pathlib import Path
from typing import Any

#: The API pages: (file stem, title, the module prefixes whose modules it lists, an intro). A
#: module goes to the page with the longest prefix that matches it.
API_PAGES: list[tuple[str, str, tuple[str, ...], str | None]] = [
    ("mass", "tumble.mass", ("tumble.mass",), None),
    ("dynamics", "tumble.dynamics", ("tumble.dynamics",), None),
    ("kernels", "The methods' kernels", (
        "tumble.dynamics.methods", "tumble.dynamics.special", "tumble.dynamics.engine", "tumble.jit"),
     "The numerical cores behind ``simulate(method=...)`` and ``simulate_batch``: the exact\n"
     "solution (one body and a batch), the splitting integrators, the compiled engine's steppers,\n"
     "the elliptic functions and integrals they rest on, and how kernels are compiled and cached.\n"
     "Most scripts need only :func:`tumble.dynamics.simulate`; these are for checking the\n"
     "formulas, each module's docstring gives them with their sources."),
    ("analysis", "tumble.analysis", ("tumble.analysis",), None),
    ("ensemble", "tumble.ensemble", ("tumble.ensemble",), None),
    ("io", "tumble.io", ("tumble.io",), None),
    ("commands", "tumble.commands", ("tumble.commands",), None),
    ("viz", "tumble.viz", ("tumble.viz",), None),
    ("shell", "The command line, the demo and the shared checks", (
        "tumble.cli", "tumble.demo", "tumble.validation", "tumble.typing"),
     "The command line's entry point, the demo behind ``make demo``, the input checks every layer\n"
     "shares (one message for a bad value from Python, a file or the command line) and the array\n"
     "type aliases of the annotations."),
]

#: Modules not walked (not importable without their extra, or not part of the package's API).
SKIPPED_MODULES = ("tumble.__main__",)


@dataclass(frozen=True)
class Entry:
    """One name of one public module's ``__all__``: where it is documented."""

    module: str  #: the module whose ``__all__`` holds the name
    name: str  #: the name there
    documented: str  #: the full public name of the page it is documented on
    alias: bool = False  #: a type alias: documented on its module's page, not a page of its own
    data: bool = False  #: a constant: documented on its module's page too (``autodata``)

    @property
    def full(self) -> str:
        return f"{self.module}.{self.name}"

    @property
    def inline(self) -> bool:
        """Whether the object is an entry of its module's page, not a page of its own: a type
        alias (autodoc cannot give one a page) or a constant (a page of its own, some 270 of them
        at 13 KB each, held one line and its comment; on its module's page it sits beside the
        functions that use it)."""
        return self.alias or self.data

    @property
    def is_home(self) -> bool:
        """Whether this module's page documents the object (not only links to it)."""
        return self.documented == self.full


def page_of(module: str) -> str:
    """The stem of the API page a module is listed on (the longest matching prefix)."""
    best, length = "", -1
    for stem, _, prefixes, _ in API_PAGES:
        for prefix in prefixes:
            if (module == prefix or module.startswith(prefix + ".")) and len(prefix) > length:
                best, length = stem, len(prefix)
    if not best:
        raise ValueError(f"module {module} belongs to no API page; add its prefix to API_PAGES")
    return best


@functools.cache
def public_modules() -> tuple[str, ...]:
    """tumble's public modules with an ``__all__``, in the order that decides where an object is
    documented: the shallowest first, then by API page, then by name."""
    import tumble

    found = []
    for info in pkgutil.walk_packages(tumble.__path__, "tumble."):
        name = info.name
        if name in SKIPPED_MODULES or any(part.startswith("_") for part in name.split(".")):
            continue
        if hasattr(importlib.import_module(name), "__all__"):
            found.append(name)
    order = [stem for stem, *_ in API_PAGES]
    return tuple(sorted(found, key=lambda m: (m.count("."), order.index(page_of(m)), m)))


@functools.cache
def imported_names(module_name: str) -> dict[str, str]:
    """``{name: "module.name"}`` for every ``from module import name`` anywhere in a module's
    source (also those under ``if TYPE_CHECKING:``); empty if it is not a module with source."""
    try:
        spec = importlib.util.find_spec(module_name)
    except (ImportError, ValueError):
        return {}
    if spec is None or not spec.origin or not spec.origin.endswith(".py"):
        return {}
    package = module_name if spec.submodule_search_locations else module_name.rpartition(".")[0]
    names = {}
    tree = ast.parse(Path(spec.origin).read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = importlib.util.resolve_name("." * node.level + base, package)
            for alias in node.names:
                names.setdefault(alias.asname or alias.name, f"{base}.{alias.name}")
    return names


def defining_module(module_name: str, name: str) -> str:
    """The module whose source assigns ``name``, following ``from ... import name`` from
    ``module_name`` (a package re-exporting a constant of one of its modules)."""
    seen = set()
    while module_name not in seen:
        seen.add(module_name)
        origin = imported_names(module_name).get(name)
        if origin is None:
            return module_name
        module_name = origin.rpartition(".")[0]
    return module_name


def is_alias(obj: Any) -> bool:
    """Whether ``obj`` is a type alias (``NDArray[np.float64]``, ``A | B``): autodoc cannot
    document one on a page of its own, so its module's page lists it."""
    return isinstance(obj, (types.GenericAlias, types.UnionType)) or typing.get_origin(obj) is not None


def is_code(obj: Any) -> bool:
    """Whether ``obj`` is a function or class (known by identity), not a constant."""
    return inspect.isclass(obj) or inspect.isroutine(obj) or hasattr(obj, "py_func")


def identity(module: str, name: str, obj: Any) -> object:
    """What makes two public names one object: the object itself for code, the assigning module
    and name for a constant (two constants may share a value, and small ints share an id)."""
    return ("code", id(obj)) if is_code(obj) else ("data", defining_module(module, name), name)


@functools.cache
def listing() -> tuple[Entry, ...]:
    """Every name of every public module's ``__all__``, with where it is documented."""
    home: dict[object, str] = {}
    entries = []
    for module_name in public_modules():
        module = importlib.import_module(module_name)
        for name in module.__all__:
            obj = getattr(module, name)
            if isinstance(obj, types.ModuleType):
                continue  # a module in an __all__ is documented as a module
            key = identity(module_name, name, obj)
            documented = home.setdefault(key, f"{module_name}.{name}")
            alias = is_alias(obj)
            entries.append(Entry(module_name, name, documented, alias, not alias and not is_code(obj)))
    return tuple(entries)


def documented_names() -> set[str]:
    """The full names that have a page of their own (``api/generated/<name>.html``): the functions
    and classes (:attr:`Entry.inline`)."""
    return {e.documented for e in listing() if not e.inline}


def html_page(name: str) -> str:
    """The built page (relative to the site) that documents a public name, with its anchor:
    ``api/generated/<name>.html`` or, for a constant or a type alias, its module's page."""
    entry = next(e for e in listing() if e.is_home and e.full == name)
    if entry.inline:
        return f"{module_html(entry.module)}#{name}"
    return f"api/generated/{name}.html#{name}"


def module_html(module_name: str) -> str:
    """The built page (relative to the site) of a public module: its API page for the root of one
    (``api/analysis.html``), else ``api/modules/<module>.html``."""
    roots = {p for _, _, prefixes, _ in API_PAGES for p in prefixes}
    if module_name in roots and _is_package(module_name):
        return f"api/{page_of(module_name)}.html"
    return f"api/modules/{module_name}.html"


_MISSING = object()


def lookup(path: str) -> Any:
    """The object at a dotted path (attributes first, importing submodules where one is
    missing), or ``_MISSING``; where that fails, from the longest importable module (the
    module ``tumble.dynamics.simulate`` behind the function of that name)."""
    parts = path.split(".")
    found = _walk(parts, 1)
    for n in range(len(parts) - 1, 1, -1):
        if found is not _MISSING:
            break
        try:
            importlib.import_module(".".join(parts[:n]))
        except ImportError:
            continue
        found = _walk(parts, n)
    return found


def _walk(parts: list[str], start: int) -> Any:
    """The object at ``parts``, from the module of its first ``start`` parts."""
    try:
        obj: Any = importlib.import_module(".".join(parts[:start]))
    except ImportError:
        return _MISSING
    prefix = ".".join(parts[:start])
    for part in parts[start:]:
        prefix = f"{prefix}.{part}"
        value = getattr(obj, part, _MISSING)
        if value is _MISSING and isinstance(obj, types.ModuleType):
            try:
                value = importlib.import_module(prefix)
            except ImportError:
                value = _MISSING
        if value is _MISSING and inspect.isclass(obj) and part in getattr(obj, "__annotations__", {}):
            value = (obj, part)  # a dataclass field without a default: a member of its class
        if value is _MISSING:
            return _MISSING
        obj = value
    return obj


def _module_or_object(path: str) -> Any:
    """The module of that name where there is one, else the object at the path."""
    try:
        return importlib.import_module(path)
    except ImportError:
        return lookup(path)


@functools.cache
def _by_identity() -> dict[object, str]:
    return {identity(e.module, e.name, getattr(importlib.import_module(e.module), e.name)): e.documented
            for e in listing() if e.is_home}


def page_for(path: str) -> str | None:
    """Where the reference documents the object a dotted name denotes: ``"mod:<module>"`` for a
    public module, ``"obj:<public name>"`` for a listed object, ``"obj:<public name>.<member>"``
    for a member of a listed class; None when it has no page (or does not exist)."""
    obj = lookup(path)
    if obj is _MISSING:
        return None
    if isinstance(obj, types.ModuleType):
        return f"mod:{path}" if path in public_modules() or path == "tumble" else None
    parent, _, attr = path.rpartition(".")
    owner = _module_or_object(parent) if parent else _MISSING
    if isinstance(owner, types.ModuleType):
        found = _by_identity().get(identity(parent, attr, obj))
        if found is None and not is_code(obj):  # a constant re-exported lazily (tumble's own __getattr__)
            found = next((e.documented for e in listing() if e.is_home and e.name == attr
                          and getattr(importlib.import_module(e.module), e.name) is obj), None)
        return f"obj:{found}" if found else None
    if inspect.isclass(owner):
        cls = page_for(parent)
        return f"{cls}.{attr}" if cls and cls.startswith("obj:") else None
    return None


# -- the pages ----------------------------------------------------------------------------------

def _ref(full: str, shown: str) -> str:
    return f":py:obj:`{shown} <{full}>`"


def _summary(module_name: str) -> str:
    """The first sentence of a module's docstring as plain text (its roles as literals: a role
    resolves in its own module's scope, not on the page that lists the module)."""
    doc = inspect.getdoc(importlib.import_module(module_name)) or ""
    first = doc.split("\n\n")[0].replace("\n", " ")
    first = re.sub(r":[a-z]+:`~?([^`<]*?)(?: <[^>]*>)?`", lambda m: f"``{m.group(1).rpartition('.')[2]}``", first)
    parts = re.split(r"(``.*?``)", first)  # |omega| outside literals is a norm, not a substitution
    return "".join(part if i % 2 else part.replace("|", "\\|") for i, part in enumerate(parts))


def _names_table(entries: list[Entry], toctree: str) -> list[str]:
    """An autosummary table of the functions and classes a page documents (bare: the current module
    is set), its constants and type aliases as entries after it."""
    lines = []
    own = [e for e in entries if e.is_home and not e.inline]
    if own:
        lines += [".. autosummary::", f"   :toctree: {toctree}", "   :nosignatures:", ""]
        lines += [f"   {e.name}" for e in own]
        lines.append("")
    for e in entries:
        if e.is_home and e.data:
            lines += [f".. autodata:: {e.name}", ""]
        elif e.is_home and e.alias:
            lines += [f".. py:data:: {e.name}", f"   :value: {_alias_text(e)}", ""]
            comment = _comment(e.module, e.name)
            if comment:
                lines += [f"   {line}" for line in comment] + [""]
    others = [e for e in entries if not e.is_home]
    if others:
        lines += ["Also here, documented under their public names: "
                  + ", ".join(_ref(e.documented, e.name) for e in others) + ".", ""]
    return lines


def _alias_text(entry: Entry) -> str:
    text = repr(getattr(importlib.import_module(entry.module), entry.name))
    return re.sub(r"\b(?:numpy|typing|tumble(?:\.[a-z_]+)*)\.", "", text)


def _comment(module_name: str, name: str) -> list[str]:
    """The ``#:`` comment above a name's assignment in its module, as lines."""
    from sphinx.pycode import ModuleAnalyzer

    return list(ModuleAnalyzer.for_module(module_name).find_attr_docs().get(("", name), []))


def render_module_page(module_name: str) -> str:
    """The reStructuredText of one module's page: its docstring, an autosummary table of the
    names it documents (one generated page each) and links to the names it re-exports."""
    title = f"``{module_name}``"
    entries = [e for e in listing() if e.module == module_name]
    lines = [title, "=" * len(title), "", f".. automodule:: {module_name}", "   :no-members:"]
    if module_name in documented_names():  # tumble.dynamics.simulate: the function has the name
        lines.append("   :no-index:")
        lines += ["", f".. currentmodule:: {module_name}"]
    lines.append("")
    return "\n".join(lines + _names_table(entries, "../generated"))


def render_api_page(stem: str) -> str:
    """The reStructuredText of one API page: the intro, the root package's names (if the page
    has one) and a table of its modules, each with its own page."""
    _, title, prefixes, intro = next(p for p in API_PAGES if p[0] == stem)
    lines = [title, "=" * len(title), ""]
    if intro:
        lines += [intro, ""]
    modules = [m for m in sorted(public_modules()) if page_of(m) == stem]
    roots = [m for m in modules if m in prefixes and _is_package(m)]
    for root in roots:
        lines += [f".. automodule:: {root}", "   :no-members:", ""]
        lines += _names_table([e for e in listing() if e.module == root], "generated")
    rest = [m for m in modules if m not in roots]
    if rest:
        heading = "Modules"
        lines += [heading, "-" * len(heading), ""]
        lines += [f"- :py:mod:`{m}`: {_summary(m)}" for m in rest]
        lines += ["", ".. toctree::", "   :hidden:", ""]
        lines += [f"   modules/{m}" for m in rest]
        lines.append("")
    return "\n".join(lines)


def _is_package(module_name: str) -> bool:
    spec = importlib.import_module(module_name).__spec__
    return spec is not None and spec.submodule_search_locations is not None


def _write(path: Path, text: str) -> None:
    """Write only a changed text, so that an unchanged page is not rebuilt."""
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")


def write_api_pages(docs: Path) -> list[str]:
    """Write docs/api/<stem>.rst for each of :data:`API_PAGES`, docs/api/modules/<module>.rst for
    each public module not the root of its page, and remove the pages of names and modules no
    longer listed (they would stand outside every table of contents). Returns the pages written
    (relative to ``docs``): autosummary's ``autosummary_generate``, so that a new module's page
    gets its stubs in an incremental build too (autosummary scans only the documents of the
    previous build when given ``True``)."""
    api = docs / "api"
    for stem, *_ in API_PAGES:
        _write(api / f"{stem}.rst", render_api_page(stem))
    roots = {p for _, _, prefixes, _ in API_PAGES for p in prefixes}
    modules = {m for m in public_modules() if not (m in roots and _is_package(m))}
    for module_name in modules:
        _write(api / "modules" / f"{module_name}.rst", render_module_page(module_name))
    for stale in (api / "modules").glob("*.rst"):
        if stale.stem not in modules:
            stale.unlink()
    names = documented_names()
    for stale in (api / "generated").glob("*.rst") if (api / "generated").is_dir() else ():
        if stale.stem not in names:
            stale.unlink()
    return [f"api/{stem}.rst" for stem, *_ in API_PAGES] + [f"api/modules/{m}.rst" for m in sorted(modules)]


def api_modules() -> list[str]:
    """The modules the reference documents (for the cross-reference resolver)."""
    return ["tumble", *public_modules()]


# -- names in the text --------------------------------------------------------------------------

#: A dotted name of tumble in prose or code: not part of a path (``src/tumble/...``) or a longer name.
NAME = re.compile(r"(?<![\w./\\-])tumble(?:\.[A-Za-z_]\w*)+(?!\w|\*|\.[\w*])")
#: Last parts that make a dotted word a file name, not a Python name (``tumble.toml``).
FILE_SUFFIXES = frozenset({"toml", "html", "json", "csv", "png", "svg", "gif", "mp4", "md", "rst", "py", "txt",
                           "npz", "parquet", "zip", "ipynb", "log", "cff", "yml", "yaml", "cfg", "whl"})


#: ``from tumble.x import a, b`` (names in parentheses over several lines too).
IMPORT = re.compile(r"^[ \t>.]*from[ \t]+(tumble(?:\.\w+)*)[ \t]+import[ \t]+(\([^)]*\)|[^\n#]+)", re.MULTILINE)


def names_in(text: str) -> list[tuple[int, str]]:
    """``(line number, name)`` of every dotted ``tumble.`` name in a text (file names left out),
    and ``tumble.x.a`` for every ``from tumble.x import a``."""
    found = []
    for number, line in enumerate(text.splitlines(), 1):
        for match in NAME.finditer(line):
            name = match.group(0)
            if name.rpartition(".")[2] not in FILE_SUFFIXES:
                found.append((number, name))
    for match in IMPORT.finditer(text):
        number = text.count("\n", 0, match.start()) + 1
        for item in match.group(2).strip("()").replace("\\", " ").split(","):
            name = item.split(" as ")[0].strip()
            if re.fullmatch(r"[A-Za-z_]\w*", name):
                found.append((number, f"{match.group(1)}.{name}"))
    return found


def html_target(page: str) -> tuple[str, str | None]:
    """The built file (relative to the site) and the anchor (an ``id``) of a :func:`page_for`
    result; the anchor is None for a module page whose module shares its name with a function
    (``tumble.dynamics.simulate``: the function's page holds that id)."""
    kind, _, name = page.partition(":")
    if kind == "mod":
        if name == "tumble":
            return "api/index.html", "module-tumble"
        page = module_html(name)
        if page.startswith("api/modules/") and name in documented_names():
            return page, None
        return page, f"module-{name}"
    documented = documented_names()
    owner = name
    while owner not in documented and "." in owner and not any(e.inline and e.full == owner for e in listing()):
        owner = owner.rpartition(".")[0]
    if owner not in documented:
        return html_page(owner).partition("#")[0], name
    return f"api/generated/{owner}.html", name
