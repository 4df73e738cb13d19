"""Make the throws that ship with tumble's examples (``examples/throws/``): synthetic logs of the
example device (``examples/devices/flywheel_device.toml``) alone, with its proof body, and strapped
to a box, on which docs/tensor.md's two commands run as shown.

Each is a throw of :func:`tumble.analysis.tensor.synthetic.synthetic_throw` (the device's 4 kHz
log), kept small: from 0.15 s before the sensed release, every fourth sample (a 1 kHz log, as a
flight controller's blackbox at ``blackbox_sample_rate = 1/4`` writes it), in the throw file's
compact form (:func:`tumble.io.throwfile.throw_csv`). tests/test_example_throws.py makes them
again and compares.

Run from the repository's root::

    python tools/make_example_throws.py            # writes src/tumble/examples/throws/*.csv
    python tools/make_example_throws.py --out DIR
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import numpy as np

from tumble.analysis.tensor import Throw
from tumble.analysis.tensor.synthetic import box, combine, synthetic_throw, throw_times, true_device, true_proof
from tumble.io.throwfile import write_throw

#: Where the examples live.
EXAMPLES = Path(__file__).resolve().parents[1] / "src" / "tumble" / "examples"
#: Every how many of the device's samples one is kept (4 kHz to 1 kHz).
STEP = 4
#: How long before the sensed release the log starts, s.
BEFORE = 0.15
#: The object of docs/tensor.md: a 0.482 kg box 16 x 9 x 4 cm, turned against the sensor's axes
#: and 4 cm off the sensor (sensor frame, m).
BOX: dict[str, Any] = {"mass": 0.482, "size": (0.16, 0.09, 0.04), "center": (0.012, -0.008, 0.035),
                       "rotvec": (0.2, -0.1, 0.35)}


def _mm(point: Any) -> str:
    return "[" + ", ".join(f"{1e3 * x:.3g}" for x in point) + "]"


#: The throws by their file's name: what flew (``"alone"``, ``"proof"``, ``"box"``), the seed, the spin's range (rad/s).
THROWS = {**{f"a{k}.csv": ("alone", k, (3.0, 8.0)) for k in (1, 2, 3)},
          **{f"p{k}.csv": ("proof", 10 + k, (10.0, 18.0)) for k in (1, 2, 3)},
          **{f"o{k}.csv": ("box", 20 + k, (10.0, 18.0)) for k in (1, 2, 3, 4)}}


def example_throw(name: str) -> tuple[Throw, str]:
    """The shipped throw ``name`` (a key of :data:`THROWS`) and its file's comment lines."""
    flying, seed, spin = THROWS[name]
    device = true_device()
    if flying == "alone":
        flown, words, truth = device, "the example device alone, thrown gently (3-8 rad/s)", ""
    elif flying == "proof":
        flown, truth = combine(device, true_proof()[1]), ""
        words = "the example device with its proof body (the device file's [proof])"
    else:
        bracket = box(BOX["mass"], BOX["size"], center=BOX["center"], rotvec=BOX["rotvec"])
        moments = ", ".join(f"{m:.6g}" for m in np.sort(np.linalg.eigvalsh(bracket.inertia)))
        flown = combine(device, bracket)
        words = f"the example device strapped to a {BOX['mass']} kg box of 16 x 9 x 4 cm"
        truth = (f"The box's principal moments: {moments} kg m^2 about its centre of mass, which is at\n"
                 f"{_mm(BOX['center'])} mm in the sensor frame (the device's own: {_mm(device.center)} mm).\n")
    full = synthetic_throw(seed, flown, spin=spin)
    keep = np.flatnonzero(full.t >= throw_times(seed).apparent - BEFORE)[::STEP]
    assert full.accel is not None
    throw = Throw(t=full.t[keep], omega=full.omega[keep], rotor=full.rotor[keep], accel=full.accel[keep])
    comment = (f"SYNTHETIC throw of {words}: not a measurement.\n{truth}"
               f"Made by tools/make_example_throws.py: tumble.analysis.tensor.synthetic.synthetic_throw(seed={seed}, "
               f"spin={spin}),\nevery {STEP}th sample (a 1 kHz log) from {BEFORE} s before the sensed release.")
    return throw, comment


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=EXAMPLES / "throws",
                        help="the folder to write (default: %(default)s)")
    out = parser.parse_args(argv).out
    for name in THROWS:
        throw, comment = example_throw(name)
        print(f"wrote {write_throw(out / name, throw, header=comment, compact=True)}")


if __name__ == "__main__":
    main()
