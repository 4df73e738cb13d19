"""griffe extension: read tumble's Sphinx-style markup for the API reference.

tumble's docstrings are numpydoc and use three pieces of Sphinx markup that griffe does not read:

- ``#:`` comments above a module constant, its documentation (Sphinx autodoc's attribute
  comments); they become the constant's docstring, so ``INERTIA_RTOL`` and the like appear in
  the reference with their text;
- literal blocks, a paragraph ending in ``::`` and an indented block (the formulas); each
  becomes a fenced code block;
- cross-reference roles, ``:func:`name```, ``:class:`~tumble.mass.Body```, ...; each becomes a
  link to the object's entry when the reference renders one, and plain code otherwise. Names are
  resolved the way Python would from the docstring's scope (imports included); ``tumble.X`` for a
  top-level name goes to the subpackage that defines it (``tumble._EXPORTS``), since griffe cannot
  follow the lazy ``__getattr__``.

A public constant whose value is longer than a line (``METHODS``, a dict of ``Method`` objects built
from private functions) is shown by its type and docstring alone.

Used by mkdocs.yml (``extensions`` of the mkdocstrings Python handler); it changes nothing in the
package, only what the documentation build reads. The package griffe-sphinx does the first part
alone; the others have no package.
"""

from __future__ import annotations

import ast
import html
import re

import griffe

_ROLE = re.compile(r":(?:py:)?(?:func|class|mod|data|meth|attr|obj|exc|const):`(?P<name>[^`]+)`")
_LONGEST_VALUE = 80  # characters of a constant's value shown in its signature
_LINK = '<autoref identifier="{target}" optional><code>{text}</code></autoref>'


def _indent(line: str) -> int:
    return len(line) - len(line.lstrip())


def _literal_blocks(text: str) -> str:
    """reST literal blocks (``text::`` + an indented block) as fenced Markdown code blocks."""
    lines = text.split("\n")
    out: list[str] = []
    i = 0
    while i < len(lines):
        line = lines[i]
        j = i + 1
        while j < len(lines) and not lines[j].strip():
            j += 1
        if not line.rstrip().endswith("::") or j == len(lines) or _indent(lines[j]) <= _indent(line):
            out.append(line)
            i += 1
            continue
        head = line.rstrip()[:-2]
        if head.strip():  # "text::" reads "text:", "text ::" reads "text" (the reST rule)
            out.append(head.rstrip() if head.endswith(" ") else head + ":")
        # inside a list item, Python-Markdown wants the block indented by four
        fence = " " * (_indent(line) + (4 if line.lstrip().startswith(("- ", "* ")) else 0))
        end = j
        while end < len(lines) and (not lines[end].strip() or _indent(lines[end]) >= _indent(lines[j])):
            end += 1
        while not lines[end - 1].strip():
            end -= 1
        cut = _indent(lines[j])
        out += ["", fence + "```text", *(fence + row[cut:] if row.strip() else "" for row in lines[j:end]),
                fence + "```"]
        i = end
    return "\n".join(out)


def _comment_above(lines: list[str], lineno: int) -> str | None:
    """The ``#:`` comment lines directly above line ``lineno`` (1-based), without the marker."""
    found = []
    index = lineno - 2
    while index >= 0 and lines[index].lstrip().startswith("#:"):
        found.append(lines[index].lstrip()[2:].strip())
        index -= 1
    return "\n".join(reversed(found)) or None


def _top_level_exports(package: griffe.Module) -> dict[str, str]:
    """``tumble._EXPORTS`` read from the source: top-level name -> subpackage that defines it."""
    exports = package.members.get("_EXPORTS")
    if exports is None or exports.value is None:
        return {}
    return ast.literal_eval(str(exports.value))


def _target(obj: griffe.Object, name: str, exports: dict[str, str]) -> str | None:
    """The full path ``name`` refers to from ``obj``'s scope, or None when it is not tumble's."""
    name = name.lstrip(".")
    first, _, rest = name.partition(".")
    if first == "tumble":
        top, _, tail = rest.partition(".")
        if top in exports:
            return ".".join(filter(None, (exports[top], top, tail)))
        return name
    try:
        resolved = obj.resolve(first)
    except griffe.NameResolutionError:
        return None
    path = ".".join(filter(None, (resolved, rest)))
    return path if path.startswith("tumble.") else None


def _rewrite(obj: griffe.Object, exports: dict[str, str]) -> None:
    """Replace the roles in ``obj``'s docstring and in its members', recursively."""
    if obj.docstring is not None:

        def link(match: re.Match) -> str:
            name = match["name"]
            text = name.split(".")[-1] if name.startswith("~") else name.lstrip("~")
            target = _target(obj, name.lstrip("~"), exports)
            if target is None:
                return f"``{text}``"
            return _LINK.format(target=html.escape(target), text=html.escape(text))

        obj.docstring.value = _ROLE.sub(link, _literal_blocks(obj.docstring.value))
    for member in obj.members.values():
        if not member.is_alias:
            _rewrite(member, exports)


class SphinxMarkup(griffe.Extension):
    """Attribute comments to docstrings, literal blocks to code blocks, roles to links."""

    def on_attribute_instance(self, *, node, attr: griffe.Attribute, **kwargs) -> None:
        if attr.is_public and attr.value is not None and len(str(attr.value)) > _LONGEST_VALUE:
            attr.value = None
        if attr.docstring is not None or attr.lineno is None or attr.filepath is None:
            return
        try:
            lines = attr.lines_collection[attr.filepath]
        except KeyError:
            return
        text = _comment_above(lines, attr.lineno)
        if text:
            attr.docstring = griffe.Docstring(text, lineno=attr.lineno, parent=attr)

    def on_package(self, *, pkg: griffe.Module, **kwargs) -> None:
        _rewrite(pkg, _top_level_exports(pkg))
