"""Sphinx extension: cross-references to tumble's names, resolved the way Python resolves them.

tumble's docstrings name objects where they are defined (``:func:`tumble.analysis.fit.fit_rotation```),
through the top-level names (``:func:`tumble.simulate```) or bare, in the scope of their module
(``:data:`ROUND_OFF```); the API reference documents each object once, under its public name
(``tumble.analysis.fit_rotation``). For a reference Sphinx cannot find by its text, this looks the
name up in Python (the module of the page's object, its class, the module named in the target) and:

- an object the API reference documents (the same object, found by identity) links to its page;
- a member of such a class links to the member's entry on the class page;
- a module of tumble links to the module the API reference documents above it (its subpackage);
- a name that exists in tumble but is not public (a module's constant, a helper) is shown as
  code with no link: there is no page to link to, and the name is still checked to exist;
- anything else stays unresolved, and the strict build fails on it (a misspelt or stale name).

Names of other packages (numpy's ``ArrayLike``, scipy's ``Rotation``) found this way are shown as
code too: without intersphinx (it downloads inventories) they cannot be linked offline.
"""

from __future__ import annotations

import inspect
import re
import types
from pathlib import Path
from typing import Any

import tumble_api

#: The one walk from a dotted path to its object, with its "nothing there" marker (tumble_api).
_import_path = tumble_api.lookup
_MISSING = tumble_api._MISSING


class Resolver:
    """Maps objects to the public names under which the API reference documents them
    (:func:`tumble_api.page_for`)."""

    def __init__(self, modules: list[str]):
        self.modules: set[str] = set(modules)

    def scopes(self, node, docname: str) -> list[str]:
        """Where a name in this reference may live: the module and class the directive sets, and
        the defining module (and class) of the object whose page holds the reference."""
        found = []
        module, cls = node.get("py:module"), node.get("py:class")
        if module and cls:
            found.append(f"{module}.{cls}")
        if module:
            found.append(module)
        page_object = _import_path(docname.rsplit("/", 1)[-1]) if docname.startswith("api/generated/") else _MISSING
        if page_object is not _MISSING:
            owner = page_object if inspect.isclass(page_object) else None
            defining = getattr(page_object, "__module__", None)
            if owner is not None and defining:
                found.append(f"{defining}.{owner.__name__}")
            if defining:
                found.append(defining)
        if cls and module:
            found.append(cls)
        return found

    def public_name(self, path: str) -> str | None:
        """The documented name of the object at ``path`` (or of its class's entry)."""
        page = tumble_api.page_for(path)
        if page is None:
            parent, _, member = path.rpartition(".")
            owner = _import_path(parent) if parent else _MISSING
            if inspect.isclass(owner):  # a member found through the class's defining module
                cls = tumble_api.page_for(f"{owner.__module__}.{owner.__qualname__}")
                page = f"{cls}.{member}" if cls and cls.startswith("obj:") else None
        return page.removeprefix("obj:") if page and page.startswith("obj:") else None

    def locate(self, target: str, node, docname: str) -> str | None:
        """The full dotted path at which ``target`` exists, or None. A name a module imports only
        for its annotations (under ``TYPE_CHECKING``) is followed to where it comes from."""
        target = target.lstrip("~.")
        scopes = self.scopes(node, docname)
        for scope in ["", *scopes]:
            path = f"{scope}.{target}" if scope else target
            if _import_path(path) is not _MISSING:
                return path
        head, _, rest = target.partition(".")
        for scope in scopes:
            origin = imported_names(scope).get(head)
            if origin is not None:
                path = f"{origin}.{rest}" if rest else origin
                if _import_path(path) is not _MISSING:
                    return path
        return None


imported_names = tumble_api.imported_names
defining_module = tumble_api.defining_module


def data_docstring(app, what, name, obj, options, lines):
    """A re-exported constant keeps its ``#:`` comment: autodoc reads comments in the module it
    documents the name under, which for ``tumble.mass.INERTIA_RTOL`` only imports it; without
    this it shows the docstring of the value's type (``str(object='') -> str``)."""
    if what not in ("data", "attribute") or not name.startswith("tumble."):
        return
    module_name, _, attr = name.rpartition(".")
    if not isinstance(_import_path(module_name), types.ModuleType):
        return  # a class attribute: autodoc reads the class's own source
    from sphinx.pycode import ModuleAnalyzer

    origin = defining_module(module_name, attr)
    comment = ModuleAnalyzer.for_module(origin).find_attr_docs().get(("", attr))
    # with no comment, what autodoc finds is the docstring of the value's type (int's, dict's, a
    # dataclass's), which says nothing of the constant: the entry shows its value alone
    lines[:] = [*comment] if comment else []


def _documented_module(path: str, modules: set[str]) -> str | None:
    """The nearest module at or above ``path`` that the API reference documents."""
    parts = path.split(".")
    for n in range(len(parts), 0, -1):
        if ".".join(parts[:n]) in modules:
            return ".".join(parts[:n])
    return None


def missing_reference(app, env, node, contnode):
    if node.get("refdomain") != "py":
        return None
    resolver = _RESOLVER[0]
    path = resolver.locate(node["reftarget"], node, node.get("refdoc", ""))
    if path is None:
        return None
    domain = env.domains["py"]
    obj = _import_path(path)
    if isinstance(obj, types.ModuleType):
        target = _documented_module(path, resolver.modules)
        kind = "mod"
    else:
        target = resolver.public_name(path)
        kind = "obj"
    if target is not None:
        resolved = domain.resolve_xref(env, node["refdoc"], app.builder, kind, target, node, contnode)
        if resolved is not None:
            return resolved
    return contnode  # exists, but has no page: code, no link


_RESOLVER: list[Resolver] = []


_LITERAL = re.compile(r"(``.*?``|`[^`]*`)")


def _escape_bars(text: str) -> str:
    """``|`` escaped outside literals and roles: ``|L|`` is a norm, not a substitution."""
    return "".join(part if i % 2 else part.replace("|", "\\|") for i, part in enumerate(_LITERAL.split(text)))


def norm_bars(app, what, name, obj, options, lines):
    """tumble's docstrings write norms as ``|L|`` and ``|omega|``, plain-text notation that
    reStructuredText would read as substitution references (an error each): escape those bars,
    leaving literals, roles and literal blocks (after ``::``) as they are."""
    block_indent = None
    after_colons = False
    for i, line in enumerate(lines):
        indent = len(line) - len(line.lstrip())
        if block_indent is not None:
            if line.strip() and indent <= block_indent:
                block_indent = None
            else:
                continue
        if after_colons and line.strip():
            after_colons = False
        if "|" in line:
            lines[i] = _escape_bars(line)
        if line.rstrip().endswith("::"):
            block_indent, after_colons = indent, True


def _plain_alias_names() -> None:
    """An alias of ``autodoc_type_aliases`` inside a union (``FloatArray | None``) written as its name,
    ``tumble.typing.FloatArray | None``: Sphinx 9.0 writes the repr of its placeholder there,
    ``TypeAliasForwardRef('tumble.typing.FloatArray') | None`` (in signatures and properties' types),
    where alone it writes the name."""
    from sphinx.util import inspect

    placeholder = getattr(inspect, "TypeAliasForwardRef", None)
    if placeholder is not None:
        placeholder.__repr__ = lambda self: self.name


def _make_resolver(app):
    _RESOLVER[:] = [Resolver(app.config.tumble_api_modules)]


#: A ``[docs]`` link of a highlighted module (sphinx.ext.viewcode) back to an object's page.
_BACK_LINK = re.compile(r'(class="viewcode-back" href="[^"#]*/)([^"#/]+\.html)#([^"]+)"')
_ID = re.compile(r'\bid="([^"]+)"')


def mend_back_links(site: Path) -> int:
    """Point every ``[docs]`` link of the highlighted modules (``_modules/``) at an anchor its page
    has; returns how many were mended.

    sphinx.ext.viewcode keeps one documented module per source module and builds each link's anchor
    from it, so an object re-exported under several names (``tumble.analysis.fit.Adequacy``,
    documented as ``tumble.analysis.fit.adequacy.Adequacy``) got the page of one name and the anchor
    of another: 116 of ~950 links opened their page without reaching the object. A link whose
    anchor is not on its page takes the page's one anchor that ends with the same trailing names
    (the object, or the class and its member), the fewest that single one out."""
    ids: dict[Path, list[str]] = {}
    mended = 0
    for page in (site / "_modules").rglob("*.html"):
        text = page.read_text(encoding="utf-8")

        def mend(m: re.Match) -> str:
            nonlocal mended
            target = (page.parent / m.group(1).split('href="', 1)[1] / m.group(2)).resolve()
            if target not in ids:
                ids[target] = _ID.findall(target.read_text(encoding="utf-8")) if target.is_file() else []
            if m.group(3) in ids[target]:
                return m.group(0)
            parts = m.group(3).split(".")
            for k in range(1, len(parts) + 1):
                tail = "." + ".".join(parts[-k:])
                found = [i for i in ids[target] if i.endswith(tail)]
                if len(found) == 1:
                    mended += 1
                    return f'{m.group(1)}{m.group(2)}#{found[0]}"'
            return m.group(0)

        lean = _BACK_LINK.sub(mend, text)
        if lean != text:
            page.write_text(lean, encoding="utf-8")
    return mended


def _finished(app, exception):
    if exception is None and app.builder.format == "html" and (Path(app.outdir) / "_modules").is_dir():
        mend_back_links(Path(app.outdir))


def setup(app):
    _plain_alias_names()
    app.add_config_value("tumble_api_modules", [], "env")
    app.connect("builder-inited", _make_resolver)
    app.connect("missing-reference", missing_reference)
    app.connect("build-finished", _finished)
    app.connect("autodoc-process-docstring", data_docstring)
    app.connect("autodoc-process-docstring", norm_bars)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
