"""Files are written whole or not at all."""

from __future__ import annotations

import pytest

from tumble.io.atomic import atomic_path, atomic_write_text


def test_a_failure_midway_leaves_neither_file_nor_temporary(tmp_path):
    target = tmp_path / "out" / "figure.png"
    with pytest.raises(RuntimeError):
        with atomic_path(target) as tmp:
            assert tmp.suffix == ".png" and tmp.parent == target.parent
            tmp.write_text("half")
            raise RuntimeError("disk on fire")
    assert list(target.parent.iterdir()) == []


def test_an_old_file_survives_a_failed_rewrite(tmp_path):
    target = atomic_write_text(tmp_path / "summary.json", "old")
    with pytest.raises(KeyboardInterrupt):
        with atomic_path(target) as tmp:
            tmp.write_text("new, half")
            raise KeyboardInterrupt
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["summary.json"]
