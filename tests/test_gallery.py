"""The gallery's index (docs/gallery/index.md), written from every entry module.

The entries are ``tests/test_gallery_*.py``; the machinery is ``tests/gallery.py``.
"""

from __future__ import annotations

from gallery import GALLERY, entries, write_if_changed


def render_index() -> str:
    """The Markdown (MyST) text of the gallery's index page: the list, and the hidden table of
    contents that puts every page in the site's navigation, in the same order."""
    items = "\n".join(f"- [{e.title}]({e.slug}.md)" for e in entries())
    toctree = "\n".join(e.slug for e in entries())
    return f"""# Published results: numbers tumble reproduces

Each page gives a published quantity, its source, the conditions, tumble's value, the
difference and the code that makes it. The pages are generated and checked by the test suite
(`tests/test_gallery_*.py`, one module per page): a page that no longer matches what the code
computes fails the suite (the test rewrites it).

{items}

```{{toctree}}
:hidden:

{toctree}
```
"""


def test_index_is_current():
    write_if_changed(GALLERY / "index.md", render_index())


def test_every_entry_has_a_page_and_a_unique_slug():
    found = entries()
    slugs = [e.slug for e in found]
    assert len(set(slugs)) == len(slugs) >= 3
    for e in found:
        assert (GALLERY / f"{e.slug}.md").exists(), e.slug
