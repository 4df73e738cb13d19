"""The benchmarks compare tumble with the shared reference peers, imported unchanged (issue 38
item 8): no copy of a peer of our own in ``benchmarks/``, the peers found where ``_harness`` says,
and every peer comparison importable (nothing is measured here: ``make bench`` does that)."""

from __future__ import annotations

import importlib
import sys
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"
COMPARISONS = ["bench_engine", "bench_models", "bench_closed_loop", "bench_call", "bench_work_precision"]


def test_no_peer_of_our_own():
    assert not (BENCH / "numba_peer.py").exists(), "the peer is ../shared/peers/numba_peer.py, imported unchanged"
    assert not list(BENCH.glob("peer_*.py"))


@pytest.fixture(scope="module")
def harness():
    sys.path.insert(0, str(BENCH))
    try:
        yield importlib.import_module("_harness")
    finally:
        sys.path.remove(str(BENCH))


def test_peers_come_from_the_shared_folder(harness):
    if not harness.PEERS.is_dir():
        with pytest.raises(SystemExit, match="shared reference peers"):
            harness.peers()
        return
    for module in harness.peers():
        assert Path(module.__file__).resolve().is_relative_to(harness.PEERS.resolve())


@pytest.mark.parametrize("name", COMPARISONS)
def test_each_comparison_imports_and_is_short(harness, name):
    assert len((BENCH / f"{name}.py").read_text().splitlines()) <= 500
    if not harness.PEERS.is_dir():
        pytest.skip(f"the shared peers are not at {harness.PEERS}")
    assert callable(importlib.import_module(name).run)
