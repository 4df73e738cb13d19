"""matplotlib, imported on first use with the non-interactive Agg backend (no screen needed)."""

from __future__ import annotations


def pyplot():
    """``matplotlib.pyplot`` on the Agg backend, unless the user already chose a backend."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt
