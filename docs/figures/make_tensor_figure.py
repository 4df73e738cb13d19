"""The tensor guide's figure (docs/figures/tensor.png): ``tumble tensor``'s ``tensor.png`` of the
guide's example, four synthetic throws of a 0.482 kg box with the flywheel device:

    .venv/bin/python docs/figures/make_tensor_figure.py [--out DIR]

The throws are the guide's (tumble.analysis.tensor.synthetic.synthetic_throw, seeds 21-24, the
box 16 x 9 x 4 cm turned by the rotation vector (0.2, -0.1, 0.35) rad, its centre at
(12, -8, 35) mm from the sensor), fitted as ``tumble tensor`` fits them (tumble.fit_tensor) with
the synthetic device as a calibration gives it (``calibrated_device``) and drawn by
tumble.viz.tensor.figure_tensor. Writes DIR/tensor.png (DIR: docs/figures by default);
tests/test_tensor_cli.py runs it.
"""

from __future__ import annotations

from pathlib import Path

from figure_script import main, write

import tumble
from tumble.analysis.tensor.synthetic import box, calibrated_device, combine, synthetic_throw, true_device
from tumble.viz.tensor import figure_tensor

#: The guide's object: mass (kg), size (m), centre (m, sensor frame), rotation vector (rad).
BRACKET = dict(mass=0.482, size=(0.16, 0.09, 0.04), center=(0.012, -0.008, 0.035), rotvec=(0.2, -0.1, 0.35))


def fitted():
    """The object (its true mass properties) and the fit of its four throws."""
    bracket = box(**BRACKET)
    throws = [synthetic_throw(seed, combine(true_device(), bracket), input=f"o{seed - 20}.csv") for seed in (21, 22, 23, 24)]
    return bracket, tumble.fit_tensor(throws, calibrated_device(), bracket.mass)


def make(out: Path) -> Path:
    """Write ``out/tensor.png``; returns its path."""
    return write(figure_tensor(fitted()[1]), out, "tensor.png")


if __name__ == "__main__":
    main(make, __doc__)
