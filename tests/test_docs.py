"""The documentation site: the Sphinx build passes with every warning an error, offline, and the
API reference is whole (a page per public name), the galleries are in it, and it works in a
browser opened from file:// with no request leaving the machine.

One fresh build (the example scripts run in it; about half a minute on two cores) serves every
test here; ``make docs`` runs the same command into site/.
"""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path

import pytest

pytest.importorskip("sphinx")
pytest.importorskip("pydata_sphinx_theme")
pytest.importorskip("numpydoc")
pytest.importorskip("myst_parser")
pytest.importorskip("sphinx_gallery")

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "docs" / "_ext"))

import tumble_api  # noqa: E402  (docs/_ext: the listing the site is built from)
from test_docs_names import written_names  # noqa: E402
from limits import BUILD_S, HANG_MS

SRC = ROOT / "src" / "tumble"
SUBPACKAGES = ("mass", "dynamics", "analysis", "ensemble", "io", "viz")
SCRIPTS = sorted((ROOT / "gallery").glob("plot_*.py"))


def _literal(path: Path, name: str):
    """The literal value assigned to ``name`` at the top of a module, read without importing it."""
    for node in ast.parse(path.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == name for t in node.targets):
            return ast.literal_eval(node.value)
    raise AssertionError(f"{path} assigns no {name}")


def _text(html: str) -> str:
    return re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", html))


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    """A fresh build (new output and doctree folders: nothing is reused from an earlier one), in one
    process: the suite's other worker has the second core, and Sphinx's ``-j 2`` cost 92 CPU-s
    against 80.5 in one (its processes' environments pickled and merged; 2026-11-29)."""
    out = tmp_path_factory.mktemp("docs")
    site, doctrees = out / "site", out / "doctrees"
    command = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-j", "1", "-q", "-E",
               "-d", str(doctrees), "-b", "html", "docs", str(site)]
    proc = subprocess.run(command, check=False, cwd=ROOT, capture_output=True, text=True, timeout=BUILD_S)
    return proc, site


@pytest.fixture(scope="module")
def site(build):
    proc, site = build
    if proc.returncode != 0:
        pytest.fail(f"sphinx-build -W failed (exit {proc.returncode}):\n{proc.stderr[-6000:]}")
    return site


def test_the_strict_build_passes_without_a_warning(build):
    proc, _ = build
    output = proc.stdout + proc.stderr
    problems = [line for line in output.splitlines() if "WARNING" in line or "ERROR" in line]
    assert proc.returncode == 0 and not problems, "\n".join(problems) or output[-4000:]


@pytest.mark.parametrize("package", SUBPACKAGES)
def test_every_public_name_has_its_own_page_listed_on_its_subpackage_page(site, package):
    """A function or class: a page of its own, linked from the subpackage's page. A constant: an
    entry of the page of the module that documents it."""
    html = (site / "api" / f"{package}.html").read_text(encoding="utf-8")
    names = _literal(SRC / package / "__init__.py", "__all__")
    assert names
    kinds = set()
    for name in names:
        full = tumble_api.page_for(f"tumble.{package}.{name}").removeprefix("obj:")  # documented once
        if full in tumble_api.documented_names():
            page = site / "api" / "generated" / f"{full}.html"
            assert page.is_file(), f"no page for {full}"
            assert f'href="generated/{full}.html' in html, f"api/{package}.html does not list {full}"
            kinds.add("page")
        else:
            page = site / tumble_api.html_page(full).partition("#")[0]
            assert not (site / "api" / "generated" / f"{full}.html").exists(), f"{full} has a page of its own"
            kinds.add("entry")
        assert f'id="{full}"' in page.read_text(encoding="utf-8"), f"{page.name} has no entry {full}"
    assert "page" in kinds


def test_every_name_the_guides_gallery_and_readme_write_has_its_entry_on_the_site(site):
    """tests/test_docs_names.py finds a page for each name in the listing; here the built page
    holds the name's entry (its anchor)."""
    missing = []
    names = {name for _, name in written_names()}
    for name in sorted(names):
        page = tumble_api.page_for(name)
        assert page is not None, name
        path, anchor = tumble_api.html_target(page)
        file = site / path
        if not file.is_file():
            missing.append(f"{name}: no {path}")
        elif anchor and f'id="{anchor}"' not in file.read_text(encoding="utf-8"):
            missing.append(f"{name}: {path} has no id {anchor}")
    assert len(names) > 150 and not missing, "\n".join(missing)


def test_every_public_module_has_its_page(site):
    for module in tumble_api.public_modules():
        path, anchor = tumble_api.html_target(f"mod:{module}")
        html = (site / path).read_text(encoding="utf-8")
        assert anchor is None or f'id="{anchor}"' in html, module


@pytest.mark.parametrize("page", ["body", "scenario", "control", "sweep", "recording"])
def test_each_file_format_page_has_a_table_of_every_key(site, page):
    import tumble_keys

    source = (ROOT / "docs" / "formats" / f"{page}.md").read_text(encoding="utf-8")
    fmt = tumble_keys.load_format(re.search(r"```\{tumble-keys\} (\S+)", source).group(1))
    html = (site / "formats" / f"{page}.html").read_text(encoding="utf-8")
    assert html.count("<table") == len(fmt.tables)
    for table in fmt.tables:
        body = html.split("<table")[fmt.tables.index(table) + 1].split("</table>")[0]
        cells = re.findall(r"<tr[^>]*>\s*<td[^>]*>(.*?)</td>", body, re.S)
        assert [_text(c).strip().replace(" ", "") for c in cells] == [k.name.replace(" ", "") for k in table.keys], \
            (page, table.title)


@pytest.mark.parametrize(("name", "words"), [
    ("tumble.dynamics.simulate", ["Parameters", "omega0", "rad/s", "Returns", "Examples"]),
    ("tumble.dynamics.Trajectory", ["nutation_angle", "principal frame"]),
    ("tumble.analysis.fit_rotation", ["Parameters", "Examples"]),
    ("tumble.mass.Body", ["principal_moments", "kg m^2"]),
    ("tumble.dynamics.methods.exact.FreeRotation", ["omega", "attitude"]),
])
def test_key_pages_carry_signature_parameters_units_and_examples(site, name, words):
    html = (site / "api" / "generated" / f"{name}.html").read_text(encoding="utf-8")
    assert 'class="sig-name descname"' in html  # the signature
    text = _text(html)
    missing = [w for w in words if w not in text]
    assert not missing, f"{name}: {missing}"


def test_the_api_index_links_every_top_level_name_to_its_page(site):
    html = (site / "api" / "index.html").read_text(encoding="utf-8")
    exports = _literal(SRC / "__init__.py", "_EXPORTS")
    # a function or class: generated/<name>.html; a constant: its module's page (api/dynamics.html#...)
    unlinked = [name for name, module in exports.items()
                if f'href="{tumble_api.html_page(f"{module}.{name}").removeprefix("api/")}"' not in html]
    assert not unlinked, f"api/index.html does not link {unlinked}"


def test_sphinx_markup_is_read_not_printed(site):
    pages = {p.name: p.read_text(encoding="utf-8") for p in (site / "api" / "generated").glob("*.html")}
    modules = {p.name: p.read_text(encoding="utf-8") for p in [*(site / "api").glob("*.html"), *(site / "api" / "modules").glob("*.html")]}
    roles = re.compile(r":(?:func|class|mod|data|meth|attr|obj):`")
    assert not [name for name, html in {**pages, **modules}.items() if roles.search(html)]
    # a role naming an object where it is defined links to its page under the public name
    # (periods.py cites :func:`tumble.analysis.flip_interval`)
    assert re.search(r'href="tumble\.analysis\.flip_interval\.html#tumble\.analysis\.flip_interval"',
                     pages["tumble.analysis.period.html"])
    # a role through a private module (simulate.py cites dynamics.models.internal.SphericalDamper)
    assert 'href="tumble.dynamics.SphericalDamper.html#tumble.dynamics.SphericalDamper"' in \
        pages["tumble.dynamics.simulate.html"]
    # a re-exported constant shows its `#:` comment, not the docstring of float, on its module's page
    html = modules["mass.html"]
    entry = html[html.index('id="tumble.mass.INERTIA_RTOL"'):]
    rtol = _text(entry[:entry.index("</dd>")])
    assert "round-off" in rtol and "Convert a string or number" not in rtol


def test_every_published_result_is_a_page_in_the_navigation(site):
    index = (site / "gallery" / "index.html").read_text(encoding="utf-8")
    pages = sorted(p for p in (ROOT / "docs" / "gallery").glob("*.md") if p.stem != "index")
    assert len(pages) >= 2
    for page in pages:
        assert (site / "gallery" / f"{page.stem}.html").is_file()
        assert f'href="{page.stem}.html"' in index, f"{page.name} is not linked from the gallery"
    home = (site / "index.html").read_text(encoding="utf-8")
    assert 'href="gallery/index.html"' in home and 'href="examples/index.html"' in home


def test_every_example_script_ran_in_the_build_and_drew_its_figure(site):
    assert len(SCRIPTS) >= 10
    index = (site / "examples" / "index.html").read_text(encoding="utf-8")
    for script in SCRIPTS:
        page = site / "examples" / f"{script.stem}.html"
        assert page.is_file(), script.name
        assert f'href="{script.stem}.html"' in index or f"{script.stem}.html" in index
        html = page.read_text(encoding="utf-8")
        assert re.search(r'<img [^>]*src="../_images/sphx_glr_' + script.stem, html), \
            f"{script.name} drew no figure in the build"


class _Resources(HTMLParser):
    """Every address a page loads by itself: scripts, styles, icons, images, frames."""

    def __init__(self):
        super().__init__()
        self.urls: list[str] = []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag in ("script", "img", "iframe", "source", "video", "audio") and attrs.get("src"):
            self.urls.append(attrs["src"])
        if tag == "link" and attrs.get("href") and attrs.get("rel") not in ("canonical",):
            self.urls.append(attrs["href"])


def test_the_site_loads_nothing_from_the_network(site):
    remote = re.compile(r"^(?:https?:)?//")
    found = {}
    for page in site.rglob("*.html"):
        parser = _Resources()
        parser.feed(page.read_text(encoding="utf-8"))
        found.update({url: page.relative_to(site) for url in parser.urls if remote.match(url)})
    for sheet in site.rglob("*.css"):
        for url in re.findall(r"url\(\s*['\"]?([^'\")]+)", sheet.read_text(encoding="utf-8")):
            if remote.match(url):
                found[url] = sheet.relative_to(site)
    assert not found, f"remote resources: {found}"
    assert (site / "searchindex.js").is_file()


def test_the_site_works_from_file_with_no_network_search_included(site, new_page):
    """Headless Chromium on the built site, every request outside file:// refused and recorded:
    the home page, an API page, a gallery page and the search all work."""
    watched = new_page()
    page = watched.page
    page.goto((site / "index.html").as_uri())
    assert page.locator("h1").first.inner_text().startswith("tumble")
    assert page.locator('a[href="api/index.html"]').count() >= 1  # the navigation bar
    page.goto((site / "api" / "generated" / "tumble.analysis.fit_rotation.html").as_uri())
    assert page.locator('[id="tumble.analysis.fit_rotation"]').count() == 1
    page.goto((site / "examples" / "plot_t_handle_flip.html").as_uri())
    figure = page.locator('img[src*="sphx_glr_plot_t_handle_flip"]').first
    assert figure.evaluate("img => img.complete && img.naturalWidth > 0")  # the figure loaded
    page.goto((site / "search.html").as_uri() + "?q=free_rotation_batch")
    hits = page.locator("#search-results li")
    hits.first.wait_for(timeout=HANG_MS)  # the index (searchindex.js) loads and is searched
    hrefs = [hits.nth(i).locator("a").first.get_attribute("href") for i in range(hits.count())]
    assert any("tumble.dynamics.methods.exact_batch.free_rotation_batch.html" in h for h in hrefs), hrefs
    assert not watched.outside, f"requests that left file://: {watched.outside}"
    assert not watched.errors, "\n".join(watched.errors)


def test_code_keeps_its_colours_in_a_browser(site, new_page):
    """A long line of code (its span.l, docs/_ext/tumble_code.py) shows its names and punctuation in
    the Pygments style's text colour (the .highlight block's), as a short line does, in the light
    and the dark mode; keywords keep theirs. (Pygments' stylesheet colours .l as a literal: with
    the names' own spans taken off, docs/_ext/tumble_lean.py, they turned brown.)"""
    watched = new_page()
    page = watched.page
    page.goto((site / "estimation.html").as_uri())
    for mode in ("light", "dark"):
        page.evaluate(f"document.documentElement.dataset.theme = '{mode}'")
        colours = page.evaluate("""() => {
            const line = document.querySelector('div.highlight pre span.l');
            const block = line.closest('div.highlight'), keyword = block.querySelector('span.k, span.kn');
            return [line, block.querySelector('pre'), block, keyword].map(e => getComputedStyle(e).color);
        }""")
        assert colours[0] == colours[1] == colours[2] != colours[3], (mode, colours)
    assert not watched.errors, "\n".join(watched.errors)


# --- pages that read well (issue 28 item 2) ---------------------------------------------------------

class _Images(HTMLParser):
    """The ``src`` of every ``<img>`` of a page, in order, and where the first code block starts."""

    def __init__(self):
        super().__init__()
        self.images: list[tuple[int, str]] = []
        self.code: list[int] = []
        self.count = 0

    def handle_starttag(self, tag, attrs):
        self.count += 1
        attrs = dict(attrs)
        if tag == "img" and attrs.get("src"):
            self.images.append((self.count, attrs["src"]))
        if tag == "div" and "highlight-python" in (attrs.get("class") or "").lower():
            self.code.append(self.count)


def test_every_figure_appears_once_on_its_page(site):
    """No page shows an image twice, by its address or by its bytes (three gallery pages drew
    their figure twice: pyplot's scraper and tumble's both saved it)."""
    import hashlib

    twice = []
    for page in sorted(site.rglob("*.html")):
        parser = _Images()
        parser.feed(page.read_text(encoding="utf-8"))
        digests: dict[str, str] = {}
        for _, src in parser.images:
            path = (page.parent / src.split("#")[0].split("?")[0]).resolve()
            if not path.is_file() or path.suffix.lower() not in (".png", ".jpg", ".jpeg", ".gif", ".webp"):
                continue
            digest = hashlib.sha256(path.read_bytes()).hexdigest()
            if digest in digests:
                twice.append(f"{page.relative_to(site)}: {src} = {digests[digest]}")
            digests.setdefault(digest, src)
    assert not twice, "\n".join(twice)


def test_each_gallery_figure_follows_the_code_that_draws_it(site):
    """On a gallery page of several code blocks, no figure comes before the first block (a page
    of one block shows its output above the code: sphinx-gallery's layout of a simple example)."""
    early = []
    for script in SCRIPTS:
        parser = _Images()
        parser.feed((site / "examples" / f"{script.stem}.html").read_text(encoding="utf-8"))
        figures = [at for at, src in parser.images if "sphx_glr_" in src]
        if len(parser.code) > 1 and figures and figures[0] < parser.code[0]:
            early.append(script.name)
    assert not early, f"a figure above its code: {early}"
    assert sum(1 for s in SCRIPTS if "# %%" in s.read_text(encoding="utf-8")) >= len(SCRIPTS) - 1


def test_no_page_shows_a_raw_object_repr_or_an_escaped_pipe(site):
    """``<matplotlib.legend.Legend object at 0x...>`` under a gallery figure on any page, or a
    guide's table cell that shows ``\\|``: what a reader should never see. (The API pages are
    left out of the second check: docstrings escape ``|L|`` for reStructuredText, and their
    doctest comments still show the backslash.)"""
    found = []
    for page in sorted(site.rglob("*.html")):
        text = _text(page.read_text(encoding="utf-8")).replace("&lt;", "<").replace("&gt;", ">")
        found += [f"{page.relative_to(site)}: {m}" for m in re.findall(r"<[\w.]+ object at 0x[0-9a-f]+>", text)]
        if page.relative_to(site).parts[0] not in ("api", "_modules"):
            found += [f"{page.relative_to(site)}: {m}" for m in re.findall(r".{0,30}\\\|.{0,30}", text)]
    assert not found, "\n".join(found[:20])


def test_signatures_name_tumbles_array_aliases(site):
    """A signature says ``omega: tumble.typing.ArrayLike`` (``autodoc_type_aliases``), also inside a
    union (``tumble.typing.Vector3 | None``, docs/_ext/tumble_xref.py), linked to the alias's entry:
    not numpy's expansion (``_Buffer | _SupportsArray[dtype[Any]] | ...``) nor Sphinx's placeholder."""
    generated = site / "api" / "generated"
    axis_of = re.sub(r"\s+", "", _text((generated / "tumble.analysis.axis_of.html").read_text(encoding="utf-8")))
    assert "axis_of(omega:tumble.typing.ArrayLike)" in axis_of
    props = (generated / "tumble.mass.MassProperties.html").read_text(encoding="utf-8")
    assert re.search(r'href="[^"]*tumble\.typing\.html#tumble\.typing\.Vector3"[^>]*><span class="pre">'
                     r'tumble\.typing\.Vector3</span></a><span class="w"> </span><span class="p"><span class="pre">\|'
                     r'</span></span><span class="w"> </span><span class="pre">None', props), "intermediate_axis's type"
    shown = [page.name for page in sorted(generated.glob("*.html"))
             if re.search(r"_SupportsArray|TypeAliasForwardRef", page.read_text(encoding="utf-8"))]
    assert not shown, shown[:10]


def test_a_table_with_pipes_in_its_code_renders_as_a_table(site):
    """docs/control.md's table of figures names ``|omega|`` in its cells: the row stays one row of
    two cells, the pipes inside the code."""
    html = (site / "control.html").read_text(encoding="utf-8")
    rows = re.findall(r"<tr[^>]*>(.*?)</tr>", html, flags=re.S)
    (rates,) = [r for r in rows if "rates.png" in r]
    cells = re.findall(r"<td[^>]*>(.*?)</td>", rates, flags=re.S)
    assert len(cells) == 2 and "|omega|" in _text(cells[1]).replace(" ", ""), rates


# --- the changelog, the citation, the version, the sources (issue 28 item 7) -------------------------

def test_the_changelog_and_citing_pages_follow_their_files(site):
    import tumble

    # Sphinx's smart quotes write an apostrophe as &#8217; ("Sensor Logger's" in the file)
    changelog = _text((site / "changelog.html").read_text(encoding="utf-8")).replace("&#8217;", "'").replace("\u2019", "'")
    assert "Unreleased" in changelog and f"{tumble.__version__}" in changelog
    first = re.search(r"^- (.{20,80}?)[`(]", (ROOT / "CHANGELOG.md").read_text(encoding="utf-8"), flags=re.M)
    assert " ".join(first.group(1).replace("`", " ").split()) in changelog  # the file's first entry, rendered
    citing = _text((site / "citing.html").read_text(encoding="utf-8"))
    cff = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    version = re.search(r"^version:\s*(\S+)", cff, flags=re.M).group(1)
    date = re.search(r"^date-released:\s*(\S+)", cff, flags=re.M).group(1)
    assert f"This is version {version}, released on {date}." in citing
    packed = citing.replace(" ", "")  # the BibTeX block, highlighted token by token
    assert "@software{tumble," in packed and f"version={{{version}}}" in packed
    assert "tumble-citation" not in citing  # the marker was replaced
    home = (site / "index.html").read_text(encoding="utf-8")
    assert 'href="changelog.html"' in home and 'href="citing.html"' in home


def test_every_page_shows_the_version_in_its_header(site):
    import tumble

    for name in ("index.html", "tour.html", "api/index.html", "examples/plot_t_handle_flip.html"):
        html = (site / name).read_text(encoding="utf-8")
        brand = re.search(r'<a class="navbar-brand logo"[^>]*>(.*?)</a>', html, flags=re.S)
        assert brand and f"tumble {tumble.__version__}" in _text(brand.group(1)), name


def test_api_pages_link_to_their_source(site):
    """sphinx.ext.viewcode: a [source] link on an API page, to a highlighted copy of the module in
    the site itself (nothing fetched)."""
    page = site / "api" / "generated" / "tumble.analysis.fit_rotation.html"
    html = page.read_text(encoding="utf-8")
    links = re.findall(r'href="([^"]*_modules/[^"]*)"', html)
    assert links, "no [source] link"
    target = (page.parent / links[0].split("#")[0]).resolve()
    assert target.is_file() and "def fit_rotation" in _text(target.read_text(encoding="utf-8"))
    # tumble's sources only: no copy of typing's, functools', types' or numpy's (docs/_ext/tumble_lean.py)
    others = [p.relative_to(site).as_posix() for p in (site / "_modules").rglob("*.html")
              if p.name != "index.html" and "tumble" not in p.relative_to(site / "_modules").parts[:1]]
    assert not others, others


def test_each_source_pages_docs_link_reaches_its_object(site):
    """The highlighted modules' [docs] links back to the API: each one's anchor is on its page
    (docs/_ext/tumble_xref.py mends viewcode's, which took the anchor of another name of a
    re-exported object for 116 of them), the object itself, not the page's top."""
    ids: dict[Path, set[str]] = {}
    links, missing = 0, []
    for page in (site / "_modules").rglob("*.html"):
        for href in re.findall(r'class="viewcode-back" href="([^"]+)"', page.read_text(encoding="utf-8")):
            links += 1
            path, _, anchor = href.partition("#")
            target = (page.parent / path).resolve()
            if target not in ids:
                ids[target] = set(re.findall(r'\bid="([^"]+)"', target.read_text(encoding="utf-8")))
            if anchor not in ids[target]:
                missing.append(f"{page.relative_to(site)}: {href}")
    assert links > 500 and not missing, missing[:10]


def test_code_blocks_wrap_long_lines(site):
    css = (site / "_static" / "tumble.css").read_text(encoding="utf-8")
    assert re.search(r"div\.highlight pre\s*{[^}]*white-space:\s*pre-wrap", css)
    assert 'href="../_static/tumble.css' in (site / "examples" / "plot_t_handle_flip.html").read_text(encoding="utf-8")


def test_the_site_is_light_enough_to_share(site):
    """Issue 40: at most 40 MB. The site was 196 MB (715 API pages of ~170 KB, each listing the
    whole API in its sidebar); the sidebar collapsed to the page's branch and left off the API
    pages (docs/conf.py) brought it to 49 MB. The rest was markup no reader sees, taken off once
    the site is built (docs/_ext/tumble_lean.py, about 10 MB): the templates' indentation, the
    spans Pygments puts round names, punctuation and spaces in code (the module sources'
    pages, _modules/, most of all), the theme's source maps; and the colour-mode switch is
    written once a page, not twice (docs/conf.py)."""
    size = sum(f.stat().st_size for f in site.rglob("*") if f.is_file())
    assert size <= 40e6, f"{size / 1e6:.1f} MB"


def test_the_lighter_pages_read_the_same(site):
    """What the lightening left: a module's source page holds the module's text, line for line;
    no source map and no reference to one; the colour-mode switch once on a page; the gallery's
    stylesheets where the gallery's markup is."""
    import html as html_lib

    page = (site / "_modules" / "tumble" / "analysis" / "fit" / "single.html").read_text(encoding="utf-8")
    (code,) = re.findall(r"<pre>(.*?)</pre>", page, flags=re.S)
    text = html_lib.unescape(re.sub(r"<[^>]+>", "", code)).replace("[docs]", "")
    source = (SRC / "analysis" / "fit" / "single.py").read_text(encoding="utf-8")
    def lines(code: str) -> list[str]:  # viewcode's blocks round each definition add blank lines
        return [line for line in code.splitlines() if line.strip()]

    assert lines(text) == lines(source)
    assert '<span class="n">' not in code and '<span class="k">' in code  # plain spans off, coloured kept
    assert not list(site.rglob("*.map"))
    assert not [p for p in (site / "_static").rglob("*.[jc]s*") if "sourceMappingURL" in p.read_text(encoding="utf-8")]
    for name in ("index.html", "tour.html", "api/generated/tumble.analysis.fit_rotation.html", "_modules/tumble/io/gyrodata.html"):
        markup = (site / name).read_text(encoding="utf-8")
        assert markup.count('class="btn btn-sm nav-link pst-navbar-icon theme-switch-button') == 1, name
        assert "\n    <" not in re.sub(r"<(pre|script|style)\b.*?</\1>", "", markup, flags=re.S), name  # no indentation
    example = (site / "examples" / "plot_t_handle_flip.html").read_text(encoding="utf-8")
    assert "sg_gallery.css" in example and "sg_gallery.css" not in (site / "tour.html").read_text(encoding="utf-8")
    # sphinx-gallery links the names in its examples' code by their spans before they are taken off
    assert example.count('<a class="sphx-glr-backref-module-tumble') >= 5


def test_numpydoc_with_its_template_kept_renders_what_numpydoc_renders():
    """docs/_ext/tumble_numpydoc.py compiles numpydoc's docstring template once: the text it
    renders is numpydoc's own, for a function, a class and a module's kernel wrapper."""
    import numpydoc.numpydoc as numpydoc_module
    import tumble_numpydoc
    from numpydoc.docscrape_sphinx import get_doc_object as numpydocs

    import tumble.jit

    before = numpydoc_module.get_doc_object
    try:
        tumble_numpydoc.setup(None)  # it only sets numpydoc's global; Sphinx's app is not read
        kept = numpydoc_module.get_doc_object
        assert kept is not numpydocs
        for obj, what in ((tumble.simulate, "function"), (tumble.MassProperties, "class"), (tumble.jit.jit, "function")):
            assert str(kept(obj, what, config={})) == str(numpydocs(obj, what, config={})), obj
    finally:
        numpydoc_module.get_doc_object = before
