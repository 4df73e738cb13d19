"""The main job run by ``make demo``: the seed's T-handle study on built-in defaults.

For now (mass properties only) it prints the mass properties of the seed's T-handle and of the
space-station T-handle and writes them as JSON into the output folder.
"""

from __future__ import annotations

import json
from pathlib import Path

from .io import mass_properties_dict, mass_properties_table
from .io.atomic import atomic_write_text
from .mass import iss_t_handle, t_handle

__all__ = ["run_demo"]


def run_demo(out="tumble-demo") -> Path:
    """Print the presets' mass properties and write ``OUT/mass_properties.json``."""
    out = Path(out)
    bodies = [t_handle(name="seed T-handle (thin rods, 1 m, 1.5 kg)"), iss_t_handle()]
    for body in bodies:
        print(mass_properties_table(body))
        print()
    data = {body.name: mass_properties_dict(body) for body in bodies}
    path = atomic_write_text(out / "mass_properties.json", json.dumps(data, indent=2) + "\n")
    print(f"wrote {path}")
    return out
