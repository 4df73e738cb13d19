"""The README's figure of the T-handle with its wheel spinning and stopped
(docs/figures/wheel_t_handle.png):

    .venv/bin/python docs/figures/make_wheel_figure.py [--out DIR]

Runs examples/wheel_t_handle.toml as it is (a 1 kg wheel at 500 rad/s on the crossbar:
h = 2.5 kg m^2/s > (I3 - I2) W, no flip) and with every rotor stopped (the seed's flip), and
draws the two omega(t) one above the other (tumble.viz.figure_omega_panels). Writes
DIR/wheel_t_handle.png (DIR: docs/figures by default); tests/test_spacecraft_examples.py runs it.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

from figure_script import ROOT, main, write

import tumble
from tumble.commands import run_scenario
from tumble.io.scenario import load_scenario
from tumble.viz.spacecraft import figure_omega_panels

SCENARIO = ROOT / "src" / "tumble" / "examples" / "wheel_t_handle.toml"


def stopped(scenario):
    """The same scenario with every rotor's spin set to 0 (the wheel as rigid ballast)."""
    parts = tuple(dataclasses.replace(p, spin_rate=0.0) if isinstance(p, tumble.Rotor) else p
                  for p in scenario.body.parts)
    return dataclasses.replace(scenario, body=tumble.Body(parts, name=scenario.body.name))


def make(out: Path) -> Path:
    """Write ``out/wheel_t_handle.png``; returns its path."""
    scenario = load_scenario(SCENARIO)
    spinning, still = run_scenario(scenario), run_scenario(stopped(scenario))
    I, h = spinning.moments, float(spinning.internal_momentum[0, 1])
    W = float(spinning.omega[0, 1])
    rate = scenario.body.rotors[0].spin_rate
    flips = tumble.stability_report(spinning)["flips"]
    cases = [
        (rf"wheel at {rate:g} rad/s: h = {h:.3g} kg m$^2$/s > $(I_3 - I_2)\,W$ = {(I[2] - I[1]) * W:.3g} kg m$^2$/s, "
         + ("no flip" if flips == 0 else f"{flips} flips"), spinning),
        ("wheel stopped (h = 0): the seed's flip", still),
    ]
    return write(figure_omega_panels(cases), out, "wheel_t_handle.png")


if __name__ == "__main__":
    main(make, __doc__)
