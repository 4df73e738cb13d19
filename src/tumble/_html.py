"""Text and JSON pasted into HTML, escaped: the one place every page and display of tumble uses.

A user's strings (a body's name, a scenario file's name, a title) reach HTML in two ways:

* as text or an attribute value: :func:`escape_text` (``&``, ``<``, ``>``, ``"`` and ``'`` as
  character references);
* inside a ``<script type="application/json">`` element: :func:`script_json`. A script's text
  ends at the first ``</script``, and after ``<!--`` a ``<script`` makes the parser swallow the
  rest of the document up to a second ``</script>`` (the HTML standard's "script data double
  escaped" state): the viewer's own scripts would be eaten and the page left blank. JSON
  allows any character as ``\\uXXXX``, so ``<``, ``>`` and ``&`` are written so and the element
  cannot hold markup at all (the escaping of the OWASP XSS prevention cheat sheet, rule 3.1).
"""

from __future__ import annotations

import html
import json

__all__ = ["escape_text", "script_json"]

#: Characters written as JSON escapes in :func:`script_json`: markup (``<``, ``>``, ``&``) and the
#: two line separators that end a line in JavaScript before ES2019.
_SCRIPT_ESCAPES = {ord(c): f"\\u{ord(c):04x}" for c in "<>&\u2028\u2029"}


def escape_text(value) -> str:
    """``str(value)`` as HTML text or a quoted attribute value (``html.escape``, quotes too).

    Examples
    --------
    >>> escape_text('a <b> & "c"')
    'a &lt;b&gt; &amp; &quot;c&quot;'
    """
    return html.escape(str(value), quote=True)


def script_json(data) -> str:
    """Compact JSON of ``data`` to paste inside ``<script type="application/json">``: it holds no
    ``<``, ``>`` or ``&`` (each written as its ``\\uXXXX`` escape), so no text of the data can
    end or change the element; ``JSON.parse`` of the element's text gives ``data`` back.

    Examples
    --------
    >>> script_json({"name": "</script><!--<script>"})
    '{"name":"\\\\u003c/script\\\\u003e\\\\u003c!--\\\\u003cscript\\\\u003e"}'
    """
    return json.dumps(data, separators=(",", ":")).translate(_SCRIPT_ESCAPES)
