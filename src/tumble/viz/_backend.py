"""matplotlib, imported on first use with the non-interactive Agg backend (no screen needed)."""

from __future__ import annotations


def pyplot():
    """``matplotlib.pyplot`` on the Agg backend, unless the user already chose a backend."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig, path, dpi: int = 110) -> None:
    """Save ``fig`` (format from the suffix) to a temporary name, rename it into place, close it.

    A failure midway leaves no half-written figure behind.
    """
    from ..io.atomic import atomic_path

    try:
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=dpi)
    finally:
        pyplot().close(fig)
