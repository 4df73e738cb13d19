"""Issue 27 item 10 (the missing extra), for every optional extra: a feature whose package is not
installed raises ``ImportError`` (``name`` the package) with the line that installs it,
``pip install 'tumble[EXTRA]'``, through one helper (``tumble._optional.optional_import``); the
command line prints that line alone and exits 2, writing nothing. On main plotly (the page), sgp4
(TLE orbits), ppigrf (IGRF) and Dask raised ValueError, so a missing extra read as a bad input.

A missing package is simulated by ``sys.modules[name] = None`` (``import name`` then raises
ImportError), with its submodules dropped from ``sys.modules`` first."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import pytest

import tumble
from tumble._optional import optional_import
from tumble.cli import main

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
ISS_TLE = ("1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991",
           "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482")


def uninstall(monkeypatch, package: str) -> None:
    """As if ``package`` were not installed."""
    for name in [m for m in sys.modules if m == package or m.startswith(package + ".")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, package, None)


def _page():
    from tumble.viz.page import page_html

    body = tumble.t_handle()
    return page_html(body, tumble.simulate(body, [0.1, 10.0, 0.1], t_end=1.0, samples=5), frames=5)


def _tle():
    from tumble.dynamics import TLEOrbit

    return TLEOrbit(*ISS_TLE)


def _igrf():
    from tumble.dynamics.environment.igrf import IGRFField
    from tumble.dynamics.environment.orbit import CircularOrbit

    orbit = CircularOrbit(altitude=500e3, inclination=math.radians(97.4))
    return IGRFField(orbit, "2026-11-25T00:00:00").world([0.0, 60.0])


def _dask():
    from tumble.ensemble import make_backend

    return make_backend(workers=2)


def _mesh():
    return tumble.Mesh(mesh=EXAMPLES / "bodies" / "meshes" / "torus.stl", mass=1.0)


def _show():
    from tumble.viz import show

    body = tumble.t_handle()
    return show(tumble.simulate(body, [0.1, 10.0, 0.1], t_end=1.0, samples=5), body)


FEATURES = [  # (package, extra, what needs it)
    ("plotly", "view", _page),
    ("sgp4", "orbit", _tle),
    ("ppigrf", "orbit", _igrf),
    ("dask", "cluster", _dask),
    ("trimesh", "mesh", _mesh),
    ("IPython", "notebook", _show),
]


@pytest.mark.parametrize("package, extra, use", FEATURES, ids=[f[0] for f in FEATURES])
def test_a_missing_extra_is_an_import_error_with_the_install_hint(monkeypatch, package, extra, use):
    uninstall(monkeypatch, package)
    with pytest.raises(ImportError, match=rf" needs {package}: pip install 'tumble\[{extra}\]'$") as info:
        use()
    assert not isinstance(info.value, ValueError) and info.value.name == package


def test_the_helper_names_the_top_level_package_and_returns_the_module():
    assert optional_import("json.decoder", "none", "this test").__name__ == "json.decoder"
    with pytest.raises(ImportError, match=r"^the page needs no_such_pkg: pip install 'tumble\[view\]'$") as info:
        optional_import("no_such_pkg.offline", "view", "the page")
    assert info.value.name == "no_such_pkg"


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("package", ["sgp4", "ppigrf"])
def test_a_tle_run_without_the_orbit_extra_is_one_line_and_status_2(tmp_path, capsys, monkeypatch, package):
    uninstall(monkeypatch, package)
    out = tmp_path / "run"
    code, printed, err = run(capsys, "simulate", str(EXAMPLES / "control" / "detumble_tle.toml"), "--out", str(out))
    assert code == 2 and "Traceback" not in err
    assert err.count("\n") == 1 and f"needs {package}: pip install 'tumble[orbit]'" in err
    assert not out.exists()


def test_a_page_without_plotly_is_one_line_and_status_2(tmp_path, capsys, monkeypatch):
    uninstall(monkeypatch, "plotly")
    page = tmp_path / "page.html"
    code, printed, err = run(capsys, "view", str(EXAMPLES / "seed_flip.toml"), "--out", str(page), "--frames", "5")
    assert code == 2 and "Traceback" not in err
    assert err.count("\n") == 1 and "the interactive page needs plotly: pip install 'tumble[view]'" in err
    assert not page.exists()
