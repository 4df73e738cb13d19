"""The citing page (docs/citing.md) from CITATION.cff: the citation's message, the version and
its release date, and a BibTeX entry, written where the page's marker comment stands.

The page holds no copy of any of these, so it cannot disagree with CITATION.cff (which
tests/test_packaging.py holds to the package's version and the changelog's release date).
CITATION.cff is YAML, read with PyYAML (a dependency of myst-parser).
"""

from __future__ import annotations

from pathlib import Path

import yaml

#: The line of docs/citing.md that the citation replaces.
MARKER = "<!-- tumble-citation:"
CFF = Path(__file__).resolve().parents[2] / "CITATION.cff"


def _author(author: dict) -> str:
    """A CFF author as BibTeX writes it: an entity in braces, a person as "Family, Given"."""
    if "name" in author:
        return "{" + author["name"] + "}"
    return ", ".join(p for p in (author.get("family-names"), author.get("given-names")) if p)


def bibtex(cff: dict) -> str:
    """The BibTeX ``@software`` entry of a CITATION.cff (read as a dict).

    >>> print(bibtex({"title": "t", "authors": [{"name": "The t authors"}], "version": "1.0",
    ...               "date-released": "2026-01-02", "license": "MIT"}))
    @software{t,
      title = {t},
      author = {{The t authors}},
      version = {1.0},
      year = {2026},
      month = {1},
      date = {2026-01-02},
      license = {MIT},
    }
    """
    date = str(cff["date-released"])
    fields = [("title", cff["title"]), ("author", " and ".join(_author(a) for a in cff["authors"])),
              ("version", str(cff["version"])), ("year", date[:4]), ("month", str(int(date[5:7]))),
              ("date", date), ("license", cff.get("license")), ("url", cff.get("url")),
              ("doi", cff.get("doi"))]
    key = cff["title"].split(":")[0].split()[0].lower()
    body = "".join(f"  {name} = {{{value}}},\n" for name, value in fields if value)
    return f"@software{{{key},\n{body}}}"


def citation_markdown(cff: dict) -> str:
    """What the marker becomes: the message, the version and date, the BibTeX entry."""
    return (f"{cff['message']} This is version {cff['version']}, released on {cff['date-released']}.\n\n"
            f"```bibtex\n{bibtex(cff)}\n```\n")


def _fill(app, docname: str, source: list[str]) -> None:
    if docname != "citing" or MARKER not in source[0]:
        return
    cff = yaml.safe_load(CFF.read_text(encoding="utf-8"))
    lines = source[0].splitlines(keepends=True)
    source[0] = "".join(citation_markdown(cff) if line.startswith(MARKER) else line for line in lines)


def setup(app):
    app.connect("source-read", _fill)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
