"""The study run by `make demo`: its outputs and that its numbers say what the physics says."""

from __future__ import annotations

import json

import numpy as np
import pytest

from tumble import __version__
from tumble.demo import CASES, animation_suffix, run_demo
from tumble.io.export import CSV_COLUMNS


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    """The whole study, its four animations drawn through the real writers with 8 frames each (the
    demo's 100 frames are most of its time; tests/test_viz.py and test_figures_fit.py check the frames)."""
    import functools

    import tumble.viz

    out = tmp_path_factory.mktemp("demo")
    with pytest.MonkeyPatch.context() as mp:
        for name in ("animate_ground_frame", "animate_body_frame"):
            mp.setattr(tumble.viz, name, functools.partial(getattr(tumble.viz, name), max_frames=8))
        run_demo(out, animate=True, t_end=20.0, samples=500)
    return out


def test_demo_writes_every_output(demo):
    for case in CASES:
        assert (demo / f"omega_{case.key}.png").stat().st_size > 10_000
        header = (demo / f"trajectory_{case.key}.csv").read_text().splitlines()[0]
        assert header == ",".join(CSV_COLUMNS)
    suffix, _ = animation_suffix()  # MP4 where an ffmpeg is found, GIF otherwise
    for name in ("omega_all.png", "summary.md", "summary.json", f"ground_seed_axis2{suffix}", f"body_iss_axis2{suffix}"):
        assert (demo / name).stat().st_size > 0
    magic = {".mp4": (4, b"ftyp"), ".gif": (0, b"GIF89a")}[suffix]
    assert (demo / f"body_iss_axis2{suffix}").read_bytes()[magic[0]:magic[0] + len(magic[1])] == magic[1]


def test_demo_summary_agrees_with_theory(demo):
    data = json.loads((demo / "summary.json").read_text())
    rows = {r["case"]: r for r in data["cases"]}
    for key, row in rows.items():
        s = row["stability"]
        # flips happen exactly for spin about the intermediate axis (tennis-racket theorem)
        assert (s["flips"] > 0) == (s["role"] == "intermediate"), key
        if row["method"] == "exact" and s["flip_period"] is not None:
            # measured (sampled every 0.04 s, zero crossings interpolated) vs elliptic closed form
            assert s["flip_period"] == pytest.approx(s["flip_period_exact"], rel=1e-3), key
            assert max(row["drift"].values()) < 1e-9
    # the seed's own vectors spin about the seed handle's intermediate axis: both flip
    assert rows["seed_literal_10"]["stability"]["role"] == "intermediate"
    assert rows["seed_literal_1"]["stability"]["flips"] >= 1
    # and the seed's computation drifts by per cent
    assert rows["seed_literal_10_seedmethod"]["drift"]["energy"] > 1e-3
    assert data["provenance"]["tumble"] == __version__
    seed_body = data["bodies"]["seed"]
    np.testing.assert_allclose(seed_body["principal_moments"], [0.125, 0.3125, 0.4375])


@pytest.mark.parametrize("ffmpeg, says", [
    (None, "animations: 4 GIF files instead of MP4: no ffmpeg found (install tumble[video] or put ffmpeg on PATH)"),
    ("/opt/ffmpeg", "animations: 4 MP4 files (ffmpeg found)"),
])
def test_demo_says_first_what_its_animations_will_be(tmp_path, monkeypatch, capsys, ffmpeg, says):
    """Issue 40: without ffmpeg the study wrote GIFs and said so only at its end; now its first line
    says what it will write and why (the animations themselves are stubbed here: they are slow)."""
    import tumble.viz
    import tumble.viz.animate

    monkeypatch.setattr(tumble.viz.animate, "ffmpeg_path", lambda: ffmpeg)
    written = []

    def animate(body, traj, path, title=None, max_frames=100):
        written.append(path.suffix)
        path.write_bytes(b"")

    monkeypatch.setattr(tumble.viz, "animate_ground_frame", animate)
    monkeypatch.setattr(tumble.viz, "animate_body_frame", animate)
    run_demo(tmp_path / "demo", t_end=0.5, samples=20)
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == says and lines[1].startswith("[1/")
    assert written == [".gif" if ffmpeg is None else ".mp4"] * 4
    assert (lines[-2] == says) == (ffmpeg is None)  # and again beside the summary where MP4 could not be


def test_demo_without_animations_says_nothing_of_them(tmp_path, capsys):
    run_demo(tmp_path / "demo", t_end=0.5, samples=20, animate=False)
    assert not any(line.startswith("animations") for line in capsys.readouterr().out.splitlines())


def test_the_animations_show_two_flips_a_small_turn_a_frame():
    """100 frames over the whole 20 s turned the spinning handle 115 degrees a frame: it seemed to jump (a
    teacher's walkthrough, 2026-12-03); and nothing said so. The demo animates its handles' first 2.2 flips
    (the interval T/2 = 2 K(m) / p written here, Landau & Lifshitz sec. 37) at 0.3 rad of spin a frame, and
    an animation that turns more than 30 degrees a frame is warned of."""
    import math
    from pathlib import Path
    from tempfile import TemporaryDirectory

    from scipy.spatial.transform import Rotation
    from scipy.special import ellipk

    import tumble
    from tumble.demo import FLIPS, FRAME_TURN, _animated_run
    from tumble.viz.animate import animate_ground_frame
    from tumble.viz.plots import AliasedSamplesWarning

    body, w = tumble.t_handle(), np.array([0.1, 10.0, 0.1])
    I = body.principal_moments
    L2, E2 = np.sum((I * w) ** 2), np.sum(I * w * w)   # circulating the major axis: L^2 > 2 E I2
    p = math.sqrt((I[2] - I[1]) * (L2 - I[0] * E2) / np.prod(I))
    m = (I[1] - I[0]) * (I[2] * E2 - L2) / ((I[2] - I[1]) * (L2 - I[0] * E2))
    whole = tumble.simulate(body, w, t_end=20.0, samples=500)
    shown, frames = _animated_run(body, whole, 20.0)
    assert shown.t[-1] == pytest.approx(FLIPS * 2 * ellipk(m) / p, rel=1e-9)
    turns = (Rotation.from_quat(shown.quat[1:]) * Rotation.from_quat(shown.quat[:-1]).inv()).magnitude()
    assert frames == len(shown.t) and np.max(turns) <= FRAME_TURN * 1.0001
    with TemporaryDirectory() as folder, pytest.warns(AliasedSamplesWarning, match=r"turns up to 1[0-7][0-9] deg between"):
        animate_ground_frame(body, whole, Path(folder) / "jumps.gif", dpi=10)
