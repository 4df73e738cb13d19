"""Shared test settings and fixtures."""

from __future__ import annotations

import os
import shutil
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, settings

settings.register_profile(
    "default", max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow]
)
settings.register_profile("thorough", max_examples=1000, deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))


@pytest.fixture
def rng():
    return np.random.default_rng(20261122)


# -- one headless Chromium for every browser test ---------------------------------------------
# The page, its live mode, hostile names, the notebook frame and the docs site all run in the
# session's one browser (started on first use), each page in its own context under one offline
# rule (LOCAL). No Chromium: a loud skip, or a failure in CI (CI=true).

#: Browsers looked for on PATH, in this order, when TUMBLE_CHROMIUM is not set.
BROWSERS = ("chromium", "chromium-browser", "google-chrome")
INSTALL = ("install Debian's Chromium (apt-get install chromium), or set TUMBLE_CHROMIUM=/path/to/chromium "
           f"(any Chromium or Chrome; also found on PATH as {', '.join(BROWSERS)})")
# Flags as Debian's Chromium needs them headless, as root, with software WebGL and no network.
FLAGS = ["--no-sandbox", "--disable-gpu", "--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--disable-background-networking", "--disable-component-update", "--no-first-run", "--disable-sync",
         "--disable-quic"]
#: The offline rule: a page may load what the machine holds (files, inline data, blobs, about:
#: pages such as an iframe's srcdoc) and nothing else; any other request is recorded and aborted.
LOCAL = ("file:", "data:", "blob:", "about:")


class BrowserMissingWarning(UserWarning):
    """The browser tests could not run: no Chromium was found."""


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


class Watched:
    """A page of the shared browser, in a context of its own, that records console errors,
    uncaught exceptions and the requests the offline rule refused (``outside``)."""

    def __init__(self, browser, **options):
        self.context = browser.new_context(**options)
        self.context.route("**/*", self._route)
        self.page = self.context.new_page()
        self.errors, self.outside = [], []
        self.page.on("console", lambda m: self.errors.append(m.text) if m.type == "error" else None)
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))

    def _route(self, route):
        if route.request.url.startswith(LOCAL):
            return route.continue_()
        self.outside.append(route.request.url)
        return route.abort()

    def clean(self) -> bool:
        return self.errors == [] and self.outside == []

    def close(self) -> None:
        self.context.close()


@pytest.fixture(scope="session")
def chromium():
    """The session's headless Chromium (playwright's Browser)."""
    path = browser_or_skip()
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=path, headless=True, args=FLAGS)
        try:
            yield browser
        finally:
            browser.close()


def _opened_pages(chromium):
    """Opens :class:`Watched` pages and, once done with, closes them and fails if any of them asked
    the network for anything."""
    opened: list[Watched] = []

    def open_page(**options) -> Watched:
        opened.append(Watched(chromium, **options))
        return opened[-1]

    yield open_page
    for watched in opened:
        watched.close()
    outside = [url for watched in opened for url in watched.outside]
    assert not outside, f"requests that left the machine: {outside}"


@pytest.fixture
def new_page(chromium):
    """Opens :class:`Watched` pages (``new_page(viewport={...})``); they are closed after the
    test, which fails if any of them asked the network for anything."""
    yield from _opened_pages(chromium)


@pytest.fixture(scope="module")
def module_page(chromium):
    """:func:`new_page` for pages that a module's tests share, closed after its last test: a page
    loaded once for several tests (each load of the viewer costs Chromium ~4 CPU-s, its software
    WebGL included; 2026-11-30), each test leaving it as the next one expects."""
    yield from _opened_pages(chromium)


# -- the order of the files ----------------------------------------------------------------------
# make test runs the files on every core, a file to a worker (``--dist loadfile``), in collection
# order (``--no-loadscope-reorder``). xdist's own order (most tests first) started the wheel's
# commands (4 tests, ~3 minutes) near the end, where one worker ran them alone. Started first,
# the docs build and the wheel's commands compiled every kernel themselves (their subprocesses
# find numba's cache cold in a clean clone): a loaded run took twice as long. So the files whose
# tests compile the kernels come first, then the two long files of subprocesses, which find the
# kernels compiled, then the other long ones, then the rest by their number of tests, as xdist
# would.

#: The files first, in this order: those that compile the kernels (engine, closed loop, exact and
#: split flows, detumble batch, filter, sampled models), then the longest (wall time of a clean
#: clone's run, longest first). The docs build and the wheel's commands come after the first
#: twelve: their subprocesses (the gallery's scripts, 68 commands, up to 8 at a time) compile
#: every kernel they use where the checkout has not yet (the wheel's copies the checkout's
#: compiled kernels when it starts). Measured alone, the wheel's test took 194 CPU-s (366 s) on a
#: cold checkout and 140 CPU-s (114 s) on a warm one (loaded machine).
FIRST = ("tests/test_fit_recording.py", "tests/test_tensor_fit.py", "tests/test_control_loop.py", "tests/test_engine.py",
         "tests/test_compiled.py", "tests/test_controlled_compiled.py", "tests/test_mekf.py", "tests/test_gyrostat.py",
         "tests/test_page_live.py", "tests/test_result_display.py", "tests/test_page.py", "tests/test_tensor_device.py",
         "tests/test_docs.py", "tests/test_wheel_commands.py",
         "tests/test_fit_find.py", "tests/test_fit_drag_law.py", "tests/test_fit_accel.py", "tests/test_calibration_stats.py")


def pytest_collection_modifyitems(session, config, items):
    """Order the items file by file: :data:`FIRST` first, then by falling number of tests, each
    file's items in their own order (the same order in every worker)."""
    counts: dict[str, int] = {}
    for item in items:
        counts[item.nodeid.split("::")[0]] = counts.get(item.nodeid.split("::")[0], 0) + 1
    first = {name: rank for rank, name in enumerate(FIRST)}
    position = {name: i for i, name in enumerate(counts)}

    def key(item) -> tuple[int, int, int]:
        path = item.nodeid.split("::")[0]
        return first.get(path, len(first)), -counts[path], position[path]

    items.sort(key=key)  # stable: a file's items keep their order


@pytest.fixture
def loop_runs(monkeypatch):
    """A list that gets an entry each time the compiled closed loop runs (``ControlKernel.run``):
    which path a run took."""
    from tumble.dynamics.control import control_kernel

    calls = []
    original = control_kernel.ControlKernel.run

    def spy(self, *args, **kwargs):
        calls.append(1)
        return original(self, *args, **kwargs)

    monkeypatch.setattr(control_kernel.ControlKernel, "run", spy)
    return calls
