"""The throws that ship with the examples (``examples/throws/``, issue 40 item 2) and the throw
file's compact form: the shipped files are what ``tools/make_example_throws.py`` makes, every
throw file round-trips through the writer and the reader, and the format's page lists the
columns the reader takes.
"""

from __future__ import annotations

import runpy
import sys
from pathlib import Path

import numpy as np
import pytest

from tumble.analysis.tensor import Throw
from tumble.analysis.tensor.synthetic import box, combine, synthetic_throw, true_device
from tumble.io.examples import list_examples
from tumble.io.throwfile import (COMPACT_PLACES, THROW_FORMAT, load_throw, parse_throw_csv, read_throw, throw_csv,
                                 write_throw)

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ROOT / "src" / "tumble" / "examples" / "throws"
SCRIPT = ROOT / "tools" / "make_example_throws.py"
#: Half of each compact column's last decimal: the most a value moves in the compact form.
HALF = np.r_[0.5e-6, np.full(3, 0.5 * 10.0 ** -COMPACT_PLACES["rate"]), 0.5 * 10.0 ** -COMPACT_PLACES["rotor"],
             np.full(3, 0.5 * 10.0 ** -COMPACT_PLACES["accel"])]


def _columns(throw: Throw) -> np.ndarray:
    assert throw.accel is not None
    return np.column_stack([throw.t, throw.omega, throw.rotor, throw.accel])


@pytest.fixture(scope="module")
def script() -> dict:
    return runpy.run_path(str(SCRIPT), run_name="make_example_throws")


def test_the_examples_ship_the_scripts_throws_and_list_them(script):
    listed = {e.path: e for e in list_examples() if e.kind == "throw"}
    assert sorted(listed) == sorted(f"throws/{name}" for name in script["THROWS"])
    assert sum(p.stat().st_size for p in SHIPPED.glob("*.csv")) < 500_000   # small enough to ship
    assert listed["throws/o1.csv"].description.startswith(
        "SYNTHETIC throw of the example device strapped to a 0.482 kg")


@pytest.mark.parametrize("name", ["a1.csv", "o4.csv"])
def test_a_shipped_throw_is_what_the_script_makes(script, name):
    throw, comment = script["example_throw"](name)
    text = (SHIPPED / name).read_text(encoding="utf-8")
    assert text.startswith("".join(f"# {line}\n" for line in comment.splitlines()))
    assert text.splitlines()[len(comment.splitlines())].startswith("t (us),")   # the compact form
    shipped = read_throw(SHIPPED / name)
    # to the compact form's decimals (a value within round-off of a rounding boundary may land in
    # either: the last digit of the platform's arithmetic)
    assert np.all(np.abs(_columns(shipped) - _columns(throw)) <= HALF * (1 + 1e-6) + 1e-12)
    dt = np.diff(shipped.t)
    assert 0.9e-3 < np.median(dt[-100:]) < 1.1e-3   # a 1 kHz log, as the docs say


def _throw(seed: int, n: int = 300) -> Throw:
    rng = np.random.default_rng(seed)
    t = 0.12 + np.cumsum(rng.uniform(190e-6, 300e-6, n))
    omega = np.round(rng.normal(0.0, 12.0, (n, 3)) / 1.0653e-3) * 1.0653e-3   # a 16-bit gyroscope's steps
    rotor = np.round(rng.uniform(0.0, 1400.0, n) / 1.4961) * 1.4961
    accel = np.round(rng.normal(0.0, 30.0, (n, 3)) / 4.788e-3) * 4.788e-3
    return Throw(t=t, omega=omega, rotor=rotor, accel=accel)


@pytest.mark.parametrize("compact", [False, True])
def test_a_written_throw_reads_back_as_written(tmp_path, compact):
    throw = _throw(5)
    path = write_throw(tmp_path / "deep" / "o1.csv", throw, header="two lines\nof comment", compact=compact)
    again, read = load_throw(path)
    if compact:
        assert np.all(np.abs(_columns(again) - _columns(throw)) <= HALF * (1 + 1e-9))
        assert read.units[0] == "us" and read.columns[0] == "t (us)"
        # a 16-bit logger's samples stay distinct: none moves by a tenth of a step
        assert np.abs(again.omega - throw.omega).max() < 0.1 * 1.0653e-3
    else:
        np.testing.assert_allclose(_columns(again), _columns(throw), rtol=1e-6, atol=1e-12)
    assert read.rows == len(throw.t) and read.ignored == ()
    assert path.read_text(encoding="utf-8").startswith("# two lines\n# of comment\n")


def test_the_compact_form_is_about_half_the_size_and_drops_the_accelerometer_when_there_is_none():
    throw = _throw(6)
    full, compact = throw_csv(throw), throw_csv(throw, compact=True)
    assert len(compact) < 0.75 * len(full)
    bare = Throw(t=throw.t, omega=throw.omega, rotor=throw.rotor, accel=None)
    samples, read = parse_throw_csv(throw_csv(bare, compact=True).encode(), "o1.csv")
    assert samples["accel"] is None and len(read.columns) == 5
    np.testing.assert_allclose(samples["rotor"], throw.rotor, atol=HALF[4])


def test_a_synthetic_throw_written_compact_fits_as_the_full_one(tmp_path):
    """The generator's 4 kHz throw through the compact form: the samples move by less than the
    decimals kept, the sensors' own steps stay distinct."""
    bracket = box(0.482, (0.16, 0.09, 0.04), center=(0.012, -0.008, 0.035), rotvec=(0.2, -0.1, 0.35))
    throw = synthetic_throw(21, combine(true_device(), bracket))
    again = read_throw(write_throw(tmp_path / "o1.csv", throw, compact=True))
    assert np.all(np.abs(_columns(again) - _columns(throw)) <= HALF * (1 + 1e-6) + 1e-12)
    assert np.all(np.diff(again.t) > 0)


def test_the_throw_format_page_lists_every_column_the_reader_takes():
    pytest.importorskip("sphinx")
    sys.path.insert(0, str(ROOT / "docs" / "_ext"))
    import tumble_keys

    page = (ROOT / "docs" / "formats" / "throw.md").read_text(encoding="utf-8")
    assert "```{tumble-keys} tumble.io.throwfile.THROW_FORMAT" in page
    assert "literalinclude} ../../src/tumble/examples/throws/o1.csv" in page
    text = tumble_keys.render_format(THROW_FORMAT)
    for table in THROW_FORMAT.tables:
        for key in table.keys:
            assert f"   * - ``{key.name}``\n" in text, key.name
    assert "\nthrow\n" in (ROOT / "docs" / "formats" / "index.md").read_text(encoding="utf-8")
    assert "formats/throw.md" in (ROOT / "docs" / "tensor.md").read_text(encoding="utf-8")


def test_a_header_of_the_pages_examples_is_read_in_their_units():
    header = THROW_FORMAT.table("header columns")
    names = [key.example.strip('"') for key in header.keys]
    assert names[:5] == ["t (s)", "wx (rad/s)", "wy (rad/s)", "wz (rad/s)", "rotor (rpm)"]
    row = "0.5,1,2,3,60,0,0,9.80665,21.5\n"
    samples, read = parse_throw_csv((",".join(names) + "\n" + row + row.replace("0.5,", "0.75,", 1)).encode(), "o1.csv")
    assert read.ignored == ("temperature (C)",)
    assert read.units == ("s", "rad/s", "rad/s", "rad/s", "rpm", "m/s^2", "m/s^2", "m/s^2")
    np.testing.assert_allclose(samples["rotor"], 2 * np.pi)   # 60 rpm
    width = len(THROW_FORMAT.table("without a header").keys)
    assert [k.name for k in THROW_FORMAT.table("without a header").keys] == ["column 1", "columns 2-4", "column 5",
                                                                             "columns 6-8"] and width == 4
