"""Sphinx extension: a file format's reference tables, rendered from the tables its parser uses.

In a page (MyST)::

    ```{tumble-keys} tumble.io.sweepfile.SWEEP_FORMAT
    ```

renders each :class:`tumble.io.keys.Table` of the :class:`tumble.io.keys.FileFormat` as a heading
(the table as the file writes it), its description and one row per key: the key, its type, unit,
default, the values allowed, an example and what it is. The parser refuses any key not in these
tables, so a key on the page is a key the parser takes, and the other way round
(tests/test_file_keys.py).
"""

from __future__ import annotations

import importlib
import re

from docutils import nodes
from docutils.parsers.rst import Parser
from docutils.utils import new_document
from sphinx.util.docutils import SphinxDirective

_LITERAL = re.compile(r"(``.*?``|:[a-z]+:`[^`]*`)")
COLUMNS = ("key", "type", "unit", "default", "allowed", "example", "what it is")


def _plain(text: str) -> str:
    """Text for a table cell: reStructuredText's markup characters escaped (``|B|`` is a norm,
    ``*`` a product), literals and roles left as they are."""
    parts = _LITERAL.split(text)
    return "".join(part if i % 2 else re.sub(r"([|*\\`_])", r"\\\1", part) for i, part in enumerate(parts))


def _literal(text: str) -> str:
    return f"``{text}``" if text else ""


def load_format(path: str):
    """The object at ``module.NAME``."""
    module, _, name = path.rpartition(".")
    return getattr(importlib.import_module(module), name)


def render_format(fmt) -> str:
    """The reStructuredText of a file format's tables."""
    lines: list[str] = []
    for table in fmt.tables:
        lines += [f".. rubric:: {_plain(table.title)}", f"   :class: tumble-keys-table", ""]
        if table.doc:
            lines += [table.doc, ""]
        lines += [".. list-table::", "   :header-rows: 1", "   :class: tumble-keys", ""]
        lines += ["   * - " + COLUMNS[0], *(f"     - {c}" for c in COLUMNS[1:])]
        for key in table.keys:
            default = "(required)" if key.required else key.default
            cells = [_literal(key.name), _plain(key.type), _plain(key.unit), _plain(default),
                     _plain(key.allowed_text()), _literal(key.example), _plain(key.doc)]
            lines += [f"   * - {cells[0]}", *(f"     - {c}" if c else "     -" for c in cells[1:])]
        lines.append("")
    return "\n".join(lines)


class KeysDirective(SphinxDirective):
    """``tumble-keys``: the tables of the :class:`~tumble.io.keys.FileFormat` named by the argument."""

    required_arguments = 1
    has_content = False

    def run(self) -> list[nodes.Node]:
        text = render_format(load_format(self.arguments[0]))
        # parsed as reStructuredText whatever the page's own markup (MyST's nested parse would read Markdown)
        document = new_document(self.get_source_info()[0], self.state.document.settings)
        document.reporter = self.state.document.reporter
        Parser().parse(text, document)
        return list(document.children)


def setup(app):
    app.add_directive("tumble-keys", KeysDirective)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
