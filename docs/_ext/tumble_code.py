"""Code blocks whose long lines wrap under themselves, not at column 0 (issue 40).

The site wraps a code block's long lines (docs/_static/tumble.css: ``white-space: pre-wrap``) so
that a comment past the column stays readable; but a wrapped line went on at the block's left
edge, where it read as a new line of code. CSS indents the continuation of a line only when the
line is an element of its own: this extension has Pygments write each line of a highlighted
block as ``<span class="line">`` (``style="--indent: N"`` when it starts with N spaces), and the
stylesheet gives the span a hanging indent of its own indentation plus four columns. The text
of the block, and what a reader copies, is unchanged: the spans hold no characters of their own
and the newlines stay between them.
"""

from __future__ import annotations

import re

from pygments.formatters.html import HtmlFormatter
from sphinx.application import Sphinx
from sphinx.highlighting import PygmentsBridge

_TAG = re.compile(r"<[^>]*>")


def _indent(html_line: str) -> int:
    """Leading spaces of a highlighted line's text (its markup left out)."""
    text = _TAG.sub("", html_line)
    return len(text) - len(text.lstrip(" "))


class LineFormatter(HtmlFormatter):
    """Pygments' HTML with each line of code in ``<span class="line">``."""

    def wrap(self, source):
        return super().wrap(self._lines(source))

    @staticmethod
    def _lines(source):
        for kind, text in source:
            if kind != 1:
                yield kind, text
                continue
            if text.endswith("\n"):
                body, end = text[:-1], "\n"
            elif text.endswith("\n</span>"):  # an emphasised line (hl_lines): its newline moved out too
                body, end = text[:-8] + "</span>", "\n"
            else:
                body, end = text, ""
            n = _indent(body)
            style = f' style="--indent: {n}"' if n else ""
            yield kind, f'<span class="line"{style}>{body}</span>{end}'


def setup(app: Sphinx) -> dict:
    PygmentsBridge.html_formatter = LineFormatter
    return {"parallel_read_safe": True, "parallel_write_safe": True}
