"""A lighter site (issue 40: at most 40 MB), the same pages to a reader.

The site was 196 MB, then 49 MB with the API pages' sidebar collapsed and left off (docs/conf.py).
Most of what remained was markup no reader sees; once the build has finished (after
sphinx-gallery has linked the names in its examples' code), every page is rewritten:

- **comments**: the theme's templates leave their comments in every page (0.4 MB); outside
  ``<pre>``, ``<textarea>``, ``<script>`` and ``<style>`` they are taken off (:func:`drop_comments`);
- **indentation**: the theme's templates indent every line of a page's header, sidebars and
  footer (about 2 KB a page, some 1300 pages). Outside ``<pre>``, ``<textarea>``, ``<script>``
  and ``<style>`` a run of whitespace that holds a line break becomes one line break: HTML shows
  either as one space (:func:`collapse_whitespace`);
- **code**: Pygments wraps every token of a highlighted block in a span, names, punctuation and
  spaces too, though the site's styles give these the block's own colour (a third of the module
  sources' pages, sphinx.ext.viewcode's ``_modules/``). The spans of the token classes that the
  site's pygments.css colours as the block's text, in the light and the dark style alike
  (:func:`plain_classes`), are taken off; their text stays (:func:`unwrap_plain`). A style that
  colours them keeps them;
- **source maps**: the theme ships a ``.map`` beside its scripts and stylesheet (1.9 MB) that only
  a browser's developer tools read. They are left out, with the comments that name them;
- **the gallery's stylesheets**: sphinx-gallery links its four on every page; a page gets them
  only where it shows the gallery's markup (its examples, an API page's "Examples using");
- **other packages' sources**: sphinx.ext.viewcode follows a documented name to the module that
  defines it and writes that module's highlighted source. A type alias, a ``functools`` wrapper
  or a ``types`` object led it to ``typing``, ``functools``, ``types`` and ``numpy`` (0.54 MB of
  Python's and numpy's code, which the reader has). Only tumble's modules get a source page
  (:func:`tumble_source_only`).

What a page shows, what a reader copies from a code block and every link are unchanged.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from pathlib import Path

from sphinx.application import Sphinx

#: Elements whose text is kept as written.
_KEEP = re.compile(r"(<(pre|textarea|script|style)\b.*?</\2>)", re.S | re.I)
_BREAK = re.compile(r"[ \t\r\f]*\n\s*")
_RULE = re.compile(r'html\[data-theme="(light|dark)"\] \.highlight(?: \.([\w-]+))? \{ ([^}]*?) \}')
_COMMENT = re.compile(r"<!--.*?-->", re.S)
_MAP = re.compile(r"\n?(?://# sourceMappingURL=\S+|/\*# sourceMappingURL=[^*\s]+\s*\*/)\s*$")


def _outside_kept(html: str, change: Callable[[str], str]) -> str:
    """``html`` with ``change`` applied to its text outside ``pre``, ``textarea``, ``script`` and ``style``."""
    parts = _KEEP.split(html)
    # split gives text, a kept element, its tag name, text, ...: only the text between is changed
    return "".join(change(part) if i % 3 == 0 else part if i % 3 == 1 else "" for i, part in enumerate(parts))


def collapse_whitespace(html: str) -> str:
    """Each run of whitespace holding a line break, outside ``pre``, ``textarea``, ``script`` and
    ``style``, as one line break.

    Examples
    --------
    >>> from tumble_lean import collapse_whitespace
    >>> collapse_whitespace("<div>\\n    <p>a\\n\\n   b</p>\\n</div><pre>x\\n    y</pre>")
    '<div>\\n<p>a\\nb</p>\\n</div><pre>x\\n    y</pre>'
    """
    return _outside_kept(html, lambda text: _BREAK.sub("\n", text))


def drop_comments(html: str) -> str:
    """``html`` without its comments outside ``pre``, ``textarea``, ``script`` and ``style``.

    Examples
    --------
    >>> from tumble_lean import drop_comments
    >>> drop_comments("<p>a<!-- a note\\n on two lines -->b</p><script>/*<!-- kept -->*/</script>")
    '<p>ab</p><script>/*<!-- kept -->*/</script>'
    """
    return _outside_kept(html, lambda text: _COMMENT.sub("", text))


def plain_classes(css: str) -> frozenset[str]:
    """The token classes that a Pygments stylesheet of the theme's colours as the block's own text,
    in its light and its dark style.

    Examples
    --------
    >>> from tumble_lean import plain_classes
    >>> css = '''html[data-theme="light"] .highlight { background: #fefefe; color: #080808 }
    ... html[data-theme="light"] .highlight .n { color: #080808 } /* Name */
    ... html[data-theme="light"] .highlight .k { color: #8045E5 } /* Keyword */
    ... html[data-theme="light"] .highlight .p { color: #080808 } /* Punctuation */
    ... html[data-theme="dark"] .highlight { background: #2b2b2b; color: #F8F8F2 }
    ... html[data-theme="dark"] .highlight .n { color: #F8F8F2 } /* Name */
    ... html[data-theme="dark"] .highlight .p { color: #F8F8F2; font-weight: bold } /* Punctuation */'''
    >>> sorted(plain_classes(css))   # p is bold in the dark style: kept
    ['n']
    """
    base: dict[str, str] = {}
    rules: dict[str, dict[str, str]] = {"light": {}, "dark": {}}
    for theme, cls, body in _RULE.findall(css):
        if cls:
            rules[theme][cls] = body.strip()
        else:
            color = re.search(r"(?:^|;)\s*(color:\s*#\w+)", body)
            if color:
                base[theme] = color.group(1)
    plain = [{c for c, body in rules[t].items() if body == base[t]} if t in base else set() for t in ("light", "dark")]
    return frozenset(plain[0] & plain[1])


def unwrap_plain(html: str, classes: frozenset[str]) -> str:
    """``html`` with the spans of the token classes ``classes`` inside ``<pre>`` taken off, their
    text kept.

    Examples
    --------
    >>> from tumble_lean import unwrap_plain
    >>> page = '<p><span class="n">x</span></p><pre><span class="n">x</span><span class="o">=</span></pre>'
    >>> unwrap_plain(page, frozenset({"n"}))
    '<p><span class="n">x</span></p><pre>x<span class="o">=</span></pre>'
    """
    if not classes:
        return html
    span = re.compile(r'<span class="(?:' + "|".join(map(re.escape, sorted(classes))) + r')">([^<]*)</span>')
    return re.sub(r"<pre\b.*?</pre>", lambda m: span.sub(r"\1", m.group(0)), html, flags=re.S | re.I)


def lighten(site: Path) -> None:
    """Rewrite the built site in ``site`` (module docstring)."""
    static = site / "_static"
    css = static / "pygments.css"
    classes = plain_classes(css.read_text(encoding="utf-8")) if css.is_file() else frozenset()
    for page in site.rglob("*.html"):
        text = page.read_text(encoding="utf-8")
        lean = collapse_whitespace(drop_comments(unwrap_plain(text, classes)))
        if lean != text:
            page.write_text(lean, encoding="utf-8")
    for source_map in static.rglob("*.map"):
        source_map.unlink()
    for asset in [*static.rglob("*.js"), *static.rglob("*.css")]:
        text = asset.read_text(encoding="utf-8")
        if "sourceMappingURL=" in text[-300:]:
            asset.write_text(_MAP.sub("\n", text), encoding="utf-8")


def tumble_source_only(app: Sphinx, modname: str, fullname: str) -> str | None:
    """sphinx.ext.viewcode's ``viewcode-follow-imported`` event: the module that defines
    ``modname.fullname`` where it is tumble's (None: viewcode looks it up as usual), else
    ``modname`` itself, whose source has no definition of the name, so no page of another package
    is written (module docstring).

    Examples
    --------
    >>> tumble_source_only(None, "tumble.typing", "FloatArray")
    'tumble.typing'
    >>> tumble_source_only(None, "tumble", "simulate") is None
    True
    """
    import importlib

    try:
        value = importlib.import_module(modname)
        for attribute in fullname.split("."):
            value = getattr(value, attribute)
    except Exception:  # noqa: BLE001 - what viewcode cannot import it leaves alone too
        return None
    defining = getattr(value, "__module__", None)
    return None if not isinstance(defining, str) or defining.split(".")[0] == "tumble" else modname


def _gallery_css_where_used(app: Sphinx, pagename: str, templatename: str, context: dict, doctree: object) -> None:
    if "sphx-glr" not in context.get("body", ""):
        context["css_files"] = [c for c in context.get("css_files", [])
                                if not str(getattr(c, "filename", c)).rsplit("/", 1)[-1].startswith("sg_gallery")]


def _finished(app: Sphinx, exception: Exception | None) -> None:
    if exception is None and app.builder.format == "html":
        lighten(Path(app.outdir))


def setup(app: Sphinx) -> dict:
    # after sphinx-gallery's own build-finished handler (priority 500), which links the names in
    # its examples' code by their spans
    app.connect("html-page-context", _gallery_css_where_used)
    app.connect("viewcode-follow-imported", tumble_source_only)
    app.connect("build-finished", _finished, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
