"""The site's pages rewritten lighter once built (docs/_ext/tumble_lean.py, issue 40): the same text
and code to a reader, less markup. These run on small pages of their own; tests/test_docs.py checks
the built site (its size, a module's source page)."""

from __future__ import annotations

import html
import re
import sys
from pathlib import Path

import pytest

pytest.importorskip("sphinx")
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "docs" / "_ext"))

from tumble_lean import collapse_whitespace, drop_comments, lighten, plain_classes, unwrap_plain  # noqa: E402

CODE = '''\
def flip(body, omega=(0.1, 10.0, 0.1)):
    """A docstring
        indented."""
    return tumble.simulate(body, omega,  t_end=20.0)   # two spaces kept
'''


def _text(markup: str) -> str:
    return html.unescape(re.sub(r"<[^>]*>", "", markup))


def _pygments_css() -> str:
    """The site's pygments.css as Sphinx writes it for the theme's light and dark styles."""
    from pydata_sphinx_theme.pygments import get_pygments_stylesheet

    return get_pygments_stylesheet("a11y-high-contrast-light", "a11y-high-contrast-dark")


@pytest.fixture(scope="module")
def highlighted() -> str:
    from pygments import highlight
    from pygments.formatters import HtmlFormatter
    from pygments.lexers import PythonLexer

    return highlight(CODE, PythonLexer(), HtmlFormatter())


def test_plain_classes_are_those_coloured_as_the_text():
    css = _pygments_css()
    plain = plain_classes(css)
    assert {"n", "p", "w"} <= plain  # names, punctuation, whitespace: the block's own colour
    assert not plain & {"k", "s1", "sd", "mf", "o", "c1", "nf"}  # keywords, strings, numbers, operators, comments
    for theme in ("light", "dark"):
        base = re.search(rf'html\[data-theme="{theme}"\] \.highlight {{[^}}]*?(color: #\w+)', css).group(1)
        for cls in plain:
            assert re.search(rf'html\[data-theme="{theme}"\] \.highlight \.{cls} {{ {base} }}', css), (theme, cls)


def test_code_keeps_its_text_and_loses_only_plain_spans(highlighted):
    lean = unwrap_plain(highlighted, plain_classes(_pygments_css()))
    assert _text(lean) == _text(highlighted) and _text(lean).startswith(CODE)
    assert '<span class="n">' not in lean and '<span class="w">' not in lean
    assert lean.count('<span class="k">') == highlighted.count('<span class="k">') == 2  # def, return
    assert len(lean) < 0.8 * len(highlighted)


def test_whitespace_collapses_outside_preformatted_text(highlighted):
    page = (f"<html>\n  <head>\n    <script>\n  var a = 1;\n    </script>\n  </head>\n  <body>\n    <p>one\n\n"
            f"      two</p>\n    {highlighted}\n    <textarea>\n  kept\n</textarea>\n  </body>\n</html>\n")
    lean = collapse_whitespace(page)
    assert "<script>\n  var a = 1;\n    </script>" in lean and "<textarea>\n  kept\n</textarea>" in lean
    assert "<p>one\ntwo</p>" in lean and "\n  <" not in lean.replace("\n    </script>", "")
    pre = re.search(r"<pre>.*?</pre>", lean, flags=re.S).group(0)
    assert pre == re.search(r"<pre>.*?</pre>", highlighted, flags=re.S).group(0)  # untouched


def test_comments_go_outside_preformatted_text_and_scripts(highlighted):
    """The theme's template comments leave; a comment a reader can see (in code) or a script reads stays."""
    code = "<pre>x = 1  <!-- shown in the code --></pre>"
    page = (f"<head><!-- Loaded before other Sphinx assets -->\n<script>var s = '<!-- kept -->';</script></head>"
            f"<body><!--\nthis give us a css class\n-->{code}{highlighted}<textarea><!-- typed --></textarea></body>")
    lean = drop_comments(page)
    assert "Loaded before" not in lean and "css class" not in lean
    assert code in lean and "var s = '<!-- kept -->';" in lean and "<textarea><!-- typed --></textarea>" in lean
    assert lean.count("<!--") == 3  # the code's, the script's, the text area's


def test_lighten_rewrites_a_site_and_drops_source_maps(tmp_path, highlighted):
    static = tmp_path / "_static" / "scripts"
    static.mkdir(parents=True)
    (tmp_path / "_static" / "pygments.css").write_text(_pygments_css(), encoding="utf-8")
    (static / "app.js").write_text("var x = 1;\n//# sourceMappingURL=app.js.map\n", encoding="utf-8")
    (static / "app.js.map").write_text("{}", encoding="utf-8")
    (static / "app.css").write_text("a{color:red}\n/*# sourceMappingURL=app.css.map*/", encoding="utf-8")
    page = tmp_path / "page.html"
    page.write_text(f"<body>\n    <div>\n      {highlighted}\n    </div>\n</body>\n", encoding="utf-8")
    lighten(tmp_path)
    assert not list(tmp_path.rglob("*.map"))
    assert (static / "app.js").read_text(encoding="utf-8") == "var x = 1;\n"
    assert (static / "app.css").read_text(encoding="utf-8") == "a{color:red}\n"
    lean = page.read_text(encoding="utf-8")
    assert _text(lean).strip() == _text(highlighted).strip() and '<span class="n">' not in lean
