"""Campaigns: statistical and many-seed checks too slow for ``make test`` (issue 40: the suite
stays under ~6 minutes on two cores; slow checks belong in benchmarks). They are tests, run by
``make bench`` (or ``python -m pytest benchmarks/campaigns``): coverage over many seeded trials,
and whole campaigns of which the suite keeps a few cases. The helpers they share with the suite
stay in tests/ (one home), put on the path here."""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
