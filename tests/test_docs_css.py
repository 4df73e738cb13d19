"""The site's stylesheet (docs/_static/tumble.css) and code lines (docs/_ext/tumble_code.py) in a
browser (issue 40): a wrapped code line goes on under itself, not at column 0; a long module
name in the API sidebar wraps before the expand arrow instead of running under it."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CSS = (ROOT / "docs" / "_static" / "tumble.css").read_text(encoding="utf-8")
sys.path.insert(0, str(ROOT / "docs" / "_ext"))

CODE = """\
import tumble

def flip(body):
    traj = tumble.simulate(body, [0.1, 10.0, 0.1], t_end=20.0)   # a comment long enough to wrap in a narrow column
    return traj
"""


def _highlighted() -> str:
    from pygments import highlight
    from pygments.lexers import PythonLexer
    from tumble_code import LineFormatter

    return highlight(CODE, PythonLexer(), LineFormatter())


def test_every_line_is_a_span_and_the_text_is_unchanged():
    import html
    import re

    page = _highlighted()
    assert page.count('<span class="l"') == 1 and page.count('<span class="l" style="--i:4">') == 1  # the long line
    from pygments import highlight
    from pygments.formatters import HtmlFormatter
    from pygments.lexers import PythonLexer

    def text(markup: str) -> str:
        return html.unescape(re.sub(r"<[^>]*>", "", markup))

    assert text(page) == text(highlight(CODE, PythonLexer(), HtmlFormatter())) and text(page).startswith(CODE)


def test_a_wrapped_code_line_hangs_under_itself(new_page):
    watched = new_page(viewport={"width": 420, "height": 400})
    page = watched.page
    page.set_content(f"<!DOCTYPE html><html><head><style>pre {{ font: 14px monospace; margin: 0; }}{CSS}</style></head>"
                     f"<body style='margin: 0'><div style='width: 380px'>{_highlighted()}</div></body></html>")
    lines = page.evaluate("""() => {
        const ch = (() => { const s = document.createElement('span'); s.textContent = '0'.repeat(10);
                           document.querySelector('pre').appendChild(s); const w = s.getBoundingClientRect().width / 10;
                           s.remove(); return w; })();
        return [ch, ...[...document.querySelectorAll('span.l')].map(line => {
            const range = document.createRange(); range.selectNodeContents(line);
            return [...range.getClientRects()].map(r => [r.left, r.top]);
        })];
    }""")
    ch, rows = lines[0], lines[1:]
    (long,) = rows  # the call with its long comment: the one line that can wrap
    tops = sorted({round(top) for _, top in long})
    assert len(tops) >= 2, long  # it does wrap at this width
    first = min(left for left, top in long if round(top) == tops[0])
    after = min(left for left, top in long if round(top) == tops[1])
    assert after - first == pytest.approx(8 * ch, abs=1.0), (first, after, ch)  # its 4 spaces, then 4 more
    assert page.inner_text("pre").rstrip("\n") == CODE.rstrip("\n")  # what a reader copies: the code, line for line
    assert watched.clean()


def test_a_long_module_name_wraps_before_the_sidebar_arrow(new_page):
    import re

    import pydata_sphinx_theme
    import sphinx

    theme = Path(pydata_sphinx_theme.__file__).parent / "theme" / "pydata_sphinx_theme" / "static" / "styles"
    basic = Path(sphinx.__file__).parent / "themes" / "basic" / "static" / "basic.css.jinja"
    pre = re.search(r"span\.pre \{[^}]*\}", basic.read_text(encoding="utf-8")).group(0)  # white-space: nowrap
    base = (theme / "pydata-sphinx-theme.css").read_text(encoding="utf-8") + pre
    name = '<code class="docutils literal notranslate"><span class="pre">tumble.analysis.fit.flightmodel</span></code>'
    sidebar = (f'<div class="bd-sidebar-primary" style="width: 220px"><nav class="bd-links"><ul class="bd-sidenav">'
               f'<li class="toctree-l1 has-children"><a class="reference internal" href="#">{name}</a>'
               f'<details><summary><span class="toctree-toggle" role="presentation">v</span></summary>'
               f'<ul><li class="toctree-l2"><a class="reference internal" href="#">calibrate</a></li></ul></details></li>'
               f"</ul></nav></div>")
    watched = new_page(viewport={"width": 800, "height": 400})
    page = watched.page
    page.set_content(f"<!DOCTYPE html><html><head><style>{base}{CSS}</style></head><body>{sidebar}</body></html>")
    right, toggle = page.evaluate("""() => {
        const a = document.querySelector('li.has-children > a.reference');
        const range = document.createRange(); range.selectNodeContents(a);
        const right = Math.max(...[...range.getClientRects()].map(r => r.right));
        return [right, document.querySelector('.toctree-toggle').getBoundingClientRect().left];
    }""")
    assert right <= toggle + 0.5, (right, toggle)
    assert watched.clean()
