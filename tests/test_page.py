"""The interactive page: one self-contained HTML file that plays in a real, offline browser."""

from __future__ import annotations

import io
import os
import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest

from tumble.cli import main

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
#: Browsers looked for on PATH, in this order, when TUMBLE_CHROMIUM is not set.
BROWSERS = ("chromium", "chromium-browser", "google-chrome")
INSTALL = ("install Debian's Chromium (apt-get install chromium), or set TUMBLE_CHROMIUM=/path/to/chromium "
           f"(any Chromium or Chrome; also found on PATH as {', '.join(BROWSERS)})")
# Flags as Debian's Chromium needs them headless, as root, with software WebGL and no network.
FLAGS = ["--no-sandbox", "--disable-gpu", "--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--disable-background-networking", "--disable-component-update", "--no-first-run", "--disable-sync",
         "--disable-quic"]


class BrowserMissingWarning(UserWarning):
    """The browser test of the interactive page could not run: no Chromium was found."""


def _in_ci(environ) -> bool:
    return environ.get("CI", "").strip().lower() in ("1", "true", "yes")


def find_browser(environ=os.environ) -> str | None:
    """The Chromium to drive: ``TUMBLE_CHROMIUM`` if set (it must be an executable), else the first
    of :data:`BROWSERS` on ``PATH``, else None."""
    chosen = environ.get("TUMBLE_CHROMIUM")
    if chosen:
        found = shutil.which(chosen, path=environ.get("PATH"))
        if found is None:
            pytest.fail(f"TUMBLE_CHROMIUM={chosen!r} is not an executable file; {INSTALL}")
        return found
    return next(filter(None, (shutil.which(name, path=environ.get("PATH")) for name in BROWSERS)), None)


def browser_or_skip(environ=os.environ) -> str:
    """The browser, or a loud skip (a warning in the test summary saying what to install); in CI
    (``CI=true``) a missing browser fails the test instead."""
    browser = find_browser(environ)
    if browser is not None:
        return browser
    message = f"no Chromium for the browser test of the interactive page: {INSTALL}"
    if _in_ci(environ):
        pytest.fail(f"CI must run the browser test: {message}")
    warnings.warn(BrowserMissingWarning(message), stacklevel=2)
    pytest.skip(message)


@pytest.fixture(scope="module")
def page_file(tmp_path_factory):
    out = tmp_path_factory.mktemp("page") / "flip.html"
    assert main(["view", str(EXAMPLES / "seed_flip.toml"), "--out", str(out), "--frames", "60"]) == 0
    return out


def test_page_is_one_self_contained_file(page_file):
    html = page_file.read_text()
    assert "<script src=" not in html  # no CDN, nothing to fetch
    assert "Plotly.newPlot" in html or "Plotly.react" in html
    assert len(html) > 1_000_000  # the plotly.js bundle is inside
    assert not list(page_file.parent.glob(".*tmp*"))


@pytest.mark.parametrize("scenario", sorted(EXAMPLES.glob("*.toml")), ids=lambda p: p.stem)
def test_view_works_for_every_example(scenario, tmp_path):
    out = tmp_path / "page.html"
    assert main(["view", str(scenario), "--out", str(out), "--frames", "10"]) == 0
    assert out.stat().st_size > 1_000_000


@pytest.mark.parametrize("frames", ["1", "-3", "5000"])
def test_view_refuses_a_bad_frame_count_before_integrating(tmp_path, capsys, frames):
    out = tmp_path / "page.html"
    assert main(["view", str(EXAMPLES / "seed_flip.toml"), "--out", str(out), "--frames", frames]) == 2
    assert "must be a whole number from 2 to 2000" in capsys.readouterr().err
    assert not out.exists()


def test_view_refuses_other_suffixes(tmp_path, capsys):
    assert main(["view", str(EXAMPLES / "seed_flip.toml"), "--out", str(tmp_path / "x.png")]) == 2
    assert "written as one .html file" in capsys.readouterr().err


def _fake_browser(folder: Path, name: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    path.write_text("#!/bin/sh\n")
    path.chmod(0o755)
    return path


def test_browser_found_by_env_var_then_on_path(tmp_path):
    bin_dir = tmp_path / "bin"
    chrome = _fake_browser(bin_dir, "google-chrome")
    own = _fake_browser(tmp_path / "opt", "my-chromium")
    assert find_browser({"PATH": str(bin_dir)}) == str(chrome)
    assert find_browser({"PATH": str(bin_dir), "TUMBLE_CHROMIUM": str(own)}) == str(own)
    assert find_browser({"PATH": str(tmp_path / "empty")}) is None
    _fake_browser(bin_dir, "chromium-browser")
    assert find_browser({"PATH": str(bin_dir)}) == str(bin_dir / "chromium-browser")  # before google-chrome


def test_a_wrong_env_var_fails_instead_of_falling_back(tmp_path):
    _fake_browser(tmp_path, "chromium")
    with pytest.raises(pytest.fail.Exception, match="TUMBLE_CHROMIUM='/nowhere/chromium' is not an executable"):
        find_browser({"PATH": str(tmp_path), "TUMBLE_CHROMIUM": "/nowhere/chromium"})


def test_missing_browser_skips_loudly_but_fails_in_ci(tmp_path):
    empty = {"PATH": str(tmp_path)}
    with pytest.warns(BrowserMissingWarning, match=r"apt-get install chromium.*TUMBLE_CHROMIUM"):
        with pytest.raises(pytest.skip.Exception, match=r"apt-get install chromium.*TUMBLE_CHROMIUM"):
            browser_or_skip(empty)
    with pytest.raises(pytest.fail.Exception, match="CI must run the browser test: .*apt-get install chromium"):
        browser_or_skip({**empty, "CI": "true"})


def test_page_plays_offline_in_chromium(page_file):
    from PIL import Image
    from playwright.sync_api import sync_playwright

    chromium = browser_or_skip()
    errors, outside = [], []
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium, headless=True, args=FLAGS)
        try:
            page = browser.new_page(viewport={"width": 1300, "height": 900})
            page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
            page.on("pageerror", lambda e: errors.append(str(e)))
            page.route("**/*", lambda route: (outside.append(route.request.url), route.abort())
                       if not route.request.url.startswith(("file:", "data:", "blob:")) else route.continue_())
            page.goto(page_file.as_uri())
            page.wait_for_selector(".js-plotly-plot .main-svg", timeout=60_000)
            page.locator(".updatemenu-button", has_text="Play").first.click()
            active = "document.querySelector('.js-plotly-plot')._fullLayout.sliders[0].active"
            page.wait_for_function(f"{active} >= 5", timeout=60_000)
            first = page.screenshot()
            page.wait_for_function(f"{active} >= 20", timeout=60_000)
            later = page.screenshot()
        finally:
            browser.close()
    assert errors == [] and outside == []

    def ground(png):  # the ground-frame scene, upper left
        return np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)[180:600, :650]

    a, b = ground(first), ground(later)
    red = ((a[..., 0] > 150) & (a[..., 1] < 90) & (a[..., 2] < 90)).sum()
    blue = ((a[..., 2] > 150) & (a[..., 0] < 90) & (a[..., 1] < 160)).sum()
    assert red + blue > 100, "no omega / L arrows drawn: blank WebGL canvas?"
    moved = np.any(np.abs(a - b) > 60, axis=-1).sum()
    assert moved > 300, "the body does not move while the page plays"
