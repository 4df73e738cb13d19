"""tumble: rigid-body rotation, from mass properties to the tennis-racket effect.

Top-level names are loaded on first use (PEP 562), so ``import tumble`` and ``tumble --help``
stay fast and plotting is never imported by the physics.

Examples
--------
>>> import tumble
>>> body = tumble.t_handle()          # the seed study's T-handle: two 1 m, 1.5 kg rods
>>> body.principal_moments.tolist()
[0.125, 0.3125, 0.4375]
"""

import importlib as _importlib
from typing import Any as _Any

from ._version import __version__

_EXPORTS = {
    # mass properties
    "Body": "tumble.mass",
    "MassProperties": "tumble.mass",
    "Part": "tumble.mass",
    "Rod": "tumble.mass",
    "Cylinder": "tumble.mass",
    "Tube": "tumble.mass",
    "Cone": "tumble.mass",
    "Box": "tumble.mass",
    "Ellipsoid": "tumble.mass",
    "Sphere": "tumble.mass",
    "Shell": "tumble.mass",
    "PointMass": "tumble.mass",
    "Rotor": "tumble.mass",
    "Mesh": "tumble.mass",
    "t_handle": "tumble.mass",
    "iss_t_handle": "tumble.mass",
    "moments_body": "tumble.mass",
    # dynamics and analysis
    "simulate": "tumble.dynamics",
    "simulate_batch": "tumble.dynamics",
    "BatchTrajectory": "tumble.dynamics",
    "Trajectory": "tumble.dynamics",
    "ConstantTorque": "tumble.dynamics",
    "TorqueSum": "tumble.dynamics",
    "SphericalDamper": "tumble.dynamics",
    "METHODS": "tumble.dynamics",
    "GravityGradient": "tumble.dynamics",
    "gravity_gradient_of": "tumble.dynamics",
    "lvlh_state": "tumble.dynamics",
    "orbit_frame_angles": "tumble.dynamics",
    "triad": "tumble.dynamics.estimation",
    "quest": "tumble.dynamics.estimation",
    "MEKF": "tumble.dynamics.estimation",
    "gravity_gradient_stability": "tumble.analysis",
    "linearised_rate": "tumble.analysis",
    "flip_interval": "tumble.analysis",
    "stability_report": "tumble.analysis",
    "fit_rotation": "tumble.analysis",
    "fit_recording": "tumble.analysis",
    "fit_tensor": "tumble.analysis.tensor",
    "calibrate_device": "tumble.analysis.tensor",
    # files
    "load_body": "tumble.io",
    "load_scenario": "tumble.io",
    # running what a file describes
    "run_scenario": "tumble.commands",
}

__all__ = ["__version__", *_EXPORTS]


#: The subpackages, imported on first use as attributes (``tumble.viz.figure_omega(run)`` after
#: ``import tumble``), as numpy's and scipy's are.
_SUBPACKAGES = ("mass", "dynamics", "analysis", "ensemble", "io", "viz", "commands", "validation")


def __getattr__(name: str) -> _Any:
    if name in _SUBPACKAGES:
        return _importlib.import_module(f"tumble.{name}")  # binds it on the package as well
    try:
        module = _EXPORTS[name]
    except KeyError:
        raise AttributeError(f"module 'tumble' has no attribute {name!r}") from None
    value = getattr(_importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """The public names and the subpackages (loaded or not), and the dunders."""
    names = {n for n in globals() if not n.startswith("_") or (n.startswith("__") and n.endswith("__"))}
    return sorted(names | set(_EXPORTS) | set(_SUBPACKAGES))
