"""Code blocks whose long lines wrap under themselves, not at column 0 (issue 40).

The site wraps a code block's long lines (docs/_static/tumble.css: ``white-space: pre-wrap``) so
that a comment past the column stays readable; but a wrapped line went on at the block's left
edge, where it read as a new line of code. CSS indents the continuation of a line only when the
line is an element of its own: this extension has Pygments write each line of a highlighted
block that could wrap (longer than :data:`SHORT` characters) as ``<span class="l">``
(``style="--i:N"`` when it starts with N spaces), and the stylesheet gives the span a hanging
indent of its own indentation plus four columns. The text of the block, and what a reader
copies, is unchanged: the spans hold no characters of their own and the newlines stay between
them. Short lines, which no column on the site wraps, are left bare: the module sources the
site shows (sphinx.ext.viewcode, some 50,000 lines) grow by less than a megabyte.
"""

from __future__ import annotations

import re

from pygments.formatters.html import HtmlFormatter
from sphinx.application import Sphinx
from sphinx.highlighting import PygmentsBridge

_TAG = re.compile(r"<[^>]*>")
#: A line of at most this many characters is never wrapped on the site (its narrowest code column
#: holds some 40): it gets no span.
SHORT = 40


def _text(html_line: str) -> str:
    """A highlighted line's text, its markup left out (its entities count as one character each)."""
    return re.sub(r"&[#\w]+;", "_", _TAG.sub("", html_line))


class LineFormatter(HtmlFormatter):
    """Pygments' HTML with each line of code that could wrap in ``<span class="l">``."""

    def wrap(self, source):
        return super().wrap(self._lines(source))

    @staticmethod
    def _lines(source):
        for kind, line in source:
            if kind != 1 or len(_text(line).rstrip("\n")) <= SHORT:  # markup, or a line that never wraps
                yield kind, line
                continue
            if line.endswith("\n"):
                body, end = line[:-1], "\n"
            elif line.endswith("\n</span>"):  # an emphasised line (hl_lines): its newline moved out too
                body, end = line[:-8] + "</span>", "\n"
            else:
                body, end = line, ""
            text = _text(body)
            n = len(text) - len(text.lstrip(" "))
            style = f' style="--i:{n}"' if n else ""
            yield kind, f'<span class="l"{style}>{body}</span>{end}'


def setup(app: Sphinx) -> dict:
    PygmentsBridge.html_formatter = LineFormatter
    return {"parallel_read_safe": True, "parallel_write_safe": True}
